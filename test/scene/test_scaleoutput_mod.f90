!> Output at a real tyre's scale: a multi-point run's totals file (t, total force,
!> contact area, points in contact), its force maps at `map_times`, its per-point histories
!> (`point_histories`, `point_every`, text or binary) and the spectra of its contact area, each
!> checked against the per-point rows of the same run; and the refusals of bad map times.
module test_scaleoutput_mod
    use, intrinsic :: iso_fortran_env, only: dp => real64
    use testsuite_mod, only: test_error, unittest_type, new_unittest, check, note
    use scene_text_mod, only: read_scene_text, run_scene_text, read_table, message_of, write_text
    use greenconv_core_error, only: error_type, stat_input
    use greenconv_io_files, only: make_directory
    use greenconv_scene_read_input, only: scene_type
    use test_tyrepatch_mod, only: bumps
    implicit none
    private

    public :: collect_scaleoutput

    !> Scratch directory for the files the tests write.
    character(len=*), parameter :: scratch = 'build/test_scratch/scaleoutput'
    !> Points of the small patch (6 x 3) and steps of its runs.
    integer, parameter :: n_c = 18, n_t = 400
    !> Its share of the patch [m^2]: 0.06 m x 0.08 m over N_c points.
    real(dp), parameter :: share = 0.06_dp*0.08_dp/n_c

