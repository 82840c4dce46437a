!> Run a scene: build the structure (identifying it when only G is known), then either
!> write the identification (task `identify`) or run the contact loop with one convolver
!> per method (task `contact`), writing column files and a summary line per method.
!>
!> Single- and multi-point runs (the tyre scene, greenconv_scene_tyre; a Green's matrix file,
!> greenconv_scene_points) share one streaming
!> loop, `stream_run`: a run is streamed in blocks of greenconv_io_files's `block_rows` steps
!> (divided by N_c for several points): the road is sampled per block, the contact loop
!> continues from the convolver's state (greenconv_contact_single's `contact_block`,
!> greenconv_contact_multi's `multi_contact_block`), and the block's rows (every
!> `output_every`-th step of the run) are appended to the column file, so the memory a run
!> needs does not grow with N_t. A numerical fault closes the file with the rows before it;
!> bad input or a failed write deletes it. A progress line (greenconv_scene_progress) shows
!> on standard error for long runs. What differs between the two kinds of run is a
!> `contact_run`: how it samples the road, steps a block and lays out the block's rows.
module greenconv_scene_runner
    use, intrinsic :: iso_fortran_env, only: int64
    use greenconv_core_kinds, only: dp
    use greenconv_core_text, only: int_text, sci_text
    use greenconv_core_error, only: error_type
    use greenconv_conv_convolver, only: convolver, free_convolver
    use greenconv_conv_multipoint, only: multipoint_convolver
    use greenconv_conv_builder, only: make_convolver
    use greenconv_contact_single, only: contact_response, contact_state, start_contact, contact_block
    use greenconv_contact_multi, only: multi_contact_response, multi_contact_state, start_multi_contact, &
                                       multi_contact_block, newton_options
    use greenconv_io_files, only: column_writer, open_columns, append_rows, close_run_file, first_kept, block_rows, &
                         make_directory, check_output_directory
    use greenconv_scene_progress, only: progress_meter, start_progress, update_progress, finish_progress
    use greenconv_scene_input, only: scene_type, output_path, input_place
    use greenconv_scene_models, only: find_model, model_requires, multi_point_model
    use greenconv_ident_structure, only: structure_model
    use greenconv_scene_structure, only: build_structure
    use greenconv_model_frf, only: frf_type, read_frf
    use greenconv_scene_report, only: write_identification, identification_summary
    use greenconv_scene_output, only: multi_contact_header
    use greenconv_scene_spectra_output, only: force_spectra, start_force_spectra, add_contact_forces, &
                                              finish_force_spectra, spectra_line, spectra_path
    use greenconv_scene_points, only: scene_points, find_scene_points, points_convolver, check_green_scene, &
                                      point_rows
    use greenconv_scene_patch, only: sample_patch_road
    implicit none
    private

    public :: run_scene, check_scene, make_convolver, output_path

    !> Layout of the summary line of a method.
    character(len=*), parameter :: summary_format = '(a,t12,a,t24,i10,t36,f10.4,t48,a)'
    !> Column titles of the summary lines.
    character(len=*), parameter :: summary_titles = '(a,t12,a,t24,a,t36,a,t48,a)'

    !> One method's contact run as the streaming loop sees it: it knows its step, samples
    !> the road of a block, steps the block and gives the block's rows.
    type, abstract :: contact_run
    contains
        !> Steps done so far.
        procedure(run_step), deferred :: step
        !> Sample the road of steps first..first + count - 1.
        procedure(run_sample), deferred :: sample
        !> Step the block sampled last; the contact loop alone, which `stream_run` times.
        procedure(run_advance), deferred :: advance
        !> The rows of the block stepped last that are written.
        procedure(run_rows), deferred :: rows
        !> The contact forces of the block stepped last, for the force spectra.
        procedure(run_forces), deferred :: forces
    end type contact_run

    abstract interface
        !> Steps done so far.
        function run_step(self) result(step)
            import :: contact_run, int64
            implicit none
            class(contact_run), intent(in) :: self
            integer(int64) :: step
        end function run_step

        !> Sample the road of `count` steps from step `first` on.
        subroutine run_sample(self, scene, first, count)
            import :: contact_run, scene_type, int64
            implicit none
            class(contact_run), intent(inout) :: self
            type(scene_type), intent(in) :: scene
            integer(int64), intent(in) :: first
            integer, intent(in) :: count
        end subroutine run_sample

        !> Step the sampled block; `fault` names a failed step (the run stops there).
        subroutine run_advance(self, fault)
            import :: contact_run, error_type
            implicit none
            class(contact_run), intent(inout) :: self
            type(error_type), allocatable, intent(out) :: fault
        end subroutine run_advance

        !> The rows of the last block (its first step `first`) for the steps that are
        !> multiples of `every`.
        subroutine run_rows(self, first, every, table)
            import :: contact_run, int64, dp
            implicit none
            class(contact_run), intent(inout) :: self
            integer(int64), intent(in) :: first
            integer, intent(in) :: every
            real(dp), allocatable, intent(out) :: table(:, :)
        end subroutine run_rows

        !> The total contact force of each step of the last block and, for several points,
        !> each point's, points(step, point) (no columns for one point).
        subroutine run_forces(self, total, points)
            import :: contact_run, dp
            implicit none
            class(contact_run), intent(in) :: self
            real(dp), allocatable, intent(out) :: total(:), points(:, :)
        end subroutine run_forces
    end interface

    !> A single-point run: one convolver, the road under one point.
    type, extends(contact_run) :: single_run
        class(convolver), allocatable :: conv
        type(contact_state) :: state
        type(contact_response) :: response
        real(dp), allocatable :: road(:)
    contains
        procedure :: step => single_step
        procedure :: sample => single_sample
        procedure :: advance => single_advance
        procedure :: rows => single_rows
        procedure :: forces => single_forces
    end type single_run

    !> A multi-point run: a Green's matrix, the road under N_c points, the peak total force.
    type, extends(contact_run) :: multi_run
        class(multipoint_convolver), allocatable :: conv
        type(multi_contact_state) :: state
        type(multi_contact_response) :: response
        real(dp), allocatable :: heights(:, :)
        !> The points: on the body (x, y) and on the road (greenconv_scene_points).
        type(scene_points) :: points
        !> Largest total force [N] so far.
        real(dp) :: peak = -huge(1.0_dp)
    contains
        procedure :: step => multi_step
        procedure :: sample => multi_sample
        procedure :: advance => multi_advance
        procedure :: rows => multi_rows
        procedure :: forces => multi_forces
    end type multi_run

