!> Dense symmetric linear algebra of the identification fits (issue 26: the Gram matrices
!> J^T J of the Levenberg-Marquardt steps took 40 % of a 50-mode fit in gfortran's general
!> matmul, the hand-written Cholesky 10 %): the Gram matrix by blocks of matmul, the Cholesky
!> factor, solve and inverse by the LAPACK the library links.
!>
!> - `gram`: A^T A and A^T b, one triangle computed by blocks of 16 rows (54 % of the work of
!>   matmul(transpose(A), A) for 50 modes), the other copied;
!> - `spd_solve`: A x = b for symmetric positive definite A by dpotrf and dpotrs;
!> - `spd_inverse`: inv(A) by dpotrf and dpotri.
!>
!> Every call has its dimensions right by construction (n >= 1, leading dimensions the
!> arrays' own), so LAPACK's XERBLA is never reached; a matrix that is not positive definite
!> (dpotrf's info > 0) is reported by `ok`, never stopped on. A NaN in the input gives a NaN
!> pivot, which dpotrf reports as not positive definite.
module greenconv_ident_dense
    use greenconv_core_kinds, only: dp
    implicit none
    private

    public :: gram, spd_factor, spd_solve, spd_inverse, identity

    !> Rows of A^T A computed per call of matmul in `gram` (16: 10.0 s on the 50-mode fit, 32: 11.0 s,
    !> 64: 12.0 s; smaller blocks cost more in calls than they save).
    integer, parameter :: block = 16

    interface
        !> Cholesky factor of a symmetric positive definite matrix, in place (LAPACK).
        pure subroutine dpotrf(uplo, n, a, lda, info)
            import :: dp
            character(len=1), intent(in) :: uplo
            integer, intent(in) :: n, lda
            real(dp), intent(inout) :: a(lda, *)
            integer, intent(out) :: info
        end subroutine dpotrf

        !> Solution of A X = B from dpotrf's factor (LAPACK).
        pure subroutine dpotrs(uplo, n, nrhs, a, lda, b, ldb, info)
            import :: dp
            character(len=1), intent(in) :: uplo
            integer, intent(in) :: n, nrhs, lda, ldb
            real(dp), intent(in) :: a(lda, *)
            real(dp), intent(inout) :: b(ldb, *)
            integer, intent(out) :: info
        end subroutine dpotrs

        !> Inverse of A from dpotrf's factor, one triangle, in place (LAPACK).
        pure subroutine dpotri(uplo, n, a, lda, info)
            import :: dp
            character(len=1), intent(in) :: uplo
            integer, intent(in) :: n, lda
            real(dp), intent(inout) :: a(lda, *)
            integer, intent(out) :: info
        end subroutine dpotri
    end interface

contains

    !> scale*A^T A and scale*A^T b for a real m x n matrix A: the upper triangle of A^T A by
    !> blocks of `block` rows, each one call of matmul on a transposed copy of the block's
    !> columns (gfortran's matmul picks the vector unit at run time; the reference BLAS's
    !> dsyrk, unblocked, took 2.6 times as long on a 50-mode fit), the lower triangle copied.
    subroutine gram(a, scale, product, b, projection, work)
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
        !> Work array (block x m), kept by the caller between calls (its fresh allocation at every
        !> call of a fit costs page faults).
        real(dp), allocatable, intent(inout) :: work(:, :)

        integer :: m, n, i, j, last

        m = size(a, 1)
        n = size(a, 2)
        if (allocated(work)) then
            if (size(work, 2) /= m) deallocate (work)
        end if
        if (.not. allocated(work)) allocate (work(block, m))
        do i = 1, n, block
            last = min(n, i + block - 1)
            work(1:last - i + 1, :) = transpose(a(:, i:last))
            product(i:last, i:n) = scale*matmul(work(1:last - i + 1, :), a(:, i:n))
            projection(i:last) = scale*matmul(work(1:last - i + 1, :), b)
        end do
        do j = 1, n - 1
            product(j + 1:n, j) = product(j, j + 1:n)
        end do
    end subroutine gram

    !> Cholesky factor (upper, in place) of a symmetric positive definite matrix.
    pure subroutine spd_factor(a, ok)
        !> In: the matrix (n x n); out: its factor U (A = U^T U) in the upper triangle.
        real(dp), intent(inout) :: a(:, :)
        !> False when A is not positive definite (a pivot <= 0 or NaN).
        logical, intent(out) :: ok

        integer :: info

        ok = .true.
        if (size(a, 1) == 0) return
        call dpotrf('U', size(a, 1), a, size(a, 1), info)
        ok = info == 0
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
        integer :: info, n

        n = size(b)
        x = b
        factor = a
        call spd_factor(factor, ok)
        if (.not. ok .or. n == 0) return
        call dpotrs('U', n, 1, factor, n, x, n, info)
        ok = info == 0
    end subroutine spd_solve

    !> Inverse of a symmetric positive definite matrix by Cholesky.
    pure subroutine spd_inverse(a, ok)
        !> In: the matrix A (n x n); out: inv(A), both triangles (incomplete when not ok).
        real(dp), intent(inout) :: a(:, :)
        !> False when A is not positive definite.
        logical, intent(out) :: ok

        integer :: info, n, j

        n = size(a, 1)
        call spd_factor(a, ok)
        if (.not. ok .or. n == 0) return
        call dpotri('U', n, a, n, info)
        ok = info == 0
        do j = 1, n - 1
            a(j + 1:n, j) = a(j, j + 1:n)
        end do
    end subroutine spd_inverse

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

end module greenconv_ident_dense
