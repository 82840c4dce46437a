!> Mutations of a text file for the driver's fuzz test: each takes the whole file as one
!> string (lines separated by new-line characters) and returns a damaged copy and the name
!> of the damage. The damage is what a user's file suffers: a byte flipped, a line lost or
!> repeated, a file cut short, a number replaced by a word, by a huge or a tiny value, by
!> NaN or Inf, its sign changed, a delimiter lost, a garbage line inserted.
module mutation_mod
    use greenconv_core_kinds, only: dp
    use greenconv_core_random, only: random_stream
    implicit none
    private

    public :: mutate, mutation_names, n_mutations

    !> Number of kinds of mutation.
    integer, parameter :: n_mutations = 12
    !> The name of each kind, in the order `mutate` numbers them.
    character(len=*), parameter :: mutation_names(n_mutations) = [character(len=16) :: &
        'flip byte', 'delete line', 'cut file', 'repeat line', 'swap lines', 'number to word', &
        'huge number', 'tiny number', 'negate number', 'NaN or Inf', 'drop delimiter', 'garbage line']

    !> New-line character.
    character(len=1), parameter :: nl = new_line('a')
    !> Words put where a number was.
    character(len=12), parameter :: words(8) = [character(len=12) :: 'abc', '.true.', "'text'", '1,2', &
                                                '', '3*', '1.0.0', '0x1F']
    !> Values a number is swapped for that overflow or nearly overflow.
    character(len=24), parameter :: huge_values(7) = [character(len=24) :: '1e308', '1.0e999', '-1.0e300', &
                                                      '9999999999', '2147483647', '-2147483648', &
                                                      '1.7976931348623157e308']
    !> Values a number is swapped for that underflow or vanish.
    character(len=12), parameter :: tiny_values(6) = [character(len=12) :: '1e-308', '4.9e-324', '0', &
                                                      '-0.0', '1e-320', '0.0']
    !> Values that are no finite number.
    character(len=12), parameter :: non_finite(6) = [character(len=12) :: 'NaN', 'Inf', '-Inf', &
                                                     '+Infinity', 'nan', '-NaN']
    !> Garbage lines.
    character(len=24), parameter :: garbage(5) = [character(len=24) :: '&', '/', 'x = ', '&scene /', &
                                                  '1 2 3 4 5 6 7 8']

