/*
 * Every constructor makes a convolver that steps: a constant unit force pushed for 3 s on a
 * mass-spring (M = 1 kg, K = 1e4 N/m, xi = 0.1, decay e^-30) must settle on the static
 * deflection F/K = 1e-4 m, the closed form, for every method; the modes constructor given the
 * SDOF's own pole and residue must equal the SDOF constructor bit for bit; a receptance file
 * gives a modal convolver. Each convolver is freed.
 */
#include <math.h>
#include "greenconv.h"
#include "check.h"

#define MASS 1.0
#define STIFFNESS 1.0e4
#define XI 0.1
#define DT 1.0e-3
#define N_STEPS 3000

/* Push a unit force N_STEPS times; the last displacement u = u_h + w0*q [m]. */
static double settle(gc_convolver *conv)
{
    double u_h = 0.0, w0 = 0.0;
    int n;
    for (n = 0; n < N_STEPS; n++) {
        gc_convolver_history(conv, &u_h);
        gc_convolver_instant_weight(conv, &w0);
        gc_convolver_push(conv, 1.0);
    }
    return u_h + w0 * 1.0;
}

/* The relative error of a settled displacement against F/K, with its check line. */
static void check_static(gc_convolver *conv, const char *what, double tol)
{
    char detail[200];
    double u = settle(conv), exact = 1.0 / STIFFNESS;
    snprintf(detail, sizeof detail, "u = %.9e m, F/K = %.9e m, relative error %.2e (tolerance %.0e)", u, exact,
             fabs(u - exact) / exact, tol);
    check(fabs(u - exact) <= tol * exact, what, detail);
}

int main(void)
{
    const char *methods[] = {"direct", "fft", "modal", "recursive", "paper", "exact", "backward", "auto"};
    /* "direct"/"fft" truncate g at 1 % of max|g| (the paper's rule) and the rectangle rule of
     * "modal"/"paper" is O(dt); the holds of "exact" and "backward" have the exact static gain. */
    const double tolerances[] = {5e-3, 5e-3, 2e-3, 2e-3, 2e-3, 1e-9, 1e-9, 5e-3};
    char msg[512], what[120];
    gc_convolver *conv = NULL, *twin = NULL;
    double omega = sqrt(STIFFNESS / MASS), omega_d = omega * sqrt(1.0 - XI * XI);
    double pole_re = -XI * omega, pole_im = omega_d, res_re = 0.0, res_im = -1.0 / (2.0 * MASS * omega_d);
    double g[N_STEPS], a, b;
    size_t i;
    int n, status, size = 0, same = 1;

    for (i = 0; i < sizeof methods / sizeof *methods; i++) {
        status = gc_convolver_new_sdof(MASS, STIFFNESS, XI, DT, methods[i], N_STEPS, &conv, msg, sizeof msg);
        snprintf(what, sizeof what, "new_sdof '%s': status 0", methods[i]);
        check_status(status, GC_OK, msg, NULL, what);
        if (status != GC_OK) continue;
        snprintf(what, sizeof what, "new_sdof '%s': settles on F/K", methods[i]);
        check_static(conv, what, tolerances[i]);
        gc_convolver_free(conv);
    }

    status = gc_convolver_new_sdof(MASS, STIFFNESS, XI, DT, "modal", N_STEPS, &conv, msg, sizeof msg);
    status += gc_convolver_new_modes(1, &pole_re, &pole_im, &res_re, &res_im, DT, "modal", N_STEPS, &twin, msg,
                                     sizeof msg);
    check_status(status, GC_OK, msg, NULL, "new_modes with the SDOF's pole and residue: status 0");
    for (n = 0; n < 500 && status == GC_OK; n++) {
        gc_convolver_history(conv, &a);
        gc_convolver_history(twin, &b);
        same = same && a == b;
        gc_convolver_push(conv, sin(0.01 * n));
        gc_convolver_push(twin, sin(0.01 * n));
    }
    check(same, "new_modes equals new_sdof bit for bit over 500 steps", NULL);
    gc_convolver_free(conv);
    gc_convolver_free(twin);

    for (n = 0; n < N_STEPS; n++) {
        double t = n * DT;
        g[n] = exp(-XI * omega * t) * sin(omega_d * t) / (MASS * omega_d);
    }
    status = gc_convolver_new_samples(N_STEPS, g, DT, "direct", N_STEPS, &conv, msg, sizeof msg);
    check_status(status, GC_OK, msg, NULL, "new_samples of the SDOF's g(n*dt): status 0");
    if (status == GC_OK) check_static(conv, "new_samples 'direct': settles on F/K", 5e-3);
    gc_convolver_free(conv);

    status = gc_convolver_new_frf_file("data/sample_receptance.frf", DT, "modal", N_STEPS, 1e-6, 30, &conv, msg,
                                       sizeof msg);
    check_status(status, GC_OK, msg, NULL, "new_frf_file data/sample_receptance.frf 'modal': status 0");
    status = gc_convolver_model_size(conv, &size);
    snprintf(what, sizeof what, "new_frf_file: modes identified (N_m = %d)", size);
    check(status == GC_OK && size >= 1, what, NULL);
    status = gc_convolver_describe(conv, msg, sizeof msg);
    check(status == GC_OK && strncmp(msg, "recursive: ", 11) == 0, "describe names the engine (modal = recursive)",
          msg);
    gc_convolver_delete(&conv);
    check(conv == NULL, "delete sets the handle to NULL", NULL);
    return check_exit();
}
