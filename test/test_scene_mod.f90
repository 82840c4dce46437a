!> Scenes from namelist files: defaults, messages for bad input, and the chains of section
!> 3.2 (random modes -> sampled G -> LSCE -> modal convolution; FRF file -> FFT and LSCE),
!> each checked against a method that does not share the step under test.
module test_scene_mod
    use, intrinsic :: iso_fortran_env, only: dp => real64
    use testsuite_mod, only: test_error, unittest_type, new_unittest, check, note
    use files_mod, only: make_directory
    use greenconv, only: scene_type, read_scene, error_type, structure_model, build_structure, make_convolver, &
                         convolver, contact_response, run_contact, sdof_modes, frf_type, frf_from_modes, &
                         write_frf, structure_from_modes, modal_set
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
                     new_unittest('FRF file: identified and FFT kernels against the sdof', test_frf_file)]
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

end module test_scene_mod
