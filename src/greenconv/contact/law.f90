!> The contact spring between a structure and the road, one type for single- and multi-point
!> contact alike (greenconv_contact_single, greenconv_contact_multi): the force it carries at a
!> compression, the compression that carries a force, and its tangent stiffness.
!>
!> The contact steppers call only these three type-bound procedures: a new contact law is
!> written here, in them, and nowhere in the steppers (plus its rows in the scene schema).
module greenconv_contact_law
    use greenconv_core_kinds, only: dp
    implicit none
    private

    public :: contact_law

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
        !> Tangent stiffness dF/d(delta) [N/m] at a compression delta > 0 [m].
        procedure :: tangent => law_tangent
    end type contact_law

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

    !> Tangent stiffness [N/m] p*k_c*delta^(p-1) at a compression delta > 0 [m]; at the
    !> static compression delta0 it is k_c' of the contact frequency sqrt(k_c'/M).
    elemental real(dp) function law_tangent(self, delta)
        !> The contact law.
        class(contact_law), intent(in) :: self
        !> Compression [m], > 0.
        real(dp), intent(in) :: delta

        law_tangent = self%exponent*self%stiffness*delta**(self%exponent - 1.0_dp)
    end function law_tangent

end module greenconv_contact_law
