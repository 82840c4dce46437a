!> Output files that are either complete or absent: column data is written to a
!> temporary file beside the target and renamed over it only when fully written.
module files_mod
    use, intrinsic :: iso_c_binding, only: c_char, c_int, c_null_char
    use kinds_mod, only: dp
    use error_mod, only: error_type, fatal_error
    implicit none
    private

    public :: write_columns, make_directory

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

        character(len=:), allocatable :: temporary
        character(len=32) :: row_format
        character(len=512) :: message
        integer :: unit, stat, i

        temporary = path//'.part'
        open (newunit=unit, file=temporary, status='replace', action='write', iostat=stat, iomsg=message)
        if (stat /= 0) then
            call fatal_error(error, path//': cannot write: '//trim(message))
            return
        end if
        do i = 1, size(comments)
            write (unit, '(a)', iostat=stat, iomsg=message) '# '//trim(comments(i))
            if (stat /= 0) exit
        end do
        write (row_format, '(a,i0,a)') '(', size(table, 2), '(es24.15e3))'
        if (stat == 0) then
            do i = 1, size(table, 1)
                write (unit, row_format, iostat=stat, iomsg=message) table(i, :)
                if (stat /= 0) exit
            end do
        end if
        if (stat /= 0) then
            close (unit, status='delete')
            call fatal_error(error, path//': write failed: '//trim(message))
            return
        end if
        close (unit)
        if (c_rename(temporary//c_null_char, path//c_null_char) /= 0) then
            call fatal_error(error, path//': cannot rename '//temporary//' to it')
        end if
    end subroutine write_columns

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

end module files_mod
