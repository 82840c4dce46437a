!> The SDOF Green's function against closed forms written independently here.
module test_sdof_mod
    use, intrinsic :: iso_fortran_env, only: dp => real64
    use testsuite_mod, only: test_error, unittest_type, new_unittest, check
    use greenconv_api_all, only: sdof_receptance, sdof_impulse, sdof_modes, modal_set
    implicit none
    private

    public :: collect_sdof

    real(dp), parameter :: mass = 1.0_dp, stiffness = 1.0e6_dp, xi = 0.02_dp

contains

    !> Tests of greenconv_model_sdof and greenconv_model_modal_set.
    subroutine collect_sdof(testsuite)
        type(unittest_type), allocatable, intent(out) :: testsuite(:)

        testsuite = [new_unittest('receptance at rest is 1/K', test_static), &
                     new_unittest('receptance against 1/(K - M w^2 + i C w)', test_receptance), &
                     new_unittest('impulse response against eq. (8)', test_impulse), &
                     new_unittest('impulse: g(0) = 0, g''(0+) = 1/M, integral = 1/K', test_impulse_moments), &
                     new_unittest('the exact mode reproduces G and g', test_mode)]
    end subroutine collect_sdof

    subroutine test_static(error)
        type(test_error), allocatable, intent(out) :: error

        complex(dp) :: g0

        g0 = sdof_receptance(mass, stiffness, xi, 0.0_dp)
        call check(error, real(g0, dp), 1.0_dp/stiffness, 'Re G(0)', thr=1.0e-15_dp, rel=.true.)
        if (allocated(error)) return
        call check(error, aimag(g0), 0.0_dp, 'Im G(0)', thr=1.0e-30_dp)
    end subroutine test_static

    subroutine test_receptance(error)
        type(test_error), allocatable, intent(out) :: error

        real(dp), parameter :: omegas(4) = [10.0_dp, 500.0_dp, 1000.0_dp, 5000.0_dp]
        complex(dp) :: expected, actual
        real(dp) :: c
        integer :: i

        c = 2.0_dp*xi*sqrt(stiffness*mass)
        do i = 1, size(omegas)
            ! Dynamic stiffness written out term by term, inverted as (a - ib)/(a^2 + b^2).
            associate (a => stiffness - mass*omegas(i)**2, b => c*omegas(i))
                expected = cmplx(a/(a**2 + b**2), -b/(a**2 + b**2), dp)
            end associate
            actual = sdof_receptance(mass, stiffness, xi, omegas(i))
            call check(error, abs(actual - expected), 0.0_dp, 'G at a sample frequency', thr=1.0e-13_dp*abs(expected))
            if (allocated(error)) return
        end do
        ! At resonance the response is -i/(C*w0): phase -90 degrees, magnitude 1/(2 xi K).
        actual = sdof_receptance(mass, stiffness, xi, sqrt(stiffness/mass))
        call check(error, aimag(actual), -1.0_dp/(2.0_dp*xi*stiffness), 'Im G(w0)', thr=1.0e-12_dp, rel=.true.)
    end subroutine test_receptance

    subroutine test_impulse(error)
        type(test_error), allocatable, intent(out) :: error

        real(dp), parameter :: times(4) = [-1.0e-3_dp, 1.0e-4_dp, 2.5e-3_dp, 0.1_dp]
        real(dp) :: w0, wd, expected
        integer :: i

        w0 = sqrt(stiffness/mass)
        wd = w0*sqrt(1.0_dp - xi**2)
        do i = 1, size(times)
            expected = 0.0_dp
            if (times(i) >= 0.0_dp) expected = exp(-xi*w0*times(i))*sin(wd*times(i))/(mass*wd)
            call check(error, sdof_impulse(mass, stiffness, xi, times(i)), expected, 'g(t)', &
                       thr=1.0e-14_dp*abs(expected) + 1.0e-30_dp)
            if (allocated(error)) return
        end do
    end subroutine test_impulse

    !> Properties that do not reuse the closed form: the impulse gives the mass a velocity
    !> 1/M with no displacement, and the area under g is the static compliance G(0) = 1/K.
    subroutine test_impulse_moments(error)
        type(test_error), allocatable, intent(out) :: error

        real(dp), parameter :: h = 1.0e-7_dp
        real(dp) :: area, step
        integer :: i, n

        call check(error, sdof_impulse(mass, stiffness, xi, 0.0_dp), 0.0_dp, 'g(0)', thr=1.0e-30_dp)
        if (allocated(error)) return
        call check(error, (sdof_impulse(mass, stiffness, xi, h) - sdof_impulse(mass, stiffness, xi, 0.0_dp))/h, &
                   1.0_dp/mass, "g'(0+)", thr=1.0e-4_dp, rel=.true.)
        if (allocated(error)) return
        ! Composite Simpson over 2 s (exp(-40) of the envelope left), 2e5 panels.
        n = 200000
        step = 2.0_dp/n
        area = sdof_impulse(mass, stiffness, xi, 0.0_dp) + sdof_impulse(mass, stiffness, xi, n*step)
        do i = 1, n - 1
            area = area + merge(4.0_dp, 2.0_dp, mod(i, 2) == 1)*sdof_impulse(mass, stiffness, xi, i*step)
        end do
        area = area*step/3.0_dp
        call check(error, area, 1.0_dp/stiffness, 'integral of g', thr=1.0e-9_dp, rel=.true.)
    end subroutine test_impulse_moments

    subroutine test_mode(error)
        type(test_error), allocatable, intent(out) :: error

        type(modal_set) :: modes
        real(dp) :: omega, t
        integer :: i

        modes = sdof_modes(mass, stiffness, xi)
        call check(error, modes%n_modes() == 1, 'one mode')
        if (allocated(error)) return
        do i = 0, 20
            omega = 250.0_dp*i
            call check(error, abs(modes%receptance(omega) - sdof_receptance(mass, stiffness, xi, omega)), 0.0_dp, &
                       'modal G', thr=1.0e-12_dp*abs(sdof_receptance(mass, stiffness, xi, omega)))
            if (allocated(error)) return
            t = 1.0e-3_dp*i
            call check(error, modes%impulse(t), sdof_impulse(mass, stiffness, xi, t), 'modal g', thr=1.0e-12_dp/mass)
            if (allocated(error)) return
        end do
    end subroutine test_mode

end module test_sdof_mod
