!> The independent reference of contact runs for the tests and the benchmark: a contact run
!> at one point (`contact_reference`) or at N_c points (`multi_contact_reference`, a Green's
!> matrix of shared modes), to compare u and F with a convolution method's at the same dt, and
!> the contact frequency that tells whether a time step can be trusted: omega_c*dt =
!> `contact_frequency(...)`*dt below 2 for the explicit contact step and below 2*sqrt(3) for
!> the implicit one (greenconv_contact_single).
!>
!> The reference solves the structure's state-space equations, not its convolution,
!> integrated by the adaptive Dormand-Prince pair of verify_ode_mod at a tight tolerance.
!> For modes shared by N_c points, g_ij(t) = sum_k phi_ik*phi_jk*2*Re(r_k*exp(lambda_k*t))
!> (greenconv_model_point_modes), each mode carries one complex state x_k with
!>
!>     x_k' = lambda_k*x_k + Q_k(t),   Q_k = sum_j phi_jk*(F_j - F0_j),
!>     u_i(t) = sum_k phi_ik*2*Re(r_k*x_k(t)),
!>
!> so that u_i is the convolution of g_ij with the loads q_j = F_j - F0_j exactly; one point
!> is the case N_c = 1, phi = 1. The contact forces are evaluated from the continuous roads
!> u_r,i(t) and u_i(t) inside the integrator, so the reference carries no time-step error of
!> its own: its only error is the integrator's tolerance (halve rtol by 100 and compare to
!> measure it). The structure starts at rest, u(0) = 0; a road that is not zero at t = 0
!> switches the loads on at t = 0+.
module verify_contact_mod
    use greenconv_core_kinds, only: dp
    use verify_ode_mod, only: ode_system, integrate
    use greenconv_model_modal_set, only: modal_set
    use greenconv_contact_single, only: contact_law
    use greenconv_model_road, only: road_profile
    use greenconv_model_point_modes, only: point_modes
    implicit none
    private

    public :: contact_reference, multi_contact_reference, contact_frequency

    !> The modal state-space equations of a structure in contact with a road at N_c points.
    type, extends(ode_system) :: modal_contact
        !> The structure's modes.
        type(modal_set) :: modes
        !> Mode shapes at the points, shape(i, k) = phi_ik (N_c x N_m).
        real(dp), allocatable :: shape(:, :)
        !> The contact law of each point.
        class(contact_law), allocatable :: laws(:)
        !> The road under each point.
        class(road_profile), allocatable :: roads(:)
        !> Static preloads F0_i [N] and static compressions delta0_i [m].
        real(dp), allocatable :: preload(:), delta0(:)
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
        class(contact_law), intent(in) :: law
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
        class(contact_law), intent(in) :: law
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
        real(dp), allocatable :: u(:, :), f(:, :)

        system%modes = modes
        allocate (system%shape(1, modes%n_modes()))
        system%shape(:, :) = 1.0_dp
        allocate (system%laws(1), source=law)
        allocate (system%roads(1), source=road)
        system%preload = [preload]
        call integrate_run(system, dt, n_steps, u, f, rtol)
        displacement = u(:, 1)
        force = f(:, 1)
    end subroutine contact_reference

    !> The multi-point contact run from rest (static equilibrium under the preloads), sampled at
    !> t_n = n*dt, n = 0..n_steps-1: displacements u_i [m] and contact forces F_i [N] at the
    !> N_c points of a structure given by its modes and their shapes at the points.
    !> `rtol` (default 1e-10) bounds the integrator's local relative error.
    subroutine multi_contact_reference(description, laws, roads, preload, dt, n_steps, displacement, force, rtol)
        !> The structure as modes and mode shapes at the N_c points (its true g_ij).
        type(point_modes), intent(in) :: description
        !> The contact law of each point (N_c).
        class(contact_law), intent(in) :: laws(:)
        !> The road under each point (N_c), evaluated continuously in time.
        class(road_profile), intent(in) :: roads(:)
        !> Static preloads F0_i [N] (N_c).
        real(dp), intent(in) :: preload(:)
        !> Sampling interval [s].
        real(dp), intent(in) :: dt
        !> Number of samples.
        integer, intent(in) :: n_steps
        !> u_i(t_n) [m], (0:n_steps-1, N_c).
        real(dp), allocatable, intent(out) :: displacement(:, :)
        !> F_i(t_n) [N], (0:n_steps-1, N_c).
        real(dp), allocatable, intent(out) :: force(:, :)
        !> Relative tolerance of the integrator (default 1e-10).
        real(dp), intent(in), optional :: rtol

        type(modal_contact) :: system

        system%modes = description%modes
        system%shape = description%shape
        allocate (system%laws, source=laws)
        allocate (system%roads, source=roads)
        system%preload = preload
        call integrate_run(system, dt, n_steps, displacement, force, rtol)
    end subroutine multi_contact_reference

    !> Integrate a system set up with its modes, shapes, laws, roads and preloads from rest,
    !> sampling u_i and F_i at t_n = n*dt.
    subroutine integrate_run(system, dt, n_steps, displacement, force, rtol)
        type(modal_contact), intent(inout) :: system
        real(dp), intent(in) :: dt
        integer, intent(in) :: n_steps
        real(dp), allocatable, intent(out) :: displacement(:, :), force(:, :)
        real(dp), intent(in), optional :: rtol

        real(dp), allocatable :: y(:), atol(:)
        real(dp) :: tolerance, h, force_scale
        integer :: n, m, i

        tolerance = 1.0e-10_dp
        if (present(rtol)) tolerance = rtol
        system%delta0 = system%laws%compression(system%preload)
        m = system%modes%n_modes()
        allocate (y(2*m), atol(2*m), displacement(0:n_steps - 1, size(system%laws)), &
                  force(0:n_steps - 1, size(system%laws)))
        force_scale = max(sum(system%preload)*maxval(abs(system%shape)), 1.0_dp)
        atol(1:2*m - 1:2) = tolerance*force_scale/abs(system%modes%pole)
        atol(2:2*m:2) = atol(1:2*m - 1:2)
        y = 0.0_dp
        h = 0.1_dp*min(dt, 1.0_dp/maxval(abs(system%modes%pole)))
        do n = 0, n_steps - 1
            if (n > 0) call integrate(system, (n - 1)*dt, n*dt, y, tolerance, atol, h)
            call system_displacement(system, y, displacement(n, :))
            do i = 1, size(system%laws)
                force(n, i) = system%laws(i)%force(system%delta0(i) + system%roads(i)%height(n*dt) &
                                                   - displacement(n, i))
            end do
        end do
    end subroutine integrate_run

    !> u_i = sum_k phi_ik*2*Re(r_k*x_k) [m] from the packed states (Re x_k, Im x_k).
    pure subroutine system_displacement(system, y, u)
        class(modal_contact), intent(in) :: system
        real(dp), intent(in) :: y(:)
        real(dp), intent(out) :: u(:)

        integer :: k

        u(:) = 0.0_dp
        do k = 1, size(system%modes%pole)
            u(:) = u + system%shape(:, k)*(2.0_dp*real(system%modes%residue(k)*cmplx(y(2*k - 1), y(2*k), kind=dp), &
                                                          kind=dp))
        end do
    end subroutine system_displacement

    !> x_k' = lambda_k*x_k + sum_j phi_jk*(F_j(delta0_j + u_r,j(t) - u_j) - F0_j).
    subroutine modal_contact_rhs(self, t, y, dydt)
        class(modal_contact), intent(in) :: self
        real(dp), intent(in) :: t
        real(dp), intent(in) :: y(:)
        real(dp), intent(out) :: dydt(:)

        real(dp) :: u(size(self%laws)), load(size(self%laws))
        complex(dp) :: rate
        integer :: k, i

        call system_displacement(self, y, u)
        do i = 1, size(self%laws)
            load(i) = self%laws(i)%force(self%delta0(i) + self%roads(i)%height(t) - u(i)) - self%preload(i)
        end do
        do k = 1, size(self%modes%pole)
            rate = self%modes%pole(k)*cmplx(y(2*k - 1), y(2*k), kind=dp) + dot_product(self%shape(:, k), load)
            dydt(2*k - 1) = real(rate, kind=dp)
            dydt(2*k) = aimag(rate)
        end do
    end subroutine modal_contact_rhs

end module verify_contact_mod
