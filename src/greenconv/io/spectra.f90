!> Force spectra in 1/3-octave bands, what acousticians compare: band levels in dB re 1 N of
!> a force history sampled at a time step dt.
!>
!> **Bands** (IEC 61260-1, base 10): exact centre frequencies f_c = 1000*10^(x/10) Hz for
!> integer x (the nominal 100, 125, 160, ... Hz are their rounded names), edges
!> f_c*10^(-1/20) and f_c*10^(+1/20), so that neighbouring bands touch and a band is
!> 0.2316*f_c wide. Every band with f_low <= f_c <= f_high whose upper edge lies below the
!> Nyquist frequency 1/(2*dt) is kept.
!>
!> **Power spectral density** (Welch's method): segments of N samples overlapping by 50 %,
!> each with its mean removed (no band reaches 0 Hz; a static preload would otherwise leak
!> into the lowest bands) and multiplied by a Hann window w_j = sin^2(pi*j/N), j = 0..N-1
!> (periodic form); the one-sided PSD of a segment is
!>
!>     P_k = c_k*|X_k|^2/(f_s*sum_j w_j^2)  [N^2/Hz],  f_k = k*f_s/N,  k = 0..N/2,
!>
!> X the DFT of the windowed segment, f_s = 1/dt, c_k = 2 except c_0 = c_{N/2} = 1, and the
!> segments' PSDs are averaged. Then sum_k P_k*df (df = f_s/N) is the window-weighted mean
!> square of the segments (Parseval). Samples after the last whole segment are not used.
!>
!> **Segment length**: from the lowest band, so that it spans at least `lines_per_band`
!> (default 8) lines: N is the smallest power of two with f_s/N <= (lowest band width)/8.
!> Then the Hann window's main lobe (+-2 lines) of a tone at a band's centre lies well inside
!> the band (which reaches at least 3.7 lines below and 4.2 above its centre), and its level
!> comes out within 1e-4 dB (suite spectra measures 1.3e-5 dB). A record shorter than N
!> samples is refused with the lowest band it could resolve.
!>
!> **Band power and level**: P_band = integral of the PSD over the band's edges, each line
!> standing for [f_k - df/2, f_k + df/2] and counted with the fraction of that interval inside
!> the band, so that the powers of adjacent bands add up to the integral over their union;
!> L = 10*log10(P_band/(1 N^2)) [dB re 1 N]. A sine of amplitude A gives P = A^2/2, so
!> L = 20*log10(A/sqrt(2)); white noise of variance sigma^2 gives sigma^2*(band width)/(f_s/2).
!> The statistical spread of a band power estimated from K segments and n lines is about
!> sqrt(1.5*1.06/(n*K)) relatively (Hann: 1.5 lines of noise bandwidth; 50 % overlap: 1.06).
module greenconv_io_spectra
    use greenconv_core_kinds, only: dp
    use greenconv_core_error, only: error_type, fatal_error
    use greenconv_core_text, only: int_text, real_text
    use greenconv_ext_fftw, only: forward_real_fft
    use greenconv_io_files, only: write_columns
    implicit none
    private

    public :: band_spectrum, third_octave_bands, welch_psd, band_levels, write_band_levels

    !> pi
    real(dp), parameter :: pi = acos(-1.0_dp)
    !> Half the width of a 1/3-octave band in decades of frequency (edges f_c*10^(+-1/20)).
    real(dp), parameter :: half_band = 0.05_dp
    !> Lines of the PSD the lowest band spans at least, by default.
    integer, parameter :: default_lines_per_band = 8

    !> Band powers and levels of one force history, with how they were estimated.
    type :: band_spectrum
        !> Exact centre frequencies f_c [Hz] of the bands, 1000*10^(x/10).
        real(dp), allocatable :: centre(:)
        !> Lower band edges f_c*10^(-1/20) [Hz].
        real(dp), allocatable :: lower(:)
        !> Upper band edges f_c*10^(+1/20) [Hz].
        real(dp), allocatable :: upper(:)
        !> Band powers P [N^2]: the PSD integrated over each band.
        real(dp), allocatable :: power(:)
        !> Band levels 10*log10(P/1 N^2) [dB re 1 N].
        real(dp), allocatable :: level(:)
        !> Segment length N [samples] of the Welch estimate.
        integer :: segment_length = 0
        !> Number of segments K averaged.
        integer :: n_segments = 0
        !> Line spacing df = f_s/N [Hz].
        real(dp) :: df = 0.0_dp
    end type band_spectrum

contains

    !> The 1/3-octave bands with f_low <= f_c <= f_high [Hz] (exact base-10 centres, see the
    !> module description), at most up to the Nyquist frequency f_nyquist: bands whose upper
    !> edge exceeds it are left out.
    pure subroutine third_octave_bands(f_low, f_high, f_nyquist, centre, lower, upper)
        !> Lowest centre frequency wanted [Hz], > 0.
        real(dp), intent(in) :: f_low
        !> Highest centre frequency wanted [Hz].
        real(dp), intent(in) :: f_high
        !> Nyquist frequency 1/(2*dt) [Hz].
        real(dp), intent(in) :: f_nyquist
        !> Centre frequencies [Hz].
        real(dp), allocatable, intent(out) :: centre(:)
        !> Lower edges [Hz].
        real(dp), allocatable, intent(out) :: lower(:)
        !> Upper edges [Hz].
        real(dp), allocatable, intent(out) :: upper(:)

        integer :: first, last, x

        ! the small tolerance keeps a band whose centre is given by its rounded value
        first = ceiling(10.0_dp*log10(f_low/1000.0_dp) - 1.0e-9_dp)
        last = floor(10.0_dp*log10(f_high/1000.0_dp) + 1.0e-9_dp)
        do while (last >= first)
            if (1000.0_dp*10.0_dp**(last/10.0_dp + half_band) <= f_nyquist) exit
            last = last - 1
        end do
        centre = [(1000.0_dp*10.0_dp**(x/10.0_dp), x=first, last)]
        lower = centre*10.0_dp**(-half_band)
        upper = centre*10.0_dp**half_band
    end subroutine third_octave_bands

    !> One-sided power spectral density by Welch's method (Hann window, 50 % overlap, the
    !> mean of each segment removed; see the module description).
    subroutine welch_psd(samples, dt, segment_length, psd, df, n_segments, error)
        !> The history [N], sampled every dt.
        real(dp), intent(in) :: samples(:)
        !> Time step [s], > 0.
        real(dp), intent(in) :: dt
        !> Segment length N [samples], >= 2 and at most size(samples).
        integer, intent(in) :: segment_length
        !> PSD P_k [N^2/Hz] at f_k = k*df, k = 0..N/2.
        real(dp), allocatable, intent(out) :: psd(:)
        !> Line spacing df = 1/(N*dt) [Hz].
        real(dp), intent(out) :: df
        !> Number of segments averaged.
        integer, intent(out) :: n_segments
        !> Set for a record shorter than one segment or a non-positive dt.
        type(error_type), allocatable, intent(out) :: error

        real(dp), allocatable :: window(:), segment(:)
        complex(dp), allocatable :: spectrum(:)
        integer :: n, hop, s, j, first

        n = segment_length
        df = 0.0_dp
        n_segments = 0
        if (.not. dt > 0.0_dp .or. n < 2 .or. n > size(samples)) then
            call fatal_error(error, 'force spectrum: expected dt > 0 and a segment of 2 to '//int_text(size(samples)) &
                             //' samples (the record), found dt = '//real_text(dt)//' s and '//int_text(n))
            return
        end if
        hop = n/2
        n_segments = 1 + (size(samples) - n)/hop
        window = [(sin(pi*j/n)**2, j=0, n - 1)]
        allocate (psd(0:n/2), spectrum(n/2 + 1))
        psd = 0.0_dp
        do s = 1, n_segments
            first = (s - 1)*hop + 1
            segment = samples(first:first + n - 1)
            segment = window*(segment - sum(segment)/n)
            call forward_real_fft(segment, spectrum, error)
            if (allocated(error)) return
            psd = psd + abs(spectrum)**2
        end do
        psd = 2.0_dp*psd*dt/(sum(window**2)*n_segments)
        psd(0) = psd(0)/2.0_dp
        if (mod(n, 2) == 0) psd(n/2) = psd(n/2)/2.0_dp
        df = 1.0_dp/(n*dt)
    end subroutine welch_psd

    !> Band powers and levels in dB re 1 N of a force history in the 1/3-octave bands with
    !> f_low <= f_c <= f_high, by Welch's PSD (module description).
    subroutine band_levels(samples, dt, f_low, f_high, spectrum, error, lines_per_band)
        !> The force history [N], sampled every dt.
        real(dp), intent(in) :: samples(:)
        !> Time step [s], > 0.
        real(dp), intent(in) :: dt
        !> Lowest band centre wanted [Hz], > 0.
        real(dp), intent(in) :: f_low
        !> Highest band centre wanted [Hz] (bands past the Nyquist frequency are left out).
        real(dp), intent(in) :: f_high
        !> The bands, their powers and levels, and the estimate's parameters.
        type(band_spectrum), intent(out) :: spectrum
        !> Set when no band fits between f_low, f_high and the Nyquist frequency, or the record
        !> is too short for the lowest band.
        type(error_type), allocatable, intent(out) :: error
        !> Lines the lowest band spans at least (default 8); sets the segment length.
        integer, intent(in), optional :: lines_per_band

        real(dp), allocatable :: psd(:)
        real(dp) :: width, lowest
        integer :: lines, n, b, k

        lines = default_lines_per_band
        if (present(lines_per_band)) lines = max(1, lines_per_band)
        if (.not. (dt > 0.0_dp .and. f_low > 0.0_dp)) then
            call fatal_error(error, 'force spectrum: expected dt > 0 and f_low > 0, found dt = '//real_text(dt) &
                             //' s, f_low = '//real_text(f_low)//' Hz')
            return
        end if
        call third_octave_bands(f_low, f_high, 0.5_dp/dt, spectrum%centre, spectrum%lower, spectrum%upper)
        if (size(spectrum%centre) == 0) then
            call fatal_error(error, 'force spectrum: no 1/3-octave band between '//real_text(f_low)//' and ' &
                             //real_text(f_high)//' Hz below the Nyquist frequency '//real_text(0.5_dp/dt) &
                             //' Hz; widen the range or reduce dt')
            return
        end if
        width = spectrum%upper(1) - spectrum%lower(1)
        n = 2
        do while (1.0_dp/(n*dt) > width/lines)
            n = 2*n
        end do
        if (n > size(samples)) then
            ! the lowest centre whose band spans `lines` lines of a segment as long as the record
            lowest = lines/(size(samples)*dt*(10.0_dp**half_band - 10.0_dp**(-half_band)))
            call fatal_error(error, 'force spectrum: the record ('//int_text(size(samples))//' samples, ' &
                             //real_text(size(samples)*dt)//' s) is shorter than the '//int_text(n) &
                             //' samples the band at '//real_text(spectrum%centre(1))//' Hz needs; ' &
                             //'raise f_low to at least '//real_text(lowest)//' Hz or give a longer record')
            return
        end if
        call welch_psd(samples, dt, n, psd, spectrum%df, spectrum%n_segments, error)
        if (allocated(error)) return
        spectrum%segment_length = n
        allocate (spectrum%power(size(spectrum%centre)))
        do b = 1, size(spectrum%centre)
            spectrum%power(b) = 0.0_dp
            do k = max(0, floor(spectrum%lower(b)/spectrum%df)), min(n/2, ceiling(spectrum%upper(b)/spectrum%df))
                spectrum%power(b) = spectrum%power(b) + psd(k)*max(0.0_dp, &
                    min(spectrum%upper(b), (k + 0.5_dp)*spectrum%df) - max(spectrum%lower(b), (k - 0.5_dp)*spectrum%df))
            end do
        end do
        spectrum%level = 10.0_dp*log10(max(spectrum%power, tiny(1.0_dp)))
    end subroutine band_levels

    !> Write a band spectrum as columns: centre, lower and upper edge [Hz], power [N^2] and
    !> level [dB re 1 N], under comment lines that say how it was estimated.
    subroutine write_band_levels(path, spectrum, what, error)
        !> Target file.
        character(len=*), intent(in) :: path
        !> A spectrum from `band_levels`.
        type(band_spectrum), intent(in) :: spectrum
        !> What the force is, for the first comment line (e.g. 'total contact force, modal').
        character(len=*), intent(in) :: what
        !> Set when the file cannot be written.
        type(error_type), allocatable, intent(out) :: error

        character(len=200) :: comments(5)

        comments(1) = '1/3-octave band levels of the '//what
        comments(2) = 'IEC 61260-1 base-10 bands, exact centres 1000*10^(x/10) Hz, edges f_c*10^(+-1/20)'
        comments(3) = 'Welch PSD: Hann window, 50 % overlap, segment mean removed, '//int_text(spectrum%n_segments) &
                      //' segments of '//int_text(spectrum%segment_length)//' samples, df = ' &
                      //real_text(spectrum%df)//' Hz; band power = PSD integrated over the band edges'
        comments(4) = 'units: Hz Hz Hz N^2 dB_re_1N'
        comments(5) = 'f_centre f_lower f_upper power level'
        call write_columns(path, comments, reshape([spectrum%centre, spectrum%lower, spectrum%upper, spectrum%power, &
                                                    spectrum%level], [size(spectrum%centre), 5]), error)
    end subroutine write_band_levels

end module greenconv_io_spectra
