!> greenconv: fast convolution with Green's functions and dynamic contact.
!>
!> The public facade: `use greenconv` gives what a program calls, and only that: kinds, the
!> error type and its statuses, structure models (modal sets, the mass-spring, receptances,
!> roads), identification, convolvers built by `new_convolver`, single-point contact (whole
!> runs, single steps, streamed blocks), multi-point contact (convolvers from modes, or from a
!> universal file of a Green's matrix by `new_green_file_convolver`), and scene files. Engines'
!> internals, test oracles and benchmarks are not here; the test suite reaches them through
!> greenconv_api_all, whose extra names are not a supported API.
!> Method: R. Meftah, D. Duhamel, J. Cesbron, H.P. Yin, "Une methode rapide pour calculer
!> un produit de convolution avec une fonction de Green", CSMA 2011 (hal-00668511).
module greenconv
    use greenconv_core_kinds, only: dp
    use greenconv_core_error, only: error_type, stat_input, stat_numerical
    use greenconv_core_version, only: greenconv_version
    use greenconv_model_modal_set, only: modal_set, modes_from_paper, random_modes
    use greenconv_model_sdof, only: sdof_modes, sdof_receptance
    use greenconv_model_frf, only: frf_type, read_frf, frf_from_modes
    use greenconv_model_road, only: road_profile, sine_road, random_road, new_random_road
    use greenconv_model_point_modes, only: point_modes
    use greenconv_ident_lsce, only: lsce_options, lsce_result, identify
    use greenconv_ident_mlfit, only: ml_options, ml_result, identify_ml
    use greenconv_ident_structure, only: structure_model, structure_from_modes, structure_from_frf, &
                                         structure_from_samples, structure_from_frf_ml
    use greenconv_conv_convolver, only: convolver
    use greenconv_conv_multipoint, only: multipoint_convolver
    use greenconv_conv_builder, only: new_multipoint_convolver => make_multipoint_convolver
    use greenconv_ident_green_structure, only: green_options, green_structure, read_green_structure
    use greenconv_conv_green_file, only: green_file_options, green_file_report, new_green_file_convolver, &
                                         green_file_convolver
    use greenconv_contact_single, only: contact_law, contact_options, contact_response, run_contact, contact_state, &
                                        start_contact, contact_block
    use greenconv_contact_multi, only: newton_options, multi_contact_response, run_multi_contact
    use greenconv_contact_laws, only: power_law, exponential_law, new_law, describe_law, law_names
    use greenconv_scene_facade, only: scene_type, read_scene, run_scene, check_scene
    use greenconv_api_library, only: new_convolver, free_convolver, contact_step, run_scene_file
    implicit none
    private

    ! kinds and errors
    public :: dp, error_type, stat_input, stat_numerical
    ! the version, "major.minor.patch" as fpm.toml states it
    public :: greenconv_version
    ! structure models and roads
    public :: modal_set, modes_from_paper, random_modes, sdof_modes, sdof_receptance
    public :: frf_type, read_frf, frf_from_modes
    public :: road_profile, sine_road, random_road, new_random_road
    public :: structure_model, structure_from_modes, structure_from_frf, structure_from_samples
    public :: structure_from_frf_ml
    ! identification
    public :: lsce_options, lsce_result, identify, ml_options, ml_result, identify_ml
    ! convolvers
    public :: convolver, new_convolver, free_convolver
    ! single-point contact: whole runs, single steps, streamed blocks
    public :: contact_law, contact_options, contact_response, run_contact, contact_step
    ! contact laws: the registry's constructor by name, the shipped laws, one line naming a law
    public :: power_law, exponential_law, new_law, describe_law, law_names
    public :: contact_state, start_contact, contact_block
    ! multi-point contact
    public :: point_modes, multipoint_convolver, new_multipoint_convolver
    ! multi-point convolvers from a universal file of a Green's matrix (G_ij(f) or g_ij(t))
    public :: new_green_file_convolver, green_file_options, green_file_report
    public :: green_options, green_structure, read_green_structure, green_file_convolver
    public :: newton_options, multi_contact_response, run_multi_contact
    ! scene files
    public :: scene_type, read_scene, check_scene, run_scene, run_scene_file

end module greenconv
