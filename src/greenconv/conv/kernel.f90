!> Sampled kernels shared by the direct engines, single- and multi-point: the paper's
!> truncation rule (section 2.1), sampling g from modes, and the vectorisable dot product of
!> the direct sum.
!>
!> The kernel is w_j = dt*g(t_j), j = 0..N_g, truncated by the paper's rule: N_g is the last
!> sample whose magnitude reaches a fraction `tol` of max |g| (1/100 in the paper), so every
!> neglected sample is below tol*max|g|. The direct sum is done in eight interleaved partial
!> sums (`lane_dot`): a single running sum cannot be vectorised without reassociating
!> floating-point additions (-ffast-math), eight independent ones can, and gfortran does so
!> at -O2 and above (about 5x the rate of `dot_product` or reference BLAS ddot at
!> N_g = 19000; the benchmark prints both).
module greenconv_conv_kernel
    use greenconv_core_kinds, only: dp
    use greenconv_model_modal_set, only: modal_set
    implicit none
    private

    public :: truncation_length, sample_kernel, lane_dot

contains

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

end module greenconv_conv_kernel
