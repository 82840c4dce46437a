/*
 * c_contact: the SDOF scene of data/sdof_sine.nml (the paper's section 3.1) run from C
 * through the greenconv C API, checked against the files the greenconv driver writes.
 *
 *     c_contact DIR [FRF]
 *
 * DIR holds sdof_sine_direct.dat and sdof_sine_modal.dat from `greenconv data/sdof_sine.nml`
 * (columns t [s], u_road [m], u [m], f_contact [N], delta [m]). The program
 *  1. runs "direct" and "modal" with gc_run_contact (whole run on arrays),
 *  2. steps an "fft" convolver itself with gc_contact_step (the same sum as "direct"),
 *  3. checks three failures: an unknown method, a NULL handle, a missing scene file,
 *  4. given a receptance file FRF (data/sample_receptance.frf: 4 modes), identifies its
 *     modes by LSCE (4 modes, E <= 1e-10 expected) and builds an "exact" convolver on them,
 * and compares u, F and delta with the driver's columns: every value within 1e-12 of the
 * column's largest magnitude (the driver prints 16 significant digits; both run the same
 * loop). It prints the largest differences and exits with status 1 on any mismatch.
 */
#include <greenconv.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define N_STEPS 2000
#define TOLERANCE 1.0e-12

/* The scene of data/sdof_sine.nml, in SI units. */
static const double dt = 1.0e-4;        /* time step [s] */
static const double mass = 1.0;         /* M [kg] */
static const double stiffness = 1.0e6;  /* K [N/m] */
static const double xi = 0.02;          /* damping ratio */
static const double amplitude = 1.0e-3; /* road amplitude A0 [m] */
static const double omega = 100.0;      /* road angular frequency [rad/s] */
static const double k_c = 1.0e6;        /* contact stiffness [N/m^1.5] */
static const double p = 1.5;            /* Hertz exponent */
static const double gravity = 9.81;     /* [m/s^2]: the preload is M*g [N] */

/* Columns u, F, delta of a driver file: returns 0 when the file has N_STEPS rows. */
static int read_reference(const char *path, double *u, double *f, double *delta)
{
    char line[512];
    int n = 0;
    FILE *file = fopen(path, "r");
    if (!file) {
        fprintf(stderr, "c_contact: cannot open %s\n", path);
        return 1;
    }
    while (fgets(line, sizeof line, file)) {
        double t, road;
        if (line[0] == '#') continue;
        if (n >= N_STEPS || sscanf(line, "%lf %lf %lf %lf %lf", &t, &road, &u[n], &f[n], &delta[n]) != 5) {
            fprintf(stderr, "c_contact: %s: unexpected row %d\n", path, n + 1);
            fclose(file);
            return 1;
        }
        n++;
    }
    fclose(file);
    if (n != N_STEPS) fprintf(stderr, "c_contact: %s: %d rows, expected %d\n", path, n, N_STEPS);
    return n != N_STEPS;
}

/* Largest |a - b| relative to max|b|; counts values off by more than TOLERANCE of max|b|. */
static double deviation(const double *a, const double *b, int *failures)
{
    double scale = 0.0, worst = 0.0;
    for (int n = 0; n < N_STEPS; n++) scale = fmax(scale, fabs(b[n]));
    for (int n = 0; n < N_STEPS; n++) {
        double d = fabs(a[n] - b[n]);
        if (!(d <= TOLERANCE * scale)) (*failures)++;
        worst = fmax(worst, d);
    }
    return scale > 0.0 ? worst / scale : worst;
}

/* Compare a run with the driver's file of `method`; returns the number of mismatches. */
static int compare(const char *dir, const char *method, const char *how, const double *u, const double *f,
                   const double *delta)
{
    static double u_ref[N_STEPS], f_ref[N_STEPS], delta_ref[N_STEPS];
    char path[1024];
    int failures = 0;
    snprintf(path, sizeof path, "%s/sdof_sine_%s.dat", dir, method);
    if (read_reference(path, u_ref, f_ref, delta_ref)) return 1;
    double du = deviation(u, u_ref, &failures);
    double df = deviation(f, f_ref, &failures);
    double dd = deviation(delta, delta_ref, &failures);
    printf("c_contact: %-30s vs driver %-6s: max|du| = %.1e, max|dF| = %.1e, max|d delta| = %.1e "
           "(of max|.|; tolerance %.0e): %s\n", how, method, du, df, dd, TOLERANCE, failures ? "MISMATCH" : "ok");
    return failures;
}

/* A receptance file of 4 modes: its modes and E by LSCE, and an "exact" convolver on the modes
 * gc_convolver_new_frf_file identifies (maximum likelihood, as a scene's frf_file model). */
