/* SPDX-License-Identifier: MIT */
/* export_anim.h: `hystviz export ANIMATION` (issue 21 item 6): an animation
 * (a built-in NAME or a scene with [keyframe] sections) as one offline HTML
 * page that plays it at its frame rate, with play/pause, a scrub slider and a
 * frame counter (src/app/export/anim.html).
 *
 * The frames are rendered by hystviz-animate (hystviz links no OpenGL), into
 * a temporary directory that is removed afterwards, and embedded as they are:
 * frame i of the page is byte for byte the PNG that `hystviz animate NAME
 * --frames i:i+1` (same --set, --size) writes.  Frames equal to an earlier
 * one (a held keyframe) are stored once.  The page:
 *
 *     <script id="meta" type="application/json">{"title":..., "name":...,
 *         "fps":F, "frames":N, "width":W, "height":H, "duration":S,
 *         "order":[d0,d1,...], "command":"hystviz animate ..."}</script>
 *     <script class="frame" type="application/octet-stream">BASE64</script>  (one per distinct PNG)
 *
 * frame i shows the distinct PNG order[i] (0-based, in order of first use). */
#ifndef HY_EXPORT_ANIM_H
#define HY_EXPORT_ANIM_H

#include <stddef.h>

#include "hy_scene_policy.h"

typedef struct exp_anim_opts {
    const char *name;              /* a built-in animation or SCENE.scene */
    char *const *sets;             /* --set overrides, as animate takes them */
    size_t nsets;
    const hy_scene_policy *pol;    /* --include-dir, --max-work */
    const char *size;              /* --size WxH, or NULL for the animation's */
    long jobs;                     /* -j of the renderer */
    const char *out;               /* the page */
    int quiet;
} exp_anim_opts;

/* Renders and writes the page; the exit status: 0 written, 1 a failure
 * while rendering or writing, 2 a bad animation or option (the renderer's
 * message printed), 3 animations not built.  Nothing is written unless 0. */
int exp_anim_run(const exp_anim_opts *o);

/* Removes directory dir with its files and, depth levels down, its
 * directories (a temporary tree of frames; links are removed, not followed). */
void exp_remove_tree(const char *dir, int depth);

#endif
