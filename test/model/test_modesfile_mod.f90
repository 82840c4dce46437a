!> The modes_file model: normal modes of a user's FE model in a universal file
!> (datasets 15 and 55), on a plate the project does not ship (aluminium 0.5 x 0.4 m x 5 mm,
!> simply supported on four edges, 32 modes to 3 kHz, written by pyuff: tools/make_modes_plate.py).
!>
!> - the reader against Python's parse of the same fields (test/data/uff/modes_plate.expected), to 1e-12;
!> - each malformed dataset refused with one line (file, line, dataset, record, field, found), status 2;
!> - the modes above a band kept as a static compliance R_ij, checked against the sum over the
!>   expected table; R in W0 of `exact` on the 9 modes up to 1 kHz against the ODE of all 32:
!>   e 3.3e-2 without R, 4.2e-3 with it at 40 and 20 us (what is left is the modes' dynamics
!>   above 1 kHz, not dt), and the scene with f_modes = 1000 Hz gives the run with R;
!> - the scene `&structure model = 'modes_file'` run with `exact` and `modal` at 80, 40 and
!>   20 us against the independent modal ODE of verify_contact_mod (adaptive
!>   Dormand-Prince, rtol 1e-10) on the file's modes: e = ||F - F_ref||/||F_ref - F0|| <= 5e-3
!>   at 20 us and the observed order log2(e(2 dt)/e(dt)) >= 1.8 for both halvings.
module test_modesfile_mod
    use, intrinsic :: iso_fortran_env, only: dp => real64, int64
    use testsuite_mod, only: test_error, unittest_type, new_unittest, check, note
    use scene_text_mod, only: run_scene_text, read_table, message_of, write_text, read_scene_text
    use greenconv_scene_settings, only: scene_type
    use greenconv_scene_run_runner, only: check_scene
    use greenconv_core_error, only: error_type, stat_input
    use greenconv_io_files, only: make_directory
    use greenconv_io_uff_types, only: uff_node
    use greenconv_io_uff_dataset55, only: uff_mode_shape, read_modes_file
    use greenconv_model_modes_file, only: file_modes, read_file_modes, band_modes
    use greenconv_model_point_modes, only: point_modes
    use greenconv_model_road_file, only: road_file, read_road_file, file_road
    use greenconv_contact_single, only: contact_law
    use greenconv_contact_multi, only: multi_contact_response, run_multi_contact
    use greenconv_conv_multipoint, only: multipoint_convolver
    use greenconv_conv_builder, only: make_multipoint_convolver
    use verify_contact_mod, only: multi_contact_reference
    use greenconv_legacy_multi, only: gcmmfl, gcmrun, gcmfre, gcmnpt
    use fixture_files_mod, only: write_wave_road, wave_roads, plate_file
    use greenconv_contact_law_power, only: power_law
    implicit none
    private

    public :: collect_modesfile

    character(len=*), parameter :: scratch = 'build/test_scratch/modesfile'
    character(len=*), parameter :: expected_file = 'test/data/uff/modes_plate.expected'
    character(len=*), parameter :: plate_2414 = 'test/data/uff/modes_plate_2414.uff'
    !> The plate in mm and newtons (dataset 164), with modal masses and mass-normalised
    !> (tools/make_modes_units.py).
    character(len=*), parameter :: plate_mm = 'test/data/uff/modes_plate_mm.uff'
    character(len=*), parameter :: plate_mm_unit = 'test/data/uff/modes_plate_mm_unit.uff'
    real(dp), parameter :: pi = acos(-1.0_dp)

