/*
 * c_patch.c - a 4 x 3 contact patch of the library's tyre belt (a pre-tensioned orthotropic
 * plate on an elastic foundation) rolling over a road, driven from C through the multi-point
 * doors of include/greenconv.h with the program's own time loop, one gc_multi_contact_step
 * call per step, and checked against the library's whole run (gc_multi_run_contact).
 *
 * The patch: 12 points over 0.12 m (x, the direction of travel) by 0.15 m (y, across), the
 * belt's modes up to 1.5 kHz; a Hertz law per point, k_c = 2e7 N/m^1.5, preload 250 N each;
 * point i at x_i sees the road at x_start + (x_i - mean x) + V*t, V = 20 m/s, a road of two
 * sines (0.3 mm at 0.25 m wavelength, 0.1 mm at 0.06 m). Methods "modal" (explicit) and
 * "exact" (implicit: all forces of a step solved together by Newton). The stepped forces must
 * equal the whole run's bit for bit; the two methods must agree to 5 % of the peak force (each
 * is second order in dt, doc/multipoint.md "Order in dt"; they differ by their dt^2 errors).
 * Exit status 0 when every check passes.
 */
#include <math.h>
#include <stdio.h>
#include <greenconv.h>

#define NX 4
#define NY 3
#define NP (NX * NY)
#define CAP 400
#define NT 2000

static double pole_re[CAP], pole_im[CAP], res_re[CAP], res_im[CAP], shape[NP * CAP];
static double road[NP * NT], u[NP * NT], f[NP * NT], f_step[NP * NT], f_modal[NP * NT];

static double road_height(double x)
{
    const double pi = 3.14159265358979323846;
    return 3.0e-4 * sin(2.0 * pi * x / 0.25) + 1.0e-4 * sin(2.0 * pi * x / 0.06 + 1.0);
}

int main(void)
{
    const char *methods[2] = {"modal", "exact"};
    const double dt = 1.0e-4, speed = 20.0;
    double x[NP], y[NP], k_c[NP], p[NP], preload[NP], x_mean = 0.0, r[NP], ui[NP], fi[NP];
    char msg[512];
    int n_modes = 0, failed = 0;

    if (gc_multi_plate_patch(NX, NY, 0.12, 0.15, 1500.0, CAP, &n_modes, pole_re, pole_im, res_re, res_im, shape, x,
                             y, msg, sizeof msg) != GC_OK) {
        fprintf(stderr, "c_patch: %s\n", msg);
        return 1;
    }
    for (int i = 0; i < NP; i++) x_mean += x[i] / NP;
    for (int i = 0; i < NP; i++) {
        k_c[i] = 2.0e7;
        p[i] = 1.5;
        preload[i] = 250.0;
        for (int n = 0; n < NT; n++) road[i * NT + n] = road_height(0.5 + (x[i] - x_mean) + speed * n * dt);
    }
    for (int m = 0; m < 2; m++) {
        gc_multi_convolver *conv = NULL;
        double worst = 0.0, peak = 0.0;
        int status = gc_multi_new_modes(NP, n_modes, pole_re, pole_im, res_re, res_im, shape, dt, methods[m], NT,
                                        NULL, &conv, msg, sizeof msg);
        if (status == GC_OK)
            status = gc_multi_run_contact(conv, NP, NT, k_c, p, preload, road, u, f, NULL, msg, sizeof msg);
        if (status == GC_OK) status = gc_multi_contact_start(conv, NP, k_c, p, preload, msg, sizeof msg);
        for (int n = 0; n < NT && status == GC_OK; n++) {
            for (int i = 0; i < NP; i++) r[i] = road[i * NT + n];
            status = gc_multi_contact_step(conv, NP, r, ui, fi, NULL, msg, sizeof msg);
            for (int i = 0; i < NP; i++) f_step[i * NT + n] = fi[i];
        }
        gc_multi_delete(&conv);
        if (status != GC_OK) {
            fprintf(stderr, "c_patch: %s: %s\n", methods[m], msg);
            return 1;
        }
        for (int j = 0; j < NP * NT; j++) {
            worst = fmax(worst, fabs(f_step[j] - f[j]));
            peak = fmax(peak, f[j]);
        }
        printf("c_patch: %s, %d points, %d modes, %d steps: peak force %.1f N, stepped - whole run: max |dF| = %g N\n",
               methods[m], NP, n_modes, NT, peak, worst);
        if (worst != 0.0) {
            printf("FAIL: c_patch: the stepped %s run differs from the whole run\n", methods[m]);
            failed = 1;
        }
        if (m == 0) {
            for (int j = 0; j < NP * NT; j++) f_modal[j] = f[j];
        } else {
            double gap = 0.0;
            for (int j = 0; j < NP * NT; j++) gap = fmax(gap, fabs(f[j] - f_modal[j]));
            printf("c_patch: exact - modal: max |dF| = %.3g N (%.2g of the peak)\n", gap, gap / peak);
            if (!(gap <= 0.05 * peak)) {
                printf("FAIL: c_patch: exact and modal disagree by more than 5 %% of the peak force\n");
                failed = 1;
            }
        }
    }
    return failed;
}
