!> Maximum-likelihood identification of a noisy receptance (issue 13): the modes, their
!> number and their uncertainty from the data alone, at the statistical limit.
!>
!> Model and convention as in greenconv_ident_lsce:
!>     G(omega) = sum_k [r_k/(i*omega - lambda_k) + conj(r_k)/(i*omega - conj(lambda_k))]
!>                + R_u - R_l/omega^2                                                   [m/N]
!> Noise: on each line l an independent complex Gaussian n_l with E|n_l|^2 = sigma_l^2 (each of
!> Re and Im has variance sigma_l^2/2). Its log-likelihood is, up to a constant, -chi2/2 with
!>     chi2 = sum_l 2*|G_l - G_model(omega_l)|^2/sigma_l^2,
!> a chi-square with nu = 2*L - P degrees of freedom at the optimum (L lines, P real parameters).
!>
!> ## What `identify_ml` does
!> 1. **Noise level.** Given by the user (`sigma`, one standard deviation per line), or
!>    estimated from the data by the local smoothness of G: d_l = sum_j c_j*G_{l+j}, the 4th
!>    difference normalised to sum c_j^2 = 1, is pure noise where G is smooth on the scale of
!>    a few lines, and E|d_l|^2 = sum_j c_j^2*sigma_{l+j}^2. For the `relative` noise model
!>    (sigma_l = rho*|G_l|, the default) rho^2 = median(|d_l|^2/sum_j c_j^2*|G_{l+j}|^2)/ln 2, for
!>    `absolute` (sigma_l = sigma) sigma^2 = median(|d_l|^2)/ln 2 (|d|^2/E|d|^2 is exponential,
!>    whose median is ln 2). Bias: the lines near sharp resonances, where the difference sees
!>    the signal, are outliers the median mostly ignores; a fraction eps of them raises the
!>    median to the 0.5/(1 - eps) quantile, rho^2 too high by about 1.4*eps (7 % for 5 % of
!>    the lines); the measured |G| in the denominator adds O(rho^2). A floor `noise_floor`*|G_l|
!>    (1e-13) keeps clean data fittable to round-off. The order choice below compares chi2 of
!>    models, so it depends on the level only through its scale; the uncertainties use the
!>    level refitted from the final residual (noise_level_fit, unbiased for the right model).
!>    Weights of the relative model: during the order search rho times the rms of |G| over 5
!>    lines, each |G| clipped at ten times their median (the noise of |G| in the weight reduced
!>    by sqrt(5), independent of any model, so the chi2 of different models stay comparable
!>    without a refit after each change; one outlier line moves no weight); for the final fit
!>    and the uncertainty rho*|G_model|.
!> 2. **Stabilisation diagram** with the linear LSCE step only (greenconv_ident_lsce's
!>    lsce_poles, no out-of-band correction, no residues, no polish) at N = 1..max_order modes:
!>    each physical pole is flagged 2 (its f within stable_frequency and its xi within
!>    stable_damping of the pole of order N - 1 nearest in f), 1 (f only) or 0. When no pole
!>    has been flagged 2 for stable_orders orders in a row by max_order (the poles of a
!>    band-limited G settle a few orders above the number of modes: the 4 modes of
!>    data/sample_receptance.frf at N = 8 to 10), the diagram goes on until the number of
!>    such poles has not grown for stable_orders orders, at most to 2*max_order + stable_orders.
!>    The LSCE step needs g, the inverse FFT of G on the uniform grid from 0 Hz; on any other
!>    grid (from df without a 0 Hz line, a band from f_min > 0, uneven lines) G is resampled
!>    onto such a grid for the diagram alone (`diagram_grid`: linear between lines, the static
!>    compliance below the first), and everything else runs on the lines given.
!> 3. **Start poles**: going down from the highest order, every pole flagged 2 along a chain
!>    of at least stable_orders orders (nearest-frequency links), one per stable_frequency
!>    band (none: the poles of the highest order flagged 1 or 2). The other poles of the
!>    highest order (wandering: n_wandering) are only candidates for step 5; roots with
!>    |z| >= 1 (unstable) or real roots (xi >= 1) never become poles (counted per order in
!>    unstable_by_order and real_by_order).
!> 4. **Maximum likelihood**: residues and residual terms by weighted linear least squares for
!>    the poles, then Levenberg-Marquardt on all parameters (Re, Im of poles and residues, R_u,
!>    R_l) with the analytic Jacobian, Marquardt's diagonal scaling and a Cholesky solve; a
!>    step that would make a pole unstable, narrower than narrow_band = 1e-3 of a line
!>    (-Re lambda < pi*1e-3*df) or move it to Im <= 0 is refused like one that raises chi2, so
!>    a returned pole always has Re < 0 < Im (0 < xi < 1). Poles the fit moves above f_max are
!>    dropped (their effect belongs to R_u), poles it pushes to the narrowest band (a spike on
!>    one line fitting noise) go first in the drop step; the result lists each with its reason.
!> 5. **Order from the data, by MDL** (Rissanen; the BIC of a Gaussian likelihood): minimise
!>    chi2 + P*ln(2L), 4*ln(2L) per mode (39 for 8193 lines, 33 for 2049). AIC's 8 per mode
!>    is too weak: a spurious mode on the largest noise bump, its pole free, lowers chi2 by
!>    the maximum of ~L*(damping scales) chi-square variables, about 2*ln(6L) + 2 plus a Gumbel
!>    tail (measured during development: up to 32 for 8193 lines, 30 for 2049, each refused).
!>    Modes are added one at a time, the candidate chosen among the diagram poles not in the
!>    model and the three largest peaks of the weighted residual (a damping grid at each),
!>    ranked by the drop of chi2 their two residue columns alone would give; the best three
!>    are fitted in turn (3 LM iterations: a true mode gains hundreds at once) and the first
!>    that lowers the criterion is kept and refined. When several candidates are strong (each
!>    worth more than a tenth of the best and ten times a mode's price) and far apart (1 % and
!>    three half-power bandwidths), they are first tried together in one trial fit: a diagram
!>    that settled only part of 30 modes then costs a few rounds instead of one round per mode.
!>    Modes are dropped while, of the three with the smallest Wald statistic for r_k = 0 (the
!>    residue against its covariance: the chi2 rise its removal would cause) below 4*ln(2L),
!>    one whose removal, fully refitted, lowers the criterion. The model never has more than
!>    max_order modes (fewer when the lines cannot give 6 impulse samples per mode), and the
!>    search makes at most max_changes changes: its cost is bounded whatever the data. R_u and
!>    R_l ('auto') take part in the whole search (a static offset would otherwise drag poles
!>    out of the band) and each is removed at its end when the residues and other term
!>    refitted for the current poles lower the criterion without it. The chi2
!>    test of the final model (chi2/nu against 1 + 3*sqrt(2/nu)) is reported, not used to stop:
!>    with an estimated level its own error (~1.4/sqrt(L) on rho^2) is as large as its width.
!> 6. **Outlier lines** (a line of a measured file damaged by a transfer, a glitch, a typing
!>    error: the fuzz test's huge, negated and zero numbers). The likelihood has a fourth move
!>    beside adding and dropping modes: leave one line out, its two values then free (2*ln(2L)
!>    of MDL). The candidate is the line whose weighted residual departs most from the cubic
!>    through the residuals of its two neighbours on each side (a model bent towards the line
!>    is smooth across lines, so the departure keeps the outlier's size), when that exceeds
!>    outlier_sigma (6). It is confirmed when, against the model refitted without it, it
!>    stands above outlier_sigma and its |e_w|^2 above ten times the sum over the two lines on
!>    each side: a mode, even an under-resolved one, lifts the lines beside its peak through
!>    its tails r/(i*(omega - omega_k)), one wrong line does not. The candidate is left
!>    out when no trial mode lowers the criterion below what the model refitted without it
!>    gives (as many LM iterations for both); and a mode narrower than a line that only takes
!>    up such a line (without it, refitted without the line, the criterion is lower) is
!>    dropped with the line left out.
!>    Lines beyond 1e100 times the median |G| are left out before anything (sums of squares
!>    would overflow). An outlier whose undamped sinusoid in g stands above the noise of g
!>    (|e_w| > sqrt(L)) has bent the diagram and the noise weights: the noise estimate, the
!>    diagram and the search start again with the line replaced by the cubic through its
!>    neighbours (at most outlier_restarts times; later ones are only left out). Each outlier
!>    is reported with its line, frequency and |G_l - G_model|/sigma_l.
!> 7. **Uncertainty**: the covariance of the parameters is the inverse of the Fisher
!>    information 2*Re(J^H*W*J), W = diag(1/sigma_l^2), at the optimum; with an estimated level
!>    it is scaled by chi2/nu. sigma_f [Hz], sigma_xi and sigma_r = sqrt(var Re r + var Im r)
!>    follow by linearisation of f = |lambda|/(2*pi), xi = -Re lambda/|lambda|. While the
!>    information of the final model is singular (two poles merged, a residue the data do not
!>    see) the mode `merged` names is dropped and the model refitted, so every mode returned has
!>    a finite uncertainty; a singularity left by a residual term is a warning (sigma huge).
!> Modes whose half-power band 2*xi*f holds fewer than `min_band_lines` lines are reported
!> as under-resolved in the warning (their xi and r rest on the few lines near the peak).
!>
!> ## Grids
!> Any increasing frequencies >= 0 Hz. The fit, the order search and the uncertainty use the
!> lines given, whatever their spacing; the 0 Hz line, when there is one, is left out with a
!> lower residual. The noise estimate (4th differences) and the smoothed |G| of the weights
!> work on neighbouring lines by index: on an uneven grid they stay right where G is smooth
!> over a few lines, as on a uniform one (lines too coarse for a resonance are the outliers the
!> median ignores). The narrowest pole (narrow_band, the spike test) is measured against the
!> smallest line spacing, the under-resolved warning against the spacing at the mode. Suite
!> identgrid: 1 % noise on a grid from df, a band from 50 Hz and log-spaced lines, worst
!> errors 1.9 to 2.6 Cramér-Rao sigma; clean log-spaced lines to round-off.
!>
!> ## Measured (suite mlfit, and 174 further draws)
!> Three structures (12 modes to 5 kHz with a 412/418 Hz pair; xi 0.001 and 0.3 with modes at
!> 0.8 % and 98.5 % of the band; 3 modes) at 0.1, 1 and 3 % noise: no mode missed or invented,
!> the worst error 3.8 CRB standard deviations in f and 3.3 in xi. The reported sigma against
!> the spread of 50 draws: ratios 0.82 to 1.09. Clean data: round-off (2e-16). One fit of 8193
!> lines, 12 modes, max_order 30: 32 LM iterations, 0.64 s CPU (release), the diagram 0.17 s; the
!> shipped scene's file (a spurious start pole that crawls along the band while it is kept): 39
!> iterations, 0.96 s (175 and 2.7-3.1 s before the fits of the search were capped at 10 iterations
!> and stopped at a chi2 fall below 1).
module greenconv_ident_mlfit
    use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
    use greenconv_core_kinds, only: dp
    use greenconv_core_error, only: error_type, fatal_error
    use greenconv_core_text, only: int_text, real_text, sci_text
    use greenconv_model_modal_set, only: modal_set, sorted_by_frequency
    use greenconv_model_frf, only: frf_type, min_frf_lines
    use greenconv_ext_lapack, only: least_squares
    use greenconv_ident_lsce, only: impulse_from_frf, lsce_poles, error_e, natural_frequency, damping_ratio
    implicit none
    private

    public :: ml_options, ml_result, identify_ml, estimate_noise, smoothed_magnitude
    public :: dropped_by_criterion, dropped_left_band, dropped_degenerate, dropped_boundary

    real(dp), parameter :: pi = 3.141592653589793238462643383279_dp
    real(dp), parameter :: two_pi = 2.0_dp*pi
    complex(dp), parameter :: i_unit = (0.0_dp, 1.0_dp)

    !> Reason code of a dropped mode: its removal lowered the MDL criterion.
    integer, parameter :: dropped_by_criterion = 1
    !> Reason code of a dropped mode: the fit moved it outside (0, f_max].
    integer, parameter :: dropped_left_band = 2
    !> Reason code of a dropped mode: its Fisher information was singular (e.g. two poles merged).
    integer, parameter :: dropped_degenerate = 3
    !> Reason code of a dropped mode: the fit pushed it to the narrowest band allowed
    !> (narrow_band of a line: a spike on one line, noise or an outlier, not a mode).
    integer, parameter :: dropped_boundary = 4

    !> Narrowest half-power band 2*xi*f of a pole, as a fraction of the line spacing df: a
    !> narrower pole acts on a single line only (its peak), which is what a spike of noise or
    !> an outlier line does; no sampled FRF can show such a mode. The fit keeps every pole at
    !> least this wide, and a pole it pushes below twice this is dropped first.
    real(dp), parameter :: narrow_band = 1.0e-3_dp
    !> Half-power half-width xi*f of a pole, as a fraction of the line spacing df, from which
    !> it is taken for a mode rather than for an outlier line when both explain a line that
    !> stands out: such a pole lifts the lines beside its peak by this fraction of the peak's
    !> excess or more, which a damaged line (whose neighbours are unchanged) drives the fit
    !> below as soon as its excess passes about 20 noise sigma (a sign lost or a zero at
    !> 3 % noise is 33 sigma or more). A lightly damped mode under-resolved by the grid
    !> (xi*f between this and df/2) is so kept, and reported as under-resolved.
    real(dp), parameter :: resolvable_width = 0.05_dp
    !> A line whose |G| exceeds the median |G| by this factor is an outlier before any fit.
    real(dp), parameter :: gross_ratio = 1.0e100_dp

    !> Damping ratios tried for a mode started at a residual peak.
    real(dp), parameter :: trial_damping(6) = [0.001_dp, 0.003_dp, 0.01_dp, 0.03_dp, 0.1_dp, 0.3_dp]
    !> Candidates refitted per attempt to add a mode.
    integer, parameter :: tries_per_add = 3

    !> Levenberg-Marquardt iterations of a trial fit (a mode added or removed, a residual term)
    !> before the criterion decides; the kept model is then refined fully.
    integer, parameter :: trial_iterations = 3
    !> Most Levenberg-Marquardt iterations of any fit during the order search (the final model
    !> is then refined with up to ml_options%max_iterations).
    integer, parameter :: search_iterations = 10
    !> Fall of chi2 in one iteration below which a fit of the order search stops: a fortieth of
    !> a mode's MDL price 4*ln(2L), too little to change a decision.
    real(dp), parameter :: search_tolerance = 1.0_dp
    !> The same for the final model: a parameter change of a few hundredths of its standard deviation.
    real(dp), parameter :: final_tolerance = 1.0e-3_dp

    !> Settings of identify_ml (every field has a default).
    type :: ml_options
        !> Largest number of modes N of the stabilisation diagram (LSCE order 2N) and of the model.
        !> The diagram goes on beyond it (to at most 2*max_order + stable_orders) only when no pole
        !> has been stable over stable_orders orders by then.
        integer :: max_order = 30
        !> Noise standard deviation per line [m/N] (E|n_l|^2 = sigma_l^2); estimated when not allocated.
        real(dp), allocatable :: sigma(:)
        !> Noise model of the estimate: 'relative' (sigma_l = rho*|G_l|) or 'absolute' (sigma_l = sigma).
        character(len=16) :: noise_model = 'relative'
        !> Smallest noise level, relative to |G_l| (clean data are fitted to round-off above it).
        real(dp) :: noise_floor = 1.0e-13_dp
        !> Residual terms: 'auto' (kept when MDL accepts them), 'none', 'upper', 'lower' or 'both'.
        character(len=8) :: residual_terms = 'auto'
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
    end type ml_result

    !> A model under fit.
    type :: model_type
        complex(dp), allocatable :: pole(:), residue(:)
        logical :: upper = .false., lower = .false.
        real(dp) :: r_u = 0.0_dp, r_l = 0.0_dp
    end type model_type

    !> The weighted data: lines used, G and 1/sigma on them; for the relative noise model the
    !> level rho and the floor of sigma, to take the weights from a model's |G|.
    type :: data_type
        real(dp), allocatable :: omega(:), weight(:), floor(:)
        complex(dp), allocatable :: g(:)
        !> Index of each used line in the FRF.
        integer, allocatable :: line(:)
        real(dp) :: penalty = 0.0_dp, f_max = 0.0_dp, level = 0.0_dp
        !> Smallest -Re(lambda) [1/s] of a pole: pi*narrow_band*df (a half-power band of narrow_band lines).
        real(dp) :: min_decay = 0.0_dp
        !> Line spacing of the FRF [Hz].
        real(dp) :: df = 0.0_dp
        logical :: relative = .false.
        integer :: max_iterations = 60
        !> Most modes of a model in the order search.
        integer :: max_modes = 0
        !> Outlier threshold on |e_l|/sigma_l (0: no detection).
        real(dp) :: outlier_sigma = 0.0_dp
        !> A Levenberg-Marquardt fit stops when chi2 falls by less than this (plus 1e-10*chi2) in an iteration.
        real(dp) :: tolerance = final_tolerance
    end type data_type


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
    end function ml_receptance

    !> Largest relative standard deviation of a natural frequency, sigma_f/f.
    pure real(dp) function ml_worst_frequency_spread(self) result(worst)
        !> The result.
        class(ml_result), intent(in) :: self

        worst = 0.0_dp
        if (self%modes%n_modes() > 0) worst = worst_ratio(self%sigma_frequency, natural_frequency(self%modes%pole)/two_pi)
    end function ml_worst_frequency_spread

    !> Largest relative standard deviation of a damping ratio, sigma_xi/xi.
    pure real(dp) function ml_worst_damping_spread(self) result(worst)
        !> The result.
        class(ml_result), intent(in) :: self

        worst = 0.0_dp
        if (self%modes%n_modes() > 0) worst = worst_ratio(self%sigma_damping, damping_ratio(self%modes%pole))
    end function ml_worst_damping_spread

    !> max(sigma/value), huge when a sigma is huge (not available).
    pure real(dp) function worst_ratio(sigma, value) result(worst)
        real(dp), intent(in) :: sigma(:), value(:)

        worst = huge(1.0_dp)
        if (any(sigma >= huge(1.0_dp))) return
        worst = maxval(sigma/value)
    end function worst_ratio

    !> The identification in one phrase, e.g. "12 modes (order by MDL), noise 1.01E-02 of |G|
    !> (estimated), worst sigma_f/f = 1.26E-04, worst sigma_xi/xi = 1.75E-02": the chosen order,
    !> the noise level refitted from the residual, the worst uncertainty (or why there is none)
    !> and the outlier lines left out.
    pure function ml_brief(self) result(text)
        !> The result.
        class(ml_result), intent(in) :: self
        character(len=:), allocatable :: text

        text = int_text(self%modes%n_modes())//' modes (order by MDL), noise '//sci_text(self%noise_level_fit)
        if (self%noise_estimated) then
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
        if (.not. allocated(self%outlier_line)) return
        if (size(self%outlier_line) > 0) text = text//', '//int_text(size(self%outlier_line)) &
                                                //' outlier line(s) left out'
    end function ml_brief

    !> Noise level of a receptance from the smoothness of G (see the module description):
    !> rho with sigma_l = rho*|G_l| for 'relative', sigma [m/N] for 'absolute'.
    pure real(dp) function estimate_noise(receptance, noise_model) result(level)
        !> Receptance lines [m/N] on a uniform grid (at least 5).
        complex(dp), intent(in) :: receptance(:)
        !> 'relative' or 'absolute'.
        character(len=*), intent(in) :: noise_model

        real(dp), parameter :: c(5) = [1.0_dp, -4.0_dp, 6.0_dp, -4.0_dp, 1.0_dp]/sqrt(70.0_dp)
        real(dp) :: q(size(receptance) - 4), m
        complex(dp) :: d
        integer :: l

        do l = 1, size(q)
            d = sum(c*receptance(l:l + 4))
            if (noise_model == 'absolute') then
                q(l) = abs(d)**2
            else
                ! Scaled by the largest |G| of the five lines: no overflow for any finite G.
                m = max(maxval(abs(receptance(l:l + 4))), tiny(1.0_dp))
                q(l) = abs(d/m)**2/max(sum(c**2*abs(receptance(l:l + 4)/m)**2), tiny(1.0_dp))
            end if
        end do
        level = sqrt(median(q)/log(2.0_dp))
    end function estimate_noise

    !> sqrt of the mean of |G|^2 over each line and its two neighbours on each side: the scale
    !> of the relative noise model during the order search, with the noise of |G| in the
    !> weights reduced by sqrt(5) and no dependence on a model (a model-based weight would
    !> have to be refitted after every change of the model). Each |G| is first clipped at ten
    !> times the median of the five, so that one outlier line neither hides among its
    !> neighbours' weights nor takes their weight away.
    pure function smoothed_magnitude(g) result(m)
        !> Receptance lines [m/N].
        complex(dp), intent(in) :: g(:)
        !> Smoothed |G| per line [m/N].
        real(dp) :: m(size(g))

        real(dp) :: window(5), top
        integer :: l, n, first, last

        n = size(g)
        do l = 1, n
            first = max(1, l - 2)
            last = min(n, l + 2)
            window(:last - first + 1) = abs(g(first:last))
            associate (w => window(:last - first + 1))
                w = min(w, 10.0_dp*median(w))
                top = max(maxval(w), tiny(1.0_dp))
                m(l) = top*sqrt(sum((w/top)**2)/size(w))
            end associate
        end do
    end function smoothed_magnitude

    !> Median of a vector (a sorted copy).
    pure real(dp) function median(x)
        real(dp), intent(in) :: x(:)

        real(dp) :: s(size(x))
        integer :: n

        s = x
        call sort(s)
        n = size(s)
        median = 0.5_dp*(s((n + 1)/2) + s(n/2 + 1))
    end function median

    !> Ascending heap sort in place.
    pure subroutine sort(a)
        real(dp), intent(inout) :: a(:)

        integer :: n, i, last
        real(dp) :: t

        n = size(a)
        do i = n/2, 1, -1
            call sift(a, i, n)
        end do
        do last = n, 2, -1
            t = a(1)
            a(1) = a(last)
            a(last) = t
            call sift(a, 1, last - 1)
        end do
    end subroutine sort

    pure subroutine sift(a, start, n)
        real(dp), intent(inout) :: a(:)
        integer, intent(in) :: start, n

        integer :: root, child
        real(dp) :: t

        root = start
        do while (2*root <= n)
            child = 2*root
            if (child < n) then
                if (a(child + 1) > a(child)) child = child + 1
            end if
            if (a(root) >= a(child)) return
            t = a(root)
            a(root) = a(child)
            a(child) = t
            root = child
        end do
    end subroutine sift

    !> Identify the modes of a noisy receptance by maximum likelihood with the order chosen by
    !> MDL, and their uncertainty (see the module description).
    subroutine identify_ml(frf, options, result, error)
        !> The sampled receptance (increasing frequencies >= 0 Hz, any spacing).
        type(frf_type), intent(in) :: frf
        !> Settings.
        type(ml_options), intent(in) :: options
        !> The model, its uncertainty, the diagram and the diagnostics.
        type(ml_result), intent(out) :: result
        !> Set on bad input or a numerical failure.
        type(error_type), allocatable, intent(out) :: error

        type(data_type) :: data
        type(model_type) :: model
        type(frf_type) :: repaired
        complex(dp), allocatable :: start(:), candidates(:)
        integer :: outlier, pass
        logical :: allow_lower

        call check_input(frf, options, error)
        if (allocated(error)) return
        allocate (result%outlier_line(0), result%outlier_frequency(0), result%outlier_excess(0))
        allow_lower = any(options%residual_terms == [character(len=8) :: 'auto', 'lower', 'both'])
        repaired = frf
        call gross_outliers(repaired, result)
        ! One pass per outlier found (up to outlier_restarts): an outlier line corrupts the noise
        ! weights of its neighbours and, through g, every order of the diagram, so the search
        ! starts again from the receptance with the line replaced by its neighbours' interpolation
        ! (for the diagram and the weights) and left out of the fit. Later outliers are only left out.
        do pass = 1, max(options%outlier_restarts, 0) + 1
            if (allocated(result%dropped_pole)) deallocate (result%dropped_pole, result%dropped_reason)
            allocate (result%dropped_pole(0), result%dropped_reason(0))
            result%warning = ''
            call prepare_data(repaired, result%outlier_line, allow_lower, options, result, data)
            call build_diagram(repaired, options, result, start, candidates, error)
            if (allocated(error)) return
            result%n_start = size(start)
            data%max_modes = result%max_modes
            data%outlier_sigma = options%outlier_sigma
            model = model_type()
            model%pole = widened(start, data%min_decay)
            ! With 'auto' both terms take part in the search (so that a static offset does not drag
            ! poles out of the band) and each is removed at its end when MDL prefers.
            model%upper = any(options%residual_terms == [character(len=8) :: 'upper', 'both', 'auto'])
            model%lower = allow_lower
            ! The order search refines each model for at most search_iterations: a spurious start pole
            ! can crawl along the band for hundreds of iterations, each lowering chi2 a little,
            ! before the search drops it; only the model the search keeps is refined fully.
            data%max_iterations = min(options%max_iterations, search_iterations)
            data%tolerance = search_tolerance
            call fit(data, model, result, error)
            if (allocated(error)) return
            call choose_order(data, options, candidates, model, result, outlier, pass > options%outlier_restarts, &
                              error)
            if (allocated(error)) return
            if (outlier == 0) exit
            repaired%receptance(outlier) = interpolated(repaired%receptance, result%outlier_line, outlier)
        end do
        data%max_iterations = options%max_iterations
        data%tolerance = final_tolerance
        call reweight(data, model, result)
        call drop_outside(data, model, result, error)
        if (allocated(error)) return
        call drop_needles(data, model, result, error)
        if (allocated(error)) return
        call drop_undetermined(data, model, result, error)
        if (allocated(error)) return
        call finish(frf, data, options, model, result)
    end subroutine identify_ml

    !> Poles the final fit left at the narrowest band allowed (within a factor 2 of min_decay):
    !> no sampled receptance can show such a mode (its peak is narrower than a thousandth of
    !> the line spacing); it stands for noise on a line or two, e.g. near an anti-resonance
    !> where the relative noise model underestimates the noise. Dropped one at a time, the
    !> narrowest first, the model refitted after each.
    subroutine drop_needles(data, model, result, error)
        type(data_type), intent(in) :: data
        type(model_type), intent(inout) :: model
        type(ml_result), intent(inout) :: result
        type(error_type), allocatable, intent(out) :: error

        integer :: k

        do while (any(narrowest(model%pole, data%min_decay)))
            k = maxloc(real(model%pole, dp), 1, narrowest(model%pole, data%min_decay))
            call record_drop(result, [model%pole(k)], dropped_boundary)
            model%pole = [model%pole(:k - 1), model%pole(k + 1:)]
            call fit(data, model, result, error)
            if (allocated(error)) return
        end do
    end subroutine drop_needles

    !> Reject inputs that cannot be used.
    subroutine check_input(frf, options, error)
        type(frf_type), intent(in) :: frf
        type(ml_options), intent(in) :: options
        type(error_type), allocatable, intent(out) :: error

        if (frf%n_freq() < min_frf_lines) then
            call fatal_error(error, 'identify_ml: the FRF has fewer than '//int_text(min_frf_lines)//' lines')
        else if (.not. (frf%frequency(1) >= 0.0_dp .and. all(frf%frequency(2:) > frf%frequency(:frf%n_freq() - 1)) &
                        .and. ieee_is_finite(frf%f_max()))) then
            call fatal_error(error, 'identify_ml: the FRF frequencies must be finite, >= 0 Hz and increasing')
        else if (size(frf%receptance) /= frf%n_freq()) then
            call fatal_error(error, 'identify_ml: the FRF has not one receptance per frequency')
        else if (.not. all(ieee_is_finite(real(frf%receptance, dp)) .and. ieee_is_finite(aimag(frf%receptance)))) then
            call fatal_error(error, 'identify_ml: the FRF holds a NaN or infinite receptance; remove or repair ' &
                             //'those lines')
        else if (.not. any(abs(frf%receptance(2:)) > 0.0_dp)) then
            call fatal_error(error, 'identify_ml: the receptance is zero on every line above 0 Hz: nothing to fit')
        else if (options%max_order < 1 .or. options%stable_orders < 1) then
            call fatal_error(error, 'identify_ml: max_order and stable_orders must be >= 1')
        else if (.not. any(options%residual_terms == [character(len=8) :: 'auto', 'none', 'upper', 'lower', &
                                                      'both'])) then
            call fatal_error(error, "identify_ml: residual_terms must be 'auto', 'none', 'upper', 'lower' or " &
                             //"'both', found '"//trim(options%residual_terms)//"'")
        else if (options%noise_model /= 'relative' .and. options%noise_model /= 'absolute') then
            call fatal_error(error, "identify_ml: noise_model must be 'relative' or 'absolute', found '" &
                             //trim(options%noise_model)//"'")
        end if
        if (allocated(error)) return
        if (allocated(options%sigma)) then
            if (size(options%sigma) /= frf%n_freq() .or. .not. all(options%sigma >= 0.0_dp)) then
                call fatal_error(error, 'identify_ml: sigma must hold one standard deviation >= 0 per line (' &
                                 //int_text(frf%n_freq())//' lines), found '//int_text(size(options%sigma)))
            end if
        end if
    end subroutine check_input

    !> The weighted data: the noise standard deviation per line (given, or estimated from the
    !> receptance), the lines used (a 0 Hz line is left out when a lower residual may be
    !> fitted, outlier lines always), their weights 1/sigma_l and the MDL price per parameter ln(2L).
    subroutine prepare_data(frf, outliers, skip_zero, options, result, data)
        !> The receptance, outlier lines already replaced by their neighbours' interpolation.
        type(frf_type), intent(in) :: frf
        !> Lines left out.
        integer, intent(in) :: outliers(:)
        logical, intent(in) :: skip_zero
        type(ml_options), intent(in) :: options
        type(ml_result), intent(inout) :: result
        type(data_type), intent(out) :: data

        real(dp) :: sigma(frf%n_freq()), floor(frf%n_freq())
        logical :: used(frf%n_freq())
        integer :: l

        floor(:) = max(options%noise_floor*abs(frf%receptance), tiny(1.0_dp)*1.0e10_dp)
        result%noise_level = 1.0_dp
        result%noise_estimated = .not. allocated(options%sigma)
        if (allocated(options%sigma)) then
            sigma(:) = options%sigma
        else
            result%noise_level = estimate_noise(frf%receptance, options%noise_model)
            if (options%noise_model == 'absolute') then
                sigma(:) = result%noise_level
            else
                sigma(:) = result%noise_level*smoothed_magnitude(frf%receptance)
            end if
        end if
        sigma(:) = max(sigma, floor)
        used(:) = .true.
        if (skip_zero .and. frf%frequency(1) == 0.0_dp) used(1) = .false.
        used(outliers) = .false.
        data%line = pack([(l, l=1, frf%n_freq())], used)
        data%omega = two_pi*frf%frequency(data%line)
        data%g = frf%receptance(data%line)
        data%weight = 1.0_dp/sigma(data%line)
        data%floor = floor(data%line)
        data%penalty = log(2.0_dp*size(data%g))
        data%f_max = frf%f_max()
        data%df = line_spacing(frf)
        data%min_decay = pi*narrow_band*data%df
        data%max_iterations = options%max_iterations
        data%relative = result%noise_estimated .and. options%noise_model /= 'absolute'
        data%level = result%noise_level
    end subroutine prepare_data

    !> Lines whose |G| exceeds the median |G| of the nonzero lines above 0 Hz by more than
    !> gross_ratio: no receptance spans that many decades, and the sums of squares of the
    !> diagram and the fit would overflow on them. They are recorded as outliers and replaced by
    !> their neighbours' interpolation before anything else.
    subroutine gross_outliers(frf, result)
        type(frf_type), intent(inout) :: frf
        type(ml_result), intent(inout) :: result

        real(dp) :: magnitude(frf%n_freq() - 1), typical
        integer :: l

        magnitude(:) = abs(frf%receptance(2:))
        if (.not. any(magnitude > 0.0_dp)) return
        typical = median(pack(magnitude, magnitude > 0.0_dp))
        do l = 1, frf%n_freq()
            if (.not. (abs(frf%receptance(l)) > gross_ratio*typical)) cycle
            result%outlier_line = [result%outlier_line, l]
            result%outlier_frequency = [result%outlier_frequency, frf%frequency(l)]
            result%outlier_excess = [result%outlier_excess, 0.0_dp]
        end do
        do l = 1, size(result%outlier_line)
            frf%receptance(result%outlier_line(l)) = interpolated(frf%receptance, result%outlier_line, &
                                                                  result%outlier_line(l))
        end do
    end subroutine gross_outliers

    !> The value of an outlier line from its neighbours: the cubic through the two lines on
    !> each side, (-G(l-2) + 4*G(l-1) + 4*G(l+1) - G(l+2))/6, or the mean of the nearest good
    !> lines when the cubic's are not all available (an edge, another outlier).
    pure complex(dp) function interpolated(g, outliers, l) result(value)
        complex(dp), intent(in) :: g(:)
        integer, intent(in) :: outliers(:), l

        integer :: j, n_good
        logical :: good(-2:2)

        do j = -2, 2
            good(j) = l + j >= 1 .and. l + j <= size(g)
            if (good(j)) good(j) = .not. any(outliers == l + j)
        end do
        good(0) = .false.
        if (all(good([-2, -1, 1, 2]))) then
            value = (-g(l - 2) + 4.0_dp*g(l - 1) + 4.0_dp*g(l + 1) - g(l + 2))/6.0_dp
            return
        end if
        value = (0.0_dp, 0.0_dp)
        n_good = 0
        do j = -2, 2
            if (.not. good(j)) cycle
            value = value + g(l + j)
            n_good = n_good + 1
        end do
        if (n_good > 0) value = value/n_good
    end function interpolated

    !> Line spacing of the data [Hz]: df on the uniform grid from 0 Hz, else the smallest
    !> spacing between two lines (the narrowest pole a line can still see is set by it).
    pure real(dp) function line_spacing(frf)
        type(frf_type), intent(in) :: frf

        if (frf%uniform_from_zero()) then
            line_spacing = frf%df()
        else
            line_spacing = minval(frf%frequency(2:) - frf%frequency(:frf%n_freq() - 1))
        end if
    end function line_spacing

    !> Spacing of the lines around frequency f [Hz]: the mean of the two intervals beside
    !> the line nearest f (the one interval at an end of the grid).
    pure real(dp) function spacing_at(frf, f)
        type(frf_type), intent(in) :: frf
        real(dp), intent(in) :: f

        integer :: l, low, high

        l = minloc(abs(frf%frequency - f), 1)
        low = max(l - 1, 1)
        high = min(l + 1, frf%n_freq())
        spacing_at = (frf%frequency(high) - frf%frequency(low))/(high - low)
    end function spacing_at

    !> G resampled onto a uniform grid from 0 Hz for the stabilisation diagram alone (its LSCE
    !> step needs g, the inverse FFT of that grid), when the lines given are not such a grid
    !> (a uniform grid from df, a band from f_min > 0, uneven lines). The step is the smallest
    !> line spacing, coarsened when needed so that the grid has at most diagram_intervals + 1
    !> lines, and adjusted to end exactly at f_max; between two lines G is interpolated
    !> linearly (Re and Im); below the first line f_1 > 0 a receptance tends to its static
    !> compliance, real at 0 Hz, with an imaginary part vanishing like omega (viscous damping):
    !> G(f) = Re G(f_1) + i*Im G(f_1)*f/f_1. The interpolation only blunts peaks between coarse
    !> lines, which moves the start poles a little: the maximum-likelihood fit and the order
    !> search then run on the lines given alone.
    pure function diagram_grid(frf) result(uniform)
        type(frf_type), intent(in) :: frf
        type(frf_type) :: uniform

        !> Most intervals of the resampled grid (the diagram uses at most max_samples of its 2*m
        !> impulse samples; 2^16 keeps the FFT and the memory small).
        integer, parameter :: diagram_intervals = 65536
        real(dp) :: f_max, step, t
        integer :: m, j, l, n

        n = frf%n_freq()
        f_max = frf%f_max()
        step = line_spacing(frf)
        m = ceiling(f_max/step*(1.0_dp - 1.0e-9_dp))
        m = max(min(m, diagram_intervals), min_frf_lines - 1)
        allocate (uniform%frequency(m + 1), uniform%receptance(m + 1))
        uniform%frequency(:) = [(j*(f_max/m), j=0, m)]
        uniform%frequency(m + 1) = f_max
        uniform%source = ''
        l = 1
        do j = 1, m + 1
            associate (f => uniform%frequency(j), g => frf%receptance, fl => frf%frequency)
                if (f <= fl(1)) then
                    uniform%receptance(j) = cmplx(real(g(1), dp), aimag(g(1))*f/fl(1), dp)
                    if (fl(1) == 0.0_dp) uniform%receptance(j) = g(1)
                    cycle
                end if
                do while (l < n - 1 .and. fl(l + 1) < f)
                    l = l + 1
                end do
                t = min(max((f - fl(l))/(fl(l + 1) - fl(l)), 0.0_dp), 1.0_dp)
                uniform%receptance(j) = g(l) + t*(g(l + 1) - g(l))
            end associate
        end do
    end function diagram_grid

    !> The stabilisation diagram (LSCE step only at N = 1..max_order, further when no pole is
    !> stable by then), the start poles (run of stable_orders or more at the highest order)
    !> and the other poles of the highest order as candidates.
    subroutine build_diagram(frf, options, result, start, candidates, error)
        type(frf_type), intent(in) :: frf
        type(ml_options), intent(in) :: options
        type(ml_result), intent(inout) :: result
        complex(dp), allocatable, intent(out) :: start(:), candidates(:)
        type(error_type), allocatable, intent(out) :: error

        real(dp), allocatable :: g(:), f(:), xi(:), f_prev(:), xi_prev(:)
        integer, allocatable :: run(:), run_prev(:), flag(:)
        complex(dp), allocatable :: poles(:)
        real(dp) :: dt
        integer :: n, n_data, n_max, k, j
        integer, allocatable :: unstable(:), real_roots(:), settled(:)

        if (frf%uniform_from_zero()) then
            call impulse_from_frf(frf, g, dt, error)
        else
            call impulse_from_frf(diagram_grid(frf), g, dt, error)
        end if
        if (allocated(error)) return
        n_data = min(size(g) - 1, options%max_samples)/6
        result%max_modes = min(options%max_order, n_data)
        ! Beyond max_order only when no pole has been stable over stable_orders orders by then: the
        ! poles of a band-limited G settle a few orders above the number of modes, and a max_order
        ! close to it would leave the fit without start poles. The diagram then goes on until the
        ! number of such poles has not grown for stable_orders orders.
        n_max = min(2*options%max_order + options%stable_orders, n_data)
        if (allocated(result%diagram_order)) deallocate (result%diagram_order, result%diagram_frequency, &
                                                         result%diagram_damping, result%diagram_flag, &
                                                         result%unstable_by_order, result%real_by_order)
        allocate (result%diagram_order(0), result%diagram_frequency(0), result%diagram_damping(0), &
                  result%diagram_flag(0), unstable(n_max), real_roots(n_max))
        allocate (f_prev(0), xi_prev(0), run_prev(0), poles(0), settled(0:n_max))
        settled = 0
        do n = 1, n_max
            if (n > result%max_modes) then
                if (settled(result%max_modes) > 0) exit
                if (settled(n - 1) > 0 .and. settled(n - 1) == settled(max(n - 1 - options%stable_orders, 0))) exit
            end if
            call lsce_poles(g, dt, 2*n, options%max_samples, poles, unstable(n), real_roots(n), error)
            if (allocated(error)) return
            f = natural_frequency(poles)/two_pi
            xi = damping_ratio(poles)
            allocate (flag(size(poles)), run(size(poles)))
            do k = 1, size(poles)
                flag(k) = 0
                run(k) = 0
                if (size(f_prev) == 0) cycle
                j = minloc(abs(f_prev - f(k)), 1)
                if (abs(f_prev(j) - f(k)) > options%stable_frequency*f_prev(j)) cycle
                flag(k) = 1
                if (abs(xi_prev(j) - xi(k)) > options%stable_damping*xi_prev(j)) cycle
                flag(k) = 2
                run(k) = run_prev(j) + 1
            end do
            result%diagram_order = [result%diagram_order, spread(n, 1, size(poles))]
            result%diagram_frequency = [result%diagram_frequency, f]
            result%diagram_damping = [result%diagram_damping, xi]
            result%diagram_flag = [result%diagram_flag, flag]
            call move_alloc(f, f_prev)
            call move_alloc(xi, xi_prev)
            settled(n) = count(run >= options%stable_orders)
            call move_alloc(run, run_prev)
            deallocate (flag)
        end do
        n = maxval([0, result%diagram_order])
        result%unstable_by_order = unstable(:n)
        result%real_by_order = real_roots(:n)
        candidates = pack(poles, .not. (run_prev >= options%stable_orders) .and. f_prev < frf%f_max())
        result%n_wandering = size(candidates)
        call start_poles(result, options, frf%f_max(), start)
    end subroutine build_diagram

    !> Start poles from the diagram: going down from the highest order, every pole stable in
    !> f and xi for stable_orders orders in a row (flag 2 that many times along its chain)
    !> whose frequency is not within stable_frequency of one already taken; when there is
    !> none, the poles of the highest order flagged 1 or 2.
    pure subroutine start_poles(result, options, f_max, start)
        type(ml_result), intent(in) :: result
        type(ml_options), intent(in) :: options
        real(dp), intent(in) :: f_max
        complex(dp), allocatable, intent(out) :: start(:)

        integer :: run(size(result%diagram_order))
        real(dp), allocatable :: taken(:)
        integer, allocatable :: length(:)
        integer :: i, j, n, needed

        ! run(i): orders in a row ending at pole i stable in f and xi, along nearest-frequency links.
        run = 0
        do i = 1, size(run)
            if (result%diagram_flag(i) < 2) cycle
            n = result%diagram_order(i)
            j = nearest_pole(result%diagram_frequency, result%diagram_order, n - 1, result%diagram_frequency(i))
            if (j > 0) run(i) = run(j) + 1
        end do
        ! When no chain is that long (max_order hardly above the number of modes: the poles of
        ! a band-limited G settle only a few orders above it), the poles of the highest order
        ! stable in f against the order below start the fit instead.
        needed = options%stable_orders
        if (.not. any(run >= needed)) then
            needed = 1
            run = 0
            where (result%diagram_order == maxval([0, result%diagram_order]) .and. result%diagram_flag >= 1) run = 1
        end if
        allocate (start(0), taken(0), length(0))
        do i = size(run), 1, -1
            if (run(i) < needed .or. result%diagram_frequency(i) >= f_max) cycle
            if (size(taken) > 0) then
                if (minval(abs(taken - result%diagram_frequency(i))) <= options%stable_frequency &
                    *result%diagram_frequency(i)) cycle
            end if
            taken = [taken, result%diagram_frequency(i)]
            length = [length, run(i)]
            start = [start, two_pi*result%diagram_frequency(i)*cmplx(-result%diagram_damping(i), &
                                                                     sqrt(1.0_dp - result%diagram_damping(i)**2), dp)]
        end do
        ! No more than the model may hold (a diagram gone beyond max_order): the longest chains.
        do while (size(start) > result%max_modes)
            i = minloc(length, 1, back=.true.)
            start = [start(:i - 1), start(i + 1:)]
            length = [length(:i - 1), length(i + 1:)]
        end do
    end subroutine start_poles

    !> Index of the pole of order n nearest in frequency to f (0 when order n has none).
    pure integer function nearest_pole(frequency, order, n, f)
        real(dp), intent(in) :: frequency(:)
        integer, intent(in) :: order(:), n
        real(dp), intent(in) :: f

        integer :: i

        nearest_pole = 0
        do i = 1, size(order)
            if (order(i) /= n) cycle
            if (nearest_pole == 0) then
                nearest_pole = i
            else if (abs(frequency(i) - f) < abs(frequency(nearest_pole) - f)) then
                nearest_pole = i
            end if
        end do
    end function nearest_pole

    !> Receptance of a model on omega [rad/s].
    pure function evaluate(model, omega) result(g)
        type(model_type), intent(in) :: model
        real(dp), intent(in) :: omega(:)
        complex(dp) :: g(size(omega))

        complex(dp) :: s(size(omega))
        integer :: k

        s = cmplx(0.0_dp, omega, dp)
        g = model%r_u
        do k = 1, size(model%pole)
            g = g + model%residue(k)/(s - model%pole(k)) + conjg(model%residue(k))/(s - conjg(model%pole(k)))
        end do
        if (model%lower) g = g - model%r_l/omega**2
    end function evaluate

    !> chi2 = sum 2*|w*(G - G_model)|^2.
    pure real(dp) function chi_square(data, model)
        type(data_type), intent(in) :: data
        type(model_type), intent(in) :: model

        chi_square = 2.0_dp*sum(abs(data%weight*(data%g - evaluate(model, data%omega)))**2)
    end function chi_square

    !> Number of real parameters of a model.
    elemental integer function n_parameters(model)
        type(model_type), intent(in) :: model

        n_parameters = 4*size(model%pole) + merge(1, 0, model%upper) + merge(1, 0, model%lower)
    end function n_parameters

    !> MDL criterion chi2 + P*ln(2L).
    pure real(dp) function criterion(data, model, chi)
        type(data_type), intent(in) :: data
        type(model_type), intent(in) :: model
        real(dp), intent(in) :: chi

        criterion = chi + data%penalty*n_parameters(model)
    end function criterion

    !> Weighted linear least squares for the residues and residual terms of the model's poles.
    subroutine fit_linear(data, model, error)
        type(data_type), intent(in) :: data
        type(model_type), intent(inout) :: model
        type(error_type), allocatable, intent(out) :: error

        real(dp), allocatable :: a(:, :), a_t(:, :), b(:), x(:), norms(:), gram(:, :), low(:, :)
        complex(dp), allocatable :: column(:, :)
        integer :: k, n, col
        logical :: ok

        n = size(model%pole)
        allocate (column(size(data%g), 2*n + merge(1, 0, model%upper) + merge(1, 0, model%lower)))
        call linear_columns(data, model, column)
        if (size(column, 2) == 0) then
            if (allocated(model%residue)) deallocate (model%residue)
            allocate (model%residue(0))
            return
        end if
        a = stacked(column)
        allocate (norms(size(a, 2)))
        norms(:) = sqrt(sum(a**2, dim=1))
        where (.not. (norms > 0.0_dp)) norms = 1.0_dp
        do col = 1, size(a, 2)
            a(:, col) = a(:, col)/norms(col)
        end do
        b = stacked_vector(data%weight*data%g)
        ! Normal equations of the unit-norm columns by Cholesky (a tenth of the SVD's time);
        ! the SVD when a pivot shows a condition beyond 1e8 (near-duplicate poles).
        a_t = transpose(a)
        gram = matmul(a_t, a)
        allocate (low(size(gram, 1), size(gram, 1)))
        call cholesky(gram, low, ok)
        if (ok) ok = minval([(low(col, col), col=1, size(gram, 1))])**2 > 1.0e-8_dp
        if (ok) then
            call cholesky_solve(gram, matmul(a_t, b), x, ok)
        end if
        if (.not. ok) then
            if (allocated(x)) deallocate (x)
            allocate (x(size(a, 2)))
            call least_squares(a, b, x, error, rcond=1.0e-13_dp)
            if (allocated(error)) return
        end if
        x = x/norms
        model%residue = [(cmplx(x(2*k - 1), x(2*k), dp), k=1, n)]
        col = 2*n
        if (model%upper) then
            col = col + 1
            model%r_u = x(col)
        end if
        if (model%lower) model%r_l = x(col + 1)
    end subroutine fit_linear

    !> Weighted columns of the linear part: per pole the responses to r = 1 and r = i, then
    !> R_u and R_l.
    pure subroutine linear_columns(data, model, column)
        type(data_type), intent(in) :: data
        type(model_type), intent(in) :: model
        complex(dp), intent(out) :: column(:, :)

        complex(dp) :: s(size(data%omega)), direct(size(data%omega)), mirror(size(data%omega))
        integer :: k, col

        s = cmplx(0.0_dp, data%omega, dp)
        do k = 1, size(model%pole)
            direct = 1.0_dp/(s - model%pole(k))
            mirror = 1.0_dp/(s - conjg(model%pole(k)))
            column(:, 2*k - 1) = data%weight*(direct + mirror)
            column(:, 2*k) = data%weight*i_unit*(direct - mirror)
        end do
        col = 2*size(model%pole)
        if (model%upper) then
            col = col + 1
            column(:, col) = data%weight
        end if
        if (model%lower) column(:, col + 1) = -data%weight/data%omega**2
    end subroutine linear_columns

    !> Weighted Jacobian of G_model, columns per mode (Re lambda, Im lambda, Re r, Im r), then
    !> R_u, R_l; real parts in rows 1..L, imaginary parts below.
    pure subroutine jacobian(data, model, jac)
        type(data_type), intent(in) :: data
        type(model_type), intent(in) :: model
        real(dp), intent(inout) :: jac(:, :)

        complex(dp) :: s(size(data%omega)), direct(size(data%omega)), mirror(size(data%omega)), r
        integer :: k, col

        s = cmplx(0.0_dp, data%omega, dp)
        do k = 1, size(model%pole)
            r = model%residue(k)
            direct = data%weight/(s - model%pole(k))
            mirror = data%weight/(s - conjg(model%pole(k)))
            col = 4*(k - 1)
            call put(jac, col + 1, (r*direct**2 + conjg(r)*mirror**2)/data%weight)
            call put(jac, col + 2, i_unit*(r*direct**2 - conjg(r)*mirror**2)/data%weight)
            call put(jac, col + 3, direct + mirror)
            call put(jac, col + 4, i_unit*(direct - mirror))
        end do
        col = 4*size(model%pole)
        if (model%upper) then
            col = col + 1
            call put(jac, col, cmplx(data%weight, 0.0_dp, dp))
        end if
        if (model%lower) call put(jac, col + 1, cmplx(-data%weight/data%omega**2, 0.0_dp, dp))
    end subroutine jacobian

    !> Column c of a stacked real matrix from complex values: [Re z; Im z].
    pure subroutine put(jac, c, z)
        real(dp), intent(inout) :: jac(:, :)
        integer, intent(in) :: c
        complex(dp), intent(in) :: z(:)

        jac(1:size(z), c) = real(z, dp)
        jac(size(z) + 1:, c) = aimag(z)
    end subroutine put

    !> A model plus a parameter step laid out as in `jacobian`.
    pure function stepped(model, step) result(trial)
        type(model_type), intent(in) :: model
        real(dp), intent(in) :: step(:)
        type(model_type) :: trial

        integer :: k, col

        trial = model
        do k = 1, size(model%pole)
            col = 4*(k - 1)
            trial%pole(k) = model%pole(k) + cmplx(step(col + 1), step(col + 2), dp)
            trial%residue(k) = model%residue(k) + cmplx(step(col + 3), step(col + 4), dp)
        end do
        col = 4*size(model%pole)
        if (model%upper) then
            col = col + 1
            trial%r_u = model%r_u + step(col)
        end if
        if (model%lower) trial%r_l = model%r_l + step(col + 1)
    end function stepped

    !> Fisher information 2*Re(J^H W J) and the gradient 2*Re(J^H W e) of -chi2/2.
    subroutine information(data, model, fisher, gradient, jac, jac_t)
        type(data_type), intent(in) :: data
        type(model_type), intent(in) :: model
        real(dp), allocatable, intent(out) :: fisher(:, :), gradient(:)
        !> Work arrays for the Jacobian and its transpose, kept between calls of one fit (their
        !> fresh allocation at every iteration cost 15 % of the time in page faults).
        real(dp), allocatable, intent(inout) :: jac(:, :), jac_t(:, :)

        real(dp), allocatable :: residual(:)
        integer :: m, p

        m = 2*size(data%g)
        p = n_parameters(model)
        if (allocated(jac)) then
            if (size(jac, 1) /= m .or. size(jac, 2) /= p) deallocate (jac, jac_t)
        end if
        if (.not. allocated(jac)) allocate (jac(m, p), jac_t(p, m))
        call jacobian(data, model, jac)
        residual = stacked_vector(data%weight*(data%g - evaluate(model, data%omega)))
        ! An explicit transposed copy: matmul(transpose(jac), jac) is three times slower (measured).
        jac_t(:, :) = transpose(jac)
        fisher = 2.0_dp*matmul(jac_t, jac)
        gradient = 2.0_dp*matmul(jac_t, residual)
    end subroutine information

    !> Residues for the model's poles, then Levenberg-Marquardt (at most `iterations`).
    subroutine fit(data, model, result, error, iterations)
        type(data_type), intent(in) :: data
        type(model_type), intent(inout) :: model
        type(ml_result), intent(inout) :: result
        type(error_type), allocatable, intent(out) :: error
        integer, intent(in), optional :: iterations

        call fit_linear(data, model, error)
        if (allocated(error)) return
        call refine(data, model, result, iterations)
    end subroutine fit

    !> The final refinement: for the relative noise model with the weights 1/max(rho*|G_model|,
    !> floor) from the model rather than from the noisy |G|.
    subroutine reweight(data, model, result)
        type(data_type), intent(inout) :: data
        type(model_type), intent(inout) :: model
        type(ml_result), intent(inout) :: result

        if (data%relative) data%weight = 1.0_dp/max(data%level*abs(evaluate(model, data%omega)), data%floor)
        call refine(data, model, result)
    end subroutine reweight

    !> Levenberg-Marquardt on all parameters: the Gauss-Newton system scaled to unit diagonal,
    !> damped by mu*I, solved by Cholesky; a step is kept when chi2 falls and every pole stays
    !> physical (Re < 0 < Im). Stops when mu grows past 1e12 or chi2 falls by less than
    !> data%tolerance + 1e-10*chi2 in an iteration (search_tolerance during the order search,
    !> final_tolerance for the final model).
    subroutine refine(data, model, result, iterations)
        type(data_type), intent(in) :: data
        type(model_type), intent(inout) :: model
        type(ml_result), intent(inout) :: result
        !> Most iterations (data%max_iterations when absent).
        integer, intent(in), optional :: iterations

        type(model_type) :: trial
        real(dp), allocatable :: fisher(:, :), gradient(:), scale(:), a(:, :), y(:), jac(:, :), jac_t(:, :)
        real(dp) :: chi, chi_trial, mu
        integer :: iteration, p, small, i, last
        logical :: ok

        if (n_parameters(model) == 0) return
        chi = chi_square(data, model)
        mu = 1.0e-4_dp
        small = 0
        last = data%max_iterations
        if (present(iterations)) last = iterations
        do iteration = 1, last
            call information(data, model, fisher, gradient, jac, jac_t)
            result%iterations = result%iterations + 1
            p = size(gradient)
            if (.not. allocated(scale)) allocate (scale(p))
            do i = 1, p
                scale(i) = sqrt(fisher(i, i))
            end do
            where (.not. (scale > 0.0_dp)) scale = 1.0_dp
            do
                a = fisher/spread(scale, 1, p)/spread(scale, 2, p)
                a = a + mu*identity(p)
                call cholesky_solve(a, gradient/scale, y, ok)
                chi_trial = huge(1.0_dp)
                if (ok) then
                    trial = stepped(model, y/scale)
                    if (physical(trial, data%min_decay)) chi_trial = chi_square(data, trial)
                end if
                if (chi_trial < chi) exit
                mu = 10.0_dp*mu
                if (mu > 1.0e12_dp) return
            end do
            small = merge(1, 0, chi - chi_trial <= data%tolerance + 1.0e-10_dp*chi)
            model = trial
            chi = chi_trial
            mu = max(0.1_dp*mu, 1.0e-12_dp)
            if (small >= 1) exit
        end do
    end subroutine refine

    !> Every pole with Re <= -min_decay < 0 < Im.
    pure logical function physical(model, min_decay)
        type(model_type), intent(in) :: model
        !> Smallest -Re(lambda) [1/s] (> 0).
        real(dp), intent(in) :: min_decay

        physical = all(real(model%pole, dp) <= -min_decay .and. aimag(model%pole) > 0.0_dp)
    end function physical

    !> Poles moved, when needed, to the narrowest band allowed: Re(lambda) <= -min_decay.
    elemental complex(dp) function widened(pole, min_decay)
        complex(dp), intent(in) :: pole
        real(dp), intent(in) :: min_decay

        widened = cmplx(min(real(pole, dp), -min_decay), aimag(pole), dp)
    end function widened

    !> Whether a pole sits within a factor 2 of the narrowest band allowed.
    elemental logical function narrowest(pole, min_decay)
        complex(dp), intent(in) :: pole
        real(dp), intent(in) :: min_decay

        narrowest = -real(pole, dp) < 2.0_dp*min_decay
    end function narrowest

    !> Identity matrix of order n.
    pure function identity(n) result(m)
        integer, intent(in) :: n
        real(dp) :: m(n, n)

        integer :: i

        m = 0.0_dp
        do i = 1, n
            m(i, i) = 1.0_dp
        end do
    end function identity

    !> Cholesky factor L (lower) of a symmetric positive definite matrix; ok = .false. if it is not.
    pure subroutine cholesky(a, low, ok)
        real(dp), intent(in) :: a(:, :)
        real(dp), intent(out) :: low(:, :)
        logical, intent(out) :: ok

        integer :: j, n
        real(dp) :: d

        n = size(a, 1)
        low = 0.0_dp
        ok = .false.
        do j = 1, n
            d = a(j, j) - sum(low(j, 1:j - 1)**2)
            if (.not. (d > 0.0_dp)) return
            low(j, j) = sqrt(d)
            low(j + 1:n, j) = (a(j + 1:n, j) - matmul(low(j + 1:n, 1:j - 1), low(j, 1:j - 1)))/low(j, j)
        end do
        ok = .true.
    end subroutine cholesky

    !> Solution of A x = b for symmetric positive definite A by Cholesky.
    pure subroutine cholesky_solve(a, b, x, ok)
        real(dp), intent(in) :: a(:, :), b(:)
        real(dp), allocatable, intent(out) :: x(:)
        logical, intent(out) :: ok

        real(dp) :: low(size(a, 1), size(a, 1))
        integer :: i, n

        n = size(b)
        allocate (x(n))
        call cholesky(a, low, ok)
        if (.not. ok) return
        do i = 1, n
            x(i) = (b(i) - dot_product(low(i, 1:i - 1), x(1:i - 1)))/low(i, i)
        end do
        do i = n, 1, -1
            x(i) = (x(i) - dot_product(low(i + 1:n, i), x(i + 1:n)))/low(i, i)
        end do
    end subroutine cholesky_solve

    !> Covariance inv(F) of a symmetric positive definite F (scaled to unit diagonal first).
    pure subroutine covariance(fisher, cov, ok)
        real(dp), intent(in) :: fisher(:, :)
        real(dp), allocatable, intent(out) :: cov(:, :)
        logical, intent(out) :: ok

        real(dp), allocatable :: x(:)
        real(dp) :: scale(size(fisher, 1)), a(size(fisher, 1), size(fisher, 1)), e(size(fisher, 1))
        integer :: j, n

        n = size(fisher, 1)
        allocate (cov(n, n))
        cov = 0.0_dp
        ok = .true.
        if (n == 0) return
        scale = [(sqrt(max(fisher(j, j), tiny(1.0_dp))), j=1, n)]
        a = fisher/spread(scale, 1, n)/spread(scale, 2, n)
        do j = 1, n
            e = 0.0_dp
            e(j) = 1.0_dp
            call cholesky_solve(a, e, x, ok)
            if (.not. ok) return
            cov(:, j) = x/scale/scale(j)
        end do
    end subroutine covariance

    !> Add modes while MDL accepts one, then drop modes while MDL accepts their removal;
    !> repeat until neither changes the model, then decide the residual terms ('auto').
    !> An outlier line MDL prefers to leave out is recorded in the result; unless `keep_going`,
    !> the search then stops and returns its FRF index in `outlier` (for a fresh start without
    !> it), otherwise the line is left out of the data and the search goes on.
    subroutine choose_order(data, options, candidates, model, result, outlier, keep_going, error)
        type(data_type), intent(inout) :: data
        type(ml_options), intent(in) :: options
        complex(dp), intent(in) :: candidates(:)
        type(model_type), intent(inout) :: model
        type(ml_result), intent(inout) :: result
        integer, intent(out) :: outlier
        logical, intent(in) :: keep_going
        type(error_type), allocatable, intent(out) :: error

        integer :: changes, line
        logical :: added, removed

        outlier = 0
        call drop_outside(data, model, result, error)
        if (allocated(error)) return
        changes = 0
        ! Adding stops when no candidate is accepted; only a removal can make a new addition
        ! worth trying (the residual changed), so the rounds end with a round that removes nothing.
        do
            do while (changes < options%max_changes)
                call add_mode(data, candidates, model, result, added, line, error)
                if (allocated(error)) return
                if (.not. added) exit
                changes = changes + 1
                if (line > 0) then
                    call take_outlier(data, model, result, line, keep_going, outlier, error)
                    if (allocated(error) .or. outlier > 0) return
                end if
            end do
            removed = .false.
            do while (changes < options%max_changes)
                call drop_mode(data, model, result, added, line, error)
                if (allocated(error)) return
                if (.not. added) exit
                removed = .true.
                changes = changes + 1
                if (line > 0) then
                    call take_outlier(data, model, result, line, keep_going, outlier, error)
                    if (allocated(error) .or. outlier > 0) return
                end if
            end do
            if (.not. removed .or. changes >= options%max_changes) exit
        end do
        if (options%residual_terms == 'auto') then
            call drop_term(data, model, result, .true., error)
            if (allocated(error)) return
            call drop_term(data, model, result, .false., error)
        end if
    end subroutine choose_order

    !> An outlier line (index in data) the search found: recorded, then either left out of the
    !> data and the model refitted, or, when its effect on the diagram outweighs the noise
    !> (|e_w| > sqrt(L): the undamped sinusoid it adds to g stands above the noise of each
    !> sample of g) and `keep_going` is false, returned in `outlier` (FRF index) for a fresh start.
    subroutine take_outlier(data, model, result, line, keep_going, outlier, error)
        type(data_type), intent(inout) :: data
        type(model_type), intent(inout) :: model
        type(ml_result), intent(inout) :: result
        integer, intent(in) :: line
        logical, intent(in) :: keep_going
        integer, intent(out) :: outlier
        type(error_type), allocatable, intent(out) :: error

        complex(dp) :: g_model(1)

        outlier = 0
        call record_outlier(data, line, result)
        g_model = evaluate(model, data%omega(line:line))
        if (.not. keep_going .and. data%weight(line)*abs(data%g(line) - g_model(1)) > sqrt(real(size(data%g), dp))) then
            outlier = data%line(line)
            return
        end if
        call leave_out(data, line)
        call fit(data, model, result, error)
    end subroutine take_outlier

    !> Append an outlier line (index in data) to the result (FRF line, frequency; its excess
    !> over the final model is filled in by `finish`).
    pure subroutine record_outlier(data, line, result)
        type(data_type), intent(in) :: data
        integer, intent(in) :: line
        type(ml_result), intent(inout) :: result

        result%outlier_line = [result%outlier_line, data%line(line)]
        result%outlier_frequency = [result%outlier_frequency, data%omega(line)/two_pi]
        result%outlier_excess = [result%outlier_excess, 0.0_dp]
    end subroutine record_outlier

    !> Remove one line (index in data) from the data.
    pure subroutine leave_out(data, line)
        type(data_type), intent(inout) :: data
        integer, intent(in) :: line

        logical :: keep(size(data%g))

        keep = .true.
        keep(line) = .false.
        data%line = pack(data%line, keep)
        data%omega = pack(data%omega, keep)
        data%g = pack(data%g, keep)
        data%weight = pack(data%weight, keep)
        data%floor = pack(data%floor, keep)
        data%penalty = log(2.0_dp*size(data%g))
    end subroutine leave_out

    !> Remove poles the fit moved above f_max (their effect belongs to R_u) and refit.
    subroutine drop_outside(data, model, result, error)
        type(data_type), intent(in) :: data
        type(model_type), intent(inout) :: model
        type(ml_result), intent(inout) :: result
        type(error_type), allocatable, intent(out) :: error

        logical, allocatable :: inside(:)

        do
            if (allocated(inside)) deallocate (inside)
            allocate (inside(size(model%pole)))
            inside(:) = natural_frequency(model%pole) <= two_pi*data%f_max
            if (all(inside)) return
            call record_drop(result, pack(model%pole, .not. inside), dropped_left_band)
            model%pole = pack(model%pole, inside)
            call fit(data, model, result, error)
            if (allocated(error)) return
        end do
    end subroutine drop_outside

    !> Remove the modes the data do not determine: while the Fisher information of the final
    !> model is singular (two poles merged, a residue the data cannot see), drop the mode
    !> `merged` names and refit, so that every mode returned has a finite uncertainty.
    subroutine drop_undetermined(data, model, result, error)
        type(data_type), intent(in) :: data
        type(model_type), intent(inout) :: model
        type(ml_result), intent(inout) :: result
        type(error_type), allocatable, intent(out) :: error

        real(dp), allocatable :: fisher(:, :), gradient(:), cov(:, :), jac(:, :), jac_t(:, :)
        integer :: worst
        logical :: ok

        do while (size(model%pole) > 0)
            call information(data, model, fisher, gradient, jac, jac_t)
            call covariance(fisher, cov, ok)
            if (ok) return
            worst = merged(model)
            call record_drop(result, [model%pole(worst)], dropped_degenerate)
            model%pole = [model%pole(:worst - 1), model%pole(worst + 1:)]
            call fit(data, model, result, error)
            if (allocated(error)) return
        end do
    end subroutine drop_undetermined

    !> Append dropped poles to the result.
    pure subroutine record_drop(result, poles, reason)
        type(ml_result), intent(inout) :: result
        complex(dp), intent(in) :: poles(:)
        integer, intent(in) :: reason

        result%dropped_pole = [result%dropped_pole, poles]
        result%dropped_reason = [result%dropped_reason, spread(reason, 1, size(poles))]
    end subroutine record_drop

    !> Try to add one mode: candidates are the diagram poles not yet in the model and the
    !> three largest peaks of the smoothed weighted residual (at each, the best of a grid of
    !> damping ratios), ranked by the chi2 drop of their two residue columns alone; the best
    !> tries_per_add are refitted in turn and the first that lowers the MDL criterion is kept.
    !> No mode is added to a model of data%max_modes. The alternative to a mode is an outlier
    !> line (`outlier_candidate`): when no mode trial lowers the criterion below what leaving
    !> that line out gives, `outlier` returns its index in data (0 otherwise).
    subroutine add_mode(data, candidates, model, result, added, outlier, error)
        type(data_type), intent(in) :: data
        complex(dp), intent(in) :: candidates(:)
        type(model_type), intent(inout) :: model
        type(ml_result), intent(inout) :: result
        logical, intent(out) :: added
        integer, intent(out) :: outlier
        type(error_type), allocatable, intent(out) :: error

        complex(dp), allocatable :: pool(:), residual(:)
        real(dp), allocatable :: score(:), power(:)
        type(model_type) :: trial
        type(data_type) :: without
        real(dp) :: best_score, s, before, target
        complex(dp) :: best_pole, p
        integer :: k, j, try, peak, l, h
        integer, allocatable :: batch(:)
        logical :: alone

        added = .false.
        l = size(data%g)
        allocate (residual(l))
        residual(:) = data%weight*(data%g - evaluate(model, data%omega))
        before = criterion(data, model, chi_square(data, model))
        ! Leaving a line out frees its two values (2*ln(2L)); the model is refitted without it as
        ! long as a trial mode is (a mode's trial also moves the other poles: a model not yet
        ! converged would otherwise always favour the mode).
        outlier = outlier_candidate(data, residual)
        target = before
        if (outlier > 0) then
            trial = model
            call without_line(data, outlier, trial_iterations, trial, result, without, alone, error)
            if (allocated(error)) return
            if (alone) then
                target = min(before, criterion(without, trial, chi_square(without, trial)) + 2.0_dp*data%penalty)
            else
                outlier = 0
            end if
        end if
        if (size(model%pole) >= data%max_modes) then
            added = target < before
            if (.not. added) outlier = 0
            return
        end if
        allocate (pool(0), power(l))
        do k = 1, size(candidates)
            if (size(model%pole) > 0) then
                if (minval(abs(model%pole - candidates(k))) < 0.01_dp*abs(candidates(k))) cycle
            end if
            pool = [pool, widened(candidates(k), data%min_decay)]
        end do
        ! Residual peaks: the largest local maxima of |e_w|^2 summed over 5 lines.
        h = 2
        do j = 1, l
            power(j) = sum(abs(residual(max(1, j - h):min(l, j + h)))**2)
        end do
        do try = 1, 3
            peak = maxloc(power, 1)
            if (.not. (power(peak) > 0.0_dp)) exit
            best_score = -1.0_dp
            best_pole = (0.0_dp, 0.0_dp)
            do j = 1, size(trial_damping)
                p = data%omega(peak)*cmplx(-trial_damping(j), sqrt(1.0_dp - trial_damping(j)**2), dp)
                if (.not. (data%omega(peak) > 0.0_dp)) cycle
                s = column_score(data, residual, p)
                if (s > best_score) then
                    best_score = s
                    best_pole = p
                end if
            end do
            if (best_score > 0.0_dp) pool = [pool, widened(best_pole, data%min_decay)]
            ! Clear the neighbourhood of this peak (about one percent of its frequency, 3 lines at least).
            j = max(3, nint(0.01_dp*peak))
            power(max(1, peak - j):min(l, peak + j)) = 0.0_dp
        end do
        ! Never again a pole the search has dropped (no add-drop cycles).
        if (size(result%dropped_pole) > 0) then
            pool = pack(pool, [(minval(abs(result%dropped_pole - pool(k))) >= 0.01_dp*abs(pool(k)), &
                                k=1, size(pool))])
        end if
        allocate (score(size(pool)))
        do k = 1, size(pool)
            score(k) = column_score(data, residual, pool(k))
        end do
        ! Many modes missing (a diagram that settled only part of them): the strong candidates
        ! far apart go in together, each worth more than a tenth of the best and ten times a
        ! mode's price; one trial fit judges them all, else they are tried one by one below.
        batch = strong_candidates(data, pool, score, size(model%pole))
        if (size(batch) > 1) then
            trial = model
            trial%pole = [model%pole, pool(batch)]
            call fit(data, trial, result, error, trial_iterations)
            if (allocated(error)) return
            if (all(natural_frequency(trial%pole) <= two_pi*data%f_max) .and. &
                criterion(data, trial, chi_square(data, trial)) < target) then
                model = trial
                call refine(data, model, result)
                added = .true.
                outlier = 0
                return
            end if
        end if
        do try = 1, min(tries_per_add, size(pool))
            k = maxloc(score, 1)
            score(k) = -huge(1.0_dp)
            trial = model
            trial%pole = [model%pole, pool(k)]
            call fit(data, trial, result, error, trial_iterations)
            if (allocated(error)) return
            if (.not. all(natural_frequency(trial%pole) <= two_pi*data%f_max)) cycle
            if (criterion(data, trial, chi_square(data, trial)) < merge(before, target, &
                resolves_line(data, trial, outlier))) then
                model = trial
                call refine(data, model, result)
                added = .true.
                outlier = 0
                return
            end if
        end do
        added = target < before
        if (.not. added) outlier = 0
    end subroutine add_mode

    !> Indices into pool of the candidates to add together, best first: the best, then each
    !> whose score exceeds a tenth of the best's and ten times a mode's MDL price and whose
    !> pole lies more than 1 % and more than three half-power bandwidths from those taken,
    !> as long as the model stays within data%max_modes.
    pure function strong_candidates(data, pool, score, n_model) result(batch)
        type(data_type), intent(in) :: data
        complex(dp), intent(in) :: pool(:)
        real(dp), intent(in) :: score(:)
        integer, intent(in) :: n_model
        integer, allocatable :: batch(:)

        real(dp) :: left(size(score))
        integer :: k, j
        logical :: apart

        allocate (batch(0))
        if (size(score) == 0) return
        left = score
        do while (n_model + size(batch) < data%max_modes)
            k = maxloc(left, 1)
            if (size(batch) > 0) then
                if (.not. (left(k) > 0.1_dp*score(batch(1)) .and. left(k) > 40.0_dp*data%penalty)) exit
            end if
            left(k) = -huge(1.0_dp)
            apart = .true.
            do j = 1, size(batch)
                associate (p => pool(k), q => pool(batch(j)))
                    apart = apart .and. abs(p - q) > max(0.01_dp*abs(p), -3.0_dp*(real(p, dp) + real(q, dp)))
                end associate
            end do
            if (apart) batch = [batch, k]
            if (all(left < -0.5_dp*huge(1.0_dp))) exit
        end do
    end function strong_candidates

    !> The line (index in data) that may be an outlier, to be confirmed by `without_line`: the
    !> one whose weighted residual departs most from the cubic through the residuals of the two
    !> lines on each side, (-e(l-2) + 4*e(l-1) + 4*e(l+1) - e(l+2))/6, when that departure
    !> exceeds data%outlier_sigma. A model bent towards an outlier is smooth across the lines,
    !> so the departure keeps the outlier's size where the residual itself may not; a mode the
    !> model lacks is smooth as well unless it is narrower than a few lines. Noise alone gives
    !> departures of standard deviation sqrt(70)/6 = 1.39 times that of e. 0 when there is none.
    pure integer function outlier_candidate(data, residual) result(line)
        type(data_type), intent(in) :: data
        complex(dp), intent(in) :: residual(:)

        real(dp) :: departure(size(residual))
        integer :: l, n

        line = 0
        n = size(residual)
        if (.not. (data%outlier_sigma > 0.0_dp) .or. n < 5) return
        departure = 0.0_dp
        do l = 3, n - 2
            departure(l) = abs(residual(l) - (-residual(l - 2) + 4.0_dp*residual(l - 1) + 4.0_dp*residual(l + 1) &
                                              - residual(l + 2))/6.0_dp)
        end do
        line = maxloc(departure, 1)
        if (.not. (departure(line) > data%outlier_sigma)) line = 0
    end function outlier_candidate

    !> Whether line l's weighted residual is above data%outlier_sigma and alone: |e_w(l)|^2 more
    !> than ten times the sum over the two lines on each side (false when detection is off).
    pure logical function lone_line(data, residual, l)
        type(data_type), intent(in) :: data
        complex(dp), intent(in) :: residual(:)
        integer, intent(in) :: l

        real(dp) :: power
        integer :: n

        n = size(residual)
        lone_line = .false.
        if (.not. (data%outlier_sigma > 0.0_dp) .or. n < 5) return
        power = abs(residual(l))**2
        if (.not. (power > data%outlier_sigma**2)) return
        lone_line = power > 10.0_dp*(sum(abs(residual(max(1, l - 2):min(n, l + 2)))**2) - power)
    end function lone_line

    !> Whether a trial model whose new pole is its last explains the outlier candidate `line`
    !> (index in data; 0: none) as a mode the grid can show: the pole within two lines of the
    !> line, its half-power half-width at least resolvable_width*df, and the line and its two
    !> neighbours within outlier_sigma of the model. Such a mode is preferred to leaving the
    !> line out whenever it lowers the criterion at all.
    pure logical function resolves_line(data, trial, line)
        type(data_type), intent(in) :: data
        type(model_type), intent(in) :: trial
        integer, intent(in) :: line

        complex(dp) :: pole
        integer :: first, last

        resolves_line = .false.
        if (line <= 0 .or. size(trial%pole) == 0) return
        pole = trial%pole(size(trial%pole))
        if (abs(aimag(pole) - data%omega(line)) > 2.0_dp*two_pi*data%df .or. &
            -real(pole, dp) < two_pi*resolvable_width*data%df) return
        first = max(1, line - 1)
        last = min(size(data%g), line + 1)
        resolves_line = all(data%weight(first:last)*abs(data%g(first:last) &
                                                        - evaluate(trial, data%omega(first:last))) <= data%outlier_sigma)
    end function resolves_line

    !> The model refitted (at most `iterations` LM iterations) on the data without line l, and
    !> whether, against it, line l stands alone far off: |e_w| above data%outlier_sigma and
    !> |e_w|^2 more than ten times the sum over the two lines on each side. A mode, even one
    !> narrower than the grid, also lifts the lines beside its peak (its tails
    !> r/(i*(omega - omega_k))); one wrong line does not, once the model no longer bends to it.
    subroutine without_line(data, l, iterations, model, result, without, alone, error)
        type(data_type), intent(in) :: data
        integer, intent(in) :: l, iterations
        !> In: the model to start from; out: refitted without line l.
        type(model_type), intent(inout) :: model
        type(ml_result), intent(inout) :: result
        !> The data without line l.
        type(data_type), intent(out) :: without
        logical, intent(out) :: alone
        type(error_type), allocatable, intent(out) :: error

        alone = .false.
        without = data
        call leave_out(without, l)
        call fit(without, model, result, error, iterations)
        if (allocated(error)) return
        alone = lone_line(data, data%weight*(data%g - evaluate(model, data%omega)), l)
    end subroutine without_line

    !> The chi2 drop the two residue columns of one pole would give alone against a residual.
    pure real(dp) function column_score(data, residual, pole) result(score)
        type(data_type), intent(in) :: data
        complex(dp), intent(in) :: residual(:)
        complex(dp), intent(in) :: pole

        complex(dp) :: s(size(residual)), a1(size(residual)), a2(size(residual))
        real(dp) :: g11, g12, g22, b1, b2, det

        s = cmplx(0.0_dp, data%omega, dp)
        a1 = data%weight*(1.0_dp/(s - pole) + 1.0_dp/(s - conjg(pole)))
        a2 = data%weight*i_unit*(1.0_dp/(s - pole) - 1.0_dp/(s - conjg(pole)))
        g11 = sum(abs(a1)**2)
        g22 = sum(abs(a2)**2)
        g12 = sum(real(conjg(a1)*a2, dp))
        b1 = sum(real(conjg(a1)*residual, dp))
        b2 = sum(real(conjg(a2)*residual, dp))
        det = g11*g22 - g12**2
        score = 0.0_dp
        if (det > 0.0_dp) score = 2.0_dp*(g22*b1**2 - 2.0_dp*g12*b1*b2 + g11*b2**2)/det
    end function column_score

    !> First a mode that only takes up an outlier line goes (`spike_mode`, the line returned in
    !> `outlier`, index in data). Otherwise try to drop one of the three modes with the smallest
    !> Wald statistic for r_k = 0 below the MDL price of a mode (poles at the narrowest band
    !> first); a removal is kept when the fully refitted model lowers the criterion. A
    !> singular information drops the mode `merged` names.
    subroutine drop_mode(data, model, result, removed, outlier, error)
        type(data_type), intent(in) :: data
        type(model_type), intent(inout) :: model
        type(ml_result), intent(inout) :: result
        logical, intent(out) :: removed
        integer, intent(out) :: outlier
        type(error_type), allocatable, intent(out) :: error

        real(dp), allocatable :: fisher(:, :), gradient(:), cov(:, :), wald(:), jac(:, :), jac_t(:, :)
        real(dp) :: block2(2, 2), before
        type(model_type) :: trial
        logical :: ok
        integer :: k, c, worst, try

        removed = .false.
        outlier = 0
        if (size(model%pole) == 0) return
        call spike_mode(data, model, result, outlier, error)
        if (allocated(error)) return
        if (outlier > 0) then
            removed = .true.
            return
        end if
        call information(data, model, fisher, gradient, jac, jac_t)
        call covariance(fisher, cov, ok)
        allocate (wald(size(model%pole)))
        if (.not. ok) then
            worst = merged(model)
            call record_drop(result, [model%pole(worst)], dropped_degenerate)
            model%pole = [model%pole(:worst - 1), model%pole(worst + 1:)]
            call fit(data, model, result, error)
            removed = .true.
            return
        end if
        do k = 1, size(model%pole)
            c = 4*(k - 1)
            block2 = cov(c + 3:c + 4, c + 3:c + 4)
            wald(k) = quadratic(block2, [real(model%residue(k), dp), aimag(model%residue(k))])
        end do
        ! Poles the fit pushed to the narrowest band go first, whatever their statistic.
        where (narrowest(model%pole, data%min_decay)) wald = -1.0_dp
        do try = 1, tries_per_add
            worst = minloc(wald, 1)
            if (.not. (wald(worst) < 4.0_dp*data%penalty)) return
            wald(worst) = huge(1.0_dp)
            trial = model
            trial%pole = [model%pole(:worst - 1), model%pole(worst + 1:)]
            ! A full refit: with several noise poles the others move when one goes.
            call fit(data, trial, result, error)
            if (allocated(error)) return
            before = criterion(data, model, chi_square(data, model))
            if (criterion(data, trial, chi_square(data, trial)) < before) then
                call record_drop(result, [model%pole(worst)], &
                                 merge(dropped_boundary, dropped_by_criterion, narrowest(model%pole(worst), &
                                                                                         data%min_decay)))
                model = trial
                removed = .true.
                return
            end if
        end do
    end subroutine drop_mode

    !> Whether a mode narrower than one line (2*xi*f < df) only takes up an outlier line: the
    !> model without it, refitted without the line of largest residual next to its frequency,
    !> leaves that line alone far off (`without_line`), and has, with the line's 2 values
    !> freed, a lower MDL criterion than with the mode (4 parameters). A real under-resolved
    !> mode also lifts the lines beside its peak (its tails r/(i*(omega - omega_k))), so its
    !> removal leaves no lone line. Then the model becomes the one without the mode, `line`
    !> the outlier (index in data), else 0.
    subroutine spike_mode(data, model, result, line, error)
        type(data_type), intent(in) :: data
        type(model_type), intent(inout) :: model
        type(ml_result), intent(inout) :: result
        integer, intent(out) :: line
        type(error_type), allocatable, intent(out) :: error

        type(model_type) :: trial
        type(data_type) :: without
        complex(dp) :: residual(size(data%g))
        real(dp) :: before
        integer :: k, near
        logical :: alone

        line = 0
        before = criterion(data, model, chi_square(data, model))
        do k = 1, size(model%pole)
            if (-real(model%pole(k), dp) >= two_pi*resolvable_width*data%df) cycle
            trial = model
            trial%pole = [model%pole(:k - 1), model%pole(k + 1:)]
            call fit(data, trial, result, error)
            if (allocated(error)) return
            residual(:) = data%weight*(data%g - evaluate(trial, data%omega))
            near = minloc(abs(data%omega - aimag(model%pole(k))), 1)
            near = near - 2 + maxloc(abs(residual(max(1, near - 1):min(size(residual), near + 1))), 1) &
                   + merge(1, 0, near == 1)
            call without_line(data, near, data%max_iterations, trial, result, without, alone, error)
            if (allocated(error)) return
            if (.not. alone) cycle
            if (criterion(without, trial, chi_square(without, trial)) + 2.0_dp*data%penalty < before) then
                call record_drop(result, [model%pole(k)], dropped_boundary)
                model = trial
                line = near
                return
            end if
        end do
    end subroutine spike_mode

    !> The mode to drop when the information is singular: of the two closest poles the one
    !> with the smaller residue, or the smallest residue when no two poles are within 0.1 %.
    pure integer function merged(model)
        type(model_type), intent(in) :: model

        real(dp) :: closest, d
        integer :: i, j

        merged = minloc(abs(model%residue), 1)
        closest = 1.0e-3_dp
        do i = 1, size(model%pole)
            do j = i + 1, size(model%pole)
                d = abs(model%pole(i) - model%pole(j))/abs(model%pole(i))
                if (d < closest) then
                    closest = d
                    merged = merge(i, j, abs(model%residue(i)) < abs(model%residue(j)))
                end if
            end do
        end do
    end function merged

    !> x^T inv(C) x for a 2 x 2 covariance C (huge when C is singular).
    pure real(dp) function quadratic(c, x)
        real(dp), intent(in) :: c(2, 2), x(2)

        real(dp) :: det

        det = c(1, 1)*c(2, 2) - c(1, 2)*c(2, 1)
        quadratic = huge(1.0_dp)
        if (det > 0.0_dp) quadratic = (c(2, 2)*x(1)**2 - (c(1, 2) + c(2, 1))*x(1)*x(2) + c(1, 1)*x(2)**2)/det
    end function quadratic

    !> Remove R_u (upper = .true.) or R_l from the model when the model without it, its
    !> residues and other term refitted for the current poles, lowers MDL; the kept model is
    !> then refined. Without the poles refitted the removal is judged conservatively.
    subroutine drop_term(data, model, result, upper, error)
        type(data_type), intent(in) :: data
        type(model_type), intent(inout) :: model
        type(ml_result), intent(inout) :: result
        logical, intent(in) :: upper
        type(error_type), allocatable, intent(out) :: error

        type(model_type) :: trial

        trial = model
        if (upper) then
            if (.not. model%upper) return
            trial%upper = .false.
            trial%r_u = 0.0_dp
        else
            if (.not. model%lower) return
            trial%lower = .false.
            trial%r_l = 0.0_dp
        end if
        call fit(data, trial, result, error, 0)
        if (allocated(error)) return
        if (criterion(data, trial, chi_square(data, trial)) < criterion(data, model, chi_square(data, model))) then
            model = trial
            call refine(data, model, result)
        end if
    end subroutine drop_term

    !> Fill the result: modes sorted by frequency with their standard deviations, chi2, E, the
    !> rescaled noise level and the warnings.
    subroutine finish(frf, data, options, model, result)
        type(frf_type), intent(in) :: frf
        type(data_type), intent(in) :: data
        type(ml_options), intent(in) :: options
        type(model_type), intent(in) :: model
        type(ml_result), intent(inout) :: result

        real(dp), allocatable :: fisher(:, :), gradient(:), cov(:, :), jac(:, :), jac_t(:, :)
        real(dp) :: scale, a, b, m, gf(2), gx(2), band, spacing
        integer :: k, c, n, j
        integer, allocatable :: index(:)
        logical :: ok
        type(modal_set) :: unsorted
        character(len=:), allocatable :: excess

        n = size(model%pole)
        result%chi_square = chi_square(data, model)
        result%dof = 2*size(data%g) - n_parameters(model)
        result%explained = result%chi_square/result%dof <= 1.0_dp + 3.0_dp*sqrt(2.0_dp/result%dof)
        scale = 1.0_dp
        if (result%noise_estimated) scale = result%chi_square/result%dof
        result%noise_level_fit = result%noise_level*sqrt(result%chi_square/result%dof)
        result%has_upper = model%upper
        result%has_lower = model%lower
        result%upper_residual = model%r_u
        result%lower_residual = model%r_l
        allocate (unsorted%pole(n), unsorted%residue(n))
        unsorted%pole(:) = model%pole
        unsorted%residue(:) = model%residue
        result%modes = sorted_by_frequency(unsorted)
        allocate (result%sigma_frequency(n), result%sigma_damping(n), result%sigma_residue(n))
        result%sigma_frequency = huge(1.0_dp)
        result%sigma_damping = huge(1.0_dp)
        result%sigma_residue = huge(1.0_dp)
        call information(data, model, fisher, gradient, jac, jac_t)
        call covariance(fisher, cov, ok)
        allocate (index(n))
        do k = 1, n
            index(k) = minloc(abs(model%pole - result%modes%pole(k)), 1)
        end do
        if (ok) then
            cov = scale*cov
            do k = 1, n
                j = index(k)
                c = 4*(j - 1)
                a = real(model%pole(j), dp)
                b = aimag(model%pole(j))
                m = abs(model%pole(j))
                gf = [a, b]/m/two_pi
                gx = [-b**2, a*b]/m**3
                result%sigma_frequency(k) = sqrt(dot_product(gf, matmul(cov(c + 1:c + 2, c + 1:c + 2), gf)))
                result%sigma_damping(k) = sqrt(dot_product(gx, matmul(cov(c + 1:c + 2, c + 1:c + 2), gx)))
                result%sigma_residue(k) = sqrt(cov(c + 3, c + 3) + cov(c + 4, c + 4))
            end do
        else
            call add_warning(result, 'the Fisher information of the final model is singular (a residual ' &
                             //'term the data do not determine): uncertainties not available (written as huge)')
        end if
        result%e = error_e(data%g, evaluate(model, data%omega))
        do k = 1, n
            band = 2.0_dp*damping_ratio(result%modes%pole(k))*natural_frequency(result%modes%pole(k))/two_pi
            spacing = frf%df()
            if (.not. frf%uniform_from_zero()) spacing = spacing_at(frf, natural_frequency(result%modes%pole(k))/two_pi)
            if (band < options%min_band_lines*spacing) then
                call add_warning(result, 'under-resolved mode at '//real_text(natural_frequency( &
                                 result%modes%pole(k))/two_pi)//' Hz: its half-power band 2*xi*f = ' &
                                 //real_text(band)//' Hz holds fewer than '//real_text(options%min_band_lines) &
                                 //' lines (df = '//real_text(spacing)//' Hz); its damping and residue rest ' &
                                 //'on the few lines near the peak: use a finer frequency step')
            end if
        end do
        call outlier_excess(frf, data, options, model, result)
        do k = 1, size(result%outlier_line)
            excess = real_text(result%outlier_excess(k))
            if (result%outlier_excess(k) >= 1.0e300_dp) excess = 'more than 1e300'
            call add_warning(result, 'line '//int_text(result%outlier_line(k))//' at ' &
                             //real_text(result%outlier_frequency(k))//' Hz left out as an outlier (|G - model| = ' &
                             //excess//' sigma, its neighbours within the noise)')
        end do
        if (.not. result%explained) then
            call add_warning(result, 'the residual is not explained by the noise (chi2/nu = ' &
                             //real_text(result%chi_square/result%dof)//'): a mode may be missing or the ' &
                             //'noise model may not fit; check the residual')
        end if
    end subroutine finish

    !> |G_l - G_model|/sigma_l of each outlier line against the final model (sigma_l as the
    !> fit's weights take it: given, absolute, or level*|G_model|), at most huge.
    pure subroutine outlier_excess(frf, data, options, model, result)
        type(frf_type), intent(in) :: frf
        type(data_type), intent(in) :: data
        type(ml_options), intent(in) :: options
        type(model_type), intent(in) :: model
        type(ml_result), intent(inout) :: result

        complex(dp) :: g_model(1)
        real(dp) :: sigma, misfit
        integer :: k, l

        do k = 1, size(result%outlier_line)
            l = result%outlier_line(k)
            g_model = evaluate(model, [two_pi*frf%frequency(l)])
            if (allocated(options%sigma)) then
                sigma = options%sigma(l)
            else if (data%relative) then
                sigma = max(data%level, options%noise_floor)*abs(g_model(1))
            else
                sigma = data%level
            end if
            misfit = abs(frf%receptance(l) - g_model(1))
            result%outlier_excess(k) = huge(1.0_dp)
            if (sigma > 0.0_dp .and. misfit > 0.0_dp) then
                result%outlier_excess(k) = exp(min(log(misfit) - log(sigma), log(huge(1.0_dp))))
            else if (sigma > 0.0_dp) then
                result%outlier_excess(k) = 0.0_dp
            end if
        end do
    end subroutine outlier_excess

    !> Append a warning ('; ' between warnings).
    pure subroutine add_warning(result, text)
        type(ml_result), intent(inout) :: result
        character(len=*), intent(in) :: text

        if (len(result%warning) > 0) result%warning = result%warning//'; '
        result%warning = result%warning//text
    end subroutine add_warning

    !> Real and imaginary parts of each column stacked: [Re; Im].
    pure function stacked(z) result(a)
        complex(dp), intent(in) :: z(:, :)
        real(dp) :: a(2*size(z, 1), size(z, 2))

        a(1:size(z, 1), :) = real(z, dp)
        a(size(z, 1) + 1:, :) = aimag(z)
    end function stacked

    !> [Re z; Im z].
    pure function stacked_vector(z) result(v)
        complex(dp), intent(in) :: z(:)
        real(dp) :: v(2*size(z))

        v(1:size(z)) = real(z, dp)
        v(size(z) + 1:) = aimag(z)
    end function stacked_vector

end module greenconv_ident_mlfit
