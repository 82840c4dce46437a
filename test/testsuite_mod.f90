!> A small unit-test harness in the pattern of test-drive: each module of tests returns
!> a list of named tests, each test reports a failure through an allocatable error, and
!> `check` compares values with explicit tolerances. `run_selected` runs every suite, one
!> suite or one test of a suite, as the command line asks (`fpm test -- SUITE [TEST]`).
module testsuite_mod
    use, intrinsic :: iso_fortran_env, only: dp => real64, error_unit
    implicit none
    private

    public :: test_error, unittest_type, new_unittest, check, note, run_testsuite, collect_interface, test_interface
    public :: testsuite_type, new_testsuite, run_selected

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

    !> A named suite: the procedure that collects its tests.
    type :: testsuite_type
        !> Name given on the command line and printed in the report.
        character(len=:), allocatable :: name
        !> Collects the suite's tests.
        procedure(collect_interface), pointer, nopass :: collect => null()
    end type testsuite_type

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

    !> A named suite.
    function new_testsuite(name, collect) result(suite)
        character(len=*), intent(in) :: name
        procedure(collect_interface) :: collect
        type(testsuite_type) :: suite

        suite%name = name
        suite%collect => collect
    end function new_testsuite

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

    !> Run the tests of one suite (or only the test named `test_name`), print one line per
    !> test, and count the outcomes. `found` is false, and nothing runs, when the suite has no
    !> test of that name.
    subroutine run_testsuite(suite_name, collect, unit, n_passed, n_failed, test_name, found)
        character(len=*), intent(in) :: suite_name
        procedure(collect_interface) :: collect
        integer, intent(in) :: unit
        integer, intent(inout) :: n_passed, n_failed
        character(len=*), intent(in), optional :: test_name
        logical, intent(out), optional :: found

        type(unittest_type), allocatable :: tests(:)
        type(test_error), allocatable :: error
        integer :: i

        call collect(tests)
        if (present(test_name)) then
            if (present(found)) found = any([(tests(i)%name == test_name, i=1, size(tests))])
        else if (present(found)) then
            found = .true.
        end if
        do i = 1, size(tests)
            if (present(test_name)) then
                if (tests(i)%name /= test_name) cycle
            end if
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

    !> Run what the command line names: no argument, every suite in order; `SUITE`, that
    !> suite; `SUITE TEST`, that one test (its full name, quoted). Prints one line per test on
    !> `unit`. `valid` is false, and nothing runs, when a name is unknown or there are more
    !> than two arguments; the message then lists the valid names on standard error.
    subroutine run_selected(suites, unit, n_passed, n_failed, valid)
        !> Every suite, in the order they run.
        type(testsuite_type), intent(in) :: suites(:)
        !> Unit of the report.
        integer, intent(in) :: unit
        !> Numbers of tests passed and failed, increased.
        integer, intent(inout) :: n_passed, n_failed
        !> The command line named existing suites and tests.
        logical, intent(out) :: valid

        character(len=:), allocatable :: suite_name, test_name
        type(unittest_type), allocatable :: tests(:)
        integer :: i, k

        valid = .true.
        if (command_argument_count() == 0) then
            do i = 1, size(suites)
                call run_testsuite(suites(i)%name, suites(i)%collect, unit, n_passed, n_failed)
            end do
            return
        end if
        valid = .false.
        if (command_argument_count() > 2) then
            write (error_unit, '(a)') 'greenconv-tests: expected at most two arguments, SUITE [TEST] ' &
                //'(quote a test name that has spaces), e.g. fpm test -- contact'
            return
        end if
        suite_name = argument(1)
        k = 0
        do i = 1, size(suites)
            if (suites(i)%name == suite_name) k = i
        end do
        if (k == 0) then
            write (error_unit, '(a)') 'greenconv-tests: no suite named "'//suite_name//'"; the suites are:'
            write (error_unit, '(4x,a)') (suites(i)%name, i=1, size(suites))
            return
        end if
        if (command_argument_count() == 1) then
            call run_testsuite(suites(k)%name, suites(k)%collect, unit, n_passed, n_failed)
            valid = .true.
            return
        end if
        test_name = argument(2)
        call run_testsuite(suites(k)%name, suites(k)%collect, unit, n_passed, n_failed, test_name, valid)
        if (valid) return
        call suites(k)%collect(tests)
        write (error_unit, '(a)') 'greenconv-tests: suite "'//suite_name//'" has no test named "'//test_name &
            //'"; its tests are (quote the name):'
        write (error_unit, '(4x,a)') (tests(i)%name, i=1, size(tests))
    end subroutine run_selected

    !> Command-line argument i.
    function argument(i) result(value)
        integer, intent(in) :: i
        character(len=:), allocatable :: value

        integer :: length

        call get_command_argument(i, length=length)
        allocate (character(len=length) :: value)
        if (length > 0) call get_command_argument(i, value)
    end function argument

end module testsuite_mod
