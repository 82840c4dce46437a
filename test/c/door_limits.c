/*
 * door_limits.c - the C doors refuse with GC_ERROR_INPUT, naming the argument, what used to
 * crash or pass wrong: NULL output arrays of gc_identify_frf_file, negative point counts of
 * the gc_multi_* calls, a max_order or max_modes past the scenes' cap (200), and a sampled
 * kernel past the cap of 1e8 values (an undamped "direct" or "fft" over 1e8 steps).
 */
#include "greenconv.h"
#include "check.h"

int main(void)
{
    char msg[512];
    const char *frf = "data/sample_receptance.frf";
    double re[40], im[40], rre[40], rim[40], e = 0.0, u = 0.0, q = 1.0, w0 = 0.0;
    double slow = -1.0e-6, pole_re = -1.0, pole_im = 100.0, res_re = 0.0, res_im = -0.005, shape = 1.0;
    int status, n = 0;
    gc_convolver *conv = NULL;
    gc_multi_convolver *multi = NULL;

    /* gc_identify_frf_file: every output pointer checked (this was a SIGSEGV). */
    status = gc_identify_frf_file(frf, 1e-6, 30, 40, &n, NULL, im, rre, rim, &e, msg, sizeof msg);
    check_status(status, GC_ERROR_INPUT, msg, "pole_re", "identify_frf_file pole_re NULL: names pole_re");
    status = gc_identify_frf_file(frf, 1e-6, 30, 40, NULL, re, im, rre, rim, &e, msg, sizeof msg);
    check_status(status, GC_ERROR_INPUT, msg, "n_modes", "identify_frf_file n_modes NULL: names n_modes");
    status = gc_identify_frf_file(frf, 1e-6, 30, 40, &n, re, im, rre, rim, NULL, msg, sizeof msg);
    check_status(status, GC_ERROR_INPUT, msg, "error_e", "identify_frf_file error_e NULL: names error_e");
    status = gc_identify_frf_file(NULL, 1e-6, 30, 40, &n, re, im, rre, rim, &e, msg, sizeof msg);
    check_status(status, GC_ERROR_INPUT, msg, "path", "identify_frf_file path NULL: names path");
    status = gc_identify_frf_file(frf, 1e-6, 30, -1, &n, re, im, rre, rim, &e, msg, sizeof msg);
    check_status(status, GC_ERROR_INPUT, msg, "capacity", "identify_frf_file capacity -1: names capacity");
    status = gc_identify_frf_file(frf, 1e-6, 2147483647, 40, &n, re, im, rre, rim, &e, msg, sizeof msg);
    check_status(status, GC_ERROR_INPUT, msg, "max_modes", "identify_frf_file max_modes 2^31-1: names max_modes");
    status = gc_identify_frf_file(frf, 1e-6, 30, 40, &n, re, im, rre, rim, &e, msg, sizeof msg);
    check_status(status, GC_OK, msg, NULL, "identify_frf_file with every array: still GC_OK");

    /* A kernel past the cap (this was a SIGSEGV for direct, gigabytes for fft). */
    status = gc_convolver_new_sdof(1.0, 1.0e6, 0.0, 1.0e-4, "direct", 100000000, &conv, msg, sizeof msg);
    check_status(status, GC_ERROR_INPUT, msg, "kernel", "new_sdof direct, xi = 0, 1e8 steps: kernel cap");
    check(conv == NULL, "no convolver past the kernel cap", NULL);
    status = gc_convolver_new_sdof(1.0, 1.0e6, 0.0, 1.0e-4, "fft", 100000000, &conv, msg, sizeof msg);
    check_status(status, GC_ERROR_INPUT, msg, "kernel", "new_sdof fft, xi = 0, 1e8 steps: kernel cap");
    status = gc_convolver_new_sdof(1.0, 1.0e6, 0.0, 1.0e-4, "modal", 100000000, &conv, msg, sizeof msg);
    check_status(status, GC_OK, msg, NULL, "new_sdof modal, xi = 0, 1e8 steps: no kernel, accepted");
    gc_convolver_free(conv);
    status = gc_multi_new_modes(1, 1, &slow, &pole_im, &res_re, &res_im, &shape, 1.0e-4, "direct",
                                100000000, NULL, &multi, msg, sizeof msg);
    check_status(status, GC_ERROR_INPUT, msg, "kernel", "multi_new_modes direct, 1e8 steps, slow decay: kernel cap");

    /* Negative point counts (these returned GC_OK, u left untouched). */
    status = gc_multi_new_modes(1, 1, &pole_re, &pole_im, &res_re, &res_im, &shape, 1.0e-4, "modal", 100, NULL,
                                &multi, msg, sizeof msg);
    check_status(status, GC_OK, msg, NULL, "multi_new_modes one point: GC_OK");
    status = gc_multi_push(multi, -1, &q, msg, sizeof msg);
    check_status(status, GC_ERROR_INPUT, msg, "n_points", "multi_push n_points = -1: names n_points");
    status = gc_multi_history(multi, -1, &u, msg, sizeof msg);
    check_status(status, GC_ERROR_INPUT, msg, "n_points", "multi_history n_points = -1: names n_points");
    status = gc_multi_instant_matrix(multi, -5, &w0, msg, sizeof msg);
    check_status(status, GC_ERROR_INPUT, msg, "n_points", "multi_instant_matrix n_points = -5: names n_points");
    status = gc_multi_push(multi, 1, &q, msg, sizeof msg);
    check_status(status, GC_OK, msg, NULL, "multi_push n_points = 1: GC_OK");
    gc_multi_free(multi);

    /* max_order past the cap (2*max_order + stable_orders overflowed: GC_OK with 6 poles). */
    status = gc_multi_new_file("data/patch_green.uff", "modal", 1.0e-4, 100, NULL, 2147483647, &multi, msg,
                               sizeof msg);
    check_status(status, GC_ERROR_INPUT, msg, "max_order", "multi_new_file max_order 2^31-1: names max_order");
    check(multi == NULL, "no convolver for max_order 2^31-1", NULL);
    return check_exit();
}
