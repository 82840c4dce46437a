!> Dataset 55 of universal files (data at nodes) for normal modes, and a file of modes: its
!> nodes (datasets 15 or 2411, greenconv_io_uff_nodes) and one dataset 55 or 2414
!> (greenconv_io_uff_dataset2414) per mode.
!>
!> Dataset 55, as this reader takes it (analysis type 2, normal mode):
!>
!> | record | format | holds                                                                |
!> |--------|--------|----------------------------------------------------------------------|
!> | 1-5    | 80A1   | ID lines (not read)                                                  |
!> | 6      | 6I10   | model type, analysis type (2), data characteristic (2: 3 DOF         |
!> |        |        | translation, 3: 6 DOF translation and rotation), specific data type, |
!> |        |        | data type (2 real single, 4 real double), values per node NDV (3, 6) |
!> | 7      | 8I10   | number of integers NINT (>= 2), number of reals NREAL (1 to 6), then |
!> |        |        | NINT integers: load case, mode number                                |
!> | 8      | 6E13.5 | NREAL reals: frequency [Hz], modal mass, viscous damping ratio,      |
!> |        |        | hysteretic damping ratio (missing ones are 0)                        |
!> | 9      | I10    | node label                                                           |
!> | 10     | 6E13.5 | NDV values at the node (data type 4: 4E20.12, on as many lines as    |
!> |        |        | needed); X, Y, Z translations first                                  |
!>
!> Records 9 and 10 repeat for every node. The lines of record 10 are counted from NDV and the
!> data type before anything is allocated, so the number of nodes is bounded by the lines the
!> file holds. Every malformed dataset gets one line with status 2 naming the file, the line,
!> the dataset and record, the field, what was expected and what was found.
module greenconv_io_uff_dataset55
    use greenconv_core_kinds, only: dp
    use greenconv_core_error, only: error_type, fatal_error
    use greenconv_core_text, only: int_text
    use greenconv_io_uff_types, only: uff_node
    use greenconv_core_sorting, only: sort_order
    use greenconv_io_uff_records, only: text_line, dataset_extent, load_lines, find_datasets, record_prefix, &
                                        real_field, locate_label
    use greenconv_io_uff_units, only: uff_units, file_units
    use greenconv_io_uff_nodes, only: read_nodes, check_node_labels
    use greenconv_io_uff_dataset2414, only: uff_mode_shape, read_analysis_mode, check_mode_values, read_node_records, &
                                            integer_fields, check_mode_codes
    implicit none
    private

    public :: uff_mode_shape, read_mode_shape, read_modes_file

