/* SPDX-License-Identifier: MIT */
/* scene_boucwen.h: the Bouc-Wen path of the scene pipeline (seeds/001, Figs. 1-2).
 *
 * A scene with `[model] kind = boucwen` is not built by the Dahl/LuGre code of
 * scene_run.c: its [model] holds Table 1 (m, c, k, alpha, bw_beta, bw_gamma,
 * delta, nu), its [input] is a force (sine, multisine or sweep at a working
 * rate fs), and its series are `data = boucwen` with a `quantity` (output y
 * in mm, input u in N, output and transient in dB, spectrum).  The output is
 * integrated by Newmark at fs x upsample and decimated back to fs like the
 * benchmark, then stored as hy_run_series that scene_draw.c draws unchanged:
 *
 *     rc = hy_scene_boucwen_load(r, err);          // in hy_scene_run_load
 *     if (hy_scene_is_boucwen(&r->doc))           // in hy_scene_run_compute
 *         return hy_scene_boucwen_compute(r, log, err);
 *
 * Every error names file:line:col of the key at fault (docs/SCENES.md).
 */
#ifndef HY_SCENE_BOUCWEN_H
#define HY_SCENE_BOUCWEN_H

#include <stdio.h>

#include "scene_run_types.h"

/* True if the scene's [model] kind is boucwen. */
int hy_scene_is_boucwen(const hy_scene_doc *d);

/* Checks a parsed scene before anything is computed.  A boucwen scene:
 * parameters, input, compute keys, figure kind and every series (errors at
 * the key's location).  Any other scene: refuses the boucwen-only pieces
 * (input kind multisine or sweep, data = boucwen).  HY_OK or HY_EINVAL. */
int hy_scene_boucwen_load(hy_scene_run *r, hy_error *err);

/* The work estimate of a boucwen scene (Newmark steps plus series samples),
 * from its setup alone; errors as hy_scene_boucwen_load. */
int hy_scene_boucwen_work(const hy_scene_run *r, double *work, hy_error *err);

/* Computes every series of a boucwen scene into r->series (x: t in s, or u in
 * N in loop figures, or f in Hz for spectra), logging the plan and timings to
 * log (may be NULL).  On error the series computed so far stay in r for
 * hy_scene_run_free. */
int hy_scene_boucwen_compute(hy_scene_run *r, FILE *log, hy_error *err);

#endif
