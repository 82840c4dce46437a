!> Numbers as text for messages and summaries, and names in one case.
module text_mod
    use kinds_mod, only: dp
    implicit none
    private

    public :: int_text, real_text, sci_text, lower_text

contains

    !> An integer as text, without blanks.
    pure function int_text(i) result(text)
        !> The integer.
        integer, intent(in) :: i
        character(len=:), allocatable :: text

        character(len=16) :: buffer

        write (buffer, '(i0)') i
        text = trim(buffer)
    end function int_text

    !> A real with up to ten significant digits, without blanks and without the trailing
    !> zeros of its digits (`0.443`, `10.0`, `0.1E-4`).
    pure function real_text(x) result(text)
        !> The real.
        real(dp), intent(in) :: x
        character(len=:), allocatable :: text

        character(len=32) :: buffer
        integer :: mark, last

        write (buffer, '(g0.10)') x
        text = trim(adjustl(buffer))
        mark = scan(text, 'EeDd')
        if (mark == 0) mark = len(text) + 1
        if (index(text(:mark - 1), '.') == 0) return
        last = mark - 1
        do while (last > 1 .and. text(last:last) == '0' .and. text(max(last - 1, 1):max(last - 1, 1)) /= '.')
            last = last - 1
        end do
        text = text(:last)//text(mark:)
    end function real_text

    !> A real in short scientific notation (three significant digits), without blanks.
    pure function sci_text(x) result(text)
        !> The real.
        real(dp), intent(in) :: x
        character(len=:), allocatable :: text

        character(len=16) :: buffer

        write (buffer, '(es9.2)') x
        text = trim(adjustl(buffer))
    end function sci_text

    !> Text with the letters A-Z in lower case and trailing blanks removed.
    pure function lower_text(text) result(lower)
        !> The text.
        character(len=*), intent(in) :: text
        character(len=:), allocatable :: lower

        integer :: i, code

        lower = trim(text)
        do i = 1, len(lower)
            code = iachar(lower(i:i))
            if (code >= iachar('A') .and. code <= iachar('Z')) lower(i:i) = achar(code + 32)
        end do
    end function lower_text

end module text_mod
