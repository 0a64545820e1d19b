/* SPDX-License-Identifier: MIT */
/* model_preisach.c: the classical Preisach model (numerics in
 * src/core/hy_preisach.c: Everett function, staircase memory) in the model
 * table, with the symmetric factorised density of model.pr_density. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "hy_preisach.h"
#include "scene_model.h"

static const char *const keys[] = {"pr_density", "pr_hc", "pr_width", "pr_ys", NULL};
static const char *const core_names[] = {"distribution", "centre must", "width", "ys", NULL};
static const char *const quantities[] = {"output", NULL};

static void outputs(const hy_preisach_mem *m, double out[HY_RI_NOUT])
{
    out[0] = m->y;
    out[1] = NAN;
    out[2] = NAN;
}

static int pr_init(const void *par, void *st, double u0, double out[HY_RI_NOUT], hy_error *err)
{
    int rc = hy_preisach_mem_init(st, par, u0, err);
    if (!rc)
        outputs(st, out);
    return rc;
}

static int pr_apply(const void *par, void *st, double u, double out[HY_RI_NOUT], hy_error *err)
{
    (void)par;
    int rc = hy_preisach_mem_apply(st, u, NULL, err);
    outputs(st, out);
    return rc;
}

static int pr_copy(const void *par, void *dst, const void *src, hy_error *err)
{
    (void)par;
    const hy_preisach_mem *a = src;
    hy_preisach_mem *b = dst;
    *b = *a;
    b->s = malloc(a->cap * sizeof *b->s);
    b->c = malloc(a->cap * sizeof *b->c);
    if (!b->s || !b->c) {
        hy_preisach_mem_free(b);
        return hy_error_set(err, HY_ENOMEM, "out of memory");
    }
    memcpy(b->s, a->s, (a->n + 1) * sizeof *b->s);
    memcpy(b->c, a->c, (a->n + 1) * sizeof *b->c);
    return HY_OK;
}

static void pr_free(void *st) { hy_preisach_mem_free(st); }

static int pr_area(const void *par, double lo, double hi, double *area, hy_error *err)
{
    return hy_preisach_loop_area(par, lo, hi, area, err);
}

static const hy_rateind_type pr_type = {"preisach", sizeof(hy_preisach_mem), HY_RI_RETURN_POINT, pr_init,
                                        pr_apply, pr_copy, pr_free, pr_area};

static int pr_read(const hy_decl_model *m, void *par, hy_error *err)
{
    const char *dist = hy_decl_enum_text(&m->h, offsetof(hy_decl_model, pr_density), m->pr_density);
    int rc = hy_preisach_symmetric(par, hy_preisach_dist_find(dist), m->pr_hc, m->pr_width, m->pr_ys, err);
    return hy_scene_model_relocate(m, &hy_scene_model_preisach, rc, err);
}

const hy_scene_model hy_scene_model_preisach = {
    "preisach", keys, quantities, NULL, NULL,
    HY_CAP_STEADY | HY_CAP_YSTAR | HY_CAP_CLOSED_MINOR | HY_CAP_ENERGY | HY_CAP_RETURN_POINT |
        HY_CAP_RATE_INDEPENDENT | HY_CAP_EXACT_STEP,
    "the staircase of the input's dominant extrema (wiping-out)", hy_scene_rateind_load, hy_scene_rateind_estimate,
    hy_scene_rateind_compute, &pr_type, sizeof(hy_preisach), pr_read, core_names};
