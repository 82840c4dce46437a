!> What the speed-against-accuracy chart of greenconv-bench rests on, checked on the SDOF
!> scene of section 3.1 (Tab. 1, A0 = 1 mm, preload M*g, 0.2 s):
!>
!> - nested grids: the ODE reference computed on a fine grid and read every 4th sample is
!>   the reference computed on the coarse grid itself, to the integrator's tolerance
!>   (rtol 1e-10; bound 1e-8 of max|u|, measured 1.5e-9);
!> - order in dt against that reference, log2(err(2 dt)/err(dt)) of the relative L2 error of
!>   u at dt = 0.2 and 0.1 ms: 2 for recursive and paper, whose error is the static gain error
!>   of the sampled convolution, (omega0*dt)^2/12, and 2 for exact (first-order hold); bound
!>   2 +- 0.1 (measured within 0.01);
!> - the size of that error: recursive at dt = 0.1 ms is (omega0*dt)^2/12 = 8.3e-4 to 10 %,
!>   since the body follows the road slowly (omega_r = omega0/10), almost statically.
module test_accuracy_mod
    use, intrinsic :: iso_fortran_env, only: dp => real64
    use testsuite_mod, only: test_error, unittest_type, new_unittest, check, note
    use greenconv_api_all, only: convolver, contact_law, contact_response, run_contact, sdof_modes, make_convolver, &
                                 error_type, sine_road, structure_from_modes, structure_model
    use verify_contact_mod, only: contact_reference
    use greenconv_contact_law_power, only: power_law
    implicit none
    private

    public :: collect_accuracy

    real(dp), parameter :: mass = 1.0_dp, stiffness = 1.0e6_dp, xi = 0.02_dp
    real(dp), parameter :: amplitude = 1.0e-3_dp, omega_road = 100.0_dp
    real(dp), parameter :: k_contact = 1.0e6_dp, exponent = 1.5_dp, preload = 9.81_dp
    !> Simulated time [s] and the finest time step [s] (the coarser ones are 2x and 4x).
    real(dp), parameter :: duration = 0.2_dp, fine_dt = 5.0e-5_dp

contains

    !> Tests of the chart's reference and error measure.
    subroutine collect_accuracy(testsuite)
        type(unittest_type), allocatable, intent(out) :: testsuite(:)

        testsuite = [new_unittest('reference on a fine grid, read every 4th sample = reference on the coarse grid', &
                                  test_nested_reference), &
                     new_unittest('order in dt against the ODE: recursive, paper and exact 2', test_orders), &
                     new_unittest('recursive error at 0.1 ms = static gain error (omega0*dt)^2/12', &
                                  test_static_gain_error)]
    end subroutine collect_accuracy

    !> The scene's road.
    function scene_road() result(road)
        type(sine_road) :: road

        road%amplitude = amplitude
        road%omega = omega_road
    end function scene_road

    !> The ODE reference over the run at step dt: u [m] and F [N].
    subroutine reference(dt, u, f)
        real(dp), intent(in) :: dt
        real(dp), allocatable, intent(out) :: u(:), f(:)

        call contact_reference(sdof_modes(mass, stiffness, xi), power_law(k_contact, exponent), scene_road(), &
                               preload, dt, nint(duration/dt), u, f)
    end subroutine reference

    !> Relative L2 error of u of `method` at dt = stride*fine_dt against the fine reference u_fine.
    subroutine method_error(method, stride, u_fine, err, error)
        character(len=*), intent(in) :: method
        integer, intent(in) :: stride
        real(dp), intent(in) :: u_fine(:)
        real(dp), intent(out) :: err
        type(test_error), allocatable, intent(out) :: error

        class(convolver), allocatable :: conv
        type(contact_response) :: response
        type(structure_model) :: structure
        type(error_type), allocatable :: failure
        character(len=:), allocatable :: accuracy
        type(sine_road) :: road
        real(dp) :: dt
        integer :: n_steps

        dt = stride*fine_dt
        n_steps = nint(duration/dt)
        structure = structure_from_modes(sdof_modes(mass, stiffness, xi))
        call make_convolver(method, structure, dt, 0.01_dp, n_steps, conv, accuracy, failure)
        err = huge(err)
        call check(error, .not. allocated(failure), method//': make_convolver failed')
        if (allocated(error)) return
        road = scene_road()
        call run_contact(conv, power_law(k_contact, exponent), road%sample(dt, n_steps), preload, response)
        err = norm2(response%displacement - u_fine(::stride))/norm2(u_fine(::stride))
    end subroutine method_error

    subroutine test_nested_reference(error)
        type(test_error), allocatable, intent(out) :: error

        real(dp), allocatable :: u_fine(:), f_fine(:), u_coarse(:), f_coarse(:)

        call reference(fine_dt, u_fine, f_fine)
        call reference(4*fine_dt, u_coarse, f_coarse)
        call check(error, size(u_fine(::4)) == size(u_coarse), 'the coarse grid has every 4th fine sample')
        if (allocated(error)) return
        call note('max du/max|u|', maxval(abs(u_fine(::4) - u_coarse))/maxval(abs(u_coarse)))
        call note('max dF/max F', maxval(abs(f_fine(::4) - f_coarse))/maxval(f_coarse))
        call check(error, maxval(abs(u_fine(::4) - u_coarse)), 0.0_dp, 'u on nested grids', &
                   thr=1.0e-8_dp*maxval(abs(u_coarse)))
        if (allocated(error)) return
        call check(error, maxval(abs(f_fine(::4) - f_coarse)), 0.0_dp, 'F on nested grids', &
                   thr=1.0e-8_dp*maxval(f_coarse))
    end subroutine test_nested_reference

    subroutine test_orders(error)
        type(test_error), allocatable, intent(out) :: error

        character(len=9), parameter :: methods(3) = [character(len=9) :: 'recursive', 'paper', 'exact']
        real(dp), allocatable :: u_fine(:), f_fine(:)
        real(dp) :: coarse, fine, order
        integer :: i

        call reference(fine_dt, u_fine, f_fine)
        do i = 1, size(methods)
            call method_error(trim(methods(i)), 4, u_fine, coarse, error)
            if (allocated(error)) return
            call method_error(trim(methods(i)), 2, u_fine, fine, error)
            if (allocated(error)) return
            order = log(coarse/fine)/log(2.0_dp)
            call note(trim(methods(i))//' order', order)
            call check(error, order, 2.0_dp, trim(methods(i))//': order in dt', thr=0.1_dp)
            if (allocated(error)) return
        end do
    end subroutine test_orders

    subroutine test_static_gain_error(error)
        type(test_error), allocatable, intent(out) :: error

        real(dp), allocatable :: u_fine(:), f_fine(:)
        real(dp) :: err, gain_error

        call reference(fine_dt, u_fine, f_fine)
        call method_error('recursive', 2, u_fine, err, error)
        if (allocated(error)) return
        gain_error = (sqrt(stiffness/mass)*2*fine_dt)**2/12.0_dp
        call note('err_u', err)
        call note('(omega0*dt)^2/12', gain_error)
        call check(error, err, gain_error, 'relative L2 error of u against (omega0*dt)^2/12', thr=0.1_dp, rel=.true.)
    end subroutine test_static_gain_error

end module test_accuracy_mod
