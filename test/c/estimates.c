/*
 * estimates.c - the single-point doors' error estimate: gc_convolver_estimate after a whole
 * run (gc_run_contact_opts, both schemes) holds its time-step term; a run stepped by
 * gc_contact_start/gc_contact_advance ends with the same estimate (the same companions, fed a
 * step at a time); gc_convolver_set_accuracy below it turns gc_run_contact into GC_ACCURACY
 * with the same results; the multi-point twin after gc_multi_contact_step equals the whole
 * run's. (The estimates' accuracy against an ODE is suite errorbudget's.)
 */
#include <math.h>
#include <stdlib.h>
#include <greenconv.h>
#include "check.h"

#define NT 1000

int main(void)
{
    char msg[512], detail[400];
    static double road[NT], u[NT], f[NT], d[NT], f2[NT];
    const double dt = 1.0e-3, k_c = 1.0e6, p = 1.5, preload = 9.81;
    for (int n = 0; n < NT; n++) road[n] = 1.0e-3 * sin(100.0 * n * dt);

    for (int scheme = GC_SCHEME_EXPLICIT; scheme <= GC_SCHEME_IMPLICIT; scheme++) {
        gc_convolver *conv = NULL;
        gc_contact_options options;
        double whole = -1.0, stepped = -2.0, model = -3.0;
        gc_contact_options_init(&options);
        options.scheme = scheme;
        int status = gc_convolver_new_sdof(1.0, 1.0e6, 0.02, dt, "exact", NT, &conv, msg, sizeof msg);
        check_status(status, GC_OK, msg, "", "gc_convolver_new_sdof exact");
        if (status != GC_OK) continue;
        status = gc_convolver_estimate(conv, &model, msg, sizeof msg);
        check(status == GC_OK && model == 0.0, "exact on the structure's own mode: no model term before a run", msg);
        status = gc_run_contact_opts(conv, k_c, p, preload, NT, road, &options, u, f, d, msg, sizeof msg);
        status |= gc_convolver_estimate(conv, &whole, msg, sizeof msg);
        snprintf(detail, sizeof detail, "scheme %d: a whole run at 1 ms has a time-step term (%.3g)", scheme, whole);
        check(status == GC_OK && whole > 1.0e-5 && whole < 0.1, detail, msg);
        status = gc_contact_start(conv, k_c, p, preload, &options, msg, sizeof msg);
        for (int n = 0; n < NT && status == GC_OK; n++)
            status = gc_contact_advance(conv, road[n], &u[n], &f2[n], &d[n], msg, sizeof msg);
        status |= gc_convolver_estimate(conv, &stepped, msg, sizeof msg);
        snprintf(detail, sizeof detail, "scheme %d: the stepped run ends with the whole run's estimate (%.17g, %.17g)",
                 scheme, stepped, whole);
        check(status == GC_OK && fabs(stepped - whole) <= 1.0e-12 * whole, detail, msg);
        status = gc_convolver_set_accuracy(conv, 0.5 * whole, msg, sizeof msg);
        check_status(status, GC_ACCURACY, msg, "time step", "an accuracy below the last run's estimate: "
                     "GC_ACCURACY at once, the accuracy kept");
        status = gc_run_contact_opts(conv, k_c, p, preload, NT, road, &options, u, f2, d, msg, sizeof msg);
        check_status(status, GC_ACCURACY, msg, "outside the accuracy asked", "a run beyond it: GC_ACCURACY");
        check(memcmp(f, f2, sizeof f) == 0, "its forces are the run's, bit for bit", "");
        status = gc_convolver_set_accuracy(conv, -1.0, msg, sizeof msg);
        check_status(status, GC_ERROR_INPUT, msg, "accuracy", "a negative accuracy is refused");
        status = gc_convolver_estimate(conv, NULL, msg, sizeof msg);
        check_status(status, GC_ERROR_INPUT, msg, "estimate", "a NULL estimate is refused");
        gc_convolver_delete(&conv);
        status = gc_convolver_estimate(conv, &whole, msg, sizeof msg);
        check_status(status, GC_ERROR_INPUT, msg, "NULL", "a NULL convolver is refused");
    }

    /* The multi-point door: its mode as a 1 x 1 Green's matrix, stepped and whole. */
    {
        gc_multi_convolver *conv = NULL;
        const double omega = 1.0e3, xi = 0.02, omega_d = omega * sqrt(1.0 - xi * xi);
        double pole_re = -xi * omega, pole_im = omega_d, res_re = 0.0, res_im = -0.5 / omega_d, shape = 1.0;
        double whole = -1.0, stepped = -2.0, r, ui, fi, di;
        int status = gc_multi_new_modes(1, 1, &pole_re, &pole_im, &res_re, &res_im, &shape, dt, "modal", NT, NULL,
                                        &conv, msg, sizeof msg);
        status |= gc_multi_run_contact(conv, 1, NT, &k_c, &p, &preload, road, u, f, d, msg, sizeof msg);
        status |= gc_multi_estimate(conv, &whole, msg, sizeof msg);
        status |= gc_multi_contact_start(conv, 1, &k_c, &p, &preload, msg, sizeof msg);
        for (int n = 0; n < NT && status == GC_OK; n++) {
            r = road[n];
            status = gc_multi_contact_step(conv, 1, &r, &ui, &fi, &di, msg, sizeof msg);
        }
        status |= gc_multi_estimate(conv, &stepped, msg, sizeof msg);
        snprintf(detail, sizeof detail, "multi-point: gc_multi_contact_step ends with the whole run's estimate "
                 "(%.17g, %.17g)", stepped, whole);
        check(status == GC_OK && whole > 1.0e-5 && fabs(stepped - whole) <= 1.0e-12 * whole, detail, msg);
        gc_multi_delete(&conv);
    }
    return check_exit();
}
