!> Modes shared by the N_c points of a contact patch, the modal description of a Green's
!> matrix:
!>
!>     g_ij(t) = sum_k phi_ik*phi_jk*h_k(t),   h_k(t) = 2*Re(r_k*exp(lambda_k*t)),
!>
!> h_k the unit modal impulse response in pole-residue form (greenconv_model_modal_set); for
!> a mode of unit modal mass, r_k = 1/(2i*omega_k^d) [1/(kg*s)] and phi_ik is in 1/sqrt(kg).
module greenconv_model_point_modes
    use greenconv_core_kinds, only: dp
    use greenconv_model_modal_set, only: modal_set
    implicit none
    private

    public :: point_modes

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


end module greenconv_model_point_modes
