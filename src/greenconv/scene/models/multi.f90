!> The multi-point structure models of the registry (greenconv_scene_models_registry), each as what the
!> registry's row names: the finder of its contact points, and what `--check` and the scene's
!> checks ask of it.
!>
!> - `tyre`: a line of points under the belt of greenconv_model_tyre, its exact modes
!>   (greenconv_scene_models_tyre);
!> - `green_file`: the nodes of a universal file of a Green's matrix (`&structure green_file`),
!>   at their coordinates, any layout, 1D or 2D: the file is read and its receptances
!>   identified once with shared poles (greenconv_ident_green_structure, the pole fit's
!>   stabilisation diagram up to `&identification max_order`), and each method is built on it
!>   by greenconv_conv_green_file (modal methods on the identified modes, `direct` and `fft`
!>   on g_ij from the file).
!>
!> - `modes_file`: the nodes of a universal file of normal modes from an FE model
!>   (`&structure modes_file`, datasets 15/2411 and 55, greenconv_model_modes_file), at their
!>   x, y; the modes up to the band (`f_modes`, or the Nyquist frequency 1/(2*dt)) are stepped;
!>   those above are kept as their static compliance (residual flexibility), added to the
!>   instant compliance W0 of the methods that have one (greenconv_scene_run_points), and the
!>   summary says how many and their share of the static flexibility at the points.
!>
!> All follow the conventions of greenconv_scene_models_patch (preload shared evenly, the points
!> seeing the road around x_start and y_start). The summary of a Green's file names the file,
!> its points and the identification: E of eq. (7) per receptance (worst, mean) and per point,
!> the worst pole uncertainty, the modes the modal methods run on.
module greenconv_scene_models_multi
    use greenconv_core_kinds, only: dp
    use greenconv_core_error, only: error_type, fatal_error
    use greenconv_core_text, only: int_text, sci_text
    use greenconv_model_tyre, only: tyre_frequency
    use greenconv_model_plate, only: plate_frequency, plate_modes, patch_points
    use greenconv_ident_green_structure, only: green_options, green_structure, identify_green, read_green_layout, &
                                               sampled_kernel, summary_text, cost_bound_text
    use greenconv_conv_methods, only: check_method, method_needs, needs_sampled_g
    use greenconv_scene_settings, only: scene_type, place_error
    use greenconv_ident_methods, only: ident_poly_reference, ident_auto
    use greenconv_scene_models_point_set, only: scene_points
    use greenconv_scene_models_patch, only: place_patch, run_text
    use greenconv_scene_models_tyre, only: tyre_points, place_band_error, tyre_band_top
    use greenconv_model_modes_file, only: file_modes, read_file_modes, split_band, band_bytes
    use greenconv_scene_limits, only: max_contact_points
    implicit none
    private

    real(dp), parameter :: pi = acos(-1.0_dp)

    public :: tyre_scene_points, tyre_decay, plate_scene_points, plate_decay, green_file_points, check_green_file
    public :: modes_file_points, check_modes_file

