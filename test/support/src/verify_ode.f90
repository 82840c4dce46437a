!> The independent reference integrator of the tests and the benchmark: the embedded
!> Runge-Kutta pair of Dormand and Prince, order 5(4) (J. Comput. Appl. Math. 6, 1980), with
!> adaptive steps, for small systems y' = f(t, y). It shares nothing with the convolution
!> code it checks: an `ode_system` extension holds a structure's state-space equations, and
!> `integrate` solves them at a tight tolerance; verify_contact_mod does so for a modal
!> structure in contact with a road. The tests and the benchmark (bench/) measure every
!> convolution method against it.
module verify_ode_mod
    use greenconv_core_kinds, only: dp
    implicit none
    private

    public :: ode_system, integrate

    !> A system y' = f(t, y): extend it with the data the right-hand side needs.
    type, abstract :: ode_system
    contains
        !> Right-hand side f(t, y).
        procedure(rhs_interface), deferred :: rhs
    end type ode_system

    abstract interface
        !> Right-hand side f(t, y).
        subroutine rhs_interface(self, t, y, dydt)
            import :: ode_system, dp
            implicit none
            !> The system.
            class(ode_system), intent(in) :: self
            !> Time [s].
            real(dp), intent(in) :: t
            !> State.
            real(dp), intent(in) :: y(:)
            !> Its time derivative.
            real(dp), intent(out) :: dydt(:)
        end subroutine rhs_interface
    end interface

    ! Butcher tableau of the Dormand-Prince pair (the 5th-order row is the 7th stage).
    real(dp), parameter :: c2 = 1.0_dp/5, c3 = 3.0_dp/10, c4 = 4.0_dp/5, c5 = 8.0_dp/9
    real(dp), parameter :: a21 = 1.0_dp/5
    real(dp), parameter :: a31 = 3.0_dp/40, a32 = 9.0_dp/40
    real(dp), parameter :: a41 = 44.0_dp/45, a42 = -56.0_dp/15, a43 = 32.0_dp/9
    real(dp), parameter :: a51 = 19372.0_dp/6561, a52 = -25360.0_dp/2187, a53 = 64448.0_dp/6561, &
                           a54 = -212.0_dp/729
    real(dp), parameter :: a61 = 9017.0_dp/3168, a62 = -355.0_dp/33, a63 = 46732.0_dp/5247, &
                           a64 = 49.0_dp/176, a65 = -5103.0_dp/18656
    real(dp), parameter :: b1 = 35.0_dp/384, b3 = 500.0_dp/1113, b4 = 125.0_dp/192, &
                           b5 = -2187.0_dp/6784, b6 = 11.0_dp/84
    ! Differences between the 5th- and 4th-order weights: the local error estimate.
    real(dp), parameter :: e1 = 71.0_dp/57600, e3 = -71.0_dp/16695, e4 = 71.0_dp/1920, &
                           e5 = -17253.0_dp/339200, e6 = 22.0_dp/525, e7 = -1.0_dp/40

contains

    !> Advance y from t0 to t1 with adaptive steps, each component's local error kept
    !> below atol(i) + rtol*|y(i)|. `h` is the first trial step and returns the last one.
    subroutine integrate(f, t0, t1, y, rtol, atol, h)
        !> The system y' = f(t, y).
        class(ode_system), intent(in) :: f
        !> Start and end of the interval [s].
        real(dp), intent(in) :: t0, t1
        !> State at t0 on entry, at t1 on return.
        real(dp), intent(inout) :: y(:)
        !> Relative tolerance of the local error.
        real(dp), intent(in) :: rtol
        !> Absolute tolerance of the local error, per component.
        real(dp), intent(in) :: atol(:)
        !> First trial step [s] on entry, the last accepted step on return.
        real(dp), intent(inout) :: h

        real(dp), dimension(size(y)) :: k1, k2, k3, k4, k5, k6, k7, y_new, scale
        real(dp) :: t, step, err
        logical :: last

        t = t0
        do
            last = t + h >= t1
            step = merge(t1 - t, h, last)
            call f%rhs(t, y, k1)
            call f%rhs(t + c2*step, y + step*a21*k1, k2)
            call f%rhs(t + c3*step, y + step*(a31*k1 + a32*k2), k3)
            call f%rhs(t + c4*step, y + step*(a41*k1 + a42*k2 + a43*k3), k4)
            call f%rhs(t + c5*step, y + step*(a51*k1 + a52*k2 + a53*k3 + a54*k4), k5)
            call f%rhs(t + step, y + step*(a61*k1 + a62*k2 + a63*k3 + a64*k4 + a65*k5), k6)
            y_new = y + step*(b1*k1 + b3*k3 + b4*k4 + b5*k5 + b6*k6)
            call f%rhs(t + step, y_new, k7)
            scale = atol + rtol*max(abs(y), abs(y_new))
            err = sqrt(sum((step*(e1*k1 + e3*k3 + e4*k4 + e5*k5 + e6*k6 + e7*k7)/scale)**2)/size(y))
            if (err <= 1.0_dp) then
                t = t + step
                y = y_new
                if (last) then
                    if (err > 0.0_dp) h = step*min(5.0_dp, max(0.2_dp, 0.9_dp*err**(-0.2_dp)))
                    return
                end if
            end if
            h = step*min(5.0_dp, max(0.2_dp, 0.9_dp*max(err, 1.0e-10_dp)**(-0.2_dp)))
        end do
    end subroutine integrate

end module verify_ode_mod
