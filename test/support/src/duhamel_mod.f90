!> Closed-form responses of the damped oscillator (mass M, stiffness K, damping ratio xi),
!> starting from rest at t = 0: the Duhamel integral u(t) = int_0^t g(t - tau)*q(tau) dtau
!> for a step and for a sine load, shared by the convolution and engine tests.
!>
!> With w0 = sqrt(K/M), wd = w0*sqrt(1 - xi^2), a = xi*w0:
!>   step F:          u(t) = (F/K)*(1 - exp(-a t)*(cos wd t + (a/wd) sin wd t))
!>   sine F*sin(W t): u(t) = F*Im(H(W)*exp(iWt)) + exp(-a t)*(c1 cos wd t + c2 sin wd t),
!>                    H(W) = 1/(K - M W^2 + 2i*xi*sqrt(K M)*W), and c1, c2 cancel the
!>                    steady state's displacement and velocity at t = 0.
!>   ramp F*t/T:      u(t) = (F/T)*int_0^t (step response to a unit force) = (F/(K T))*
!>                    (t - Re E - (a/wd)*Im E),  E = (exp(mu t) - 1)/mu,  mu = -a + i*wd.
module duhamel_mod
    use, intrinsic :: iso_fortran_env, only: dp => real64
    implicit none
    private

    public :: step_response, sine_response, ramp_response

contains

    !> Displacement [m] at time t [s] under a force F [N] switched on at t = 0.
    elemental real(dp) function step_response(t, mass, stiffness, xi, force)
        !> Time [s], >= 0.
        real(dp), intent(in) :: t
        !> Mass M [kg], stiffness K [N/m], damping ratio xi in [0, 1).
        real(dp), intent(in) :: mass, stiffness, xi
        !> Force amplitude F [N].
        real(dp), intent(in) :: force

        real(dp) :: w0, wd, a

        w0 = sqrt(stiffness/mass)
        wd = w0*sqrt(1.0_dp - xi**2)
        a = xi*w0
        step_response = force/stiffness*(1.0_dp - exp(-a*t)*(cos(wd*t) + a/wd*sin(wd*t)))
    end function step_response

    !> Displacement [m] at time t [s] under F*sin(W t) applied from rest at t = 0.
    elemental real(dp) function sine_response(t, mass, stiffness, xi, force, omega_load)
        !> Time [s], >= 0.
        real(dp), intent(in) :: t
        !> Mass M [kg], stiffness K [N/m], damping ratio xi in [0, 1).
        real(dp), intent(in) :: mass, stiffness, xi
        !> Force amplitude F [N].
        real(dp), intent(in) :: force
        !> Load angular frequency W [rad/s].
        real(dp), intent(in) :: omega_load

        real(dp) :: w0, wd, a, c1, c2
        complex(dp) :: h

        w0 = sqrt(stiffness/mass)
        wd = w0*sqrt(1.0_dp - xi**2)
        a = xi*w0
        h = 1.0_dp/cmplx(stiffness - mass*omega_load**2, 2.0_dp*xi*sqrt(stiffness*mass)*omega_load, dp)
        c1 = -force*aimag(h)
        c2 = (-force*omega_load*real(h, dp) + a*c1)/wd
        sine_response = force*aimag(h*exp(cmplx(0.0_dp, omega_load*t, dp))) &
                        + exp(-a*t)*(c1*cos(wd*t) + c2*sin(wd*t))
    end function sine_response

    !> Displacement [m] at time t [s] under the ramp F*t/T applied from rest at t = 0.
    elemental real(dp) function ramp_response(t, mass, stiffness, xi, force, ramp_time)
        !> Time [s], >= 0.
        real(dp), intent(in) :: t
        !> Mass M [kg], stiffness K [N/m], damping ratio xi in [0, 1).
        real(dp), intent(in) :: mass, stiffness, xi
        !> Force F [N] reached at t = T.
        real(dp), intent(in) :: force
        !> Ramp time T [s].
        real(dp), intent(in) :: ramp_time

        real(dp) :: w0, wd, a
        complex(dp) :: mu, e

        w0 = sqrt(stiffness/mass)
        wd = w0*sqrt(1.0_dp - xi**2)
        a = xi*w0
        mu = cmplx(-a, wd, dp)
        e = (exp(mu*t) - 1.0_dp)/mu
        ramp_response = force/(stiffness*ramp_time)*(t - real(e, dp) - a/wd*aimag(e))
    end function ramp_response

end module duhamel_mod
