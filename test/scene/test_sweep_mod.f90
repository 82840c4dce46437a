!> Parameter sweeps (greenconv_scene_sweep): the variants of value lists (cartesian product,
!> last list fastest) and of a table file, how a value is written into the base scene's text
!> (replaced on its line, added to its group, or in a new group), the content key, the
!> table's row, the record's text, and the messages for a bad &sweep group or option. Serial
!> runs of small sweeps: the band level columns against a tone's closed form and against the
!> spectrum of the history file the histories option writes; history files only when asked,
!> named and decimated; the content key following an edited road file; a variant whose
!> method runs outside the accuracy asked (status 4 in its row and of the sweep, a worse
!> status of another variant first). The runs on 1 and
!> 2 MPI ranks, resume and failures are checked by tools/test_sweep.sh (make sweep-test).
module test_sweep_mod
    use, intrinsic :: iso_fortran_env, only: int64
    use testsuite_mod, only: test_error, unittest_type, new_unittest, check
    use scene_text_mod, only: write_text
    use greenconv_core_error, only: error_type, stat_input, stat_accuracy
    use greenconv_core_kinds, only: dp
    use greenconv_io_files, only: make_directory
    use greenconv_io_columns, only: read_line
    use greenconv_io_spectra, only: band_spectrum, band_levels
    use greenconv_scene_sweep, only: sweep_text, sweep_plan, variant_outcome, read_sweep, variant_lines, &
                                     variant_key, summary_row, outcome_text, outcome_from_text, is_sweep_file, &
                                     run_sweep, replaced_all, scene_files, take_variant, variant_ran, variant_bad
    implicit none
    private

    public :: collect_sweep

    !> Scratch directory for the files the tests write.
    character(len=*), parameter :: scratch = 'build/test_scratch/sweep'

