/* The Gram product A^T A of the identification fits (src/greenconv/ident/dense.f90's `gram`),
 * in one fixed order of summation whatever the build.
 *
 * Each element (i, j), i <= j, is the sum over the rows r = 0, 1, ..., m - 1 of
 * a[r + i*m] * a[r + j*m], added in that order into one accumulator that starts at 0.  The
 * order does not depend on the block an element falls in, so the bits do not either; they do
 * not depend on the BLAS, the thread count or the CPU.  GCC contracts a*b + c into a fused
 * multiply-add only when told it may (fp-contract) and the target has one: the function asks
 * for fp-contract=off, so no build of it contracts.
 *
 * Why C: the kernel must be fast in every build, the Fortran debug profile (-O0) included,
 * which the test suites run; a GCC function attribute asks for -O2 here alone.  Eight columns j
 * are packed row by row (a[r, j..j+7] side by side), and four columns i are taken against them:
 * per row, two 4-wide vector loads, four broadcasts, eight vector products and eight vector
 * sums make the 32 products.  Each vector lane is one element's sum, so the vectors change
 * the speed and not the order: a lane adds x*y (rounded) to its accumulator exactly as a
 * scalar loop does.  The vector kernel is compiled for AVX2 (four doubles per instruction; no
 * FMA: fp-contract is off) and taken when the CPU has it; otherwise, or without the memory for
 * the packed columns (8*m doubles), the scalar kernel takes the same sums, columns four by
 * four, sixteen sums over the rows together.
 */
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

#if defined(__GNUC__) && !defined(__clang__)
#define GC_GRAM_OPTIMIZE __attribute__((optimize("O2", "fp-contract=off")))
#else
#define GC_GRAM_OPTIMIZE
#endif
#if defined(__GNUC__) && defined(__x86_64__)
#define GC_GRAM_HAS_VECTOR 1
#define GC_GRAM_AVX2 __attribute__((target("avx2")))
#else
#define GC_GRAM_HAS_VECTOR 0
#define GC_GRAM_AVX2
#endif

/* The scalar kernel: columns four by four, sixteen sums over the rows together. */
GC_GRAM_OPTIMIZE
static void gc_gram_scalar(int m, int n, const double *a, double *product)
{
    for (int jb = 0; jb < n; jb += 4) {
        int width_j = n - jb < 4 ? n - jb : 4;
        const double *cj[4];
        for (int q = 0; q < 4; q++) cj[q] = a + (size_t)(jb + (q < width_j ? q : width_j - 1)) * (size_t)m;
        for (int ib = 0; ib <= jb; ib += 4) {
            int width_i = n - ib < 4 ? n - ib : 4;
            const double *ci[4];
            for (int p = 0; p < 4; p++) ci[p] = a + (size_t)(ib + (p < width_i ? p : width_i - 1)) * (size_t)m;
            double s00 = 0.0, s01 = 0.0, s02 = 0.0, s03 = 0.0, s10 = 0.0, s11 = 0.0, s12 = 0.0, s13 = 0.0;
            double s20 = 0.0, s21 = 0.0, s22 = 0.0, s23 = 0.0, s30 = 0.0, s31 = 0.0, s32 = 0.0, s33 = 0.0;
            for (int r = 0; r < m; r++) {
                double x0 = ci[0][r], x1 = ci[1][r], x2 = ci[2][r], x3 = ci[3][r];
                double y0 = cj[0][r], y1 = cj[1][r], y2 = cj[2][r], y3 = cj[3][r];
                s00 += x0 * y0; s01 += x0 * y1; s02 += x0 * y2; s03 += x0 * y3;
                s10 += x1 * y0; s11 += x1 * y1; s12 += x1 * y2; s13 += x1 * y3;
                s20 += x2 * y0; s21 += x2 * y1; s22 += x2 * y2; s23 += x2 * y3;
                s30 += x3 * y0; s31 += x3 * y1; s32 += x3 * y2; s33 += x3 * y3;
            }
            double s[4][4] = {{s00, s01, s02, s03}, {s10, s11, s12, s13}, {s20, s21, s22, s23}, {s30, s31, s32, s33}};
            for (int q = 0; q < width_j; q++)
                for (int p = 0; p < width_i; p++)
                    if (ib + p <= jb + q) product[(size_t)(ib + p) + (size_t)(jb + q) * (size_t)n] = s[p][q];
        }
    }
}

