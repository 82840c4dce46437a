/*
 * greenconv.h - C and C++ interface of greenconv: fast convolution with Green's functions
 * and dynamic contact (after Meftah, Duhamel, Cesbron, Yin, CSMA 2011, hal-00668511).
 *
 * Link: `pkg-config --cflags --libs greenconv` after `make install`, or by hand
 *     cc prog.c -Iinclude build/make/libgreenconv.a -lgfortran -lgomp -llapack -lblas -lfftw3 -lm
 *
 * Units are SI throughout: s, m, N, kg; stiffness N/m, contact stiffness N/m^p, poles rad/s,
 * residues and impulse-response samples m/(N*s), receptances m/N, frequencies Hz.
 *
 * Conventions.
 * - Functions return a status: GC_OK (0) on success, GC_ERROR_INPUT (2) for a bad value,
 *   file or NULL pointer, GC_ERROR_NUMERICAL (3) for a numerical failure (a failed fit, a
 *   contact run that diverged); gc_run_scene and the multi-point doors also GC_ACCURACY
 *   (4), a run outside the accuracy asked. These are the status codes of the library's
 *   Fortran error type (greenconv_core_error).
 * - Functions that take `char *errmsg, size_t errmsg_len` write a one-line message there on
 *   failure ("" on success): the whole message when errmsg_len exceeds its length, else its
 *   first errmsg_len - 1 bytes; always NUL-terminated when errmsg_len >= 1. errmsg may be
 *   NULL and errmsg_len may be 0: nothing is written then. Messages have no length limit.
 *   There is no global "last error": nothing is kept between calls.
 * - A NULL handle or a NULL output pointer that is not documented as optional gives
 *   GC_ERROR_INPUT, never a crash.
 * - Strings passed in are NUL-terminated. Arrays are plain C arrays of the stated length.
 * - A gc_convolver is an opaque object made by a gc_convolver_new_* function and released by
 *   gc_convolver_delete(&conv), which frees it and sets your pointer to NULL, so that a second
 *   delete does nothing and any other call with conv is refused (GC_ERROR_INPUT, a NULL
 *   handle). gc_convolver_free(conv) frees it without touching your pointer: every call with
 *   that pointer afterwards, a second free included, is undefined. Multi-point handles alike:
 *   gc_multi_delete(&conv), gc_multi_free(conv). Objects are independent: two simulations in
 *   one program do not interfere.
 *
 * Threads. Different convolvers may be used from different threads at the same time; one
 * convolver must not be used by two threads at once. The library built by the Makefile is
 * compiled with OpenMP, which serialises FFTW's planner (plan creation and destruction, done
 * when an "fft" convolver first runs and when it is freed) from any thread. A build without
 * OpenMP (e.g. fpm's default) leaves that to the caller: create, first run and free "fft"
 * convolvers from one thread at a time, or call fftw_make_planner_thread_safe() first.
 * Known limit (doc/library.md, "Threads"): building, stepping and refusing convolvers from two threads
 * is checked (make thread-stress, thread-helgrind); scene and universal files are read through code that
 * still shares a static string length between threads: read them from one thread at a time.
 *
 * The convolution (eq. 20 of the paper): a convolver holds the force history q(t_m) [N]
 * pushed so far and gives the displacement
 *     u(t_n) = u_h(n) + w0*q(t_n),   u_h(n) = sum_{m<n} w(n-m)*q(t_m),   t_n = n*dt,
 * where u_h(n) is the history displacement (gc_convolver_history) and w0 the instantaneous
 * weight (gc_convolver_instant_weight, 0 for the paper's scheme on a mass-spring).
 *
 * Methods (the `method` string): "direct" (the truncated sum, cost per step ~ N_g),
 * "fft" (the same sum by partitioned FFT, ~ log N_g), "modal" = "recursive" (modal recursion
 * with decaying factors, ~ N_m), "paper" (the paper's recursion, eqs. 15-17), "exact"
 * (force linear within a step, integrated exactly), "backward" (the force of a step held
 * from the step before it to it: with the implicit contact scheme a backward-Euler contact
 * spring), "auto" (the cheapest of these that meets a relative accuracy of 1e-3). "direct"
 * and "fft" truncate g where it falls below 1 % of max|g| (the paper's rule), never beyond
 * n_steps samples. Both numbers can be changed with gc_build_options and the *_opts
 * constructors.
 */
#ifndef GREENCONV_H
#define GREENCONV_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/** Version of the library this header describes (fpm.toml's `version`; `make ctest` checks
 *  that it equals what gc_version reports). */
#define GREENCONV_VERSION "0.2.0"

/**
 * The version of the library linked, "major.minor.patch" (fpm.toml's `version`), written to
 * text (at most text_len bytes, NUL-terminated, as every message). Returns GC_OK when all of
 * it fitted (16 bytes are plenty), GC_ERROR_INPUT when text is NULL or too short. Keeps no
 * state: safe from any thread.
 */
int gc_version(char *text, size_t text_len);

