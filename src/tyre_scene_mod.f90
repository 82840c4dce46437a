!> The tyre/road scene: a line of N_c contact points under the tyre belt of
!> tyre_model_mod, rolling over a road read from a file, all forces solved together at each
!> step (multi_contact_mod). One column file per method, `<output_dir>/<name>_<method>.dat`,
!> one row per step and point (t x u_road u f_contact delta f_total), and a summary line per
!> method like the single-point scenes.
!>
!> Methods: `modal`/`recursive` (modes shared by all points, the rectangle-rule recursion:
!> explicit, W0 = 0), `exact` (the same modes, first-order hold: W0 /= 0, so every step is
!> solved by Newton on the active set) and `direct` (the sampled Green's matrix g_ij(t_n),
!> truncated by the 1 % rule).
module tyre_scene_mod
    use kinds_mod, only: dp
    use text_mod, only: int_text, sci_text
    use error_mod, only: error_type, fatal_error
    use contact_mod, only: contact_law
    use scene_mod, only: scene_type, output_path
    use tyre_model_mod, only: tyre_modes, tyre_band, contact_positions, tyre_frequency
    use road_file_mod, only: sample_road_file
    use green_matrix_mod, only: point_modes, multipoint_convolver, sample_green_matrix
    use green_modal_mod, only: modal_green_matrix, new_modal_green_matrix
    use green_sampled_mod, only: sampled_green_matrix, new_sampled_green_matrix
    use multi_contact_mod, only: multi_contact_response, run_multi_contact, write_multi_contact
    implicit none
    private

    public :: run_tyre_scene

    real(dp), parameter :: pi = acos(-1.0_dp)

contains

    !> Run the tyre/road scene with each of its methods, print a summary on `unit`.
    subroutine run_tyre_scene(scene, unit, error)
        !> The scene (model 'tyre', road profile 'file').
        type(scene_type), intent(in) :: scene
        !> Unit of the summary.
        integer, intent(in) :: unit
        !> Set for an unusable scene, a failed step, or a file that cannot be written.
        type(error_type), allocatable, intent(out) :: error

        type(point_modes) :: description
        real(dp), allocatable :: positions(:), heights(:, :)
        real(dp) :: f_max
        integer :: i

        if (scene%task /= 'contact' .or. .not. allocated(scene%road_data%x)) then
            call fatal_error(error, scene%file//": &structure model: 'tyre' needs task = 'contact' and " &
                             //"&road profile = 'file'")
            return
        end if
        positions = contact_positions(0.5_dp*scene%tyre%length, scene%patch_length, scene%n_points)
        f_max = scene%f_modes
        if (f_max <= 0.0_dp) f_max = tyre_band(abs(scene%speed), 2.0_dp*minval(scene%road_data%x(2:) &
                                               - scene%road_data%x(:size(scene%road_data%x) - 1)), scene%dt)
        call tyre_modes(scene%tyre, positions, f_max, description, error)
        if (allocated(error)) return
        call sample_road_file(scene%road_data, scene%x_start + positions - 0.5_dp*scene%tyre%length, scene%speed, &
                              scene%dt, scene%n_steps, heights, error)
        if (allocated(error)) return
        write (unit, '(a,i0,a,f0.3,a,i0,a,f0.1,a,f0.0,a,i0,a,es9.2,a,f0.1,a)') &
            '# scene '//scene%name//': tyre belt, ', scene%n_points, ' contact points over ', scene%patch_length, &
            ' m, ', description%modes%n_modes(), &
            ' modes from ', tyre_frequency(scene%tyre, 1)/(2.0_dp*pi), ' Hz to f_max = ', f_max, ' Hz, ', &
            scene%n_steps, ' steps of ', scene%dt, ' s at ', scene%speed, ' m/s'
        write (unit, '(a,t12,a,t24,a,t36,a,t48,a)') '# method', 'size', 'steps', 'cpu_s', 'accuracy'
        do i = 1, size(scene%methods)
            call run_method(scene, trim(scene%methods(i)), description, positions, heights, unit, error)
            if (allocated(error)) return
        end do
    end subroutine run_tyre_scene

    !> One method: build its Green's matrix, run, write the file and the summary line.
    subroutine run_method(scene, method, description, positions, heights, unit, error)
        type(scene_type), intent(in) :: scene
        character(len=*), intent(in) :: method
        type(point_modes), intent(in) :: description
        real(dp), intent(in) :: positions(:), heights(0:, :)
        integer, intent(in) :: unit
        type(error_type), allocatable, intent(out) :: error

        class(multipoint_convolver), allocatable :: conv
        type(multi_contact_response) :: response
        type(error_type), allocatable :: run_error
        character(len=:), allocatable :: accuracy, label, path
        real(dp) :: start, finish
        integer :: n

        call make_green_matrix(method, description, scene%dt, scene%truncation_tol, scene%n_steps, conv, accuracy, &
                               error)
        if (allocated(error)) then
            error%message = scene%file//': &convolution methods: '//error%message
            return
        end if
        call cpu_time(start)
        call run_multi_contact(conv, [(scene%law, n=1, scene%n_points)], heights, &
                               [(scene%preload/scene%n_points, n=1, scene%n_points)], response, run_error)
        call cpu_time(finish)
        ! A failed step keeps the rows computed before it: write them, then report.
        path = output_path(scene, method)
        call write_multi_contact(path, 'greenconv tyre/road scene '//scene%name//', method '//method, positions, &
                                 response, error)
        if (allocated(error)) return
        if (allocated(run_error)) then
            call move_alloc(run_error, error)
            error%message = scene%file//': '//method//': '//error%message//' (rows up to then in '//path//')'
            return
        end if
        call conv%model_size(n, label)
        write (unit, '(a,t12,a,t24,i10,t36,f10.4,t48,a)') method, label//'='//int_text(n), scene%n_steps, &
            finish - start, accuracy//'; peak total force '//sci_text(maxval(response%total_force))//' N'
    end subroutine run_method

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

end module tyre_scene_mod
