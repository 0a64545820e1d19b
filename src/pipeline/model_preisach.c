/* SPDX-License-Identifier: MIT */
/* model_preisach.c: the classical Preisach model (numerics in
 * src/core/hy_preisach.c: Everett function, staircase memory) in the model
 * table, with the symmetric factorised density of its [model] keys (rows:
 * hy_scene_model_rows.h), on the half-plane or the triangle up to pr_hs,
 * from negative or positive saturation or the demagnetised state. */
#include <stddef.h>

#include "hy_cost.h"
#include "hy_preisach.h"
#include "hy_scene_model_rows.h"

/* The [model] keys: the density hy_preisach_symmetric builds, its support
 * and the state before u(0). */
typedef struct pr_par {
    int density; /* index in hy_preisach_dist_names: the HY_PREISACH_ value */
    double hc, width, ys;
    int start;   /* index in start_names */
    int support; /* index in support_names */
    double hs;
    const char *file; /* pr_file: a tabulated density instead (NULL: none) */
} pr_par;

#ifdef HY_MODEL_ROWS_ONLY /* the rows' enums (the stages read the indices) */
static const char *const start_names[] = {"negative", "positive", "demagnetised", NULL};
static const char *const support_names[] = {"halfplane", "triangle", NULL};
#endif

#define PAR pr_par
HY_MODEL_ROWS(preisach, pr_par,
    HY_ROW(NULL, NULL, pr_density, density, HY_KIND_ENUM, hy_preisach_dist_names, HY_NOLIM, 0, 0, "gaussian",
           "preisach: distribution of both switching fields (factorised density)"),
    HY_ROW("H_c", NULL, pr_hc, hc, HY_KIND_NUMBER, NULL, HY_NONNEG, 0, 0, "0.5",
           "preisach: centre of the up-switching fields alpha (the down-switching beta around -pr_hc), in input units"),
    HY_ROW("w", NULL, pr_width, width, HY_KIND_NUMBER, NULL, HY_POS, 0, 0, "0.2",
           "preisach: width of both switching-field distributions, in input units"),
    HY_ROW("y_s", NULL, pr_ys, ys, HY_KIND_NUMBER, NULL, HY_POS, 0, 0, "1", "preisach: output at positive saturation"),
    HY_ROW(NULL, NULL, pr_start, start, HY_KIND_ENUM, start_names, HY_NOLIM, 0, 0, "negative",
           "preisach: state before u(0): negative or positive saturation, or demagnetised (the state an alternating "
           "input of decaying amplitude leaves: relays up where alpha + beta < 0), then moved to u(0)"),
    HY_ROW(NULL, NULL, pr_support, support, HY_KIND_ENUM, support_names, HY_NOLIM, 0, 0, "halfplane",
           "preisach: where the density lives, normalised to saturation there: the half-plane alpha >= beta, or the "
           "triangle -pr_hs <= beta <= alpha <= pr_hs (saturated for |u| >= pr_hs)"),
    HY_ROW("H_s", NULL, pr_hs, hs, HY_KIND_NUMBER, NULL, HY_POS, 0, 0, "1",
           "preisach: saturation field of the triangle (pr_support = triangle), in input units"),
    HY_ROW(NULL, NULL, pr_file, file, HY_KIND_PATH, NULL, HY_NOLIM, 0, 0, NULL,
           "preisach: a tabulated density instead of the analytic one: a density file (rows hc,hu,mu on a regular "
           "grid, written by hystviz forc --density-out; docs/FORC.md), relative to the scene file and below its "
           "directory; its relays' total weight is the saturation output (pr_density, pr_hc, pr_width, pr_ys, "
           "pr_support and pr_hs are then refused)"));

#ifndef HY_MODEL_ROWS_ONLY /* the stages (the pipeline's compile of this file) */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "hy_preisach_table.h"
#include "hy_scene_policy.h"
#include "scene_model.h"

/* how hy_preisach.c's messages name each row's key */
static const char *const core_names[] = {"distribution", "centre must", "width", "ys", "Preisach start", "on the triangle",
                                         "hs", "tabulated density", NULL};
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

