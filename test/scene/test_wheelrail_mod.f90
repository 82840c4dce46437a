!> A wheel on a rail: the rail's closed-form receptance against a numerical wavenumber
!> integral and Hetenyi's static stiffness, the Timoshenko rail against its Euler-Bernoulli
!> limit, and bad track parameters refused; the wheel from a pyuff-written universal file of
!> modes (tools/make_wheel_modes.py) against the mass on its suspension in closed form.
module test_wheelrail_mod
    use, intrinsic :: iso_fortran_env, only: dp => real64
    use testsuite_mod, only: test_error, unittest_type, new_unittest, check, note
    use greenconv_core_error, only: error_type
    use greenconv_model_rail, only: rail_track, wheel_mass, wheel_from_modes, hertz_constant, hertz_tangent, &
                                   wheel_rail_frf
    use greenconv_model_frf, only: frf_type, frf_grid
    use greenconv_ident_lsce, only: impulse_from_frf
    use greenconv_ident_structure, only: structure_model, structure_from_samples
    use greenconv_conv_convolver, only: convolver
    use greenconv_conv_builder, only: make_convolver
    use greenconv_contact_single, only: contact_law, contact_options, contact_response, run_contact
    use greenconv_core_error, only: stat_input
    use greenconv_scene_read_input, only: scene_type
    use greenconv_scene_run_runner, only: run_scene
    use greenconv_io_columns, only: read_columns
    use scene_text_mod, only: read_scene_text, write_text
    use greenconv_scene_sweep, only: run_sweep
    use fixture_files_mod, only: read_bands
    use greenconv_contact_law_power, only: power_law
    implicit none
    private

    public :: collect_wheelrail

    real(dp), parameter :: pi = acos(-1.0_dp)
    !> A UIC60-like rail in round numbers on a pad of 300 MN/m per 0.6 m sleeper spacing.
    real(dp), parameter :: ei = 6.4e6_dp, m_rail = 60.0_dp, s_pad = 5.0e8_dp, c_pad = 5.0e4_dp
    !> A wheel's modes written by pyuff (tools/make_wheel_modes.py).
    character(len=*), parameter :: wheel_file = 'test/data/uff/wheel_modes.uff'

