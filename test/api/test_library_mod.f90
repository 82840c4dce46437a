!> The embedding API: `new_convolver` and its checks, the three ways to build a structure,
!> `contact_step` against `run_contact`, and the Fortran 77 style layer (greenconv_legacy)
!> against the Fortran API. Equalities are to the bit wherever the same arithmetic runs.
module test_library_mod
    use, intrinsic :: iso_fortran_env, only: dp => real64, int64
    use testsuite_mod, only: test_error, unittest_type, new_unittest, check, note
    use greenconv_api_all, only: error_type, stat_input, convolver, contact_law, contact_response, run_contact, &
                                 sdof_modes, sdof_impulse, structure_model, structure_from_modes, &
                                 structure_from_samples, new_convolver, free_convolver, contact_step, read_frf, &
                                 frf_type, lsce_options, structure_from_frf, frf_from_modes
    use greenconv_legacy, only: gcsdof, gcsamp, gcmode, gccont, gcstep, gchist, gcfree, gcid, gcfrf, gcfrfi, gcdesc, &
                                gcscen
    use greenconv_api_all, only: scene_type, build_structure
    use greenconv_api_handle, only: frf_file_structure
    use scene_text_mod, only: read_scene_text
    use greenconv_contact_law_power, only: power_law
    implicit none
    private

    public :: collect_library

    !> The scene of data/sdof_sine.nml (SI units).
    real(dp), parameter :: mass = 1.0_dp, stiffness = 1.0e6_dp, xi = 0.02_dp, dt = 1.0e-4_dp
    real(dp), parameter :: k_c = 1.0e6_dp, exponent = 1.5_dp, preload = 9.81_dp
    integer, parameter :: n_steps = 2000

