/*
 * Reliability at the C door: xi = 0 (undamped) accepted by every method as the driver accepts
 * it; a "direct" or "fft" convolver whose kernel was cut at its n_steps refuses the steps
 * past them (never a short, wrong sum); identification warnings reach the caller
 * (gc_convolver_warnings); a NaN road height stops a run with GC_ERROR_NUMERICAL and zero
 * outputs from the fault on; errmsg_len = 2^32 writes nothing outside the buffer.
 */
#include <math.h>
#include <stdio.h>
#include <string.h>
#include "greenconv.h"
#include "check.h"

#define RUN 100

/* A receptance file of a mass-spring (M = 1 kg, K = 1e4 N/m, damping ratio xi) on a grid
 * of df [Hz] up to f_max [Hz]. */
static int write_sdof_frf(const char *path, double xi, double df, double f_max)
{
    const double pi = 3.14159265358979323846, m = 1.0, k = 1.0e4;
    FILE *file = fopen(path, "w");
    double f;
    if (!file) return 0;
    fprintf(file, "# f [Hz], Re G, Im G [m/N]\n");
    for (f = 0.0; f <= f_max + 1e-9; f += df) {
        double w = 2.0 * pi * f, re = k - m * w * w, im = 2.0 * xi * sqrt(k * m) * w, d = re * re + im * im;
        fprintf(file, "%.17g %.17g %.17g\n", f, re / d, -im / d);
    }
    fclose(file);
    return 1;
}

