/*
 * multi_modes_file.c - gc_multi_new_modes_file and the accuracy doors
 * gc_multi_estimate / gc_multi_set_accuracy.
 *
 * The modes file test/data/uff/modes_plate.uff (9 nodes of a plate, 32 modes in datasets 55):
 * a scene with `&structure model = 'modes_file'` on it is run by gc_run_scene ("exact" and
 * "modal", 100 steps of 80 us, a road file this program writes); the door's convolver, made on
 * the same file with the same damping ratio, direction and band, is stepped from this
 * program's loop (gc_multi_contact_step) on the road heights the scene wrote, with the scene's
 * contact (k_c per point, the preload shared evenly); its displacements and forces must be
 * those of the scene's file to 1e-12 (bit for bit expected: the same routines on the same
 * doubles, the file printed with 17 digits). Then bad files (missing, truncated) end
 * GC_ERROR_INPUT with the reader's message, and bad arguments are named. Last, the accuracy:
 * modes given exactly estimate 0 (any accuracy met); "fft" on a receptance file cut at
 * 200 Hz and run at 1 kHz estimates what the band leaves out, and an accuracy below that
 * estimate gives GC_ACCURACY from gc_multi_set_accuracy and gc_multi_run_contact (whose
 * results stay whole), an accuracy above it GC_OK.
 *
 * The band: the plate's 23 modes above f_band = 1000 Hz are kept as their static
 * compliance R in W0 by the one builder a scene and the door both call. A scene with
 * f_modes = 1000 and the door with f_band = 1000 give the same forces bit for bit ("exact",
 * R in W0; "modal", R left out: explicit). Against the run on all 32 modes (the door's
 * "exact" with f_band = 0 at dt/4 = 5 us, second order: about 3e-6 from the modal ODE, which
 * the Fortran suite modesfile checks with Dormand-Prince), 40 ms on a wavy road at 20 us:
 * "exact" on the 9 modes with R is within 5e-3, "modal" on them (no R) is not; run whole
 * (gc_multi_run_contact), the door's estimate (the model's, time step's and band's terms, as a
 * scene's error budget) is within a factor 3 of that error for both.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <greenconv.h>
#include "check.h"

#define NC 9
#define NT 100
#define MAX_ROWS (NC * NT)

static const char *modes_path = "test/data/uff/modes_plate.uff";
static const double dt = 8.0e-5, k_contact = 1.0e7, exponent = 1.5, total_preload = 300.0, xi = 0.03;
static double rows[MAX_ROWS][8];

/* The wavy road's height [m] at x [m]. */
static double road_height(double x)
{
    const double pi = 3.14159265358979323846;
    return 1.0e-4 * sin(2.0 * pi * x / 0.05) + 0.5e-4 * sin(2.0 * pi * x / 0.021);
}

/* The wavy road: "x height" lines, 0 to 1 m by 0.1 mm. */
static int write_road(const char *path)
{
    FILE *file = fopen(path, "w");
    if (file == NULL) return 0;
    fprintf(file, "# x [m], height [m]\n");
    for (int j = 0; j <= 10000; j++) {
        double x = 1.0e-4 * j;
        fprintf(file, "%.17e %.17e\n", x, road_height(x));
    }
    fclose(file);
    return 1;
}

/* The rows (t x u_road u f_contact delta f_total y) of a multi-point column file. */
static int read_rows(const char *path)
{
    char line[1024];
    int n = 0;
    FILE *file = fopen(path, "r");
    if (file == NULL) return -1;
    while (fgets(line, sizeof line, file) != NULL && n < MAX_ROWS) {
        if (line[strspn(line, " \t")] == '#') continue;
        double *r = rows[n];
        if (sscanf(line, "%lf %lf %lf %lf %lf %lf %lf %lf", &r[0], &r[1], &r[2], &r[3], &r[4], &r[5], &r[6], &r[7]) == 8)
            n++;
    }
    fclose(file);
    return n;
}

