!> The contact scene of section 3.1 (Tab. 1, with A0 = 1 mm and the preload M*g) run by
!> both convolutions and checked against each other, against the unilateral law, and
!> against an independent reference: the state-space ODE of the oscillator with the same
!> contact spring, integrated by an adaptive Dormand-Prince 5(4) method at tolerance 1e-12.
module test_contact_mod
    use, intrinsic :: iso_fortran_env, only: dp => real64
    use testsuite_mod, only: test_error, unittest_type, new_unittest, check, note
    use verify_ode_mod, only: ode_system, integrate
    use greenconv_api_all, only: convolver, contact_law, contact_response, run_contact, sdof_modes, make_convolver, &
                                 error_type, sine_road, structure_from_modes
    use verify_contact_mod, only: contact_reference
    use greenconv_contact_law_power, only: power_law
    implicit none
    private

    public :: collect_contact

    real(dp), parameter :: mass = 1.0_dp, stiffness = 1.0e6_dp, xi = 0.02_dp
    real(dp), parameter :: amplitude = 1.0e-3_dp, omega_road = 100.0_dp
    real(dp), parameter :: k_contact = 1.0e6_dp, exponent = 1.5_dp, preload = 9.81_dp
    real(dp), parameter :: dt = 1.0e-4_dp
    integer, parameter :: n_steps = 2000

    !> M u'' + C u' + K u = 1 N (a unit step), from rest.
    type, extends(ode_system) :: step_oscillator
    contains
        procedure :: rhs => oscillator
    end type step_oscillator

    !> M u'' + C u' + K u = F(delta0 + u_r(t) - u) - F0: the scene's contact, written again.
    type, extends(ode_system) :: contact_oscillator
    contains
        procedure :: rhs => contact_ode
    end type contact_oscillator

