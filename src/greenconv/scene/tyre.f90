!> The tyre/road scene: a line of N_c contact points under the tyre belt of
!> greenconv_model_tyre, rolling over a road read from a file, all forces solved together at each
!> step (greenconv_contact_multi). One column file per method, `<output_dir>/<name>_<method>.dat`,
!> one row per step and point (t x u_road u f_contact delta f_total), and a summary line per
!> method like the single-point scenes.
!>
!> Methods: `modal`/`recursive` (modes shared by all points, the rectangle-rule recursion:
!> explicit, W0 = 0), `exact` (the same modes, first-order hold: W0 /= 0, so every step is
!> solved by Newton on the active set) and `direct` (the sampled Green's matrix g_ij(t_n),
!> truncated by the 1 % rule).
!>
!> The run is streamed in blocks as greenconv_scene_runner's single-point runs are: road heights
!> sampled per block, greenconv_contact_multi's `multi_contact_block` continuing the run, the
!> block's rows (steps that are multiples of `output_every`) appended to the file. The
!> scene's `divergence_bound` [m] stops a run whose |u_i| exceeds it at any point.
module greenconv_scene_tyre
    use, intrinsic :: iso_fortran_env, only: int64
    use greenconv_core_kinds, only: dp
    use greenconv_core_text, only: int_text, sci_text
    use greenconv_core_error, only: error_type, fatal_error
    use greenconv_contact_single, only: contact_law
    use greenconv_scene_input, only: scene_type, output_path
    use greenconv_model_tyre, only: tyre_modes, tyre_band, contact_positions, tyre_frequency
    use greenconv_model_road_file, only: check_road_coverage, sample_road_steps
    use greenconv_conv_multipoint, only: multipoint_convolver, sample_green_matrix
    use greenconv_model_point_modes, only: point_modes
    use greenconv_conv_green_modal, only: modal_green_matrix, new_modal_green_matrix
    use greenconv_conv_green_sampled, only: sampled_green_matrix, new_sampled_green_matrix
    use greenconv_contact_multi, only: multi_contact_response, multi_contact_state, start_multi_contact, &
                                 multi_contact_block, newton_options
    use greenconv_scene_output, only: multi_contact_header, multi_contact_table
    use greenconv_io_files, only: column_writer, open_columns, append_rows, close_run_file, first_kept, block_rows
    use greenconv_scene_progress, only: progress_meter, start_progress, update_progress, finish_progress
    implicit none
    private

    public :: run_tyre_scene

    real(dp), parameter :: pi = acos(-1.0_dp)

