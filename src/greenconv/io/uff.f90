!> Reading universal files (ASCII): functions at nodal DOF (dataset 58) and nodes (datasets
!> 15 and 2411), the format measurement systems and FE codes export FRFs, impulse responses
!> and geometry in. Other datasets are skipped and listed.
!>
!> A file is a sequence of datasets, each between two lines holding `-1` right-justified in
!> columns 1-6; the line after the opening one holds the dataset number (columns 1-6; a `b`
!> in column 7 marks a binary dataset, which is refused). Blank lines between datasets are
!> ignored, and so is a UTF-8 byte-order mark at the start of the file.
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
!> definition coordinate system. A label given again with other coordinates is refused,
!> naming both lines.
!>
!> Dataset 164 (units, greenconv_io_uff_units): the functions and coordinates are taken as
!> SI, so a file whose dataset 164 states other factors than 1 for lengths and forces is
!> refused, naming the record and the factors (the dataset stays listed as skipped).
!>
!> Sizes: the point count of record 7 takes no memory before record 12 has held that many
!> points (the values are stored as they are read, at most what the lines hold), so a
!> damaged count is refused at once, not after gigabytes.
!>
!> Every malformed file gets one line with status 2 (`stat_input`), e.g.
!>
!>     frf.uff:12: universal file dataset 58 record 7: expected the number of points > 0
!>     (an integer in columns 11-20), found "0"
!>
!> The reader is split in modules: greenconv_io_uff_types (the types and code names, all
!> re-exported here), greenconv_io_uff_records (lines, datasets and fixed-width fields),
!> greenconv_io_uff_dataset58 and greenconv_io_uff_nodes (the datasets it reads).
module greenconv_io_uff
    use greenconv_core_error, only: error_type, fatal_error
    use greenconv_core_text, only: int_text
    use greenconv_io_uff_types, only: uff_axis, uff_function, uff_node, uff_skipped, uff_file, uff_kind_name, &
                                      uff_data_type_name, uff_function_type_name, uff_other, uff_receptance, &
                                      uff_mobility, uff_accelerance
    use greenconv_io_uff_records, only: text_line, dataset_extent, load_lines, find_datasets
    use greenconv_io_uff_dataset58, only: read_function
    use greenconv_io_uff_nodes, only: read_nodes, check_node_labels
    use greenconv_io_uff_units, only: uff_units, file_units
    implicit none
    private

    public :: uff_axis, uff_function, uff_node, uff_skipped, uff_file
    public :: read_uff, uff_summary, uff_kind_name, uff_data_type_name, uff_function_type_name
    public :: uff_other, uff_receptance, uff_mobility, uff_accelerance

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
        call check_node_labels(path, file%nodes, error)
        if (.not. allocated(error)) call check_si(path, lines, sets, error)
    end subroutine read_uff

    !> Refuse a file whose dataset 164 states other units than SI for lengths and forces: its
    !> functions and coordinates are taken as SI, never converted here.
    subroutine check_si(path, lines, sets, error)
        character(len=*), intent(in) :: path
        type(text_line), intent(in) :: lines(:)
        type(dataset_extent), intent(in) :: sets(:)
        type(error_type), allocatable, intent(out) :: error

        type(uff_units) :: units
        character(len=:), allocatable :: stated

        call file_units(path, lines, sets, units, error)
        if (allocated(error) .or. units%is_si()) return
        call units%describe(stated)
        call fatal_error(error, path//':'//int_text(units%line + 3)//': universal file dataset 164 record 2: ' &
                         //'expected SI units (length and force factors 1: metres and newtons) for the functions ' &
                         //'of datasets 58 and their nodes, found '//stated//': export the file in SI units')
    end subroutine check_si

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

end module greenconv_io_uff
