/*
 * A diverging run is a failure, never a success: k_c = 1e12 N/m^1.5 at dt = 1 ms, and a NaN
 * road height, each give GC_ERROR_NUMERICAL with the step and time named, the outputs kept
 * before that step and 0 from it on (and no read past the steps done: run under a memory
 * checker to see it). Stepped runs report the same step, and end. A road height that is NaN
 * or infinite is a fault of the single-point step doors too (gc_contact_step,
 * gc_contact_step_law, gc_contact_advance), as of the multi-point step of one point: status 3,
 * the outputs 0, the convolver not advanced.
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

/* gc_contact_step (law NULL) or gc_contact_step_law on a height that is not finite, from
 * step 0: status 3 and outputs 0, and the convolver not advanced, so that the next step from a
 * finite height gives the values of a first step, bit for bit. */
static void check_point_step(gc_convolver *conv, const gc_law *law, double height, const char *label)
{
    const char *door = law == NULL ? "gc_contact_step" : "gc_contact_step_law";
    char what[200];
    double u = 1234.5, f = 1234.5, d = 1234.5, u0, f0, d0, u1, f1, d1;
    int status;

    gc_convolver_reset(conv);
    status = law == NULL ? gc_contact_step(conv, 1e6, 1.5, 981.0, 1e-4, &u0, &f0, &d0)
                         : gc_contact_step_law(conv, law, 981.0, 1e-4, &u0, &f0, &d0);
    gc_convolver_reset(conv);
    status = status == GC_OK ? GC_OK : -1;
    if (status == GC_OK)
        status = law == NULL ? gc_contact_step(conv, 1e6, 1.5, 981.0, height, &u, &f, &d)
                             : gc_contact_step_law(conv, law, 981.0, height, &u, &f, &d);
    snprintf(what, sizeof what, "%s on a %s road height: status 3 (got %d), outputs 0", door, label, status);
    check(status == GC_ERROR_NUMERICAL && u == 0.0 && f == 0.0 && d == 0.0, what, NULL);
    status = law == NULL ? gc_contact_step(conv, 1e6, 1.5, 981.0, 1e-4, &u1, &f1, &d1)
                         : gc_contact_step_law(conv, law, 981.0, 1e-4, &u1, &f1, &d1);
    snprintf(what, sizeof what, "%s after the %s height: the convolver not advanced (the next step is step 0)",
             door, label);
    check(status == GC_OK && u1 == u0 && f1 == f0 && d1 == d0, what, NULL);
}

/* gc_contact_advance on a height that is not finite at step 3 of a started run: status 3, the
 * door and step 3 named, outputs 0, and the run ended; the multi-point step of one point on
 * the same run says the same of its own door. */
static void check_advance(gc_convolver *conv, double height, const char *label)
{
    char msg[1024], fault[1024], multi[1024], what[200];
    const double k_c = 1e6, p = 1.5, preload = 981.0;
    double u = 1234.5, f = 1234.5, d = 1234.5;
    int n, status, multi_status;

    status = gc_contact_start(conv, k_c, p, preload, NULL, msg, sizeof msg);
    for (n = 0; n < 3 && status == GC_OK; n++) status = gc_contact_advance(conv, 1e-4, &u, &f, &d, msg, sizeof msg);
    u = f = d = 1234.5;
    if (status == GC_OK) status = gc_contact_advance(conv, height, &u, &f, &d, msg, sizeof msg);
    snprintf(what, sizeof what, "gc_contact_advance on a %s road height at step 3: status 3, door and step named",
             label);
    check_status(status, GC_ERROR_NUMERICAL, msg, "at step 3 ", what);
    check(strncmp(msg, "gc_contact_advance: ", 20) == 0, "  the message begins with the door's name", msg);
    snprintf(what, sizeof what, "gc_contact_advance on a %s road height: outputs 0", label);
    check(u == 0.0 && f == 0.0 && d == 0.0, what, NULL);
    snprintf(fault, sizeof fault, "%s", msg);
    status = gc_contact_advance(conv, 1e-4, &u, &f, &d, msg, sizeof msg);
    check_status(status, GC_ERROR_INPUT, msg, "gc_contact_start", "  the run ended: the next advance says to start");

    multi_status = gc_multi_contact_start((gc_multi_convolver *)conv, 1, &k_c, &p, &preload, multi, sizeof multi);
    for (n = 0; n < 3 && multi_status == GC_OK; n++)
        multi_status = gc_multi_contact_step((gc_multi_convolver *)conv, 1, (const double[]){1e-4}, &u, &f, &d, multi,
                                             sizeof multi);
    if (multi_status == GC_OK)
        multi_status = gc_multi_contact_step((gc_multi_convolver *)conv, 1, &height, &u, &f, &d, multi, sizeof multi);
    snprintf(what, sizeof what, "gc_multi_contact_step of one point on the %s height: status 3 at step 3 too",
             label);
    check_status(multi_status, GC_ERROR_NUMERICAL, multi, "at step 3 ", what);
    check(strncmp(multi, "gc_multi_contact_step: ", 23) == 0 && strchr(fault, ':') != NULL &&
              strcmp(strchr(fault, ':'), strchr(multi, ':')) == 0,
          "  both doors say the same after their names", NULL);
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

    {
        const double power[2] = {1e6, 1.5};
        gc_law *law = NULL;
        status = gc_law_new("power", power, 2, &law, msg, sizeof msg);
        check_status(status, GC_OK, msg, NULL, "gc_law_new power (1e6, 1.5)");
        check_point_step(conv, NULL, NAN, "NaN");
        check_point_step(conv, NULL, INFINITY, "+Inf");
        check_point_step(conv, NULL, -INFINITY, "-Inf");
        check_point_step(conv, law, NAN, "NaN");
        check_point_step(conv, law, INFINITY, "+Inf");
        check_point_step(conv, law, -INFINITY, "-Inf");
        check_advance(conv, NAN, "NaN");
        check_advance(conv, INFINITY, "+Inf");
        check_advance(conv, -INFINITY, "-Inf");
        gc_law_free(law);
    }

    gc_convolver_delete(&conv);
    return check_exit();
}
