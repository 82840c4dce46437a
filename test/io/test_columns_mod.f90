!> The text readers of greenconv_io_columns, on files written here byte by byte: `read_columns`
!> gives the numbers written and the line each stands on, past comments, blank lines, tabs and
!> a UTF-8 byte-order mark, and refuses a bad row at its line; `read_lines` pads the lines to
!> the longest; both refuse a line longer than `max_line_length` at that line.
module test_columns_mod
    use, intrinsic :: iso_fortran_env, only: dp => real64
    use testsuite_mod, only: test_error, unittest_type, new_unittest, check
    use greenconv_core_error, only: error_type
    use greenconv_io_files, only: make_directory
    use greenconv_io_columns, only: read_columns, read_lines, max_line_length, byte_order_mark
    implicit none
    private

    public :: collect_columns

    !> Scratch directory of these tests.
    character(len=*), parameter :: scratch = 'build/test_scratch/columns'
    !> A line end.
    character(len=*), parameter :: nl = new_line('a')

contains

    !> Tests of the column and text readers.
    subroutine collect_columns(testsuite)
        !> The suite's tests.
        type(unittest_type), allocatable, intent(out) :: testsuite(:)

        testsuite = [new_unittest('read_columns: the numbers and their lines, past comments and a BOM', &
                                  test_columns), &
                     new_unittest('read_columns: a bad row refused at its line', test_bad_row), &
                     new_unittest('read_lines: lines padded to the longest, the BOM skipped', test_lines), &
                     new_unittest('a line longer than max_line_length refused at its line', test_long_line)]
    end subroutine collect_columns

    subroutine test_columns(error)
        type(test_error), allocatable, intent(out) :: error

        type(error_type), allocatable :: read_error
        real(dp), allocatable :: table(:, :)
        integer, allocatable :: line_of(:)

        call write_bytes('table.dat', byte_order_mark//'# x height'//nl//nl//'0.0 1.5e-3'//nl//'   '//nl &
                         //'# a comment'//nl//achar(9)//'2.5'//achar(9)//'-4.0'//nl//'1e1 0'//nl)
        call read_columns(scratch//'/table.dat', ['x     ', 'height'], ['m', 'm'], table, line_of, read_error)
        call check(error, .not. allocated(read_error), 'refused a good file')
        if (allocated(error)) return
        call check(error, all(shape(table) == [3, 2]) .and. size(line_of) == 3, 'expected 3 rows of 2 columns')
        if (allocated(error)) return
        call check(error, all(table(:, 1) == [0.0_dp, 2.5_dp, 10.0_dp]) .and. &
                   all(table(:, 2) == [1.5e-3_dp, -4.0_dp, 0.0_dp]) .and. all(line_of == [3, 6, 7]), &
                   'numbers or lines differ from those written')
    end subroutine test_columns

    subroutine test_bad_row(error)
        type(test_error), allocatable, intent(out) :: error

        type(error_type), allocatable :: read_error
        real(dp), allocatable :: table(:, :)
        integer, allocatable :: line_of(:)

        call write_bytes('bad.dat', '# x height'//nl//'0 1'//nl//nl//'1 2 3'//nl//'2 abc'//nl)
        call read_columns(scratch//'/bad.dat', ['x     ', 'height'], ['m', 'm'], table, line_of, read_error)
        call check(error, allocated(read_error), 'a row of 3 numbers is accepted')
        if (allocated(error)) return
        call check(error, read_error%stat == 2 .and. index(read_error%message, scratch//'/bad.dat:4: expected 2 ' &
                                                           //'columns') == 1, 'bad row: '//read_error%message)
    end subroutine test_bad_row

    subroutine test_lines(error)
        type(test_error), allocatable, intent(out) :: error

        type(error_type), allocatable :: read_error
        character(len=:), allocatable :: lines(:)

        call write_bytes('text.txt', byte_order_mark//'ab'//nl//nl//'a longer line'//nl//'c  '//nl)
        call read_lines(scratch//'/text.txt', 'text file', lines, read_error)
        call check(error, .not. allocated(read_error), 'refused a good file')
        if (allocated(error)) return
        call check(error, len(lines) == len('a longer line') .and. size(lines) == 4, 'expected 4 lines of 13')
        if (allocated(error)) return
        call check(error, lines(1) == 'ab' .and. lines(2) == '' .and. lines(3) == 'a longer line' .and. &
                   lines(4) == 'c', 'lines differ from those written')
    end subroutine test_lines

    subroutine test_long_line(error)
        type(test_error), allocatable, intent(out) :: error

        type(error_type), allocatable :: read_error
        real(dp), allocatable :: table(:, :)
        integer, allocatable :: line_of(:)
        character(len=:), allocatable :: lines(:)

        call write_bytes('long.dat', '0 1'//nl//repeat('1', 2*max_line_length)//nl//'2 3'//nl)
        call read_columns(scratch//'/long.dat', ['x     ', 'height'], ['m', 'm'], table, line_of, read_error)
        call check(error, allocated(read_error), 'read_columns accepts a long line')
        if (allocated(error)) return
        call check(error, index(read_error%message, scratch//'/long.dat:2: expected lines of at most') == 1, &
                   'read_columns: '//read_error%message(:min(200, len(read_error%message))))
        if (allocated(error)) return
        call read_lines(scratch//'/long.dat', 'text file', lines, read_error)
        call check(error, allocated(read_error), 'read_lines accepts a long line')
        if (allocated(error)) return
        call check(error, index(read_error%message, scratch//'/long.dat:2: expected lines of at most') == 1, &
                   'read_lines: '//read_error%message(:min(200, len(read_error%message))))
    end subroutine test_long_line

    !> Write `text` as the file scratch/name, byte for byte.
    subroutine write_bytes(name, text)
        character(len=*), intent(in) :: name, text

        type(error_type), allocatable :: dir_error
        integer :: unit

        call make_directory(scratch, dir_error)
        open (newunit=unit, file=scratch//'/'//name, status='replace', action='write', access='stream', &
              form='unformatted')
        write (unit) text
        close (unit)
    end subroutine write_bytes

end module test_columns_mod
