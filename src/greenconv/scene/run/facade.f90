!> Running a scene as the folders above it see it (scene/sweep and the scene facade): a scene's
!> methods run and checked (greenconv_scene_run_runner), the streaming loop a sweep steps
!> (greenconv_scene_run_stream) and the multi-point column file (greenconv_scene_run_output).
!> `make layers` refuses any other module of scene/run to the folders above it.
module greenconv_scene_run_facade
    use greenconv_scene_run_output, only: multi_contact_header, write_multi_contact
    use greenconv_scene_run_runner, only: check_scene, check_scene_line, make_convolver, output_path, run_scene
    use greenconv_scene_run_stream, only: band_estimate, contact_run, force_summary, make_run_convolver, start_run, &
                                          start_step_doubling, step_doubling, stream_run, stream_sinks, &
                                          time_step_estimate
    implicit none
    private

    !> Re-exported from the modules of scene/run named above.
    public :: band_estimate, check_scene, check_scene_line, contact_run, force_summary, make_convolver, &
              make_run_convolver, multi_contact_header, output_path, run_scene, start_run, start_step_doubling, &
              step_doubling, stream_run, stream_sinks, time_step_estimate, write_multi_contact

end module greenconv_scene_run_facade
