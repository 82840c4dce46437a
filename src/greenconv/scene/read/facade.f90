!> Reading a scene as the rest of the scene layer sees it (scene/run, scene/sweep and the scene
!> facade): the scene read from its namelist file or from lines (greenconv_scene_read_input) and
!> the table of scene variables (greenconv_scene_read_schema). `make layers` refuses any other
!> module of scene/read to the folders above it.
module greenconv_scene_read_facade
    use greenconv_scene_read_input, only: output_path, place_error, read_scene, read_scene_lines, scene_files, &
                                          scene_type
    use greenconv_scene_read_schema, only: scene_table, scene_variable
    implicit none
    private

    !> Re-exported from the modules of scene/read named above.
    public :: output_path, place_error, read_scene, read_scene_lines, scene_files, scene_table, scene_type, &
              scene_variable

end module greenconv_scene_read_facade
