!> The contact law as an object (greenconv_contact_law) and its registry
!> (greenconv_contact_laws): the exponential pressure-overclosure law against its closed forms
!> and, in a contact run of the SDOF scene, against the independent ODE reference
!> (verify_contact_mod: the modal state space with the same law, adaptive Dormand-Prince at
!> 1e-11) at two time steps, with the observed order; the registry's constructor, its refusals
!> and its descriptions; the power law built by name equal to `contact_law(k_c, p)` bit for bit.
module test_laws_mod
    use, intrinsic :: iso_fortran_env, only: dp => real64
    use testsuite_mod, only: test_error, unittest_type, new_unittest, check, note
    use scene_text_mod, only: read_scene_text, message_of
    use verify_contact_mod, only: contact_reference
    use greenconv_core_error, only: error_type, stat_input
    use greenconv_model_sdof, only: sdof_modes
    use greenconv_model_road, only: sine_road
    use greenconv_ident_structure, only: structure_from_modes
    use greenconv_conv_convolver, only: convolver
    use greenconv_conv_builder, only: make_convolver
    use greenconv_contact_single, only: contact_response, run_contact
    use greenconv_contact_laws, only: contact_law, power_law, exponential_law, new_law, describe_law, law_names
    use greenconv_scene_read_input, only: scene_type
    implicit none
    private

    public :: collect_laws

    real(dp), parameter :: mass = 1.0_dp, stiffness = 1.0e6_dp, xi = 0.02_dp, preload = 9.81_dp
    !> The exponential law of the runs: F_s [N], delta_s [m].
    real(dp), parameter :: force_scale = 5.0_dp, compression_scale = 2.0e-4_dp
    !> The road: 0.3 mm at 100 rad/s, enough to lift the body off (delta0 is 0.22 mm).
    real(dp), parameter :: amplitude = 3.0e-4_dp, omega_road = 100.0_dp
    !> The run: 0.2 s.
    real(dp), parameter :: duration = 0.2_dp
    character(len=*), parameter :: scratch = 'build/test_laws'

