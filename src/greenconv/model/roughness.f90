!> A rail's roughness as the railway gives it: a 1/3-octave band spectrum of wavelength, levels
!> L_b in dB re 1 um (EN 15610, ISO 3095), made into a profile of random phases and run over at
!> the train speed V:
!>
!>     r(t) = sum_j a_j*H(k_j)*cos(k_j*(x0 + V*t) + phi_j),
!>
!> each band b (edges lambda_b*10^(+-1/20)) carrying `terms_per_band` cosines of wavenumbers
!> k_j spread evenly in wavenumber across the band and equal amplitudes a_j, so that the band's
!> mean square sum_j a_j^2/2 is (1 um*10^(L_b/20))^2; the phases phi_j drawn uniformly in
!> [0, 2*pi) from a seed (SplitMix64, greenconv_core_random). H is the optional contact
!> filter: the roughness averaged over a contact patch of length 2a, sin(k*a)/(k*a) (1 without).
!>
!> `iso3095_limit` is the limit curve of ISO 3095:2013 (Figure 2; the "2007 TSI limit" of
!> EN 15610:2009), 22 bands from 40 cm to 3.15 mm.
module greenconv_model_roughness
    use greenconv_core_kinds, only: dp
    use greenconv_core_constants, only: two_pi
    use greenconv_core_random, only: random_stream
    use greenconv_model_road, only: road_profile
    implicit none
    private

    public :: roughness_road, new_roughness_road, iso3095_wavelengths, iso3095_levels

    !> Band centres [m] of the ISO 3095 limit, 40 cm to 3.15 mm (nominal).
    real(dp), parameter :: iso3095_wavelengths(22) = [0.4_dp, 0.315_dp, 0.25_dp, 0.2_dp, 0.16_dp, 0.125_dp, 0.1_dp, &
        0.08_dp, 0.063_dp, 0.05_dp, 0.04_dp, 0.0315_dp, 0.025_dp, 0.02_dp, 0.016_dp, 0.0125_dp, 0.01_dp, 0.008_dp, &
        0.0063_dp, 0.005_dp, 0.004_dp, 0.00315_dp]
    !> Levels [dB re 1 um] of the ISO 3095 limit at those wavelengths.
    real(dp), parameter :: iso3095_levels(22) = [17.1_dp, 15.0_dp, 13.0_dp, 11.0_dp, 9.0_dp, 7.0_dp, 4.9_dp, 2.9_dp, &
        0.9_dp, -1.1_dp, -3.2_dp, -5.0_dp, -5.6_dp, -6.2_dp, -6.8_dp, -7.4_dp, -8.0_dp, -8.6_dp, -9.2_dp, -9.8_dp, &
        -10.4_dp, -11.0_dp]

    !> A roughness profile from a band spectrum, run over at a speed.
    type, extends(road_profile) :: roughness_road
        !> Amplitudes a_j*H(k_j) [m].
        real(dp), allocatable :: amplitude(:)
        !> Wavenumbers k_j [rad/m].
        real(dp), allocatable :: wavenumber(:)
        !> Phases phi_j [rad].
        real(dp), allocatable :: phase(:)
        !> Speed V [m/s].
        real(dp) :: speed = 27.8_dp
        !> Position x0 [m] at t = 0.
        real(dp) :: x_start = 0.0_dp
    contains
        !> r(t) [m] (module description).
        procedure :: height => roughness_height
    end type roughness_road

contains

    !> The profile of a band spectrum (module description).
    function new_roughness_road(wavelength, level, seed, speed, x_start, contact_length, terms_per_band) result(road)
        !> Band centre wavelengths [m], > 0 (nominal or exact; the band is the 1/3 octave around it).
        real(dp), intent(in) :: wavelength(:)
        !> Band levels [dB re 1 um], one per wavelength.
        real(dp), intent(in) :: level(:)
        !> Seed of the phases.
        integer, intent(in) :: seed
        !> Speed V [m/s].
        real(dp), intent(in) :: speed
        !> Position x0 [m] at t = 0.
        real(dp), intent(in) :: x_start
        !> Length 2a [m] of the contact patch of the filter; 0: no filter.
        real(dp), intent(in) :: contact_length
        !> Cosines per band, >= 1.
        integer, intent(in) :: terms_per_band
        type(roughness_road) :: road

        type(random_stream) :: stream
        real(dp) :: k_low, k_high, rms, ka
        integer :: b, j, n

        n = size(wavelength)*terms_per_band
        allocate (road%amplitude(n), road%wavenumber(n), road%phase(n))
        stream = random_stream(seed)
        do b = 1, size(wavelength)
            rms = 1.0e-6_dp*10.0_dp**(level(b)/20.0_dp)
            k_low = two_pi/(wavelength(b)*10.0_dp**0.05_dp)
            k_high = two_pi/(wavelength(b)*10.0_dp**(-0.05_dp))
            do j = 1, terms_per_band
                associate (i => (b - 1)*terms_per_band + j)
                    road%wavenumber(i) = k_low + (j - 0.5_dp)*(k_high - k_low)/terms_per_band
                    road%amplitude(i) = rms*sqrt(2.0_dp/terms_per_band)
                    if (contact_length > 0.0_dp) then
                        ka = 0.5_dp*contact_length*road%wavenumber(i)
                        road%amplitude(i) = road%amplitude(i)*abs(sin(ka)/ka)
                    end if
                    road%phase(i) = two_pi*stream%uniform()
                end associate
            end do
        end do
        road%speed = speed
        road%x_start = x_start
    end function new_roughness_road

    !> r(t) [m] (module description).
    elemental real(dp) function roughness_height(self, t) result(height)
        !> The profile.
        class(roughness_road), intent(in) :: self
        !> Time [s].
        real(dp), intent(in) :: t

        height = sum(self%amplitude*cos(self%wavenumber*(self%x_start + self%speed*t) + self%phase))
    end function roughness_height

end module greenconv_model_roughness
