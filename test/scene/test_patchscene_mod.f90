!> The multi-point scene on a user's Green's matrix: `&structure model = 'green_file'`
!> against the same structure given as modes, the methods against each other on the shipped
!> patch, the library entry on a file of impulse responses, the road texture reader on each
!> malformed case and its bilinear interpolation against closed forms, a sweep of such a scene.
module test_patchscene_mod
    use, intrinsic :: iso_fortran_env, only: dp => real64, int64
    use testsuite_mod, only: test_error, unittest_type, new_unittest, check, note
    use scene_text_mod, only: read_scene_text, run_scene_text, read_table, message_of, write_text
    use greenconv_core_error, only: error_type, stat_input
    use greenconv_io_files, only: make_directory
    use greenconv_io_columns, only: read_columns
    use greenconv_io_uff, only: uff_function, uff_node
    use greenconv_io_uff_write, only: write_uff, receptance_function, impulse_function
    use greenconv_model_point_modes, only: point_modes
    use greenconv_model_plate, only: tyre_plate, plate_modes, patch_points, patch_receptance
    use greenconv_model_road_file, only: road_file, read_road_file, sample_road, road_travel
    use greenconv_model_road_texture, only: road_texture, read_road_texture
    use greenconv_contact_single, only: contact_law
    use greenconv_contact_multi, only: multi_contact_response, run_multi_contact
    use greenconv_conv_multipoint, only: multipoint_convolver
    use greenconv_conv_builder, only: make_multipoint_convolver
    use greenconv_ident_green_structure, only: green_options, green_structure, read_green_structure
    use greenconv_conv_green_file, only: green_file_convolver, new_green_file_convolver, green_file_report
    use greenconv_scene_read_input, only: scene_type
    use greenconv_scene_run_runner, only: run_scene, check_scene
    use greenconv_scene_sweep, only: run_sweep
    use greenconv_core_text, only: int_text
    use fixture_files_mod, only: write_receptance_file
    use greenconv_contact_law_power, only: power_law
    implicit none
    private

    public :: collect_patchscene

    !> Scratch directory for the files the tests write.
    character(len=*), parameter :: scratch = 'build/test_scratch/patchscene'
    real(dp), parameter :: pi = acos(-1.0_dp)

    !> The shipped data/patch_green.uff, read and identified once for the tests that use it.
    type(green_structure), save :: shipped
    logical, save :: shipped_ready = .false.

