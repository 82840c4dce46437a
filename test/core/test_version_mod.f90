!> The version: the library's text equals the `version = "..."` line of fpm.toml (read here, from
!> the project folder `fpm test` runs in), has the form major.minor.patch, and the Fortran 77
!> door GCVERS gives the same text. The C door is checked by test/c/version.c, the driver's
!> `--version` by tools/check_version.sh (both in `make test`).
module test_version_mod
    use testsuite_mod, only: test_error, unittest_type, new_unittest, check
    use greenconv, only: greenconv_version
    use greenconv_legacy, only: gcvers
    implicit none
    private

    public :: collect_version

contains

    !> Tests of greenconv_version and GCVERS.
    subroutine collect_version(testsuite)
        !> The suite's tests.
        type(unittest_type), allocatable, intent(out) :: testsuite(:)

        testsuite = [new_unittest('the version is fpm.toml''s', test_fpm_toml), &
                     new_unittest('the version is major.minor.patch', test_form), &
                     new_unittest('GCVERS gives the same text, blank-padded or cut', test_legacy)]
    end subroutine collect_version

    subroutine test_fpm_toml(error)
        type(test_error), allocatable, intent(out) :: error

        character(len=:), allocatable :: expected

        call manifest_version(expected)
        call check(error, len(expected) > 0, 'fpm.toml has a line version = "..."')
        if (allocated(error)) return
        call check(error, greenconv_version() == expected, &
                   'greenconv_version() is "'//greenconv_version()//'", fpm.toml says "'//expected//'"')
    end subroutine test_fpm_toml

    subroutine test_form(error)
        type(test_error), allocatable, intent(out) :: error

        character(len=:), allocatable :: version
        integer :: i, dots
        logical :: digits_between

        version = greenconv_version()
        dots = 0
        digits_between = len(version) > 0
        do i = 1, len(version)
            if (version(i:i) == '.') then
                dots = dots + 1
                ! a dot neither first, last nor next to another
                if (i == 1 .or. i == len(version)) digits_between = .false.
                if (i > 1) digits_between = digits_between .and. version(i - 1:i - 1) /= '.'
            else if (verify(version(i:i), '0123456789') /= 0) then
                digits_between = .false.
            end if
        end do
        call check(error, dots == 2 .and. digits_between, 'the version "'//version//'" is three numbers and two dots')
    end subroutine test_form

    subroutine test_legacy(error)
        type(test_error), allocatable, intent(out) :: error

        character(len=32) :: text
        character(len=3) :: short
        character(len=:), allocatable :: version

        version = greenconv_version()
        text = repeat('#', len(text))
        call gcvers(text)
        call check(error, text == version, 'GCVERS(TEXT*32) = "'//trim(text)//'"')
        if (allocated(error)) return
        call gcvers(short)
        call check(error, short == version(1:min(3, len(version))), &
                   'GCVERS(TEXT*3) = "'//short//'", the first 3 characters')
    end subroutine test_legacy

    !> The value of the first line `version = "..."` of fpm.toml, or "" when there is none.
    subroutine manifest_version(version)
        character(len=:), allocatable, intent(out) :: version

        character(len=512) :: line
        integer :: unit, status, first, last

        version = ''
        open (newunit=unit, file='fpm.toml', status='old', action='read', iostat=status)
        if (status /= 0) return
        do
            read (unit, '(a)', iostat=status) line
            if (status /= 0) exit
            if (index(line, 'version') /= 1) cycle
            if (verify(line(8:index(line, '=') - 1), ' ') /= 0) cycle
            first = index(line, '"')
            last = index(line, '"', back=.true.)
            if (first > 0 .and. last > first) version = line(first + 1:last - 1)
            exit
        end do
        close (unit)
    end subroutine manifest_version

end module test_version_mod
