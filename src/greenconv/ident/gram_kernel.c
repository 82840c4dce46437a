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
 * the packed columns, the scalar kernel takes the same sums, columns four by
 * four, sixteen sums over the rows together.  On a CPU with AVX-512 a third kernel packs
 * sixteen columns j and takes eight doubles per instruction, again one lane per element and
 * the rows in order: the same bits at up to twice the speed.
 *
 * A^T b (greenconv_ident_gram_projection) takes each column's dot product in the order of
 * dense.f90's `dot`: four partial sums over the rows r = 0, 4, 8, ... (and 1, 2, 3 on), added
 * as (s0 + s1) + (s2 + s3), then the remaining rows one by one; the four partial sums are the
 * four lanes of one vector.
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
#define GC_GRAM_AVX512 __attribute__((target("avx512f")))
#else
#define GC_GRAM_HAS_VECTOR 0
#define GC_GRAM_AVX2
#define GC_GRAM_AVX512
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
/* A vector kernel, with the same sums as gc_gram_scalar: 2*LANES columns j packed row by row,
 * four columns i against them, eight LANES-wide sums.  The rows are taken in chunks whose
 * packed columns stay in the core's cache (the 16,386 rows of a 50-mode fit packed sixteen
 * wide are 2 MB); each element's sum is kept in `product` from one chunk to the next, so it
 * still adds the rows in order into one accumulator.  0 without the memory for the chunk. */
#define GC_GRAM_VECTOR_KERNEL(NAME, VECTOR, LANES, TARGET)                                              \
    GC_GRAM_OPTIMIZE TARGET static int NAME(int m, int n, const double *a, double *product)            \
    {                                                                                                   \
        enum { chunk = 2048, width = 2 * (LANES) };                                                     \
        double *packed = malloc(sizeof(double) * width * chunk);                                       \
        if (packed == NULL) return 0;                                                                   \
        for (int j = 0; j < n; j++)                                                                     \
            for (int i = 0; i <= j; i++) product[(size_t)i + (size_t)j * (size_t)n] = 0.0;             \
        for (int jb = 0; jb < n; jb += width) {                                                         \
            int width_j = n - jb < width ? n - jb : width;                                              \
            for (int rb = 0; rb < m; rb += chunk) {                                                     \
                int rows = m - rb < chunk ? m - rb : chunk;                                             \
                for (int r = 0; r < rows; r++)                                                          \
                    for (int q = 0; q < width; q++)                                                     \
                        packed[(size_t)r * width + (size_t)q] =                                         \
                            q < width_j ? a[(size_t)(rb + r) + (size_t)(jb + q) * (size_t)m] : 0.0;     \
                for (int ib = 0; ib < jb + width_j; ib += 4) {                                          \
                    int width_i = n - ib < 4 ? n - ib : 4;                                              \
                    const double *ci[4];                                                                \
                    for (int p = 0; p < 4; p++)                                                         \
                        ci[p] = a + (size_t)rb + (size_t)(ib + (p < width_i ? p : width_i - 1)) * (size_t)m; \
                    double s[4][width];                                                                 \
                    for (int p = 0; p < 4; p++)                                                         \
                        for (int q = 0; q < width; q++)                                                 \
                            s[p][q] = (p < width_i && q < width_j && ib + p <= jb + q)                  \
                                          ? product[(size_t)(ib + p) + (size_t)(jb + q) * (size_t)n]    \
                                          : 0.0;                                                        \
                    VECTOR s0[2], s1[2], s2[2], s3[2];                                                  \
                    memcpy(s0, s[0], sizeof s0); memcpy(s1, s[1], sizeof s1);                           \
                    memcpy(s2, s[2], sizeof s2); memcpy(s3, s[3], sizeof s3);                           \
                    for (int r = 0; r < rows; r++) {                                                    \
                        VECTOR y0, y1;                                                                  \
                        memcpy(&y0, packed + (size_t)r * width, sizeof y0);                             \
                        memcpy(&y1, packed + (size_t)r * width + (LANES), sizeof y1);                   \
                        double x0 = ci[0][r], x1 = ci[1][r], x2 = ci[2][r], x3 = ci[3][r];              \
                        s0[0] += x0 * y0; s0[1] += x0 * y1;                                             \
                        s1[0] += x1 * y0; s1[1] += x1 * y1;                                             \
                        s2[0] += x2 * y0; s2[1] += x2 * y1;                                             \
                        s3[0] += x3 * y0; s3[1] += x3 * y1;                                             \
                    }                                                                                   \
                    memcpy(s[0], s0, sizeof s0); memcpy(s[1], s1, sizeof s1);                           \
                    memcpy(s[2], s2, sizeof s2); memcpy(s[3], s3, sizeof s3);                           \
                    for (int q = 0; q < width_j; q++)                                                   \
                        for (int p = 0; p < width_i; p++)                                               \
                            if (ib + p <= jb + q)                                                       \
                                product[(size_t)(ib + p) + (size_t)(jb + q) * (size_t)n] = s[p][q];     \
                }                                                                                       \
            }                                                                                           \
        }                                                                                               \
        free(packed);                                                                                   \
        return 1;                                                                                       \
    }

