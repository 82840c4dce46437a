!> Maximum-likelihood identification (greenconv_ident_mlfit) against the Cramér-Rao bound.
!>
!> The bound is computed here, independently of the fit: the Jacobian of the modal model
!> with respect to (f_k [Hz], xi_k, Re r_k, Im r_k) at the TRUE parameters by central
!> differences of greenconv_model_modal_set's `receptance`, W = diag(1/sigma_l^2) with the
!> true sigma_l = level*|G_l|, Fisher F = sum_l 2*Re(J_l^H*J_l)/sigma_l^2 (the noise is complex
!> Gaussian, E|n_l|^2 = sigma_l^2, variance sigma_l^2/2 in each of Re and Im), CRB = inv(F).
!>
!> Structures: (a) 12 modes to 5 kHz on 8193 lines, a close pair 412/418 Hz, xi 0.003 to
!> 0.2, mixed signs; (b) xi = 0.001 and 0.3, modes at 8 Hz and 985 Hz of a 1 kHz band;
!> (c) 3 modes. Amplitudes A_k = sign*c_k*xi_k*omega_k^2 give peaks |G| = c_k/2 of the same order.
module test_mlfit_mod
    use, intrinsic :: iso_fortran_env, only: dp => real64
    use testsuite_mod, only: test_error, unittest_type, new_unittest, check, note
    use greenconv_core_error, only: error_type
    use greenconv_core_text, only: int_text
    use greenconv_ident_shared_poles, only: shared_fit, identify_shared
    use greenconv_ext_lapack, only: solve_linear
    use greenconv_model_modal_set, only: modal_set, modes_from_paper
    use greenconv_model_frf, only: frf_type, frf_from_modes, add_relative_noise
    use greenconv_ident_mlfit, only: ml_options, ml_result, identify_ml
    use greenconv_model_frf, only: read_frf
    use greenconv_io_uff, only: uff_function, uff_node
    use greenconv_io_uff_write, only: write_uff, receptance_function, impulse_function
    use greenconv_scene_read_input, only: scene_type
    use greenconv_ident_methods, only: ident_ml
    use greenconv_ident_structure, only: structure_model, structure_from_frf_ml
    use greenconv_conv_convolver, only: convolver
    use greenconv_conv_builder, only: make_convolver
    use greenconv_scene_models_structure, only: build_structure
    use greenconv_scene_run_report, only: write_identification, identification_summary
    use scene_text_mod, only: read_scene_text
    implicit none
    private

    public :: collect_mlfit, cramer_rao, structure, fit_draw_on, case_a

    real(dp), parameter :: pi = 3.141592653589793238462643383279_dp
    real(dp), parameter :: two_pi = 2.0_dp*pi
    !> Largest error allowed, in units of the CRB standard deviation, for every mode and draw.
    real(dp), parameter :: crb_limit = 5.0_dp
    !> Noise levels (fraction of |G| per line).
    real(dp), parameter :: levels(3) = [1.0e-3_dp, 1.0e-2_dp, 3.0e-2_dp]

