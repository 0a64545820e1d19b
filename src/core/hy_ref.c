/* SPDX-License-Identifier: MIT */
/* hy_ref.c: long-double references for y°, y*_u, y*_{u,k} (run-by-run
 * propagation of the limit map, Eq. (4) of seed 000) and y_γ (Eq. (3), exact
 * piecewise exponential), coded apart from hy_limit and hy_gamma. */
#include "hy_ref.h"

#include "hy_args.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>

/* one monotone stretch of variation d from y, direction s */
static long double limit_step(const hy_ref_limit *R, long double y, int s, long double d)
{
    long double e = expl(-R->a * d);
    return e * y + s * R->g0 * (1 - e);
}

int hy_ref_limit_init(hy_ref_limit *R, double sigma0, double g0, const hy_input *in, hy_error *err)
{
    HY_NONNULL(err, R);
    R->y_run = NULL;
    HY_INPUT_READY(err, in);
    if (!(sigma0 > 0) || !isfinite(sigma0) || !(g0 > 0) || !isfinite(g0))
        return hy_error_set(err, HY_EINVAL, "reference: sigma0 and g(0) must be finite and > 0");
    R->in = in;
    R->a = (long double)sigma0 / g0;
    R->g0 = g0;
    R->y_run = malloc((in->nruns + 1) * sizeof *R->y_run);
    if (!R->y_run)
        return hy_error_set(err, HY_ENOMEM, "out of memory");
    long double B = 0, rho = 0;
    for (size_t i = 0; i < in->nruns; i++) { /* the period map applied to 0 */
        long double d = fabsl((long double)in->runs[i].u1 - in->runs[i].u0);
        B = limit_step(R, B, in->runs[i].sign, d);
        rho += d;
    }
    R->rho_T = rho;
    long double one_minus_A = -expm1l(-R->a * rho);
    long double y = B / one_minus_A;
    for (size_t i = 0; i < in->nruns; i++) {
        R->y_run[i] = y;
        y = limit_step(R, y, in->runs[i].sign, fabsl((long double)in->runs[i].u1 - in->runs[i].u0));
    }
    R->y_run[in->nruns] = y;
    /* B carries ~(nruns + 2) roundings of size g0; dividing by 1 - A
     * amplifies them by 1/(1 - A) (small aρ_T: the terms of B cancel) */
    R->accuracy = (double)((long double)(in->nruns + 4) * LDBL_EPSILON * R->g0 / fminl(1, one_minus_A));
    return HY_OK;
}

void hy_ref_limit_free(hy_ref_limit *R)
{
    if (R) {
        free(R->y_run);
        R->y_run = NULL;
    }
}

static long double run_len(const hy_run *run)
{
    return fabsl((long double)run->u1 - run->u0);
}

/* the run containing variation r of the period (binary search) */
static size_t run_at(const hy_input *in, long double r)
{
    size_t lo = 0, hi = in->nruns - 1;
    while (lo < hi) {
        size_t mid = (lo + hi + 1) / 2;
        if (in->runs[mid].rho0 <= r)
            lo = mid;
        else
            hi = mid - 1;
    }
    return lo;
}

/* R was initialised: its input and table (hy_ref.h). */
static int ready(const hy_ref_limit *R)
{
    return R && R->y_run && hy__input_ready(R->in);
}

double hy_ref_steady_rho(const hy_ref_limit *R, double rho)
{
    if (!ready(R))
        return NAN;
    const hy_input *in = R->in;
    double k = floor(rho / in->rho_T);
    long double r = (long double)rho - (long double)k * in->rho_T;
    size_t i = run_at(in, r);
    const hy_run *run = &in->runs[i];
    long double d = r - run->rho0, len = run_len(run);
    d = d < 0 ? 0 : d > len ? len : d;
    return (double)limit_step(R, R->y_run[i], run->sign, d);
}

void hy_ref_runs(const hy_ref_limit *R, long double y0, long double *yrun)
{
    if (!ready(R) || !yrun)
        return;
    const hy_input *in = R->in;
    for (size_t i = 0; i < in->nruns; i++) {
        yrun[i] = y0;
        y0 = limit_step(R, y0, in->runs[i].sign, run_len(&in->runs[i]));
    }
    yrun[in->nruns] = y0;
}

