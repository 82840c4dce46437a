!> A progress line on standard error for long runs:
!>
!>     greenconv: modal       42.0 %   1.23E+07 steps/s   0:01:23 left
!>
!> It appears only when standard error is a terminal (isatty(2)) and the caller asks for it
!> (a scene's `progress`, off with the driver's `--quiet`), and only once the run has taken
!> `quiet_seconds` of wall time, so short runs print nothing. It is rewritten in place (a
!> carriage return before it) at most every `refresh_seconds`, and ended with a newline by
!> `finish_progress`. Wall time comes from `system_clock` with 64-bit counts. The caller
!> updates it between blocks of steps, so reading the clock costs nothing per step.
module greenconv_scene_run_progress
    use, intrinsic :: iso_c_binding, only: c_int
    use, intrinsic :: iso_fortran_env, only: int64, error_unit
    use greenconv_core_kinds, only: dp
    implicit none
    private

    public :: progress_meter, start_progress, update_progress, finish_progress
    public :: progress_line, progress_due, stderr_is_terminal
    public :: quiet_seconds, refresh_seconds

    !> Wall time [s] a run must have taken before its progress line appears.
    real(dp), parameter :: quiet_seconds = 2.0_dp
    !> Shortest wall time [s] between two updates of the line.
    real(dp), parameter :: refresh_seconds = 0.5_dp

    !> The progress of one run (one method of a scene).
    type :: progress_meter
        !> Whether the line may be shown at all (asked for, and standard error is a terminal).
        logical :: enabled = .false.
        !> Name of what runs (the method).
        character(len=:), allocatable :: label
        !> Number of steps of the whole run.
        integer(int64) :: total = 0
        !> Clock count at the start of the run.
        integer(int64) :: start = 0
        !> Clock counts per second.
        integer(int64) :: rate = 1
        !> Wall time [s] since the start when the line was last written (negative: never).
        real(dp) :: last_shown = -1.0_dp
        !> Length of the line last written, to blank what a shorter one leaves behind.
        integer :: width = 0
    end type progress_meter

    interface
        !> C library isatty(3): 1 when the file descriptor is a terminal.
        function c_isatty(descriptor) bind(c, name='isatty') result(answer)
            import :: c_int
            implicit none
            integer(c_int), value :: descriptor
            integer(c_int) :: answer
        end function c_isatty
    end interface

