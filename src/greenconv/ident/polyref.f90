!> Poly-reference estimation of the poles of a Green's matrix G_ij(omega) (issues 23 and 26):
!> every row of the matrix, not only the summed driving points, takes part, so that modes whose
!> peaks overlap are told apart by their different shapes across the points.
!>
!> **Model** (a right matrix-fraction description in the discrete frequency variable
!> z = exp(i*omega*dt_z), dt_z = 1/(2*f_max), which keeps the powers of z of modulus one and the
!> equations well conditioned): for each response point o, the row H_o(omega) (1 x N_c) is
!>
!>     H_o(omega)*A(z) = B_o(z),   A(z) = sum_{r=0..p} z^r*alpha_r (N_c x N_c),
!>     B_o(z) = sum_{r=0..p} z^r*beta_o,r (1 x N_c),
!>
!> with real coefficients. The equation error w_o(omega)*(B_o - H_o*A) is minimised in the
!> least-squares sense over all lines above 0 Hz, w_o = 1/rms_i|H_oi| (each line relative to the
!> row's size there). The numerators are eliminated row by row (the reduced normal equations
!> M = sum_o (T_o - S_o^T*R_o^-1*S_o), R, S, T the real parts of the Gram matrices of the
!> numerator and denominator regressors), alpha_p = I fixes the scale, and the poles are the
!> eigenvalues z_k of the block companion matrix of A, lambda_k = ln(z_k)/dt_z. One order p gives
!> up to p*N_c poles, so a few orders cover many modes.
!>
!> **Common denominator**: the matrix fraction fails where the structure has more modes than a
!> few matrix orders resolve and its modes above the band weigh as much as those inside (the
!> shipped patch: 59 modes below 600 Hz, 1523 above, 12 points within 10 cm; no order found
!> one of its 2 % poles). So the poles of one scalar polynomial a(z) = sum_{r=0..p} a_r*z^r shared
!> by every receptance, G_t(omega)*a(z) = b_t(z), are tried too (the classical least-squares
!> complex-frequency estimator on all receptances): each line of target t weighted by 1/|G_t|
!> (relative, as the noise), the numerators eliminated target by target from Toeplitz normal
!> equations, a_p = 1, the poles the roots of a(z) (orders p = 6, 12, .., 2*max_modes).
!>
!> **Order from the data**: for every order (matrix p = 1..p_max and every common-denominator
!> order) the physical poles (stable, damping
!> ratio below `max_damping`, inside the band) are scored by MDL, with the residues of every
!> G_ij (and an upper and a lower residual) fitted by linear least squares on one shared design
!> (lines weighted by the targets' common relative size):
!>
!>     MDL(p) = N/2*ln(RSS_p) + K_p/2*ln(N),   K_p = 2*n_m + (2*n_m + 2)*n_targets,
!>
!> N the number of real data; the order of least MDL is kept.
!>
!> **Refinement**: the poles of that order are refined over all receptances by variable
!> projection, first with the targets' common weight per line (`refine_shared`: one design for
!> all, cheap), then by maximum likelihood for noise relative to each receptance
!> (`refine_weighted`): line l of receptance t weighted by its own 1/|G_t(omega_l)| (from the
!> data, then from the model of the first pass), so that the estimator's covariance is the
!> Cramer-Rao bound below. The Fisher information of the
!> shared-pole model (`pole_covariance`) gives the Cramer-Rao bound of the poles for a given
!> noise per line, with the residues and residual terms as nuisance parameters.
module greenconv_ident_polyref
    use greenconv_core_kinds, only: dp
    use greenconv_core_constants, only: two_pi, i_unit
    use greenconv_core_error, only: error_type, fatal_error
    use greenconv_ext_lapack, only: eigenvalues, solve_linear
    use greenconv_model_modal_set, only: sorted_order
    use greenconv_ident_dense, only: spd_inverse, gram_product => gram
    implicit none
    private

    public :: polyref_poles, pole_covariance, pole_design, pole_spread
    public :: max_polynomial_order, common_step

    !> Poles with a larger damping ratio are taken as mathematical, not modes.
    real(dp), parameter :: max_damping = 0.3_dp
    !> Largest matrix-polynomial order tried.
    integer, parameter :: max_polynomial_order = 24
    !> Step between the orders of the common denominator tried.
    integer, parameter :: common_step = 6

    !> A least-squares problem in the poles for `levenberg_marquardt`: its data travel with it,
    !> so no internal procedure is passed as an argument (that would need an executable stack).
    type, abstract :: pole_problem
    contains
        !> The misfit of given poles and, when asked, its normal equations.
        procedure(pole_system), deferred :: system
    end type pole_problem

    abstract interface
        !> The misfit of the poles `trial` [rad/s] (huge and ok false when it cannot be computed)
        !> and, when asked, the Gauss-Newton normal matrix and gradient in (Re, Im) of each pole.
        subroutine pole_system(self, trial, cost, ok, normal, gradient)
            import :: dp, pole_problem
            class(pole_problem), intent(in) :: self
            complex(dp), intent(in) :: trial(:)
            real(dp), intent(out) :: cost
            logical, intent(out) :: ok
            real(dp), allocatable, intent(out), optional :: normal(:, :), gradient(:)
        end subroutine pole_system
    end interface

    !> The common-weight fit of `refine_shared`: every target weighted by one weight per line.
    type, extends(pole_problem) :: shared_problem
        !> Line frequencies [Hz].
        real(dp), allocatable :: frequency(:)
        !> The stacked real targets (Re, Im per line) of every receptance.
        real(dp), allocatable :: targets(:, :)
        !> The weight of each line [1/(m/N)].
        real(dp), allocatable :: weight(:)
    contains
        procedure :: system => shared_system
    end type shared_problem

    !> The maximum-likelihood fit of `refine_weighted`: each receptance with its own weights.
    type, extends(pole_problem) :: weighted_problem
        !> Line frequencies [Hz].
        real(dp), allocatable :: frequency(:)
        !> The receptances (line, target) [m/N].
        complex(dp), allocatable :: y(:, :)
        !> Their weights (line, target) [1/(m/N)].
        real(dp), allocatable :: w(:, :)
    contains
        procedure :: system => weighted_problem_system
    end type weighted_problem

