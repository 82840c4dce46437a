!> Run a scene: build the structure (identifying it when only G is known), then either
!> write the identification (task `identify`) or run the contact loop with one convolver
!> per method (task `contact`), writing column files and a summary line per method.
!>
!> Single- and multi-point runs (the tyre scene, greenconv_scene_models_tyre; a Green's matrix file,
!> greenconv_scene_run_points) are one `contact_run` each, streamed by greenconv_scene_run_stream's
!> `stream_run` into the method's column file (and its force spectra with `&scene spectra`);
!> this module starts each method's run, in one loop for both, and prints its summary line.
!>
!> A multi-point run writes, per method, its totals `<name>_<method>_totals.dat` (t, total
!> force, contact area, points in contact, a row every `output_every` steps) and, with
!> `spectra`, the spectra of both; its per-point histories `<name>_<method>.dat` (or `.bin`)
!> as `point_histories` asks (`auto`: for at most `auto_history_points` points), a row every
!> `point_every` steps; and with `map_times`, `<name>_<method>_maps.dat`, the per-point rows
!> at the steps nearest those times, one block of N_c rows a time.
module greenconv_scene_run_runner
    use, intrinsic :: iso_fortran_env, only: int64
    use greenconv_core_kinds, only: dp
    use greenconv_core_text, only: int_text, sci_text, trimmed_real_text
    use greenconv_core_error, only: error_type, fatal_error, stat_accuracy
    use greenconv_conv_methods, only: method_needs, needs_sampled_g, needs_modes, method_order
    use greenconv_conv_multipoint, only: multipoint_convolver
    use greenconv_conv_builder, only: make_convolver
    use greenconv_contact_laws, only: describe_law
    use greenconv_conv_engines, only: engine_constructors, engine_of
    use greenconv_io_files, only: block_rows, make_directory, check_output_directory
    use greenconv_scene_read_facade, only: scene_type, output_path, place_error
    use greenconv_scene_models_facade, only: structure_kind, find_model, multi_point_model, point_share, &
                                             build_structure, scene_points
    use greenconv_ident_structure, only: structure_model
    use greenconv_scene_run_report, only: write_identification, identification_summary
    use greenconv_scene_run_output, only: multi_contact_header, check_inputs_kept, totals_header
    use greenconv_scene_run_spectra_output, only: spectra_line, spectra_path
    use greenconv_scene_run_stream, only: contact_run, stream_sinks, stream_run, make_run_convolver, start_run, &
                                      halve_step, step_doubling, start_step_doubling, time_step_estimate, band_estimate
    use greenconv_scene_limits, only: work_rate, projected_run, smaller_step
    use greenconv_scene_run_linear_reference, only: write_linear_reference, write_patch_reference, contact_loss_text
    implicit none
    private

    public :: run_scene, check_scene, check_scene_line, check_cost_lines, make_convolver, output_path
    public :: auto_history_points, writes_point_histories

    !> Layout of the summary line of a method.
    character(len=*), parameter :: summary_format = '(a,t12,a,t24,i10,t36,f10.4,t48,es10.3,t60,a)'
    !> Column titles of the summary lines.
    character(len=*), parameter :: summary_titles = '(a,t12,a,t24,a,t36,a,t48,a,t60,a)'
    !> Longest line of `check_cost_lines`.
    integer, parameter :: cost_line_length = 240
    !> Bytes of one value of a text column file (a field of 25 characters).
    real(dp), parameter :: text_value_bytes = 25.0_dp
    !> Most points whose histories `point_histories = 'auto'` writes.
    integer, parameter :: auto_history_points = 100
    !> Fewest steps of `--check`'s projection of the error budget (`check_budget_lines`), when
    !> they fit in `pilot_seconds`.
    integer, parameter :: pilot_steps = 200
    !> Most projected CPU seconds [s] of a method's projection, its companions included.
    real(dp), parameter :: pilot_seconds = 0.5_dp
    !> CPU seconds [s] of projections after which `--check` projects no further method.
    real(dp), parameter :: pilot_total = 5.0_dp

