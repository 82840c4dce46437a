!> Many contact points: the Green's matrix in modal and sampled form, the
!> multi-point contact loop, the tyre model and road files (the cost table is a smoke check of
!> the benchmark: `greenconv-bench --smoke`).
!>
!> Tolerances, each against something computed another way:
!> - one point: the same arithmetic as greenconv_contact_single's loop, so equal to 1e-15 of the peak
!>   (in practice bit for bit); a driving point of many modes, where the multi-point engine
!>   sums phi*(phi*q) and the single-point one phi^2*q: 1e-12 of the peak, a few hundred
!>   roundings (one per mode and step of memory) of a stable recursion;
!> - modal against a sampled table from the same modes covering the whole run: the two are
!>   the same sum (eq. 20), rounded differently: 1e-12 of max|u|, as the single-point
!>   direct-vs-modal check;
!> - mirror symmetry: positions mirrored to one ulp and sums taken in other orders, through
!>   a loop that loses and regains contact (Hertz: the slope is continuous at delta = 0, so a
!>   point switching one step apart in the two mirrors costs only round-off): 1e-12 of max F;
!> - static closed form: the `exact` scheme has the exact static gain, transients decay as
!>   exp(-xi*omega_1*t) = 2e-18 after 1.5 s, Newton stops at 1e-12: 1e-10 of the force change;
!> - tyre frequencies and shapes: the same closed form evaluated twice: 1e-14;
!> - complementarity holds exactly (F = 0 where delta <= 0 is a branch, not a tolerance);
!>   the compressions match delta0 + u_r - u to the Newton tolerance: 1e-10 of the scale.
module test_multicontact_mod
    use, intrinsic :: iso_fortran_env, only: dp => real64
    use testsuite_mod, only: test_error, unittest_type, new_unittest, check, note
    use greenconv_io_files, only: make_directory
    use greenconv_core_error, only: error_type, stat_input, stat_numerical
    use greenconv_core_text, only: int_text
    use greenconv_core_random, only: random_stream
    use greenconv_model_sdof, only: sdof_modes
    use greenconv_model_modal_set, only: modal_set
    use greenconv_ext_lapack, only: solve_linear, least_squares
    use greenconv_conv_direct, only: direct_convolver, new_direct_convolver
    use greenconv_conv_kernel, only: sample_kernel
    use greenconv_conv_recursive, only: recursive_convolver, new_recursive_convolver, new_exact_convolver
    use greenconv_contact_single, only: contact_law, contact_response, run_contact, contact_options
    use greenconv_model_road, only: sine_road, random_road, new_random_road
    use greenconv_io_columns, only: read_columns
    use greenconv_conv_multipoint, only: multipoint_convolver, sample_green_matrix
    use greenconv_conv_convolver, only: convolver
    use greenconv_conv_point_matrix, only: point_matrix, wrap_point
    use greenconv_conv_methods, only: method_scheme, scheme_first_order
    use greenconv_conv_recursive, only: new_modal_engine
    use greenconv_model_point_modes, only: point_modes
    use greenconv_conv_green_modal, only: modal_green_matrix, new_modal_green_matrix
    use greenconv_conv_green_sampled, only: sampled_green_matrix, new_sampled_green_matrix
    use greenconv_contact_multi, only: newton_options, multi_contact_response, run_multi_contact
    use greenconv_scene_run_output, only: write_multi_contact
    use greenconv_model_tyre, only: tyre_belt, tyre_modes, tyre_mode_count, tyre_band, contact_positions
    use greenconv_model_road_file, only: road_file, read_road_file, sample_road, road_travel
    use greenconv_contact_law_power, only: power_law
    implicit none
    private

    public :: collect_multicontact

    !> The oscillator and contact of the paper's Tab. 1 (as test_contact_mod).
    real(dp), parameter :: mass = 1.0_dp, stiffness = 1.0e6_dp, xi = 0.02_dp
    real(dp), parameter :: k_contact = 1.0e6_dp, exponent = 1.5_dp, preload = 9.81_dp
    real(dp), parameter :: dt = 1.0e-4_dp
    integer, parameter :: n_steps = 2000
    real(dp), parameter :: pi = acos(-1.0_dp)
    !> The tyre with its documented defaults.
    type(tyre_belt), parameter :: default_tyre = tyre_belt()
    !> Scratch directory for the files the tests write.
    character(len=*), parameter :: scratch = 'build/test_scratch'

