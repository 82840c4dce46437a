!> Thin wrapper of the FFTW3 real-data transforms that greenconv uses.
!>
!> The `bind(c)` interfaces below are written from FFTW's documented C prototypes
!> (fftw3.h, "Real-data DFTs" in the FFTW manual): plans are `type(c_ptr)`, the
!> `unsigned flags` argument is passed as `integer(c_int), value`.
!>
!> What the front ends compute (FFTW's unnormalized definitions, n samples, m = n/2 + 1 lines):
!>
!>     forward_real_fft:  Y_k = sum_{j=0}^{n-1} y_j*exp(-2*pi*i*j*k/n),  k = 0..m-1
!>     inverse_real_fft:  y_j = sum_{k=0}^{n-1} Y_k*exp(+2*pi*i*j*k/n),  j = 0..n-1,
!>                        with Y_{n-k} = conj(Y_k) implied; the imaginary parts of Y_0
!>                        and (n even) Y_{n/2} are ignored.
!>
!> so inverse(forward(y)) = n*y. Scaling to physical units is the caller's business.
!>
!> One-shot transforms (`forward_real_fft`, `inverse_real_fft`): each call copies its data
!> to private contiguous arrays, makes the plan pair of a plan set for arrays placed as
!> these are (FFTW_ESTIMATE, see below), executes the plan it needs and destroys both.
!> Simple and correct for occasional use.
!>
!> Repeated transforms (`fft_plan_set`, used by the partitioned FFT convolver): an object
!> owns the plans it executes, applied to the caller's arrays with FFTW's new-array
!> execute functions. These require the new arrays to have the alignment of the arrays the
!> plan was made on (or the plan to be made with FFTW_UNALIGNED, which forbids FFTW's SIMD
!> codelets and costs about a factor 2 here). Fortran's `allocate` guarantees no particular
!> alignment, so a plan set keys its plans by the transform size n and by the byte offsets,
!> modulo 64, of the real and the complex array they are executed on; its r2c and c2r plans
!> are made with FFTW_ESTIMATE (which never touches the arrays) on scratch arrays placed at
!> exactly those offsets. The new arrays then have the planned alignment by construction,
!> whatever FFTW's SIMD alignment is (16, 32 or 64 bytes), and SIMD is kept. (Should no
!> scratch position match, the plans are made with FFTW_UNALIGNED instead.) The plans are
!> always out-of-place. Results are reproducible to the bit for the same arrays; arrays at
!> other offsets may get another plan and differ in the last bits.
!>
!> Ownership: a plan set makes a pair of plans the first time it meets a size and placement
!> (at most `max_pairs` pairs; past that a transform gives NaN), and destroys them in
!> `release`. It records its own address when it plans; a copy (intrinsic assignment,
!> `source=`) sits elsewhere, recognises the plans as its original's, forgets them without
!> destroying them and plans for itself at its first transform. So objects holding a plan set
!> may be copied, and original and copy used and released independently. There is no
!> process-wide state. There is no finalizer either (gfortran 12 finalizes uninitialised
!> memory when an intent(out) polymorphic allocatable is deallocated): a set that is dropped
!> without `release` leaves its plans allocated in FFTW, a few kilobytes per plan pair.
!>
!> Threads: executing a plan (FFTW's new-array execute functions) is thread-safe, so
!> independent objects may transform concurrently. FFTW's planner (plan creation and
!> destruction) is not re-entrant: every call of it here is inside the OpenMP critical
!> section `greenconv_fftw_planner`, so with greenconv compiled with OpenMP (-fopenmp) any
!> number of OpenMP threads may each build, step and free their own objects. Compiled
!> without OpenMP the directive is a comment: then create, first run and release objects
!> that plan from one thread at a time (or call FFTW's fftw_make_planner_thread_safe from
!> libfftw3_threads once before starting threads). One object is never safe to use from two
!> threads at once.
module greenconv_ext_fftw
    use, intrinsic :: iso_c_binding, only: c_int, c_double, c_double_complex, c_ptr, c_associated, &
                                           c_null_ptr, c_loc, c_f_pointer, c_intptr_t
    use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
    use greenconv_core_kinds, only: dp
    use greenconv_core_error, only: error_type, fatal_error, stat_numerical
    implicit none
    private

    public :: forward_real_fft, inverse_real_fft
    public :: fft_plan_set

    !> Planner flag FFTW_ESTIMATE (1U << 6 in fftw3.h): cheap heuristic plan, arrays untouched.
    integer(c_int), parameter :: fftw_estimate = 64_c_int
    !> Planner flag FFTW_UNALIGNED (1U << 1 in fftw3.h): no alignment assumed (no SIMD).
    integer(c_int), parameter :: fftw_unaligned = 2_c_int

    !> Alignment period [bytes] of the plan keys: the largest SIMD alignment FFTW uses.
    integer, parameter :: period = 64

    !> The r2c and c2r plans of one transform size and one placement of the arrays.
    type :: plan_pair
        !> Transform size n (real samples).
        integer :: n = 0
        !> Byte offset modulo `period` of the real array (samples).
        integer :: real_offset = 0
        !> Byte offset modulo `period` of the complex array (spectrum).
        integer :: complex_offset = 0
        !> Plan of the forward (r2c) transform.
        type(c_ptr) :: forward = c_null_ptr
        !> Plan of the inverse (c2r) transform.
        type(c_ptr) :: inverse = c_null_ptr
    end type plan_pair

    !> Most plan pairs one set holds (one per transform size and array placement it meets; the
    !> partitioned FFT convolver needs one per level, and its schedule has at most bit_size(0)).
    integer, parameter :: max_pairs = 32

    !> The FFTW plans one object executes, keyed by transform size and array placement, owned
    !> by that object (see the module notes on ownership and threads). Default-initialised
    !> empty; plans are made on demand by `forward` and `inverse` and destroyed by `release`.
    type :: fft_plan_set
        private
        !> Number of plan pairs in use, entries 1..count of `pairs`.
        integer :: count = 0
        !> Address of this set when it made its plans (0: none made); a copy sits elsewhere,
        !> which tells it the plans are not its own.
        integer(c_intptr_t) :: owner = 0_c_intptr_t
        !> The plan pairs.
        type(plan_pair) :: pairs(max_pairs)
    contains
        !> Forward real DFT of an array by this set's plans.
        procedure :: forward => set_forward
        !> Inverse real DFT of an array by this set's plans.
        procedure :: inverse => set_inverse
        !> Destroy the plans this set owns and empty it.
        procedure :: release => set_release
        !> Number of plan pairs the set owns.
        procedure :: plan_count => set_plan_count
    end type fft_plan_set

    interface
        !> fftw_plan fftw_plan_dft_r2c_1d(int n, double *in, fftw_complex *out, unsigned flags)
        function fftw_plan_dft_r2c_1d(n, in, out, flags) bind(c, name='fftw_plan_dft_r2c_1d') result(plan)
            import :: c_int, c_double, c_double_complex, c_ptr
            implicit none
            integer(c_int), value :: n
            real(c_double), intent(inout) :: in(*)
            complex(c_double_complex), intent(inout) :: out(*)
            integer(c_int), value :: flags
            type(c_ptr) :: plan
        end function fftw_plan_dft_r2c_1d

        !> fftw_plan fftw_plan_dft_c2r_1d(int n, fftw_complex *in, double *out, unsigned flags)
        function fftw_plan_dft_c2r_1d(n, in, out, flags) bind(c, name='fftw_plan_dft_c2r_1d') result(plan)
            import :: c_int, c_double, c_double_complex, c_ptr
            implicit none
            integer(c_int), value :: n
            complex(c_double_complex), intent(inout) :: in(*)
            real(c_double), intent(inout) :: out(*)
            integer(c_int), value :: flags
            type(c_ptr) :: plan
        end function fftw_plan_dft_c2r_1d

        !> void fftw_execute_dft_r2c(const fftw_plan p, double *in, fftw_complex *out)
        !> (`in` is declared intent(in): every plan here is out-of-place and made without
        !> FFTW_DESTROY_INPUT, and FFTW then preserves the input of an r2c transform).
        subroutine fftw_execute_dft_r2c(plan, in, out) bind(c, name='fftw_execute_dft_r2c')
            import :: c_double, c_double_complex, c_ptr
            implicit none
            type(c_ptr), value :: plan
            real(c_double), intent(in) :: in(*)
            complex(c_double_complex), intent(inout) :: out(*)
        end subroutine fftw_execute_dft_r2c

        !> void fftw_execute_dft_c2r(const fftw_plan p, fftw_complex *in, double *out)
        !> (the input is destroyed by default for c2r transforms).
        subroutine fftw_execute_dft_c2r(plan, in, out) bind(c, name='fftw_execute_dft_c2r')
            import :: c_double, c_double_complex, c_ptr
            implicit none
            type(c_ptr), value :: plan
            complex(c_double_complex), intent(inout) :: in(*)
            real(c_double), intent(inout) :: out(*)
        end subroutine fftw_execute_dft_c2r

        !> void fftw_destroy_plan(fftw_plan p)
        subroutine fftw_destroy_plan(plan) bind(c, name='fftw_destroy_plan')
            import :: c_ptr
            implicit none
            type(c_ptr), value :: plan
        end subroutine fftw_destroy_plan
    end interface