contains

    !> Run a scene and print its summary on `unit`. Contact: for each method, the file
    !> `<output_dir>/<name>_<method>.dat` and a line (method, model size, steps, CPU seconds,
    !> what the model neglects). Identified structures also get their modes and G files.
    subroutine run_scene(scene, unit, error, block)
        !> The scene.
        type(scene_type), intent(in) :: scene
        !> Unit the summary is printed on.
        integer, intent(in) :: unit
        !> Set when the structure cannot be built or a file cannot be written (`stat_input`), a
        !> run fails (`stat_numerical`), or, every method run and written, one of them is outside
        !> the scene's `accuracy` (`stat_accuracy`).
        type(error_type), allocatable, intent(out) :: error
        !> Steps per block of the streamed run (>= 1); by default greenconv_io_files's `block_rows`
        !> (divided by N_c for a multi-point scene, at least 1). The files do not depend on it.
        integer, intent(in), optional :: block

        type(structure_model) :: structure
        type(structure_kind) :: model
        type(contact_run) :: run
        character(len=:), allocatable :: summary, law_line
        integer :: block_size

        call check_inputs_kept(scene, error)
        if (allocated(error)) return
        model = find_model(scene%model)
        if (model%multi_point()) then
            call make_directory(scene%output_dir, error)
            if (.not. allocated(error)) call model%find_points(scene, run%points, summary, error)
            if (allocated(error)) return
            write (unit, '(a)') summary
            block_size = max(block_rows/run%points%n_points(), 1)
        else
            block_size = block_rows
            call build_structure(scene, structure, error)
            if (allocated(error)) return
            call make_directory(scene%output_dir, error)
            if (allocated(error)) return
            if (structure%identified) then
                call identification_summary(structure, summary)
                write (unit, '(a)') summary
                call write_identification(scene, structure, error)
                if (allocated(error)) return
            end if
            if (scene%task /= 'contact') return
            write (unit, '(a,i0,a,es10.3,a)') '# scene '//scene%name//': ', scene%n_steps, ' steps of ', scene%dt, ' s'
        end if
        if (present(block)) block_size = max(block, 1)
        call describe_law(scene%law, law_line)
        if (model%multi_point()) law_line = law_line//' at each point'
        write (unit, '(a)') '# contact: '//law_line
        call run_methods(scene, structure, run, unit, block_size, error)
        if (associated(model%receptance)) call write_linear_reference(scene, model%receptance, unit, error)
        if (model%multi_point()) call write_patch_reference(scene, run%points, unit, error)
    end subroutine run_scene

    !> Check a scene without running it and print `check_scene_line`'s line on `unit`, then
    !> `check_cost_lines`' projected time and memory of each method.
    !>
    !>     greenconv: data/sdof_sine.nml: ok: task contact, model sdof, N_t = 2000 steps of 1.000E-04 s, ...
    !>     greenconv: check: method 'direct': about 2.3E-03 s, 1.2E-02 MB in memory, ...
    subroutine check_scene(scene, unit, error)
        !> The scene, as `read_scene` returned it.
        type(scene_type), intent(in) :: scene
        !> Unit the line is printed on.
        integer, intent(in) :: unit
        !> Set when a file the scene names is unusable.
        type(error_type), allocatable, intent(out) :: error

        character(len=:), allocatable :: line
        character(len=cost_line_length), allocatable :: costs(:)
        real(dp), allocatable :: projected(:)
        integer :: i, n_c

        call check_scene_line(scene, line, error, n_c)
        if (allocated(error)) return
        call check_cost_lines(scene, n_c, costs, error, projected)
        if (allocated(error)) return
        write (unit, '(a)') line
        do i = 1, size(costs)
            write (unit, '(a)') trim(costs(i))
        end do
        call check_budget_lines(scene, projected, unit, error)
    end subroutine check_scene

    !> What a contact scene's methods are projected to cost, one line each (none for another
    !> task): the CPU time, from the work of the method's steps (greenconv_scene_limits'
    !> `projected_run`) at `work_rate` multiply-adds per second, the memory the run holds and
    !> the bytes of its files, with the sizes they come from, e.g.
    !>
    !>     greenconv: check: method 'exact': about 1.10E+01 s, 1.73E+01 MB in memory, 4.21E+02 MB of files
    !>     (N_c 1000, N_m 229, N_g 5000, 5000 steps)
    !>
    !> N_m of a model identified at the run is its bound, `max_order` ("N_m <= 60"); its N_g,
    !> N_t. The modes of a tyre, plate or modes file are found here (closed form, or the file).
    subroutine check_cost_lines(scene, n_c, lines, error, seconds)
        !> The scene, as `read_scene` returned it.
        type(scene_type), intent(in) :: scene
        !> Number of contact points N_c (`check_scene_line`'s).
        integer, intent(in) :: n_c
        !> One line a method.
        character(len=cost_line_length), allocatable, intent(out) :: lines(:)
        !> Set when the model's points or modes cannot be found.
        type(error_type), allocatable, intent(out) :: error
        !> The projected CPU seconds of each method's run (none for another task).
        real(dp), allocatable, intent(out), optional :: seconds(:)

        type(structure_kind) :: model
        type(scene_points) :: points
        character(len=:), allocatable :: summary, bound
        real(dp) :: n_g, work, bytes, file_bytes
        integer :: i, n_m, n_terms

        if (present(seconds)) allocate (seconds(0))
        if (scene%task /= 'contact') then
            allocate (lines(0))
            return
        end if
        model = find_model(scene%model)
        bound = ''
        if (model%modes_bounded) bound = '<= '
        if (associated(model%mode_count)) then
            n_m = model%mode_count(scene)
        else
            n_m = scene%n_modes
            if (associated(model%find_points)) then
                call model%find_points(scene, points, summary, error)
                if (allocated(error)) return
                n_m = points%modes%modes%n_modes()
            end if
        end if
        n_g = real(scene%n_steps, dp)
        if (associated(model%slowest_decay)) then
            if (model%slowest_decay(scene) > 0.0_dp) n_g = min(n_g, log(1.0_dp/scene%truncation_tol) &
                                                                /(model%slowest_decay(scene)*scene%dt) + 1.0_dp)
        end if
        ! a Green's matrix's modal terms: each mode with its residues at every pair of points
        n_terms = n_m
        if (model%residue_matrices) n_terms = n_m*n_c
        file_bytes = output_bytes(scene, n_c)
        allocate (lines(size(scene%methods)))
        if (present(seconds)) seconds = [(0.0_dp, i=1, size(scene%methods))]
        do i = 1, size(scene%methods)
            call projected_run(trim(scene%methods(i)), n_c, n_m, n_terms, n_g, scene%n_steps, work, bytes)
            if (present(seconds)) seconds(i) = work/work_rate
            lines(i) = "greenconv: check: method '"//trim(scene%methods(i))//"': about "//sci_text(work/work_rate) &
                       //' s, '//sci_text(bytes/1.0e6_dp)//' MB in memory, '//sci_text(file_bytes/1.0e6_dp) &
                       //' MB of files (N_c '//int_text(n_c)//', N_m '//bound//int_text(n_m)//', N_g ' &
                       //int_text(nint(n_g))//', '//int_text(scene%n_steps)//' steps)'
        end do
    end subroutine check_cost_lines

    !> Bytes a method's files will hold: a row every `output_every` steps, of 5 values for one
    !> point; for several, the totals (4 values a row, text), the maps (N_c rows of 7 or 8
    !> values a map, text) and, when written, the per-point histories (N_c rows of 7, the tyre's
    !> line, or 8 values, with y, every `point_every` steps); each value `text_value_bytes` in
    !> text and 8 in binary.
    real(dp) function output_bytes(scene, n_c)
        type(scene_type), intent(in) :: scene
        integer, intent(in) :: n_c

        real(dp) :: rows, values, value_bytes
        type(structure_kind) :: model

        model = find_model(scene%model)
        value_bytes = merge(8.0_dp, text_value_bytes, scene%output_format == 'binary')
        rows = real(scene%n_steps/max(scene%output_every, 1) + 1, dp)
        if (.not. model%multi_point()) then
            output_bytes = rows*5.0_dp*value_bytes
            return
        end if
        ! points on a line (the tyre's) have no y column
        values = merge(7.0_dp, 8.0_dp, model%grid_dimensions == 1)*n_c
        output_bytes = rows*4.0_dp*text_value_bytes + size(scene%map_times)*values*text_value_bytes
        if (writes_point_histories(scene, n_c)) output_bytes = output_bytes &
            + real(scene%n_steps/point_every(scene) + 1, dp)*values*value_bytes
    end function output_bytes

    !> Check a scene without running it: the scene was read and checked by `read_scene`
    !> (with its road file); this also reads and checks a receptance file the structure
    !> names, and says in `line` what a run would do. Nothing is written or printed.
    subroutine check_scene_line(scene, line, error, n_points)
        !> The scene, as `read_scene` returned it.
        type(scene_type), intent(in) :: scene
        !> "greenconv: FILE: ok: task ..., model ..., ..." (set when the scene is usable).
        character(len=:), allocatable, intent(out) :: line
        !> Set when a file the scene names is unusable.
        type(error_type), allocatable, intent(out) :: error
        !> Number of contact points N_c (the file's for a Green's matrix or modes file).
        integer, intent(out), optional :: n_points

        type(structure_kind) :: model
        character(len=:), allocatable :: spectra
        integer :: i, n_c

        call check_inputs_kept(scene, error)
        if (allocated(error)) return
        call check_output_directory(scene%output_dir, error)
        if (allocated(error)) then
            call place_error(error, scene, 'scene', 'output_dir')
            return
        end if
        line = 'greenconv: '//scene%file//': ok: task '//scene%task//', model '//scene%model
        n_c = scene%n_points
        model = find_model(scene%model)
        if (associated(model%check_file)) call model%check_file(scene, line, n_c, error)
        if (allocated(error)) return
        if (present(n_points)) n_points = n_c
        if (scene%task == 'contact') then
            line = line//', N_t = '//int_text(scene%n_steps)//' steps of '//sci_text(scene%dt)//' s, ' &
                   //int_text(n_c)//' contact point(s), '
            if (multi_point_model(scene%model)) then
                line = line//'Newton on all points'
            else
                line = line//trim(scene%contact%scheme)//' step'
            end if
            line = line//', a row every '//int_text(scene%output_every)//' step(s), methods'
            do i = 1, size(scene%methods)
                line = line//' '//trim(scene%methods(i))
            end do
            if (scene%spectra) then
                call spectra_line(scene, spectra)
                line = line//', '//spectra
            end if
        end if
    end subroutine check_scene_line

    !> The contact loop once per method of a scene, single- or multi-point (`run%points`
    !> found for a multi-point one), in blocks of `block` steps. A method whose own error
    !> estimate exceeds the scene's `accuracy` still runs and writes its files; its summary
    !> line starts "outside the accuracy asked: ..." and, when every method has run, `error`
    !> is set with status `stat_accuracy` naming them (a fault or a bad input stops the loop
    !> first, with its own status).
    subroutine run_methods(scene, structure, run, unit, block, error)
        type(scene_type), intent(in) :: scene
        type(structure_model), intent(in) :: structure
        type(contact_run), intent(inout) :: run
        integer, intent(in) :: unit, block
        type(error_type), allocatable, intent(out) :: error

        type(stream_sinks) :: sinks
        type(step_doubling) :: doubling
        character(len=:), allocatable :: method, accuracy, label, prefix, outside, text, path, loss_text
        real(dp) :: seconds, estimate
        integer :: i, n
        type(structure_kind) :: model
        logical :: reports_loss

        model = find_model(scene%model)
        reports_loss = associated(model%receptance)
        if (scene%spectra) then
            call spectra_line(scene, text)
            call spectra_path(scene, '<method>', path)
            write (unit, '(a)') '# '//text//': '//path
        end if
        write (unit, summary_titles) '# method', 'size', 'steps', 'cpu_s', 'estimate', 'accuracy'
        outside = ''
        do i = 1, size(scene%methods)
            method = trim(scene%methods(i))
            call make_run_convolver(run, scene, structure, method, accuracy, error, estimate)
            if (allocated(error)) then
                if (run%several) call place_error(error, scene, 'convolution', 'methods')
                return
            end if
            seconds = 0.0_dp
            prefix = ''
            call start_run(run, scene, error)
            if (allocated(error)) then
                if (.not. run%several) error%message = scene%file//': '//method//': '//error%message
            else if (run%several) then
                call title(scene, method, point_every(scene), text)
                sinks = column_sinks(scene, method, multi_contact_header(text, run%points%across), &
                                     merge(8, 7, run%points%across))
                call patch_sinks(scene, method, run, sinks)
                prefix = scene%file//': '//method//': '
            else
                sinks = column_sinks(scene, method, response_header(scene, run%conv), 5)
                prefix = scene%file//': '//method//' ('//trim(scene%contact%scheme)//' step): '
            end if
            sinks%summarise = reports_loss
            if (.not. allocated(error)) call start_step_doubling(doubling, run, scene, structure, method)
            if (.not. allocated(error)) call stream_run(run, scene, method, block, sinks, prefix, seconds, error, &
                                                        doubling)
            if (sinks%summarise) then
                call contact_loss_text(sinks%summary, scene%dt, loss_text)
                accuracy = accuracy//loss_text
            end if
            call run%conv%model_size(n, label)
            call run%conv%release()
            if (allocated(error)) return
            call halve_step(doubling, run, scene, structure, method, block)
            call close_budget(doubling, scene, method, run%points, estimate, accuracy, text)
            if (run%several) accuracy = accuracy//'; peak total force '//sci_text(run%peak)//' N'
            if (len(text) > 0) then
                accuracy = text//'; '//accuracy
                outside = outside//' '//method
            end if
            write (unit, summary_format) method, label//'='//int_text(n), scene%n_steps, seconds, estimate, accuracy
        end do
        if (len(outside) > 0) call fatal_error(error, scene%file//': method(s)'//outside//' ran outside the ' &
                                               //'accuracy asked ('//sci_text(scene%accuracy)//', &convolution ' &
                                               //'accuracy): their files are written, their summary lines say ' &
                                               //'by how much and what to do', stat_accuracy)
    end subroutine run_methods

    !> Close a run's error budget: its companions' terms (time step, modes above the band) added
    !> to the model's, the budget in words after what the model neglects, and, when the sum
    !> exceeds the scene's accuracy, the line that says so and what to do ('' within it).
    subroutine close_budget(doubling, scene, method, points, estimate, accuracy, outside)
        !> The companions, the run done.
        type(step_doubling), intent(inout) :: doubling
        !> The run's scene.
        type(scene_type), intent(in) :: scene
        !> The method's name.
        character(len=*), intent(in) :: method
        !> The run's points (their band, and the static compliance above it), or none.
        type(scene_points), intent(in) :: points
        !> In: the model's terms [-]; out: the whole estimate [-].
        real(dp), intent(inout) :: estimate
        !> In: what the model neglects; out: the budget in words, then that.
        character(len=:), allocatable, intent(inout) :: accuracy
        !> `outside_line`'s line when the estimate exceeds the accuracy, else ''.
        character(len=:), allocatable, intent(out) :: outside

        character(len=:), allocatable :: text, band_text
        real(dp) :: step_part, band_part
        type(engine_constructors) :: engine
        logical :: static_left_out

        call time_step_estimate(doubling, step_part, text)
        call band_estimate(doubling, band_part, band_text)
        if (len(band_text) > 0) text = text//'; '//band_text
        call budget_text(estimate, step_part, band_part, doubling%seconds, accuracy//'; '//text, accuracy)
        estimate = estimate + step_part + band_part
        outside = ''
        if (estimate <= scene%accuracy) return
        static_left_out = .false.
        if (allocated(points%static)) then
            engine = engine_of(method)
            static_left_out = .not. (engine%samples_g() .or. engine%instant_part)
        end if
        call outside_line(method, estimate, scene%accuracy, outside, step_part, scene%dt, band_part, points%band, &
                          static_left_out)
    end subroutine close_budget

    !> `--check`'s projection of each method's error budget, one line a method on `unit`: the
    !> method run over the scene's first steps (an eighth of the run, at least `pilot_steps`
    !> and at most the whole run, as many as fit in `pilot_seconds` of projected CPU) with its
    !> companions, no file written, e.g.
    !>
    !>     greenconv: check: method 'modal': error about 5.7E-02 from its first 250 of 2000 steps
    !>     (0.01 s of CPU): outside the accuracy asked: estimate 5.7E-02 > accuracy 1.0E-02, ...
    !>
    !> A model identified at the run (a receptance or Green's file, the rail) is not run here:
    !> its E is known once identified, and the run prints the whole budget.
    subroutine check_budget_lines(scene, projected, unit, error)
        !> The scene, as `read_scene` returned it.
        type(scene_type), intent(in) :: scene
        !> The projected CPU seconds of each method's whole run (`check_cost_lines`).
        real(dp), intent(in) :: projected(:)
        !> Unit the lines are printed on.
        integer, intent(in) :: unit
        !> Set when the pilot's structure or points cannot be made (the run would refuse them too).
        type(error_type), allocatable, intent(out) :: error

        type(scene_type) :: pilot
        type(structure_kind) :: model
        type(structure_model) :: structure
        type(contact_run) :: run
        type(stream_sinks) :: sinks
        type(step_doubling) :: doubling
        type(error_type), allocatable :: fault
        character(len=:), allocatable :: method, accuracy, outside, head, summary
        real(dp) :: estimate, seconds, begin, finish, per_step, spent
        integer :: i, n_pilot
        type(engine_constructors) :: engine

        if (scene%task /= 'contact') return
        model = find_model(scene%model)
        if (model%identified_modes) then
            write (unit, '(a)') 'greenconv: check: error budget not projected: the model is identified at the run, ' &
                //'which prints each method''s budget with its E (eq. 7)'
            return
        end if
        spent = 0.0_dp
        pilot = scene
        pilot%progress = .false.
        pilot%spectra = .false.
        if (model%multi_point()) then
            call model%find_points(pilot, run%points, summary, error)
        else
            call build_structure(pilot, structure, error)
        end if
        if (allocated(error)) return
        do i = 1, size(scene%methods)
            method = trim(scene%methods(i))
            head = "greenconv: check: method '"//method//"': "
            ! the pilot's steps: an eighth of the run, at least pilot_steps, within pilot_seconds of
            ! projected CPU with its companions (0.75 of the run at 2*dt and 4*dt, up to 2 for the band)
            per_step = merge(3.75_dp, 1.75_dp, run%points%band > 0.0_dp)*projected(i)/scene%n_steps
            ! a kernel sampled from modes costs N_m*N_c^2 a sample to build, for the run and its companions
            engine = engine_of(method)
            if (engine%samples_g() .and. model%multi_point()) per_step = per_step + 2.75_dp &
                *real(run%points%modes%modes%n_modes(), dp)*real(run%points%n_points(), dp)**2/work_rate
            n_pilot = min(scene%n_steps, max(pilot_steps, scene%n_steps/8))
            if (per_step*n_pilot > pilot_seconds) n_pilot = int(pilot_seconds/per_step)
            if (n_pilot < min(16, scene%n_steps)) then
                write (unit, '(a)') head//'error budget not projected: a run of its first 16 steps with its ' &
                    //'companions would take about '//sci_text(16*per_step)//' s; the run prints its budget'
                cycle
            end if
            if (spent > pilot_total) then
                write (unit, '(a)') head//'error budget not projected: the projections took '//sci_text(spent) &
                    //' s of CPU already; the run prints its budget'
                cycle
            end if
            pilot%n_steps = n_pilot
            call cpu_time(begin)
            call make_run_convolver(run, pilot, structure, method, accuracy, fault, estimate)
            if (.not. allocated(fault)) call start_run(run, pilot, fault)
            if (.not. allocated(fault)) then
                call start_step_doubling(doubling, run, pilot, structure, method)
                call stream_run(run, pilot, method, block_rows, sinks, '', seconds, fault, doubling)
            end if
            if (allocated(run%conv)) call run%conv%release()
            call cpu_time(finish)
            if (allocated(fault)) then
                write (unit, '(a)') head//'error budget not projected: the run over its first ' &
                    //int_text(pilot%n_steps)//' steps failed: '//fault%message
                deallocate (fault)
                cycle
            end if
            spent = spent + (finish - begin)
            call close_budget(doubling, scene, method, run%points, estimate, accuracy, outside)
            head = head//'error about '//sci_text(estimate)//' from its first '//int_text(pilot%n_steps)//' of ' &
                   //int_text(scene%n_steps)//' steps ('//sci_text(finish - begin)//' s of CPU): '
            if (len(outside) > 0) then
                write (unit, '(a)') head//outside
            else
                write (unit, '(a)') head//'within the accuracy asked, '//sci_text(scene%accuracy)
            end if
        end do
    end subroutine check_budget_lines

    !> The budget in words: "budget: model M + time step T [+ band B] (CPU s of the companion
    !> runs); <what the model neglects>; <how the time step and the band were estimated>".
    pure subroutine budget_text(model_part, step_part, band_part, seconds, detail, text)
        !> The model's own terms (E, kernel, sampled band), the time step's and the modes above
        !> the band's [-].
        real(dp), intent(in) :: model_part, step_part, band_part
        !> CPU seconds of the companions.
        real(dp), intent(in) :: seconds
        !> What the model neglects and how the time step was estimated.
        character(len=*), intent(in) :: detail
        !> The budget in words (a subroutine: a deferred-length function result is static storage).
        character(len=:), allocatable, intent(out) :: text

        text = 'budget: model '//sci_text(model_part)//' + time step '//sci_text(step_part)
        if (band_part > 0.0_dp) text = text//' + modes above the band '//sci_text(band_part)
        text = text//' (estimated in '//sci_text(seconds)//' s); '//detail
    end subroutine budget_text

    !> "outside the accuracy asked: estimate X > accuracy Y, <what to do>" for a method whose
    !> own error estimate exceeds the accuracy asked.
    subroutine outside_line(method, estimate, accuracy, line, step_part, dt, band_part, band, static_left_out)
        character(len=*), intent(in) :: method
        real(dp), intent(in) :: estimate, accuracy
        character(len=:), allocatable, intent(out) :: line
        !> The time-step term of `estimate` [-] and the run's time step [s].
        real(dp), intent(in) :: step_part, dt
        !> The term of the modes above the band [-] and the band's top [Hz] (0: no band).
        real(dp), intent(in) :: band_part, band
        !> Whether the method leaves out a static compliance of the modes above the band that
        !> another method would hold.
        logical, intent(in) :: static_left_out

        line = 'outside the accuracy asked: estimate '//sci_text(estimate)//' > accuracy '//sci_text(accuracy) &
               //', '
        if (step_part >= 0.5_dp*estimate) then
            line = line//'the time step dominates: dt = '//sci_text(smaller_step(dt, step_part, accuracy, &
                                                                                     method_order(method))) &
                   //' s or less, or ask a larger accuracy'
        else if (band_part >= 0.5_dp*estimate) then
            line = line//'the modes above the band dominate: &structure f_modes = ' &
                   //trimmed_real_text(band*band_part/(0.5_dp*accuracy), 0.1_dp, 1.0e7_dp, 1, 1)//' Hz meets it ' &
                   //'(the term taken to fall as 1/f_modes from '//trimmed_real_text(band, 0.1_dp, 1.0e7_dp, 1, 1) &
                   //' Hz)'
            if (static_left_out) line = line//', or exact or direct, which hold the static compliance of the modes ' &
                                            //'above the band'
            line = line//', or ask a larger accuracy'
        else if (method_needs(method, needs_sampled_g) .and. method_needs(method, needs_modes)) then
            line = line//'no method auto may choose meets it: a higher max_order, G on a finer grid, or ask a larger ' &
                   //'accuracy'
        else if (method_needs(method, needs_sampled_g)) then
            line = line//'use a modal method (exact), G on a finer frequency grid or a wider band, or ask a larger ' &
                   //'accuracy'
        else
            line = line//'use exact (with the upper residual), a model with a smaller E (a higher max_order, ' &
                   //'less noisy data), or ask a larger accuracy'
        end if
    end subroutine outside_line

    !> The sinks of a driver's run: the method's column file `<output_dir>/<name>_<method>.dat`
    !> (or `.bin`) with the lines `header` and rows of `n_columns` values, and the force
    !> spectra when the scene asks for them.
    function column_sinks(scene, method, header, n_columns) result(sinks)
        type(scene_type), intent(in) :: scene
        character(len=*), intent(in) :: method, header(:)
        integer, intent(in) :: n_columns
        type(stream_sinks) :: sinks

        sinks%path = output_path(scene, method)
        sinks%header = header
        sinks%n_columns = n_columns
        sinks%binary = scene%output_format == 'binary'
        sinks%scene_spectra = .true.
    end function column_sinks

    !> Whether a multi-point run of N_c points writes its per-point histories
    !> (`&scene point_histories`: `all`, `none`, or `auto`, for at most `auto_history_points`).
    pure logical function writes_point_histories(scene, n_c)
        !> The scene.
        type(scene_type), intent(in) :: scene
        !> Number of contact points N_c.
        integer, intent(in) :: n_c

        select case (scene%point_histories)
        case ('all')
            writes_point_histories = .true.
        case ('none')
            writes_point_histories = .false.
        case default
            writes_point_histories = n_c <= auto_history_points
        end select
    end function writes_point_histories

    !> Steps between two rows of the per-point histories: `point_every`, 0 meaning `output_every`.
    pure integer function point_every(scene)
        type(scene_type), intent(in) :: scene

        point_every = merge(scene%point_every, scene%output_every, scene%point_every > 0)
    end function point_every

    !> The sinks of a multi-point run beside its column file: the file dropped when the scene
    !> asks for no per-point histories; the totals file; the map file at the steps nearest
    !> `map_times`.
    subroutine patch_sinks(scene, method, run, sinks)
        type(scene_type), intent(in) :: scene
        character(len=*), intent(in) :: method
        type(contact_run), intent(in) :: run
        type(stream_sinks), intent(inout) :: sinks

        character(len=:), allocatable :: line
        character(len=200) :: header(3)
        type(structure_kind) :: model

        model = find_model(scene%model)
        sinks%every = point_every(scene)
        if (.not. writes_point_histories(scene, run%points%n_points())) deallocate (sinks%path)
        sinks%share = point_share(scene, run%points%x, run%points%y, model%grid_dimensions > 0)
        sinks%totals_path = scene%output_dir//'/'//scene%name//'_'//method//'_totals.dat'
        call title(scene, method, scene%output_every, line)
        sinks%totals_header = totals_header(line//': totals', sinks%share)
        if (size(scene%map_times) == 0) return
        sinks%maps_path = scene%output_dir//'/'//scene%name//'_'//method//'_maps.dat'
        call title(scene, method, 1, line)
        header = multi_contact_header(line//': force maps, N_c rows at each step nearest map_times, ' &
                                      //int_text(size(scene%map_times))//' blocks', run%points%across)
        sinks%maps_header = header
        sinks%map_steps = nint(scene%map_times/scene%dt, int64)
    end subroutine patch_sinks

    !> The header of a method's column file: what ran, the units, the columns (t, u_road,
    !> u, f_contact, delta); with `output_every` > 1, which steps the rows are.
    function response_header(scene, conv) result(comments)
        type(scene_type), intent(in) :: scene
        class(multipoint_convolver), intent(in) :: conv
        character(len=400) :: comments(3)

        character(len=:), allocatable :: label
        integer :: n

        call conv%model_size(n, label)
        write (comments(1), '(a,i0,a,es10.3,a)') 'greenconv scene '//scene%name//', method '//conv%name//' (' &
            //label//' = '//int_text(n)//'), ', scene%n_steps, ' steps of ', scene%dt, ' s'
        if (scene%output_every > 1) comments(1) = trim(comments(1))//', a row every '//int_text(scene%output_every) &
                                                  //' steps (steps 0, '//int_text(scene%output_every)//', ' &
                                                  //int_text(2*scene%output_every)//', ...)'
        comments(2) = 'units: s m m N m'
        comments(3) = 't u_road u f_contact delta'
    end function response_header

    !> First header line of a multi-point method's file; with a row every `every` > 1 steps, which
    !> steps the rows are.
    subroutine title(scene, method, every, line)
        type(scene_type), intent(in) :: scene
        character(len=*), intent(in) :: method
        integer, intent(in) :: every
        character(len=:), allocatable, intent(out) :: line

        type(structure_kind) :: model

        model = find_model(scene%model)
        line = 'greenconv '//trim(model%title)//' scene '//scene%name
        if (model%title_names_file) line = line//' ('//scene%green_file//')'
        line = line//', method '//method
        if (every > 1) line = line//', a row every '//int_text(every)//' steps (steps 0, '//int_text(every)//', ' &
                              //int_text(2*every)//', ...)'
    end subroutine title

end module greenconv_scene_run_runner