double hy_ref_in_period(const hy_ref_limit *R, const long double *yrun, double tm)
{
    if (!ready(R))
        return NAN;
    if (!yrun)
        yrun = R->y_run;
    const hy_input *in = R->in;
    if (tm >= in->period)
        return (double)yrun[in->nruns];
    size_t lo = 0, hi = in->npieces - 1; /* the piece containing tm */
    while (lo < hi) {
        size_t mid = (lo + hi + 1) / 2;
        if (in->pieces[mid].t0 <= tm)
            lo = mid;
        else
            hi = mid - 1;
    }
    const hy_piece *p = &in->pieces[lo];
    long double u;
    if (tm >= p->t1)
        u = p->u1;
    else if (p->shape == HY_PIECE_LINEAR)
        u = p->u0 + ((long double)p->u1 - p->u0) * (((long double)tm - p->t0) / ((long double)p->t1 - p->t0));
    else
        u = hy_piece_u(p, tm);
    size_t a = 0, b = in->nruns - 1; /* the last run starting at or before piece lo */
    while (a < b) {
        size_t mid = (a + b + 1) / 2;
        if (in->runs[mid].p0 <= lo)
            a = mid;
        else
            b = mid - 1;
    }
    const hy_run *run = &in->runs[a];
    size_t i = a;
    return (double)limit_step(R, yrun[i], run->sign, fabsl(u - run->u0));
}

long double hy_ref_period(const hy_ref_limit *R, long double y0)
{
    if (!ready(R))
        return NAN;
    const hy_input *in = R->in;
    for (size_t i = 0; i < in->nruns; i++)
        y0 = limit_step(R, y0, in->runs[i].sign, run_len(&in->runs[i]));
    return y0;
}

/* g(v) in long double, from the model's fields (not hy_model_g). */
static long double g_ld(const hy_model *m, long double v)
{
    if (m->type != hy_model_lugre)
        return m->fc;
    long double r = fabsl(v / m->vs);
    return m->fc + ((long double)m->fs - m->fc) * expl(-powl(r, m->beta));
}

int hy_ref_gamma(const hy_model *m, const hy_input *in, double gamma, const double *t, size_t n, double *y,
                 hy_error *err)
{
    int rc = hy__solve_args(__func__, m, in, gamma, t, n, y, "y", err);
    if (rc)
        return rc;
    if (m->type->has_filter || !in->all_linear)
        return hy_error_set(err, HY_EUNSUP, "long-double reference needs a piecewise-linear input and no filter");
    long double z = m->x0;   /* z at the start of piece p of period k */
    double k = 0;
    size_t p = 0;
    for (size_t i = 0; i < n; i++) {
        const hy_piece *pc = &in->pieces[p];
        /* time within period k: k T = hi + lo exactly (fma), t - hi exact */
        double hi = k * in->period, lo = fma(k, in->period, -hi);
        long double tm = (long double)(t[i] - hi) - lo;
        /* advance while t[i] is at or past the end of the current piece */
        while (tm >= pc->t1 - hy_input_snap(hi + pc->t1)) {
            long double v = ((long double)pc->u1 - pc->u0) / ((long double)pc->t1 - pc->t0);
            long double lam = m->sigma0 * fabsl(v) / g_ld(m, v / gamma);
            if (v != 0)
                z = v / lam + (z - v / lam) * expl(-lam * ((long double)pc->t1 - pc->t0));
            if (++p == in->npieces) {
                p = 0;
                k += 1;
                hi = k * in->period;
                lo = fma(k, in->period, -hi);
                tm = (long double)(t[i] - hi) - lo;
            }
            pc = &in->pieces[p];
        }
        long double v = ((long double)pc->u1 - pc->u0) / ((long double)pc->t1 - pc->t0);
        long double zz = z, zd = 0;
        if (v != 0) {
            long double lam = m->sigma0 * fabsl(v) / g_ld(m, v / gamma), zeq = v / lam;
            zz = zeq + (z - zeq) * expl(-lam * (tm - pc->t0));
            zd = -lam * (zz - zeq);
        }
        y[i] = (double)(m->sigma0 * zz + (long double)m->sigma1 / gamma * zd + (long double)m->sigma2 * v / gamma);
    }
    return HY_OK;
}
