/*
 * two_readers.c - two POSIX threads read universal files through the C API at once:
 * each round, a thread builds a multi-point convolver from the modes file
 * test/data/uff/modes_plate.uff (dataset 15 + 55: reader, mode table, summary texts), reads its
 * points, frees it, identifies the modes of test/data/uff/frf_complex_double_even.uff
 * (dataset 58 reader, LSCE) and asks for a file that does not exist (thread 1 and thread 2 name
 * different paths, so their refusals differ). Every status, point, pole and message must be
 * exactly what the same calls gave before the threads started: a text cut or spliced by a
 * static string length shared between threads, or a value from the other thread's file, fails.
 *
 *     two_readers [ROUNDS]     ROUNDS (default 50) rounds per thread
 *
 * Run from the top of the repository (the files' paths are relative). Prints "ok: ..." or
 * "FAIL: ..." lines (test/c/check.h) and exits 1 on a failure; under `valgrind --tool=helgrind`
 * any race it reports fails `make thread-readers-helgrind`.
 */
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "greenconv.h"
#include "../c/check.h"

#define MODES_FILE "test/data/uff/modes_plate.uff"
#define FRF_FILE "test/data/uff/frf_complex_double_even.uff"
#define N_POINTS 9
#define CAPACITY 40

/* What one round gives. */
typedef struct reading {
    int node[N_POINTS];
    double x[N_POINTS], y[N_POINTS];
    int n_modes;
    double pole_re[CAPACITY], pole_im[CAPACITY], error_e;
    char refusal[512];
} reading;

typedef struct worker {
    const char *missing;  /* the file this thread asks for that does not exist */
    long rounds;
    reading expected;     /* the round run before the threads started */
    long bad_status, bad_value, bad_message;
    char first_bad[512];
} worker;

/* One round; 0, or 1 when a status was wrong. */
static int round_of(const worker *w, reading *r)
{
    char msg[512];
    gc_multi_convolver *conv = NULL, *none = NULL;
    int n_modes = 0;
    double residue_re[CAPACITY], residue_im[CAPACITY];

    memset(r, 0, sizeof *r);
    if (gc_multi_new_modes_file(MODES_FILE, 3, 0.02, 0.0, "exact", 8.0e-5, 100, NULL, &conv, msg, sizeof msg)
        != GC_OK) return 1;
    if (gc_multi_points(conv, N_POINTS, r->node, r->x, r->y, msg, sizeof msg) != GC_OK) return 1;
    gc_multi_free(conv);
    if (gc_identify_frf_file(FRF_FILE, 1.0e-3, 20, CAPACITY, &n_modes, r->pole_re, r->pole_im, residue_re,
                             residue_im, &r->error_e, msg, sizeof msg) != GC_OK) return 1;
    r->n_modes = n_modes;
    if (gc_multi_new_modes_file(w->missing, 3, 0.02, 0.0, "exact", 8.0e-5, 100, NULL, &none, r->refusal,
                                sizeof r->refusal) != GC_ERROR_INPUT || none != NULL) return 1;
    return 0;
}

static pthread_barrier_t start;

static void *work(void *argument)
{
    worker *w = argument;
    reading r;
    long k;

    pthread_barrier_wait(&start);
    for (k = 0; k < w->rounds; k++) {
        if (round_of(w, &r) != 0) {
            w->bad_status++;
            continue;
        }
        if (strcmp(r.refusal, w->expected.refusal) != 0) {
            if (w->bad_message == 0) snprintf(w->first_bad, sizeof w->first_bad, "%s", r.refusal);
            w->bad_message++;
        }
        if (memcmp(r.node, w->expected.node, sizeof r.node) != 0 || memcmp(r.x, w->expected.x, sizeof r.x) != 0
            || memcmp(r.y, w->expected.y, sizeof r.y) != 0 || r.n_modes != w->expected.n_modes
            || memcmp(r.pole_re, w->expected.pole_re, sizeof r.pole_re) != 0
            || memcmp(r.pole_im, w->expected.pole_im, sizeof r.pole_im) != 0 || r.error_e != w->expected.error_e)
            w->bad_value++;
    }
    return NULL;
}

int main(int argc, char **argv)
{
    long rounds = argc > 1 ? atol(argv[1]) : 50;
    worker workers[2] = {{.missing = "no/such/modes_a.uff"}, {.missing = "no/such/other/modes_bb.uff"}};
    pthread_t threads[2];
    char detail[1200];
    int i;

    for (i = 0; i < 2; i++) {
        workers[i].rounds = rounds;
        if (round_of(&workers[i], &workers[i].expected) != 0) {
            check(0, "one thread alone: the round runs (run from the top of the repository)",
                  workers[i].expected.refusal);
            return check_exit();
        }
    }
    check(workers[0].expected.n_modes > 0 && workers[0].expected.node[0] == 101,
          "one thread alone: the plate's nodes read and the FRF's modes identified", "");
    check(strcmp(workers[0].expected.refusal, workers[1].expected.refusal) != 0
              && strstr(workers[0].expected.refusal, "modes_a.uff") != NULL,
          "one thread alone: the two refusals differ and name their file", workers[0].expected.refusal);
    pthread_barrier_init(&start, NULL, 2);
    for (i = 0; i < 2; i++) pthread_create(&threads[i], NULL, work, &workers[i]);
    for (i = 0; i < 2; i++) pthread_join(threads[i], NULL);
    pthread_barrier_destroy(&start);
    for (i = 0; i < 2; i++) {
        snprintf(detail, sizeof detail, "thread %d, %ld rounds: %ld wrong statuses, %ld wrong values, %ld messages "
                 "cut or spliced; first wrong message '%.400s'", i + 1, workers[i].rounds, workers[i].bad_status,
                 workers[i].bad_value, workers[i].bad_message, workers[i].first_bad);
        check(workers[i].bad_status == 0 && workers[i].bad_value == 0 && workers[i].bad_message == 0,
              "two threads reading files: every status, value and message as with one thread", detail);
    }
    return check_exit();
}
