!> Settings and outcome of the maximum-likelihood identification (greenconv_ident_mlfit, whose
!> description says what each step does): `ml_options`, `ml_result` with its receptance and its
!> summary phrase, the reason codes of a dropped mode and the small helpers that append to a
!> result (a dropped pole, a warning). Every part of the identification fills its own fields.
module greenconv_ident_ml_types
    use greenconv_core_kinds, only: dp
    use greenconv_core_constants, only: two_pi
    use greenconv_core_text, only: int_text, sci_text
    use greenconv_model_modal_set, only: modal_set
    use greenconv_ident_lsce, only: natural_frequency, damping_ratio
    implicit none
    private

    public :: ml_options, ml_result, record_drop, add_warning
    public :: dropped_by_criterion, dropped_left_band, dropped_degenerate, dropped_boundary, max_lines


    !> Most lines identify_ml takes, 2^20 + 1 (a uniform grid from 0 Hz on an FFT of 2^21 points):
    !> its memory and time grow with the lines (the Jacobian holds 2*lines*parameters numbers;
    !> 1,000,001 lines, 3 modes at 1 % noise: 1.3 GB and 57 s CPU, release build).
    integer, parameter :: max_lines = 2**20 + 1
    !> Reason code of a dropped mode: its removal lowered the MDL criterion.
    integer, parameter :: dropped_by_criterion = 1
    !> Reason code of a dropped mode: the fit moved it outside (0, f_max].
    integer, parameter :: dropped_left_band = 2
    !> Reason code of a dropped mode: its Fisher information was singular (e.g. two poles merged).
    integer, parameter :: dropped_degenerate = 3
    !> Reason code of a dropped mode: the fit pushed it to the narrowest band allowed
    !> (narrow_band of a line: a spike on one line, noise or an outlier, not a mode).
    integer, parameter :: dropped_boundary = 4

    !> Settings of identify_ml (every field has a default).
    type :: ml_options
        !> Largest number of modes N of the stabilisation diagram (LSCE order 2N) and of the model.
        !> The diagram goes on beyond it (to at most 2*max_order + stable_orders) only when no pole
        !> has been stable over stable_orders orders by then.
        integer :: max_order = 30
        !> Noise standard deviation per line [m/N] (E|n_l|^2 = sigma_l^2); estimated when not allocated.
        real(dp), allocatable :: sigma(:)
        !> Noise model of the estimate: 'relative' (sigma_l = rho*|G_l|), 'absolute' (sigma_l = sigma),
        !> 'floor' (sigma_l^2 = (rho*|G_l|)^2 + s^2: a measurement's coherence-limited floor s [m/N]
        !> under its relative noise, both estimated from the data), 'band' (sigma_l = rho_b*|G_l|, one
        !> level rho_b per band of lines: a measurement whose noise changes along the band) or 'auto'
        !> (each of 'relative', 'absolute', 'floor' and 'band' fitted, the one of the smallest full
        !> likelihood criterion kept: result%noise_model says which, result%noise_choice why; the
        !> scenes' default, four identifications' time).
        character(len=16) :: noise_model = 'relative'
        !> Smallest noise level, relative to |G_l| (clean data are fitted to round-off above it).
        real(dp) :: noise_floor = 1.0e-13_dp
        !> Residual terms: 'auto' (kept when MDL accepts them), 'none', 'upper', 'lower' or 'both'.
        character(len=8) :: residual_terms = 'auto'
        !> Modes above the band: 'auto' (pseudo-modes, poles above f_max with their residues, kept
        !> when MDL accepts them; the constant R_u alone stands for them otherwise) or 'none'.
        character(len=8) :: outside_modes = 'auto'
        !> Stability across consecutive orders: relative tolerance on the natural frequency.
        real(dp) :: stable_frequency = 0.01_dp
        !> Stability across consecutive orders: relative tolerance on the damping ratio.
        real(dp) :: stable_damping = 0.05_dp
        !> Orders in a row a pole must be stable in f and xi to start the fit.
        integer :: stable_orders = 3
        !> Most impulse samples used by the linear prediction.
        integer :: max_samples = 4096
        !> Most Levenberg-Marquardt iterations per fit.
        integer :: max_iterations = 60
        !> Most modes added or dropped in the order search.
        integer :: max_changes = 40
        !> Global order search: variable projection in the fits of the search, death
        !> moves after its greedy rounds and the final pruning under the final weights
        !> (greenconv_ident_order_search), so that the model is the MDL minimum rather than a
        !> neighbour. Its model is used when its residual is explained by the noise model; when
        !> not, the greedy search runs as well and its model is returned, with a warning
        !> (greenconv_ident_mlfit, step 5). Off: the greedy search alone.
        logical :: global_search = .true.
        !> A mode is reported as under-resolved when its half-power band 2*xi*f holds fewer lines.
        real(dp) :: min_band_lines = 2.0_dp
        !> A line whose weighted residual |G_l - G_model|/sigma_l exceeds this, alone among its
        !> neighbours, is a candidate outlier (left out when MDL prefers that to a mode); 0 turns
        !> the detection off.
        real(dp) :: outlier_sigma = 6.0_dp
        !> Most outlier lines after each of which the noise, the diagram and the search start again
        !> from the repaired receptance (later ones are only left out).
        integer :: outlier_restarts = 4
    end type ml_options

    !> Outcome of identify_ml.
    type :: ml_result
        !> Identified modes sorted by frequency (poles [rad/s], residues [m/(N*s)]).
        type(modal_set) :: modes
        !> Standard deviation of each mode's natural frequency [Hz].
        real(dp), allocatable :: sigma_frequency(:)
        !> Standard deviation of each mode's damping ratio.
        real(dp), allocatable :: sigma_damping(:)
        !> Standard deviation of each residue, sqrt(var Re r + var Im r) [m/(N*s)].
        real(dp), allocatable :: sigma_residue(:)
        !> Upper residual R_u [m/N] (0 unless kept).
        real(dp) :: upper_residual = 0.0_dp
        !> Lower residual R_l [1/kg] of the term -R_l/omega^2 (0 unless kept).
        real(dp) :: lower_residual = 0.0_dp
        !> Pseudo-modes above the band (poles above f_max [rad/s], residues [m/(N*s)]): the modes
        !> past the upper edge the data ask for (outside_modes = 'auto'); part of `receptance`,
        !> not of `modes` (the data do not determine them as modes).
        type(modal_set) :: outside
        !> Whether R_u is part of the model.
        logical :: has_upper = .false.
        !> Whether R_l is part of the model (the 0 Hz line is then left out).
        logical :: has_lower = .false.
        !> Noise level used for the order choice: rho (relative model) or sigma [m/N] (absolute);
        !> 1 when sigma is given (the scale of the given sigma).
        real(dp) :: noise_level = 0.0_dp
        !> Noise level refitted from the final residual, noise_level*sqrt(chi2/nu) (for a given
        !> sigma: the factor the residual asks of it).
        real(dp) :: noise_level_fit = 0.0_dp
        !> Whether the noise level was estimated from the data (not given).
        logical :: noise_estimated = .false.
        !> Noise floor s [m/N] of the 'floor' noise model, estimated with noise_level (0 otherwise).
        real(dp) :: noise_floor_level = 0.0_dp
        !> Noise model used: 'relative', 'absolute', 'floor', 'band' (the one 'auto' chose) or 'given'.
        character(len=16) :: noise_model = ''
        !> Why the noise model was taken, in a phrase: for noise_model = 'auto', the full likelihood
        !> criterion of each model compared against the one chosen ('' when the model was given).
        character(len=:), allocatable :: noise_choice
        !> Parameters of the noise model estimated from the data (rho; rho and s; one rho_b per band).
        integer :: noise_parameters = 0
        !> Noise levels estimated per band of lines (the 'band' model; empty otherwise): the
        !> smallest and largest rho_b.
        real(dp) :: band_level_range(2) = 0.0_dp
        !> Full likelihood criterion of the final model: -2 ln(likelihood) with the noise scale
        !> refitted, 2L*ln(chi2/(2L)) + 2L + 2*sum ln sigma_l^2 (sigma_l [m/N]), plus ln(2L) per
        !> parameter of the model and of the noise model and 2*ln(2L) per outlier line: it compares
        !> noise models, which chi2 alone does not.
        real(dp) :: likelihood_criterion = 0.0_dp
        !> Whether the data determine each mode (false: sigma_xi/xi >= 0.3 or the residue's Wald
        !> statistic, noise scaled to the residual, below 4*ln(2L); such a pole is part of the fitted
        !> receptance, not a mode the data give).
        logical, allocatable :: determined(:)
        !> chi2 of the final model with the weights used (before the chi2/nu rescaling).
        real(dp) :: chi_square = 0.0_dp
        !> Degrees of freedom nu = 2L - P.
        integer :: dof = 0
        !> Whether chi2/nu <= 1 + 3*sqrt(2/nu): the residual is explained by the noise.
        logical :: explained = .false.
        !> Error E of eq. (7) on the lines fitted.
        real(dp) :: e = 1.0_dp
        !> Levenberg-Marquardt iterations over all fits.
        integer :: iterations = 0
        !> Stabilisation diagram: order N (modes) of each pole.
        integer, allocatable :: diagram_order(:)
        !> Stabilisation diagram: natural frequency of each pole [Hz].
        real(dp), allocatable :: diagram_frequency(:)
        !> Stabilisation diagram: damping ratio of each pole.
        real(dp), allocatable :: diagram_damping(:)
        !> Stabilisation diagram: 2 stable in f and xi, 1 in f only, 0 neither (against order N - 1).
        integer, allocatable :: diagram_flag(:)
        !> Unstable roots (|z| >= 1) dropped at each order N of the diagram.
        integer, allocatable :: unstable_by_order(:)
        !> Real roots dropped at each order N of the diagram.
        integer, allocatable :: real_by_order(:)
        !> Physical poles of the highest order not used as start poles (stable for too few orders).
        integer :: n_wandering = 0
        !> Number of start poles taken from the diagram.
        integer :: n_start = 0
        !> Modes removed during the fit (pole [rad/s]).
        complex(dp), allocatable :: dropped_pole(:)
        !> Why each was removed: dropped_by_criterion, dropped_left_band, dropped_degenerate or dropped_boundary.
        integer, allocatable :: dropped_reason(:)
        !> Lines of the FRF left out as outliers (indices into frf%frequency), in the order found.
        integer, allocatable :: outlier_line(:)
        !> Their frequencies [Hz].
        real(dp), allocatable :: outlier_frequency(:)
        !> Their weighted residual |G_l - G_model|/sigma_l against the model when each was found.
        real(dp), allocatable :: outlier_excess(:)
        !> Largest number of modes the order search could reach: max_order, or less when the
        !> diagram's top order is lower (few lines or samples).
        integer :: max_modes = 0
        !> Warnings for the user ('' when none).
        character(len=:), allocatable :: warning
    contains
        !> Receptance [m/N] of the model (modes and residual terms) at omega [rad/s].
        procedure :: receptance => ml_receptance
        !> Largest sigma_f/f over the modes (huge when the information was singular, 0 without modes).
        procedure :: worst_frequency_spread => ml_worst_frequency_spread
        !> Largest sigma_xi/xi over the modes (huge when the information was singular, 0 without modes).
        procedure :: worst_damping_spread => ml_worst_damping_spread
        !> One phrase for a summary line: order, noise, worst uncertainty, outliers.
        procedure :: brief => ml_brief
        !> Whether the data determine each of the modes (all, when `determined` is not set).
        procedure :: determined_modes => ml_determined_modes
    end type ml_result

