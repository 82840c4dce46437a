!> The column writer (greenconv_io_files) and the scene's `output_format`: text rows read back
!> as the very doubles that were written, binary rows (little-endian float64) read back with
!> stream access as the same doubles, and a scene run in both formats gives equal numbers,
!> with decimation and the divergence rule as for text.
module test_writer_mod
    use, intrinsic :: iso_fortran_env, only: dp => real64, int64
    use testsuite_mod, only: test_error, unittest_type, new_unittest, check, note
    use scene_text_mod, only: tab1_scene, read_scene_text
    use greenconv_core_random, only: random_stream
    use greenconv_io_files, only: column_writer, open_columns, append_rows, close_columns, make_directory, &
                                  binary_header
    use greenconv_api_all, only: scene_type, run_scene, error_type, stat_numerical
    implicit none
    private

    public :: collect_writer

    !> Scratch directory of these tests.
    character(len=*), parameter :: scratch = 'build/test_scratch/writer'
    !> Rows of the random table: 5 columns of 25 characters, about 8 MB of text, eight times
    !> the writer's buffer.
    integer, parameter :: n_rows = 60000, n_columns = 5

contains

    !> Tests of the column writer's text and binary output.
    subroutine collect_writer(testsuite)
        type(unittest_type), allocatable, intent(out) :: testsuite(:)

        testsuite = [new_unittest('writer: text rows in uneven blocks read back bit for bit', test_text_rows), &
                     new_unittest('writer: binary rows read back with stream access bit for bit', test_binary_rows), &
                     new_unittest('writer: a scene in text and in binary, every row equal', test_scene_formats), &
                     new_unittest('writer: a diverged binary run keeps its rows and counts them', test_binary_fault)]
    end subroutine collect_writer

    !> A table of random doubles over the whole range of magnitudes and signs, with ±0.
    function random_table() result(table)
        real(dp), allocatable :: table(:, :)

        type(random_stream) :: stream
        integer :: i, j

        stream = random_stream(23)
        allocate (table(n_rows, n_columns))
        do j = 1, n_columns
            do i = 1, n_rows
                table(i, j) = (stream%uniform() - 0.5_dp)*10.0_dp**int(600.0_dp*stream%uniform() - 300.0_dp)
            end do
        end do
        table(1, 1) = 0.0_dp
        table(2, 1) = -0.0_dp
        table(3, 1) = huge(1.0_dp)
        table(4, 1) = tiny(1.0_dp)/1024.0_dp
    end function random_table

    !> Write `table` to `path` in blocks of 1, 777, 1 and the rest of the rows.
    subroutine write_in_blocks(path, table, binary, error)
        character(len=*), intent(in) :: path
        real(dp), intent(in) :: table(:, :)
        logical, intent(in) :: binary
        type(error_type), allocatable, intent(out) :: error

        type(column_writer) :: writer

        call make_directory(scratch, error)
        if (allocated(error)) return
        call open_columns(writer, path, [character(len=14) :: 'a test table', 'c1 c2 c3 c4 c5'], size(table, 2), error, binary)
        if (.not. allocated(error)) call append_rows(writer, table(1:1, :), error)
        if (.not. allocated(error)) call append_rows(writer, table(2:778, :), error)
        if (.not. allocated(error)) call append_rows(writer, table(779:779, :), error)
        if (.not. allocated(error)) call append_rows(writer, table(780:, :), error)
        if (.not. allocated(error)) call close_columns(writer, error)
    end subroutine write_in_blocks

    !> The numbers of a text column file (`#` lines skipped), row after row; `n` rows read.
    subroutine read_text(path, columns, values, n)
        character(len=*), intent(in) :: path
        integer, intent(in) :: columns
        real(dp), allocatable, intent(out) :: values(:, :)
        integer, intent(out) :: n

        character(len=1024) :: line
        integer :: unit, stat

        allocate (values(0, columns))
        n = 0
        open (newunit=unit, file=path, status='old', action='read', iostat=stat)
        if (stat /= 0) return
        do
            read (unit, '(a)', iostat=stat) line
            if (stat /= 0) exit
            if (line(1:1) == '#') cycle
            n = n + 1
            if (n > size(values, 1)) values = grow(values)
            read (line, *, iostat=stat) values(n, :)
            if (stat /= 0) exit
        end do
        close (unit)
        values = values(1:n, :)
    end subroutine read_text

    !> `values` with room for twice as many rows (at least 1024).
    pure function grow(values) result(bigger)
        real(dp), intent(in) :: values(:, :)
        real(dp), allocatable :: bigger(:, :)

        allocate (bigger(max(2*size(values, 1), 1024), size(values, 2)))
        bigger(1:size(values, 1), :) = values
    end function grow

    !> The rows of a binary column file of `columns` float64 values per row, read with stream
    !> access (this machine is little-endian, as the files are); `n` rows, -1 when unreadable.
    subroutine read_binary(path, columns, values, n)
        character(len=*), intent(in) :: path
        integer, intent(in) :: columns
        real(dp), allocatable, intent(out) :: values(:, :)
        integer, intent(out) :: n

        real(dp), allocatable :: flat(:)
        integer :: unit, stat, bytes

        allocate (values(0, columns))
        n = -1
        open (newunit=unit, file=path, status='old', action='read', access='stream', form='unformatted', &
              iostat=stat)
        if (stat /= 0) return
        inquire (unit=unit, size=bytes)
        allocate (flat(bytes/8))
        read (unit, iostat=stat) flat
        close (unit)
        if (stat /= 0 .or. mod(bytes, 8*columns) /= 0) return
        n = size(flat)/columns
        values = transpose(reshape(flat, [columns, n]))
    end subroutine read_binary

    !> Whether two tables hold the same doubles, bit for bit.
    pure logical function same_bits(a, b)
        real(dp), intent(in) :: a(:, :), b(:, :)

        same_bits = all(shape(a) == shape(b))
        if (same_bits) same_bits = all(transfer(a, 0_int64, size(a)) == transfer(b, 0_int64, size(b)))
    end function same_bits

    !> The row count a binary file's header file gives (`rows: N`), -1 when absent.
    function header_rows(path) result(rows)
        character(len=*), intent(in) :: path
        integer :: rows

        character(len=512) :: line
        integer :: unit, stat

        rows = -1
        open (newunit=unit, file=binary_header(path), status='old', action='read', iostat=stat)
        if (stat /= 0) return
        do
            read (unit, '(a)', iostat=stat) line
            if (stat /= 0) exit
            if (line(1:8) == '# rows: ') read (line(9:), *, iostat=stat) rows
        end do
        close (unit)
    end function header_rows

    !> 60000 rows of random doubles (8 MB of text) in uneven blocks: the header lines come
    !> first and every number reads back as the same bits.
    subroutine test_text_rows(error)
        type(test_error), allocatable, intent(out) :: error

        character(len=*), parameter :: path = scratch//'/random.dat'
        real(dp), allocatable :: table(:, :), back(:, :)
        type(error_type), allocatable :: failure
        character(len=64) :: first_line
        integer :: n, unit

        table = random_table()
        call write_in_blocks(path, table, .false., failure)
        call check(error, .not. allocated(failure), 'written')
        if (allocated(error)) return
        open (newunit=unit, file=path, status='old', action='read')
        read (unit, '(a)') first_line
        close (unit)
        call check(error, first_line == '# a test table', 'header line kept: '//first_line)
        if (allocated(error)) return
        call read_text(path, n_columns, back, n)
        call note('rows read back', real(n, dp))
        call check(error, n == n_rows .and. same_bits(table, back), 'every number reads back bit for bit')
    end subroutine test_text_rows

    !> The same table in binary: the file is 8*5 bytes per row, reads back bit for bit with
    !> stream access, and its header file gives the columns and the row count.
    subroutine test_binary_rows(error)
        type(test_error), allocatable, intent(out) :: error

        character(len=*), parameter :: path = scratch//'/random.bin'
        real(dp), allocatable :: table(:, :), back(:, :)
        type(error_type), allocatable :: failure
        integer :: n

        table = random_table()
        call write_in_blocks(path, table, .true., failure)
        call check(error, .not. allocated(failure), 'written')
        if (allocated(error)) return
        call read_binary(path, n_columns, back, n)
        call check(error, n == n_rows .and. same_bits(table, back), 'every number reads back bit for bit')
        if (allocated(error)) return
        call check(error, header_rows(path) == n_rows, 'the header file counts the rows')
    end subroutine test_binary_rows

    !> Write `text` as a scene file and run it (summary discarded).
    subroutine run_text(name, text, failure)
        character(len=*), intent(in) :: name, text
        type(error_type), allocatable, intent(out) :: failure

        type(scene_type) :: scene
        integer :: unit

        call make_directory(scratch, failure)
        if (allocated(failure)) return
        call read_scene_text(scratch, name, text, scene, failure)
        if (allocated(failure)) return
        open (newunit=unit, status='scratch', action='readwrite')
        call run_scene(scene, unit, failure, 7)
        close (unit)
    end subroutine run_text

    !> The Tab. 1 scene with a row every 3 steps, in text and in binary: the text file's
    !> numbers read back as exactly the doubles of the binary file (the values the run held),
    !> for direct and modal.
    subroutine test_scene_formats(error)
        type(test_error), allocatable, intent(out) :: error

        character(len=*), parameter :: methods(2) = ['direct', 'modal ']
        real(dp), allocatable :: text_rows(:, :), binary_rows(:, :)
        type(error_type), allocatable :: failure
        integer :: k, n_text, n_binary

        call run_text('form_text.nml', tab1_scene(scene="name = 'form', output_dir = '"//scratch &
                      //"', dt = 1.0e-4, n_steps = 2000, output_every = 3"), failure)
        if (.not. allocated(failure)) &
            call run_text('form_binary.nml', tab1_scene(scene="name = 'form', output_dir = '"//scratch &
                          //"', dt = 1.0e-4, n_steps = 2000, output_every = 3, output_format = 'binary'"), failure)
        if (allocated(failure)) then
            call check(error, .false., 'runs: '//failure%message)
            return
        end if
        do k = 1, size(methods)
            call read_text(scratch//'/form_'//trim(methods(k))//'.dat', 5, text_rows, n_text)
            call read_binary(scratch//'/form_'//trim(methods(k))//'.bin', 5, binary_rows, n_binary)
            call check(error, n_text == 667 .and. n_binary == 667 .and. same_bits(text_rows, binary_rows), &
                       trim(methods(k))//': 667 rows, text and binary equal bit for bit')
            if (allocated(error)) return
            call check(error, header_rows(scratch//'/form_'//trim(methods(k))//'.bin') == 667, &
                       trim(methods(k))//': the header file counts 667 rows')
            if (allocated(error)) return
        end do
    end subroutine test_scene_formats

    !> The stiff linear contact that diverges at step 97 (doc/methods.md), in binary: the run is
    !> stopped, its .bin holds steps 0..96, the header file says 97 rows, no .part is left.
    subroutine test_binary_fault(error)
        type(test_error), allocatable, intent(out) :: error

        character(len=*), parameter :: path = scratch//'/stiff_modal.bin'
        real(dp), allocatable :: rows(:, :)
        type(error_type), allocatable :: failure
        integer :: n
        logical :: part_left

        call run_text('stiff_binary.nml', tab1_scene(scene="name = 'stiff', output_dir = '"//scratch &
                      //"', dt = 1.0e-4, n_steps = 2000, output_format = 'binary'", &
                      contact='stiffness = 1.0e9, exponent = 1.0', convolution="methods = 'modal'"), failure)
        call check(error, allocated(failure), 'the stiff run is stopped')
        if (allocated(error)) return
        call check(error, failure%stat == stat_numerical .and. index(failure%message, 'diverged at step 97') > 0 &
                   .and. index(failure%message, 'rows up to then in '//path) > 0, 'message: '//failure%message)
        if (allocated(error)) return
        call read_binary(path, 5, rows, n)
        inquire (file=path//'.part', exist=part_left)
        call check(error, n == 97 .and. header_rows(path) == 97 .and. .not. part_left, &
                   'steps 0..96 in the .bin, counted by its header file')
    end subroutine test_binary_fault

end module test_writer_mod
