!> Explicit interfaces to the LAPACK routines greenconv uses, and assumed-shape
!> front ends that copy their inputs, query the workspace and report failures
!> through an `error_type` (never `stop`).
!>
!> - dgelsd: minimum-norm least squares by the SVD (divide and conquer), so that a
!>   rank-deficient or ill-conditioned system gives a bounded answer; no normal equations.
!> - dgeev: eigenvalues of a general real matrix (balanced, then Hessenberg QR).
!> - dgesv: a square linear system by LU factorisation with partial pivoting.
!> - dgetrf, dgetrs: the same factorisation kept, then solved again for other right-hand sides
!>   (`lu_factor`, `lu_solve`: a Newton matrix that repeats from one iteration to the next).
!>
!> LAPACK reports a bad argument through XERBLA, whose reference version prints a line and
!> stops the program, and which belongs to the host program (it may have its own): greenconv
!> neither replaces it nor lets LAPACK reach it. Every argument is checked before each call
!> (`check_arguments`): dimensions, leading dimensions and the workspace sizes the query
!> returned; so are the inputs, which must be finite, because LAPACK's inner scaling (DLASCL,
!> called by DGELSD and DGEEV with the norm of the input) rejects a NaN or infinite norm
!> through XERBLA. A result that overflowed is reported rather than returned. Every failure
!> is an `error_type` with status `stat_numerical`.
!>
!> Threads: OpenBLAS's OpenMP build (the system's libblas/liblapack) threads a call made outside
!> a parallel region over `omp_get_max_threads()` threads, and its threaded sums are taken in
!> another order than its serial ones (last bits of an LU, a least-squares solution, the
!> eigenvalues, a Cholesky factor; 20 x 20 and up); inside a parallel region it runs serially.
!> dgelsd, dgeev, dgesv, dgetrf and dgetrs (the contact layer's LU) are called here between
!> `lapack_serial_begin` and `lapack_serial_end` (the calling thread's OpenMP thread count set
!> to 1), and so are the Cholesky factor and inverse of `cholesky_alone` and
!> `cholesky_inverse_alone`, so that every result of these front ends is that of one thread
!> whatever OMP_NUM_THREADS says, in builds with and without OpenMP (ext/thread_pin.c).
module greenconv_ext_lapack
    use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
    use, intrinsic :: iso_c_binding, only: c_int, c_double
    use greenconv_core_kinds, only: dp
    use greenconv_core_error, only: error_type, fatal_error, stat_numerical
    use greenconv_core_text, only: int_text
    implicit none
    private

    public :: least_squares, eigenvalues, solve_linear, lu_factor, lu_solve
    public :: lapack_serial_begin, lapack_serial_end
    public :: cholesky_alone, cholesky_inverse_alone

    interface
        !> Minimum-norm solution of min ||b - A x||_2 by the SVD of A (LAPACK).
        subroutine dgelsd(m, n, nrhs, a, lda, b, ldb, s, rcond, rank, work, lwork, iwork, info)
            import :: dp
            implicit none
            integer, intent(in) :: m, n, nrhs, lda, ldb, lwork
            real(dp), intent(inout) :: a(lda, *), b(ldb, *)
            real(dp), intent(out) :: s(*)
            real(dp), intent(in) :: rcond
            integer, intent(out) :: rank, info
            real(dp), intent(inout) :: work(*)
            integer, intent(inout) :: iwork(*)
        end subroutine dgelsd

        !> Eigenvalues (and optionally eigenvectors) of a general real matrix (LAPACK).
        subroutine dgeev(jobvl, jobvr, n, a, lda, wr, wi, vl, ldvl, vr, ldvr, work, lwork, info)
            import :: dp
            implicit none
            character(len=1), intent(in) :: jobvl, jobvr
            integer, intent(in) :: n, lda, ldvl, ldvr, lwork
            real(dp), intent(inout) :: a(lda, *)
            real(dp), intent(out) :: wr(*), wi(*)
            real(dp), intent(inout) :: vl(ldvl, *), vr(ldvr, *)
            real(dp), intent(inout) :: work(*)
            integer, intent(out) :: info
        end subroutine dgeev

        !> Solution of A X = B for a square A by LU factorisation with partial pivoting (LAPACK).
        subroutine dgesv(n, nrhs, a, lda, ipiv, b, ldb, info)
            import :: dp
            implicit none
            integer, intent(in) :: n, nrhs, lda, ldb
            real(dp), intent(inout) :: a(lda, *), b(ldb, *)
            integer, intent(out) :: ipiv(*)
            integer, intent(out) :: info
        end subroutine dgesv

        !> LU factorisation with partial pivoting of a general matrix, in place (LAPACK).
        subroutine dgetrf(m, n, a, lda, ipiv, info)
            import :: dp
            implicit none
            integer, intent(in) :: m, n, lda
            real(dp), intent(inout) :: a(lda, *)
            integer, intent(out) :: ipiv(*)
            integer, intent(out) :: info
        end subroutine dgetrf

        !> Solution of A X = B from dgetrf's factors of A (LAPACK).
        subroutine dgetrs(trans, n, nrhs, a, lda, ipiv, b, ldb, info)
            import :: dp
            implicit none
            character(len=1), intent(in) :: trans
            integer, intent(in) :: n, nrhs, lda, ldb
            real(dp), intent(in) :: a(lda, *)
            integer, intent(in) :: ipiv(*)
            real(dp), intent(inout) :: b(ldb, *)
            integer, intent(out) :: info
        end subroutine dgetrs

        !> Cholesky factor of a symmetric positive definite matrix, in place (LAPACK).
        subroutine dpotrf(uplo, n, a, lda, info)
            import :: dp
            implicit none
            character(len=1), intent(in) :: uplo
            integer, intent(in) :: n, lda
            real(dp), intent(inout) :: a(lda, *)
            integer, intent(out) :: info
        end subroutine dpotrf

        !> Inverse of A from dpotrf's factor, one triangle, in place (LAPACK).
        subroutine dpotri(uplo, n, a, lda, info)
            import :: dp
            implicit none
            character(len=1), intent(in) :: uplo
            integer, intent(in) :: n, lda
            real(dp), intent(inout) :: a(lda, *)
            integer, intent(out) :: info
        end subroutine dpotri
    end interface

contains

    !> Least-squares solution x of min ||b - A x||_2 (m >= 1 rows, n >= 1 unknowns) by dgelsd.
    !> Singular values below rcond*s_max are treated as zero (minimum-norm solution).
    subroutine least_squares(a, b, x, error, rcond, rank, singular_values)
        !> Matrix A (m x n); not modified.
        real(dp), intent(in) :: a(:, :)
        !> Right-hand side b (m).
        real(dp), intent(in) :: b(:)
        !> Solution x (n).
        real(dp), intent(out) :: x(:)
        !> Set on a size mismatch or when the SVD does not converge.
        type(error_type), allocatable, intent(out) :: error
        !> Relative threshold on the singular values; machine precision when absent.
        real(dp), intent(in), optional :: rcond
        !> Effective rank of A.
        integer, intent(out), optional :: rank
        !> Singular values of A, largest first (size min(m, n)).
        real(dp), intent(out), optional :: singular_values(:)

        real(dp), allocatable :: a_work(:, :), b_work(:, :), s(:), work(:)
        integer, allocatable :: iwork(:)
        real(dp) :: threshold, query(1)
        integer :: m, n, ldb, lwork, info, effective_rank, iquery(1), threads

        m = size(a, 1)
        n = size(a, 2)
        if (m < 1 .or. n < 1 .or. size(b) /= m .or. size(x) /= n) then
            call fatal_error(error, 'least_squares: inconsistent sizes of A, b and x', stat_numerical)
            return
        end if
        threshold = -1.0_dp
        if (present(rcond)) threshold = rcond
        ldb = max(m, n)
        call require_finite('dgelsd', 'input', [all(ieee_is_finite(a)), all(ieee_is_finite(b)), &
                                                ieee_is_finite(threshold)], error)
        if (allocated(error)) return
        allocate (a_work(m, n), b_work(ldb, 1), s(min(m, n)))
        a_work(:, :) = a
        b_work(:, 1) = 0.0_dp
        b_work(1:m, 1) = b
        call check_arguments('dgelsd', [m >= 1, n >= 1, size(a_work, 1) >= max(1, m), &
                                        size(b_work, 1) >= max(1, m, n)], error)
        if (allocated(error)) return
        call dgelsd(m, n, 1, a_work, m, b_work, ldb, s, threshold, effective_rank, query, -1, iquery, info)
        if (info /= 0) then
            call lapack_error(error, 'dgelsd (workspace query)', info)
            return
        end if
        call workspace_size('dgelsd', query(1), 1, lwork, error)
        if (allocated(error)) return
        call check_arguments('dgelsd', [iquery(1) >= 1], error)
        if (allocated(error)) return
        allocate (work(lwork), iwork(iquery(1)))
        call lapack_serial_begin(threads)
        call dgelsd(m, n, 1, a_work, m, b_work, ldb, s, threshold, effective_rank, work, lwork, iwork, info)
        call lapack_serial_end(threads)
        if (info /= 0) then
            call lapack_error(error, 'dgelsd', info)
            return
        end if
        call require_finite('dgelsd', 'result', [all(ieee_is_finite(b_work(1:n, 1)))], error)
        if (allocated(error)) return
        x(:) = b_work(1:n, 1)
        if (present(rank)) rank = effective_rank
        if (present(singular_values)) then
            singular_values(:) = 0.0_dp
            singular_values(1:min(size(singular_values), size(s))) = s(1:min(size(singular_values), size(s)))
        end if
    end subroutine least_squares

    !> Eigenvalues of a general real square matrix by dgeev (no eigenvectors).
    subroutine eigenvalues(a, w, error)
        !> Square matrix (n x n, n >= 1); not modified.
        real(dp), intent(in) :: a(:, :)
        !> Eigenvalues (n); complex pairs come as conjugates with exactly opposite imaginary parts.
        complex(dp), intent(out) :: w(:)
        !> Set on a size mismatch or when the QR algorithm does not converge.
        type(error_type), allocatable, intent(out) :: error

        real(dp), allocatable :: a_work(:, :), wr(:), wi(:), work(:)
        real(dp) :: query(1), dummy(1, 1)
        integer :: n, lwork, info, threads

        n = size(a, 1)
        if (n < 1 .or. size(a, 2) /= n .or. size(w) /= n) then
            call fatal_error(error, 'eigenvalues: expected a square matrix and n eigenvalues', stat_numerical)
            return
        end if
        call require_finite('dgeev', 'input', [all(ieee_is_finite(a))], error)
        if (allocated(error)) return
        allocate (a_work(n, n), wr(n), wi(n))
        a_work(:, :) = a
        ! no eigenvectors (jobvl = jobvr = 'N'): their leading dimensions need only be >= 1
        call check_arguments('dgeev', [n >= 1, size(a_work, 1) >= max(1, n), size(dummy, 1) >= 1], error)
        if (allocated(error)) return
        call dgeev('N', 'N', n, a_work, n, wr, wi, dummy, 1, dummy, 1, query, -1, info)
        if (info /= 0) then
            call lapack_error(error, 'dgeev (workspace query)', info)
            return
        end if
        ! documented minimum without eigenvectors: 3*n
        call workspace_size('dgeev', query(1), 3*n, lwork, error)
        if (allocated(error)) return
        allocate (work(lwork))
        call lapack_serial_begin(threads)
        call dgeev('N', 'N', n, a_work, n, wr, wi, dummy, 1, dummy, 1, work, lwork, info)
        call lapack_serial_end(threads)
        if (info /= 0) then
            call lapack_error(error, 'dgeev', info)
            return
        end if
        call require_finite('dgeev', 'result', [all(ieee_is_finite(wr)), all(ieee_is_finite(wi))], error)
        if (allocated(error)) return
        w(:) = cmplx(wr, wi, kind=dp)
    end subroutine eigenvalues

    !> Solution x of the square system A x = b by dgesv (LU with partial pivoting).
    subroutine solve_linear(a, b, x, error)
        !> Square matrix A (n x n, n >= 1); not modified.
        real(dp), intent(in) :: a(:, :)
        !> Right-hand side b (n).
        real(dp), intent(in) :: b(:)
        !> Solution x (n).
        real(dp), intent(out) :: x(:)
        !> Set on a size mismatch or when A is exactly singular (a zero pivot).
        type(error_type), allocatable, intent(out) :: error

        real(dp), allocatable :: a_work(:, :), b_work(:, :)
        integer, allocatable :: pivot(:)
        integer :: n, info, threads

        n = size(a, 1)
        if (n < 1 .or. size(a, 2) /= n .or. size(b) /= n .or. size(x) /= n) then
            call fatal_error(error, 'solve_linear: expected a square matrix and n-vectors b and x', stat_numerical)
            return
        end if
        call require_finite('dgesv', 'input', [all(ieee_is_finite(a)), all(ieee_is_finite(b))], error)
        if (allocated(error)) return
        allocate (a_work(n, n), b_work(n, 1), pivot(n))
        a_work(:, :) = a
        b_work(:, 1) = b
        call check_arguments('dgesv', [n >= 1, size(a_work, 1) >= max(1, n), size(b_work, 1) >= max(1, n)], error)
        if (allocated(error)) return
        call lapack_serial_begin(threads)
        call dgesv(n, 1, a_work, n, pivot, b_work, n, info)
        call lapack_serial_end(threads)
        if (info > 0) then
            call fatal_error(error, 'dgesv: singular matrix (zero pivot in column '//int_text(info)//')', &
                             stat_numerical)
            return
        else if (info < 0) then
            call lapack_error(error, 'dgesv', info)
            return
        end if
        call require_finite('dgesv', 'result', [all(ieee_is_finite(b_work))], error)
        if (allocated(error)) return
        x(:) = b_work(:, 1)
    end subroutine solve_linear

    !> The LU factors of a square A in place by dgetrf (partial pivoting), for `lu_solve`.
    subroutine lu_factor(a, pivot, error)
        !> On entry A (n x n, n >= 1); on return its factors L and U.
        real(dp), intent(inout) :: a(:, :)
        !> The row interchanges (n).
        integer, intent(out) :: pivot(:)
        !> Set on a size mismatch, a NaN or Inf in A, or when A is exactly singular.
        type(error_type), allocatable, intent(out) :: error

        integer :: n, info, threads

        n = size(a, 1)
        call check_arguments('dgetrf', [n >= 1, size(a, 2) == n, size(pivot) == n], error)
        if (allocated(error)) return
        call require_finite('dgetrf', 'input', [all(ieee_is_finite(a))], error)
        if (allocated(error)) return
        call lapack_serial_begin(threads)
        call dgetrf(n, n, a, n, pivot, info)
        call lapack_serial_end(threads)
        if (info > 0) then
            call fatal_error(error, 'dgetrf: singular matrix (zero pivot in column '//int_text(info)//')', &
                             stat_numerical)
        else if (info < 0) then
            call lapack_error(error, 'dgetrf', info)
        end if
    end subroutine lu_factor

    !> x = A^-1*b from `lu_factor`'s factors of A by dgetrs.
    subroutine lu_solve(factors, pivot, b, x, error)
        !> The factors of A (n x n) from `lu_factor`.
        real(dp), intent(in) :: factors(:, :)
        !> The row interchanges from `lu_factor` (n).
        integer, intent(in) :: pivot(:)
        !> Right-hand side b (n).
        real(dp), intent(in) :: b(:)
        !> Solution x (n).
        real(dp), intent(out) :: x(:)
        !> Set on a size mismatch or a result that overflowed.
        type(error_type), allocatable, intent(out) :: error

        real(dp), allocatable :: b_work(:, :)
        integer :: n, info, threads

        n = size(factors, 1)
        call check_arguments('dgetrs', [n >= 1, size(factors, 2) == n, size(pivot) == n, size(b) == n, &
                                        size(x) == n], error)
        if (allocated(error)) return
        b_work = reshape(b, [n, 1])
        call lapack_serial_begin(threads)
        call dgetrs('N', n, 1, factors, n, pivot, b_work, n, info)
        call lapack_serial_end(threads)
        if (info < 0) then
            call lapack_error(error, 'dgetrs', info)
            return
        end if
        call require_finite('dgetrs', 'result', [all(ieee_is_finite(b_work))], error)
        if (allocated(error)) return
        x(:) = b_work(:, 1)
    end subroutine lu_solve

    !> Make the BLAS and LAPACK calls that follow serial, without a parallel region, until
    !> `lapack_serial_end`. A threaded BLAS adds the parts of a sum in another order than one
    !> thread (a 441 x 441 LU, a 16,386 x 202 Gram matrix differ in their last bits), so the
    !> results would follow the thread count. ext/thread_pin.c finds the BLAS's thread setting
    !> at run time, in builds with and without OpenMP: OpenBLAS on OpenMP (or any OpenMP BLAS)
    !> gets the calling thread's OpenMP count set to 1, OpenBLAS on POSIX threads its global
    !> count; inside a host's parallel region (where OpenBLAS is serial already), with a serial
    !> BLAS or on one thread nothing changes. No second thread is woken: a region of two
    !> threads around every call of an identification (thousands) cost more than the fit itself
    !> on a loaded machine (see doc/identification.md, "Threads").
    subroutine lapack_serial_begin(threads)
        !> What `lapack_serial_end` restores (0: nothing was changed).
        integer, intent(out) :: threads

        interface
            integer(c_int) function serial_begin() bind(c, name='greenconv_ext_serial_begin')
                import :: c_int
            end function serial_begin
        end interface

        threads = int(serial_begin())
    end subroutine lapack_serial_begin

    !> Undo `lapack_serial_begin`: the thread count it changed restored.
    subroutine lapack_serial_end(threads)
        !> What `lapack_serial_begin` returned.
        integer, intent(in) :: threads

        interface
            subroutine serial_end(restore) bind(c, name='greenconv_ext_serial_end')
                import :: c_int
                integer(c_int), value :: restore
            end subroutine serial_end
        end interface

        if (threads /= 0) call serial_end(int(threads, c_int))
    end subroutine lapack_serial_end

    !> dpotrf ('U', in place) of an n x n matrix, called serially (`lapack_serial_begin`). Bound to C so
    !> that the identification's pure Cholesky routines (ident/dense.f90) can reach it through
    !> an interface that declares it pure, as they declare LAPACK's own routines: the region of
    !> threads changes nothing but which thread makes the call.
    subroutine cholesky_alone(n, a, info) bind(c, name='greenconv_ext_cholesky_alone')
        !> Order of the matrix (n >= 1).
        integer(c_int), value :: n
        !> In: the symmetric positive definite matrix (upper triangle read); out: its factor U.
        real(c_double), intent(inout) :: a(n, n)
        !> dpotrf's info: 0, or k > 0 when the leading minor of order k is not positive definite.
        integer(c_int), intent(out) :: info

        integer :: threads

        call lapack_serial_begin(threads)
        call dpotrf('U', n, a, n, info)
        call lapack_serial_end(threads)
    end subroutine cholesky_alone

    !> dpotri ('U', in place): the inverse of A from its factor U by `cholesky_alone`, upper
    !> triangle, called serially (`lapack_serial_begin`) (bound to C as `cholesky_alone`).
    subroutine cholesky_inverse_alone(n, a, info) bind(c, name='greenconv_ext_cholesky_inverse_alone')
        !> Order of the matrix (n >= 1).
        integer(c_int), value :: n
        !> In: the factor U (upper triangle); out: inv(A), upper triangle.
        real(c_double), intent(inout) :: a(n, n)
        !> dpotri's info: 0, or k > 0 when U(k, k) is zero.
        integer(c_int), intent(out) :: info

        integer :: threads

        call lapack_serial_begin(threads)
        call dpotri('U', n, a, n, info)
        call lapack_serial_end(threads)
    end subroutine cholesky_inverse_alone

    !> An error (status `stat_numerical`) unless every array checked is finite.
    pure subroutine require_finite(routine, what, finite, error)
        character(len=*), intent(in) :: routine, what
        logical, intent(in) :: finite(:)
        type(error_type), allocatable, intent(inout) :: error

        if (all(finite)) return
        call fatal_error(error, routine//': the '//what//' holds NaN or Inf (values beyond the double range, ' &
                         //'about 1.8e308, or an overflow in the data given to it)', stat_numerical)
    end subroutine require_finite

    !> An error (status `stat_numerical`) unless every argument condition holds: checked before
    !> a call, so that LAPACK never reaches XERBLA. A failure here is a bug of greenconv's.
    pure subroutine check_arguments(routine, conditions, error)
        character(len=*), intent(in) :: routine
        logical, intent(in) :: conditions(:)
        type(error_type), allocatable, intent(inout) :: error

        integer :: i

        do i = 1, size(conditions)
            if (conditions(i)) cycle
            call fatal_error(error, routine//': argument check '//int_text(i)//' failed before the call (sizes of ' &
                             //'the arrays given to LAPACK); please report this as a greenconv bug', stat_numerical)
            return
        end do
    end subroutine check_arguments

    !> The workspace length from a LAPACK workspace query (`optimal`, returned as a real), checked
    !> to be a whole number of at least `minimum` that fits a default integer.
    pure subroutine workspace_size(routine, optimal, minimum, lwork, error)
        character(len=*), intent(in) :: routine
        real(dp), intent(in) :: optimal
        integer, intent(in) :: minimum
        integer, intent(out) :: lwork
        type(error_type), allocatable, intent(inout) :: error

        lwork = 0
        if (.not. (optimal >= real(max(1, minimum), dp) .and. optimal <= real(huge(lwork), dp))) then
            call fatal_error(error, routine//': the workspace query gave an unusable size; the problem is too ' &
                             //'large for one LAPACK call (use fewer frequency lines or a smaller model order)', &
                             stat_numerical)
            return
        end if
        lwork = int(optimal)
    end subroutine workspace_size

    !> An error naming the routine and its info code.
    pure subroutine lapack_error(error, routine, info)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), intent(in) :: routine
        integer, intent(in) :: info

        character(len=16) :: text

        write (text, '(i0)') info
        if (info < 0) then
            call fatal_error(error, routine//': illegal value of argument '//trim(text(2:)) &
                             //'; please report this as a greenconv bug', stat_numerical)
        else
            call fatal_error(error, routine//': failed to converge (info = '//trim(text)//')', stat_numerical)
        end if
    end subroutine lapack_error

end module greenconv_ext_lapack
