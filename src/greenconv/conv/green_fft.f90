!> The sampled Green's matrix convolved by partitioned FFT: the multi-point `fft` engine.
!>
!> It computes the sum of the multi-point `direct` (greenconv_conv_green_sampled),
!>
!>     u_h,i(n) = sum_j sum_{m=1..N_g} W_ij(m)*q_j(t_{n-m}),   W_ij(m) = dt*g_ij(t_m),
!>
!> with the partition of the single-point engine (greenconv_conv_fft, whose notes say how the
!> taps are split and why every contribution is in place before its output is due): a head
!> of the newest H taps summed directly, then levels l of P_l partitions of B_l taps, here
!> one partition per level (the block doubling per level) and at most two in the last. What
!> changes with N_c points is the bookkeeping of a level's block, done once per block:
!>
!> - one forward transform per source point j of its last B_l forces, kept in j's
!>   frequency-domain delay line X_j (the last P_l block spectra);
!> - per receiving point i, the product sum over every source point and partition,
!>   Y_i = sum_j sum_p W_ij,p * X_j,b-p+1, and one inverse transform of Y_i added to the
!>   pending outputs of i.
!>
!> That is 2*N_c transforms per block instead of the N_c^2 of N_c^2 single-point engines; the
!> N_c^2*P_l products per spectral line remain (the matrix-vector product the direct sum
!> does per tap, done per line). The per-step cost is the head's N_c^2*H multiply-adds plus,
!> averaged over a block, N_c^2*P_l complex multiply-adds per level: for the tyre scene
!> (N_c = 20, N_g = 2741) about 1/50 of the direct sum's N_c^2*N_g.
!>
!> Plans, copies, `reset` and `release` behave as in greenconv_conv_fft: the object owns its
!> FFTW plans (made on demand, destroyed by `release`); a rerun after `reset` repeats itself
!> to the bit. Round-off: about 1e-16*log2(N_g) of sum_j sum_m |W_ij(m)*q_j|.
module greenconv_conv_green_fft
    use, intrinsic :: iso_fortran_env, only: int64
    use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
    use greenconv_core_kinds, only: dp
    use greenconv_core_error, only: error_type
    use greenconv_ext_fftw, only: fft_plan_set
    use greenconv_conv_multipoint, only: multipoint_convolver, check_green_table
    use greenconv_conv_fft, only: add_to_ring, partition_rings, lay_out
    implicit none
    private

    public :: fft_green_matrix, new_fft_green_matrix
    public :: default_multipoint_head

    !> Taps summed directly when the constructor is given no `head`: fewer than the
    !> single-point engine's 64, because the head costs N_c^2 multiply-adds per tap and step.
    integer, parameter :: default_multipoint_head = 32
    !> Partitions per level that is not the last: one, so that the block size doubles per
    !> level. The N_c^2 products per line and partition dominate the cost, and one partition
    !> per level gives the fewest partitions (about log2(N_g/H)) at the price of more levels
    !> of cheap transforms.
    integer, parameter :: level_parts = 1
    !> A level that can cover the remaining taps with at most this many partitions is the last.
    integer, parameter :: finish_parts = 2

    !> One level: P partitions of B taps for every pair of points.
    type :: green_fft_level
        !> Block size B (forces per block, taps per partition); transforms have 2*B points.
        integer :: block = 0
        !> Number of partitions P.
        integer :: parts = 0
        !> First tap s of the level.
        integer :: first_tap = 0
        !> Column of `input_spectra` holding the newest block's spectrum.
        integer :: newest = 1
        !> kernel_re(k, p, i, j), kernel_im(k, p, i, j): real and imaginary parts of the
        !> spectrum of partition p of W_ij, zero-padded, divided by 2*B [m/N], lines k = 1..B + 1
        !> (held apart so that the product sums vectorise; columns padded to 64 bytes).
        real(dp), allocatable :: kernel_re(:, :, :, :), kernel_im(:, :, :, :)
        !> input_re(k, c, j), input_im(k, c, j): spectra of the last P force blocks of point
        !> j [N], a ring of columns c.
        real(dp), allocatable :: input_re(:, :, :), input_im(:, :, :)
    end type green_fft_level

    !> Partitioned FFT convolution with a sampled Green's matrix.
    type, extends(multipoint_convolver) :: fft_green_matrix
        !> Kernel length N_g.
        integer :: n_g = 0
        !> Head weights head_weight(i, m, j) = W_ij(m) [m/N], m = 1..H (receiving point first,
        !> so that the head's sum is a vectorised update of all points per tap and source).
        real(dp), allocatable :: head_weight(:, :, :)
        !> The FFT levels, smallest block first (none when N_g <= H).
        type(green_fft_level), allocatable :: levels(:)
        !> Scratch: real and imaginary parts of a product sum, (largest block) + 1 lines.
        real(dp), allocatable :: sum_re(:), sum_im(:)
        !> Force rings (one column per point), pending outputs, scratch and FFTW plans.
        type(partition_rings) :: rings
    contains
        procedure :: history => green_fft_history
        procedure :: push => green_fft_push
        procedure :: clear => green_fft_clear
        procedure :: release => green_fft_release
    end type fft_green_matrix

contains

    !> A multi-point FFT convolver from kernel(m, i, j) = g_ij(m*dt) [m/(N*s)], m = 0..N_g
    !> (N_g >= 1), at time step dt [s]: the same sum as `new_sampled_green_matrix`.
    subroutine new_fft_green_matrix(kernel, dt, conv, error, head)
        !> Samples g_ij(m*dt), first index m = 0..N_g, then i and j (N_c x N_c).
        real(dp), intent(in) :: kernel(0:, :, :)
        !> Time step [s].
        real(dp), intent(in) :: dt
        !> The convolver, at step 0.
        type(fft_green_matrix), intent(out) :: conv
        !> Set when the table is not square in (i, j) or has no sample after t = 0.
        type(error_type), allocatable, intent(out) :: error
        !> Number of taps H summed directly (default `default_multipoint_head`; clipped to 1..N_g).
        integer, intent(in), optional :: head

        integer :: n_g, n_c, n_head

        call check_green_table(kernel, error)
        if (allocated(error)) return
        n_g = ubound(kernel, 1)
        n_c = size(kernel, 2)
        n_head = default_multipoint_head
        if (present(head)) n_head = head
        n_head = min(max(n_head, 1), n_g)
        call conv%set_model('fft', dt, n_g, 'N_g')
        conv%n_g = n_g
        call conv%set_instant_matrix(dt*kernel(0, :, :))
        allocate (conv%head_weight(n_c, n_head, n_c))
        conv%head_weight(:, :, :) = reshape(dt*kernel(1:n_head, :, :), [n_c, n_head, n_c], order=[2, 1, 3])
        call build_levels(conv, kernel, dt, n_head)
        ! The kernel spectra are made: the new object holds no plan (as the single-point engine).
        call conv%rings%plans%release()
        call conv%reset()
    end subroutine new_fft_green_matrix

    !> Destroy the FFTW plans this object owns; stepping on plans again.
    subroutine green_fft_release(self)
        class(fft_green_matrix), intent(inout) :: self

        call self%rings%plans%release()
    end subroutine green_fft_release

    !> Lay out the levels behind the head, size the rings and the scratch, transform the partitions.
    subroutine build_levels(conv, kernel, dt, n_head)
        type(fft_green_matrix), intent(inout) :: conv
        real(dp), intent(in) :: kernel(0:, :, :)
        real(dp), intent(in) :: dt
        integer, intent(in) :: n_head

        integer :: blocks(bit_size(0)), parts(bit_size(0)), first(bit_size(0))
        integer :: n_levels, l, n_c

        n_c = size(kernel, 2)
        call lay_out(conv%rings, conv%n_g, n_head, n_c, n_levels, blocks, parts, first, level_parts, finish_parts)
        allocate (conv%levels(n_levels), conv%sum_re(size(conv%rings%spectrum)), &
                  conv%sum_im(size(conv%rings%spectrum)))
        do l = 1, n_levels
            call build_level(conv%levels(l), kernel, dt, blocks(l), parts(l), first(l), conv%rings%samples, &
                             conv%rings%plans)
        end do
    end subroutine build_levels

    !> One level: the scaled spectra of the zero-padded partitions of every W_ij, empty delay lines.
    subroutine build_level(level, kernel, dt, block, parts, first, samples, plans)
        type(green_fft_level), intent(out) :: level
        real(dp), intent(in) :: kernel(0:, :, :)
        real(dp), intent(in) :: dt
        integer, intent(in) :: block, parts, first
        real(dp), contiguous, intent(inout) :: samples(:)
        type(fft_plan_set), intent(inout) :: plans

        complex(dp) :: lines(block + 1)
        integer :: p, i, j, tap, last, lead, n_c

        n_c = size(kernel, 2)
        level%block = block
        level%parts = parts
        level%first_tap = first
        lead = 8*((block + 8)/8)
        allocate (level%kernel_re(lead, parts, n_c, n_c), level%kernel_im(lead, parts, n_c, n_c))
        allocate (level%input_re(lead, parts, n_c), level%input_im(lead, parts, n_c))
        level%kernel_re(:, :, :, :) = 0.0_dp
        level%kernel_im(:, :, :, :) = 0.0_dp
        do j = 1, n_c
            do i = 1, n_c
                do p = 1, parts
                    tap = first + (p - 1)*block
                    last = min(tap + block - 1, ubound(kernel, 1))
                    samples(1:2*block) = 0.0_dp
                    samples(1:last - tap + 1) = dt*kernel(tap:last, i, j)
                    call plans%forward(samples(1:2*block), lines)
                    level%kernel_re(1:block + 1, p, i, j) = real(lines, dp)/real(2*block, dp)
                    level%kernel_im(1:block + 1, p, i, j) = aimag(lines)/real(2*block, dp)
                end do
            end do
        end do
    end subroutine build_level

    !> u_h,i(n) [m]: the head's direct sums plus the levels' pending output of the step; NaN
    !> from step `valid_steps` on.
    subroutine green_fft_history(self, u)
        class(fft_green_matrix), intent(in) :: self
        real(dp), intent(out) :: u(:)

        integer :: h, m, j, first

        if (self%step >= self%valid_steps) then
            u(:) = ieee_value(1.0_dp, ieee_quiet_nan)
            return
        end if
        h = size(self%head_weight, 2)
        associate (r => self%rings)
            first = r%head_position - 1
            u(:) = r%pending(r%pending_position, :)
            do j = 1, size(r%head_past, 2)
                do m = 1, h
                    u(:) = u(:) + self%head_weight(:, m, j)*r%head_past(first + m, j)
                end do
            end do
        end associate
    end subroutine green_fft_history

    !> Store the forces of step n, retire output n, advance, and run every level whose block
    !> has just been completed.
    subroutine green_fft_push(self, forces)
        class(fft_green_matrix), intent(inout) :: self
        real(dp), intent(in) :: forces(:)

        integer :: l, n_due

        call self%rings%store(self%recorded_load(forces), self%step + 1, n_due)
        self%step = self%step + 1
        do l = 1, n_due
            call run_level(self, l)
        end do
    end subroutine green_fft_push

    !> Level l at step n (a multiple of its block size B): transform each point's forces of
    !> steps n - B..n - 1, then per receiving point sum the products over source points and
    !> partitions, transform back and add to its pending outputs n - B + s..n + B + s - 2.
    subroutine run_level(self, l)
        class(fft_green_matrix), intent(inout) :: self
        integer, intent(in) :: l

        integer :: b, first, p, i, j, column, n_c

        n_c = size(self%rings%recent, 2)
        associate (level => self%levels(l), r => self%rings)
            b = level%block
            first = int(mod(self%step - b, size(r%recent, 1, kind=int64))) + 1
            level%newest = level%newest - 1
            if (level%newest < 1) level%newest = level%parts
            r%samples(b + 1:2*b) = 0.0_dp
            do j = 1, n_c
                r%samples(1:b) = r%recent(first:first + b - 1, j)
                call r%plans%forward(r%samples(1:2*b), r%spectrum(1:b + 1))
                level%input_re(1:b + 1, level%newest, j) = real(r%spectrum(1:b + 1), dp)
                level%input_im(1:b + 1, level%newest, j) = aimag(r%spectrum(1:b + 1))
            end do
            do i = 1, n_c
                self%sum_re(1:b + 1) = 0.0_dp
                self%sum_im(1:b + 1) = 0.0_dp
                do j = 1, n_c
                    do p = 1, level%parts
                        column = mod(level%newest + p - 2, level%parts) + 1
                        call multiply_add(b + 1, level%kernel_re(:, p, i, j), level%kernel_im(:, p, i, j), &
                                          level%input_re(:, column, j), level%input_im(:, column, j), &
                                          self%sum_re, self%sum_im)
                    end do
                end do
                r%spectrum(1:b + 1) = cmplx(self%sum_re(1:b + 1), self%sum_im(1:b + 1), dp)
                call r%plans%inverse(r%spectrum(1:b + 1), r%samples(1:2*b))
                call add_to_ring(r%pending(:, i), self%step - b + level%first_tap, r%samples(1:2*b - 1))
            end do
        end associate
    end subroutine run_level

    !> (s_re + i*s_im) += (k_re + i*k_im)*(x_re + i*x_im), lines 1..n, on split parts.
    pure subroutine multiply_add(n, k_re, k_im, x_re, x_im, s_re, s_im)
        integer, intent(in) :: n
        real(dp), intent(in) :: k_re(n), k_im(n), x_re(n), x_im(n)
        real(dp), intent(inout) :: s_re(n), s_im(n)

        integer :: k

        do k = 1, n
            s_re(k) = s_re(k) + (k_re(k)*x_re(k) - k_im(k)*x_im(k))
            s_im(k) = s_im(k) + (k_re(k)*x_im(k) + k_im(k)*x_re(k))
        end do
    end subroutine multiply_add

    !> No force pushed yet: every point's delay lines of block spectra and rings emptied.
    subroutine green_fft_clear(self)
        class(fft_green_matrix), intent(inout) :: self

        integer :: l

        do l = 1, size(self%levels)
            self%levels(l)%input_re(:, :, :) = 0.0_dp
            self%levels(l)%input_im(:, :, :) = 0.0_dp
        end do
        self%levels(:)%newest = 1
        call self%rings%clear()
    end subroutine green_fft_clear

end module greenconv_conv_green_fft
