!> Reading column files: any number of lines starting with `#` (comments) and blank lines,
!> and data lines of exactly N numbers separated by blanks or tabs. A bad line gets one
!> message naming the file, the line, and what was expected and found:
!>
!>     road.dat:7: expected 2 columns (x [m], height [m]), found 3: "0.1 0.2 0.3"
!>     road.dat:9: column 2 (height): expected a number, found "abc"
!>     road.dat:9: column 1 (x): expected a finite number, found "NaN"
module greenconv_io_columns
    use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
    use greenconv_core_kinds, only: dp
    use greenconv_core_text, only: int_text
    use greenconv_core_error, only: error_type, fatal_error
    use greenconv_core_number_text, only: is_number, is_nan_or_inf
    implicit none
    private

    public :: read_columns, read_line, read_lines, read_line_list, open_to_read, text_line, max_line_length
    public :: parse_row, count_tokens, byte_order_mark, pad_lines

    !> Longest line the readers accept [characters]: a longer one is not a scene, receptance
    !> or road file (a binary file, a file without line ends) and is refused at that line.
    integer, parameter :: max_line_length = 1048576

    !> The UTF-8 byte-order mark some editors write at the start of a text file; the readers skip it.
    character(len=*), parameter :: byte_order_mark = achar(239)//achar(187)//achar(191)

    !> Most bytes of a text file `read_lines` holds, as its lines padded to the longest one.
    integer, parameter :: max_text_bytes = 64*1048576

    !> One line of a text file, without its line end.
    type :: text_line
        !> The text of the line.
        character(len=:), allocatable :: text
    end type text_line

