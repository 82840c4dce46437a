/* The C doors that are another door with a fixed argument: each is a line or a few, so that
 * one body (src/greenconv/api/capi.f90, capi_multi.f90) serves both names and the header
 * (include/greenconv.h) keeps every name it has declared.
 *
 * - The constructors and the whole run without build or contact options are their `_opts`
 *   door with NULL options (the library's defaults).
 * - gc_convolver_new_frf_file and its `_opts` door are gc_convolver_new_frf_file_ident with
 *   the identification method NULL: the identification registry's default for a measured
 *   receptance ("ml"), as a scene's `frf_file` model.
 * - The contact doors that take the power law's (k_c, p), single- and multi-point, are their
 *   `_law` door with that power law (one a point), made for the call and freed after it; their
 *   messages name them as before. A multi-point one reads k_c[i] and p[i] only after
 *   greenconv_multi_check_for_door has checked its handle, n_points against the convolver's
 *   points, its arrays and n_steps as the door always has.
 * - A single-point convolver is the multi-point convolver of one point (n_points = 1, the
 *   same box behind both handle types): its history, push, instantaneous weight and reset
 *   are the gc_multi_* doors on arrays of one value, with no message buffer (these
 *   single-point doors return a status alone). gc_multi_free and gc_multi_delete are the
 *   single-point ones, the box being the same.
 * - The estimate and accuracy doors of both handle types are one body each, told by a flag
 *   which door it is, so that its messages name the door and its kind of handle.
 *
 * The doors that stay apart, and why: the single-point constructors accept every method of
 * the registry ("paper", "backward", "auto") and the build option `accuracy`, the
 * multi-point ones a subset; gc_run_contact_opts and gc_contact_start take a scheme and a
 * divergence bound of 0.1 m in gc_contact_options, the multi-point runs take the Newton
 * settings of gc_multi_set_newton (bound 1 m) and choose the step from W0, and they keep the
 * error budget of a single-point run; gc_contact_step takes one explicit step without a
 * start; gc_convolver_model_size refuses a NULL size where gc_multi_describe skips it. */
#include <stdio.h>
#include <stdlib.h>
#include <stddef.h>

#include "../../../include/greenconv.h"

int gc_convolver_new_sdof(double mass, double stiffness, double damping_ratio, double dt, const char *method,
                          int n_steps, gc_convolver **conv, char *errmsg, size_t errmsg_len)
{
    return gc_convolver_new_sdof_opts(mass, stiffness, damping_ratio, dt, method, n_steps, NULL, conv, errmsg,
                                      errmsg_len);
}

int gc_convolver_new_modes(int n_modes, const double *pole_re, const double *pole_im, const double *residue_re,
                           const double *residue_im, double dt, const char *method, int n_steps,
                           gc_convolver **conv, char *errmsg, size_t errmsg_len)
{
    return gc_convolver_new_modes_opts(n_modes, pole_re, pole_im, residue_re, residue_im, dt, method, n_steps, NULL,
                                       conv, errmsg, errmsg_len);
}

int gc_convolver_new_samples(int n_samples, const double *g, double dt, const char *method, int n_steps,
                             gc_convolver **conv, char *errmsg, size_t errmsg_len)
{
    return gc_convolver_new_samples_opts(n_samples, g, dt, method, n_steps, NULL, conv, errmsg, errmsg_len);
}

int gc_convolver_new_frf_file(const char *path, double dt, const char *method, int n_steps, double tol_e,
                              int max_modes, gc_convolver **conv, char *errmsg, size_t errmsg_len)
{
    return gc_convolver_new_frf_file_ident(path, dt, method, n_steps, NULL, tol_e, max_modes, NULL, conv, errmsg,
                                           errmsg_len);
}

