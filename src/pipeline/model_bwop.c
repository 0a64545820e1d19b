/* SPDX-License-Identifier: MIT */
/* model_bwop.c: the Bouc-Wen hysteresis operator as a rate-independent model
 * (the z equation of seed 001, Eq. (3), driven by a displacement u instead of
 * the oscillator's y):
 *     ż = α u̇ − β (γ |u̇| |z|^(ν−1) z + δ u̇ |z|^ν),
 * i.e. dz/du = α − β (γ s |z|^(ν−1) z + δ |z|^ν) with s = sign(u̇), so z
 * depends on the path of u only.  For ν = 1 it is linear in z between sign
 * changes of z: with r the distance travelled in direction s and σ = sign z,
 *     dz/dr = s α − κ z,   κ = β (γ + s δ σ),
 * solved exactly, z = z∞ + (z0 − z∞) e^{−κ r}, z∞ = s α / κ, the crossing of
 * z = 0 located in closed form (r* = log1p(−z0/z∞)/κ) and the step restarted
 * there; ∫ z du along the path is the exact integral of the same expression.
 * It saturates at z_s = α / (β (γ + δ)) when β (γ + δ) > 0 (else z grows
 * without bound as u rises: refused).  One file and one line of the model
 * table (src/pipeline/meson.build); its keys are the Bouc-Wen oscillator's
 * shared rows of hy_scene_schema.c (alpha, bw_beta, ...). */
#include <math.h>
#include <stddef.h>
#include <string.h>

#include "hy_cost.h"
#include "scene_model.h"

typedef struct bwop {
    double alpha, beta, gamma, delta, nu, z0;
} bwop;

typedef struct bwop_state {
    double u, z, iz;   /* input, output, ∫ z du along the path */
} bwop_state;

static const char *const keys[] = {"alpha", "bw_beta", "bw_gamma", "delta", "nu", "x0", NULL};
static const size_t offsets[] = {offsetof(bwop, alpha), offsetof(bwop, beta), offsetof(bwop, gamma),
                                 offsetof(bwop, delta), offsetof(bwop, nu), offsetof(bwop, z0)};
static const char *const core_names[] = {"alpha must", "beta (bw_beta)", "gamma + delta", "delta = ", "nu = ", "z0", NULL};
static const char *const quantities[] = {"output", NULL};

/* (1 - e^{-x})/x for any x, 1 at 0 */
static double phi1(double x)
{
    return x == 0 ? 1.0 : -expm1(-x) / x;
}

/* Moves the distance d >= 0 in direction s without z changing sign (or
 * reaching 0 at the end): z and ∫ z dr updated. */
static void piece(const bwop *p, double *z, double *iz_r, int s, double d)
{
    int sg = *z > 0 ? 1 : *z < 0 ? -1 : s;
    double kappa = p->beta * (p->gamma + s * p->delta * sg);
    double x = kappa * d;
    if (kappa == 0) {
        *iz_r += *z * d + s * p->alpha * d * d / 2;
        *z += s * p->alpha * d;
        return;
    }
    double zinf = s * p->alpha / kappa;
    *iz_r += zinf * d + (*z - zinf) * d * phi1(x);
    *z = zinf + (*z - zinf) * exp(-x);
}

/* Distance in direction s at which z reaches 0, or INFINITY if it does not:
 * z(r) = z∞ + (z0 − z∞) e^{−κ r} = 0 at r = log1p(−z0/z∞)/κ when that is > 0. */
static double to_zero(const bwop *p, double z, int s)
{
    if (z == 0) /* it leaves 0 in direction s (dz/dr = s α there) */
        return INFINITY;
    double kappa = p->beta * (p->gamma + s * p->delta * (z > 0 ? 1 : -1));
    if (kappa == 0) {
        double r = -z / (s * p->alpha);
        return r > 0 ? r : INFINITY;
    }
    double w = -z / (s * p->alpha / kappa);
    if (!(w > -1))
        return INFINITY;
    double r = log1p(w) / kappa;
    return r > 0 && isfinite(r) ? r : INFINITY;
}