contains

    !> Tests of greenconv_model_rail and the wheel_rail scenes.
    subroutine collect_wheelrail(testsuite)
        type(unittest_type), allocatable, intent(out) :: testsuite(:)

        testsuite = [new_unittest('rail at rest: Hetenyi''s beta/(2s)', test_static), &
                     new_unittest('Euler-Bernoulli rail against the wavenumber integral', test_integral_eb), &
                     new_unittest('two-layer support against the wavenumber integral', test_integral_two_layer), &
                     new_unittest('Timoshenko rail against the wavenumber integral', test_integral_timoshenko), &
                     new_unittest('Timoshenko rail tends to Euler-Bernoulli', test_timoshenko_limit), &
                     new_unittest('free rail: -(1+i)/(4 EI k^3)', test_free_rail), &
                     new_unittest('Hertz constant and its tangent', test_hertz), &
                     new_unittest('bad track and wheel values refused', test_bad_values), &
                     new_unittest('small sine roughness: time domain = linear model within 2 %', test_linear_limit), &
                     new_unittest('scene: bad track, wheel and a resonance above Nyquist refused', &
                                  test_scene_refusals), &
                     new_unittest('scene: loss of contact reported at large roughness', test_scene_contact_loss), &
                     new_unittest('scene: linear reference beside the run, band for band', test_scene_reference), &
                     new_unittest('scene: auto states its choice on the rail', test_scene_auto), &
                     new_unittest('wheel of a modes file against its closed form', test_wheel_modes), &
                     new_unittest('scene: wheel of a modes file = mass on its suspension', test_scene_wheel_modes), &
                     new_unittest('sweep over the roughness: the linear model scales, the table meets it', &
                                  test_roughness_sweep)]
    end subroutine collect_wheelrail

    !> At omega = 0 the receptance is beta/(2s), beta = (s/(4 EI))^(1/4) (Hetenyi, art. 10).
    subroutine test_static(error)
        type(test_error), allocatable, intent(out) :: error

        type(rail_track) :: track
        complex(dp) :: alpha
        real(dp) :: beta

        track = rail_track(bending=ei, mass=m_rail, pad_stiffness=s_pad, pad_damping=c_pad)
        alpha = track%receptance(0.0_dp)
        beta = (s_pad/(4.0_dp*ei))**0.25_dp
        call check(error, real(alpha, dp), beta/(2.0_dp*s_pad), 'Re alpha(0)', thr=1.0e-14_dp, rel=.true.)
        if (allocated(error)) return
        call check(error, aimag(alpha), 0.0_dp, 'Im alpha(0)', thr=1.0e-14_dp*abs(alpha))
        if (allocated(error)) return
        ! Timoshenko at rest: the same static deflection plus the shear's, no inertia
        track%shear = 1.0e9_dp
        track%rotary = 0.24_dp
        alpha = track%receptance(0.0_dp)
        call check(error, real(alpha, dp), integral(track, 0.0_dp), 'Re alpha(0), Timoshenko', thr=1.0e-8_dp, &
                   rel=.true.)
    end subroutine test_static

    subroutine test_integral_eb(error)
        type(test_error), allocatable, intent(out) :: error

        type(rail_track) :: track

        track = rail_track(bending=ei, mass=m_rail, pad_stiffness=s_pad, pad_damping=c_pad)
        call compare_integral(track, error)
    end subroutine test_integral_eb

    subroutine test_integral_two_layer(error)
        type(test_error), allocatable, intent(out) :: error

        type(rail_track) :: track

        track = rail_track(bending=ei, mass=m_rail, pad_stiffness=s_pad, pad_damping=c_pad, sleeper_mass=270.0_dp, &
                           ballast_stiffness=1.0e8_dp, ballast_damping=1.3e5_dp)
        call compare_integral(track, error)
    end subroutine test_integral_two_layer

    subroutine test_integral_timoshenko(error)
        type(test_error), allocatable, intent(out) :: error

        type(rail_track) :: track

        ! kappa*G*A of a UIC60 rail: G = 81 GPa, A = 7.7e-3 m^2, kappa = 0.4; rho*I = 7850*3.05e-5
        track = rail_track(bending=ei, mass=m_rail, shear=2.5e8_dp, rotary=0.24_dp, pad_stiffness=s_pad, &
                           pad_damping=c_pad, sleeper_mass=270.0_dp, ballast_stiffness=1.0e8_dp, &
                           ballast_damping=1.3e5_dp)
        call compare_integral(track, error)
    end subroutine test_integral_timoshenko

    !> The closed form and the numerical integral from 10 Hz to 5 kHz, within 1e-7 relative.
    subroutine compare_integral(track, error)
        type(rail_track), intent(in) :: track
        type(test_error), allocatable, intent(out) :: error

        real(dp), parameter :: f(7) = [10.0_dp, 100.0_dp, 300.0_dp, 800.0_dp, 1500.0_dp, 3000.0_dp, 5000.0_dp]
        complex(dp) :: closed, numeric
        integer :: i
        character(len=80) :: label

        do i = 1, size(f)
            closed = track%receptance(2.0_dp*pi*f(i))
            numeric = integral_complex(track, 2.0_dp*pi*f(i))
            write (label, '(a,f7.1,a)') '|alpha - integral|/|alpha| at ', f(i), ' Hz'
            call check(error, abs(closed - numeric)/abs(closed), 0.0_dp, trim(label), thr=1.0e-7_dp)
            if (allocated(error)) return
        end do
    end subroutine compare_integral

    !> kappa*G*A -> infinity, rho*I -> 0: the Timoshenko rail's receptance tends to Euler-Bernoulli's.
    subroutine test_timoshenko_limit(error)
        type(test_error), allocatable, intent(out) :: error

        type(rail_track) :: eb, timo
        real(dp) :: omega, gap
        integer :: i

        eb = rail_track(bending=ei, mass=m_rail, pad_stiffness=s_pad, pad_damping=c_pad)
        timo = eb
        timo%shear = 1.0e16_dp
        timo%rotary = 1.0e-12_dp
        do i = 1, 5
            omega = 2.0_dp*pi*10.0_dp**i
            gap = abs(timo%receptance(omega) - eb%receptance(omega))/abs(eb%receptance(omega))
            call check(error, gap, 0.0_dp, 'Timoshenko near its limit against Euler-Bernoulli', thr=1.0e-6_dp)
            if (allocated(error)) return
        end do
        ! and a real shear stiffness softens the rail at high frequency (more than 5 % at 5 kHz)
        timo%shear = 2.5e8_dp
        timo%rotary = 0.24_dp
        omega = 2.0_dp*pi*5000.0_dp
        call check(error, abs(timo%receptance(omega)) > 1.05_dp*abs(eb%receptance(omega)), &
                   'shear and rotary inertia raise |alpha| at 5 kHz')
    end subroutine test_timoshenko_limit

    !> With no support, alpha = -(1 + i)/(4 EI k^3), k^4 = m omega^2/EI (Thompson, ch. 3).
    subroutine test_free_rail(error)
        type(test_error), allocatable, intent(out) :: error

        type(rail_track) :: track
        real(dp) :: omega, k
        complex(dp) :: expected

        track = rail_track(bending=ei, mass=m_rail, pad_stiffness=tiny(1.0_dp), pad_damping=0.0_dp)
        omega = 2.0_dp*pi*1000.0_dp
        k = (m_rail*omega**2/ei)**0.25_dp
        expected = -(1.0_dp, 1.0_dp)/(4.0_dp*ei*k**3)
        call check(error, abs(track%receptance(omega) - expected)/abs(expected), 0.0_dp, 'free rail', &
                   thr=1.0e-12_dp)
    end subroutine test_free_rail

    !> C_H of equal radii against Hertz's spheres written out, and k_H against a difference quotient.
    subroutine test_hertz(error)
        type(test_error), allocatable, intent(out) :: error

        real(dp), parameter :: e = 2.1e11_dp, nu = 0.3_dp, r = 0.4_dp, c = 9.4e10_dp, f0 = 7.5e4_dp
        real(dp) :: expected, d0, h

        ! a sphere of radius r on a flat, F = (4/3) E* sqrt(r) delta^(3/2), E* = E/(2(1 - nu^2)): the
        ! contact of crossed cylinders of equal radii r is that of this sphere (Johnson, 4.2)
        expected = 4.0_dp/3.0_dp*e/(2.0_dp*(1.0_dp - nu**2))*sqrt(r)
        call check(error, hertz_constant(r, r, e, nu), expected, 'C_H of crossed cylinders', &
                   thr=1.0e-14_dp, rel=.true.)
        if (allocated(error)) return
        d0 = (f0/c)**(2.0_dp/3.0_dp)
        h = 1.0e-4_dp*d0
        call check(error, hertz_tangent(c, 1.5_dp, f0), (c*(d0 + h)**1.5_dp - c*(d0 - h)**1.5_dp)/(2.0_dp*h), &
                   'k_H', thr=1.0e-7_dp, rel=.true.)
    end subroutine test_hertz

    subroutine test_bad_values(error)
        type(test_error), allocatable, intent(out) :: error

        type(rail_track) :: track
        type(wheel_mass) :: wheel
        type(error_type), allocatable :: fault

        track = rail_track(bending=ei, mass=m_rail, pad_stiffness=-1.0_dp)
        call track%check(fault)
        call check(error, allocated(fault), 'negative support stiffness refused')
        if (allocated(error)) return
        call check(error, index(fault%message, 'support_stiffness') == 1, 'message names it: '//fault%message)
        if (allocated(error)) return
        wheel = wheel_mass(mass=0.0_dp)
        call wheel%check(fault)
        call check(error, allocated(fault), 'zero wheel mass refused')
        if (allocated(error)) return
        call check(error, index(fault%message, 'wheel_mass') == 1, 'message names it: '//fault%message)
    end subroutine test_bad_values

    !> A wheel on the rail over a sine roughness of 0.05 um, dt = 10 us, implicit step on the
    !> FFT convolver of g (the inverse FFT of alpha_w + alpha_r on 1 Hz lines to 50 kHz): the
    !> steady-state contact-force amplitude (least squares over whole periods after the start
    !> has died out) against |r|/|alpha_w + alpha_r + 1/k_H|, alpha_r from the wavenumber
    !> integral and k_H from the law, at 30 Hz to 2.5 kHz.
    subroutine test_linear_limit(error)
        type(test_error), allocatable, intent(out) :: error

        real(dp), parameter :: dt = 1.0e-5_dp, amplitude = 5.0e-8_dp, c_hertz = 9.4e10_dp, preload = 7.5e4_dp
        real(dp), parameter :: f(4) = [30.0_dp, 250.0_dp, 1000.0_dp, 2500.0_dp]
        type(rail_track) :: track
        type(wheel_mass) :: wheel
        type(frf_type) :: frf
        type(structure_model) :: structure
        class(convolver), allocatable :: conv
        type(power_law) :: law
        type(contact_options) :: options
        type(contact_response) :: response
        type(error_type), allocatable :: fault
        character(len=:), allocatable :: accuracy
        real(dp), allocatable :: g(:), road(:), basis(:, :)
        real(dp) :: dt_g, omega, k_h, linear, measured, ramp, settle, window, t, worst
        complex(dp) :: alpha
        integer :: i, n, n_steps, first
        character(len=80) :: label

        track = rail_track(bending=ei, mass=m_rail, pad_stiffness=s_pad, pad_damping=2.0_dp*c_pad)
        wheel = wheel_mass(mass=600.0_dp, stiffness=1.0e6_dp, damping=2.0e4_dp)
        frf = wheel_rail_frf(track, wheel, frf_grid(0.5_dp/dt, 50001))
        call impulse_from_frf(frf, g, dt_g, fault)
        call check(error, .not. allocated(fault) .and. abs(dt_g - dt) < 1.0e-12_dp*dt, 'g from G at dt')
        if (allocated(error)) return
        structure = structure_from_samples(g(1:size(g)/2))
        law = power_law(stiffness=c_hertz, exponent=1.5_dp)
        options%scheme = 'implicit'
        k_h = (c_hertz*(((preload/c_hertz)**(2.0_dp/3.0_dp))*(1.0_dp + 1.0e-6_dp))**1.5_dp &
               - c_hertz*(((preload/c_hertz)**(2.0_dp/3.0_dp))*(1.0_dp - 1.0e-6_dp))**1.5_dp) &
              /(2.0e-6_dp*(preload/c_hertz)**(2.0_dp/3.0_dp))
        worst = 0.0_dp
        do i = 1, size(f)
            omega = 2.0_dp*pi*f(i)
            ! a roughness faded in over 20 ms, left 120 ms to settle, then whole periods over >= 40 ms
            ramp = 0.02_dp
            settle = 0.12_dp
            window = ceiling(0.04_dp*f(i))/f(i)
            n_steps = nint((ramp + settle + window)/dt) + 1
            allocate (road(0:n_steps - 1))
            do n = 0, n_steps - 1
                t = n*dt
                road(n) = amplitude*sin(omega*t)*merge(0.5_dp - 0.5_dp*cos(pi*t/ramp), 1.0_dp, t < ramp)
            end do
            call make_convolver('fft', structure, dt, 0.0_dp, n_steps, conv, accuracy, fault)
            call check(error, .not. allocated(fault), 'fft convolver')
            if (allocated(error)) return
            call run_contact(conv, law, road, preload, response, options, fault)
            call conv%release()
            call check(error, .not. allocated(fault), 'contact run')
            if (allocated(error)) return
            ! F - F0 = a*cos + b*sin + c over the window
            first = n_steps - nint(window/dt)
            allocate (basis(first:n_steps - 1, 3))
            basis(:, 1) = [(cos(omega*n*dt), n=first, n_steps - 1)]
            basis(:, 2) = [(sin(omega*n*dt), n=first, n_steps - 1)]
            basis(:, 3) = 1.0_dp
            measured = amplitude_fit(basis, response%force(first:n_steps - 1) - preload)
            alpha = wheel%receptance(omega) + integral_complex(track, omega)
            linear = amplitude/abs(alpha + 1.0_dp/k_h)
            worst = max(worst, abs(measured/linear - 1.0_dp))
            write (label, '(a,f7.1,a)') 'force amplitude / linear model at ', f(i), ' Hz'
            call check(error, measured/linear, 1.0_dp, trim(label), thr=0.02_dp)
            deallocate (road, basis)
            if (allocated(error)) return
        end do
        call note('worst |F/F_linear - 1|', worst)
    end subroutine test_linear_limit

    !> A wheel_rail scene: dt, n_steps, the &structure values after the model ('': a UIC60-like
    !> rail on a pad, a 600 kg wheel), the &road text, the methods, more &identification text and
    !> the accuracy asked (default 0.05).
    function rail_scene(dt, n_steps, structure, road, methods, identification, accuracy) result(text)
        character(len=*), intent(in) :: dt, n_steps, structure, road, methods
        character(len=*), intent(in), optional :: identification
        character(len=*), intent(in), optional :: accuracy
        character(len=:), allocatable :: text

        character(len=:), allocatable :: values

        values = structure
        if (len(values) == 0) values = 'rail_bending = 6.4e6, rail_mass = 60.0, support_stiffness = 5.0e8, ' &
                                       //'support_damping = 5.0e4, wheel_mass = 600.0, suspension_stiffness = 1.0e6, ' &
                                       //'suspension_damping = 2.0e4'
        text = "&scene name = 'wr', output_dir = 'out/test_wheelrail', dt = "//dt//', n_steps = '//n_steps &
               //', spectra = .true., spectra_f_low = 200.0 /'//new_line('a') &
               //"&structure model = 'wheel_rail', "//values//' /'//new_line('a') &
               //'&identification n_freq = 10001'
        if (present(identification)) text = text//', '//identification
        text = text//' /'//new_line('a') &
               //'&road '//road//' /'//new_line('a') &
               //"&contact stiffness = 9.4e10, exponent = 1.5, preload = 7.5e4, scheme = 'implicit' /"//new_line('a') &
               //'&convolution methods = '//methods//', truncation_tol = 1.0e-4, accuracy = '
        if (present(accuracy)) then
            text = text//accuracy//' /'
        else
            text = text//'0.05 /'
        end if
    end function rail_scene

    subroutine test_scene_refusals(error)
        type(test_error), allocatable, intent(out) :: error

        character(len=*), parameter :: cases(3) = [character(len=100) :: &
            'rail_bending = 6.4e6, rail_mass = 60.0, support_stiffness = -1.0, wheel_mass = 600.0', &
            'rail_bending = 6.4e6, rail_mass = 60.0, support_stiffness = 5.0e8, wheel_mass = 0.0', &
            'rail_bending = 6.4e6, rail_mass = 60.0, support_stiffness = 4.0e9, wheel_mass = 600.0']
        character(len=*), parameter :: names(3) = [character(len=24) :: '&structure support_stiff', &
                                                   '&structure wheel_mass', 'Nyquist']
        ! the third: the rail on a 4e9 N/m^2 pad resonates at 1.3 kHz, above 1/(2*dt) = 500 Hz
        character(len=*), parameter :: steps(3) = [character(len=8) :: '1.0e-4', '1.0e-4', '1.0e-3']
        type(scene_type) :: scene
        type(error_type), allocatable :: fault
        integer :: i

        do i = 1, size(cases)
            call read_scene_text('out/test_wheelrail', 'bad.nml', rail_scene(trim(steps(i)), '100', trim(cases(i)), &
                                 "profile = 'sine'", "'fft'"), scene, fault)
            call check(error, allocated(fault), 'refused: '//trim(cases(i)))
            if (allocated(error)) return
            call check(error, fault%stat == stat_input .and. index(fault%message, 'bad.nml:2: &structure ') > 0 .and. &
                       index(fault%message, trim(names(i))) > 0 .and. index(fault%message, new_line('a')) == 0, &
                       'one line, status 2, naming file, line and variable: '//fault%message)
            if (allocated(error)) return
        end do
    end subroutine test_scene_refusals

    !> Sine roughness at 2 kHz of 0.1 um and 0.1 mm (above the static compression 86 um): the summary
    !> line says the contact was never lost, then for how long it was.
    subroutine test_scene_contact_loss(error)
        type(test_error), allocatable, intent(out) :: error

        character(len=:), allocatable :: line
        real(dp), allocatable :: rows(:, :)
        integer :: lost

        ! accuracy 0.2: the loss of contact is under test; fft's budget here is about 6e-2 (model
        ! 3.4e-2, time step 3e-2 with the coarse pair far apart)
        call summary_of(rail_scene('5.0e-5', '8192', '', "profile = 'sine', amplitude = 1.0e-7, omega = 12566.0", &
                                   "'fft'", accuracy='0.2'), 'fft', line, error)
        if (allocated(error)) return
        call check(error, index(line, 'contact never lost') > 0, 'small roughness: '//line)
        if (allocated(error)) return
        call summary_of(rail_scene('5.0e-5', '8192', '', "profile = 'sine', amplitude = 1.0e-4, omega = 12566.0", &
                                   "'fft'", accuracy='0.2'), 'fft', line, error)
        if (allocated(error)) return
        call check(error, index(line, 'contact lost in ') > 0, 'large roughness: '//line)
        if (allocated(error)) return
        ! the count is the run's own: the steps of zero force in its column file
        call read_history('out/test_wheelrail/wr_fft.dat', rows, error)
        if (allocated(error)) return
        lost = count(rows(:, 4) <= 0.0_dp)
        call check(error, index(line, 'contact lost in '//itoa(lost)//' of 8192 steps') > 0, &
                   'lost steps '//itoa(lost)//' in: '//line)
    end subroutine test_scene_contact_loss

    !> At the ISO 3095 limit roughness at 100 km/h the linear reference's band levels and the
    !> fft run's agree within 0.5 dB from 315 Hz to 5 kHz (the bands below hold the start from
    !> rest), and so do their narrowband PSDs on the Welch lines that carry the roughness.
    subroutine test_scene_reference(error)
        type(test_error), allocatable, intent(out) :: error

        character(len=:), allocatable :: line
        real(dp), allocatable :: run(:, :), linear(:, :)
        real(dp) :: worst
        integer :: b, n_lines

        ! accuracy = 0.2 (methods text): the bands against the linear model are under test; fft's
        ! budget at this dt is about 8e-2 (model 3.4e-2, time step 4.4e-2)
        call summary_of(rail_scene('5.0e-5', '16384', '', "profile = 'spectrum', speed = 27.78", &
                                   "'fft'", accuracy='0.2'), 'fft', line, error)
        if (allocated(error)) return
        call read_bands('out/test_wheelrail/wr_fft_spectra.dat', 7, run, error)
        if (allocated(error)) return
        call read_bands('out/test_wheelrail/wr_linear_spectra.dat', 6, linear, error)
        if (allocated(error)) return
        call check(error, size(run, 1) == size(linear, 1) .and. all(run(:, 2) == linear(:, 2)), 'the same bands')
        if (allocated(error)) return
        worst = 0.0_dp
        do b = 1, size(run, 1)
            if (run(b, 1) < 315.0_dp .or. run(b, 1) > 5000.0_dp) cycle
            worst = max(worst, abs(run(b, 6) - linear(b, 6)))
        end do
        call note('worst |L_run - L_linear| [dB]', worst)
        call check(error, worst, 0.0_dp, 'band levels of the run against the linear reference [dB]', thr=0.5_dp)
        if (allocated(error)) return
        ! the narrowband PSDs, line for line on the same Welch lines
        call read_named('out/test_wheelrail/wr_fft_narrowband.dat', [character(len=16) :: 'f', 'psd_force'], run, &
                        error)
        if (allocated(error)) return
        call read_named('out/test_wheelrail/wr_linear_narrowband.dat', [character(len=16) :: 'f', 'psd_roughness', &
                        'alpha_abs', 'h_abs', 'psd_force'], linear, error)
        if (allocated(error)) return
        call check(error, size(run, 1) == size(linear, 1) .and. all(run(:, 1) == linear(:, 1)), 'the same lines')
        if (allocated(error)) return
        ! the roughness is a sum of cosines: between them the PSD is the window's leakage, whose
        ! shape differs; compared are the lines within 10 dB of the largest in the third octave
        ! around them
        worst = 0.0_dp
        n_lines = 0
        do b = 1, size(run, 1)
            if (run(b, 1) < 315.0_dp .or. run(b, 1) > 5000.0_dp) cycle
            if (linear(b, 5) < 0.1_dp*maxval(linear(:, 5), run(:, 1) > run(b, 1)/1.26_dp .and. &
                                              run(:, 1) < run(b, 1)*1.26_dp)) cycle
            worst = max(worst, abs(10.0_dp*log10(run(b, 2)/linear(b, 5))))
            n_lines = n_lines + 1
        end do
        call note('lines 315 Hz - 5 kHz compared', real(n_lines, dp))
        call note('worst |10 lg(S_run/S_linear)| [dB]', worst)
        call check(error, n_lines > 200 .and. worst <= 0.5_dp, &
                   'narrowband PSD of the run against the linear reference within 0.5 dB')
    end subroutine test_scene_reference

    !> Read a column file of the named columns (no units asked).
    subroutine read_named(path, names, rows, error)
        character(len=*), intent(in) :: path
        character(len=*), intent(in) :: names(:)
        real(dp), allocatable, intent(out) :: rows(:, :)
        type(test_error), allocatable, intent(out) :: error

        type(error_type), allocatable :: fault
        integer, allocatable :: line_of(:)
        integer :: i

        call read_columns(path, names, [(' ', i=1, size(names))], rows, line_of, fault)
        call check(error, .not. allocated(fault), 'read '//path)
    end subroutine read_named

    !> The wheel of test/data/uff/wheel_modes.uff (pyuff: a 600 kg mass on a suspension at
    !> 6.5 Hz, damping ratio 0.4, and a 2.5 kHz mode of 150 kg, shape 0.8 at node 7 and 0 at
    !> node 9, its damping ratio 0 in the file) against the closed forms computed here: node 7
    !> 1/(k - M w^2 + i w c) + 0.8^2/(150 (w2^2 - w^2 + 2 i xi w2 w)) with the default ratio
    !> xi = 0.01, node 9 the mass on its suspension, from 0 to 5 kHz, to 1e-12; a node the file
    !> does not have and a missing file refused, naming the variable.
    subroutine test_wheel_modes(error)
        type(test_error), allocatable, intent(out) :: error

        real(dp), parameter :: f(7) = [0.0_dp, 1.0_dp, 6.5_dp, 100.0_dp, 1000.0_dp, 2500.0_dp, 5000.0_dp]
        type(wheel_mass) :: wheel, suspension
        type(error_type), allocatable :: fault
        real(dp) :: w1, w2, w, worst
        complex(dp) :: closed
        integer :: i

        w1 = 2.0_dp*pi*6.5_dp
        w2 = 2.0_dp*pi*2500.0_dp
        suspension = wheel_mass(mass=600.0_dp, stiffness=600.0_dp*w1**2, damping=2.0_dp*0.4_dp*600.0_dp*w1)
        call wheel_from_modes(wheel_file, 3, 7, 0.01_dp, wheel, fault)
        call check(error, .not. allocated(fault), 'read node 7 of '//wheel_file)
        if (allocated(error)) return
        worst = 0.0_dp
        do i = 1, size(f)
            w = 2.0_dp*pi*f(i)
            closed = 1.0_dp/cmplx(suspension%stiffness - 600.0_dp*w**2, w*suspension%damping, kind=dp) &
                     + 0.64_dp/(150.0_dp*cmplx(w2**2 - w**2, 2.0_dp*0.01_dp*w2*w, kind=dp))
            worst = max(worst, abs(wheel%receptance(w)/closed - 1.0_dp))
        end do
        call note('node 7: worst |alpha_file/alpha_closed - 1|', worst)
        call check(error, worst, 0.0_dp, 'node 7 against the closed form', thr=1.0e-12_dp)
        if (allocated(error)) return
        call wheel_from_modes(wheel_file, 3, 9, 0.01_dp, wheel, fault)
        call check(error, .not. allocated(fault), 'read node 9')
        if (allocated(error)) return
        worst = maxval(abs(wheel%receptance(2.0_dp*pi*f)/suspension%receptance(2.0_dp*pi*f) - 1.0_dp))
        call note('node 9: worst |alpha_file/alpha_suspension - 1|', worst)
        call check(error, worst, 0.0_dp, 'node 9 against the mass on its suspension', thr=1.0e-12_dp)
        if (allocated(error)) return
        call wheel_from_modes(wheel_file, 3, 5, 0.01_dp, wheel, fault)
        call check(error, allocated(fault), 'node 5 refused')
        if (allocated(error)) return
        call check(error, index(fault%message, 'wheel_node: ') == 1, 'message names wheel_node: '//fault%message)
        if (allocated(error)) return
        call wheel_from_modes('test/data/uff/no_such_wheel.uff', 3, 0, 0.01_dp, wheel, fault)
        call check(error, allocated(fault), 'a missing file refused')
        if (allocated(error)) return
        call check(error, index(fault%message, 'wheel_modes_file: ') == 1, 'message names wheel_modes_file: ' &
                   //fault%message)
    end subroutine test_wheel_modes

    !> The same scene (sine roughness at 500 Hz, `fft`) with the wheel as a mass on its
    !> suspension and as node 9 of the modes file: the same contact force to 1e-9 of the
    !> preload; a node the file does not have is one line naming `&structure wheel_node`.
    subroutine test_scene_wheel_modes(error)
        type(test_error), allocatable, intent(out) :: error

        character(len=*), parameter :: rail = 'rail_bending = 6.4e6, rail_mass = 60.0, support_stiffness = 5.0e8, ' &
                                              //'support_damping = 5.0e4, '
        character(len=*), parameter :: road = "profile = 'sine', amplitude = 1.0e-6, omega = 3141.6"
        type(scene_type) :: scene
        type(error_type), allocatable :: fault
        character(len=:), allocatable :: line
        character(len=120) :: values
        real(dp), allocatable :: suspension(:, :), modes(:, :)
        real(dp) :: w1, difference

        w1 = 2.0_dp*pi*6.5_dp
        write (values, '(a,es24.16,a,es24.16)') 'suspension_stiffness = ', 600.0_dp*w1**2, ', suspension_damping = ', &
            2.0_dp*0.4_dp*600.0_dp*w1
        call summary_of(rail_scene('5.0e-5', '4096', rail//'wheel_mass = 600.0, '//trim(values), road, "'fft'"), &
                        'fft', line, error)
        if (allocated(error)) return
        call read_history('out/test_wheelrail/wr_fft.dat', suspension, error)
        if (allocated(error)) return
        call summary_of(rail_scene('5.0e-5', '4096', rail//"wheel_mass = 600.0, wheel_modes_file = '"//wheel_file &
                                   //"', wheel_node = 9", road, "'fft'"), 'fft', line, error)
        if (allocated(error)) return
        call read_history('out/test_wheelrail/wr_fft.dat', modes, error)
        if (allocated(error)) return
        difference = maxval(abs(modes(:, 4) - suspension(:, 4)))/7.5e4_dp
        call note('max |F_modes - F_suspension|/F0', difference)
        call check(error, size(modes, 1) == size(suspension, 1) .and. difference <= 1.0e-9_dp, &
                   'the same force history')
        if (allocated(error)) return
        call read_scene_text('out/test_wheelrail', 'bad.nml', rail_scene('5.0e-5', '100', rail &
                             //"wheel_mass = 600.0, wheel_modes_file = '"//wheel_file//"', wheel_node = 5", road, &
                             "'fft'"), scene, fault)
        call check(error, allocated(fault), 'node 5 refused')
        if (allocated(error)) return
        call check(error, fault%stat == stat_input .and. index(fault%message, 'bad.nml:2: &structure wheel_node') > 0 &
                   .and. index(fault%message, new_line('a')) == 0, 'one line, status 2: '//fault%message)
    end subroutine test_scene_wheel_modes

    !> What the chart of data/wheel_rail_sweep.nml (plot/wheel_rail_sweep.gp) rests on, at the
    !> ISO 3095 limit roughness shifted by roughness_offset: the linear reference scales with
    !> the roughness (its band levels at -20 dB are those at 0 dB less 20 dB, to 1e-9 dB); a
    !> sweep's band levels are those of the contact scene of the same values (to the table's
    !> 1e-4 dB); at -20 dB they meet the linear model within 0.5 dB from 315 Hz to 5 kHz with
    !> the contact never lost, at +12 dB the contact is lost for some steps (fraction < 1).
    subroutine test_roughness_sweep(error)
        type(test_error), allocatable, intent(out) :: error

        character(len=*), parameter :: road = "profile = 'spectrum', speed = 27.78, roughness_offset = "
        character(len=*), parameter :: directory = 'out/test_wheelrail'
        character(len=:), allocatable :: line, text, names(:)
        real(dp), allocatable :: linear_low(:, :), linear(:, :), run_low(:, :), table(:, :)
        type(error_type), allocatable :: fault
        real(dp) :: worst, departure
        integer :: b, c, report

        ! accuracy 0.2: fft's budget at this dt is about 8e-2 (model 3.4e-2, time step 4.4e-2); the
        ! bands against the linear model are under test
        call summary_of(rail_scene('5.0e-5', '16384', '', road//'0.0', "'fft'", accuracy='0.2'), 'fft', line, error)
        if (allocated(error)) return
        call read_bands(directory//'/wr_linear_spectra.dat', 6, linear, error)
        if (allocated(error)) return
        call summary_of(rail_scene('5.0e-5', '16384', '', road//'-20.0', "'fft'", accuracy='0.2'), 'fft', line, &
                        error)
        if (allocated(error)) return
        call read_bands(directory//'/wr_linear_spectra.dat', 6, linear_low, error)
        if (allocated(error)) return
        call read_bands(directory//'/wr_fft_spectra.dat', 7, run_low, error)
        if (allocated(error)) return
        worst = maxval(abs(linear_low(:, 6) + 20.0_dp - linear(:, 6)))
        call note('|L_linear(-20 dB) + 20 - L_linear(0 dB)| [dB]', worst)
        call check(error, worst <= 1.0e-9_dp, 'the linear reference scales with the roughness')
        if (allocated(error)) return
        ! the sweep of the same scene over the offset
        text = rail_scene('5.0e-5', '16384', '', road//'0.0', "'fft'", accuracy='0.2')
        text = "&scene task = 'sweep', name = 'wrs', output_dir = '"//directory//"', dt = 5.0e-5, n_steps = 16384 /" &
               //text(index(text, new_line('a')):)//new_line('a') &
               //'&sweep road.roughness_offset = -20.0, 12.0, spectra = .true., f_low = 200.0, f_high = 5000.0 /' &
               //new_line('a')
        call execute_command_line('rm -rf '//directory//'/wrs_sweep.d')
        call write_text(directory//'/wrs.nml', text)
        open (newunit=report, status='scratch', action='readwrite')
        call run_sweep(directory//'/wrs.nml', report, .false., fault)
        close (report)
        call check(error, .not. allocated(fault), 'the sweep runs')
        if (allocated(error)) then
            error%message = error%message//': '//fault%message
            return
        end if
        call read_sweep_table(directory//'/wrs_sweep.dat', names, table, error)
        if (allocated(error)) return
        call check(error, size(table, 1) == 2, 'two variants')
        if (allocated(error)) return
        worst = 0.0_dp
        departure = 0.0_dp
        do b = 1, size(run_low, 1)
            c = column_named(names, 'L'//nominal_text(run_low(b, 1))//'_fft')
            if (c == 0) cycle
            worst = max(worst, abs(table(1, c) - run_low(b, 6)))
            if (run_low(b, 1) >= 315.0_dp .and. run_low(b, 1) <= 5000.0_dp) &
                departure = max(departure, abs(table(1, c) - (linear(b, 6) - 20.0_dp)))
        end do
        call note('|L_sweep - L_scene| at -20 dB [dB]', worst)
        call note('|L_sweep - L_linear| at -20 dB, 315 Hz - 5 kHz [dB]', departure)
        call check(error, count(index(names, '_fft') > 0 .and. names(:)(1:1) == 'L') >= 10 .and. &
                   worst <= 1.0e-4_dp, 'the sweep''s band levels are the scene''s')
        if (allocated(error)) return
        call check(error, departure <= 0.5_dp, 'at -20 dB the sweep meets the linear model within 0.5 dB')
        if (allocated(error)) return
        c = column_named(names, 'contact_fft')
        call check(error, c > 0, 'a column contact_fft')
        if (allocated(error)) return
        call note('contact fraction at -20 dB', table(1, c))
        call note('contact fraction at +12 dB', table(2, c))
        call check(error, table(1, c) == 1.0_dp .and. table(2, c) < 1.0_dp, &
                   'contact never lost at -20 dB, lost for some steps at +12 dB')
    end subroutine test_roughness_sweep

    !> The column of `name` in `names`, 0 when absent.
    pure integer function column_named(names, name) result(c)
        character(len=*), intent(in) :: names(:), name

        do c = 1, size(names)
            if (names(c) == name) return
        end do
        c = 0
    end function column_named

    !> A band's nominal frequency as a sweep table names its column ('315', '1000').
    function nominal_text(f) result(text)
        real(dp), intent(in) :: f
        character(len=:), allocatable :: text

        character(len=24) :: buffer

        write (buffer, '(i0)') nint(f)
        text = trim(buffer)
    end function nominal_text

    !> A sweep table: the names of its '# variant' header line and its rows of numbers.
    subroutine read_sweep_table(path, names, rows, error)
        character(len=*), intent(in) :: path
        character(len=:), allocatable, intent(out) :: names(:)
        real(dp), allocatable, intent(out) :: rows(:, :)
        type(test_error), allocatable, intent(out) :: error

        character(len=8000) :: buffer
        character(len=40) :: words(400)
        real(dp) :: values(400)
        integer :: unit, stat, n, k, i

        n = 0
        k = 0
        allocate (rows(0, 0))
        allocate (character(len=40) :: names(0))
        open (newunit=unit, file=path, status='old', action='read', iostat=stat)
        call check(error, stat == 0, 'open '//path)
        if (allocated(error)) return
        do
            read (unit, '(a)', iostat=stat) buffer
            if (stat /= 0) exit
            if (index(buffer, '# variant') == 1) then
                n = 0
                do i = 1, size(words)
                    words = ''
                    read (buffer(2:), *, iostat=stat) words(:i)
                    if (stat /= 0) exit
                    n = i
                end do
                read (buffer(2:), *) words(:n)
                names = words(:n)
                deallocate (rows)
                allocate (rows(0, n))
            else if (buffer(1:1) /= '#' .and. n > 0 .and. len_trim(buffer) > 0) then
                read (buffer, *) values(:n)
                rows = reshape([transpose(rows), values(:n)], [n, size(rows, 1) + 1])
                rows = transpose(rows)
                k = k + 1
            end if
        end do
        close (unit)
        call check(error, n > 0 .and. k > 0, 'a header and rows in '//path)
    end subroutine read_sweep_table

    !> `auto` on the rail (G not a finite sum of modes): its summary line names what it chose
    !> and why.
    subroutine test_scene_auto(error)
        type(test_error), allocatable, intent(out) :: error

        character(len=:), allocatable :: line

        ! accuracy 0.2: what auto says is under test; its budget here is about 5.8e-2 (E 2.1e-2, time
        ! step 3.7e-2)
        call summary_of(rail_scene('1.0e-4', '4096', '', "profile = 'sine', amplitude = 1.0e-7, omega = 3000.0", &
                                   "'auto'", 'max_order = 8', accuracy='0.2'), 'auto', line, error)
        if (allocated(error)) return
        call check(error, index(line, 'chose ') > 0, 'auto says what it chose: '//line)
    end subroutine test_scene_auto

    !> Run a scene and return the summary line of `method`.
    subroutine summary_of(text, method, line, error)
        character(len=*), intent(in) :: text, method
        character(len=:), allocatable, intent(out) :: line
        type(test_error), allocatable, intent(out) :: error

        type(scene_type) :: scene
        type(error_type), allocatable :: fault
        character(len=2000) :: buffer
        integer :: unit, stat

        call read_scene_text('out/test_wheelrail', 'wr.nml', text, scene, fault)
        if (.not. allocated(fault)) then
            open (newunit=unit, status='scratch', action='readwrite')
            call run_scene(scene, unit, fault)
        end if
        call check(error, .not. allocated(fault), 'scene runs')
        if (allocated(error)) then
            error%message = error%message//': '//fault%message
            return
        end if
        rewind (unit)
        line = ''
        do
            read (unit, '(a)', iostat=stat) buffer
            if (stat /= 0) exit
            if (index(buffer, method//' ') == 1) line = trim(buffer)
        end do
        close (unit)
        call check(error, len(line) > 0, 'a summary line for '//method)
    end subroutine summary_of

    subroutine read_history(path, rows, error)
        character(len=*), intent(in) :: path
        real(dp), allocatable, intent(out) :: rows(:, :)
        type(test_error), allocatable, intent(out) :: error

        type(error_type), allocatable :: fault
        integer, allocatable :: line_of(:)

        call read_columns(path, [character(len=10) :: 't', 'u_road', 'u', 'f_contact', 'delta'], &
                          [character(len=1) :: 's', 'm', 'm', 'N', 'm'], rows, line_of, fault)
        call check(error, .not. allocated(fault), 'read '//path)
    end subroutine read_history

    pure function itoa(i) result(text)
        integer, intent(in) :: i
        character(len=:), allocatable :: text
        character(len=16) :: buffer

        write (buffer, '(i0)') i
        text = trim(buffer)
    end function itoa

    !> Amplitude sqrt(a^2 + b^2) of the least-squares fit y = a*basis(:,1) + b*basis(:,2) +
    !> c*basis(:,3), by the normal equations (3 x 3, Cramer's rule).
    real(dp) function amplitude_fit(basis, y) result(amplitude)
        real(dp), intent(in) :: basis(:, :), y(:)

        real(dp) :: a(3, 3), r(3), x(3), m(3, 3), det
        integer :: i, j

        do i = 1, 3
            r(i) = sum(basis(:, i)*y)
            do j = 1, 3
                a(i, j) = sum(basis(:, i)*basis(:, j))
            end do
        end do
        det = determinant(a)
        do i = 1, 3
            m = a
            m(:, i) = r
            x(i) = determinant(m)/det
        end do
        amplitude = sqrt(x(1)**2 + x(2)**2)
    end function amplitude_fit

    pure real(dp) function determinant(a)
        real(dp), intent(in) :: a(3, 3)

        determinant = a(1, 1)*(a(2, 2)*a(3, 3) - a(2, 3)*a(3, 2)) - a(1, 2)*(a(2, 1)*a(3, 3) - a(2, 3)*a(3, 1)) &
                      + a(1, 3)*(a(2, 1)*a(3, 2) - a(2, 2)*a(3, 1))
    end function determinant

    !> The receptance (1/pi) * integral over k > 0 of dk/D(k), D the rail's dynamic stiffness
    !> per wavenumber written out here, by Simpson's rule after k = k0*tan(theta).
    complex(dp) function integral_complex(track, omega) result(alpha)
        type(rail_track), intent(in) :: track
        real(dp), intent(in) :: omega

        integer, parameter :: n = 400000
        real(dp) :: h, theta, k, k0, weight
        integer :: j

        k0 = (abs(track%support(omega) - track%mass*omega**2)/track%bending)**0.25_dp
        k0 = max(k0, (track%pad_stiffness/track%bending)**0.25_dp)
        h = 0.5_dp*pi/n
        alpha = (0.0_dp, 0.0_dp)
        do j = 0, n
            theta = j*h
            weight = merge(1.0_dp, merge(4.0_dp, 2.0_dp, mod(j, 2) == 1), j == 0 .or. j == n)
            if (j == n) then
                ! the limit at theta = pi/2: D -> kappa*G*A*k^2 (Timoshenko), EI*k^4 (Euler-Bernoulli)
                if (track%shear > 0.0_dp) alpha = alpha + weight/(track%shear*k0)
                cycle
            end if
            k = k0*tan(theta)
            alpha = alpha + weight*k0/cos(theta)**2/stiffness(track, k, omega)
        end do
        alpha = alpha*h/3.0_dp/pi
    end function integral_complex

    real(dp) function integral(track, omega)
        type(rail_track), intent(in) :: track
        real(dp), intent(in) :: omega

        integral = real(integral_complex(track, omega), dp)
    end function integral

    !> D(k, omega): EI k^4 - m omega^2 + s*, or Timoshenko's with the rotation eliminated,
    !> s* the pad in series with the sleepers on the ballast.
    complex(dp) function stiffness(track, k, omega) result(d)
        type(rail_track), intent(in) :: track
        real(dp), intent(in) :: k, omega

        complex(dp) :: s, pad, ballast

        pad = cmplx(track%pad_stiffness, omega*track%pad_damping, kind=dp)
        s = pad
        if (track%sleeper_mass > 0.0_dp) then
            ballast = cmplx(track%ballast_stiffness, omega*track%ballast_damping, kind=dp) - track%sleeper_mass*omega**2
            s = 1.0_dp/(1.0_dp/pad + 1.0_dp/ballast)
        end if
        if (track%shear > 0.0_dp) then
            d = track%shear*k**2*(track%bending*k**2 - track%rotary*omega**2) &
                /(track%bending*k**2 + track%shear - track%rotary*omega**2) + s - track%mass*omega**2
        else
            d = track%bending*k**4 + s - track%mass*omega**2
        end if
    end function stiffness

end module test_wheelrail_mod
