/*
 * multi_faults.c - the multi-point C doors on bad input (status 2 naming the argument), on a
 * run that diverges or whose Newton iteration does not converge (status 3 naming the step and
 * the point, outputs zero from the fault on), and on NULL handles and double deletes.
 */
#include <greenconv.h>
#include "check.h"
#include "multi_patch_common.h"

int main(void)
{
    char msg[512];
    double u[NP * NT], f[NP * NT], d[NP * NT], r[NP], ui[NP], fi[NP];
    gc_multi_convolver *conv = NULL;
    int status, n = 0;
    multi_setup();

    /* Bad input to the constructors. */
    double bad_pole[NM] = {pole_re[0], 10.0};
    status = gc_multi_new_modes(NP, NM, bad_pole, pole_im, res_re, res_im, shape, DT, "modal", NT, NULL, &conv, msg,
                                sizeof msg);
    check_status(status, GC_ERROR_INPUT, msg, "pole_re", "undamped pole -> 2 naming pole_re");
    check(conv == NULL, "no handle after a failed constructor", "");
    status = gc_multi_new_modes(0, NM, pole_re, pole_im, res_re, res_im, shape, DT, "modal", NT, NULL, &conv, msg,
                                sizeof msg);
    check_status(status, GC_ERROR_INPUT, msg, "n_points", "n_points = 0 -> 2");
    status = gc_multi_new_modes(NP, NM, pole_re, pole_im, res_re, res_im, NULL, DT, "modal", NT, NULL, &conv, msg,
                                sizeof msg);
    check_status(status, GC_ERROR_INPUT, msg, "shape", "shape NULL -> 2");
    status = gc_multi_new_modes(NP, NM, pole_re, pole_im, res_re, res_im, shape, -DT, "modal", NT, NULL, &conv, msg,
                                sizeof msg);
    check_status(status, GC_ERROR_INPUT, msg, "dt", "dt < 0 -> 2 naming dt");
    status = gc_multi_new_modes(NP, NM, pole_re, pole_im, res_re, res_im, shape, DT, "paper", NT, NULL, &conv, msg,
                                sizeof msg);
    check_status(status, GC_ERROR_INPUT, msg, "multi-point", "single-point method -> 2 saying so");
    double g[NP * NP * 4] = {0};
    status = gc_multi_new_samples(NP, 4, g, DT, "modal", NT, NULL, &conv, msg, sizeof msg);
    check_status(status, GC_ERROR_INPUT, msg, "needs modes", "modal on samples -> 2");
    status = gc_multi_new_samples(NP, 1, g, DT, "direct", NT, NULL, &conv, msg, sizeof msg);
    check_status(status, GC_ERROR_INPUT, msg, "n_samples", "one sample -> 2 naming n_samples");
    status = gc_multi_new_modes(NP, NM, pole_re, pole_im, res_re, res_im, shape, DT, "modal", NT, NULL, NULL, msg,
                                sizeof msg);
    check_status(status, GC_ERROR_INPUT, msg, "conv is NULL", "conv NULL -> 2");

    /* Bad input to a good convolver. */
    status = gc_multi_new_modes(NP, NM, pole_re, pole_im, res_re, res_im, shape, DT, "exact", NT, NULL, &conv, msg,
                                sizeof msg);
    check_status(status, GC_OK, msg, "", "exact convolver made");
    status = gc_multi_history(conv, NP + 1, ui, msg, sizeof msg);
    check_status(status, GC_ERROR_INPUT, msg, "n_points = 4", "wrong n_points -> 2 naming n_points");
    status = gc_multi_push(conv, NP, NULL, msg, sizeof msg);
    check_status(status, GC_ERROR_INPUT, msg, "force", "force NULL -> 2");
    double neg[NP] = {1.0e6, -1.0, 1.0e6};
    status = gc_multi_contact_start(conv, NP, neg, p_c, preload, msg, sizeof msg);
    check_status(status, GC_ERROR_INPUT, msg, "point 2", "k_c < 0 at point 2 -> 2 naming the point");
    status = gc_multi_contact_step(conv, NP, road, ui, fi, NULL, msg, sizeof msg);
    check_status(status, GC_ERROR_INPUT, msg, "start", "step without a run -> 2");
    status = gc_multi_set_newton(conv, 0.0, 50, 1.0, msg, sizeof msg);
    check_status(status, GC_ERROR_INPUT, msg, "tolerance", "tolerance 0 -> 2 naming tolerance");

    /* Newton that cannot converge in one iteration: 3 naming step and point. */
    status = gc_multi_set_newton(conv, 1.0e-300, 1, 1.0, msg, sizeof msg);
    status = gc_multi_run_contact(conv, NP, NT, k_c, p_c, preload, road, u, f, d, msg, sizeof msg);
    check_status(status, GC_ERROR_NUMERICAL, msg, "at step 0", "Newton not converged -> 3 naming the step");
    check(strstr(msg, "at point") != NULL && f[NT - 1] == 0.0, "... and the point, outputs zero", msg);
    status = gc_multi_contact_start(conv, NP, k_c, p_c, preload, msg, sizeof msg);
    for (int i = 0; i < NP; i++) r[i] = road[i * NT];
    status = gc_multi_contact_step(conv, NP, r, ui, fi, NULL, msg, sizeof msg);
    check_status(status, GC_ERROR_NUMERICAL, msg, "at point", "stepped: Newton not converged -> 3 naming the point");
    status = gc_multi_contact_step(conv, NP, r, ui, fi, NULL, msg, sizeof msg);
    check_status(status, GC_ERROR_INPUT, msg, "no contact run", "a fault ends the stepped run");

    /* Divergence: a bound of 1 micrometre is crossed; 3 naming step, time and point. */
    status = gc_multi_set_newton(conv, 1.0e-12, 50, 1.0e-6, msg, sizeof msg);
    status = gc_multi_run_contact(conv, NP, NT, k_c, p_c, preload, road, u, f, d, msg, sizeof msg);
    check_status(status, GC_ERROR_NUMERICAL, msg, "diverged", "divergence -> 3");
    check(strstr(msg, "at point") != NULL && strstr(msg, "at step") != NULL && strstr(msg, "t = ") != NULL,
          "... naming point, step and time", msg);
    for (int j = NT - 5; j < NT; j++) n += u[j] != 0.0 || f[j] != 0.0 || d[j] != 0.0;
    check(n == 0, "outputs zero from the fault on", "");

    /* Message buffers: clamped and NUL-terminated; NULL buffers accepted. */
    char tiny[8] = "xxxxxxx";
    status = gc_multi_reset(NULL, tiny, 5);
    check(status == GC_ERROR_INPUT && strcmp(tiny, "gc_m") == 0, "message clamped to 4 bytes + NUL", tiny);
    status = gc_multi_reset(NULL, NULL, 0);
    check(status == GC_ERROR_INPUT, "NULL handle, NULL buffer -> 2", "");
    status = gc_multi_describe(NULL, NULL, msg, sizeof msg);
    check_status(status, GC_ERROR_INPUT, msg, "conv is NULL", "describe NULL -> 2");

    /* Handles: delete sets NULL, a second delete and a free of NULL do nothing. */
    gc_multi_delete(&conv);
    check(conv == NULL, "gc_multi_delete sets the handle to NULL", "");
    gc_multi_delete(&conv);
    gc_multi_delete(NULL);
    gc_multi_free(NULL);
    check(1, "double delete and NULL free are harmless", "");
    return check_exit();
}