/** Status codes returned by the functions below. */
enum gc_status {
    GC_OK = 0,              /**< success */
    GC_ERROR_INPUT = 2,     /**< bad input: a value out of range, an unreadable file, a NULL handle */
    GC_ERROR_NUMERICAL = 3, /**< numerical failure: overflow, divergence, failed fit */
    GC_ACCURACY = 4         /**< ran, but outside the accuracy asked: gc_run_scene when the run ended and wrote
                                 all its files but a method's own accuracy estimate exceeds the scene's
                                 `accuracy` (the message and the summary line name the method, the estimate and
                                 what to do; 2 and 3 take priority); gc_multi_set_accuracy,
                                 gc_multi_contact_start and gc_multi_run_contact when the host asked an accuracy
                                 that the multi-point convolver's own estimate (gc_multi_estimate) exceeds, their
                                 results whole; gc_convolver_set_accuracy, gc_run_contact, gc_run_contact_opts
                                 and gc_contact_start alike for a single-point convolver (gc_convolver_estimate) */
};

/** Opaque convolver: one structure's Green's function and one force history. */
typedef struct gc_convolver gc_convolver;

/** Settings of a new convolver (the *_opts constructors). Fill with gc_build_options_init. */
typedef struct gc_build_options {
    double truncation_tol; /**< "direct", "fft": truncate g below this fraction of max|g|, in (0, 1); 0.01 */
    double accuracy;       /**< "auto": the relative accuracy (largest error E, eq. 7) to meet, > 0; 1e-3 */
} gc_build_options;

/** Contact schemes (gc_contact_options.scheme). */
enum gc_scheme {
    GC_SCHEME_EXPLICIT = 0, /**< the paper's step: the force from the history displacement alone */
    GC_SCHEME_IMPLICIT = 1  /**< force, compression and displacement of a step solved together
                                 (safeguarded Newton); needs w0 >= 0, gains with w0 > 0 ("exact",
                                 "backward") */
};

/** How a contact run steps and when it gives up. Fill with gc_contact_options_init. */
typedef struct gc_contact_options {
    int scheme;              /**< GC_SCHEME_EXPLICIT (default) or GC_SCHEME_IMPLICIT */
    int max_iterations;      /**< implicit step: most Newton/bisection iterations per step, >= 1; 100 */
    double divergence_bound; /**< largest |u| [m] accepted; beyond it (or NaN) the run stops; 0.1 m */
    double tolerance;        /**< implicit step: residual tolerance relative to the compression, > 0; 1e-12 */
} gc_contact_options;

/* ---- creating and freeing convolvers ------------------------------------------------ */

/**
 * Convolver of a damped mass-spring system (mass [kg], stiffness [N/m], damping ratio in
 * [0, 1)), stepped every dt [s] for at most n_steps steps, by `method`. On success *conv is
 * the new convolver, at step 0; on failure NULL. Every constructor refuses (GC_ERROR_INPUT) a
 * "direct", "fft" or "auto" kernel on modes above 1e8 stored values (N_g*N_c^2 + 2*N_g*N_c,
 * N_g from the slowest decay and n_steps), the scenes' cap; its peak memory is about 18
 * ("direct") or 34 ("fft") bytes per value (doc/reliability.md).
 */
int gc_convolver_new_sdof(double mass, double stiffness, double damping_ratio, double dt,
                          const char *method, int n_steps, gc_convolver **conv,
                          char *errmsg, size_t errmsg_len);

/**
 * Convolver of a structure given by n_modes modes in pole-residue form,
 *     g(t) = sum_k 2*Re(r_k*exp(lambda_k*t))  [m/(N*s)],
 * poles lambda_k = pole_re[k] + i*pole_im[k] [rad/s] with pole_re < 0 and pole_im > 0,
 * residues r_k = residue_re[k] + i*residue_im[k] [m/(N*s)]. (The paper's eq. (6) with real
 * amplitude A_k [1/kg] is r_k = A_k/(2i*omega_dk), omega_dk = pole_im.)
 */
int gc_convolver_new_modes(int n_modes, const double *pole_re, const double *pole_im,
                           const double *residue_re, const double *residue_im, double dt,
                           const char *method, int n_steps, gc_convolver **conv,
                           char *errmsg, size_t errmsg_len);

/**
 * Convolver of a structure known only by its impulse response sampled at the time step,
 * g[n] = g(n*dt) [m/(N*s)], n = 0..n_samples-1 (n_samples >= 2). Methods "direct" and "fft".
 */
int gc_convolver_new_samples(int n_samples, const double *g, double dt, const char *method,
                             int n_steps, gc_convolver **conv, char *errmsg, size_t errmsg_len);

/**
 * Convolver of a structure known by a receptance file: lines starting with '#' are comments,
 * then columns f [Hz], Re G, Im G [m/N] on a uniform grid from 0 Hz. The modal methods run on
 * modes identified as a scene's `frf_file` model identifies them: by maximum likelihood, the
 * order chosen by MDL up to max_modes modes (30 is usual) and the noise model from the data
 * (gc_convolver_new_frf_file_ident selects LSCE instead, which uses tol_e: the smallest model
 * with error E <= tol_e, eq. 7; 1e-6 is usual); "direct" and "fft" on g from the inverse FFT
 * of G (dt must then be a whole multiple of 1/(2*f_max)).
 */
