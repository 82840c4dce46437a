!> Long runs: a run streamed in blocks equals the whole run bit for bit (single
!> point, explicit and implicit; the tyre scene); `output_every` decimation; a divergent run
!> keeps its rows in the final file; convolvers stepped past 2^31 pushes; the progress line;
!> and 1e8 steps of the modal solver through the driver's blocked path in bounded memory.
module test_longrun_mod
    use, intrinsic :: iso_fortran_env, only: dp => real64, int64
    use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
    use testsuite_mod, only: test_error, unittest_type, new_unittest, check, note
    use scene_text_mod, only: tab1_scene, read_scene_text
    use greenconv_scene_run_progress, only: progress_meter, start_progress, progress_line, progress_due
    use greenconv_api_all, only: scene_type, read_scene, run_scene, error_type, stat_numerical, convolver, &
                                 contact_law, contact_options, contact_response, run_contact, contact_state, &
                                 start_contact, contact_block, road_profile, sine_road, sdof_modes, &
                                 new_recursive_convolver, new_exact_convolver, new_direct_convolver, &
                                 new_fft_convolver, fft_convolver, sdof_impulse, point_modes, tyre_belt, tyre_modes, &
                                 contact_positions, modal_green_matrix, new_modal_green_matrix, &
                                 multi_contact_response, run_multi_contact, multi_contact_state, start_multi_contact, &
                                 multi_contact_block, road_file, read_road_file, sample_road, road_travel
    use greenconv_contact_law_power, only: power_law
    implicit none
    private

    public :: collect_longrun

    !> Scratch directory for the files the tests write.
    character(len=*), parameter :: scratch = 'build/test_scratch/longrun'
    !> Time step [s] and steps of the short runs.
    real(dp), parameter :: dt = 1.0e-4_dp
    integer, parameter :: n_short = 2000
    !> Block sizes tried: one step, sizes that do not divide N_t, N_t itself and beyond.
    integer, parameter :: blocks(6) = [1, 7, 333, 1024, n_short, 5000]

    !> A road that steps to a constant height at t = 0 (the body starts in equilibrium on a
    !> flat road), so the run settles on a static state known in closed form.
    type, extends(road_profile) :: step_road
        !> Height of the step [m].
        real(dp) :: level = 0.0_dp
    contains
        procedure :: height => step_height
    end type step_road

