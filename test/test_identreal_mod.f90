!> Identification of what real measurements contain (issue 26): abscissae rounded by a
!> universal file's E13.5 fields snapped back to the uniform grid they state.
module test_identreal_mod
    use, intrinsic :: iso_fortran_env, only: dp => real64
    use testsuite_mod, only: test_error, unittest_type, new_unittest, check, note
    use greenconv_core_error, only: error_type
    use greenconv_io_uff, only: uff_function, uff_node, uff_receptance
    use greenconv_io_uff_write, only: receptance_function, write_uff
    use greenconv_model_frf, only: frf_type, frf_from_uff, read_frf
    implicit none
    private

    public :: collect_identreal

contains

    !> Tests of the identification on measured-like files.
    subroutine collect_identreal(testsuite)
        type(unittest_type), allocatable, intent(out) :: testsuite(:)

        testsuite = [new_unittest('grid: E13.5 df (10-1700 Hz, 5000 lines) snapped to the stated grid', test_even_band), &
                     new_unittest('grid: E13.5 df from 0 Hz (5000/8192 Hz) snapped, FFT grid kept', test_even_zero), &
                     new_unittest('grid: per-line E13.5 abscissae snapped; log-spaced lines kept', test_uneven)]
    end subroutine collect_identreal

    !> x as an E13.5 field gives it back: six significant digits.
    real(dp) function e13_5(x)
        real(dp), intent(in) :: x

        character(len=13) :: field

        write (field, '(es13.5)') x
        read (field, *) e13_5
    end function e13_5

    !> numpy's linspace(first, last, n).
    pure function linspace(first, last, n) result(f)
        real(dp), intent(in) :: first, last
        integer, intent(in) :: n
        real(dp) :: f(n)

        integer :: j

        f = [(first + j*((last - first)/(n - 1)), j=0, n - 1)]
        f(n) = last
    end function linspace

    !> A receptance dataset 58 on the given abscissae (even: from the first with the given step).
    function dataset(abscissa, even) result(function)
        real(dp), intent(in) :: abscissa(:)
        logical, intent(in) :: even
        type(uff_function) :: function

        function = receptance_function([1, 3], [1, 3], abscissa(1), abscissa(2) - abscissa(1), &
                                       spread((1.0_dp, 0.0_dp), 1, size(abscissa)), 'grid test')
        function%kind = uff_receptance
        function%even = even
        function%abscissa = abscissa
        function%line = 1
    end function dataset

    !> sdypy-EMA's grid, np.linspace(10, 1700, 5000): df 0.338067613... written 3.38068E-01,
    !> 2e-3 Hz off at the last line when read back; through a file written and read.
    subroutine test_even_band(error)
        type(test_error), allocatable, intent(out) :: error

        real(dp), allocatable :: truth(:)
        type(frf_type) :: frf
        type(error_type), allocatable :: failure
        character(len=*), parameter :: path = 'build/test_identreal_band.uff'

        truth = linspace(10.0_dp, 1700.0_dp, 5000)
        call write_uff(path, [receptance_function([1, 3], [1, 3], truth(1), truth(2) - truth(1), &
                       spread((1.0_dp, 0.0_dp), 1, 5000), 'grid test')], [uff_node ::], failure)
        call check(error, .not. allocated(failure), 'write_uff failed')
        if (allocated(error)) return
        call read_frf(path, frf, failure)
        call check(error, .not. allocated(failure), 'read_frf failed')
        if (allocated(error)) return
        call note('10-1700 Hz: largest grid error [Hz]', maxval(abs(frf%frequency - truth)))
        call check(error, maxval(abs(frf%frequency - truth)) <= 1.0e-12_dp*1700.0_dp, &
                   'the E13.5 grid was not snapped to 10 + j*1690/4999 Hz')
        if (allocated(error)) return
        call check(error, frf%frequency(5000) == 1700.0_dp, 'the last line is not 1700 Hz exactly')
    end subroutine test_even_band

    !> The shipped scene's grid: 8193 lines to 5 kHz, df = 0.6103515625 written 6.10352E-01.
    subroutine test_even_zero(error)
        type(test_error), allocatable, intent(out) :: error

        real(dp), allocatable :: truth(:), read(:)
        type(frf_type) :: frf
        type(error_type), allocatable :: failure
        integer :: j

        truth = [(j*(5000.0_dp/8192), j=0, 8192)]
        read = [(j*e13_5(5000.0_dp/8192), j=0, 8192)]
        call frf_from_uff(dataset(read, .true.), frf, failure, 'grid test')
        call check(error, .not. allocated(failure), 'frf_from_uff failed')
        if (allocated(error)) return
        call note('0-5000 Hz: largest grid error before [Hz]', maxval(abs(read - truth)))
        call note('0-5000 Hz: largest grid error after [Hz]', maxval(abs(frf%frequency - truth)))
        call check(error, all(frf%frequency == truth), 'the E13.5 grid was not snapped to j*5000/8192 Hz')
        if (allocated(error)) return
        call check(error, frf%uniform_from_zero(), 'the snapped grid is not the FFT grid from 0 Hz')
    end subroutine test_even_zero

    !> Per-line abscissae, each rounded to six digits: snapped to the uniform grid from the
    !> first line; log-spaced lines (no uniform grid within the rounding) stay as read.
    subroutine test_uneven(error)
        type(test_error), allocatable, intent(out) :: error

        real(dp), allocatable :: truth(:), read(:)
        type(frf_type) :: frf
        type(error_type), allocatable :: failure
        integer :: j

        truth = linspace(10.0_dp, 1700.0_dp, 5000)
        read = [(e13_5(truth(j)), j=1, 5000)]
        call frf_from_uff(dataset(read, .false.), frf, failure, 'grid test')
        call check(error, .not. allocated(failure), 'frf_from_uff failed')
        if (allocated(error)) return
        call note('uneven 10-1700 Hz: largest grid error before [Hz]', maxval(abs(read - truth)))
        call note('uneven 10-1700 Hz: largest grid error after [Hz]', maxval(abs(frf%frequency - truth)))
        call check(error, maxval(abs(frf%frequency - truth)) <= 1.0e-12_dp*1700.0_dp, &
                   'per-line E13.5 abscissae were not snapped')
        if (allocated(error)) return
        read = [(e13_5(20.0_dp*1.001_dp**j), j=0, 999)]
        call frf_from_uff(dataset(read, .false.), frf, failure, 'grid test')
        call check(error, .not. allocated(failure), 'frf_from_uff failed on log-spaced lines')
        if (allocated(error)) return
        call check(error, all(frf%frequency == read), 'log-spaced lines were moved')
    end subroutine test_uneven

end module test_identreal_mod
