!> A small unit-test harness in the pattern of test-drive: each module of tests returns
!> a list of named tests, each test reports a failure through an allocatable error, and
!> `check` compares values with explicit tolerances.
module testsuite_mod
    use, intrinsic :: iso_fortran_env, only: dp => real64
    implicit none
    private

    public :: test_error, unittest_type, new_unittest, check, note, run_testsuite, collect_interface, test_interface

    !> A failed check: what was compared and by how much it missed.
    type :: test_error
        !> Description of the failure.
        character(len=:), allocatable :: message
    end type test_error

    abstract interface
        !> One test: leaves `error` unallocated when it passes.
        subroutine test_interface(error)
            import :: test_error
            implicit none
            type(test_error), allocatable, intent(out) :: error
        end subroutine test_interface
    end interface

    !> A named test.
    type :: unittest_type
        !> Name printed in the report.
        character(len=:), allocatable :: name
        !> The test procedure.
        procedure(test_interface), pointer, nopass :: test => null()
    end type unittest_type

    abstract interface
        !> Collect the tests of one module.
        subroutine collect_interface(testsuite)
            import :: unittest_type
            implicit none
            type(unittest_type), allocatable, intent(out) :: testsuite(:)
        end subroutine collect_interface
    end interface

    !> Measured values a test reports, printed after its name (cleared before each test).
    character(len=:), allocatable :: notes

    !> Compare and record a failure: `check(error, condition, message)` or
    !> `check(error, actual, expected, message, thr=, rel=)`.
    interface check
        module procedure check_condition
        module procedure check_real
    end interface check

contains

    !> A named test.
    function new_unittest(name, test) result(unittest)
        character(len=*), intent(in) :: name
        procedure(test_interface) :: test
        type(unittest_type) :: unittest

        unittest%name = name
        unittest%test => test
    end function new_unittest

    !> Report a measured value with the test's result, e.g. `call note('u error', 8.1e-4_dp)`.
    subroutine note(label, value)
        character(len=*), intent(in) :: label
        real(dp), intent(in) :: value

        character(len=16) :: text

        write (text, '(es10.3)') value
        notes = notes//' ['//label//' = '//trim(adjustl(text))//']'
    end subroutine note

    !> Fail with `message` unless `condition` holds.
    subroutine check_condition(error, condition, message)
        type(test_error), allocatable, intent(out) :: error
        logical, intent(in) :: condition
        character(len=*), intent(in) :: message

        if (condition) return
        allocate (error)
        error%message = message
    end subroutine check_condition

    !> Fail unless |actual - expected| <= thr (absolute) or, with rel = .true.,
    !> |actual - expected| <= thr*|expected|. A NaN never passes.
    subroutine check_real(error, actual, expected, message, thr, rel)
        type(test_error), allocatable, intent(out) :: error
        real(dp), intent(in) :: actual, expected
        character(len=*), intent(in) :: message
        real(dp), intent(in) :: thr
        logical, intent(in), optional :: rel

        real(dp) :: bound
        character(len=160) :: detail
        logical :: relative

        relative = .false.
        if (present(rel)) relative = rel
        bound = thr
        if (relative) bound = thr*abs(expected)
        if (abs(actual - expected) <= bound) return
        write (detail, '(a,es23.15,a,es23.15,a,es9.2,a,es9.2)') ': got ', actual, ', expected ', expected, &
            ', |diff| ', abs(actual - expected), ' > ', bound
        allocate (error)
        error%message = message//trim(detail)
    end subroutine check_real

    !> Run the tests of one suite, print one line per test, and count the outcomes.
    subroutine run_testsuite(suite_name, collect, unit, n_passed, n_failed)
        character(len=*), intent(in) :: suite_name
        procedure(collect_interface) :: collect
        integer, intent(in) :: unit
        integer, intent(inout) :: n_passed, n_failed

        type(unittest_type), allocatable :: tests(:)
        type(test_error), allocatable :: error
        integer :: i

        call collect(tests)
        do i = 1, size(tests)
            notes = ''
            call tests(i)%test(error)
            if (allocated(error)) then
                n_failed = n_failed + 1
                write (unit, '(a)') '  FAIL  '//suite_name//' :: '//tests(i)%name//notes//': '//error%message
                deallocate (error)
            else
                n_passed = n_passed + 1
                write (unit, '(a)') '  pass  '//suite_name//' :: '//tests(i)%name//notes
            end if
        end do
    end subroutine run_testsuite

end module testsuite_mod
