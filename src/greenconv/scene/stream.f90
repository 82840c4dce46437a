!> The one streaming loop of a contact run, used by the driver's runner (greenconv_scene_runner),
!> by each variant of a sweep (greenconv_scene_sweep_variant) and so by the library's
!> `gc_run_scene`: a run is streamed in blocks of steps, the road sampled per block, the
!> contact loop continued from the convolver's state, and each block handed to the sinks the
!> caller asked for:
!>
!> - a column file (text `.dat`, or binary `.bin` with its header `.bin.txt`) of the rows of
!>   every `output_every`-th step;
!> - the scene's force spectra (`&scene spectra`, greenconv_scene_spectra_output);
!> - a force summary (max, mean, rms of the total contact force, steps in contact: a sweep row);
!> - the whole total-force history (a sweep's band levels).
!>
!> So the memory a run needs does not grow with N_t (unless the history is asked for). A
!> numerical fault stops the run: the column file is completed with the rows before it; a
!> failed write deletes it. What differs between a single- and a multi-point run is a
!> `contact_run`: how it samples the road, steps a block and lays out the block's rows.
module greenconv_scene_stream
    use, intrinsic :: iso_fortran_env, only: int64
    use greenconv_core_kinds, only: dp
    use greenconv_core_error, only: error_type
    use greenconv_conv_convolver, only: convolver
    use greenconv_conv_multipoint, only: multipoint_convolver
    use greenconv_contact_single, only: contact_response, contact_state, contact_block
    use greenconv_contact_multi, only: multi_contact_response, multi_contact_state, multi_contact_block
    use greenconv_io_files, only: column_writer, open_columns, append_rows, close_run_file, first_kept
    use greenconv_scene_progress, only: progress_meter, start_progress, update_progress, finish_progress
    use greenconv_scene_input, only: scene_type
    use greenconv_scene_spectra_output, only: force_spectra, start_force_spectra, add_contact_forces, &
                                              finish_force_spectra
    use greenconv_scene_points, only: scene_points, point_rows
    use greenconv_scene_patch, only: sample_patch_road
    implicit none
    private

    public :: contact_run, single_run, multi_run, stream_sinks, force_summary, stream_run

    !> One method's contact run as the streaming loop sees it: it knows its step, samples
    !> the road of a block, steps the block and gives the block's rows and forces.
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
        !> The contact forces of the block stepped last.
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
            class(contact_run), intent(in) :: self
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
        !> The convolver, started by the caller.
        class(convolver), allocatable :: conv
        !> The contact loop's state (start_contact).
        type(contact_state) :: state
        !> The last block's response.
        type(contact_response) :: response
        !> The road height [m] under the point at each step of the block.
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
        !> The convolver, started by the caller.
        class(multipoint_convolver), allocatable :: conv
        !> The contact loop's state (start_multi_contact).
        type(multi_contact_state) :: state
        !> The last block's response.
        type(multi_contact_response) :: response
        !> Road heights [m] under the points, heights(step, point), of the block.
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
        !> Whether the scene's force spectra (`&scene spectra`) are computed and written.
        logical :: scene_spectra = .false.
        !> Whether the total force is summarised into `summary`.
        logical :: summarise = .false.
        !> The summary of the total force [N] (with `summarise`).
        type(force_summary) :: summary
        !> The total force [N] of every step (allocated by the caller to N_t to ask for it).
        real(dp), allocatable :: history(:)
    end type stream_sinks

contains

    !> One method's contact run (`run`, started at step 0), streamed in blocks of `block` steps
    !> into the sinks. `seconds` is the CPU time of the contact loop alone. On return `error`
    !> is a failed write (the column file then gone) or the numerical fault that stopped the
    !> run, its message after `prefix` and naming the column file that keeps the rows before it.
    subroutine stream_run(run, scene, method, block, sinks, prefix, seconds, error)
        !> The run.
        class(contact_run), intent(inout) :: run
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

        type(column_writer) :: writer
        type(progress_meter) :: meter
        type(force_spectra) :: spectra
        type(error_type), allocatable :: fault
        real(dp), allocatable :: table(:, :), total(:), points(:, :)
        integer(int64) :: first
        real(dp) :: start, finish
        integer :: m

        seconds = 0.0_dp
        if (allocated(sinks%path)) then
            call open_columns(writer, sinks%path, sinks%header, sinks%n_columns, error, binary=sinks%binary)
            if (allocated(error)) return
        end if
        call start_progress(meter, method, int(scene%n_steps, int64), scene%progress)
        if (sinks%scene_spectra) call start_force_spectra(spectra, scene)
        do while (run%step() < scene%n_steps)
            first = run%step()
            m = int(min(int(block, int64), scene%n_steps - first))
            call run%sample(scene, first, m)
            call cpu_time(start)
            call run%advance(fault)
            call cpu_time(finish)
            seconds = seconds + (finish - start)
            if ((spectra%active .and. .not. allocated(fault)) .or. sinks%summarise .or. allocated(sinks%history)) &
                call run%forces(total, points)
            if (spectra%active .and. .not. allocated(fault)) call add_contact_forces(spectra, total, points)
            if (sinks%summarise) call add_forces(sinks%summary, total)
            if (allocated(sinks%history)) sinks%history(first + 1:first + size(total)) = total
            if (writer%opened) then
                call run%rows(first, scene%output_every, table)
                call append_rows(writer, table, error)
            end if
            if (allocated(error) .or. allocated(fault)) exit
            call update_progress(meter, run%step())
        end do
        call finish_progress(meter, run%step())
        if (allocated(sinks%path)) then
            call close_run_file(writer, fault, prefix, error)
        else if (allocated(fault)) then
            call move_alloc(fault, error)
            error%message = prefix//error%message
        end if
        if (sinks%scene_spectra) call finish_force_spectra(spectra, scene, method, error)
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
        class(single_run), intent(in) :: self
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

    !> Step the block; the peak total force of the block is noted.
    subroutine multi_advance(self, fault)
        class(multi_run), intent(inout) :: self
        type(error_type), allocatable, intent(out) :: fault

        call multi_contact_block(self%conv, self%state, self%heights, self%response, fault)
        if (size(self%response%total_force) > 0) self%peak = max(self%peak, maxval(self%response%total_force))
    end subroutine multi_advance

    !> N_c rows per kept step (greenconv_scene_points's `point_rows`, with the column y
    !> for a Green's matrix file's points).
    subroutine multi_rows(self, first, every, table)
        class(multi_run), intent(in) :: self
        integer(int64), intent(in) :: first
        integer, intent(in) :: every
        real(dp), allocatable, intent(out) :: table(:, :)

        table = point_rows(self%points, self%response, first_kept(first, every), every)
    end subroutine multi_rows

    !> The total force and each point's force of each step of the block.
    subroutine multi_forces(self, total, points)
        class(multi_run), intent(in) :: self
        real(dp), allocatable, intent(out) :: total(:), points(:, :)

        total = self%response%total_force
        points = self%response%force
    end subroutine multi_forces

end module greenconv_scene_stream
