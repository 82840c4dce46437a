!> The exact double-to-text conversion (greenconv_core_real_text): every number written reads
!> back with Fortran's list-directed `read` as the same double, bit for bit.
!>
!> Numbers are written in rows of `row_length` by `real_rows_text` and each row is read back
!> by one list-directed read, so that 2e6 random numbers stay within a few seconds in the
!> debug build.
module test_realtext_mod
    use, intrinsic :: iso_fortran_env, only: dp => real64, int64
    use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_positive_inf, ieee_negative_inf, ieee_quiet_nan, &
                                             ieee_is_nan
    use testsuite_mod, only: test_error, unittest_type, new_unittest, check, note
    use greenconv_core_random, only: random_stream
    use greenconv_core_real_text, only: real_field, real_text, real_rows_text, rows_text_length
    implicit none
    private

    public :: collect_realtext

    !> Numbers per row of the read-back checks.
    integer, parameter :: row_length = 1000
    !> Random bit patterns checked.
    integer, parameter :: n_random = 2000000

contains

    !> Tests of the exact text of doubles.
    subroutine collect_realtext(testsuite)
        type(unittest_type), allocatable, intent(out) :: testsuite(:)

        testsuite = [new_unittest('real text: 2e6 random finite bit patterns read back exactly', test_random), &
                     new_unittest('real text: subnormals read back exactly', test_subnormals), &
                     new_unittest('real text: powers of ten 1e-308..1e308 and neighbours', test_powers_of_ten), &
                     new_unittest('real text: every power of two and its neighbours', test_powers_of_two), &
                     new_unittest('real text: +-0, huge, tiny, and decimal rounding boundaries', test_extremes), &
                     new_unittest('real text: layout, infinities and NaN', test_layout), &
                     new_unittest('real text: rows of a table, one line each', test_rows)]
    end subroutine collect_realtext

    !> Count the numbers of `values` whose text does not read back to the same bits; `checked`
    !> is increased by size(values).
    subroutine read_back(values, failures, checked, first_failure)
        real(dp), intent(in) :: values(:)
        integer, intent(inout) :: failures
        integer(int64), intent(inout) :: checked
        character(len=real_field), intent(inout) :: first_failure

        character(len=:), allocatable :: text
        real(dp) :: back(row_length)
        integer :: start, n, length, stat, i

        allocate (character(len=rows_text_length(1, row_length)) :: text)
        do start = 1, size(values), row_length
            n = min(row_length, size(values) - start + 1)
            call real_rows_text(reshape(values(start:start + n - 1), [1, n]), text, length)
            read (text(1:length - 1), *, iostat=stat) back(1:n)
            if (stat /= 0) then
                failures = failures + n
                first_failure = text(1:real_field)
                cycle
            end if
            do i = 1, n
                if (transfer(back(i), 0_int64) /= transfer(values(start + i - 1), 0_int64)) then
                    if (failures == 0) first_failure = real_text(values(start + i - 1))
                    failures = failures + 1
                end if
            end do
        end do
        checked = checked + size(values)
    end subroutine read_back

    !> Check that all values round-trip and note how many were checked.
    subroutine expect_exact(error, values, what)
        type(test_error), allocatable, intent(out) :: error
        real(dp), intent(in) :: values(:)
        character(len=*), intent(in) :: what

        integer :: failures
        integer(int64) :: checked
        character(len=real_field) :: first

        failures = 0
        checked = 0
        first = ''
        call read_back(values, failures, checked, first)
        call note('numbers read back', real(checked, dp))
        call check(error, failures == 0, what//': numbers that do not read back exactly, first '//first)
    end subroutine expect_exact

    subroutine test_random(error)
        type(test_error), allocatable, intent(out) :: error

        type(random_stream) :: stream
        real(dp), allocatable :: values(:)
        integer(int64) :: bits, high, low, checked
        integer :: failures, i, block
        character(len=real_field) :: first

        stream = random_stream(16)
        allocate (values(100000))
        failures = 0
        checked = 0
        first = ''
        do block = 1, n_random/size(values)
            i = 0
            do while (i < size(values))
                high = int(stream%uniform()*4294967296.0_dp, int64)
                low = int(stream%uniform()*4294967296.0_dp, int64)
                bits = ior(shiftl(high, 32), low)
                if (iand(shiftr(bits, 52), 2047_int64) == 2047_int64) cycle
                i = i + 1
                values(i) = transfer(bits, 1.0_dp)
            end do
            call read_back(values, failures, checked, first)
        end do
        call note('numbers read back', real(checked, dp))
        call check(error, failures == 0, 'random doubles that do not read back exactly, first '//first)
    end subroutine test_random

    subroutine test_subnormals(error)
        type(test_error), allocatable, intent(out) :: error

        type(random_stream) :: stream
        real(dp) :: values(20000)
        integer(int64) :: bits
        integer :: i

        stream = random_stream(17)
        do i = 1, 52
            values(i) = transfer(shiftl(1_int64, i - 1), 1.0_dp)
            values(52 + i) = transfer(shiftl(1_int64, i) - 1_int64, 1.0_dp)
        end do
        do i = 105, size(values)
            bits = int(stream%uniform()*4503599627370496.0_dp, int64)
            if (mod(i, 2) == 0) bits = int(stream%uniform()*65536.0_dp, int64) + 1
            values(i) = transfer(bits, 1.0_dp)
            if (mod(i, 3) == 0) values(i) = -values(i)
        end do
        call expect_exact(error, values, 'subnormals')
    end subroutine test_subnormals

    subroutine test_powers_of_ten(error)
        type(test_error), allocatable, intent(out) :: error

        real(dp) :: values(6*617 + 2)
        character(len=12) :: text
        integer :: e, n

        n = 0
        do e = -308, 308
            write (text, '(a,i0)') '1e', e
            n = n + 1
            read (text, *) values(n)
            values(n + 1) = nearest(values(n), 1.0_dp)
            values(n + 2) = nearest(values(n), -1.0_dp)
            values(n + 3) = -values(n)
            values(n + 4) = 9.999999999999999_dp*values(n)
            values(n + 5) = 5.0_dp*values(n)
            n = n + 5
        end do
        values(n + 1) = 1.0e-323_dp
        values(n + 2) = 1.0e23_dp
        call expect_exact(error, values, 'powers of ten')
    end subroutine test_powers_of_ten

    subroutine test_powers_of_two(error)
        type(test_error), allocatable, intent(out) :: error

        real(dp) :: values(3*2098)
        integer :: e, n

        n = 0
        do e = -1074, 1023
            n = n + 1
            values(n) = 2.0_dp**e
            values(n + 1) = nearest(values(n), 1.0_dp)
            values(n + 2) = nearest(values(n), -1.0_dp)
            n = n + 2
        end do
        call expect_exact(error, values, 'powers of two')
    end subroutine test_powers_of_two

    subroutine test_extremes(error)
        type(test_error), allocatable, intent(out) :: error

        real(dp), allocatable :: values(:)
        integer :: i

        values = [0.0_dp, -0.0_dp, huge(1.0_dp), -huge(1.0_dp), nearest(huge(1.0_dp), -1.0_dp), tiny(1.0_dp), &
                  nearest(tiny(1.0_dp), -1.0_dp), nearest(tiny(1.0_dp), 1.0_dp), 0.1_dp, 0.2_dp, 0.3_dp, &
                  1.0_dp/3.0_dp, 2.0_dp/3.0_dp, 1.0_dp - epsilon(1.0_dp), 1.0_dp + epsilon(1.0_dp), &
                  9007199254740993.0_dp, 9007199254740991.0_dp, 1.0e16_dp, 1.0e17_dp, 99999999999999999.0_dp, &
                  5.0e-324_dp, 2.2250738585072011e-308_dp, 1.7976931348623157e308_dp, 0.5_dp, 0.05_dp, 0.005_dp, &
                  123456789012345678.0_dp, 1.2345678901234567e-5_dp, 4.35_dp, 0.15_dp, 2.675_dp]
        ! Halfway cases of 17 digits: x = (D + 1/2)*10^j exactly representable, then its neighbours.
        values = [values, [(nearest(values(i), 1.0_dp), nearest(values(i), -1.0_dp), i=3, size(values))], &
                  [(real(10000000000000000_int64 + 2*i + 1, dp)/2.0_dp, i=1, 200)]]
        call expect_exact(error, values, 'extremes and rounding boundaries')
    end subroutine test_extremes

    subroutine test_layout(error)
        type(test_error), allocatable, intent(out) :: error

        real(dp) :: back
        character(len=real_field) :: text

        call check(error, real_text(1.0e-4_dp) == '  1.0000000000000000E-004', 'layout of 1e-4: '//real_text(1.0e-4_dp))
        if (allocated(error)) return
        call check(error, real_text(-2.5_dp) == ' -2.5000000000000000E+000', 'layout of -2.5: '//real_text(-2.5_dp))
        if (allocated(error)) return
        call check(error, real_text(0.0_dp) == '  0.0000000000000000E+000', 'layout of 0: '//real_text(0.0_dp))
        if (allocated(error)) return
        call check(error, real_text(-0.0_dp) == ' -0.0000000000000000E+000', 'layout of -0: '//real_text(-0.0_dp))
        if (allocated(error)) return
        call check(error, real_text(1.0e-300_dp) == '  1.0000000000000000E-300', 'layout of 1e-300')
        if (allocated(error)) return
        call check(error, adjustl(real_text(ieee_value(1.0_dp, ieee_positive_inf))) == 'Infinity' &
                   .and. adjustl(real_text(ieee_value(1.0_dp, ieee_negative_inf))) == '-Infinity' &
                   .and. adjustl(real_text(ieee_value(1.0_dp, ieee_quiet_nan))) == 'NaN', 'infinities and NaN')
        if (allocated(error)) return
        text = real_text(ieee_value(1.0_dp, ieee_quiet_nan))
        read (text, *) back
        call check(error, ieee_is_nan(back), 'NaN reads back as NaN')
    end subroutine test_layout

    subroutine test_rows(error)
        type(test_error), allocatable, intent(out) :: error

        real(dp) :: table(3, 2), back(2)
        character(len=:), allocatable :: text
        integer :: length, i, stat

        table = reshape([1.0_dp, 2.0_dp, 3.0_dp, -0.1_dp, 1.0e300_dp, 7.0e-310_dp], [3, 2])
        allocate (character(len=rows_text_length(3, 2)) :: text)
        call real_rows_text(table, text, length)
        call check(error, length == 3*(2*real_field + 1) .and. text(length:length) == achar(10) &
                   .and. text(2*real_field + 1:2*real_field + 1) == achar(10), 'three lines of two fields')
        if (allocated(error)) return
        do i = 1, 3
            read (text((i - 1)*(2*real_field + 1) + 1:i*(2*real_field + 1) - 1), *, iostat=stat) back
            call check(error, stat == 0 .and. all(transfer(back, 0_int64, 2) == transfer(table(i, :), 0_int64, 2)), &
                       'row read back')
            if (allocated(error)) return
        end do
        call real_rows_text(table, text(1:10), length)
        call check(error, length == 0, 'a buffer too short is refused with length 0')
    end subroutine test_rows

end module test_realtext_mod