/* The scene `name`'s run of `method` against the door's convolver (band f_band [Hz]) stepped
 * from this loop. */
static void compare_with_scene(const char *name, const char *method, double f_band)
{
    char msg[1024], path[256], what[256];
    gc_multi_convolver *conv = NULL;
    double k_c[NC], p[NC], preload[NC], road[NC], u[NC], f[NC], x[NC], y[NC];
    int node[NC], status, n_points = 0;

    snprintf(path, sizeof path, "build/ctest_modes_file/%s_%s.dat", name, method);
    int n_rows = read_rows(path);
    snprintf(what, sizeof what, "%s: the scene wrote %d rows (N_t*N_c = %d)", method, n_rows, NC * NT);
    check(n_rows == NC * NT, what, path);
    if (n_rows != NC * NT) return;
    status = gc_multi_new_modes_file(modes_path, 3, xi, f_band, method, dt, NT, NULL, &conv, msg, sizeof msg);
    snprintf(what, sizeof what, "%s: gc_multi_new_modes_file on %s, f_band %g Hz", method, modes_path, f_band);
    check_status(status, GC_OK, msg, "", what);
    if (status != GC_OK) return;
    status = gc_multi_n_points(conv, &n_points, msg, sizeof msg);
    check(status == GC_OK && n_points == NC, "its points: the file's 9 nodes", msg);
    status = gc_multi_points(conv, NC, node, x, y, msg, sizeof msg);
    int same_points = status == GC_OK && node[0] == 101 && node[8] == 109;
    for (int i = 0; i < NC && same_points; i++) same_points = x[i] == rows[i][1] && y[i] == rows[i][7];
    check(same_points, "gc_multi_points: nodes 101..109 at the x, y of the scene's rows", msg);
    for (int i = 0; i < NC; i++) {
        k_c[i] = k_contact;
        p[i] = exponent;
        preload[i] = total_preload / NC;
    }
    /* Before a run: 0 for modes given exactly, but for "modal" with modes above the band the
     * static flexibility it leaves out (the description's 3.22 %). */
    int leaves_static = f_band > 0.0 && strcmp(method, "modal") == 0;
    double estimate = -1.0;
    status = gc_multi_estimate(conv, &estimate, msg, sizeof msg);
    snprintf(what, sizeof what, "%s, f_band %g Hz: before a run the estimate is %s (%.4g)", method, f_band,
             leaves_static ? "the static share above the band" : "0", estimate);
    check(status == GC_OK && (leaves_static ? fabs(estimate - 0.0322) < 5e-5 : estimate == 0.0), what, msg);
    status = gc_multi_set_accuracy(conv, 1e-15, msg, sizeof msg);
    check_status(status, leaves_static ? GC_ACCURACY : GC_OK, msg, "", "1e-15 asked before a run");
    status = gc_multi_set_accuracy(conv, 0.0, msg, sizeof msg);
    status = gc_multi_contact_start(conv, NC, k_c, p, preload, msg, sizeof msg);
    check_status(status, GC_OK, msg, "", "the contact run starts");
    double worst_u = 0.0, worst_f = 0.0, peak_u = 0.0, peak_f = 0.0;
    for (int n = 0; n < NT && status == GC_OK; n++) {
        for (int i = 0; i < NC; i++) road[i] = rows[n * NC + i][2];
        status = gc_multi_contact_step(conv, NC, road, u, f, NULL, msg, sizeof msg);
        for (int i = 0; i < NC && status == GC_OK; i++) {
            worst_u = fmax(worst_u, fabs(u[i] - rows[n * NC + i][3]));
            worst_f = fmax(worst_f, fabs(f[i] - rows[n * NC + i][4]));
            peak_u = fmax(peak_u, fabs(rows[n * NC + i][3]));
            peak_f = fmax(peak_f, fabs(rows[n * NC + i][4]));
        }
    }
    snprintf(msg, sizeof msg, "status %d, max |du| %.3g of %.3g m, max |dF| %.3g of %.3g N", status, worst_u, peak_u,
             worst_f, peak_f);
    snprintf(what, sizeof what, "%s, f_band %g Hz: the door stepped from C = the scene's run, 100 steps, bit for bit",
             method, f_band);
    check(status == GC_OK && peak_u > 0.0 && worst_u == 0.0 && worst_f == 0.0, what, msg);
    status = gc_multi_estimate(conv, &estimate, msg, sizeof msg);
    snprintf(what, sizeof what, "%s, f_band %g Hz: after the stepped run the estimate holds its time-step and band "
             "terms (%.3g)", method, f_band, estimate);
    check(status == GC_OK && estimate > 0.0 && estimate < 0.1, what, msg);
    status = gc_multi_set_accuracy(conv, 0.5 * estimate, msg, sizeof msg);
    check_status(status, GC_ACCURACY, msg, "time step", "half of it: GC_ACCURACY at once");
    gc_multi_delete(&conv);
}