contains

    !> Read one dataset 55 of a normal mode, keeping component |direction| (1 x, 2 y, 3 z) of
    !> each node's values times the sign of `direction`.
    subroutine read_mode_shape(path, lines, set, direction, mode, error)
        !> File the lines come from (for messages).
        character(len=*), intent(in) :: path
        !> The file's lines.
        type(text_line), intent(in) :: lines(:)
        !> Where the dataset 55 lies in them.
        type(dataset_extent), intent(in) :: set
        !> Direction of the shape kept: +-1, +-2, +-3 for +-X, +-Y, +-Z.
        integer, intent(in) :: direction
        !> The mode read.
        type(uff_mode_shape), intent(out) :: mode
        !> Set (status 2) for a malformed dataset or one that is not a real normal mode.
        type(error_type), allocatable, intent(out) :: error

        integer, parameter :: record_line(8) = [2, 3, 4, 5, 6, 7, 8, 9]
        integer :: numbers(6), n_integers, n_reals, per_line, width, i, line, values
        real(dp) :: reals(6)

        mode%line = set%first
        if (set%last - set%first < 12) then
            call fatal_error(error, path//':'//int_text(set%last)//': universal file dataset 55: expected records ' &
                             //'1 to 8 and a node (at least 10 lines), found '//int_text(set%last - set%first - 2) &
                             //' lines before the -1 that ends the dataset')
            return
        end if
        line = set%first + record_line(6)
        call read_integers(6, 6, numbers, error)
        if (.not. allocated(error)) call check_mode_codes(record_prefix(path, line, 55, 6), numbers, values, error)
        if (allocated(error)) return
        mode%data_characteristic = numbers(3)
        width = merge(13, 20, numbers(5) == 2)
        per_line = merge(6, 4, numbers(5) == 2)
        line = set%first + record_line(7)
        call read_integers(7, 2, numbers, error)
        if (allocated(error)) return
        n_integers = numbers(1)
        n_reals = numbers(2)
        if (n_integers < 2 .or. n_integers > 6) then
            call fatal_error(error, record_prefix(path, line, 55, 7)//'expected the number of integer values from 2 ' &
                             //'to 6 (columns 1-10), found '//int_text(n_integers))
            return
        end if
        if (n_reals < 1 .or. n_reals > 6) then
            call fatal_error(error, record_prefix(path, line, 55, 7)//'expected the number of real values from 1 ' &
                             //'to 6 (columns 11-20), found '//int_text(n_reals))
            return
        end if
        call read_integers(7, 2 + n_integers, numbers, error)
        if (allocated(error)) return
        mode%load_case = numbers(3)
        mode%mode_number = numbers(4)
        line = set%first + record_line(8)
        reals = 0.0_dp
        do i = 1, n_reals
            call real_field(record_prefix(path, line, 55, 8), lines(line)%text, 13*i - 12, 13*i, &
                            'real value '//int_text(i), '6E13.5', .true., reals(i), error)
            if (allocated(error)) return
        end do
        mode%frequency = reals(1)
        mode%modal_mass = reals(2)
        mode%damping_ratio = reals(3)
        call check_mode_values(record_prefix(path, line, 55, 8), lines(line)%text, [1, 14, 27], mode, error)
        if (allocated(error)) return
        ! records 9 and 10: one label line and the value lines of every node
        call read_node_records(path, lines, set, set%first + 10, 9, values, per_line, width, &
                               trim(merge('6E13.5 ', '4E20.12', width == 13)), direction, mode, error)

    contains

        !> Fields 1..n of an I10 record.
        subroutine read_integers(record, n, found, fail)
            !> Record number and number of fields to read.
            integer, intent(in) :: record, n
            !> The fields read, found(1:n).
            integer, intent(inout) :: found(:)
            !> Set (status 2) for a field that holds no integer.
            type(error_type), allocatable, intent(out) :: fail

            call integer_fields(record_prefix(path, line, 55, record), lines(line)%text, n, found, fail)
        end subroutine read_integers
    end subroutine read_mode_shape

    !> Read a file of normal modes: its nodes (datasets 15, 2411) and every dataset 55 or 2414,
    !> each mode at the same nodes, every node defined and given once; other datasets are
    !> ignored. Returned in SI whatever units its dataset 164 states (greenconv_io_uff_units):
    !> coordinates divided by the length factor, and phi_i*phi_j/m_k [1/kg] by the mass factor
    !> (the modal mass multiplied by it, or, where the file gives none for mass-normalised
    !> shapes, the shapes divided by its square root).
    subroutine read_modes_file(path, direction, nodes, modes, error)
        !> File to read.
        character(len=*), intent(in) :: path
        !> Direction of the shapes kept: +-1, +-2, +-3 for +-X, +-Y, +-Z.
        integer, intent(in) :: direction
        !> The nodes of the modes, in the order of the first dataset 55's records 9; x, y, z [m].
        type(uff_node), allocatable, intent(out) :: nodes(:)
        !> The modes, in file order (modal masses [kg] and shapes in SI).
        type(uff_mode_shape), allocatable, intent(out) :: modes(:)
        !> Set (status 2) for an unreadable or malformed file, no mode, a mode at other nodes
        !> than the first, a node without coordinates or given twice, a malformed dataset 164.
        type(error_type), allocatable, intent(out) :: error

        type(text_line), allocatable :: lines(:)
        type(dataset_extent), allocatable :: sets(:)
        type(uff_node), allocatable :: defined(:)
        type(uff_units) :: units
        real(dp), allocatable :: sorted(:)
        integer, allocatable :: order(:)
        character(len=40) :: where
        integer :: i, k, j, n_defined, n_modes

        call load_lines(path, lines, error)
        if (allocated(error)) return
        call find_datasets(path, lines, sets, error)
        if (allocated(error)) return
        allocate (defined(0), modes(count(sets%number == 55 .or. sets%number == 2414)))
        n_defined = 0
        n_modes = 0
        do i = 1, size(sets)
            select case (sets(i)%number)
            case (15, 2411)
                call read_nodes(path, lines, sets(i), defined, n_defined, error)
            case (55)
                n_modes = n_modes + 1
                call read_mode_shape(path, lines, sets(i), direction, modes(n_modes), error)
            case (2414)
                n_modes = n_modes + 1
                call read_analysis_mode(path, lines, sets(i), direction, modes(n_modes), error)
            end select
            if (allocated(error)) return
        end do
        defined = defined(1:n_defined)
        call check_node_labels(path, defined, error)
        if (allocated(error)) return
        call file_units(path, lines, sets, units, error)
        if (allocated(error)) return
        deallocate (lines)
        if (n_modes == 0) then
            call fatal_error(error, path//':1: universal file: expected normal modes (datasets 55 or 2414 of analysis ' &
                             //'type 2), found none')
            return
        end if
        do k = 2, n_modes
            where = ''
            if (size(modes(k)%node) == size(modes(1)%node)) then
                if (all(modes(k)%node == modes(1)%node)) cycle
                j = findloc(modes(k)%node /= modes(1)%node, .true., 1)
                where = ', node '//int_text(modes(k)%node(j))//' in place '//int_text(j)
            end if
            call fatal_error(error, path//':'//int_text(modes(k)%line)//': universal file dataset ' &
                             //int_text(modes(k)%dataset)//': expected mode ' &
                             //int_text(modes(k)%mode_number)//' at the '//int_text(size(modes(1)%node)) &
                             //' nodes of the dataset at line '//int_text(modes(1)%line)//' in the same order, found ' &
                             //int_text(size(modes(k)%node))//' nodes'//trim(where))
            return
        end do
        ! each node's coordinates by bisection in the defined labels, sorted: O(n log n)
        order = defined%label
        order = sort_order(order)
        sorted = real(defined(order)%label, dp)
        allocate (nodes(size(modes(1)%node)))
        do k = 1, size(nodes)
            j = locate_label(sorted, modes(1)%node(k))
            if (j == 0) then
                call fatal_error(error, path//':'//int_text(modes(1)%line)//': universal file dataset ' &
                                 //int_text(modes(1)%dataset)//': expected ' &
                                 //'node '//int_text(modes(1)%node(k))//' in a dataset 15 or 2411, found no ' &
                                 //'coordinates for it')
                return
            end if
            nodes(k) = defined(order(j))
        end do
        if (units%is_si()) return
        ! to SI: lengths / length factor; phi_i*phi_j/m_k [1/mass] * force factor / length factor
        do k = 1, size(nodes)
            nodes(k)%position = nodes(k)%position/units%length_factor
        end do
        do k = 1, n_modes
            if (modes(k)%modal_mass > 0.0_dp) then
                modes(k)%modal_mass = modes(k)%modal_mass*units%mass_factor()
            else
                modes(k)%value = modes(k)%value/sqrt(units%mass_factor())
            end if
        end do
    end subroutine read_modes_file

end module greenconv_io_uff_dataset55
