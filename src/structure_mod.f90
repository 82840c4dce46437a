!> The structure of a scene as the convolution methods need it: the exact modes when they
!> are known (an sdof, the random modes of section 3.2), the impulse response sampled at the
!> scene's time step when only G is known (an FRF file), and the modes the modal method
!> uses, which are either the exact ones or an LSCE fit of G.
module structure_mod
    use kinds_mod, only: dp
    use error_mod, only: error_type, fatal_error
    use modal_set_mod, only: modal_set, random_modes, sorted_by_frequency
    use sdof_mod, only: sdof_modes
    use frf_mod, only: frf_type, frf_from_modes, read_frf
    use lsce_mod, only: lsce_options, lsce_result, identify, impulse_from_frf
    use scene_mod, only: scene_type
    implicit none
    private

    public :: structure_model, structure_from_modes, build_structure

    !> A structure ready for the convolvers.
    type :: structure_model
        !> Whether the exact modes are known.
        logical :: has_exact = .false.
        !> The structure's own modes (when `has_exact`).
        type(modal_set) :: exact
        !> Impulse response g(t_n) [m/(N*s)] at the scene's time step, n = 0.. (when not `has_exact`).
        real(dp), allocatable :: sampled_g(:)
        !> The modes the modal methods use.
        type(modal_set) :: model
        !> Whether `model` comes from an LSCE fit (then `frf` and `fit` are set).
        logical :: identified = .false.
        !> The sampled receptance that was identified.
        type(frf_type) :: frf
        !> The identification: order, E of eq. (7), warnings.
        type(lsce_result) :: fit
    end type structure_model

contains

    !> A structure known by its modes, used as they are by the modal methods.
    function structure_from_modes(modes) result(structure)
        !> The modes.
        type(modal_set), intent(in) :: modes
        type(structure_model) :: structure

        structure%has_exact = .true.
        structure%exact = modes
        structure%model = modes
    end function structure_from_modes

    !> Build the structure of a scene: exact modes, or G sampled and identified by LSCE.
    subroutine build_structure(scene, structure, error)
        !> The scene.
        type(scene_type), intent(in) :: scene
        !> The structure.
        type(structure_model), intent(out) :: structure
        !> Set when the FRF file is unusable or the identification fails.
        type(error_type), allocatable, intent(out) :: error

        select case (scene%model)
        case ('sdof')
            structure = structure_from_modes(sdof_modes(scene%mass, scene%stiffness, scene%damping_ratio))
        case ('random_modes')
            structure%has_exact = .true.
            structure%exact = random_modes(scene%modes_seed, scene%n_modes, scene%f_low, scene%f_high, &
                                           scene%xi_low, scene%xi_high, scene%a_low, scene%a_high)
            structure%frf = frf_from_modes(structure%exact, scene%f_max, scene%n_freq)
            call identify_structure(scene, structure, error)
        case ('frf_file')
            call read_frf(scene%frf_file, structure%frf, error)
            if (allocated(error)) return
            call identify_structure(scene, structure, error)
            if (allocated(error)) return
            if (scene%task == 'contact') call sample_from_frf(scene, structure, error)
        case default
            call fatal_error(error, scene%file//": &structure model: unknown model '"//scene%model//"'")
        end select
    end subroutine build_structure

    !> Fit modes to structure%frf with the scene's identification settings.
    subroutine identify_structure(scene, structure, error)
        type(scene_type), intent(in) :: scene
        type(structure_model), intent(inout) :: structure
        type(error_type), allocatable, intent(out) :: error

        type(lsce_options) :: options

        options%tol_e = scene%tol_e
        ! `auto` wants the smallest model that meets the scene's accuracy, not more.
        if (allocated(scene%methods)) then
            if (any(scene%methods == 'auto')) options%tol_e = scene%accuracy
        end if
        options%max_modes = scene%max_order
        options%fixed_modes = scene%order
        call identify(structure%frf, options, structure%fit, error)
        if (allocated(error)) return
        structure%model = sorted_by_frequency(structure%fit%modes)
        structure%identified = .true.
    end subroutine identify_structure

    !> g at the scene's time step from the FRF: the inverse FFT gives it at 1/(2*f_max);
    !> the scene's dt must be that step or a whole multiple of it.
    subroutine sample_from_frf(scene, structure, error)
        type(scene_type), intent(in) :: scene
        type(structure_model), intent(inout) :: structure
        type(error_type), allocatable, intent(out) :: error

        real(dp), allocatable :: g(:)
        real(dp) :: dt_frf
        integer :: stride
        character(len=64) :: text

        call impulse_from_frf(structure%frf, g, dt_frf, error)
        if (allocated(error)) return
        stride = nint(scene%dt/dt_frf)
        if (stride < 1 .or. abs(stride*dt_frf - scene%dt) > 1.0e-9_dp*scene%dt) then
            write (text, '(es12.5)') dt_frf
            call fatal_error(error, scene%file//': &scene dt: expected a whole multiple of 1/(2*f_max) = ' &
                             //trim(adjustl(text))//' s, the step of g from '//scene%frf_file)
            return
        end if
        ! Only the first half of the period 1/df: the second half holds the wrapped end of g.
        structure%sampled_g = g(1:size(g)/2:stride)
    end subroutine sample_from_frf

end module structure_mod
