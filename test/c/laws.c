/*
 * laws.c - the contact law object of the C API (gc_law): made by name from the registry,
 * refused for a bad name, count or parameter (status 2, the message naming what is wrong),
 * evaluated by gc_law_force and gc_law_compression against the closed forms, and given to the
 * contact doors. The (k_c, p) doors equal the `_law` doors on the power law bit for bit,
 * single- and multi-point; a run on the exponential law equals the Fortran driver's run of
 * the same scene (&contact law = 'exponential') to the 16 digits it prints, and the
 * multi-point door refuses two different laws at two points.
 */
#include <greenconv.h>

#include <math.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>

#include "check.h"

#define N_STEPS 1500
#define SCENE_DIR "build/ctest/laws_scene"

static const double dt = 1.0e-4, mass = 1.0, stiffness = 1.0e6, xi = 0.02, preload = 9.81;
static const double f_s = 5.0, delta_s = 2.0e-4; /* the exponential law: F_s [N], delta_s [m] */

/* Largest |a - b| over n values, relative to max |b|. */
static double deviation(const double *a, const double *b, int n)
{
    double scale = 0.0, worst = 0.0;
    for (int i = 0; i < n; i++) scale = fmax(scale, fabs(b[i]));
    for (int i = 0; i < n; i++) worst = fmax(worst, fabs(a[i] - b[i]));
    return scale > 0.0 ? worst / scale : worst;
}

static void test_new_and_refusals(void)
{
    char msg[400];
    gc_law *law = (gc_law *)&msg; /* not NULL: a refusal must set it to NULL */
    const double power[2] = {1.0e6, 1.5}, bad_scale[2] = {f_s, -2.0e-4}, one[1] = {1.0};
    double force = -1.0, compression = -1.0;
    int status;

    status = gc_law_new("hertz", power, 2, &law, msg, sizeof msg);
    check_status(status, GC_ERROR_INPUT, msg, "'hertz'", "unknown law: status 2, names it");
    check(law == NULL && strstr(msg, "'power'") && strstr(msg, "'exponential'"), "unknown law: NULL, lists the laws",
          msg);
    status = gc_law_new("exponential", bad_scale, 2, &law, msg, sizeof msg);
    check_status(status, GC_ERROR_INPUT, msg, "delta_s [m]", "delta_s < 0: status 2, names delta_s and its unit");
    check(law == NULL && strstr(msg, "> 0") && strstr(msg, "-2.00E-04"), "delta_s < 0: range and value", msg);
    status = gc_law_new("exponential", one, 1, &law, msg, sizeof msg);
    check_status(status, GC_ERROR_INPUT, msg, "expected 2 parameters", "one value for two: status 2");
    status = gc_law_new(NULL, power, 2, &law, msg, sizeof msg);
    check_status(status, GC_ERROR_INPUT, msg, "name", "NULL name: status 2");
    status = gc_law_new("power", NULL, 2, &law, msg, sizeof msg);
    check_status(status, GC_ERROR_INPUT, msg, "parameters", "NULL parameters: status 2");

    status = gc_law_new("power", power, 2, &law, msg, sizeof msg);
    check_status(status, GC_OK, msg, NULL, "power law made");
    status = gc_law_force(law, 4.0e-4, &force);
    check(status == GC_OK && fabs(force - 1.0e6 * 4.0e-4 * sqrt(4.0e-4)) <= 1e-15 * force, "power: F = k_c*delta^1.5",
          NULL);
    status = gc_law_compression(law, preload, &compression);
    check(status == GC_OK && fabs(compression - pow(preload / 1.0e6, 1.0 / 1.5)) <= 1e-15 * compression,
          "power: compression (F0/k_c)^(1/p)", NULL);
    check(gc_law_compression(law, -1.0, &compression) == GC_ERROR_INPUT, "compression of F < 0: status 2", NULL);
    check(gc_law_force(NULL, 1.0e-4, &force) == GC_ERROR_INPUT && gc_law_force(law, 1.0e-4, NULL) == GC_ERROR_INPUT,
          "NULL law or output: status 2", NULL);
    gc_law_free(law);
    gc_law_free(NULL);

    const double exponential[2] = {f_s, delta_s};
    status = gc_law_new("exponential", exponential, 2, &law, msg, sizeof msg);
    check_status(status, GC_OK, msg, NULL, "exponential law made");
    gc_law_force(law, 3.0e-4, &force);
    gc_law_compression(law, preload, &compression);
    check(fabs(force - f_s * expm1(3.0e-4 / delta_s)) <= 4e-16 * force &&
              fabs(compression - delta_s * log1p(preload / f_s)) <= 4e-16 * compression,
          "exponential: F = F_s*expm1(delta/delta_s), compression delta_s*log1p(F/F_s) (C's libm)", NULL);
    gc_law_force(law, -1.0e-6, &force);
    check(force == 0.0, "exponential: no force in tension", NULL);
    gc_law_free(law);
}

