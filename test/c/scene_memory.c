/*
 * gc_run_scene called again and again by one host keeps no memory: a single-point scene on
 * the sample road file (it used to cost about 82 KB a call, 80 KB of it the road file). The
 * resident size after 40 calls may exceed the size after the first few by less than 1 MB;
 * `make valgrind` runs this program too, where nothing may be "definitely lost".
 *
 * Under AddressSanitizer the resident size also holds the sanitizer's own bookkeeping (its
 * per-thread allocator caches and the store of allocation stack traces, which keeps growing,
 * more and more slowly, as the run's two OpenMP threads meet new call stacks). There the
 * measure is the heap the program holds live, from the sanitizer's allocator, with the same
 * bound.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "greenconv.h"
#include "check.h"

#if defined(__SANITIZE_ADDRESS__)
#define GC_LIVE_HEAP 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define GC_LIVE_HEAP 1
#endif
#endif
#ifdef GC_LIVE_HEAP
/* From the sanitizer's allocator interface (libasan exports it; not every compiler ships the
 * header): the bytes the program has allocated and not yet freed. */
size_t __sanitizer_get_current_allocated_bytes(void);
#endif

/* Resident pages of this process (0 when /proc is not there); under AddressSanitizer the
 * heap held live, both in KB. */
static const char *measure =
#ifdef GC_LIVE_HEAP
    "live heap";
#else
    "resident size";
#endif

static long resident_kb(void)
{
#ifdef GC_LIVE_HEAP
    return (long)(__sanitizer_get_current_allocated_bytes() / 1024);
#else
    long pages = 0, resident = 0;
    FILE *file = fopen("/proc/self/statm", "r");
    if (!file) return 0;
    if (fscanf(file, "%ld %ld", &pages, &resident) != 2) resident = 0;
    fclose(file);
    return resident * 4;
#endif
}

int main(int argc, char **argv)
{
    const char *path = "build/ctest_scene_memory.nml";
    int calls = argc > 1 ? atoi(argv[1]) : 40, i, status = GC_OK;
    char message[1024] = "", what[200];
    long before = 0, after;
    FILE *file = fopen(path, "w");

    if (!file) {
        check(0, "scene file written", path);
        return check_exit();
    }
    fputs("&scene name = 'memory', output_dir = 'build/ctest_scene_memory', dt = 1.0e-4, n_steps = 200 /\n"
          "&structure model = 'sdof', mass = 1.0, stiffness = 1.0e6, damping_ratio = 0.02 /\n"
          "&road profile = 'file', road_file = 'data/road_sample.dat', x_start = 0.5, speed = 20.0 /\n"
          "&contact stiffness = 1.0e6, exponent = 1.5 /\n"
          "&convolution methods = 'direct', 'modal' /\n",
          file);
    fclose(file);
    fflush(stdout);
    for (i = 0; i < calls && status == GC_OK; ++i) {
        status = gc_run_scene(path, message, sizeof message);
        if (i == 4 || (calls <= 4 && i == 0)) before = resident_kb();
    }
    after = resident_kb();
    snprintf(what, sizeof what, "%d calls of gc_run_scene: %s grew by %ld KB after the first five",
             calls, measure, after - before);
    check(status == GC_OK && after - before < 1024, what, message);
    remove(path);
    return check_exit();
}
