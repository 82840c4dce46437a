!> Unilateral contact between a linear structure and a road, stepped as in eqs. (20)-(24).
!>
!> Sign convention (SI units): the body's displacement u [m] and the road height u_r [m]
!> point up; u is measured from the static equilibrium under the preload F0 [N]. The
!> contact spring's compression is delta = delta0 + u_r - u, with delta0 = (F0/k_c)^(1/p)
!> its static compression, so delta plays the part of Delta x in eq. (21) with l0 = delta0.
!> The contact force (up, on the body) is F = k_c*delta^p for delta > 0 and F = 0 otherwise
!> (eq. 23: Hertz, p = 3/2; p = 1 is a linear spring). The structure is loaded by F - F0.
!>
!> Each step n (explicit, as in the paper): the convolver gives the history displacement
!> u_h(n) from the forces of steps 0..n-1 (eq. 20 or 24); the compression and force follow
!> from u_h; the step's load F - F0 is pushed; u(t_n) = u_h(n) + w0*(F - F0).
module contact_mod
    use kinds_mod, only: dp
    use convolver_mod, only: convolver
    implicit none
    private

    public :: contact_law, contact_response, run_contact

    !> Power-law contact spring F = k_c*delta^p, active in compression only.
    type :: contact_law
        !> Contact stiffness k_c [N/m^p], > 0.
        real(dp) :: stiffness = 1.0e6_dp
        !> Exponent p (3/2 for Hertz, 1 for a linear spring), > 0.
        real(dp) :: exponent = 1.5_dp
    contains
        !> Contact force F(delta) [N] for a compression delta [m].
        procedure :: force => law_force
        !> Compression delta [m] that carries a force F >= 0 [N].
        procedure :: compression => law_compression
    end type contact_law

    !> Time histories of a contact run, sampled at t_n = n*dt, n = 0..N_t-1.
    type :: contact_response
        !> Times t_n [s].
        real(dp), allocatable :: time(:)
        !> Road height u_r(t_n) [m].
        real(dp), allocatable :: road(:)
        !> Body displacement u(t_n) [m] from static equilibrium.
        real(dp), allocatable :: displacement(:)
        !> Contact force F(t_n) [N], >= 0.
        real(dp), allocatable :: force(:)
        !> Compression delta(t_n) [m] of the contact spring (negative: no contact).
        real(dp), allocatable :: compression(:)
    end type contact_response

contains

    !> Contact force [N]: k_c*delta^p when delta > 0, exactly zero otherwise.
    elemental real(dp) function law_force(self, delta)
        !> The contact law.
        class(contact_law), intent(in) :: self
        !> Compression [m].
        real(dp), intent(in) :: delta

        law_force = 0.0_dp
        if (delta <= 0.0_dp) return
        ! Hertz and linear springs without the general power (a pow call costs more than a
        ! whole step of the modal recursion); the same value to the last bit or two.
        if (abs(self%exponent - 1.5_dp) < epsilon(1.0_dp)) then
            law_force = self%stiffness*delta*sqrt(delta)
        else if (abs(self%exponent - 1.0_dp) < epsilon(1.0_dp)) then
            law_force = self%stiffness*delta
        else
            law_force = self%stiffness*delta**self%exponent
        end if
    end function law_force

    !> Compression [m] at which the spring carries a force F >= 0 [N]: (F/k_c)^(1/p).
    elemental real(dp) function law_compression(self, force)
        !> The contact law.
        class(contact_law), intent(in) :: self
        !> Force [N], >= 0.
        real(dp), intent(in) :: force

        law_compression = (force/self%stiffness)**(1.0_dp/self%exponent)
    end function law_compression

    !> Run the explicit contact loop over size(road) steps with any convolver.
    !>
    !> The convolver is reset first; it starts from rest (no force history), which is the
    !> static equilibrium under the preload.
    subroutine run_contact(conv, law, road, preload, response)
        !> The convolution method: history before each step, load pushed after it.
        class(convolver), intent(inout) :: conv
        !> The contact law.
        type(contact_law), intent(in) :: law
        !> Road heights u_r(t_n) [m], n = 0..N_t-1.
        real(dp), intent(in) :: road(0:)
        !> Static preload F0 [N] pressing the body onto the road, >= 0.
        real(dp), intent(in) :: preload
        !> Histories of the run.
        type(contact_response), intent(out) :: response

        real(dp) :: delta0, u_h, load, w0
        integer :: n, n_t

        n_t = size(road)
        allocate (response%time(0:n_t - 1), response%road(0:n_t - 1), response%displacement(0:n_t - 1), &
                  response%force(0:n_t - 1), response%compression(0:n_t - 1))
        call conv%reset()
        delta0 = law%compression(preload)
        w0 = conv%instant_weight()
        do n = 0, n_t - 1
            u_h = conv%history()
            response%compression(n) = delta0 + road(n) - u_h
            response%force(n) = law%force(response%compression(n))
            load = response%force(n) - preload
            call conv%push(load)
            response%displacement(n) = u_h + w0*load
        end do
        response%time = [(n*conv%dt, n=0, n_t - 1)]
        response%road = road
    end subroutine run_contact

end module contact_mod
