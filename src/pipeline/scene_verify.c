/* SPDX-License-Identifier: MIT */
/* scene_verify.c: the printed error of every closed-form series (y°, y*_{u,k},
 * y*, the loops, y_γ of the exact solver), measured against the long-double
 * references of hy_ref.h at the points the series drew. */
#include "scene_verify.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "hy_gamma.h"
#include "hy_ref.h"

/* Periods the y* reference propagates run by run before it uses the
 * long-double e^{-a k ρ_T} form instead. */
#define PROPAGATE_MAX 100000.0

static size_t stride_of(size_t n)
{
    return n > HY_VERIFY_POINTS ? (n + HY_VERIFY_POINTS - 1) / HY_VERIFY_POINTS : 1;
}

static void set_ref(hy_run_series *se, double e, const char *what, size_t stride, size_t n)
{
    se->err = e;
    if (stride > 1)
        snprintf(se->err_note, sizeof se->err_note, "%s, 1 in %zu of %zu points", what, stride, n);
    else
        snprintf(se->err_note, sizeof se->err_note, "%s, all %zu points", what, n);
    se->err_ref = se->err_note;
}

static void not_measured(hy_run_series *se, const char *why)
{
    se->err = NAN;
    snprintf(se->err_note, sizeof se->err_note, "not measured: %.180s", why);
    se->err_ref = se->err_note;
}

/* The reference, or "not measured" in se when it cannot judge (returns -1). */
static int ref_init(const hy_scene_run *r, hy_ref_limit *R, hy_run_series *se)
{
    hy_error err = {0};
    if (!r->have_steady || hy_ref_limit_init(R, r->model.sigma0, r->steady.g0, &r->input, &err)) {
        not_measured(se, r->have_steady ? err.msg : "no steady state");
        return -1;
    }
    if (R->accuracy > 1e-14 * (double)R->g0) {
        char why[128];
        snprintf(why, sizeof why, "the long-double reference is only good to %.1e here (a rho_T = %.2g)",
                 R->accuracy, (double)(R->a * R->rho_T));
        not_measured(se, why);
        hy_ref_limit_free(R);
        return -1;
    }
    return 0;
}

void hy_verify_loops(const hy_scene_run *r, hy_run_series *se, const double *a, const double *b, int k, size_t per,
                     int thinned)
{
    hy_ref_limit R;
    if (ref_init(r, &R, se))
        return;
    size_t total = (size_t)k * per, stride = stride_of(total), q = 0;
    double e = 0;
    for (int i = 0; i < k; i++)
        for (size_t j = 0; j < per; j++, q++) {
            if (q % stride)
                continue;
            /* the parameter sample() drew at */
            double rho = per > 1 ? a[i] + (b[i] - a[i]) * (double)j / (double)(per - 1) : a[i];
            double y = thinned ? hy_steady_at_rho(&r->steady, rho) : se->y[(size_t)i * (per + 1) + j];
            e = fmax(e, fabs(y - hy_ref_steady_rho(&R, rho)));
        }
    set_ref(se, e, "long-double run-by-run propagation of the limit map (y° by forward composition)", stride,
            total);
    hy_ref_limit_free(&R);
}

/* y*_u at the start of period k from y*(0) = σ0 x0: propagated run by run,
 * or past PROPAGATE_MAX periods the long-double e^{-a k ρ_T} form */
static long double ystar_start(const hy_ref_limit *R, long double y00, double k)
{
    if (k > PROPAGATE_MAX) {
        long double yo = R->y_run[0];
        return yo + (y00 - yo) * expl(-R->a * R->rho_T * k);
    }
    for (double i = 0; i < k; i++)
        y00 = hy_ref_period(R, y00);
    return y00;
}

void hy_verify_time(const hy_scene_run *r, hy_run_series *se, const double *t, const double *y, size_t n)
{
    hy_ref_limit R;
    if (ref_init(r, &R, se))
        return;
    const hy_input *in = &r->input;
    long double *yrun = malloc((in->nruns + 1) * sizeof *yrun);
    if (!yrun) {
        not_measured(se, "out of memory");
        hy_ref_limit_free(&R);
        return;
    }
    long double y00 = (long double)r->model.sigma0 * r->model.x0;
    const char *what = "long-double run-by-run propagation of the limit map (y° by forward composition)";
    if (se->data == HY_DATA_YK) {
        hy_ref_runs(&R, ystar_start(&R, y00, (double)se->k), yrun);
        what = (double)se->k <= PROPAGATE_MAX ? "long-double run-by-run propagation of K periods from sigma0 x0"
                                               : "long-double y° + (sigma0 x0 - y°(0)) e^{-a K rho_T}";
    } else if (se->data == HY_DATA_YSTAR) {
        what = "long-double run-by-run propagation from sigma0 x0";
    } else {
        hy_ref_runs(&R, R.y_run[0], yrun);
    }
    size_t stride = stride_of(n);
    double e = 0, kcur = -1, T = in->period;
    long double ystart = y00; /* y* at the start of period kcur */
    for (size_t i = 0; i < n; i += stride) {
        double tm = t ? t[i] : n > 1 ? T * (double)i / (double)(n - 1) : 0; /* as sample() on [0, T] */
        if (t && se->data == HY_DATA_YSTAR) {
            double k = floor(t[i] / in->period);
            tm = hy_input_reduce(in, t[i], k);
            if (tm < 0 && k > 0)
                tm = hy_input_reduce(in, t[i], --k);
            if (k != kcur) { /* t ascends: propagate on from the last period */
                if (kcur >= 0 && k > kcur && k - kcur <= 1000 && k <= PROPAGATE_MAX)
                    for (; kcur < k; kcur++)
                        ystart = hy_ref_period(&R, ystart);
                else
                    ystart = ystar_start(&R, y00, k);
                if (k > PROPAGATE_MAX)
                    what = "long-double y° + (sigma0 x0 - y°(0)) e^{-a k rho_T} past 1e5 periods";
                kcur = k;
                hy_ref_runs(&R, ystart, yrun);
            }
        }
        e = fmax(e, fabs(y[i] - hy_ref_in_period(&R, yrun, tm)));
    }
    set_ref(se, e, what, stride, n);
    free(yrun);
    hy_ref_limit_free(&R);
}

void hy_verify_gamma(const hy_scene_run *r, double gamma, const double *t, const double *y, size_t n, double *err,
                     char *ref, size_t refsize)
{
    *err = NAN;
    if (r->model.type->has_filter || !r->input.all_linear) {
        snprintf(ref, refsize, "not measured: no independent reference for %s",
                 r->model.type->has_filter ? "the filter of system (16)" : "a smooth input");
        return;
    }
    size_t stride = stride_of(n), m = (n + stride - 1) / stride;
    double *ts = calloc(2 * m, sizeof *ts);
    hy_error e = {0};
    if (!ts) {
        snprintf(ref, refsize, "not measured: out of memory");
        return;
    }
    for (size_t i = 0; i < m; i++)
        ts[i] = t[i * stride];
    if (hy_ref_gamma(&r->model, &r->input, gamma, ts, m, ts + m, &e)) {
        snprintf(ref, refsize, "not measured: %.180s", e.msg);
    } else {
        *err = 0;
        for (size_t i = 0; i < m; i++)
            *err = fmax(*err, fabs(y[i * stride] - ts[m + i]));
        if (stride > 1)
            snprintf(ref, refsize, "long-double piecewise exponential (hy_ref), 1 in %zu of %zu points", stride, n);
        else
            snprintf(ref, refsize, "long-double piecewise exponential (hy_ref), all %zu points", n);
    }
    free(ts);
}
