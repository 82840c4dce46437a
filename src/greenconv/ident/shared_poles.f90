!> Shared-pole identification of a Green's matrix G_ij(omega), i, j = 1..N_c: the
!> poles are the structure's, the same in all N_c^2 receptances, so they are identified once and
!> only the residues differ from pair to pair:
!>
!>     G_ij(omega) = sum_k [R_k,ij/(i*omega - lambda_k) + conj(R_k,ij)/(i*omega - conj(lambda_k))]
!>                   + U_ij - L_ij/omega^2                                              [m/N]
!>
!> R_k the complex residue matrix [m/(N*s)] of mode k, U and L the upper and lower residual
!> matrices (present when the pole fit keeps them).
!>
!> 1. **Poles**: greenconv_ident_mlfit's `identify_ml` on the sum of the driving-point
!>    receptances, sum_i G_ii: every mode with a non-zero shape at some point shows in it with
!>    a positive-definite weight (for real modes R_k,ii = r_k*phi_ik^2 adds up without
!>    cancelling), its noise estimated from the data and the order chosen by MDL. A pair of
!>    modes of one frequency (the cosine and sine modes of a ring) gives one pole there.
!>    **Refinement** over all receptances together (`refine_poles`, variable projection): the
!>    summed driving points weigh overlapping modes together and bias their poles; with the
!>    residues eliminated by least squares, Levenberg-Marquardt moves the poles to minimise the
!>    misfit of every receptance, each weighted by its own size. On the shipped patch (1 %
!>    noise) it takes E worst from 0.026 to 0.013, at the noise; the number of poles stays the
!>    pole fit's, so the fit's max_order must let it find the modes in band (60 there).
!> 2. **Residue matrices**: for those poles, linear least squares on each receptance (the same
!>    design matrix for all, unweighted, so that the fit minimises |G - G_model|^2 as E of
!>    eq. (7) measures it), R_k general complex: a repeated pole gets the rank two its pair of
!>    modes needs. When the matrix is reciprocal the fit is to (G_ij + G_ji)/2, which makes
!>    every R_k, U, L symmetric.
!> 3. **Report**: E of eq. (7) per receptance (worst and mean), per point (of row i, all
!>    receptances at response point i together), and per mode how far R_k is from rank one,
!>    ||R_k - best rank one||_F/||R_k||_F = sqrt(1 - s_1^2/sum s^2) (s the singular values;
!>    0 for one real mode, 1/sqrt(2) for two equal modes on one pole).
!> 4. **Modes for the convolvers** (`shared_point_modes`): greenconv_model_point_modes holds
!>    real shapes; a symmetric complex R_k = A + i*B is written exactly as terms with real
!>    shapes from the eigenvectors of A and of B, R_k = sum_l a_l*v_l*v_l^T + i*sum_l b_l*w_l*w_l^T,
!>    each term a mode of pole lambda_k with residue a_l (or i*b_l) and shape v_l (w_l); terms
!>    with |a_l| or |b_l| below `term_tol` of the pole's largest are dropped. A proportionally
!>    damped mode (R_k = r_k*phi*phi^T, r_k imaginary) is one term. U and L have no place in a
!>    modal recursion: they are neglected there and reported.
module greenconv_ident_shared_poles
    use greenconv_core_kinds, only: dp
    use greenconv_core_constants, only: two_pi, i_unit
    use greenconv_core_error, only: error_type, fatal_error
    use greenconv_core_text, only: int_text
    use greenconv_model_modal_set, only: modal_set
    use greenconv_model_point_modes, only: point_modes
    use greenconv_model_frf, only: frf_type
    use greenconv_ext_lapack, only: least_squares, solve_linear
    use greenconv_ident_lsce, only: error_e
    use greenconv_ident_mlfit, only: ml_options, ml_result, identify_ml, estimate_noise, smoothed_magnitude
    use greenconv_ident_polyref, only: polyref_poles, pole_design, pole_covariance, pole_spread
    implicit none
    private

    public :: shared_fit, identify_shared, shared_point_modes, shared_receptance
    public :: refine_iterations, refine_attempts

    !> Most Gauss-Newton iterations of the poles' refinement over all receptances (`refine_poles`),
    !> and most trial steps (mu raised tenfold each) per iteration.
    integer, parameter :: refine_iterations = 40, refine_attempts = 8


    !> A Green's matrix identified with shared poles.
    type :: shared_fit
        !> The fit of the summed driving points that gave the poles (order, noise, warnings).
        type(ml_result) :: pole_fit
        !> Noise level of the summed driving points relative to their |sum G_ii| (estimated
        !> from the sum's smoothness, times the factor the pole fit's residual asks).
        real(dp) :: noise_level = 0.0_dp
        !> Poles lambda_k [rad/s] (Re < 0 < Im), by frequency.
        complex(dp), allocatable :: pole(:)
        !> Residue matrices residue(i, j, k) = R_k,ij [m/(N*s)].
        complex(dp), allocatable :: residue(:, :, :)
        !> Upper residual matrix U [m/N] (zero unless the pole fit kept R_u).
        real(dp), allocatable :: upper(:, :)
        !> Lower residual matrix L [1/kg] of -L/omega^2 (zero unless the pole fit kept R_l).
        real(dp), allocatable :: lower(:, :)
        !> Whether R_k, U, L were fitted to (G_ij + G_ji)/2 (symmetric).
        logical :: symmetric = .true.
        !> E of eq. (7) of each receptance, e_pair(i, j).
        real(dp), allocatable :: e_pair(:, :)
        !> E of eq. (7) of each response point i over its row of receptances.
        real(dp), allocatable :: e_point(:)
        !> Largest and mean E over the receptances.
        real(dp) :: e_worst = 0.0_dp, e_mean = 0.0_dp
        !> Distance of each R_k from rank one, sqrt(1 - s_1^2/sum s^2).
        real(dp), allocatable :: rank_one(:)
        !> Whether the poles came from the poly-reference fit of all receptances
        !> (greenconv_ident_polyref) rather than from the summed driving points.
        logical :: poly_reference = .false.
        !> The order the poly-reference fit kept: matrix order p > 0, -p for the common
        !> denominator of order p (0 for the summed driving points).
        integer :: order = 0
        !> Standard deviations of each pole's natural frequency [Hz] and damping ratio at the
        !> Cramer-Rao bound of the shared-pole model for the estimated noise (poly-reference only).
        real(dp), allocatable :: sigma_f(:), sigma_xi(:)
    end type shared_fit

