/* The anchor of the output benchmark (bench/bench_output_mod.f90): write the same rows as the
 * benchmark, N rows of five numbers, with printf("%.16e") the way a C program would, and print
 * the wall-clock seconds of the whole job (open, format, write, close) on standard output.
 *
 *     printf_rows FILE [N]        (N = 200000 by default)
 */
#define _POSIX_C_SOURCE 199309L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

/* Row n of the benchmark's table; the Fortran benchmark computes the same values. */
static void row(long n, double v[5])
{
    double t = n * 1.0e-5;
    v[0] = t;
    v[1] = 1.0e-3 * sin(100.0 * t);
    v[2] = 2.0e-4 * cos(37.0 * t);
    v[3] = 3000.0 + 500.0 * sin(50.0 * t);
    v[4] = 1.0e-3 * cos(10.0 * t) - 5.0e-4;
}

int main(int argc, char **argv)
{
    struct timespec start, finish;
    long n, rows = 200000;
    double v[5];
    FILE *file;

    if (argc < 2) {
        fprintf(stderr, "usage: printf_rows FILE [ROWS]\n");
        return 2;
    }
    if (argc > 2) rows = atol(argv[2]);
    clock_gettime(CLOCK_MONOTONIC, &start);
    file = fopen(argv[1], "w");
    if (file == NULL) {
        perror(argv[1]);
        return 1;
    }
    for (n = 0; n < rows; n++) {
        row(n, v);
        fprintf(file, "%24.16e%24.16e%24.16e%24.16e%24.16e\n", v[0], v[1], v[2], v[3], v[4]);
    }
    if (fclose(file) != 0) {
        perror(argv[1]);
        return 1;
    }
    clock_gettime(CLOCK_MONOTONIC, &finish);
    printf("%.6f\n", (double)(finish.tv_sec - start.tv_sec) + 1.0e-9 * (double)(finish.tv_nsec - start.tv_nsec));
    return 0;
}
