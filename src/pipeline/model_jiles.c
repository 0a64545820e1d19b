/* SPDX-License-Identifier: MIT */
/* model_jiles.c: the Jiles-Atherton model (J. Magn. Magn. Mater. 61 (1986)
 * 48; numerics in src/core/hy_jiles.c) in the model table: input H in A/m,
 * output B in T (quantity magnetisation: M in A/m). */
#include <stddef.h>
#include <string.h>

#include "hy_jiles.h"
#include "scene_model.h"

static const char *const keys[] = {"ja_ms", "ja_a", "ja_k", "ja_c", "ja_alpha", "ja_m0", NULL};
static const size_t offsets[] = {offsetof(hy_jiles, ms), offsetof(hy_jiles, a), offsetof(hy_jiles, k),
                                 offsetof(hy_jiles, c), offsetof(hy_jiles, alpha), offsetof(hy_jiles, m0)};
/* how hy_jiles.c's messages name each key (alpha before k: one message names both) */
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

static int ja_read(const hy_decl_model *m, void *par, hy_error *err)
{
    hy_jiles *j = par;
    hy_jiles_init(j, 1.6e6, 1100, 400, 0.2, 1.6e-3, err); /* rtol; every key has a schema default */
    hy_scene_model_read_numbers(m, keys, offsets, j);
    return hy_scene_model_relocate(m, &hy_scene_model_jiles, hy_jiles_validate(j, err), err);
}

const hy_scene_model hy_scene_model_jiles = {
    "jiles-atherton", keys, quantities, "H (A/m)", "B (T)",
    HY_CAP_STEADY | HY_CAP_YSTAR | HY_CAP_ENERGY | HY_CAP_RATE_INDEPENDENT | HY_CAP_GSL,
    "H, M and the path integral of B dH (GSL rk8pd in H, restarted at every reversal)", hy_scene_rateind_load,
    hy_scene_rateind_estimate, hy_scene_rateind_compute, &ja_type, sizeof(hy_jiles), ja_read, core_names};
