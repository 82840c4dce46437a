/* The CPU time of the calling thread, for the run's and its companions' own CPU seconds when
 * they are stepped on separate OpenMP threads (src/greenconv/ext/clock.f90 is its Fortran
 * side).  POSIX's CLOCK_THREAD_CPUTIME_ID where the system has it; -1 where it does not, and
 * the caller then falls back on the process's CPU time.
 */
#define _POSIX_C_SOURCE 199309L
#include <time.h>

double greenconv_ext_thread_seconds(void)
{
#ifdef CLOCK_THREAD_CPUTIME_ID
    struct timespec now;
    if (clock_gettime(CLOCK_THREAD_CPUTIME_ID, &now) == 0) {
        return (double)now.tv_sec + 1.0e-9 * (double)now.tv_nsec;
    }
#endif
    return -1.0;
}
