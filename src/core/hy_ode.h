/* SPDX-License-Identifier: MIT */
/* hy_ode.h: y_γ of Eq. (3) of seed 000 (and system (16)) by GSL odeiv2
 * integration, for any input, with the stepper chosen by name.
 *
 * By default the integration restarts at every breakpoint of u̇ (each piece of
 * the input), so no step straddles a kink; restart = 0 integrates straight
 * through (for work-precision comparisons).  The GSL error handler must be off
 * (gsl_set_error_handler_off) in programs that call this; every status is
 * checked and a failure returns HY_ENUM with the time and the GSL reason.
 * Time is kept as (period index k, time within the period) with k T formed
 * from k, so no error grows with the number of periods; an output time within
 * 8 ulps of a breakpoint or of the current time is served there (never a step
 * of a few ulps, which the implicit and multistep steppers refuse).
 *
 *     hy_ode_opts o = hy_ode_defaults();
 *     o.stepper = "rk8pd"; o.rtol = 1e-10;
 *     hy_ode_stats s;
 *     hy_ode_solve(&m, &in, 10.0, &o, t, n, y, &s, &err);
 */
#ifndef HY_ODE_H
#define HY_ODE_H

#include "hy_input.h"
#include "hy_cancel.h"
#include "hy_model.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct hy_ode_opts {
    const char *stepper;      /* rk2 rk4 rkf45 rkck rk8pd rk1imp rk2imp rk4imp bsimp msadams msbdf */
    double rtol, atol;        /* local error control: atol + rtol |y|          */
    double h0;                /* first step (0: a guess from the piece length) */
    int restart;              /* restart at every breakpoint of u̇ (default 1)  */
    unsigned long max_steps;  /* step cap per segment (0: no cap)              */
    int dense;                /* 0: every output time ends a step; 1: the
                               * stepper chooses its steps between breakpoints
                               * and outputs come from the cubic Hermite
                               * interpolant of its step ends (error O(h^4))   */
    double *trace_t, *trace_y;/* dense: step ends and y there (NULL: none)     */
    size_t trace_cap;         /* room in trace_t, trace_y                      */
    double work_limit;        /* refuse up front (HY_EINVAL, "stiff") when
                               * hy_ode_work_estimate exceeds it; 0: never     */
    const hy_cancel *cancel;  /* asked between pieces and output times; stop:
                               * HY_ECANCEL (NULL: never; hy_cancel.h)        */
} hy_ode_opts;

typedef struct hy_ode_stats {
    unsigned long nfev, njev, steps, fails, restarts;
    size_t ntrace;            /* step ends written to the trace                */
} hy_ode_stats;

/* rkf45, rtol 1e-8, atol 1e-10, restart on, 1e7 steps, output times hit,
 * work limit 1e7 evaluations of f (about a second). */
hy_ode_opts hy_ode_defaults(void);

/* The GSL odeiv2 steppers, one table: HY_ODE_STEPPERS(X) calls
 * X(name, kind, order, place) once per stepper, in the order
 * hy_ode_stepper_names() lists them (`report --solvers`):
 *   kind   HY_ODE_EXPLICIT or HY_ODE_IMPLICIT (hy_ode_work_estimate's bound);
 *   order  the order of a one-step implicit Runge-Kutta stepper, whose
 *          transients the estimate counts; 0: none counted (explicit ones,
 *          bsimp's extrapolation, msbdf's multistep);
 *   place  its place in the scene schema's [gamma] solver values, after
 *          "exact" (0) (hy_scene_schema.c: the documented order).
 * The stepper table of hy_ode.c, the name list and the schema's values are
 * generated from it; a stepper is one line here. */
#define HY_ODE_EXPLICIT 1
#define HY_ODE_IMPLICIT 2
#define HY_ODE_STEPPERS(X)                 \
    X(rk2, HY_ODE_EXPLICIT, 0, 6)          \
    X(rk4, HY_ODE_EXPLICIT, 0, 7)          \
    X(rkf45, HY_ODE_EXPLICIT, 0, 1)        \
    X(rkck, HY_ODE_EXPLICIT, 0, 8)         \
    X(rk8pd, HY_ODE_EXPLICIT, 0, 2)        \
    X(rk1imp, HY_ODE_IMPLICIT, 1, 9)       \
    X(rk2imp, HY_ODE_IMPLICIT, 2, 10)      \
    X(rk4imp, HY_ODE_IMPLICIT, 4, 3)       \
    X(bsimp, HY_ODE_IMPLICIT, 0, 4)        \
    X(msadams, HY_ODE_EXPLICIT, 0, 11)     \
    X(msbdf, HY_ODE_IMPLICIT, 0, 5)
/* An X that counts: (0 HY_ODE_STEPPERS(HY_ODE_COUNT_OF)) steppers. */
#define HY_ODE_COUNT_OF(name, kind, order, place) +1

/* Names of every stepper, NULL-terminated. */
const char *const *hy_ode_stepper_names(void);
/* Nonzero when name is a stepper (0 for NULL). */
int hy_ode_stepper_known(const char *name);

/* A lower bound on the evaluations of f the stepper needs up to t_end, from
 * the stiffness ratio λΔt = σ0|Δu|/g(v/γ) of each input piece (and γΔt/τ for
 * the filter of system (16)), whose maximum goes to *stiff (may be NULL):
 * explicit steppers (rk2 rk4 rkf45 rkck rk8pd msadams) are held to h < 6/λ
 * by stability on every piece, so >= λΔt/6 steps; rk1imp, rk2imp and rk4imp
 * by accuracy to >= rtol^{-1/(p+1)} steps (p = 1, 2, 4) on each piece that
 * starts a run (a fresh transient); bsimp and msbdf: no bound (0).  Steps
 * count as 6 (explicit) or 9 (implicit, Jacobian and solves) evaluations.
 * NaN when m (with its type), in (with pieces) or o is NULL, or t_end is
 * not finite. */
double hy_ode_work_estimate(const hy_model *m, const hy_input *in, double gamma, const hy_ode_opts *o,
                            double t_end, double *stiff);

/* HY_OK when hy_ode_work_estimate up to t_end is within o->work_limit (or
 * the limit is 0), else HY_EINVAL with hy_ode_solve's refusal message: what
 * hy_ode_solve checks first, for a caller that plans several solves and
 * refuses before it starts any.  m, in and o must not be NULL (HY_EINVAL); a
 * work_limit that is negative or not finite (INFINITY would disable the
 * check) and a t_end that is not finite are refused (HY_EINVAL). */
int hy_ode_check_work(const hy_model *m, const hy_input *in, double gamma, const hy_ode_opts *o, double t_end,
                      hy_error *err);

/* y_γ at n ascending times t[] >= 0 from z(0) = m->x0.  stats may be NULL;
 * m, in, o and y_out must not be NULL, nor t when n > 0, and o->trace_t and
 * o->trace_y are both NULL or both given (HY_EINVAL).
 * HY_EINVAL for bad model/γ/options (message names it) and for a run whose
 * work estimate passes o->work_limit (the message says "stiff", the ratio,
 * the estimate and which solvers to use instead), HY_ENUM when GSL fails
 * or the step cap is hit (message gives the time), HY_ENOMEM. */
int hy_ode_solve(const hy_model *m, const hy_input *in, double gamma, const hy_ode_opts *o,
                 const double *t, size_t n, double *y_out, hy_ode_stats *stats, hy_error *err);

#ifdef __cplusplus
}
#endif

#endif