contains

    !> Run a scene and print its summary on `unit`. Contact: for each method, the file
    !> `<output_dir>/<name>_<method>.dat` and a line (method, model size, steps, CPU seconds,
    !> what the model neglects). Identified structures also get their modes and G files.
    subroutine run_scene(scene, unit, error, block)
        !> The scene.
        type(scene_type), intent(in) :: scene
        !> Unit the summary is printed on.
        integer, intent(in) :: unit
        !> Set when the structure cannot be built or a file cannot be written.
        type(error_type), allocatable, intent(out) :: error
        !> Steps per block of the streamed run (>= 1); by default greenconv_io_files's `block_rows`
        !> (divided by N_c for a multi-point scene, at least 1). The files do not depend on it.
        integer, intent(in), optional :: block

        type(structure_model) :: structure
        integer :: block_size

        if (multi_point_model(scene%model)) then
            call make_directory(scene%output_dir, error)
            if (.not. allocated(error)) call run_multipoint_methods(scene, unit, error, block)
            return
        end if
        block_size = block_rows
        if (present(block)) block_size = max(block, 1)
        call build_structure(scene, structure, error)
        if (allocated(error)) return
        call make_directory(scene%output_dir, error)
        if (allocated(error)) return
        if (structure%identified) then
            call identification_summary(structure, unit)
            call write_identification(scene, structure, error)
            if (allocated(error)) return
        end if
        if (scene%task == 'contact') call run_methods(scene, structure, unit, block_size, error)
    end subroutine run_scene

    !> Check a scene without running it: the scene file was read and checked by `read_scene`
    !> (with its road file); this also reads and checks a receptance file the structure
    !> names, then prints one line on `unit` saying what a run would do. Nothing is written.
    !>
    !>     greenconv: data/sdof_sine.nml: ok: task contact, model sdof, N_t = 2000 steps of 1.000E-04 s, ...
    subroutine check_scene(scene, unit, error)
        !> The scene, as `read_scene` returned it.
        type(scene_type), intent(in) :: scene
        !> Unit the line is printed on.
        integer, intent(in) :: unit
        !> Set when a file the scene names is unusable.
        type(error_type), allocatable, intent(out) :: error

        type(frf_type) :: frf
        character(len=:), allocatable :: line
        integer :: i, n_c

        call check_output_directory(scene%output_dir, error)
        if (allocated(error)) then
            error%message = input_place(scene, 'scene', 'output_dir')//': '//error%message
            return
        end if
        line = 'greenconv: '//scene%file//': ok: task '//scene%task//', model '//scene%model
        if (model_requires(find_model(scene%model), 'frf_file')) then
            call read_frf(scene%frf_file, frf, error, scene%frf_dataset)
            if (allocated(error)) then
                error%message = input_place(scene, 'structure', 'frf_file')//': '//error%message
                return
            end if
            line = line//' ('//scene%frf_file//': '//int_text(size(frf%frequency))//' lines to ' &
                   //sci_text(frf%frequency(size(frf%frequency)))//' Hz)'
        end if
        n_c = scene%n_points
        if (model_requires(find_model(scene%model), 'green_file')) call check_green_scene(scene, line, n_c, error)
        if (allocated(error)) return
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
            if (scene%spectra) line = line//', '//spectra_line(scene)
        end if
        write (unit, '(a)') line
    end subroutine check_scene

    !> The contact loop once per method of a single-point scene.
    subroutine run_methods(scene, structure, unit, block, error)
        type(scene_type), intent(in) :: scene
        type(structure_model), intent(in) :: structure
        integer, intent(in) :: unit, block
        type(error_type), allocatable, intent(out) :: error

        type(single_run) :: run
        character(len=:), allocatable :: method, accuracy, label
        real(dp) :: seconds
        integer :: i, n

        write (unit, '(a,i0,a,es10.3,a)') '# scene '//scene%name//': ', scene%n_steps, ' steps of ', scene%dt, ' s'
        if (scene%spectra) write (unit, '(a)') '# '//spectra_line(scene)//': '//spectra_path(scene, '<method>')
        write (unit, summary_titles) '# method', 'size', 'steps', 'cpu_s', 'accuracy'
        do i = 1, size(scene%methods)
            method = trim(scene%methods(i))
            call make_convolver(method, structure, scene%dt, scene%truncation_tol, scene%n_steps, run%conv, &
                                accuracy, error, scene%accuracy)
            if (allocated(error)) return
            call start_contact(run%conv, scene%law, scene%preload, run%state, error, scene%contact)
            if (allocated(error)) then
                error%message = scene%file//': '//method//': '//error%message
            else
                call stream_run(run, scene, method, response_header(scene, run%conv), 5, block, &
                                scene%file//': '//method//' ('//trim(scene%contact%scheme)//' step): ', seconds, &
                                error)
            end if
            call run%conv%model_size(n, label)
            call free_convolver(run%conv)
            if (allocated(error)) return
            write (unit, summary_format) method, label//'='//int_text(n), scene%n_steps, seconds, accuracy
        end do
    end subroutine run_methods

    !> The contact loop once per method of a multi-point scene (the tyre, a Green's matrix
    !> file), in blocks of `block` steps (default greenconv_io_files's `block_rows`/N_c).
    subroutine run_multipoint_methods(scene, unit, error, block)
        type(scene_type), intent(in) :: scene
        integer, intent(in) :: unit
        type(error_type), allocatable, intent(out) :: error
        integer, intent(in), optional :: block

        type(multi_run) :: run
        character(len=:), allocatable :: method, accuracy, label
        real(dp) :: seconds
        integer :: i, n, n_c, block_size

        call find_scene_points(scene, unit, run%points, error)
        if (allocated(error)) return
        n_c = run%points%n_points()
        block_size = max(block_rows/n_c, 1)
        if (present(block)) block_size = max(block, 1)
        if (scene%spectra) write (unit, '(a)') '# '//spectra_line(scene)//': '//spectra_path(scene, '<method>')
        write (unit, summary_titles) '# method', 'size', 'steps', 'cpu_s', 'accuracy'
        do i = 1, size(scene%methods)
            method = trim(scene%methods(i))
            call points_convolver(run%points, scene, method, run%conv, accuracy, error)
            if (allocated(error)) then
                error%message = input_place(scene, 'convolution', 'methods')//': '//error%message
                return
            end if
            call start_multi_contact(run%conv, [(scene%law, n=1, n_c)], [(scene%preload/n_c, n=1, n_c)], run%state, &
                                     error, newton_options(max_displacement=scene%contact%divergence_bound))
            if (allocated(error)) return
            run%peak = -huge(1.0_dp)
            call stream_run(run, scene, method, multi_contact_header(title(scene, method), run%points%from_file), &
                            merge(8, 7, run%points%from_file), block_size, scene%file//': '//method//': ', seconds, &
                            error)
            call run%conv%release()
            if (allocated(error)) return
            call run%conv%model_size(n, label)
            write (unit, summary_format) method, label//'='//int_text(n), scene%n_steps, seconds, &
                accuracy//'; peak total force '//sci_text(run%peak)//' N'
        end do
    end subroutine run_multipoint_methods

    !> One method's contact run, streamed in blocks of `block` steps into its column file,
    !> `<output_dir>/<name>_<method>.dat` with the lines `header` and rows of `n_columns`
    !> values. `seconds` is the CPU time of the contact loop alone. A numerical fault keeps
    !> the rows written before it: the file is completed and `error` names it after `prefix`.
    !> With `&scene spectra`, every step's contact forces also feed the force spectra
    !> (greenconv_scene_spectra_output), written when the run ends.
    subroutine stream_run(run, scene, method, header, n_columns, block, prefix, seconds, error)
        class(contact_run), intent(inout) :: run
        type(scene_type), intent(in) :: scene
        character(len=*), intent(in) :: method, header(:), prefix
        integer, intent(in) :: n_columns, block
        real(dp), intent(out) :: seconds
        type(error_type), allocatable, intent(out) :: error

        type(column_writer) :: writer
        type(progress_meter) :: meter
        type(force_spectra) :: spectra
        type(error_type), allocatable :: fault
        real(dp), allocatable :: table(:, :), total(:), points(:, :)
        integer(int64) :: first
        real(dp) :: start, finish
        integer :: m

        seconds = 0.0_dp
        call open_columns(writer, output_path(scene, method), header, n_columns, error, &
                          binary=scene%output_format == 'binary')
        if (allocated(error)) return
        call start_progress(meter, method, int(scene%n_steps, int64), scene%progress)
        call start_force_spectra(spectra, scene)
        do while (run%step() < scene%n_steps)
            first = run%step()
            m = int(min(int(block, int64), scene%n_steps - first))
            call run%sample(scene, first, m)
            call cpu_time(start)
            call run%advance(fault)
            call cpu_time(finish)
            seconds = seconds + (finish - start)
            if (spectra%active .and. .not. allocated(fault)) then
                call run%forces(total, points)
                call add_contact_forces(spectra, total, points)
            end if
            call run%rows(first, scene%output_every, table)
            call append_rows(writer, table, error)
            if (allocated(error) .or. allocated(fault)) exit
            call update_progress(meter, run%step())
        end do
        call finish_progress(meter, run%step())
        call close_run_file(writer, fault, prefix, error)
        call finish_force_spectra(spectra, scene, method, error)
    end subroutine stream_run

    !> The header of a method's column file: what ran, the units, the columns (t, u_road,
    !> u, f_contact, delta); with `output_every` > 1, which steps the rows are.
    function response_header(scene, conv) result(comments)
        type(scene_type), intent(in) :: scene
        class(convolver), intent(in) :: conv
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

    !> First header line of a multi-point method's file; with `output_every` > 1, which steps the rows are.
    function title(scene, method) result(line)
        type(scene_type), intent(in) :: scene
        character(len=*), intent(in) :: method
        character(len=:), allocatable :: line

        line = 'greenconv tyre/road scene '//scene%name//', method '//method
        if (scene%model /= 'tyre') line = 'greenconv patch scene '//scene%name//' ('//scene%green_file//'), method ' &
                                          //method
        if (scene%output_every > 1) line = line//', a row every '//int_text(scene%output_every)//' steps (steps 0, ' &
                                           //int_text(scene%output_every)//', '//int_text(2*scene%output_every) &
                                           //', ...)'
    end function title

    function single_step(self) result(step)
        class(single_run), intent(in) :: self
        integer(int64) :: step

        step = self%state%step
    end function single_step

    !> The road height under the point at steps first..first + count - 1.
    subroutine single_sample(self, scene, first, count)
        class(single_run), intent(inout) :: self
        type(scene_type), intent(in) :: scene
        integer(int64), intent(in) :: first
        integer, intent(in) :: count

        self%road = scene%road%sample_steps(scene%dt, first, count)
    end subroutine single_sample

    subroutine single_advance(self, fault)
        class(single_run), intent(inout) :: self
        type(error_type), allocatable, intent(out) :: fault

        call contact_block(self%conv, self%state, self%road, self%response, fault)
    end subroutine single_advance

    !> The columns t, u_road, u, f_contact, delta of the steps of the block that are multiples of `every`.
    subroutine single_rows(self, first, every, table)
        class(single_run), intent(inout) :: self
        integer(int64), intent(in) :: first
        integer, intent(in) :: every
        real(dp), allocatable, intent(out) :: table(:, :)

        integer :: j

        j = first_kept(first, every)
        associate (response => self%response)
            table = reshape([response%time(j::every), response%road(j::every), response%displacement(j::every), &
                             response%force(j::every), response%compression(j::every)], &
                            [size(response%time(j::every)), 5])
        end associate
    end subroutine single_rows

    !> The contact force of each step of the block.
    subroutine single_forces(self, total, points)
        class(single_run), intent(in) :: self
        real(dp), allocatable, intent(out) :: total(:), points(:, :)

        total = self%response%force
        allocate (points(size(total), 0))
    end subroutine single_forces

    function multi_step(self) result(step)
        class(multi_run), intent(in) :: self
        integer(int64) :: step

        step = self%state%step
    end function multi_step

    !> The road heights under the N_c points at steps first..first + count - 1.
    subroutine multi_sample(self, scene, first, count)
        class(multi_run), intent(inout) :: self
        type(scene_type), intent(in) :: scene
        integer(int64), intent(in) :: first
        integer, intent(in) :: count

        call sample_patch_road(scene, self%points%road_x, self%points%road_y, first, count, self%heights)
    end subroutine multi_sample

    subroutine multi_advance(self, fault)
        class(multi_run), intent(inout) :: self
        type(error_type), allocatable, intent(out) :: fault

        call multi_contact_block(self%conv, self%state, self%heights, self%response, fault)
    end subroutine multi_advance

    !> N_c rows per kept step (greenconv_scene_points's `point_rows`, with the column y
    !> for a Green's matrix file's points); the peak total force of the block is noted.
    subroutine multi_rows(self, first, every, table)
        class(multi_run), intent(inout) :: self
        integer(int64), intent(in) :: first
        integer, intent(in) :: every
        real(dp), allocatable, intent(out) :: table(:, :)

        if (size(self%response%total_force) > 0) self%peak = max(self%peak, maxval(self%response%total_force))
        table = point_rows(self%points, self%response, first_kept(first, every), every)
    end subroutine multi_rows

    !> The total force and each point's force of each step of the block.
    subroutine multi_forces(self, total, points)
        class(multi_run), intent(in) :: self
        real(dp), allocatable, intent(out) :: total(:), points(:, :)

        total = self%response%total_force
        points = self%response%force
    end subroutine multi_forces

end module greenconv_scene_runner
