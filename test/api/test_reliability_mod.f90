!> Reliability: a failed run is never reported as a success. Output files are
!> complete or absent (a full disk, a planted symlink, two writers of one file), `--check`
!> refuses an output directory a run cannot write, and the other cases below.
module test_reliability_mod
    use, intrinsic :: iso_c_binding, only: c_char, c_int, c_null_char
    use, intrinsic :: iso_fortran_env, only: dp => real64, int64
    use testsuite_mod, only: test_error, unittest_type, new_unittest, check, note
    use scene_text_mod, only: tab1_scene, read_scene_text, write_text, feed_fifo
    use greenconv_io_files, only: make_directory, column_writer, open_columns, append_rows, close_columns, &
                                  write_columns
    use greenconv_core_text, only: sci_text, real_text, exact_text, int_text
    use greenconv_core_number_text, only: compact_real
    use greenconv_api_all, only: scene_type, error_type, run_scene, check_scene, read_scene
    use greenconv_io_columns, only: read_columns
    use, intrinsic :: ieee_arithmetic, only: ieee_is_nan
    use greenconv_api_all, only: convolver, new_convolver, structure_from_modes, sdof_modes, structure_model, &
                                 structure_from_frf, frf_from_modes, lsce_options, free_convolver
    use greenconv_legacy, only: gcsdof, gchist, gcpush, gcfree
    use greenconv_api_all, only: point_modes, multipoint_convolver, modes_from_paper, run_multi_contact, &
                                 multi_contact_response, contact_law
    use greenconv_conv_builder, only: make_multipoint_convolver
    use greenconv_legacy_multi, only: gcmmod, gcmbeg, gcmstp, gcmrun, gcmhis, gcmpsh, gcmfre, gcmplt
    use greenconv_contact_law_power, only: power_law
    implicit none
    private

    public :: collect_reliability

    !> Scratch directory for the files the tests write.
    character(len=*), parameter :: scratch = 'build/test_scratch/reliability'

    interface
        !> C library symlink(2).
        function c_symlink(target, link) bind(c, name='symlink') result(stat)
            import :: c_char, c_int
            implicit none
            character(kind=c_char), intent(in) :: target(*), link(*)
            integer(c_int) :: stat
        end function c_symlink

        !> C library getpid(2).
        function c_getpid() bind(c, name='getpid') result(pid)
            import :: c_int
            implicit none
            integer(c_int) :: pid
        end function c_getpid
    end interface