contains

    !> Tests of the streamed runs, the step counters and the progress line.
    subroutine collect_longrun(testsuite)
        type(unittest_type), allocatable, intent(out) :: testsuite(:)

        testsuite = [new_unittest('blocked run equals the whole run bit for bit (explicit, implicit)', test_blocks), &
                     new_unittest('tyre: blocked multi-point run equals the whole run bit for bit', test_tyre_blocks), &
                     new_unittest('driver files do not depend on the block size (sdof, tyre)', test_block_files), &
                     new_unittest('output_every = 7 writes steps 0, 7, 14, ... and says so', test_output_every), &
                     new_unittest('a divergent run keeps its rows in the final file (sdof, tyre)', test_divergence), &
                     new_unittest('convolvers stepped past 2^31 pushes equal fresh ones', test_past_int32), &
                     new_unittest('progress line: text, when it shows, when it stays silent', test_progress), &
                     new_unittest('1e8 steps of the modal solver: steady state, finite, no memory growth', &
                                  test_hundred_million)]
    end subroutine collect_longrun

    ! ---- helpers -----------------------------------------------------------------------

    !> The step road's height [m]: `level` from t = 0 on.
    elemental real(dp) function step_height(self, t)
        class(step_road), intent(in) :: self
        real(dp), intent(in) :: t

        step_height = merge(self%level, 0.0_dp, t >= 0.0_dp)
    end function step_height

    !> Write `text` as a scene file in the scratch directory and read it, or stop.
    function scene_from_text(name, text) result(scene)
        character(len=*), intent(in) :: name, text
        type(scene_type) :: scene

        type(error_type), allocatable :: failure

        call read_scene_text(scratch, name, text, scene, failure)
        if (allocated(failure)) error stop 'test_longrun_mod: '//failure%message
    end function scene_from_text

    !> Run a scene through the driver's path with blocks of `block` steps; summary discarded.
    subroutine run_blocked(scene, block, failure)
        type(scene_type), intent(in) :: scene
        integer, intent(in) :: block
        type(error_type), allocatable, intent(out) :: failure

        integer :: unit

        open (newunit=unit, status='scratch', action='readwrite')
        call run_scene(scene, unit, failure, block)
        close (unit)
    end subroutine run_blocked

    !> Every line of a text file (empty when it cannot be read).
    subroutine read_lines(path, lines)
        character(len=*), intent(in) :: path
        character(len=256), allocatable, intent(out) :: lines(:)

        character(len=256) :: line
        integer :: unit, stat, n

        allocate (lines(0))
        open (newunit=unit, file=path, status='old', action='read', iostat=stat)
        if (stat /= 0) return
        n = 0
        do
            read (unit, '(a)', iostat=stat) line
            if (stat /= 0) exit
            n = n + 1
            lines = [character(len=256) :: lines, line]
        end do
        close (unit)
    end subroutine read_lines

    !> Whether two text files hold the same lines.
    logical function same_lines(path_a, path_b)
        character(len=*), intent(in) :: path_a, path_b

        character(len=256), allocatable :: a(:), b(:)

        call read_lines(path_a, a)
        call read_lines(path_b, b)
        same_lines = size(a) == size(b) .and. size(a) > 0
        if (same_lines) same_lines = all(a == b)
    end function same_lines

    !> Number of data (non-`#`) lines of a text file.
    integer function data_rows(path)
        character(len=*), intent(in) :: path

        character(len=256), allocatable :: lines(:)
        integer :: i

        call read_lines(path, lines)
        data_rows = 0
        do i = 1, size(lines)
            if (lines(i)(1:1) /= '#') data_rows = data_rows + 1
        end do
    end function data_rows

    !> Whether a file exists.
    logical function exists(path)
        character(len=*), intent(in) :: path

        inquire (file=path, exist=exists)
    end function exists

    ! ---- blocked against whole -----------------------------------------------------------

    !> run_contact on the whole road against start_contact + contact_block over blocks of 1,
    !> 7, 333, 1024, N_t and more steps: every history equal bit for bit, for the explicit
    !> step (recursive, direct) and the implicit one (exact, whose Newton guess is the
    !> previous step's compression and must cross the blocks).
    subroutine test_blocks(error)
        type(test_error), allocatable, intent(out) :: error

        class(convolver), allocatable :: conv
        type(contact_options) :: options
        character(len=9), parameter :: methods(3) = ['recursive', 'direct   ', 'exact    ']
        integer :: i, j

        do i = 1, size(methods)
            call sdof_convolver(trim(methods(i)), conv)
            options%scheme = merge('implicit', 'explicit', methods(i) == 'exact')
            do j = 1, size(blocks)
                call check(error, blocked_equals_whole(conv, options, blocks(j)), trim(methods(i))//' ('// &
                           trim(options%scheme)//'): blocks differ from the whole run')
                if (allocated(error)) return
            end do
            deallocate (conv)
        end do
    end subroutine test_blocks

    !> The oscillator of Tab. 1 as a convolver of one method.
    subroutine sdof_convolver(method, conv)
        character(len=*), intent(in) :: method
        class(convolver), allocatable, intent(out) :: conv

        integer :: j

        select case (method)
        case ('recursive')
            conv = new_recursive_convolver(sdof_modes(1.0_dp, 1.0e6_dp, 0.02_dp), dt)
        case ('exact')
            conv = new_exact_convolver(sdof_modes(1.0_dp, 1.0e6_dp, 0.02_dp), dt)
        case default
            conv = new_direct_convolver(sdof_impulse(1.0_dp, 1.0e6_dp, 0.02_dp, [(j*dt, j=0, 1500)]), dt)
        end select
    end subroutine sdof_convolver

    !> Whether the SDOF scene on the sine road run in blocks of `block` steps equals it run whole.
    logical function blocked_equals_whole(conv, options, block) result(same)
        class(convolver), intent(inout) :: conv
        type(contact_options), intent(in) :: options
        integer, intent(in) :: block

        type(contact_response) :: whole, part
        type(contact_state) :: state
        type(power_law) :: law
        type(sine_road) :: road
        type(error_type), allocatable :: failure
        real(dp), allocatable :: heights(:)
        integer :: first, last

        road%amplitude = 1.0e-3_dp
        road%omega = 100.0_dp
        heights = road%sample(dt, n_short)
        call run_contact(conv, law, heights, 9.81_dp, whole, options, failure)
        same = .not. allocated(failure) .and. size(whole%time) == n_short
        call start_contact(conv, law, 9.81_dp, state, failure, options)
        same = same .and. .not. allocated(failure)
        first = 0
        do while (same .and. first < n_short)
            last = min(first + block, n_short) - 1
            call contact_block(conv, state, road%sample_steps(dt, int(first, int64), last - first + 1), part, failure)
            same = .not. allocated(failure) .and. size(part%time) == last - first + 1
            if (.not. same) exit
            same = all(part%time == whole%time(first:last)) .and. all(part%road == whole%road(first:last)) .and. &
                   all(part%displacement == whole%displacement(first:last)) .and. &
                   all(part%force == whole%force(first:last)) .and. &
                   all(part%compression == whole%compression(first:last))
            first = last + 1
        end do
        same = same .and. state%step == n_short
    end function blocked_equals_whole

    !> The multi-point loop on the default tyre (6 points, modes to 1 kHz, the road file),
    !> whole against blocks: every history equal bit for bit, with the explicit recursion and
    !> with `exact`, whose Newton iteration starts from the previous step's compressions.
    subroutine test_tyre_blocks(error)
        type(test_error), allocatable, intent(out) :: error

        character(len=9), parameter :: schemes(2) = ['recursive', 'exact    ']
        integer, parameter :: n_c = 6, n_t = 600
        real(dp), parameter :: tyre_dt = 2.0e-5_dp, speed = 20.0_dp
        type(point_modes) :: description
        type(modal_green_matrix) :: conv
        type(tyre_belt) :: tyre
        type(road_file) :: profile
        type(multi_contact_response) :: whole, part
        type(multi_contact_state) :: state
        type(error_type), allocatable :: failure
        type(power_law) :: laws(n_c)
        real(dp) :: positions(n_c), preloads(n_c)
        real(dp), allocatable :: heights(:, :)
        logical :: same
        integer :: i, j, first, last

        positions = contact_positions(0.5_dp*tyre%length, 0.1_dp, n_c)
        laws(:) = power_law(2.0e5_dp, 1.0_dp)
        preloads(:) = 200.0_dp
        call tyre_modes(tyre, positions, 1000.0_dp, description, failure)
        if (.not. allocated(failure)) call read_road_file('data/road_sample.dat', profile, failure)
        if (.not. allocated(failure)) call sample_road(profile, road_travel(x=1.0_dp + positions - positions(1), speed=speed, &
                                                                                    dt=tyre_dt), n_t, heights, failure)
        call check(error, .not. allocated(failure), 'tyre modes and road')
        if (allocated(error)) return
        do i = 1, size(schemes)
            call new_modal_green_matrix(description, tyre_dt, trim(schemes(i)), conv, failure)
            if (.not. allocated(failure)) call run_multi_contact(conv, laws, heights, preloads, whole, failure)
            call check(error, .not. allocated(failure), trim(schemes(i))//': the whole run')
            if (allocated(error)) return
            do j = 1, size(blocks) - 1
                call start_multi_contact(conv, laws, preloads, state, failure)
                same = .not. allocated(failure)
                first = 0
                do while (same .and. first < n_t)
                    last = min(first + blocks(j), n_t) - 1
                    call multi_contact_block(conv, state, heights(first:last, :), part, failure)
                    same = .not. allocated(failure)
                    if (same) same = all(part%time == whole%time(first:last)) .and. &
                                     all(part%displacement == whole%displacement(first:last, :)) .and. &
                                     all(part%force == whole%force(first:last, :)) .and. &
                                     all(part%compression == whole%compression(first:last, :)) .and. &
                                     all(part%iterations == whole%iterations(first:last))
                    first = last + 1
                end do
                call check(error, same, trim(schemes(i))//': blocks differ from the whole run')
                if (allocated(error)) return
            end do
        end do
    end subroutine test_tyre_blocks

    !> The driver's files (run_scene) written with blocks of 1, 7, 333 steps and the default
    !> equal those of one block holding the whole run (which is run_contact's path), line
    !> for line: an SDOF scene with direct (explicit) and exact (implicit), and the tyre.
    subroutine test_block_files(error)
        type(test_error), allocatable, intent(out) :: error

        character(len=:), allocatable :: sdof_text
        character(len=*), parameter :: tyre_text = "&scene name = 'tyre', output_dir = '"//scratch//"', " &
            //"dt = 2.0e-5, n_steps = 300 / &structure model = 'tyre', f_modes = 1000.0 / &road profile = " &
            //"'file', road_file = 'data/road_sample.dat', x_start = 1.0, speed = 20.0 / &contact n_points = 5, " &
            //"stiffness = 2.0e5, exponent = 1.0, preload = 1000.0 / &convolution methods = 'exact', 'modal', " &
            //"accuracy = 0.5 /"
        ! accuracy 0.5: the files against the block size are under test, not the 1 kHz band's error

        sdof_text = tab1_scene(scene="name = 'sdof', output_dir = '"//scratch//"', dt = 1.0e-4, n_steps = 2000", &
                               contact="stiffness = 1.0e6, exponent = 1.5, scheme = 'implicit'", &
                               convolution="methods = 'direct', 'exact'")
        call check_files(scene_from_text('sdof.nml', sdof_text), ['direct', 'exact '], error)
        if (.not. allocated(error)) call check_files(scene_from_text('tyre.nml', tyre_text), ['exact', 'modal'], error)
    end subroutine test_block_files

    !> Run a scene whole (one block) and in blocks; each method's files must be equal.
    subroutine check_files(scene, methods, error)
        type(scene_type), intent(in) :: scene
        character(len=*), intent(in) :: methods(:)
        type(test_error), allocatable, intent(out) :: error

        integer, parameter :: tried(4) = [1, 7, 333, 0]
        type(error_type), allocatable :: failure
        character(len=:), allocatable :: path
        integer :: i, k, status

        call run_blocked(scene, huge(1), failure)
        call check(error, .not. allocated(failure), scene%name//': the whole run')
        if (allocated(error)) return
        do k = 1, size(methods)
            path = scratch//'/'//scene%name//'_'//trim(methods(k))//'.dat'
            call execute_command_line('cp '//path//' '//path//'.whole', exitstat=status)
        end do
        do i = 1, size(tried)
            if (tried(i) > 0) then
                call run_blocked(scene, tried(i), failure)
            else
                open (newunit=status, status='scratch', action='readwrite')
                call run_scene(scene, status, failure)
                close (status)
            end if
            call check(error, .not. allocated(failure), scene%name//': a blocked run')
            if (allocated(error)) return
            do k = 1, size(methods)
                path = scratch//'/'//scene%name//'_'//trim(methods(k))//'.dat'
                call check(error, same_lines(path, path//'.whole'), path//' differs with blocks of '// &
                           trim(adjustl(int_label(tried(i))))//' steps')
                if (allocated(error)) return
            end do
        end do
    end subroutine check_files

    !> A block size as text (0: the default).
    pure function int_label(i) result(text)
        integer, intent(in) :: i
        character(len=12) :: text

        write (text, '(i0)') i
        if (i == 0) text = 'default'
    end function int_label

    ! ---- decimation and faults -----------------------------------------------------------

    !> output_every = 7 over 100 steps, in blocks of 10: 15 rows, the lines of steps 0, 7,
    !> ..., 98 of the undecimated file, and the header says which steps they are.
    subroutine test_output_every(error)
        type(test_error), allocatable, intent(out) :: error

        character(len=:), allocatable :: text
        character(len=*), parameter :: path = scratch//'/every_modal.dat'
        type(error_type), allocatable :: failure
        character(len=256), allocatable :: all_rows(:), some_rows(:)
        integer :: j

        text = tab1_scene(scene="name = 'every', output_dir = '"//scratch//"', dt = 1.0e-4, n_steps = 100, " &
                          //'output_every = OUT', convolution="methods = 'modal'")
        call run_blocked(scene_from_text('every1.nml', replace_mark(text, '1')), 10, failure)
        call read_lines(path, all_rows)
        if (.not. allocated(failure)) call run_blocked(scene_from_text('every7.nml', replace_mark(text, '7')), 10, &
                                                       failure)
        call read_lines(path, some_rows)
        call check(error, .not. allocated(failure) .and. size(all_rows) == 103 .and. size(some_rows) == 3 + 15, &
                   'rows: 100 and 15 under 3 header lines')
        if (allocated(error)) return
        call check(error, all(some_rows(4:) == all_rows([(4 + 7*j, j=0, 14)])), 'the rows of steps 0, 7, ..., 98')
        if (allocated(error)) return
        call check(error, index(some_rows(1), 'a row every 7 steps (steps 0, 7, 14, ...)') > 0, &
                   'header: '//trim(some_rows(1)))
        if (allocated(error)) return
        call check(error, all(some_rows(2:3) == all_rows(2:3)) .and. index(all_rows(1), 'a row every') == 0, &
                   'units and columns unchanged; no decimation note at output_every = 1')
    end subroutine test_output_every

    !> `text` with the mark OUT replaced.
    pure function replace_mark(text, value) result(replaced)
        character(len=*), intent(in) :: text, value
        character(len=:), allocatable :: replaced

        integer :: at

        at = index(text, 'OUT')
        replaced = text(:at - 1)//value//text(at + 3:)
    end function replace_mark

    !> The explicit step with a linear k_c = 1e9 N/m at 0.1 ms (omega_c*dt = 3.16) diverges at
    !> step 97 (doc/methods.md): run in blocks of 10, the file holds steps 0..96 (no `.part` left) and
    !> the message names it and the step. The tyre with a divergence bound of 50 micrometres
    !> stops at its first step beyond it (step 17, in the third block of 7), with N_c rows per
    !> step before it in its file.
    subroutine test_divergence(error)
        type(test_error), allocatable, intent(out) :: error

        character(len=:), allocatable :: sdof_text
        character(len=*), parameter :: tyre_text = "&scene name = 'bound', output_dir = '"//scratch//"', " &
            //"dt = 2.0e-5, n_steps = 300 / &structure model = 'tyre', f_modes = 1000.0 / &road profile = " &
            //"'file', road_file = 'data/road_sample.dat', x_start = 1.0, speed = 20.0 / &contact n_points = 4, " &
            //"stiffness = 2.0e5, exponent = 1.0, preload = 1000.0, divergence_bound = 5.0e-5 / " &
            //"&convolution methods = 'modal' /"
        character(len=*), parameter :: sdof_path = scratch//'/stiff_modal.dat', tyre_path = scratch//'/bound_modal.dat'
        type(error_type), allocatable :: failure
        integer :: step

        sdof_text = tab1_scene(scene="name = 'stiff', output_dir = '"//scratch//"', dt = 1.0e-4, n_steps = 2000", &
                               contact='stiffness = 1.0e9, exponent = 1.0', convolution="methods = 'modal'")
        call run_blocked(scene_from_text('stiff.nml', sdof_text), 10, failure)
        call check(error, allocated(failure), 'the stiff run is stopped')
        if (allocated(error)) return
        call check(error, failure%stat == stat_numerical .and. index(failure%message, 'diverged at step 97') > 0 &
                   .and. index(failure%message, 'rows up to then in '//sdof_path) > 0, 'message: '//failure%message)
        if (allocated(error)) return
        call check(error, data_rows(sdof_path) == 97 .and. .not. exists(sdof_path//'.part'), &
                   'steps 0..96 in the final file, no .part')
        if (allocated(error)) return
        call run_blocked(scene_from_text('bound.nml', tyre_text), 7, failure)
        call check(error, allocated(failure), 'the tyre run is stopped by its bound')
        if (allocated(error)) return
        step = step_of(failure%message)
        call note('tyre stopped at step', real(step, dp))
        call check(error, failure%stat == stat_numerical .and. step > 0 .and. &
                   index(failure%message, 'rows up to then in '//tyre_path) > 0, 'message: '//failure%message)
        if (allocated(error)) return
        call check(error, data_rows(tyre_path) == 4*step .and. .not. exists(tyre_path//'.part'), &
                   'N_c rows per step before the fault in the final file, no .part')
    end subroutine test_divergence

    !> The step number after 'at step ' in a message (-1 when there is none).
    integer function step_of(message)
        character(len=*), intent(in) :: message

        integer :: at, stat

        step_of = -1
        at = index(message, 'at step ')
        if (at == 0) return
        read (message(at + 8:), *, iostat=stat) step_of
        if (stat /= 0) step_of = -1
    end function step_of

    ! ---- counters, progress, the long run ------------------------------------------------

    !> A convolver whose step counter starts beyond 2^31 - 1 (a multiple of its ring sizes,
    !> so that the FFT levels are aligned as at step 0) gives the same histories as a fresh
    !> one: direct, fft and recursive over 5000 pushes of a 3000-tap kernel, bit for bit once
    !> the kernel is full (before that, direct sums the ring's leading zeros in another
    !> order: equal to round-off).
    subroutine test_past_int32(error)
        type(test_error), allocatable, intent(out) :: error

        class(convolver), allocatable :: fresh, late
        real(dp), allocatable :: kernel(:)
        integer(int64) :: offset
        real(dp) :: worst
        integer :: i, n
        logical :: same

        kernel = sdof_impulse(1.0_dp, 1.0e6_dp, 0.002_dp, [(n*dt, n=0, 3000)])
        do i = 1, 3
            select case (i)
            case (1)
                fresh = new_direct_convolver(kernel, dt)
                late = new_direct_convolver(kernel, dt)
            case (2)
                fresh = new_fft_convolver(kernel, dt)
                late = new_fft_convolver(kernel, dt)
            case default
                fresh = new_recursive_convolver(sdof_modes(1.0_dp, 1.0e6_dp, 0.02_dp), dt)
                late = new_recursive_convolver(sdof_modes(1.0_dp, 1.0e6_dp, 0.02_dp), dt)
            end select
            offset = 2_int64**31 + 2_int64**20
            late%step = offset*ring_period(late)
            same = .true.
            worst = 0.0_dp
            do n = 0, 4999
                if (n > size(kernel)) same = same .and. fresh%history() == late%history()
                worst = max(worst, abs(fresh%history() - late%history()))
                call fresh%push(sin(0.01_dp*n) + 1.0_dp)
                call late%push(sin(0.01_dp*n) + 1.0_dp)
            end do
            call check(error, same .and. worst <= 1.0e-12_dp*abs(fresh%history()) .and. &
                       late%step == offset*ring_period(late) + 5000, fresh%name//': histories differ past 2^31 pushes')
            call fresh%release()
            call late%release()
            deallocate (fresh, late)
            if (allocated(error)) return
        end do
    end subroutine test_past_int32

    !> The period of a convolver's ring positions in steps (1 when it has none that follow the
    !> step counter): for fft, the product of its ring sizes.
    integer(int64) function ring_period(conv)
        class(convolver), intent(in) :: conv

        ring_period = 1
        select type (conv)
        type is (fft_convolver)
            ring_period = size(conv%rings%recent, 1, kind=int64)*size(conv%rings%pending, 1, kind=int64)
        end select
    end function ring_period

    !> Text, decision and silence of the progress line (not its timing).
    subroutine test_progress(error)
        type(test_error), allocatable, intent(out) :: error

        type(progress_meter) :: meter
        character(len=:), allocatable :: line

        line = progress_line('modal', 25_int64, 100_int64, 2.5_dp)
        call check(error, line == 'greenconv: modal    25.0 %    1.00E+01 steps/s  0:00:08 left', 'line: '//line)
        if (allocated(error)) return
        line = progress_line('exact', 0_int64, 100000000_int64, 3.0_dp)
        call check(error, index(line, '0.0 %') > 0 .and. index(line, '--:--:-- left') > 0, 'no step yet: '//line)
        if (allocated(error)) return
        line = progress_line('direct', 1_int64, 100000000_int64, 1.0_dp)
        call check(error, index(line, '27777:46:39 left') > 0, 'hours beyond a day: '//line)
        if (allocated(error)) return
        call check(error, .not. progress_due(1.9_dp, -1.0_dp) .and. progress_due(2.0_dp, -1.0_dp) .and. &
                   .not. progress_due(2.3_dp, 2.0_dp) .and. progress_due(2.5_dp, 2.0_dp), &
                   'shown after 2 s, then at most every 0.5 s')
        if (allocated(error)) return
        call start_progress(meter, 'modal', 100_int64, .true., terminal=.true.)
        call check(error, meter%enabled, 'asked for, on a terminal: enabled')
        if (allocated(error)) return
        call start_progress(meter, 'modal', 100_int64, .true., terminal=.false.)
        call check(error, .not. meter%enabled, 'standard error not a terminal: silent')
        if (allocated(error)) return
        call start_progress(meter, 'modal', 100_int64, .false., terminal=.true.)
        call check(error, .not. meter%enabled, 'progress = .false. (--quiet): silent')
    end subroutine test_progress

    !> 1e8 steps of 0.1 ms (10^4 s) of the SDOF oscillator (M = 1 kg, K = 1e6 N/m, xi = 0.02)
    !> on a linear contact spring (k_c = 1e6 N/m) over a road step of h = 0.1 mm, with `exact`
    !> and the implicit step (discretely exact static balance), through run_scene as the
    !> driver runs it, a row every 1e6 steps. (a) From the second row on the run rests in
    !> the static state u = k_c*h/(K + k_c), F = F0 + K*u; (b) all 100 rows are finite and the
    !> last is at t = 9900 s; (c) the peak resident memory (VmHWM, reset through
    !> /proc/self/clear_refs) stays within 64 MB of the resident memory before the run, where
    !> the histories of 1e8 steps would take 4 GB; with the force spectra on (20 Hz to 4 kHz:
    !> Welch segments of 32768 steps), whose file must say that every step went into its
    !> 1 + (1e8 - 32768)/16384 = 6102 segments.
    subroutine test_hundred_million(error)
        type(test_error), allocatable, intent(out) :: error

        character(len=:), allocatable :: text
        real(dp), parameter :: h = 1.0e-4_dp, stiffness = 1.0e6_dp, k_c = 1.0e6_dp
        type(scene_type) :: scene
        type(error_type), allocatable :: failure
        real(dp), allocatable :: rows(:, :)
        character(len=256), allocatable :: lines(:)
        real(dp) :: u_static, worst, seconds
        integer(int64) :: before_kb, peak_kb, clock_start, clock_end, clock_rate
        logical :: measured

        text = tab1_scene(scene="name = 'long', output_dir = '"//scratch//"', dt = 1.0e-4, n_steps = 100000000, " &
                          //'output_every = 1000000, spectra = .true.', &
                          contact="stiffness = 1.0e6, exponent = 1.0, scheme = 'implicit'", &
                          convolution="methods = 'exact'")
        scene = scene_from_text('long.nml', text)
        scene%progress = .false.
        deallocate (scene%road)
        allocate (scene%road, source=step_road(level=h))
        call memory_baseline(before_kb, measured)
        call system_clock(clock_start, clock_rate)
        call run_blocked(scene, 16384, failure)
        call system_clock(clock_end)
        seconds = real(clock_end - clock_start, dp)/real(clock_rate, dp)
        call note('wall s', seconds)
        call check(error, .not. allocated(failure), 'the run completes')
        if (allocated(error)) return
        call read_table(scratch//'/long_exact.dat', rows)
        call check(error, size(rows, 2) == 100 .and. all(ieee_is_finite(rows)), '100 finite rows')
        if (allocated(error)) return
        call check(error, rows(1, 100), 9900.0_dp, 'time of the last row [s]', thr=1.0e-12_dp, rel=.true.)
        if (allocated(error)) return
        call read_lines(scratch//'/long_exact_spectra.dat', lines)
        call check(error, size(lines) > 3, 'the spectra file is written')
        if (allocated(error)) return
        call check(error, index(lines(3), 'segments of 32768 samples') > 0 .and. &
                   index(lines(3), ' '//trim(adjustl(int_label(1 + (100000000 - 32768)/16384)))//' segments averaged') &
                   > 0, 'spectra: '//trim(lines(3)))
        if (allocated(error)) return
        u_static = k_c*h/(stiffness + k_c)
        worst = max(maxval(abs(rows(3, 2:) - u_static))/u_static, &
                    maxval(abs(rows(4, 2:) - (scene%preload + stiffness*u_static)))/(stiffness*u_static))
        call note('max rel. error to the static state', worst)
        call check(error, worst, 0.0_dp, 'u and F against k_c*h/(K + k_c)', thr=1.0e-10_dp)
        if (allocated(error)) return
        if (.not. measured) then
            call note('memory not measured: /proc/self/clear_refs or status unavailable', 0.0_dp)
            return
        end if
        peak_kb = status_kb('VmHWM:')
        call note('peak RSS growth MB', real(peak_kb - before_kb, dp)/1024.0_dp)
        call check(error, peak_kb - before_kb < 64*1024, 'peak resident memory within 64 MB of that before the run')
        if (allocated(error)) return
        call check(error, probe_sees(128), 'control: the peak RSS sees a 128 MB array filled after the run')
    end subroutine test_hundred_million

    !> Whether VmHWM grows by most of `megabytes` when an array that large is filled: the
    !> measurement would see the histories of a run that stored them.
    logical function probe_sees(megabytes)
        integer, intent(in) :: megabytes

        real(dp), allocatable :: ballast(:)
        integer(int64) :: before_kb

        before_kb = status_kb('VmHWM:')
        allocate (ballast(megabytes*131072))
        ballast(:) = 1.0_dp
        probe_sees = status_kb('VmHWM:') - before_kb > int(0.9_dp*megabytes*1024, int64) .and. sum(ballast) > 0.0_dp
    end function probe_sees

    !> Reset the peak resident size to the current one (Linux: "5" into /proc/self/clear_refs)
    !> and return the current one [kB]; `measured` is false when /proc does not allow it.
    subroutine memory_baseline(rss_kb, measured)
        integer(int64), intent(out) :: rss_kb
        logical, intent(out) :: measured

        integer :: unit, stat

        rss_kb = -1
        measured = .false.
        open (newunit=unit, file='/proc/self/clear_refs', action='write', status='old', iostat=stat)
        if (stat /= 0) return
        write (unit, '(a)', iostat=stat) '5'
        close (unit)
        if (stat /= 0) return
        rss_kb = status_kb('VmRSS:')
        measured = rss_kb > 0 .and. status_kb('VmHWM:') > 0
    end subroutine memory_baseline

    !> A size [kB] from /proc/self/status, e.g. `VmHWM:` (-1 when absent).
    integer(int64) function status_kb(key)
        character(len=*), intent(in) :: key

        character(len=256) :: line
        integer :: unit, stat

        status_kb = -1
        open (newunit=unit, file='/proc/self/status', action='read', status='old', iostat=stat)
        if (stat /= 0) return
        do
            read (unit, '(a)', iostat=stat) line
            if (stat /= 0) exit
            if (index(line, key) == 1) then
                read (line(len(key) + 1:), *, iostat=stat) status_kb
                if (stat /= 0) status_kb = -1
                exit
            end if
        end do
        close (unit)
    end function status_kb

    !> The 5 columns of a single-point output file, one column of `rows` per line.
    subroutine read_table(path, rows)
        character(len=*), intent(in) :: path
        real(dp), allocatable, intent(out) :: rows(:, :)

        character(len=256), allocatable :: lines(:)
        integer :: i, n

        call read_lines(path, lines)
        allocate (rows(5, count(lines(:)(1:1) /= '#')))
        n = 0
        do i = 1, size(lines)
            if (lines(i)(1:1) == '#') cycle
            n = n + 1
            read (lines(i), *) rows(:, n)
        end do
    end subroutine read_table

end module test_longrun_mod
