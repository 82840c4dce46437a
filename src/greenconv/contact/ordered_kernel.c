/* The products of the implicit step's low-rank solve (src/greenconv/contact/lowrank_solve.f90)
 * in one fixed order of summation whatever the build and the CPU.
 *
 * greenconv_contact_ordered_rows: y = A(first.., :)*x for m rows of a column-major matrix of
 * leading dimension lda, each y_i = (((0 + a_i1*x_1) + a_i2*x_2) + ...) + a_in*x_n, the order
 * of MATMUL's sum.  Each vector lane holds one y_i, so the vector width changes the speed and
 * not the order: a lane adds a_ij*x_j (rounded) to its sum exactly as a scalar loop does.  GCC
 * contracts a*b + c into a fused multiply-add only when told it may; the functions ask for
 * fp-contract=off, so no build contracts, and a CPU with FMA gives the bits of one without.
 *
 * greenconv_contact_ordered_rows_many: the same products for several vectors x, the matrix read
 * once for four of them (the sums are those of greenconv_contact_ordered_rows, vector by vector).
 *
 * greenconv_contact_symmetric_updates: M^-1 <- M^-1 - sum_p c_p*(x_p*x_p^T), p = 1..d, in one
 * pass over M^-1, each entry ((inv_lk - c_1*(x_l1*x_k1)) - c_2*(x_l2*x_k2)) - ..., the bits of d
 * rank-one updates one after the other; (l, k) and (k, l) get the same bits (x_l*x_k = x_k*x_l).
 *
 * The vector kernels are compiled for AVX2 (four doubles per instruction) and AVX-512 (eight)
 * and taken when the CPU has them; otherwise SSE2's two doubles (every x86-64), and on other
 * processors the plain loops, take the same sums.  Why C:
 * the library's Fortran is built for the baseline x86-64 (two doubles per instruction), and a
 * GCC function attribute asks for a wider target here alone, chosen when the program runs.
 */
#include <stddef.h>
#include <string.h>

#if defined(__GNUC__) && !defined(__clang__)
#define GC_ORDERED_OPTIMIZE __attribute__((optimize("O2", "fp-contract=off")))
#else
#define GC_ORDERED_OPTIMIZE
#endif
#if defined(__GNUC__) && defined(__x86_64__)
#define GC_ORDERED_HAS_VECTOR 1
#define GC_ORDERED_AVX2 __attribute__((target("avx2")))
#define GC_ORDERED_AVX512 __attribute__((target("avx512f")))
#else
#define GC_ORDERED_HAS_VECTOR 0
#define GC_ORDERED_AVX2
#define GC_ORDERED_AVX512
#endif

/* y(0:m-1) = A*x by plain loops, the columns four a pass. */
GC_ORDERED_OPTIMIZE static void gc_rows_scalar(int m, int n, int lda, const double *restrict a,
                                               const double *restrict x, double *restrict y)
{
    size_t ld = (size_t)lda;
    int n4 = n - n % 4;
    for (int i = 0; i < m; i++) y[i] = 0.0;
    for (int j = 0; j < n4; j += 4) {
        const double *a0 = a + (size_t)j * ld, *a1 = a0 + ld, *a2 = a1 + ld, *a3 = a2 + ld;
        double x0 = x[j], x1 = x[j + 1], x2 = x[j + 2], x3 = x[j + 3];
        for (int i = 0; i < m; i++) {
            double partial = y[i] + a0[i] * x0;
            partial = partial + a1[i] * x1;
            partial = partial + a2[i] * x2;
            y[i] = partial + a3[i] * x3;
        }
    }
    for (int j = n4; j < n; j++) {
        const double *a0 = a + (size_t)j * ld;
        for (int i = 0; i < m; i++) y[i] = y[i] + a0[i] * x[j];
    }
}

