!> LSCE identification (greenconv_ident_lsce), the FRF type and reader (greenconv_model_frf) and the FFT
!> scaling (greenconv_ext_fftw), each against the modes that generated the data.
!>
!> Grid of the noise-free tests: f_max = 500 Hz, 4001 lines (df = 0.125 Hz, period
!> 1/df = 8 s, dt = 1 ms). Every mode decays below 1 % of its peak well within 0.9 of the
!> period, so no wrap-around is reported, and the slowest (150 Hz, xi = 0.001, time
!> constant 1.06 s) is still resolved by 17 lines per half-power bandwidth.
module test_lsce_mod
    use, intrinsic :: iso_fortran_env, only: dp => real64
    use testsuite_mod, only: test_error, unittest_type, new_unittest, check, note
    use greenconv_core_error, only: error_type
    use greenconv_model_modal_set, only: modal_set, modes_from_paper
    use greenconv_model_sdof, only: sdof_impulse, sdof_receptance
    use greenconv_core_random, only: random_stream
    use greenconv_ext_fftw, only: forward_real_fft
    use greenconv_model_frf, only: frf_type, frf_from_modes, read_frf, write_frf
    use greenconv_ident_lsce, only: lsce_options, lsce_result, identify, impulse_from_frf, paper_form, &
                        natural_frequency, damping_ratio
    implicit none
    private

    public :: collect_lsce

    real(dp), parameter :: pi = 3.141592653589793238462643383279_dp
    real(dp), parameter :: two_pi = 2.0_dp*pi
    !> Grid of the noise-free tests.
    real(dp), parameter :: f_max = 500.0_dp
    integer, parameter :: n_freq = 4001

