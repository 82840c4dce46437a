!> Text of names: `quoted_list` against a list built independently (each kept name appended
!> to a deferred-length text, the last joined by " or "), for every choice of names kept, and
!> without a mask (every name).
module test_text_mod
    use testsuite_mod, only: test_error, unittest_type, new_unittest, check
    use greenconv_core_text, only: quoted_list, quoted_list_length, int_text
    implicit none
    private

    public :: collect_text

contains

    !> Tests of greenconv_core_text's lists of names.
    subroutine collect_text(testsuite)
        !> The suite's tests.
        type(unittest_type), allocatable, intent(out) :: testsuite(:)

        testsuite = [new_unittest('quoted_list is the names kept, quoted, with '', '' and '' or ''', test_quoted_list), &
                     new_unittest('quoted_list of names alone lists them all', test_quoted_all)]
    end subroutine collect_text

    subroutine test_quoted_list(error)
        type(test_error), allocatable, intent(out) :: error

        character(len=8), parameter :: names(5) = [character(len=8) :: 'direct', 'fft', 'a', 'longname', 'x y']
        logical :: keep(size(names))
        integer :: mask, i

        do mask = 0, 2**size(names) - 1
            keep = [(btest(mask, i - 1), i=1, size(names))]
            call check(error, quoted_list(names, keep) == expected(names, keep) .and. &
                       len(quoted_list(names, keep)) == len(expected(names, keep)) .and. &
                       quoted_list_length(names, keep) == len(expected(names, keep)), &
                       'mask '//int_text(mask)//': "'//quoted_list(names, keep)//'", expected "' &
                       //expected(names, keep)//'"')
            if (allocated(error)) return
        end do
    end subroutine test_quoted_list

    !> Without a mask every name is listed: against the independent list keeping all of 1 to 5
    !> names, and against two lists written out.
    subroutine test_quoted_all(error)
        type(test_error), allocatable, intent(out) :: error

        character(len=8), parameter :: names(5) = [character(len=8) :: 'direct', 'fft', 'a', 'longname', 'x y']
        logical :: keep(size(names))
        integer :: n

        keep = .true.
        do n = 1, size(names)
            call check(error, quoted_list(names(:n)) == expected(names(:n), keep(:n)) .and. &
                       len(quoted_list(names(:n))) == len(expected(names(:n), keep(:n))) .and. &
                       quoted_list_length(names(:n)) == len(expected(names(:n), keep(:n))), &
                       int_text(n)//' names: "'//quoted_list(names(:n))//'", expected "' &
                       //expected(names(:n), keep(:n))//'"')
            if (allocated(error)) return
        end do
        call check(error, quoted_list(names(2:2)) == "'fft'" .and. len(quoted_list(names(2:2))) == 5, &
                   'one name: "'//quoted_list(names(2:2))//'"')
        if (allocated(error)) return
        call check(error, quoted_list(names(1:3)) == "'direct', 'fft' or 'a'" .and. &
                   len(quoted_list(names(1:3))) == 22, 'three names: "'//quoted_list(names(1:3))//'"')
    end subroutine test_quoted_all

    !> The list built name by name: the kept names quoted, joined by ", ", the last comma
    !> replaced by " or ".
    function expected(names, keep) result(text)
        character(len=*), intent(in) :: names(:)
        logical, intent(in) :: keep(:)
        character(len=:), allocatable :: text

        integer :: i, last_comma

        text = ''
        do i = 1, size(names)
            if (keep(i)) text = text//", '"//trim(names(i))//"'"
        end do
        if (len(text) > 0) text = text(3:)
        last_comma = index(text, ", '", back=.true.)
        if (last_comma > 0) text = text(:last_comma - 1)//' or '//text(last_comma + 2:)
    end function expected

end module test_text_mod
