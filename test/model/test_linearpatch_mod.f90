!> The linear frequency-domain reference of a contact patch, dF = (A + K^-1)^-1 u_r
!> (greenconv_model_linear_patch), against what does not share its code:
!>
!> - on a diagonal A (points that do not see each other) each point's single-point formula
!>   u_r,i/(alpha_i + 1/k_i), written here, to 1e-13;
!> - the modal A of unit-mass modes against phi_i*phi_j/(m*(omega_0^2 - omega^2 + 2*i*xi*omega_0*omega))
!>   summed here, to 1e-13;
!> - on three points of three coupled modes with Hertz laws at their preload shares, the
!>   steady-state complex amplitude of each point's force in a time-domain run (`exact`,
!>   dt = 10 us, sine road heights of 0.1 um with a different amplitude and phase at each
!>   point, least squares over whole periods) within 1 % of the largest force amplitude, at
!>   40 Hz to 1.5 kHz;
!> - a scene of the tyre on its 20 points over data/road_sample.dat (linear tread springs, the
!>   contact held): the reference's band levels beside the `exact` run's within 0.5 dB from
!>   200 Hz to 2 kHz; more points than the reference takes: one line, no file.
module test_linearpatch_mod
    use, intrinsic :: iso_fortran_env, only: dp => real64
    use testsuite_mod, only: test_error, unittest_type, new_unittest, check, note
    use greenconv_core_error, only: error_type
    use greenconv_ext_lapack, only: least_squares
    use greenconv_model_modal_set, only: modes_from_paper
    use greenconv_model_point_modes, only: point_modes
    use greenconv_model_linear_patch, only: modal_receptance_matrix, linear_patch_force
    use greenconv_conv_multipoint, only: multipoint_convolver
    use greenconv_conv_builder, only: make_multipoint_convolver
    use greenconv_contact_single, only: contact_law
    use greenconv_contact_multi, only: multi_contact_response, run_multi_contact
    use linearpatch_scene_mod, only: test_scene_tyre
    use greenconv_contact_law_power, only: power_law
    implicit none
    private

    public :: collect_linearpatch

    real(dp), parameter :: pi = acos(-1.0_dp)
    !> Three modes [Hz], their masses [kg] and damping ratios.
    real(dp), parameter :: f_mode(3) = [120.0_dp, 310.0_dp, 700.0_dp], mass(3) = [2.0_dp, 1.0_dp, 0.5_dp], &
                           xi(3) = [0.05_dp, 0.04_dp, 0.03_dp]
    !> Their shapes at three points, shape(i, k).
    real(dp), parameter :: shape(3, 3) = reshape([1.0_dp, 0.8_dp, 0.3_dp, 0.5_dp, -0.6_dp, 0.9_dp, &
                                                  0.2_dp, 0.5_dp, -0.7_dp], [3, 3])