contains

    !> Tests of the embedding API.
    subroutine collect_library(testsuite)
        type(unittest_type), allocatable, intent(out) :: testsuite(:)

        testsuite = [new_unittest('contact_step equals run_contact, recursive and fft', test_contact_step), &
                     new_unittest('sampled g: direct equals direct on the modes', test_samples), &
                     new_unittest('new_convolver: bad requests give stat_input and a message', test_bad_requests), &
                     new_unittest('legacy: gcsdof + gccont and gcstep equal the Fortran API', test_legacy_contact), &
                     new_unittest('legacy: statuses and messages, null handles', test_legacy_errors), &
                     new_unittest('legacy: gcid and gcfrf on data/sample_receptance.frf', test_legacy_frf), &
                     new_unittest('a door identifies a file as a scene does, ml and lsce', test_door_as_scene), &
                     new_unittest('g from a receptance runs only at the dt it was sampled at', test_sample_step)]
    end subroutine collect_library

    !> Road heights of the scene [m].
    function road() result(heights)
        real(dp) :: heights(n_steps)

        integer :: n

        heights = [(1.0e-3_dp*sin(100.0_dp*(n*dt)), n=0, n_steps - 1)]
    end function road

    !> A caller's own loop of contact_step gives run_contact's histories to the bit.
    subroutine test_contact_step(error)
        type(test_error), allocatable, intent(out) :: error

        character(len=9), parameter :: methods(2) = [character(len=9) :: 'recursive', 'fft']
        class(convolver), allocatable :: conv
        type(error_type), allocatable :: build_error
        type(contact_response) :: response
        real(dp) :: u(n_steps), f(n_steps), delta(n_steps), heights(n_steps), worst
        integer :: i, n

        heights = road()
        worst = 0.0_dp
        do i = 1, size(methods)
            call new_convolver(trim(methods(i)), structure_from_modes(sdof_modes(mass, stiffness, xi)), dt, n_steps, &
                               conv, build_error)
            call check(error, .not. allocated(build_error), 'new_convolver '//trim(methods(i)))
            if (allocated(error)) return
            call run_contact(conv, power_law(k_c, exponent), heights, preload, response)
            call conv%reset()
            do n = 1, n_steps
                call contact_step(conv, power_law(k_c, exponent), heights(n), preload, u(n), f(n), delta(n))
            end do
            worst = max(worst, maxval(abs(u - response%displacement)), maxval(abs(f - response%force)), &
                        maxval(abs(delta - response%compression)))
            call free_convolver(conv)
        end do
        call note('max difference', worst)
        call check(error, worst, 0.0_dp, 'identical histories', thr=0.0_dp)
    end subroutine test_contact_step

    !> g sampled from the sdof's eq. (8) at dt over the run: `direct` on the samples equals
    !> `direct` on the exact mode (the same kernel, truncated by the same rule) to 1e-13 of
    !> max|u| (eq. 8 and the pole-residue form give g to the last bits only).
    subroutine test_samples(error)
        type(test_error), allocatable, intent(out) :: error

        class(convolver), allocatable :: on_modes, on_samples
        type(error_type), allocatable :: build_error
        type(contact_response) :: a, b
        type(structure_model) :: sampled
        integer :: j

        sampled = structure_from_samples(sdof_impulse(mass, stiffness, xi, [(j*dt, j=0, n_steps - 1)]))
        call new_convolver('direct', structure_from_modes(sdof_modes(mass, stiffness, xi)), dt, n_steps, on_modes, &
                           build_error)
        if (.not. allocated(build_error)) call new_convolver('direct', sampled, dt, n_steps, on_samples, build_error)
        call check(error, .not. allocated(build_error), 'both convolvers built')
        if (allocated(error)) return
        call run_contact(on_modes, power_law(k_c, exponent), road(), preload, a)
        call run_contact(on_samples, power_law(k_c, exponent), road(), preload, b)
        call note('max|u_samples - u_modes|/max|u|', maxval(abs(a%displacement - b%displacement)) &
                  /maxval(abs(a%displacement)))
        call check(error, maxval(abs(a%displacement - b%displacement)), 0.0_dp, 'same displacements', &
                   thr=1.0e-13_dp*maxval(abs(a%displacement)))
    end subroutine test_samples

    !> Requests new_convolver refuses, each with stat_input and a message naming the problem.
    subroutine test_bad_requests(error)
        type(test_error), allocatable, intent(out) :: error

        type(structure_model) :: modes, sampled

        modes = structure_from_modes(sdof_modes(mass, stiffness, xi))
        sampled = structure_from_samples([0.0_dp, 1.0_dp, 0.5_dp])
        call refused('modal', sampled, dt, n_steps, 'needs modes', error)
        if (allocated(error)) return
        call refused('auto', sampled, dt, n_steps, 'needs modes', error)
        if (allocated(error)) return
        call refused('direct', modes, 0.0_dp, n_steps, 'time step', error)
        if (allocated(error)) return
        call refused('direct', modes, dt, 0, 'number of steps', error)
        if (allocated(error)) return
        call refused('spline', modes, dt, n_steps, 'unknown convolution method', error)
    end subroutine test_bad_requests

    !> new_convolver refuses the request with stat_input and a message containing `expected`.
    subroutine refused(method, structure, step, steps, expected, error)
        character(len=*), intent(in) :: method, expected
        type(structure_model), intent(in) :: structure
        real(dp), intent(in) :: step
        integer, intent(in) :: steps
        type(test_error), allocatable, intent(out) :: error

        class(convolver), allocatable :: conv
        type(error_type), allocatable :: build_error

        call new_convolver(method, structure, step, steps, conv, build_error)
        call check(error, allocated(build_error), method//': refused')
        if (allocated(error)) return
        call check(error, build_error%stat == stat_input .and. index(build_error%message, expected) > 0 &
                   .and. .not. allocated(conv), method//': got "'//build_error%message//'"')
    end subroutine refused

    !> The legacy layer runs the same loops: gccont (modal) and a gcstep loop (direct) equal
    !> run_contact on the Fortran API's convolvers to the bit.
    subroutine test_legacy_contact(error)
        type(test_error), allocatable, intent(out) :: error

        class(convolver), allocatable :: conv
        type(error_type), allocatable :: build_error
        type(contact_response) :: modal, direct
        real(dp) :: u(n_steps), f(n_steps), delta(n_steps), heights(n_steps), worst
        integer(int64) :: handle
        integer :: ierr, n
        character(len=200) :: message

        heights = road()
        call new_convolver('modal', structure_from_modes(sdof_modes(mass, stiffness, xi)), dt, n_steps, conv, &
                           build_error)
        call run_contact(conv, power_law(k_c, exponent), heights, preload, modal)
        call new_convolver('direct', structure_from_modes(sdof_modes(mass, stiffness, xi)), dt, n_steps, conv, &
                           build_error)
        call run_contact(conv, power_law(k_c, exponent), heights, preload, direct)
        call gcsdof(mass, stiffness, xi, dt, n_steps, 'MODAL', handle, ierr, message)
        call gccont(handle, k_c, exponent, preload, n_steps, heights, u, f, delta, ierr, message)
        call gcfree(handle)
        worst = maxval(abs(u - modal%displacement)) + maxval(abs(f - modal%force))
        call gcsdof(mass, stiffness, xi, dt, n_steps, 'direct', handle, ierr, message)
        do n = 1, n_steps
            call gcstep(handle, k_c, exponent, preload, heights(n), u(n), f(n), delta(n), ierr)
        end do
        call gcfree(handle)
        worst = worst + maxval(abs(u - direct%displacement)) + maxval(abs(f - direct%force))
        call note('sum of max differences', worst)
        call check(error, worst, 0.0_dp, 'identical histories', thr=0.0_dp)
        if (allocated(error)) return
        call check(error, handle == 0_int64, 'gcfree sets the handle to 0')
    end subroutine test_legacy_contact

    !> Bad values give status 2 with a message and a null handle; a null handle, status 2; a
    !> missing scene file, status 2 and a message naming it.
    subroutine test_legacy_errors(error)
        type(test_error), allocatable, intent(out) :: error

        integer(int64) :: handle
        integer :: ierr
        real(dp) :: uh, u(3), f(3), delta(3)
        character(len=200) :: message

        call gcsdof(-1.0_dp, stiffness, xi, dt, n_steps, 'direct', handle, ierr, message)
        call check(error, ierr == stat_input .and. handle == 0_int64 .and. index(message, 'mass') > 0, &
                   'negative mass: '//trim(message))
        if (allocated(error)) return
        call gcmode(1, [-1.0_dp], [-5.0_dp], [0.0_dp], [1.0_dp], dt, n_steps, 'modal', handle, ierr, message)
        call check(error, ierr == stat_input .and. index(message, 'pole') > 0, 'bad pole: '//trim(message))
        if (allocated(error)) return
        call gcsamp(3, [0.0_dp, 1.0_dp, 0.5_dp], dt, n_steps, 'exact', handle, ierr, message)
        call check(error, ierr == stat_input .and. index(message, 'needs modes') > 0, 'samples, exact: '//trim(message))
        if (allocated(error)) return
        call gchist(0_int64, uh, ierr)
        call check(error, ierr == stat_input, 'gchist on handle 0')
        if (allocated(error)) return
        call gccont(0_int64, k_c, exponent, preload, 3, [0.0_dp, 0.0_dp, 0.0_dp], u, f, delta, ierr, message)
        call check(error, ierr == stat_input .and. index(message, 'null') > 0, 'gccont on handle 0: '//trim(message))
        if (allocated(error)) return
        call gcsdof(mass, stiffness, xi, dt, n_steps, 'direct', handle, ierr, message)
        call gccont(handle, -k_c, exponent, preload, 3, [0.0_dp, 0.0_dp, 0.0_dp], u, f, delta, ierr, message)
        call gcfree(handle)
        call check(error, ierr == stat_input .and. index(message, 'stiffness') > 0, 'negative k_c: '//trim(message))
        if (allocated(error)) return
        call gcscen('no/such/scene.nml', ierr, message)
        call check(error, ierr == stat_input .and. index(message, 'cannot open') > 0, 'missing scene: '//trim(message))
    end subroutine test_legacy_errors

    !> gcid finds the modes structure_from_frf finds; gcfrf builds a modal convolver on them.
    subroutine test_legacy_frf(error)
        type(test_error), allocatable, intent(out) :: error

        character(len=*), parameter :: path = 'data/sample_receptance.frf'
        type(frf_type) :: frf
        type(lsce_options) :: options
        type(structure_model) :: structure
        type(error_type), allocatable :: fit_error
        real(dp) :: pole_re(30), pole_im(30), residue_re(30), residue_im(30), e
        integer(int64) :: handle
        integer :: n_modes, ierr
        character(len=200) :: message, description

        call read_frf(path, frf, fit_error)
        if (.not. allocated(fit_error)) call structure_from_frf(frf, options, 0.0_dp, structure, fit_error)
        call check(error, .not. allocated(fit_error), 'structure_from_frf')
        if (allocated(error)) return
        call gcid(path, options%tol_e, options%max_modes, 30, n_modes, pole_re, pole_im, residue_re, residue_im, e, &
                  ierr, message)
        call note('modes', real(n_modes, dp))
        call note('E', e)
        call check(error, ierr == 0 .and. n_modes == structure%model%n_modes() .and. e == structure%fit%e, &
                   'gcid: '//trim(message))
        if (allocated(error)) return
        call gcid(path, options%tol_e, options%max_modes, 1, n_modes, pole_re, pole_im, residue_re, residue_im, e, &
                  ierr, message)
        call check(error, ierr == stat_input .and. index(message, 'ncap') > 0, 'gcid, too small: '//trim(message))
        if (allocated(error)) return
        call gcfrf(path, dt, n_steps, 'modal', options%tol_e, options%max_modes, handle, ierr, message)
        call gcdesc(handle, description, ierr)
        call gcfree(handle)
        call check(error, ierr == 0 .and. index(description, 'ML fit') > 0, 'gcfrf: '//trim(description))
        if (allocated(error)) return
        call gcfrfi(path, dt, n_steps, 'modal', 'LSCE', options%tol_e, options%max_modes, handle, ierr, message)
        call gcdesc(handle, description, ierr)
        call gcfree(handle)
        call check(error, ierr == 0 .and. index(description, 'LSCE') > 0, 'gcfrfi lsce: '//trim(description))
        if (allocated(error)) return
        call gcfrfi(path, dt, n_steps, 'modal', 'poly_reference', options%tol_e, options%max_modes, handle, ierr, &
                    message)
        call check(error, ierr == stat_input .and. handle == 0 .and. index(message, 'poly_reference') > 0, &
                   'gcfrfi poly_reference: '//trim(message))
    end subroutine test_legacy_frf

    !> The doors' receptance file and a scene's `frf_file` model on the same file identify the
    !> same modes to the bit: by maximum likelihood by default, by LSCE when both ask it.
    subroutine test_door_as_scene(error)
        type(test_error), allocatable, intent(out) :: error

        character(len=*), parameter :: path = 'data/sample_receptance.frf'
        character(len=*), parameter :: scratch = 'build/test_scratch/door_ident'
        character(len=4), parameter :: methods(2) = ['    ', 'lsce']
        type(scene_type) :: scene
        type(structure_model) :: by_scene, by_door
        type(error_type), allocatable :: fault
        character(len=:), allocatable :: text
        integer :: i

        do i = 1, size(methods)
            text = "&scene task = 'identify', name = 'door_ident', output_dir = '"//scratch//"' /" &
                   //new_line('a')//"&structure model = 'frf_file', frf_file = '"//path//"' /"//new_line('a')
            if (len_trim(methods(i)) > 0) text = text//"&identification method = '"//trim(methods(i))//"' /" &
                                                 //new_line('a')
            call read_scene_text(scratch, 'door_ident.nml', text, scene, fault)
            if (.not. allocated(fault)) call build_structure(scene, by_scene, fault)
            if (.not. allocated(fault)) call frf_file_structure(path, 'modal', dt, scene%tol_e, scene%max_order, &
                                                                by_door, fault, methods(i))
            call check(error, .not. allocated(fault), 'identification '//trim(methods(i)))
            if (allocated(error)) return
            call note('modes, '//merge('default', methods(i)//'   ', methods(i) == ''), &
                      real(by_door%model%n_modes(), dp))
            call check(error, by_door%method == by_scene%method .and. by_door%model%n_modes() > 0 .and. &
                       by_door%model%n_modes() == by_scene%model%n_modes(), 'same method and order '//trim(methods(i)))
            if (allocated(error)) return
            call check(error, all(by_door%model%pole == by_scene%model%pole) .and. &
                       all(by_door%model%residue == by_scene%model%residue) .and. by_door%fit_e() == by_scene%fit_e(), &
                       'poles, residues and E to the bit '//trim(methods(i)))
            if (allocated(error)) return
        end do
    end subroutine test_door_as_scene

    !> A structure from a receptance samples g at the dt it is given; `direct`, `fft` and
    !> `auto` at another dt are refused (stat_input, naming both steps), at the same dt built.
    subroutine test_sample_step(error)
        type(test_error), allocatable, intent(out) :: error

        character(len=6), parameter :: methods(3) = [character(len=6) :: 'direct', 'fft', 'auto']
        type(structure_model) :: structure
        class(convolver), allocatable :: conv
        type(error_type), allocatable :: build_error
        integer :: i

        ! 3201 lines: df = 1.6 Hz, fine enough for g to decay within 1/df (no wrap-around, which
        ! `direct` and `fft` refuse).
        call structure_from_frf(frf_from_modes(sdof_modes(mass, stiffness, xi), 5000.0_dp, 3201), lsce_options(), &
                                dt, structure, build_error)
        call check(error, .not. allocated(build_error), 'the structure from G builds at dt = 1e-4 s')
        if (allocated(error)) return
        do i = 1, size(methods)
            call new_convolver(trim(methods(i)), structure, 2.0_dp*dt, 100, conv, build_error)
            call check(error, allocated(build_error), trim(methods(i))//' at 2e-4 s is refused')
            if (allocated(error)) return
            call check(error, build_error%stat == stat_input .and. index(build_error%message, '1.00E-04') > 0 &
                       .and. index(build_error%message, '2.00E-04') > 0, &
                       'the message names both steps: '//build_error%message)
            if (allocated(error)) return
            call new_convolver(trim(methods(i)), structure, dt, 100, conv, build_error)
            call check(error, .not. allocated(build_error), trim(methods(i))//' at 1e-4 s builds')
            if (allocated(error)) return
            call free_convolver(conv)
        end do
    end subroutine test_sample_step

end module test_library_mod
