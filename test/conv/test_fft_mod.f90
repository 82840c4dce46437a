!> The `fft` engine (greenconv_conv_fft) against `direct` (greenconv_conv_direct), which sums the same
!> truncated kernel w_0 = dt*g_0, w_j = dt*g_j (j = 1..N_g) with the same one step of latency.
!>
!> Tolerance: 1e-12 relative, max|u_fft - u_direct|/max|u_direct| over the run, with
!> u = history + w0*q for both. FFT convolution errs by about 1e-16*log2(N_g) of
!> sum_j |w_j*q|, which for these kernels and loads is within a factor 100 of max|u|.
!> Runs last at least 3*N_g steps, so that every level's delay line and every ring wraps
!> around several times. For N_g > 4097 `direct` is asked for its history (N_g operations)
!> only every 13th step, so that the suite stays fast in the debug profile; both engines
!> are pushed every step, and 13 is odd, so every phase of every power-of-two block is
!> checked.
module test_fft_mod
    use, intrinsic :: iso_fortran_env, only: dp => real64
    use, intrinsic :: iso_c_binding, only: c_loc, c_f_pointer
    use, intrinsic :: ieee_arithmetic, only: ieee_is_nan
    use testsuite_mod, only: test_error, unittest_type, new_unittest, check, note
    use greenconv_core_random, only: random_stream
    use greenconv_model_sdof, only: sdof_modes
    use greenconv_conv_direct, only: direct_convolver, new_direct_convolver
    use greenconv_conv_kernel, only: sample_kernel
    use greenconv_conv_fft, only: fft_convolver, new_fft_convolver, default_head
    use greenconv_ext_fftw, only: fft_plan_set, forward_real_fft
    use greenconv_core_error, only: error_type
    implicit none
    private

    public :: collect_fft

    !> Largest load magnitude [N].
    real(dp), parameter :: force = 10.0_dp
    !> Time step of the random kernels [s].
    real(dp), parameter :: dt_random = 1.0e-4_dp
    !> Relative tolerance of fft against direct.
    real(dp), parameter :: tolerance = 1.0e-12_dp

