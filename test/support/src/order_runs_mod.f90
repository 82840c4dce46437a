!> Multi-point contact runs whose forces are measured against the modal ODE of the true
!> structure (verify_contact_mod) at three time steps: the setup (structure, laws,
!> preloads, a smooth road of three waves), the forces of a method and of the reference, the
!> error and the observed order. Shared by the suites multiorder (contact) and accuracystatus
!> (scene).
module order_runs_mod
    use, intrinsic :: iso_fortran_env, only: dp => real64
    use testsuite_mod, only: test_error, check, note
    use greenconv_core_error, only: error_type
    use greenconv_model_road, only: road_profile
    use greenconv_model_point_modes, only: point_modes
    use greenconv_contact_laws, only: contact_law, power_law
    use greenconv_contact_multi, only: multi_contact_response, run_multi_contact
    use greenconv_conv_multipoint, only: multipoint_convolver
    use greenconv_conv_builder, only: make_multipoint_convolver
    use verify_contact_mod, only: multi_contact_reference
    use greenconv_ident_green_structure, only: green_structure
    use greenconv_conv_green_file, only: green_file_convolver
    implicit none
    private

    public :: run_setup, wave_road, wave_setup, reference_forces, method_forces, force_error, measure

    real(dp), parameter :: pi = acos(-1.0_dp)
    !> Travel speed [m/s].
    real(dp), parameter :: speed = 8.0_dp
    !> A smooth road seen by one point: sum_k a_k*sin(2*pi*(x0 + V*t)/lambda_k + phase_k).
    type, extends(road_profile) :: wave_road
        !> Position [m] of the point on the road at t = 0.
        real(dp) :: x0 = 0.0_dp
    contains
        procedure :: height => wave_height
    end type wave_road

    !> A contact run to measure: structure, laws, preloads, roads, length and finest step.
    type :: run_setup
        !> The structure's modes and shapes at the points.
        type(point_modes) :: description
        !> Contact law of each point.
        type(power_law), allocatable :: laws(:)
        !> Static preloads F0_i [N].
        real(dp), allocatable :: preload(:)
        !> The road under each point.
        class(road_profile), allocatable :: roads(:)
        !> Simulated time [s].
        real(dp) :: duration = 0.06_dp
        !> The finest step [s]; the others are 2x and 4x.
        real(dp) :: fine_dt = 1.0e-5_dp
    end type run_setup
    !> Amplitudes [m], wavelengths [m] and phases of the road's three waves.
    real(dp), parameter :: wave_amplitude(3) = [6.0e-5_dp, 3.0e-5_dp, 1.5e-5_dp]
    real(dp), parameter :: wave_length(3) = [0.25_dp, 0.07_dp, 0.031_dp]
    real(dp), parameter :: wave_phase(3) = [0.7_dp, 2.1_dp, -1.3_dp]

