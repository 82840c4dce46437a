!> The cost of multi-point contact at a real patch's scale: CPU seconds per step of
!> the implicit `exact` loop (Newton on all points, its systems solved with the low-rank W0 of
!> greenconv_contact_lowrank_solve) and of the explicit `modal` loop against N_c, 20 to 4,000
!> points, at the fixed 52 modes of the tyre line, with the fitted growth exponents.
!>
!> The scene is bench_multipoint_mod's: the default tyre, modes up to 2 kHz (dt = 50 us,
!> V = 20 m/s), N_c points over a 0.15 m patch at mid-belt, Hertz springs at 1 mm static
!> compression under 3 kN, the road of eq. (35). Each run is streamed through
!> `start_multi_contact` and `multi_contact_block` (one start per run, as a scene runs): the
!> factorisation of W0, O(N_c^2*r) once, is timed apart as `start_s`.
!>
!> `direct` and `fft` hold an N_c x N_c x (N_g + 1) table of g_ij: that memory is printed
!> (N_g by the 1 % rule at 20 points, which barely moves with N_c) and they are not timed
!> here past 100 points (bench_multipoint_mod and bench_greenfft_mod time them up to there).
!>
!> Columns of DIR/scale_cost.dat and of the printed table: n_c n_m exact_s_per_step
!> modal_s_per_step start_s rank table_gb. A second printed table holds the same costs at
!> 1,000 points against N_m (the tyre's modes up to 500 Hz to 8 kHz).
module bench_scale_mod
    use greenconv_core_kinds, only: dp
    use greenconv_core_error, only: error_type
    use greenconv_contact_laws, only: contact_law
    use greenconv_model_road, only: random_road, new_random_road
    use greenconv_conv_multipoint, only: sample_green_matrix
    use greenconv_model_point_modes, only: point_modes
    use greenconv_conv_green_modal, only: modal_green_matrix, new_modal_green_matrix
    use greenconv_contact_step, only: contact_options
    use greenconv_contact_multi, only: multi_contact_state, multi_contact_response, start_multi_contact, &
                                       multi_contact_block
    use greenconv_model_tyre, only: tyre_belt, tyre_modes, tyre_band, contact_positions
    use greenconv_contact_law_power, only: power_law
    implicit none
    private

    public :: scale_cost_table

    !> Travel speed [m/s], shortest road wavelength [m], time step [s].
    real(dp), parameter :: speed = 20.0_dp, shortest_wavelength = 0.02_dp, dt = 5.0e-5_dp
    !> Contact patch length [m], wheel load [N] and static compression [m].
    real(dp), parameter :: patch = 0.15_dp, wheel_load = 3000.0_dp, compression0 = 1.0e-3_dp

contains

    !> Print and write the cost per step against N_c, then the fitted exponents.
    subroutine scale_cost_table(unit, output_dir, error, n_points, n_steps)
        !> Unit the table is printed on.
        integer, intent(in) :: unit
        !> Folder of scale_cost.dat.
        character(len=*), intent(in) :: output_dir
        !> Set when a model cannot be built or a run fails.
        type(error_type), allocatable, intent(out) :: error
        !> Numbers of contact points; (20, 80, 320, 1000, 2000, 4000) when absent.
        integer, intent(in), optional :: n_points(:)
        !> Timed steps per run (200 when absent).
        integer, intent(in), optional :: n_steps

        integer, allocatable :: counts(:)
        real(dp), allocatable :: exact(:), modal(:)
        real(dp) :: f_max, start, table_gb
        integer :: steps, i, n_m, rank, n_g, file
        character(len=*), parameter :: columns = '# n_c   n_m  exact_s_per_step  modal_s_per_step  start_s' &
                                                 //'  rank  table_gb'

        counts = [20, 80, 320, 1000, 2000, 4000]
        if (present(n_points)) counts = n_points
        steps = 200
        if (present(n_steps)) steps = n_steps
        f_max = tyre_band(speed, shortest_wavelength, dt)
        n_g = table_length(f_max)
        allocate (exact(size(counts)), modal(size(counts)))
        open (newunit=file, file=output_dir//'/scale_cost.dat', status='replace', action='write')
        write (unit, '(a,f0.1,a,i0,a,i0,a)') '# multi-point cost at scale: tyre modes up to ', f_max, ' Hz, ', steps, &
            ' steps per run; direct/fft table N_c^2*(N_g+1)*8 bytes, N_g = ', n_g, ' (not timed here)'
        write (file, '(a,f0.1,a,i0,a)') '# multi-point cost at scale: tyre modes up to ', f_max, ' Hz, ', steps, &
            ' steps per run'
        write (unit, '(a)') columns
        write (file, '(a)') columns
        do i = 1, size(counts)
            call time_runs(counts(i), f_max, steps, exact(i), modal(i), start, n_m, rank, error)
            if (allocated(error)) then
                close (file)
                return
            end if
            table_gb = real(counts(i), dp)**2*(n_g + 1)*8.0_dp/1.0e9_dp
            write (unit, '(i5,i6,2(3x,es14.4),3x,es10.3,i6,3x,es10.3)') counts(i), n_m, exact(i), modal(i), start, &
                rank, table_gb
            write (file, '(i5,i6,2(3x,es14.4),3x,es10.3,i6,3x,es10.3)') counts(i), n_m, exact(i), modal(i), start, &
                rank, table_gb
        end do
        close (file)
        write (unit, '(a,f6.2,a,f6.2,a)') '# fitted growth t ~ N_c^p: exact p = ', exponent(counts, exact), &
            ', modal p = ', exponent(counts, modal), ''
        call modes_cost_table(unit, steps, error)
    end subroutine scale_cost_table

    !> Print the cost per step against N_m (modes up to 500 Hz to 8 kHz) at 1,000 points, then
    !> the fitted exponents.
    subroutine modes_cost_table(unit, steps, error)
        integer, intent(in) :: unit, steps
        type(error_type), allocatable, intent(out) :: error

        real(dp), parameter :: bands(5) = [500.0_dp, 1000.0_dp, 2000.0_dp, 4000.0_dp, 8000.0_dp]
        integer, parameter :: n_c = 1000
        real(dp) :: exact(size(bands)), modal(size(bands)), start
        integer :: modes(size(bands)), rank, i

        write (unit, '(a,i0,a)') '# the same at ', n_c, ' points against the number of modes N_m (f_max 500 Hz to 8 kHz)'
        write (unit, '(a)') '# n_c   n_m  exact_s_per_step  modal_s_per_step  start_s  rank'
        do i = 1, size(bands)
            call time_runs(n_c, bands(i), steps, exact(i), modal(i), start, modes(i), rank, error)
            if (allocated(error)) return
            write (unit, '(i5,i6,2(3x,es14.4),3x,es10.3,i6)') n_c, modes(i), exact(i), modal(i), start, rank
        end do
        write (unit, '(a,f6.2,a,f6.2,a)') '# fitted growth t ~ N_m^p: exact p = ', exponent(modes, exact), &
            ', modal p = ', exponent(modes, modal), ''
        write (unit, '(a)') ''
    end subroutine modes_cost_table

    !> N_g of the 1 % rule for the tyre at 20 points (the table the sampled methods would hold).
    integer function table_length(f_max) result(n_g)
        real(dp), intent(in) :: f_max

        type(point_modes) :: description
        type(tyre_belt) :: belt
        type(error_type), allocatable :: failure
        real(dp), allocatable :: kernel(:, :, :)
        real(dp) :: tail

        n_g = 0
        call tyre_modes(belt, contact_positions(0.5_dp*belt%length, patch, 20), f_max, description, &
                        failure)
        if (allocated(failure)) return
        call sample_green_matrix(description, dt, 0.01_dp, huge(1), kernel, tail)
        n_g = ubound(kernel, 1)
    end function table_length

    !> Least-squares slope of log(t) against log(N) over the rows with t > 0.
    real(dp) function exponent(counts, seconds)
        integer, intent(in) :: counts(:)
        real(dp), intent(in) :: seconds(:)

        real(dp), allocatable :: x(:), y(:)

        x = log(real(pack(counts, seconds > 0.0_dp), dp))
        y = log(pack(seconds, seconds > 0.0_dp))
        exponent = 0.0_dp
        if (size(x) < 2) return
        exponent = sum((x - sum(x)/size(x))*(y - sum(y)/size(y)))/sum((x - sum(x)/size(x))**2)
    end function exponent

    !> CPU seconds per step of the implicit exact and explicit modal runs at n_c points, the
    !> start of the exact run (W0's factorisation) and the rank it found.
    subroutine time_runs(n_c, f_max, steps, exact, modal, start, n_m, rank, error)
        integer, intent(in) :: n_c, steps
        real(dp), intent(in) :: f_max
        real(dp), intent(out) :: exact, modal, start
        integer, intent(out) :: n_m, rank
        type(error_type), allocatable, intent(out) :: error

        type(point_modes) :: description
        type(tyre_belt) :: belt
        type(modal_green_matrix) :: conv
        type(multi_contact_state) :: state
        type(multi_contact_response) :: response
        type(power_law), allocatable :: laws(:)
        real(dp), allocatable :: preload(:), road(:, :), offset(:)
        real(dp) :: t0, t1, t2
        type(random_road) :: profile
        integer :: i, n

        call tyre_modes(belt, contact_positions(0.5_dp*belt%length, patch, n_c), f_max, description, &
                        error)
        if (allocated(error)) return
        n_m = size(description%shape, 2)
        allocate (laws(n_c), preload(n_c), road(0:steps - 1, n_c))
        preload(:) = wheel_load/n_c
        laws(:) = power_law(wheel_load/n_c/compression0**1.5_dp, 1.5_dp)
        profile = new_random_road(35, 10, 0.5e-3_dp, 0.05_dp, speed)
        offset = contact_positions(0.0_dp, patch, n_c)/speed
        do i = 1, n_c
            road(:, i) = profile%height([(n*dt + offset(i), n=0, steps - 1)])
        end do
        call new_modal_green_matrix(description, dt, 'exact', conv, error)
        if (allocated(error)) return
        call start_multi_contact(conv, laws, preload, state, error)
        if (allocated(error)) return
        call cpu_time(t0)
        call multi_contact_block(conv, state, road(0:0, :), response, error)
        if (allocated(error)) return
        call cpu_time(t1)
        call multi_contact_block(conv, state, road(1:, :), response, error)
        if (allocated(error)) return
        call cpu_time(t2)
        start = t1 - t0
        exact = (t2 - t1)/max(1, steps - 1)
        rank = state%compliance%rank
        call new_modal_green_matrix(description, dt, 'recursive', conv, error)
        if (allocated(error)) return
        call start_multi_contact(conv, laws, preload, state, error, settings=contact_options(scheme='explicit'))
        if (allocated(error)) return
        call cpu_time(t0)
        call multi_contact_block(conv, state, road, response, error)
        if (allocated(error)) return
        call cpu_time(t1)
        modal = (t1 - t0)/steps
    end subroutine time_runs

end module bench_scale_mod
