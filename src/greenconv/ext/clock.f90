!> CPU time of the calling thread (ext/thread_clock.c: POSIX's CLOCK_THREAD_CPUTIME_ID), so that
!> runs stepped at once on separate OpenMP threads each report their own CPU seconds.
module greenconv_ext_clock
    use, intrinsic :: iso_c_binding, only: c_double
    use greenconv_core_kinds, only: dp
    implicit none
    private

    public :: thread_seconds

    interface
        !> CPU seconds [s] of the calling thread; -1 where the system has no thread clock.
        function c_thread_seconds() result(seconds) bind(c, name='greenconv_ext_thread_seconds')
            import :: c_double
            real(c_double) :: seconds
        end function c_thread_seconds
    end interface

contains

    !> CPU seconds [s] of the calling thread; the process's (`cpu_time`) where the system has no
    !> thread clock.
    real(dp) function thread_seconds()
        thread_seconds = real(c_thread_seconds(), dp)
        if (thread_seconds < 0.0_dp) call cpu_time(thread_seconds)
    end function thread_seconds

end module greenconv_ext_clock
