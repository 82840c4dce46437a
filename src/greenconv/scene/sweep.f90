!> Parameter sweeps (issue 17): a contact scene with `task = 'sweep'` and a `&sweep` group
!> that varies any of its variables, named `group.variable`:
!>
!>     &sweep
!>         road.speed = 10.0, 20.0, 30.0        ! a list: the variants are the cartesian product
!>         contact.stiffness = 1.0e5, 2.0e5     ! (the last variable named varies fastest)
!>         table_file = 'data/design.txt'       ! or a table: a header naming the variables,
!>     /                                        ! one row of values per variant
!>
!> A variant is the base scene's text with each varied value written in (replacing the
!> assignment, or added to its group), read by `read_scene` like any scene; the `&sweep`
!> group is blanked and the task set to 'contact', so lines keep their numbers in messages.
!> Every variant is read and checked before anything runs. A variant runs each method of
!> the scene through the library's contact loop (greenconv_contact_single or _multi, in
!> blocks as the runner does), keeping only a summary of the total contact force: max,
!> mean, rms, the fraction of steps in contact, the status (0, 2 bad input, 3 numerical
!> fault) and the step of a fault, with its CPU time. Every model of a contact scene can be
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
!> This module holds the pieces (read, check, run one variant, record, write the table)
!> and the serial run `run_sweep`; the MPI driver (mpi/) shares them among ranks.
module greenconv_scene_sweep
    use, intrinsic :: iso_fortran_env, only: int64
    use, intrinsic :: iso_c_binding, only: c_char, c_int, c_null_char
    use greenconv_core_kinds, only: dp
    use greenconv_core_error, only: error_type, fatal_error, stat_input
    use greenconv_core_text, only: int_text, lower_text, real_text
    use greenconv_io_columns, only: read_line
    use greenconv_io_files, only: make_directory, block_rows, column_writer, open_columns, append_rows, &
                                  close_run_file, first_kept
    use greenconv_io_spectra, only: segment_for_band, first_band, default_lines_per_band, band_spectrum, &
                                    band_levels, third_octave_bands
    use greenconv_conv_convolver, only: convolver, free_convolver
    use greenconv_conv_multipoint, only: multipoint_convolver
    use greenconv_conv_builder, only: make_convolver
    use greenconv_contact_single, only: contact_response, contact_state, start_contact, contact_block
    use greenconv_contact_multi, only: multi_contact_response, multi_contact_state, start_multi_contact, &
                                       multi_contact_block, newton_options
    use greenconv_ident_structure, only: structure_model
    use greenconv_scene_schema, only: scene_table, scene_variable
    use greenconv_scene_input, only: scene_type, read_scene
    use greenconv_scene_models, only: multi_point_model
    use greenconv_scene_structure, only: build_structure
    use greenconv_scene_points, only: scene_points, find_scene_points, points_convolver, point_rows
    use greenconv_scene_patch, only: sample_patch_road
    use greenconv_scene_output, only: multi_contact_header
    use greenconv_scene_runner, only: check_scene
    implicit none
    private

    public :: sweep_text, sweep_plan, variant_outcome
    public :: is_sweep_file, read_sweep, variant_lines, variant_key, content_key, read_variant, check_sweep, &
              run_variant
    public :: save_record, summary_row, write_sweep_table, outcome_text, outcome_from_text, run_sweep
    public :: report_check, report_variant, finish_report, replaced_all

    !> Options of the `&sweep` group that are not varied variables.
    character(len=*), parameter :: option_names(4) = [character(len=9) :: 'spectra', 'histories', 'f_low', 'f_high']
    !> Lines of the PSD the lowest band spans (greenconv_io_spectra's default): sets the record a variant needs.
    integer, parameter :: lines_per_band = default_lines_per_band
    !> f_low and f_high name bands by their nominal centres (800 Hz for 794.3 Hz, 5000 Hz for
    !> 5011.9 Hz): a band counts when its exact centre is within this factor (2.3 %, a tenth of
    !> the distance to the next band) of the range; the nominal names differ from the exact by < 1 %.
    real(dp), parameter :: nominal_margin = 10.0_dp**(-0.01_dp)
    !> Width of a band level's column.
    integer, parameter :: level_width = 11

    !> Scene variables a sweep may not vary: they name the sweep and its columns.
    character(len=*), parameter :: fixed_variables(4) = [character(len=19) :: 'scene.task', 'scene.name', &
                                                          'scene.output_dir', 'convolution.methods']

    !> A text of any length: a line of a file, a value as written, a name.
    type :: sweep_text
        !> The text.
        character(len=:), allocatable :: text
    end type sweep_text

    !> A sweep as read from its scene file: the base scene's text and the values of each variant.
    type :: sweep_plan
        !> The sweep scene file.
        character(len=:), allocatable :: file
        !> Lines of the base scene: the file with the `&sweep` group blanked and task 'contact'.
        type(sweep_text), allocatable :: base(:)
        !> The base scene's `name` and `output_dir`.
        character(len=:), allocatable :: name, output_dir
        !> The base scene's methods, in order.
        type(sweep_text), allocatable :: methods(:)
        !> The varied variables, `group.variable` in lower case, in column order.
        type(sweep_text), allocatable :: variables(:)
        !> values(k, j): the value of variable j in variant k, as written (texts with quotes).
        type(sweep_text), allocatable :: values(:, :)
        !> Line of each variable's assignment in the base (0: not assigned) and of its group (0: absent).
        integer, allocatable :: value_line(:), group_line(:)
        !> Start of the names of the temporary variant files (a directory and a unique prefix).
        character(len=:), allocatable :: temp_prefix
        !> Whether the table has the 1/3-octave band levels of each method's total contact force.
        logical :: spectra = .false.
        !> Lowest and highest band centre [Hz] of the levels.
        real(dp) :: f_low = 100.0_dp, f_high = 5000.0_dp
        !> Exact centres [Hz] and upper edges [Hz] of the bands of the levels (none without `spectra`).
        real(dp), allocatable :: band_centre(:), band_upper(:)
        !> Whether each variant writes its per-method column files `<name>_v<k>_<method>.dat`.
        logical :: histories = .false.
    end type sweep_plan

    !> What one variant gave: its summary per method, the CPU times, the worst status.
    type :: variant_outcome
        !> Per method: max, mean, rms of the total contact force [N], fraction of steps in
        !> contact, status, step of the fault; blank-separated, the same on every machine run.
        character(len=:), allocatable :: result
        !> CPU seconds of the contact loop of each method, blank-separated.
        character(len=:), allocatable :: cpu
        !> Worst status of its methods: 0 done, 2 bad input, 3 numerical fault.
        integer :: status = 0
        !> The first failure's message ('' when none).
        character(len=:), allocatable :: message
        !> The variant's content key (`content_key`), set when it ran; its record's name. Not
        !> part of the outcome's text: unset, the outcome is not recorded.
        character(len=:), allocatable :: key
    end type variant_outcome

    !> Running summary of a force history.
    type :: force_summary
        integer(int64) :: steps = 0, in_contact = 0
        real(dp) :: peak = 0.0_dp, total = 0.0_dp, squares = 0.0_dp
    end type force_summary

    interface
        !> C library rename(2): atomic within one file system.
        function c_rename(old_path, new_path) bind(c, name='rename') result(stat)
            import :: c_char, c_int
            implicit none
            character(kind=c_char), intent(in) :: old_path(*)
            character(kind=c_char), intent(in) :: new_path(*)
            integer(c_int) :: stat
        end function c_rename
    end interface

contains

    !> Whether a scene file holds a `&sweep` group (a line starting with `&sweep`); .false.
    !> when it cannot be read (the ordinary reader then says why).
    logical function is_sweep_file(path)
        !> The scene file.
        character(len=*), intent(in) :: path

        type(sweep_text), allocatable :: lines(:)
        type(error_type), allocatable :: error
        integer :: i

        is_sweep_file = .false.
        call read_lines(path, lines, error)
        if (allocated(error)) return
        do i = 1, size(lines)
            if (starts_sweep(lines(i)%text)) is_sweep_file = .true.
        end do
    end function is_sweep_file

    !> Read a sweep scene: its `&sweep` group (and table file), then the base scene, checked
    !> as a scene (so bad base input stops the sweep with status 2 before anything runs).
    subroutine read_sweep(path, plan, error, tag)
        !> The sweep scene file.
        character(len=*), intent(in) :: path
        !> The sweep.
        type(sweep_plan), intent(out) :: plan
        !> Set (status 2) with file:line and what was expected when the sweep is unusable.
        type(error_type), allocatable, intent(out) :: error
        !> A tag that makes this process's temporary file names unique (the MPI rank).
        character(len=*), intent(in), optional :: tag

        type(sweep_text), allocatable :: tokens(:)
        integer, allocatable :: token_lines(:)
        type(scene_type) :: base
        integer :: first, j
        character(len=:), allocatable :: group, variable

        plan%file = path
        plan%temp_prefix = temp_prefix(tag)
        call read_lines(path, plan%base, error)
        if (allocated(error)) return
        call cut_sweep_group(plan, tokens, token_lines, first, error)
        if (.not. allocated(error)) call parse_sweep(plan, tokens, token_lines, first, error)
        if (.not. allocated(error)) call set_task(plan, error)
        if (allocated(error)) return
        call read_text_scene(plan, plan%base, 'the base scene', base, error)
        if (allocated(error)) return
        plan%name = base%name
        plan%output_dir = base%output_dir
        allocate (plan%methods(size(base%methods)))
        do j = 1, size(base%methods)
            plan%methods(j)%text = trim(base%methods(j))
        end do
        allocate (plan%value_line(size(plan%variables)), plan%group_line(size(plan%variables)))
        do j = 1, size(plan%variables)
            call split_name(plan%variables(j)%text, group, variable)
            plan%value_line(j) = base%input%line_of(group, variable)
            plan%group_line(j) = base%input%line_of(group, '')
        end do
    end subroutine read_sweep

    !> The lines of variant k: the base with each varied value written into its group.
    function variant_lines(plan, k) result(lines)
        !> The sweep.
        type(sweep_plan), intent(in) :: plan
        !> Variant number, 1..size(plan%values, 1).
        integer, intent(in) :: k
        !> The variant's scene text, one line per element.
        type(sweep_text), allocatable :: lines(:)

        character(len=:), allocatable :: group, variable, assignment
        integer :: j, line

        lines = plan%base
        do j = 1, size(plan%variables)
            call split_name(plan%variables(j)%text, group, variable)
            assignment = variable//' = '//plan%values(k, j)%text
            if (plan%value_line(j) > 0) then
                line = plan%value_line(j)
                lines(line)%text = replaced_value(lines(line)%text, variable, plan%values(k, j)%text)
                cycle
            end if
            line = plan%group_line(j)
            if (line == 0) line = added_group_line(lines, group)
            if (line == 0) then
                call append_text(lines, '&'//group//' '//assignment//' /')
            else
                lines(line)%text = after_group_name(lines(line)%text, group, assignment)
            end if
        end do
    end function variant_lines

    !> The content key of a variant: two 32-bit FNV-1a hashes (forwards and backwards) of its
    !> text, as 16 hexadecimal digits. Equal texts give equal keys on every machine.
    function variant_key(lines) result(key)
        !> The variant's lines.
        type(sweep_text), intent(in) :: lines(:)
        character(len=16) :: key

        integer(int64), parameter :: prime = 16777619_int64, modulus = 4294967296_int64
        integer(int64) :: forward, backward
        integer :: i, c

        forward = 2166136261_int64
        backward = 3421674724_int64
        do i = 1, size(lines)
            do c = 1, len(lines(i)%text)
                forward = mod(ieor(forward, int(ichar(lines(i)%text(c:c)), int64))*prime, modulus)
            end do
            forward = mod(ieor(forward, 10_int64)*prime, modulus)
        end do
        do i = size(lines), 1, -1
            backward = mod(ieor(backward, 10_int64)*prime, modulus)
            do c = len(lines(i)%text), 1, -1
                backward = mod(ieor(backward, int(ichar(lines(i)%text(c:c)), int64))*prime, modulus)
            end do
        end do
        write (key, '(z8.8,z8.8)') forward, backward
    end function variant_key

    !> Read and check variant k as a scene (also the receptance file it names). A message
    !> names the sweep file and the variant, with the line in the sweep file.
    subroutine read_variant(plan, k, scene, error)
        !> The sweep.
        type(sweep_plan), intent(in) :: plan
        !> Variant number.
        integer, intent(in) :: k
        !> The variant's scene.
        type(scene_type), intent(out) :: scene
        !> Set when the variant is unusable.
        type(error_type), allocatable, intent(out) :: error

        call read_text_scene(plan, variant_lines(plan, k), 'variant '//int_text(k), scene, error)
        if (.not. allocated(error)) call check_spectra(plan, k, scene, error)
    end subroutine read_variant

    !> The content key of variant k, its record's name: `variant_key` of its lines, followed
    !> by a line of the options that change its result (spectra and their bands, histories)
    !> when set, and by each file the scene names (road file or texture, receptance file, Green's
    !> matrix file): its name and
    !> every line of it. An edited road file so changes the key of every variant that reads it.
    !> With histories the key also holds k, which names the variant's files: a variant whose
    !> number an edit of the lists changed runs again and rewrites the files of its number.
    function content_key(plan, k, scene) result(key)
        !> The sweep.
        type(sweep_plan), intent(in) :: plan
        !> Variant number.
        integer, intent(in) :: k
        !> The variant's scene, as `read_variant` gave it.
        type(scene_type), intent(in) :: scene
        character(len=16) :: key

        type(sweep_text), allocatable :: lines(:)

        ! allocated first: gfortran -O2 warns of an unset descriptor otherwise (an array
        ! constructor around variant_lines instead leaks its texts)
        allocate (lines(0))
        lines = variant_lines(plan, k)
        if (plan%spectra) call append_text(lines, '&sweep spectra = .true., f_low = '//real_text(plan%f_low) &
                                           //', f_high = '//real_text(plan%f_high)//' /')
        if (plan%histories) call append_text(lines, '&sweep histories = .true. / ! variant '//int_text(k))
        if (allocated(scene%road_data%path)) call append_file(lines, scene%road_data%path)
        if (allocated(scene%texture%path)) call append_file(lines, scene%texture%path)
        if (allocated(scene%frf_file)) then
            if (len_trim(scene%frf_file) > 0) call append_file(lines, scene%frf_file)
        end if
        if (allocated(scene%green_file)) then
            if (len_trim(scene%green_file) > 0) call append_file(lines, scene%green_file)
        end if
        key = variant_key(lines)
    end function content_key

    !> Append a file's name and its lines (or that it cannot be read) to the lines of a key.
    subroutine append_file(lines, path)
        type(sweep_text), allocatable, intent(inout) :: lines(:)
        character(len=*), intent(in) :: path

        type(sweep_text), allocatable :: content(:)
        type(error_type), allocatable :: error
        integer :: i

        call append_text(lines, '! file '//path)
        call read_lines(path, content, error)
        if (allocated(error)) then
            call append_text(lines, '! unreadable')
            return
        end if
        do i = 1, size(content)
            call append_text(lines, content(i)%text)
        end do
    end subroutine append_file

    !> With spectra, every band must lie below the variant's Nyquist frequency and its record
    !> hold a Welch segment of the lowest band (as greenconv_io_spectra's `band_levels` needs).
    subroutine check_spectra(plan, k, scene, error)
        type(sweep_plan), intent(in) :: plan
        integer, intent(in) :: k
        type(scene_type), intent(in) :: scene
        type(error_type), allocatable, intent(out) :: error

        integer(int64) :: n
        character(len=:), allocatable :: where

        if (size(plan%band_centre) == 0) return
        where = plan%file//' (variant '//int_text(k)//'): &sweep spectra: '
        if (plan%band_upper(size(plan%band_upper)) > 0.5_dp/scene%dt) then
            call fatal_error(error, where//'expected every band up to f_high = '//real_text(plan%f_high) &
                             //' Hz below the Nyquist frequency 1/(2 dt) = '//real_text(0.5_dp/scene%dt) &
                             //' Hz; lower f_high or dt')
            return
        end if
        ! the segment band_levels takes for the lowest band
        n = segment_for_band(first_band(plan%band_centre(1)), scene%dt, lines_per_band)
        if (n > scene%n_steps) call fatal_error(error, where//'expected a record of at least '//int_text(n) &
            //' steps for the band at '//real_text(plan%band_centre(1))//' Hz, found n_steps = ' &
            //int_text(scene%n_steps)//'; raise f_low or n_steps')
    end subroutine check_spectra

    !> Check every variant and find those a previous run finished (their records). On return
    !> `pending` lists the variants to run; `outcomes` holds those done (from their records)
    !> and those that failed their check (status 2, not recorded: a fixed file reruns them).
    !> `unit` gets one line per failed variant and the count.
    subroutine check_sweep(plan, unit, pending, outcomes, n_done, n_bad)
        !> The sweep.
        type(sweep_plan), intent(in) :: plan
        !> Unit of the report.
        integer, intent(in) :: unit
        !> Variants still to run, in order.
        integer, allocatable, intent(out) :: pending(:)
        !> One per variant; set for the variants not pending.
        type(variant_outcome), allocatable, intent(out) :: outcomes(:)
        !> Variants found done, and variants that failed their check.
        integer, intent(out) :: n_done, n_bad

        type(scene_type) :: scene
        type(error_type), allocatable :: error
        logical :: found
        integer :: k, n

        n = size(plan%values, 1)
        allocate (outcomes(n), pending(0))
        n_done = 0
        n_bad = 0
        do k = 1, n
            call read_variant(plan, k, scene, error)
            if (allocated(error)) then
                outcomes(k) = failed_outcome(plan, error)
                n_bad = n_bad + 1
                write (unit, '(a)') 'greenconv: '//error%message
                cycle
            end if
            call load_record(record_path(plan, content_key(plan, k, scene)), outcomes(k), found)
            if (found) then
                n_done = n_done + 1
            else
                pending = [pending, k]
            end if
        end do
    end subroutine check_sweep

    !> Run variant k: every method of its scene, summarised. A fault (bad input, divergence)
    !> is kept in the outcome; nothing is written.
    subroutine run_variant(plan, k, outcome)
        !> The sweep.
        type(sweep_plan), intent(in) :: plan
        !> Variant number.
        integer, intent(in) :: k
        !> Its outcome.
        type(variant_outcome), intent(out) :: outcome

        type(scene_type) :: scene
        type(error_type), allocatable :: error

        call read_variant(plan, k, scene, error)
        if (allocated(error)) then
            outcome = failed_outcome(plan, error)
            return
        end if
        outcome%result = ''
        outcome%cpu = ''
        outcome%message = ''
        scene%progress = .false.
        if (plan%histories) call make_directory(plan%output_dir, error)
        if (allocated(error)) then
            outcome = failed_outcome(plan, error)
            return
        end if
        if (multi_point_model(scene%model)) then
            call run_multipoint_variant(plan, k, scene, outcome)
        else
            call run_single_variant(plan, k, scene, outcome)
        end if
        outcome%key = content_key(plan, k, scene)
    end subroutine run_variant

    !> Record variant k's outcome, atomically, under its content key (nothing when the
    !> outcome has none: the variant failed its check, a fixed file reruns it).
    subroutine save_record(plan, k, outcome, error)
        !> The sweep.
        type(sweep_plan), intent(in) :: plan
        !> Variant number.
        integer, intent(in) :: k
        !> Its outcome.
        type(variant_outcome), intent(in) :: outcome
        !> Set when the record cannot be written.
        type(error_type), allocatable, intent(out) :: error

        type(sweep_text), allocatable :: lines(:)

        if (.not. allocated(outcome%key)) return
        call make_directory(record_directory(plan), error)
        if (allocated(error)) return
        allocate (lines(0))
        call append_text(lines, outcome_text(outcome))
        call write_atomically(record_path(plan, outcome%key), lines, error)
        if (allocated(error)) error%message = 'variant '//int_text(k)//': '//error%message
    end subroutine save_record

    !> The row of variant k in the table: its number, its values, its result.
    function summary_row(plan, k, outcome) result(row)
        !> The sweep.
        type(sweep_plan), intent(in) :: plan
        !> Variant number.
        integer, intent(in) :: k
        !> Its outcome.
        type(variant_outcome), intent(in) :: outcome
        character(len=:), allocatable :: row

        integer :: j

        row = padded(int_text(k), len('# variant') - 2)
        do j = 1, size(plan%variables)
            row = row//'  '//padded(plan%values(k, j)%text, column_width(plan, j))
        end do
        row = row//outcome%result
    end function summary_row

    !> Write `<name>_sweep.dat` (one row per variant, in order) and `<name>_sweep_cpu.dat`
    !> (the CPU seconds of each method), each atomically.
    subroutine write_sweep_table(plan, outcomes, error)
        !> The sweep.
        type(sweep_plan), intent(in) :: plan
        !> One per variant, in variant order.
        type(variant_outcome), intent(in) :: outcomes(:)
        !> Set when a file cannot be written.
        type(error_type), allocatable, intent(out) :: error

        type(sweep_text), allocatable :: table(:), cpu(:)
        character(len=:), allocatable :: names, cpu_names
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
                names = names//' '//padded('L'//nominal_text(plan%band_centre(b))//'_'//plan%methods(j)%text, &
                                           level_width)
            end do
        end do
        allocate (table(0), cpu(0))
        call append_text(table, '# greenconv sweep '//plan%name//' of '//plan%file//': '//int_text(size(outcomes)) &
                         //' variants, rows in variant order')
        call append_text(table, '# per method: max, mean, rms of the total contact force [N], fraction of steps in ' &
                         //'contact, status (0 done, 2 bad input, 3 numerical fault), step of the fault (0: none)')
        if (plan%spectra) call append_text(table, '# then per method and 1/3-octave band L<f_c>_<method>: level of ' &
            //'the total contact force [dB re 1 N] (IEC 61260-1 bands '//real_text(plan%f_low)//' to ' &
            //real_text(plan%f_high)//' Hz; Welch PSD, Hann window, 50 % overlap; nan: the method failed)')
        call append_text(table, names)
        call append_text(cpu, '# greenconv sweep '//plan%name//': CPU seconds of the contact loop of each method')
        call append_text(cpu, cpu_names)
        do k = 1, size(outcomes)
            call append_text(table, summary_row(plan, k, outcomes(k)))
            call append_text(cpu, padded(int_text(k), len('# variant') - 2)//outcomes(k)%cpu)
        end do
        call make_directory(plan%output_dir, error)
        if (.not. allocated(error)) call write_atomically(plan%output_dir//'/'//plan%name//'_sweep.dat', table, error)
        if (.not. allocated(error)) call write_atomically(plan%output_dir//'/'//plan%name//'_sweep_cpu.dat', cpu, error)
    end subroutine write_sweep_table

    !> An outcome as one text (its record, and what an MPI rank sends): four lines.
    function outcome_text(outcome) result(text)
        !> The outcome.
        type(variant_outcome), intent(in) :: outcome
        character(len=:), allocatable :: text

        text = outcome%result//new_line('a')//outcome%cpu//new_line('a')//int_text(outcome%status)//new_line('a') &
               //outcome%message
    end function outcome_text

    !> The outcome `outcome_text` wrote; `ok` is .false. when the text is not one.
    subroutine outcome_from_text(text, outcome, ok)
        !> The text.
        character(len=*), intent(in) :: text
        !> The outcome.
        type(variant_outcome), intent(out) :: outcome
        !> Whether the text held an outcome.
        logical, intent(out) :: ok

        integer :: a, b, c, stat

        a = index(text, new_line('a'))
        b = a + index(text(a + 1:), new_line('a'))
        c = b + index(text(b + 1:), new_line('a'))
        ok = a > 0 .and. b > a .and. c > b
        if (.not. ok) return
        outcome%result = text(:a - 1)
        outcome%cpu = text(a + 1:b - 1)
        read (text(b + 1:c - 1), *, iostat=stat) outcome%status
        ok = stat == 0
        outcome%message = text(c + 1:)
    end subroutine outcome_from_text

    !> Run a sweep on this process alone: read it, check every variant, run those not done
    !> (each recorded as it finishes), write the table. `check_only`: check and print the
    !> count, run nothing. Reports go to `unit`; failed variants are in the table, not errors.
    subroutine run_sweep(path, unit, check_only, error)
        !> The sweep scene file.
        character(len=*), intent(in) :: path
        !> Unit of the report.
        integer, intent(in) :: unit
        !> Only check.
        logical, intent(in) :: check_only
        !> Set for bad input in the sweep or its base (nothing runs), a variant failing
        !> `--check`, or a file that cannot be written.
        type(error_type), allocatable, intent(out) :: error

        type(sweep_plan) :: plan
        type(variant_outcome), allocatable :: outcomes(:)
        integer, allocatable :: pending(:)
        integer :: i, n_done, n_bad

        call read_sweep(path, plan, error)
        if (allocated(error)) return
        call check_sweep(plan, unit, pending, outcomes, n_done, n_bad)
        call report_check(plan, unit, n_done, n_bad, check_only, error)
        if (check_only .or. allocated(error)) return
        do i = 1, size(pending)
            call run_variant(plan, pending(i), outcomes(pending(i)))
            call report_variant(plan, pending(i), outcomes(pending(i)), unit)
            call save_record(plan, pending(i), outcomes(pending(i)), error)
            if (allocated(error)) return
        end do
        call finish_report(plan, outcomes, unit, error)
    end subroutine run_sweep

    ! ---- reports, shared by the serial and the MPI run --------------------------------

    !> The line after the check: the count of variants, done and bad; with `check_only`,
    !> an error (status 2) when a variant is bad.
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

    ! ---- running one variant ------------------------------------------------------------

    !> Each method of a single-point variant, summarised (with its band levels and history
    !> file when the sweep asks for them).
    subroutine run_single_variant(plan, k, scene, outcome)
        type(sweep_plan), intent(in) :: plan
        integer, intent(in) :: k
        type(scene_type), intent(in) :: scene
        type(variant_outcome), intent(inout) :: outcome

        type(structure_model) :: structure
        class(convolver), allocatable :: conv
        type(contact_state) :: state
        type(contact_response) :: response
        type(error_type), allocatable :: failure, error, fault
        type(force_summary) :: summary
        type(column_writer) :: writer
        character(len=:), allocatable :: accuracy, levels, prefix, method
        real(dp), allocatable :: history(:), table(:, :)
        real(dp) :: start, finish, seconds
        integer(int64) :: first
        integer :: i, m, j

        prefix = 'variant '//int_text(k)//': '
        levels = ''
        if (plan%spectra) allocate (history(scene%n_steps))
        call build_structure(scene, structure, failure)
        do i = 1, size(scene%methods)
            method = trim(scene%methods(i))
            summary = force_summary()
            seconds = 0.0_dp
            state%step = 0
            if (allocated(failure)) then
                error = failure
            else
                call make_convolver(method, structure, scene%dt, scene%truncation_tol, scene%n_steps, &
                                    conv, accuracy, error, scene%accuracy)
                if (.not. allocated(error)) call start_contact(conv, scene%law, scene%preload, state, error, &
                                                               scene%contact)
                if (.not. allocated(error) .and. plan%histories) call open_columns(writer, &
                    history_path(plan, scene, k, method), single_header(plan, scene, k, method), 5, error, &
                    binary(scene))
            end if
            do while (.not. (allocated(error) .or. allocated(fault)) .and. state%step < scene%n_steps)
                first = state%step
                m = int(min(int(block_rows, int64), scene%n_steps - first))
                call cpu_time(start)
                call contact_block(conv, state, scene%road%sample_steps(scene%dt, first, m), response, fault)
                call cpu_time(finish)
                seconds = seconds + (finish - start)
                call add_forces(summary, response%force)
                if (plan%spectra) history(first + 1:first + size(response%force)) = response%force
                if (plan%histories) then
                    j = first_kept(first, scene%output_every)
                    associate (r => response, every => scene%output_every)
                        table = reshape([r%time(j::every), r%road(j::every), r%displacement(j::every), &
                                         r%force(j::every), r%compression(j::every)], [size(r%time(j::every)), 5])
                    end associate
                    call append_rows(writer, table, error)
                end if
            end do
            call end_method(plan, writer, fault, error)
            call add_method(outcome, summary, seconds, error, state%step, prefix//method//': ')
            levels = levels//band_text(plan, history, scene, .not. allocated(error))
            call free_convolver(conv)
            if (allocated(error)) deallocate (error)
        end do
        outcome%result = outcome%result//levels
    end subroutine run_single_variant

    !> Each method of a multi-point variant (the tyre's line of points or the nodes of a Green's
    !> matrix file, on a road file or a texture), summarised on the total force (with its band
    !> levels and history file when the sweep asks for them). The points and their convolvers
    !> are those of a contact scene (greenconv_scene_points): a file's receptances are
    !> identified once per variant.
    subroutine run_multipoint_variant(plan, k, scene, outcome)
        type(sweep_plan), intent(in) :: plan
        integer, intent(in) :: k
        type(scene_type), intent(in) :: scene
        type(variant_outcome), intent(inout) :: outcome

        type(scene_points) :: points
        class(multipoint_convolver), allocatable :: conv
        type(multi_contact_state) :: state
        type(multi_contact_response) :: response
        type(error_type), allocatable :: failure, error, fault
        type(force_summary) :: summary
        type(column_writer) :: writer
        real(dp), allocatable :: heights(:, :), history(:)
        character(len=:), allocatable :: accuracy, levels, prefix, method
        real(dp) :: start, finish, seconds
        integer :: i, m, n, n_c, scratch, block
        integer(int64) :: step, first

        prefix = 'variant '//int_text(k)//': '
        levels = ''
        if (plan%spectra) allocate (history(scene%n_steps))
        call find_scene_points(scene, points, failure)
        n_c = max(points%n_points(), 1)
        block = max(block_rows/n_c, 1)
        do i = 1, size(scene%methods)
            method = trim(scene%methods(i))
            summary = force_summary()
            seconds = 0.0_dp
            step = 0
            if (allocated(failure)) then
                error = failure
            else
                call points_convolver(points, scene, method, conv, accuracy, error)
                if (.not. allocated(error)) call start_multi_contact(conv, [(scene%law, n=1, n_c)], &
                    [(scene%preload/n_c, n=1, n_c)], state, error, &
                    newton_options(max_displacement=scene%contact%divergence_bound))
                if (.not. allocated(error) .and. plan%histories) call open_columns(writer, &
                    history_path(plan, scene, k, method), multi_contact_header(history_title(plan, scene, k, &
                    method), points%from_file), merge(8, 7, points%from_file), error, binary(scene))
            end if
            do while (.not. (allocated(error) .or. allocated(fault)) .and. step < scene%n_steps)
                first = step
                m = int(min(int(block, int64), scene%n_steps - step))
                call sample_patch_road(scene, points%road_x, points%road_y, step, m, heights)
                call cpu_time(start)
                call multi_contact_block(conv, state, heights, response, fault)
                call cpu_time(finish)
                seconds = seconds + (finish - start)
                step = state%step
                call add_forces(summary, response%total_force)
                if (plan%spectra) history(first + 1:first + size(response%total_force)) = response%total_force
                if (plan%histories) call append_rows(writer, point_rows(points, response, &
                    first_kept(first, scene%output_every), scene%output_every), error)
            end do
            call end_method(plan, writer, fault, error)
            call add_method(outcome, summary, seconds, error, step, prefix//method//': ')
            levels = levels//band_text(plan, history, scene, .not. allocated(error))
            if (allocated(conv)) then
                call conv%release()
                deallocate (conv)
            end if
            if (allocated(error)) deallocate (error)
            if (allocated(fault)) deallocate (fault)
        end do
        outcome%result = outcome%result//levels
    end subroutine run_multipoint_variant

    !> The column file of variant k's method: `<output_dir>/<name>_v<k>_<method>.dat`, or
    !> `.bin` (with its header `.bin.txt`) for `output_format = 'binary'`, as a contact scene
    !> names its files.
    function history_path(plan, scene, k, method) result(path)
        type(sweep_plan), intent(in) :: plan
        type(scene_type), intent(in) :: scene
        integer, intent(in) :: k
        character(len=*), intent(in) :: method
        character(len=:), allocatable :: path

        path = plan%output_dir//'/'//plan%name//'_v'//int_text(k)//'_'//method//merge('.bin', '.dat', binary(scene))
    end function history_path

    !> Whether a variant's history files are binary (`&scene output_format = 'binary'`).
    logical function binary(scene)
        type(scene_type), intent(in) :: scene

        binary = scene%output_format == 'binary'
    end function binary

    !> First header line of a variant's history file: the sweep, the variant and its values,
    !> the method, the steps; with `output_every` > 1, which steps the rows are.
    function history_title(plan, scene, k, method) result(line)
        type(sweep_plan), intent(in) :: plan
        type(scene_type), intent(in) :: scene
        integer, intent(in) :: k
        character(len=*), intent(in) :: method
        character(len=:), allocatable :: line

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
    end function history_title

    !> The header of a single-point variant's history file: title, units, columns (those of a
    !> contact scene's file).
    function single_header(plan, scene, k, method) result(comments)
        type(sweep_plan), intent(in) :: plan
        type(scene_type), intent(in) :: scene
        integer, intent(in) :: k
        character(len=*), intent(in) :: method
        character(len=:), allocatable :: comments(:)

        character(len=:), allocatable :: title

        title = history_title(plan, scene, k, method)
        allocate (character(len=max(len(title), 40)) :: comments(3))
        comments(1) = title
        comments(2) = 'units: s m m N m'
        comments(3) = 't u_road u f_contact delta'
    end function single_header

    !> End a method: close its history file (when written) and make its failure `error`. A
    !> numerical fault keeps the rows before it (the file is completed and named in the
    !> message); a failed write (its file then gone) is the error instead.
    subroutine end_method(plan, writer, fault, error)
        type(sweep_plan), intent(in) :: plan
        type(column_writer), intent(inout) :: writer
        type(error_type), allocatable, intent(inout) :: fault, error

        if (plan%histories .and. writer%opened) call close_run_file(writer, fault, '', error)
        if (.not. allocated(error) .and. allocated(fault)) call move_alloc(fault, error)
        if (allocated(fault)) deallocate (fault)
    end subroutine end_method

    !> One method's band levels as table columns: ' ' and the level [dB re 1 N] per band of
    !> the sweep; 'nan' for a method that failed (its history is not whole). Empty without spectra.
    function band_text(plan, history, scene, ok) result(text)
        type(sweep_plan), intent(in) :: plan
        real(dp), allocatable, intent(in) :: history(:)
        type(scene_type), intent(in) :: scene
        logical, intent(in) :: ok
        character(len=:), allocatable :: text

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
    end function band_text

    !> Add a block's forces to a summary.
    pure subroutine add_forces(summary, force)
        type(force_summary), intent(inout) :: summary
        real(dp), intent(in) :: force(:)

        integer :: j

        do j = 1, size(force)
            if (summary%steps == 0) summary%peak = force(j)
            summary%steps = summary%steps + 1
            summary%peak = max(summary%peak, force(j))
            summary%total = summary%total + force(j)
            summary%squares = summary%squares + force(j)**2
            if (force(j) > 0.0_dp) summary%in_contact = summary%in_contact + 1
        end do
    end subroutine add_forces

    !> Append one method's columns (and CPU time) to an outcome; a failure sets the status.
    subroutine add_method(outcome, summary, seconds, error, step, prefix)
        type(variant_outcome), intent(inout) :: outcome
        type(force_summary), intent(in) :: summary
        real(dp), intent(in) :: seconds
        type(error_type), allocatable, intent(in) :: error
        integer(int64), intent(in) :: step
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
                         //' '//int_text(status)//' '//int_text(merge(step, 0_int64, status /= 0))
        outcome%cpu = outcome%cpu//' '//cpu_text(seconds)
        if (status /= 0 .and. outcome%status == 0) outcome%message = prefix//error%message
        outcome%status = max(outcome%status, status)
    end subroutine add_method

    !> An outcome whose every method failed before running (the variant's check).
    function failed_outcome(plan, error) result(outcome)
        type(sweep_plan), intent(in) :: plan
        type(error_type), intent(in) :: error
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
    end function failed_outcome

    !> The nominal name of a 1/3-octave band (100, 125, 160, ..., 1000, 1250, ...) from its
    !> exact centre 1000*10^(x/10) Hz: the preferred numbers of IEC 61260-1, three digits.
    function nominal_text(centre) result(text)
        real(dp), intent(in) :: centre
        character(len=:), allocatable :: text

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
    end function nominal_text

    !> CPU seconds as the CPU file shows them.
    function cpu_text(seconds) result(text)
        real(dp), intent(in) :: seconds
        character(len=:), allocatable :: text

        character(len=12) :: buffer

        write (buffer, '(f12.4)') seconds
        text = trim(adjustl(buffer))
    end function cpu_text

    !> One line per finished variant that failed, on `unit`.
    subroutine report_variant(plan, k, outcome, unit)
        !> The sweep.
        type(sweep_plan), intent(in) :: plan
        !> Variant number.
        integer, intent(in) :: k
        !> Its outcome.
        type(variant_outcome), intent(in) :: outcome
        !> Unit of the line.
        integer, intent(in) :: unit

        if (outcome%status /= 0) write (unit, '(a)') 'greenconv: '//plan%file//' variant '//int_text(k) &
            //' failed (status '//int_text(outcome%status)//', recorded in its row): '//outcome%message
    end subroutine report_variant

    !> Write the table and say where it is and how many variants failed. A sweep with failed
    !> variants is not a success even though every other variant completed and the table is
    !> whole: `error` then says how many failed, with the worst status of theirs (3 when one
    !> met a numerical fault, else 2), which the drivers return.
    subroutine finish_report(plan, outcomes, unit, error)
        !> The sweep.
        type(sweep_plan), intent(in) :: plan
        !> One per variant, in variant order.
        type(variant_outcome), intent(in) :: outcomes(:)
        !> Unit of the line.
        integer, intent(in) :: unit
        !> Set when the table cannot be written, or when a variant failed.
        type(error_type), allocatable, intent(out) :: error

        integer :: n_failed

        call write_sweep_table(plan, outcomes, error)
        if (allocated(error)) return
        n_failed = count(outcomes%status /= 0)
        write (unit, '(a)') 'greenconv: sweep '//plan%name//': '//int_text(size(outcomes))//' variants, ' &
            //int_text(n_failed)//' failed; table '//plan%output_dir//'/'//plan%name//'_sweep.dat'
        if (n_failed > 0) call fatal_error(error, 'sweep '//plan%name//': '//int_text(n_failed)//' of ' &
                                           //int_text(size(outcomes))//' variants failed (each named above, its ' &
                                           //'status and step in its row of the table); the others are done', &
                                           maxval(outcomes%status))
    end subroutine finish_report

    ! ---- records ------------------------------------------------------------------------

    !> The directory of the records of finished variants.
    function record_directory(plan) result(path)
        type(sweep_plan), intent(in) :: plan
        character(len=:), allocatable :: path

        path = plan%output_dir//'/'//plan%name//'_sweep.d'
    end function record_directory

    !> The record of a variant, named by its content key.
    function record_path(plan, key) result(path)
        type(sweep_plan), intent(in) :: plan
        character(len=*), intent(in) :: key
        character(len=:), allocatable :: path

        path = record_directory(plan)//'/'//key//'.rec'
    end function record_path

    !> Read a record; `found` is .false. when there is none (or it is not one).
    subroutine load_record(path, outcome, found)
        character(len=*), intent(in) :: path
        type(variant_outcome), intent(out) :: outcome
        logical, intent(out) :: found

        type(sweep_text), allocatable :: lines(:)
        type(error_type), allocatable :: error
        character(len=:), allocatable :: text
        integer :: i

        inquire (file=path, exist=found)
        if (.not. found) return
        call read_lines(path, lines, error)
        found = .not. allocated(error)
        if (.not. found) return
        found = size(lines) >= 3
        if (.not. found) return
        text = lines(1)%text
        do i = 2, size(lines)
            text = text//new_line('a')//lines(i)%text
        end do
        if (size(lines) == 3) text = text//new_line('a')
        call outcome_from_text(text, outcome, found)
    end subroutine load_record

    ! ---- files --------------------------------------------------------------------------

    !> Every line of a text file.
    subroutine read_lines(path, lines, error)
        character(len=*), intent(in) :: path
        type(sweep_text), allocatable, intent(out) :: lines(:)
        type(error_type), allocatable, intent(out) :: error

        character(len=:), allocatable :: line
        character(len=512) :: message
        integer :: unit, stat

        allocate (lines(0))
        open (newunit=unit, file=path, status='old', action='read', iostat=stat, iomsg=message)
        if (stat /= 0) then
            call fatal_error(error, path//': cannot open the file: '//trim(message))
            return
        end if
        do
            call read_line(unit, line, stat)
            if (stat /= 0) exit
            call append_text(lines, line)
        end do
        close (unit)
    end subroutine read_lines

    !> Write lines to `path.part`, then rename it to `path` (a reader never sees half a file).
    subroutine write_atomically(path, lines, error)
        character(len=*), intent(in) :: path
        type(sweep_text), intent(in) :: lines(:)
        type(error_type), allocatable, intent(out) :: error

        character(len=512) :: message
        integer :: unit, stat, i

        open (newunit=unit, file=path//'.part', status='replace', action='write', iostat=stat, iomsg=message)
        do i = 1, size(lines)
            if (stat == 0) write (unit, '(a)', iostat=stat, iomsg=message) lines(i)%text
        end do
        if (stat == 0) close (unit, iostat=stat, iomsg=message)
        if (stat == 0) stat = c_rename(path//'.part'//c_null_char, path//c_null_char)
        if (stat /= 0) call fatal_error(error, path//': cannot write the file ('//trim(message) &
                                        //'); check that its directory is writable and the disk not full')
    end subroutine write_atomically

    !> Write lines to a new temporary file, read it as a scene, delete it; messages name the
    !> sweep file and `what` instead of the temporary file. Also checks files the scene names.
    subroutine read_text_scene(plan, lines, what, scene, error)
        type(sweep_plan), intent(in) :: plan
        type(sweep_text), intent(in) :: lines(:)
        character(len=*), intent(in) :: what
        type(scene_type), intent(out) :: scene
        type(error_type), allocatable, intent(out) :: error

        character(len=:), allocatable :: path
        integer :: unit, stat, i, attempt, scratch

        do attempt = 1, 1000
            path = plan%temp_prefix//int_text(attempt)//'.nml'
            open (newunit=unit, file=path, status='new', action='write', iostat=stat)
            if (stat == 0) exit
        end do
        if (stat /= 0) then
            call fatal_error(error, path//': cannot write a temporary scene file; set TMPDIR to a writable directory')
            return
        end if
        do i = 1, size(lines)
            write (unit, '(a)') lines(i)%text
        end do
        close (unit)
        call read_scene(path, scene, error)
        if (.not. allocated(error)) then
            open (newunit=scratch, status='scratch', action='readwrite')
            call check_scene(scene, scratch, error)
            close (scratch)
        end if
        open (newunit=unit, file=path, status='old', iostat=stat)
        if (stat == 0) close (unit, status='delete')
        scene%file = plan%file
        if (allocated(error)) error%message = replaced_all(error%message, path, plan%file//' ('//what//')')
    end subroutine read_text_scene

    !> A unique start for this process's temporary file names: $TMPDIR (or /tmp), the clock, the tag.
    function temp_prefix(tag) result(prefix)
        character(len=*), intent(in), optional :: tag
        character(len=:), allocatable :: prefix

        character(len=1024) :: directory
        integer(int64) :: clock
        integer :: length, stat

        call get_environment_variable('TMPDIR', directory, length, stat)
        if (stat /= 0 .or. length == 0) directory = '/tmp'
        call system_clock(clock)
        prefix = trim(directory)//'/greenconv_sweep_'//int_text(clock)//'_'
        if (present(tag)) prefix = prefix//tag//'_'
    end function temp_prefix

    ! ---- the &sweep group -----------------------------------------------------------------

    !> Whether a line opens the `&sweep` group.
    logical function starts_sweep(line)
        character(len=*), intent(in) :: line

        character(len=:), allocatable :: text

        text = lower_text(adjustl(line))
        starts_sweep = .false.
        if (index(text, '&sweep') /= 1) return
        ! (Fortran does not short-circuit .or.: text(7:7) is read only when it exists)
        starts_sweep = len_trim(text) == 6
        if (.not. starts_sweep) starts_sweep = verify(text(7:7), ' !/') == 0
    end function starts_sweep

    !> Find the `&sweep` group, take its tokens (with their lines) and blank its lines in the base.
    subroutine cut_sweep_group(plan, tokens, token_lines, first, error)
        type(sweep_plan), intent(inout) :: plan
        type(sweep_text), allocatable, intent(out) :: tokens(:)
        integer, allocatable, intent(out) :: token_lines(:)
        integer, intent(out) :: first
        type(error_type), allocatable, intent(out) :: error

        type(sweep_text), allocatable :: found(:)
        integer :: i, j

        allocate (tokens(0), token_lines(0))
        first = 0
        do i = 1, size(plan%base)
            if (starts_sweep(plan%base(i)%text)) then
                first = i
                exit
            end if
        end do
        if (first == 0) then
            call fatal_error(error, plan%file//": &sweep: expected a group &sweep ... / naming the varied " &
                             //"variables (task 'sweep'), found none")
            return
        end if
        do i = first, size(plan%base)
            found = split_tokens(plan%base(i)%text)
            if (i == first) found = found(2:)
            plan%base(i)%text = ''
            do j = 1, size(found)
                if (found(j)%text == '/') return
                tokens = [tokens, found(j)]
                token_lines = [token_lines, i]
            end do
        end do
        call fatal_error(error, plan%file//':'//int_text(first)//": &sweep: expected '/' to close the group, " &
                         //'found the end of the file')
    end subroutine cut_sweep_group

    !> The entries of the `&sweep` group: `group.variable = value, ...` lists and `table_file`;
    !> then the variants (the table's rows times the lists' cartesian product).
    subroutine parse_sweep(plan, tokens, token_lines, first, error)
        type(sweep_plan), intent(inout) :: plan
        type(sweep_text), intent(in) :: tokens(:)
        integer, intent(in) :: token_lines(:), first
        type(error_type), allocatable, intent(out) :: error

        type(sweep_text), allocatable :: names(:), lists(:, :), table(:, :), table_names(:), values(:)
        integer, allocatable :: counts(:)
        character(len=:), allocatable :: name, where, table_file
        integer :: i, j, n

        allocate (names(0), counts(0), lists(0, 0), table_names(0), table(1, 0))
        table_file = ''
        i = 1
        do while (i <= size(tokens))
            name = lower_text(tokens(i)%text)
            where = plan%file//':'//int_text(token_lines(i))//': &sweep '//name//': '
            if (i + 1 > size(tokens) .or. is_value(name)) then
                call fatal_error(error, where//"expected 'group.variable = value, value, ...' or " &
                                 //"'table_file = ''file''', found '"//tokens(i)%text//"'")
                return
            end if
            if (tokens(i + 1)%text /= '=') then
                call fatal_error(error, where//"expected '=' after the name, found '"//tokens(i + 1)%text//"'")
                return
            end if
            i = i + 2
            allocate (values(0))
            do while (i <= size(tokens))
                if (tokens(i)%text == ',') then
                    i = i + 1
                    cycle
                end if
                if (i < size(tokens)) then
                    if (tokens(i + 1)%text == '=') exit
                end if
                values = [values, tokens(i)]
                i = i + 1
            end do
            if (size(values) == 0) then
                call fatal_error(error, where//'expected at least one value, found none')
                return
            end if
            if (name == 'table_file') then
                table_file = unquoted(values(1)%text)
                call read_design(plan%file, token_lines(i - 1), table_file, table_names, table, error)
            else if (any(option_names == name)) then
                call set_option(plan, name, values, where, error)
            else
                call check_variable(where, name, names, table_names, error)
                if (.not. allocated(error)) then
                    call append_text(names, name)
                    counts = [counts, size(values)]
                    lists = widened(lists, values)
                end if
            end if
            deallocate (values)
            if (allocated(error)) return
        end do
        do j = 1, size(table_names)
            call check_variable(plan%file//':'//int_text(first)//': &sweep table_file: '//table_file//': ', &
                                table_names(j)%text, table_names(:j - 1), names, error)
            if (allocated(error)) return
        end do
        plan%variables = [table_names, names]
        call set_bands(plan, first, error)
        if (allocated(error)) return
        if (size(plan%variables) == 0) then
            call fatal_error(error, plan%file//':'//int_text(first)//': &sweep: expected at least one varied ' &
                             //"variable ('road.speed = 10.0, 20.0' or 'table_file = ''design.txt'''), found none")
            return
        end if
        n = size(table, 1)*product(counts)
        allocate (plan%values(n, size(plan%variables)))
        do i = 1, n
            call variant_values(i, table, lists, counts, plan%values(i, :))
        end do
    end subroutine parse_sweep

    !> An option of the `&sweep` group (`spectra`, `histories`: a logical; `f_low`, `f_high`: Hz).
    subroutine set_option(plan, name, values, where, error)
        type(sweep_plan), intent(inout) :: plan
        character(len=*), intent(in) :: name, where
        type(sweep_text), intent(in) :: values(:)
        type(error_type), allocatable, intent(out) :: error

        logical :: flag
        real(dp) :: x
        integer :: stat

        if (size(values) /= 1) then
            call fatal_error(error, where//'expected one value, found '//int_text(size(values)))
            return
        end if
        select case (name)
        case ('spectra', 'histories')
            read (values(1)%text, *, iostat=stat) flag
            if (stat /= 0) then
                call fatal_error(error, where//"expected .true. or .false., found '"//values(1)%text//"'")
                return
            end if
            if (name == 'spectra') plan%spectra = flag
            if (name == 'histories') plan%histories = flag
        case default
            read (values(1)%text, *, iostat=stat) x
            if (stat /= 0 .or. .not. (x > 0.0_dp .and. x < huge(x))) then
                call fatal_error(error, where//"expected a band centre frequency > 0 in Hz, found '" &
                                 //values(1)%text//"'")
                return
            end if
            if (name == 'f_low') plan%f_low = x
            if (name == 'f_high') plan%f_high = x
        end select
    end subroutine set_option

    !> The bands of the levels, from f_low and f_high, when the sweep asks for spectra.
    subroutine set_bands(plan, first, error)
        type(sweep_plan), intent(inout) :: plan
        integer, intent(in) :: first
        type(error_type), allocatable, intent(out) :: error

        real(dp), allocatable :: lower(:)

        allocate (plan%band_centre(0), plan%band_upper(0))
        if (.not. plan%spectra) return
        call third_octave_bands(plan%f_low*nominal_margin, plan%f_high/nominal_margin, huge(1.0_dp), &
                                plan%band_centre, lower, plan%band_upper)
        if (size(plan%band_centre) == 0) call fatal_error(error, plan%file//':'//int_text(first) &
            //': &sweep f_low, f_high: expected a range holding a 1/3-octave band centre (e.g. f_low = 100.0, ' &
            //'f_high = 5000.0), found '//real_text(plan%f_low)//' to '//real_text(plan%f_high)//' Hz')
    end subroutine set_bands

    !> The values of variant i: table row slowest, then the lists, the last one fastest.
    subroutine variant_values(i, table, lists, counts, values)
        integer, intent(in) :: i, counts(:)
        type(sweep_text), intent(in) :: table(:, :), lists(:, :)
        type(sweep_text), intent(inout) :: values(:)

        integer :: rest, j, n_table

        n_table = size(table, 2)
        rest = i - 1
        do j = size(counts), 1, -1
            values(n_table + j) = lists(mod(rest, counts(j)) + 1, j)
            rest = rest/counts(j)
        end do
        if (n_table > 0) values(:n_table) = table(rest + 1, :)
    end subroutine variant_values

    !> A list of lists with one more column (lists(:, j) the values of variable j).
    function widened(lists, values) result(wider)
        type(sweep_text), intent(in) :: lists(:, :), values(:)
        type(sweep_text), allocatable :: wider(:, :)

        integer :: j

        allocate (wider(max(size(lists, 1), size(values)), size(lists, 2) + 1))
        do j = 1, size(lists, 2)
            wider(:size(lists, 1), j) = lists(:, j)
        end do
        wider(:size(values), size(lists, 2) + 1) = values
    end function widened

    !> A table of variants: a header naming the variables (a leading `#` allowed), then one
    !> row of values per variant; blank lines and later `#` lines are skipped.
    subroutine read_design(file, line, path, names, table, error)
        character(len=*), intent(in) :: file, path
        integer, intent(in) :: line
        type(sweep_text), allocatable, intent(inout) :: names(:), table(:, :)
        type(error_type), allocatable, intent(out) :: error

        type(sweep_text), allocatable :: lines(:), row(:)
        character(len=:), allocatable :: text
        integer :: i

        if (size(names) > 0) then
            call fatal_error(error, file//':'//int_text(line)//': &sweep table_file: expected one table file, ' &
                             //'found a second')
            return
        end if
        call read_lines(path, lines, error)
        if (allocated(error)) then
            error%message = file//':'//int_text(line)//': &sweep table_file: '//error%message
            return
        end if
        do i = 1, size(lines)
            text = adjustl(lines(i)%text)
            if (len_trim(text) == 0) cycle
            if (size(names) == 0) then
                if (text(1:1) == '#') text = text(2:)
                names = without_commas(split_tokens(lower_text(text)))
                deallocate (table)
                allocate (table(0, size(names)))
                cycle
            end if
            if (text(1:1) == '#') cycle
            if (allocated(row)) deallocate (row)
            row = without_commas(split_tokens(text))
            if (size(row) /= size(names)) then
                call fatal_error(error, path//':'//int_text(i)//': expected '//int_text(size(names)) &
                                 //' values (one per variable of the header), found '//int_text(size(row)))
                return
            end if
            table = appended_row(table, row)
        end do
        if (size(names) == 0 .or. size(table, 1) == 0) then
            call fatal_error(error, path//': expected a header naming the variables and at least one row of ' &
                             //'values, found none')
        end if
    end subroutine read_design

    !> Tokens without the commas between them.
    function without_commas(tokens) result(kept)
        type(sweep_text), intent(in) :: tokens(:)
        type(sweep_text), allocatable :: kept(:)

        integer :: i

        allocate (kept(0))
        do i = 1, size(tokens)
            if (tokens(i)%text /= ',') kept = [kept, tokens(i)]
        end do
    end function without_commas

    !> A table with one more row.
    function appended_row(table, row) result(longer)
        type(sweep_text), intent(in) :: table(:, :), row(:)
        type(sweep_text), allocatable :: longer(:, :)

        allocate (longer(size(table, 1) + 1, size(row)))
        longer(:size(table, 1), :) = table
        longer(size(table, 1) + 1, :) = row
    end function appended_row

    !> A varied variable must be a scene variable `group.variable`, not one naming the sweep, and named once.
    subroutine check_variable(where, name, earlier, others, error)
        character(len=*), intent(in) :: where, name
        type(sweep_text), intent(in) :: earlier(:), others(:)
        type(error_type), allocatable, intent(out) :: error

        type(scene_variable), allocatable :: table(:)
        integer :: i

        if (named(earlier, name) .or. named(others, name)) then
            call fatal_error(error, where//"expected each variable varied once, found '"//name//"' again")
            return
        end if
        if (any(fixed_variables == name)) then
            call fatal_error(error, where//"expected a variable the sweep may vary, found '"//name &
                             //"', which names the sweep or its columns; make one sweep per value instead")
            return
        end if
        table = scene_table()
        do i = 1, size(table)
            if (table(i)%group//'.'//table(i)%name == name) return
        end do
        call fatal_error(error, where//"expected a scene variable written group.variable (e.g. road.speed, " &
                         //"contact.stiffness), found '"//name//"'")
    end subroutine check_variable

    !> Append a text to a list.
    subroutine append_text(list, text)
        type(sweep_text), allocatable, intent(inout) :: list(:)
        character(len=*), intent(in) :: text

        type(sweep_text), allocatable :: longer(:)
        integer :: i

        allocate (longer(size(list) + 1))
        do i = 1, size(list)
            call move_alloc(list(i)%text, longer(i)%text)
        end do
        longer(size(longer))%text = text
        call move_alloc(longer, list)
    end subroutine append_text

    !> Whether a list of names holds `name`.
    logical function named(names, name)
        type(sweep_text), intent(in) :: names(:)
        character(len=*), intent(in) :: name

        integer :: i

        named = .false.
        do i = 1, size(names)
            if (names(i)%text == name) named = .true.
        end do
    end function named

    !> Set task = 'sweep' to 'contact' in the base (the line keeps its number).
    subroutine set_task(plan, error)
        type(sweep_plan), intent(inout) :: plan
        type(error_type), allocatable, intent(out) :: error

        character(len=:), allocatable :: text
        integer :: i, at

        do i = 1, size(plan%base)
            text = lower_text(plan%base(i)%text)
            if (index(text, 'task') == 0) cycle
            at = max(index(text, "'sweep'"), index(text, '"sweep"'))
            if (at == 0) cycle
            plan%base(i)%text = plan%base(i)%text(:at - 1)//"'contact'"//plan%base(i)%text(at + 7:)
            return
        end do
        call fatal_error(error, plan%file//": &scene task: expected task = 'sweep' in a scene with a &sweep " &
                         //"group, found another task; set task = 'sweep' or remove the &sweep group")
    end subroutine set_task

    ! ---- text ---------------------------------------------------------------------------

    !> Tokens of a line: words, texts in quotes (kept with their quotes), `=`, `,`, `/`; a `!`
    !> outside quotes starts a comment.
    function split_tokens(line) result(tokens)
        character(len=*), intent(in) :: line
        type(sweep_text), allocatable :: tokens(:)

        integer :: i, j

        allocate (tokens(0))
        i = 1
        do while (i <= len(line))
            select case (line(i:i))
            case (' ', char(9))
                i = i + 1
            case ('!')
                return
            case ('=', ',', '/')
                call append_text(tokens, line(i:i))
                i = i + 1
            case ("'", '"')
                j = i + 1
                do while (j <= len(line))
                    if (line(j:j) == line(i:i)) then
                        if (j < len(line)) then
                            if (line(j + 1:j + 1) == line(i:i)) then
                                j = j + 2
                                cycle
                            end if
                        end if
                        exit
                    end if
                    j = j + 1
                end do
                call append_text(tokens, line(i:min(j, len(line))))
                i = j + 1
            case default
                j = i
                do while (j < len(line))
                    if (scan(line(j + 1:j + 1), ' =,/!''"'//char(9)) > 0) exit
                    j = j + 1
                end do
                call append_text(tokens, line(i:j))
                i = j + 1
            end select
        end do
    end function split_tokens

    !> Whether a token is a value rather than a name (a number, a logical, a text in quotes).
    pure logical function is_value(token)
        character(len=*), intent(in) :: token

        is_value = scan(token(1:1), '0123456789+-.''"') > 0
    end function is_value

    !> A text without its quotes.
    pure function unquoted(text) result(bare)
        character(len=*), intent(in) :: text
        character(len=:), allocatable :: bare

        bare = text
        if (len(text) >= 2) then
            if (scan(text(1:1), '''"') > 0 .and. text(len(text):len(text)) == text(1:1)) bare = text(2:len(text) - 1)
        end if
    end function unquoted

    !> `group.variable` split in two.
    subroutine split_name(name, group, variable)
        character(len=*), intent(in) :: name
        character(len=:), allocatable, intent(out) :: group, variable

        group = name(:index(name, '.') - 1)
        variable = name(index(name, '.') + 1:)
    end subroutine split_name

    !> A line with the value of `variable = ...` replaced by `value` (up to a comment, the
    !> group's `/` or the next assignment on the line).
    function replaced_value(line, variable, value) result(changed)
        character(len=*), intent(in) :: line, variable, value
        character(len=:), allocatable :: changed

        character(len=:), allocatable :: low, rest
        integer :: at, start, finish, i, j

        low = lower_text(line)//repeat(' ', len(line) - len(lower_text(line)))
        changed = line
        at = 0
        do i = 1, len(low) - len(variable) + 1
            if (low(i:i + len(variable) - 1) /= variable) cycle
            if (i > 1) then
                if (verify(low(i - 1:i - 1), ' ,&'//char(9)) /= 0) cycle
            end if
            j = i + len(variable)
            do while (j <= len(low))
                if (low(j:j) /= ' ') exit
                j = j + 1
            end do
            if (j > len(low)) cycle
            if (low(j:j) /= '=') cycle
            at = j
            exit
        end do
        if (at == 0) return
        start = at + 1
        finish = at
        i = start
        do while (i <= len(line))
            select case (line(i:i))
            case (' ', ',', char(9))
                i = i + 1
            case ('!', '/')
                exit
            case ("'", '"')
                j = index(line(i + 1:), line(i:i))
                if (j == 0) j = len(line) - i
                finish = i + j
                i = finish + 1
            case default
                j = i
                do while (j < len(line))
                    if (scan(line(j + 1:j + 1), ' =,/!'//char(9)) > 0) exit
                    j = j + 1
                end do
                rest = adjustl(line(j + 1:))
                if (len_trim(rest) > 0) then
                    if (rest(1:1) == '=') exit
                end if
                finish = j
                i = j + 1
            end select
        end do
        changed = line(:at)//' '//value//line(finish + 1:)
    end function replaced_value

    !> A line with `assignment` written right after its `&group`.
    function after_group_name(line, group, assignment) result(changed)
        character(len=*), intent(in) :: line, group, assignment
        character(len=:), allocatable :: changed

        integer :: at

        at = index(lower_text(line), '&'//group) + len(group)
        changed = line(:at)//' '//assignment//' '//line(at + 1:)
    end function after_group_name

    !> The line of a group added at the end of a variant (0 when none was added).
    integer function added_group_line(lines, group)
        type(sweep_text), intent(in) :: lines(:)
        character(len=*), intent(in) :: group

        integer :: i

        added_group_line = 0
        do i = 1, size(lines)
            if (index(lower_text(adjustl(lines(i)%text)), '&'//group//' ') == 1) added_group_line = i
        end do
    end function added_group_line

    !> Every occurrence of `old` in `text` replaced by `new` (left to right, each once: `new`
    !> may hold `old`).
    function replaced_all(text, old, new) result(changed)
        !> The text.
        character(len=*), intent(in) :: text
        !> What to replace (not empty).
        character(len=*), intent(in) :: old
        !> What replaces it.
        character(len=*), intent(in) :: new
        character(len=:), allocatable :: changed

        integer :: at, from

        changed = ''
        from = 1
        do while (len(old) > 0)
            at = index(text(from:), old)
            if (at == 0) exit
            changed = changed//text(from:from + at - 2)//new
            from = from + at - 1 + len(old)
        end do
        changed = changed//text(from:)
    end function replaced_all

    !> A text padded with blanks on the right to at least `width` characters.
    pure function padded(text, width) result(wide)
        character(len=*), intent(in) :: text
        integer, intent(in) :: width
        character(len=max(len(text), width)) :: wide

        wide = text
    end function padded

    !> The width of variable j's column: its name or its widest value.
    integer function column_width(plan, j)
        type(sweep_plan), intent(in) :: plan
        integer, intent(in) :: j

        integer :: k

        column_width = len(plan%variables(j)%text)
        do k = 1, size(plan%values, 1)
            column_width = max(column_width, len(plan%values(k, j)%text))
        end do
    end function column_width

end module greenconv_scene_sweep