contains

    !> A damaged copy of `text` and the kind of damage (1..n_mutations).
    subroutine mutate(text, stream, mutated, kind)
        !> The file's text, lines separated by new-line characters.
        character(len=*), intent(in) :: text
        !> The random stream choosing the damage (advanced).
        type(random_stream), intent(inout) :: stream
        !> The damaged text.
        character(len=:), allocatable, intent(out) :: mutated
        !> Which damage was done: an index into `mutation_names`.
        integer, intent(out) :: kind

        kind = pick(stream, n_mutations)
        select case (kind)
        case (1)
            mutated = flip_byte(text, stream)
        case (2)
            mutated = edit_line(text, pick(stream, count_lines(text)), '', .false.)
        case (3)
            mutated = text(1:pick(stream, len(text)) - 1)
        case (4)
            mutated = repeat_line(text, pick(stream, count_lines(text)))
        case (5)
            mutated = swap_lines(text, pick(stream, count_lines(text)), pick(stream, count_lines(text)))
        case (6)
            mutated = replace_number(text, stream, words(pick(stream, size(words))))
        case (7)
            mutated = replace_number(text, stream, huge_values(pick(stream, size(huge_values))))
        case (8)
            mutated = replace_number(text, stream, tiny_values(pick(stream, size(tiny_values))))
        case (9)
            mutated = replace_number(text, stream, '-')
        case (10)
            mutated = replace_number(text, stream, non_finite(pick(stream, size(non_finite))))
        case (11)
            mutated = drop_delimiter(text, stream)
        case default
            mutated = edit_line(text, pick(stream, count_lines(text) + 1), &
                                trim(garbage(pick(stream, size(garbage)))), .true.)
        end select
    end subroutine mutate

    !> A uniform integer in 1..n (1 when n < 1).
    integer function pick(stream, n)
        type(random_stream), intent(inout) :: stream
        integer, intent(in) :: n

        pick = 1
        if (n > 1) pick = min(n, 1 + int(stream%uniform()*n))
    end function pick

    !> One byte replaced by a random byte, printable three times in four.
    function flip_byte(text, stream) result(mutated)
        character(len=*), intent(in) :: text
        type(random_stream), intent(inout) :: stream
        character(len=:), allocatable :: mutated

        integer :: position, code

        mutated = text
        if (len(text) == 0) return
        position = pick(stream, len(text))
        if (stream%uniform() < 0.75_dp) then
            code = 31 + pick(stream, 95)
        else
            code = pick(stream, 256) - 1
        end if
        mutated(position:position) = achar(code)
    end function flip_byte

    !> Number of lines (a last line without a new line counts).
    pure integer function count_lines(text)
        character(len=*), intent(in) :: text

        integer :: i

        count_lines = 0
        do i = 1, len(text)
            if (text(i:i) == nl) count_lines = count_lines + 1
        end do
        if (len(text) > 0) then
            if (text(len(text):len(text)) /= nl) count_lines = count_lines + 1
        end if
    end function count_lines

    !> Start and end (the new line included) of line k, or an empty range past the end.
    pure subroutine line_bounds(text, k, first, last)
        character(len=*), intent(in) :: text
        integer, intent(in) :: k
        integer, intent(out) :: first, last

        integer :: line, i

        first = len(text) + 1
        last = len(text)
        line = 1
        do i = 1, len(text)
            if (line == k .and. first > len(text)) first = i
            if (text(i:i) == nl) then
                if (line == k) then
                    last = i
                    return
                end if
                line = line + 1
            end if
        end do
    end subroutine line_bounds

    !> Line k deleted and `insert` put there (with `before`, line k is kept after it).
    pure function edit_line(text, k, insert, before) result(mutated)
        character(len=*), intent(in) :: text, insert
        integer, intent(in) :: k
        logical, intent(in) :: before
        character(len=:), allocatable :: mutated

        integer :: first, last

        call line_bounds(text, k, first, last)
        if (before) then
            mutated = text(1:first - 1)//insert//nl//text(first:)
        else if (len(insert) > 0) then
            mutated = text(1:first - 1)//insert//nl//text(last + 1:)
        else
            mutated = text(1:first - 1)//text(last + 1:)
        end if
    end function edit_line

    !> Line k written twice.
    pure function repeat_line(text, k) result(mutated)
        character(len=*), intent(in) :: text
        integer, intent(in) :: k
        character(len=:), allocatable :: mutated

        integer :: first, last

        call line_bounds(text, k, first, last)
        mutated = text(1:last)//text(first:last)//text(last + 1:)
    end function repeat_line

    !> Lines j and k exchanged.
    pure function swap_lines(text, j, k) result(mutated)
        character(len=*), intent(in) :: text
        integer, intent(in) :: j, k
        character(len=:), allocatable :: mutated

        integer :: first_a, last_a, first_b, last_b

        if (j == k) then
            mutated = text
            return
        end if
        call line_bounds(text, min(j, k), first_a, last_a)
        call line_bounds(text, max(j, k), first_b, last_b)
        mutated = text(1:first_a - 1)//text(first_b:last_b)//text(last_a + 1:first_b - 1) &
                  //text(first_a:last_a)//text(last_b + 1:)
    end function swap_lines

    !> One number of the text (chosen at random) replaced by `value`; `value` = '-' changes
    !> its sign instead.
    function replace_number(text, stream, value) result(mutated)
        character(len=*), intent(in) :: text, value
        type(random_stream), intent(inout) :: stream
        character(len=:), allocatable :: mutated

        integer :: n, first, last, target

        n = count_numbers(text)
        mutated = text
        if (n == 0) return
        target = pick(stream, n)
        call number_bounds(text, target, first, last)
        if (value == '-') then
            if (text(first:first) == '-') then
                mutated = text(1:first - 1)//text(first + 1:)
            else
                mutated = text(1:first - 1)//'-'//text(first:)
            end if
        else
            mutated = text(1:first - 1)//trim(value)//text(last + 1:)
        end if
    end function replace_number

    !> Number of numeric tokens: a digit run, with its sign, point and exponent, that does
    !> not continue a name.
    pure integer function count_numbers(text)
        character(len=*), intent(in) :: text

        integer :: first, last

        count_numbers = 0
        last = 0
        do
            call next_number(text, last + 1, first, last)
            if (first == 0) exit
            count_numbers = count_numbers + 1
        end do
    end function count_numbers

    !> Bounds of the k-th numeric token.
    pure subroutine number_bounds(text, k, first, last)
        character(len=*), intent(in) :: text
        integer, intent(in) :: k
        integer, intent(out) :: first, last

        integer :: i

        first = 0
        last = 0
        do i = 1, k
            call next_number(text, last + 1, first, last)
            if (first == 0) return
        end do
    end subroutine number_bounds

    !> The first numeric token at or after `start` (first = 0 when there is none).
    pure subroutine next_number(text, start, first, last)
        character(len=*), intent(in) :: text
        integer, intent(in) :: start
        integer, intent(out) :: first, last

        integer :: i

        first = 0
        last = len(text)
        do i = start, len(text)
            if (.not. is_digit(text(i:i))) cycle
            if (i > 1) then
                if (is_name_char(text(i - 1:i - 1))) cycle
            end if
            first = i
            if (i > 1) then
                if (scan(text(i - 1:i - 1), '-+.') == 1) first = i - 1
            end if
            last = i
            do while (last < len(text))
                if (scan(text(last + 1:last + 1), '0123456789.eEdD+-') /= 1) exit
                last = last + 1
            end do
            return
        end do
    end subroutine next_number

    !> A decimal digit.
    elemental logical function is_digit(c)
        character(len=1), intent(in) :: c

        is_digit = c >= '0' .and. c <= '9'
    end function is_digit

    !> A character that may continue a Fortran name.
    elemental logical function is_name_char(c)
        character(len=1), intent(in) :: c

        is_name_char = (c >= 'a' .and. c <= 'z') .or. (c >= 'A' .and. c <= 'Z') .or. c == '_' .or. is_digit(c)
    end function is_name_char

    !> One delimiter (&, /, =, a quote or a comma) removed.
    function drop_delimiter(text, stream) result(mutated)
        character(len=*), intent(in) :: text
        type(random_stream), intent(inout) :: stream
        character(len=:), allocatable :: mutated

        integer :: i, n, target

        mutated = text
        n = 0
        do i = 1, len(text)
            if (scan(text(i:i), '&/=''",') == 1) n = n + 1
        end do
        if (n == 0) return
        target = pick(stream, n)
        n = 0
        do i = 1, len(text)
            if (scan(text(i:i), '&/=''",') /= 1) cycle
            n = n + 1
            if (n == target) then
                mutated = text(1:i - 1)//text(i + 1:)
                return
            end if
        end do
    end function drop_delimiter

end module mutation_mod