contains

    !> Tests of the reliability suite.
    subroutine collect_reliability(testsuite)
        type(unittest_type), allocatable, intent(out) :: testsuite(:)

        testsuite = [new_unittest('full disk: status 2 naming the file, no file left', test_full_disk), &
                     new_unittest('planted .part symlinks are never followed', test_planted_symlink), &
                     new_unittest('two writers of one file: the last whole file wins', test_two_writers), &
                     new_unittest('--check refuses an output_dir a run cannot write', test_check_output_dir), &
                     new_unittest('three-digit exponents printed as numbers', test_three_digit_exponents), &
                     new_unittest('scene from a FIFO, read once', test_scene_fifo), &
                     new_unittest('scene with a byte-order mark, CR-only line ends, 1e-300', test_scene_text_forms), &
                     new_unittest('long lines read in linear time; over 1 MiB refused at once', test_long_lines), &
                     new_unittest('direct/fft past a cut kernel: NaN (Fortran), refused (F77); xi = 0', &
                                  test_cut_kernel), &
                     new_unittest('wrap-around: direct/fft refused, auto picks the modes', test_wrapped_g), &
                     new_unittest('an input where an output goes: refused by run and --check, kept', &
                                  test_input_kept), &
                     new_unittest('several points past a cut kernel: refused (Fortran, F77), NaN history', &
                                  test_cut_kernel_multi), &
                     new_unittest('tyre_plate on a coarse road: the message names &structure f_modes', &
                                  test_band_message)]
    end subroutine collect_reliability

    !> Number of names in a directory matching a shell pattern (0 when none).
    integer function count_files(directory, pattern)
        character(len=*), intent(in) :: directory, pattern

        integer :: unit, stat

        call execute_command_line('ls -A '//directory//' | grep -c -e '''//pattern//''' > '//scratch &
                                  //'/count.txt 2>/dev/null || true')
        count_files = -1
        open (newunit=unit, file=scratch//'/count.txt', status='old', action='read', iostat=stat)
        if (stat /= 0) return
        read (unit, *, iostat=stat) count_files
        close (unit, status='delete')
    end function count_files

    !> A run onto a 64 KiB file system (a tmpfs mounted for the test; skipped with a note when
    !> mount is not allowed): status 2, the file and the reason named, no output and no
    !> temporary file left (gfortran's own I/O reported success here and left a cut file).
    subroutine test_full_disk(error)
        type(test_error), allocatable, intent(out) :: error

        character(len=*), parameter :: mount_point = scratch//'/full'
        type(scene_type) :: scene
        type(error_type), allocatable :: run_error
        integer :: status, sink

        call make_directory(mount_point, run_error)
        call execute_command_line('mount -t tmpfs -o size=64k tmpfs '//mount_point//' 2>/dev/null', &
                                  exitstat=status)
        if (status /= 0) then
            call note('skipped', 0.0_dp)
            return
        end if
        call read_scene_text(scratch, 'full.nml', tab1_scene(scene="dt = 1.0e-4, n_steps = 2000, output_dir = '" &
                                                              //mount_point//"/out'"), scene, run_error)
        if (.not. allocated(run_error)) then
            open (newunit=sink, file='/dev/null', action='write')
            call run_scene(scene, sink, run_error)
            close (sink)
        end if
        call check(error, allocated(run_error), 'a run onto a full disk reported success')
        if (.not. allocated(error)) then
            call check(error, run_error%stat == 2 .and. index(run_error%message, mount_point//'/out/') > 0 &
                       .and. index(run_error%message, 'No space left') > 0, &
                       'status 2, the file and the reason: '//run_error%message)
        end if
        if (.not. allocated(error)) then
            call check(error, count_files(mount_point//'/out', '.') == 0, &
                       'files left on the full disk after a failed write')
        end if
        call execute_command_line('umount '//mount_point)
    end subroutine test_full_disk

    !> Symlinks planted under the old temporary name and under every name this process could
    !> choose next: the writer writes none of their targets and leaves a regular output file.
    subroutine test_planted_symlink(error)
        type(test_error), allocatable, intent(out) :: error

        character(len=*), parameter :: target = scratch//'/target.txt', output = scratch//'/planted.dat'
        character(len=64) :: suffix
        type(error_type), allocatable :: write_error
        character(len=32) :: line
        integer :: n, unit, stat

        call make_directory(scratch, write_error)
        call execute_command_line('rm -f '//output//'*')
        call write_text(target, 'secret')
        stat = c_symlink('target.txt'//c_null_char, output//'.part'//c_null_char)
        do n = 1, 5000
            write (suffix, '(a,i0,a,i0,a)') '.', c_getpid(), '.', n, '.part'
            stat = c_symlink('target.txt'//c_null_char, output//trim(suffix)//c_null_char)
        end do
        call write_columns(output, ['t'], reshape([1.0_dp, 2.0_dp], [2, 1]), write_error)
        call check(error, .not. allocated(write_error), 'the writer gave up on planted names')
        if (allocated(error)) return
        open (newunit=unit, file=target, status='old', action='read')
        read (unit, '(a)') line
        close (unit)
        call check(error, line == 'secret', 'the target of a planted symlink was overwritten: '//trim(line))
        if (allocated(error)) return
        call check(error, count_files(scratch, '^planted.dat$') == 1, 'no output file')
        if (allocated(error)) return
        call execute_command_line('test -L '//output, exitstat=stat)
        call check(error, stat /= 0, 'the output is a symlink')
        call execute_command_line('rm -f '//output//'*')
    end subroutine test_planted_symlink

    !> Two writers of one file open at once, their rows interleaved: the file holds the whole
    !> content of the one closed last, not a mix (they shared one temporary file before).
    subroutine test_two_writers(error)
        type(test_error), allocatable, intent(out) :: error

        character(len=*), parameter :: output = scratch//'/shared.dat'
        type(column_writer) :: first, second
        type(error_type), allocatable :: write_error
        real(dp) :: value
        character(len=80) :: line
        integer :: i, unit, stat, rows

        call make_directory(scratch, write_error)
        call open_columns(first, output, ['first'], 1, write_error)
        if (.not. allocated(write_error)) call open_columns(second, output, ['second'], 1, write_error)
        do i = 1, 3000
            if (.not. allocated(write_error)) call append_rows(first, reshape([1.0_dp], [1, 1]), write_error)
            if (.not. allocated(write_error)) call append_rows(second, reshape([2.0_dp], [1, 1]), write_error)
        end do
        if (.not. allocated(write_error)) call append_rows(second, reshape([2.0_dp], [1, 1]), write_error)
        if (.not. allocated(write_error)) call close_columns(first, write_error)
        if (.not. allocated(write_error)) call close_columns(second, write_error)
        call check(error, .not. allocated(write_error), 'two writers of one file failed')
        if (allocated(error)) return
        open (newunit=unit, file=output, status='old', action='read')
        read (unit, '(a)') line
        call check(error, line == '# second', 'header of the last writer expected: '//trim(line))
        rows = 0
        do
            read (unit, *, iostat=stat) value
            if (stat /= 0) exit
            rows = rows + 1
            if (value /= 2.0_dp) exit
        end do
        close (unit)
        if (allocated(error)) return
        call check(error, rows == 3001 .and. stat /= 0, 'rows of one writer only, all of them')
        if (allocated(error)) return
        call check(error, count_files(scratch, '^shared.dat.*part$') == 0, 'a temporary file was left')
    end subroutine test_two_writers

    !> `--check` (check_scene) on an output_dir under a regular file: status 2 naming
    !> &scene output_dir; a writable one (not yet made) still passes and is not created.
    subroutine test_check_output_dir(error)
        type(test_error), allocatable, intent(out) :: error

        type(scene_type) :: scene
        type(error_type), allocatable :: check_error
        integer :: sink
        logical :: made

        call read_scene_text(scratch, 'check_dir.nml', tab1_scene(scene="dt = 1.0e-4, n_steps = 2000, output_dir = '" &
                                                                   //scratch//"/check_dir.nml/out'"), scene, check_error)
        call check(error, .not. allocated(check_error), 'the scene was refused on reading')
        if (allocated(error)) return
        open (newunit=sink, file='/dev/null', action='write')
        call check_scene(scene, sink, check_error)
        call check(error, allocated(check_error), '--check said ok for an output_dir under a file')
        if (.not. allocated(error)) then
            call check(error, check_error%stat == 2 .and. index(check_error%message, 'output_dir') > 0, &
                       'status 2 naming output_dir: '//check_error%message)
        end if
        if (allocated(error)) then
            close (sink)
            return
        end if
        call read_scene_text(scratch, 'check_dir2.nml', tab1_scene(scene="dt = 1.0e-4, n_steps = 2000, output_dir = '" &
                                                                    //scratch//"/not_yet/made'"), scene, check_error)
        if (.not. allocated(check_error)) call check_scene(scene, sink, check_error)
        close (sink)
        call check(error, .not. allocated(check_error), 'a writable output_dir refused')
        if (allocated(error)) return
        inquire (file=scratch//'/not_yet/.', exist=made)
        call check(error, .not. made, '--check created the output directory')
    end subroutine test_check_output_dir

    !> Messages print 1e-300 and 3.15e284 with their `E` (Fortran's ESw.d drops it for a
    !> three-digit exponent, and compact_real read text(-1:-1) then), two-digit ones as before.
    subroutine test_three_digit_exponents(error)
        type(test_error), allocatable, intent(out) :: error

        character(len=*), parameter :: expected(8) = [character(len=12) :: '-1.0E-300', '1.0E-04', '3.15E+284', &
                                                      '1.50E+09', '1.0E-300', '1.5E+09', '1.E-300', '1.E-02']
        character(len=12) :: actual(8)
        integer :: i

        actual = [character(len=12) :: compact_real(-1.0e-300_dp), compact_real(1.0e-4_dp), sci_text(3.15e284_dp), &
                  sci_text(1.5e9_dp), real_text(1.0e-300_dp), real_text(1.5e9_dp), exact_text(1.0e-300_dp), &
                  exact_text(0.01_dp)]
        do i = 1, size(expected)
            call check(error, actual(i) == expected(i), 'expected '//trim(expected(i))//', got '//trim(actual(i)))
            if (allocated(error)) return
        end do
    end subroutine test_three_digit_exponents

    !> A scene read from a FIFO with one writer: read once (it used to be opened twice, the
    !> second open waiting for a writer that never came, and rewound, which a pipe cannot do).
    subroutine test_scene_fifo(error)
        type(test_error), allocatable, intent(out) :: error

        character(len=*), parameter :: fifo = scratch//'/scene.fifo'
        type(scene_type) :: scene
        type(error_type), allocatable :: read_error
        logical :: made

        call feed_fifo(fifo, 'data/sdof_sine.nml', made)
        if (.not. made) then
            call note('skipped', 0.0_dp)
            return
        end if
        call read_scene(fifo, scene, read_error)
        if (allocated(read_error)) then
            call check(error, .false., 'a scene from a FIFO refused: '//read_error%message)
            return
        end if
        call check(error, scene%n_steps == 2000 .and. scene%name == 'sdof_sine', 'the FIFO scene read wrong')
        call execute_command_line('rm -f '//fifo)
    end subroutine test_scene_fifo

    !> A UTF-8 byte-order mark is skipped; CR-only line ends read with the right line numbers;
    !> 1e-300 read and shown in a message as -1.0E-300.
    subroutine test_scene_text_forms(error)
        type(test_error), allocatable, intent(out) :: error

        character(len=*), parameter :: cr = achar(13), bom = achar(239)//achar(187)//achar(191)
        type(scene_type) :: scene
        type(error_type), allocatable :: read_error
        character(len=:), allocatable :: text
        integer :: i

        call read_scene_text(scratch, 'bom.nml', bom//tab1_scene(), scene, read_error)
        call check(error, .not. allocated(read_error), 'a byte-order mark refused')
        if (allocated(error)) return
        text = tab1_scene(contact='stiffness = 1.0e6, exponent = -1.5')
        do i = 1, len(text)
            if (text(i:i) == new_line('a')) text(i:i) = cr
        end do
        call read_scene_text(scratch, 'cr.nml', text, scene, read_error)
        call check(error, allocated(read_error), 'CR-only: a bad exponent accepted')
        if (allocated(error)) return
        call check(error, index(read_error%message, 'cr.nml:4: &contact exponent') > 0, &
                   'CR-only: the line of the mistake: '//read_error%message)
        if (allocated(error)) return
        call read_scene_text(scratch, 'tiny.nml', tab1_scene(road="profile = 'sine', amplitude = 1.0e-300", &
                                                             contact='stiffness = -1.0e-300, exponent = 1.5'), &
                             scene, read_error)
        call check(error, allocated(read_error), 'a negative contact stiffness accepted')
        if (allocated(error)) return
        call check(error, index(read_error%message, 'found -1.0E-300') > 0, &
                   'the value shown with its exponent: '//read_error%message)
    end subroutine test_scene_text_forms

    !> A 1,000,000-character comment line of a road file is read in well under a second (the
    !> line used to grow 256 characters at a time: 2.9 s); a 21 MB file without line ends is
    !> refused at line 1 naming the limit, at once.
    subroutine test_long_lines(error)
        type(test_error), allocatable, intent(out) :: error

        character(len=*), parameter :: long = scratch//'/long_comment.dat', garbage = scratch//'/garbage.dat'
        type(error_type), allocatable :: read_error
        real(dp), allocatable :: table(:, :)
        integer, allocatable :: line_of(:)
        integer(int64) :: start, finish, rate
        integer :: unit
        real(dp) :: seconds

        call make_directory(scratch, read_error)
        open (newunit=unit, file=long, status='replace', action='write')
        write (unit, '(a)') '# '//repeat('x', 1000000)
        write (unit, '(a)') '0.0 1.0'
        write (unit, '(a)') '1.0 2.0'
        close (unit)
        call system_clock(start, rate)
        call read_columns(long, ['x     ', 'height'], ['m', 'm'], table, line_of, read_error)
        call system_clock(finish)
        seconds = real(finish - start, dp)/real(rate, dp)
        call note('seconds for a 1 MB line', seconds)
        call check(error, .not. allocated(read_error), 'a long comment refused')
        if (allocated(error)) return
        call check(error, size(table, 1) == 2 .and. line_of(2) == 3 .and. seconds < 0.5_dp, &
                   'two rows, quickly (under 0.5 s)')
        if (allocated(error)) return
        call execute_command_line('head -c 21000000 /dev/zero | tr ''\000'' ''a'' > '//garbage)
        call system_clock(start, rate)
        call read_columns(garbage, ['x     ', 'height'], ['m', 'm'], table, line_of, read_error)
        call system_clock(finish)
        seconds = real(finish - start, dp)/real(rate, dp)
        call note('seconds to refuse 21 MB', seconds)
        call check(error, allocated(read_error), 'a 21 MB line accepted')
        if (allocated(error)) return
        call check(error, index(read_error%message, garbage//':1: expected lines of at most 1048576') == 1 &
                   .and. seconds < 1.0_dp, 'refused at line 1 at once: '//read_error%message)
        call execute_command_line('rm -f '//garbage//' '//long)
    end subroutine test_long_lines

    !> A `direct` or `fft` convolver made for 100 steps of a lightly damped mass-spring (its
    !> kernel cut there, g far from decayed): through the Fortran API its history from step
    !> 100 on is NaN (a contact run then stops at that step), through the F77 door the step is
    !> refused with status 2; before, both went on with a short sum, 62-68 % off. xi = 0 is
    !> accepted by GCSDOF for every method, as the driver accepts it.
    subroutine test_cut_kernel(error)
        type(test_error), allocatable, intent(out) :: error

        character(len=*), parameter :: methods(2) = ['direct', 'fft   ']
        class(convolver), allocatable :: conv
        type(error_type), allocatable :: make_error
        character(len=200) :: message
        integer(int64) :: handle
        real(dp) :: u
        integer :: i, n, ierr

        do i = 1, size(methods)
            call new_convolver(trim(methods(i)), structure_from_modes(sdof_modes(1.0_dp, 1.0e4_dp, 0.001_dp)), &
                               1.0e-3_dp, 100, conv, make_error)
            call check(error, .not. allocated(make_error), trim(methods(i))//': not made')
            if (allocated(error)) return
            do n = 0, 99
                u = conv%history()
                if (ieee_is_nan(u)) exit
                call conv%push(merge(1.0_dp, 0.0_dp, n == 0))
            end do
            call check(error, n == 100 .and. ieee_is_nan(conv%history()), &
                       trim(methods(i))//': history finite for steps 0-99 and NaN at step 100')
            if (allocated(error)) return
            call gcsdof(1.0_dp, 1.0e4_dp, 0.001_dp, 1.0e-3_dp, 100, trim(methods(i)), handle, ierr, message)
            do n = 0, 99
                call gchist(handle, u, ierr)
                if (ierr == 0) call gcpush(handle, 0.0_dp, ierr)
                if (ierr /= 0) exit
            end do
            call gchist(handle, u, ierr)
            call check(error, n == 100 .and. ierr == 2, trim(methods(i))//': GCHIST refused at step 100 only')
            call gcfree(handle)
            if (allocated(error)) return
            call gcsdof(1.0_dp, 1.0e4_dp, 0.0_dp, 1.0e-3_dp, 100, trim(methods(i)), handle, ierr, message)
            call check(error, ierr == 0, trim(methods(i))//': GCSDOF refused xi = 0: '//trim(message))
            call gcfree(handle)
            if (allocated(error)) return
        end do
    end subroutine test_cut_kernel

    !> A receptance of a mass-spring with xi = 1e-5 on a 0.25 Hz grid: g has not decayed within
    !> 1/df = 4 s, so its inverse FFT wraps around and `direct`/`fft` on it were 6-20 times off
    !> while the run said 0. Now both are refused with a message naming the cause and the way
    !> out, `auto` picks the identified modes, and `modal` runs.
    subroutine test_wrapped_g(error)
        type(test_error), allocatable, intent(out) :: error

        type(structure_model) :: structure
        type(error_type), allocatable :: make_error
        class(convolver), allocatable :: conv
        character(len=:), allocatable :: description

        call structure_from_frf(frf_from_modes(sdof_modes(1.0_dp, 1.0e4_dp, 1.0e-5_dp), 50.0_dp, 201), &
                                lsce_options(), 0.01_dp, structure, make_error)
        call check(error, .not. allocated(make_error), 'the receptance was not identified')
        if (allocated(error)) return
        call check(error, structure%fit%wrap_around, 'the test receptance does not wrap around')
        if (allocated(error)) return
        call new_convolver('direct', structure, 0.01_dp, 1000, conv, make_error)
        call check(error, allocated(make_error), 'direct on a wrapped g accepted')
        if (allocated(error)) return
        call check(error, make_error%stat == 2 .and. index(make_error%message, 'wrap-around') > 0 .and. &
                   index(make_error%message, 'finer frequency grid') > 0, 'direct: message '//make_error%message)
        if (allocated(error)) return
        call new_convolver('fft', structure, 0.01_dp, 1000, conv, make_error)
        call check(error, allocated(make_error), 'fft on a wrapped g accepted')
        if (allocated(error)) return
        call new_convolver('auto', structure, 0.01_dp, 1000, conv, make_error, description=description)
        call check(error, .not. allocated(make_error), 'auto refused')
        if (allocated(error)) return
        call check(error, index(description, 'chose exact') > 0, 'auto: '//description)
        call free_convolver(conv)
        if (allocated(error)) return
        call new_convolver('modal', structure, 0.01_dp, 1000, conv, make_error)
        call check(error, .not. allocated(make_error), 'modal refused')
        if (allocated(conv)) call free_convolver(conv)
    end subroutine test_wrapped_g

    !> A receptance file named like an output of its own scene (`<output_dir>/<name>_frf.dat`,
    !> the fit the identification writes) is refused by the run and by `--check`, status 2, both
    !> names in the message, and the measurement is left as it was; so is the same file reached
    !> by another spelling (a symbolic link from elsewhere). Another name in that directory runs.
    subroutine test_input_kept(error)
        type(test_error), allocatable, intent(out) :: error

        character(len=*), parameter :: folder = scratch//'/kept', measured = folder//'/id_frf.dat'
        character(len=*), parameter :: linked = scratch//'/kept_link.frf', safe = folder//'/measured.frf'
        character(len=:), allocatable :: before, after
        type(scene_type) :: scene
        type(error_type), allocatable :: run_error
        integer :: sink, stat, pass
        character(len=:), allocatable :: input

        call make_directory(folder, run_error)
        call execute_command_line('cp data/sample_receptance.frf '//measured//' && cp data/sample_receptance.frf ' &
                                  //safe//' && rm -f '//linked, exitstat=stat)
        stat = c_symlink('kept/id_frf.dat'//c_null_char, linked//c_null_char)
        before = file_text(measured)
        open (newunit=sink, file='/dev/null', action='write')
        do pass = 1, 4
            input = linked
            if (pass <= 2) input = measured
            call read_scene_text(scratch, 'kept.nml', "&scene task = 'identify', name = 'id', output_dir = '" &
                                 //folder//"' / &structure model = 'frf_file', frf_file = '"//input &
                                 //"' / &identification method = 'lsce', max_order = 4 /", scene, run_error)
            if (.not. allocated(run_error)) then
                if (mod(pass, 2) == 1) call check_scene(scene, sink, run_error)
                if (mod(pass, 2) == 0) call run_scene(scene, sink, run_error)
            end if
            call check(error, allocated(run_error), 'an input named like an output was accepted ('//input//')')
            if (allocated(error)) exit
            call check(error, run_error%stat == 2 .and. index(run_error%message, 'frf_file') > 0 .and. &
                       index(run_error%message, input) > 0 .and. index(run_error%message, folder//'/id_*') > 0, &
                       'status 2 with both names: '//run_error%message)
            if (allocated(error)) exit
        end do
        close (sink)
        if (allocated(error)) return
        after = file_text(measured)
        call check(error, after == before, 'the measurement was overwritten')
        if (allocated(error)) return
        call read_scene_text(scratch, 'kept.nml', "&scene task = 'identify', name = 'id', output_dir = '" &
                             //folder//"' / &structure model = 'frf_file', frf_file = '"//safe &
                             //"' / &identification method = 'lsce', max_order = 4 /", scene, run_error)
        if (.not. allocated(run_error)) then
            open (newunit=sink, file='/dev/null', action='write')
            call run_scene(scene, sink, run_error)
            close (sink)
        end if
        if (allocated(run_error)) then
            call check(error, .false., 'another name in the output directory: '//run_error%message)
        end if
    end subroutine test_input_kept

    !> A several-point `direct` or `fft` convolver made for 10 steps, its kernel cut there (modes
    !> at 100 and 250 Hz, 5 % damping, dt = 0.1 ms: g has not decayed in 1 ms): the Fortran
    !> library's run of 400 steps is refused before its first step (status 2, naming step 10),
    !> its own history is NaN from step 10 on; the F77 doors refuse step 10 of a stepped run
    !> (GCMSTP), a whole run (GCMRUN) and history and push (GCMHIS, GCMPSH) alike, after
    !> serving steps 0-9. A modal convolver made for 10 steps runs 400.
    subroutine test_cut_kernel_multi(error)
        type(test_error), allocatable, intent(out) :: error

        integer, parameter :: n_c = 3, n_short = 10, n_long = 400
        real(dp), parameter :: dt = 1.0e-4_dp, pi = acos(-1.0_dp)
        character(len=*), parameter :: methods(3) = ['direct', 'fft   ', 'modal ']
        type(point_modes) :: modes
        class(multipoint_convolver), allocatable :: conv
        type(multi_contact_response) :: response
        type(error_type), allocatable :: run_error
        character(len=:), allocatable :: accuracy
        character(len=300) :: message
        real(dp) :: road(n_long, n_c), u(n_long, n_c), f(n_long, n_c), delta(n_long, n_c), u_h(n_c)
        real(dp) :: k_c(n_c), p(n_c), preload(n_c), r_n(n_c), u_n(n_c), f_n(n_c), d_n(n_c)
        integer(int64) :: handle
        integer :: i, n, m, ierr
        logical :: cut

        modes%modes = modes_from_paper([1.0_dp, 1.0_dp], 2.0_dp*pi*[100.0_dp, 250.0_dp], [0.05_dp, 0.05_dp])
        modes%shape = reshape([0.9_dp, 1.0_dp, 0.8_dp, 0.7_dp, -0.1_dp, -0.6_dp], [n_c, 2])
        k_c = 2.0e6_dp
        p = 1.5_dp
        preload = 60.0_dp
        road = reshape([((1.2e-3_dp*sin(2.0_dp*pi*180.0_dp*n*dt - 0.8_dp*i), n=0, n_long - 1), i=0, n_c - 1)], &
                       [n_long, n_c])
        do m = 1, size(methods)
            cut = m <= 2
            call make_multipoint_convolver(trim(methods(m)), modes, dt, 0.01_dp, n_short, conv, accuracy, run_error)
            call check(error, .not. allocated(run_error), trim(methods(m))//': not made')
            if (allocated(error)) return
            call run_multi_contact(conv, [(power_law(k_c(i), p(i)), i=1, n_c)], road, preload, response, run_error)
            if (cut) then
                call check(error, allocated(run_error), trim(methods(m))//': a run of 400 steps accepted')
                if (allocated(error)) return
                call check(error, run_error%stat == 2 .and. index(run_error%message, 'step 10 is past') > 0 .and. &
                           size(response%force, 1) == 0, trim(methods(m))//': '//run_error%message)
            else
                call check(error, .not. allocated(run_error), trim(methods(m))//': a run of 400 steps refused')
            end if
            if (allocated(error)) return
            call conv%reset()
            do n = 0, n_long - 1
                call conv%history(u_h)
                if (any(ieee_is_nan(u_h))) exit
                call conv%push([1.0_dp, 0.0_dp, 0.0_dp])
            end do
            call check(error, n == merge(n_short, n_long, cut), trim(methods(m))//': history finite up to step ' &
                       //int_text(n - 1))
            if (allocated(error)) return
            call gcmmod(n_c, 2, real(modes%modes%pole), aimag(modes%modes%pole), real(modes%modes%residue), &
                        aimag(modes%modes%residue), modes%shape, dt, n_short, 0.01_dp, trim(methods(m)), handle, ierr, &
                        message)
            call check(error, ierr == 0, trim(methods(m))//': GCMMOD: '//trim(message))
            if (allocated(error)) return
            call gcmbeg(handle, n_c, k_c, p, preload, ierr, message)
            do n = 1, n_long
                r_n = road(n, :)
                if (ierr == 0) call gcmstp(handle, n_c, r_n, u_n, f_n, d_n, ierr, message)
                if (ierr /= 0) exit
            end do
            call check(error, n - 1 == merge(n_short, n_long, cut) .and. (ierr == 2 .eqv. cut), trim(methods(m)) &
                       //': GCMSTP served '//int_text(n - 1)//' steps: '//trim(message))
            if (allocated(error)) return
            if (cut) call check(error, index(message, 'gcmstp: step 10 is past') == 1, 'GCMSTP: '//trim(message))
            if (allocated(error)) return
            call gcmrun(handle, n_c, n_long, k_c, p, preload, road, u, f, delta, ierr, message)
            call check(error, (ierr == 2 .and. index(message, 'gcmrun: step 10 is past') == 1 .and. all(f == 0.0_dp)) &
                       .eqv. cut, trim(methods(m))//': GCMRUN of 400 steps: '//trim(message))
            if (allocated(error)) return
            do n = 0, n_long - 1
                call gcmhis(handle, n_c, u_h, ierr, message)
                if (ierr == 0) call gcmpsh(handle, n_c, [1.0_dp, 0.0_dp, 0.0_dp], ierr, message)
                if (ierr /= 0) exit
            end do
            call check(error, n == merge(n_short, n_long, cut) .and. &
                       (index(message, 'gcmhis: step 10') == 1 .eqv. cut), &
                       trim(methods(m))//': GCMHIS/GCMPSH served '//int_text(n)//' steps: '//trim(message))
            call gcmfre(handle)
            if (allocated(error)) return
            call conv%release()
            deallocate (conv)
        end do
    end subroutine test_cut_kernel_multi

    !> A tyre_plate scene on a road sampled every 0.1 m at 1 m/s: the band rule gives
    !> min(2*V/lambda_min, 1/(10*dt)) = 10 Hz, below the belt's first mode, and so does f_modes
    !> = 5 Hz. Both are refused in one line at `&structure f_modes`, the variable that sets the
    !> band (it said "raise f_max", a variable of &identification), the first saying where its
    !> band came from; the C door says f_max (its argument), the F77 door FMAX.
    subroutine test_band_message(error)
        type(test_error), allocatable, intent(out) :: error

        character(len=*), parameter :: road = scratch//'/road_coarse.dat'
        character(len=*), parameter :: head = "&scene name = 'coarse', output_dir = '"//scratch//"', dt = 1.0e-4, " &
            //"n_steps = 100 / &structure model = 'tyre_plate', damping_ratio = 0.05"
        character(len=*), parameter :: tail = " / &road profile = 'file', road_file = '"//road//"', x_start = 2.0, " &
            //"speed = 1.0 / &contact n_points_x = 4, n_points_y = 3, patch_length = 0.12, patch_width = 0.15, " &
            //"stiffness = 1.0e7, exponent = 1.5, preload = 300.0 / &convolution methods = 'modal' /"
        character(len=*), parameter :: settings(2) = [character(len=16) :: '', ', f_modes = 5.0']
        type(scene_type) :: scene
        type(error_type), allocatable :: fail
        real(dp) :: pole_re(1), pole_im(1), res_re(1), res_im(1), shape(1), x(1), y(1)
        character(len=300) :: message
        integer :: unit, j, sink, k, n_modes, ierr

        call make_directory(scratch, fail)
        open (newunit=unit, file=road, status='replace', action='write')
        do j = 0, 100
            write (unit, '(2es16.8)') 0.1_dp*j, 1.0e-3_dp*sin(0.7_dp*j)
        end do
        close (unit)
        open (newunit=sink, file='/dev/null', action='write')
        do k = 1, size(settings)
            call read_scene_text(scratch, 'coarse.nml', head//trim(settings(k))//tail, scene, fail)
            if (.not. allocated(fail)) call check_scene(scene, sink, fail)
            call check(error, allocated(fail), 'a band below the first mode accepted')
            if (allocated(error)) exit
            call check(error, fail%stat == 2 .and. index(fail%message, 'coarse.nml:1: &structure f_modes: plate ' &
                       //'model: no mode below f_modes = ') > 0 .and. index(fail%message, 'raise f_modes') > 0 .and. &
                       index(fail%message, 'f_max') == 0 .and. index(fail%message, new_line('a')) == 0 .and. &
                       ((index(fail%message, 'f_modes = 0 takes the band min(2*V/lambda_min') > 0) .eqv. k == 1), &
                       'one line naming &structure f_modes: '//fail%message)
            if (allocated(error)) exit
        end do
        close (sink)
        if (allocated(error)) return
        call gcmplt(1, 1, 0.1_dp, 0.1_dp, 5.0_dp, 1, n_modes, pole_re, pole_im, res_re, res_im, shape, x, y, ierr, &
                    message)
        call check(error, ierr == 2 .and. index(message, 'gcmplt: plate model: no mode below FMAX = 5') == 1 .and. &
                   index(message, 'raise FMAX') > 0, 'GCMPLT names FMAX: '//trim(message))
    end subroutine test_band_message

    !> The whole text of a file, its lines joined by new lines.
    function file_text(path) result(text)
        character(len=*), intent(in) :: path
        character(len=:), allocatable :: text

        character(len=4096) :: line
        integer :: unit, stat

        text = ''
        open (newunit=unit, file=path, status='old', action='read', iostat=stat)
        if (stat /= 0) return
        do
            read (unit, '(a)', iostat=stat) line
            if (stat /= 0) exit
            text = text//trim(line)//new_line('a')
        end do
        close (unit)
    end function file_text

end module test_reliability_mod
