!> The scene's structure models as the rest of the scene layer sees them (scene/read, scene/run,
!> scene/sweep and the scene facade): the model registry (greenconv_scene_models_registry), a
!> single-point scene's structure (greenconv_scene_models_structure), a multi-point scene's
!> points (greenconv_scene_models_point_set) and the patch conventions
!> (greenconv_scene_models_patch). The builders and finders behind the registry's rows
!> (single, multi, tyre) stay inside scene/models: `make layers` refuses any other module of
!> this folder to the folders above it.
module greenconv_scene_models_facade
    use greenconv_scene_models_patch, only: point_share, sample_patch_road
    use greenconv_scene_models_point_set, only: scene_points
    use greenconv_scene_models_registry, only: contact_receptance, find_model, model_id, model_names, &
                                               model_requires, multi_point_model, structure_kind
    use greenconv_scene_models_structure, only: build_structure
    implicit none
    private

    !> Re-exported from the modules of scene/models named above.
    public :: build_structure, contact_receptance, find_model, model_id, model_names, model_requires, &
              multi_point_model, point_share, sample_patch_road, scene_points, structure_kind

end module greenconv_scene_models_facade
