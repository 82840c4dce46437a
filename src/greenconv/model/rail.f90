!> A wheel on a rail, as a railway engineer gives them (SI units, time factor exp(i*omega*t),
!> so that a receptance is 1/(K - M*omega^2 + i*C*omega) as in greenconv_model_sdof):
!>
!> **The rail** is an infinite beam (bending stiffness EI [N m^2], mass per length m [kg/m])
!> on a continuous support of dynamic stiffness per length s*(omega) [N/m^2]. Its point
!> receptance at the load is the wavenumber integral of the beam's dynamic stiffness,
!>
!>     alpha_r(omega) = (1/(2*pi)) * integral over k of dk/D(k, omega),
!>
!> with D = EI*k^4 - m*omega^2 + s* for Euler-Bernoulli. With a^4 = (s* - m*omega^2)/EI
!> (principal fourth root; s* has Im >= 0, and a^4 on the negative real axis is the limit
!> Im -> 0+) the integral is closed:
!>
!>     alpha_r = 1/(2*sqrt(2)*EI*a^3),
!>
!> whose static limit, a = sqrt(2)*beta with beta = (s/(4*EI))^(1/4), is Hetenyi's
!> beta/(2*s) (M. Hetenyi, Beams on Elastic Foundation, 1946, art. 10), and whose limit for a
!> free rail (s* = 0) is -(1 + i)/(4*EI*k^3), k^4 = m*omega^2/EI (D. Thompson, Railway Noise
!> and Vibration, 2009, ch. 3). A Timoshenko rail (shear stiffness kappa*G*A [N], rotary
!> inertia rho*I [kg m]) has, after the rotation is eliminated,
!>
!>     1/D = (EI*q + kGA - rhoI*omega^2) / (kGA*EI*q^2 + (EI*(s* - m*omega^2) - kGA*rhoI*omega^2)*q
!>                                           + (s* - m*omega^2)*(kGA - rhoI*omega^2)),   q = k^2,
!>
!> a ratio of polynomials in q whose two roots q_j give alpha_r = (i/2)*sum_j A_j/sqrt(q_j)
!> (residues A_j of the partial fractions in q, sqrt(q_j) with Im > 0: integral of
!> dk/(k^2 - q) = i*pi/sqrt(q)); kGA -> infinity and rhoI -> 0 give back Euler-Bernoulli.
!>
!> **The support** is one layer (a stiffness s and a viscous damping c per length:
!> s* = s + i*omega*c) or two: the pad (s_p, c_p) on sleepers smeared into a mass per length
!> m_s on the ballast (s_b, c_b), the pad in series with the sleeper mass on the ballast,
!>
!>     s*(omega) = s_p* * (s_b* - m_s*omega^2) / (s_p* + s_b* - m_s*omega^2).
!>
!> **The wheel** is a mass M_w on a primary suspension (k_s, c_s) to a bogie that does not
!> move: alpha_w = 1/(k_s - M_w*omega^2 + i*omega*c_s), or its normal modes at the contact
!> node from a universal file (dataset 55, greenconv_model_modes_file), frequencies f_k > 0
!> (the wheel held by its suspension), modal masses m_k, viscous damping ratios xi_k and shapes
!> phi_k at the node: alpha_w = sum_k phi_k^2/(m_k*(omega_k^2 - omega^2 + 2*i*xi_k*omega_k*omega)),
!> omega_k = 2*pi*f_k; one mode of f = sqrt(k_s/M_w)/(2*pi), m = M_w, xi = c_s/(2*sqrt(k_s*M_w))
!> and phi = 1 is the mass on its suspension. The wheel and the rail are in series
!> at the contact: the contact's compression falls by (alpha_w + alpha_r)*F under a force F
!> pressing them apart.
!>
!> **Hertz's contact** of the wheel (rolling radius R_w) on the rail head (transverse radius
!> R_r), both of Young's modulus E and Poisson's ratio nu: F = C_H*delta^(3/2) with
!> C_H = (4/3)*E'*sqrt(R_e), E' = E/(2*(1 - nu^2)), R_e = sqrt(R_w*R_r), the equivalent
!> sphere of K. L. Johnson, Contact Mechanics (1985), section 4.2 (its correction for the
!> ellipticity of the contact left out: exact for R_w = R_r). Linearised at the preload F0:
!> k_H = (3/2)*C_H^(2/3)*F0^(1/3) [N/m].
module greenconv_model_rail
    use greenconv_core_kinds, only: dp
    use greenconv_core_error, only: error_type, fatal_error
    use greenconv_core_constants, only: two_pi
    use greenconv_core_text, only: sci_text, int_text
    use greenconv_model_frf, only: frf_type
    use greenconv_model_modes_file, only: file_modes, read_file_modes
    implicit none
    private

    public :: rail_track, wheel_mass, wheel_from_modes, hertz_constant, hertz_tangent, wheel_rail_frf, band_tail

    !> An infinite rail on a continuous one- or two-layer support.
    type :: rail_track
        !> Bending stiffness EI [N m^2], > 0.
        real(dp) :: bending = 6.4e6_dp
        !> Mass per length m [kg/m], > 0.
        real(dp) :: mass = 60.0_dp
        !> Shear stiffness kappa*G*A [N]; 0: Euler-Bernoulli (no shear deformation).
        real(dp) :: shear = 0.0_dp
        !> Rotary inertia per length rho*I [kg m]; used with `shear` only.
        real(dp) :: rotary = 0.0_dp
        !> Stiffness per length of the support (one layer) or of the pad (two layers) [N/m^2], > 0.
        real(dp) :: pad_stiffness = 5.0e8_dp
        !> Viscous damping per length of the support or the pad [N s/m^2], >= 0.
        real(dp) :: pad_damping = 0.0_dp
        !> Sleeper mass per length [kg/m]; 0: one layer (no sleepers, no ballast).
        real(dp) :: sleeper_mass = 0.0_dp
        !> Ballast stiffness per length [N/m^2] (two layers), > 0.
        real(dp) :: ballast_stiffness = 0.0_dp
        !> Ballast viscous damping per length [N s/m^2] (two layers), >= 0.
        real(dp) :: ballast_damping = 0.0_dp
    contains
        !> Dynamic stiffness per length s*(omega) [N/m^2] of the support.
        procedure :: support => track_support
        !> Point receptance alpha_r(omega) [m/N] at the load.
        procedure :: receptance => track_receptance
        !> Highest resonance [Hz] of the track's masses on their springs: the rail on the
        !> support (sqrt(s/m)/(2*pi), one layer) or on the pad, and the sleepers between pad and
        !> ballast (two layers).
        procedure :: top_resonance => track_top_resonance
        !> Refuse values that make no track, naming the first.
        procedure :: check => track_check
    end type rail_track

    !> A wheel: a mass on a primary suspension to a fixed bogie, or its normal modes at the
    !> contact (`modal_frequency` allocated: the mass and suspension are then not used).
    type :: wheel_mass
        !> Unsprung mass M_w [kg], > 0.
        real(dp) :: mass = 600.0_dp
        !> Suspension stiffness k_s [N/m], > 0.
        real(dp) :: stiffness = 1.0e6_dp
        !> Suspension viscous damping c_s [N s/m], >= 0.
        real(dp) :: damping = 1.0e4_dp
        !> Natural frequencies f_k [Hz] of the wheel's modes (not allocated: the mass on its
        !> suspension).
        real(dp), allocatable :: modal_frequency(:)
        !> Modal masses m_k [kg] of the modes.
        real(dp), allocatable :: modal_mass(:)
        !> Viscous damping ratios xi_k of the modes.
        real(dp), allocatable :: modal_damping(:)
        !> Shapes phi_k at the contact node, in the direction normal to the rail (dimensionless
        !> with m_k in kg).
        real(dp), allocatable :: modal_shape(:)
    contains
        !> Receptance alpha_w(omega) [m/N] at the contact.
        procedure :: receptance => wheel_receptance
        !> Refuse values that make no wheel, naming the first.
        procedure :: check => wheel_check
    end type wheel_mass

