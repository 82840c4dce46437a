!> The cost of multi-point contact per time step: modal recursion against the sampled
!> Green's matrix, for the tyre of greenconv_model_tyre touched at N_c points.
!>
!> The paper's conclusion expects the modal method's gain to grow with the number of contact
!> points: a step costs O(N_c*N_m) with modes and O(N_c^2*N_g) with a sampled g_ij table.
!> `multipoint_cost_table` measures both, through the same loop (`multi_contact_step`):
!>
!> - the tyre with its default parameters, modes up to f_max = tyre_band(V, lambda_min, dt)
!>   with V = 20 m/s and lambda_min = 20 mm, i.e. 2 kHz at dt = 50 us (52 modes);
!> - N_c points evenly over a 0.15 m contact patch at mid-belt, Hertz springs (p = 3/2),
!>   a wheel load of 3 kN shared equally, static compression 1 mm at every point;
!> - the road of eq. (35) (A0 = 0.5 mm, lambda_r = 50 mm, 10 terms, seed 35) at V, each
!>   point seeing it x_i/V later than the patch centre;
!> - `recursive` (explicit) modal and `direct` sampled tables, the latter truncated by the
!>   1 % rule over all pairs; the direct loop's buffer is first filled with N_g steps of
!>   zero load, so that every timed step sums all N_g samples (the steady-state cost of a
!>   long run); the `exact` modal scheme (implicit: Newton, dgesv) is timed as well.
!>
!> CPU seconds per step are the CPU time of the timed steps over their number.
module bench_multipoint_mod
    use greenconv_core_kinds, only: dp
    use greenconv_core_error, only: error_type
    use greenconv_contact_single, only: contact_law
    use greenconv_model_road, only: random_road, new_random_road
    use greenconv_conv_multipoint, only: multipoint_convolver, sample_green_matrix
    use greenconv_model_point_modes, only: point_modes
    use greenconv_conv_green_modal, only: modal_green_matrix, new_modal_green_matrix
    use greenconv_conv_green_sampled, only: sampled_green_matrix, new_sampled_green_matrix
    use greenconv_contact_multi, only: newton_options, multi_contact_step
    use greenconv_model_tyre, only: tyre_belt, tyre_modes, tyre_band, contact_positions
    use greenconv_contact_law_power, only: power_law
    implicit none
    private

    public :: multipoint_cost_table

    !> Travel speed [m/s] and shortest road wavelength [m] of the band rule.
    real(dp), parameter :: speed = 20.0_dp, shortest_wavelength = 0.02_dp
    !> Contact patch length [m], wheel load [N] and static compression [m].
    real(dp), parameter :: patch = 0.15_dp, wheel_load = 3000.0_dp, compression0 = 1.0e-3_dp

    !> The contact scene a timing runs.
    type :: bench_scene
        type(power_law), allocatable :: laws(:)
        real(dp), allocatable :: preload(:), delta0(:), road(:, :)
    end type bench_scene

