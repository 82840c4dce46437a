!> Convolution by modal decomposition with decaying recursions: `recursive`, `exact` and
!> `backward`.
!>
!> Both engines keep one complex state per mode (pole lambda_k, residue r_k, see
!> greenconv_model_modal_set) and advance it by the factor z_k = exp(lambda_k*dt), of modulus below 1
!> for a damped mode, so that nothing grows and the run length is unlimited. Each state
!> holds 2*r_k times the mode's share of the history, so that
!>
!>     u_h(n) = sum_k Re(p_k(n)),     p_k(n + 1) = z_k*p_k(n) + c_k*q(t_n),
!>     u(t_n) = u_h(n) + w0*q(t_n),
!>
!> and the kernel of the causal convolution of eq. (20) is w_0 = w0, w_j = Re(c_k*z_k^(j-1))
!> summed over the modes. z_k and c_k are computed once, at construction: the step costs
!> four multiplications and four additions per mode, with no exponential or trigonometric
!> call. Real and imaginary parts sit in separate arrays so the loop vectorises.
!>
!> `recursive` is the paper's scheme, eqs. (15)-(17), rewritten without the growth factors
!> exp(+xi_k*omega_k*t): the same rectangle rule, so the same numbers up to round-off,
!>
!>     c_k = 2*r_k*dt*z_k,   w0 = 0,   w_j = dt*g(t_j)                       (eq. 20).
!>
!> `exact` takes the force piecewise linear between the samples q(t_n) (first-order hold,
!> q = 0 before step 0) and integrates each mode's exponential exactly over the step. With
!> x = lambda_k*dt,
!>
!>     phi1(x) = (exp(x) - 1)/x,   phi2(x) = (exp(x) - 1 - x)/x^2,
!>
!> the continuous state s_k(t) = r_k*int exp(lambda_k*(t - tau))*q(tau) dtau obeys
!>
!>     s_k(t_{n+1}) = z_k*s_k(t_n) + r_k*dt*[(phi1 - phi2)*q(t_n) + phi2*q(t_{n+1})],
!>
!> the step of Nigam and Jennings (1969) for one complex mode. q(t_n) reaches u(t_n) with
!> the weight r_k*dt*phi2 (the instantaneous term); the part of s_k without it is
!> p_k/2, and z_k*phi2 + (phi1 - phi2) = phi1^2, so
!>
!>     c_k = 2*r_k*dt*phi1(x)^2,   w0 = sum_k 2*Re(r_k*dt*phi2(x)),
!>     w_j = int g(t_j - tau)*hat(tau/dt) dtau,   hat(v) = max(0, 1 - |v|):
!>
!> the kernel is g averaged against the hat function of the linear interpolation, which
!> makes the scheme second-order accurate in dt for a smooth force. A load switched on at
!> t = 0 should be given its mean value at t = 0 (F/2 for a step), as with the rectangle
!> rule; a load that starts from zero (the contact loop from equilibrium) needs nothing.
!> For |x| < 1, phi1 and phi2 are summed from their Taylor series, which avoids the
!> cancellation of exp(x) - 1 - x at small dt.
!>
!> `backward` holds the force constant over the step that ends at its sample: q(t) = q_m
!> for t_{m-1} < t <= t_m (a backward zero-order hold, q = 0 before step 0). Then (our own
!> derivation)
!>
!>     u(t_n) = sum_{m<=n} q_m*a_{n-m},   a_j = int_{j*dt}^{(j+1)*dt} g(s) ds
!>            = sum_k 2*Re(r_k*z_k^j*(z_k - 1)/lambda_k) = sum_k 2*Re(r_k*dt*phi1(x)*z_k^j).
!>
!> The instantaneous weight is a_0, and the rest of the sum is carried by the states: after
!> the pushes of q_0..q_{n-1}, p_k(n) = sum_{m<n} z_k^(n-1-m)*c_k*q_m, which equals the
!> share 2*r_k*dt*phi1*sum_{m<n} z_k^(n-m)*q_m of mode k when
!>
!>     c_k = 2*r_k*dt*phi1(x)*z_k,   w0 = a_0 = sum_k 2*Re(r_k*dt*phi1(x)),
!>
!> with (z_k - 1)/lambda_k = dt*phi1(x) taken from hold_functions (no cancellation at small
!> dt). The kernel w_j = a_j is g averaged over the step [t_j, t_{j+1}]: first order in dt,
!> but sum_j a_j = int_0^inf g = G(0) exactly (the static gain), and a_0 ~ dt^2/(2*M) > 0
!> for a structure that starts like a mass. In the implicit contact step the spring sees
!> u(t_n) = u_h + a_0*F(t_n) with the whole of the step's impulse on the current force,
!> which is backward Euler on the contact: dissipative at any omega_c*dt.
!>
!> A state that decays with no force passes through subnormal numbers for a few hundred
!> steps before it becomes zero; this is correct and only slow on some processors.
module greenconv_conv_recursive
    use greenconv_core_kinds, only: dp
    use greenconv_conv_convolver, only: convolver
    use greenconv_model_modal_set, only: modal_set
    use greenconv_conv_methods, only: scheme_rectangle, scheme_first_order, scheme_backward
    implicit none
    private

    public :: recursive_convolver, new_recursive_convolver, new_exact_convolver, new_backward_convolver
    public :: new_modal_engine
    public :: hold_functions

    !> A decaying modal recursion: `recursive` (rectangle rule), `exact` (first-order hold)
    !> or `backward` (backward zero-order hold).
    type, extends(convolver) :: recursive_convolver
        !> Real part of the decay factors z_k = exp(lambda_k*dt) (dimensionless).
        real(dp), allocatable :: decay_re(:)
        !> Imaginary part of the decay factors z_k.
        real(dp), allocatable :: decay_im(:)
        !> Real part of the input coefficients c_k [m/N].
        real(dp), allocatable :: input_re(:)
        !> Imaginary part of the input coefficients c_k [m/N].
        real(dp), allocatable :: input_im(:)
        !> Real part of the states p_k [m]; their sum is u_h(n).
        real(dp), allocatable :: state_re(:)
        !> Imaginary part of the states p_k [m].
        real(dp), allocatable :: state_im(:)
        !> Share of each mode in w0 [m/N] (zero for the rectangle rule); their sum is w0. The
        !> multi-point engine (greenconv_conv_green_modal) weighs them with the mode shapes.
        real(dp), allocatable :: mode_weight(:)
    contains
        procedure :: history => recursive_history
        procedure :: push => recursive_push
        procedure :: clear => recursive_clear
    end type recursive_convolver

    !> Terms kept in the Taylor series of phi1 and phi2 for |x| < 1 (error below 1/21!).
    integer, parameter :: series_terms = 20

