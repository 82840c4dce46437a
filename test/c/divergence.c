/*
 * A diverging run is a failure, never a success: k_c = 1e12 N/m^1.5 at dt = 1 ms, and a NaN
 * road height, each give GC_ERROR_NUMERICAL with the step and time named, the outputs kept
 * before that step and 0 from it on (and no read past the steps done: run under a memory
 * checker to see it). Stepped runs report the same step, and end.
 */
#include <math.h>
#include <stdlib.h>
#include "greenconv.h"
#include "check.h"

#define N_STEPS 2000
#define DT 1.0e-3

/* The step a message names ("... at step N ..."), or -1. */
static int named_step(const char *message)
{
    const char *at = strstr(message, "at step ");
    return at ? atoi(at + 8) : -1;
}

/* Outputs hold finite values before `step` and exact zeros from it on. */
static int kept_then_zero(const double *values, int step)
{
    int n;
    for (n = 0; n < N_STEPS; n++) {
        if (n < step && !isfinite(values[n])) return 0;
        if (n >= step && values[n] != 0.0) return 0;
    }
    return 1;
}

int main(void)
{
    static double road[N_STEPS], u[N_STEPS], f[N_STEPS], delta[N_STEPS];
    char msg[1024], what[200];
    gc_convolver *conv = NULL;
    double u1, f1, d1;
    int n, status, step;

    for (n = 0; n < N_STEPS; n++) road[n] = 1e-3 * sin(50.0 * n * DT);
    status = gc_convolver_new_sdof(100.0, 1e5, 0.05, DT, "modal", N_STEPS, &conv, msg, sizeof msg);
    check_status(status, GC_OK, msg, NULL, "new_sdof (100 kg, 1e5 N/m) 'modal'");

    for (n = 0; n < N_STEPS; n++) u[n] = f[n] = delta[n] = 1234.5;
    status = gc_run_contact(conv, 1e12, 1.5, 981.0, N_STEPS, road, u, f, delta, msg, sizeof msg);
    check_status(status, GC_ERROR_NUMERICAL, msg, "diverged", "k_c = 1e12, dt = 1 ms: status 3, 'diverged'");
    step = named_step(msg);
    snprintf(what, sizeof what, "the message names the step (%d) and its time", step);
    check(step > 0 && step < N_STEPS && strstr(msg, "t = ") != NULL, what, NULL);
    check(step > 0 && kept_then_zero(u, step) && kept_then_zero(f, step) && kept_then_zero(delta, step),
          "u, F, delta: the steps before it kept, 0 from it on", NULL);

    road[5] = NAN;
    status = gc_run_contact(conv, 1e6, 1.5, 981.0, N_STEPS, road, u, f, NULL, msg, sizeof msg);
    check_status(status, GC_ERROR_NUMERICAL, msg, "at step 5 ", "NaN road height at step 5: status 3, step 5 named");
    check(strstr(msg, "road") != NULL, "the message says the road height is not finite", msg);
    check(kept_then_zero(u, 5) && kept_then_zero(f, 5), "u, F: steps 0-4 kept, 0 from step 5 on", NULL);

    status = gc_contact_start(conv, 1e6, 1.5, 981.0, NULL, msg, sizeof msg);
    check_status(status, GC_OK, msg, NULL, "contact_start (defaults)");
    for (n = 0; n < 5 && status == GC_OK; n++)
        status = gc_contact_advance(conv, road[n], &u1, &f1, &d1, msg, sizeof msg);
    check(status == GC_OK, "advance: steps 0-4 succeed", msg);
    status = gc_contact_advance(conv, road[5], &u1, &f1, &d1, msg, sizeof msg);
    check_status(status, GC_ERROR_NUMERICAL, msg, "at step 5 ", "advance on the NaN height: status 3, step 5 named");
    check(u1 == 0.0 && f1 == 0.0 && d1 == 0.0, "advance on a fault: outputs 0", NULL);
    status = gc_contact_advance(conv, 0.0, &u1, &f1, &d1, msg, sizeof msg);
    check_status(status, GC_ERROR_INPUT, msg, "gc_contact_start", "advance after a fault: status 2, says to start");

    gc_convolver_delete(&conv);
    return check_exit();
}
