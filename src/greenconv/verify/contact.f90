!> Verification of contact runs, a user feature: the independent reference of a contact run
!> and the contact frequency that tells whether a time step can be trusted. Use it to check
!> your own scene: run it with your convolution method and with `contact_reference`, at
!> your dt, and compare u and F; keep omega_c*dt = `contact_frequency(...)`*dt below 2 for
!> the explicit contact step and below 2*sqrt(3) for the implicit one (greenconv_contact_single).
!> The library's tests and the benchmark (bench/) check every method against it the same way.
!>
!> The reference solves the structure's state-space equations, not its convolution,
!> integrated by the adaptive Dormand-Prince pair of greenconv_verify_ode at a tight tolerance.
!> For a modal set g(t) = sum_k 2*Re(r_k*exp(lambda_k*t)) each mode carries one complex
!> state x_k with x_k' = lambda_k*x_k + q(t), so that u(t) = sum_k 2*Re(r_k*x_k(t)) is the
!> convolution of g with the load q = F - F0 exactly. The contact force is evaluated from
!> the continuous road u_r(t) and u(t) inside the integrator, so the reference carries no
!> time-step error of its own: its only error is the integrator's tolerance.
module greenconv_verify_contact
    use greenconv_core_kinds, only: dp
    use greenconv_verify_ode, only: ode_system, integrate
    use greenconv_model_modal_set, only: modal_set
    use greenconv_contact_single, only: contact_law
    use greenconv_model_road, only: road_profile
    implicit none
    private

    public :: contact_reference, contact_frequency

    !> The modal state-space equations of a structure in contact with a road.
    type, extends(ode_system) :: modal_contact
        !> The structure's modes.
        type(modal_set) :: modes
        !> The contact law.
        type(contact_law) :: law
        !> The road under the contact point.
        class(road_profile), allocatable :: road
        !> Static preload F0 [N] and static compression delta0 [m].
        real(dp) :: preload = 0.0_dp, delta0 = 0.0_dp
    contains
        procedure :: rhs => modal_contact_rhs
    end type modal_contact

contains

    !> Contact frequency omega_c = sqrt(k_c'/M) [rad/s] of a body of mass M resting on the law
    !> under the preload F0: k_c' = p*k_c*delta0^(p-1) is the tangent stiffness of the law at
    !> the static compression delta0 = (F0/k_c)^(1/p). The explicit contact step is stable for
    !> omega_c*dt < 2, the implicit one for omega_c*dt < 2*sqrt(3) (greenconv_contact_single).
    elemental real(dp) function contact_frequency(law, preload, body_mass)
        !> The contact law.
        type(contact_law), intent(in) :: law
        !> Static preload F0 [N], > 0.
        real(dp), intent(in) :: preload
        !> Mass M [kg] of the body on the spring, > 0.
        real(dp), intent(in) :: body_mass

        contact_frequency = sqrt(law%tangent(law%compression(preload))/body_mass)
    end function contact_frequency

    !> The contact run from rest (static equilibrium under the preload), sampled at
    !> t_n = n*dt, n = 0..n_steps-1: displacement u [m] and contact force F [N].
    !> `rtol` (default 1e-10) bounds the integrator's local relative error.
    subroutine contact_reference(modes, law, road, preload, dt, n_steps, displacement, force, rtol)
        !> The structure as modes (its true g, not a fitted one).
        type(modal_set), intent(in) :: modes
        !> The contact law.
        type(contact_law), intent(in) :: law
        !> The road, evaluated continuously in time.
        class(road_profile), intent(in) :: road
        !> Static preload F0 [N].
        real(dp), intent(in) :: preload
        !> Sampling interval [s].
        real(dp), intent(in) :: dt
        !> Number of samples.
        integer, intent(in) :: n_steps
        !> u(t_n) [m], n = 0..n_steps-1.
        real(dp), allocatable, intent(out) :: displacement(:)
        !> F(t_n) [N], n = 0..n_steps-1.
        real(dp), allocatable, intent(out) :: force(:)
        !> Relative tolerance of the integrator (default 1e-10).
        real(dp), intent(in), optional :: rtol

        type(modal_contact) :: system
        real(dp), allocatable :: y(:), atol(:)
        real(dp) :: tolerance, h, force_scale
        integer :: n, m

        tolerance = 1.0e-10_dp
        if (present(rtol)) tolerance = rtol
        system%modes = modes
        system%law = law
        allocate (system%road, source=road)
        system%preload = preload
        system%delta0 = law%compression(preload)
        m = modes%n_modes()
        allocate (y(2*m), atol(2*m), displacement(0:n_steps - 1), force(0:n_steps - 1))
        force_scale = max(preload, 1.0_dp)
        atol(1:2*m - 1:2) = tolerance*force_scale/abs(modes%pole)
        atol(2:2*m:2) = atol(1:2*m - 1:2)
        y = 0.0_dp
        h = 0.1_dp*min(dt, 1.0_dp/maxval(abs(modes%pole)))
        do n = 0, n_steps - 1
            if (n > 0) call integrate(system, (n - 1)*dt, n*dt, y, tolerance, atol, h)
            displacement(n) = system_displacement(system, y)
            force(n) = law%force(system%delta0 + road%height(n*dt) - displacement(n))
        end do
    end subroutine contact_reference

    !> u = sum_k 2*Re(r_k*x_k) [m] from the packed states (Re x_k, Im x_k).
    pure real(dp) function system_displacement(system, y) result(u)
        class(modal_contact), intent(in) :: system
        real(dp), intent(in) :: y(:)

        integer :: k

        u = 0.0_dp
        do k = 1, size(system%modes%pole)
            u = u + 2.0_dp*real(system%modes%residue(k)*cmplx(y(2*k - 1), y(2*k), kind=dp), kind=dp)
        end do
    end function system_displacement

    !> x_k' = lambda_k*x_k + F(delta0 + u_r(t) - u) - F0.
    subroutine modal_contact_rhs(self, t, y, dydt)
        class(modal_contact), intent(in) :: self
        real(dp), intent(in) :: t
        real(dp), intent(in) :: y(:)
        real(dp), intent(out) :: dydt(:)

        complex(dp) :: rate
        real(dp) :: load
        integer :: k

        load = self%law%force(self%delta0 + self%road%height(t) - system_displacement(self, y)) - self%preload
        do k = 1, size(self%modes%pole)
            rate = self%modes%pole(k)*cmplx(y(2*k - 1), y(2*k), kind=dp) + load
            dydt(2*k - 1) = real(rate, kind=dp)
            dydt(2*k) = aimag(rate)
        end do
    end subroutine modal_contact_rhs

end module greenconv_verify_contact
