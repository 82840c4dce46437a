!> The cost of writing rows of results: 200000 rows of five doubles, as a long scene writes
!> them, by
!>
!> - `formatted`: one formatted WRITE per row with the writer's format (5(es24.15e3)), as
!>   greenconv_io_files's `append_rows` does today;
!> - `real_text`: rows laid out by greenconv_core_real_text's `real_rows_text` in a buffer of
!>   4096 rows, written with stream access in one WRITE per block (17 digits, exact);
!> - `binary`: the same blocks as little-endian float64 rows, with stream access;
!> - the anchor, bench/anchor/printf_rows.c: a C program writing the same rows with printf("%.16e"),
!>   run by this benchmark when its path is given, timing itself.
!>
!> Seconds are wall-clock seconds of open, write and close; the rows are computed outside the
!> timed part, except in the C program (sin and cos, about 5 % of its time). Then the text
!> file is read back and compared with the binary one bit for bit.
module bench_output_mod
    use, intrinsic :: iso_fortran_env, only: int64
    use greenconv_core_kinds, only: dp
    use greenconv_core_error, only: error_type, fatal_error
    use greenconv_core_real_text, only: real_rows_text, rows_text_length
    implicit none
    private

    public :: output_table

    !> Number of columns of the rows.
    integer, parameter :: n_columns = 5
    !> Rows per block of the stream writes.
    integer, parameter :: block_rows = 4096