/* The scene `name` on the plate's modes with f_modes = f_band [Hz] (written to the file
 * `scene`, run by gc_run_scene), then the door against it for "exact" and "modal". */
static void run_scene_and_door(const char *scene, const char *name, double f_band)
{
    /* The scene asks 0.5: the door against the scene is under test here; at 80 us the modal
     * step's own estimate of its time-step error is 1.4e-3 with every mode, and with the band at
     * 1 kHz the band's term is 2.7e-2 (modal) and 5e-3 (exact), above the default. */
    char msg[1024], what[256];
    FILE *file = fopen(scene, "w");
    if (file == NULL) {
        check(0, "writing the scene", scene);
        return;
    }
    fprintf(file, "&scene name = '%s', output_dir = 'build/ctest_modes_file', dt = 8.0e-5, n_steps = %d /\n"
                  "&structure model = 'modes_file', modes_file = '%s', damping_ratio = %g, f_modes = %g /\n"
                  "&road profile = 'file', road_file = 'build/ctest_modes_file/wave.dat', x_start = 0.3, speed = 5.0 /\n"
                  "&contact stiffness = %g, exponent = %g, preload = %g /\n"
                  "&convolution methods = 'exact', 'modal', accuracy = 0.5 /\n",
            name, NT, modes_path, xi, f_band, k_contact, exponent, total_preload);
    fclose(file);
    fflush(stdout);
    int status = gc_run_scene(scene, msg, sizeof msg);
    snprintf(what, sizeof what, "the modes_file scene with f_modes = %g runs (exact, modal)", f_band);
    check_status(status, GC_OK, msg, "", what);
    if (status != GC_OK) return;
    compare_with_scene(name, "exact", f_band);
    compare_with_scene(name, "modal", f_band);
}

/* The door's `method` on the plate's modes up to f_band [Hz] at time step `step` [s] over
 * `n_steps`, stepped here on the wavy road (node i at 0.3 m + x_i - mean x + 5 m/s * t); the
 * forces of every `every`-th step into force[(n / every) * NC + i]. Returns the status. */
static int run_on_road(const char *method, double f_band, double step, int n_steps, int every, double *force,
                       char *msg, size_t msg_len)
{
    gc_multi_convolver *conv = NULL;
    double k_c[NC], p[NC], preload[NC], road[NC], u[NC], f[NC], x[NC], y[NC], mean_x = 0.0;
    int node[NC];
    int status = gc_multi_new_modes_file(modes_path, 3, xi, f_band, method, step, n_steps, NULL, &conv, msg, msg_len);
    if (status == GC_OK) status = gc_multi_points(conv, NC, node, x, y, msg, msg_len);
    for (int i = 0; i < NC; i++) {
        k_c[i] = k_contact;
        p[i] = exponent;
        preload[i] = total_preload / NC;
        mean_x += x[i] / NC;
    }
    if (status == GC_OK) status = gc_multi_contact_start(conv, NC, k_c, p, preload, msg, msg_len);
    for (int n = 0; n < n_steps && status == GC_OK; n++) {
        for (int i = 0; i < NC; i++) road[i] = road_height(0.3 + (x[i] - mean_x) + 5.0 * n * step);
        status = gc_multi_contact_step(conv, NC, road, u, f, NULL, msg, msg_len);
        if (n % every == 0)
            for (int i = 0; i < NC; i++) force[(n / every) * NC + i] = f[i];
    }
    gc_multi_delete(&conv);
    return status;
}

