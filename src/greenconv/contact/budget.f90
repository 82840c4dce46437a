!> The time-step term of a contact run's error budget, by step doubling: the same run at dt,
!> 2*dt and 4*dt, its contact forces F_i compared where the grids meet. With the sums over the
!> run and the points
!>
!>     S_0  = sum |F(dt) - F0|^2            on the 2*dt grid,
!>     S_1  = sum |F(dt) - F(2 dt)|^2       on the 2*dt grid,
!>     S_12 = sum |F(dt) - F(2 dt)|^2       on the 4*dt grid,
!>     S_24 = sum |F(2 dt) - F(4 dt)|^2     on the 4*dt grid,
!>
!> the run's relative error ||F(dt) - F_true||/||F(dt) - F0|| is about
!>
!>     sqrt(S_1/S_0)/sqrt((r - 1)*(2^p - 1)),   r = sqrt(S_24/S_12) held within [1.75, 4]
!>
!> (1.75 when the run at 4*dt is missing, or more than 25 % off the run at 2*dt: near the
!> method's stable step a coarse pair's ratio says nothing), for a method of order p in dt: Richardson's
!> d/(rho - 1), the ratio rho of the errors at 2*dt
!> and dt taken between the ratio r observed on the coarser pair and the asymptotic 2^p (their
!> geometric mean), as a pair's ratio approaches 2^p from the coarse side (doc/methods.md, "The
!> error budget"). The scene driver (greenconv_scene_run_stream) adds the sums block by block as its
!> companions step alongside a run; the C and Fortran 77 doors from a whole run's arrays.
module greenconv_contact_budget
    use greenconv_core_kinds, only: dp
    implicit none
    private

    public :: doubling_sums, add_doubling_sums, step_doubling_error

    !> The largest relative difference ||F(2 dt) - F(4 dt)||/||F - F0|| [-] whose ratio is
    !> taken: beyond it the coarse pair is far from the asymptotic range.
    real(dp), parameter :: coarse_limit = 0.25_dp

    !> The sums of step doubling [N^2], over the run and the points (module comment).
    type :: doubling_sums
        !> S_0 and S_1, over the 2*dt grid.
        real(dp) :: fine = 0.0_dp, fine_2 = 0.0_dp
        !> S_12 and S_24, over the 4*dt grid.
        real(dp) :: grid_12 = 0.0_dp, grid_24 = 0.0_dp
    end type doubling_sums

contains

    !> Add to `sums` the forces of three whole runs at dt, 2*dt and 4*dt from the same state:
    !> force(n, i) = F_i(n*dt), force_2(j, i) = F_i(2*j*dt), force_4(k, i) = F_i(4*k*dt).
    pure subroutine add_doubling_sums(sums, force, force_2, force_4, preload)
        !> The sums, added to.
        type(doubling_sums), intent(inout) :: sums
        !> Forces [N] of the run at dt, (0:N_t-1, N_c).
        real(dp), intent(in) :: force(0:, :)
        !> Forces [N] of the run at 2*dt, (0:, N_c).
        real(dp), intent(in) :: force_2(0:, :)
        !> Forces [N] of the run at 4*dt, (0:, N_c); none (size 0 along time) to leave S_12, S_24.
        real(dp), intent(in) :: force_4(0:, :)
        !> Static preloads F0_i [N].
        real(dp), intent(in) :: preload(:)

        integer :: j, n_t

        ! last indices from the sizes: UBOUND of an empty dimension is 0, not -1
        n_t = size(force, 1)
        do j = 0, min(size(force_2, 1), (n_t + 1)/2) - 1
            sums%fine = sums%fine + sum((force(2*j, :) - preload)**2)
            sums%fine_2 = sums%fine_2 + sum((force(2*j, :) - force_2(j, :))**2)
        end do
        do j = 0, min(size(force_4, 1), (n_t + 3)/4, (size(force_2, 1) + 1)/2) - 1
            sums%grid_12 = sums%grid_12 + sum((force(4*j, :) - force_2(2*j, :))**2)
            sums%grid_24 = sums%grid_24 + sum((force_2(2*j, :) - force_4(j, :))**2)
        end do
    end subroutine add_doubling_sums

    !> The run's relative error [-] due to its time step (module comment), from the sums; the
    !> ratio r used in `ratio` [-]. 0 when the run's forces stayed at F0 throughout.
    pure subroutine step_doubling_error(sums, order, estimate, ratio)
        !> The sums of the run and its companions; S_12 = 0 when the run at 4*dt is missing.
        type(doubling_sums), intent(in) :: sums
        !> Order p of the method in dt (1 or 2).
        integer, intent(in) :: order
        !> Relative error [-] of the contact forces due to dt.
        real(dp), intent(out) :: estimate
        !> The ratio r taken [-].
        real(dp), intent(out) :: ratio

        real(dp) :: asymptotic

        estimate = 0.0_dp
        asymptotic = 2.0_dp**order
        ! without the run at 4*dt (it failed: 4*dt is beyond the method's stable step, so dt is
        ! not far into the asymptotic range) the slowest convergence held
        ratio = 1.75_dp
        if (sums%fine <= 0.0_dp) return
        ! a coarse pair more than `coarse_limit` apart is far from the asymptotic range (near the
        ! method's stable step its ratio can be anything): its ratio is not taken either
        if (sums%grid_12 > 0.0_dp .and. 2.0_dp*sums%grid_24 <= coarse_limit**2*sums%fine) &
            ratio = sqrt(sums%grid_24/sums%grid_12)
        ! held below 4, not 2^p: a first-order method's forces may converge at second order
        ratio = min(max(ratio, 1.75_dp), 4.0_dp)
        estimate = sqrt(sums%fine_2/sums%fine)/sqrt((ratio - 1.0_dp)*(asymptotic - 1.0_dp))
    end subroutine step_doubling_error

end module greenconv_contact_budget
