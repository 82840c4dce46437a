!> The multi-point patch from a user's Green's matrix: the universal-file reader of
!> a Green's matrix (greenconv_model_green_matrix_file) on the shipped file and on each
!> malformed case, and the shared-pole identification (greenconv_ident_shared_poles) on clean
!> plate data (round-off, the true number of poles) and with 1 % noise (against the noise-free
!> receptances).
module test_patch_mod
    use, intrinsic :: iso_fortran_env, only: dp => real64
    use testsuite_mod, only: test_error, unittest_type, new_unittest, check, note
    use greenconv_core_error, only: error_type
    use scene_text_mod, only: message_of
    use greenconv_core_random, only: random_stream
    use greenconv_io_files, only: make_directory
    use greenconv_io_uff, only: uff_function, uff_node
    use greenconv_io_uff_write, only: write_uff, receptance_function
    use greenconv_model_point_modes, only: point_modes
    use greenconv_model_plate, only: tyre_plate, plate_modes, patch_points, patch_receptance
    use greenconv_model_green_matrix_file, only: green_matrix, read_green_matrix
    use greenconv_ident_lsce, only: error_e
    use greenconv_ident_mlfit, only: ml_options
    use greenconv_ident_shared_poles, only: shared_fit, identify_shared, shared_point_modes, shared_receptance
    implicit none
    private

    public :: collect_patch
    ! shared with the universal-file checks of test_uffchecks_mod
    public :: two_point_file

    !> Scratch directory for the files the tests write.
    character(len=*), parameter :: scratch = 'build/test_scratch/patch'
    real(dp), parameter :: pi = acos(-1.0_dp)

