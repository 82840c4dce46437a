!> Writing universal files (ASCII): a header (dataset 151), nodes (dataset 15 or 2411) and
!> functions at nodal DOF (dataset 58), in the record layouts that greenconv_io_uff reads (see
!> its description for the table of records), so that `read_uff` gives back what was written
!> to the precision of the fields.
!>
!> Each function is one `uff_function` of greenconv_io_uff, the type the reader returns; the
!> fields written are the ID lines, record 6 (function type, identification, version, load
!> case, response and reference entity, node and direction), record 7 (ordinate type, number
!> of points, spacing, abscissa minimum and increment, z value), records 8 to 11 (data type,
!> unit exponents, label and units of each axis) and record 12, the data, in the layout of the
!> ordinate type and spacing:
!>
!> | ordinate        | even spacing                | uneven spacing                   |
!> |-----------------|-----------------------------|----------------------------------|
!> | 2 real single   | 6E13.5: y                   | 6E13.5: x, y pairs               |
!> | 4 real double   | 4E20.12: y                  | 2(E13.5,E20.12): x, y pairs      |
!> | 5 complex single| 6E13.5: Re, Im              | 6E13.5: x, Re, Im                |
!> | 6 complex double| 4E20.12: Re, Im             | E13.5,2E20.12: x, Re, Im         |
!>
!> E13.5 fields are written as ES13.5 (six significant digits, relative precision 5e-6),
!> E20.12 as ES20.12 (thirteen, 5e-13); record 7's abscissa minimum and increment are E13.5
!> fields, so an even grid is known to six digits. Nodes: dataset 15 one record per node,
!> 4I10,1P3E13.5; dataset 2411 two records, 4I10 and 1P3D25.16 (seventeen digits). A value
!> whose decimal exponent needs three digits is written with one digit less (ES13.4E3,
!> ES20.11E3, ES25.15E3) so that every field keeps its exponent letter: Fortran's E13.5 would
!> write 1.23457-100, which Fortran reads back but readers in other languages (pyuff) do not.
!>
!> `receptance_function` and `impulse_function` fill a `uff_function` for the two cases
!> greenconv writes: a receptance G_ij(f) [m/N] (function type 4, complex double, even in
!> frequency) and a sampled impulse response g_ij(t) [m/(N*s)] (function type 1, real
!> double, even in time), each with displacement over excitation force in records 9 and 10.
!>
!> A function or node that cannot be written as the format says (a field too wide, a
!> non-finite value, a grid that is not even when it says so, ...) gets one message naming
!> the dataset and what to change, with status 2; nothing is left on disk then.
module greenconv_io_uff_write
    use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
    use greenconv_core_kinds, only: dp
    use greenconv_core_error, only: error_type, fatal_error
    use greenconv_core_text, only: int_text
    use greenconv_io_uff, only: uff_function, uff_node, uff_axis
    implicit none
    private

    public :: uff_header, write_uff, receptance_function, impulse_function

    !> The header of a file, written as dataset 151. Dates are the caller's, so that a file
    !> written twice from the same data is the same byte for byte.
    type :: uff_header
        !> Model name (record 1, 80A1).
        character(len=80) :: model = ''
        !> Description of the model (record 2, 80A1): how the file was made.
        character(len=80) :: description = ''
        !> Program that created the data (record 3, 80A1).
        character(len=80) :: application = 'greenconv'
        !> Date the data was created (record 4, 10A1), e.g. `01-Jan-26`.
        character(len=10) :: date = ''
        !> Program that wrote the file (record 6, 80A1).
        character(len=80) :: program = 'greenconv (greenconv_io_uff_write)'
    end type uff_header

