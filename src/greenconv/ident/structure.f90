!> The structure of a scene as the convolution methods need it: the exact modes when they
!> are known (an sdof, the random modes of section 3.2), the impulse response sampled at the
!> scene's time step when only G is known (an FRF file), and the modes the modal method
!> uses, which are either the exact ones or an LSCE fit of G.
!>
!> Library callers build one without a scene: `structure_from_modes` (known modes),
!> `structure_from_frf` (a sampled G: LSCE modes and g by inverse FFT; the uniform grid from
!> 0 Hz only), `structure_from_frf_ml` (the maximum-likelihood fit of greenconv_ident_mlfit,
!> for measured G on any increasing grid: g by inverse FFT on the uniform grid from 0 Hz,
!> else sampled from the identified modes) or `structure_from_samples` (g sampled at the time
!> step: `direct` and `fft` only).
module greenconv_ident_structure
    use greenconv_core_kinds, only: dp
    use greenconv_core_error, only: error_type, fatal_error
    use greenconv_core_text, only: sci_text, int_text
    use greenconv_model_modal_set, only: modal_set, sorted_by_frequency
    use greenconv_model_frf, only: frf_type
    use greenconv_ident_lsce, only: lsce_options, lsce_result, identify, impulse_from_frf
    use greenconv_ident_mlfit, only: ml_options, ml_result, identify_ml
    use greenconv_ident_methods, only: ident_none, ident_lsce, ident_ml, ident_one_receptance, default_ident_method, &
                                       ident_scheme
    implicit none
    private

    public :: structure_model, structure_from_modes, structure_from_frf, structure_from_samples
    public :: structure_from_frf_ml, structure_from_receptance
    public :: receptance_identification, identify_receptance

    !> g sampled from modes reaches until the modal envelope has fallen to this fraction of its
    !> value at t = 0 (far below any truncation a run asks, 1e-2 in the paper) ...
    real(dp), parameter :: modal_g_decay = 1.0e-8_dp
    !> ... or this many samples (32 MB), whichever comes first.
    integer, parameter :: max_modal_g = 4194304

    !> A structure ready for the convolvers.
    type :: structure_model
        !> Whether the exact modes are known.
        logical :: has_exact = .false.
        !> The structure's own modes (when `has_exact`).
        type(modal_set) :: exact
        !> Impulse response g(t_n) [m/(N*s)] at the scene's time step, n = 0.. (when not `has_exact`).
        real(dp), allocatable :: sampled_g(:)
        !> Time step [s] at which `sampled_g` was sampled from a receptance (0 when the caller
        !> gave the samples: the step is then the one given to the convolvers).
        real(dp) :: sampled_step = 0.0_dp
        !> Relative error of `sampled_g` from what the inverse FFT leaves out above f_max,
        !> 2*int_{f_max}^inf |G| df / max|g|, when G is known there (a closed form); < 0 unknown
        !> (then estimated from the identified modes).
        real(dp) :: band_error = -1.0_dp
        !> The modes the modal methods use.
        type(modal_set) :: model
        !> Whether `model` comes from a fit of G (then `frf`, `method` and `fit` or `ml` are set).
        logical :: identified = .false.
        !> The sampled receptance that was identified.
        type(frf_type) :: frf
        !> The identification used, a scheme of greenconv_ident_methods: `ident_lsce` (`fit`) or
        !> `ident_ml` (`ml`); `ident_none` when not identified.
        integer :: method = ident_none
        !> The LSCE identification (method 'lsce'): order, E of eq. (7), warnings.
        type(lsce_result) :: fit
        !> The maximum-likelihood identification (method 'ml'): modes with their standard
        !> deviations, noise level, stabilisation diagram, dropped modes, E of eq. (7).
        type(ml_result) :: ml
        !> CPU time of the identification [s].
        real(dp) :: cpu_time = 0.0_dp
    contains
        !> E of eq. (7) of the identified model (1 when not identified).
        procedure :: fit_e => structure_fit_e
        !> The identification in one phrase for a method's summary line ('' when not identified).
        procedure :: fit_brief => structure_fit_brief
        !> The identification's warnings, '; '-separated ('' when none or not identified).
        procedure :: fit_warnings => structure_fit_warnings
        !> Receptance [m/N] of the identified model, residual terms included, at omega [rad/s].
        procedure :: fitted => structure_fitted
    end type structure_model

    !> How one measured receptance is identified, by a scene's `frf_file` model and by the C and
    !> Fortran 77 doors alike: a method of the identification registry (greenconv_ident_methods)
    !> and its settings, with the defaults of a scene's `&identification` group.
    type :: receptance_identification
        !> The method's scheme: `ident_ml` or `ident_lsce` (`ident_none`: the registry's default
        !> for a measured receptance, `default_ident_method`).
        integer :: scheme = ident_none
        !> Largest order (number of modes) the order search tries (ml: the diagram's top; lsce:
        !> its scan), >= 1.
        integer :: max_order = 30
        !> lsce: the order fixed (0: the smallest model with E <= tol_e).
        integer :: order = 0
        !> lsce: the target of the error E of eq. (7), > 0.
        real(dp) :: tol_e = 1.0e-6_dp
        !> ml: the noise model, 'auto' (chosen from the data), 'relative', 'absolute', 'floor' or 'band'.
        character(len=16) :: noise_model = 'auto'
        !> ml: the global order search (greedy rounds, death moves, projected fits), or the
        !> greedy rounds alone.
        logical :: global_search = .true.
    end type receptance_identification