contains

    !> Whether standard error (file descriptor 2) is a terminal.
    logical function stderr_is_terminal()
        stderr_is_terminal = c_isatty(2_c_int) == 1_c_int
    end function stderr_is_terminal

    !> Start measuring a run of `total` steps. The line is enabled only when `requested` and
    !> standard error is a terminal (`terminal` overrides that check, for tests).
    subroutine start_progress(meter, label, total, requested, terminal)
        !> The meter, at step 0 of the run.
        type(progress_meter), intent(out) :: meter
        !> Name of what runs (the method).
        character(len=*), intent(in) :: label
        !> Number of steps of the whole run.
        integer(int64), intent(in) :: total
        !> Whether the caller wants a progress line (a scene's `progress`).
        logical, intent(in) :: requested
        !> Whether standard error is a terminal; asked of isatty(2) when absent.
        logical, intent(in), optional :: terminal

        meter%enabled = requested
        if (meter%enabled) then
            if (present(terminal)) then
                meter%enabled = terminal
            else
                meter%enabled = stderr_is_terminal()
            end if
        end if
        meter%label = label
        meter%total = total
        call system_clock(meter%start, meter%rate)
        if (meter%rate <= 0) meter%enabled = .false.
    end subroutine start_progress

    !> Rewrite the line after `done` steps when it is due (see `progress_due`).
    subroutine update_progress(meter, done)
        !> The meter.
        type(progress_meter), intent(inout) :: meter
        !> Number of steps done so far.
        integer(int64), intent(in) :: done

        real(dp) :: elapsed

        if (.not. meter%enabled) return
        elapsed = seconds_since_start(meter)
        if (progress_due(elapsed, meter%last_shown)) call show(meter, done, elapsed)
    end subroutine update_progress

    !> End the line with the final count and a newline, when it was ever shown.
    subroutine finish_progress(meter, done)
        !> The meter; disabled on return.
        type(progress_meter), intent(inout) :: meter
        !> Number of steps done (the whole run, or up to a fault).
        integer(int64), intent(in) :: done

        if (meter%enabled .and. meter%last_shown >= 0.0_dp) then
            call show(meter, done, seconds_since_start(meter))
            write (error_unit, '(a)') ''
            flush (error_unit)
        end if
        meter%enabled = .false.
    end subroutine finish_progress

    !> Whether the line is due at `elapsed` [s] since the start of the run, when it was last
    !> written at `last_shown` [s] (negative: never): the run has taken at least
    !> `quiet_seconds` and the last update is at least `refresh_seconds` old.
    pure logical function progress_due(elapsed, last_shown)
        !> Wall time since the start of the run [s].
        real(dp), intent(in) :: elapsed
        !> Wall time of the last update [s]; negative when there was none.
        real(dp), intent(in) :: last_shown

        progress_due = elapsed >= quiet_seconds
        if (last_shown >= 0.0_dp) progress_due = progress_due .and. elapsed - last_shown >= refresh_seconds
    end function progress_due

    !> Steps per second so far; 0 before any time has passed.
    pure real(dp) function steps_per_second(done, elapsed)
        integer(int64), intent(in) :: done
        real(dp), intent(in) :: elapsed

        steps_per_second = 0.0_dp
        if (elapsed > 0.0_dp) steps_per_second = real(done, dp)/elapsed
    end function steps_per_second

    !> Percent done and steps per second of a progress line.
    pure function progress_numbers(done, total, elapsed) result(buffer)
        integer(int64), intent(in) :: done, total
        real(dp), intent(in) :: elapsed
        character(len=80) :: buffer

        real(dp) :: percent

        percent = 100.0_dp*real(done, dp)/real(max(total, 1_int64), dp)
        write (buffer, '(f6.1,a,es10.2,a)') percent, ' %  ', steps_per_second(done, elapsed), ' steps/s  '
    end function progress_numbers

    !> "h:mm:ss left" at the rate so far (hours unbounded, rounded to the second); "--:--:-- left"
    !> before any step, padded with blanks.
    pure function time_left(done, total, elapsed) result(buffer)
        integer(int64), intent(in) :: done, total
        real(dp), intent(in) :: elapsed
        character(len=40) :: buffer

        real(dp) :: rate
        integer(int64) :: whole

        rate = steps_per_second(done, elapsed)
        if (rate > 0.0_dp) then
            whole = nint(min(max(real(total - done, dp)/rate, 0.0_dp), 3.6e9_dp), int64)
            write (buffer, '(i0,a,i2.2,a,i2.2,a)') whole/3600, ':', mod(whole/60, 60_int64), ':', &
                mod(whole, 60_int64), ' left'
        else
            buffer = '--:--:-- left'
        end if
    end function time_left

    !> Length of `progress_line(label, done, total, elapsed)`.
    pure integer function progress_length(label, done, total, elapsed)
        character(len=*), intent(in) :: label
        integer(int64), intent(in) :: done, total
        real(dp), intent(in) :: elapsed

        progress_length = 15 + len(label) + len_trim(progress_numbers(done, total, elapsed)) &
                          + len_trim(time_left(done, total, elapsed))
    end function progress_length

    !> The progress line after `done` of `total` steps in `elapsed` seconds: label, percent,
    !> steps per second and the time left at that rate (h:mm:ss; `--:--:--` before any step).
    pure function progress_line(label, done, total, elapsed) result(line)
        !> Name of what runs (the method).
        character(len=*), intent(in) :: label
        !> Steps done.
        integer(int64), intent(in) :: done
        !> Steps of the whole run, >= 1.
        integer(int64), intent(in) :: total
        !> Wall time since the start [s].
        real(dp), intent(in) :: elapsed
        character(len=progress_length(label, done, total, elapsed)) :: line

        line = 'greenconv: '//label//'  '//trim(progress_numbers(done, total, elapsed))//'  ' &
               //time_left(done, total, elapsed)
    end function progress_line

    !> Write the line in place of the previous one.
    subroutine show(meter, done, elapsed)
        type(progress_meter), intent(inout) :: meter
        integer(int64), intent(in) :: done
        real(dp), intent(in) :: elapsed

        character(len=:), allocatable :: line
        integer :: width

        line = progress_line(meter%label, done, meter%total, elapsed)
        width = len(line)
        write (error_unit, '(a)', advance='no') achar(13)//line//repeat(' ', max(meter%width - width, 0))
        flush (error_unit)
        meter%width = width
        meter%last_shown = elapsed
    end subroutine show

    !> Wall time [s] since the meter was started.
    real(dp) function seconds_since_start(meter)
        type(progress_meter), intent(in) :: meter

        integer(int64) :: now

        call system_clock(now)
        seconds_since_start = real(now - meter%start, dp)/real(meter%rate, dp)
    end function seconds_since_start

end module greenconv_scene_run_progress