contains

    !> Tests of greenconv_ident_mlfit.
    subroutine collect_mlfit(testsuite)
        type(unittest_type), allocatable, intent(out) :: testsuite(:)

        testsuite = [new_unittest('crb: (a) 12 modes, close pair, mixed signs; 0.1/1/3 % noise', test_case_a), &
                     new_unittest('crb: (b) xi 0.001 and 0.3, both band edges; 0.1/1/3 % noise', test_case_b), &
                     new_unittest('crb: (c) 3 modes; 0.1/1/3 % noise', test_case_c), &
                     new_unittest('uncertainty: reported sigma against the spread of 50 draws', test_monte_carlo), &
                     new_unittest('clean: (a) fitted to round-off with exactly 12 modes', test_clean), &
                     new_unittest('coarse grid: an under-resolved light mode is reported', test_coarse), &
                     new_unittest('coarse grid among 9 modes: the light mode is a mode, not an outlier line', &
                                  test_coarse_among), &
                     new_unittest('shared poles of a matrix whose summed driving points have an anti-resonance', test_needle), &
                     new_unittest('noise given per line: same modes, sigma scale confirmed', test_given_sigma), &
                     new_unittest('drop: spurious start poles are removed by the criterion and listed', test_drop), &
                     new_unittest('diagram: orders 1..max_order, flags, stable poles at true modes', test_diagram), &
                     new_unittest('residual terms: R_u, R_l kept when in the data, not otherwise', test_terms), &
                     new_unittest('noise: level estimated and refitted, 8193 lines, 12 modes', test_noise_level), &
                     new_unittest('scene: a noisy universal file fitted end to end, within CRB', test_scene_noisy), &
                     new_unittest('uff: receptance, mobility, accelerance give the same receptance', test_uff_kinds), &
                     new_unittest('uff: malformed or ambiguous files get one file:line message', test_uff_refused), &
                     new_unittest('outliers: one damaged line is named and left out, the modes unchanged', &
                                  test_outliers), &
                     new_unittest('order: never above max_order; a short diagram still starts the fit', &
                                  test_order_bound), &
                     new_unittest('summaries: identify and contact lines quote order, noise, uncertainty', &
                                  test_summaries)]
    end subroutine collect_mlfit

    ! ---- structures --------------------------------------------------------------------

    !> Paper modes with peaks |G| = c_k/2 [m/N]: A_k = sign_k*c_k*xi_k*omega_k^2.
    pure function structure(frequency, damping, height) result(modes)
        real(dp), intent(in) :: frequency(:), damping(:), height(:)
        type(modal_set) :: modes

        modes = modes_from_paper(height*damping*(two_pi*frequency)**2, two_pi*frequency, damping)
    end function structure

    !> (a) 12 modes to 5 kHz.
    function case_a() result(modes)
        type(modal_set) :: modes

        modes = structure([95.0_dp, 412.0_dp, 418.0_dp, 730.0_dp, 1150.0_dp, 1600.0_dp, 2100.0_dp, 2650.0_dp, &
                           3200.0_dp, 3800.0_dp, 4300.0_dp, 4750.0_dp], &
                          [0.01_dp, 0.003_dp, 0.005_dp, 0.02_dp, 0.12_dp, 0.008_dp, 0.05_dp, 0.2_dp, 0.015_dp, &
                           0.03_dp, 0.006_dp, 0.04_dp], &
                          1.0e-6_dp*[1.0_dp, -0.6_dp, 0.8_dp, 1.5_dp, -2.0_dp, 0.7_dp, 3.0_dp, -4.0_dp, 1.2_dp, &
                                     -0.9_dp, 0.5_dp, 2.0_dp])
    end function case_a

    !> (b) light and heavy damping, modes near both band edges of 1 kHz.
    function case_b() result(modes)
        type(modal_set) :: modes

        modes = structure([8.0_dp, 300.0_dp, 520.0_dp, 700.0_dp, 985.0_dp], &
                          [0.05_dp, 0.001_dp, 0.3_dp, 0.01_dp, 0.005_dp], &
                          1.0e-6_dp*[1.0_dp, 0.5_dp, -3.0_dp, 1.0_dp, -0.8_dp])
    end function case_b

    !> (c) 3 modes to 500 Hz.
    function case_c() result(modes)
        type(modal_set) :: modes

        modes = structure([60.0_dp, 180.0_dp, 320.0_dp], [0.02_dp, 0.01_dp, 0.04_dp], &
                          1.0e-6_dp*[1.0_dp, -0.7_dp, 1.5_dp])
    end function case_c

    ! ---- helpers -----------------------------------------------------------------------

    !> Receptance of modes given as (f [Hz], xi, Re r, Im r) per mode, at omega [rad/s].
    pure function model_of(theta, omega) result(g)
        real(dp), intent(in) :: theta(:), omega(:)
        complex(dp) :: g(size(omega))

        type(modal_set) :: modes
        integer :: k, n

        n = size(theta)/4
        allocate (modes%pole(n), modes%residue(n))
        do k = 1, n
            modes%pole(k) = two_pi*theta(4*k - 3)*cmplx(-theta(4*k - 2), sqrt(1.0_dp - theta(4*k - 2)**2), dp)
            modes%residue(k) = cmplx(theta(4*k - 1), theta(4*k), dp)
        end do
        g = modes%receptance(omega)
    end function model_of

    !> Cramér-Rao standard deviations of f [Hz] and xi of each true mode for noise level*|G|
    !> (and a floor: sigma^2 = (level*|G|)^2 + floor^2 [m/N], when given). A `background` [m/N]
    !> per line (terms of the data outside `truth`, known: rigid-body motion, modes above the
    !> band) is added to the model whose |G| sets the noise.
    subroutine cramer_rao(truth, frf, level, sigma_f, sigma_xi, error, floor, background)
        type(modal_set), intent(in) :: truth
        type(frf_type), intent(in) :: frf
        real(dp), intent(in) :: level
        real(dp), allocatable, intent(out) :: sigma_f(:), sigma_xi(:)
        type(test_error), allocatable, intent(out) :: error
        real(dp), intent(in), optional :: floor
        complex(dp), intent(in), optional :: background(:)

        real(dp), allocatable :: theta(:), omega(:), fisher(:, :), x(:), e(:), w(:), scale(:)
        complex(dp), allocatable :: jac(:, :), g(:)
        type(error_type), allocatable :: failure
        real(dp) :: h
        integer :: n, p, i, j, k

        n = truth%n_modes()
        p = 4*n
        allocate (theta(p), jac(frf%n_freq(), p), fisher(p, p), x(p), e(p), sigma_f(n), sigma_xi(n))
        do k = 1, n
            theta(4*k - 3) = abs(truth%pole(k))/two_pi
            theta(4*k - 2) = -real(truth%pole(k), dp)/abs(truth%pole(k))
            theta(4*k - 1) = real(truth%residue(k), dp)
            theta(4*k) = aimag(truth%residue(k))
        end do
        omega = two_pi*frf%frequency
        do i = 1, p
            h = 1.0e-6_dp*max(abs(theta(i)), abs(truth%residue((i + 3)/4)))
            if (mod(i, 4) == 1 .or. mod(i, 4) == 2) h = 1.0e-6_dp*abs(theta(i))
            e = 0.0_dp
            e(i) = h
            jac(:, i) = (model_of(theta + e, omega) - model_of(theta - e, omega))/(2.0_dp*h)
        end do
        g = model_of(theta, omega)
        if (present(background)) g = g + background
        w = 2.0_dp/(level*abs(g))**2
        if (present(floor)) w = 2.0_dp/((level*abs(g))**2 + floor**2)
        do j = 1, p
            do i = 1, p
                fisher(i, j) = sum(w*real(conjg(jac(:, i))*jac(:, j), dp))
            end do
        end do
        scale = [(sqrt(fisher(i, i)), i=1, p)]
        fisher = fisher/spread(scale, 1, p)/spread(scale, 2, p)
        do k = 1, n
            do i = 1, 2
                j = 4*(k - 1) + i
                e = 0.0_dp
                e(j) = 1.0_dp
                call solve_linear(fisher, e, x, failure)
                call check(error, .not. allocated(failure), 'CRB: singular Fisher information')
                if (allocated(error)) return
                if (i == 1) sigma_f(k) = sqrt(x(j))/scale(j)
                if (i == 2) sigma_xi(k) = sqrt(x(j))/scale(j)
            end do
        end do
    end subroutine cramer_rao

    !> Fit one noisy draw and measure the worst error of f and xi in CRB units; fails when a
    !> mode is missed or invented (numbers differ or two true modes share a found one).
    subroutine fit_draw(truth, f_max, n_freq, level, seed, worst_f, worst_xi, error, result)
        type(modal_set), intent(in) :: truth
        real(dp), intent(in) :: f_max, level
        integer, intent(in) :: n_freq, seed
        real(dp), intent(out) :: worst_f, worst_xi
        type(test_error), allocatable, intent(out) :: error
        type(ml_result), intent(out), optional :: result

        call fit_draw_on(truth, frf_from_modes(truth, f_max, n_freq), level, seed, worst_f, worst_xi, error, result)
    end subroutine fit_draw

    !> `fit_draw` on a clean receptance of `truth` given on any grid: noise level*|G| added
    !> (seed), fitted, and the CRB computed on the same lines.
    subroutine fit_draw_on(truth, clean, level, seed, worst_f, worst_xi, error, result)
        type(modal_set), intent(in) :: truth
        type(frf_type), intent(in) :: clean
        real(dp), intent(in) :: level
        integer, intent(in) :: seed
        real(dp), intent(out) :: worst_f, worst_xi
        type(test_error), allocatable, intent(out) :: error
        type(ml_result), intent(out), optional :: result

        type(frf_type) :: noisy
        type(ml_options) :: options
        type(ml_result) :: fitted
        real(dp), allocatable :: sigma_f(:), sigma_xi(:)
        integer, allocatable :: match(:)
        character(len=200) :: text
        integer :: k

        worst_f = huge(1.0_dp)
        worst_xi = huge(1.0_dp)
        noisy = clean
        call add_relative_noise(noisy, level, seed)
        call fit_ok(noisy, options, fitted, error)
        if (allocated(error)) return
        write (text, '(a,es8.1,a,i0,a,i0,a,i0)') 'noise ', level, ', seed ', seed, ': found ', &
            fitted%modes%n_modes(), ' modes, expected ', truth%n_modes()
        call check(error, fitted%modes%n_modes() == truth%n_modes(), trim(text))
        if (allocated(error)) return
        call check(error, size(fitted%outlier_line) == 0, trim(text)//': a line of Gaussian noise taken for an outlier')
        if (allocated(error)) return
        allocate (match(truth%n_modes()))
        do k = 1, truth%n_modes()
            match(k) = minloc(abs(fitted%modes%pole - truth%pole(k)), 1)
        end do
        do k = 1, truth%n_modes()
            call check(error, count(match == match(k)) == 1, trim(text)//': two true modes share one found mode')
            if (allocated(error)) return
        end do
        call cramer_rao(truth, clean, level, sigma_f, sigma_xi, error)
        if (allocated(error)) return
        worst_f = 0.0_dp
        worst_xi = 0.0_dp
        do k = 1, truth%n_modes()
            associate (found => fitted%modes%pole(match(k)), pole => truth%pole(k))
                worst_f = max(worst_f, abs(abs(found) - abs(pole))/two_pi/sigma_f(k))
                worst_xi = max(worst_xi, abs(real(found, dp)/abs(found) - real(pole, dp)/abs(pole))/sigma_xi(k))
            end associate
        end do
        if (present(result)) result = fitted
    end subroutine fit_draw_on

    !> Every noise level with `seeds` draws: no mode missed or invented, every error within
    !> crb_limit CRB standard deviations; the worst per level is noted.
    subroutine check_case(error, truth, f_max, n_freq, seeds)
        type(test_error), allocatable, intent(out) :: error
        type(modal_set), intent(in) :: truth
        real(dp), intent(in) :: f_max
        integer, intent(in) :: n_freq, seeds

        real(dp) :: worst_f, worst_xi, level_f, level_xi
        character(len=24) :: label
        integer :: i, seed

        do i = 1, size(levels)
            level_f = 0.0_dp
            level_xi = 0.0_dp
            do seed = 1, seeds
                call fit_draw(truth, f_max, n_freq, levels(i), 1000*i + seed, worst_f, worst_xi, error)
                if (allocated(error)) return
                level_f = max(level_f, worst_f)
                level_xi = max(level_xi, worst_xi)
            end do
            write (label, '(f4.1,a)') 100.0_dp*levels(i), ' %'
            call note('f/crb '//trim(adjustl(label)), level_f)
            call note('xi/crb '//trim(adjustl(label)), level_xi)
            call check(error, level_f, 0.0_dp, 'worst |f - f_true|/sigma_CRB at '//trim(adjustl(label)), thr=crb_limit)
            if (allocated(error)) return
            call check(error, level_xi, 0.0_dp, 'worst |xi - xi_true|/sigma_CRB at '//trim(adjustl(label)), &
                       thr=crb_limit)
            if (allocated(error)) return
        end do
    end subroutine check_case

    !> identify_ml, failing the test when it returns an error (its message is passed on), when
    !> a mode has no finite uncertainty or when the model has more modes than max_order.
    subroutine fit_ok(frf, options, result, error)
        type(frf_type), intent(in) :: frf
        type(ml_options), intent(in) :: options
        type(ml_result), intent(out) :: result
        type(test_error), allocatable, intent(out) :: error

        type(error_type), allocatable :: failure

        call identify_ml(frf, options, result, failure)
        if (allocated(failure)) call check(error, .false., 'identify_ml failed: '//failure%message)
        if (allocated(error)) return
        call check(error, all(result%sigma_frequency < huge(1.0_dp) .and. result%sigma_damping < huge(1.0_dp) &
                              .and. result%sigma_residue < huge(1.0_dp)), 'every mode has a finite uncertainty')
        if (allocated(error)) return
        call check(error, result%modes%n_modes() <= options%max_order, 'no more modes than max_order')
    end subroutine fit_ok

    ! ---- tests -------------------------------------------------------------------------

    subroutine test_case_a(error)
        type(test_error), allocatable, intent(out) :: error

        call check_case(error, case_a(), 5000.0_dp, 8193, 2)
    end subroutine test_case_a

    subroutine test_case_b(error)
        type(test_error), allocatable, intent(out) :: error

        call check_case(error, case_b(), 1000.0_dp, 4097, 3)
    end subroutine test_case_b

    subroutine test_case_c(error)
        type(test_error), allocatable, intent(out) :: error

        call check_case(error, case_c(), 500.0_dp, 2049, 3)
    end subroutine test_case_c

    !> Case (c) at 1 % noise, 50 draws: for every mode the standard deviation of f_hat and of
    !> xi_hat over the draws agrees with the mean reported sigma within +-30 % (the spread of
    !> a standard deviation from 50 draws is about 10 %); the ratio to the CRB is noted.
    subroutine test_monte_carlo(error)
        type(test_error), allocatable, intent(out) :: error

        integer, parameter :: draws = 50
        type(modal_set) :: truth
        type(ml_result) :: result
        real(dp) :: f(draws, 3), xi(draws, 3), sf(draws, 3), sx(draws, 3), worst_f, worst_xi, ratio
        real(dp) :: worst_ratio, best_ratio
        integer :: d, k, j

        truth = case_c()
        do d = 1, draws
            call fit_draw(truth, 500.0_dp, 2049, 1.0e-2_dp, 7000 + d, worst_f, worst_xi, error, result)
            if (allocated(error)) return
            do k = 1, 3
                j = minloc(abs(result%modes%pole - truth%pole(k)), 1)
                f(d, k) = abs(result%modes%pole(j))/two_pi
                xi(d, k) = -real(result%modes%pole(j), dp)/abs(result%modes%pole(j))
                sf(d, k) = result%sigma_frequency(j)
                sx(d, k) = result%sigma_damping(j)
            end do
        end do
        worst_ratio = 0.0_dp
        best_ratio = huge(1.0_dp)
        do k = 1, 3
            ratio = spread_of(f(:, k))/(sum(sf(:, k))/draws)
            worst_ratio = max(worst_ratio, ratio)
            best_ratio = min(best_ratio, ratio)
            ratio = spread_of(xi(:, k))/(sum(sx(:, k))/draws)
            worst_ratio = max(worst_ratio, ratio)
            best_ratio = min(best_ratio, ratio)
        end do
        call note('max std/sigma', worst_ratio)
        call note('min std/sigma', best_ratio)
        call check(error, worst_ratio, 1.0_dp, 'largest spread/reported sigma', thr=0.3_dp)
        if (allocated(error)) return
        call check(error, best_ratio, 1.0_dp, 'smallest spread/reported sigma', thr=0.3_dp)
    contains
        pure real(dp) function spread_of(x)
            real(dp), intent(in) :: x(:)

            spread_of = sqrt(sum((x - sum(x)/size(x))**2)/(size(x) - 1))
        end function spread_of
    end subroutine test_monte_carlo

    !> Case (a) without noise: exactly 12 modes, f and xi to 1e-9 relative, residual below
    !> 1e-10 of max |G| on every line.
    subroutine test_clean(error)
        type(test_error), allocatable, intent(out) :: error

        type(modal_set) :: truth
        type(frf_type) :: frf
        type(ml_options) :: options
        type(ml_result) :: result
        real(dp) :: err_f, err_xi, misfit
        integer :: k, j

        truth = case_a()
        frf = frf_from_modes(truth, 5000.0_dp, 8193)
        call fit_ok(frf, options, result, error)
        if (allocated(error)) return
        call check(error, result%modes%n_modes() == 12, 'expected 12 modes on clean data')
        if (allocated(error)) return
        err_f = 0.0_dp
        err_xi = 0.0_dp
        do k = 1, 12
            j = minloc(abs(result%modes%pole - truth%pole(k)), 1)
            err_f = max(err_f, abs(abs(result%modes%pole(j))/abs(truth%pole(k)) - 1.0_dp))
            err_xi = max(err_xi, abs(real(result%modes%pole(j), dp)/abs(result%modes%pole(j)) &
                                     /(real(truth%pole(k), dp)/abs(truth%pole(k))) - 1.0_dp))
        end do
        misfit = maxval(abs(frf%receptance(2:) - result%receptance(two_pi*frf%frequency(2:)))) &
                 /maxval(abs(frf%receptance))
        call note('f err', err_f)
        call note('xi err', err_xi)
        call note('misfit', misfit)
        call check(error, err_f, 0.0_dp, 'relative error of f', thr=1.0e-9_dp)
        if (allocated(error)) return
        call check(error, err_xi, 0.0_dp, 'relative error of xi', thr=1.0e-9_dp)
        if (allocated(error)) return
        call check(error, misfit, 0.0_dp, 'max |G - G_model|/max |G|', thr=1.0e-10_dp)
    end subroutine test_clean

    !> 100 Hz with xi = 0.001 (half-power band 0.2 Hz) on a 1 Hz grid, beside 300 Hz with xi =
    !> 0.02, 0.1 % noise: both found, and the light one named as under-resolved.
    subroutine test_coarse(error)
        type(test_error), allocatable, intent(out) :: error

        type(frf_type) :: frf
        type(ml_options) :: options
        type(ml_result) :: result

        frf = frf_from_modes(structure([100.0_dp, 300.0_dp], [0.001_dp, 0.02_dp], 1.0e-6_dp*[1.0_dp, 1.0_dp]), &
                             500.0_dp, 501)
        call add_relative_noise(frf, 1.0e-3_dp, 11)
        call fit_ok(frf, options, result, error)
        if (allocated(error)) return
        call check(error, result%modes%n_modes() == 2, 'expected 2 modes')
        if (allocated(error)) return
        call check(error, index(result%warning, 'under-resolved mode at 100') > 0, &
                   'expected a warning naming the under-resolved mode at 100 Hz, got: '//result%warning)
        if (allocated(error)) return
        call check(error, index(result%warning, 'under-resolved mode at 300') == 0, &
                   'the resolved mode at 300 Hz must not be reported: '//result%warning)
    end subroutine test_coarse

    !> (d) 9 modes to 4 kHz on a 1 Hz grid, one of them light (xi = 0.001 at 180 Hz, its
    !> half-power band 0.36 Hz: one line carries its peak) with a small modal constant beside a
    !> stronger mode at 240 Hz: at 0.1 % and 1 % noise, 3 draws each, all 9 modes found within
    !> crb_limit Cramér-Rao sigma, the light mode reported as under-resolved and its peak line
    !> never left out as an outlier (a single line standing out is what a damaged line looks
    !> like too; the mode, which also lifts the lines beside it, is preferred).
    subroutine test_coarse_among(error)
        type(test_error), allocatable, intent(out) :: error

        type(modal_set) :: truth
        type(ml_result) :: result
        real(dp), parameter :: coarse_levels(2) = [1.0e-3_dp, 1.0e-2_dp]
        real(dp) :: worst_f, worst_xi, level_f, level_xi
        integer :: i, seed

        truth = structure([35.0_dp, 180.0_dp, 240.0_dp, 870.0_dp, 905.0_dp, 1450.0_dp, 2600.0_dp, 3100.0_dp, &
                           3850.0_dp], &
                          [0.05_dp, 0.001_dp, 0.015_dp, 0.008_dp, 0.012_dp, 0.2_dp, 0.004_dp, 0.02_dp, 0.03_dp], &
                          1.0e-6_dp*[-1.0_dp, 0.3_dp, 2.0_dp, 1.0_dp, -0.8_dp, 4.0_dp, 0.5_dp, -1.2_dp, 2.2_dp])
        level_f = 0.0_dp
        level_xi = 0.0_dp
        do i = 1, 2
            do seed = 1, 3
                call fit_draw(truth, 4096.0_dp, 4097, coarse_levels(i), 500*i + seed, worst_f, worst_xi, &
                              error, result)
                if (allocated(error)) return
                level_f = max(level_f, worst_f)
                level_xi = max(level_xi, worst_xi)
                call check(error, size(result%outlier_line) == 0, 'no line left out as an outlier, draw ' &
                           //int_text(500*i + seed)//': '//result%warning)
                if (allocated(error)) return
                call check(error, index(result%warning, 'under-resolved mode at 1') > 0, &
                           'expected the light mode near 180 Hz reported as under-resolved, got: '//result%warning)
                if (allocated(error)) return
            end do
        end do
        call note('f/crb', level_f)
        call note('xi/crb', level_xi)
        call check(error, level_f, 0.0_dp, 'worst |f - f_true|/sigma_CRB', thr=crb_limit)
        if (allocated(error)) return
        call check(error, level_xi, 0.0_dp, 'worst |xi - xi_true|/sigma_CRB', thr=crb_limit)
    end subroutine test_coarse_among

    !> The Green's matrix of three points on a chain of five masses (modes at 62, 125, 192, 256
    !> and 302 Hz; the middle point is a node of the 2nd and 4th), 0 to 1 kHz by 1 Hz, each G_ij
    !> with its own 0.1, 1 or 2 % relative noise, identified with shared poles
    !> (greenconv_ident_shared_poles). The sum of the driving points has an anti-resonance near
    !> 217 Hz where its |G| is far below the noise of its terms: with the noise taken relative
    !> to the sum alone, 2 to 6 spurious poles settled there (one at the narrowest band, sigma_xi/xi
    !> about 150). Exactly the 5 poles, each within 1e-3 of its frequency, at every level.
    subroutine test_needle(error)
        type(test_error), allocatable, intent(out) :: error

        real(dp), parameter :: f(5) = [62.260393380595175_dp, 125.33935316204327_dp, 192.01937151189844_dp, &
                                       255.63058006191443_dp, 301.6119081125747_dp]
        real(dp), parameter :: xi(5) = [0.02_dp, 0.015_dp, 0.03_dp, 0.01_dp, 0.025_dp]
        real(dp), parameter :: shape(3, 5) = reshape([0.73463958085222403_dp, 0.79550890919739792_dp, &
            0.73463958085222403_dp, -0.60814868121215659_dp, 0.0_dp, 0.60814868121215715_dp, &
            -0.25005184625600457_dp, -0.91867678272220299_dp, -0.25005184625600418_dp, &
            -0.93816586035727956_dp, 0.0_dp, 0.93816586035727922_dp, -0.80484704163538556_dp, &
            1.0115327697483403_dp, -0.80484704163538623_dp], [3, 5])
        real(dp), parameter :: needle_levels(3) = [1.0e-3_dp, 1.0e-2_dp, 2.0e-2_dp]
        type(frf_type) :: one
        type(ml_options) :: options
        type(shared_fit) :: fit
        type(error_type), allocatable :: failure
        complex(dp), allocatable :: g(:, :, :)
        real(dp) :: worst
        integer :: i, j, n, k

        worst = 0.0_dp
        do n = 1, size(needle_levels)
            allocate (g(3, 3, 1001))
            do i = 1, 3
                do j = 1, 3
                    one = frf_from_modes(modes_from_paper(shape(i, :)*shape(j, :), two_pi*f, xi), 1000.0_dp, 1001)
                    call add_relative_noise(one, needle_levels(n), 100*n + 10*i + j)
                    g(i, j, :) = one%receptance
                end do
            end do
            call identify_shared(one%frequency, g, .true., options, fit, failure)
            deallocate (g)
            call check(error, .not. allocated(failure), 'identify_shared failed: '//message_of(failure))
            if (allocated(error)) return
            call check(error, size(fit%pole) == 5, 'expected the 5 poles at noise level ' &
                       //int_text(nint(1.0e3_dp*needle_levels(n)))//' per mille, found ' &
                       //int_text(size(fit%pole))//': '//fit%pole_fit%warning)
            if (allocated(error)) return
            do k = 1, 5
                worst = max(worst, abs(abs(fit%pole(k))/two_pi - f(k))/f(k))
            end do
        end do
        call note('worst relative frequency error', worst)
        call check(error, worst <= 1.0e-3_dp, 'a pole more than 1e-3 off its frequency')
    end subroutine test_needle

    !> The message of an error, '' when none.
    function message_of(failure) result(text)
        type(error_type), allocatable, intent(in) :: failure
        character(len=:), allocatable :: text

        text = ''
        if (allocated(failure)) text = failure%message
    end function message_of

    !> Case (a) at 1 % noise with the default max_order = 30: the chosen order and the noise
    !> estimate (the CPU time of such a fit is measured by `make bench`, bench_ident_mod).
    subroutine test_noise_level(error)
        type(test_error), allocatable, intent(out) :: error

        type(frf_type) :: frf
        type(ml_options) :: options
        type(ml_result) :: result

        frf = frf_from_modes(case_a(), 5000.0_dp, 8193)
        call add_relative_noise(frf, 1.0e-2_dp, 5)
        call fit_ok(frf, options, result, error)
        if (allocated(error)) return
        call note('modes', real(result%modes%n_modes(), dp))
        call note('noise', result%noise_level)
        call note('noise fit', result%noise_level_fit)
        call note('LM iterations', real(result%iterations, dp))
        call check(error, result%modes%n_modes() == 12, 'expected 12 modes')
        if (allocated(error)) return
        ! The smoothness estimate (bias stated in the module) within 10 %, the refit within 3 %
        ! (its own spread is about 1/sqrt(2L) = 0.8 %).
        call check(error, result%noise_level, 1.0e-2_dp, 'noise level estimated from the data', thr=0.1_dp, rel=.true.)
        if (allocated(error)) return
        call check(error, result%noise_level_fit, 1.0e-2_dp, 'noise level from the final residual', thr=0.03_dp, &
                   rel=.true.)
    end subroutine test_noise_level

    !> Case (c) at 1 % noise with the true sigma_l = 0.01*|G_l| given: 3 modes within the CRB
    !> limit, the residual asks a factor within 5 % of 1 on the given sigma, and the chi2 test
    !> says the residual is explained.
    subroutine test_given_sigma(error)
        type(test_error), allocatable, intent(out) :: error

        type(modal_set) :: truth
        type(frf_type) :: frf
        type(ml_options) :: options
        type(ml_result) :: result
        real(dp), allocatable :: sigma_f(:), sigma_xi(:)
        real(dp) :: worst
        integer :: k, j

        truth = case_c()
        frf = frf_from_modes(truth, 500.0_dp, 2049)
        options%sigma = 1.0e-2_dp*abs(frf%receptance)
        call cramer_rao(truth, frf, 1.0e-2_dp, sigma_f, sigma_xi, error)
        if (allocated(error)) return
        call add_relative_noise(frf, 1.0e-2_dp, 42)
        call fit_ok(frf, options, result, error)
        if (allocated(error)) return
        call check(error, result%modes%n_modes() == 3 .and. .not. result%noise_estimated, &
                   'expected 3 modes and the noise not estimated')
        if (allocated(error)) return
        worst = 0.0_dp
        do k = 1, 3
            j = minloc(abs(result%modes%pole - truth%pole(k)), 1)
            worst = max(worst, abs(abs(result%modes%pole(j)) - abs(truth%pole(k)))/two_pi/sigma_f(k))
        end do
        call note('f/crb', worst)
        call note('sigma factor', result%noise_level_fit)
        call check(error, worst, 0.0_dp, 'worst |f - f_true|/sigma_CRB', thr=crb_limit)
        if (allocated(error)) return
        call check(error, result%noise_level_fit, 1.0_dp, 'factor on the given sigma', thr=0.05_dp)
        if (allocated(error)) return
        call check(error, result%explained, 'chi2 test: residual explained by the given noise')
    end subroutine test_given_sigma

    !> Case (c) at 1 % noise with stable_orders = 1: every pole of the highest order that is
    !> stable once starts the fit (noise poles among them); the result still has the 3 true
    !> modes, and the removed ones are listed with their reason.
    subroutine test_drop(error)
        type(test_error), allocatable, intent(out) :: error

        type(frf_type) :: frf
        type(ml_options) :: options
        type(ml_result) :: result

        frf = frf_from_modes(case_c(), 500.0_dp, 2049)
        call add_relative_noise(frf, 1.0e-2_dp, 43)
        options%stable_orders = 1
        call fit_ok(frf, options, result, error)
        if (allocated(error)) return
        call note('start poles', real(result%n_start, dp))
        call note('dropped', real(size(result%dropped_pole), dp))
        call check(error, result%n_start > 3, 'expected noise poles among the start poles with stable_orders = 1')
        if (allocated(error)) return
        call check(error, result%modes%n_modes() == 3, 'expected the 3 true modes')
        if (allocated(error)) return
        call check(error, size(result%dropped_pole) >= result%n_start - 3 .and. size(result%dropped_reason) &
                   == size(result%dropped_pole), 'expected every start pole not kept to be listed as dropped')
    end subroutine test_drop

    !> Case (c) at 0.1 % noise: the diagram holds the orders 1..30 (the default max_order), flags
    !> in 0..2, and at the highest order a pole stable in f and xi within 1 % of each true mode.
    subroutine test_diagram(error)
        type(test_error), allocatable, intent(out) :: error

        type(modal_set) :: truth
        type(frf_type) :: frf
        type(ml_options) :: options
        type(ml_result) :: result
        logical :: top(0:0)
        integer :: k
        real(dp) :: f

        truth = case_c()
        frf = frf_from_modes(truth, 500.0_dp, 2049)
        call add_relative_noise(frf, 1.0e-3_dp, 44)
        call fit_ok(frf, options, result, error)
        if (allocated(error)) return
        call check(error, minval(result%diagram_order) >= 1 .and. maxval(result%diagram_order) == 30 .and. &
                   all(result%diagram_flag >= 0 .and. result%diagram_flag <= 2) .and. &
                   size(result%unstable_by_order) == 30, 'diagram orders 1..30, flags 0..2')
        if (allocated(error)) return
        do k = 1, 3
            f = abs(truth%pole(k))/two_pi
            top(0) = any(result%diagram_order == 30 .and. result%diagram_flag == 2 .and. &
                         abs(result%diagram_frequency - f) < 0.01_dp*f)
            call check(error, top(0), 'no stable pole at the highest order near '//trim(text_of(f))//' Hz')
            if (allocated(error)) return
        end do
    contains
        function text_of(x) result(text)
            real(dp), intent(in) :: x
            character(len=16) :: text

            write (text, '(f8.1)') x
        end function text_of
    end subroutine test_diagram

    !> Case (c) at 0.1 % noise on 2049 lines to 500 Hz: with a constant R_u = 2e-9 m/N added
    !> (the static flexibility of modes far above the band) R_u is kept, within 1 %; with a
    !> mass-like term -R_l/omega^2, R_l = 0.04 1/kg (1e-7 m/N at 100 Hz, of the order of the
    !> modes there), R_l is kept, within 1 %; the plain case keeps neither. Each time the 3 modes.
    subroutine test_terms(error)
        type(test_error), allocatable, intent(out) :: error

        type(frf_type) :: plain, frf
        type(ml_options) :: options
        type(ml_result) :: result

        plain = frf_from_modes(case_c(), 500.0_dp, 2049)
        frf = plain
        call add_relative_noise(frf, 1.0e-3_dp, 61)
        call fit_ok(frf, options, result, error)
        if (allocated(error)) return
        call check(error, result%modes%n_modes() == 3 .and. .not. (result%has_upper .or. result%has_lower), &
                   'plain case: 3 modes and no residual term')
        if (allocated(error)) return
        frf = plain
        frf%receptance = frf%receptance + 2.0e-9_dp
        call add_relative_noise(frf, 1.0e-3_dp, 64)
        call fit_ok(frf, options, result, error)
        if (allocated(error)) return
        call note('R_u', result%upper_residual)
        call check(error, result%modes%n_modes() == 3 .and. result%has_upper .and. .not. result%has_lower, &
                   'constant added: 3 modes and R_u alone kept')
        if (allocated(error)) return
        call check(error, result%upper_residual, 2.0e-9_dp, 'R_u', thr=0.01_dp, rel=.true.)
        if (allocated(error)) return
        frf = plain
        frf%receptance(2:) = frf%receptance(2:) - 4.0e-2_dp/(two_pi*frf%frequency(2:))**2
        call add_relative_noise(frf, 1.0e-3_dp, 63)
        call fit_ok(frf, options, result, error)
        if (allocated(error)) return
        call note('R_l', result%lower_residual)
        call check(error, result%modes%n_modes() == 3 .and. result%has_lower .and. .not. result%has_upper, &
                   'mass-like term added: 3 modes and R_l alone kept')
        if (allocated(error)) return
        call check(error, result%lower_residual, 4.0e-2_dp, 'R_l', thr=0.01_dp, rel=.true.)
    end subroutine test_terms

    !> The fuzz test's damages, one line each, in structure (c) (2049 lines) clean and at 1 %
    !> noise: a value 1e16 times too large between two modes, the imaginary part negated at the
    !> 180 Hz peak, a zero line, a value 1e300 (beyond what sums of squares hold). Each time the
    !> damaged line and no other is named an outlier; clean: the 3 modes to 1e-9 and E <= 1e-12;
    !> 1 %: the 3 modes within crb_limit CRB sigma of the truth. The LM iterations of the
    !> damaged fits are noted beside the intact one's.
    subroutine test_outliers(error)
        type(test_error), allocatable, intent(out) :: error

        integer, parameter :: n_damages = 4
        type(modal_set) :: truth
        type(frf_type) :: clean, damaged
        type(ml_options) :: options
        type(ml_result) :: result
        real(dp), allocatable :: sigma_f(:), sigma_xi(:)
        real(dp) :: level, worst_f, worst_xi, worst_clean
        integer :: damage, line, k, j, noisy, most
        character(len=80) :: label

        truth = case_c()
        worst_f = 0.0_dp
        worst_xi = 0.0_dp
        worst_clean = 0.0_dp
        most = 0
        do noisy = 0, 1
            level = 1.0e-2_dp*noisy
            clean = frf_from_modes(truth, 500.0_dp, 2049)
            if (noisy == 1) then
                call cramer_rao(truth, clean, level, sigma_f, sigma_xi, error)
                if (allocated(error)) return
                call add_relative_noise(clean, level, 404)
                call fit_ok(clean, options, result, error)
                if (allocated(error)) return
                call note('intact, 1 %: LM iterations', real(result%iterations, dp))
            end if
            do damage = 1, n_damages
                damaged = clean
                select case (damage)
                case (1)
                    line = 1025
                    damaged%receptance(line) = 1.0e16_dp*damaged%receptance(line)
                case (2)
                    line = nint(180.0_dp/500.0_dp*2048) + 1
                    damaged%receptance(line) = conjg(damaged%receptance(line))
                case (3)
                    line = 1639
                    damaged%receptance(line) = (0.0_dp, 0.0_dp)
                case default
                    line = 411
                    damaged%receptance(line) = (1.0e300_dp, 0.0_dp)
                end select
                write (label, '(a,i0,a,i0,a,f4.1,a)') 'damage ', damage, ' at line ', line, ', noise ', 100*level, ' %'
                call fit_ok(damaged, options, result, error)
                if (allocated(error)) return
                most = max(most, result%iterations)
                call check(error, size(result%outlier_line) == 1, trim(label)//': expected one outlier line')
                if (allocated(error)) return
                call check(error, result%outlier_line(1) == line .and. result%modes%n_modes() == 3, &
                           trim(label)//': expected the damaged line left out and 3 modes; warning: '//result%warning)
                if (allocated(error)) return
                do k = 1, 3
                    j = minloc(abs(result%modes%pole - truth%pole(k)), 1)
                    associate (found => result%modes%pole(j), pole => truth%pole(k))
                        if (noisy == 1) then
                            worst_f = max(worst_f, abs(abs(found) - abs(pole))/two_pi/sigma_f(k))
                            worst_xi = max(worst_xi, abs(real(found, dp)/abs(found) - real(pole, dp)/abs(pole)) &
                                       /sigma_xi(k))
                        else
                            worst_clean = max(worst_clean, abs(found - pole)/abs(pole))
                        end if
                    end associate
                end do
                if (noisy == 0) then
                    call check(error, result%e, 0.0_dp, trim(label)//': E of the clean fit', thr=1.0e-12_dp)
                    if (allocated(error)) return
                end if
            end do
        end do
        call note('clean: worst |pole error|/|pole|', worst_clean)
        call note('1 %: worst |f error|/CRB sigma', worst_f)
        call note('1 %: worst |xi error|/CRB sigma', worst_xi)
        call note('damaged fits: most LM iterations', real(most, dp))
        call check(error, worst_clean, 0.0_dp, 'clean: relative pole error', thr=1.0e-9_dp)
        if (allocated(error)) return
        call check(error, worst_f <= crb_limit .and. worst_xi <= crb_limit, '1 %: within the CRB limit')
    end subroutine test_outliers

    !> The order search never goes above max_order: structure (a) (12 modes) at 1 % noise with
    !> max_order = 6 gets at most 6 modes and a residual said not to be explained by the noise.
    !> data/sample_receptance.frf (4 clean modes, 2001 lines) with max_order = 4 to 8, too
    !> few orders for a pole to be stable over 3 of them (its modes settle at N = 8): the poles
    !> of the highest order start the fit, and the 4 modes come back to round-off (E <= 1e-12);
    !> with max_order = 8 and one line negated (the fuzz test's case), the same with that line
    !> left out.
    subroutine test_order_bound(error)
        type(test_error), allocatable, intent(out) :: error

        type(frf_type) :: frf, damaged
        type(ml_options) :: options
        type(ml_result) :: result
        type(error_type), allocatable :: failure
        integer :: order
        character(len=60) :: label

        frf = frf_from_modes(case_a(), 5000.0_dp, 8193)
        call add_relative_noise(frf, 1.0e-2_dp, 66)
        options%max_order = 6
        call fit_ok(frf, options, result, error)
        if (allocated(error)) return
        call note('max_order 6: modes', real(result%modes%n_modes(), dp))
        call check(error, result%modes%n_modes() <= 6 .and. .not. result%explained, &
                   'max_order = 6: at most 6 modes and the residual not explained')
        if (allocated(error)) return
        call read_frf('data/sample_receptance.frf', frf, failure)
        if (allocated(failure)) call check(error, .false., failure%message)
        if (allocated(error)) return
        do order = 4, 8
            options%max_order = order
            write (label, '(a,i0)') 'data/sample_receptance.frf, max_order = ', order
            call fit_ok(frf, options, result, error)
            if (allocated(error)) return
            call check(error, result%modes%n_modes() == 4, trim(label)//': expected 4 modes')
            if (allocated(error)) return
            call check(error, result%e, 0.0_dp, trim(label)//': E', thr=1.0e-12_dp)
            if (allocated(error)) return
        end do
        damaged = frf
        damaged%receptance(901) = cmplx(-real(damaged%receptance(901), dp), aimag(damaged%receptance(901)), dp)
        call fit_ok(damaged, options, result, error)
        if (allocated(error)) return
        call note('negated line, max_order 8: LM iterations', real(result%iterations, dp))
        call check(error, result%modes%n_modes() == 4 .and. result%e <= 1.0e-12_dp, &
                   'one line negated, max_order 8: expected 4 modes, E <= 1e-12')
        if (allocated(error)) return
        call check(error, size(result%outlier_line) == 1, 'one line negated: one outlier')
        if (allocated(error)) return
        call check(error, result%outlier_line(1) == 901, 'one line negated: line 901 left out')
    end subroutine test_order_bound

    !> Structure (c) at 1 % noise with one line 1e16 times too large, identified for a contact
    !> run (g sampled at 1 ms): the identification summary, and the accuracy line of `modal`
    !> and of `auto` (short run: direct; long run: fft, no model meeting 1e-3 at 1 % noise),
    !> each quote the chosen order, the noise estimated, the worst uncertainty and the outlier;
    !> a result whose information was singular says so in words instead of a number.
    subroutine test_summaries(error)
        type(test_error), allocatable, intent(out) :: error

        type(frf_type) :: frf
        type(ml_options) :: options
        type(structure_model) :: built
        type(ml_result) :: singular
        type(error_type), allocatable :: failure
        class(convolver), allocatable :: conv
        character(len=:), allocatable :: accuracy, text, summary
        character(len=1000) :: line
        integer :: unit, stat, i
        character(len=*), parameter :: methods(3) = [character(len=6) :: 'modal', 'auto', 'auto']
        integer, parameter :: steps(3) = [1000, 1000, 1000000]

        frf = frf_from_modes(case_c(), 500.0_dp, 2049)
        call add_relative_noise(frf, 1.0e-2_dp, 77)
        frf%receptance(1025) = 1.0e16_dp*frf%receptance(1025)
        call structure_from_frf_ml(frf, options, 1.0e-3_dp, built, failure)
        if (allocated(failure)) call check(error, .false., failure%message)
        if (allocated(error)) return
        open (newunit=unit, status='scratch', action='readwrite', iostat=stat)
        call identification_summary(built, summary)
        write (unit, '(a)') summary
        rewind (unit)
        read (unit, '(a)', iostat=stat) line
        close (unit)
        call check(error, stat == 0 .and. quotes_all(line), 'identification summary: '//trim(line))
        if (allocated(error)) return
        call check(error, index(line, 'CPU ') > 0, 'identification summary quotes the CPU time: '//trim(line))
        if (allocated(error)) return
        do i = 1, size(methods)
            call make_convolver(trim(methods(i)), built, 1.0e-3_dp, 1.0e-6_dp, steps(i), conv, accuracy, failure)
            if (allocated(failure)) call check(error, .false., failure%message)
            if (allocated(error)) return
            call check(error, quotes_all(accuracy), trim(methods(i))//' line: '//accuracy)
            if (allocated(error)) return
        end do
        singular = built%ml
        singular%sigma_frequency(1) = huge(1.0_dp)
        call singular%brief(text)
        call check(error, index(text, 'uncertainty not available') > 0 .and. index(text, 'Infinity') == 0, &
                   'a singular information said in words: '//text)
    contains
        logical function quotes_all(text)
            character(len=*), intent(in) :: text

            quotes_all = index(text, '3 modes (order by MDL), noise ') > 0 .and. &
                         index(text, 'of |G| (estimated from the data), worst sigma_f/f = ') > 0 .and. &
                         index(text, 'worst sigma_xi/xi = ') > 0 .and. index(text, '1 outlier line(s) left out') > 0
        end function quotes_all
    end subroutine test_summaries

    ! ---- the scene path and universal files -----------------------------------------

    !> A noisy receptance of structure (a) at 1 % written as a universal file, a scene naming it
    !> (method 'ml' by default for a file), the structure built and its files written: every
    !> mode found, none invented, f and xi within crb_limit CRB standard deviations, the
    !> modes file with its sigma columns and the diagram file present.
    subroutine test_scene_noisy(error)
        type(test_error), allocatable, intent(out) :: error

        character(len=*), parameter :: dir = 'build/test_scratch'
        type(modal_set) :: truth
        type(frf_type) :: clean, noisy
        type(scene_type) :: scene
        type(structure_model) :: built
        type(error_type), allocatable :: failure
        type(uff_node) :: nodes(0)
        real(dp), allocatable :: sigma_f(:), sigma_xi(:)
        real(dp) :: worst_f, worst_xi
        integer :: k, m
        logical :: exists

        truth = case_a()
        clean = frf_from_modes(truth, 5000.0_dp, 8193)
        noisy = clean
        call add_relative_noise(noisy, 1.0e-2_dp, 131)
        call read_scene_text(dir, 'ml_scene.nml', "&scene task = 'identify', name = 'ml_scene', output_dir = '" &
                             //dir//"' /"//new_line('a')//"&structure model = 'frf_file', frf_file = '"//dir &
                             //"/ml_scene.uff' /"//new_line('a')//'&identification max_order = 30 /', scene, failure)
        call check(error, .not. allocated(failure), 'scene read')
        if (allocated(error)) return
        call write_uff(dir//'/ml_scene.uff', [receptance_function([7, -2], [3, 1], 0.0_dp, noisy%frequency(2), &
                                                                   noisy%receptance, 'test')], nodes, failure)
        call check(error, .not. allocated(failure), 'universal file written')
        if (allocated(error)) return
        call build_structure(scene, built, failure)
        if (allocated(failure)) call check(error, .false., failure%message)
        if (allocated(error)) return
        call check(error, built%method == ident_ml .and. index(built%frf%source, 'response 7-Y, reference 3+X') > 0, &
                   'method ml and the DOFs reported, source: '//built%frf%source)
        if (allocated(error)) return
        call check(error, built%model%n_modes() == truth%n_modes(), 'modes found: expected 12')
        if (allocated(error)) return
        call cramer_rao(truth, clean, 1.0e-2_dp, sigma_f, sigma_xi, error)
        if (allocated(error)) return
        worst_f = 0.0_dp
        worst_xi = 0.0_dp
        do k = 1, truth%n_modes()
            m = minloc(abs(built%model%pole - truth%pole(k)), 1)
            associate (found => built%model%pole(m), pole => truth%pole(k))
                worst_f = max(worst_f, abs(abs(found) - abs(pole))/two_pi/sigma_f(k))
                worst_xi = max(worst_xi, abs(real(found, dp)/abs(found) - real(pole, dp)/abs(pole))/sigma_xi(k))
            end associate
        end do
        call note('scene, 1 % noise: worst |f error|/CRB sigma', worst_f)
        call note('scene, 1 % noise: worst |xi error|/CRB sigma', worst_xi)
        call check(error, worst_f <= crb_limit .and. worst_xi <= crb_limit, 'within the CRB limit')
        if (allocated(error)) return
        call write_identification(scene, built, failure)
        call check(error, .not. allocated(failure), 'identification files written')
        if (allocated(error)) return
        inquire (file=dir//'/ml_scene_diagram.dat', exist=exists)
        call check(error, exists, 'the stabilisation diagram file is written')
        if (allocated(error)) return
        call check(error, column_count(dir//'/ml_scene_modes.dat') == 11, &
                   'modes file: 11 columns with sigma and determined')
    end subroutine test_scene_noisy

    !> Number of columns of the first data line of a column file (0 when none).
    function column_count(path) result(n)
        character(len=*), intent(in) :: path
        integer :: n

        character(len=1000) :: line
        real(dp) :: values(20)
        integer :: unit, stat

        n = 0
        open (newunit=unit, file=path, status='old', action='read', iostat=stat)
        if (stat /= 0) return
        do
            read (unit, '(a)', iostat=stat) line
            if (stat /= 0) exit
            if (line(1:1) == '#') cycle
            do n = 20, 1, -1
                read (line, *, iostat=stat) values(1:n)
                if (stat == 0) exit
            end do
            exit
        end do
        close (unit)
    end function column_count

    !> The same receptance written as a receptance, a mobility Y = i*omega*G and an accelerance
    !> A = -omega^2*G (records 9 of velocity 11 and acceleration 12): read_frf gives G back on
    !> every line above 0 Hz to round-off, and at 0 Hz within the extrapolation error (df = 0.5 Hz,
    !> exact in the E13.5 increment of record 7).
    subroutine test_uff_kinds(error)
        type(test_error), allocatable, intent(out) :: error

        character(len=*), parameter :: path = 'build/test_scratch/ml_kinds.uff'
        character(len=*), parameter :: names(3) = ['receptance ', 'mobility   ', 'accelerance']
        type(frf_type) :: exact, read_back
        type(uff_function) :: function
        type(uff_node) :: nodes(0)
        type(error_type), allocatable :: failure
        complex(dp), allocatable :: values(:)
        real(dp), allocatable :: omega(:)
        real(dp) :: worst
        integer :: kind

        exact = frf_from_modes(case_c(), 512.0_dp, 1025)
        omega = two_pi*exact%frequency
        do kind = 1, 3
            select case (kind)
            case (1)
                values = exact%receptance
            case (2)
                values = cmplx(0.0_dp, omega, dp)*exact%receptance
            case (3)
                values = -omega**2*exact%receptance
            end select
            function = receptance_function([1, 3], [1, 3], 0.0_dp, exact%frequency(2), values, 'kinds')
            if (kind == 2) function%numerator%data_type = 11
            if (kind == 3) function%numerator%data_type = 12
            call write_uff(path, [function], nodes, failure)
            if (.not. allocated(failure)) call read_frf(path, read_back, failure)
            if (allocated(failure)) call check(error, .false., trim(names(kind))//': '//failure%message)
            if (allocated(error)) return
            worst = maxval(abs(read_back%receptance(2:) - exact%receptance(2:)))/maxval(abs(exact%receptance))
            call note(trim(names(kind))//': worst relative error above 0 Hz', worst)
            call check(error, worst < 1.0e-10_dp, trim(names(kind))//': G back to round-off above 0 Hz')
            if (allocated(error)) return
            call check(error, abs(read_back%receptance(1) - exact%receptance(1)) < 1.0e-4_dp*abs(exact%receptance(1)), &
                       trim(names(kind))//': 0 Hz line within 1e-4')
            if (allocated(error)) return
            call check(error, index(read_back%source, trim(names(kind))) > 0, trim(names(kind))//': the kind is ' &
                       //'reported: '//read_back%source)
            if (allocated(error)) return
        end do
    end subroutine test_uff_kinds

    !> Universal files that cannot give a receptance, each refused with the file, the line and
    !> what to do: two datasets 58 without frf_dataset (both listed), frf_dataset too large, a
    !> time response (function type 1), a negative frequency; an uneven abscissa off the uniform
    !> grid is accepted and kept as read.
    subroutine test_uff_refused(error)
        type(test_error), allocatable, intent(out) :: error

        character(len=*), parameter :: path = 'build/test_scratch/ml_bad.uff'
        type(frf_type) :: exact, read_back
        type(uff_function) :: first, second
        type(uff_node) :: nodes(0)
        type(error_type), allocatable :: failure
        integer :: j

        exact = frf_from_modes(case_c(), 512.0_dp, 257)
        first = receptance_function([1, 3], [1, 3], 0.0_dp, exact%frequency(2), exact%receptance, 'one')
        second = receptance_function([2, 3], [1, 3], 0.0_dp, exact%frequency(2), exact%receptance, 'two')
        call write_uff(path, [first, second], nodes, failure)
        call read_frf(path, read_back, failure)
        call expect_refusal(error, failure, path//': the file holds 2 datasets 58; say which one with ' &
                            //'&structure frf_dataset', 'response 2+Z')
        if (allocated(error)) return
        call read_frf(path, read_back, failure, 2)
        call check(error, .not. allocated(failure), 'frf_dataset = 2 accepted')
        if (allocated(error)) return
        call check(error, index(read_back%source, 'response 2+Z') > 0, 'frf_dataset = 2 reads the second')
        if (allocated(error)) return
        call read_frf(path, read_back, failure, 3)
        call expect_refusal(error, failure, 'frf_dataset = 3 asks for dataset 58 number 3', '#2 line')
        if (allocated(error)) return
        call write_uff(path, [impulse_function([1, 3], [1, 3], 0.0_dp, 1.0e-3_dp, real(exact%receptance, dp), &
                                               'time')], nodes, failure)
        call read_frf(path, read_back, failure)
        call expect_refusal(error, failure, path//':1: dataset 58: expected function type 4', 'time response')
        if (allocated(error)) return
        first%even = .false.
        first%abscissa = [(exact%frequency(j) + merge(0.3_dp, 0.0_dp, j == 9), j=1, exact%n_freq())]
        call write_uff(path, [first], nodes, failure)
        call read_frf(path, read_back, failure)
        call check(error, .not. allocated(failure), 'an uneven abscissa off the uniform grid is accepted')
        if (allocated(error)) return
        call check(error, .not. read_back%uniform_from_zero() .and. read_back%frequency(9) == first%abscissa(9), &
                   'and kept as read')
        if (allocated(error)) return
        first%abscissa = exact%frequency - exact%frequency(2)
        call write_uff(path, [first], nodes, failure)
        call read_frf(path, read_back, failure)
        call expect_refusal(error, failure, path//':1: expected frequencies >= 0 Hz', 'uneven')
        if (allocated(error)) return
        first%abscissa = exact%frequency
        first%abscissa(9) = first%abscissa(9) + 1.0e-9_dp*exact%frequency(2)
        call write_uff(path, [first], nodes, failure)
        call read_frf(path, read_back, failure)
        call check(error, .not. allocated(failure), 'an uneven abscissa on the uniform grid is accepted')
    end subroutine test_uff_refused

    !> The failure is set and its message holds both parts.
    subroutine expect_refusal(error, failure, start, detail)
        type(test_error), allocatable, intent(out) :: error
        type(error_type), allocatable, intent(in) :: failure
        character(len=*), intent(in) :: start, detail

        if (.not. allocated(failure)) then
            call check(error, .false., 'expected a refusal: '//start)
            return
        end if
        call check(error, index(failure%message, start) > 0 .and. index(failure%message, detail) > 0, &
                   'expected "'//start//'" and "'//detail//'", found: '//failure%message)
    end subroutine expect_refusal

end module test_mlfit_mod
