!> Output files that are either complete or absent: column data is written to a
!> temporary file beside the target and renamed over it only when fully written. A long
!> run streams its rows in blocks through a `column_writer`; when a numerical fault stops
!> it, the caller closes the file with the rows written so far, and on bad input or a
!> failed write it discards it.
!>
!> The temporary file is `<path>.<pid>.<n>.part` (the process id and a counter of the
!> process), created exclusively: an existing file or symlink of that name is never opened,
!> and two processes writing one output each write their own file; the last rename wins
!> with a whole file. Rows are collected in a buffer and written with write(2) through
!> io/part_files.c, every write and the close checked (gfortran's own I/O loses the error
!> of a buffered write on a full disk); a failed one deletes the temporary file and says
!> which file and why. `remove_parts_on_signals`
!> (called by the driver) makes SIGINT and SIGTERM delete the temporary files in flight.
module greenconv_io_files
    use, intrinsic :: iso_c_binding, only: c_char, c_int, c_size_t, c_null_char, c_ptr, c_associated
    use, intrinsic :: iso_fortran_env, only: int32, int64
    use greenconv_core_kinds, only: dp
    use greenconv_core_error, only: error_type, fatal_error
    use greenconv_core_text, only: int_text
    use greenconv_core_real_text, only: real_rows_text, rows_text_length
    use greenconv_io_columns, only: read_line
    implicit none
    private

    public :: write_columns, make_directory, check_output_directory, remove_parts_on_signals, check_input_kept
    public :: column_writer, open_columns, append_rows, close_columns, discard_columns, close_run_file, first_kept
    public :: block_rows, binary_header, write_text, standard_output_is_terminal, relay_to_standard_output

    !> Rows a run streamed in blocks computes and writes at a time (a block of this many steps
    !> of a single-point run, of block_rows/N_c steps of an N_c-point run): what a long run
    !> holds of its histories, whatever its number of steps.
    integer, parameter :: block_rows = 16384

    !> Whether this machine stores numbers most significant byte first (binary files are
    !> written little-endian everywhere).
    logical, parameter :: big_endian = ichar(transfer(1_int32, 'a')) == 0

    !> Temporary files this process has created (a counter for their unique names).
    integer, save :: parts_made = 0

    !> Bytes a writer collects before it writes them to its file (a block of a thousand rows
    !> and more of text, written by one write(2)).
    integer, parameter :: buffer_bytes = 1048576

    !> A column file written in blocks (`open_columns`, `append_rows`, `close_columns`): the
    !> rows go to a temporary file `part`, renamed to `path` when closed, so a reader never
    !> sees a file that is still growing under the target name.
    type :: column_writer
        !> Target file.
        character(len=:), allocatable :: path
        !> Temporary file being written, `<path>.<pid>.<n>.part`.
        character(len=:), allocatable :: part
        !> File descriptor of `part` (-1: none).
        integer(c_int) :: fd = -1
        !> Text not yet written to `part`: its first `used` characters.
        character(len=:), allocatable :: buffer
        !> Characters of `buffer` in use.
        integer :: used = 0
        !> Whether `part` is open.
        logical :: opened = .false.
        !> Slot of `part` in the table of files removed on a signal (-1: not recorded).
        integer :: slot = -1
        !> Number of values of every row.
        integer :: n_columns = 0
        !> Whether rows are written as little-endian float64 (`binary_header` beside the file)
        !> rather than text.
        logical :: binary = .false.
        !> Header lines, kept for the header file of a binary file.
        character(len=:), allocatable :: comments(:)
        !> Number of rows written so far.
        integer(int64) :: rows = 0
    end type column_writer

    interface
        !> C library rename(2): atomic within one file system.
        function c_rename(old_path, new_path) bind(c, name='rename') result(stat)
            import :: c_char, c_int
            implicit none
            character(kind=c_char), intent(in) :: old_path(*)
            character(kind=c_char), intent(in) :: new_path(*)
            integer(c_int) :: stat
        end function c_rename


        !> C library realpath(3).
        function c_realpath(path, resolved) bind(c, name='realpath') result(answer)
            import :: c_char, c_ptr
            character(kind=c_char), intent(in) :: path(*)
            character(kind=c_char), intent(out) :: resolved(*)
            type(c_ptr) :: answer
        end function c_realpath

        !> C library getpid(2).
        function c_getpid() bind(c, name='getpid') result(pid)
            import :: c_int
            implicit none
            integer(c_int) :: pid
        end function c_getpid


        !> Forget a slot of `c_part_register` (io/part_files.c).
        subroutine c_part_release(slot) bind(c, name='gc_part_release')
            import :: c_int
            implicit none
            integer(c_int), value :: slot
        end subroutine c_part_release


        !> Whether a result of `c_part_create` says that the name exists (io/part_files.c): 1 or 0.
        function c_part_name_taken(result) bind(c, name='gc_part_name_taken') result(taken)
            import :: c_int
            implicit none
            integer(c_int), value :: result
            integer(c_int) :: taken
        end function c_part_name_taken

        !> Write bytes to a descriptor (io/part_files.c): 0 or errno.
        function c_part_write(fd, bytes, length) bind(c, name='gc_part_write') result(number)
            import :: c_char, c_int, c_size_t
            implicit none
            integer(c_int), value :: fd
            character(kind=c_char), intent(in) :: bytes(*)
            integer(c_size_t), value :: length
            integer(c_int) :: number
        end function c_part_write

        !> C library isatty(3): 1 when the descriptor is a terminal.
        function c_isatty(fd) bind(c, name='isatty') result(answer)
            import :: c_int
            implicit none
            integer(c_int), value :: fd
            integer(c_int) :: answer
        end function c_isatty

        !> Close a descriptor (io/part_files.c): 0 or errno.
        function c_part_close(fd) bind(c, name='gc_part_close') result(number)
            import :: c_int
            implicit none
            integer(c_int), value :: fd
            integer(c_int) :: number
        end function c_part_close

        !> The text of an errno value (io/part_files.c).
        subroutine c_part_strerror(number, text, length) bind(c, name='gc_part_strerror')
            import :: c_char, c_int, c_size_t
            implicit none
            integer(c_int), value :: number
            character(kind=c_char), intent(out) :: text(*)
            integer(c_size_t), value :: length
        end subroutine c_part_strerror

        !> Install the SIGINT/SIGTERM handler (io/part_files.c); 0 or -1.
        function c_part_remove_on_signals() bind(c, name='gc_part_remove_on_signals') result(stat)
            import :: c_int
            implicit none
            integer(c_int) :: stat
        end function c_part_remove_on_signals
    end interface

    abstract interface
        !> A C call on a NUL-terminated path alone, returning an int.
        function path_call(path) bind(c) result(stat)
            import :: c_char, c_int
            implicit none
            character(kind=c_char), intent(in) :: path(*)
            integer(c_int) :: stat
        end function path_call

        !> A C library call on a path and an int: mkdir(2) (the mode) and access(2) (the test).
        function path_and_flag_call(path, flag) bind(c) result(stat)
            import :: c_char, c_int
            implicit none
            character(kind=c_char), intent(in) :: path(*)
            integer(c_int), value :: flag
            integer(c_int) :: stat
        end function path_and_flag_call
    end interface

    !> C library unlink(2).
    procedure(path_call), bind(c, name='unlink') :: c_unlink
    !> Record a temporary file to delete on SIGINT/SIGTERM (io/part_files.c); its slot or -1.
    procedure(path_call), bind(c, name='gc_part_register') :: c_part_register
    !> Create a file exclusively (io/part_files.c): a descriptor, or -errno.
    procedure(path_call), bind(c, name='gc_part_create') :: c_part_create
    !> C library mkdir(2).
    procedure(path_and_flag_call), bind(c, name='mkdir') :: c_mkdir
    !> C library access(2).
    procedure(path_and_flag_call), bind(c, name='access') :: c_access

