!> The scene layer as the layers above it see it: a scene read from its namelist file, checked
!> and run as the driver runs it, its structure built, a multi-point run's column file written,
!> and the size limits every door shares with the scenes. The C and Fortran 77 doors and the
!> library's entry points (greenconv_api_*) use the scene layer through this module only
!> (`make layers` checks it), so that the scene's own modules (its reading, its models, its
!> runs) can change without touching a door.
module greenconv_scene_facade
    use greenconv_scene_read_facade, only: scene_type, read_scene
    use greenconv_scene_run_facade, only: run_scene, check_scene, make_convolver, output_path, write_multi_contact
    use greenconv_scene_models_facade, only: build_structure
    use greenconv_scene_limits, only: max_lsce_modes, max_contact_points
    implicit none
    private

    !> Re-exported: the scene (greenconv_scene_read_input), its run and check (greenconv_scene_run_runner),
    !> the single-point structure it builds (greenconv_scene_models_structure), the multi-point column
    !> file (greenconv_scene_run_output), the limits on the modes identified and the contact points
    !> (greenconv_scene_limits).
    public :: scene_type, read_scene, run_scene, check_scene, make_convolver, output_path
    public :: build_structure, write_multi_contact, max_lsce_modes, max_contact_points

end module greenconv_scene_facade