static int op_init(const void *par, void *st, double u0, double out[HY_RI_NOUT], hy_error *err)
{
    (void)err;
    const bwop *p = par;
    bwop_state *s = st;
    s->u = u0;
    s->z = p->z0;
    s->iz = 0;
    out[0] = s->z;
    out[1] = NAN;
    out[2] = 0;
    return HY_OK;
}

static int op_apply(const void *par, void *st, double u, double out[HY_RI_NOUT], hy_error *err)
{
    const bwop *p = par;
    bwop_state *s = st;
    if (!isfinite(u))
        return hy_error_set(err, HY_EINVAL, "Bouc-Wen operator: input must be finite (got %g)", u);
    int dir = u > s->u ? 1 : -1;
    double left = fabs(u - s->u), iz_r = 0;
    while (left > 0) {
        double r0 = to_zero(p, s->z, dir), d = r0 < left ? r0 : left;
        piece(p, &s->z, &iz_r, dir, d);
        if (r0 < left)
            s->z = 0; /* exactly at the switch */
        left -= d;
    }
    s->iz += dir * iz_r;
    s->u = u;
    out[0] = s->z;
    out[1] = NAN;
    out[2] = s->iz;
    return HY_OK;
}

static int op_copy(const void *par, void *dst, const void *src, hy_error *err)
{
    (void)par;
    (void)err;
    memcpy(dst, src, sizeof(bwop_state));
    return HY_OK;
}

static const hy_rateind_type op_type = {"boucwen-operator", sizeof(bwop_state), HY_RI_PATH_AREA | HY_RI_AREA_YDU,
                                        op_init, op_apply,
                                        op_copy, NULL, NULL};

static int op_validate(const bwop *p, hy_error *err)
{
    if (!(p->alpha > 0))
        return hy_error_set(err, HY_EINVAL, "alpha must be > 0 for the Bouc-Wen operator (got %g)", p->alpha);
    if (!(p->beta > 0))
        return hy_error_set(err, HY_EINVAL, "beta (bw_beta) must be > 0 for the Bouc-Wen operator (got %g): "
                            "0 is the linear spring z = alpha u", p->beta);
    if (p->nu != 1)
        return hy_error_set(err, HY_EINVAL, "nu = %g: the Bouc-Wen operator is solved exactly for nu = 1 only", p->nu);
    if (!(p->gamma + p->delta > 0))
        return hy_error_set(err, HY_EINVAL,
                            "gamma + delta = %g must be > 0: else z grows without bound as the input rises "
                            "(no saturation alpha / (beta (gamma + delta)))", p->gamma + p->delta);
    if (!(p->gamma - p->delta > 0) && !(p->gamma - p->delta == 0))
        return hy_error_set(err, HY_EINVAL,
                            "delta = %g exceeds gamma = %g: z would be pushed away from 0 on every reversal",
                            p->delta, p->gamma);
    return HY_OK;
}

static int op_read(const hy_scene *s, const hy_decl_model *m, void *par, hy_error *err)
{
    (void)s;
    bwop *p = par;
    *p = (bwop){1, 1, 0.5, 0.5, 1, 0};
    hy_scene_model_read_numbers(m, keys, offsets, p);
    return hy_scene_model_relocate(m, &hy_scene_model_bwop, op_validate(p, err), err);
}

const hy_scene_model hy_scene_model_bwop = {
    "boucwen-operator", keys, quantities, NULL, NULL,
    HY_CAP_STEADY | HY_CAP_YSTAR | HY_CAP_ENERGY | HY_CAP_RATE_INDEPENDENT | HY_CAP_EXACT_STEP,
    "z and the path integral of z du (exact piecewise-exponential steps)", hy_scene_rateind_load,
    hy_scene_rateind_estimate, hy_scene_rateind_compute, &op_type, sizeof(bwop), op_read, core_names, NULL, HY_INPUT_OTHERS, HY_DATA_PATH, HY_COST_PLAY};