contains

    !> sum_k a_k*sin(2*pi*(x0 + V*t)/lambda_k + phase_k) [m].
    elemental real(dp) function wave_height(self, t)
        class(wave_road), intent(in) :: self
        real(dp), intent(in) :: t

        integer :: k

        wave_height = 0.0_dp
        do k = 1, size(wave_amplitude)
            wave_height = wave_height + wave_amplitude(k)*sin(2.0_dp*pi*(self%x0 + speed*t)/wave_length(k) &
                                                              + wave_phase(k))
        end do
    end function wave_height

    !> A run on `description`: Hertz contact at every point (k_c = 1e7 N/m^1.5, 2 kHz shared
    !> evenly), the wave road under points 13 mm apart, 60 ms, finest step 10 us.
    function wave_setup(description) result(setup)
        type(point_modes), intent(in) :: description
        type(run_setup) :: setup

        type(wave_road), allocatable :: roads(:)
        integer :: i, n_c

        n_c = description%n_points()
        setup%description = description
        setup%laws = [(power_law(1.0e7_dp, 1.5_dp), i=1, n_c)]
        setup%preload = [(2000.0_dp/n_c, i=1, n_c)]
        allocate (roads(n_c))
        roads(:)%x0 = [(0.013_dp*i, i=1, n_c)]
        call move_alloc(roads, setup%roads)
    end function wave_setup

    !> The reference forces at dt (0:n_steps-1, N_c) [N], with its tolerance rtol.
    subroutine reference_forces(setup, dt, rtol, force)
        type(run_setup), intent(in) :: setup
        real(dp), intent(in) :: dt, rtol
        real(dp), allocatable, intent(out) :: force(:, :)

        real(dp), allocatable :: u(:, :)

        call multi_contact_reference(setup%description, setup%laws, setup%roads, setup%preload, dt, &
                                     nint(setup%duration/dt), u, force, rtol)
    end subroutine reference_forces

    !> The forces (0:n_steps-1, N_c) [N] of `method` at dt, on the setup's modes or on `green`.
    subroutine method_forces(setup, method, dt, force, error, green)
        type(run_setup), intent(in) :: setup
        character(len=*), intent(in) :: method
        real(dp), intent(in) :: dt
        real(dp), allocatable, intent(out) :: force(:, :)
        type(test_error), allocatable, intent(out) :: error
        type(green_structure), intent(in), optional :: green

        class(multipoint_convolver), allocatable :: conv
        type(multi_contact_response) :: response
        type(error_type), allocatable :: failure
        character(len=:), allocatable :: accuracy
        real(dp), allocatable :: road(:, :)
        integer :: n_steps, i, n

        n_steps = nint(setup%duration/dt)
        allocate (road(0:n_steps - 1, size(setup%roads)))
        do i = 1, size(setup%roads)
            road(:, i) = [(setup%roads(i)%height(n*dt), n=0, n_steps - 1)]
        end do
        if (present(green)) then
            call green_file_convolver(green, method, dt, 0.0_dp, n_steps, conv, accuracy, failure)
        else
            call make_multipoint_convolver(method, setup%description, dt, 0.0_dp, n_steps, conv, accuracy, failure)
        end if
        if (.not. allocated(failure)) call run_multi_contact(conv, setup%laws, road, setup%preload, response, failure)
        if (allocated(failure)) then
            call check(error, .false., method//': '//failure%message)
            return
        end if
        force = response%force
    end subroutine method_forces

    !> e = ||F - F_ref||_2/||F_ref - F0||_2 with F_ref on a grid `stride` times finer.
    real(dp) function force_error(force, reference, stride, preload) result(e)
        real(dp), intent(in) :: force(0:, :), reference(0:, :)
        integer, intent(in) :: stride
        real(dp), intent(in) :: preload(:)

        integer :: n

        e = 0.0_dp
        do n = 0, ubound(force, 1)
            e = e + sum((force(n, :) - reference(n*stride, :))**2)
        end do
        e = sqrt(e/sum((reference(0:ubound(force, 1)*stride:stride, :) - spread(preload, 1, ubound(force, 1) + 1))**2))
    end function force_error

    !> Errors at 4, 2 and 1 times the finest step against the reference on the finest grid,
    !> and the orders of the two halvings.
    subroutine measure(setup, method, label, errors, orders, error, green)
        type(run_setup), intent(in) :: setup
        character(len=*), intent(in) :: method, label
        real(dp), intent(out) :: errors(3), orders(2)
        type(test_error), allocatable, intent(out) :: error
        type(green_structure), intent(in), optional :: green

        real(dp), allocatable :: reference(:, :), force(:, :)
        integer :: level, stride

        call reference_forces(setup, setup%fine_dt, 1.0e-10_dp, reference)
        do level = 1, 3
            stride = 2**(3 - level)
            call method_forces(setup, method, stride*setup%fine_dt, force, error, green)
            if (allocated(error)) return
            errors(level) = force_error(force, reference, stride, setup%preload)
        end do
        orders(:) = log(errors(1:2)/errors(2:3))/log(2.0_dp)
        call note(label//' e(4 dt)', errors(1))
        call note(label//' e(2 dt)', errors(2))
        call note(label//' e(dt)', errors(3))
        call note(label//' order', orders(2))
        print '(a,a12,3es11.3,2f7.2)', '    ', label, errors, orders
    end subroutine measure

end module order_runs_mod
