!> The record layer of the universal-file reader (greenconv_io_uff): a file's lines, the
!> datasets between its `-1` lines, and the fixed-width integer and real fields of a record,
!> each read with one message naming the file, the line, the dataset and record, what was
!> expected and what was found (status 2).
module greenconv_io_uff_records
    use greenconv_core_kinds, only: dp
    use greenconv_core_error, only: error_type, fatal_error
    use greenconv_core_text, only: int_text
    use greenconv_core_sorting, only: heap_sort
    use greenconv_core_number_text, only: is_number, is_nan_or_inf, is_integer, read_real, read_integer
    use greenconv_io_columns, only: read_line_list, text_line
    implicit none
    private

    public :: text_line, dataset_extent, load_lines, find_datasets, record_prefix
    public :: columns, span, quoted, number_words, integer_field, real_field, parse_real
    public :: repeated_labels, locate_label, quick_integer, quick_real

    !> Extent of one dataset in the file's lines.
    type :: dataset_extent
        !> Dataset number.
        integer :: number = 0
        !> Lines of the opening and closing `-1`.
        integer :: first = 0, last = 0
    end type dataset_extent

contains

    !> Read every line of a file (`read_line_list`: a UTF-8 byte-order mark at its start and
    !> a trailing carriage return of each line removed).
    subroutine load_lines(path, lines, error)
        !> File to read.
        character(len=*), intent(in) :: path
        !> Its lines, in order.
        type(text_line), allocatable, intent(out) :: lines(:)
        !> Set (status 2) when the file cannot be opened, is empty or has a line longer than `max_line_length`.
        type(error_type), allocatable, intent(out) :: error

        integer :: i, n

        call read_line_list(path, 'universal file', '; check the file name and that it is readable', lines, error)
        if (allocated(error)) return
        if (size(lines) == 0) then
            call fatal_error(error, path//':1: universal file: expected datasets between lines "    -1", ' &
                             //'found an empty file')
            return
        end if
        do i = 1, size(lines)
            n = len(lines(i)%text)
            if (n == 0) cycle
            if (lines(i)%text(n:n) == achar(13)) lines(i)%text = lines(i)%text(:n - 1)
        end do
    end subroutine load_lines

    !> Whether a line is a dataset delimiter: `-1` ending within columns 1-6, nothing else.
    pure logical function is_delimiter(line)
        character(len=*), intent(in) :: line

        is_delimiter = len_trim(line) <= 6 .and. trim(adjustl(line)) == '-1'
    end function is_delimiter

    !> Locate every dataset: its number and the lines of its opening and closing `-1`.
    subroutine find_datasets(path, lines, sets, error)
        !> File the lines come from (for messages).
        character(len=*), intent(in) :: path
        !> The file's lines (`load_lines`).
        type(text_line), intent(in) :: lines(:)
        !> Every dataset, in file order.
        type(dataset_extent), allocatable, intent(out) :: sets(:)
        !> Set (status 2) on a line outside a dataset, a missing or binary dataset number, or a dataset
        !> without its closing `-1`.
        type(error_type), allocatable, intent(out) :: error

        type(dataset_extent), allocatable :: found(:)
        character(len=:), allocatable :: token, hint
        integer :: i, j, n, number
        logical :: ok

        allocate (found(count([(is_delimiter(lines(i)%text), i=1, size(lines))])/2 + 1))
        n = 0
        i = 1
        do while (i <= size(lines))
            if (len_trim(lines(i)%text) == 0) then
                i = i + 1
                cycle
            end if
            if (.not. is_delimiter(lines(i)%text)) then
                hint = ''
                if (n > 0) hint = '; is the -1 line that ends the dataset '//int_text(found(n)%number) &
                                  //' started at line '//int_text(found(n)%first)//' missing?'
                call fatal_error(error, path//':'//int_text(i)//': universal file: expected a line "    -1" ' &
                                 //'that starts a dataset, found "'//trim(lines(i)%text)//'"'//hint)
                return
            end if
            if (i == size(lines)) then
                call fatal_error(error, path//':'//int_text(i)//': universal file: expected a dataset number ' &
                                 //'after the -1 line, found the end of the file')
                return
            end if
            token = first_token(lines(i + 1)%text)
            ok = is_integer(token)
            if (ok) call read_integer(token, number, ok)
            if (.not. ok) then
                if (len(token) > 1 .and. is_integer(token(:max(len(token) - 1, 1))) &
                    .and. scan(token(len(token):), 'bB') == 1) then
                    call fatal_error(error, path//':'//int_text(i + 1)//': universal file dataset ' &
                                     //token//': expected an ASCII dataset, found a binary one; export the file ' &
                                     //'as an ASCII universal file')
                else
                    call fatal_error(error, path//':'//int_text(i + 1)//': universal file: expected a dataset ' &
                                     //'number (an integer in columns 1-6) after the -1 line, found "' &
                                     //trim(lines(i + 1)%text)//'"')
                end if
                return
            end if
            j = i + 2
            do while (j <= size(lines))
                if (is_delimiter(lines(j)%text)) exit
                j = j + 1
            end do
            if (j > size(lines)) then
                call fatal_error(error, path//':'//int_text(size(lines))//': universal file dataset ' &
                                 //int_text(number)//': expected a line "    -1" that ends the dataset started at ' &
                                 //'line '//int_text(i)//', found the end of the file; the file may be truncated')
                return
            end if
            n = n + 1
            found(n) = dataset_extent(number, i, j)
            i = j + 1
        end do
        sets = found(1:n)
    end subroutine find_datasets

    !> The first blank-separated word of a line ('' when blank).
    pure function first_token(line) result(token)
        character(len=*), intent(in) :: line
        character(len=merge(index(adjustl(line), ' ') - 1, len(line), index(adjustl(line), ' ') > 0)) :: token

        token = adjustl(line)
    end function first_token

    !> `path:line: universal file dataset N record R: `, the start of every message about a record.
    pure function record_prefix(path, line, dataset, record) result(prefix)
        !> File (for the message).
        character(len=*), intent(in) :: path
        !> Line of the file, dataset number and record number.
        integer, intent(in) :: line, dataset, record
        character(len=len(path//':'//int_text(line)//': universal file dataset '//int_text(dataset)//' record ' &
                          //int_text(record)//': ')) :: prefix

        prefix = path//':'//int_text(line)//': universal file dataset '//int_text(dataset)//' record ' &
                 //int_text(record)//': '
    end function record_prefix

    !> Columns first..last of a line, blank-padded where the line is shorter.
    pure function columns(line, first, last) result(field)
        !> The line.
        character(len=*), intent(in) :: line
        !> First and last column (1-based).
        integer, intent(in) :: first, last
        character(len=last - first + 1) :: field

        field = ''
        if (first <= len(line)) field = line(first:min(last, len(line)))
    end function columns

    !> `columns a-b` for messages.
    pure function span(first, last) result(text)
        !> First and last column.
        integer, intent(in) :: first, last
        character(len=len('columns '//int_text(first)//'-'//int_text(last))) :: text

        text = 'columns '//int_text(first)//'-'//int_text(last)
    end function span

    !> Columns first..last of a line in quotes for messages, or `blanks`.
    pure function quoted(line, first, last) result(text)
        !> The line.
        character(len=*), intent(in) :: line
        !> First and last column.
        integer, intent(in) :: first, last
        character(len=merge(len_trim(line(first:min(last, len(line)))) - verify(line(first:min(last, len(line))), ' ') &
                            + 3, 6, len_trim(line(first:min(last, len(line)))) > 0)) :: text

        if (len_trim(columns(line, first, last)) == 0) then
            text = 'blanks'
        else
            text = '"'//trim(adjustl(columns(line, first, last)))//'"'
        end if
    end function quoted

    !> What a field of `parse_real` status 1 or 2 should have held, for messages.
    pure function number_words(status) result(text)
        !> Status 1 (not a number) or 2 (not finite) of `parse_real`.
        integer, intent(in) :: status
        character(len=merge(15, 8, status == 2)) :: text

        text = 'a number'
        if (status == 2) text = 'a finite number'
    end function number_words

    !> Read the integer in columns first..last; a blank field is 0 unless `required`.
    subroutine integer_field(prefix, line, first, last, what, required, value, error)
        !> Start of the message (`record_prefix`), the line, and what the field holds (for the message).
        character(len=*), intent(in) :: prefix, line, what
        !> First and last column of the field.
        integer, intent(in) :: first, last
        !> Whether a blank field is an error rather than 0.
        logical, intent(in) :: required
        !> The integer read (0 when blank or on error).
        integer, intent(out) :: value
        !> Set (status 2) when the field holds no integer (or is blank and required).
        type(error_type), allocatable, intent(out) :: error

        character(len=:), allocatable :: field
        logical :: ok

        value = 0
        field = trim(adjustl(columns(line, first, last)))
        if (len(field) == 0 .and. .not. required) return
        ok = is_integer(field)
        if (ok) call read_integer(field, value, ok)
        if (.not. ok) call fatal_error(error, prefix//'expected '//what//' (an integer in '//span(first, last) &
                                       //'), found '//quoted(line, first, last))
    end subroutine integer_field

    !> Read the real in columns first..last; a blank field is 0 unless `required`. `layout`
    !> names the record's format for messages.
    subroutine real_field(prefix, line, first, last, what, layout, required, value, error)
        !> Start of the message, the line, what the field holds and the record's format (for the message).
        character(len=*), intent(in) :: prefix, line, what, layout
        !> First and last column of the field.
        integer, intent(in) :: first, last
        !> Whether a blank field is an error rather than 0.
        logical, intent(in) :: required
        !> The number read, in the file's unit (0 when blank or on error).
        real(dp), intent(out) :: value
        !> Set (status 2) when the field holds no finite number (or is blank and required).
        type(error_type), allocatable, intent(out) :: error

        character(len=:), allocatable :: field
        integer :: status

        value = 0.0_dp
        field = trim(adjustl(columns(line, first, last)))
        if (len(field) == 0 .and. .not. required) return
        call parse_real(field, value, status)
        if (status /= 0) call fatal_error(error, prefix//'expected '//what//' ('//number_words(status)//' in ' &
                                          //span(first, last)//', '//layout//'), found '//quoted(line, first, last))
    end subroutine real_field

    !> Read a number written as a Fortran E, D or F field would hold it, blanks removed:
    !> `1.5E+02`, `1.5e2`, `1.5D+02`, `0.15+003` (exponent without its letter), `150`.
    !> status: 0 read, 1 not a number (or blank), 2 NaN, infinite or beyond double precision.
    subroutine parse_real(field, value, status)
        !> The field, without blanks.
        character(len=*), intent(in) :: field
        !> The number read (0 unless status is 0).
        real(dp), intent(out) :: value
        !> 0 read, 1 not a number, 2 not finite or beyond double precision.
        integer, intent(out) :: status

        character(len=len(field) + 1) :: token
        integer :: i, sign_at
        logical :: ok

        value = 0.0_dp
        status = 1
        if (len(field) == 0 .or. index(field, ' ') > 0) return
        if (is_nan_or_inf(field)) then
            status = 2
            return
        end if
        token = field
        do i = 1, len(field)
            if (token(i:i) == 'd' .or. token(i:i) == 'D') token(i:i) = 'E'
        end do
        if (scan(token, 'eE') == 0) then
            sign_at = scan(token(2:), '+-')
            if (sign_at > 0) token = token(:sign_at)//'E'//field(sign_at + 1:)
        end if
        if (.not. is_number(trim(token))) return
        call read_real(trim(token), value, ok)
        status = merge(0, 2, ok)
    end subroutine parse_real

    !> The integer in columns first..last (required), with no message: the fast path of a
    !> reader's loop over many records, which calls `integer_field` for the message only when
    !> `ok` is false (building every record's message prefix beforehand cost a minute on a
    !> file of 10^5 nodes).
    subroutine quick_integer(line, first, last, value, ok)
        !> The line.
        character(len=*), intent(in) :: line
        !> First and last column of the field.
        integer, intent(in) :: first, last
        !> The integer read (0 when not ok).
        integer, intent(out) :: value
        !> Whether the field holds an integer.
        logical, intent(out) :: ok

        character(len=last - first + 1) :: field
        integer :: n

        value = 0
        field = adjustl(columns(line, first, last))
        n = len_trim(field)
        ok = n > 0
        if (ok) ok = is_integer(field(:n))
        if (ok) call read_integer(field(:n), value, ok)
    end subroutine quick_integer

    !> The real in columns first..last (required), with no message: `quick_integer`'s
    !> counterpart for `real_field`.
    subroutine quick_real(line, first, last, value, ok)
        !> The line.
        character(len=*), intent(in) :: line
        !> First and last column of the field.
        integer, intent(in) :: first, last
        !> The number read (0 when not ok), in the file's unit.
        real(dp), intent(out) :: value
        !> Whether the field holds a finite number.
        logical, intent(out) :: ok

        character(len=last - first + 1) :: field
        integer :: status

        field = adjustl(columns(line, first, last))
        call parse_real(field(:len_trim(field)), value, status)
        ok = status == 0
    end subroutine quick_real

    !> The labels that occur more than once in `labels`, each once, ascending (as reals: node
    !> labels are integers, exact as reals); empty when every label is unique. O(n log n).
    pure function repeated_labels(labels) result(repeated)
        !> The labels, in any order.
        integer, intent(in) :: labels(:)
        real(dp), allocatable :: repeated(:)

        real(dp), allocatable :: sorted(:)
        integer :: k, n

        allocate (repeated(0))
        if (size(labels) < 2) return
        sorted = real(labels, dp)
        call heap_sort(sorted)
        repeated = pack(sorted(2:), sorted(2:) == sorted(:size(sorted) - 1))
        n = min(1, size(repeated))
        do k = 2, size(repeated)
            if (repeated(k) /= repeated(n)) then
                n = n + 1
                repeated(n) = repeated(k)
            end if
        end do
        repeated = repeated(:n)
    end function repeated_labels

    !> Index of `label` in the ascending list `repeated_labels` gives, 0 when absent (bisection).
    pure integer function locate_label(list, label) result(at)
        !> Labels as reals, ascending.
        real(dp), intent(in) :: list(:)
        !> The label sought.
        integer, intent(in) :: label

        integer :: low, high, middle

        at = 0
        low = 1
        high = size(list)
        do while (low <= high)
            middle = (low + high)/2
            if (list(middle) == real(label, dp)) then
                at = middle
                return
            else if (list(middle) < real(label, dp)) then
                low = middle + 1
            else
                high = middle - 1
            end if
        end do
    end function locate_label

end module greenconv_io_uff_records