/* The door's `method` on the plate's modes up to f_band [Hz] at `step` [s], a whole run of
 * n_steps on the wavy road (gc_multi_run_contact); the forces of every step into
 * force[n * NC + i] and the door's estimate after it (gc_multi_estimate: the model's terms and
 * the run's time-step and band terms) into *estimate. Returns the status. */
static int run_whole_on_road(const char *method, double f_band, double step, int n_steps, double *force,
                             double *estimate, char *msg, size_t msg_len)
{
    gc_multi_convolver *conv = NULL;
    double k_c[NC], p[NC], preload[NC], x[NC], y[NC], mean_x = 0.0;
    int node[NC];
    double *road = malloc(sizeof(double) * (size_t)n_steps * NC);
    double *u = malloc(sizeof(double) * (size_t)n_steps * NC), *f = malloc(sizeof(double) * (size_t)n_steps * NC);
    int status = road != NULL && u != NULL && f != NULL ? GC_OK : GC_ERROR_INPUT;
    if (status == GC_OK)
        status = gc_multi_new_modes_file(modes_path, 3, xi, f_band, method, step, n_steps, NULL, &conv, msg, msg_len);
    if (status == GC_OK) status = gc_multi_points(conv, NC, node, x, y, msg, msg_len);
    for (int i = 0; i < NC && status == GC_OK; i++) {
        k_c[i] = k_contact;
        p[i] = exponent;
        preload[i] = total_preload / NC;
        mean_x += x[i] / NC;
    }
    for (int i = 0; i < NC && status == GC_OK; i++)
        for (int n = 0; n < n_steps; n++) road[n + (size_t)n_steps * i] = road_height(0.3 + (x[i] - mean_x) + 5.0 * n * step);
    if (status == GC_OK)
        status = gc_multi_run_contact(conv, NC, n_steps, k_c, p, preload, road, u, f, NULL, msg, msg_len);
    if (status == GC_OK) status = gc_multi_estimate(conv, estimate, msg, msg_len);
    for (int n = 0; n < n_steps && status == GC_OK; n++)
        for (int i = 0; i < NC; i++) force[n * NC + i] = f[n + (size_t)n_steps * i];
    gc_multi_delete(&conv);
    free(road);
    free(u);
    free(f);
    return status;
}

/* exact with R (f_band = 1000 Hz) and modal without it against all 32 modes: e = ||F - F_ref||
 * / ||F_ref - F0|| over 40 ms at 20 us. Run whole (gc_multi_run_contact), each door's estimate
 * (its time-step term from the runs at 40 and 80 us, its band term from the run with the modes
 * to 2 kHz) is within a factor 3 of that e. */
