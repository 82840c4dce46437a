!> Universal files that were read wrong or at a great cost: a point count of record
!> 7 held against the lines before anything is allocated, a UTF-8 byte-order mark, a node
!> given twice with other coordinates, a Green's matrix that would not be square, directions
!> other than +Z, real-valued receptances, datasets left out for their function type, and a
!> value of 1e308. Each is refused with one message naming the file, line, record and field,
!> or read right.
module test_uffchecks_mod
    use, intrinsic :: iso_fortran_env, only: dp => real64, int64
    use testsuite_mod, only: test_error, unittest_type, new_unittest, check, note
    use greenconv_core_error, only: error_type
    use greenconv_core_text, only: int_text
    use greenconv_io_files, only: make_directory
    use greenconv_io_columns, only: byte_order_mark
    use greenconv_io_uff, only: uff_file, uff_function, uff_node, read_uff
    use greenconv_io_uff_write, only: write_uff, receptance_function
    use greenconv_model_green_matrix_file, only: green_matrix, read_green_matrix
    use greenconv_model_frf, only: frf_type, read_frf
    use test_patch_mod, only: two_point_file
    use scene_text_mod, only: write_text, message_of
    implicit none
    private

    public :: collect_uffchecks

    !> Scratch directory for the files the tests write.
    character(len=*), parameter :: scratch = 'build/test_scratch/uffchecks'

