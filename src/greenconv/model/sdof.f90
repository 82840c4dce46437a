!> The damped single-degree-of-freedom oscillator (mass M, stiffness K, damping ratio xi)
!> of the paper's section 3.1: its receptance, its impulse response (eq. 8) and its mode.
module greenconv_model_sdof
    use greenconv_core_kinds, only: dp
    use greenconv_model_modal_set, only: modal_set, modes_from_paper
    implicit none
    private

    public :: sdof_receptance, sdof_impulse, sdof_modes

contains

    !> Receptance G(omega) = 1/(K - M*omega^2 + i*C*omega) [m/N], C = 2*xi*sqrt(K*M).
    elemental complex(dp) function sdof_receptance(mass, stiffness, damping_ratio, omega)
        !> Mass M [kg], > 0.
        real(dp), intent(in) :: mass
        !> Stiffness K [N/m], > 0.
        real(dp), intent(in) :: stiffness
        !> Damping ratio xi, 0 <= xi < 1.
        real(dp), intent(in) :: damping_ratio
        !> Angular frequency [rad/s].
        real(dp), intent(in) :: omega

        real(dp) :: damping

        damping = 2.0_dp*damping_ratio*sqrt(stiffness*mass)
        sdof_receptance = 1.0_dp/cmplx(stiffness - mass*omega**2, damping*omega, kind=dp)
    end function sdof_receptance

    !> Impulse response of eq. (8), g(t) = exp(-xi*w0*t)*sin(wd*t)/(M*wd) [m/(N*s)],
    !> w0 = sqrt(K/M), wd = w0*sqrt(1 - xi^2); zero for t < 0.
    elemental real(dp) function sdof_impulse(mass, stiffness, damping_ratio, t)
        !> Mass M [kg], > 0.
        real(dp), intent(in) :: mass
        !> Stiffness K [N/m], > 0.
        real(dp), intent(in) :: stiffness
        !> Damping ratio xi, 0 <= xi < 1.
        real(dp), intent(in) :: damping_ratio
        !> Time [s].
        real(dp), intent(in) :: t

        real(dp) :: omega0, omega_d

        sdof_impulse = 0.0_dp
        if (t < 0.0_dp) return
        omega0 = sqrt(stiffness/mass)
        omega_d = omega0*sqrt(1.0_dp - damping_ratio**2)
        sdof_impulse = exp(-damping_ratio*omega0*t)*sin(omega_d*t)/(mass*omega_d)
    end function sdof_impulse

    !> The single exact mode of the oscillator: A = 1/M, omega = sqrt(K/M), xi.
    pure function sdof_modes(mass, stiffness, damping_ratio) result(modes)
        !> Mass M [kg], > 0.
        real(dp), intent(in) :: mass
        !> Stiffness K [N/m], > 0.
        real(dp), intent(in) :: stiffness
        !> Damping ratio xi, 0 <= xi < 1.
        real(dp), intent(in) :: damping_ratio
        type(modal_set) :: modes

        modes = modes_from_paper([1.0_dp/mass], [sqrt(stiffness/mass)], [damping_ratio])
    end function sdof_modes

end module greenconv_model_sdof
