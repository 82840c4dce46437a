!> Both convolutions of known loads against the Duhamel integral in closed form.
!>
!> The discrete convolution u_n = dt*sum_{k<n} g_{n-k}*q_k is the trapezoidal rule of
!> u(t_n) = int_0^t_n g(t_n - tau)*q(tau) dtau when g(0) = 0 and q(0) is the load's mean
!> value at t = 0 (F/2 for a step switched on at t = 0). Its error is then
!> (dt^2/12)*[d/dtau (g(t_n - tau)*q(tau))] between the ends, which gives the tolerances:
!>   step F:         |error| <= (dt^2/12)*F*(|g'(0)| + max|g'|) <= (dt^2/6)*F/M
!>   sine F*sin(W t): |error| <= (dt^2/12)*F*(W*max|g| + 1/M) <= (dt^2/12)*F*(W/(M*wd) + 1/M)
!> and second order: halving dt divides the error by about 4.
module test_convolution_mod
    use, intrinsic :: iso_fortran_env, only: dp => real64
    use testsuite_mod, only: test_error, unittest_type, new_unittest, check, note
    use duhamel_mod, only: step_response, sine_response
    use, intrinsic :: iso_fortran_env, only: int64
    use, intrinsic :: ieee_arithmetic, only: ieee_is_nan
    use greenconv_api_all, only: convolver, modal_set, sdof_modes, sdof_impulse, new_direct_convolver, &
                                 new_paper_convolver, truncation_length, sample_kernel, direct_convolver, lane_dot
    use greenconv_core_random, only: random_stream
    implicit none
    private

    public :: collect_convolution

    real(dp), parameter :: mass = 1.0_dp, stiffness = 1.0e6_dp, xi = 0.02_dp
    real(dp), parameter :: force = 10.0_dp
    !> Sine load frequency [rad/s], below resonance (w0 = 1000 rad/s).
    real(dp), parameter :: omega_load = 700.0_dp

