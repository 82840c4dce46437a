!> Road profiles seen by a body travelling at constant speed, as heights over time.
module greenconv_model_road
    use, intrinsic :: iso_fortran_env, only: int64
    use greenconv_core_kinds, only: dp
    use greenconv_core_random, only: random_stream
    implicit none
    private

    public :: road_profile, sine_road, random_road, new_random_road

    !> pi
    real(dp), parameter :: pi = acos(-1.0_dp)

    !> A road height u_r(t) [m] under the contact point at time t [s].
    type, abstract :: road_profile
    contains
        !> Road height [m] at time t [s].
        procedure(height_interface), deferred :: height
        !> Road heights [m] at t_n = n*dt, n = 0..n_steps-1.
        procedure :: sample
        !> Road heights [m] at t_n = n*dt for the steps n = first..first+count-1 of a run, for
        !> a run streamed in blocks (the whole run is never sampled).
        procedure :: sample_steps
    end type road_profile

    abstract interface
        !> Road height [m] at time t [s].
        elemental real(dp) function height_interface(self, t)
            import :: road_profile, dp
            implicit none
            class(road_profile), intent(in) :: self
            real(dp), intent(in) :: t
        end function height_interface
    end interface

    !> The sinusoidal road of eq. (25): u_r(t) = A0*sin(omega_r*t).
    type, extends(road_profile) :: sine_road
        !> Amplitude A0 [m].
        real(dp) :: amplitude = 1.0e-3_dp
        !> Angular frequency omega_r = 2*pi*V0/lambda_r [rad/s].
        real(dp) :: omega = 100.0_dp
    contains
        procedure :: height => sine_height
    end type sine_road

    !> The pseudo-random road of eq. (35), travelled at constant speed V:
    !> u_r(x) = A0*sum_k phi_k*sin(psi_k*2*pi*x/lambda_r), x = V*t, with phi_k, psi_k in (0, 1).
    !>
    !> The paper prints phi_k twice (as weight and as wavenumber factor) and calls them two
    !> random parameters; greenconv reads them as two draws, phi_k weighting the amplitude and
    !> psi_k scaling the wavenumber, so every wavelength is at least lambda_r.
    type, extends(road_profile) :: random_road
        !> Amplitude A0 [m].
        real(dp) :: amplitude = 5.0e-3_dp
        !> Base wavelength lambda_r [m].
        real(dp) :: wavelength = 50.0e-3_dp
        !> Travel speed V [m/s].
        real(dp) :: speed = 1.0_dp
        !> Amplitude weights phi_k in (0, 1).
        real(dp), allocatable :: weight(:)
        !> Wavenumber factors psi_k in (0, 1).
        real(dp), allocatable :: wavenumber_factor(:)
    contains
        procedure :: height => random_height
    end type random_road

contains

    !> The road of eq. (35) with n_terms pairs (phi_k, psi_k) drawn from `seed`
    !> (SplitMix64, the same on every compiler): phi_1, psi_1, phi_2, psi_2, ...
    function new_random_road(seed, n_terms, amplitude, wavelength, speed) result(road)
        !> Seed of the draws.
        integer, intent(in) :: seed
        !> Number of terms (10 in the paper).
        integer, intent(in) :: n_terms
        !> Amplitude A0 [m].
        real(dp), intent(in) :: amplitude
        !> Base wavelength lambda_r [m].
        real(dp), intent(in) :: wavelength
        !> Travel speed V [m/s].
        real(dp), intent(in) :: speed
        type(random_road) :: road

        type(random_stream) :: stream
        integer :: k

        stream = random_stream(seed)
        allocate (road%weight(n_terms), road%wavenumber_factor(n_terms))
        do k = 1, n_terms
            road%weight(k) = stream%uniform()
            road%wavenumber_factor(k) = stream%uniform()
        end do
        road%amplitude = amplitude
        road%wavelength = wavelength
        road%speed = speed
    end function new_random_road

    !> Road heights [m] at t_n = n*dt, n = 0..n_steps-1.
    function sample(self, dt, n_steps) result(heights)
        !> The road.
        class(road_profile), intent(in) :: self
        !> Time step [s].
        real(dp), intent(in) :: dt
        !> Number of samples.
        integer, intent(in) :: n_steps
        real(dp), allocatable :: heights(:)

        heights = self%sample_steps(dt, 0_int64, n_steps)
    end function sample

    !> Road heights [m] at t_n = n*dt, n = first..first+count-1; t_n is computed as in a
    !> whole run's `sample`, so the blocks of a run put together equal it bit for bit.
    function sample_steps(self, dt, first, count) result(heights)
        !> The road.
        class(road_profile), intent(in) :: self
        !> Time step [s].
        real(dp), intent(in) :: dt
        !> Index of the first step.
        integer(int64), intent(in) :: first
        !> Number of samples.
        integer, intent(in) :: count
        real(dp), allocatable :: heights(:)

        integer :: j

        heights = self%height([((first + j)*dt, j=0, count - 1)])
    end function sample_steps

    !> A0*sin(omega_r*t).
    elemental real(dp) function sine_height(self, t)
        class(sine_road), intent(in) :: self
        real(dp), intent(in) :: t

        sine_height = self%amplitude*sin(self%omega*t)
    end function sine_height

    !> A0*sum_k phi_k*sin(psi_k*2*pi*V*t/lambda_r).
    elemental real(dp) function random_height(self, t)
        class(random_road), intent(in) :: self
        real(dp), intent(in) :: t

        random_height = self%amplitude*sum(self%weight*sin(self%wavenumber_factor*2.0_dp*pi*self%speed*t &
                                                            /self%wavelength))
    end function random_height

end module greenconv_model_road