#define AT(field) (offsetof(hy_decl_model, par) + offsetof(pr_par, field))

static void pr_par_free(void *par)
{
    hy_preisach *pr = par;
    hy_preisach_table *t = (hy_preisach_table *)pr->table; /* allocated by pr_file_read */
    if (t) {
        hy_preisach_table_free(t);
        free(t);
    }
    pr->table = NULL;
}

/* pr_file: the density file read under the scene's file policy (file:line:col
 * of the density file on refusal), its relays as pr's density. */
static int pr_file_read(const hy_scene *s, const hy_decl_model *m, hy_preisach *pr, hy_error *err)
{
    const pr_par *p = (const void *)m->par;
    for (size_t i = 0; i < hy_model_rows_preisach.n; i++) { /* the rows of the analytic density: all but two */
        const hy_scene_key_spec *k = &hy_model_rows_preisach.rows[i];
        if (k->field != AT(start) && k->field != AT(file) && hy_decl_got(&m->h, k->field) == HY_SCENE_SET)
            return hy_decl_error(&m->h, k->field, err, HY_EINVAL, "%s is for the analytic densities: pr_file's "
                                 "tabulated density is used as written", k->name);
    }
    char *text;
    size_t len;
    int user, rc = hy_scene_read_path_max(s, "model", NULL, "pr_file", HY_PREISACH_TABLE_MAX_BYTES, &text, &len,
                                          &user, err);
    if (rc)
        return rc; /* at the key, by the policy */
    hy_forc_grid g;
    hy_preisach_table *t = calloc(1, sizeof *t);
    rc = t ? hy_preisach_table_read(text, len, p->file, &g, err) : hy_error_set(err, HY_ENOMEM, "out of memory");
    free(text);
    if (!rc) {
        rc = hy_preisach_table_from_grid(t, &g, err);
        free(g.rho);
    }
    if (!rc && (rc = hy_preisach_tabulated(pr, t, err)))
        rc = hy_decl_error(&m->h, AT(file), err, rc, "%s: %s", p->file, err->msg);
    if (rc) {
        if (t)
            hy_preisach_table_free(t);
        free(t);
        pr->table = NULL;
    }
    return rc;
}

static int pr_read(const hy_scene *s, const hy_decl_model *m, void *par, hy_error *err)
{
    const pr_par *p = (const void *)m->par;
    hy_preisach *pr = par;
    if (p->file) {
        int rc = pr_file_read(s, m, pr, err);
        pr->start = p->start == 2 ? HY_PREISACH_DEMAGNETISED : p->start == 1 ? HY_PREISACH_POSITIVE : HY_PREISACH_NEGATIVE;
        return rc;
    }
    int rc = hy_preisach_symmetric(pr, p->density, p->hc, p->width, p->ys, err);
    if (!rc && p->support == 1)
        rc = hy_preisach_support(pr, p->hs, err);
    pr->start = p->start == 2 ? HY_PREISACH_DEMAGNETISED : p->start == 1 ? HY_PREISACH_POSITIVE : HY_PREISACH_NEGATIVE;
    return hy_scene_model_relocate(m, &hy_scene_model_preisach, rc, err);
}

const hy_scene_model hy_scene_model_preisach = {
    "preisach", NULL, quantities, NULL, NULL,
    HY_CAP_STEADY | HY_CAP_YSTAR | HY_CAP_CLOSED_MINOR | HY_CAP_ENERGY | HY_CAP_RETURN_POINT |
        HY_CAP_RATE_INDEPENDENT | HY_CAP_EXACT_STEP,
    "the staircase of the input's dominant extrema (wiping-out)", hy_scene_rateind_load, hy_scene_rateind_estimate,
    hy_scene_rateind_compute, &pr_type, sizeof(hy_preisach), pr_read, core_names, pr_par_free, HY_INPUT_OTHERS, HY_DATA_PATH, HY_COST_PREISACH};
#endif
