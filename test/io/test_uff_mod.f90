!> The universal-file reader (greenconv_io_uff): files written by pyuff, an independent writer
!> (test/data/uff, made by tools/make_uff_fixtures.py), compared value by value with the
!> closed forms that script wrote beside them; files written here with Fortran's own edit
!> descriptors (the format's READ/WRITE statements) in every layout; and every malformed
!> case, whose one-line message must name the file, the line, the dataset, the record, what
!> was expected and what was found.
module test_uff_mod
    use, intrinsic :: iso_fortran_env, only: dp => real64
    use testsuite_mod, only: test_error, unittest_type, new_unittest, check, note
    use scene_text_mod, only: write_text, feed_fifo
    use greenconv_core_error, only: error_type
    use greenconv_io_files, only: make_directory
    use greenconv_io_columns, only: max_line_length
    use greenconv_io_uff, only: uff_file, read_uff, uff_summary, uff_kind_name, uff_data_type_name, &
                                uff_function_type_name, uff_receptance, uff_mobility, uff_accelerance
    implicit none
    private

    public :: collect_uff

    !> Fixtures written by pyuff.
    character(len=*), parameter :: fixtures = 'test/data/uff/'
    !> Scratch directory for the files the tests write.
    character(len=*), parameter :: scratch = 'build/test_scratch/uff'
    !> Relative precision of an E13.5 field written by pyuff (%13.5e: six significant digits).
    real(dp), parameter :: single_digits = 6.0e-6_dp
    !> Relative precision of an E20.12 field written by pyuff (%20.11e: twelve significant digits).
    real(dp), parameter :: double_digits = 6.0e-12_dp

contains

    !> Tests of greenconv_io_uff.
    subroutine collect_uff(testsuite)
        type(unittest_type), allocatable, intent(out) :: testsuite(:)

        testsuite = [new_unittest('pyuff: complex double even FRF (case 7)', test_pyuff_complex_double), &
                     new_unittest('pyuff: complex single uneven mobility (case 4)', test_pyuff_complex_single), &
                     new_unittest('pyuff: real single time response (case 1)', test_pyuff_time), &
                     new_unittest('pyuff: nodes 15 + 2411 and cases 5 to 8', test_pyuff_patch), &
                     new_unittest('pyuff: datasets skipped, cases 2 and 3', test_pyuff_skipped), &
                     new_unittest('pyuff FRF equals the SDOF receptance computed here', test_closed_form), &
                     new_unittest('Fortran writer: all 8 cases, E and D, 3-digit exponents, touching fields', &
                                  test_fortran_cases), &
                     new_unittest('layout: CRLF, blank lines, short records, names, integers in real fields', &
                                  test_layout), &
                     new_unittest('nodes: Fortran 1P3E13.5 and 1P3D25.16', test_fortran_nodes), &
                     new_unittest('names of kinds, data types and function types', test_names), &
                     new_unittest('malformed: missing, empty, structure, binary, long line', test_bad_structure), &
                     new_unittest('a universal file from a FIFO, read once', test_fifo), &
                     new_unittest('malformed: records 6 to 11', test_bad_header), &
                     new_unittest('malformed: data values and counts', test_bad_data), &
                     new_unittest('malformed: nodes', test_bad_nodes)]
    end subroutine collect_uff

    ! ---- files written by pyuff ------------------------------------------------------------

    subroutine test_pyuff_complex_double(error)
        type(test_error), allocatable, intent(out) :: error

        call check_fixture('frf_complex_double_even', error)
    end subroutine test_pyuff_complex_double

    subroutine test_pyuff_complex_single(error)
        type(test_error), allocatable, intent(out) :: error

        call check_fixture('frf_complex_single_uneven', error)
    end subroutine test_pyuff_complex_single

    subroutine test_pyuff_time(error)
        type(test_error), allocatable, intent(out) :: error

        call check_fixture('time_real_single', error)
    end subroutine test_pyuff_time

    subroutine test_pyuff_patch(error)
        type(test_error), allocatable, intent(out) :: error

        call check_fixture('patch_geometry', error)
    end subroutine test_pyuff_patch

    subroutine test_pyuff_skipped(error)
        type(test_error), allocatable, intent(out) :: error

        type(uff_file) :: file
        type(error_type), allocatable :: read_error

        call check_fixture('skipped_datasets', error)
        if (allocated(error)) return
        call read_uff(fixtures//'skipped_datasets.uff', file, read_error)
        call check(error, uff_summary(file) == fixtures//'skipped_datasets.uff: 2 functions (dataset 58), ' &
                   //'0 nodes (datasets 15, 2411), skipped: 151 (line 1), 164 (line 11)', &
                   'summary: '//uff_summary(file))
    end subroutine test_pyuff_skipped

    !> Read fixtures/name.uff and compare everything with fixtures/name.expected: counts,
    !> record 6 and 7 fields, the kind, every abscissa and ordinate (to the precision of the
    !> format: E13.5 or E20.12 relative, abscissa 1e-12), every node and every skipped dataset.
    subroutine check_fixture(name, error)
        character(len=*), intent(in) :: name
        type(test_error), allocatable, intent(out) :: error

        type(uff_file) :: file
        type(error_type), allocatable :: read_error
        character(len=256) :: line
        character(len=32) :: keyword, text
        integer :: unit, stat, i_function, i_node, i_skipped, counts(3), fields(6), n, p, label, dataset
        real(dp) :: x, re, im, xyz(3), tol, worst

        call read_uff(fixtures//name//'.uff', file, read_error)
        if (allocated(read_error)) then
            call check(error, .false., name//': '//read_error%message)
            return
        end if
        open (newunit=unit, file=fixtures//name//'.expected', status='old', action='read')
        i_function = 0
        i_node = 0
        i_skipped = 0
        worst = 0.0_dp
        do
            read (unit, '(a)', iostat=stat) line
            if (stat /= 0) exit
            if (line(1:1) == '#') cycle
            read (line, *) keyword
            select case (keyword)
            case ('file')
                read (line, *) keyword, text, counts
                call check(error, size(file%functions) == counts(1) .and. size(file%nodes) == counts(2) &
                           .and. size(file%skipped) == counts(3), name//': counts: '//uff_summary(file))
            case ('function')
                i_function = i_function + 1
                read (line, *) keyword, fields, text, n
                associate (f => file%functions(i_function))
                    call check(error, f%function_type == fields(1) .and. f%response_node == fields(2) .and. &
                               f%response_direction == fields(3) .and. f%reference_node == fields(4) .and. &
                               f%reference_direction == fields(5) .and. f%ordinate_type == fields(6) .and. &
                               uff_kind_name(f%kind) == trim(text) .and. size(f%ordinate) == n .and. &
                               size(f%abscissa) == n, name//': record 6/7 fields or kind of function: '//trim(line))
                    if (allocated(error)) exit
                    tol = double_digits
                    if (f%ordinate_type == 2 .or. f%ordinate_type == 5) tol = single_digits
                    do p = 1, n
                        read (unit, *) x, re, im
                        call check(error, abs(f%abscissa(p) - x) <= 1.0e-12_dp*abs(x) .and. &
                                   abs(f%ordinate(p)%re - re) <= tol*abs(re) .and. &
                                   abs(f%ordinate(p)%im - im) <= tol*abs(im), name//': point of '//trim(line))
                        if (allocated(error)) exit
                        worst = max(worst, relative(f%ordinate(p)%re, re), relative(f%ordinate(p)%im, im))
                    end do
                end associate
            case ('node')
                i_node = i_node + 1
                read (line, *) keyword, label, dataset, xyz
                associate (node => file%nodes(i_node))
                    call check(error, node%label == label .and. node%dataset == dataset .and. &
                               all(abs(node%position - xyz) <= merge(single_digits, 1.0e-15_dp, dataset == 15) &
                                   *abs(xyz)), name//': '//trim(line))
                end associate
            case ('skipped')
                i_skipped = i_skipped + 1
                read (line, *) keyword, dataset
                call check(error, file%skipped(i_skipped)%dataset == dataset, name//': '//trim(line))
            case default
                call check(error, .false., name//'.expected: unknown line "'//trim(line)//'"')
            end select
            if (allocated(error)) exit
        end do
        close (unit)
        if (allocated(error)) return
        call check(error, i_function == size(file%functions) .and. i_node == size(file%nodes) .and. &
                   i_skipped == size(file%skipped), name//': the expected file lists fewer items than read')
        call note('worst relative error', worst)
    end subroutine check_fixture

    !> |actual - expected| / |expected| (0 when both are 0).
    pure real(dp) function relative(actual, expected)
        real(dp), intent(in) :: actual, expected

        relative = 0.0_dp
        if (expected /= 0.0_dp) relative = abs(actual - expected)/abs(expected)
    end function relative

    !> The first pyuff FRF against H(f) = 1/(k - m w^2 + i c w) evaluated here, independently
    !> of the Python script: m = 1.5 kg, f_n = 50 Hz, zeta = 0.02, f = 0, 2.5, ..., 200 Hz; and
    !> the header fields the script wrote (labels, units, data types).
    subroutine test_closed_form(error)
        type(test_error), allocatable, intent(out) :: error

        real(dp), parameter :: pi = acos(-1.0_dp), mass = 1.5_dp, zeta = 0.02_dp, omega_n = 2*pi*50.0_dp
        type(uff_file) :: file
        type(error_type), allocatable :: read_error
        complex(dp) :: h
        real(dp) :: w, worst
        integer :: i

        call read_uff(fixtures//'frf_complex_double_even.uff', file, read_error)
        call check(error, .not. allocated(read_error), 'the fixture reads')
        if (allocated(error)) return
        associate (f => file%functions(1))
            call check(error, size(f%abscissa) == 81 .and. f%even .and. f%kind == uff_receptance .and. &
                       f%function_type == 4 .and. f%abscissa_axis%data_type == 18 .and. &
                       f%abscissa_axis%units == 'Hz' .and. f%numerator%units == 'm' .and. &
                       f%denominator%data_type == 13 .and. f%denominator%units == 'N' .and. &
                       f%response_entity == 'NONE' .and. f%line == 1 .and. &
                       f%id_lines(1) == 'greenconv fixture frf_complex_double_even function 1', 'header fields')
            if (allocated(error)) return
            worst = 0.0_dp
            do i = 1, 81
                call check(error, f%abscissa(i), 2.5_dp*(i - 1), 'abscissa', thr=0.0_dp)
                if (allocated(error)) return
                w = 2*pi*f%abscissa(i)
                h = 1.0_dp/cmplx(mass*omega_n**2 - mass*w**2, 2*zeta*mass*omega_n*w, dp)
                worst = max(worst, abs(f%ordinate(i) - h)/abs(h))
            end do
        end associate
        call note('worst |G - H|/|H|', worst)
        call check(error, worst < 1.0e-11_dp, 'FRF equals the closed form to the 12 digits of the file')
    end subroutine test_closed_form

    ! ---- files written here ----------------------------------------------------------------

    !> The eleven header records of a dataset 58 after its number, with the given records 6
    !> and 7, a frequency abscissa and a displacement/force ordinate.
    pure function header58(record6, record7) result(text)
        character(len=*), intent(in) :: record6, record7
        character(len=:), allocatable :: text

        character(len=*), parameter :: nl = new_line('a')

        text = 'written by test_uff_mod'//nl//'NONE'//nl//'NONE'//nl//'NONE'//nl//'NONE'//nl//record6//nl &
               //record7//nl//'        18    0    0    0 Frequency            Hz'//nl &
               //'         8    1    0    0 Displacement         m'//nl &
               //'        13    0    1    0 Force                N'//nl &
               //'         0    0    0    0 NONE                 NONE'//nl
    end function header58

    !> A whole dataset 58 (with its -1 lines): header58 and the data lines.
    pure function dataset58(record6, record7, data) result(text)
        character(len=*), intent(in) :: record6, record7, data
        character(len=:), allocatable :: text

        character(len=*), parameter :: nl = new_line('a')

        text = '    -1'//nl//'    58'//nl//header58(record6, record7)//data//'    -1'//nl
    end function dataset58

    !> Record 6 of a FRF between response node/direction and reference node/direction.
    pure function record6(response, response_dir, reference, reference_dir) result(text)
        integer, intent(in) :: response, response_dir, reference, reference_dir
        character(len=80) :: text

        write (text, '(2(i5,i10),2(1x,a10,i10,i4))') 4, 1, 0, 0, 'NONE', response, response_dir, 'NONE', &
            reference, reference_dir
    end function record6

    !> Record 7 as Fortran writes it (3I10,3E13.5).
    pure function record7(ordinate_type, n, spacing, minimum, step) result(text)
        integer, intent(in) :: ordinate_type, n, spacing
        real(dp), intent(in) :: minimum, step
        character(len=69) :: text

        write (text, '(3i10,3e13.5)') ordinate_type, n, spacing, minimum, step, 0.0_dp
    end function record7

    !> Lines of `values` written with a Fortran format of `per_line` fields.
    function data_lines(values, edit, per_line) result(text)
        real(dp), intent(in) :: values(:)
        character(len=*), intent(in) :: edit
        integer, intent(in) :: per_line
        character(len=:), allocatable :: text

        character(len=200) :: buffer
        integer :: i

        text = ''
        do i = 1, size(values), per_line
            write (buffer, edit) values(i:min(i + per_line - 1, size(values)))
            text = text//trim(buffer)//new_line('a')
        end do
    end function data_lines

    !> Write `text` as scratch/name and read it; fail on an error.
    subroutine read_text(name, text, file, error)
        character(len=*), intent(in) :: name, text
        type(uff_file), intent(out) :: file
        type(test_error), allocatable, intent(out) :: error

        type(error_type), allocatable :: read_error

        call make_directory(scratch, read_error)
        call write_text(scratch//'/'//name, text)
        call read_uff(scratch//'/'//name, file, read_error)
        if (allocated(read_error)) call check(error, .false., name//': '//read_error%message)
    end subroutine read_text

    !> The eight cases of record 12 as the format's own Fortran WRITE statements produce them
    !> (E, D and ES descriptors; values from 1e-100 to 1e+115 so that three-digit exponents
    !> lose their letter, `0.12346-119`; ES20.13 fields of negative numbers touch), read back
    !> to the precision of each field.
    subroutine test_fortran_cases(error)
        type(test_error), allocatable, intent(out) :: error

        integer, parameter :: n = 7
        character(len=*), parameter :: single_edit = '(1p,6e13.5)', single_plain = '(6e13.5)'
        real(dp) :: x(n), y(n), z(n), flat(3*n)
        type(uff_file) :: file
        character(len=:), allocatable :: text
        integer :: i, case

        do i = 1, n
            x(i) = 10.0_dp + 2.5_dp*i**2
            y(i) = (-1)**i*1.234567890123456_dp*10.0_dp**(35*i - 130)
            z(i) = -0.987654321098765_dp*10.0_dp**(110 - 30*i)
        end do
        ! Cases 1 to 8 in order; each writes its data with the descriptors the spec gives.
        text = dataset58(record6(1, 3, 1, 3), record7(2, n, 1, 0.0_dp, 1.0_dp), data_lines(y, single_plain, 6))
        flat(1:2*n:2) = x
        flat(2:2*n:2) = y
        text = text//dataset58(record6(1, 3, 1, 3), record7(2, n, 0, 0.0_dp, 0.0_dp), &
                               data_lines(flat(:2*n), single_edit, 6))
        flat(1:2*n:2) = y
        flat(2:2*n:2) = z
        text = text//dataset58(record6(1, 3, 1, 3), record7(5, n, 1, 5.0_dp, 0.5_dp), &
                               data_lines(flat(:2*n), '(6d13.5)', 6))
        flat(1:3*n:3) = x
        flat(2:3*n:3) = y
        flat(3:3*n:3) = z
        text = text//dataset58(record6(1, 3, 1, 3), record7(5, n, 0, 0.0_dp, 0.0_dp), &
                               data_lines(flat(:3*n), single_plain, 6))
        text = text//dataset58(record6(1, 3, 1, 3), record7(4, n, 1, 0.0_dp, 1.0_dp), data_lines(y, '(4e20.12)', 4))
        flat(1:2*n:2) = x
        flat(2:2*n:2) = y
        text = text//dataset58(record6(1, 3, 1, 3), record7(4, n, 0, 0.0_dp, 0.0_dp), &
                               data_lines(flat(:2*n), '(2(e13.5,1p,d20.12,0p))', 4))
        flat(1:2*n:2) = -abs(y)
        flat(2:2*n:2) = -abs(z)
        text = text//dataset58(record6(1, 3, 1, 3), record7(6, n, 1, 0.0_dp, 1.0_dp), &
                               data_lines(flat(:2*n), '(4es20.13)', 4))
        flat(1:3*n:3) = x
        flat(2:3*n:3) = y
        flat(3:3*n:3) = z
        text = text//dataset58(record6(1, 3, 1, 3), record7(6, n, 0, 0.0_dp, 0.0_dp), &
                               data_lines(flat(:3*n), '(e13.5,2d20.12)', 3))
        call read_text('fortran_cases.uff', text, file, error)
        if (allocated(error)) return
        call check(error, size(file%functions) == 8, 'eight functions')
        if (allocated(error)) return
        do case = 1, 8
            associate (f => file%functions(case))
                ! Even spacing: abscissa from record 7; uneven: x (E13.5, five digits, exact here).
                if (f%even) then
                    call check(error, all(f%abscissa == [(merge(5.0_dp + 0.5_dp*(i - 1), real(i - 1, dp), &
                                                                case == 3), i=1, n)]), 'even abscissa')
                else
                    call check(error, all(f%abscissa == x), 'uneven abscissa')
                end if
                if (allocated(error)) return
                call check_values(case, f%ordinate, y, z, error)
                if (allocated(error)) return
            end associate
        end do
        ! The test's own writer must have produced what it is meant to exercise.
        call check(error, index(text, '0.12346+116') > 0 .and. index(text, '-0.98765-100') > 0 &
                   .and. index(text, 'D+') > 0 .and. index(text, 'E-95-') > 0, &
                   'the text holds letterless exponents, D and touching fields')
    end subroutine test_fortran_cases

    !> The ordinates of case `case` of test_fortran_cases: y (real cases), y + i z (complex
    !> cases; -|y| - i|z| for case 7), within the digits of the field (5 for E13.5, 6 for
    !> 1PE13.5, 12 for E20.12 and D20.12, 13 for 1PD20.12, 14 for ES20.13).
    subroutine check_values(case, ordinate, y, z, error)
        integer, intent(in) :: case
        complex(dp), intent(in) :: ordinate(:)
        real(dp), intent(in) :: y(:), z(:)
        type(test_error), allocatable, intent(out) :: error

        real(dp), parameter :: digits(8) = [5e-5_dp, 5e-6_dp, 5e-5_dp, 5e-5_dp, 5e-11_dp, 5e-12_dp, 5e-14_dp, &
                                            5e-11_dp]
        real(dp) :: re(size(y)), im(size(y))

        re = y
        im = 0.0_dp
        if (case == 3 .or. case == 4 .or. case == 8) im = z
        if (case == 7) then
            re = -abs(y)
            im = -abs(z)
        end if
        call check(error, all(abs(ordinate%re - re) <= digits(case)*abs(re)) .and. &
                   all(abs(ordinate%im - im) <= digits(case)*abs(im)), 'case '//achar(48 + case)//' values')
    end subroutine check_values

    !> What real files show: CRLF line ends, blank lines between datasets and in the data,
    !> trailing blanks, records 8-11 cut after their units, entity names, the z-axis value,
    !> integers in real fields, lower-case exponents, a dataset number not right-justified,
    !> a negative direction and node labels of ten digits touching the previous field.
    subroutine test_layout(error)
        type(test_error), allocatable, intent(out) :: error

        character(len=*), parameter :: nl = new_line('a'), cr = achar(13)
        type(uff_file) :: file
        character(len=:), allocatable :: text
        integer :: i

        text = '    -1'//cr//nl//'    58   '//cr//nl//'crlf file'//cr//nl//'NONE'//cr//nl//cr//nl//'NONE'//cr//nl &
               //'NONE'//cr//nl &
               //'    4       123    2         0 POINT A   1234567890  -2 REF B     2147483647   6'//cr//nl &
               //'         2         8         1          100           50  1.50000e+00   '//cr//nl &
               //'        18    0    0    0 Frequency            Hz'//cr//nl &
               //'        12    1    0    0'//cr//nl//'         9'//cr//nl//'         5    0    0    1'//cr//nl &
               //'  1.00000e+00 -2.50000e-01            3  4.00000E+00  5.00000d-01  0.60000-100'//cr//nl &
               //cr//nl//'  7.00000E+00  8.00000E+00   '//cr//nl//'    -1  '//cr//nl//nl//nl &
               //'    -1'//nl//'58'//nl//header58(record6(1, 3, 2, -1), record7(6, 1, 0, 0.0_dp, 0.0_dp)) &
               //'  2.00000E+01  1.000000000000E+00 -2.000000000000E+00'//nl//'    -1'
        call read_text('layout.uff', text, file, error)
        if (allocated(error)) return
        call check(error, size(file%functions) == 2, 'two functions')
        if (allocated(error)) return
        associate (f => file%functions(1))
            call check(error, f%function_type == 4 .and. f%function_id == 123 .and. f%version == 2 .and. &
                       f%response_entity == 'POINT A' .and. f%response_node == 1234567890 .and. &
                       f%response_direction == -2 .and. f%reference_entity == 'REF B' .and. &
                       f%reference_node == huge(1) .and. f%reference_direction == 6, 'record 6: '//f%response_entity)
            if (allocated(error)) return
            call check(error, f%id_lines(3) == '' .and. f%id_lines(1) == 'crlf file', 'ID lines kept as written')
            if (allocated(error)) return
            call check(error, f%kind == uff_accelerance .and. f%numerator%label == '' .and. &
                       f%denominator%data_type == 9 .and. f%z_axis%temperature_exponent == 1 .and. &
                       f%z_value == 1.5_dp .and. all(f%abscissa == [(100.0_dp + 50*i, i=0, 7)]), 'records 7 to 11')
            if (allocated(error)) return
            call check(error, all(f%ordinate%re == [1.0_dp, -0.25_dp, 3.0_dp, 4.0_dp, 0.5_dp, 0.6e-100_dp, 7.0_dp, &
                                                    8.0_dp]) .and. &
                       all(f%ordinate%im == 0.0_dp), 'values with blank lines, short lines and an integer')
            if (allocated(error)) return
        end associate
        associate (f => file%functions(2))
            call check(error, f%reference_direction == -1 .and. f%line == 20 .and. f%abscissa(1) == 20.0_dp .and. &
                       f%ordinate(1) == (1.0_dp, -2.0_dp), 'second dataset after blank lines')
        end associate
    end subroutine test_layout

    !> Datasets 15 and 2411 as Fortran writes them (1P3E13.5, 1P3D25.16).
    subroutine test_fortran_nodes(error)
        type(test_error), allocatable, intent(out) :: error

        character(len=*), parameter :: nl = new_line('a')
        real(dp), parameter :: xyz(3, 3) = reshape([0.1_dp, -2.5e-3_dp, 1.0e5_dp, 1.0_dp/3, 2.0_dp/3, -1.0_dp, &
                                                    0.0_dp, 1.0e-110_dp, -7.25_dp], [3, 3])
        type(uff_file) :: file
        character(len=120) :: line
        character(len=:), allocatable :: text
        integer :: i

        text = '    -1'//nl//'    15'//nl
        do i = 1, 2
            write (line, '(4i10,1p3e13.5)') 10*i, 0, 0, 7, xyz(:, i)
            text = text//trim(line)//nl
        end do
        text = text//'    -1'//nl//'    -1'//nl//'  2411'//nl
        write (line, '(4i10)') 99, 1, 1, 8
        text = text//trim(line)//nl
        write (line, '(1p3d25.16)') xyz(:, 3)
        text = text//trim(line)//nl//'    -1'
        call read_text('nodes.uff', text, file, error)
        if (allocated(error)) return
        call check(error, size(file%nodes) == 3 .and. size(file%functions) == 0, 'three nodes')
        if (allocated(error)) return
        call check(error, all(file%nodes%label == [10, 20, 99]) .and. all(file%nodes%dataset == [15, 15, 2411]) &
                   .and. all(file%nodes%line == [3, 4, 8]) .and. all(file%nodes%color == [7, 7, 8]) .and. &
                   file%nodes(3)%definition_system == 1, 'labels, datasets, lines, colors')
        if (allocated(error)) return
        do i = 1, 2
            call check(error, all(abs(file%nodes(i)%position - xyz(:, i)) <= 5.0e-6_dp*abs(xyz(:, i))), &
                       'dataset 15 coordinates')
            if (allocated(error)) return
        end do
        call check(error, all(abs(file%nodes(3)%position - xyz(:, 3)) <= 1.0e-15_dp*abs(xyz(:, 3))), &
                   'dataset 2411 coordinates')
    end subroutine test_fortran_nodes

    subroutine test_names(error)
        type(test_error), allocatable, intent(out) :: error

        call check(error, uff_kind_name(uff_receptance) == 'receptance' .and. uff_kind_name(uff_mobility) == &
                   'mobility' .and. uff_kind_name(uff_accelerance) == 'accelerance' .and. uff_kind_name(0) == &
                   'other' .and. uff_data_type_name(13) == 'excitation force' .and. uff_data_type_name(4) == &
                   'type 4' .and. uff_function_type_name(4) == 'frequency response function' .and. &
                   uff_function_type_name(1) == 'time response' .and. uff_function_type_name(28) == 'type 28', &
                   'names')
    end subroutine test_names

    !> A fixture read through a FIFO with one writer gives the summary of the file itself (the
    !> lines are read once: a pipe cannot be rewound).
    subroutine test_fifo(error)
        type(test_error), allocatable, intent(out) :: error

        character(len=*), parameter :: fifo = scratch//'/skipped.fifo'
        character(len=*), parameter :: fixture = fixtures//'skipped_datasets.uff'
        type(uff_file) :: file, piped
        type(error_type), allocatable :: read_error
        character(len=:), allocatable :: from_file, from_fifo
        logical :: made

        call read_uff(fixture, file, read_error)
        call check(error, .not. allocated(read_error), 'the fixture refused')
        if (allocated(error)) return
        call feed_fifo(fifo, fixture, made)
        if (.not. made) then
            call note('skipped', 0.0_dp)
            return
        end if
        call read_uff(fifo, piped, read_error)
        call execute_command_line('rm -f '//fifo)
        if (allocated(read_error)) then
            call check(error, .false., 'a universal file from a FIFO refused: '//read_error%message)
            return
        end if
        from_file = uff_summary(file)
        from_fifo = uff_summary(piped)
        call check(error, from_fifo == fifo//from_file(len(fixture) + 1:), 'FIFO: '//from_fifo//'; file: '//from_file)
    end subroutine test_fifo

    ! ---- malformed files -----------------------------------------------------------------

    !> Write `text` as scratch/name, read it, and check: an error, status 2, one line starting
    !> with `scratch/name:line:` and containing every piece.
    subroutine expect_error(error, name, line, text, pieces)
        type(test_error), allocatable, intent(out) :: error
        character(len=*), intent(in) :: name, text
        integer, intent(in) :: line
        character(len=*), intent(in) :: pieces(:)

        type(uff_file) :: file
        type(error_type), allocatable :: read_error
        character(len=16) :: number
        integer :: i

        call make_directory(scratch, read_error)
        call write_text(scratch//'/'//name, text)
        call read_uff(scratch//'/'//name, file, read_error)
        call check(error, allocated(read_error), name//': no error')
        if (allocated(error)) return
        write (number, '(i0)') line
        call check(error, read_error%stat == 2 .and. index(read_error%message, scratch//'/'//name//':' &
                                                                 //trim(number)//': universal file') == 1 &
                   .and. index(read_error%message, new_line('a')) == 0, &
                   name//': status 2 and one line starting with file:'//trim(number)//': '//read_error%message)
        if (allocated(error)) return
        do i = 1, size(pieces)
            call check(error, index(read_error%message, trim(pieces(i))) > 0, &
                       name//': message "'//read_error%message//'" lacks "'//trim(pieces(i))//'"')
            if (allocated(error)) return
        end do
    end subroutine expect_error

    subroutine test_bad_structure(error)
        type(test_error), allocatable, intent(out) :: error

        character(len=*), parameter :: nl = new_line('a')
        type(uff_file) :: file
        type(error_type), allocatable :: read_error
        character(len=:), allocatable :: good

        call read_uff(scratch//'/no such file.uff', file, read_error)
        call check(error, allocated(read_error), 'a missing file is refused')
        if (allocated(error)) return
        call check(error, read_error%stat == 2 .and. index(read_error%message, scratch//'/no such file.uff: ' &
                                                           //'cannot open the universal file') == 1, &
                   'missing file: '//read_error%message)
        if (allocated(error)) return
        call make_directory(scratch, read_error)
        call write_empty(scratch//'/empty.uff')
        call read_uff(scratch//'/empty.uff', file, read_error)
        call check(error, allocated(read_error), 'an empty file is refused')
        if (allocated(error)) return
        call check(error, index(read_error%message, scratch//'/empty.uff:1: universal file: expected datasets') &
                   == 1 .and. index(read_error%message, 'found an empty file') > 0, 'empty: '//read_error%message)
        if (allocated(error)) return
        good = dataset58(record6(1, 3, 1, 3), record7(2, 2, 1, 0.0_dp, 1.0_dp), '  1.00000E+00  2.00000E+00'//nl)
        call expect_error(error, 'stray.uff', 1, 'comment'//nl//good, &
                          [character(len=60) :: 'expected a line "    -1" that starts a dataset', 'found "comment"'])
        if (allocated(error)) return
        call expect_error(error, 'cut_header.uff', 5, '    -1'//nl//'    58'//nl//'id'//nl//'NONE'//nl//'NONE', &
                          [character(len=70) :: 'dataset 58: expected a line "    -1" that ends the dataset', &
                           'started at line 1, found the end of the file'])
        if (allocated(error)) return
        call expect_error(error, 'short_header.uff', 11, '    -1'//nl//'    58'//nl//'id'//nl//'NONE'//nl//'NONE' &
                          //nl//'NONE'//nl//'NONE'//nl//record6(1, 3, 1, 3)//nl//record7(2, 2, 1, 0.0_dp, 1.0_dp) &
                          //nl//'        18    0    0    0 Frequency            Hz'//nl//'    -1', &
                          [character(len=70) :: 'dataset 58 record 9: expected the ordinate characteristics', &
                           'found the -1 line that ends the dataset'])
        if (allocated(error)) return
        call expect_error(error, 'no_end.uff', 17, good(:len(good) - 7)//nl//good, &
                          [character(len=70) :: 'expected a line "    -1" that starts a dataset, found "    58"', &
                           'is the -1 line that ends the dataset 58 started at line 1 missing?'])
        if (allocated(error)) return
        call expect_error(error, 'no_end_at_eof.uff', 15, good(:len(good) - 7), &
                          [character(len=70) :: 'expected a line "    -1" that ends the dataset started at line 1', &
                           'found the end of the file'])
        if (allocated(error)) return
        call expect_error(error, 'no_number.uff', 2, '    -1'//nl//'  abc'//nl//'    -1', &
                          [character(len=70) :: 'expected a dataset number (an integer in columns 1-6)', &
                           'found "  abc"'])
        if (allocated(error)) return
        call expect_error(error, 'binary.uff', 2, '    -1'//nl//'    58b     1     2'//nl//'    -1', &
                          [character(len=70) :: 'dataset 58b: expected an ASCII dataset, found a binary one', &
                           'export the file as an ASCII universal file'])
        if (allocated(error)) return
        ! A line longer than the readers take is refused at that line, not taken for the file's end.
        call write_text(scratch//'/long_line.uff', '    -1'//nl//repeat('1', 2*max_line_length)//nl//'    -1'//nl)
        call read_uff(scratch//'/long_line.uff', file, read_error)
        call check(error, allocated(read_error), 'a line longer than max_line_length is refused')
        if (allocated(error)) return
        call check(error, read_error%stat == 2 .and. index(read_error%message, scratch//'/long_line.uff:2: ' &
                                                           //'expected lines of at most') == 1, &
                   'long line: '//read_error%message(:min(len(read_error%message), 200)))
    end subroutine test_bad_structure

    !> An empty file.
    subroutine write_empty(path)
        character(len=*), intent(in) :: path

        integer :: unit

        open (newunit=unit, file=path, status='replace', action='write')
        close (unit)
    end subroutine write_empty

    subroutine test_bad_header(error)
        type(test_error), allocatable, intent(out) :: error

        character(len=*), parameter :: nl = new_line('a')
        character(len=*), parameter :: data = '  1.00000E+00  2.00000E+00'//nl
        character(len=80) :: r6, r7

        r6 = record6(1, 3, 1, 3)
        r7 = record7(2, 2, 1, 0.0_dp, 1.0_dp)
        call expect_error(error, 'node.uff', 8, dataset58(r6(:41)//'       1x3'//r6(52:), r7, data), &
                          [character(len=80) :: 'dataset 58 record 6: expected the response node (an integer in ' &
                           //'columns 42-51), found "1x3"'])
        if (allocated(error)) return
        call expect_error(error, 'direction.uff', 8, dataset58(r6(:51)//'   9'//r6(56:), r7, data), &
                          [character(len=80) :: 'record 6: expected a direction from -6 to 6', &
                           'in columns 52-55, found "9"'])
        if (allocated(error)) return
        call expect_error(error, 'blank_type.uff', 8, dataset58('     '//r6(6:), r7, data), &
                          [character(len=80) :: 'record 6: expected the function type (an integer in columns 1-5)' &
                           //', found blanks'])
        if (allocated(error)) return
        call expect_error(error, 'ordinate_type.uff', 9, dataset58(r6, record7(3, 2, 1, 0.0_dp, 1.0_dp), data), &
                          [character(len=100) :: 'dataset 58 record 7: expected an ordinate data type 2 (real ' &
                           //'single), 4 (real double), 5 (complex single) or 6 (complex double)', 'found "3"'])
        if (allocated(error)) return
        call expect_error(error, 'zero_points.uff', 9, dataset58(r6, record7(2, 0, 1, 0.0_dp, 1.0_dp), data), &
                          [character(len=80) :: 'record 7: expected the number of points > 0', 'found "0"'])
        if (allocated(error)) return
        call expect_error(error, 'negative_points.uff', 9, dataset58(r6, record7(2, -4, 1, 0.0_dp, 1.0_dp), data), &
                          [character(len=80) :: 'record 7: expected the number of points > 0', 'found "-4"'])
        if (allocated(error)) return
        call expect_error(error, 'spacing.uff', 9, dataset58(r6, record7(2, 2, 2, 0.0_dp, 1.0_dp), data), &
                          [character(len=80) :: 'record 7: expected the abscissa spacing 1 (even) or 0 (uneven)', &
                           'found "2"'])
        if (allocated(error)) return
        call expect_error(error, 'increment.uff', 9, dataset58(r6, r7(:43)//'  abc        '//r7(57:), data), &
                          [character(len=80) :: 'record 7: expected the abscissa increment (a number in columns ' &
                           //'44-56, 3I10,3E13.5)', 'found "abc"'])
        if (allocated(error)) return
        call expect_error(error, 'zero_increment.uff', 9, dataset58(r6, record7(2, 2, 1, 1.0_dp, 0.0_dp), data), &
                          [character(len=80) :: 'record 7: expected an abscissa increment > 0 for even spacing', &
                           'found "0.00000E+00"'])
        if (allocated(error)) return
        call expect_error(error, 'nan_minimum.uff', 9, dataset58(r6, r7(:30)//'          NaN'//r7(44:), data), &
                          [character(len=80) :: 'record 7: expected the abscissa minimum (a finite number in ' &
                           //'columns 31-43', 'found "NaN"'])
        if (allocated(error)) return
        call expect_error(error, 'inf_z.uff', 9, dataset58(r6, r7(:56)//'     Infinity', data), &
                          [character(len=80) :: 'record 7: expected the z-axis value (a finite number', &
                           'found "Infinity"'])
        if (allocated(error)) return
        call expect_error(error, 'overflow.uff', 9, dataset58(r6, r7(:56)//'  1.00000+999', data), &
                          [character(len=80) :: 'record 7: expected the z-axis value (a finite number', &
                           'found "1.00000+999"'])
        if (allocated(error)) return
        call expect_error(error, 'record7_long.uff', 9, dataset58(r6, r7(:69)//'    7', data), &
                          [character(len=80) :: 'record 7: expected nothing after column 69 (3I10,3E13.5)', &
                           'found "7"'])
        if (allocated(error)) return
        call expect_error(error, 'record9.uff', 11, replace_line(dataset58(r6, r7, data), 11, '  velocity'), &
                          [character(len=80) :: 'dataset 58 record 9: expected the specific data type (an ' &
                           //'integer in columns 1-10), found "velocity"'])
    end subroutine test_bad_header

    !> The text with its line `number` replaced.
    pure function replace_line(text, number, line) result(out)
        character(len=*), intent(in) :: text, line
        integer, intent(in) :: number
        character(len=:), allocatable :: out

        integer :: start, i, finish

        start = 1
        do i = 1, number - 1
            start = start + index(text(start:), new_line('a'))
        end do
        finish = start + index(text(start:), new_line('a')) - 1
        out = text(:start - 1)//line//text(finish:)
    end function replace_line

    subroutine test_bad_data(error)
        type(test_error), allocatable, intent(out) :: error

        character(len=*), parameter :: nl = new_line('a')
        character(len=*), parameter :: six = '  1.00000E+00  2.00000E+00  3.00000E+00  4.00000E+00  5.00000E+00' &
                                             //'  6.00000E+00'//nl
        character(len=80) :: r6

        r6 = record6(1, 3, 1, 3)
        call expect_error(error, 'garbage.uff', 14, dataset58(r6, record7(2, 8, 1, 0.0_dp, 1.0_dp), &
                                                              '  1.00000E+00  2.0O000E+00'//nl), &
                          [character(len=80) :: 'dataset 58 record 12: expected a number in columns 14-26 (6E13.5)', &
                           'found "2.0O000E+00"'])
        if (allocated(error)) return
        call expect_error(error, 'nan.uff', 15, dataset58(r6, record7(5, 4, 1, 0.0_dp, 1.0_dp), &
                                                          six//'          nan  1.00000E+00'//nl), &
                          [character(len=80) :: 'record 12: expected a finite number in columns 1-13 (6E13.5)', &
                           'found "nan"'])
        if (allocated(error)) return
        call expect_error(error, 'inf.uff', 14, dataset58(r6, record7(4, 2, 1, 0.0_dp, 1.0_dp), &
                                                          '  1.000000000000E+00                -Inf'//nl), &
                          [character(len=80) :: 'record 12: expected a finite number in columns 21-40 (4E20.12)', &
                           'found "-Inf"'])
        if (allocated(error)) return
        call expect_error(error, 'more_lines.uff', 15, dataset58(r6, record7(2, 6, 1, 0.0_dp, 1.0_dp), six//six), &
                          [character(len=80) :: 'record 12: expected the -1 line after the 6 points of record 7', &
                           'found more data: "  1.00000E+00'])
        if (allocated(error)) return
        call expect_error(error, 'more_fields.uff', 14, dataset58(r6, record7(2, 5, 1, 0.0_dp, 1.0_dp), six), &
                          [character(len=80) :: 'record 12: expected no more values after the points of record 7', &
                           'found "6.00000E+00" in columns 66-78 (6E13.5)'])
        if (allocated(error)) return
        call expect_error(error, 'short_line.uff', 14, dataset58(r6, record7(2, 8, 1, 0.0_dp, 1.0_dp), &
                                                                 six(:40)//nl//six), &
                          [character(len=80) :: 'record 12: expected 6 values on this line (6E13.5), found none in ' &
                           //'columns 40-52'])
        if (allocated(error)) return
        call expect_error(error, 'fewer.uff', 16, dataset58(r6, record7(2, 14, 1, 0.0_dp, 1.0_dp), &
                                                            six//six(:27)//nl), &
                          [character(len=120) :: 'dataset 58 record 12: expected 14 points (record 7 field 2, ' &
                           //'6E13.5), found 8 before the -1 line'])
        if (allocated(error)) return
        call expect_error(error, 'fewer_pairs.uff', 15, dataset58(r6, record7(5, 4, 1, 0.0_dp, 1.0_dp), six), &
                          [character(len=80) :: 'expected 4 points (record 7 field 2, 6E13.5), found 3 before', &
                           'the dataset is truncated or record 7 is wrong'])
        if (allocated(error)) return
        call expect_error(error, 'odd_values.uff', 16, dataset58(r6, record7(6, 3, 0, 0.0_dp, 0.0_dp), &
                          '  1.00000E+00  1.000000000000E+00  1.000000000000E+00'//nl//'  2.00000E+00' &
                          //'  1.000000000000E+00'//nl), &
                          [character(len=80) :: 'expected 3 points (record 7 field 2, E13.5,2E20.12), found 1 and 2 ' &
                           //'of the 3 values of point 2 before the -1 line'])
        if (allocated(error)) return
        call expect_error(error, 'tail.uff', 14, dataset58(r6, record7(4, 4, 1, 0.0_dp, 1.0_dp), &
                          '  1.000000000000E+00  2.000000000000E+00  3.000000000000E+00  4.000000000000E+00' &
                          //'  5.0'//nl), &
                          [character(len=80) :: 'record 12: expected nothing after column 80 (4E20.12), found "5.0"'])
        if (allocated(error)) return
        call expect_error(error, 'misaligned.uff', 14, dataset58(r6, record7(4, 2, 1, 0.0_dp, 1.0_dp), &
                          '     1.000000000000E+00     2.000000000000E+00'//nl), &
                          [character(len=80) :: 'record 12: expected a number in columns 1-20 (4E20.12), found ' &
                           //'"1.000000000000E"'])
        if (allocated(error)) return
        call expect_error(error, 'decreasing.uff', 15, dataset58(r6, record7(2, 4, 0, 0.0_dp, 0.0_dp), &
                          '  1.00000E+01  1.00000E+00  2.00000E+01  1.00000E+00  3.00000E+01  1.00000E+00'//nl &
                          //'  3.00000E+01  1.00000E+00'//nl), &
                          [character(len=80) :: 'record 12: expected abscissa values that increase (uneven spacing)', &
                           'found 30.0 at point 4 after 30.0'])
    end subroutine test_bad_data

    subroutine test_bad_nodes(error)
        type(test_error), allocatable, intent(out) :: error

        character(len=*), parameter :: nl = new_line('a')

        call expect_error(error, 'node15.uff', 3, '    -1'//nl//'    15'//nl//'         1         0         0' &
                          //'         1  1.00000E+00  2.0000xE+00  3.00000E+00'//nl//'    -1', &
                          [character(len=100) :: 'dataset 15 record 1: expected the y coordinate of node 1 (a number ' &
                           //'in columns 54-66, 4I10,1P3E13.5), found "2.0000xE+00"'])
        if (allocated(error)) return
        call expect_error(error, 'node2411.uff', 4, '    -1'//nl//'  2411'//nl//'         1         0         0' &
                          //'         1'//nl//'    -1', &
                          [character(len=100) :: 'dataset 2411 record 2: expected the coordinates of node 1 ' &
                           //'(1P3D25.16), found the -1 line'])
        if (allocated(error)) return
        call expect_error(error, 'label.uff', 3, '    -1'//nl//'    15'//nl//'       one'//nl//'    -1', &
                          [character(len=100) :: 'dataset 15 record 1: expected the node label (an integer in ' &
                           //'columns 1-10), found "one"'])
    end subroutine test_bad_nodes

end module test_uff_mod
