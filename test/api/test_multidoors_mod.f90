!> The multi-point front doors for legacy codes (greenconv_legacy_multi, and through the same
!> layer greenconv_capi_multi) against the Fortran API: a 4 x 3 patch of the plate model run
!> by `GCMMOD` + `GCMRUN` and by a `GCMSTP` loop equals `make_multipoint_convolver` +
!> `run_multi_contact` to the bit for every multi-point method; `GCMSMP` equals the sampled
!> engine on the same table; statuses and messages of bad input and of a diverged run; the
!> single-point doors `GCHIST`, `GCPUSH`, `GCW0` refuse a handle of more than one point.
module test_multidoors_mod
    use, intrinsic :: iso_fortran_env, only: dp => real64, int64
    use testsuite_mod, only: test_error, unittest_type, new_unittest, check, note
    use greenconv_api_all, only: error_type, contact_law, point_modes, multipoint_convolver, run_multi_contact, &
                                 multi_contact_response, new_sampled_green_matrix, sampled_green_matrix
    use greenconv_model_plate, only: tyre_plate, plate_modes, patch_points
    use greenconv_conv_builder, only: make_multipoint_convolver
    use greenconv_legacy_multi, only: gcmmod, gcmsmp, gcmplt, gcmfre, gcmrun, gcmbeg, gcmstp, gcmhis, gcmw0, gcmnpt, &
                                      gcmopt, gcmdsc
    use greenconv_legacy, only: gchist, gcpush, gcw0
    use greenconv_contact_law_power, only: power_law
    implicit none
    private

    public :: collect_multidoors

    !> The patch: 4 x 3 points, modes to 1.5 kHz; dt [s], steps, Hertz law, preload [N].
    integer, parameter :: n_x = 4, n_y = 3, n_c = n_x*n_y, capacity = 400, n_steps = 600
    real(dp), parameter :: extent(2) = [0.12_dp, 0.15_dp], f_max = 1500.0_dp, dt = 1.0e-4_dp
    real(dp), parameter :: k_c = 2.0e7_dp, exponent = 1.5_dp, preload = 250.0_dp