contains

    !> Print rows/s of the three ways of writing and, with `anchor`, of the C printf program
    !> and the ratios of times to it.
    subroutine output_table(unit, output_dir, error, n_rows, anchor)
        !> Unit the table is printed on.
        integer, intent(in) :: unit
        !> Directory of the files written.
        character(len=*), intent(in) :: output_dir
        !> Set when a file cannot be written or read back.
        type(error_type), allocatable, intent(out) :: error
        !> Number of rows (200000 when absent).
        integer, intent(in), optional :: n_rows
        !> Path of the compiled bench/anchor/printf_rows.c; no anchor when absent or ''.
        character(len=*), intent(in), optional :: anchor

        real(dp), allocatable :: table(:, :)
        real(dp) :: t_formatted, t_text, t_binary, t_printf
        integer :: rows, n

        rows = 200000
        if (present(n_rows)) rows = n_rows
        allocate (table(0:rows - 1, n_columns))
        do n = 0, rows - 1
            table(n, :) = row_values(n)
        end do
        t_formatted = formatted_seconds(table, output_dir//'/rows_formatted.dat', error)
        if (allocated(error)) return
        t_text = text_seconds(table, output_dir//'/rows_text.dat', error)
        if (allocated(error)) return
        t_binary = binary_seconds(table, output_dir//'/rows_binary.bin', error)
        if (allocated(error)) return
        call compare_files(output_dir//'/rows_text.dat', output_dir//'/rows_binary.bin', rows, error)
        if (allocated(error)) return
        write (unit, '(a,i0,a,i0,a)') '# Output: ', rows, ' rows of ', n_columns, ' doubles (wall-clock seconds of ' &
            //'open, write, close); the text file read back equals the binary one bit for bit'
        write (unit, '(a)') '# way                    seconds        rows_per_s'
        call print_line(unit, 'formatted WRITE', t_formatted, rows)
        call print_line(unit, 'real_text + stream', t_text, rows)
        call print_line(unit, 'binary float64 stream', t_binary, rows)
        t_printf = 0.0_dp
        if (present(anchor)) then
            if (len_trim(anchor) > 0) call run_anchor(anchor, output_dir, rows, t_printf, error)
            if (allocated(error)) return
        end if
        if (t_printf > 0.0_dp) then
            call print_line(unit, 'C printf("%.16e")', t_printf, rows)
            write (unit, '(a,3(f0.3,a))') '# time / printf time: formatted WRITE ', t_formatted/t_printf, &
                ', real_text ', t_text/t_printf, ', binary ', t_binary/t_printf, ' (target: real_text < 0.5)'
        end if
        write (unit, '(a)') ''
    end subroutine output_table

    !> Row n of the benchmark's table (bench/anchor/printf_rows.c computes the same).
    pure function row_values(n) result(v)
        integer, intent(in) :: n
        real(dp) :: v(n_columns)

        real(dp) :: t

        t = n*1.0e-5_dp
        v(1) = t
        v(2) = 1.0e-3_dp*sin(100.0_dp*t)
        v(3) = 2.0e-4_dp*cos(37.0_dp*t)
        v(4) = 3000.0_dp + 500.0_dp*sin(50.0_dp*t)
        v(5) = 1.0e-3_dp*cos(10.0_dp*t) - 5.0e-4_dp
    end function row_values

    !> One line of the table.
    subroutine print_line(unit, label, seconds, rows)
        integer, intent(in) :: unit, rows
        character(len=*), intent(in) :: label
        real(dp), intent(in) :: seconds

        write (unit, '(a,t24,f10.4,4x,es12.3)') label, seconds, rows/max(seconds, 1.0e-9_dp)
    end subroutine print_line

    !> Wall-clock seconds since an arbitrary origin.
    function wall_seconds() result(seconds)
        real(dp) :: seconds

        integer(int64) :: count, rate

        call system_clock(count, rate)
        seconds = real(count, dp)/real(rate, dp)
    end function wall_seconds

    !> One formatted WRITE per row, as the column writer does today.
    function formatted_seconds(table, path, error) result(seconds)
        real(dp), intent(in) :: table(0:, :)
        character(len=*), intent(in) :: path
        type(error_type), allocatable, intent(out) :: error
        real(dp) :: seconds

        integer :: file, stat, n

        seconds = wall_seconds()
        open (newunit=file, file=path, status='replace', action='write', iostat=stat)
        if (stat /= 0) then
            call fatal_error(error, 'output benchmark: cannot write '//path)
            return
        end if
        do n = 0, size(table, 1) - 1
            write (file, '(5(es24.15e3))') table(n, :)
        end do
        close (file)
        seconds = wall_seconds() - seconds
    end function formatted_seconds

    !> Blocks of rows laid out by `real_rows_text`, one stream WRITE per block.
    function text_seconds(table, path, error) result(seconds)
        real(dp), intent(in) :: table(0:, :)
        character(len=*), intent(in) :: path
        type(error_type), allocatable, intent(out) :: error
        real(dp) :: seconds

        character(len=:), allocatable :: text
        integer :: file, first, last, length

        seconds = wall_seconds()
        allocate (character(len=rows_text_length(block_rows, size(table, 2))) :: text)
        call open_stream(path, file, error)
        if (allocated(error)) return
        do first = 0, size(table, 1) - 1, block_rows
            last = min(first + block_rows, size(table, 1)) - 1
            call real_rows_text(table(first:last, :), text, length)
            write (file) text(1:length)
        end do
        close (file)
        seconds = wall_seconds() - seconds
    end function text_seconds

    !> Blocks of rows as float64, row after row, one stream WRITE per block.
    function binary_seconds(table, path, error) result(seconds)
        real(dp), intent(in) :: table(0:, :)
        character(len=*), intent(in) :: path
        type(error_type), allocatable, intent(out) :: error
        real(dp) :: seconds

        integer :: file, first, last

        seconds = wall_seconds()
        call open_stream(path, file, error)
        if (allocated(error)) return
        do first = 0, size(table, 1) - 1, block_rows
            last = min(first + block_rows, size(table, 1)) - 1
            write (file) transpose(table(first:last, :))
        end do
        close (file)
        seconds = wall_seconds() - seconds
    end function binary_seconds

    !> Open a new file for stream writes.
    subroutine open_stream(path, file, error)
        character(len=*), intent(in) :: path
        integer, intent(out) :: file
        type(error_type), allocatable, intent(out) :: error

        integer :: stat

        open (newunit=file, file=path, status='replace', action='write', access='stream', form='unformatted', &
              iostat=stat)
        if (stat /= 0) call fatal_error(error, 'output benchmark: cannot write '//path)
    end subroutine open_stream

    !> Run the C anchor on the same rows and read the seconds it prints.
    subroutine run_anchor(anchor, output_dir, rows, seconds, error)
        character(len=*), intent(in) :: anchor, output_dir
        integer, intent(in) :: rows
        real(dp), intent(out) :: seconds
        type(error_type), allocatable, intent(out) :: error

        character(len=32) :: count
        integer :: status, file, stat

        seconds = 0.0_dp
        write (count, '(i0)') rows
        call execute_command_line(anchor//' '//output_dir//'/rows_printf.dat '//trim(count)//' > ' &
                                  //output_dir//'/rows_printf.seconds', exitstat=status)
        if (status /= 0) then
            call fatal_error(error, 'output benchmark: the anchor '//anchor//' failed: compile ' &
                             //'bench/anchor/printf_rows.c (bash bench/output_bench.sh does)')
            return
        end if
        open (newunit=file, file=output_dir//'/rows_printf.seconds', status='old', action='read', iostat=stat)
        if (stat == 0) read (file, *, iostat=stat) seconds
        if (stat == 0) close (file)
        if (stat /= 0) call fatal_error(error, 'output benchmark: no seconds from the anchor '//anchor)
    end subroutine run_anchor

    !> The text file read back equals the binary file bit for bit.
    subroutine compare_files(text_path, binary_path, rows, error)
        character(len=*), intent(in) :: text_path, binary_path
        integer, intent(in) :: rows
        type(error_type), allocatable, intent(out) :: error

        real(dp) :: from_text(n_columns), from_binary(n_columns)
        integer :: text_file, binary_file, n, stat

        open (newunit=text_file, file=text_path, status='old', action='read', iostat=stat)
        if (stat == 0) open (newunit=binary_file, file=binary_path, status='old', action='read', &
                             access='stream', form='unformatted', iostat=stat)
        do n = 1, rows
            if (stat /= 0) exit
            read (text_file, *, iostat=stat) from_text
            if (stat == 0) read (binary_file, iostat=stat) from_binary
            if (stat == 0 .and. any(transfer(from_text, 0_int64, n_columns) /= &
                                    transfer(from_binary, 0_int64, n_columns))) stat = -1
        end do
        if (stat /= 0) then
            call fatal_error(error, 'output benchmark: the text rows do not read back as the binary rows')
            return
        end if
        close (text_file)
        close (binary_file)
    end subroutine compare_files

end module bench_output_mod
