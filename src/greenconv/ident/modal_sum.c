/* The receptance of a modal model on many lines (src/greenconv/ident/lm_fit.f90's `evaluate`),
 * the weighted columns of its linear least squares (`linear_matrix`) and of its Jacobian
 * (`jacobian`), with the bits of the Fortran loops they replace and vectorised over the lines.
 *
 * For each pole k in turn and each line l:
 *     g_l <- (g_l + r_k*z) + conj(r_k)*w,
 *     z = 1/(i*omega_l - lambda_k), w = 1/(i*omega_l - conj(lambda_k)),
 * each reciprocal by one real division (a = -Re lambda, d = omega - Im lambda, q = 1/(a*a + d*d),
 * z = (a*q, -(d*q))) and each complex product as gfortran takes it (the
 * straightforward (ac - bd, ad + bc); Fortran's rules, no NaN recovery).  Every operation is
 * one IEEE operation on one line's values, so the order is that of the Fortran loop whatever the
 * vector width: the lines only run side by side.  Contraction into fused multiply-adds is off
 * (the function attribute), as in gram_kernel.c; AVX2 when the CPU has it (four lines per
 * division), the baseline otherwise, the same bits.
 */
#include <stddef.h>

#if defined(__GNUC__) && !defined(__clang__)
#define GC_MODAL_OPTIMIZE __attribute__((optimize("O3", "fp-contract=off")))
#define GC_MODAL_INLINE __attribute__((always_inline)) inline
#else
#define GC_MODAL_OPTIMIZE
#define GC_MODAL_INLINE inline
#endif
#if defined(__GNUC__) && defined(__x86_64__)
#define GC_MODAL_HAS_AVX2 1
#else
#define GC_MODAL_HAS_AVX2 0
#endif

/* 1/(i*omega - lambda) = (a*q, -(d*q)), a = -Re lambda, d = omega - Im lambda, q = 1/(a*a + d*d)
 * (one real division, no cancellation in a*a + d*d), and the same at conj(lambda). */
static GC_MODAL_INLINE void gc_modal_reciprocals(double omega, double pr, double pi, double *dr, double *di,
                                                 double *mr, double *mi)
{
    double a = -pr;
    double d = omega - pi;
    double q = 1.0 / (a * a + d * d);
    double d2 = omega - (-pi);
    double q2 = 1.0 / (a * a + d2 * d2);
    *dr = a * q;
    *di = -(d * q);
    *mr = a * q2;
    *mi = -(d2 * q2);
}

/* The sums of the model: g (n_lines complex values as re, im pairs) gets the terms of the
 * n_poles poles (re, im pairs) and residues (re, im pairs) at omega. */
static GC_MODAL_INLINE void gc_modal_terms(int n_lines, int n_poles, const double *omega, const double *pole,
                                           const double *residue, double *restrict g)
{
    for (int k = 0; k < n_poles; k++) {
        const double pr = pole[2 * k], pi = pole[2 * k + 1];
        const double rr = residue[2 * k], ri = residue[2 * k + 1];
        const double cr = rr, ci = -ri;
        for (int l = 0; l < n_lines; l++) {
            double zr, zi, wr, wi;
            gc_modal_reciprocals(omega[l], pr, pi, &zr, &zi, &wr, &wi);
            /* r*z and conj(r)*w */
            double xr = rr * zr - ri * zi, xi = rr * zi + ri * zr;
            double yr = cr * wr - ci * wi, yi = cr * wi + ci * wr;
            double gr = g[2 * (size_t)l] + xr, gi = g[2 * (size_t)l + 1] + xi;
            g[2 * (size_t)l] = gr + yr;
            g[2 * (size_t)l + 1] = gi + yi;
        }
    }
}

/* The columns of the linear least squares, stacked [Re; Im] (2*n_lines rows): per pole
 * w*(z + w_c) and w*i*(z - w_c), z and w_c the reciprocals. */
static GC_MODAL_INLINE void gc_modal_linear(int n_lines, int n_poles, const double *omega, const double *weight,
                                            const double *pole, double *restrict a)
{
    const size_t lda = 2 * (size_t)n_lines;
    for (int k = 0; k < n_poles; k++) {
        double *c1 = a + (size_t)(2 * k) * lda, *c2 = a + (size_t)(2 * k + 1) * lda;
        for (int l = 0; l < n_lines; l++) {
            double dr, di, mr, mi;
            gc_modal_reciprocals(omega[l], pole[2 * k], pole[2 * k + 1], &dr, &di, &mr, &mi);
            double w = weight[l];
            c1[l] = w * (dr + mr);
            c1[n_lines + l] = w * (di + mi);
            c2[l] = w * (-(di - mi));
            c2[n_lines + l] = w * (dr - mr);
        }
    }
}

