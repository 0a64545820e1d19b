/* SPDX-License-Identifier: MIT */
/* model_jiles.c: the Jiles-Atherton model (J. Magn. Magn. Mater. 61 (1986)
 * 48, or the total-M form of Jiles, Thoelke and Devine, IEEE Trans. Magn. 28
 * (1992) 27: ja_variant; numerics in src/core/hy_jiles.c) in the model table:
 * input H in A/m, output B in T (quantity magnetisation: M in A/m).  Its
 * [model] keys fill a hy_jiles (rows: hy_scene_model_rows.h); an input beyond
 * what the model integrates is refused at [input], at load when the scene's
 * numbers show it, else when the step budget runs out. */
#include <stddef.h>

#include "hy_cost.h"
#include "hy_jiles.h"
#include "hy_scene_model_rows.h"

#define PAR hy_jiles
HY_MODEL_ROWS(jiles, hy_jiles,
    HY_ROW("M_s", "A/m", ja_ms, ms, HY_KIND_NUMBER, NULL, HY_POS, 0, 0, "1.6e6",
           "jiles-atherton: saturation magnetisation Ms in A/m (default: Jiles & Atherton 1986)"),
    HY_ROW("a", "A/m", ja_a, a, HY_KIND_NUMBER, NULL, HY_POS, 0, 0, "1100",
           "jiles-atherton: a in A/m, the width of the anhysteretic curve Ms L(H_e/a)"),
    HY_ROW("k", "A/m", ja_k, k, HY_KIND_NUMBER, NULL, HY_POS, 0, 0, "400",
           "jiles-atherton: pinning k in A/m (the loop's half-width)"),
    HY_ROW("c", NULL, ja_c, c, HY_KIND_NUMBER, NULL, HY_NONNEG, 0, 0, "0.2",
           "jiles-atherton: reversible fraction c: in [0, 1) for jiles1986; >= 0 for jtd1992 (whose reversible "
           "term is c/(1 + c) dM_an/dH_e: JAmodel's c = 1 is a half)"),
    HY_ROW("α", NULL, ja_alpha, alpha, HY_KIND_NUMBER, NULL, HY_NONNEG, 0, 0, "1.6e-3",
           "jiles-atherton: mean-field coupling alpha (alpha Ms / (3a) < 1, and small enough for k)"),
    HY_ROW("M_0", "A/m", ja_m0, m0, HY_KIND_NUMBER, NULL, HY_NOLIM, 0, 0, "0",
           "jiles-atherton: magnetisation M in A/m at t = 0 (|m0| < Ms; 0: demagnetised)"),
    HY_ROW(NULL, NULL, ja_variant, variant, HY_KIND_ENUM, hy_jiles_variant_names, HY_NOLIM, 0, 0, "jiles1986",
           "jiles-atherton: the law dM/dH: jiles1986 (Jiles & Atherton 1986, chi/(1 - alpha chi)) or jtd1992 (the "
           "total-M form of Jiles, Thoelke & Devine 1992); equations under Magnetic models"));

#ifndef HY_MODEL_ROWS_ONLY /* the stages (the pipeline's compile of this file) */
#include <math.h>
#include <string.h>

#include "scene_model.h"

/* how hy_jiles.c's messages name each row's key (alpha before k: one message names both) */
static const char *const core_names[] = {"Jiles-Atherton Ms", "Jiles-Atherton a (", "Jiles-Atherton k (",
                                         "Jiles-Atherton c (", "Jiles-Atherton alpha", "m0", NULL};
static const char *const quantities[] = {"output", "magnetisation", NULL};

static void outputs(const hy_jiles_state *s, double out[HY_RI_NOUT])
{
    out[0] = hy_jiles_b(s);
    out[1] = s->M;
    out[2] = HY_MU0 * s->hb; /* ∫ B dH */
}

static int ja_init(const void *par, void *st, double u0, double out[HY_RI_NOUT], hy_error *err)
{
    (void)err;
    hy_jiles_state_init(par, st, u0);
    outputs(st, out);
    return HY_OK;
}

static int ja_apply(const void *par, void *st, double u, double out[HY_RI_NOUT], hy_error *err)
{
    int rc = hy_jiles_apply(par, st, u, NULL, err);
    outputs(st, out);
    return rc;
}

static int ja_copy(const void *par, void *dst, const void *src, hy_error *err)
{
    (void)par;
    (void)err;
    memcpy(dst, src, sizeof(hy_jiles_state));
    return HY_OK;
}

static const hy_rateind_type ja_type = {"jiles-atherton", sizeof(hy_jiles_state), HY_RI_PATH_AREA, ja_init,
                                        ja_apply, ja_copy, NULL, NULL};

static int ja_read(const hy_scene *s, const hy_decl_model *m, void *par, hy_error *err)
{
    (void)s;
    hy_jiles *j = par;
    memcpy(j, m->par, sizeof *j); /* every row: set or its default */
    j->rtol = HY_JILES_RTOL;
    j->stepper = NULL;
    j->max_steps = 0; /* HY_JILES_MAX_STEPS */
    j->cancel = NULL; /* hy_scene_rateind_compute hands it the run's */
    return hy_scene_model_relocate(m, &hy_scene_model_jiles, hy_jiles_validate(j, err), err);
}

/* The core's messages that blame the input's scale, not a [model] key. */
static const char *const input_tags[] = {"the input's scale is beyond", "Jiles-Atherton step budget", NULL};

/* Re-raises such a message (already placed at [model] by the shared stages)
 * at the scene's [input] section. */
static int at_input(hy_scene_run *r, int rc, hy_error *err)
{
    for (size_t i = 0; rc && input_tags[i]; i++) {
        const char *p = strstr(err->msg, input_tags[i]);
        if (p) {
            char core[sizeof err->msg];
            snprintf(core, sizeof core, "%s", p);
            return hy_decl_error(&r->doc.input.h, HY_DECL_HEAD, err, rc, "%s", core);
        }
    }
    return rc;
}

/* The shared load, then the input's largest |H| and a period's travel against
 * what the model integrates (hy_jiles_input_check): refused before anything
 * is computed. */
static int ja_load(hy_scene_run *r, hy_error *err)
{
    int rc = hy_scene_rateind_load(r, err);
    if (rc)
        return rc;
    double hmax = fabs(hy_input_u(&r->input, 0));
    for (size_t i = 0; i < r->input.nruns; i++)
        hmax = fmax(hmax, fmax(fabs(r->input.runs[i].u0), fabs(r->input.runs[i].u1)));
    return at_input(r, hy_jiles_input_check(r->ri_par, hmax, r->input.rho_T, err), err);
}

static int ja_compute(hy_scene_run *r, FILE *log, hy_error *err)
{
    ((hy_jiles *)r->ri_par)->cancel = hy_scene_run_cancel_hook(r); /* every 64 GSL steps of one move too */
    return at_input(r, hy_scene_rateind_compute(r, log, err), err);
}

const hy_scene_model hy_scene_model_jiles = {
    "jiles-atherton", NULL, quantities, "H (A/m)", "B (T)",
    HY_CAP_STEADY | HY_CAP_YSTAR | HY_CAP_ENERGY | HY_CAP_RATE_INDEPENDENT | HY_CAP_GSL,
    "H, M and the path integral of B dH (GSL rk8pd in H, restarted at every reversal)", ja_load,
    hy_scene_rateind_estimate, ja_compute, &ja_type, sizeof(hy_jiles), ja_read, core_names, NULL, HY_INPUT_OTHERS, HY_DATA_PATH, HY_COST_JILES};
#endif