contains

    !> Tests of the multi-point doors.
    subroutine collect_multidoors(testsuite)
        type(unittest_type), allocatable, intent(out) :: testsuite(:)

        testsuite = [new_unittest('gcmplt gives plate_modes at patch_points', test_plate), &
                     new_unittest('gcmmod + gcmrun and a gcmstp loop equal run_multi_contact', test_runs), &
                     new_unittest('gcmsmp equals the sampled engine on the same table', test_samples), &
                     new_unittest('statuses and messages: bad input, divergence, handle 0', test_errors)]
    end subroutine collect_multidoors

    !> Road heights road(n, i) [m] of the patch, a sine shifted from point to point.
    function patch_road() result(road)
        real(dp) :: road(n_steps, n_c)

        integer :: i, n

        do i = 1, n_c
            road(:, i) = [(3.0e-4_dp*sin(2*acos(-1.0_dp)*(80.0_dp*(n*dt) + 0.1_dp*i)), n=0, n_steps - 1)]
        end do
    end function patch_road

    !> The patch's modes through the door, checked against the model's.
    subroutine door_modes(modes, error)
        type(point_modes), intent(out) :: modes
        type(test_error), allocatable, intent(out) :: error

        real(dp) :: p_re(capacity), p_im(capacity), r_re(capacity), r_im(capacity), shape(n_c, capacity)
        real(dp) :: x(n_c), y(n_c)
        integer :: n_m, ierr
        character(len=200) :: message

        call gcmplt(n_x, n_y, extent(1), extent(2), f_max, capacity, n_m, p_re, p_im, r_re, r_im, shape, x, y, &
                    ierr, message)
        call check(error, ierr == 0, 'gcmplt: '//trim(message))
        if (allocated(error)) return
        modes%modes%pole = cmplx(p_re(:n_m), p_im(:n_m), dp)
        modes%modes%residue = cmplx(r_re(:n_m), r_im(:n_m), dp)
        modes%shape = shape(:, :n_m)
    end subroutine door_modes

    !> GCMMOD on modes held by a `point_modes` (copied to plain arrays, as a legacy code holds them).
    subroutine door_new(modes, dt_run, method, handle, ierr, message)
        type(point_modes), intent(in) :: modes
        real(dp), intent(in) :: dt_run
        character(len=*), intent(in) :: method
        integer(int64), intent(out) :: handle
        integer, intent(out) :: ierr
        character(len=*), intent(out) :: message

        real(dp), allocatable :: p_re(:), p_im(:), r_re(:), r_im(:)

        p_re = modes%modes%pole%re
        p_im = modes%modes%pole%im
        r_re = modes%modes%residue%re
        r_im = modes%modes%residue%im
        call gcmmod(n_c, size(p_re), p_re, p_im, r_re, r_im, modes%shape, dt_run, n_steps, 0.01_dp, method, handle, &
                    ierr, message)
    end subroutine door_new

    !> GCMPLT's arrays are the plate model's at the patch's points, to the bit.
    subroutine test_plate(error)
        type(test_error), allocatable, intent(out) :: error

        type(point_modes) :: door, model
        type(error_type), allocatable :: fail
        type(tyre_plate) :: plate
        real(dp) :: x(n_c), y(n_c)

        call door_modes(door, error)
        if (allocated(error)) return
        call patch_points([plate%length/2, plate%width/2], extent, n_x, n_y, x, y)
        call plate_modes(plate, x, y, f_max, model, fail)
        call check(error, .not. allocated(fail), 'plate_modes failed')
        if (allocated(error)) return
        call note('modes', real(model%modes%n_modes(), dp))
        call check(error, all(door%modes%pole == model%modes%pole) .and. all(door%modes%residue == model%modes%residue) &
                   .and. all(door%shape == model%shape), 'identical poles, residues and shapes')
    end subroutine test_plate

    !> Every multi-point method: the door's whole run and its stepped run equal the Fortran API's run.
    subroutine test_runs(error)
        type(test_error), allocatable, intent(out) :: error

        character(len=6), parameter :: methods(4) = [character(len=6) :: 'modal', 'exact', 'direct', 'fft']
        type(point_modes) :: modes
        class(multipoint_convolver), allocatable :: conv
        type(error_type), allocatable :: fail
        type(multi_contact_response) :: response
        character(len=:), allocatable :: accuracy
        real(dp) :: road(n_steps, n_c), u(n_steps, n_c), f(n_steps, n_c), delta(n_steps, n_c), worst
        real(dp) :: kc(n_c), p(n_c), f0(n_c), ui(n_c), fi(n_c), di(n_c), ri(n_c)
        integer(int64) :: handle
        integer :: m, n, ierr
        character(len=300) :: message

        call door_modes(modes, error)
        if (allocated(error)) return
        road = patch_road()
        kc(:) = k_c
        p(:) = exponent
        f0(:) = preload
        worst = 0.0_dp
        do m = 1, size(methods)
            call make_multipoint_convolver(trim(methods(m)), modes, dt, 0.01_dp, n_steps, conv, accuracy, fail)
            call run_multi_contact(conv, [(power_law(k_c, exponent), n=1, n_c)], road, f0, response, fail)
            call check(error, .not. allocated(fail), trim(methods(m))//': the Fortran API''s run failed')
            if (allocated(error)) return
            call conv%release()
            call door_new(modes, dt, methods(m), handle, ierr, message)
            call gcmrun(handle, n_c, n_steps, kc, p, f0, road, u, f, delta, ierr, message)
            call check(error, ierr == 0, trim(methods(m))//': gcmrun: '//trim(message))
            if (allocated(error)) return
            worst = max(worst, maxval(abs(u - response%displacement)), maxval(abs(f - response%force)), &
                        maxval(abs(delta - response%compression)))
            call gcmbeg(handle, n_c, kc, p, f0, ierr, message)
            do n = 1, n_steps
                ri(:) = road(n, :)
                call gcmstp(handle, n_c, ri, ui, fi, di, ierr, message)
                worst = max(worst, maxval(abs(ui - response%displacement(n - 1, :))), &
                            maxval(abs(fi - response%force(n - 1, :))), maxval(abs(di - response%compression(n - 1, :))))
            end do
            call check(error, ierr == 0, trim(methods(m))//': gcmstp: '//trim(message))
            call gcmfre(handle)
            if (allocated(error)) return
        end do
        call note('peak force of the last run [N]', maxval(response%force))
        call note('largest difference over 4 methods, u, F, delta', worst)
        call check(error, worst, 0.0_dp, 'identical histories', thr=0.0_dp)
    end subroutine test_runs

    !> GCMSMP (tolerance 0: the whole table) equals new_sampled_green_matrix on the same samples.
    subroutine test_samples(error)
        type(test_error), allocatable, intent(out) :: error

        type(point_modes) :: modes
        type(sampled_green_matrix) :: conv
        type(error_type), allocatable :: fail
        type(multi_contact_response) :: response
        real(dp) :: g(0:n_steps - 1, n_c, n_c), road(n_steps, n_c), u(n_steps, n_c), f(n_steps, n_c)
        real(dp) :: delta(n_steps, n_c), kc(n_c), p(n_c), f0(n_c), w0(n_c, n_c)
        integer(int64) :: handle
        integer :: i, j, m, ierr
        character(len=300) :: message

        call door_modes(modes, error)
        if (allocated(error)) return
        do j = 1, n_c
            do i = 1, n_c
                g(:, i, j) = [(modes%green(i, j, m*dt), m=0, n_steps - 1)]
            end do
        end do
        road = patch_road()
        kc(:) = k_c
        p(:) = exponent
        f0(:) = preload
        call new_sampled_green_matrix(g, dt, conv, fail)
        call run_multi_contact(conv, [(power_law(k_c, exponent), i=1, n_c)], road, f0, response, fail)
        call gcmsmp(n_c, n_steps, g, dt, n_steps, 0.0_dp, 'Direct', handle, ierr, message)
        call check(error, ierr == 0, 'gcmsmp: '//trim(message))
        if (allocated(error)) return
        call gcmw0(handle, n_c, w0, ierr, message)
        call check(error, all(w0 == conv%weight0), 'gcmw0 gives W0 = dt*g(0)')
        if (allocated(error)) return
        call gcmrun(handle, n_c, n_steps, kc, p, f0, road, u, f, delta, ierr, message)
        call gcmfre(handle)
        call check(error, ierr == 0, 'gcmrun: '//trim(message))
        if (allocated(error)) return
        call check(error, maxval(abs(f - response%force)) + maxval(abs(u - response%displacement)), 0.0_dp, &
                   'identical histories', thr=0.0_dp)
    end subroutine test_samples

    !> Bad input gives 2 naming the argument; a diverged run 3 naming step and point; handle 0 gives 2.
    subroutine test_errors(error)
        type(test_error), allocatable, intent(out) :: error

        type(point_modes) :: modes
        real(dp) :: road(n_steps, n_c), u(n_steps, n_c), f(n_steps, n_c), delta(n_steps, n_c)
        real(dp) :: kc(n_c), p(n_c), f0(n_c), uh(n_c)
        integer(int64) :: handle
        integer :: ierr, n, n_size
        character(len=300) :: message

        call door_modes(modes, error)
        if (allocated(error)) return
        call door_new(modes, 0.0_dp, 'modal', handle, ierr, message)
        call check(error, ierr == 2 .and. index(message, 'dt =') > 0 .and. handle == 0_int64, 'dt = 0: '//message)
        if (allocated(error)) return
        call door_new(modes, dt, 'paper', handle, ierr, message)
        call check(error, ierr == 2 .and. index(message, 'multi-point') > 0, 'paper: '//message)
        if (allocated(error)) return
        call door_new(modes, dt, 'modal', handle, ierr, message)
        call gcmnpt(handle, n, ierr, message)
        call check(error, ierr == 0 .and. n == n_c, 'gcmnpt')
        if (allocated(error)) return
        call gcmdsc(handle, n_size, message, ierr)
        call check(error, ierr == 0 .and. n_size == modes%modes%n_modes() .and. index(message, 'recursive') == 1, &
                   'gcmdsc: '//message)
        if (allocated(error)) return
        call gcmhis(handle, n_c - 1, uh, ierr, message)
        call check(error, ierr == 2 .and. index(message, 'n_points = 11') > 0, 'wrong NC: '//message)
        if (allocated(error)) return
        ! GCHIST, GCPUSH and GCW0 are the GCM doors of one point: a 12-point handle is refused
        uh(1) = -1.0_dp
        call gchist(handle, uh(1), ierr)
        call check(error, ierr == 2 .and. uh(1) == 0.0_dp, 'GCHIST on a 12-point handle: IERR = 2, 0')
        if (allocated(error)) return
        call gcpush(handle, 1.0_dp, ierr)
        call check(error, ierr == 2, 'GCPUSH on a 12-point handle: IERR = 2')
        if (allocated(error)) return
        uh(1) = -1.0_dp
        call gcw0(handle, uh(1), ierr)
        call check(error, ierr == 2 .and. uh(1) == 0.0_dp, 'GCW0 on a 12-point handle: IERR = 2, 0')
        if (allocated(error)) return
        road = patch_road()
        kc(:) = k_c
        p(:) = exponent
        f0(:) = preload
        f0(5) = -1.0_dp
        call gcmrun(handle, n_c, n_steps, kc, p, f0, road, u, f, delta, ierr, message)
        call check(error, ierr == 2 .and. index(message, 'point 5') > 0, 'negative preload: '//message)
        if (allocated(error)) return
        f0(5) = preload
        call gcmopt(handle, 1.0e-12_dp, 50, 1.0e-5_dp, ierr, message)
        call gcmrun(handle, n_c, n_steps, kc, p, f0, road, u, f, delta, ierr, message)
        call check(error, ierr == 3 .and. index(message, 'at step') > 0 .and. index(message, 'at point') > 0 &
                   .and. f(n_steps, 1) == 0.0_dp, 'divergence: '//message)
        if (allocated(error)) return
        call gcmfre(handle)
        call gcmfre(handle)
        call gcmhis(handle, n_c, uh, ierr, message)
        call check(error, ierr == 2 .and. index(message, 'handle is 0') > 0, 'handle 0: '//message)
    end subroutine test_errors

end module test_multidoors_mod