contains

    !> The points of a `tyre` scene: the belt's modes at a line of points, placed on the road.
    subroutine tyre_scene_points(scene, points, summary, error)
        !> The scene (model 'tyre', task 'contact', road profile 'file' or 'texture').
        type(scene_type), intent(in) :: scene
        !> The points, at y = 0 on the belt.
        type(scene_points), intent(out) :: points
        !> The scene's summary line.
        character(len=:), allocatable, intent(out) :: summary
        !> Set for an unusable scene (greenconv_scene_models_tyre's `tyre_points`).
        type(error_type), allocatable, intent(out) :: error

        call tyre_points(scene, points%modes, points%x, points%road_x, summary, error, points%road_y)
        if (.not. allocated(error)) points%y = 0.0_dp*points%x
        points%band = tyre_band_top(scene)
    end subroutine tyre_scene_points

    !> Decay rate [1/s] of the tyre's slowest mode, xi*omega_1, which bounds a sampled kernel's
    !> length.
    pure real(dp) function tyre_decay(scene)
        !> The scene (model 'tyre').
        type(scene_type), intent(in) :: scene

        tyre_decay = scene%damping_ratio*tyre_frequency(scene%tyre, 1)
    end function tyre_decay

    !> The points of a `tyre_plate` scene: an n_x by n_y grid over the patch, centred on the
    !> belt (x = L/2, y = b/2), each point the middle of its share; the plate's modes up to
    !> f_modes (or the band rule of the 1D tyre) at them; placed on the road around x_start
    !> and y_start.
    subroutine plate_scene_points(scene, points, summary, error)
        !> The scene (model 'tyre_plate', task 'contact', road profile 'file' or 'texture').
        type(scene_type), intent(in) :: scene
        !> The points.
        type(scene_points), intent(out) :: points
        !> The scene's summary line.
        character(len=:), allocatable, intent(out) :: summary
        !> Set for an unusable plate, no mode below the band or a road that does not cover the run.
        type(error_type), allocatable, intent(out) :: error

        real(dp) :: f_max
        character(len=200) :: numbers

        allocate (points%x(scene%n_points), points%y(scene%n_points))
        points%across = .true.
        call patch_points([0.5_dp*scene%plate%length, 0.5_dp*scene%plate%width], &
                          [scene%patch_length, scene%patch_width], scene%n_points_x, scene%n_points_y, &
                          points%x, points%y)
        f_max = tyre_band_top(scene)
        points%band = f_max
        call plate_modes(scene%plate, points%x, points%y, f_max, points%modes, error, band_name='f_modes')
        if (allocated(error)) then
            call place_band_error(error, scene)
            return
        end if
        call place_patch(scene, points%x, points%y, points%road_x, points%road_y, error)
        if (allocated(error)) then
            call place_error(error, scene, 'structure', 'model')
            return
        end if
        write (numbers, '(i0,a,i0,a,f0.3,a,f0.3,a,i0,a,f0.1,a,f0.0,a)') scene%n_points_x, ' x ', scene%n_points_y, &
            ' contact points over ', scene%patch_length, ' m x ', scene%patch_width, ' m, ', &
            points%modes%modes%n_modes(), ' modes from ', plate_frequency(scene%plate, 0, 1)/(2.0_dp*pi), &
            ' Hz up to the band, ', f_max, ' Hz, '
        summary = '# scene '//scene%name//': tyre belt as a plate, '//trim(numbers)//' '//run_text(scene)
    end subroutine plate_scene_points

    !> Decay rate [1/s] of the plate's slowest mode, xi*omega_01, which bounds a sampled
    !> kernel's length.
    pure real(dp) function plate_decay(scene)
        !> The scene (model 'tyre_plate').
        type(scene_type), intent(in) :: scene

        plate_decay = scene%damping_ratio*plate_frequency(scene%plate, 0, 1)
    end function plate_decay

    !> The points of a `green_file` scene: the file's nodes, placed on the road, and its
    !> receptances identified with shared poles.
    subroutine green_file_points(scene, points, summary, error)
        !> The scene (model 'green_file', task 'contact').
        type(scene_type), intent(in) :: scene
        !> The points and the identified Green's matrix.
        type(scene_points), intent(out) :: points
        !> The summary: "# scene NAME: ..." lines, separated by new_line('a').
        character(len=:), allocatable, intent(out) :: summary
        !> Set for a bad file, a failed identification or a road that does not cover the run.
        type(error_type), allocatable, intent(out) :: error

        type(green_options) :: options
        character(len=:), allocatable :: fit_summary

        points%from_file = .true.
        points%across = .true.
        points%green%path = scene%green_file
        call read_green_layout(scene%green_file, points%green%matrix, error)
        if (allocated(error)) then
            call place_error(error, scene, 'structure', 'green_file')
            return
        end if
        points%x = points%green%matrix%x
        points%y = points%green%matrix%y
        call place_patch(scene, points%x, points%y, points%road_x, points%road_y, error)
        if (allocated(error)) return
        options = green_settings(scene)
        call identify_green(options, points%green, error)
        if (allocated(error)) then
            call place_error(error, scene, 'structure', 'green_file')
            return
        end if
        call summary_text(points%green, fit_summary)
        summary = '# scene '//scene%name//': Green''s matrix of '//scene%green_file//', ' &
                  //int_text(points%n_points())//' contact points, '//run_text(scene)//new_line('a') &
                  //fit_summary
    end subroutine green_file_points

    !> The identification settings of a `green_file` scene (&structure max_order, ident_search,
    !> ident_method).
    function green_settings(scene) result(options)
        !> The scene.
        type(scene_type), intent(in) :: scene
        type(green_options) :: options

        options%fit%max_order = scene%max_order
        if (allocated(scene%ident_search)) options%fit%global_search = scene%ident_search == 'global'
        options%poly_reference = scene%identification == ident_poly_reference
        options%choose_poles = scene%identification == ident_auto
    end function green_settings

    !> For `--check`: read a scene's Green's matrix file (without identifying it), check that its
    !> points stay on the road for the whole run, and append what was found to `line`.
    subroutine check_green_file(scene, line, n_points, error)
        !> The scene (model 'green_file').
        type(scene_type), intent(in) :: scene
        !> The check's line, extended with the file's points and grid.
        character(len=:), allocatable, intent(inout) :: line
        !> Number of contact points N_c: every point of the file (unchanged when it cannot be read).
        integer, intent(inout) :: n_points
        !> Set for a bad file, a road that does not cover the run, or a method the file cannot
        !> serve (a modal method on impulse responses, g_ij off the file's step).
        type(error_type), allocatable, intent(out) :: error

        type(green_structure) :: green
        real(dp), allocatable :: road_x(:), road_y(:), kernel(:, :, :)
        character(len=:), allocatable :: source, bound
        integer :: i

        green%path = scene%green_file
        call read_green_layout(scene%green_file, green%matrix, error)
        if (allocated(error)) then
            call place_error(error, scene, 'structure', 'green_file')
            return
        end if
        associate (matrix => green%matrix)
            n_points = matrix%n_points()
            if (scene%task /= 'contact') return
            call place_patch(scene, matrix%x, matrix%y, road_x, road_y, error)
            if (allocated(error)) return
            ! a file of impulse responses: no modes, and g_ij only at whole multiples of its step
            do i = 1, size(scene%methods)
                call check_method(trim(scene%methods(i)), .true., .true., matrix%function_type == 4, error)
                if (.not. allocated(error) .and. matrix%function_type /= 4 .and. &
                    method_needs(trim(scene%methods(i)), needs_sampled_g)) &
                    call sampled_kernel(green, scene%dt, kernel, source, error)
                if (allocated(error)) then
                    call place_error(error, scene, 'convolution', 'methods')
                    return
                end if
            end do
            line = line//' ('//scene%green_file//': '//int_text(matrix%n_points())//' points, '
            if (matrix%function_type == 4) then
                call cost_bound_text(matrix, green_settings(scene), bound)
                line = line//int_text(size(matrix%frequency))//' lines of G_ij; '//bound//')'
            else
                line = line//int_text(size(matrix%frequency))//' samples of g_ij(t))'
            end if
        end associate
    end subroutine check_green_file

    !> The points of a `modes_file` scene: the file's nodes (those inside the scene's patch when
    !> it gives `modes_patch_length` x `modes_patch_width`) at their x, y, placed on the road,
    !> with the file's modes up to the band (`f_modes`, else 1/(2*dt)); the modes above it are
    !> kept as their static compliance between the nodes (`points%static`), counted in the
    !> summary with their share of the static flexibility at the nodes.
    subroutine modes_file_points(scene, points, summary, error)
        !> The scene (model 'modes_file', task 'contact').
        type(scene_type), intent(in) :: scene
        !> The points (the nodes the patch keeps) and the modes at them.
        type(scene_points), intent(out) :: points
        !> The scene's summary line.
        character(len=:), allocatable, intent(out) :: summary
        !> Set for a bad file, a patch that keeps no node or more than `max_contact_points`, no
        !> mode in the band, or a road that does not cover the run.
        type(error_type), allocatable, intent(out) :: error

        type(file_modes) :: modes
        real(dp) :: f_band
        character(len=:), allocatable :: band
        integer, allocatable :: selected(:)

        call read_file_modes(scene%modes_file, scene%modes_direction, scene%damping_ratio, modes, error)
        if (.not. allocated(error)) call patch_nodes(scene, modes, selected, error)
        f_band = scene%f_modes
        if (f_band <= 0.0_dp) f_band = 0.5_dp/scene%dt
        if (.not. allocated(error)) call split_band(modes, f_band, selected, scene%damping_ratio, points%modes, &
                                                    points%static, band, error)
        points%band = f_band
        points%complete = .not. allocated(points%static)
        if (allocated(error)) then
            call place_error(error, scene, 'structure', 'modes_file')
            return
        end if
        points%x = modes%x(selected)
        points%y = modes%y(selected)
        points%across = any(points%y /= points%y(1))
        call place_patch(scene, points%x, points%y, points%road_x, points%road_y, error)
        if (allocated(error)) return
        summary = '# scene '//scene%name//': modes of '//scene%modes_file//', '//band//', '//run_text(scene)
    end subroutine modes_file_points

    !> For `--check`: read a scene's modes file and append its nodes and modes to `line`.
    subroutine check_modes_file(scene, line, n_points, error)
        !> The scene (model 'modes_file').
        type(scene_type), intent(in) :: scene
        !> The check's line, extended with the file's nodes and modes.
        character(len=:), allocatable, intent(inout) :: line
        !> Number of contact points N_c: the file's nodes the scene's patch keeps (unchanged when
        !> the file cannot be read).
        integer, intent(inout) :: n_points
        !> Set for a bad file, a patch that keeps no node or more than `max_contact_points`, or a
        !> road that does not cover the run.
        type(error_type), allocatable, intent(out) :: error

        type(file_modes) :: modes
        real(dp), allocatable :: road_x(:), road_y(:)
        integer, allocatable :: selected(:)

        call read_file_modes(scene%modes_file, scene%modes_direction, scene%damping_ratio, modes, error)
        if (.not. allocated(error)) call patch_nodes(scene, modes, selected, error)
        if (allocated(error)) then
            call place_error(error, scene, 'structure', 'modes_file')
            return
        end if
        n_points = size(selected)
        if (scene%task == 'contact') call place_patch(scene, modes%x(selected), modes%y(selected), road_x, road_y, &
                                                      error)
        if (allocated(error)) return
        line = line//' ('//scene%modes_file//': '//int_text(n_points)//' of '//int_text(size(modes%x)) &
               //' nodes, '//int_text(size(modes%frequency))//' modes)'
    end subroutine check_modes_file

    !> The file's nodes inside the scene's patch, modes_patch_length along x by modes_patch_width
    !> along y centred on the middle of the nodes' extent (a 0 leaves that coordinate unbounded).
    subroutine patch_nodes(scene, modes, selected, error)
        type(scene_type), intent(in) :: scene
        type(file_modes), intent(in) :: modes
        integer, allocatable, intent(out) :: selected(:)
        type(error_type), allocatable, intent(out) :: error

        logical :: inside(size(modes%x))
        real(dp) :: centre(2)
        integer :: i

        centre = 0.5_dp*[minval(modes%x) + maxval(modes%x), minval(modes%y) + maxval(modes%y)]
        inside = .true.
        ! half a micrometre of slack: nodes on the patch's edge, written to a few digits, are in
        if (scene%modes_patch_length > 0.0_dp) inside = inside .and. &
            abs(modes%x - centre(1)) <= 0.5_dp*scene%modes_patch_length + 0.5e-6_dp
        if (scene%modes_patch_width > 0.0_dp) inside = inside .and. &
            abs(modes%y - centre(2)) <= 0.5_dp*scene%modes_patch_width + 0.5e-6_dp
        selected = pack([(i, i=1, size(inside))], inside)
        if (size(selected) == 0) call fatal_error(error, 'expected nodes inside the patch of modes_patch_length x ' &
                                                  //'modes_patch_width around the nodes'' centre, found none of ' &
                                                  //int_text(size(inside)))
        ! each node in the patch is a contact point: sized before its N_c x N_c matrices are made
        if (size(selected) > max_contact_points) call fatal_error(error, 'expected at most ' &
            //int_text(max_contact_points)//' contact points (nodes inside modes_patch_length x modes_patch_width), ' &
            //'found '//int_text(size(selected))//' of the file''s '//int_text(size(inside))//' nodes, whose ' &
            //'N_c x N_c static compliance alone would take '//sci_text(band_bytes(size(selected), &
            size(modes%frequency))/1.0e9_dp)//' GB: give a smaller modes_patch_length x modes_patch_width')
    end subroutine patch_nodes

end module greenconv_scene_models_multi