/* The four vectors' products by plain loops, one after the other. */
GC_ORDERED_OPTIMIZE static void gc_rows_four_scalar(int m, int n, int lda, const double *restrict a,
                                                    const double *restrict x, int ldx, double *restrict y, int ldy)
{
    for (int v = 0; v < 4; v++) gc_rows_scalar(m, n, lda, a, x + (size_t)v * (size_t)ldx, y + (size_t)v * (size_t)ldy);
}

/* inv -= sum_p c_p*(x_p*x_p^T), p = 1..d in order, by plain loops, column by column. */
GC_ORDERED_OPTIMIZE static void gc_updates_scalar(int r, int ld, double *restrict inv, int d, int ldx,
                                                  const double *restrict x, const double *restrict c)
{
    for (int k = 0; k < r; k++) {
        double *column = inv + (size_t)k * (size_t)ld;
        for (int l = 0; l < r; l++) {
            double entry = column[l];
            for (int p = 0; p < d; p++) {
                const double *xp = x + (size_t)p * (size_t)ldx;
                entry = entry - c[p] * (xp[l] * xp[k]);
            }
            column[l] = entry;
        }
    }
}

#if GC_ORDERED_HAS_VECTOR
/* The same sums with LANES rows in the lanes of one vector: four vectors of rows at a time
 * (four independent sums in flight), then one, each block's sums held in registers over all
 * the columns; the rows after the last multiple of LANES by the next narrower kernel (TAIL),
 * down to the plain loop. */
#define GC_ORDERED_ROWS_KERNEL(NAME, VECTOR, LANES, TARGET, TAIL)                                   \
    GC_ORDERED_OPTIMIZE TARGET static void NAME(int m, int n, int lda, const double *restrict a,   \
                                               const double *restrict x, double *restrict y)       \
    {                                                                                               \
        size_t ld = (size_t)lda;                                                                    \
        int i = 0;                                                                                  \
        for (; i + 4 * (LANES) <= m; i += 4 * (LANES)) {                                            \
            VECTOR s0 = {0.0}, s1 = {0.0}, s2 = {0.0}, s3 = {0.0}, c0, c1, c2, c3;                  \
            for (int j = 0; j < n; j++) {                                                           \
                const double *column = a + (size_t)i + (size_t)j * ld;                              \
                double xj = x[j];                                                                   \
                memcpy(&c0, column, sizeof c0);                                                     \
                memcpy(&c1, column + (LANES), sizeof c1);                                           \
                memcpy(&c2, column + 2 * (LANES), sizeof c2);                                       \
                memcpy(&c3, column + 3 * (LANES), sizeof c3);                                       \
                s0 = s0 + c0 * xj;                                                                  \
                s1 = s1 + c1 * xj;                                                                  \
                s2 = s2 + c2 * xj;                                                                  \
                s3 = s3 + c3 * xj;                                                                  \
            }                                                                                       \
            memcpy(y + i, &s0, sizeof s0);                                                          \
            memcpy(y + i + (LANES), &s1, sizeof s1);                                                \
            memcpy(y + i + 2 * (LANES), &s2, sizeof s2);                                            \
            memcpy(y + i + 3 * (LANES), &s3, sizeof s3);                                            \
        }                                                                                           \
        for (; i + (LANES) <= m; i += (LANES)) {                                                    \
            VECTOR sum = {0.0}, column;                                                             \
            for (int j = 0; j < n; j++) {                                                           \
                memcpy(&column, a + (size_t)i + (size_t)j * ld, sizeof column);                     \
                sum = sum + column * x[j];                                                          \
            }                                                                                       \
            memcpy(y + i, &sum, sizeof sum);                                                        \
        }                                                                                           \
        if (i < m) TAIL(m - i, n, lda, a + i, x, y + i);                                            \
    }

/* y_v = A*x_v for four vectors at once, LANES rows a vector register: each column of A is read
 * once for the four sums; the rows after the last multiple of LANES by the next narrower
 * kernel (TAIL), down to the plain loops. */
