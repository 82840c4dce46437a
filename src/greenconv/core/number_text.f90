!> Recognising numbers written as text, before reading them: what a column file or a
!> namelist value may hold. Used to tell "not a number" from "a number that is not finite"
!> or "a number too large", so that each gets its own message.
module greenconv_core_number_text
    use, intrinsic :: iso_fortran_env, only: int64
    use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
    use greenconv_core_kinds, only: dp
    use greenconv_core_text, only: lower_text, trimmed_real_text
    implicit none
    private

    public :: is_number, is_nan_or_inf, is_integer, read_real, read_integer, compact_real

contains

    !> Whether a token is a decimal number: optional sign, digits with at most one point,
    !> optional exponent (e, E, d, D) with optional sign and digits.
    pure logical function is_number(token)
        !> The token, without blanks.
        character(len=*), intent(in) :: token

        integer :: i, n_digits, n_points, exponent_at

        is_number = .false.
        n_digits = 0
        n_points = 0
        exponent_at = 0
        do i = 1, len(token)
            select case (token(i:i))
            case ('0':'9')
                n_digits = n_digits + 1
            case ('.')
                if (exponent_at > 0) return
                n_points = n_points + 1
            case ('+', '-')
                if (i /= 1 .and. i /= exponent_at + 1) return
            case ('e', 'E', 'd', 'D')
                if (exponent_at > 0 .or. n_digits == 0) return
                exponent_at = i
            case default
                return
            end select
        end do
        if (n_points > 1 .or. n_digits == 0) return
        if (exponent_at > 0) then
            if (verify(token(exponent_at + 1:), '+-') == 0) return
            if (scan(token(exponent_at + 1:), '0123456789') == 0) return
        end if
        is_number = .true.
    end function is_number

    !> Whether a token spells NaN or an infinity, with optional sign, in any case
    !> (`NaN`, `nan(0x1)`, `Inf`, `+Infinity`, `-inf`).
    pure logical function is_nan_or_inf(token)
        !> The token, without blanks.
        character(len=*), intent(in) :: token

        character(len=:), allocatable :: lower
        integer :: start

        lower = lower_text(token)
        start = 1
        if (len(lower) > 0) then
            if (lower(1:1) == '+' .or. lower(1:1) == '-') start = 2
        end if
        is_nan_or_inf = lower(start:) == 'nan' .or. lower(start:) == 'inf' .or. lower(start:) == 'infinity' &
                        .or. index(lower(start:), 'nan(') == 1
    end function is_nan_or_inf

    !> Whether a token is an integer: optional sign and digits only.
    pure logical function is_integer(token)
        !> The token, without blanks.
        character(len=*), intent(in) :: token

        integer :: start

        start = 1
        if (len(token) > 0) then
            if (token(1:1) == '+' .or. token(1:1) == '-') start = 2
        end if
        is_integer = len(token) >= start .and. verify(token(start:), '0123456789') == 0
    end function is_integer

    !> Read a token that `is_number` accepts as a real; ok is false when it overflows double
    !> precision (e.g. 1e999).
    subroutine read_real(token, value, ok)
        !> The token.
        character(len=*), intent(in) :: token
        !> The value (0 when not ok).
        real(dp), intent(out) :: value
        !> Whether the token is a finite double-precision number.
        logical, intent(out) :: ok

        integer :: stat

        value = 0.0_dp
        read (token, *, iostat=stat) value
        ok = stat == 0 .and. ieee_is_finite(value)
        if (.not. ok) value = 0.0_dp
    end subroutine read_real

    !> Read a token that `is_integer` accepts; ok is false when it lies outside the default
    !> integer range.
    subroutine read_integer(token, value, ok)
        !> The token.
        character(len=*), intent(in) :: token
        !> The value (0 when not ok).
        integer, intent(out) :: value
        !> Whether the token fits a default integer.
        logical, intent(out) :: ok

        integer(int64) :: wide
        integer :: stat

        value = 0
        ok = .false.
        read (token, *, iostat=stat) wide
        if (stat /= 0) return
        if (abs(wide) > huge(value)) return
        value = int(wide)
        ok = .true.
    end subroutine read_integer

    !> A real as short text for messages: up to six significant digits, without trailing
    !> zeros, in plain notation from 1e-3 to 1e6 (`0.02`, `-1.5`, `2000`) and scientific
    !> notation otherwise (`-1.0E+06`, `1.0E-04`).
    pure function compact_real(x) result(text)
        !> The real.
        real(dp), intent(in) :: x
        character(len=len(trimmed_real_text(x, 1.0e-3_dp, 1.0e6_dp, 6, 5))) :: text

        text = trimmed_real_text(x, 1.0e-3_dp, 1.0e6_dp, 6, 5)
    end function compact_real

end module greenconv_core_number_text
