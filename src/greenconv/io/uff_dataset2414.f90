!> Dataset 2414 of universal files (analysis data) for normal modes, as FE codes export them,
!> and what it shares with dataset 55 (greenconv_io_uff_dataset55): the mode read from either,
!> the checks of its frequency, modal mass and damping ratio, and the node records.
!>
!> Dataset 2414, as this reader takes it (data at nodes of a real normal mode):
!>
!> | record | format | holds                                                                |
!> |--------|--------|----------------------------------------------------------------------|
!> | 1      | I10    | analysis dataset label (not read)                                    |
!> | 2      | 40A2   | analysis dataset name (not read)                                     |
!> | 3      | I10    | dataset location (1: data at nodes)                                  |
!> | 4-8    | 40A2   | ID lines (not read)                                                  |
!> | 9      | 6I10   | model type, analysis type (2: normal mode), data characteristic (2:  |
!> |        |        | 3 DOF translation, 3: 6 DOF translation and rotation), result type   |
!> |        |        | (8 displacement, 95/96 unknown 3/6 DOF vector), data type (2 real    |
!> |        |        | single, 4 real double), values per node NVALDC (3, 6)                |
!> | 10     | 8I10   | design set, iteration, solution set, boundary condition, load set,   |
!> |        |        | mode number, time step, frequency number                             |
!> | 11     | 8I10   | creation option, number retained (not read)                          |
!> | 12     | 6E13.5 | time, frequency [Hz], eigenvalue, modal mass, viscous damping ratio, |
!> |        |        | hysteretic damping ratio                                             |
!> | 13     | 6E13.5 | complex eigenvalue, modal A and B (not read)                         |
!> | 14     | I10    | node label                                                           |
!> | 15     | 6E13.5 | NVALDC values at the node, six to a line; X, Y, Z translations first |
!>
!> Records 14 and 15 repeat for every node. Record 15 is read in fields of 13 columns for both
!> data types, as the specification writes it (a double-precision file in wider fields is
!> refused at its first value, naming the columns). Every malformed dataset gets one line with
!> status 2 naming the file, the line, the dataset and record, the field, what was expected and
!> what was found.
module greenconv_io_uff_dataset2414
    use greenconv_core_kinds, only: dp
    use greenconv_core_error, only: error_type, fatal_error
    use greenconv_core_text, only: int_text, sci_text
    use greenconv_io_uff_records, only: text_line, dataset_extent, record_prefix, integer_field, real_field, columns, &
                                        repeated_labels, locate_label, quick_integer, quick_real
    implicit none
    private

    public :: uff_mode_shape, read_analysis_mode, check_mode_values, read_node_records, integer_fields, check_mode_codes

    !> One normal mode of a dataset 55 or 2414: its number, frequency, modal mass, damping ratio
    !> and one component of its shape at its nodes.
    type :: uff_mode_shape
        !> Line of the file where the dataset starts (its opening `-1`), and its number (55, 2414),
        !> for messages.
        integer :: line = 0, dataset = 55
        !> Load case (load set) and mode number.
        integer :: load_case = 0, mode_number = 0
        !> Natural frequency [Hz].
        real(dp) :: frequency = 0.0_dp
        !> Modal mass (0 when the file gives none) [kg, with the shapes' units].
        real(dp) :: modal_mass = 0.0_dp
        !> Viscous damping ratio (0 when the file gives none).
        real(dp) :: damping_ratio = 0.0_dp
        !> Data characteristic (2: 3 DOF per node, 3: 6 DOF).
        integer :: data_characteristic = 0
        !> Label of every node, in file order.
        integer, allocatable :: node(:)
        !> The component in the chosen direction at every node, times the direction's sign.
        real(dp), allocatable :: value(:)
    end type uff_mode_shape

    !> Line offsets of records 3, 9, 10 and 12 and of the first record 14 after the opening -1.
    integer, parameter :: at_location = 4, at_codes = 10, at_integers = 11, at_reals = 13, at_nodes = 15

contains

    !> Read one dataset 2414 of a real normal mode at nodes, keeping component |direction|
    !> (1 x, 2 y, 3 z) of each node's values times the sign of `direction`.
    subroutine read_analysis_mode(path, lines, set, direction, mode, error)
        !> File the lines come from (for messages).
        character(len=*), intent(in) :: path
        !> The file's lines.
        type(text_line), intent(in) :: lines(:)
        !> Where the dataset 2414 lies in them.
        type(dataset_extent), intent(in) :: set
        !> Direction of the shape kept: +-1, +-2, +-3 for +-X, +-Y, +-Z.
        integer, intent(in) :: direction
        !> The mode read.
        type(uff_mode_shape), intent(out) :: mode
        !> Set (status 2) for a malformed dataset or one that is not a real normal mode at nodes.
        type(error_type), allocatable, intent(out) :: error

        character(len=:), allocatable :: prefix
        integer :: codes(6), location, values, line

        mode%line = set%first
        mode%dataset = 2414
        if (set%last - set%first < at_nodes + 2) then
            call fatal_error(error, path//':'//int_text(set%last)//': universal file dataset 2414: expected records ' &
                             //'1 to 13 and a node (at least 15 lines), found '//int_text(set%last - set%first - 2) &
                             //' lines before the -1 that ends the dataset')
            return
        end if
        line = set%first + at_location
        call integer_field(record_prefix(path, line, 2414, 3), lines(line)%text, 1, 10, 'the dataset location', &
                           .true., location, error)
        if (allocated(error)) return
        if (location /= 1) then
            call fatal_error(error, record_prefix(path, line, 2414, 3)//'expected the dataset location 1 (data at ' &
                             //'nodes; columns 1-10), found '//int_text(location))
            return
        end if
        line = set%first + at_codes
        prefix = record_prefix(path, line, 2414, 9)
        call integer_fields(prefix, lines(line)%text, 6, codes, error)
        if (.not. allocated(error)) call check_mode_codes(prefix, codes, values, error)
        if (.not. allocated(error)) call check_code_field(prefix, 4, codes(4), [8, 95, 96], 'the result type', &
                                                          'of a displacement (8, or 95, 96: unknown 3 or 6 DOF ' &
                                                          //'vector)', error)
        if (allocated(error)) return
        mode%data_characteristic = codes(3)
        line = set%first + at_integers
        call integer_fields(record_prefix(path, line, 2414, 10), lines(line)%text, 6, codes, error)
        if (allocated(error)) return
        mode%load_case = codes(5)
        mode%mode_number = codes(6)
        line = set%first + at_reals
        call real_field(record_prefix(path, line, 2414, 12), lines(line)%text, 14, 26, 'the frequency', '6E13.5', &
                        .true., mode%frequency, error)
        if (.not. allocated(error)) call real_field(record_prefix(path, line, 2414, 12), lines(line)%text, 40, 52, &
                                                    'the modal mass', '6E13.5', .false., mode%modal_mass, error)
        if (.not. allocated(error)) call real_field(record_prefix(path, line, 2414, 12), lines(line)%text, 53, 65, &
                                                    'the viscous damping ratio', '6E13.5', .false., &
                                                    mode%damping_ratio, error)
        if (.not. allocated(error)) call check_mode_values(record_prefix(path, line, 2414, 12), lines(line)%text, &
                                                           [14, 40, 53], mode, error)
        if (allocated(error)) return
        call read_node_records(path, lines, set, set%first + at_nodes, 14, values, 6, 13, '6E13.5', direction, mode, &
                               error)

    end subroutine read_analysis_mode

    !> Fields 1..n of a record of I10 fields, each required.
    subroutine integer_fields(prefix, text, n, found, error)
        !> Start of the message (`record_prefix`).
        character(len=*), intent(in) :: prefix
        !> The record's line.
        character(len=*), intent(in) :: text
        !> Number of fields to read.
        integer, intent(in) :: n
        !> The fields read, found(1:n).
        integer, intent(inout) :: found(:)
        !> Set (status 2) for a field that holds no integer.
        type(error_type), allocatable, intent(out) :: error

        integer :: j

        do j = 1, n
            call integer_field(prefix, text, 10*j - 9, 10*j, 'field '//int_text(j), .true., found(j), error)
            if (allocated(error)) return
        end do
    end subroutine integer_fields

    !> An error unless the codes of a record 6 (dataset 55) or 9 (2414) are those of a real
    !> normal mode: analysis type 2 (field 2), data characteristic 2 or 3 (field 3), data type
    !> 2 or 4 (field 5), and the values per node (field 6) the data characteristic implies.
    subroutine check_mode_codes(prefix, codes, values, error)
        !> Start of the message (`record_prefix`).
        character(len=*), intent(in) :: prefix
        !> Fields 1 to 6 of the record.
        integer, intent(in) :: codes(6)
        !> Values per node: 3 for data characteristic 2, 6 for 3.
        integer, intent(out) :: values
        !> Set (status 2) for a code out of those.
        type(error_type), allocatable, intent(out) :: error

        values = merge(3, 6, codes(3) == 2)
        call check_code_field(prefix, 2, codes(2), [2], 'the analysis type', 'of a normal mode', error)
        if (.not. allocated(error)) call check_code_field(prefix, 3, codes(3), [2, 3], 'the data characteristic', &
                                                          'of 3 DOF (2) or 6 DOF (3) per node', error)
        if (.not. allocated(error)) call check_code_field(prefix, 5, codes(5), [2, 4], 'the data type', &
                                                          'real single (2) or real double (4); complex modes are ' &
                                                          //'not read', error)
        if (.not. allocated(error)) call check_code_field(prefix, 6, codes(6), [values], &
                                                          'the number of values per node', 'for data characteristic ' &
                                                          //int_text(codes(3)), error)
    end subroutine check_mode_codes

    !> An error unless the I10 field `field` of a record holds one of `allowed`.
    subroutine check_code_field(prefix, field, value, allowed, what, meaning, error)
        !> Start of the message (`record_prefix`).
        character(len=*), intent(in) :: prefix
        !> Field number, its value and the values allowed.
        integer, intent(in) :: field, value, allowed(:)
        !> What the field holds and what the allowed values mean, for the message.
        character(len=*), intent(in) :: what, meaning
        !> Set (status 2) when the value is not allowed.
        type(error_type), allocatable, intent(out) :: error

        if (any(allowed == value)) return
        call fatal_error(error, prefix//'expected '//what//' '//meaning//' (columns '//int_text(10*field - 9)//'-' &
                         //int_text(10*field)//'), found '//int_text(value))
    end subroutine check_code_field

    !> An error unless a mode's frequency is > 0, its modal mass >= 0 and its viscous damping
    !> ratio in [0, 1); the message quotes the field of 13 columns it came from.
    subroutine check_mode_values(prefix, text, first, mode, error)
        !> Start of the message (`record_prefix`).
        character(len=*), intent(in) :: prefix
        !> The record's line.
        character(len=*), intent(in) :: text
        !> First column of the frequency, the modal mass and the damping ratio.
        integer, intent(in) :: first(3)
        !> The mode, its three values read.
        type(uff_mode_shape), intent(in) :: mode
        !> Set (status 2) for a value out of its range.
        type(error_type), allocatable, intent(out) :: error

        character(len=80) :: expected
        integer :: bad

        bad = 0
        if (.not. (mode%frequency > 0.0_dp)) then
            bad = 1
            expected = 'the natural frequency > 0 Hz'
        else if (mode%modal_mass < 0.0_dp) then
            bad = 2
            expected = 'the modal mass >= 0'
        else if (mode%damping_ratio < 0.0_dp .or. mode%damping_ratio >= 1.0_dp) then
            bad = 3
            expected = 'the viscous damping ratio in [0, 1)'
        end if
        if (bad == 0) return
        call fatal_error(error, prefix//'expected '//trim(expected)//' (columns '//int_text(first(bad))//'-' &
                         //int_text(first(bad) + 12)//trim(merge('; 0: unit modal mass)', ')                    ', &
                                                                 bad == 2))//', found ' &
                         //trim(adjustl(columns(text, first(bad), first(bad) + 12))))
    end subroutine check_mode_values

    !> The node records of a dataset 55 (records 9 and 10) or 2414 (14 and 15) from line `start`
    !> to the end of the dataset: a label line (I10), then `values` numbers in fields of `width`
    !> columns, `per_line` to a line; component |direction| of each node kept, times its sign.
    !> The number of nodes follows from the lines, so nothing is allocated beyond what they hold.
    subroutine read_node_records(path, lines, set, start, label_record, values, per_line, width, layout, &
                                 direction, mode, error)
        !> File the lines come from (for messages).
        character(len=*), intent(in) :: path
        !> The file's lines.
        type(text_line), intent(in) :: lines(:)
        !> Where the dataset lies in them.
        type(dataset_extent), intent(in) :: set
        !> Line of the first node's label.
        integer, intent(in) :: start
        !> Record number of the label (its values are the next record).
        integer, intent(in) :: label_record
        !> Values per node, values per line and the width of a field.
        integer, intent(in) :: values, per_line, width
        !> The values' format, for messages.
        character(len=*), intent(in) :: layout
        !> Direction of the shape kept: +-1, +-2, +-3 for +-X, +-Y, +-Z.
        integer, intent(in) :: direction
        !> The mode whose nodes and values are read.
        type(uff_mode_shape), intent(inout) :: mode
        !> Set (status 2) for a malformed record, a dataset that ends inside a node, or a node
        !> given twice (naming both lines, and the first value that differs).
        type(error_type), allocatable, intent(out) :: error

        real(dp) :: component(6), earlier(6)
        real(dp), allocatable :: repeated(:)
        integer, allocatable :: first(:)
        integer :: lines_per_node, n_nodes, k, i, line, n_lines, at

        lines_per_node = 1 + (values + per_line - 1)/per_line
        n_lines = set%last - start
        n_nodes = n_lines/lines_per_node
        if (n_nodes < 1 .or. mod(n_lines, lines_per_node) /= 0) then
            call fatal_error(error, record_prefix(path, set%last, set%number, label_record + mod(n_lines, &
                             lines_per_node))//'expected records '//int_text(label_record)//' and ' &
                             //int_text(label_record + 1)//' ('//int_text(lines_per_node)//' lines) for every node, ' &
                             //'found '//int_text(n_lines)//' lines after record '//int_text(label_record - 1))
            return
        end if
        allocate (mode%node(n_nodes), mode%value(n_nodes))
        do k = 1, n_nodes
            call read_node(k, component, error)
            if (allocated(error)) return
            mode%value(k) = sign(1.0_dp, real(direction, dp))*component(abs(direction))
        end do
        ! a node given twice would be two contact points on one spot: refused, naming both
        repeated = repeated_labels(mode%node)
        if (size(repeated) == 0) return
        allocate (first(size(repeated)))
        first(:) = 0
        do k = 1, n_nodes
            at = locate_label(repeated, mode%node(k))
            if (at == 0) cycle
            if (first(at) == 0) then
                first(at) = k
                cycle
            end if
            call read_node(first(at), earlier, error)
            if (.not. allocated(error)) call read_node(k, component, error)
            if (allocated(error)) return
            line = start + (k - 1)*lines_per_node
            i = findloc(component(:values) /= earlier(:values), .true., 1)
            if (i > 0) then
                call fatal_error(error, record_prefix(path, line, set%number, label_record)//'node ' &
                                 //int_text(mode%node(k))//' is given again with other values (value '//int_text(i) &
                                 //' = '//sci_text(component(i))//') than at line ' &
                                 //int_text(start + (first(at) - 1)*lines_per_node)//' (value '//int_text(i)//' = ' &
                                 //sci_text(earlier(i))//'); give each node once')
            else
                call fatal_error(error, record_prefix(path, line, set%number, label_record)//'node ' &
                                 //int_text(mode%node(k))//' is given again, as at line ' &
                                 //int_text(start + (first(at) - 1)*lines_per_node)//': give each node once ' &
                                 //'(each node of a mode is one contact point)')
            end if
            return
        end do

    contains

        !> The label and the values of node k (records label_record and label_record + 1).
        subroutine read_node(k, found, fail)
            !> Index of the node in the dataset.
            integer, intent(in) :: k
            !> Its values, found(1:values).
            real(dp), intent(out) :: found(:)
            !> Set (status 2) for a malformed record.
            type(error_type), allocatable, intent(out) :: fail

            integer :: i, line, at, first
            logical :: ok

            found(:) = 0.0_dp
            line = start + (k - 1)*lines_per_node
            call quick_integer(lines(line)%text, 1, 10, mode%node(k), ok)
            if (.not. ok) call integer_field(record_prefix(path, line, set%number, label_record), lines(line)%text, &
                                             1, 10, 'the node label', .true., mode%node(k), fail)
            if (allocated(fail)) return
            do i = 1, values
                at = line + 1 + (i - 1)/per_line
                first = width*mod(i - 1, per_line) + 1
                call quick_real(lines(at)%text, first, first + width - 1, found(i), ok)
                if (ok) cycle
                call real_field(record_prefix(path, at, set%number, label_record + 1), lines(at)%text, first, &
                                first + width - 1, 'value '//int_text(i)//' of node '//int_text(mode%node(k)), &
                                layout, .true., found(i), fail)
                return
            end do
        end subroutine read_node
    end subroutine read_node_records

end module greenconv_io_uff_dataset2414