int main(void)
{
    const char *methods[] = {"direct", "fft", "modal", "recursive", "paper", "exact", "backward", "auto"};
    char message[1024], what[200];
    double road[2 * RUN], u[2 * RUN], f[2 * RUN], delta[2 * RUN], history;
    gc_convolver *conv = NULL;
    int i, n, status, finite;

    for (n = 0; n < 2 * RUN; ++n) road[n] = 1e-4 * sin(0.1 * n);

    /* xi = 0: one rule, [0, 1), for the driver and both doors. */
    for (i = 0; i < 8; ++i) {
        status = gc_convolver_new_sdof(1.0, 1e4, 0.0, 1e-3, methods[i], RUN, &conv, message, sizeof message);
        finite = 0;
        if (status == GC_OK) {
            status = gc_run_contact(conv, 1e6, 1.5, 9.81, RUN, road, u, f, delta, message, sizeof message);
            finite = 1;
            for (n = 0; n < RUN; ++n) finite = finite && isfinite(u[n]);
        }
        snprintf(what, sizeof what, "%s with xi = 0: made and run", methods[i]);
        check(status == GC_OK && finite, what, message);
        gc_convolver_delete(&conv);
    }

    /* A kernel cut at n_steps (xi = 0.001: g far from decayed after 100 steps of 1 ms). */
    for (i = 0; i < 2; ++i) {
        int refused_at = -1;
        gc_convolver_new_sdof(1.0, 1e4, 0.001, 1e-3, methods[i], RUN, &conv, message, sizeof message);
        for (n = 0; n < 2 * RUN; ++n) {
            if (gc_convolver_history(conv, &history) != GC_OK) {
                refused_at = n;
                break;
            }
            if (gc_convolver_push(conv, n == 0 ? 1.0 : 0.0) != GC_OK) {
                refused_at = 1000 + n;
                break;
            }
        }
        snprintf(what, sizeof what, "%s made for %d steps: history refused at step %d (got %d)", methods[i], RUN, RUN,
                 refused_at);
        check(refused_at == RUN && gc_convolver_push(conv, 0.0) == GC_ERROR_INPUT, what, NULL);
        status = gc_run_contact(conv, 1e6, 1.5, 9.81, 2 * RUN, road, u, f, delta, message, sizeof message);
        snprintf(what, sizeof what, "%s: a run of %d steps refused, outputs 0", methods[i], 2 * RUN);
        check(status == GC_ERROR_INPUT && strstr(message, "n_steps >=") != NULL && u[0] == 0.0 && f[2 * RUN - 1] == 0.0,
              what, message);
        status = gc_run_contact(conv, 1e6, 1.5, 9.81, RUN, road, u, f, delta, message, sizeof message);
        snprintf(what, sizeof what, "%s: a run of its %d steps still works", methods[i], RUN);
        check(status == GC_OK, what, message);
        gc_convolver_delete(&conv);
    }
    /* A kernel that decays within the run is valid for any number of steps. */
    gc_convolver_new_sdof(1.0, 1e4, 0.2, 1e-3, "direct", 2000, &conv, message, sizeof message);
    status = GC_OK;
    for (n = 0; n < 5000 && status == GC_OK; ++n) {
        status = gc_convolver_history(conv, &history);
        if (status == GC_OK) status = gc_convolver_push(conv, 0.0);
    }
    check(status == GC_OK, "direct with a decayed kernel: 5000 steps past its 2000", NULL);
    gc_convolver_delete(&conv);

    /* Identification warnings: a lightly damped receptance on a coarse grid wraps around
     * within the period 1/df, which LSCE, fitting g from the inverse FFT of G, warns of. */
    if (write_sdof_frf("build/ctest_wrap.frf", 1e-4, 0.25, 50.0)) {
        status = gc_convolver_new_frf_file_ident("build/ctest_wrap.frf", 0.01, "modal", RUN, "lsce", 1e-3, 4, NULL,
                                                 &conv, message, sizeof message);
        if (status == GC_OK) status = gc_convolver_warnings(conv, message, sizeof message);
        check(status == GC_OK && strstr(message, "wrap-around") != NULL, "wrap-around warning returned", message);
        gc_convolver_delete(&conv);
        status = gc_convolver_new_frf_file_ident("build/ctest_wrap.frf", 0.01, "modal", RUN, "poly_reference", 1e-3,
                                                 4, NULL, &conv, message, sizeof message);
        check_status(status, GC_ERROR_INPUT, message, "poly_reference", "an identification that fits no receptance");
        check(conv == NULL, "refused: no convolver", NULL);
        remove("build/ctest_wrap.frf");
    }
    gc_convolver_new_sdof(1.0, 1e4, 0.02, 1e-3, "modal", RUN, &conv, message, sizeof message);
    strcpy(message, "#");
    status = gc_convolver_warnings(conv, message, sizeof message);
    check(status == GC_OK && message[0] == '\0', "no identification: no warning", message);

    /* A NaN road height: status 3 naming the step, zero outputs from it on. */
    road[40] = NAN;
    status = gc_run_contact(conv, 1e6, 1.5, 9.81, RUN, road, u, f, delta, message, sizeof message);
    finite = 1;
    for (n = 40; n < RUN; ++n) finite = finite && u[n] == 0.0 && f[n] == 0.0 && delta[n] == 0.0;
    check(status == GC_ERROR_NUMERICAL && strstr(message, "step 40") != NULL && finite && isfinite(u[39]),
          "NaN road height at step 40: status 3, the step named, zeros after", message);
    road[40] = 0.0;
    gc_convolver_delete(&conv);

    /* errmsg_len = 2^32 (it used to be cut to a default integer: a write before the buffer). */
    {
        static char guarded[4096];
        size_t huge_length = (size_t)1 << 32;
        int clean = 1;
        memset(guarded, '#', sizeof guarded);
        status = gc_convolver_new_sdof(-1.0, 1e4, 0.02, 1e-3, "modal", RUN, &conv, guarded + 64, huge_length);
        for (i = 0; i < 64; ++i) clean = clean && guarded[i] == '#';
        check(status == GC_ERROR_INPUT && clean && strstr(guarded + 64, "mass") != NULL &&
                  guarded[64 + strlen(guarded + 64) + 1] == '#',
              "errmsg_len = 2^32: the message and its NUL, nothing outside", guarded + 64);
    }
    return check_exit();
}
