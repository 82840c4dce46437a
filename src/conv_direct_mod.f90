!> Standard causal convolution with a sampled Green's function, eqs. (4), (5) and (20).
!>
!> The kernel is w_j = dt*g(t_j), j = 0..N_g, truncated by the paper's rule (section 2.1):
!> N_g is the last sample whose magnitude reaches a fraction `tol` of max |g| (1/100 in the
!> paper), so every neglected sample is below tol*max|g|. Past forces sit in a doubled ring
!> buffer, newest first, so that the history is one contiguous dot product of length
!> min(n, N_g) per step. That product is summed in eight interleaved partial sums
!> (`lane_dot`): a single running sum cannot be vectorised without reassociating
!> floating-point additions (-ffast-math), eight independent ones can, and gfortran does so
!> at -O2 and above (about 5x the rate of `dot_product` or reference BLAS ddot at
!> N_g = 19000; the benchmark prints both).
module conv_direct_mod
    use kinds_mod, only: dp
    use convolver_mod, only: convolver, capped_step
    use modal_set_mod, only: modal_set
    implicit none
    private

    public :: direct_convolver, new_direct_convolver
    public :: truncation_length, sample_kernel, lane_dot

    !> Direct sum over N_g past forces (cost per step proportional to N_g).
    type, extends(convolver) :: direct_convolver
        !> Kernel weights w_j = dt*g(t_j) [m/N], j = 1..N_g.
        real(dp), allocatable :: weight(:)
        !> Past forces [N], each stored twice (positions i and i + N_g), newest at `head`.
        real(dp), allocatable :: past(:)
        !> Position of the newest force in `past`.
        integer :: head = 1
    contains
        procedure :: history => direct_history
        procedure :: push => direct_push
        procedure :: reset => direct_reset
        procedure :: model_size => direct_size
    end type direct_convolver

contains

    !> A direct convolver from kernel samples g(t_j) [m/(N*s)], j = 0..N_g (N_g >= 1), step dt [s].
    function new_direct_convolver(kernel, dt) result(conv)
        !> Samples g(j*dt), j = 0..N_g, of the impulse response [m/(N*s)].
        real(dp), intent(in) :: kernel(0:)
        !> Time step [s].
        real(dp), intent(in) :: dt
        type(direct_convolver) :: conv

        integer :: n_g

        n_g = ubound(kernel, 1)
        conv%name = 'direct'
        conv%dt = dt
        conv%weight0 = dt*kernel(0)
        conv%weight = dt*kernel(1:n_g)
        allocate (conv%past(2*n_g))
        call conv%reset()
    end function new_direct_convolver

    !> The paper's truncation: the last index j with |g_j| >= tol*max|g| (at least 1).
    pure function truncation_length(kernel, tol) result(n_g)
        !> Samples g(j*dt), j = 0..J.
        real(dp), intent(in) :: kernel(0:)
        !> Fraction of max |g| below which the tail is neglected (0.01 in the paper).
        real(dp), intent(in) :: tol
        integer :: n_g

        real(dp) :: threshold

        threshold = tol*maxval(abs(kernel))
        do n_g = ubound(kernel, 1), 1, -1
            if (abs(kernel(n_g)) >= threshold) return
        end do
        n_g = 1
    end function truncation_length

    !> Sample g of a modal set at t_j = j*dt and truncate it by the paper's rule.
    !>
    !> Samples are taken until the modal envelope falls below tol*max|g| or the run ends
    !> (`n_steps`); N_g <= n_steps - 1, so a kernel that covers the whole run is exact.
    !> `tail` is the largest neglected |g_j|/max|g| that a run of n_steps can reach.
    subroutine sample_kernel(modes, dt, tol, n_steps, kernel, tail)
        !> The Green's function as modes.
        type(modal_set), intent(in) :: modes
        !> Time step [s].
        real(dp), intent(in) :: dt
        !> Truncation fraction of max |g| (0.01 in the paper).
        real(dp), intent(in) :: tol
        !> Number of steps of the run; the kernel never exceeds it.
        integer, intent(in) :: n_steps
        !> Samples g(j*dt), j = 0..N_g [m/(N*s)].
        real(dp), allocatable, intent(out) :: kernel(:)
        !> Largest neglected sample within the run, relative to max |g|.
        real(dp), intent(out) :: tail

        real(dp), allocatable :: samples(:)
        real(dp) :: peak
        integer :: last, j, n_g

        last = min(max(n_steps - 1, 1), 1024)
        do
            if (allocated(samples)) deallocate (samples)
            allocate (samples(0:last))
            samples(:) = modes%impulse([(j*dt, j=0, last)])
            peak = maxval(abs(samples))
            if (last >= n_steps - 1) exit
            if (modes%envelope(last*dt) < tol*peak) exit
            last = min(2*last, n_steps - 1)
        end do
        n_g = truncation_length(samples, tol)
        allocate (kernel(0:n_g))
        kernel(:) = samples(0:n_g)
        tail = 0.0_dp
        if (n_g < last) tail = maxval(abs(samples(n_g + 1:last)))/peak
        if (last < n_steps - 1) tail = max(tail, modes%envelope(last*dt)/peak)
    end subroutine sample_kernel

    !> Displacement from past forces: sum_{j=1..min(n,N_g)} w_j*q(t_{n-j}).
    function direct_history(self) result(u)
        class(direct_convolver), intent(in) :: self
        real(dp) :: u

        integer :: m

        m = capped_step(self%step, size(self%weight))
        u = lane_dot(m, self%weight, self%past(self%head:))
    end function direct_history

    !> Dot product of the first n entries of a and b, summed in eight interleaved partial sums
    !> so that the compiler vectorises it without reassociating additions. The result differs
    !> from a left-to-right sum by round-off only.
    pure function lane_dot(n, a, b) result(s)
        !> Number of terms.
        integer, intent(in) :: n
        !> First factor (at least n entries, contiguous).
        real(dp), intent(in) :: a(n)
        !> Second factor (at least n entries, contiguous).
        real(dp), intent(in) :: b(n)
        real(dp) :: s

        integer, parameter :: lanes = 8
        real(dp) :: partial(lanes)
        integer :: i, m

        partial = 0.0_dp
        m = n - mod(n, lanes)
        do i = 1, m, lanes
            partial = partial + a(i:i + lanes - 1)*b(i:i + lanes - 1)
        end do
        s = sum(partial)
        do i = m + 1, n
            s = s + a(i)*b(i)
        end do
    end function lane_dot

    !> Store the force of the current step in both halves of the ring and advance.
    subroutine direct_push(self, force)
        class(direct_convolver), intent(inout) :: self
        real(dp), intent(in) :: force

        integer :: n_g

        n_g = size(self%weight)
        self%head = self%head - 1
        if (self%head < 1) self%head = n_g
        self%past(self%head) = force
        self%past(self%head + n_g) = force
        self%step = self%step + 1
    end subroutine direct_push

    !> Clear the force history.
    subroutine direct_reset(self)
        class(direct_convolver), intent(inout) :: self

        self%past = 0.0_dp
        self%head = 1
        self%step = 0
    end subroutine direct_reset

    !> Kernel length N_g.
    subroutine direct_size(self, n, label)
        class(direct_convolver), intent(in) :: self
        integer, intent(out) :: n
        character(len=:), allocatable, intent(out) :: label

        n = size(self%weight)
        label = 'N_g'
    end subroutine direct_size

end module conv_direct_mod
