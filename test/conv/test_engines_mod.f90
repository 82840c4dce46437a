!> The convolution engines against each other and against closed forms:
!> `paper` (greenconv_conv_paper, eqs. 15-17), `recursive`, `exact` and `backward` (greenconv_conv_recursive).
!>
!> Tolerances:
!> - `recursive` is `paper` without its growth factors: equal to 1e-12 of max|u|, the
!>   round-off of the paper's phase omega*t_n (about 1e-16*omega*t_n rad) over these runs.
!> - `exact` (first-order hold) integrates a piecewise-linear force exactly: a ramp gives
!>   the closed form to 1e-12 of max|u|. For a smooth force its error is the hold's,
!>   |q_hold - q| <= (dt^2/8)*max|q''|, times int|g| <= 1/(M*wd*a): second order in dt.
!> - `backward` (backward zero-order hold) is its own definition, u(t_n) = sum q_m*a_{n-m}
!>   with a_j the integral of g over [j*dt, (j+1)*dt], to 1e-12 of max|u| (the a_j by
!>   Gauss-Legendre quadrature of g, independent of the modal form); first order in dt.
module test_engines_mod
    use, intrinsic :: iso_fortran_env, only: dp => real64
    use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
    use testsuite_mod, only: test_error, unittest_type, new_unittest, check, note
    use duhamel_mod, only: step_response, sine_response, ramp_response
    use greenconv_core_random, only: random_stream
    use greenconv_model_modal_set, only: modal_set, random_modes
    use greenconv_model_sdof, only: sdof_modes, sdof_impulse
    use greenconv_conv_convolver, only: convolver
    use greenconv_conv_paper, only: new_paper_convolver
    use greenconv_conv_recursive, only: new_recursive_convolver, new_exact_convolver, new_backward_convolver, &
                                  hold_functions
    implicit none
    private

    public :: collect_engines

    !> The oscillator of the paper's Tab. 1 and the test loads.
    real(dp), parameter :: mass = 1.0_dp, stiffness = 1.0e6_dp, xi = 0.02_dp
    real(dp), parameter :: force = 10.0_dp
    real(dp), parameter :: pi = acos(-1.0_dp)

