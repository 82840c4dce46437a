!> The exponential pressure-overclosure contact spring F = F_s*(exp(delta/delta_s) - 1) for
!> delta > 0, zero otherwise (registry name `exponential`, parameters F_s [N] and delta_s [m]):
!> soft at first touch, tangent F_s/delta_s at delta = 0+, stiffening without bound as the
!> compression grows, the "softened" contact of finite-element codes.
module greenconv_contact_law_exponential
    use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
    use greenconv_core_kinds, only: dp
    use greenconv_core_error, only: error_type, fatal_error
    use greenconv_contact_law, only: contact_law, law_name_length
    implicit none
    private

    public :: exponential_law, build_exponential_law

    !> Exponential contact spring F = F_s*(exp(delta/delta_s) - 1), active in compression only.
    type, extends(contact_law) :: exponential_law
        !> Force scale F_s [N], > 0.
        real(dp) :: force_scale = 1.0_dp
        !> Compression scale delta_s [m], > 0.
        real(dp) :: compression_scale = 1.0e-4_dp
    contains
        !> Contact force F_s*(exp(delta/delta_s) - 1) [N] for a compression delta [m].
        procedure :: force => exponential_force
        !> Compression delta_s*log(1 + F/F_s) [m] that carries a force F >= 0 [N].
        procedure :: compression => exponential_compression
        !> Tangent stiffness (F_s/delta_s)*exp(delta/delta_s) [N/m].
        procedure :: tangent => exponential_tangent
        !> Refuse F_s or delta_s not finite and > 0 (status `stat_input`).
        procedure :: check => exponential_check
        !> 'exponential'.
        procedure :: name => exponential_name
        !> [F_s, delta_s].
        procedure :: parameters => exponential_parameters
    end type exponential_law

contains

    !> Exponential laws of the parameters values(:, i) = [F_s [N], delta_s [m]], one a point
    !> (the registry's constructor).
    subroutine build_exponential_law(values, laws)
        !> F_s [N] and delta_s [m] of each law (2 x n).
        real(dp), intent(in) :: values(:, :)
        !> The laws (n).
        class(contact_law), allocatable, intent(out) :: laws(:)

        integer :: i

        allocate (laws, source=[(exponential_law(force_scale=values(1, i), compression_scale=values(2, i)), &
                                 i=1, size(values, 2))])
    end subroutine build_exponential_law
    !> Contact force [N]: F_s*(exp(delta/delta_s) - 1) when delta > 0, exactly zero otherwise
    !> (exp(x) - 1 to full relative accuracy at small x: a light touch keeps its digits).
    elemental real(dp) function exponential_force(self, delta)
        !> The contact law.
        class(exponential_law), intent(in) :: self
        !> Compression [m].
        real(dp), intent(in) :: delta

        exponential_force = 0.0_dp
        if (delta <= 0.0_dp) return
        exponential_force = self%force_scale*exp_minus_one(delta/self%compression_scale)
    end function exponential_force

    !> Compression [m] at which the spring carries a force F >= 0 [N]: delta_s*log(1 + F/F_s).
    elemental real(dp) function exponential_compression(self, force)
        !> The contact law.
        class(exponential_law), intent(in) :: self
        !> Force [N], >= 0.
        real(dp), intent(in) :: force

        exponential_compression = self%compression_scale*log_one_plus(force/self%force_scale)
    end function exponential_compression

    !> Tangent stiffness [N/m] (F_s/delta_s)*exp(delta/delta_s) at a compression delta > 0 [m].
    elemental real(dp) function exponential_tangent(self, delta)
        !> The contact law.
        class(exponential_law), intent(in) :: self
        !> Compression [m], > 0.
        real(dp), intent(in) :: delta

        exponential_tangent = self%force_scale/self%compression_scale*exp(delta/self%compression_scale)
    end function exponential_tangent

    !> Refuse a law whose parameters make no spring: F_s > 0 N and delta_s > 0 m, both finite.
    subroutine exponential_check(self, error)
        !> The contact law.
        class(exponential_law), intent(in) :: self
        !> Set when a parameter is out of range.
        type(error_type), allocatable, intent(out) :: error

        if (.not. (self%force_scale > 0.0_dp .and. ieee_is_finite(self%force_scale))) then
            call fatal_error(error, 'contact: the exponential law''s force scale F_s must be finite and > 0 N')
        else if (.not. (self%compression_scale > 0.0_dp .and. ieee_is_finite(self%compression_scale))) then
            call fatal_error(error, 'contact: the exponential law''s compression scale delta_s must be finite and ' &
                             //'> 0 m')
        end if
    end subroutine exponential_check

    !> The registry name, 'exponential'.
    pure function exponential_name(self) result(name)
        !> The contact law.
        class(exponential_law), intent(in) :: self
        !> 'exponential'.
        character(len=law_name_length) :: name

        name = 'exponential'
    end function exponential_name

    !> The parameters [F_s [N], delta_s [m]].
    pure function exponential_parameters(self) result(values)
        !> The contact law.
        class(exponential_law), intent(in) :: self
        !> F_s and delta_s.
        real(dp), allocatable :: values(:)

        values = [self%force_scale, self%compression_scale]
    end function exponential_parameters

    !> exp(x) - 1, accurate to a few ulps for every x (Kahan's form: the rounding of exp(x)
    !> cancels in (u - 1)*x/log(u)).
    elemental real(dp) function exp_minus_one(x)
        !> Argument.
        real(dp), intent(in) :: x

        real(dp) :: u

        u = exp(x)
        if (u == 1.0_dp) then
            exp_minus_one = x
        else if (u - 1.0_dp == -1.0_dp .or. .not. ieee_is_finite(u)) then
            exp_minus_one = u - 1.0_dp
        else
            exp_minus_one = (u - 1.0_dp)*x/log(u)
        end if
    end function exp_minus_one

    !> log(1 + x), accurate to a few ulps for x > -1 (Kahan's form: log(u)*x/(u - 1), u = 1 + x).
    elemental real(dp) function log_one_plus(x)
        !> Argument, > -1.
        real(dp), intent(in) :: x

        real(dp) :: u

        u = 1.0_dp + x
        if (u == 1.0_dp) then
            log_one_plus = x
        else if (.not. ieee_is_finite(u)) then
            log_one_plus = log(u)
        else
            log_one_plus = log(u)*x/(u - 1.0_dp)
        end if
    end function log_one_plus

end module greenconv_contact_law_exponential
