!> Output files that are either complete or absent: column data is written to a
!> temporary file beside the target and renamed over it only when fully written. A long
!> run streams its rows in blocks through a `column_writer`; when a numerical fault stops
!> it, the caller closes the file with the rows written so far, and on bad input or a
!> failed write it discards it.
module greenconv_io_files
    use, intrinsic :: iso_c_binding, only: c_char, c_int, c_null_char
    use, intrinsic :: iso_fortran_env, only: int64
    use greenconv_core_kinds, only: dp
    use greenconv_core_error, only: error_type, fatal_error
    implicit none
    private

    public :: write_columns, make_directory
    public :: column_writer, open_columns, append_rows, close_columns, discard_columns, close_run_file, first_kept
    public :: block_rows

    !> Rows a run streamed in blocks computes and writes at a time (a block of this many steps
    !> of a single-point run, of block_rows/N_c steps of an N_c-point run): what a long run
    !> holds of its histories, whatever its number of steps.
    integer, parameter :: block_rows = 16384

    !> A column file written in blocks (`open_columns`, `append_rows`, `close_columns`): the
    !> rows go to `path.part`, renamed to `path` when closed, so a reader never sees a file
    !> that is still growing under the target name.
    type :: column_writer
        !> Target file.
        character(len=:), allocatable :: path
        !> Fortran unit of `path.part`.
        integer :: unit = -1
        !> Whether `path.part` is open.
        logical :: opened = .false.
        !> Edit descriptor of one row.
        character(len=32) :: row_format = ''
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

        !> C library mkdir(2).
        function c_mkdir(path, mode) bind(c, name='mkdir') result(stat)
            import :: c_char, c_int
            implicit none
            character(kind=c_char), intent(in) :: path(*)
            integer(c_int), value :: mode
            integer(c_int) :: stat
        end function c_mkdir
    end interface

contains

    !> Write a table of reals with `#` comment lines above it, atomically.
    !>
    !> `comments` are written as `# ` lines; the last one should name the columns.
    subroutine write_columns(path, comments, table, error)
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

    !> Start a column file written in blocks: open `path.part` and write the `# ` header
    !> lines (the last should name the columns). Then `append_rows` per block, and
    !> `close_columns` to rename it to `path`.
    subroutine open_columns(writer, path, comments, n_columns, error)
        !> The file being written.
        type(column_writer), intent(out) :: writer
        !> Target file.
        character(len=*), intent(in) :: path
        !> Header lines, written after `# `.
        character(len=*), intent(in) :: comments(:)
        !> Number of columns of every row.
        integer, intent(in) :: n_columns
        !> Set when the file cannot be written (nothing is left behind).
        type(error_type), allocatable, intent(out) :: error

        character(len=512) :: message
        integer :: stat, i

        writer%path = path
        open (newunit=writer%unit, file=path//'.part', status='replace', action='write', iostat=stat, iomsg=message)
        if (stat /= 0) then
            call fatal_error(error, path//': cannot write: '//trim(message))
            return
        end if
        writer%opened = .true.
        write (writer%row_format, '(a,i0,a)') '(', n_columns, '(es24.15e3))'
        do i = 1, size(comments)
            write (writer%unit, '(a)', iostat=stat, iomsg=message) '# '//trim(comments(i))
            if (stat /= 0) exit
        end do
        if (stat /= 0) call write_failed(writer, message, error)
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

        character(len=512) :: message
        integer :: stat, i

        stat = 0
        do i = 1, size(table, 1)
            write (writer%unit, writer%row_format, iostat=stat, iomsg=message) table(i, :)
            if (stat /= 0) exit
        end do
        if (stat /= 0) then
            call write_failed(writer, message, error)
            return
        end if
        writer%rows = writer%rows + size(table, 1)
    end subroutine append_rows

    !> Finish a column file: close `path.part` and rename it to `path`.
    subroutine close_columns(writer, error)
        !> The file being written; closed on return.
        type(column_writer), intent(inout) :: writer
        !> Set when the file cannot be renamed.
        type(error_type), allocatable, intent(out) :: error

        if (.not. writer%opened) return
        close (writer%unit)
        writer%opened = .false.
        if (c_rename(writer%path//'.part'//c_null_char, writer%path//c_null_char) /= 0) then
            call fatal_error(error, writer%path//': cannot rename '//writer%path//'.part to it')
        end if
    end subroutine close_columns

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

    !> Abandon a column file: close and delete `path.part` (for a run stopped by bad input).
    subroutine discard_columns(writer)
        !> The file being written; closed on return.
        type(column_writer), intent(inout) :: writer

        if (.not. writer%opened) return
        close (writer%unit, status='delete')
        writer%opened = .false.
    end subroutine discard_columns

    !> A write failed: delete the partial file and say why.
    subroutine write_failed(writer, message, error)
        type(column_writer), intent(inout) :: writer
        character(len=*), intent(in) :: message
        type(error_type), allocatable, intent(out) :: error

        call discard_columns(writer)
        call fatal_error(error, writer%path//': write failed: '//trim(message))
    end subroutine write_failed

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

end module greenconv_io_files
