/*
 * past_length.c - a "direct" or "fft" convolver whose kernel was cut at the n_steps it was
 * made for (g not decayed by then) is refused, alike at every C door, one step past that
 * length: status GC_ERROR_INPUT and a message naming the door, the step and the length,
 * never GC_OK with a short, wrong sum. The steps before it are served (the same forces as a
 * convolver made for the whole run, bit for bit), a modal convolver runs on, and a reset
 * serves the steps again. The multi-point structure is multi_patch_common.h's 3 points.
 */
#include <stdlib.h>
#include <greenconv.h>
#include "check.h"
#include "multi_patch_common.h"

#define SHORT 10 /* steps the short convolvers are made for */

static const char *cut[] = {"direct", "fft"};

/* The multi-point doors: contact steps, history and push, a whole run. */
static void multi_doors(const char *method)
{
    char msg[512], what[200];
    double r[NP], u[NP], f[NP], d[NP], uh[NP], q[NP] = {1.0, 1.0, 1.0};
    double fl[NP * SHORT], ul[NP * SHORT], dl[NP * SHORT];
    static double ur[NP * NT], fr[NP * NT], dr[NP * NT];
    gc_multi_convolver *conv = NULL, *whole = NULL;
    int status, n = 0;

    status = gc_multi_new_modes(NP, NM, pole_re, pole_im, res_re, res_im, shape, DT, method, SHORT, NULL, &conv,
                                msg, sizeof msg);
    status |= gc_multi_new_modes(NP, NM, pole_re, pole_im, res_re, res_im, shape, DT, method, NT, NULL, &whole, msg,
                                 sizeof msg);
    snprintf(what, sizeof what, "multi %s: made for %d and for %d steps", method, SHORT, NT);
    check(status == GC_OK, what, msg);
    if (status != GC_OK) return;

    /* 400 contact steps on a convolver made for 10: the first 10 served, the 11th refused. */
    status = gc_multi_contact_start(conv, NP, k_c, p_c, preload, msg, sizeof msg);
    for (n = 0; n < NT && status == GC_OK; n++) {
        for (int i = 0; i < NP; i++) r[i] = road[i * NT + n];
        status = gc_multi_contact_step(conv, NP, r, u, f, d, msg, sizeof msg);
        if (status == GC_OK)
            for (int i = 0; i < NP; i++) fl[i * SHORT + n] = f[i];
    }
    snprintf(what, sizeof what, "multi %s: gc_multi_contact_step refused at step %d of %d (status %d)", method,
             n - 1, NT, status);
    check(status == GC_ERROR_INPUT && n - 1 == SHORT && strstr(msg, "gc_multi_contact_step") != NULL &&
              strstr(msg, "step 10") != NULL && strstr(msg, "n_steps") != NULL && f[0] == 0.0,
          what, msg);
    status = gc_multi_contact_step(conv, NP, r, u, f, d, msg, sizeof msg);
    check_status(status, GC_ERROR_INPUT, msg, "no contact run", "multi: the refusal ends the run");

    /* The steps served equal those of a convolver made for the whole run. */
    status = gc_multi_run_contact(whole, NP, NT, k_c, p_c, preload, road, ur, fr, dr, msg, sizeof msg);
    double worst = 0.0;
    for (int i = 0; i < NP; i++)
        for (int m = 0; m < SHORT; m++) worst = fmax(worst, fabs(fl[i * SHORT + m] - fr[i * NT + m]));
    snprintf(what, sizeof what, "multi %s: the %d steps served equal the whole run's (max |dF| %.3g N, "
             "F up to %.1f N)", method, SHORT, worst, fr[SHORT - 1]);
    check(status == GC_OK && worst <= 1e-9 * fabs(fr[SHORT - 1]) && fr[SHORT - 1] > 0.0, what, msg);

    /* A whole run longer than the kernel: refused before any step, outputs zero. */
    ur[0] = fr[0] = 1.0;
    status = gc_multi_run_contact(conv, NP, NT, k_c, p_c, preload, road, ur, fr, dr, msg, sizeof msg);
    snprintf(what, sizeof what, "multi %s: gc_multi_run_contact of %d steps refused, outputs zero", method, NT);
    check(status == GC_ERROR_INPUT && strstr(msg, "gc_multi_run_contact") != NULL && strstr(msg, "step 10") &&
              fr[0] == 0.0 && ur[0] == 0.0,
          what, msg);
    status = gc_multi_run_contact(conv, NP, SHORT, k_c, p_c, preload, road, ul, fl, dl, msg, sizeof msg);
    check_status(status, GC_OK, msg, NULL, "multi: a run of the length made for still runs");

    /* history and push: served up to step 9, refused at step 10; a reset serves them again. */
    status = gc_multi_reset(conv, msg, sizeof msg);
    for (n = 0; n < NT && status == GC_OK; n++) {
        status = gc_multi_history(conv, NP, uh, msg, sizeof msg);
        if (status == GC_OK) status = gc_multi_push(conv, NP, q, msg, sizeof msg);
    }
    snprintf(what, sizeof what, "multi %s: gc_multi_history refused at step %d", method, n - 1);
    check(status == GC_ERROR_INPUT && n - 1 == SHORT && strstr(msg, "gc_multi_history") != NULL, what, msg);
    status = gc_multi_push(conv, NP, q, msg, sizeof msg);
    check_status(status, GC_ERROR_INPUT, msg, "gc_multi_push: step 10", "multi: gc_multi_push refused at step 10");
    status = gc_multi_reset(conv, msg, sizeof msg);
    status |= gc_multi_history(conv, NP, uh, msg, sizeof msg);
    check(status == GC_OK && uh[0] == 0.0, "multi: after a reset, step 0 is served", msg);
    gc_multi_delete(&conv);
    gc_multi_delete(&whole);
}

