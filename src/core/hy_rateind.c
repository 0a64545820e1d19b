/* SPDX-License-Identifier: MIT */
/* hy_rateind.c: feeds a rate-independent model the extrema and samples of a
 * periodic piecewise-monotone input (hy_input.h, seed 000 Definition 1). */
#include "hy_rateind.h"

#include "hy_args.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Time at which run r of period k ends, and its value. */
static double run_end_time(const hy_input *in, size_t r, double k)
{
    return k * in->period + in->pieces[in->runs[r].p1 - 1].t1;
}

int hy_rateind_drive(const hy_input *in, const double *t, size_t n, hy_rateind_fn fn, void *ctx,
                     double *y, hy_error *err)
{
    double k = 0, tprev = 0;
    HY_INPUT_READY(err, in);
    HY_NONNULL(err, fn);
    HY_NONNULL(err, y);
    HY_NONNULL_N(err, t, n);
    size_t r = 0;
    for (size_t i = 0; i < n; i++) {
        if (!(t[i] >= tprev) || !isfinite(t[i]))
            return hy_error_set(err, HY_EINVAL, "output time %zu (%g) is not finite and ascending from %g",
                                i, t[i], tprev);
        double yi = 0;
        int rc;
        for (;;) {
            double te = run_end_time(in, r, k);
            if (!(te <= t[i]))
                break;
            if ((rc = fn(ctx, in->runs[r].u1, &yi, err)))
                return rc;
            if (++r == in->nruns) {
                r = 0;
                k += 1;
            }
        }
        if ((rc = fn(ctx, hy_input_u(in, t[i]), &yi, err)))
            return rc;
        y[i] = yi;
        tprev = t[i];
    }
    return HY_OK;
}

int hy_rateind_bimodal(const hy_input *in, double e[4], hy_error *err)
{
    HY_INPUT_READY(err, in);
    HY_NONNULL(err, e);
    if (in->nruns != 4 || in->runs[0].sign != 1)
        return hy_error_set(err, HY_EINVAL,
                            "%s is not a bimodal input of Definition 1 (4 monotone runs from u_min,1 up)", in->desc);
    double v[4] = {in->runs[0].u0, in->runs[0].u1, in->runs[1].u1, in->runs[2].u1};
    if (!(v[0] <= v[2] && v[2] < v[1] && v[1] <= v[3]))
        return hy_error_set(err, HY_EINVAL,
                            "%s: extrema %g, %g, %g, %g do not satisfy u_min,1 <= u_min,2 < u_max,1 <= u_max,2",
                            in->desc, v[0], v[2], v[1], v[3]);
    for (int i = 0; i < 4; i++)
        e[i] = v[i];
    return HY_OK;
}

/* ---- model types ------------------------------------------------------ */

int hy_rateind_alloc(hy_rateind *m, const hy_rateind_type *type, const void *par, double u0, hy_error *err)
{
    HY_NONNULL(err, m);
    m->st = NULL;
    HY_NONNULL(err, type);
    HY_NONNULL(err, type->init);
    m->type = type;
    m->par = par;
    m->cancel = NULL;
    m->tick = 0;
    m->st = calloc(1, type->state_size ? type->state_size : 1);
    if (!m->st)
        return hy_error_set(err, HY_ENOMEM, "out of memory for a %s state", type->name);
    int rc = type->init(par, m->st, u0, m->out, err);
    if (rc) {
        free(m->st);
        m->st = NULL;
    }
    return rc;
}

/* m was allocated (hy_rateind.h): its type, apply and state. */
static int ready(const hy_rateind *m)
{
    return m && m->type && m->type->apply && m->st;
}

/* The refusal of a model that is NULL or not allocated. */
static int not_ready(const char *fn, const char *name, const hy_rateind *m, hy_error *err)
{
    return hy_error_set(err, HY_EINVAL, "%s: %s %s", fn, name, m ? "is not allocated (or was freed)" : "must not be NULL");
}