contains

    !> Tests of greenconv_conv_direct and greenconv_conv_paper.
    subroutine collect_convolution(testsuite)
        type(unittest_type), allocatable, intent(out) :: testsuite(:)

        testsuite = [new_unittest('direct: step load against Duhamel', test_direct_step), &
                     new_unittest('modal: step load against Duhamel', test_modal_step), &
                     new_unittest('direct: sine load against Duhamel', test_direct_sine), &
                     new_unittest('modal: sine load against Duhamel', test_modal_sine), &
                     new_unittest('second order in dt (step and sine, both methods)', test_order), &
                     new_unittest('direct and modal agree to round-off on a full kernel', test_agreement), &
                     new_unittest('direct: blocked sum against a plain sum, reset, NaN past the kernel', &
                                  test_direct_plain), &
                     new_unittest('truncation rule on a known kernel', test_truncation_rule), &
                     new_unittest('truncated sdof kernel: length and neglected tail', test_sdof_truncation)]
    end subroutine collect_convolution

    !> Largest |u_n - u(t_n)| over n steps of a convolver driven by a step or a sine load.
    function max_error(conv, load, n_steps) result(worst)
        class(convolver), intent(inout) :: conv
        character(len=*), intent(in) :: load
        integer, intent(in) :: n_steps
        real(dp) :: worst

        real(dp) :: t, q, exact
        integer :: n

        worst = 0.0_dp
        call conv%reset()
        do n = 0, n_steps - 1
            t = n*conv%dt
            if (load == 'step') then
                q = merge(0.5_dp*force, force, n == 0)
                exact = step_response(t, mass, stiffness, xi, force)
            else
                q = force*sin(omega_load*t)
                exact = sine_response(t, mass, stiffness, xi, force, omega_load)
            end if
            worst = max(worst, abs(conv%history() + conv%instant_weight()*q - exact))
            call conv%push(q)
        end do
    end function max_error

    !> A convolver of the sdof at step dt over n_steps: 'direct' (full kernel) or 'modal'.
    subroutine build(method, dt, n_steps, conv)
        character(len=*), intent(in) :: method
        real(dp), intent(in) :: dt
        integer, intent(in) :: n_steps
        class(convolver), allocatable, intent(out) :: conv

        real(dp), allocatable :: kernel(:)
        integer :: j

        if (method == 'direct') then
            allocate (kernel(0:n_steps))
            kernel(:) = sdof_impulse(mass, stiffness, xi, [(j*dt, j=0, n_steps)])
            conv = new_direct_convolver(kernel, dt)
        else
            conv = new_paper_convolver(sdof_modes(mass, stiffness, xi), dt)
        end if
    end subroutine build

    !> Check one method and load at dt = 0.1 ms over 0.2 s against its error bound.
    subroutine check_load(error, method, load)
        type(test_error), allocatable, intent(out) :: error
        character(len=*), intent(in) :: method, load

        real(dp), parameter :: dt = 1.0e-4_dp
        integer, parameter :: n_steps = 2000
        class(convolver), allocatable :: conv
        real(dp) :: bound, wd, worst

        wd = sqrt(stiffness/mass)*sqrt(1.0_dp - xi**2)
        if (load == 'step') then
            bound = dt**2/6.0_dp*force/mass
        else
            bound = dt**2/12.0_dp*force*(omega_load/(mass*wd) + 1.0_dp/mass)
        end if
        call build(method, dt, n_steps, conv)
        worst = max_error(conv, load, n_steps)
        call note('max error/bound', worst/bound)
        call check(error, worst, 0.0_dp, method//' '//load//' max error', thr=bound)
    end subroutine check_load

    subroutine test_direct_step(error)
        type(test_error), allocatable, intent(out) :: error
        call check_load(error, 'direct', 'step')
    end subroutine test_direct_step

    subroutine test_modal_step(error)
        type(test_error), allocatable, intent(out) :: error
        call check_load(error, 'modal', 'step')
    end subroutine test_modal_step

    subroutine test_direct_sine(error)
        type(test_error), allocatable, intent(out) :: error
        call check_load(error, 'direct', 'sine')
    end subroutine test_direct_sine

    subroutine test_modal_sine(error)
        type(test_error), allocatable, intent(out) :: error
        call check_load(error, 'modal', 'sine')
    end subroutine test_modal_sine

    !> The error ratio between dt and dt/2 over the same 0.1 s must be 4 within 10 %.
    subroutine test_order(error)
        type(test_error), allocatable, intent(out) :: error

        character(len=6), parameter :: methods(2) = ['direct', 'modal ']
        character(len=4), parameter :: loads(2) = ['step', 'sine']
        class(convolver), allocatable :: coarse, fine
        real(dp) :: order
        integer :: i, j

        do i = 1, 2
            do j = 1, 2
                call build(trim(methods(i)), 2.0e-4_dp, 500, coarse)
                call build(trim(methods(i)), 1.0e-4_dp, 1000, fine)
                order = log(max_error(coarse, loads(j), 500)/max_error(fine, loads(j), 1000))/log(2.0_dp)
                call note(trim(methods(i))//' '//loads(j), order)
                call check(error, order, 2.0_dp, 'observed order, '//trim(methods(i))//' '//loads(j), thr=0.15_dp)
                if (allocated(error)) return
            end do
        end do
    end subroutine test_order

    !> With a kernel covering the run, eq. (20) and the recursion (15)-(17) are the same sum.
    subroutine test_agreement(error)
        type(test_error), allocatable, intent(out) :: error

        class(convolver), allocatable :: direct, modal
        real(dp) :: q, u_direct, u_modal, worst, scale
        integer :: n

        call build('direct', 1.0e-4_dp, 3000, direct)
        call build('modal', 1.0e-4_dp, 3000, modal)
        worst = 0.0_dp
        scale = force/stiffness
        do n = 0, 2999
            u_direct = direct%history()
            u_modal = modal%history()
            worst = max(worst, abs(u_direct - u_modal))
            q = force*sin(0.013_dp*n**1.3_dp)
            call direct%push(q)
            call modal%push(q)
        end do
        call check(error, worst/scale, 0.0_dp, 'max |u_direct - u_modal|/(F/K)', thr=1.0e-11_dp)
    end subroutine test_agreement

    !> The blocked direct sum against a plain left-to-right sum of eq. (20) computed here from
    !> the same forces, and against one dot product per step (`lane_dot`, eight partial sums):
    !> random kernels of N_g = 1..9, 13, 64 and 1001 taps (every N_g mod 4 and every step of a
    !> block), random loads over 2*N_g + 23 steps (the ring filled and wrapped). Each sum is the
    !> same m = min(n, N_g) terms in its own order, so each lies within gamma_m*S of the exact
    !> one (gamma_m = m*eps/(1 - m*eps), S = sum |w_k*q_{n-k}|): the test asks
    !> |u - u_other| <= 2*gamma_m*S of both. A reset in the middle of a block repeats the first
    !> steps bit for bit; a kernel valid for 10 steps gives NaN at step 10 and not before.
    subroutine test_direct_plain(error)
        type(test_error), allocatable, intent(out) :: error

        integer, parameter :: lengths(12) = [1, 2, 3, 4, 5, 6, 7, 8, 9, 13, 64, 1001]
        real(dp), parameter :: dt = 1.0e-4_dp
        type(random_stream) :: stream
        type(direct_convolver) :: conv
        real(dp), allocatable :: kernel(:), w(:), q(:), first(:), newest(:)
        real(dp) :: u, plain, scale, gamma, worst_plain, worst_lane, relative_plain, relative_lane
        integer :: c, n_g, n_steps, n, k, m
        logical :: same, nan_late, finite_before

        stream = random_stream(2011)
        worst_plain = 0.0_dp
        worst_lane = 0.0_dp
        relative_plain = 0.0_dp
        relative_lane = 0.0_dp
        same = .true.
        do c = 1, size(lengths)
            n_g = lengths(c)
            n_steps = 2*n_g + 23
            allocate (kernel(0:n_g), q(0:n_steps - 1), first(0:n_steps - 1))
            do k = 0, n_g
                kernel(k) = stream%between(-1.0_dp, 1.0_dp)
            end do
            w = dt*kernel(1:n_g)
            conv = new_direct_convolver(kernel, dt)
            do n = 0, n_steps - 1
                m = min(n, n_g)
                u = conv%history()
                first(n) = u
                if (m == 0) then
                    same = same .and. u == 0.0_dp
                else
                    plain = 0.0_dp
                    scale = 0.0_dp
                    do k = 1, m
                        plain = plain + w(k)*q(n - k)
                        scale = scale + abs(w(k)*q(n - k))
                    end do
                    newest = [(q(n - k), k=1, m)]
                    gamma = m*epsilon(1.0_dp)/(1.0_dp - m*epsilon(1.0_dp))
                    worst_plain = max(worst_plain, abs(u - plain)/(2.0_dp*gamma*scale))
                    worst_lane = max(worst_lane, abs(u - lane_dot(m, w, newest))/(2.0_dp*gamma*scale))
                    relative_plain = max(relative_plain, abs(u - plain)/scale)
                    relative_lane = max(relative_lane, abs(u - lane_dot(m, w, newest))/scale)
                end if
                q(n) = stream%between(-10.0_dp, 10.0_dp)
                call conv%push(q(n))
            end do
            ! n_steps = 2*N_g + 23 leaves the block at every phase over the lengths.
            call conv%reset()
            do n = 0, min(n_steps, n_g + 9) - 1
                same = same .and. conv%history() == first(n)
                call conv%push(q(n))
            end do
            if (c < size(lengths)) deallocate (kernel)
            deallocate (q, first)
        end do
        call note('max |u - u_plain|/S', relative_plain)
        call note('max |u - u_lane_dot|/S', relative_lane)
        call check(error, same, 'direct: the history at step 0 is 0, and a reset repeats the run bit for bit')
        if (allocated(error)) return
        call check(error, worst_plain, 0.0_dp, 'max |u - u_plain|/(2*gamma_m*S)', thr=1.0_dp)
        if (allocated(error)) return
        call check(error, worst_lane, 0.0_dp, 'max |u - u_lane_dot|/(2*gamma_m*S)', thr=1.0_dp)
        if (allocated(error)) return
        conv = new_direct_convolver(kernel(0:3), dt, valid_steps=10_int64)
        finite_before = .true.
        do n = 0, 9
            finite_before = finite_before .and. .not. ieee_is_nan(conv%history())
            call conv%push(1.0_dp)
        end do
        nan_late = ieee_is_nan(conv%history())
        call check(error, finite_before .and. nan_late, 'direct: NaN from valid_steps on, finite before')
    end subroutine test_direct_plain

    !> g_j = (-1/2)^j: with tol = 0.01 the last kept sample is j = 6 (1/64 >= 0.01 > 1/128).
    subroutine test_truncation_rule(error)
        type(test_error), allocatable, intent(out) :: error

        real(dp) :: kernel(0:20)
        integer :: j

        kernel = [((-0.5_dp)**j, j=0, 20)]
        call check(error, truncation_length(kernel, 0.01_dp) == 6, 'N_g for (-1/2)^j at 1 %')
        if (allocated(error)) return
        call check(error, truncation_length(kernel, 0.5_dp) == 1, 'N_g for (-1/2)^j at 50 %')
    end subroutine test_truncation_rule

    !> The sdof envelope exp(-xi*w0*t) falls to 1 % of the peak at t = ln(100)/(xi*w0)
    !> (less the peak's own decay): N_g*dt must sit within one period of it, and the
    !> neglected samples must all stay below 1 % of max |g|.
    subroutine test_sdof_truncation(error)
        type(test_error), allocatable, intent(out) :: error

        real(dp), parameter :: dt = 1.0e-4_dp, tol = 0.01_dp
        real(dp), allocatable :: kernel(:), beyond(:)
        real(dp) :: tail, w0, peak, expected_time
        type(modal_set) :: modes
        integer :: n_g, j

        modes = sdof_modes(mass, stiffness, xi)
        call sample_kernel(modes, dt, tol, 10**6, kernel, tail)
        n_g = ubound(kernel, 1)
        w0 = sqrt(stiffness/mass)
        peak = maxval(abs(kernel))
        expected_time = log(1.0_dp/tol)/(xi*w0) - 0.5_dp*3.14159265358979_dp/w0
        call check(error, n_g*dt, expected_time, 'N_g*dt against the envelope', thr=2.0_dp*3.1416_dp/w0)
        if (allocated(error)) return
        beyond = sdof_impulse(mass, stiffness, xi, [(j*dt, j=n_g + 1, 2*n_g)])
        call check(error, maxval(abs(beyond)) < tol*peak, 'neglected samples below tol*max|g|')
        if (allocated(error)) return
        call check(error, tail, maxval(abs(beyond))/peak, 'reported tail', thr=1.0e-3_dp*tol)
        if (allocated(error)) return
        call check(error, tail < tol, 'tail below tol')
    end subroutine test_sdof_truncation

end module test_convolution_mod
