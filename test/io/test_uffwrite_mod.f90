!> The universal-file writer (greenconv_io_uff_write) read back by the project's reader
!> (greenconv_io_uff): every ordinate type in even and uneven spacing, nodes in datasets 15
!> and 2411, the header; values equal to the precision of their fields, every header field
!> equal; and every case the writer refuses, with its message and no file left behind.
module test_uffwrite_mod
    use, intrinsic :: iso_fortran_env, only: dp => real64
    use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
    use testsuite_mod, only: test_error, unittest_type, new_unittest, check, note
    use greenconv_core_error, only: error_type
    use greenconv_io_files, only: make_directory
    use greenconv_io_uff, only: uff_file, uff_function, uff_node, uff_axis, read_uff, uff_receptance
    use greenconv_io_uff_write, only: uff_header, write_uff, receptance_function, impulse_function
    use greenconv_model_point_modes, only: point_modes
    use greenconv_model_plate, only: tyre_plate, plate_modes, patch_receptance
    implicit none
    private

    public :: collect_uffwrite

    !> Scratch directory for the files the tests write.
    character(len=*), parameter :: scratch = 'build/test_scratch/uffwrite'
    !> Relative precision of an ES13.5 field (six significant digits).
    real(dp), parameter :: single_digits = 5.0e-6_dp
    !> Relative precision of an ES20.12 field (thirteen significant digits).
    real(dp), parameter :: double_digits = 5.0e-13_dp

