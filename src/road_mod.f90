!> Road profiles seen by a body travelling at constant speed, as heights over time.
module road_mod
    use kinds_mod, only: dp
    implicit none
    private

    public :: road_profile, sine_road

    !> A road height u_r(t) [m] under the contact point at time t [s].
    type, abstract :: road_profile
    contains
        !> Road height [m] at time t [s].
        procedure(height_interface), deferred :: height
        !> Road heights [m] at t_n = n*dt, n = 0..n_steps-1.
        procedure :: sample
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

contains

    !> Road heights [m] at t_n = n*dt, n = 0..n_steps-1.
    function sample(self, dt, n_steps) result(heights)
        !> The road.
        class(road_profile), intent(in) :: self
        !> Time step [s].
        real(dp), intent(in) :: dt
        !> Number of samples.
        integer, intent(in) :: n_steps
        real(dp), allocatable :: heights(:)

        integer :: n

        heights = self%height([(n*dt, n=0, n_steps - 1)])
    end function sample

    !> A0*sin(omega_r*t).
    elemental real(dp) function sine_height(self, t)
        class(sine_road), intent(in) :: self
        real(dp), intent(in) :: t

        sine_height = self%amplitude*sin(self%omega*t)
    end function sine_height

end module road_mod