contains

    !> Write a table of reals with `#` comment lines above it, atomically.
    !>
    !> `comments` are written as `# ` lines; the last one should name the columns.
    recursive subroutine write_columns(path, comments, table, error)
        !> Target file.
        character(len=*), intent(in) :: path
        !> Header lines, written after `# `.
        character(len=*), intent(in) :: comments(:)
        !> Values, one row per line: table(row, column).
        real(dp), intent(in) :: table(:, :)
        !> Set when the file cannot be written.
        type(error_type), allocatable, intent(out) :: error

        type(column_writer) :: writer

        call open_columns(writer, path, comments, size(table, 2), error)
        if (.not. allocated(error)) call append_rows(writer, table, error)
        if (.not. allocated(error)) call close_columns(writer, error)
    end subroutine write_columns

    !> Write a text (lines separated by new_line('a'), each kept as it is, trailing blanks
    !> too) and a final newline to `path`, atomically as a column file.
    subroutine write_text(path, text, error)
        !> Target file.
        character(len=*), intent(in) :: path
        !> The text.
        character(len=*), intent(in) :: text
        !> Set when the file cannot be written (nothing is left behind).
        type(error_type), allocatable, intent(out) :: error

        type(column_writer) :: writer
        character(len=1) :: no_comments(0)

        call open_columns(writer, path, no_comments, 0, error)
        if (.not. allocated(error)) call put_line(writer, text, error)
        if (.not. allocated(error)) call close_columns(writer, error)
    end subroutine write_text

    !> Start a column file written in blocks: create its temporary file exclusively and write
    !> the `# ` header lines (the last should name the columns). Then `append_rows` per block,
    !> and `close_columns` to rename it to `path`.
    !>
    !> With `binary` true, each row is written as n_columns little-endian IEEE float64 values
    !> (8 bytes each, no header, no separators), and `close_columns` writes the text file
    !> `binary_header(path)` beside it: the header lines, the row count and how to read it.
    subroutine open_columns(writer, path, comments, n_columns, error, binary)
        !> The file being written.
        type(column_writer), intent(out) :: writer
        !> Target file.
        character(len=*), intent(in) :: path
        !> Header lines, written after `# ` (for binary rows: into the header file).
        character(len=*), intent(in) :: comments(:)
        !> Number of columns of every row.
        integer, intent(in) :: n_columns
        !> Set when the file cannot be written (nothing is left behind).
        type(error_type), allocatable, intent(out) :: error
        !> Whether the rows are written as binary float64 (default: text).
        logical, intent(in), optional :: binary

        character(len=40) :: suffix
        integer(c_int) :: fd
        integer, parameter :: max_attempts = 100000
        integer :: i, attempt

        writer%path = path
        ! Created with O_EXCL: an existing name (a planted file or symlink, the part of a dead
        ! process that had the same pid) is never opened: the next name is tried.
        do attempt = 1, max_attempts
            !$omp critical (greenconv_part_names)
            parts_made = parts_made + 1
            write (suffix, '(a,i0,a,i0,a)') '.', c_getpid(), '.', parts_made, '.part'
            !$omp end critical (greenconv_part_names)
            writer%part = path//trim(suffix)
            fd = c_part_create(writer%part//c_null_char)
            if (c_part_name_taken(fd) == 0) exit
        end do
        if (fd < 0) then
            call fatal_error(error, path//': cannot write: '//trim(error_text(-fd))//' (creating '//writer%part//')')
            return
        end if
        writer%fd = fd
        writer%opened = .true.
        writer%slot = c_part_register(writer%part//c_null_char)
        allocate (character(len=buffer_bytes) :: writer%buffer)
        writer%used = 0
        writer%n_columns = n_columns
        if (present(binary)) writer%binary = binary
        if (writer%binary) then
            allocate (character(len=max(len(comments), 1)) :: writer%comments(size(comments)))
            writer%comments = comments
            return
        end if
        do i = 1, size(comments)
            call put_line(writer, '# '//trim(comments(i)), error)
            if (allocated(error)) return
        end do
    end subroutine open_columns

    !> Append rows to a column file opened by `open_columns`; on a write error the partial
    !> file is deleted and `error` says why.
    subroutine append_rows(writer, table, error)
        !> The file being written.
        type(column_writer), intent(inout) :: writer
        !> Values, one row per line: table(row, column).
        real(dp), intent(in) :: table(:, :)
        !> Set when the rows cannot be written.
        type(error_type), allocatable, intent(out) :: error

        integer :: first, last, per_row, room, length

        ! Rows are laid out as exact text (greenconv_core_real_text) or as bytes straight into
        ! the buffer, as many as fit, and the buffer is written out whole when full.
        per_row = rows_text_length(1, size(table, 2))
        if (writer%binary) per_row = 8*size(table, 2)
        if (len(writer%buffer) < per_row) then
            call flush_buffer(writer, error)
            if (allocated(error)) return
            deallocate (writer%buffer)
            allocate (character(len=per_row) :: writer%buffer)
        end if
        first = 1
        do while (first <= size(table, 1))
            room = (len(writer%buffer) - writer%used)/per_row
            if (room == 0) then
                call flush_buffer(writer, error)
                if (allocated(error)) return
                cycle
            end if
            last = min(size(table, 1), first + room - 1)
            if (writer%binary) then
                call put_binary_rows(table(first:last, :), writer%buffer(writer%used + 1:), length)
            else
                call real_rows_text(table(first:last, :), writer%buffer(writer%used + 1:), length)
            end if
            writer%used = writer%used + length
            first = last + 1
        end do
        writer%rows = writer%rows + size(table, 1)
    end subroutine append_rows

    !> The rows of a table as little-endian IEEE float64 bytes, row after row.
    pure subroutine put_binary_rows(table, bytes, length)
        !> Values table(row, column).
        real(dp), intent(in) :: table(:, :)
        !> At least 8*size(table) characters.
        character(len=*), intent(inout) :: bytes
        !> Number of characters set, bytes(1:length).
        integer, intent(out) :: length

        character(len=8) :: value
        integer :: i, j, k

        length = 0
        do i = 1, size(table, 1)
            do j = 1, size(table, 2)
                value = transfer(table(i, j), value)
                if (big_endian) then
                    do k = 1, 8
                        bytes(length + k:length + k) = value(9 - k:9 - k)
                    end do
                else
                    bytes(length + 1:length + 8) = value
                end if
                length = length + 8
            end do
        end do
    end subroutine put_binary_rows

    !> Path of the text header file of a binary column file: `<path>.txt`.
    pure function binary_header(path) result(header)
        !> The binary column file.
        character(len=*), intent(in) :: path
        character(len=len(path) + 4) :: header

        header = path//'.txt'
    end function binary_header

    !> Write the header file of a binary column file: its header lines, then the layout, the
    !> row count and one-line readers (gnuplot, numpy, MATLAB/Octave).
    recursive subroutine write_binary_header(writer, error)
        type(column_writer), intent(in) :: writer
        type(error_type), allocatable, intent(out) :: error

        character(len=:), allocatable :: name, n
        character(len=400), allocatable :: lines(:)
        real(dp) :: no_rows(0, writer%n_columns)
        integer :: c

        name = writer%path(index(writer%path, '/', back=.true.) + 1:)
        n = int_text(int(writer%n_columns, int64))
        ! The header lines, the layout and readers, and last the column names (the last `#`
        ! line names the columns, as in a text file).
        c = max(size(writer%comments) - 1, 0)
        allocate (lines(c + 8))
        lines(1:c) = writer%comments(1:c)
        lines(c + 8) = 'columns as numbered'
        if (size(writer%comments) > 0) lines(c + 8) = writer%comments(c + 1)
        lines(c + 1) = 'binary column file '//name//': '//int_text(writer%rows)//' rows of '//n &
                   //' little-endian IEEE float64 values (8 bytes each), row after row, no header'
        lines(c + 2) = 'rows: '//int_text(writer%rows)
        lines(c + 3) = 'columns: '//n//' (names and units in the lines above)'
        lines(c + 4) = 'format: float64 little-endian'
        lines(c + 5) = "gnuplot: plot '"//name//"' binary format='%"//n//"float64' using 1:2"
        lines(c + 6) = "numpy: numpy.fromfile('"//name//"', dtype='<f8').reshape(-1, "//n//')'
        lines(c + 7) = "MATLAB/Octave: fread(fopen('"//name//"'), ["//n//" Inf], 'float64', 0, 'ieee-le')'"
        call write_columns(binary_header(writer%path), lines, no_rows, error)
    end subroutine write_binary_header

    !> Finish a column file: write what the buffer holds, close the temporary file and rename
    !> it to `path`. When a write, the close or the rename fails, the temporary file is
    !> deleted and `error` names the file and the reason.
    !> Recursive: a binary file's header file is itself written as a (text) column file.
    recursive subroutine close_columns(writer, error)
        !> The file being written; closed on return.
        type(column_writer), intent(inout) :: writer
        !> Set when the file cannot be completed.
        type(error_type), allocatable, intent(out) :: error

        integer(c_int) :: number

        if (.not. writer%opened) return
        call flush_buffer(writer, error)
        if (allocated(error)) return
        number = c_part_close(writer%fd)
        writer%fd = -1
        writer%opened = .false.
        if (number /= 0) then
            call write_failed(writer, error_text(number), error)
            return
        end if
        ! A binary file's header file is complete before the file appears under its name.
        if (writer%binary) then
            call write_binary_header(writer, error)
            if (allocated(error)) then
                call discard_columns(writer)
                return
            end if
        end if
        if (c_rename(writer%part//c_null_char, writer%path//c_null_char) /= 0) then
            if (writer%binary) number = c_unlink(binary_header(writer%path)//c_null_char)
            call write_failed(writer, 'cannot rename '//writer%part//' to it', error)
            return
        end if
        call forget_part(writer)
    end subroutine close_columns

    !> Add one line (and its newline) to the writer's buffer, writing the buffer out when full.
    subroutine put_line(writer, line, error)
        type(column_writer), intent(inout) :: writer
        character(len=*), intent(in) :: line
        type(error_type), allocatable, intent(out) :: error

        if (writer%used + len(line) + 1 > len(writer%buffer)) then
            call flush_buffer(writer, error)
            if (allocated(error)) return
            if (len(line) + 1 > len(writer%buffer)) then
                deallocate (writer%buffer)
                allocate (character(len=len(line) + 1) :: writer%buffer)
            end if
        end if
        writer%buffer(writer%used + 1:writer%used + len(line)) = line
        writer%buffer(writer%used + len(line) + 1:writer%used + len(line) + 1) = new_line('a')
        writer%used = writer%used + len(line) + 1
    end subroutine put_line

    !> Write the buffer to the temporary file; on failure delete it and say why.
    subroutine flush_buffer(writer, error)
        type(column_writer), intent(inout) :: writer
        type(error_type), allocatable, intent(out) :: error

        integer(c_int) :: number

        if (writer%used == 0) return
        number = c_part_write(writer%fd, writer%buffer, int(writer%used, c_size_t))
        writer%used = 0
        if (number /= 0) call write_failed(writer, error_text(number), error)
    end subroutine flush_buffer

    !> Whether standard output (descriptor 1) is a terminal.
    logical function standard_output_is_terminal()
        standard_output_is_terminal = c_isatty(1_c_int) == 1
    end function standard_output_is_terminal

    !> Copy the lines a formatted unit holds (a scratch file the driver's summary went to) to
    !> standard output with every write(2) checked, and close the unit. gfortran's runtime
    !> drops the errors of writes on its standard output (a full device, a closed pipe): the
    !> WRITE, FLUSH and CLOSE statements all report success, so a driver whose output is not a
    !> terminal writes its summary to a scratch unit and hands it over here at its end.
    subroutine relay_to_standard_output(unit, error)
        !> The unit, open for reading and writing; closed (deleted when scratch) on return.
        integer, intent(in) :: unit
        !> Set (status 2) when a write on standard output failed, with the system's reason.
        type(error_type), allocatable, intent(out) :: error

        character(len=:), allocatable :: line
        integer :: stat
        integer(c_int) :: number

        rewind (unit)
        do
            call read_line(unit, line, stat)
            if (stat /= 0) exit
            line = line//new_line('a')
            number = c_part_write(1_c_int, line, int(len(line), c_size_t))
            if (number /= 0) then
                call fatal_error(error, 'standard output: writing the summary failed: '//trim(error_text(number)) &
                                 //'; the output files of the run are written, its summary is lost')
                exit
            end if
        end do
        close (unit)
    end subroutine relay_to_standard_output

    !> The system's text for an errno value, blank-padded (a fixed length keeps the result off
    !> static storage; trim it).
    function error_text(number) result(text)
        integer(c_int), intent(in) :: number
        character(len=200) :: text

        text = ''
        call c_part_strerror(number, text, int(len(text), c_size_t))
        if (index(text, c_null_char) > 0) text(index(text, c_null_char):) = ''
    end function error_text

    !> End the file of a run streamed in blocks. After a failed write (`error` already set)
    !> there is nothing left to do: the partial file is gone. Otherwise the file is closed
    !> and renamed, and when a numerical `fault` stopped the run it becomes `error`: `prefix`,
    !> its message, and the file that holds the rows before it.
    subroutine close_run_file(writer, fault, prefix, error)
        !> The file being written; closed on return.
        type(column_writer), intent(inout) :: writer
        !> The fault that stopped the run, if any; moved into `error`.
        type(error_type), allocatable, intent(inout) :: fault
        !> Text put before the fault's message (the scene file and method).
        character(len=*), intent(in) :: prefix
        !> A failed write on entry; on return also a failed rename or the fault.
        type(error_type), allocatable, intent(inout) :: error

        if (allocated(error)) return
        call close_columns(writer, error)
        if (allocated(error) .or. .not. allocated(fault)) return
        call move_alloc(fault, error)
        error%message = prefix//error%message//' (rows up to then in '//writer%path//')'
    end subroutine close_run_file

    !> Abandon a column file: close and delete its temporary file (for a run stopped by bad
    !> input).
    subroutine discard_columns(writer)
        !> The file being written; closed on return.
        type(column_writer), intent(inout) :: writer

        integer(c_int) :: number

        if (writer%opened) number = c_part_close(writer%fd)
        writer%fd = -1
        writer%opened = .false.
        writer%used = 0
        if (allocated(writer%part)) number = c_unlink(writer%part//c_null_char)
        call forget_part(writer)
    end subroutine discard_columns

    !> A write failed: delete the temporary file and say which file and why.
    subroutine write_failed(writer, message, error)
        type(column_writer), intent(inout) :: writer
        character(len=*), intent(in) :: message
        type(error_type), allocatable, intent(out) :: error

        call discard_columns(writer)
        call fatal_error(error, writer%path//': write failed: '//trim(message)//'; nothing was left under that name')
    end subroutine write_failed

    !> The temporary file is gone (renamed or deleted): take it off the signal table.
    subroutine forget_part(writer)
        type(column_writer), intent(inout) :: writer

        if (writer%slot >= 0) call c_part_release(int(writer%slot, c_int))
        writer%slot = -1
    end subroutine forget_part

    !> Decimated output of a run streamed in blocks: the index j (from 0) of the first step
    !> n = first + j of a block that is a multiple of `every`, the first row it writes (then
    !> every `every`-th); the block writes nothing when j is past its end.
    pure integer function first_kept(first, every)
        !> Index n of the block's first step in the run.
        integer(int64), intent(in) :: first
        !> A row every this many steps (>= 1): steps 0, every, 2*every, ...
        integer, intent(in) :: every

        first_kept = int(mod(every - mod(first, int(every, int64)), int(every, int64)))
    end function first_kept

    !> Create a directory and its missing parents (like `mkdir -p`).
    subroutine make_directory(path, error)
        !> Directory path.
        character(len=*), intent(in) :: path
        !> Set when the directory does not exist afterwards.
        type(error_type), allocatable, intent(out) :: error

        integer :: i, stat
        logical :: exists

        do i = 2, len(path)
            if (path(i:i) == '/') stat = c_mkdir(path(1:i - 1)//c_null_char, int(o'755', c_int))
        end do
        stat = c_mkdir(path//c_null_char, int(o'755', c_int))
        inquire (file=path//'/.', exist=exists)
        if (.not. exists) call fatal_error(error, path//': cannot create the output directory')
    end subroutine make_directory

    !> Check, without creating anything, that a run could write into directory `path`: it
    !> exists and is writable, or its nearest existing parent is a writable directory (a run
    !> creates the missing ones).
    subroutine check_output_directory(path, error)
        !> Directory path.
        character(len=*), intent(in) :: path
        !> Set when a run could not write there: which directory and why.
        type(error_type), allocatable, intent(out) :: error

        integer(c_int), parameter :: w_ok = 2, x_ok = 1
        character(len=:), allocatable :: parent
        logical :: is_directory, exists
        integer :: cut

        parent = path
        do
            inquire (file=parent//'/.', exist=is_directory)
            if (is_directory) exit
            inquire (file=parent, exist=exists)
            if (exists) then
                call fatal_error(error, path//': cannot create the output directory: '//parent &
                                 //' is a file, not a directory; choose another output_dir')
                return
            end if
            cut = index(parent, '/', back=.true.)
            if (cut == 0) then
                parent = '.'
            else if (cut == 1) then
                parent = '/'
            else
                parent = parent(1:cut - 1)
            end if
        end do
        if (c_access(parent//c_null_char, ior(w_ok, x_ok)) /= 0) then
            call fatal_error(error, path//': cannot write the output directory: '//parent &
                             //' is not writable; choose another output_dir')
        end if
    end subroutine check_output_directory

    !> Refuse (`stat_input`) an input file that a run's outputs would replace. A run owns the
    !> names `<output_dir>/<prefix>*.dat`, `.bin`, `.bin.txt` (its column files, identification
    !> files, sweep table) and the folders `<output_dir>/<prefix>*/` (a sweep's records), each written to a temporary file and renamed over its target: an input whose
    !> real location (symbolic links and `..` resolved, so that two spellings of one file
    !> are one) lies there would be lost. Checked before anything is written; an input or
    !> output directory that does not exist yet cannot collide and passes.
    subroutine check_input_kept(input, output_dir, prefix, error)
        !> Path of the input file, as the scene gives it (the caller puts what names it, e.g.
        !> "data/id.nml:4: &structure frf_file: ", before the message).
        character(len=*), intent(in) :: input
        !> Directory the run writes to.
        character(len=*), intent(in) :: output_dir
        !> Start of the name of every file the run writes there, e.g. "<name>_".
        character(len=*), intent(in) :: prefix
        !> Set (`stat_input`) when the input lies where an output goes, with both names.
        type(error_type), allocatable, intent(out) :: error

        character(len=:), allocatable :: input_real, dir_real, rest

        call real_path(input, input_real)
        call real_path(output_dir, dir_real)
        if (len(input_real) == 0 .or. len(dir_real) == 0) return
        if (dir_real /= '/') dir_real = dir_real//'/'
        if (index(input_real, dir_real//prefix) /= 1) return
        rest = input_real(len(dir_real//prefix) + 1:)
        ! What the run writes there ends in .dat, .bin or .bin.txt, or is in a folder of its own
        ! (a sweep's records): other names (a scene file, a universal file) are left alone.
        if (index(rest, '/') == 0 .and. .not. any(ends_with(rest, ['.dat    ', '.bin    ', '.bin.txt']))) return
        call fatal_error(error, ''''//input//''': this input lies where the run writes its outputs (' &
                         //output_dir//'/'//prefix//'*) and would be overwritten: move it, or change the ' &
                         //'scene''s name or output_dir')
    end subroutine check_input_kept

    !> Whether text ends with the (trimmed) suffix.
    elemental logical function ends_with(text, suffix)
        character(len=*), intent(in) :: text, suffix

        integer :: n

        n = len_trim(suffix)
        ends_with = len(text) >= n
        if (ends_with) ends_with = text(len(text) - n + 1:) == suffix(1:n)
    end function ends_with

    !> The canonical absolute path of an existing file or directory (POSIX realpath), or ''
    !> when it does not exist or cannot be resolved.
    subroutine real_path(path, resolved)
        !> The file or directory.
        character(len=*), intent(in) :: path
        !> Its canonical absolute path, or ''.
        character(len=:), allocatable, intent(out) :: resolved

        character(kind=c_char, len=4097) :: buffer
        integer :: n

        resolved = ''
        buffer = c_null_char
        if (.not. c_associated(c_realpath(path//c_null_char, buffer))) return
        n = index(buffer, c_null_char) - 1
        if (n > 0) resolved = buffer(1:n)
    end subroutine real_path

    !> Make SIGINT and SIGTERM delete the temporary files of the column files being written,
    !> then end the program by that signal (for a program such as the driver; a host program
    !> that handles these signals itself keeps its handlers). Signals that are ignored stay so.
    subroutine remove_parts_on_signals()
        integer(c_int) :: stat

        stat = c_part_remove_on_signals()
    end subroutine remove_parts_on_signals

end module greenconv_io_files
