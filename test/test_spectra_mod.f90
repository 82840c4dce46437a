!> 1/3-octave force spectra (greenconv_io_spectra) against closed forms: the IEC 61260 band
!> centres and edges, a sine of amplitude A at a band's centre (L = 20*log10(A/sqrt(2))),
!> Gaussian white noise of variance sigma^2 (band power sigma^2*(band width)/(f_s/2) within
!> the statistical spread of the averaging), Parseval (the bands add up to the mean square of
!> a signal inside their coverage) and the record-too-short message.
module test_spectra_mod
    use, intrinsic :: iso_fortran_env, only: dp => real64
    use testsuite_mod, only: test_error, unittest_type, new_unittest, check, note
    use greenconv_core_error, only: error_type
    use greenconv_core_random, only: random_stream
    use greenconv_io_files, only: make_directory
    use greenconv_io_spectra, only: band_spectrum, third_octave_bands, welch_psd, band_levels, write_band_levels
    implicit none
    private

    public :: collect_spectra

    real(dp), parameter :: pi = acos(-1.0_dp)
    !> Time step of the tyre scene [s] (f_s = 20 kHz).
    real(dp), parameter :: dt = 5.0e-5_dp

contains

    !> Tests of greenconv_io_spectra.
    subroutine collect_spectra(testsuite)
        type(unittest_type), allocatable, intent(out) :: testsuite(:)

        testsuite = [new_unittest('IEC 61260 base-10 centres and edges', test_bands), &
                     new_unittest('sine at each band centre: L = 20 log10(A/sqrt 2) within 0.1 dB', test_sine), &
                     new_unittest('white noise: sigma^2 * band width/(f_s/2) within 4 standard deviations', &
                                  test_white_noise), &
                     new_unittest('Parseval: bands add up to the mean square, PSD to the windowed one', &
                                  test_parseval), &
                     new_unittest('a record too short for the lowest band is refused', test_too_short)]
    end subroutine collect_spectra

    subroutine test_bands(error)
        type(test_error), allocatable, intent(out) :: error

        real(dp), allocatable :: centre(:), lower(:), upper(:)
        real(dp), parameter :: nominal(10) = [100.0_dp, 125.0_dp, 160.0_dp, 200.0_dp, 250.0_dp, 315.0_dp, 400.0_dp, &
                                              500.0_dp, 630.0_dp, 800.0_dp]

        call third_octave_bands(100.0_dp, 10000.0_dp, 10000.0_dp, centre, lower, upper)
        call check(error, size(centre) == 20, 'expected the 20 bands 100 Hz .. 8 kHz below 10 kHz (the 8 kHz ' &
                   //'band reaches 8.98 kHz, the 10 kHz band 11.2 kHz)')
        if (allocated(error)) return
        call note('f_c(1) [Hz]', centre(1))
        call note('f_c(9) [Hz]', centre(9))
        ! nominal values are the exact ones rounded to the preferred numbers (within 1.5 %)
        call check(error, all(abs(centre(1:10) - nominal)/nominal < 0.015_dp) .and. centre(11) == 1000.0_dp &
                   .and. maxval(abs(upper(:19) - lower(2:))/upper(:19)) < 1.0e-14_dp &
                   .and. abs(upper(11)/lower(11) - 10.0_dp**0.1_dp) < 1.0e-14_dp, &
                   'centres, edges or touching bands differ from IEC 61260 base 10')
    end subroutine test_bands

    !> A sine of amplitude A = 3 N at the exact centre of each band from 50 Hz to 5 kHz, 2 s.
    subroutine test_sine(error)
        type(test_error), allocatable, intent(out) :: error

        type(band_spectrum) :: spectrum
        type(error_type), allocatable :: fail
        real(dp), allocatable :: centre(:), lower(:), upper(:), force(:)
        real(dp), parameter :: amplitude = 3.0_dp
        real(dp) :: worst, leak
        integer :: b, j

        call third_octave_bands(50.0_dp, 5000.0_dp, 0.5_dp/dt, centre, lower, upper)
        worst = 0.0_dp
        leak = -huge(1.0_dp)
        do b = 1, size(centre)
            force = [(amplitude*sin(2.0_dp*pi*centre(b)*j*dt + 0.3_dp), j=0, 39999)]
            call band_levels(force, dt, 50.0_dp, 5000.0_dp, spectrum, fail)
            call check(error, .not. allocated(fail), 'band_levels failed')
            if (allocated(error)) return
            worst = max(worst, abs(spectrum%level(b) - 20.0_dp*log10(amplitude/sqrt(2.0_dp))))
            if (b > 1) leak = max(leak, spectrum%level(b - 1) - spectrum%level(b))
            if (b < size(centre)) leak = max(leak, spectrum%level(b + 1) - spectrum%level(b))
        end do
        call note('bands', real(size(centre), dp))
        call note('max |L - 20 log10(A/sqrt 2)| [dB]', worst)
        call note('neighbour band, worst [dB re tone band]', leak)
        call check(error, worst < 0.1_dp, 'a sine''s band level differs from 20 log10(A/sqrt 2) by more than 0.1 dB')
    end subroutine test_sine

    !> Gaussian white noise, sigma = 2 N, 2^18 samples (13 s at 20 kHz).
    subroutine test_white_noise(error)
        type(test_error), allocatable, intent(out) :: error

        type(band_spectrum) :: spectrum
        type(error_type), allocatable :: fail
        real(dp), allocatable :: force(:), expected(:), spread(:), z(:)
        real(dp), parameter :: sigma = 2.0_dp

        force = gaussian_noise(2**18, sigma, 61260)
        call band_levels(force, dt, 100.0_dp, 8000.0_dp, spectrum, fail)
        call check(error, .not. allocated(fail), 'band_levels failed')
        if (allocated(error)) return
        expected = sigma**2*(spectrum%upper - spectrum%lower)/(0.5_dp/dt)
        ! relative standard deviation: Hann 1.5 lines of noise bandwidth, 50 % overlap 1.06
        spread = sqrt(1.5_dp*1.06_dp/((spectrum%upper - spectrum%lower)/spectrum%df*spectrum%n_segments))
        z = (spectrum%power/expected - 1.0_dp)/spread
        call note('segments', real(spectrum%n_segments, dp))
        call note('rel. spread, lowest band', spread(1))
        call note('max |z|', maxval(abs(z)))
        call note('max |L - L_expected| [dB]', maxval(abs(spectrum%level - 10.0_dp*log10(expected))))
        call note('mean z', sum(z)/size(z))
        call check(error, maxval(abs(z)) < 4.0_dp, 'a white-noise band power is more than 4 standard deviations ' &
                   //'from sigma^2*(band width)/(f_s/2)')
    end subroutine test_white_noise

    !> Seven sines inside the coverage of the bands 100 Hz .. 5 kHz: the band powers add up to
    !> sum A^2/2; and the PSD lines add up to the window-weighted mean square (estimator
    !> Parseval, to round-off).
    subroutine test_parseval(error)
        type(test_error), allocatable, intent(out) :: error

        type(band_spectrum) :: spectrum
        type(error_type), allocatable :: fail
        real(dp), allocatable :: force(:), psd(:), window(:), segment(:)
        real(dp), parameter :: f(7) = [123.4_dp, 200.0_dp, 377.7_dp, 901.0_dp, 1500.0_dp, 2718.3_dp, 4400.0_dp]
        real(dp), parameter :: a(7) = [1.0_dp, 0.5_dp, 2.0_dp, 0.1_dp, 1.5_dp, 0.7_dp, 0.3_dp]
        real(dp) :: df, windowed
        integer :: j, k, n_segments, n

        force = [(sum(a*sin(2.0_dp*pi*f*j*dt + [(0.7_dp*k, k=1, 7)])), j=0, 59999)]
        call band_levels(force, dt, 100.0_dp, 5000.0_dp, spectrum, fail)
        call check(error, .not. allocated(fail), 'band_levels failed')
        if (allocated(error)) return
        call note('sum of bands/sum A^2/2 - 1', sum(spectrum%power)/sum(a**2/2.0_dp) - 1.0_dp)
        call check(error, abs(sum(spectrum%power)/sum(a**2/2.0_dp) - 1.0_dp) < 1.0e-3_dp, &
                   'the band powers do not add up to the mean square within 0.1 %')
        if (allocated(error)) return
        call make_directory('build/test_scratch', fail)
        call write_band_levels('build/test_scratch/seven_sines_bands.dat', spectrum, 'seven sines', fail)
        call check(error, .not. allocated(fail), 'write_band_levels failed')
        if (allocated(error)) return
        n = 4096
        call welch_psd(force, dt, n, psd, df, n_segments, fail)
        window = [(sin(pi*j/n)**2, j=0, n - 1)]
        windowed = 0.0_dp
        do k = 1, n_segments
            segment = force((k - 1)*n/2 + 1:(k - 1)*n/2 + n)
            windowed = windowed + sum((window*(segment - sum(segment)/n))**2)/sum(window**2)
        end do
        windowed = windowed/n_segments
        call note('sum P_k df/windowed mean square - 1', sum(psd)*df/windowed - 1.0_dp)
        call check(error, abs(sum(psd)*df/windowed - 1.0_dp) < 1.0e-12_dp, 'PSD lines do not add up to the ' &
                   //'windowed mean square')
    end subroutine test_parseval

    subroutine test_too_short(error)
        type(test_error), allocatable, intent(out) :: error

        type(band_spectrum) :: spectrum
        type(error_type), allocatable :: fail
        real(dp) :: force(6000)

        force = 1.0_dp
        call band_levels(force, dt, 20.0_dp, 5000.0_dp, spectrum, fail)
        call check(error, allocated(fail), 'expected an error for 0.3 s and a 20 Hz band')
        if (allocated(error)) return
        call check(error, index(fail%message, 'raise f_low to at least') > 0, 'unhelpful message: '//fail%message)
    end subroutine test_too_short

    !> n samples of Gaussian noise of standard deviation sigma (Box-Muller on SplitMix64).
    function gaussian_noise(n, sigma, seed) result(x)
        integer, intent(in) :: n, seed
        real(dp), intent(in) :: sigma
        real(dp) :: x(n)

        type(random_stream) :: stream
        real(dp) :: u1, u2
        integer :: i

        stream = random_stream(seed)
        do i = 1, n
            u1 = 1.0_dp - stream%uniform()
            u2 = stream%uniform()
            x(i) = sigma*sqrt(-2.0_dp*log(u1))*cos(2.0_dp*pi*u2)
        end do
    end function gaussian_noise

end module test_spectra_mod
