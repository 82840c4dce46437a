!> The reports of a sweep: its table `<output_dir>/<name>_sweep.dat`, one row per
!> variant in variant order (the variant, its values, per method max, mean, rms of the total
!> contact force, the fraction of steps in contact, status and fault step, then the band
!> levels), the same byte for byte whatever runs the variants; the CPU times, which vary from
!> run to run, in `<name>_sweep_cpu.dat`; and the lines the drivers print (the count of
!> variants, a failed variant, the end).
module greenconv_scene_sweep_report
    use, intrinsic :: iso_fortran_env, only: int64
    use greenconv_core_kinds, only: dp
    use greenconv_core_error, only: error_type, fatal_error, stat_accuracy
    use greenconv_core_text, only: int_text, real_text
    use greenconv_io_files, only: make_directory, write_text
    use greenconv_io_spectra, only: band_spectrum, band_levels
    use greenconv_scene_read_facade, only: scene_type
    use greenconv_scene_run_facade, only: force_summary
    use greenconv_scene_sweep_plan, only: sweep_plan, padded, column_width, lines_per_band, nominal_margin
    use greenconv_scene_sweep_record, only: variant_outcome
    implicit none
    private

    public :: summary_row, write_sweep_table, report_check, finish_report, add_method, &
              failed_outcome, band_text, worse_status, estimate_width

    !> Width of a band level's column.
    integer, parameter :: level_width = 11
    !> Width of an error estimate's column (es10.3e3).
    integer, parameter :: estimate_width = 10

