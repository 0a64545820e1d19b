/* SPDX-License-Identifier: MIT */
/* model_duhem.c: the Duhem model (Duhem 1897; Macki, Nistri and Zecca, SIAM
 * Review 35, 1993, Sect. 4; Visintin, Differential Models of Hysteresis,
 * 1994, Ch. V) in its classical form
 *     dy/dt = α |du/dt| (f(u) - y) + g(u) du/dt,
 * here with f(u) = a u (the curve y is pulled to) and g(u) = b (the slope
 * where y = f(u)).  dt cancels: y follows the path of u alone (a
 * rate-independent model), and along a monotone move of u (s = ±1)
 *     dy/du = α s (a u - y) + b,
 * a linear equation whose solution from (u0, y0) is
 *     y(u) = p(u) + (y0 - p(u0)) e^{-α |u - u0|},  p(u) = a u + s (b - a) / α,
 * so every move is exact (no step size), and so is the path integral
 *     ∫ y du = a (u² - u0²) / 2 + s (b - a) / α (u - u0)
 *              + (y0 - p(u0)) (1 - e^{-α |u - u0|}) / (α s).
 * Rising, y approaches a u - (a - b) / α from below; falling, a u + (a - b) / α
 * from above: for a > b the loops run counter-clockwise (y lags u), so the
 * area printed is ∮ u dy = -∮ y du (no HY_RI_AREA_YDU, as for play).  Minor
 * loops do not close at their reversal point.  The model's keys, stages and
 * table entry are this file; its table line is in src/pipeline/meson.build. */
#include <stddef.h>

#include "hy_cost.h"
#include "hy_scene_model_rows.h"

/* The [model] keys. */
typedef struct duhem_par {
    double alpha, a, b, y0;
} duhem_par;

#define PAR duhem_par
HY_MODEL_ROWS(duhem, duhem_par,
    HY_ROW("α", NULL, duhem_alpha, alpha, HY_KIND_NUMBER, NULL, HY_POS, 0, 0, "5",
           "duhem: rate alpha at which y is pulled to f(u) = a u per unit of input travel (1 / input units)"),
    HY_ROW("a", NULL, duhem_a, a, HY_KIND_NUMBER, NULL, HY_NOLIM, 0, 0, "1",
           "duhem: slope a of the curve f(u) = a u that y is pulled to"),
    HY_ROW("b", NULL, duhem_b, b, HY_KIND_NUMBER, NULL, HY_NOLIM, 0, 0, "0.5",
           "duhem: slope g(u) = b of y where y = f(u); the branches lie (a - b) / alpha either side of f"),
    HY_ROW("y_0", NULL, duhem_y0, y0, HY_KIND_NUMBER, NULL, HY_NOLIM, 0, 0, "0", "duhem: output at t = 0"));

#ifndef HY_MODEL_ROWS_ONLY /* the stages (the pipeline's compile of this file) */
#include <math.h>

#include "scene_model.h"

typedef struct duhem_state {
    double u, y, iy; /* input, output, ∫ y du along the path */
} duhem_state;

static const char *const quantities[] = {"output", NULL};

static void outputs(const duhem_state *s, double out[HY_RI_NOUT])
{
    out[0] = s->y;
    out[1] = NAN;
    out[2] = s->iy;
}

static int duhem_init(const void *par, void *st, double u0, double out[HY_RI_NOUT], hy_error *err)
{
    const duhem_par *p = par;
    duhem_state *s = st;
    if (!isfinite(u0))
        return hy_error_set(err, HY_EINVAL, "duhem: input must be finite (got %g)", u0);
    s->u = u0;
    s->y = p->y0;
    s->iy = 0;
    outputs(s, out);
    return HY_OK;
}

/* u monotonically to u: the exact solution of the linear equation above. */
static int duhem_apply(const void *par, void *st, double u, double out[HY_RI_NOUT], hy_error *err)
{
    const duhem_par *p = par;
    duhem_state *s = st;
    if (!isfinite(u))
        return hy_error_set(err, HY_EINVAL, "duhem: input must be finite (got %g)", u);
    double du = u - s->u, sgn = du >= 0 ? 1.0 : -1.0;
    double lag = sgn * (p->b - p->a) / p->alpha;            /* p(u) - a u */
    double d0 = s->y - (p->a * s->u + lag);                 /* y0 - p(u0) */
    double decay = -expm1(-p->alpha * fabs(du));            /* 1 - e^{-α |du|} */
    double y = p->a * u + lag + d0 * (1 - decay);
    double iy = s->iy + p->a * du * (u + s->u) / 2 + lag * du + d0 * decay / (p->alpha * sgn);
    if (!isfinite(y) || !isfinite(iy))
        return hy_error_set(err, HY_EINVAL, "duhem: output overflows at u = %g", u);
    s->u = u;
    s->y = y;
    s->iy = iy;
    outputs(s, out);
    return HY_OK;
}

static const hy_rateind_type duhem_type = {"duhem", sizeof(duhem_state), HY_RI_PATH_AREA, duhem_init, duhem_apply,
                                           NULL, NULL, NULL};

const hy_scene_model hy_scene_model_duhem = {
    "duhem", NULL, quantities, NULL, NULL,
    HY_CAP_STEADY | HY_CAP_YSTAR | HY_CAP_ENERGY | HY_CAP_RATE_INDEPENDENT | HY_CAP_EXACT_STEP,
    "the output y and the path integral of y du (exact: exponential approach to a u -/+ (a - b) / alpha)",
    hy_scene_rateind_load, hy_scene_rateind_estimate, hy_scene_rateind_compute, &duhem_type, sizeof(duhem_par),
    NULL, NULL, NULL, HY_INPUT_OTHERS, HY_DATA_PATH, HY_COST_PLAY};
#endif
