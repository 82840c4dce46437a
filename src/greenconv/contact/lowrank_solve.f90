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
!> M is kept as its inverse and follows the active set: when a few slopes change from one
!> Newton matrix to the next (points entering or leaving the contact, as from one time step to
!> the next), each change t_i -> t_i' is the rank-one term (t_i' - t_i)*v_i*u_i^T of M
!> (u_i, v_i the rows i of U and V), and M^-1 is updated by the Sherman-Morrison formula in
!> 3*r^2 operations (2*r^2 when V = U, below) instead of being formed and factored again in
!> N_a*r^2 + r^3. M is formed anew when more than N_a/3 slopes change at once, when M^-1*1 no
!> longer solves M to 1e-12 (asked after every N_c updates: their round-off grows slowly), and
!> when an update's pivot 1 + (t_i' - t_i)*u_i^T*M^-1*v_i is below `update_pivot` (a nearly
!> singular intermediate). The Newton iteration stops on its
!> residual, not on this matrix, so the inverse's round-off changes the number of iterations
!> at most, never the tolerance the compressions meet.
!>
!> **In the modes' span.** When the convolver holds separable mode shapes Phi (a plate's patch on
!> a grid, greenconv_model_point_modes) and W0 = Phi*diag(w)*Phi^T with w >= 0, W0 is first
!> written in a smaller orthonormal basis of the modes' span on the grid, W0 = Psi*C*Psi^T
!> (`compressed_span`: Psi the products of orthonormal bases of the shapes' x and y factors, S
!> columns, 207 against 441 modes on the shipped tyre patch), and every column of the
!> elimination is then Psi times a coefficient vector, so `factor_modal_compliance` makes
!> U = V = Psi*A (A: S x r; W0 = U*U^T, M symmetric) by a pivoted Cholesky on the S x S
!> coefficients, without forming or eliminating the N_c x N_c W0 (O(r*S^2) instead of
!> O(N_c^2*r)). The products U*z and V^T*y of a step are then Psi*(A*z) and A^T*(Psi^T*y), the
!> products by Psi small dense ones on the grid (n_col*n_row*rho_y + n_col*rho_x*rho_y
!> multiply-adds) and those by A S*r, instead of N_c*r; U and V are kept too, for their rows
!> u_i = psi_i*A (M on the active set and its rank-one updates). When S would not be below N_m
!> the basis is Phi itself (C = diag(w)) and its products those of the separable factors.
!>
!> The factors are used only when the rank found is below N_c/2; otherwise (a structure that
!> is not modal, N_m >= N_c, or a full upper residual added to W0) everything stays dense and
!> the results are those of the dense solve bit for bit.
!>
!> The products by U, V^T, A, B^T, Psi and M^-1 and the updates of M^-1 are ordered_kernel.c's: each
!> sum in MATMUL's order, at the CPU's vector width (SSE2, AVX2 or AVX-512) and never fused,
!> so every CPU gives the same bits.
!>
!> Threads (a build with OpenMP): W0*x, the Woodbury products and the Newton matrix are shared
!> out by fixed blocks of rows or columns, each sum done by one thread in the serial order, and
!> the LU is made serially by greenconv_ext_lapack itself (`lapack_serial_begin`), so that any
!> number of threads gives the one-thread results bit for bit; inside a host's parallel region
!> all stays serial.
module greenconv_contact_lowrank_solve
    use greenconv_core_kinds, only: dp
    use greenconv_core_error, only: error_type
    use greenconv_ext_lapack, only: solve_linear, lu_factor, lu_solve
    use greenconv_model_point_modes, only: separable_shapes, separable_displacements, separable_modal_forces, &
                                           separable_work
    !$ use omp_lib, only: omp_in_parallel
    use, intrinsic :: iso_c_binding, only: c_int, c_double, c_ptr, c_loc
    implicit none
    private

    interface
        !> y = A*x for m rows of a column-major matrix, each sum in the order of the columns
        !> from zero, never fused (ordered_kernel.c).
        pure subroutine ordered_rows(m, n, lda, a, x, y) bind(c, name='greenconv_contact_ordered_rows')
            import :: c_int, c_double, c_ptr
            !> Rows taken.
            integer(c_int), value :: m
            !> Columns.
            integer(c_int), value :: n
            !> Leading dimension of A (>= m).
            integer(c_int), value :: lda
            !> A's first row taken, column-major (lda x n), not written.
            type(c_ptr), value :: a
            !> x (n).
            real(c_double), intent(in) :: x(n)
            !> A*x (m).
            real(c_double), intent(out) :: y(m)
        end subroutine ordered_rows

        !> Y(:, v) = A*X(:, v) for nv vectors, each sum that of `ordered_rows` (ordered_kernel.c).
        pure subroutine ordered_rows_many(m, n, lda, a, nv, ldx, x, ldy, y) &
            bind(c, name='greenconv_contact_ordered_rows_many')
            import :: c_int, c_double
            !> Rows.
            integer(c_int), value :: m
            !> Columns.
            integer(c_int), value :: n
            !> Leading dimension of A (>= m).
            integer(c_int), value :: lda
            !> A, column-major (lda x n).
            real(c_double), intent(in) :: a(lda, n)
            !> Number of vectors.
            integer(c_int), value :: nv
            !> Leading dimension of X (>= n).
            integer(c_int), value :: ldx
            !> The vectors X (ldx x nv).
            real(c_double), intent(in) :: x(ldx, nv)
            !> Leading dimension of Y (>= m).
            integer(c_int), value :: ldy
            !> A*X (ldy x nv).
            real(c_double), intent(out) :: y(ldy, nv)
        end subroutine ordered_rows_many

        !> inv <- inv - sum_p c_p*(x_p*x_p^T), p = 1..d in order, each entry the same roundings
        !> as d rank-one updates one after the other (ordered_kernel.c).
        pure subroutine symmetric_updates(r, ld, inverse, d, ldx, x, c) &
            bind(c, name='greenconv_contact_symmetric_updates')
            import :: c_int, c_double
            !> Order r of the matrix.
            integer(c_int), value :: r
            !> Its leading dimension (>= r).
            integer(c_int), value :: ld
            !> The matrix (ld x r), updated.
            real(c_double), intent(inout) :: inverse(ld, r)
            !> Number of updates d.
            integer(c_int), value :: d
            !> Leading dimension of x (>= r).
            integer(c_int), value :: ldx
            !> x_p, the columns of x (ldx x d).
            real(c_double), intent(in) :: x(ldx, d)
            !> c_p (d).
            real(c_double), intent(in) :: c(d)
        end subroutine symmetric_updates

    end interface

    public :: lowrank_compliance, factor_compliance, factor_modal_compliance, apply_compliance, newton_solve, &
              woodbury_step

    !> The factored Newton matrix of the low-rank solve, kept for the slopes it was formed for.
    type :: newton_matrix
        !> Whether the factors below are those of the last slopes.
        logical :: ready = .false.
        !> Whether it is the matrix on the active set (I + W0_AA*diag(t_A)), else M of Woodbury.
        logical :: on_active_set = .false.
        !> The slopes t [N/m] (N_c) the factors were formed for.
        real(dp), allocatable :: slopes(:)
        !> The active set A: indices of the points with t_i /= 0.
        integer, allocatable :: active(:)
        !> LU factors from dgetrf: of the matrix on the active set (N_a x N_a), or of M (r x r)
        !> when `inverse` was last formed.
        real(dp), allocatable :: factors(:, :)
        !> dgetrf's row interchanges, on the active set.
        integer, allocatable :: pivot(:)
        !> M^-1 (r x r) [dimensionless], for Woodbury.
        real(dp), allocatable :: inverse(:, :)
        !> Rank-one updates of `inverse` since M was last formed or its inverse last checked.
        integer :: updates = 0
        !> Times the inverse was checked after N_c updates and kept (`inverse_accurate`).
        integer :: kept = 0
    end type newton_matrix

    !> W0 [m/N] of a run as the step uses it: dense, or U*V^T.
    type :: lowrank_compliance
        !> Whether `factor_compliance` has looked at this run's W0.
        logical :: checked = .false.
        !> Whether the factors stand for W0 (otherwise the dense W0 is used).
        logical :: low_rank = .false.
        !> Rank r of the factors (0 when dense).
        integer :: rank = 0
        !> Whether V = U (W0 = U*U^T, `factor_modal_compliance`): M is then symmetric and so is
        !> M^-1, whose rank-one updates take one product by it instead of two.
        logical :: symmetric = .false.
        !> U (N_c x r) [m/N].
        real(dp), allocatable :: left(:, :)
        !> V (N_c x r) [dimensionless]: W0 = U*V^T.
        real(dp), allocatable :: right(:, :)
        !> V^T (r x N_c) [dimensionless], for the products V^T*x (contiguous in k).
        real(dp), allocatable :: right_t(:, :)
        !> The basis Psi (N_c x S) of the modes' span when the factors lie in it
        !> (`factor_modal_compliance`: the compressed basis, or the modes' shapes Phi themselves);
        !> unallocated for factors of a dense W0.
        type(separable_shapes), allocatable :: shapes
        !> A (S x r) [sqrt(m/N) for an orthonormal basis, W0 in m/N]: U = Psi*A.
        real(dp), allocatable :: modal_left(:, :)
        !> B^T (r x S) [as A]: V = Psi*B.
        real(dp), allocatable :: modal_right_t(:, :)
        !> When Psi is the compressed basis, every product of the columns of Q_x (n_col x rho_x)
        !> and Q_y (n_row x rho_y), dimensionless (`compressed_span`): Q_x, Q_x^T, Q_y and Q_y^T,
        !> for the products by Psi and Psi^T as small dense products on the grid (`grid_loads`,
        !> `grid_values`); unallocated otherwise.
        real(dp), allocatable :: along_q(:, :), along_q_t(:, :), across_q(:, :), across_q_t(:, :)
        !> The last Newton matrix factored (low-rank case only).
        type(newton_matrix) :: newton
    end type lowrank_compliance

    !> The remainder of the elimination counts as round-off below this fraction of max|W0_ij|.
    real(dp), parameter :: rank_tolerance = 1.0e-14_dp
    !> Products of fewer multiply-adds than this stay on one thread (a parallel region costs
    !> some microseconds): the N_c*N_m rule of greenconv_conv_green_modal.
    real(dp), parameter :: thread_work = 2.0e4_dp
    !> Rows per block of the products by rows (one thread's share at a time).
    integer, parameter :: row_block = 256
    !> Rows of V^T per block of the products V^T*x (one thread's share at a time).
    integer, parameter :: column_block = 64
    !> Smallest |1 + (t_i' - t_i)*u_i^T*M^-1*v_i| a rank-one update of M^-1 accepts; M is formed
    !> anew below it.
    real(dp), parameter :: update_pivot = 1.0e-6_dp
    !> Largest |M*(M^-1*1) - 1| of a kept M^-1 after its rank-one updates (`inverse_accurate`);
    !> M is formed anew above it. A freshly inverted M of the shipped patch is at about 1e-15.
    real(dp), parameter :: inverse_drift = 1.0e-12_dp
    !> Changed slopes whose rank-one updates of M^-1 are made together (`symmetric_group`).
    integer, parameter :: update_group = 8

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
        ! the first pivot: the scan of `subtract_outer` with nothing subtracted
        left(:, 1) = 0.0_dp
        right(:, 1) = 0.0_dp
        call subtract_outer(remainder, left(:, 1), right(:, 1), at)
        do k = 1, max_rank + 1
            pivot = remainder(at(1), at(2))
            if (abs(pivot) <= rank_tolerance*largest) then
                compliance%low_rank = .true.
                compliance%rank = k - 1
                ! allocated before the assignments: the sanitizer flags gfortran's reallocation
                ! reading the unset bounds of an unallocated component
                allocate (compliance%left(n_c, k - 1), compliance%right(n_c, k - 1), compliance%right_t(k - 1, n_c))
                compliance%left(:, :) = left(:, 1:k - 1)
                compliance%right(:, :) = right(:, 1:k - 1)
                compliance%right_t(:, :) = transpose(compliance%right)
                return
            end if
            if (k > max_rank) return
            left(:, k) = remainder(:, at(2))
            right(:, k) = remainder(at(1), :)/pivot
            call subtract_outer(remainder, left(:, k), right(:, k), at)
        end do
    end subroutine factor_compliance

    !> Factor W0 = Phi*diag(w)*Phi^T = U*V^T in the modes' span, U = Psi*A and V = Psi*B, without
    !> forming W0. Psi (N_c x S) is the span's orthonormal basis on the grid (`compressed_span`):
    !> W0 = Psi*C*Psi^T to round-off, C (S x S) symmetric positive semi-definite, S often well
    !> below N_m (a short patch resolves fewer shapes than the modes have). Then the elimination of
    !> `factor_compliance` with the pivots on the diagonal (W0 is symmetric positive
    !> semi-definite for w >= 0, so its largest entry is a diagonal one and complete pivoting is a
    !> pivoted Cholesky). The remainder is kept as Psi*R*Psi^T, R (S x S) starting at C; at pivot
    !> p, with psi_p the basis at point p,
    !>
    !>     a = R*psi_p,   pivot = psi_p^T*a,   u = Psi*a (column p of the remainder),
    !>     U(:, k) = u/sqrt(pivot),   A(:, k) = a/sqrt(pivot),
    !>     R <- R - a*a^T/pivot,   d_i <- d_i - u_i^2/pivot,
    !>
    !> d the remainder's diagonal, whose largest entry is the next pivot; V = U and B = A
    !> (W0 = U*U^T, the pivots positive), so that M = I_r + U_A^T*diag(t_A)*U_A is symmetric. A
    !> step costs 2*S^2 and one product by the separable factors instead of the N_c^2 of an
    !> elimination step on the dense W0, and no N_c x N_c array is made. It stops, as the dense
    !> elimination, when a pivot is at most `rank_tolerance` of max|W0_ij| = max_i d_i; U and V
    !> are kept as well for their rows (the Newton matrix M and its rank-one updates). `done` is
    !> false (nothing set) when some w_k < 0 (W0 indefinite: the diagonal no longer bounds it),
    !> when W0 = 0, or when the remainder is not round-off after min(S, (N_c - 1)/2) pivots: the
    !> caller then factors the dense W0 (`factor_compliance`).
    subroutine factor_modal_compliance(shapes, weight, compliance, done)
        !> The mode shapes' factors Phi over the grid of points (N_c points, N_m modes).
        type(separable_shapes), intent(in) :: shapes
        !> w_k (N_m): W0_ij = sum_k phi_ik*w_k*phi_jk [m/N].
        real(dp), intent(in) :: weight(:)
        !> The factors, when `done`.
        type(lowrank_compliance), intent(out) :: compliance
        !> Whether W0 was factored here.
        logical, intent(out) :: done

        type(separable_shapes) :: basis
        real(dp), allocatable :: remainder(:, :), left(:, :), coefficients(:, :), diagonal(:), pivots(:)
        real(dp), allocatable :: along(:, :), across(:, :)
        real(dp), allocatable :: psi(:), a(:)
        real(dp) :: largest, pivot
        integer :: n_c, n_s, max_rank, k, i, p

        done = .false.
        if (any(.not. (weight >= 0.0_dp))) return
        call compressed_span(shapes, weight, basis, remainder, along, across)
        n_c = size(basis%column)
        n_s = size(remainder, 1)
        max_rank = min(n_s, (n_c - 1)/2)
        if (max_rank < 1) return
        allocate (diagonal(n_c), psi(n_s), a(n_s))
        do i = 1, n_c
            psi(:) = shape_row(basis, i)
            call ordered_product(remainder, 1, psi, a)
            diagonal(i) = dot_product(psi, a)
        end do
        largest = maxval(diagonal)
        if (.not. (largest > 0.0_dp)) return
        allocate (left(n_c, max_rank), coefficients(n_s, max_rank), pivots(max_rank))
        do k = 1, max_rank + 1
            p = maxloc(diagonal, 1)
            psi(:) = shape_row(basis, p)
            call ordered_product(remainder, 1, psi, a)
            pivot = dot_product(psi, a)
            if (abs(pivot) <= rank_tolerance*largest) then
                compliance%checked = .true.
                compliance%low_rank = .true.
                compliance%rank = k - 1
                allocate (compliance%left(n_c, k - 1), compliance%right(n_c, k - 1), compliance%right_t(k - 1, n_c), &
                          compliance%modal_left(n_s, k - 1), compliance%modal_right_t(k - 1, n_s))
                compliance%symmetric = .true.
                do i = 1, k - 1
                    compliance%left(:, i) = left(:, i)/sqrt(pivots(i))
                    compliance%modal_left(:, i) = coefficients(:, i)/sqrt(pivots(i))
                    compliance%modal_right_t(i, :) = compliance%modal_left(:, i)
                end do
                compliance%right(:, :) = compliance%left
                compliance%right_t(:, :) = transpose(compliance%right)
                compliance%shapes = basis
                if (allocated(along)) then
                    compliance%along_q = along
                    compliance%along_q_t = transpose(along)
                    compliance%across_q = across
                    compliance%across_q_t = transpose(across)
                end if
                done = .true.
                return
            end if
            if (k > max_rank) return
            call separable_displacements(basis, a, left(:, k), .false.)
            coefficients(:, k) = a
            pivots(k) = pivot
            diagonal(:) = diagonal - left(:, k)**2/pivot
            call subtract_symmetric(remainder, a, pivot)
        end do
    end subroutine factor_modal_compliance

    !> W0 = Phi*diag(w)*Phi^T in fewer coordinates: Psi*C*Psi^T to round-off. With the shapes
    !> phi_ik = X_f(k)(x_col(i))*Y_n(k)(y_row(i)), the functions X at the grid's columns
    !> (n_col x N_x) span a space of some dimension rho_x <= min(n_col, N_x) to round-off, and
    !> the functions Y at its rows one of rho_y (`orthonormal_range`: X = Q_x*R_x, Y = Q_y*R_y).
    !> The basis Psi is every product Q_x(:, a)*Q_y(:, b) (S = rho_x*rho_y separable columns,
    !> orthonormal on the grid), mode k is Psi*p_k with p_k = R_x(:, f(k)) (x) R_y(:, n(k)), and
    !> C = sum_k w_k*p_k*p_k^T. On a short patch the modes' x functions are smooth and many,
    !> so S is well below N_m (441 modes of the shipped tyre patch: S = 207), and the
    !> factors' products cost S*r instead of N_m*r. When S is not below N_m the basis is the
    !> modes themselves and C = diag(w).
    subroutine compressed_span(shapes, weight, basis, core, along, across)
        !> The mode shapes' factors Phi (N_c points, N_m modes).
        type(separable_shapes), intent(in) :: shapes
        !> w_k [m/N] (N_m).
        real(dp), intent(in) :: weight(:)
        !> Psi (N_c points, S columns).
        type(separable_shapes), intent(out) :: basis
        !> C (S x S) [m/N].
        real(dp), allocatable, intent(out) :: core(:, :)
        !> Q_x and Q_y when the basis is compressed (unallocated when it is the modes').
        real(dp), allocatable, intent(out) :: along(:, :), across(:, :)

        real(dp), allocatable :: along_r(:, :), across_r(:, :), p(:)
        integer :: n_along, n_across, n_s, a, b, k, l

        call orthonormal_range(shapes%along, along)
        call orthonormal_range(shapes%across, across)
        n_along = size(along, 2)
        n_across = size(across, 2)
        n_s = n_along*n_across
        if (n_s >= size(weight)) then
            deallocate (along, across)
            basis = shapes
            allocate (core(size(weight), size(weight)))
            core(:, :) = 0.0_dp
            do k = 1, size(weight)
                core(k, k) = weight(k)
            end do
            return
        end if
        basis%along = along
        basis%across = across
        basis%mode_along = [((a, a=1, n_along), b=1, n_across)]
        basis%mode_across = [((b, a=1, n_along), b=1, n_across)]
        basis%column = shapes%column
        basis%row = shapes%row
        ! R_x = Q_x^T*X and R_y = Q_y^T*Y, the modes' coordinates in the basis
        along_r = coordinates(along, shapes%along)
        across_r = coordinates(across, shapes%across)
        allocate (core(n_s, n_s), p(n_s))
        core(:, :) = 0.0_dp
        do k = 1, size(weight)
            p(:) = [((along_r(a, shapes%mode_along(k))*across_r(b, shapes%mode_across(k)), a=1, n_along), &
                     b=1, n_across)]
            do l = 1, n_s
                if (p(l) /= 0.0_dp) core(:, l) = core(:, l) + p*(weight(k)*p(l))
            end do
        end do
    end subroutine compressed_span

    !> Q^T*F (rho x m) for Q (n x rho) and F (n x m), each entry a dot product in the order of
    !> the rows (no library product whose sums depend on the CPU).
    pure function coordinates(q, f) result(r)
        real(dp), intent(in) :: q(:, :), f(:, :)
        real(dp) :: r(size(q, 2), size(f, 2))

        integer :: a, j

        do j = 1, size(f, 2)
            do a = 1, size(q, 2)
                r(a, j) = dot_product(q(:, a), f(:, j))
            end do
        end do
    end function coordinates

    !> An orthonormal basis Q (n x rho) of the range of F (n x m) to round-off, by Gram-Schmidt
    !> with column pivoting: the column of the remainder with the largest norm is taken next,
    !> orthogonalised twice against Q, and removed from the remainder; it stops when no column's
    !> remainder exceeds `rank_tolerance` of F's largest column norm.
    pure subroutine orthonormal_range(f, q)
        !> F (n x m).
        real(dp), intent(in) :: f(:, :)
        !> Q (n x rho), Q^T*Q = I to round-off.
        real(dp), allocatable, intent(out) :: q(:, :)

        real(dp), allocatable :: rest(:, :), found(:, :)
        real(dp) :: norms(size(f, 2)), v(size(f, 1)), largest
        integer :: rank, j, l, pass

        rest = f
        allocate (found(size(f, 1), min(size(f, 1), size(f, 2))))
        do j = 1, size(f, 2)
            norms(j) = norm2(f(:, j))
        end do
        largest = maxval(norms, 1)
        rank = 0
        do while (rank < size(found, 2) .and. largest > 0.0_dp)
            do j = 1, size(f, 2)
                norms(j) = norm2(rest(:, j))
            end do
            j = maxloc(norms, 1)
            if (norms(j) <= rank_tolerance*largest) exit
            v(:) = rest(:, j)/norms(j)
            do pass = 1, 2
                do l = 1, rank
                    v(:) = v - dot_product(found(:, l), v)*found(:, l)
                end do
            end do
            rank = rank + 1
            found(:, rank) = v/norm2(v)
            do l = 1, size(f, 2)
                rest(:, l) = rest(:, l) - dot_product(found(:, rank), rest(:, l))*found(:, rank)
            end do
        end do
        q = found(:, 1:rank)
    end subroutine orthonormal_range

    !> The mode shapes at point i, phi_ik = X_f(k)(x_col(i))*Y_n(k)(y_row(i)) (N_m).
    pure function shape_row(shapes, i) result(phi)
        type(separable_shapes), intent(in) :: shapes
        integer, intent(in) :: i
        real(dp) :: phi(size(shapes%mode_along))

        phi(:) = shapes%along(shapes%column(i), shapes%mode_along)*shapes%across(shapes%row(i), shapes%mode_across)
    end function shape_row

    !> C = C - a*a^T/pivot for a symmetric C, column by column.
    pure subroutine subtract_symmetric(c, a, pivot)
        real(dp), intent(inout) :: c(:, :)
        real(dp), intent(in) :: a(:), pivot

        integer :: j

        do j = 1, size(c, 2)
            if (a(j) /= 0.0_dp) c(:, j) = c(:, j) - a*(a(j)/pivot)
        end do
    end subroutine subtract_symmetric

    !> A = A - x*y^T (columns with y_j = 0 untouched), and the indices of the first largest
    !> |a_ij| of the result in array element order (as maxloc(abs(a)), without its N_c x N_c
    !> temporary), found in the same pass over A: an elimination step then reads the N_c x N_c
    !> remainder once instead of twice.
    pure subroutine subtract_outer(a, x, y, at)
        real(dp), intent(inout) :: a(:, :)
        real(dp), intent(in) :: x(:), y(:)
        integer, intent(out) :: at(2)

        real(dp) :: largest
        integer :: i, j

        at = [1, 1]
        largest = 0.0_dp
        do j = 1, size(a, 2)
            if (y(j) /= 0.0_dp) a(:, j) = a(:, j) - x*y(j)
            if (j == 1) largest = abs(a(1, 1))
            do i = 1, size(a, 1)
                if (abs(a(i, j)) > largest) then
                    largest = abs(a(i, j))
                    at = [i, j]
                end if
            end do
        end do
    end subroutine subtract_outer

    !> W0*x [m] for loads x [N]: U*(V^T*x) with the factors (Psi*(A*(B^T*(Psi^T*x))) when they
    !> lie in the modes' span), else the dense product.
    !>
    !> V^T*x is MATMUL on blocks of rows of the stored V^T (contiguous in k).
    !> Threads: V^T*x by fixed blocks of `column_block` rows of V^T, then U*z (or W0*x) by fixed
    !> blocks of `row_block` rows, in one parallel region. Every y_i and z_k is the same
    !> ordered sum (MATMUL on a block of rows) whoever does its block, so any number
    !> of threads gives the one-thread result bit for bit; small products and calls from inside
    !> a parallel region (a host's, or ours) stay on the calling thread.
    function apply_compliance(compliance, weight0, x) result(y)
        !> W0 as the run uses it.
        type(lowrank_compliance), intent(in) :: compliance
        !> The dense W0 [m/N] (N_c x N_c).
        real(dp), intent(in) :: weight0(:, :)
        !> Loads [N] (N_c).
        real(dp), intent(in) :: x(:)
        real(dp) :: y(size(x))

        real(dp) :: z(compliance%rank), loads(size(x)), product(size(x))
        integer :: first, last

        if (.not. compliance%low_rank) then
            !$omp parallel do if (sharing(real(size(weight0), dp))) default(none) shared(weight0, x, y) &
            !$omp private(last) schedule(static)
            do first = 1, size(x), row_block
                last = min(first + row_block - 1, size(x))
                y(first:last) = matmul(weight0(first:last, :), x)
            end do
            !$omp end parallel do
            return
        end if
        if (allocated(compliance%shapes)) then
            call right_product(compliance, x, z)
            call left_product(compliance, z, x, y, subtract=.false.)
            return
        end if
        ! the loads side by side (x may be a row of the caller's array) for the kernel
        loads(:) = x
        !$omp parallel if (sharing(real(size(compliance%left), dp))) default(none) &
        !$omp shared(compliance, loads, product, z) private(last)
        !$omp do schedule(static)
        do first = 1, compliance%rank, column_block
            last = min(first + column_block - 1, compliance%rank)
            call ordered_product(compliance%right_t, first, loads, z(first:last))
        end do
        !$omp end do
        !$omp do schedule(static)
        do first = 1, size(loads), row_block
            last = min(first + row_block - 1, size(loads))
            call ordered_product(compliance%left, first, z, product(first:last))
        end do
        !$omp end do
        !$omp end parallel
        y(:) = product
    end function apply_compliance

    !> z = V_A^T*x = V^T*x_s, V_A the rows `active` of V and x_s the values x at the active
    !> points and zero elsewhere (no gathered copy of V), by `right_product`.
    subroutine gathered_product(x, compliance, active, z)
        !> Values at the active points (N_a).
        real(dp), intent(in) :: x(:)
        !> The factors.
        type(lowrank_compliance), intent(in) :: compliance
        !> The active points (N_a).
        integer, intent(in) :: active(:)
        !> V_A^T*x (r).
        real(dp), intent(out) :: z(:)

        real(dp) :: scattered(size(compliance%right_t, 2))

        scattered(:) = 0.0_dp
        scattered(active) = x
        call right_product(compliance, scattered, z)
    end subroutine gathered_product

    !> z = V^T*x (r) for x at every point (N_c): by the stored V^T (`transposed_product`), or as
    !> B^T*(Psi^T*x) when the factors lie in the modes' span (S*r multiply-adds and the small
    !> products on the grid instead of N_c*r), each sum in a fixed order whatever the threads.
    subroutine right_product(compliance, x, z)
        !> The factors.
        type(lowrank_compliance), intent(in) :: compliance
        !> Values at the points (N_c).
        real(dp), intent(in) :: x(:)
        !> V^T*x (r).
        real(dp), intent(out) :: z(:)

        if (.not. allocated(compliance%shapes)) then
            ! x side by side for the kernel (it may be a row of the caller's array)
            call transposed_product(compliance%right_t, [x], z)
            return
        end if
        block
            real(dp) :: modal(size(compliance%modal_right_t, 2))

            if (allocated(compliance%along_q)) then
                call grid_loads(compliance, x, modal)
            else
                call separable_modal_forces(compliance%shapes, x, modal, shapes_threaded(compliance))
            end if
            call transposed_product(compliance%modal_right_t, modal, z)
        end block
    end subroutine right_product

    !> s = b - U*y (`subtract`) or s = U*y (N_c): by the stored U (`subtract_product`), or as
    !> Psi*(A*y) when the factors lie in the modes' span, each sum in a fixed order whatever
    !> the threads.
    subroutine left_product(compliance, y, b, s, subtract)
        !> The factors.
        type(lowrank_compliance), intent(in) :: compliance
        !> Coefficients (r).
        real(dp), intent(in) :: y(:)
        !> Values at the points (N_c), unused unless `subtract`.
        real(dp), intent(in) :: b(:)
        !> b - U*y or U*y (N_c).
        real(dp), intent(out) :: s(:)
        !> Whether U*y is subtracted from b.
        logical, intent(in) :: subtract

        integer :: i

        if (.not. allocated(compliance%shapes)) then
            if (subtract) then
                call subtract_product(compliance%left, y, b, s)
            else
                ! 0 - U*y, negated: U*y exactly
                call subtract_product(compliance%left, y, [(0.0_dp, i=1, size(s))], s)
                s(:) = -s
            end if
            return
        end if
        block
            real(dp) :: modal(size(compliance%modal_left, 1))

            call transposed_product(compliance%modal_left, y, modal)
            if (allocated(compliance%along_q)) then
                call grid_values(compliance, modal, s)
            else
                call separable_displacements(compliance%shapes, modal, s, shapes_threaded(compliance))
            end if
        end block
        if (subtract) s(:) = b - s
    end subroutine left_product

    !> Whether the products by the modes' shapes Phi share their work among threads (`sharing`).
    logical function shapes_threaded(compliance)
        type(lowrank_compliance), intent(in) :: compliance

        shapes_threaded = sharing(real(separable_work(compliance%shapes), dp))
    end function shapes_threaded

    !> Psi^T*q (S) on the compressed basis: the loads on the grid G (n_col x n_row), then
    !> T = G*Q_y (n_col x rho_y) and Q_x^T*T (rho_x x rho_y, the basis' order: a first), each
    !> sum in the order of the grid's rows, then of its columns (`rows_product`).
    subroutine grid_loads(compliance, q, modal)
        !> The factors, with the compressed basis.
        type(lowrank_compliance), intent(in) :: compliance
        !> Loads at the points (N_c).
        real(dp), intent(in) :: q(:)
        !> Psi^T*q (S).
        real(dp), intent(out) :: modal(:)

        real(dp) :: grid(size(compliance%along_q, 1), size(compliance%across_q, 1)), &
                    by_column(size(compliance%along_q, 1), size(compliance%across_q, 2))
        integer :: i

        grid(:, :) = 0.0_dp
        do i = 1, size(q)
            grid(compliance%shapes%column(i), compliance%shapes%row(i)) = &
                grid(compliance%shapes%column(i), compliance%shapes%row(i)) + q(i)
        end do
        call rows_product(size(grid, 1), size(grid, 2), size(by_column, 2), grid, compliance%across_q, by_column)
        call rows_product(size(compliance%along_q, 2), size(grid, 1), size(by_column, 2), compliance%along_q_t, &
                          by_column, modal)
    end subroutine grid_loads

    !> Psi*y (N_c) on the compressed basis: Z = Q_x*Y (n_col x rho_y, Y the rho_x x rho_y
    !> coefficients), the grid Z*Q_y^T (n_col x n_row), read at the points' cells; each sum in
    !> the order of the coefficients (`rows_product`).
    subroutine grid_values(compliance, modal, s)
        !> The factors, with the compressed basis.
        type(lowrank_compliance), intent(in) :: compliance
        !> The coefficients y (S).
        real(dp), intent(in) :: modal(:)
        !> Psi*y at the points (N_c).
        real(dp), intent(out) :: s(:)

        real(dp) :: by_column(size(compliance%along_q, 1), size(compliance%across_q, 2)), &
                    grid(size(compliance%along_q, 1), size(compliance%across_q, 1))

        call rows_product(size(by_column, 1), size(compliance%along_q, 2), size(by_column, 2), compliance%along_q, &
                          modal, by_column)
        call rows_product(size(grid, 1), size(by_column, 2), size(grid, 2), by_column, compliance%across_q_t, grid)
        s(:) = grid_at_points(grid, compliance%shapes%column, compliance%shapes%row)
    end subroutine grid_values

    !> The grid's values at the points' cells (N_c).
    pure function grid_at_points(grid, column, row) result(values)
        real(dp), intent(in) :: grid(:, :)
        integer, intent(in) :: column(:), row(:)
        real(dp) :: values(size(column))

        integer :: i

        do i = 1, size(column)
            values(i) = grid(column(i), row(i))
        end do
    end function grid_at_points

    !> Y(:, v) = A*X(:, v) for v = 1..nv, A (m x n), each sum in the order of A's columns
    !> (`ordered_rows_many`; X and Y may be any arrays of n*nv and m*nv values).
    subroutine rows_product(m, n, nv, a, x, y)
        !> Rows m, columns n of A and number of vectors nv.
        integer, intent(in) :: m, n, nv
        !> A.
        real(dp), intent(in) :: a(m, n)
        !> X.
        real(dp), intent(in) :: x(n, nv)
        !> A*X.
        real(dp), intent(out) :: y(m, nv)

        call ordered_rows_many(int(m, c_int), int(n, c_int), int(m, c_int), a, int(nv, c_int), int(n, c_int), x, &
                               int(m, c_int), y)
    end subroutine rows_product

    !> z = V^T*x (r) for x at every point (N_c), by fixed blocks of `column_block` rows of V^T
    !> shared among threads: each z_k is one MATMUL sum whoever computes it.
    subroutine transposed_product(right_t, x, z)
        !> V^T (r x N_c).
        real(dp), intent(in), contiguous :: right_t(:, :)
        !> Values at the points (N_c).
        real(dp), intent(in) :: x(:)
        !> V^T*x (r).
        real(dp), intent(out) :: z(:)

        integer :: first, last

        !$omp parallel do if (sharing(real(size(right_t), dp))) default(none) &
        !$omp shared(x, right_t, z) private(last) schedule(static)
        do first = 1, size(right_t, 1), column_block
            last = min(first + column_block - 1, size(right_t, 1))
            call ordered_product(right_t, first, x, z(first:last))
        end do
        !$omp end parallel do
    end subroutine transposed_product

    !> y = A(first:first + m - 1, :)*x (m = size(y)) with y_i = sum_j a_ij*x_j added in the order
    !> of j from zero, the sum MATMUL takes: ordered_kernel.c, the rows in SIMD lanes at the
    !> CPU's width, never fused, so the bits are MATMUL's on every CPU.
    pure subroutine ordered_product(a, first, x, y)
        !> A (N x n), contiguous.
        real(dp), intent(in), contiguous, target :: a(:, :)
        !> The first row of A taken.
        integer, intent(in) :: first
        !> x (n).
        real(dp), intent(in) :: x(:)
        !> The rows' products (m).
        real(dp), intent(out) :: y(:)

        if (size(y) == 0) return
        if (size(x) == 0) then
            y(:) = 0.0_dp
            return
        end if
        call ordered_rows(int(size(y), c_int), int(size(x), c_int), int(size(a, 1), c_int), c_loc(a(first, 1)), x, y)
    end subroutine ordered_product

    !> The full Newton step of R(delta) = delta - a + W0*(F(delta) - F0) from a compression
    !> `delta` without R(delta) itself, when W0 = U*V^T and Woodbury's M^-1 serves the slopes t
    !> of `delta`: with q = F(delta) - F0 - diag(t)*(delta - a),
    !>
    !>     delta + s = a - U*M^-1*(V^T*q),
    !>
    !> the same point as `newton_solve` with b = -R(delta) (R's own U*V^T*(F - F0) cancels
    !> against Woodbury's), for two products by N_c x r factors instead of four. `taken` is
    !> false (nothing done) when W0 is dense, no slope is positive, or the system on the
    !> active set is the cheaper: the caller then takes `newton_solve`.
    subroutine woodbury_step(compliance, weight0, slopes, q, free, next, taken, error)
        !> W0 as the run uses it; keeps the last Newton matrix.
        type(lowrank_compliance), intent(inout) :: compliance
        !> The dense W0 [m/N] (N_c x N_c).
        real(dp), intent(in) :: weight0(:, :)
        !> t_i = dF_i/ddelta_i [N/m] at `delta` (N_c), zero off the active set.
        real(dp), intent(in) :: slopes(:)
        !> q = F(delta) - F0 - diag(t)*(delta - a) [N] (N_c).
        real(dp), intent(in) :: q(:)
        !> The free compressions a [m] (N_c).
        real(dp), intent(in) :: free(:)
        !> delta + s [m] (N_c), when `taken`.
        real(dp), intent(out) :: next(:)
        !> Whether the step was made here.
        logical, intent(out) :: taken
        !> Set when the Newton matrix is singular.
        type(error_type), allocatable, intent(out) :: error

        real(dp) :: z(compliance%rank), y(compliance%rank)
        integer :: n_active

        taken = .false.
        if (.not. compliance%low_rank .or. compliance%rank == 0) return
        n_active = count(slopes /= 0.0_dp)
        if (n_active == 0) return
        if (active_set_cheaper(real(n_active, dp), real(compliance%rank, dp))) return
        call form_newton_matrix(compliance, weight0, slopes, n_active, error)
        if (allocated(error)) return
        call right_product(compliance, q, z)
        call ordered_product(compliance%newton%inverse, 1, z, y)
        call left_product(compliance, y, free, next, subtract=.true.)
        taken = .true.
    end subroutine woodbury_step

    !> Whether a loop of `work` multiply-adds is shared among threads: large enough to pay for
    !> a parallel region, and not called from inside one (no nested threads in a host's region).
    logical function sharing(work)
        !> Multiply-adds (or comparable operations) of the loop.
        real(dp), intent(in) :: work

        sharing = work >= thread_work
        !$ sharing = sharing .and. .not. omp_in_parallel()
    end function sharing

    !> The Newton step s [m] solving (I + W0*diag(t))*s = b: on the active set or by Woodbury
    !> with the factors, or a dense LU when W0 has no low-rank factors.
    subroutine newton_solve(compliance, weight0, slopes, b, s, error)
        !> W0 as the run uses it; keeps the last factored Newton matrix.
        type(lowrank_compliance), intent(inout) :: compliance
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

        real(dp), allocatable :: jacobian(:, :), y(:), scaled_b(:)
        real(dp) :: z(compliance%rank)
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
        if (compliance%rank == 0 .or. all(slopes == 0.0_dp)) then
            s(:) = b
            return
        end if
        call form_newton_matrix(compliance, weight0, slopes, count(slopes /= 0.0_dp), error)
        if (allocated(error)) return
        associate (newton => compliance%newton, r => compliance%rank)
            if (newton%on_active_set) then
                allocate (y(size(newton%factors, 1)))
                call lu_solve(newton%factors, newton%pivot, b(newton%active), y, error)
                if (allocated(error)) return
                y(:) = slopes(newton%active)*y
                call gathered_product(y, compliance, newton%active, z)
                call left_product(compliance, z, b, s, subtract=.true.)
            else
                scaled_b = slopes(newton%active)*b(newton%active)
                call gathered_product(scaled_b, compliance, newton%active, z)
                allocate (y(r))
                call ordered_product(newton%inverse, 1, z, y)
                call left_product(compliance, y, b, s, subtract=.true.)
            end if
        end associate
    end subroutine newton_solve

    !> Factor the Newton matrix of `slopes` unless it is the one kept: on the active set
    !> (N_a^3/3 operations) or M = I_r + V_A^T*diag(t_A)*U_A (N_a*r^2 + r^3/3), the cheaper;
    !> M^-1 is updated instead when few slopes changed (`update_inverse`).
    subroutine form_newton_matrix(compliance, weight0, slopes, n_active, error)
        type(lowrank_compliance), intent(inout) :: compliance
        real(dp), intent(in) :: weight0(:, :), slopes(:)
        !> Number of nonzero slopes.
        integer, intent(in) :: n_active
        type(error_type), allocatable, intent(out) :: error

        real(dp) :: rank
        integer :: changed(size(slopes)), n_changed, i, j
        logical :: on_active_set, updated

        associate (newton => compliance%newton)
            rank = real(compliance%rank, dp)
            on_active_set = active_set_cheaper(real(n_active, dp), rank)
            if (newton%ready) then
                n_changed = 0
                do i = 1, size(slopes)
                    if (slopes(i) /= newton%slopes(i)) then
                        n_changed = n_changed + 1
                        changed(n_changed) = i
                    end if
                end do
                if (n_changed == 0) return
                if (.not. (on_active_set .or. newton%on_active_set)) then
                    call update_inverse(compliance, slopes, changed(1:n_changed), n_active, updated)
                    if (updated) return
                end if
            end if
            newton%ready = .false.
            newton%slopes = slopes
            call set_active(slopes, n_active, newton%active)
            newton%on_active_set = on_active_set
            if (newton%on_active_set) then
                newton%factors = weight0(newton%active, newton%active)
                do j = 1, size(newton%active)
                    newton%factors(:, j) = newton%factors(:, j)*slopes(newton%active(j))
                    newton%factors(j, j) = newton%factors(j, j) + 1.0_dp
                end do
            else
                call woodbury_matrix(compliance%left, compliance%right, slopes, newton%active, newton%factors)
            end if
            if (allocated(newton%pivot)) deallocate (newton%pivot)
            allocate (newton%pivot(size(newton%factors, 1)))
            call lu_factor(newton%factors, newton%pivot, error)
            if (allocated(error)) return
            if (.not. newton%on_active_set) then
                call inverse_of_factors(newton%factors, newton%pivot, newton%inverse, error)
                if (allocated(error)) return
                ! M symmetric: its inverse made so to the bit, for the updates' y = x
                if (compliance%symmetric) newton%inverse = (newton%inverse + transpose(newton%inverse))/2
                newton%updates = 0
            end if
            newton%ready = .true.
        end associate
    end subroutine form_newton_matrix

    !> Whether the LU on an active set of n_a points (n_a^3/3 operations) is cheaper than
    !> forming and factoring M of rank r (n_a*r^2 + r^3/3).
    pure logical function active_set_cheaper(n_a, rank)
        real(dp), intent(in) :: n_a, rank

        active_set_cheaper = n_a**3/3 < n_a*rank**2 + rank**3/3
    end function active_set_cheaper

    !> M^-1 (r x r) from the LU factors of M, column by column.
    subroutine inverse_of_factors(factors, pivot, inverse, error)
        real(dp), intent(in) :: factors(:, :)
        integer, intent(in) :: pivot(:)
        real(dp), allocatable, intent(out) :: inverse(:, :)
        type(error_type), allocatable, intent(out) :: error

        real(dp) :: unit(size(factors, 1))
        integer :: k

        allocate (inverse(size(factors, 1), size(factors, 1)))
        do k = 1, size(factors, 1)
            unit(:) = 0.0_dp
            unit(k) = 1.0_dp
            call lu_solve(factors, pivot, unit, inverse(:, k), error)
            if (allocated(error)) return
        end do
    end subroutine inverse_of_factors

    !> M^-1 brought to the slopes `slopes` by one Sherman-Morrison update per changed slope:
    !> M' = M + (t_i' - t_i)*v_i*u_i^T, M'^-1 = M^-1 - c*x*y^T with x = M^-1*v_i,
    !> y^T = u_i^T*M^-1 and c = (t_i' - t_i)/(1 + (t_i' - t_i)*u_i^T*x). Not done (`updated`
    !> false, the kept matrix marked stale) when too many slopes changed, when after N_c updates
    !> since M was formed or last checked M^-1 no longer inverts M to `inverse_drift`
    !> (`inverse_accurate`), or at a pivot below `update_pivot`.
    !>
    !> Symmetric factors (u_i = v_i, M^-1 symmetric): y = x, and the changes are made in groups
    !> of up to `update_group` (`symmetric_group`), two passes over M^-1 a group instead of two
    !> a change.
    subroutine update_inverse(compliance, slopes, changed, n_active, updated)
        type(lowrank_compliance), intent(inout) :: compliance
        real(dp), intent(in) :: slopes(:)
        !> The points whose slopes differ from those of the kept M^-1, in increasing order.
        integer, intent(in) :: changed(:)
        !> Number of nonzero slopes.
        integer, intent(in) :: n_active
        logical, intent(out) :: updated

        real(dp) :: x(compliance%rank), y(compliance%rank), change, pivot
        integer :: i, j, k, l, r, first, last
        logical :: done

        updated = .false.
        associate (newton => compliance%newton, u => compliance%left, v_t => compliance%right_t)
            if (3*size(changed) > n_active) return
            if (newton%updates + size(changed) > size(slopes)) then
                if (.not. inverse_accurate(compliance)) return
                newton%updates = 0
                newton%kept = newton%kept + 1
            end if
            newton%ready = .false.
            if (compliance%symmetric) then
                r = compliance%rank
                do first = 1, size(changed), update_group
                    last = min(first + update_group - 1, size(changed))
                    call symmetric_group(newton%inverse, r, v_t, changed(first:last), &
                                         slopes(changed(first:last)) - newton%slopes(changed(first:last)), done)
                    if (.not. done) return
                end do
            else
                do j = 1, size(changed)
                    i = changed(j)
                    change = slopes(i) - newton%slopes(i)
                    call ordered_product(newton%inverse, 1, v_t(:, i), x)
                    y(:) = matmul(u(i, :), newton%inverse)
                    pivot = 1.0_dp + change*dot_product(u(i, :), x)
                    if (.not. (abs(pivot) >= update_pivot)) return
                    x(:) = (change/pivot)*x
                    do k = 1, size(y)
                        !$omp simd
                        do l = 1, size(x)
                            newton%inverse(l, k) = newton%inverse(l, k) - x(l)*y(k)
                        end do
                    end do
                end do
            end if
            newton%slopes(:) = slopes
            call set_active(slopes, n_active, newton%active)
            newton%updates = newton%updates + size(changed)
            newton%ready = .true.
            updated = .true.
        end associate
    end subroutine update_inverse

    !> The indices of the nonzero slopes in increasing order (`active` reallocated only when
    !> their number changes).
    pure subroutine set_active(slopes, n_active, active)
        !> Slopes t [N/m] (N_c).
        real(dp), intent(in) :: slopes(:)
        !> Number of nonzero slopes.
        integer, intent(in) :: n_active
        !> The active points (n_active).
        integer, allocatable, intent(inout) :: active(:)

        integer :: i, k

        if (allocated(active)) then
            if (size(active) /= n_active) deallocate (active)
        end if
        if (.not. allocated(active)) allocate (active(n_active))
        k = 0
        do i = 1, size(slopes)
            if (slopes(i) /= 0.0_dp) then
                k = k + 1
                active(k) = i
            end if
        end do
    end subroutine set_active

    !> Whether the kept M^-1 still inverts M = I_r + V_A^T*diag(t_A)*U_A of its slopes to
    !> `inverse_drift`: w = M^-1*1 by the kept inverse, then |M*w - 1|_max from the rows of the
    !> factors at the active points (2*N_a*r + r^2 operations against the N_a*r^2 + r^3 of
    !> forming and inverting M anew). Asked after every N_c rank-one updates: the updates'
    !> round-off grows slowly, and M is formed anew only once it shows.
    logical function inverse_accurate(compliance)
        type(lowrank_compliance), intent(in) :: compliance

        real(dp) :: ones(compliance%rank), w(compliance%rank), product(compliance%rank)
        integer :: j, a

        ones(:) = 1.0_dp
        call ordered_product(compliance%newton%inverse, 1, ones, w)
        product(:) = w
        do j = 1, size(compliance%newton%active)
            a = compliance%newton%active(j)
            product(:) = product + (compliance%newton%slopes(a)*dot_product(compliance%left(a, :), w)) &
                         *compliance%right_t(:, a)
        end do
        inverse_accurate = maxval(abs(product - 1.0_dp)) <= inverse_drift
    end function inverse_accurate

    !> The rank-one updates of a symmetric M^-1 for d changed slopes at once (d small): with
    !> M_p^-1 the inverse after the first p - 1 of them, x_p = M_p^-1*v_p =
    !> M^-1*v_p - sum_{q<p} c_q*x_q*(x_q^T*v_p). The products M^-1*v_p in one pass (four
    !> vectors a reading of M^-1), the corrections in O(d^2*r), every pivot
    !> 1 + (t_p' - t_p)*v_p^T*x_p checked before anything changes, then the d updates
    !> c_p*(x_p*x_p^T) in one pass, each entry the same roundings as d updates one after the
    !> other, so M^-1 stays symmetric to the bit. `done` false (M^-1 untouched) at a pivot below
    !> `update_pivot`.
    subroutine symmetric_group(inverse, r, right_t, points, changes, done)
        !> M^-1 (r x r), updated when `done`.
        real(dp), intent(inout) :: inverse(:, :)
        !> Its order r.
        integer, intent(in) :: r
        !> V^T (r x N_c).
        real(dp), intent(in) :: right_t(:, :)
        !> The points whose slopes changed (d).
        integer, intent(in) :: points(:)
        !> t_p' - t_p [N/m] (d).
        real(dp), intent(in) :: changes(:)
        !> Whether the updates were made.
        logical, intent(out) :: done

        real(dp) :: rows(r, size(points)), products(r, size(points)), factors(size(points)), pivot
        integer :: p, q

        done = .false.
        rows(:, :) = right_t(:, points)
        call rows_product(r, r, size(points), inverse, rows, products)
        do p = 1, size(points)
            do q = 1, p - 1
                products(:, p) = products(:, p) - (factors(q)*four_way_dot(products(:, q), rows(:, p)))*products(:, q)
            end do
            pivot = 1.0_dp + changes(p)*four_way_dot(rows(:, p), products(:, p))
            if (.not. (abs(pivot) >= update_pivot)) return
            factors(p) = changes(p)/pivot
        end do
        ! c*(x_l*x_k): the same bits in (l, k) and (k, l)
        call symmetric_updates(int(r, c_int), int(size(inverse, 1), c_int), inverse, int(size(points), c_int), &
                               int(r, c_int), products, factors)
        done = .true.
    end subroutine symmetric_group

    !> x^T*y in four running sums (terms 1, 5, 9, ...; 2, 6, ...; ...) added at the end: a fixed
    !> order, four additions in flight instead of one.
    pure real(dp) function four_way_dot(x, y)
        real(dp), intent(in) :: x(:), y(:)

        real(dp) :: sums(4)
        integer :: i, body

        sums(:) = 0.0_dp
        body = size(x) - mod(size(x), 4)
        do i = 1, body, 4
            sums(:) = sums + x(i:i + 3)*y(i:i + 3)
        end do
        do i = body + 1, size(x)
            sums(1) = sums(1) + x(i)*y(i)
        end do
        four_way_dot = (sums(1) + sums(2)) + (sums(3) + sums(4))
    end function four_way_dot

    !> M = I_r + V_A^T*diag(t_A)*U_A (r x r) in one parallel region: the rows of the active
    !> points gathered from V (scaled by t, transposed) and U column by column, then column j
    !> of M as (t_A*V_A)^T*U_A(:, j) by `ordered_product`, the columns shared among threads:
    !> every entry is one thread's ordered sum, so the factors depend neither on the number of
    !> threads nor on the CPU.
    subroutine woodbury_matrix(left, right, slopes, active, m)
        !> U (N_c x r) [m/N].
        real(dp), intent(in) :: left(:, :)
        !> V (N_c x r).
        real(dp), intent(in) :: right(:, :)
        !> t [N/m] (N_c).
        real(dp), intent(in) :: slopes(:)
        !> The active points (N_a).
        integer, intent(in) :: active(:)
        !> M (r x r).
        real(dp), allocatable, intent(out) :: m(:, :)

        real(dp), allocatable :: scaled_t(:, :), gathered(:, :)
        integer :: a, k, r

        r = size(left, 2)
        allocate (m(r, r), scaled_t(r, size(active)), gathered(size(active), r))
        !$omp parallel if (sharing(real(size(active), dp)*r**2)) default(none) &
        !$omp shared(left, right, slopes, active, m, scaled_t, gathered, r) private(a)
        !$omp do schedule(static)
        do k = 1, r
            do a = 1, size(active)
                scaled_t(k, a) = right(active(a), k)*slopes(active(a))
                gathered(a, k) = left(active(a), k)
            end do
        end do
        !$omp end do
        !$omp do schedule(static)
        do k = 1, r
            call ordered_product(scaled_t, 1, gathered(:, k), m(:, k))
            m(k, k) = m(k, k) + 1.0_dp
        end do
        !$omp end do
        !$omp end parallel
    end subroutine woodbury_matrix

    !> s = b - u*y, by fixed blocks of rows shared among threads.
    subroutine subtract_product(u, y, b, s)
        real(dp), intent(in), contiguous :: u(:, :)
        real(dp), intent(in) :: y(:), b(:)
        real(dp), intent(out) :: s(:)

        real(dp) :: product(row_block)
        integer :: first, last

        !$omp parallel do if (sharing(real(size(u), dp))) default(none) shared(u, y, b, s) private(last, product) &
        !$omp schedule(static)
        do first = 1, size(u, 1), row_block
            last = min(first + row_block - 1, size(u, 1))
            call ordered_product(u, first, y, product(1:last - first + 1))
            s(first:last) = b(first:last) - product(1:last - first + 1)
        end do
        !$omp end parallel do
    end subroutine subtract_product

end module greenconv_contact_lowrank_solve