contains

    !> A structure known by a measured receptance, identified as `settings` say: by maximum
    !> likelihood (`structure_from_frf_ml`) or by LSCE (`structure_from_frf`); g at dt when
    !> dt > 0.
    subroutine identify_receptance(frf, settings, dt, structure, error)
        !> The receptance G [m/N].
        type(frf_type), intent(in) :: frf
        !> The method and its settings.
        type(receptance_identification), intent(in) :: settings
        !> Time step [s] of the convolvers; 0 for the modes alone.
        real(dp), intent(in) :: dt
        !> The structure.
        type(structure_model), intent(out) :: structure
        !> Set when the identification fails or dt does not fit the grid.
        type(error_type), allocatable, intent(out) :: error

        type(ml_options) :: ml
        type(lsce_options) :: lsce
        integer :: scheme

        scheme = settings%scheme
        if (scheme == ident_none) scheme = ident_scheme(default_ident_method(ident_one_receptance, .true.))
        if (scheme == ident_ml) then
            ml%max_order = settings%max_order
            ml%noise_model = settings%noise_model
            ml%global_search = settings%global_search
            call structure_from_frf_ml(frf, ml, dt, structure, error)
        else
            lsce%tol_e = settings%tol_e
            lsce%max_modes = settings%max_order
            lsce%fixed_modes = settings%order
            call structure_from_frf(frf, lsce, dt, structure, error)
        end if
    end subroutine identify_receptance

    !> A structure known by its modes, used as they are by the modal methods.
    function structure_from_modes(modes) result(structure)
        !> The modes.
        type(modal_set), intent(in) :: modes
        type(structure_model) :: structure

        structure%has_exact = .true.
        structure%exact = modes
        structure%model = modes
    end function structure_from_modes

    !> A structure known only by its impulse response sampled at the time step of the run:
    !> `direct` and `fft` convolve with it (truncated by the paper's rule); it has no modes.
    pure function structure_from_samples(g) result(structure)
        !> Samples g(n*dt), n = 0..N-1 [m/(N*s)], at the time step dt of the convolvers.
        real(dp), intent(in) :: g(:)
        type(structure_model) :: structure

        allocate (structure%sampled_g(size(g)))
        structure%sampled_g(:) = g
        allocate (structure%model%pole(0), structure%model%residue(0))
    end function structure_from_samples

    !> A structure known by its sampled receptance G: modes fitted by LSCE (`identify`) for
    !> the modal methods and, when dt > 0, g sampled at dt from the inverse FFT of G for
    !> `direct` and `fft` (dt must then be a whole multiple of 1/(2*f_max)). Both need the
    !> uniform grid from 0 Hz; another grid is refused (status 2) naming the line, with the
    !> way out: the maximum-likelihood fit (`structure_from_frf_ml`, `method = 'ml'`).
    subroutine structure_from_frf(frf, options, dt, structure, error)
        !> The receptance G [m/N] on a uniform grid from 0 Hz.
        type(frf_type), intent(in) :: frf
        !> LSCE settings.
        type(lsce_options), intent(in) :: options
        !> Time step [s] of the convolvers (a whole multiple of 1/(2*f_max)); 0 for the modes alone.
        real(dp), intent(in) :: dt
        !> The structure: the LSCE modes and their fit, g when dt > 0.
        type(structure_model), intent(out) :: structure
        !> Set when the grid is not the uniform grid from 0 Hz, the identification fails or dt
        !> does not fit the grid.
        type(error_type), allocatable, intent(out) :: error

        if (.not. frf%uniform_from_zero()) then
            call fatal_error(error, frf%fft_grid_problem()//': the LSCE identification and g by inverse FFT need ' &
                             //'it; use the maximum-likelihood fit (&identification method = ''ml'', the default ' &
                             //'for a file), which takes any increasing grid, or resample G onto that grid')
            return
        end if
        call identify_timed(frf, structure, error, lsce=options)
        if (allocated(error)) return
        if (dt > 0.0_dp) call sample_from_frf(structure%frf, dt, structure, error)
    end subroutine structure_from_frf

    !> A structure known by its sampled receptance G, possibly measured with noise: modes
    !> fitted by maximum likelihood (`identify_ml`: the noise level, the order and each
    !> mode's uncertainty from the data) for the modal methods and, when dt > 0, g sampled
    !> at dt for `direct` and `fft`: on the uniform grid from 0 Hz from the inverse FFT of G,
    !> as `structure_from_frf`; on any other grid (no inverse FFT) from the identified modes
    !> (their residual terms left out: R_u would be an impulse at t = 0, R_l a rigid drift),
    !> until their envelope falls to modal_g_decay of its start, and the fit's warning says so.
    subroutine structure_from_frf_ml(frf, options, dt, structure, error)
        !> The receptance G [m/N] on increasing frequencies >= 0 Hz.
        type(frf_type), intent(in) :: frf
        !> Maximum-likelihood settings.
        type(ml_options), intent(in) :: options
        !> Time step [s] of the convolvers; 0 for the modes alone.
        real(dp), intent(in) :: dt
        !> The structure: the modes with their uncertainty and the fit's diagnostics, g when dt > 0.
        type(structure_model), intent(out) :: structure
        !> Set when the identification fails or, on the uniform grid from 0 Hz, dt is not a whole
        !> multiple of 1/(2*f_max).
        type(error_type), allocatable, intent(out) :: error

        type(frf_type) :: repaired
        integer :: l

        call identify_timed(frf, structure, error, ml=options)
        if (allocated(error)) return
        if (dt <= 0.0_dp) return
        if (.not. frf%uniform_from_zero()) then
            call sample_from_modes(dt, structure)
            return
        end if
        ! g from G with the outlier lines the fit left out replaced by the model's value (one
        ! such line adds an undamped sinusoid to the whole of g).
        repaired = frf
        do l = 1, size(structure%ml%outlier_line)
            associate (line => structure%ml%outlier_line(l))
                repaired%receptance(line) = structure%ml%receptance(2.0_dp*acos(-1.0_dp)*frf%frequency(line))
            end associate
        end do
        call sample_from_frf(repaired, dt, structure, error)
    end subroutine structure_from_frf_ml

    !> A structure known by its receptance G on the uniform grid from 0 Hz, with no modes: g
    !> sampled at dt from the inverse FFT of G (dt a whole multiple of 1/(2*f_max)), for
    !> `direct` and `fft` alone.
    subroutine structure_from_receptance(frf, dt, structure, error)
        !> The receptance G [m/N] on a uniform grid from 0 Hz.
        type(frf_type), intent(in) :: frf
        !> Time step [s] of the convolvers, > 0.
        real(dp), intent(in) :: dt
        !> The structure: g, no modes.
        type(structure_model), intent(out) :: structure
        !> Set when the grid is not the uniform grid from 0 Hz or dt does not fit it.
        type(error_type), allocatable, intent(out) :: error

        if (.not. frf%uniform_from_zero()) then
            call fatal_error(error, frf%fft_grid_problem()//': g by inverse FFT needs the uniform grid from 0 Hz')
            return
        end if
        structure%frf = frf
        allocate (structure%model%pole(0), structure%model%residue(0))
        call sample_from_frf(frf, dt, structure, error)
    end subroutine structure_from_receptance

    !> The identification of G into a structure, by LSCE (`lsce` given) or by maximum likelihood
    !> (`ml` given), timed: sets frf, fit or ml, method, model (sorted by frequency), identified
    !> and cpu_time.
    subroutine identify_timed(frf, structure, error, lsce, ml)
        !> The receptance G [m/N].
        type(frf_type), intent(in) :: frf
        !> The structure to fill.
        type(structure_model), intent(inout) :: structure
        !> Set when the identification fails.
        type(error_type), allocatable, intent(out) :: error
        !> LSCE settings (LSCE fit).
        type(lsce_options), intent(in), optional :: lsce
        !> Maximum-likelihood settings (ML fit, when lsce is absent).
        type(ml_options), intent(in), optional :: ml

        real(dp) :: start, finish

        structure%frf = frf
        call cpu_time(start)
        if (present(lsce)) then
            call identify(structure%frf, lsce, structure%fit, error)
        else
            call identify_ml(structure%frf, ml, structure%ml, error)
        end if
        if (allocated(error)) return
        call cpu_time(finish)
        structure%cpu_time = finish - start
        if (present(lsce)) then
            structure%method = ident_lsce
            structure%model = sorted_by_frequency(structure%fit%modes)
        else
            structure%method = ident_ml
            structure%model = structure%ml%modes
        end if
        structure%identified = .true.
    end subroutine identify_timed

    !> E of eq. (7) of the identified model; 1 when the structure was not identified.
    elemental real(dp) function structure_fit_e(self)
        !> The structure.
        class(structure_model), intent(in) :: self

        select case (self%method)
        case (ident_lsce)
            structure_fit_e = self%fit%e
        case (ident_ml)
            structure_fit_e = self%ml%e
        case default
            structure_fit_e = 1.0_dp
        end select
    end function structure_fit_e

    !> The identification in one phrase, e.g. "ML fit of G: 12 modes (order by MDL), noise 1.01E-02
    !> of |G| (estimated from the data), worst sigma_f/f = 1.26E-04, worst sigma_xi/xi = 1.75E-02,
    !> E = 8.95E-03 (eq. 7)" or "LSCE fit of G: E = 1.00E-06 (eq. 7)"; '' when not identified.
    pure subroutine structure_fit_brief(self, text)
        !> The structure.
        class(structure_model), intent(in) :: self
        !> The phrase.
        character(len=:), allocatable, intent(out) :: text

        select case (self%method)
        case (ident_lsce)
            text = 'LSCE fit of G: E = '//sci_text(self%fit%e)//' (eq. 7)'
        case (ident_ml)
            call self%ml%brief(text)
            text = 'ML fit of G: '//text//', E = '//sci_text(self%ml%e)//' (eq. 7)'
        case default
            text = ''
        end select
    end subroutine structure_fit_brief

    !> The identification's warnings (wrap-around, a fit that missed its target, dropped
    !> poles, modes sampled short), '; '-separated; '' when there are none or G was not identified.
    pure subroutine structure_fit_warnings(self, text)
        !> The structure.
        class(structure_model), intent(in) :: self
        !> The warnings.
        character(len=:), allocatable, intent(out) :: text

        text = ''
        select case (self%method)
        case (ident_lsce)
            if (allocated(self%fit%warning)) text = self%fit%warning
        case (ident_ml)
            if (allocated(self%ml%warning)) text = self%ml%warning
        end select
    end subroutine structure_fit_warnings

    !> Receptance of the identified model [m/N] at omega [rad/s] (0 when not identified).
    elemental complex(dp) function structure_fitted(self, omega)
        !> The structure.
        class(structure_model), intent(in) :: self
        !> Angular frequency [rad/s].
        real(dp), intent(in) :: omega

        select case (self%method)
        case (ident_lsce)
            structure_fitted = self%fit%receptance(omega)
        case (ident_ml)
            structure_fitted = self%ml%receptance(omega)
        case default
            structure_fitted = (0.0_dp, 0.0_dp)
        end select
    end function structure_fitted

    !> g at the time step dt from the identified modes (a receptance off the uniform grid from
    !> 0 Hz): t_j = j*dt until the modal envelope falls to modal_g_decay of its value at 0, the
    !> slowest mode deciding (at most max_modal_g samples; what is left then is in the warning).
    subroutine sample_from_modes(dt, structure)
        real(dp), intent(in) :: dt
        type(structure_model), intent(inout) :: structure

        character(len=:), allocatable :: note
        real(dp) :: decay, span, left
        integer :: n, j

        associate (modes => structure%model, ml => structure%ml)
            n = 2
            if (modes%n_modes() > 0) then
                decay = minval(-real(modes%pole, dp))
                span = huge(1.0_dp)
                if (decay > 0.0_dp) span = log(1.0_dp/modal_g_decay)/decay
                n = int(min(span/dt + 2.0_dp, real(max_modal_g, dp)))
            end if
            structure%sampled_g = [(0.0_dp, j=1, n)]
            if (modes%n_modes() > 0) structure%sampled_g = modes%impulse([(j*dt, j=0, n - 1)])
            structure%sampled_step = dt
            note = 'the grid is not the uniform grid from 0 Hz ('//structure%frf%fft_grid_problem()//'): g for ' &
                   //'direct and fft is sampled from the '//int_text(modes%n_modes())//' identified modes (' &
                   //int_text(n)//' samples), the residual terms left out, not by inverse FFT of G'
            if (modes%n_modes() > 0) then
                left = modes%envelope((n - 1)*dt)/modes%envelope(0.0_dp)
                if (left > 2.0_dp*modal_g_decay) note = note//'; cut at '//int_text(max_modal_g) &
                                                         //' samples, the modal envelope still at '//sci_text(left) &
                                                         //' of its start'
            end if
            if (len(ml%warning) > 0) ml%warning = ml%warning//'; '
            ml%warning = ml%warning//note
        end associate
    end subroutine sample_from_modes

    !> g at the time step dt from a receptance: the inverse FFT gives it at 1/(2*f_max); dt must
    !> be that step or a whole multiple of it.
    subroutine sample_from_frf(frf, dt, structure, error)
        type(frf_type), intent(in) :: frf
        real(dp), intent(in) :: dt
        type(structure_model), intent(inout) :: structure
        type(error_type), allocatable, intent(out) :: error

        real(dp), allocatable :: g(:)
        real(dp) :: dt_frf
        integer :: stride
        character(len=64) :: text

        call impulse_from_frf(frf, g, dt_frf, error)
        if (allocated(error)) return
        stride = nint(dt/dt_frf)
        if (stride < 1 .or. abs(stride*dt_frf - dt) > 1.0e-9_dp*dt) then
            write (text, '(es12.5)') dt_frf
            call fatal_error(error, 'time step dt: expected a whole multiple of '//trim(adjustl(text)) &
                             //' s, the step of g from the FRF (1/(2*f) at its last line f)')
            return
        end if
        ! Only the first half of the period 1/df: the second half holds the wrapped end of g.
        structure%sampled_g = g(1:size(g)/2:stride)
        structure%sampled_step = dt
    end subroutine sample_from_frf

end module greenconv_ident_structure
