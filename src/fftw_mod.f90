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
!> Each call creates its plan with FFTW_ESTIMATE (which never overwrites the arrays
!> while planning), executes it on private contiguous copies and destroys it. This is
!> simple and correct for serial code. Thread safety is NOT provided yet: FFTW's
!> planner (plan creation and destruction) is not re-entrant, so a threaded caller
!> must serialize these calls (or call fftw_make_planner_thread_safe once, FFTW >= 3.3.5),
!> and a caller doing many transforms of one size should keep its plan instead.
module fftw_mod
    use, intrinsic :: iso_c_binding, only: c_int, c_double, c_double_complex, c_ptr, c_associated
    use kinds_mod, only: dp
    use error_mod, only: error_type, fatal_error, stat_numerical
    implicit none
    private

    public :: forward_real_fft, inverse_real_fft

    !> Planner flag FFTW_ESTIMATE (1U << 6 in fftw3.h): cheap heuristic plan, arrays untouched.
    integer(c_int), parameter :: fftw_estimate = 64_c_int

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
        subroutine fftw_execute_dft_r2c(plan, in, out) bind(c, name='fftw_execute_dft_r2c')
            import :: c_double, c_double_complex, c_ptr
            implicit none
            type(c_ptr), value :: plan
            real(c_double), intent(inout) :: in(*)
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

        real(c_double), allocatable :: input(:)
        complex(c_double_complex), allocatable :: output(:)
        type(c_ptr) :: plan
        integer :: n

        n = size(samples)
        if (n < 1 .or. size(spectrum) /= n/2 + 1) then
            call fatal_error(error, 'forward_real_fft: expected n/2 + 1 spectrum lines for n samples', stat_numerical)
            return
        end if
        allocate (input(n), output(n/2 + 1))
        plan = fftw_plan_dft_r2c_1d(int(n, c_int), input, output, fftw_estimate)
        if (.not. c_associated(plan)) then
            call fatal_error(error, 'forward_real_fft: FFTW could not plan the transform', stat_numerical)
            return
        end if
        input(:) = samples
        call fftw_execute_dft_r2c(plan, input, output)
        call fftw_destroy_plan(plan)
        spectrum(:) = output
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

        complex(c_double_complex), allocatable :: input(:)
        real(c_double), allocatable :: output(:)
        type(c_ptr) :: plan
        integer :: n

        n = size(samples)
        if (n < 1 .or. size(spectrum) /= n/2 + 1) then
            call fatal_error(error, 'inverse_real_fft: expected n/2 + 1 spectrum lines for n samples', stat_numerical)
            return
        end if
        allocate (input(n/2 + 1), output(n))
        plan = fftw_plan_dft_c2r_1d(int(n, c_int), input, output, fftw_estimate)
        if (.not. c_associated(plan)) then
            call fatal_error(error, 'inverse_real_fft: FFTW could not plan the transform', stat_numerical)
            return
        end if
        input(:) = spectrum
        call fftw_execute_dft_c2r(plan, input, output)
        call fftw_destroy_plan(plan)
        samples(:) = output
    end subroutine inverse_real_fft

end module fftw_mod