contains

    !> Tests of the partitioned FFT engine.
    subroutine collect_fft(testsuite)
        type(unittest_type), allocatable, intent(out) :: testsuite(:)

        testsuite = [new_unittest('fft equals direct: random kernels, N_g = 1 to 19000', test_random_kernels), &
                     new_unittest('fft equals direct: heads of 1, 3 and 16 taps', test_small_heads), &
                     new_unittest('fft equals direct: sdof kernel, dt = 10 us, 1 % rule', test_sdof), &
                     new_unittest('fft: partitions tile taps H+1..N_g, each due after its block', test_schedule), &
                     new_unittest('fft: reset then rerun gives identical results', test_reset), &
                     new_unittest('fft: release mid-run changes nothing', test_release_plans), &
                     new_unittest('fft: a copy made mid-run continues like the original', test_copy), &
                     new_unittest('plan set: arrays at every 8-byte offset, against one-shot FFTs', test_plan_set), &
                     new_unittest('fft: two convolvers interleaved equal each run alone', test_interleaved)]
    end subroutine collect_fft

    !> Kernel samples g_j in [-1, 1) [m/(N*s)], j = 0..n_g, from a seed.
    function random_kernel(n_g, seed) result(kernel)
        integer, intent(in) :: n_g, seed
        real(dp), allocatable :: kernel(:)

        type(random_stream) :: stream
        integer :: j

        allocate (kernel(0:n_g))
        stream = random_stream(seed)
        do j = 0, n_g
            kernel(j) = stream%between(-1.0_dp, 1.0_dp)
        end do
    end function random_kernel

    !> Drive both engines with the same random loads in [-F, F] for n_steps steps; compare
    !> u = history + w0*q every `stride` steps. Returns max|u_fft - u_direct| and max|u_direct|.
    subroutine compare(fft, direct, n_steps, seed, stride, worst, peak)
        type(fft_convolver), intent(inout) :: fft
        type(direct_convolver), intent(inout) :: direct
        integer, intent(in) :: n_steps, seed, stride
        real(dp), intent(out) :: worst, peak

        type(random_stream) :: stream
        real(dp) :: q, u_fft, u_direct
        integer :: n

        stream = random_stream(seed)
        call fft%reset()
        call direct%reset()
        worst = 0.0_dp
        peak = 0.0_dp
        do n = 0, n_steps - 1
            q = stream%between(-force, force)
            if (mod(n, stride) == 0) then
                u_fft = fft%history() + fft%instant_weight()*q
                u_direct = direct%history() + direct%instant_weight()*q
                worst = max(worst, abs(u_fft - u_direct))
                peak = max(peak, abs(u_direct))
            end if
            call fft%push(q)
            call direct%push(q)
        end do
    end subroutine compare

    !> Relative difference of fft and direct on a random kernel of n_g taps behind a head
    !> of n_head taps, over 3*n_g + 200 steps.
    function random_case(n_g, n_head) result(relative)
        integer, intent(in) :: n_g, n_head
        real(dp) :: relative

        type(fft_convolver) :: fft
        type(direct_convolver) :: direct
        real(dp), allocatable :: kernel(:)
        real(dp) :: worst, peak
        integer :: stride

        allocate (kernel(0:n_g))
        kernel(:) = random_kernel(n_g, n_g)
        fft = new_fft_convolver(kernel, dt_random, n_head)
        direct = new_direct_convolver(kernel, dt_random)
        stride = 1
        if (n_g > 4097) stride = 13
        call compare(fft, direct, 3*n_g + 200, 1000 + n_g, stride, worst, peak)
        relative = worst/peak
    end function random_case

    !> N_g in {1, 10, 63, 64, 65, 1000, 4097, 19000} with the default head (64 taps):
    !> head alone up to N_g = 64, then FFT levels; w0 = dt*g_0 != 0 throughout.
    subroutine test_random_kernels(error)
        type(test_error), allocatable, intent(out) :: error

        integer, parameter :: sizes(8) = [1, 10, 63, 64, 65, 1000, 4097, 19000]
        real(dp) :: relative(size(sizes))
        integer :: i

        do i = 1, size(sizes)
            relative(i) = random_case(sizes(i), default_head)
            call check(error, relative(i), 0.0_dp, 'fft against direct, random kernel', thr=tolerance)
            if (allocated(error)) then
                call note('N_g', real(sizes(i), dp))
                return
            end if
        end do
        call note('N_g = 1000', relative(6))
        call note('N_g = 4097', relative(7))
        call note('N_g = 19000', relative(8))
        call note('worst', maxval(relative))
    end subroutine test_random_kernels

    !> Short heads put FFT levels on short kernels, with non-power-of-two transform sizes
    !> for H = 3 (6, 12, 24, ... points): N_g in {1, 10, 63, 64, 65, 1000}.
    subroutine test_small_heads(error)
        type(test_error), allocatable, intent(out) :: error

        integer, parameter :: sizes(6) = [1, 10, 63, 64, 65, 1000], heads(3) = [1, 3, 16]
        real(dp) :: relative, worst
        integer :: i, h

        worst = 0.0_dp
        do h = 1, size(heads)
            do i = 1, size(sizes)
                relative = random_case(sizes(i), heads(h))
                worst = max(worst, relative)
                call check(error, relative, 0.0_dp, 'fft against direct, small head', thr=tolerance)
                if (allocated(error)) then
                    call note('N_g', real(sizes(i), dp))
                    call note('H', real(heads(h), dp))
                    return
                end if
            end do
        end do
        call note('worst', worst)
    end subroutine test_small_heads

    !> Tab. 1's oscillator (M = 1 kg, K = 1e6 N/m, xi = 0.02) at dt = 10 us, its kernel
    !> truncated by the paper's 1 % rule (sample_kernel), random loads over 3*N_g steps.
    subroutine test_sdof(error)
        type(test_error), allocatable, intent(out) :: error

        real(dp), parameter :: dt = 1.0e-5_dp
        type(fft_convolver) :: fft
        type(direct_convolver) :: direct
        real(dp), allocatable :: kernel(:)
        real(dp) :: tail, worst, peak
        integer :: n_g

        call sample_kernel(sdof_modes(1.0_dp, 1.0e6_dp, 0.02_dp), dt, 0.01_dp, 1000000, kernel, tail)
        n_g = ubound(kernel, 1)
        fft = new_fft_convolver(kernel, dt)
        direct = new_direct_convolver(kernel, dt)
        call compare(fft, direct, 3*n_g, 77, 13, worst, peak)
        call note('N_g', real(n_g, dp))
        call note('steps', real(3*n_g, dp))
        call note('max|u_fft - u_direct|/max|u|', worst/peak)
        call check(error, n_g >= 19000 .and. n_g <= 24000, 'N_g of the 1 % rule in 19000..24000')
        if (allocated(error)) return
        call check(error, worst/peak, 0.0_dp, 'fft against direct, sdof kernel', thr=tolerance)
    end subroutine test_sdof

    !> For several N_g and heads: the head and the levels' partitions tile taps 1..N_g with
    !> no gap or overlap (the last partition may run past N_g, by less than one block), each
    !> level starts at a tap s >= B (its outputs are due no earlier than its block is
    !> complete), blocks are H*2^k and grow; plus the engine's name, model size and w0.
    subroutine test_schedule(error)
        type(test_error), allocatable, intent(out) :: error

        integer, parameter :: sizes(6) = [1, 65, 1000, 4097, 19000, 100000], heads(3) = [1, 3, 64]
        type(fft_convolver) :: fft
        real(dp), allocatable :: kernel(:)
        character(len=:), allocatable :: label
        integer :: i, h, l, tap, n, b
        logical :: ok

        ok = .true.
        do h = 1, size(heads)
            do i = 1, size(sizes)
                fft = new_fft_convolver(random_kernel(sizes(i), 1), dt_random, heads(h))
                tap = size(fft%head_weight) + 1
                do l = 1, size(fft%levels)
                    b = fft%levels(l)%block
                    ok = ok .and. fft%levels(l)%first_tap == tap .and. tap >= b .and. fft%levels(l)%parts >= 1
                    ok = ok .and. mod(b, size(fft%head_weight)) == 0 .and. popcnt(b/size(fft%head_weight)) == 1
                    if (l > 1) ok = ok .and. b > fft%levels(l - 1)%block
                    tap = tap + fft%levels(l)%parts*b
                end do
                ok = ok .and. tap > sizes(i)
                if (size(fft%levels) > 0) ok = ok .and. tap - fft%levels(size(fft%levels))%block <= sizes(i)
            end do
        end do
        call check(error, ok, 'partitions tile the kernel, s >= B, blocks H*2^k growing')
        if (allocated(error)) return
        fft = new_fft_convolver(random_kernel(19000, 1), dt_random)
        call note('levels at N_g = 19000', real(size(fft%levels), dp))
        call note('largest block', real(fft%levels(size(fft%levels))%block, dp))
        call note('its partitions', real(fft%levels(size(fft%levels))%parts, dp))
        call fft%model_size(n, label)
        call check(error, fft%name == 'fft' .and. label == 'N_g' .and. n == 19000, 'name fft, model size N_g')
        if (allocated(error)) return
        allocate (kernel(0:19000))
        kernel(:) = random_kernel(19000, 1)
        call check(error, fft%instant_weight(), dt_random*kernel(0), 'w0 = dt*g_0', thr=0.0_dp)
    end subroutine test_schedule

    !> N_g = 1000 behind a 16-tap head, 5000 steps; reset; the same loads again: every u
    !> identical to the bit, and the step counter back at 0.
    subroutine test_reset(error)
        type(test_error), allocatable, intent(out) :: error

        integer, parameter :: n_steps = 5000
        type(fft_convolver) :: fft
        real(dp) :: first(n_steps), second(n_steps)

        fft = new_fft_convolver(random_kernel(1000, 5), dt_random, 16)
        call run(fft, n_steps, 21, first)
        call fft%reset()
        call check(error, fft%step == 0, 'step counter 0 after reset')
        if (allocated(error)) return
        call run(fft, n_steps, 21, second)
        call note('max|first - second|', maxval(abs(first - second)))
        call check(error, maxval(abs(first - second)), 0.0_dp, 'identical results after reset', thr=0.0_dp)
    end subroutine test_reset

    !> The object's plans destroyed at step 3000, then the run continued: the same numbers to
    !> the bit as the same object run straight through after a reset, and the object plans
    !> again on demand. A new object holds no plan.
    subroutine test_release_plans(error)
        type(test_error), allocatable, intent(out) :: error

        integer, parameter :: n_first = 3000, n_more = 4000
        type(fft_convolver) :: fft
        real(dp) :: reference(n_first + n_more), before(n_first), after(n_more)
        integer :: count_new, count_after_release

        fft = new_fft_convolver(random_kernel(2500, 9), dt_random, 16)
        count_new = fft%rings%plan_count()
        call run(fft, n_first + n_more, 33, reference)
        call fft%reset()
        call run(fft, n_first, 33, before)
        call fft%release()
        count_after_release = fft%rings%plan_count()
        call continue_run(fft, n_first, n_more, 33, after)
        call note('plans of a new object', real(count_new, dp))
        call note('plans after the run', real(fft%rings%plan_count(), dp))
        call check(error, count_new == 0 .and. count_after_release == 0 .and. fft%rings%plan_count() > 0, &
                   'none when new, none after release, then planned again')
        if (allocated(error)) return
        call check(error, maxval(abs([before, after] - reference)), 0.0_dp, &
                   'identical results across release', thr=0.0_dp)
        call fft%release()
    end subroutine test_release_plans

    !> Two fft convolvers on different kernels, stepped in turn in one loop (each planning on
    !> its own), give to the bit what each gives when run alone: no state is shared.
    subroutine test_interleaved(error)
        type(test_error), allocatable, intent(out) :: error

        integer, parameter :: n_steps = 6000
        type(fft_convolver) :: first, second
        type(random_stream) :: stream_first, stream_second
        real(dp) :: alone_first(n_steps), alone_second(n_steps), both_first(n_steps), both_second(n_steps)
        real(dp) :: q
        integer :: n

        first = new_fft_convolver(random_kernel(3000, 41), dt_random, 32)
        second = new_fft_convolver(random_kernel(1700, 42), dt_random)
        call run(first, n_steps, 51, alone_first)
        call run(second, n_steps, 52, alone_second)
        call first%reset()
        call second%reset()
        stream_first = random_stream(51)
        stream_second = random_stream(52)
        do n = 1, n_steps
            q = stream_first%between(-force, force)
            both_first(n) = first%history() + first%instant_weight()*q
            call first%push(q)
            q = stream_second%between(-force, force)
            both_second(n) = second%history() + second%instant_weight()*q
            call second%push(q)
        end do
        call note('max|interleaved - alone|, first', maxval(abs(both_first - alone_first)))
        call note('max|interleaved - alone|, second', maxval(abs(both_second - alone_second)))
        call check(error, maxval(abs(both_first - alone_first)) + maxval(abs(both_second - alone_second)), 0.0_dp, &
                   'interleaved runs identical to single runs', thr=0.0_dp)
        call first%release()
        call second%release()
    end subroutine test_interleaved

    !> A convolver copied by intrinsic assignment at step 3000, then both continued with
    !> the same loads, the copy first, its plans released before the original goes on: the
    !> copy owns its state and plans (the original is not disturbed) and agrees
    !> with it to round-off, 1e-14 of max|u| (its arrays may sit at other alignments and
    !> get other FFTW plans, so the bits may differ).
    subroutine test_copy(error)
        type(test_error), allocatable, intent(out) :: error

        integer, parameter :: n_first = 3000, n_more = 4000
        type(fft_convolver) :: fft, copy
        real(dp) :: reference(n_first + n_more), before(n_first), after(n_more), copied(n_more)
        real(dp) :: difference

        fft = new_fft_convolver(random_kernel(2500, 9), dt_random, 16)
        call run(fft, n_first + n_more, 34, reference)
        call fft%reset()
        call run(fft, n_first, 34, before)
        copy = fft
        call continue_run(copy, n_first, n_more, 34, copied)
        ! The copy made plans of its own; releasing them leaves the original's intact.
        call copy%release()
        call continue_run(fft, n_first, n_more, 34, after)
        difference = maxval(abs(copied - after))/maxval(abs(after))
        call note('max|u_copy - u|/max|u|', difference)
        call check(error, maxval(abs(after - reference(n_first + 1:))), 0.0_dp, 'original undisturbed by its copy', &
                   thr=0.0_dp)
        if (allocated(error)) return
        call check(error, difference, 0.0_dp, 'copy against original', thr=1.0e-14_dp)
        call fft%release()
    end subroutine test_copy

    !> A plan set's transforms on real and complex arrays starting at every 8-byte offset
    !> modulo 64 (one set per placement, released after use; one plan pair each): forward against the one-shot
    !> forward_real_fft to 1e-14 of max|Y|, inverse(forward(y)) = n*y to 1e-14 of n*max|y|,
    !> for n = 6, 64 and 1000; a size mismatch gives NaN.
    subroutine test_plan_set(error)
        type(test_error), allocatable, intent(out) :: error

        integer, parameter :: sizes(3) = [6, 64, 1000]
        real(dp), allocatable, target :: real_buffer(:), complex_buffer(:)
        real(dp), allocatable :: reference_samples(:)
        complex(dp), allocatable :: reference(:)
        complex(dp), pointer, contiguous :: spectrum(:)
        type(error_type), allocatable :: fft_error
        type(fft_plan_set) :: plans
        type(random_stream) :: stream
        real(dp) :: worst_forward, worst_inverse
        integer :: i, j, k, n, most_plans

        worst_forward = 0.0_dp
        worst_inverse = 0.0_dp
        most_plans = 0
        stream = random_stream(3)
        do i = 1, size(sizes)
            n = sizes(i)
            allocate (real_buffer(n + 8), complex_buffer(2*(n/2 + 1) + 8), reference_samples(n), reference(n/2 + 1))
            do j = 1, n
                reference_samples(j) = stream%between(-1.0_dp, 1.0_dp)
            end do
            call forward_real_fft(reference_samples, reference, fft_error)
            call check(error, .not. allocated(fft_error), 'one-shot forward_real_fft')
            if (allocated(error)) return
            do j = 0, 7
                do k = 0, 7
                    real_buffer(:) = 0.0_dp
                    real_buffer(j + 1:j + n) = reference_samples
                    call c_f_pointer(c_loc(complex_buffer(k + 1)), spectrum, [n/2 + 1])
                    call plans%forward(real_buffer(j + 1:j + n), spectrum)
                    worst_forward = max(worst_forward, maxval(abs(spectrum - reference))/maxval(abs(reference)))
                    call plans%inverse(spectrum, real_buffer(j + 1:j + n))
                    worst_inverse = max(worst_inverse, maxval(abs(real_buffer(j + 1:j + n) - n*reference_samples)) &
                                        /(n*maxval(abs(reference_samples))))
                    most_plans = max(most_plans, plans%plan_count())
                    call plans%release()
                end do
            end do
            deallocate (real_buffer, complex_buffer, reference_samples, reference)
        end do
        call note('forward', worst_forward)
        call note('inverse', worst_inverse)
        call note('most plan pairs in one set', real(most_plans, dp))
        call check(error, worst_forward, 0.0_dp, 'plan set forward against one-shot', thr=1.0e-14_dp)
        if (allocated(error)) return
        call check(error, worst_inverse, 0.0_dp, 'plan set inverse of forward', thr=1.0e-14_dp)
        if (allocated(error)) return
        call check(error, most_plans == 1, 'one plan pair per size and placement')
        if (allocated(error)) return
        allocate (reference_samples(8), reference(4))
        reference_samples(:) = 1.0_dp
        call plans%forward(reference_samples, reference)
        call check(error, all(ieee_is_nan(real(reference, dp))), 'NaN on a size mismatch')
        call plans%release()
    end subroutine test_plan_set

    !> u = history + w0*q for n_steps random loads from the start.
    subroutine run(conv, n_steps, seed, u)
        type(fft_convolver), intent(inout) :: conv
        integer, intent(in) :: n_steps, seed
        real(dp), intent(out) :: u(:)

        call continue_run(conv, 0, n_steps, seed, u)
    end subroutine run

    !> Steps skip + 1..skip + n_steps of the random load of `seed`, from the current state.
    subroutine continue_run(conv, skip, n_steps, seed, u)
        type(fft_convolver), intent(inout) :: conv
        integer, intent(in) :: skip, n_steps, seed
        real(dp), intent(out) :: u(:)

        type(random_stream) :: stream
        real(dp) :: q
        integer :: n

        stream = random_stream(seed)
        do n = 1, skip
            q = stream%between(-force, force)
        end do
        do n = 1, n_steps
            q = stream%between(-force, force)
            u(n) = conv%history() + conv%instant_weight()*q
            call conv%push(q)
        end do
    end subroutine continue_run

end module test_fft_mod
