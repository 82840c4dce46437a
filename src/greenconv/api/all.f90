!> greenconv's full facade: every public name of the layers below, for the test suite and
!> for code that needs an engine's internals (kernels, FFT heads, test oracles, the scene
!> runner's factory). Programs that use greenconv should `use greenconv` instead, whose
!> curated names are the supported API; the names here may change between versions.
module greenconv_api_all
    use greenconv_core_kinds, only: dp
    use greenconv_core_error, only: error_type, stat_input, stat_numerical
    use greenconv_model_modal_set, only: modal_set, modes_from_paper, random_modes
    use greenconv_model_sdof, only: sdof_receptance, sdof_impulse, sdof_modes
    use greenconv_conv_convolver, only: convolver
    use greenconv_conv_direct, only: direct_convolver, new_direct_convolver
    use greenconv_conv_kernel, only: truncation_length, sample_kernel, lane_dot
    use greenconv_conv_paper, only: paper_convolver, new_paper_convolver
    use greenconv_conv_recursive, only: recursive_convolver, new_recursive_convolver, new_exact_convolver, &
                                 new_backward_convolver
    use greenconv_conv_fft, only: fft_convolver, new_fft_convolver, default_head
    use greenconv_contact_single, only: contact_law, contact_response, contact_options, run_contact, contact_state, &
                           start_contact, contact_block
    use greenconv_model_road, only: road_profile, sine_road, random_road, new_random_road
    use greenconv_model_frf, only: frf_type, frf_from_modes, read_frf, write_frf
    use greenconv_ident_lsce, only: lsce_options, lsce_result, identify, impulse_from_frf, error_e, paper_form
    use greenconv_conv_multipoint, only: multipoint_convolver, sample_green_matrix
    use greenconv_model_point_modes, only: point_modes
    use greenconv_conv_green_modal, only: modal_green_matrix, new_modal_green_matrix
    use greenconv_conv_green_sampled, only: sampled_green_matrix, new_sampled_green_matrix
    use greenconv_contact_multi, only: newton_options, multi_contact_response, run_multi_contact, multi_contact_step, &
                                 multi_contact_state, start_multi_contact, multi_contact_block
    use greenconv_contact_laws, only: power_law, exponential_law, new_law, describe_law, law_names, law_kind, &
                                      law_kinds, find_law, replicate_law, max_law_parameters
    use greenconv_model_tyre, only: tyre_belt, tyre_frequency, tyre_mode_shape, tyre_modes, tyre_band, &
                                    contact_positions
    use greenconv_model_road_file, only: road_file, read_road_file, sample_road, check_road_coverage, &
                                         sample_road_steps, file_road, road_travel
    use greenconv_ident_structure, only: structure_model, structure_from_modes, structure_from_frf, &
                                         structure_from_samples
    use greenconv_scene_facade, only: scene_type, read_scene, run_scene, check_scene, make_convolver, output_path, &
                                      build_structure, write_multi_contact
    use greenconv_api_library, only: new_convolver, free_convolver, contact_step, check_contact_law, run_scene_file, &
                           default_truncation_tol, default_accuracy
    implicit none
    private

    public :: dp
    public :: error_type, stat_input, stat_numerical
    public :: modal_set, modes_from_paper, random_modes
    public :: sdof_receptance, sdof_impulse, sdof_modes
    public :: convolver
    public :: direct_convolver, new_direct_convolver, truncation_length, sample_kernel, lane_dot
    public :: paper_convolver, new_paper_convolver
    public :: recursive_convolver, new_recursive_convolver, new_exact_convolver, new_backward_convolver
    public :: fft_convolver, new_fft_convolver, default_head
    public :: contact_law, contact_response, contact_options, run_contact
    public :: contact_state, start_contact, contact_block
    public :: power_law, exponential_law, new_law, describe_law, law_names, law_kind, law_kinds, find_law, &
              replicate_law, max_law_parameters
    public :: road_profile, sine_road, random_road, new_random_road
    public :: frf_type, frf_from_modes, read_frf, write_frf
    public :: lsce_options, lsce_result, identify, impulse_from_frf, error_e, paper_form
    public :: scene_type, read_scene
    public :: point_modes, multipoint_convolver, sample_green_matrix
    public :: modal_green_matrix, new_modal_green_matrix, sampled_green_matrix, new_sampled_green_matrix
    public :: newton_options, multi_contact_response, run_multi_contact, multi_contact_step, write_multi_contact
    public :: multi_contact_state, start_multi_contact, multi_contact_block
    public :: tyre_belt, tyre_frequency, tyre_mode_shape, tyre_modes, tyre_band, contact_positions
    public :: road_file, read_road_file, sample_road, check_road_coverage, sample_road_steps, file_road, road_travel
    public :: structure_model, structure_from_modes, structure_from_frf, structure_from_samples, build_structure
    public :: run_scene, check_scene, make_convolver, output_path
    public :: new_convolver, free_convolver, contact_step, check_contact_law, run_scene_file
    public :: default_truncation_tol, default_accuracy

end module greenconv_api_all