contains

    !> s*(omega) [N/m^2]: s + i*omega*c (one layer), or the pad in series with the sleeper mass
    !> on the ballast (two layers).
    elemental complex(dp) function track_support(self, omega) result(s)
        !> The track.
        class(rail_track), intent(in) :: self
        !> Angular frequency [rad/s], >= 0.
        real(dp), intent(in) :: omega

        complex(dp) :: pad, lower

        pad = cmplx(self%pad_stiffness, omega*self%pad_damping, kind=dp)
        if (self%sleeper_mass <= 0.0_dp) then
            s = pad
            return
        end if
        lower = cmplx(self%ballast_stiffness - self%sleeper_mass*omega**2, omega*self%ballast_damping, kind=dp)
        s = pad*lower/(pad + lower)
    end function track_support

    !> alpha_r(omega) [m/N], Euler-Bernoulli in closed form, or Timoshenko by the roots of its
    !> dispersion relation in k^2 (module description).
    elemental complex(dp) function track_receptance(self, omega) result(alpha)
        !> The track.
        class(rail_track), intent(in) :: self
        !> Angular frequency [rad/s], >= 0.
        real(dp), intent(in) :: omega

        complex(dp) :: net, a4, a, c2, c1, c0, root, q(2), sq
        real(dp) :: inertia
        integer :: j

        net = self%support(omega) - self%mass*omega**2
        ! the limit Im -> 0+ on the cut (an undamped support above its cut-on)
        net = cmplx(real(net, dp), max(aimag(net), 0.0_dp), kind=dp)
        if (self%shear <= 0.0_dp) then
            a4 = net/self%bending
            a = sqrt(sqrt(a4))
            alpha = 1.0_dp/(2.0_dp*sqrt(2.0_dp)*self%bending*a**3)
            return
        end if
        inertia = self%rotary*omega**2
        c2 = cmplx(self%shear*self%bending, 0.0_dp, kind=dp)
        c1 = self%bending*net - self%shear*inertia
        c0 = net*(self%shear - inertia)
        root = sqrt(c1**2 - 4.0_dp*c2*c0)
        ! the two roots, each by the form that does not cancel
        if (real(conjg(c1)*root, dp) >= 0.0_dp) then
            q(1) = -(c1 + root)/(2.0_dp*c2)
        else
            q(1) = -(c1 - root)/(2.0_dp*c2)
        end if
        q(2) = c0/(c2*q(1))
        alpha = (0.0_dp, 0.0_dp)
        do j = 1, 2
            sq = sqrt(q(j))
            if (aimag(sq) < 0.0_dp) sq = -sq
            alpha = alpha + (self%bending*q(j) + self%shear - inertia)/(c2*(q(j) - q(3 - j)))/sq
        end do
        alpha = (0.0_dp, 0.5_dp)*alpha
    end function track_receptance

    !> Highest resonance [Hz] of the track's masses on their springs (its type description).
    elemental real(dp) function track_top_resonance(self) result(f)
        !> The track.
        class(rail_track), intent(in) :: self

        f = sqrt(self%pad_stiffness/self%mass)/two_pi
        if (self%sleeper_mass > 0.0_dp) &
            f = max(f, sqrt((self%pad_stiffness + self%ballast_stiffness)/self%sleeper_mass)/two_pi)
    end function track_top_resonance

    !> Refuse a track that is not one: EI, m, the support's stiffness > 0, dampings >= 0, a
    !> two-layer support with a ballast stiffness > 0, kappa*G*A and rho*I >= 0, all finite.
    !> The message names the first value at fault: "rail_mass: expected ..., found ...".
    pure subroutine track_check(self, error)
        !> The track.
        class(rail_track), intent(in) :: self
        !> Set for the first value at fault (status 2).
        type(error_type), allocatable, intent(out) :: error

        call positive(self%bending, 'rail_bending', 'a bending stiffness EI > 0 N m^2', error)
        if (.not. allocated(error)) call positive(self%mass, 'rail_mass', 'a mass per length > 0 kg/m', error)
        if (.not. allocated(error)) call positive(self%pad_stiffness, 'support_stiffness', &
                                                  'a stiffness per length > 0 N/m^2', error)
        if (.not. allocated(error)) call not_negative(self%pad_damping, 'support_damping', &
                                                      'a damping per length >= 0 N s/m^2', error)
        if (.not. allocated(error)) call not_negative(self%shear, 'rail_shear', &
                                                      'a shear stiffness kappa*G*A >= 0 N (0: Euler-Bernoulli)', error)
        if (.not. allocated(error)) call not_negative(self%rotary, 'rail_rotary', &
                                                      'a rotary inertia rho*I >= 0 kg m', error)
        if (.not. allocated(error)) call not_negative(self%sleeper_mass, 'sleeper_mass', &
                                                      'a mass per length >= 0 kg/m (0: one layer)', error)
        if (allocated(error) .or. self%sleeper_mass <= 0.0_dp) return
        call positive(self%ballast_stiffness, 'ballast_stiffness', &
                      'a stiffness per length > 0 N/m^2 under sleepers (sleeper_mass > 0)', error)
        if (.not. allocated(error)) call not_negative(self%ballast_damping, 'ballast_damping', &
                                                      'a damping per length >= 0 N s/m^2', error)
    end subroutine track_check

    !> alpha_w(omega) [m/N]: 1/(k_s - M_w*omega^2 + i*omega*c_s), or the sum over the wheel's
    !> modes (module description).
    elemental complex(dp) function wheel_receptance(self, omega) result(alpha)
        !> The wheel.
        class(wheel_mass), intent(in) :: self
        !> Angular frequency [rad/s].
        real(dp), intent(in) :: omega

        real(dp) :: omega_k
        integer :: k

        if (.not. allocated(self%modal_frequency)) then
            alpha = 1.0_dp/cmplx(self%stiffness - self%mass*omega**2, omega*self%damping, kind=dp)
            return
        end if
        alpha = (0.0_dp, 0.0_dp)
        do k = 1, size(self%modal_frequency)
            omega_k = two_pi*self%modal_frequency(k)
            alpha = alpha + self%modal_shape(k)**2 &
                    /(self%modal_mass(k)*cmplx(omega_k**2 - omega**2, 2.0_dp*self%modal_damping(k)*omega_k*omega, kind=dp))
        end do
    end function wheel_receptance

    !> The wheel of a universal file's normal modes (greenconv_model_modes_file's reader): its
    !> modes at the contact node `node` (0: the file's first node), the shapes in `direction`.
    !> Refused (status 2, the message starting with the variable at fault): an unreadable or
    !> malformed file (`wheel_modes_file`), a node the file does not have (`wheel_node`), a
    !> mode at 0 Hz (a wheel free of its suspension would sink under the preload), no mode
    !> that moves the node.
    subroutine wheel_from_modes(path, direction, node, damping_ratio, wheel, error)
        !> The universal file (datasets 15/2411 and 55).
        character(len=*), intent(in) :: path
        !> Direction of the shapes normal to the rail: +-1, +-2, +-3 for +-X, +-Y, +-Z.
        integer, intent(in) :: direction
        !> Label of the contact node; 0: the file's first node.
        integer, intent(in) :: node
        !> Viscous damping ratio where the file gives 0, in [0, 1).
        real(dp), intent(in) :: damping_ratio
        !> The wheel.
        type(wheel_mass), intent(out) :: wheel
        !> Set (status 2) as above.
        type(error_type), allocatable, intent(out) :: error

        type(file_modes) :: modes
        integer :: i

        call read_file_modes(path, direction, damping_ratio, modes, error)
        if (allocated(error)) then
            error%message = 'wheel_modes_file: '//error%message
            return
        end if
        i = 1
        if (node /= 0) i = findloc(modes%label, node, 1)
        if (i == 0) then
            call fatal_error(error, 'wheel_node: expected the label of a node of '//path//', found '//int_text(node))
            return
        end if
        wheel%modal_frequency = modes%frequency
        wheel%modal_mass = modes%modal_mass
        wheel%modal_damping = modes%damping_ratio
        wheel%modal_shape = modes%shape(i, :)
        if (any(wheel%modal_frequency <= 0.0_dp)) then
            call fatal_error(error, 'wheel_modes_file: expected modes of a wheel held by its suspension (every ' &
                             //'frequency > 0 Hz) in '//path//', found one at ' &
                             //sci_text(minval(wheel%modal_frequency))//' Hz')
        else if (all(wheel%modal_shape == 0.0_dp)) then
            call fatal_error(error, 'wheel_modes_file: expected a mode that moves the contact node in '//path &
                             //', found every shape 0 there')
        end if
    end subroutine wheel_from_modes

    !> Refuse a wheel that is not one: M_w > 0, k_s > 0, c_s >= 0, all finite (a wheel of
    !> modes was checked when it was read).
    pure subroutine wheel_check(self, error)
        !> The wheel.
        class(wheel_mass), intent(in) :: self
        !> Set for the first value at fault (status 2).
        type(error_type), allocatable, intent(out) :: error

        if (allocated(self%modal_frequency)) return
        call positive(self%mass, 'wheel_mass', 'a mass > 0 kg', error)
        if (.not. allocated(error)) call positive(self%stiffness, 'suspension_stiffness', &
                                                  'a stiffness > 0 N/m', error)
        if (.not. allocated(error)) call not_negative(self%damping, 'suspension_damping', &
                                                      'a damping >= 0 N s/m', error)
    end subroutine wheel_check

    !> The receptance the contact sees, alpha_w + alpha_r [m/N], on the lines `frequency` (for
    !> an identification, greenconv_model_frf's uniform grid from 0 Hz, `frf_grid`).
    pure function wheel_rail_frf(track, wheel, frequency) result(frf)
        !> The track.
        type(rail_track), intent(in) :: track
        !> The wheel.
        type(wheel_mass), intent(in) :: wheel
        !> The lines [Hz], >= 0.
        real(dp), intent(in) :: frequency(:)
        type(frf_type) :: frf

        frf%frequency = frequency
        frf%receptance = wheel%receptance(two_pi*frequency) + track%receptance(two_pi*frequency)
        frf%source = 'wheel on rail, closed form'
    end function wheel_rail_frf

    !> int_{f_from}^inf |alpha_w + alpha_r| df [m/(N s)]: what a receptance sampled up to f_from
    !> leaves out, bounding the change of each sample of g. Trapezoidal rule on 400 log-spaced
    !> points to 1000*f_from, then 2*F*|G(F)| for the rest (|G| falls at least as f^(-3/2)).
    pure real(dp) function band_tail(track, wheel, f_from) result(tail)
        !> The track.
        type(rail_track), intent(in) :: track
        !> The wheel.
        type(wheel_mass), intent(in) :: wheel
        !> Lower end [Hz], > 0.
        real(dp), intent(in) :: f_from

        integer, parameter :: n = 400
        real(dp) :: f(0:n), magnitude(0:n)
        integer :: k

        f(:) = [(f_from*1000.0_dp**(real(k, dp)/n), k=0, n)]
        magnitude(:) = abs(wheel%receptance(two_pi*f) + track%receptance(two_pi*f))
        tail = 0.5_dp*sum((magnitude(1:) + magnitude(:n - 1))*(f(1:) - f(:n - 1))) + 2.0_dp*magnitude(n)*f(n)
    end function band_tail

    !> Hertz's constant C_H [N/m^1.5] of a wheel (rolling radius R_w) on a rail head
    !> (transverse radius R_r) of one material: (4/3)*E/(2*(1 - nu^2))*sqrt(sqrt(R_w*R_r))
    !> (module description).
    elemental real(dp) function hertz_constant(wheel_radius, rail_radius, young, poisson) result(c)
        !> Rolling radius of the wheel R_w [m], > 0.
        real(dp), intent(in) :: wheel_radius
        !> Transverse radius of the rail head R_r [m], > 0.
        real(dp), intent(in) :: rail_radius
        !> Young's modulus E [Pa], > 0.
        real(dp), intent(in) :: young
        !> Poisson's ratio nu, in [0, 0.5).
        real(dp), intent(in) :: poisson

        c = 4.0_dp/3.0_dp*young/(2.0_dp*(1.0_dp - poisson**2))*sqrt(sqrt(wheel_radius*rail_radius))
    end function hertz_constant

    !> Tangent stiffness k_H = p*C*delta0^(p-1) [N/m] of the law F = C*delta^p at the preload
    !> F0 = C*delta0^p: (3/2)*C^(2/3)*F0^(1/3) for Hertz (p = 3/2).
    elemental real(dp) function hertz_tangent(stiffness, exponent, preload) result(k)
        !> C [N/m^p], > 0.
        real(dp), intent(in) :: stiffness
        !> p, > 0.
        real(dp), intent(in) :: exponent
        !> F0 [N], > 0.
        real(dp), intent(in) :: preload

        k = exponent*stiffness**(1.0_dp/exponent)*preload**(1.0_dp - 1.0_dp/exponent)
    end function hertz_tangent

    !> Set `error` unless 0 < value < huge.
    pure subroutine positive(value, name, what, error)
        real(dp), intent(in) :: value
        character(len=*), intent(in) :: name, what
        type(error_type), allocatable, intent(inout) :: error

        if (value > 0.0_dp .and. value < huge(value)) return
        call fatal_error(error, name//': expected '//what//', found '//sci_text(value))
    end subroutine positive

    !> Set `error` unless 0 <= value < huge.
    pure subroutine not_negative(value, name, what, error)
        real(dp), intent(in) :: value
        character(len=*), intent(in) :: name, what
        type(error_type), allocatable, intent(inout) :: error

        if (value >= 0.0_dp .and. value < huge(value)) return
        call fatal_error(error, name//': expected '//what//', found '//sci_text(value))
    end subroutine not_negative

end module greenconv_model_rail