static int identify(const char *frf)
{
    double pole_re[8], pole_im[8], residue_re[8], residue_im[8], e = 1.0;
    char message[256], text[256];
    int n_modes = 0, failures = 0;
    gc_convolver *conv = NULL;

    if (gc_identify_frf_file(frf, 1.0e-6, 20, 8, &n_modes, pole_re, pole_im, residue_re, residue_im, &e, message,
                             sizeof message) != GC_OK) {
        fprintf(stderr, "c_contact: %s\n", message);
        return 1;
    }
    printf("c_contact: %s: %d modes, E = %.1e, at", frf, n_modes, e);
    for (int k = 0; k < n_modes; k++) {
        printf(" %.2f Hz", hypot(pole_re[k], pole_im[k]) / (2.0 * acos(-1.0)));
        if (!(pole_re[k] < 0.0 && pole_im[k] > 0.0)) failures++;
    }
    printf("\n");
    if (n_modes != 4 || !(e <= 1.0e-10)) failures++;
    if (gc_convolver_new_frf_file(frf, dt, "exact", N_STEPS, 1.0e-6, 20, &conv, message, sizeof message) != GC_OK) {
        fprintf(stderr, "c_contact: %s\n", message);
        return failures + 1;
    }
    gc_convolver_describe(conv, text, sizeof text);
    printf("c_contact: %s\n", text);
    gc_convolver_delete(&conv);
    return failures;
}

int main(int argc, char **argv)
{
    static double road[N_STEPS], u[N_STEPS], f[N_STEPS], delta[N_STEPS];
    const char *methods[2] = {"direct", "modal"};
    char message[256], text[256];
    gc_convolver *conv = NULL;
    int failures = 0;

    if (argc != 2 && argc != 3) {
        fprintf(stderr, "usage: c_contact DIR [FRF]   (DIR: the driver's output for data/sdof_sine.nml)\n");
        return 2;
    }
    for (int n = 0; n < N_STEPS; n++) road[n] = amplitude * sin(omega * (n * dt));

    /* 1. Whole runs on arrays. */
    for (int i = 0; i < 2; i++) {
        if (gc_convolver_new_sdof(mass, stiffness, xi, dt, methods[i], N_STEPS, &conv, message, sizeof message)
            != GC_OK) {
            fprintf(stderr, "c_contact: %s\n", message);
            return 1;
        }
        gc_convolver_describe(conv, text, sizeof text);
        printf("c_contact: %s\n", text);
        if (gc_run_contact(conv, k_c, p, mass * gravity, N_STEPS, road, u, f, delta, message, sizeof message)
            != GC_OK) {
            fprintf(stderr, "c_contact: %s\n", message);
            return 1;
        }
        failures += compare(argv[1], methods[i], "gc_run_contact", u, f, delta);
        gc_convolver_delete(&conv);
    }

    /* 2. An fft convolver stepped by the caller, one contact step at a time. */
    if (gc_convolver_new_sdof(mass, stiffness, xi, dt, "fft", N_STEPS, &conv, message, sizeof message) != GC_OK) {
        fprintf(stderr, "c_contact: %s\n", message);
        return 1;
    }
    for (int n = 0; n < N_STEPS; n++) {
        if (gc_contact_step(conv, k_c, p, mass * gravity, road[n], &u[n], &f[n], &delta[n]) != GC_OK) {
            fprintf(stderr, "c_contact: gc_contact_step failed at step %d\n", n);
            return 1;
        }
    }
    gc_convolver_delete(&conv);
    failures += compare(argv[1], "direct", "fft, gc_contact_step", u, f, delta);

    /* 3. Failures come back as status codes and messages. */
    int status = gc_convolver_new_sdof(mass, stiffness, xi, dt, "spline", N_STEPS, &conv, message, sizeof message);
    printf("c_contact: unknown method -> status %d, conv %s, \"%s\"\n", status, conv ? "set" : "NULL", message);
    if (status != GC_ERROR_INPUT || conv != NULL || strstr(message, "spline") == NULL) failures++;
    double displacement;
    status = gc_convolver_history(NULL, &displacement);
    printf("c_contact: NULL handle -> status %d\n", status);
    if (status != GC_ERROR_INPUT) failures++;
    status = gc_run_scene("no/such/scene.nml", message, sizeof message);
    printf("c_contact: missing scene -> status %d, \"%s\"\n", status, message);
    if (status != GC_ERROR_INPUT || strstr(message, "cannot open") == NULL) failures++;

    /* 4. Modes identified from a receptance file. */
    if (argc == 3) failures += identify(argv[2]);

    printf("c_contact: %s\n", failures ? "FAILED" : "all checks passed");
    return failures ? 1 : 0;
}
