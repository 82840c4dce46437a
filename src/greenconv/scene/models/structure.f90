!> The structure of a single-point scene: its `&structure` and `&identification` groups turned
!> into a `structure_model` (greenconv_ident_structure) by the builder its model's row of the
!> registry names (greenconv_scene_models_registry), with the scene's file and line put in front of any
!> error.
module greenconv_scene_models_structure
    use greenconv_core_error, only: error_type, fatal_error
    use greenconv_ident_structure, only: structure_model
    use greenconv_scene_settings, only: scene_type, place_error
    use greenconv_scene_models_registry, only: structure_kind, find_model
    implicit none
    private

    public :: build_structure

contains

    !> Build the structure of a single-point scene: exact modes, or G sampled or read and
    !> identified by the scene's method, as its model's builder does.
    subroutine build_structure(scene, structure, error)
        !> The scene.
        type(scene_type), intent(in) :: scene
        !> The structure.
        type(structure_model), intent(out) :: structure
        !> Set when the model builds no single-point structure, the file is unusable or the
        !> identification fails.
        type(error_type), allocatable, intent(out) :: error

        type(structure_kind) :: model

        model = find_model(scene%model)
        if (associated(model%build)) then
            call model%build(scene, structure, error)
        else
            call fatal_error(error, "'"//scene%model//"' builds no single-point structure (a multi-point model, " &
                             //"or an unknown one)")
            call place_error(error, scene, 'structure', 'model')
        end if
    end subroutine build_structure

end module greenconv_scene_models_structure
