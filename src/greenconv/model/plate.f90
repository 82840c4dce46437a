!> An analytic tyre belt in two dimensions: a pre-tensioned orthotropic Kirchhoff plate on an
!> elastic (Winkler) foundation, closed over one circumference L and simply supported along its
!> two edges, seen at the N_c points of a 2D contact patch. It extends the 1D belt of
!> greenconv_model_tyre across the width b (the kind of model of W. Kropp, "Structure-borne
!> sound on a smooth tyre", Applied Acoustics 26 (1989) 181-192; the derivation below is ours).
!>
!> **Equation.** x runs along the circumference (the direction of travel), 0 <= x < L, y across
!> the belt, 0 <= y <= b. The radial displacement w(x, y, t) [m] under a pressure p [N/m^2] obeys
!>
!>     rho_h*w_tt + D_x*w_xxxx + 2*D_xy*w_xxyy + D_y*w_yyyy - T_x*w_xx - T_y*w_yy + s*w = p,
!>
!> rho_h the mass per area [kg/m^2]; D_x, D_y the bending stiffnesses [N*m] for bending along x
!> and along y; D_xy [N*m] the effective torsional stiffness of the orthotropic plate (Huber's
!> H = D_1*nu_2 + 2*D_k); T_x, T_y the membrane tensions [N/m] that the inflation pressure puts
!> in the belt; s [N/m^3] the foundation stiffness per area (sidewalls and air). The plate terms
!> come from the bending moments M_x = -(D_x*w_xx + D_1*nu_2*w_yy), M_y likewise and the twisting
!> moment M_xy = -2*D_k*w_xy in the moment balance M_x,xx + 2*M_xy,xy + M_y,yy = -q; the tension
!> terms from the vertical component of the membrane forces on a curved element; the foundation
!> from a spring bed. Curvature of the ring and coupling to in-plane motion are neglected.
!>
!> **Boundary conditions.** The belt is a closed ring: w is periodic in x with period L (it
!> needs no supports along x, unlike the 1D model). Its edges y = 0 and y = b sit on the
!> sidewalls, which stop the radial motion but hardly resist rotation: simply supported,
!> w = 0 and w_yy = 0 (zero moment M_y; the D_1*nu_2*w_xx part vanishes with w along the edge).
!>
!> **Modes.** Separation w = X(x)*Y(y)*exp(i*omega*t) with X'' = -k^2*X, Y'' = -q^2*Y turns
!> every derivative into a factor: w_xx = -k^2*w, w_xxxx = k^4*w, w_xxyy = k^2*q^2*w, ... The
!> conditions allow Y = sin(q_n*y), q_n = n*pi/b (n >= 1; both conditions then hold since
!> Y'' is proportional to Y), and X = cos(k_m*x) or sin(k_m*x), k_m = 2*pi*m/L (m >= 0, m = 0
!> only with the cosine). Substituting gives
!>
!>     omega_mn^2 = (D_x*k^4 + 2*D_xy*k^2*q^2 + D_y*q^4 + T_x*k^2 + T_y*q^2 + s)/rho_h,
!>
!> the same for the cosine and the sine of one (m, n): modes with m >= 1 come in pairs, the
!> standing-wave form of the two waves travelling around the ring. The operator is symmetric
!> and positive under these conditions, so the modes are orthogonal; normalised to unit modal
!> mass, int int rho_h*phi^2 dx dy = 1, with int_0^L cos^2 = int_0^L sin^2 = L/2 (m >= 1),
!> int_0^L 1 = L and int_0^b sin^2(q_n*y) dy = b/2:
!>
!>     phi(x, y) = c_m*cos(k_m*x)*sin(q_n*y)  or  c_m*sin(k_m*x)*sin(q_n*y),
!>     c_m = 2/sqrt(rho_h*L*b) for m >= 1,   c_0 = sqrt(2/(rho_h*L*b)).
!>
!> Damping is modal, one ratio xi for every mode, as in the 1D model. The Green's matrix
!> between points (x_i, y_i) and (x_j, y_j) is then
!>
!>     G_ij(omega) = sum_k phi_k(x_i, y_i)*phi_k(x_j, y_j)/(omega_k^2 - omega^2 + 2i*xi*omega_k*omega),
!>
!> symmetric (reciprocal) by construction; a cosine-sine pair adds up to
!> c_m^2*cos(k_m*(x_i - x_j))*sin(q_n*y_i)*sin(q_n*y_j): it depends on x_i - x_j alone, as a
!> ring's response must.
!>
!> **Defaults** (SI; a 205/55 R16 passenger-car tyre in round numbers, consistent with the
!> 1D belt of greenconv_model_tyre spread over b = 0.2 m): L = 2*pi*0.3 m = 1.885 m;
!> rho_h = 2.5 kg/m / 0.2 m = 12.5 kg/m^2; D_x = 5 N*m^2 / 0.2 m = 25 N*m; D_y = 10 N*m (we
!> assume the belt bends more easily across, where the tread grooves cut it; no measured value
!> was at hand); D_xy = sqrt(D_x*D_y) = 15.8 N*m (Huber's approximation); T_x = p0*R =
!> 2.2e5 Pa * 0.3 m = 6.6e4 N/m (hoop tension at 2.2 bar); T_y = 1.0e4 N/m, smaller since the
!> carcass and sidewalls carry most of the inflation load across the width (an assumption);
!> s = 1.5e6 N/m^3 (air and sidewalls per area; the edge supports already carry part of the 1D
!> model's foundation); xi = 0.05. They give the first modes at 96 Hz (m = 0, n = 1), 105 Hz
!> (m = 1, a pair) and 127 Hz (m = 2), the range of the first radial resonances measured on car
!> tyres; 285 modes below 2 kHz; a static point stiffness at mid-belt of 1.1e5 N/m (the double
!> Fourier series of the static problem, converged), half that of the 1D belt, whose line
!> load is spread over the whole width.
module greenconv_model_plate
    use greenconv_core_kinds, only: dp
    use greenconv_core_error, only: error_type, fatal_error
    use greenconv_core_text, only: real_text, int_text
    use greenconv_model_modal_set, only: modes_from_paper
    use greenconv_model_point_modes, only: point_modes, separable_shapes, check_on_belt
    use greenconv_model_tyre, only: contact_positions
    implicit none
    private

    public :: tyre_plate, plate_mode, plate_frequency, plate_mode_shape, plate_mode_list, plate_modes
    public :: patch_points, patch_receptance

    !> pi
    real(dp), parameter :: pi = acos(-1.0_dp)
    !> Most modes a plate model keeps.
    integer, parameter :: max_modes = 100000

    !> A tyre belt: pre-tensioned orthotropic plate on an elastic foundation, periodic over the
    !> circumference L (x), simply supported at the edges y = 0 and y = b.
    type :: tyre_plate
        !> Circumference L [m] (x), 2*pi*0.3 m.
        real(dp) :: length = 1.885_dp
        !> Width b [m] (y).
        real(dp) :: width = 0.2_dp
        !> Mass per area rho_h [kg/m^2] of belt and tread.
        real(dp) :: mass_per_area = 12.5_dp
        !> Bending stiffness D_x [N*m] for bending along x (the circumference).
        real(dp) :: bending_x = 25.0_dp
        !> Bending stiffness D_y [N*m] for bending along y (across the belt).
        real(dp) :: bending_y = 10.0_dp
        !> Effective torsional stiffness D_xy [N*m] (the operator has 2*D_xy*w_xxyy);
        !> default sqrt(D_x*D_y).
        real(dp) :: bending_xy = 15.811388300841896_dp
        !> Membrane tension T_x [N/m] along the circumference (p0*R).
        real(dp) :: tension_x = 6.6e4_dp
        !> Membrane tension T_y [N/m] across the belt.
        real(dp) :: tension_y = 1.0e4_dp
        !> Foundation stiffness s [N/m^3] (sidewalls and air, per area of belt).
        real(dp) :: foundation = 1.5e6_dp
        !> Modal damping ratio xi, the same for every mode, in [0, 1).
        real(dp) :: damping_ratio = 0.05_dp
    end type tyre_plate

    !> Which mode of the plate: circumferential order m, order n across, cosine or sine in x.
    type :: plate_mode
        !> Circumferential order m >= 0 (k_m = 2*pi*m/L [rad/m]).
        integer :: m = 0
        !> Order across n >= 1 (q_n = n*pi/b [rad/m]).
        integer :: n = 1
        !> Whether the x dependence is sin(k_m*x) rather than cos(k_m*x) (never for m = 0).
        logical :: sine = .false.
    end type plate_mode

contains

    !> Natural angular frequency omega_mn [rad/s] of the modes of orders (m, n):
    !> sqrt((D_x*k^4 + 2*D_xy*k^2*q^2 + D_y*q^4 + T_x*k^2 + T_y*q^2 + s)/rho_h).
    elemental real(dp) function plate_frequency(plate, m, n)
        !> The plate.
        type(tyre_plate), intent(in) :: plate
        !> Circumferential order, >= 0.
        integer, intent(in) :: m
        !> Order across the width, >= 1.
        integer, intent(in) :: n

        real(dp) :: k2, q2

        k2 = (2.0_dp*pi*m/plate%length)**2
        q2 = (n*pi/plate%width)**2
        plate_frequency = sqrt((plate%bending_x*k2**2 + 2.0_dp*plate%bending_xy*k2*q2 + plate%bending_y*q2**2 &
                                + plate%tension_x*k2 + plate%tension_y*q2 + plate%foundation)/plate%mass_per_area)
    end function plate_frequency

    !> Mode shape phi(x, y) [1/sqrt(kg)] of unit modal mass: c_m*cos(k_m*x)*sin(q_n*y) or
    !> c_m*sin(k_m*x)*sin(q_n*y), c_m = 2/sqrt(rho_h*L*b) (m >= 1), sqrt(2/(rho_h*L*b)) (m = 0).
    elemental real(dp) function plate_mode_shape(plate, mode, x, y)
        !> The plate.
        type(tyre_plate), intent(in) :: plate
        !> Which mode.
        type(plate_mode), intent(in) :: mode
        !> Position along the circumference [m].
        real(dp), intent(in) :: x
        !> Position across the belt [m], 0..b.
        real(dp), intent(in) :: y

        plate_mode_shape = plate_along(plate, mode, x)*plate_across(plate, mode%n, y)
    end function plate_mode_shape

    !> The x factor of a mode shape [1/sqrt(kg)]: c_m*cos(k_m*x) or c_m*sin(k_m*x).
    elemental real(dp) function plate_along(plate, mode, x)
        type(tyre_plate), intent(in) :: plate
        type(plate_mode), intent(in) :: mode
        real(dp), intent(in) :: x

        if (mode%m == 0) then
            plate_along = sqrt(2.0_dp/(plate%mass_per_area*plate%length*plate%width))
        else if (mode%sine) then
            plate_along = 2.0_dp/sqrt(plate%mass_per_area*plate%length*plate%width)*sin(2.0_dp*pi*mode%m*x/plate%length)
        else
            plate_along = 2.0_dp/sqrt(plate%mass_per_area*plate%length*plate%width)*cos(2.0_dp*pi*mode%m*x/plate%length)
        end if
    end function plate_along

    !> The y factor of a mode shape: sin(q_n*y), dimensionless.
    elemental real(dp) function plate_across(plate, n, y)
        type(tyre_plate), intent(in) :: plate
        integer, intent(in) :: n
        real(dp), intent(in) :: y

        plate_across = sin(n*pi*y/plate%width)
    end function plate_across

    !> Every mode whose natural frequency is at most f_max [Hz], by increasing frequency (a
    !> cosine before its sine; equal frequencies by m, then n). omega_mn grows with m and with
    !> n, so the search stops at the first order past f_max.
    subroutine plate_mode_list(plate, f_max, modes, error, band_name)
        !> The plate.
        type(tyre_plate), intent(in) :: plate
        !> Highest natural frequency kept [Hz].
        real(dp), intent(in) :: f_max
        !> The modes kept.
        type(plate_mode), allocatable, intent(out) :: modes(:)
        !> Set for a non-physical plate, no mode below f_max or more than `max_modes`.
        type(error_type), allocatable, intent(out) :: error
        !> The name the caller gives f_max, for the messages (`band_text`); `f_max` when absent.
        character(len=*), intent(in), optional :: band_name

        type(plate_mode), allocatable :: found(:)
        real(dp), allocatable :: omega(:)
        real(dp) :: omega_max
        integer :: m, n, count, i, j

        call check_plate(plate, error)
        if (allocated(error)) return
        omega_max = 2.0_dp*pi*f_max
        allocate (found(64))
        count = 0
        n = 1
        do while (plate_frequency(plate, 0, n) <= omega_max)
            m = 0
            do while (plate_frequency(plate, m, n) <= omega_max)
                if (count + 2 > max_modes) then
                    call fatal_error(error, 'plate model: more than '//int_text(max_modes)//' modes below ' &
                                     //trim(band_text(band_name))//' = '//real_text(f_max)//' Hz: lower ' &
                                     //trim(band_text(band_name)))
                    return
                end if
                if (count + 2 > size(found)) found = [found, found]
                count = count + 1
                found(count) = plate_mode(m, n, .false.)
                if (m > 0) then
                    count = count + 1
                    found(count) = plate_mode(m, n, .true.)
                end if
                m = m + 1
            end do
            n = n + 1
        end do
        if (count == 0) then
            call fatal_error(error, 'plate model: no mode below '//trim(band_text(band_name))//' = '//real_text(f_max) &
                             //' Hz (the first is at '//real_text(plate_frequency(plate, 0, 1)/(2.0_dp*pi)) &
                             //' Hz): raise '//trim(band_text(band_name)))
            return
        end if
        ! insertion sort by frequency, stable: the enumeration order breaks ties
        modes = found(1:count)
        omega = plate_frequency(plate, modes%m, modes%n)
        do i = 2, count
            j = i
            do while (j > 1)
                if (.not. omega(j - 1) > omega(j)) exit
                modes(j - 1:j) = modes([j, j - 1])
                omega(j - 1:j) = omega([j, j - 1])
                j = j - 1
            end do
        end do
    end subroutine plate_mode_list

    !> The modes of the plate up to f_max [Hz] seen at the points (x_i, y_i): unit modal
    !> responses (A_k = 1, omega_k, xi in the paper's form) and shapes phi_k(x_i, y_i).
    subroutine plate_modes(plate, x, y, f_max, description, error, band_name)
        !> The plate.
        type(tyre_plate), intent(in) :: plate
        !> Contact point positions x_i [m] along the circumference, within [0, L].
        real(dp), intent(in) :: x(:)
        !> Contact point positions y_i [m] across the belt, within [0, b]; size(y) = size(x).
        real(dp), intent(in) :: y(:)
        !> Highest natural frequency kept [Hz].
        real(dp), intent(in) :: f_max
        !> Modes and mode shapes at the points.
        type(point_modes), intent(out) :: description
        !> Set for a non-physical plate, points off the plate or no mode below f_max.
        type(error_type), allocatable, intent(out) :: error
        !> The name the caller's user gives f_max (`&structure f_modes`, `FMAX`), for the
        !> messages; `f_max` when absent.
        character(len=*), intent(in), optional :: band_name

        type(plate_mode), allocatable :: modes(:)
        integer :: k, n_m

        call check_points(plate, x, y, error)
        if (allocated(error)) return
        call plate_mode_list(plate, f_max, modes, error, band_name)
        if (allocated(error)) return
        n_m = size(modes)
        description%modes = modes_from_paper([(1.0_dp, k=1, n_m)], plate_frequency(plate, modes%m, modes%n), &
                                             [(plate%damping_ratio, k=1, n_m)])
        allocate (description%shape(size(x), n_m))
        do k = 1, n_m
            description%shape(:, k) = plate_mode_shape(plate, modes(k), x, y)
        end do
        call grid_factors(plate, modes, x, y, description%separable)
    end subroutine plate_modes

    !> The shapes' factors (greenconv_model_point_modes's `separable_shapes`) when the points
    !> form a grid: n_col distinct x by n_row distinct y with every (x, y) pair taken by one
    !> point (`patch_points` gives one, in any order); unallocated otherwise. The x functions
    !> are the modes' distinct (m, cosine or sine), the y functions their distinct n, each
    !> numbered by its first mode; shape(i, k) is the product of the two factors bit for bit.
    subroutine grid_factors(plate, modes, x, y, factors)
        type(tyre_plate), intent(in) :: plate
        type(plate_mode), intent(in) :: modes(:)
        real(dp), intent(in) :: x(:), y(:)
        type(separable_shapes), allocatable, intent(out) :: factors

        real(dp), allocatable :: columns(:), rows(:)
        integer, allocatable :: column(:), row(:)
        type(plate_mode), allocatable :: along(:)
        integer, allocatable :: across(:)
        logical, allocatable :: taken(:, :)
        integer :: i, k, f

        call distinct_values(x, columns, column)
        call distinct_values(y, rows, row)
        if (size(columns)*size(rows) /= size(x)) return
        allocate (taken(size(columns), size(rows)), source=.false.)
        do i = 1, size(x)
            if (taken(column(i), row(i))) return
            taken(column(i), row(i)) = .true.
        end do
        allocate (factors)
        allocate (factors%mode_along(size(modes)), factors%mode_across(size(modes)), along(0), across(0))
        do k = 1, size(modes)
            f = findloc(along%m == modes(k)%m .and. (along%sine .eqv. modes(k)%sine), .true., dim=1)
            if (f == 0) then
                along = [along, modes(k)]
                f = size(along)
            end if
            factors%mode_along(k) = f
            f = findloc(across, modes(k)%n, dim=1)
            if (f == 0) then
                across = [across, modes(k)%n]
                f = size(across)
            end if
            factors%mode_across(k) = f
        end do
        allocate (factors%along(size(columns), size(along)), factors%across(size(rows), size(across)))
        do f = 1, size(along)
            factors%along(:, f) = plate_along(plate, along(f), columns)
        end do
        do f = 1, size(across)
            factors%across(:, f) = plate_across(plate, across(f), rows)
        end do
        factors%column = column
        factors%row = row
    end subroutine grid_factors

    !> The distinct values of a list in the order of their first appearance, and the index of
    !> each entry among them.
    pure subroutine distinct_values(values, found, index)
        real(dp), intent(in) :: values(:)
        real(dp), allocatable, intent(out) :: found(:)
        integer, allocatable, intent(out) :: index(:)

        integer :: i, j, count

        allocate (found(size(values)), index(size(values)))
        count = 0
        do i = 1, size(values)
            j = findloc(found(1:count), values(i), dim=1)
            if (j == 0) then
                count = count + 1
                found(count) = values(i)
                j = count
            end if
            index(i) = j
        end do
        found = found(1:count)
    end subroutine distinct_values

    !> Points of an n_x by n_y contact patch, each the middle of its share of the patch, x
    !> fastest: point i = (i_y - 1)*n_x + i_x is at (x(i_x), y(i_y)) (the layout of
    !> `greenconv_model_tyre`'s contact_positions in each direction).
    pure subroutine patch_points(centre, extent, n_x, n_y, x, y)
        !> Centre of the patch (x, y) [m], e.g. (L/2, b/2).
        real(dp), intent(in) :: centre(2)
        !> Length along x and width along y of the patch [m].
        real(dp), intent(in) :: extent(2)
        !> Points along x (the direction of travel), >= 1.
        integer, intent(in) :: n_x
        !> Points along y (across), >= 1.
        integer, intent(in) :: n_y
        !> x_i [m] of the n_x*n_y points.
        real(dp), intent(out) :: x(n_x*n_y)
        !> y_i [m] of the n_x*n_y points.
        real(dp), intent(out) :: y(n_x*n_y)

        real(dp) :: along(n_x), across(n_y)
        integer :: j

        along = contact_positions(centre(1), extent(1), n_x)
        across = contact_positions(centre(2), extent(2), n_y)
        do j = 1, n_y
            x((j - 1)*n_x + 1:j*n_x) = along
            y((j - 1)*n_x + 1:j*n_x) = across(j)
        end do
    end subroutine patch_points

    !> The Green's matrix G_ij(omega) [m/N] of modes shared by N_c points:
    !> sum_k phi_ik*phi_jk*(r_k/(i*omega - lambda_k) + conj(r_k)/(i*omega - conj(lambda_k))).
    pure function patch_receptance(description, omega) result(g)
        !> Modes and shapes at the points.
        type(point_modes), intent(in) :: description
        !> Angular frequency omega [rad/s].
        real(dp), intent(in) :: omega
        complex(dp) :: g(size(description%shape, 1), size(description%shape, 1))

        complex(dp) :: modal(size(description%modes%pole))
        complex(dp) :: s
        integer :: j

        s = cmplx(0.0_dp, omega, kind=dp)
        modal = description%modes%residue/(s - description%modes%pole) &
                + conjg(description%modes%residue)/(s - conjg(description%modes%pole))
        do j = 1, size(g, 2)
            g(:, j) = matmul(description%shape, modal*description%shape(j, :))
        end do
    end function patch_receptance

    !> An error for a non-physical plate.
    pure subroutine check_plate(plate, error)
        type(tyre_plate), intent(in) :: plate
        type(error_type), allocatable, intent(out) :: error

        if (.not. (plate%length > 0.0_dp .and. plate%width > 0.0_dp .and. plate%mass_per_area > 0.0_dp &
                   .and. plate%foundation > 0.0_dp)) then
            call fatal_error(error, 'plate model: expected L > 0, b > 0, rho_h > 0 and s > 0')
        else if (.not. (plate%bending_x >= 0.0_dp .and. plate%bending_y >= 0.0_dp .and. plate%bending_xy >= 0.0_dp &
                        .and. plate%tension_x >= 0.0_dp .and. plate%tension_y >= 0.0_dp)) then
            call fatal_error(error, 'plate model: expected D_x, D_y, D_xy, T_x and T_y >= 0')
        else if (.not. (plate%bending_x + plate%bending_xy + plate%tension_x > 0.0_dp)) then
            call fatal_error(error, 'plate model: expected D_x + D_xy + T_x > 0 (else every order m has the ' &
                             //'same frequency and no f_max bounds the modes)')
        else if (.not. (plate%damping_ratio >= 0.0_dp .and. plate%damping_ratio < 1.0_dp)) then
            call fatal_error(error, 'plate model: expected a damping ratio in [0, 1), found ' &
                             //real_text(plate%damping_ratio))
        end if
    end subroutine check_plate

    !> An error for a non-physical plate or a point off the plate.
    pure subroutine check_points(plate, x, y, error)
        type(tyre_plate), intent(in) :: plate
        real(dp), intent(in) :: x(:), y(:)
        type(error_type), allocatable, intent(out) :: error

        call check_plate(plate, error)
        if (allocated(error)) return
        if (size(x) < 1 .or. size(y) /= size(x)) then
            call fatal_error(error, 'plate model: expected at least one contact point and as many y as x positions')
            return
        end if
        call check_on_belt('plate', 'x', 'L', x, plate%length, error)
        if (.not. allocated(error)) call check_on_belt('plate', 'y', 'b', y, plate%width, error)
    end subroutine check_points

    !> The name of the band's top in a message, blank-padded: `band_name`, or `f_max` when absent.
    pure function band_text(band_name) result(text)
        !> The caller's name for it.
        character(len=*), intent(in), optional :: band_name
        character(len=64) :: text

        text = 'f_max'
        if (present(band_name)) text = band_name
    end function band_text

end module greenconv_model_plate