int gc_convolver_new_frf_file_opts(const char *path, double dt, const char *method, int n_steps, double tol_e,
                                   int max_modes, const gc_build_options *options, gc_convolver **conv, char *errmsg,
                                   size_t errmsg_len)
{
    return gc_convolver_new_frf_file_ident(path, dt, method, n_steps, NULL, tol_e, max_modes, options, conv, errmsg,
                                           errmsg_len);
}

/* The power law (k_c, p), unchecked, whose door names itself `door` in its messages
 * (src/greenconv/api/capi_law.f90): the law door then checks it as the (k_c, p) door did. */
int greenconv_law_for_door(const char *door, double k_c, double p, gc_law **law);

int gc_run_contact(gc_convolver *conv, double k_c, double p, double preload, int n_steps, const double *road,
                   double *displacement, double *force, double *compression, char *errmsg, size_t errmsg_len)
{
    return gc_run_contact_opts(conv, k_c, p, preload, n_steps, road, NULL, displacement, force, compression, errmsg,
                               errmsg_len);
}

int gc_run_contact_opts(gc_convolver *conv, double k_c, double p, double preload, int n_steps, const double *road,
                        const gc_contact_options *options, double *displacement, double *force, double *compression,
                        char *errmsg, size_t errmsg_len)
{
    gc_law *law = NULL;
    int status = greenconv_law_for_door("gc_run_contact", k_c, p, &law);
    if (status == GC_OK)
        status = gc_run_contact_law(conv, law, preload, n_steps, road, options, displacement, force, compression,
                                    errmsg, errmsg_len);
    gc_law_free(law);
    return status;
}

int gc_contact_start(gc_convolver *conv, double k_c, double p, double preload, const gc_contact_options *options,
                     char *errmsg, size_t errmsg_len)
{
    gc_law *law = NULL;
    int status = greenconv_law_for_door("gc_contact_start", k_c, p, &law);
    if (status == GC_OK) status = gc_contact_start_law(conv, law, preload, options, errmsg, errmsg_len);
    gc_law_free(law);
    return status;
}

int gc_contact_step(gc_convolver *conv, double k_c, double p, double preload, double road, double *displacement,
                    double *force, double *compression)
{
    gc_law *law = NULL;
    int status = greenconv_law_for_door("gc_contact_step", k_c, p, &law);
    if (status == GC_OK) status = gc_contact_step_law(conv, law, preload, road, displacement, force, compression);
    gc_law_free(law);
    return status;
}

/* The checks a multi-point (k_c, p) door makes before it reads its arrays, its messages naming
 * `door` (src/greenconv/api/capi_multi.f90); starts: the door starts a stepped run. */
int greenconv_multi_check_for_door(const char *door, gc_multi_convolver *conv, int n_points, int n_steps,
                                   int n_arrays, const void *const *arrays, const char *names, int starts,
                                   char *errmsg, size_t errmsg_len);

static void free_laws(gc_law **laws, int n_points)
{
    for (int i = 0; i < n_points; ++i) gc_law_free(laws[i]);
    free(laws);
}

/* The power laws (k_c[i], p[i]) of n_points checked points for the door `door`, or NULL
 * (status 3 and its message) when memory runs out. */
static gc_law **power_laws(const char *door, int n_points, const double *k_c, const double *p, char *errmsg,
                           size_t errmsg_len)
{
    gc_law **laws = calloc((size_t)n_points, sizeof *laws);
    for (int i = 0; laws != NULL && i < n_points; ++i) {
        if (greenconv_law_for_door(door, k_c[i], p[i], &laws[i]) != GC_OK) {
            free_laws(laws, n_points);
            laws = NULL;
        }
    }
    if (laws == NULL && errmsg != NULL && errmsg_len > 0)
        snprintf(errmsg, errmsg_len, "%s: out of memory for the laws of %d points", door, n_points);
    return laws;
}

