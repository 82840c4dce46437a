!> An upper bound of the cost of identifying a Green's matrix file with shared poles
!> (greenconv_ident_shared_poles on the summed driving points, then greenconv_ident_green_structure),
!> known before the identification starts: from the file's size (N_c points, L lines) and the
!> algorithm's own limits, in floating-point operations (a multiplication and an addition
!> count two), and in CPU seconds at a rate measured on the machine.
!>
!> Worst case of every limit at once: M = max_order modes in every fit (P = 4M + 2 real
!> parameters, Q = 2M + 2 linear ones), every fit run to its iteration cap, every cap of
!> changes, outlier restarts and searches reached.
!>
!> - **One Levenberg-Marquardt fit** of I iterations (greenconv_ident_lm_fit's `fit`): the
!>   residues by linear least squares, then per iteration the information (Jacobian 2L x P,
!>   its Gram product, the gradient, the projection's Schur complement) and the trial steps.
!>   mu starts at 1e-4, is divided by 10 at each accepted step and multiplied by 10 at each
!>   refused one, and the fit stops past 1e12: at most I + (I + 17) trial steps, each a
!>   Cholesky solve, a linear least squares for the residues (its Gram product, or when the
!>   normal equations are ill-conditioned Householder's reduction and at most 60 one-sided
!>   Jacobi sweeps of 9*Q^3) and the model on every line.
!> - **One order search** (greenconv_ident_order_search's `choose_order`): at most
!>   max_changes changes; the calls that change nothing end a phase (add, drop) or a round
!>   (death move), at most 3*(max_changes + 1) of them. The dearest call is a drop (a spike
!>   test and a degenerate test refitting each of M poles, a merged pole's drop,
!>   tries_per_add removals, a refinement: 2M + 5 fits of search_iterations; an add is at
!>   most an outlier's refit, a batch and tries_per_add trials and a refinement); after each
!>   change an outlier fit.
!> - **One identification under one noise model** (greenconv_ident_mlfit's `identify_with`):
!>   outlier_restarts + 1 passes, each the noise estimate, the stabilisation diagram to
!>   2*max_order + stable_orders (each order a least squares on at most max_samples impulse
!>   samples and a companion's eigenvalues), a start fit and an order search; then the final
!>   refinement and at most 2M drops refitted with max_iterations, the residual terms' pruning,
!>   and with outside_modes = 'auto' max_outside rounds of outside_start fits and a search.
!>   The global search and the greedy one: two identifications; noise_model = 'auto' without a
!>   given sigma: each of its four models.
!> - **The poly-reference fit** (greenconv_ident_polyref, with ident_method 'poly_reference' or
!>   'auto'): see `polyref_flops`.
!> - **Shared poles over all receptances** (`refine_poles`): refine_iterations iterations of
!>   Kaufman's Gauss-Newton system (derivative products over 2L rows, the normal matrix per
!>   target) with at most refine_attempts projections each (Gram-Schmidt twice over 2L x N_b,
!>   N_b = 2M + 2), the residue matrices (one least squares per distinct receptance), the
!>   model and E of every receptance, the residue matrices' eigen-split into real shapes.
!>
!> LAPACK's least squares (dgelsd) and eigenvalues (dgeev) of the diagram and the residue
!> matrices are charged 12*m*n^2 + 100*n^3 and 100*n^3 for an m x n or n x n matrix, many times
!> their usual cost. The bound is far above what a file costs (every cap is rarely reached,
!> let alone all at once); it is a guarantee, not an estimate: suite identcost measures
!> identifications against it (doc/identification.md, "The cost of a Green's matrix file").
module greenconv_ident_cost
    use, intrinsic :: iso_fortran_env, only: int64
    use greenconv_core_kinds, only: dp
    use greenconv_core_text, only: sci_text
    use greenconv_ident_ml_types, only: ml_options
    use greenconv_ident_dense, only: gram
    use greenconv_ident_mlfit, only: search_iterations, max_outside, outside_start
    use greenconv_ident_order_search, only: tries_per_add
    use greenconv_ident_shared_poles, only: refine_iterations, refine_attempts
    use greenconv_ident_polyref, only: max_polynomial_order, common_step
    implicit none
    private

    public :: green_cost, green_cost_bound, measured_rate, cost_text

    !> An upper bound of the cost of a Green's matrix file's identification, by part [flop].
    type :: green_cost
        !> The pole fit of the summed driving points (greenconv_ident_mlfit's identify_ml).
        real(dp) :: pole_fit = 0.0_dp
        !> The poles refined over all receptances (refine_poles).
        real(dp) :: refinement = 0.0_dp
        !> The poly-reference fit of all receptances (greenconv_ident_polyref), when it runs.
        real(dp) :: poly_reference = 0.0_dp
        !> The residue matrices, the model, E per receptance, the real shapes (of each fit).
        real(dp) :: residues = 0.0_dp
        !> The sum of the parts.
        real(dp) :: total = 0.0_dp
        !> Levenberg-Marquardt iterations of the pole fit at most (compare ml_result%iterations).
        real(dp) :: lm_iterations = 0.0_dp
    end type green_cost

    !> Powers of ten from mu's start to the value past which a fit stops (1e-4 to 1e12): a fit of
    !> I iterations makes at most 2I + mu_decades + 1 trial steps.
    integer, parameter :: mu_decades = 16

contains

    !> The bound of the identification of a Green's matrix of n_c points on n_lines lines (see
    !> the module description).
    pure function green_cost_bound(n_c, n_lines, symmetric, options, summed, poly_reference) result(cost)
        !> Contact points N_c.
        integer, intent(in) :: n_c
        !> Frequency lines L of each receptance.
        integer, intent(in) :: n_lines
        !> Whether the fit is to (G_ij + G_ji)/2 (N_c(N_c + 1)/2 distinct receptances).
        logical, intent(in) :: symmetric
        !> Settings of the pole fit (max_order, max_changes, max_iterations, outlier_restarts,
        !> stable_orders, max_samples, noise model, global search, outside modes).
        type(ml_options), intent(in) :: options
        !> Whether the poles are fitted on the summed driving points (identify_ml, refine_poles).
        logical, intent(in) :: summed
        !> Whether the poles are fitted by the poly-reference fit of all receptances.
        logical, intent(in) :: poly_reference
        type(green_cost) :: cost

        real(dp) :: l, m, p, q, passes, searches, calls, order_flops, s, k, n_t, n_b, search, short_fits, long_fits
        real(dp) :: trials, rounds
        integer :: n, orders

        l = real(n_lines, dp)
        m = real(max(options%max_order, 1), dp)
        p = 4.0_dp*m + 2.0_dp
        q = 2.0_dp*m + 2.0_dp
        ! one order search: at most max_changes changes and 3*(max_changes + 1) calls that
        ! change nothing, each at most a drop's 2M + 5 fits; an outlier fit after each change,
        ! the residual terms' two tests at the end: fits of at most search_iterations each
        calls = 4.0_dp*options%max_changes + 3.0_dp
        search = calls*(2.0_dp*m + tries_per_add + 2.0_dp) + options%max_changes + 2.0_dp
        ! one identification: passes of a start fit and a search; the final refinement and at
        ! most 2M drops refitted, the terms' pruning (fits of max_iterations); with outside
        ! modes, each round's starts and search and a second final refinement
        passes = real(max(options%outlier_restarts, 0) + 1, dp)
        short_fits = passes*(1.0_dp + search)
        long_fits = 2.0_dp*m + 3.0_dp
        rounds = passes
        if (options%outside_modes == 'auto') then
            short_fits = short_fits + max_outside*(size(outside_start) + search)
            long_fits = 2.0_dp*long_fits
            rounds = rounds + max_outside
        end if
        searches = merge(2.0_dp, 1.0_dp, options%global_search)
        if (options%noise_model == 'auto' .and. .not. allocated(options%sigma)) searches = 4.0_dp*searches
        cost%lm_iterations = searches*(short_fits*search_iterations + long_fits*options%max_iterations)
        ! each fit of at most I iterations: one linear least squares, then per iteration the
        ! information, and at most 2I + 17 trial steps in all (mu from 1e-4, tenfold down at an
        ! accepted step, up at a refused one, the fit ends past 1e12); per call of the search
        ! its information and covariance and the candidates' scores (every diagram pole of the
        ! top order and three residual peaks at six dampings, one pass over the lines each)
        trials = searches*(short_fits*(2.0_dp*search_iterations + mu_decades + 2.0_dp) &
                           + long_fits*(2.0_dp*options%max_iterations + mu_decades + 2.0_dp))
        orders = 2*options%max_order + options%stable_orders
        cost%pole_fit = cost%lm_iterations*information_flops(l, m, p, q) + trials*trial_flops(l, m, p, q) &
                        + searches*rounds*calls*(information_flops(l, m, p, q) + 2.0_dp*p**3 &
                                                 + (2.0_dp*orders + 18.0_dp)*80.0_dp*l) &
                        + searches*100.0_dp*l*m
        ! the stabilisation diagram of each pass: the impulse response and every order
        s = real(min(max(2*(n_lines - 1) - 1, 1), options%max_samples), dp)
        order_flops = 0.0_dp
        do n = 1, orders
            k = 2.0_dp*n
            order_flops = order_flops + 12.0_dp*s*k**2 + 200.0_dp*k**3
        end do
        cost%pole_fit = cost%pole_fit + searches*passes*(order_flops + 5.0_dp*2.0_dp*l*log(2.0_dp*l)/log(2.0_dp) &
                                                         + noise_flops(l))
        ! the sum of the driving points and their noise estimates
        cost%pole_fit = cost%pole_fit + 2.0_dp*n_c*l + (n_c + 1)*noise_flops(l)
        ! refine_poles over every distinct receptance
        n_t = real(merge(n_c*(n_c + 1)/2, n_c*n_c, symmetric), dp)
        n_b = 2.0_dp*m + 2.0_dp
        cost%refinement = (refine_iterations + 1)*refinement_flops(l, m, n_t, n_b)
        ! the residue matrices (least squares of 2L x N_b per target), the model and E of each
        ! receptance, the eigen-split of each residue matrix, the modes' E (green_structure)
        cost%residues = n_t*(12.0_dp*2.0_dp*l*n_b**2 + 100.0_dp*n_b**3) + 20.0_dp*2.0_dp*l*n_b &
                        + real(n_c, dp)**2*l*(20.0_dp*m + 10.0_dp) + 2.0_dp*m*100.0_dp*real(n_c, dp)**3 &
                        + l*(40.0_dp*2.0_dp*m*real(n_c, dp)**3 + 40.0_dp*real(n_c, dp)**2)
        if (.not. summed) then
            cost%pole_fit = 0.0_dp
            cost%refinement = 0.0_dp
            cost%lm_iterations = 0.0_dp
        end if
        if (poly_reference) cost%poly_reference = polyref_flops(real(n_c, dp), l, options%max_order)
        cost%total = cost%pole_fit + cost%refinement + cost%poly_reference + merge(2.0_dp, 1.0_dp, summed .and. &
                                                                                     poly_reference)*cost%residues
    end function green_cost_bound

    !> greenconv_ident_polyref's fit of all receptances (identify_polyref) [flop]: its Gram
    !> blocks, every matrix order to p_max and every common-denominator order to 2M (each a
    !> reduced normal system, a companion's eigenvalues and the MDL score's projection), the
    !> refinement with the targets' common weight (30 iterations of at most 10 trial steps, once
    !> more after pruning), the one with each receptance's own weight (three runs of 20
    !> iterations of at most 10 trial steps) and the poles' covariance, for n_m poles at most
    !> max(p_max*N_c, 2M) and N_c(N_c + 1)/2 targets.
    pure real(dp) function polyref_flops(n_c, l, max_order) result(flops)
        real(dp), intent(in) :: n_c, l
        integer, intent(in) :: max_order

        real(dp) :: n_t, n_m, n_b, rows, p_max, k_max, p, n, na, shared, weighted
        integer :: order, top

        n_t = n_c*(n_c + 1.0_dp)/2.0_dp
        top = min(max_polynomial_order, max(2, (2*max_order + nint(n_c) - 1)/nint(n_c) + 2))
        p_max = real(top, dp)
        k_max = 2.0_dp*max_order
        n_m = max(p_max*n_c, k_max)
        n_b = 2.0_dp*n_m + 2.0_dp
        rows = 2.0_dp*l
        ! the Gram blocks of every row (complex products, 8 flop each)
        flops = n_c*(8.0_dp*l*(p_max + 1.0_dp)*n_c + 8.0_dp*l*(p_max + 1.0_dp)**2*(1.0_dp + n_c + n_c**2))
        do order = 1, top
            p = real(order, dp)
            n = (p + 1.0_dp)*n_c
            na = p*n_c
            flops = flops + n_c*(4.0_dp*(p + 1.0_dp)**3 + 2.0_dp*(p + 1.0_dp)**2*n + 2.0_dp*n**2*(p + 1.0_dp) + n**2) &
                    + 4.0_dp*na**3 + 2.0_dp*na**2*n_c + 100.0_dp*na**3 + score_flops(na)
        end do
        flops = flops + n_t*l*(3.0_dp*k_max + 2.0_dp)*20.0_dp
        do order = common_step, 2*max_order, common_step
            p = real(order, dp)
            flops = flops + n_t*(2.0_dp*(p + 1.0_dp)**2 + 10.0_dp*(p + 1.0_dp)**3) + 2.0_dp*p**3 + 100.0_dp*p**3 &
                    + score_flops(p)
        end do
        ! refine_shared (twice: the refinement and after pruning): per iteration one system with
        ! its normal matrix, at most 10 trial steps each a damped solve and a system without it
        shared = 2.0_dp*rows*n_b**2*3.0_dp + 8.0_dp*n_b**3 + 4.0_dp*rows*n_b*n_t*2.0_dp + 40.0_dp*l*n_m &
                 + 16.0_dp*rows*n_b*n_m + 2.0_dp*rows*(4.0_dp*n_m)**2 + n_t*(8.0_dp*(2.0_dp*n_m)**2 + 8.0_dp*rows*n_m)
        flops = flops + 2.0_dp*30.0_dp*(11.0_dp*shared + 10.0_dp*4.0_dp*(2.0_dp*n_m)**3)
        ! refine_weighted: three runs of 20 iterations, each target's own design per system
        weighted = n_t*(2.0_dp*rows*n_b + 2.0_dp*rows*n_b**2 + 8.0_dp*n_b**3 + 2.0_dp*n_b**2 + 4.0_dp*rows*n_b &
                        + 40.0_dp*rows*n_m + 4.0_dp*rows*n_b*n_m + 2.0_dp*rows*(2.0_dp*n_m)**2 &
                        + 4.0_dp*n_m*n_b**2 + 8.0_dp*n_m**2*n_b)
        flops = flops + 3.0_dp*20.0_dp*(11.0_dp*weighted + 10.0_dp*4.0_dp*(2.0_dp*n_m)**3) + 3.0_dp*weighted
        ! the poles' covariance: each target's design orthonormalised, the information inverted
        flops = flops + n_t*(20.0_dp*l*n_b + 8.0_dp*rows*n_b**2 + 4.0_dp*rows*n_b*n_m) + 4.0_dp*(2.0_dp*n_m)**3

    contains

        !> The MDL score of k poles: the weighted design orthonormalised twice, the targets projected.
        pure real(dp) function score_flops(k) result(score)
            real(dp), intent(in) :: k

            real(dp) :: columns

            columns = 2.0_dp*k + 2.0_dp
            score = 20.0_dp*l*columns + 8.0_dp*rows*columns**2 + 4.0_dp*rows*columns*n_t + rows*n_t
        end function score_flops
    end function polyref_flops

    !> One iteration's information: the Jacobian (2L x P), its Gram product and the gradient,
    !> the weighted residual, the projection's Schur complement and inverse [flop].
    pure real(dp) function information_flops(l, m, p, q) result(flops)
        real(dp), intent(in) :: l, m, p, q

        flops = 20.0_dp*l*p + 2.0_dp*l*p*(p + 1.0_dp) + 4.0_dp*l*p + 20.0_dp*l*m + 10.0_dp*l &
                + 4.0_dp*p**3 + 2.0_dp*q**3
    end function information_flops

    !> One trial step: scaling, Cholesky factor and solve of P unknowns, the residues by linear
    !> least squares (design 2L x Q, its Gram product, the SVD fallback: Householder 4*(2L)*Q^2
    !> and 60 Jacobi sweeps of 9*Q^3) and the model on every line [flop].
    pure real(dp) function trial_flops(l, m, p, q) result(flops)
        real(dp), intent(in) :: l, m, p, q

        flops = 2.0_dp*p**2 + p**3/3.0_dp + 4.0_dp*p**2 + 20.0_dp*l*q + 2.0_dp*l*q*(q + 1.0_dp) &
                + 8.0_dp*l*q**2 + 540.0_dp*q**3 + 20.0_dp*l*m + 10.0_dp*l
    end function trial_flops

    !> The noise estimate of one receptance: differences, their median and the smoothed |G| [flop].
    pure real(dp) function noise_flops(l) result(flops)
        real(dp), intent(in) :: l

        flops = 100.0_dp*l + 20.0_dp*l*log(max(l, 2.0_dp))/log(2.0_dp)
    end function noise_flops

    !> One iteration of refine_poles with its projections: the derivatives D (2L x 4M), D^T D,
    !> Q^T D, D^T R, the normal matrix per target, refine_attempts solves and projections
    !> (Gram-Schmidt twice, Q^T Y, the residual, Q^T B, the back substitution) [flop].
    pure real(dp) function refinement_flops(l, m, n_t, n_b) result(flops)
        real(dp), intent(in) :: l, m, n_t, n_b

        real(dp) :: rows, projection

        rows = 2.0_dp*l
        projection = 20.0_dp*l*n_b + 8.0_dp*rows*n_b**2 + 2.0_dp*rows*n_b*n_t*2.0_dp + 2.0_dp*rows*n_b**2 &
                     + n_b**2*n_t + rows*n_t
        flops = 40.0_dp*rows*m + 2.0_dp*rows*(4.0_dp*m)**2 + 2.0_dp*rows*n_b*4.0_dp*m + 2.0_dp*rows*4.0_dp*m*n_t &
                + n_t*(2.0_dp*m)**2*(2.0_dp*n_b + 8.0_dp) &
                + refine_attempts*((2.0_dp*m)**3 + projection)
    end function refinement_flops

    !> Floating-point operations per CPU second of the fits' Gram product (greenconv_ident_dense's
    !> `gram`, most of a fit's time) on this machine: a 2048 x 64 product repeated for at least
    !> `seconds` of CPU [flop/s].
    function measured_rate(seconds) result(rate)
        !> CPU time to measure over [s] (0.05 is enough for a rate within a few per cent).
        real(dp), intent(in) :: seconds
        real(dp) :: rate

        integer, parameter :: rows = 2048, columns = 64
        real(dp), allocatable :: a(:, :), b(:), product(:, :), projection(:)
        real(dp) :: start, finish, sink
        integer(int64) :: repeats
        integer :: i, j

        allocate (a(rows, columns), b(rows), product(columns, columns), projection(columns))
        do j = 1, columns
            do i = 1, rows
                a(i, j) = sin(0.001_dp*i*j) + 1.0e-3_dp*j
            end do
        end do
        b = a(:, 1)
        sink = 0.0_dp
        repeats = 0
        call cpu_time(start)
        do
            call gram(a, 1.0_dp, product, b, projection)
            sink = sink + product(1, columns)
            repeats = repeats + 1
            call cpu_time(finish)
            if (finish - start >= seconds) exit
        end do
        ! the products' sum keeps them from being optimised away
        if (.not. (sink == sink)) repeats = repeats + 1
        rate = repeats*(2.0_dp*rows*columns*(columns + 1.0_dp) + 2.0_dp*rows*columns) &
               /max(finish - start, epsilon(1.0_dp))
    end function measured_rate

    !> The bound in words: flop, seconds at the rate, the parts (a subroutine: a deferred-length
    !> function result is static storage at its call site, see tools/check_statics.sh).
    subroutine cost_text(cost, rate, text)
        !> The bound.
        type(green_cost), intent(in) :: cost
        !> Floating-point operations per second [flop/s] (`measured_rate`).
        real(dp), intent(in) :: rate
        !> The bound in words.
        character(len=:), allocatable, intent(out) :: text

        text = 'identification cost at most '//sci_text(cost%total)//' flop, '//sci_text(cost%total/rate) &
               //' s of CPU at '//sci_text(rate)//' flop/s (the fits'' Gram product measured here; pole fit ' &
               //sci_text(cost%pole_fit)//', shared-pole refinement '//sci_text(cost%refinement)//', poly-reference ' &
               //sci_text(cost%poly_reference)//', residues '//sci_text(cost%residues)//'; every limit reached at once)'
    end subroutine cost_text

end module greenconv_ident_cost