static void check_band_accuracy(void)
{
    enum { N_COARSE = 2000, REFINE = 4 };
    static double reference[N_COARSE * NC], force[N_COARSE * NC];
    const double coarse = 2.0e-5;
    const char *methods[2] = {"exact", "modal"};
    char msg[1024], what[256];
    double e[2] = {1.0, 1.0};

    int status = run_on_road("exact", 0.0, coarse / REFINE, N_COARSE * REFINE, REFINE, reference, msg, sizeof msg);
    check_status(status, GC_OK, msg, "", "the reference: exact on all 32 modes at 5 us, 40 ms");
    if (status != GC_OK) return;
    for (int m = 0; m < 2; m++) {
        status = run_on_road(methods[m], 1000.0, coarse, N_COARSE, 1, force, msg, sizeof msg);
        snprintf(what, sizeof what, "%s on the 9 modes up to 1000 Hz at 20 us runs", methods[m]);
        check_status(status, GC_OK, msg, "", what);
        if (status != GC_OK) return;
        double numerator = 0.0, denominator = 0.0;
        for (int k = 0; k < N_COARSE * NC; k++) {
            numerator += (force[k] - reference[k]) * (force[k] - reference[k]);
            denominator += (reference[k] - total_preload / NC) * (reference[k] - total_preload / NC);
        }
        e[m] = sqrt(numerator / denominator);
        double estimate = -1.0;
        status = run_whole_on_road(methods[m], 1000.0, coarse, N_COARSE, force, &estimate, msg, sizeof msg);
        snprintf(what, sizeof what, "%s: a whole run on the 9 modes up to 1000 Hz and its estimate", methods[m]);
        check_status(status, GC_OK, msg, "", what);
        if (status != GC_OK) return;
        snprintf(msg, sizeof msg, "%s: estimate %.3e, true %.3e, factor %.2f", methods[m], estimate, e[m],
                 estimate / e[m]);
        check(estimate <= 3.0 * e[m] && e[m] <= 3.0 * estimate, "the door's estimate after a whole run within 3x of "
              "its error against all 32 modes", msg);
        printf("  door budget: %s\n", msg);
    }
    snprintf(msg, sizeof msg, "e = %.3e with R (exact), %.3e without (modal)", e[0], e[1]);
    check(e[0] <= 5.0e-3 && e[1] > 5.0e-3, "f_band = 1000 Hz: exact with R within 5e-3 of all 32 modes, modal without R not",
          msg);
    printf("  band: %s\n", msg);
}

/* A receptance file of one mass-spring system at one node (as multi_file.c writes it), to
 * 200 Hz by 2.5 Hz. */
static int write_receptance(const char *path)
{
    const double pi = 3.14159265358979323846, mass = 1.5, f_n = 50.0, zeta = 0.02, df = 2.5;
    const double w_n = 2.0 * pi * f_n, k = mass * w_n * w_n, c = 2.0 * zeta * mass * w_n;
    const int lines = 81;
    FILE *file = fopen(path, "w");
    if (file == NULL) return 0;
    fprintf(file, "    -1\n    15\n         1         0         0         1  0.00000E+00  0.00000E+00  0.00000E+00\n"
                  "    -1\n    -1\n    58\nmulti_modes_file test\nSDOF\nNONE\nNONE\nNONE\n"
                  "    4         0    0         0       NONE         1   3       NONE         1   3\n"
                  "         6%10d         1  0.00000e+00  %.5e  0.00000e+00\n"
                  "        18    0    0    0 NONE                 Hz                  \n"
                  "         8    1    0    0 NONE                 m                   \n"
                  "        13    0    1    0 NONE                 N                   \n"
                  "         0    0    0    0 NONE                 NONE                \n",
            lines, df);
    for (int l = 0; l < lines; l++) {
        double w = 2.0 * pi * df * l, re = k - mass * w * w, im = c * w, d = re * re + im * im;
        fprintf(file, "%20.11e%20.11e%s", re / d, -im / d, l % 2 == 1 || l == lines - 1 ? "\n" : "");
    }
    fprintf(file, "    -1\n");
    fclose(file);
    return 1;
}