contains

    !> Tests of the output of multi-point runs.
    subroutine collect_scaleoutput(testsuite)
        type(unittest_type), allocatable, intent(out) :: testsuite(:)

        testsuite = [new_unittest('totals: the sum of the per-point forces, area = count x share', test_totals), &
                     new_unittest('maps: the per-point rows at the steps of map_times', test_maps), &
                     new_unittest('histories: point_every, none, auto above 100 points, binary round trip', &
                                  test_histories), &
                     new_unittest('map_times: negative, beyond the run, not increasing refused with their line', &
                                  test_map_refusals)]
    end subroutine collect_scaleoutput

    !> The patch scene (tyre_plate, 6 x 3 points over bumps at 10 m/s, law per area, 200 N of
    !> preload so that some points lift off, `modal`) with `extra` added to its &scene group
    !> (`n_x` points along the travel, `n_steps` steps).
    function patch_scene(name, extra, n_x, n_steps) result(text)
        character(len=*), intent(in) :: name, extra
        integer, intent(in), optional :: n_x, n_steps
        character(len=:), allocatable :: text

        character(len=12) :: count, steps

        count = '6'
        if (present(n_x)) write (count, '(i0)') n_x
        steps = '400'
        if (present(n_steps)) write (steps, '(i0)') n_steps
        text = "&scene name = '"//name//"', output_dir = '"//scratch//"', dt = 5.0e-5, n_steps = "//trim(steps)//", " &
               //extra//" /"//new_line('a') &
               //" &structure model = 'tyre_plate', damping_ratio = 0.05, f_modes = 800.0 /"//new_line('a') &
               //" &road profile = 'texture', texture_file = '"//scratch//"/bumps.dat', x_start = 0.5, " &
               //"speed = 10.0 /"//new_line('a') &
               //" &contact n_points_x = "//trim(count)//", n_points_y = 3, patch_length = 0.06, " &
               //"patch_width = 0.08, stiffness_per_area = 2.0e8, exponent = 1.0, preload = 200.0 /" &
               //new_line('a')//" &convolution methods = 'modal', accuracy = 0.5 /"
        ! accuracy 0.5: the files' layout is under test, not the 800 Hz band's error
    end function patch_scene

    !> Run a scene text; a failure fails the test.
    subroutine run(name, text, error)
        character(len=*), intent(in) :: name, text
        type(test_error), allocatable, intent(out) :: error

        type(error_type), allocatable :: fail

        call make_directory(scratch, fail)
        call write_text(scratch//'/bumps.dat', '# bumps'//new_line('a')//'  -0.1  0.1'//new_line('a')//bumps())
        call run_scene_text(scratch, name//'.nml', text, fail)
        call check(error, .not. allocated(fail), name//': the scene runs: '//message_of(fail))
    end subroutine run

    !> Read a table; a failure or a wrong row count fails the test.
    subroutine table(path, n_columns, n_rows, rows, error)
        character(len=*), intent(in) :: path
        integer, intent(in) :: n_columns, n_rows
        real(dp), allocatable, intent(out) :: rows(:, :)
        type(test_error), allocatable, intent(out) :: error

        type(error_type), allocatable :: fail
        character(len=12) :: count

        write (count, '(i0)') n_rows
        call read_table(path, n_columns, rows, fail)
        call check(error, .not. allocated(fail), path//': '//message_of(fail))
        if (allocated(error)) return
        call check(error, size(rows, 1) == n_rows, path//': expected '//trim(count)//' rows')
    end subroutine table

    !> Totals every 2 steps against the per-point histories every 2 steps of the same run: the
    !> total force equals the sum of the column f_contact over the points of each step (to
    !> round-off, 1e-13 of the largest total), the points in contact are those with f > 0 and
    !> the contact area is their count times the share patch_length*patch_width/N_c (1e-15
    !> relative); the run has steps with some points off the road, so the count varies.
    subroutine test_totals(error)
        type(test_error), allocatable, intent(out) :: error

        real(dp), allocatable :: points(:, :), totals(:, :), forces(:, :)
        real(dp) :: worst_force, worst_area
        integer :: n, in_contact
        logical :: exists

        call run('totals', patch_scene('totals', 'output_every = 2, spectra = .true., spectra_f_low = 3150.0'), error)
        if (allocated(error)) return
        call table(scratch//'/totals_modal.dat', 8, n_c*n_t/2, points, error)
        if (allocated(error)) return
        call table(scratch//'/totals_modal_totals.dat', 4, n_t/2, totals, error)
        if (allocated(error)) return
        forces = reshape(points(:, 5), [n_c, n_t/2])
        worst_force = 0.0_dp
        worst_area = 0.0_dp
        do n = 1, n_t/2
            in_contact = count(forces(:, n) > 0.0_dp)
            call check(error, abs(totals(n, 1) - points((n - 1)*n_c + 1, 1)) <= 0.0_dp .and. &
                       nint(totals(n, 4)) == in_contact, &
                       'a totals row''s time or points in contact differ from the per-point rows')
            if (allocated(error)) return
            worst_force = max(worst_force, abs(totals(n, 2) - sum(forces(:, n))))
            worst_area = max(worst_area, abs(totals(n, 3) - in_contact*share)/(n_c*share))
        end do
        call note('max |F_total - sum F_i| / max F_total', worst_force/maxval(totals(:, 2)))
        call note('max |area - count*share| / patch area', worst_area)
        call note('points in contact, least', minval(totals(:, 4)))
        call note('points in contact, most', maxval(totals(:, 4)))
        call check(error, worst_force <= 1.0e-13_dp*maxval(totals(:, 2)), &
                   'the total force is not the sum of the points''')
        if (allocated(error)) return
        call check(error, worst_area <= 1.0e-15_dp, 'the contact area is not the count times the share')
        if (allocated(error)) return
        call check(error, minval(totals(:, 4)) < n_c .and. maxval(totals(:, 4)) > 0, &
                   'the run should have steps with some but not all points in contact')
        if (allocated(error)) return
        inquire (file=scratch//'/totals_modal_area_spectra.dat', exist=exists)
        call check(error, exists, 'the contact area''s spectra file is missing')
    end subroutine test_totals

    !> Maps at 2 ms and 10 ms (steps 40 and 200): N_c rows each, equal (every digit) to the
    !> per-point rows of those steps of the same run written every step.
    subroutine test_maps(error)
        type(test_error), allocatable, intent(out) :: error

        integer, parameter :: steps(2) = [40, 200]
        real(dp), allocatable :: points(:, :), maps(:, :)
        integer :: k

        call run('maps', patch_scene('maps', 'map_times = 0.002, 0.01'), error)
        if (allocated(error)) return
        call table(scratch//'/maps_modal.dat', 8, n_c*n_t, points, error)
        if (allocated(error)) return
        call table(scratch//'/maps_modal_maps.dat', 8, n_c*size(steps), maps, error)
        if (allocated(error)) return
        do k = 1, size(steps)
            call check(error, maxval(abs(maps((k - 1)*n_c + 1:k*n_c, :) &
                                         - points(steps(k)*n_c + 1:(steps(k) + 1)*n_c, :))) <= 0.0_dp, &
                       'a map''s rows differ from the per-point rows of its step')
            if (allocated(error)) return
        end do
    end subroutine test_maps

    !> The per-point histories: every 4th step with output_every = 1 (the totals every step);
    !> none asked; none by default above 100 points (11 x 10), the totals still written; and the
    !> same run in binary (the .bin's float64 rows equal the text rows read back, every bit).
    subroutine test_histories(error)
        type(test_error), allocatable, intent(out) :: error

        real(dp), allocatable :: points(:, :), totals(:, :), values(:)
        logical :: exists
        integer :: unit, bytes

        call run('every', patch_scene('every', 'point_every = 4'), error)
        if (allocated(error)) return
        call table(scratch//'/every_modal.dat', 8, n_c*n_t/4, points, error)
        if (allocated(error)) return
        call table(scratch//'/every_modal_totals.dat', 4, n_t, totals, error)
        if (allocated(error)) return
        call check(error, maxval(abs(points(::n_c, 1) - totals(::4, 1))) <= 0.0_dp, &
                   'the histories are not every 4th step')
        if (allocated(error)) return
        call run('binary', patch_scene('binary', "point_every = 4, output_format = 'binary'"), error)
        if (allocated(error)) return
        inquire (file=scratch//'/binary_modal.bin', size=bytes)
        call check(error, bytes == 8*size(points), 'the binary file holds N_c*N_t/4 rows of 8 float64')
        if (allocated(error)) return
        allocate (values(size(points)))
        open (newunit=unit, file=scratch//'/binary_modal.bin', access='stream', form='unformatted', action='read')
        read (unit) values
        close (unit)
        call check(error, maxval(abs(reshape(values, [8, size(points, 1)]) - transpose(points))) <= 0.0_dp, &
                   'the binary rows differ from the text rows')
        if (allocated(error)) return
        call run('none', patch_scene('none', "point_histories = 'none'"), error)
        if (allocated(error)) return
        inquire (file=scratch//'/none_modal.dat', exist=exists)
        call check(error, .not. exists, "point_histories = 'none' wrote none_modal.dat")
        if (allocated(error)) return
        call run('auto', patch_scene('auto', 'progress = .false.', 37, 20), error)
        if (allocated(error)) return
        inquire (file=scratch//'/auto_modal.dat', exist=exists)
        call check(error, .not. exists, '111 points: auto wrote per-point histories')
        if (allocated(error)) return
        call table(scratch//'/auto_modal_totals.dat', 4, 20, totals, error)
    end subroutine test_histories

    !> map_times out of place: each refused with status 2, the scene file's name and line, the
    !> variable and what was expected.
    subroutine test_map_refusals(error)
        type(test_error), allocatable, intent(out) :: error

        character(len=60) :: times(5), expected(5)
        type(scene_type) :: scene
        type(error_type), allocatable :: fail
        integer :: k

        times = [character(len=60) :: 'map_times = -0.001', 'map_times = 0.02', 'map_times = 0.01, 0.005', &
                 'map_times = 0.01, 0.01', 'map_times(2) = 0.01']
        expected = [character(len=60) :: 'expected times >= 0 s', 'expected times within the run', &
                    'expected increasing times', 'expected increasing times', 'without gaps']
        call make_directory(scratch, fail)
        call write_text(scratch//'/bumps.dat', '# bumps'//new_line('a')//'  -0.1  0.1'//new_line('a')//bumps())
        do k = 1, size(times)
            call read_scene_text(scratch, 'bad.nml', patch_scene('bad', trim(times(k))), scene, fail)
            call check(error, allocated(fail), trim(times(k))//': refused')
            if (allocated(error)) return
            call check(error, fail%stat == stat_input .and. index(fail%message, trim(expected(k))) > 0 .and. &
                       index(fail%message, 'bad.nml:1') > 0 .and. index(fail%message, 'map_times') > 0, &
                       trim(times(k))//': expected "'//trim(expected(k))//'" at bad.nml:1, map_times in: ' &
                       //fail%message)
            if (allocated(error)) return
        end do
    end subroutine test_map_refusals

end module test_scaleoutput_mod
