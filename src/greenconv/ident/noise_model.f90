!> The noise of a receptance and the weighted data of the maximum-likelihood fit (step 1 of
!> greenconv_ident_mlfit's description): the noise level from the smoothness of G, the smoothed
!> |G| of the relative noise model's weights, the lines left out (0 Hz with a lower residual,
!> outliers) and their weights 1/sigma_l; also the lines that are gross outliers before any fit
!> (repaired by their neighbours' cubic) and the line spacing of a grid.
module greenconv_ident_noise_model
    use, intrinsic :: iso_fortran_env, only: int64
    use greenconv_core_kinds, only: dp
    use greenconv_core_constants, only: pi, two_pi
    use greenconv_core_sorting, only: median, heap_sort
    use greenconv_model_frf, only: frf_type
    use greenconv_ident_ml_types, only: ml_options, ml_result
    use greenconv_ident_lm_fit, only: data_type, narrow_band, within_range
    implicit none
    private

    public :: estimate_noise, smoothed_magnitude, prepare_data, gross_outliers, interpolated
    public :: line_spacing, spacing_at, band_bounds


    !> A line whose |G| exceeds the median |G| by this factor is an outlier before any fit.
    real(dp), parameter :: gross_ratio = 1.0e100_dp
    !> The 'band' noise model: at most this many bands, each of at least band_lines lines.
    integer, parameter :: max_bands = 32, band_lines = 32

contains

    !> Noise level of a receptance from the smoothness of G (step 1 of greenconv_ident_mlfit's description):
    !> rho with sigma_l = rho*|G_l| for 'relative', sigma [m/N] for 'absolute'.
    pure real(dp) function estimate_noise(receptance, noise_model) result(level)
        !> Receptance lines [m/N] on a uniform grid (at least 5).
        complex(dp), intent(in) :: receptance(:)
        !> 'relative' or 'absolute'.
        character(len=*), intent(in) :: noise_model

        real(dp), parameter :: c(5) = [1.0_dp, -4.0_dp, 6.0_dp, -4.0_dp, 1.0_dp]/sqrt(70.0_dp)
        real(dp) :: q(size(receptance) - 4)
        integer :: l

        if (noise_model == 'absolute') then
            do l = 1, size(q)
                q(l) = abs(sum(c*receptance(l:l + 4)))**2
            end do
        else
            q = relative_differences(receptance)
        end if
        level = sqrt(median(q)/log(2.0_dp))
    end function estimate_noise

    !> The squared 4th differences of G relative to the lines they span, |d_l|^2/sum_j c_j^2*|G_{l+j}|^2
    !> (d_l = sum_j c_j*G_{l+j}, sum c_j^2 = 1): rho^2 times an exponential variable where G is
    !> smooth over five lines and the noise relative.
    pure function relative_differences(receptance) result(q)
        !> Receptance lines [m/N] on a uniform grid (at least 5).
        complex(dp), intent(in) :: receptance(:)
        !> One value per difference, size(receptance) - 4.
        real(dp) :: q(size(receptance) - 4)

        real(dp), parameter :: c(5) = [1.0_dp, -4.0_dp, 6.0_dp, -4.0_dp, 1.0_dp]/sqrt(70.0_dp)
        real(dp) :: m
        integer :: l

        do l = 1, size(q)
            ! Scaled by the largest |G| of the five lines: no overflow for any finite G.
            m = max(maxval(abs(receptance(l:l + 4))), tiny(1.0_dp))
            q(l) = abs(sum(c*receptance(l:l + 4))/m)**2/max(sum(c**2*abs(receptance(l:l + 4)/m)**2), tiny(1.0_dp))
        end do
    end function relative_differences

    !> Noise of the 'floor' model, sigma_l^2 = (rho*|G_l|)^2 + s^2, from the smoothness of G: the
    !> 4th difference d_l (as estimate_noise) has E|d_l|^2 = rho^2*a_l + s^2, a_l = sum_j c_j^2*|G_{l+j}|^2.
    !> The lines are sorted by a_l into `bins` groups of equal count; in each, median(|d|^2)/ln 2
    !> against median(a) (robust to the lines where d sees a resonance, as in estimate_noise), and
    !> rho^2, s^2 >= 0 fitted to these points by least squares relative to each point (the
    !> points span many decades). Too few lines for the bins: s = 0 and rho as 'relative'.
    pure subroutine estimate_floor_noise(receptance, level, floor_level)
        !> Receptance lines [m/N] on a uniform grid (at least 5).
        complex(dp), intent(in) :: receptance(:)
        !> rho, relative to |G|.
        real(dp), intent(out) :: level
        !> s [m/N].
        real(dp), intent(out) :: floor_level

        integer, parameter :: bins = 16
        real(dp), parameter :: c(5) = [1.0_dp, -4.0_dp, 6.0_dp, -4.0_dp, 1.0_dp]/sqrt(70.0_dp)
        real(dp) :: q(size(receptance) - 4), a(size(receptance) - 4), sorted(size(receptance) - 4)
        real(dp) :: x(bins), y(bins), w(bins), scale, low, high, s_xx, s_x, s_1, s_xy, s_y, det, r, s2
        integer :: l, b, n, first, last
        logical :: inside(size(receptance) - 4)

        n = size(q)
        floor_level = 0.0_dp
        if (n < 5*bins) then
            level = estimate_noise(receptance, 'relative')
            return
        end if
        scale = max(maxval(abs(receptance)), tiny(1.0_dp))
        do l = 1, n
            q(l) = abs(sum(c*receptance(l:l + 4))/scale)**2
            a(l) = sum(c**2*abs(receptance(l:l + 4)/scale)**2)
        end do
        sorted = a
        call heap_sort(sorted)
        do b = 1, bins
            call band_bounds(b, n, bins, first, last)
            low = sorted(first)
            high = sorted(last)
            inside = a >= low .and. a <= high
            x(b) = median(pack(a, inside))
            y(b) = max(median(pack(q, inside))/log(2.0_dp), tiny(1.0_dp))
        end do
        ! Weighted least squares of y = r*x + s2 with weights 1/y^2, then r, s2 >= 0.
        w = 1.0_dp/y**2
        s_xx = sum(w*x*x)
        s_x = sum(w*x)
        s_1 = sum(w)
        s_xy = sum(w*x*y)
        s_y = sum(w*y)
        det = s_xx*s_1 - s_x**2
        r = -1.0_dp
        s2 = -1.0_dp
        if (det > 0.0_dp) then
            r = (s_xy*s_1 - s_x*s_y)/det
            s2 = (s_xx*s_y - s_x*s_xy)/det
        end if
        if (.not. (s2 > 0.0_dp)) then
            s2 = 0.0_dp
            r = s_xy/s_xx
        else if (.not. (r > 0.0_dp)) then
            r = 0.0_dp
            s2 = s_y/s_1
        end if
        level = sqrt(max(r, 0.0_dp))
        floor_level = sqrt(s2)*scale
    end subroutine estimate_floor_noise

    !> Noise of the 'band' model, sigma_l = rho_b*|G_l| with one level per band of neighbouring
    !> lines (a measurement whose coherence changes along the band: the lines below 20 Hz of
    !> pyuff's beam, whose phase wanders by up to 180 degrees between neighbours, are 10 times
    !> noisier than those between its modes). The 4th differences q_l of estimate_noise's
    !> relative model are cut into n_bands groups of equal count (at most max_bands, each at
    !> least band_lines), rho_b^2 = median(q)/ln 2 in each (the median ignores the lines near
    !> an under-resolved peak, as in estimate_noise); each line takes the level of the group of
    !> the difference centred on it. Too few lines for two bands: one band ('relative').
    pure subroutine estimate_band_noise(receptance, line_level, n_bands)
        !> Receptance lines [m/N] on a uniform grid (at least 5).
        complex(dp), intent(in) :: receptance(:)
        !> rho_b of each line, relative to |G|.
        real(dp), intent(out) :: line_level(size(receptance))
        !> Number of bands (noise parameters).
        integer, intent(out) :: n_bands

        real(dp) :: q(size(receptance) - 4), level
        integer :: b, n, first, last

        n = size(q)
        q = relative_differences(receptance)
        n_bands = max(1, min(max_bands, n/band_lines))
        do b = 1, n_bands
            call band_bounds(b, n, n_bands, first, last)
            level = sqrt(median(q(first:last))/log(2.0_dp))
            ! Line l + 2 is the centre of difference l; the two lines at each end take the nearest band.
            if (b == 1) first = -1
            if (b == n_bands) last = n + 2
            line_level(first + 2:last + 2) = level
        end do
    end subroutine estimate_band_noise

    !> sqrt of the mean of |G|^2 over each line and its two neighbours on each side: the scale
    !> of the relative noise model during the order search, with the noise of |G| in the
    !> weights reduced by sqrt(5) and no dependence on a model (a model-based weight would
    !> have to be refitted after every change of the model). Each |G| is first clipped at ten
    !> times the median of the five, so that one outlier line neither hides among its
    !> neighbours' weights nor takes their weight away.
    pure function smoothed_magnitude(g) result(m)
        !> Receptance lines [m/N].
        complex(dp), intent(in) :: g(:)
        !> Smoothed |G| per line [m/N].
        real(dp) :: m(size(g))

        real(dp) :: window(5), top
        integer :: l, n, first, last

        n = size(g)
        do l = 1, n
            first = max(1, l - 2)
            last = min(n, l + 2)
            window(:last - first + 1) = abs(g(first:last))
            associate (w => window(:last - first + 1))
                w = min(w, 10.0_dp*median(w))
                top = max(maxval(w), tiny(1.0_dp))
                m(l) = top*sqrt(sum((w/top)**2)/size(w))
            end associate
        end do
    end function smoothed_magnitude

    !> The weighted data: the noise standard deviation per line (given, or estimated from the
    !> receptance), the lines used (a 0 Hz line is left out when a lower residual may be
    !> fitted, outlier lines always), their weights 1/sigma_l and the MDL price per parameter ln(2L).
    subroutine prepare_data(frf, outliers, skip_zero, options, result, data)
        !> The receptance, outlier lines already replaced by their neighbours' interpolation.
        type(frf_type), intent(in) :: frf
        !> Lines left out (indices into frf%frequency).
        integer, intent(in) :: outliers(:)
        !> Whether a 0 Hz line is left out (a lower residual may be fitted).
        logical, intent(in) :: skip_zero
        !> Settings: the noise given or its model, the floor, max_iterations.
        type(ml_options), intent(in) :: options
        !> The result: noise_level and noise_estimated are set.
        type(ml_result), intent(inout) :: result
        !> The weighted data.
        type(data_type), intent(out) :: data

        real(dp) :: sigma(frf%n_freq()), floor(frf%n_freq()), line_level(frf%n_freq())
        logical :: used(frf%n_freq())
        integer :: l

        floor(:) = max(options%noise_floor*abs(frf%receptance), tiny(1.0_dp)*1.0e10_dp)
        result%noise_level = 1.0_dp
        result%noise_estimated = .not. allocated(options%sigma)
        result%noise_model = options%noise_model
        result%noise_parameters = merge(2, 1, options%noise_model == 'floor')
        if (allocated(options%sigma)) then
            sigma(:) = options%sigma
            result%noise_model = 'given'
            result%noise_parameters = 0
        else
            if (options%noise_model == 'floor') then
                call estimate_floor_noise(frf%receptance, result%noise_level, result%noise_floor_level)
            else if (options%noise_model == 'band') then
                call estimate_band_noise(frf%receptance, line_level, result%noise_parameters)
                result%noise_level = sqrt(sum(line_level**2)/size(line_level))
                result%band_level_range = [minval(line_level), maxval(line_level)]
            else
                result%noise_level = estimate_noise(frf%receptance, options%noise_model)
            end if
            if (options%noise_model == 'absolute') then
                sigma(:) = result%noise_level
            else if (options%noise_model == 'floor') then
                sigma(:) = within_range(hypot(result%noise_level*smoothed_magnitude(frf%receptance), &
                                              result%noise_floor_level))
            else if (options%noise_model == 'band') then
                sigma(:) = within_range(line_level*smoothed_magnitude(frf%receptance))
            else
                sigma(:) = within_range(result%noise_level*smoothed_magnitude(frf%receptance))
            end if
        end if
        sigma(:) = max(sigma, floor)
        used(:) = .true.
        if (skip_zero .and. frf%frequency(1) == 0.0_dp) used(1) = .false.
        used(outliers) = .false.
        data%line = pack([(l, l=1, frf%n_freq())], used)
        data%omega = two_pi*frf%frequency(data%line)
        data%g = frf%receptance(data%line)
        data%weight = 1.0_dp/sigma(data%line)
        data%floor = floor(data%line)
        data%penalty = log(2.0_dp*size(data%g))
        data%f_max = frf%f_max()
        data%df = line_spacing(frf)
        data%min_decay = pi*narrow_band*data%df
        data%max_iterations = options%max_iterations
        data%relative = result%noise_estimated .and. options%noise_model /= 'absolute'
        data%level = result%noise_level
        data%absolute_floor = result%noise_floor_level
        if (data%relative .and. options%noise_model == 'band') data%line_level = line_level(data%line)
    end subroutine prepare_data

    !> Lines whose |G| exceeds the median |G| of the nonzero lines above 0 Hz by more than
    !> gross_ratio: no receptance spans that many decades, and the sums of squares of the
    !> diagram and the fit would overflow on them. They are recorded as outliers and replaced by
    !> their neighbours' interpolation before anything else.
    subroutine gross_outliers(frf, result)
        !> The receptance, its gross outliers replaced on return.
        type(frf_type), intent(inout) :: frf
        !> The result: the outliers are appended to outlier_line, outlier_frequency, outlier_excess.
        type(ml_result), intent(inout) :: result

        real(dp) :: magnitude(frf%n_freq() - 1), typical
        integer :: l

        magnitude(:) = abs(frf%receptance(2:))
        if (.not. any(magnitude > 0.0_dp)) return
        typical = median(pack(magnitude, magnitude > 0.0_dp))
        do l = 1, frf%n_freq()
            if (.not. (abs(frf%receptance(l)) > gross_ratio*typical)) cycle
            result%outlier_line = [result%outlier_line, l]
            result%outlier_frequency = [result%outlier_frequency, frf%frequency(l)]
            result%outlier_excess = [result%outlier_excess, 0.0_dp]
        end do
        do l = 1, size(result%outlier_line)
            frf%receptance(result%outlier_line(l)) = interpolated(frf%receptance, result%outlier_line, &
                                                                  result%outlier_line(l))
        end do
    end subroutine gross_outliers

    !> The value of an outlier line from its neighbours: the cubic through the two lines on
    !> each side, (-G(l-2) + 4*G(l-1) + 4*G(l+1) - G(l+2))/6, or the mean of the nearest good
    !> lines when the cubic's are not all available (an edge, another outlier).
    pure complex(dp) function interpolated(g, outliers, l) result(value)
        !> Receptance lines [m/N].
        complex(dp), intent(in) :: g(:)
        !> Lines that are outliers (not used for the value).
        integer, intent(in) :: outliers(:)
        !> The line whose value [m/N] is wanted.
        integer, intent(in) :: l

        integer :: j, n_good
        logical :: good(-2:2)

        do j = -2, 2
            good(j) = l + j >= 1 .and. l + j <= size(g)
            if (good(j)) good(j) = .not. any(outliers == l + j)
        end do
        good(0) = .false.
        if (all(good([-2, -1, 1, 2]))) then
            value = (-g(l - 2) + 4.0_dp*g(l - 1) + 4.0_dp*g(l + 1) - g(l + 2))/6.0_dp
            return
        end if
        value = (0.0_dp, 0.0_dp)
        n_good = 0
        do j = -2, 2
            if (.not. good(j)) cycle
            value = value + g(l + j)
            n_good = n_good + 1
        end do
        if (n_good > 0) value = value/n_good
    end function interpolated

    !> First and last of the n items in band b of n_bands bands of equal count (the counts differ
    !> by at most one): items 1 + (b - 1)*n/n_bands to b*n/n_bands, the products in 64-bit
    !> integers (b*n passes 2^31 for a few hundred thousand lines cut into bands of 32).
    pure subroutine band_bounds(b, n, n_bands, first, last)
        !> The band, 1 to n_bands.
        integer, intent(in) :: b
        !> Number of items.
        integer, intent(in) :: n
        !> Number of bands.
        integer, intent(in) :: n_bands
        !> First item of the band.
        integer, intent(out) :: first
        !> Last item of the band.
        integer, intent(out) :: last

        first = int(1_int64 + (int(b - 1, int64)*n)/n_bands)
        last = int((int(b, int64)*n)/n_bands)
    end subroutine band_bounds

    !> Line spacing of the data [Hz]: df on the uniform grid from 0 Hz, else the smallest
    !> spacing between two lines (the narrowest pole a line can still see is set by it).
    pure real(dp) function line_spacing(frf)
        !> The receptance's grid.
        type(frf_type), intent(in) :: frf

        if (frf%uniform_from_zero()) then
            line_spacing = frf%df()
        else
            line_spacing = minval(frf%frequency(2:) - frf%frequency(:frf%n_freq() - 1))
        end if
    end function line_spacing

    !> Spacing of the lines around frequency f [Hz]: the mean of the two intervals beside
    !> the line nearest f (the one interval at an end of the grid).
    pure real(dp) function spacing_at(frf, f)
        !> The receptance's grid.
        type(frf_type), intent(in) :: frf
        !> Frequency [Hz].
        real(dp), intent(in) :: f

        integer :: l, low, high

        l = minloc(abs(frf%frequency - f), 1)
        low = max(l - 1, 1)
        high = min(l + 1, frf%n_freq())
        spacing_at = (frf%frequency(high) - frf%frequency(low))/(high - low)
    end function spacing_at

end module greenconv_ident_noise_model
