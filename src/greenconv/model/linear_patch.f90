!> The linear frequency-domain reference of a contact patch of N_c points, the matrix form of
!> the single-point F = -r/(alpha + 1/k_H) (greenconv_scene_run_linear_reference): each point's
!> contact law linearised at its share of the preload, k_i [N/m], the structure by its point
!> receptance matrix A(omega) [m/N] (time factor exp(i*omega*t), A_ij the displacement at i
!> under a unit force at j). With the patch's conventions (greenconv_scene_models_patch: compression
!> delta_i = delta0_i + u_r,i - u_i, the body loaded by F_i - F0_i), the force's change at
!> angular frequency omega under road heights u_r(omega) [m] is
!>
!>     dF(omega) = (A(omega) + K^-1)^-1 u_r(omega),   K = diag(k_i),
!>
!> which is F = -(A + K^-1)^-1 r for a roughness r of the opposite sign, and for one point
!> the single-point formula. The reference holds while every point stays in contact and the
!> roughness is small against the static compressions.
!>
!> A modal structure (greenconv_model_point_modes: g_ij(t) = sum_k phi_ik*phi_jk*h_k(t),
!> h_k(t) = 2*Re(r_k*exp(lambda_k*t))) has
!>
!>     A_ij(omega) = sum_k phi_ik*phi_jk*(r_k/(i*omega - lambda_k) + conj(r_k)/(i*omega - conj(lambda_k))) + R_ij,
!>
!> R the static compliance of the modes above the band, when there is one.
module greenconv_model_linear_patch
    use greenconv_core_kinds, only: dp
    use greenconv_core_error, only: error_type, fatal_error, stat_numerical
    use greenconv_ext_lapack, only: solve_linear
    use greenconv_model_point_modes, only: point_modes
    implicit none
    private

    public :: modal_receptance_matrix, linear_patch_force

contains

    !> A(omega) [m/N] of a modal structure at its points (module description), N_c x N_c.
    pure function modal_receptance_matrix(modes, omega, static) result(a)
        !> The modes and their shapes at the points.
        type(point_modes), intent(in) :: modes
        !> Angular frequency [rad/s], >= 0.
        real(dp), intent(in) :: omega
        !> Static compliance R [m/N] of the modes above the band (N_c x N_c), if any.
        real(dp), intent(in), optional :: static(:, :)
        complex(dp) :: a(modes%n_points(), modes%n_points())

        complex(dp) :: s, h(size(modes%modes%pole))
        integer :: i, j

        s = cmplx(0.0_dp, omega, kind=dp)
        h = modes%modes%residue/(s - modes%modes%pole) + conjg(modes%modes%residue)/(s - conjg(modes%modes%pole))
        do j = 1, size(a, 2)
            do i = 1, size(a, 1)
                a(i, j) = sum(modes%shape(i, :)*modes%shape(j, :)*h)
            end do
        end do
        if (present(static)) a = a + static
    end function modal_receptance_matrix

    !> dF = (A + K^-1)^-1 u_r [N] at one frequency (module description), solved as the real
    !> system of twice the size (LAPACK's dgesv).
    subroutine linear_patch_force(a, k, road, force, error)
        !> Point receptance matrix A(omega) [m/N], N_c x N_c.
        complex(dp), intent(in) :: a(:, :)
        !> Tangent stiffness k_i [N/m] of each point's law at its share of the preload, > 0.
        real(dp), intent(in) :: k(:)
        !> Road heights u_r,i(omega) [m] under the points (complex amplitudes).
        complex(dp), intent(in) :: road(:)
        !> The force's change dF_i(omega) [N] at each point.
        complex(dp), intent(out) :: force(:)
        !> Set (status 3) for sizes that do not agree, a stiffness not > 0 or a singular system.
        type(error_type), allocatable, intent(out) :: error

        complex(dp) :: m(size(k), size(k))
        real(dp) :: big(2*size(k), 2*size(k)), x(2*size(k))
        integer :: n, i

        n = size(k)
        if (size(a, 1) /= n .or. size(a, 2) /= n .or. size(road) /= n .or. size(force) /= n .or. n < 1) then
            call fatal_error(error, 'linear_patch_force: expected an N_c x N_c receptance matrix and N_c ' &
                             //'stiffnesses, road heights and forces', stat_numerical)
            return
        end if
        if (any(.not. (k > 0.0_dp))) then
            call fatal_error(error, 'linear_patch_force: expected tangent stiffnesses > 0 N/m', stat_numerical)
            return
        end if
        m = a
        do i = 1, n
            m(i, i) = m(i, i) + 1.0_dp/k(i)
        end do
        big(:n, :n) = real(m, dp)
        big(:n, n + 1:) = -aimag(m)
        big(n + 1:, :n) = aimag(m)
        big(n + 1:, n + 1:) = real(m, dp)
        call solve_linear(big, [real(road, dp), aimag(road)], x, error)
        if (allocated(error)) return
        force = cmplx(x(:n), x(n + 1:), kind=dp)
    end subroutine linear_patch_force

end module greenconv_model_linear_patch
