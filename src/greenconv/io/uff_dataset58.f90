!> Dataset 58 of universal files (function at nodal DOF) for the reader greenconv_io_uff:
!> records 1 to 11 (ID lines, DOF identification, data form, the four axes) and the values
!> of record 12, in the layouts the module greenconv_io_uff describes.
module greenconv_io_uff_dataset58
    use, intrinsic :: iso_fortran_env, only: int64
    use greenconv_core_kinds, only: dp
    use greenconv_core_error, only: error_type, fatal_error
    use greenconv_core_text, only: int_text, real_text
    use greenconv_io_uff_types, only: uff_axis, uff_function, uff_other, uff_receptance, uff_mobility, &
                                      uff_accelerance
    use greenconv_io_uff_records, only: text_line, dataset_extent, record_prefix, columns, span, quoted, &
                                        number_words, integer_field, real_field, parse_real
    implicit none
    private

    public :: read_function

    !> Columns of the fixed-width integer fields of record 6 (2(I5,I10),2(1X,10A1,I10,I4)).
    integer, parameter :: record6_first(10) = [1, 6, 16, 21, 32, 42, 52, 57, 67, 77]
    integer, parameter :: record6_last(10) = [5, 15, 20, 30, 41, 51, 55, 66, 76, 80]

contains

    !> Read one dataset 58: records 1 to 11 from the eleven lines after the dataset number,
    !> record 12 from the lines up to the closing -1.
    subroutine read_function(path, lines, set, function, error)
        !> File the lines come from (for messages).
        character(len=*), intent(in) :: path
        !> The file's lines.
        type(text_line), intent(in) :: lines(:)
        !> Where the dataset lies in them.
        type(dataset_extent), intent(in) :: set
        !> The function the dataset holds.
        type(uff_function), intent(out) :: function
        !> Set (status 2) when a record is missing or malformed.
        type(error_type), allocatable, intent(out) :: error

        character(len=*), parameter :: record_names(11) = [character(len=56) :: &
            'ID line 1 (80A1)', 'ID line 2 (80A1)', 'ID line 3 (80A1)', 'ID line 4 (80A1)', 'ID line 5 (80A1)', &
            'the DOF identification (2(I5,I10),2(1X,10A1,I10,I4))', 'the data form (3I10,3E13.5)', &
            'the abscissa characteristics (I10,3I5,2(1X,20A1))', &
            'the ordinate characteristics (I10,3I5,2(1X,20A1))', &
            'the denominator characteristics (I10,3I5,2(1X,20A1))', &
            'the z-axis characteristics (I10,3I5,2(1X,20A1))']
        type(uff_axis) :: axes(8:11)
        real(dp) :: minimum, step
        integer :: record, n_points, k

        function%line = set%first
        do record = 1, 11
            if (set%first + 1 + record >= set%last) then
                call fatal_error(error, record_prefix(path, set%last, 58, record)//'expected ' &
                                 //trim(record_names(record)) &
                                 //', found the -1 line that ends the dataset; the dataset is truncated')
                return
            end if
        end do
        ! record r is on line set%first + 1 + r
        do record = 1, 5
            function%id_lines(record) = lines(set%first + 1 + record)%text
        end do
        k = set%first + 7
        call read_record6(record_prefix(path, k, 58, 6), lines(k)%text, function, error)
        if (allocated(error)) return
        k = set%first + 8
        call read_record7(record_prefix(path, k, 58, 7), lines(k)%text, function, n_points, minimum, step, error)
        if (allocated(error)) return
        do record = 8, 11
            k = set%first + 1 + record
            call read_axis(record_prefix(path, k, 58, record), lines(k)%text, axes(record), error)
            if (allocated(error)) return
        end do
        function%abscissa_axis = axes(8)
        function%numerator = axes(9)
        function%denominator = axes(10)
        function%z_axis = axes(11)
        function%kind = ordinate_kind(function%numerator%data_type, function%denominator%data_type)
        call read_data(path, lines, set%first + 13, set%last, n_points, function, error)
        if (allocated(error)) return
        ! Only now that record 12 held the points record 7 promised: a damaged count (1e9) is
        ! refused by read_data, whose storage the lines bound, before any grid is built.
        if (function%even) function%abscissa = [(minimum + (k - 1)*step, k=1, n_points)]
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

    !> Record 7: data form, 3I10,3E13.5 (the abscissa minimum and increment of even spacing are
    !> returned, for the grid built once the points are read).
    subroutine read_record7(prefix, line, function, n_points, minimum, step, error)
        character(len=*), intent(in) :: prefix, line
        type(uff_function), intent(inout) :: function
        integer, intent(out) :: n_points
        real(dp), intent(out) :: minimum, step
        type(error_type), allocatable, intent(out) :: error

        character(len=*), parameter :: layout = '3I10,3E13.5'
        integer :: spacing

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
                call fatal_error(error, record_prefix(path, k, 58, 12)//'expected the -1 line after the ' &
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
            call read_data_line(record_prefix(path, k, 58, 12), lines(k)%text, widths, layout, n_values - n_read, &
                                next == last, values(n_read + 1:), n_read, error)
            if (allocated(error)) return
            value_line(n_before + 1:n_read) = k
        end do
        if (n_read < n_values) then
            partial = ''
            if (mod(n_read, per_point) > 0) partial = ' and '//int_text(mod(n_read, per_point))//' of the ' &
                                                      //int_text(per_point)//' values of point ' &
                                                      //int_text(n_read/per_point + 1)
            call fatal_error(error, record_prefix(path, last, 58, 12)//'expected '//int_text(n_points) &
                             //' points (record 7 field 2, '//layout//'), found '//int_text(n_read/per_point)//partial &
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
        allocate (function%ordinate(n), function%point_line(n))
        if (.not. function%even) allocate (function%abscissa(n))
        do i = 1, n
            at_x = (i - 1)*per_point + 1
            function%point_line(i) = value_line(at_x)
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
                    call fatal_error(error, record_prefix(path, value_line(at_x), 58, 12) &
                                     //'expected abscissa values that increase (uneven spacing), found ' &
                                     //real_text(function%abscissa(i))//' at point '//int_text(i)//' after ' &
                                     //real_text(function%abscissa(i - 1)))
                    return
                end if
            end if
        end do
    end subroutine store_points

end module greenconv_io_uff_dataset58