static void check_accuracy(void)
{
    const char *path = "build/ctest_modes_file/sdof_band.uff";
    char msg[1024];
    gc_multi_convolver *conv = NULL;
    double estimate = -1.0, k_c = 1.0e6, p = 1.5, preload = 10.0, road[200], u[200], f[200];

    if (!write_receptance(path)) {
        check(0, "writing the receptance file", path);
        return;
    }
    int status = gc_multi_new_file(path, "fft", 1.0e-3, 200, NULL, 6, &conv, msg, sizeof msg);
    check_status(status, GC_OK, msg, "", "fft on a receptance to 200 Hz, dt = 1 ms");
    if (status != GC_OK) return;
    status = gc_multi_estimate(conv, &estimate, msg, sizeof msg);
    snprintf(msg, sizeof msg, "status %d, estimate %.3g", status, estimate);
    check(status == GC_OK && estimate > 0.0 && estimate < 1.0, "its own estimate: what the band leaves out, in (0, 1)",
          msg);
    status = gc_multi_set_accuracy(conv, 2.0 * estimate, msg, sizeof msg);
    check_status(status, GC_OK, msg, "", "an accuracy above the estimate: GC_OK");
    for (int n = 0; n < 200; n++) road[n] = 1.0e-5 * sin(0.3 * n);
    status = gc_multi_set_accuracy(conv, 0.0, msg, sizeof msg);
    status = gc_multi_run_contact(conv, 1, 200, &k_c, &p, &preload, road, u, f, NULL, msg, sizeof msg);
    check_status(status, GC_OK, msg, "", "a run with no accuracy asked: GC_OK");
    double whole = -1.0;
    status = gc_multi_estimate(conv, &whole, msg, sizeof msg);
    snprintf(msg, sizeof msg, "status %d, estimate before %.3g, after the run %.3g", status, estimate, whole);
    check(status == GC_OK && whole > estimate, "after a whole run the estimate holds its time-step term", msg);
    estimate = whole;
    status = gc_multi_set_accuracy(conv, 2.0 * estimate, msg, sizeof msg);
    check_status(status, GC_OK, msg, "", "an accuracy above the run's estimate: GC_OK");
    status = gc_multi_run_contact(conv, 1, 200, &k_c, &p, &preload, road, u, f, NULL, msg, sizeof msg);
    check_status(status, GC_OK, msg, "", "a run inside the accuracy: GC_OK");
    double kept = f[199];
    status = gc_multi_set_accuracy(conv, 0.5 * estimate, msg, sizeof msg);
    check_status(status, GC_ACCURACY, msg, "outside the accuracy asked", "an accuracy below it: GC_ACCURACY at once");
    status = gc_multi_run_contact(conv, 1, 200, &k_c, &p, &preload, road, u, f, NULL, msg, sizeof msg);
    check_status(status, GC_ACCURACY, msg, "estimate", "the run outside it: GC_ACCURACY naming the estimate");
    check(f[199] == kept && f[199] > 0.0, "its results whole, the same as inside", "");
    status = gc_multi_contact_start(conv, 1, &k_c, &p, &preload, msg, sizeof msg);
    check_status(status, GC_ACCURACY, msg, "accuracy", "gc_multi_contact_start outside it: GC_ACCURACY");
    status = gc_multi_contact_step(conv, 1, road, u, f, NULL, msg, sizeof msg);
    check_status(status, GC_OK, msg, "", "the run started all the same: its steps GC_OK");
    status = gc_multi_set_accuracy(conv, 0.0, msg, sizeof msg);
    check_status(status, GC_OK, msg, "", "accuracy 0: none asked");
    status = gc_multi_set_accuracy(conv, -1.0, msg, sizeof msg);
    check_status(status, GC_ERROR_INPUT, msg, "accuracy", "a negative accuracy -> 2 naming it");
    status = gc_multi_set_accuracy(NULL, 1.0, msg, sizeof msg);
    check_status(status, GC_ERROR_INPUT, msg, "conv is NULL", "gc_multi_set_accuracy: conv NULL -> 2");
    status = gc_multi_estimate(conv, NULL, msg, sizeof msg);
    check_status(status, GC_ERROR_INPUT, msg, "estimate is NULL", "gc_multi_estimate: estimate NULL -> 2");
    gc_multi_delete(&conv);
    remove(path);
}

