!> The contact points of a multi-point scene and its convolvers, whatever the model:
!>
!> - `tyre`: a line of points under the belt of greenconv_model_tyre, its exact modes
!>   (greenconv_scene_tyre);
!> - `green_file`: the nodes of a universal file of a Green's matrix (`&structure green_file`),
!>   at their coordinates, any layout, 1D or 2D: the file is read and its receptances
!>   identified once with shared poles (greenconv_ident_green_structure, the pole fit's
!>   stabilisation diagram up to `&identification max_order`), and each method is built on it
!>   by greenconv_conv_green_file (modal methods on the identified modes, `direct` and `fft`
!>   on g_ij from the file).
!>
!> Both follow the conventions of greenconv_scene_patch (preload shared evenly, the points
!> seeing the road around x_start and y_start). The scene's summary names the file, its points
!> and the identification: E of eq. (7) per receptance (worst, mean) and per point, the worst
!> pole uncertainty, the modes the modal methods run on.
module greenconv_scene_points
    use greenconv_core_kinds, only: dp
    use greenconv_core_error, only: error_type
    use greenconv_core_text, only: int_text
    use greenconv_model_point_modes, only: point_modes
    use greenconv_ident_green_structure, only: green_options, green_structure, identify_green, read_green_layout, &
                                               sampled_kernel
    use greenconv_conv_methods, only: check_method, method_needs_g
    use greenconv_conv_multipoint, only: multipoint_convolver
    use greenconv_conv_builder, only: make_multipoint_convolver
    use greenconv_conv_green_file, only: green_file_convolver
    use greenconv_scene_input, only: scene_type, input_place
    use greenconv_scene_models, only: model_requires, find_model
    use greenconv_scene_patch, only: place_patch, run_text
    use greenconv_scene_tyre, only: tyre_points
    use greenconv_scene_output, only: multi_contact_table
    use greenconv_contact_multi, only: multi_contact_response
    implicit none
    private

    public :: scene_points, find_scene_points, points_convolver, check_green_scene, point_rows

    !> The points of a multi-point scene and what their convolvers are built from.
    type :: scene_points
        !> Positions x_i, y_i [m] of the points on the body (the columns x, y of the output).
        real(dp), allocatable :: x(:), y(:)
        !> Positions X_i(0), Y_i [m] of the points on the road (greenconv_scene_patch).
        real(dp), allocatable :: road_x(:), road_y(:)
        !> Whether the points come from a Green's matrix file (else the tyre belt's modes).
        logical :: from_file = .false.
        !> The tyre belt's modes at the points.
        type(point_modes) :: modes
        !> The Green's matrix read from the file, identified.
        type(green_structure) :: green
    contains
        !> Number of points N_c.
        procedure :: n_points => points_n_points
    end type scene_points

