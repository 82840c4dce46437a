/*
 * Handles: NULL everywhere is refused with GC_ERROR_INPUT, never a crash; gc_convolver_free
 * of NULL does nothing; gc_convolver_delete (and gc_multi_delete) frees once and then finds
 * NULL, however often it is called, and every call on the deleted handle is refused; two
 * convolvers are independent. A single-point door is the multi-point door of one point: on a
 * one-point multi-point handle it steps the same box, a handle of more points it refuses (the
 * contact step doors too, a multi-point run going on left as it was).
 */
#include "greenconv.h"
#include "check.h"

int main(void)
{
    char msg[256];
    gc_convolver *conv = NULL, *other = NULL;
    double value = 0.0, road = 0.0;
    int size = 0, status;

    gc_convolver_free(NULL);
    check(1, "free(NULL): no crash", NULL);
    gc_convolver_delete(NULL);
    gc_convolver_delete(&conv);
    check(conv == NULL, "delete(NULL) and delete(&NULL): no crash", NULL);
    check(gc_convolver_history(NULL, &value) == GC_ERROR_INPUT, "history(NULL): status 2", NULL);
    check(gc_convolver_push(NULL, 1.0) == GC_ERROR_INPUT, "push(NULL): status 2", NULL);
    check(gc_convolver_instant_weight(NULL, &value) == GC_ERROR_INPUT, "instant_weight(NULL): status 2", NULL);
    check(gc_convolver_reset(NULL) == GC_ERROR_INPUT, "reset(NULL): status 2", NULL);
    check(gc_convolver_model_size(NULL, &size) == GC_ERROR_INPUT, "model_size(NULL): status 2", NULL);
    check(gc_convolver_describe(NULL, msg, sizeof msg) == GC_ERROR_INPUT && msg[0] == '\0',
          "describe(NULL): status 2, \"\"", NULL);
    check(gc_contact_step(NULL, 1e6, 1.5, 10.0, 0.0, &value, &value, NULL) == GC_ERROR_INPUT,
          "contact_step(NULL): status 2", NULL);
    status = gc_run_contact(NULL, 1e6, 1.5, 10.0, 1, &road, &value, &value, NULL, msg, sizeof msg);
    check_status(status, GC_ERROR_INPUT, msg, "conv", "run_contact(NULL): status 2 naming conv");
    status = gc_contact_start(NULL, 1e6, 1.5, 10.0, NULL, msg, sizeof msg);
    check_status(status, GC_ERROR_INPUT, msg, "conv", "contact_start(NULL): status 2 naming conv");
    status = gc_contact_advance(NULL, 0.0, &value, &value, NULL, msg, sizeof msg);
    check_status(status, GC_ERROR_INPUT, msg, "conv", "contact_advance(NULL): status 2 naming conv");
    check(gc_contact_options_init(NULL) == GC_ERROR_INPUT && gc_build_options_init(NULL) == GC_ERROR_INPUT,
          "options_init(NULL): status 2", NULL);

    status = gc_convolver_new_sdof(1.0, 1e4, 0.1, 1e-3, "fft", 100, &conv, msg, sizeof msg);
    status += gc_convolver_new_sdof(1.0, 1e4, 0.1, 1e-3, "fft", 100, &other, msg, sizeof msg);
    check(status == GC_OK && conv != NULL && other != NULL && conv != other, "two new convolvers", msg);
    check(gc_convolver_history(conv, NULL) == GC_ERROR_INPUT, "history(conv, NULL): status 2", NULL);
    gc_convolver_push(conv, 1.0);
    gc_convolver_push(conv, 1.0);
    gc_convolver_history(other, &value);
    check(value == 0.0, "pushing one leaves the other at rest", NULL);
    gc_convolver_delete(&conv);
    check(conv == NULL, "delete: the handle is NULL", NULL);
    gc_convolver_delete(&conv);
    check(1, "delete twice: no crash", NULL);
    check(gc_convolver_push(conv, 1.0) == GC_ERROR_INPUT, "push on the deleted handle: status 2", NULL);
    check(gc_convolver_history(conv, &value) == GC_ERROR_INPUT, "history on the deleted handle: status 2", NULL);
    check(gc_contact_step(conv, 1e6, 1.5, 10.0, 0.0, &value, &value, NULL) == GC_ERROR_INPUT,
          "contact_step on the deleted handle: status 2", NULL);
    gc_convolver_delete(&other);
    check(other == NULL, "delete the second: its handle is NULL", NULL);

    /* The multi-point pair: gc_multi_delete frees once, then finds NULL. */
    {
        double pole_re = -30.0, pole_im = 600.0, res_re = 0.0, res_im = -1.0 / 1200.0, shape = 1.0, u = 1.0;
        gc_multi_convolver *multi = NULL;
        status = gc_multi_new_modes(1, 1, &pole_re, &pole_im, &res_re, &res_im, &shape, 1e-4, "direct", 100, NULL,
                                    &multi, msg, sizeof msg);
        check(status == GC_OK && multi != NULL, "a new multi-point convolver", msg);
        gc_multi_delete(&multi);
        check(multi == NULL, "multi delete: the handle is NULL", NULL);
        gc_multi_delete(&multi);
        gc_multi_delete(NULL);
        check(1, "multi delete twice, and of NULL: no crash", NULL);
        status = gc_multi_history(multi, 1, &u, msg, sizeof msg);
        check_status(status, GC_ERROR_INPUT, msg, "conv", "multi history on the deleted handle: status 2");
        status = gc_multi_push(multi, 1, &u, msg, sizeof msg);
        check_status(status, GC_ERROR_INPUT, msg, "conv", "multi push on the deleted handle: status 2");
    }

    /* One handle family: the single-point doors are the multi-point ones of one point. On a
     * one-point multi-point convolver they step and read the same box; given a two-point one
     * (cast), they refuse it instead of reading or writing one value of a two-value array. */
    {
        double pole_re = -30.0, pole_im = 600.0, res_re = 0.0, res_im = -1.0 / 1200.0, shape[2] = {1.0, 0.5};
        double u_point = -1.0, u_multi = -2.0, w_point = -1.0, w_multi = -2.0, q[2] = {1.0, 1.0};
        gc_multi_convolver *multi = NULL;
        int k;
        status = gc_multi_new_modes(1, 1, &pole_re, &pole_im, &res_re, &res_im, shape, 1e-4, "exact", 100, NULL,
                                    &multi, msg, sizeof msg);
        check(status == GC_OK, "a one-point multi-point convolver", msg);
        status = 0;
        for (k = 0; k < 20; k++) {
            status += gc_convolver_push((gc_convolver *)multi, 1.0 + 0.1 * k);
            status += gc_convolver_history((const gc_convolver *)multi, &u_point);
            status += gc_multi_history(multi, 1, &u_multi, msg, sizeof msg);
            if (u_point != u_multi) status += 100;
        }
        status += gc_convolver_instant_weight((const gc_convolver *)multi, &w_point);
        status += gc_multi_instant_matrix(multi, 1, &w_multi, msg, sizeof msg);
        check(status == GC_OK && u_point == u_multi && u_point != 0.0 && w_point == w_multi,
              "one point: gc_convolver_push/history/instant_weight step and read the multi-point box", msg);
        check(gc_convolver_reset((gc_convolver *)multi) == GC_OK && gc_multi_history(multi, 1, &u_multi, msg,
              sizeof msg) == GC_OK && u_multi == 0.0, "one point: gc_convolver_reset resets the multi-point box", msg);
        gc_multi_delete(&multi);

        status = gc_multi_new_modes(2, 1, &pole_re, &pole_im, &res_re, &res_im, shape, 1e-4, "exact", 100, NULL,
                                    &multi, msg, sizeof msg);
        check(status == GC_OK, "a two-point multi-point convolver", msg);
        gc_multi_push(multi, 2, q, msg, sizeof msg);
        check(gc_convolver_history((const gc_convolver *)multi, &u_point) == GC_ERROR_INPUT,
              "two points: gc_convolver_history refuses the handle (status 2)", NULL);
        check(gc_convolver_push((gc_convolver *)multi, 1.0) == GC_ERROR_INPUT,
              "two points: gc_convolver_push refuses the handle (status 2)", NULL);
        check(gc_convolver_instant_weight((const gc_convolver *)multi, &w_point) == GC_ERROR_INPUT,
              "two points: gc_convolver_instant_weight refuses the handle (status 2)", NULL);
        check(gc_contact_step((gc_convolver *)multi, 1e6, 1.5, 10.0, 0.0, &u_point, &w_point, NULL) ==
              GC_ERROR_INPUT, "two points: gc_contact_step refuses the handle (status 2)", NULL);
        {
            const double k_c[2] = {1e6, 1e6}, p[2] = {1.5, 1.5}, preload[2] = {10.0, 10.0};
            status = gc_multi_contact_start(multi, 2, k_c, p, preload, msg, sizeof msg);
            check_status(status, GC_OK, msg, NULL, "two points: a multi-point run started");
            status = gc_contact_advance((gc_convolver *)multi, 0.0, &u_point, &w_point, NULL, msg, sizeof msg);
            check_status(status, GC_ERROR_INPUT, msg, "single-point",
                         "two points: gc_contact_advance on the multi-point run refuses the handle (status 2)");
            status = gc_multi_contact_step(multi, 2, (const double[]){0.0, 0.0}, q, q, NULL, msg, sizeof msg);
            check_status(status, GC_OK, msg, NULL, "  the multi-point run goes on");
        }
        gc_multi_delete(&multi);
    }
    return check_exit();
}
