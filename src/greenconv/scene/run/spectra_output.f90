!> Force spectra of the contact runs (`&scene spectra = .true.`): each method's run also
!> writes `<output_dir>/<name>_<method>_spectra.dat`, the 1/3-octave band levels of its
!> total contact force in dB re 1 N (greenconv_io_spectra: IEC 61260-1 bands, Welch's PSD
!> with a Hann window and 50 % overlap), and with `spectra_points` those of each contact
!> point of a multi-point run. A multi-point run also writes
!> `<output_dir>/<name>_<method>_area_spectra.dat`, the band levels of its contact area in
!> dB re 1 m^2 (the same columns, power in m^4).
!>
!> The force of every step is analysed (not only the rows `output_every` keeps), as the run
!> streams: each block's forces go into a Welch accumulator that holds one segment per
!> history, so the memory stays that of one segment, whatever N_t, and the file is the same
!> whatever the block size. The band range was resolved and checked when the scene was read
!> (greenconv_scene_read_input's `check_spectra`). The file is always text, written atomically
!> when the run ends; a run stopped by a numerical fault writes none (and removes one left
!> by an earlier run, which would no longer match the column file, as its narrowband file).
!>
!> A single-point run of a structure whose receptance is known (a model whose registry row
!> names `receptance`, as `wheel_rail`, which writes a linear reference beside the runs,
!> greenconv_scene_run_linear_reference) also writes `<output_dir>/<name>_<method>_narrowband.dat`:
!> f [Hz] and the force PSD [N^2/Hz] on the Welch lines, the lines of the reference's
!> `<name>_linear_narrowband.dat`.
!>
!> Columns: f_nominal, f_centre, f_lower, f_upper [Hz], power [N^2], level [dB re 1 N],
!> spread_db [dB] (the statistical standard deviation of the level for a random force), then
!> level_1 .. level_Nc [dB re 1 N] of the points. The header states the window, the segment
!> length and count, the overlap and the spread.
module greenconv_scene_run_spectra_output
    use, intrinsic :: iso_fortran_env, only: int64
    use greenconv_core_kinds, only: dp
    use greenconv_core_error, only: error_type
    use greenconv_core_text, only: int_text, sci_text
    use greenconv_core_number_text, only: compact_real
    use greenconv_io_files, only: write_columns
    use greenconv_io_spectra, only: welch_accumulator, start_welch, add_welch_samples, welch_average, &
                                    third_octave_bands, first_band, segment_for_band, nominal_frequency, band_powers, &
                                    level_spread, default_lines_per_band
    use greenconv_scene_read_facade, only: scene_type
    use greenconv_scene_models_facade, only: structure_kind, find_model
    implicit none
    private

    public :: force_spectra, start_force_spectra, add_contact_forces, finish_force_spectra, spectra_path
    public :: spectra_line, spectra_segment_length, band_table

    !> The spectra of one method's run, built block by block.
    type :: force_spectra
        !> Whether the scene asks for spectra.
        logical :: active = .false.
        !> Whether the accumulator has been started (at the first block, which gives N_c).
        logical :: started = .false.
        !> Whether each point's level is written too.
        logical :: per_point = .false.
        !> Whether the history is the contact area [m^2] (`<name>_<method>_area_spectra.dat`)
        !> rather than the contact force [N].
        logical :: area = .false.
        !> Segment length N [samples].
        integer :: segment_length = 0
        !> Steps analysed so far.
        integer(int64) :: steps = 0
        !> Welch's average of the total force (channel 1) and of each point.
        type(welch_accumulator) :: welch
    end type force_spectra

contains

    !> Path of a method's spectra file: `<output_dir>/<name>_<method>_spectra.dat`, or of its
    !> contact area's, `<output_dir>/<name>_<method>_area_spectra.dat` (a subroutine: a
    !> deferred-length function result keeps its length in a static shared by threads).
    subroutine spectra_path(scene, method, path, area)
        !> The scene.
        type(scene_type), intent(in) :: scene
        !> Method name.
        character(len=*), intent(in) :: method
        !> The path.
        character(len=:), allocatable, intent(out) :: path
        !> Whether the contact area's file is meant.
        logical, intent(in), optional :: area

        path = scene%output_dir//'/'//scene%name//'_'//method//'_spectra.dat'
        if (present(area)) then
            if (area) path = scene%output_dir//'/'//scene%name//'_'//method//'_area_spectra.dat'
        end if
    end subroutine spectra_path

    !> What a run's spectra will be, for the scene's summary and `--check`: '' when off, else
    !> e.g. "force spectra 400 Hz to 4000 Hz (11 bands), 2 Hann segments of 1024 samples".
    subroutine spectra_line(scene, line)
        !> The scene, read by `read_scene`.
        type(scene_type), intent(in) :: scene
        !> The line.
        character(len=:), allocatable, intent(out) :: line

        real(dp), allocatable :: centre(:), lower(:), upper(:)
        integer :: n

        line = ''
        if (.not. scene%spectra .or. scene%task /= 'contact') return
        call third_octave_bands(scene%spectra_f_low, scene%spectra_f_high, 0.5_dp/scene%dt, centre, lower, upper)
        n = spectra_segment_length(scene)
        line = 'force spectra '//compact_real(nominal_frequency(scene%spectra_f_low))//' Hz to ' &
               //compact_real(nominal_frequency(scene%spectra_f_high))//' Hz ('//int_text(size(centre)) &
               //' bands), '//int_text(segments(int(scene%n_steps, int64), n))//' Hann segment' &
               //trim(merge('s', ' ', segments(int(scene%n_steps, int64), n) > 1))//' of '//int_text(n)//' samples'
    end subroutine spectra_line

    !> Get ready for a method's run of `scene`.
    subroutine start_force_spectra(spectra, scene, area)
        !> The spectra, emptied.
        type(force_spectra), intent(inout) :: spectra
        !> The scene.
        type(scene_type), intent(in) :: scene
        !> Whether the history analysed is the contact area [m^2] (default: the force).
        logical, intent(in), optional :: area

        spectra%active = scene%spectra .and. scene%task == 'contact'
        spectra%started = .false.
        spectra%area = .false.
        if (present(area)) spectra%area = area
        spectra%per_point = scene%spectra_points .and. .not. spectra%area
        spectra%steps = 0
        if (spectra%active) spectra%segment_length = spectra_segment_length(scene)
    end subroutine start_force_spectra

    !> Add a block's forces: the total contact force of each step and, for several points,
    !> each point's force.
    subroutine add_contact_forces(spectra, total, points)
        !> The spectra.
        type(force_spectra), intent(inout) :: spectra
        !> Total contact force [N] of each step of the block.
        real(dp), intent(in) :: total(:)
        !> Force [N] of each point, points(step, point); no columns for a single point.
        real(dp), intent(in) :: points(:, :)

        integer :: n_points

        if (.not. spectra%active) return
        n_points = 0
        if (spectra%per_point .and. size(points, 2) > 1) n_points = size(points, 2)
        if (.not. spectra%started) then
            call start_welch(spectra%welch, spectra%segment_length, 1 + n_points)
            spectra%started = .true.
        end if
        if (n_points > 0) then
            call add_welch_samples(spectra%welch, reshape([total, reshape(points, [size(points)])], &
                                                          [size(total), 1 + n_points]))
        else
            call add_welch_samples(spectra%welch, reshape(total, [size(total), 1]))
        end if
        spectra%steps = spectra%steps + size(total)
    end subroutine add_contact_forces

    !> End a method's spectra. When the run succeeded (`error` not set), write the file;
    !> otherwise remove a spectra file of that name left by an earlier run (the run's own
    !> error is kept).
    subroutine finish_force_spectra(spectra, scene, method, error)
        !> The spectra of the run.
        type(force_spectra), intent(inout) :: spectra
        !> The scene.
        type(scene_type), intent(in) :: scene
        !> Method name.
        character(len=*), intent(in) :: method
        !> The run's error on entry (a fault, a failed write); a failed spectra file on return.
        type(error_type), allocatable, intent(inout) :: error

        real(dp), allocatable :: psd(:, :), table(:, :), lower(:), upper(:)
        character(len=:), allocatable :: comments(:), path
        real(dp) :: df
        integer :: c, n_channels, unit, stat

        if (.not. spectra%active) return
        call spectra_path(scene, method, path, spectra%area)
        if (allocated(error) .or. .not. spectra%started) then
            call spectra%welch%plans%release()
            open (newunit=unit, file=path, status='old', iostat=stat)
            if (stat == 0) close (unit, status='delete', iostat=stat)
            path = scene%output_dir//'/'//scene%name//'_'//method//'_narrowband.dat'
            if (.not. spectra%area) open (newunit=unit, file=path, status='old', iostat=stat)
            if (.not. spectra%area .and. stat == 0) close (unit, status='delete', iostat=stat)
            return
        end if
        call welch_average(spectra%welch, scene%dt, psd, df, error)
        if (allocated(error)) then
            error%message = scene%file//': '//method//': '//error%message
            return
        end if
        n_channels = size(psd, 2)
        call band_table(scene, psd(:, 1), df, n_channels, table)
        lower = table(:, 3)
        upper = table(:, 4)
        do c = 2, n_channels
            table(:, 6 + c) = 10.0_dp*log10(max(band_powers(psd(:, c), df, lower, upper), tiny(1.0_dp)))
        end do
        table(:, 7) = level_spread(lower, upper, df, spectra%welch%n_segments)
        call spectra_header(scene, method, spectra, df, n_channels - 1, table(:, 7), comments)
        call write_columns(path, comments, table, error)
        if (.not. allocated(error)) call write_narrowband(spectra, scene, method, psd, df, comments, error)
    end subroutine finish_force_spectra

    !> `<name>_<method>_narrowband.dat` (module description) for a single-point force run of a
    !> model with a known receptance; nothing otherwise.
    subroutine write_narrowband(spectra, scene, method, psd, df, comments, error)
        type(force_spectra), intent(in) :: spectra
        type(scene_type), intent(in) :: scene
        character(len=*), intent(in) :: method
        real(dp), intent(in) :: psd(:, :), df
        character(len=*), intent(in) :: comments(:)
        type(error_type), allocatable, intent(inout) :: error

        type(structure_kind) :: model
        character(len=len(comments)), allocatable :: lines(:)
        integer :: k

        if (spectra%area .or. size(psd, 2) /= 1) return
        model = find_model(scene%model)
        if (.not. associated(model%receptance)) return
        lines = [comments(1), comments(3), comments(7:8)]
        lines(1) = lines(1)(:index(lines(1), ': 1/3-octave') - 1)//': power spectral density of the total contact ' &
                   //'force on the Welch lines, '//lines(1)(index(lines(1), 'every step'):)
        lines(3) = 'units: Hz N^2/Hz'
        lines(4) = 'f psd_force'
        call write_columns(scene%output_dir//'/'//scene%name//'_'//method//'_narrowband.dat', lines, &
                           reshape([[(k*df, k=0, size(psd, 1) - 1)], psd(:, 1)], [size(psd, 1), 2]), error)
    end subroutine write_narrowband

    !> The header lines of a spectra file.
    subroutine spectra_header(scene, method, spectra, df, n_points, spread, comments)
        type(scene_type), intent(in) :: scene
        character(len=*), intent(in) :: method
        type(force_spectra), intent(in) :: spectra
        real(dp), intent(in) :: df, spread(:)
        integer, intent(in) :: n_points
        character(len=:), allocatable, intent(out) :: comments(:)

        character(len=:), allocatable :: lines(:), names, units, what, power_unit, level_unit
        integer :: n, k, unused, i

        n = spectra%segment_length
        k = spectra%welch%n_segments
        unused = int(spectra%steps - (int(k - 1, int64)*(n/2) + n))
        what = 'the total contact force'
        power_unit = 'N^2'
        level_unit = 'dB_re_1N'
        if (spectra%area) then
            what = 'the contact area (the shares of the points in contact)'
            power_unit = 'm^4'
            level_unit = 'dB_re_1m^2'
        end if
        if (n_points > 0) what = what//' and of each of the '//int_text(n_points)//' points (level_i: the i-th ' &
                                 //'point of the column file)'
        names = 'f_nominal f_centre f_lower f_upper power level spread_db'
        units = 'Hz Hz Hz Hz '//power_unit//' '//level_unit//' dB'
        do i = 1, n_points
            names = names//' level_'//int_text(i)
            units = units//' dB_re_1N'
        end do
        allocate (character(len=max(400, len(names) + 8)) :: lines(8))
        lines(1) = 'greenconv scene '//scene%name//', method '//method//': 1/3-octave band levels of '//what &
                   //', every step of the run ('//int_text(int(spectra%steps))//' steps of '//sci_text(scene%dt) &
                   //' s, f_s = '//compact_real(1.0_dp/scene%dt)//' Hz)'
        lines(2) = 'bands: IEC 61260-1 base 10, exact centres f_centre = 1000*10^(x/10) Hz, f_nominal their ' &
                   //'preferred-number names, edges f_centre*10^(+-1/20); level = 10*log10(power/1 N^2) dB re 1 N'
        if (spectra%area) lines(2) = lines(2)(:index(lines(2), 'level =') - 1)//'level = 10*log10(power/1 m^4) ' &
                                     //'dB re 1 m^2'
        lines(3) = 'PSD: Welch, Hann window (periodic, sin^2), segments of '//int_text(n)//' samples (' &
                   //compact_real(n*scene%dt)//' s, line spacing df = '//compact_real(df)//' Hz, at least ' &
                   //int_text(default_lines_per_band)//' lines in the lowest band), 50 % overlap, ' &
                   //int_text(k)//' segments averaged, each segment''s mean removed; the last ' &
                   //int_text(unused)//' steps fill no whole segment and are not used'
        lines(4) = 'power: the PSD integrated over the band edges (lines split at the edges), so adjacent bands ' &
                   //'add up; a sine of amplitude A gives A^2/2'
        lines(5) = 'spread_db: statistical standard deviation of a level for a random, noise-like force, ' &
                   //'4.34*sqrt(1.5*r/(n_lines*K)) (Hann: 1.5 lines of noise bandwidth, r = 1 + 2*(1 - 1/K)*0.028 ' &
                   //'for 50 % overlap); '//compact_real(maxval(spread))//' dB in the lowest band, ' &
                   //compact_real(minval(spread))//' dB in the highest; a steady tone does not scatter'
        lines(6) = 'window leakage: a tone at a band centre comes out within 1e-4 dB, a band above or below ' &
                   //'a tone reads at least 57 dB under it (greenconv_io_spectra, suite spectra)'
        lines(7) = 'units: '//units
        lines(8) = names
        call move_alloc(lines, comments)
    end subroutine spectra_header

    !> Segment length N [samples] of the Welch averages of a scene's spectra: the runs' and
    !> their linear reference's (greenconv_scene_run_linear_reference), `default_lines_per_band`
    !> lines in the scene's lowest band.
    integer function spectra_segment_length(scene)
        !> The scene (spectra_f_low, dt).
        type(scene_type), intent(in) :: scene

        spectra_segment_length = segment_for_band(first_band(scene%spectra_f_low), scene%dt, default_lines_per_band)
    end function spectra_segment_length

    !> The columns a scene's spectra files begin with, in its 1/3-octave bands from
    !> spectra_f_low to spectra_f_high: f_nominal, f_centre, f_lower, f_upper [Hz], the band
    !> power of `psd` [u^2] and its level [dB re 1 u] (u: N for a force, m^2 for a contact
    !> area); then `extra` columns set to zero, for the caller's. The runs' files and the
    !> linear reference's share them.
    subroutine band_table(scene, psd, df, extra, table)
        !> The scene (the bands, dt).
        type(scene_type), intent(in) :: scene
        !> Power spectral density [u^2/Hz] on lines 0, df, 2*df, ...
        real(dp), intent(in) :: psd(:)
        !> Line spacing [Hz].
        real(dp), intent(in) :: df
        !> Number of columns after the six.
        integer, intent(in) :: extra
        !> The table, one row a band.
        real(dp), allocatable, intent(out) :: table(:, :)

        real(dp), allocatable :: centre(:), lower(:), upper(:), power(:)
        integer :: c

        call third_octave_bands(scene%spectra_f_low, scene%spectra_f_high, 0.5_dp/scene%dt, centre, lower, upper)
        power = band_powers(psd, df, lower, upper)
        allocate (table(size(centre), 6 + extra))
        table(:, 1) = [(nominal_frequency(centre(c)), c=1, size(centre))]
        table(:, 2) = centre
        table(:, 3) = lower
        table(:, 4) = upper
        table(:, 5) = power
        table(:, 6) = 10.0_dp*log10(max(power, tiny(1.0_dp)))
        table(:, 7:) = 0.0_dp
    end subroutine band_table

    !> Whole segments of n samples, overlapping by half, in a record of `steps` samples.
    pure integer function segments(steps, n)
        integer(int64), intent(in) :: steps
        integer, intent(in) :: n

        segments = 0
        if (steps >= n) segments = int(1 + (steps - n)/(n/2))
    end function segments

end module greenconv_scene_run_spectra_output