contains

    !> Tests of the contact laws and their registry.
    subroutine collect_laws(testsuite)
        type(unittest_type), allocatable, intent(out) :: testsuite(:)

        testsuite = [new_unittest('exponential law: closed forms, small forces, tangent', test_exponential_forms), &
                     new_unittest('exponential law: static compression of the SDOF scene', test_static_compression), &
                     new_unittest('exponential law: run against the ODE reference at two dt', test_exponential_run), &
                     new_unittest('registry: power law by name equals contact_law(k_c, p)', test_power_by_name), &
                     new_unittest('registry: refusals name law, parameter, unit and range', test_refusals), &
                     new_unittest('registry: one line naming each law', test_describe), &
                     new_unittest('scene: &contact law and law_parameters', test_scene_law)]
    end subroutine collect_laws

    !> F = F_s*(exp(delta/delta_s) - 1), its inverse and its tangent against their closed forms:
    !> at a light touch (F/F_s = 1e-12, where 1 + F/F_s loses four digits) the law keeps full
    !> precision; the tangent against a central difference of F.
    subroutine test_exponential_forms(error)
        type(test_error), allocatable, intent(out) :: error

        type(exponential_law) :: law
        real(dp) :: delta, x, h, difference
        integer :: i

        law = exponential_law(force_scale=force_scale, compression_scale=compression_scale)
        call check(error, law%force(-1.0e-9_dp) == 0.0_dp .and. law%force(0.0_dp) == 0.0_dp, 'no force in tension')
        if (allocated(error)) return
        do i = 1, 4
            delta = compression_scale*0.5_dp*i
            call check(error, law%force(delta), force_scale*(exp(0.5_dp*i) - 1.0_dp), 'F at delta/delta_s = ' &
                       //trim(adjustl(real_text(0.5_dp*i))), thr=4.0e-16_dp, rel=.true.)
            if (allocated(error)) return
            call check(error, law%compression(law%force(delta)), delta, 'compression(force(delta))', &
                       thr=4.0e-16_dp, rel=.true.)
            if (allocated(error)) return
            h = 1.0e-6_dp*compression_scale
            difference = (law%force(delta + h) - law%force(delta - h))/(2.0_dp*h)
            call check(error, law%tangent(delta), difference, 'tangent against a central difference', &
                       thr=1.0e-8_dp, rel=.true.)
            if (allocated(error)) return
        end do
        ! a light touch: the series x - x^2/2 and x + x^2/2 are exact to round-off at x = 1e-12
        x = 1.0e-12_dp
        call check(error, law%compression(x*force_scale), compression_scale*(x - 0.5_dp*x**2), &
                   'compression at F/F_s = 1e-12', thr=2.0e-16_dp, rel=.true.)
        if (allocated(error)) return
        call check(error, law%force(x*compression_scale), force_scale*(x + 0.5_dp*x**2), &
                   'force at delta/delta_s = 1e-12', thr=2.0e-16_dp, rel=.true.)
    end subroutine test_exponential_forms

    !> On a flat road the body rests at the static compression delta0 = delta_s*log(1 + F0/F_s)
    !> that carries the preload, the force F0, and does not move.
    subroutine test_static_compression(error)
        type(test_error), allocatable, intent(out) :: error

        type(contact_response) :: response
        class(convolver), allocatable :: conv
        character(len=:), allocatable :: accuracy
        type(error_type), allocatable :: fail
        real(dp) :: delta0, road(200)

        delta0 = compression_scale*log(1.0_dp + preload/force_scale)
        call make_convolver('exact', structure_from_modes(sdof_modes(mass, stiffness, xi)), 1.0e-4_dp, 0.01_dp, &
                            size(road), conv, accuracy, fail)
        call check(error, .not. allocated(fail), 'the convolver: '//message_of(fail))
        if (allocated(error)) return
        road(:) = 0.0_dp
        call run_contact(conv, exponential_law(force_scale, compression_scale), road, preload, response, error=fail)
        call check(error, .not. allocated(fail), 'the run: '//message_of(fail))
        if (allocated(error)) return
        call note('delta0 [m]', delta0)
        call check(error, maxval(abs(response%compression - delta0)), 0.0_dp, 'delta = delta0 at every step', &
                   thr=1.0e-14_dp*delta0)
        if (allocated(error)) return
        call check(error, maxval(abs(response%force - preload)), 0.0_dp, 'F = F0 at every step', &
                   thr=1.0e-13_dp*preload)
        if (allocated(error)) return
        call check(error, maxval(abs(response%displacement)), 0.0_dp, 'u = 0 at every step', thr=1.0e-18_dp)
    end subroutine test_static_compression

    !> The SDOF scene on the exponential law, lifted off the road each period, against the ODE
    !> reference: `exact` (first-order hold, explicit contact step) at dt = 50 us and 25 us.
    !> `exact` is second order in dt (doc/methods.md), the law's kink at delta = 0 crossed twice a
    !> period notwithstanding: the relative L2 errors of F must fall below 2e-4 and 5e-5 and their
    !> ratio show an order of 2 +- 0.3.
    subroutine test_exponential_run(error)
        type(test_error), allocatable, intent(out) :: error

        real(dp) :: errors(2), steps(2), order
        integer :: k

        steps = [5.0e-5_dp, 2.5e-5_dp]
        do k = 1, 2
            call run_error(steps(k), errors(k), error)
            if (allocated(error)) return
        end do
        order = log(errors(1)/errors(2))/log(2.0_dp)
        call note('relative L2 error of F at dt = 50 us', errors(1))
        call note('at 25 us', errors(2))
        call note('observed order', order)
        call check(error, errors(1) < 2.0e-4_dp .and. errors(2) < 5.0e-5_dp, 'errors below 2e-4 and 5e-5')
        if (allocated(error)) return
        call check(error, order, 2.0_dp, 'observed order in dt', thr=0.3_dp)
    end subroutine test_exponential_run

    !> The relative L2 error of the contact force of one run at time step `dt`.
    subroutine run_error(dt, relative, error)
        real(dp), intent(in) :: dt
        real(dp), intent(out) :: relative
        type(test_error), allocatable, intent(out) :: error

        class(convolver), allocatable :: conv
        character(len=:), allocatable :: accuracy
        type(error_type), allocatable :: fail
        type(contact_response) :: response
        type(sine_road) :: road
        real(dp), allocatable :: u_ref(:), f_ref(:)
        integer :: n_steps

        n_steps = nint(duration/dt)
        road%amplitude = amplitude
        road%omega = omega_road
        call make_convolver('exact', structure_from_modes(sdof_modes(mass, stiffness, xi)), dt, 0.01_dp, n_steps, &
                            conv, accuracy, fail)
        if (.not. allocated(fail)) call run_contact(conv, exponential_law(force_scale, compression_scale), &
                                                    road%sample(dt, n_steps), preload, response, error=fail)
        call check(error, .not. allocated(fail), 'the run: '//message_of(fail))
        if (allocated(error)) return
        call contact_reference(sdof_modes(mass, stiffness, xi), exponential_law(force_scale, compression_scale), &
                               road, preload, dt, n_steps, u_ref, f_ref, rtol=1.0e-11_dp)
        ! the scene must lift the body off, or the kink of the law at delta = 0 is never crossed
        call check(error, count(f_ref == 0.0_dp) > n_steps/20 .and. count(f_ref > 0.0_dp) > n_steps/2, &
                   'the body both loses and regains contact')
        if (allocated(error)) return
        relative = norm2(response%force - f_ref)/norm2(f_ref)
    end subroutine run_error

    !> The power law built by the registry is `contact_law(k_c, p)`: the same force, compression
    !> and tangent to the bit, on the Hertz, linear and general paths.
    subroutine test_power_by_name(error)
        type(test_error), allocatable, intent(out) :: error

        class(contact_law), allocatable :: law
        type(error_type), allocatable :: fail
        real(dp), parameter :: exponents(3) = [1.5_dp, 1.0_dp, 1.3_dp]
        real(dp), parameter :: forces(3) = [0.0_dp, 5.0_dp, 300.0_dp]
        real(dp) :: delta(5)
        type(power_law) :: direct
        integer :: i

        delta = [-1.0e-4_dp, 0.0_dp, 1.0e-7_dp, 3.0e-4_dp, 2.0e-3_dp]
        do i = 1, size(exponents)
            call new_law('power', [2.0e7_dp, exponents(i)], law, fail)
            call check(error, .not. allocated(fail), 'power law by name: '//message_of(fail))
            if (allocated(error)) return
            direct = contact_law(2.0e7_dp, exponents(i))
            call check(error, all(law%force(delta) == direct%force(delta)) .and. &
                       all(law%compression(forces) == direct%compression(forces)) .and. &
                       all(law%tangent(delta(3:)) == direct%tangent(delta(3:))), &
                       'the same values as contact_law(k_c, p), p = '//real_text(exponents(i)))
            if (allocated(error)) return
        end do
        call check(error, direct%force(3.0e-4_dp) == 2.0e7_dp*3.0e-4_dp**1.3_dp, 'k_c*delta^p on the general path')
    end subroutine test_power_by_name

    !> new_law refuses an unknown name, a wrong count, a value out of range or not finite; each
    !> message names the law, the parameter with its unit and range, and the value found.
    subroutine test_refusals(error)
        type(test_error), allocatable, intent(out) :: error

        class(contact_law), allocatable :: law
        type(error_type), allocatable :: fail
        real(dp) :: zero

        zero = 0.0_dp
        call new_law('hertz', [1.0_dp, 1.5_dp], law, fail)
        call refused(fail, law, ["'hertz'      ", "'power'      ", "'exponential'"], error)
        if (allocated(error)) return
        call new_law('exponential', [1.0_dp], law, fail)
        call refused(fail, law, [character(len=13) :: 'expected 2', 'F_s [N]', 'delta_s [m]', 'found 1'], error)
        if (allocated(error)) return
        call new_law('exponential', [1.0_dp, -2.0e-4_dp], law, fail)
        call refused(fail, law, [character(len=13) :: 'delta_s [m]', '> 0', '-2.00E-04'], error)
        if (allocated(error)) return
        call new_law('power', [1.0e6_dp/zero, 1.5_dp], law, fail)
        call refused(fail, law, [character(len=13) :: "'power'", 'k_c [N/m^p]', 'finite'], error)
        if (allocated(error)) return
        call check(error, law_names() == "'power', 'exponential'", 'the registry lists its laws: '//law_names())
    end subroutine test_refusals

    !> A refusal: status 2, no law, and every word of `words` in the message.
    subroutine refused(fail, law, words, error)
        type(error_type), allocatable, intent(in) :: fail
        class(contact_law), allocatable, intent(in) :: law
        character(len=*), intent(in) :: words(:)
        type(test_error), allocatable, intent(out) :: error

        integer :: i

        call check(error, allocated(fail), 'refused')
        if (allocated(error)) return
        call check(error, fail%stat == stat_input .and. .not. allocated(law), 'status 2 and no law: '//fail%message)
        do i = 1, size(words)
            if (allocated(error)) return
            call check(error, index(fail%message, trim(words(i))) > 0, 'the message names '//trim(words(i)) &
                       //': '//fail%message)
        end do
    end subroutine refused

    !> describe_law names a law and its parameters with their units.
    subroutine test_describe(error)
        type(test_error), allocatable, intent(out) :: error

        character(len=:), allocatable :: text

        call describe_law(contact_law(1.0e6_dp, 1.5_dp), text)
        call check(error, text == 'power law k_c = 1.00E+06 N/m^p, p = 1.50E+00', 'power: '//text)
        if (allocated(error)) return
        call describe_law(exponential_law(5.0_dp, 2.0e-4_dp), text)
        call check(error, text == 'exponential law F_s = 5.00E+00 N, delta_s = 2.00E-04 m', 'exponential: '//text)
    end subroutine test_describe
    !> A scene's &contact: the default power law from stiffness and exponent, the exponential law
    !> from law_parameters, and the reader's refusals (file, line, group, variable, expected,
    !> found; status 2).
    subroutine test_scene_law(error)
        type(test_error), allocatable, intent(out) :: error

        type(scene_type) :: scene
        type(error_type), allocatable :: fail

        call read_scene_text(scratch, 'power.nml', scene_text('stiffness = 2.0e6, exponent = 1.0'), scene, fail)
        call check(error, .not. allocated(fail), 'the power scene reads: '//message_of(fail))
        if (allocated(error)) return
        call check(error, scene%law%name() == 'power' .and. all(scene%law%parameters() == [2.0e6_dp, 1.0_dp]), &
                   'stiffness and exponent make the power law')
        if (allocated(error)) return
        call read_scene_text(scratch, 'exp.nml', scene_text("law = 'exponential', law_parameters = 5.0, 2.0e-4"), &
                             scene, fail)
        call check(error, .not. allocated(fail), 'the exponential scene reads: '//message_of(fail))
        if (allocated(error)) return
        call check(error, scene%law%name() == 'exponential' .and. &
                   all(scene%law%parameters() == [5.0_dp, 2.0e-4_dp]), 'law_parameters make the exponential law')
        if (allocated(error)) return
        call scene_refused("law = 'exponential', law_parameters = 5.0, -2.0e-4", &
                           "exp.nml:11: &contact law_parameters: expected a finite delta_s [m] > 0.0 (value 2 of " &
                           //"law 'exponential'), found -2.0E-04", error)
        if (allocated(error)) return
        call scene_refused("law = 'exponential', law_parameters = 5.0", "exp.nml:11: &contact law_parameters: " &
                           //"expected 2 values for law 'exponential' (F_s [N], delta_s [m]), found 1", error)
        if (allocated(error)) return
        call scene_refused("law = 'exponential', law_parameters = 5.0, 2.0e-4, exponent = 1.5", &
                           "exp.nml:11: &contact law_parameters: expected no value beside stiffness, exponent", error)
        if (allocated(error)) return
        call scene_refused("law = 'hertz', stiffness = 1.0e6, exponent = 1.5", &
                           "exp.nml:11: &contact law: expected 'power' or 'exponential', found 'hertz'", error)
    end subroutine test_scene_law

    !> A scene refused with status 2 and a message that starts `expected` after the directory.
    subroutine scene_refused(contact, expected, error)
        character(len=*), intent(in) :: contact, expected
        type(test_error), allocatable, intent(out) :: error

        type(scene_type) :: scene
        type(error_type), allocatable :: fail

        call read_scene_text(scratch, 'exp.nml', scene_text(contact), scene, fail)
        call check(error, allocated(fail), 'refused: '//contact)
        if (allocated(error)) return
        call check(error, fail%stat == stat_input .and. index(fail%message, expected) > 0, &
                   'status 2 and the message "'//expected//'", found "'//fail%message//'"')
    end subroutine scene_refused

    !> The SDOF scene with `contact` as its &contact group's values (line 11).
    function scene_text(contact) result(text)
        character(len=*), intent(in) :: contact
        character(len=:), allocatable :: text

        character(len=*), parameter :: nl = new_line('a')

        text = "&scene name = 'laws', output_dir = '"//scratch//"', dt = 1.0e-4, n_steps = 100 /"//nl &
               //"&structure model = 'sdof', mass = 1.0, stiffness = 1.0e6, damping_ratio = 0.02 /"//nl &
               //"&road profile = 'sine', amplitude = 1.0e-4, omega = 100.0 /"//nl//nl//nl//nl//nl//nl//nl//nl &
               //'&contact '//contact//' /'//nl &
               //"&convolution methods = 'modal' /"//nl
    end function scene_text

    !> A real in short text.
    function real_text(x) result(text)
        real(dp), intent(in) :: x
        character(len=:), allocatable :: text

        character(len=24) :: buffer

        write (buffer, '(g0.4)') x
        text = trim(adjustl(buffer))
    end function real_text

end module test_laws_mod
