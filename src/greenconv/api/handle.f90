!> The one object behind every foreign handle, single- and multi-point alike, and what the
!> single-point front doors share: the checks of the constructors' plain arguments, and
!> contact runs into caller-sized arrays.
!>
!> The C API (greenconv_capi, greenconv_capi_multi) and the Fortran 77 layer (greenconv_legacy,
!> greenconv_legacy_multi) all point at a `convolver_box`: a multi-point convolver, a
!> single-point structure's convolver being its 1 x 1 case (greenconv_conv_point_matrix), what
!> its model neglects, and the state of a contact run stepped one call at a time.
!> Multi-point handles are made and run by greenconv_api_multi_handle. Everything here works on
!> the Fortran API; the doors only convert arguments and messages. There is no module state.
module greenconv_api_handle
    use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
    use, intrinsic :: iso_fortran_env, only: int64
    use, intrinsic :: iso_c_binding, only: c_ptr, c_associated, c_f_pointer
    use greenconv_core_kinds, only: dp
    use greenconv_core_error, only: error_type, fatal_error
    use greenconv_core_text, only: lower_text, sci_text, int_text
    use greenconv_model_modal_set, only: modal_set, sorted_by_frequency
    use greenconv_model_sdof, only: sdof_modes
    use greenconv_model_frf, only: frf_type, read_frf
    use greenconv_ident_lsce, only: lsce_options, lsce_result, identify
    use greenconv_ident_mlfit, only: ml_options, ml_result, identify_ml
    use greenconv_ident_structure, only: structure_model, structure_from_modes, structure_from_samples, &
                                         receptance_identification, identify_receptance
    use greenconv_ident_methods, only: check_ident_method, ident_scheme, ident_one_receptance
    use greenconv_ident_green_structure, only: green_structure
    use greenconv_model_point_modes, only: point_modes
    use greenconv_model_modes_file, only: file_modes
    use greenconv_conv_convolver, only: convolver
    use greenconv_conv_multipoint, only: multipoint_convolver
    use greenconv_conv_point_matrix, only: point_matrix, wrap_point
    use greenconv_conv_methods, only: method_needs, needs_sampled_g
    use greenconv_contact_law, only: contact_law
    use greenconv_contact_single, only: contact_options
    use greenconv_contact_multi, only: newton_options, multi_contact_state
    use greenconv_contact_budget, only: doubling_sums
    use greenconv_scene_facade, only: max_lsce_modes
    use greenconv_api_library, only: new_convolver, check_contact_law, contact_step, default_truncation_tol
    implicit none
    private

    public :: convolver_box, companion_run, door_budget, release_companions, new_box, free_box, box_at
    public :: sdof_structure, modes_structure, samples_structure, frf_file_structure
    public :: identify_file, identify_file_ml, check_steps, step_box, refuse_multi_point
    public :: reset_box, describe_box

    !> The mark of a live box (`convolver_box%mark`); `free_box` overwrites it before the box
    !> goes back to the allocator.
    integer(int64), parameter :: live_mark = int(z'6763636F6E763031', int64)

    !> One companion of a contact run's error budget (greenconv_api_budget): the box's method on
    !> its source at another time step or with a wider band, stepped alongside the run.
    type :: companion_run
        !> Its convolver (a single-point one as the 1 x 1 case).
        class(multipoint_convolver), allocatable :: conv
        !> Its contact run.
        type(multi_contact_state) :: state
        !> Whether it is running (false when it could not be built or started, or failed).
        logical :: running = .false.
    end type companion_run

    !> The error budget of the contact run going on (or last run) on a box: its companions at
    !> 2*dt and 4*dt and, for a modes file's box, with the modes up to twice the band, and the
    !> sums their forces add (greenconv_contact_budget).
    type :: door_budget
        !> The companions: 1 at 2*dt, 2 at 4*dt, 3 at dt with the wider band.
        type(companion_run) :: run(3)
        !> Whether the run is a single-point one, stepped with its scheme.
        logical :: single = .false.
        !> Order of the method in dt (1 for `backward`, else 2).
        integer :: order = 2
        !> Steps of the run fed so far.
        integer(int64) :: step = 0_int64
        !> Whether the companion at 2*dt is missing (could not be built, or failed).
        logical :: step_missing = .false.
        !> Whether the band's term is doubled (the wider run does not hold every mode).
        logical :: band_doubled = .false.
        !> Static preloads F0_i [N] of the run.
        real(dp), allocatable :: preload(:)
        !> The sums of step doubling [N^2].
        type(doubling_sums) :: sums
        !> Sums over the steps of |F - F_band|^2 and |F_band - F0|^2 [N^2], over the points.
        real(dp) :: band_difference = 0.0_dp, band_reference = 0.0_dp
    end type door_budget

    !> What a foreign handle points to.
    type :: convolver_box
        !> `live_mark` while the box is in use: `box_at` refuses an address without it, which
        !> catches a handle freed a moment ago as long as its memory has not been given out
        !> again (a cheap check, not a guarantee).
        integer(int64) :: mark = live_mark
        !> The convolver: a Green's matrix of N_c points, or the 1 x 1 `point_matrix` of a
        !> single-point structure.
        class(multipoint_convolver), allocatable :: conv
        !> What the model neglects, in words.
        character(len=:), allocatable :: description
        !> Warnings of the identification the structure came from (wrap-around, a fit that
        !> missed its target, dropped poles), '' when none.
        character(len=:), allocatable :: warning
        !> Newton and divergence settings of the multi-point contact runs on this convolver.
        type(newton_options) :: settings
        !> The contact run stepped one call at a time, at N_c points or at one (C:
        !> `gc_multi_contact_start`, or `gc_contact_start` with the single-point scheme):
        !> one state for both (greenconv_contact_step's).
        type(multi_contact_state) :: contact
        !> True between a successful start of a stepped contact run and its first fault or reset.
        logical :: stepping = .false.
        !> The Green's matrix file the convolver was built from, read and identified (its points:
        !> node labels, x_i, y_i [m]); unallocated for a convolver made otherwise.
        type(green_structure), allocatable :: green
        !> The method's own estimate of its relative error (greenconv_conv_builder,
        !> greenconv_conv_green_file), 0 when it has none; compared with `accuracy`.
        real(dp) :: estimate = 0.0_dp
        !> Relative accuracy the host asked (gc_multi_set_accuracy, GCMACC); 0: none asked.
        real(dp) :: accuracy = 0.0_dp
        !> The convolver's method, for the error budget's companion runs of a whole multi-point
        !> contact run (greenconv_api_multi_handle's `run_multi_box`).
        character(len=:), allocatable :: method
        !> The convolver's time step [s] and truncation fraction of max |g_ij|, for the companions.
        real(dp) :: dt = 0.0_dp, truncation_tol = 0.0_dp
        !> The modes at the points the convolver was built on; unallocated when built otherwise.
        type(point_modes), allocatable :: source_modes
        !> The static compliance [m/N] added to its W0 (a modes file's modes above its band).
        real(dp), allocatable :: source_residual(:, :)
        !> The samples g(m, i, j) [m/(N*s)] at dt the convolver was built on; unallocated when
        !> built otherwise.
        real(dp), allocatable :: source_g(:, :, :)
        !> The modes of the modes file the convolver was built on (every node a point), for the
        !> band's companion; unallocated when built otherwise.
        type(file_modes), allocatable :: source_file
        !> Top of the band of a modes file's modes stepped [Hz] (0: no band).
        real(dp) :: band = 0.0_dp
        !> The time-step and band terms [-] of the error budget of the contact run going on or
        !> last run (0 before one), added to `estimate` by the estimate doors and the accuracy check.
        real(dp) :: run_terms = 0.0_dp
        !> The companions and sums behind `run_terms`.
        type(door_budget) :: budget
        !> What is known of the run's terms before a run [-] (`run_terms` until a run has 8
        !> steps): a modes file's static share above its band for a method that leaves it out.
        real(dp) :: prior_terms = 0.0_dp
        !> Number of steps N_t the convolver was built for (caps the companions' kernels).
        integer :: n_steps = 0
        !> The single-point structure the convolver was built on; unallocated for a multi-point box.
        type(structure_model), allocatable :: structure
        !> The scheme of the single-point contact run stepped one call at a time.
        type(contact_options) :: point_options
        !> Node labels of the points of a convolver made from a modes file (gc_multi_new_modes_file,
        !> GCMMFL); unallocated otherwise.
        integer, allocatable :: node(:)
        !> x_i and y_i [m] of those nodes.
        real(dp), allocatable :: node_x(:), node_y(:)
    end type convolver_box

contains

    !> A new box holding the convolver `method` (any case) for a structure; null on failure.
    subroutine new_box(method, structure, dt, n_steps, box, error, truncation_tol, accuracy)
        !> Method name (see `new_convolver`), any case.
        character(len=*), intent(in) :: method
        !> The structure.
        type(structure_model), intent(in) :: structure
        !> Time step dt [s], > 0.
        real(dp), intent(in) :: dt
        !> Number of steps N_t of the run, >= 1.
        integer, intent(in) :: n_steps
        !> The new box; null when `error` is set.
        type(convolver_box), pointer, intent(out) :: box
        !> Set when the convolver cannot be made.
        type(error_type), allocatable, intent(out) :: error
        !> Truncation fraction of max |g| for `direct` and `fft`, in (0, 1); the library's default when absent.
        real(dp), intent(in), optional :: truncation_tol
        !> Relative accuracy `auto` must meet, > 0; the library's default when absent.
        real(dp), intent(in), optional :: accuracy

        class(convolver), allocatable :: point

        allocate (box)
        call new_convolver(lower_text(method), structure, dt, n_steps, point, error, truncation_tol, accuracy, &
                           box%description, box%estimate, box%method)
        if (allocated(error)) then
            deallocate (box)
            box => null()
            return
        end if
        allocate (point_matrix :: box%conv)
        select type (matrix => box%conv)
        type is (point_matrix)
            call wrap_point(point, matrix)
        end select
        call structure%fit_warnings(box%warning)
        box%dt = dt
        box%n_steps = n_steps
        box%truncation_tol = default_truncation_tol
        if (present(truncation_tol)) box%truncation_tol = truncation_tol
        box%structure = structure
    end subroutine new_box

    !> Free a box and its convolver (FFTW plans too), single- or multi-point; nothing for a null
    !> pointer. Null on return.
    subroutine free_box(box)
        !> The box.
        type(convolver_box), pointer, intent(inout) :: box

        if (.not. associated(box)) return
        box%mark = 0_int64
        if (allocated(box%conv)) then
            call box%conv%release()
            deallocate (box%conv)
        end if
        call release_companions(box%budget)
        deallocate (box)
        box => null()
    end subroutine free_box

    !> Release the companions of a budget (their FFTW plans too) and stop them.
    subroutine release_companions(budget)
        !> The budget.
        type(door_budget), intent(inout) :: budget

        integer :: f

        do f = 1, size(budget%run)
            if (allocated(budget%run(f)%conv)) then
                call budget%run(f)%conv%release()
                deallocate (budget%run(f)%conv)
            end if
            budget%run(f)%running = .false.
        end do
    end subroutine release_companions

    !> The box at a C address: a C handle, or the address a Fortran 77 handle stands for
    !> (greenconv_api_doors's `handle_address`); null for C NULL, and for a box without the
    !> live mark (one freed, whose memory the allocator has not yet given out again: the doors
    !> then refuse it as a null handle rather than read a freed object; a handle whose memory
    !> was reused cannot be told apart, so a call after a free stays undefined).
    function box_at(address) result(box)
        !> The address of a box made by `new_box` or greenconv_api_multi_handle, or C NULL.
        type(c_ptr), intent(in) :: address
        type(convolver_box), pointer :: box

        box => null()
        if (.not. c_associated(address)) return
        call c_f_pointer(address, box)
        if (box%mark /= live_mark) box => null()
    end function box_at

    !> Back to step 0 with no force history, ending a contact run stepped one call at a time.
    subroutine reset_box(box)
        !> The box.
        type(convolver_box), intent(inout) :: box

        call box%conv%reset()
        box%stepping = .false.
        call release_companions(box%budget)
    end subroutine reset_box

    !> "method: what the model neglects", and with `n` present ", N_g = n" (or N_m): the model's
    !> size, returned in `n` too.
    subroutine describe_box(box, text, n)
        !> The box.
        type(convolver_box), intent(in) :: box
        !> The description.
        character(len=:), allocatable, intent(out) :: text
        !> The model's size (N_g kernel samples or N_m modes); absent: not in the text.
        integer, intent(out), optional :: n

        character(len=:), allocatable :: label

        text = box%conv%name//': '//box%description
        if (.not. present(n)) return
        call box%conv%model_size(n, label)
        text = text//', '//label//' = '//int_text(n)
    end subroutine describe_box

    !> Refuse steps a box's kernel does not cover, single- or multi-point: a `direct` or `fft`
    !> convolver whose kernel was cut at the n_steps it was made for (g not decayed by then)
    !> would give a short, wrong sum from there on (greenconv_conv_convolver's `check_validity`).
    !> `steps` more steps from the current one must stay below it.
    subroutine check_steps(box, caller, steps, error)
        !> The box.
        type(convolver_box), intent(in) :: box
        !> Name of the front-door routine, first word of a message.
        character(len=*), intent(in) :: caller
        !> Steps about to be taken from the current step (history or push of this step: 1).
        integer(int64), intent(in) :: steps
        !> Set (`stat_input`) when a step lies past the kernel's validity.
        type(error_type), allocatable, intent(out) :: error

        call box%conv%check_validity(steps, error)
        if (allocated(error)) error%message = caller//': '//error%message
    end subroutine check_steps

    !> The structure of a damped mass-spring system, its arguments checked by name.
    subroutine sdof_structure(caller, mass, stiffness, damping_ratio, structure, error)
        !> Name of the front-door routine, first word of a message.
        character(len=*), intent(in) :: caller
        !> Mass M [kg], finite and > 0.
        real(dp), intent(in) :: mass
        !> Stiffness K [N/m], finite and > 0.
        real(dp), intent(in) :: stiffness
        !> Damping ratio xi, in [0, 1).
        real(dp), intent(in) :: damping_ratio
        !> The structure (one exact mode).
        type(structure_model), intent(out) :: structure
        !> Set (`stat_input`) naming the first argument out of range.
        type(error_type), allocatable, intent(out) :: error

        if (.not. (mass > 0.0_dp .and. ieee_is_finite(mass))) then
            call fatal_error(error, caller//': mass = '//sci_text(mass)//' kg: give a finite mass > 0 kg')
        else if (.not. (stiffness > 0.0_dp .and. ieee_is_finite(stiffness))) then
            call fatal_error(error, caller//': stiffness = '//sci_text(stiffness) &
                             //' N/m: give a finite stiffness > 0 N/m')
        else if (.not. (damping_ratio >= 0.0_dp .and. damping_ratio < 1.0_dp)) then
            call fatal_error(error, caller//': damping ratio = '//sci_text(damping_ratio) &
                             //': give a damping ratio in [0, 1)')
        else
            structure = structure_from_modes(sdof_modes(mass, stiffness, damping_ratio))
        end if
    end subroutine sdof_structure

    !> The structure of modes in pole-residue form, the arrays checked.
    subroutine modes_structure(caller, pole_re, pole_im, residue_re, residue_im, structure, error)
        !> Name of the front-door routine, first word of a message.
        character(len=*), intent(in) :: caller
        !> Real parts of the poles [rad/s], < 0.
        real(dp), intent(in) :: pole_re(:)
        !> Imaginary parts of the poles [rad/s], > 0.
        real(dp), intent(in) :: pole_im(:)
        !> Real parts of the residues [m/(N*s)].
        real(dp), intent(in) :: residue_re(:)
        !> Imaginary parts of the residues [m/(N*s)].
        real(dp), intent(in) :: residue_im(:)
        !> The structure.
        type(structure_model), intent(out) :: structure
        !> Set (`stat_input`) naming what is out of range.
        type(error_type), allocatable, intent(out) :: error

        type(modal_set) :: modes

        if (size(pole_re) < 1) then
            call fatal_error(error, caller//': number of modes = '//int_text(size(pole_re))//': give at least 1 mode')
        else if (.not. all(pole_re < 0.0_dp .and. pole_im > 0.0_dp .and. ieee_is_finite(pole_re) &
                           .and. ieee_is_finite(pole_im))) then
            call fatal_error(error, caller//': poles: give every pole a finite real part < 0 and imaginary ' &
                             //'part > 0 rad/s (a damped mode)')
        else if (.not. all(ieee_is_finite(residue_re) .and. ieee_is_finite(residue_im))) then
            call fatal_error(error, caller//': residues: give finite residues [m/(N*s)]')
        else
            modes%pole = cmplx(pole_re, pole_im, dp)
            modes%residue = cmplx(residue_re, residue_im, dp)
            structure = structure_from_modes(modes)
        end if
    end subroutine modes_structure

    !> The structure known by samples of g, the samples checked.
    subroutine samples_structure(caller, g, structure, error)
        !> Name of the front-door routine, first word of a message.
        character(len=*), intent(in) :: caller
        !> Samples g(n*dt) [m/(N*s)], at least two, finite.
        real(dp), intent(in) :: g(:)
        !> The structure.
        type(structure_model), intent(out) :: structure
        !> Set (`stat_input`) naming what is out of range.
        type(error_type), allocatable, intent(out) :: error

        if (size(g) < 2) then
            call fatal_error(error, caller//': number of samples = '//int_text(size(g)) &
                             //': give at least 2 samples of g')
        else if (.not. all(ieee_is_finite(g))) then
            call fatal_error(error, caller//': samples of g: give finite values [m/(N*s)]')
        else
            structure = structure_from_samples(g)
        end if
    end subroutine samples_structure

    !> The structure known by a receptance file, identified as a scene's `frf_file` model is
    !> (greenconv_ident_structure's `identify_receptance`): by default with the identification
    !> registry's method for a measured receptance (maximum likelihood, the order by MDL up to
    !> max_modes, the noise model chosen from the data), or by LSCE when asked (the smallest
    !> model with E <= tol_e up to max_modes modes); and g at dt for the methods that convolve
    !> with it (`direct`, `fft`, `auto`).
    subroutine frf_file_structure(path, method, dt, tol_e, max_modes, structure, error, identification)
        !> Path of the receptance file (`#` comments, then f [Hz], Re G, Im G [m/N]).
        character(len=*), intent(in) :: path
        !> Method name, any case.
        character(len=*), intent(in) :: method
        !> Time step dt [s] of the run.
        real(dp), intent(in) :: dt
        !> Target of the identification error E of eq. (7), > 0 (LSCE's).
        real(dp), intent(in) :: tol_e
        !> Largest number of modes the order search tries, >= 1.
        integer, intent(in) :: max_modes
        !> The structure.
        type(structure_model), intent(out) :: structure
        !> Set when the file or the identification method is unusable (`stat_input`) or the fit
        !> fails (`stat_numerical`).
        type(error_type), allocatable, intent(out) :: error
        !> Identification method, any case: 'ml' or 'lsce'; absent or blank: the registry's
        !> default for a measured receptance ('ml').
        character(len=*), intent(in), optional :: identification

        type(frf_type) :: frf
        type(lsce_options) :: options
        type(receptance_identification) :: settings
        character(len=:), allocatable :: refused
        real(dp) :: dt_g

        if (present(identification)) then
            if (len_trim(identification) > 0) then
                call check_ident_method(lower_text(trim(identification)), ident_one_receptance, 'frf_file', 0, &
                                        refused, error)
                if (allocated(error)) then
                    error%message = 'identification method = '''//trim(identification)//''': expected '//error%message
                    return
                end if
                settings%scheme = ident_scheme(lower_text(trim(identification)))
            end if
        end if
        call read_receptance(path, tol_e, max_modes, frf, options, error)
        if (allocated(error)) return
        settings%tol_e = options%tol_e
        settings%max_order = options%max_modes
        dt_g = 0.0_dp
        if (method_needs(lower_text(method), needs_sampled_g)) dt_g = dt
        call identify_receptance(frf, settings, dt_g, structure, error)
    end subroutine frf_file_structure

    !> One explicit step of the single-point contact loop on a box (the law and the kernel's
    !> validity checked first): u, F and delta of this step, the convolver advanced; all zero
    !> and the convolver untouched on bad input.
    subroutine step_box(caller, box, law, preload, road, displacement, force, compression, error)
        !> Name of the front-door routine, first word of a message.
        character(len=*), intent(in) :: caller
        !> The box of a single-point structure.
        type(convolver_box), intent(inout) :: box
        !> The contact law between body and road, checked here.
        class(contact_law), intent(in) :: law
        !> F0 [N] pressing the body onto the road at rest, checked here (>= 0).
        real(dp), intent(in) :: preload
        !> u_r(t_n) [m] under the contact at this step.
        real(dp), intent(in) :: road
        !> u(t_n) [m] of this step (0 on bad input or a fault).
        real(dp), intent(out) :: displacement
        !> F(t_n) [N] of this step (0 on bad input or a fault).
        real(dp), intent(out) :: force
        !> delta(t_n) [m] of this step (0 on bad input or a fault).
        real(dp), intent(out) :: compression
        !> Set (`stat_input`) for a bad law or a step past the kernel; (`stat_numerical`, the
        !> caller and the step named) when u, F or delta of the step is not finite (a road height
        !> that is NaN or infinite, a step that diverged), the convolver then not advanced.
        type(error_type), allocatable, intent(out) :: error

        displacement = 0.0_dp
        force = 0.0_dp
        compression = 0.0_dp
        call check_contact_law(law, preload, error)
        if (.not. allocated(error)) call check_steps(box, caller, 1_int64, error)
        if (allocated(error)) return
        select type (matrix => box%conv)
        type is (point_matrix)
            call contact_step(matrix%point, law, road, preload, displacement, force, compression, error)
            matrix%step = matrix%point%step
        class default
            call refuse_multi_point(caller, box, error)
            return
        end select
        if (.not. allocated(error)) return
        error%message = caller//': '//error%message
        displacement = 0.0_dp
        force = 0.0_dp
        compression = 0.0_dp
    end subroutine step_box

    !> Refuse a box of several points at a single-point step door (a multi-point handle cast).
    subroutine refuse_multi_point(caller, box, error)
        !> Name of the front-door routine, first word of the message.
        character(len=*), intent(in) :: caller
        !> The box.
        type(convolver_box), intent(in) :: box
        !> Set (`stat_input`) naming the box's number of points.
        type(error_type), allocatable, intent(out) :: error

        call fatal_error(error, caller//': the convolver has '//int_text(box%conv%n_points()) &
                         //' points: this door steps a single-point convolver (step a multi-point one with ' &
                         //'the multi-point doors)')
    end subroutine refuse_multi_point

    !> Modes identified by LSCE from a receptance file, lowest natural frequency first.
    subroutine identify_file(path, tol_e, max_modes, modes, e, error)
        !> Path of the receptance file (`#` comments, then f [Hz], Re G, Im G [m/N]).
        character(len=*), intent(in) :: path
        !> Target of the identification error E of eq. (7), > 0.
        real(dp), intent(in) :: tol_e
        !> Largest number of modes the LSCE order scan tries, >= 1.
        integer, intent(in) :: max_modes
        !> The modes (poles [rad/s], residues [m/(N*s)]).
        type(modal_set), intent(out) :: modes
        !> Error E of eq. (7) of the fit; 0 on failure.
        real(dp), intent(out) :: e
        !> Set for a file that cannot be read (`stat_input`) or a fit that fails (`stat_numerical`).
        type(error_type), allocatable, intent(out) :: error

        type(frf_type) :: frf
        type(lsce_options) :: options
        type(lsce_result) :: fit

        e = 0.0_dp
        call read_receptance(path, tol_e, max_modes, frf, options, error)
        if (allocated(error)) return
        call identify(frf, options, fit, error)
        if (allocated(error)) return
        modes = sorted_by_frequency(fit%modes)
        e = fit%e
    end subroutine identify_file

    !> Identify the modes of a receptance file by maximum likelihood (greenconv_ident_mlfit),
    !> the order by MDL and the noise model as asked ('auto': from the data), as a scene's
    !> `method = 'ml'` does: the modes lowest frequency first, their standard deviations and
    !> whether the data determine each (ml_result%determined).
    subroutine identify_file_ml(path, noise_model, max_order, result, error)
        !> Path of the receptance file (columns f [Hz], Re G, Im G [m/N], or a universal file).
        character(len=*), intent(in) :: path
        !> 'auto', 'relative', 'absolute', 'floor' or 'band' (ml_options%noise_model).
        character(len=*), intent(in) :: noise_model
        !> Highest order of the stabilisation diagram (modes), 1 to max_lsce_modes.
        integer, intent(in) :: max_order
        !> The identification (modes, sigma_frequency [Hz], sigma_damping, determined, ...).
        type(ml_result), intent(out) :: result
        !> Set for a file that cannot be read or bad settings (`stat_input`), a failed fit (`stat_numerical`).
        type(error_type), allocatable, intent(out) :: error

        type(frf_type) :: frf
        type(ml_options) :: options

        if (max_order < 1 .or. max_order > max_lsce_modes) then
            call fatal_error(error, 'max_order = '//int_text(max_order)//': expected a number of modes from 1 to ' &
                             //int_text(max_lsce_modes))
            return
        end if
        call read_frf(path, frf, error)
        if (allocated(error)) return
        options%noise_model = lower_text(noise_model)
        options%max_order = max_order
        call identify_ml(frf, options, result, error)
    end subroutine identify_file_ml

    !> A receptance file read, and the LSCE settings its identification runs with.
    subroutine read_receptance(path, tol_e, max_modes, frf, options, error)
        character(len=*), intent(in) :: path
        real(dp), intent(in) :: tol_e
        integer, intent(in) :: max_modes
        type(frf_type), intent(out) :: frf
        type(lsce_options), intent(out) :: options
        type(error_type), allocatable, intent(out) :: error

        ! Capped as in scenes: the LSCE companion matrix is 2N x 2N, and a huge N overflows its sizes.
        if (max_modes < 1 .or. max_modes > max_lsce_modes) then
            call fatal_error(error, 'max_modes = '//int_text(max_modes)//': expected a number of modes from 1 to ' &
                             //int_text(max_lsce_modes))
            return
        end if
        call read_frf(path, frf, error)
        options%tol_e = tol_e
        options%max_modes = max_modes
    end subroutine read_receptance

end module greenconv_api_handle
