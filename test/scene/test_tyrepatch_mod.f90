!> The built-in 2D tyre (`&structure model = 'tyre_plate'`): a scene on the plate's
!> patch grid against run_multi_contact on the plate's own modes (the scene's conventions
!> written out here), the contact law per area (each point's share of the patch; the total force
!> converging as the grid is refined, a law per point stiffening instead), and the refusals of
!> the grid's values, each with its line.
module test_tyrepatch_mod
    use, intrinsic :: iso_fortran_env, only: dp => real64, int64
    use testsuite_mod, only: test_error, unittest_type, new_unittest, check, note
    use scene_text_mod, only: read_scene_text, run_scene_text, read_table, message_of, write_text
    use greenconv_core_error, only: error_type, stat_input
    use greenconv_io_files, only: make_directory
    use greenconv_io_columns, only: read_columns
    use greenconv_model_point_modes, only: point_modes
    use greenconv_model_plate, only: tyre_plate, plate_modes, patch_points
    use greenconv_model_road_texture, only: road_texture, read_road_texture
    use greenconv_model_road_file, only: road_travel, sample_road_steps
    use greenconv_contact_laws, only: contact_law, replicate_law
    use greenconv_contact_multi, only: multi_contact_response, run_multi_contact
    use greenconv_conv_multipoint, only: multipoint_convolver
    use greenconv_conv_builder, only: make_multipoint_convolver
    use greenconv_scene_read_input, only: scene_type
    use greenconv_scene_run_runner, only: run_scene
    use greenconv_scene_models_registry, only: structure_kind, find_model
    use greenconv_scene_models_point_set, only: scene_points
    use greenconv_scene_run_points, only: points_convolver
    use greenconv_scene_models_patch, only: sample_patch_road
    use greenconv_contact_law_power, only: power_law
    implicit none
    private

    public :: collect_tyrepatch, bumps

    !> Scratch directory for the files the tests write.
    character(len=*), parameter :: scratch = 'build/test_scratch/tyrepatch'