/* The (k_c, p) doors against the `_law` doors on the same power law: the same bits. */
static void test_power_doors_equal(void)
{
    char msg[400];
    gc_convolver *conv = NULL;
    gc_law *law = NULL;
    const double power[2] = {2.0e6, 1.5};
    double road[N_STEPS], u[2][N_STEPS], f[2][N_STEPS], d[2][N_STEPS];
    int status, same;

    for (int n = 0; n < N_STEPS; n++) road[n] = 1.0e-4 * sin(300.0 * n * dt);
    status = gc_convolver_new_sdof(mass, stiffness, xi, dt, "exact", N_STEPS, &conv, msg, sizeof msg);
    status |= gc_law_new("power", power, 2, &law, msg, sizeof msg);
    status |= gc_run_contact(conv, power[0], power[1], preload, N_STEPS, road, u[0], f[0], d[0], msg, sizeof msg);
    status |= gc_run_contact_law(conv, law, preload, N_STEPS, road, NULL, u[1], f[1], d[1], msg, sizeof msg);
    same = memcmp(u[0], u[1], sizeof u[0]) == 0 && memcmp(f[0], f[1], sizeof f[0]) == 0 &&
           memcmp(d[0], d[1], sizeof d[0]) == 0;
    check(status == GC_OK && same, "gc_run_contact equals gc_run_contact_law on the power law bit for bit", msg);

    status = gc_contact_start_law(conv, law, preload, NULL, msg, sizeof msg);
    same = 1;
    for (int n = 0; n < N_STEPS && status == GC_OK; n++) {
        double un, fn, dn;
        status = gc_contact_advance(conv, road[n], &un, &fn, &dn, msg, sizeof msg);
        same = same && un == u[1][n] && fn == f[1][n] && dn == d[1][n];
    }
    check(status == GC_OK && same, "gc_contact_start_law stepped equals the whole run bit for bit", msg);

    /* gc_contact_step and gc_contact_step_law from two resets */
    double us[2][50], fs[2][50];
    status = gc_convolver_reset(conv);
    for (int n = 0; n < 50; n++) status |= gc_contact_step(conv, power[0], power[1], preload, road[n], &us[0][n],
                                                         &fs[0][n], NULL);
    gc_convolver_reset(conv);
    for (int n = 0; n < 50; n++) status |= gc_contact_step_law(conv, law, preload, road[n], &us[1][n], &fs[1][n], NULL);
    same = memcmp(us[0], us[1], sizeof us[0]) == 0 && memcmp(fs[0], fs[1], sizeof fs[0]) == 0;
    check(status == GC_OK && same, "gc_contact_step equals gc_contact_step_law bit for bit", NULL);

    status = gc_run_contact(conv, -1.0, 1.5, preload, N_STEPS, road, u[0], f[0], NULL, msg, sizeof msg);
    check_status(status, GC_ERROR_INPUT, msg, "gc_run_contact: contact: the stiffness k_c",
                 "gc_run_contact k_c < 0: the message names the door and k_c as before");
    status = gc_contact_start(conv, 1.0e6, 0.0, preload, NULL, msg, sizeof msg);
    check_status(status, GC_ERROR_INPUT, msg, "the exponent p", "gc_contact_start p = 0: names p as before");
    status = gc_run_contact_law(conv, NULL, preload, N_STEPS, road, NULL, u[0], f[0], NULL, msg, sizeof msg);
    check_status(status, GC_ERROR_INPUT, msg, "law is NULL", "gc_run_contact_law NULL law: status 2");
    gc_law_free(law);
    gc_convolver_delete(&conv);
}

