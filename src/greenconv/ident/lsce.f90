!> Modal identification of a sampled receptance G(omega) by the least-squares complex
!> exponential method (LSCE): the step of the paper (section 2.2) that gives the modes of
!> eq. (6), hence the g(t) of eq. (8) that the modal convolution uses.
!>
!> ## What `identify` does
!> 1. Impulse response g_n = df*c2r(G), n = 0..N_t-1, N_t = 2*(n_freq - 1), dt = 1/(2*f_max).
!> 2. For N = 1, 2, .. max_modes (LSCE polynomial order 2N): linear prediction of g_n, roots,
!>    physical poles, with the out-of-band correction below iterated; the poles stable against
!>    those of order N - 1 make the candidate model.
!> 3. Residues of the candidate poles by least squares against G (LSFD), then, unless
!>    `polish = .false.`, Gauss-Newton on all parameters.
!> 4. E of eq. (7). The first candidate with E <= tol_e (or with exactly fixed_modes modes) is
!>    returned, with its order, E, the counts of dropped poles and the wrap-around check.
!>
!> ## FFT scaling and sign
!> G(omega) = int g(t)*exp(-i*omega*t) dt, the pair of greenconv_model_modal_set's `receptance` and
!> `impulse`. The lines G_k = G(2*pi*k*df) give the Fourier coefficients c_k = df*G_k of g
!> periodized with period T = 1/df, so g_n = df*sum_k G_k*exp(+2*pi*i*k*n/N_t) over the
!> Hermitian-completed lines: FFTW's c2r (sign +, no 1/N_t) times df. The tests check it to
!> 3e-15 on an sdof whose G is made exactly periodic, and within its band-limitation bound
!> (2 % of max|g| there, attained) on the true G.
!>
!> ## LSCE step
!> g_{n+p} = -sum_{j=0}^{p-1} a_j*g_{n+j}, p = 2N, over the samples t_1..t_M, M =
!> min(N_t - 1, max_samples), scaled by 1/max|g| (the roots do not change); solved by dgelsd,
!> singular values below 1e-11 of the largest dropped (an over-specified clean fit is
!> rank-deficient). t_0 is left out: there a Fourier series gives the mean of the jump of the
!> periodized g, (g(0+) + g(T-))/2, not a value of the exponential sum, and a constant
!> term of G (upper residual) puts all its weight on it. The roots z of the prediction
!> polynomial are the eigenvalues of its companion matrix (dgeev, balanced); lambda = ln(z)/dt.
!> Only roots with Im z > 0 and |z| < 1 become poles (Re lambda < 0, 0 < Im lambda < pi/dt);
!> real roots (n_real) and roots with |z| >= 1 (n_unstable) are counted and never returned;
!> unstable ones dropped (Re lambda >= 0) are also named in the result's warning.
!> Modes must lie below f_max: dt = 1/(2*f_max) cannot tell a higher mode from its alias.
!>
!> ## Out-of-band correction (why plain LSCE is not enough)
!> df*c2r(G) is the periodized g minus its Fourier lines above f_max (and half the Nyquist
!> line): about A/(pi*omega_max) at every sample, 2 % of max|g| for the tests' sdof, and not
!> a sum of exponentials. Plain LSCE on it biases the poles: measured on one mode (xi = 0.001)
!> xi is 1.7 % high at the exact order and 1e-4 low at the first stable order, and two close
!> modes merge. The missing lines are those of the model, so each pass replaces the samples by
!>     g_n = sum_k 2*Re(r_k*z_k^n/(1 - z_k^N_t)) + df*c2r(G - G_model)_n,
!> the model's exact periodized response plus the band-limited FFT of what it does not
!> explain: a pure sum of exponentials when the model is right. Passes shrink the change by
!> about 0.35 each and stop below 1e-12*max|g| or after max_refinements (0: plain LSCE).
!> Alone (no polish) it gives omega_k, xi_k to 1e-11..1e-12 in the clean tests; its floor,
!> about 1e-11*max|g|, can still move xi of overlapping modes by a few 1e-8 (measured 3e-8
!> for the 100/101 Hz pair inside a six-mode system).
!>
!> ## Residues (LSFD), residual terms and the paper's A_k
!> Model, in greenconv_model_modal_set's convention, with optional residual terms:
!>     G(omega) = sum_k [r_k/(i*omega - lambda_k) + conj(r_k)/(i*omega - conj(lambda_k))]
!>                + R_u - R_l/omega^2                                                   [m/N]
!> Unknowns Re r_k, Im r_k [m/(N*s)], R_u [m/N], R_l [1/kg] (real, since g is real); real and
!> imaginary parts of the equations on every line stacked, columns scaled to unit norm,
!> dgelsd. Complex r_k (non-proportional damping) are allowed. R_u (upper residual) is the
!> quasi-static flexibility of modes above f_max, g = R_u*delta(t); R_l/(i*omega)^2 = -R_l/omega^2
!> (lower residual) is a mass-like term, g = R_l*t: it is infinite at 0 Hz, so that line is
!> then left out of the fit and of E. Both take part in E and in the correction above, but
!> not in `modes`: a convolution built from result%modes drops them (greenconv's convolvers
!> take modes only). The paper's eq. (6) term A_k/(omega_k^2 - omega^2 + 2i*xi_k*omega*omega_k)
!> is the case r_k = A_k/(2i*omega_k^d), i.e. purely imaginary r_k; `paper_form` returns
!> A_k = -2*omega_k^d*Im(r_k) and the share |Re r_k|/|r_k| it drops (see there).
!>
!> ## Polish
!> Gauss-Newton on (Re lambda_k, Im lambda_k, Re r_k, Im r_k, R_u, R_l) against G on the grid,
!> each step an SVD least-squares solve, halved until ||G - G_model||_2 decreases. From the
!> LSCE start it converges to round-off on clean data (xi from 1e-11..3e-8 to 2e-16, E to
!> ~1e-17). Poles it moves out of the physical region are dropped and counted.
!>
!> ## Error E (eq. 7)
!> int_0^omega_max |G - G_model| domega / int_0^omega_max |G| domega by the trapezoidal rule on
!> the grid, for every candidate (result%e_by_order) and the result (result%e). E sees G only
!> on the lines: between them, on a grid too coarse for the damping, it is blind.
!>
!> ## Order selection and stability
!> At order N a pole is stable when a pole of order N - 1 has its natural frequency within
!> stable_frequency (1 %) and its damping ratio within stable_damping (5 %), both relative;
!> order 1 has no predecessor and gives the empty model (E = 1). The scan returns the first
!> candidate with E <= tol_e: the smallest order that meets it, and with it the smallest
!> model. If no order does, it returns the first candidate within 10 % of the smallest E
!> seen, with a warning (on 1 % noise and tol_e = 1e-6 the smallest E came at 15 modes that
!> fit the noise; the rule keeps the 10 true ones). The order that yields N_m modes is
!> larger than N_m on purpose: the extra roots absorb what the prediction cannot fit and
!> are dropped as unstable across orders (the tests' 10 clean modes come at N = 12). This is
!> also why fixed_modes stops at the first candidate with that many stable modes rather than
!> forcing the order 2*fixed_modes: forced
!> exact orders fail on band-limited data (measured without polish: 10 modes at order 10 gave
!> 9 modes, E = 0.1; two modes 1 % apart at order 2 gave xi 6 % off).
!>
!> ## Wrap-around (g not decayed within the period 1/df)
!> Detected on the impulse response of the final model (the correction's g_n, free of the
!> band-truncation ringing near t = T): tail_level = max|g_n| over the last wrap_fraction
!> (10 %) of the period relative to max|g|; above wrap_level (1 %) wrap_around is set and a
!> warning written. Effect, checked and measured: none on the poles or the residues of this
!> method, because the periodized samples z^n/(1 - z^N_t) are still geometric (the linear
!> prediction holds with the same z) and the correction models the periodization exactly,
!> while the residues are fitted to G itself, which wrap-around does not touch. One mode at
!> 100 Hz with xi = 0.001 (f_max = 500 Hz, df = 0.1 to 20 Hz, g left at 0.4 % to 97 % at the
!> end of the period): omega, xi, r within 3e-12 (polished: 1e-16) on every grid. Plain LSCE
!> (max_refinements = 0, no polish) shows the damping bias growing with it, from -9e-5 (df =
!> 0.1 Hz) to -4.4e-4 (1 Hz) and -5e-4 (20 Hz): the jump of the periodized g at t = 0 adds a
!> 1/omega tail above f_max; the sign is that of the order used (downward here), not a rule.
!> What wrap-around does harm: g from impulse_from_frf itself (e.g. for a direct convolution)
!> is the periodized one, wrong by the tail; and a grid that coarse resolves light damping
!> with few lines, where E is blind (with 1 % noise on one line per 4 Hz, E fell to 1.5e-3,
!> below the 9e-3 of the noise itself, as the fit absorbed the noise of the peak lines).
module greenconv_ident_lsce
    use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
    use greenconv_core_kinds, only: dp
    use greenconv_core_error, only: error_type, fatal_error, stat_input, stat_numerical
    use greenconv_core_text, only: int_text, sci_text
    use greenconv_model_modal_set, only: modal_set
    use greenconv_model_frf, only: frf_type, min_frf_lines
    use greenconv_ext_fftw, only: inverse_real_fft
    use greenconv_ext_lapack, only: least_squares, eigenvalues
    implicit none
    private

    public :: lsce_options, lsce_result, identify
    public :: impulse_from_frf, fit_residues, error_e, paper_form
    public :: natural_frequency, damping_ratio
    public :: lsce_poles, receptance_problem, stack, add_parameter_step

    !> Relative grid of the diagram's poles' real and imaginary parts (2^-20, 1e-6): twenty times
    !> below the sigma_f/f of the sharpest measured mode identified here (2e-5), far above the
    !> differences of LAPACK's results between BLAS kernels for a settled pole (1e-13).
    real(dp), parameter :: reproducible_grid = 2.0_dp**(-20)

    real(dp), parameter :: pi = 3.141592653589793238462643383279_dp
    real(dp), parameter :: two_pi = 2.0_dp*pi

    !> Singular values below this fraction of the largest are dropped in the linear
    !> prediction (an over-modelled clean fit is rank-deficient by design).
    real(dp), parameter :: rcond_prediction = 1.0e-11_dp
    !> The same threshold for the residue fit (columns scaled to unit norm first).
    real(dp), parameter :: rcond_residues = 1.0e-13_dp
    !> The out-of-band refinement stops when the corrected impulse response moves by
    !> less than this fraction of max |g|.
    real(dp), parameter :: refinement_tolerance = 1.0e-12_dp
    !> When no order meets the target, the first candidate with E <= near_best*(smallest E).
    real(dp), parameter :: near_best = 1.1_dp
    !> A receptance whose lines above 0 Hz differ from the first of them by at most this
    !> fraction of it is constant (receptance_problem): it holds no resonance.
    real(dp), parameter :: constant_tolerance = 1.0e-12_dp

    !> Settings of an identification (every field has a default).
    type :: lsce_options
        !> Tolerance on the error E of eq. (7): the order scan returns the first model with E <= tol_e.
        real(dp) :: tol_e = 1.0e-6_dp
        !> Largest number of modes N of the scan (LSCE polynomial order 2N).
        integer :: max_modes = 30
        !> Fixed number of modes (> 0): the scan stops at the first order whose stable model has
        !> exactly this many modes, whatever its E (0: stop on tol_e).
        integer :: fixed_modes = 0
        !> Fit an upper residual R_u [m/N] (constant term, modes above the band).
        logical :: upper_residual = .false.
        !> Fit a lower residual R_l [1/kg] (term -R_l/omega^2, mass-like; the 0 Hz line is then left out).
        logical :: lower_residual = .false.
        !> Stability across consecutive orders: relative tolerance on the natural frequency.
        real(dp) :: stable_frequency = 0.01_dp
        !> Stability across consecutive orders: relative tolerance on the damping ratio.
        real(dp) :: stable_damping = 0.05_dp
        !> Most impulse samples used by the linear prediction (samples 1..max_samples).
        integer :: max_samples = 4096
        !> Most passes of the out-of-band correction of the impulse response (0: plain LSCE on the raw FFT).
        integer :: max_refinements = 30
        !> Polish poles and residues by Gauss-Newton against G after LSCE and LSFD.
        logical :: polish = .true.
        !> Most Gauss-Newton steps of the polish.
        integer :: max_polish = 50
        !> Fraction of the period 1/df at its end inspected for wrap-around.
        real(dp) :: wrap_fraction = 0.1_dp
        !> Wrap-around is reported when |g| there exceeds this fraction of max |g|.
        real(dp) :: wrap_level = 0.01_dp
    end type lsce_options

    !> Outcome of an identification: the modes, their error and what was dropped or suspected.
    type :: lsce_result
        !> Identified modes (poles lambda_k [rad/s], residues r_k [m/(N*s)], greenconv_model_modal_set convention).
        type(modal_set) :: modes
        !> Upper residual R_u [m/N] (0 unless fitted).
        real(dp) :: upper_residual = 0.0_dp
        !> Lower residual R_l [1/kg] of the term -R_l/omega^2 (0 unless fitted).
        real(dp) :: lower_residual = 0.0_dp
        !> Number of modes N of the LSCE order 2N that gave the model (the model may have fewer modes).
        integer :: order_modes = 0
        !> Error E of eq. (7) of the model on the input grid.
        real(dp) :: e = 1.0_dp
        !> E of the candidate model at each scanned N (index N = 1..last order scanned).
        real(dp), allocatable :: e_by_order(:)
        !> Whether E <= tol_e.
        logical :: tolerance_met = .false.
        !> Whether the scan stopped on an accepted model (E <= tol_e, or fixed_modes modes);
        !> if not, the model is the scanned candidate with the smallest E.
        logical :: accepted = .false.
        !> Roots dropped at the chosen order because |z| >= 1 (Re lambda >= 0: unstable).
        integer :: n_unstable = 0
        !> Real roots dropped at the chosen order (no conjugate pair: Im lambda = 0 or pi/dt).
        integer :: n_real = 0
        !> Physical poles dropped at the chosen order because they were not stable across orders.
        integer :: n_not_stable = 0
        !> Passes of the out-of-band correction used at the chosen order.
        integer :: n_refinements = 0
        !> Time step of the impulse response, dt = 1/(2*f_max) [s].
        real(dp) :: dt = 0.0_dp
        !> max |g| over the last wrap_fraction of the period, relative to max |g|.
        real(dp) :: tail_level = 0.0_dp
        !> Whether g(t) has not decayed within the period 1/df (time-domain wrap-around).
        logical :: wrap_around = .false.
        !> Warnings for the user, '' when none.
        character(len=:), allocatable :: warning
    contains
        !> Receptance [m/N] of the model (modes and residual terms) at omega [rad/s].
        procedure :: receptance => result_receptance
    end type lsce_result

contains

    !> Undamped natural angular frequency omega_k = |lambda_k| [rad/s] of a pole.
    elemental real(dp) function natural_frequency(pole)
        !> Pole lambda_k [rad/s].
        complex(dp), intent(in) :: pole

        natural_frequency = abs(pole)
    end function natural_frequency

    !> Damping ratio xi_k = -Re(lambda_k)/|lambda_k| of a pole.
    elemental real(dp) function damping_ratio(pole)
        !> Pole lambda_k [rad/s], nonzero.
        complex(dp), intent(in) :: pole

        damping_ratio = -real(pole, dp)/abs(pole)
    end function damping_ratio

    !> Receptance of an identification result: modes plus residual terms [m/N]; infinite at
    !> omega = 0 when a lower residual is present.
    elemental complex(dp) function result_receptance(self, omega)
        !> The identification result.
        class(lsce_result), intent(in) :: self
        !> Angular frequency [rad/s].
        real(dp), intent(in) :: omega

        result_receptance = self%upper_residual
        if (self%modes%n_modes() > 0) result_receptance = result_receptance + self%modes%receptance(omega)
        if (abs(self%lower_residual) > 0.0_dp) result_receptance = result_receptance - self%lower_residual/omega**2
    end function result_receptance

    !> Impulse response g(t_n) [m/(N*s)], t_n = n*dt, n = 0..2(n_freq - 1) - 1, dt = 1/(2*f_max),
    !> by the inverse real FFT of the sampled G: g_n = df*sum_k G_k*exp(+2*pi*i*k*n/N_t).
    !> It is the band-limited (|f| <= f_max) Fourier series of g periodized with period 1/df.
    subroutine impulse_from_frf(frf, g, dt, error)
        !> The sampled receptance (uniform grid from 0 Hz, at least 2 lines).
        type(frf_type), intent(in) :: frf
        !> Samples g(n*dt), n = 0..N_t-1, N_t = 2*(n_freq - 1) [m/(N*s)].
        real(dp), allocatable, intent(out) :: g(:)
        !> Time step dt = 1/(2*f_max) [s].
        real(dp), intent(out) :: dt
        !> Set when the FFT fails.
        type(error_type), allocatable, intent(out) :: error

        dt = 0.0_dp
        if (frf%n_freq() < 2) then
            call fatal_error(error, 'impulse_from_frf: at least two frequency lines are needed')
            return
        end if
        call band_limited_impulse(frf%receptance, frf%df(), g, error)
        dt = 1.0_dp/(2.0_dp*frf%f_max())
    end subroutine impulse_from_frf

    !> df*c2r(G): the band-limited periodic impulse response of receptance lines G_k = G(k*df).
    subroutine band_limited_impulse(receptance, df, g, error)
        complex(dp), intent(in) :: receptance(:)
        real(dp), intent(in) :: df
        real(dp), allocatable, intent(out) :: g(:)
        type(error_type), allocatable, intent(out) :: error

        allocate (g(2*(size(receptance) - 1)))
        call inverse_real_fft(receptance, g, error)
        if (allocated(error)) return
        g = df*g
    end subroutine band_limited_impulse

    !> Error E of eq. (7): int |G - G_model| domega / int |G| domega over the lines used,
    !> by the trapezoidal rule on the uniform grid (the step cancels).
    pure real(dp) function error_e(measured, model)
        !> Input receptance on the lines used [m/N].
        complex(dp), intent(in) :: measured(:)
        !> Model receptance on the same lines [m/N].
        complex(dp), intent(in) :: model(:)

        real(dp) :: difference, reference
        integer :: n

        n = size(measured)
        difference = sum(abs(measured - model)) - 0.5_dp*(abs(measured(1) - model(1)) + abs(measured(n) - model(n)))
        reference = sum(abs(measured)) - 0.5_dp*(abs(measured(1)) + abs(measured(n)))
        if (reference > 0.0_dp) then
            error_e = difference/reference
        else
            error_e = huge(1.0_dp)
        end if
    end function error_e

    !> The paper's form of eq. (6) of modes: A_k = Re(2i*omega_k^d*r_k) = -2*omega_k^d*Im(r_k)
    !> [1/kg], omega_k = |lambda_k| [rad/s], xi_k = -Re(lambda_k)/|lambda_k|, exact when
    !> Re(r_k) = 0. lost(k) = |Re r_k|/|r_k| is the part of the residue that the real form
    !> drops: the term 2*Re(r_k)*exp(-xi_k*omega_k*t)*cos(omega_k^d*t) of g(t), i.e. the
    !> numerator 2*Re(r_k)*(i*omega + xi_k*omega_k) of the mode in G(omega).
    pure subroutine paper_form(modes, amplitude, omega, damping, lost)
        !> The modes.
        type(modal_set), intent(in) :: modes
        !> A_k [1/kg].
        real(dp), allocatable, intent(out) :: amplitude(:)
        !> omega_k [rad/s].
        real(dp), allocatable, intent(out) :: omega(:)
        !> xi_k.
        real(dp), allocatable, intent(out) :: damping(:)
        !> |Re r_k|/|r_k|: 0 when the residue is purely imaginary (the form is then exact).
        real(dp), allocatable, intent(out) :: lost(:)

        integer :: n

        n = modes%n_modes()
        allocate (amplitude(n), omega(n), damping(n), lost(n))
        if (n == 0) return
        omega = natural_frequency(modes%pole)
        damping = damping_ratio(modes%pole)
        amplitude = -2.0_dp*aimag(modes%pole)*aimag(modes%residue)
        lost = 0.0_dp
        where (abs(modes%residue) > 0.0_dp) lost = abs(real(modes%residue, dp))/abs(modes%residue)
    end subroutine paper_form

    !> Residues (and residual terms) by linear least squares against G on the grid (LSFD),
    !> for given poles. Unknowns Re r_k, Im r_k (and R_u, R_l); the real and imaginary parts
    !> of the equations are stacked; columns are scaled to unit norm and the system is solved
    !> by the SVD (dgelsd).
    subroutine fit_residues(frf, poles, options, modes, upper, lower, error)
        !> The sampled receptance.
        type(frf_type), intent(in) :: frf
        !> Poles lambda_k [rad/s] (Re < 0, Im > 0).
        complex(dp), intent(in) :: poles(:)
        !> Which residual terms to fit (upper_residual, lower_residual).
        type(lsce_options), intent(in) :: options
        !> The modes: the poles with their fitted residues [m/(N*s)].
        type(modal_set), intent(out) :: modes
        !> Upper residual R_u [m/N] (0 when not fitted).
        real(dp), intent(out) :: upper
        !> Lower residual R_l [1/kg] (0 when not fitted).
        real(dp), intent(out) :: lower
        !> Set when the least-squares problem is too small or fails.
        type(error_type), allocatable, intent(out) :: error

        real(dp), allocatable :: a(:, :), b(:), x(:), norms(:)
        integer :: first, n_lines, n_unknowns, col

        upper = 0.0_dp
        lower = 0.0_dp
        modes%pole = poles
        allocate (modes%residue(size(poles)))
        modes%residue = (0.0_dp, 0.0_dp)
        first = merge(2, 1, options%lower_residual)
        n_lines = size(frf%frequency) - first + 1
        n_unknowns = 2*size(poles) + merge(1, 0, options%upper_residual) + merge(1, 0, options%lower_residual)
        if (n_unknowns == 0) return
        if (2*n_lines < n_unknowns) then
            call fatal_error(error, 'fit_residues: more unknowns than equations', stat_numerical)
            return
        end if
        allocate (a(2*n_lines, n_unknowns), b(2*n_lines), x(n_unknowns), norms(n_unknowns))
        call design_matrix(two_pi*frf%frequency(first:), poles, options, a)
        norms(:) = sqrt(sum(a**2, dim=1))
        where (.not. (norms > 0.0_dp)) norms = 1.0_dp
        do col = 1, n_unknowns
            a(:, col) = a(:, col)/norms(col)
        end do
        b(:) = stack(frf%receptance(first:))
        call least_squares(a, b, x, error, rcond=rcond_residues)
        if (allocated(error)) return
        x = x/norms
        modes%residue = cmplx(x(1:2*size(poles):2), x(2:2*size(poles):2), dp)
        col = 2*size(poles)
        if (options%upper_residual) then
            col = col + 1
            upper = x(col)
        end if
        if (options%lower_residual) lower = x(col + 1)
    end subroutine fit_residues

    !> Columns of the LSFD system at angular frequencies omega [rad/s]: for each pole the
    !> responses to r = 1 and r = i, then the residual terms; real parts above imaginary parts.
    pure subroutine design_matrix(omega, poles, options, a)
        real(dp), intent(in) :: omega(:)
        complex(dp), intent(in) :: poles(:)
        type(lsce_options), intent(in) :: options
        real(dp), intent(out) :: a(:, :)

        complex(dp) :: direct(size(omega)), conjugate(size(omega)), s(size(omega))
        integer :: k, col

        s = cmplx(0.0_dp, omega, dp)
        col = 0
        do k = 1, size(poles)
            direct = 1.0_dp/(s - poles(k))
            conjugate = 1.0_dp/(s - conjg(poles(k)))
            a(:, col + 1) = stack(direct + conjugate)
            a(:, col + 2) = stack(cmplx(0.0_dp, 1.0_dp, dp)*(direct - conjugate))
            col = col + 2
        end do
        if (options%upper_residual) then
            col = col + 1
            a(:, col) = stack(cmplx(1.0_dp, 0.0_dp, dp) + 0.0_dp*s)
        end if
        if (options%lower_residual) a(:, col + 1) = stack(cmplx(-1.0_dp/omega**2, 0.0_dp, dp))
    end subroutine design_matrix

    !> Real and imaginary parts stacked: [Re z; Im z].
    pure function stack(z) result(v)
        !> Complex values (any units).
        complex(dp), intent(in) :: z(:)
        !> Their real parts, then their imaginary parts (the same units).
        real(dp) :: v(2*size(z))

        v(1:size(z)) = real(z, dp)
        v(size(z) + 1:) = aimag(z)
    end function stack

    !> Identify modes of a sampled receptance: LSCE poles with the out-of-band correction,
    !> LSFD residues, the Gauss-Newton polish, E of eq. (7), the order scan (stop on tol_e or
    !> on fixed_modes) and the wrap-around check (see the module description).
    subroutine identify(frf, options, result, error)
        !> The sampled receptance (uniform grid from 0 Hz, at least min_frf_lines lines).
        type(frf_type), intent(in) :: frf
        !> Settings.
        type(lsce_options), intent(in) :: options
        !> The identified model, its error E and the diagnostics.
        type(lsce_result), intent(out) :: result
        !> Set on bad input or a numerical failure (never for a fit that merely misses tol_e).
        type(error_type), allocatable, intent(out) :: error

        real(dp), allocatable :: g_raw(:)

        call check_input(frf, options, error)
        if (allocated(error)) return
        call impulse_from_frf(frf, g_raw, result%dt, error)
        if (allocated(error)) return
        if (.not. (maxval(abs(g_raw(2:))) > 0.0_dp)) then
            call fatal_error(error, 'identify: the receptance has no dynamic content (impulse response is zero)')
            return
        end if
        call identify_scan(frf, g_raw, options, result, error)
        if (allocated(error)) return
        call finish(frf, g_raw, options, result, error)
    end subroutine identify

    !> `receptance_problem` blank-padded to a fixed length, which gives that function a result of spec length.
    pure function receptance_problem_buffer(frf) result(problem)
        !> The sampled receptance.
        type(frf_type), intent(in) :: frf
        !> The problem in a phrase ('' when none).
        character(len=192) :: problem

        problem = ''
        if (frf%n_freq() < min_frf_lines) then
            problem = 'the FRF has fewer than '//int_text(min_frf_lines)//' lines'
        else if (.not. (frf%frequency(1) >= 0.0_dp .and. all(frf%frequency(2:) > frf%frequency(:frf%n_freq() - 1)) &
                        .and. ieee_is_finite(frf%f_max()))) then
            problem = 'the FRF frequencies must be finite, >= 0 Hz and increasing'
        else if (size(frf%receptance) /= frf%n_freq()) then
            problem = 'the FRF has not one receptance per frequency'
        else if (.not. all(ieee_is_finite(real(frf%receptance, dp)) .and. ieee_is_finite(aimag(frf%receptance)))) then
            problem = 'the FRF holds a NaN or infinite receptance; remove or repair those lines'
        else if (abs(frf%receptance(2)) > 0.0_dp .and. all(abs(frf%receptance(2:) - frf%receptance(2)) &
                                                          <= constant_tolerance*abs(frf%receptance(2)))) then
            problem = 'the FRF is the same on every line above 0 Hz, G = '//sci_text(real(frf%receptance(2), dp)) &
                      //' + i*'//sci_text(aimag(frf%receptance(2)))//' m/N: no resonance to identify (a ' &
                      //'constant G is a static compliance, a residual alone)'
        end if
    end function receptance_problem_buffer

    !> What makes a sampled receptance unusable by any identification, '' when nothing: fewer
    !> than min_frf_lines lines, frequencies not finite, negative or not increasing, not one
    !> receptance per frequency, a NaN or infinite receptance, the same nonzero G on every line
    !> above 0 Hz (the first found, in this order).
    pure function receptance_problem(frf) result(problem)
        !> The sampled receptance.
        type(frf_type), intent(in) :: frf
        !> The problem in a phrase ('' when none).
        character(len=len_trim(receptance_problem_buffer(frf))) :: problem

        problem = receptance_problem_buffer(frf)
    end function receptance_problem

    !> Reject inputs the identification cannot use.
    subroutine check_input(frf, options, error)
        !> The receptance (the uniform grid from 0 Hz is needed).
        type(frf_type), intent(in) :: frf
        !> LSCE settings.
        type(lsce_options), intent(in) :: options
        !> Set, naming the first problem found, when the input cannot be used.
        type(error_type), allocatable, intent(out) :: error

        character(len=:), allocatable :: problem

        problem = receptance_problem(frf)
        if (len(problem) > 0) then
            call fatal_error(error, 'identify: '//problem)
        else if (.not. frf%uniform_from_zero()) then
            ! The impulse response is the inverse FFT of the lines: any other grid would give a wrong g.
            call fatal_error(error, 'identify: '//frf%fft_grid_problem()//' (LSCE works on the inverse FFT of G); ' &
                             //'the maximum-likelihood fit (identify_ml) takes any increasing grid')
        else if (options%fixed_modes < 0 .or. options%max_modes < max(1, options%fixed_modes)) then
            call fatal_error(error, 'identify: need fixed_modes >= 0 and max_modes >= max(1, fixed_modes)')
        else if (.not. (options%tol_e > 0.0_dp)) then
            call fatal_error(error, 'identify: tol_e must be > 0')
        else if (options%max_samples < 8 .or. options%max_refinements < 0) then
            call fatal_error(error, 'identify: max_samples must be >= 8 and max_refinements >= 0')
        end if
    end subroutine check_input

    !> Scan N = 1..max_modes. At each N the LSCE poles stable against those of order N - 1
    !> make the candidate model (residues, polish, E). Stop at the first candidate that is
    !> accepted: E <= tol_e, or with fixed_modes > 0, exactly fixed_modes modes. When none
    !> is, return the first candidate whose E is within near_best of the smallest E (the
    !> smallest E alone would favour models that fit noise with extra modes); the result's
    !> `accepted`, `tolerance_met` and warning say so.
    subroutine identify_scan(frf, g_raw, options, result, error)
        type(frf_type), intent(in) :: frf
        real(dp), intent(in) :: g_raw(:)
        type(lsce_options), intent(in) :: options
        type(lsce_result), intent(inout) :: result
        type(error_type), allocatable, intent(out) :: error

        type(lsce_result), allocatable :: candidates(:)
        complex(dp), allocatable :: poles(:), previous(:), kept(:)
        real(dp), allocatable :: history(:)
        logical :: accepted
        integer :: n, n_max, chosen

        n_max = min(options%max_modes, max_feasible_modes(size(g_raw), options))
        if (n_max < max(1, options%fixed_modes)) then
            call fatal_error(error, 'identify: too few impulse samples (or max_modes too small) for the modes asked')
            return
        end if
        allocate (candidates(n_max), previous(0))
        accepted = .false.
        do n = 1, n_max
            associate (trial => candidates(n))
                trial%dt = result%dt
                call fit_order(frf, g_raw, n, options, poles, trial, error)
                if (allocated(error)) return
                kept = pack(poles, stable_poles(poles, previous, options))
                trial%n_not_stable = size(poles) - size(kept)
                trial%order_modes = n
                call fit_model(frf, kept, options, trial, error)
                if (allocated(error)) return
                if (options%fixed_modes > 0) then
                    accepted = trial%modes%n_modes() == options%fixed_modes
                else
                    accepted = trial%e <= options%tol_e
                end if
            end associate
            if (accepted) exit
            previous = poles
        end do
        n = min(n, n_max)
        allocate (history(n))
        do chosen = 1, n
            history(chosen) = candidates(chosen)%e
        end do
        chosen = n
        if (.not. accepted) chosen = findloc(history <= near_best*minval(history), .true., 1)
        call keep_scan(result, candidates(chosen), history)
        result%accepted = accepted
    end subroutine identify_scan

    !> Copy the chosen trial into the result, keeping the scan history.
    subroutine keep_scan(result, chosen, history)
        type(lsce_result), intent(inout) :: result
        type(lsce_result), intent(in) :: chosen
        real(dp), intent(in) :: history(:)

        result = chosen
        allocate (result%e_by_order(size(history)))
        result%e_by_order(:) = history
    end subroutine keep_scan

    !> Largest N whose linear prediction is still overdetermined (rows >= 2*columns).
    pure integer function max_feasible_modes(n_samples, options)
        integer, intent(in) :: n_samples
        type(lsce_options), intent(in) :: options

        integer :: n_used

        n_used = min(n_samples - 1, options%max_samples)
        max_feasible_modes = n_used/6
    end function max_feasible_modes

    !> For each pole, whether one of `previous` has its natural frequency within
    !> stable_frequency and its damping ratio within stable_damping (relative).
    pure function stable_poles(poles, previous, options) result(stable)
        complex(dp), intent(in) :: poles(:), previous(:)
        type(lsce_options), intent(in) :: options
        logical :: stable(size(poles))

        real(dp) :: w, xi, w_prev(size(previous)), xi_prev(size(previous))
        integer :: k

        w_prev = natural_frequency(previous)
        xi_prev = damping_ratio(previous)
        do k = 1, size(poles)
            w = natural_frequency(poles(k))
            xi = damping_ratio(poles(k))
            stable(k) = any(abs(w - w_prev) <= options%stable_frequency*w_prev .and. &
                            abs(xi - xi_prev) <= options%stable_damping*xi_prev)
        end do
    end function stable_poles

    !> Residues for the poles (LSFD), the optional Gauss-Newton polish, then E of the
    !> model on the grid. Poles the polish pushes out of the physical region are dropped
    !> (counted in n_unstable or n_real) and the residues refitted.
    subroutine fit_model(frf, poles, options, result, error)
        type(frf_type), intent(in) :: frf
        complex(dp), intent(in) :: poles(:)
        type(lsce_options), intent(in) :: options
        type(lsce_result), intent(inout) :: result
        type(error_type), allocatable, intent(out) :: error

        logical, allocatable :: physical(:)
        integer :: first

        call fit_residues(frf, poles, options, result%modes, result%upper_residual, result%lower_residual, error)
        if (allocated(error)) return
        if (options%polish .and. result%modes%n_modes() > 0) then
            call polish(frf, options, result, error)
            if (allocated(error)) return
            associate (pole => result%modes%pole)
                physical = real(pole, dp) < 0.0_dp .and. aimag(pole) > 0.0_dp
                result%n_unstable = result%n_unstable + count(.not. (real(pole, dp) < 0.0_dp))
                result%n_real = result%n_real + count(real(pole, dp) < 0.0_dp .and. .not. physical)
            end associate
            if (.not. all(physical)) then
                call fit_residues(frf, pack(result%modes%pole, physical), options, result%modes, &
                                  result%upper_residual, result%lower_residual, error)
                if (allocated(error)) return
            end if
        end if
        first = merge(2, 1, options%lower_residual)
        result%e = error_e(frf%receptance(first:), result%receptance(two_pi*frf%frequency(first:)))
    end subroutine fit_model

    !> Gauss-Newton polish of all parameters (Re and Im of poles and residues, residual terms)
    !> against G on the grid: the nonlinear least-squares problem whose linear part is LSFD.
    !> Each step is an SVD least-squares solve of the linearized system (columns scaled to
    !> unit norm), halved until the misfit ||G - G_model||_2 decreases; stops when no step
    !> decreases it or after max_polish steps.
    subroutine polish(frf, options, result, error)
        type(frf_type), intent(in) :: frf
        type(lsce_options), intent(in) :: options
        type(lsce_result), intent(inout) :: result
        type(error_type), allocatable, intent(out) :: error

        type(lsce_result) :: trial
        real(dp), allocatable :: omega(:), jacobian(:, :), norms(:), step(:), misfit_vector(:)
        complex(dp), allocatable :: measured(:)
        real(dp) :: misfit, trial_misfit, factor
        integer :: first, iteration, halving, col, n_lines, n_unknowns

        first = merge(2, 1, options%lower_residual)
        n_lines = frf%n_freq() - first + 1
        n_unknowns = 4*result%modes%n_modes() + merge(1, 0, options%upper_residual) &
                     + merge(1, 0, options%lower_residual)
        allocate (omega(n_lines), measured(n_lines), misfit_vector(2*n_lines), step(n_unknowns), norms(n_unknowns))
        omega(:) = two_pi*frf%frequency(first:)
        measured(:) = frf%receptance(first:)
        misfit_vector(:) = stack(measured - result%receptance(omega))
        misfit = norm2(misfit_vector)
        do iteration = 1, options%max_polish
            call polish_jacobian(omega, result, options, jacobian)
            norms(:) = sqrt(sum(jacobian**2, dim=1))
            where (.not. (norms > 0.0_dp)) norms = 1.0_dp
            do col = 1, size(jacobian, 2)
                jacobian(:, col) = jacobian(:, col)/norms(col)
            end do
            call least_squares(jacobian, misfit_vector, step, error, rcond=rcond_residues)
            if (allocated(error)) return
            step = step/norms
            factor = 1.0_dp
            trial_misfit = huge(1.0_dp)
            do halving = 0, 30
                trial = result
                call add_parameter_step(factor*step, options%upper_residual, options%lower_residual, trial%modes%pole, &
                                        trial%modes%residue, trial%upper_residual, trial%lower_residual)
                trial_misfit = norm2(stack(measured - trial%receptance(omega)))
                if (trial_misfit < misfit) exit
                factor = 0.5_dp*factor
            end do
            if (.not. (trial_misfit < misfit)) exit
            result = trial
            misfit = trial_misfit
            misfit_vector(:) = stack(measured - result%receptance(omega))
        end do
    end subroutine polish

    !> Jacobian of the stacked model [Re G; Im G] with respect to, per mode,
    !> (Re lambda, Im lambda, Re r, Im r), then R_u and R_l when fitted.
    pure subroutine polish_jacobian(omega, result, options, jacobian)
        real(dp), intent(in) :: omega(:)
        type(lsce_result), intent(in) :: result
        type(lsce_options), intent(in) :: options
        real(dp), allocatable, intent(out) :: jacobian(:, :)

        complex(dp), parameter :: i_unit = (0.0_dp, 1.0_dp)
        complex(dp) :: direct(size(omega)), conjugate(size(omega)), s(size(omega)), r
        integer :: k, col, n_modes

        n_modes = result%modes%n_modes()
        allocate (jacobian(2*size(omega), 4*n_modes + merge(1, 0, options%upper_residual) + &
                                          merge(1, 0, options%lower_residual)))
        s = cmplx(0.0_dp, omega, dp)
        do k = 1, n_modes
            r = result%modes%residue(k)
            direct = 1.0_dp/(s - result%modes%pole(k))
            conjugate = 1.0_dp/(s - conjg(result%modes%pole(k)))
            col = 4*(k - 1)
            jacobian(:, col + 1) = stack(r*direct**2 + conjg(r)*conjugate**2)
            jacobian(:, col + 2) = stack(i_unit*(r*direct**2 - conjg(r)*conjugate**2))
            jacobian(:, col + 3) = stack(direct + conjugate)
            jacobian(:, col + 4) = stack(i_unit*(direct - conjugate))
        end do
        col = 4*n_modes
        if (options%upper_residual) then
            col = col + 1
            jacobian(:, col) = stack(cmplx(1.0_dp, 0.0_dp, dp) + 0.0_dp*s)
        end if
        if (options%lower_residual) jacobian(:, col + 1) = stack(cmplx(-1.0_dp/omega**2, 0.0_dp, dp))
    end subroutine polish_jacobian

    !> Add a parameter step laid out per mode as (Re lambda, Im lambda, Re r, Im r), then R_u
    !> and R_l when present (the layout of polish_jacobian here and of the ML fit's Jacobian).
    pure subroutine add_parameter_step(step, upper, lower, pole, residue, upper_residual, lower_residual)
        !> The step: [rad/s] for the poles, [m/(N*s)] for the residues, [m/N] for R_u, [1/kg] for R_l.
        real(dp), intent(in) :: step(:)
        !> Whether the step holds R_u.
        logical, intent(in) :: upper
        !> Whether the step holds R_l.
        logical, intent(in) :: lower
        !> Poles [rad/s], moved by the step (none when not allocated).
        complex(dp), allocatable, intent(inout) :: pole(:)
        !> Residues [m/(N*s)], one per pole, moved by the step.
        complex(dp), allocatable, intent(inout) :: residue(:)
        !> Upper residual R_u [m/N], moved when `upper`.
        real(dp), intent(inout) :: upper_residual
        !> Lower residual R_l [1/kg], moved when `lower`.
        real(dp), intent(inout) :: lower_residual

        integer :: k, col, n

        n = 0
        if (allocated(pole)) n = size(pole)
        do k = 1, n
            col = 4*(k - 1)
            pole(k) = pole(k) + cmplx(step(col + 1), step(col + 2), dp)
            residue(k) = residue(k) + cmplx(step(col + 3), step(col + 4), dp)
        end do
        col = 4*n
        if (upper) then
            col = col + 1
            upper_residual = upper_residual + step(col)
        end if
        if (lower) lower_residual = lower_residual + step(col + 1)
    end subroutine add_parameter_step

    !> LSCE at order 2*n_modes with the out-of-band correction iterated to convergence:
    !> returns the physical poles and fills the drop counts of `result`.
    subroutine fit_order(frf, g_raw, n_modes, options, poles, result, error)
        type(frf_type), intent(in) :: frf
        real(dp), intent(in) :: g_raw(:)
        integer, intent(in) :: n_modes
        type(lsce_options), intent(in) :: options
        complex(dp), allocatable, intent(out) :: poles(:)
        type(lsce_result), intent(inout) :: result
        type(error_type), allocatable, intent(out) :: error

        real(dp), allocatable :: g(:), g_next(:)
        real(dp) :: change
        integer :: pass

        allocate (g(size(g_raw)))
        g(:) = g_raw
        result%n_refinements = 0
        do pass = 0, options%max_refinements
            call lsce_poles(g, result%dt, 2*n_modes, options%max_samples, poles, result%n_unstable, result%n_real, &
                            error)
            if (allocated(error)) return
            if (pass == options%max_refinements) exit
            call fit_residues(frf, poles, options, result%modes, result%upper_residual, result%lower_residual, error)
            if (allocated(error)) return
            call corrected_impulse(frf, result, options%lower_residual, g_next, error)
            if (allocated(error)) return
            change = maxval(abs(g_next(2:) - g(2:)))
            g(:) = g_next
            result%n_refinements = pass + 1
            if (change <= refinement_tolerance*maxval(abs(g(2:)))) exit
        end do
    end subroutine fit_order

    !> The impulse response as the model's exact periodized response plus the band-limited
    !> FFT of what the model does not explain, G - G_model (left at 0 on the 0 Hz line when
    !> a lower residual is fitted, since the model is infinite there).
    subroutine corrected_impulse(frf, model, skip_zero, g, error)
        type(frf_type), intent(in) :: frf
        type(lsce_result), intent(in) :: model
        logical, intent(in) :: skip_zero
        real(dp), allocatable, intent(out) :: g(:)
        type(error_type), allocatable, intent(out) :: error

        complex(dp) :: unexplained(frf%n_freq())

        unexplained(2:) = frf%receptance(2:) - model%receptance(two_pi*frf%frequency(2:))
        if (skip_zero) then
            unexplained(1) = (0.0_dp, 0.0_dp)
        else
            unexplained(1) = frf%receptance(1) - model%receptance(0.0_dp)
        end if
        call band_limited_impulse(unexplained, frf%df(), g, error)
        if (allocated(error)) return
        g = g + periodic_impulse(model%modes, model%dt, size(g))
    end subroutine corrected_impulse

    !> Samples n = 0..n_t-1 of the modes' impulse response periodized with period n_t*dt,
    !> sum_k 2*Re(r_k*z_k^n/(1 - z_k^n_t)), z_k = exp(lambda_k*dt); at n = 0 the mean of the
    !> two sides of the jump, which is what a Fourier series converges to.
    pure function periodic_impulse(modes, dt, n_t) result(g)
        type(modal_set), intent(in) :: modes
        real(dp), intent(in) :: dt
        integer, intent(in) :: n_t
        real(dp) :: g(n_t)

        complex(dp) :: scale
        integer :: k, n

        g = 0.0_dp
        do k = 1, modes%n_modes()
            scale = 2.0_dp*modes%residue(k)/(1.0_dp - exp(modes%pole(k)*(n_t*dt)))
            g = g + [(real(scale*exp(modes%pole(k)*(n*dt)), dp), n=0, n_t - 1)]
            g(1) = g(1) - real(modes%residue(k), dp)
        end do
    end function periodic_impulse

    !> The LSCE step: linear prediction of order p of the samples g_1..g_M (M = min(N_t - 1,
    !> max_samples)), solved by SVD least squares, roots of the prediction polynomial as the
    !> eigenvalues of its companion matrix, physical poles lambda = ln(z)/dt kept.
    !> Public as the cheap linear step of a stabilisation diagram (one call per order, no
    !> out-of-band correction, no residues). The poles are rounded to reproducible_grid of
    !> their magnitude (`reproducible`): the SVD and the eigenvalues are LAPACK's, whose last
    !> bits follow the BLAS kernels and threads, and the diagram's decisions and the start of
    !> the fits must not.
    subroutine lsce_poles(g, dt, p, max_samples, poles, n_unstable, n_real, error)
        !> Impulse samples g(n*dt), n = 0..N_t-1 [m/(N*s)] (e.g. from impulse_from_frf).
        real(dp), intent(in) :: g(:)
        !> Time step [s].
        real(dp), intent(in) :: dt
        !> Order of the prediction polynomial (2 per mode).
        integer, intent(in) :: p
        !> Most samples used (t_1..t_M, M = min(N_t - 1, max_samples)).
        integer, intent(in) :: max_samples
        !> Physical poles lambda = ln(z)/dt [rad/s] (Re < 0, Im > 0).
        complex(dp), allocatable, intent(out) :: poles(:)
        !> Roots dropped with |z| >= 1 (unstable), upper half plane only.
        integer, intent(out) :: n_unstable
        !> Real roots dropped (no conjugate pair).
        integer, intent(out) :: n_real
        !> Set when there are too few samples for the order or LAPACK fails.
        type(error_type), allocatable, intent(out) :: error

        real(dp), allocatable :: a(:, :), b(:), coefficients(:), companion(:, :), h(:)
        complex(dp), allocatable :: roots(:)
        integer :: m, rows, i, j

        ! g(1) is t = 0 (index shift of one): use t_1 .. t_M.
        m = min(size(g) - 1, max_samples)
        rows = m - p
        if (rows < p) then
            call fatal_error(error, 'lsce: too few impulse samples for the requested order', stat_input)
            return
        end if
        allocate (h(m), a(rows, p), b(rows), coefficients(p), companion(p, p), roots(p))
        h(:) = g(2:m + 1)/maxval(abs(g(2:m + 1)))
        do j = 1, p
            a(:, j) = h(j:j + rows - 1)
        end do
        b(:) = -h(p + 1:p + rows)
        call least_squares(a, b, coefficients, error, rcond=rcond_prediction)
        if (allocated(error)) return
        companion = 0.0_dp
        do i = 1, p - 1
            companion(i, i + 1) = 1.0_dp
        end do
        companion(p, :) = -coefficients
        call eigenvalues(companion, roots, error)
        if (allocated(error)) return
        call physical_poles(roots, dt, poles, n_unstable, n_real)
        poles = reproducible(poles)
    end subroutine lsce_poles

    !> A pole with its real part and its imaginary part each rounded to a multiple of
    !> reproducible_grid times the power of two at or above its own magnitude (so that the
    !> damping keeps its relative precision): the same bits from any BLAS whose result differs
    !> from another's by less than the grid, except within that difference of a rounding
    !> boundary.
    elemental complex(dp) function reproducible(pole)
        !> Pole [rad/s].
        complex(dp), intent(in) :: pole

        reproducible = cmplx(rounded(real(pole, dp)), rounded(aimag(pole)), dp)
    contains
        !> x rounded to reproducible_grid of the power of two at or above |x|.
        elemental real(dp) function rounded(x)
            real(dp), intent(in) :: x

            real(dp) :: unit

            rounded = x
            if (.not. (abs(x) > 0.0_dp) .or. abs(x) > huge(1.0_dp)) return
            unit = reproducible_grid*set_exponent(1.0_dp, exponent(x))
            rounded = unit*anint(x/unit)
        end function rounded
    end function reproducible

    !> Keep the roots z with Im z > 0 and |z| < 1 as poles ln(z)/dt (Re < 0, 0 < Im < pi/dt);
    !> count the dropped ones. Roots with Im z < 0 are the conjugates of kept or counted ones.
    pure subroutine physical_poles(roots, dt, poles, n_unstable, n_real)
        complex(dp), intent(in) :: roots(:)
        real(dp), intent(in) :: dt
        complex(dp), allocatable, intent(out) :: poles(:)
        integer, intent(out) :: n_unstable, n_real

        logical :: upper(size(roots)), inside(size(roots))

        upper = aimag(roots) > 0.0_dp
        inside = abs(roots) < 1.0_dp
        n_real = count(.not. (abs(aimag(roots)) > 0.0_dp))
        n_unstable = count(upper .and. .not. inside)
        poles = log(pack(roots, upper .and. inside))/dt
    end subroutine physical_poles

    !> max |g_n| over the last `fraction` of the samples relative to max |g_n|, n >= 1.
    pure real(dp) function tail_level(g, fraction)
        real(dp), intent(in) :: g(:)
        real(dp), intent(in) :: fraction

        integer :: first

        first = max(2, size(g) - max(1, nint(fraction*size(g))) + 1)
        tail_level = maxval(abs(g(first:)))/maxval(abs(g(2:)))
    end function tail_level

    !> Wrap-around check on the impulse response of the final model (its periodized response
    !> plus the band-limited FFT of what it does not explain), and the warnings: wrap-around,
    !> unstable poles dropped (Re lambda >= 0), tolerance not met.
    subroutine finish(frf, g_raw, options, result, error)
        type(frf_type), intent(in) :: frf
        real(dp), intent(in) :: g_raw(:)
        type(lsce_options), intent(in) :: options
        type(lsce_result), intent(inout) :: result
        type(error_type), allocatable, intent(out) :: error

        real(dp), allocatable :: g(:)
        integer :: n_t
        character(len=300) :: text

        n_t = size(g_raw)
        if (result%modes%n_modes() > 0) then
            call corrected_impulse(frf, result, options%lower_residual, g, error)
            if (allocated(error)) return
            result%tail_level = tail_level(g, options%wrap_fraction)
        else
            result%tail_level = tail_level(g_raw, options%wrap_fraction)
        end if
        result%wrap_around = result%tail_level > options%wrap_level
        result%warning = ''
        if (result%wrap_around) then
            write (text, '(a,es9.2,a,es9.2,a,es8.1,a)') 'wrap-around: g(t) has not decayed within the period 1/df = ', &
                n_t*result%dt, ' s (end of period at', result%tail_level, ' of max|g|, limit', options%wrap_level, &
                '); use a finer frequency step'
            result%warning = trim(text)
        end if
        if (result%n_unstable > 0) then
            write (text, '(i0,a)') result%n_unstable, ' pole(s) with Re lambda >= 0 (unstable, not a passive ' &
                //'structure) dropped from the model'
            if (len(result%warning) > 0) result%warning = result%warning//'; '
            result%warning = result%warning//trim(text)
        end if
        result%tolerance_met = result%e <= options%tol_e
        if (.not. result%accepted) then
            if (options%fixed_modes > 0) then
                write (text, '(a,i0,a,i0,a,i0,a,es9.2)') 'no order up to N = ', size(result%e_by_order), &
                    ' gave ', options%fixed_modes, ' stable modes; kept the first model within 10 % of the '// &
                    'smallest E (', result%modes%n_modes(), ' modes), E = ', result%e
            else
                write (text, '(a,i0,a,es9.2,a,i0,a,es9.2)') 'no order up to N = ', size(result%e_by_order), &
                    ' met tol_e = ', options%tol_e, '; kept the first model within 10 % of the smallest E: N = ', &
                    result%order_modes, ', E = ', result%e
            end if
            if (len(result%warning) > 0) result%warning = result%warning//'; '
            result%warning = result%warning//trim(text)
        end if
    end subroutine finish

end module greenconv_ident_lsce
