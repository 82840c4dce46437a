!> Green's-matrix files in any unit and on any grid: a file of mobilities or
!> accelerances reads as the receptances it stands for, a pressure or a velocity time history
!> is refused naming the dataset and record, and `direct`/`fft` on a file whose lines start
!> above 0 Hz or are uneven follow the structure (the plate's own modes run by `exact`)
!> instead of an inverse FFT that puts line l at l*df.
module test_greenfiles_mod
    use, intrinsic :: iso_fortran_env, only: dp => real64
    use testsuite_mod, only: test_error, unittest_type, new_unittest, check, note
    use greenconv_core_error, only: error_type, stat_input
    use greenconv_io_files, only: make_directory
    use greenconv_io_uff, only: uff_file, uff_function, uff_node, uff_axis, read_uff
    use greenconv_io_uff_write, only: write_uff, receptance_function, impulse_function
    use greenconv_model_point_modes, only: point_modes
    use greenconv_model_plate, only: tyre_plate, plate_modes, patch_points, patch_receptance
    use greenconv_model_road_file, only: road_file, read_road_file, sample_road, road_travel
    use greenconv_model_green_matrix_file, only: green_matrix, read_green_matrix
    use greenconv_contact_single, only: contact_law
    use greenconv_contact_multi, only: multi_contact_response, run_multi_contact
    use greenconv_conv_multipoint, only: multipoint_convolver
    use greenconv_conv_builder, only: make_multipoint_convolver
    use greenconv_ident_green_structure, only: green_options, green_structure, read_green_structure
    use greenconv_conv_green_file, only: green_file_convolver
    use scene_text_mod, only: message_of
    use greenconv_contact_law_power, only: power_law
    implicit none
    private

    public :: collect_greenfiles

    !> Scratch directory for the files the tests write.
    character(len=*), parameter :: scratch = 'build/test_scratch/greenfiles'
    real(dp), parameter :: pi = acos(-1.0_dp)
    !> What the ordinate of a written file is: G itself, i*omega*G or -omega^2*G.
    integer, parameter :: as_receptance = 1, as_mobility = 2, as_accelerance = 3

contains

    !> Tests of Green's-matrix files in other units and on other grids.
    subroutine collect_greenfiles(testsuite)
        type(unittest_type), allocatable, intent(out) :: testsuite(:)

        testsuite = [new_unittest('units: mobility and accelerance files read as the receptance file', test_units), &
                     new_unittest('units: a pressure and a velocity time history refused with dataset and record', &
                                  test_refused_units), &
                     new_unittest('grids: band from 50 Hz and uneven lines: direct and fft follow the structure', &
                                  test_grids), &
                     new_unittest('band: direct and fft on a file to 400 Hz of a plate with modes to 1500 Hz', &
                                  test_band), &
                     new_unittest('shipped patch, whole and from 50 Hz: the methods against the plate''s modes', &
                                  test_shipped_cut)]
    end subroutine collect_greenfiles

    !> The 2 x 2 patch of the plate (xi = 0.02, modes to 300 Hz) written on 0 to 400 Hz by 1 Hz
    !> as receptances, mobilities (Y = i*omega*G) and accelerances (A = -omega^2*G), datasets in
    !> complex double (17 digits): each read must give G. Above 0 Hz the conversion divides by
    !> omega or omega^2 in double precision: bound 1e-11 of max|G| (measured 3e-13, 4e-13). The
    !> 0 Hz line is extrapolated linearly from 1 and 2 Hz: its error is of order
    !> |G''|*df^2/2, measured 1.2e-4 of |G(0)| (bound 1e-2). Before the reading of records 9/10
    !> the mobility came back as i*omega*G, off by a factor up to 2.5e3.
    subroutine test_units(error)
        type(test_error), allocatable, intent(out) :: error

        character(len=*), parameter :: names(3) = [character(len=11) :: 'receptance', 'mobility', 'accelerance']
        type(point_modes) :: truth
        type(green_matrix) :: matrix(3)
        type(error_type), allocatable :: fail
        real(dp) :: x(4), y(4), frequency(401), worst, peak, zero
        integer :: k, l

        frequency = [(1.0_dp*l, l=0, 400)]
        call patch_modes(truth, x, y, fail)
        do k = 1, 3
            if (.not. allocated(fail)) call write_file_of(scratch//'/'//trim(names(k))//'.uff', truth, x, y, &
                                                         frequency, k, fail)
            if (.not. allocated(fail)) call read_green_matrix(scratch//'/'//trim(names(k))//'.uff', matrix(k), fail)
            call check(error, .not. allocated(fail), trim(names(k))//' file: '//message_of(fail))
            if (allocated(error)) return
        end do
        peak = maxval(abs(matrix(1)%g))
        do k = 2, 3
            worst = maxval(abs(matrix(k)%g(:, :, 2:) - matrix(1)%g(:, :, 2:)))/peak
            zero = maxval(abs(matrix(k)%g(:, :, 1) - matrix(1)%g(:, :, 1)))/maxval(abs(matrix(1)%g(:, :, 1)))
            call note(trim(names(k))//': max |G - G_receptance|/max|G| above 0 Hz', worst)
            call note(trim(names(k))//': at 0 Hz (extrapolated), relative', zero)
            call check(error, worst <= 1.0e-11_dp, trim(names(k))//': G differs from the receptance file''s')
            if (allocated(error)) return
            call check(error, zero <= 1.0e-2_dp, trim(names(k))//': the 0 Hz line is off')
            if (allocated(error)) return
            call check(error, index(matrix(k)%conversion, trim(names(k))//' converted') == 1, &
                       trim(names(k))//': the conversion is named: '//matrix(k)%conversion)
            if (allocated(error)) return
        end do
    end subroutine test_units

    !> A file of pressures over force (records 9/10 data types 15 over 13) as function type 4,
    !> and a time response (function type 1) of velocity over force, are no Green's function in
    !> m/N or m/(N*s): each is refused with status 2, the message naming the dataset, records
    !> 9/10 and what they hold. Before, both were taken as they were.
    subroutine test_refused_units(error)
        type(test_error), allocatable, intent(out) :: error

        type(uff_function) :: functions(4)
        type(uff_node) :: nodes(2)
        type(green_matrix) :: matrix
        type(error_type), allocatable :: fail
        character(len=:), allocatable :: path
        integer :: i, j, k, l

        call make_directory(scratch, fail)
        call check(error, .not. allocated(fail), 'scratch: '//message_of(fail))
        if (allocated(error)) return
        do k = 1, 2
            do i = 1, 2
                do j = 1, 2
                    if (k == 1) then
                        functions(2*(i - 1) + j) = receptance_function([i, 3], [j, 3], 0.0_dp, 1.0_dp, &
                            [(cmplx(1.0_dp/(1.0_dp + l), 0.1_dp, dp), l=0, 20)], 'p')
                        functions(2*(i - 1) + j)%numerator = uff_axis(15, -2, 1, 0, 'Pressure', 'Pa')
                    else
                        functions(2*(i - 1) + j) = impulse_function([i, 3], [j, 3], 0.0_dp, 1.0e-3_dp, &
                            [(exp(-0.1_dp*l), l=0, 20)], 'v')
                        functions(2*(i - 1) + j)%numerator = uff_axis(11, 1, 0, 0, 'Velocity', 'm/s')
                    end if
                end do
                nodes(i) = uff_node(label=i, position=[0.1_dp*i, 0.0_dp, 0.0_dp])
            end do
            path = scratch//'/'//trim(merge('pressure', 'velocity', k == 1))//'.uff'
            call write_uff(path, functions, nodes, fail)
            call check(error, .not. allocated(fail), 'writing '//path//': '//message_of(fail))
            if (allocated(error)) return
            call read_green_matrix(path, matrix, fail, function_type=merge(4, 1, k == 1))
            call check(error, allocated(fail), path//' was taken as a Green''s function')
            if (allocated(error)) return
            call check(error, fail%stat == stat_input .and. index(fail%message, path) == 1 .and. &
                       index(fail%message, 'dataset 58') > 0 .and. index(fail%message, 'records 9/10') > 0 .and. &
                       index(fail%message, trim(merge('pressure', 'velocity', k == 1))) > 0, &
                       'the message names the file, dataset, records and what was found: '//fail%message)
            if (allocated(error)) return
        end do
    end subroutine test_refused_units

    !> The 2 x 2 patch's receptances on lines that are not the uniform grid from 0 Hz: 50 to
    !> 400 Hz by 1 Hz (the band starting above 0 Hz), and 0 to 400 Hz with every line moved by
    !> up to 0.3 Hz (uneven). Rolled over data/road_sample.dat (dt = 0.5 ms, 400 steps), the
    !> contact forces of `direct` and `fft` built from the file must be within 2 % of the largest
    !> force of `exact` run on the plate's own modes (the structure the file describes); the
    !> accuracy must say that g_ij did not come from the inverse FFT and name the band. Before,
    !> the inverse FFT put line l at l*df from 0 Hz: direct 5.6e-2 off on the 50 Hz band; now
    !> 3.6e-3 (the rectangle rule against the first-order hold at this dt).
    subroutine test_grids(error)
        type(test_error), allocatable, intent(out) :: error

        character(len=*), parameter :: methods(2) = ['direct', 'fft   ']
        type(point_modes) :: truth
        type(green_structure) :: structure
        type(error_type), allocatable :: fail
        type(multi_contact_response) :: reference, response
        class(multipoint_convolver), allocatable :: conv
        character(len=:), allocatable :: accuracy, path
        real(dp), allocatable :: frequency(:)
        real(dp) :: x(4), y(4), worst, dt
        integer :: g, m, l

        dt = 5.0e-4_dp
        call patch_modes(truth, x, y, fail)
        if (.not. allocated(fail)) &
            call make_multipoint_convolver('exact', truth, dt, 0.01_dp, 400, conv, accuracy, fail)
        if (.not. allocated(fail)) call roll(conv, x, 1.0_dp, dt, 400, 5.0e4_dp, 1000.0_dp, reference, fail)
        call check(error, .not. allocated(fail), 'the reference run: '//message_of(fail))
        if (allocated(error)) return
        do g = 1, 2
            if (g == 1) then
                frequency = [(1.0_dp*l, l=50, 400)]
                path = scratch//'/band_50.uff'
            else
                frequency = [(l + 0.3_dp*sin(1.7_dp*l), l=0, 400)]
                frequency(1) = 0.0_dp
                path = scratch//'/uneven.uff'
            end if
            call write_file_of(path, truth, x, y, frequency, as_receptance, fail)
            if (.not. allocated(fail)) call read_green_structure(path, green_options(), structure, fail)
            call check(error, .not. allocated(fail), path//': '//message_of(fail))
            if (allocated(error)) return
            do m = 1, size(methods)
                call green_file_convolver(structure, trim(methods(m)), dt, 0.01_dp, 400, conv, accuracy, fail)
                if (.not. allocated(fail)) call roll(conv, x, 1.0_dp, dt, 400, 5.0e4_dp, 1000.0_dp, response, fail)
                call check(error, .not. allocated(fail), path//' '//trim(methods(m))//': '//message_of(fail))
                if (allocated(error)) return
                worst = maxval(abs(response%force - reference%force))/maxval(abs(reference%force))
                call note(path//' '//trim(methods(m))//': max |F - F_exact(truth)|/max F', worst)
                call check(error, worst <= 0.02_dp, path//' '//trim(methods(m))//': more than 2 % off the structure; ' &
                           //accuracy)
                if (allocated(error)) return
                call check(error, index(accuracy, 'not from the inverse FFT') > 0 .and. &
                           index(accuracy, 'band') > 0, trim(methods(m))//': the accuracy names the grid and band: ' &
                           //accuracy)
                if (allocated(error)) return
            end do
        end do
    end subroutine test_grids

    !> The band outside the file: the 2 x 2 patch's plate with its modes up to 1500 Hz (the
    !> structure), its receptances written on 0 to 400 Hz by 1 Hz (what a user measured). The
    !> inverse FFT of the file gives g_ij band-limited to 400 Hz; the structure responds above.
    !> Rolled over data/road_sample.dat with stiff contact springs (2e5 N/m per point) at
    !> dt = 0.25 ms, `direct` and `fft` from the file are compared with `exact` on the
    !> structure's own modes: their largest force difference must be below 2e-2 of the largest
    !> force. Measured: 3.3e-2 with G zero above 400 Hz, 1.75e-2 with G above the band from the
    !> identified poles and U; `exact` on the file's identified modes and U (noted, same bound):
    !> 2.0e-2, the floor of a fit to 400 Hz at this dt.
    subroutine test_band(error)
        type(test_error), allocatable, intent(out) :: error

        character(len=*), parameter :: methods(3) = ['direct', 'fft   ', 'exact ']
        character(len=*), parameter :: path = scratch//'/band_400.uff'
        type(point_modes) :: truth, file_modes
        type(green_structure) :: structure
        type(error_type), allocatable :: fail
        type(multi_contact_response) :: reference, response
        class(multipoint_convolver), allocatable :: conv
        character(len=:), allocatable :: accuracy
        real(dp) :: x(4), y(4), worst, dt
        integer :: m, l

        dt = 2.5e-4_dp
        call patch_modes(file_modes, x, y, fail)
        if (.not. allocated(fail)) call plate_modes(tyre_plate(damping_ratio=0.02_dp), x, y, 1500.0_dp, truth, fail)
        if (.not. allocated(fail)) call write_file_of(path, truth, x, y, [(1.0_dp*l, l=0, 400)], as_receptance, fail)
        if (.not. allocated(fail)) call read_green_structure(path, green_options(), structure, fail)
        if (.not. allocated(fail)) &
            call make_multipoint_convolver('exact', truth, dt, 0.0_dp, 800, conv, accuracy, fail)
        if (.not. allocated(fail)) call roll(conv, x, 1.0_dp, dt, 800, 2.0e5_dp, 1000.0_dp, reference, fail)
        call check(error, .not. allocated(fail), 'the structure and its reference run: '//message_of(fail))
        if (allocated(error)) return
        call note('modes of the structure', real(truth%modes%n_modes(), dp))
        call note('modes of the file''s fit', real(structure%modes%modes%n_modes(), dp))
        do m = 1, size(methods)
            call green_file_convolver(structure, trim(methods(m)), dt, 0.0_dp, 800, conv, accuracy, fail)
            if (.not. allocated(fail)) call roll(conv, x, 1.0_dp, dt, 800, 2.0e5_dp, 1000.0_dp, response, fail)
            call check(error, .not. allocated(fail), trim(methods(m))//': '//message_of(fail))
            if (allocated(error)) return
            worst = maxval(abs(response%force - reference%force))/maxval(abs(reference%force))
            call note(trim(methods(m))//': max |F - F_structure|/max F', worst)
            call check(error, worst <= 2.0e-2_dp, trim(methods(m))//': more than 2e-2 off the structure; '//accuracy)
            if (allocated(error)) return
        end do
    end subroutine test_band

    !> data/patch_green.uff as shipped, and without its lines below 50 Hz (25 of 301) as a
    !> user's analyser might export it, each identified as data/patch_road.nml does (max_order
    !> 60) and rolled as it rolls (x_start 0.5 m, 5 m/s, 5e4 N/m per point, 3 kN, dt = 0.2 ms,
    !> 1000 steps), against `exact` on the plate's own modes to 10 kHz (the structure the file
    !> was written from), on the swing of its total force:
    !> - the file as shipped: `direct` and `fft` (g_ij by the inverse FFT, the model above
    !>   600 Hz) within 8e-3 (measured 7.5e-3; with G zero above 600 Hz 8.75e-3);
    !> - cut at 50 Hz: every method within 5 %. Before, `direct` and `fft` put line l at l*df
    !>   from 0 Hz: 0.61 off. Measured now: exact 2.3e-3, modal 3.8e-2 (no U), direct and fft
    !>   1.5e-2 (the identified modes, U in W0, by the rectangle rule).
    subroutine test_shipped_cut(error)
        type(test_error), allocatable, intent(out) :: error

        character(len=*), parameter :: methods(4) = ['exact ', 'modal ', 'direct', 'fft   ']
        type(uff_file) :: file
        type(point_modes) :: truth
        type(green_options) :: options
        type(green_structure) :: structure
        type(error_type), allocatable :: fail
        type(multi_contact_response) :: reference, response
        class(multipoint_convolver), allocatable :: conv
        character(len=:), allocatable :: accuracy, path
        real(dp) :: swing, worst, bound
        integer :: k, m, cut

        call make_directory(scratch, fail)
        call check(error, .not. allocated(fail), 'scratch: '//message_of(fail))
        if (allocated(error)) return
        do cut = 0, 25, 25
            call read_uff('data/patch_green.uff', file, fail)
            call check(error, .not. allocated(fail), 'the shipped file: '//message_of(fail))
            if (allocated(error)) return
            do k = 1, size(file%functions)
                associate (fun => file%functions(k))
                    fun%abscissa = fun%abscissa(cut + 1:)
                    fun%ordinate = fun%ordinate(cut + 1:)
                    if (allocated(fun%point_line)) deallocate (fun%point_line)
                end associate
            end do
            path = scratch//'/patch_green_from_'//trim(merge('0 ', '50', cut == 0))//'.uff'
            call write_uff(path, file%functions, file%nodes, fail, node_dataset=15)
            options%fit%max_order = 60
            if (.not. allocated(fail)) call read_green_structure(path, options, structure, fail)
            call check(error, .not. allocated(fail), path//': '//message_of(fail))
            if (allocated(error)) return
            if (cut == 0) then
                call plate_modes(tyre_plate(damping_ratio=0.02_dp), structure%matrix%x, structure%matrix%y, &
                                 1.0e4_dp, truth, fail)
                if (.not. allocated(fail)) &
                    call make_multipoint_convolver('exact', truth, 2.0e-4_dp, 0.01_dp, 1000, conv, accuracy, fail)
                if (.not. allocated(fail)) &
                    call roll(conv, structure%matrix%x, 0.5_dp, 2.0e-4_dp, 1000, 5.0e4_dp, 3000.0_dp, reference, fail)
                call check(error, .not. allocated(fail), 'the plate''s own modes: '//message_of(fail))
                if (allocated(error)) return
                swing = maxval(reference%total_force) - minval(reference%total_force)
            end if
            do m = 1, size(methods)
                bound = 0.05_dp
                if (cut == 0) bound = merge(8.0e-3_dp, 0.05_dp, m >= 3)
                call green_file_convolver(structure, trim(methods(m)), 2.0e-4_dp, 0.01_dp, 1000, conv, accuracy, &
                                          fail)
                if (.not. allocated(fail)) &
                    call roll(conv, structure%matrix%x, 0.5_dp, 2.0e-4_dp, 1000, 5.0e4_dp, 3000.0_dp, response, fail)
                call check(error, .not. allocated(fail), trim(methods(m))//': '//message_of(fail))
                if (allocated(error)) return
                worst = maxval(abs(response%total_force - reference%total_force))/swing
                call note('from '//trim(merge('0 ', '50', cut == 0))//' Hz, '//trim(methods(m)) &
                          //': max |total - total_plate|/swing', worst)
                call check(error, worst <= bound, path//' '//trim(methods(m))//': too far off the plate; '//accuracy)
                if (allocated(error)) return
            end do
        end do
    end subroutine test_shipped_cut

    !> A patch (points at x [m]) rolled by a convolver over data/road_sample.dat, its centre
    !> from x_start [m] at 5 m/s for n_steps of dt [s], linear contact springs of the given
    !> stiffness [N/m] per point, the preload [N] shared evenly.
    subroutine roll(conv, x, x_start, dt, n_steps, stiffness, preload, response, fail)
        class(multipoint_convolver), intent(inout) :: conv
        real(dp), intent(in) :: x(:), x_start, dt, stiffness, preload
        integer, intent(in) :: n_steps
        type(multi_contact_response), intent(out) :: response
        type(error_type), allocatable, intent(out) :: fail

        type(road_file) :: road
        real(dp), allocatable :: heights(:, :)
        integer :: i

        call read_road_file('data/road_sample.dat', road, fail)
        if (.not. allocated(fail)) &
            call sample_road(road, road_travel(x=x_start + (x - sum(x)/size(x)), speed=5.0_dp, dt=dt), n_steps, heights, fail)
        if (.not. allocated(fail)) &
            call run_multi_contact(conv, [(power_law(stiffness, 1.0_dp), i=1, size(x))], heights, &
                                   [(preload/size(x), i=1, size(x))], response, fail)
    end subroutine roll

    !> Points 0.06 m by 0.1 m around (L/2, b/2) of the plate (xi = 0.02) and its modes to 300 Hz.
    subroutine patch_modes(truth, x, y, fail)
        type(point_modes), intent(out) :: truth
        real(dp), intent(out) :: x(4), y(4)
        type(error_type), allocatable, intent(out) :: fail

        call make_directory(scratch, fail)
        if (allocated(fail)) return
        call patch_points([0.9425_dp, 0.1_dp], [0.06_dp, 0.1_dp], 2, 2, x, y)
        call plate_modes(tyre_plate(damping_ratio=0.02_dp), x, y, 300.0_dp, truth, fail)
    end subroutine patch_modes

    !> The modes' receptances at the given lines [Hz], written as `kind` (`as_receptance`,
    !> `as_mobility` or `as_accelerance`, records 9/10 saying so) with the nodes.
    subroutine write_file_of(path, modes, x, y, frequency, kind, fail)
        character(len=*), intent(in) :: path
        type(point_modes), intent(in) :: modes
        real(dp), intent(in) :: x(:), y(:), frequency(:)
        integer, intent(in) :: kind
        type(error_type), allocatable, intent(out) :: fail

        type(uff_function), allocatable :: functions(:)
        type(uff_node), allocatable :: nodes(:)
        complex(dp), allocatable :: g(:, :, :)
        complex(dp) :: factor
        integer :: i, j, k, l, n_c, n

        n_c = size(x)
        n = size(frequency)
        allocate (g(n_c, n_c, n), functions(n_c*n_c), nodes(n_c))
        do l = 1, n
            g(:, :, l) = patch_receptance(modes, 2.0_dp*pi*frequency(l))
            factor = (1.0_dp, 0.0_dp)
            if (kind == as_mobility) factor = cmplx(0.0_dp, 2.0_dp*pi*frequency(l), dp)
            if (kind == as_accelerance) factor = cmplx(-(2.0_dp*pi*frequency(l))**2, 0.0_dp, dp)
            g(:, :, l) = factor*g(:, :, l)
        end do
        do i = 1, n_c
            do j = 1, n_c
                k = (i - 1)*n_c + j
                functions(k) = receptance_function([i, 3], [j, 3], frequency(1), frequency(2) - frequency(1), &
                                                   g(i, j, :), 'G')
                functions(k)%abscissa = frequency
                functions(k)%even = all(abs(frequency(2:) - frequency(:n - 1) - (frequency(2) - frequency(1))) &
                                        <= 1.0e-9_dp)
                if (kind == as_mobility) functions(k)%numerator = uff_axis(11, 1, 0, 0, 'Velocity', 'm/s')
                if (kind == as_accelerance) functions(k)%numerator = uff_axis(12, 1, 0, 0, 'Acceleration', 'm/s^2')
            end do
            nodes(i) = uff_node(label=i, position=[x(i), y(i), 0.0_dp])
        end do
        call write_uff(path, functions, nodes, fail, node_dataset=2411)
    end subroutine write_file_of

end module test_greenfiles_mod
