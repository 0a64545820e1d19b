/* SPDX-License-Identifier: MIT */
/* hy_ticks.c: round-number tick selection (1, 2, 2.5, 5 x 10^k), log decades, and label fitting. */
#include "hy_ticks.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "hy_status.h"

double hy_ticks_nice_step(double lo, double hi, int target)
{
    static const double mant[] = {1.0, 2.0, 2.5, 5.0, 10.0};
    if (!(hi > lo) || !isfinite(hi - lo))
        return 0.0;
    if (target < 1)
        target = 1;
    double raw = (hi - lo) / target;
    double mag = pow(10.0, floor(log10(raw)));
    for (size_t i = 0; i < sizeof mant / sizeof mant[0]; i++)
        if (mant[i] * mag >= raw * (1.0 - 1e-9))
            return mant[i] * mag;
    return 10.0 * mag;
}

/* floor(log10(x)) as an int for any x: clamped to the doubles' range of
 * exponents before the conversion (0 for 0, inf or NaN). */
static int decade_of(double x)
{
    double e = floor(log10(x) + 1e-9);
    if (!isfinite(e))
        return 0;
    return (int)fmax(-400.0, fmin(400.0, e));
}

/* Decimals needed to tell apart multiples of step = m x 10^e. */
static int step_decimals(double step)
{
    int e = decade_of(step);
    double m = step / pow(10.0, e);
    int d = -e + (fabs(m - 2.5) < 1e-6 ? 1 : 0);
    return d > 0 ? d : 0;
}

static void label_linear(hy_ticks *t)
{
    double amax = 0.0;
    for (int i = 0; i < t->n; i++)
        if (fabs(t->v[i]) > amax)
            amax = fabs(t->v[i]);
    int sci = amax >= 1e5 || (amax > 0.0 && amax < 1e-3);
    int e = sci ? decade_of(amax) : 0;
    double scale = pow(10.0, e);
    int d = step_decimals(t->step / scale);
    for (int i = 0; i < t->n; i++) {
        char *out = t->label[i];
        double m = t->v[i] / scale;
        if (t->v[i] == 0.0 && sci)
            snprintf(out, HY_TICK_LABEL, "0");
        else if (sci)
            snprintf(out, HY_TICK_LABEL, "%.*f\\times10^{%d}", d, m, e);
        else
            snprintf(out, HY_TICK_LABEL, "%.*f", d, m);
    }
}

/* Multiples of step inside [lo, hi]. */
static void fill_linear(double lo, double hi, double step, hy_ticks *t)
{
    double k0 = ceil(lo / step - 1e-9);
    t->n = 0;
    t->step = step;
    for (int i = 0; i < HY_TICKS_MAX; i++) {
        double v = (k0 + i) * step;
        if (v > hi + 1e-9 * step || !isfinite(v)) /* hi + slack may be inf near DBL_MAX */
            break;
        if (fabs(v) < 1e-9 * step)
            v = 0.0;
        t->v[t->n++] = v;
    }
}

int hy_ticks_linear(double lo, double hi, int target, hy_ticks *t)
{
    memset(t, 0, sizeof *t);
    if (!isfinite(lo) || !isfinite(hi) || hy_ticks_nice_step(lo, hi, target) <= 0.0)
        return hy_error_set(NULL, HY_EINVAL, "empty range");
    /* A coarse step may leave a single multiple inside: refine until two show. */
    for (int tg = target < 1 ? 1 : target; tg <= target + 8; tg++) {
        fill_linear(lo, hi, hy_ticks_nice_step(lo, hi, tg), t);
        if (t->n >= 2)
            break;
    }
    label_linear(t);
    return HY_OK;
}

/* 1-2-5 ticks for a log axis spanning less than two decades; the decimal
 * labels all get the decimals of the smallest (0.05, 0.10, 0.20). */