contains

    !> Poles of a Green's matrix by poly-reference least squares, the order chosen by MDL (see
    !> the module description).
    subroutine polyref_poles(frequency, g, max_modes, pole, order, error, averaged)
        !> Frequency lines [Hz], increasing, >= 0.
        real(dp), intent(in) :: frequency(:)
        !> Receptances g(i, j, l) = G_ij(2*pi*f_l) [m/N] (symmetrised by the caller if reciprocal).
        complex(dp), intent(in) :: g(:, :, :)
        !> Largest number of modes (poles with Im > 0) the orders tried may reach.
        integer, intent(in) :: max_modes
        !> The poles lambda_k [rad/s] of the order kept (Re < 0 < Im), by frequency.
        complex(dp), allocatable, intent(out) :: pole(:)
        !> The order kept: the matrix-polynomial order p > 0, or -p for the common denominator.
        integer, intent(out) :: order
        !> Set when no order gives a pole in the band.
        type(error_type), allocatable, intent(out) :: error
        !> Whether each G_ij, i /= j, is the mean of the reciprocal pair (G_ij + G_ji)/2, so holds
        !> half the noise variance of a driving point (default false).
        logical, intent(in), optional :: averaged

        real(dp), allocatable :: r(:, :, :), s(:, :, :), t(:, :, :), targets(:, :), weight(:)
        real(dp), allocatable :: cd_r(:, :), cd_s(:, :), cd_t(:)
        complex(dp), allocatable :: candidate(:)
        integer, allocatable :: lines(:)
        real(dp) :: dt_z, score, best
        integer :: n_c, p, p_max, l
        logical :: mean_of_pairs

        n_c = size(g, 1)
        lines = pack([(l, l=1, size(frequency))], frequency > 0.0_dp)
        dt_z = 0.5_dp/maxval(frequency(lines))
        p_max = min(max_polynomial_order, max(2, (2*max_modes + n_c - 1)/n_c + 2))
        call gram_blocks(frequency(lines), g(:, :, lines), dt_z, p_max, r, s, t)
        call shared_targets(g(:, :, lines), targets, weight)
        best = huge(1.0_dp)
        order = 0
        allocate (pole(0))
        do p = 1, p_max
            call poles_of_order(r, s, t, n_c, p, dt_z, frequency(lines), candidate)
            call keep_best(p)
        end do
        call common_denominator_grams(frequency(lines), g(:, :, lines), dt_z, 2*max_modes, cd_r, cd_s, cd_t)
        do p = common_step, 2*max_modes, common_step
            call common_denominator_poles(cd_r, cd_s, cd_t, p, dt_z, frequency(lines), candidate)
            call keep_best(-p)
        end do
        if (size(pole) == 0) then
            call fatal_error(error, 'poly-reference poles: no order up to the largest gives a stable pole ' &
                             //'inside the band')
            return
        end if
        call refine_shared(frequency(lines), targets, weight, pole)
        call prune(frequency(lines), targets, weight, pole)
        mean_of_pairs = .false.
        if (present(averaged)) mean_of_pairs = averaged
        call refine_weighted(frequency(lines), g(:, :, lines), mean_of_pairs, pole)

    contains

        !> Keep the candidate poles of order `label` when their MDL is the least so far.
        subroutine keep_best(label)
            !> The order: a matrix order p > 0, or -p for the common denominator of order p.
            integer, intent(in) :: label

            if (size(candidate) == 0 .or. size(candidate) > max_modes) return
            score = mdl_score(frequency(lines), candidate, targets, weight)
            if (score < best) then
                best = score
                pole = candidate
                order = label
            end if
        end subroutine keep_best

    end subroutine polyref_poles

    !> The Toeplitz generators of the common-denominator normal equations of every distinct
    !> receptance t (i >= j), each line weighted by 1/|G_t| (relative, as the noise):
    !> R_t(q, r) = Re sum_l w^2*z^(r - q) = cd_r(|r - q|, t), S_t(q, r) = -Re sum_l w^2*G_t*z^(r - q)
    !> = cd_s(r - q, t), and the common T(q, r) = Re sum_l z^(r - q) = cd_t(|r - q|) (w*|G_t| = 1).
    subroutine common_denominator_grams(frequency, g, dt_z, p_max, cd_r, cd_s, cd_t)
        real(dp), intent(in) :: frequency(:), dt_z
        complex(dp), intent(in) :: g(:, :, :)
        integer, intent(in) :: p_max
        real(dp), allocatable, intent(out) :: cd_r(:, :), cd_s(:, :), cd_t(:)

        complex(dp), allocatable :: z(:), target(:)
        real(dp), allocatable :: w2(:)
        integer :: i, j, k, q, n_c

        n_c = size(g, 1)
        z = exp(i_unit*two_pi*frequency*dt_z)
        allocate (cd_r(0:p_max, n_c*(n_c + 1)/2), cd_s(-p_max:p_max, n_c*(n_c + 1)/2), cd_t(0:p_max))
        cd_t = [(real(sum(z**k), dp), k=0, p_max)]
        q = 0
        do j = 1, n_c
            do i = j, n_c
                q = q + 1
                target = g(i, j, :)
                w2 = 1.0_dp/max(abs(target), tiny(1.0_dp))**2
                cd_r(:, q) = [(real(sum(w2*z**k), dp), k=0, p_max)]
                cd_s(:, q) = [(-real(sum(w2*target*z**k), dp), k=-p_max, p_max)]
            end do
        end do
    end subroutine common_denominator_grams

    !> The physical poles of the common denominator of order p (one scalar polynomial for every
    !> receptance, the numerators eliminated target by target, a_p = 1).
    subroutine common_denominator_poles(cd_r, cd_s, cd_t, p, dt_z, frequency, pole)
        real(dp), intent(in) :: cd_t(0:)
        real(dp), intent(in) :: cd_r(0:, :), cd_s(-size(cd_t) + 1:, :)
        integer, intent(in) :: p
        real(dp), intent(in) :: dt_z, frequency(:)
        complex(dp), allocatable, intent(out) :: pole(:)

        real(dp), allocatable :: m(:, :), rt(:, :), st(:, :), a(:), companion(:, :)
        complex(dp), allocatable :: z(:)
        type(error_type), allocatable :: failed
        integer :: q, k, l
        logical :: ok

        allocate (pole(0), m(0:p, 0:p), rt(0:p, 0:p), st(0:p, 0:p), a(0:p - 1), companion(p, p), z(p))
        m = size(cd_r, 2)*reshape([((cd_t(abs(l - k)), k=0, p), l=0, p)], [p + 1, p + 1])
        do q = 1, size(cd_r, 2)
            rt = reshape([((cd_r(abs(l - k), q), k=0, p), l=0, p)], [p + 1, p + 1])
            st = reshape([((cd_s(l - k, q), k=0, p), l=0, p)], [p + 1, p + 1])
            call spd_inverse(rt, ok)
            if (.not. ok) return
            m = m - matmul(transpose(st), matmul(rt, st))
        end do
        call solve_linear(m(0:p - 1, 0:p - 1), -m(0:p - 1, p), a, failed)
        if (allocated(failed)) return
        companion(:, :) = 0.0_dp
        do k = 1, p - 1
            companion(k + 1, k) = 1.0_dp
        end do
        companion(:, p) = -a
        call eigenvalues(companion, z, failed)
        if (allocated(failed)) return
        call physical_poles(z, dt_z, frequency, pole)
    end subroutine common_denominator_poles

    !> Real parts of the Gram matrices of every row's regressors at the largest order: R (numerator),
    !> S (numerator x denominator), T (denominator), index (r, j) -> r*N_c + j.
    subroutine gram_blocks(frequency, g, dt_z, p_max, r, s, t)
        real(dp), intent(in) :: frequency(:), dt_z
        complex(dp), intent(in) :: g(:, :, :)
        integer, intent(in) :: p_max
        real(dp), allocatable, intent(out) :: r(:, :, :), s(:, :, :), t(:, :, :)

        complex(dp), allocatable :: x(:, :), y(:, :), z(:)
        real(dp), allocatable :: w(:)
        integer :: n_c, n_l, o, q, j

        n_c = size(g, 1)
        n_l = size(frequency)
        z = exp(i_unit*two_pi*frequency*dt_z)
        allocate (x(n_l, p_max + 1), y(n_l, (p_max + 1)*n_c), w(n_l))
        allocate (r(p_max + 1, p_max + 1, n_c), s(p_max + 1, (p_max + 1)*n_c, n_c), &
                  t((p_max + 1)*n_c, (p_max + 1)*n_c, n_c))
        do o = 1, n_c
            w = 1.0_dp/max(sqrt(sum(abs(g(o, :, :))**2, dim=1)/n_c), tiny(1.0_dp))
            do q = 0, p_max
                x(:, q + 1) = w*z**q
                do j = 1, n_c
                    y(:, q*n_c + j) = -x(:, q + 1)*g(o, j, :)
                end do
            end do
            r(:, :, o) = real(matmul(conjg(transpose(x)), x), kind=dp)
            s(:, :, o) = real(matmul(conjg(transpose(x)), y), kind=dp)
            t(:, :, o) = real(matmul(conjg(transpose(y)), y), kind=dp)
        end do
    end subroutine gram_blocks

    !> The physical poles of the matrix polynomial of order p (reduced normal equations, alpha_p = I).
    subroutine poles_of_order(r, s, t, n_c, p, dt_z, frequency, pole)
        real(dp), intent(in) :: r(:, :, :), s(:, :, :), t(:, :, :)
        integer, intent(in) :: n_c, p
        real(dp), intent(in) :: dt_z, frequency(:)
        complex(dp), allocatable, intent(out) :: pole(:)

        real(dp), allocatable :: m(:, :), rp(:, :), sol(:, :), alpha(:, :), companion(:, :)
        complex(dp), allocatable :: z(:)
        type(error_type), allocatable :: failed
        integer :: n, na, o, k
        logical :: ok

        allocate (pole(0))
        n = (p + 1)*n_c
        na = p*n_c
        allocate (m(n, n), sol(p + 1, n))
        m(:, :) = 0.0_dp
        do o = 1, n_c
            rp = r(1:p + 1, 1:p + 1, o)
            call spd_inverse(rp, ok)
            if (.not. ok) return
            sol = matmul(rp, s(1:p + 1, 1:n, o))
            m = m + t(1:n, 1:n, o) - matmul(transpose(s(1:p + 1, 1:n, o)), sol)
        end do
        rp = m(1:na, 1:na)
        call spd_inverse(rp, ok)
        if (.not. ok) return
        alpha = -matmul(rp, m(1:na, na + 1:n))
        allocate (companion(na, na), z(na))
        companion(:, :) = 0.0_dp
        do k = 1, na - n_c
            companion(k, k + n_c) = 1.0_dp
        end do
        do k = 0, p - 1
            companion(na - n_c + 1:na, k*n_c + 1:(k + 1)*n_c) = -alpha(k*n_c + 1:(k + 1)*n_c, :)
        end do
        call eigenvalues(companion, z, failed)
        if (allocated(failed)) return
        call physical_poles(z, dt_z, frequency, pole)
    end subroutine poles_of_order

    !> The poles lambda = ln(z)/dt_z of the roots z that are stable, damped below `max_damping`
    !> and inside the band (Im lambda > 0 of each pair), by frequency.
    subroutine physical_poles(z, dt_z, frequency, pole)
        complex(dp), intent(in) :: z(:)
        real(dp), intent(in) :: dt_z, frequency(:)
        complex(dp), allocatable, intent(out) :: pole(:)

        complex(dp), allocatable :: lambda(:)
        real(dp) :: f, xi
        integer :: k

        allocate (pole(0))
        lambda = log(pack(z, abs(z) > 0.0_dp))/dt_z
        do k = 1, size(lambda)
            if (aimag(lambda(k)) <= 0.0_dp .or. real(lambda(k), dp) >= 0.0_dp) cycle
            f = abs(lambda(k))/two_pi
            xi = -real(lambda(k), dp)/abs(lambda(k))
            if (xi < max_damping .and. f > frequency(1) .and. f < frequency(size(frequency))) pole = [pole, lambda(k)]
        end do
        pole = pole(sorted_order(abs(pole)))
    end subroutine physical_poles

    !> The distinct receptances (i >= j), each scaled by its rms and stacked real then imaginary
    !> parts, and the lines' common weight 1/rms_t of the scaled targets.
    subroutine shared_targets(g, targets, weight)
        complex(dp), intent(in) :: g(:, :, :)
        real(dp), allocatable, intent(out) :: targets(:, :), weight(:)

        complex(dp), allocatable :: scaled(:, :)
        integer :: i, j, q, n_c, n_l

        n_c = size(g, 1)
        n_l = size(g, 3)
        allocate (scaled(n_l, n_c*(n_c + 1)/2))
        q = 0
        do j = 1, n_c
            do i = j, n_c
                q = q + 1
                scaled(:, q) = g(i, j, :)/max(sqrt(sum(abs(g(i, j, :))**2)/n_l), tiny(1.0_dp))
            end do
        end do
        weight = 1.0_dp/max(sqrt(sum(abs(scaled)**2, dim=2)/size(scaled, 2)), tiny(1.0_dp))
        allocate (targets(2*n_l, size(scaled, 2)))
        do q = 1, size(scaled, 2)
            targets(:, q) = [real(scaled(:, q), dp)*weight, aimag(scaled(:, q))*weight]
        end do
    end subroutine shared_targets

    !> MDL of the linear fit of every target for these poles with an upper and a lower residual.
    function mdl_score(frequency, pole, targets, weight) result(score)
        real(dp), intent(in) :: frequency(:)
        complex(dp), intent(in) :: pole(:)
        real(dp), intent(in) :: targets(:, :), weight(:)
        real(dp) :: score

        real(dp), allocatable :: basis(:, :), rest(:, :)
        real(dp) :: n_data, n_parameters

        basis = pole_design(frequency, pole, .true., .true.)
        basis = basis*spread([weight, weight], 2, size(basis, 2))
        call orthonormalise(basis)
        rest = targets - matmul(basis, matmul(transpose(basis), targets))
        n_data = real(size(targets), dp)
        n_parameters = 2.0_dp*size(pole) + real(size(basis, 2)*size(targets, 2), dp)
        score = 0.5_dp*n_data*log(max(sum(rest**2), tiny(1.0_dp))) + 0.5_dp*n_parameters*log(n_data)
    end function mdl_score

    !> Gauss-Newton refinement of the poles over all targets (variable projection with Kaufman's
    !> Jacobian): for given poles the residues and residual terms of every target are the linear
    !> least-squares solution on the shared weighted design B; the derivative of the projected
    !> misfit of target t with respect to Re and Im of lambda_k is P*(R_tk*d_k + conj(R_tk)*e_k),
    !> d_k = 1/(s - lambda_k)^2, e_k = 1/(s - conj lambda_k)^2, P the projector off B's columns.
    !> The four real vectors per pole are projected once per iteration and every target's normal
    !> equations are assembled from their Gram matrix. Levenberg-Marquardt damping; a step is kept
    !> only when it lowers the misfit and keeps every pole stable, so the result is never worse.
    subroutine refine_shared(frequency, targets, weight, pole)
        real(dp), intent(in) :: frequency(:), targets(:, :), weight(:)
        complex(dp), intent(inout) :: pole(:)

        type(shared_problem) :: problem

        problem%frequency = frequency
        problem%targets = targets
        problem%weight = weight
        call levenberg_marquardt(problem, pole, 30, 1.0e-9_dp)

    end subroutine refine_shared

    !> The misfit of the common-weight linear fit for these poles and its normal equations.
    subroutine shared_system(self, trial, cost, ok, normal, gradient)
        class(shared_problem), intent(in) :: self
        complex(dp), intent(in) :: trial(:)
        real(dp), intent(out) :: cost
        logical, intent(out) :: ok
        real(dp), allocatable, intent(out), optional :: normal(:, :), gradient(:)

        real(dp), allocatable :: x(:, :), rest(:, :), gu(:, :), ur(:, :), u(:, :), coefficient(:, :)
        integer :: n_m, t, k

        cost = huge(1.0_dp)
        call linear_fit(self%frequency, trial, self%targets, self%weight, x, rest, ok)
        if (.not. ok) return
        cost = sum(rest**2)
        if (.not. present(normal)) return
        n_m = size(trial)
        call projected_derivatives(self%frequency, trial, self%weight, u, ok)
        if (.not. ok) return
        gu = matmul(transpose(u), u)
        ur = matmul(transpose(u), rest)
        allocate (normal(2*n_m, 2*n_m), gradient(2*n_m), coefficient(4*n_m, 2*n_m))
        normal(:, :) = 0.0_dp
        gradient(:) = 0.0_dp
        do t = 1, size(self%targets, 2)
            coefficient(:, :) = 0.0_dp
            do k = 1, n_m
                associate (a => x(2*k - 1, t), b => x(2*k, t))
                    ! Re lambda: R d + conj(R) e; Im lambda: i R d - i conj(R) e (R = a + i b)
                    coefficient(4*k - 3:4*k, 2*k - 1) = [a, b, a, -b]
                    coefficient(4*k - 3:4*k, 2*k) = [-b, a, -b, -a]
                end associate
            end do
            normal = normal + matmul(transpose(coefficient), matmul(gu, coefficient))
            gradient = gradient + matmul(transpose(coefficient), ur(:, t))
        end do
    end subroutine shared_system

    !> Levenberg-Marquardt on the poles (Re lambda_k, Im lambda_k) with the Gauss-Newton normal
    !> equations of `system`: the damping mu starts at 1e-4, a trial is kept only when it lowers
    !> the misfit and keeps every pole stable (so the result is never worse than the start), mu
    !> rises tenfold per refused trial (at most 10) and falls tenfold per kept one; it stops when
    !> a step gains less than `tolerance` of the misfit.
    subroutine levenberg_marquardt(problem, pole, max_iterations, tolerance)
        !> The misfit of given poles and, when asked, its normal matrix and gradient.
        class(pole_problem), intent(in) :: problem
        !> In: the start; out: the refined poles [rad/s].
        complex(dp), intent(inout) :: pole(:)
        !> Largest number of iterations.
        integer, intent(in) :: max_iterations
        !> Relative gain of the misfit below which it stops.
        real(dp), intent(in) :: tolerance

        real(dp), allocatable :: normal(:, :), gradient(:)
        complex(dp), allocatable :: trial(:)
        real(dp) :: cost, cost_trial, mu
        integer :: iteration, attempt
        logical :: ok, accepted

        mu = 1.0e-4_dp
        do iteration = 1, max_iterations
            call problem%system(pole, cost, ok, normal, gradient)
            if (.not. ok) return
            accepted = .false.
            do attempt = 1, 10
                call damped_trial(normal, gradient, mu, pole, trial, ok)
                if (ok) then
                    call problem%system(trial, cost_trial, ok)
                    if (ok .and. cost_trial < cost) then
                        accepted = .true.
                        exit
                    end if
                end if
                mu = 10.0_dp*mu
            end do
            if (.not. accepted) exit
            pole = trial
            mu = max(mu/10.0_dp, 1.0e-8_dp)
            if (cost - cost_trial < tolerance*cost) exit
        end do
    end subroutine levenberg_marquardt

    !> Maximum-likelihood refinement of the shared poles for noise relative to each receptance
    !> (the noise model of `pole_covariance`): line l of receptance t weighted by its own
    !> w_tl = c_t/|G_t(omega_l)|, c_t = sqrt(2) for the mean of a reciprocal pair, so that the
    !> misfit sum_t,l w_tl^2*|G_t - G_t,model|^2 is the negative log-likelihood and its minimiser
    !> has the Cramer-Rao bound as covariance. The common weight per line of `refine_shared`
    !> (the receptances' mean relative size) puts receptances near their anti-resonances far
    !> below their noise and biases the poles there (a 24-mode plate: 4 poles beyond 5 sigma).
    !> |G_t| is taken from the data in a first pass and from the model of that pass in a
    !> second, so the weights do not follow the noise. Variable projection as in
    !> `refine_shared`, but each target's residues are solved on its own weighted design and its
    !> derivatives projected off that design (Kaufman), so the normal equations are assembled
    !> target by target from Gram matrices. Poles the refinement moves out of the band are
    !> dropped and the rest refined again.
    subroutine refine_weighted(frequency, g, averaged, pole)
        real(dp), intent(in) :: frequency(:)
        complex(dp), intent(in) :: g(:, :, :)
        logical, intent(in) :: averaged
        complex(dp), allocatable, intent(inout) :: pole(:)

        integer, parameter :: passes = 2
        !> The misfit is about rho^2 per complex datum, so a relative gain of 1e-7 is below a
        !> hundredth of one unit of log-likelihood on 1e5 data: converged.
        real(dp), parameter :: tolerance = 1.0e-7_dp
        complex(dp), allocatable :: y(:, :), model(:, :)
        real(dp), allocatable :: w(:, :), factor(:), least(:), gain(:)
        logical, allocatable :: inside(:)
        real(dp) :: cost, rho2
        integer :: n_c, i, j, q, pass, k
        logical :: ok
        type(weighted_problem) :: problem

        n_c = size(g, 1)
        allocate (y(size(frequency), n_c*(n_c + 1)/2), factor(n_c*(n_c + 1)/2))
        q = 0
        do j = 1, n_c
            do i = j, n_c
                q = q + 1
                y(:, q) = g(i, j, :)
                factor(q) = merge(sqrt(2.0_dp), 1.0_dp, averaged .and. i /= j)
            end do
        end do
        ! a magnitude far below the receptance's own rms counts as that floor (no line dominates)
        least = 1.0e-6_dp*sqrt(sum(abs(y)**2, dim=1)/size(frequency))
        problem%frequency = frequency
        problem%y = y
        do
            model = y
            do pass = 1, passes
                if (size(pole) == 0) return
                w = spread(factor, 1, size(frequency))/max(abs(model), spread(least, 1, size(frequency)))
                problem%w = w
                call levenberg_marquardt(problem, pole, 20, tolerance)
                call weighted_system(frequency, y, w, pole, cost, model, ok)
                if (.not. ok) return
            end do
            ! a pole moved out of the band or above max_damping: drop it and refine the rest
            inside = in_band(pole, frequency(1), frequency(size(frequency)))
            if (all(inside) .or. .not. any(inside)) exit
            pole = pack(pole, inside)
        end do
        ! a pole the data do not ask for: the likelihood gained by its residues in every target,
        ! gain/rho^2, is chi^2_K/2 with K = 2*n_t + 2 for a pole fitted to noise (mean K/2,
        ! standard deviation sqrt(K/2)); the least significant pole below 5 standard deviations
        ! above that mean is dropped and the rest refined again
        do while (size(pole) > 1)
            call weighted_system(frequency, y, w, pole, cost, model, ok, gain=gain)
            if (.not. ok) return
            k = minloc(gain, 1)
            rho2 = cost/max(1.0_dp, size(y) - 0.5_dp*(2*size(pole) + size(y, 2)*(2*size(pole) + 2)))
            if (gain(k)/rho2 >= size(y, 2) + 1 + 5.0_dp*sqrt(size(y, 2) + 1.0_dp)) exit
            pole = [pole(:k - 1), pole(k + 1:)]
            problem%w = w
            call levenberg_marquardt(problem, pole, 20, tolerance)
        end do

    end subroutine refine_weighted

    !> The weighted misfit of given poles and, when asked, its normal equations.
    subroutine weighted_problem_system(self, trial, cost, ok, normal, gradient)
        class(weighted_problem), intent(in) :: self
        complex(dp), intent(in) :: trial(:)
        real(dp), intent(out) :: cost
        logical, intent(out) :: ok
        real(dp), allocatable, intent(out), optional :: normal(:, :), gradient(:)

        complex(dp), allocatable :: trial_model(:, :)

        call weighted_system(self%frequency, self%y, self%w, trial, cost, trial_model, ok, normal, gradient)
    end subroutine weighted_problem_system

    !> One Levenberg-Marquardt trial: the poles moved by the solution of the normal equations
    !> with their diagonal raised by the factor 1 + mu; ok is false when that matrix is not
    !> positive definite or a trial pole is not stable (Re < 0 < Im).
    subroutine damped_trial(normal, gradient, mu, pole, trial, ok)
        real(dp), intent(in) :: normal(:, :), gradient(:), mu
        complex(dp), intent(in) :: pole(:)
        complex(dp), allocatable, intent(out) :: trial(:)
        logical, intent(out) :: ok

        real(dp), allocatable :: lhs(:, :), step(:)
        integer :: l

        lhs = normal
        do l = 1, size(normal, 1)
            lhs(l, l) = normal(l, l)*(1.0_dp + mu)
        end do
        call spd_inverse(lhs, ok)
        if (.not. ok) return
        step = matmul(lhs, gradient)
        trial = pole + cmplx(step(1:size(step):2), step(2:size(step):2), dp)
        ok = all(real(trial, dp) < 0.0_dp) .and. all(aimag(trial) > 0.0_dp)
    end subroutine damped_trial

    !> Whether a pole lies inside the band (f_low, f_high) [Hz] with a damping ratio below
    !> `max_damping`.
    elemental logical function in_band(lambda, f_low, f_high)
        complex(dp), intent(in) :: lambda
        real(dp), intent(in) :: f_low, f_high

        in_band = abs(lambda)/two_pi > f_low .and. abs(lambda)/two_pi < f_high &
                  .and. -real(lambda, dp)/abs(lambda) < max_damping
    end function in_band

    !> The weighted misfit of every target for these poles, cost = sum_t ||w_t*(G_t - B*x_t)||^2
    !> with x_t (residues, upper and lower residual) the weighted least-squares solution on the
    !> shared design B (`pole_design`), and the model B*x_t of each; optionally the Gauss-Newton
    !> normal matrix and gradient in (Re lambda_k, Im lambda_k): sum_t J_t^T*P_t*J_t and
    !> sum_t J_t^T*r_t, J_t the weighted derivatives of the model at fixed residues, P_t the
    !> projector off target t's weighted design, r_t its weighted residual (Kaufman).
    subroutine weighted_system(frequency, y, w, pole, cost, model, ok, normal, gradient, gain)
        real(dp), intent(in) :: frequency(:), w(:, :)
        complex(dp), intent(in) :: y(:, :), pole(:)
        real(dp), intent(out) :: cost
        complex(dp), allocatable, intent(out) :: model(:, :)
        logical, intent(out) :: ok
        real(dp), allocatable, intent(out), optional :: normal(:, :), gradient(:)
        !> Per pole, how much the cost would rise without its two residue columns in every
        !> target (the other residues fitted again, the poles fixed): sum_t x_S^T*C_SS^-1*x_S,
        !> C = the inverse Gram matrix of target t, S the pole's columns.
        real(dp), allocatable, intent(out), optional :: gain(:)

        real(dp), allocatable :: design(:, :), b(:, :), jac(:, :), gbb(:, :), gjj(:, :), gbj(:, :)
        real(dp), allocatable :: rhs(:), projection(:), x(:), rest(:), w2(:), scale(:), gj(:), fitted(:)
        complex(dp), allocatable :: dl(:, :), dc(:, :), pl(:), pc(:)
        complex(dp) :: residue
        integer :: n_l, n_m, n_p, t, k

        n_l = size(frequency)
        n_m = size(pole)
        n_p = 2*n_m + 2
        design = pole_design(frequency, pole, .true., .true.)
        allocate (model(n_l, size(y, 2)), gbb(n_p, n_p), projection(n_p))
        if (present(normal)) then
            allocate (normal(2*n_m, 2*n_m), gradient(2*n_m), dl(n_l, n_m), dc(n_l, n_m), jac(2*n_l, 2*n_m), &
                      gjj(2*n_m, 2*n_m), gj(2*n_m))
            normal(:, :) = 0.0_dp
            gradient(:) = 0.0_dp
            associate (s => i_unit*two_pi*frequency)
                do k = 1, n_m
                    dl(:, k) = 1.0_dp/(s - pole(k))**2
                    dc(:, k) = 1.0_dp/(s - conjg(pole(k)))**2
                end do
            end associate
        end if
        cost = huge(1.0_dp)
        ok = .true.
        if (size(y, 2) > 0) cost = 0.0_dp
        if (present(gain)) then
            allocate (gain(n_m))
            gain(:) = 0.0_dp
        end if
        do t = 1, size(y, 2)
            w2 = [w(:, t), w(:, t)]
            b = design*spread(w2, 2, n_p)
            rhs = w2*[real(y(:, t), dp), aimag(y(:, t))]
            call gram_product(b, 1.0_dp, gbb, rhs, projection)
            scale = 1.0_dp/sqrt(max([(gbb(k, k), k=1, n_p)], tiny(1.0_dp)))
            gbb = gbb*spread(scale, 1, n_p)*spread(scale, 2, n_p)
            call spd_inverse(gbb, ok)
            if (.not. ok) then
                cost = huge(1.0_dp)
                return
            end if
            ! gbb is now the inverse of the unscaled Gram matrix
            gbb = gbb*spread(scale, 1, n_p)*spread(scale, 2, n_p)
            x = matmul(gbb, projection)
            fitted = matmul(design, x)
            model(:, t) = cmplx(fitted(1:n_l), fitted(n_l + 1:), dp)
            rest = rhs - w2*fitted
            cost = cost + sum(rest**2)
            if (present(gain)) then
                do k = 1, n_m
                    associate (c => gbb(2*k - 1:2*k, 2*k - 1:2*k), a => x(2*k - 1), b => x(2*k))
                        gain(k) = gain(k) + (c(2, 2)*a**2 - 2.0_dp*c(1, 2)*a*b + c(1, 1)*b**2) &
                                  /max(c(1, 1)*c(2, 2) - c(1, 2)**2, tiny(1.0_dp))
                    end associate
                end do
            end if
            if (.not. present(normal)) cycle
            do k = 1, n_m
                residue = cmplx(x(2*k - 1), x(2*k), dp)
                pl = residue*dl(:, k)
                pc = conjg(residue)*dc(:, k)
                jac(:, 2*k - 1) = w2*[real(pl + pc, dp), aimag(pl + pc)]
                jac(:, 2*k) = w2*[real(i_unit*(pl - pc), dp), aimag(i_unit*(pl - pc))]
            end do
            gbj = matmul(transpose(b), jac)
            call gram_product(jac, 1.0_dp, gjj, rest, gj)
            normal = normal + gjj - matmul(transpose(gbj), matmul(gbb, gbj))
            gradient = gradient + gj
        end do
    end subroutine weighted_system

    !> Drop any pole the refinement moved out of the band or above `max_damping` and refine the
    !> rest. (Dropping poles one at a time by the MDL of the linear fit was tried: its penalty per
    !> pole, (2 + 2*n_targets)/2*ln N, removed real modes of the dense plate and biased their
    !> neighbours beyond 5 sigma, so the order stays the one MDL chose among the matrix orders.)
    subroutine prune(frequency, targets, weight, pole)
        real(dp), intent(in) :: frequency(:), targets(:, :), weight(:)
        complex(dp), allocatable, intent(inout) :: pole(:)

        logical :: inside(size(pole))

        inside = in_band(pole, frequency(1), frequency(size(frequency)))
        if (.not. all(inside) .and. count(inside) > 0) then
            pole = pack(pole, inside)
            call refine_shared(frequency, targets, weight, pole)
        end if
    end subroutine prune

    !> Residues and residual terms x (columns per target) of the weighted linear fit and its
    !> residual, by the normal equations of the column-scaled shared design.
    subroutine linear_fit(frequency, pole, targets, weight, x, rest, ok)
        real(dp), intent(in) :: frequency(:), targets(:, :), weight(:)
        complex(dp), intent(in) :: pole(:)
        real(dp), allocatable, intent(out) :: x(:, :), rest(:, :)
        logical, intent(out) :: ok

        real(dp), allocatable :: b(:, :), gram(:, :), scale(:)

        b = pole_design(frequency, pole, .true., .true.)*spread([weight, weight], 2, 2*size(pole) + 2)
        scale = 1.0_dp/max(norm2(b, dim=1), tiny(1.0_dp))
        b = b*spread(scale, 1, size(b, 1))
        gram = matmul(transpose(b), b)
        call spd_inverse(gram, ok)
        if (.not. ok) return
        x = matmul(gram, matmul(transpose(b), targets))
        rest = targets - matmul(b, x)
        x = x*spread(scale, 2, size(x, 2))
    end subroutine linear_fit

    !> The four real vectors per pole, [Re d; Im d], [-Im d; Re d], [Re e; Im e], [-Im e; Re e],
    !> weighted and projected off the shared design's columns.
    subroutine projected_derivatives(frequency, pole, weight, u, ok)
        real(dp), intent(in) :: frequency(:), weight(:)
        complex(dp), intent(in) :: pole(:)
        real(dp), allocatable, intent(out) :: u(:, :)
        logical, intent(out) :: ok

        real(dp), allocatable :: b(:, :), gram(:, :), scale(:), w(:)
        complex(dp), allocatable :: d(:), e(:)
        integer :: k

        w = [weight, weight]
        allocate (u(2*size(frequency), 4*size(pole)))
        associate (s => i_unit*two_pi*frequency)
            do k = 1, size(pole)
                d = 1.0_dp/(s - pole(k))**2
                e = 1.0_dp/(s - conjg(pole(k)))**2
                u(:, 4*k - 3) = w*[real(d, dp), aimag(d)]
                u(:, 4*k - 2) = w*[-aimag(d), real(d, dp)]
                u(:, 4*k - 1) = w*[real(e, dp), aimag(e)]
                u(:, 4*k) = w*[-aimag(e), real(e, dp)]
            end do
        end associate
        b = pole_design(frequency, pole, .true., .true.)*spread(w, 2, 2*size(pole) + 2)
        scale = 1.0_dp/max(norm2(b, dim=1), tiny(1.0_dp))
        b = b*spread(scale, 1, size(b, 1))
        gram = matmul(transpose(b), b)
        call spd_inverse(gram, ok)
        if (.not. ok) return
        u = u - matmul(b, matmul(gram, matmul(transpose(b), u)))
    end subroutine projected_derivatives

    !> Orthonormal basis of the columns, in place (Gram-Schmidt, each column twice for round-off;
    !> a column in the span of the previous ones becomes zero).
    pure subroutine orthonormalise(basis)
        !> In: the columns; out: the basis.
        real(dp), intent(inout) :: basis(:, :)

        real(dp) :: size_before
        integer :: k, pass

        do k = 1, size(basis, 2)
            size_before = norm2(basis(:, k))
            do pass = 1, 2
                if (k > 1) basis(:, k) = basis(:, k) - matmul(basis(:, :k - 1), matmul(basis(:, k), basis(:, :k - 1)))
            end do
            if (norm2(basis(:, k)) > 1.0e-12_dp*size_before) then
                basis(:, k) = basis(:, k)/norm2(basis(:, k))
            else
                basis(:, k) = 0.0_dp
            end if
        end do
    end subroutine orthonormalise

    !> The real design matrix of a shared-pole model on the given lines: rows the real then the
    !> imaginary parts, columns per pole the responses to Re R_k and Im R_k,
    !> 1/(s - lambda_k) + 1/(s - conj lambda_k) and i/(s - lambda_k) - i/(s - conj lambda_k)
    !> [s], then 1 (upper residual) and 1/s^2 (lower residual) when kept.
    pure function pole_design(frequency, pole, upper, lower) result(design)
        !> Frequencies of the lines [Hz].
        real(dp), intent(in) :: frequency(:)
        !> Poles [rad/s].
        complex(dp), intent(in) :: pole(:)
        !> Whether to add the upper (constant) and the lower (1/s^2) residual column.
        logical, intent(in) :: upper, lower
        !> The design matrix (2*size(frequency) x 2*size(pole) + residual columns).
        real(dp), allocatable :: design(:, :)

        complex(dp), allocatable :: columns(:, :)
        integer :: k, n_p

        n_p = 2*size(pole) + merge(1, 0, upper) + merge(1, 0, lower)
        allocate (columns(size(frequency), n_p))
        associate (s => i_unit*two_pi*frequency)
            do k = 1, size(pole)
                columns(:, 2*k - 1) = 1.0_dp/(s - pole(k)) + 1.0_dp/(s - conjg(pole(k)))
                columns(:, 2*k) = i_unit*(1.0_dp/(s - pole(k)) - 1.0_dp/(s - conjg(pole(k))))
            end do
            if (upper) columns(:, 2*size(pole) + 1) = 1.0_dp
            if (lower) columns(:, n_p) = 1.0_dp/s**2
        end associate
        allocate (design(2*size(frequency), n_p))
        design(1:size(frequency), :) = real(columns, kind=dp)
        design(size(frequency) + 1:, :) = aimag(columns)
    end function pole_design

    !> Covariance of the poles (Re lambda_1, Im lambda_1, Re lambda_2, ...) [rad^2/s^2] at the
    !> Cramer-Rao bound: the inverse of the Fisher information of the shared-pole model
    !> G_t = sum_k [R_tk/(s - lambda_k) + conj(R_tk)/(s - conj(lambda_k))] + U_t + L_t/s^2 for
    !> complex Gaussian noise of standard deviation sigma(t, l) on each line (half the variance
    !> in the real, half in the imaginary part), the residues and residual terms of every target
    !> eliminated as nuisance parameters (the Schur complement of their block).
    subroutine pole_covariance(frequency, pole, residue, sigma, covariance, error)
        !> Frequency lines [Hz], > 0.
        real(dp), intent(in) :: frequency(:)
        !> Poles lambda_k [rad/s].
        complex(dp), intent(in) :: pole(:)
        !> Residues residue(t, k) of target t [m/(N*s)].
        complex(dp), intent(in) :: residue(:, :)
        !> Noise standard deviation sigma(t, l) [m/N], > 0.
        real(dp), intent(in) :: sigma(:, :)
        !> The covariance (2*size(pole) square).
        real(dp), allocatable, intent(out) :: covariance(:, :)
        !> Set when the information matrix is singular.
        type(error_type), allocatable, intent(out) :: error

        real(dp), allocatable :: design(:, :), b(:, :), d(:, :), w(:), scale(:)
        complex(dp), allocatable :: dl(:), dc(:)
        integer :: n_m, n_l, q, k
        logical :: ok

        n_m = size(pole)
        n_l = size(frequency)
        design = pole_design(frequency, pole, .true., .true.)
        allocate (covariance(2*n_m, 2*n_m), d(2*n_l, 2*n_m))
        covariance(:, :) = 0.0_dp
        associate (s => i_unit*two_pi*frequency)
            do q = 1, size(residue, 1)
                w = sqrt(2.0_dp)/[sigma(q, :), sigma(q, :)]
                b = design*spread(w, 2, size(design, 2))
                do k = 1, n_m
                    dl = residue(q, k)/(s - pole(k))**2
                    dc = conjg(residue(q, k))/(s - conjg(pole(k)))**2
                    d(:, 2*k - 1) = w*[real(dl + dc, dp), aimag(dl + dc)]
                    d(:, 2*k) = w*[real(i_unit*(dl - dc), dp), aimag(i_unit*(dl - dc))]
                end do
                call orthonormalise(b)
                d = d - matmul(b, matmul(transpose(b), d))
                covariance = covariance + matmul(transpose(d), d)
            end do
        end associate
        scale = 1.0_dp/sqrt(max([(covariance(k, k), k=1, 2*n_m)], tiny(1.0_dp)))
        covariance = covariance*spread(scale, 1, 2*n_m)*spread(scale, 2, 2*n_m)
        call spd_inverse(covariance, ok)
        if (.not. ok) call fatal_error(error, 'pole covariance: the poles'' information is singular', stat=3)
        covariance = covariance*spread(scale, 1, 2*n_m)*spread(scale, 2, 2*n_m)
    end subroutine pole_covariance

    !> Standard deviations of the natural frequency f = |lambda|/(2*pi) [Hz] and of the damping
    !> ratio xi = -Re lambda/|lambda| of each pole, from the covariance of `pole_covariance`
    !> (first-order propagation).
    pure subroutine pole_spread(pole, covariance, sigma_f, sigma_xi)
        !> Poles lambda_k [rad/s].
        complex(dp), intent(in) :: pole(:)
        !> Covariance of (Re lambda_k, Im lambda_k) pairs [rad^2/s^2].
        real(dp), intent(in) :: covariance(:, :)
        !> sigma_f [Hz] per pole.
        real(dp), intent(out) :: sigma_f(size(pole))
        !> sigma_xi per pole.
        real(dp), intent(out) :: sigma_xi(size(pole))

        real(dp) :: a, b, m, gf(2), gx(2), c(2, 2)
        integer :: k

        do k = 1, size(pole)
            a = real(pole(k), dp)
            b = aimag(pole(k))
            m = abs(pole(k))
            c = covariance(2*k - 1:2*k, 2*k - 1:2*k)
            gf = [a, b]/(two_pi*m)
            gx = [-b**2, a*b]/m**3
            sigma_f(k) = sqrt(max(0.0_dp, dot_product(gf, matmul(c, gf))))
            sigma_xi(k) = sqrt(max(0.0_dp, dot_product(gx, matmul(c, gx))))
        end do
    end subroutine pole_spread

end module greenconv_ident_polyref
