/* hy_rateind.c: feeds a rate-independent model the extrema and samples of a
 * periodic piecewise-monotone input (hy_input.h, seed 000 Definition 1). */
#include "hy_rateind.h"

#include <math.h>

/* Time at which run r of period k ends, and its value. */
static double run_end_time(const hy_input *in, size_t r, double k)
{
    return k * in->period + in->pieces[in->runs[r].p1 - 1].t1;
}

int hy_rateind_drive(const hy_input *in, const double *t, size_t n, hy_rateind_fn fn, void *ctx,
                     double *y, hy_error *err)
{
    double k = 0, tprev = 0;
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