#define GC_ORDERED_ROWS_FOUR_KERNEL(NAME, VECTOR, LANES, TARGET, TAIL)                              \
    GC_ORDERED_OPTIMIZE TARGET static void NAME(int m, int n, int lda, const double *restrict a,   \
                                               const double *restrict x, int ldx, double *restrict y, \
                                               int ldy)                                             \
    {                                                                                               \
        size_t ld = (size_t)lda, sx = (size_t)ldx, sy = (size_t)ldy;                                \
        int i = 0;                                                                                  \
        for (; i + (LANES) <= m; i += (LANES)) {                                                    \
            VECTOR s0 = {0.0}, s1 = {0.0}, s2 = {0.0}, s3 = {0.0}, column;                          \
            for (int j = 0; j < n; j++) {                                                           \
                memcpy(&column, a + (size_t)i + (size_t)j * ld, sizeof column);                     \
                s0 = s0 + column * x[j];                                                            \
                s1 = s1 + column * x[sx + (size_t)j];                                               \
                s2 = s2 + column * x[2 * sx + (size_t)j];                                           \
                s3 = s3 + column * x[3 * sx + (size_t)j];                                           \
            }                                                                                       \
            memcpy(y + i, &s0, sizeof s0);                                                          \
            memcpy(y + sy + i, &s1, sizeof s1);                                                     \
            memcpy(y + 2 * sy + i, &s2, sizeof s2);                                                 \
            memcpy(y + 3 * sy + i, &s3, sizeof s3);                                                 \
        }                                                                                           \
        if (i < m) TAIL(m - i, n, lda, a + i, x, ldx, y + i, ldy);                                  \
    }

/* inv -= sum_p c_p*(x_p*x_p^T) in one pass, LANES entries of a column a vector. */
#define GC_ORDERED_UPDATES_KERNEL(NAME, VECTOR, LANES, TARGET)                                      \
    GC_ORDERED_OPTIMIZE TARGET static void NAME(int r, int ld, double *restrict inv, int d, int ldx, \
                                               const double *restrict x, const double *restrict c) \
    {                                                                                               \
        int body = r - r % (LANES);                                                                 \
        size_t sx = (size_t)ldx;                                                                    \
        for (int k = 0; k < r; k++) {                                                               \
            double *column = inv + (size_t)k * (size_t)ld;                                          \
            VECTOR entries, values;                                                                 \
            for (int l = 0; l < body; l += (LANES)) {                                               \
                memcpy(&entries, column + l, sizeof entries);                                       \
                for (int p = 0; p < d; p++) {                                                       \
                    memcpy(&values, x + (size_t)p * sx + (size_t)l, sizeof values);                 \
                    entries = entries - c[p] * (values * x[(size_t)p * sx + (size_t)k]);            \
                }                                                                                   \
                memcpy(column + l, &entries, sizeof entries);                                       \
            }                                                                                       \
            for (int l = body; l < r; l++) {                                                        \
                double entry = column[l];                                                           \
                for (int p = 0; p < d; p++)                                                         \
                    entry = entry - c[p] * (x[(size_t)p * sx + (size_t)l] * x[(size_t)p * sx + (size_t)k]); \
                column[l] = entry;                                                                  \
            }                                                                                       \
        }                                                                                           \
    }

/* Two (SSE2, in every x86-64 build), four and eight doubles. */
typedef double gc_ordered_v2 __attribute__((vector_size(16)));
typedef double gc_ordered_v4 __attribute__((vector_size(32)));
typedef double gc_ordered_v8 __attribute__((vector_size(64)));