contains

    !> Tests of greenconv_contact_single on the SDOF scene.
    subroutine collect_contact(testsuite)
        type(unittest_type), allocatable, intent(out) :: testsuite(:)

        testsuite = [new_unittest('contact law: power law, zero in tension, inverse', test_law), &
                     new_unittest('reference integrator: oscillator step response', test_reference_integrator), &
                     new_unittest('library contact reference equals this test''s ODE', test_library_reference), &
                     new_unittest('direct and modal agree to round-off in the scene', test_methods_agree), &
                     new_unittest('F >= 0, and F = 0 exactly when delta <= 0', test_unilateral), &
                     new_unittest('direct within 1e-3 (relative L2) of the ODE reference', test_direct_reference), &
                     new_unittest('modal within 1e-3 (relative L2) of the ODE reference', test_modal_reference), &
                     new_unittest('paper within 1e-3 (relative L2) of the ODE reference', test_paper_reference), &
                     new_unittest('exact within 1e-4 (relative L2) of the ODE reference', test_exact_reference)]
    end subroutine collect_contact

    !> Run the scene with `method` (through the driver's factory, as a user scene would).
    subroutine run_method(method, response)
        character(len=*), intent(in) :: method
        type(contact_response), intent(out) :: response

        class(convolver), allocatable :: conv
        character(len=:), allocatable :: accuracy
        type(error_type), allocatable :: error
        type(sine_road) :: road

        call make_convolver(method, structure_from_modes(sdof_modes(mass, stiffness, xi)), dt, 0.01_dp, n_steps, &
                            conv, accuracy, error)
        if (allocated(error)) error stop 'test_contact_mod: cannot build a convolver'
        road%amplitude = amplitude
        road%omega = omega_road
        call run_contact(conv, power_law(k_contact, exponent), road%sample(dt, n_steps), preload, response)
    end subroutine run_method

    subroutine test_law(error)
        type(test_error), allocatable, intent(out) :: error

        type(power_law) :: law

        law = power_law(k_contact, exponent)
        call check(error, law%force(4.0e-4_dp), k_contact*4.0e-4_dp*sqrt(4.0e-4_dp), 'k_c*delta^1.5', &
                   thr=1.0e-14_dp, rel=.true.)
        if (allocated(error)) return
        call check(error, law%force(-1.0e-9_dp) == 0.0_dp .and. law%force(0.0_dp) == 0.0_dp, 'no force in tension')
        if (allocated(error)) return
        call check(error, law%force(law%compression(preload)), preload, 'force(compression(F0))', &
                   thr=1.0e-14_dp, rel=.true.)
    end subroutine test_law

    !> The integrator on M u'' + C u' + K u = F from rest, against the closed form.
    subroutine test_reference_integrator(error)
        type(test_error), allocatable, intent(out) :: error

        type(step_oscillator) :: system
        real(dp) :: y(2), h, t, w0, wd, a, exact
        integer :: n

        w0 = sqrt(stiffness/mass)
        wd = w0*sqrt(1.0_dp - xi**2)
        a = xi*w0
        y = 0.0_dp
        h = 1.0e-6_dp
        do n = 1, 200
            call integrate(system, (n - 1)*1.0e-3_dp, n*1.0e-3_dp, y, 1.0e-12_dp, [1.0e-18_dp, 1.0e-15_dp], h)
        end do
        t = 0.2_dp
        exact = 1.0_dp/stiffness*(1.0_dp - exp(-a*t)*(cos(wd*t) + a/wd*sin(wd*t)))
        call check(error, y(1), exact, 'u(0.2 s) under a unit step', thr=1.0e-10_dp/stiffness)
    end subroutine test_reference_integrator

    !> The step-loaded oscillator (self carries no data).
    subroutine oscillator(self, t, y, dydt)
        class(step_oscillator), intent(in) :: self
        real(dp), intent(in) :: t
        real(dp), intent(in) :: y(:)
        real(dp), intent(out) :: dydt(:)

        dydt(1) = y(2)
        dydt(2) = (1.0_dp - 2.0_dp*xi*sqrt(stiffness*mass)*y(2) - stiffness*y(1))/mass + 0.0_dp*t
    end subroutine oscillator

    subroutine test_methods_agree(error)
        type(test_error), allocatable, intent(out) :: error

        type(contact_response) :: direct, modal

        call run_method('direct', direct)
        call run_method('modal', modal)
        call note('max du/max|u|', &
                  maxval(abs(direct%displacement - modal%displacement))/maxval(abs(direct%displacement)))
        call check(error, maxval(abs(direct%displacement - modal%displacement)), 0.0_dp, 'max |u_direct - u_modal|', &
                   thr=1.0e-10_dp*maxval(abs(direct%displacement)))
        if (allocated(error)) return
        call check(error, maxval(abs(direct%force - modal%force)), 0.0_dp, 'max |F_direct - F_modal|', &
                   thr=1.0e-10_dp*maxval(direct%force))
    end subroutine test_methods_agree

    !> contact_reference (modal state space, used by the benchmark) against the oscillator
    !> written out here: both integrate the same ODE at 1e-12 and 1e-10, so they agree to
    !> well within 1e-7 of max|u|.
    subroutine test_library_reference(error)
        type(test_error), allocatable, intent(out) :: error

        real(dp) :: u_ref(0:n_steps - 1), f_ref(0:n_steps - 1)
        real(dp), allocatable :: u_lib(:), f_lib(:)
        type(sine_road) :: road

        road%amplitude = amplitude
        road%omega = omega_road
        call reference_solution(u_ref, f_ref)
        call contact_reference(sdof_modes(mass, stiffness, xi), power_law(k_contact, exponent), road, preload, &
                               dt, n_steps, u_lib, f_lib)
        call note('max du/max|u|', maxval(abs(u_lib - u_ref))/maxval(abs(u_ref)))
        call note('max dF/max F', maxval(abs(f_lib - f_ref))/maxval(f_ref))
        call check(error, maxval(abs(u_lib - u_ref)), 0.0_dp, 'contact_reference u', thr=1.0e-7_dp*maxval(abs(u_ref)))
        if (allocated(error)) return
        call check(error, maxval(abs(f_lib - f_ref)), 0.0_dp, 'contact_reference F', thr=1.0e-7_dp*maxval(f_ref))
    end subroutine test_library_reference

    subroutine test_unilateral(error)
        type(test_error), allocatable, intent(out) :: error

        type(contact_response) :: response
        character(len=6), parameter :: methods(2) = ['direct', 'modal ']
        integer :: i

        do i = 1, 2
            call run_method(trim(methods(i)), response)
            call check(error, all(response%force >= 0.0_dp), trim(methods(i))//': F >= 0')
            if (allocated(error)) return
            call check(error, all((response%force == 0.0_dp) .eqv. (response%compression <= 0.0_dp)), &
                       trim(methods(i))//': F = 0 exactly where delta <= 0')
            if (allocated(error)) return
            ! The scene must exercise both states, or the two checks above prove nothing.
            call check(error, count(response%force == 0.0_dp) > 100 .and. count(response%force > 0.0_dp) > 100, &
                       trim(methods(i))//': the body both loses and regains contact')
            if (allocated(error)) return
        end do
    end subroutine test_unilateral

    subroutine test_direct_reference(error)
        type(test_error), allocatable, intent(out) :: error
        call check_reference(error, 'direct')
    end subroutine test_direct_reference

    subroutine test_modal_reference(error)
        type(test_error), allocatable, intent(out) :: error
        call check_reference(error, 'modal')
    end subroutine test_modal_reference

    subroutine test_paper_reference(error)
        type(test_error), allocatable, intent(out) :: error
        call check_reference(error, 'paper')
    end subroutine test_paper_reference

    !> The first-order hold integrates the static gain exactly, so it must do better than the
    !> paper's sampling, whose static gain is off by (w0*dt)^2/12 = 8.3e-4.
    subroutine test_exact_reference(error)
        type(test_error), allocatable, intent(out) :: error
        call check_reference(error, 'exact', 1.0e-4_dp)
    end subroutine test_exact_reference

    !> Relative L2 errors of u and F against the ODE reference, each below `bound` (1e-3).
    subroutine check_reference(error, method, bound)
        type(test_error), allocatable, intent(out) :: error
        character(len=*), intent(in) :: method
        real(dp), intent(in), optional :: bound

        type(contact_response) :: response
        real(dp) :: u_ref(0:n_steps - 1), f_ref(0:n_steps - 1)
        real(dp) :: thr

        thr = 1.0e-3_dp
        if (present(bound)) thr = bound
        call reference_solution(u_ref, f_ref)
        call run_method(method, response)
        call note('u', norm2(response%displacement - u_ref)/norm2(u_ref))
        call note('F', norm2(response%force - f_ref)/norm2(f_ref))
        call check(error, norm2(response%displacement - u_ref)/norm2(u_ref), 0.0_dp, &
                   method//': relative L2 error of u', thr=thr)
        if (allocated(error)) return
        call check(error, norm2(response%force - f_ref)/norm2(f_ref), 0.0_dp, &
                   method//': relative L2 error of F', thr=thr)
    end subroutine check_reference

    !> M u'' + C u' + K u = F(delta0 + u_r(t) - u) - F0 from rest, sampled at t_n.
    subroutine reference_solution(u_ref, f_ref)
        real(dp), intent(out) :: u_ref(0:), f_ref(0:)

        type(contact_oscillator) :: system
        real(dp) :: y(2), h
        integer :: n

        y = 0.0_dp
        h = dt/10.0_dp
        do n = 0, n_steps - 1
            if (n > 0) call integrate(system, (n - 1)*dt, n*dt, y, 1.0e-12_dp, [1.0e-18_dp, 1.0e-15_dp], h)
            u_ref(n) = y(1)
            f_ref(n) = spring(static_compression() + amplitude*sin(omega_road*n*dt) - y(1))
        end do
    end subroutine reference_solution

    subroutine contact_ode(self, t, y, dydt)
        class(contact_oscillator), intent(in) :: self
        real(dp), intent(in) :: t
        real(dp), intent(in) :: y(:)
        real(dp), intent(out) :: dydt(:)

        dydt(1) = y(2)
        dydt(2) = (spring(static_compression() + amplitude*sin(omega_road*t) - y(1)) - preload &
                   - 2.0_dp*xi*sqrt(stiffness*mass)*y(2) - stiffness*y(1))/mass
    end subroutine contact_ode

    !> delta0 = (F0/k_c)^(1/p) [m].
    pure real(dp) function static_compression()
        static_compression = (preload/k_contact)**(1.0_dp/exponent)
    end function static_compression

    !> The contact spring written out again: k_c*delta^p in compression, zero otherwise.
    elemental real(dp) function spring(delta)
        real(dp), intent(in) :: delta

        spring = 0.0_dp
        if (delta > 0.0_dp) spring = k_contact*delta**exponent
    end function spring

end module test_contact_mod
