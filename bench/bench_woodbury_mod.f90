!> The implicit many-point step on a plate's patch with W0's low-rank factors made two ways:
!> by eliminating the dense N_c x N_c W0 (`factor_compliance`, complete pivoting) and in the
!> span of the separable mode shapes (`factor_modal_compliance`: U = Phi*A, V = Phi*B, the
!> products U*z and V^T*y on the separable factors). The plate of data/tyre_patch.nml (441
!> modes to 3 kHz, 5 % damping), `exact` at dt = 20 us, linear tread springs (3e8 N/m^3 per
!> area) under 3 kN, a random road at 15 m/s (1 mm, 50 mm) that lifts points off, at
!> 50 x 20 and 100 x 50 points; the explicit `modal` step of the same patch for scale.
!>
!> Per grid: the set-up of each factorisation (wall seconds), then rounds of one run of each
!> kind (dense factors, factors in the modes' span, explicit), interleaved, the factors made
!> before the run so that only steps are timed: wall ms per step (`system_clock`, all
!> threads), their ratio, the implicit step over the explicit one, and the largest force
!> difference between the two implicit runs relative to the peak force.
module bench_woodbury_mod
    use greenconv_core_kinds, only: dp
    use greenconv_core_error, only: error_type
    use greenconv_model_point_modes, only: point_modes
    use greenconv_model_plate, only: tyre_plate, plate_modes, patch_points
    use greenconv_model_road, only: random_road, new_random_road
    use greenconv_conv_green_modal, only: modal_green_matrix, new_modal_green_matrix
    use greenconv_contact_multi, only: multi_contact_state, multi_contact_response, start_multi_contact, &
                                       multi_contact_block
    use greenconv_contact_lowrank_solve, only: lowrank_compliance, factor_compliance, factor_modal_compliance
    use greenconv_contact_law_power, only: power_law
    implicit none
    private

    public :: woodbury_table

    !> Time step [s], travel speed [m/s], tread stiffness per area [N/m^3], wheel load [N].
    real(dp), parameter :: dt = 2.0e-5_dp, speed = 15.0_dp, per_area = 3.0e8_dp, wheel_load = 3000.0_dp
    !> Patch length and width [m].
    real(dp), parameter :: patch(2) = [0.15_dp, 0.16_dp]
    !> Rounds per grid.
    integer, parameter :: rounds = 3

contains

    !> Print the table: the set-up per grid, then one row per grid and round.
    subroutine woodbury_table(unit, error, n_steps)
        !> Output unit.
        integer, intent(in) :: unit
        !> Set when the plate's modes or a run fail.
        type(error_type), allocatable, intent(out) :: error
        !> Steps per run (100 when absent).
        integer, intent(in), optional :: n_steps

        integer, parameter :: grids(2, 2) = reshape([50, 20, 100, 50], [2, 2])
        integer :: g, steps

        steps = 100
        if (present(n_steps)) steps = n_steps
        write (unit, '(a,i0,a)') '# implicit step, W0''s factors by dense elimination (dense) or in the modes'' span ' &
            //'(span); ', steps, ' steps a run, wall time'
        do g = 1, size(grids, 2)
            call grid_rows(unit, grids(1, g), grids(2, g), steps, error)
            if (allocated(error)) return
        end do
    end subroutine woodbury_table

    !> The rows of one n_x x n_y grid.
    subroutine grid_rows(unit, n_x, n_y, steps, error)
        integer, intent(in) :: unit, n_x, n_y, steps
        type(error_type), allocatable, intent(out) :: error

        real(dp) :: x(n_x*n_y), y(n_x*n_y), setup_dense, setup_span, dense_ms, span_ms, explicit_ms, peak
        type(point_modes) :: description
        type(modal_green_matrix) :: conv, explicit
        type(lowrank_compliance) :: dense, span
        type(multi_contact_response) :: by_dense, by_span, by_explicit
        type(power_law), allocatable :: laws(:)
        real(dp), allocatable :: road(:, :), preloads(:)
        integer :: r, n_c
        logical :: done

        n_c = n_x*n_y
        call patch_points([0.9425_dp, 0.1_dp], patch, n_x, n_y, x, y)
        call plate_modes(tyre_plate(damping_ratio=0.05_dp), x, y, 3000.0_dp, description, error)
        if (allocated(error)) return
        call new_modal_green_matrix(description, dt, 'exact', conv, error)
        if (allocated(error)) return
        call new_modal_green_matrix(description, dt, 'modal', explicit, error)
        if (allocated(error)) return
        call patch_run(x, n_c, steps, laws, preloads, road)
        setup_dense = wall()
        call factor_compliance(conv%weight0, dense)
        setup_dense = wall() - setup_dense
        setup_span = wall()
        call factor_modal_compliance(conv%separable, conv%engine%mode_weight, span, done)
        setup_span = wall() - setup_span
        if (.not. done) then
            write (unit, '(a,i0,a)') '# ', n_c, ' points: no factors in the modes'' span'
            return
        end if
        write (unit, '(a,i0,a,i0,a,i0,a,i0,a,f0.3,a,f0.4,a,f0.1)') '# ', n_c, ' points, N_m = ', &
            size(description%shape, 2), ', rank dense ', dense%rank, ', span ', span%rank, ': set-up dense ', &
            setup_dense, ' s, span ', setup_span, ' s, dense/span ', setup_dense/max(setup_span, tiny(1.0_dp))
        write (unit, '(a)') '# points  round  dense [ms/step]  span [ms/step]  dense/span  modal [ms/step]' &
            //'  span/modal  max|dF|/max F  contact min..max'
        do r = 1, rounds
            call timed_run(conv, laws, preloads, road, dense, by_dense, dense_ms, error)
            if (allocated(error)) return
            call timed_run(conv, laws, preloads, road, span, by_span, span_ms, error)
            if (allocated(error)) return
            call timed_run(explicit, laws, preloads, road, span, by_explicit, explicit_ms, error)
            if (allocated(error)) return
            peak = maxval(abs(by_dense%force))
            write (unit, '(i8, i7, 2f16.3, f12.2, f17.3, f12.2, es15.3, i9, a, i0)') n_c, r, dense_ms, span_ms, &
                dense_ms/max(span_ms, tiny(1.0_dp)), explicit_ms, span_ms/max(explicit_ms, tiny(1.0_dp)), &
                maxval(abs(by_span%force - by_dense%force))/peak, minval(count(by_span%force > 0.0_dp, dim=2)), &
                '..', maxval(count(by_span%force > 0.0_dp, dim=2))
        end do
    end subroutine grid_rows

    !> Linear tread springs sharing the wheel load, and the road under the points over `steps`.
    subroutine patch_run(x, n_c, steps, laws, preloads, road)
        real(dp), intent(in) :: x(:)
        integer, intent(in) :: n_c, steps
        type(power_law), allocatable, intent(out) :: laws(:)
        real(dp), allocatable, intent(out) :: preloads(:), road(:, :)

        type(random_road) :: profile
        integer :: i, m

        profile = new_random_road(35, 10, 1.0e-3_dp, 0.05_dp, speed)
        allocate (road(0:steps - 1, n_c), preloads(n_c), laws(n_c))
        do i = 1, n_c
            road(:, i) = profile%height([(m*dt + x(i)/speed, m=0, steps - 1)])
        end do
        preloads(:) = wheel_load/n_c
        laws(:) = power_law(per_area*patch(1)*patch(2)/n_c, 1.0_dp)
    end subroutine patch_run

    !> One run from rest with the factors given (unused by an explicit convolver): wall ms a step.
    subroutine timed_run(conv, laws, preloads, road, factors, response, ms, error)
        type(modal_green_matrix), intent(inout) :: conv
        type(power_law), intent(in) :: laws(:)
        real(dp), intent(in) :: preloads(:), road(0:, :)
        type(lowrank_compliance), intent(in) :: factors
        type(multi_contact_response), intent(out) :: response
        real(dp), intent(out) :: ms
        type(error_type), allocatable, intent(out) :: error

        type(multi_contact_state) :: state

        call start_multi_contact(conv, laws, preloads, state, error)
        if (allocated(error)) return
        state%compliance = factors
        ms = wall()
        call multi_contact_block(conv, state, road, response, error)
        ms = 1.0e3_dp*(wall() - ms)/size(road, 1)
    end subroutine timed_run

    !> Wall-clock seconds.
    real(dp) function wall()
        integer(8) :: count, rate

        call system_clock(count, rate)
        wall = real(count, dp)/real(rate, dp)
    end function wall

end module bench_woodbury_mod