contains

    !> Write a universal file: the header (dataset 151) when given, the nodes (one dataset 15
    !> or 2411) when there are any, then one dataset 58 per function, in order.
    subroutine write_uff(path, functions, nodes, error, header, node_dataset)
        !> File to write (replaced if it exists).
        character(len=*), intent(in) :: path
        !> Functions, one dataset 58 each.
        type(uff_function), intent(in) :: functions(:)
        !> Nodes (may be empty).
        type(uff_node), intent(in) :: nodes(:)
        !> Set (status 2) when a function or node cannot be written or the file cannot be
        !> opened or written; the file is deleted then.
        type(error_type), allocatable, intent(out) :: error
        !> Header written as dataset 151; none when absent.
        type(uff_header), intent(in), optional :: header
        !> 15 (default: single-precision coordinates) or 2411 (double precision).
        integer, intent(in), optional :: node_dataset

        character(len=512) :: message
        integer :: unit, stat, i, nodes_as

        nodes_as = 15
        if (present(node_dataset)) nodes_as = node_dataset
        if (nodes_as /= 15 .and. nodes_as /= 2411) then
            call fatal_error(error, path//': universal file: nodes are written as dataset 15 or 2411, not ' &
                             //int_text(nodes_as))
            return
        end if
        call check_nodes(path, nodes, error)
        if (allocated(error)) return
        do i = 1, size(functions)
            call check_function(path//': universal file: function '//int_text(i)//' (dataset 58): ', &
                                functions(i), error)
            if (allocated(error)) return
        end do
        open (newunit=unit, file=path, status='replace', action='write', iostat=stat, iomsg=message)
        if (stat /= 0) then
            call fatal_error(error, path//': cannot write the universal file: '//trim(message) &
                             //'; check that the directory exists and is writable')
            return
        end if
        if (present(header)) call write_header(unit, header, stat)
        if (stat == 0 .and. size(nodes) > 0) call write_nodes(unit, nodes, nodes_as, stat)
        do i = 1, size(functions)
            if (stat /= 0) exit
            call write_function(unit, functions(i), stat)
        end do
        if (stat /= 0) then
            close (unit, status='delete')
            call fatal_error(error, path//': writing the universal file failed (disk full?); nothing was kept')
            return
        end if
        close (unit, iostat=stat)
        if (stat /= 0) call fatal_error(error, path//': closing the universal file failed')
    end subroutine write_uff

    !> A receptance G_ij(f) [m/N] as a dataset 58: function type 4, complex double, even
    !> spacing from f_0 by df [Hz]; displacement [m] at (response node, direction) over
    !> excitation force [N] at (reference node, direction).
    pure function receptance_function(response, reference, f_0, df, values, description) result(function)
        !> Response node label and direction (+-1..3 for X, Y, Z translation).
        integer, intent(in) :: response(2)
        !> Reference node label and direction.
        integer, intent(in) :: reference(2)
        !> First frequency [Hz].
        real(dp), intent(in) :: f_0
        !> Frequency increment [Hz], > 0.
        real(dp), intent(in) :: df
        !> G_ij at f_0 + (k - 1)*df [m/N].
        complex(dp), intent(in) :: values(:)
        !> ID line 1 (at most 80 characters).
        character(len=*), intent(in) :: description
        type(uff_function) :: function

        call fill_dof(function, 4, response, reference, f_0, df, size(values), description)
        function%ordinate_type = 6
        function%abscissa_axis = uff_axis(18, 0, 0, 0, 'Frequency', 'Hz')
        function%ordinate = values
    end function receptance_function

    !> A sampled impulse response g_ij(t) [m/(N*s)] as a dataset 58: function type 1 (time
    !> response), real double, even spacing from t_0 by dt [s]; displacement [m] at the
    !> response over excitation force [N] at the reference (per second of impulse).
    pure function impulse_function(response, reference, t_0, dt, values, description) result(function)
        !> Response node label and direction.
        integer, intent(in) :: response(2)
        !> Reference node label and direction.
        integer, intent(in) :: reference(2)
        !> First time [s].
        real(dp), intent(in) :: t_0
        !> Time step [s], > 0.
        real(dp), intent(in) :: dt
        !> g_ij at t_0 + (k - 1)*dt [m/(N*s)].
        real(dp), intent(in) :: values(:)
        !> ID line 1 (at most 80 characters).
        character(len=*), intent(in) :: description
        type(uff_function) :: function

        call fill_dof(function, 1, response, reference, t_0, dt, size(values), description)
        function%ordinate_type = 4
        function%abscissa_axis = uff_axis(17, 0, 0, 0, 'Time', 's')
        function%ordinate = cmplx(values, 0.0_dp, kind=dp)
    end function impulse_function

    !> The fields `receptance_function` and `impulse_function` share.
    pure subroutine fill_dof(function, function_type, response, reference, first, step, n, description)
        type(uff_function), intent(inout) :: function
        integer, intent(in) :: function_type, response(2), reference(2), n
        real(dp), intent(in) :: first, step
        character(len=*), intent(in) :: description

        integer :: k

        function%id_lines(1) = description
        function%function_type = function_type
        function%response_entity = 'NONE'
        function%response_node = response(1)
        function%response_direction = response(2)
        function%reference_entity = 'NONE'
        function%reference_node = reference(1)
        function%reference_direction = reference(2)
        function%even = .true.
        function%abscissa = [(first + (k - 1)*step, k=1, n)]
        function%numerator = uff_axis(8, 1, 0, 0, 'Displacement', 'm')
        function%denominator = uff_axis(13, 0, 1, 0, 'Force', 'N')
        function%z_axis = uff_axis(0, 0, 0, 0, 'NONE', 'NONE')
    end subroutine fill_dof

    ! ---- checks ------------------------------------------------------------------------

    !> An error for a function the format cannot hold as given.
    pure subroutine check_function(prefix, function, error)
        character(len=*), intent(in) :: prefix
        type(uff_function), intent(in) :: function
        type(error_type), allocatable, intent(out) :: error

        integer :: n, k
        real(dp) :: step

        if (.not. any(function%ordinate_type == [2, 4, 5, 6])) then
            call fatal_error(error, prefix//'expected the ordinate type 2, 4 (real single, double) or 5, 6 ' &
                             //'(complex single, double), found '//int_text(function%ordinate_type))
            return
        end if
        if (.not. (allocated(function%ordinate) .and. allocated(function%abscissa))) then
            call fatal_error(error, prefix//'expected abscissa and ordinate values; set both')
            return
        end if
        n = size(function%ordinate)
        if (n < 1 .or. size(function%abscissa) /= n) then
            call fatal_error(error, prefix//'expected as many abscissa as ordinate values, at least one, found ' &
                             //int_text(size(function%abscissa))//' and '//int_text(n))
            return
        end if
        if (.not. (all(ieee_is_finite(function%abscissa)) .and. all(ieee_is_finite(function%ordinate%re)) &
                   .and. all(ieee_is_finite(function%ordinate%im)))) then
            call fatal_error(error, prefix//'expected finite values, found a NaN or an infinity')
            return
        end if
        if (function%ordinate_type <= 4 .and. any(abs(function%ordinate%im) > 0.0_dp)) then
            call fatal_error(error, prefix//'a real ordinate type ('//int_text(function%ordinate_type) &
                             //') cannot hold the imaginary parts given; use type 5 or 6')
            return
        end if
        if (function%even .and. n > 1) then
            step = (function%abscissa(n) - function%abscissa(1))/(n - 1)
            if (.not. step > 0.0_dp .or. any([(abs(function%abscissa(k) - function%abscissa(1) - (k - 1)*step), &
                                                k=1, n)] > 1.0e-9_dp*max(step, abs(function%abscissa(n))))) then
                call fatal_error(error, prefix//'expected an even, increasing abscissa (spacing 1), found ' &
                                 //'other values; set even = .false. for uneven spacing')
                return
            end if
        else if (n > 1) then
            if (any(function%abscissa(2:) <= function%abscissa(:n - 1))) then
                call fatal_error(error, prefix//'expected increasing abscissa values')
                return
            end if
        end if
        call check_record6(prefix, function, error)
        if (allocated(error)) return
        do k = 1, 5
            if (trim(adjustl(function%id_lines(k))) == '-1') then
                call fatal_error(error, prefix//'ID line '//int_text(k)//' reads "-1", which ends a dataset; ' &
                                 //'change it')
                return
            end if
        end do
    end subroutine check_function

    !> Record 6's integer fields must fit their widths (I5, I10, I5, I10, I10, I4, I10, I4),
    !> the entity names 10 characters, the labels and units of records 8 to 11 20.
    pure subroutine check_record6(prefix, function, error)
        character(len=*), intent(in) :: prefix
        type(uff_function), intent(in) :: function
        type(error_type), allocatable, intent(out) :: error

        integer :: values(8), widths(8), k
        character(len=*), parameter :: names(8) = [character(len=27) :: 'the function type', &
            'the function identification', 'the version', 'the load case', 'the response node', &
            'the response direction', 'the reference node', 'the reference direction']

        values = [function%function_type, function%function_id, function%version, function%load_case, &
                  function%response_node, function%response_direction, function%reference_node, &
                  function%reference_direction]
        widths = [5, 10, 5, 10, 10, 4, 10, 4]
        do k = 1, 8
            if (len(int_text(values(k))) > widths(k)) then
                call fatal_error(error, prefix//trim(names(k))//' '//int_text(values(k))//' does not fit the ' &
                                 //int_text(widths(k))//' columns of record 6')
                return
            end if
        end do
        if (given_length(function%response_entity) > 10 .or. given_length(function%reference_entity) > 10) then
            call fatal_error(error, prefix//'the entity names of record 6 have at most 10 characters; shorten them')
        else if (max(given_length(function%abscissa_axis%label), given_length(function%abscissa_axis%units), &
                     given_length(function%numerator%label), given_length(function%numerator%units), &
                     given_length(function%denominator%label), given_length(function%denominator%units), &
                     given_length(function%z_axis%label), given_length(function%z_axis%units)) > 20) then
            call fatal_error(error, prefix//'the axis labels and units of records 8 to 11 have at most 20 ' &
                             //'characters; shorten them')
        end if
    end subroutine check_record6

    !> An error for a node the format cannot hold.
    pure subroutine check_nodes(path, nodes, error)
        character(len=*), intent(in) :: path
        type(uff_node), intent(in) :: nodes(:)
        type(error_type), allocatable, intent(out) :: error

        integer :: i

        do i = 1, size(nodes)
            if (nodes(i)%label < 1 .or. .not. all(ieee_is_finite(nodes(i)%position))) then
                call fatal_error(error, path//': universal file: node '//int_text(i)//' (label ' &
                                 //int_text(nodes(i)%label)//'): expected a label >= 1 and finite coordinates')
                return
            end if
        end do
    end subroutine check_nodes

    ! ---- records -----------------------------------------------------------------------

    !> Dataset 151.
    subroutine write_header(unit, header, stat)
        integer, intent(in) :: unit
        type(uff_header), intent(in) :: header
        integer, intent(out) :: stat

        write (unit, '(i6/i6/a/a/a/a10,a10,3i10/a10,a10/a/a10,a10/i6)', iostat=stat) -1, 151, trim(header%model), &
            trim(header%description), trim(header%application), header%date, '', 0, 0, 0, header%date, '', &
            trim(header%program), header%date, '', -1
    end subroutine write_header

    !> One dataset 15 (4I10,1P3E13.5) or 2411 (4I10 / 1P3D25.16) with every node.
    subroutine write_nodes(unit, nodes, dataset, stat)
        integer, intent(in) :: unit, dataset
        type(uff_node), intent(in) :: nodes(:)
        integer, intent(out) :: stat

        integer :: i, k

        write (unit, '(i6/i6)', iostat=stat) -1, dataset
        do i = 1, size(nodes)
            if (stat /= 0) return
            if (dataset == 15) then
                write (unit, '(4i10,3a)', iostat=stat) nodes(i)%label, nodes(i)%definition_system, &
                    nodes(i)%displacement_system, nodes(i)%color, (number_field(nodes(i)%position(k), 13), k=1, 3)
            else
                write (unit, '(4i10/3a)', iostat=stat) nodes(i)%label, nodes(i)%definition_system, &
                    nodes(i)%displacement_system, nodes(i)%color, (number_field(nodes(i)%position(k), 25), k=1, 3)
            end if
        end do
        if (stat == 0) write (unit, '(i6)', iostat=stat) -1
    end subroutine write_nodes

    !> One dataset 58: records 1 to 12.
    subroutine write_function(unit, function, stat)
        integer, intent(in) :: unit
        type(uff_function), intent(in) :: function
        integer, intent(out) :: stat

        integer :: n, k
        real(dp) :: step
        character(len=:), allocatable :: response, reference

        n = size(function%ordinate)
        step = 0.0_dp
        if (function%even .and. n > 1) step = (function%abscissa(n) - function%abscissa(1))/(n - 1)
        write (unit, '(i6/i6)', iostat=stat) -1, 58
        do k = 1, 5
            if (stat == 0) write (unit, '(a)', iostat=stat) trim(function%id_lines(k))
        end do
        if (stat /= 0) return
        call entity(function%response_entity, response)
        call entity(function%reference_entity, reference)
        write (unit, '(i5,i10,i5,i10,1x,a10,i10,i4,1x,a10,i10,i4)', iostat=stat) function%function_type, &
            function%function_id, function%version, function%load_case, response, &
            function%response_node, function%response_direction, reference, &
            function%reference_node, function%reference_direction
        if (stat /= 0) return
        write (unit, '(3i10,3a)', iostat=stat) function%ordinate_type, n, merge(1, 0, function%even), &
            number_field(merge(function%abscissa(1), 0.0_dp, function%even), 13), number_field(step, 13), &
            number_field(function%z_value, 13)
        if (stat == 0) call write_axis(unit, function%abscissa_axis, stat)
        if (stat == 0) call write_axis(unit, function%numerator, stat)
        if (stat == 0) call write_axis(unit, function%denominator, stat)
        if (stat == 0) call write_axis(unit, function%z_axis, stat)
        if (stat == 0) call write_data(unit, function, stat)
        if (stat == 0) write (unit, '(i6)', iostat=stat) -1
    end subroutine write_function

    !> Records 8 to 11: I10,3I5,2(1X,20A1).
    subroutine write_axis(unit, axis, stat)
        integer, intent(in) :: unit
        type(uff_axis), intent(in) :: axis
        integer, intent(out) :: stat

        character(len=:), allocatable :: label, units

        call entity(axis%label, label)
        call entity(axis%units, units)
        write (unit, '(i10,3i5,1x,a20,1x,a20)', iostat=stat) axis%data_type, axis%length_exponent, &
            axis%force_exponent, axis%temperature_exponent, label, units
    end subroutine write_axis

    !> Record 12 in the layout of the ordinate type and spacing (see the module description).
    subroutine write_data(unit, function, stat)
        integer, intent(in) :: unit
        type(uff_function), intent(in) :: function
        integer, intent(out) :: stat

        real(dp), allocatable :: values(:)
        integer, allocatable :: widths(:)
        character(len=:), allocatable :: line
        integer :: per_point, n, i, k, at

        n = size(function%ordinate)
        per_point = merge(2, 1, function%ordinate_type >= 5) + merge(0, 1, function%even)
        allocate (values(n*per_point))
        do i = 1, n
            at = (i - 1)*per_point
            if (.not. function%even) then
                values(at + 1) = function%abscissa(i)
                at = at + 1
            end if
            values(at + 1) = function%ordinate(i)%re
            if (function%ordinate_type >= 5) values(at + 2) = function%ordinate(i)%im
        end do
        if (function%ordinate_type == 2 .or. function%ordinate_type == 5) then
            widths = [13, 13, 13, 13, 13, 13]
        else if (function%even) then
            widths = [20, 20, 20, 20]
        else if (function%ordinate_type == 6) then
            widths = [13, 20, 20]
        else
            widths = [13, 20, 13, 20]
        end if
        stat = 0
        do i = 1, size(values), size(widths)
            line = ''
            do k = 1, min(size(widths), size(values) - i + 1)
                line = line//number_field(values(i + k - 1), widths(k))
            end do
            write (unit, '(a)', iostat=stat) line
            if (stat /= 0) return
        end do
    end subroutine write_data

    !> A value in a field of 13, 20 or 25 columns, with its exponent letter (see the module
    !> description): ES13.5, ES20.12 or 1PD25.16, one digit less for a three-digit exponent.
    pure function number_field(value, width) result(text)
        real(dp), intent(in) :: value
        integer, intent(in) :: width
        character(len=width) :: text

        select case (width)
        case (13)
            write (text, '(es13.5)') value
            if (scan(text, 'E') == 0) write (text, '(es13.4e3)') value
        case (20)
            write (text, '(es20.12)') value
            if (scan(text, 'E') == 0) write (text, '(es20.11e3)') value
        case default
            write (text, '(1pd25.16)') value
            if (scan(text, 'D') == 0) write (text, '(es25.15e3)') value
        end select
    end function number_field

    !> Length of a name without its leading and trailing blanks, 0 when it is unset.
    pure integer function given_length(name)
        character(len=:), allocatable, intent(in) :: name

        given_length = 0
        if (allocated(name)) given_length = len_trim(adjustl(name))
    end function given_length

    !> An entity name (record 6) or an axis label or units (records 8 to 11) as written:
    !> `NONE` when empty or unset.
    pure subroutine entity(name, text)
        !> The name, unset or blank for `NONE`.
        character(len=:), allocatable, intent(in) :: name
        !> The name as written.
        character(len=:), allocatable, intent(out) :: text

        text = 'NONE'
        if (given_length(name) > 0) text = trim(adjustl(name))
    end subroutine entity

end module greenconv_io_uff_write
