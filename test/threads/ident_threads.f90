!> The maximum-likelihood identification on one thread, on two, and inside a host's parallel
!> region: the same poles, residues and chi^2 bit for bit.
!>
!> OpenBLAS's OpenMP build threads a BLAS or LAPACK call as `omp_get_max_threads()` says when
!> it is called outside a parallel region, and the threaded sums come out in another order:
!> before the identification's calls were made serially (ext/lapack.f90's
!> `lapack_serial_begin`), pyuff's measured beam FRF 1 gave 13 poles on one thread and 11 on
!> two (main d8be39a: "FAIL: ... 2 threads give the 1-thread poles" on both cases).
!> Each case (a universal file and its dataset) is identified with omp_set_num_threads(1), then
!> with omp_set_num_threads(2), then by two host threads at once inside one parallel region;
!> every result must equal the first bit for bit. Prints "ok: ..." or "FAIL: ..." per check
!> and the poles, the determined modes, chi^2/nu and the seconds of each run; exit status 1 on
!> a failure. Built by the Makefile (with OpenMP): `make thread-ident`.
program ident_threads
    !$ use omp_lib, only: omp_set_num_threads, omp_get_wtime, omp_get_thread_num
    use, intrinsic :: iso_fortran_env, only: int64, output_unit
    use greenconv_core_kinds, only: dp
    use greenconv_core_error, only: error_type
    use greenconv_model_frf, only: frf_type, read_frf
    use greenconv_ident_mlfit, only: ml_options, ml_result, identify_ml
    implicit none

    !> One identification's outcome, kept as bits.
    type :: outcome
        !> Whether the identification failed, and its message.
        character(len=:), allocatable :: failure
        !> Bits of Re and Im of the poles, of the residues, then of chi^2.
        integer(int64), allocatable :: bits(:)
        !> Number of poles, and of those the data determine.
        integer :: poles = 0, determined = 0
        !> chi^2/nu.
        real(dp) :: chi2_nu = 0.0_dp
        !> Wall-clock seconds.
        real(dp) :: seconds = 0.0_dp
    end type outcome

    character(len=*), parameter :: beam = 'test/data/pyuff_beam/beam_accelerance.uff'
    character(len=*), parameter :: sdypy = 'test/data/sdypy/synth_accelerance.uff'
    integer :: failed

    failed = 0
    !$ if (.false.) then
    write (output_unit, '(a)') 'FAIL: built without OpenMP: the thread counts cannot be set'
    stop 1
    !$ end if
    call check_case(beam, 1, 'pyuff measured beam, FRF 1')
    call check_case(sdypy, 5, 'sdypy synthetic accelerance H_51')
    if (failed > 0) stop 1

contains

    !> Identify one dataset of a file on one thread, on two, and in two host threads at once.
    subroutine check_case(path, dataset, label)
        character(len=*), intent(in) :: path
        integer, intent(in) :: dataset
        character(len=*), intent(in) :: label

        type(frf_type) :: frf
        type(error_type), allocatable :: failure
        type(outcome) :: one, two, host(2)
        integer :: t

        call read_frf(path, frf, failure, dataset)
        if (allocated(failure)) then
            call report(.false., label//': '//failure%message)
            return
        end if
        !$ call omp_set_num_threads(1)
        call identify(frf, one)
        call describe(label//', 1 thread', one)
        !$ call omp_set_num_threads(2)
        call identify(frf, two)
        call describe(label//', 2 threads', two)
        call report(same(one, two), label//': 2 threads give the 1-thread poles, residues and chi^2 bit for bit')
        t = 1
        !$omp parallel num_threads(2) default(shared) private(t)
        !$ t = omp_get_thread_num() + 1
        call identify(frf, host(t))
        !$omp end parallel
        call describe(label//', host thread 1 of 2', host(1))
        call report(same(one, host(1)) .and. same(one, host(2)), &
                    label//': two host threads at once give the 1-thread results bit for bit')
    end subroutine check_case

    !> The default maximum-likelihood identification of frf, its result as bits.
    subroutine identify(frf, result)
        type(frf_type), intent(in) :: frf
        type(outcome), intent(out) :: result

        type(ml_options) :: options
        type(ml_result) :: fit
        type(error_type), allocatable :: failure
        real(dp) :: start

        start = 0.0_dp
        !$ start = omp_get_wtime()
        call identify_ml(frf, options, fit, failure)
        !$ result%seconds = omp_get_wtime() - start
        if (allocated(failure)) then
            result%failure = failure%message
            return
        end if
        result%failure = ''
        associate (p => fit%modes%pole, r => fit%modes%residue)
            result%bits = [transfer(real(p, dp), 1_int64, size(p)), transfer(aimag(p), 1_int64, size(p)), &
                           transfer(real(r, dp), 1_int64, size(r)), transfer(aimag(r), 1_int64, size(r)), &
                           transfer(fit%chi_square, 1_int64)]
            result%poles = size(p)
        end associate
        result%determined = count(fit%determined)
        result%chi2_nu = fit%chi_square/max(fit%dof, 1)
    end subroutine identify

    !> Whether two outcomes are the same bit for bit (a failure only equals the same failure).
    logical function same(a, b)
        type(outcome), intent(in) :: a, b

        same = a%failure == b%failure
        if (same .and. len(a%failure) == 0) same = size(a%bits) == size(b%bits)
        if (same .and. len(a%failure) == 0) same = all(a%bits == b%bits)
    end function same

    !> One line: poles, determined modes, chi^2/nu and seconds (or the failure).
    subroutine describe(label, result)
        character(len=*), intent(in) :: label
        type(outcome), intent(in) :: result

        if (len(result%failure) > 0) then
            write (output_unit, '(a)') label//': identification failed: '//result%failure
        else
            write (output_unit, '(a,": ",i0," poles, ",i0," determined, chi2/nu ",es24.17,", ",f0.2," s")') &
                label, result%poles, result%determined, result%chi2_nu, result%seconds
        end if
    end subroutine describe

    !> An "ok: " or "FAIL: " line.
    subroutine report(passed, text)
        logical, intent(in) :: passed
        character(len=*), intent(in) :: text

        if (passed) then
            write (output_unit, '(a)') 'ok: '//text
        else
            write (output_unit, '(a)') 'FAIL: '//text
            failed = failed + 1
        end if
    end subroutine report

end program ident_threads