contains

    !> Tests of the modal engines.
    subroutine collect_engines(testsuite)
        type(unittest_type), allocatable, intent(out) :: testsuite(:)

        testsuite = [new_unittest('recursive equals paper to round-off: sdof', test_recursive_sdof), &
                     new_unittest('recursive equals paper to round-off: 10 modes', test_recursive_modes), &
                     new_unittest('paper overflows past xi*omega*t = 709; recursive, exact do not', test_overflow), &
                     new_unittest('recursive and exact over 1e8 steps: finite, steady state to round-off', &
                                  test_long_run), &
                     new_unittest('hold functions phi1, phi2 against quadruple precision', test_hold_functions), &
                     new_unittest('exact: instant weight w0 against quadrature', test_instant_weight), &
                     new_unittest('exact: ramp load reproduced to round-off (u = history + w0*q)', test_ramp), &
                     new_unittest('exact: ramp on 10 modes to round-off', test_ramp_modes), &
                     new_unittest('exact: second order against Duhamel (step, sine)', test_exact_order), &
                     new_unittest('exact: more accurate than paper for a slow sine', test_exact_sine), &
                     new_unittest('backward: its definition by quadrature of g, random load', &
                                  test_backward_definition), &
                     new_unittest('backward: static gain F/K exact', test_backward_static), &
                     new_unittest('backward: first order against Duhamel (sine)', test_backward_order)]
    end subroutine collect_engines

    !> Largest |u_a - u_b| over n_steps of two convolvers driven by the same random load in
    !> [-F, F], and the largest |u_b|; u = history + w0*q for each.
    subroutine compare_random(a, b, n_steps, seed, worst, peak)
        class(convolver), intent(inout) :: a, b
        integer, intent(in) :: n_steps, seed
        real(dp), intent(out) :: worst, peak

        type(random_stream) :: stream
        real(dp) :: q, u_a, u_b
        integer :: n

        stream = random_stream(seed)
        call a%reset()
        call b%reset()
        worst = 0.0_dp
        peak = 0.0_dp
        do n = 0, n_steps - 1
            q = stream%between(-force, force)
            u_a = a%history() + a%instant_weight()*q
            u_b = b%history() + b%instant_weight()*q
            worst = max(worst, abs(u_a - u_b))
            peak = max(peak, abs(u_b))
            call a%push(q)
            call b%push(q)
        end do
    end subroutine compare_random

    !> Largest |u_n - u(t_n)| of the oscillator (M, K, zeta) under a step, sine or ramp load.
    function max_error(conv, load, n_steps, stiff, zeta, omega_load) result(worst)
        class(convolver), intent(inout) :: conv
        character(len=*), intent(in) :: load
        integer, intent(in) :: n_steps
        real(dp), intent(in) :: stiff, zeta, omega_load
        real(dp) :: worst

        real(dp) :: t, q, u
        integer :: n

        worst = 0.0_dp
        call conv%reset()
        do n = 0, n_steps - 1
            t = n*conv%dt
            select case (load)
            case ('step')
                q = merge(0.5_dp*force, force, n == 0)
                u = step_response(t, mass, stiff, zeta, force)
            case ('ramp')
                q = force*t/(n_steps*conv%dt)
                u = ramp_response(t, mass, stiff, zeta, force, n_steps*conv%dt)
            case default
                q = force*sin(omega_load*t)
                u = sine_response(t, mass, stiff, zeta, force, omega_load)
            end select
            worst = max(worst, abs(conv%history() + conv%instant_weight()*q - u))
            call conv%push(q)
        end do
    end function max_error

    !> Tab. 1's oscillator, dt = 0.1 ms, 10000 steps (xi*omega*t up to 20).
    subroutine test_recursive_sdof(error)
        type(test_error), allocatable, intent(out) :: error

        class(convolver), allocatable :: paper, recursive
        real(dp) :: worst, peak

        paper = new_paper_convolver(sdof_modes(mass, stiffness, xi), 1.0e-4_dp)
        recursive = new_recursive_convolver(sdof_modes(mass, stiffness, xi), 1.0e-4_dp)
        call compare_random(recursive, paper, 10000, 11, worst, peak)
        call note('max|u_rec - u_paper|/max|u|', worst/peak)
        call check(error, worst/peak, 0.0_dp, 'recursive against paper, sdof', thr=1.0e-12_dp)
    end subroutine test_recursive_sdof

    !> Ten random modes of 20-500 Hz, xi 0.02-0.05, dt = 0.1 ms, 5000 steps.
    subroutine test_recursive_modes(error)
        type(test_error), allocatable, intent(out) :: error

        class(convolver), allocatable :: paper, recursive
        type(modal_set) :: modes
        real(dp) :: worst, peak

        modes = random_modes(7, 10, 20.0_dp, 500.0_dp, 0.02_dp, 0.05_dp, 0.2_dp, 1.0_dp)
        paper = new_paper_convolver(modes, 1.0e-4_dp)
        recursive = new_recursive_convolver(modes, 1.0e-4_dp)
        call compare_random(recursive, paper, 5000, 12, worst, peak)
        call note('max|u_rec - u_paper|/max|u|', worst/peak)
        call check(error, worst/peak, 0.0_dp, 'recursive against paper, 10 modes', thr=1.0e-12_dp)
    end subroutine test_recursive_modes

    !> A 2 kHz mode with xi = 0.05 (a = xi*omega = 628 1/s) under F*sin(W t), W = 2*pi*100,
    !> dt = 10 us, 120000 steps (a*t reaches 754): `paper` agrees with `recursive` to 1e-10
    !> while a*t <= 700 and its history is Inf or NaN from the step after exp(a*t_n)
    !> overflows (a*t_n > 709.78); `recursive` and `exact` stay within their error bounds of
    !> the Duhamel integral to the end (rectangle rule: (dt^2/12)*F*(W/(M*wd) + 1/M)).
    subroutine test_overflow(error)
        type(test_error), allocatable, intent(out) :: error

        real(dp), parameter :: dt = 1.0e-5_dp, zeta = 0.05_dp
        integer, parameter :: n_steps = 120000
        class(convolver), allocatable :: paper, recursive, exact
        real(dp) :: omega, stiff, a, wd, w, t, q, u, u_paper, agree, peak, err_rec, err_exact
        real(dp) :: bound_rec, bound_exact, fail_time
        integer :: n

        omega = 2.0_dp*pi*2000.0_dp
        stiff = mass*omega**2
        a = zeta*omega
        wd = omega*sqrt(1.0_dp - zeta**2)
        w = 2.0_dp*pi*100.0_dp
        paper = new_paper_convolver(sdof_modes(mass, stiff, zeta), dt)
        recursive = new_recursive_convolver(sdof_modes(mass, stiff, zeta), dt)
        exact = new_exact_convolver(sdof_modes(mass, stiff, zeta), dt)
        agree = 0.0_dp
        peak = 0.0_dp
        err_rec = 0.0_dp
        err_exact = 0.0_dp
        fail_time = -1.0_dp
        do n = 0, n_steps - 1
            t = n*dt
            q = force*sin(w*t)
            u = sine_response(t, mass, stiff, zeta, force, w)
            peak = max(peak, abs(u))
            u_paper = paper%history()
            if (a*t <= 700.0_dp) agree = max(agree, abs(u_paper - recursive%history()))
            if (.not. ieee_is_finite(u_paper) .and. fail_time < 0.0_dp) fail_time = t
            err_rec = max(err_rec, abs(recursive%history() - u))
            err_exact = max(err_exact, abs(exact%history() + exact%instant_weight()*q - u))
            call paper%push(q)
            call recursive%push(q)
            call exact%push(q)
        end do
        bound_rec = dt**2/12.0_dp*force*(w/(mass*wd) + 1.0_dp/mass)
        bound_exact = dt**2/8.0_dp*w**2*force/(mass*wd*a)
        call note('a*t at first non-finite paper u', a*fail_time)
        call note('paper vs recursive to a*t = 700', agree/peak)
        call note('recursive error/bound', err_rec/bound_rec)
        call note('exact error/bound', err_exact/bound_exact)
        call note('exact error/max|u|', err_exact/peak)
        call check(error, agree/peak, 0.0_dp, 'paper against recursive while a*t <= 700', thr=1.0e-10_dp)
        if (allocated(error)) return
        call check(error, fail_time > 0.0_dp, 'paper overflows')
        if (allocated(error)) return
        call check(error, a*fail_time > 700.0_dp .and. a*fail_time <= log(huge(1.0_dp)) + 2.0_dp*a*dt, &
                   'paper overflows at a*t in (700, 709.78 + 2*a*dt]')
        if (allocated(error)) return
        call check(error, ieee_is_finite(recursive%history()) .and. ieee_is_finite(exact%history()), &
                   'recursive and exact finite at the end')
        if (allocated(error)) return
        call check(error, err_rec, 0.0_dp, 'recursive against Duhamel', thr=bound_rec)
        if (allocated(error)) return
        call check(error, err_exact, 0.0_dp, 'exact against Duhamel', thr=bound_exact)
    end subroutine test_overflow

    !> The 2 kHz, xi = 0.05 mode at dt = 10 us for 1e8 steps (1000 s; `paper` overflows
    !> after 1.13 s). `recursive` under a sine load of exactly 64 samples per period
    !> (1562.5 Hz, from a table, so the load carries no phase drift) must end on the
    !> steady state of its own discrete sum, which a geometric series gives in closed form:
    !> with w_j = dt*2*Re(r*z^j), z = exp(lambda*dt), s = exp(-i*W*dt), and q_m = Im(e^{iWt_m}),
    !>     u_h(n) = Im( e^{iWt_n} * dt*( r*z*s/(1 - z*s) + conj(r)*conj(z)*s/(1 - conj(z)*s) ) ).
    !> `exact` under a constant force must end on the static F/K exactly (the hold integrates
    !> a constant force without error). Both to 1e-12 of the amplitude: the states are
    !> multiplied by |z| = 0.9937 each step, so round-off does not accumulate.
    subroutine test_long_run(error)
        type(test_error), allocatable, intent(out) :: error

        real(dp), parameter :: dt = 1.0e-5_dp, zeta = 0.05_dp
        integer, parameter :: n_steps = 100000000, period = 64
        class(convolver), allocatable :: recursive, exact
        type(modal_set) :: modes
        complex(dp) :: z, s, r, gain
        real(dp) :: table(0:period - 1), stiff, u, expected, worst_rec, worst_exact, amplitude
        integer :: n

        stiff = mass*(2.0_dp*pi*2000.0_dp)**2
        modes = sdof_modes(mass, stiff, zeta)
        recursive = new_recursive_convolver(modes, dt)
        exact = new_exact_convolver(modes, dt)
        table = sin(2.0_dp*pi*[(n, n=0, period - 1)]/period)
        do n = 0, n_steps - 1
            call recursive%push(table(mod(n, period)))
            call exact%push(1.0_dp)
        end do
        ! Closed form of the discrete steady state, at the last steps n_steps .. n_steps + period - 1.
        r = modes%residue(1)
        z = exp(modes%pole(1)*dt)
        s = exp(cmplx(0.0_dp, -2.0_dp*pi/period, kind=dp))
        gain = dt*(r*z*s/(1.0_dp - z*s) + conjg(r)*conjg(z)*s/(1.0_dp - conjg(z)*s))
        amplitude = abs(gain)
        worst_rec = 0.0_dp
        worst_exact = 0.0_dp
        do n = n_steps, n_steps + period - 1
            u = recursive%history()
            expected = aimag(exp(cmplx(0.0_dp, 2.0_dp*pi*mod(n, period)/period, kind=dp))*gain)
            worst_rec = max(worst_rec, abs(u - expected))
            worst_exact = max(worst_exact, abs(exact%history() + exact%instant_weight() - 1.0_dp/stiff))
            call recursive%push(table(mod(n, period)))
            call exact%push(1.0_dp)
        end do
        call note('recursive: max error/amplitude', worst_rec/amplitude)
        call note('exact: max error/(F/K)', worst_exact*stiff)
        call check(error, ieee_is_finite(recursive%history()) .and. ieee_is_finite(exact%history()), &
                   'finite after 1e8 steps')
        if (allocated(error)) return
        call check(error, worst_rec, 0.0_dp, 'recursive: discrete steady state', thr=1.0e-12_dp*amplitude)
        if (allocated(error)) return
        call check(error, worst_exact, 0.0_dp, 'exact: static F/K', thr=1.0e-12_dp/stiff)
    end subroutine test_long_run

    !> phi1(x) = (exp(x) - 1)/x and phi2(x) = (exp(x) - 1 - x)/x^2 against the closed form
    !> in quadruple precision, on both sides of |x| = 1 where the series gives way to the
    !> closed form, at tiny |x| where the closed form in double would lose every digit, and
    !> at large |x| (heavy damping or a long step): 1e-15 relative.
    subroutine test_hold_functions(error)
        type(test_error), allocatable, intent(out) :: error

        integer, parameter :: qp = selected_real_kind(30)
        complex(dp), parameter :: direction = cmplx(-0.05_dp, 1.0_dp, dp)/abs(cmplx(-0.05_dp, 1.0_dp, dp))
        real(dp), parameter :: radii(9) = [1.0e-9_dp, 1.0e-3_dp, 0.5_dp, 0.999_dp, 1.001_dp, 2.0_dp, &
                                           5.0_dp, 20.0_dp, 300.0_dp]
        complex(dp) :: x, phi1, phi2
        complex(qp) :: xq, q1, q2
        real(dp) :: worst
        integer :: r

        worst = 0.0_dp
        do r = 1, size(radii)
            x = radii(r)*direction
            call hold_functions(x, phi1, phi2)
            xq = cmplx(x, kind=qp)
            q1 = (exp(xq) - 1.0_qp)/xq
            q2 = (exp(xq) - 1.0_qp - xq)/xq**2
            worst = max(worst, real(abs(phi1 - q1)/abs(q1), dp), real(abs(phi2 - q2)/abs(q2), dp))
        end do
        call note('max relative error', worst)
        call check(error, worst, 0.0_dp, 'phi1, phi2 against quadruple precision', thr=1.0e-15_dp)
    end subroutine test_hold_functions

    !> w0 = int_0^dt g(s)*(1 - s/dt) ds, by composite Simpson on 2000 intervals of the
    !> closed-form g of eq. (8) (error below 1e-13 relative), for dt = 0.1 ms and 1 ms.
    subroutine test_instant_weight(error)
        type(test_error), allocatable, intent(out) :: error

        integer, parameter :: intervals = 2000
        class(convolver), allocatable :: exact
        real(dp) :: dt, s, h, quadrature, w0
        integer :: i, trial

        do trial = 1, 2
            dt = 10.0_dp**(-5 + trial)
            h = dt/intervals
            quadrature = 0.0_dp
            do i = 0, intervals
                s = i*h
                quadrature = quadrature + merge(1.0_dp, merge(4.0_dp, 2.0_dp, mod(i, 2) == 1), &
                                                i == 0 .or. i == intervals) &
                             *sdof_impulse(mass, stiffness, xi, s)*(1.0_dp - s/dt)
            end do
            quadrature = quadrature*h/3.0_dp
            exact = new_exact_convolver(sdof_modes(mass, stiffness, xi), dt)
            w0 = exact%instant_weight()
            call note('w0*K', w0*stiffness)
            call note('|w0 - quadrature|/w0', abs(w0 - quadrature)/w0)
            call check(error, w0, quadrature, 'w0 of exact', thr=1.0e-12_dp, rel=.true.)
            if (allocated(error)) return
        end do
    end subroutine test_instant_weight

    !> A ramp F*t/T is piecewise linear, so `exact` gives the Duhamel integral to round-off
    !> at every step, the current force entering through w0 (dt = 0.1 ms, 2000 steps);
    !> without the w0*q term the error is of the order of w0*F.
    subroutine test_ramp(error)
        type(test_error), allocatable, intent(out) :: error

        real(dp), parameter :: dt = 1.0e-4_dp
        integer, parameter :: n_steps = 2000
        class(convolver), allocatable :: exact
        real(dp) :: worst, peak

        exact = new_exact_convolver(sdof_modes(mass, stiffness, xi), dt)
        worst = max_error(exact, 'ramp', n_steps, stiffness, xi, 0.0_dp)
        peak = force/stiffness
        call note('max error/(F/K)', worst/peak)
        call note('w0*F/(F/K)', exact%instant_weight()*stiffness)
        call check(error, worst/peak, 0.0_dp, 'exact on a ramp', thr=1.0e-12_dp)
    end subroutine test_ramp

    !> The ramp F*t/T on ten random modes (20-500 Hz): u(t) = (F/T)*sum_k 2*Re(r_k*
    !> (exp(lambda_k*t) - 1 - lambda_k*t)/lambda_k^2), to 1e-12 of max|u| (dt = 0.1 ms).
    subroutine test_ramp_modes(error)
        type(test_error), allocatable, intent(out) :: error

        real(dp), parameter :: dt = 1.0e-4_dp
        integer, parameter :: n_steps = 2000
        class(convolver), allocatable :: exact
        type(modal_set) :: modes
        real(dp) :: t, ramp_time, q, u, worst, peak
        integer :: n

        modes = random_modes(7, 10, 20.0_dp, 500.0_dp, 0.02_dp, 0.05_dp, 0.2_dp, 1.0_dp)
        exact = new_exact_convolver(modes, dt)
        ramp_time = n_steps*dt
        worst = 0.0_dp
        peak = 0.0_dp
        do n = 0, n_steps - 1
            t = n*dt
            q = force*t/ramp_time
            u = 0.0_dp
            if (n > 0) u = force/ramp_time*2.0_dp*sum(real(modes%residue &
                           *(exp(modes%pole*t) - 1.0_dp - modes%pole*t)/modes%pole**2, dp))
            worst = max(worst, abs(exact%history() + exact%instant_weight()*q - u))
            peak = max(peak, abs(u))
            call exact%push(q)
        end do
        call note('max error/max|u|', worst/peak)
        call check(error, worst/peak, 0.0_dp, 'exact on a ramp, 10 modes', thr=1.0e-12_dp)
    end subroutine test_ramp_modes

    !> Errors at dt = 0.2, 0.1, 0.05 ms over 0.1 s (Tab. 1's oscillator, W = 700 rad/s):
    !> each halving of dt divides the error by 4 within 10 % (order 2 +- 0.15), and the error
    !> at 0.1 ms is within the hold bound (sine) or, for the step given F/2 at t = 0, within
    !> 1.1 times its leading term (dt^2/6)*F*max|g'| = (dt^2/6)*F/M (the hat functions
    !> around t = 0 shift the load's first moment by -F*dt^2/6).
    subroutine test_exact_order(error)
        type(test_error), allocatable, intent(out) :: error

        character(len=4), parameter :: loads(2) = ['step', 'sine']
        real(dp), parameter :: w = 700.0_dp
        class(convolver), allocatable :: conv
        real(dp) :: errors(3), dt, order, bound, wd
        integer :: i, j

        wd = sqrt(stiffness/mass)*sqrt(1.0_dp - xi**2)
        do j = 1, 2
            do i = 1, 3
                dt = 2.0e-4_dp/2**(i - 1)
                conv = new_exact_convolver(sdof_modes(mass, stiffness, xi), dt)
                errors(i) = max_error(conv, loads(j), 500*2**(i - 1), stiffness, xi, w)
            end do
            do i = 1, 2
                order = log(errors(i)/errors(i + 1))/log(2.0_dp)
                call note(loads(j)//' order', order)
                call check(error, order, 2.0_dp, 'observed order of exact, '//loads(j), thr=0.15_dp)
                if (allocated(error)) return
            end do
            if (loads(j) == 'step') then
                bound = 1.1_dp*1.0e-8_dp/6.0_dp*force/mass
            else
                bound = 1.0e-8_dp/8.0_dp*w**2*force/(mass*wd*xi*sqrt(stiffness/mass))
            end if
            call note(loads(j)//' error/bound', errors(2)/bound)
            call check(error, errors(2), 0.0_dp, 'exact error at 0.1 ms, '//loads(j), thr=bound)
            if (allocated(error)) return
        end do
    end subroutine test_exact_order

    !> Tab. 1's oscillator under F*sin(100 t) (the road frequency of Tab. 1), dt = 0.1 ms,
    !> 2000 steps: `exact` at least 10 times more accurate than `paper`. (The hold's error is
    !> about (dt^2/12)*W^2*|u|, the rectangle rule's (dt^2/12)*|q/M + g*F*W|: the hold wins
    !> for W well below the mode, W^2/(omega^2 - W^2) < 1, not above it.)
    subroutine test_exact_sine(error)
        type(test_error), allocatable, intent(out) :: error

        real(dp), parameter :: dt = 1.0e-4_dp
        class(convolver), allocatable :: paper, exact
        real(dp) :: err_paper, err_exact
        integer :: i
        real(dp), parameter :: loads(3) = [100.0_dp, 700.0_dp, 3000.0_dp]

        do i = 1, 3
            paper = new_paper_convolver(sdof_modes(mass, stiffness, xi), dt)
            exact = new_exact_convolver(sdof_modes(mass, stiffness, xi), dt)
            err_paper = max_error(paper, 'sine', 2000, stiffness, xi, loads(i))
            err_exact = max_error(exact, 'sine', 2000, stiffness, xi, loads(i))
            call note('W', loads(i))
            call note('paper/exact error', err_paper/err_exact)
        end do
        paper = new_paper_convolver(sdof_modes(mass, stiffness, xi), dt)
        exact = new_exact_convolver(sdof_modes(mass, stiffness, xi), dt)
        err_paper = max_error(paper, 'sine', 2000, stiffness, xi, 100.0_dp)
        err_exact = max_error(exact, 'sine', 2000, stiffness, xi, 100.0_dp)
        call check(error, err_exact < 0.1_dp*err_paper, 'exact 10 times more accurate than paper at W = 100 rad/s')
    end subroutine test_exact_sine

    !> `backward` against its definition u(t_n) = sum_{m<=n} q_m*a_{n-m} summed directly, with
    !> a_j = int_{j*dt}^{(j+1)*dt} g(s) ds from the closed-form g of the oscillator by 5-point
    !> Gauss-Legendre on 4 sub-intervals per step (omega*h <= 0.25: quadrature error below
    !> 1e-16 relative), for a random load in [-F, F], dt = 0.1 ms and 1 ms, 2000 steps.
    subroutine test_backward_definition(error)
        type(test_error), allocatable, intent(out) :: error

        integer, parameter :: n_steps = 2000, sub = 4
        real(dp), parameter :: nodes(5) = [-0.9061798459386640_dp, -0.5384693101056831_dp, 0.0_dp, &
                                           0.5384693101056831_dp, 0.9061798459386640_dp]
        real(dp), parameter :: weights(5) = [0.2369268850561891_dp, 0.4786286704993665_dp, &
                                             0.5688888888888889_dp, 0.4786286704993665_dp, 0.2369268850561891_dp]
        class(convolver), allocatable :: backward
        type(random_stream) :: stream
        real(dp) :: a(0:n_steps - 1), q(0:n_steps - 1), dt, h, centre, u, worst, peak
        integer :: trial, j, i, n

        do trial = 1, 2
            dt = 10.0_dp**(-5 + trial)
            h = dt/sub
            do j = 0, n_steps - 1
                a(j) = 0.0_dp
                do i = 0, sub - 1
                    centre = j*dt + (i + 0.5_dp)*h
                    a(j) = a(j) + 0.5_dp*h*sum(weights*sdof_impulse(mass, stiffness, xi, centre + 0.5_dp*h*nodes))
                end do
            end do
            backward = new_backward_convolver(sdof_modes(mass, stiffness, xi), dt)
            call check(error, backward%instant_weight(), a(0), 'backward: w0 = a_0', thr=1.0e-12_dp, rel=.true.)
            if (allocated(error)) return
            stream = random_stream(11 + trial)
            worst = 0.0_dp
            peak = 0.0_dp
            do n = 0, n_steps - 1
                q(n) = stream%between(-force, force)
                u = sum(q(0:n)*a(n:0:-1))
                worst = max(worst, abs(backward%history() + backward%instant_weight()*q(n) - u))
                peak = max(peak, abs(u))
                call backward%push(q(n))
            end do
            call note('dt', dt)
            call note('max error/max|u|', worst/peak)
            call check(error, worst/peak, 0.0_dp, 'backward against its definition', thr=1.0e-12_dp)
            if (allocated(error)) return
        end do
    end subroutine test_backward_definition

    !> A constant force F from step 0: u(t_n) = F*sum_{j<=n} a_j tends to F*int g = F/K
    !> exactly; after 3 s (exp(-xi*omega*t) = e^-60) it is F/K to 1e-12, at dt = 0.1 ms and 1 ms.
    subroutine test_backward_static(error)
        type(test_error), allocatable, intent(out) :: error

        class(convolver), allocatable :: backward
        real(dp) :: dt
        integer :: trial, n

        do trial = 1, 2
            dt = 10.0_dp**(-5 + trial)
            backward = new_backward_convolver(sdof_modes(mass, stiffness, xi), dt)
            do n = 1, nint(3.0_dp/dt)
                call backward%push(force)
            end do
            call note('|u - F/K|/(F/K)', abs(backward%history() + backward%instant_weight()*force &
                                             - force/stiffness)*stiffness/force)
            call check(error, backward%history() + backward%instant_weight()*force, force/stiffness, &
                       'backward: static u = F/K', thr=1.0e-12_dp, rel=.true.)
            if (allocated(error)) return
        end do
    end subroutine test_backward_static

    !> Errors under F*sin(W t), W = 700 rad/s, at dt = 0.2, 0.1, 0.05 ms over 0.1 s: the hold
    !> delays the force by dt/2 on average, an error of (dt/2)*|q'| times the gain, so each
    !> halving of dt halves the error: order 1 +- 0.1.
    subroutine test_backward_order(error)
        type(test_error), allocatable, intent(out) :: error

        real(dp), parameter :: w = 700.0_dp
        class(convolver), allocatable :: conv
        real(dp) :: errors(3), dt, order
        integer :: i

        do i = 1, 3
            dt = 2.0e-4_dp/2**(i - 1)
            conv = new_backward_convolver(sdof_modes(mass, stiffness, xi), dt)
            errors(i) = max_error(conv, 'sine', 500*2**(i - 1), stiffness, xi, w)
        end do
        call note('max error/(F/K), dt = 0.1 ms', errors(2)*stiffness/force)
        do i = 1, 2
            order = log(errors(i)/errors(i + 1))/log(2.0_dp)
            call note('sine order', order)
            call check(error, order, 1.0_dp, 'observed order of backward, sine', thr=0.1_dp)
            if (allocated(error)) return
        end do
    end subroutine test_backward_order

end module test_engines_mod
