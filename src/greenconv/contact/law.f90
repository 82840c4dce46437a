!> The contact spring between a structure and the road, an abstract type that single- and
!> multi-point contact share (greenconv_contact_step, greenconv_contact_single,
!> greenconv_contact_multi): the force it carries at a compression, the compression that
!> carries a force, and its tangent stiffness.
!>
!> The contact steppers call only `force`, `compression` and `tangent`; every door (scenes,
!> Fortran, C, F77) builds a law through the registry greenconv_contact_laws, which names its
!> parameters, their SI units and ranges, and checks a law by `check`. A new law is one module
!> extending `contact_law` (contact/law_<name>.f90, as greenconv_contact_law_power and
!> greenconv_contact_law_exponential), its row in the registry and its line in doc/scenes.md.
module greenconv_contact_law
    use greenconv_core_kinds, only: dp
    use greenconv_core_error, only: error_type
    implicit none
    private

    public :: contact_law, point_forces

    !> Length of a law's name (`name`), blank-padded.
    integer, parameter, public :: law_name_length = 16

    !> A contact spring F(delta), active in compression (delta > 0) only: F = 0 for delta <= 0.
    type, abstract :: contact_law
    contains
        !> Contact force F(delta) [N] for a compression delta [m].
        procedure(law_force), deferred :: force
        !> Compression delta [m] that carries a force F >= 0 [N].
        procedure(law_compression), deferred :: compression
        !> Tangent stiffness dF/d(delta) [N/m] at a compression delta > 0 [m].
        procedure(law_tangent), deferred :: tangent
        !> Refuse a law whose parameters are out of range (status `stat_input`).
        procedure(law_check), deferred :: check
        !> The law's name in the registry (greenconv_contact_laws), as scenes and doors give it.
        procedure(law_name), deferred :: name
        !> The law's parameters in the order of its registry row, in their SI units.
        procedure(law_parameters), deferred :: parameters
        !> Forces F_i(delta_i) [N] of the points' laws, an array of this law's dynamic type
        !> (`call laws(1)%forces(laws, delta, force)`), and with `slope` their slopes
        !> dF_i/ddelta_i [N/m] (the `tangent` in compression, zero otherwise): the steppers' call
        !> on every point at once. By default each point's `force` and `tangent`; a law may
        !> override it with a loop the compiler inlines (the power law does).
        procedure, nopass :: forces => point_forces
    end type contact_law

    abstract interface
        !> Contact force [N] at a compression delta [m]; exactly zero for delta <= 0.
        elemental real(dp) function law_force(self, delta)
            import :: contact_law, dp
            !> The contact law.
            class(contact_law), intent(in) :: self
            !> Compression [m].
            real(dp), intent(in) :: delta
        end function law_force

        !> Compression [m] at which the spring carries a force F >= 0 [N].
        elemental real(dp) function law_compression(self, force)
            import :: contact_law, dp
            !> The contact law.
            class(contact_law), intent(in) :: self
            !> Force [N], >= 0.
            real(dp), intent(in) :: force
        end function law_compression

        !> Tangent stiffness dF/d(delta) [N/m] at a compression delta > 0 [m]; at the static
        !> compression delta0 it is k_c' of the contact frequency sqrt(k_c'/M).
        elemental real(dp) function law_tangent(self, delta)
            import :: contact_law, dp
            !> The contact law.
            class(contact_law), intent(in) :: self
            !> Compression [m], > 0.
            real(dp), intent(in) :: delta
        end function law_tangent

        !> Set `error` (status `stat_input`) when a parameter is out of range; the message
        !> names the parameter, its unit and its range.
        subroutine law_check(self, error)
            import :: contact_law, error_type
            !> The contact law.
            class(contact_law), intent(in) :: self
            !> Set when a parameter is out of range.
            type(error_type), allocatable, intent(out) :: error
        end subroutine law_check

        !> The law's registry name.
        pure function law_name(self) result(name)
            import :: contact_law, law_name_length
            !> The contact law.
            class(contact_law), intent(in) :: self
            !> Its name, e.g. 'power', blank-padded (a fixed length: no static length per call site).
            character(len=law_name_length) :: name
        end function law_name

        !> The law's parameters [their SI units], in its registry row's order.
        pure function law_parameters(self) result(values)
            import :: contact_law, dp
            !> The contact law.
            class(contact_law), intent(in) :: self
            !> Its parameter values.
            real(dp), allocatable :: values(:)
        end function law_parameters
    end interface

contains

    !> F_i = laws(i)%force(delta(i)) [N] for every point.
    subroutine point_forces(laws, delta, force, slope)
        !> The points' laws (N_c), of one dynamic type.
        class(contact_law), intent(in) :: laws(:)
        !> Compressions delta_i [m] (N_c).
        real(dp), intent(in) :: delta(:)
        !> Forces F_i [N] (N_c).
        real(dp), intent(out) :: force(:)
        !> Slopes dF_i/ddelta_i [N/m] (N_c), zero where delta_i <= 0, when present.
        real(dp), intent(out), optional :: slope(:)

        integer :: i

        force(:) = laws%force(delta)
        if (.not. present(slope)) return
        do i = 1, size(laws)
            slope(i) = 0.0_dp
            if (delta(i) > 0.0_dp) slope(i) = laws(i)%tangent(delta(i))
        end do
    end subroutine point_forces

end module greenconv_contact_law