#if GC_GRAM_HAS_VECTOR
/* Four doubles. */
typedef double gc_v4 __attribute__((vector_size(32)));

/* The vector kernel (AVX2), with the same sums as gc_gram_scalar; 0 without the memory for
 * the packed columns. */
GC_GRAM_OPTIMIZE GC_GRAM_AVX2
static int gc_gram_vector(int m, int n, const double *a, double *product)
{
    double *packed = malloc(sizeof(double) * 8 * (size_t)m);
    if (packed == NULL) return 0;
    for (int jb = 0; jb < n; jb += 8) {
        int width_j = n - jb < 8 ? n - jb : 8;
        for (int r = 0; r < m; r++)
            for (int q = 0; q < 8; q++)
                packed[(size_t)r * 8 + (size_t)q] = q < width_j ? a[(size_t)r + (size_t)(jb + q) * (size_t)m] : 0.0;
        for (int ib = 0; ib < jb + width_j; ib += 4) {
            int width_i = n - ib < 4 ? n - ib : 4;
            const double *ci[4];
            for (int p = 0; p < 4; p++) ci[p] = a + (size_t)(ib + (p < width_i ? p : width_i - 1)) * (size_t)m;
            gc_v4 s00 = {0.0, 0.0, 0.0, 0.0}, s01 = s00, s10 = s00, s11 = s00;
            gc_v4 s20 = s00, s21 = s00, s30 = s00, s31 = s00;
            for (int r = 0; r < m; r++) {
                gc_v4 y0, y1;
                memcpy(&y0, packed + (size_t)r * 8, sizeof y0);
                memcpy(&y1, packed + (size_t)r * 8 + 4, sizeof y1);
                double x0 = ci[0][r], x1 = ci[1][r], x2 = ci[2][r], x3 = ci[3][r];
                s00 += x0 * y0; s01 += x0 * y1;
                s10 += x1 * y0; s11 += x1 * y1;
                s20 += x2 * y0; s21 += x2 * y1;
                s30 += x3 * y0; s31 += x3 * y1;
            }
            double s[4][8];
            memcpy(&s[0][0], &s00, sizeof s00); memcpy(&s[0][4], &s01, sizeof s01);
            memcpy(&s[1][0], &s10, sizeof s10); memcpy(&s[1][4], &s11, sizeof s11);
            memcpy(&s[2][0], &s20, sizeof s20); memcpy(&s[2][4], &s21, sizeof s21);
            memcpy(&s[3][0], &s30, sizeof s30); memcpy(&s[3][4], &s31, sizeof s31);
            for (int q = 0; q < width_j; q++)
                for (int p = 0; p < width_i; p++)
                    if (ib + p <= jb + q) product[(size_t)(ib + p) + (size_t)(jb + q) * (size_t)n] = s[p][q];
        }
    }
    free(packed);
    return 1;
}
#endif

/* The upper triangle (i <= j) of A^T A for a column-major m x n matrix a, written into the
 * column-major n x n matrix product; the strict lower triangle is not touched. */
void greenconv_ident_gram_upper(int m, int n, const double *a, double *product)
{
    if (n <= 0) return;
#if GC_GRAM_HAS_VECTOR
    if (__builtin_cpu_supports("avx2") && gc_gram_vector(m, n, a, product)) return;
#endif
    gc_gram_scalar(m, n, a, product);
}
