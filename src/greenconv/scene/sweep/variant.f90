!> One variant of a sweep, taken as a whole by whichever process runs it: its scene
!> read from memory and checked, its content key, its record when a previous run finished it
!> (then nothing runs), else each method of its scene run through the one streaming loop
!> (greenconv_scene_run_stream's `stream_run`) into the sinks a sweep asks for: the force summary
!> of the table's row, the total-force history of the band levels (`spectra`) and the column
!> file of each method (`histories`: `<name>_v<k>_<method>.dat`, or `.bin` with its header
!> `.bin.txt` for `output_format = 'binary'`; a numerical fault keeps the rows before it).
!> Every model of a contact scene can be swept: one point (sdof, random_modes, frf_file), the
!> tyre's line of points, and the nodes of a Green's matrix file (identified once per variant).
module greenconv_scene_sweep_variant
    use, intrinsic :: iso_fortran_env, only: int64
    use greenconv_core_kinds, only: dp
    use greenconv_core_error, only: error_type, fatal_error, stat_accuracy
    use greenconv_core_text, only: int_text, real_text, sci_text
    use greenconv_io_files, only: make_directory, block_rows
    use greenconv_ident_structure, only: structure_model
    use greenconv_scene_read_facade, only: scene_type
    use greenconv_scene_models_facade, only: structure_kind, find_model, build_structure
    use greenconv_scene_run_facade, only: multi_contact_header, contact_run, stream_sinks, stream_run, &
                                          make_run_convolver, start_run, step_doubling, start_step_doubling, &
                                          time_step_estimate, band_estimate
    use greenconv_scene_sweep_plan, only: sweep_plan, scene_files, read_variant
    use greenconv_scene_sweep_record, only: variant_outcome, content_key, load_record, record_path
    use greenconv_scene_sweep_report, only: add_method, failed_outcome, band_text, estimate_width
    implicit none
    private

    public :: take_variant, variant_ran, variant_done, variant_bad

    !> What `take_variant` did with a variant: ran it, found it done (its record), found it bad.
    integer, parameter :: variant_ran = 0, variant_done = 1, variant_bad = 2

contains

    !> Take variant k: read and check it; a bad one (status 2, message in the outcome) is not
    !> run; one a previous run recorded under its content key is not run either (its record is
    !> the outcome); else each method runs. With `check_only`, only the check. The outcome of a
    !> variant that ran carries its key (`save_record` then records it).
    subroutine take_variant(plan, k, check_only, outcome, what, files)
        !> The sweep.
        type(sweep_plan), intent(in) :: plan
        !> Variant number.
        integer, intent(in) :: k
        !> Only check it.
        logical, intent(in) :: check_only
        !> Its outcome (unset with `check_only` when it is good).
        type(variant_outcome), intent(out) :: outcome
        !> `variant_ran`, `variant_done` or `variant_bad`.
        integer, intent(out) :: what
        !> Road files and textures read by earlier variants (each file is read once).
        type(scene_files), intent(inout) :: files

        type(scene_type) :: scene
        type(error_type), allocatable :: error
        character(len=16) :: key
        logical :: found

        what = variant_bad
        call read_variant(plan, k, scene, error, files)
        if (allocated(error)) then
            outcome = failed_outcome(plan, error)
            return
        end if
        what = variant_ran
        if (check_only) return
        call content_key(plan, k, scene, files, key, error)
        if (allocated(error)) then
            what = variant_bad
            outcome = failed_outcome(plan, error)
            return
        end if
        call load_record(record_path(plan, key), outcome, found)
        if (found) then
            what = variant_done
            return
        end if
        if (plan%histories) call make_directory(plan%output_dir, error)
        if (allocated(error)) then
            outcome = failed_outcome(plan, error)
            return
        end if
        call run_variant(plan, k, scene, outcome)
        outcome%key = key
    end subroutine take_variant

    !> Run variant k's scene: every method, summarised. A fault (bad input, divergence) is
    !> kept in the outcome; so is a method that ran whole but whose own error estimate
    !> (greenconv_scene_run_stream's `make_run_convolver`) exceeds the scene's `accuracy`, with
    !> status 4 (`stat_accuracy`), as the driver's runner says it.
    subroutine run_variant(plan, k, scene, outcome)
        type(sweep_plan), intent(in) :: plan
        integer, intent(in) :: k
        type(scene_type), intent(inout) :: scene
        type(variant_outcome), intent(out) :: outcome

        type(structure_model) :: structure
        type(contact_run) :: run
        type(stream_sinks) :: sinks
        type(error_type), allocatable :: failure, error
        character(len=:), allocatable :: accuracy, levels, method, summary, bands, estimates, text
        type(step_doubling) :: doubling
        real(dp) :: seconds, estimate, step_part, band_part
        integer(int64) :: step
        integer :: i, n_c, block
        logical :: several, whole
        type(structure_kind) :: model

        outcome%result = ''
        outcome%cpu = ''
        outcome%message = ''
        scene%progress = .false.
        model = find_model(scene%model)
        several = model%multi_point()
        if (several) then
            call model%find_points(scene, run%points, summary, failure)
            n_c = max(run%points%n_points(), 1)
            block = max(block_rows/n_c, 1)
        else
            call build_structure(scene, structure, failure)
            block = block_rows
        end if
        levels = ''
        estimates = ''
        do i = 1, size(scene%methods)
            method = trim(scene%methods(i))
            sinks = variant_sinks(plan, scene, k, method, several, run%points%across)
            seconds = 0.0_dp
            step = 0
            estimate = 0.0_dp
            if (allocated(failure)) then
                error = failure
            else
                call make_run_convolver(run, scene, structure, method, accuracy, error, estimate)
                if (.not. allocated(error)) call start_run(run, scene, error)
                if (.not. allocated(error)) then
                    call start_step_doubling(doubling, run, scene, structure, method)
                    call stream_run(run, scene, method, block, sinks, '', seconds, error, doubling)
                    step = run%step()
                    call time_step_estimate(doubling, step_part, text)
                    call band_estimate(doubling, band_part, text)
                    estimate = estimate + step_part + band_part
                end if
                if (allocated(run%conv)) then
                    call run%conv%release()
                    deallocate (run%conv)
                end if
            end if
            whole = .not. allocated(error)
            estimates = estimates//' '//estimate_column(estimate, whole)
            if (whole .and. estimate > scene%accuracy) call fatal_error(error, 'ran outside the accuracy asked: its ' &
                //'own error estimate '//sci_text(estimate)//' > accuracy '//sci_text(scene%accuracy) &
                //' (&convolution accuracy); its row is whole', stat_accuracy)
            call add_method(outcome, sinks%summary, seconds, error, step, 'variant '//int_text(k)//': '//method//': ')
            call band_text(plan, sinks%history, scene, whole, bands)
            levels = levels//bands
            if (allocated(error)) deallocate (error)
        end do
        outcome%result = outcome%result//levels//estimates
    end subroutine run_variant

    !> A method's error estimate as a sweep table column (greenconv_scene_sweep_report's
    !> `estimate_width` characters): 'nan' when it did not run whole.
    function estimate_column(estimate, whole) result(text)
        real(dp), intent(in) :: estimate
        logical, intent(in) :: whole
        character(len=estimate_width) :: text

        text = 'nan'
        if (whole) write (text, '(es10.3e3)') estimate
    end function estimate_column

    !> The sinks of a variant's method: its force summary, its total-force history with
    !> `spectra`, its column file with `histories` (the header of a contact scene's file, the
    !> first line naming the sweep, the variant and its values).
    function variant_sinks(plan, scene, k, method, several, across) result(sinks)
        type(sweep_plan), intent(in) :: plan
        type(scene_type), intent(in) :: scene
        integer, intent(in) :: k
        character(len=*), intent(in) :: method
        logical, intent(in) :: several, across
        type(stream_sinks) :: sinks

        character(len=:), allocatable :: title

        sinks%summarise = .true.
        if (plan%spectra) allocate (sinks%history(scene%n_steps))
        if (.not. plan%histories) return
        sinks%binary = scene%output_format == 'binary'
        sinks%path = plan%output_dir//'/'//plan%name//'_v'//int_text(k)//'_'//method &
                     //merge('.bin', '.dat', sinks%binary)
        call history_title(plan, scene, k, method, title)
        if (several) then
            sinks%header = multi_contact_header(title, across)
            sinks%n_columns = merge(8, 7, across)
        else
            allocate (character(len=max(len(title), 40)) :: sinks%header(3))
            sinks%header(1) = title
            sinks%header(2) = 'units: s m m N m'
            sinks%header(3) = 't u_road u f_contact delta'
            sinks%n_columns = 5
        end if
    end function variant_sinks

    !> First header line of a variant's history file: the sweep, the variant and its values,
    !> the method, the steps; with `output_every` > 1, which steps the rows are.
    subroutine history_title(plan, scene, k, method, line)
        type(sweep_plan), intent(in) :: plan
        type(scene_type), intent(in) :: scene
        integer, intent(in) :: k
        character(len=*), intent(in) :: method
        character(len=:), allocatable, intent(out) :: line

        integer :: j

        line = 'greenconv sweep '//plan%name//', variant '//int_text(k)//' ('
        do j = 1, size(plan%variables)
            if (j > 1) line = line//', '
            line = line//plan%variables(j)%text//' = '//plan%values(k, j)%text
        end do
        line = line//'), method '//method//', '//int_text(scene%n_steps)//' steps of '//real_text(scene%dt)//' s'
        if (scene%output_every > 1) line = line//', a row every '//int_text(scene%output_every)//' steps (steps 0, ' &
                                           //int_text(scene%output_every)//', '//int_text(2*scene%output_every) &
                                           //', ...)'
    end subroutine history_title

end module greenconv_scene_sweep_variant
