/* The two products of a modal convolver on separable mode shapes on one thread
 * (src/greenconv/model/point_modes.f90), each sum in the order of the Fortran loops they
 * replace, whatever the CPU.
 *
 * greenconv_model_separable_displacements: u_i = sum_k phi_ik*a_k as
 *     B(c, n) = sum over the modes k with n(k) = n, in the order of k, of X_f(k)(x_c)*a_k,
 *     G(c, r) = sum over n in order of B(c, n)*Y_n(y_r),   u_i = G(col(i), row(i)).
 * greenconv_model_separable_forces: Q_k = sum_i phi_ik*q_i as
 *     H(n, c) = sum over the points i of column c, in the order of i, of q_i*Y_n(y_row(i)),
 *     Q_k = sum over c in order of X_f(k)(x_c)*H(n(k), c).
 *
 * Each sum starts at zero and adds one rounded product at a time. The loops over the columns
 * c (B, G), the y functions n (H) and the modes k (Q) run side by side in vector lanes: the
 * lanes hold different sums, so the width changes the speed and not the order. GCC is asked
 * for -O3 (its vectoriser) and fp-contract=off (no fused multiply-add), and makes a clone of
 * each function for AVX-512, AVX2 and the baseline, chosen when the program loads
 * (target_clones): every CPU gives the bits of the Fortran loops. Indices from Fortran count
 * from 1. */
#include <stddef.h>

#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__)
#define GC_SEPARABLE_KERNEL                                                                        \
    __attribute__((optimize("O3", "fp-contract=off"), target_clones("avx512f", "avx2", "default")))
#elif defined(__GNUC__) && !defined(__clang__)
#define GC_SEPARABLE_KERNEL __attribute__((optimize("O3", "fp-contract=off")))
#else
#define GC_SEPARABLE_KERNEL
#endif

/* along (n_col x N_x), across (n_row x n_y), column-major; by_column (n_col x n_y) and grid
 * (n_col x n_row) work space. */
GC_SEPARABLE_KERNEL
void greenconv_model_separable_displacements(int n_col, int n_y, int n_row, int n_m, int n_c, const double *along,
                                             const int *mode_along, const int *mode_across, const double *across,
                                             const double *amplitudes, const int *column, const int *row,
                                             double *by_column, double *grid, double *u)
{
    size_t nc = (size_t)n_col;
    for (size_t e = 0; e < nc * (size_t)n_y; e++) by_column[e] = 0.0;
    for (int k = 0; k < n_m; k++) {
        double *b = by_column + (size_t)(mode_across[k] - 1) * nc;
        const double *x = along + (size_t)(mode_along[k] - 1) * nc;
        double a = amplitudes[k];
        for (size_t c = 0; c < nc; c++) b[c] = b[c] + x[c] * a;
    }
    for (int r = 0; r < n_row; r++) {
        double *g = grid + (size_t)r * nc;
        for (size_t c = 0; c < nc; c++) g[c] = 0.0;
        for (int n = 0; n < n_y; n++) {
            const double *b = by_column + (size_t)n * nc;
            double y = across[(size_t)r + (size_t)n * (size_t)n_row];
            for (size_t c = 0; c < nc; c++) g[c] = g[c] + b[c] * y;
        }
    }
    for (int i = 0; i < n_c; i++) u[i] = grid[(size_t)(column[i] - 1) + (size_t)(row[i] - 1) * nc];
}

/* along_t (N_x x n_col) and across_t (n_y x n_row): the factors transposed; by_point
 * (n_y x n_col) work space. */
GC_SEPARABLE_KERNEL
void greenconv_model_separable_forces(int n_col, int n_y, int n_x, int n_m, int n_c, const double *along_t,
                                      const int *mode_along, const int *mode_across, const double *across_t,
                                      const double *loads, const int *column, const int *row, double *by_point,
                                      double *modal)
{
    size_t ny = (size_t)n_y, nx = (size_t)n_x;
    for (size_t e = 0; e < ny * (size_t)n_col; e++) by_point[e] = 0.0;
    for (int i = 0; i < n_c; i++) {
        double *h = by_point + (size_t)(column[i] - 1) * ny;
        const double *y = across_t + (size_t)(row[i] - 1) * ny;
        double q = loads[i];
        for (size_t n = 0; n < ny; n++) h[n] = h[n] + q * y[n];
    }
    for (int k = 0; k < n_m; k++) modal[k] = 0.0;
    for (int c = 0; c < n_col; c++) {
        const double *x = along_t + (size_t)c * nx;
        const double *h = by_point + (size_t)c * ny;
        for (int k = 0; k < n_m; k++) modal[k] = modal[k] + x[mode_along[k] - 1] * h[mode_across[k] - 1];
    }
}
