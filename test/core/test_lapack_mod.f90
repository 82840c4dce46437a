!> The LAPACK front ends (greenconv_ext_lapack) at the edge of the double range: every bad
!> input must come back as an error with status 3 (`stat_numerical`) and a message, never as
!> a call that reaches LAPACK's XERBLA. greenconv does not replace XERBLA, so the reference
!> one would print "On entry to ... had an illegal value" and stop this program: a test that
!> reached it would end the run before the closing "N passed, N failed" line.
!>
!> The case the fuzz test found: a receptance file holding a value near 1.8e308 (the largest
!> double). Its impulse response overflows, and the least squares of the identification
!> were given Inf; DGELSD's inner scaling (DLASCL with the NaN norm of that input) then
!> called XERBLA. Now the input is refused before the call.
module test_lapack_mod
    use, intrinsic :: iso_fortran_env, only: dp => real64
    use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan, ieee_positive_inf, ieee_is_finite
    use testsuite_mod, only: test_error, unittest_type, new_unittest, check
    use greenconv_core_error, only: error_type, stat_numerical
    use greenconv_ext_lapack, only: least_squares, eigenvalues, solve_linear
    use greenconv_model_sdof, only: sdof_modes
    use greenconv_model_frf, only: frf_type, frf_from_modes
    use greenconv_ident_lsce, only: lsce_options, lsce_result, identify
    implicit none
    private

    public :: collect_lapack

    !> The largest double, about 1.8e308.
    real(dp), parameter :: big = huge(1.0_dp)

contains

    !> Tests of the LAPACK front ends.
    subroutine collect_lapack(testsuite)
        type(unittest_type), allocatable, intent(out) :: testsuite(:)

        testsuite = [new_unittest('receptance value 1.8e308: identify fails with status 3 (fuzz case)', &
                                  test_fuzz_receptance), &
                     new_unittest('NaN or Inf input: status 3 before any LAPACK call', test_non_finite), &
                     new_unittest('least squares near 1.8e308: solved, or status 3 when x overflows', &
                                  test_least_squares_range), &
                     new_unittest('eigenvalues and solve_linear near 1.8e308: status 3 on overflow', &
                                  test_other_range)]
    end subroutine collect_lapack

    !> An error with status 3 whose message names `routine`.
    subroutine expect_numerical(error, fault, routine, what)
        type(test_error), allocatable, intent(out) :: error
        type(error_type), allocatable, intent(in) :: fault
        character(len=*), intent(in) :: routine, what

        call check(error, allocated(fault), what//': an error')
        if (allocated(error)) return
        call check(error, fault%stat == stat_numerical .and. index(fault%message, routine) > 0, &
                   what//': status 3 naming '//routine//', got: '//fault%message)
    end subroutine expect_numerical

    !> The SDOF receptance of Tab. 1 with one line set to 1.8e308 (as the damaged file read):
    !> identify must stop with status 3 at the least squares, whose input overflowed.
    subroutine test_fuzz_receptance(error)
        type(test_error), allocatable, intent(out) :: error

        integer, parameter :: lines(3) = [1, 200, 1500]
        type(frf_type) :: frf
        type(lsce_options) :: options
        type(lsce_result) :: result
        type(error_type), allocatable :: fault
        integer :: i

        do i = 1, size(lines)
            frf = frf_from_modes(sdof_modes(1.0_dp, 1.0e6_dp, 0.02_dp), 1000.0_dp, 2001)
            frf%receptance(lines(i)) = cmplx(big, 0.0_dp, kind=dp)
            call identify(frf, options, result, fault)
            call expect_numerical(error, fault, 'dgelsd', 'G = 1.8e308 at one line')
            if (allocated(error)) return
        end do
    end subroutine test_fuzz_receptance

    !> NaN and Inf in A or b are refused, with the routine named.
    subroutine test_non_finite(error)
        type(test_error), allocatable, intent(out) :: error

        type(error_type), allocatable :: fault
        real(dp) :: a(2, 2), b(2), x(2), nan, inf
        complex(dp) :: w(2)

        nan = ieee_value(1.0_dp, ieee_quiet_nan)
        inf = ieee_value(1.0_dp, ieee_positive_inf)
        a = reshape([1.0_dp, 0.0_dp, 0.0_dp, 1.0_dp], [2, 2])
        b = [1.0_dp, nan]
        call least_squares(a, b, x, fault)
        call expect_numerical(error, fault, 'dgelsd', 'NaN in b')
        if (allocated(error)) return
        a(1, 2) = inf
        call least_squares(a, [1.0_dp, 1.0_dp], x, fault)
        call expect_numerical(error, fault, 'dgelsd', 'Inf in A')
        if (allocated(error)) return
        call eigenvalues(a, w, fault)
        call expect_numerical(error, fault, 'dgeev', 'Inf in A')
        if (allocated(error)) return
        call solve_linear(a, [1.0_dp, 1.0_dp], x, fault)
        call expect_numerical(error, fault, 'dgesv', 'Inf in A')
    end subroutine test_non_finite

    !> Finite inputs at the top of the range: DGELSD scales them into range itself, so a
    !> well-posed system is solved (x = 1), and one whose solution exceeds the range is an error.
    subroutine test_least_squares_range(error)
        type(test_error), allocatable, intent(out) :: error

        type(error_type), allocatable :: fault
        real(dp) :: x2(2), x1(1)

        call least_squares(reshape([big, 0.0_dp, 0.0_dp, 0.0_dp, big, 0.0_dp], [3, 2]), [big, big, 0.0_dp], x2, fault)
        call check(error, .not. allocated(fault), 'A = 1.8e308 on the diagonal (3 x 2), b = 1.8e308: solved')
        if (allocated(error)) return
        call check(error, maxval(abs(x2 - 1.0_dp)), 0.0_dp, 'x = 1', thr=1.0e-12_dp)
        if (allocated(error)) return
        call least_squares(reshape([1.0e-300_dp], [1, 1]), [big], x1, fault)
        call expect_numerical(error, fault, 'dgelsd', 'x = 1.8e308/1e-300')
    end subroutine test_least_squares_range

    !> Overflowing results of dgeev and dgesv are errors, not Inf returned.
    subroutine test_other_range(error)
        type(test_error), allocatable, intent(out) :: error

        type(error_type), allocatable :: fault
        complex(dp) :: w(2)
        real(dp) :: x(2)

        call eigenvalues(reshape([big, big, big, big], [2, 2]), w, fault)
        if (allocated(fault)) then
            call expect_numerical(error, fault, 'dgeev', 'eigenvalues 0 and 3.6e308')
        else
            call check(error, all(ieee_is_finite(w%re)) .and. all(ieee_is_finite(w%im)), &
                       'eigenvalues 0 and 3.6e308: an error or finite values')
        end if
        if (allocated(error)) return
        call solve_linear(reshape([1.0e-300_dp, 0.0_dp, 0.0_dp, 1.0_dp], [2, 2]), [big, 1.0_dp], x, fault)
        call expect_numerical(error, fault, 'dgesv', 'x = 1.8e308/1e-300')
    end subroutine test_other_range

end module test_lapack_mod