contains

    !> Unnormalized forward real DFT: spectrum(k) = sum_j samples(j)*exp(-2*pi*i*j*k/n),
    !> n = size(samples), k = 0..n/2 (size(spectrum) must be n/2 + 1).
    subroutine forward_real_fft(samples, spectrum, error)
        !> Real samples y_j, j = 0..n-1, n >= 1 (any unit u).
        real(dp), intent(in) :: samples(:)
        !> Lines Y_k, k = 0..n/2 [u].
        complex(dp), intent(out) :: spectrum(:)
        !> Set on a size mismatch or when FFTW cannot plan the transform.
        type(error_type), allocatable, intent(out) :: error

        real(dp), allocatable :: copy(:)

        allocate (copy, source=samples)
        call transform_once('forward_real_fft', .true., copy, spectrum, error)
    end subroutine forward_real_fft

    !> Unnormalized inverse real DFT: samples(j) = sum_k spectrum(k)*exp(+2*pi*i*j*k/n) over the
    !> Hermitian-completed spectrum, n = size(samples), size(spectrum) = n/2 + 1.
    subroutine inverse_real_fft(spectrum, samples, error)
        !> Lines Y_k, k = 0..n/2 (any unit u); Im Y_0 and, n even, Im Y_{n/2} are ignored.
        complex(dp), intent(in) :: spectrum(:)
        !> Real samples y_j, j = 0..n-1 [u].
        real(dp), intent(out) :: samples(:)
        !> Set on a size mismatch or when FFTW cannot plan the transform.
        type(error_type), allocatable, intent(out) :: error

        complex(dp), allocatable :: copy(:)

        allocate (copy, source=spectrum)
        call transform_once('inverse_real_fft', .false., samples, copy, error)
    end subroutine inverse_real_fft

    !> A one-shot transform (`name`, for messages): forward, `samples` into `spectrum`, or
    !> inverse, `spectrum` into `samples`, on private contiguous copies (`plan_once`) with plans
    !> made for them and destroyed; the other argument is left as it was.
    subroutine transform_once(name, forward, samples, spectrum, error)
        character(len=*), intent(in) :: name
        logical, intent(in) :: forward
        real(dp), intent(inout) :: samples(:)
        complex(dp), intent(inout) :: spectrum(:)
        type(error_type), allocatable, intent(out) :: error

        real(c_double), allocatable, target :: real_array(:)
        complex(c_double_complex), allocatable, target :: complex_array(:)
        type(plan_pair) :: plans

        call plan_once(name, size(samples), size(spectrum), real_array, complex_array, plans, error)
        if (allocated(error)) return
        if (forward) then
            real_array(:) = samples
            call fftw_execute_dft_r2c(plans%forward, real_array, complex_array)
            spectrum(:) = complex_array
        else
            complex_array(:) = spectrum
            call fftw_execute_dft_c2r(plans%inverse, complex_array, real_array)
            samples(:) = real_array
        end if
        call destroy_pair(plans)
    end subroutine transform_once

    !> For a one-shot transform (`name`, for messages) of n real samples and m lines: check
    !> m = n/2 + 1, allocate the private contiguous copies `real_array` (n) and
    !> `complex_array` (m), and plan both transforms for arrays placed as they are.
    subroutine plan_once(name, n, m, real_array, complex_array, plans, error)
        character(len=*), intent(in) :: name
        integer, intent(in) :: n, m
        real(c_double), allocatable, target, intent(out) :: real_array(:)
        complex(c_double_complex), allocatable, target, intent(out) :: complex_array(:)
        type(plan_pair), intent(out) :: plans
        type(error_type), allocatable, intent(out) :: error

        if (n < 1 .or. m /= n/2 + 1) then
            call fatal_error(error, name//': expected n/2 + 1 spectrum lines for n samples', stat_numerical)
            return
        end if
        allocate (real_array(n), complex_array(m))
        call make_plans(n, offset_of(c_loc(real_array)), offset_of(c_loc(complex_array)), plans)
        if (.not. (c_associated(plans%forward) .and. c_associated(plans%inverse))) then
            call destroy_pair(plans)
            call fatal_error(error, name//': FFTW could not plan the transform', stat_numerical)
        end if
    end subroutine plan_once

    !> Forward real DFT by this set's plan, out-of-place, n = size(samples):
    !> spectrum(k+1) = sum_j samples(j+1)*exp(-2*pi*i*j*k/n), k = 0..n/2.
    !>
    !> Plans on first use of this size and placement (see the module notes on threads). On a
    !> size mismatch, or if FFTW cannot plan, the spectrum is set to NaN.
    subroutine set_forward(self, samples, spectrum)
        !> The plan set; may gain a plan pair.
        class(fft_plan_set), target, intent(inout) :: self
        !> Real samples y_j, j = 0..n-1, n >= 1 (any unit u); unchanged.
        real(dp), contiguous, target, intent(in) :: samples(:)
        !> Lines Y_k, k = 0..n/2 [u]: size(spectrum) must be n/2 + 1, distinct from samples.
        complex(dp), contiguous, target, intent(out) :: spectrum(:)

        integer :: i

        i = plan_for(self, samples, spectrum)
        if (i == 0) then
            spectrum(:) = cmplx(ieee_value(0.0_dp, ieee_quiet_nan), ieee_value(0.0_dp, ieee_quiet_nan), dp)
            return
        end if
        call fftw_execute_dft_r2c(self%pairs(i)%forward, samples, spectrum)
    end subroutine set_forward

    !> Inverse real DFT by this set's plan, out-of-place, n = size(samples):
    !> samples(j+1) = sum_k Y_k*exp(+2*pi*i*j*k/n) over the Hermitian-completed spectrum,
    !> so that the inverse of the forward is n times the samples.
    !>
    !> The spectrum is overwritten (FFTW's c2r default). Plans on first use of this size and
    !> placement. On a size mismatch, or if FFTW cannot plan, the samples are set to NaN.
    subroutine set_inverse(self, spectrum, samples)
        !> The plan set; may gain a plan pair.
        class(fft_plan_set), target, intent(inout) :: self
        !> Lines Y_k, k = 0..n/2 (any unit u); destroyed on return.
        complex(dp), contiguous, target, intent(inout) :: spectrum(:)
        !> Real samples y_j, j = 0..n-1 [u]; n >= 1, size(spectrum) = n/2 + 1.
        real(dp), contiguous, target, intent(out) :: samples(:)

        integer :: i

        i = plan_for(self, samples, spectrum)
        if (i == 0) then
            samples(:) = ieee_value(0.0_dp, ieee_quiet_nan)
            return
        end if
        call fftw_execute_dft_c2r(self%pairs(i)%inverse, spectrum, samples)
    end subroutine set_inverse

    !> Destroy the plans this set owns (a copy's inherited plans are only forgotten) and
    !> empty it; later transforms plan again. Safe at any time no transform of this set runs.
    subroutine set_release(self)
        !> The plan set.
        class(fft_plan_set), target, intent(inout) :: self

        integer :: i

        if (owns_plans(self)) then
            do i = 1, self%count
                call destroy_pair(self%pairs(i))
            end do
        end if
        self%pairs(:) = plan_pair()
        self%count = 0
        self%owner = 0_c_intptr_t
    end subroutine set_release

    !> Number of plan pairs (one r2c and one c2r plan for one size and placement each) that
    !> the set owns; 0 for a copy that has not transformed yet.
    function set_plan_count(self) result(count)
        !> The plan set.
        class(fft_plan_set), target, intent(in) :: self
        integer :: count

        count = 0
        if (owns_plans(self)) count = self%count
    end function set_plan_count

    !> Whether the set made the plans it holds (it is where it was when it planned).
    function owns_plans(self) result(owns)
        class(fft_plan_set), target, intent(in) :: self
        logical :: owns

        owns = self%count > 0 .and. self%owner == address_of(self)
    end function owns_plans

    !> Address of a plan set (of its first component).
    function address_of(self) result(address)
        class(fft_plan_set), target, intent(in) :: self
        integer(c_intptr_t) :: address

        address = transfer(c_loc(self%count), 0_c_intptr_t)
    end function address_of

    !> Index in the set of the plans for transforms between these arrays (their sizes and
    !> placement; only their addresses are looked at), planned and appended if missing; 0 on a
    !> size mismatch or when FFTW cannot plan.
    function plan_for(self, samples, spectrum) result(i)
        class(fft_plan_set), target, intent(inout) :: self
        real(dp), contiguous, target, intent(in) :: samples(:)
        complex(dp), contiguous, target, intent(in) :: spectrum(:)
        integer :: i

        i = 0
        if (size(samples) >= 1 .and. size(spectrum) == size(samples)/2 + 1) then
            i = plan_index(self, size(samples), offset_of(c_loc(samples)), offset_of(c_loc(spectrum)))
        end if
    end function plan_for

    !> Index in the set of the plans of size n for arrays at these byte offsets, planned and
    !> appended if missing; 0 when FFTW cannot plan. Plans inherited by a copy are forgotten.
    function plan_index(self, n, real_offset, complex_offset) result(i)
        class(fft_plan_set), target, intent(inout) :: self
        integer, intent(in) :: n, real_offset, complex_offset
        integer :: i

        type(plan_pair) :: entry

        if (self%count > 0 .and. .not. owns_plans(self)) then
            self%pairs(:) = plan_pair()
            self%count = 0
        end if
        do i = 1, self%count
            if (self%pairs(i)%n == n .and. self%pairs(i)%real_offset == real_offset &
                .and. self%pairs(i)%complex_offset == complex_offset) return
        end do
        i = 0
        if (self%count == max_pairs) return
        call make_plans(n, real_offset, complex_offset, entry)
        if (.not. (c_associated(entry%forward) .and. c_associated(entry%inverse))) then
            call destroy_pair(entry)
            return
        end if
        call append(self, entry)
        i = self%count
    end function plan_index

    !> Destroy a plan (nothing for a null one), serialised with every other planner call.
    subroutine destroy_plan(plan)
        type(c_ptr), intent(inout) :: plan

        if (.not. c_associated(plan)) return
        !$omp critical (greenconv_fftw_planner)
        call fftw_destroy_plan(plan)
        !$omp end critical (greenconv_fftw_planner)
        plan = c_null_ptr
    end subroutine destroy_plan

    !> Destroy both plans of a pair (nothing for a null one).
    subroutine destroy_pair(pair)
        type(plan_pair), intent(inout) :: pair

        call destroy_plan(pair%forward)
        call destroy_plan(pair%inverse)
    end subroutine destroy_pair

    !> Byte offset of an address modulo `period`.
    function offset_of(address) result(offset)
        type(c_ptr), intent(in) :: address
        integer :: offset

        offset = int(modulo(transfer(address, 0_c_intptr_t), int(period, c_intptr_t)))
    end function offset_of

    !> Plan both transforms of size n on scratch arrays placed at the given byte offsets
    !> (modulo `period`), with FFTW_UNALIGNED if no placement matches; FFTW_ESTIMATE leaves
    !> the scratch untouched. The scratch is freed on return: the plans keep its address
    !> but are only ever run by the new-array execute functions, never by fftw_execute.
    subroutine make_plans(n, real_offset, complex_offset, entry)
        integer, intent(in) :: n, real_offset, complex_offset
        type(plan_pair), intent(out) :: entry

        integer, parameter :: slack = period/8
        real(c_double), allocatable, target :: real_scratch(:), complex_scratch(:)
        real(c_double), pointer, contiguous :: samples(:)
        complex(c_double_complex), pointer, contiguous :: spectrum(:)
        integer(c_int) :: flags
        integer :: i_real, i_complex

        allocate (real_scratch(n + slack), complex_scratch(2*(n/2 + 1) + slack))
        real_scratch(:) = 0.0_c_double
        complex_scratch(:) = 0.0_c_double
        i_real = placed_at(real_scratch, real_offset)
        i_complex = placed_at(complex_scratch, complex_offset)
        flags = fftw_estimate
        if (i_real == 0 .or. i_complex == 0) then
            flags = ior(fftw_estimate, fftw_unaligned)
            i_real = 1
            i_complex = 1
        end if
        samples(1:n) => real_scratch(i_real:i_real + n - 1)
        call c_f_pointer(c_loc(complex_scratch(i_complex)), spectrum, [n/2 + 1])
        entry%n = n
        entry%real_offset = real_offset
        entry%complex_offset = complex_offset
        !$omp critical (greenconv_fftw_planner)
        entry%forward = fftw_plan_dft_r2c_1d(int(n, c_int), samples, spectrum, flags)
        entry%inverse = fftw_plan_dft_c2r_1d(int(n, c_int), spectrum, samples, flags)
        !$omp end critical (greenconv_fftw_planner)
    end subroutine make_plans

    !> The index i <= period/8 at which buffer(i) sits at the byte offset `offset` modulo
    !> `period`; 0 if there is none.
    function placed_at(buffer, offset) result(i)
        real(c_double), target, intent(in) :: buffer(:)
        integer, intent(in) :: offset
        integer :: i

        do i = 1, period/8
            if (offset_of(c_loc(buffer(i))) == offset) return
        end do
        i = 0
    end function placed_at

    !> Append a plan pair to the set (not full); the set then owns its plans.
    subroutine append(self, entry)
        class(fft_plan_set), target, intent(inout) :: self
        type(plan_pair), intent(in) :: entry

        self%count = self%count + 1
        self%pairs(self%count) = entry
        self%owner = address_of(self)
    end subroutine append

end module greenconv_ext_fftw