/* The single-point doors: gc_contact_step, gc_contact_advance, history and push, a whole run. */
static void single_doors(const char *method)
{
    char msg[512], what[200];
    double u = 0.0, f = 0.0, d = 0.0, road1[NT];
    static double ur[NT], fr[NT], dr[NT];
    gc_convolver *conv = NULL;
    int status, n;

    for (n = 0; n < NT; n++) road1[n] = road[n];
    status = gc_convolver_new_sdof(1.0, 1.0e6, 0.02, DT, method, SHORT, &conv, msg, sizeof msg);
    check_status(status, GC_OK, msg, NULL, "single: made for 10 steps");
    if (status != GC_OK) return;
    for (n = 0; n < NT && status == GC_OK; n++)
        status = gc_contact_step(conv, 1.0e6, 1.5, 10.0, road1[n], &u, &f, &d);
    snprintf(what, sizeof what, "single %s: gc_contact_step refused at step %d (status %d)", method, n - 1,
             status);
    check(status == GC_ERROR_INPUT && n - 1 == SHORT, what, NULL);

    status = gc_contact_start(conv, 1.0e6, 1.5, 10.0, NULL, msg, sizeof msg);
    for (n = 0; n < NT && status == GC_OK; n++)
        status = gc_contact_advance(conv, road1[n], &u, &f, &d, msg, sizeof msg);
    snprintf(what, sizeof what, "single %s: gc_contact_advance refused at step %d", method, n - 1);
    check(status == GC_ERROR_INPUT && n - 1 == SHORT && strstr(msg, "gc_contact_advance: step 10") != NULL, what,
          msg);

    gc_convolver_reset(conv);
    for (n = 0, status = GC_OK; n < NT && status == GC_OK; n++) {
        status = gc_convolver_history(conv, &u);
        if (status == GC_OK) status = gc_convolver_push(conv, 1.0);
    }
    snprintf(what, sizeof what, "single %s: gc_convolver_history refused at step %d", method, n - 1);
    check(status == GC_ERROR_INPUT && n - 1 == SHORT, what, NULL);

    status = gc_run_contact(conv, 1.0e6, 1.5, 10.0, NT, road1, ur, fr, dr, msg, sizeof msg);
    snprintf(what, sizeof what, "single %s: gc_run_contact of %d steps refused", method, NT);
    check(status == GC_ERROR_INPUT && strstr(msg, "step 10") != NULL, what, msg);
    gc_convolver_delete(&conv);
}

int main(void)
{
    char msg[512];
    double r[NP], u[NP], f[NP], d[NP];
    gc_multi_convolver *conv = NULL;
    int status = GC_OK, n;

    multi_setup();
    for (int m = 0; m < 2; m++) {
        multi_doors(cut[m]);
        single_doors(cut[m]);
    }

    /* A modal convolver holds no kernel: made for 10 steps, it runs all 400. */
    status = gc_multi_new_modes(NP, NM, pole_re, pole_im, res_re, res_im, shape, DT, "modal", SHORT, NULL, &conv,
                                msg, sizeof msg);
    status |= gc_multi_contact_start(conv, NP, k_c, p_c, preload, msg, sizeof msg);
    for (n = 0; n < NT && status == GC_OK; n++) {
        for (int i = 0; i < NP; i++) r[i] = road[i * NT + n];
        status = gc_multi_contact_step(conv, NP, r, u, f, d, msg, sizeof msg);
    }
    check(status == GC_OK && n == NT, "modal, made for 10 steps: 400 contact steps served", msg);
    gc_multi_delete(&conv);
    return check_exit();
}
