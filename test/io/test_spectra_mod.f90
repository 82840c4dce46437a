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
    use greenconv_io_spectra, only: band_spectrum, third_octave_bands, welch_psd, band_levels, write_band_levels, &
                                    welch_accumulator, start_welch, add_welch_samples, welch_average, band_centre, &
                                    first_band, edge_band, nominal_frequency, segment_for_band, lowest_resolved_band, &
                                    highest_band_below
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
                     new_unittest('a record too short for the lowest band is refused', test_too_short), &
                     new_unittest('nominal names; the lowest band a record resolves, the highest below Nyquist', &
                                  test_band_limits), &
                     new_unittest('Welch fed in uneven pieces, two channels: the one-piece PSD bit for bit', &
                                  test_pieces)]
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

    !> IEC 61260-1's nominal names 10 Hz .. 20 kHz; a range given by nominal names selects
    !> those bands; the lowest band a record resolves is the first whose segment fits it; the
    !> highest band below a Nyquist frequency is the last whose upper edge does.
    subroutine test_band_limits(error)
        type(test_error), allocatable, intent(out) :: error

        real(dp), parameter :: names(34) = [10.0_dp, 12.5_dp, 16.0_dp, 20.0_dp, 25.0_dp, 31.5_dp, 40.0_dp, 50.0_dp, &
            63.0_dp, 80.0_dp, 100.0_dp, 125.0_dp, 160.0_dp, 200.0_dp, 250.0_dp, 315.0_dp, 400.0_dp, 500.0_dp, &
            630.0_dp, 800.0_dp, 1000.0_dp, 1250.0_dp, 1600.0_dp, 2000.0_dp, 2500.0_dp, 3150.0_dp, 4000.0_dp, &
            5000.0_dp, 6300.0_dp, 8000.0_dp, 10000.0_dp, 12500.0_dp, 16000.0_dp, 20000.0_dp]
        integer, parameter :: records(4) = [2000, 6000, 10000, 100000000]
        integer :: x, i, low, top
        real(dp) :: nyquist

        do x = -20, 13
            call check(error, abs(nominal_frequency(band_centre(x)) - names(x + 21)) < 1.0e-9_dp*names(x + 21) &
                       .and. first_band(names(x + 21)) == x .and. edge_band(names(x + 21), 1) == x, &
                       'band '//int_label(x)//': nominal name or the band its name selects')
            if (allocated(error)) return
        end do
        do i = 1, size(records)
            low = lowest_resolved_band(records(i), dt, 8)
            call check(error, segment_for_band(low, dt, 8) <= records(i) .and. &
                       segment_for_band(low - 1, dt, 8) > records(i), 'lowest band of '//int_label(records(i)) &
                       //' samples')
            if (allocated(error)) return
        end do
        call note('lowest band of 6000 samples at 20 kHz [Hz]', band_centre(lowest_resolved_band(6000, dt, 8)))
        do i = 1, 50
            nyquist = 10.0_dp**(1.0_dp + 0.077_dp*i)
            top = highest_band_below(nyquist)
            call check(error, band_centre(top)*10.0_dp**0.05_dp <= nyquist .and. &
                       band_centre(top + 1)*10.0_dp**0.05_dp > nyquist, 'highest band below the Nyquist frequency')
            if (allocated(error)) return
        end do
    end subroutine test_band_limits

    !> Two channels (noise and a sine) fed to the accumulator in pieces of 1, 999, 4096 and
    !> 3 samples and the rest give each channel's `welch_psd` bit for bit.
    subroutine test_pieces(error)
        type(test_error), allocatable, intent(out) :: error

        type(welch_accumulator) :: welch
        type(error_type), allocatable :: fail
        real(dp), allocatable :: samples(:, :), psd(:, :), whole(:)
        integer, parameter :: cuts(5) = [0, 1, 1000, 5096, 5099]
        real(dp) :: df, df_whole
        integer :: j, c, n_segments

        allocate (samples(30000, 2))
        samples(:, 1) = gaussian_noise(30000, 1.0_dp, 7)
        samples(:, 2) = [(2.0_dp*sin(2.0_dp*pi*440.0_dp*j*dt), j=0, 29999)]
        call start_welch(welch, 2048, 2)
        do j = 1, size(cuts) - 1
            call add_welch_samples(welch, samples(cuts(j) + 1:cuts(j + 1), :))
        end do
        call add_welch_samples(welch, samples(cuts(size(cuts)) + 1:, :))
        call welch_average(welch, dt, psd, df, fail)
        call check(error, .not. allocated(fail) .and. lbound(psd, 1) == 0 .and. ubound(psd, 1) == 1024, &
                   'welch_average: lines 0..N/2')
        if (allocated(error)) return
        do c = 1, 2
            call welch_psd(samples(:, c), dt, 2048, whole, df_whole, n_segments, fail)
            call check(error, .not. allocated(fail) .and. n_segments == welch%n_segments .and. df == df_whole .and. &
                       all(psd(:, c) == whole), 'channel '//int_label(c)//' differs from welch_psd')
            if (allocated(error)) return
        end do
        call note('segments', real(n_segments, dp))
    end subroutine test_pieces

    !> An integer as text.
    pure function int_label(i) result(text)
        integer, intent(in) :: i
        character(len=:), allocatable :: text

        character(len=12) :: buffer

        write (buffer, '(i0)') i
        text = trim(buffer)
    end function int_label

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
