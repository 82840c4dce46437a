!> The single-point structure models of the registry (greenconv_scene_models_registry), each as what the
!> registry's row names: its builder (a `structure_model` from the scene's values), and what the
!> scene's checks and `--check` ask of it.
!>
!> - `sdof`: the oscillator (M, K, xi) of Tab. 1, its exact mode;
!> - `random_modes`: the random modes of section 3.2, G sampled from them and identified;
!> - `frf_file`: a receptance read from a file (columns or a universal file), identified by the
!>   scene's method ('ml' or 'lsce'), g by inverse FFT at the scene's dt;
!> - `wheel_rail`: a wheel on an infinite rail (greenconv_model_rail), its receptance
!>   alpha_w + alpha_r sampled from 0 to f_max in closed form and then used as a file's:
!>   identified by the scene's method, g by inverse FFT at the scene's dt.
module greenconv_scene_models_single
    use greenconv_core_kinds, only: dp
    use greenconv_core_error, only: error_type
    use greenconv_core_text, only: int_text, sci_text
    use greenconv_model_modal_set, only: modal_set, random_modes
    use greenconv_model_sdof, only: sdof_modes
    use greenconv_model_frf, only: frf_type, frf_from_modes, read_frf, frf_grid
    use greenconv_model_rail, only: wheel_rail_frf, band_tail
    use greenconv_ident_structure, only: structure_model, structure_from_modes, structure_from_receptance, &
                                         receptance_identification, identify_receptance
    use greenconv_conv_methods, only: method_scheme, scheme_auto, method_needs, needs_modes
    use greenconv_scene_settings, only: scene_type, place_error
    use greenconv_ident_methods, only: ident_ml, ident_lsce
    implicit none
    private

    public :: sdof_structure, sdof_decay, random_modes_structure, random_modes_decay
    public :: frf_file_structure, check_frf_file, wheel_rail_structure, wheel_rail_receptance

    real(dp), parameter :: pi = acos(-1.0_dp)

