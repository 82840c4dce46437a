!> The one streaming loop of a contact run, used by the driver's runner (greenconv_scene_run_runner),
!> by each variant of a sweep (greenconv_scene_sweep_variant) and so by the library's
!> `gc_run_scene`: a run is streamed in blocks of steps, the road sampled per block, the
!> contact loop continued from the convolver's state, and each block handed to the sinks the
!> caller asked for:
!>
!> - a column file (text `.dat`, or binary `.bin` with its header `.bin.txt`) of the rows of
!>   every `output_every`-th step (a multi-point run's per-point histories: every `point_every`-th);
!> - a multi-point run's totals file (t, total force, contact area, points in contact, every
!>   `output_every`-th step), its map file (the per-point rows at the steps of `map_times`) and,
!>   with the spectra, the spectra of its contact area;
!> - the scene's force spectra (`&scene spectra`, greenconv_scene_run_spectra_output);
!> - a force summary (max, mean, rms of the total contact force, steps in contact: a sweep row);
!> - the whole total-force history (a sweep's band levels).
!>
!> So the memory a run needs does not grow with N_t (unless the history is asked for). A
!> numerical fault stops the run: the column file is completed with the rows before it; a
!> failed write deletes it. A `contact_run` is one method's run, single- and multi-point
!> alike: a multi-point convolver (a single-point structure's convolver wrapped as the 1 x 1
!> case, greenconv_conv_point_matrix) stepped by greenconv_contact_multi's loop. Only what a
!> scene asks for differs: where the road is sampled (under the one point, or under the
!> points of the tyre or of a Green's matrix file) and how the rows are laid out.
module greenconv_scene_run_stream
    use, intrinsic :: iso_fortran_env, only: int64
    use greenconv_ext_clock, only: thread_seconds
    !$ use omp_lib, only: omp_get_max_threads, omp_in_parallel
    use greenconv_core_kinds, only: dp
    use greenconv_core_error, only: error_type, fatal_error
    use greenconv_core_text, only: sci_text, trimmed_real_text, int_text
    use greenconv_conv_convolver, only: convolver
    use greenconv_conv_multipoint, only: multipoint_convolver
    use greenconv_conv_point_matrix, only: point_matrix, wrap_point
    use greenconv_conv_builder, only: make_convolver
    use greenconv_ident_structure, only: structure_model
    use greenconv_contact_multi, only: multi_contact_response, multi_contact_state, multi_contact_block, &
                                       start_multi_contact, newton_options
    use greenconv_contact_budget, only: doubling_sums, step_doubling_error
    use greenconv_contact_laws, only: contact_law, replicate_law
    use greenconv_conv_methods, only: method_order
    use greenconv_io_files, only: column_writer, open_columns, append_rows, close_columns, discard_columns, first_kept
    use greenconv_scene_run_progress, only: progress_meter, start_progress, update_progress, finish_progress
    use greenconv_scene_read_facade, only: scene_type
    use greenconv_scene_models_facade, only: multi_point_model, structure_kind, find_model, sample_patch_road
    use greenconv_scene_run_spectra_output, only: force_spectra, start_force_spectra, add_contact_forces, &
                                              finish_force_spectra
    use greenconv_scene_run_points, only: scene_points, point_rows, points_convolver
    use greenconv_scene_run_output, only: totals_table
    implicit none
    private

    public :: contact_run, stream_sinks, force_summary, stream_run, make_run_convolver, start_run
    public :: step_doubling, start_step_doubling, time_step_estimate, band_estimate, halve_step

    !> One method's contact run of a scene, single- or multi-point.
    type :: contact_run
        !> Whether the scene is a multi-point one (the tyre, a Green's matrix file): the road
        !> under `points`, N_c rows per step; else one point, the scene's road, 5 columns.
        logical :: several = .false.
        !> The convolver (`make_run_convolver`).
        class(multipoint_convolver), allocatable :: conv
        !> The contact loop's state (`start_run`).
        type(multi_contact_state) :: state
        !> The last block's response.
        type(multi_contact_response) :: response
        !> Road heights [m] under the points, heights(step, point), of the block.
        real(dp), allocatable :: heights(:, :)
        !> The points of a multi-point scene: on the body (x, y) and on the road
        !> (the `find_points` of the scene's model, greenconv_scene_models_registry, called by the owner of the run).
        type(scene_points) :: points
        !> Largest total force [N] so far.
        real(dp) :: peak = -huge(1.0_dp)
    contains
        !> Steps done so far.
        procedure :: step => run_step
        !> Sample the road of steps first..first + count - 1.
        procedure :: sample => run_sample
        !> Step the block sampled last; the contact loop alone, which `stream_run` times.
        procedure :: advance => run_advance
        !> The rows of the block stepped last that are written.
        procedure :: rows => run_rows
        !> The contact forces of the block stepped last.
        procedure :: forces => run_forces
        !> The totals rows of the block stepped last that are written.
        procedure :: totals => run_totals
    end type contact_run

    !> Running summary of a total-force history.
    type :: force_summary
        !> Steps summarised and steps with a positive force.
        integer(int64) :: steps = 0, in_contact = 0
        !> Largest force [N], sum of the forces [N], sum of their squares [N^2].
        real(dp) :: peak = 0.0_dp, total = 0.0_dp, squares = 0.0_dp
    end type force_summary

    !> Where the blocks of a run go; each sink is used when asked for.
    type :: stream_sinks
        !> Column file: its path (unallocated: none), header lines and number of columns.
        character(len=:), allocatable :: path
        !> Header lines of the column file (written after `# `).
        character(len=:), allocatable :: header(:)
        !> Number of values of each row of the column file.
        integer :: n_columns = 0
        !> Whether the column file is binary float64 (`.bin` with `.bin.txt`) rather than text.
        logical :: binary = .false.
        !> Steps between two rows of the column file (0: the scene's `output_every`).
        integer :: every = 0
        !> Totals file of a multi-point run (text): its path (unallocated: none) and header lines.
        character(len=:), allocatable :: totals_path
        !> Header lines of the totals file (written after `# `).
        character(len=:), allocatable :: totals_header(:)
        !> Area [m^2] a point in contact adds to the contact area (totals file, area spectra).
        real(dp) :: share = 0.0_dp
        !> Map file of a multi-point run (text, the column file's rows at `map_steps`): its path
        !> (unallocated: none) and header lines.
        character(len=:), allocatable :: maps_path
        !> Header lines of the map file (written after `# `).
        character(len=:), allocatable :: maps_header(:)
        !> Steps (from 0, increasing) of the maps.
        integer(int64), allocatable :: map_steps(:)
        !> Whether the scene's force spectra (`&scene spectra`) are computed and written.
        logical :: scene_spectra = .false.
        !> Whether the total force is summarised into `summary`.
        logical :: summarise = .false.
        !> The summary of the total force [N] (with `summarise`).
        type(force_summary) :: summary
        !> The total force [N] of every step (allocated by the caller to N_t to ask for it).
        real(dp), allocatable :: history(:)
    end type stream_sinks

    !> The time-step term of a run's error budget, estimated from the run itself by step
    !> doubling: the same method on the same scene at 2*dt and 4*dt, stepped alongside the run
    !> (no file, no spectra), and the contact forces F_i compared where the grids meet. With the
    !> differences d_1 = ||F(dt) - F(2 dt)|| on the 2*dt grid and the ratio
    !> r = ||F(2 dt) - F(4 dt)||/||F(dt) - F(2 dt)|| on the 4*dt grid, the run's own error is
    !> about d_1/sqrt((r - 1)*(2^p - 1)) relative to ||F(dt) - F0||, r held within [1.75, 4] for
    !> a method of order p (1 for `backward`, else 2): Richardson's d_1/(rho - 1) with the ratio rho
    !> of the errors at 2*dt and dt taken between the ratio observed at the coarser pair and the
    !> method's asymptotic 2^p (geometrically), as the order of a pair approaches p from the coarse
    !> side. It costs 1/2 + 1/4 of the run for a
    !> modal method, 1/4 + 1/16 for `direct` (half and a quarter of the kernel).
    type :: step_doubling
        !> Whether the companions were asked for (a run of at least 8 steps).
        logical :: active = .false.
        !> Order of the method in dt.
        integer :: order = 2
        !> The scene at 2*dt and 4*dt (their n_steps cover the same time).
        type(scene_type) :: scenes(2)
        !> The companion runs.
        type(contact_run) :: coarse(2)
        !> Whether each companion is running (false once it failed or could not be built).
        logical :: running(2) = .false.
        !> The sums of step doubling (greenconv_contact_budget), over the run and the points.
        type(doubling_sums) :: sums
        !> CPU seconds of the companions.
        real(dp) :: seconds = 0.0_dp
        !> Why the run at 2*dt is missing (its build's or its fault's message), or ''.
        character(len=:), allocatable :: missing
        !> The band companion's scene: the run's with f_modes the wider band.
        type(scene_type) :: band_scene
        !> The band's companion: the same run at dt with the modes up to the wider band, for a
        !> model whose band leaves modes out.
        type(contact_run) :: band_run
        !> Whether the band's companion is running; whether it holds every mode of the structure.
        logical :: band_running = .false., band_complete = .false.
        !> Modes of the run and of the band's companion.
        integer :: band_modes(2) = 0
        !> Sums over the steps of |F - F_band|^2 and |F_band - F0|^2 [N^2], over the points.
        real(dp) :: band_difference = 0.0_dp, band_reference = 0.0_dp
        !> Why the band is not estimated, or ''.
        character(len=:), allocatable :: band_missing
        !> The time-step term [-] from the same run at dt/2 (`halve_step`), when the run at 2*dt
        !> failed; negative: none.
        real(dp) :: halved = -1.0_dp
        !> How the run at dt/2 went, in words.
        character(len=:), allocatable :: halved_text
    end type step_doubling

contains

    !> Build and start the companions of a run (`run` made by `make_run_convolver`, its points
    !> found) at 2*dt and 4*dt. A companion that cannot be built or started is left out; the
    !> estimate says so (`time_step_estimate`).
    subroutine start_step_doubling(doubling, run, scene, structure, method)
        !> The companions, started.
        type(step_doubling), intent(out) :: doubling
        !> The run they accompany.
        type(contact_run), intent(in) :: run
        !> The run's scene.
        type(scene_type), intent(in) :: scene
        !> The structure of a single-point scene (not used for a multi-point one).
        type(structure_model), intent(in) :: structure
        !> The method's name.
        character(len=*), intent(in) :: method

        type(error_type), allocatable :: error
        type(structure_model) :: coarse
        character(len=:), allocatable :: text
        integer :: f

        doubling%active = scene%n_steps >= 8
        doubling%missing = ''
        doubling%band_missing = ''
        if (.not. doubling%active) return
        call start_band_companion(doubling, run, scene, structure, method)
        doubling%order = method_order(method)
        do f = 1, 2
            doubling%scenes(f) = scene
            doubling%scenes(f)%dt = scene%dt*2**f
            doubling%scenes(f)%n_steps = (scene%n_steps + 2**f - 1)/2**f
            doubling%scenes(f)%progress = .false.
            doubling%coarse(f)%points = run%points
            ! g sampled at dt (from a receptance, or given): every 2^f-th sample is g at 2^f*dt
            coarse = structure
            if (allocated(structure%sampled_g)) then
                coarse%sampled_g = structure%sampled_g(1::2**f)
                coarse%sampled_step = structure%sampled_step*2**f
            end if
            call make_run_convolver(doubling%coarse(f), doubling%scenes(f), coarse, method, text, error)
            if (.not. allocated(error)) call start_run(doubling%coarse(f), doubling%scenes(f), error)
            doubling%running(f) = .not. allocated(error)
            if (f == 1 .and. allocated(error)) doubling%missing = error%message
            if (allocated(error)) deallocate (error)
        end do
    end subroutine start_step_doubling

    !> When the run at 2*dt failed (dt within a factor 2 of the method's stable step), the
    !> time-step term from the other side: the same run at dt/2 over the whole time, with its own
    !> companion at dt (the run itself again), so that d = ||F(dt) - F(dt/2)||/||F(dt/2) - F0||
    !> and F(dt/2)'s own term e_2 (from its pair dt/2, dt, the ratio held at 1.75 without the run
    !> at 2*dt) give F(dt)'s as d + e_2: the two errors add along F(dt) - F(dt/2) + F(dt/2) -
    !> F_true, and with the asymptotic ratio 2^p this is Richardson's 2^p*d/(2^p - 1). It costs
    !> twice the run and its companion at dt once more (for `direct` on g's samples, four times:
    !> the kernel is twice as long); a g sampled at dt only (from a receptance, or given) has no
    !> samples at dt/2 and keeps the term at 1.
    subroutine halve_step(doubling, run, scene, structure, method, block)
        !> The run's companions, the run done; `halved` set.
        type(step_doubling), intent(inout) :: doubling
        !> The run (its points).
        type(contact_run), intent(in) :: run
        !> The run's scene.
        type(scene_type), intent(in) :: scene
        !> The structure of a single-point scene.
        type(structure_model), intent(in) :: structure
        !> The method's name.
        character(len=*), intent(in) :: method
        !> Rows of a block of the stream.
        integer, intent(in) :: block

        type(scene_type) :: half
        type(contact_run) :: fine
        type(step_doubling) :: fine_doubling
        type(stream_sinks) :: none
        type(error_type), allocatable :: fault
        character(len=:), allocatable :: text
        real(dp) :: seconds, e_half, begin, finish

        if (.not. doubling%active .or. doubling%running(1)) return
        if (.not. run%several .and. allocated(structure%sampled_g)) then
            doubling%halved_text = 'g is sampled at dt only: no run at dt/2'
            return
        end if
        call cpu_time(begin)
        half = scene
        half%dt = scene%dt/2
        half%n_steps = 2*scene%n_steps
        half%progress = .false.
        half%spectra = .false.
        fine%points = run%points
        call make_run_convolver(fine, half, structure, method, text, fault)
        if (.not. allocated(fault)) call start_run(fine, half, fault)
        if (.not. allocated(fault)) then
            call start_step_doubling(fine_doubling, fine, half, structure, method)
            ! the band's companion is the run's own business
            if (allocated(fine_doubling%band_run%conv)) call fine_doubling%band_run%conv%release()
            fine_doubling%band_running = .false.
            call stream_run(fine, half, method, block, none, '', seconds, fault, fine_doubling)
        end if
        if (allocated(fine%conv)) call fine%conv%release()
        if (.not. allocated(fault) .and. .not. fine_doubling%running(1)) then
            call fatal_error(fault, fine_doubling%missing)
        end if
        call cpu_time(finish)
        doubling%seconds = doubling%seconds + (finish - begin)
        if (allocated(fault)) then
            doubling%halved_text = 'the same run at dt/2 failed too ('//fault%message//')'
            return
        end if
        call time_step_estimate(fine_doubling, e_half, text)
        doubling%halved = 0.0_dp
        if (fine_doubling%sums%fine > 0.0_dp) doubling%halved = sqrt(fine_doubling%sums%fine_2/fine_doubling%sums%fine)
        doubling%halved = doubling%halved + e_half
        doubling%halved_text = 'its difference '//sci_text(doubling%halved - e_half)//' plus its own term ' &
                               //sci_text(e_half)//' ('//text//', in '//sci_text(finish - begin)//' s)'
    end subroutine halve_step

    !> Start the band's companion of a multi-point run whose model steps the modes up to a band
    !> (`run%points%band` > 0) and leaves some out: the same method at the same dt with the modes
    !> up to twice the band (four or eight times when no mode lies between), so that the
    !> difference of the two runs is the share of the modes between, dynamic and static alike.
    subroutine start_band_companion(doubling, run, scene, structure, method)
        type(step_doubling), intent(inout) :: doubling
        type(contact_run), intent(in) :: run
        type(scene_type), intent(in) :: scene
        type(structure_model), intent(in) :: structure
        character(len=*), intent(in) :: method

        type(structure_kind) :: model
        type(error_type), allocatable :: error
        character(len=:), allocatable :: text
        integer :: widening

        if (.not. run%several .or. run%points%band <= 0.0_dp .or. run%points%complete) return
        model = find_model(scene%model)
        if (.not. associated(model%find_points)) return
        doubling%band_modes(1) = run%points%modes%modes%n_modes()
        doubling%band_scene = scene
        doubling%band_scene%progress = .false.
        do widening = 1, 3
            doubling%band_scene%f_modes = run%points%band*2**widening
            call model%find_points(doubling%band_scene, doubling%band_run%points, text, error)
            if (allocated(error)) exit
            doubling%band_modes(2) = doubling%band_run%points%modes%modes%n_modes()
            if (doubling%band_modes(2) > doubling%band_modes(1)) exit
        end do
        if (.not. allocated(error) .and. doubling%band_modes(2) <= doubling%band_modes(1)) then
            doubling%band_missing = 'modes above the band not estimated: none up to '// &
                                    sci_text(doubling%band_scene%f_modes)//' Hz'
            return
        end if
        if (.not. allocated(error)) call make_run_convolver(doubling%band_run, doubling%band_scene, structure, method, &
                                                            text, error)
        if (.not. allocated(error)) call start_run(doubling%band_run, doubling%band_scene, error)
        doubling%band_running = .not. allocated(error)
        doubling%band_complete = doubling%band_run%points%complete
        if (allocated(error)) doubling%band_missing = 'modes above the band not estimated: the run with the modes ' &
            //'up to '//sci_text(doubling%band_scene%f_modes)//' Hz could not start ('//error%message//')'
    end subroutine start_band_companion

    !> Step the companions over the time of the run's last block (steps first..first + m - 1)
    !> and add the block's differences.
    subroutine advance_step_doubling(doubling, run, first, m)
        type(step_doubling), intent(inout) :: doubling
        type(contact_run), intent(in) :: run
        integer(int64), intent(in) :: first
        integer, intent(in) :: m

        integer(int64) :: start(2)
        real(dp) :: begin, finish

        call cpu_time(begin)
        start = [doubling%coarse(1)%step(), doubling%coarse(2)%step()]
        if (doubling%band_running) call step_band_companion(doubling, first, m)
        call step_coarse_companions(doubling, first, m)
        call add_differences(doubling, run, first, m, start)
        call cpu_time(finish)
        doubling%seconds = doubling%seconds + (finish - begin)
    end subroutine advance_step_doubling

    !> Whether `advance_together` steps a run and its companions at once: companions started,
    !> at least two threads, and not inside a parallel region (a host's, or a sweep's).
    logical function concurrent_companions(doubling)
        type(step_doubling), intent(in) :: doubling

        concurrent_companions = .false.
        if (.not. doubling%active) return
        !$ concurrent_companions = omp_get_max_threads() > 1
        !$ if (concurrent_companions) concurrent_companions = .not. omp_in_parallel()
    end function concurrent_companions

    !> The run's block and its companions' (`advance_step_doubling`) stepped at once as three
    !> OpenMP tasks on two threads: the run, the band's companion, the runs at 2*dt and 4*dt.
    !> They are independent runs, each stepped by one thread alone (the loops inside a parallel
    !> region stay serial), so every result is bit for bit that of one thread; the block's
    !> differences are added afterwards, unless the run failed. `seconds` is the run's CPU
    !> time and the companions' is added to theirs, each the CPU time of the thread that
    !> stepped it.
    subroutine advance_together(doubling, run, first, m, fault, seconds)
        type(step_doubling), intent(inout) :: doubling
        type(contact_run), intent(inout) :: run
        integer(int64), intent(in) :: first
        integer, intent(in) :: m
        type(error_type), allocatable, intent(out) :: fault
        !> CPU seconds [s] of the run's block.
        real(dp), intent(out) :: seconds

        integer(int64) :: start(2)
        real(dp) :: band_seconds, coarse_seconds, begin

        start = [doubling%coarse(1)%step(), doubling%coarse(2)%step()]
        seconds = 0.0_dp
        band_seconds = 0.0_dp
        coarse_seconds = 0.0_dp
        !$omp parallel num_threads(2) default(none) shared(doubling, run, first, m, fault, seconds, band_seconds, &
        !$omp coarse_seconds) private(begin)
        !$omp single
        !$omp task
        begin = thread_seconds()
        call run%advance(fault)
        seconds = thread_seconds() - begin
        !$omp end task
        !$omp task
        begin = thread_seconds()
        if (doubling%band_running) call step_band_companion(doubling, first, m)
        band_seconds = thread_seconds() - begin
        !$omp end task
        !$omp task
        begin = thread_seconds()
        call step_coarse_companions(doubling, first, m)
        coarse_seconds = thread_seconds() - begin
        !$omp end task
        !$omp end single
        !$omp end parallel
        doubling%seconds = doubling%seconds + band_seconds + coarse_seconds
        if (.not. allocated(fault)) call add_differences(doubling, run, first, m, start)
    end subroutine advance_together

    !> Step the band's companion over the run's last block (steps first..first + m - 1).
    subroutine step_band_companion(doubling, first, m)
        type(step_doubling), intent(inout) :: doubling
        integer(int64), intent(in) :: first
        integer, intent(in) :: m

        character(len=:), allocatable :: why

        if (.not. doubling%band_running) return
        call step_companion(doubling%band_run, doubling%band_scene, first, m, doubling%band_running, why)
        if (.not. doubling%band_running) doubling%band_missing = 'modes above the band not estimated: the run with ' &
            //'the modes up to '//sci_text(doubling%band_scene%f_modes)//' Hz failed ('//why//')'
    end subroutine step_band_companion

    !> Step the runs at 2*dt and 4*dt over the time of the run's last block (steps
    !> first..first + m - 1).
    subroutine step_coarse_companions(doubling, first, m)
        type(step_doubling), intent(inout) :: doubling
        integer(int64), intent(in) :: first
        integer, intent(in) :: m

        character(len=:), allocatable :: why
        integer(int64) :: start, target
        integer :: f

        do f = 1, 2
            start = doubling%coarse(f)%step()
            if (.not. doubling%running(f)) cycle
            target = min((first + m + 2**f - 1)/2**f, int(doubling%scenes(f)%n_steps, int64))
            if (target <= start) cycle
            call step_companion(doubling%coarse(f), doubling%scenes(f), start, int(target - start), &
                                doubling%running(f), why)
            if (f == 1 .and. .not. doubling%running(f)) doubling%missing = why
        end do
    end subroutine step_coarse_companions

    !> Add the differences of the run's last block (steps first..first + m - 1) and of its
    !> companions' steps from `start` (their steps before the block) to the budget's sums.
    subroutine add_differences(doubling, run, first, m, start)
        type(step_doubling), intent(inout) :: doubling
        type(contact_run), intent(in) :: run
        integer(int64), intent(in) :: first
        integer, intent(in) :: m
        integer(int64), intent(in) :: start(2)

        integer(int64) :: j

        if (doubling%band_running) then
            associate (u => run%response%force, wide => doubling%band_run%response%force, f0 => run%state%preload)
                do j = 0, m - 1
                    doubling%band_difference = doubling%band_difference + sum((u(j, :) - wide(j, :))**2)
                    doubling%band_reference = doubling%band_reference + sum((wide(j, :) - f0)**2)
                end do
            end associate
        end if
        if (doubling%running(1)) then
            associate (u => run%response%force, u2 => doubling%coarse(1)%response%force, f0 => run%state%preload, &
                       sums => doubling%sums)
                do j = start(1), doubling%coarse(1)%step() - 1
                    sums%fine = sums%fine + sum((u(2*j - first, :) - f0)**2)
                    sums%fine_2 = sums%fine_2 + sum((u(2*j - first, :) - u2(j - start(1), :))**2)
                end do
                if (doubling%running(2)) then
                    associate (u4 => doubling%coarse(2)%response%force)
                        do j = start(2), doubling%coarse(2)%step() - 1
                            sums%grid_12 = sums%grid_12 + sum((u(4*j - first, :) - u2(2*j - start(1), :))**2)
                            sums%grid_24 = sums%grid_24 + sum((u2(2*j - start(1), :) - u4(j - start(2), :))**2)
                        end do
                    end associate
                end if
            end associate
        end if
    end subroutine add_differences

    !> Step a companion run over `count` steps from `first`; a fault stops it (`running` false,
    !> its convolver released) with its message in `why`.
    subroutine step_companion(companion, scene, first, count, running, why)
        type(contact_run), intent(inout) :: companion
        type(scene_type), intent(in) :: scene
        integer(int64), intent(in) :: first
        integer, intent(in) :: count
        logical, intent(inout) :: running
        character(len=:), allocatable, intent(out) :: why

        type(error_type), allocatable :: fault

        why = ''
        call companion%sample(scene, first, count)
        call companion%advance(fault)
        if (.not. allocated(fault)) return
        running = .false.
        why = fault%message
        call companion%conv%release()
    end subroutine step_companion

    !> The band's term of the run's relative error: ||F - F_wide||/||F_wide - F0|| from the band's
    !> companion (`start_band_companion`), times 1 when it holds every mode of the structure,
    !> else times 2 (the modes above the wider band taken to leave out at most as much again:
    !> a plate's static flexibility above f falls as 1/f, and faster with the static compliance
    !> of those modes in W0), and in words how it was found; 0 and '' for a model without a band.
    subroutine band_estimate(doubling, estimate, text)
        !> The companions, the run done.
        type(step_doubling), intent(inout) :: doubling
        !> Relative error [-] of the contact forces due to the modes above the band.
        real(dp), intent(out) :: estimate
        !> How it was found.
        character(len=:), allocatable, intent(out) :: text

        estimate = 0.0_dp
        text = ''
        if (allocated(doubling%band_missing)) text = doubling%band_missing
        if (allocated(doubling%band_run%conv)) call doubling%band_run%conv%release()
        if (.not. doubling%band_running .or. doubling%band_reference <= 0.0_dp) return
        estimate = sqrt(doubling%band_difference/doubling%band_reference)
        if (.not. doubling%band_complete) estimate = 2.0_dp*estimate
        text = 'modes above the band from the run with the '//int_text(doubling%band_modes(2))//' modes up to ' &
               //trimmed_real_text(doubling%band_scene%f_modes, 0.1_dp, 1.0e7_dp, 1, 1)//' Hz'
        if (doubling%band_complete) then
            text = text//' (every mode)'
        else
            text = text//' (twice the difference)'
        end if
    end subroutine band_estimate

    !> The time-step term of the run's relative error (module `step_doubling`), and in words how
    !> it was found. 0 without companions (a run of fewer than 8 steps); 1 when the run at 2*dt
    !> could not be made or failed (the time step is then near the method's limit).
    subroutine time_step_estimate(doubling, estimate, text)
        !> The companions, the run done.
        type(step_doubling), intent(inout) :: doubling
        !> Relative error [-] of the contact forces due to the time step.
        real(dp), intent(out) :: estimate
        !> How it was found.
        character(len=:), allocatable, intent(out) :: text

        real(dp) :: ratio
        integer :: f

        estimate = 0.0_dp
        text = 'time step not estimated (fewer than 8 steps)'
        if (.not. doubling%active) return
        do f = 1, 2
            if (allocated(doubling%coarse(f)%conv)) call doubling%coarse(f)%conv%release()
        end do
        if (.not. doubling%running(1)) then
            estimate = 1.0_dp
            text = 'the same run at 2*dt failed ('//doubling%missing//'): dt is near the limit of the method'
            if (doubling%halved >= 0.0_dp) then
                estimate = doubling%halved
                text = text//'; dt from the same run at dt/2, '//doubling%halved_text
            else if (allocated(doubling%halved_text)) then
                text = text//'; '//doubling%halved_text
            end if
            return
        end if
        if (doubling%sums%fine <= 0.0_dp) then
            text = 'time step: F = F0 throughout'
            return
        end if
        if (.not. doubling%running(2)) doubling%sums%grid_12 = 0.0_dp
        call step_doubling_error(doubling%sums, doubling%order, estimate, ratio)
        text = 'dt from the runs at 2*dt and 4*dt, ratio ' &
               //trimmed_real_text(ratio, 0.01_dp, 100.0_dp, 2, 2)
    end subroutine time_step_estimate

    !> One method's contact run (`run`, started at step 0), streamed in blocks of `block` steps
    !> into the sinks. `seconds` is the CPU time of the contact loop alone. On return `error`
    !> is a failed write (the column file then gone) or the numerical fault that stopped the
    !> run, its message after `prefix` and naming the column file that keeps the rows before it.
    subroutine stream_run(run, scene, method, block, sinks, prefix, seconds, error, doubling)
        !> The run.
        type(contact_run), intent(inout) :: run
        !> The scene (dt, n_steps, output_every, progress, spectra).
        type(scene_type), intent(in) :: scene
        !> The method's name (progress line, spectra file).
        character(len=*), intent(in) :: method
        !> Steps per block (>= 1); the results do not depend on it.
        integer, intent(in) :: block
        !> The sinks.
        type(stream_sinks), intent(inout) :: sinks
        !> Text put before a fault's message.
        character(len=*), intent(in) :: prefix
        !> CPU seconds of the contact loop.
        real(dp), intent(out) :: seconds
        !> Set for a failed write or a numerical fault.
        type(error_type), allocatable, intent(out) :: error
        !> Companions at 2*dt and 4*dt (`start_step_doubling`), stepped alongside, when present.
        type(step_doubling), intent(inout), optional :: doubling

        type(column_writer) :: writers(3)
        type(progress_meter) :: meter
        type(force_spectra) :: spectra, area_spectra
        type(error_type), allocatable :: fault
        real(dp), allocatable :: table(:, :), total(:), points(:, :), no_points(:, :)
        integer(int64) :: first
        real(dp) :: start, finish
        integer :: m, every, k, j
        logical :: together

        seconds = 0.0_dp
        every = merge(sinks%every, scene%output_every, sinks%every > 0)
        if (allocated(sinks%path)) call open_columns(writers(1), sinks%path, sinks%header, sinks%n_columns, error, &
                                                     binary=sinks%binary)
        if (allocated(sinks%totals_path) .and. .not. allocated(error)) &
            call open_columns(writers(2), sinks%totals_path, sinks%totals_header, 4, error)
        if (allocated(sinks%maps_path) .and. .not. allocated(error)) &
            call open_columns(writers(3), sinks%maps_path, sinks%maps_header, sinks%n_columns, error)
        if (allocated(error)) then
            call discard_all()
            return
        end if
        call start_progress(meter, method, int(scene%n_steps, int64), scene%progress)
        if (sinks%scene_spectra) call start_force_spectra(spectra, scene)
        if (sinks%scene_spectra .and. allocated(sinks%totals_path)) call start_force_spectra(area_spectra, scene, &
                                                                                             area=.true.)
        allocate (no_points(0, 0))
        together = .false.
        if (present(doubling)) together = concurrent_companions(doubling)
        do while (run%step() < scene%n_steps)
            first = run%step()
            m = int(min(int(block, int64), scene%n_steps - first))
            call run%sample(scene, first, m)
            if (together) then
                call advance_together(doubling, run, first, m, fault, finish)
                seconds = seconds + finish
            else
                call cpu_time(start)
                call run%advance(fault)
                call cpu_time(finish)
                seconds = seconds + (finish - start)
                if (present(doubling) .and. .not. allocated(fault)) then
                    if (doubling%active) call advance_step_doubling(doubling, run, first, m)
                end if
            end if
            if (((spectra%active .or. area_spectra%active) .and. .not. allocated(fault)) .or. sinks%summarise .or. &
                allocated(sinks%history)) call run%forces(total, points)
            if (spectra%active .and. .not. allocated(fault)) call add_contact_forces(spectra, total, points)
            if (area_spectra%active .and. .not. allocated(fault)) &
                call add_contact_forces(area_spectra, sinks%share*count(points > 0.0_dp, dim=2), no_points)
            if (sinks%summarise) call add_forces(sinks%summary, total)
            if (allocated(sinks%history)) sinks%history(first + 1:first + size(total)) = total
            if (writers(1)%opened) then
                call run%rows(first, every, table)
                call append_rows(writers(1), table, error)
            end if
            if (writers(2)%opened .and. .not. allocated(error)) then
                call run%totals(first, scene%output_every, sinks%share, table)
                call append_rows(writers(2), table, error)
            end if
            if (writers(3)%opened .and. .not. allocated(error)) then
                do k = 1, size(sinks%map_steps)
                    j = int(sinks%map_steps(k) - first)
                    if (j < 0 .or. j >= size(run%response%time)) cycle
                    call append_rows(writers(3), point_rows(run%points, run%response, j, size(run%response%time)), error)
                    if (allocated(error)) exit
                end do
            end if
            if (allocated(error) .or. allocated(fault)) exit
            call update_progress(meter, run%step())
        end do
        call finish_progress(meter, run%step())
        call close_all()
        if (sinks%scene_spectra) call finish_force_spectra(spectra, scene, method, error)
        if (area_spectra%active) call finish_force_spectra(area_spectra, scene, method, error)

    contains

        !> End the files: after a failed write, every one is deleted; else each is closed and
        !> renamed, and a numerical fault becomes `error`, naming the first file, which holds
        !> the rows before it.
        subroutine close_all()
            character(len=:), allocatable :: kept

            if (allocated(error)) then
                call discard_all()
                return
            end if
            do k = 1, size(writers)
                if (.not. writers(k)%opened) cycle
                if (.not. allocated(kept)) kept = writers(k)%path
                call close_columns(writers(k), error)
                if (allocated(error)) then
                    call discard_all()
                    return
                end if
            end do
            if (.not. allocated(fault)) return
            call move_alloc(fault, error)
            error%message = prefix//error%message
            if (allocated(kept)) error%message = error%message//' (rows up to then in '//kept//')'
        end subroutine close_all

        !> Delete the files still open.
        subroutine discard_all()
            integer :: w

            do w = 1, size(writers)
                if (writers(w)%opened) call discard_columns(writers(w))
            end do
        end subroutine discard_all
    end subroutine stream_run

    !> Add a block's forces to a summary.
    pure subroutine add_forces(summary, force)
        type(force_summary), intent(inout) :: summary
        real(dp), intent(in) :: force(:)

        integer :: j

        do j = 1, size(force)
            if (summary%steps == 0) summary%peak = force(j)
            summary%steps = summary%steps + 1
            summary%peak = max(summary%peak, force(j))
            summary%total = summary%total + force(j)
            summary%squares = summary%squares + force(j)**2
            if (force(j) > 0.0_dp) summary%in_contact = summary%in_contact + 1
        end do
    end subroutine add_forces

    !> The convolver called `method` for a scene, at step 0, and what its model neglects: the
    !> Green's matrix of the points of a multi-point scene (`run%points` found already), or the
    !> structure's single-point convolver wrapped as the 1 x 1 case.
    subroutine make_run_convolver(run, scene, structure, method, accuracy, error, estimate)
        !> The run; its convolver made.
        type(contact_run), intent(inout) :: run
        !> The scene.
        type(scene_type), intent(in) :: scene
        !> The structure of a single-point scene (not used for a multi-point one).
        type(structure_model), intent(in) :: structure
        !> The method's name.
        character(len=*), intent(in) :: method
        !> What the model neglects, in words.
        character(len=:), allocatable, intent(out) :: accuracy
        !> Set when the method cannot run on the structure.
        type(error_type), allocatable, intent(out) :: error
        !> The method's own estimate of its relative error, to compare with the scene's
        !> `accuracy` (greenconv_conv_builder's `make_convolver`, greenconv_scene_run_points's
        !> `points_convolver`).
        real(dp), intent(out), optional :: estimate

        class(convolver), allocatable :: point
        real(dp) :: own

        run%several = multi_point_model(scene%model)
        if (allocated(run%conv)) deallocate (run%conv)
        if (run%several) then
            call points_convolver(run%points, scene, method, run%conv, accuracy, error, own)
            if (present(estimate)) estimate = own
            return
        end if
        call make_convolver(method, structure, scene%dt, scene%truncation_tol, scene%n_steps, point, accuracy, &
                            error, scene%accuracy, own)
        if (present(estimate)) estimate = own
        if (allocated(error)) return
        allocate (point_matrix :: run%conv)
        select type (matrix => run%conv)
        type is (point_matrix)
            call wrap_point(point, matrix)
        end select
    end subroutine make_run_convolver

    !> Start the contact loop of a run at step 0 with the scene's law: one point under the
    !> whole preload with the scene's `&contact` scheme and settings, or N_c points sharing it
    !> with the multi-point settings (the implicit step, the scene's divergence bound).
    subroutine start_run(run, scene, error)
        !> The run, its convolver made.
        type(contact_run), intent(inout) :: run
        !> The scene.
        type(scene_type), intent(in) :: scene
        !> Set when the contact settings are unusable with the convolver.
        type(error_type), allocatable, intent(out) :: error

        class(contact_law), allocatable :: laws(:)
        integer :: n, n_c

        run%peak = -huge(1.0_dp)
        n_c = run%conv%n_points()
        call replicate_law(scene%law, n_c, laws)
        if (run%several) then
            call start_multi_contact(run%conv, laws, [(scene%preload/n_c, n=1, n_c)], run%state, &
                                     error, newton_options(max_displacement=scene%contact%divergence_bound))
        else
            call start_multi_contact(run%conv, laws, [scene%preload], run%state, error, settings=scene%contact)
        end if
    end subroutine start_run

    function run_step(self) result(step)
        class(contact_run), intent(in) :: self
        integer(int64) :: step

        step = self%state%step
    end function run_step

    !> The road heights under the point or points at steps first..first + count - 1.
    subroutine run_sample(self, scene, first, count)
        class(contact_run), intent(inout) :: self
        type(scene_type), intent(in) :: scene
        integer(int64), intent(in) :: first
        integer, intent(in) :: count

        if (self%several) then
            call sample_patch_road(scene, self%points%road_x, self%points%road_y, first, count, self%heights)
        else
            self%heights = reshape(scene%road%sample_steps(scene%dt, first, count), [count, 1])
        end if
    end subroutine run_sample

    !> Step the block; the peak total force of the block is noted.
    subroutine run_advance(self, fault)
        class(contact_run), intent(inout) :: self
        type(error_type), allocatable, intent(out) :: fault

        call multi_contact_block(self%conv, self%state, self%heights, self%response, fault)
        if (size(self%response%total_force) > 0) self%peak = max(self%peak, maxval(self%response%total_force))
    end subroutine run_advance

    !> The rows of the steps of the block that are multiples of `every`: t, u_road, u,
    !> f_contact, delta for one point; N_c rows per step for several (greenconv_scene_run_points's
    !> `point_rows`, with the column y for a Green's matrix file's points).
    subroutine run_rows(self, first, every, table)
        class(contact_run), intent(in) :: self
        integer(int64), intent(in) :: first
        integer, intent(in) :: every
        real(dp), allocatable, intent(out) :: table(:, :)

        integer :: j

        j = first_kept(first, every)
        if (self%several) then
            table = point_rows(self%points, self%response, j, every)
            return
        end if
        associate (response => self%response)
            table = reshape([response%time(j::every), response%road(j::every, 1), &
                             response%displacement(j::every, 1), response%force(j::every, 1), &
                             response%compression(j::every, 1)], [size(response%time(j::every)), 5])
        end associate
    end subroutine run_rows

    !> The totals rows (t, total force, contact area of `share` [m^2] a point in contact, points
    !> in contact) of the steps of the block that are multiples of `every` (a multi-point run).
    subroutine run_totals(self, first, every, share, table)
        class(contact_run), intent(in) :: self
        integer(int64), intent(in) :: first
        integer, intent(in) :: every
        real(dp), intent(in) :: share
        real(dp), allocatable, intent(out) :: table(:, :)

        table = totals_table(self%response, first_kept(first, every), every, share)
    end subroutine run_totals

    !> The total contact force of each step of the block and, for a multi-point scene, each
    !> point's, points(step, point) (no columns for one point).
    subroutine run_forces(self, total, points)
        class(contact_run), intent(in) :: self
        real(dp), allocatable, intent(out) :: total(:), points(:, :)

        if (self%several) then
            total = self%response%total_force
            points = self%response%force
        else
            total = self%response%force(:, 1)
            allocate (points(size(total), 0))
        end if
    end subroutine run_forces

end module greenconv_scene_run_stream
