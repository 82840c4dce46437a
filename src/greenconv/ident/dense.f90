!> Dense symmetric linear algebra of the identification fits (issue 26: the Gram matrices
!> J^T J of the Levenberg-Marquardt steps took 40 % of a 50-mode fit in gfortran's general
!> matmul, the hand-written Cholesky 10 %): the Gram matrix, the Cholesky factor, solve and
!> inverse by the BLAS and LAPACK the library links.
!>
!> - `gram`: A^T A by dsyrk (one triangle, the other copied) and A^T b by dgemv;
!> - `spd_solve`: A x = b for symmetric positive definite A by dpotrf and dpotrs;
!> - `spd_inverse`: inv(A) by dpotrf and dpotri.
!>
!> Every call has its dimensions right by construction (n >= 1, leading dimensions the
!> arrays' own), so LAPACK's XERBLA is never reached; a matrix that is not positive definite
!> (dpotrf's info > 0) is reported by `ok`, never stopped on. A NaN in the input gives a NaN
!> pivot; the reference LAPACK's dpotrf reported it as not positive definite, OpenBLAS's does
!> not (info = 0), so `spd_factor` also rejects a factor whose diagonal is not positive.
!>
!> Threads: every BLAS and LAPACK call here is made serially when OpenMP would give it more
!> threads (greenconv_ext_lapack's `lapack_serial_begin` and `lapack_serial_end`): OpenBLAS's
!> OpenMP build threads dsyrk, dgemv, dpotrf, dpotrs and dpotri (20 x 20 and up) and takes
!> their sums in another order, which changed the fits (pyuff's measured beam FRF 1: 13 poles
!> on one thread, 11 on two). `gram` and `spd_solve` pin their calls themselves; the pure
!> `spd_factor` and `spd_inverse` call ext's `cholesky_alone` and `cholesky_inverse_alone`,
!> which do.
module greenconv_ident_dense
    use, intrinsic :: iso_c_binding, only: c_int, c_double
    use greenconv_core_kinds, only: dp
    use greenconv_ext_lapack, only: lapack_serial_begin, lapack_serial_end
    implicit none
    private

    public :: gram, spd_factor, spd_solve, spd_inverse, identity

    interface
        !> C = alpha*A^T A + beta*C, one triangle of C (BLAS; trans = 'T': A is k x n).
        pure subroutine dsyrk(uplo, trans, n, k, alpha, a, lda, beta, c, ldc)
            import :: dp
            character(len=1), intent(in) :: uplo, trans
            integer, intent(in) :: n, k, lda, ldc
            real(dp), intent(in) :: alpha, beta
            real(dp), intent(in) :: a(lda, *)
            real(dp), intent(inout) :: c(ldc, *)
        end subroutine dsyrk

        !> y = alpha*op(A) x + beta*y (BLAS).
        pure subroutine dgemv(trans, m, n, alpha, a, lda, x, incx, beta, y, incy)
            import :: dp
            character(len=1), intent(in) :: trans
            integer, intent(in) :: m, n, lda, incx, incy
            real(dp), intent(in) :: alpha, beta
            real(dp), intent(in) :: a(lda, *), x(*)
            real(dp), intent(inout) :: y(*)
        end subroutine dgemv

        !> dpotrf ('U') of an n x n matrix, serially (greenconv_ext_lapack's
        !> `cholesky_alone`, reached by its binding label: pure as LAPACK's own routines are).
        pure subroutine cholesky_alone(n, a, info) bind(c, name='greenconv_ext_cholesky_alone')
            import :: c_int, c_double
            integer(c_int), value :: n
            real(c_double), intent(inout) :: a(n, n)
            integer(c_int), intent(out) :: info
        end subroutine cholesky_alone

        !> dpotri ('U') from cholesky_alone's factor, serially (greenconv_ext_lapack's
        !> `cholesky_inverse_alone`).
        pure subroutine cholesky_inverse_alone(n, a, info) bind(c, name='greenconv_ext_cholesky_inverse_alone')
            import :: c_int, c_double
            integer(c_int), value :: n
            real(c_double), intent(inout) :: a(n, n)
            integer(c_int), intent(out) :: info
        end subroutine cholesky_inverse_alone

        !> Solution of A X = B from dpotrf's factor (LAPACK).
        pure subroutine dpotrs(uplo, n, nrhs, a, lda, b, ldb, info)
            import :: dp
            character(len=1), intent(in) :: uplo
            integer, intent(in) :: n, nrhs, lda, ldb
            real(dp), intent(in) :: a(lda, *)
            real(dp), intent(inout) :: b(ldb, *)
            integer, intent(out) :: info
        end subroutine dpotrs
    end interface

contains

    !> scale*A^T A and scale*A^T b for a real m x n matrix A: the upper triangle of A^T A by
    !> BLAS's dsyrk, the lower triangle copied, A^T b by dgemv. With the system's OpenBLAS
    !> (one thread) dsyrk takes about half the time of the blocks of gfortran's matmul it
    !> replaced (16,386 x 202, the 50-mode bench fit: 41 against 74 ms per call); with the
    !> reference BLAS it took 2.6 times as long as those blocks.
    !> Both products are computed serially (`lapack_serial_begin`), whatever the threads.
    subroutine gram(a, scale, product, b, projection)
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

        integer :: m, n, j, threads

        m = size(a, 1)
        n = size(a, 2)
        if (n == 0) return
        if (m == 0) then
            product = 0.0_dp
            projection = 0.0_dp
            return
        end if
        call lapack_serial_begin(threads)
        call dsyrk('U', 'T', n, m, scale, a, m, 0.0_dp, product, n)
        call dgemv('T', m, n, scale, a, m, b, 1, 0.0_dp, projection, 1)
        call lapack_serial_end(threads)
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

        integer :: info, i

        ok = .true.
        if (size(a, 1) == 0) return
        call cholesky_alone(size(a, 1), a, info)
        ok = info == 0
        ! A NaN pivot fails the comparison (OpenBLAS's dpotrf returns info = 0 for it).
        if (ok) ok = all([(a(i, i) > 0.0_dp, i=1, size(a, 1))])
    end subroutine spd_factor

    !> Solution x of A x = b for a symmetric positive definite A by Cholesky (factor and solve
    !> serially, `lapack_serial_begin`).
    subroutine spd_solve(a, b, x, ok)
        !> The matrix A (n x n).
        real(dp), intent(in) :: a(:, :)
        !> Right-hand side b (n).
        real(dp), intent(in) :: b(:)
        !> Solution x (n); incomplete when not ok.
        real(dp), allocatable, intent(out) :: x(:)
        !> False when A is not positive definite.
        logical, intent(out) :: ok

        real(dp) :: factor(size(a, 1), size(a, 1))
        integer :: info, n, threads

        n = size(b)
        x = b
        factor = a
        call lapack_serial_begin(threads)
        call spd_factor(factor, ok)
        if (ok .and. n > 0) then
            call dpotrs('U', n, 1, factor, n, x, n, info)
            ok = info == 0
        end if
        call lapack_serial_end(threads)
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
        call cholesky_inverse_alone(n, a, info)
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