int gc_multi_contact_start(gc_multi_convolver *conv, int n_points, const double *k_c, const double *p,
                           const double *preload, char *errmsg, size_t errmsg_len)
{
    static const char door[] = "gc_multi_contact_start";
    const void *arrays[] = {k_c, p, preload};
    int status = greenconv_multi_check_for_door(door, conv, n_points, 1, 3, arrays, "k_c, p and preload", 1,
                                                errmsg, errmsg_len);
    if (status != GC_OK) return status;
    gc_law **laws = power_laws(door, n_points, k_c, p, errmsg, errmsg_len);
    if (laws == NULL) return GC_ERROR_NUMERICAL;
    status = gc_multi_contact_start_law(conv, n_points, (const gc_law *const *)laws, preload, errmsg, errmsg_len);
    free_laws(laws, n_points);
    return status;
}

int gc_multi_run_contact(gc_multi_convolver *conv, int n_points, int n_steps, const double *k_c, const double *p,
                         const double *preload, const double *road, double *displacement, double *force,
                         double *compression, char *errmsg, size_t errmsg_len)
{
    static const char door[] = "gc_multi_run_contact";
    const void *arrays[] = {k_c, p, preload, road, displacement, force};
    int status = greenconv_multi_check_for_door(door, conv, n_points, n_steps, 6, arrays,
                                                "k_c, p, preload, road, displacement and force", 0, errmsg,
                                                errmsg_len);
    if (status != GC_OK) return status;
    gc_law **laws = power_laws(door, n_points, k_c, p, errmsg, errmsg_len);
    if (laws == NULL) return GC_ERROR_NUMERICAL;
    status = gc_multi_run_contact_law(conv, n_points, n_steps, (const gc_law *const *)laws, preload, road,
                                      displacement, force, compression, errmsg, errmsg_len);
    free_laws(laws, n_points);
    return status;
}

/* The estimate and accuracy doors of both handle types (src/greenconv/api/capi_multi.f90):
 * single not 0 for the single-point door, whose name its messages give. */
int greenconv_estimate_door(int single, const gc_multi_convolver *conv, double *estimate, char *errmsg,
                            size_t errmsg_len);
int greenconv_accuracy_door(int single, gc_multi_convolver *conv, double accuracy, char *errmsg, size_t errmsg_len);

int gc_multi_estimate(const gc_multi_convolver *conv, double *estimate, char *errmsg, size_t errmsg_len)
{
    return greenconv_estimate_door(0, conv, estimate, errmsg, errmsg_len);
}

int gc_convolver_estimate(const gc_convolver *conv, double *estimate, char *errmsg, size_t errmsg_len)
{
    return greenconv_estimate_door(1, (const gc_multi_convolver *)conv, estimate, errmsg, errmsg_len);
}

int gc_multi_set_accuracy(gc_multi_convolver *conv, double accuracy, char *errmsg, size_t errmsg_len)
{
    return greenconv_accuracy_door(0, conv, accuracy, errmsg, errmsg_len);
}

int gc_convolver_set_accuracy(gc_convolver *conv, double accuracy, char *errmsg, size_t errmsg_len)
{
    return greenconv_accuracy_door(1, (gc_multi_convolver *)conv, accuracy, errmsg, errmsg_len);
}

int gc_convolver_history(const gc_convolver *conv, double *displacement)
{
    return gc_multi_history((const gc_multi_convolver *)conv, 1, displacement, NULL, 0);
}

int gc_convolver_push(gc_convolver *conv, double force)
{
    return gc_multi_push((gc_multi_convolver *)conv, 1, &force, NULL, 0);
}

int gc_convolver_instant_weight(const gc_convolver *conv, double *weight)
{
    return gc_multi_instant_matrix((const gc_multi_convolver *)conv, 1, weight, NULL, 0);
}

int gc_convolver_reset(gc_convolver *conv)
{
    return gc_multi_reset((gc_multi_convolver *)conv, NULL, 0);
}

void gc_multi_free(gc_multi_convolver *conv)
{
    gc_convolver_free((gc_convolver *)conv);
}

void gc_multi_delete(gc_multi_convolver **conv)
{
    gc_convolver_delete((gc_convolver **)conv);
}
