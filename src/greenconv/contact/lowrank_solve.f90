!> The linear algebra of the implicit multi-point step when the instant compliance W0 has low
!> rank, as it has for a modal structure: W0 = sum_k w_k*phi_k*phi_k^T over N_m modes, rank
!> N_m whatever the number of points N_c.
!>
!> The semismooth Newton method of greenconv_contact_step solves at each iteration
!>
!>     J*s = b,   J = I + W0*diag(t),
!>
!> t_i = dF_i/ddelta_i [N/m] (zero off the active set). A dense LU costs N_c^3/3 per iteration.
!> Here W0 is factored once per run into W0 = U*V^T (U, V: N_c x r) by Gaussian elimination
!> with complete pivoting (a cross approximation that stops when the remainder is round-off),
!> and J is solved by the Sherman-Morrison-Woodbury identity
!>
!>     J^-1*b = b - U*M^-1*(V^T*diag(t)*b),   M = I_r + V^T*diag(t)*U,
!>
!> in O(N_c*r^2 + r^3) per iteration; the products W0*x of the residual cost O(N_c*r). J is
!> singular exactly when M is (det J = det M), so a failure is reported as for the dense solve.
!>
!> The factors are used only when the rank found is below N_c/2; otherwise (a structure that
!> is not modal, N_m >= N_c, or a full upper residual added to W0) everything stays dense and
!> the results are those of the dense solve bit for bit.
module greenconv_contact_lowrank_solve
    use greenconv_core_kinds, only: dp
    use greenconv_core_error, only: error_type
    use greenconv_ext_lapack, only: solve_linear
    implicit none
    private

    public :: lowrank_compliance, factor_compliance, apply_compliance, newton_solve

    !> W0 [m/N] of a run as the step uses it: dense, or U*V^T.
    type :: lowrank_compliance
        !> Whether `factor_compliance` has looked at this run's W0.
        logical :: checked = .false.
        !> Whether the factors stand for W0 (otherwise the dense W0 is used).
        logical :: low_rank = .false.
        !> Rank r of the factors (0 when dense).
        integer :: rank = 0
        !> U (N_c x r) [m/N].
        real(dp), allocatable :: left(:, :)
        !> V (N_c x r) [dimensionless]: W0 = U*V^T.
        real(dp), allocatable :: right(:, :)
    end type lowrank_compliance

    !> The remainder of the elimination counts as round-off below this fraction of max|W0_ij|.
    real(dp), parameter :: rank_tolerance = 1.0e-14_dp

contains

    !> Factor W0 = U*V^T when its rank is below N_c/2 (cost O(N_c^2*r), once per run); else
    !> mark it dense.
    subroutine factor_compliance(weight0, compliance)
        !> The instant compliance W0 [m/N] (N_c x N_c).
        real(dp), intent(in) :: weight0(:, :)
        !> The factors, or the mark that W0 stays dense.
        type(lowrank_compliance), intent(out) :: compliance

        real(dp), allocatable :: remainder(:, :), left(:, :), right(:, :)
        real(dp) :: largest, pivot
        integer :: n_c, max_rank, k, at(2)

        compliance%checked = .true.
        n_c = size(weight0, 1)
        max_rank = (n_c - 1)/2
        if (max_rank < 1) return
        largest = maxval(abs(weight0))
        if (.not. (largest > 0.0_dp)) return
        allocate (remainder(n_c, n_c), left(n_c, max_rank), right(n_c, max_rank))
        remainder(:, :) = weight0
        do k = 1, max_rank + 1
            at = maxloc(abs(remainder))
            pivot = remainder(at(1), at(2))
            if (abs(pivot) <= rank_tolerance*largest) then
                compliance%low_rank = .true.
                compliance%rank = k - 1
                compliance%left = left(:, 1:k - 1)
                compliance%right = right(:, 1:k - 1)
                return
            end if
            if (k > max_rank) return
            left(:, k) = remainder(:, at(2))
            right(:, k) = remainder(at(1), :)/pivot
            call subtract_outer(remainder, left(:, k), right(:, k))
        end do
    end subroutine factor_compliance

    !> A = A - x*y^T.
    pure subroutine subtract_outer(a, x, y)
        real(dp), intent(inout) :: a(:, :)
        real(dp), intent(in) :: x(:), y(:)

        integer :: j

        do j = 1, size(a, 2)
            if (y(j) /= 0.0_dp) a(:, j) = a(:, j) - x*y(j)
        end do
    end subroutine subtract_outer

    !> W0*x [m] for loads x [N], from the factors when there are any.
    pure function apply_compliance(compliance, weight0, x) result(y)
        !> W0 as the run uses it.
        type(lowrank_compliance), intent(in) :: compliance
        !> The dense W0 [m/N] (N_c x N_c).
        real(dp), intent(in) :: weight0(:, :)
        !> Loads [N] (N_c).
        real(dp), intent(in) :: x(:)
        real(dp) :: y(size(x))

        if (compliance%low_rank) then
            y(:) = matmul(compliance%left, matmul(x, compliance%right))
        else
            y(:) = matmul(weight0, x)
        end if
    end function apply_compliance

    !> The Newton step s [m] solving (I + W0*diag(t))*s = b: Woodbury with the factors, or a
    !> dense LU.
    subroutine newton_solve(compliance, weight0, slopes, b, s, error)
        !> W0 as the run uses it.
        type(lowrank_compliance), intent(in) :: compliance
        !> The dense W0 [m/N] (N_c x N_c).
        real(dp), intent(in) :: weight0(:, :)
        !> t_i = dF_i/ddelta_i [N/m] (N_c), zero off the active set.
        real(dp), intent(in) :: slopes(:)
        !> Right-hand side [m] (N_c).
        real(dp), intent(in) :: b(:)
        !> The Newton step [m] (N_c).
        real(dp), intent(out) :: s(:)
        !> Set when the system is singular.
        type(error_type), allocatable, intent(out) :: error

        real(dp), allocatable :: jacobian(:, :), scaled(:, :), small(:, :), y(:)
        integer :: j

        if (.not. compliance%low_rank) then
            allocate (jacobian(size(b), size(b)))
            do j = 1, size(b)
                jacobian(:, j) = weight0(:, j)*slopes(j)
                jacobian(j, j) = jacobian(j, j) + 1.0_dp
            end do
            call solve_linear(jacobian, b, s, error)
            return
        end if
        if (compliance%rank == 0) then
            s(:) = b
            return
        end if
        scaled = compliance%right*spread(slopes, 2, compliance%rank)
        small = matmul(transpose(scaled), compliance%left)
        do j = 1, compliance%rank
            small(j, j) = small(j, j) + 1.0_dp
        end do
        allocate (y(compliance%rank))
        call solve_linear(small, matmul(b, scaled), y, error)
        if (allocated(error)) return
        s(:) = b - matmul(compliance%left, y)
    end subroutine newton_solve

end module greenconv_contact_lowrank_solve
