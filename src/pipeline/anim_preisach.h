/* SPDX-License-Identifier: MIT */
/* anim_preisach.h: the built-in animation preisach-plane (issue 22 item 5):
 * the (α, β) half-plane of a Preisach model, relays up or down, shaded by
 * the density, with the staircase boundary of the model's memory, beside the
 * input-output loop it draws, driven by Fig. 2's bimodal input (Definition 1)
 * for two periods from negative saturation.  Listed in anim_scenes.c's table.
 *
 * The helpers below give a frame's state, for tests: the staircase drawn at
 * a time, and where the plane panel is in a frame. */
#ifndef HY_ANIM_PREISACH_H
#define HY_ANIM_PREISACH_H

#include "hy_anim.h"
#include "hy_preisach.h"

int pplane_prepare(void **state, const hy_anim_params *p, hy_error *err);
int pplane_draw(void *state, const hy_anim_frame *f, hy_error *err);
const char *pplane_describe(void *state);
void pplane_release(void *state);

/* The model (density) and the input time at animation time `time`. */
const hy_preisach *pplane_model(const void *state);
double pplane_input_time(const void *state, double time);

/* The memory at animation time `time` (hy_preisach_mem, to free) from
 * negative saturation through every extremum of the input before it. */
int pplane_memory(const void *state, double time, hy_preisach_mem *m, hy_error *err);

/* The staircase of memory m as drawn: vertices (β, α), *n of them (at most
 * cap), from the panel's edge to the diagonal point (u, u); lo/hi stand in
 * for the infinite saturations. */
size_t pplane_staircase(const hy_preisach_mem *m, double lo, double hi, double *beta, double *alpha, size_t cap);

/* The plane panel of frame f: its rectangle in pixels (x, y, w, h, y down)
 * and its ranges: β from lim[0] to lim[1] across, α from lim[2] to lim[3] up. */
int pplane_panel(const void *state, const hy_anim_frame *f, double rect[4], double lim[4], hy_error *err);

#endif