contains

    !> The `sdof` structure: the oscillator's exact mode.
    subroutine sdof_structure(scene, structure, error)
        !> The scene (mass, stiffness, damping_ratio).
        type(scene_type), intent(in) :: scene
        !> The structure.
        type(structure_model), intent(out) :: structure
        !> Never set: the scene's checks bound the values.
        type(error_type), allocatable, intent(out) :: error

        structure = structure_from_modes(sdof_modes(scene%mass, scene%stiffness, scene%damping_ratio))
    end subroutine sdof_structure

    !> Decay rate [1/s] xi*sqrt(K/M) of the oscillator's g.
    pure real(dp) function sdof_decay(scene)
        !> The scene (model 'sdof').
        type(scene_type), intent(in) :: scene

        sdof_decay = scene%damping_ratio*sqrt(scene%stiffness/scene%mass)
    end function sdof_decay

    !> The `random_modes` structure: G sampled from the random modes, identified by the scene's
    !> method; the exact modes kept beside the identified ones.
    subroutine random_modes_structure(scene, structure, error)
        !> The scene (the random modes' seed, number and ranges, f_max, n_freq).
        type(scene_type), intent(in) :: scene
        !> The structure.
        type(structure_model), intent(out) :: structure
        !> Set when the identification fails.
        type(error_type), allocatable, intent(out) :: error

        type(modal_set) :: exact

        exact = random_modes(scene%modes_seed, scene%n_modes, scene%f_low, scene%f_high, &
                             scene%xi_low, scene%xi_high, scene%a_low, scene%a_high)
        call identify_scene(scene, frf_from_modes(exact, scene%f_max, scene%n_freq), 0.0_dp, structure, error)
        structure%has_exact = .true.
        structure%exact = exact
    end subroutine random_modes_structure

    !> Decay rate [1/s] xi_low*2*pi*f_low bounding the slowest random mode's.
    pure real(dp) function random_modes_decay(scene)
        !> The scene (model 'random_modes').
        type(scene_type), intent(in) :: scene

        random_modes_decay = scene%xi_low*2.0_dp*pi*scene%f_low
    end function random_modes_decay

    !> The `frf_file` structure: the file's receptance identified by the scene's method, g
    !> sampled at the scene's dt for a contact run.
    subroutine frf_file_structure(scene, structure, error)
        !> The scene (frf_file, frf_dataset, the identification's settings).
        type(scene_type), intent(in) :: scene
        !> The structure.
        type(structure_model), intent(out) :: structure
        !> Set when the file is unusable or the identification fails, with the file's place.
        type(error_type), allocatable, intent(out) :: error

        type(frf_type) :: frf

        call read_frf(scene%frf_file, frf, error, scene%frf_dataset)
        if (.not. allocated(error)) then
            call identify_scene(scene, frf, sampling_step(scene), structure, error)
            if (allocated(error)) error%message = scene%frf_file//': '//error%message
        end if
        if (allocated(error)) call place_error(error, scene, 'structure', 'frf_file')
    end subroutine frf_file_structure

    !> The `wheel_rail` structure: the receptance the contact sees, alpha_w + alpha_r, on the
    !> scene's n_freq lines from 0 to f_max, g sampled at the scene's dt by inverse FFT; the
    !> modes identified by the scene's method ('lsce' unless 'ml' is asked) only when a method
    !> needs them (a modal method, or `auto`, which weighs a modal fit against the sampled g) or
    !> the task is 'identify'. G being known above f_max, the own error estimate of `direct` and
    !> `fft` counts what the band leaves out from G itself (`band_error`), not from a fit.
    subroutine wheel_rail_structure(scene, structure, error)
        !> The scene (track, wheel, f_max, n_freq, the identification's settings).
        type(scene_type), intent(in) :: scene
        !> The structure: g sampled at dt, the modes when a method or the task needs them.
        type(structure_model), intent(out) :: structure
        !> Set, placed at `&identification` f_max and n_freq, when the modes cannot be fitted
        !> or dt is not a whole multiple of the grid's 1/(2*f_max).
        type(error_type), allocatable, intent(out) :: error

        type(frf_type) :: frf
        logical :: modal
        integer :: i

        frf = wheel_rail_frf(scene%track, scene%wheel, frf_grid(scene%f_max, scene%n_freq))
        modal = scene%task /= 'contact'
        if (allocated(scene%methods)) then
            do i = 1, size(scene%methods)
                modal = modal .or. method_needs(trim(scene%methods(i)), needs_modes) .or. &
                        method_scheme(trim(scene%methods(i))) == scheme_auto
            end do
        end if
        if (modal) then
            call identify_scene(scene, frf, sampling_step(scene), structure, error)
        else
            call structure_from_receptance(frf, scene%dt, structure, error)
        end if
        if (allocated(error)) then
            call place_error(error, scene, 'identification', 'f_max, n_freq')
            return
        end if
        if (allocated(structure%sampled_g) .and. structure%sampled_step > 0.0_dp) &
            structure%band_error = 2.0_dp*band_tail(scene%track, scene%wheel, 0.5_dp/structure%sampled_step) &
                                   /maxval(abs(structure%sampled_g))
    end subroutine wheel_rail_structure

    !> alpha_w + alpha_r [m/N], the receptance the wheel_rail contact sees, at omega [rad/s].
    subroutine wheel_rail_receptance(scene, omega, alpha)
        !> The scene (track, wheel).
        type(scene_type), intent(in) :: scene
        !> Angular frequencies [rad/s], >= 0.
        real(dp), intent(in) :: omega(:)
        !> The receptance at each.
        complex(dp), intent(out) :: alpha(:)

        alpha = scene%wheel%receptance(omega) + scene%track%receptance(omega)
    end subroutine wheel_rail_receptance

    !> For `--check`: read the scene's receptance file and append its lines to `line`.
    subroutine check_frf_file(scene, line, n_points, error)
        !> The scene (model 'frf_file').
        type(scene_type), intent(in) :: scene
        !> The check's line, extended with the file's lines.
        character(len=:), allocatable, intent(inout) :: line
        !> Number of contact points (unchanged: one).
        integer, intent(inout) :: n_points
        !> Set for an unusable file.
        type(error_type), allocatable, intent(out) :: error

        type(frf_type) :: frf

        call read_frf(scene%frf_file, frf, error, scene%frf_dataset)
        if (allocated(error)) then
            call place_error(error, scene, 'structure', 'frf_file')
            return
        end if
        line = line//' ('//scene%frf_file//': '//int_text(size(frf%frequency))//' lines to ' &
               //sci_text(frf%frequency(size(frf%frequency)))//' Hz)'
    end subroutine check_frf_file

    !> Identify G by the scene's method (`&identification method`), as the C and Fortran 77
    !> doors identify a receptance file (greenconv_ident_structure's `identify_receptance`).
    subroutine identify_scene(scene, frf, dt, structure, error)
        !> The scene (`&identification`: method, max_order, order, tol_e, noise, search; its
        !> methods and accuracy for `auto`).
        type(scene_type), intent(in) :: scene
        !> The receptance G [m/N].
        type(frf_type), intent(in) :: frf
        !> Time step [s] g is sampled at; 0 for the modes alone.
        real(dp), intent(in) :: dt
        !> The identified structure.
        type(structure_model), intent(out) :: structure
        !> Set when the identification fails or dt does not fit the grid.
        type(error_type), allocatable, intent(out) :: error

        type(receptance_identification) :: settings

        settings%scheme = merge(ident_ml, ident_lsce, scene%identification == ident_ml)
        settings%max_order = scene%max_order
        settings%order = scene%order
        settings%tol_e = scene%tol_e
        ! `auto` (by the registry's scheme, not its spelling) wants the smallest model that
        ! meets the scene's accuracy, not more.
        if (allocated(scene%methods)) then
            if (any(method_scheme(scene%methods) == scheme_auto)) settings%tol_e = scene%accuracy
        end if
        if (allocated(scene%ident_noise)) settings%noise_model = scene%ident_noise
        if (allocated(scene%ident_search)) settings%global_search = scene%ident_search == 'global'
        call identify_receptance(frf, settings, dt, structure, error)
    end subroutine identify_scene

    !> The step [s] g is sampled at: the scene's dt for a contact run (the step every convolver
    !> of the run gets), 0 (modes alone, no g) for task `identify`.
    pure real(dp) function sampling_step(scene)
        type(scene_type), intent(in) :: scene

        sampling_step = 0.0_dp
        if (scene%task == 'contact') sampling_step = scene%dt
    end function sampling_step

end module greenconv_scene_models_single