contains

    !> The paper's convolution, eqs. (15)-(17), as a decaying recursion named `recursive`:
    !> the same numbers as `new_paper_convolver` without its overflow.
    function new_recursive_convolver(modes, dt) result(conv)
        !> The Green's function as modes (Re lambda_k <= 0), summed by the rectangle rule.
        type(modal_set), intent(in) :: modes
        !> Time step [s]: the kernel is w_j = dt*g(t_j) [m/N] and w0 = 0.
        real(dp), intent(in) :: dt
        !> The convolver, at step 0.
        type(recursive_convolver) :: conv

        conv = new_modal_engine(scheme_rectangle, modes, dt)
    end function new_recursive_convolver

    !> The first-order-hold convolution named `exact`: the force linear within each step,
    !> integrated exactly against each mode; w0 = sum_k 2*Re(r_k*dt*phi2(lambda_k*dt)).
    function new_exact_convolver(modes, dt) result(conv)
        !> The Green's function as modes (Re lambda_k <= 0), each integrated exactly over a step.
        type(modal_set), intent(in) :: modes
        !> Time step [s]; the error is of second order in it for a smooth force.
        real(dp), intent(in) :: dt
        !> The convolver, at step 0; its w0 [m/N] is the weight of phi2.
        type(recursive_convolver) :: conv

        conv = new_modal_engine(scheme_first_order, modes, dt)
    end function new_exact_convolver

    !> The backward-zero-order-hold convolution named `backward`: the force constant over the
    !> step that ends at its sample; w0 = a_0 = sum_k 2*Re(r_k*dt*phi1(lambda_k*dt)) [m/N],
    !> c_k = 2*r_k*dt*phi1*z_k. First order in dt, static gain exact.
    function new_backward_convolver(modes, dt) result(conv)
        !> The Green's function as modes (Re lambda_k <= 0); their static gain is kept exactly.
        type(modal_set), intent(in) :: modes
        !> Time step [s]; the error is of first order in it.
        real(dp), intent(in) :: dt
        !> The convolver, at step 0; its w0 = a_0 [m/N].
        type(recursive_convolver) :: conv

        conv = new_modal_engine(scheme_backward, modes, dt)
    end function new_backward_convolver

    !> The decaying recursion of a scheme of the registry (greenconv_conv_methods's
    !> `method_scheme`): `scheme_rectangle` (`recursive`: c_k = 2*r_k*dt*z_k, w0 = 0),
    !> `scheme_first_order` (`exact`: c_k = 2*r_k*dt*phi1^2, w0_k = 2*Re(r_k*dt*phi2)) or
    !> `scheme_backward` (`backward`: c_k = 2*r_k*dt*phi1*z_k, w0_k = 2*Re(r_k*dt*phi1)), with
    !> z_k = exp(lambda_k*dt) and phi1, phi2 of lambda_k*dt (`hold_functions`). The one place
    !> these three are told apart, for single- and multi-point contact alike; any other scheme
    !> gives the rectangle rule.
    function new_modal_engine(scheme, modes, dt) result(conv)
        !> The scheme.
        integer, intent(in) :: scheme
        !> The Green's function as modes (Re lambda_k <= 0).
        type(modal_set), intent(in) :: modes
        !> Time step [s].
        real(dp), intent(in) :: dt
        type(recursive_convolver) :: conv

        complex(dp), dimension(modes%n_modes()) :: z, phi1, phi2, none

        z = exp(modes%pole*dt)
        select case (scheme)
        case (scheme_first_order)
            call hold_functions(modes%pole*dt, phi1, phi2)
            call set_up(conv, 'exact', dt, z, 2.0_dp*modes%residue*dt*phi1**2, modes%residue*dt*phi2)
        case (scheme_backward)
            call hold_functions(modes%pole*dt, phi1, phi2)
            call set_up(conv, 'backward', dt, z, 2.0_dp*modes%residue*dt*phi1*z, modes%residue*dt*phi1)
        case default
            none(:) = (0.0_dp, 0.0_dp)
            call set_up(conv, 'recursive', dt, z, 2.0_dp*modes%residue*dt*z, none)
        end select
    end function new_modal_engine

    !> phi1(x) = (exp(x) - 1)/x and phi2(x) = (exp(x) - 1 - x)/x^2 (1 and 1/2 at x = 0),
    !> from their Taylor series when |x| < 1 and in closed form otherwise.
    elemental subroutine hold_functions(x, phi1, phi2)
        !> Argument x = lambda*dt (dimensionless).
        complex(dp), intent(in) :: x
        !> phi1(x) = int_0^1 exp(x*(1 - v)) dv.
        complex(dp), intent(out) :: phi1
        !> phi2(x) = int_0^1 exp(x*(1 - v))*v dv.
        complex(dp), intent(out) :: phi2

        real(dp) :: factorial
        integer :: k

        if (abs(x) < 1.0_dp) then
            ! Horner on sum_k x^k/(k + 1)! and sum_k x^k/(k + 2)!, highest term first.
            factorial = 1.0_dp
            do k = 2, series_terms + 2
                factorial = factorial*k
            end do
            phi2 = 1.0_dp/factorial
            phi1 = (series_terms + 2)/factorial
            do k = series_terms - 1, 0, -1
                factorial = factorial/(k + 3)
                phi2 = phi2*x + 1.0_dp/factorial
                phi1 = phi1*x + (k + 2)/factorial
            end do
        else
            phi1 = (exp(x) - 1.0_dp)/x
            phi2 = (phi1 - 1.0_dp)/x
        end if
    end subroutine hold_functions

    !> Fill a convolver from its decay factors z_k, input coefficients c_k and the halves
    !> v_k of each mode's share in w0, 2*Re(v_k) [m/N] (w0 = sum_k 2*Re(v_k)).
    subroutine set_up(conv, name, dt, z, c, v)
        type(recursive_convolver), intent(inout) :: conv
        character(len=*), intent(in) :: name
        real(dp), intent(in) :: dt
        complex(dp), intent(in) :: z(:), c(:), v(:)

        call conv%set_model(name, dt, size(z), 'N_m')
        conv%weight0 = 2.0_dp*sum(real(v, kind=dp))
        conv%mode_weight = 2.0_dp*real(v, kind=dp)
        conv%decay_re = real(z, kind=dp)
        conv%decay_im = aimag(z)
        conv%input_re = real(c, kind=dp)
        conv%input_im = aimag(c)
        allocate (conv%state_re(size(z)), conv%state_im(size(z)))
        call conv%reset()
    end subroutine set_up

    !> History displacement u_h(n) = sum_k Re p_k(n) [m].
    function recursive_history(self) result(u)
        class(recursive_convolver), intent(in) :: self
        real(dp) :: u

        u = sum(self%state_re)
    end function recursive_history

    !> p_k <- z_k*p_k + c_k*q(t_n), then advance to the next step.
    subroutine recursive_push(self, force)
        class(recursive_convolver), intent(inout) :: self
        real(dp), intent(in) :: force

        real(dp) :: re, im
        integer :: k

        do k = 1, size(self%state_re)
            re = self%state_re(k)
            im = self%state_im(k)
            self%state_re(k) = self%decay_re(k)*re - self%decay_im(k)*im + self%input_re(k)*force
            self%state_im(k) = self%decay_re(k)*im + self%decay_im(k)*re + self%input_im(k)*force
        end do
        self%step = self%step + 1
    end subroutine recursive_push

    !> Clear the states.
    subroutine recursive_clear(self)
        class(recursive_convolver), intent(inout) :: self

        self%state_re = 0.0_dp
        self%state_im = 0.0_dp
    end subroutine recursive_clear

end module greenconv_conv_recursive
