!> Numbers as text for messages and summaries.
module text_mod
    use kinds_mod, only: dp
    implicit none
    private

    public :: int_text, real_text, sci_text

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

    !> A real with up to ten significant digits, without blanks.
    pure function real_text(x) result(text)
        !> The real.
        real(dp), intent(in) :: x
        character(len=:), allocatable :: text

        character(len=32) :: buffer

        write (buffer, '(g0.10)') x
        text = trim(adjustl(buffer))
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

end module text_mod