/* Multi-point: the (k_c, p) doors against the `_law` doors, and one law for every point. */
static void test_multi_doors(void)
{
    enum { NP = 3, NT = 200 };
    char msg[400];
    gc_multi_convolver *conv = NULL;
    const double pole_re[1] = {-0.02 * 1000.0}, pole_im[1] = {1000.0 * sqrt(1.0 - 0.02 * 0.02)};
    const double shape[NP] = {1.0, 0.8, 0.5}, residue_re[1] = {0.0}, residue_im[1] = {-1.0 / (2.0 * pole_im[0])};
    double k_c[NP] = {1.0e6, 2.0e6, 3.0e6}, p_c[NP] = {1.5, 1.5, 1.5};
    double f0[NP] = {3.0, 3.0, 3.0}, road[NP * NT], u[2][NP * NT], f[2][NP * NT];
    gc_law *laws[NP], *other = NULL;
    int status = 0;

    /* one mode of unit modal mass at 1000 rad/s, shaped over three points */
    for (int i = 0; i < NP; i++)
        for (int n = 0; n < NT; n++) road[i * NT + n] = 5.0e-5 * sin(200.0 * n * dt + i);
    status = gc_multi_new_modes(NP, 1, pole_re, pole_im, residue_re, residue_im, shape, dt, "exact", NT, NULL, &conv,
                                msg, sizeof msg);
    check_status(status, GC_OK, msg, NULL, "multi-point convolver made");
    if (status != GC_OK) return;
    for (int i = 0; i < NP; i++) {
        const double values[2] = {k_c[i], p_c[i]};
        status |= gc_law_new("power", values, 2, &laws[i], msg, sizeof msg);
    }
    status |= gc_multi_run_contact(conv, NP, NT, k_c, p_c, f0, road, u[0], f[0], NULL, msg, sizeof msg);
    status |= gc_multi_run_contact_law(conv, NP, NT, (const gc_law *const *)laws, f0, road, u[1], f[1], NULL, msg,
                                       sizeof msg);
    check(status == GC_OK && memcmp(u[0], u[1], sizeof u[0]) == 0 && memcmp(f[0], f[1], sizeof f[0]) == 0,
          "gc_multi_run_contact equals gc_multi_run_contact_law on power laws bit for bit", msg);

    const double exponential[2] = {f_s, delta_s};
    gc_law_new("exponential", exponential, 2, &other, msg, sizeof msg);
    gc_law *mixed[NP] = {laws[0], other, laws[2]};
    status = gc_multi_contact_start_law(conv, NP, (const gc_law *const *)mixed, f0, msg, sizeof msg);
    check_status(status, GC_ERROR_INPUT, msg, "laws[1] is a law 'exponential'", "two laws at two points: status 2");
    gc_law *missing[NP] = {laws[0], NULL, laws[2]};
    status = gc_multi_contact_start_law(conv, NP, (const gc_law *const *)missing, f0, msg, sizeof msg);
    check_status(status, GC_ERROR_INPUT, msg, "laws[1] is NULL", "a NULL law: status 2 naming the point");
    gc_law *shared[NP] = {other, other, other};
    status = gc_multi_contact_start_law(conv, NP, (const gc_law *const *)shared, f0, msg, sizeof msg);
    check_status(status, GC_OK, msg, NULL, "one exponential law shared by every point starts");
    for (int i = 0; i < NP; i++) gc_law_free(laws[i]);
    gc_law_free(other);
    gc_multi_delete(&conv);
}