contains

    !> Run the tyre/road scene with each of its methods, print a summary on `unit`.
    subroutine run_tyre_scene(scene, unit, error, block)
        !> The scene (model 'tyre', road profile 'file').
        type(scene_type), intent(in) :: scene
        !> Unit of the summary.
        integer, intent(in) :: unit
        !> Set for an unusable scene, a failed step, or a file that cannot be written.
        type(error_type), allocatable, intent(out) :: error
        !> Steps per block of the streamed run (>= 1); by default greenconv_io_files's `block_rows`/N_c.
        !> The files do not depend on it.
        integer, intent(in), optional :: block

        type(point_modes) :: description
        real(dp), allocatable :: positions(:), road_positions(:)
        real(dp) :: f_max
        integer :: i, block_steps

        if (scene%task /= 'contact' .or. .not. allocated(scene%road_data%x)) then
            call fatal_error(error, scene%file//": &structure model: 'tyre' needs task = 'contact' and " &
                             //"&road profile = 'file'")
            return
        end if
        block_steps = max(block_rows/scene%n_points, 1)
        if (present(block)) block_steps = max(block, 1)
        positions = contact_positions(0.5_dp*scene%tyre%length, scene%patch_length, scene%n_points)
        f_max = scene%f_modes
        if (f_max <= 0.0_dp) f_max = tyre_band(abs(scene%speed), 2.0_dp*minval(scene%road_data%x(2:) &
                                               - scene%road_data%x(:size(scene%road_data%x) - 1)), scene%dt)
        call tyre_modes(scene%tyre, positions, f_max, description, error)
        if (allocated(error)) return
        road_positions = scene%x_start + positions - 0.5_dp*scene%tyre%length
        call check_road_coverage(scene%road_data, road_positions, scene%speed, scene%dt, scene%n_steps, error)
        if (allocated(error)) return
        write (unit, '(a,i0,a,f0.3,a,i0,a,f0.1,a,f0.0,a,i0,a,es9.2,a,f0.1,a)') &
            '# scene '//scene%name//': tyre belt, ', scene%n_points, ' contact points over ', scene%patch_length, &
            ' m, ', description%modes%n_modes(), &
            ' modes from ', tyre_frequency(scene%tyre, 1)/(2.0_dp*pi), ' Hz to f_max = ', f_max, ' Hz, ', &
            scene%n_steps, ' steps of ', scene%dt, ' s at ', scene%speed, ' m/s'
        write (unit, '(a,t12,a,t24,a,t36,a,t48,a)') '# method', 'size', 'steps', 'cpu_s', 'accuracy'
        do i = 1, size(scene%methods)
            call run_method(scene, trim(scene%methods(i)), description, positions, road_positions, block_steps, &
                            unit, error)
            if (allocated(error)) return
        end do
    end subroutine run_tyre_scene

    !> One method: build its Green's matrix, run, write the file and the summary line.
    subroutine run_method(scene, method, description, positions, road_positions, block, unit, error)
        type(scene_type), intent(in) :: scene
        character(len=*), intent(in) :: method
        type(point_modes), intent(in) :: description
        real(dp), intent(in) :: positions(:), road_positions(:)
        integer, intent(in) :: block, unit
        type(error_type), allocatable, intent(out) :: error

        class(multipoint_convolver), allocatable :: conv
        character(len=:), allocatable :: accuracy, label
        real(dp) :: seconds, peak
        integer :: n

        call make_green_matrix(method, description, scene%dt, scene%truncation_tol, scene%n_steps, conv, accuracy, &
                               error)
        if (allocated(error)) then
            error%message = scene%file//': &convolution methods: '//error%message
            return
        end if
        call stream_method(scene, method, conv, positions, road_positions, block, seconds, peak, error)
        if (allocated(error)) return
        call conv%model_size(n, label)
        write (unit, '(a,t12,a,t24,i10,t36,f10.4,t48,a)') method, label//'='//int_text(n), scene%n_steps, &
            seconds, accuracy//'; peak total force '//sci_text(peak)//' N'
    end subroutine run_method

    !> One method's run, streamed in blocks of `block` steps into its file; `seconds` is the
    !> CPU time of the contact loop, `peak` the largest total force [N]. A failed step keeps
    !> the rows written before it: the file is completed and `error` names it.
    subroutine stream_method(scene, method, conv, positions, road_positions, block, seconds, peak, error)
        type(scene_type), intent(in) :: scene
        character(len=*), intent(in) :: method
        class(multipoint_convolver), intent(inout) :: conv
        real(dp), intent(in) :: positions(:), road_positions(:)
        integer, intent(in) :: block
        real(dp), intent(out) :: seconds, peak
        type(error_type), allocatable, intent(out) :: error

        type(multi_contact_state) :: state
        type(multi_contact_response) :: response
        type(column_writer) :: writer
        type(progress_meter) :: meter
        type(error_type), allocatable :: fault
        real(dp), allocatable :: heights(:, :)
        integer(int64) :: first
        real(dp) :: start, finish
        integer :: m, n

        seconds = 0.0_dp
        peak = -huge(1.0_dp)
        call start_multi_contact(conv, [(scene%law, n=1, scene%n_points)], &
                                 [(scene%preload/scene%n_points, n=1, scene%n_points)], state, error, &
                                 newton_options(max_displacement=scene%contact%divergence_bound))
        if (allocated(error)) return
        call open_columns(writer, output_path(scene, method), multi_contact_header(title(scene, method)), 7, &
                          error)
        if (allocated(error)) return
        call start_progress(meter, method, int(scene%n_steps, int64), scene%progress)
        do while (state%step < scene%n_steps)
            first = state%step
            m = int(min(int(block, int64), scene%n_steps - first))
            call sample_road_steps(scene%road_data, road_positions, scene%speed, scene%dt, first, m, heights)
            call cpu_time(start)
            call multi_contact_block(conv, state, heights, response, fault)
            call cpu_time(finish)
            seconds = seconds + (finish - start)
            if (size(response%total_force) > 0) peak = max(peak, maxval(response%total_force))
            call append_rows(writer, multi_contact_table(positions, response, first_kept(first, scene%output_every), &
                                                         scene%output_every), error)
            if (allocated(error) .or. allocated(fault)) exit
            call update_progress(meter, state%step)
        end do
        call finish_progress(meter, state%step)
        call close_run_file(writer, fault, scene%file//': '//method//': ', error)
    end subroutine stream_method

    !> First header line of a method's file; with `output_every` > 1, which steps the rows are.
    function title(scene, method) result(line)
        type(scene_type), intent(in) :: scene
        character(len=*), intent(in) :: method
        character(len=:), allocatable :: line

        line = 'greenconv tyre/road scene '//scene%name//', method '//method
        if (scene%output_every > 1) line = line//', a row every '//int_text(scene%output_every)//' steps (steps 0, ' &
                                           //int_text(scene%output_every)//', '//int_text(2*scene%output_every) &
                                           //', ...)'
    end function title

    !> The Green's matrix of a method and what it neglects, in words.
    subroutine make_green_matrix(method, description, dt, tol, n_steps, conv, accuracy, error)
        character(len=*), intent(in) :: method
        type(point_modes), intent(in) :: description
        real(dp), intent(in) :: dt, tol
        integer, intent(in) :: n_steps
        class(multipoint_convolver), allocatable, intent(out) :: conv
        character(len=:), allocatable, intent(out) :: accuracy
        type(error_type), allocatable, intent(out) :: error

        type(modal_green_matrix) :: modal
        type(sampled_green_matrix) :: sampled
        real(dp), allocatable :: kernel(:, :, :)
        real(dp) :: tail

        accuracy = ''
        select case (method)
        case ('modal', 'recursive', 'exact')
            call new_modal_green_matrix(description, dt, merge('exact    ', 'recursive', method == 'exact'), modal, &
                                        error)
            if (allocated(error)) return
            allocate (conv, source=modal)
            accuracy = 'exact on the model''s modes (explicit step)'
            if (method == 'exact') accuracy = 'first-order hold, implicit step (Newton, all points)'
        case ('direct')
            call sample_green_matrix(description, dt, tol, n_steps, kernel, tail)
            call new_sampled_green_matrix(kernel, dt, sampled, error)
            if (allocated(error)) return
            allocate (conv, source=sampled)
            accuracy = 'neglected tail <= '//sci_text(tail)//' of max|g_ij|'
        case default
            call fatal_error(error, "method '"//method//"' is not available for multi-point contact: expected " &
                             //"'direct', 'modal', 'recursive' or 'exact'")
        end select
    end subroutine make_green_matrix

end module greenconv_scene_tyre
