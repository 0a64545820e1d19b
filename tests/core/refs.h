/* SPDX-License-Identifier: MIT */
/* refs.h: independent references for the core tests.
 *  - ref_quad_steady: y°(t) by adaptive quadrature (GSL QAG) of Eqs. (6) and (8)
 *    in the input's own time t, with u̇(t) of the real (non-normalised) input.
 *  - ref_q*: y° by naive forward composition of the period map in 113-bit
 *    __float128 arithmetic (libquadmath), a different algorithm at 1e-34 precision. */
#ifndef HY_REFS_H
#define HY_REFS_H

#include <gsl/gsl_integration.h>
#include <quadmath.h>

#include "hy_input.h"

typedef struct qctx { const hy_input *in; double a, rref; } qctx;

static inline double q_integrand(double tau, void *p)
{
    const qctx *c = p;
    return exp(c->a * (hy_input_rho(c->in, tau) - c->rref)) * hy_input_du(c->in, tau);
}

/* ∫_{t0}^{t1} e^{a(ρ(τ) - rref)} u̇(τ) dτ, piece by piece (t1 <= T). */
static inline double q_integral(const hy_input *in, double a, double rref, double t0, double t1,
                         gsl_integration_workspace *w)
{
    qctx c = {in, a, rref};
    gsl_function F = {q_integrand, &c};
    double sum = 0;
    for (size_t i = 0; i < in->npieces; i++) {
        double lo = fmax(t0, in->pieces[i].t0), hi = fmin(t1, in->pieces[i].t1);
        if (hi <= lo)
            continue;
        double r, e;
        gsl_integration_qag(&F, lo, hi, 0, 1e-13, 1000, GSL_INTEG_GAUSS41, w, &r, &e);
        sum += r;
    }
    return sum;
}

/* y°(t), t in [0, T], from Eqs. (8) and (6) by quadrature. */
static inline double ref_quad_steady(const hy_input *in, double sigma0, double g0, double t,
                              gsl_integration_workspace *w)
{
    double a = sigma0 / g0;
    double y0 = sigma0 * q_integral(in, a, in->rho_T, 0, in->period, w) / -expm1(-a * in->rho_T);
    double r = hy_input_rho(in, t);
    return exp(-a * r) * y0 + sigma0 * q_integral(in, a, r, 0, t, w);
}

/* Affine period map y -> A y + B in quad precision by direct composition. */
static inline void ref_q_map(const hy_input *in, __float128 a, __float128 g0, __float128 *A, __float128 *B)
{
    __float128 AA = 1, BB = 0;
    for (size_t i = 0; i < in->nruns; i++) {
        const hy_run *r = &in->runs[i];
        __float128 d = (__float128)r->u1 - (__float128)r->u0;
        if (d < 0)
            d = -d;
        __float128 E = expq(-a * d);
        AA *= E;
        BB = E * BB + r->sign * g0 * -expm1q(-a * d); /* 1 - E without cancellation */
    }
    *A = AA;
    *B = BB;
}

/* y°(ϱ) in quad precision: fixed point, then propagation along the runs. */
static inline __float128 ref_q_steady_rho(const hy_input *in, double sigma0, double g0, double rho)
{
    __float128 a = (__float128)sigma0 / (__float128)g0, A, B;
    ref_q_map(in, a, g0, &A, &B);
    __float128 y = B / -expm1q(-a * (__float128)in->rho_T);
    (void)A;
    for (size_t i = 0; i < in->nruns; i++) {
        const hy_run *r = &in->runs[i];
        __float128 d = (__float128)r->u1 - (__float128)r->u0;
        if (d < 0)
            d = -d;
        if (rho < r->rho1 || i + 1 == in->nruns) {
            __float128 dd = (__float128)rho - (__float128)r->rho0;
            return expq(-a * dd) * y + r->sign * g0 * -expm1q(-a * dd);
        }
        y = expq(-a * d) * y + r->sign * g0 * -expm1q(-a * d);
    }
    return y;
}

#endif
