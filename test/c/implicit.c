/*
 * The implicit contact scheme through gc_contact_options. A linear spring (p = 1, k_c =
 * 1e6 N/m) pressed by a constant road height h = 5 um under an SDOF (M = 1 kg, K = 1e4 N/m,
 * xi = 0.2) with the "exact" engine: the implicit step enforces the static balance
 * K*u = k_c*(h - u) at every step, so after the transient it lands on the closed form
 * u = k_c*h/(K + k_c); the explicit step settles elsewhere (on its own limit). A run stepped
 * with gc_contact_start/advance equals gc_run_contact_opts bit for bit.
 */
#include <math.h>
#include "greenconv.h"
#include "check.h"

#define N_STEPS 20000
#define DT 1.0e-4
#define H 5.0e-6
#define K_C 1.0e6
#define STIFFNESS 1.0e4
#define PRELOAD 10.0

int main(void)
{
    static double road[N_STEPS], u[N_STEPS], f[N_STEPS], u_explicit[N_STEPS];
    char msg[512], detail[200];
    gc_convolver *conv = NULL;
    gc_contact_options options;
    double exact = K_C * H / (STIFFNESS + K_C), u1, f1, error_implicit, error_explicit;
    int n, status, same = 1;

    for (n = 0; n < N_STEPS; n++) road[n] = H;
    status = gc_convolver_new_sdof(1.0, STIFFNESS, 0.2, DT, "exact", N_STEPS, &conv, msg, sizeof msg);
    check_status(status, GC_OK, msg, NULL, "new_sdof 'exact'");
    status = gc_contact_options_init(&options);
    check(status == GC_OK && options.scheme == GC_SCHEME_EXPLICIT && options.max_iterations == 100 &&
              options.divergence_bound == 0.1 && options.tolerance == 1e-12,
          "contact_options_init: the explicit scheme, 100 iterations, 0.1 m, 1e-12", NULL);

    options.scheme = GC_SCHEME_IMPLICIT;
    status = gc_run_contact_opts(conv, K_C, 1.0, PRELOAD, N_STEPS, road, &options, u, f, NULL, msg, sizeof msg);
    check_status(status, GC_OK, msg, NULL, "implicit run: status 0");
    status = gc_run_contact_opts(conv, K_C, 1.0, PRELOAD, N_STEPS, road, NULL, u_explicit, f, NULL, msg, sizeof msg);
    check_status(status, GC_OK, msg, NULL, "explicit run (options NULL): status 0");
    error_implicit = fabs(u[N_STEPS - 1] - exact) / exact;
    error_explicit = fabs(u_explicit[N_STEPS - 1] - exact) / exact;
    snprintf(detail, sizeof detail, "u = %.12e m, k_c*h/(K + k_c) = %.12e m, relative error %.1e", u[N_STEPS - 1],
             exact, error_implicit);
    check(error_implicit < 1e-9, "implicit: the static balance, to 1e-9", detail);
    snprintf(detail, sizeof detail, "explicit relative error %.1e > implicit %.1e", error_explicit, error_implicit);
    check(error_explicit > 10.0 * error_implicit, "explicit: not on it (the schemes differ)", detail);

    status = gc_contact_start(conv, K_C, 1.0, PRELOAD, &options, msg, sizeof msg);
    check_status(status, GC_OK, msg, NULL, "contact_start, implicit");
    for (n = 0; n < N_STEPS && status == GC_OK; n++) {
        status = gc_contact_advance(conv, road[n], &u1, &f1, NULL, msg, sizeof msg);
        same = same && u1 == u[n];
    }
    check(status == GC_OK && same, "stepped implicit run equals gc_run_contact_opts bit for bit", msg);
    gc_convolver_delete(&conv);
    return check_exit();
}