contains

    !> Tests of greenconv_model_linear_patch.
    subroutine collect_linearpatch(testsuite)
        type(unittest_type), allocatable, intent(out) :: testsuite(:)

        testsuite = [new_unittest('diagonal A: the single-point formula at each point', test_diagonal), &
                     new_unittest('modal A against the sum of unit-mass modes', test_modal_matrix), &
                     new_unittest('three coupled points: time domain = matrix reference within 1 %', &
                                  test_time_domain), &
                     new_unittest('scene: the tyre''s linear reference beside its run', test_scene_tyre)]
    end subroutine collect_linearpatch

    subroutine test_diagonal(error)
        type(test_error), allocatable, intent(out) :: error

        complex(dp), parameter :: alpha(3) = [(1.0e-7_dp, -3.0e-8_dp), (-2.0e-8_dp, -5.0e-9_dp), &
                                              (4.0e-9_dp, -1.0e-9_dp)]
        real(dp), parameter :: k(3) = [2.0e7_dp, 5.0e8_dp, 1.0e9_dp]
        complex(dp), parameter :: road(3) = [(1.0e-6_dp, 0.0_dp), (0.0_dp, 2.0e-6_dp), (-1.0e-6_dp, 3.0e-7_dp)]
        complex(dp) :: a(3, 3), force(3)
        type(error_type), allocatable :: fault
        real(dp) :: worst
        integer :: i

        a = (0.0_dp, 0.0_dp)
        do i = 1, 3
            a(i, i) = alpha(i)
        end do
        call linear_patch_force(a, k, road, force, fault)
        call check(error, .not. allocated(fault), 'solved')
        if (allocated(error)) return
        worst = maxval(abs(force/(road/(alpha + 1.0_dp/k)) - 1.0_dp))
        call note('worst |dF/dF_single - 1|', worst)
        call check(error, worst <= 1.0e-13_dp, 'each point as a single point')
    end subroutine test_diagonal

    subroutine test_modal_matrix(error)
        type(test_error), allocatable, intent(out) :: error

        type(point_modes) :: modes
        complex(dp) :: a(3, 3), expected
        real(dp) :: omega, omega_0, worst
        integer :: i, j, k, n

        modes = coupled_modes()
        worst = 0.0_dp
        do n = 0, 20
            omega = 2.0_dp*pi*100.0_dp*n
            a = modal_receptance_matrix(modes, omega)
            do j = 1, 3
                do i = 1, 3
                    expected = (0.0_dp, 0.0_dp)
                    do k = 1, 3
                        omega_0 = 2.0_dp*pi*f_mode(k)
                        expected = expected + shape(i, k)*shape(j, k) &
                                   /(mass(k)*cmplx(omega_0**2 - omega**2, 2.0_dp*xi(k)*omega_0*omega, kind=dp))
                    end do
                    worst = max(worst, abs(a(i, j) - expected)/abs(expected))
                end do
            end do
        end do
        call note('worst |A_ij/A_ij,closed - 1|, 0 to 2 kHz', worst)
        call check(error, worst <= 1.0e-12_dp, 'the modal A')
    end subroutine test_modal_matrix

    !> Three points on the modes of `coupled_modes`, Hertz laws C = 1e8 N/m^1.5 at 1000 N each,
    !> road heights a_i*sin(omega*t + p_i) faded in over 20 ms, 150 ms to settle, then whole
    !> periods over >= 40 ms: F_i - F0_i = Re(F_i^ exp(i*omega*t)) by least squares, against
    !> (A + K^-1)^-1 u_r^ with u_r,i^ = -i*a_i*exp(i*p_i).
    subroutine test_time_domain(error)
        type(test_error), allocatable, intent(out) :: error

        real(dp), parameter :: dt = 1.0e-5_dp, c_hertz = 1.0e8_dp, share = 1000.0_dp
        real(dp), parameter :: f(5) = [40.0_dp, 120.0_dp, 310.0_dp, 700.0_dp, 1500.0_dp]
        real(dp), parameter :: amplitude(3) = [1.0e-7_dp, 0.6e-7_dp, 0.8e-7_dp], phase(3) = [0.0_dp, 1.0_dp, 2.5_dp]
        type(point_modes) :: modes
        class(multipoint_convolver), allocatable :: conv
        type(multi_contact_response) :: response
        type(power_law) :: laws(3)
        type(error_type), allocatable :: fault
        character(len=:), allocatable :: accuracy
        real(dp), allocatable :: road(:, :), basis(:, :)
        real(dp) :: omega, k_h, ramp, settle, window, t, worst, x(3), gap
        complex(dp) :: expected(3), measured(3)
        integer :: i, n, p, n_steps, first
        character(len=80) :: label

        modes = coupled_modes()
        laws = power_law(stiffness=c_hertz, exponent=1.5_dp)
        k_h = 1.5_dp*c_hertz**(2.0_dp/3.0_dp)*share**(1.0_dp/3.0_dp)
        worst = 0.0_dp
        do i = 1, size(f)
            omega = 2.0_dp*pi*f(i)
            ramp = 0.02_dp
            settle = 0.15_dp
            window = ceiling(0.04_dp*f(i))/f(i)
            n_steps = nint((ramp + settle + window)/dt) + 1
            allocate (road(0:n_steps - 1, 3))
            do p = 1, 3
                do n = 0, n_steps - 1
                    t = n*dt
                    road(n, p) = amplitude(p)*sin(omega*t + phase(p))*merge(0.5_dp - 0.5_dp*cos(pi*t/ramp), 1.0_dp, &
                                                                            t < ramp)
                end do
            end do
            call make_multipoint_convolver('exact', modes, dt, 1.0e-8_dp, n_steps, conv, accuracy, fault)
            if (.not. allocated(fault)) call run_multi_contact(conv, laws, road, [share, share, share], response, fault)
            call check(error, .not. allocated(fault), 'the time-domain run')
            if (allocated(error)) return
            first = n_steps - nint(window/dt)
            allocate (basis(n_steps - first, 3))
            basis(:, 1) = [(cos(omega*n*dt), n=first, n_steps - 1)]
            basis(:, 2) = [(sin(omega*n*dt), n=first, n_steps - 1)]
            basis(:, 3) = 1.0_dp
            do p = 1, 3
                call least_squares(basis, response%force(first:n_steps - 1, p) - share, x, fault)
                call check(error, .not. allocated(fault), 'the fit')
                if (allocated(error)) return
                measured(p) = cmplx(x(1), -x(2), kind=dp)
            end do
            call linear_patch_force(modal_receptance_matrix(modes, omega), [k_h, k_h, k_h], &
                                    cmplx(0.0_dp, -amplitude, kind=dp)*exp(cmplx(0.0_dp, phase, kind=dp)), expected, &
                                    fault)
            call check(error, .not. allocated(fault), 'the reference')
            if (allocated(error)) return
            gap = maxval(abs(measured - expected))/maxval(abs(expected))
            worst = max(worst, gap)
            write (label, '(a,f7.1,a)') 'max |dF_run - dF_linear|/max |dF_linear| at ', f(i), ' Hz'
            call note(trim(label), gap)
            call check(error, gap <= 0.01_dp, trim(label))
            deallocate (road, basis)
            if (allocated(error)) return
        end do
        call note('worst over the frequencies', worst)
    end subroutine test_time_domain

    !> Three modes of f_mode, mass and xi at three points (shape).
    function coupled_modes() result(modes)
        type(point_modes) :: modes

        modes%modes = modes_from_paper(1.0_dp/mass, 2.0_dp*pi*f_mode, xi)
        modes%shape = shape
    end function coupled_modes

end module test_linearpatch_mod
