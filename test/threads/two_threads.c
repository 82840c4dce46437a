/*
 * two_threads.c - two POSIX threads use the C API at once, each with its own convolvers, as
 * include/greenconv.h promises they may. Each thread, CALLS/2 times in all:
 * builds a convolver, pushes forces and reads the history, builds a second one with a
 * misspelled method (thread 1 "direc", thread 2 "fftx": refused with different messages),
 * and frees the first. Every status must be the expected one and every message exactly the
 * one the same call gave before the threads started: a message cut or spliced with the
 * other thread's (what a shared, static string length does) is a failure.
 *
 *     two_threads [CALLS]     CALLS (default 20000) calls of the API in all, both threads
 *
 * Prints "ok: ..." or "FAIL: ..." lines (test/c/check.h) and exits 1 on a failure. Run it
 * under `valgrind --tool=helgrind` to see the races themselves (`make thread-helgrind`).
 */
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "greenconv.h"
#include "../c/check.h"

/* API calls one round of a thread makes: new_sdof, 8 x (push + history), a refused
 * new_sdof, free. */
#define CALLS_PER_ROUND 19

typedef struct worker {
    const char *bad_method;  /* the misspelled method this thread asks for */
    char expected[512];      /* the message that call gave before the threads started */
    long rounds;             /* rounds to run */
    long bad_status;         /* calls whose status was wrong */
    long bad_message;        /* refusals whose message differed from `expected` */
    long bad_value;          /* history values that differed from the first thread-free run */
    char first_bad[512];     /* the first wrong message seen */
    double history[8];       /* u_h of the 8 steps, as computed before the threads started */
} worker;

/* One round: build, step, be refused, free. Returns 0, or 1 when a status was wrong. */
static int round_of(worker *w, double *history, char *refusal, size_t refusal_len)
{
    char msg[512];
    gc_convolver *conv = NULL, *other = NULL;
    int k;

    if (gc_convolver_new_sdof(1.0, 1.0e4, 0.05, 1.0e-3, "modal", 100, &conv, msg, sizeof msg) != GC_OK) return 1;
    for (k = 0; k < 8; k++) {
        if (gc_convolver_push(conv, 1.0 + k) != GC_OK) return 1;
        if (gc_convolver_history(conv, &history[k]) != GC_OK) return 1;
    }
    if (gc_convolver_new_sdof(1.0, 1.0e4, 0.05, 1.0e-3, w->bad_method, 100, &other, refusal, refusal_len)
        != GC_ERROR_INPUT || other != NULL) return 1;
    gc_convolver_free(conv);
    return 0;
}

/* Both threads start their rounds together. */
static pthread_barrier_t start;

static void *work(void *argument)
{
    worker *w = argument;
    char message[512];
    double history[8];
    long r;
    int k;

    pthread_barrier_wait(&start);
    for (r = 0; r < w->rounds; r++) {
        memset(message, 0, sizeof message);
        if (round_of(w, history, message, sizeof message) != 0) {
            w->bad_status++;
            continue;
        }
        if (strcmp(message, w->expected) != 0) {
            if (w->bad_message == 0) snprintf(w->first_bad, sizeof w->first_bad, "%s", message);
            w->bad_message++;
        }
        for (k = 0; k < 8; k++) {
            if (history[k] != w->history[k]) {
                w->bad_value++;
                break;
            }
        }
    }
    return NULL;
}

int main(int argc, char **argv)
{
    long calls = argc > 1 ? atol(argv[1]) : 20000;
    worker workers[2] = {{.bad_method = "direc"}, {.bad_method = "fftx"}};
    pthread_t threads[2];
    char detail[1200];
    int i;

    for (i = 0; i < 2; i++) {
        workers[i].rounds = calls / (2 * CALLS_PER_ROUND) + 1;
        if (round_of(&workers[i], workers[i].history, workers[i].expected, sizeof workers[i].expected) != 0) {
            check(0, "one thread alone: the round runs", workers[i].expected);
            return check_exit();
        }
    }
    check(strcmp(workers[0].expected, workers[1].expected) != 0 && strstr(workers[0].expected, "direc") != NULL,
          "one thread alone: the two refusals differ and name the method", workers[0].expected);
    pthread_barrier_init(&start, NULL, 2);
    for (i = 0; i < 2; i++) pthread_create(&threads[i], NULL, work, &workers[i]);
    for (i = 0; i < 2; i++) pthread_join(threads[i], NULL);
    pthread_barrier_destroy(&start);
    for (i = 0; i < 2; i++) {
        snprintf(detail, sizeof detail, "thread %d, %ld rounds (%ld calls): %ld wrong statuses, %ld messages cut or "
                 "spliced, %ld wrong histories; first wrong message '%.400s'", i + 1, workers[i].rounds,
                 workers[i].rounds * CALLS_PER_ROUND, workers[i].bad_status, workers[i].bad_message,
                 workers[i].bad_value, workers[i].first_bad);
        check(workers[i].bad_status == 0 && workers[i].bad_message == 0 && workers[i].bad_value == 0,
              "two threads: every status, message and value as with one thread", detail);
    }
    return check_exit();
}