contains

    !> The row of variant k in the table: its number, its values, its result.
    subroutine summary_row(plan, k, result, row)
        !> The sweep.
        type(sweep_plan), intent(in) :: plan
        !> Variant number.
        integer, intent(in) :: k
        !> Its result columns (`variant_outcome%result`).
        character(len=*), intent(in) :: result
        !> The row.
        character(len=:), allocatable, intent(out) :: row

        integer :: j

        row = padded(int_text(k), len('# variant') - 2)
        do j = 1, size(plan%variables)
            row = row//'  '//padded(plan%values(k, j)%text, column_width(plan, j))
        end do
        row = row//result
    end subroutine summary_row

    !> Write `<name>_sweep.dat` (one row per variant, in order) and `<name>_sweep_cpu.dat`
    !> (the CPU seconds of each method), each atomically.
    subroutine write_sweep_table(plan, outcomes, error)
        !> The sweep.
        type(sweep_plan), intent(in) :: plan
        !> One per variant, in variant order.
        type(variant_outcome), intent(in) :: outcomes(:)
        !> Set when a file cannot be written.
        type(error_type), allocatable, intent(out) :: error

        character(len=:), allocatable :: names, cpu_names, table, cpu, nominal, row
        integer :: j, k, b

        names = '# variant'
        do j = 1, size(plan%variables)
            names = names//'  '//padded(plan%variables(j)%text, column_width(plan, j))
        end do
        cpu_names = '# variant'
        do j = 1, size(plan%methods)
            associate (m => plan%methods(j)%text)
                names = names//' '//padded('max_'//m, 15)//' '//padded('mean_'//m, 15)//' '//padded('rms_'//m, 15) &
                        //' '//padded('contact_'//m, 9)//' '//padded('status_'//m, 2)//' '//'step_'//m
                cpu_names = cpu_names//' cpu_s_'//m
            end associate
        end do
        do j = 1, size(plan%methods)
            do b = 1, size(plan%band_centre)
                call nominal_text(plan%band_centre(b), nominal)
                names = names//' '//padded('L'//nominal//'_'//plan%methods(j)%text, level_width)
            end do
        end do
        do j = 1, size(plan%methods)
            names = names//' '//padded('estimate_'//plan%methods(j)%text, estimate_width)
        end do
        table = '# greenconv sweep '//plan%name//' of '//plan%file//': '//int_text(size(outcomes)) &
                //' variants, rows in variant order'//new_line('a') &
                //'# per method: max, mean, rms of the total contact force [N], fraction of steps in ' &
                //'contact, status (0 done, 2 bad input, 3 numerical fault, 4 ran outside the accuracy asked), step of the ' &
                //'fault (0: none)'
        if (plan%spectra) table = table//new_line('a')//'# then per method and 1/3-octave band L<f_c>_<method>: ' &
            //'level of the total contact force [dB re 1 N] (IEC 61260-1 bands '//real_text(plan%f_low)//' to ' &
            //real_text(plan%f_high)//' Hz; Welch PSD, Hann window, 50 % overlap; nan: the method failed)'
        table = table//new_line('a')//'# last, per method estimate_<method>: its own estimate of the relative ' &
                //'error of u (the model''s terms and the time step''s, doc/methods.md; nan: the method failed)'
        table = table//new_line('a')//names
        cpu = '# greenconv sweep '//plan%name//': CPU seconds of the contact loop of each method'//new_line('a') &
              //cpu_names
        do k = 1, size(outcomes)
            call summary_row(plan, k, outcomes(k)%result, row)
            table = table//new_line('a')//row
            cpu = cpu//new_line('a')//padded(int_text(k), len('# variant') - 2)//outcomes(k)%cpu
        end do
        call make_directory(plan%output_dir, error)
        if (.not. allocated(error)) call write_text(plan%output_dir//'/'//plan%name//'_sweep.dat', table, error)
        if (.not. allocated(error)) call write_text(plan%output_dir//'/'//plan%name//'_sweep_cpu.dat', cpu, error)
    end subroutine write_sweep_table

    !> The count of variants, done (skipped) and bad, once every variant was taken; with
    !> `check_only`, an error (status 2) when a variant is bad.
    subroutine report_check(plan, unit, n_done, n_bad, check_only, error)
        !> The sweep.
        type(sweep_plan), intent(in) :: plan
        !> Unit of the line.
        integer, intent(in) :: unit
        !> Variants found done (skipped).
        integer, intent(in) :: n_done
        !> Variants that failed their check.
        integer, intent(in) :: n_bad
        !> Whether this is `--check` (nothing runs).
        logical, intent(in) :: check_only
        !> Set (status 2) with `check_only` when a variant is bad.
        type(error_type), allocatable, intent(out) :: error

        character(len=:), allocatable :: line
        integer :: j

        line = 'greenconv: '//plan%file//': '//int_text(size(plan%values, 1))//' variants of'
        do j = 1, size(plan%variables)
            line = line//' '//plan%variables(j)%text
        end do
        line = line//', methods'
        do j = 1, size(plan%methods)
            line = line//' '//plan%methods(j)%text
        end do
        line = line//'; '//int_text(size(plan%values, 1) - n_bad)//' checked ok, '//int_text(n_bad)//' bad'
        if (.not. check_only) line = line//', '//int_text(n_done)//' already done (skipped)'
        write (unit, '(a)') line
        if (check_only .and. n_bad > 0) call fatal_error(error, plan%file//': '//int_text(n_bad) &
            //' variant(s) failed their check (see above); fix the values named there')
    end subroutine report_check

    !> Write the table and say where it is and how many variants failed. A sweep with failed
    !> variants is not a success even though every other variant completed and the table is
    !> whole: `error` then says how many failed, with the worst status of theirs (3 when one
    !> met a numerical fault, else 2), which the drivers return. Without a failed variant, one
    !> that ran outside the accuracy asked (status 4 in its row) sets `error` with status 4.
    subroutine finish_report(plan, outcomes, unit, error)
        !> The sweep.
        type(sweep_plan), intent(in) :: plan
        !> One per variant, in variant order.
        type(variant_outcome), intent(in) :: outcomes(:)
        !> Unit of the line.
        integer, intent(in) :: unit
        !> Set when the table cannot be written, or when a variant failed or ran outside the accuracy asked.
        type(error_type), allocatable, intent(out) :: error

        character(len=:), allocatable :: line
        integer :: n_failed, n_outside, worst, k

        call write_sweep_table(plan, outcomes, error)
        if (allocated(error)) return
        n_outside = count(outcomes%status == stat_accuracy)
        n_failed = count(outcomes%status /= 0) - n_outside
        worst = 0
        do k = 1, size(outcomes)
            worst = worse_status(worst, outcomes(k)%status)
        end do
        line = 'greenconv: sweep '//plan%name//': '//int_text(size(outcomes))//' variants, '//int_text(n_failed) &
               //' failed'
        if (n_outside > 0) line = line//', '//int_text(n_outside)//' outside the accuracy asked (status 4)'
        write (unit, '(a)') line//'; table '//plan%output_dir//'/'//plan%name//'_sweep.dat'
        if (n_failed > 0) then
            call fatal_error(error, 'sweep '//plan%name//': '//int_text(n_failed)//' of ' &
                             //int_text(size(outcomes))//' variants failed (each named above, its ' &
                             //'status and step in its row of the table); the others are done', worst)
        else if (n_outside > 0) then
            call fatal_error(error, 'sweep '//plan%name//': '//int_text(n_outside)//' of '//int_text(size(outcomes)) &
                             //' variants ran outside the accuracy asked (each named above, status 4 in its row ' &
                             //'of the table): their rows are whole; use a method inside it or ask a larger ' &
                             //'accuracy', stat_accuracy)
        end if
    end subroutine finish_report

    !> The worse of two statuses of a method or a variant: 3 (numerical fault) before 2 (bad
    !> input) before 4 (ran, but outside the accuracy asked) before 0 (done).
    pure integer function worse_status(a, b) result(worse)
        !> One status (0, 2, 3 or 4).
        integer, intent(in) :: a
        !> The other.
        integer, intent(in) :: b

        integer :: rank_a, rank_b

        ! status 4 ranks between 0 and 2
        rank_a = merge(1, a, a == stat_accuracy)
        rank_b = merge(1, b, b == stat_accuracy)
        worse = merge(a, b, rank_a >= rank_b)
    end function worse_status

    !> Append one method's columns (and CPU time) to an outcome; a failure sets the status.
    subroutine add_method(outcome, summary, seconds, error, step, prefix)
        !> The variant's outcome so far.
        type(variant_outcome), intent(inout) :: outcome
        !> The method's summary of the total contact force (greenconv_scene_run_stream).
        type(force_summary), intent(in) :: summary
        !> CPU seconds of its contact loop.
        real(dp), intent(in) :: seconds
        !> Its failure, if any (its status is the method's; `stat_accuracy`: it ran whole, outside the
        !> accuracy asked, and its step column stays 0).
        type(error_type), allocatable, intent(in) :: error
        !> Steps it did (the fault's step when it failed).
        integer(int64), intent(in) :: step
        !> Text put before the failure's message (the variant and the method).
        character(len=*), intent(in) :: prefix

        character(len=16) :: mean, rms, fraction, peak
        integer :: status

        status = 0
        if (allocated(error)) status = error%stat
        if (summary%steps > 0) then
            write (peak, '(es15.7e3)') summary%peak
            write (mean, '(es15.7e3)') summary%total/real(summary%steps, dp)
            write (rms, '(es15.7e3)') sqrt(summary%squares/real(summary%steps, dp))
            write (fraction, '(f9.6)') real(summary%in_contact, dp)/real(summary%steps, dp)
        else
            peak = padded('nan', 15)
            mean = peak
            rms = peak
            fraction = padded('nan', 9)
        end if
        outcome%result = outcome%result//' '//peak(:15)//' '//mean(:15)//' '//rms(:15)//' '//fraction(:9) &
                         //' '//int_text(status)//' '//int_text(merge(step, 0_int64, status /= 0 .and. &
                                                                    status /= stat_accuracy))
        outcome%cpu = outcome%cpu//' '//cpu_text(seconds)
        ! the first failure's message, or the first failure after methods outside the accuracy
        if (status /= 0 .and. (outcome%status == 0 .or. (outcome%status == stat_accuracy .and. &
                                                          status /= stat_accuracy))) outcome%message = prefix//error%message
        outcome%status = worse_status(outcome%status, status)
    end subroutine add_method

    !> An outcome whose every method failed before running (the variant's check).
    function failed_outcome(plan, error) result(outcome)
        !> The sweep.
        type(sweep_plan), intent(in) :: plan
        !> Why the variant failed.
        type(error_type), intent(in) :: error
        !> Every method failed with its status, the levels nan, the message the error's.
        type(variant_outcome) :: outcome

        type(error_type), allocatable :: failure
        integer :: j

        outcome%result = ''
        outcome%cpu = ''
        outcome%message = ''
        failure = error
        do j = 1, size(plan%methods)
            call add_method(outcome, force_summary(), 0.0_dp, failure, 0_int64, '')
        end do
        do j = 1, size(plan%methods)*size(plan%band_centre)
            outcome%result = outcome%result//' '//padded('nan', level_width)
        end do
        do j = 1, size(plan%methods)
            outcome%result = outcome%result//' '//padded('nan', estimate_width)
        end do
    end function failed_outcome

    !> One method's band levels as table columns: ' ' and the level [dB re 1 N] per band of
    !> the sweep; 'nan' for a method that failed (its history is not whole). Empty without spectra.
    subroutine band_text(plan, history, scene, ok, text)
        !> The sweep (its bands).
        type(sweep_plan), intent(in) :: plan
        !> The method's total contact force [N] at every step (allocated with `spectra`).
        real(dp), allocatable, intent(in) :: history(:)
        !> The variant's scene (dt).
        type(scene_type), intent(in) :: scene
        !> Whether the method completed (else every level is nan).
        logical, intent(in) :: ok
        !> The columns, each after a blank.
        character(len=:), allocatable, intent(out) :: text

        type(band_spectrum) :: spectrum
        type(error_type), allocatable :: error
        character(len=level_width) :: level
        integer :: b

        text = ''
        if (size(plan%band_centre) == 0) return
        if (ok) call band_levels(history, scene%dt, plan%f_low*nominal_margin, plan%f_high/nominal_margin, spectrum, &
                                 error, lines_per_band)
        if (ok .and. .not. allocated(error)) then
            if (size(spectrum%level) /= size(plan%band_centre)) allocate (error)
        end if
        do b = 1, size(plan%band_centre)
            level = padded('nan', level_width)
            if (ok .and. .not. allocated(error)) write (level, '(f11.4)') spectrum%level(b)
            text = text//' '//level
        end do
    end subroutine band_text

    !> The nominal name of a 1/3-octave band (100, 125, 160, ..., 1000, 1250, ...) from its
    !> exact centre 1000*10^(x/10) Hz: the preferred numbers of IEC 61260-1, three digits.
    subroutine nominal_text(centre, text)
        real(dp), intent(in) :: centre
        character(len=:), allocatable, intent(out) :: text

        real(dp), parameter :: preferred(0:9) = [1.0_dp, 1.25_dp, 1.6_dp, 2.0_dp, 2.5_dp, 3.15_dp, 4.0_dp, 5.0_dp, &
                                                 6.3_dp, 8.0_dp]
        character(len=32) :: buffer
        real(dp) :: nominal
        integer :: x

        x = nint(10.0_dp*log10(centre/1000.0_dp))
        nominal = preferred(modulo(x, 10))*10.0_dp**(3 + floor(x/10.0_dp))
        if (nominal >= 100.0_dp) then
            write (buffer, '(i0)') nint(nominal)
        else
            write (buffer, '(f0.3)') nominal
        end if
        text = trim(buffer)
        if (index(text, '.') > 0) then
            do while (text(len(text):len(text)) == '0')
                text = text(:len(text) - 1)
            end do
            if (text(len(text):len(text)) == '.') text = text(:len(text) - 1)
        end if
        if (text(1:1) == '.') text = '0'//text
    end subroutine nominal_text

    !> CPU seconds in a fixed buffer.
    pure function cpu_buffer(seconds) result(buffer)
        real(dp), intent(in) :: seconds
        character(len=12) :: buffer

        write (buffer, '(f12.4)') seconds
    end function cpu_buffer

    !> CPU seconds as the CPU file shows them.
    pure function cpu_text(seconds) result(text)
        real(dp), intent(in) :: seconds
        character(len=len_trim(adjustl(cpu_buffer(seconds)))) :: text

        text = adjustl(cpu_buffer(seconds))
    end function cpu_text

end module greenconv_scene_sweep_report
