/* SPDX-License-Identifier: MIT */
/* hy_ref.h: independent long-double references for the closed forms, used to
 * measure the errors that `render -v`, `data` and the gallery print.
 *
 * The limit map of seed 000 (Eq. 4 on a monotone run of variation Δ,
 * direction s, a = σ0/g(0)),
 *     y ← e^{-aΔ} y + s g0 (1 - e^{-aΔ}),
 * is propagated run by run in long double, with run lengths taken from the
 * input's u values; y° is the fixed point of the period map obtained by
 * forward composition (y ↦ A y + B, y° = B/(1 - A)), not by hy_limit's
 * cancellation-free series.  y_γ of Eq. (3) on piecewise-linear inputs is the
 * piecewise exponential in long double.  None of this shares formula code
 * with hy_limit, hy_loops or hy_gamma, so a comparison measures them.
 *
 *     hy_ref_limit R;
 *     hy_ref_limit_init(&R, sigma0, g0, &in, &err);
 *     double e = fabs(hy_steady_at_rho(&st, r) - hy_ref_steady_rho(&R, r));
 *     hy_ref_limit_free(&R);
 */
#ifndef HY_REF_H
#define HY_REF_H

#include "hy_input.h"
#include "hy_model.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct hy_ref_limit {
    const hy_input *in;       /* borrowed                                     */
    long double a, g0, rho_T;
    long double *y_run;       /* y° at the start of each run, nruns + 1      */
    double accuracy;          /* bound on the reference's own error (abs.)  */
} hy_ref_limit;

/* HY_EINVAL for a non-positive or non-finite σ0 or g0, HY_ENOMEM.  R and in
 * (with pieces) must not be NULL (HY_EINVAL; R->y_run NULL when R is not). */
int hy_ref_limit_init(hy_ref_limit *R, double sigma0, double g0, const hy_input *in, hy_error *err);
/* Frees R's table (R may be NULL; a second call is harmless). */
void hy_ref_limit_free(hy_ref_limit *R);
/* y°(ρ) for any ρ >= 0 (periodic); R NULL or not initialised: NaN. */
double hy_ref_steady_rho(const hy_ref_limit *R, double rho);
/* y at the start of every run of a period that starts at y0 (nruns + 1
 * values, the last one the period's end); R NULL or not initialised, or yrun
 * NULL: nothing written. */
void hy_ref_runs(const hy_ref_limit *R, long double y0, long double *yrun);
/* y at time tm in [0, T] of the period whose run starts are yrun (R->y_run:
 * the steady state y°_u; NULL: R->y_run).  R NULL or not initialised: NaN. */
double hy_ref_in_period(const hy_ref_limit *R, const long double *yrun, double tm);
/* y at the end of a period that starts at y0; R NULL or not initialised: NaN. */
long double hy_ref_period(const hy_ref_limit *R, long double y0);

/* y_γ of Eq. (3) at n ascending times (no filter, piecewise-linear input),
 * with the time within the period formed exactly; HY_EUNSUP otherwise.
 * HY_EINVAL for a bad model or γ; m, in and y must not be NULL, nor t when
 * n > 0. */
int hy_ref_gamma(const hy_model *m, const hy_input *in, double gamma, const double *t, size_t n, double *y,
                 hy_error *err);

#ifdef __cplusplus
}
#endif

#endif