GC_ORDERED_ROWS_KERNEL(gc_rows_sse2, gc_ordered_v2, 2, , gc_rows_scalar)
GC_ORDERED_ROWS_KERNEL(gc_rows_avx2, gc_ordered_v4, 4, GC_ORDERED_AVX2, gc_rows_sse2)
GC_ORDERED_ROWS_KERNEL(gc_rows_avx512, gc_ordered_v8, 8, GC_ORDERED_AVX512, gc_rows_avx2)
GC_ORDERED_ROWS_FOUR_KERNEL(gc_rows_four_sse2, gc_ordered_v2, 2, , gc_rows_four_scalar)
GC_ORDERED_ROWS_FOUR_KERNEL(gc_rows_four_avx2, gc_ordered_v4, 4, GC_ORDERED_AVX2, gc_rows_four_sse2)
GC_ORDERED_ROWS_FOUR_KERNEL(gc_rows_four_avx512, gc_ordered_v8, 8, GC_ORDERED_AVX512, gc_rows_four_avx2)
GC_ORDERED_UPDATES_KERNEL(gc_updates_sse2, gc_ordered_v2, 2, )
GC_ORDERED_UPDATES_KERNEL(gc_updates_avx2, gc_ordered_v4, 4, GC_ORDERED_AVX2)
GC_ORDERED_UPDATES_KERNEL(gc_updates_avx512, gc_ordered_v8, 8, GC_ORDERED_AVX512)
#endif

/* The widest kernel the CPU runs: 2 AVX-512, 1 AVX2, 0 neither. */
static int gc_ordered_width(void)
{
#if GC_ORDERED_HAS_VECTOR
    if (__builtin_cpu_supports("avx512f")) return 2;
    if (__builtin_cpu_supports("avx2")) return 1;
#endif
    return 0;
}

/* y(0:m-1) = A*x for the m x n matrix at a (column-major, leading dimension lda >= m). */
void greenconv_contact_ordered_rows(int m, int n, int lda, const double *a, const double *x, double *y)
{
    if (m <= 0) return;
#if GC_ORDERED_HAS_VECTOR
    switch (gc_ordered_width()) {
    case 2: gc_rows_avx512(m, n, lda, a, x, y); return;
    case 1: gc_rows_avx2(m, n, lda, a, x, y); return;
    default: gc_rows_sse2(m, n, lda, a, x, y); return;
    }
#endif
    gc_rows_scalar(m, n, lda, a, x, y);
}

/* y(:, v) = A*x(:, v) for v = 1..nv: x (n x nv, leading dimension ldx), y (m x nv, leading
 * dimension ldy); four vectors a pass over A, the others one by one. */
void greenconv_contact_ordered_rows_many(int m, int n, int lda, const double *a, int nv, int ldx, const double *x,
                                         int ldy, double *y)
{
    if (m <= 0) return;
    int v = 0;
#if GC_ORDERED_HAS_VECTOR
    int width = gc_ordered_width();
    for (; v + 4 <= nv; v += 4) {
        const double *xv = x + (size_t)v * (size_t)ldx;
        double *yv = y + (size_t)v * (size_t)ldy;
        switch (width) {
        case 2: gc_rows_four_avx512(m, n, lda, a, xv, ldx, yv, ldy); break;
        case 1: gc_rows_four_avx2(m, n, lda, a, xv, ldx, yv, ldy); break;
        default: gc_rows_four_sse2(m, n, lda, a, xv, ldx, yv, ldy); break;
        }
    }
#endif
    for (; v < nv; v++)
        greenconv_contact_ordered_rows(m, n, lda, a, x + (size_t)v * (size_t)ldx, y + (size_t)v * (size_t)ldy);
}

/* inv -= sum_p c_p*(x_p*x_p^T), p = 1..d in order, for the r x r matrix at inv (leading
 * dimension ld >= r); x_p the columns of x (r x d, leading dimension ldx). */
void greenconv_contact_symmetric_updates(int r, int ld, double *inv, int d, int ldx, const double *x, const double *c)
{
    if (r <= 0 || d <= 0) return;
#if GC_ORDERED_HAS_VECTOR
    switch (gc_ordered_width()) {
    case 2: gc_updates_avx512(r, ld, inv, d, ldx, x, c); return;
    case 1: gc_updates_avx2(r, ld, inv, d, ldx, x, c); return;
    default: gc_updates_sse2(r, ld, inv, d, ldx, x, c); return;
    }
#endif
    gc_updates_scalar(r, ld, inv, d, ldx, x, c);
}
