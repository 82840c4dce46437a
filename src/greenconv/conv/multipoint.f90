!> The Green's matrix of a structure touched at N_c points, and the seam between the
!> multi-point contact loop and its convolution methods.
!>
!> With forces q_j(t) [N] at the points j = 1..N_c, the displacement at point i is
!>
!>     u_i(t) = sum_j int_0^t g_ij(t - tau)*q_j(tau) dtau,
!>
!> g_ij(t) [m/(N*s)] being the displacement at i per unit impulse at j. Sampled at
!> t_n = n*dt it becomes the matrix form of the causal convolution of eq. (20):
!>
!>     u(t_n) = u_h(n) + W0*q(t_n),   u_h(n) = sum_{m < n} W(n - m)*q(t_m),
!>
!> W(m) being N_c x N_c matrices [m/N]. A `multipoint_convolver` is stepped like the
!> single-point `convolver`: `history(u_h)` gives u_h(n) at every point, the loop decides the
!> forces of the step and hands them over with `push(q)`. W0 (`weight0`) is the instant
!> compliance matrix of the current step's forces, zero in the paper's explicit scheme.
!>
!> The first push after a reset, q(t_0), is recorded at half weight (`recorded_load`): the
!> weights W(m) ~ dt*g(t_m) are the trapezoidal rule of the convolution integral, whose end
!> sample at tau = 0 carries half a weight. A contact run starts at rest with loads switched
!> on at t = 0+ (a road not at its static height at t = 0), and with the whole q(t_0) it would
!> carry an impulse q(t_0)*dt/2 too much: an error of first order in dt. With the
!> half weight every method is second order (the rectangle rule becomes the trapezoidal rule;
!> for the first-order hold of `exact` the weight of q(t_0) in u(t_n) is dt*g(t_n)/2 + O(dt^3)
!> against the exact dt*g(t_n)/2 + O(dt^2)). A load that starts from zero is not changed. The
!> convolver does it, not the loop, so that a caller's own loop of `history` and `push` equals
!> the library's run (greenconv_contact_multi).
!>
!> When the structure's modes k = 1..N_m are shared by all points, with mode shapes phi_ik
!> at the points (normalised to unit modal mass),
!>
!>     g_ij(t) = sum_k phi_ik*phi_jk*h_k(t),   h_k(t) = 2*Re(r_k*exp(lambda_k*t)),
!>
!> h_k the unit modal impulse response in pole-residue form (greenconv_model_modal_set); for a mode of
!> unit modal mass, r_k = 1/(2i*omega_k^d) [1/(kg*s)] and phi_ik is in 1/sqrt(kg).
!> `point_modes` (greenconv_model_point_modes) holds that description; `sample_green_matrix`
!> tabulates g_ij(t_m) from it.
module greenconv_conv_multipoint
    use greenconv_core_kinds, only: dp
    use greenconv_core_error, only: error_type, fatal_error
    use greenconv_conv_convolver, only: convolver_core
    use greenconv_model_modal_set, only: modal_set
    use greenconv_model_point_modes, only: point_modes, separable_shapes
    use greenconv_conv_kernel, only: truncation_length
    implicit none
    private

    public :: multipoint_convolver, sample_green_matrix, check_green_table

    !> A causal multi-point convolver stepped once per time step.
    type, abstract, extends(convolver_core) :: multipoint_convolver
        !> Instant compliance matrix W0 (N_c x N_c) [m/N]: displacement at i per newton of
        !> the current step's own force at j; fixed when the convolver is built.
        real(dp), allocatable :: weight0(:, :)
        !> Whether W0 = 0 (set with W0 by `set_instant_matrix`).
        logical :: explicit = .true.
    contains
        !> History displacements u_h(n) [m] at all points from the forces pushed so far.
        procedure(history_interface), deferred :: history
        !> Record the forces q(t_n) [N] of the current step and advance to the next.
        procedure(push_interface), deferred :: push
        !> Number of contact points N_c.
        procedure :: n_points
        !> Whether W0 = 0, so that the forces of a step follow from the history alone.
        procedure :: is_explicit
        !> Set the instant compliance matrix W0 [m/N] (by the constructors).
        procedure :: set_instant_matrix
        !> The loads [N] a push records: the forces, halved at step 0 (for the engines' `push`).
        procedure :: recorded_load
        !> Whether `apply_instant_kept` is cheaper than a product by low-rank factors of W0, so
        !> that an implicit step should call it for its products W0*x.
        procedure :: fast_instant
        !> y = W0*x [m] for loads x [N]: the dense product.
        procedure :: apply_instant
        !> y = W0*x as `apply_instant`, or on an engine's own factors, the engine keeping what a
        !> push of the same loads x can reuse (its modal loads): the implicit step's last product
        !> is of the loads it pushes.
        procedure :: apply_instant_kept
        !> W0 = Phi*diag(w)*Phi^T on separable mode shapes Phi, when the engine holds them, so
        !> that W0's low-rank factors can be made and applied in the modes' span.
        procedure :: instant_modes
    end type multipoint_convolver

    abstract interface
        !> History displacements u_h(n) [m] at the N_c points.
        subroutine history_interface(self, u)
            import :: multipoint_convolver, dp
            implicit none
            class(multipoint_convolver), intent(in) :: self
            real(dp), intent(out) :: u(:)
        end subroutine history_interface

        !> Record the forces [N] at the N_c points for the current step and advance.
        subroutine push_interface(self, forces)
            import :: multipoint_convolver, dp
            implicit none
            class(multipoint_convolver), intent(inout) :: self
            real(dp), intent(in) :: forces(:)
        end subroutine push_interface
    end interface

contains

    !> Number of contact points N_c.
    pure integer function n_points(self)
        !> The convolver.
        class(multipoint_convolver), intent(in) :: self

        n_points = 0
        if (allocated(self%weight0)) n_points = size(self%weight0, 1)
    end function n_points

    !> Whether the instant compliance W0 is zero (the paper's explicit scheme).
    pure logical function is_explicit(self)
        !> The convolver.
        class(multipoint_convolver), intent(in) :: self

        is_explicit = self%explicit
    end function is_explicit

    !> Set W0 (N_c x N_c) [m/N], the number of points, and whether the scheme is explicit.
    pure subroutine set_instant_matrix(self, w0)
        !> The convolver.
        class(multipoint_convolver), intent(inout) :: self
        !> Instant compliance matrix [m/N].
        real(dp), intent(in) :: w0(:, :)

        if (allocated(self%weight0)) deallocate (self%weight0)
        allocate (self%weight0(size(w0, 1), size(w0, 2)))
        self%weight0(:, :) = w0
        self%explicit = maxval(abs(w0)) <= 0.0_dp
    end subroutine set_instant_matrix

    !> The loads [N] that `push` records at the current step: q, or q/2 at step 0 (the
    !> trapezoidal rule's end sample, see the module description).
    pure function recorded_load(self, forces) result(load)
        !> The convolver, before the push.
        class(multipoint_convolver), intent(in) :: self
        !> Forces q_j(t_n) [N] handed to `push`.
        real(dp), intent(in) :: forces(:)
        real(dp) :: load(size(forces))

        load(:) = forces
        if (self%step == 0) load(:) = 0.5_dp*forces
    end function recorded_load

    !> Whether `apply_instant_kept` costs less than the O(N_c*r) of W0's low-rank factors: not for
    !> the dense product; an engine that holds cheaper factors of W0 says so.
    pure logical function fast_instant(self)
        !> The convolver.
        class(multipoint_convolver), intent(in) :: self

        associate (unused => self%step)
        end associate
        fast_instant = .false.
    end function fast_instant

    !> y = W0*x [m] for loads x [N] (N_c), by the dense W0 (N_c^2 multiply-adds).
    subroutine apply_instant(self, x, y)
        !> The convolver.
        class(multipoint_convolver), intent(in) :: self
        !> Loads [N] at the points (N_c).
        real(dp), intent(in) :: x(:)
        !> W0*x [m] (N_c).
        real(dp), intent(out) :: y(:)

        y(:) = matmul(self%weight0, x)
    end subroutine apply_instant

    !> y = W0*x [m] for loads x [N] (N_c) by `apply_instant`, keeping nothing: an engine that
    !> holds cheaper factors of W0 makes the product on them, and keeps what its push shares
    !> with it for a push of the same loads.
    subroutine apply_instant_kept(self, x, y)
        !> The convolver.
        class(multipoint_convolver), intent(inout) :: self
        !> Loads [N] at the points (N_c).
        real(dp), intent(in) :: x(:)
        !> W0*x [m] (N_c).
        real(dp), intent(out) :: y(:)

        call self%apply_instant(x, y)
    end subroutine apply_instant_kept

    !> The modal form W0 = Phi*diag(w)*Phi^T [m/N] of the instant compliance on separable mode
    !> shapes: none for the dense W0 (`offered` false); an engine that steps separable modes
    !> offers their factors and w_k.
    subroutine instant_modes(self, shapes, weight, offered)
        !> The convolver.
        class(multipoint_convolver), intent(in) :: self
        !> The mode shapes' factors Phi over the grid of points, when offered.
        type(separable_shapes), allocatable, intent(out) :: shapes
        !> The modal weights w_k (N_m), when offered: W0_ij = sum_k phi_ik*w_k*phi_jk [m/N]
        !> (w_k in s^2 for unit-modal-mass shapes in 1/sqrt(kg)).
        real(dp), allocatable, intent(out) :: weight(:)
        !> Whether W0 = Phi*diag(w)*Phi^T is offered.
        logical, intent(out) :: offered

        associate (unused => self%step)
        end associate
        offered = .false.
    end subroutine instant_modes

    !> Check a table kernel(m, i, j) = g_ij(m*dt) of a sampled Green's matrix: samples
    !> m = 0..N_g with N_g >= 1 of an N_c x N_c matrix, N_c >= 1.
    subroutine check_green_table(kernel, error)
        !> Samples g_ij(m*dt) [m/(N*s)], first index m = 0..N_g, then i and j.
        real(dp), intent(in) :: kernel(0:, :, :)
        !> Set when the table is not square in (i, j) or has no sample after t = 0.
        type(error_type), allocatable, intent(out) :: error

        if (ubound(kernel, 1) < 1 .or. size(kernel, 2) < 1 .or. size(kernel, 3) /= size(kernel, 2)) then
            call fatal_error(error, 'sampled Green''s matrix: expected samples m = 0..N_g (N_g >= 1) of an ' &
                             //'N_c x N_c matrix')
        end if
    end subroutine check_green_table

    !> Tabulate g_ij(t_m), t_m = m*dt, from modes and truncate it by the paper's rule.
    !>
    !> N_g is the last sample at which some |g_ij| reaches tol*max|g| over all pairs and
    !> times (the single-point rule of greenconv_conv_direct applied to max_ij |g_ij(t_m)|), never
    !> beyond the run: N_g <= n_steps - 1, and with tol = 0 the table covers the whole run.
    !> Samples are computed until a bound of every |g_ij| (sum_k 2*|r_k|*max_i phi_ik^2
    !> *exp(Re(lambda_k)*t)) falls below tol times the largest driving-point |g_ii|.
    !> `tail` is the largest neglected max_ij |g_ij(t_m)|/max|g| that the run can reach.
    subroutine sample_green_matrix(description, dt, tol, n_steps, kernel, tail)
        !> Modes and mode shapes at the points.
        type(point_modes), intent(in) :: description
        !> Time step [s].
        real(dp), intent(in) :: dt
        !> Truncation fraction of max |g| (0.01 in the paper; 0 keeps the whole run).
        real(dp), intent(in) :: tol
        !> Number of steps of the run; the table never exceeds it.
        integer, intent(in) :: n_steps
        !> kernel(m, i, j) = g_ij(m*dt) [m/(N*s)], m = 0..N_g.
        real(dp), allocatable, intent(out) :: kernel(:, :, :)
        !> Largest neglected sample within the run, relative to max |g|.
        real(dp), intent(out) :: tail

        real(dp), allocatable :: modal(:, :), row_max(:)
        type(modal_set) :: bound
        real(dp) :: peak
        integer :: last, n_g, n_c, j

        n_c = description%n_points()
        bound = description%modes
        bound%residue = abs(bound%residue)*maxval(description%shape**2, dim=1)
        last = min(max(n_steps - 1, 1), 1024)
        do
            call modal_impulses(description%modes, dt, last, modal)
            peak = driving_point_peak(modal, description%shape)
            if (last >= n_steps - 1 .or. tol <= 0.0_dp) exit
            if (bound%envelope(last*dt) < tol*peak) exit
            last = min(2*last, n_steps - 1)
        end do
        if (tol <= 0.0_dp .and. last < n_steps - 1) then
            last = n_steps - 1
            call modal_impulses(description%modes, dt, last, modal)
        end if
        allocate (row_max(0:last))
        row_max(:) = 0.0_dp
        do j = 1, n_c
            row_max(:) = max(row_max, maxval(abs(pair_block(modal, description%shape, j)), dim=2))
        end do
        n_g = last
        if (tol > 0.0_dp) n_g = truncation_length(row_max, tol)
        allocate (kernel(0:n_g, n_c, n_c))
        do j = 1, n_c
            kernel(:, :, j) = pair_block(modal(0:n_g, :), description%shape, j)
        end do
        peak = maxval(row_max)
        tail = 0.0_dp
        if (n_g < last) tail = maxval(row_max(n_g + 1:last))/peak
        if (last < n_steps - 1) tail = max(tail, bound%envelope(last*dt)/peak)
    end subroutine sample_green_matrix

    !> modal(m, k) = h_k(m*dt) = 2*Re(r_k*exp(lambda_k*m*dt)), m = 0..last.
    subroutine modal_impulses(modes, dt, last, modal)
        type(modal_set), intent(in) :: modes
        real(dp), intent(in) :: dt
        integer, intent(in) :: last
        real(dp), allocatable, intent(inout) :: modal(:, :)

        integer :: k, m

        if (allocated(modal)) deallocate (modal)
        allocate (modal(0:last, modes%n_modes()))
        do k = 1, modes%n_modes()
            modal(:, k) = [(2.0_dp*real(modes%residue(k)*exp(modes%pole(k)*(m*dt)), kind=dp), m=0, last)]
        end do
    end subroutine modal_impulses

    !> Largest |g_ii(t_m)| over the points and the sampled times.
    pure real(dp) function driving_point_peak(modal, shape)
        real(dp), intent(in) :: modal(:, :), shape(:, :)

        integer :: i

        driving_point_peak = 0.0_dp
        do i = 1, size(shape, 1)
            driving_point_peak = max(driving_point_peak, maxval(abs(matmul(modal, shape(i, :)**2))))
        end do
    end function driving_point_peak

    !> block(m, i) = g_ij(t_m) = sum_k h_k(t_m)*phi_ik*phi_jk for one source point j.
    pure function pair_block(modal, shape, j) result(block)
        real(dp), intent(in) :: modal(:, :), shape(:, :)
        integer, intent(in) :: j
        real(dp) :: block(size(modal, 1), size(shape, 1))

        real(dp) :: weights(size(shape, 2), size(shape, 1))
        integer :: i

        do i = 1, size(shape, 1)
            weights(:, i) = shape(i, :)*shape(j, :)
        end do
        block = matmul(modal, weights)
    end function pair_block

end module greenconv_conv_multipoint