contains

    !> Print the CPU seconds per step of the modal and direct multi-point loops, for each N_c.
    !>
    !> One `#` line states the set-up, one `#` line names the columns:
    !> N_c, N_m, N_g, modal [s/step], direct [s/step], direct/modal, exact [s/step]
    !> (direct/modal is 0 when the modal loop ran faster than the CPU clock resolves).
    subroutine multipoint_cost_table(unit, error, n_points, n_steps_modal, n_steps_direct, dt)
        !> Unit the table is printed on.
        integer, intent(in) :: unit
        !> Set when a model cannot be built or a timed run fails.
        type(error_type), allocatable, intent(out) :: error
        !> Numbers of contact points N_c; (1, 10, 20, 50, 100) when absent.
        integer, intent(in), optional :: n_points(:)
        !> Timed steps of the modal loops (20000 when absent; the exact scheme runs a tenth).
        integer, intent(in), optional :: n_steps_modal
        !> Timed steps of the direct loop (50 when absent), after N_g warm-up steps.
        integer, intent(in), optional :: n_steps_direct
        !> Time step [s]; 5e-5 when absent.
        real(dp), intent(in), optional :: dt

        integer, allocatable :: counts(:)
        integer :: steps_modal, steps_direct, i
        real(dp) :: step, f_max

        if (present(n_points)) then
            allocate (counts(size(n_points)))
            counts(:) = n_points
        else
            allocate (counts(5))
            counts(:) = [1, 10, 20, 50, 100]
        end if
        steps_modal = 20000
        if (present(n_steps_modal)) steps_modal = n_steps_modal
        steps_direct = 50
        if (present(n_steps_direct)) steps_direct = n_steps_direct
        step = 5.0e-5_dp
        if (present(dt)) step = dt
        f_max = tyre_band(speed, shortest_wavelength, step)
        write (unit, '(a,f0.1,a,es9.2,a,i0,a,i0,a,i0,a)') '# tyre belt, modes up to ', f_max, ' Hz, dt = ', step, &
            ' s; modal ', steps_modal, ', direct ', steps_direct, ' (after N_g warm-up), exact ', &
            max(1, steps_modal/10), ' timed steps'
        write (unit, '(a)') '# N_c   N_m    N_g    modal_s_per_step  direct_s_per_step  direct/modal  exact_s_per_step'
        do i = 1, size(counts)
            call cost_row(unit, counts(i), step, f_max, steps_modal, steps_direct, error)
            if (allocated(error)) return
        end do
    end subroutine multipoint_cost_table

    !> Time the three loops at N_c points and print one row.
    subroutine cost_row(unit, n_c, dt, f_max, steps_modal, steps_direct, error)
        integer, intent(in) :: unit, n_c, steps_modal, steps_direct
        real(dp), intent(in) :: dt, f_max
        type(error_type), allocatable, intent(out) :: error

        type(tyre_belt) :: tyre
        type(point_modes) :: description
        type(bench_scene) :: scene
        type(modal_green_matrix) :: modal
        type(sampled_green_matrix) :: direct
        real(dp), allocatable :: kernel(:, :, :)
        real(dp) :: tail, t_modal, t_direct, t_exact, ratio
        integer :: n_m, n_g
        character(len=:), allocatable :: label

        call tyre_modes(tyre, contact_positions(0.5_dp*tyre%length, patch, n_c), f_max, description, error)
        if (allocated(error)) return
        call make_scene(n_c, dt, max(steps_modal, steps_direct), scene)
        call new_modal_green_matrix(description, dt, 'recursive', modal, error)
        if (allocated(error)) return
        call time_steps(modal, scene, 0, steps_modal, t_modal, error)
        if (allocated(error)) return
        call modal%model_size(n_m, label)
        call new_modal_green_matrix(description, dt, 'exact', modal, error)
        if (allocated(error)) return
        call time_steps(modal, scene, 0, max(1, steps_modal/10), t_exact, error)
        if (allocated(error)) return
        call sample_green_matrix(description, dt, 0.01_dp, huge(1), kernel, tail)
        call new_sampled_green_matrix(kernel, dt, direct, error)
        if (allocated(error)) return
        deallocate (kernel)
        call direct%model_size(n_g, label)
        call time_steps(direct, scene, n_g, steps_direct, t_direct, error)
        if (allocated(error)) return
        ratio = 0.0_dp
        if (t_modal > 0.0_dp) ratio = t_direct/t_modal
        write (unit, '(i5,i6,i7,3x,es14.4,5x,es14.4,5x,f10.1,3x,es14.4)') n_c, n_m, n_g, t_modal, t_direct, &
            ratio, t_exact
    end subroutine cost_row

    !> Hertz springs with 1 mm static compression under an equal share of the wheel load, and
    !> the road of eq. (35) under each point, for n_steps steps.
    subroutine make_scene(n_c, dt, n_steps, scene)
        integer, intent(in) :: n_c, n_steps
        real(dp), intent(in) :: dt
        type(bench_scene), intent(out) :: scene

        type(random_road) :: road
        real(dp) :: offset(n_c)
        integer :: i, n

        allocate (scene%laws(n_c), scene%preload(n_c), scene%delta0(n_c), scene%road(0:n_steps - 1, n_c))
        scene%preload(:) = wheel_load/n_c
        scene%laws(:) = power_law(wheel_load/n_c/compression0**1.5_dp, 1.5_dp)
        scene%delta0(:) = scene%laws%compression(scene%preload)
        road = new_random_road(35, 10, 0.5e-3_dp, 0.05_dp, speed)
        offset(:) = contact_positions(0.0_dp, patch, n_c)/speed
        do i = 1, n_c
            scene%road(:, i) = road%height([(n*dt + offset(i), n=0, n_steps - 1)])
        end do
    end subroutine make_scene

    !> CPU seconds per step of `n_steps` contact steps, after `warm_up` pushes of zero load.
    subroutine time_steps(conv, scene, warm_up, n_steps, seconds, error)
        class(multipoint_convolver), intent(inout) :: conv
        type(bench_scene), intent(in) :: scene
        integer, intent(in) :: warm_up, n_steps
        real(dp), intent(out) :: seconds
        type(error_type), allocatable, intent(out) :: error

        type(newton_options) :: options
        real(dp) :: delta(size(scene%laws)), force(size(scene%laws)), u(size(scene%laws)), start, finish
        integer :: n, iterations

        call conv%reset()
        force(:) = 0.0_dp
        do n = 1, warm_up
            call conv%push(force)
        end do
        delta(:) = scene%delta0
        call cpu_time(start)
        do n = 0, n_steps - 1
            call multi_contact_step(conv, scene%laws, scene%delta0, scene%preload, scene%road(n, :), delta, force, u, &
                                    iterations, error, options)
            if (allocated(error)) return
        end do
        call cpu_time(finish)
        seconds = (finish - start)/n_steps
    end subroutine time_steps

end module bench_multipoint_mod
