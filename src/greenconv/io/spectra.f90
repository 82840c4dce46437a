!> Force spectra in 1/3-octave bands, what acousticians compare: band levels in dB re 1 N of
!> a force history sampled at a time step dt.
!>
!> **Bands** (IEC 61260-1, base 10): band x (an integer, 0 at 1 kHz) has the exact centre
!> frequency f_c = 1000*10^(x/10) Hz, whose nominal name is the preferred number it rounds
!> to (100, 125, 160, ... Hz: `nominal_frequency`), and the edges f_c*10^(-1/20) and
!> f_c*10^(+1/20), so that neighbouring bands touch and a band is 0.2316*f_c wide. Every
!> band with f_low <= f_c <= f_high whose upper edge lies below the Nyquist frequency
!> 1/(2*dt) is kept.
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
!> A `welch_accumulator` computes the same average as the samples arrive, holding one
!> segment per channel, so a history of any length is analysed in bounded memory; given the
!> same samples in any number of pieces it adds the same segments in the same order.
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
!>
!> **Statistical spread** (`level_spread`): for a random, noise-like force the band power
!> estimated from K segments and n lines scatters by about s = sqrt(1.5*r_K/(n*K)) relatively
!> (Hann: 1.5 lines of noise bandwidth; r_K = 1 + 2*(1 - 1/K)*0.167^2, the correlation of
!> segments overlapping by 50 %, about 1.06 for many segments), that is 10*log10(e)*s dB.
!> A steady tone does not scatter.
module greenconv_io_spectra
    use, intrinsic :: iso_c_binding, only: c_ptr, c_loc, c_intptr_t
    use greenconv_core_kinds, only: dp
    use greenconv_core_error, only: error_type, fatal_error, stat_numerical
    use greenconv_core_text, only: int_text, real_text
    use greenconv_ext_fftw, only: fft_plan_set
    use greenconv_io_files, only: write_columns
    implicit none
    private

    public :: band_spectrum, third_octave_bands, welch_psd, band_levels, write_band_levels
    public :: welch_accumulator, start_welch, add_welch_samples, welch_average, set_welch_gains
    public :: band_centre, first_band, edge_band, nominal_frequency, segment_for_band, lowest_resolved_band
    public :: highest_band_below, band_powers, level_spread, default_lines_per_band

    !> pi
    real(dp), parameter :: pi = acos(-1.0_dp)
    !> Half the width of a 1/3-octave band in decades of frequency (edges f_c*10^(+-1/20)).
    real(dp), parameter :: half_band = 0.05_dp
    !> Lines of the PSD the lowest band spans at least, by default.
    integer, parameter :: default_lines_per_band = 8
    !> Correlation of the power estimates of two Hann segments overlapping by 50 % (the
    !> square of the window's overlap correlation 0.167).
    real(dp), parameter :: overlap_correlation = 0.167_dp**2
    !> Lines of noise bandwidth of the Hann window.
    real(dp), parameter :: hann_noise_lines = 1.5_dp

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

    !> Welch's average (module description) of one or more histories sampled together
    !> (channels), built as their samples arrive: `start_welch`, `add_welch_samples` per
    !> piece, `welch_average`. It holds one segment of each channel and the sums of |X_k|^2.
    type :: welch_accumulator
        !> Segment length N [samples].
        integer :: segment_length = 0
        !> Number of channels.
        integer :: n_channels = 0
        !> Whole segments added so far.
        integer :: n_segments = 0
        !> Samples of the current segment held in `buffer` (rows 1..filled).
        integer :: filled = 0
        !> The Hann window w_j, j = 0..N-1.
        real(dp), allocatable :: window(:)
        !> The current segment of each channel, buffer(j, channel).
        real(dp), allocatable :: buffer(:, :)
        !> Sums of |X_k|^2 over the segments, sums(k, channel), k = 0..N/2.
        real(dp), allocatable :: sums(:, :)
        !> Room for one windowed segment: N values from the first element on a 64-byte
        !> boundary (`aligned_first`), so that FFTW gets the same plan, and the same bits, in
        !> every run, wherever the heap puts the array.
        real(dp), allocatable :: segment(:)
        !> Room for its lines X_k, k = 0..N/2, also from a 64-byte boundary.
        complex(dp), allocatable :: lines(:)
        !> Complex gains G_k,c of a filtered sum of the channels, gains(k, channel), k = 0..N/2
        !> (`set_welch_gains`; not allocated: none): its |sum_c G_k,c*X_k,c|^2 are summed in the
        !> last column of `sums`, the PSD of the channels each filtered and then added.
        complex(dp), allocatable :: gains(:, :)
        !> The filtered sum's lines of the current segment.
        complex(dp), allocatable :: mixed(:)
        !> The forward transform's plan.
        type(fft_plan_set) :: plans
    end type welch_accumulator

contains

    !> Exact centre frequency [Hz] of band x: 1000*10^(x/10).
    pure real(dp) function band_centre(x)
        !> Band number (0: the 1 kHz band).
        integer, intent(in) :: x

        band_centre = 1000.0_dp*10.0_dp**(x/10.0_dp)
    end function band_centre

    !> The lowest band whose centre is at or above f [Hz] (> 0); a centre given by its
    !> nominal, rounded value counts as that band.
    pure integer function first_band(f)
        !> Frequency [Hz].
        real(dp), intent(in) :: f

        first_band = edge_band(f, -1)
    end function first_band

    !> The band nearest f [Hz] (> 0) on the side `side` of it: -1 the lowest band whose centre
    !> is at or above f, +1 the highest at or below f; a centre given by its nominal, rounded
    !> value counts as that band. With side = -1, side*floor(side*y + 1e-9) is
    !> ceiling(y - 1e-9) exactly (negation is exact, so is rounding of a negated sum).
    pure integer function edge_band(f, side)
        !> Frequency [Hz], > 0.
        real(dp), intent(in) :: f
        !> -1: the lowest band at or above f (`first_band`); +1: the highest at or below f.
        integer, intent(in) :: side

        edge_band = side*floor(side*(10.0_dp*log10(f/1000.0_dp)) + 1.0e-9_dp)
        ! the nominal names round the exact centres by up to 1.5 %
        if (side*nominal_frequency(band_centre(edge_band + side)) <= side*f) edge_band = edge_band + side
    end function edge_band

    !> The nominal centre frequency [Hz] of a band (IEC 61260-1, annex E): its exact centre
    !> rounded to the preferred numbers 1, 1.25, 1.6, 2, 2.5, 3.15, 4, 5, 6.3, 8 times a power
    !> of ten (31.5 Hz, 1.25 kHz, ...).
    pure real(dp) function nominal_frequency(centre)
        !> Exact centre frequency [Hz], 1000*10^(x/10).
        real(dp), intent(in) :: centre

        real(dp), parameter :: preferred(0:9) = [1.0_dp, 1.25_dp, 1.6_dp, 2.0_dp, 2.5_dp, 3.15_dp, 4.0_dp, 5.0_dp, &
                                                 6.3_dp, 8.0_dp]
        integer :: x

        x = nint(10.0_dp*log10(centre/1000.0_dp))
        nominal_frequency = preferred(modulo(x, 10))*10.0_dp**(3 + floor(x/10.0_dp))
    end function nominal_frequency

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

        integer :: x

        centre = [(band_centre(x), x=first_band(f_low), min(edge_band(f_high, 1), highest_band_below(f_nyquist)))]
        lower = centre*10.0_dp**(-half_band)
        upper = centre*10.0_dp**half_band
    end subroutine third_octave_bands

    !> The highest band whose upper edge is at or below f_nyquist [Hz] (> 0).
    pure integer function highest_band_below(f_nyquist)
        !> Nyquist frequency 1/(2*dt) [Hz].
        real(dp), intent(in) :: f_nyquist

        highest_band_below = floor(10.0_dp*(log10(f_nyquist/1000.0_dp) - half_band)) + 1
        do while (band_centre(highest_band_below)*10.0_dp**half_band > f_nyquist)
            highest_band_below = highest_band_below - 1
        end do
    end function highest_band_below

    !> Segment length N [samples] of a Welch estimate whose lines resolve band x: the smallest
    !> power of two with 1/(N*dt) <= (band width)/lines.
    pure integer function segment_for_band(x, dt, lines)
        !> Band number.
        integer, intent(in) :: x
        !> Time step [s], > 0.
        real(dp), intent(in) :: dt
        !> Lines the band spans at least, >= 1.
        integer, intent(in) :: lines

        real(dp) :: width

        width = band_centre(x)*(10.0_dp**half_band - 10.0_dp**(-half_band))
        segment_for_band = 2
        do while (1.0_dp/(segment_for_band*dt) > width/lines .and. segment_for_band < 2**30)
            segment_for_band = 2*segment_for_band
        end do
    end function segment_for_band

    !> The lowest band a record of n_samples samples resolves: the lowest x whose segment
    !> (`segment_for_band`) is at most n_samples long.
    pure integer function lowest_resolved_band(n_samples, dt, lines)
        !> Samples of the record, >= 2.
        integer, intent(in) :: n_samples
        !> Time step [s], > 0.
        real(dp), intent(in) :: dt
        !> Lines the band spans at least, >= 1.
        integer, intent(in) :: lines

        integer :: longest

        ! the longest power-of-two segment in the record sets the finest line spacing
        longest = 2**(bit_size(n_samples) - 1 - leadz(n_samples))
        lowest_resolved_band = first_band(lines/(longest*dt*(10.0_dp**half_band - 10.0_dp**(-half_band))))
        do while (segment_for_band(lowest_resolved_band, dt, lines) > n_samples .and. lowest_resolved_band < 400)
            lowest_resolved_band = lowest_resolved_band + 1
        end do
        ! (segments stop doubling at 2^30 samples: band -200, 1e-17 Hz, ends the search)
        do while (segment_for_band(lowest_resolved_band - 1, dt, lines) <= n_samples &
                  .and. lowest_resolved_band > -200)
            lowest_resolved_band = lowest_resolved_band - 1
        end do
    end function lowest_resolved_band

    !> Start a Welch average of `n_channels` histories in segments of `segment_length` samples.
    subroutine start_welch(welch, segment_length, n_channels)
        !> The accumulator, emptied.
        type(welch_accumulator), intent(inout) :: welch
        !> Segment length N [samples], >= 2.
        integer, intent(in) :: segment_length
        !> Number of histories averaged together, >= 1.
        integer, intent(in) :: n_channels

        integer :: j, n

        call welch%plans%release()
        n = segment_length
        welch%segment_length = n
        welch%n_channels = n_channels
        welch%n_segments = 0
        welch%filled = 0
        welch%window = [(sin(pi*j/n)**2, j=0, n - 1)]
        if (allocated(welch%buffer)) deallocate (welch%buffer, welch%sums, welch%segment, welch%lines)
        if (allocated(welch%gains)) deallocate (welch%gains, welch%mixed)
        allocate (welch%buffer(n, n_channels), welch%sums(0:n/2, n_channels), welch%segment(n + 7), &
                  welch%lines(n/2 + 4))
        welch%sums = 0.0_dp
    end subroutine start_welch

    !> Also average the PSD of a filtered sum of the channels, sum_c G_c(f)*X_c(f): the last
    !> column of `welch_average`'s psd (after the channels'). Call after `start_welch`, before
    !> any sample.
    subroutine set_welch_gains(welch, gains)
        !> The accumulator, started.
        type(welch_accumulator), intent(inout) :: welch
        !> Gains G_k,c at the lines f_k = k/(N*dt), gains(k, channel), k = 0..N/2.
        complex(dp), intent(in) :: gains(0:, :)

        welch%gains = gains
        allocate (welch%mixed(0:welch%segment_length/2))
        deallocate (welch%sums)
        allocate (welch%sums(0:welch%segment_length/2, welch%n_channels + 1))
        welch%sums = 0.0_dp
    end subroutine set_welch_gains

    !> Add the next samples of every channel, samples(step, channel); each segment completed
    !> is windowed, transformed and added, and the next starts half a segment later.
    subroutine add_welch_samples(welch, samples)
        !> The accumulator.
        type(welch_accumulator), target, intent(inout) :: welch
        !> The next samples [N], as many rows as given, one column per channel.
        real(dp), intent(in) :: samples(:, :)

        integer :: n, hop, first, count, c, r, k

        n = welch%segment_length
        hop = n/2
        r = aligned_first(c_loc(welch%segment), storage_size(welch%segment)/8)
        k = aligned_first(c_loc(welch%lines), storage_size(welch%lines)/8)
        first = 1
        do while (first <= size(samples, 1))
            count = min(n - welch%filled, size(samples, 1) - first + 1)
            welch%buffer(welch%filled + 1:welch%filled + count, :) = samples(first:first + count - 1, :)
            welch%filled = welch%filled + count
            first = first + count
            if (welch%filled < n) exit
            if (allocated(welch%gains)) welch%mixed(:) = (0.0_dp, 0.0_dp)
            do c = 1, welch%n_channels
                welch%segment(r:r + n - 1) = welch%window*(welch%buffer(:, c) - sum(welch%buffer(:, c))/n)
                call welch%plans%forward(welch%segment(r:r + n - 1), welch%lines(k:k + n/2))
                welch%sums(:, c) = welch%sums(:, c) + abs(welch%lines(k:k + n/2))**2
                if (allocated(welch%gains)) welch%mixed(:) = welch%mixed + welch%gains(:, c)*welch%lines(k:k + n/2)
            end do
            if (allocated(welch%gains)) welch%sums(:, size(welch%sums, 2)) = welch%sums(:, size(welch%sums, 2)) &
                                                                          + abs(welch%mixed)**2
            welch%n_segments = welch%n_segments + 1
            welch%buffer(1:n - hop, :) = welch%buffer(hop + 1:n, :)
            welch%filled = n - hop
        end do
    end subroutine add_welch_samples

    !> Index of the first element of an array (its first element at `address`, `bytes` per
    !> element, 8 or 16) that lies on a 64-byte boundary; within the first 8 elements when the
    !> array is 8-byte aligned, as every allocated array is.
    integer function aligned_first(address, bytes)
        type(c_ptr), intent(in) :: address
        integer, intent(in) :: bytes

        integer(c_intptr_t) :: offset

        offset = modulo(transfer(address, 0_c_intptr_t), 64_c_intptr_t)
        aligned_first = 1
        if (offset /= 0 .and. modulo(64 - offset, int(bytes, c_intptr_t)) == 0) &
            aligned_first = 1 + int((64 - offset)/bytes)
    end function aligned_first

    !> The one-sided PSD of each channel from the segments added so far (at least one), and
    !> the accumulator's FFTW plans released (a new `start_welch` makes them again).
    subroutine welch_average(welch, dt, psd, df, error)
        !> The accumulator.
        type(welch_accumulator), intent(inout) :: welch
        !> Time step [s], > 0.
        real(dp), intent(in) :: dt
        !> PSD psd(k, channel) [N^2/Hz] at f_k = k*df, k = 0..N/2 (and of the filtered sum last).
        real(dp), allocatable, intent(out) :: psd(:, :)
        !> Line spacing df = 1/(N*dt) [Hz].
        real(dp), intent(out) :: df
        !> Set when no whole segment was added or a transform failed (non-finite lines).
        type(error_type), allocatable, intent(out) :: error

        integer :: n

        n = welch%segment_length
        df = 1.0_dp/(n*dt)
        call welch%plans%release()
        if (welch%n_segments == 0) then
            call fatal_error(error, 'force spectrum: the record is shorter than one segment of '//int_text(n) &
                             //' samples')
            return
        end if
        allocate (psd(0:n/2, size(welch%sums, 2)))
        psd(:, :) = 2.0_dp*welch%sums*dt/(sum(welch%window**2)*welch%n_segments)
        psd(0, :) = psd(0, :)/2.0_dp
        if (mod(n, 2) == 0) psd(n/2, :) = psd(n/2, :)/2.0_dp
        if (.not. all(abs(psd) <= huge(1.0_dp))) call fatal_error(error, 'force spectrum: the transform of a ' &
            //int_text(n)//'-sample segment is not finite (a non-finite force, or FFTW could not plan)', &
            stat_numerical)
    end subroutine welch_average

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

        type(welch_accumulator) :: welch
        real(dp), allocatable :: psds(:, :)

        df = 0.0_dp
        n_segments = 0
        if (.not. dt > 0.0_dp .or. segment_length < 2 .or. segment_length > size(samples)) then
            call fatal_error(error, 'force spectrum: expected dt > 0 and a segment of 2 to '//int_text(size(samples)) &
                             //' samples (the record), found dt = '//real_text(dt)//' s and '//int_text(segment_length))
            return
        end if
        call start_welch(welch, segment_length, 1)
        call add_welch_samples(welch, reshape(samples, [size(samples), 1]))
        n_segments = welch%n_segments
        call welch_average(welch, dt, psds, df, error)
        if (allocated(error)) return
        allocate (psd(0:segment_length/2))
        psd(:) = psds(:, 1)
    end subroutine welch_psd

    !> Band powers [N^2]: the PSD integrated over each band's edges (module description).
    pure function band_powers(psd, df, lower, upper) result(power)
        !> PSD P_k [N^2/Hz] at f_k = k*df, k = 0..N/2 (any lower bound of the array).
        real(dp), intent(in) :: psd(0:)
        !> Line spacing [Hz].
        real(dp), intent(in) :: df
        !> Lower band edges [Hz].
        real(dp), intent(in) :: lower(:)
        !> Upper band edges [Hz], same size.
        real(dp), intent(in) :: upper(:)
        real(dp) :: power(size(lower))

        integer :: b, k, top

        top = ubound(psd, 1)
        do b = 1, size(lower)
            power(b) = 0.0_dp
            do k = max(0, floor(lower(b)/df)), min(top, ceiling(upper(b)/df))
                power(b) = power(b) + psd(k)*max(0.0_dp, min(upper(b), (k + 0.5_dp)*df) - max(lower(b), (k - 0.5_dp)*df))
            end do
        end do
    end function band_powers

    !> Statistical standard deviation [dB] of a band level estimated from `n_segments`
    !> segments with line spacing df, for a random (noise-like) force (module description).
    elemental real(dp) function level_spread(lower, upper, df, n_segments)
        !> Lower band edge [Hz].
        real(dp), intent(in) :: lower
        !> Upper band edge [Hz].
        real(dp), intent(in) :: upper
        !> Line spacing [Hz].
        real(dp), intent(in) :: df
        !> Segments averaged, >= 1.
        integer, intent(in) :: n_segments

        real(dp) :: correlation

        correlation = 1.0_dp + 2.0_dp*(1.0_dp - 1.0_dp/n_segments)*overlap_correlation
        level_spread = 10.0_dp/log(10.0_dp)*sqrt(hann_noise_lines*correlation/((upper - lower)/df*n_segments))
    end function level_spread

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
        integer :: lines, n

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
        n = segment_for_band(first_band(f_low), dt, lines)
        if (n > size(samples)) then
            call fatal_error(error, 'force spectrum: the record ('//int_text(size(samples))//' samples, ' &
                             //real_text(size(samples)*dt)//' s) is shorter than the '//int_text(n) &
                             //' samples the band at '//real_text(spectrum%centre(1))//' Hz needs; ' &
                             //'raise f_low to at least '//real_text(nominal_frequency(band_centre( &
                             lowest_resolved_band(max(size(samples), 2), dt, lines))))//' Hz or give a longer record')
            return
        end if
        call welch_psd(samples, dt, n, psd, spectrum%df, spectrum%n_segments, error)
        if (allocated(error)) return
        spectrum%segment_length = n
        spectrum%power = band_powers(psd, spectrum%df, spectrum%lower, spectrum%upper)
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