contains

    !> Identify a Green's matrix with shared poles (see the module description).
    subroutine identify_shared(frequency, g, symmetric, options, fit, error, poly_reference)
        !> Frequency lines f_l = l*df, l = 0..n - 1 [Hz] (uniform, from 0 Hz).
        real(dp), intent(in) :: frequency(:)
        !> Receptances g(i, j, l) = G_ij(2*pi*f_l) [m/N].
        complex(dp), intent(in) :: g(:, :, :)
        !> Fit (G_ij + G_ji)/2 (a reciprocal structure) rather than each G_ij on its own.
        logical, intent(in) :: symmetric
        !> Settings of the pole fit (greenconv_ident_mlfit).
        type(ml_options), intent(in) :: options
        !> The identification.
        type(shared_fit), intent(out) :: fit
        !> Set when the grid is not uniform from 0 Hz, the pole fit fails or finds no mode.
        type(error_type), allocatable, intent(out) :: error
        !> Take the poles from all receptances by the poly-reference fit (`identify_polyref`)
        !> instead of the summed driving points (default false).
        logical, intent(in), optional :: poly_reference

        type(frf_type) :: summed
        type(ml_options) :: pole_options
        complex(dp), allocatable :: model(:, :, :)
        real(dp), allocatable :: variance(:)
        real(dp) :: level
        integer :: i, n_c

        if (present(poly_reference)) then
            if (poly_reference) then
                call identify_polyref(frequency, g, symmetric, options%max_order, fit, error)
                return
            end if
        end if
        n_c = size(g, 1)
        summed%frequency = frequency
        allocate (summed%receptance(size(frequency)))
        summed%receptance(:) = 0.0_dp
        do i = 1, n_c
            summed%receptance = summed%receptance + g(i, i, :)
        end do
        ! The sum's noise, sigma_l = rho*|sum G_ii| with rho from the sum's smoothness, is at
        ! least the driving points' own added in quadrature, sqrt(sum_i (rho_i*|G_ii,l|)^2):
        ! near an anti-resonance of the sum its |G| is far below the noise of its terms, and
        ! a noise taken relative to the sum alone lets the fit put spurious poles there.
        pole_options = options
        ! The residues of every G_ij are fitted later with R_u and R_l only: no pseudo-modes above
        ! the band for the sum either (they are for a single FRF).
        pole_options%outside_modes = 'none'
        level = 1.0_dp
        if (.not. allocated(options%sigma)) then
            level = estimate_noise(summed%receptance, 'relative')
            allocate (variance(size(frequency)))
            variance(:) = 0.0_dp
            do i = 1, n_c
                variance = variance + (estimate_noise(g(i, i, :), 'relative')*smoothed_magnitude(g(i, i, :)))**2
            end do
            pole_options%sigma = max(level*smoothed_magnitude(summed%receptance), sqrt(variance))
        end if
        call identify_ml(summed, pole_options, fit%pole_fit, error)
        if (allocated(error)) then
            error%message = 'shared poles: the sum of the driving-point receptances: '//error%message
            return
        end if
        if (fit%pole_fit%modes%n_modes() == 0) then
            call fatal_error(error, 'shared poles: no mode found in the sum of the driving-point receptances; ' &
                             //'check the file''s units and band')
            return
        end if
        fit%noise_level = level*fit%pole_fit%noise_level_fit
        fit%pole = fit%pole_fit%modes%pole
        fit%symmetric = symmetric
        call refine_poles(frequency, g, fit)
        call fit_residues(frequency, g, fit, error)
        if (allocated(error)) return
        call shared_receptance(fit, frequency, model)
        call report_errors(g, model, fit)
    end subroutine identify_shared

    !> Identify with the poles of the poly-reference fit of all receptances (greenconv_ident_polyref,
    !> order by MDL), the residue matrices and both residual terms by linear least squares, the
    !> noise from the residual of that model relative to its size (noise proportional to |G|:
    !> E|G - G_model|^2 = rho^2*|G|^2 on every line), rho^2 = sum |G - G_model|^2/sum |G_model|^2
    !> * n/(n - K/2) over the distinct receptances' lines above 0 Hz (n complex data, K real
    !> parameters; a reciprocal pair's mean has half the variance); the ratio of sums, not a sum
    !> of ratios, so that anti-resonances, where |G_model| is small, do not dominate it
    !> over the distinct receptances' lines above 0 Hz (n complex data, K real parameters), and
    !> each pole's Cramer-Rao spread for that noise.
    subroutine identify_polyref(frequency, g, symmetric, max_modes, fit, error)
        real(dp), intent(in) :: frequency(:)
        complex(dp), intent(in) :: g(:, :, :)
        logical, intent(in) :: symmetric
        integer, intent(in) :: max_modes
        type(shared_fit), intent(out) :: fit
        type(error_type), allocatable, intent(out) :: error

        complex(dp), allocatable :: model(:, :, :), target(:, :, :), residue(:, :), trial_model(:, :, :)
        type(shared_fit) :: trial
        real(dp), allocatable :: sigma(:, :), covariance(:, :)
        integer, allocatable :: lines(:)
        type(error_type), allocatable :: no_bound
        real(dp) :: misfit, energy
        integer :: i, j, l, q, n_c, n_t, n_m

        n_c = size(g, 1)
        target = g
        if (symmetric) then
            do l = 1, size(frequency)
                target(:, :, l) = 0.5_dp*(g(:, :, l) + transpose(g(:, :, l)))
            end do
        end if
        call polyref_poles(frequency, target, max_modes, fit%pole, fit%order, error, averaged=symmetric)
        if (allocated(error)) return
        fit%poly_reference = .true.
        fit%symmetric = symmetric
        fit%pole_fit%has_upper = .true.
        ! a file with a line at 0 Hz gives G(0) finite: no mode below its band, so no lower
        ! residual -L/omega^2 (infinite at 0 Hz); MDL would otherwise choose it on round-off alone
        ! for exact data, and a fit with L cannot extend the band above f_max
        fit%pole_fit%has_lower = frequency(1) > 0.0_dp
        call fit_residues(frequency, g, fit, error)
        if (allocated(error)) return
        lines = pack([(l, l=1, size(frequency))], frequency > 0.0_dp)
        call shared_receptance(fit, frequency, model)
        ! the lower residual only when the data ask for it (MDL: n_t more parameters): a structure
        ! with no mode below the band gets none, so that its g from the model is not skewed by a
        ! -L/omega^2 fitted to noise
        trial = fit
        trial%pole_fit%has_lower = .false.
        if (allocated(trial%residue)) deallocate (trial%residue)
        if (allocated(trial%upper)) deallocate (trial%upper)
        if (allocated(trial%lower)) deallocate (trial%lower)
        if (fit%pole_fit%has_lower) call fit_residues(frequency, g, trial, no_bound)
        if (fit%pole_fit%has_lower .and. .not. allocated(no_bound)) then
            call shared_receptance(trial, frequency, trial_model)
            misfit = relative_misfit(target(:, :, lines), model(:, :, lines))
            energy = relative_misfit(target(:, :, lines), trial_model(:, :, lines))
            n_t = n_c*(n_c + 1)/2
            if (n_t*size(lines)*log(energy/max(misfit, tiny(1.0_dp))) <= 0.5_dp*n_t*log(2.0_dp*n_t*size(lines))) then
                fit = trial
                model = trial_model
            end if
        end if
        call report_errors(g, model, fit)
        n_m = size(fit%pole)
        n_t = n_c*(n_c + 1)/2
        allocate (sigma(n_t, size(lines)), residue(n_t, n_m))
        misfit = 0.0_dp
        energy = 0.0_dp
        q = 0
        do j = 1, n_c
            do i = j, n_c
                q = q + 1
                ! a reciprocal pair's mean holds two measurements: half the variance
                sigma(q, :) = max(abs(model(i, j, lines)), tiny(1.0_dp))/merge(sqrt(2.0_dp), 1.0_dp, symmetric .and. i /= j)
                misfit = misfit + sum(abs(target(i, j, lines) - model(i, j, lines))**2)*merge(2, 1, symmetric .and. i /= j)
                energy = energy + sum(abs(model(i, j, lines))**2)
                residue(q, :) = fit%residue(i, j, :)
            end do
        end do
        fit%noise_level = sqrt(misfit/energy*n_t*size(lines)/max(1.0_dp, n_t*size(lines) - real(n_m + (n_m + 1)*n_t, dp)))
        fit%pole_fit%noise_level_fit = fit%noise_level
        sigma = fit%noise_level*sigma
        allocate (fit%sigma_f(n_m), fit%sigma_xi(n_m))
        fit%sigma_f(:) = huge(1.0_dp)
        fit%sigma_xi(:) = huge(1.0_dp)
        call pole_covariance(frequency(lines), fit%pole, residue, sigma, covariance, no_bound)
        if (.not. allocated(no_bound)) call pole_spread(fit%pole, covariance, fit%sigma_f, fit%sigma_xi)
    end subroutine identify_polyref

    !> sum |target - model|^2/|target|^2 over the distinct receptances (i >= j) and the lines given.
    pure real(dp) function relative_misfit(target, model) result(misfit)
        complex(dp), intent(in) :: target(:, :, :), model(:, :, :)

        integer :: i, j

        misfit = 0.0_dp
        do j = 1, size(target, 1)
            do i = j, size(target, 1)
                misfit = misfit + sum(abs(target(i, j, :) - model(i, j, :))**2/max(abs(target(i, j, :)), tiny(1.0_dp))**2)
            end do
        end do
    end function relative_misfit

    !> Residue and residual matrices by linear least squares for the fit's poles.
    subroutine fit_residues(frequency, g, fit, error)
        real(dp), intent(in) :: frequency(:)
        complex(dp), intent(in) :: g(:, :, :)
        type(shared_fit), intent(inout) :: fit
        type(error_type), allocatable, intent(out) :: error

        real(dp), allocatable :: design(:, :), x(:), rhs(:)
        complex(dp), allocatable :: target(:)
        integer, allocatable :: lines(:)
        integer :: n_c, n_m, n_p, i, j, l, i_u, i_l

        n_c = size(g, 1)
        n_m = size(fit%pole)
        if (fit%pole_fit%has_lower) then
            allocate (lines(count(frequency > 0.0_dp)))
            lines(:) = pack([(l, l=1, size(frequency))], frequency > 0.0_dp)
        else
            allocate (lines(size(frequency)))
            lines(:) = [(l, l=1, size(frequency))]
        end if
        n_p = 2*n_m
        i_u = 0
        i_l = 0
        if (fit%pole_fit%has_upper) then
            n_p = n_p + 1
            i_u = n_p
        end if
        if (fit%pole_fit%has_lower) then
            n_p = n_p + 1
            i_l = n_p
        end if
        design = pole_design(frequency(lines), fit%pole, i_u > 0, i_l > 0)
        allocate (fit%residue(n_c, n_c, n_m), fit%upper(n_c, n_c), fit%lower(n_c, n_c), x(n_p))
        fit%upper(:, :) = 0.0_dp
        fit%lower(:, :) = 0.0_dp
        do j = 1, n_c
            do i = 1, n_c
                if (fit%symmetric .and. i < j) then
                    fit%residue(i, j, :) = fit%residue(j, i, :)
                    fit%upper(i, j) = fit%upper(j, i)
                    fit%lower(i, j) = fit%lower(j, i)
                    cycle
                end if
                target = g(i, j, lines)
                if (fit%symmetric) target = 0.5_dp*(g(i, j, lines) + g(j, i, lines))
                rhs = [real(target, kind=dp), aimag(target)]
                call least_squares(design, rhs, x, error)
                if (allocated(error)) then
                    error%message = 'shared poles: residues of G_'//int_text(i)//','//int_text(j)//': ' &
                                    //error%message
                    return
                end if
                fit%residue(i, j, :) = cmplx(x(1:2*n_m:2), x(2:2*n_m:2), kind=dp)
                if (i_u > 0) fit%upper(i, j) = x(i_u)
                if (i_l > 0) fit%lower(i, j) = x(i_l)
            end do
        end do
    end subroutine fit_residues

    !> Refine the poles over all receptances together (variable projection): the residues are
    !> eliminated by least squares for given poles, and Levenberg-Marquardt moves the poles to
    !> minimise sum_t ||P y_t||^2, y_t = G_ij/||G_ij||_1 (each receptance weighted by its own
    !> size, as E of eq. (7) is relative per receptance) and P the projection off the design
    !> matrix B of the poles' columns. The poles of the summed driving points are biased where
    !> modes overlap; every receptance weighs the modes by its own shapes, which separates them.
    !> A step is kept only when it lowers the cost and leaves every pole stable, so the result
    !> is never worse than the start.
    !>
    !> The Gauss-Newton system is Kaufman's (Kaufman 1975; Golub & Pereyra 2003), from the
    !> columns' analytic derivatives: for target t with coefficients c_t = B^+ y_t, the Jacobian
    !> is J_t = -P E_t, column q of E_t the derivative of B in parameter q applied to c_t. Pole k
    !> moves only its own two columns, so E_t(:, q) = d_q1*c_k1,t + d_q2*c_k2,t with the four
    !> derivative columns d of each pole (D, 2*N_l x 4*N_m). The normal matrix
    !> sum_t E_t^T E_t - (Q^T E_t)^T (Q^T E_t) (Q an orthonormal basis of B's columns) and the
    !> gradient -sum_t E_t^T r_t then come from D^T D, Q^T D and D^T R, computed once per
    !> iteration whatever the number of targets: the cost of an iteration is that of about two
    !> projections (N_l lines, N_t targets, N_m poles: 2*N_l*(16*N_m^2 + 4*N_m*N_t) products and
    !> N_t*(2*N_m)^2*(N_b + 4) more), where finite differences took 2*N_m + 1 projections.
    subroutine refine_poles(frequency, g, fit)
        !> Frequency lines [Hz].
        real(dp), intent(in) :: frequency(:)
        !> Receptances g(i, j, l) [m/N].
        complex(dp), intent(in) :: g(:, :, :)
        !> The fit; its poles are replaced by the refined ones.
        type(shared_fit), intent(inout) :: fit

        real(dp), allocatable :: targets(:, :), scale(:), p(:), trial(:), r(:, :), r_trial(:, :)
        real(dp), allocatable :: normal(:, :), gradient(:), step(:), lhs(:, :), q_basis(:, :), coefficients(:, :)
        real(dp), allocatable :: derivative(:, :), d_gram(:, :), q_d(:, :), d_r(:, :), e_q(:, :)
        real(dp), allocatable :: basis_trial(:, :), coefficients_trial(:, :)
        integer, allocatable :: lines(:)
        type(error_type), allocatable :: failed
        real(dp) :: cost, cost_trial, mu, c1, c2, c1b, c2b
        integer :: n_c, n_m, n_t, n_l, i, j, q, qq, k, kk, l, t, iteration, attempt
        logical :: accepted

        n_c = size(g, 1)
        n_m = size(fit%pole)
        if (fit%pole_fit%has_lower) then
            lines = pack([(l, l=1, size(frequency))], frequency > 0.0_dp)
        else
            lines = [(l, l=1, size(frequency))]
        end if
        n_l = size(lines)
        n_t = merge(n_c*(n_c + 1)/2, n_c*n_c, fit%symmetric)
        allocate (targets(2*n_l, n_t))
        q = 0
        do j = 1, n_c
            do i = 1, n_c
                if (fit%symmetric .and. i < j) cycle
                q = q + 1
                associate (y => merge(0.5_dp*(g(i, j, lines) + g(j, i, lines)), g(i, j, lines), fit%symmetric))
                    targets(:, q) = [real(y, kind=dp), aimag(y)]/max(sum(abs(y)), tiny(1.0_dp))
                end associate
            end do
        end do
        scale = abs(fit%pole)
        allocate (p(2*n_m))
        p(1:2*n_m:2) = aimag(fit%pole)/scale
        p(2:2*n_m:2) = real(fit%pole, kind=dp)/scale
        call project(p, r, q_basis, coefficients)
        cost = sum(r**2)
        cost_trial = cost
        mu = 1.0e-3_dp
        allocate (normal(2*n_m, 2*n_m), gradient(2*n_m), e_q(size(q_basis, 2), 2*n_m))
        do iteration = 1, refine_iterations
            derivative = pole_derivatives(p)
            d_gram = matmul(transpose(derivative), derivative)
            q_d = matmul(transpose(q_basis), derivative)
            d_r = matmul(transpose(derivative), r)
            normal(:, :) = 0.0_dp
            gradient(:) = 0.0_dp
            do t = 1, n_t
                ! E_t(:, q) = d(:, 2q-1)*c_k1 + d(:, 2q)*c_k2, k the pole of parameter q
                do q = 1, 2*n_m
                    k = (q + 1)/2
                    c1 = coefficients(2*k - 1, t)
                    c2 = coefficients(2*k, t)
                    e_q(:, q) = q_d(:, 2*q - 1)*c1 + q_d(:, 2*q)*c2
                    gradient(q) = gradient(q) - (d_r(2*q - 1, t)*c1 + d_r(2*q, t)*c2)
                    do qq = 1, q
                        kk = (qq + 1)/2
                        c1b = coefficients(2*kk - 1, t)
                        c2b = coefficients(2*kk, t)
                        normal(qq, q) = normal(qq, q) + c1*(d_gram(2*qq - 1, 2*q - 1)*c1b + d_gram(2*qq, 2*q - 1)*c2b) &
                                        + c2*(d_gram(2*qq - 1, 2*q)*c1b + d_gram(2*qq, 2*q)*c2b)
                    end do
                end do
                normal = normal - upper_gram(e_q)
            end do
            do q = 1, 2*n_m
                normal(q + 1:, q) = normal(q, q + 1:)
            end do
            accepted = .false.
            do attempt = 1, refine_attempts
                lhs = normal
                do q = 1, 2*n_m
                    lhs(q, q) = normal(q, q)*(1.0_dp + mu) + tiny(1.0_dp)
                end do
                allocate (step(2*n_m))
                call solve_linear(lhs, -gradient, step, failed)
                trial = p + step
                deallocate (step)
                if (.not. allocated(failed) .and. all(trial(2:2*n_m:2) < 0.0_dp) &
                    .and. all(trial(1:2*n_m:2) > 0.0_dp)) then
                    call project(trial, r_trial, basis_trial, coefficients_trial)
                    cost_trial = sum(r_trial**2)
                    if (cost_trial < cost) then
                        accepted = .true.
                        exit
                    end if
                end if
                if (allocated(failed)) deallocate (failed)
                mu = 10.0_dp*mu
            end do
            if (.not. accepted) exit
            p = trial
            call move_alloc(r_trial, r)
            call move_alloc(basis_trial, q_basis)
            call move_alloc(coefficients_trial, coefficients)
            mu = max(mu/3.0_dp, 1.0e-9_dp)
            if (cost - cost_trial < 1.0e-8_dp*cost) then
                cost = cost_trial
                exit
            end if
            cost = cost_trial
        end do
        fit%pole = cmplx(p(2:2*n_m:2)*scale, p(1:2*n_m:2)*scale, kind=dp)

    contains

        !> The poles of (scaled) parameters.
        pure function poles_of(parameters) result(pole)
            real(dp), intent(in) :: parameters(:)
            complex(dp) :: pole(n_m)

            pole = cmplx(parameters(2:2*n_m:2)*scale, parameters(1:2*n_m:2)*scale, kind=dp)
        end function poles_of

        !> The part of every target that the model of these (scaled) poles cannot fit, R = P Y
        !> (2*N_l x N_t); with `basis` and `coefficients` also Q, an orthonormal basis of B's
        !> columns (Gram-Schmidt, twice for round-off), and C = B^+ Y.
        subroutine project(parameters, residual, basis, coefficients)
            real(dp), intent(in) :: parameters(:)
            real(dp), allocatable, intent(out) :: residual(:, :)
            real(dp), allocatable, intent(out), optional :: basis(:, :), coefficients(:, :)

            real(dp), allocatable :: design(:, :), ortho(:, :), triangle(:, :), solution(:, :)
            integer :: col, pass, row

            allocate (design(2*n_l, 2*n_m + merge(1, 0, fit%pole_fit%has_upper) &
                             + merge(1, 0, fit%pole_fit%has_lower)))
            design(:, :) = pole_design(frequency(lines), poles_of(parameters), fit%pole_fit%has_upper, &
                                       fit%pole_fit%has_lower)
            ortho = design
            do col = 1, size(ortho, 2)
                do pass = 1, 2
                    if (col > 1) ortho(:, col) = ortho(:, col) - matmul(ortho(:, :col - 1), &
                                                                        matmul(ortho(:, col), ortho(:, :col - 1)))
                    if (norm2(ortho(:, col)) > 0.0_dp) ortho(:, col) = ortho(:, col)/norm2(ortho(:, col))
                end do
            end do
            solution = matmul(transpose(ortho), targets)
            residual = targets - matmul(ortho, solution)
            if (.not. present(basis)) return
            ! B = Q T with T = Q^T B upper triangular: C = T^-1 Q^T Y by back substitution (a
            ! column of B that Gram-Schmidt found dependent has a zero pivot and no coefficient)
            triangle = matmul(transpose(ortho), design)
            do row = size(triangle, 1), 1, -1
                if (row < size(triangle, 1)) solution(row, :) = solution(row, :) &
                    - matmul(triangle(row, row + 1:), solution(row + 1:, :))
                if (abs(triangle(row, row)) > 0.0_dp) then
                    solution(row, :) = solution(row, :)/triangle(row, row)
                else
                    solution(row, :) = 0.0_dp
                end if
            end do
            call move_alloc(ortho, basis)
            call move_alloc(solution, coefficients)
        end subroutine project

        !> The derivatives of each pole's two columns of B in its two parameters, stacked
        !> [Re; Im] (2*N_l x 4*N_m): for parameter q (Im lambda_k/|lambda_k| when odd, Re when
        !> even) the columns 2q-1 and 2q are d b_k1/dp_q and d b_k2/dp_q, with
        !> b_k1 = 1/(s - lambda) + 1/(s - conj(lambda)), b_k2 = i*(1/(s - lambda) - 1/(s - conj(lambda))).
        function pole_derivatives(parameters) result(d)
            real(dp), intent(in) :: parameters(:)
            real(dp), allocatable :: d(:, :)

            complex(dp) :: pole(n_m), direct(n_l), mirror(n_l), column(n_l, 4)
            integer :: m

            pole = poles_of(parameters)
            allocate (d(2*n_l, 4*n_m))
            do m = 1, n_m
                direct = scale(m)/(i_unit*two_pi*frequency(lines) - pole(m))**2
                mirror = scale(m)/(i_unit*two_pi*frequency(lines) - conjg(pole(m)))**2
                ! parameter Im: d lambda = i*scale, d conj(lambda) = -i*scale
                column(:, 1) = i_unit*(direct - mirror)
                column(:, 2) = -(direct + mirror)
                ! parameter Re: d lambda = d conj(lambda) = scale
                column(:, 3) = direct + mirror
                column(:, 4) = i_unit*(direct - mirror)
                d(1:n_l, 4*m - 3:4*m) = real(column, kind=dp)
                d(n_l + 1:, 4*m - 3:4*m) = aimag(column)
            end do
        end function pole_derivatives

        !> The upper triangle of A^T A (the strict lower triangle zero).
        pure function upper_gram(a) result(product)
            real(dp), intent(in) :: a(:, :)
            real(dp) :: product(size(a, 2), size(a, 2))

            integer :: col

            product = 0.0_dp
            do col = 1, size(a, 2)
                product(1:col, col) = matmul(a(:, col), a(:, 1:col))
            end do
        end function upper_gram

    end subroutine refine_poles

    !> The receptances of a shared-pole model, model(i, j, l) = G_ij(2*pi*f_l) [m/N]; a lower
    !> residual is left out at 0 Hz (infinite there).
    pure subroutine shared_receptance(fit, frequency, model)
        !> The identification.
        type(shared_fit), intent(in) :: fit
        !> Frequencies [Hz].
        real(dp), intent(in) :: frequency(:)
        !> The model's receptances [m/N].
        complex(dp), allocatable, intent(out) :: model(:, :, :)

        complex(dp) :: s
        integer :: k, l

        allocate (model(size(fit%residue, 1), size(fit%residue, 2), size(frequency)))
        do l = 1, size(frequency)
            s = i_unit*two_pi*frequency(l)
            model(:, :, l) = fit%upper
            if (frequency(l) > 0.0_dp) model(:, :, l) = model(:, :, l) + fit%lower/s**2
            do k = 1, size(fit%pole)
                model(:, :, l) = model(:, :, l) + fit%residue(:, :, k)/(s - fit%pole(k)) &
                                 + conjg(fit%residue(:, :, k))/(s - conjg(fit%pole(k)))
            end do
        end do
    end subroutine shared_receptance

    !> E of eq. (7) per receptance and per point, and each residue matrix's distance from rank one.
    subroutine report_errors(g, model, fit)
        complex(dp), intent(in) :: g(:, :, :), model(:, :, :)
        type(shared_fit), intent(inout) :: fit

        integer :: i, j, k, n_c

        n_c = size(g, 1)
        allocate (fit%e_pair(n_c, n_c), fit%e_point(n_c), fit%rank_one(size(fit%pole)))
        do j = 1, n_c
            do i = 1, n_c
                fit%e_pair(i, j) = error_e(g(i, j, :), model(i, j, :))
            end do
        end do
        do i = 1, n_c
            fit%e_point(i) = error_e(reshape(g(i, :, :), [size(g(i, :, :))]), &
                                     reshape(model(i, :, :), [size(model(i, :, :))]))
        end do
        fit%e_worst = maxval(fit%e_pair)
        fit%e_mean = sum(fit%e_pair)/n_c**2
        do k = 1, size(fit%pole)
            fit%rank_one(k) = rank_one_distance(fit%residue(:, :, k))
        end do
    end subroutine report_errors

    !> sqrt(1 - s_1^2/||R||_F^2), s_1 the largest singular value of R (power iteration on R^H*R).
    pure real(dp) function rank_one_distance(r) result(distance)
        complex(dp), intent(in) :: r(:, :)

        complex(dp) :: v(size(r, 2)), w(size(r, 2))
        real(dp) :: frobenius, s1_squared
        integer :: iteration

        frobenius = sum(abs(r)**2)
        distance = 0.0_dp
        if (frobenius <= 0.0_dp) return
        v = sum(abs(r), dim=1) + 1.0_dp
        v = v/norm2(abs(v))
        s1_squared = 0.0_dp
        do iteration = 1, 500
            w = matmul(conjg(transpose(r)), matmul(r, v))
            s1_squared = real(dot_product(v, w), kind=dp)
            if (norm2(abs(w)) <= 0.0_dp) exit
            v = w/norm2(abs(w))
        end do
        distance = sqrt(max(0.0_dp, 1.0_dp - s1_squared/frobenius))
    end function rank_one_distance

    !> The fit as modes with real shapes at the points, for the multi-point convolvers (see the
    !> module description, 4.): the symmetric part of each R_k split into eigen-terms; terms below
    !> `term_tol` of the pole's largest dropped. U and L are not part of it.
    pure subroutine shared_point_modes(fit, term_tol, modes)
        !> The identification.
        type(shared_fit), intent(in) :: fit
        !> Terms with |eigenvalue| below this fraction of the pole's largest are dropped (e.g. 1e-10).
        real(dp), intent(in) :: term_tol
        !> Poles, residues and real shapes (N_c x terms).
        type(point_modes), intent(out) :: modes

        real(dp), allocatable :: a(:, :), b(:, :), va(:, :), vb(:, :), ea(:), eb(:)
        complex(dp), allocatable :: pole(:), residue(:)
        real(dp), allocatable :: shape(:, :)
        real(dp) :: largest
        integer :: k, l, n_c

        n_c = size(fit%residue, 1)
        allocate (pole(0), residue(0), shape(n_c, 0), a(n_c, n_c), b(n_c, n_c))
        do k = 1, size(fit%pole)
            a(:, :) = 0.5_dp*real(fit%residue(:, :, k) + transpose(fit%residue(:, :, k)), kind=dp)
            b(:, :) = 0.5_dp*aimag(fit%residue(:, :, k) + transpose(fit%residue(:, :, k)))
            call symmetric_eigen(a, ea, va)
            call symmetric_eigen(b, eb, vb)
            largest = max(maxval(abs(ea)), maxval(abs(eb)))
            do l = 1, n_c
                if (abs(ea(l)) > term_tol*largest) then
                    pole = [pole, fit%pole(k)]
                    residue = [residue, cmplx(ea(l), 0.0_dp, kind=dp)]
                    shape = reshape([shape, va(:, l)], [n_c, size(shape, 2) + 1])
                end if
                if (abs(eb(l)) > term_tol*largest) then
                    pole = [pole, fit%pole(k)]
                    residue = [residue, cmplx(0.0_dp, eb(l), kind=dp)]
                    shape = reshape([shape, vb(:, l)], [n_c, size(shape, 2) + 1])
                end if
            end do
        end do
        modes%modes = modal_set(pole, residue)
        modes%shape = shape
    end subroutine shared_point_modes

    !> Eigenvalues and eigenvectors (columns) of a small real symmetric matrix by cyclic Jacobi
    !> rotations, to round-off.
    pure subroutine symmetric_eigen(matrix, values, vectors)
        real(dp), intent(in) :: matrix(:, :)
        real(dp), allocatable, intent(out) :: values(:)
        real(dp), allocatable, intent(out) :: vectors(:, :)

        real(dp), allocatable :: a(:, :), column_p(:), column_q(:)
        real(dp) :: theta, t, c, s, off, scale
        integer :: n, p, q, sweep

        n = size(matrix, 1)
        allocate (a(n, n), column_p(n), column_q(n), vectors(n, n), values(n))
        a(:, :) = matrix
        vectors(:, :) = 0.0_dp
        do p = 1, n
            vectors(p, p) = 1.0_dp
        end do
        scale = sum(a**2)
        do sweep = 1, 60
            off = 0.0_dp
            do q = 2, n
                do p = 1, q - 1
                    off = off + a(p, q)**2
                end do
            end do
            if (off <= 1.0e-32_dp*scale .or. scale <= 0.0_dp) exit
            do q = 2, n
                do p = 1, q - 1
                    if (abs(a(p, q)) <= tiny(1.0_dp)) cycle
                    theta = (a(q, q) - a(p, p))/(2.0_dp*a(p, q))
                    t = sign(1.0_dp, theta)/(abs(theta) + sqrt(theta**2 + 1.0_dp))
                    c = 1.0_dp/sqrt(t**2 + 1.0_dp)
                    s = t*c
                    column_p = a(:, p)
                    column_q = a(:, q)
                    a(:, p) = c*column_p - s*column_q
                    a(:, q) = s*column_p + c*column_q
                    column_p = a(p, :)
                    column_q = a(q, :)
                    a(p, :) = c*column_p - s*column_q
                    a(q, :) = s*column_p + c*column_q
                    column_p = vectors(:, p)
                    column_q = vectors(:, q)
                    vectors(:, p) = c*column_p - s*column_q
                    vectors(:, q) = s*column_p + c*column_q
                end do
            end do
        end do
        do p = 1, n
            values(p) = a(p, p)
        end do
    end subroutine symmetric_eigen

end module greenconv_ident_shared_poles