int gc_convolver_new_frf_file(const char *path, double dt, const char *method, int n_steps,
                              double tol_e, int max_modes, gc_convolver **conv,
                              char *errmsg, size_t errmsg_len);

/**
 * Free *conv and everything it holds (FFTW plans included) and set *conv to NULL: the safe way
 * to free. Calling it again on the same variable does nothing, and every other call with the
 * NULL handle is refused (GC_ERROR_INPUT). conv == NULL or *conv == NULL: nothing.
 */
void gc_convolver_delete(gc_convolver **conv);

/**
 * Free a convolver and everything it holds (FFTW plans included); NULL: nothing. conv itself
 * (and every copy of it) then points at freed memory: every call with it afterwards is
 * undefined, a second gc_convolver_free included, and so are gc_convolver_history, _push,
 * _reset, _describe, gc_contact_step, gc_run_contact and every other function taking conv.
 * The library marks the object before freeing it, so such a call soon after the free is
 * usually refused as a NULL handle (GC_ERROR_INPUT), but once the memory is given out again
 * nothing can tell: prefer gc_convolver_delete(&conv).
 */
void gc_convolver_free(gc_convolver *conv);

/** Fill *options with the library's defaults (truncation_tol 0.01, accuracy 1e-3). */
int gc_build_options_init(gc_build_options *options);

/**
 * The constructors above with build options (NULL: the defaults; the constructors above are
 * these with options = NULL), e.g. a finer truncation
 * of g for "direct" and "fft" or another accuracy for "auto". Bad options give
 * GC_ERROR_INPUT with a message naming them.
 */
int gc_convolver_new_sdof_opts(double mass, double stiffness, double damping_ratio, double dt,
                               const char *method, int n_steps, const gc_build_options *options,
                               gc_convolver **conv, char *errmsg, size_t errmsg_len);
int gc_convolver_new_modes_opts(int n_modes, const double *pole_re, const double *pole_im,
                                const double *residue_re, const double *residue_im, double dt,
                                const char *method, int n_steps, const gc_build_options *options,
                                gc_convolver **conv, char *errmsg, size_t errmsg_len);
int gc_convolver_new_samples_opts(int n_samples, const double *g, double dt, const char *method,
                                  int n_steps, const gc_build_options *options,
                                  gc_convolver **conv, char *errmsg, size_t errmsg_len);
int gc_convolver_new_frf_file_opts(const char *path, double dt, const char *method, int n_steps,
                                   double tol_e, int max_modes, const gc_build_options *options,
                                   gc_convolver **conv, char *errmsg, size_t errmsg_len);

/**
 * gc_convolver_new_frf_file_opts with the identification method: "ml" (maximum likelihood,
 * the default, as a scene's `&identification method`) or "lsce" (the smallest model with
 * E <= tol_e up to max_modes modes); NULL or "" for the default. Another name gives
 * GC_ERROR_INPUT naming the methods that identify one receptance.
 */
int gc_convolver_new_frf_file_ident(const char *path, double dt, const char *method, int n_steps,
                                    const char *identification, double tol_e, int max_modes,
                                    const gc_build_options *options, gc_convolver **conv,
                                    char *errmsg, size_t errmsg_len);

/* ---- stepping a convolver ------------------------------------------------------------- */

/*
 * A single-point convolver is the multi-point convolver of one point (one object behind both
 * handle types): gc_convolver_history, _push, _instant_weight and _reset are gc_multi_history,
 * _push, _instant_matrix and _reset with n_points = 1 and no message buffer, and refuse a
 * handle of more points (GC_ERROR_INPUT).
 */

/** History displacement u_h(n) [m] at t_n from the forces pushed so far. */
int gc_convolver_history(const gc_convolver *conv, double *displacement);

/**
 * Record the force q(t_n) [N] of the current step and advance to step n + 1.
 *
 * "direct" and "fft" cut g at the n_steps they were made for when it has not decayed below
 * the truncation level by then: such a convolver is valid for n_steps steps only, and
 * gc_convolver_history, gc_convolver_push, gc_contact_step, gc_contact_advance and
 * gc_run_contact refuse a later step with GC_ERROR_INPUT (the messages say so) instead of
 * returning a short, wrong sum. Make the convolver for the whole run, or use a modal method.
 */
int gc_convolver_push(gc_convolver *conv, double force);

/** Instantaneous weight w0 [m/N]: displacement per newton of the current step's own force. */
int gc_convolver_instant_weight(const gc_convolver *conv, double *weight);

/** Forget every force pushed: back to step 0, the structure at rest. */
int gc_convolver_reset(gc_convolver *conv);

/** Size of the model: N_g kernel samples ("direct", "fft") or N_m modes. */
int gc_convolver_model_size(const gc_convolver *conv, int *size);

/**
 * "method: what the model neglects" (for "auto": what it chose and why), written to text
 * (at most text_len bytes, NUL-terminated; text may be NULL).
 */
int gc_convolver_describe(const gc_convolver *conv, char *text, size_t text_len);

