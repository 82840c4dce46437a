!> The power-law contact spring F = k_c*delta^p (p = 3/2: Hertz, p = 1: a linear spring), the
!> law of the paper (eq. 22) and the default of scenes and doors (registry name `power`,
!> parameters k_c [N/m^p] and p).
module greenconv_contact_law_power
    use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
    use greenconv_core_kinds, only: dp
    use greenconv_core_error, only: error_type, fatal_error
    use greenconv_contact_law, only: contact_law, law_name_length, point_forces
    implicit none
    private

    public :: power_law, build_power_law

    !> Power-law contact spring F = k_c*delta^p, active in compression only.
    type, extends(contact_law) :: power_law
        !> Contact stiffness k_c [N/m^p], > 0.
        real(dp) :: stiffness = 1.0e6_dp
        !> Exponent p (3/2 for Hertz, 1 for a linear spring), > 0.
        real(dp) :: exponent = 1.5_dp
    contains
        !> Contact force k_c*delta^p [N] for a compression delta [m].
        procedure :: force => power_force
        !> Compression (F/k_c)^(1/p) [m] that carries a force F >= 0 [N].
        procedure :: compression => power_compression
        !> Tangent stiffness p*k_c*delta^(p-1) [N/m] at a compression delta > 0 [m].
        procedure :: tangent => power_tangent
        !> Refuse k_c or p not finite and > 0 (status `stat_input`).
        procedure :: check => power_check
        !> 'power'.
        procedure :: name => power_name
        !> [k_c, p].
        procedure :: parameters => power_parameters
        !> k_c,i*delta_i^p_i [N] at every point, the law's `force` inlined.
        procedure, nopass :: forces => power_forces
    end type power_law

contains

    !> Power laws of the parameters values(:, i) = [k_c [N/m^p], p], one a point (the
    !> registry's constructor).
    subroutine build_power_law(values, laws)
        !> k_c [N/m^p] and p of each law (2 x n).
        real(dp), intent(in) :: values(:, :)
        !> The laws (n).
        class(contact_law), allocatable, intent(out) :: laws(:)

        integer :: i

        allocate (laws, source=[(power_law(stiffness=values(1, i), exponent=values(2, i)), i=1, size(values, 2))])
    end subroutine build_power_law
    !> Contact force [N]: k_c*delta^p when delta > 0, exactly zero otherwise.
    elemental real(dp) function power_force(self, delta)
        !> The contact law.
        class(power_law), intent(in) :: self
        !> Compression [m].
        real(dp), intent(in) :: delta

        power_force = 0.0_dp
        if (delta <= 0.0_dp) return
        ! Hertz and linear springs without the general power (a pow call costs more than a
        ! whole step of the modal recursion); the same value to the last bit or two.
        if (abs(self%exponent - 1.5_dp) < epsilon(1.0_dp)) then
            power_force = self%stiffness*delta*sqrt(delta)
        else if (abs(self%exponent - 1.0_dp) < epsilon(1.0_dp)) then
            power_force = self%stiffness*delta
        else
            power_force = self%stiffness*delta**self%exponent
        end if
    end function power_force

    !> F_i = k_c,i*delta_i^p_i [N] for every point (zero where delta_i <= 0), and with `slope`
    !> the slopes p_i*k_c,i*delta_i^(p_i-1) [N/m] (zero where delta_i <= 0): `power_force` and
    !> `power_tangent` in a loop the compiler inlines, no call through the type's table per point.
    subroutine power_forces(laws, delta, force, slope)
        !> The points' laws (N_c), all power laws.
        class(contact_law), intent(in) :: laws(:)
        !> Compressions delta_i [m] (N_c).
        real(dp), intent(in) :: delta(:)
        !> Forces F_i [N] (N_c).
        real(dp), intent(out) :: force(:)
        !> Slopes dF_i/ddelta_i [N/m] (N_c), when present.
        real(dp), intent(out), optional :: slope(:)

        integer :: i

        select type (laws)
        type is (power_law)
            if (present(slope)) then
                do i = 1, size(laws)
                    force(i) = power_force(laws(i), delta(i))
                    slope(i) = 0.0_dp
                    if (delta(i) > 0.0_dp) slope(i) = power_tangent(laws(i), delta(i))
                end do
            else
                do i = 1, size(laws)
                    force(i) = power_force(laws(i), delta(i))
                end do
            end if
        class default
            call point_forces(laws, delta, force, slope)
        end select
    end subroutine power_forces

    !> Compression [m] at which the spring carries a force F >= 0 [N]: (F/k_c)^(1/p).
    elemental real(dp) function power_compression(self, force)
        !> The contact law.
        class(power_law), intent(in) :: self
        !> Force [N], >= 0.
        real(dp), intent(in) :: force

        power_compression = (force/self%stiffness)**(1.0_dp/self%exponent)
    end function power_compression

    !> Tangent stiffness [N/m] p*k_c*delta^(p-1) at a compression delta > 0 [m].
    elemental real(dp) function power_tangent(self, delta)
        !> The contact law.
        class(power_law), intent(in) :: self
        !> Compression [m], > 0.
        real(dp), intent(in) :: delta

        ! a linear spring without the pow call (delta^0 = 1: the same value to the bit)
        if (abs(self%exponent - 1.0_dp) < epsilon(1.0_dp)) then
            power_tangent = self%exponent*self%stiffness
        else
            power_tangent = self%exponent*self%stiffness*delta**(self%exponent - 1.0_dp)
        end if
    end function power_tangent

    !> Refuse a law whose parameters make no spring: k_c > 0 and p > 0, both finite; the
    !> message names the parameter and its range.
    subroutine power_check(self, error)
        !> The contact law.
        class(power_law), intent(in) :: self
        !> Set when a parameter is out of range.
        type(error_type), allocatable, intent(out) :: error

        if (.not. (self%stiffness > 0.0_dp .and. ieee_is_finite(self%stiffness))) then
            call fatal_error(error, 'contact: the stiffness k_c must be finite and > 0 N/m^p')
        else if (.not. (self%exponent > 0.0_dp .and. ieee_is_finite(self%exponent))) then
            call fatal_error(error, 'contact: the exponent p must be finite and > 0')
        end if
    end subroutine power_check

    !> The registry name, 'power'.
    pure function power_name(self) result(name)
        !> The contact law.
        class(power_law), intent(in) :: self
        !> 'power'.
        character(len=law_name_length) :: name

        name = 'power'
    end function power_name

    !> The parameters [k_c [N/m^p], p].
    pure function power_parameters(self) result(values)
        !> The contact law.
        class(power_law), intent(in) :: self
        !> k_c and p.
        real(dp), allocatable :: values(:)

        values = [self%stiffness, self%exponent]
    end function power_parameters

end module greenconv_contact_law_power