contains

    !> Tests of greenconv_scene_sweep.
    subroutine collect_sweep(testsuite)
        type(unittest_type), allocatable, intent(out) :: testsuite(:)

        testsuite = [new_unittest('lists: cartesian product, last list fastest', test_product), &
                     new_unittest('variant text: replaced, added to its group, new group', test_variant_text), &
                     new_unittest('content key: equal texts, one changed character', test_key), &
                     new_unittest('table file: rows are the variants', test_table_file), &
                     new_unittest('summary row and record text', test_row), &
                     new_unittest('bad &sweep group: messages with the line', test_bad_sweep), &
                     new_unittest('band levels: a tone''s closed form, the history''s spectrum', test_spectra), &
                     new_unittest('histories: only when asked, named, decimated, renumbered', test_histories), &
                     new_unittest('&sweep options: bad values and unresolvable bands refused', test_bad_options), &
                     new_unittest('content key: an edited road file reruns its variants', test_file_key), &
                     new_unittest('a road file edited between variants: the later ones refused', test_edited_file), &
                     new_unittest('a variant outside its accuracy: status 4 in its row, the sweep ends 4', &
                                  test_accuracy_status)]
    end subroutine collect_sweep

    !> A small SDOF sweep scene with the given &sweep group.
    function sweep_scene(group) result(text)
        character(len=*), intent(in) :: group
        character(len=:), allocatable :: text

        character(len=*), parameter :: nl = new_line('a')

        text = "&scene task = 'sweep', name = 'unit', output_dir = '"//scratch//"/out', dt = 1.0e-4, n_steps = 200 /" &
               //nl//"&structure model = 'sdof', mass = 1.0, stiffness = 1.0e6, damping_ratio = 0.02 /"//nl &
               //"&road"//nl//"    profile = 'sine'   ! the road"//nl//"    amplitude = 1.0e-3 ! [m]"//nl//"/"//nl &
               //"&contact stiffness = 1.0e6, exponent = 1.5 /"//nl//"&convolution methods = 'direct' /"//nl//group//nl
    end function sweep_scene

    !> Read a sweep written from `text`.
    subroutine read_text(name, text, plan, failure)
        character(len=*), intent(in) :: name, text
        type(sweep_plan), intent(out) :: plan
        type(error_type), allocatable, intent(out) :: failure

        call make_directory(scratch, failure)
        if (allocated(failure)) return
        call write_text(scratch//'/'//name, text)
        call read_sweep(scratch//'/'//name, plan, failure)
    end subroutine read_text

    subroutine test_product(error)
        type(test_error), allocatable, intent(out) :: error

        type(sweep_plan) :: plan
        type(error_type), allocatable :: failure

        call read_text('product.nml', sweep_scene("&sweep"//new_line('a')//"  road.amplitude = 1.0e-3, 2.0e-3, 3.0e-3" &
                       //new_line('a')//"  contact.stiffness = 1.0e6 2.0e6 /"), plan, failure)
        call check(error, .not. allocated(failure), 'the sweep reads')
        if (allocated(error)) return
        call check(error, is_sweep_file(scratch//'/product.nml'), 'it is a sweep file')
        if (allocated(error)) return
        call check(error, size(plan%values, 1) == 6 .and. size(plan%values, 2) == 2, '3 x 2 = 6 variants')
        if (allocated(error)) return
        call check(error, plan%variables(1)%text == 'road.amplitude' .and. plan%variables(2)%text == &
                   'contact.stiffness', 'variables in order')
        if (allocated(error)) return
        call check(error, plan%values(2, 1)%text == '1.0e-3' .and. plan%values(2, 2)%text == '2.0e6' .and. &
                   plan%values(3, 1)%text == '2.0e-3' .and. plan%values(6, 2)%text == '2.0e6', &
                   'the last list varies fastest')
    end subroutine test_product

    subroutine test_variant_text(error)
        type(test_error), allocatable, intent(out) :: error

        type(sweep_plan) :: plan
        type(error_type), allocatable :: failure
        type(sweep_text), allocatable :: lines(:)

        call read_text('text.nml', sweep_scene("&sweep road.amplitude = 5.0e-4, road.omega = 50.0, " &
                       //"identification.order = 3 /"), plan, failure)
        call check(error, .not. allocated(failure), 'the sweep reads')
        if (allocated(error)) return
        lines = variant_lines(plan, 1)
        call check(error, size(lines) == size(plan%base) + 1, 'one line added (the new group)')
        if (allocated(error)) return
        call check(error, lines(5)%text == "    amplitude = 5.0e-4 ! [m]", 'the value replaced, its comment kept: ' &
                   //lines(5)%text)
        if (allocated(error)) return
        call check(error, lines(3)%text == "&road omega = 50.0 ", 'added right after its group''s name: ' &
                   //lines(3)%text)
        if (allocated(error)) return
        call check(error, lines(size(lines))%text == '&identification order = 3 /', 'a new group at the end')
        if (allocated(error)) return
        call check(error, len_trim(lines(9)%text) == 0 .and. index(lines(1)%text, "task = 'contact'") > 0, &
                   'the &sweep line blanked, the task set to contact')
    end subroutine test_variant_text

    subroutine test_key(error)
        type(test_error), allocatable, intent(out) :: error

        type(sweep_text), allocatable :: a(:), b(:)
        character(len=16) :: key

        a = [sweep_text('&scene n_steps = 10 /'), sweep_text('&road speed = 20.0 /')]
        b = a
        key = variant_key(a)
        call check(error, key == variant_key(b) .and. verify(key, '0123456789ABCDEF') == 0, 'equal texts, equal keys')
        if (allocated(error)) return
        b(2)%text = '&road speed = 20.1 /'
        call check(error, key /= variant_key(b), 'one character changed, another key')
        if (allocated(error)) return
        b = [sweep_text('&scene n_steps = 10 /&road'), sweep_text(' speed = 20.0 /')]
        call check(error, key /= variant_key(b), 'line breaks count')
    end subroutine test_key

    subroutine test_table_file(error)
        type(test_error), allocatable, intent(out) :: error

        type(sweep_plan) :: plan
        type(error_type), allocatable :: failure
        character(len=*), parameter :: nl = new_line('a')

        call make_directory(scratch, failure)
        call write_text(scratch//'/design.txt', '# road.amplitude contact.stiffness'//nl//'1.0e-3 1.0e6'//nl//nl &
                        //'# a comment'//nl//'2.0e-3, 4.0e6'//nl)
        call read_text('table.nml', sweep_scene("&sweep table_file = '"//scratch//"/design.txt' /"), plan, failure)
        call check(error, .not. allocated(failure), 'the sweep reads')
        if (allocated(error)) return
        call check(error, size(plan%values, 1) == 2 .and. plan%values(2, 2)%text == '4.0e6', 'two rows, two variants')
        if (allocated(error)) return
        call write_text(scratch//'/design.txt', 'road.amplitude contact.stiffness'//nl//'1.0e-3'//nl)
        call read_text('table.nml', sweep_scene("&sweep table_file = '"//scratch//"/design.txt' /"), plan, failure)
        call check(error, allocated(failure), 'a short row is refused')
        if (allocated(error)) return
        call check(error, index(failure%message, 'design.txt:2: expected 2 values') > 0, failure%message)
    end subroutine test_table_file

    subroutine test_row(error)
        type(test_error), allocatable, intent(out) :: error

        type(sweep_plan) :: plan
        type(error_type), allocatable :: failure
        type(variant_outcome) :: outcome, back
        character(len=:), allocatable :: row
        logical :: ok

        call read_text('row.nml', sweep_scene("&sweep road.amplitude = 1.0e-3, 2.5e-3 /"), plan, failure)
        call check(error, .not. allocated(failure), 'the sweep reads')
        if (allocated(error)) return
        outcome%result = ' 1.0 2.0 3.0 0.5 0 0'
        outcome%cpu = ' 0.0100'
        outcome%status = 3
        outcome%message = 'diverged'
        call summary_row(plan, 2, outcome%result, row)
        call check(error, row == '2        2.5e-3         1.0 2.0 3.0 0.5 0 0', 'the row: '//row)
        if (allocated(error)) return
        call outcome_from_text(outcome_text(outcome), back, ok)
        call check(error, ok .and. back%result == outcome%result .and. back%cpu == outcome%cpu .and. &
                   back%status == 3 .and. back%message == 'diverged', 'the record text reads back')
    end subroutine test_row

    subroutine test_bad_sweep(error)
        type(test_error), allocatable, intent(out) :: error

        type(sweep_plan) :: plan
        type(error_type), allocatable :: failure

        call read_text('bad.nml', sweep_scene("&sweep"//new_line('a')//"road.sped = 1.0 /"), plan, failure)
        call check(error, allocated(failure), 'an unknown variable is refused')
        if (allocated(error)) return
        call check(error, failure%stat == 2 .and. index(failure%message, 'bad.nml:10: &sweep road.sped: expected a ' &
                   //'scene variable') > 0, failure%message)
        if (allocated(error)) return
        call read_text('bad.nml', sweep_scene("&sweep scene.name = 'a', 'b' /"), plan, failure)
        call check(error, allocated(failure), 'scene.name may not vary')
        if (allocated(error)) return
        call read_text('bad.nml', sweep_scene("&sweep road.amplitude = 1.0e-3"), plan, failure)
        call check(error, allocated(failure), 'an unclosed group is refused')
        if (allocated(error)) return
        call read_text('bad.nml', sweep_scene("&sweep road.amplitude = 1.0e-3 /") // "&road profile = 'x' /", &
                       plan, failure)
        call check(error, allocated(failure), 'a bad base scene is refused')
        if (allocated(error)) return
        call check(error, index(failure%message, '(the base scene)') > 0, failure%message)
    end subroutine test_bad_sweep

    !> Band levels against a closed form. A linear contact spring (p = 1, k_c) under a preload
    !> F0 > k_c*A on a sine road A*sin(2*pi*1000 Hz*t) pressing a body so heavy (M = 1e6 kg,
    !> |G| = 1/(M*omega^2) = 2.5e-14 m/N at 1 kHz, k_c*|G| <= 5e-8) that it barely moves: the
    !> total force is F0 + k_c*A*sin(omega*t) to 1e-7 relatively, so the 1 kHz band's level is
    !> 20*log10(k_c*A/sqrt(2)) [dB re 1 N] (56.99 and 63.01 dB for the two variants), within
    !> 1e-3 dB (the spectra module puts a tone at a band centre within 1e-4 dB, the column is
    !> printed to 1e-4 dB); the bands 500 and 2000 Hz hold only the window's leakage, more than
    !> 60 dB below. Then every level column of variant 2 equals greenconv_io_spectra's
    !> band_levels on the force column of the history file the histories option wrote (every
    !> step), within the printing's 1e-4 dB.
    subroutine test_spectra(error)
        type(test_error), allocatable, intent(out) :: error

        type(error_type), allocatable :: failure
        type(band_spectrum) :: spectrum
        character(len=:), allocatable :: text, header, row
        character(len=*), parameter :: nl = new_line('a')
        real(dp), parameter :: amplitude = 1.0e-3_dp
        real(dp), allocatable :: force(:)
        real(dp) :: values(15), exact
        integer :: k

        text = "&scene task = 'sweep', name = 'spectra', output_dir = '"//scratch//"/out', dt = 1.0e-4, " &
               //"n_steps = 2000 /"//nl//"&structure model = 'sdof', mass = 1.0e6, stiffness = 1.0e6, " &
               //"damping_ratio = 0.02 /"//nl//"&road profile = 'sine', amplitude = 1.0e-3, " &
               //"omega = 6283.185307179586 /"//nl//"&contact stiffness = 1.0e6, exponent = 1.0, preload = 5000.0 /" &
               //nl//"&convolution methods = 'direct' /"//nl//"&sweep contact.stiffness = 1.0e6, 2.0e6" &
               //nl//"    spectra = .true., f_low = 500.0, f_high = 2000.0, histories = .true. /"//nl
        call run_fresh('spectra', text, failure)
        call check(error, .not. allocated(failure), 'the sweep runs')
        if (allocated(error)) return
        call table_lines(scratch//'/out/spectra_sweep.dat', header, row, 1)
        call check(error, index(header, ' L500_direct ') > 0 .and. index(header, ' L2000_direct') > 0 .and. &
                   index(header, 'L400') == 0 .and. index(header, 'L2500') == 0, 'columns L500..L2000: '//header)
        if (allocated(error)) return
        ! the row: variant, stiffness, 6 summary columns of the method, then its 7 levels (500..2000 Hz)
        do k = 1, 2
            call table_lines(scratch//'/out/spectra_sweep.dat', header, row, k)
            read (row, *) values
            exact = 20.0_dp*log10(k*1.0e6_dp*amplitude/sqrt(2.0_dp))
            call check(error, abs(values(12) - exact) < 1.0e-3_dp, 'variant '//trim(row(:1))//': the 1 kHz band ' &
                       //'against 20 log10(k_c A/sqrt 2): '//row)
            if (allocated(error)) return
            call check(error, values(9) < exact - 60.0_dp .and. values(15) < exact - 60.0_dp, &
                       'the 500 and 2000 Hz bands hold only leakage: '//row)
            if (allocated(error)) return
        end do
        force = history_column(scratch//'/out/spectra_v2_direct.dat', 4)
        call check(error, size(force) == 2000, 'the history has every step')
        if (allocated(error)) return
        call band_levels(force, 1.0e-4_dp, 490.0_dp, 2050.0_dp, spectrum, failure)
        call check(error, .not. allocated(failure) .and. size(spectrum%level) == 7, 'seven bands 500..2000 Hz')
        if (allocated(error)) return
        call check(error, all(abs(values(9:) - spectrum%level) < 1.0e-4_dp), 'levels as the history''s spectrum: ' &
                   //row)
    end subroutine test_spectra

    !> Histories: written only when asked, named <name>_v<k>_<method>.dat, a row every
    !> output_every steps (times 0, 10 dt, ...), the variant's values in the first header
    !> line; an edit that renumbers the variants reruns them with histories (their files carry
    !> the number) and skips them without.
    subroutine test_histories(error)
        type(test_error), allocatable, intent(out) :: error

        type(error_type), allocatable :: failure
        character(len=:), allocatable :: text, title
        real(dp), allocatable :: time(:)
        logical :: exists
        integer :: r

        text = replaced_all(sweep_scene("&sweep road.amplitude = 1.0e-3, 2.0e-3, histories = .true. /"), &
                        "name = 'unit'", "name = 'hist', output_every = 10")
        call run_fresh('hist', text, failure)
        call check(error, .not. allocated(failure), 'the sweep with histories runs')
        if (allocated(error)) return
        time = history_column(scratch//'/out/hist_v2_direct.dat', 1)
        call check(error, size(time) == 20 .and. all([(abs(time(r) - (r - 1)*1.0e-3_dp) < 1.0e-15_dp, &
                   r=1, size(time))]), 'variant 2: 20 rows at t = 0, 10 dt, ...')
        if (allocated(error)) return
        title = first_line(scratch//'/out/hist_v2_direct.dat')
        call check(error, index(title, 'variant 2 (road.amplitude = 2.0e-3), method direct') > 0, title)
        if (allocated(error)) return
        call run_fresh('histbin', replaced_all(text, "name = 'hist'", "name = 'histbin', output_format = 'binary'"), &
                       failure)
        call check(error, .not. allocated(failure), 'the sweep with binary histories runs')
        if (allocated(error)) return
        call check(error, same_rows(scratch//'/out/hist_v2_direct.dat', scratch//'/out/histbin_v2_direct.bin', 5), &
                   'output_format = ''binary'': histbin_v2_direct.bin holds the text file''s rows bit for bit')
        if (allocated(error)) return
        inquire (file=scratch//'/out/histbin_v2_direct.bin.txt', exist=exists)
        call check(error, exists, 'with its header file .bin.txt')
        if (allocated(error)) return
        call run_fresh('nohist', replaced_all(text, 'histories = .true.', 'histories = .false.'), failure)
        call check(error, .not. allocated(failure), 'the sweep without histories runs')
        if (allocated(error)) return
        inquire (file=scratch//'/out/nohist_v1_direct.dat', exist=exists)
        call check(error, .not. exists, 'no history file unless asked')
        if (allocated(error)) return
        ! drop the first amplitude: variant 1 is now 2.0e-3, done before as variant 2
        call write_text(scratch//'/hist.nml', replaced_all(text, '1.0e-3, 2.0e-3', '2.0e-3'))
        call check(error, skipped_line(scratch//'/hist.nml') == '0 already done', &
                   'with histories, a renumbered variant runs again')
        if (allocated(error)) return
        title = first_line(scratch//'/out/hist_v1_direct.dat')
        call check(error, index(title, 'variant 1 (road.amplitude = 2.0e-3)') > 0, 'its file rewritten: '//title)
        if (allocated(error)) return
        call write_text(scratch//'/nohist.nml', replaced_all(replaced_all(text, 'histories = .true.', &
                        'histories = .false.'), '1.0e-3, 2.0e-3', '2.0e-3'))
        call check(error, skipped_line(scratch//'/nohist.nml') == '1 already done', &
                   'without histories, it is skipped')
    end subroutine test_histories

    !> The &sweep options: a value that is not one, and bands the variants cannot resolve
    !> (above Nyquist, or a record too short), each refused with where and what.
    subroutine test_bad_options(error)
        type(test_error), allocatable, intent(out) :: error

        type(sweep_plan) :: plan
        type(error_type), allocatable :: failure
        character(len=:), allocatable :: report

        call read_text('opt.nml', sweep_scene("&sweep road.amplitude = 1.0e-3,"//new_line('a') &
                       //"    spectra = maybe /"), plan, failure)
        call check(error, allocated(failure), 'spectra = maybe is refused')
        if (allocated(error)) return
        call check(error, index(failure%message, "opt.nml:10: &sweep spectra: expected .true. or .false., found " &
                   //"'maybe'") > 0, failure%message)
        if (allocated(error)) return
        call read_text('opt.nml', sweep_scene("&sweep road.amplitude = 1.0e-3, spectra = .true., f_low = 11.0, " &
                       //"f_high = 12.0 /"), plan, failure)
        call check(error, allocated(failure), 'a range without a band is refused')
        if (allocated(error)) return
        call check(error, index(failure%message, 'expected a range holding a 1/3-octave band') > 0, failure%message)
        if (allocated(error)) return
        ! dt = 1e-4 s: Nyquist 5000 Hz, below the 5000 Hz band's upper edge 5623 Hz
        report = check_report(sweep_scene("&sweep road.amplitude = 1.0e-3, spectra = .true., f_low = 1000.0, " &
                              //"f_high = 5000.0 /"), failure)
        call check(error, allocated(failure), '--check fails on bands above Nyquist')
        if (allocated(error)) return
        call check(error, index(report, '(variant 1): &sweep spectra: expected every band up to f_high = ') > 0 .and. &
                   index(report, '1 variants of road.amplitude, methods direct; 0 checked ok, 1 bad') > 0, report)
        if (allocated(error)) return
        ! 200 steps of 1e-4 s: the 100 Hz band needs 4096
        report = check_report(sweep_scene("&sweep road.amplitude = 1.0e-3, spectra = .true., f_low = 100.0, " &
                              //"f_high = 1000.0 /"), failure)
        call check(error, index(report, 'expected a record of at least 4096 steps') > 0, report)
    end subroutine test_bad_options

    !> A sweep over two road files; editing one reruns its variant only, the other is skipped.
    subroutine test_file_key(error)
        type(test_error), allocatable, intent(out) :: error

        type(error_type), allocatable :: failure
        character(len=:), allocatable :: text
        character(len=*), parameter :: nl = new_line('a')
        character(len=*), parameter :: road = '# x height'//nl//'0.0 0.0'//nl//'0.5 1.0e-4'//nl//'1.0 0.0'//nl

        text = replaced_all(sweep_scene("&sweep road.road_file = '"//scratch//"/road_a.dat', '"//scratch &
                                    //"/road_b.dat' /"), "name = 'unit'", "name = 'files'")
        ! the base scene is complete on its own: it names a road file, which the sweep replaces
        text = replaced_all(text, "profile = 'sine'", "profile = 'file', speed = 10.0, road_file = '"//scratch &
                        //"/road_a.dat'")
        call make_directory(scratch//'/out', failure)
        call write_text(scratch//'/road_a.dat', road)
        call write_text(scratch//'/road_b.dat', road)
        call write_text(scratch//'/files.nml', text)
        call execute_command_line('rm -rf '//scratch//'/out/files_sweep.d')
        call check(error, skipped_line(scratch//'/files.nml') == '0 already done', 'a first run runs both')
        if (allocated(error)) return
        call check(error, skipped_line(scratch//'/files.nml') == '2 already done', 'a rerun skips both')
        if (allocated(error)) return
        call write_text(scratch//'/road_b.dat', replaced_all(road, '1.0e-4', '2.0e-4'))
        call check(error, skipped_line(scratch//'/files.nml') == '1 already done', &
                   'an edited road file reruns its variant')
    end subroutine test_file_key

    !> A road file edited while a sweep runs (between its variants 1 and 2): variant 2 would run
    !> on the road data variant 1 read (the sweep reads each road file once) under the key of
    !> the edited file, a table mixing two versions; it is refused (status 2) with both hashes,
    !> and variant 3, the file restored, runs.
    subroutine test_edited_file(error)
        type(test_error), allocatable, intent(out) :: error

        type(error_type), allocatable :: failure
        type(sweep_plan) :: plan
        type(scene_files) :: files
        type(variant_outcome) :: outcome
        character(len=:), allocatable :: text
        integer :: what
        character(len=*), parameter :: nl = new_line('a')
        character(len=*), parameter :: road = '# x height'//nl//'0.0 0.0'//nl//'0.5 1.0e-4'//nl//'1.0 0.0'//nl

        text = replaced_all(sweep_scene("&sweep road.speed = 10.0, 12.0, 14.0 /"), "name = 'unit'", "name = 'edit'")
        text = replaced_all(text, "profile = 'sine'", "profile = 'file', speed = 10.0, road_file = '"//scratch &
                            //"/road_edit.dat'")
        call make_directory(scratch//'/out', failure)
        call write_text(scratch//'/road_edit.dat', road)
        call execute_command_line('rm -rf '//scratch//'/out/edit_sweep.d')
        call read_text('edit.nml', text, plan, failure)
        call check(error, .not. allocated(failure), 'the sweep reads')
        if (allocated(error)) return
        call take_variant(plan, 1, .false., outcome, what, files)
        call check(error, what == variant_ran .and. outcome%status == 0, 'variant 1 runs: '//outcome%message)
        if (allocated(error)) return
        call write_text(scratch//'/road_edit.dat', replaced_all(road, '1.0e-4', '3.0e-4'))
        call take_variant(plan, 2, .false., outcome, what, files)
        call check(error, what == variant_bad .and. outcome%status == 2, 'variant 2 of an edited file refused')
        if (allocated(error)) return
        call check(error, index(outcome%message, 'edit.nml (variant 2): '//scratch//'/road_edit.dat changed while ' &
                   //'the sweep ran: expected its lines as variant 1 read them (hash ') > 0 &
                   .and. index(outcome%message, '), found hash ') > 0, outcome%message)
        if (allocated(error)) return
        call write_text(scratch//'/road_edit.dat', road)
        call take_variant(plan, 3, .false., outcome, what, files)
        call check(error, what == variant_ran .and. outcome%status == 0, 'the file restored, variant 3 runs: ' &
                   //outcome%message)
    end subroutine test_edited_file

    !> One mode (100 Hz, xi = 9.4e-3) measured from 0 to 500 Hz by 1 Hz, run at dt = 1 ms:
    !> `direct` on g from the inverse FFT of the band estimates its own error at about 7e-2
    !> (greenconv_conv_builder's `kernel_estimate`; test_accuracystatus_mod checks that it is
    !> the kernel's real error), `exact` on the identified mode 6e-3 (its time step's). Swept over
    !> `convolution.accuracy = 0.5, 3.0e-2`: variant 2's direct runs whole but outside (status 4
    !> in its row, step 0, its numbers those of variant 1), its exact 0, and the sweep ends with
    !> status 4. With a bad variant beside it (contact exponent -1), the sweep ends with 2.
    subroutine test_accuracy_status(error)
        type(test_error), allocatable, intent(out) :: error

        character(len=*), parameter :: nl = new_line('a')
        type(error_type), allocatable :: failure
        character(len=:), allocatable :: text, header, row_1, row_2
        character(len=32) :: words(14), first(14)
        real(dp) :: omega0, omega
        integer :: unit, l

        call make_directory(scratch, failure)
        if (allocated(failure)) then
            call check(error, .false., 'scratch directory: '//failure%message)
            return
        end if
        omega0 = 2.0_dp*acos(-1.0_dp)*100.0_dp
        open (newunit=unit, file=scratch//'/one_mode.frf', status='replace', action='write')
        write (unit, '(a)') '# one mode, 100 Hz, xi = 9.4e-3: f [Hz], Re G, Im G [m/N]'
        do l = 0, 500
            omega = 2.0_dp*acos(-1.0_dp)*l
            write (unit, '(f6.1,2es25.16e3)') real(l, dp), 1.0_dp/cmplx(omega0**2 - omega**2, &
                                                                         2.0_dp*9.4e-3_dp*omega0*omega, dp)
        end do
        close (unit)
        text = "&scene task = 'sweep', name = 'acc', output_dir = '"//scratch//"/out', dt = 1.0e-3, " &
               //"n_steps = 100 /"//nl//"&structure model = 'frf_file', frf_file = '"//scratch//"/one_mode.frf' /" &
               //nl//"&road profile = 'sine', amplitude = 1.0e-4, omega = 300.0 /"//nl &
               //"&contact stiffness = 1.0e6, exponent = 1.5, preload = 10.0 /"//nl &
               //"&convolution methods = 'direct', 'exact' /"//nl
        call run_fresh('acc', text//"&sweep convolution.accuracy = 0.5, 3.0e-2 /"//nl, failure)
        call check(error, allocated(failure), 'a variant outside its accuracy: the sweep ends with an error')
        if (allocated(error)) return
        call check(error, failure%stat == stat_accuracy .and. index(failure%message, 'outside the accuracy') > 0, &
                   'status 4 saying why, found '//failure%message)
        if (allocated(error)) return
        call table_lines(scratch//'/out/acc_sweep.dat', header, row_1, 1)
        call table_lines(scratch//'/out/acc_sweep.dat', header, row_2, 2)
        read (row_1, *) first
        read (row_2, *) words
        call check(error, all(first([7, 8, 13, 14]) == ['0', '0', '0', '0']), 'variant 1 (accuracy 0.5): direct and ' &
                   //'exact status 0, found '//row_1)
        if (allocated(error)) return
        call check(error, all(words([7, 8, 13, 14]) == ['4', '0', '0', '0']), 'variant 2 (accuracy 1e-3): direct ' &
                   //'status 4 with step 0, exact 0, found '//row_2)
        if (allocated(error)) return
        call check(error, all(words(3:6) == first(3:6)), 'direct outside its accuracy still ran whole: its row''s ' &
                   //'numbers are those of variant 1')
        if (allocated(error)) return
        call check(error, index(header, 'status_direct') > 0, 'a status column per method: '//header)
        if (allocated(error)) return
        call run_fresh('accbad', replaced_all(text, "name = 'acc'", "name = 'accbad'") &
                       //"&sweep convolution.accuracy = 1.0e-3, contact.exponent = 1.5, -1.0 /"//nl, failure)
        call check(error, allocated(failure), 'a variant outside and a bad one: an error')
        if (allocated(error)) return
        call check(error, failure%stat == stat_input, 'the bad variant''s status 2 before status 4, found ' &
                   //failure%message)
    end subroutine test_accuracy_status

    !> Run a sweep serially; what its report says it skipped ('N already done').
    function skipped_line(path) result(said)
        character(len=*), intent(in) :: path
        character(len=:), allocatable :: said

        type(error_type), allocatable :: failure
        character(len=:), allocatable :: line
        integer :: report, stat, at

        said = 'no report'
        open (newunit=report, status='scratch', action='readwrite')
        call run_sweep(path, report, .false., failure)
        if (allocated(failure)) said = failure%message
        rewind (report)
        do
            call read_line(report, line, stat)
            if (stat /= 0) exit
            at = index(line, ' already done')
            if (at > 0 .and. .not. allocated(failure)) said = line(index(line(:at - 1), ' ', back=.true.) + 1:at + 12)
        end do
        close (report)
    end function skipped_line

    !> Run a sweep written from `text` as `<name>.nml`, from scratch (its records removed).
    subroutine run_fresh(name, text, failure)
        character(len=*), intent(in) :: name, text
        type(error_type), allocatable, intent(out) :: failure

        integer :: report

        call make_directory(scratch//'/out', failure)
        if (allocated(failure)) return
        call execute_command_line('rm -rf '//scratch//'/out/'//name//'_sweep.d')
        call write_text(scratch//'/'//name//'.nml', text)
        open (newunit=report, status='scratch', action='readwrite')
        call run_sweep(scratch//'/'//name//'.nml', report, .false., failure)
        close (report)
    end subroutine run_fresh

    !> What `--check` on a sweep written from `text` reports (its lines joined), and its error.
    function check_report(text, failure) result(said)
        character(len=*), intent(in) :: text
        type(error_type), allocatable, intent(out) :: failure
        character(len=:), allocatable :: said

        character(len=:), allocatable :: line
        integer :: report, stat

        said = ''
        call make_directory(scratch, failure)
        if (allocated(failure)) return
        call write_text(scratch//'/check.nml', text)
        open (newunit=report, status='scratch', action='readwrite')
        call run_sweep(scratch//'/check.nml', report, .true., failure)
        rewind (report)
        do
            call read_line(report, line, stat)
            if (stat /= 0) exit
            said = said//line//' | '
        end do
        close (report)
    end function check_report

    !> Column `j` of a column file's data rows.
    function history_column(path, j) result(column)
        character(len=*), intent(in) :: path
        integer, intent(in) :: j
        real(dp), allocatable :: column(:)

        character(len=:), allocatable :: line
        real(dp) :: values(j)
        integer :: unit, stat

        allocate (column(0))
        open (newunit=unit, file=path, status='old', action='read', iostat=stat)
        if (stat /= 0) return
        do
            call read_line(unit, line, stat)
            if (stat /= 0) exit
            if (line(1:1) == '#') cycle
            read (line, *) values
            column = [column, values(j)]
        end do
        close (unit)
    end function history_column

    !> Whether a binary column file (little-endian float64 rows of n values, as this machine
    !> reads them) holds the rows of a text column file, bit for bit.
    logical function same_rows(text_path, binary_path, n)
        character(len=*), intent(in) :: text_path, binary_path
        integer, intent(in) :: n

        real(dp), allocatable :: text_rows(:, :), binary_rows(:, :)
        integer :: unit, stat, j, bytes

        same_rows = .false.
        allocate (text_rows(size(history_column(text_path, 1)), n))
        do j = 1, n
            text_rows(:, j) = history_column(text_path, j)
        end do
        inquire (file=binary_path, size=bytes)
        if (bytes /= 8*size(text_rows)) return
        allocate (binary_rows(n, size(text_rows, 1)))
        open (newunit=unit, file=binary_path, access='stream', form='unformatted', status='old', action='read', &
              iostat=stat)
        if (stat /= 0) return
        read (unit, iostat=stat) binary_rows
        close (unit)
        same_rows = stat == 0 .and. all(transfer(binary_rows, 1_int64, size(binary_rows)) == &
                                        transfer(transpose(text_rows), 1_int64, size(text_rows)))
    end function same_rows

    !> The first line of a file ('' when it cannot be read).
    function first_line(path) result(line)
        character(len=*), intent(in) :: path
        character(len=:), allocatable :: line

        integer :: unit, stat

        line = ''
        open (newunit=unit, file=path, status='old', action='read', iostat=stat)
        if (stat /= 0) return
        call read_line(unit, line, stat)
        close (unit)
    end function first_line

    !> The column names (the last `#` line) and data row `k` of a table.
    subroutine table_lines(path, header, row, k)
        character(len=*), intent(in) :: path
        character(len=:), allocatable, intent(out) :: header, row
        integer, intent(in) :: k

        character(len=:), allocatable :: line
        integer :: unit, stat, n

        header = ''
        row = ''
        n = 0
        open (newunit=unit, file=path, status='old', action='read')
        do
            call read_line(unit, line, stat)
            if (stat /= 0) exit
            if (line(1:1) == '#') then
                header = line
            else
                n = n + 1
                if (n == k) row = line
            end if
        end do
        close (unit)
    end subroutine table_lines
end module test_sweep_mod