contains

    !> Number of points N_c.
    elemental integer function points_n_points(self)
        !> The points.
        class(scene_points), intent(in) :: self

        points_n_points = 0
        if (allocated(self%x)) points_n_points = size(self%x)
    end function points_n_points

    !> The points of a multi-point scene, placed on the road and checked against it for the whole
    !> run, and the scene's summary lines (printed by the caller who wants them).
    subroutine find_scene_points(scene, points, summary, error)
        !> The scene (a multi-point model, task 'contact', road profile 'file' or 'texture').
        type(scene_type), intent(in) :: scene
        !> The points.
        type(scene_points), intent(out) :: points
        !> The summary: "# scene NAME: ..." lines, separated by new_line('a').
        character(len=:), allocatable, intent(out) :: summary
        !> Set for a bad file, a failed identification or a road that does not cover the run.
        type(error_type), allocatable, intent(out) :: error

        type(green_options) :: options

        if (.not. model_requires(find_model(scene%model), 'green_file')) then
            call tyre_points(scene, points%modes, points%x, points%road_x, summary, error, points%road_y)
            if (.not. allocated(error)) points%y = 0.0_dp*points%x
            return
        end if
        points%from_file = .true.
        points%green%path = scene%green_file
        call read_green_layout(scene%green_file, points%green%matrix, error)
        if (allocated(error)) then
            error%message = input_place(scene, 'structure', 'green_file')//': '//error%message
            return
        end if
        points%x = points%green%matrix%x
        points%y = points%green%matrix%y
        call place_patch(scene, points%x, points%y, points%road_x, points%road_y, error)
        if (allocated(error)) return
        options%fit%max_order = scene%max_order
        call identify_green(options, points%green, error)
        if (allocated(error)) then
            error%message = input_place(scene, 'structure', 'green_file')//': '//error%message
            return
        end if
        summary = '# scene '//scene%name//': Green''s matrix of '//scene%green_file//', ' &
                  //int_text(points%n_points())//' contact points, '//run_text(scene)//new_line('a') &
                  //points%green%summary()
    end subroutine find_scene_points

    !> The convolver called `method` on a scene's points, and what its model neglects.
    subroutine points_convolver(points, scene, method, conv, accuracy, error)
        !> The points (`find_scene_points`).
        type(scene_points), intent(in) :: points
        !> The scene (dt, n_steps, truncation_tol).
        type(scene_type), intent(in) :: scene
        !> Method, one of greenconv_conv_methods's `method_list(multi_point=.true.)`.
        character(len=*), intent(in) :: method
        !> The convolver, at step 0.
        class(multipoint_convolver), allocatable, intent(out) :: conv
        !> What the model neglects, in words.
        character(len=:), allocatable, intent(out) :: accuracy
        !> Set when the method cannot run on the points' structure.
        type(error_type), allocatable, intent(out) :: error

        if (points%from_file) then
            call green_file_convolver(points%green, method, scene%dt, scene%truncation_tol, scene%n_steps, conv, &
                                      accuracy, error)
        else
            call make_multipoint_convolver(method, points%modes, scene%dt, scene%truncation_tol, scene%n_steps, conv, &
                                           accuracy, error)
        end if
    end subroutine points_convolver

    !> Output rows of a multi-point run (greenconv_scene_output's `multi_contact_table`): N_c
    !> rows per kept step, with the column y [m] for a Green's matrix file's points.
    function point_rows(points, response, first, every) result(table)
        !> The points.
        type(scene_points), intent(in) :: points
        !> A block of the run.
        type(multi_contact_response), intent(in) :: response
        !> Index in the block of the first step kept.
        integer, intent(in) :: first
        !> Keep every `every`-th step.
        integer, intent(in) :: every
        !> Rows (t, x, u_road, u, F, delta, F_total[, y]).
        real(dp), allocatable :: table(:, :)

        if (points%from_file) then
            table = multi_contact_table(points%x, response, first, every, points%y)
        else
            table = multi_contact_table(points%x, response, first, every)
        end if
    end function point_rows

    !> For `--check`: read a scene's Green's matrix file (without identifying it), check that its
    !> points stay on the road for the whole run, and append what was found to `line`.
    subroutine check_green_scene(scene, line, n_points, error)
        !> The scene (model 'green_file').
        type(scene_type), intent(in) :: scene
        !> The check's line, extended with the file's points and grid.
        character(len=:), allocatable, intent(inout) :: line
        !> Number of contact points N_c of the file (unchanged when it cannot be read).
        integer, intent(inout) :: n_points
        !> Set for a bad file or a road that does not cover the run.
        type(error_type), allocatable, intent(out) :: error

        type(green_structure) :: green
        real(dp), allocatable :: road_x(:), road_y(:), kernel(:, :, :)
        character(len=:), allocatable :: source
        integer :: i

        green%path = scene%green_file
        call read_green_layout(scene%green_file, green%matrix, error)
        if (allocated(error)) then
            error%message = input_place(scene, 'structure', 'green_file')//': '//error%message
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
                    method_needs_g(trim(scene%methods(i)))) call sampled_kernel(green, scene%dt, kernel, source, error)
                if (allocated(error)) then
                    error%message = input_place(scene, 'convolution', 'methods')//': '//error%message
                    return
                end if
            end do
            line = line//' ('//scene%green_file//': '//int_text(matrix%n_points())//' points, '
            if (matrix%function_type == 4) then
                line = line//int_text(size(matrix%frequency))//' lines of G_ij)'
            else
                line = line//int_text(size(matrix%frequency))//' samples of g_ij(t))'
            end if
        end associate
    end subroutine check_green_scene

end module greenconv_scene_points