/* Four and eight doubles. */
typedef double gc_v4 __attribute__((vector_size(32)));
typedef double gc_v8 __attribute__((vector_size(64)));

/* AVX2: eight columns j against four, 4-wide sums. */
GC_GRAM_VECTOR_KERNEL(gc_gram_vector, gc_v4, 4, GC_GRAM_AVX2)
/* AVX-512: sixteen columns j against four, 8-wide sums. */
GC_GRAM_VECTOR_KERNEL(gc_gram_vector512, gc_v8, 8, GC_GRAM_AVX512)
#endif

/* The upper triangle (i <= j) of A^T A for a column-major m x n matrix a, written into the
 * column-major n x n matrix product; the strict lower triangle is not touched. */
static void greenconv_ident_gram_upper(int m, int n, const double *a, double *product)
{
    if (n <= 0) return;
#if GC_GRAM_HAS_VECTOR
    if (__builtin_cpu_supports("avx512f") && gc_gram_vector512(m, n, a, product)) return;
    if (__builtin_cpu_supports("avx2") && gc_gram_vector(m, n, a, product)) return;
#endif
    gc_gram_scalar(m, n, a, product);
}

/* A^T b for a column-major m x n matrix a: projection[j] is column j's dot product with b, its
 * four partial sums (rows 0, 4, 8, ...; 1, 5, 9, ...; ...) the four lanes of one vector
 * (SSE2, in every x86-64 build; the same sums in any build), added as (s0 + s1) + (s2 + s3),
 * then the rows after the last multiple of four one by one: dense.f90's `dot`. */
GC_GRAM_OPTIMIZE
static void greenconv_ident_gram_projection(int m, int n, const double *a, const double *b, double *projection)
{
    typedef double gc_v2 __attribute__((vector_size(16)));
    int body = m - m % 4;
    for (int j = 0; j < n; j++) {
        const double *x = a + (size_t)j * (size_t)m;
        gc_v2 low = {0.0, 0.0}, high = {0.0, 0.0};
        for (int r = 0; r < body; r += 4) {
            gc_v2 x0, x1, y0, y1;
            memcpy(&x0, x + r, sizeof x0);
            memcpy(&x1, x + r + 2, sizeof x1);
            memcpy(&y0, b + r, sizeof y0);
            memcpy(&y1, b + r + 2, sizeof y1);
            low += x0 * y0;
            high += x1 * y1;
        }
        double sum = (low[0] + low[1]) + (high[0] + high[1]);
        for (int r = body; r < m; r++) sum += x[r] * b[r];
        projection[j] = sum;
    }
}

/* dense.f90's `gram`: the upper triangle of A^T A into product (n x n, the strict lower
 * triangle not touched) and A^T b into projection (n), for a column-major m x n matrix a. */
void greenconv_ident_gram(int m, int n, const double *a, const double *b, double *product, double *projection)
{
    greenconv_ident_gram_upper(m, n, a, product);
    greenconv_ident_gram_projection(m, n, a, b, projection);
}
