!> Numbers as text for messages and summaries, and names in one case.
module greenconv_core_text
    use, intrinsic :: iso_fortran_env, only: int64
    use greenconv_core_kinds, only: dp
    implicit none
    private

    public :: int_text, real_text, sci_text, lower_text, exact_text, sci_digits, trimmed_real_text

    !> An integer (default or 64-bit) as text, without blanks.
    interface int_text
        module procedure default_int_text
        module procedure long_int_text
    end interface int_text

contains

    !> A default integer as text, without blanks.
    pure function default_int_text(i) result(text)
        !> The integer.
        integer, intent(in) :: i
        character(len=:), allocatable :: text

        text = long_int_text(int(i, int64))
    end function default_int_text

    !> A 64-bit integer (a step count of a long run) as text, without blanks.
    pure function long_int_text(i) result(text)
        !> The integer.
        integer(int64), intent(in) :: i
        character(len=:), allocatable :: text

        character(len=24) :: buffer

        write (buffer, '(i0)') i
        text = trim(buffer)
    end function long_int_text

    !> A real with up to ten significant digits, without blanks and without the trailing
    !> zeros of its digits: plain from 0.1 to 1e7 (`0.443`, `10.0`, `600.556`), scientific
    !> otherwise (`-7.0E-03`, `1.5E+09`).
    pure function real_text(x) result(text)
        !> The real.
        real(dp), intent(in) :: x
        character(len=:), allocatable :: text

        text = trimmed_real_text(x, 0.1_dp, 1.0e7_dp, 9, 9)
    end function real_text

    !> A real without blanks, its digits without trailing zeros (one kept after the point):
    !> in plain notation with `plain_digits` decimals when it is zero or low <= |x| < high
    !> (`10.0`, `0.02`), else in scientific notation with `science_digits` digits after the
    !> point (`1.5E+09`). Non-finite values are written as Fortran writes them.
    pure function trimmed_real_text(x, low, high, plain_digits, science_digits) result(text)
        !> The real.
        real(dp), intent(in) :: x
        !> Smallest magnitude written plainly (zero aside), in the unit of x.
        real(dp), intent(in) :: low
        !> Magnitude from which on x is written in scientific notation, in the unit of x.
        real(dp), intent(in) :: high
        !> Decimals of the plain notation before the zeros are removed (0 to 20).
        integer, intent(in) :: plain_digits
        !> Digits after the point of the scientific notation before the zeros are removed.
        integer, intent(in) :: science_digits
        character(len=:), allocatable :: text

        character(len=32) :: buffer
        character(len=12) :: form
        integer :: mark, last

        if (abs(x) < tiny(x) .or. (abs(x) >= low .and. abs(x) < high)) then
            write (form, '(a,i0,a)') '(f0.', plain_digits, ')'
            write (buffer, form) x
            text = trim(adjustl(buffer))
        else
            text = sci_digits(x, science_digits)
        end if
        if (text(1:1) == '.') text = '0'//text
        if (text(1:2) == '-.') text = '-0'//text(2:)
        mark = scan(text, 'E')
        if (mark == 0) mark = len(text) + 1
        last = mark - 1
        do while (text(last:last) == '0' .and. text(last - 1:last - 1) /= '.')
            last = last - 1
        end do
        text = text(:last)//text(mark:)
    end function trimmed_real_text

    !> A real in short scientific notation (three significant digits), without blanks.
    pure function sci_text(x) result(text)
        !> The real.
        real(dp), intent(in) :: x
        character(len=:), allocatable :: text

        text = sci_digits(x, 2)
    end function sci_text

    !> A real in scientific notation with `digits` digits after the point, without blanks,
    !> its exponent of two digits or three when it needs them: `1.50E+09`, `1.00E-300`
    !> (Fortran's `ESw.d` drops the `E` of a three-digit exponent: `1.00-300`). Non-finite
    !> values are written as Fortran writes them.
    pure function sci_digits(x, digits) result(text)
        !> The real.
        real(dp), intent(in) :: x
        !> Digits after the decimal point (0 to 20).
        integer, intent(in) :: digits
        character(len=:), allocatable :: text

        character(len=40) :: buffer
        character(len=24) :: form
        integer :: mark

        write (form, '(a,i0,a,i0,a)') '(es', digits + 9, '.', digits, 'e3)'
        write (buffer, form) x
        text = trim(adjustl(buffer))
        mark = index(text, 'E')
        if (mark > 0 .and. mark + 2 <= len(text)) then
            if (text(mark + 2:mark + 2) == '0') text = text(:mark + 1)//text(mark + 3:)
        end if
    end function sci_digits

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

    !> A real as the shortest scientific text (1 to 17 significant digits) that reads back to
    !> the same double, without blanks: `1.E-02` for 0.01, `1.5E+00`. Non-finite values are
    !> written as Fortran writes them.
    function exact_text(x) result(text)
        !> The number.
        real(dp), intent(in) :: x
        character(len=:), allocatable :: text

        real(dp) :: back
        integer :: digits, status

        do digits = 1, 17
            text = sci_digits(x, digits - 1)
            read (text, *, iostat=status) back
            if (status == 0 .and. back == x) exit
        end do
    end function exact_text

end module greenconv_core_text
