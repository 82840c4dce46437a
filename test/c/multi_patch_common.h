/*
 * multi_patch_common.h - a small 3-point structure with two modes of unit modal mass, the
 * contact data and a road, shared by the multi-point C tests (multi_*.c).
 */
#ifndef GREENCONV_TEST_MULTI_COMMON_H
#define GREENCONV_TEST_MULTI_COMMON_H

#include <math.h>

#define NP 3      /* points */
#define NM 2      /* modes */
#define NT 400    /* steps */
#define DT 1.0e-4 /* s */

static double pole_re[NM], pole_im[NM], res_re[NM], res_im[NM];
static const double shape[NM * NP] = {0.9, 1.0, 0.8, /* mode 1 at points 1..3 */
                                      0.7, -0.1, -0.6}; /* mode 2 */
static double k_c[NP], p_c[NP], preload[NP], road[NP * NT];

/* Poles and residues of unit-modal-mass modes at 100 Hz and 250 Hz, 5 % damping; the contact
 * (Hertz, k_c = 2e6 N/m^1.5, F0 = 60 N) and a road of sines shifted from point to point. */
static inline void multi_setup(void)
{
    const double pi = 3.14159265358979323846, f[NM] = {100.0, 250.0}, xi = 0.05;
    for (int k = 0; k < NM; k++) {
        double w = 2.0 * pi * f[k], wd = w * sqrt(1.0 - xi * xi);
        pole_re[k] = -xi * w;
        pole_im[k] = wd;
        res_re[k] = 0.0;
        res_im[k] = -1.0 / (2.0 * wd); /* 1/(2i*wd) */
    }
    for (int i = 0; i < NP; i++) {
        k_c[i] = 2.0e6;
        p_c[i] = 1.5;
        preload[i] = 60.0;
        for (int n = 0; n < NT; n++)
            road[i * NT + n] = 1.2e-3 * sin(2.0 * pi * 180.0 * n * DT - 0.8 * i);
    }
}

/* Largest |a - b| over n values. */
static inline double max_diff(const double *a, const double *b, int n)
{
    double worst = 0.0;
    for (int i = 0; i < n; i++)
        if (fabs(a[i] - b[i]) > worst || a[i] != a[i] || b[i] != b[i]) worst = fabs(a[i] - b[i]);
    return worst;
}

#endif