/* The exponential law from C against the driver's run of the same scene (its 16 digits). */
static void test_exponential_against_driver(void)
{
    char msg[400], line[512];
    double road[N_STEPS], u_ref[N_STEPS], f_ref[N_STEPS], d_ref[N_STEPS], u[N_STEPS], f[N_STEPS], d[N_STEPS];
    const double exponential[2] = {f_s, delta_s};
    gc_convolver *conv = NULL;
    gc_law *law = NULL;
    int status, n = 0;

    mkdir("build", 0777);
    mkdir("build/ctest", 0777);
    mkdir(SCENE_DIR, 0777);
    FILE *file = fopen(SCENE_DIR "/laws.nml", "w");
    if (!file) {
        check(0, "scene file written", SCENE_DIR "/laws.nml");
        return;
    }
    fprintf(file, "&scene name = 'laws', output_dir = '%s', dt = 1.0e-4, n_steps = %d /\n", SCENE_DIR, N_STEPS);
    fprintf(file, "&structure model = 'sdof', mass = 1.0, stiffness = 1.0e6, damping_ratio = 0.02 /\n");
    fprintf(file, "&road profile = 'sine', amplitude = 3.0e-4, omega = 100.0 /\n");
    fprintf(file, "&contact law = 'exponential', law_parameters = 5.0, 2.0e-4, preload = 9.81 /\n");
    fprintf(file, "&convolution methods = 'exact' /\n");
    fclose(file);
    status = gc_run_scene(SCENE_DIR "/laws.nml", msg, sizeof msg);
    check(status == GC_OK || status == GC_ACCURACY, "the driver runs the exponential scene", msg);
    file = fopen(SCENE_DIR "/laws_exact.dat", "r");
    while (file && fgets(line, sizeof line, file)) {
        double t;
        if (line[0] == '#') continue;
        if (n >= N_STEPS || sscanf(line, "%lf %lf %lf %lf %lf", &t, &road[n], &u_ref[n], &f_ref[n], &d_ref[n]) != 5)
            break;
        n++;
    }
    if (file) fclose(file);
    check(n == N_STEPS, "the driver's file has a row a step", SCENE_DIR "/laws_exact.dat");
    if (n != N_STEPS) return;

    status = gc_convolver_new_sdof(mass, stiffness, xi, dt, "exact", N_STEPS, &conv, msg, sizeof msg);
    status |= gc_law_new("exponential", exponential, 2, &law, msg, sizeof msg);
    status |= gc_run_contact_law(conv, law, preload, N_STEPS, road, NULL, u, f, d, msg, sizeof msg);
    double du = deviation(u, u_ref, N_STEPS), df = deviation(f, f_ref, N_STEPS), dd = deviation(d, d_ref, N_STEPS);
    snprintf(line, sizeof line, "max|du|/max|u| = %.2e, max|dF|/max F = %.2e, max|ddelta|/max delta = %.2e", du, df,
             dd);
    check(status == GC_OK && du <= 1e-12 && df <= 1e-12 && dd <= 1e-12,
          "exponential law from C equals the driver's run within 1e-12 (16 printed digits)", line);
    int lifted = 0;
    for (int i = 0; i < N_STEPS; i++) lifted += f[i] == 0.0;
    check(lifted > 0 && lifted < N_STEPS / 2, "the run lifts off and lands again", NULL);
    gc_law_free(law);
    gc_convolver_delete(&conv);
}

int main(void)
{
    test_new_and_refusals();
    test_power_doors_equal();
    test_multi_doors();
    test_exponential_against_driver();
    return check_exit();
}