contains

    !> Read all data lines of a file (`read_line_list`) into table(:, 1:N), N = size(names),
    !> with the file line number of each row in line_of.
    subroutine read_columns(path, names, units, table, line_of, error)
        !> File to read.
        character(len=*), intent(in) :: path
        !> Short name of each column, for messages (e.g. `x`, `height`).
        character(len=*), intent(in) :: names(:)
        !> Unit of each column, for messages (e.g. `m`).
        character(len=*), intent(in) :: units(:)
        !> The numbers, one row per data_line line.
        real(dp), allocatable, intent(out) :: table(:, :)
        !> Line number in the file of each row.
        integer, allocatable, intent(out) :: line_of(:)
        !> Set when the file cannot be opened or a data_line line does not hold N finite numbers.
        type(error_type), allocatable, intent(out) :: error

        type(text_line), allocatable :: lines(:)
        logical, allocatable :: data_line(:)
        integer :: i, n, stat

        call read_line_list(path, '', '', lines, error)
        if (allocated(error)) return
        allocate (data_line(size(lines)))
        do i = 1, size(lines)
            data_line(i) = len_trim(lines(i)%text) > 0 .and. index(adjustl(lines(i)%text), '#') /= 1
        end do
        allocate (table(count(data_line), size(names)), line_of(count(data_line)), stat=stat)
        if (stat /= 0) then
            call fatal_error(error, path//': expected a file that fits in memory, found ' &
                             //int_text(count(data_line))//' data lines')
            return
        end if
        n = 0
        do i = 1, size(lines)
            if (.not. data_line(i)) cycle
            n = n + 1
            call parse_row(path//':'//int_text(i)//': ', names, units, lines(i)%text, table(n, :), error)
            if (allocated(error)) return
            line_of(n) = i
        end do
    end subroutine read_columns

    !> Parse one data line: exactly N finite numbers, N = size(names), each refused with its
    !> column's name when it is not a finite number.
    subroutine parse_row(prefix, names, units, line, row, error)
        !> Start of every message, `path:line: `.
        character(len=*), intent(in) :: prefix
        !> Short name of each column, for messages.
        character(len=*), intent(in) :: names(:)
        !> Unit of each column, for messages.
        character(len=*), intent(in) :: units(:)
        !> The data line.
        character(len=*), intent(in) :: line
        !> Its numbers.
        real(dp), intent(out) :: row(:)
        !> Set when the line does not hold N finite numbers.
        type(error_type), allocatable, intent(out) :: error

        integer :: first(size(names)), last(size(names)), n_tokens, i, stat
        character(len=:), allocatable :: list

        call split(line, first, last, n_tokens)
        if (n_tokens /= size(names)) then
            call list_columns(names, units, list)
            call fatal_error(error, prefix//'expected '//int_text(size(names))//' columns (' &
                             //list//'), found '//int_text(n_tokens)//': "' &
                             //trim(adjustl(line))//'"')
            return
        end if
        do i = 1, size(names)
            associate (token => line(first(i):last(i)), what => prefix//'column '//int_text(i)//' (' &
                                                                   //trim(names(i))//'): expected a ')
                if (.not. is_number(token)) then
                    if (is_nan_or_inf(token)) then
                        call fatal_error(error, what//'finite number, found "'//token//'"')
                    else
                        call fatal_error(error, what//'number, found "'//token//'"')
                    end if
                    return
                end if
                read (token, *, iostat=stat) row(i)
                if (stat /= 0 .or. .not. ieee_is_finite(row(i))) then
                    call fatal_error(error, what//'finite number (|x| < 1.8e308), found "'//token//'"')
                    return
                end if
            end associate
        end do
    end subroutine parse_row

    !> `name [unit], name [unit], ...` for messages.
    pure subroutine list_columns(names, units, text)
        !> Names and units of the columns.
        character(len=*), intent(in) :: names(:), units(:)
        !> The list.
        character(len=:), allocatable, intent(out) :: text

        integer :: i

        text = ''
        do i = 1, size(names)
            if (i > 1) text = text//', '
            text = text//trim(names(i))//' ['//trim(units(i))//']'
        end do
    end subroutine list_columns

    !> Number of blank- or tab-separated tokens of a line.
    pure integer function count_tokens(line)
        !> The line.
        character(len=*), intent(in) :: line

        integer :: first(0), last(0)

        call split(line, first, last, count_tokens)
    end function count_tokens

    !> Positions of the blank- or tab-separated tokens of a line (at most size(first)
    !> recorded, all counted).
    pure subroutine split(line, first, last, n_tokens)
        character(len=*), intent(in) :: line
        integer, intent(out) :: first(:), last(:)
        integer, intent(out) :: n_tokens

        logical :: inside, blank
        integer :: i, n_max

        n_max = size(first)
        n_tokens = 0
        first = 0
        last = 0
        inside = .false.
        do i = 1, len(line)
            blank = line(i:i) == ' ' .or. line(i:i) == achar(9) .or. line(i:i) == achar(13)
            if (.not. blank .and. .not. inside) then
                n_tokens = n_tokens + 1
                if (n_tokens <= n_max) first(n_tokens) = i
                inside = .true.
            else if (blank .and. inside) then
                if (n_tokens <= n_max) last(n_tokens) = i - 1
                inside = .false.
            end if
        end do
        if (inside .and. n_tokens <= n_max) last(n_tokens) = len(line)
    end subroutine split

    !> Read one whole line (stat: 0, or the iostat of the end of the file or a failure) in
    !> time linear in its length. A line longer than `max_line_length` is not read to its
    !> end: stat is then nonzero and `too_long` true.
    subroutine read_line(unit, line, stat, too_long)
        !> An open formatted sequential unit.
        integer, intent(in) :: unit
        !> The line, without its end.
        character(len=:), allocatable, intent(out) :: line
        !> 0 when a line was read.
        integer, intent(out) :: stat
        !> Whether the line was longer than `max_line_length` (then stat is nonzero).
        logical, intent(out), optional :: too_long

        character(len=4096) :: buffer
        character(len=:), allocatable :: work, longer
        integer :: n_read, used

        if (present(too_long)) too_long = .false.
        allocate (character(len=len(buffer)) :: work)
        used = 0
        do
            read (unit, '(a)', advance='no', iostat=stat, size=n_read) buffer
            if (used + n_read > len(work)) then
                allocate (character(len=2*len(work)) :: longer)
                longer(1:used) = work(1:used)
                call move_alloc(longer, work)
            end if
            work(used + 1:used + n_read) = buffer(1:n_read)
            used = used + n_read
            if (is_iostat_eor(stat) .or. (is_iostat_end(stat) .and. used > 0)) then
                stat = 0
                exit
            end if
            if (stat /= 0) exit
            if (used > max_line_length) then
                if (present(too_long)) too_long = .true.
                stat = 1
                exit
            end if
        end do
        line = work(1:used)
    end subroutine read_line

    !> A whole text file's lines, padded to the longest (`read_line_list`, at most
    !> `max_text_bytes` once padded). Refused with `read_line_list`'s messages.
    subroutine read_lines(path, what, lines, error)
        !> The file.
        character(len=*), intent(in) :: path
        !> What the file is, for messages (e.g. `scene file`).
        character(len=*), intent(in) :: what
        !> Its lines, without their ends, padded with blanks to the longest.
        character(len=:), allocatable, intent(out) :: lines(:)
        !> Set when the file cannot be read, naming it (and the line).
        type(error_type), allocatable, intent(out) :: error

        type(text_line), allocatable :: list(:)

        call read_line_list(path, what, '', list, error, max_text_bytes)
        if (allocated(error)) return
        call pad_lines(list, lines)
    end subroutine read_lines

    !> Lines as one character array, each padded with blanks to the longest (at least 1).
    pure subroutine pad_lines(list, lines)
        !> The lines.
        type(text_line), intent(in) :: list(:)
        !> The same lines, padded.
        character(len=:), allocatable, intent(out) :: lines(:)

        integer :: i, longest

        longest = 1
        do i = 1, size(list)
            longest = max(longest, len(list(i)%text))
        end do
        allocate (character(len=longest) :: lines(size(list)))
        do i = 1, size(list)
            lines(i) = list(i)%text
        end do
    end subroutine pad_lines

    !> Read a whole text file once, from its start to its end, without rewinding or opening it
    !> again (so a pipe, a FIFO or a process substitution works): its lines, a UTF-8 byte-order
    !> mark at its start skipped. Lines may end with LF, CR LF or a CR alone (old Mac text):
    !> gfortran's runtime ends a record at each. Refused with a message (and no lines): a file
    !> that cannot be opened (`open_to_read`'s message, with `advice`), a line longer than
    !> `max_line_length`, and with `max_bytes`, lines that padded to the longest would hold more
    !> bytes than that.
    !> Files are read one at a time in the process (the critical section greenconv_input_files):
    !> a file may be connected to one Fortran unit only, so two threads opening the same file
    !> at once would see "File already opened in another unit".
    subroutine read_line_list(path, what, advice, lines, error, max_bytes)
        !> The file.
        character(len=*), intent(in) :: path
        !> What the file is, for messages (e.g. `scene file`), or empty.
        character(len=*), intent(in) :: what
        !> What the message of a file that cannot be opened ends with (e.g. `; check the file name`).
        character(len=*), intent(in) :: advice
        !> Its lines, without their ends.
        type(text_line), allocatable, intent(out) :: lines(:)
        !> Set when the file cannot be read, naming it (and the line).
        type(error_type), allocatable, intent(out) :: error
        !> Most bytes [B] of the lines padded to the longest (a multiple of 1 MiB); no limit when absent.
        integer, intent(in), optional :: max_bytes

        !$omp critical (greenconv_input_files)
        call read_text()
        !$omp end critical (greenconv_input_files)

    contains

        !> The reading itself, inside the lock (the arguments are the host's).
        subroutine read_text()
            type(text_line), allocatable :: longer(:)
            integer :: unit, stat, n, longest, i
            logical :: too_long

            call open_to_read(path, what, advice, unit, error)
            if (allocated(error)) return
            allocate (lines(64))
            n = 0
            longest = 0
            do
                if (n == size(lines)) then
                    allocate (longer(2*n))
                    longer(1:n) = lines
                    call move_alloc(longer, lines)
                end if
                call read_line(unit, lines(n + 1)%text, stat, too_long)
                if (too_long) then
                    call fatal_error(error, long_line(path, n + 1))
                    exit
                end if
                if (stat /= 0) exit
                n = n + 1
                if (n == 1 .and. index(lines(1)%text, byte_order_mark) == 1) &
                    lines(1)%text = lines(1)%text(len(byte_order_mark) + 1:)
                longest = max(longest, len(lines(n)%text))
                if (.not. present(max_bytes)) cycle
                if (real(longest, dp)*real(n, dp) > real(max_bytes, dp)) then
                    call fatal_error(error, path//':'//int_text(n)//': expected a '//what//' of at most ' &
                                     //int_text(max_bytes/1048576)//' MiB, found more')
                    exit
                end if
            end do
            close (unit)
            if (allocated(error)) then
                deallocate (lines)
                return
            end if
            allocate (longer(n))
            do i = 1, n
                call move_alloc(lines(i)%text, longer(i)%text)
            end do
            call move_alloc(longer, lines)
        end subroutine read_text
    end subroutine read_line_list

    !> Open an existing file to read it, on a new unit; when it cannot be opened, the message
    !> `PATH: cannot open the WHAT: REASON` + `advice` (`PATH: cannot open: REASON` + `advice`
    !> for an empty `what`), status 2.
    subroutine open_to_read(path, what, advice, unit, error)
        !> The file.
        character(len=*), intent(in) :: path
        !> What the file is, for messages (e.g. `scene file`), or empty.
        character(len=*), intent(in) :: what
        !> What the message ends with after the system's reason (e.g. `; check the file name`).
        character(len=*), intent(in) :: advice
        !> The unit it is connected to.
        integer, intent(out) :: unit
        !> Set when the file cannot be opened.
        type(error_type), allocatable, intent(out) :: error

        character(len=512) :: message
        integer :: stat

        open (newunit=unit, file=path, status='old', action='read', iostat=stat, iomsg=message)
        if (stat == 0) return
        if (len(what) == 0) then
            call fatal_error(error, path//': cannot open: '//trim(message)//advice)
        else
            call fatal_error(error, path//': cannot open the '//what//': '//trim(message)//advice)
        end if
    end subroutine open_to_read

    !> The message on a line longer than `max_line_length`.
    function long_line(path, line_number) result(text)
        character(len=*), intent(in) :: path
        integer, intent(in) :: line_number
        character(len=len(path//':'//int_text(line_number)//': expected lines of at most '//int_text(max_line_length) &
                          //' characters, found a longer one (a binary file, or a file without line ends?)')) :: text

        text = path//':'//int_text(line_number)//': expected lines of at most '//int_text(max_line_length) &
               //' characters, found a longer one (a binary file, or a file without line ends?)'
    end function long_line

end module greenconv_io_columns
