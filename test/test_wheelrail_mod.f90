!> A wheel on a rail: the rail's closed-form receptance against a numerical wavenumber
!> integral and Hetenyi's static stiffness, the Timoshenko rail against its Euler-Bernoulli
!> limit, and bad track parameters refused.
module test_wheelrail_mod
    use, intrinsic :: iso_fortran_env, only: dp => real64
    use testsuite_mod, only: test_error, unittest_type, new_unittest, check
    use greenconv_core_error, only: error_type
    use greenconv_model_rail, only: rail_track, wheel_mass, hertz_constant, hertz_tangent
    implicit none
    private

    public :: collect_wheelrail

    real(dp), parameter :: pi = acos(-1.0_dp)
    !> A UIC60-like rail in round numbers on a pad of 300 MN/m per 0.6 m sleeper spacing.
    real(dp), parameter :: ei = 6.4e6_dp, m_rail = 60.0_dp, s_pad = 5.0e8_dp, c_pad = 5.0e4_dp

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
                     new_unittest('bad track and wheel values refused', test_bad_values)]
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
