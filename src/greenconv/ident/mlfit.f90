!> Maximum-likelihood identification of a noisy receptance: the modes, their
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
!>    whose median is ln 2). For `floor` (sigma_l^2 = (rho*|G_l|)^2 + s^2, a measurement's
!>    relative noise over a coherence-limited floor s [m/N]) E|d_l|^2 = rho^2*a_l + s^2 with
!>    a_l = sum_j c_j^2*|G_{l+j}|^2: rho and s from those medians in 16 groups of lines sorted
!>    by a_l (noise_model's estimate_floor_noise); the weights and the final fit use both, the
!>    uncertainty too. Suite identreal: 0.1 and 1 % plus a floor of 1e-3 of the peak, the 12
!>    modes of (a) within 2.7 CRB sigma, the floor within 20 %; `relative` invents modes there.
!>    For `band` (sigma_l = rho_b*|G_l|, a measurement whose noise changes along the band) rho_b
!>    from the median of the relative differences in each of at most 32 bands of lines. `auto`
!>    runs the whole identification under `relative`, `floor` and `band` and keeps the one of the
!>    smallest full likelihood criterion (full_criterion: chi2 alone cannot compare noise models). Bias: the lines near sharp resonances, where the difference sees
!>    the signal, are outliers the median mostly ignores; a fraction eps of them raises the
!>    median to the 0.5/(1 - eps) quantile, rho^2 too high by about 1.4*eps (7 % for 5 % of
!>    the lines); the measured |G| in the denominator adds O(rho^2). A floor `noise_floor`*|G_l|
!>    (1e-13) keeps clean data fittable to round-off. The order choice below compares chi2 of
!>    models, so it depends on the level only through its scale; the uncertainties use the
!>    level refitted from the final residual (noise_level_fit, unbiased for the right model).
!>    Weights of the relative model: during the order search rho times the rms of |G| over 5
!>    lines, each |G| clipped at ten times their median (the noise of |G| in the weight reduced
!>    by sqrt(5), independent of any model, so the chi2 of different models stay comparable
!>    without a refit after each change; one outlier line moves no weight), at least 1e-4 of
!>    the largest such sigma (`dynamic_range`: an FRF rolling off as omega^-10 otherwise has
!>    the fit ruled by its tail and its resonances thrown out); for the final fit and the
!>    uncertainty rho*|G_model|, again at least 1e-4 of the largest (lm_fit's `within_range`).
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
!>    With `global_search` (the default) the fits are projected and death moves follow the
!>    greedy rounds (greenconv_ident_order_search), so that the model is the MDL minimum, not
!>    a neighbour of it. That search trusts the likelihood: when its final residual is not
!>    explained by the noise model (the chi2 test above fails: measurement errors at the
!>    anti-resonances, modes outside the band the model lacks), the likelihood is misspecified
!>    and pursuing its minimum further can fit the residual's structure with poles (measured
!>    during development: a free-free beam's driving point at 0.1 %, chi2/nu = 1.75, a mode 9.4
!>    sigma_CRB off; pyuff's measured beam, 1 to 7 determined poles besides its six modes). The
!>    identification then runs again from the same start with the greedy rounds alone, and of
!>    the two models returns the one of the lower full likelihood criterion (full_criterion;
!>    within choice_margin the one with fewer poles), with a warning that names the other: two
!>    starts of one likelihood, neither trusted blindly. The free-free beam's greedy model is
!>    2,685 lower; pyuff's measured beam's global models are 360 to 3,100 lower than the greedy
!>    ones (chi2/nu 2.8, 9.6 and 5.0 against 14.6, 21.0 and 4.3 once the fits' sums were fixed),
!>    each with exactly the six modes determined.
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
!>    Against the noise each band of 32 lines shows in the final residual, an in-band pole whose
!>    residue's Wald statistic is below a mode's MDL price 4*ln(2L), or whose sigma_xi/xi
!>    reaches 0.3 while its peak is resolved, whose frequency the lines do not fix, or that
!>    the stabilisation diagram does not confirm, is not determined by the data:
!>    result%determined is false for it (it stays in the model; mark_undetermined says why).
!> Modes whose half-power band 2*xi*f holds fewer than `min_band_lines` lines are reported
!> as under-resolved in the warning (their xi and r rest on the few lines near the peak).
!> 8. **Modes above the band** (`outside_modes = 'auto'`). R_u is the first term of
!>    the modes past f_max; a mode just above the edge (a free-free beam's next bending mode
!>    at 1.1*f_max) bends G near the edge far more than a constant: the fit then pulls the
!>    highest modes (635 CRB sigma at 0.1 % on suite outofband's beam, chi2/nu 7e3). After the
!>    model above is final, one pole is started at 1.05, 1.2, 1.5 and 2.5*f_max (xi 0.02) and
!>    fitted with it; the best is kept when it lowers the MDL criterion (4*ln(2L) for its four
!>    parameters) and stays above f_max, the order search runs again with poles up to 10*f_max
!>    allowed (a heavily damped in-band pole that stood for the missing term is then dropped),
!>    and the model is refined as before; then another, at most 3. The poles above f_max are
!>    the result's `outside` pseudo-modes: part of its receptance, not of its modes.
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
!> and stopped at a chi2 fall below 1); 0.46 s since J^T J is one triangle by blocks, the model
!> takes one real division per line and pole, and the Cholesky steps are LAPACK's
!> (greenconv_ident_dense; 50 modes: 19.1 to 9.0 s, the same 262 iterations).
!>
!> ## Parts
!> This module is the entry: `identify_ml`, the checks of its input, the passes restarted after
!> an outlier and the final result (step 7, the warnings). The steps are modules of their own:
!> greenconv_ident_ml_types (`ml_options`, `ml_result`, re-exported here), greenconv_ident_noise_model
!> (step 1, the gross outliers), greenconv_ident_diagram (steps 2 and 3), greenconv_ident_lm_fit
!> (step 4), greenconv_ident_order_search (steps 5 and 6 and the clean-up of the final model).
module greenconv_ident_mlfit
    use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
    use greenconv_core_kinds, only: dp
    use greenconv_core_error, only: error_type, fatal_error
    use greenconv_core_text, only: int_text, real_text, trimmed_real_text
    use greenconv_model_modal_set, only: modal_set, sorted_by_frequency
    use greenconv_model_frf, only: frf_type
    use greenconv_ident_lsce, only: error_e, natural_frequency, damping_ratio, receptance_problem
    use greenconv_ident_ml_types, only: ml_options, ml_result, add_warning, dropped_by_criterion, &
                                        dropped_left_band, dropped_degenerate, dropped_boundary, max_lines
    use greenconv_ident_dense, only: quadratic_form
    use greenconv_ident_lm_fit, only: model_type, data_type, final_tolerance, evaluate, chi_square, &
                                      n_parameters, fit, reweight, information, covariance, widened, criterion
    use greenconv_ident_noise_model, only: estimate_noise, smoothed_magnitude, prepare_data, gross_outliers, &
                                           interpolated, spacing_at, band_bounds
    use greenconv_ident_diagram, only: build_diagram
    use greenconv_ident_order_search, only: choose_order, drop_outside, drop_needles, drop_undetermined, prune_terms
    implicit none
    private

    public :: ml_options, ml_result, identify_ml, estimate_noise, smoothed_magnitude
    public :: dropped_by_criterion, dropped_left_band, dropped_degenerate, dropped_boundary, max_lines
    public :: search_iterations, max_outside, outside_start

    real(dp), parameter :: two_pi = 2.0_dp*3.141592653589793238462643383279_dp

    !> Most Levenberg-Marquardt iterations of any fit during the order search (the final model
    !> is then refined with up to ml_options%max_iterations).
    integer, parameter :: search_iterations = 10
    !> Fall of chi2 in one iteration below which a fit of the order search stops: a fortieth of
    !> a mode's MDL price 4*ln(2L), too little to change a decision.
    real(dp), parameter :: search_tolerance = 1.0_dp
    !> Start frequencies of a pseudo-mode above the band, as multiples of f_max, and its start
    !> damping ratio: the fit moves it where the data ask.
    real(dp), parameter :: outside_start(4) = [1.05_dp, 1.2_dp, 1.5_dp, 2.5_dp]
    real(dp), parameter :: outside_damping = 0.02_dp
    !> Poles up to this multiple of f_max stay in the model as pseudo-modes once they are tried.
    real(dp), parameter :: outside_ceiling = 10.0_dp
    !> Most pseudo-modes tried above the band, one at a time.
    integer, parameter :: max_outside = 3
    !> The noise models noise_model = 'auto' compares by the full likelihood, simplest first.
    character(len=8), parameter :: auto_models(4) = [character(len=8) :: 'relative', 'absolute', 'floor', 'band']
    !> chi2/nu above which 'auto''s first search is taken as lost (far from any model the noise
    !> explains) and its poles screen no other noise model: each is searched.
    real(dp), parameter :: lost_search = 1.0e3_dp
    !> Smallest fall of the full likelihood criterion for which 'auto' takes a later noise model of
    !> auto_models over an earlier one (a tenth of the MDL price of a parameter for 8193 lines).
    real(dp), parameter :: choice_margin = 1.0_dp
    !> An in-band pole whose sigma_xi/xi reaches this (or whose residue's evidence does not pay
    !> for the mode, see mark_undetermined) is not determined by the data: not reported as a mode.
    real(dp), parameter :: undetermined_spread = 0.3_dp
    !> MDL price of a mode in units of ln(2L): its four real parameters.
    real(dp), parameter :: mode_price = 4.0_dp
    !> Largest damping ratio of a mode with a resonance peak, 1/sqrt(2): a pole more damped is
    !> never reported as determined (mark_undetermined).
    real(dp), parameter :: peak_damping = 0.7071067811865476_dp
    !> Wald statistic of a residue, in mode prices, that needs no confirmation by the
    !> stabilisation diagram (mark_undetermined).
    real(dp), parameter :: strong_evidence = 1000.0_dp
    !> Widest relative distance of a close pair whose partner's diagram poles confirm a pole
    !> (confirmations_of).
    real(dp), parameter :: pair_span = 0.05_dp
    !> Lines per band of the noise scale the determined rule uses (band_scale).
    integer, parameter :: scale_lines = 32

contains

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

        type(ml_options) :: trial_options
        type(ml_result) :: trial
        real(dp) :: criteria(size(auto_models))
        logical :: searched(size(auto_models)), screen
        integer :: i, best

        call check_input(frf, options, error)
        if (allocated(error)) return
        if (options%noise_model /= 'auto' .or. allocated(options%sigma)) then
            call identify_searched(frf, options, result, error)
            return
        end if
        ! 'auto': the whole identification under the first noise model (relative); each other
        ! model refits that model's poles under its own weights (`screened_criterion`), and only a
        ! model that wins there by more than choice_margin has the whole identification run under
        ! it. The full likelihood (the noise scale refitted, every parameter priced, noise model
        ! included) decides; within choice_margin the earlier of auto_models (the simpler) is
        ! kept, so that a last-bit difference of two criteria decides nothing. A first search that
        ! ends far from its noise model (chi2/nu above lost_search) screens nothing: its poles are
        ! no place to refit the others at, and every other model is searched.
        trial_options = options
        trial_options%noise_model = auto_models(1)
        call identify_searched(frf, trial_options, result, error)
        if (allocated(error)) return
        criteria(1) = result%likelihood_criterion
        searched(:) = .false.
        searched(1) = .true.
        best = 1
        screen = reduced_chi_square(result) <= lost_search
        do i = 2, size(auto_models)
            trial_options%noise_model = auto_models(i)
            if (screen) then
                call screened_criterion(frf, trial_options, result, criteria(i), error)
                if (allocated(error)) return
                if (criteria(i) >= criteria(best) - choice_margin) cycle
            end if
            call identify_searched(frf, trial_options, trial, error)
            if (allocated(error)) return
            searched(i) = .true.
            criteria(i) = trial%likelihood_criterion
            if (criteria(i) < criteria(best) - choice_margin) then
                result = trial
                best = i
            end if
        end do
        result%noise_choice = 'chosen from the data by the full likelihood with its MDL price (criterion of'
        do i = 1, size(auto_models)
            if (i == best) cycle
            result%noise_choice = result%noise_choice//' '//trim(auto_models(i))//' ' &
                                  //trim(merge('+', ' ', criteria(i) >= criteria(best))) &
                                  //trimmed_real_text(criteria(i) - criteria(best), 0.1_dp, 1.0e7_dp, 1, 2) &
                                  //trim(merge(' ', '*', searched(i)))
        end do
        result%noise_choice = result%noise_choice//' against it; *: refitted at the first search''s poles, ' &
                              //'not searched)'
    end subroutine identify_ml

    !> The full likelihood criterion of an identified model refitted under another noise model
    !> (options%noise_model), without an order search: its lines (the outliers it left out
    !> stay out), the other model's noise estimated from the receptance, the poles, residues and
    !> residual terms refined with the final weights and settings, and the criterion of
    !> `full_criterion`. identify_ml's 'auto' searches under a noise model only when it beats
    !> the identified one here by choice_margin: the search would start from the diagram and
    !> price each mode again, which moves the criterion by far less than the wrong noise model's
    !> misfit on a receptance whose noise that model describes (tens of thousands on 8,193
    !> lines, against a mode's price of 4*ln(2L) = 39).
    subroutine screened_criterion(frf, options, identified, value, error)
        !> The receptance.
        type(frf_type), intent(in) :: frf
        !> Settings with the noise model to screen.
        type(ml_options), intent(in) :: options
        !> The model identified under another noise model.
        type(ml_result), intent(in) :: identified
        !> Its full likelihood criterion under options%noise_model.
        real(dp), intent(out) :: value
        !> Set when the criterion is not finite.
        type(error_type), allocatable, intent(out) :: error

        type(ml_result) :: screen
        type(data_type) :: data
        type(model_type) :: model
        type(frf_type) :: repaired

        allocate (screen%outlier_line(0), screen%outlier_frequency(0), screen%outlier_excess(0))
        repaired = frf
        call gross_outliers(repaired, screen)
        call prepare_data(repaired, identified%outlier_line, &
                          any(options%residual_terms == [character(len=8) :: 'auto', 'lower', 'both']), options, &
                          screen, data)
        screen%outlier_line = identified%outlier_line
        model%pole = [identified%modes%pole, identified%outside%pole]
        model%residue = [identified%modes%residue, identified%outside%residue]
        model%upper = identified%has_upper
        model%lower = identified%has_lower
        model%r_u = identified%upper_residual
        model%r_l = identified%lower_residual
        data%max_iterations = options%max_iterations
        data%tolerance = final_tolerance
        call reweight(data, model, screen%iterations)
        screen%chi_square = chi_square(data, model)
        value = full_criterion(data, model, screen)
        if (.not. ieee_is_finite(value)) call fatal_error(error, "identify_ml: the noise model '" &
                                                          //trim(options%noise_model)//"' gave a criterion " &
                                                          //'that is not finite')
    end subroutine screened_criterion

    !> identify_ml under one noise model (not 'auto'), the input checked: with the global
    !> search first; when its residual is not explained by the noise model, again with the
    !> greedy rounds alone, and the model of the lower full likelihood criterion is returned
    !> (step 5 of the description).
    subroutine identify_searched(frf, options, result, error)
        type(frf_type), intent(in) :: frf
        type(ml_options), intent(in) :: options
        type(ml_result), intent(out) :: result
        type(error_type), allocatable, intent(out) :: error

        type(ml_options) :: greedy_options
        type(ml_result) :: global

        call identify_with(frf, options, result, error)
        if (allocated(error) .or. .not. options%global_search .or. result%explained) return
        global = result
        greedy_options = options
        greedy_options%global_search = .false.
        call identify_with(frf, greedy_options, result, error)
        if (allocated(error)) return
        ! Two starts of one likelihood: the full criterion (the noise scale refitted, every
        ! parameter priced) keeps the better model; within choice_margin, the one with fewer poles.
        if (global%likelihood_criterion < result%likelihood_criterion - choice_margin .or. &
            (abs(global%likelihood_criterion - result%likelihood_criterion) <= choice_margin .and. &
             size(global%modes%pole) < size(result%modes%pole))) then
            call add_warning(global, 'the global order search''s residual is not explained by the noise model ' &
                             //'(chi2/nu = '//trim(real_text(reduced_chi_square(global)))//'); the greedy ' &
                             //'search''s model (chi2/nu = '//trim(real_text(reduced_chi_square(result)))//', ' &
                             //int_text(size(result%modes%pole))//' poles) has a full likelihood criterion ' &
                             //trim(real_text(result%likelihood_criterion - global%likelihood_criterion)) &
                             //' higher: this is the global search''s model')
            result = global
            return
        end if
        call add_warning(result, 'the global order search''s residual is not explained by the noise model ' &
                         //'(chi2/nu = '//trim(real_text(reduced_chi_square(global)))//'; ' &
                         //int_text(size(global%modes%pole))//' poles, '//int_text(count(global%determined)) &
                         //' determined); the greedy search''s model has the lower full likelihood criterion ' &
                         //'(by '//trim(real_text(global%likelihood_criterion - result%likelihood_criterion)) &
                         //'): this is its model')
    end subroutine identify_searched

    !> chi2/nu of a result.
    pure real(dp) function reduced_chi_square(result)
        !> The result.
        type(ml_result), intent(in) :: result

        reduced_chi_square = result%chi_square/max(result%dof, 1)
    end function reduced_chi_square

    !> identify_ml under one noise model (not 'auto'), the input checked.
    subroutine identify_with(frf, options, result, error)
        type(frf_type), intent(in) :: frf
        type(ml_options), intent(in) :: options
        type(ml_result), intent(out) :: result
        type(error_type), allocatable, intent(out) :: error

        type(data_type) :: data
        type(model_type) :: model
        type(frf_type) :: repaired
        complex(dp), allocatable :: start(:), candidates(:)
        integer :: outlier, pass
        logical :: allow_lower

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
            call fit(data, model, result%iterations, error)
            if (allocated(error)) return
            call choose_order(data, options, candidates, model, result, outlier, pass > options%outlier_restarts, &
                              error)
            if (allocated(error)) return
            if (outlier == 0) exit
            repaired%receptance(outlier) = interpolated(repaired%receptance, result%outlier_line, outlier)
        end do
        call refine_final(data, options, model, result, error)
        if (allocated(error)) return
        if (options%outside_modes == 'auto') then
            call try_outside(data, options, candidates, model, result, error)
            if (allocated(error)) return
        end if
        if (data%projection .and. options%residual_terms == 'auto') then
            call prune_terms(data, model, result, error)
            if (allocated(error)) return
        end if
        call finish(frf, data, options, model, result)
    end subroutine identify_with

    !> Modes above the band as pseudo-modes (step 8 of the description): one pole started above
    !> f_max at each of outside_start, fitted with the model; the best kept when it lowers the
    !> MDL criterion (its four parameters paid for) and stays above f_max, and tried again for
    !> another one, at most max_outside, while the model has fewer than max_modes poles. After each the order search runs again with poles up to outside_ceiling*f_max allowed (a mode near the upper edge
    !> that the constant R_u could not stand for was missed or bent before) and the model is
    !> refined as the first time. The model is unchanged when no pseudo-mode pays.
    subroutine try_outside(data, options, candidates, model, result, error)
        type(data_type), intent(inout) :: data
        type(ml_options), intent(in) :: options
        complex(dp), intent(in) :: candidates(:)
        type(model_type), intent(inout) :: model
        type(ml_result), intent(inout) :: result
        type(error_type), allocatable, intent(out) :: error

        type(model_type) :: trial, best
        real(dp) :: f_band, best_criterion, trial_criterion
        integer :: i, n, outlier, added

        f_band = data%f_max
        data%max_iterations = min(options%max_iterations, search_iterations)
        data%tolerance = search_tolerance
        data%f_max = outside_ceiling*f_band
        do added = 0, max_outside - 1
            ! A pseudo-mode counts as a mode of the model: never more than max_modes poles.
            if (size(model%pole) >= data%max_modes) exit
            best_criterion = criterion(data, model, chi_square(data, model))
            if (allocated(best%pole)) deallocate (best%pole, best%residue)
            n = size(model%pole) + 1
            do i = 1, size(outside_start)
                trial = model
                trial%pole = [model%pole, two_pi*outside_start(i)*f_band &
                              *cmplx(-outside_damping, sqrt(1.0_dp - outside_damping**2), dp)]
                trial%residue = [model%residue, (0.0_dp, 0.0_dp)]
                call fit(data, trial, result%iterations, error)
                if (allocated(error)) return
                trial_criterion = criterion(data, trial, chi_square(data, trial))
                if (trial_criterion < best_criterion .and. natural_frequency(trial%pole(n)) > two_pi*f_band) then
                    best = trial
                    best_criterion = trial_criterion
                end if
            end do
            if (.not. allocated(best%pole)) exit
            model = best
            call choose_order(data, options, candidates, model, result, outlier, .true., error)
            if (allocated(error)) return
        end do
        if (added == 0) then
            data%max_iterations = options%max_iterations
            data%tolerance = final_tolerance
            data%f_max = f_band
            return
        end if
        call refine_final(data, options, model, result, error)
    end subroutine try_outside

    !> The model the search chose, refined with the final weights and settings (all iterations,
    !> final_tolerance), then cleaned: poles outside the allowed band, needles, modes the data
    !> do not determine.
    subroutine refine_final(data, options, model, result, error)
        type(data_type), intent(inout) :: data
        type(ml_options), intent(in) :: options
        type(model_type), intent(inout) :: model
        type(ml_result), intent(inout) :: result
        type(error_type), allocatable, intent(out) :: error

        data%max_iterations = options%max_iterations
        data%tolerance = final_tolerance
        call reweight(data, model, result%iterations)
        call drop_outside(data, model, result, error)
        if (allocated(error)) return
        call drop_needles(data, model, result, error)
        if (allocated(error)) return
        call drop_undetermined(data, model, result, error)
    end subroutine refine_final

    !> Reject inputs that cannot be used.
    subroutine check_input(frf, options, error)
        !> The receptance (any increasing grid from 0 Hz or above).
        type(frf_type), intent(in) :: frf
        !> Maximum-likelihood settings (sigma, when given, one per line).
        type(ml_options), intent(in) :: options
        !> Set on the first problem found.
        type(error_type), allocatable, intent(out) :: error

        character(len=:), allocatable :: problem

        problem = receptance_problem(frf)
        if (len(problem) > 0) then
            call fatal_error(error, 'identify_ml: '//problem)
        else if (frf%n_freq() > max_lines) then
            call fatal_error(error, 'identify_ml: the FRF has '//int_text(frf%n_freq())//' lines, more than the ' &
                             //int_text(max_lines)//' it takes (memory and time grow with the lines); use a ' &
                             //'coarser step or a narrower band')
        else if (.not. any(abs(frf%receptance(2:)) > 0.0_dp)) then
            call fatal_error(error, 'identify_ml: the receptance is zero on every line above 0 Hz: nothing to fit')
        else if (options%max_order < 1 .or. options%stable_orders < 1) then
            call fatal_error(error, 'identify_ml: max_order and stable_orders must be >= 1')
        else if (.not. any(options%residual_terms == [character(len=8) :: 'auto', 'none', 'upper', 'lower', &
                                                      'both'])) then
            call fatal_error(error, "identify_ml: residual_terms must be 'auto', 'none', 'upper', 'lower' or " &
                             //"'both', found '"//trim(options%residual_terms)//"'")
        else if (all(options%noise_model /= [character(len=8) :: 'relative', 'absolute', 'floor', 'band', 'auto'])) then
            call fatal_error(error, "identify_ml: noise_model must be 'relative', 'absolute', 'floor', 'band' or " &
                             //"'auto', found '"//trim(options%noise_model)//"'")
        else if (all(options%outside_modes /= [character(len=8) :: 'auto', 'none'])) then
            call fatal_error(error, "identify_ml: outside_modes must be 'auto' or 'none', found '" &
                             //trim(options%outside_modes)//"'")
        end if
        if (allocated(error)) return
        if (allocated(options%sigma)) then
            if (size(options%sigma) /= frf%n_freq() .or. .not. all(options%sigma >= 0.0_dp)) then
                call fatal_error(error, 'identify_ml: sigma must hold one standard deviation >= 0 per line (' &
                                 //int_text(frf%n_freq())//' lines), found '//int_text(size(options%sigma)))
            end if
        end if
    end subroutine check_input

    !> Fill the result: modes sorted by frequency with their standard deviations, chi2, E, the
    !> rescaled noise level and the warnings.
    subroutine finish(frf, data, options, model, result)
        type(frf_type), intent(in) :: frf
        type(data_type), intent(in) :: data
        type(ml_options), intent(in) :: options
        type(model_type), intent(in) :: model
        type(ml_result), intent(inout) :: result

        real(dp), allocatable :: fisher(:, :), gradient(:), cov(:, :), jac(:, :)
        real(dp) :: scale, a, b, m, gf(2), gx(2), band, spacing
        integer :: k, c, n, j
        integer, allocatable :: index(:)
        logical :: ok
        logical, allocatable :: inside(:), narrow(:)
        type(modal_set) :: unsorted, outside
        character(len=:), allocatable :: excess

        ! Poles above the band are the pseudo-modes of try_outside: part of the model, not modes.
        inside = natural_frequency(model%pole) <= two_pi*frf%f_max()
        n = count(inside)
        outside%pole = pack(model%pole, .not. inside)
        outside%residue = pack(model%residue, .not. inside)
        result%outside = sorted_by_frequency(outside)
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
        unsorted%pole = pack(model%pole, inside)
        unsorted%residue = pack(model%residue, inside)
        result%modes = sorted_by_frequency(unsorted)
        allocate (result%sigma_frequency(n), result%sigma_damping(n), result%sigma_residue(n))
        result%sigma_frequency = huge(1.0_dp)
        result%sigma_damping = huge(1.0_dp)
        result%sigma_residue = huge(1.0_dp)
        call information(data, model, fisher, gradient, jac)
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
                result%sigma_frequency(k) = sqrt(quadratic_form(cov(c + 1:c + 2, c + 1:c + 2), gf))
                result%sigma_damping(k) = sqrt(quadratic_form(cov(c + 1:c + 2, c + 1:c + 2), gx))
                result%sigma_residue(k) = sqrt(cov(c + 3, c + 3) + cov(c + 4, c + 4))
            end do
        else
            call add_warning(result, 'the Fisher information of the final model is singular (a residual ' &
                             //'term the data do not determine): uncertainties not available (written as huge)')
        end if
        result%e = error_e(data%g, evaluate(model, data%omega))
        result%likelihood_criterion = full_criterion(data, model, result)
        allocate (narrow(n))
        do k = 1, n
            band = 2.0_dp*damping_ratio(result%modes%pole(k))*natural_frequency(result%modes%pole(k))/two_pi
            spacing = frf%df()
            if (.not. frf%uniform_from_zero()) spacing = spacing_at(frf, natural_frequency(result%modes%pole(k))/two_pi)
            narrow(k) = band < options%min_band_lines*spacing
            if (narrow(k)) then
                call add_warning(result, 'under-resolved mode at '//real_text(natural_frequency( &
                                 result%modes%pole(k))/two_pi)//' Hz: its half-power band 2*xi*f = ' &
                                 //real_text(band)//' Hz holds fewer than '//real_text(options%min_band_lines) &
                                 //' lines (df = '//real_text(spacing)//' Hz); its damping and residue rest ' &
                                 //'on the few lines near the peak: use a finer frequency step')
            end if
        end do
        ! A singular information leaves the uncertainties unknown: no mode is then claimed determined.
        result%determined = spread(ok, 1, n)
        if (ok) call mark_undetermined(data, options, model, index, narrow, result)
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

    !> The full likelihood criterion of the final model (ml_result%likelihood_criterion): with
    !> sigma_l = c*s_l (s_l the fit's 1/weight) and the scale c refitted, -2 ln(likelihood) is
    !> 2L*ln(chi2/(2L)) + 2L + 2*sum ln s_l^2 up to a constant (each line's complex Gaussian has
    !> density exp(-|e_l|^2/sigma_l^2)/(pi*sigma_l^2)); MDL adds ln(2L) per parameter of the model
    !> and of the noise model and 2*ln(2L) per outlier line left out.
    pure real(dp) function full_criterion(data, model, result) result(value)
        type(data_type), intent(in) :: data
        type(model_type), intent(in) :: model
        type(ml_result), intent(in) :: result

        real(dp) :: two_l

        two_l = 2.0_dp*size(data%g)
        value = two_l*log(max(result%chi_square, tiny(1.0_dp))/two_l) + two_l - 4.0_dp*sum(log(data%weight)) &
                + (n_parameters(model) + result%noise_parameters + 2*size(result%outlier_line))*data%penalty
    end function full_criterion

    !> Mark the modes the data do not determine in result%determined and say so in a warning.
    !> The rule is judged against the noise the residual shows near each mode: every line's
    !> sigma is scaled by its band's residual (band_scale, at least the noise estimated before the
    !> fit), and with the Fisher information of those lines a pole is a mode when all hold:
    !>  - its residue's Wald statistic for r = 0 (against its 2x2 covariance) is at least a
    !>    mode's MDL price 4*ln(2L): the evidence pays for the mode's four parameters;
    !>  - its sigma_xi/xi is below undetermined_spread, or it is under-resolved (half-power band
    !>    narrower than min_band_lines lines): a peak narrower than the lines gives its
    !>    frequency and residue, not its damping (the warning says so), so its damping's spread
    !>    does not unmake the mode (pyuff's beam at 51.5 Hz: 2*xi*f = 0.05 Hz on 1 Hz lines,
    !>    sigma_xi/xi 0.34, the residue 190 sigma from 0);
    !>  - its sigma_f is below undetermined_spread of its half-power half-width xi*f, or of the
    !>    line spacing when that is wider: a pole whose frequency the lines do not fix to a
    !>    fraction of its own peak is no mode (pyuff's beam, FRF 1: 1.6 Hz at xi 0.88,
    !>    sigma_f 5.4 Hz);
    !>  - its frequency lies between the first and the last line fitted (pyuff's beam, FRF 3:
    !>    0.74 Hz at xi 0.91 on lines from 1 Hz, under OpenBLAS's Sandybridge kernels);
    !>  - it has a resonance peak: xi < 1/sqrt(2) (peak_damping; above it |G| of the mode falls
    !>    from 0 Hz on, a real pole in all but name);
    !>  - the stabilisation diagram confirms it: at least stable_orders of its poles stable in
    !>    frequency (flag 1 or 2) lie within stable_frequency of its frequency (or within xi*f,
    !>    when wider; for one of a close pair, which the linear step merges into one stable pole,
    !>    within the distance to its partner: confirmations_of), unless its residue's Wald
    !>    statistic reaches strong_evidence times the price (a residue some 200 sigma from zero).
    !>    The diagram is the test of physical poles in
    !>    experimental modal analysis: a pole of the structure comes back at every order of the
    !>    linear fit, a pole that takes up noise or a wandering phase does not (pyuff's beam:
    !>    each of its six modes 14 to 41 times under five BLAS set-ups, the poles below 20 Hz on
    !>    the lines whose phase wanders never, their Wald statistics at most 170 prices). It keeps
    !>    the flag off the path the order search took, which follows the last bits of the
    !>    arithmetic: the diagram's poles move by round-off only.
    !> The order search prices a mode against the noise estimated before any fit; where the
    !> lines are noisier than that (pyuff's measured beam below 8 Hz, whose phase wanders by up
    !> to 180 degrees between neighbours: 1e3 to 1e4 times the expected chi2 per line) it buys
    !> poles that this noise does not pay for, while one scale for the whole band (chi2/nu 21
    !> on its FRF 2) would blur the modes where the lines are quiet. Such poles stay in
    !> result%modes (the fitted receptance, the engines' structure and the shared poles keep
    !> them) but are not counted as modes the data give. With the noise given (sigma), the lines
    !> keep it.
    subroutine mark_undetermined(data, options, model, index, narrow, result)
        !> The weighted data of the final fit.
        type(data_type), intent(in) :: data
        !> Settings (stable_orders, stable_frequency: the diagram's confirmation).
        type(ml_options), intent(in) :: options
        !> The final model.
        type(model_type), intent(in) :: model
        !> The model's pole of each of result%modes.
        integer, intent(in) :: index(:)
        !> Whether each of result%modes is under-resolved.
        logical, intent(in) :: narrow(:)
        !> The result: determined is set, a warning added.
        type(ml_result), intent(inout) :: result

        type(data_type) :: local
        real(dp), allocatable :: fisher(:, :), gradient(:), cov(:, :), jac(:, :)
        real(dp) :: a, b, m, gx(2), gf(2), r(2), det, evidence, price, sigma_xi, sigma_f, f, xi, spacing
        integer :: k, c, confirmations
        logical :: ok

        local = data
        if (result%noise_estimated) local%weight = data%weight/sqrt(band_scale(data, model, result%dof))
        call information(local, model, fisher, gradient, jac)
        call covariance(fisher, cov, ok)
        if (.not. ok) then
            ! The rescaled lines leave the information singular: judge against the fit's own noise.
            call information(data, model, fisher, gradient, jac)
            call covariance(fisher, cov, ok)
            if (.not. ok) return
        end if
        price = mode_price*data%penalty
        do k = 1, size(index)
            c = 4*(index(k) - 1)
            a = real(model%pole(index(k)), dp)
            b = aimag(model%pole(index(k)))
            m = abs(model%pole(index(k)))
            gx = [-b**2, a*b]/m**3
            gf = [a, b]/m/two_pi
            sigma_xi = sqrt(quadratic_form(cov(c + 1:c + 2, c + 1:c + 2), gx))
            sigma_f = sqrt(quadratic_form(cov(c + 1:c + 2, c + 1:c + 2), gf))
            f = m/two_pi
            xi = damping_ratio(model%pole(index(k)))
            spacing = line_spacing(data%omega, m)/two_pi
            ! Wald statistic of r_k = 0 against the residue's 2x2 covariance (Re, Im).
            r = [real(model%residue(index(k)), dp), aimag(model%residue(index(k)))]
            det = cov(c + 3, c + 3)*cov(c + 4, c + 4) - cov(c + 3, c + 4)**2
            evidence = huge(1.0_dp)
            if (det > 0.0_dp) evidence = (cov(c + 4, c + 4)*r(1)**2 - 2.0_dp*cov(c + 3, c + 4)*r(1)*r(2) &
                                          + cov(c + 3, c + 3)*r(2)**2)/det
            confirmations = confirmations_of(result, options, model%pole, index(k))
            result%determined(k) = evidence >= price &
                                   .and. (narrow(k) .or. sigma_xi < undetermined_spread*xi) &
                                   .and. sigma_f < undetermined_spread*max(xi*f, spacing) &
                                   .and. xi < peak_damping &
                                   .and. m >= data%omega(1) .and. m <= data%omega(size(data%omega)) &
                                   .and. (confirmations >= options%stable_orders .or. evidence >= strong_evidence*price)
        end do
        if (all(result%determined)) return
        call add_warning(result, int_text(count(.not. result%determined))//' pole(s) in the band the data do ' &
                         //'not determine against the noise their lines show (the Wald statistic of the residue ' &
                         //'below the MDL price of a mode, '//real_text(price)//', sigma_xi/xi >= ' &
                         //real_text(undetermined_spread)//' for a resolved peak, sigma_f >= ' &
                         //real_text(undetermined_spread)//' of its half-power half-width, xi >= 1/sqrt(2), outside the ' &
                         //'lines, or fewer than '//int_text(options%stable_orders)//' stable poles of the diagram ' &
                         //'near it without overwhelming evidence): part ' &
                         //'of the fitted receptance, not modes the data give')
    end subroutine mark_undetermined

    !> The number of the diagram's poles stable in frequency (flag 1 or 2) within window [Hz]
    !> of f [Hz].
    pure integer function diagram_support(result, f, window)
        !> The result holding the diagram.
        type(ml_result), intent(in) :: result
        !> Frequency [Hz].
        real(dp), intent(in) :: f
        !> Half-width [Hz].
        real(dp), intent(in) :: window

        diagram_support = 0
        if (allocated(result%diagram_flag)) diagram_support = count(result%diagram_flag >= 1 .and. &
                                                                    abs(result%diagram_frequency - f) <= window)
    end function diagram_support

    !> The diagram's confirmations of pole k (mark_undetermined): its stable poles within
    !> max(stable_frequency, xi)*f of the pole; when they are fewer than stable_orders, within
    !> the distance to the nearest other pole of the model closer than pair_span*f that has
    !> stable_orders of its own (one of a close pair, which the linear step merges into one
    !> stable pole between the two).
    pure integer function confirmations_of(result, options, poles, k)
        !> The result holding the diagram.
        type(ml_result), intent(in) :: result
        !> Settings (stable_frequency, stable_orders).
        type(ml_options), intent(in) :: options
        !> The model's poles [rad/s].
        complex(dp), intent(in) :: poles(:)
        !> Which pole.
        integer, intent(in) :: k

        real(dp) :: f, f_other, gap, nearest
        integer :: j

        f = natural_frequency(poles(k))/two_pi
        confirmations_of = diagram_support(result, f, max(options%stable_frequency, damping_ratio(poles(k)))*f)
        if (confirmations_of >= options%stable_orders) return
        nearest = -1.0_dp
        do j = 1, size(poles)
            if (j == k) cycle
            f_other = natural_frequency(poles(j))/two_pi
            gap = abs(f_other - f)
            if (gap > pair_span*f .or. (nearest >= 0.0_dp .and. gap >= nearest)) cycle
            if (diagram_support(result, f_other, max(options%stable_frequency, damping_ratio(poles(j)))*f_other) &
                < options%stable_orders) cycle
            nearest = gap
        end do
        if (nearest >= 0.0_dp) confirmations_of = diagram_support(result, f, &
                                                                  max(options%stable_frequency*f, nearest))
    end function confirmations_of

    !> The spacing [rad/s] of the lines at omega: the wider of the two gaps beside the line
    !> nearest to it (0 with a single line).
    pure real(dp) function line_spacing(omega, at)
        !> The lines [rad/s], increasing.
        real(dp), intent(in) :: omega(:)
        !> Where [rad/s].
        real(dp), intent(in) :: at

        integer :: j, n

        n = size(omega)
        line_spacing = 0.0_dp
        if (n < 2) return
        j = minloc(abs(omega - at), 1)
        line_spacing = max(omega(min(j + 1, n)) - omega(j), omega(j) - omega(max(j - 1, 1)))
    end function line_spacing

    !> Each line's noise scale for the determined rule: the weighted residual's mean square over
    !> its band of scale_lines neighbouring lines (the band's chi2 per line over its expectation,
    !> the parameters' share 2L/nu given back), at least 1 (the noise estimated before the fit).
    pure function band_scale(data, model, dof) result(scale)
        !> The weighted data of the final fit.
        type(data_type), intent(in) :: data
        !> The final model.
        type(model_type), intent(in) :: model
        !> Degrees of freedom of the final fit, 2L - P.
        integer, intent(in) :: dof
        !> Variance factor of each line used.
        real(dp) :: scale(size(data%g))

        real(dp) :: e2(size(data%g))
        integer :: b, n, n_bands, first, last

        n = size(data%g)
        e2 = abs(data%weight*(data%g - evaluate(model, data%omega)))**2
        n_bands = max(1, n/scale_lines)
        do b = 1, n_bands
            call band_bounds(b, n, n_bands, first, last)
            scale(first:last) = max(1.0_dp, sum(e2(first:last))/(last - first + 1)*(2.0_dp*n)/max(dof, 1))
        end do
    end function band_scale

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
            else if (data%relative .and. data%absolute_floor > 0.0_dp) then
                sigma = hypot(data%level*abs(g_model(1)), data%absolute_floor)
            else if (data%relative .and. allocated(data%line_level)) then
                sigma = data%line_level(minloc(abs(data%line - l), 1))*abs(g_model(1))
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

end module greenconv_ident_mlfit