contains

    !> Receptance of the identified model [m/N]; infinite at omega = 0 with a lower residual.
    elemental complex(dp) function ml_receptance(self, omega)
        !> The result.
        class(ml_result), intent(in) :: self
        !> Angular frequency [rad/s].
        real(dp), intent(in) :: omega

        ml_receptance = self%upper_residual
        if (self%modes%n_modes() > 0) ml_receptance = ml_receptance + self%modes%receptance(omega)
        if (self%has_lower) ml_receptance = ml_receptance - self%lower_residual/omega**2
        if (self%outside%n_modes() > 0) ml_receptance = ml_receptance + self%outside%receptance(omega)
    end function ml_receptance

    !> Whether the data determine each of the modes: `determined`, or all when it was not set.
    pure function ml_determined_modes(self) result(flags)
        !> The result.
        class(ml_result), intent(in) :: self
        !> One flag per mode of self%modes.
        logical :: flags(self%modes%n_modes())

        flags = .true.
        if (.not. allocated(self%determined)) return
        if (size(self%determined) == size(flags)) flags = self%determined
    end function ml_determined_modes

    !> Largest relative standard deviation of a natural frequency, sigma_f/f.
    pure real(dp) function ml_worst_frequency_spread(self) result(worst)
        !> The result: its modes and their sigma_frequency [Hz].
        class(ml_result), intent(in) :: self

        worst = worst_spread(self, frequency=.true.)
    end function ml_worst_frequency_spread

    !> Largest relative standard deviation of a damping ratio, sigma_xi/xi.
    pure real(dp) function ml_worst_damping_spread(self) result(worst)
        !> The result: its modes and their sigma_damping.
        class(ml_result), intent(in) :: self

        worst = worst_spread(self, frequency=.false.)
    end function ml_worst_damping_spread

    !> Largest sigma/value over the modes, of the natural frequency or of the damping ratio:
    !> 0 without modes, huge when a sigma is huge (not available).
    pure real(dp) function worst_spread(self, frequency) result(worst)
        !> The result.
        class(ml_result), intent(in) :: self
        !> True: sigma_f/f; false: sigma_xi/xi.
        logical, intent(in) :: frequency

        worst = 0.0_dp
        if (self%modes%n_modes() == 0) return
        if (frequency) then
            worst = worst_ratio(self%sigma_frequency, natural_frequency(self%modes%pole)/two_pi)
        else
            worst = worst_ratio(self%sigma_damping, damping_ratio(self%modes%pole))
        end if
    end function worst_spread

    !> max(sigma/value), huge when a sigma is huge (not available).
    pure real(dp) function worst_ratio(sigma, value) result(worst)
        real(dp), intent(in) :: sigma(:), value(:)

        worst = huge(1.0_dp)
        if (any(sigma >= huge(1.0_dp))) return
        worst = maxval(sigma/value)
    end function worst_ratio

    !> The identification in one phrase, e.g. "12 determined of 12 modes (order by MDL), noise
    !> 1.01E-02 of |G| (estimated), worst sigma_f/f = 1.26E-04, worst sigma_xi/xi = 1.75E-02": the
    !> modes the data determine first, then the chosen order, the noise level refitted from the
    !> residual, the worst uncertainty (or why there is none), the noise model chosen and why,
    !> and the outlier lines left out.
    pure subroutine ml_brief(self, text)
        !> The result.
        class(ml_result), intent(in) :: self
        !> The phrase (an intent(out) text: no static length between threads).
        character(len=:), allocatable, intent(out) :: text

        integer :: n_determined

        n_determined = count(self%determined_modes())
        text = int_text(n_determined)//' determined of '//int_text(self%modes%n_modes()) &
               //' modes (order by MDL), noise '//sci_text(self%noise_level_fit)
        if (self%noise_model == 'absolute' .and. self%noise_estimated) then
            text = text//' m/N on every line (estimated from the data)'
        else if (self%noise_floor_level > 0.0_dp) then
            text = text//' of |G| and a floor of '//sci_text(self%noise_floor_level)//' m/N (estimated from the data)'
        else if (self%noise_model == 'band') then
            text = text//' of |G| (rms; estimated per band of lines, from '//sci_text(self%band_level_range(1)) &
                   //' to '//sci_text(self%band_level_range(2))//')'
        else if (self%noise_estimated) then
            text = text//' of |G| (estimated from the data)'
        else
            text = text//' times the sigma given'
        end if
        if (self%worst_frequency_spread() >= huge(1.0_dp) .or. self%worst_damping_spread() >= huge(1.0_dp)) then
            text = text//', uncertainty not available (singular Fisher information)'
        else
            text = text//', worst sigma_f/f = '//sci_text(self%worst_frequency_spread())//', worst sigma_xi/xi = ' &
                   //sci_text(self%worst_damping_spread())
        end if
        if (self%outside%n_modes() > 0) text = text//', '//int_text(self%outside%n_modes()) &
                                               //' pseudo-mode(s) above the band'
        if (allocated(self%noise_choice)) then
            if (len(self%noise_choice) > 0) text = text//', noise model '''//trim(self%noise_model)//''' ' &
                                                   //self%noise_choice
        end if
        if (.not. allocated(self%outlier_line)) return
        if (size(self%outlier_line) > 0) text = text//', '//int_text(size(self%outlier_line)) &
                                                //' outlier line(s) left out'
    end subroutine ml_brief

    !> Append dropped poles to the result.
    pure subroutine record_drop(result, poles, reason)
        !> The result (dropped_pole, dropped_reason).
        type(ml_result), intent(inout) :: result
        !> The poles removed [rad/s].
        complex(dp), intent(in) :: poles(:)
        !> Why: dropped_by_criterion, dropped_left_band, dropped_degenerate or dropped_boundary.
        integer, intent(in) :: reason

        result%dropped_pole = [result%dropped_pole, poles]
        result%dropped_reason = [result%dropped_reason, spread(reason, 1, size(poles))]
    end subroutine record_drop

    !> Append a warning ('; ' between warnings).
    pure subroutine add_warning(result, text)
        !> The result (warning).
        type(ml_result), intent(inout) :: result
        !> The warning.
        character(len=*), intent(in) :: text

        if (len(result%warning) > 0) result%warning = result%warning//'; '
        result%warning = result%warning//text
    end subroutine add_warning

end module greenconv_ident_ml_types
