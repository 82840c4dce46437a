!> Force spectra of the contact scenes (`&scene spectra`, greenconv_scene_run_spectra_output):
!> the band level of a linear contact on an SDOF under a sine road against its closed form;
!> the spectra of runs streamed in blocks against the whole run and against the library's
!> band_levels of the force history the column file holds (single point, and the tyre with
!> each point's level); the band ranges refused when the scene is read, each with its one
!> line; the defaults narrowed to what the record resolves; no spectra after a fault.
module test_scenespectra_mod
    use, intrinsic :: iso_fortran_env, only: dp => real64
    use testsuite_mod, only: test_error, unittest_type, new_unittest, check, note
    use scene_text_mod, only: tab1_scene, read_scene_text
    use greenconv_api_all, only: scene_type, run_scene, check_scene, error_type, stat_input, stat_numerical
    use greenconv_io_columns, only: read_columns
    use greenconv_core_text, only: int_text
    use greenconv_io_spectra, only: band_spectrum, band_levels
    implicit none
    private

    public :: collect_scenespectra

    !> Scratch directory for the files the tests write.
    character(len=*), parameter :: scratch = 'build/test_scratch/scenespectra'
    real(dp), parameter :: pi = acos(-1.0_dp)

contains

    !> Tests of the scenes' force spectra.
    subroutine collect_scenespectra(testsuite)
        type(unittest_type), allocatable, intent(out) :: testsuite(:)

        testsuite = [new_unittest('linear contact, SDOF, sine road: the tone''s band level is the closed form', &
                                  test_closed_form), &
                     new_unittest('blocks of 1, 7, 333 and the default give the whole run''s file', test_blocks), &
                     new_unittest('levels equal band_levels of the written force history (sdof; tyre per point)', &
                                  test_history), &
                     new_unittest('band ranges the run cannot resolve are refused in one line', test_refused), &
                     new_unittest('defaults narrowed to the record; --check and the summary name the spectra', &
                                  test_defaults), &
                     new_unittest('a run stopped by a fault leaves no spectra file', test_fault)]
    end subroutine collect_scenespectra

    !> Linear contact (p = 1, k_c = 1e5 N/m) on the SDOF M = 1 kg, K = 1e6 N/m, xi = 0.2,
    !> preload 100 N, road A0*sin(omega*t) with A0 = 0.1 mm at 520 Hz (inside the 500 Hz band,
    !> off its centre), 2 s at 0.1 ms. The contact never opens (the force varies by about
    !> 10 N), so in steady state the force varies by dF = k_c*A0/|1 + k_c*H(omega)| with
    !> H = 1/(K - M*omega^2 + i*2*xi*sqrt(K*M)*omega), and its band level is
    !> 20*log10(dF/sqrt(2)). What may separate the run from it: the explicit step answers
    !> about a step late, which moves dF by at most k_c*|H|*omega*dt relatively; the transient
    !> of the start (0.19 damping at 167 Hz, gone in 50 ms, one segment of 8 and another band)
    !> and the Hann window's leakage (1e-4 dB, suite spectra) are taken as 0.01 dB together.
    !> The neighbouring bands must read at least 40 dB under the tone's.
    subroutine test_closed_form(error)
        type(test_error), allocatable, intent(out) :: error

        real(dp), parameter :: mass = 1.0_dp, stiffness = 1.0e6_dp, xi = 0.2_dp, k_c = 1.0e5_dp, &
                               amplitude = 1.0e-4_dp, f_road = 520.0_dp, dt = 1.0e-4_dp
        character(len=:), allocatable :: text
        character(len=6), parameter :: methods(2) = ['modal ', 'direct']
        type(scene_type) :: scene
        type(error_type), allocatable :: failure
        real(dp), allocatable :: table(:, :)
        complex(dp) :: receptance
        real(dp) :: omega, expected, tolerance
        integer :: m, b

        omega = 2.0_dp*pi*f_road
        text = "&scene name = 'tone', output_dir = '"//scratch//"', dt = 1.0e-4, n_steps = 20000, " &
               //"spectra = .true., spectra_f_low = 100.0, spectra_f_high = 2000.0 /"//new_line('a') &
               //"&structure model = 'sdof', mass = 1.0, stiffness = 1.0e6, damping_ratio = 0.2 /"//new_line('a') &
               //"&road profile = 'sine', amplitude = 1.0e-4, omega = "//real_word(omega)//" /"//new_line('a') &
               //"&contact stiffness = 1.0e5, exponent = 1.0, preload = 100.0 /"//new_line('a') &
               //"&convolution methods = 'modal', 'direct' /"
        call read_scene_text(scratch, 'tone.nml', text, scene, failure)
        if (.not. allocated(failure)) call run_quietly(scene, failure)
        call check(error, .not. allocated(failure), 'the tone scene runs')
        if (allocated(error)) return
        receptance = 1.0_dp/cmplx(stiffness - mass*omega**2, 2.0_dp*xi*sqrt(stiffness*mass)*omega, dp)
        expected = 20.0_dp*log10(k_c*amplitude/abs(1.0_dp + k_c*receptance)/sqrt(2.0_dp))
        tolerance = 20.0_dp*log10(1.0_dp + k_c*abs(receptance)*omega*dt) + 0.01_dp
        call note('closed form [dB re 1 N]', expected)
        call note('tolerance [dB]', tolerance)
        do m = 1, size(methods)
            call read_spectra(scratch//'/tone_'//trim(methods(m))//'_spectra.dat', 7, table, error)
            if (allocated(error)) return
            b = minloc(abs(table(:, 1) - 500.0_dp), 1)
            call check(error, table(b, 3) < f_road .and. f_road < table(b, 4), 'the 500 Hz band holds 520 Hz')
            if (allocated(error)) return
            call note(trim(methods(m))//': level - closed form [dB]', table(b, 6) - expected)
            call note(trim(methods(m))//': neighbours under the tone [dB]', &
                      table(b, 6) - max(table(b - 1, 6), table(b + 1, 6)))
            call check(error, abs(table(b, 6) - expected) <= tolerance, trim(methods(m))//': the 500 Hz band ' &
                       //'level differs from 20 log10(dF/sqrt 2) by more than the tolerance')
            if (allocated(error)) return
            call check(error, table(b, 6) - max(table(b - 1, 6), table(b + 1, 6)) > 40.0_dp, &
                       trim(methods(m))//': a neighbouring band is within 40 dB of the tone')
            if (allocated(error)) return
        end do
    end subroutine test_closed_form

    !> The SDOF scene of Tab. 1 with spectra (defaults: 400 Hz to 4 kHz for 0.2 s at 0.1 ms)
    !> run whole, then in blocks of 1, 7 and 333 steps and the default: every spectra file is
    !> the whole run's, line for line.
    subroutine test_blocks(error)
        type(test_error), allocatable, intent(out) :: error

        integer, parameter :: tried(4) = [1, 7, 333, 0]
        type(scene_type) :: scene
        type(error_type), allocatable :: failure
        character(len=:), allocatable :: path
        integer :: i

        call read_scene_text(scratch, 'blocks.nml', tab1_scene(scene="name = 'blocks', output_dir = '"//scratch &
                             //"', dt = 1.0e-4, n_steps = 2000, spectra = .true."), scene, failure)
        if (.not. allocated(failure)) call run_quietly(scene, failure, huge(1))
        call check(error, .not. allocated(failure), 'the whole run')
        if (allocated(error)) return
        path = scratch//'/blocks_modal_spectra.dat'
        call execute_command_line('cp '//path//' '//path//'.whole')
        do i = 1, size(tried)
            if (tried(i) > 0) then
                call run_quietly(scene, failure, tried(i))
            else
                call run_quietly(scene, failure)
            end if
            call check(error, .not. allocated(failure), 'a run in blocks')
            if (allocated(error)) return
            call check(error, same_file(path, path//'.whole'), path//' differs with blocks of '//int_text(tried(i)))
            if (allocated(error)) return
        end do
    end subroutine test_blocks

    !> The spectra file's levels against greenconv_io_spectra's band_levels of the history
    !> that the run's column file holds (read back exactly): the SDOF's f_contact, and the
    !> tyre's total force and each point's force (spectra_points), run in blocks of 7 steps.
    subroutine test_history(error)
        type(test_error), allocatable, intent(out) :: error

        character(len=*), parameter :: tyre_text = "&scene name = 'tyrespec', output_dir = '"//scratch//"', " &
            //"dt = 2.0e-5, n_steps = 3000, spectra = .true., spectra_points = .true., spectra_f_low = 1000.0 / " &
            //"&structure model = 'tyre', f_modes = 1000.0 / &road profile = 'file', road_file = " &
            //"'data/road_sample.dat', x_start = 1.0, speed = 20.0 / &contact n_points = 5, stiffness = 2.0e5, " &
            //"exponent = 1.0, preload = 1000.0 / &convolution methods = 'exact', 'modal', accuracy = 0.5 /"
        ! accuracy 0.5: the spectra of the written forces are under test, not the 1 kHz band's error
        integer, parameter :: n_c = 5
        type(scene_type) :: scene
        type(error_type), allocatable :: failure
        real(dp), allocatable :: rows(:, :), spectra(:, :)
        real(dp) :: worst
        integer :: i

        call read_scene_text(scratch, 'history.nml', tab1_scene(scene="name = 'history', output_dir = '"//scratch &
                             //"', dt = 1.0e-4, n_steps = 2000, spectra = .true."), scene, failure)
        if (.not. allocated(failure)) call run_quietly(scene, failure, 7)
        call check(error, .not. allocated(failure), 'the sdof run')
        if (allocated(error)) return
        call read_table(scratch//'/history_direct.dat', 5, rows, error)
        if (.not. allocated(error)) call read_spectra(scratch//'/history_direct_spectra.dat', 7, spectra, error)
        if (allocated(error)) return
        worst = level_gap(rows(:, 4), scene, spectra(:, 6))
        call note('sdof: max |level - band_levels| [dB]', worst)
        call check(error, worst <= 1.0e-12_dp, 'sdof: the spectra differ from band_levels of f_contact')
        if (allocated(error)) return

        call read_scene_text(scratch, 'tyrespec.nml', tyre_text, scene, failure)
        if (.not. allocated(failure)) call run_quietly(scene, failure, 7)
        call check(error, .not. allocated(failure), 'the tyre run')
        if (allocated(error)) return
        call read_table(scratch//'/tyrespec_modal.dat', 7, rows, error)
        if (.not. allocated(error)) call read_spectra(scratch//'/tyrespec_modal_spectra.dat', 7 + n_c, spectra, error)
        if (allocated(error)) return
        call check(error, size(rows, 1) == n_c*scene%n_steps, 'tyre: N_c rows per step')
        if (allocated(error)) return
        worst = level_gap(rows(1::n_c, 7), scene, spectra(:, 6))
        do i = 1, n_c
            worst = max(worst, level_gap(rows(i::n_c, 5), scene, spectra(:, 7 + i)))
        end do
        call note('tyre: bands', real(size(spectra, 1), dp))
        call note('tyre: max |level - band_levels|, total and points [dB]', worst)
        call check(error, worst <= 1.0e-12_dp, 'tyre: the spectra differ from band_levels of the forces')
    end subroutine test_history

    !> Largest |difference| [dB] between `levels` and band_levels of `force` over the scene's range.
    function level_gap(force, scene, levels) result(gap)
        real(dp), intent(in) :: force(:)
        type(scene_type), intent(in) :: scene
        real(dp), intent(in) :: levels(:)
        real(dp) :: gap

        type(band_spectrum) :: spectrum
        type(error_type), allocatable :: failure

        gap = huge(1.0_dp)
        call band_levels(force, scene%dt, scene%spectra_f_low, scene%spectra_f_high, spectrum, failure)
        if (allocated(failure)) return
        if (size(spectrum%level) /= size(levels)) return
        gap = maxval(abs(spectrum%level - levels))
    end function level_gap

    !> Each band range a run cannot resolve, on the Tab. 1 scene (2000 steps of 0.1 ms: 0.2 s,
    !> f_s = 10 kHz): one line with the file, line, group and variable, status 2.
    subroutine test_refused(error)
        type(test_error), allocatable, intent(out) :: error

        character(len=*), parameter :: base = 'dt = 1.0e-4, n_steps = 2000, spectra = .true., '
        character(len=*), parameter :: cases(5) = [character(len=60) :: &
            'spectra_f_high = 5000.0', 'spectra_f_low = 20.0', 'spectra_f_low = 6000.0', &
            'spectra_f_low = 1000.0, spectra_f_high = 800.0', 'n_steps = 10']
        character(len=*), parameter :: wanted(5) = [character(len=130) :: &
            ':1: &scene spectra_f_high: expected a highest band centre whose band ends below the Nyquist frequency', &
            ':1: &scene spectra_f_low: expected a lowest band centre the record resolves: N_t = 2000 steps', &
            ':1: &scene spectra_f_low: expected a lowest band centre below the Nyquist frequency', &
            ':1: &scene spectra_f_high: expected a highest band centre at or above the lowest, 1000', &
            ':1: &scene spectra: expected a record that resolves a band below the Nyquist frequency']
        character(len=*), parameter :: hint(5) = [character(len=40) :: '(at most 4000', 'from 400', &
            'is 4000', 'found 800', 'raise n_steps']
        type(scene_type) :: scene
        type(error_type), allocatable :: failure
        character(len=:), allocatable :: body
        integer :: i

        do i = 1, size(cases)
            body = base//trim(cases(i))
            if (i == 5) body = 'dt = 1.0e-4, spectra = .true., '//trim(cases(i))
            call read_scene_text(scratch, 'refused.nml', tab1_scene(scene=body), scene, failure)
            call check(error, allocated(failure), 'refused: '//trim(cases(i)))
            if (allocated(error)) return
            call check(error, failure%stat == stat_input .and. index(failure%message, scratch//'/refused.nml' &
                       //trim(wanted(i))) == 1 .and. index(failure%message, trim(hint(i))) > 0 .and. &
                       index(failure%message, new_line('a')) == 0, trim(cases(i))//': '//failure%message)
            if (allocated(error)) return
        end do
    end subroutine test_refused

    !> Spectra with the default range on 0.2 s at 0.1 ms: 20 Hz..20 kHz narrowed to the 400 Hz
    !> band (the lowest whose 8 lines fit a 1024-sample segment; 2048 would exceed the 2000
    !> steps) and the 4 kHz band (the highest below 5 kHz); the --check line and the run's
    !> summary say so; a scene without spectra writes none.
    subroutine test_defaults(error)
        type(test_error), allocatable, intent(out) :: error

        character(len=*), parameter :: summary = 'force spectra 400.0 Hz to 4000.0 Hz (11 bands), 2 Hann segments ' &
                                                 //'of 1024 samples'
        type(scene_type) :: scene
        type(error_type), allocatable :: failure
        character(len=1024) :: line
        integer :: unit
        logical :: exists

        call read_scene_text(scratch, 'defaults.nml', tab1_scene(scene="name = 'defaults', output_dir = '" &
                             //scratch//"', dt = 1.0e-4, n_steps = 2000, spectra = .true."), scene, failure)
        call check(error, .not. allocated(failure), 'the default range is resolved')
        if (allocated(error)) return
        call check(error, abs(scene%spectra_f_low - 1000.0_dp*10.0_dp**(-0.4_dp)) < 1.0e-9_dp .and. &
                   abs(scene%spectra_f_high - 1000.0_dp*10.0_dp**0.6_dp) < 1.0e-9_dp, 'bands 400 Hz to 4 kHz')
        if (allocated(error)) return
        open (newunit=unit, status='scratch', action='readwrite')
        call check_scene(scene, unit, failure)
        rewind (unit)
        read (unit, '(a)') line
        close (unit)
        call check(error, index(line, ', '//summary) > 0, '--check: '//trim(line))
        if (allocated(error)) return
        open (newunit=unit, status='scratch', action='readwrite')
        call run_scene(scene, unit, failure)
        rewind (unit)
        read (unit, '(a)') line
        read (unit, '(a)') line
        ! the scene's line, its contact law's, then the spectra's
        read (unit, '(a)') line
        close (unit)
        call check(error, .not. allocated(failure) .and. trim(line) == '# '//summary//': '//scratch &
                   //'/defaults_<method>_spectra.dat', 'summary: '//trim(line))
        if (allocated(error)) return
        call read_scene_text(scratch, 'nospectra.nml', tab1_scene(scene="name = 'nospectra', output_dir = '" &
                             //scratch//"', dt = 1.0e-4, n_steps = 20"), scene, failure)
        if (.not. allocated(failure)) call run_quietly(scene, failure)
        inquire (file=scratch//'/nospectra_modal_spectra.dat', exist=exists)
        call check(error, .not. allocated(failure) .and. .not. exists, 'spectra off: no spectra file')
    end subroutine test_defaults

    !> The explicit step with a linear k_c = 1e9 N/m at 0.1 ms diverges at step 97 (suite
    !> longrun): with spectra on, a spectra file left under its name beforehand is removed and
    !> none is written; the fault is reported as before.
    subroutine test_fault(error)
        type(test_error), allocatable, intent(out) :: error

        character(len=*), parameter :: path = scratch//'/fault_direct_spectra.dat'
        type(scene_type) :: scene
        type(error_type), allocatable :: failure
        integer :: unit
        logical :: exists

        call read_scene_text(scratch, 'fault.nml', tab1_scene(scene="name = 'fault', output_dir = '"//scratch &
                             //"', dt = 1.0e-4, n_steps = 2000, spectra = .true.", &
                             contact='stiffness = 1.0e9, exponent = 1.0', convolution="methods = 'direct'"), &
                             scene, failure)
        call check(error, .not. allocated(failure), 'the scene reads')
        if (allocated(error)) return
        open (newunit=unit, file=path, status='replace', action='write')
        write (unit, '(a)') '# a stale spectrum'
        close (unit)
        call run_quietly(scene, failure)
        call check(error, allocated(failure), 'the run diverges')
        if (allocated(error)) return
        call check(error, failure%stat == stat_numerical .and. index(failure%message, 'step 97') > 0, &
                   'fault: '//failure%message)
        if (allocated(error)) return
        inquire (file=path, exist=exists)
        call check(error, .not. exists, 'the stale spectra file is gone and none was written')
    end subroutine test_fault

    ! ---- helpers ----------------------------------------------------------------------------

    !> Run a scene with its summary discarded, in blocks of `block` steps when given.
    subroutine run_quietly(scene, failure, block)
        type(scene_type), intent(in) :: scene
        type(error_type), allocatable, intent(out) :: failure
        integer, intent(in), optional :: block

        integer :: unit

        open (newunit=unit, status='scratch', action='readwrite')
        call run_scene(scene, unit, failure, block)
        close (unit)
    end subroutine run_quietly

    !> The data rows of a column file of n columns.
    subroutine read_table(path, n, table, error)
        character(len=*), intent(in) :: path
        integer, intent(in) :: n
        real(dp), allocatable, intent(out) :: table(:, :)
        type(test_error), allocatable, intent(out) :: error

        type(error_type), allocatable :: failure
        integer, allocatable :: line_of(:)
        character(len=8) :: names(n)

        names = 'value'
        call read_columns(path, names, names, table, line_of, failure)
        call check(error, .not. allocated(failure), path//' reads as '//int_text(n)//' columns')
    end subroutine read_table

    !> A spectra file (n columns) with at least three bands.
    subroutine read_spectra(path, n, table, error)
        character(len=*), intent(in) :: path
        integer, intent(in) :: n
        real(dp), allocatable, intent(out) :: table(:, :)
        type(test_error), allocatable, intent(out) :: error

        call read_table(path, n, table, error)
        if (allocated(error)) return
        call check(error, size(table, 1) >= 3, path//': fewer than three bands')
    end subroutine read_spectra

    !> Whether two files have the same bytes.
    logical function same_file(path_a, path_b)
        character(len=*), intent(in) :: path_a, path_b

        integer :: status

        call execute_command_line('cmp -s '//path_a//' '//path_b, exitstat=status)
        same_file = status == 0
    end function same_file

    !> A real as namelist text that reads back to the same double.
    pure function real_word(x) result(text)
        real(dp), intent(in) :: x
        character(len=:), allocatable :: text

        character(len=32) :: buffer

        write (buffer, '(es25.17)') x
        text = trim(adjustl(buffer))
    end function real_word

end module test_scenespectra_mod
