/*
 * multi_stepping.c - multi-point convolvers made from modes and from samples; the caller's
 * own loop of gc_multi_contact_step calls equals gc_multi_run_contact bit for bit for every
 * method; a history/push loop equals the explicit run; samples equal the modes they came from.
 */
#include <stdlib.h>
#include <greenconv.h>
#include "check.h"
#include "multi_patch_common.h"

static const char *methods[] = {"modal", "exact", "direct", "fft"};

int main(void)
{
    char msg[512], detail[400];
    double u[NP * NT], f[NP * NT], d[NP * NT], us[NP * NT], fs[NP * NT], ds[NP * NT];
    double r[NP], ui[NP], fi[NP], di[NP];
    gc_build_options whole;
    multi_setup();
    gc_build_options_init(&whole);
    whole.truncation_tol = 0.0;

    for (int m = 0; m < 4; m++) {
        gc_multi_convolver *conv = NULL;
        int status = gc_multi_new_modes(NP, NM, pole_re, pole_im, res_re, res_im, shape, DT, methods[m], NT, NULL,
                                        &conv, msg, sizeof msg);
        snprintf(detail, sizeof detail, "gc_multi_new_modes %s", methods[m]);
        check_status(status, GC_OK, msg, "", detail);
        if (status != GC_OK) continue;
        status = gc_multi_run_contact(conv, NP, NT, k_c, p_c, preload, road, u, f, d, msg, sizeof msg);
        snprintf(detail, sizeof detail, "%s: whole run", methods[m]);
        check_status(status, GC_OK, msg, "", detail);
        status = gc_multi_contact_start(conv, NP, k_c, p_c, preload, msg, sizeof msg);
        for (int n = 0; n < NT && status == GC_OK; n++) {
            for (int i = 0; i < NP; i++) r[i] = road[i * NT + n];
            status = gc_multi_contact_step(conv, NP, r, ui, fi, di, msg, sizeof msg);
            for (int i = 0; i < NP; i++) {
                us[i * NT + n] = ui[i];
                fs[i * NT + n] = fi[i];
                ds[i * NT + n] = di[i];
            }
        }
        double worst = max_diff(u, us, NP * NT) + max_diff(f, fs, NP * NT) + max_diff(d, ds, NP * NT), fmax = 0.0;
        for (int j = 0; j < NP * NT; j++) fmax = f[j] > fmax ? f[j] : fmax;
        snprintf(detail, sizeof detail, "%s: %d steps of gc_multi_contact_step equal the whole run bit for bit "
                 "(max F %.1f N, sum of max differences %.3g)", methods[m], NT, fmax, worst);
        check(status == GC_OK && worst == 0.0 && fmax > 2.0 * preload[0], detail, msg);
        gc_multi_delete(&conv);
    }

    /* The caller's own explicit loop on the history and push doors equals the modal run. */
    {
        gc_multi_convolver *conv = NULL;
        double w0[NP * NP], uh[NP], q[NP], delta0 = pow(preload[0] / k_c[0], 1.0 / p_c[0]), worst = 0.0;
        int status = gc_multi_new_modes(NP, NM, pole_re, pole_im, res_re, res_im, shape, DT, "modal", NT, NULL,
                                        &conv, msg, sizeof msg);
        status |= gc_multi_run_contact(conv, NP, NT, k_c, p_c, preload, road, u, f, d, msg, sizeof msg);
        status |= gc_multi_instant_matrix(conv, NP, w0, msg, sizeof msg);
        status |= gc_multi_reset(conv, msg, sizeof msg);
        check(status == GC_OK && max_diff(w0, (double[NP * NP]){0}, NP * NP) == 0.0, "modal: W0 = 0 (explicit)", msg);
        for (int n = 0; n < NT && status == GC_OK; n++) {
            status |= gc_multi_history(conv, NP, uh, msg, sizeof msg);
            for (int i = 0; i < NP; i++) {
                double delta = delta0 + road[i * NT + n] - uh[i];
                double force = delta > 0.0 ? k_c[i] * delta * sqrt(delta) : 0.0;
                q[i] = force - preload[i];
                if (fabs(force - f[i * NT + n]) > worst) worst = fabs(force - f[i * NT + n]);
            }
            status |= gc_multi_push(conv, NP, q, msg, sizeof msg);
        }
        snprintf(detail, sizeof detail, "modal: own loop of gc_multi_history/gc_multi_push equals the run "
                 "(max |dF| = %.3g N)", worst);
        check(status == GC_OK && worst == 0.0, detail, msg);
        gc_multi_free(conv);
    }

    /* From samples: direct on g sampled here equals direct on the modes (whole kernels). */
    {
        static double g[NP * NP * NT];
        gc_multi_convolver *from_modes = NULL, *from_samples = NULL, *exact = NULL;
        double w0[NP * NP], fmax = 0.0;
        char text[300];
        int size = 0;
        for (int j = 0; j < NP; j++)
            for (int i = 0; i < NP; i++)
                for (int n = 0; n < NT; n++) {
                    double t = n * DT, sum = 0.0;
                    for (int k = 0; k < NM; k++)
                        sum += shape[k * NP + i] * shape[k * NP + j] * 2.0 * exp(pole_re[k] * t) *
                               (res_re[k] * cos(pole_im[k] * t) - res_im[k] * sin(pole_im[k] * t));
                    g[(j * NP + i) * NT + n] = sum;
                }
        int status = gc_multi_new_modes(NP, NM, pole_re, pole_im, res_re, res_im, shape, DT, "direct", NT, &whole,
                                        &from_modes, msg, sizeof msg);
        status |= gc_multi_new_samples(NP, NT, g, DT, "DIRECT", NT, &whole, &from_samples, msg, sizeof msg);
        check_status(status, GC_OK, msg, "", "gc_multi_new_samples direct (any case)");
        status |= gc_multi_run_contact(from_modes, NP, NT, k_c, p_c, preload, road, u, f, d, msg, sizeof msg);
        status |= gc_multi_run_contact(from_samples, NP, NT, k_c, p_c, preload, road, us, fs, ds, msg, sizeof msg);
        for (int j = 0; j < NP * NT; j++) fmax = f[j] > fmax ? f[j] : fmax;
        snprintf(detail, sizeof detail, "samples equal modes under direct: max |dF| = %.3g N of %.1f N",
                 max_diff(f, fs, NP * NT), fmax);
        check(status == GC_OK && max_diff(f, fs, NP * NT) <= 1e-9 * fmax, detail, msg);
        status = gc_multi_describe(from_samples, &size, text, sizeof text);
        snprintf(detail, sizeof detail, "gc_multi_describe: '%s'", text);
        check(status == GC_OK && size == NT - 1 && strstr(text, "direct") == text, detail, "");
        /* W0 of "exact" is non-zero and symmetric: the implicit step. */
        status = gc_multi_new_modes(NP, NM, pole_re, pole_im, res_re, res_im, shape, DT, "exact", NT, NULL, &exact,
                                    msg, sizeof msg);
        status |= gc_multi_instant_matrix(exact, NP, w0, msg, sizeof msg);
        snprintf(detail, sizeof detail, "exact: W0_11 = %.3g m/N, W0_12 - W0_21 = %.3g", w0[0], w0[3] - w0[1]);
        check(status == GC_OK && w0[0] > 0.0 && fabs(w0[3] - w0[1]) <= 1e-15 * w0[0], detail, msg);
        gc_multi_delete(&from_modes);
        gc_multi_delete(&from_samples);
        gc_multi_delete(&exact);
    }
    return check_exit();
}
