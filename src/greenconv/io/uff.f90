!> Reading universal files (ASCII): functions at nodal DOF (dataset 58) and nodes (datasets
!> 15 and 2411), the format measurement systems and FE codes export FRFs, impulse responses
!> and geometry in. Other datasets are skipped and listed.
!>
!> A file is a sequence of datasets, each between two lines holding `-1` right-justified in
!> columns 1-6; the line after the opening one holds the dataset number (columns 1-6; a `b`
!> in column 7 marks a binary dataset, which is refused). Blank lines between datasets are
!> ignored.
!>
!> Dataset 58 (function at nodal DOF), where each output of `uff_function` comes from:
!>
!> | record | format                          | output                                          |
!> |--------|---------------------------------|-------------------------------------------------|
!> | 1-5    | 80A1                            | `id_lines(1:5)`                                 |
!> | 6      | 2(I5,I10),2(1X,10A1,I10,I4)     | `function_type`, `function_id`, `version`,      |
!> |        |                                 | `load_case`, `response_entity`, `response_node`,|
!> |        |                                 | `response_direction`, `reference_entity`,       |
!> |        |                                 | `reference_node`, `reference_direction`         |
!> | 7      | 3I10,3E13.5                     | `ordinate_type` (2, 4, 5, 6), number of points, |
!> |        |                                 | `even` (spacing 1) or uneven (0), abscissa      |
!> |        |                                 | minimum and increment, `z_value`                |
!> | 8      | I10,3I5,2(1X,20A1)              | `abscissa_axis` (17 time [s], 18 frequency [Hz])|
!> | 9      | I10,3I5,2(1X,20A1)              | `numerator` (ordinate numerator)                |
!> | 10     | I10,3I5,2(1X,20A1)              | `denominator` (ordinate denominator)            |
!> | 11     | I10,3I5,2(1X,20A1)              | `z_axis`                                        |
!> | 12     | see below                       | `abscissa`, `ordinate`                          |
!>
!> `kind` is derived from records 9 and 10: a denominator of force (specific data type 9 or
!> 13) over a numerator of displacement (8) is a receptance, of velocity (11) a mobility,
!> of acceleration (12) an accelerance; anything else is `uff_other`. No conversion is
!> done here. `abscissa` is always an array: for even spacing it is minimum + (i - 1)
!> increment from record 7, for uneven spacing the values interleaved in record 12.
!> `ordinate` is complex; real data (types 2 and 4) get a zero imaginary part.
!>
!> Record 12 is read in fixed-width fields, as the format says (fields may touch; numbers
!> may use E or D exponents, or the Fortran form without a letter such as `0.12345-100`;
!> the last line may be shorter; blank lines are skipped):
!>
!> | ordinate        | even spacing        | uneven spacing                     |
!> |-----------------|---------------------|------------------------------------|
!> | real single     | 6E13.5: y           | 6E13.5: x, y pairs                 |
!> | complex single  | 6E13.5: Re, Im      | 6E13.5: x, Re, Im                  |
!> | real double     | 4E20.12: y          | 2(E13.5,E20.12): x, y pairs        |
!> | complex double  | 4E20.12: Re, Im     | E13.5,2E20.12: x, Re, Im per line  |
!>
!> Dataset 15: one record per node, 4I10,1P3E13.5 (label, definition and displacement
!> coordinate systems, color, x, y, z). Dataset 2411: two records per node, 4I10 (the
!> same integers) and 1P3D25.16 (x, y, z). Coordinates are returned as written, in the
!> definition coordinate system.
!>
!> Every malformed file gets one line with status 2 (`stat_input`), e.g.
!>
!>     frf.uff:12: universal file dataset 58 record 7: expected the number of points > 0
!>     (an integer in columns 11-20), found "0"
module greenconv_io_uff
    use, intrinsic :: iso_fortran_env, only: int64
    use greenconv_core_kinds, only: dp
    use greenconv_core_error, only: error_type, fatal_error
    use greenconv_core_text, only: int_text, real_text
    use greenconv_core_number_text, only: is_number, is_nan_or_inf, is_integer, read_real, read_integer
    use greenconv_io_columns, only: read_line
    implicit none
    private

    public :: uff_axis, uff_function, uff_node, uff_skipped, uff_file
    public :: read_uff, uff_summary, uff_kind_name, uff_data_type_name, uff_function_type_name
    public :: uff_other, uff_receptance, uff_mobility, uff_accelerance

    !> Ordinate kind of a dataset 58 that is none of the three below (see `uff_kind_name`).
    integer, parameter :: uff_other = 0
    !> Ordinate kind: displacement over force (records 9/10 specific data types 8 over 9 or 13),
    !> [m/N] in SI.
    integer, parameter :: uff_receptance = 1
    !> Ordinate kind: velocity over force (11 over 9 or 13), [m/(s N)] in SI.
    integer, parameter :: uff_mobility = 2
    !> Ordinate kind: acceleration over force (12 over 9 or 13), [m/(s^2 N)] in SI.
    integer, parameter :: uff_accelerance = 3

    !> Data characteristics of one axis of a dataset 58 (records 8 to 11).
    type :: uff_axis
        !> Specific data type (field 1): 0 unknown, 8 displacement, 9 reaction force,
        !> 11 velocity, 12 acceleration, 13 excitation force, 17 time, 18 frequency, ...
        !> (see `uff_data_type_name`).
        integer :: data_type = 0
        !> Length units exponent (field 2; meaningful for data type 1, general).
        integer :: length_exponent = 0
        !> Force units exponent (field 3).
        integer :: force_exponent = 0
        !> Temperature units exponent (field 4).
        integer :: temperature_exponent = 0
        !> Axis label (field 5, columns 27-46), trimmed; `NONE` when unused.
        character(len=:), allocatable :: label
        !> Axis units label (field 6, columns 48-67), trimmed; `NONE` when unused.
        character(len=:), allocatable :: units
    end type uff_axis

    !> One dataset 58: a function (FRF, time response, ...) at a response and a reference DOF.
    type :: uff_function
        !> Line of the file where the dataset starts (its opening `-1`), for messages.
        integer :: line = 0
        !> Records 1-5: ID lines (description, run, date, load case name, ...).
        character(len=80) :: id_lines(5) = ''
        !> Record 6 field 1: 0 general, 1 time response, 4 frequency response function, ...
        !> (see `uff_function_type_name`).
        integer :: function_type = 0
        !> Record 6 field 2: function identification number.
        integer :: function_id = 0
        !> Record 6 field 3: version or sequence number.
        integer :: version = 0
        !> Record 6 field 4: load case identification number (0: single point excitation).
        integer :: load_case = 0
        !> Record 6 field 5: response entity name, trimmed.
        character(len=:), allocatable :: response_entity
        !> Record 6 field 6: response node label.
        integer :: response_node = 0
        !> Record 6 field 7: response direction: 0 scalar, +-1/2/3 X/Y/Z translation,
        !> +-4/5/6 X/Y/Z rotation.
        integer :: response_direction = 0
        !> Record 6 field 8: reference entity name, trimmed.
        character(len=:), allocatable :: reference_entity
        !> Record 6 field 9: reference node label.
        integer :: reference_node = 0
        !> Record 6 field 10: reference direction (coded as the response direction).
        integer :: reference_direction = 0
        !> Record 7 field 1: 2 real single, 4 real double, 5 complex single, 6 complex double.
        integer :: ordinate_type = 0
        !> Record 7 field 3: whether the abscissa spacing is even (1) rather than uneven (0).
        logical :: even = .true.
        !> Record 7 field 6: z-axis value (0 when unused), in the units of `z_axis`.
        real(dp) :: z_value = 0.0_dp
        !> Record 8: abscissa data characteristics.
        type(uff_axis) :: abscissa_axis
        !> Record 9: ordinate (numerator) data characteristics.
        type(uff_axis) :: numerator
        !> Record 10: ordinate denominator data characteristics.
        type(uff_axis) :: denominator
        !> Record 11: z-axis data characteristics.
        type(uff_axis) :: z_axis
        !> From records 9 and 10: `uff_receptance`, `uff_mobility`, `uff_accelerance` or `uff_other`.
        integer :: kind = uff_other
        !> Abscissa of every point [Hz for frequency, s for time, as `abscissa_axis` says].
        real(dp), allocatable :: abscissa(:)
        !> Ordinate of every point, in the units records 9 and 10 say (e.g. [m/N]).
        complex(dp), allocatable :: ordinate(:)
    end type uff_function

    !> One node of dataset 15 or 2411.
    type :: uff_node
        !> Node label.
        integer :: label = 0
        !> Definition (export) coordinate system number.
        integer :: definition_system = 0
        !> Displacement coordinate system number.
        integer :: displacement_system = 0
        !> Color number.
        integer :: color = 0
        !> x, y, z coordinates in the definition system [the model's length unit].
        real(dp) :: position(3) = 0.0_dp
        !> Dataset the node came from: 15 or 2411.
        integer :: dataset = 0
        !> Line of the file holding the node's (first) record.
        integer :: line = 0
    end type uff_node

    !> A dataset the reader does not read.
    type :: uff_skipped
        !> Dataset number.
        integer :: dataset = 0
        !> Line of the file where it starts (its opening `-1`).
        integer :: line = 0
    end type uff_skipped

    !> What `read_uff` found in a universal file, in file order.
    type :: uff_file
        !> The file read.
        character(len=:), allocatable :: path
        !> Every dataset 58.
        type(uff_function), allocatable :: functions(:)
        !> Every node of datasets 15 and 2411.
        type(uff_node), allocatable :: nodes(:)
        !> Every dataset skipped.
        type(uff_skipped), allocatable :: skipped(:)
    end type uff_file

    !> One line of the file, without its line end.
    type :: text_line
        character(len=:), allocatable :: text
    end type text_line

    !> Extent of one dataset in the file's lines.
    type :: dataset_extent
        !> Dataset number.
        integer :: number = 0
        !> Lines of the opening and closing `-1`.
        integer :: first = 0, last = 0
    end type dataset_extent

    !> Columns of the fixed-width integer fields of record 6 (2(I5,I10),2(1X,10A1,I10,I4)).
    integer, parameter :: record6_first(10) = [1, 6, 16, 21, 32, 42, 52, 57, 67, 77]
    integer, parameter :: record6_last(10) = [5, 15, 20, 30, 41, 51, 55, 66, 76, 80]

contains

    !> Read a universal file: every dataset 58, 15 and 2411; others are listed in `skipped`.
    subroutine read_uff(path, file, error)
        !> File to read.
        character(len=*), intent(in) :: path
        !> What the file holds.
        type(uff_file), intent(out) :: file
        !> Set (status 2) when the file cannot be read or is malformed; the message names
        !> the file, the line, the dataset and record, what was expected and what was found.
        type(error_type), allocatable, intent(out) :: error

        type(text_line), allocatable :: lines(:)
        type(dataset_extent), allocatable :: sets(:)
        integer :: i, n_functions, n_skipped, n_nodes

        file%path = path
        allocate (file%functions(0), file%nodes(0), file%skipped(0))
        call load_lines(path, lines, error)
        if (allocated(error)) return
        call find_datasets(path, lines, sets, error)
        if (allocated(error)) return
        n_functions = count(sets%number == 58)
        n_skipped = count(sets%number /= 58 .and. sets%number /= 15 .and. sets%number /= 2411)
        deallocate (file%functions, file%skipped)
        allocate (file%functions(n_functions), file%skipped(n_skipped))
        n_functions = 0
        n_skipped = 0
        n_nodes = 0
        do i = 1, size(sets)
            select case (sets(i)%number)
            case (58)
                n_functions = n_functions + 1
                call read_function(path, lines, sets(i), file%functions(n_functions), error)
            case (15, 2411)
                call read_nodes(path, lines, sets(i), file%nodes, n_nodes, error)
            case default
                n_skipped = n_skipped + 1
                file%skipped(n_skipped) = uff_skipped(sets(i)%number, sets(i)%first)
            end select
            if (allocated(error)) return
        end do
        file%nodes = file%nodes(1:n_nodes)
    end subroutine read_uff

    !> One line saying what a file held: functions, nodes and the datasets skipped, e.g.
    !> `frf.uff: 4 functions (dataset 58), 6 nodes (datasets 15, 2411), skipped: 151 (line 1)`.
    pure function uff_summary(file) result(text)
        !> A file read by `read_uff`.
        type(uff_file), intent(in) :: file
        character(len=:), allocatable :: text

        integer :: i

        text = file%path//': '//int_text(size(file%functions))//' functions (dataset 58), ' &
               //int_text(size(file%nodes))//' nodes (datasets 15, 2411)'
        if (size(file%skipped) == 0) return
        text = text//', skipped:'
        do i = 1, size(file%skipped)
            if (i > 1) text = text//','
            text = text//' '//int_text(file%skipped(i)%dataset)//' (line '//int_text(file%skipped(i)%line)//')'
        end do
    end function uff_summary

    !> Name of an ordinate kind: `receptance`, `mobility`, `accelerance` or `other`.
    pure function uff_kind_name(kind) result(name)
        !> `uff_receptance`, `uff_mobility`, `uff_accelerance` or `uff_other`.
        integer, intent(in) :: kind
        character(len=:), allocatable :: name

        select case (kind)
        case (uff_receptance)
            name = 'receptance'
        case (uff_mobility)
            name = 'mobility'
        case (uff_accelerance)
            name = 'accelerance'
        case default
            name = 'other'
        end select
    end function uff_kind_name

    !> Name of a specific data type of records 8-11 (`displacement`, `excitation force`, ...);
    !> `type N` for a code the format does not list.
    pure function uff_data_type_name(code) result(name)
        !> Specific data type (record 8-11 field 1).
        integer, intent(in) :: code
        character(len=:), allocatable :: name

        select case (code)
        case (0); name = 'unknown'
        case (1); name = 'general'
        case (2); name = 'stress'
        case (3); name = 'strain'
        case (5); name = 'temperature'
        case (6); name = 'heat flux'
        case (8); name = 'displacement'
        case (9); name = 'reaction force'
        case (11); name = 'velocity'
        case (12); name = 'acceleration'
        case (13); name = 'excitation force'
        case (15); name = 'pressure'
        case (16); name = 'mass'
        case (17); name = 'time'
        case (18); name = 'frequency'
        case (19); name = 'rpm'
        case (20); name = 'order'
        case default; name = 'type '//int_text(code)
        end select
    end function uff_data_type_name

    !> Name of a function type of record 6 field 1 (`time response`, `frequency response
    !> function`, ...); `type N` for a code the format does not list.
    pure function uff_function_type_name(code) result(name)
        !> Function type (record 6 field 1).
        integer, intent(in) :: code
        character(len=:), allocatable :: name

        character(len=*), parameter :: names(0:27) = [character(len=34) :: 'general or unknown', 'time response', &
            'auto spectrum', 'cross spectrum', 'frequency response function', 'transmissibility', 'coherence', &
            'auto correlation', 'cross correlation', 'power spectral density', 'energy spectral density', &
            'probability density function', 'spectrum', 'cumulative frequency distribution', 'peaks valley', &
            'stress/cycles', 'strain/cycles', 'orbit', 'mode indicator function', 'force pattern', 'partial power', &
            'partial coherence', 'eigenvalue', 'eigenvector', 'shock response spectrum', &
            'finite impulse response filter', 'multiple coherence', 'order function']

        if (code >= lbound(names, 1) .and. code <= ubound(names, 1)) then
            name = trim(names(code))
        else
            name = 'type '//int_text(code)
        end if
    end function uff_function_type_name

    ! ---- file structure ----------------------------------------------------------------

    !> Read every line of a file (a trailing carriage return removed).
    subroutine load_lines(path, lines, error)
        character(len=*), intent(in) :: path
        type(text_line), allocatable, intent(out) :: lines(:)
        type(error_type), allocatable, intent(out) :: error

        character(len=:), allocatable :: line
        character(len=512) :: message
        integer :: unit, stat, n, i

        open (newunit=unit, file=path, status='old', action='read', iostat=stat, iomsg=message)
        if (stat /= 0) then
            call fatal_error(error, path//': cannot open the universal file: '//trim(message) &
                             //'; check the file name and that it is readable')
            return
        end if
        n = 0
        do
            call read_line(unit, line, stat)
            if (stat /= 0) exit
            n = n + 1
        end do
        if (n == 0) then
            close (unit)
            call fatal_error(error, path//':1: universal file: expected datasets between lines "    -1", ' &
                             //'found an empty file')
            return
        end if
        rewind (unit)
        allocate (lines(n))
        do i = 1, n
            call read_line(unit, line, stat)
            if (len(line) > 0) then
                if (line(len(line):len(line)) == achar(13)) line = line(:len(line) - 1)
            end if
            lines(i)%text = line
        end do
        close (unit)
    end subroutine load_lines

    !> Whether a line is a dataset delimiter: `-1` ending within columns 1-6, nothing else.
    pure logical function is_delimiter(line)
        character(len=*), intent(in) :: line

        is_delimiter = len_trim(line) <= 6 .and. trim(adjustl(line)) == '-1'
    end function is_delimiter

    !> Locate every dataset: its number and the lines of its opening and closing `-1`.
    subroutine find_datasets(path, lines, sets, error)
        character(len=*), intent(in) :: path
        type(text_line), intent(in) :: lines(:)
        type(dataset_extent), allocatable, intent(out) :: sets(:)
        type(error_type), allocatable, intent(out) :: error

        type(dataset_extent), allocatable :: found(:)
        character(len=:), allocatable :: token, hint
        integer :: i, j, n, number
        logical :: ok

        allocate (found(count([(is_delimiter(lines(i)%text), i=1, size(lines))])/2 + 1))
        n = 0
        i = 1
        do while (i <= size(lines))
            if (len_trim(lines(i)%text) == 0) then
                i = i + 1
                cycle
            end if
            if (.not. is_delimiter(lines(i)%text)) then
                hint = ''
                if (n > 0) hint = '; is the -1 line that ends the dataset '//int_text(found(n)%number) &
                                  //' started at line '//int_text(found(n)%first)//' missing?'
                call fatal_error(error, path//':'//int_text(i)//': universal file: expected a line "    -1" ' &
                                 //'that starts a dataset, found "'//trim(lines(i)%text)//'"'//hint)
                return
            end if
            if (i == size(lines)) then
                call fatal_error(error, path//':'//int_text(i)//': universal file: expected a dataset number ' &
                                 //'after the -1 line, found the end of the file')
                return
            end if
            token = first_token(lines(i + 1)%text)
            ok = is_integer(token)
            if (ok) call read_integer(token, number, ok)
            if (.not. ok) then
                if (len(token) > 1 .and. is_integer(token(:max(len(token) - 1, 1))) &
                    .and. scan(token(len(token):), 'bB') == 1) then
                    call fatal_error(error, path//':'//int_text(i + 1)//': universal file dataset ' &
                                     //token//': expected an ASCII dataset, found a binary one; export the file ' &
                                     //'as an ASCII universal file')
                else
                    call fatal_error(error, path//':'//int_text(i + 1)//': universal file: expected a dataset ' &
                                     //'number (an integer in columns 1-6) after the -1 line, found "' &
                                     //trim(lines(i + 1)%text)//'"')
                end if
                return
            end if
            j = i + 2
            do while (j <= size(lines))
                if (is_delimiter(lines(j)%text)) exit
                j = j + 1
            end do
            if (j > size(lines)) then
                call fatal_error(error, path//':'//int_text(size(lines))//': universal file dataset ' &
                                 //int_text(number)//': expected a line "    -1" that ends the dataset started at ' &
                                 //'line '//int_text(i)//', found the end of the file; the file may be truncated')
                return
            end if
            n = n + 1
            found(n) = dataset_extent(number, i, j)
            i = j + 1
        end do
        sets = found(1:n)
    end subroutine find_datasets

    !> The first blank-separated word of a line ('' when blank).
    pure function first_token(line) result(token)
        character(len=*), intent(in) :: line
        character(len=:), allocatable :: token

        integer :: last

        token = trim(adjustl(line))
        last = index(token, ' ')
        if (last > 0) token = token(:last - 1)
    end function first_token

    !> `path:line: universal file dataset N record R: `, the start of every message about a record.
    pure function at(path, line, dataset, record) result(prefix)
        character(len=*), intent(in) :: path
        integer, intent(in) :: line, dataset, record
        character(len=:), allocatable :: prefix

        prefix = path//':'//int_text(line)//': universal file dataset '//int_text(dataset)//' record ' &
                 //int_text(record)//': '
    end function at

    ! ---- fields --------------------------------------------------------------------------

    !> Columns first..last of a line, blank-padded where the line is shorter.
    pure function columns(line, first, last) result(field)
        character(len=*), intent(in) :: line
        integer, intent(in) :: first, last
        character(len=last - first + 1) :: field

        field = ''
        if (first <= len(line)) field = line(first:min(last, len(line)))
    end function columns

    !> `columns a-b` for messages.
    pure function span(first, last) result(text)
        integer, intent(in) :: first, last
        character(len=:), allocatable :: text

        text = 'columns '//int_text(first)//'-'//int_text(last)
    end function span

    !> Columns first..last of a line in quotes for messages, or `blanks`.
    pure function quoted(line, first, last) result(text)
        character(len=*), intent(in) :: line
        integer, intent(in) :: first, last
        character(len=:), allocatable :: text

        text = trim(adjustl(columns(line, first, last)))
        if (len(text) == 0) then
            text = 'blanks'
        else
            text = '"'//text//'"'
        end if
    end function quoted

    !> What a field of `parse_real` status 1 or 2 should have held, for messages.
    pure function number_words(status) result(text)
        integer, intent(in) :: status
        character(len=:), allocatable :: text

        text = 'a number'
        if (status == 2) text = 'a finite number'
    end function number_words

    !> Read the integer in columns first..last; a blank field is 0 unless `required`.
    subroutine integer_field(prefix, line, first, last, what, required, value, error)
        character(len=*), intent(in) :: prefix, line, what
        integer, intent(in) :: first, last
        logical, intent(in) :: required
        integer, intent(out) :: value
        type(error_type), allocatable, intent(out) :: error

        character(len=:), allocatable :: field
        logical :: ok

        value = 0
        field = trim(adjustl(columns(line, first, last)))
        if (len(field) == 0 .and. .not. required) return
        ok = is_integer(field)
        if (ok) call read_integer(field, value, ok)
        if (.not. ok) call fatal_error(error, prefix//'expected '//what//' (an integer in '//span(first, last) &
                                       //'), found '//quoted(line, first, last))
    end subroutine integer_field

    !> Read the real in columns first..last; a blank field is 0 unless `required`. `layout`
    !> names the record's format for messages.
    subroutine real_field(prefix, line, first, last, what, layout, required, value, error)
        character(len=*), intent(in) :: prefix, line, what, layout
        integer, intent(in) :: first, last
        logical, intent(in) :: required
        real(dp), intent(out) :: value
        type(error_type), allocatable, intent(out) :: error

        character(len=:), allocatable :: field
        integer :: status

        value = 0.0_dp
        field = trim(adjustl(columns(line, first, last)))
        if (len(field) == 0 .and. .not. required) return
        call parse_real(field, value, status)
        if (status /= 0) call fatal_error(error, prefix//'expected '//what//' ('//number_words(status)//' in ' &
                                          //span(first, last)//', '//layout//'), found '//quoted(line, first, last))
    end subroutine real_field

    !> Read a number written as a Fortran E, D or F field would hold it, blanks removed:
    !> `1.5E+02`, `1.5e2`, `1.5D+02`, `0.15+003` (exponent without its letter), `150`.
    !> status: 0 read, 1 not a number (or blank), 2 NaN, infinite or beyond double precision.
    subroutine parse_real(field, value, status)
        character(len=*), intent(in) :: field
        real(dp), intent(out) :: value
        integer, intent(out) :: status

        character(len=len(field) + 1) :: token
        integer :: i, sign_at
        logical :: ok

        value = 0.0_dp
        status = 1
        if (len(field) == 0 .or. index(field, ' ') > 0) return
        if (is_nan_or_inf(field)) then
            status = 2
            return
        end if
        token = field
        do i = 1, len(field)
            if (token(i:i) == 'd' .or. token(i:i) == 'D') token(i:i) = 'E'
        end do
        if (scan(token, 'eE') == 0) then
            sign_at = scan(token(2:), '+-')
            if (sign_at > 0) token = token(:sign_at)//'E'//field(sign_at + 1:)
        end if
        if (.not. is_number(trim(token))) return
        call read_real(trim(token), value, ok)
        status = merge(0, 2, ok)
    end subroutine parse_real

    ! ---- dataset 58 ----------------------------------------------------------------------

    !> Read one dataset 58: records 1 to 11 from the eleven lines after the dataset number,
    !> record 12 from the lines up to the closing -1.
    subroutine read_function(path, lines, set, function, error)
        character(len=*), intent(in) :: path
        type(text_line), intent(in) :: lines(:)
        type(dataset_extent), intent(in) :: set
        type(uff_function), intent(out) :: function
        type(error_type), allocatable, intent(out) :: error

        character(len=*), parameter :: record_names(11) = [character(len=56) :: &
            'ID line 1 (80A1)', 'ID line 2 (80A1)', 'ID line 3 (80A1)', 'ID line 4 (80A1)', 'ID line 5 (80A1)', &
            'the DOF identification (2(I5,I10),2(1X,10A1,I10,I4))', 'the data form (3I10,3E13.5)', &
            'the abscissa characteristics (I10,3I5,2(1X,20A1))', &
            'the ordinate characteristics (I10,3I5,2(1X,20A1))', &
            'the denominator characteristics (I10,3I5,2(1X,20A1))', &
            'the z-axis characteristics (I10,3I5,2(1X,20A1))']
        integer :: record, n_points

        function%line = set%first
        do record = 1, 11
            if (set%first + 1 + record >= set%last) then
                call fatal_error(error, at(path, set%last, 58, record)//'expected '//trim(record_names(record)) &
                                 //', found the -1 line that ends the dataset; the dataset is truncated')
                return
            end if
        end do
        do record = 1, 5
            function%id_lines(record) = lines(set%first + 1 + record)%text
        end do
        call read_record6(at(path, set%first + 7, 58, 6), lines(set%first + 7)%text, function, error)
        if (allocated(error)) return
        call read_record7(at(path, set%first + 8, 58, 7), lines(set%first + 8)%text, function, n_points, error)
        if (allocated(error)) return
        call read_axis(at(path, set%first + 9, 58, 8), lines(set%first + 9)%text, function%abscissa_axis, error)
        if (allocated(error)) return
        call read_axis(at(path, set%first + 10, 58, 9), lines(set%first + 10)%text, function%numerator, error)
        if (allocated(error)) return
        call read_axis(at(path, set%first + 11, 58, 10), lines(set%first + 11)%text, function%denominator, error)
        if (allocated(error)) return
        call read_axis(at(path, set%first + 12, 58, 11), lines(set%first + 12)%text, function%z_axis, error)
        if (allocated(error)) return
        function%kind = ordinate_kind(function%numerator%data_type, function%denominator%data_type)
        call read_data(path, lines, set%first + 13, set%last, n_points, function, error)
    end subroutine read_function

    !> Record 6: DOF identification, 2(I5,I10),2(1X,10A1,I10,I4).
    subroutine read_record6(prefix, line, function, error)
        character(len=*), intent(in) :: prefix, line
        type(uff_function), intent(inout) :: function
        type(error_type), allocatable, intent(out) :: error

        character(len=*), parameter :: names(10) = [character(len=36) :: 'the function type', &
            'the function identification number', 'the version number', 'the load case number', '', &
            'the response node', 'the response direction', '', 'the reference node', 'the reference direction']
        logical, parameter :: required(10) = [.true., .false., .false., .false., .false., .true., .true., &
                                              .false., .true., .true.]
        integer :: values(10), field

        values = 0
        do field = 1, 10
            if (field == 5 .or. field == 8) cycle
            call integer_field(prefix, line, record6_first(field), record6_last(field), trim(names(field)), &
                               required(field), values(field), error)
            if (allocated(error)) return
        end do
        call check_direction(prefix, line, 7, values(7), error)
        if (.not. allocated(error)) call check_direction(prefix, line, 10, values(10), error)
        if (allocated(error)) return
        function%function_type = values(1)
        function%function_id = values(2)
        function%version = values(3)
        function%load_case = values(4)
        function%response_entity = trim(adjustl(columns(line, record6_first(5), record6_last(5))))
        function%response_node = values(6)
        function%response_direction = values(7)
        function%reference_entity = trim(adjustl(columns(line, record6_first(8), record6_last(8))))
        function%reference_node = values(9)
        function%reference_direction = values(10)
    end subroutine read_record6

    !> A direction code of record 6 must lie in -6..6.
    subroutine check_direction(prefix, line, field, value, error)
        character(len=*), intent(in) :: prefix, line
        integer, intent(in) :: field, value
        type(error_type), allocatable, intent(out) :: error

        if (abs(value) <= 6) return
        call fatal_error(error, prefix//'expected a direction from -6 to 6 (0 scalar, 1-3 translation, 4-6 ' &
                         //'rotation) in '//span(record6_first(field), record6_last(field))//', found ' &
                         //quoted(line, record6_first(field), record6_last(field)))
    end subroutine check_direction

    !> Record 7: data form, 3I10,3E13.5.
    subroutine read_record7(prefix, line, function, n_points, error)
        character(len=*), intent(in) :: prefix, line
        type(uff_function), intent(inout) :: function
        integer, intent(out) :: n_points
        type(error_type), allocatable, intent(out) :: error

        character(len=*), parameter :: layout = '3I10,3E13.5'
        integer :: spacing
        real(dp) :: minimum, step
        integer :: i

        call integer_field(prefix, line, 1, 10, 'the ordinate data type', .true., function%ordinate_type, error)
        if (allocated(error)) return
        if (all(function%ordinate_type /= [2, 4, 5, 6])) then
            call fatal_error(error, prefix//'expected an ordinate data type 2 (real single), 4 (real double), ' &
                             //'5 (complex single) or 6 (complex double) in columns 1-10, found ' &
                             //quoted(line, 1, 10))
            return
        end if
        call integer_field(prefix, line, 11, 20, 'the number of points', .true., n_points, error)
        if (allocated(error)) return
        if (n_points <= 0) then
            call fatal_error(error, prefix//'expected the number of points > 0 (an integer in columns 11-20), ' &
                             //'found '//quoted(line, 11, 20))
            return
        end if
        call integer_field(prefix, line, 21, 30, 'the abscissa spacing', .true., spacing, error)
        if (allocated(error)) return
        if (spacing /= 0 .and. spacing /= 1) then
            call fatal_error(error, prefix//'expected the abscissa spacing 1 (even) or 0 (uneven) in columns ' &
                             //'21-30, found '//quoted(line, 21, 30))
            return
        end if
        function%even = spacing == 1
        call real_field(prefix, line, 31, 43, 'the abscissa minimum', layout, function%even, minimum, error)
        if (allocated(error)) return
        call real_field(prefix, line, 44, 56, 'the abscissa increment', layout, function%even, step, error)
        if (allocated(error)) return
        call real_field(prefix, line, 57, 69, 'the z-axis value', layout, .false., function%z_value, error)
        if (allocated(error)) return
        if (len_trim(line) > 69) then
            call fatal_error(error, prefix//'expected nothing after column 69 ('//layout//'), found "' &
                             //trim(adjustl(line(70:)))//'"')
            return
        end if
        if (function%even .and. n_points > 1 .and. .not. step > 0.0_dp) then
            call fatal_error(error, prefix//'expected an abscissa increment > 0 for even spacing (columns 44-56), ' &
                             //'found '//quoted(line, 44, 56))
            return
        end if
        if (function%even) function%abscissa = [(minimum + (i - 1)*step, i=1, n_points)]
    end subroutine read_record7

    !> Records 8 to 11: data characteristics, I10,3I5,2(1X,20A1).
    subroutine read_axis(prefix, line, axis, error)
        character(len=*), intent(in) :: prefix, line
        type(uff_axis), intent(out) :: axis
        type(error_type), allocatable, intent(out) :: error

        call integer_field(prefix, line, 1, 10, 'the specific data type', .true., axis%data_type, error)
        if (allocated(error)) return
        call integer_field(prefix, line, 11, 15, 'the length units exponent', .false., axis%length_exponent, error)
        if (allocated(error)) return
        call integer_field(prefix, line, 16, 20, 'the force units exponent', .false., axis%force_exponent, error)
        if (.not. allocated(error)) call integer_field(prefix, line, 21, 25, 'the temperature units exponent', &
                                                       .false., axis%temperature_exponent, error)
        axis%label = trim(adjustl(columns(line, 27, 46)))
        axis%units = trim(adjustl(columns(line, 48, 67)))
    end subroutine read_axis

    !> Receptance, mobility or accelerance from the specific data types of records 9 and 10.
    pure integer function ordinate_kind(numerator, denominator)
        integer, intent(in) :: numerator, denominator

        ordinate_kind = uff_other
        if (denominator /= 9 .and. denominator /= 13) return
        select case (numerator)
        case (8)
            ordinate_kind = uff_receptance
        case (11)
            ordinate_kind = uff_mobility
        case (12)
            ordinate_kind = uff_accelerance
        case default
            ordinate_kind = uff_other
        end select
    end function ordinate_kind

    !> Record 12: the values of lines first..last - 1 (last is the closing -1), read in the
    !> fixed-width fields of the function's case, into `abscissa` (uneven) and `ordinate`.
    subroutine read_data(path, lines, first, last, n_points, function, error)
        character(len=*), intent(in) :: path
        type(text_line), intent(in) :: lines(:)
        integer, intent(in) :: first, last, n_points
        type(uff_function), intent(inout) :: function
        type(error_type), allocatable, intent(out) :: error

        integer, allocatable :: widths(:), value_line(:)
        real(dp), allocatable :: values(:)
        character(len=:), allocatable :: layout, partial
        integer :: per_point, n_values, n_read, k, next, n_before
        logical :: complex_data

        complex_data = function%ordinate_type >= 5
        per_point = merge(2, 1, complex_data) + merge(0, 1, function%even)
        select case (function%ordinate_type)
        case (2, 5)
            widths = [13, 13, 13, 13, 13, 13]
            layout = '6E13.5'
        case default
            if (function%even) then
                widths = [20, 20, 20, 20]
                layout = '4E20.12'
            else if (complex_data) then
                widths = [13, 20, 20]
                layout = 'E13.5,2E20.12'
            else
                widths = [13, 20, 13, 20]
                layout = '2(E13.5,E20.12)'
            end if
        end select
        ! The lines hold at most size(widths) values each: no more storage than that is needed
        ! before a file that promises more points than it holds is refused.
        n_values = int(min(int(n_points, int64)*per_point, huge(n_points) + 0_int64))
        allocate (values(min(n_values, max(last - first, 0)*size(widths))))
        allocate (value_line(size(values)))
        n_read = 0
        do k = first, last - 1
            if (len_trim(lines(k)%text) == 0) cycle
            if (n_read == n_values) then
                call fatal_error(error, at(path, k, 58, 12)//'expected the -1 line after the ' &
                                 //int_text(n_points)//' points of record 7, found more data: "' &
                                 //trim(lines(k)%text)//'"')
                return
            end if
            next = k + 1
            do while (next < last)
                if (len_trim(lines(next)%text) > 0) exit
                next = next + 1
            end do
            n_before = n_read
            call read_data_line(at(path, k, 58, 12), lines(k)%text, widths, layout, n_values - n_read, &
                                next == last, values(n_read + 1:), n_read, error)
            if (allocated(error)) return
            value_line(n_before + 1:n_read) = k
        end do
        if (n_read < n_values) then
            partial = ''
            if (mod(n_read, per_point) > 0) partial = ' and '//int_text(mod(n_read, per_point))//' of the ' &
                                                      //int_text(per_point)//' values of point ' &
                                                      //int_text(n_read/per_point + 1)
            call fatal_error(error, at(path, last, 58, 12)//'expected '//int_text(n_points)//' points (record 7 ' &
                             //'field 2, '//layout//'), found '//int_text(n_read/per_point)//partial &
                             //' before the -1 line; the dataset is truncated or record 7 is wrong')
            return
        end if
        call store_points(path, values, value_line, per_point, complex_data, function, error)
    end subroutine read_data

    !> Read the values of one data line: all fields of `widths` when at least that many
    !> values remain, else exactly the remaining ones (the last line), nothing after them.
    !> `last_line` says no data line follows, for the message of a file cut short.
    subroutine read_data_line(prefix, line, widths, layout, remaining, last_line, values, n_read, error)
        character(len=*), intent(in) :: prefix, line, layout
        integer, intent(in) :: widths(:), remaining
        logical, intent(in) :: last_line
        real(dp), intent(inout) :: values(:)
        integer, intent(inout) :: n_read
        type(error_type), allocatable, intent(out) :: error

        character(len=:), allocatable :: text
        integer :: field, n_expected, a, b, status, n_here

        n_expected = min(size(widths), remaining)
        n_here = 0
        b = 0
        do field = 1, size(widths)
            a = b + 1
            b = b + widths(field)
            text = trim(adjustl(columns(line, a, b)))
            if (field > n_expected) then
                if (len(text) == 0) cycle
                call fatal_error(error, prefix//'expected no more values after the points of record 7 ' &
                                 //'field 2, found "'//text//'" in '//span(a, b)//' ('//layout//')')
                return
            end if
            if (len(text) == 0) then
                if (last_line .and. len_trim(line) < a) exit
                call fatal_error(error, prefix//'expected '//int_text(n_expected)//' values on this line (' &
                                 //layout//'), found none in '//span(a, b)//': "'//trim(line)//'"')
                return
            end if
            call parse_real(text, values(n_here + 1), status)
            if (status /= 0) then
                call fatal_error(error, prefix//'expected '//number_words(status)//' in '//span(a, b)//' (' &
                                 //layout//'), found '//quoted(line, a, b))
                return
            end if
            n_here = n_here + 1
        end do
        n_read = n_read + n_here
        if (n_here < n_expected) return
        if (len_trim(line) > b) then
            call fatal_error(error, prefix//'expected nothing after column '//int_text(b)//' ('//layout &
                             //'), found "'//trim(adjustl(line(b + 1:)))//'"')
        end if
    end subroutine read_data_line

    !> Split the flat values into abscissa (uneven spacing) and complex ordinate; the
    !> abscissa of uneven data must increase.
    subroutine store_points(path, values, value_line, per_point, complex_data, function, error)
        character(len=*), intent(in) :: path
        real(dp), intent(in) :: values(:)
        integer, intent(in) :: value_line(:), per_point
        logical, intent(in) :: complex_data
        type(uff_function), intent(inout) :: function
        type(error_type), allocatable, intent(out) :: error

        integer :: n, i, at_x

        n = size(values)/per_point
        allocate (function%ordinate(n))
        if (.not. function%even) allocate (function%abscissa(n))
        do i = 1, n
            at_x = (i - 1)*per_point + 1
            if (function%even) then
                if (complex_data) then
                    function%ordinate(i) = cmplx(values(at_x), values(at_x + 1), dp)
                else
                    function%ordinate(i) = cmplx(values(at_x), 0.0_dp, dp)
                end if
                cycle
            end if
            function%abscissa(i) = values(at_x)
            if (complex_data) then
                function%ordinate(i) = cmplx(values(at_x + 1), values(at_x + 2), dp)
            else
                function%ordinate(i) = cmplx(values(at_x + 1), 0.0_dp, dp)
            end if
            if (i > 1) then
                if (.not. function%abscissa(i) > function%abscissa(i - 1)) then
                    call fatal_error(error, at(path, value_line(at_x), 58, 12)//'expected abscissa values that ' &
                                     //'increase (uneven spacing), found '//real_text(function%abscissa(i)) &
                                     //' at point '//int_text(i)//' after '//real_text(function%abscissa(i - 1)))
                    return
                end if
            end if
        end do
    end subroutine store_points

    ! ---- datasets 15 and 2411 ------------------------------------------------------------

    !> Append the nodes of a dataset 15 (one record per node, 4I10,1P3E13.5) or 2411 (4I10,
    !> then 1P3D25.16) to nodes(1:n_nodes).
    subroutine read_nodes(path, lines, set, nodes, n_nodes, error)
        character(len=*), intent(in) :: path
        type(text_line), intent(in) :: lines(:)
        type(dataset_extent), intent(in) :: set
        type(uff_node), allocatable, intent(inout) :: nodes(:)
        integer, intent(inout) :: n_nodes
        type(error_type), allocatable, intent(out) :: error

        type(uff_node) :: node
        character(len=:), allocatable :: line, prefix
        integer :: k, field, record

        record = 1
        do k = set%first + 2, set%last - 1
            if (len_trim(lines(k)%text) == 0) cycle
            line = lines(k)%text
            prefix = at(path, k, set%number, record)
            if (record == 1) then
                node = uff_node(dataset=set%number, line=k)
                call integer_field(prefix, line, 1, 10, 'the node label', .true., node%label, error)
                if (.not. allocated(error)) call integer_field(prefix, line, 11, 20, &
                    'the definition coordinate system', .false., node%definition_system, error)
                if (.not. allocated(error)) call integer_field(prefix, line, 21, 30, &
                    'the displacement coordinate system', .false., node%displacement_system, error)
                if (allocated(error)) return
                call integer_field(prefix, line, 31, 40, 'the color', .false., node%color, error)
                if (allocated(error)) return
            end if
            if (set%number == 15) then
                call read_coordinates(prefix, line, 40, 13, '4I10,1P3E13.5', node, error)
            else if (record == 2) then
                call read_coordinates(prefix, line, 0, 25, '1P3D25.16', node, error)
            else if (len_trim(line) > 40) then
                call fatal_error(error, prefix//'expected nothing after column 40 (4I10), found "' &
                                 //trim(adjustl(line(41:)))//'"')
            end if
            if (allocated(error)) return
            if (set%number == 2411 .and. record == 1) then
                record = 2
                cycle
            end if
            record = 1
            if (n_nodes == size(nodes)) nodes = [nodes, (uff_node(), field=1, max(16, n_nodes))]
            n_nodes = n_nodes + 1
            nodes(n_nodes) = node
        end do
        if (record == 2) then
            call fatal_error(error, at(path, set%last, set%number, 2)//'expected the coordinates of node ' &
                             //int_text(node%label)//' (1P3D25.16), found the -1 line that ends the dataset')
        end if
    end subroutine read_nodes

    !> Three coordinates in fields of `width` columns after column `skip`; nothing after them.
    subroutine read_coordinates(prefix, line, skip, width, layout, node, error)
        character(len=*), intent(in) :: prefix, line, layout
        integer, intent(in) :: skip, width
        type(uff_node), intent(inout) :: node
        type(error_type), allocatable, intent(out) :: error

        character(len=1), parameter :: axes(3) = ['x', 'y', 'z']
        integer :: i, a

        do i = 1, 3
            a = skip + (i - 1)*width + 1
            call real_field(prefix, line, a, a + width - 1, 'the '//axes(i)//' coordinate of node ' &
                            //int_text(node%label), layout, .true., node%position(i), error)
            if (allocated(error)) return
        end do
        if (len_trim(line) > skip + 3*width) then
            call fatal_error(error, prefix//'expected nothing after column '//int_text(skip + 3*width)//' (' &
                             //layout//'), found "'//trim(adjustl(line(skip + 3*width + 1:)))//'"')
        end if
    end subroutine read_coordinates

end module greenconv_io_uff