contains

    !> Tests of the Green's matrix reader and the shared-pole identification.
    subroutine collect_patch(testsuite)
        type(unittest_type), allocatable, intent(out) :: testsuite(:)

        testsuite = [new_unittest('reader: shipped data/patch_green.uff, 12 points, layout, reciprocal', test_shipped), &
                     new_unittest('reader: each malformed file refused with its message', test_malformed), &
                     new_unittest('reader: a non-reciprocal matrix warns and names the worst pair', &
                                  test_non_reciprocal), &
                     new_unittest('shared poles: clean plate data to round-off, true number of poles', test_clean), &
                     new_unittest('shared poles: 1 % noise, model against the noise-free matrix', test_noisy), &
                     new_unittest('shared poles: shipped data/patch_green.uff against its noise-free plate', &
                                  test_shipped_fit)]
    end subroutine collect_patch

    !> The shipped file: 12 points in label order with the 4 x 3 layout, 301 lines, reciprocal.
    subroutine test_shipped(error)
        type(test_error), allocatable, intent(out) :: error

        type(green_matrix) :: matrix
        type(error_type), allocatable :: fail
        real(dp) :: x(12), y(12)
        integer :: k

        call read_green_matrix('data/patch_green.uff', matrix, fail)
        call check(error, .not. allocated(fail), 'read_green_matrix failed: '//message_of(fail))
        if (allocated(error)) return
        call patch_points([0.9425_dp, 0.1_dp], [0.12_dp, 0.15_dp], 4, 3, x, y)
        call note('reciprocity ratio (about 1 for noise)', matrix%reciprocity)
        call check(error, matrix%n_points() == 12 .and. size(matrix%frequency) == 301 .and. &
                   all(matrix%node == [(k, k=1, 12)]), 'expected 12 points 1..12 and 301 lines')
        if (allocated(error)) return
        call check(error, maxval(abs(matrix%x - x)) < 1.0e-6_dp .and. maxval(abs(matrix%y - y)) < 1.0e-6_dp, &
                   'point layout differs from the 4 x 3 patch')
        if (allocated(error)) return
        call check(error, matrix%reciprocal .and. matrix%reciprocity < 1.5_dp, &
                   'the shipped (reciprocal, noisy) file should pass the reciprocity check: '//matrix%warning)
    end subroutine test_shipped

    !> Writes a small 2 x 2 matrix file with one defect and expects the message.
    subroutine test_malformed(error)
        type(test_error), allocatable, intent(out) :: error

        character(len=*), parameter :: expected(5) = [character(len=40) :: 'missing G for response node 2', &
                                                      'frequency grid', 'has no coordinates', 'mixed directions', &
                                                      'is given twice']
        type(uff_function), allocatable :: functions(:)
        type(uff_node), allocatable :: nodes(:)
        type(green_matrix) :: matrix
        type(error_type), allocatable :: fail
        character(len=:), allocatable :: path
        integer :: case

        call make_directory(scratch, fail)
        do case = 1, size(expected)
            call two_point_file(functions, nodes)
            select case (case)
            case (1)
                functions = functions([1, 2, 4])
            case (2)
                functions(3) = receptance_function([2, 3], [1, 3], 0.0_dp, 2.5_dp, functions(3)%ordinate, 'G')
            case (3)
                nodes = nodes(1:1)
            case (4)
                functions(2)%reference_direction = 2
            case (5)
                functions = [functions, functions(4)]
            end select
            path = scratch//'/bad_'//char(iachar('0') + case)//'.uff'
            call write_uff(path, functions, nodes, fail)
            call check(error, .not. allocated(fail), 'write_uff failed: '//message_of(fail))
            if (allocated(error)) return
            call read_green_matrix(path, matrix, fail)
            call check(error, allocated(fail), 'case '//trim(expected(case))//': accepted')
            if (allocated(error)) return
            call check(error, index(fail%message, trim(expected(case))) > 0, &
                       'case '//trim(expected(case))//': message "'//fail%message//'"')
            if (allocated(error)) return
        end do
    end subroutine test_malformed

    !> G_12 and G_21 differing by a smooth 20 % give a warning naming nodes 1 and 2.
    subroutine test_non_reciprocal(error)
        type(test_error), allocatable, intent(out) :: error

        type(uff_function), allocatable :: functions(:)
        type(uff_node), allocatable :: nodes(:)
        type(green_matrix) :: matrix
        type(error_type), allocatable :: fail
        character(len=:), allocatable :: path

        call make_directory(scratch, fail)
        call two_point_file(functions, nodes)
        functions(2)%ordinate = 1.2_dp*functions(2)%ordinate
        path = scratch//'/non_reciprocal.uff'
        call write_uff(path, functions, nodes, fail)
        call read_green_matrix(path, matrix, fail)
        call check(error, .not. allocated(fail), 'read_green_matrix failed: '//message_of(fail))
        if (allocated(error)) return
        call note('reciprocity ratio', matrix%reciprocity)
        call check(error, .not. matrix%reciprocal .and. index(matrix%warning, 'nodes 1 and 2') > 0, &
                   'expected a warning naming nodes 1 and 2, got "'//matrix%warning//'"')
    end subroutine test_non_reciprocal

    !> Clean receptances of the plate's modes up to 400 Hz (xi = 0.01, so that the 18 distinct
    !> frequencies stay apart in the summed driving points) on a 0-600 Hz grid by 1 Hz (the closest pair, 277.5 and 281.4 Hz, 4 half-power bands apart): the shared poles are
    !> the distinct plate frequencies (a cosine-sine pair is one pole), E at round-off, and the
    !> point modes for the convolvers give back the matrix.
    subroutine test_clean(error)
        type(test_error), allocatable, intent(out) :: error

        type(point_modes) :: truth, modes
        type(shared_fit) :: fit
        type(error_type), allocatable :: fail
        real(dp), allocatable :: frequency(:), distinct(:)
        complex(dp), allocatable :: g(:, :, :), rebuilt(:, :, :)
        real(dp) :: x(6), y(6), worst_pole
        integer :: l, k

        call patch_points([0.9425_dp, 0.1_dp], [0.12_dp, 0.15_dp], 3, 2, x, y)
        call plate_modes(tyre_plate(damping_ratio=0.01_dp), x, y, 400.0_dp, truth, fail)
        call check(error, .not. allocated(fail), 'plate_modes failed')
        if (allocated(error)) return
        frequency = [(1.0_dp*l, l=0, 600)]
        allocate (g(6, 6, size(frequency)))
        do l = 1, size(frequency)
            g(:, :, l) = patch_receptance(truth, 2.0_dp*pi*frequency(l))
        end do
        call identify_shared(frequency, g, .true., ml_options(residual_terms='none'), fit, fail)
        call check(error, .not. allocated(fail), 'identify_shared failed: '//message_of(fail))
        if (allocated(error)) return
        distinct = unique(aimag(truth%modes%pole))
        call note('true distinct poles', real(size(distinct), dp))
        call note('identified poles', real(size(fit%pole), dp))
        call note('E worst', fit%e_worst)
        call note('E mean', fit%e_mean)
        call check(error, size(fit%pole) == size(distinct), 'expected one pole per distinct plate frequency')
        if (allocated(error)) return
        worst_pole = 0.0_dp
        do k = 1, size(fit%pole)
            worst_pole = max(worst_pole, minval(abs(truth%modes%pole - fit%pole(k))/abs(fit%pole(k))))
        end do
        call note('worst relative pole error', worst_pole)
        call check(error, fit%e_worst < 1.0e-9_dp .and. worst_pole < 1.0e-9_dp, 'clean data not fitted to round-off')
        if (allocated(error)) return
        call note('largest distance from rank one', maxval(fit%rank_one))
        call shared_point_modes(fit, 1.0e-10_dp, modes)
        call note('terms of the point modes', real(modes%modes%n_modes(), dp))
        allocate (rebuilt(6, 6, size(frequency)))
        do l = 1, size(frequency)
            rebuilt(:, :, l) = patch_receptance(modes, 2.0_dp*pi*frequency(l))
        end do
        call note('point modes vs data, max |dG|/max|G|', maxval(abs(rebuilt - g))/maxval(abs(g)))
        call check(error, maxval(abs(rebuilt - g)) < 1.0e-9_dp*maxval(abs(g)), 'point modes do not rebuild G')
    end subroutine test_clean

    !> The clean case's matrix with 1 % complex Gaussian noise per line (G_ij and G_ji drawn
    !> apart, as the shipped file): the model must be closer to the noise-free receptances than
    !> the data are, E of eq. (7) against them below half the noise (0.005) for every pair. The
    !> closest pair (277.5/281.4 Hz) may merge into one pole under the noise: 17 or 18 poles.
    subroutine test_noisy(error)
        type(test_error), allocatable, intent(out) :: error

        type(point_modes) :: truth
        type(shared_fit) :: fit
        type(random_stream) :: stream
        type(error_type), allocatable :: fail
        real(dp), allocatable :: frequency(:)
        complex(dp), allocatable :: g(:, :, :), exact(:, :, :), model(:, :, :)
        real(dp) :: x(6), y(6), a, b, squares, worst_pole
        integer :: i, j, k, l

        call patch_points([0.9425_dp, 0.1_dp], [0.12_dp, 0.15_dp], 3, 2, x, y)
        call plate_modes(tyre_plate(damping_ratio=0.01_dp), x, y, 400.0_dp, truth, fail)
        frequency = [(1.0_dp*l, l=0, 600)]
        allocate (g(6, 6, size(frequency)), exact(6, 6, size(frequency)))
        stream = random_stream(14)
        do l = 1, size(frequency)
            exact(:, :, l) = patch_receptance(truth, 2.0_dp*pi*frequency(l))
            do j = 1, 6
                do i = 1, 6
                    a = gaussian(stream)
                    b = gaussian(stream)
                    g(i, j, l) = exact(i, j, l)*(1.0_dp + 0.01_dp*cmplx(a, b, kind=dp)/sqrt(2.0_dp))
                end do
            end do
        end do
        call identify_shared(frequency, g, .true., ml_options(), fit, fail)
        call check(error, .not. allocated(fail), 'identify_shared failed: '//message_of(fail))
        if (allocated(error)) return
        call shared_receptance(fit, frequency, model)
        squares = 0.0_dp
        do j = 1, 6
            do i = 1, 6
                squares = max(squares, error_e(exact(i, j, :), model(i, j, :)))
            end do
        end do
        worst_pole = 0.0_dp
        do k = 1, size(fit%pole)
            worst_pole = max(worst_pole, minval(abs(truth%modes%pole - fit%pole(k))/abs(fit%pole(k))))
        end do
        call note('poles', real(size(fit%pole), dp))
        call note('E worst', fit%e_worst)
        call note('E mean', fit%e_mean)
        call note('worst relative pole error', worst_pole)
        call note('worst E of the model against the noise-free G', squares)
        call check(error, size(fit%pole) >= 17 .and. squares < 0.005_dp, &
                   'expected at least 17 of the 18 poles and a model within half the 1 % noise of the noise-free G')
    end subroutine test_noisy

    !> The shipped file (0-600 Hz by 2 Hz, xi = 0.02, 1 % noise; example/write_patch_green.f90)
    !> identified with max_order = 60: the model against the noise-free receptances of the same
    !> plate must be within the noise, E of eq. (7) below 0.01 for every pair (the 1 % complex
    !> noise alone gives E about 0.009), with at least 25 of the 31 distinct mode frequencies
    !> the patch sees in band.
    subroutine test_shipped_fit(error)
        type(test_error), allocatable, intent(out) :: error

        type(green_matrix) :: matrix
        type(point_modes) :: truth
        type(shared_fit) :: fit
        type(error_type), allocatable :: fail
        complex(dp), allocatable :: model(:, :, :)
        complex(dp) :: exact(12, 12)
        real(dp) :: squares, e_mean
        integer :: i, j, l

        call read_green_matrix('data/patch_green.uff', matrix, fail)
        call check(error, .not. allocated(fail), 'read_green_matrix failed: '//message_of(fail))
        if (allocated(error)) return
        call identify_shared(matrix%frequency, matrix%g, .true., ml_options(max_order=60), fit, fail)
        call check(error, .not. allocated(fail), 'identify_shared failed: '//message_of(fail))
        if (allocated(error)) return
        call plate_modes(tyre_plate(damping_ratio=0.02_dp), matrix%x, matrix%y, 1.0e4_dp, truth, fail)
        call shared_receptance(fit, matrix%frequency, model)
        do l = 1, size(matrix%frequency)
            exact = patch_receptance(truth, 2.0_dp*pi*matrix%frequency(l))
            model(:, :, l) = model(:, :, l) - exact
            matrix%g(:, :, l) = exact
        end do
        squares = 0.0_dp
        e_mean = 0.0_dp
        do j = 1, 12
            do i = 1, 12
                associate (e => error_e(matrix%g(i, j, :), matrix%g(i, j, :) + model(i, j, :)))
                    squares = max(squares, e)
                    e_mean = e_mean + e/144
                end associate
            end do
        end do
        call note('poles', real(size(fit%pole), dp))
        call note('E worst (against the file)', fit%e_worst)
        call note('E mean (against the file)', fit%e_mean)
        call note('E worst against the noise-free G', squares)
        call note('E mean against the noise-free G', e_mean)
        call check(error, size(fit%pole) >= 25 .and. squares < 0.01_dp, &
                   'expected at least 25 poles and a model within the 1 % noise of the noise-free G')
    end subroutine test_shipped_fit

    !> A standard Gaussian number (Box-Muller).
    real(dp) function gaussian(stream)
        type(random_stream), intent(inout) :: stream

        real(dp) :: u1, u2

        u1 = 1.0_dp - stream%uniform()
        u2 = stream%uniform()
        gaussian = sqrt(-2.0_dp*log(u1))*cos(2.0_dp*pi*u2)
    end function gaussian

    !> A 2-point matrix file: G of a 2-degree-of-freedom-like pair of modes on 0..100 Hz, nodes 1, 2.
    subroutine two_point_file(functions, nodes)
        type(uff_function), allocatable, intent(out) :: functions(:)
        type(uff_node), allocatable, intent(out) :: nodes(:)

        complex(dp) :: g(2, 2, 51), s
        integer :: i, j, l

        do l = 1, 51
            s = cmplx(0.0_dp, 2.0_dp*pi*(l - 1)*2.0_dp, kind=dp)
            g(:, :, l) = reshape([1.0_dp, 0.5_dp, 0.5_dp, 1.0_dp], [2, 2])/(s**2 + 2.0_dp*0.05_dp*300.0_dp*s + 9.0e4_dp) &
                         + reshape([1.0_dp, -0.5_dp, -0.5_dp, 1.0_dp], [2, 2])/(s**2 + 2.0_dp*0.05_dp*500.0_dp*s + 2.5e5_dp)
        end do
        allocate (functions(4))
        do i = 1, 2
            do j = 1, 2
                functions((i - 1)*2 + j) = receptance_function([i, 3], [j, 3], 0.0_dp, 2.0_dp, g(i, j, :), 'G')
            end do
        end do
        nodes = [uff_node(label=1, position=[0.0_dp, 0.0_dp, 0.0_dp]), &
                 uff_node(label=2, position=[0.03_dp, 0.0_dp, 0.0_dp])]
    end subroutine two_point_file

    !> The distinct values of a list (relative tolerance 1e-9), in first-seen order.
    pure function unique(values) result(distinct)
        real(dp), intent(in) :: values(:)
        real(dp), allocatable :: distinct(:)

        integer :: k

        allocate (distinct(0))
        do k = 1, size(values)
            if (.not. any(abs(distinct - values(k)) <= 1.0e-9_dp*abs(values(k)))) distinct = [distinct, values(k)]
        end do
    end function unique

end module test_patch_mod
