/*
 * c_patch_file.c - the shipped 2D contact patch (data/patch_road.nml) run from C through the
 * multi-point doors of include/greenconv.h with the program's own time loop, and checked
 * against the driver's output files.
 *
 * The scene: data/patch_green.uff holds the receptances G_ij(f) between the 12 points of a
 * 4 x 3 patch under a tyre belt (0-600 Hz, 1 % noise) and the points' coordinates. This
 * program reads it once (gc_multi_new_file: shared poles identified, diagram up to 60 modes
 * as the scene's &identification max_order), builds "exact" (implicit, on the identified
 * modes and the fit's upper residual) and, on the same file without a second identification,
 * "fft" (g_ij from the inverse FFT of the file's receptances; gc_multi_new_method). It then
 * follows the scene's conventions (greenconv_scene_models_patch): preload 3000 N shared evenly by
 * the points, a linear law k_c = 5e4 N/m per point, point i at x_i sees the road of
 * data/road_sample.dat (linearly interpolated) at x_start + (x_i - mean x) + V*t_n,
 * x_start = 0.5 m, V = 5 m/s, t_n = n*dt, dt = 2e-4 s, 3000 steps. One
 * gc_multi_contact_step call per step.
 *
 * Usage: c_patch_file [DIR]: DIR holds the driver's patch_road_exact.dat and
 * patch_road_fft.dat for data/patch_road.nml (default "out", where `greenconv
 * data/patch_road.nml` writes them); run from the top folder (it reads data/). The road
 * heights and the contact forces must equal the driver's bit for bit: the same library
 * routines on the same numbers, the files printed with 17 digits (which give back the very
 * doubles). Exit status 0 when every check passes.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <greenconv.h>

#define NP 12
#define NT 3000
#define ROAD_MAX 20000

static const double dt = 2.0e-4, speed = 5.0, x_start = 0.5, k_contact = 5.0e4, total_preload = 3000.0;

static double road_x[ROAD_MAX], road_h[ROAD_MAX];
static int road_n = 0;
static double road[NP * NT], ref_road[NP * NT], ref_force[NP * NT];

/* The road file: "x height" per line, "#" lines are comments. */
static int read_road(const char *path)
{
    char line[512];
    FILE *file = fopen(path, "r");
    if (file == NULL) return 0;
    while (fgets(line, sizeof line, file) != NULL && road_n < ROAD_MAX) {
        if (line[strspn(line, " \t")] == '#') continue;
        if (sscanf(line, "%lf %lf", &road_x[road_n], &road_h[road_n]) == 2) road_n++;
    }
    fclose(file);
    return road_n >= 2;
}

/* Height at x by linear interpolation, the end values beyond the file (as the library's
 * road reader: the same interval search and weight, so the same doubles). */
static double road_height(double x)
{
    int low = 0, high = road_n - 1;
    if (x <= road_x[0]) return road_h[0];
    if (x >= road_x[high]) return road_h[high];
    while (high - low > 1) {
        int middle = (low + high) / 2;
        if (road_x[middle] <= x) low = middle; else high = middle;
    }
    double weight = (x - road_x[low]) / (road_x[low + 1] - road_x[low]);
    return (1.0 - weight) * road_h[low] + weight * road_h[low + 1];
}

/* The driver's columns "t x u_road u f_contact delta f_total y", one row per step and point. */
static int read_reference(const char *path)
{
    char line[1024];
    int row = 0;
    FILE *file = fopen(path, "r");
    if (file == NULL) return 0;
    while (fgets(line, sizeof line, file) != NULL) {
        double t, x, u_road, u, f;
        if (line[strspn(line, " \t")] == '#') continue;
        if (sscanf(line, "%lf %lf %lf %lf %lf", &t, &x, &u_road, &u, &f) != 5 || row >= NP * NT) break;
        ref_road[(row % NP) * NT + row / NP] = u_road;
        ref_force[(row % NP) * NT + row / NP] = f;
        row++;
    }
    fclose(file);
    return row == NP * NT;
}

