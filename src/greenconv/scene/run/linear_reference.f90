!> The linear frequency-domain reference of a single-point contact run whose structure has a
!> known receptance (a model whose registry row names `receptance`, as `wheel_rail`): the
!> contact linearised at the preload, the force spectrum
!>
!>     F(omega) = -r(omega)/(alpha(omega) + 1/k_H),   k_H = p*k_c*delta0^(p-1),
!>
!> r the roughness under the contact, alpha the receptance the contact sees (wheel and rail in
!> series), k_H the law's tangent stiffness at the static compression delta0 (Hertz:
!> (3/2)*C_H^(2/3)*F0^(1/3)). Its power spectral density is |H|^2 times the roughness's,
!> H = 1/(alpha + 1/k_H), the roughness's PSD estimated as the time-domain runs' force spectra
!> are (greenconv_io_spectra: Welch, the same segments, the same Hann window), so that the two
!> band spectra compare band for band:
!>
!> - `<name>_linear_spectra.dat`: 1/3-octave band levels of the linear force, the columns of a
!>   method's `<name>_<method>_spectra.dat` (f_nominal, f_centre, f_lower, f_upper, power,
!>   level);
!> - `<name>_linear_narrowband.dat`: f, the roughness PSD, |alpha|, |H| and the linear force PSD
!>   on the Welch lines.
!>
!> A multi-point scene of a modal structure (its points' `modes`: models 'tyre', 'tyre_plate',
!> 'modes_file') gets the matrix form (greenconv_model_linear_patch): each point's law
!> linearised at its share F0/N_c of the preload (greenconv_scene_models_patch), the force's change
!> dF = (A + K^-1)^-1 u_r under the road heights u_r,i at the points, and the total force's
!> PSD that of sum_j c_j(f)*u_r,j(f), c = (A + K^-1)^-1 1 (A and K symmetric), averaged by
!> Welch as the runs' spectra are, each segment's lines of the points' heights filtered and
!> added (greenconv_io_spectra's `set_welch_gains`): `<name>_linear_spectra.dat` (the same
!> bands) and `<name>_linear_narrowband.dat` (f and the total force's PSD), for up to
!> `patch_reference_points` points (one complex solve of N_c unknowns per Welch line).
!>
!> Where the time-domain run departs from this, the contact is nonlinear (the Hertz law over a
!> large roughness, or contact lost): each method's summary line says for how many steps and
!> how long the contact was lost (`contact_loss_text`).
module greenconv_scene_run_linear_reference
    use, intrinsic :: iso_fortran_env, only: int64
    use greenconv_core_kinds, only: dp
    use greenconv_core_constants, only: two_pi
    use greenconv_core_error, only: error_type, stat_accuracy
    use greenconv_core_text, only: int_text, sci_text
    use greenconv_io_files, only: write_columns, block_rows
    use greenconv_io_spectra, only: welch_accumulator, start_welch, add_welch_samples, welch_average, set_welch_gains
    use greenconv_scene_settings, only: scene_type
    use greenconv_scene_models_facade, only: contact_receptance, scene_points, sample_patch_road
    use greenconv_scene_run_stream, only: force_summary
    use greenconv_scene_run_spectra_output, only: spectra_segment_length, band_table
    use greenconv_model_linear_patch, only: modal_receptance_matrix, linear_patch_force
    implicit none
    private

    public :: write_linear_reference, write_patch_reference, contact_loss_text, patch_reference_points

    !> Most points of a patch whose linear reference is written.
    integer, parameter :: patch_reference_points = 64

contains

    !> Write the linear reference of a scene beside its runs (module description), when the
    !> scene asks for force spectra; nothing after an error other than status 4 (every file
    !> written, an estimate above the accuracy asked), which is kept.
    subroutine write_linear_reference(scene, receptance, unit, error)
        !> The scene (task 'contact', a single point).
        type(scene_type), intent(in) :: scene
        !> The receptance the contact sees, from the scene's values.
        procedure(contact_receptance) :: receptance
        !> Unit of the summary, where one line names the files.
        integer, intent(in) :: unit
        !> The run's error on entry; a failed write on return.
        type(error_type), allocatable, intent(inout) :: error

        type(welch_accumulator) :: welch
        type(error_type), allocatable :: fault
        real(dp), allocatable :: psd(:, :), f(:), force(:)
        complex(dp), allocatable :: alpha(:), h(:)
        character(len=:), allocatable :: base, comments(:)
        real(dp) :: df, k_h
        integer(int64) :: first
        integer :: n, m, k

        if (allocated(error)) then
            if (error%stat /= stat_accuracy) return
        end if
        if (.not. scene%spectra .or. scene%task /= 'contact') return
        n = spectra_segment_length(scene)
        call start_welch(welch, n, 1)
        first = 0
        do while (first < scene%n_steps)
            m = int(min(int(block_rows, int64), scene%n_steps - first))
            call add_welch_samples(welch, reshape(scene%road%sample_steps(scene%dt, first, m), [m, 1]))
            first = first + m
        end do
        call welch_average(welch, scene%dt, psd, df, fault)
        call welch%plans%release()
        if (.not. allocated(fault)) then
            f = [(k*df, k=0, size(psd, 1) - 1)]
            allocate (alpha(size(f)))
            call receptance(scene, two_pi*f, alpha)
            k_h = scene%law%tangent(scene%law%compression(scene%preload))
            h = 1.0_dp/(alpha + 1.0_dp/k_h)
            force = abs(h)**2*psd(:, 1)
            base = scene%output_dir//'/'//scene%name//'_linear'
            call reference_comments(scene, k_h, n, df, welch%n_segments, comments)
            comments(size(comments) - 1) = 'units: Hz m^2/Hz m/N N/m N^2/Hz'
            comments(size(comments)) = 'f psd_roughness alpha_abs h_abs psd_force'
            call write_columns(base//'_narrowband.dat', comments, reshape([f, psd(:, 1), abs(alpha), abs(h), force], &
                                                                          [size(f), 5]), fault)
        end if
        if (.not. allocated(fault)) call write_band_file(scene, base, force, df, comments, fault)
        if (allocated(fault)) then
            fault%message = scene%file//': linear reference: '//fault%message
            call move_alloc(fault, error)
            return
        end if
        write (unit, '(a)') '# linear reference (k_H = '//sci_text(k_h)//' N/m at F0 = '//sci_text(scene%preload) &
            //' N): '//base//'_spectra.dat, '//base//'_narrowband.dat'
    end subroutine write_linear_reference

    !> `<base>_spectra.dat`: the 1/3-octave band levels of the force PSD `force` [N^2/Hz] on
    !> lines df apart, in the scene's bands, the columns of a run's spectra file.
    subroutine write_band_file(scene, base, force, df, comments, error)
        type(scene_type), intent(in) :: scene
        character(len=*), intent(in) :: base
        real(dp), intent(in) :: force(:), df
        character(len=*), intent(inout) :: comments(:)
        type(error_type), allocatable, intent(out) :: error

        real(dp), allocatable :: table(:, :)

        call band_table(scene, force, df, 0, table)
        comments(size(comments) - 1) = 'units: Hz Hz Hz Hz N^2 dB_re_1N'
        comments(size(comments)) = 'f_nominal f_centre f_lower f_upper power level'
        call write_columns(base//'_spectra.dat', comments, table, error)
    end subroutine write_band_file

    !> Write the matrix form of the linear reference of a multi-point scene of a modal
    !> structure beside its runs (module description), when the scene asks for force spectra;
    !> a line says why not for more than `patch_reference_points` points; nothing for a
    !> structure without modes at its points (a Green's matrix file) or after an error other
    !> than status 4.
    subroutine write_patch_reference(scene, points, unit, error)
        !> The scene (task 'contact', several points).
        type(scene_type), intent(in) :: scene
        !> Its points: their modes, static compliance and places on the road.
        type(scene_points), intent(in) :: points
        !> Unit of the summary.
        integer, intent(in) :: unit
        !> The run's error on entry; a failed write or solve on return.
        type(error_type), allocatable, intent(inout) :: error

        type(welch_accumulator) :: welch
        type(error_type), allocatable :: fault
        real(dp), allocatable :: psd(:, :), f(:), heights(:, :), k_h(:)
        complex(dp), allocatable :: gains(:, :), a(:, :), ones(:)
        character(len=:), allocatable :: base, comments(:)
        real(dp) :: df
        integer(int64) :: first
        integer :: n, m, k, n_c

        if (allocated(error)) then
            if (error%stat /= stat_accuracy) return
        end if
        n_c = points%n_points()
        if (.not. scene%spectra .or. scene%task /= 'contact' .or. n_c < 1) return
        if (.not. allocated(points%modes%shape) .or. points%modes%modes%n_modes() == 0) return
        if (n_c > patch_reference_points) then
            write (unit, '(a)') '# linear reference: not written for '//int_text(n_c)//' points (at most ' &
                //int_text(patch_reference_points)//')'
            return
        end if
        k_h = [(scene%law%tangent(scene%law%compression(scene%preload/n_c)), k=1, n_c)]
        n = spectra_segment_length(scene)
        df = 1.0_dp/(n*scene%dt)
        allocate (gains(0:n/2, n_c), ones(n_c))
        ones(:) = (1.0_dp, 0.0_dp)
        do k = 0, n/2
            if (allocated(points%static)) then
                a = modal_receptance_matrix(points%modes, two_pi*k*df, points%static)
            else
                a = modal_receptance_matrix(points%modes, two_pi*k*df)
            end if
            call linear_patch_force(a, k_h, ones, gains(k, :), fault)
            if (allocated(fault)) exit
        end do
        if (.not. allocated(fault)) then
            call start_welch(welch, n, n_c)
            call set_welch_gains(welch, gains)
            first = 0
            do while (first < scene%n_steps)
                m = int(min(int(max(block_rows/n_c, 1), int64), scene%n_steps - first))
                call sample_patch_road(scene, points%road_x, points%road_y, first, m, heights)
                call add_welch_samples(welch, heights)
                first = first + m
            end do
            call welch_average(welch, scene%dt, psd, df, fault)
            call welch%plans%release()
        end if
        if (.not. allocated(fault)) then
            f = [(k*df, k=0, size(psd, 1) - 1)]
            base = scene%output_dir//'/'//scene%name//'_linear'
            call reference_comments(scene, k_h(1), n, df, welch%n_segments, comments)
            comments(1) = 'greenconv scene '//scene%name//': linear frequency-domain reference of the total contact ' &
                          //'force of '//int_text(n_c)//' points, dF = (A + K^-1)^-1 u_r, its PSD that of ' &
                          //'sum_j c_j*u_r,j, c = (A + K^-1)^-1 1'
            comments(2) = 'K = k_H*I, k_H = '//sci_text(k_h(1))//' N/m, the tangent of the contact law at each ' &
                          //'point''s share F0/N_c = '//sci_text(scene%preload/n_c)//' N; A the modal point ' &
                          //'receptance matrix'
            comments(3) = comments(3)(:index(comments(3), 'segments of the') - 1)//'segments of the road ' &
                          //'heights under the points over the run, filtered and added line by line'
            comments(size(comments) - 1) = 'units: Hz N^2/Hz'
            comments(size(comments)) = 'f psd_force'
            call write_columns(base//'_narrowband.dat', comments, reshape([f, psd(:, n_c + 1)], [size(f), 2]), fault)
        end if
        if (.not. allocated(fault)) call write_band_file(scene, base, psd(:, n_c + 1), df, comments, fault)
        if (allocated(fault)) then
            fault%message = scene%file//': linear reference: '//fault%message
            call move_alloc(fault, error)
            return
        end if
        write (unit, '(a)') '# linear reference (k_H = '//sci_text(k_h(1))//' N/m per point at F0/N_c = ' &
            //sci_text(scene%preload/n_c)//' N): '//base//'_spectra.dat, '//base//'_narrowband.dat'
    end subroutine write_patch_reference

    !> The header lines of the reference's files, the last two left for the units and names.
    subroutine reference_comments(scene, k_h, n, df, n_segments, comments)
        type(scene_type), intent(in) :: scene
        real(dp), intent(in) :: k_h, df
        integer, intent(in) :: n, n_segments
        character(len=:), allocatable, intent(out) :: comments(:)

        allocate (character(len=320) :: comments(5))
        comments(:) = ''
        comments(1) = 'greenconv scene '//scene%name//': linear frequency-domain reference of the contact force, ' &
                      //'F = -r/(alpha + 1/k_H), its PSD |H|^2 times the roughness PSD, H = 1/(alpha + 1/k_H)'
        comments(2) = 'k_H = '//sci_text(k_h)//' N/m, the tangent of the contact law at the preload F0 = ' &
                      //sci_text(scene%preload)//' N; alpha the receptance the contact sees (wheel and rail in series)'
        comments(3) = 'roughness PSD: Welch as the force spectra of the runs, Hann window, segments of ' &
                      //int_text(n)//' samples (df = '//sci_text(df)//' Hz), 50 % overlap, '//int_text(n_segments) &
                      //' segments of the roughness under the contact over the run'
    end subroutine reference_comments

    !> "; contact lost in N of M steps (T s)" for a run's force summary, or "; contact never
    !> lost".
    subroutine contact_loss_text(summary, dt, text)
        !> The run's force summary (steps and steps in contact).
        type(force_summary), intent(in) :: summary
        !> Time step [s].
        real(dp), intent(in) :: dt
        !> '; contact never lost' or '; contact lost in N of M steps (T s)'. A subroutine, not a
        !> deferred-length function: gfortran keeps such a result's length static (threads).
        character(len=:), allocatable, intent(out) :: text

        integer(int64) :: lost

        lost = summary%steps - summary%in_contact
        if (lost == 0) then
            text = '; contact never lost'
        else
            text = '; contact lost in '//int_text(int(lost))//' of '//int_text(int(summary%steps))//' steps (' &
                   //sci_text(lost*dt)//' s)'
        end if
    end subroutine contact_loss_text

end module greenconv_scene_run_linear_reference
