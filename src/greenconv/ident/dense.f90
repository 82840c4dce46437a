!> Dense symmetric linear algebra of the identification fits: the Gram matrix, the Cholesky
!> factor, solve and inverse, and a least-squares solve by a one-sided Jacobi SVD, all in
!> this module's own loops with every sum taken in one fixed order.
!>
!> - `gram`: A^T A (one triangle by gram_kernel.c's C kernel, the other copied) and A^T b;
!> - `spd_factor`, `spd_solve`, `spd_inverse`: Cholesky A = U^T U, A x = b, inv(A) for a
!>   symmetric positive definite A;
!> - `svd_solve`: the minimum-norm least-squares solution with singular values below rcond
!>   times the largest left out (what LAPACK's dgelsd gives), by Householder reduction and
!>   Hestenes' one-sided Jacobi;
!> - `product_of`, `quadratic_form`: A B and x^T A x in place of the intrinsic matmul, whose
!>   order of summation depends on the optimisation level and the CPU.
!>
!> Why not BLAS and LAPACK: the order search decides on differences of chi2 and on Wald
!> statistics that these products feed, and a BLAS takes its sums in an order of its own
!> choosing (OpenBLAS's Haswell, SkylakeX and Sandybridge kernels, its threads, the reference
!> BLAS each give other last bits). An ill-conditioned information amplifies those bits into
!> the steps of the fits, and the search's many decisions then part ways (pyuff's measured
!> beam, FRF 1: six modes with OpenBLAS's default kernels, two under OPENBLAS_CORETYPE=Haswell).
!> Here every dot product is `dot`'s: four partial sums over the index in a fixed order, added
!> pairwise, so the same inputs give the same bits whatever the BLAS, the thread count or the
!> optimisation level (gfortran keeps IEEE order without -ffast-math, and the x86-64 baseline
!> has no fused multiply-add to contract into). No BLAS or LAPACK is called here, so nothing
!> here depends on threads.
!>
!> Every call has its dimensions right by construction; a matrix that is not positive
!> definite (a pivot <= 0 or NaN) is reported by `ok`, never stopped on.
module greenconv_ident_dense
    use, intrinsic :: iso_c_binding, only: c_int, c_double
    use greenconv_core_kinds, only: dp
    implicit none
    private

    interface
        !> The upper triangle of A^T A in a fixed order and A^T b, each column's dot product in
        !> the order of `dot` (gram_kernel.c).
        pure subroutine gram_kernel(m, n, a, b, product, projection) bind(c, name='greenconv_ident_gram')
            import :: c_int, c_double
            !> Rows of A.
            integer(c_int), value :: m
            !> Columns of A.
            integer(c_int), value :: n
            !> A (m x n, contiguous).
            real(c_double), intent(in) :: a(m, n)
            !> b (m).
            real(c_double), intent(in) :: b(m)
            !> A^T A's upper triangle (n x n).
            real(c_double), intent(inout) :: product(n, n)
            !> A^T b (n).
            real(c_double), intent(out) :: projection(n)
        end subroutine gram_kernel
    end interface

    public :: gram, spd_factor, spd_solve, spd_inverse, svd_solve, identity, dot, product_of, quadratic_form

    !> Most sweeps of the one-sided Jacobi SVD (each rotates every pair of columns once);
    !> double precision converges in 6 to 12.
    integer, parameter :: max_sweeps = 60

contains

    !> x . y with four partial sums over i = 1, 5, 9, ... (and 2, 3, 4 on), added as
    !> (s1 + s2) + (s3 + s4), then the tail: one fixed order for every machine and build.
    pure real(dp) function dot(x, y)
        !> First vector (n).
        real(dp), intent(in) :: x(:)
        !> Second vector (n).
        real(dp), intent(in) :: y(:)

        real(dp) :: s1, s2, s3, s4
        integer :: i, n, m

        n = size(x)
        m = n - mod(n, 4)
        s1 = 0.0_dp
        s2 = 0.0_dp
        s3 = 0.0_dp
        s4 = 0.0_dp
        do i = 1, m, 4
            s1 = s1 + x(i)*y(i)
            s2 = s2 + x(i + 1)*y(i + 1)
            s3 = s3 + x(i + 2)*y(i + 2)
            s4 = s4 + x(i + 3)*y(i + 3)
        end do
        dot = (s1 + s2) + (s3 + s4)
        do i = m + 1, n
            dot = dot + x(i)*y(i)
        end do
    end function dot

    !> scale*A^T A and scale*A^T b for a real m x n matrix A. A^T A is gram_kernel.c's
    !> `greenconv_ident_gram_upper`: each element's sum over the rows in order, one
    !> accumulator, in one fixed order whatever the build (it runs at -O2 in the debug build too);
    !> A^T b is its `greenconv_ident_gram_projection`, each column's sum in the order of `dot`.
    pure subroutine gram(a, scale, product, b, projection)
        !> The matrix A (m x n).
        real(dp), intent(in) :: a(:, :)
        !> Factor of both results (units of 1 per unit of A squared).
        real(dp), intent(in) :: scale
        !> scale*A^T A (n x n, symmetric, both triangles filled).
        real(dp), intent(out) :: product(:, :)
        !> Vector b (m).
        real(dp), intent(in) :: b(:)
        !> scale*A^T b (n).
        real(dp), intent(out) :: projection(:)

        real(dp) :: upper(size(a, 2), size(a, 2)), along(size(a, 2))
        integer :: i, j, n

        n = size(a, 2)
        if (n == 0) return
        upper = 0.0_dp
        call gram_kernel(int(size(a, 1), c_int), int(n, c_int), a, b, upper, along)
        do j = 1, n
            do i = 1, j
                product(i, j) = scale*upper(i, j)
                product(j, i) = product(i, j)
            end do
            projection(j) = scale*along(j)
        end do
    end subroutine gram

    !> Cholesky factor (upper, in place) of a symmetric positive definite matrix; the strict
    !> lower triangle is left as it was.
    pure subroutine spd_factor(a, ok)
        !> In: the matrix (n x n, upper triangle read); out: its factor U (A = U^T U) in the upper triangle.
        real(dp), intent(inout) :: a(:, :)
        !> False when A is not positive definite (a pivot <= 0 or NaN).
        logical, intent(out) :: ok

        real(dp) :: pivot
        integer :: i, j, n

        ok = .true.
        n = size(a, 1)
        do j = 1, n
            pivot = a(j, j) - dot(a(1:j - 1, j), a(1:j - 1, j))
            if (.not. (pivot > 0.0_dp)) then
                ok = .false.
                return
            end if
            a(j, j) = sqrt(pivot)
            do i = j + 1, n
                a(j, i) = (a(j, i) - dot(a(1:j - 1, j), a(1:j - 1, i)))/a(j, j)
            end do
        end do
    end subroutine spd_factor

    !> Solution x of A x = b for a symmetric positive definite A by Cholesky.
    pure subroutine spd_solve(a, b, x, ok)
        !> The matrix A (n x n).
        real(dp), intent(in) :: a(:, :)
        !> Right-hand side b (n).
        real(dp), intent(in) :: b(:)
        !> Solution x (n); incomplete when not ok.
        real(dp), allocatable, intent(out) :: x(:)
        !> False when A is not positive definite.
        logical, intent(out) :: ok

        real(dp) :: factor(size(a, 1), size(a, 1))
        integer :: i, n

        n = size(b)
        x = b
        factor = a
        call spd_factor(factor, ok)
        if (.not. ok) return
        ! U^T y = b (column i of U above the diagonal holds row i of U^T), then U x = y.
        do i = 1, n
            x(i) = (x(i) - dot(factor(1:i - 1, i), x(1:i - 1)))/factor(i, i)
        end do
        do i = n, 1, -1
            x(i) = (x(i) - dot(factor(i, i + 1:n), x(i + 1:n)))/factor(i, i)
        end do
    end subroutine spd_solve

    !> Inverse of a symmetric positive definite matrix by Cholesky: inv(A) = inv(U) inv(U)^T.
    pure subroutine spd_inverse(a, ok)
        !> In: the matrix A (n x n); out: inv(A), both triangles (incomplete when not ok).
        real(dp), intent(inout) :: a(:, :)
        !> False when A is not positive definite.
        logical, intent(out) :: ok

        real(dp) :: v(size(a, 1), size(a, 1))
        integer :: i, j, n

        n = size(a, 1)
        call spd_factor(a, ok)
        if (.not. ok .or. n == 0) return
        ! V = inv(U), upper triangular, column by column: U v_j = e_j.
        v = 0.0_dp
        do j = 1, n
            v(j, j) = 1.0_dp/a(j, j)
            do i = j - 1, 1, -1
                v(i, j) = -dot(a(i, i + 1:j), v(i + 1:j, j))/a(i, i)
            end do
        end do
        ! inv(A)(i, j) = sum over k >= max(i, j) of V(i, k) V(j, k).
        do j = 1, n
            do i = 1, j
                a(i, j) = dot(v(i, j:n), v(j, j:n))
                a(j, i) = a(i, j)
            end do
        end do
    end subroutine spd_inverse

    !> Minimum-norm least-squares solution x of A x = b, singular values below rcond times the
    !> largest left out (LAPACK's dgelsd's rule), by Hestenes' one-sided Jacobi SVD: pairs of
    !> columns of A rotated until every pair is orthogonal to within n*eps; the column norms are
    !> then the singular values, the rotations V. Cost: a sweep is n^2/2 rotations of two columns
    !> of m; a sweep count bounded by max_sweeps. A tall A (m > n) is first reduced by
    !> Householder reflections to R (n x n) and Q^T b, which have A's singular values and right
    !> singular vectors (cost 2*m*n^2, as one Gram product), and R solved in its place, whose
    !> sweeps cost n^3 each instead of m*n^2.
    pure recursive subroutine svd_solve(a, b, x, rcond)
        !> The matrix A (m x n).
        real(dp), intent(in) :: a(:, :)
        !> Right-hand side b (m).
        real(dp), intent(in) :: b(:)
        !> Solution x (n).
        real(dp), intent(out) :: x(:)
        !> Relative threshold on the singular values.
        real(dp), intent(in) :: rcond

        integer :: m, n

        m = size(a, 1)
        n = size(a, 2)
        if (m > n) then
            block
                real(dp), allocatable :: r(:, :), c(:), v(:)
                real(dp) :: norm, alpha, v_norm2, factor
                integer :: k, j

                r = a
                c = b
                do k = 1, n
                    norm = sqrt(dot(r(k:, k), r(k:, k)))
                    if (.not. (norm > 0.0_dp)) cycle
                    alpha = -sign(norm, r(k, k))
                    v = r(k:, k)
                    v(1) = v(1) - alpha
                    v_norm2 = dot(v, v)
                    if (.not. (v_norm2 > 0.0_dp)) cycle
                    r(k, k) = alpha
                    r(k + 1:, k) = 0.0_dp
                    do j = k + 1, n
                        factor = 2.0_dp*dot(v, r(k:, j))/v_norm2
                        r(k:, j) = r(k:, j) - factor*v
                    end do
                    factor = 2.0_dp*dot(v, c(k:))/v_norm2
                    c(k:) = c(k:) - factor*v
                end do
                call svd_solve(r(1:n, 1:n), c(1:n), x, rcond)
            end block
            return
        end if
        block
            real(dp) :: u(m, n), v(n, n), s(n)
            real(dp) :: alpha, beta, gamma, zeta, t, c, sn, tolerance, column(m), row(n)
            integer :: i, j, sweep
            logical :: rotated

            u = a
            v = 0.0_dp
            do j = 1, n
                v(j, j) = 1.0_dp
            end do
            tolerance = n*epsilon(1.0_dp)
            do sweep = 1, max_sweeps
                rotated = .false.
                do j = 2, n
                    do i = 1, j - 1
                        alpha = dot(u(:, i), u(:, i))
                        beta = dot(u(:, j), u(:, j))
                        gamma = dot(u(:, i), u(:, j))
                        if (.not. (abs(gamma) > tolerance*sqrt(alpha*beta))) cycle
                        rotated = .true.
                        zeta = (beta - alpha)/(2.0_dp*gamma)
                        t = sign(1.0_dp, zeta)/(abs(zeta) + sqrt(1.0_dp + zeta**2))
                        c = 1.0_dp/sqrt(1.0_dp + t**2)
                        sn = c*t
                        column = u(:, i)
                        u(:, i) = c*column - sn*u(:, j)
                        u(:, j) = sn*column + c*u(:, j)
                        row = v(:, i)
                        v(:, i) = c*row - sn*v(:, j)
                        v(:, j) = sn*row + c*v(:, j)
                    end do
                end do
                if (.not. rotated) exit
            end do
            do j = 1, n
                s(j) = sqrt(dot(u(:, j), u(:, j)))
            end do
            x = 0.0_dp
            if (n == 0) return
            do j = 1, n
                if (.not. (s(j) > rcond*maxval(s))) cycle
                x = x + v(:, j)*(dot(u(:, j), b)/s(j)**2)
            end do
        end block
    end subroutine svd_solve

    !> Identity matrix of order n.
    pure function identity(n) result(m)
        !> Order.
        integer, intent(in) :: n
        !> The identity matrix (n x n).
        real(dp) :: m(n, n)

        integer :: i

        m = 0.0_dp
        do i = 1, n
            m(i, i) = 1.0_dp
        end do
    end function identity

    !> A B, each element one `dot` (gfortran's matmul takes its sums in an order of its own:
    !> inlined at -O2, its library's blocked kernels for the CPU at -O0).
    pure function product_of(a, b) result(c)
        !> Left matrix (m x k).
        real(dp), intent(in) :: a(:, :)
        !> Right matrix (k x n).
        real(dp), intent(in) :: b(:, :)
        real(dp) :: c(size(a, 1), size(b, 2))

        real(dp) :: row(size(a, 2))
        integer :: i, j

        do i = 1, size(a, 1)
            row = a(i, :)
            do j = 1, size(b, 2)
                c(i, j) = dot(row, b(:, j))
            end do
        end do
    end function product_of

    !> x^T A x for a square A, in one fixed order.
    pure real(dp) function quadratic_form(a, x)
        !> Matrix (n x n).
        real(dp), intent(in) :: a(:, :)
        !> Vector (n).
        real(dp), intent(in) :: x(:)

        integer :: j

        quadratic_form = 0.0_dp
        do j = 1, size(x)
            quadratic_form = quadratic_form + x(j)*dot(a(:, j), x)
        end do
    end function quadratic_form

end module greenconv_ident_dense
