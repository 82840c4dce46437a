!> W0*x of the implicit step at a plate's patch: by W0's low-rank factors U*(V^T*x)
!> (greenconv_contact_lowrank_solve's `apply_compliance`) against the convolver's own product
!> on the separable mode shapes, Phi*(w o (Phi^T*x)) (`apply_instant_kept` of the modal Green's
!> matrix), at 50 x 20 and 100 x 50 points with 441 modes, `exact`. Rounds of 2,000 products of
!> each kind, interleaved, CPU time per product, their ratio per round, and the largest
!> difference between the two relative to the largest entry (round-off).
module bench_instant_mod
    use greenconv_core_kinds, only: dp
    use greenconv_core_error, only: error_type
    use greenconv_model_point_modes, only: point_modes
    use greenconv_model_plate, only: tyre_plate, plate_modes, patch_points
    use greenconv_conv_green_modal, only: modal_green_matrix, new_modal_green_matrix
    use greenconv_contact_lowrank_solve, only: lowrank_compliance, factor_compliance, apply_compliance
    implicit none
    private

    public :: instant_product_table

    !> Products of each kind per round.
    integer, parameter :: repeats = 2000
    !> Rounds per grid.
    integer, parameter :: rounds = 5

contains

    !> Print the table: one row per grid and round.
    subroutine instant_product_table(unit, error)
        !> Output unit.
        integer, intent(in) :: unit
        !> Set when the plate's modes or the convolver cannot be made.
        type(error_type), allocatable, intent(out) :: error

        integer, parameter :: grids(2, 2) = reshape([50, 20, 100, 50], [2, 2])
        integer :: g

        write (unit, '(a)') '# W0*x: low-rank factors U*(V^T*x) against the separable factors Phi*(w o Phi^T*x)'
        write (unit, '(a)') '# points  rank  round  U*(V^T*x) [us]  Phi*(w o Phi^T*x) [us]  ratio  max|diff|/max'
        do g = 1, size(grids, 2)
            call grid_rows(unit, grids(1, g), grids(2, g), error)
            if (allocated(error)) return
        end do
    end subroutine instant_product_table

    !> The rows of one n_x x n_y grid.
    subroutine grid_rows(unit, n_x, n_y, error)
        integer, intent(in) :: unit, n_x, n_y
        type(error_type), allocatable, intent(out) :: error

        real(dp) :: x(n_x*n_y), y(n_x*n_y), q(n_x*n_y), a(n_x*n_y), b(n_x*n_y)
        real(dp) :: t0, t1, low_rank, separable
        type(point_modes) :: description
        type(modal_green_matrix) :: conv
        type(lowrank_compliance) :: compliance
        integer :: r, i, at

        call patch_points([0.9425_dp, 0.1_dp], [0.15_dp, 0.16_dp], n_x, n_y, x, y)
        call plate_modes(tyre_plate(), x, y, 3000.0_dp, description, error)
        if (allocated(error)) return
        call new_modal_green_matrix(description, 2.0e-5_dp, 'exact', conv, error)
        if (allocated(error)) return
        call factor_compliance(conv%weight0, compliance)
        q(:) = [(100.0_dp*(1.0_dp + sin(0.37_dp*i)), i=1, size(q))]
        do r = 1, rounds
            call cpu_time(t0)
            do i = 1, repeats
                at = 1 + mod(i, size(q))
                q(at) = q(at) + 1.0e-3_dp
                a(:) = apply_compliance(compliance, conv%weight0, q)
            end do
            call cpu_time(t1)
            low_rank = (t1 - t0)/repeats
            call cpu_time(t0)
            do i = 1, repeats
                at = 1 + mod(i, size(q))
                q(at) = q(at) + 1.0e-3_dp
                call conv%apply_instant_kept(q, b)
            end do
            call cpu_time(t1)
            separable = (t1 - t0)/repeats
            a(:) = apply_compliance(compliance, conv%weight0, q)
            write (unit, '(i8, i6, i7, 2f17.1, f8.2, es14.3)') n_x*n_y, compliance%rank, r, 1.0e6_dp*low_rank, &
                1.0e6_dp*separable, low_rank/max(separable, tiny(1.0_dp)), &
                maxval(abs(a - b))/max(maxval(abs(b)), tiny(1.0_dp))
        end do
    end subroutine grid_rows

end module bench_instant_mod
