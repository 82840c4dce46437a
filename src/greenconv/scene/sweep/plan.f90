!> A parameter sweep's plan: the `&sweep` group of a scene with `task = 'sweep'`,
!> the base scene and the values of every variant (see greenconv_scene_sweep for the
!> format). A variant is the base scene's text with each varied value written in (replacing
!> the assignment, or added to its group); the `&sweep` group is blanked and the task set to
!> 'contact', so lines keep their numbers in messages. A variant's scene is read from these
!> lines in memory (greenconv_scene_read_input's `read_scene_lines`) and checked as the driver's
!> `--check` does (greenconv_scene_run_runner's `check_scene_line`): no file is written.
module greenconv_scene_sweep_plan
    use, intrinsic :: iso_fortran_env, only: int64
    use greenconv_core_kinds, only: dp
    use greenconv_core_error, only: error_type, fatal_error
    use greenconv_core_text, only: int_text, lower_text, real_text
    ! sweep_text: a text of any length (a line of a file, a value as written, a name).
    use greenconv_io_columns, only: sweep_text => text_line, read_line_list, pad_lines
    use greenconv_io_spectra, only: segment_for_band, first_band, default_lines_per_band, third_octave_bands
    use greenconv_scene_read_facade, only: scene_table, scene_variable, scene_type, scene_files, read_scene_lines
    use greenconv_scene_run_facade, only: check_scene_line
    implicit none
    private

    public :: sweep_text, sweep_plan, scene_files, lines_per_band, nominal_margin
    public :: is_sweep_file, read_sweep, variant_lines, read_variant, read_text_lines, append_text, replaced_all, &
              padded, column_width

    !> Options of the `&sweep` group that are not varied variables.
    character(len=*), parameter :: option_names(4) = [character(len=9) :: 'spectra', 'histories', 'f_low', 'f_high']
    !> Lines of the PSD the lowest band spans (greenconv_io_spectra's default): sets the record a variant needs.
    integer, parameter :: lines_per_band = default_lines_per_band
    !> f_low and f_high name bands by their nominal centres (800 Hz for 794.3 Hz, 5000 Hz for
    !> 5011.9 Hz): a band counts when its exact centre is within this factor (2.3 %, a tenth of
    !> the distance to the next band) of the range; the nominal names differ from the exact by < 1 %.
    real(dp), parameter :: nominal_margin = 10.0_dp**(-0.01_dp)

    !> Scene variables a sweep may not vary: they name the sweep and its columns.
    character(len=*), parameter :: fixed_variables(4) = [character(len=19) :: 'scene.task', 'scene.name', &
                                                          'scene.output_dir', 'convolution.methods']

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
        !> Whether the table has the 1/3-octave band levels of each method's total contact force.
        logical :: spectra = .false.
        !> Lowest and highest band centre [Hz] of the levels.
        real(dp) :: f_low = 100.0_dp, f_high = 5000.0_dp
        !> Exact centres [Hz] and upper edges [Hz] of the bands of the levels (none without `spectra`).
        real(dp), allocatable :: band_centre(:), band_upper(:)
        !> Whether each variant writes its per-method column files `<name>_v<k>_<method>.dat`.
        logical :: histories = .false.
    end type sweep_plan

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
        call read_text_lines(path, lines, error)
        if (allocated(error)) return
        do i = 1, size(lines)
            if (starts_sweep(lines(i)%text)) is_sweep_file = .true.
        end do
    end function is_sweep_file

    !> Read a sweep scene: its `&sweep` group (and table file), then the base scene, checked
    !> as a scene (so bad base input stops the sweep with status 2 before anything runs).
    subroutine read_sweep(path, plan, error)
        !> The sweep scene file.
        character(len=*), intent(in) :: path
        !> The sweep.
        type(sweep_plan), intent(out) :: plan
        !> Set (status 2) with file:line and what was expected when the sweep is unusable.
        type(error_type), allocatable, intent(out) :: error

        type(sweep_text), allocatable :: tokens(:)
        integer, allocatable :: token_lines(:)
        type(scene_type) :: base
        integer :: first, j
        character(len=:), allocatable :: group, variable

        plan%file = path
        call read_text_lines(path, plan%base, error)
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

        character(len=:), allocatable :: group, variable, assignment, changed
        integer :: j, line

        lines = plan%base
        do j = 1, size(plan%variables)
            call split_name(plan%variables(j)%text, group, variable)
            assignment = variable//' = '//plan%values(k, j)%text
            if (plan%value_line(j) > 0) then
                line = plan%value_line(j)
                call replace_value(lines(line)%text, variable, plan%values(k, j)%text, changed)
                lines(line)%text = changed
                cycle
            end if
            line = plan%group_line(j)
            if (line == 0) line = added_group_line(lines, group)
            if (line == 0) then
                call append_text(lines, '&'//group//' '//assignment//' /')
            else
                call after_group_name(lines(line)%text, group, assignment, changed)
                lines(line)%text = changed
            end if
        end do
    end function variant_lines

    !> Read and check variant k as a scene, from memory (also the files it names). A message
    !> names the sweep file and the variant, with the line in the sweep file.
    subroutine read_variant(plan, k, scene, error, files)
        !> The sweep.
        type(sweep_plan), intent(in) :: plan
        !> Variant number.
        integer, intent(in) :: k
        !> The variant's scene.
        type(scene_type), intent(out) :: scene
        !> Set when the variant is unusable.
        type(error_type), allocatable, intent(out) :: error
        !> Road files and textures read by earlier variants (each file is read once).
        type(scene_files), intent(inout) :: files

        call read_text_scene(plan, variant_lines(plan, k), 'variant '//int_text(k), scene, error, files)
        if (.not. allocated(error)) call check_spectra(plan, k, scene, error)
    end subroutine read_variant

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
                             //' Hz; lower f_high, or &scene dt')
            return
        end if
        ! the segment band_levels takes for the lowest band
        n = segment_for_band(first_band(plan%band_centre(1)), scene%dt, lines_per_band)
        if (n > scene%n_steps) call fatal_error(error, where//'expected a record of at least '//int_text(n) &
            //' steps for the band at '//real_text(plan%band_centre(1))//' Hz, found n_steps = ' &
            //int_text(scene%n_steps)//'; raise f_low, or &scene n_steps')
    end subroutine check_spectra

    !> Every line of a text file (greenconv_io_columns's `read_line_list`), trailing blanks kept;
    !> no lines when it cannot be read.
    subroutine read_text_lines(path, lines, error)
        !> The file.
        character(len=*), intent(in) :: path
        !> Its lines.
        type(sweep_text), allocatable, intent(out) :: lines(:)
        !> Set when the file cannot be opened or read.
        type(error_type), allocatable, intent(out) :: error

        call read_line_list(path, 'file', '', lines, error)
        if (allocated(error)) allocate (lines(0))
    end subroutine read_text_lines

    !> Read lines as a scene from memory and check it as `--check` does (the files it names
    !> too); messages name the sweep file and `what` (the base scene, variant k), with the line.
    subroutine read_text_scene(plan, lines, what, scene, error, files)
        type(sweep_plan), intent(in) :: plan
        type(sweep_text), intent(in) :: lines(:)
        character(len=*), intent(in) :: what
        type(scene_type), intent(out) :: scene
        type(error_type), allocatable, intent(out) :: error
        type(scene_files), intent(inout), optional :: files

        character(len=:), allocatable :: fixed(:), line

        call pad_lines(lines, fixed)
        call read_scene_lines(plan%file//' ('//what//')', fixed, scene, error, files)
        if (.not. allocated(error)) call check_scene_line(scene, line, error)
        scene%file = plan%file
    end subroutine read_text_scene

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
        call read_text_lines(path, lines, error)
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
        !> The list [texts], grown by one.
        type(sweep_text), allocatable, intent(inout) :: list(:)
        !> The text to append.
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

    !> Whether a text is between two equal quotes.
    pure logical function quoted(text)
        character(len=*), intent(in) :: text

        quoted = .false.
        if (len(text) >= 2) quoted = scan(text(1:1), '''"') > 0 .and. text(len(text):len(text)) == text(1:1)
    end function quoted

    !> A text without its quotes.
    pure function unquoted(text) result(bare)
        character(len=*), intent(in) :: text
        character(len=len(text) - merge(2, 0, quoted(text))) :: bare

        bare = text
        if (quoted(text)) bare = text(2:len(text) - 1)
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
    subroutine replace_value(line, variable, value, changed)
        character(len=*), intent(in) :: line, variable, value
        character(len=:), allocatable, intent(out) :: changed

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
    end subroutine replace_value

    !> A line with `assignment` written right after its `&group`.
    subroutine after_group_name(line, group, assignment, changed)
        character(len=*), intent(in) :: line, group, assignment
        character(len=:), allocatable, intent(out) :: changed

        integer :: at

        at = index(lower_text(line), '&'//group) + len(group)
        changed = line(:at)//' '//assignment//' '//line(at + 1:)
    end subroutine after_group_name

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
        !> The text.
        character(len=*), intent(in) :: text
        !> The least width [characters].
        integer, intent(in) :: width
        character(len=max(len(text), width)) :: wide

        wide = text
    end function padded

    !> The width of variable j's column: its name or its widest value.
    integer function column_width(plan, j)
        !> The sweep.
        type(sweep_plan), intent(in) :: plan
        !> Index of the varied variable.
        integer, intent(in) :: j

        integer :: k

        column_width = len(plan%variables(j)%text)
        do k = 1, size(plan%values, 1)
            column_width = max(column_width, len(plan%values(k, j)%text))
        end do
    end function column_width

end module greenconv_scene_sweep_plan
