!> The matrix form of the linear reference written beside a multi-point scene's runs
!> (greenconv_scene_run_linear_reference's `write_patch_reference`), for test_linearpatch_mod.
module linearpatch_scene_mod
    use, intrinsic :: iso_fortran_env, only: dp => real64
    use testsuite_mod, only: test_error, check, note
    use greenconv_core_error, only: error_type
    use greenconv_scene_read_input, only: scene_type
    use greenconv_scene_run_runner, only: run_scene
    use scene_text_mod, only: read_scene_text
    use fixture_files_mod, only: read_bands
    implicit none
    private

    public :: test_scene_tyre

contains

    !> The tyre of data/tyre_road.nml on its 20 points (linear tread springs, the contact held):
    !> the reference's band levels beside the `exact` run's within 0.5 dB from 200 Hz to 2 kHz;
    !> 80 points, more than the reference takes: one line, no file.
    subroutine test_scene_tyre(error)
        type(test_error), allocatable, intent(out) :: error

        character(len=*), parameter :: directory = 'build/test_scratch/linearpatch'
        type(scene_type) :: scene
        type(error_type), allocatable :: fault
        real(dp), allocatable :: run(:, :), linear(:, :)
        character(len=:), allocatable :: said
        real(dp) :: worst
        integer :: b, unit, n_bands
        logical :: exists

        call read_scene_text(directory, 'tyre.nml', tyre_scene(directory, 20, 'exact'), scene, fault)
        if (.not. allocated(fault)) then
            open (newunit=unit, status='scratch', action='readwrite')
            call run_scene(scene, unit, fault)
            close (unit)
        end if
        call check(error, .not. allocated(fault), 'the tyre scene runs')
        if (allocated(error)) return
        call read_bands(directory//'/lt_exact_spectra.dat', 7, run, error)
        if (allocated(error)) return
        call read_bands(directory//'/lt_linear_spectra.dat', 6, linear, error)
        if (allocated(error)) return
        call check(error, size(run, 1) == size(linear, 1) .and. all(run(:, 2) == linear(:, 2)), 'the same bands')
        if (allocated(error)) return
        worst = 0.0_dp
        n_bands = 0
        do b = 1, size(run, 1)
            if (run(b, 1) < 200.0_dp .or. run(b, 1) > 2000.0_dp) cycle
            worst = max(worst, abs(run(b, 6) - linear(b, 6)))
            n_bands = n_bands + 1
        end do
        call note('bands 200 Hz - 2 kHz compared', real(n_bands, dp))
        call note('worst |L_exact - L_linear| [dB]', worst)
        call check(error, n_bands == 11 .and. worst <= 0.5_dp, 'the exact run meets the linear reference')
        if (allocated(error)) return
        ! more points than the reference takes: a line, no file
        call execute_command_line('rm -f '//directory//'/lt_linear_spectra.dat')
        call read_scene_text(directory, 'tyre.nml', tyre_scene(directory, 80, 'modal'), scene, fault)
        said = ''
        if (.not. allocated(fault)) then
            open (newunit=unit, status='scratch', action='readwrite')
            call run_scene(scene, unit, fault)
            said = summary_text(unit)
            close (unit)
        end if
        call check(error, .not. allocated(fault), 'the scene of 80 points runs')
        if (allocated(error)) return
        inquire (file=directory//'/lt_linear_spectra.dat', exist=exists)
        call check(error, index(said, '# linear reference: not written for 80 points (at most 64)') > 0 .and. &
                   .not. exists, 'a line says why, no file: '//said)
    end subroutine test_scene_tyre

    !> The tyre of data/tyre_road.nml on `n` points, 4096 steps, spectra.
    function tyre_scene(directory, n, method) result(text)
        character(len=*), intent(in) :: directory, method
        integer, intent(in) :: n
        character(len=:), allocatable :: text

        character(len=12) :: count

        write (count, '(i0)') n
        text = "&scene name = 'lt', output_dir = '"//directory//"', dt = 5.0e-5, n_steps = 4096, spectra = .true. /" &
               //new_line('a')//"&structure model = 'tyre', belt_length = 1.885, belt_mass = 2.5, " &
               //'belt_bending = 5.0, ' &
               //'belt_tension = 1.2e4, belt_foundation = 7.0e5, damping_ratio = 0.05 /'//new_line('a') &
               //"&road profile = 'file', road_file = 'data/road_sample.dat', x_start = 0.5, speed = 20.0 /" &
               //new_line('a')//'&contact n_points = '//trim(count)//', patch_length = 0.12, stiffness = ' &
               //'2.0e5, exponent = 1.0, preload = 3000.0 /'//new_line('a')//"&convolution methods = '"//method &
               //"', accuracy = 0.5 /"
        ! accuracy 0.5: the bands against the linear reference are under test, not the default band's error
    end function tyre_scene

    !> The lines written on a scratch unit, joined.
    function summary_text(unit) result(text)
        integer, intent(in) :: unit
        character(len=:), allocatable :: text

        character(len=1000) :: buffer
        integer :: stat

        text = ''
        rewind (unit)
        do
            read (unit, '(a)', iostat=stat) buffer
            if (stat /= 0) exit
            text = text//trim(buffer)//new_line('a')
        end do
    end function summary_text

end module linearpatch_scene_mod
