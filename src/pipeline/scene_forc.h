/* SPDX-License-Identifier: MIT */
/* scene_forc.h: the stages of a [figure] kind = forc (scene_forc.c): the
 * FORC protocol on the scene's model (any rate-independent model of the
 * model table, or the limit y*_u of one that has it) or a measured FORC file
 * ([forc] file), its distribution and its heat map (docs/FORC.md, "In a
 * scene").  scene_run.c and scene_draw.c call these in place of the model's
 * stages and of the line figure when r->figure_kind is FIG_FORC.
 */
#ifndef HY_SCENE_FORC_H
#define HY_SCENE_FORC_H

#include <stdio.h>

#include "hy_plot.h"
#include "scene_run_types.h" /* hy_scene_run */

typedef struct hy_scene_forc hy_scene_forc;

/* Reads [forc] (and the file it names, under the scene's file policy:
 * errors file:line:col of that file) and the model's parameters.  HY_EINVAL
 * at the key for a scene with [series], a model without a FORC protocol. */
int hy_scene_forc_load(hy_scene_run *r, hy_error *err);
/* The work: the protocol's points (or the file's), times the regression's. */
int hy_scene_forc_estimate(const hy_scene_run *r, double *work, char *what, size_t size, hy_error *err);
/* The protocol (unless a file was read) and ρ on the data's grid; log: one line. */
int hy_scene_forc_compute(hy_scene_run *r, FILE *log, hy_error *err);
/* The diagram as format (HY_FORMAT_*) into fp / into memory (*buf malloc'd). */
int hy_scene_forc_draw(const hy_scene_run *r, FILE *fp, int format, hy_error *err);
int hy_scene_forc_render(const hy_scene_run *r, int format, unsigned char **buf, size_t *len, hy_error *err);
/* Every format into paths[i] (hy_out: all or none replaced). */
int hy_scene_forc_write_all(const hy_scene_run *r, char (*paths)[4400], const int *fmt, size_t nf, hy_error *err);
/* ρ as CSV "hc,hu,rho" (hystviz forc -o's format) into out. */
void hy_scene_forc_data(const hy_scene_run *r, FILE *out);
/* Frees r->forc (NULL: nothing). */
void hy_scene_forc_free(hy_scene_run *r);

#endif