contains

    !> Tests of the 2D tyre scene and the law per area.
    subroutine collect_tyrepatch(testsuite)
        type(unittest_type), allocatable, intent(out) :: testsuite(:)

        testsuite = [new_unittest('tyre_plate scene equals run_multi_contact on the plate''s modes', &
                                  test_scene_against_modes), &
                     new_unittest('law per area: N_c*k_c = k_a*patch area; the total force converges with the grid', &
                                  test_law_per_area), &
                     new_unittest('patch grid: each value out of place refused with its line', test_grid_refusals)]
    end subroutine collect_tyrepatch

    !> A 6 x 3 grid over 0.06 m x 0.08 m of the default plate (xi = 0.05, modes up to 800 Hz),
    !> rolled by a scene over a texture of bumps at 10 m/s, methods modal (explicit) and exact
    !> (implicit), against run_multi_contact on plate_modes at patch_points with the scene's
    !> conventions: points at (L/2, b/2) + the grid, preload shared evenly, point i on the road at
    !> x_start + (x_i - x_mean) + V*t and y_start + (y_i - y_mean), k_c = k_a*area/N_c. The same
    !> engine on the same inputs: agreement to 1e-12 of the largest force is what is asked.
    subroutine test_scene_against_modes(error)
        type(test_error), allocatable, intent(out) :: error

        character(len=*), parameter :: texture_path = scratch//'/bumps.dat'
        character(len=*), parameter :: methods(2) = ['modal', 'exact']
        integer, parameter :: n_x = 6, n_y = 3, n_c = n_x*n_y, n_t = 400
        real(dp), parameter :: dt = 5.0e-5_dp, speed = 10.0_dp, k_a = 2.0e8_dp, preload = 1500.0_dp
        type(tyre_plate) :: plate
        type(point_modes) :: modes
        type(road_texture) :: texture
        type(error_type), allocatable :: fail
        class(multipoint_convolver), allocatable :: conv
        type(multi_contact_response) :: response
        character(len=:), allocatable :: accuracy
        real(dp), allocatable :: rows(:, :), road(:, :)
        real(dp) :: x(n_c), y(n_c), worst, scale
        integer :: m, i

        call make_directory(scratch, fail)
        call write_text(texture_path, '# bumps'//new_line('a')//'  -0.1  0.1'//new_line('a')//bumps())
        call run_scene_text(scratch, 'plate.nml', "&scene name = 'plate', output_dir = '"//scratch &
                            //"', dt = 5.0e-5, n_steps = 400 /" &
                      //" &structure model = 'tyre_plate', damping_ratio = 0.05, f_modes = 800.0 /" &
                      //" &road profile = 'texture', texture_file = '"//texture_path//"', x_start = 0.5, speed = 10.0 /" &
                      //" &contact n_points_x = 6, n_points_y = 3, patch_length = 0.06, patch_width = 0.08," &
                      //" stiffness_per_area = 2.0e8, exponent = 1.0, preload = 1500.0 /" &
                      //" &convolution methods = 'modal', 'exact', accuracy = 0.5 /", fail)
        ! accuracy = 0.5: the scene against run_multi_contact is under test, not the step's error
        call check(error, .not. allocated(fail), 'the scene runs: '//message_of(fail))
        if (allocated(error)) return
        plate = tyre_plate(damping_ratio=0.05_dp)
        call patch_points([0.5_dp*plate%length, 0.5_dp*plate%width], [0.06_dp, 0.08_dp], n_x, n_y, x, y)
        call plate_modes(plate, x, y, 800.0_dp, modes, fail)
        if (.not. allocated(fail)) call read_road_texture(texture_path, texture, fail)
        call check(error, .not. allocated(fail), 'modes and texture: '//message_of(fail))
        if (allocated(error)) return
        call sample_road_steps(texture, road_travel(0.5_dp + (x - sum(x)/n_c), y - sum(y)/n_c, speed, dt), 0_8, n_t, road)
        worst = 0.0_dp
        do m = 1, size(methods)
            call make_multipoint_convolver(trim(methods(m)), modes, dt, 0.01_dp, n_t, conv, accuracy, fail)
            if (.not. allocated(fail)) call run_multi_contact(conv, [(power_law(k_a*0.06_dp*0.08_dp/n_c, 1.0_dp), &
                                                             i=1, n_c)], road, [(preload/n_c, i=1, n_c)], response, fail)
            call check(error, .not. allocated(fail), trim(methods(m))//' on the modes: '//message_of(fail))
            if (allocated(error)) return
            call read_table(scratch//'/plate_'//trim(methods(m))//'.dat', 8, rows, fail)
            call check(error, .not. allocated(fail) .and. size(rows, 1) == n_t*n_c, &
                       trim(methods(m))//': N_t*N_c rows of 8 columns (t x u_road u f delta f_total y)')
            if (allocated(error)) return
            scale = maxval(abs(response%force))
            worst = max(worst, maxval(abs(reshape(rows(:, 5), [n_c, n_t]) - transpose(response%force)))/scale)
            call check(error, maxval(abs(rows(:, 8) - [(y, i=1, n_t)])) <= 1.0e-12_dp, &
                       trim(methods(m))//': the column y holds each point''s place across the belt')
            if (allocated(error)) return
        end do
        call note('max |F_scene - F_modes| / max|F|', worst)
        call check(error, worst <= 1.0e-12_dp, 'the scene''s forces differ from the plate''s modes run directly')
    end subroutine test_scene_against_modes

    !> The law per area on one patch (0.12 m x 0.12 m, linear tread k_a = 3e8 N/m^3, 2,000 N)
    !> over the bumps at 15 m/s, `modal`, grids 8 x 8, 16 x 16 and 32 x 32: the scene's k_c is
    !> k_a*area/N_c to round-off, and the rms fluctuation of the total force changes by at most
    !> 5 % from 16 x 16 to 32 x 32 (the criterion for halving both counts); the same
    !> patch with k_c per point fixed at the 8 x 8 value (6.75e4 N/m) stiffens with the grid instead (its peak
    !> total force grows by more than 5 %), which is why the law per area exists.
    subroutine test_law_per_area(error)
        type(test_error), allocatable, intent(out) :: error

        character(len=*), parameter :: texture_path = scratch//'/bumps.dat'
        integer, parameter :: grids(3) = [8, 16, 32]
        type(scene_type) :: scene
        type(error_type), allocatable :: fail
        real(dp) :: rms(3), peak(3), fixed_peak(3), rms_fixed
        real(dp), allocatable :: law_values(:)
        integer :: g

        call make_directory(scratch, fail)
        call write_text(texture_path, '# bumps'//new_line('a')//'  -0.1  0.1'//new_line('a')//bumps())
        do g = 1, size(grids)
            call read_scene_text(scratch, 'area.nml', area_scene(grids(g), 'stiffness_per_area = 3.0e8'), scene, fail)
            call check(error, .not. allocated(fail), 'the scene reads: '//message_of(fail))
            if (allocated(error)) return
            law_values = scene%law%parameters()
            call check(error, scene%n_points == grids(g)**2 .and. abs(law_values(1)*scene%n_points &
                       - 3.0e8_dp*0.12_dp*0.12_dp) <= 1.0e-12_dp*3.0e8_dp*0.12_dp*0.12_dp, &
                       'N_c*k_c is not k_a times the patch area')
            if (allocated(error)) return
            call total_force(area_scene(grids(g), 'stiffness_per_area = 3.0e8'), rms(g), peak(g), error)
            if (allocated(error)) return
            call total_force(area_scene(grids(g), 'stiffness = 6.75e4'), rms_fixed, fixed_peak(g), error)
            if (allocated(error)) return
        end do
        call note('rms fluctuation of the total force, 8x8 [N]', rms(1))
        call note('rms fluctuation, 16x16 [N]', rms(2))
        call note('rms fluctuation, 32x32 [N]', rms(3))
        call note('change 16x16 -> 32x32', abs(rms(3) - rms(2))/rms(3))
        call note('law per point: peak total force 8x8 [N]', fixed_peak(1))
        call note('law per point: peak total force 32x32 [N]', fixed_peak(3))
        call check(error, abs(rms(3) - rms(2)) <= 0.05_dp*rms(3), 'the rms fluctuation changes by more than 5 % ' &
                   //'from 16 x 16 to 32 x 32 points')
        if (allocated(error)) return
        call check(error, fixed_peak(3) > 1.05_dp*fixed_peak(1), 'a law per point should stiffen with the grid')
    end subroutine test_law_per_area

    !> The scene of test_law_per_area on an n x n grid with the law `law`.
    function area_scene(n, law) result(text)
        integer, intent(in) :: n
        character(len=*), intent(in) :: law
        character(len=:), allocatable :: text

        character(len=12) :: count

        write (count, '(i0)') n
        text = "&scene name = 'area', output_dir = '"//scratch//"', dt = 2.0e-5, n_steps = 2000 /" &
               //" &structure model = 'tyre_plate', damping_ratio = 0.05, f_modes = 1500.0 /" &
               //" &road profile = 'texture', texture_file = '"//scratch//"/bumps.dat', x_start = 0.5, " &
               //"speed = 15.0 / &contact n_points_x = "//trim(count)//", n_points_y = "//trim(count) &
               //", patch_length = 0.12, patch_width = 0.12, "//law//", exponent = 1.0, preload = 2000.0 /" &
               //" &convolution methods = 'modal' /"
    end function area_scene

    !> Read a scene and run its first method on its points as the runner does (points from
    !> the model's row, road heights from greenconv_scene_models_patch, preload shared evenly), without
    !> writing rows: the rms fluctuation and the peak of the total force [N].
    subroutine total_force(text, rms, peak, error)
        character(len=*), intent(in) :: text
        real(dp), intent(out) :: rms, peak
        type(test_error), allocatable, intent(out) :: error

        type(scene_type) :: scene
        type(structure_kind) :: model
        type(scene_points) :: points
        class(multipoint_convolver), allocatable :: conv
        type(multi_contact_response) :: response
        type(error_type), allocatable :: fail
        character(len=:), allocatable :: summary, accuracy
        real(dp), allocatable :: heights(:, :), total(:)
        class(contact_law), allocatable :: laws(:)
        integer :: n_c, i

        call read_scene_text(scratch, 'area.nml', text, scene, fail)
        if (.not. allocated(fail)) then
            model = find_model(scene%model)
            call model%find_points(scene, points, summary, fail)
        end if
        if (.not. allocated(fail)) call points_convolver(points, scene, trim(scene%methods(1)), conv, accuracy, fail)
        call check(error, .not. allocated(fail), 'the scene''s points and convolver: '//message_of(fail))
        if (allocated(error)) return
        n_c = points%n_points()
        call sample_patch_road(scene, points%road_x, points%road_y, 0_int64, scene%n_steps, heights)
        call replicate_law(scene%law, n_c, laws)
        call run_multi_contact(conv, laws, heights, [(scene%preload/n_c, i=1, n_c)], response, fail)
        call check(error, .not. allocated(fail), 'the run: '//message_of(fail))
        if (allocated(error)) return
        total = sum(response%force, dim=2)
        rms = sqrt(sum((total - sum(total)/size(total))**2)/size(total))
        peak = maxval(total)
    end subroutine total_force

    !> Values of the patch grid out of place: each refused with status 2 and its line.
    subroutine test_grid_refusals(error)
        type(test_error), allocatable, intent(out) :: error

        character(len=*), parameter :: road = " &road profile = 'texture', texture_file = '"//scratch &
                                              //"/bumps.dat', x_start = 0.5, speed = 10.0 /"
        character(len=*), parameter :: head = "&scene name = 'bad', output_dir = '"//scratch &
                                              //"', dt = 5.0e-5, n_steps = 10 /"
        character(len=*), parameter :: tail = " &convolution methods = 'modal' /"
        character(len=120) :: contacts(6), expected(6)
        character(len=40) :: models(6)
        type(scene_type) :: scene
        type(error_type), allocatable :: fail
        integer :: k

        call make_directory(scratch, fail)
        call write_text(scratch//'/bumps.dat', '# bumps'//new_line('a')//'  -0.1  0.1'//new_line('a')//bumps())
        models = [character(len=40) :: 'tyre', 'tyre_plate', 'tyre_plate', 'random_modes', 'tyre_plate', 'tyre_plate']
        contacts(1) = 'n_points_x = 4, n_points_y = 2, stiffness = 1e5, preload = 100.0, exponent = 1.0'
        expected(1) = '&contact n_points_x, n_points_y: expected no value'
        contacts(2) = 'n_points_x = 4, stiffness = 1e5, stiffness_per_area = 1e8, preload = 100.0, exponent = 1.0'
        expected(2) = '&contact stiffness: expected no value beside stiffness_per_area'
        contacts(3) = 'n_points_x = 4, patch_width = 0.25, stiffness = 1e5, preload = 100.0, exponent = 1.0'
        expected(3) = '&contact patch_width: expected a width below belt_width'
        contacts(4) = 'stiffness_per_area = 1e8, exponent = 1.0, preload = 100.0'
        expected(4) = '&contact stiffness_per_area: expected 0 for model'
        contacts(5) = 'n_points_x = 100, n_points_y = 100, stiffness = 1e5, preload = 100.0, exponent = 1.0'
        expected(5) = '&contact n_points_x, n_points_y: expected at most'
        contacts(6) = 'n_points_x = 4, preload = 100.0, exponent = 1.0'
        expected(6) = 'or stiffness_per_area or wheel_radius or law_parameters, found neither'
        do k = 1, size(contacts)
            call read_scene_text(scratch, 'bad.nml', head//new_line('a')//" &structure model = '" &
                                 //trim(models(k))//"' /"//new_line('a')//road//new_line('a')//new_line('a') &
                                 //new_line('a')//new_line('a')//new_line('a')//new_line('a')//new_line('a') &
                                 //new_line('a')//new_line('a')//" &contact "//trim(contacts(k))//" /" &
                                 //new_line('a')//tail, scene, fail)
            call check(error, allocated(fail), 'case '//trim(contacts(k))//': refused')
            if (allocated(error)) return
            call check(error, fail%stat == stat_input .and. index(fail%message, trim(expected(k))) > 0 .and. &
                       index(fail%message, 'bad.nml:') == 1 + len(scratch//'/'), &
                       'case '//trim(contacts(k))//': expected "'//trim(expected(k))//'" in: '//fail%message)
            if (allocated(error)) return
        end do
    end subroutine test_grid_refusals

    !> Rows of a texture over x = 0..4 m by 5 mm: 1 mm bumps of 30 mm wavelength along the
    !> travel, 0.5 mm of rocking across (y = -0.1, 0.1 m).
    function bumps() result(text)
        character(len=:), allocatable :: text

        character(len=80) :: line
        real(dp) :: x, h
        integer :: i

        text = ''
        do i = 0, 800
            x = 0.005_dp*i
            h = 0.5e-3_dp*(1.0_dp + sin(2.0_dp*acos(-1.0_dp)*x/0.03_dp))
            write (line, '(f8.3,2es16.8)') x, h - 0.25e-3_dp, h + 0.25e-3_dp
            text = text//trim(line)//new_line('a')
        end do
    end function bumps

end module test_tyrepatch_mod
