!> The contact spring between a structure and the road, one type for single- and multi-point
!> contact alike (greenconv_contact_single, greenconv_contact_multi): the force it carries at a
!> compression, the compression that carries a force, and its tangent stiffness.
!>
!> The contact steppers call only these three type-bound procedures, and every door (scenes,
!> Fortran, C, F77) checks a law by its fourth, `check`: a new contact law is written here, in
!> them, and nowhere in the steppers or the doors (plus its rows in the scene schema).
module greenconv_contact_law
    use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
    use greenconv_core_kinds, only: dp
    use greenconv_core_error, only: error_type, fatal_error
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
        !> Refuse a law whose parameters are out of range (status `stat_input`).
        procedure :: check => law_check
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

    !> Refuse a law whose parameters make no spring: k_c > 0 and p > 0, both finite; the
    !> message names the parameter and its range.
    subroutine law_check(self, error)
        !> The contact law.
        class(contact_law), intent(in) :: self
        !> Set when a parameter is out of range.
        type(error_type), allocatable, intent(out) :: error

        if (.not. (self%stiffness > 0.0_dp .and. ieee_is_finite(self%stiffness))) then
            call fatal_error(error, 'contact: the stiffness k_c must be finite and > 0 N/m^p')
        else if (.not. (self%exponent > 0.0_dp .and. ieee_is_finite(self%exponent))) then
            call fatal_error(error, 'contact: the exponent p must be finite and > 0')
        end if
    end subroutine law_check

end module greenconv_contact_law
