!> Scenes from namelist files: defaults, messages for bad input, and the chains of section
!> 3.2 (random modes -> sampled G -> LSCE -> modal convolution; FRF file -> FFT and LSCE),
!> each checked against a method that does not share the step under test.
module test_scene_mod
    use, intrinsic :: iso_fortran_env, only: dp => real64
    use testsuite_mod, only: test_error, unittest_type, new_unittest, check, note
    use files_mod, only: make_directory
    use greenconv, only: scene_type, read_scene, error_type, structure_model, build_structure, make_convolver, &
                         convolver, contact_response, run_contact, sdof_modes, frf_type, frf_from_modes, &
                         write_frf, structure_from_modes, modal_set, error_e
    implicit none
    private

    public :: collect_scene

    !> Scratch directory for the files the tests write.
    character(len=*), parameter :: scratch = 'build/test_scratch'

contains

    !> Tests of scene_mod, structure_mod and scene_run_mod.
    subroutine collect_scene(testsuite)
        type(unittest_type), allocatable, intent(out) :: testsuite(:)

        testsuite = [new_unittest('an empty scene file gives the paper''s Tab. 1', test_defaults), &
                     new_unittest('bad values: one message naming file, group and variable', test_bad_values), &
                     new_unittest('random modes: LSCE recovers the modes of the sampled G', test_random_identified), &
                     new_unittest('random modes: modal on LSCE modes equals direct on the true g', &
                                  test_random_contact), &
                     new_unittest('FRF file: identified and FFT kernels against the sdof', test_frf_file), &
                     new_unittest('auto: direct for a small N_t*N_g, exact modes for a long run', test_auto_sdof), &
                     new_unittest('auto: the smallest LSCE model meeting the accuracy, else fft', test_auto_modes)]
    end subroutine collect_scene

    !> Write `text` as a scene file and read it.
    subroutine scene_from_text(name, text, scene, error)
        character(len=*), intent(in) :: name, text
        type(scene_type), intent(out) :: scene
        type(error_type), allocatable, intent(out) :: error

        type(error_type), allocatable :: ignored
        integer :: unit

        call make_directory(scratch, ignored)
        open (newunit=unit, file=scratch//'/'//name, status='replace', action='write')
        write (unit, '(a)') text
        close (unit)
        call read_scene(scratch//'/'//name, scene, error)
    end subroutine scene_from_text

    subroutine test_defaults(error)
        type(test_error), allocatable, intent(out) :: error

        type(scene_type) :: scene
        type(error_type), allocatable :: input_error

        call scene_from_text('empty.nml', '! nothing', scene, input_error)
        call check(error, .not. allocated(input_error), 'an empty file is a valid scene')
        if (allocated(error)) return
        call check(error, scene%dt == 1.0e-4_dp .and. scene%n_steps == 2000 .and. scene%mass == 1.0_dp .and. &
                   scene%stiffness == 1.0e6_dp .and. scene%damping_ratio == 0.02_dp .and. &
                   scene%law%stiffness == 1.0e6_dp .and. scene%law%exponent == 1.5_dp .and. &
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

        character(len=*), parameter :: bodies(5) = [character(len=60) :: &
                                                    '&structure mass = -1.0 /', &
                                                    '&structure damping_ratio = 1.5 /', &
                                                    '&scene dt = 0.0 /', &
                                                    '&road profile = ''bumpy'' /', &
                                                    '&structure model = ''random_modes'' /']
        character(len=*), parameter :: expected(5) = [character(len=40) :: &
                                                      'bad.nml: &structure mass: expected', &
                                                      'bad.nml: &structure damping_ratio', &
                                                      'bad.nml: &scene dt: expected', &
                                                      'bad.nml: &road profile: expected', &
                                                      'bad.nml: &contact preload: expected']
        type(scene_type) :: scene
        type(error_type), allocatable :: input_error
        integer :: i

        do i = 1, size(bodies)
            call scene_from_text('bad.nml', trim(bodies(i)), scene, input_error)
            call check(error, allocated(input_error), 'rejected: '//trim(bodies(i)))
            if (allocated(error)) return
            call check(error, index(input_error%message, trim(expected(i))) > 0 .and. input_error%stat == 2, &
                       'message for '//trim(bodies(i))//': '//input_error%message)
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

        call scene_from_text('sdof_frf.nml', "&structure model = 'frf_file', frf_file = '"//scratch// &
                             "/sdof.frf' / &contact preload = 9.81 / &scene n_steps = 3000 /", scene, input_error)
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

        call auto_choice('auto_short.nml', "&convolution methods = 'auto' /", accuracy, label, n, structure, error)
        if (allocated(error)) return
        call check(error, index(accuracy, 'chose direct: N_t*N_g = ') == 1 .and. label == 'N_g' .and. n == 1999, &
                   'short run: direct with N_g = 1999, said so ('//accuracy//')')
        if (allocated(error)) return
        call auto_choice('auto_long.nml', "&scene dt = 1.0e-5, n_steps = 200000 / &convolution methods = 'auto' /", &
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
        character(len=*), parameter :: common = "&scene n_steps = 10000 / &structure model = 'random_modes' / " &
                                        //"&contact preload = 100.0 / "
        character(len=:), allocatable :: accuracy, label
        type(structure_model) :: structure
        type(modal_set) :: fewer
        real(dp) :: e_fewer
        integer :: n, k, j

        call auto_choice('auto_modes.nml', common//"&identification f_max = 2000.0, n_freq = 8001 / " &
                         //"&convolution methods = 'auto', accuracy = 1.0e-3 /", accuracy, label, n, structure, error)
        if (allocated(error)) return
        call note('modes chosen', real(n, dp))
        call note('E', structure%fit%e)
        call check(error, index(accuracy, 'chose exact: ') == 1 .and. label == 'N_m' &
                   .and. structure%fit%e <= 1.0e-3_dp, 'an LSCE model meeting E <= 1e-3, said so ('//accuracy//')')
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
        call auto_choice('auto_fft.nml', common//"&identification f_max = 2000.0, n_freq = 8001, max_order = 3 / " &
                         //"&convolution methods = 'auto', accuracy = 1.0e-3 /", accuracy, label, n, structure, error)
        if (allocated(error)) return
        call check(error, index(accuracy, 'chose fft: no LSCE model meets') == 1 .and. label == 'N_g', &
                   'no model within 3 modes: fft, said so ('//accuracy//')')
    end subroutine test_auto_modes

end module test_scene_mod
