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

/* The entry points, looked up once.  Every thread that looks them up finds the same values, so
 * the stores may race harmlessly; they are atomic all the same. */
static gc_int_query gc_in_parallel, gc_max_threads, gc_parallel_kind, gc_blas_threads;
static gc_int_setter gc_set_threads, gc_set_blas_threads;
static int gc_resolved;

static void *gc_symbol(const char *name)
{
    return dlsym(RTLD_DEFAULT, name);
}

/* ISO C has no conversion from an object pointer to a function pointer: the bits are copied. */
#define GC_LOOK_UP(target, name)                                                                  \
    do {                                                                                           \
        void *found = gc_symbol(name);                                                             \
        __typeof__(target) entry;                                                                  \
        memcpy(&entry, &found, sizeof entry);                                                      \
        __atomic_store_n(&(target), entry, __ATOMIC_RELAXED);                                      \
    } while (0)

static void gc_resolve(void)
{
    if (__atomic_load_n(&gc_resolved, __ATOMIC_ACQUIRE)) return;
    GC_LOOK_UP(gc_in_parallel, "omp_in_parallel");
    GC_LOOK_UP(gc_max_threads, "omp_get_max_threads");
    GC_LOOK_UP(gc_set_threads, "omp_set_num_threads");
    GC_LOOK_UP(gc_parallel_kind, "openblas_get_parallel");
    GC_LOOK_UP(gc_blas_threads, "openblas_get_num_threads");
    GC_LOOK_UP(gc_set_blas_threads, "openblas_set_num_threads");
    __atomic_store_n(&gc_resolved, 1, __ATOMIC_RELEASE);
}

/* What must be restored: > 0 an OpenMP thread count, < 0 minus an OpenBLAS thread count, 0
 * nothing.  Returned by greenconv_ext_serial_begin, handed back to greenconv_ext_serial_end. */
int greenconv_ext_serial_begin(void)
{
    gc_resolve();
    if (gc_in_parallel != NULL && gc_in_parallel()) return 0;

    int kind = gc_parallel_kind != NULL ? gc_parallel_kind() : -1;
    if (kind == 1) {
        if (gc_blas_threads == NULL || gc_set_blas_threads == NULL) return 0;
        int threads = gc_blas_threads();
        if (threads <= 1) return 0;
        gc_set_blas_threads(1);
        return -threads;
    }
    if (kind == 0) return 0;

    if (gc_max_threads == NULL || gc_set_threads == NULL) return 0;
    int threads = gc_max_threads();
    if (threads <= 1) return 0;
    gc_set_threads(1);
    return threads;
}

void greenconv_ext_serial_end(int restore)
{
    gc_resolve();
    if (restore > 0 && gc_set_threads != NULL) gc_set_threads(restore);
    if (restore < 0 && gc_set_blas_threads != NULL) gc_set_blas_threads(-restore);
}
