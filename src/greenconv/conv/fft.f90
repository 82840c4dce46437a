!> Exact causal convolution by non-uniformly partitioned FFT (Gardner 1995): the `fft` engine.
!>
!> It computes the same truncated sum as `direct` (greenconv_conv_direct), with the same one step
!> of latency,
!>
!>     u(t_n) = u_h(n) + w0*q(t_n),   u_h(n) = sum_{j=1..N_g} w_j*q(t_{n-j}),   q(t_m) = 0 for m < 0,
!>
!> w0 = dt*g(0) and w_j = dt*g(t_j) [m/N], at a cost per step that grows like log N_g
!> instead of N_g. The taps j = 1..N_g are split into
!>
!> - a head, taps 1..H (H = `default_head` = 64 unless asked otherwise), summed directly
!>   every step from a doubled ring of the last H forces, as in `direct`;
!> - levels l = 1..L, each of P_l consecutive partitions of B_l taps. Level l starts at tap
!>   s_l: s_1 = H + 1, s_{l+1} = s_l + P_l*B_l. B_1 = H, and B_{l+1} is the largest H*2^k
!>   not above s_{l+1}. P_l is the number of B_l-blocks left to cover when that is at most
!>   `finish_parts` = 8 (the last level, whose last partition is zero-padded past N_g),
!>   else `parts_per_level` = 3, which makes the block size grow fourfold per level:
!>   (B, P) = (64, 3), (256, 3), (1024, 3), (4096, 4) for N_g = 19000 and H = 64.
!>
!> Level l works on blocks of B_l forces, q(t_m) for m = b*B_l..(b+1)*B_l - 1. When block b
!> is complete (right after the push of its last force, at step n = (b+1)*B_l), its
!> zero-padded 2*B_l-point real spectrum X_b is computed and kept in a frequency-domain
!> delay line of the last P_l block spectra; one product sum and one inverse transform
!>
!>     y = IFFT( sum_{p=1..P_l} W_{l,p} * X_{b-p+1} ),
!>
!> where W_{l,p} is the precomputed spectrum of partition p (taps s_l + (p-1)*B_l onwards,
!> zero-padded to 2*B_l, scaled by 1/(2*B_l)), give the contribution of all P_l partitions
!> to the outputs n' = b*B_l + s_l + i, i = 0..2*B_l - 2, which are added into a ring of
!> pending outputs. The first of them, n' = n - B_l + s_l, is never earlier than the next
!> history because B_l <= s_l (by the choice of B_l; the one step of latency is what lets
!> B_1 = H with s_1 = H + 1): every contribution is in place before its output is due.
!> `history()` is the head's dot product plus the pending output of the current step.
!>
!> The work is done in bursts: a push at a step that is a multiple of B_l runs level l
!> (two real FFTs of 2*B_l points and P_l*(B_l + 1) complex multiply-adds), so the push at
!> a multiple of the largest block runs every level at once, O(N_g log N_g) operations in
!> that one push (about 0.1 ms at N_g = 19000), while most pushes cost only the head.
!> Averaged over the steps, the cost is H multiply-adds plus, per level, two transforms
!> of 2*B_l points per B_l steps and P_l complex multiply-adds per step: about
!> log4(N_g/H) levels of O(log B_l) each. Gardner's spreading of each level's work over
!> its block is not done; a caller that needs a bounded time per step would need it.
!>
!> Round-off: FFT convolution errs by about 1e-16*log2(N_g) relative to sum_j |w_j*q|,
!> not to |u|; the tests measure it below 1e-13 of max|u| against `direct`.
!>
!> Transforms use FFTW_ESTIMATE plans that the object owns (an `fft_plan_set` of greenconv_ext_fftw),
!> made for the size and the alignment of its own work arrays and applied to them by FFTW's
!> new-array execute functions, so SIMD codelets are kept. A new object holds no plan: the
!> first push that runs a level plans it (tens of microseconds). Plans are destroyed by
!> `release` (the object plans again if stepped further): call it before dropping an
!> object that has run, or its plans stay allocated in FFTW (there is no finalizer; see
!> greenconv_ext_fftw). A copy (intrinsic assignment, `source=`) plans for itself and never destroys
!> its original's plans; its arrays may sit at other alignments and get other plans, so it
!> may differ from the original in the last bits. One object rerun after `reset` repeats
!> itself to the bit. Threads: independent objects may be stepped in parallel; plan creation
!> and destruction are serialised as greenconv_ext_fftw describes (OpenMP critical section
!> `greenconv_fftw_planner`).
module greenconv_conv_fft
    use, intrinsic :: iso_fortran_env, only: int64
    use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
    use greenconv_core_kinds, only: dp
    use greenconv_conv_convolver, only: convolver
    use greenconv_ext_fftw, only: fft_plan_set
    use greenconv_ident_dense, only: dot
    implicit none
    private

    public :: fft_convolver, new_fft_convolver
    public :: default_head
    public :: partition_schedule, add_to_ring
    public :: partition_rings, lay_out

    !> Number of taps summed directly when the constructor is given no `head`.
    integer, parameter :: default_head = 64
    !> Partitions per level that is not the last (the block size then grows fourfold).
    integer, parameter :: parts_per_level = 3
    !> A level that can cover all remaining taps with at most this many partitions is the last.
    integer, parameter :: finish_parts = 8

    !> One level of the partition: P partitions of B taps sharing one block size.
    type :: fft_level
        !> Block size B (forces per block, taps per partition); transforms have 2*B points.
        integer :: block = 0
        !> Number of partitions P.
        integer :: parts = 0
        !> First tap s of the level (taps s..s + P*B - 1, zero past N_g).
        integer :: first_tap = 0
        !> Column of `input_spectra` holding the newest block's spectrum.
        integer :: newest = 1
        !> Spectra of the partitions' zero-padded taps divided by 2*B [m/N]: lines 1..B + 1
        !> of each of the P columns (columns padded to a multiple of 64 bytes).
        complex(dp), allocatable :: kernel_spectra(:, :)
        !> Spectra of the last P zero-padded force blocks [N], lines 1..B + 1, a ring of columns.
        complex(dp), allocatable :: input_spectra(:, :)
    end type fft_level

    !> What a partitioned-FFT engine keeps between pushes besides its levels, for N_c points
    !> (one column per point; one for `fft`, N_c for greenconv_conv_green_fft): the rings of
    !> past forces and of pending outputs, the count down to the next block, the scratch of
    !> the transforms and their FFTW plans.
    type :: partition_rings
        !> The last H forces of each point [N], each stored twice (rows r and r + H), newest
        !> at row `head_position`.
        real(dp), allocatable :: head_past(:, :)
        !> Row of the newest force in `head_past`.
        integer :: head_position = 1
        !> The last forces [N], force of step m at row mod(m, rows) + 1 (rows = largest block).
        real(dp), allocatable :: recent(:, :)
        !> Row in `recent` of the force of the current step, mod(step, rows) + 1.
        integer :: recent_position = 1
        !> Contributions of the levels to coming outputs [m], output n at row mod(n, rows) + 1.
        real(dp), allocatable :: pending(:, :)
        !> Row in `pending` of the output of the current step, mod(step, rows) + 1.
        integer :: pending_position = 1
        !> Block size B_l of each level, smallest first.
        integer, allocatable :: blocks(:)
        !> Pushes left until the step is a multiple of the smallest block (huge without levels).
        integer :: countdown = 0
        !> Scratch: zero-padded samples of a block or partition, 2*(largest block).
        real(dp), allocatable :: samples(:)
        !> Scratch: a spectrum, (largest block) + 1 lines.
        complex(dp), allocatable :: spectrum(:)
        !> The FFTW plans of the engine's transforms, made on demand.
        type(fft_plan_set) :: plans
    contains
        !> Empty rings, positions at the start, the count down at the smallest block.
        procedure :: clear => rings_clear
        !> Take the forces of a push and say which levels it completes.
        procedure :: store => rings_store
        !> Number of FFTW plan pairs (r2c and c2r) the rings' transforms own.
        procedure :: plan_count => rings_plan_count
    end type partition_rings

    !> Partitioned FFT convolution: a direct head and FFT levels of growing block size.
    type, extends(convolver) :: fft_convolver
        !> Kernel length N_g (taps 1..N_g).
        integer :: n_g = 0
        !> Head weights w_j = dt*g(t_j) [m/N], j = 1..H.
        real(dp), allocatable :: head_weight(:)
        !> The FFT levels, smallest block first (none when N_g <= H).
        type(fft_level), allocatable :: levels(:)
        !> Force rings, pending outputs, scratch and FFTW plans (one column: one point).
        type(partition_rings) :: rings
    contains
        procedure :: history => fft_history
        procedure :: push => fft_push
        procedure :: clear => fft_clear
        !> Destroy this object's FFTW plans now (it plans again if stepped further).
        procedure :: release => fft_release_plans
    end type fft_convolver

