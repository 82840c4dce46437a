/*
 * Bad input gives GC_ERROR_INPUT (2), no convolver, and a message that names the argument.
 */
#include <math.h>
#include "greenconv.h"
#include "check.h"

int main(void)
{
    char msg[512];
    gc_convolver *conv = (gc_convolver *)&msg; /* not NULL: a failed constructor must set NULL */
    double one = 1.0, minus = -1.0, road = 0.0, u[4], f[4];
    int status;
    gc_build_options build;
    gc_contact_options options;

    status = gc_convolver_new_sdof(-1.0, 1e4, 0.1, 1e-3, "modal", 10, &conv, msg, sizeof msg);
    check_status(status, GC_ERROR_INPUT, msg, "mass", "new_sdof mass = -1: names the mass");
    check(conv == NULL, "new_sdof failure: *conv = NULL", NULL);
    status = gc_convolver_new_sdof(1.0, 0.0, 0.1, 1e-3, "modal", 10, &conv, msg, sizeof msg);
    check_status(status, GC_ERROR_INPUT, msg, "stiffness", "new_sdof stiffness = 0: names the stiffness");
    status = gc_convolver_new_sdof(1.0, 1e4, 1.5, 1e-3, "modal", 10, &conv, msg, sizeof msg);
    check_status(status, GC_ERROR_INPUT, msg, "damping", "new_sdof damping ratio = 1.5: names the damping ratio");
    status = gc_convolver_new_sdof(1.0, 1e4, 0.1, 0.0, "modal", 10, &conv, msg, sizeof msg);
    check_status(status, GC_ERROR_INPUT, msg, "dt", "new_sdof dt = 0: names dt");
    status = gc_convolver_new_sdof(1.0, 1e4, 0.1, NAN, "modal", 10, &conv, msg, sizeof msg);
    check_status(status, GC_ERROR_INPUT, msg, "dt", "new_sdof dt = NaN: names dt");
    status = gc_convolver_new_sdof(1.0, 1e4, 0.1, 1e-3, "modal", 0, &conv, msg, sizeof msg);
    check_status(status, GC_ERROR_INPUT, msg, "steps", "new_sdof n_steps = 0: names the number of steps");
    status = gc_convolver_new_sdof(1.0, 1e4, 0.1, 1e-3, "bogus", 10, &conv, msg, sizeof msg);
    check_status(status, GC_ERROR_INPUT, msg, "bogus", "new_sdof method 'bogus': names it");
    status = gc_convolver_new_sdof(1.0, 1e4, 0.1, 1e-3, NULL, 10, &conv, msg, sizeof msg);
    check_status(status, GC_ERROR_INPUT, msg, "method", "new_sdof method NULL: names the method");
    status = gc_convolver_new_sdof(1.0, 1e4, 0.1, 1e-3, "modal", 10, NULL, msg, sizeof msg);
    check_status(status, GC_ERROR_INPUT, msg, "conv", "new_sdof conv NULL: names conv");
    status = gc_convolver_new_modes(0, &minus, &one, &one, &one, 1e-3, "modal", 10, &conv, msg, sizeof msg);
    check_status(status, GC_ERROR_INPUT, msg, "n_modes", "new_modes n_modes = 0: names n_modes");
    status = gc_convolver_new_modes(1, &one, &one, &one, &one, 1e-3, "modal", 10, &conv, msg, sizeof msg);
    check_status(status, GC_ERROR_INPUT, msg, "pole", "new_modes pole with Re > 0: names the poles");
    status = gc_convolver_new_modes(1, NULL, &one, &one, &one, 1e-3, "modal", 10, &conv, msg, sizeof msg);
    check_status(status, GC_ERROR_INPUT, msg, "pole_re", "new_modes pole_re NULL: names pole_re");
    status = gc_convolver_new_samples(1, &one, 1e-3, "direct", 10, &conv, msg, sizeof msg);
    check_status(status, GC_ERROR_INPUT, msg, "samples", "new_samples n_samples = 1: names the samples");
    status = gc_convolver_new_frf_file("no/such/file.frf", 1e-3, "modal", 10, 1e-6, 30, &conv, msg, sizeof msg);
    check_status(status, GC_ERROR_INPUT, msg, "no/such/file.frf", "new_frf_file missing file: names the path");

    gc_build_options_init(&build);
    build.truncation_tol = 2.0;
    status = gc_convolver_new_sdof_opts(1.0, 1e4, 0.1, 1e-3, "direct", 10, &build, &conv, msg, sizeof msg);
    check_status(status, GC_ERROR_INPUT, msg, "truncation_tol", "build option truncation_tol = 2: names it");
    gc_build_options_init(&build);
    build.accuracy = -1.0;
    status = gc_convolver_new_sdof_opts(1.0, 1e4, 0.1, 1e-3, "auto", 10, &build, &conv, msg, sizeof msg);
    check_status(status, GC_ERROR_INPUT, msg, "accuracy", "build option accuracy = -1: names it");

    status = gc_convolver_new_sdof(1.0, 1e4, 0.1, 1e-3, "exact", 4, &conv, msg, sizeof msg);
    check_status(status, GC_OK, msg, NULL, "a good convolver for the contact checks");
    status = gc_run_contact(conv, -1.0, 1.5, 10.0, 4, &road, u, f, NULL, msg, sizeof msg);
    check_status(status, GC_ERROR_INPUT, msg, "k_c", "run_contact k_c = -1: names k_c");
    status = gc_run_contact(conv, 1e6, 1.5, -10.0, 4, &road, u, f, NULL, msg, sizeof msg);
    check_status(status, GC_ERROR_INPUT, msg, "preload", "run_contact preload = -10: names the preload");
    status = gc_contact_start(conv, 1e6, 1.5, -10.0, NULL, msg, sizeof msg);
    check_status(status, GC_ERROR_INPUT, msg, "preload", "contact_start preload = -10: names the preload");
    check_status(status, GC_ERROR_INPUT, msg, "gc_contact_start: ", "contact_start preload = -10: names the door");
    status = gc_run_contact(conv, 1e6, 1.5, -10.0, 4, &road, u, f, NULL, msg, sizeof msg);
    check_status(status, GC_ERROR_INPUT, msg, "gc_run_contact: ", "run_contact preload = -10: names the door");
    status = gc_run_contact(conv, 1e6, 1.5, 10.0, 0, &road, u, f, NULL, msg, sizeof msg);
    check_status(status, GC_ERROR_INPUT, msg, "n_steps", "run_contact n_steps = 0: names n_steps");
    status = gc_run_contact(conv, 1e6, 1.5, 10.0, 4, NULL, u, f, NULL, msg, sizeof msg);
    check_status(status, GC_ERROR_INPUT, msg, "road", "run_contact road NULL: names road");
    gc_contact_options_init(&options);
    options.scheme = 7;
    status = gc_run_contact_opts(conv, 1e6, 1.5, 10.0, 1, &road, &options, u, f, NULL, msg, sizeof msg);
    check_status(status, GC_ERROR_INPUT, msg, "scheme", "contact option scheme = 7: names the scheme");
    gc_contact_options_init(&options);
    options.tolerance = -1.0;
    status = gc_run_contact_opts(conv, 1e6, 1.5, 10.0, 1, &road, &options, u, f, NULL, msg, sizeof msg);
    check_status(status, GC_ERROR_INPUT, msg, "tolerance", "contact option tolerance = -1: names the tolerance");
    gc_contact_options_init(&options);
    options.max_iterations = 0;
    status = gc_contact_start(conv, 1e6, 1.5, 10.0, &options, msg, sizeof msg);
    check_status(status, GC_ERROR_INPUT, msg, "max_iterations", "contact_start max_iterations = 0: names it");
    gc_convolver_free(conv);
    return check_exit();
}
