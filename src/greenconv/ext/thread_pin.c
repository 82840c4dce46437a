/* One thread for the BLAS and LAPACK calls of src/greenconv/ext/lapack.f90, in every build.
 *
 * A threaded BLAS splits a sum between its threads, and the parts are added in another order
 * than one thread adds them: the last bits of a result then follow the thread count.  The
 * identification and the contact layer's LU want the one-thread bits whatever the machine.
 *
 * The calls that set a BLAS's thread count are found by name at run time (dlsym), so that the
 * library links, and behaves, the same with or without OpenMP and with any BLAS:
 *   - OpenBLAS built on OpenMP (openblas_get_parallel() == 2), or any OpenMP BLAS: a call
 *     outside a parallel region runs on omp_get_max_threads() threads, so the calling thread's
 *     OpenMP count is set to 1 and restored afterwards (a per-thread setting: other threads of
 *     the host are not touched);
 *   - OpenBLAS on POSIX threads (== 1): its global thread count is set to 1 and restored;
 *   - a serial BLAS, or a call inside an OpenMP parallel region (which OpenBLAS runs serially):
 *     nothing is changed.
 * The Fortran side (lapack_serial_begin/_end) brackets each call with these two functions.
 */
#define _GNU_SOURCE
#include <dlfcn.h>
#include <stddef.h>
#include <string.h>

typedef int (*gc_int_query)(void);
typedef void (*gc_int_setter)(int);

/* The entry points, looked up at each call (no static storage: two host threads may call at
 * once; a lookup costs a microsecond or so, next to a LAPACK call of tens). */
struct gc_thread_calls {
    gc_int_query in_parallel, max_threads, parallel_kind, blas_threads;
    gc_int_setter set_threads, set_blas_threads;
};

/* ISO C has no conversion from an object pointer to a function pointer: the bits are copied. */
#define GC_LOOK_UP(target, name)                                                                  \
    do {                                                                                           \
        void *found = dlsym(RTLD_DEFAULT, name);                                                   \
        memcpy(&(target), &found, sizeof(target));                                                 \
    } while (0)

static struct gc_thread_calls gc_resolve(void)
{
    struct gc_thread_calls calls;
    GC_LOOK_UP(calls.in_parallel, "omp_in_parallel");
    GC_LOOK_UP(calls.max_threads, "omp_get_max_threads");
    GC_LOOK_UP(calls.set_threads, "omp_set_num_threads");
    GC_LOOK_UP(calls.parallel_kind, "openblas_get_parallel");
    GC_LOOK_UP(calls.blas_threads, "openblas_get_num_threads");
    GC_LOOK_UP(calls.set_blas_threads, "openblas_set_num_threads");
    return calls;
}

/* What must be restored: > 0 an OpenMP thread count, < 0 minus an OpenBLAS thread count, 0
 * nothing.  Returned by greenconv_ext_serial_begin, handed back to greenconv_ext_serial_end. */
int greenconv_ext_serial_begin(void)
{
    struct gc_thread_calls calls = gc_resolve();
    if (calls.in_parallel != NULL && calls.in_parallel()) return 0;

    int kind = calls.parallel_kind != NULL ? calls.parallel_kind() : -1;
    if (kind == 1) {
        if (calls.blas_threads == NULL || calls.set_blas_threads == NULL) return 0;
        int threads = calls.blas_threads();
        if (threads <= 1) return 0;
        calls.set_blas_threads(1);
        return -threads;
    }
    if (kind == 0) return 0;

    if (calls.max_threads == NULL || calls.set_threads == NULL) return 0;
    int threads = calls.max_threads();
    if (threads <= 1) return 0;
    calls.set_threads(1);
    return threads;
}

void greenconv_ext_serial_end(int restore)
{
    struct gc_thread_calls calls = gc_resolve();
    if (restore > 0 && calls.set_threads != NULL) calls.set_threads(restore);
    if (restore < 0 && calls.set_blas_threads != NULL) calls.set_blas_threads(-restore);
}