/**
 * The warnings of the identification the convolver's structure came from (a receptance
 * file: wrap-around, a fit that missed tol_e, dropped unstable poles), "; " between them,
 * "" when there are none, written to text as gc_convolver_describe does. A constructor that
 * succeeds with a warning still returns GC_OK: ask this before trusting an identified model.
 */
int gc_convolver_warnings(const gc_convolver *conv, char *text, size_t text_len);

/* ---- dynamic contact ----------------------------------------------------------------- */

/*
 * The contact (eqs. 21-24): the body displacement u [m] and the road height u_r [m] point
 * up, u is measured from the static equilibrium under the preload F0 [N]; the compression is
 * delta = delta0 + u_r - u with delta0 the compression that carries F0; the contact force is
 * F(delta) for delta > 0, else 0; the structure is loaded by F - F0. Each step is explicit:
 * delta from the history displacement u_h. The law F(delta) is a gc_law, or, at the doors that
 * take (k_c, p), the power law F = k_c*delta^p (p = 1.5: Hertz, p = 1: linear spring), which
 * are the `_law` doors with that law.
 */

/**
 * A contact law: an opaque object made by gc_law_new from a name of the law registry and its
 * parameter values (SI units, in this order), freed by gc_law_free:
 *   "power"        F = k_c*delta^p:                  k_c [N/m^p] > 0, p > 0
 *   "exponential"  F = F_s*(exp(delta/delta_s) - 1): F_s [N] > 0, delta_s [m] > 0
 *                  (pressure-overclosure: soft at first touch, stiffening without bound)
 * A law is read-only once made: one law may serve several convolvers, points and threads.
 */
typedef struct gc_law gc_law;

/** Make a law: GC_ERROR_INPUT for an unknown name (the message lists the laws), a wrong count
 *  or a value out of range (the message names the parameter, its unit and range, and the
 *  value), *law then NULL. */
int gc_law_new(const char *name, const double *parameters, int n_parameters, gc_law **law, char *errmsg,
               size_t errmsg_len);
/** Free a law (NULL: nothing); the contact runs it was given to do not keep it. */
void gc_law_free(gc_law *law);
/** The force F(delta) [N] at a compression delta [m] (0 for delta <= 0) into *force. */
int gc_law_force(const gc_law *law, double compression, double *force);
/** The compression [m] that carries a force F >= 0 [N] (the static compression under a
 *  preload) into *compression; GC_ERROR_INPUT for F < 0. */
int gc_law_compression(const gc_law *law, double force, double *compression);

/** gc_contact_step with a law. */
int gc_contact_step_law(gc_convolver *conv, const gc_law *law, double preload, double road,
                        double *displacement, double *force, double *compression);
/** gc_run_contact_opts with a law (options NULL: the defaults). */
int gc_run_contact_law(gc_convolver *conv, const gc_law *law, double preload, int n_steps,
                       const double *road, const gc_contact_options *options, double *displacement,
                       double *force, double *compression, char *errmsg, size_t errmsg_len);
/** gc_contact_start with a law; then gc_contact_advance as for gc_contact_start. */
int gc_contact_start_law(gc_convolver *conv, const gc_law *law, double preload,
                         const gc_contact_options *options, char *errmsg, size_t errmsg_len);

/**
 * One contact step: road height `road` [m] at this step in; displacement u [m], contact force
 * F [N] and (unless compression is NULL) compression delta [m] out; the convolver advanced.
 * Start from a new or reset convolver. A step whose u, F or delta is not finite (a road height
 * that is NaN or infinite, a step that diverged) is a fault, as in gc_multi_contact_step:
 * GC_ERROR_NUMERICAL, the outputs 0, the convolver not advanced.
 */
int gc_contact_step(gc_convolver *conv, double k_c, double p, double preload, double road,
                    double *displacement, double *force, double *compression);

/**
 * A whole contact run of n_steps steps (the convolver is reset first) on the road heights
 * road[n] = u_r(n*dt) [m]: displacement[n] [m], force[n] [N] and, unless NULL,
 * compression[n] [m]. The same loop as the greenconv driver, with the explicit step.
 * A run that diverges (|u| beyond 0.1 m, or a NaN or infinite value, e.g. from a NaN road
 * height) stops: GC_ERROR_NUMERICAL, the message names the step and its time, the outputs
 * hold the steps before it and 0 from that step on.
 */
int gc_run_contact(gc_convolver *conv, double k_c, double p, double preload, int n_steps,
                   const double *road, double *displacement, double *force, double *compression,
                   char *errmsg, size_t errmsg_len);

/** Fill *options with the defaults: the explicit scheme, bound 0.1 m, 1e-12, 100 iterations. */
int gc_contact_options_init(gc_contact_options *options);

/**
 * gc_run_contact with contact options (NULL: the defaults), e.g. the implicit scheme. Bad
 * options give GC_ERROR_INPUT naming the field; an implicit step that does not converge,
 * GC_ERROR_NUMERICAL naming the step, the outputs then as for a divergent run.
 */
int gc_run_contact_opts(gc_convolver *conv, double k_c, double p, double preload, int n_steps,
                        const double *road, const gc_contact_options *options,
                        double *displacement, double *force, double *compression,
                        char *errmsg, size_t errmsg_len);

