!> The 2D tyre belt (greenconv_model_plate) against checks that do not use its formulas: the
!> natural frequencies against the eigenvalues of a finite-difference discretisation of the
!> plate operator (LAPACK dsyev, Richardson-extrapolated over two grids), unit modal mass and
!> orthogonality by quadrature, the static point compliance against the double Fourier series
!> of the static problem, and reciprocity and the ring's translation invariance of G_ij.
module test_plate_mod
    use, intrinsic :: iso_fortran_env, only: dp => real64
    use testsuite_mod, only: test_error, unittest_type, new_unittest, check, note
    use greenconv_core_error, only: error_type
    use greenconv_model_point_modes, only: point_modes
    use greenconv_model_plate, only: tyre_plate, plate_mode, plate_frequency, plate_mode_shape, plate_mode_list, &
                                     plate_modes, patch_points, patch_receptance
    implicit none
    private

    public :: collect_plate

    real(dp), parameter :: pi = acos(-1.0_dp)

    interface
        !> LAPACK's symmetric eigen solver (the library's ext/lapack.f90 has none; the test
        !> declares it here from LAPACK's documented prototype).
        subroutine dsyev(jobz, uplo, n, a, lda, w, work, lwork, info)
            import :: dp
            implicit none
            character(len=1), intent(in) :: jobz, uplo
            integer, intent(in) :: n, lda, lwork
            real(dp), intent(inout) :: a(lda, *)
            real(dp), intent(out) :: w(*), work(*)
            integer, intent(out) :: info
        end subroutine dsyev
    end interface

