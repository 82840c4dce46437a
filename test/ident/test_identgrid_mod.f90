!> The maximum-likelihood identification on grids other than the uniform grid from 0 Hz
!> (even abscissa spacing, and uneven too): a uniform grid from df (no 0 Hz line),
!> a band from f_min > 0 and log-spaced lines, each against the Cramér-Rao bound computed on
!> those same lines (test_mlfit_mod's `cramer_rao`, the Jacobian of the true model); a clean
!> uneven receptance to round-off; the LSCE path refused with the line and the way out; g for
!> `direct` sampled from the identified modes and the modal methods built on such a grid; the
!> pyuff fixture (an SDOF mobility on 20 uneven lines from 5 Hz) through a scene file.
module test_identgrid_mod
    use, intrinsic :: iso_fortran_env, only: dp => real64
    use testsuite_mod, only: test_error, unittest_type, new_unittest, check, note
    use greenconv_core_error, only: error_type
    use greenconv_model_modal_set, only: modal_set
    use greenconv_model_frf, only: frf_type, add_relative_noise, read_frf
    use greenconv_ident_lsce, only: lsce_options, natural_frequency, damping_ratio
    use greenconv_ident_mlfit, only: ml_options, ml_result, identify_ml
    use greenconv_ident_methods, only: ident_ml
    use greenconv_ident_structure, only: structure_model, structure_from_frf, structure_from_frf_ml
    use greenconv_conv_convolver, only: convolver
    use greenconv_conv_builder, only: make_convolver
    use greenconv_scene_read_input, only: scene_type
    use greenconv_scene_models_structure, only: build_structure
    use scene_text_mod, only: read_scene_text
    use test_mlfit_mod, only: fit_draw_on, structure
    implicit none
    private

    public :: collect_identgrid

    real(dp), parameter :: pi = 3.141592653589793238462643383279_dp
    real(dp), parameter :: two_pi = 2.0_dp*pi
    !> Largest error allowed, in Cramér-Rao standard deviations (as suite mlfit).
    real(dp), parameter :: crb_limit = 5.0_dp
    !> Noise level, fraction of |G| per line.
    real(dp), parameter :: level = 1.0e-2_dp
    !> Draws per grid.
    integer, parameter :: seeds = 3

contains

    !> Tests of the identification on grids off the uniform grid from 0 Hz.
    subroutine collect_identgrid(testsuite)
        type(unittest_type), allocatable, intent(out) :: testsuite(:)

        testsuite = [new_unittest('crb: uniform grid from df, no 0 Hz line; 1 % noise', test_from_df), &
                     new_unittest('crb: band from 50 Hz; 1 % noise', test_band), &
                     new_unittest('crb: log-spaced lines from 20 Hz; 1 % noise', test_log), &
                     new_unittest('clean: log-spaced lines fitted to round-off', test_clean_log), &
                     new_unittest('lsce: refused off the grid from 0 Hz, naming the line and the way out', &
                                  test_lsce_refused), &
                     new_unittest('contact: g from the modes and the modal methods on a band grid', test_contact), &
                     new_unittest('scene: the pyuff uneven SDOF mobility identified end to end', test_pyuff_scene)]
    end subroutine collect_identgrid

    !> Five modes to 1 kHz: a close pair 240/250 Hz, modal constants of both signs.
    function truth() result(modes)
        type(modal_set) :: modes

        modes = structure([70.0_dp, 240.0_dp, 250.0_dp, 520.0_dp, 830.0_dp], &
                          [0.02_dp, 0.005_dp, 0.008_dp, 0.03_dp, 0.01_dp], &
                          1.0e-6_dp*[1.0_dp, -0.7_dp, 0.9_dp, 1.5_dp, -0.8_dp])
    end function truth

    !> The receptance of `modes` on the frequencies f [Hz].
    function sampled(modes, f) result(frf)
        type(modal_set), intent(in) :: modes
        real(dp), intent(in) :: f(:)
        type(frf_type) :: frf

        frf%frequency = f
        frf%receptance = modes%receptance(two_pi*f)
        frf%source = ''
    end function sampled

    !> j*1000/1024 Hz, j = 1..1024.
    function grid_from_df() result(f)
        real(dp), allocatable :: f(:)
        integer :: j

        f = [(j*(1000.0_dp/1024), j=1, 1024)]
    end function grid_from_df

    !> 50 to 1000 Hz by 0.5 Hz.
    function grid_band() result(f)
        real(dp), allocatable :: f(:)
        integer :: j

        f = [(50.0_dp + 0.5_dp*j, j=0, 1900)]
    end function grid_band

    !> 1500 lines from 20 to 1000 Hz, equally spaced in log f (0.05 Hz apart at 20 Hz, 2.6 Hz at 1 kHz).
    function grid_log() result(f)
        real(dp), allocatable :: f(:)
        integer :: j

        f = [(20.0_dp*exp(log(50.0_dp)*j/1499.0_dp), j=0, 1499)]
    end function grid_log

    !> `seeds` noisy draws on grid f (test_mlfit_mod's `fit_draw_on`): every mode found, none
    !> invented, no line taken for an outlier, f and xi within crb_limit Cramér-Rao standard
    !> deviations computed on the same lines; the worst noted.
    subroutine check_grid_fit(error, f, label)
        type(test_error), allocatable, intent(out) :: error
        real(dp), intent(in) :: f(:)
        character(len=*), intent(in) :: label

        type(modal_set) :: modes
        type(frf_type) :: clean
        real(dp) :: worst_f, worst_xi, draw_f, draw_xi
        integer :: seed

        modes = truth()
        clean = sampled(modes, f)
        worst_f = 0.0_dp
        worst_xi = 0.0_dp
        do seed = 1, seeds
            call fit_draw_on(modes, clean, level, 700 + seed, draw_f, draw_xi, error)
            if (allocated(error)) then
                error%message = label//': '//error%message
                return
            end if
            worst_f = max(worst_f, draw_f)
            worst_xi = max(worst_xi, draw_xi)
        end do
        call note(label//': worst |f - f_true|/sigma_CRB', worst_f)
        call note(label//': worst |xi - xi_true|/sigma_CRB', worst_xi)
        call check(error, worst_f, 0.0_dp, label//': worst f error in CRB sigma', thr=crb_limit)
        if (allocated(error)) return
        call check(error, worst_xi, 0.0_dp, label//': worst xi error in CRB sigma', thr=crb_limit)
    end subroutine check_grid_fit

    subroutine test_from_df(error)
        type(test_error), allocatable, intent(out) :: error

        call check_grid_fit(error, grid_from_df(), 'from df')
    end subroutine test_from_df

    subroutine test_band(error)
        type(test_error), allocatable, intent(out) :: error

        call check_grid_fit(error, grid_band(), 'band')
    end subroutine test_band

    subroutine test_log(error)
        type(test_error), allocatable, intent(out) :: error

        call check_grid_fit(error, grid_log(), 'log')
    end subroutine test_log

    !> Noise-free log-spaced lines: five modes, each pole within 1e-9 of the truth (relative),
    !> E of eq. (7) below 1e-12.
    subroutine test_clean_log(error)
        type(test_error), allocatable, intent(out) :: error

        type(modal_set) :: modes
        type(ml_options) :: options
        type(ml_result) :: fitted
        type(error_type), allocatable :: failure
        real(dp) :: worst
        integer :: k

        modes = truth()
        call identify_ml(sampled(modes, grid_log()), options, fitted, failure)
        if (allocated(failure)) call check(error, .false., 'identify_ml failed: '//failure%message)
        if (allocated(error)) return
        call check(error, fitted%modes%n_modes() == modes%n_modes(), 'expected 5 modes')
        if (allocated(error)) return
        worst = 0.0_dp
        do k = 1, modes%n_modes()
            worst = max(worst, minval(abs(fitted%modes%pole - modes%pole(k)))/abs(modes%pole(k)))
        end do
        call note('clean log grid: worst relative pole error', worst)
        call note('clean log grid: E (eq. 7)', fitted%e)
        call check(error, worst < 1.0e-9_dp, 'poles to round-off')
        if (allocated(error)) return
        call check(error, fitted%e < 1.0e-12_dp, 'E to round-off')
    end subroutine test_clean_log

    !> `structure_from_frf` (LSCE, g by inverse FFT) on a band grid: status set, the message
    !> names the first line off the grid from 0 Hz and points to method = 'ml'.
    subroutine test_lsce_refused(error)
        type(test_error), allocatable, intent(out) :: error

        type(frf_type) :: frf
        type(lsce_options) :: options
        type(structure_model) :: built
        type(error_type), allocatable :: failure
        integer :: l

        frf = sampled(truth(), grid_band())
        frf%line = [(l + 10, l=1, frf%n_freq())]
        call structure_from_frf(frf, options, 0.0_dp, built, failure)
        call check(error, allocated(failure), 'LSCE on a band grid refused')
        if (allocated(error)) return
        call check(error, index(failure%message, 'line 11: expected the uniform grid from 0 Hz') == 1 .and. &
                   index(failure%message, 'found 50') > 0 .and. index(failure%message, "method = 'ml'") > 0, &
                   'message: '//failure%message)
    end subroutine test_lsce_refused

    !> A noisy band from 50 Hz with dt > 0: the ML structure's g is the identified modes' g
    !> (within 1 % of max|g| of the true modes' g at 1 % noise: the modes within a few CRB
    !> sigma), `modal`, `exact`, `auto` and `direct` build, and the fit's warning says where g
    !> came from.
    subroutine test_contact(error)
        type(test_error), allocatable, intent(out) :: error

        real(dp), parameter :: dt = 2.0e-4_dp
        type(modal_set) :: modes
        type(frf_type) :: frf
        type(ml_options) :: options
        type(structure_model) :: built
        type(error_type), allocatable :: failure
        class(convolver), allocatable :: conv
        character(len=:), allocatable :: accuracy
        character(len=*), parameter :: methods(4) = [character(len=6) :: 'modal', 'exact', 'auto', 'direct']
        real(dp), allocatable :: g_true(:)
        real(dp) :: misfit
        integer :: i, j

        modes = truth()
        frf = sampled(modes, grid_band())
        call add_relative_noise(frf, level, 91)
        call structure_from_frf_ml(frf, options, dt, built, failure)
        if (allocated(failure)) call check(error, .false., 'structure_from_frf_ml: '//failure%message)
        if (allocated(error)) return
        call check(error, built%sampled_step == dt .and. size(built%sampled_g) > 1000, 'g sampled at dt')
        if (allocated(error)) return
        g_true = modes%impulse([(j*dt, j=0, size(built%sampled_g) - 1)])
        misfit = maxval(abs(built%sampled_g - g_true))/maxval(abs(g_true))
        call note('band grid: max|g_modes - g_true|/max|g_true|', misfit)
        call check(error, misfit < 1.0e-2_dp, 'g from the identified modes near the true g')
        if (allocated(error)) return
        call check(error, index(built%ml%warning, 'sampled from the 5 identified modes') > 0, &
                   'the warning says g comes from the modes: '//built%ml%warning)
        if (allocated(error)) return
        do i = 1, size(methods)
            call make_convolver(trim(methods(i)), built, dt, 1.0e-2_dp, 2000, conv, accuracy, failure)
            if (allocated(failure)) call check(error, .false., trim(methods(i))//': '//failure%message)
            if (allocated(error)) return
        end do
    end subroutine test_contact

    !> test/data/uff/frf_complex_single_uneven.uff (pyuff, tools/make_uff_fixtures.py): the
    !> mobility of m = 1.5 kg, f_n = 50 Hz, zeta = 0.02 on 20 uneven lines from 5 to 150.25 Hz,
    !> written to six digits. A scene (task 'identify', method 'ml' by default) finds one mode,
    !> f_n within 1e-4 and zeta within 1e-3 (relative), the residue within 1e-3 of
    !> 1/(2*m*omega_d): the fixture's six digits on 20 lines.
    subroutine test_pyuff_scene(error)
        type(test_error), allocatable, intent(out) :: error

        character(len=*), parameter :: dir = 'build/test_scratch'
        real(dp), parameter :: mass = 1.5_dp, f_n = 50.0_dp, zeta = 0.02_dp
        type(scene_type) :: scene
        type(structure_model) :: built
        type(frf_type) :: frf
        type(error_type), allocatable :: failure
        real(dp) :: f_found, xi_found, r_expected

        call read_frf('test/data/uff/frf_complex_single_uneven.uff', frf, failure)
        if (allocated(failure)) call check(error, .false., 'fixture read: '//failure%message)
        if (allocated(error)) return
        call check(error, frf%frequency(1) == 5.0_dp .and. .not. frf%uniform_from_zero(), 'uneven from 5 Hz')
        if (allocated(error)) return
        call read_scene_text(dir, 'grid_pyuff.nml', "&scene task = 'identify', name = 'grid_pyuff', " &
                             //"output_dir = '"//dir//"' /"//new_line('a')//"&structure model = 'frf_file', " &
                             //"frf_file = 'test/data/uff/frf_complex_single_uneven.uff' /", scene, failure)
        if (allocated(failure)) call check(error, .false., 'scene read: '//failure%message)
        if (allocated(error)) return
        call build_structure(scene, built, failure)
        if (allocated(failure)) call check(error, .false., 'scene built: '//failure%message)
        if (allocated(error)) return
        call check(error, built%method == ident_ml .and. built%model%n_modes() == 1, 'one mode by ML')
        if (allocated(error)) return
        f_found = natural_frequency(built%model%pole(1))/two_pi
        xi_found = damping_ratio(built%model%pole(1))
        r_expected = 1.0_dp/(2.0_dp*mass*two_pi*f_n*sqrt(1.0_dp - zeta**2))
        call note('pyuff SDOF: relative error of f_n', abs(f_found - f_n)/f_n)
        call note('pyuff SDOF: relative error of zeta', abs(xi_found - zeta)/zeta)
        call note('pyuff SDOF: relative error of |r|', abs(abs(built%model%residue(1)) - r_expected)/r_expected)
        call check(error, abs(f_found - f_n) <= 1.0e-4_dp*f_n, 'f_n within 1e-4')
        if (allocated(error)) return
        call check(error, abs(xi_found - zeta) <= 1.0e-3_dp*zeta, 'zeta within 1e-3')
        if (allocated(error)) return
        call check(error, abs(abs(built%model%residue(1)) - r_expected) <= 1.0e-3_dp*r_expected, '|r| within 1e-3')
    end subroutine test_pyuff_scene

end module test_identgrid_mod
