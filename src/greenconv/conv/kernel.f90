!> Sampled kernels shared by the direct engines, single- and multi-point: the paper's
!> truncation rule (section 2.1), sampling g from modes, and the vectorisable sums of the
!> direct convolution.
!>
!> The kernel is w_j = dt*g(t_j), j = 0..N_g, truncated by the paper's rule: N_g is the last
!> sample whose magnitude reaches a fraction `tol` of max |g| (1/100 in the paper), so every
!> neglected sample is below tol*max|g|. A single running sum cannot be vectorised without
!> reassociating floating-point additions (-ffast-math); independent partial sums can, and
!> gfortran does so at -O2 and above. `lane_dot` is one dot product in eight interleaved
!> partial sums (about 5x the rate of `dot_product` or reference BLAS ddot at N_g = 19000; the
!> benchmark prints both). `block_sums` gives `block_size` dot products of one force history
!> against the kernel shifted by 0..block_size-1 taps (a Toeplitz matrix-vector product): each
!> force is loaded once for all of them, so that eight histories cost about the memory traffic of
!> one, which is what bounds `lane_dot` once the kernel outgrows the first-level cache.
module greenconv_conv_kernel
    use greenconv_core_kinds, only: dp
    use greenconv_model_modal_set, only: modal_set
    implicit none
    private

    public :: truncation_length, sample_kernel, lane_dot, block_sums, period_end_level, beyond_nyquist

    !> Number of consecutive histories `block_sums` sums together.
    integer, parameter, public :: block_size = 8

    !> Fraction of a period at its end that `period_end_level` looks at (a tenth, as the
    !> identification's wrap-around check).
    real(dp), parameter :: end_fraction = 0.1_dp

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

    !> How much of g is left at the end of the period it was sampled over by an inverse FFT:
    !> max |g_j| over the last tenth of the samples, relative to max |g|. g from the inverse
    !> FFT of a receptance on lines df apart is periodic with period 1/df, so what has not
    !> decayed within it wraps onto its start (and a band cut at f_max rings there): a
    !> kernel's own estimate of its wrap-around error (0 for fewer than 10 samples or g = 0).
    pure real(dp) function period_end_level(samples) result(level)
        !> |g_j| (or, for a table, max over i, j of |g_ij|), j over one period or half of one.
        real(dp), intent(in) :: samples(:)

        integer :: first
        real(dp) :: peak

        level = 0.0_dp
        peak = maxval(abs(samples))
        if (size(samples) < 10 .or. .not. peak > 0.0_dp) return
        first = int((1.0_dp - end_fraction)*size(samples)) + 1
        level = maxval(abs(samples(first:)))/peak
    end function period_end_level

    !> What g sampled at dt from its spectrum below the Nyquist frequency f_N = 1/(2*dt) (an
    !> inverse FFT of a receptance measured to f_N) leaves out of the true samples g(j*dt): the
    !> part of the spectrum above f_N changes each sample by at most 2*int_{f_N}^inf |G(f)| df,
    !> here relative to `peak`, with G the modes' receptance (the residual flexibility the modes
    !> of the band carry above it). Trapezoidal rule on 400 log-spaced points from f_N to
    !> 1000*f_N, and |G(F)|*F for the rest (|G| falls as 1/f^2 there).
    real(dp) function beyond_nyquist(modes, dt, peak) result(level)
        !> The modes (identified in the band).
        type(modal_set), intent(in) :: modes
        !> Time step [s] g was sampled at.
        real(dp), intent(in) :: dt
        !> max |g| [m/(N*s)] the level is relative to.
        real(dp), intent(in) :: peak

        integer, parameter :: n = 400
        real(dp), parameter :: two_pi = 2.0_dp*acos(-1.0_dp)
        real(dp) :: f(0:n), magnitude(0:n)
        integer :: k

        level = 0.0_dp
        if (.not. peak > 0.0_dp .or. modes%n_modes() < 1) return
        f(:) = [(0.5_dp/dt*1000.0_dp**(real(k, dp)/n), k=0, n)]
        magnitude(:) = abs(modes%receptance(two_pi*f))
        level = 0.5_dp*sum((magnitude(1:) + magnitude(:n - 1))*(f(1:) - f(:n - 1))) + magnitude(n)*f(n)
        level = 2.0_dp*level/peak
    end function beyond_nyquist

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

    !> The block_size = 8 sums s_i = sum_{m=1..n} w(m + i)*p(m), i = 0..7, of one vector p
    !> against w shifted by i taps, in 2 x 8 interleaved partial sums. Each differs from a
    !> left-to-right sum by round-off only.
    pure subroutine block_sums(n, w, p, s)
        !> Number of terms of each sum, even.
        integer, intent(in) :: n
        !> The shifted factor, at least n + 7 entries (contiguous).
        real(dp), intent(in) :: w(n + block_size - 1)
        !> The common factor, at least n entries (contiguous).
        real(dp), intent(in) :: p(n)
        !> The eight sums.
        real(dp), intent(out) :: s(0:block_size - 1)

        ! w passed as two overlapping views, so that the compiler keeps no window of w across
        ! iterations (which, two doubles to a register, costs shuffles and spills).
        call toeplitz_streams(n, w(1:n + block_size - 2), w(2:n + block_size - 1), p, s)
    end subroutine block_sums

    !> s_i = sum_{m=1..n} w(m + i)*p(m), i = 0..7, from the views w1 = w(1:n+6) and
    !> w2 = w(2:n+7): two streams over m (m = 1, 3, ... and 2, 4, ...), each a vector of the
    !> eight sums times one p(m), so that every p(m) is loaded once and the 16 partial sums are
    !> independent.
    pure subroutine toeplitz_streams(n, w1, w2, p, s)
        !> Number of terms, even.
        integer, intent(in) :: n
        !> w shifted by 0 and 1 taps.
        real(dp), intent(in) :: w1(n + block_size - 2), w2(n + block_size - 2)
        !> The common factor.
        real(dp), intent(in) :: p(n)
        !> The eight sums.
        real(dp), intent(out) :: s(0:block_size - 1)

        real(dp) :: a1(block_size), a2(block_size)
        integer :: m

        a1 = 0.0_dp
        a2 = 0.0_dp
        ! Each statement is one short vector operation; vectorising the loop over m as well
        ! would interleave the streams through shuffles.
        !GCC$ novector
        do m = 1, n - 1, 2
            a1 = a1 + w1(m:m + block_size - 1)*p(m)
            a2 = a2 + w2(m:m + block_size - 1)*p(m + 1)
        end do
        s = a1 + a2
    end subroutine toeplitz_streams

end module greenconv_conv_kernel
