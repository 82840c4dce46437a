/*
 * multi_file.c - gc_multi_new_file and its companions (gc_multi_new_method, gc_multi_points,
 * gc_multi_file_summary) on small universal files this program writes: the receptance of a
 * mass-spring system at one node, noise-free, whose identified convolver must step as the
 * same system given by its exact pole and residue (gc_multi_new_modes); its impulse response
 * (no receptance: modal methods refused); a truncated file; a missing one; NULL arguments.
 */
#include <math.h>
#include <stdio.h>
#include <greenconv.h>
#include "check.h"

#define N_LINES 81
#define N_TIME 200

static const double pi = 3.14159265358979323846;
static const double mass = 1.5, f_n = 50.0, zeta = 0.02, df = 2.5, dt = 1.0e-3;

/* One node at (0.25, -0.5) m (dataset 15), then one dataset 58: the receptance G_11(f) [m/N]
 * (function type 4, complex double, N_LINES lines from 0 Hz by df; `lines` of them written)
 * or the impulse response g_11(t) [m/(N*s)] (function type 1, real single, N_TIME samples by dt). */
static int write_file(const char *path, int receptance, int lines)
{
    const double w_n = 2.0 * pi * f_n, k = mass * w_n * w_n, c = 2.0 * zeta * mass * w_n;
    const double w_d = w_n * sqrt(1.0 - zeta * zeta);
    FILE *file = fopen(path, "w");
    if (file == NULL) return 0;
    fprintf(file, "    -1\n    15\n         1         0         0         1  2.50000E-01 -5.00000E-01  0.00000E+00\n"
                  "    -1\n    -1\n    58\nmulti_file test\nSDOF\nNONE\nNONE\nNONE\n");
    if (receptance) {
        fprintf(file, "    4         0    0         0       NONE         1   3       NONE         1   3\n"
                      "         6%10d         1  0.00000e+00  %.5e  0.00000e+00\n"
                      "        18    0    0    0 NONE                 Hz                  \n",
                N_LINES, df);
    } else {
        fprintf(file, "    1         0    0         0       NONE         1   3       NONE         1   3\n"
                      "         2%10d         1  0.00000e+00  %.5e  0.00000e+00\n"
                      "        17    0    0    0 NONE                 s                   \n",
                N_TIME, dt);
    }
    fprintf(file, "         8    1    0    0 NONE                 m                   \n"
                  "        13    0    1    0 NONE                 N                   \n"
                  "         0    0    0    0 NONE                 NONE                \n");
    if (receptance) {
        for (int l = 0; l < lines; l++) {
            double w = 2.0 * pi * df * l, re = k - mass * w * w, im = c * w, d = re * re + im * im;
            fprintf(file, "%20.11e%20.11e%s", re / d, -im / d, l % 2 == 1 || l == lines - 1 ? "\n" : "");
        }
    } else {
        for (int m = 0; m < N_TIME; m++) {
            double t = m * dt, g = exp(-zeta * w_n * t) * sin(w_d * t) / (mass * w_d);
            fprintf(file, "%13.5e%s", g, m % 6 == 5 || m == N_TIME - 1 ? "\n" : "");
        }
    }
    fprintf(file, "    -1\n");
    fclose(file);
    return 1;
}