contains

    !> Tests of the modes_file model.
    subroutine collect_modesfile(testsuite)
        type(unittest_type), allocatable, intent(out) :: testsuite(:)

        testsuite = [new_unittest('dataset 55 read to 1e-12 of Python''s parse; direction and sign', test_read), &
                     new_unittest('malformed datasets 55 refused with one line, status 2', test_malformed), &
                     new_unittest('pyuff''s datasets 2411 + 2414 give the dataset-55 file''s modes', test_read_2414), &
                     new_unittest('malformed datasets 2414 refused with one line, status 2', test_malformed_2414), &
                     new_unittest('modes above the band kept as a static flexibility', test_residual), &
                     new_unittest('scene on the plate''s modes: exact, modal 5e-3 of the ODE at 20 us, order', &
                                  test_scene_orders), &
                     new_unittest('modes above 1 kHz as a static compliance in W0: error of exact drops, order', &
                                  test_static_residual), &
                     new_unittest('a patch of the nodes: the nodes inside it are the contact points', test_patch), &
                     new_unittest('nodes off a grid run at their own x, y; a law per area refused', test_off_grid), &
                     new_unittest('a node given twice in a mode refused, naming both lines', test_node_twice), &
                     new_unittest('dataset 164 in mm: pyuff''s file read in SI, the same modes and run', test_units), &
                     new_unittest('10^5 nodes: a patch past 5000 points refused in one line, a small one runs', &
                                  test_many_nodes)]
    end subroutine collect_modesfile

    !> The expected table: node labels and coordinates, the modes' frequency, modal mass and
    !> damping ratio, and the Z shapes (node, mode).
    subroutine read_expected(label, position, mode_values, shape)
        integer, allocatable, intent(out) :: label(:)
        real(dp), allocatable, intent(out) :: position(:, :), mode_values(:, :), shape(:, :)

        character(len=200) :: line
        character(len=8) :: word
        integer :: unit, stat, n_nodes, n_modes, number, node, i
        real(dp) :: values(3)

        allocate (label(100), position(3, 100), mode_values(3, 100), shape(100, 100))
        n_nodes = 0
        n_modes = 0
        i = 0
        open (newunit=unit, file=expected_file, status='old', action='read')
        do
            read (unit, '(a)', iostat=stat) line
            if (stat /= 0) exit
            if (line(1:1) == '#') cycle
            read (line, *) word
            select case (trim(word))
            case ('node')
                n_nodes = n_nodes + 1
                read (line, *) word, label(n_nodes), position(:, n_nodes)
            case ('mode')
                n_modes = n_modes + 1
                read (line, *) word, number, values
                mode_values(:, n_modes) = values
                i = 0
            case ('shape')
                i = i + 1
                read (line, *) word, node, shape(i, n_modes)
            end select
        end do
        close (unit)
        label = label(:n_nodes)
        position = position(:, :n_nodes)
        mode_values = mode_values(:, :n_modes)
        shape = shape(:n_nodes, :n_modes)
    end subroutine read_expected

    !> Every frequency, modal mass, damping ratio, coordinate and Z shape as Python parsed
    !> them, to 1e-12 relative; -Z flips the shapes, +X reads the zeros of column 1.
    subroutine test_read(error)
        type(test_error), allocatable, intent(out) :: error

        integer, allocatable :: label(:)
        real(dp), allocatable :: position(:, :), mode_values(:, :), shape(:, :)
        type(uff_node), allocatable :: nodes(:)
        type(uff_mode_shape), allocatable :: modes(:)
        type(error_type), allocatable :: fail
        real(dp) :: worst
        integer :: k, i

        call read_expected(label, position, mode_values, shape)
        call read_modes_file(plate_file, 3, nodes, modes, fail)
        call check(error, .not. allocated(fail), 'the plate file reads: '//message_of(fail))
        if (allocated(error)) return
        call check(error, size(modes) == 32 .and. size(nodes) == 9 .and. size(mode_values, 2) == 32, &
                   '32 modes at 9 nodes')
        if (allocated(error)) return
        call check(error, all(nodes%label == label), 'the node labels in the order of the first dataset 55')
        if (allocated(error)) return
        worst = 0.0_dp
        do i = 1, 9
            worst = max(worst, maxval(abs(nodes(i)%position - position(:, i))))
        end do
        do k = 1, size(modes)
            worst = max(worst, abs(modes(k)%frequency/mode_values(1, k) - 1.0_dp), &
                        abs(modes(k)%modal_mass/mode_values(2, k) - 1.0_dp), &
                        abs(modes(k)%damping_ratio - mode_values(3, k)), &
                        maxval(abs(modes(k)%value - shape(:, k)))/maxval(abs(shape(:, k))))
        end do
        call note('worst relative difference from Python''s parse', worst)
        call check(error, worst <= 1.0e-12_dp, 'frequencies, masses, damping, coordinates and shapes to 1e-12')
        if (allocated(error)) return
        call read_modes_file(plate_file, -3, nodes, modes, fail)
        call check(error, .not. allocated(fail), '-Z reads')
        if (allocated(error)) return
        call check(error, all([(all(modes(k)%value == -shape(:, k)), k=1, size(modes))]), '-Z flips every shape')
        if (allocated(error)) return
        call read_modes_file(plate_file, 1, nodes, modes, fail)
        call check(error, .not. allocated(fail) .and. all([(all(modes(k)%value == 0.0_dp), k=1, size(modes))]), &
                   '+X reads the in-plane zeros')
    end subroutine test_read

    !> The file `source` with line `at` replaced by `text` (deleted when `text` is '<delete>').
    subroutine write_variant(name, at, text, source)
        character(len=*), intent(in) :: name, text, source
        integer, intent(in) :: at

        character(len=200) :: line
        integer :: in, out, stat, n

        open (newunit=in, file=source, status='old', action='read')
        open (newunit=out, file=scratch//'/'//name, status='replace', action='write')
        n = 0
        do
            read (in, '(a)', iostat=stat) line
            if (stat /= 0) exit
            n = n + 1
            if (n /= at) then
                write (out, '(a)') trim(line)
            else if (text /= '<delete>') then
                write (out, '(a)') text
            end if
        end do
        close (in)
        close (out)
    end subroutine write_variant

    !> One variant per fault, each refused with status 2 and a message holding `expect`.
    subroutine test_malformed(error)
        type(test_error), allocatable, intent(out) :: error

        integer, parameter :: n_cases = 7
        character(len=*), parameter :: r6 = '         1'
        character(len=24) :: names(n_cases)
        character(len=80) :: lines(n_cases)
        character(len=120) :: expect(n_cases)
        integer :: at(n_cases)

        names = [character(len=24) :: 'analysis.uff', 'complex.uff', 'frequency.uff', 'mismatch.uff', &
                 'no_coordinates.uff', 'value.uff', 'truncated.uff']
        at = [20, 20, 22, 23, 3, 24, 24]
        lines(1) = r6//'         3         3         8         2         6'
        lines(2) = r6//'         2         3         8         5         6'
        lines(3) = '  0.00000e+00  6.75000e-01  2.00000e-02  0.00000e+00'
        lines(4) = '       199'
        lines(5) = ''
        lines(6) = '  0.00000e+00  0.00000e+00  x.80795e-01  3.12459e+00 -2.69703e+00  0.00000e+00'
        lines(7) = '<delete>'
        expect(1) = 'modes_plate_analysis.uff:20: universal file dataset 55 record 6: expected the analysis type'
        expect(2) = ':20: universal file dataset 55 record 6: expected the data type real single (2) or real'
        expect(3) = ':22: universal file dataset 55 record 8: expected the natural frequency > 0 Hz'
        expect(4) = ':42: universal file dataset 55: expected mode 2 at the 9 nodes'
        expect(5) = ':13: universal file dataset 55: expected node 101 in a dataset 15 or 2411'
        expect(6) = ':24: universal file dataset 55 record 10: expected value 3 of node 101 (a number in columns 27-39'
        expect(7) = 'universal file dataset 55 record 10: expected records 9 and 10 (2 lines) for every node'
        call check_refusals(plate_file, 'modes_plate_', names, at, lines, expect, error)
    end subroutine test_malformed

    !> Each variant of `source` (line at(k) replaced by lines(k)) refused by the reader with
    !> status 2 and one line holding expect(k).
    subroutine check_refusals(source, stem, names, at, lines, expect, error)
        character(len=*), intent(in) :: source, stem, names(:), lines(:), expect(:)
        integer, intent(in) :: at(:)
        type(test_error), allocatable, intent(out) :: error

        type(uff_node), allocatable :: nodes(:)
        type(uff_mode_shape), allocatable :: modes(:)
        type(error_type), allocatable :: fail
        integer :: k

        call make_directory(scratch, fail)
        do k = 1, size(names)
            call write_variant(stem//trim(names(k)), at(k), trim(lines(k)), source)
            call read_modes_file(scratch//'/'//stem//trim(names(k)), 3, nodes, modes, fail)
            call check(error, allocated(fail), trim(names(k))//': refused')
            if (allocated(error)) return
            call check(error, fail%stat == stat_input .and. index(fail%message, trim(expect(k))) > 0 .and. &
                       index(fail%message, new_line('a')) == 0, trim(names(k))//': expected "'//trim(expect(k)) &
                       //'", found "'//fail%message//'"')
            if (allocated(error)) return
        end do
    end subroutine check_refusals

    !> The plate written by pyuff as datasets 2411 and 2414 (tools/make_modes_2414.py) reads as
    !> the same modes as its datasets 15 and 55: the same labels, coordinates to 1e-12 (2411
    !> holds them to 17 digits, 15 to 6), and identical frequencies, masses, damping ratios and
    !> shapes in every direction.
    subroutine test_read_2414(error)
        type(test_error), allocatable, intent(out) :: error

        type(uff_node), allocatable :: nodes(:), nodes_55(:)
        type(uff_mode_shape), allocatable :: modes(:), modes_55(:)
        type(error_type), allocatable :: fail
        integer :: direction, k, i
        logical :: same

        do direction = -3, 3
            if (direction == 0) cycle
            call read_modes_file(plate_file, direction, nodes_55, modes_55, fail)
            if (.not. allocated(fail)) call read_modes_file(plate_2414, direction, nodes, modes, fail)
            call check(error, .not. allocated(fail), 'both files read: '//message_of(fail))
            if (allocated(error)) return
            call check(error, size(modes) == 32 .and. size(nodes) == 9 .and. all(nodes%label == nodes_55%label) &
                       .and. all(nodes%dataset == 2411), '32 modes at the same 9 nodes, from a dataset 2411')
            if (allocated(error)) return
            call check(error, all([(maxval(abs(nodes(i)%position - nodes_55(i)%position)) <= 1.0e-12_dp, &
                                    i=1, 9)]), 'coordinates to 1e-12')
            if (allocated(error)) return
            same = .true.
            do k = 1, 32
                same = same .and. modes(k)%frequency == modes_55(k)%frequency .and. &
                       modes(k)%modal_mass == modes_55(k)%modal_mass .and. &
                       modes(k)%damping_ratio == modes_55(k)%damping_ratio .and. &
                       modes(k)%mode_number == modes_55(k)%mode_number .and. all(modes(k)%node == modes_55(k)%node) &
                       .and. all(modes(k)%value == modes_55(k)%value)
            end do
            call check(error, same, 'frequencies, masses, damping ratios and shapes identical, direction ' &
                       //achar(48 + abs(direction)))
            if (allocated(error)) return
        end do
    end subroutine test_read_2414

    !> One variant of the 2414 file per fault, each refused with status 2 and a message naming
    !> the line, the dataset, the record, the field and what was found.
    subroutine test_malformed_2414(error)
        type(test_error), allocatable, intent(out) :: error

        character(len=*), parameter :: r9 = '         1', r12 = '  0.00000e+00  1.25351e+02  6.20317e+05'

        call check_refusals(plate_2414, 'plate_2414_', &
            [character(len=24) :: 'location.uff', 'analysis.uff', 'complex.uff', 'stress.uff', 'per_node.uff', &
             'frequency.uff', 'damping.uff', 'value.uff'], [26, 32, 32, 32, 32, 35, 35, 38], &
            [character(len=80) :: '         2', r9//'         5         3         8         2         6', &
             r9//'         2         3         8         5         6', &
             r9//'         2         3         2         2         6', &
             r9//'         2         3         8         2         3', &
             '  0.00000e+00 -1.25351e+02  6.20317e+05  6.75000e-01  2.00000e-02  0.00000e+00', &
             r12//'  6.75000e-01  1.20000e+00  0.00000e+00', &
             '  0.00000e+00  0.00000e+00  7.8x795e-01  3.12459e+00 -2.69703e+00  0.00000e+00'], &
            [character(len=120) :: &
             ':26: universal file dataset 2414 record 3: expected the dataset location 1 (data at nodes', &
             ':32: universal file dataset 2414 record 9: expected the analysis type of a normal mode', &
             ':32: universal file dataset 2414 record 9: expected the data type real single (2) or real', &
             ':32: universal file dataset 2414 record 9: expected the result type of a displacement', &
             ':32: universal file dataset 2414 record 9: expected the number of values per node for data', &
             ':35: universal file dataset 2414 record 12: expected the natural frequency > 0 Hz (columns 14-26)', &
             ':35: universal file dataset 2414 record 12: expected the viscous damping ratio in [0, 1) (columns 53', &
             ':38: universal file dataset 2414 record 15: expected value 3 of node 101'], error)
    end subroutine test_malformed_2414

    !> A band of 1 kHz keeps the modes below it; those above give R_ii = sum phi_ik**2/(m_k*omega_k**2),
    !> summed here from the expected table, and their share of the whole.
    subroutine test_residual(error)
        type(test_error), allocatable, intent(out) :: error

        integer, allocatable :: label(:)
        real(dp), allocatable :: position(:, :), mode_values(:, :), shape(:, :), residual(:, :), expected(:, :)
        real(dp) :: share, total, stiffness
        type(file_modes) :: modes
        type(point_modes) :: description
        type(error_type), allocatable :: fail
        integer :: k

        call read_expected(label, position, mode_values, shape)
        call read_file_modes(plate_file, 3, 0.05_dp, modes, fail)
        call check(error, .not. allocated(fail), 'reads')
        if (allocated(error)) return
        call check(error, modes%n_damped_by_file == 16 .and. all(modes%damping_ratio(2:32:2) == 0.05_dp) .and. &
                   all(modes%damping_ratio(1:31:2) == 0.02_dp), 'the file''s damping where given, the scene''s elsewhere')
        if (allocated(error)) return
        call band_modes(modes, 1000.0_dp, [1, 5, 9], description, residual, share, fail)
        call check(error, .not. allocated(fail), 'band of 1 kHz')
        if (allocated(error)) return
        allocate (expected(3, 3))
        expected = 0.0_dp
        total = 0.0_dp
        do k = 1, size(mode_values, 2)
            stiffness = mode_values(2, k)*(2.0_dp*pi*mode_values(1, k))**2
            total = total + sum(shape([1, 5, 9], k)**2)/stiffness
            if (mode_values(1, k) > 1000.0_dp) expected = expected + matmul(reshape(shape([1, 5, 9], k), [3, 1]), &
                                                                            reshape(shape([1, 5, 9], k), [1, 3]))/stiffness
        end do
        call note('modes in the band', real(description%modes%n_modes(), dp))
        call note('static share of the residual', share)
        call check(error, description%modes%n_modes() == count(mode_values(1, :) <= 1000.0_dp) .and. &
                   size(description%shape, 1) == 3, 'the modes up to 1 kHz at the three nodes')
        if (allocated(error)) return
        call check(error, maxval(abs(residual - expected))/maxval(abs(expected)) <= 1.0e-12_dp .and. &
                   abs(share/((expected(1, 1) + expected(2, 2) + expected(3, 3))/total) - 1.0_dp) <= 1.0e-12_dp, &
                   'R_ij and its share to 1e-12')
        if (allocated(error)) return
        call band_modes(modes, 100.0_dp, [1], description, residual, share, fail)
        call check(error, allocated(fail), 'a band below every mode is refused')
    end subroutine test_residual

    !> The scene at 80, 40 and 20 us against the ODE reference at 20 us (its samples every
    !> stride at the coarser steps).
    subroutine test_scene_orders(error)
        type(test_error), allocatable, intent(out) :: error

        character(len=*), parameter :: methods(2) = ['exact', 'modal']
        real(dp), parameter :: duration = 0.04_dp, preload = 900.0_dp
        real(dp), parameter :: steps(3) = [8.0e-5_dp, 4.0e-5_dp, 2.0e-5_dp]
        type(file_modes) :: modes
        type(point_modes) :: description
        type(road_file) :: road
        type(file_road), allocatable :: roads(:)
        type(error_type), allocatable :: fail
        real(dp), allocatable :: residual(:, :), u(:, :), reference(:, :), rows(:, :)
        real(dp) :: share, e(3)
        character(len=16) :: dt_text, steps_text
        character(len=800) :: text
        integer :: m, s, n_steps, stride, i, n_c

        call make_directory(scratch, fail)
        call write_wave_road(scratch//'/wave.dat')
        call read_file_modes(plate_file, 3, 0.03_dp, modes, fail)
        if (.not. allocated(fail)) call band_modes(modes, 0.5_dp/steps(3), [(i, i=1, 9)], description, residual, &
                                                   share, fail)
        if (.not. allocated(fail)) call read_road_file(scratch//'/wave.dat', road, fail)
        call check(error, .not. allocated(fail), 'modes and road: '//message_of(fail))
        if (allocated(error)) return
        n_c = 9
        roads = wave_roads(modes, road)
        call multi_contact_reference(description, [(power_law(1.0e7_dp, 1.5_dp), i=1, n_c)], roads, &
                                     [(preload/n_c, i=1, n_c)], steps(3), nint(duration/steps(3)), u, reference, &
                                     1.0e-10_dp)
        do m = 1, size(methods)
            do s = 1, size(steps)
                n_steps = nint(duration/steps(s))
                stride = nint(steps(s)/steps(3))
                write (dt_text, '(es9.2)') steps(s)
                write (steps_text, '(i0)') n_steps
                text = "&scene name = 'plate', output_dir = '"//scratch//"', dt = "//trim(dt_text)//", n_steps = " &
                       //trim(steps_text)//" / &structure model = 'modes_file', modes_file = '"//plate_file &
                       //"', damping_ratio = 0.03 / &road profile = 'file', road_file = '"//scratch &
                       //"/wave.dat', x_start = 0.3, speed = 5.0 / &contact stiffness = 1.0e7, exponent = 1.5, " &
                       //"preload = 900.0 / &convolution methods = '"//trim(methods(m))//"', accuracy = 0.5 /"
                ! accuracy = 0.5: the error against the ODE is measured here, at each dt
                call run_scene_text(scratch, 'plate.nml', trim(text), fail)
                call check(error, .not. allocated(fail), trim(methods(m))//': the scene runs: '//message_of(fail))
                if (allocated(error)) return
                call read_table(scratch//'/plate_'//trim(methods(m))//'.dat', 8, rows, fail)
                call check(error, .not. allocated(fail) .and. size(rows, 1) == n_steps*n_c, trim(methods(m)) &
                           //': N_t*N_c rows of 8 columns: '//message_of(fail))
                if (allocated(error)) return
                e(s) = force_error(transpose(reshape(rows(:, 5), [n_c, n_steps])), reference, stride)
                call note(trim(methods(m))//' e at dt = '//trim(dt_text)//' s', e(s))
            end do
            call note(trim(methods(m))//' order 80 -> 40 us', log(e(1)/e(2))/log(2.0_dp))
            call note(trim(methods(m))//' order 40 -> 20 us', log(e(2)/e(3))/log(2.0_dp))
            call check(error, e(3) <= 5.0e-3_dp, trim(methods(m))//': e <= 5e-3 at 20 us')
            if (allocated(error)) return
            call check(error, all(log(e(1:2)/e(2:3))/log(2.0_dp) >= 1.8_dp), trim(methods(m))//': order >= 1.8')
            if (allocated(error)) return
        end do
    end subroutine test_scene_orders

    !> The plate's 9 modes up to 1 kHz stepped by `exact` at 40 and 20 us, with and without the
    !> static compliance R of its 23 modes above 1 kHz in W0, against the modal ODE of all 32
    !> modes (Dormand-Prince, rtol 1e-10): without R the error stays at what the missing modes
    !> leave out whatever dt; with R it is at least 5 times smaller, and the scene
    !> (`f_modes = 1000`) runs with R. The Fortran 77 door on the same file and band (GCMMFL,
    !> GCMRUN on the scene's road heights) builds the same structure: its forces are the
    !> scene's bit for bit, within 5e-3 of the ODE where the modes in band alone are not.
    subroutine test_static_residual(error)
        type(test_error), allocatable, intent(out) :: error

        real(dp), parameter :: duration = 0.04_dp, preload = 900.0_dp
        real(dp), parameter :: steps(2) = [4.0e-5_dp, 2.0e-5_dp], f_band = 1000.0_dp
        integer, parameter :: n_c = 9
        type(file_modes) :: modes
        type(point_modes) :: all_modes, in_band
        type(road_file) :: road
        type(file_road), allocatable :: roads(:)
        type(error_type), allocatable :: fail
        type(power_law) :: laws(n_c)
        class(multipoint_convolver), allocatable :: conv
        type(multi_contact_response) :: response
        real(dp), allocatable :: none(:, :), static(:, :), u(:, :), reference(:, :), heights(:, :), rows(:, :)
        real(dp), allocatable :: door_u(:, :), door_f(:, :), door_delta(:, :)
        real(dp) :: share, e(2, 4), door_gap
        character(len=:), allocatable :: accuracy
        character(len=16) :: dt_text
        character(len=600) :: text, message
        integer :: s, n_steps, stride, i, n, with, ierr
        integer(int64) :: handle

        call make_directory(scratch, fail)
        call write_wave_road(scratch//'/wave.dat')
        call read_file_modes(plate_file, 3, 0.03_dp, modes, fail)
        if (.not. allocated(fail)) call band_modes(modes, 1.0e6_dp, [(i, i=1, n_c)], all_modes, none, share, fail)
        if (.not. allocated(fail)) call band_modes(modes, f_band, [(i, i=1, n_c)], in_band, static, share, fail)
        if (.not. allocated(fail)) call read_road_file(scratch//'/wave.dat', road, fail)
        call check(error, .not. allocated(fail), 'modes and road: '//message_of(fail))
        if (allocated(error)) return
        call check(error, in_band%modes%n_modes() == 9 .and. maxval(abs(none)) == 0.0_dp, &
                   '9 modes up to 1 kHz; no residual when every mode is in the band')
        if (allocated(error)) return
        call note('static share of the 23 modes above 1 kHz', share)
        laws = power_law(1.0e7_dp, 1.5_dp)
        roads = wave_roads(modes, road)
        call multi_contact_reference(all_modes, laws, roads, [(preload/n_c, i=1, n_c)], steps(2), &
                                     nint(duration/steps(2)), u, reference, 1.0e-10_dp)
        do s = 1, size(steps)
            n_steps = nint(duration/steps(s))
            stride = nint(steps(s)/steps(2))
            heights = reshape([((roads(i)%height(n*steps(s)), n=0, n_steps - 1), i=1, n_c)], [n_steps, n_c])
            write (dt_text, '(es9.2)') steps(s)
            do with = 1, 2
                call make_multipoint_convolver('exact', in_band, steps(s), 1.0e-6_dp, n_steps, conv, accuracy, fail)
                if (with == 2 .and. .not. allocated(fail)) call conv%set_instant_matrix(conv%weight0 + static)
                if (.not. allocated(fail)) call run_multi_contact(conv, laws, heights, [(preload/n_c, i=1, n_c)], &
                                                                  response, fail)
                call check(error, .not. allocated(fail), 'exact runs: '//message_of(fail))
                if (allocated(error)) return
                e(s, with) = force_error(response%force, reference, stride)
            end do
            call note('exact on 9 modes, e without R at dt = '//trim(dt_text)//' s', e(s, 1))
            call note('exact on 9 modes, e with R in W0 at dt = '//trim(dt_text)//' s', e(s, 2))
            ! the scene: f_modes = 1000 Hz steps the same 9 modes, with R in W0 (accuracy 0.5: it is
            ! compared with the ODE and the door here; its budget's band term is about 8e-3)
            write (text, '(a,es9.2,a,i0,a)') "&scene name = 'band', output_dir = '"//scratch//"', dt = ", steps(s), &
                ', n_steps = ', n_steps, " / &structure model = 'modes_file', modes_file = '"//plate_file &
                //"', damping_ratio = 0.03, f_modes = 1000.0 / &road profile = 'file', road_file = '"//scratch &
                //"/wave.dat', x_start = 0.3, speed = 5.0 / &contact stiffness = 1.0e7, exponent = 1.5, " &
                //"preload = 900.0 / &convolution methods = 'exact', accuracy = 0.5 /"
            call run_scene_text(scratch, 'band.nml', trim(text), fail)
            if (.not. allocated(fail)) call read_table(scratch//'/band_exact.dat', 8, rows, fail)
            call check(error, .not. allocated(fail), 'the scene with f_modes = 1000 runs: '//message_of(fail))
            if (allocated(error)) return
            e(s, 3) = force_error(transpose(reshape(rows(:, 5), [n_c, n_steps])), reference, stride)
            call note('scene (f_modes = 1000 Hz), e at dt = '//trim(dt_text)//' s', e(s, 3))
            ! the F77 door (the C door shares its box): the same file, band and contact
            allocate (door_u(n_steps, n_c), door_f(n_steps, n_c), door_delta(n_steps, n_c))
            call gcmmfl(plate_file, 3, 0.03_dp, f_band, 'exact', steps(s), n_steps, 1.0e-6_dp, handle, ierr, message)
            if (ierr == 0) call gcmrun(handle, n_c, n_steps, [(1.0e7_dp, i=1, n_c)], [(1.5_dp, i=1, n_c)], &
                                       [(preload/n_c, i=1, n_c)], transpose(reshape(rows(:, 3), [n_c, n_steps])), &
                                       door_u, door_f, door_delta, ierr, message)
            call gcmfre(handle)
            call check(error, ierr == 0, 'GCMMFL and GCMRUN with FBAND = 1000: '//trim(message))
            if (allocated(error)) return
            door_gap = maxval(abs(door_f - transpose(reshape(rows(:, 5), [n_c, n_steps]))))
            e(s, 4) = force_error(door_f, reference, stride)
            deallocate (door_u, door_f, door_delta)
            call note('F77 door (FBAND = 1000 Hz), e at dt = '//trim(dt_text)//' s', e(s, 4))
            call note('F77 door against the scene: max |dF| [N]', door_gap)
            call check(error, door_gap == 0.0_dp, 'the F77 door''s forces are the scene''s bit for bit')
            if (allocated(error)) return
        end do
        call note('order of exact with R, 40 -> 20 us', log(e(1, 2)/e(2, 2))/log(2.0_dp))
        call check(error, all(e(:, 2) <= 0.2_dp*e(:, 1)), 'R in W0 divides the error by 5 or more at both dt')
        if (allocated(error)) return
        call check(error, all(e(:, 4) <= 5.0e-3_dp) .and. all(e(:, 1) > 5.0e-3_dp), &
                   'the door with R within 5e-3 of the ODE of all 32 modes, the 9 modes without R not')
        if (allocated(error)) return
        call check(error, all(abs(e(:, 3)/e(:, 2) - 1.0_dp) <= 1.0e-3_dp), 'the scene runs with R in W0')
    end subroutine test_static_residual

    !> e = ||F - F_ref||/||F_ref - F0||, F(n, i) against every `stride`-th sample of the
    !> reference, F0 = 100 N the preload of each of the 9 points.
    real(dp) function force_error(force, reference, stride) result(e)
        real(dp), intent(in) :: force(0:, :), reference(0:, :)
        integer, intent(in) :: stride

        real(dp) :: numerator, denominator
        integer :: n

        numerator = 0.0_dp
        denominator = 0.0_dp
        do n = 0, ubound(force, 1)
            numerator = numerator + sum((force(n, :) - reference(n*stride, :))**2)
            denominator = denominator + sum((reference(n*stride, :) - 100.0_dp)**2)
        end do
        e = sqrt(numerator/denominator)
    end function force_error

    !> modes_patch_length = 70 mm by modes_patch_width = 1 mm around the nodes' centre (0.2, 0.17)
    !> keeps the middle row of the 3 x 3 grid; a 20 mm square, the middle node.
    subroutine test_patch(error)
        type(test_error), allocatable, intent(out) :: error

        character(len=*), parameter :: head = "&scene name = 'row', output_dir = '"//scratch//"', dt = 8.0e-5, " &
            //"n_steps = 100 / &structure model = 'modes_file', modes_file = '"//plate_file//"', damping_ratio = 0.03, "
        character(len=*), parameter :: tail = " / &road profile = 'file', road_file = '"//scratch//"/wave.dat', " &
            //"x_start = 0.3, speed = 5.0 / &contact stiffness = 1.0e7, exponent = 1.5, preload = 300.0 / " &
            //"&convolution methods = 'modal', accuracy = 0.5 /"
        ! accuracy = 0.5: which nodes the patch keeps is under test, not the step's error
        type(error_type), allocatable :: fail
        real(dp), allocatable :: rows(:, :)

        call make_directory(scratch, fail)
        call write_wave_road(scratch//'/wave.dat')
        call run_scene_text(scratch, 'row.nml', head//'modes_patch_length = 0.07, modes_patch_width = 0.001'//tail, fail)
        call check(error, .not. allocated(fail), 'the scene on a row runs: '//message_of(fail))
        if (allocated(error)) return
        ! one row of points: no column y
        call read_table(scratch//'/row_modal.dat', 7, rows, fail)
        call check(error, .not. allocated(fail) .and. size(rows, 1) == 300, '100 steps x 3 points: '//message_of(fail))
        if (allocated(error)) return
        call check(error, all(abs(rows(1:3, 2) - [0.17_dp, 0.2_dp, 0.23_dp]) < 1.0e-12_dp), &
                   'the middle row, x = 0.17, 0.2, 0.23 m')
        if (allocated(error)) return
        call run_scene_text(scratch, 'middle.nml', head//'modes_patch_length = 0.02, modes_patch_width = 0.02'//tail, &
                            fail)
        call check(error, .not. allocated(fail), 'the scene on the middle node runs: '//message_of(fail))
        if (allocated(error)) return
        call read_table(scratch//'/row_modal.dat', 7, rows, fail)
        call check(error, .not. allocated(fail) .and. size(rows, 1) == 100 .and. abs(rows(1, 2) - 0.2_dp) < 1.0e-12_dp, &
                   'a 20 mm square keeps the middle node alone')
    end subroutine test_patch

    !> The plate's middle node moved off the 3 x 3 grid, to (201.3, 168.8) mm: the contact points
    !> need no grid (each has its own law and road), so the scene runs on the nodes as they are;
    !> a contact law per area, which needs each point's share of a patch grid, is refused.
    subroutine test_off_grid(error)
        type(test_error), allocatable, intent(out) :: error

        character(len=*), parameter :: head = "&scene name = 'scattered', output_dir = '"//scratch//"', dt = 8.0e-5, " &
            //"n_steps = 50 / &structure model = 'modes_file', modes_file = '"//scratch//"/scattered.uff', " &
            //"damping_ratio = 0.03 / &road profile = 'file', road_file = '"//scratch//"/wave.dat', x_start = 0.3, " &
            //"speed = 5.0 / &contact exponent = 1.5, preload = 900.0, "
        character(len=*), parameter :: tail = " / &convolution methods = 'exact', accuracy = 0.5 /"
        ! accuracy = 0.5: the points' positions and the refusal are under test, not the step's error
        type(error_type), allocatable :: fail
        real(dp), allocatable :: rows(:, :)

        call make_directory(scratch, fail)
        call write_wave_road(scratch//'/wave.dat')
        call write_variant('scattered.uff', 7, '       105         0         0         1  2.01300E-01  1.68800E-01' &
                           //'  0.00000E+00', plate_file)
        call run_scene_text(scratch, 'scattered.nml', head//'stiffness = 1.0e7'//tail, fail)
        call check(error, .not. allocated(fail), 'the scene on nodes off a grid runs: '//message_of(fail))
        if (allocated(error)) return
        call read_table(scratch//'/scattered_exact.dat', 8, rows, fail)
        call check(error, .not. allocated(fail) .and. size(rows, 1) == 450, '50 steps x 9 points, with y: ' &
                   //message_of(fail))
        if (allocated(error)) return
        call check(error, abs(rows(5, 2) - 0.2013_dp) < 1.0e-12_dp .and. abs(rows(5, 8) - 0.1688_dp) < 1.0e-12_dp, &
                   'node 105 at its own x = 201.3 mm, y = 168.8 mm')
        if (allocated(error)) return
        call run_scene_text(scratch, 'scattered.nml', head//'stiffness_per_area = 1.0e9, patch_width = 0.1'//tail, fail)
        call check(error, allocated(fail), 'a law per area on a modes file is refused')
        if (allocated(error)) return
        call check(error, index(fail%message, 'stiffness_per_area') > 0 .and. index(fail%message, 'grid') > 0 .and. &
                   index(fail%message, new_line('a')) == 0, 'one line naming stiffness_per_area and the grid: ' &
                   //fail%message)
    end subroutine test_off_grid

    !> Node 101 given again in the first mode, in place of node 102: with node 102's values it
    !> is refused naming both lines and the first value that differs; with its own values it is
    !> refused too (two contact points on one node), naming both lines.
    subroutine test_node_twice(error)
        type(test_error), allocatable, intent(out) :: error

        type(uff_node), allocatable :: nodes(:)
        type(uff_mode_shape), allocatable :: modes(:)
        type(error_type), allocatable :: fail
        character(len=*), parameter :: values_101 = '  0.00000e+00  0.00000e+00  7.80795e-01  3.12459e+00 ' &
                                                    //'-2.69703e+00  0.00000e+00'

        call check_refusals(plate_file, 'modes_plate_', ['twice_other.uff'], [25], ['       101'], &
                            [character(len=100) :: ':25: universal file dataset 55 record 9: node 101 is given again ' &
                            //'with other values (value 3 = '], error)
        if (allocated(error)) return
        call write_variant('twice_step.uff', 25, '       101', plate_file)
        call write_variant('twice_same.uff', 26, values_101, scratch//'/twice_step.uff')
        call read_modes_file(scratch//'/twice_same.uff', 3, nodes, modes, fail)
        call check(error, allocated(fail), 'node 101 given twice with the same values accepted')
        if (allocated(error)) return
        call check(error, fail%stat == stat_input .and. index(fail%message, 'twice_same.uff:25: universal file ' &
                   //'dataset 55 record 9: node 101 is given again, as at line 23') > 0 .and. &
                   index(fail%message, new_line('a')) == 0, 'one line naming both: '//fail%message)
    end subroutine test_node_twice

    !> pyuff's plate in mm and newtons (dataset 164: length factor 1000, force 1; a mass in
    !> N*s^2/mm): the reader gives what it gives for the plate in SI, coordinates to 1e-15 m,
    !> modal masses to 1e-12, shapes equal; the mass-normalised file gives phi_i^2/m_k to 2e-5
    !> (its shapes carry E13.5's 6 digits); and the same scene on either file writes the same
    !> forces and contact areas (the nodes read as metres gave 1e6 times the area per point).
    subroutine test_units(error)
        type(test_error), allocatable, intent(out) :: error

        character(len=*), parameter :: head = "&scene name = 'NAME', output_dir = '"//scratch//"', dt = 8.0e-5, " &
            //"n_steps = 60 / &structure model = 'modes_file', modes_file = '"
        character(len=*), parameter :: tail = "', damping_ratio = 0.03 / &road profile = 'file', road_file = '" &
            //scratch//"/wave.dat', x_start = 0.3, speed = 5.0 / &contact stiffness = 1.0e7, exponent = 1.5, " &
            //"preload = 300.0 / &convolution methods = 'exact', accuracy = 0.5 /"
        ! accuracy = 0.5: the two files' runs against each other are under test, not the step's error
        type(file_modes) :: si, mm, unit
        type(error_type), allocatable :: fail
        real(dp), allocatable :: rows_si(:, :), rows_mm(:, :), totals_si(:, :), totals_mm(:, :)
        real(dp) :: worst
        integer :: k

        call read_file_modes(plate_file, 3, 0.03_dp, si, fail)
        if (.not. allocated(fail)) call read_file_modes(plate_mm, 3, 0.03_dp, mm, fail)
        if (.not. allocated(fail)) call read_file_modes(plate_mm_unit, 3, 0.03_dp, unit, fail)
        call check(error, .not. allocated(fail), 'the files read: '//message_of(fail))
        if (allocated(error)) return
        call check(error, maxval(abs(mm%x - si%x)) <= 1.0e-15_dp .and. maxval(abs(mm%y - si%y)) <= 1.0e-15_dp .and. &
                   all(mm%label == si%label), 'the nodes in m: x = '//trim(real_list(mm%x(1:3))))
        if (allocated(error)) return
        call check(error, all(mm%frequency == si%frequency) .and. &
                   maxval(abs(mm%modal_mass/si%modal_mass - 1.0_dp)) <= 1.0e-12_dp .and. all(mm%shape == si%shape), &
                   'modal masses in kg: '//trim(real_list(mm%modal_mass(1:2))))
        if (allocated(error)) return
        worst = 0.0_dp
        do k = 1, size(si%frequency)
            worst = max(worst, maxval(abs(unit%shape(:, k)**2/unit%modal_mass(k) - si%shape(:, k)**2 &
                                          /si%modal_mass(k)))/maxval(si%shape(:, k)**2/si%modal_mass(k)))
        end do
        call check(error, worst <= 2.0e-5_dp, 'mass-normalised in mm: phi^2/m off by '//trim(real_list([worst])))
        if (allocated(error)) return
        call make_directory(scratch, fail)
        call write_wave_road(scratch//'/wave.dat')
        call run_scene_text(scratch, 'units_si.nml', named(head, 'units_si')//plate_file//tail, fail)
        if (.not. allocated(fail)) call run_scene_text(scratch, 'units_mm.nml', named(head, 'units_mm')//plate_mm &
                                                       //tail, fail)
        call check(error, .not. allocated(fail), 'the scenes run: '//message_of(fail))
        if (allocated(error)) return
        call read_table(scratch//'/units_si_exact.dat', 8, rows_si, fail)
        if (.not. allocated(fail)) call read_table(scratch//'/units_mm_exact.dat', 8, rows_mm, fail)
        if (.not. allocated(fail)) call read_table(scratch//'/units_si_exact_totals.dat', 4, totals_si, fail)
        if (.not. allocated(fail)) call read_table(scratch//'/units_mm_exact_totals.dat', 4, totals_mm, fail)
        call check(error, .not. allocated(fail), 'the outputs read: '//message_of(fail))
        if (allocated(error)) return
        worst = maxval(abs(rows_mm - rows_si))/maxval(abs(rows_si))
        call check(error, size(rows_mm, 1) == size(rows_si, 1) .and. worst <= 1.0e-9_dp, &
                   'the points'' histories in mm and in m differ by '//trim(real_list([worst])))
        if (allocated(error)) return
        call check(error, maxval(abs(totals_mm(:, 3) - totals_si(:, 3))) <= 1.0e-9_dp*maxval(totals_si(:, 3)) .and. &
                   maxval(totals_si(:, 3)) < 1.0e-2_dp, 'the contact area [m^2], largest '// &
                   trim(real_list([maxval(totals_mm(:, 3))])))
    end subroutine test_units

    !> A scene text with NAME replaced.
    function named(text, name) result(whole)
        character(len=*), intent(in) :: text, name
        character(len=:), allocatable :: whole

        integer :: at

        at = index(text, 'NAME')
        whole = text(:at - 1)//name//text(at + 4:)
    end function named

    !> Numbers as text, for messages.
    function real_list(values) result(text)
        real(dp), intent(in) :: values(:)
        character(len=200) :: text

        write (text, '(*(es12.4))') values
    end function real_list

    !> A modes file of 317 x 317 = 100,489 nodes 3 mm apart and two modes: a patch holding
    !> 97,969 of them is refused by `--check` in one line naming the limit of 5000 points and
    !> the size (77 GB for the N_c x N_c static compliance; it was an allocation failure and a
    !> backtrace), and so is the file at the F77 door, which makes every node a point; a 6 cm
    !> square patch, 441 nodes, passes the check.
    subroutine test_many_nodes(error)
        type(test_error), allocatable, intent(out) :: error

        integer, parameter :: n = 317
        character(len=*), parameter :: big = scratch//'/many_nodes.uff'
        character(len=*), parameter :: head = "&scene name = 'many', output_dir = '"//scratch//"', dt = 1.0e-4, " &
            //"n_steps = 100 / &structure model = 'modes_file', modes_file = '"//big//"', damping_ratio = 0.03, "
        character(len=*), parameter :: tail = " / &road profile = 'file', road_file = '"//scratch//"/wave.dat', " &
            //"x_start = 0.5, speed = 5.0 / &contact stiffness = 1.0e7, exponent = 1.5, preload = 300.0 / " &
            //"&convolution methods = 'modal' /"
        type(scene_type) :: scene
        type(error_type), allocatable :: fail
        character(len=300) :: message
        integer(int64) :: handle
        integer :: unit, i, j, m, sink, ierr, n_c

        call make_directory(scratch, fail)
        call write_wave_road(scratch//'/wave.dat')
        open (newunit=unit, file=big, status='replace', action='write')
        write (unit, '(a)') '    -1', '    15'
        do j = 0, n - 1
            do i = 0, n - 1
                write (unit, '(4i10,3es13.5)') j*n + i + 1, 0, 0, 1, 0.003_dp*i, 0.003_dp*j, 0.0_dp
            end do
        end do
        write (unit, '(a)') '    -1'
        do m = 1, 2
            write (unit, '(a)') '    -1', '    55', 'mode', 'NONE', 'NONE', 'NONE', 'NONE'
            write (unit, '(6i10)') 1, 2, 2, 8, 2, 3
            write (unit, '(4i10)') 2, 4, 1, m
            write (unit, '(4es13.5)') 100.0_dp*m, 1.0_dp, 0.02_dp, 0.0_dp
            do j = 1, n
                do i = 1, n
                    write (unit, '(i10)') (j - 1)*n + i
                    write (unit, '(3es13.5)') 0.0_dp, 0.0_dp, sin(pi*i*m/(n + 1))*sin(pi*j/(n + 1))
                end do
            end do
            write (unit, '(a)') '    -1'
        end do
        close (unit)
        open (newunit=sink, file='/dev/null', action='write')
        call read_scene_text(scratch, 'many.nml', head//'modes_patch_length = 0.94, modes_patch_width = 0.94'//tail, &
                             scene, fail)
        if (.not. allocated(fail)) call check_scene(scene, sink, fail)
        call check(error, allocated(fail), 'a patch of 97,969 nodes passed --check')
        if (allocated(error)) return
        call check(error, fail%stat == stat_input .and. index(fail%message, 'many.nml:1: &structure') > 0 .and. &
                   index(fail%message, 'expected at most 5000 contact points') > 0 .and. &
                   index(fail%message, 'found 97969 of the file''s 100489 nodes') > 0 .and. &
                   index(fail%message, ' GB') > 0 .and. index(fail%message, new_line('a')) == 0, &
                   'one line, the limit and the size: '//fail%message)
        if (allocated(error)) return
        call read_scene_text(scratch, 'many.nml', head//'modes_patch_length = 0.06, modes_patch_width = 0.06'//tail, &
                             scene, fail)
        if (.not. allocated(fail)) call check_scene(scene, sink, fail)
        close (sink)
        call check(error, .not. allocated(fail), 'a 6 cm patch, 441 nodes: '//message_of(fail))
        if (allocated(error)) return
        call gcmmfl(big, 3, 0.03_dp, 0.0_dp, 'modal', 1.0e-4_dp, 100, 0.01_dp, handle, ierr, message)
        call check(error, ierr == 2 .and. handle == 0 .and. index(message, 'expected at most 5000 nodes') > 0 .and. &
                   index(message, 'found 100489') > 0, 'GCMMFL on 100,489 nodes: '//trim(message))
        if (handle /= 0) call gcmfre(handle)
        n_c = 0
        if (allocated(error)) return
        call gcmnpt(handle, n_c, ierr, message)
        call check(error, ierr == 2 .and. n_c == 0, 'no handle')
    end subroutine test_many_nodes

end module test_modesfile_mod
