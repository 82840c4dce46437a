!> A small unit-test harness in the pattern of test-drive: each module of tests returns
!> a list of named tests, each test reports a failure through an allocatable error, and
!> `check` compares values with explicit tolerances. The suites sit in test/<layer>/, one
!> folder and one test program per layer of the library; `run_layer` runs a layer's suites,
!> one suite or one test of a suite, as the command line asks (`fpm test -- SUITE [TEST]`
!> reaches every layer's program, and the one that holds SUITE runs it).
module testsuite_mod
    use, intrinsic :: iso_fortran_env, only: dp => real64, error_unit, output_unit
    use suite_index_mod, only: suite_index, index_layer, index_name
    implicit none
    private

    public :: test_error, unittest_type, new_unittest, check, note, run_testsuite, collect_interface, test_interface
    public :: testsuite_type, new_testsuite, run_selected, run_layer

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

    !> The program of one layer's folder test/<layer>/: check that the folder, the layer's
    !> suites and the index of every suite (greenconv_test_support's suite_index_mod) agree,
    !> then run what the command line asks. No argument: every suite of the layer, ending
    !> with `<layer>: N passed, N failed`. `SUITE [TEST]`: run by the layer that holds SUITE,
    !> ending with `N passed, N failed`; the other layers' programs stay silent. A suite that
    !> no layer holds is reported by the first layer's program (status 2). Stops with status 1
    !> when a test failed or the folder and the index disagree.
    subroutine run_layer(layer, suites)
        !> The layer: the folder's name under test/.
        character(len=*), intent(in) :: layer
        !> The layer's suites, in the order they run.
        type(testsuite_type), intent(in) :: suites(:)

        integer :: n_passed, n_failed, disagreements, i
        logical :: valid

        call check_layer_folder(layer, suites, disagreements)
        n_passed = 0
        n_failed = disagreements
        if (command_argument_count() == 0) then
            call run_selected(suites, output_unit, n_passed, n_failed, valid)
            write (output_unit, '(a,i0,a,i0,a)') layer//': ', n_passed, ' passed, ', n_failed, ' failed'
        else if (any([(suites(i)%name == argument(1), i=1, size(suites))])) then
            call run_selected(suites, output_unit, n_passed, n_failed, valid)
            if (.not. valid) stop 2, quiet=.true.
            write (output_unit, '(i0,a,i0,a)') n_passed, ' passed, ', n_failed, ' failed'
        else if (any([(index_name(i) == argument(1), i=1, size(suite_index))])) then
            continue
        else if (layer == index_layer(1)) then
            write (error_unit, '(a)') 'greenconv-tests: no suite named "'//argument(1)//'"; the suites are:'
            write (error_unit, '(4x,a)') (index_layer(i)//' '//index_name(i), i=1, size(suite_index))
            stop 2, quiet=.true.
        end if
        if (n_failed > 0) stop 1, quiet=.true.
    end subroutine run_layer

    !> Compare a layer's suites with its folder and the index: each suite is in the index under
    !> this layer and has its module file test/<layer>/test_<name>_mod.f90, and the index names
    !> no suite of this layer that the program does not run. Prints a line per disagreement.
    subroutine check_layer_folder(layer, suites, disagreements)
        character(len=*), intent(in) :: layer
        type(testsuite_type), intent(in) :: suites(:)
        integer, intent(out) :: disagreements

        character(len=:), allocatable :: file
        integer :: i, k
        logical :: exists

        disagreements = 0
        do i = 1, size(suites)
            file = 'test/'//layer//'/test_'//suites(i)%name//'_mod.f90'
            inquire (file=file, exist=exists)
            if (.not. exists) call disagree('suite "'//suites(i)%name//'" runs in layer "'//layer//'" but '// &
                                            file//' does not exist: move its file there')
            if (.not. any([(index_layer(k) == layer .and. index_name(k) == suites(i)%name, &
                            k=1, size(suite_index))])) &
                call disagree('suite "'//suites(i)%name//'" runs in layer "'//layer//'" but the index '// &
                              '(test/support/src/suite_index_mod.f90) does not list it there')
        end do
        do k = 1, size(suite_index)
            if (index_layer(k) /= layer) cycle
            if (.not. any([(suites(i)%name == index_name(k), i=1, size(suites))])) &
                call disagree('the index lists suite "'//index_name(k)//'" in layer "'//layer// &
                              '" but test/'//layer//'/main.f90 does not run it')
        end do

    contains

        subroutine disagree(message)
            character(len=*), intent(in) :: message
            disagreements = disagreements + 1
            write (error_unit, '(a)') 'greenconv-tests-'//layer//': '//message
        end subroutine disagree
    end subroutine check_layer_folder

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