contains

    !> A partitioned-FFT convolver from kernel samples g(t_j) [m/(N*s)], j = 0..N_g, and step
    !> dt [s]: the kernel and the results of `new_direct_convolver(kernel, dt)`.
    function new_fft_convolver(kernel, dt, head, valid_steps) result(conv)
        !> Samples g(j*dt), j = 0..N_g, of the impulse response [m/(N*s)].
        real(dp), intent(in) :: kernel(0:)
        !> Time step [s].
        real(dp), intent(in) :: dt
        !> Number of taps H summed directly (default `default_head`; clipped to 1..N_g).
        integer, intent(in), optional :: head
        !> Number of steps the kernel is valid for, when it was cut at a run's length (default:
        !> any number).
        integer(int64), intent(in), optional :: valid_steps
        type(fft_convolver) :: conv

        real(dp), allocatable :: weight(:)
        integer :: n_g, n_head

        n_g = ubound(kernel, 1)
        n_head = default_head
        if (present(head)) n_head = head
        n_head = min(max(n_head, 1), n_g)
        allocate (weight(n_g))
        weight(:) = dt*kernel(1:n_g)
        call conv%set_model('fft', dt, n_g, 'N_g')
        conv%weight0 = dt*kernel(0)
        conv%n_g = n_g
        if (present(valid_steps)) conv%valid_steps = valid_steps
        allocate (conv%head_weight(n_head))
        conv%head_weight(:) = weight(1:n_head)
        call build_levels(conv, weight, n_head)
        ! The kernel spectra are made: the new object holds no plan (see the module notes).
        call conv%rings%plans%release()
        call conv%reset()
    end function new_fft_convolver

    !> Destroy the FFTW plans this object owns; stepping on plans again.
    subroutine fft_release_plans(self)
        !> The convolver.
        class(fft_convolver), intent(inout) :: self

        call self%rings%plans%release()
    end subroutine fft_release_plans

    !> Lay out the levels behind a head of n_head taps, size the rings and scratch arrays,
    !> and transform the partitions.
    subroutine build_levels(conv, weight, n_head)
        type(fft_convolver), intent(inout) :: conv
        real(dp), intent(in) :: weight(:)
        integer, intent(in) :: n_head

        integer :: blocks(bit_size(0)), parts(bit_size(0)), first(bit_size(0))
        integer :: n_levels, l

        call lay_out(conv%rings, size(weight), n_head, 1, n_levels, blocks, parts, first)
        allocate (conv%levels(n_levels))
        do l = 1, n_levels
            call build_level(conv%levels(l), weight, blocks(l), parts(l), first(l), conv%rings%samples, &
                             conv%rings%plans)
        end do
    end subroutine build_levels

    !> The levels' schedule (`partition_schedule`, whose optional arguments it hands on) and
    !> rings and scratch sized for it, for n_c points behind a head of n_head taps.
    subroutine lay_out(rings, n_g, n_head, n_c, n_levels, blocks, parts, first, level_parts, finish)
        !> The rings to size.
        type(partition_rings), intent(inout) :: rings
        !> Kernel length N_g (taps 1..N_g).
        integer, intent(in) :: n_g
        !> Number of taps H summed directly.
        integer, intent(in) :: n_head
        !> Number of points N_c (columns of the rings).
        integer, intent(in) :: n_c
        !> Number of levels L (0 when N_g <= H).
        integer, intent(out) :: n_levels
        !> Block size B_l, partition count P_l and first tap s_l of each level l = 1..L.
        integer, intent(out) :: blocks(:), parts(:), first(:)
        !> Partitions of a level that is not the last.
        integer, intent(in), optional :: level_parts
        !> Partitions that make a level the last.
        integer, intent(in), optional :: finish

        integer :: largest, span

        call partition_schedule(n_g, n_head, n_levels, blocks, parts, first, level_parts, finish)
        largest = 1
        span = 1
        if (n_levels > 0) then
            largest = blocks(n_levels)
            span = maxval(first(1:n_levels) + blocks(1:n_levels) - 1)
        end if
        rings%blocks = blocks(1:n_levels)
        allocate (rings%head_past(2*n_head, n_c), rings%recent(largest, n_c), rings%pending(span, n_c))
        allocate (rings%samples(2*largest), rings%spectrum(largest + 1))
    end subroutine lay_out

    !> The schedule: block size, partition count and first tap of each level (see the module
    !> notes); also the schedule of the multi-point engine (greenconv_conv_green_fft).
    pure subroutine partition_schedule(n_g, n_head, n_levels, blocks, parts, first, level_parts, finish)
        !> Kernel length N_g (taps 1..N_g).
        integer, intent(in) :: n_g
        !> Number of taps H summed directly.
        integer, intent(in) :: n_head
        !> Number of levels L (0 when N_g <= H).
        integer, intent(out) :: n_levels
        !> Block size B_l of each level l = 1..L (room for bit_size(0) levels).
        integer, intent(out) :: blocks(:)
        !> Partition count P_l of each level.
        integer, intent(out) :: parts(:)
        !> First tap s_l of each level.
        integer, intent(out) :: first(:)
        !> Partitions of a level that is not the last (default `parts_per_level`).
        integer, intent(in), optional :: level_parts
        !> A level that covers the remaining taps with at most this many partitions is the
        !> last (default `finish_parts`).
        integer, intent(in), optional :: finish

        integer :: block, start, count, per_level, last_parts

        per_level = parts_per_level
        if (present(level_parts)) per_level = level_parts
        last_parts = finish_parts
        if (present(finish)) last_parts = finish

        n_levels = 0
        block = max(n_head, 1)
        start = n_head + 1
        do while (start <= n_g)
            count = (n_g - start + block)/block
            if (count > last_parts) count = per_level
            n_levels = n_levels + 1
            blocks(n_levels) = block
            parts(n_levels) = count
            first(n_levels) = start
            start = start + count*block
            do while (2*block <= start)
                block = 2*block
            end do
        end do
    end subroutine partition_schedule

    !> One level: the scaled spectra of its zero-padded partitions, an empty delay line.
    subroutine build_level(level, weight, block, parts, first, samples, plans)
        type(fft_level), intent(out) :: level
        real(dp), intent(in) :: weight(:)
        integer, intent(in) :: block, parts, first
        real(dp), contiguous, intent(inout) :: samples(:)
        type(fft_plan_set), intent(inout) :: plans

        complex(dp) :: lines(block + 1)
        integer :: p, tap, last, lead

        level%block = block
        level%parts = parts
        level%first_tap = first
        lead = 4*((block + 4)/4)
        allocate (level%kernel_spectra(lead, parts), level%input_spectra(lead, parts))
        level%kernel_spectra(:, :) = (0.0_dp, 0.0_dp)
        do p = 1, parts
            tap = first + (p - 1)*block
            last = min(tap + block - 1, size(weight))
            samples(1:2*block) = 0.0_dp
            samples(1:last - tap + 1) = weight(tap:last)
            call plans%forward(samples(1:2*block), lines)
            level%kernel_spectra(1:block + 1, p) = lines/real(2*block, dp)
        end do
    end subroutine build_level

    !> History displacement u_h(n) [m]: the head's dot product (`dot` of greenconv_ident_dense,
    !> one fixed order of sums) plus the levels' pending sum; NaN from step `valid_steps` on.
    function fft_history(self) result(u)
        class(fft_convolver), intent(in) :: self
        real(dp) :: u

        integer :: h

        if (self%step >= self%valid_steps) then
            u = ieee_value(u, ieee_quiet_nan)
            return
        end if
        h = size(self%head_weight)
        associate (r => self%rings)
            u = dot(self%head_weight, r%head_past(r%head_position:r%head_position + h - 1, 1)) &
                + r%pending(r%pending_position, 1)
        end associate
    end function fft_history

    !> Store the force of step n, retire output n, advance, and run every level whose
    !> block has just been completed.
    subroutine fft_push(self, force)
        class(fft_convolver), intent(inout) :: self
        real(dp), intent(in) :: force

        integer :: l, n_due

        self%step = self%step + 1
        call self%rings%store([force], self%step, n_due)
        do l = 1, n_due
            call run_level(self, l)
        end do
    end subroutine fft_push

    !> Level l at step n (a multiple of its block size B): transform the block of forces
    !> n - B..n - 1, multiply-add against the partitions, and add the inverse transform to
    !> the pending outputs n - B + s..n + B + s - 2.
    subroutine run_level(self, l)
        class(fft_convolver), intent(inout) :: self
        integer, intent(in) :: l

        integer :: b, first, p, column

        associate (level => self%levels(l), r => self%rings)
            b = level%block
            first = int(mod(self%step - b, size(r%recent, 1, kind=int64))) + 1
            r%samples(1:b) = r%recent(first:first + b - 1, 1)
            r%samples(b + 1:2*b) = 0.0_dp
            level%newest = level%newest - 1
            if (level%newest < 1) level%newest = level%parts
            call r%plans%forward(r%samples(1:2*b), level%input_spectra(1:b + 1, level%newest))
            r%spectrum(1:b + 1) = level%kernel_spectra(1:b + 1, 1)*level%input_spectra(1:b + 1, level%newest)
            do p = 2, level%parts
                column = mod(level%newest + p - 2, level%parts) + 1
                r%spectrum(1:b + 1) = r%spectrum(1:b + 1) &
                                         + level%kernel_spectra(1:b + 1, p)*level%input_spectra(1:b + 1, column)
            end do
            call r%plans%inverse(r%spectrum(1:b + 1), r%samples(1:2*b))
            call add_to_ring(r%pending(:, 1), self%step - b + level%first_tap, r%samples(1:2*b - 1))
        end associate
    end subroutine run_level

    !> ring(n) += values(i) for n = start + i - 1, ring position mod(n, size(ring)) + 1.
    pure subroutine add_to_ring(ring, start, values)
        !> A ring of pending outputs [m] (size >= size(values)).
        real(dp), intent(inout) :: ring(:)
        !> Step n of the first value (>= 0).
        integer(int64), intent(in) :: start
        !> Contributions [m] to outputs start, start + 1, ...
        real(dp), intent(in) :: values(:)

        integer :: i0, n1, m

        m = size(values)
        i0 = int(mod(start, size(ring, kind=int64))) + 1
        n1 = min(m, size(ring) - i0 + 1)
        ring(i0:i0 + n1 - 1) = ring(i0:i0 + n1 - 1) + values(1:n1)
        ring(1:m - n1) = ring(1:m - n1) + values(n1 + 1:m)
    end subroutine add_to_ring

    !> No force pushed yet: empty delay lines of block spectra, empty rings.
    subroutine fft_clear(self)
        class(fft_convolver), intent(inout) :: self

        integer :: l

        do l = 1, size(self%levels)
            self%levels(l)%input_spectra(:, :) = (0.0_dp, 0.0_dp)
        end do
        self%levels(:)%newest = 1
        call self%rings%clear()
    end subroutine fft_clear


    !> Empty rings of forces and outputs, every position at its start, the count down at the
    !> smallest block (huge without levels).
    subroutine rings_clear(self)
        !> The rings.
        class(partition_rings), intent(inout) :: self

        self%head_past(:, :) = 0.0_dp
        self%head_position = 1
        self%recent(:, :) = 0.0_dp
        self%recent_position = 1
        self%pending(:, :) = 0.0_dp
        self%pending_position = 1
        self%countdown = huge(0)
        if (size(self%blocks) > 0) self%countdown = self%blocks(1)
    end subroutine rings_clear

    !> Take the forces of step n - 1 into the head and the recent forces, retire output n - 1,
    !> and count the levels the push completes: levels 1..n_due, those whose block size
    !> divides n (each block size divides the next, so they are the first ones).
    subroutine rings_store(self, forces, step, n_due)
        !> The rings.
        class(partition_rings), intent(inout) :: self
        !> The forces of the push [N], one per point.
        real(dp), intent(in) :: forces(:)
        !> The step n after the push.
        integer(int64), intent(in) :: step
        !> Number of levels whose block the push completes.
        integer, intent(out) :: n_due

        integer :: h

        h = size(self%head_past, 1)/2
        if (h > 0) then
            self%head_position = self%head_position - 1
            if (self%head_position < 1) self%head_position = h
            self%head_past(self%head_position, :) = forces
            self%head_past(self%head_position + h, :) = forces
        end if
        self%recent(self%recent_position, :) = forces
        self%recent_position = self%recent_position + 1
        if (self%recent_position > size(self%recent, 1)) self%recent_position = 1
        self%pending(self%pending_position, :) = 0.0_dp
        self%pending_position = self%pending_position + 1
        if (self%pending_position > size(self%pending, 1)) self%pending_position = 1
        n_due = 0
        self%countdown = self%countdown - 1
        if (self%countdown > 0 .or. size(self%blocks) == 0) return
        self%countdown = self%blocks(1)
        do while (n_due < size(self%blocks))
            if (mod(step, int(self%blocks(n_due + 1), int64)) /= 0) exit
            n_due = n_due + 1
        end do
    end subroutine rings_store

    !> Number of FFTW plan pairs (r2c and c2r) the engine owns.
    function rings_plan_count(self) result(count)
        !> The rings.
        class(partition_rings), intent(in) :: self
        integer :: count

        count = self%plans%plan_count()
    end function rings_plan_count

end module greenconv_conv_fft
