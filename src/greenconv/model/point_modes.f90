!> Modes shared by the N_c points of a contact patch, the modal description of a Green's
!> matrix:
!>
!>     g_ij(t) = sum_k phi_ik*phi_jk*h_k(t),   h_k(t) = 2*Re(r_k*exp(lambda_k*t)),
!>
!> h_k the unit modal impulse response in pole-residue form (greenconv_model_modal_set); for
!> a mode of unit modal mass, r_k = 1/(2i*omega_k^d) [1/(kg*s)] and phi_ik is in 1/sqrt(kg).
module greenconv_model_point_modes
    use greenconv_core_kinds, only: dp
    use greenconv_core_error, only: error_type, fatal_error
    use greenconv_core_text, only: real_text
    use greenconv_model_modal_set, only: modal_set
    implicit none
    private

    public :: point_modes, check_on_belt

    !> Modes shared by N_c points: g_ij(t) = sum_k phi_ik*phi_jk*2*Re(r_k*exp(lambda_k*t)).
    type :: point_modes
        !> Poles lambda_k [rad/s] and residues r_k of the modal impulse responses h_k.
        type(modal_set) :: modes
        !> Mode shapes at the points, shape(i, k) = phi_ik (N_c x N_m), in units such that
        !> phi_ik*phi_jk*r_k is in m/(N*s) (1/sqrt(kg) for unit-modal-mass modes).
        real(dp), allocatable :: shape(:, :)
    contains
        !> Number of points N_c.
        procedure :: n_points => modes_n_points
        !> Green's function g_ij(t) [m/(N*s)] between two points.
        procedure :: green => modes_green
    end type point_modes

contains

    !> Number of points N_c of a modal description.
    elemental integer function modes_n_points(self)
        !> The modal description.
        class(point_modes), intent(in) :: self

        modes_n_points = 0
        if (allocated(self%shape)) modes_n_points = size(self%shape, 1)
    end function modes_n_points

    !> g_ij(t) = sum_k phi_ik*phi_jk*2*Re(r_k*exp(lambda_k*t)) [m/(N*s)]; zero for t < 0.
    elemental real(dp) function modes_green(self, i, j, t)
        !> The modal description.
        class(point_modes), intent(in) :: self
        !> Point where the displacement is taken, 1..N_c.
        integer, intent(in) :: i
        !> Point where the impulse acts, 1..N_c.
        integer, intent(in) :: j
        !> Time [s].
        real(dp), intent(in) :: t

        modes_green = 0.0_dp
        if (t < 0.0_dp) return
        modes_green = 2.0_dp*sum(self%shape(i, :)*self%shape(j, :) &
                                 *real(self%modes%residue*exp(self%modes%pole*t), kind=dp))
    end function modes_green

    !> An error unless every contact point lies on the belt of an analytic model in one
    !> coordinate, 0 <= value <= extent; the message names the model, the coordinate and
    !> the symbol of the extent (`tyre`, `x`, `L`).
    pure subroutine check_on_belt(model, coordinate, symbol, values, extent, error)
        !> Name of the model (`tyre`, `plate`).
        character(len=*), intent(in) :: model
        !> Name of the coordinate (`x`, `y`).
        character(len=*), intent(in) :: coordinate
        !> Symbol of the belt's extent in that coordinate (`L`, `b`).
        character(len=*), intent(in) :: symbol
        !> The coordinate of every contact point [m].
        real(dp), intent(in) :: values(:)
        !> The belt's extent in that coordinate [m].
        real(dp), intent(in) :: extent
        !> Set (status 2) when a point lies off the belt.
        type(error_type), allocatable, intent(out) :: error

        if (any(values < 0.0_dp .or. values > extent)) then
            call fatal_error(error, model//' model: contact points must lie on the belt, 0 <= '//coordinate//' <= ' &
                             //symbol//' = '//real_text(extent)//' m')
        end if
    end subroutine check_on_belt

end module greenconv_model_point_modes
