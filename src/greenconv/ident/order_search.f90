!> The order search of the maximum-likelihood identification (steps 5 and 6 of
!> greenconv_ident_mlfit's description): modes added and dropped while the MDL criterion falls,
!> the residual terms kept or removed, outlier lines left out when MDL prefers that to a mode,
!> and the clean-up of the final model (poles outside the band, needles at the narrowest band,
!> modes the Fisher information does not determine).
!>
!> The greedy rounds (add while MDL falls, then drop) can end in a local optimum: a mode split
!> over two poles with large residues of opposite sign, or a pole on a noise bump that the
!> others would take up once it is gone (on a measured receptance: 12 modes kept for 8, 149
!> above the true model's MDL). `death_move` then removes, in turn, each mode whose residue the information
!> barely separates from zero or from another's, refits, and keeps the first removal that
!> lowers MDL; the greedy rounds start again from it (births at the residual's peaks). When
!> the best rejected removal is within `close_call` (10) of the chosen model's MDL, a warning
!> says so: the data barely decide between the two orders. After the final refinement
!> (new weights) `prune_final` removes, by the same price, the modes the likelihood no longer
!> pays for (needles beside a mode under a rolled-off tail); a singular information in the
!> search removes a mode only when MDL accepts it (`degenerate_order`). Death moves, these two
!> and the variable projection of the fits (data%projection) run only with
!> ml_options%global_search.
module greenconv_ident_order_search
    use greenconv_core_kinds, only: dp
    use greenconv_core_constants, only: two_pi, i_unit
    use greenconv_core_error, only: error_type
    use greenconv_ident_lsce, only: natural_frequency
    use greenconv_core_text, only: real_text
    use greenconv_ident_ml_types, only: ml_options, ml_result, record_drop, add_warning, dropped_by_criterion, &
                                        dropped_left_band, dropped_degenerate, dropped_boundary
    use greenconv_ident_lm_fit, only: model_type, data_type, evaluate, chi_square, criterion, fit, refine, &
                                      information, covariance, widened, narrowest, leave_out
    implicit none
    private

    public :: choose_order, drop_outside, drop_needles, drop_undetermined, prune_terms
    public :: tries_per_add


    !> Half-power half-width xi*f of a pole, as a fraction of the line spacing df, from which
    !> it is taken for a mode rather than for an outlier line when both explain a line that
    !> stands out: such a pole lifts the lines beside its peak by this fraction of the peak's
    !> excess or more, which a damaged line (whose neighbours are unchanged) drives the fit
    !> below as soon as its excess passes about 20 noise sigma (a sign lost or a zero at
    !> 3 % noise is 33 sigma or more). A lightly damped mode under-resolved by the grid
    !> (xi*f between this and df/2) is so kept, and reported as under-resolved.
    real(dp), parameter :: resolvable_width = 0.05_dp

    !> Damping ratios tried for a mode started at a residual peak.
    real(dp), parameter :: trial_damping(6) = [0.001_dp, 0.003_dp, 0.01_dp, 0.03_dp, 0.1_dp, 0.3_dp]
    !> Candidates refitted per attempt to add a mode.
    integer, parameter :: tries_per_add = 3

    !> Levenberg-Marquardt iterations of a trial fit (a mode added or removed, a residual term)
    !> before the criterion decides; the kept model is then refined fully.
    integer, parameter :: trial_iterations = 3

    !> Death moves (`escape`) try the modes whose Wald statistic for r_k = 0 is below this
    !> many MDL prices of a mode.
    real(dp), parameter :: death_wald = 25.0_dp
    !> A rejected model within this of the chosen model's MDL criterion is reported.
    real(dp), parameter :: close_call = 10.0_dp
    !> Relative tolerance of every comparison of criteria (`simpler_wins`, `richer_wins`): two
    !> values within tie_tolerance*max(1, |value|) are a tie, and a tie goes to the model with
    !> fewer parameters (a mode or a term fewer, a line not left out). 1e-9 of a criterion of
    !> 1e4 to 1e6 is 1e-5 to 1e-3, far above the last bits of its sums (1e-12) and far below
    !> any statistical difference (a mode's price is 4*ln(2L), 30 or more).
    real(dp), parameter :: tie_tolerance = 1.0e-9_dp

contains

    !> Add modes while MDL accepts one, then drop modes while MDL accepts their removal;
    !> repeat until neither changes the model, then decide the residual terms ('auto').
    !> An outlier line MDL prefers to leave out is recorded in the result; unless `keep_going`,
    !> the search then stops and returns its FRF index in `outlier` (for a fresh start without
    !> it), otherwise the line is left out of the data and the search goes on.
    subroutine choose_order(data, options, candidates, model, result, outlier, keep_going, error)
        !> The weighted data (outlier lines found are left out of it).
        type(data_type), intent(inout) :: data
        !> Settings: max_changes, residual_terms.
        type(ml_options), intent(in) :: options
        !> Poles of the diagram [rad/s] that may be added.
        complex(dp), intent(in) :: candidates(:)
        !> In: the start model, fitted; out: the model chosen.
        type(model_type), intent(inout) :: model
        !> The result: LM iterations, dropped poles, outlier lines.
        type(ml_result), intent(inout) :: result
        !> FRF index of an outlier line that asks for a fresh start, 0 when none.
        integer, intent(out) :: outlier
        !> Whether an outlier line is only left out (no fresh start asked).
        logical, intent(in) :: keep_going
        !> Set when a fit fails.
        type(error_type), allocatable, intent(out) :: error

        !> Phases of a round of the search: modes added, then modes dropped.
        integer, parameter :: adding = 1, dropping = 2
        integer :: changes, line, phase
        logical :: changed, removed
        real(dp) :: closest

        outlier = 0
        data%projection = options%global_search
        call drop_outside(data, model, result, error)
        if (allocated(error)) return
        changes = 0
        closest = huge(1.0_dp)
        do
            ! Adding stops when no candidate is accepted; only a removal can make a new addition
            ! worth trying (the residual changed), so the rounds end with a round that removes nothing.
            do
                removed = .false.
                do phase = adding, dropping
                    do while (changes < options%max_changes)
                        if (phase == adding) then
                            call add_mode(data, candidates, model, result, changed, line, error)
                        else
                            call drop_mode(data, model, result, changed, line, error)
                        end if
                        if (allocated(error)) return
                        if (.not. changed) exit
                        removed = removed .or. phase == dropping
                        changes = changes + 1
                        if (line > 0) then
                            call take_outlier(data, model, result, line, keep_going, outlier, error)
                            if (allocated(error) .or. outlier > 0) return
                        end if
                    end do
                end do
                if (.not. removed .or. changes >= options%max_changes) exit
            end do
            ! The greedy rounds end in a local optimum of MDL when the fit split one mode over
            ! two poles or kept a pole on noise that the others would take up: a death move,
            ! then the rounds again from the model it leaves.
            if (changes >= options%max_changes .or. .not. options%global_search) exit
            call death_move(data, model, result, changed, closest, error)
            if (allocated(error)) return
            if (.not. changed) exit
            changes = changes + 1
        end do
        if (closest < close_call) then
            call add_warning(result, 'a model with one mode fewer is within '//trim(real_text(closest)) &
                             //' of the chosen model''s MDL (the data barely decide between them)')
        end if
        if (options%residual_terms == 'auto') then
            call drop_term(data, model, result, .true., error)
            if (allocated(error)) return
            call drop_term(data, model, result, .false., error)
        end if
    end subroutine choose_order

    !> A death move out of a local optimum of the greedy search: each mode whose Wald statistic
    !> for r_k = 0 lies below death_wald prices of a mode (a pole sharing its mode with another
    !> has a residue the information barely separates, so a small statistic) is removed in
    !> turn, smallest statistic first, and the rest refitted (search iterations); the first
    !> removal that lowers the MDL criterion is kept and refined. `closest` returns the least
    !> rise of the criterion among the removals rejected (huge when none was tried).
    subroutine death_move(data, model, result, removed, closest, error)
        !> The weighted data.
        type(data_type), intent(in) :: data
        !> The model, without the mode when a removal is kept.
        type(model_type), intent(inout) :: model
        !> The result: the mode removed (dropped_by_criterion), LM iterations.
        type(ml_result), intent(inout) :: result
        !> Whether a mode was removed.
        logical, intent(out) :: removed
        !> Least rise of the MDL criterion among the rejected removals (dimensionless).
        real(dp), intent(out) :: closest
        !> Set when a refit fails.
        type(error_type), allocatable, intent(out) :: error

        real(dp), allocatable :: fisher(:, :), gradient(:), cov(:, :), jac(:, :)
        integer, allocatable :: order(:)
        logical :: ok

        removed = .false.
        closest = huge(1.0_dp)
        if (size(model%pole) < 2) return
        call information(data, model, fisher, gradient, jac)
        call covariance(fisher, cov, ok)
        if (.not. ok) return
        order = smallest_below(wald_statistics(model, cov), death_wald*4.0_dp*data%penalty, size(model%pole))
        call first_removal(data, order, spread(dropped_by_criterion, 1, size(order)), model, result, removed, &
                           error, closest)
        if (removed) call refine(data, model, result%iterations)
    end subroutine death_move

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
        call fit(data, model, result%iterations, error)
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

    !> Remove poles the fit moved above f_max (their effect belongs to R_u) and refit.
    subroutine drop_outside(data, model, result, error)
        !> The weighted data.
        type(data_type), intent(in) :: data
        !> The model, without the poles above f_max, refitted.
        type(model_type), intent(inout) :: model
        !> The result: the poles removed (dropped_left_band), LM iterations.
        type(ml_result), intent(inout) :: result
        !> Set when a refit fails.
        type(error_type), allocatable, intent(out) :: error

        logical, allocatable :: inside(:)

        do
            if (allocated(inside)) deallocate (inside)
            allocate (inside(size(model%pole)))
            inside(:) = natural_frequency(model%pole) <= two_pi*data%f_max
            if (all(inside)) return
            call record_drop(result, pack(model%pole, .not. inside), dropped_left_band)
            model%pole = pack(model%pole, inside)
            call fit(data, model, result%iterations, error)
            if (allocated(error)) return
        end do
    end subroutine drop_outside

    !> Poles the final fit left at the narrowest band allowed (within a factor 2 of min_decay):
    !> no sampled receptance can show such a mode (its peak is narrower than a thousandth of
    !> the line spacing); it stands for noise on a line or two, e.g. near an anti-resonance
    !> where the relative noise model underestimates the noise. Dropped one at a time, the
    !> narrowest first, the model refitted after each.
    subroutine drop_needles(data, model, result, error)
        !> The weighted data.
        type(data_type), intent(in) :: data
        !> The model, without the needles, refitted.
        type(model_type), intent(inout) :: model
        !> The result: the poles removed (dropped_boundary), LM iterations.
        type(ml_result), intent(inout) :: result
        !> Set when a refit fails.
        type(error_type), allocatable, intent(out) :: error

        integer :: k

        do while (any(narrowest(model%pole, data%min_decay)))
            k = maxloc(real(model%pole, dp), 1, narrowest(model%pole, data%min_decay))
            call drop_pole(data, k, dropped_boundary, model, result, error)
            if (allocated(error)) return
        end do
    end subroutine drop_needles

    !> Remove the modes the data do not determine: while the Fisher information of the final
    !> model is singular (two poles merged, a residue the data cannot see), drop the mode
    !> `merged` names and refit, so that every mode returned has a finite uncertainty; then,
    !> with the global search (data%projection), the modes MDL does not pay for under the final
    !> weights (`prune_final`).
    subroutine drop_undetermined(data, model, result, error)
        !> The weighted data.
        type(data_type), intent(in) :: data
        !> The model, without the modes the data do not determine, refitted.
        type(model_type), intent(inout) :: model
        !> The result: the poles removed (dropped_degenerate), LM iterations.
        type(ml_result), intent(inout) :: result
        !> Set when a refit fails.
        type(error_type), allocatable, intent(out) :: error

        real(dp), allocatable :: fisher(:, :), gradient(:), cov(:, :), jac(:, :)
        logical :: ok

        do while (size(model%pole) > 0)
            call information(data, model, fisher, gradient, jac)
            call covariance(fisher, cov, ok)
            if (ok) exit
            call drop_pole(data, merged(model), dropped_degenerate, model, result, error)
            if (allocated(error)) return
        end do
        if (data%projection) call prune_final(data, model, result, error)
    end subroutine drop_undetermined

    !> The final pruning of the global search: the model refined under the final weights is not
    !> the one the search judged (its weights came from the smoothed |G|), so each mode the
    !> information barely separates from zero (Wald statistic for r_k = 0 below death_wald
    !> prices of a mode), smallest statistic first, is removed and the rest fully refitted under
    !> the final weights; the removal is kept when it does not raise -2 ln(likelihood) by more
    !> than the mode's MDL price 4*ln(2L). With an estimated noise level that likelihood has its
    !> scale refitted, 2L*ln(chi2) (a level the residual shows wrong by chi2/nu must not inflate
    !> what a needle buys: sdypy-EMA's H_51, chi2/nu = 2.3, kept two needles worth 64 and 74 of
    !> chi2, 28 and 32 of likelihood); with a given sigma it is chi2 itself. A needle beside a
    !> mode so merges into it: the mode left takes up what the pair fitted.
    subroutine prune_final(data, model, result, error)
        !> The weighted data (final weights).
        type(data_type), intent(in) :: data
        !> The model, without the modes MDL does not pay for, refitted.
        type(model_type), intent(inout) :: model
        !> The result: the modes removed (dropped_by_criterion), LM iterations; noise_estimated.
        type(ml_result), intent(inout) :: result
        !> Set when a refit fails.
        type(error_type), allocatable, intent(out) :: error

        real(dp), allocatable :: fisher(:, :), gradient(:), cov(:, :), wald(:), jac(:, :)
        type(model_type) :: trial
        real(dp) :: before
        integer :: worst
        logical :: ok, removed

        removed = .true.
        do while (removed .and. size(model%pole) > 0)
            removed = .false.
            call information(data, model, fisher, gradient, jac)
            call covariance(fisher, cov, ok)
            if (.not. ok) return
            wald = wald_statistics(model, cov)
            before = likelihood(data, result, chi_square(data, model))
            do
                worst = minloc(wald, 1)
                if (.not. (wald(worst) < death_wald*4.0_dp*data%penalty)) exit
                wald(worst) = huge(1.0_dp)
                call refit_without(data, model, worst, result%iterations, trial, error)
                if (allocated(error)) return
                if (.not. simpler_wins(likelihood(data, result, chi_square(data, trial)), &
                                       before + 4.0_dp*data%penalty)) cycle
                ! A removal must leave every uncertainty finite (the rest refitted can merge).
                call information(data, trial, fisher, gradient, jac)
                call covariance(fisher, cov, ok)
                if (ok) then
                    call record_drop(result, [model%pole(worst)], dropped_by_criterion)
                    model = trial
                    removed = .true.
                    exit
                end if
            end do
        end do

    end subroutine prune_final

    !> The global search's last step, once the modes above the band are decided: each residual
    !> term the search chose ('auto') removed, the rest fully refitted under the final weights,
    !> and the removal kept when -2 ln(likelihood) rises by no more than its price ln(2L) and
    !> the information stays regular. The search judged a term with the poles fixed, so R_u kept
    !> while it stood for modes above the band could outlive the pseudo-modes that replaced it
    !> (a pair and a triple with two modes above a 1.2 kHz band at 0.1 %: 8.3 above the true
    !> model's MDL, R_u's price less what it fitted).
    subroutine prune_terms(data, model, result, error)
        !> The weighted data (final weights).
        type(data_type), intent(in) :: data
        !> The model, without the terms MDL does not pay for, refitted.
        type(model_type), intent(inout) :: model
        !> The result: LM iterations; noise_estimated.
        type(ml_result), intent(inout) :: result
        !> Set when a refit fails.
        type(error_type), allocatable, intent(out) :: error

        real(dp), allocatable :: fisher(:, :), gradient(:), cov(:, :), jac(:, :)
        type(model_type) :: trial
        integer :: term
        logical :: ok

        do term = 1, 2
            if (.not. without_term(model, term == 1, trial)) cycle
            call fit(data, trial, result%iterations, error)
            if (allocated(error)) return
            if (.not. simpler_wins(likelihood(data, result, chi_square(data, trial)), &
                                   likelihood(data, result, chi_square(data, model)) + data%penalty)) cycle
            call information(data, trial, fisher, gradient, jac)
            call covariance(fisher, cov, ok)
            if (ok) model = trial
        end do
    end subroutine prune_terms

    !> -2 ln(likelihood) up to a constant for a chi2 under the final weights: chi2 itself with a
    !> given sigma, 2L*ln(chi2/(2L)) with the noise scale refitted when it was estimated.
    pure real(dp) function likelihood(data, result, chi)
        !> The weighted data (its number of lines L).
        type(data_type), intent(in) :: data
        !> The result (noise_estimated).
        type(ml_result), intent(in) :: result
        !> chi2 of a model under the final weights.
        real(dp), intent(in) :: chi

        real(dp) :: two_l

        two_l = 2.0_dp*size(data%g)
        likelihood = chi
        if (result%noise_estimated) likelihood = two_l*log(max(chi, tiny(1.0_dp))/two_l)
    end function likelihood

    !> Remove mode k from the model, record it with its reason and refit the rest.
    subroutine drop_pole(data, k, reason, model, result, error)
        type(data_type), intent(in) :: data
        !> Index of the mode in model.
        integer, intent(in) :: k
        !> Why: dropped_boundary, dropped_degenerate, ...
        integer, intent(in) :: reason
        type(model_type), intent(inout) :: model
        type(ml_result), intent(inout) :: result
        type(error_type), allocatable, intent(out) :: error

        call record_drop(result, [model%pole(k)], reason)
        model%pole = [model%pole(:k - 1), model%pole(k + 1:)]
        call fit(data, model, result%iterations, error)
    end subroutine drop_pole

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
            added = richer_wins(target, before)
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
            call fit(data, trial, result%iterations, error, trial_iterations)
            if (allocated(error)) return
            added = all(natural_frequency(trial%pole) <= two_pi*data%f_max) .and. &
                    richer_wins(criterion(data, trial, chi_square(data, trial)), target)
        end if
        do try = 1, min(tries_per_add, size(pool))
            if (added) exit
            k = maxloc(score, 1)
            score(k) = -huge(1.0_dp)
            trial = model
            trial%pole = [model%pole, pool(k)]
            call fit(data, trial, result%iterations, error, trial_iterations)
            if (allocated(error)) return
            if (.not. all(natural_frequency(trial%pole) <= two_pi*data%f_max)) cycle
            added = richer_wins(criterion(data, trial, chi_square(data, trial)), &
                                merge(before, target, resolves_line(data, trial, outlier)))
        end do
        ! The trial kept (the batch or one candidate) is refined fully.
        if (added) then
            model = trial
            call refine(data, model, result%iterations)
            outlier = 0
            return
        end if
        added = richer_wins(target, before)
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
        resolves_line = all(data%weight(first:last)*abs(data%g(first:last) - evaluate(trial, data%omega(first:last))) &
                            <= data%outlier_sigma)
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
        call fit(without, model, result%iterations, error, iterations)
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
        !> The weighted data.
        type(data_type), intent(in) :: data
        !> The model, without the mode when a removal is kept.
        type(model_type), intent(inout) :: model
        !> The result: the mode removed and why (dropped_by_criterion, dropped_boundary,
        !> dropped_degenerate), LM iterations.
        type(ml_result), intent(inout) :: result
        !> Whether a mode was removed.
        logical, intent(out) :: removed
        !> Index in data of the line a removed spike mode took up, 0 when none.
        integer, intent(out) :: outlier
        !> Set when a refit fails.
        type(error_type), allocatable, intent(out) :: error

        real(dp), allocatable :: fisher(:, :), gradient(:), cov(:, :), wald(:), jac(:, :)
        integer, allocatable :: order(:), reason(:)
        logical :: ok
        integer :: j

        removed = .false.
        outlier = 0
        if (size(model%pole) == 0) return
        call spike_mode(data, model, result, outlier, error)
        if (allocated(error)) return
        if (outlier > 0) then
            removed = .true.
            return
        end if
        call information(data, model, fisher, gradient, jac)
        call covariance(fisher, cov, ok)
        if (.not. ok) then
            if (data%projection) then
                order = degenerate_order(data, model)
                call first_removal(data, order, spread(dropped_degenerate, 1, size(order)), model, result, &
                                   removed, error)
                return
            end if
            call drop_pole(data, merged(model), dropped_degenerate, model, result, error)
            removed = .true.
            return
        end if
        wald = wald_statistics(model, cov)
        ! Poles the fit pushed to the narrowest band go first, whatever their statistic.
        where (narrowest(model%pole, data%min_decay)) wald = -1.0_dp
        order = smallest_below(wald, 4.0_dp*data%penalty, tries_per_add)
        reason = [(merge(dropped_boundary, dropped_by_criterion, narrowest(model%pole(order(j)), data%min_decay)), &
                   j=1, size(order))]
        ! A full refit: with several noise poles the others move when one goes.
        call first_removal(data, order, reason, model, result, removed, error)
    end subroutine drop_mode

    !> The removals tried on a singular information in the search (global search, by
    !> `first_removal`): the mode `merged` names, then each pole at the narrowest band; the
    !> first removal that lowers the MDL criterion is kept (a true duplicate adds nothing to the
    !> fit, so its removal saves its price). Unjudged, the removal of `merged`'s choice repeated
    !> while the information stayed singular (the null direction on another pole, a needle) took
    !> real modes one after another: suite outofband's measured beam, FRF 2, lost all six
    !> (chi2/nu 9e6).
    pure function degenerate_order(data, model) result(order)
        !> The weighted data.
        type(data_type), intent(in) :: data
        !> The model.
        type(model_type), intent(in) :: model
        !> Indices in model of the modes to try, in turn.
        integer, allocatable :: order(:)

        integer :: k

        order = [merged(model)]
        do k = 1, size(model%pole)
            if (narrowest(model%pole(k), data%min_decay) .and. k /= order(1)) order = [order, k]
        end do
    end function degenerate_order

    !> Remove the modes `order` names in turn, each from the same model with the rest refitted
    !> (search iterations), and keep the first removal that lowers the MDL criterion, recorded
    !> with its reason. `closest`, when present, is lowered to the least rise of the criterion
    !> among the removals rejected (dimensionless).
    subroutine first_removal(data, order, reason, model, result, removed, error, closest)
        type(data_type), intent(in) :: data
        !> Indices in model of the modes to try, in turn.
        integer, intent(in) :: order(:)
        !> Why each is dropped when kept (dropped_by_criterion, ...), one per entry of order.
        integer, intent(in) :: reason(:)
        type(model_type), intent(inout) :: model
        type(ml_result), intent(inout) :: result
        logical, intent(out) :: removed
        type(error_type), allocatable, intent(out) :: error
        real(dp), intent(inout), optional :: closest

        type(model_type) :: trial
        real(dp) :: before, after
        integer :: j

        removed = .false.
        if (size(order) == 0) return
        before = criterion(data, model, chi_square(data, model))
        do j = 1, size(order)
            call refit_without(data, model, order(j), result%iterations, trial, error)
            if (allocated(error)) return
            after = criterion(data, trial, chi_square(data, trial))
            if (simpler_wins(after, before)) then
                call record_drop(result, [model%pole(order(j))], reason(j))
                model = trial
                removed = .true.
                return
            end if
            if (present(closest)) closest = min(closest, after - before)
        end do
    end subroutine first_removal

    !> The model without mode k, the rest refitted by `fit`.
    subroutine refit_without(data, model, k, lm_iterations, trial, error)
        type(data_type), intent(in) :: data
        type(model_type), intent(in) :: model
        !> Index of the mode in model.
        integer, intent(in) :: k
        !> Count of LM iterations, the fit's added.
        integer, intent(inout) :: lm_iterations
        type(model_type), intent(out) :: trial
        type(error_type), allocatable, intent(out) :: error

        trial = model
        trial%pole = [model%pole(:k - 1), model%pole(k + 1:)]
        call fit(data, trial, lm_iterations, error)
    end subroutine refit_without

    !> The Wald statistic for r_k = 0 of each mode of the model, from the covariance of its
    !> parameters (four per mode, the residue's real and imaginary parts third and fourth).
    pure function wald_statistics(model, cov) result(wald)
        type(model_type), intent(in) :: model
        real(dp), intent(in) :: cov(:, :)
        real(dp) :: wald(size(model%pole))

        integer :: k, c

        do k = 1, size(model%pole)
            c = 4*(k - 1)
            wald(k) = quadratic(cov(c + 3:c + 4, c + 3:c + 4), [real(model%residue(k), dp), aimag(model%residue(k))])
        end do
    end function wald_statistics

    !> Indices of the statistics below `limit`, smallest first (of equal ones the first), at
    !> most `most` of them.
    pure function smallest_below(statistic, limit, most) result(order)
        real(dp), intent(in) :: statistic(:), limit
        integer, intent(in) :: most
        integer, allocatable :: order(:)

        real(dp) :: left(size(statistic))
        integer :: k

        order = [integer ::]
        if (size(statistic) == 0) return
        left = statistic
        do while (size(order) < most)
            k = minloc(left, 1)
            if (.not. (left(k) < limit)) exit
            order = [order, k]
            left(k) = huge(1.0_dp)
        end do
    end function smallest_below

    !> Whether a mode narrower than one line (2*xi*f < df) only takes up an outlier line: the
    !> model without it, refitted without the line of largest residual next to its frequency,
    !> leaves that line alone far off (`without_line`), and has, with the line's 2 values
    !> freed, a lower MDL criterion than with the mode (4 parameters). A real under-resolved
    !> mode also lifts the lines beside its peak (its tails r/(i*(omega - omega_k))), so its
    !> removal leaves no lone line. Then the model becomes the one without the mode, `line`
    !> the outlier (index in data), else 0.
    subroutine spike_mode(data, model, result, line, error)
        !> The weighted data.
        type(data_type), intent(in) :: data
        !> The model, without the spike mode when one is found.
        type(model_type), intent(inout) :: model
        !> The result: the spike mode's pole (dropped_boundary), LM iterations.
        type(ml_result), intent(inout) :: result
        !> Index in data of the outlier line the spike mode took up, 0 when none.
        integer, intent(out) :: line
        !> Set when a refit fails.
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
            call fit(data, trial, result%iterations, error)
            if (allocated(error)) return
            residual(:) = data%weight*(data%g - evaluate(trial, data%omega))
            near = minloc(abs(data%omega - aimag(model%pole(k))), 1)
            near = near - 2 + maxloc(abs(residual(max(1, near - 1):min(size(residual), near + 1))), 1) &
                   + merge(1, 0, near == 1)
            call without_line(data, near, data%max_iterations, trial, result, without, alone, error)
            if (allocated(error)) return
            if (.not. alone) cycle
            if (simpler_wins(criterion(without, trial, chi_square(without, trial)) + 2.0_dp*data%penalty, before)) then
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

    !> x^T inv(C) x for a 2 x 2 covariance C (huge when C is singular); C and x as sections (no copy).
    pure real(dp) function quadratic(c, x)
        real(dp), intent(in) :: c(:, :), x(:)

        real(dp) :: det

        det = c(1, 1)*c(2, 2) - c(1, 2)*c(2, 1)
        quadratic = huge(1.0_dp)
        if (det > 0.0_dp) quadratic = (c(2, 2)*x(1)**2 - (c(1, 2) + c(2, 1))*x(1)*x(2) + c(1, 1)*x(2)**2)/det
    end function quadratic

    !> Remove R_u (upper = .true.) or R_l from the model when the model without it, its
    !> residues and other term refitted for the current poles, lowers MDL; the kept model is
    !> then refined. Without the poles refitted the removal is judged conservatively.
    subroutine drop_term(data, model, result, upper, error)
        !> The weighted data.
        type(data_type), intent(in) :: data
        !> The model, without the term when MDL prefers.
        type(model_type), intent(inout) :: model
        !> The result: LM iterations.
        type(ml_result), intent(inout) :: result
        !> Which term: R_u (true) or R_l (false).
        logical, intent(in) :: upper
        !> Set when a refit fails.
        type(error_type), allocatable, intent(out) :: error

        type(model_type) :: trial

        if (.not. without_term(model, upper, trial)) return
        call fit(data, trial, result%iterations, error, 0)
        if (allocated(error)) return
        if (simpler_wins(criterion(data, trial, chi_square(data, trial)), &
                         criterion(data, model, chi_square(data, model)))) then
            model = trial
            call refine(data, model, result%iterations)
        end if
    end subroutine drop_term

    !> The model without one residual term (its value zeroed, the rest as is); false when the
    !> model has no such term.
    logical function without_term(model, upper, trial)
        !> The model.
        type(model_type), intent(in) :: model
        !> Which term: R_u (true) or R_l (false).
        logical, intent(in) :: upper
        !> The model without it.
        type(model_type), intent(out) :: trial

        trial = model
        if (upper) then
            without_term = model%upper
            trial%upper = .false.
            trial%r_u = 0.0_dp
        else
            without_term = model%lower
            trial%lower = .false.
            trial%r_l = 0.0_dp
        end if
    end function without_term

    !> Whether a simpler model (criterion `simpler`) is preferred to a richer one (`richer`):
    !> lower, or within the tie tolerance.
    pure logical function simpler_wins(simpler, richer)
        !> Criterion of the simpler model (dimensionless).
        real(dp), intent(in) :: simpler
        !> Criterion of the richer model (dimensionless).
        real(dp), intent(in) :: richer

        simpler_wins = simpler <= richer + tie_tolerance*max(1.0_dp, abs(richer))
    end function simpler_wins

    !> Whether a richer model (criterion `richer`) is preferred to a simpler one (`simpler`):
    !> lower by more than the tie tolerance.
    pure logical function richer_wins(richer, simpler)
        !> Criterion of the richer model (dimensionless).
        real(dp), intent(in) :: richer
        !> Criterion of the simpler model (dimensionless).
        real(dp), intent(in) :: simpler

        richer_wins = .not. simpler_wins(simpler, richer)
    end function richer_wins

end module greenconv_ident_order_search
