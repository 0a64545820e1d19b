/* SPDX-License-Identifier: MIT */
/* model_play.c: the play operator (backlash; Krasnosel'skii and Pokrovskii,
 * Systems with Hysteresis, 1989, Sect. 2.2), the elementary rate-independent
 * hysteresis of half-width r:
 *     y(t) = max(u(t) - r, min(u(t) + r, y(t-))),
 * i.e. y stays put while |u - y| < r and is dragged at distance r behind u
 * otherwise.  On a monotone move of u the output is a constant piece then a
 * line of slope 1, so y and ∫ y du along the path are exact; a loop between
 * reversals lo and hi (hi - lo > 2r) from a dragged branch is the
 * parallelogram of area 2r (hi - lo - 2r).  Its loops run counter-clockwise
 * (y lags u), so the area printed is ∮ u dy = -∮ y du (no HY_RI_AREA_YDU):
 * the energy the play's elastic-plastic pair dissipates (docs/SCENES.md,
 * "Loop areas").  The model's keys, stages and
 * table entry are this file; its table line is in src/pipeline/meson.build. */
#include <stddef.h>

#include "hy_cost.h"
#include "hy_scene_model_rows.h"

/* The [model] keys. */
typedef struct play_par {
    double r, y0;
} play_par;

#define PAR play_par
HY_MODEL_ROWS(play, play_par,
    HY_ROW("r", NULL, play_r, r, HY_KIND_NUMBER, NULL, HY_POS, 0, 0, "0.1",
           "play: half-width r of the dead band, in input units (y lags u by r while dragged)"),
    HY_ROW("y_0", NULL, play_y0, y0, HY_KIND_NUMBER, NULL, HY_NOLIM, 0, 0, "0",
           "play: output at t = 0, moved into [u(0) - r, u(0) + r]"));

#ifndef HY_MODEL_ROWS_ONLY /* the stages (the pipeline's compile of this file) */
#include <math.h>

#include "scene_model.h"

/* The path integral is kept in the lag's scale: iy = ∫ (y - u) du, which
 * changes by ∮ y du over a closed path (∮ u du = 0) while its terms are the
 * lag d = y - u (|d| <= r) times du, so it neither overflows where y du would
 * (|u| >= 1e154) nor cancels O(u^2) terms down to an O(r u) area (r = 1e-300).
 * d is tracked as its own state: at |u| = 1e200 and r = 0.01, y = u - r is u. */
typedef struct play_state {
    double u, y, d, iy; /* input, output, lag y - u in [-r, r], ∫ (y - u) du along the path */
} play_state;

static const char *const quantities[] = {"output", NULL};

static void outputs(const play_state *s, double out[HY_RI_NOUT])
{
    out[0] = s->y;
    out[1] = NAN;
    out[2] = s->iy; /* ∫ (y - u) du: its change over a closed path is ∮ y du */
}

static int play_init(const void *par, void *st, double u0, double out[HY_RI_NOUT], hy_error *err)
{
    const play_par *p = par;
    play_state *s = st;
    if (!isfinite(u0))
        return hy_error_set(err, HY_EINVAL, "play operator: input must be finite (got %g)", u0);
    s->u = u0;
    s->y = fmax(u0 - p->r, fmin(u0 + p->r, p->y0));
    s->d = fmax(-p->r, fmin(p->r, p->y0 - u0)); /* the lag, not y - u: exact where y rounds to u */
    s->iy = 0;
    outputs(s, out);
    return HY_OK;
}

/* u monotonically to u: y constant until |u - y| = r, then u -/+ r. */
static int play_apply(const void *par, void *st, double u, double out[HY_RI_NOUT], hy_error *err)
{
    const play_par *p = par;
    play_state *s = st;
    if (!isfinite(u))
        return hy_error_set(err, HY_EINVAL, "play operator: input must be finite (got %g)", u);
    double dir = u > s->u ? 1.0 : -1.0;
    double grab = s->y + dir * p->r;                        /* where u starts to drag y */
    double held = dir * (u - grab) > 0 ? grab : u;          /* end of the constant piece */
    if (held != u)                                          /* the dragged piece, y = u - dir r */
        s->y = u - dir * p->r;
    /* ∫ (y - u) du in the lag's terms: y constant while u moves by up to
     * d + dir r (the lag falls from d to -dir r), then dragged at lag -dir r */
    double move = u - s->u, free_run = s->d + dir * p->r;  /* dir * free_run in [0, 2r] */
    double h = dir * move < dir * free_run ? move : free_run;
    s->iy += h * (s->d - h / 2);
    if (h != move) {
        s->iy += -dir * p->r * (move - h);
        s->d = -dir * p->r;
    } else
        s->d = fmax(-p->r, fmin(p->r, s->d - h));
    s->u = u;
    outputs(s, out);
    return HY_OK;
}

static const hy_rateind_type play_type = {"play", sizeof(play_state), HY_RI_PATH_AREA, play_init, play_apply,
                                          NULL, NULL, NULL};

const hy_scene_model hy_scene_model_play = {
    "play", NULL, quantities, NULL, NULL,
    HY_CAP_STEADY | HY_CAP_YSTAR | HY_CAP_ENERGY | HY_CAP_RATE_INDEPENDENT | HY_CAP_EXACT_STEP,
    "the output y and the path integral of y du (exact: constant, then dragged at distance r)",
    hy_scene_rateind_load, hy_scene_rateind_estimate, hy_scene_rateind_compute, &play_type, sizeof(play_par),
    NULL, NULL, NULL, HY_INPUT_OTHERS, HY_DATA_PATH, HY_COST_PLAY};
#endif
