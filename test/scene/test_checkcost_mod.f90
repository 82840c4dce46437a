!> `--check`'s projected cost of a scene: a line per method with the time and
!> memory its sizes imply, checked against the closed forms of greenconv_scene_limits'
!> `projected_run` and against the kernel cap, which `--check` refuses as the run does.
module test_checkcost_mod
    use, intrinsic :: iso_fortran_env, only: dp => real64
    use testsuite_mod, only: test_error, unittest_type, new_unittest, check
    use greenconv, only: scene_type, error_type
    use greenconv_core_error, only: stat_input
    use greenconv_scene_run_runner, only: check_scene
    use greenconv_scene_limits, only: work_rate
    use scene_text_mod, only: tab1_scene, read_scene_text
    implicit none
    private

    public :: collect_checkcost

    !> Scratch directory for the scenes the tests write.
    character(len=*), parameter :: scratch = 'build/test_scratch'
    !> Relative rounding of a time printed with three significant digits.
    real(dp), parameter :: printed = 5.0e-3_dp

contains

    !> The tests of `--check`'s projected cost.
    subroutine collect_checkcost(testsuite)
        !> The tests.
        type(unittest_type), allocatable, intent(out) :: testsuite(:)

        testsuite = [new_unittest('check: a line per method, the closed-form work at work_rate', test_lines), &
                     new_unittest('check: twice the steps, twice the projected time', test_doubling), &
                     new_unittest('check: a kernel above the cap is refused (status 2)', test_cap)]
    end subroutine collect_checkcost

    !> The sdof of Tab. 1 (1000 rad/s, xi = 0.02, 2000 steps of 0.1 ms): its kernel is cut at
    !> N_t (ln(100)/(xi*omega*dt) + 1 = 2304 > 2000), so direct does N_t*(N_g + 200) = 4.4e6
    !> multiply-adds (200 a step whatever the method); modal N_t*(4 + 200) (4 for its one mode
    !> at its one point), exact 3*4 more a step (three Newton iterations); auto the dearer.
    subroutine test_lines(error)
        type(test_error), allocatable, intent(out) :: error

        character(len=240), allocatable :: lines(:)

        call checked_lines(tab1_scene(convolution="methods = 'direct', 'modal', 'exact', 'auto'"), lines, error)
        if (allocated(error)) return
        call check(error, size(lines) == 9, 'the ok line, four cost lines and four error budgets')
        if (allocated(error)) return
        call check(error, index(lines(6), "greenconv: check: method 'direct': error about ") == 1, lines(6))
        if (allocated(error)) return
        call check(error, index(lines(2), "greenconv: check: method 'direct': about ") == 1 .and. &
                   index(lines(2), '(N_c 1, N_m 1, N_g 2000, 2000 steps)') > 0, lines(2))
        if (allocated(error)) return
        call check(error, projected(lines, 'direct'), 2000.0_dp*2200.0_dp/work_rate, 'direct: N_t*(N_g + 200)', &
                   rel=.true., thr=printed)
        if (allocated(error)) return
        call check(error, projected(lines, 'modal'), 2000.0_dp*204.0_dp/work_rate, 'modal: 204 N_t', &
                   rel=.true., thr=printed)
        if (allocated(error)) return
        call check(error, projected(lines, 'exact'), 2000.0_dp*216.0_dp/work_rate, 'exact: 216 N_t', &
                   rel=.true., thr=printed)
        if (allocated(error)) return
        call check(error, projected(lines, 'auto'), projected(lines, 'direct'), 'auto: the dearer, direct', &
                   rel=.true., thr=printed)
    end subroutine test_lines

    !> With xi = 0.2 the kernel is 231 samples long whatever N_t: every method's time doubles
    !> with N_t (2000 to 4000 steps), and direct's is N_t*(231 + 200) multiply-adds.
    subroutine test_doubling(error)
        type(test_error), allocatable, intent(out) :: error

        character(len=*), parameter :: structure = "model = 'sdof', mass = 1.0, stiffness = 1.0e6, damping_ratio = 0.2"
        character(len=*), parameter :: methods(3) = [character(len=6) :: 'direct', 'modal', 'exact']
        character(len=240), allocatable :: short(:), long(:)
        integer :: i

        call checked_lines(tab1_scene(structure=structure, convolution="methods = 'direct', 'modal', 'exact'"), &
                           short, error)
        if (allocated(error)) return
        call checked_lines(tab1_scene(scene='dt = 1.0e-4, n_steps = 4000', structure=structure, &
                                      convolution="methods = 'direct', 'modal', 'exact'"), long, error)
        if (allocated(error)) return
        call check(error, projected(short, 'direct'), 2000.0_dp*431.0_dp/work_rate, 'direct: N_g = 231', &
                   rel=.true., thr=printed)
        if (allocated(error)) return
        do i = 1, size(methods)
            call check(error, projected(long, trim(methods(i)))/projected(short, trim(methods(i))), 2.0_dp, &
                       trim(methods(i))//': 4000 steps against 2000', rel=.true., thr=2.0_dp*printed)
            if (allocated(error)) return
        end do
    end subroutine test_doubling

    !> Nearly undamped (xi = 1e-7) over 1e8 steps: direct's kernel would be N_t = 1e8 samples
    !> (0.8 GB, with its histories 2.4 GB): refused before anything runs, by the same read that
    !> `--check` does, with status 2 and the estimate.
    subroutine test_cap(error)
        type(test_error), allocatable, intent(out) :: error

        type(error_type), allocatable :: input_error
        character(len=240), allocatable :: lines(:)

        call printed_lines(tab1_scene(scene='dt = 1.0e-4, n_steps = 100000000', &
                                      structure="model = 'sdof', mass = 1.0, stiffness = 1.0e6, " &
                                                //'damping_ratio = 1.0e-7', &
                                      convolution="methods = 'direct'"), lines, input_error)
        call check(error, allocated(input_error), 'a direct kernel of 1e8 samples is refused')
        if (allocated(error)) return
        call check(error, input_error%stat == stat_input .and. index(input_error%message, 'sampled kernel') > 0 &
                   .and. index(input_error%message, 'checkcost.nml:') > 0 .and. size(lines) == 0, input_error%message)
    end subroutine test_cap

    !> The lines `check_scene` prints for a valid scene given as text.
    subroutine checked_lines(text, lines, error)
        character(len=*), intent(in) :: text
        character(len=240), allocatable, intent(out) :: lines(:)
        type(test_error), allocatable, intent(out) :: error

        type(error_type), allocatable :: input_error

        call printed_lines(text, lines, input_error)
        if (allocated(input_error)) call check(error, .false., 'a valid scene: '//input_error%message)
    end subroutine checked_lines

    !> The lines `check_scene` prints for a scene given as text, as `--check` reads and checks
    !> it (none when it is refused, `input_error` set).
    subroutine printed_lines(text, lines, input_error)
        character(len=*), intent(in) :: text
        character(len=240), allocatable, intent(out) :: lines(:)
        type(error_type), allocatable, intent(out) :: input_error

        type(scene_type) :: scene
        character(len=240) :: line
        integer :: unit, stat

        allocate (lines(0))
        call read_scene_text(scratch, 'checkcost.nml', text, scene, input_error)
        if (allocated(input_error)) return
        open (newunit=unit, status='scratch', action='readwrite')
        call check_scene(scene, unit, input_error)
        rewind (unit)
        do
            read (unit, '(a)', iostat=stat) line
            if (stat /= 0) exit
            lines = [character(len=240) :: lines, line]
        end do
        close (unit)
    end subroutine printed_lines

    !> The projected seconds of a method's line; -1 when there is none.
    real(dp) function projected(lines, method)
        character(len=*), intent(in) :: lines(:), method

        character(len=*), parameter :: about = "': about "
        integer :: i, first, last, stat

        projected = -1.0_dp
        do i = 1, size(lines)
            if (index(lines(i), "method '"//method//about) == 0) cycle
            first = index(lines(i), "method '"//method//about) + len("method '"//method//about)
            last = first + index(lines(i)(first:), ' s,') - 2
            read (lines(i)(first:last), *, iostat=stat) projected
            if (stat /= 0) projected = -1.0_dp
        end do
    end function projected

end module test_checkcost_mod