static void log_125(double lo, double hi, hy_ticks *t)
{
    static const double mant[] = {1.0, 2.0, 5.0};
    int d0 = (int)floor(log10(lo)), d1 = (int)floor(log10(hi)), dec = 0;
    for (int d = d0; d <= d1 && dec == 0; d++)
        for (int j = 0; j < 3; j++) {
            double v = mant[j] * pow(10.0, d);
            if (v >= lo * (1 - 1e-9) && v <= hi * (1 + 1e-9) && d >= -3 && d <= 4) {
                dec = d < 0 ? -d : 0;
                break;
            }
        }
    for (int d = d0; d <= d1; d++)
        for (int j = 0; j < 3 && t->n < HY_TICKS_MAX; j++) {
            double v = mant[j] * pow(10.0, d);
            if (v < lo * (1 - 1e-9) || v > hi * (1 + 1e-9))
                continue;
            t->v[t->n] = v;
            if (d >= -3 && d <= 4)
                snprintf(t->label[t->n], HY_TICK_LABEL, "%.*f", dec, v);
            else if (j == 0)
                snprintf(t->label[t->n], HY_TICK_LABEL, "10^{%d}", d);
            else
                snprintf(t->label[t->n], HY_TICK_LABEL, "%g\\times10^{%d}", mant[j], d);
            t->n++;
        }
}

int hy_ticks_log(double lo, double hi, int target, hy_ticks *t)
{
    memset(t, 0, sizeof *t);
    if (!(lo > 0.0) || !(hi > lo) || !isfinite(hi))
        return hy_error_set(NULL, HY_EINVAL, "empty range");
    int d0 = (int)ceil(log10(lo) - 1e-9), d1 = (int)floor(log10(hi) + 1e-9);
    int count = d1 - d0 + 1;
    if (count < 2) {
        log_125(lo, hi, t);
        if (t->n < 2)
            return hy_ticks_linear(lo, hi, target, t);
        t->step = 0.0;
        return HY_OK;
    }
    if (target < 1)
        target = 1;
    int stride = (count + target - 1) / target;
    if (stride < 1)
        stride = 1;
    t->step = stride;
    for (int d = d0; d <= d1 && t->n < HY_TICKS_MAX; d++) {
        if (((d % stride) + stride) % stride)
            continue;
        t->v[t->n] = pow(10.0, d);
        snprintf(t->label[t->n], HY_TICK_LABEL, "10^{%d}", d);
        t->n++;
    }
    return HY_OK;
}

static double axis_pos(double v, double lo, double hi, int log_scale, double length)
{
    if (log_scale)
        return (log10(v) - log10(lo)) / (log10(hi) - log10(lo)) * length;
    return (v - lo) / (hi - lo) * length;
}

static int labels_fit(const hy_ticks *t, double lo, double hi, int log_scale, double length,
                      double gap, hy_ticks_measure_fn measure, void *ctx)
{
    double prev_pos = 0.0, prev_half = 0.0;
    for (int i = 0; i < t->n; i++) {
        double pos = axis_pos(t->v[i], lo, hi, log_scale, length);
        double half = 0.5 * measure(ctx, t->label[i]);
        if (i > 0 && pos - prev_pos < prev_half + half + gap)
            return 0;
        prev_pos = pos;
        prev_half = half;
    }
    return 1;
}

int hy_ticks_fit(double lo, double hi, int log_scale, double length, double gap,
                 int max_target, hy_ticks_measure_fn measure, void *ctx, hy_ticks *t)
{
    int st = HY_EINVAL;
    for (int target = max_target; target >= 1; target--) {
        st = log_scale ? hy_ticks_log(lo, hi, target, t) : hy_ticks_linear(lo, hi, target, t);
        if (st)
            return st;
        if (labels_fit(t, lo, hi, log_scale, length, gap, measure, ctx))
            return HY_OK;
    }
    /* Nothing fits: keep the extreme ticks, or only the first if even they collide. */
    if (t->n > 2) {
        t->v[1] = t->v[t->n - 1];
        memcpy(t->label[1], t->label[t->n - 1], HY_TICK_LABEL);
        t->n = 2;
    }
    if (t->n == 2 && !labels_fit(t, lo, hi, log_scale, length, gap, measure, ctx))
        t->n = 1;
    return st;
}
