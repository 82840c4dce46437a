!> Parameter sweeps: a contact scene with `task = 'sweep'` and a `&sweep` group
!> that varies any of its variables, named `group.variable`:
!>
!>     &sweep
!>         road.speed = 10.0, 20.0, 30.0        ! a list: the variants are the cartesian product
!>         contact.stiffness = 1.0e5, 2.0e5     ! (the last variable named varies fastest)
!>         table_file = 'data/design.txt'       ! or a table: a header naming the variables,
!>     /                                        ! one row of values per variant
!>
!> A variant is the base scene's text with each varied value written in (replacing the
!> assignment, or added to its group), read from memory like any scene; the `&sweep`
!> group is blanked and the task set to 'contact', so lines keep their numbers in messages.
!> Each variant is checked when it is taken (by the process that runs it), so no serial
!> phase grows with the number of variants. A variant runs each method of the scene through
!> the driver's streaming loop (greenconv_scene_run_stream), keeping only a summary of the total
!> contact force: max,
!> mean, rms, the fraction of steps in contact, the status (0, 2 bad input, 3 numerical
!> fault, 4 ran whole but outside the scene's `accuracy` by the method's own estimate, as
!> the driver's status 4) and the step of a fault, with its CPU time. The sweep ends with the
!> worst status of its variants, 3 before 2 before 4. Every model of a contact scene can be
!> swept: one point (sdof, random_modes, frf_file), the tyre's line of points, and the nodes
!> of a Green's matrix file (`green_file`, identified once per variant) on a road file or a
!> 2D texture.
!>
!> Options of the `&sweep` group besides the varied variables:
!>
!>     spectra = .true.     ! 1/3-octave band levels of each method's total contact force
!>     f_low = 100.0        ! [Hz] lowest nominal band centre (default 100 Hz)
!>     f_high = 5000.0      ! [Hz] highest nominal band centre (default 5000 Hz)
!>     histories = .true.   ! each variant's column files <name>_v<k>_<method>.dat (default off)
!>
!> With `spectra`, the table gets, after the methods' summaries, one column `L<fc>_<method>`
!> per band and method: the band level in dB re 1 N of the variant's total-force history
!> (greenconv_io_spectra's `band_levels`: IEC 61260-1 bands, Welch PSD with a Hann window),
!> printed to 1e-4 dB, `fc` the band's nominal centre (800 for the band at 794.3 Hz); `nan`
!> for a method that failed. Every band must lie below each variant's Nyquist frequency and
!> its record be long enough for the lowest band (checked with the variants, so a variant
!> that cannot give every column fails its check). With `histories`, each method of each
!> variant streams its rows (every `output_every`-th step) to its own column file, as a
!> contact scene writes `<name>_<method>.dat` (text or, with `output_format = 'binary'`,
!> `.bin` and its header `.bin.txt`); a numerical fault keeps the rows before it.
!>
!> Results: `<output_dir>/<name>_sweep.dat`, one row per variant in variant order, the
!> same byte for byte whatever runs the variants; CPU times, which vary from run to run,
!> go to `<name>_sweep_cpu.dat`. Each finished variant is recorded at once (atomically) in
!> `<output_dir>/<name>_sweep.d/<key>.rec`, keyed by a hash of the variant's text, of the
!> contents of the files it names (road file or texture, receptance or Green's matrix file)
!> and of the options that change
!> what a variant gives (spectra and their band range, histories with the variant's number,
!> which names its files), so a rerun skips what is done and reruns what was edited, also
!> through the files.
!>
!> The pieces are in scene/sweep/: `plan` (the &sweep group, the variants, a variant's scene
!> read from memory), `record` (content keys, records), `report` (the table, the drivers'
!> lines), `variant` (take one variant: check, skip or run). This module holds the serial run
!> `run_sweep` and gives the pieces the drivers use; the MPI driver (mpi/) hands the variants
!> out to the ranks one at a time.
module greenconv_scene_sweep
    use greenconv_core_error, only: error_type, stat_accuracy
    use greenconv_core_text, only: int_text
    use greenconv_scene_sweep_plan, only: sweep_text, sweep_plan, scene_files, is_sweep_file, read_sweep, &
                                          variant_lines, replaced_all
    use greenconv_scene_sweep_record, only: variant_outcome, variant_key, content_key, outcome_text, &
                                            outcome_from_text, save_record
    use greenconv_scene_sweep_report, only: summary_row, write_sweep_table, report_check, finish_report
    use greenconv_scene_sweep_variant, only: take_variant, variant_ran, variant_done, variant_bad
    implicit none
    private

    public :: sweep_text, sweep_plan, scene_files, variant_outcome
    public :: is_sweep_file, read_sweep, variant_lines, variant_key, content_key, take_variant, variant_ran, &
              variant_done, variant_bad
    public :: save_record, summary_row, write_sweep_table, outcome_text, outcome_from_text, run_sweep
    public :: report_check, report_taken, finish_report, replaced_all

contains

    !> Run a sweep on this process alone: read it, take each variant in turn (check it, skip
    !> it when recorded, else run it and record it at once), then print the count and write
    !> the table. `check_only`: check every variant and print the count, run nothing. Reports
    !> go to `unit`; failed variants are in the table, not errors.
    subroutine run_sweep(path, unit, check_only, error)
        !> The sweep scene file.
        character(len=*), intent(in) :: path
        !> Unit of the report.
        integer, intent(in) :: unit
        !> Only check.
        logical, intent(in) :: check_only
        !> Set for bad input in the sweep or its base (nothing runs), a variant failing
        !> `--check`, a variant that failed, or a file that cannot be written.
        type(error_type), allocatable, intent(out) :: error

        type(sweep_plan) :: plan
        type(variant_outcome), allocatable :: outcomes(:)
        type(scene_files) :: files
        integer :: k, what, n_done, n_bad

        call read_sweep(path, plan, error)
        if (allocated(error)) return
        allocate (outcomes(size(plan%values, 1)))
        n_done = 0
        n_bad = 0
        do k = 1, size(outcomes)
            call take_variant(plan, k, check_only, outcomes(k), what, files)
            call report_taken(plan, k, outcomes(k), what, unit, n_done, n_bad, error)
            if (allocated(error)) return
        end do
        call report_check(plan, unit, n_done, n_bad, check_only, error)
        if (check_only .or. allocated(error)) return
        call finish_report(plan, outcomes, unit, error)
    end subroutine run_sweep

    !> After a variant was taken (`take_variant`): count it, say why a bad or failed one
    !> failed (one line on `unit`), and record one that ran.
    subroutine report_taken(plan, k, outcome, what, unit, n_done, n_bad, error)
        !> The sweep.
        type(sweep_plan), intent(in) :: plan
        !> Variant number.
        integer, intent(in) :: k
        !> Its outcome.
        type(variant_outcome), intent(in) :: outcome
        !> What `take_variant` did.
        integer, intent(in) :: what
        !> Unit of the lines.
        integer, intent(in) :: unit
        !> Counts of the variants found done and found bad.
        integer, intent(inout) :: n_done, n_bad
        !> Set when the record cannot be written.
        type(error_type), allocatable, intent(out) :: error

        select case (what)
        case (variant_bad)
            n_bad = n_bad + 1
            write (unit, '(a)') 'greenconv: '//outcome%message
        case (variant_done)
            n_done = n_done + 1
        case default
            if (.not. allocated(outcome%key)) return
            if (outcome%status == stat_accuracy) then
                write (unit, '(a)') 'greenconv: '//plan%file//' variant '//int_text(k)//' ran outside the accuracy ' &
                    //'asked (status 4, recorded in its row): '//outcome%message
            else if (outcome%status /= 0) then
                write (unit, '(a)') 'greenconv: '//plan%file//' variant '//int_text(k)//' failed (status ' &
                    //int_text(outcome%status)//', recorded in its row): '//outcome%message
            end if
            call save_record(plan, outcome, error)
            if (allocated(error)) error%message = 'variant '//int_text(k)//': '//error%message
        end select
    end subroutine report_taken

end module greenconv_scene_sweep