contains

    !> Tests of greenconv_model_plate.
    subroutine collect_plate(testsuite)
        type(unittest_type), allocatable, intent(out) :: testsuite(:)

        testsuite = [new_unittest('frequencies equal finite-difference eigenvalues (dsyev)', test_fd_frequencies), &
                     new_unittest('unit modal mass and orthogonality by quadrature', test_modal_mass), &
                     new_unittest('static point compliance equals the double Fourier series', test_static), &
                     new_unittest('reciprocity and translation invariance of G_ij', test_reciprocity), &
                     new_unittest('defaults: first modes and point stiffness of a car tyre', test_defaults), &
                     new_unittest('errors: non-physical plate, points off the belt, no mode', test_errors)]
    end subroutine collect_plate

    !> The 9 lowest omega^2 of the plate operator discretised by central differences (periodic
    !> in x, simply supported in y through antisymmetric ghost points) on an n_x by n_y grid
    !> and on the grid twice as fine, Richardson-extrapolated (the error is O(h^2)), against
    !> the closed form.
    subroutine test_fd_frequencies(error)
        type(test_error), allocatable, intent(out) :: error

        type(tyre_plate) :: plate
        type(plate_mode), allocatable :: modes(:)
        type(error_type), allocatable :: fail
        real(dp) :: coarse(9), fine(9), extrapolated(9), exact(9)

        call fd_eigenvalues(plate, 48, 6, coarse)
        call fd_eigenvalues(plate, 96, 12, fine)
        extrapolated = (4.0_dp*fine - coarse)/3.0_dp
        call plate_mode_list(plate, 300.0_dp, modes, fail)
        call check(error, .not. allocated(fail) .and. size(modes) >= 9, 'expected at least 9 modes below 300 Hz')
        if (allocated(error)) return
        exact = plate_frequency(plate, modes(1:9)%m, modes(1:9)%n)**2
        call note('fine grid rel. error', maxval(abs(fine - exact)/exact))
        call note('extrapolated rel. error', maxval(abs(extrapolated - exact)/exact))
        call check(error, maxval(abs(extrapolated - exact)/exact) < 2.0e-4_dp, &
                   'extrapolated FD omega^2 differs from the closed form by more than 2e-4')
    end subroutine test_fd_frequencies

    !> Lowest 9 eigenvalues omega^2 = lambda/rho_h of the FD plate operator.
    subroutine fd_eigenvalues(plate, n_x, n_y, omega2)
        type(tyre_plate), intent(in) :: plate
        integer, intent(in) :: n_x, n_y
        real(dp), intent(out) :: omega2(:)

        real(dp), allocatable :: ax(:, :), ay(:, :), k(:, :), w(:), work(:), eye_x(:, :), eye_y(:, :)
        real(dp) :: hx, hy
        integer :: i, n, info

        hx = plate%length/n_x
        hy = plate%width/n_y
        allocate (ax(n_x, n_x), ay(n_y - 1, n_y - 1), eye_x(n_x, n_x), eye_y(n_y - 1, n_y - 1))
        ax = 0.0_dp
        ay = 0.0_dp
        eye_x = 0.0_dp
        eye_y = 0.0_dp
        do i = 1, n_x
            ax(i, i) = -2.0_dp/hx**2
            ax(i, modulo(i, n_x) + 1) = 1.0_dp/hx**2
            ax(modulo(i, n_x) + 1, i) = 1.0_dp/hx**2
            eye_x(i, i) = 1.0_dp
        end do
        do i = 1, n_y - 1
            ay(i, i) = -2.0_dp/hy**2
            if (i > 1) ay(i, i - 1) = 1.0_dp/hy**2
            if (i < n_y - 1) ay(i, i + 1) = 1.0_dp/hy**2
            eye_y(i, i) = 1.0_dp
        end do
        ! w(x_i, y_j) at index (j - 1)*n_x + i: an operator A_y (x) A_x is kron(A_y, A_x)
        k = plate%bending_x*kron(eye_y, matmul(ax, ax)) + 2.0_dp*plate%bending_xy*kron(ay, ax) &
            + plate%bending_y*kron(matmul(ay, ay), eye_x) - plate%tension_x*kron(eye_y, ax) &
            - plate%tension_y*kron(ay, eye_x) + plate%foundation*kron(eye_y, eye_x)
        n = size(k, 1)
        allocate (w(n), work(max(1, 3*n)))
        call dsyev('N', 'U', n, k, n, w, work, size(work), info)
        if (info /= 0) w = huge(1.0_dp)
        omega2 = w(1:size(omega2))/plate%mass_per_area
    end subroutine fd_eigenvalues

    !> Kronecker product a (x) b.
    pure function kron(a, b) result(c)
        real(dp), intent(in) :: a(:, :), b(:, :)
        real(dp) :: c(size(a, 1)*size(b, 1), size(a, 2)*size(b, 2))

        integer :: i, j, p, q

        p = size(b, 1)
        q = size(b, 2)
        do j = 1, size(a, 2)
            do i = 1, size(a, 1)
                c((i - 1)*p + 1:i*p, (j - 1)*q + 1:j*q) = a(i, j)*b
            end do
        end do
    end function kron

    !> int int rho_h*phi_k*phi_l dx dy = delta_kl by the trapezoidal rule on a grid fine enough
    !> to be exact for these trigonometric products (periodic in x; sin*sin in y with
    !> n + n' < 2*n_y), for every mode below 600 Hz.
    subroutine test_modal_mass(error)
        type(test_error), allocatable, intent(out) :: error

        type(tyre_plate) :: plate
        type(plate_mode), allocatable :: modes(:)
        type(error_type), allocatable :: fail
        real(dp), allocatable :: phi(:, :), mass(:, :)
        integer, parameter :: n_x = 128, n_y = 64
        real(dp) :: x, y, deviation
        integer :: i, j, k

        call plate_mode_list(plate, 600.0_dp, modes, fail)
        call check(error, .not. allocated(fail), 'plate_mode_list failed')
        if (allocated(error)) return
        allocate (phi(n_x*(n_y + 1), size(modes)))
        do j = 0, n_y
            y = j*plate%width/n_y
            do i = 1, n_x
                x = (i - 1)*plate%length/n_x
                phi(j*n_x + i, :) = plate_mode_shape(plate, modes, x, y)
            end do
        end do
        ! edge rows y = 0 and y = b have weight 1/2, but phi vanishes there
        mass = plate%mass_per_area*(plate%length/n_x)*(plate%width/n_y)*matmul(transpose(phi), phi)
        deviation = 0.0_dp
        do k = 1, size(modes)
            mass(k, k) = mass(k, k) - 1.0_dp
        end do
        deviation = maxval(abs(mass))
        call note('modes', real(size(modes), dp))
        call note('max |M - I|', deviation)
        call check(error, deviation < 1.0e-12_dp, 'modal mass matrix differs from the identity by more than 1e-12')
    end subroutine test_modal_mass

    !> G_ij(0) of the modes up to f_max equals the double Fourier series of the static
    !> problem, w = sum_{m in Z} sum_n (2/(L*b))*exp(i*k_m*(x - x'))*sin(q_n*y)*sin(q_n*y')/K_mn
    !> with K_mn = D_x*k^4 + 2*D_xy*k^2*q^2 + D_y*q^4 + T_x*k^2 + T_y*q^2 + s written out here,
    !> summed over the same wavenumbers (K_mn <= rho_h*(2*pi*f_max)^2).
    subroutine test_static(error)
        type(test_error), allocatable, intent(out) :: error

        type(tyre_plate) :: plate
        type(point_modes) :: description
        type(error_type), allocatable :: fail
        real(dp) :: x(12), y(12), direct(12, 12), g(12, 12), full(12, 12)
        real(dp), parameter :: f_max = 3000.0_dp

        call patch_points([plate%length/2, plate%width/2], [0.12_dp, 0.15_dp], 4, 3, x, y)
        call plate_modes(plate, x, y, f_max, description, fail)
        call check(error, .not. allocated(fail), 'plate_modes failed')
        if (allocated(error)) return
        g = real(patch_receptance(description, 0.0_dp), dp)
        direct = fourier_compliance(plate, x, y, plate%mass_per_area*(2.0_dp*pi*f_max)**2)
        call note('modes', real(size(description%shape, 2), dp))
        call note('rel. difference', maxval(abs(g - direct))/maxval(abs(direct)))
        full = fourier_compliance(plate, x, y, plate%mass_per_area*(2.0_dp*pi*60000.0_dp)**2)
        call note('truncation at f_max', maxval(abs(g - full))/maxval(abs(full)))
        call check(error, maxval(abs(g - direct)) <= 1.0e-12_dp*maxval(abs(direct)), &
                   'modal G(0) differs from the Fourier series over the same wavenumbers by more than 1e-12')
    end subroutine test_static

    !> Static compliance matrix [m/N] by the double Fourier series over K_mn <= k_max.
    function fourier_compliance(plate, x, y, k_max) result(w)
        type(tyre_plate), intent(in) :: plate
        real(dp), intent(in) :: x(:), y(:), k_max
        real(dp) :: w(size(x), size(x))

        real(dp) :: k2, q2, stiffness
        integer :: m, n, i, j

        w = 0.0_dp
        n = 1
        do
            q2 = (n*pi/plate%width)**2
            if (plate%bending_y*q2**2 + plate%tension_y*q2 + plate%foundation > k_max) exit
            m = 0
            do
                k2 = (2.0_dp*pi*m/plate%length)**2
                stiffness = plate%bending_x*k2**2 + 2.0_dp*plate%bending_xy*k2*q2 + plate%bending_y*q2**2 &
                            + plate%tension_x*k2 + plate%tension_y*q2 + plate%foundation
                if (stiffness > k_max) exit
                do j = 1, size(x)
                    do i = 1, size(x)
                        ! m and -m together: 2*cos; m = 0 once
                        w(i, j) = w(i, j) + merge(1.0_dp, 2.0_dp, m == 0)*2.0_dp/(plate%length*plate%width) &
                                  *cos(sqrt(k2)*(x(i) - x(j)))*sin(sqrt(q2)*y(i))*sin(sqrt(q2)*y(j))/stiffness
                    end do
                end do
                m = m + 1
            end do
            n = n + 1
        end do
    end function fourier_compliance

    !> G_ij(omega) = G_ji(omega) at frequencies through the band; points on one line y = const
    !> equally spaced in x see the same G between neighbours (the ring has no preferred x).
    subroutine test_reciprocity(error)
        type(test_error), allocatable, intent(out) :: error

        type(tyre_plate) :: plate
        type(point_modes) :: description
        type(error_type), allocatable :: fail
        real(dp) :: x(12), y(12), asymmetry, shift
        complex(dp) :: g(12, 12)
        integer :: i

        call patch_points([0.3_dp, 0.1_dp], [0.12_dp, 0.15_dp], 4, 3, x, y)
        call plate_modes(plate, x, y, 2000.0_dp, description, fail)
        call check(error, .not. allocated(fail), 'plate_modes failed')
        if (allocated(error)) return
        asymmetry = 0.0_dp
        shift = 0.0_dp
        do i = 0, 40
            g = patch_receptance(description, 2.0_dp*pi*50.0_dp*i)
            asymmetry = max(asymmetry, maxval(abs(g - transpose(g)))/maxval(abs(g)))
            shift = max(shift, abs(g(1, 2) - g(2, 3))/abs(g(1, 2)), abs(g(5, 6) - g(7, 8))/abs(g(5, 6)))
        end do
        call note('max |G - G^T|/max |G|', asymmetry)
        call note('max rel. |G_12 - G_23|', shift)
        call check(error, asymmetry < 1.0e-14_dp .and. shift < 1.0e-10_dp, &
                   'G is not symmetric or not invariant under a shift along x')
    end subroutine test_reciprocity

    !> The defaults documented in the module: first modes at 96, 105 (a pair) and 127 Hz; the
    !> static point stiffness at the patch centre, reported.
    subroutine test_defaults(error)
        type(test_error), allocatable, intent(out) :: error

        type(tyre_plate) :: plate
        type(plate_mode), allocatable :: modes(:)
        type(error_type), allocatable :: fail
        real(dp) :: f(5), w(1, 1)

        call plate_mode_list(plate, 200.0_dp, modes, fail)
        call check(error, .not. allocated(fail), 'plate_mode_list failed')
        if (allocated(error)) return
        f = plate_frequency(plate, modes(1:5)%m, modes(1:5)%n)/(2.0_dp*pi)
        call note('f_1 [Hz]', f(1))
        call note('f_2 [Hz]', f(2))
        call note('f_4 [Hz]', f(4))
        w = fourier_compliance(plate, [plate%length/2], [plate%width/2], plate%mass_per_area*(2.0_dp*pi*1.0e5_dp)**2)
        call note('point stiffness [N/m]', 1.0_dp/w(1, 1))
        call note('modes below 2 kHz', real(count_below(plate, 2000.0_dp), dp))
        call check(error, nint(f(1)) == 96 .and. nint(f(2)) == 105 .and. nint(f(3)) == 105 .and. nint(f(4)) == 127, &
                   'first modes differ from the 96, 105, 105, 127 Hz documented')
    end subroutine test_defaults

    integer function count_below(plate, f_max)
        type(tyre_plate), intent(in) :: plate
        real(dp), intent(in) :: f_max

        type(plate_mode), allocatable :: modes(:)
        type(error_type), allocatable :: fail

        call plate_mode_list(plate, f_max, modes, fail)
        count_below = 0
        if (.not. allocated(fail)) count_below = size(modes)
    end function count_below

    subroutine test_errors(error)
        type(test_error), allocatable, intent(out) :: error

        type(tyre_plate) :: plate
        type(point_modes) :: description
        type(error_type), allocatable :: fail

        plate%foundation = 0.0_dp
        call plate_modes(plate, [0.5_dp], [0.1_dp], 500.0_dp, description, fail)
        call check(error, allocated(fail), 'expected an error for s = 0')
        if (allocated(error)) return
        call check(error, index(fail%message, 's > 0') > 0, 'message should name s: '//fail%message)
        if (allocated(error)) return
        plate = tyre_plate()
        call plate_modes(plate, [0.5_dp], [0.25_dp], 500.0_dp, description, fail)
        call check(error, allocated(fail), 'expected an error for a point off the belt (y > b)')
        if (allocated(error)) return
        call check(error, index(fail%message, 'y <= b') > 0, 'message should name the width: '//fail%message)
        if (allocated(error)) return
        call plate_modes(plate, [0.5_dp], [0.1_dp], 50.0_dp, description, fail)
        call check(error, allocated(fail), 'expected an error for f_max below the first mode')
        if (allocated(error)) return
        call check(error, index(fail%message, 'raise f_max') > 0, 'message should say what to do: '//fail%message)
        if (allocated(error)) return
        plate%damping_ratio = 1.0_dp
        call plate_modes(plate, [0.5_dp], [0.1_dp], 500.0_dp, description, fail)
        call check(error, allocated(fail), 'expected an error for xi = 1')
    end subroutine test_errors

end module test_plate_mod