/**
 * Start a contact run stepped one call at a time with options (NULL: the defaults): the
 * convolver is reset, the body at rest under the preload. Then call gc_contact_advance once
 * per step. The run ends at its first fault, at gc_convolver_reset or at a new start; do not
 * mix gc_contact_step or gc_convolver_push into it.
 */
int gc_contact_start(gc_convolver *conv, double k_c, double p, double preload,
                     const gc_contact_options *options, char *errmsg, size_t errmsg_len);

/**
 * The next step of the run gc_contact_start began, with its scheme: road height in;
 * displacement [m], force [N] and (unless NULL) compression [m] out. A divergent or
 * unconverged step gives GC_ERROR_NUMERICAL naming the step, outputs 0, and ends the run;
 * without a run going on, GC_ERROR_INPUT. A run stepped this way equals gc_run_contact_opts
 * on the same road bit for bit.
 */
int gc_contact_advance(gc_convolver *conv, double road, double *displacement, double *force,
                       double *compression, char *errmsg, size_t errmsg_len);

/**
 * The method's own estimate of the relative error of the contact forces of the convolver's
 * run, ||F - F_true||/||F_true - F0||, into *estimate: the model's terms (0 for modes given
 * exactly, E of eq. (7) of the modes identified from a receptance file, the truncation and
 * wrap-around of a sampled g) plus the time-step term of the run going on (gc_contact_start,
 * gc_contact_advance) or last run (gc_run_contact, gc_run_contact_opts): the same run at 2*dt
 * and 4*dt on every second and fourth road height, with the same scheme, by Richardson
 * (8 steps or more; about 3/4 of the run's cost). gc_contact_step adds no term.
 * GC_ERROR_INPUT for a NULL pointer.
 */
int gc_convolver_estimate(const gc_convolver *conv, double *estimate, char *errmsg, size_t errmsg_len);

/**
 * The relative accuracy the host asks of the convolver's runs (> 0; 0: none, the default).
 * Returns GC_ACCURACY at once (the accuracy kept) when gc_convolver_estimate exceeds it; from
 * then on gc_run_contact, gc_run_contact_opts (with the run's own time-step term) and
 * gc_contact_start return GC_ACCURACY, their results whole, with a message naming the
 * estimate, the accuracy and what to do. GC_ERROR_INPUT for a negative or non-finite accuracy.
 */
int gc_convolver_set_accuracy(gc_convolver *conv, double accuracy, char *errmsg, size_t errmsg_len);

/* ---- identification and scenes -------------------------------------------------------- */

/**
 * Identify modes from a receptance file (format as gc_convolver_new_frf_file) by LSCE: at
 * most `capacity` modes written to the four arrays, lowest natural frequency first, their
 * number in *n_modes (status GC_ERROR_INPUT if it exceeds capacity) and the fit's error E
 * (eq. 7) in *error_e. GC_ERROR_INPUT, naming the argument, for a NULL path or output pointer,
 * a negative capacity, or max_modes outside 1..200.
 */
int gc_identify_frf_file(const char *path, double tol_e, int max_modes, int capacity,
                         int *n_modes, double *pole_re, double *pole_im, double *residue_re,
                         double *residue_im, double *error_e, char *errmsg, size_t errmsg_len);

/**
 * Identify modes from a receptance file (columns as gc_convolver_new_frf_file, or a universal
 * file's dataset 58) by maximum likelihood, as a scene's method 'ml': the order by MDL, the
 * noise model noise_model ("auto": the one of the highest likelihood with its MDL price among
 * "relative", "absolute", "floor" and "band"; NULL means "auto"), the stabilisation diagram up
 * to max_order modes (1..200). At most `capacity` modes, lowest natural frequency first: poles
 * [rad/s], residues [m/(N*s)], the standard deviations sigma_f [Hz] and sigma_xi, and
 * determined[k] = 1 when the data determine mode k, 0 for a pole of the fitted receptance they
 * do not (the column `determined` of a scene's modes file). *n_modes is set even when it
 * exceeds capacity (then GC_ERROR_INPUT); *n_determined counts the ones.
 */
int gc_identify_ml_file(const char *path, const char *noise_model, int max_order, int capacity,
                        int *n_modes, int *n_determined, double *pole_re, double *pole_im,
                        double *residue_re, double *residue_im, double *sigma_f, double *sigma_xi,
                        int *determined, char *errmsg, size_t errmsg_len);

/**
 * Run a scene namelist file as the greenconv driver does: one column file per method in the
 * scene's output_dir, a summary line per method on standard output (Fortran's unit, flushed
 * on return: call fflush(stdout) before, to keep the order of lines).
 */
int gc_run_scene(const char *path, char *errmsg, size_t errmsg_len);

#ifdef __cplusplus
}
#endif

#endif /* GREENCONV_H */

/* ======================================================================================== *
 * Multi-point contact (N_c contact points, all forces of a step solved together)            *
 * ======================================================================================== */