/* The Jacobian's columns per pole (Re lambda, Im lambda, Re r, Im r), stacked [Re; Im]: with
 * s = (w*r)*z^2 and t = (w*conj(r))*w_c^2, s + t, i*(s - t), w*z + w*w_c, i*(w*z - w*w_c). */
static GC_MODAL_INLINE void gc_modal_jacobian(int n_lines, int n_poles, const double *omega, const double *weight,
                                              const double *pole, const double *residue, double *restrict jac)
{
    const size_t ldj = 2 * (size_t)n_lines;
    for (int k = 0; k < n_poles; k++) {
        const double rr = residue[2 * k], ri = residue[2 * k + 1];
        const double cr = rr, ci = -ri;
        const double pr = pole[2 * k], pi = pole[2 * k + 1];
        double *c1 = jac + (size_t)(4 * k) * ldj, *c2 = c1 + ldj, *c3 = c2 + ldj, *c4 = c3 + ldj;
        /* the four columns do not overlap (ldj = 2*n_lines) */
#pragma GCC ivdep
        for (int l = 0; l < n_lines; l++) {
            double dr, di, mr, mi;
            gc_modal_reciprocals(omega[l], pr, pi, &dr, &di, &mr, &mi);
            double w = weight[l];
            /* (w*r)*z^2 and (w*conj(r))*w_c^2, each complex product (ac - bd, ad + bc) */
            double ar = w * rr, ai = w * ri, br = w * cr, bi = w * ci;
            double zr2 = dr * dr - di * di, zi2 = dr * di + di * dr;
            double mr2 = mr * mr - mi * mi, mi2 = mr * mi + mi * mr;
            double sr = ar * zr2 - ai * zi2, si = ar * zi2 + ai * zr2;
            double tr = br * mr2 - bi * mi2, ti = br * mi2 + bi * mr2;
            c1[l] = sr + tr;
            c1[n_lines + l] = si + ti;
            c2[l] = -(si - ti);
            c2[n_lines + l] = sr - tr;
            double wdr = w * dr, wdi = w * di, wmr = w * mr, wmi = w * mi;
            c3[l] = wdr + wmr;
            c3[n_lines + l] = wdi + wmi;
            c4[l] = -(wdi - wmi);
            c4[n_lines + l] = wdr - wmr;
        }
    }
}

/* Each kernel twice, for AVX2 and for the baseline, and the public entry that picks one. */
#if GC_MODAL_HAS_AVX2
#define GC_MODAL_AVX2_CLONE(NAME, PARAMETERS, ARGUMENTS)                                            \
    GC_MODAL_OPTIMIZE __attribute__((target("avx2"))) static void NAME##_avx2 PARAMETERS { NAME ARGUMENTS; }
#define GC_MODAL_DISPATCH(NAME, ARGUMENTS)                                                          \
    if (__builtin_cpu_supports("avx2")) {                                                           \
        NAME##_avx2 ARGUMENTS;                                                                      \
        return;                                                                                     \
    }
#else
#define GC_MODAL_AVX2_CLONE(NAME, PARAMETERS, ARGUMENTS)
#define GC_MODAL_DISPATCH(NAME, ARGUMENTS)
#endif
#define GC_MODAL_ENTRY(PUBLIC, NAME, PARAMETERS, ARGUMENTS)                                         \
    GC_MODAL_AVX2_CLONE(NAME, PARAMETERS, ARGUMENTS)                                                \
    GC_MODAL_OPTIMIZE static void NAME##_base PARAMETERS { NAME ARGUMENTS; }                        \
    void PUBLIC PARAMETERS                                                                          \
    {                                                                                               \
        GC_MODAL_DISPATCH(NAME, ARGUMENTS)                                                          \
        NAME##_base ARGUMENTS;                                                                      \
    }

/* g[l] += sum_k r_k/(i*omega_l - lambda_k) + conj(r_k)/(i*omega_l - conj(lambda_k)), poles in
 * order, for lm_fit.f90's `evaluate`. */
GC_MODAL_ENTRY(greenconv_ident_modal_terms, gc_modal_terms,
               (int n_lines, int n_poles, const double *omega, const double *pole, const double *residue, double *g),
               (n_lines, n_poles, omega, pole, residue, g))

/* The first 2*n_poles columns of lm_fit.f90's `linear_matrix` (a: 2*n_lines x 2*n_poles). */
GC_MODAL_ENTRY(greenconv_ident_modal_linear, gc_modal_linear,
               (int n_lines, int n_poles, const double *omega, const double *weight, const double *pole, double *a),
               (n_lines, n_poles, omega, weight, pole, a))

/* The first 4*n_poles columns of lm_fit.f90's `jacobian` (jac: 2*n_lines x 4*n_poles). */
GC_MODAL_ENTRY(greenconv_ident_modal_jacobian, gc_modal_jacobian,
               (int n_lines, int n_poles, const double *omega, const double *weight, const double *pole,
                const double *residue, double *jac),
               (n_lines, n_poles, omega, weight, pole, residue, jac))
