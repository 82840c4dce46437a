!> greenconv: fast convolution with Green's functions and dynamic contact.
!>
!> The public facade: `use greenconv` gives every type and procedure a user calls.
!> Method: R. Meftah, D. Duhamel, J. Cesbron, H.P. Yin, "Une methode rapide pour calculer
!> un produit de convolution avec une fonction de Green", CSMA 2011 (hal-00668511).
module greenconv
    use kinds_mod, only: dp
    use error_mod, only: error_type, stat_input, stat_numerical
    use modal_set_mod, only: modal_set, modes_from_paper, random_modes
    use sdof_mod, only: sdof_receptance, sdof_impulse, sdof_modes
    use convolver_mod, only: convolver
    use conv_direct_mod, only: direct_convolver, new_direct_convolver, truncation_length, sample_kernel, lane_dot
    use conv_modal_mod, only: paper_convolver, new_paper_convolver
    use conv_recursive_mod, only: recursive_convolver, new_recursive_convolver, new_exact_convolver, &
                                 new_backward_convolver
    use conv_fft_mod, only: fft_convolver, new_fft_convolver, default_head
    use contact_mod, only: contact_law, contact_response, contact_options, run_contact, contact_state, &
                           start_contact, contact_block
    use ode_reference_mod, only: ode_system, integrate
    use contact_reference_mod, only: contact_reference
    use contact_stability_mod, only: stability_cell, stability_map, contact_frequency
    use road_mod, only: road_profile, sine_road, random_road, new_random_road
    use frf_mod, only: frf_type, frf_from_modes, read_frf, write_frf
    use lsce_mod, only: lsce_options, lsce_result, identify, impulse_from_frf, error_e, paper_form
    use scene_mod, only: scene_type, read_scene
    use green_matrix_mod, only: point_modes, multipoint_convolver, sample_green_matrix
    use green_modal_mod, only: modal_green_matrix, new_modal_green_matrix
    use green_sampled_mod, only: sampled_green_matrix, new_sampled_green_matrix
    use multi_contact_mod, only: newton_options, multi_contact_response, run_multi_contact, multi_contact_step, &
                                 write_multi_contact, multi_contact_state, start_multi_contact, multi_contact_block
    use tyre_model_mod, only: tyre_belt, tyre_frequency, tyre_mode_shape, tyre_modes, tyre_band, contact_positions
    use road_file_mod, only: road_file, read_road_file, sample_road_file, check_road_coverage, sample_road_steps, &
                             file_road
    use structure_mod, only: structure_model, structure_from_modes, structure_from_frf, structure_from_samples, &
                             build_structure
    use scene_run_mod, only: run_scene, check_scene, make_convolver, output_path
    use library_mod, only: new_convolver, free_convolver, contact_step, check_contact_law, run_scene_file, &
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
    public :: ode_system, integrate, contact_reference
    public :: stability_cell, stability_map, contact_frequency
    public :: road_profile, sine_road, random_road, new_random_road
    public :: frf_type, frf_from_modes, read_frf, write_frf
    public :: lsce_options, lsce_result, identify, impulse_from_frf, error_e, paper_form
    public :: scene_type, read_scene
    public :: point_modes, multipoint_convolver, sample_green_matrix
    public :: modal_green_matrix, new_modal_green_matrix, sampled_green_matrix, new_sampled_green_matrix
    public :: newton_options, multi_contact_response, run_multi_contact, multi_contact_step, write_multi_contact
    public :: multi_contact_state, start_multi_contact, multi_contact_block
    public :: tyre_belt, tyre_frequency, tyre_mode_shape, tyre_modes, tyre_band, contact_positions
    public :: road_file, read_road_file, sample_road_file, check_road_coverage, sample_road_steps, file_road
    public :: structure_model, structure_from_modes, structure_from_frf, structure_from_samples, build_structure
    public :: run_scene, check_scene, make_convolver, output_path
    public :: new_convolver, free_convolver, contact_step, check_contact_law, run_scene_file
    public :: default_truncation_tol, default_accuracy

end module greenconv