contains

    !> Tests of the multi-point modules.
    subroutine collect_multicontact(testsuite)
        type(unittest_type), allocatable, intent(out) :: testsuite(:)

        testsuite = [new_unittest('solve_linear (dgesv): known solution, singular matrix', test_solve_linear), &
                     new_unittest('one point, modal: equals run_contact with recursive', test_one_point_modal), &
                     new_unittest('one point, sampled: equals run_contact with direct', test_one_point_sampled), &
                     new_unittest('one point, exact: W0 and history equal the exact engine', test_one_point_exact), &
                     new_unittest('one point as the 1 x 1 case: a wrapped engine equals run_contact', &
                                  test_wrapped_point), &
                     new_unittest('one point, implicit: the multi-point loop takes run_contact''s step', &
                                  test_wrapped_implicit), &
                     new_unittest('modal Green''s matrix: W0 from the engine''s per-mode shares', test_mode_shares), &
                     new_unittest('tyre driving point equals run_contact on phi^2 r_k modes', test_driving_point), &
                     new_unittest('modal and sampled Green''s matrices agree (same modes)', test_modal_sampled), &
                     new_unittest('symmetric tyre, symmetric road: mirrored forces equal', test_symmetry), &
                     new_unittest('linear springs, road step: static closed form (exact, Newton)', test_static), &
                     new_unittest('unilateral per point, contact lost at some points', test_unilateral), &
                     new_unittest('Newton failure and divergence: errors name the step, rows kept', test_failures), &
                     new_unittest('tyre: frequencies, shapes, unit modal mass, defaults', test_tyre), &
                     new_unittest('road file: sample profile follows its header, interpolation', test_road_sample), &
                     new_unittest('road file: bad files and ranges give one clear message', test_road_errors), &
                     new_unittest('write_multi_contact: one row per step and point', test_write)]
    end subroutine collect_multicontact

    ! ---- helpers -----------------------------------------------------------------------

    !> The oscillator of Tab. 1 as a one-point modal description (phi = 1).
    function sdof_description() result(description)
        type(point_modes) :: description

        description%modes = sdof_modes(mass, stiffness, xi)
        allocate (description%shape(1, 1))
        description%shape(:, :) = 1.0_dp
    end function sdof_description

    !> The default tyre up to f_max [Hz] at the given positions.
    function tyre_description(positions, f_max) result(description)
        real(dp), intent(in) :: positions(:), f_max
        type(point_modes) :: description

        type(error_type), allocatable :: failure

        call tyre_modes(tyre_belt(), positions, f_max, description, failure)
        if (allocated(failure)) error stop 'test_multicontact_mod: '//failure%message
    end function tyre_description

    !> A modal multi-point convolver, or stop: the constructor is tested elsewhere.
    function modal_matrix(description, scheme) result(conv)
        type(point_modes), intent(in) :: description
        character(len=*), intent(in) :: scheme
        type(modal_green_matrix) :: conv

        type(error_type), allocatable :: failure

        call new_modal_green_matrix(description, dt, scheme, conv, failure)
        if (allocated(failure)) error stop 'test_multicontact_mod: '//failure%message
    end function modal_matrix

    !> Run the loop, or stop with the message: these scenes must run.
    subroutine run_or_stop(conv, laws, road, preloads, response)
        class(multipoint_convolver), intent(inout) :: conv
        type(power_law), intent(in) :: laws(:)
        real(dp), intent(in) :: road(0:, :), preloads(:)
        type(multi_contact_response), intent(out) :: response

        type(error_type), allocatable :: failure

        call run_multi_contact(conv, laws, road, preloads, response, failure)
        if (allocated(failure)) error stop 'test_multicontact_mod: '//failure%message
    end subroutine run_or_stop

    !> The sine road of Tab. 1 (A0 = 1 mm, 100 rad/s) as one column.
    function sine_column() result(road)
        real(dp) :: road(0:n_steps - 1, 1)

        type(sine_road) :: sine

        sine%amplitude = 1.0e-3_dp
        sine%omega = 100.0_dp
        road(:, 1) = sine%sample(dt, n_steps)
    end function sine_column

    !> Largest |a - b| over a single-point response and column 1 of a multi-point one.
    real(dp) function worst_difference(single, multi) result(worst)
        type(contact_response), intent(in) :: single
        type(multi_contact_response), intent(in) :: multi

        worst = max(maxval(abs(single%displacement - multi%displacement(:, 1)))/maxval(abs(single%displacement)), &
                    maxval(abs(single%force - multi%force(:, 1)))/maxval(single%force), &
                    maxval(abs(single%compression - multi%compression(:, 1)))/maxval(abs(single%compression)))
    end function worst_difference

    !> Hertz laws with static compression delta0 [m] under preload f0 [N] at n points.
    subroutine hertz_points(n, f0, delta0, laws, preloads)
        integer, intent(in) :: n
        real(dp), intent(in) :: f0, delta0
        type(power_law), allocatable, intent(out) :: laws(:)
        real(dp), allocatable, intent(out) :: preloads(:)

        allocate (laws(n), preloads(n))
        laws(:) = power_law(f0/delta0**1.5_dp, 1.5_dp)
        preloads(:) = f0
    end subroutine hertz_points

    !> The road of eq. (35) (seed 35, 10 terms) under points x_i moving at `speed`.
    function travelling_road(positions, amplitude, speed, n) result(road)
        real(dp), intent(in) :: positions(:), amplitude, speed
        integer, intent(in) :: n
        real(dp) :: road(0:n - 1, size(positions))

        type(random_road) :: profile
        integer :: i, m

        profile = new_random_road(35, 10, amplitude, 0.05_dp, speed)
        do i = 1, size(positions)
            road(:, i) = profile%height([(m*dt + positions(i)/speed, m=0, n - 1)])
        end do
    end function travelling_road

    ! ---- LAPACK ------------------------------------------------------------------------

    subroutine test_solve_linear(error)
        type(test_error), allocatable, intent(out) :: error

        real(dp) :: a(3, 3), x(3), x_true(3), s(2, 2), y(2)
        type(error_type), allocatable :: failure

        a = reshape([4.0_dp, 1.0_dp, 0.0_dp, 1.0_dp, 3.0_dp, 1.0_dp, 0.0_dp, 1.0_dp, 2.0_dp], [3, 3])
        x_true = [1.0_dp, -2.0_dp, 3.0_dp]
        call solve_linear(a, matmul(a, x_true), x, failure)
        call check(error, .not. allocated(failure), 'solve_linear failed on a regular matrix')
        if (allocated(error)) return
        call note('max|x - x_true|', maxval(abs(x - x_true)))
        ! Condition number about 4: a few roundings of numbers near 1.
        call check(error, maxval(abs(x - x_true)), 0.0_dp, 'solution of a 3 x 3 system', thr=1.0e-14_dp)
        if (allocated(error)) return
        s = reshape([1.0_dp, 2.0_dp, 2.0_dp, 4.0_dp], [2, 2])
        call solve_linear(s, [1.0_dp, 1.0_dp], y, failure)
        call check(error, allocated(failure), 'no error for a singular matrix')
        if (allocated(error)) return
        call check(error, index(failure%message, 'dgesv: singular matrix') == 1 .and. failure%stat == stat_numerical, &
                   'message for a singular matrix: '//failure%message)
    end subroutine test_solve_linear

    ! ---- one point -----------------------------------------------------------------------

    !> The SDOF scene of section 3.1 through both loops with the `recursive` engine.
    subroutine test_one_point_modal(error)
        type(test_error), allocatable, intent(out) :: error

        type(modal_green_matrix) :: multi_conv
        type(recursive_convolver) :: single_conv
        type(multi_contact_response) :: multi
        type(contact_response) :: single
        real(dp) :: road(0:n_steps - 1, 1)

        road = sine_column()
        multi_conv = modal_matrix(sdof_description(), 'recursive')
        call run_or_stop(multi_conv, [power_law(k_contact, exponent)], road, [preload], multi)
        single_conv = new_recursive_convolver(sdof_modes(mass, stiffness, xi), dt)
        call run_contact(single_conv, power_law(k_contact, exponent), road(:, 1), preload, single)
        call note('max relative difference', worst_difference(single, multi))
        call check(error, worst_difference(single, multi), 0.0_dp, 'u, F, delta: multi-point against run_contact', &
                   thr=1.0e-15_dp)
        if (allocated(error)) return
        call check(error, all(multi%iterations == 0) .and. multi_conv%is_explicit(), &
                   'W0 = 0: forces evaluated directly, no Newton iteration')
        if (allocated(error)) return
        call check(error, count(multi%force(:, 1) == 0.0_dp) > 100, 'the scene loses contact')
    end subroutine test_one_point_modal

    !> A single-point engine wrapped as a 1 x 1 Green's matrix (greenconv_conv_point_matrix)
    !> runs the multi-point loop with the engine's own numbers: the explicit step on `recursive`
    !> and on `direct` gives u, F and delta of run_contact bit for bit.
    subroutine test_wrapped_point(error)
        type(test_error), allocatable, intent(out) :: error

        class(convolver), allocatable :: engine
        type(point_matrix) :: wrapped
        type(recursive_convolver) :: single_conv
        type(multi_contact_response) :: multi
        type(contact_response) :: single
        real(dp), allocatable :: kernel(:)
        real(dp) :: road(0:n_steps - 1, 1), tail

        road = sine_column()
        engine = new_recursive_convolver(sdof_modes(mass, stiffness, xi), dt)
        call wrap_point(engine, wrapped)
        call check(error, wrapped%n_points() == 1 .and. wrapped%is_explicit() .and. wrapped%name == 'recursive' &
                   .and. .not. allocated(engine), 'the engine moved into a 1 x 1 matrix, W0 = 0, its name kept')
        if (allocated(error)) return
        call run_or_stop(wrapped, [power_law(k_contact, exponent)], road, [preload], multi)
        single_conv = new_recursive_convolver(sdof_modes(mass, stiffness, xi), dt)
        call run_contact(single_conv, power_law(k_contact, exponent), road(:, 1), preload, single)
        call check(error, worst_difference(single, multi) == 0.0_dp .and. wrapped%step == n_steps, &
                   'recursive: u, F, delta bit for bit, the steps counted')
        if (allocated(error)) return
        call sample_kernel(sdof_modes(mass, stiffness, xi), dt, 0.01_dp, n_steps, kernel, tail)
        engine = new_direct_convolver(kernel, dt)
        call wrap_point(engine, wrapped)
        call run_or_stop(wrapped, [power_law(k_contact, exponent)], road, [preload], multi)
        engine = new_direct_convolver(kernel, dt)
        call run_contact(engine, power_law(k_contact, exponent), road(:, 1), preload, single)
        call check(error, worst_difference(single, multi) == 0.0_dp, 'direct: u, F, delta bit for bit')
    end subroutine test_wrapped_point

    !> One stepping path: a wrapped `exact` engine (w0 > 0) run by the multi-point loop with
    !> its defaults (the implicit scheme, 50 iterations, 1 m) solves each step by the same
    !> scalar Newton iteration as run_contact's implicit scheme with those settings, so u, F
    !> and delta agree bit for bit; the iterations are counted (a few per step in contact).
    subroutine test_wrapped_implicit(error)
        type(test_error), allocatable, intent(out) :: error

        class(convolver), allocatable :: engine
        type(point_matrix) :: wrapped
        type(multi_contact_response) :: multi
        type(contact_response) :: single
        type(error_type), allocatable :: failure
        real(dp) :: road(0:n_steps - 1, 1)

        road = sine_column()
        engine = new_exact_convolver(sdof_modes(mass, stiffness, xi), dt)
        call wrap_point(engine, wrapped)
        call run_or_stop(wrapped, [power_law(k_contact, exponent)], road, [preload], multi)
        engine = new_exact_convolver(sdof_modes(mass, stiffness, xi), dt)
        call run_contact(engine, power_law(k_contact, exponent), road(:, 1), preload, single, &
                         contact_options(scheme='implicit', divergence_bound=1.0_dp, max_iterations=50), failure)
        call check(error, .not. allocated(failure), 'run_contact failed')
        if (allocated(error)) return
        call note('most iterations in a step', real(maxval(multi%iterations), dp))
        call check(error, worst_difference(single, multi) == 0.0_dp .and. .not. wrapped%is_explicit() .and. &
                   maxval(multi%iterations) > 0 .and. maxval(multi%iterations) <= 50, &
                   'exact, implicit: u, F, delta bit for bit, iterations counted')
    end subroutine test_wrapped_implicit

    !> The exact scheme's W0 on the points is the engine's per-mode shares of w0 weighed by the
    !> mode shapes: one point of unit shape gives the engine's own w0 (their sum); the scheme
    !> comes from the registry, `modal` being `recursive`.
    subroutine test_mode_shares(error)
        type(test_error), allocatable, intent(out) :: error

        type(point_modes) :: description
        type(modal_green_matrix) :: multi_conv
        type(recursive_convolver) :: engine
        type(error_type), allocatable :: failure

        description = sdof_description()
        call new_modal_green_matrix(description, dt, 'exact', multi_conv, failure)
        call check(error, .not. allocated(failure), 'new_modal_green_matrix failed')
        if (allocated(error)) return
        engine = new_modal_engine(method_scheme('exact'), description%modes, dt)
        call check(error, method_scheme('exact') == scheme_first_order .and. engine%name == 'exact' .and. &
                   multi_conv%name == 'exact', 'exact: the first-order hold, by the registry''s scheme')
        if (allocated(error)) return
        call check(error, multi_conv%weight0(1, 1), engine%instant_weight(), 'W0 = w0 of the engine', &
                   thr=1.0e-15_dp*abs(engine%instant_weight()))
        if (allocated(error)) return
        call check(error, sum(engine%mode_weight) == engine%instant_weight(), 'w0 is the sum of the per-mode shares')
        if (allocated(error)) return
        engine = new_modal_engine(method_scheme('modal'), description%modes, dt)
        call check(error, method_scheme('modal') == method_scheme('recursive') .and. engine%name == 'recursive', &
                   'modal is the rectangle rule of recursive')
    end subroutine test_mode_shares

    !> The same scene with sampled tables from the same mode: multi-point against direct.
    subroutine test_one_point_sampled(error)
        type(test_error), allocatable, intent(out) :: error

        type(sampled_green_matrix) :: multi_conv
        type(direct_convolver) :: direct
        type(multi_contact_response) :: multi
        type(contact_response) :: single
        type(error_type), allocatable :: failure
        real(dp), allocatable :: table(:, :, :), kernel(:)
        real(dp) :: road(0:n_steps - 1, 1), tail_multi, tail_single

        road = sine_column()
        ! Truncated at 1 % by both rules, so that the tables have the same N_g < the run.
        call sample_green_matrix(sdof_description(), dt, 0.01_dp, 4*n_steps, table, tail_multi)
        call sample_kernel(sdof_modes(mass, stiffness, xi), dt, 0.01_dp, 4*n_steps, kernel, tail_single)
        call note('N_g', real(ubound(table, 1), dp))
        call check(error, ubound(table, 1) == ubound(kernel, 1) .and. ubound(kernel, 1) < 4*n_steps - 1, &
                   'the 1 % rule: the same N_g for one point, shorter than the run')
        if (allocated(error)) return
        call check(error, maxval(abs(table(:, 1, 1) - kernel)), 0.0_dp, 'g table against sample_kernel', &
                   thr=1.0e-15_dp*maxval(abs(kernel)))
        if (allocated(error)) return
        call check(error, tail_multi, tail_single, 'neglected tail', thr=1.0e-15_dp)
        if (allocated(error)) return
        call new_sampled_green_matrix(table, dt, multi_conv, failure)
        call check(error, .not. allocated(failure), 'new_sampled_green_matrix failed')
        if (allocated(error)) return
        call run_or_stop(multi_conv, [power_law(k_contact, exponent)], road, [preload], multi)
        direct = new_direct_convolver(kernel, dt)
        call run_contact(direct, power_law(k_contact, exponent), road(:, 1), preload, single)
        call note('max relative difference', worst_difference(single, multi))
        ! The same N_g products summed in two orders (one dot product per step, and direct's
        ! blocks): round-off of the order of eps per term, at most N_g*eps relative (5e-13 here).
        call check(error, worst_difference(single, multi), 0.0_dp, 'u, F, delta: sampled against direct', &
                   thr=ubound(kernel, 1)*epsilon(1.0_dp))
    end subroutine test_one_point_sampled

    !> The first-order hold: per-mode W0 summed equals the engine's w0, histories equal.
    subroutine test_one_point_exact(error)
        type(test_error), allocatable, intent(out) :: error

        type(modal_green_matrix) :: multi_conv
        type(recursive_convolver) :: single_conv
        type(random_stream) :: stream
        type(modal_set) :: modes
        real(dp) :: q, u(1), worst, peak
        integer :: n

        modes = sdof_modes(mass, stiffness, xi)
        multi_conv = modal_matrix(sdof_description(), 'exact')
        single_conv = new_exact_convolver(modes, dt)
        call note('W0*K', multi_conv%weight0(1, 1)*stiffness)
        call check(error, multi_conv%weight0(1, 1), single_conv%instant_weight(), 'W0 against w0', &
                   thr=1.0e-15_dp, rel=.true.)
        if (allocated(error)) return
        call check(error, .not. multi_conv%is_explicit(), 'exact is implicit')
        if (allocated(error)) return
        stream = random_stream(7)
        worst = 0.0_dp
        peak = 0.0_dp
        do n = 1, n_steps
            call multi_conv%history(u)
            worst = max(worst, abs(u(1) - single_conv%history()))
            peak = max(peak, abs(u(1)))
            q = stream%between(-10.0_dp, 10.0_dp)
            call multi_conv%push([q])
            call single_conv%push(merge(0.5_dp, 1.0_dp, n == 1)*q)  ! the multi-point push halves step 0's
        end do
        call note('max|u_multi - u_single|/max|u|', worst/peak)
        call check(error, worst, 0.0_dp, 'history under random loads', thr=1.0e-15_dp*peak)
    end subroutine test_one_point_exact

    !> One point on the tyre (all modes to 1 kHz) against the single-point loop on the modes
    !> of its driving-point response, r_k*phi_k^2.
    subroutine test_driving_point(error)
        type(test_error), allocatable, intent(out) :: error

        type(point_modes) :: description
        type(modal_green_matrix) :: multi_conv
        type(multi_contact_response) :: multi
        type(contact_response) :: single
        type(modal_set) :: driving
        type(recursive_convolver) :: single_conv
        type(power_law), allocatable :: laws(:)
        real(dp), allocatable :: preloads(:)
        real(dp) :: road(0:n_steps - 1, 1)

        description = tyre_description([0.5_dp*default_tyre%length + 0.03_dp], 1000.0_dp)
        call hertz_points(1, 1000.0_dp, 1.0e-3_dp, laws, preloads)
        road = travelling_road([0.0_dp], 2.0e-4_dp, 10.0_dp, n_steps)
        multi_conv = modal_matrix(description, 'recursive')
        call run_or_stop(multi_conv, laws, road, preloads, multi)
        driving = description%modes
        driving%residue = driving%residue*description%shape(1, :)**2
        single_conv = new_recursive_convolver(driving, dt)
        call run_contact(single_conv, laws(1), road(:, 1), preloads(1), single)
        call note('N_m', real(description%modes%n_modes(), dp))
        call note('max relative difference', worst_difference(single, multi))
        call check(error, worst_difference(single, multi), 0.0_dp, 'u, F, delta against the driving-point modes', &
                   thr=1.0e-12_dp)
    end subroutine test_driving_point

    ! ---- modal against sampled -----------------------------------------------------------

    subroutine test_modal_sampled(error)
        type(test_error), allocatable, intent(out) :: error

        integer, parameter :: n_c = 4, n_run = 3000
        type(point_modes) :: description
        type(modal_green_matrix) :: modal
        type(sampled_green_matrix) :: sampled
        type(multi_contact_response) :: by_modes, by_table
        type(error_type), allocatable :: failure
        type(power_law), allocatable :: laws(:)
        real(dp), allocatable :: table(:, :, :), preloads(:)
        real(dp) :: positions(n_c), tail, worst, peak

        positions = contact_positions(0.5_dp*default_tyre%length, 0.1_dp, n_c)
        description = tyre_description(positions, 500.0_dp)
        call sample_green_matrix(description, dt, 0.0_dp, n_run, table, tail)
        call check(error, ubound(table, 1) == n_run - 1 .and. tail == 0.0_dp, 'tol = 0: the table covers the run')
        if (allocated(error)) return
        call check(error, all(table == reshape(table, shape(table), order=[1, 3, 2])), 'g_ij = g_ji exactly')
        if (allocated(error)) return
        call check(error, maxval(abs(table(7, :, :) - description%green(spread([1, 2, 3, 4], 2, n_c), &
                                                                         spread([1, 2, 3, 4], 1, n_c), 7*dt))), &
                   0.0_dp, 'table against point_modes%green', thr=1.0e-14_dp*maxval(abs(table)))
        if (allocated(error)) return
        modal = modal_matrix(description, 'recursive')
        call new_sampled_green_matrix(table, dt, sampled, failure)
        if (allocated(failure)) error stop 'test_modal_sampled: '//failure%message
        call compare_random(modal, sampled, n_run, worst, peak)
        call note('random loads: max|du|/max|u|', worst/peak)
        call check(error, worst, 0.0_dp, 'histories under random loads', thr=1.0e-12_dp*peak)
        if (allocated(error)) return
        call hertz_points(n_c, 300.0_dp, 5.0e-4_dp, laws, preloads)
        call run_or_stop(modal, laws, travelling_road(positions, 1.0e-3_dp, 10.0_dp, n_run), preloads, by_modes)
        call run_or_stop(sampled, laws, travelling_road(positions, 1.0e-3_dp, 10.0_dp, n_run), preloads, by_table)
        worst = maxval(abs(by_modes%force - by_table%force))/maxval(by_table%force)
        call note('contact run: max|dF|/max F', worst)
        call check(error, worst, 0.0_dp, 'contact forces, modal against sampled', thr=1.0e-12_dp)
        if (allocated(error)) return
        call sample_green_matrix(description, dt, 0.01_dp, huge(1), table, tail)
        call note('1 % rule: N_g', real(ubound(table, 1), dp))
        call note('tail', tail)
        call check(error, tail < 0.01_dp .and. ubound(table, 1) < n_run, '1 % rule: tail below 1 % of max|g|')
    end subroutine test_modal_sampled

    !> Push the same random loads (N, in [-10, 10] at each point) into both; largest
    !> difference of the histories and largest history.
    subroutine compare_random(a, b, n_run, worst, peak)
        class(multipoint_convolver), intent(inout) :: a, b
        integer, intent(in) :: n_run
        real(dp), intent(out) :: worst, peak

        type(random_stream) :: stream
        real(dp) :: q(a%n_points()), u_a(a%n_points()), u_b(a%n_points())
        integer :: n, i

        stream = random_stream(11)
        call a%reset()
        call b%reset()
        worst = 0.0_dp
        peak = 0.0_dp
        do n = 1, n_run
            call a%history(u_a)
            call b%history(u_b)
            worst = max(worst, maxval(abs(u_a - u_b)))
            peak = max(peak, maxval(abs(u_b)))
            do i = 1, size(q)
                q(i) = stream%between(-10.0_dp, 10.0_dp)
            end do
            call a%push(q)
            call b%push(q)
        end do
    end subroutine compare_random

    ! ---- symmetry, statics, unilateral -----------------------------------------------------

    !> Six points mirrored about mid-belt, a road symmetric in x: F_i = F_(7-i) at all times.
    subroutine test_symmetry(error)
        type(test_error), allocatable, intent(out) :: error

        integer, parameter :: n_c = 6
        character(len=*), parameter :: schemes(2) = ['recursive', 'exact    ']
        type(point_modes) :: description
        type(modal_green_matrix) :: conv
        type(multi_contact_response) :: response
        type(power_law), allocatable :: laws(:)
        real(dp), allocatable :: preloads(:)
        real(dp) :: positions(n_c), road(0:n_steps - 1, n_c), centre, asymmetry
        integer :: i, n, s

        centre = 0.5_dp*default_tyre%length
        positions = contact_positions(centre, 0.12_dp, n_c)
        do i = 1, n_c
            road(:, i) = [(1.0e-3_dp*sin(1000.0_dp*n*dt)*cos(2.0_dp*pi*(positions(i) - centre)/0.1_dp), &
                           n=0, n_steps - 1)]
        end do
        road(:, n_c/2 + 1:) = road(:, n_c/2:1:-1)
        description = tyre_description(positions, 1000.0_dp)
        call hertz_points(n_c, 200.0_dp, 4.0e-4_dp, laws, preloads)
        do s = 1, 2
            conv = modal_matrix(description, trim(schemes(s)))
            call run_or_stop(conv, laws, road, preloads, response)
            asymmetry = maxval(abs(response%force - response%force(:, n_c:1:-1)))/maxval(response%force)
            call note(trim(schemes(s))//': max|F_i - F_mirror|/max F', asymmetry)
            call note('samples with F = 0', real(count(response%force == 0.0_dp), dp))
            call check(error, asymmetry, 0.0_dp, trim(schemes(s))//': mirrored forces', thr=1.0e-12_dp)
            if (allocated(error)) return
            ! Not symmetric by accident: the points carry different forces, and lose contact.
            call check(error, maxval(abs(response%force(:, 1) - response%force(:, 3))) > 1.0e-3_dp &
                       *maxval(response%force) .and. count(response%force == 0.0_dp) > 0, &
                       trim(schemes(s))//': the points differ and lose contact')
            if (allocated(error)) return
        end do
    end subroutine test_symmetry

    !> Linear springs k_c, a road step d at every point from t = 0: after the transient,
    !> (I/k_c + G(0)) dF = d*[1 .. 1], G(0)_ij = sum_k phi_k(x_i)*phi_k(x_j)/omega_k^2 written
    !> out from the beam's closed form and solved by the SVD (dgelsd), not by the loop's dgesv.
    subroutine test_static(error)
        type(test_error), allocatable, intent(out) :: error

        integer, parameter :: n_c = 5, n_run = 15000
        real(dp), parameter :: k_c = 2.0e5_dp, f0 = 400.0_dp, step = 2.0e-4_dp
        type(tyre_belt) :: tyre
        type(modal_green_matrix) :: conv
        type(multi_contact_response) :: response
        type(error_type), allocatable :: failure
        real(dp) :: positions(n_c), road(0:n_run - 1, n_c), g0(n_c, n_c), system(n_c, n_c), change(n_c)
        real(dp) :: worst
        integer :: i, n_m

        positions = contact_positions(0.5_dp*tyre%length, 0.1_dp, n_c)
        n_m = tyre_mode_count(tyre, 300.0_dp)
        g0 = static_compliance(tyre, positions, n_m)
        system = g0
        do i = 1, n_c
            system(i, i) = system(i, i) + 1.0_dp/k_c
        end do
        call least_squares(system, [(step, i=1, n_c)], change, failure)
        if (allocated(failure)) error stop 'test_static: '//failure%message
        road(:, :) = step
        conv = modal_matrix(tyre_description(positions, 300.0_dp), 'exact')
        call run_or_stop(conv, [(power_law(k_c, 1.0_dp), i=1, n_c)], road, [(f0, i=1, n_c)], response)
        worst = maxval(abs(response%force(n_run - 1, :) - f0 - change))/maxval(abs(change))
        call note('N_m', real(n_m, dp))
        call note('max|dF - closed form|/max|dF|', worst)
        call note('max Newton iterations', real(maxval(response%iterations), dp))
        call check(error, worst, 0.0_dp, 'static force change', thr=1.0e-10_dp)
        if (allocated(error)) return
        worst = maxval(abs(response%displacement(n_run - 1, :) - matmul(g0, change)))/maxval(abs(matmul(g0, change)))
        call note('max|u - G(0)*dF|/max|u|', worst)
        call check(error, worst, 0.0_dp, 'static displacement', thr=1.0e-10_dp)
        if (allocated(error)) return
        call check(error, maxval(response%iterations) >= 1, 'W0 /= 0: the forces were solved by Newton')
    end subroutine test_static

    !> G(0)_ij = sum_{k<=n_m} phi_k(x_i)*phi_k(x_j)/omega_k^2, phi_k = sqrt(2/(rhoA*L))*sin(k*pi*x/L).
    function static_compliance(tyre, x, n_m) result(g0)
        type(tyre_belt), intent(in) :: tyre
        real(dp), intent(in) :: x(:)
        integer, intent(in) :: n_m
        real(dp) :: g0(size(x), size(x))

        real(dp) :: phi(size(x)), beta, omega2
        integer :: k

        g0 = 0.0_dp
        do k = 1, n_m
            beta = k*pi/tyre%length
            omega2 = (tyre%bending_stiffness*beta**4 + tyre%tension*beta**2 + tyre%foundation_stiffness) &
                     /tyre%mass_per_length
            phi = sqrt(2.0_dp/(tyre%mass_per_length*tyre%length))*sin(beta*x)
            g0 = g0 + spread(phi, 2, size(x))*spread(phi, 1, size(x))/omega2
        end do
    end function static_compliance

    !> Nine points over a rough road of 1 mm against a static compression of 0.2 mm: every
    !> point both carries load and lifts off, some while others are in contact.
    subroutine test_unilateral(error)
        type(test_error), allocatable, intent(out) :: error

        integer, parameter :: n_c = 9, n_run = 3000
        character(len=*), parameter :: schemes(2) = ['recursive', 'exact    ']
        type(modal_green_matrix) :: conv
        type(multi_contact_response) :: response
        type(power_law), allocatable :: laws(:)
        real(dp), allocatable :: preloads(:)
        real(dp) :: positions(n_c), mismatch, scale
        integer :: s, i, mixed

        positions = contact_positions(0.5_dp*default_tyre%length, 0.15_dp, n_c)
        call hertz_points(n_c, 100.0_dp, 2.0e-4_dp, laws, preloads)
        do s = 1, 2
            conv = modal_matrix(tyre_description(positions, 1000.0_dp), trim(schemes(s)))
            call run_or_stop(conv, laws, travelling_road(positions, 1.0e-3_dp, 10.0_dp, n_run), preloads, response)
            do i = 1, n_c
                call check(error, all(response%force(:, i) >= 0.0_dp) .and. &
                           all((response%force(:, i) == 0.0_dp) .eqv. (response%compression(:, i) <= 0.0_dp)), &
                           trim(schemes(s))//': F >= 0, and F = 0 exactly where delta <= 0, at point '//int_text(i))
                if (allocated(error)) return
                call check(error, count(response%force(:, i) == 0.0_dp) > 50 .and. &
                           count(response%force(:, i) > 0.0_dp) > 50, &
                           trim(schemes(s))//': point '//int_text(i)//' both loses and regains contact')
                if (allocated(error)) return
            end do
            mixed = count(any(response%force > 0.0_dp, dim=2) .and. any(response%force == 0.0_dp, dim=2))
            call note(trim(schemes(s))//': steps with mixed contact', real(mixed, dp))
            call check(error, mixed > 100, trim(schemes(s))//': steps where some points touch and others do not')
            if (allocated(error)) return
            scale = max(maxval(abs(response%road)), maxval(abs(response%displacement)))
            mismatch = maxval(abs(response%compression - (laws(1)%compression(preloads(1)) + response%road &
                                                          - response%displacement)))/scale
            call note(trim(schemes(s))//': max|delta - (delta0 + u_r - u)|/scale', mismatch)
            call note(trim(schemes(s))//': max Newton iterations', real(maxval(response%iterations), dp))
            call check(error, mismatch, 0.0_dp, trim(schemes(s))//': compressions consistent', thr=1.0e-10_dp)
            if (allocated(error)) return
        end do
    end subroutine test_unilateral

    ! ---- failures ----------------------------------------------------------------------------

    subroutine test_failures(error)
        type(test_error), allocatable, intent(out) :: error

        integer, parameter :: n_c = 9, n_run = 500
        type(modal_green_matrix) :: conv
        type(multi_contact_response) :: response
        type(newton_options) :: options
        type(error_type), allocatable :: failure
        type(power_law), allocatable :: laws(:)
        real(dp), allocatable :: preloads(:)
        real(dp) :: positions(n_c)

        ! Newton limited to one iteration cannot reach 1e-12 on Hertz springs.
        positions = contact_positions(0.5_dp*default_tyre%length, 0.15_dp, n_c)
        call hertz_points(n_c, 100.0_dp, 2.0e-4_dp, laws, preloads)
        conv = modal_matrix(tyre_description(positions, 1000.0_dp), 'exact')
        options%max_iterations = 1
        call run_multi_contact(conv, laws, travelling_road(positions, 1.0e-3_dp, 10.0_dp, n_run), preloads, &
                               response, failure, options)
        call check(error, allocated(failure), 'no error with max_iterations = 1')
        if (allocated(error)) return
        call check(error, index(failure%message, 'implicit contact step did not converge at step ' &
                                //int_text(size(response%time))//' (t = ') == 1 .and. index(failure%message, &
                                's) at point ') > 0 .and. index(failure%message, 'after 1 iterations') > 0 &
                   .and. failure%stat == stat_numerical, 'Newton message and rows kept: '//failure%message)
        if (allocated(error)) return
        ! Explicit scheme, contact 1e5 times stiffer than the oscillator: unstable, caught.
        conv = modal_matrix(sdof_description(), 'recursive')
        call run_multi_contact(conv, [power_law(1.0e11_dp, 1.0_dp)], sine_column(), [preload], response, failure)
        call check(error, allocated(failure), 'no error for a diverging run')
        if (allocated(error)) return
        call note('steps kept', real(size(response%time), dp))
        call check(error, index(failure%message, 'contact run diverged at step '//int_text(size(response%time))) &
                   == 1 .and. index(failure%message, 'at point') == 0 .and. index(failure%message, 'omega_c') > 0 .and. &
                   size(response%time) < n_steps .and. all(abs(response%displacement) <= 1.0_dp), &
                   'divergence message and rows kept: '//failure%message)
        if (allocated(error)) return
        call run_multi_contact(conv, [power_law(), power_law()], sine_column(), [preload], response, failure)
        call check(error, allocated(failure), 'no error for inconsistent sizes')
        if (allocated(error)) return
        call check(error, failure%stat == stat_input .and. index(failure%message, 'the laws 2') > 0, &
                   'size message: '//failure%message)
    end subroutine test_failures

    ! ---- tyre ------------------------------------------------------------------------------

    subroutine test_tyre(error)
        type(test_error), allocatable, intent(out) :: error

        type(tyre_belt) :: tyre
        type(point_modes) :: description
        type(error_type), allocatable :: failure
        real(dp) :: x(3), omega(200), f(3), mass_k, worst, stiffness_point
        integer :: k, n_m, j

        x = [0.1_dp, 0.9_dp, 1.7_dp]
        call tyre_modes(tyre, x, 2000.0_dp, description, failure)
        call check(error, .not. allocated(failure), 'tyre_modes failed with the defaults')
        if (allocated(error)) return
        n_m = description%modes%n_modes()
        do k = 1, size(omega)
            omega(k) = sqrt((tyre%bending_stiffness*(k*pi/tyre%length)**4 + tyre%tension*(k*pi/tyre%length)**2 &
                             + tyre%foundation_stiffness)/tyre%mass_per_length)
        end do
        call note('N_m to 2 kHz', real(n_m, dp))
        call check(error, omega(n_m) <= 2.0_dp*pi*2000.0_dp .and. omega(n_m + 1) > 2.0_dp*pi*2000.0_dp, &
                   'f_max rule: all modes up to 2 kHz and none above')
        if (allocated(error)) return
        ! |lambda_k| = omega_k for lambda = -xi*omega + i*omega*sqrt(1 - xi^2).
        worst = maxval(abs(abs(description%modes%pole) - omega(1:n_m))/omega(1:n_m))
        call note('max relative error of omega_k', worst)
        call check(error, worst, 0.0_dp, 'omega_k against the closed form', thr=1.0e-14_dp)
        if (allocated(error)) return
        worst = 0.0_dp
        do k = 1, n_m
            worst = max(worst, maxval(abs(description%shape(:, k) &
                                          - sqrt(2.0_dp/(tyre%mass_per_length*tyre%length))*sin(k*pi*x/tyre%length))))
        end do
        call check(error, worst, 0.0_dp, 'phi_k(x_i) against the closed form', thr=1.0e-14_dp)
        if (allocated(error)) return
        ! Unit modal mass by the midpoint rule, exact for sin^2 of k < 2000 half-waves.
        mass_k = 0.0_dp
        do j = 1, 2000
            mass_k = mass_k + tyre%mass_per_length*(2.0_dp/(tyre%mass_per_length*tyre%length)) &
                     *sin(7*pi*(j - 0.5_dp)/2000)**2*tyre%length/2000
        end do
        call check(error, mass_k, 1.0_dp, 'modal mass of mode 7', thr=1.0e-13_dp)
        if (allocated(error)) return
        f = omega(1:3)/(2.0_dp*pi)
        call note('f_1', f(1))
        call note('f_2', f(2))
        call note('f_3', f(3))
        call check(error, abs(f(1) - 86.0_dp) < 0.5_dp .and. abs(f(2) - 92.0_dp) < 0.5_dp .and. &
                   abs(f(3) - 101.0_dp) < 0.5_dp, 'defaults: first resonances at 86, 92, 101 Hz as documented')
        if (allocated(error)) return
        ! Mid-belt: sum_k phi_k(L/2)^2/omega_k^2 = sum_k 2*sin(k*pi/2)^2/(L*(EI*b^4 + T*b^2 + s)).
        stiffness_point = 1.0_dp/sum([(2.0_dp*sin(k*pi/2)**2/(tyre%length*(tyre%bending_stiffness &
                                       *(k*pi/tyre%length)**4 + tyre%tension*(k*pi/tyre%length)**2 &
                                       + tyre%foundation_stiffness)), k=1, 20001)])
        call note('static point stiffness [N/m]', stiffness_point)
        ! The belt is long against the decay length sqrt(T/s) = 0.13 m: the infinite beam's
        ! compliance (1/pi)*int_0^inf db/(EI*b^4 + T*b^2 + s), summed by the midpoint rule.
        call check(error, stiffness_point, 1.0_dp/infinite_beam_compliance(tyre), &
                   'mid-belt static stiffness against the infinite beam', thr=1.0e-4_dp, rel=.true.)
        if (allocated(error)) return
        call check(error, stiffness_point, 2.1e5_dp, 'defaults: static point stiffness 2.1e5 N/m as documented', &
                   thr=0.01_dp, rel=.true.)
        if (allocated(error)) return
        call tyre_modes(tyre, [2.0_dp], 2000.0_dp, description, failure)
        call check(error, allocated(failure), 'no error for a point off the belt')
        if (allocated(error)) return
        call tyre_modes(tyre, x, 50.0_dp, description, failure)
        call check(error, allocated(failure), 'no error without a mode below f_max')
        if (allocated(error)) return
        call check(error, tyre_band(20.0_dp, 0.02_dp, 5.0e-5_dp), 2000.0_dp, 'band rule', thr=1.0e-9_dp)
    end subroutine test_tyre

    !> (1/pi)*int_0^inf db/(EI*b^4 + T*b^2 + s) [m/N] by the midpoint rule on [0, 2000] 1/m
    !> (the tail beyond is below 1/(3*EI*2000^3) = 8e-12 m/N, against 5e-6).
    real(dp) function infinite_beam_compliance(tyre) result(compliance)
        type(tyre_belt), intent(in) :: tyre

        real(dp), parameter :: h = 0.01_dp
        real(dp) :: b
        integer :: i

        compliance = 0.0_dp
        do i = 0, 199999
            b = (i + 0.5_dp)*h
            compliance = compliance + h/(tyre%bending_stiffness*b**4 + tyre%tension*b**2 + tyre%foundation_stiffness)
        end do
        compliance = compliance/pi
    end function infinite_beam_compliance

    ! ---- road files ------------------------------------------------------------------------

    !> data/road_sample.dat against the recipe of its header, and the interpolation.
    subroutine test_road_sample(error)
        type(test_error), allocatable, intent(out) :: error

        type(road_file) :: road
        type(error_type), allocatable :: failure
        type(random_stream) :: stream
        real(dp), allocatable :: heights(:, :)
        real(dp) :: frequency(490), amplitude(490), phase(490), worst, expected
        integer :: j, i

        call read_road_file('data/road_sample.dat', road, failure)
        call check(error, .not. allocated(failure), 'the sample road file reads')
        if (allocated(error)) return
        call note('points', real(size(road%x), dp))
        call note('rms height [m]', sqrt(sum(road%height**2)/size(road%height)))
        call check(error, size(road%x) == 5001 .and. road%x(5001) == 10.0_dp, '5001 points over 10 m')
        if (allocated(error)) return
        stream = random_stream(8608)
        do j = 1, 490
            frequency(j) = 2.0_dp + (j - 0.5_dp)*0.2_dp
            amplitude(j) = sqrt(2.0_dp*16.0e-6_dp*(frequency(j)/0.1_dp)**(-2)*0.2_dp)
            phase(j) = 2.0_dp*pi*stream%uniform()
        end do
        worst = 0.0_dp
        do i = 1, 5001, 500
            expected = sum(amplitude*cos(2.0_dp*pi*frequency*road%x(i) + phase))
            worst = max(worst, abs(road%height(i) - expected))
        end do
        call note('max|h_file - h_header| [m]', worst)
        ! Eight significant digits of heights below 1.5 mm.
        call check(error, worst, 0.0_dp, 'heights follow the header''s formula', thr=1.0e-10_dp)
        if (allocated(error)) return
        call check(error, road%height_at(0.5_dp*(road%x(10) + road%x(11))), &
                   0.5_dp*(road%height(10) + road%height(11)), 'midpoint interpolation', thr=1.0e-18_dp)
        if (allocated(error)) return
        call sample_road(road, road_travel(x=[0.1_dp, 0.2_dp], speed=20.0_dp, dt=1.0e-4_dp), 4001, heights, failure)
        call check(error, .not. allocated(failure), 'a run within the file samples')
        if (allocated(error)) return
        call check(error, heights(4000, 2), road%height_at(8.2_dp), 'x_i + V*t_n', thr=1.0e-18_dp)
    end subroutine test_road_sample

    subroutine test_road_errors(error)
        type(test_error), allocatable, intent(out) :: error

        character(len=*), parameter :: path = scratch//'/test_road.dat'
        type(road_file) :: road
        type(error_type), allocatable :: failure
        real(dp), allocatable :: heights(:, :)

        call expect(error, path, [character(len=30) :: '# x height', '0.0 1e-4', '0.2 2e-4', '0.1 3e-4'], &
                    path//':4: expected x above 0.2 m (x must increase), found 0.1')
        if (allocated(error)) return
        call expect(error, path, [character(len=30) :: '0.0 1e-4', '0.1 abc'], &
                    path//':2: column 2 (height): expected a number, found "abc"')
        if (allocated(error)) return
        call expect(error, path, [character(len=30) :: '0.0 1e-4', 'garbage'], &
                    path//':2: expected 2 columns (x [m], height [m]), found 1: "garbage"')
        if (allocated(error)) return
        call expect(error, path, [character(len=30) :: '0.0 1e-4 5', '0.1 0'], &
                    path//':1: expected 2 columns (x [m], height [m]), found 3')
        if (allocated(error)) return
        call expect(error, path, [character(len=30) :: '# one line', '0.0 NaN'], &
                    path//':2: column 2 (height): expected a finite number, found "NaN"')
        if (allocated(error)) return
        call expect(error, path, [character(len=30) :: '# one line', '0.0 1e-4'], &
                    path//': expected at least 2 data lines (x [m], height [m]), found 1')
        if (allocated(error)) return
        call read_road_file(scratch//'/no_such_road.dat', road, failure)
        call check(error, allocated(failure), 'no error for a missing file')
        if (allocated(error)) return
        call check(error, index(failure%message, scratch//'/no_such_road.dat: cannot open') == 1, &
                   'missing file: '//failure%message)
        if (allocated(error)) return
        call read_road_file('data/road_sample.dat', road, failure)
        call sample_road(road, road_travel(x=[0.0_dp], speed=20.0_dp, dt=1.0e-4_dp), 10000, heights, failure)
        call check(error, allocated(failure), 'no error for a run beyond the file')
        if (allocated(error)) return
        call check(error, index(failure%message, 'data/road_sample.dat: expected a road from x = 0') == 1 &
                   .and. index(failure%message, '(the run), found 0') > 0, 'range message: '//failure%message)
    end subroutine test_road_errors

    !> Write `lines` to `path`, read it as a road, and require an error containing `expected`.
    subroutine expect(error, path, lines, expected)
        type(test_error), allocatable, intent(out) :: error
        character(len=*), intent(in) :: path, lines(:), expected

        type(road_file) :: road
        type(error_type), allocatable :: failure, ignored
        integer :: unit, j

        call make_directory(scratch, ignored)
        open (newunit=unit, file=path, status='replace', action='write')
        do j = 1, size(lines)
            write (unit, '(a)') trim(lines(j))
        end do
        close (unit)
        call read_road_file(path, road, failure)
        call check(error, allocated(failure), 'no error for a file expected to give "'//expected//'"')
        if (allocated(error)) return
        call check(error, index(failure%message, expected) == 1 .and. failure%stat == stat_input, &
                   'message "'//failure%message//'" does not start with "'//expected//'"')
    end subroutine expect

    ! ---- output and cost -----------------------------------------------------------------------

    subroutine test_write(error)
        type(test_error), allocatable, intent(out) :: error

        character(len=*), parameter :: path = scratch//'/test_multi.dat'
        type(modal_green_matrix) :: conv
        type(multi_contact_response) :: response
        type(error_type), allocatable :: failure
        type(power_law), allocatable :: laws(:)
        real(dp), allocatable :: preloads(:), table(:, :)
        integer, allocatable :: line_of(:)
        real(dp) :: positions(3)

        positions = contact_positions(0.9_dp, 0.06_dp, 3)
        call hertz_points(3, 100.0_dp, 2.0e-4_dp, laws, preloads)
        conv = modal_matrix(tyre_description(positions, 500.0_dp), 'exact')
        call run_or_stop(conv, laws, travelling_road(positions, 1.0e-3_dp, 10.0_dp, 50), preloads, response)
        call make_directory(scratch, failure)
        call write_multi_contact(path, 'test', positions, response, failure)
        call check(error, .not. allocated(failure), 'write_multi_contact failed')
        if (allocated(error)) return
        call read_columns(path, [character(len=9) :: 't', 'x', 'u_road', 'u', 'f_contact', 'delta', 'f_total'], &
                          ['s', 'm', 'm', 'm', 'N', 'm', 'N'], table, line_of, failure)
        call check(error, .not. allocated(failure), 'the file reads as 7 columns')
        if (allocated(error)) return
        call check(error, size(table, 1) == 150 .and. table(59, 1) == response%time(19) .and. &
                   table(59, 2) == positions(2) .and. table(59, 5) == response%force(19, 2) .and. &
                   table(59, 7) == response%total_force(19), 'row (t_19, x_2) holds that step and point')
        if (allocated(error)) return
        call check(error, maxval(abs(response%total_force - sum(response%force, dim=2))), 0.0_dp, &
                   'total force is the sum over the points', thr=0.0_dp)
    end subroutine test_write

end module test_multicontact_mod