int main(void)
{
    const char *good = "build/multi_file_good.uff", *bad = "build/multi_file_bad.uff";
    const char *impulses = "build/multi_file_impulses.uff";
    const double w_n = 2.0 * pi * f_n, w_d = w_n * sqrt(1.0 - zeta * zeta);
    char msg[512], text[4096];
    gc_multi_convolver *conv = NULL, *other = NULL, *exact = NULL;
    int status, n_points = 0, node = 0, n_poles = -1;
    double x = 0.0, y = 0.0, e_worst = -1.0, e_mean = -1.0;

    if (!write_file(good, 1, N_LINES) || !write_file(bad, 1, N_LINES / 2) || !write_file(impulses, 0, 0)) {
        check(0, "writing the test files in the current folder", "");
        return check_exit();
    }

    /* A good file: one point, one pole, equal to the exact system's convolver. */
    status = gc_multi_new_file(good, "modal", dt, 400, NULL, 6, &conv, msg, sizeof msg);
    check_status(status, GC_OK, msg, "", "receptance file -> modal convolver");
    if (status == GC_OK) {
        status = gc_multi_n_points(conv, &n_points, msg, sizeof msg);
        check(status == GC_OK && n_points == 1, "its points: the file's one node", msg);
        status = gc_multi_points(conv, 1, &node, &x, &y, msg, sizeof msg);
        check(status == GC_OK && node == 1 && x == 0.25 && y == -0.5, "node label 1 at (0.25, -0.5) m", msg);
        status = gc_multi_file_summary(conv, &e_worst, &e_mean, &n_poles, text, sizeof text);
        snprintf(msg, sizeof msg, "status %d, %d poles, E worst %.3g, mean %.3g", status, n_poles, e_worst, e_mean);
        check(status == GC_OK && n_poles == 1 && e_worst >= e_mean && e_worst < 1e-6 &&
                  strncmp(text, "# ", 2) == 0 && strstr(text, good) != NULL,
              "summary: 1 shared pole, E (eq. 7) < 1e-6 on clean data, '# ' lines naming the file", msg);
        status = gc_multi_file_summary(conv, NULL, NULL, NULL, NULL, 0);
        check(status == GC_OK, "summary with every output NULL", "");

        /* The exact system: lambda = -zeta*w_n + i*w_d, r = 1/(2i*m*w_d), phi = 1. */
        double p_re = -zeta * w_n, p_im = w_d, r_re = 0.0, r_im = -1.0 / (2.0 * mass * w_d), phi = 1.0;
        status = gc_multi_new_modes(1, 1, &p_re, &p_im, &r_re, &r_im, &phi, dt, "modal", 400, NULL, &exact, msg,
                                    sizeof msg);
        check_status(status, GC_OK, msg, "", "the exact system from its pole and residue");
        double worst = 0.0, peak = 0.0;
        for (int n = 0; n < 400 && status == GC_OK; n++) {
            double u_file, u_exact, q = n < 5 ? 1.0 : 0.0;
            status = gc_multi_history(conv, 1, &u_file, msg, sizeof msg);
            if (status == GC_OK) status = gc_multi_history(exact, 1, &u_exact, msg, sizeof msg);
            if (status == GC_OK) status = gc_multi_push(conv, 1, &q, msg, sizeof msg);
            if (status == GC_OK) status = gc_multi_push(exact, 1, &q, msg, sizeof msg);
            worst = fmax(worst, fabs(u_file - u_exact));
            peak = fmax(peak, fabs(u_exact));
        }
        snprintf(msg, sizeof msg, "max |du| = %.3g of the peak %.3g m (tolerance 1e-9: clean data, E worst %.3g)",
                 worst / peak, peak, e_worst);
        check(status == GC_OK && peak > 0.0 && worst <= 1e-9 * peak,
              "identified from the file = given as modes, 400 steps of a 5-step pulse", msg);
        gc_multi_delete(&exact);

        /* Another method on the same file, and the refusals of the companions. */
        status = gc_multi_new_method(conv, "fft", dt, 400, NULL, &other, msg, sizeof msg);
        check_status(status, GC_OK, msg, "", "gc_multi_new_method: fft on the same file");
        status = gc_multi_points(other, 1, &node, NULL, NULL, msg, sizeof msg);
        check(status == GC_OK && node == 1, "the new convolver keeps the file's points", msg);
        gc_multi_delete(&other);
        status = gc_multi_new_method(conv, "paper", dt, 400, NULL, &other, msg, sizeof msg);
        check_status(status, GC_ERROR_INPUT, msg, "multi-point", "gc_multi_new_method: single-point method -> 2");
        check(other == NULL, "no handle after a failed gc_multi_new_method", "");
        status = gc_multi_points(conv, 2, &node, &x, &y, msg, sizeof msg);
        check_status(status, GC_ERROR_INPUT, msg, "n_points = 2", "gc_multi_points: wrong n_points -> 2");
    }
    gc_multi_delete(&conv);

    /* A missing file, a truncated file, a method the file cannot serve. */
    status = gc_multi_new_file("no/such/green.uff", "modal", dt, 400, NULL, 6, &conv, msg, sizeof msg);
    check_status(status, GC_ERROR_INPUT, msg, "no/such/green.uff", "missing file -> 2 naming the file");
    check(conv == NULL, "no handle after a failed gc_multi_new_file", "");
    status = gc_multi_new_file(bad, "modal", dt, 400, NULL, 6, &conv, msg, sizeof msg);
    check_status(status, GC_ERROR_INPUT, msg, bad, "truncated dataset 58 -> 2 naming the file");
    status = gc_multi_new_file(impulses, "modal", dt, 400, NULL, 6, &conv, msg, sizeof msg);
    check_status(status, GC_ERROR_INPUT, msg, "modal", "modal on a file of impulse responses -> 2");
    status = gc_multi_new_file(impulses, "direct", dt, 400, NULL, 6, &conv, msg, sizeof msg);
    check_status(status, GC_OK, msg, "", "direct on the file of impulse responses");
    if (status == GC_OK) {
        status = gc_multi_file_summary(conv, &e_worst, &e_mean, &n_poles, text, sizeof text);
        check(status == GC_OK && n_poles == 0 && e_worst == 0.0, "impulse responses: no poles, E = 0", text);
    }
    gc_multi_delete(&conv);
    status = gc_multi_new_file(good, "paper", dt, 400, NULL, 6, &conv, msg, sizeof msg);
    check_status(status, GC_ERROR_INPUT, msg, "multi-point", "single-point method -> 2 before any identification");

    /* Bad arguments and NULLs. */
    status = gc_multi_new_file(good, "modal", -dt, 400, NULL, 6, &conv, msg, sizeof msg);
    check_status(status, GC_ERROR_INPUT, msg, "dt", "dt < 0 -> 2 naming dt");
    status = gc_multi_new_file(good, "modal", dt, 400, NULL, -1, &conv, msg, sizeof msg);
    check_status(status, GC_ERROR_INPUT, msg, "max_order", "max_order < 0 -> 2 naming max_order");
    status = gc_multi_new_file(NULL, "modal", dt, 400, NULL, 6, &conv, msg, sizeof msg);
    check_status(status, GC_ERROR_INPUT, msg, "path is NULL", "path NULL -> 2");
    status = gc_multi_new_file(good, NULL, dt, 400, NULL, 6, &conv, msg, sizeof msg);
    check_status(status, GC_ERROR_INPUT, msg, "method is NULL", "method NULL -> 2");
    status = gc_multi_new_file(good, "modal", dt, 400, NULL, 6, NULL, msg, sizeof msg);
    check_status(status, GC_ERROR_INPUT, msg, "conv is NULL", "conv NULL -> 2");
    status = gc_multi_new_file(NULL, "modal", dt, 400, NULL, 6, &conv, NULL, 0);
    check(status == GC_ERROR_INPUT, "errmsg NULL: the status alone", "");
    status = gc_multi_new_method(NULL, "fft", dt, 400, NULL, &other, msg, sizeof msg);
    check_status(status, GC_ERROR_INPUT, msg, "source is NULL", "gc_multi_new_method: source NULL -> 2");
    status = gc_multi_points(NULL, 1, &node, &x, &y, msg, sizeof msg);
    check_status(status, GC_ERROR_INPUT, msg, "conv is NULL", "gc_multi_points: conv NULL -> 2");
    status = gc_multi_file_summary(NULL, NULL, NULL, NULL, text, sizeof text);
    check_status(status, GC_ERROR_INPUT, text, "conv is NULL", "gc_multi_file_summary: conv NULL -> 2");

    /* A convolver made from modes has no file behind it. */
    double p_re = -1.0, p_im = 10.0, r_re = 0.0, r_im = -0.05, phi = 1.0;
    status = gc_multi_new_modes(1, 1, &p_re, &p_im, &r_re, &r_im, &phi, dt, "modal", 10, NULL, &exact, msg, sizeof msg);
    if (status == GC_OK) {
        status = gc_multi_points(exact, 1, &node, &x, &y, msg, sizeof msg);
        check_status(status, GC_ERROR_INPUT, msg, "not made from a file", "gc_multi_points on modes -> 2");
        status = gc_multi_new_method(exact, "fft", dt, 10, NULL, &other, msg, sizeof msg);
        check_status(status, GC_ERROR_INPUT, msg, "not made from a file", "gc_multi_new_method on modes -> 2");
    }
    gc_multi_delete(&exact);
    remove(good);
    remove(bad);
    remove(impulses);
    return check_exit();
}
