!> The structure of a scene: its `&structure` and `&identification` groups turned into a
!> `structure_model` (greenconv_ident_structure) from values, with the scene's file and line
!> put in front of any error.
module greenconv_scene_structure
    use greenconv_core_kinds, only: dp
    use greenconv_core_error, only: error_type, fatal_error
    use greenconv_model_modal_set, only: modal_set, random_modes
    use greenconv_model_sdof, only: sdof_modes
    use greenconv_model_frf, only: frf_type, frf_from_modes, read_frf
    use greenconv_ident_lsce, only: lsce_options
    use greenconv_ident_mlfit, only: ml_options
    use greenconv_ident_structure, only: structure_model, structure_from_modes, structure_from_frf, &
                                         structure_from_frf_ml
    use greenconv_scene_input, only: scene_type, input_place
    use greenconv_scene_models, only: model_id, model_sdof, model_random_modes, model_frf_file
    use greenconv_conv_methods, only: method_scheme, scheme_auto
    implicit none
    private

    public :: build_structure

contains

    !> Build the structure of a scene: exact modes, or G sampled (random_modes) or read (frf_file,
    !> a column or universal file) and identified by the scene's method, 'ml' or 'lsce'.
    subroutine build_structure(scene, structure, error)
        !> The scene.
        type(scene_type), intent(in) :: scene
        !> The structure.
        type(structure_model), intent(out) :: structure
        !> Set when the FRF file is unusable or the identification fails.
        type(error_type), allocatable, intent(out) :: error

        type(frf_type) :: frf
        type(modal_set) :: exact

        select case (model_id(scene%model))
        case (model_sdof)
            structure = structure_from_modes(sdof_modes(scene%mass, scene%stiffness, scene%damping_ratio))
        case (model_random_modes)
            exact = random_modes(scene%modes_seed, scene%n_modes, scene%f_low, scene%f_high, &
                                 scene%xi_low, scene%xi_high, scene%a_low, scene%a_high)
            call identify_scene(scene, frf_from_modes(exact, scene%f_max, scene%n_freq), 0.0_dp, structure, error)
            structure%has_exact = .true.
            structure%exact = exact
        case (model_frf_file)
            call read_frf(scene%frf_file, frf, error, scene%frf_dataset)
            if (.not. allocated(error)) then
                call identify_scene(scene, frf, sampling_step(scene), structure, error)
                if (allocated(error)) error%message = scene%frf_file//': '//error%message
            end if
            if (allocated(error)) error%message = input_place(scene, 'structure', 'frf_file')//': '//error%message
        case default
            call fatal_error(error, scene%file//": &structure model: unknown model '"//scene%model//"'")
        end select
    end subroutine build_structure

    !> Identify G by the scene's method (`&identification method`).
    subroutine identify_scene(scene, frf, dt, structure, error)
        type(scene_type), intent(in) :: scene
        type(frf_type), intent(in) :: frf
        real(dp), intent(in) :: dt
        type(structure_model), intent(out) :: structure
        type(error_type), allocatable, intent(out) :: error

        type(ml_options) :: options
        logical :: ml

        ml = .false.
        if (allocated(scene%ident_method)) ml = scene%ident_method == 'ml'
        if (ml) then
            options%max_order = scene%max_order
            call structure_from_frf_ml(frf, options, dt, structure, error)
        else
            call structure_from_frf(frf, scene_options(scene), dt, structure, error)
        end if
    end subroutine identify_scene

    !> The step [s] g is sampled at: the scene's dt for a contact run (the step every convolver
    !> of the run gets), 0 (modes alone, no g) for task `identify`.
    pure real(dp) function sampling_step(scene)
        type(scene_type), intent(in) :: scene

        sampling_step = 0.0_dp
        if (scene%task == 'contact') sampling_step = scene%dt
    end function sampling_step

    !> The scene's identification settings.
    function scene_options(scene) result(options)
        type(scene_type), intent(in) :: scene
        type(lsce_options) :: options

        options%tol_e = scene%tol_e
        ! `auto` (by the registry's scheme, not its spelling) wants the smallest model that
        ! meets the scene's accuracy, not more.
        if (allocated(scene%methods)) then
            if (any(method_scheme(scene%methods) == scheme_auto)) options%tol_e = scene%accuracy
        end if
        options%max_modes = scene%max_order
        options%fixed_modes = scene%order
    end function scene_options


end module greenconv_scene_structure