int main(void)
{
    const char *scene = "build/ctest_modes_file/plate.nml", *truncated = "build/ctest_modes_file/truncated.uff";
    char msg[1024], line[512];
    gc_multi_convolver *conv = NULL;
    int status;

    if (system("mkdir -p build/ctest_modes_file") != 0 || !write_road("build/ctest_modes_file/wave.dat")) {
        check(0, "writing the test files in build/ctest_modes_file", "");
        return check_exit();
    }
    /* The whole band (f_modes 0: every mode below 1/(2 dt) = 6250 Hz), then 1000 Hz: 9 modes
     * stepped, 23 as R. */
    run_scene_and_door(scene, "plate", 0.0);
    run_scene_and_door(scene, "band", 1000.0);
    check_band_accuracy();

    /* Bad files and arguments. */
    status = gc_multi_new_modes_file("no/such/modes.uff", 3, xi, 0.0, "modal", dt, NT, NULL, &conv, msg, sizeof msg);
    check_status(status, GC_ERROR_INPUT, msg, "no/such/modes.uff", "missing file -> 2 naming the file");
    check(conv == NULL, "no handle after a failed gc_multi_new_modes_file", "");
    FILE *in = fopen(modes_path, "r"), *out = fopen(truncated, "w");
    int n_lines = 0;
    while (in != NULL && out != NULL && fgets(line, sizeof line, in) != NULL && n_lines < 40) {
        fputs(line, out);
        n_lines++;
    }
    if (in != NULL) fclose(in);
    if (out != NULL) fclose(out);
    status = gc_multi_new_modes_file(truncated, 3, xi, 0.0, "modal", dt, NT, NULL, &conv, msg, sizeof msg);
    check_status(status, GC_ERROR_INPUT, msg, truncated, "a file cut after 40 lines -> 2 naming the file");
    check(strchr(msg, '\n') == NULL, "the reader's message on one line", msg);
    status = gc_multi_new_modes_file(modes_path, 4, xi, 0.0, "modal", dt, NT, NULL, &conv, msg, sizeof msg);
    check_status(status, GC_ERROR_INPUT, msg, "direction", "direction 4 -> 2 naming it");
    status = gc_multi_new_modes_file(modes_path, 3, 1.5, 0.0, "modal", dt, NT, NULL, &conv, msg, sizeof msg);
    check_status(status, GC_ERROR_INPUT, msg, "damping_ratio", "damping ratio 1.5 -> 2 naming it");
    status = gc_multi_new_modes_file(modes_path, 3, xi, 10.0, "modal", dt, NT, NULL, &conv, msg, sizeof msg);
    check_status(status, GC_ERROR_INPUT, msg, "band", "f_band below the lowest mode -> 2");
    status = gc_multi_new_modes_file(modes_path, 3, xi, 0.0, "paper", dt, NT, NULL, &conv, msg, sizeof msg);
    check_status(status, GC_ERROR_INPUT, msg, "multi-point", "a single-point method -> 2");
    status = gc_multi_new_modes_file(NULL, 3, xi, 0.0, "modal", dt, NT, NULL, &conv, msg, sizeof msg);
    check_status(status, GC_ERROR_INPUT, msg, "path is NULL", "path NULL -> 2");
    status = gc_multi_new_modes_file(modes_path, 3, xi, 0.0, NULL, dt, NT, NULL, &conv, msg, sizeof msg);
    check_status(status, GC_ERROR_INPUT, msg, "method is NULL", "method NULL -> 2");
    status = gc_multi_new_modes_file(modes_path, 3, xi, 0.0, "modal", dt, NT, NULL, NULL, msg, sizeof msg);
    check_status(status, GC_ERROR_INPUT, msg, "conv is NULL", "conv NULL -> 2");
    remove(truncated);

    check_accuracy();
    return check_exit();
}