/*
 * A gc_multi_convolver holds the Green's matrix g_ij(t) [m/(N*s)] of a structure touched at
 * N_c points (the displacement at i per unit impulse at j) and steps the matrix form of
 * eq. (20): u(t_n) = u_h(n) + W0*q(t_n), u_h(n) the history displacements of all points,
 * W0 the N_c x N_c instant compliance (zero for the explicit methods "modal"/"recursive",
 * "direct" and "fft" on modal g; non-zero for "exact", solved by Newton at every step).
 *
 * Conventions as above (status GC_OK / GC_ERROR_INPUT / GC_ERROR_NUMERICAL / GC_ACCURACY, a message in
 * errmsg on every call, NULL checked). Arrays are laid out first index fastest (as Fortran
 * stores them):
 *     shape[k*n_points + i]                 = phi_ik, mode k at point i
 *     g[(j*n_points + i)*n_samples + m]     = g_ij(m*dt)
 *     road[i*n_steps + n], and the outputs  = value at point i, step n
 *     w0[j*n_points + i]                    = W0_ij [m/N]
 * Functions taking `n_points` check it against the convolver's N_c (GC_ERROR_INPUT, naming
 * n_points, when they differ; a negative n_points too).
 *
 * Contact, per point i (as the single-point run): compression delta_i = delta0_i + u_r,i - u_i,
 * delta0_i = (F0_i/k_c,i)^(1/p_i); F_i = k_c,i*delta_i^p_i in compression, 0 otherwise; the
 * structure is loaded by F - F0 and rests in static equilibrium at step 0. A step that
 * diverges (|u_i| above the bound, or not finite) or whose Newton iteration does not converge
 * returns GC_ERROR_NUMERICAL with a message naming the step, its time and the point.
 */
#ifndef GREENCONV_MULTI_H
#define GREENCONV_MULTI_H

