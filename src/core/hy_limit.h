/* SPDX-License-Identifier: MIT */
/* hy_limit.h: the γ → ∞ limit y*_u (seed 000, Theorem 2, Eqs. (4)-(8)), the
 * k-cycle functions y*_{u,k}, the steady state y°_u and Theorem A.
 *
 * y* depends only on the input's values: on a monotone run of variation Δ with
 * direction s (+1 rising, -1 falling), with a = σ0/g(0),
 *     y ← e^{-aΔ} y + s g(0) (1 - e^{-aΔ}).
 * Everything here is evaluated with e^{-…}, expm1 and series forms only, so it
 * stays finite and accurate for σ0 ∈ [1e-6, 1e12], g(0) ∈ [1e-12, 1e6] and
 * k up to 1e9 cycles (the printed closed form overflows there; see
 * hy_theorem_a_printed for it, kept for comparison).
 *
 *     hy_steady st;
 *     hy_steady_init(&st, &model, &input, &err);
 *     double y = hy_steady_at(&st, t);             // y°_u(t)
 *     double yk = hy_ystar_k(&st, x0, 3, t);       // y*_{u,3}(t)
 *     hy_steady_free(&st);
 */
#ifndef HY_LIMIT_H
#define HY_LIMIT_H

#include "hy_input.h"
#include "hy_model.h"

#ifdef __cplusplus
extern "C" {
#endif

/* φ1(x) = (1 - e^{-x})/x, φ1(0) = 1; accurate for every x >= 0. */
double hy_phi1(double x);
/* φ2(x) = (x - 1 + e^{-x})/x², φ2(0) = 1/2; accurate for every x >= 0. */
double hy_phi2(double x);

/* One monotone run: y after variation d in direction s (exact). */
double hy_limit_step(double a, double g0, double y, int s, double d);
/* ∫_0^d y(r) s dr along that run: its contribution to ∮ y du (exact). */
double hy_limit_step_area(double a, double g0, double y, int s, double d);
/* The same, given em = expm1(-(a d)) (a caller that needs e^{-ad} - 1 too
 * computes it once); the same bits as hy_limit_step_area. */
double hy_limit_step_area_em(double a, double g0, double y, int s, double d, double em);

typedef struct hy_steady {
    const hy_input *in;   /* borrowed: must outlive the hy_steady          */
    double sigma0, g0, a;
    double contraction;   /* e^{-a ρ_T}: y*_{u,k} - y°_u shrinks by it per cycle */
    double *y_run;        /* y° at the start of each run, nruns + 1 values  */
} hy_steady;

/* Computes y° at every extremum of the input (fixed point of the period map).
 * Returns HY_OK, HY_EINVAL (bad model) or HY_ENOMEM.  st, m and in must not
 * be NULL, and in must have runs (HY_EINVAL; st->y_run NULL when st is not). */
int hy_steady_init(hy_steady *st, const hy_model *m, const hy_input *in, hy_error *err);
/* As hy_steady_init, y° written into y_run (nruns + 1 doubles, the caller's:
 * st->y_run points there; do not hy_steady_free st): no allocation, the same
 * numbers (hystviz sweep's closed-form kernel).  HY_OK or HY_EINVAL (also
 * for st, m, in or y_run NULL, as hy_steady_init). */
int hy_steady_init_buf(hy_steady *st, const hy_model *m, const hy_input *in, double *y_run, hy_error *err);
/* Frees the steady state's table (st may be NULL; a second call is harmless). */
void hy_steady_free(hy_steady *st);

/* y°(ϱ): the steady state along the normalised input ψ_u (Eqs. 11-14).  st
 * NULL, or one not initialised by hy_steady_init (no table or input): NaN. */
double hy_steady_at_rho(const hy_steady *st, double rho);
/* y°_u(t) = y°(ρ_u(t)) for any t (periodic).  st NULL or not initialised:
 * NaN. */
double hy_steady_at(const hy_steady *st, double t);
/* y*_u(t) from the initial state z(0) = x0 (Eq. 4), any t >= 0.  st NULL or
 * not initialised: NaN. */
double hy_ystar_at(const hy_steady *st, double x0, double t);
/* y*_{u,k}(t) = y*_u(t + kT), t in [0, T], without forming t + kT.  st NULL
 * or not initialised: NaN. */
double hy_ystar_k(const hy_steady *st, double x0, double k, double t);

/* y° on n >= 2 points ϱ_j = j ρ_T/(n-1); u_out (ψ_u) may be NULL.  Within a
 * run one multiply-add per point, re-anchored exactly every 64 points.  st or
 * y_out NULL, or n < 2: nothing written. */
void hy_steady_sample(const hy_steady *st, size_t n, double *u_out, double *y_out);

/* Theorem A for a bimodal input, evaluated stably: rho[0..5] = ϱ0..ϱ5 and
 * y[0..4] = y°(ϱ0..ϱ4).  Returns HY_EINVAL when Definition 1 fails. */
typedef struct hy_theorem_a {
    double a, g0;
    double umin1, umin2, umax1, umax2;
    double rho[6];
    double y[5];
} hy_theorem_a;
/* Fills th from Theorem A for LuGre's σ0 and g0 and the bimodal extrema;
 * HY_EINVAL (th unspecified) when Definition 1 fails or th is NULL. */
int hy_theorem_a_init(hy_theorem_a *th, double sigma0, double g0, double umin1, double umin2,
                      double umax1, double umax2, hy_error *err);
/* y°(ϱ) from Eqs. (11)-(14) (signs alternate: + on rising pieces).  th NULL,
 * or rho not finite: NaN. */
double hy_theorem_a_eval(const hy_theorem_a *th, double rho);
/* ψ_u(ϱ) of Theorem A (Eq. 10).  th NULL, or rho not finite: NaN. */
double hy_theorem_a_psi(const hy_theorem_a *th, double rho);
/* The closed form exactly as printed (e^{+aϱ} factors): overflows to inf/nan
 * for stiff parameters.  statement_signs != 0 uses the statement's "−" on every
 * piece instead of the proof's alternating signs.  For tests and reports only.
 * th NULL, or rho not finite: NaN. */
double hy_theorem_a_printed(const hy_theorem_a *th, double rho, int statement_signs);

#ifdef __cplusplus
}
#endif

#endif