contains

    !> Tests of the universal-file checks.
    subroutine collect_uffchecks(testsuite)
        type(unittest_type), allocatable, intent(out) :: testsuite(:)

        testsuite = [new_unittest('record 7 claims of 1e9 and 3e8 points refused before allocating', test_point_claim), &
                     new_unittest('a UTF-8 byte-order mark is skipped', test_byte_order_mark), &
                     new_unittest('a node label repeated with other coordinates is refused', test_repeated_node), &
                     new_unittest('an extra reference or response node is refused (not square)', test_one_way_node), &
                     new_unittest('directions: X refused, -Z/-Z as +Z, +Z/-Z with its sign', test_directions), &
                     new_unittest('a real-valued receptance is refused', test_real_receptance), &
                     new_unittest('a G left out for its function type is named', test_left_out), &
                     new_unittest('a value of 1e308 is refused at its line', test_huge_value), &
                     new_unittest('a receptance file value of 1e308 is refused at its line', test_huge_frf), &
                     new_unittest('dataset 164: SI read, other units and bad factors refused at record 2', &
                                  test_units_record)]
    end subroutine collect_uffchecks

    !> A file with one receptance whose record 7 claims 1e9 or 3e8 points: refused at once,
    !> with the count claimed and the points found, without taking the memory (the grid of
    !> even spacing was built from the claim before the data were counted: 8 GB for 1e9).
    subroutine test_point_claim(error)
        type(test_error), allocatable, intent(out) :: error

        character(len=*), parameter :: claims(2) = ['1000000000', ' 300000000']
        type(uff_function), allocatable :: functions(:)
        type(uff_node), allocatable :: nodes(:)
        type(uff_file) :: file
        type(error_type), allocatable :: fail
        character(len=:), allocatable :: path
        integer(int64) :: start, finish, rate
        integer :: case

        call make_directory(scratch, fail)
        do case = 1, size(claims)
            call two_point_file(functions, nodes)
            path = scratch//'/claim.uff'
            call write_uff(path, functions(1:1), nodes, fail)
            call check(error, .not. allocated(fail), 'write_uff failed')
            if (allocated(error)) return
            ! record 7 is the 7th line after the dataset number 58: columns 11-20 hold the point count
            call replace_columns(path, line_of(path, '    58') + 7, 11, claims(case))
            call system_clock(start, rate)
            call read_uff(path, file, fail)
            call system_clock(finish)
            call note('seconds to refuse', real(finish - start, dp)/real(rate, dp))
            call check(error, allocated(fail), 'a claim of '//trim(adjustl(claims(case)))//' points was accepted')
            if (allocated(error)) return
            call check(error, index(fail%message, ': universal file dataset 58 record 12: expected ' &
                                    //trim(adjustl(claims(case)))//' points (record 7 field 2') > 0 .and. &
                       index(fail%message, path//':') == 1 .and. index(fail%message, 'found 51 before the -1 line') > 0, &
                       'message: '//fail%message)
            if (allocated(error)) return
            call check(error, real(finish - start, dp)/real(rate, dp) < 1.0_dp, 'took a second or more')
            if (allocated(error)) return
        end do
    end subroutine test_point_claim

    !> The same file with and without a byte-order mark before its first `-1` reads the same.
    subroutine test_byte_order_mark(error)
        type(test_error), allocatable, intent(out) :: error

        type(uff_function), allocatable :: functions(:)
        type(uff_node), allocatable :: nodes(:)
        type(uff_file) :: plain, marked
        type(error_type), allocatable :: fail
        character(len=:), allocatable :: path

        call make_directory(scratch, fail)
        call two_point_file(functions, nodes)
        path = scratch//'/bom.uff'
        call write_uff(path, functions, nodes, fail)
        call read_uff(path, plain, fail)
        call check(error, .not. allocated(fail), 'the file without a mark was refused')
        if (allocated(error)) return
        call replace_columns(path, 1, 1, byte_order_mark//'    -1', whole=.true.)
        call read_uff(path, marked, fail)
        call check(error, .not. allocated(fail), 'refused with a byte-order mark: '//message_of(fail))
        if (allocated(error)) return
        call check(error, size(marked%functions) == size(plain%functions) .and. size(marked%nodes) == 2 .and. &
                   all(marked%functions(4)%ordinate == plain%functions(4)%ordinate), 'read differently')
    end subroutine test_byte_order_mark

    !> Node 1 again with other coordinates: refused naming both lines; again with the same
    !> coordinates: accepted.
    subroutine test_repeated_node(error)
        type(test_error), allocatable, intent(out) :: error

        type(uff_function), allocatable :: functions(:)
        type(uff_node), allocatable :: nodes(:)
        type(uff_file) :: file
        type(error_type), allocatable :: fail
        character(len=:), allocatable :: path

        call make_directory(scratch, fail)
        call two_point_file(functions, nodes)
        path = scratch//'/repeated_same.uff'
        call write_uff(path, functions, [nodes, nodes(1)], fail)
        call read_uff(path, file, fail)
        call check(error, .not. allocated(fail), 'a node repeated with the same coordinates: '//message_of(fail))
        if (allocated(error)) return
        nodes = [nodes, uff_node(label=1, position=[0.5_dp, 0.0_dp, 0.0_dp])]
        path = scratch//'/repeated_other.uff'
        call write_uff(path, functions, nodes, fail)
        call read_uff(path, file, fail)
        call check(error, allocated(fail), 'node 1 given twice with other coordinates was accepted')
        if (allocated(error)) return
        call check(error, index(fail%message, 'node 1 is given again with other coordinates (x, y, z = 0.5') > 0 &
                   .and. index(fail%message, 'than at line') > 0 .and. index(fail%message, 'dataset 15') > 0, &
                   'message: '//fail%message)
    end subroutine test_repeated_node

    !> A G_13 with node 3 never a response node, and a G_31 with node 3 never a reference node.
    subroutine test_one_way_node(error)
        type(test_error), allocatable, intent(out) :: error

        type(uff_function), allocatable :: functions(:)
        type(uff_node), allocatable :: nodes(:)
        character(len=*), parameter :: expected(2) = [character(len=80) :: &
            'node 3 is a reference node here but never a response node', &
            'node 3 is a response node here but never a reference node']
        integer :: case

        do case = 1, 2
            call two_point_file(functions, nodes)
            if (case == 1) then
                functions = [functions, receptance_function([1, 3], [3, 3], 0.0_dp, 2.0_dp, functions(1)%ordinate, 'G')]
            else
                functions = [functions, receptance_function([3, 3], [1, 3], 0.0_dp, 2.0_dp, functions(1)%ordinate, 'G')]
            end if
            nodes = [nodes, uff_node(label=3, position=[0.06_dp, 0.0_dp, 0.0_dp])]
            call expect_refused('one_way.uff', functions, nodes, [character(len=80) :: expected(case), &
                                'dataset 58 record 6', 'not square'], error)
            if (allocated(error)) return
        end do
    end subroutine test_one_way_node

    !> X/X is refused naming the directions; -Z/-Z reads as +Z/+Z; +Z/-Z gets the opposite sign.
    subroutine test_directions(error)
        type(test_error), allocatable, intent(out) :: error

        type(uff_function), allocatable :: functions(:)
        type(uff_node), allocatable :: nodes(:)
        type(green_matrix) :: plus, matrix
        type(error_type), allocatable :: fail
        character(len=:), allocatable :: path
        integer :: k

        call make_directory(scratch, fail)
        call two_point_file(functions, nodes)
        path = scratch//'/plus_z.uff'
        call write_uff(path, functions, nodes, fail)
        call read_green_matrix(path, plus, fail)
        call check(error, .not. allocated(fail), '+Z refused: '//message_of(fail))
        if (allocated(error)) return
        do k = 1, size(functions)
            functions(k)%response_direction = 1
            functions(k)%reference_direction = 1
        end do
        call expect_refused('x.uff', functions, nodes, [character(len=80) :: 'record 6: expected the response and ' &
                            //'reference directions along Z', 'found response 1+X and reference 1+X'], error)
        if (allocated(error)) return
        do k = 1, size(functions)
            functions(k)%response_direction = -3
            functions(k)%reference_direction = -3
        end do
        path = scratch//'/minus_z.uff'
        call write_uff(path, functions, nodes, fail)
        call read_green_matrix(path, matrix, fail)
        call check(error, .not. allocated(fail), '-Z/-Z refused: '//message_of(fail))
        if (allocated(error)) return
        call check(error, all(matrix%g == plus%g), '-Z/-Z differs from +Z/+Z')
        if (allocated(error)) return
        do k = 1, size(functions)
            functions(k)%response_direction = 3
        end do
        path = scratch//'/plus_minus_z.uff'
        call write_uff(path, functions, nodes, fail)
        call read_green_matrix(path, matrix, fail)
        call check(error, .not. allocated(fail), '+Z/-Z refused: '//message_of(fail))
        if (allocated(error)) return
        call check(error, all(matrix%g == -plus%g), '+Z/-Z is not the negative of +Z/+Z')
    end subroutine test_directions

    !> Receptances written as real double (ordinate data type 4) are refused naming the type.
    subroutine test_real_receptance(error)
        type(test_error), allocatable, intent(out) :: error

        type(uff_function), allocatable :: functions(:)
        type(uff_node), allocatable :: nodes(:)
        integer :: k

        call two_point_file(functions, nodes)
        do k = 1, size(functions)
            functions(k)%ordinate_type = 4
            functions(k)%ordinate = cmplx(functions(k)%ordinate%re, 0.0_dp, dp)
        end do
        call expect_refused('real.uff', functions, nodes, [character(len=80) :: ': universal file dataset 58 ' &
                            //'record 7: expected complex values', 'found real-valued data (type 4)'], error)
    end subroutine test_real_receptance

    !> G_21 written as function type 12 (spectrum): the missing-G message says it was left out.
    subroutine test_left_out(error)
        type(test_error), allocatable, intent(out) :: error

        type(uff_function), allocatable :: functions(:)
        type(uff_node), allocatable :: nodes(:)

        call two_point_file(functions, nodes)
        functions(3)%function_type = 12
        call expect_refused('left_out.uff', functions, nodes, [character(len=80) :: &
                            'missing G for response node 2, reference node 1', 'for this pair was left out', &
                            'function type (record 6 field 1) is 12 (spectrum), not 4'], error)
    end subroutine test_left_out

    !> One G_ij of 1e308 is refused at the line that holds it, with the point and frequency.
    subroutine test_huge_value(error)
        type(test_error), allocatable, intent(out) :: error

        type(uff_function), allocatable :: functions(:)
        type(uff_node), allocatable :: nodes(:)
        type(green_matrix) :: matrix
        type(error_type), allocatable :: fail
        character(len=200) :: buffer
        character(len=:), allocatable :: path
        integer :: line, unit, k, stat

        call two_point_file(functions, nodes)
        functions(2)%ordinate(7) = cmplx(1.0e308_dp, 0.0_dp, dp)
        call expect_refused('huge.uff', functions, nodes, [character(len=80) :: &
                            ': universal file dataset 58 record 12: expected values of at most 1.0E+10', &
                            'found 1.0E+308 + 0.0i at point 7 (12.0 Hz)'], error)
        if (allocated(error)) return
        ! the line named holds the value
        path = scratch//'/huge.uff'
        call read_green_matrix(path, matrix, fail)
        k = len(path) + 2
        read (fail%message(k:k + index(fail%message(k:), ':') - 2), *, iostat=stat) line
        buffer = ''
        open (newunit=unit, file=path, status='old', action='read')
        do k = 1, line
            read (unit, '(a)', iostat=stat) buffer
        end do
        close (unit)
        call check(error, index(buffer, 'E+308') > 0, 'line '//int_text(line)//' holds no 1e308: '//trim(buffer))
    end subroutine test_huge_value

    !> The same in a column receptance file (f, Re G, Im G).
    subroutine test_huge_frf(error)
        type(test_error), allocatable, intent(out) :: error

        type(frf_type) :: frf
        type(error_type), allocatable :: fail
        character(len=:), allocatable :: path
        integer :: unit, l

        call make_directory(scratch, fail)
        path = scratch//'/huge.frf'
        open (newunit=unit, file=path, status='replace', action='write')
        write (unit, '(a)') '# f [Hz]  Re G [m/N]  Im G [m/N]'
        do l = 0, 9
            write (unit, '(i0, 2es14.3e3)') l, merge(1.0e308_dp, 1.0e-6_dp, l == 4), -1.0e-7_dp
        end do
        close (unit)
        call read_frf(path, frf, fail)
        call check(error, allocated(fail), '1e308 accepted')
        if (allocated(error)) return
        call check(error, index(fail%message, path//':6: expected Re G and Im G of at most 1.0E+10 m/N in ' &
                                //'magnitude, found 1.0E+308') == 1, 'message: '//fail%message)
    end subroutine test_huge_frf

    ! ---- helpers ---------------------------------------------------------------------------

    !> Write the functions and nodes to `name` in the scratch directory and expect
    !> read_green_matrix to refuse it with a message holding every piece of `expected`.
    subroutine expect_refused(name, functions, nodes, expected, error)
        character(len=*), intent(in) :: name, expected(:)
        type(uff_function), intent(in) :: functions(:)
        type(uff_node), intent(in) :: nodes(:)
        type(test_error), allocatable, intent(out) :: error

        type(green_matrix) :: matrix
        type(error_type), allocatable :: fail
        character(len=:), allocatable :: path
        integer :: k

        call make_directory(scratch, fail)
        path = scratch//'/'//name
        call write_uff(path, functions, nodes, fail)
        call check(error, .not. allocated(fail), 'write_uff failed: '//message_of(fail))
        if (allocated(error)) return
        call read_green_matrix(path, matrix, fail)
        call check(error, allocated(fail), name//': accepted')
        if (allocated(error)) return
        call check(error, index(fail%message, path) == 1, name//': the message does not start with the file: ' &
                   //fail%message)
        do k = 1, size(expected)
            if (allocated(error)) return
            call check(error, index(fail%message, trim(expected(k))) > 0, name//': expected "'//trim(expected(k)) &
                       //'" in "'//fail%message//'"')
        end do
    end subroutine expect_refused

    !> Number of the first line of a text file that is `text` (0 when none).
    integer function line_of(path, text)
        character(len=*), intent(in) :: path, text

        character(len=200) :: buffer
        integer :: unit, stat

        line_of = 0
        open (newunit=unit, file=path, status='old', action='read')
        do
            read (unit, '(a)', iostat=stat) buffer
            if (stat /= 0) exit
            line_of = line_of + 1
            if (buffer == text) then
                close (unit)
                return
            end if
        end do
        close (unit)
        line_of = 0
    end function line_of

    !> Replace line `line_number` of a text file from column `first` by `text` (the whole line
    !> when `whole`).
    subroutine replace_columns(path, line_number, first, text, whole)
        character(len=*), intent(in) :: path, text
        integer, intent(in) :: line_number, first
        logical, intent(in), optional :: whole

        character(len=200), allocatable :: lines(:)
        character(len=200) :: buffer
        integer :: unit, stat, n, k

        open (newunit=unit, file=path, status='old', action='read')
        n = 0
        do
            read (unit, '(a)', iostat=stat) buffer
            if (stat /= 0) exit
            n = n + 1
        end do
        rewind (unit)
        allocate (lines(n))
        do k = 1, n
            read (unit, '(a)') lines(k)
        end do
        close (unit)
        if (present(whole)) then
            lines(line_number) = text
        else
            lines(line_number)(first:first + len(text) - 1) = text
        end if
        open (newunit=unit, file=path, status='replace', action='write')
        do k = 1, n
            write (unit, '(a)') trim(lines(k))
        end do
        close (unit)
    end subroutine replace_columns

    !> pyuff's fixture with two receptances and a dataset 164 stating SI (line 12) reads; the
    !> same with the factors of millimetres and newtons (1000, 1), whose receptances would be
    !> read 1000 times too large as SI, is refused at record 2 naming the factors (dataset 58 is
    !> read in SI only); a factor of 0, a word for a factor, and two datasets 164 that disagree
    !> are refused with their line and record.
    subroutine test_units_record(error)
        type(test_error), allocatable, intent(out) :: error

        character(len=*), parameter :: source = 'test/data/uff/skipped_datasets.uff'
        character(len=*), parameter :: one = '   1.0000000000000000D+00'
        character(len=*), parameter :: mm = '   1.0000000000000000D+03'//one//one
        character(len=*), parameter :: zero = '   0.0000000000000000D+00'//one//one
        character(len=*), parameter :: word = one//'   newton                '//one
        character(len=80) :: variants(3)
        character(len=100) :: expect(3)
        type(uff_file) :: file
        type(error_type), allocatable :: fail
        character(len=:), allocatable :: text
        integer :: k

        call make_directory(scratch, fail)
        call read_uff(source, file, fail)
        call check(error, .not. allocated(fail), 'the fixture with a dataset 164 in SI: '//message_of(fail))
        if (allocated(error)) return
        variants = [character(len=80) :: mm, zero, word]
        expect(1) = 'units.uff:14: universal file dataset 164 record 2: expected SI units'
        expect(2) = 'units.uff:14: universal file dataset 164 record 2: expected the length factor to SI > 0'
        expect(3) = 'units.uff:14: universal file dataset 164 record 2: expected the force factor'
        do k = 1, size(variants)
            text = file_with(source, 14, trim(variants(k)))
            call write_text(scratch//'/units.uff', text)
            call read_uff(scratch//'/units.uff', file, fail)
            call check(error, allocated(fail), 'dataset 164 variant '//int_text(k)//' accepted')
            if (allocated(error)) return
            call check(error, fail%stat == 2 .and. index(fail%message, trim(expect(k))) > 0 .and. &
                       index(fail%message, new_line('a')) == 0, 'expected "'//trim(expect(k))//'", found "' &
                       //fail%message//'"')
            if (allocated(error)) return
        end do
        call check(error, index(fail%message, 'found "newton"') > 0, 'the word found: '//fail%message)
        if (allocated(error)) return
        ! a dataset 164 in mm before the one in SI: the file has two unit systems
        text = file_with(source, 10, '    -1'//new_line('a')//'    -1'//new_line('a')//'   164'//new_line('a') &
                         //'        10mm (newton)                2'//new_line('a')//mm//new_line('a') &
                         //'   2.7314999999999998D+02'//new_line('a')//'    -1')
        call write_text(scratch//'/units.uff', text)
        call read_uff(scratch//'/units.uff', file, fail)
        call check(error, allocated(fail), 'two datasets 164 that disagree accepted')
        if (allocated(error)) return
        call check(error, index(fail%message, 'units.uff:20: universal file dataset 164 record 2: expected the units ' &
                               //'of the dataset 164 at line 11') > 0, 'two unit systems: '//fail%message)
    end subroutine test_units_record

    !> The lines of a file, line `at` replaced by `text` (which may hold several lines).
    function file_with(path, at, text) result(whole)
        character(len=*), intent(in) :: path, text
        integer, intent(in) :: at
        character(len=:), allocatable :: whole

        character(len=200) :: line
        integer :: unit, stat, n

        whole = ''
        n = 0
        open (newunit=unit, file=path, status='old', action='read')
        do
            read (unit, '(a)', iostat=stat) line
            if (stat /= 0) exit
            n = n + 1
            if (n == at) then
                whole = whole//text//new_line('a')
            else
                whole = whole//trim(line)//new_line('a')
            end if
        end do
        close (unit)
    end function file_with

end module test_uffchecks_mod
