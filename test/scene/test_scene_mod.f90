!> Scenes from namelist files: defaults, messages for bad input, and the chains of section
!> 3.2 (random modes -> sampled G -> LSCE -> modal convolution; FRF file -> FFT and LSCE),
!> each checked against a method that does not share the step under test.
module test_scene_mod
    use, intrinsic :: iso_fortran_env, only: dp => real64
    use testsuite_mod, only: test_error, unittest_type, new_unittest, check, note
    use scene_text_mod, only: tab1_scene, read_scene_text
    use greenconv_api_all, only: scene_type, read_scene, error_type, structure_model, build_structure, make_convolver, &
                                 convolver, contact_response, run_contact, sdof_modes, frf_type, frf_from_modes, &
                                 write_frf, structure_from_modes, modal_set, error_e, run_scene, &
                                 check_scene, stat_input
    use greenconv_conv_methods, only: method_names, method_name_length
    implicit none
    private

    public :: collect_scene

    !> Scratch directory for the files the tests write.
    character(len=*), parameter :: scratch = 'build/test_scratch'

contains

    !> Tests of greenconv_scene_read_input, greenconv_ident_structure and greenconv_scene_run_runner.
    subroutine collect_scene(testsuite)
        type(unittest_type), allocatable, intent(out) :: testsuite(:)

        testsuite = [new_unittest('a scene of the required values gets the paper''s Tab. 1', test_defaults), &
                     new_unittest('bad values: one message naming file, group and variable', test_bad_values), &
                     new_unittest('random modes: LSCE recovers the modes of the sampled G', test_random_identified), &
                     new_unittest('random modes: modal on LSCE modes equals direct on the true g', &
                                  test_random_contact), &
                     new_unittest('FRF file: identified and FFT kernels against the sdof', test_frf_file), &
                     new_unittest('auto: direct for a small N_t*N_g, exact modes for a long run', test_auto_sdof), &
                     new_unittest('auto: the smallest LSCE model meeting the accuracy, else fft', test_auto_modes), &
                     new_unittest('tyre scene: files for each method; implicit near explicit', test_tyre_scene), &
                     new_unittest('tyre scene: bad combinations get one message each', test_tyre_bad), &
                     new_unittest('dt: a receptance''s g is sampled at the scene''s one dt', test_one_dt), &
                     new_unittest('--check refuses a method on a model exactly when the run does', &
                                  test_check_equals_run)]
    end subroutine collect_scene

    !> Write `text` as a scene file in the scratch directory and read it.
    subroutine scene_from_text(name, text, scene, error)
        character(len=*), intent(in) :: name, text
        type(scene_type), intent(out) :: scene
        type(error_type), allocatable, intent(out) :: error

        call read_scene_text(scratch, name, text, scene, error)
    end subroutine scene_from_text

    subroutine test_defaults(error)
        type(test_error), allocatable, intent(out) :: error

        type(scene_type) :: scene
        type(error_type), allocatable :: input_error

        call scene_from_text('required.nml', tab1_scene(), scene, input_error)
        call check(error, .not. allocated(input_error), 'the required values make a valid scene')
        if (allocated(error)) return
        call check(error, scene%dt == 1.0e-4_dp .and. scene%n_steps == 2000 .and. scene%mass == 1.0_dp .and. &
                   scene%stiffness == 1.0e6_dp .and. scene%damping_ratio == 0.02_dp .and. &
                   scene%law%name() == 'power' .and. all(scene%law%parameters() == [1.0e6_dp, 1.5_dp]) .and. &
                   scene%truncation_tol == 0.01_dp .and. scene%task == 'contact' .and. scene%model == 'sdof', &
                   'Tab. 1 values')
        if (allocated(error)) return
        call check(error, scene%preload, 1.0_dp*9.81_dp, 'preload M*g', thr=1.0e-15_dp)
        if (allocated(error)) return
        call check(error, size(scene%methods) == 2, 'two methods')
        if (allocated(error)) return
        call check(error, scene%methods(1) == 'direct' .and. scene%methods(2) == 'modal', 'direct and modal')
    end subroutine test_defaults

    subroutine test_bad_values(error)
        type(test_error), allocatable, intent(out) :: error

        character(len=*), parameter :: expected(5) = [character(len=40) :: &
                                                      'bad.nml:2: &structure mass: expected', &
                                                      'bad.nml:2: &structure damping_ratio', &
                                                      'bad.nml:1: &scene dt: expected', &
                                                      'bad.nml:3: &road profile: expected', &
                                                      'bad.nml:4: &contact preload: expected']
        character(len=:), allocatable :: text
        type(scene_type) :: scene
        type(error_type), allocatable :: input_error
        integer :: i

        do i = 1, size(expected)
            select case (i)
            case (1)
                text = tab1_scene(structure="model = 'sdof', mass = -1.0, stiffness = 1.0e6, damping_ratio = 0.02")
            case (2)
                text = tab1_scene(structure="model = 'sdof', mass = 1.0, stiffness = 1.0e6, damping_ratio = 1.5")
            case (3)
                text = tab1_scene(scene='dt = 0.0, n_steps = 2000')
            case (4)
                text = tab1_scene(road="profile = 'bumpy'")
            case default
                text = tab1_scene(structure="model = 'random_modes'", contact='stiffness = 1.0e6, exponent = 1.5')
            end select
            call scene_from_text('bad.nml', text, scene, input_error)
            call check(error, allocated(input_error), 'rejected: '//trim(expected(i)))
            if (allocated(error)) return
            call check(error, index(input_error%message, trim(expected(i))) > 0 .and. input_error%stat == 2, &
                       'message for '//trim(expected(i))//': '//input_error%message)
            if (allocated(error)) return
        end do
    end subroutine test_bad_values

    !> The shipped scene's structure: every identified mode within 1e-8 of a true one.
    subroutine test_random_identified(error)
        type(test_error), allocatable, intent(out) :: error

        type(scene_type) :: scene
        type(structure_model) :: structure
        type(error_type), allocatable :: input_error
        real(dp) :: worst_frequency, worst_damping

        call read_scene('data/mdof_random.nml', scene, input_error)
        if (.not. allocated(input_error)) call build_structure(scene, structure, input_error)
        call check(error, .not. allocated(input_error), 'data/mdof_random.nml builds')
        if (allocated(error)) return
        call check(error, structure%model%n_modes() == structure%exact%n_modes(), 'as many modes as the system')
        if (allocated(error)) return
        worst_frequency = maxval(abs(abs(structure%model%pole) - abs(structure%exact%pole))/abs(structure%exact%pole))
        worst_damping = maxval(abs(damping(structure%model) - damping(structure%exact))/damping(structure%exact))
        call note('max rel. frequency error', worst_frequency)
        call note('max rel. damping error', worst_damping)
        call note('E', structure%fit%e)
        call check(error, worst_frequency, 0.0_dp, 'frequencies', thr=1.0e-8_dp)
        if (allocated(error)) return
        call check(error, worst_damping, 0.0_dp, 'damping ratios', thr=1.0e-8_dp)
    end subroutine test_random_identified

    !> With a kernel covering the run, direct on the true g and modal on the LSCE modes are the
    !> same convolution of the same system, up to the identification error.
    subroutine test_random_contact(error)
        type(test_error), allocatable, intent(out) :: error

        type(scene_type) :: scene
        type(structure_model) :: structure
        type(error_type), allocatable :: input_error
        type(contact_response) :: direct, modal
        real(dp) :: difference

        call read_scene('data/mdof_random.nml', scene, input_error)
        if (.not. allocated(input_error)) call build_structure(scene, structure, input_error)
        call check(error, .not. allocated(input_error), 'data/mdof_random.nml builds')
        if (allocated(error)) return
        scene%n_steps = 4000
        call run_method('direct', 1.0e-15_dp, direct)
        call run_method('modal', 0.01_dp, modal)
        difference = maxval(abs(direct%displacement - modal%displacement))/maxval(abs(direct%displacement))
        call note('max |du|/max|u|', difference)
        call check(error, difference, 0.0_dp, 'direct (true g) against modal (LSCE)', thr=1.0e-9_dp)
    contains
        subroutine run_method(method, tol, response)
            character(len=*), intent(in) :: method
            real(dp), intent(in) :: tol
            type(contact_response), intent(out) :: response

            class(convolver), allocatable :: conv
            character(len=:), allocatable :: accuracy

            call make_convolver(method, structure, scene%dt, tol, scene%n_steps, conv, accuracy, input_error)
            call run_contact(conv, scene%law, scene%road%sample(scene%dt, scene%n_steps), scene%preload, response)
        end subroutine run_method
    end subroutine test_random_contact

    !> An sdof's G written to a file: identification must give its one mode back (1e-8), the
    !> modal run must match the exact mode's run, and the direct run on the FFT kernel must
    !> stay within the band-limitation error of that kernel.
    subroutine test_frf_file(error)
        type(test_error), allocatable, intent(out) :: error

        type(scene_type) :: scene
        type(structure_model) :: structure, exact
        type(error_type), allocatable :: input_error
        type(contact_response) :: reference, modal, direct
        real(dp) :: modal_difference, direct_difference

        call scene_from_text('sdof_frf.nml', tab1_scene(scene='dt = 1.0e-4, n_steps = 3000', &
                                                        structure="model = 'frf_file', frf_file = '"//scratch &
                                                                  //"/sdof.frf'", &
                                                        contact='stiffness = 1.0e6, exponent = 1.5, preload = 9.81'), &
                             scene, input_error)
        call check(error, .not. allocated(input_error), 'scene reads')
        if (allocated(error)) return
        ! G of the Tab. 1 oscillator from 0 to 5 kHz: g comes at 1/(2*5 kHz) = the scene's dt.
        call write_frf(scratch//'/sdof.frf', frf_from_modes(sdof_modes(1.0_dp, 1.0e6_dp, 0.02_dp), 5000.0_dp, 8001), &
                       input_error)
        call build_structure(scene, structure, input_error)
        call check(error, .not. allocated(input_error), 'structure from the FRF file')
        if (allocated(error)) return
        call check(error, structure%model%n_modes() == 1, 'one mode identified')
        if (allocated(error)) return
        call check(error, abs(structure%model%pole(1) - sdof_pole())/abs(sdof_pole()), 0.0_dp, 'pole', thr=1.0e-8_dp)
        if (allocated(error)) return
        exact = structure_from_modes(sdof_modes(1.0_dp, 1.0e6_dp, 0.02_dp))
        call run_method(exact, 'modal', reference)
        call run_method(structure, 'modal', modal)
        call run_method(structure, 'direct', direct)
        modal_difference = maxval(abs(modal%displacement - reference%displacement))/maxval(abs(reference%displacement))
        direct_difference = maxval(abs(direct%displacement - reference%displacement)) &
                            /maxval(abs(reference%displacement))
        call note('modal: max |du|/max|u|', modal_difference)
        call note('direct on FFT g: max |du|/max|u|', direct_difference)
        call check(error, modal_difference, 0.0_dp, 'modal from the FRF file', thr=1.0e-8_dp)
        if (allocated(error)) return
        ! The FFT kernel misses the lines above 5 kHz: a bias of about A/(pi*w_max) per sample,
        ! 2 % of max|g|, but of alternating effect on u (its sum over the kernel is what G(0)
        ! misses: the band above 5 kHz holds 1e-3 of the static compliance 1/K).
        call check(error, direct_difference, 0.0_dp, 'direct on the FFT kernel', thr=2.0e-3_dp)
    contains
        subroutine run_method(system, method, response)
            type(structure_model), intent(in) :: system
            character(len=*), intent(in) :: method
            type(contact_response), intent(out) :: response

            class(convolver), allocatable :: conv
            character(len=:), allocatable :: accuracy

            call make_convolver(method, system, scene%dt, 1.0e-15_dp, scene%n_steps, conv, accuracy, input_error)
            call run_contact(conv, scene%law, scene%road%sample(scene%dt, scene%n_steps), scene%preload, response)
        end subroutine run_method
    end subroutine test_frf_file

    !> Damping ratios of a modal set.
    function damping(modes) result(xi)
        type(modal_set), intent(in) :: modes
        real(dp), allocatable :: xi(:)

        xi = -real(modes%pole, dp)/abs(modes%pole)
    end function damping

    !> The pole of the Tab. 1 oscillator.
    complex(dp) function sdof_pole()
        type(modal_set) :: modes

        modes = sdof_modes(1.0_dp, 1.0e6_dp, 0.02_dp)
        sdof_pole = modes%pole(1)
    end function sdof_pole

    !> Build the `auto` convolver of a scene given as text; its summary text and model size.
    subroutine auto_choice(name, text, accuracy, label, n, structure, error)
        character(len=*), intent(in) :: name, text
        character(len=:), allocatable, intent(out) :: accuracy, label
        integer, intent(out) :: n
        type(structure_model), intent(out) :: structure
        type(test_error), allocatable, intent(out) :: error

        type(scene_type) :: scene
        type(error_type), allocatable :: run_error
        class(convolver), allocatable :: conv

        call scene_from_text(name, text, scene, run_error)
        if (.not. allocated(run_error)) call build_structure(scene, structure, run_error)
        if (.not. allocated(run_error)) call make_convolver('auto', structure, scene%dt, scene%truncation_tol, &
                                                            scene%n_steps, conv, accuracy, run_error, scene%accuracy)
        if (allocated(run_error)) then
            call check(error, .false., name//': '//run_error%message)
            return
        end if
        call conv%model_size(n, label)
        call check(error, conv%name == 'auto', name//': the convolver is named auto')
    end subroutine auto_choice

    !> Tab. 1: 2000 steps with N_g = 1999 is 4e6 multiply-adds, under the 1e7 limit: direct.
    !> At dt = 10 us for 200000 steps (N_g = 23112): 4.6e9, and the sdof's own mode: exact.
    subroutine test_auto_sdof(error)
        type(test_error), allocatable, intent(out) :: error

        character(len=:), allocatable :: accuracy, label
        type(structure_model) :: structure
        integer :: n

        call auto_choice('auto_short.nml', tab1_scene(convolution="methods = 'auto'"), accuracy, label, n, &
                         structure, error)
        if (allocated(error)) return
        call check(error, index(accuracy, 'chose direct: N_t*N_g = ') == 1 .and. label == 'N_g' .and. n == 1999, &
                   'short run: direct with N_g = 1999, said so ('//accuracy//')')
        if (allocated(error)) return
        call auto_choice('auto_long.nml', tab1_scene(scene='dt = 1.0e-5, n_steps = 200000', &
                                                     convolution="methods = 'auto'"), &
                         accuracy, label, n, structure, error)
        if (allocated(error)) return
        call check(error, index(accuracy, 'chose exact: ') == 1 .and. label == 'N_m' .and. n == 1, &
                   'long run: exact on the one mode, said so ('//accuracy//')')
    end subroutine test_auto_sdof

    !> The section 3.2 structure (10 modes) seen through its sampled G, 10000 steps: with
    !> accuracy 1e-3 auto must recur on an LSCE model with E <= 1e-3 that needs all its
    !> modes (without any one of them E, recomputed here against G, exceeds 1e-3); allowed
    !> at most 3 modes, no model can, and auto falls back to fft on the true g.
    subroutine test_auto_modes(error)
        type(test_error), allocatable, intent(out) :: error

        real(dp), parameter :: two_pi = 2.0_dp*acos(-1.0_dp)
        character(len=*), parameter :: scene_body = 'dt = 1.0e-4, n_steps = 10000', &
                                       structure_body = "model = 'random_modes'", &
                                       contact_body = 'stiffness = 1.0e6, exponent = 1.5, preload = 100.0', &
                                       convolution_body = "methods = 'auto', accuracy = 1.0e-3"
        character(len=:), allocatable :: accuracy, label
        type(structure_model) :: structure
        type(modal_set) :: fewer
        real(dp) :: e_fewer
        integer :: n, k, j

        call auto_choice('auto_modes.nml', tab1_scene(scene_body, structure_body, 'f_max = 2000.0, n_freq = 8001', &
                                                      contact=contact_body, convolution=convolution_body), &
                         accuracy, label, n, structure, error)
        if (allocated(error)) return
        call note('modes chosen', real(n, dp))
        call note('E', structure%fit%e)
        call check(error, index(accuracy, 'chose exact: ') == 1 .and. label == 'N_m' .and. &
                   structure%fit%e <= 1.0e-3_dp, &
                   'an LSCE model meeting E <= 1e-3, said so ('//accuracy//')')
        if (allocated(error)) return
        e_fewer = huge(1.0_dp)
        do k = 1, n
            fewer%pole = pack(structure%model%pole, [(k /= j, j=1, size(structure%model%pole))])
            fewer%residue = pack(structure%model%residue, [(k /= j, j=1, size(structure%model%pole))])
            e_fewer = min(e_fewer, error_e(structure%frf%receptance, &
                                           fewer%receptance(two_pi*structure%frf%frequency)))
        end do
        call note('smallest E with one mode left out', e_fewer)
        call check(error, e_fewer > 1.0e-3_dp, 'every mode of the choice is needed for E <= 1e-3')
        if (allocated(error)) return
        call auto_choice('auto_fft.nml', tab1_scene(scene_body, structure_body, &
                                                    'f_max = 2000.0, n_freq = 8001, max_order = 3', &
                                                    contact=contact_body, convolution=convolution_body), &
                         accuracy, label, n, structure, error)
        if (allocated(error)) return
        call check(error, index(accuracy, 'chose fft: no LSCE model meets') == 1 .and. label == 'N_g', &
                   'no model within 3 modes: fft, said so ('//accuracy//')')
    end subroutine test_auto_modes

    !> A short tyre/road run (6 points, 400 steps of 20 us) through run_scene: one file per
    !> method with N_t*N_c rows; the implicit (exact) and explicit (modal) total forces agree
    !> to within 1 % of the preload (the hold's O(dt) shift of the force against the
    !> rectangle rule's, measured 2e-3 here), and direct equals modal to 1e-9 (same modes,
    !> sampled, the kernel not truncated within 400 steps).
    subroutine test_tyre_scene(error)
        type(test_error), allocatable, intent(out) :: error

        character(len=*), parameter :: text = "&scene name = 'tyre', output_dir = '"//scratch//"', dt = 2.0e-5, " &
            //"n_steps = 400 / &structure model = 'tyre', damping_ratio = 0.05 / &road profile = 'file', " &
            //"road_file = 'data/road_sample.dat', x_start = 1.0, speed = 20.0 / &contact n_points = 6, " &
            //"patch_length = 0.1, stiffness = 2.0e5, exponent = 1.0, preload = 1200.0 / " &
            //"&convolution methods = 'exact', 'modal', 'direct', truncation_tol = 1.0e-6, accuracy = 0.5 /"
        ! accuracy 0.5: the methods against each other are under test, not the default band's error
        type(scene_type) :: scene
        type(error_type), allocatable :: run_error
        real(dp), allocatable :: exact(:, :), modal(:, :), direct(:, :)
        integer :: unit

        call scene_from_text('tyre.nml', text, scene, run_error)
        if (.not. allocated(run_error)) then
            open (newunit=unit, status='scratch', action='readwrite')
            call run_scene(scene, unit, run_error)
            close (unit)
        end if
        call check(error, .not. allocated(run_error), 'the tyre scene runs')
        if (allocated(error)) return
        call read_rows(scratch//'/tyre_exact.dat', exact)
        call read_rows(scratch//'/tyre_modal.dat', modal)
        call read_rows(scratch//'/tyre_direct.dat', direct)
        call check(error, size(exact, 2) == 400*6 .and. size(modal, 2) == 400*6 .and. size(direct, 2) == 400*6, &
                   'N_t*N_c rows in each file')
        if (allocated(error)) return
        call note('max |F_exact - F_modal| / F0 (total)', maxval(abs(exact(7, :) - modal(7, :)))/1200.0_dp)
        call note('max |u_direct - u_modal| / max|u|', &
                  maxval(abs(direct(4, :) - modal(4, :)))/maxval(abs(modal(4, :))))
        call check(error, maxval(abs(exact(7, :) - modal(7, :))), 0.0_dp, 'total force, implicit vs explicit', &
                   thr=0.01_dp*1200.0_dp)
        if (allocated(error)) return
        call check(error, maxval(abs(direct(4, :) - modal(4, :))), 0.0_dp, 'u, direct vs modal', &
                   thr=1.0e-9_dp*maxval(abs(modal(4, :))))
    end subroutine test_tyre_scene

    !> The 7 columns of a multi-point output file, one column of `rows` per line.
    subroutine read_rows(path, rows)
        character(len=*), intent(in) :: path
        real(dp), allocatable, intent(out) :: rows(:, :)

        character(len=512) :: line
        real(dp) :: values(7)
        integer :: unit, stat, n

        allocate (rows(7, 0))
        open (newunit=unit, file=path, status='old', action='read', iostat=stat)
        if (stat /= 0) return
        n = 0
        do
            read (unit, '(a)', iostat=stat) line
            if (stat /= 0) exit
            if (line(1:1) == '#' .or. len_trim(line) == 0) cycle
            read (line, *) values
            rows = reshape([rows, values], [7, n + 1])
            n = n + 1
        end do
        close (unit)
    end subroutine read_rows

    !> A multi-point scene needs the tyre model and a road file, and the tyre a file road.
    subroutine test_tyre_bad(error)
        type(test_error), allocatable, intent(out) :: error

        type(scene_type) :: scene
        type(error_type), allocatable :: run_error
        integer :: unit

        call scene_from_text('bad_points.nml', tab1_scene(contact='stiffness = 1.0e6, exponent = 1.5, n_points = 5'), &
                             scene, run_error)
        call check(error, allocated(run_error), 'sdof with 5 points is refused')
        if (allocated(error)) return
        call check(error, index(run_error%message, "&contact n_points: expected 1, or a number of points >= 1 " &
                                //"for model 'tyre' or 'tyre_plate', found 5") > 0, 'message: '//run_error%message)
        if (allocated(error)) return
        call scene_from_text('bad_tyre.nml', tab1_scene(structure="model = 'tyre'", &
                                                        contact='stiffness = 1.0e6, exponent = 1.5, preload = 100.0'), &
                             scene, run_error)
        call check(error, allocated(run_error), 'a tyre on the sine road is refused when the scene is read')
        if (allocated(error)) return
        call check(error, index(run_error%message, "bad_tyre.nml:2: &structure model: expected task = 'contact' " &
                                //"and &road profile = 'file' or 'texture' for model 'tyre'") > 0, &
                   'message: '//run_error%message)
        if (allocated(error)) return
        call scene_from_text('bad_road.nml', tab1_scene(road="profile = 'file', road_file = 'data/road_sample.dat', " &
                                                        //'speed = 1.0e4'), scene, run_error)
        call check(error, allocated(run_error), 'a single point running off the road file is refused')
        if (allocated(error)) return
        call check(error, index(run_error%message, '&road x_start: data/road_sample.dat: expected a road from ' &
                                //'x = 0.0 m to 1999.0 m (the run), found 0.0 m to 10.0 m') > 0, &
                   'message: '//run_error%message)
    end subroutine test_tyre_bad

    !> The scene's dt is the only time step: build_structure samples a receptance's g at it
    !> (every second FFT sample for twice the FFT step), and an `identify` scene samples none.
    subroutine test_one_dt(error)
        type(test_error), allocatable, intent(out) :: error

        type(scene_type) :: scene
        type(structure_model) :: fine, coarse
        type(error_type), allocatable :: input_error
        character(len=*), parameter :: structure = "model = 'frf_file', frf_file = '"//scratch//"/one_dt.frf'"
        integer :: n

        call write_frf(scratch//'/one_dt.frf', frf_from_modes(sdof_modes(1.0_dp, 1.0e6_dp, 0.02_dp), 5000.0_dp, &
                                                                 801), input_error)
        call scene_from_text('one_dt_fine.nml', tab1_scene(scene='dt = 1.0e-4, n_steps = 100', structure=structure, &
                             contact='stiffness = 1.0e6, exponent = 1.5, preload = 9.81'), scene, input_error)
        if (.not. allocated(input_error)) call build_structure(scene, fine, input_error)
        call check(error, .not. allocated(input_error), 'the scene at dt = 1e-4 s builds')
        if (allocated(error)) return
        call scene_from_text('one_dt_coarse.nml', tab1_scene(scene='dt = 2.0e-4, n_steps = 100', &
                             structure=structure, contact='stiffness = 1.0e6, exponent = 1.5, preload = 9.81'), &
                             scene, input_error)
        if (.not. allocated(input_error)) call build_structure(scene, coarse, input_error)
        call check(error, .not. allocated(input_error), 'the scene at dt = 2e-4 s builds')
        if (allocated(error)) return
        n = size(coarse%sampled_g)
        call check(error, n > 1 .and. all(coarse%sampled_g == fine%sampled_g(1:2*n - 1:2)), &
                   'g at 2e-4 s is every second sample of g at 1e-4 s')
        if (allocated(error)) return
        call scene_from_text('one_dt_identify.nml', "&scene task = 'identify', dt = 1.0e-4 /"//new_line('a') &
                             //'&structure '//structure//' /', scene, input_error)
        if (.not. allocated(input_error)) call build_structure(scene, coarse, input_error)
        call check(error, .not. allocated(input_error), 'the identify scene builds')
        if (allocated(error)) return
        call check(error, .not. allocated(coarse%sampled_g), 'task identify samples no g')
    end subroutine test_one_dt

    !> Every method of the registry on every model (sdof, random_modes, frf_file, tyre), in
    !> scenes of 40 steps: the check (`read_scene`, then `check_scene`, as `--check` runs
    !> them) refuses the pair exactly when the run refuses it (bad input, `stat_input`), and
    !> its message names the file, line, group and variable. The run is given the method
    !> behind the check's back: the scene is read with `direct`, then its list replaced.
    subroutine test_check_equals_run(error)
        type(test_error), allocatable, intent(out) :: error

        character(len=*), parameter :: models(4) = [character(len=12) :: 'sdof', 'random_modes', 'frf_file', &
                                                     'tyre']
        character(len=method_name_length) :: names(size(method_names()))
        type(scene_type) :: scene
        type(error_type), allocatable :: check_error, run_error
        logical :: check_refuses, run_refuses
        integer :: i, j, unit, refused

        names = method_names()
        refused = 0
        open (newunit=unit, status='scratch', action='readwrite')
        do i = 1, size(models)
            do j = 1, size(names)
                call scene_from_text('pair.nml', pair_scene(trim(models(i)), trim(names(j))), scene, check_error)
                if (.not. allocated(check_error)) call check_scene(scene, unit, check_error)
                check_refuses = allocated(check_error)
                call scene_from_text('pair.nml', pair_scene(trim(models(i)), 'direct'), scene, run_error)
                call check(error, .not. allocated(run_error), trim(models(i))//' with direct is a valid scene')
                if (allocated(error)) exit
                scene%methods = [names(j)]
                call run_scene(scene, unit, run_error)
                run_refuses = .false.
                if (allocated(run_error)) run_refuses = run_error%stat == stat_input
                call check(error, check_refuses .eqv. run_refuses, trim(names(j))//' on '//trim(models(i))// &
                           ': check '//merge('refuses', 'accepts', check_refuses)//', run ' &
                           //merge('refuses', 'accepts', run_refuses))
                if (allocated(error)) exit
                if (.not. check_refuses) cycle
                refused = refused + 1
                call check(error, index(check_error%message, 'pair.nml:') > 0 .and. &
                           index(check_error%message, ': &convolution methods: ') > 0, &
                           'file:line, group and variable: '//check_error%message)
                if (allocated(error)) exit
            end do
            if (allocated(error)) exit
        end do
        close (unit)
        call note('pairs refused', real(refused, dp))
    end subroutine test_check_equals_run

    !> A scene of 40 steps of `model` running `method` (in the scratch directory).
    function pair_scene(model, method) result(text)
        character(len=*), intent(in) :: model, method
        character(len=:), allocatable :: text

        character(len=*), parameter :: scene = "name = 'pair', output_dir = '"//scratch//"', n_steps = 40, ", &
                                       preload = 'stiffness = 1.0e6, exponent = 1.5, preload = 100.0'

        select case (model)
        case ('sdof')
            text = tab1_scene(scene=scene//'dt = 1.0e-4', convolution="methods = '"//method//"'")
        case ('random_modes')
            text = tab1_scene(scene=scene//'dt = 1.0e-4', structure="model = 'random_modes', n_modes = 2", &
                              identification='f_max = 2000.0, n_freq = 1001', contact=preload, &
                              convolution="methods = '"//method//"'")
        case ('frf_file')
            text = tab1_scene(scene=scene//'dt = 5.0e-4', &
                              structure="model = 'frf_file', frf_file = 'data/sample_receptance.frf'", &
                              contact=preload, convolution="methods = '"//method//"'")
        case default
            text = tab1_scene(scene=scene//'dt = 2.0e-5', structure="model = 'tyre', damping_ratio = 0.05", &
                              road="profile = 'file', road_file = 'data/road_sample.dat', x_start = 1.0, " &
                              //'speed = 20.0', &
                              contact='n_points = 3, patch_length = 0.1, stiffness = 2.0e5, exponent = 1.0, ' &
                              //'preload = 1200.0', convolution="methods = '"//method//"'")
        end select
    end function pair_scene

end module test_scene_mod
