/* SPDX-License-Identifier: MIT */
/* hy_workprec.h: work-precision measurement (error against a reference and the
 * time it cost) for the hysteresis core: the problems of `hystviz report`,
 * one timed run of a solver, and error norms that `render -v` can reuse.
 *
 * Conventions follow DiffEqDevTools/SciMLBenchmarks: the error of a run is
 * measured on a fixed output grid against a reference solution, as the max
 * norm (L∞) and the discrete L2 norm sqrt(mean(e²)); the time is the median
 * of repeated runs (min and max kept as the spread).  The GSL steppers run as
 * their users run them: they choose their own steps between the input's
 * breakpoints (no step is forced to end at an output time) and the grid
 * values come from the cubic Hermite interpolant of the step ends (hy_ode's
 * dense mode, its cost in the time); err_steps is the error at the step ends
 * themselves, so the interpolant's share of err_max is visible.
 *
 *     hy_wp_problem p;  hy_error err;
 *     if (hy_wp_problem_init(&p, "ex3-g10", 0, &err)) ...
 *     hy_wp_cfg cfg = hy_wp_cfg_defaults();
 *     hy_wp_run r;
 *     hy_wp_run_solver(&p, "rkf45", 1, 1e-6, &cfg, &r);  // r.status, r.err_max, r.t_med
 *     hy_wp_problem_free(&p);
 */
#ifndef HY_WORKPREC_H
#define HY_WORKPREC_H

#include <stddef.h>
#include <stdio.h>

#include "hy_boucwen.h"
#include "hy_input.h"
#include "hy_jiles.h"
#include "hy_model.h"
#include "hy_status.h"

enum { HY_WP_LUGRE = 0, HY_WP_BOUCWEN = 1, HY_WP_JILES = 2 };

/* Run status, as written in the CSV "status" column. */
enum { HY_WP_OK = 0, HY_WP_FAIL, HY_WP_STEPCAP, HY_WP_TIMECAP, HY_WP_SKIPPED };

typedef struct hy_wp_problem {
    char name[32];            /* "ex3-g10", "lugre-stiff", "boucwen"          */
    char title[128];          /* plot title (markup)                          */
    char ref_method[128];     /* how the reference was obtained               */
    int kind;                 /* HY_WP_LUGRE, HY_WP_BOUCWEN or HY_WP_JILES    */
    hy_model model;           /* LuGre kinds                                   */
    hy_input input;
    double gamma;
    hy_boucwen_params bw;     /* Bouc-Wen kind                                 */
    hy_jiles ja;              /* Jiles-Atherton kind (input: H in A/m, output B) */
    double bw_h_ref;          /* reference step (s)                            */
    double *t, *yref;         /* output grid and reference, n points          */
    size_t n;
} hy_wp_problem;

typedef struct hy_wp_cfg {
    int repeats;              /* timed repeats (median), >= 1                 */
    unsigned long max_steps;  /* ODE step cap between two breakpoints (hy_ode) */
    double time_cap;          /* seconds: a run slower than this is not repeated
                                 and tighter tolerances of its solver are skipped */
} hy_wp_cfg;

typedef struct hy_wp_run {
    char problem[32], solver[16];
    int restart;              /* 1: restart at breakpoints, 0: straight, -1: n/a */
    double tol;               /* rtol (atol = rtol · 1e-2 · scale); Bouc-Wen: h   */
    int status;               /* HY_WP_*                                        */
    double err_max, err_l2;   /* on the output grid; NaN unless status is OK    */
    double err_steps;         /* GSL steppers: max error at the integrator's own
                                 step ends (no interpolation), against the exact
                                 reference; NaN where there is none             */
    double t_med, t_min, t_max; /* seconds                                      */
    int repeats;
    unsigned long nfev, njev, steps, fails;
    char msg[160];            /* reason for a non-OK status                    */
} hy_wp_run;

/* repeats 5, 2e5 steps per segment, 2 s time cap. */
hy_wp_cfg hy_wp_cfg_defaults(void);
/* Monotonic wall clock in seconds. */
double hy_wp_now(void);
/* Max-norm and discrete L2 (RMS) of y - yref over n points; non-finite y gives
 * +inf for both.  Either output may be NULL. */
void hy_wp_error(const double *y, const double *yref, size_t n, double *emax, double *el2);
/* Status name for the CSV ("ok", "fail", "stepcap", "timecap", "skipped"). */
const char *hy_wp_status_name(int status);

/* Names of the built-in problems, NULL-terminated. */
const char *const *hy_wp_problem_names(void);
/* Builds problem name with its output grid and reference (quick != 0: coarser
 * reference where it is computed).  HY_EINVAL for an unknown name. */
int hy_wp_problem_init(hy_wp_problem *p, const char *name, int quick, hy_error *err);
void hy_wp_problem_free(hy_wp_problem *p);
/* Nonzero when solver ("exact", a GSL stepper name, "newmark") applies to p. */
int hy_wp_solver_applies(const hy_wp_problem *p, const char *solver);

/* One measured run: solver at tolerance tol (Bouc-Wen: step h = tol) with or
 * without restarts.  Always fills out (a failure is a status, not an error);
 * returns out->status. */
int hy_wp_run_solver(const hy_wp_problem *p, const char *solver, int restart, double tol,
                     const hy_wp_cfg *cfg, hy_wp_run *out);

/* y_γ of Eq. (3) on piecewise-linear inputs by the exact exponential formula
 * in long double, written independently of hy_gamma (a cross-check reference).
 * HY_EUNSUP for a non-linear piece or a filter model. */
int hy_wp_exact_ld(const hy_model *m, const hy_input *in, double gamma, const double *t, size_t n,
                   double *y, hy_error *err);

/* CSV header and one row (all columns of hy_wp_run). */
void hy_wp_csv_header(FILE *f);
void hy_wp_csv_row(FILE *f, const hy_wp_run *r);

#endif
