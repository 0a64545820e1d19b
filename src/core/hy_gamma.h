/* SPDX-License-Identifier: MIT */
/* hy_gamma.h: the exact finite-γ solution y_γ of the time-scaled LuGre model
 * (seed 000, Eq. (3)) and of system (16).
 *
 * On a piece where u̇ = v is constant, Eq. (3) is linear with constant
 * coefficients: with λ = σ0|v|/g(v/γ) and z_eq = v/λ,
 *     z(t) = z_eq + (z0 - z_eq) e^{-λ(t - t0)},
 *     y_γ = σ0 z + (σ1/γ) ż + σ2 v/γ,   ż = -λ (z - z_eq),
 * exact also in the σ1 and f terms.  The filter of system (16), in the time of
 * Eq. (3), is ẏ = (γ/τ)(x - y) with x = σ0 z; it is solved exactly on the same
 * pieces.  A rate-independent model (Dahl) is exact on any monotone piece.
 * Other cases need hy_ode (GSL).
 *
 *     double t[1000], y[1000];
 *     for (i...) t[i] = ...;                          // ascending
 *     hy_gamma_exact(&m, &in, 10.0, t, 1000, y, NULL, &err);
 */
#ifndef HY_GAMMA_H
#define HY_GAMMA_H

#include "hy_input.h"
#include "hy_model.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Nonzero when hy_gamma_exact can solve this model/input pair (0 when m or
 * in is NULL, or in has no pieces). */
int hy_gamma_exact_applies(const hy_model *m, const hy_input *in);

/* y_γ at the n ascending times t[] (>= 0) from z(0) = m->x0; z_out (may be
 * NULL) receives the internal state.  At a breakpoint the value on the piece
 * starting there is given (ż may jump).  HY_EUNSUP when it does not apply,
 * HY_EINVAL for a bad model, γ or unsorted times.  m, in (with pieces) and
 * y_out must not be NULL, nor t when n > 0 (HY_EINVAL). */
int hy_gamma_exact(const hy_model *m, const hy_input *in, double gamma, const double *t, size_t n,
                   double *y_out, double *z_out, hy_error *err);

/* Checks γ: finite and > 0. */
int hy_gamma_check(double gamma, hy_error *err);

#ifdef __cplusplus
}
#endif

#endif
