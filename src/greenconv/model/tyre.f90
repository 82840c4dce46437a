!> An analytic tyre: the belt as a tensioned Euler-Bernoulli beam on an elastic (Winkler)
!> foundation, simply supported over one circumference L, seen at N_c contact points.
!>
!> The belt's radial displacement w(x, t) under a line load f(x, t) [N/m] obeys
!>
!>     rhoA*w_tt + EI*w_xxxx - T*w_xx + s*w = f,
!>
!> with rhoA the mass per length [kg/m], EI the bending stiffness [N*m^2], T the tension [N]
!> that the inflation pressure puts in the belt and s the stiffness per length [N/m^2] of the
!> sidewalls and the air (the beam on elastic foundation of M. Hetenyi, "Beams on Elastic
!> Foundation", University of Michigan Press, 1946; with tension, K.F. Graff, "Wave Motion in
!> Elastic Solids", Oxford, 1975). It is the one-dimensional, circumferential reduction of
!> the tyre model of W. Kropp, "Structure-borne sound on a smooth tyre", Applied Acoustics 26
!> (1989) 181-192, a pre-tensioned orthotropic plate on an elastic foundation. Simple supports
!> at x = 0 and x = L give the modes, orthonormal to unit modal mass (int rhoA*phi_k^2 dx = 1),
!>
!>     phi_k(x) = sqrt(2/(rhoA*L))*sin(beta_k*x),   beta_k = k*pi/L,
!>     omega_k^2 = (EI*beta_k^4 + T*beta_k^2 + s)/rhoA,   k = 1, 2, ...
!>
!> (substitute w = phi_k(x)*exp(i*omega*t) in the equation). The closed ring has the
!> wavenumbers 2*pi*n/L, each twice (sine and cosine): the beam's k*pi/L are as dense, so the
!> beam over one circumference has the ring's modal density. Curvature and rotation (the
!> ring's coupling with the tangential motion, the splitting of the travelling waves) are
!> neglected: the contact points stay at fixed x_i. Damping is modal, h_k(t) =
!> exp(-xi*omega_k*t)*sin(omega_k^d*t)/omega_k^d per unit modal force, with one damping ratio
!> xi for every mode (xi = eta/2 for a loss factor eta at resonance).
!>
!> Defaults (SI), a passenger-car tyre 205/55 R16 in round numbers: radius 0.3 m, so
!> L = 2*pi*0.3 = 1.885 m; belt and tread 2.5 kg/m; EI = 5 N*m^2 (steel belt, 0.18 m wide);
!> T = p0*R*b = 2.2e5 Pa * 0.3 m * 0.18 m = 1.2e4 N at 2.2 bar; s = 7e5 N/m^2; xi = 0.05. They
!> give the first radial resonances at 86, 92 and 101 Hz and a static point stiffness at
!> mid-belt of 2.1e5 N/m (2*sqrt(T*s) = 1.8e5 N/m for the string on its foundation, bending
!> adds 15 %), both in the range measured on car tyres.
!>
!> Mode truncation (`tyre_band`): a road of shortest wavelength lambda_min [m] travelled at V
!> [m/s] excites frequencies up to V/lambda_min; modes up to twice that are kept, and never
!> above 1/(10*dt), so that the fastest kept mode has at least ten steps per period. Higher
!> modes respond quasi-statically; their compliance is neglected.
module greenconv_model_tyre
    use greenconv_core_kinds, only: dp
    use greenconv_core_error, only: error_type, fatal_error
    use greenconv_core_text, only: real_text
    use greenconv_model_modal_set, only: modes_from_paper
    use greenconv_model_point_modes, only: point_modes, check_on_belt
    implicit none
    private

    public :: tyre_belt, tyre_frequency, tyre_mode_shape, tyre_mode_count, tyre_modes, tyre_band
    public :: contact_positions

    !> pi
    real(dp), parameter :: pi = acos(-1.0_dp)
    !> Most modes a tyre model keeps.
    integer, parameter :: max_modes = 100000

    !> A tyre belt: tensioned beam on an elastic foundation, simply supported over L.
    type :: tyre_belt
        !> Length L [m]: one circumference, 2*pi*0.3 m.
        real(dp) :: length = 1.885_dp
        !> Mass per length rhoA [kg/m] of belt and tread.
        real(dp) :: mass_per_length = 2.5_dp
        !> Bending stiffness EI [N*m^2].
        real(dp) :: bending_stiffness = 5.0_dp
        !> Tension T [N] from the inflation pressure (p0*R*b).
        real(dp) :: tension = 1.2e4_dp
        !> Foundation stiffness s [N/m^2] (sidewalls and air, per length of belt).
        real(dp) :: foundation_stiffness = 7.0e5_dp
        !> Modal damping ratio xi, the same for every mode, in [0, 1).
        real(dp) :: damping_ratio = 0.05_dp
    end type tyre_belt

contains

    !> Natural angular frequency omega_k [rad/s] of mode k >= 1:
    !> sqrt((EI*beta^4 + T*beta^2 + s)/rhoA), beta = k*pi/L.
    elemental real(dp) function tyre_frequency(tyre, k)
        !> The tyre.
        type(tyre_belt), intent(in) :: tyre
        !> Mode number, >= 1.
        integer, intent(in) :: k

        real(dp) :: beta

        beta = k*pi/tyre%length
        tyre_frequency = sqrt((tyre%bending_stiffness*beta**4 + tyre%tension*beta**2 &
                               + tyre%foundation_stiffness)/tyre%mass_per_length)
    end function tyre_frequency

    !> Mode shape phi_k(x) = sqrt(2/(rhoA*L))*sin(k*pi*x/L) [1/sqrt(kg)], unit modal mass.
    elemental real(dp) function tyre_mode_shape(tyre, k, x)
        !> The tyre.
        type(tyre_belt), intent(in) :: tyre
        !> Mode number, >= 1.
        integer, intent(in) :: k
        !> Position along the belt [m], 0..L.
        real(dp), intent(in) :: x

        tyre_mode_shape = sqrt(2.0_dp/(tyre%mass_per_length*tyre%length))*sin(k*pi*x/tyre%length)
    end function tyre_mode_shape

    !> Number of modes whose natural frequency is at most f_max [Hz] (omega_k grows with k
    !> when EI > 0 or T > 0); at most `max_modes`.
    pure integer function tyre_mode_count(tyre, f_max)
        !> The tyre.
        type(tyre_belt), intent(in) :: tyre
        !> Highest natural frequency kept [Hz].
        real(dp), intent(in) :: f_max

        tyre_mode_count = 0
        do while (tyre_mode_count < max_modes)
            if (tyre_frequency(tyre, tyre_mode_count + 1) > 2.0_dp*pi*f_max) exit
            tyre_mode_count = tyre_mode_count + 1
        end do
    end function tyre_mode_count

    !> The band rule: f_max = min(2*V/lambda_min, 1/(10*dt)) [Hz].
    pure real(dp) function tyre_band(speed, shortest_wavelength, dt)
        !> Travel speed V [m/s].
        real(dp), intent(in) :: speed
        !> Shortest road wavelength lambda_min [m] (at least two road samples).
        real(dp), intent(in) :: shortest_wavelength
        !> Time step [s].
        real(dp), intent(in) :: dt

        tyre_band = min(2.0_dp*speed/shortest_wavelength, 0.1_dp/dt)
    end function tyre_band

    !> n_points positions [m] spread evenly over a contact patch centred on `centre`:
    !> x_i = centre + (i - (n_points + 1)/2)*patch/n_points, each the middle of its share.
    pure function contact_positions(centre, patch_length, n_points) result(x)
        !> Centre of the patch [m] (L/2 for the tyre).
        real(dp), intent(in) :: centre
        !> Length of the contact patch [m].
        real(dp), intent(in) :: patch_length
        !> Number of points, >= 1.
        integer, intent(in) :: n_points
        real(dp) :: x(n_points)

        integer :: i

        x = [(centre + (i - 0.5_dp*(n_points + 1))*patch_length/n_points, i=1, n_points)]
    end function contact_positions

    !> The modes of the tyre up to f_max [Hz] seen at the points x_i: unit modal responses
    !> (A_k = 1, omega_k, xi in the paper's form) and shapes phi_k(x_i).
    subroutine tyre_modes(tyre, positions, f_max, description, error, band_name)
        !> The tyre.
        type(tyre_belt), intent(in) :: tyre
        !> Contact point positions x_i [m], within [0, L].
        real(dp), intent(in) :: positions(:)
        !> Highest natural frequency kept [Hz].
        real(dp), intent(in) :: f_max
        !> Modes and mode shapes at the points.
        type(point_modes), intent(out) :: description
        !> Set for non-physical parameters, points off the belt or no mode below f_max.
        type(error_type), allocatable, intent(out) :: error
        !> The name the caller's user gives f_max (`&structure f_modes`), for the message;
        !> `f_max` when absent.
        character(len=*), intent(in), optional :: band_name

        integer :: k, n_m

        call check_tyre(tyre, positions, error)
        if (allocated(error)) return
        n_m = tyre_mode_count(tyre, f_max)
        if (n_m < 1) then
            if (present(band_name)) then
                call fatal_error(error, 'tyre model: no mode below '//band_name//' = '//real_text(f_max) &
                                 //' Hz (the first is at '//real_text(tyre_frequency(tyre, 1)/(2.0_dp*pi)) &
                                 //' Hz): raise '//band_name)
            else
                call fatal_error(error, 'tyre model: no mode below f_max = '//real_text(f_max)//' Hz (the first is ' &
                                 //'at '//real_text(tyre_frequency(tyre, 1)/(2.0_dp*pi))//' Hz): raise f_max')
            end if
            return
        end if
        description%modes = modes_from_paper([(1.0_dp, k=1, n_m)], tyre_frequency(tyre, [(k, k=1, n_m)]), &
                                             [(tyre%damping_ratio, k=1, n_m)])
        allocate (description%shape(size(positions), n_m))
        do k = 1, n_m
            description%shape(:, k) = tyre_mode_shape(tyre, k, positions)
        end do
    end subroutine tyre_modes

    !> An error for a non-physical tyre or a point off the belt.
    pure subroutine check_tyre(tyre, positions, error)
        type(tyre_belt), intent(in) :: tyre
        real(dp), intent(in) :: positions(:)
        type(error_type), allocatable, intent(out) :: error

        if (.not. (tyre%length > 0.0_dp .and. tyre%mass_per_length > 0.0_dp .and. tyre%bending_stiffness >= 0.0_dp &
                   .and. tyre%tension >= 0.0_dp .and. tyre%foundation_stiffness > 0.0_dp &
                   .and. tyre%bending_stiffness + tyre%tension > 0.0_dp)) then
            call fatal_error(error, 'tyre model: expected L > 0, rhoA > 0, s > 0, EI >= 0, T >= 0 and EI + T > 0')
        else if (.not. (tyre%damping_ratio >= 0.0_dp .and. tyre%damping_ratio < 1.0_dp)) then
            call fatal_error(error, 'tyre model: expected a damping ratio in [0, 1), found ' &
                             //real_text(tyre%damping_ratio))
        else if (size(positions) < 1) then
            call fatal_error(error, 'tyre model: expected at least one contact point')
        end if
        if (.not. allocated(error)) call check_on_belt('tyre', 'x', 'L', positions, tyre%length, error)
    end subroutine check_tyre

end module greenconv_model_tyre
