!> Entry points for programs that embed greenconv rather than run the driver: build any
!> convolver from a structure with its inputs checked, step a contact loop yourself one step
!> at a time, free a convolver, run a scene file.
!>
!> Every procedure here works only on its arguments: there is no module state, so two
!> simulations in one program (or in two threads, see greenconv_ext_fftw on FFTW's planner) do not
!> interfere. Failures come back as an allocated `error_type` (status and message), never
!> as a `stop`.
module greenconv_api_library
    use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
    use greenconv_core_kinds, only: dp
    use greenconv_core_error, only: error_type, fatal_error
    use greenconv_conv_convolver, only: convolver, free_convolver
    use greenconv_contact_single, only: contact_law
    use greenconv_ident_structure, only: structure_model
    use greenconv_model_modal_set, only: modal_set
    use greenconv_core_text, only: int_text, sci_text
    use greenconv_scene_input, only: scene_type, read_scene
    use greenconv_scene_runner, only: make_convolver, run_scene
    implicit none
    private

    public :: new_convolver, free_convolver, contact_step, check_contact_law, run_scene_file
    public :: default_truncation_tol, default_accuracy

    !> Truncation of g for `direct` and `fft` when none is given: the paper's 1 % of max |g|.
    real(dp), parameter :: default_truncation_tol = 0.01_dp
    !> Relative accuracy `auto` must meet when none is given: the largest E (eq. 7) it accepts.
    real(dp), parameter :: default_accuracy = 1.0e-3_dp

contains

    !> Build the convolver called `method` for a structure, after checking that the method
    !> can run on it: `direct` and `fft` need g (exact modes, or g sampled at dt), the modal
    !> methods (`modal`, `recursive`, `paper`, `exact`, `backward`) and `auto` need modes. See
    !> `make_convolver` (greenconv_scene_runner) for what each method computes.
    subroutine new_convolver(method, structure, dt, n_steps, conv, error, truncation_tol, accuracy, description)
        !> Method: `direct`, `fft`, `modal`, `recursive`, `paper`, `exact`, `backward` or `auto`.
        character(len=*), intent(in) :: method
        !> The structure (from `structure_from_modes`, `structure_from_frf` or `structure_from_samples`).
        type(structure_model), intent(in) :: structure
        !> Time step dt [s], > 0; for a structure from samples or an FRF, the step of its g.
        real(dp), intent(in) :: dt
        !> Number of steps N_t the run will take, >= 1 (caps the kernel of `direct` and `fft`).
        integer, intent(in) :: n_steps
        !> The convolver, at step 0. Free it with `free_convolver` (an `fft` convolver holds FFTW plans).
        class(convolver), allocatable, intent(out) :: conv
        !> Set (status `stat_input`) when the inputs cannot make this convolver.
        type(error_type), allocatable, intent(out) :: error
        !> Truncation fraction of max |g| for `direct` and `fft`, in (0, 1); default 0.01.
        real(dp), intent(in), optional :: truncation_tol
        !> Relative accuracy `auto` must meet, > 0; default 1e-3.
        real(dp), intent(in), optional :: accuracy
        !> What the model neglects, in words (and, for `auto`, what it chose and why).
        character(len=:), allocatable, intent(out), optional :: description

        character(len=:), allocatable :: text
        real(dp) :: tol, requested

        tol = default_truncation_tol
        if (present(truncation_tol)) tol = truncation_tol
        requested = default_accuracy
        if (present(accuracy)) requested = accuracy
        call check_request(method, structure, dt, n_steps, tol, requested, error)
        if (allocated(error)) return
        call make_convolver(method, structure, dt, tol, n_steps, conv, text, error, requested)
        if (allocated(error)) return
        if (present(description)) description = text
    end subroutine new_convolver

    !> Reject a request `make_convolver` cannot serve.
    subroutine check_request(method, structure, dt, n_steps, tol, requested, error)
        character(len=*), intent(in) :: method
        type(structure_model), intent(in) :: structure
        real(dp), intent(in) :: dt, tol, requested
        integer, intent(in) :: n_steps
        type(error_type), allocatable, intent(out) :: error

        logical :: has_g

        has_g = structure%has_exact
        if (allocated(structure%sampled_g)) has_g = has_g .or. size(structure%sampled_g) >= 2
        if (.not. (dt > 0.0_dp .and. ieee_is_finite(dt))) then
            call fatal_error(error, 'new_convolver: the time step dt must be finite and > 0 s')
        else if (n_steps < 1) then
            call fatal_error(error, 'new_convolver: the number of steps must be >= 1')
        else if (.not. (tol > 0.0_dp .and. tol < 1.0_dp)) then
            call fatal_error(error, 'new_convolver: truncation_tol must be in (0, 1)')
        else if (.not. (requested > 0.0_dp)) then
            call fatal_error(error, 'new_convolver: accuracy must be > 0')
        else if ((method == 'direct' .or. method == 'fft') .and. .not. has_g) then
            call fatal_error(error, "new_convolver: method '"//method//"' needs g: give the structure modes, " &
                             //'samples of g, or an FRF with dt > 0')
        else if (method /= 'direct' .and. method /= 'fft' .and. structure%model%n_modes() == 0) then
            call fatal_error(error, "new_convolver: method '"//method//"' needs modes, and this structure has " &
                             //"none (only sampled g): use 'direct' or 'fft'")
        else
            call check_modes(structure%model, error)
            if (.not. allocated(error) .and. structure%has_exact) call check_modes(structure%exact, error)
        end if
    end subroutine check_request

    !> Modes a caller gives (structure_from_modes) must be those of a passive structure:
    !> finite poles with Re lambda < 0 and Im lambda > 0, finite residues.
    subroutine check_modes(modes, error)
        type(modal_set), intent(in) :: modes
        type(error_type), allocatable, intent(out) :: error

        integer :: k

        do k = 1, modes%n_modes()
            associate (pole => modes%pole(k), residue => modes%residue(k))
                if (.not. (ieee_is_finite(real(pole, dp)) .and. ieee_is_finite(aimag(pole)) .and. &
                           ieee_is_finite(real(residue, dp)) .and. ieee_is_finite(aimag(residue)))) then
                    call fatal_error(error, 'new_convolver: mode '//int_text(k)//': expected a finite pole and ' &
                                     //'residue, found lambda = ('//sci_text(real(pole, dp))//', ' &
                                     //sci_text(aimag(pole))//') rad/s, r = ('//sci_text(real(residue, dp))//', ' &
                                     //sci_text(aimag(residue))//')')
                else if (.not. (real(pole, dp) < 0.0_dp .and. aimag(pole) > 0.0_dp)) then
                    call fatal_error(error, 'new_convolver: mode '//int_text(k)//': expected a pole with ' &
                                     //'Re lambda < 0 and Im lambda > 0 rad/s (a damped mode), found lambda = (' &
                                     //sci_text(real(pole, dp))//', '//sci_text(aimag(pole))//') rad/s')
                end if
            end associate
            if (allocated(error)) return
        end do
    end subroutine check_modes

    !> One explicit step n of the contact loop, exactly as `run_contact` takes it (eqs. 20-24):
    !> u_h = history, delta = delta0 + u_r - u_h with delta0 = (F0/k_c)^(1/p), F = k_c*delta^p
    !> (0 when delta <= 0), the load F - F0 pushed, u = u_h + w0*(F - F0). Start from a
    !> convolver at step 0 (new or reset): the body rests in static equilibrium under F0.
    subroutine contact_step(conv, law, road, preload, displacement, force, compression)
        !> The convolver, advanced by one step.
        class(convolver), intent(inout) :: conv
        !> The contact law (k_c [N/m^p], p).
        type(contact_law), intent(in) :: law
        !> Road height u_r(t_n) [m] under the contact.
        real(dp), intent(in) :: road
        !> Static preload F0 [N], >= 0.
        real(dp), intent(in) :: preload
        !> Body displacement u(t_n) [m] from static equilibrium.
        real(dp), intent(out) :: displacement
        !> Contact force F(t_n) [N], >= 0.
        real(dp), intent(out) :: force
        !> Compression delta(t_n) [m] of the contact spring (<= 0: no contact).
        real(dp), intent(out), optional :: compression

        real(dp) :: u_h, delta, load

        u_h = conv%history()
        delta = law%compression(preload) + road - u_h
        force = law%force(delta)
        load = force - preload
        call conv%push(load)
        displacement = u_h + conv%instant_weight()*load
        if (present(compression)) compression = delta
    end subroutine contact_step

    !> Check a contact law and preload: k_c > 0, p > 0 and F0 >= 0, all finite.
    subroutine check_contact_law(law, preload, error)
        !> The contact law.
        type(contact_law), intent(in) :: law
        !> Static preload F0 [N].
        real(dp), intent(in) :: preload
        !> Set (status `stat_input`) when a value is out of range.
        type(error_type), allocatable, intent(out) :: error

        if (.not. (law%stiffness > 0.0_dp .and. ieee_is_finite(law%stiffness))) then
            call fatal_error(error, 'contact: the stiffness k_c must be finite and > 0 N/m^p')
        else if (.not. (law%exponent > 0.0_dp .and. ieee_is_finite(law%exponent))) then
            call fatal_error(error, 'contact: the exponent p must be finite and > 0')
        else if (.not. (preload >= 0.0_dp .and. ieee_is_finite(preload))) then
            call fatal_error(error, 'contact: the preload F0 must be finite and >= 0 N')
        end if
    end subroutine check_contact_law

    !> Read a scene file and run it as the driver does: column files in its output_dir and
    !> a summary line per method on `unit`.
    subroutine run_scene_file(path, unit, error)
        !> Path of the namelist scene file.
        character(len=*), intent(in) :: path
        !> Unit the summary is printed on (an open formatted unit, e.g. output_unit).
        integer, intent(in) :: unit
        !> Set when the scene is unusable (status `stat_input`) or a run fails.
        type(error_type), allocatable, intent(out) :: error

        type(scene_type) :: scene

        call read_scene(path, scene, error)
        if (allocated(error)) return
        call run_scene(scene, unit, error)
    end subroutine run_scene_file

end module greenconv_api_library
