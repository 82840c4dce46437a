!> Numbers as text for messages and summaries, and names in one case.
!>
!> Every function here returns a result whose length is a specification expression (the text
!> formatted into a fixed buffer first, its length the buffer's trimmed length), never a
!> deferred length: gfortran keeps the length of a deferred-length function result in a static
!> variable at each call site, which two threads running the same code would share.
!> Each text is formatted twice, once for its length; these texts are messages and summaries.
module greenconv_core_text
    use, intrinsic :: iso_fortran_env, only: int64
    use greenconv_core_kinds, only: dp
    implicit none
    private

    public :: int_text, real_text, sci_text, lower_text, exact_text, sci_digits, trimmed_real_text
    public :: quoted_list, quoted_list_length

    !> An integer (default or 64-bit) as text, without blanks.
    interface int_text
        module procedure default_int_text
        module procedure long_int_text
    end interface int_text

    !> Names for a message, trimmed and quoted, in their order: "'a', 'b' or 'c'"; all of
    !> them, or those a mask keeps (empty when none).
    interface quoted_list
        module procedure quoted_all
        module procedure quoted_kept
    end interface quoted_list

    !> Length of `quoted_list` of the same arguments.
    interface quoted_list_length
        module procedure quoted_all_length
        module procedure quoted_kept_length
    end interface quoted_list_length

    !> Length of the buffers the numbers are formatted into.
    integer, parameter :: buffer_length = 48

contains

    !> An integer's digits, left-justified and blank-padded.
    pure function int_buffer(i) result(buffer)
        !> The integer.
        integer(int64), intent(in) :: i
        !> Its digits.
        character(len=buffer_length) :: buffer

        write (buffer, '(i0)') i
    end function int_buffer

    !> `sci_digits`'s text, left-justified and blank-padded.
    pure function sci_buffer(x, digits) result(buffer)
        !> The real.
        real(dp), intent(in) :: x
        !> Digits after the decimal point (0 to 20).
        integer, intent(in) :: digits
        !> Its text.
        character(len=buffer_length) :: buffer

        character(len=24) :: form
        integer :: mark

        write (form, '(a,i0,a,i0,a)') '(es', digits + 9, '.', digits, 'e3)'
        write (buffer, form) x
        buffer = adjustl(buffer)
        mark = index(buffer, 'E')
        if (mark > 0 .and. mark + 2 <= len_trim(buffer)) then
            if (buffer(mark + 2:mark + 2) == '0') buffer = buffer(:mark + 1)//buffer(mark + 3:)
        end if
    end function sci_buffer

    !> `trimmed_real_text`'s text, left-justified and blank-padded: plain notation with
    !> digits(1) decimals when x is zero or span(1) <= |x| < span(2), else scientific with
    !> digits(2) digits after the point; the trailing zeros of the digits removed.
    pure function trimmed_buffer(x, span, digits) result(buffer)
        !> The real.
        real(dp), intent(in) :: x
        !> Range of magnitudes written plainly (zero aside), in the unit of x.
        real(dp), intent(in) :: span(2)
        !> Decimals of the plain notation, digits after the point of the scientific one.
        integer, intent(in) :: digits(2)
        !> Its text.
        character(len=buffer_length) :: buffer

        character(len=buffer_length) :: text
        character(len=12) :: form
        integer :: mark, last, n

        if (abs(x) < tiny(x) .or. (abs(x) >= span(1) .and. abs(x) < span(2))) then
            write (form, '(a,i0,a)') '(f0.', digits(1), ')'
            write (text, form) x
            text = adjustl(text)
        else
            text = sci_buffer(x, digits(2))
        end if
        if (text(1:1) == '.') text = '0'//text
        if (text(1:2) == '-.') text = '-0'//text(2:)
        n = len_trim(text)
        mark = scan(text(:n), 'E')
        if (mark == 0) mark = n + 1
        last = mark - 1
        do while (last > 2 .and. text(last:last) == '0' .and. text(last - 1:last - 1) /= '.')
            last = last - 1
        end do
        buffer = text(:last)//text(mark:n)
    end function trimmed_buffer

    !> The fewest significant digits (1 to 17) whose scientific text reads back to x.
    pure integer function exact_digits(x)
        !> The number.
        real(dp), intent(in) :: x

        character(len=buffer_length) :: buffer
        real(dp) :: back
        integer :: status

        do exact_digits = 1, 17
            buffer = sci_buffer(x, exact_digits - 1)
            read (buffer, *, iostat=status) back
            if (status == 0 .and. back == x) return
        end do
        exact_digits = 17
    end function exact_digits

    !> A default integer as text, without blanks.
    pure function default_int_text(i) result(text)
        !> The integer.
        integer, intent(in) :: i
        !> Its digits, with a sign when negative.
        character(len=len_trim(int_buffer(int(i, int64)))) :: text

        text = int_buffer(int(i, int64))
    end function default_int_text

    !> A 64-bit integer (a step count of a long run) as text, without blanks.
    pure function long_int_text(i) result(text)
        !> The integer.
        integer(int64), intent(in) :: i
        !> Its digits, with a sign when negative.
        character(len=len_trim(int_buffer(i))) :: text

        text = int_buffer(i)
    end function long_int_text

    !> A real with up to ten significant digits, without blanks and without the trailing
    !> zeros of its digits: plain from 0.1 to 1e7 (`0.443`, `10.0`, `600.556`), scientific
    !> otherwise (`-7.0E-03`, `1.5E+09`).
    pure function real_text(x) result(text)
        !> The real.
        real(dp), intent(in) :: x
        !> Its text.
        character(len=len_trim(trimmed_buffer(x, [0.1_dp, 1.0e7_dp], [9, 9]))) :: text

        text = trimmed_buffer(x, [0.1_dp, 1.0e7_dp], [9, 9])
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
        !> Its text.
        character(len=len_trim(trimmed_buffer(x, [low, high], [plain_digits, science_digits]))) :: text

        text = trimmed_buffer(x, [low, high], [plain_digits, science_digits])
    end function trimmed_real_text

    !> A real in short scientific notation (three significant digits), without blanks.
    pure function sci_text(x) result(text)
        !> The real.
        real(dp), intent(in) :: x
        !> Its text.
        character(len=len_trim(sci_buffer(x, 2))) :: text

        text = sci_buffer(x, 2)
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
        !> Its text.
        character(len=len_trim(sci_buffer(x, digits))) :: text

        text = sci_buffer(x, digits)
    end function sci_digits

    !> Text with the letters A-Z in lower case and trailing blanks removed.
    pure function lower_text(text) result(lower)
        !> The text.
        character(len=*), intent(in) :: text
        !> The same letters in lower case.
        character(len=len_trim(text)) :: lower

        integer :: i, code

        lower = text
        do i = 1, len(lower)
            code = iachar(lower(i:i))
            if (code >= iachar('A') .and. code <= iachar('Z')) lower(i:i) = achar(code + 32)
        end do
    end function lower_text

    !> A real as the shortest scientific text (1 to 17 significant digits) that reads back to
    !> the same double, without blanks: `1.E-02` for 0.01, `1.5E+00`. Non-finite values are
    !> written as Fortran writes them.
    pure function exact_text(x) result(text)
        !> The number.
        real(dp), intent(in) :: x
        !> Its text.
        character(len=len_trim(sci_buffer(x, exact_digits(x) - 1))) :: text

        text = sci_buffer(x, exact_digits(x) - 1)
    end function exact_text

    !> Length of `quoted_kept(names, keep)`: the trimmed names kept, each quoted, ", " between
    !> them and " or " before the last.
    pure integer function quoted_kept_length(names, keep)
        !> The names (blank-padded).
        character(len=*), intent(in) :: names(:)
        !> Which names to list.
        logical, intent(in) :: keep(size(names))

        integer :: n

        n = count(keep)
        quoted_kept_length = sum(len_trim(names) + 2, mask=keep) + 2*max(n - 2, 0) + merge(4, 0, n > 1)
    end function quoted_kept_length

    !> The names kept, trimmed and quoted, in their order: "'a', 'b' or 'c'" (empty when none).
    pure function quoted_kept(names, keep) result(text)
        !> The names (blank-padded).
        character(len=*), intent(in) :: names(:)
        !> Which names to list.
        logical, intent(in) :: keep(size(names))
        !> The list.
        character(len=quoted_kept_length(names, keep)) :: text

        integer :: i, k, n, at, width

        n = count(keep)
        k = 0
        at = 0
        do i = 1, size(names)
            if (.not. keep(i)) cycle
            k = k + 1
            if (k > 1 .and. k == n) then
                text(at + 1:at + 4) = ' or '
                at = at + 4
            else if (k > 1) then
                text(at + 1:at + 2) = ', '
                at = at + 2
            end if
            width = len_trim(names(i)) + 2
            text(at + 1:at + width) = "'"//trim(names(i))//"'"
            at = at + width
        end do
    end function quoted_kept

    !> Length of `quoted_all(names)`.
    pure integer function quoted_all_length(names)
        !> The names (blank-padded).
        character(len=*), intent(in) :: names(:)

        quoted_all_length = quoted_kept_length(names, spread(.true., 1, size(names)))
    end function quoted_all_length

    !> Every name, trimmed and quoted, in its order: "'a', 'b' or 'c'" (`quoted_kept` keeping
    !> them all).
    pure function quoted_all(names) result(text)
        !> The names (blank-padded).
        character(len=*), intent(in) :: names(:)
        !> The list.
        character(len=quoted_all_length(names)) :: text

        text = quoted_kept(names, spread(.true., 1, size(names)))
    end function quoted_all

end module greenconv_core_text