int hy_rateind_apply(hy_rateind *m, double u, hy_error *err)
{
    if (!ready(m))
        return not_ready(__func__, "m", m, err);
    if (hy_cancel_poll(m->cancel, &m->tick, HY_RI_CANCEL_MOVES))
        return hy_cancel_error(err);
    return m->type->apply(m->par, m->st, u, m->out, err);
}

int hy_rateind_clone(hy_rateind *dst, const hy_rateind *src, hy_error *err)
{
    HY_NONNULL(err, dst);
    dst->st = NULL;
    if (!ready(src))
        return not_ready(__func__, "src", src, err);
    *dst = *src;
    dst->st = calloc(1, src->type->state_size ? src->type->state_size : 1);
    if (!dst->st)
        return hy_error_set(err, HY_ENOMEM, "out of memory for a %s state", src->type->name);
    int rc = HY_OK;
    if (src->type->copy)
        rc = src->type->copy(src->par, dst->st, src->st, err);
    else /* plain bytes */
        memcpy(dst->st, src->st, src->type->state_size);
    if (rc) {
        free(dst->st);
        dst->st = NULL;
    }
    return rc;
}

void hy_rateind_free(hy_rateind *m)
{
    if (!m)
        return;
    if (m->st && m->type && m->type->free)
        m->type->free(m->st);
    free(m->st);
    m->st = NULL;
}

int hy_rateind_settle(hy_rateind *m, const hy_input *in, double tol, int max_periods, int *periods,
                      hy_error *err)
{
    if (!ready(m))
        return not_ready(__func__, "m", m, err);
    HY_INPUT_READY(err, in);
    if (!isfinite(tol) || tol < 0 || max_periods < 1)
        return hy_error_set(err, HY_EINVAL, "%s: tol (%g) must be finite and >= 0, max_periods (%d) >= 1", __func__,
                            tol, max_periods);
    double prev = m->out[0];
    int calm = 0;
    for (int k = 1; k <= max_periods; k++) {
        double big = fabs(prev);
        for (size_t r = 0; r < in->nruns; r++) {
            int rc = hy_rateind_apply(m, in->runs[r].u1, err);
            if (rc)
                return rc;
            big = fmax(big, fabs(m->out[0]));
        }
        double d = fabs(m->out[0] - prev);
        prev = m->out[0];
        calm = d <= tol * big ? calm + 1 : 0;
        if (calm == 2) {
            if (periods)
                *periods = k;
            return HY_OK;
        }
    }
    return hy_error_set(err, HY_ENUM, "%s: the output did not become periodic (to %g of its range) in %d periods of %s",
                        m->type->name, tol, max_periods, in->desc);
}

int hy_rateind_sample(hy_rateind *m, const hy_input *in, int by_rho, const double *x, size_t n,
                      double *const rows[HY_RI_NOUT], hy_error *err)
{
    double k = 0, prev = 0;
    if (!ready(m))
        return not_ready(__func__, "m", m, err);
    HY_INPUT_READY(err, in);
    HY_NONNULL_N(err, x, n);
    size_t r = 0;
    for (size_t i = 0; i < n; i++) {
        if (!(x[i] >= prev) || !isfinite(x[i]))
            return hy_error_set(err, HY_EINVAL, "sample %zu (%g) is not finite and ascending from %g", i, x[i], prev);
        int rc;
        for (;;) { /* the extrema up to x[i] */
            double end = by_rho ? k * in->rho_T + in->runs[r].rho1 : run_end_time(in, r, k);
            if (!(end <= x[i]))
                break;
            if ((rc = hy_rateind_apply(m, in->runs[r].u1, err)))
                return rc;
            if (++r == in->nruns) {
                r = 0;
                k += 1;
            }
        }
        if ((rc = hy_rateind_apply(m, by_rho ? hy_input_psi(in, x[i]) : hy_input_u(in, x[i]), err)))
            return rc;
        for (int q = 0; q < HY_RI_NOUT; q++)
            if (rows && rows[q])
                rows[q][i] = m->out[q];
        prev = x[i];
    }
    return HY_OK;
}