contains

    !> Tests of greenconv_io_uff_write.
    subroutine collect_uffwrite(testsuite)
        type(unittest_type), allocatable, intent(out) :: testsuite(:)

        testsuite = [new_unittest('round trip: ordinate types 2, 4, 5, 6, even and uneven, dataset 15', &
                                  test_round_trip_15), &
                     new_unittest('round trip: nodes in dataset 2411 to 17 digits', test_round_trip_2411), &
                     new_unittest('receptance and impulse response functions: kinds, axes, grids', test_builders), &
                     new_unittest('refused: types, grids, values, fields, nodes, paths; no file left', test_refused), &
                     new_unittest('shipped data/patch_green.uff equals the plate model within its 1 % noise', &
                                  test_shipped_patch)]
    end subroutine collect_uffwrite

    !> Eight functions, one per ordinate type and spacing, with values over many decades
    !> (three-digit exponents included, written with one digit less) and every header field set.
    function sample_functions() result(functions)
        type(uff_function) :: functions(8)

        integer, parameter :: types(4) = [2, 4, 5, 6]
        integer :: k, i, n
        real(dp) :: x

        do k = 1, 8
            n = 3 + k
            functions(k)%id_lines = [character(len=80) :: 'function '//achar(48 + k)//' written by the test', &
                                     'run 7', '', &
                                     'load case A', 'last ID line']
            functions(k)%function_type = merge(4, 1, mod(k, 2) == 0)
            functions(k)%function_id = 100 + k
            functions(k)%version = k
            functions(k)%load_case = 2*k
            functions(k)%response_entity = 'PATCH'
            functions(k)%response_node = 10*k
            functions(k)%response_direction = 3
            functions(k)%reference_entity = 'ROAD'
            functions(k)%reference_node = 1234567890
            functions(k)%reference_direction = -3
            functions(k)%ordinate_type = types(mod(k - 1, 4) + 1)
            functions(k)%even = k <= 4
            functions(k)%z_value = 0.5_dp*k
            functions(k)%abscissa_axis = uff_axis(18, 0, 0, 0, 'Frequency', 'Hz')
            functions(k)%numerator = uff_axis(11, 1, 0, 0, 'Velocity', 'm/s')
            functions(k)%denominator = uff_axis(13, 0, 1, 0, 'Force', 'N')
            functions(k)%z_axis = uff_axis(0, 0, 0, 0, 'NONE', 'NONE')
            allocate (functions(k)%abscissa(n), functions(k)%ordinate(n))
            do i = 1, n
                if (functions(k)%even) then
                    functions(k)%abscissa(i) = 2.5_dp + (i - 1)*0.125_dp
                else
                    functions(k)%abscissa(i) = 1.0e-3_dp*i**2 + 0.1234567_dp*i
                end if
                x = 10.0_dp**(-150 + 50*mod(i, 7))*(1.0_dp + 0.123456789012345_dp*i)
                functions(k)%ordinate(i) = cmplx(merge(-x, x, mod(i, 2) == 0), 0.0_dp, kind=dp)
                if (functions(k)%ordinate_type >= 5) functions(k)%ordinate(i)%im = 3.0_dp*x/7.0_dp
            end do
        end do
    end function sample_functions

    !> Nodes of a 4 x 3 patch with coordinates that need all digits.
    function sample_nodes() result(nodes)
        type(uff_node) :: nodes(12)

        integer :: i

        do i = 1, 12
            nodes(i) = uff_node(label=i, definition_system=0, displacement_system=1, color=11, &
                                position=[0.9125_dp + 0.03_dp*mod(i - 1, 4)/7.0_dp, 0.05_dp*((i - 1)/4 + 1), &
                                          -1.0e-7_dp*i])
        end do
    end function sample_nodes

    subroutine test_round_trip_15(error)
        type(test_error), allocatable, intent(out) :: error

        call round_trip(15, single_digits, error)
    end subroutine test_round_trip_15

    subroutine test_round_trip_2411(error)
        type(test_error), allocatable, intent(out) :: error

        call round_trip(2411, 1.0e-16_dp, error)
    end subroutine test_round_trip_2411

    !> Write the sample functions and nodes, read them back, compare field by field.
    subroutine round_trip(node_dataset, node_digits, error)
        integer, intent(in) :: node_dataset
        real(dp), intent(in) :: node_digits
        type(test_error), allocatable, intent(out) :: error

        type(uff_function) :: written(8)
        type(uff_node) :: nodes(12)
        type(uff_file) :: file
        type(error_type), allocatable :: fail
        character(len=:), allocatable :: path
        real(dp) :: worst_single, worst_double, worst_x, worst_node, digits
        integer :: k, i

        written = sample_functions()
        nodes = sample_nodes()
        path = scratch//'/round_trip_'//trim(merge('15  ', '2411', node_dataset == 15))//'.uff'
        call prepare(fail)
        call write_uff(path, written, nodes, fail, header=uff_header(model='test model', &
                       description='eight functions, twelve nodes', date='01-Jan-26'), node_dataset=node_dataset)
        call check(error, .not. allocated(fail), 'write_uff failed: '//message_of(fail))
        if (allocated(error)) return
        call read_uff(path, file, fail)
        call check(error, .not. allocated(fail), 'read_uff failed on the written file: '//message_of(fail))
        if (allocated(error)) return
        call check(error, size(file%functions) == 8 .and. size(file%nodes) == 12 .and. size(file%skipped) == 1, &
                   'expected 8 functions, 12 nodes and the header (151) skipped')
        if (allocated(error)) return
        call check(error, file%skipped(1)%dataset == 151, 'expected dataset 151 first')
        if (allocated(error)) return
        worst_single = 0.0_dp
        worst_double = 0.0_dp
        worst_x = 0.0_dp
        do k = 1, 8
            call compare_header(written(k), file%functions(k), error)
            if (allocated(error)) return
            digits = merge(single_digits, double_digits, any(written(k)%ordinate_type == [2, 5]))
            do i = 1, size(written(k)%ordinate)
                call relative(written(k)%ordinate(i)%re, file%functions(k)%ordinate(i)%re, digits, &
                              worst_single, worst_double, error)
                if (.not. allocated(error)) call relative(written(k)%ordinate(i)%im, file%functions(k)%ordinate(i)%im, &
                                                          digits, worst_single, worst_double, error)
                if (allocated(error)) return
                worst_x = max(worst_x, abs(written(k)%abscissa(i) - file%functions(k)%abscissa(i)) &
                              /abs(written(k)%abscissa(i)))
            end do
        end do
        worst_node = 0.0_dp
        do i = 1, 12
            call check(error, file%nodes(i)%label == i .and. file%nodes(i)%displacement_system == 1 .and. &
                       file%nodes(i)%color == 11 .and. file%nodes(i)%dataset == node_dataset, &
                       'node integers differ after the round trip')
            if (allocated(error)) return
            worst_node = max(worst_node, maxval(abs(file%nodes(i)%position - nodes(i)%position) &
                                                /abs(nodes(i)%position)))
        end do
        call note('single rel.', worst_single)
        call note('double rel.', worst_double)
        call note('abscissa rel.', worst_x)
        call note('node rel.', worst_node)
        call check(error, worst_x <= single_digits .and. worst_node <= node_digits, &
                   'abscissa or node coordinates differ by more than the precision of their fields')
    end subroutine round_trip

    !> Every field of records 1 to 11 equal.
    subroutine compare_header(a, b, error)
        type(uff_function), intent(in) :: a, b
        type(test_error), allocatable, intent(out) :: error

        logical :: same

        same = all(a%id_lines == b%id_lines) .and. a%function_type == b%function_type &
               .and. a%function_id == b%function_id .and. a%version == b%version .and. a%load_case == b%load_case &
               .and. a%response_entity == b%response_entity .and. a%response_node == b%response_node &
               .and. a%response_direction == b%response_direction .and. a%reference_entity == b%reference_entity &
               .and. a%reference_node == b%reference_node .and. a%reference_direction == b%reference_direction &
               .and. a%ordinate_type == b%ordinate_type .and. (a%even .eqv. b%even) .and. a%z_value == b%z_value &
               .and. size(a%ordinate) == size(b%ordinate) .and. same_axis(a%abscissa_axis, b%abscissa_axis) &
               .and. same_axis(a%numerator, b%numerator) .and. same_axis(a%denominator, b%denominator) &
               .and. same_axis(a%z_axis, b%z_axis)
        call check(error, same, 'a header field of "'//trim(a%id_lines(1))//'" differs after the round trip')
    end subroutine compare_header

    pure logical function same_axis(a, b)
        type(uff_axis), intent(in) :: a, b

        same_axis = a%data_type == b%data_type .and. a%length_exponent == b%length_exponent &
                    .and. a%force_exponent == b%force_exponent .and. a%temperature_exponent == b%temperature_exponent &
                    .and. a%label == b%label .and. a%units == b%units
    end function same_axis

    !> Check |read - written| <= digits*|written| and track the worst single and double error.
    subroutine relative(written, read, digits, worst_single, worst_double, error)
        real(dp), intent(in) :: written, read, digits
        real(dp), intent(inout) :: worst_single, worst_double
        type(test_error), allocatable, intent(out) :: error

        real(dp) :: deviation, precision

        ! a three-digit exponent costs the field one digit
        precision = digits
        if (abs(written) >= 1.0e99_dp .or. abs(written) < 1.0e-99_dp) precision = 10.0_dp*digits
        deviation = 0.0_dp
        if (written /= 0.0_dp) deviation = abs(read - written)/abs(written)
        if (digits > 1.0e-8_dp) then
            worst_single = max(worst_single, deviation)
        else
            worst_double = max(worst_double, deviation)
        end if
        call check(error, abs(read - written) <= precision*abs(written), 'a value differs by more than its field''s ' &
                   //'precision after the round trip')
    end subroutine relative

    !> The builders give what the reader classifies as receptances, on the grid given.
    subroutine test_builders(error)
        type(test_error), allocatable, intent(out) :: error

        type(uff_function) :: functions(2)
        type(uff_file) :: file
        type(error_type), allocatable :: fail
        complex(dp) :: g(401)
        real(dp) :: h(300)
        integer :: k

        g = [(cmplx(1.0_dp/(1.0_dp + k), -0.5_dp/(1.0_dp + k**2), kind=dp), k=0, 400)]
        h = [(exp(-0.01_dp*k)*sin(0.3_dp*k), k=0, 299)]
        functions(1) = receptance_function([3, 3], [7, 3], 0.0_dp, 4.0_dp, g, 'G_3,7')
        functions(2) = impulse_function([7, 3], [3, 3], 0.0_dp, 5.0e-5_dp, h, 'g_7,3')
        call prepare(fail)
        call write_uff(scratch//'/builders.uff', functions, [uff_node ::], fail)
        if (.not. allocated(fail)) call read_uff(scratch//'/builders.uff', file, fail)
        call check(error, .not. allocated(fail), 'writing or reading failed: '//message_of(fail))
        if (allocated(error)) return
        call check(error, file%functions(1)%function_type == 4 .and. file%functions(2)%function_type == 1 .and. &
                   all(file%functions%kind == uff_receptance) .and. file%functions(1)%ordinate_type == 6 .and. &
                   file%functions(2)%ordinate_type == 4 .and. file%functions(1)%abscissa_axis%data_type == 18 &
                   .and. file%functions(2)%abscissa_axis%data_type == 17 .and. file%functions(1)%response_node == 3 &
                   .and. file%functions(1)%reference_node == 7, 'function types, kinds, axes or nodes differ')
        if (allocated(error)) return
        call note('f_max [Hz]', file%functions(1)%abscissa(401))
        call note('G rel.', maxval(abs(file%functions(1)%ordinate - g)/abs(g)))
        call note('g abs.', maxval(abs(file%functions(2)%ordinate%re - h)))
        call check(error, file%functions(1)%abscissa(401) == 1600.0_dp .and. &
                   abs(file%functions(2)%abscissa(300) - 299*5.0e-5_dp) < 1.0e-15_dp .and. &
                   maxval(abs(file%functions(1)%ordinate - g)/abs(g)) < double_digits .and. &
                   maxval(abs(file%functions(2)%ordinate%re - h)) < double_digits, 'grids or values differ')
    end subroutine test_builders

    !> The shipped file read back: 144 receptances on 0..600 Hz by 2 Hz and 12 nodes; each line
    !> divided by the noiseless G of the plate (xi = 0.02) at the file's node coordinates deviates from 1
    !> by the stated 1 % rms of complex noise.
    subroutine test_shipped_patch(error)
        type(test_error), allocatable, intent(out) :: error

        type(uff_file) :: file
        type(point_modes) :: description
        type(error_type), allocatable :: fail
        complex(dp), allocatable :: g(:, :)
        real(dp) :: x(12), y(12), squares, worst
        integer :: k, f, i, j

        call read_uff('data/patch_green.uff', file, fail)
        call check(error, .not. allocated(fail), 'read_uff failed: '//message_of(fail))
        if (allocated(error)) return
        call check(error, size(file%functions) == 144 .and. size(file%nodes) == 12, 'expected 144 functions, 12 nodes')
        if (allocated(error)) return
        x = file%nodes%position(1)
        y = file%nodes%position(2)
        call plate_modes(tyre_plate(damping_ratio=0.02_dp), x, y, 1.0e4_dp, description, fail)
        call check(error, .not. allocated(fail), 'plate_modes failed')
        if (allocated(error)) return
        squares = 0.0_dp
        worst = 0.0_dp
        do f = 1, size(file%functions(1)%ordinate)
            g = patch_receptance(description, 2.0_dp*acos(-1.0_dp)*file%functions(1)%abscissa(f))
            do k = 1, 144
                i = file%functions(k)%response_node
                j = file%functions(k)%reference_node
                squares = squares + abs(file%functions(k)%ordinate(f)/g(i, j) - 1.0_dp)**2
                worst = max(worst, abs(file%functions(k)%ordinate(f)/g(i, j) - 1.0_dp))
            end do
        end do
        squares = sqrt(squares/(144*size(file%functions(1)%ordinate)))
        call note('rms |G_file/G - 1|', squares)
        call note('max |G_file/G - 1|', worst)
        call note('f_max [Hz]', file%functions(1)%abscissa(size(file%functions(1)%abscissa)))
        call check(error, abs(squares - 0.01_dp) < 5.0e-4_dp .and. worst < 0.06_dp, &
                   'the shipped file differs from the plate model by more than its 1 % noise')
    end subroutine test_shipped_patch

    !> Each case the writer refuses: one message naming what to change, and no file.
    subroutine test_refused(error)
        type(test_error), allocatable, intent(out) :: error

        type(uff_function) :: good(1), bad(1)
        type(uff_node) :: nodes(1)
        character(len=:), allocatable :: path
        integer :: case

        good(1) = receptance_function([1, 3], [1, 3], 0.0_dp, 1.0_dp, [(1.0_dp, 0.5_dp), (2.0_dp, 0.0_dp)], 'ok')
        nodes(1) = uff_node(label=1)
        do case = 1, 9
            bad = good
            select case (case)
            case (1)
                bad(1)%ordinate_type = 3
                call expect_refused(bad, nodes, 15, 'ordinate type', error)
            case (2)
                bad(1)%abscissa = [0.0_dp, 0.0_dp]
                call expect_refused(bad, nodes, 15, 'set even = .false.', error)
            case (3)
                bad(1)%ordinate_type = 4
                call expect_refused(bad, nodes, 15, 'use type 5 or 6', error)
            case (4)
                bad(1)%ordinate(2) = cmplx(ieee_value(1.0_dp, ieee_quiet_nan), 0.0_dp, kind=dp)
                call expect_refused(bad, nodes, 15, 'finite', error)
            case (5)
                bad(1)%response_direction = 12345
                call expect_refused(bad, nodes, 15, 'the response direction 12345 does not fit', error)
            case (6)
                bad(1)%reference_entity = 'A_VERY_LONG_NAME'
                call expect_refused(bad, nodes, 15, 'at most 10 characters', error)
            case (7)
                bad(1)%id_lines(3) = '    -1'
                call expect_refused(bad, nodes, 15, 'ID line 3', error)
            case (8)
                call expect_refused(bad, [uff_node(label=0)], 15, 'label >= 1', error)
            case (9)
                call expect_refused(bad, nodes, 16, 'dataset 15 or 2411', error)
            end select
            if (allocated(error)) return
        end do
        path = scratch//'/no_such_directory/file.uff'
        block
            type(error_type), allocatable :: fail
            call write_uff(path, good, nodes, fail)
            call check(error, allocated(fail), 'expected an error for a path in a missing directory')
            if (allocated(error)) return
            call check(error, index(fail%message, 'directory exists') > 0, 'unhelpful message: '//fail%message)
        end block
    end subroutine test_refused

    !> write_uff must refuse, with `expected` in the message, and leave no file.
    subroutine expect_refused(functions, nodes, node_dataset, expected, error)
        type(uff_function), intent(in) :: functions(:)
        type(uff_node), intent(in) :: nodes(:)
        integer, intent(in) :: node_dataset
        character(len=*), intent(in) :: expected
        type(test_error), allocatable, intent(out) :: error

        type(error_type), allocatable :: fail
        character(len=*), parameter :: path = scratch//'/refused.uff'
        logical :: exists

        call prepare(fail)
        call write_uff(path, functions, nodes, fail, node_dataset=node_dataset)
        inquire (file=path, exist=exists)
        call check(error, allocated(fail), 'expected write_uff to refuse a case ('//expected//')')
        if (allocated(error)) return
        call check(error, index(fail%message, expected) > 0 .and. .not. exists, 'expected "'//expected &
                   //'" in the message and no file, found: '//fail%message)
    end subroutine expect_refused

    !> The scratch directory, and no file refused.uff left from an earlier case.
    subroutine prepare(fail)
        type(error_type), allocatable, intent(out) :: fail

        integer :: unit, stat

        call make_directory('build/test_scratch', fail)
        call make_directory(scratch, fail)
        open (newunit=unit, file=scratch//'/refused.uff', status='old', iostat=stat)
        if (stat == 0) close (unit, status='delete')
    end subroutine prepare

    pure function message_of(fail) result(text)
        type(error_type), allocatable, intent(in) :: fail
        character(len=:), allocatable :: text

        text = ''
        if (allocated(fail)) text = fail%message
    end function message_of

end module test_uffwrite_mod