contains

    !> Tests of greenconv_ident_lsce, greenconv_model_frf and greenconv_ext_fftw.
    subroutine collect_lsce(testsuite)
        type(unittest_type), allocatable, intent(out) :: testsuite(:)

        testsuite = [new_unittest('fft: exactly periodic sdof G gives sdof_impulse to round-off', test_fft_exact), &
                     new_unittest('fft: band-limited sdof G within its truncation bound', test_fft_band_limited), &
                     new_unittest('clean: two closely spaced modes (100, 101 Hz)', test_close_modes), &
                     new_unittest('clean: light (xi = 0.001) and heavy (xi = 0.2) damping', test_damping_extremes), &
                     new_unittest('clean: modes near the band edges (5 Hz, 490 Hz)', test_band_edges), &
                     new_unittest('noise 1 %: physical poles, f within 0.5 %, xi spread', test_noise), &
                     new_unittest('order scan: 10 clean modes give 10 modes', test_order_scan), &
                     new_unittest('wrap-around: a coarse grid is reported, a fine one not', test_wrap_around), &
                     new_unittest('residues: complex residues and G reconstructed', test_residues), &
                     new_unittest('residues: upper and lower residual terms', test_residual_terms), &
                     new_unittest('paper form: real A_k round-trips', test_paper_form), &
                     new_unittest('frf file: write then read back', test_frf_round_trip), &
                     new_unittest('frf file: one message per kind of bad file', test_frf_errors)]
    end subroutine collect_lsce

    ! ---- helpers ---------------------------------------------------------------------

    !> Modes from natural frequencies [Hz], damping ratios and complex residues [m/(N*s)].
    pure function modes_from(frequency, damping, residue) result(modes)
        real(dp), intent(in) :: frequency(:), damping(:)
        complex(dp), intent(in) :: residue(:)
        type(modal_set) :: modes

        allocate (modes%pole(size(frequency)), modes%residue(size(frequency)))
        modes%pole(:) = two_pi*frequency*cmplx(-damping, sqrt(1.0_dp - damping**2), dp)
        modes%residue(:) = residue
    end function modes_from

    !> For each true mode, the identified pole nearest to it: the largest relative errors
    !> of omega_k, xi_k and r_k. Fails unless the numbers of modes agree.
    subroutine compare(error, found, truth, err_omega, err_xi, err_residue)
        type(test_error), allocatable, intent(out) :: error
        type(modal_set), intent(in) :: found, truth
        real(dp), intent(out) :: err_omega, err_xi, err_residue

        integer :: k, j

        err_omega = huge(1.0_dp)
        err_xi = huge(1.0_dp)
        err_residue = huge(1.0_dp)
        call check(error, found%n_modes() == truth%n_modes(), 'number of modes identified differs from the truth')
        if (allocated(error)) return
        err_omega = 0.0_dp
        err_xi = 0.0_dp
        err_residue = 0.0_dp
        do k = 1, truth%n_modes()
            j = minloc(abs(found%pole - truth%pole(k)), 1)
            err_omega = max(err_omega, abs(natural_frequency(found%pole(j))/natural_frequency(truth%pole(k)) - 1.0_dp))
            err_xi = max(err_xi, abs(damping_ratio(found%pole(j))/damping_ratio(truth%pole(k)) - 1.0_dp))
            err_residue = max(err_residue, abs(found%residue(j) - truth%residue(k))/abs(truth%residue(k)))
        end do
    end subroutine compare

    !> Identify the modes of noise-free G at a fixed order on the standard grid and check
    !> omega_k, xi_k to 1e-8 relative and E < 1e-10; also note what LSCE alone (no polish)
    !> gives, checked only against a loose 1e-6.
    subroutine check_clean(error, truth)
        type(test_error), allocatable, intent(out) :: error
        type(modal_set), intent(in) :: truth

        type(frf_type) :: frf
        type(lsce_options) :: options
        type(lsce_result) :: result
        type(error_type), allocatable :: failure
        real(dp) :: err_omega, err_xi, err_residue

        frf = frf_from_modes(truth, f_max, n_freq)
        options%fixed_modes = truth%n_modes()
        options%polish = .false.
        call identify(frf, options, result, failure)
        call check(error, .not. allocated(failure), 'identify (LSCE only) failed')
        if (allocated(error)) return
        call compare(error, result%modes, truth, err_omega, err_xi, err_residue)
        if (allocated(error)) return
        call note('LSCE only: xi err', err_xi)
        call check(error, err_xi, 0.0_dp, 'LSCE only, xi relative error', thr=1.0e-6_dp)
        if (allocated(error)) return
        options%polish = .true.
        call identify(frf, options, result, failure)
        call check(error, .not. allocated(failure), 'identify failed')
        if (allocated(error)) return
        call compare(error, result%modes, truth, err_omega, err_xi, err_residue)
        if (allocated(error)) return
        call note('omega err', err_omega)
        call note('xi err', err_xi)
        call note('r err', err_residue)
        call note('E', result%e)
        call check(error, err_omega, 0.0_dp, 'omega_k relative error', thr=1.0e-8_dp)
        if (allocated(error)) return
        call check(error, err_xi, 0.0_dp, 'xi_k relative error', thr=1.0e-8_dp)
        if (allocated(error)) return
        call check(error, result%e, 0.0_dp, 'E of eq. (7)', thr=1.0e-10_dp)
        if (allocated(error)) return
        call check(error, result%accepted .and. .not. result%wrap_around .and. len(result%warning) == 0, &
                   'accepted, and no wrap-around or other warning on clean, well-sampled data')
    end subroutine check_clean

    !> Multiply each line by 1 + level*n, n complex Gaussian with E|n|^2 = 1 (Box-Muller on
    !> the portable random_stream, so the noise is the same with every compiler).
    subroutine add_noise(frf, level, seed)
        type(frf_type), intent(inout) :: frf
        real(dp), intent(in) :: level
        integer, intent(in) :: seed

        type(random_stream) :: stream
        real(dp) :: u1, u2, radius
        integer :: j

        stream = random_stream(seed)
        do j = 1, frf%n_freq()
            u1 = 1.0_dp - stream%uniform()
            u2 = stream%uniform()
            radius = sqrt(-log(u1))
            frf%receptance(j) = frf%receptance(j)*(1.0_dp + level*radius*cmplx(cos(two_pi*u2), sin(two_pi*u2), dp))
        end do
    end subroutine add_noise

    ! ---- fft ---------------------------------------------------------------------------

    !> G_d(omega) = dt*sum_{n>=0} g(n dt)*exp(-i omega n dt) is the transform of the sampled
    !> sdof response; on the grid f_k = k*df it is exactly the DFT of the samples periodized
    !> with period 1/df, so df*c2r(G_d) must return the samples g(n dt) + wrapped tail (the
    !> tail is below 1e-17 here) to round-off. A wrong sign would reverse time, a wrong
    !> scale would miss by a factor. Also checks dt*r2c(g) = G_d (the forward direction).
    subroutine test_fft_exact(error)
        type(test_error), allocatable, intent(out) :: error

        real(dp), parameter :: mass = 1.0_dp, stiffness = 1.0e6_dp, xi = 0.02_dp
        integer, parameter :: lines = 5001
        real(dp), parameter :: top = 2500.0_dp
        type(modal_set) :: modes
        type(frf_type) :: frf
        type(error_type), allocatable :: failure
        real(dp), allocatable :: g(:), expected(:)
        complex(dp), allocatable :: spectrum(:)
        complex(dp) :: z, w, r
        real(dp) :: dt, scale
        integer :: k, n

        modes = modes_from_paper([1.0_dp/mass], [sqrt(stiffness/mass)], [xi])
        frf = frf_from_modes(modes, top, lines)
        dt = 1.0_dp/(2.0_dp*top)
        z = exp(modes%pole(1)*dt)
        r = modes%residue(1)
        do k = 1, lines
            w = exp(cmplx(0.0_dp, -two_pi*frf%frequency(k)*dt, dp))
            frf%receptance(k) = dt*(r/(1.0_dp - z*w) + conjg(r)/(1.0_dp - conjg(z)*w))
        end do
        call impulse_from_frf(frf, g, dt, failure)
        call check(error, .not. allocated(failure), 'impulse_from_frf failed')
        if (allocated(error)) return
        call check(error, size(g) == 2*(lines - 1) .and. abs(dt - 2.0e-4_dp) < 1.0e-18_dp, &
            'N_t = 2(n - 1), dt = 1/(2 f_max)')
        if (allocated(error)) return
        allocate (expected(size(g)))
        expected(:) = sdof_impulse(mass, stiffness, xi, [(n*dt, n=0, size(g) - 1)])
        scale = maxval(abs(expected))
        call note('max|g_fft - g|/max|g|', maxval(abs(g - expected))/scale)
        call check(error, maxval(abs(g - expected))/scale, 0.0_dp, 'df*c2r(G_d) against sdof_impulse', thr=1.0e-12_dp)
        if (allocated(error)) return
        allocate (spectrum(lines))
        call forward_real_fft(expected, spectrum, failure)
        call check(error, .not. allocated(failure), 'forward_real_fft failed')
        if (allocated(error)) return
        call note('max|dt*r2c(g) - G_d|/max|G_d|', &
            maxval(abs(dt*spectrum - frf%receptance))/maxval(abs(frf%receptance)))
        call check(error, maxval(abs(dt*spectrum - frf%receptance))/maxval(abs(frf%receptance)), 0.0_dp, &
                   'dt*r2c(g) against G_d', thr=1.0e-12_dp)
    end subroutine test_fft_exact

    !> With the true G sampled up to f_max, df*c2r(G) is the band-limited Fourier series of
    !> the periodized g. Its coefficients are c_k = df*G(2 pi k df); the lines |k| > K are
    !> missing and the Nyquist line enters with half weight, so at every sample
    !>     |g_fft - g| <= |c_K| + 2*sum_{k>K} |c_k| + wrapped tail
    !>              <= df*|G(w_max)| + (A/(2 pi w0))*ln((w_max + w0)/(w_max - w0)) + tail,
    !> using |G(w)| <= A/(w^2 - w0^2) above resonance and the integral bound of the sum.
    !> Here (w0 = 1000 rad/s, f_max = 2500 Hz) that is 2.0e-5 m/(N s), 2 % of max|g|.
    subroutine test_fft_band_limited(error)
        type(test_error), allocatable, intent(out) :: error

        real(dp), parameter :: mass = 1.0_dp, stiffness = 1.0e6_dp, xi = 0.02_dp
        integer, parameter :: lines = 5001
        real(dp), parameter :: top = 2500.0_dp
        type(frf_type) :: frf
        type(error_type), allocatable :: failure
        real(dp), allocatable :: g(:), expected(:)
        real(dp) :: dt, w0, w_max, bound, worst
        integer :: n

        frf = frf_from_modes(modes_from_paper([1.0_dp/mass], [sqrt(stiffness/mass)], [xi]), top, lines)
        call impulse_from_frf(frf, g, dt, failure)
        call check(error, .not. allocated(failure), 'impulse_from_frf failed')
        if (allocated(error)) return
        allocate (expected(size(g)))
        expected(:) = sdof_impulse(mass, stiffness, xi, [(n*dt, n=0, size(g) - 1)])
        w0 = sqrt(stiffness/mass)
        w_max = two_pi*top
        bound = frf%df()*abs(sdof_receptance(mass, stiffness, xi, w_max)) &
                + (1.0_dp/mass)/(two_pi*w0)*log((w_max + w0)/(w_max - w0)) &
                + exp(-xi*w0*size(g)*dt)/(mass*w0)/(1.0_dp - exp(-xi*w0*size(g)*dt))
        worst = maxval(abs(g - expected))
        call note('max|g_fft - g|/max|g|', worst/maxval(abs(expected)))
        call note('error/bound', worst/bound)
        call check(error, worst, 0.0_dp, 'band-limited impulse response error', thr=bound)
    end subroutine test_fft_band_limited

    ! ---- noise-free identification -----------------------------------------------------

    !> 100 and 101 Hz, xi = 0.01 each: the half-power bands (2 Hz) overlap. The residues are
    !> complex (non-proportional damping), 8 lines per Hz.
    subroutine test_close_modes(error)
        type(test_error), allocatable, intent(out) :: error

        call check_clean(error, modes_from([100.0_dp, 101.0_dp], [0.01_dp, 0.01_dp], &
                                           [(2.0_dp, -30.0_dp), (-5.0_dp, -20.0_dp)]))
    end subroutine test_close_modes

    !> xi = 0.001 at 150 Hz (time constant 1.06 s, 8 s period) beside xi = 0.2 at 300 Hz.
    subroutine test_damping_extremes(error)
        type(test_error), allocatable, intent(out) :: error

        call check_clean(error, modes_from_paper([5.0e4_dp, 3.0e6_dp], two_pi*[150.0_dp, 300.0_dp], [0.001_dp, 0.2_dp]))
    end subroutine test_damping_extremes

    !> 5 Hz (1 % of f_max, xi = 0.05) and 490 Hz (98 % of f_max, 0.98 of the Nyquist
    !> angle pi per sample, xi = 0.02), with a mode at 250 Hz between them.
    subroutine test_band_edges(error)
        type(test_error), allocatable, intent(out) :: error

        call check_clean(error, modes_from_paper([1.0e3_dp, 1.0e6_dp, 5.0e6_dp], two_pi*[5.0_dp, 250.0_dp, 490.0_dp], &
                                                 [0.05_dp, 0.01_dp, 0.02_dp]))
    end subroutine test_band_edges

    ! ---- noise ---------------------------------------------------------------------------

    !> Three modes (60, 150, 320 Hz; xi = 0.02, 0.05, 0.01) on 2001 lines to 500 Hz, each line
    !> multiplied by 1 + 0.01*n (complex Gaussian, rms |n| = 1), 8 seeds, order scan with
    !> tol_e = 0.015 (the noise alone gives E = 0.01*sqrt(pi)/2 = 0.0089 on average).
    !> Checks: 3 modes, all physical, frequencies within 0.5 %, every xi within 2 %;
    !> notes the rms and largest relative xi error over the 24 estimates (all within 2 %), for the full
    !> method and for LSCE and LSFD alone (no Gauss-Newton polish), checked alike.
    subroutine test_noise(error)
        type(test_error), allocatable, intent(out) :: error

        call noise_run(error, .true., '')
        if (allocated(error)) return
        call noise_run(error, .false., 'LSCE only: ')
    end subroutine test_noise

    !> One set of noisy identifications (see test_noise).
    subroutine noise_run(error, polish, label)
        type(test_error), allocatable, intent(out) :: error
        logical, intent(in) :: polish
        character(len=*), intent(in) :: label

        integer, parameter :: n_seeds = 8
        type(modal_set) :: truth
        type(frf_type) :: frf
        type(lsce_options) :: options
        type(lsce_result) :: result
        type(error_type), allocatable :: failure
        real(dp) :: err_omega, worst_omega, sum_xi2, worst_xi, worst_e, xi_error
        integer :: seed, k, j

        truth = modes_from_paper([2.0e3_dp, 1.0e4_dp, 2.0e4_dp], two_pi*[60.0_dp, 150.0_dp, 320.0_dp], &
                                 [0.02_dp, 0.05_dp, 0.01_dp])
        options%tol_e = 0.015_dp
        options%max_modes = 12
        options%polish = polish
        worst_omega = 0.0_dp
        worst_xi = 0.0_dp
        worst_e = 0.0_dp
        sum_xi2 = 0.0_dp
        do seed = 1, n_seeds
            frf = frf_from_modes(truth, f_max, 2001)
            call add_noise(frf, 0.01_dp, 1000 + seed)
            call identify(frf, options, result, failure)
            call check(error, .not. allocated(failure), label//'identify failed on noisy data')
            if (allocated(error)) return
            call check(error, all(real(result%modes%pole, dp) < 0.0_dp .and. aimag(result%modes%pole) > 0.0_dp), &
                       label//'a non-physical pole was returned')
            if (allocated(error)) return
            call check(error, result%modes%n_modes() == 3, label//'three modes expected from the noisy data')
            if (allocated(error)) return
            do k = 1, 3
                j = minloc(abs(result%modes%pole - truth%pole(k)), 1)
                err_omega = abs(natural_frequency(result%modes%pole(j))/natural_frequency(truth%pole(k)) - 1.0_dp)
                xi_error = damping_ratio(result%modes%pole(j))/damping_ratio(truth%pole(k)) - 1.0_dp
                worst_omega = max(worst_omega, err_omega)
                worst_xi = max(worst_xi, abs(xi_error))
                sum_xi2 = sum_xi2 + xi_error**2
            end do
            worst_e = max(worst_e, result%e)
        end do
        call note(label//'max f err', worst_omega)
        call note(label//'rms xi err', sqrt(sum_xi2/(3*n_seeds)))
        call note(label//'max xi err', worst_xi)
        call note(label//'max E', worst_e)
        call check(error, worst_omega, 0.0_dp, label//'frequency relative error under 1 % noise', thr=0.005_dp)
        if (allocated(error)) return
        call check(error, worst_xi, 0.0_dp, label//'damping relative error under 1 % noise', thr=0.02_dp)
    end subroutine noise_run

    ! ---- order selection -----------------------------------------------------------------

    !> Ten modes from 210 to 4400 Hz (xi 0.01..0.05) sampled to 5 kHz (dt = 0.1 ms as in the
    !> paper's section 3.2) on 2501 lines; scan with tol_e = 1e-6 up to 20 modes.
    subroutine test_order_scan(error)
        type(test_error), allocatable, intent(out) :: error

        real(dp), parameter :: frequency(10) = [210.0_dp, 530.0_dp, 870.0_dp, 1240.0_dp, 1650.0_dp, &
                                                2080.0_dp, 2600.0_dp, 3150.0_dp, 3720.0_dp, 4400.0_dp]
        real(dp), parameter :: damping(10) = [0.01_dp, 0.03_dp, 0.02_dp, 0.05_dp, 0.015_dp, &
                                              0.04_dp, 0.025_dp, 0.035_dp, 0.02_dp, 0.045_dp]
        real(dp), parameter :: weight(10) = [1.0_dp, 0.8_dp, 1.2_dp, 0.6_dp, 1.0_dp, 0.9_dp, 1.1_dp, 0.7_dp, &
            1.3_dp, 0.5_dp]
        type(modal_set) :: truth
        type(frf_type) :: frf
        type(lsce_options) :: options
        type(lsce_result) :: result
        type(error_type), allocatable :: failure
        real(dp) :: err_omega, err_xi, err_residue

        truth = modes_from_paper(weight*(two_pi*frequency)**2*1.0e-6_dp, two_pi*frequency, damping)
        frf = frf_from_modes(truth, 5000.0_dp, 2501)
        options%tol_e = 1.0e-6_dp
        options%max_modes = 20
        call identify(frf, options, result, failure)
        call check(error, .not. allocated(failure), 'identify failed')
        if (allocated(error)) return
        call note('modes', real(result%modes%n_modes(), dp))
        call note('order N', real(result%order_modes, dp))
        call note('E', result%e)
        call note('poles not stable across orders, dropped', real(result%n_not_stable, dp))
        call check(error, result%tolerance_met .and. result%modes%n_modes() == 10, 'ten modes meeting tol_e')
        if (allocated(error)) return
        call compare(error, result%modes, truth, err_omega, err_xi, err_residue)
        if (allocated(error)) return
        call note('xi err', err_xi)
        call check(error, max(err_omega, err_xi), 0.0_dp, 'omega_k and xi_k relative errors', thr=1.0e-8_dp)
    end subroutine test_order_scan

    ! ---- wrap-around ---------------------------------------------------------------------

    !> One mode at 100 Hz with xi = 0.001 (time constant 1.6 s) on grids to 500 Hz: df = 1 Hz
    !> (period 1 s, g still at 53 % at the end) must be reported; df = 0.1 Hz (period 10 s,
    !> 0.2 %) must not. Notes the xi error of the full method on the coarse grid and of the
    !> plain LSCE (no out-of-band correction, no polish) on both.
    subroutine test_wrap_around(error)
        type(test_error), allocatable, intent(out) :: error

        type(modal_set) :: truth
        type(frf_type) :: coarse, fine
        type(lsce_options) :: options
        type(lsce_result) :: result
        type(error_type), allocatable :: failure
        real(dp) :: err_omega, err_xi, err_residue

        truth = modes_from_paper([1.0e4_dp], [two_pi*100.0_dp], [0.001_dp])
        coarse = frf_from_modes(truth, f_max, 501)
        fine = frf_from_modes(truth, f_max, 5001)
        options%fixed_modes = 1
        call identify(coarse, options, result, failure)
        call check(error, .not. allocated(failure), 'identify failed on the coarse grid')
        if (allocated(error)) return
        call note('coarse tail', result%tail_level)
        call check(error, result%wrap_around .and. index(result%warning, 'wrap-around') > 0, &
                   'wrap-around not reported on the coarse grid')
        if (allocated(error)) return
        call compare(error, result%modes, truth, err_omega, err_xi, err_residue)
        if (allocated(error)) return
        call note('coarse xi err', err_xi)
        call check(error, max(err_xi, err_residue), 0.0_dp, 'xi and r despite wrap-around', thr=1.0e-8_dp)
        if (allocated(error)) return
        call identify(fine, options, result, failure)
        call check(error, .not. allocated(failure), 'identify failed on the fine grid')
        if (allocated(error)) return
        call note('fine tail', result%tail_level)
        call check(error, .not. result%wrap_around .and. len(result%warning) == 0, &
            'wrap-around reported on the fine grid')
        if (allocated(error)) return
        options%max_refinements = 0
        options%polish = .false.
        call identify(coarse, options, result, failure)
        call check(error, .not. allocated(failure), 'plain LSCE failed on the coarse grid')
        if (allocated(error)) return
        call compare(error, result%modes, truth, err_omega, err_xi, err_residue)
        if (allocated(error)) return
        call note('plain LSCE coarse xi err', err_xi)
        call identify(fine, options, result, failure)
        call check(error, .not. allocated(failure), 'plain LSCE failed on the fine grid')
        if (allocated(error)) return
        call compare(error, result%modes, truth, err_omega, err_xi, err_residue)
        if (allocated(error)) return
        call note('plain LSCE fine xi err', err_xi)
    end subroutine test_wrap_around

    ! ---- residues ------------------------------------------------------------------------

    !> Complex residues of both signs of Re r (non-proportional damping): the identified
    !> residues, G from the identified modal_set (its own `receptance`, the convention of
    !> greenconv_model_modal_set) on and between the grid lines, and g(t) from its `impulse`.
    subroutine test_residues(error)
        type(test_error), allocatable, intent(out) :: error

        type(modal_set) :: truth
        type(frf_type) :: frf
        type(lsce_options) :: options
        type(lsce_result) :: result
        type(error_type), allocatable :: failure
        real(dp) :: omega_between(n_freq - 1), t(0:2000)
        real(dp) :: err_omega, err_xi, err_residue, on_grid, between, impulse
        integer :: j

        truth = modes_from([40.0_dp, 130.0_dp, 260.0_dp], [0.03_dp, 0.02_dp, 0.05_dp], &
                           [(0.5_dp, -3.0_dp), (-1.0_dp, -2.0_dp), (3.0_dp, 4.0_dp)])
        frf = frf_from_modes(truth, f_max, n_freq)
        options%fixed_modes = 3
        call identify(frf, options, result, failure)
        call check(error, .not. allocated(failure), 'identify failed')
        if (allocated(error)) return
        call compare(error, result%modes, truth, err_omega, err_xi, err_residue)
        if (allocated(error)) return
        on_grid = maxval(abs(result%modes%receptance(two_pi*frf%frequency) - frf%receptance)) &
                  /maxval(abs(frf%receptance))
        omega_between(:) = two_pi*(frf%frequency(1:n_freq - 1) + 0.5_dp*frf%df())
        between = maxval(abs(result%modes%receptance(omega_between) - truth%receptance(omega_between))) &
                  /maxval(abs(frf%receptance))
        t(:) = [(j*1.0e-3_dp, j=0, 2000)]
        impulse = maxval(abs(result%modes%impulse(t) - truth%impulse(t)))/maxval(abs(truth%impulse(t)))
        call note('r err', err_residue)
        call note('G err on grid', on_grid)
        call note('G err between lines', between)
        call note('g(t) err', impulse)
        call check(error, err_residue, 0.0_dp, 'complex residues, relative error', thr=1.0e-8_dp)
        if (allocated(error)) return
        call check(error, max(on_grid, between, impulse), 0.0_dp, 'G and g from the identified modes', thr=1.0e-10_dp)
    end subroutine test_residues

    !> G = modes + R_u (modes above the band, 2e-6 m/N) and G = modes - R_l/omega^2
    !> (a mass-like term, R_l = 0.5 1/kg; the 0 Hz line then holds just the modes), each
    !> identified with its residual term: the term and the modes to 1e-8 relative.
    subroutine test_residual_terms(error)
        type(test_error), allocatable, intent(out) :: error

        real(dp), parameter :: upper = 2.0e-6_dp, lower = 0.5_dp
        type(modal_set) :: truth
        type(frf_type) :: frf
        type(lsce_options) :: options
        type(lsce_result) :: result
        type(error_type), allocatable :: failure
        real(dp) :: err_omega, err_xi, err_residue

        truth = modes_from_paper([4.0e3_dp, 2.0e4_dp], two_pi*[70.0_dp, 210.0_dp], [0.02_dp, 0.03_dp])
        frf = frf_from_modes(truth, f_max, n_freq)
        frf%receptance = frf%receptance + upper
        options%fixed_modes = 2
        options%upper_residual = .true.
        call identify(frf, options, result, failure)
        call check(error, .not. allocated(failure), 'identify with an upper residual failed')
        if (allocated(error)) return
        call compare(error, result%modes, truth, err_omega, err_xi, err_residue)
        if (allocated(error)) return
        call note('R_u err', abs(result%upper_residual/upper - 1.0_dp))
        call check(error, max(err_xi, err_residue, abs(result%upper_residual/upper - 1.0_dp)), 0.0_dp, &
                   'modes and R_u', thr=1.0e-8_dp)
        if (allocated(error)) return
        frf = frf_from_modes(truth, f_max, n_freq)
        frf%receptance(2:) = frf%receptance(2:) - lower/(two_pi*frf%frequency(2:))**2
        options%upper_residual = .false.
        options%lower_residual = .true.
        call identify(frf, options, result, failure)
        call check(error, .not. allocated(failure), 'identify with a lower residual failed')
        if (allocated(error)) return
        call compare(error, result%modes, truth, err_omega, err_xi, err_residue)
        if (allocated(error)) return
        call note('R_l err', abs(result%lower_residual/lower - 1.0_dp))
        call check(error, max(err_xi, err_residue, abs(result%lower_residual/lower - 1.0_dp)), 0.0_dp, &
                   'modes and R_l', thr=1.0e-8_dp)
    end subroutine test_residual_terms

    !> modes_from_paper then paper_form gives A_k, omega_k, xi_k back to round-off; the
    !> same after identification to 1e-8; a complex residue reports what the real form loses.
    subroutine test_paper_form(error)
        type(test_error), allocatable, intent(out) :: error

        real(dp), parameter :: amplitude(3) = [3.0e3_dp, 1.0e4_dp, 4.0e4_dp]
        real(dp), parameter :: omega(3) = two_pi*[35.0_dp, 120.0_dp, 330.0_dp]
        real(dp), parameter :: damping(3) = [0.04_dp, 0.002_dp, 0.15_dp]
        type(modal_set) :: modes
        type(frf_type) :: frf
        type(lsce_options) :: options
        type(lsce_result) :: result
        type(error_type), allocatable :: failure
        real(dp), allocatable :: a(:), w(:), xi(:), lost(:)
        real(dp) :: worst
        integer :: k, j

        modes = modes_from_paper(amplitude, omega, damping)
        call paper_form(modes, a, w, xi, lost)
        worst = max(maxval(abs(a/amplitude - 1.0_dp)), maxval(abs(w/omega - 1.0_dp)), maxval(abs(xi/damping - 1.0_dp)))
        call note('direct round trip', worst)
        call check(error, max(worst, maxval(lost)), 0.0_dp, 'modes_from_paper then paper_form', thr=1.0e-14_dp)
        if (allocated(error)) return
        frf = frf_from_modes(modes, f_max, n_freq)
        options%fixed_modes = 3
        call identify(frf, options, result, failure)
        call check(error, .not. allocated(failure) .and. result%modes%n_modes() == 3, 'identify failed')
        if (allocated(error)) return
        call paper_form(result%modes, a, w, xi, lost)
        worst = 0.0_dp
        do k = 1, 3
            j = minloc(abs(w - omega(k)), 1)
            worst = max(worst, abs(a(j)/amplitude(k) - 1.0_dp), abs(w(j)/omega(k) - 1.0_dp), &
                abs(xi(j)/damping(k) - 1.0_dp))
        end do
        call note('after identification', worst)
        call note('max lost', maxval(lost))
        call check(error, max(worst, maxval(lost)), 0.0_dp, 'A_k, omega_k, xi_k after identification', thr=1.0e-8_dp)
        if (allocated(error)) return
        modes = modes_from([50.0_dp], [0.02_dp], [(1.0_dp, -1.0_dp)])
        call paper_form(modes, a, w, xi, lost)
        call check(error, lost(1), 1.0_dp/sqrt(2.0_dp), 'lost part of r = 1 - i', thr=1.0e-15_dp)
        if (allocated(error)) return
        call check(error, a(1), 2.0_dp*aimag(modes%pole(1)), 'A = -2 omega_d Im r for r = 1 - i', &
            thr=1.0e-12_dp, rel=.true.)
    end subroutine test_paper_form

    ! ---- frf files -----------------------------------------------------------------------

    !> write_frf then read_frf: the grid exactly, G to the 16 digits written.
    subroutine test_frf_round_trip(error)
        type(test_error), allocatable, intent(out) :: error

        character(len=*), parameter :: path = 'test_lsce_round_trip.frf'
        type(frf_type) :: written, read_back
        type(error_type), allocatable :: failure
        real(dp) :: worst
        integer :: unit

        written = frf_from_modes(modes_from_paper([1.0e4_dp], [two_pi*80.0_dp], [0.02_dp]), 400.0_dp, 801)
        call write_frf(path, written, failure)
        call check(error, .not. allocated(failure), 'write_frf failed')
        if (allocated(error)) return
        call read_frf(path, read_back, failure)
        open (newunit=unit, file=path, status='old')
        close (unit, status='delete')
        call check(error, .not. allocated(failure), 'read_frf failed on a file from write_frf')
        if (allocated(error)) return
        worst = maxval(abs(read_back%receptance - written%receptance))/maxval(abs(written%receptance))
        call note('G err', worst)
        call check(error, worst, 0.0_dp, 'G read back', thr=1.0e-14_dp)
        if (allocated(error)) return
        call check(error, maxval(abs(read_back%frequency - written%frequency)), 0.0_dp, 'grid read back', &
            thr=1.0e-12_dp)
    end subroutine test_frf_round_trip

    !> Each bad file gives an error whose message names the file and, where there is one,
    !> the line, and says what was expected.
    subroutine test_frf_errors(error)
        type(test_error), allocatable, intent(out) :: error

        character(len=*), parameter :: path = 'test_lsce_bad.frf'
        character(len=40) :: good(8)
        integer :: j

        do j = 1, 8
            write (good(j), '(f6.1,a)') 10.0_dp*(j - 1), '  1.0e-6  -2.0e-7'
        end do
        call expect(error, path, [character(len=40) :: '# only comments', ''], &
                    path//': expected data lines f [Hz], Re G [m/N], Im G [m/N], found none')
        if (allocated(error)) return
        call expect(error, path, [character(len=40) :: '# too short', good(1:5)], &
                    'expected at least 8 data lines (a uniform grid from 0 Hz), found 5')
        if (allocated(error)) return
        call expect(error, path, [character(len=40) :: '# negative', ' -5.0 1.0 0.0', good(2:8)], &
                    path//':2: expected frequencies >= 0 Hz, found -5.0')
        if (allocated(error)) return
        call expect(error, path, [character(len=40) :: '# repeated', good(1:4), ' 30.0 1.0 0.0', good(6:8)], &
                    path//':6: expected a frequency above 30.0 Hz (increasing), found 30.0')
        if (allocated(error)) return
        call expect(error, path, [character(len=40) :: good(1:3), ' 30.0 NaN 0.0', good(5:8)], &
                    path//':4: column 2 (Re G): expected a finite number, found "NaN"')
        if (allocated(error)) return
        call expect(error, path, [character(len=40) :: good(1:3), ' 30.0 1.0 -Infinity', good(5:8)], &
                    path//':4: column 3 (Im G): expected a finite number, found "-Infinity"')
        if (allocated(error)) return
        call expect(error, path, [character(len=40) :: good(1:2), ' 20.0 1.0', good(4:8)], &
                    path//':3: expected 3 columns (f [Hz], Re G [m/N], Im G [m/N]), found 2')
        if (allocated(error)) return
        call expect(error, path, [character(len=40) :: good(1:6), ' 60.0 1.0 0.0 7.0', good(8:8)], &
                    'found 4')
        if (allocated(error)) return
        call expect(error, path, [character(len=40) :: good(1:6), ' 60.0 1.0 abc', good(8:8)], &
                    path//':7: column 3 (Im G): expected a number, found "abc"')
        if (allocated(error)) return
        call expect(error, path, [character(len=40) :: good(1:6), ' 60.0 1,0 0.0', good(8:8)], &
                    path//':7: column 2 (Re G): expected a number, found "1,0"')
        if (allocated(error)) return
        call expect(error, path, [character(len=40) :: good(1:6), ' 60.0 1e999 0.0', good(8:8)], &
                    path//':7: column 2 (Re G): expected a finite number (|x| < 1.8e308), found "1e999"')
        if (allocated(error)) return
        call expect(error, path, [character(len=40) :: good(8:1:-1)], &
                    path//':2: expected frequencies increasing from 0 Hz, found 70.0')
        if (allocated(error)) return
        call expect_missing(error, 'test_lsce_no_such_file.frf')
    end subroutine test_frf_errors

    !> Write `lines` to `path`, read it, and require an error containing `expected`.
    subroutine expect(error, path, lines, expected)
        type(test_error), allocatable, intent(out) :: error
        character(len=*), intent(in) :: path, lines(:), expected

        type(frf_type) :: frf
        type(error_type), allocatable :: failure
        integer :: unit, j

        open (newunit=unit, file=path, status='replace', action='write')
        do j = 1, size(lines)
            write (unit, '(a)') trim(lines(j))
        end do
        close (unit)
        call read_frf(path, frf, failure)
        open (newunit=unit, file=path, status='old')
        close (unit, status='delete')
        call check(error, allocated(failure), 'no error for a file expected to give "'//expected//'"')
        if (allocated(error)) return
        call check(error, index(failure%message, expected) > 0, &
                   'message "'//failure%message//'" does not contain "'//expected//'"')
    end subroutine expect

    !> A file that does not exist.
    subroutine expect_missing(error, path)
        type(test_error), allocatable, intent(out) :: error
        character(len=*), intent(in) :: path

        type(frf_type) :: frf
        type(error_type), allocatable :: failure

        call read_frf(path, frf, failure)
        call check(error, allocated(failure), 'no error for a missing file')
        if (allocated(error)) return
        call check(error, index(failure%message, path//': cannot open') == 1, &
            'message for a missing file: '//failure%message)
    end subroutine expect_missing

end module test_lsce_mod
