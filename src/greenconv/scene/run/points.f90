!> The contact points of a multi-point scene, found by its model's row of the registry
!> (greenconv_scene_models_registry' `find_points`: the tyre's line of points, a Green's file's nodes,
!> ...), and the convolver of each method on them: on the points' modes (greenconv_conv_builder) or on the
!> identified Green's matrix of a file (greenconv_conv_green_file).
module greenconv_scene_run_points
    use greenconv_core_kinds, only: dp
    use greenconv_core_error, only: error_type
    use greenconv_conv_multipoint, only: multipoint_convolver
    use greenconv_conv_builder, only: make_multipoint_convolver
    use greenconv_conv_green_file, only: green_file_convolver
    use greenconv_scene_settings, only: scene_type
    use greenconv_scene_models_facade, only: scene_points
    use greenconv_scene_run_output, only: multi_contact_table
    use greenconv_contact_multi, only: multi_contact_response
    implicit none
    private

    public :: scene_points, points_convolver, point_rows

contains

    !> The convolver called `method` on a scene's points, and what its model neglects.
    subroutine points_convolver(points, scene, method, conv, accuracy, error, estimate)
        !> The points (the `find_points` of the scene's model, greenconv_scene_models_registry).
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
        !> The method's own estimate of its relative error (greenconv_conv_green_file's
        !> `green_file_convolver`, greenconv_conv_builder's `make_multipoint_convolver`).
        real(dp), intent(out), optional :: estimate

        real(dp) :: own

        if (points%from_file) then
            call green_file_convolver(points%green, method, scene%dt, scene%truncation_tol, scene%n_steps, conv, &
                                      accuracy, error, own)
        else
            ! `points%static`, the modes file's modes above the band, is unallocated when none are:
            ! the builder adds it to W0 as it does for the C and F77 doors (one structure).
            call make_multipoint_convolver(method, points%modes, scene%dt, scene%truncation_tol, scene%n_steps, conv, &
                                           accuracy, error, own, residual=points%static)
        end if
        if (present(estimate)) estimate = own
    end subroutine points_convolver

    !> Output rows of a multi-point run (greenconv_scene_run_output's `multi_contact_table`): N_c
    !> rows per kept step, with the column y [m] for points spread across the patch.
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

        if (points%across) then
            table = multi_contact_table(points%x, response, first, every, points%y)
        else
            table = multi_contact_table(points%x, response, first, every)
        end if
    end function point_rows

end module greenconv_scene_run_points