contains

    !> Tests of the Green's-matrix scene, the library entry and the road texture.
    subroutine collect_patchscene(testsuite)
        type(unittest_type), allocatable, intent(out) :: testsuite(:)

        testsuite = [new_unittest('scene on a Green''s matrix file equals the plate''s modes run directly', &
                                  test_scene_against_modes), &
                     new_unittest('shipped patch: exact against the plate''s own modes within E', test_shipped_truth), &
                     new_unittest('shipped patch: modal, direct and fft agree with exact', test_shipped_methods), &
                     new_unittest('library entry on a file of g_ij(t): direct and fft equal the sampled modes', &
                                  test_impulse_file), &
                     new_unittest('scene on a file of g_ij(t): --check refuses what the run refuses', &
                                  test_impulse_scene), &
                     new_unittest('scene: a green_file scene''s bad values refused with their line', &
                                  test_scene_refusals), &
                     new_unittest('texture: each malformed file refused with file:line', test_texture_malformed), &
                     new_unittest('texture: bilinear gives back a plane and a bilinear surface, x^2 its closed form', &
                                  test_texture_bilinear), &
                     new_unittest('texture scene: rows across the patch see their own heights', test_texture_scene), &
                     new_unittest('sweep of a green_file scene on a texture: each row equals the scene run alone', &
                                  test_sweep_green_file)]
    end subroutine collect_patchscene

    ! ---- the scene against the same structure given as modes ------------------------------------

    !> A 2 x 2 patch of the plate with its modes up to 300 Hz, written as receptances on 0 to
    !> 400 Hz by 1 Hz (clean), rolled by a scene over data/road_sample.dat, against
    !> run_multi_contact on the plate's own modes with the scene's conventions (preload shared
    !> evenly, point i at x_start + (x_i - x_mean) + V*t). The identification recovers the modes
    !> to round-off (E of eq. (7) worst about 1e-13), so the contact forces of exact (implicit) and
    !> modal (explicit) must agree within 100*E_worst + 1e-12 of the largest force (1e-12: the
    !> Newton tolerance). Measured: 2e-15 for both.
    subroutine test_scene_against_modes(error)
        type(test_error), allocatable, intent(out) :: error

        character(len=*), parameter :: path = scratch//'/plate_2x2.uff'
        character(len=*), parameter :: methods(2) = ['exact', 'modal']
        type(point_modes) :: truth
        type(green_structure) :: structure
        type(error_type), allocatable :: fail
        type(road_file) :: road
        type(multi_contact_response) :: response
        class(multipoint_convolver), allocatable :: conv
        character(len=:), allocatable :: accuracy
        real(dp), allocatable :: rows(:, :), heights(:, :)
        real(dp) :: x(4), y(4), worst, bound
        integer :: m, i, n

        call small_patch(path, truth, x, y, fail)
        call check(error, .not. allocated(fail), 'the 2 x 2 patch file: '//message_of(fail))
        if (allocated(error)) return
        call read_green_structure(path, green_options(), structure, fail)
        call check(error, .not. allocated(fail), 'read_green_structure failed: '//message_of(fail))
        if (allocated(error)) return
        call note('E worst of the fit', structure%fit%e_worst)
        bound = 100.0_dp*structure%fit%e_worst + 1.0e-12_dp
        call run_scene_text(scratch, 'plate_2x2.nml', "&scene name = 'plate2x2', output_dir = '"//scratch &
            //"', dt = 5.0e-4, n_steps = 400 / &structure model = 'green_file', green_file = '"//path//"' / " &
            //"&road profile = 'file', road_file = 'data/road_sample.dat', x_start = 1.0, speed = 5.0 / " &
            //"&contact stiffness = 5.0e4, exponent = 1.0, preload = 1000.0 / " &
            //"&convolution methods = 'exact', 'modal', accuracy = 0.5 /", fail)
        ! accuracy = 0.5: the scene against the same modes run directly is under test, at one dt
        call check(error, .not. allocated(fail), 'the scene runs: '//message_of(fail))
        if (allocated(error)) return
        call read_road_file('data/road_sample.dat', road, fail)
        call sample_road(road, road_travel(x=1.0_dp + (x - sum(x)/4), speed=5.0_dp, dt=5.0e-4_dp), 400, heights, fail)
        call check(error, .not. allocated(fail), 'the road covers the run')
        if (allocated(error)) return
        do m = 1, size(methods)
            call read_table(scratch//'/plate2x2_'//trim(methods(m))//'.dat', 8, rows, fail)
            call check(error, .not. allocated(fail) .and. size(rows, 1) == 400*4, trim(methods(m)) &
                       //': N_t*N_c rows of 8 columns: '//message_of(fail))
            if (allocated(error)) return
            ! the layout: x and y of the file's nodes, the road under each point at t = 0
            call check(error, all(rows(1:4, 2) == x) .and. all(rows(1:4, 8) == y) .and. &
                       all(rows(1:4, 3) == heights(0, :)), trim(methods(m))//': columns x, y and u_road at t = 0')
            if (allocated(error)) return
            call make_multipoint_convolver(trim(methods(m)), truth, 5.0e-4_dp, 0.01_dp, 400, conv, accuracy, fail)
            call run_multi_contact(conv, [(power_law(5.0e4_dp, 1.0_dp), i=1, 4)], heights, [(250.0_dp, i=1, 4)], &
                                   response, fail)
            call check(error, .not. allocated(fail), trim(methods(m))//': reference run: '//message_of(fail))
            if (allocated(error)) return
            worst = 0.0_dp
            do n = 0, 399
                worst = max(worst, maxval(abs(rows(4*n + 1:4*n + 4, 5) - response%force(n, :))))
            end do
            worst = worst/maxval(abs(response%force))
            call note(trim(methods(m))//': max |F_scene - F_modes|/max F', worst)
            call check(error, worst <= bound, trim(methods(m))//': the scene on the file differs from the modes by ' &
                       //'more than 100*E_worst + 1e-12')
            if (allocated(error)) return
        end do
    end subroutine test_scene_against_modes

    ! ---- the shipped patch ---------------------------------------------------------------------

    !> data/patch_green.uff read and identified once (as data/patch_road.nml does, max_order 60).
    subroutine shipped_structure(fail)
        type(error_type), allocatable, intent(out) :: fail

        type(green_options) :: options

        if (shipped_ready) return
        options%fit%max_order = 60
        call read_green_structure('data/patch_green.uff', options, shipped, fail)
        shipped_ready = .not. allocated(fail)
    end subroutine shipped_structure

    !> The total contact force of a run of `method` on the shipped patch (dt = 0.2 ms, 1000 steps
    !> at 5 m/s over data/road_sample.dat from x_start = 0.5 m, k_c = 5e4 N/m per point, 3000 N).
    subroutine shipped_run(method, total, accuracy, fail)
        character(len=*), intent(in) :: method
        real(dp), allocatable, intent(out) :: total(:)
        character(len=:), allocatable, intent(out) :: accuracy
        type(error_type), allocatable, intent(out) :: fail

        class(multipoint_convolver), allocatable :: conv
        type(multi_contact_response) :: response
        real(dp), allocatable :: heights(:, :)
        integer :: n

        call shipped_structure(fail)
        if (allocated(fail)) return
        call green_file_convolver(shipped, method, 2.0e-4_dp, 0.01_dp, 1000, conv, accuracy, fail)
        if (allocated(fail)) return
        call patch_road(shipped%matrix%x, heights, fail)
        if (allocated(fail)) return
        call run_multi_contact(conv, [(power_law(5.0e4_dp, 1.0_dp), n=1, 12)], heights, &
                               [(250.0_dp, n=1, 12)], response, fail)
        call conv%release()
        total = response%total_force
    end subroutine shipped_run

    !> The road heights under points at x_i, with the scene's conventions (x_start = 0.5 m).
    subroutine patch_road(x, heights, fail)
        real(dp), intent(in) :: x(:)
        real(dp), allocatable, intent(out) :: heights(:, :)
        type(error_type), allocatable, intent(out) :: fail

        type(road_file) :: road

        call read_road_file('data/road_sample.dat', road, fail)
        if (.not. allocated(fail)) call sample_road(road, road_travel(x=0.5_dp + (x - sum(x)/size(x)), speed=5.0_dp, &
                                                                                 dt=2.0e-4_dp), 1000, heights, fail)
    end subroutine patch_road

    !> The shipped file is the plate of example/write_patch_green.f90 (every mode to 10 kHz,
    !> xi = 0.02) with 1 % noise. exact on the file (the identified modes and the fit's upper
    !> residual U, implicit) must follow exact on the plate's own 1582 modes within E_worst (the
    !> fit's worst E of eq. (7), 0.0126) of the total force's range: a compliance off by E moves
    !> the forces by about E of their swing. Measured: 2.3e-3 of a 167 N swing.
    subroutine test_shipped_truth(error)
        type(test_error), allocatable, intent(out) :: error

        type(point_modes) :: truth
        type(error_type), allocatable :: fail
        class(multipoint_convolver), allocatable :: conv
        type(multi_contact_response) :: response
        character(len=:), allocatable :: accuracy
        real(dp), allocatable :: total(:), heights(:, :)
        real(dp) :: swing, worst
        integer :: n

        call shipped_run('exact', total, accuracy, fail)
        call check(error, .not. allocated(fail), 'exact on the file: '//message_of(fail))
        if (allocated(error)) return
        call plate_modes(tyre_plate(damping_ratio=0.02_dp), shipped%matrix%x, shipped%matrix%y, 1.0e4_dp, truth, fail)
        call patch_road(shipped%matrix%x, heights, fail)
        call make_multipoint_convolver('exact', truth, 2.0e-4_dp, 0.01_dp, 1000, conv, accuracy, fail)
        call run_multi_contact(conv, [(power_law(5.0e4_dp, 1.0_dp), n=1, 12)], heights, [(250.0_dp, n=1, 12)], &
                               response, fail)
        call check(error, .not. allocated(fail), 'exact on the plate''s modes: '//message_of(fail))
        if (allocated(error)) return
        swing = maxval(response%total_force) - minval(response%total_force)
        worst = maxval(abs(total - response%total_force))/swing
        call note('plate modes', real(truth%modes%n_modes(), dp))
        call note('E worst of the fit', shipped%fit%e_worst)
        call note('total force swing [N]', swing)
        call note('max |F_file - F_plate|/swing', worst)
        call check(error, worst <= shipped%fit%e_worst, 'exact on the file is off the plate by more than E_worst')
    end subroutine test_shipped_truth

    !> The four methods of data/patch_road.nml on the shipped file, on the total force's swing:
    !> - fft equals direct (one table, summed two ways) within 1e-9;
    !> - direct (g_ij by the inverse FFT of G: the data, band-limited) against exact (the fit,
    !>   with U) within 2*E_worst (0.025): two routes from the same noisy data, each within about
    !>   E of it;
    !> - modal (explicit, the modes without U) against exact within the modes' own worst E
    !>   (0.142: E of the modes alone, the accuracy its summary line states).
    !> Measured: 5e-15, 9.1e-3 and 3.8e-2.
    subroutine test_shipped_methods(error)
        type(test_error), allocatable, intent(out) :: error

        type(error_type), allocatable :: fail
        character(len=:), allocatable :: accuracy
        real(dp), allocatable :: exact(:), modal(:), direct(:), fft(:)
        real(dp) :: swing, modal_gap, direct_gap, fft_gap

        call shipped_run('exact', exact, accuracy, fail)
        if (.not. allocated(fail)) call shipped_run('modal', modal, accuracy, fail)
        if (.not. allocated(fail)) call shipped_run('fft', fft, accuracy, fail)
        if (.not. allocated(fail)) call shipped_run('direct', direct, accuracy, fail)
        call check(error, .not. allocated(fail), 'the four runs: '//message_of(fail))
        if (allocated(error)) return
        call check(error, index(accuracy, 'inverse FFT of G') > 0, 'direct uses the inverse FFT of G: '//accuracy)
        if (allocated(error)) return
        swing = maxval(exact) - minval(exact)
        fft_gap = maxval(abs(fft - direct))/swing
        direct_gap = maxval(abs(direct - exact))/swing
        modal_gap = maxval(abs(modal - exact))/swing
        call note('max |fft - direct|/swing', fft_gap)
        call note('max |direct - exact|/swing', direct_gap)
        call note('max |modal - exact|/swing', modal_gap)
        call note('E worst of the modes alone', maxval(shipped%e_modes))
        call check(error, fft_gap <= 1.0e-9_dp, 'fft differs from direct')
        if (allocated(error)) return
        call check(error, direct_gap <= 2.0_dp*shipped%fit%e_worst, 'direct is off exact by more than 2*E_worst')
        if (allocated(error)) return
        call check(error, modal_gap <= maxval(shipped%e_modes), 'modal is off exact by more than its modes'' E')
    end subroutine test_shipped_methods

    ! ---- the library entry on impulse responses ------------------------------------------------

    !> A 2-point patch's g_ij(t) sampled from the plate's modes to 300 Hz every 0.2 ms for 0.3 s,
    !> written as datasets 58 of function type 1 (13 digits). new_green_file_convolver at dt = 0.4 ms
    !> (every 2nd sample) must give, for direct and fft, the forces of make_multipoint_convolver's
    !> direct on the same modes within 1e-9 of the largest force; modal is refused (no modes), and
    !> so is a dt that is not a whole multiple of the file's step.
    subroutine test_impulse_file(error)
        type(test_error), allocatable, intent(out) :: error

        character(len=*), parameter :: path = scratch//'/impulses_2.uff'
        character(len=*), parameter :: methods(2) = ['direct', 'fft   ']
        type(point_modes) :: truth
        type(error_type), allocatable :: fail
        type(green_file_report) :: report
        class(multipoint_convolver), allocatable :: conv
        type(multi_contact_response) :: reference, response
        character(len=:), allocatable :: accuracy
        real(dp), allocatable :: heights(:, :)
        real(dp) :: x(2), worst
        integer :: i, m

        call impulse_file(path, truth, x, fail)
        call check(error, .not. allocated(fail), 'the impulse file: '//message_of(fail))
        if (allocated(error)) return
        heights = reshape([((1.0e-3_dp*sin(2.0_dp*pi*30.0_dp*4.0e-4_dp*m + i), m=0, 499), i=1, 2)], [500, 2])
        call make_multipoint_convolver('direct', truth, 4.0e-4_dp, 0.01_dp, 500, conv, accuracy, fail)
        call run_multi_contact(conv, [power_law(5.0e4_dp, 1.0_dp), power_law(5.0e4_dp, 1.0_dp)], heights, &
                               [200.0_dp, 200.0_dp], reference, fail)
        do m = 1, size(methods)
            call new_green_file_convolver(path, trim(methods(m)), 4.0e-4_dp, 500, conv, report, fail)
            call check(error, .not. allocated(fail), trim(methods(m))//': '//message_of(fail))
            if (allocated(error)) return
            call check(error, all(report%node == [1, 2]) .and. all(abs(report%x - x) <= 1.0e-6_dp*maxval(x)) .and. &
                       index(report%accuracy, 'of the file') > 0, trim(methods(m))//': report '//report%accuracy)
            if (allocated(error)) return
            call run_multi_contact(conv, [power_law(5.0e4_dp, 1.0_dp), power_law(5.0e4_dp, 1.0_dp)], heights, &
                                   [200.0_dp, 200.0_dp], response, fail)
            call conv%release()
            worst = maxval(abs(response%force - reference%force))/maxval(abs(reference%force))
            call note(trim(methods(m))//': max |F_file - F_modes|/max F', worst)
            call check(error, worst <= 1.0e-9_dp, trim(methods(m))//': off the sampled modes')
            if (allocated(error)) return
        end do
        call new_green_file_convolver(path, 'modal', 4.0e-4_dp, 500, conv, report, fail)
        call check(error, allocated(fail), 'modal accepted on a file of g_ij(t)')
        if (allocated(error)) return
        call check(error, index(fail%message, 'needs modes') > 0, 'modal message: '//fail%message)
        if (allocated(error)) return
        call new_green_file_convolver(path, 'direct', 3.0e-4_dp, 500, conv, report, fail)
        call check(error, allocated(fail), 'dt = 3e-4 s accepted on a file sampled every 2e-4 s')
        if (allocated(error)) return
        call check(error, fail%stat == stat_input .and. index(fail%message, 'a whole multiple of it') > 0, &
                   'dt message: '//fail%message)
    end subroutine test_impulse_file

    !> The file of test_impulse_file: g_ij(t) of a 2-point patch (0.06 m apart along x) of the
    !> plate's modes to 300 Hz, every 0.2 ms for 0.3 s, as datasets 58 of function type 1.
    subroutine impulse_file(path, truth, x, fail)
        character(len=*), intent(in) :: path
        type(point_modes), intent(out) :: truth
        real(dp), intent(out) :: x(2)
        type(error_type), allocatable, intent(out) :: fail

        type(uff_function) :: functions(4)
        type(uff_node) :: nodes(2)
        real(dp) :: y(2), t(1500)
        integer :: i, j, m

        call make_directory(scratch, fail)
        if (allocated(fail)) return
        call patch_points([0.9425_dp, 0.1_dp], [0.06_dp, 0.05_dp], 2, 1, x, y)
        call plate_modes(tyre_plate(damping_ratio=0.02_dp), x, y, 300.0_dp, truth, fail)
        if (allocated(fail)) return
        t = [(2.0e-4_dp*m, m=0, 1499)]
        do i = 1, 2
            do j = 1, 2
                functions(2*(i - 1) + j) = impulse_function([i, 3], [j, 3], 0.0_dp, 2.0e-4_dp, truth%green(i, j, t), &
                                                            'g')
            end do
            nodes(i) = uff_node(label=i, position=[x(i), y(i), 0.0_dp])
        end do
        call write_uff(path, functions, nodes, fail, node_dataset=2411)
    end subroutine impulse_file

    !> A green_file scene on a file of g_ij(t) runs direct; --check (check_scene) refuses modal
    !> and a dt that is not a whole multiple of the file's step with the run's own message.
    subroutine test_impulse_scene(error)
        type(test_error), allocatable, intent(out) :: error

        character(len=*), parameter :: path = scratch//'/impulses_scene.uff'
        character(len=*), parameter :: cases(3) = [character(len=40) :: &
            "dt = 4.0e-4 / x methods = 'direct'", "dt = 4.0e-4 / x methods = 'modal'", &
            "dt = 3.0e-4 / x methods = 'fft'"]
        type(point_modes) :: truth
        type(scene_type) :: scene
        type(error_type), allocatable :: fail, run_fail
        character(len=:), allocatable :: text
        real(dp) :: x(2)
        integer :: k, unit, slash

        call impulse_file(path, truth, x, fail)
        call check(error, .not. allocated(fail), 'the impulse file: '//message_of(fail))
        if (allocated(error)) return
        do k = 1, size(cases)
            slash = index(cases(k), ' x ')
            text = "&scene name = 'impulses', output_dir = '"//scratch//"', n_steps = 200, "//cases(k)(:slash) &
                   //"&structure model = 'green_file', green_file = '"//path//"' / &road profile = 'file', " &
                   //"road_file = 'data/road_sample.dat', x_start = 1.0, speed = 5.0 / &contact stiffness = 5.0e4, " &
                   //"exponent = 1.0, preload = 400.0 / &convolution "//trim(cases(k)(slash + 3:)) &
                   //', accuracy = 0.5 /'
            ! accuracy = 0.5: what --check and the run accept is under test, not the step's error
            call read_scene_text(scratch, 'impulses.nml', text, scene, fail)
            call check(error, .not. allocated(fail), 'case '//int_text(k)//': read: '//message_of(fail))
            if (allocated(error)) return
            open (newunit=unit, status='scratch', action='readwrite')
            call check_scene(scene, unit, fail)
            call run_scene(scene, unit, run_fail)
            close (unit)
            if (k == 1) then
                call check(error, .not. (allocated(fail) .or. allocated(run_fail)), 'direct: checked and run: ' &
                           //message_of(fail)//message_of(run_fail))
            else
                call check(error, allocated(fail) .and. allocated(run_fail), 'case '//int_text(k)//': accepted')
                if (allocated(error)) return
                call check(error, fail%message == run_fail%message .and. fail%stat == stat_input .and. &
                           index(fail%message, 'impulses.nml:1: &convolution methods: ') > 0, &
                           'case '//int_text(k)//': --check "'//fail%message//'", run "'//run_fail%message//'"')
            end if
            if (allocated(error)) return
        end do
    end subroutine test_impulse_scene

    ! ---- scene refusals ------------------------------------------------------------------------

    !> A green_file scene states no n_points (the file's nodes are the points), identifies by
    !> 'ml' only, and a texture needs a multi-point model: each refused with its file and line.
    subroutine test_scene_refusals(error)
        type(test_error), allocatable, intent(out) :: error

        character(len=*), parameter :: head = "&scene dt = 2.0e-4, n_steps = 10 / &structure model = 'green_file', " &
            //"green_file = 'data/patch_green.uff' /"
        character(len=*), parameter :: tail = " / &contact stiffness = 5.0e4, exponent = 1.0, preload = 3000.0 / " &
            //"&convolution methods = 'exact' /"
        character(len=*), parameter :: road = " &road profile = 'file', road_file = 'data/road_sample.dat'"
        type(scene_type) :: scene
        type(error_type), allocatable :: fail

        call read_scene_text(scratch, 'points.nml', head//road//" / &contact n_points = 12, stiffness = 5.0e4, " &
                             //"exponent = 1.0, preload = 3000.0 / &convolution methods = 'exact' /", scene, fail)
        call check(error, allocated(fail), 'n_points accepted for green_file')
        if (allocated(error)) return
        call check(error, index(fail%message, "points.nml:1: &contact n_points: expected no value for model " &
                                //"'green_file'") > 0, 'message: '//fail%message)
        if (allocated(error)) return
        call read_scene_text(scratch, 'lsce.nml', head//" &identification method = 'lsce' /"//road//tail, scene, fail)
        call check(error, allocated(fail), 'lsce accepted for green_file')
        if (allocated(error)) return
        call check(error, index(fail%message, "lsce.nml:1: &identification method: expected 'ml', 'poly_reference' " &
                                //"or 'auto' for model 'green_file'") > 0, 'message: '//fail%message)
        if (allocated(error)) return
        call read_scene_text(scratch, 'sdof_texture.nml', "&scene dt = 1.0e-4, n_steps = 100 / " &
                             //"&structure model = 'sdof', " &
                             //"mass = 1.0, stiffness = 1.0e6, damping_ratio = 0.02 / &road profile = 'texture', " &
                             //"texture_file = 'data/road_texture.dat' / &contact stiffness = 1.0e6, exponent = 1.5 /" &
                             //" &convolution methods = 'modal' /", scene, fail)
        call check(error, allocated(fail), 'a texture accepted for one contact point')
        if (allocated(error)) return
        call check(error, index(fail%message, "sdof_texture.nml:1: &road profile: expected 'sine', 'random' or " &
                                //"'file' for model 'sdof'") > 0, 'message: '//fail%message)
        if (allocated(error)) return
        call run_scene_text(scratch, 'off_texture.nml', head//" &road profile = 'texture', texture_file = " &
                            //"'data/road_texture.dat', x_start = 3.98"//tail, fail)
        call check(error, allocated(fail), 'a run off the texture accepted')
        if (allocated(error)) return
        call check(error, fail%stat == stat_input .and. index(fail%message, "off_texture.nml:1: &road x_start: " &
                   //"data/road_texture.dat: expected a texture from x =") > 0, 'message: '//fail%message)
    end subroutine test_scene_refusals

    ! ---- road texture --------------------------------------------------------------------------

    !> Each malformed texture file gets one message naming the file and the line, status 2.
    subroutine test_texture_malformed(error)
        type(test_error), allocatable, intent(out) :: error

        character(len=*), parameter :: nl = new_line('a')
        character(len=*), parameter :: y3 = '# texture'//nl//'  -0.1 0.0 0.1'//nl
        character(len=100) :: expected(10)
        character(len=200) :: text(10)
        type(road_texture) :: texture
        type(error_type), allocatable :: fail
        character(len=:), allocatable :: path
        integer :: k

        text(1) = '# only comments'//nl//nl
        expected(1) = ': expected a header line of lateral positions y [m]'
        text(2) = '# one y'//nl//'0.0'//nl//'0.0 1e-3'//nl//'1.0 2e-3'
        expected(2) = ':2: expected at least 2 lateral positions y [m]'
        text(3) = '  -0.1 abc 0.1'//nl
        expected(3) = ':1: column 2 (y_2): expected a number, found "abc"'
        text(4) = '  -0.1 0.1 0.1'//nl
        expected(4) = ':1: y_3: expected a position above 0.1 m (y must increase)'
        text(5) = y3//'0.0 0 0 0'//nl//'0.1 0 0'
        expected(5) = ':4: expected 4 values (x [m], then the heights [m] at the 3 y of line 2), found 3'
        text(6) = y3//'0.0 0 NaN 0'//nl//'0.1 0 0 0'
        expected(6) = ':3: column 3 (h(y_2)): expected a finite number, found "NaN"'
        text(7) = y3//'0.0 0 0 0'//nl//'0.0 0 0 0'
        expected(7) = ':4: expected x above 0.0 m (x must increase), found 0.0 m'
        text(8) = y3//'0.0 0 0 0'//nl
        expected(8) = ': expected at least 2 lines of x [m] and heights [m] after the header line 2, found 1'
        text(9) = y3//'0.0 0 0 0 0'//nl//'0.1 0 0 0'
        expected(9) = ':3: expected 4 values'
        text(10) = ''
        expected(10) = ': cannot open the road texture file'
        call make_directory(scratch, fail)
        do k = 1, size(text)
            path = scratch//'/texture_'//char(iachar('a') + k - 1)//'.dat'
            if (k < size(text)) then
                call write_text(path, trim(text(k)))
            else
                path = scratch//'/no_such_texture.dat'
            end if
            call read_road_texture(path, texture, fail)
            call check(error, allocated(fail), 'case '//char(iachar('a') + k - 1)//' accepted')
            if (allocated(error)) return
            call check(error, fail%stat == stat_input .and. index(fail%message, path//trim(expected(k))) == 1, &
                       'case '//char(iachar('a') + k - 1)//': expected "'//path//trim(expected(k))//'", found "' &
                       //fail%message//'"')
            if (allocated(error)) return
        end do
    end subroutine test_texture_malformed

    !> On an uneven grid, h = a + b*x + c*y + d*x*y (a plane for d = 0) is bilinear and the
    !> interpolation gives it back to round-off (1e-13 of its size) everywhere in the grid; beyond
    !> the grid the edge value. h = x^2 is not: between x_i and x_i+1 the linear interpolation
    !> exceeds it by (x - x_i)*(x_i+1 - x), to round-off.
    subroutine test_texture_bilinear(error)
        type(test_error), allocatable, intent(out) :: error

        real(dp), parameter :: xs(5) = [0.0_dp, 0.013_dp, 0.05_dp, 0.21_dp, 0.3_dp]
        real(dp), parameter :: ys(4) = [-0.1_dp, -0.02_dp, 0.04_dp, 0.1_dp]
        real(dp), parameter :: a = 1.0e-3_dp, b = -2.0e-3_dp, c = 5.0e-3_dp
        type(road_texture) :: plane, twisted, square
        type(error_type), allocatable :: fail
        real(dp) :: x, y, worst, worst_square, exact, bound
        integer :: i, j, low

        call texture_file(scratch//'/plane.dat', xs, ys, 0.0_dp, plane, fail)
        if (.not. allocated(fail)) call texture_file(scratch//'/twisted.dat', xs, ys, 0.07_dp, twisted, fail)
        if (.not. allocated(fail)) call texture_file(scratch//'/square.dat', xs, ys, -1.0_dp, square, fail)
        call check(error, .not. allocated(fail), 'texture files: '//message_of(fail))
        if (allocated(error)) return
        worst = 0.0_dp
        worst_square = 0.0_dp
        do i = 0, 60
            do j = 0, 40
                x = 0.3_dp*i/60
                y = -0.1_dp + 0.2_dp*j/40
                worst = max(worst, abs(plane%height_at(x, y) - (a + b*x + c*y)), &
                            abs(twisted%height_at(x, y) - (a + b*x + c*y + 0.07_dp*x*y)))
                low = count(xs <= x)
                low = min(low, size(xs) - 1)
                exact = x**2 + (x - xs(low))*(xs(low + 1) - x)
                worst_square = max(worst_square, abs(square%height_at(x, y) - exact))
            end do
        end do
        bound = 1.0e-13_dp*(abs(a) + abs(b)*0.3_dp + abs(c)*0.1_dp)
        call note('plane and bilinear: max |h - closed form|', worst)
        call note('x^2: max |h - (x^2 + (x - x_i)(x_i+1 - x))|', worst_square)
        call check(error, worst <= bound, 'a bilinear surface is not reproduced')
        if (allocated(error)) return
        call check(error, worst_square <= 1.0e-15_dp, 'x^2: interpolation error off its closed form')
        if (allocated(error)) return
        call check(error, plane%height_at(-1.0_dp, 0.5_dp) == plane%height_at(0.0_dp, 0.1_dp) .and. &
                   plane%height_at(9.0_dp, -3.0_dp) == plane%height_at(0.3_dp, -0.1_dp), &
                   'beyond the grid: the edge value')
    end subroutine test_texture_bilinear

    !> Write and read a texture on the grid xs x ys: a + b*x + c*y + d*x*y with the constants of
    !> test_texture_bilinear, or x^2 when d < 0. Written with 17 digits.
    subroutine texture_file(path, xs, ys, d, texture, fail)
        character(len=*), intent(in) :: path
        real(dp), intent(in) :: xs(:), ys(:), d
        type(road_texture), intent(out) :: texture
        type(error_type), allocatable, intent(out) :: fail

        integer :: unit, i, j

        call make_directory(scratch, fail)
        if (allocated(fail)) return
        open (newunit=unit, file=path, status='replace', action='write')
        write (unit, '(a)') '# a test texture'
        write (unit, '(*(es26.17e3))') ys
        do i = 1, size(xs)
            if (d < 0.0_dp) then
                write (unit, '(*(es26.17e3))') xs(i), [(xs(i)**2, j=1, size(ys))]
            else
                write (unit, '(*(es26.17e3))') xs(i), 1.0e-3_dp - 2.0e-3_dp*xs(i) + 5.0e-3_dp*ys + d*xs(i)*ys
            end if
        end do
        close (unit)
        call read_road_texture(path, texture, fail)
    end subroutine texture_file

    !> A green_file scene (the 2 x 2 patch) over a texture whose height varies across only,
    !> h = 1e-3*y/0.1 m (uniform along x): the rows of points across the patch, at
    !> y_start + (y_i - y_mean), see 1e-3*(y_i - y_mean)/0.1 m to round-off (column u_road), and
    !> the row on the higher side carries more force.
    subroutine test_texture_scene(error)
        type(test_error), allocatable, intent(out) :: error

        character(len=*), parameter :: path = scratch//'/slope.dat', patch = scratch//'/plate_2x2_slope.uff'
        type(point_modes) :: truth
        type(error_type), allocatable :: fail
        real(dp), allocatable :: rows(:, :)
        real(dp) :: x(4), y(4), y_mean, worst
        integer :: k

        call small_patch(patch, truth, x, y, fail)
        call check(error, .not. allocated(fail), 'the 2 x 2 patch file: '//message_of(fail))
        if (allocated(error)) return
        call write_text(path, '# slope across'//new_line('a')//'  -0.1  0.1'//new_line('a')//'0.0 -1e-3 1e-3' &
                        //new_line('a')//'10.0 -1e-3 1e-3')
        call run_scene_text(scratch, 'slope.nml', "&scene name = 'slope', output_dir = '"//scratch &
            //"', dt = 2.0e-4, n_steps = 20 / &structure model = 'green_file', green_file = '"//patch//"' /" &
            //" &road profile = 'texture', texture_file = '"//path &
            //"', x_start = 1.0, speed = 5.0 / &contact stiffness = 5.0e4, exponent = 1.0, preload = 3000.0 / " &
            //"&convolution methods = 'fft', accuracy = 0.5 /", fail)
        ! accuracy = 0.5: the heights each row sees are under test, on 20 steps
        call check(error, .not. allocated(fail), 'the scene runs: '//message_of(fail))
        if (allocated(error)) return
        call read_table(scratch//'/slope_fft.dat', 8, rows, fail)
        call check(error, .not. allocated(fail) .and. size(rows, 1) == 20*4, '20*4 rows of 8 columns')
        if (allocated(error)) return
        y_mean = sum(rows(1:4, 8))/4
        worst = 0.0_dp
        do k = 1, size(rows, 1)
            worst = max(worst, abs(rows(k, 3) - 1.0e-3_dp*(rows(k, 8) - y_mean)/0.1_dp))
        end do
        call note('max |u_road - slope(y - y_mean)| [m]', worst)
        call check(error, worst <= 1.0e-18_dp, 'rows across the patch do not see the slope at y - y_mean')
        if (allocated(error)) return
        call check(error, all(rows(4*19 + 3:4*19 + 4, 5) > maxval(rows(4*19 + 1:4*19 + 2, 5))), &
                   'the row on the higher side (y = 0.125 m) carries more force')
    end subroutine test_texture_scene

    !> A sweep (`&scene task = 'sweep'`) of a green_file scene (the 2 x 2 patch) on a texture
    !> over road.speed = 4 and 6 m/s, methods exact and fft: each row of the table, read back,
    !> gives the max, mean and rms of the total force that the same scene run alone at that
    !> speed writes in its output (its column f_total), to the table's 8 significant digits
    !> (relative 1e-7), with status 0 and every step in contact.
    subroutine test_sweep_green_file(error)
        type(test_error), allocatable, intent(out) :: error

        character(len=*), parameter :: patch = scratch//'/plate_2x2_sweep.uff', texture = scratch//'/bumps.dat'
        character(len=*), parameter :: methods(2) = ['exact', 'fft  ']
        character(len=:), allocatable :: base
        type(point_modes) :: truth
        type(error_type), allocatable :: fail
        real(dp), allocatable :: rows(:, :), table(:, :), total(:)
        real(dp) :: x(4), y(4), expected(3), worst
        character(len=8) :: names(16)
        integer, allocatable :: line_of(:)
        integer :: unit, v, m, k

        call small_patch(patch, truth, x, y, fail)
        call check(error, .not. allocated(fail), 'the 2 x 2 patch file: '//message_of(fail))
        if (allocated(error)) return
        ! heights varying along x and across y: 1 mm bumps 0.05 m apart, 0.5 mm higher on one side
        call write_text(texture, '# bumps'//new_line('a')//'  -0.1  0.1'//new_line('a') &
                        //bump_rows(0.0_dp, 12.0_dp, 0.01_dp))
        base = " &structure model = 'green_file', green_file = '"//patch//"' /" &
               //" &road profile = 'texture', texture_file = '"//texture &
               //"', x_start = 1.0, speed = 5.0 / &contact stiffness = 5.0e4, exponent = 1.0, preload = 1000.0 / " &
               //"&convolution methods = 'exact', 'fft', accuracy = 0.5 /"
        ! accuracy = 0.5: the rows against the scene run alone are under test here, not the step's
        ! error (dt = 0.5 ms is coarse for 1 mm bumps; the rows hold the estimates all the same)
        call write_text(scratch//'/sweep_green.nml', "&scene task = 'sweep', name = 'sweep_green', output_dir = '" &
                        //scratch//"', dt = 5.0e-4, n_steps = 400 /"//base//new_line('a')//"&sweep"//new_line('a') &
                        //"    road.speed = 4.0, 6.0"//new_line('a')//"/")
        call execute_command_line('rm -rf '//scratch//'/sweep_green_sweep.d')
        open (newunit=unit, status='scratch', action='readwrite')
        call run_sweep(scratch//'/sweep_green.nml', unit, .false., fail)
        close (unit)
        call check(error, .not. allocated(fail), 'the sweep runs: '//message_of(fail))
        if (allocated(error)) return
        do k = 1, size(names)
            write (names(k), '(a,i0)') 'c', k
        end do
        call read_columns(scratch//'/sweep_green_sweep.dat', names, [(' ', k=1, size(names))], table, line_of, fail)
        call check(error, .not. allocated(fail), 'the table reads back with 2 + 2*6 + 2 columns: '//message_of(fail))
        if (allocated(error)) return
        call check(error, size(table, 1) == 2 .and. all(table(:, 2) == [4.0_dp, 6.0_dp]), &
                   'two rows, in the order of the variants')
        if (allocated(error)) return
        worst = 0.0_dp
        do v = 1, 2
            call run_scene_text(scratch, 'sweep_alone.nml', "&scene name = 'sweep_alone', output_dir = '"//scratch &
                                //"', dt = 5.0e-4, n_steps = 400 /"//replace_speed(base, table(v, 2)), fail)
            call check(error, .not. allocated(fail), 'the scene alone runs: '//message_of(fail))
            if (allocated(error)) return
            do m = 1, size(methods)
                call read_table(scratch//'/sweep_alone_'//trim(methods(m))//'.dat', 8, rows, fail)
                call check(error, .not. allocated(fail) .and. size(rows, 1) == 4*400, 'rows of the scene alone')
                if (allocated(error)) return
                total = rows(1::4, 7)
                expected = [maxval(total), sum(total)/size(total), sqrt(sum(total**2)/size(total))]
                associate (got => table(v, 3 + 6*(m - 1):5 + 6*(m - 1)))
                    worst = max(worst, maxval(abs(got - expected)/abs(expected)))
                    call check(error, all(abs(got - expected) <= 1.0e-7_dp*abs(expected)), trim(methods(m)) &
                               //' at '//int_text(nint(table(v, 2)))//' m/s: max, mean, rms of the total force')
                end associate
                if (allocated(error)) return
                call check(error, table(v, 6 + 6*(m - 1)) == 1.0_dp .and. table(v, 7 + 6*(m - 1)) == 0.0_dp, &
                           trim(methods(m))//': in contact at every step, status 0')
                if (allocated(error)) return
            end do
        end do
        call note('worst relative difference, table against the scene alone', worst)
    end subroutine test_sweep_green_file

    !> Rows x, h(x, y = -0.1), h(x, y = 0.1) of a texture from x0 to x1 by dx: bumps of 1 mm
    !> every 0.05 m, 0.5 mm higher at y = 0.1 m.
    function bump_rows(x0, x1, dx) result(text)
        real(dp), intent(in) :: x0, x1, dx
        character(len=:), allocatable :: text

        character(len=80) :: row
        real(dp) :: x, h
        integer :: k

        text = ''
        do k = 0, nint((x1 - x0)/dx)
            x = x0 + k*dx
            h = 1.0e-3_dp*sin(2.0_dp*pi*x/0.05_dp)**2
            write (row, '(3es24.16)') x, h, h + 5.0e-4_dp
            text = text//trim(row)//new_line('a')
        end do
    end function bump_rows

    !> The scene's groups with `speed = 5.0` replaced by the given speed [m/s].
    function replace_speed(text, speed) result(changed)
        character(len=*), intent(in) :: text
        real(dp), intent(in) :: speed
        character(len=:), allocatable :: changed

        character(len=32) :: value
        integer :: at

        write (value, '(f0.1)') speed
        at = index(text, 'speed = 5.0')
        changed = text(:at - 1)//'speed = '//trim(value)//text(at + len('speed = 5.0'):)
    end function replace_speed

    ! ---- helpers -------------------------------------------------------------------------------

    !> The 2 x 2 patch of test_scene_against_modes: points 0.06 m by 0.1 m around (L/2, b/2) of
    !> the plate (xi = 0.02), its modes up to 300 Hz, and their receptances on 0 to 400 Hz by 1 Hz
    !> written to `path` (nodes in dataset 2411, 17 digits).
    subroutine small_patch(path, truth, x, y, fail)
        character(len=*), intent(in) :: path
        type(point_modes), intent(out) :: truth
        real(dp), intent(out) :: x(4), y(4)
        type(error_type), allocatable, intent(out) :: fail

        call make_directory(scratch, fail)
        if (allocated(fail)) return
        call patch_points([0.9425_dp, 0.1_dp], [0.06_dp, 0.1_dp], 2, 2, x, y)
        call plate_modes(tyre_plate(damping_ratio=0.02_dp), x, y, 300.0_dp, truth, fail)
        if (.not. allocated(fail)) call write_receptance_file(path, truth, x, y, 1.0_dp, 401, fail)
    end subroutine small_patch

end module test_patchscene_mod