int main(int argc, char **argv)
{
    const char *dir = argc > 1 ? argv[1] : "out";
    const char *methods[2] = {"exact", "fft"};
    gc_multi_convolver *conv[2] = {NULL, NULL};
    double x[NP], y[NP], k_c[NP], p[NP], preload[NP], x_sum = 0.0, r[NP], ui[NP], fi[NP], e_worst, e_mean;
    int node[NP], n_points = 0, n_poles = 0, failed = 0;
    char msg[512], path[1024], summary[4096];

    if (!read_road("data/road_sample.dat")) {
        fprintf(stderr, "c_patch_file: cannot read data/road_sample.dat (run from the top folder)\n");
        return 1;
    }
    int status = gc_multi_new_file("data/patch_green.uff", methods[0], dt, NT, NULL, 60, &conv[0], msg, sizeof msg);
    if (status == GC_OK) status = gc_multi_new_method(conv[0], methods[1], dt, NT, NULL, &conv[1], msg, sizeof msg);
    if (status == GC_OK) status = gc_multi_n_points(conv[0], &n_points, msg, sizeof msg);
    if (status == GC_OK && n_points != NP) {
        fprintf(stderr, "c_patch_file: data/patch_green.uff has %d points, expected %d\n", n_points, NP);
        status = GC_ERROR_INPUT;
    }
    if (status == GC_OK) status = gc_multi_points(conv[0], NP, node, x, y, msg, sizeof msg);
    if (status == GC_OK)
        status = gc_multi_file_summary(conv[0], &e_worst, &e_mean, &n_poles, summary, sizeof summary);
    if (status != GC_OK) {
        fprintf(stderr, "c_patch_file: %s\n", msg);
        gc_multi_delete(&conv[0]);
        gc_multi_delete(&conv[1]);
        return 1;
    }
    printf("c_patch_file: data/patch_green.uff: %d points (nodes %d to %d), %d shared poles, E of the modes "
           "alone worst %.3g, mean %.3g (eq. 7)\n", NP, node[0], node[NP - 1], n_poles, e_worst, e_mean);

    /* The scene's conventions: the patch centre at x_start + V*t, F0 shared evenly. */
    for (int i = 0; i < NP; i++) x_sum += x[i];
    for (int i = 0; i < NP; i++) {
        double start = x_start + (x[i] - x_sum / NP);
        k_c[i] = k_contact;
        p[i] = 1.0;
        preload[i] = total_preload / NP;
        for (int n = 0; n < NT; n++) road[i * NT + n] = road_height(start + speed * ((double)n * dt));
    }

    for (int m = 0; m < 2 && !failed; m++) {
        double worst = 0.0, worst_road = 0.0, peak = 0.0;
        snprintf(path, sizeof path, "%s/patch_road_%s.dat", dir, methods[m]);
        if (!read_reference(path)) {
            fprintf(stderr, "c_patch_file: cannot read %d rows of %s (run greenconv data/patch_road.nml)\n",
                    NP * NT, path);
            failed = 1;
            break;
        }
        status = gc_multi_contact_start(conv[m], NP, k_c, p, preload, msg, sizeof msg);
        for (int n = 0; n < NT && status == GC_OK; n++) {
            for (int i = 0; i < NP; i++) r[i] = road[i * NT + n];
            status = gc_multi_contact_step(conv[m], NP, r, ui, fi, NULL, msg, sizeof msg);
            for (int i = 0; i < NP && status == GC_OK; i++) {
                worst = fmax(worst, fabs(fi[i] - ref_force[i * NT + n]));
                worst_road = fmax(worst_road, fabs(r[i] - ref_road[i * NT + n]));
                peak = fmax(peak, fabs(ref_force[i * NT + n]));
            }
        }
        if (status != GC_OK) {
            fprintf(stderr, "c_patch_file: %s: %s\n", methods[m], msg);
            failed = 1;
            break;
        }
        gc_multi_describe(conv[m], NULL, msg, sizeof msg);
        printf("c_patch_file: %s (%s)\n", methods[m], msg);
        printf("c_patch_file: %s, own loop of %d gc_multi_contact_step calls vs %s: peak force %.1f N, "
               "max |dF| = %g N, max |d u_road| = %g m\n", methods[m], NT, path, peak, worst, worst_road);
        if (worst != 0.0 || worst_road != 0.0) {
            printf("FAIL: c_patch_file: %s differs from the driver's %s\n", methods[m], path);
            failed = 1;
        }
    }
    gc_multi_delete(&conv[0]);
    gc_multi_delete(&conv[1]);
    return failed;
}
