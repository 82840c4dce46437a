!> The one place convolvers are built, single- and multi-point alike, from a method name of
!> the registry (greenconv_conv_methods): the registry says whether the method can run on the
!> structure, this module calls the engine's constructor and says in words what the model
!> neglects.
!>
!> - `new_convolver`: a single-point convolver from a `structure_model`, its inputs checked
!>   (what the library and both APIs call);
!> - `make_convolver`: the same without the value checks (the scene runner, whose scene was
!>   checked when it was read);
!> - `make_multipoint_convolver`: a multi-point convolver (a Green's matrix) from modes and
!>   mode shapes at the contact points;
!> - `table_convolver`: a multi-point `direct` or `fft` convolver on a table g_ij(t_m) (from a
!>   file, or given by a caller), truncated by the paper's rule.
!>
!> Methods are never told apart here: greenconv_conv_engines's `engine_of` gives a method's
!> constructors (on the sampled g or on modes, single- or multi-point) and whether it picks
!> another method (`auto`), and this module calls what it gives.
module greenconv_conv_builder
    use, intrinsic :: iso_fortran_env, only: int64
    use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
    use greenconv_core_kinds, only: dp
    use greenconv_core_text, only: int_text, sci_text
    use greenconv_core_error, only: error_type, fatal_error
    use greenconv_model_modal_set, only: modal_set
    use greenconv_model_point_modes, only: point_modes
    use greenconv_ident_structure, only: structure_model
    use greenconv_ident_methods, only: ident_ml
    use greenconv_conv_methods, only: default_truncation_tol, default_accuracy, method_needs, needs_sampled_g, &
                                       needs_modes, check_method
    use greenconv_conv_convolver, only: convolver
    use greenconv_conv_kernel, only: sample_kernel, truncation_length, period_end_level, beyond_nyquist
    use greenconv_conv_multipoint, only: multipoint_convolver, sample_green_matrix
    use greenconv_conv_engines, only: engine_constructors, engine_of
    implicit none
    private

    public :: new_convolver, make_convolver, make_multipoint_convolver, table_convolver
    public :: max_kernel_values, check_kernel_values

    !> Largest number of stored values of a sampled kernel: N_g*N_c^2 weights and 2*N_g*N_c
    !> past forces (10^8 values: 0.8 GB at 8 bytes each). The peak while a convolver is built
    !> is larger (doc/reliability.md, measured with /usr/bin/time -v on one point): about 18
    !> bytes per value for `direct` (the samples are held twice while the kernel is cut) and
    !> 34 for `fft` (the partition spectra, complex, and their delay lines), so 10^8 values
    !> peak at about 1.8 GB (`direct`) and 3.4 GB (`fft`).
    integer, parameter :: max_kernel_values = 100000000

    !> `auto` runs the direct sum when N_t*N_g is at most this many multiply-adds (about
    !> 2 ms at the measured 6-7 GMAC/s): then no model is worth building.
    real(dp), parameter :: direct_work_limit = 1.0e7_dp

contains

    !> Build the convolver called `method` for a structure, after checking the inputs and
    !> that the method can run on it (greenconv_conv_methods's `check_method`: `direct` and
    !> `fft` need g, exact modes or g sampled at dt; the modal methods need modes; `auto`
    !> needs both). See `make_convolver` for what each method computes.
    subroutine new_convolver(method, structure, dt, n_steps, conv, error, truncation_tol, accuracy, description, &
                             estimate, chosen)
        !> Method, one of greenconv_conv_methods's `method_list()`.
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
        !> Truncation fraction of max |g| for `direct` and `fft`, in (0, 1); default `default_truncation_tol`.
        real(dp), intent(in), optional :: truncation_tol
        !> Relative accuracy `auto` must meet, > 0; default `default_accuracy`.
        real(dp), intent(in), optional :: accuracy
        !> What the model neglects, in words (and, for `auto`, what it chose and why).
        character(len=:), allocatable, intent(out), optional :: description
        !> The method's own estimate of its relative error [-] (see `make_convolver`).
        real(dp), intent(out), optional :: estimate
        !> The method built: `method` itself, or the one `auto` chose.
        character(len=:), allocatable, intent(out), optional :: chosen

        character(len=:), allocatable :: text, built
        real(dp) :: tol, requested

        tol = default_truncation_tol
        if (present(truncation_tol)) tol = truncation_tol
        requested = default_accuracy
        if (present(accuracy)) requested = accuracy
        call check_request(method, structure, dt, n_steps, tol, requested, error)
        if (allocated(error)) return
        call make_convolver(method, structure, dt, tol, n_steps, conv, text, error, requested, estimate, built)
        if (allocated(error)) return
        if (present(description)) description = text
        if (present(chosen)) chosen = built
    end subroutine new_convolver

    !> Refuse (`stat_input`) a sampled kernel larger than `max_kernel_values`: a `direct` or
    !> `fft` convolver stores N_g*N_c^2 + 2*N_g*N_c values, with N_g estimated from the slowest
    !> decay rate (the envelope exp(-sigma*t) falls to tol by t = ln(1/tol)/sigma, and the
    !> kernel never exceeds the run's N_t samples), counted as a real so that absurd sizes do
    !> not overflow. The one cap check of scenes (greenconv_scene_read_input) and of every door.
    subroutine check_kernel_values(method, decay_rate, dt, tol, n_steps, n_points, error)
        !> Method name (lower case): nothing is checked for one that needs no sampled g.
        character(len=*), intent(in) :: method
        !> Slowest modal decay rate sigma = min xi_k*omega_k [1/s] (0: no decay).
        real(dp), intent(in) :: decay_rate
        !> Time step [s].
        real(dp), intent(in) :: dt
        !> Truncation fraction of max |g|, in (0, 1).
        real(dp), intent(in) :: tol
        !> Number of steps N_t.
        integer, intent(in) :: n_steps
        !> Number of contact points N_c.
        integer, intent(in) :: n_points
        !> Set (`stat_input`) above the cap, with the estimate and the remedies.
        type(error_type), allocatable, intent(out) :: error

        real(dp) :: n_g, values

        if (.not. method_needs(method, needs_sampled_g)) return
        n_g = real(n_steps, dp)
        if (decay_rate > 0.0_dp) n_g = min(n_g, log(1.0_dp/tol)/(decay_rate*dt) + 1.0_dp)
        values = n_g*real(n_points, dp)**2 + 2.0_dp*n_g*n_points
        if (values <= max_kernel_values) return
        call fatal_error(error, 'method '''//method//''': expected a sampled kernel (direct, fft, auto) of at most ' &
                         //sci_text(real(max_kernel_values, dp))//' values (8 bytes each), found ' &
                         //sci_text(values)//' values (N_t = '//int_text(n_steps)//', slowest decay rate ' &
                         //sci_text(decay_rate)//' 1/s): use fewer steps, a larger dt or truncation_tol, ' &
                         //'or a modal method (modal, exact)')
    end subroutine check_kernel_values

    !> Reject a request `make_convolver` cannot serve, the message starting "new_convolver: ".
    subroutine check_request(method, structure, dt, n_steps, tol, requested, error)
        character(len=*), intent(in) :: method
        type(structure_model), intent(in) :: structure
        real(dp), intent(in) :: dt, tol, requested
        integer, intent(in) :: n_steps
        type(error_type), allocatable, intent(out) :: error

        if (.not. (dt > 0.0_dp .and. ieee_is_finite(dt))) then
            call fatal_error(error, 'new_convolver: the time step dt must be finite and > 0 s')
        else if (n_steps < 1) then
            call fatal_error(error, 'new_convolver: the number of steps must be >= 1')
        else if (.not. (tol > 0.0_dp .and. tol < 1.0_dp)) then
            call fatal_error(error, 'new_convolver: truncation_tol must be in (0, 1)')
        else if (.not. (requested > 0.0_dp)) then
            call fatal_error(error, 'new_convolver: accuracy must be > 0')
        else
            call check_structure_method(method, structure, error)
            if (allocated(error)) then
                error%message = 'new_convolver: '//error%message
                return
            end if
            call check_modes(structure%model, error)
            if (.not. allocated(error) .and. structure%has_exact) call check_modes(structure%exact, error)
            if (.not. allocated(error) .and. structure%has_exact) then
                call check_kernel_values(method, structure%exact%slowest_decay(), dt, tol, n_steps, 1, error)
                if (allocated(error)) error%message = 'new_convolver: '//error%message
            end if
        end if
    end subroutine check_request

    !> The registry's check of a single-point method on what a structure has (g, modes).
    subroutine check_structure_method(method, structure, error)
        character(len=*), intent(in) :: method
        type(structure_model), intent(in) :: structure
        type(error_type), allocatable, intent(out) :: error

        logical :: has_g

        has_g = structure%has_exact
        if (allocated(structure%sampled_g)) has_g = has_g .or. size(structure%sampled_g) >= 2
        call check_method(method, .false., has_g, structure%model%n_modes() > 0, error)
    end subroutine check_structure_method

    !> Modes a caller gives (structure_from_modes) must be those of a passive structure:
    !> finite poles with Re lambda <= 0 (0: undamped, xi = 0, as the driver accepts) and
    !> Im lambda > 0, finite residues.
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
                else if (.not. (real(pole, dp) <= 0.0_dp .and. aimag(pole) > 0.0_dp)) then
                    call fatal_error(error, 'new_convolver: mode '//int_text(k)//': expected a pole with ' &
                                     //'Re lambda <= 0 and Im lambda > 0 rad/s (a damped or undamped mode), ' &
                                     //'found lambda = (' &
                                     //sci_text(real(pole, dp))//', '//sci_text(aimag(pole))//') rad/s')
                end if
            end associate
            if (allocated(error)) return
        end do
    end subroutine check_modes

    !> Build the convolver called `method` for a structure. The registry checks that the
    !> method is known and serves single-point contact; whether the structure has what the
    !> method needs (g, modes) and the values dt, n_steps and truncation_tol are the caller's
    !> to check, as `new_convolver` does.
    !>
    !> `direct` convolves with the structure's own g (from its exact modes, or sampled from
    !> its FRF), truncated by the paper's rule; `fft` computes the same sum by partitioned FFT.
    !> The modal methods recur on the structure's model modes: `paper` (eqs. 15-17 as
    !> written), `recursive` (the same sum with decaying factors), `exact` (force linear
    !> within a step) and `backward` (force constant over the step ending at its sample, first
    !> order, for the implicit step of stiff contacts); `modal` is `recursive`. `auto` picks
    !> the cheapest of these that meets `requested` (see `choose_method`; never `backward`).
    !> `accuracy` says in words how far the model is from the exact g (and, for `auto`, what it
    !> chose and why).
    subroutine make_convolver(method, structure, dt, truncation_tol, n_steps, conv, accuracy, error, requested, &
                              estimate, chosen_method)
        !> Method, one of greenconv_conv_methods's `method_list()`.
        character(len=*), intent(in) :: method
        !> The structure.
        type(structure_model), intent(in) :: structure
        !> Time step [s].
        real(dp), intent(in) :: dt
        !> Truncation fraction of max |g| for `direct`.
        real(dp), intent(in) :: truncation_tol
        !> Number of steps of the run.
        integer, intent(in) :: n_steps
        !> The convolver.
        class(convolver), allocatable, intent(out) :: conv
        !> What the model neglects, in words.
        character(len=:), allocatable, intent(out) :: accuracy
        !> Set for a method the registry does not know or that does not serve single-point contact.
        type(error_type), allocatable, intent(out) :: error
        !> Relative accuracy `auto` must meet (default `default_accuracy`): the largest E (eq. 7) it accepts.
        real(dp), intent(in), optional :: requested
        !> The method's own estimate of its relative error, to compare with an accuracy asked
        !> (see `build_method`); 0 when nothing beyond the truncation asked is neglected.
        real(dp), intent(out), optional :: estimate
        !> The method built: `method` itself, or the one `auto` chose.
        character(len=:), allocatable, intent(out), optional :: chosen_method

        character(len=:), allocatable :: chosen, reason, brief
        type(engine_constructors) :: engine
        real(dp) :: target, own

        ! What the structure has is the caller's to check (`new_convolver` does; a scene's
        ! structures all have g and modes, the modes an LSCE fit may have left empty).
        call check_method(method, .false., .true., .true., error)
        if (allocated(error)) return
        call check_sample_step(structure, dt, error)
        if (allocated(error)) return
        call check_wrapped_g(method, structure, error)
        if (allocated(error)) return
        engine = engine_of(method)
        if (.not. engine%chooses) then
            call build_method(method, structure, dt, truncation_tol, n_steps, conv, accuracy, own)
            if (present(estimate)) estimate = own
            if (present(chosen_method)) chosen_method = method
            return
        end if
        target = default_accuracy
        if (present(requested)) target = requested
        call choose_method(structure, dt, truncation_tol, n_steps, target, chosen, reason)
        call build_method(chosen, structure, dt, truncation_tol, n_steps, conv, accuracy, own)
        if (present(estimate)) estimate = own
        if (present(chosen_method)) chosen_method = chosen
        conv%name = 'auto'
        ! A kernel method on an identified structure: the identification is quoted all the same.
        if (structure%identified .and. .not. method_needs(chosen, needs_modes)) then
            call structure%fit_brief(brief)
            accuracy = accuracy//'; '//brief
        end if
        accuracy = 'chose '//chosen//': '//reason//'; '//accuracy
    end subroutine make_convolver

    !> The cheapest method whose model meets a requested accuracy, and why, in words:
    !> - `direct` when N_t*N_g is at most `direct_work_limit` (the run costs a few ms and
    !>   its only approximation is the truncation of g) and its g's own error estimate
    !>   (`kernel_estimate`: wrap-around, or g sampled from an identified model) meets the accuracy;
    !> - otherwise `exact` (the first-order hold: a modal recursion's cost, second order in
    !>   dt, the static gain exact) on the structure's modes when they are its own, or on the
    !>   identified model when its E (eq. 7) meets the accuracy; the identification scan
    !>   stops at the smallest such order;
    !> - otherwise `fft` on the sampled g: no modal model up to the scan's largest order does.
    subroutine choose_method(structure, dt, truncation_tol, n_steps, requested, chosen, reason)
        type(structure_model), intent(in) :: structure
        real(dp), intent(in) :: dt, truncation_tol, requested
        integer, intent(in) :: n_steps
        character(len=:), allocatable, intent(out) :: chosen, reason

        real(dp), allocatable :: kernel(:)
        real(dp) :: tail, work

        call direct_kernel(structure, dt, truncation_tol, n_steps, kernel, tail)
        work = real(n_steps, dp)*(size(kernel) - 1)
        if (wrapped_g(structure)) then
            chosen = 'exact'
            reason = 'g by FFT of the receptance wraps around (not decayed within 1/df), so not direct or fft; '// &
                     int_text(structure%model%n_modes())//' LSCE modes, E = '//sci_text(structure%fit%e)
        else if (work <= direct_work_limit .and. kernel_estimate(structure) <= requested) then
            chosen = 'direct'
            reason = 'N_t*N_g = '//sci_text(work)//' <= '//sci_text(direct_work_limit)//' multiply-adds'
        else if (.not. structure%identified) then
            chosen = 'exact'
            reason = 'N_t*N_g = '//sci_text(work)//' and the '//int_text(structure%model%n_modes()) &
                     //' modes are the structure''s own'
        else if (structure%fit_e() <= requested .and. structure%method == ident_ml) then
            chosen = 'exact'
            reason = 'the maximum-likelihood model''s E <= '//sci_text(requested)//' (N_t*N_g = '//sci_text(work)//')'
        else if (structure%fit_e() <= requested) then
            chosen = 'exact'
            reason = int_text(structure%model%n_modes())//' modes, the smallest LSCE model with E <= ' &
                     //sci_text(requested)//' (N_t*N_g = '//sci_text(work)//')'
        else
            chosen = 'fft'
            reason = 'no '//trim(merge('ML  ', 'LSCE', structure%method == ident_ml))//' model meets E <= ' &
                     //sci_text(requested)//' (best E = '//sci_text(structure%fit_e())//'), N_t*N_g = '//sci_text(work)
        end if
    end subroutine choose_method

    !> Build one method the registry accepted for this structure (not `auto`).
    !> Its error estimate: E (eq. 7) of an identified model for the modal methods (0 on the
    !> structure's own modes), `kernel_estimate` for `direct` and `fft` (the truncation is the
    !> one `truncation_tol` asks, and not counted).
    subroutine build_method(method, structure, dt, truncation_tol, n_steps, conv, accuracy, estimate)
        character(len=*), intent(in) :: method
        type(structure_model), intent(in) :: structure
        real(dp), intent(in) :: dt
        real(dp), intent(in) :: truncation_tol
        integer, intent(in) :: n_steps
        class(convolver), allocatable, intent(out) :: conv
        character(len=:), allocatable, intent(out) :: accuracy
        real(dp), intent(out) :: estimate

        type(engine_constructors) :: engine
        real(dp), allocatable :: kernel(:)
        real(dp) :: tail, misfit
        integer(int64) :: valid
        integer :: j

        engine = engine_of(method)
        if (engine%samples_g()) then
            call direct_kernel(structure, dt, truncation_tol, n_steps, kernel, tail)
            valid = kernel_validity(size(kernel) - 1, n_steps)
            call engine%on_kernel(kernel, dt, valid, conv)
            accuracy = 'exact: the kernel covers the whole run'
            if (tail > 0.0_dp) accuracy = 'neglected tail <= '//sci_text(tail)//' of max|g|'
            if (structure%identified .and. .not. structure%has_exact) then
                if (.not. structure%frf%uniform_from_zero()) then
                    ! No inverse FFT on this grid: g is the modes' own (structure_from_frf_ml).
                    accuracy = accuracy//'; g sampled from the '//int_text(structure%model%n_modes()) &
                               //' identified modes (the grid has no inverse FFT), their residual terms left out, E = ' &
                               //sci_text(structure%fit_e())//' (eq. 7)'
                else
                    misfit = maxval(abs(kernel - structure%model%impulse([(j*dt, j=0, size(kernel) - 1)])))
                    accuracy = accuracy//'; g by FFT of the band-limited G is off the identified modes'' g by ' &
                               //sci_text(misfit/maxval(abs(kernel)))//' of max|g|'
                end if
            end if
            estimate = kernel_estimate(structure)
        else
            call engine%on_modes(structure%model, dt, conv)
        end if
        if (method_needs(method, needs_modes)) then
            accuracy = 'exact: the modes are the structure''s own'
            estimate = 0.0_dp
            if (structure%identified) call structure%fit_brief(accuracy)
            if (structure%identified) estimate = structure%fit_e()
        end if
    end subroutine build_method

    !> The own error estimate of a kernel of the structure's g, relative to max|g|: 0 for g
    !> from its exact modes; E (eq. 7) of the identified modes when g was sampled from them
    !> (a grid with no inverse FFT); else, g being the inverse FFT of the receptance, the
    !> larger of how much of it is left at the end of the samples it has (half the period
    !> 1/df: a cut there, or wrap-around; greenconv_conv_kernel's `period_end_level`) and what
    !> the spectrum above the Nyquist frequency of its step leaves out (`band_error` when the
    !> structure knows G there, else `beyond_nyquist` from the identified modes).
    real(dp) function kernel_estimate(structure) result(estimate)
        type(structure_model), intent(in) :: structure

        estimate = 0.0_dp
        if (structure%has_exact .or. .not. allocated(structure%sampled_g)) return
        if (structure%band_error >= 0.0_dp .and. structure%sampled_step > 0.0_dp) then
            ! G known above f_max (a closed form): no model needed for what the band leaves out
            estimate = max(period_end_level(structure%sampled_g), structure%band_error)
            return
        end if
        if (.not. structure%identified) return
        if (.not. structure%frf%uniform_from_zero()) then
            estimate = structure%fit_e()
        else if (structure%sampled_step > 0.0_dp) then
            estimate = max(period_end_level(structure%sampled_g), &
                           beyond_nyquist(structure%model, structure%sampled_step, maxval(abs(structure%sampled_g))))
        end if
    end function kernel_estimate

    !> g sampled from a receptance reaches the convolvers by one route: the structure records
    !> the step it was sampled at, and a convolver at any other step is refused (its kernel
    !> would be g at the wrong times).
    subroutine check_sample_step(structure, dt, error)
        type(structure_model), intent(in) :: structure
        real(dp), intent(in) :: dt
        type(error_type), allocatable, intent(out) :: error

        if (structure%has_exact .or. .not. allocated(structure%sampled_g)) return
        if (structure%sampled_step <= 0.0_dp) return
        if (abs(dt - structure%sampled_step) <= 1.0e-9_dp*structure%sampled_step) return
        call fatal_error(error, 'time step dt: expected '//sci_text(structure%sampled_step) &
                         //' s, the step g was sampled at from the receptance, found '//sci_text(dt) &
                         //' s: build the structure with the run''s dt')
    end subroutine check_sample_step

    !> Whether the structure's g is the inverse FFT of a receptance that has not decayed within
    !> the period 1/df of its grid (the identification's wrap-around check): such a g is wrong
    !> (its end wraps onto its start), and a convolution with it wrong by far more than any
    !> accuracy asked (6 to 20 times the response for xi = 1e-5 on a 0.25 Hz grid), while the
    !> modes fitted to G itself are right.
    pure logical function wrapped_g(structure)
        type(structure_model), intent(in) :: structure

        wrapped_g = .false.
        if (structure%has_exact .or. .not. structure%identified) return
        wrapped_g = structure%fit%wrap_around
    end function wrapped_g

    !> Refuse `direct` and `fft` on a wrapped g, and `auto` when there are no modes to fall
    !> back on, saying why and what to do.
    subroutine check_wrapped_g(method, structure, error)
        character(len=*), intent(in) :: method
        type(structure_model), intent(in) :: structure
        type(error_type), allocatable, intent(out) :: error

        character(len=:), allocatable :: why
        type(engine_constructors) :: engine

        if (.not. wrapped_g(structure)) return
        why = 'g from the receptance has not decayed within the period 1/df of its frequency grid (wrap-around: ' &
              //sci_text(structure%fit%tail_level)//' of max|g| left at its end), so a convolution with it is wrong'
        engine = engine_of(method)
        if (engine%samples_g()) then
            call fatal_error(error, 'method '//method//': '//why//': use a modal method (''modal'', ''exact'') on ' &
                             //'the identified modes, or a receptance on a finer frequency grid')
        else if (engine%chooses) then
            if (structure%model%n_modes() == 0) call fatal_error(error, 'method auto: '//why//', and the ' &
                                                                 //'identification kept no modes: give a ' &
                                                                 //'receptance on a finer frequency grid')
        end if
    end subroutine check_wrapped_g

    !> The truncated kernel of the structure's own g and the largest neglected sample.
    subroutine direct_kernel(structure, dt, truncation_tol, n_steps, kernel, tail)
        type(structure_model), intent(in) :: structure
        real(dp), intent(in) :: dt, truncation_tol
        integer, intent(in) :: n_steps
        real(dp), allocatable, intent(out) :: kernel(:)
        real(dp), intent(out) :: tail

        integer :: last, n_g

        if (structure%has_exact) then
            call sample_kernel(structure%exact, dt, truncation_tol, n_steps, kernel, tail)
            return
        end if
        last = min(n_steps, size(structure%sampled_g)) - 1
        n_g = truncation_length(structure%sampled_g(1:last + 1), truncation_tol)
        allocate (kernel(0:n_g))
        kernel(:) = structure%sampled_g(1:n_g + 1)
        tail = 0.0_dp
        if (n_g < last) tail = maxval(abs(structure%sampled_g(n_g + 2:last + 1)))/maxval(abs(kernel))
    end subroutine direct_kernel

    !> Build the multi-point convolver (Green's matrix) called `method` for modes shared by
    !> N_c contact points, after the registry's check that it serves multi-point contact:
    !> `modal`/`recursive` (the rectangle-rule recursion, explicit: W0 = 0), `exact` (the
    !> first-order hold: W0 /= 0, every step solved by Newton on the active set), `direct`
    !> (the sampled table g_ij(t_n), truncated by the paper's rule) and `fft` (the same sum by
    !> partitioned FFT; free it with its `release`, it holds FFTW plans). With `residual`, the
    !> static compliance R of modes left out of `modes` (a modes file's modes above its band,
    !> greenconv_model_modes_file) is part of the structure: those modes respond without lag at
    !> the run's frequencies, an impulse R*delta(t) in g_ij, so R is added to the instant
    !> compliance W0 of the methods that have one (`exact`, `direct`, `fft`); the explicit
    !> `modal` (W0 = 0) cannot take it, and its accuracy says so.
    subroutine make_multipoint_convolver(method, modes, dt, truncation_tol, n_steps, conv, accuracy, error, estimate, &
                                         residual)
        !> Method, one of greenconv_conv_methods's `method_list(multi_point=.true.)`.
        character(len=*), intent(in) :: method
        !> Modes and mode shapes at the points.
        type(point_modes), intent(in) :: modes
        !> Time step [s].
        real(dp), intent(in) :: dt
        !> Truncation fraction of max |g_ij| for `direct` and `fft`.
        real(dp), intent(in) :: truncation_tol
        !> Number of steps of the run (caps the table of `direct` and `fft`).
        integer, intent(in) :: n_steps
        !> The convolver, at step 0.
        class(multipoint_convolver), allocatable, intent(out) :: conv
        !> What the model neglects, in words.
        character(len=:), allocatable, intent(out) :: accuracy
        !> Set for a method that does not serve multi-point contact or modes that do not fit.
        type(error_type), allocatable, intent(out) :: error
        !> Its own error estimate: 0, the modes being the structure's own and the truncation of
        !> `direct` and `fft` the one `truncation_tol` asks.
        real(dp), intent(out), optional :: estimate
        !> Static compliance R_ij [m/N] (N_c x N_c) of the modes left out of `modes`; absent or
        !> unallocated when there are none (allocatable, so that an unallocated one is passed with
        !> a valid descriptor: as a plain optional array gfortran builds it from garbage bounds).
        real(dp), allocatable, intent(in), optional :: residual(:, :)

        type(engine_constructors) :: engine
        real(dp), allocatable :: kernel(:, :, :)
        real(dp) :: tail

        accuracy = ''
        if (present(estimate)) estimate = 0.0_dp
        call check_method(method, .true., modes%modes%n_modes() > 0, modes%modes%n_modes() > 0, error)
        if (allocated(error)) return
        engine = engine_of(method)
        if (engine%samples_g()) then
            call sample_green_matrix(modes, dt, truncation_tol, n_steps, kernel, tail)
            call engine%on_table(kernel, dt, conv, error)
            if (allocated(error)) return
            conv%valid_steps = kernel_validity(ubound(kernel, 1), n_steps)
            accuracy = 'neglected tail <= '//sci_text(tail)//' of max|g_ij|'
        else
            call engine%on_point_modes(modes, dt, conv, error)
            if (allocated(error)) return
            accuracy = 'exact on the model''s modes (explicit step)'
            if (engine%instant_part) accuracy = 'first-order hold, implicit step (Newton, all points)'
        end if
        if (.not. present(residual)) return
        if (.not. allocated(residual)) return
        if (engine%samples_g() .or. engine%instant_part) then
            call conv%set_instant_matrix(conv%weight0 + residual)
            accuracy = accuracy//'; the static compliance of the modes above the band added to W0'
        else
            accuracy = accuracy//'; the static compliance of the modes above the band left out (explicit step)'
        end if
    end subroutine make_multipoint_convolver

    !> `direct` or `fft` on a table g_ij(t_m), truncated by the paper's rule: the last m at
    !> which some |g_ij| reaches tol*max|g| (tol = 0 keeps it all), within the run
    !> (m <= n_steps - 1). With `fitted` (an identified model's g_ij by the same inverse FFT),
    !> the accuracy also says how far the table is from it.
    subroutine table_convolver(method, kernel, dt, tol, n_steps, conv, accuracy, error, fitted)
        !> Method, `direct` or `fft` (the registry's check is the caller's).
        character(len=*), intent(in) :: method
        !> kernel(m, i, j) = g_ij(m*dt) [m/(N*s)], m = 0..N_s-1, N_s >= 2.
        real(dp), intent(in) :: kernel(0:, :, :)
        !> Time step dt [s] of the table and of the run.
        real(dp), intent(in) :: dt
        !> Fraction of max |g_ij| below which the table's tail is cut, in [0, 1).
        real(dp), intent(in) :: tol
        !> Number of steps N_t of the run; the table is never used past it.
        integer, intent(in) :: n_steps
        !> The multi-point convolver on the truncated table, at step 0.
        class(multipoint_convolver), allocatable, intent(out) :: conv
        !> The neglected tail (and the misfit to `fitted`), in words.
        character(len=:), allocatable, intent(out) :: accuracy
        !> Set when the table does not make a convolver.
        type(error_type), allocatable, intent(out) :: error
        !> The identified model's g_ij(m*dt) on the same samples [m/(N*s)].
        real(dp), intent(in), optional :: fitted(0:, :, :)

        type(engine_constructors) :: engine
        real(dp), allocatable :: row_max(:)
        real(dp) :: tail, misfit
        integer :: last, n_g, m

        last = min(ubound(kernel, 1), max(n_steps - 1, 1))
        allocate (row_max(0:last))
        do m = 0, last
            row_max(m) = maxval(abs(kernel(m, :, :)))
        end do
        n_g = truncation_length(row_max, tol)
        tail = 0.0_dp
        if (n_g < last .and. maxval(row_max) > 0.0_dp) tail = maxval(row_max(n_g + 1:))/maxval(row_max)
        engine = engine_of(method)
        call engine%on_table(kernel(0:n_g, :, :), dt, conv, error)
        if (allocated(error)) return
        conv%valid_steps = kernel_validity(n_g, n_steps)
        accuracy = 'neglected tail <= '//sci_text(tail)//' of max|g_ij|'
        if (.not. present(fitted)) return
        misfit = maxval(abs(kernel(0:n_g, :, :) - fitted(0:n_g, :, :)))/maxval(row_max)
        accuracy = accuracy//'; the identified model''s g_ij by the same FFT differs by '//sci_text(misfit) &
                   //' of max|g_ij|'
    end subroutine table_convolver

    !> The steps a kernel of lags 0..N_g covers in a run of n_steps: n_steps when it reaches
    !> the run's end (it was cut there, g not decayed by then), any number (huge) when it ends
    !> before (g decayed, or the samples given end there).
    pure integer(int64) function kernel_validity(n_g, n_steps) result(valid)
        !> Last lag N_g of the kernel.
        integer, intent(in) :: n_g
        !> Number of steps of the run it was made for.
        integer, intent(in) :: n_steps

        valid = huge(valid)
        if (n_g + 1 >= n_steps) valid = n_steps
    end function kernel_validity

end module greenconv_conv_builder