#ifdef __cplusplus
extern "C" {
#endif

/** Opaque multi-point convolver (a Green's matrix of N_c points). */
typedef struct gc_multi_convolver gc_multi_convolver;

/**
 * A multi-point convolver from modes shared by the points:
 *     g_ij(t) = sum_k phi_ik*phi_jk*2*Re(r_k*exp(lambda_k*t)),
 * poles lambda_k = pole_re + i*pole_im [rad/s] (damped: pole_re < 0 < pole_im), residues r_k of
 * the unit modal impulse responses (1/(2i*omega_d,k) [1/(kg*s)] for modes of unit modal mass,
 * phi then in 1/sqrt(kg)), shape as above. This is a rank-one residue matrix r_k*phi_k*phi_k^T
 * per mode; a general residue matrix is not accepted. method: "modal" (= "recursive"),
 * "exact", "direct" or "fft"; options: truncation_tol for "direct"/"fft" (accuracy unused),
 * NULL for the defaults.
 */
int gc_multi_new_modes(int n_points, int n_modes, const double *pole_re, const double *pole_im,
                       const double *residue_re, const double *residue_im, const double *shape,
                       double dt, const char *method, int n_steps, const gc_build_options *options,
                       gc_multi_convolver **conv, char *errmsg, size_t errmsg_len);

/**
 * A multi-point convolver from samples g_ij(m*dt) [m/(N*s)], m = 0..n_samples-1 ("direct" or
 * "fft"), truncated where max_ij |g_ij| falls below truncation_tol of its maximum (the paper's
 * rule; 0 keeps every sample), never beyond n_steps. W0 = dt*g(0): non-zero g_ij(0) make the
 * contact step implicit.
 */
int gc_multi_new_samples(int n_points, int n_samples, const double *g, double dt, const char *method,
                         int n_steps, const gc_build_options *options, gc_multi_convolver **conv,
                         char *errmsg, size_t errmsg_len);

/**
 * A multi-point convolver on a universal file of a Green's matrix (path: nodes with their
 * coordinates in dataset 15 or 2411, datasets 58 of the receptances G_ij(f) [m/N] or of the
 * impulse responses g_ij(t) [m/(N*s)] between them; doc/multipoint.md). Its
 * points are the file's nodes, in the file's order (gc_multi_points). Receptances are
 * identified once with shared poles (a maximum-likelihood pole fit of the summed driving
 * points, its stabilisation diagram up to max_order modes (at most 200, as in scenes), 0 for
 * the library's default 30,
 * then every receptance's residue matrix): "modal"/"exact" run on the identified modes
 * ("exact" with the fit's upper residual in W0), "direct"/"fft" on g_ij from the inverse FFT
 * of the file's receptances when dt fits their grid (from the modes otherwise), as the
 * driver's `&structure model = 'green_file'` does. The identification takes seconds for a
 * dozen points; build further methods on the same file with gc_multi_new_method. What the
 * model neglects: gc_multi_describe; the identification: gc_multi_file_summary.
 * GC_ERROR_INPUT for an unreadable or malformed file (the message names the file and the
 * line) or a method the file cannot serve (modes from impulse responses).
 */
int gc_multi_new_file(const char *path, const char *method, double dt, int n_steps,
                      const gc_build_options *options, int max_order, gc_multi_convolver **conv,
                      char *errmsg, size_t errmsg_len);

/**
 * Another method, time step or run length on the file that gc_multi_new_file read (and
 * identified) into source, without reading or identifying it again: the same convolver as
 * gc_multi_new_file with these arguments and source's max_order would make.
 */
int gc_multi_new_method(const gc_multi_convolver *source, const char *method, double dt, int n_steps,
                        const gc_build_options *options, gc_multi_convolver **conv, char *errmsg,
                        size_t errmsg_len);

/**
 * The points of a convolver made from a file: node labels, x_i [m] (along the travel) and
 * y_i [m] (across) from the file's coordinates, in the convolver's order; any of node, x, y
 * may be NULL. GC_ERROR_INPUT for a convolver made from modes or samples.
 */
int gc_multi_points(const gc_multi_convolver *conv, int n_points, int *node, double *x, double *y,
                    char *errmsg, size_t errmsg_len);

/**
 * What gc_multi_new_file found in its file: E of eq. (7) of the identified modes alone against
 * the file's receptances, worst and mean over the receptances, the number of shared poles (all
 * 0 for a file of impulse responses), each output may be NULL; and into text (clamped as
 * errmsg; the message on failure) the summary in lines starting "# " (the file and its points,
 * the identification with E per receptance and per point and the worst pole uncertainty, the
 * modes), as the driver prints it.
 */
int gc_multi_file_summary(const gc_multi_convolver *conv, double *e_worst, double *e_mean, int *n_poles,
                          char *text, size_t text_len);

/**
 * The modes of the library's tyre belt (a pre-tensioned orthotropic plate on an elastic
 * foundation, default parameters) up to f_max [Hz], seen at an n_x by n_y patch of length x
 * width [m] centred on the belt; point i = iy*n_x + ix at (x[i], y[i]) (x and y may be NULL).
 * At most `capacity` modes (shape: n_x*n_y*capacity values); *n_modes is set even when it
 * exceeds capacity (GC_ERROR_INPUT). The arrays feed gc_multi_new_modes.
 */
int gc_multi_plate_patch(int n_x, int n_y, double length, double width, double f_max, int capacity,
                         int *n_modes, double *pole_re, double *pole_im, double *residue_re,
                         double *residue_im, double *shape, double *x, double *y, char *errmsg,
                         size_t errmsg_len);

/**
 * Free *conv and set it to NULL (conv or *conv NULL: nothing): the safe way to free, as
 * gc_convolver_delete. A second call does nothing; other calls with the NULL handle are refused.
 */
void gc_multi_delete(gc_multi_convolver **conv);
/**
 * Free a multi-point convolver (NULL: nothing), leaving conv pointing at freed memory: every
 * call with it afterwards (gc_multi_free again, gc_multi_history, _push, _contact_step,
 * _run_contact, ...) is undefined, as after gc_convolver_free. Prefer gc_multi_delete(&conv).
 */
void gc_multi_free(gc_multi_convolver *conv);

/** The number of points N_c. */
int gc_multi_n_points(const gc_multi_convolver *conv, int *n_points, char *errmsg, size_t errmsg_len);
/** History displacements u_h,i(n) [m] of all points from the forces pushed so far. */
int gc_multi_history(const gc_multi_convolver *conv, int n_points, double *displacement, char *errmsg,
                     size_t errmsg_len);
/** Record this step's forces q_i(t_n) [N] and advance to the next step. */
int gc_multi_push(gc_multi_convolver *conv, int n_points, const double *force, char *errmsg,
                  size_t errmsg_len);
/** The instant compliance matrix W0 [m/N] (n_points*n_points values). */
int gc_multi_instant_matrix(const gc_multi_convolver *conv, int n_points, double *w0, char *errmsg,
                            size_t errmsg_len);
/** Back to step 0 with no force history (ends a stepped contact run). */
int gc_multi_reset(gc_multi_convolver *conv, char *errmsg, size_t errmsg_len);
/** "method: what the model neglects, N_g (or N_m) = size" into text (the message on failure);
 *  the model size into *model_size unless NULL. */
int gc_multi_describe(const gc_multi_convolver *conv, int *model_size, char *text, size_t text_len);

/** Newton and divergence settings of the next contact runs: relative tolerance of a step's
 *  residual (default 1e-12), most iterations per step (50), largest |u_i| [m] (1). */
int gc_multi_set_newton(gc_multi_convolver *conv, double tolerance, int max_iterations,
                        double divergence_bound, char *errmsg, size_t errmsg_len);

/** Reset the convolver and start a contact run stepped by gc_multi_contact_step: per point,
 *  k_c [N/m^p] > 0, p > 0 and preload F0 [N] >= 0 (the message names a bad point). GC_ACCURACY
 *  when the run started but the method is outside the accuracy asked (gc_multi_set_accuracy). */
int gc_multi_contact_start(gc_multi_convolver *conv, int n_points, const double *k_c, const double *p,
                           const double *preload, char *errmsg, size_t errmsg_len);
/** The next step: road heights u_r,i [m] in; displacements, forces and compressions out
 *  (compression may be NULL; all 0 on a fault, which ends the run). Stepping a whole road
 *  equals gc_multi_run_contact bit for bit. */
int gc_multi_contact_step(gc_multi_convolver *conv, int n_points, const double *road, double *displacement,
                          double *force, double *compression, char *errmsg, size_t errmsg_len);
/** A whole run over n_steps (the convolver reset first); outputs 0 from a fault on
 *  (compression may be NULL). GC_ACCURACY when the run is whole but the method is outside the
 *  accuracy asked (gc_multi_set_accuracy). */
int gc_multi_run_contact(gc_multi_convolver *conv, int n_points, int n_steps, const double *k_c,
                         const double *p, const double *preload, const double *road, double *displacement,
                         double *force, double *compression, char *errmsg, size_t errmsg_len);
/** gc_multi_contact_start with laws: laws[i] is point i's law, n_points handles (one handle may
 *  serve several points); every point has the same law (the same name), its parameters free
 *  per point, else GC_ERROR_INPUT naming the point. The power law with k_c[i], p[i] gives what
 *  gc_multi_contact_start gives. */
int gc_multi_contact_start_law(gc_multi_convolver *conv, int n_points, const gc_law *const *laws,
                               const double *preload, char *errmsg, size_t errmsg_len);
/** gc_multi_run_contact with laws as gc_multi_contact_start_law takes them. */
int gc_multi_run_contact_law(gc_multi_convolver *conv, int n_points, int n_steps, const gc_law *const *laws,
                             const double *preload, const double *road, double *displacement, double *force,
                             double *compression, char *errmsg, size_t errmsg_len);

/**
 * A multi-point convolver on a universal file of normal modes from an FE model (path: nodes
 * with their coordinates in dataset 15 or 2411, one dataset 55 per mode: analysis type 2,
 * natural frequency, modal mass (0: mass-normalised shapes), viscous damping ratio; shapes at
 * the nodes), the same convolver as a scene with `&structure model = 'modes_file'` on every
 * node of the file: its points are the file's nodes in the file's order (gc_multi_points);
 * the shapes are taken in `direction` (1, 2, 3 for X, Y, Z, negative for the opposite sense);
 * damping_ratio in [0, 1) applies to the modes the file gives none; the modes up to f_band [Hz]
 * (0: the Nyquist frequency 1/(2*dt)) are stepped, those above are kept as their static
 * compliance R_ij = sum phi_ik*phi_jk/(m_k*omega_k^2) [m/N] in the instant matrix W0 of "exact",
 * "direct" and "fft" (the explicit "modal" leaves R out and says so), the same convolver as the
 * scene's; gc_multi_describe says how many modes are above the band, R's share of the static
 * flexibility at the points and its largest diagonal term. method: "modal"
 * (= "recursive"), "exact", "direct" or "fft"; options: truncation_tol, NULL for the
 * defaults. Stepped from the host's loop with gc_multi_contact_start/_step (or
 * gc_multi_history/_push) as every multi-point convolver. GC_ERROR_INPUT for a bad argument or
 * an unreadable or malformed file, with the reader's message (the file, dataset, record and
 * field), or no mode in the band.
 */
int gc_multi_new_modes_file(const char *path, int direction, double damping_ratio, double f_band,
                            const char *method, double dt, int n_steps, const gc_build_options *options,
                            gc_multi_convolver **conv, char *errmsg, size_t errmsg_len);

/**
 * The method's own estimate of the relative error of its contact forces,
 * ||F - F_true||/||F_true - F0|| over a run and the points, into *estimate: the model's terms
 * (0 for modes given exactly, E of eq. (7) of the identified modes of gc_multi_new_file, what a
 * sampled kernel leaves out for "direct"/"fft" on a band-limited file) plus, after a whole run
 * (gc_multi_run_contact, 8 steps or more), that run's time-step term (the same run at 2*dt and
 * 4*dt on every second and fourth road height, by Richardson) and, for
 * gc_multi_new_modes_file with modes above its band, the band's term (the same run with the
 * modes up to twice the band); before a run, the share of the static flexibility the modes above
 * the band carry, for a method that leaves it out ("modal", "recursive"). A run stepped one call at a time (gc_multi_contact_start,
 * gc_multi_contact_step) steps the same companions alongside, so that the estimate holds the
 * steps so far at every step (from the 8th on; they cost about 3/4 of the run). GC_ERROR_INPUT
 * for a NULL pointer.
 */
int gc_multi_estimate(const gc_multi_convolver *conv, double *estimate, char *errmsg, size_t errmsg_len);

/**
 * The relative accuracy the host asks of the convolver's runs (> 0; 0: none, the default).
 * Returns GC_ACCURACY at once (the accuracy kept) when gc_multi_estimate exceeds it; from then
 * on gc_multi_contact_start and gc_multi_run_contact return GC_ACCURACY (their results whole,
 * the run started) with a message naming the estimate, the accuracy and what to do (a whole
 * run checks the estimate with its own time-step and band terms);
 * gc_multi_contact_step returns GC_OK for the steps. GC_ERROR_INPUT for a negative or
 * non-finite accuracy.
 */
int gc_multi_set_accuracy(gc_multi_convolver *conv, double accuracy, char *errmsg, size_t errmsg_len);

#ifdef __cplusplus
}
#endif

#endif /* GREENCONV_MULTI_H */
