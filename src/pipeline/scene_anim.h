/* SPDX-License-Identifier: MIT */
/* scene_anim.h: animations declared in scene files ([animation] and
 * [keyframe NAME] sections, docs/SCENES.md "Animations").
 *
 * Load the scene once to read its timing and keyframes and to validate them
 * (every error names file:line:col), check every frame's overrides before a
 * frame is written, then hand scene_anim_draw to hy_anim_run.  Each frame
 * applies the interpolated keyframe values as overrides to a freshly parsed
 * scene and runs the normal pipeline (hy_scene_run_load/compute).  Frames
 * that resolve to the same override text share one run, computed once by the
 * first thread that needs it; a run is lent to one drawing thread at a time
 * (under its own mutex, so no scene is used by two threads at once) and freed
 * after its last frame.
 *
 *     scene_anim a;
 *     if (scene_anim_load(&a, "scenes/anim_gamma_sweep_ex3.scene", &err)) ...
 *     if (scene_anim_check(&a, nframes, &err)) ...
 *     hy_anim_run(&p, scene_anim_draw, &a, &stats, &err);   (GL builds only)
 *     scene_anim_free(&a);
 */
#ifndef HY_SCENE_ANIM_H
#define HY_SCENE_ANIM_H

#include <pthread.h>
#include <stddef.h>
#include <stdint.h>

#include "hy_scene.h"
#include "hy_scene_decl.h"
#include "hy_scene_policy.h"
#include "hy_status.h"

/* One [keyframe NAME]: the key it drives and its keys. */
typedef struct scene_kf {
    const hy_decl_keyframe *decl; /* the decoded section (owned by scene_anim.doc) */
    const char *label;        /* the section's NAME (owned by the scene)      */
    char target[160];         /* "section.key" or "section.NAME.key"          */
    int integer;              /* the key is an INTEGER: values are rounded    */
    const double *t, *v;      /* n keys (owned by the scene)                  */
    size_t n;
    int ease;                 /* 0 linear, 1 smooth                           */
    int log;                  /* interpolate log(v)                           */
} scene_kf;

typedef struct scene_entry scene_entry;

#define SCENE_ANIM_MAX_SETS 64    /* the user's overrides of one animation */

typedef struct scene_anim {
    const char *path;
    hy_scene *scene;          /* the scene as parsed                          */
    hy_scene_doc doc;         /* ... decoded: timing, keyframes, error places */
    scene_kf *kf;
    size_t nkf;
    double duration, fps;     /* the [animation] values (or defaults)         */
    int fps_set, quality_set; /* whether the scene set them                   */
    const char *quality;
    char name[256];           /* output base name                             */
    pthread_mutex_t mu;       /* guards everything below                     */
    pthread_cond_t cv;        /* a run finished computing                     */
    scene_entry **entries;    /* runs in use, one per distinct override text  */
    size_t nentries;
    uint64_t *frame_hash;     /* per frame: hash of its override text         */
    long nhash;
    long computes, hits;      /* runs computed / frames that reused a run     */
    hy_scene_policy pol;      /* include dirs and work budget of every load   */
    char *text;               /* the scene's text (NULL: read from path)      */
    size_t len;
    char **user;              /* the user's overrides (--set), before the keyframes' */
    size_t nuser;
    int single;               /* one drawing thread, frames in any order: keep one run */
    scene_entry *last;        /* ... the last frame's */
} scene_anim;

/* Parses the scene at path, reads [animation] and every [keyframe NAME] and
 * validates them (known numeric key, equal lengths, ascending times, log
 * values > 0).  On error returns a status with file:line:col in err and
 * leaves nothing to free. */
int scene_anim_load(scene_anim *a, const char *path, hy_error *err);

/* As scene_anim_load under pol (--include-dir, --max-work; NULL: defaults);
 * pol's include dirs must outlive a. */
int scene_anim_load_policy(scene_anim *a, const char *path, const hy_scene_policy *pol, hy_error *err);

/* As scene_anim_load_policy, from the scene's text when text is not NULL
 * (read by the caller through one descriptor: hystviz serve; path then
 * only names it in messages and is where its includes are looked up), with
 * the user's overrides sets ("section.key=value", at most
 * SCENE_ANIM_MAX_SETS, applied before each frame's keyframe values, which
 * beat them).  text and sets are copied. */
int scene_anim_load_src(scene_anim *a, const char *path, const char *text, size_t len, char *const *sets,
                        size_t nsets, const hy_scene_policy *pol, hy_error *err);

/* The keyframe's value at time t seconds: exact key values at the key times,
 * held before the first and after the last. */
double scene_kf_eval(const scene_kf *k, double t);

/* The time a frame shows: index/(nframes-1) of the duration (0 for a single
 * frame), so the first frame shows the start and the last one the end. */
double scene_anim_time(long index, long nframes, double duration);

/* Writes the overrides of time t ("model.sigma0=2.5", one per keyframe) into
 * buf and points sets[0..nkf) at them; returns 0, or -1 if buf is too small. */
int scene_anim_sets(const scene_anim *a, double t, char *buf, size_t size, char **sets);

/* Checks every frame before rendering: applies its overrides to a copy of the
 * scene (a refused value is reported at its keyframe's values, file:line:col)
 * and builds its model and input (a refused combination: at the first keyframe);
 * the work of all frames together must fit the budget (docs/SCENES.md). */
int scene_anim_check(const scene_anim *a, long nframes, double duration, hy_error *err);

/* Frees the scene, the keyframes and the cached runs. */
void scene_anim_free(scene_anim *a);

#include "hy_config.h"
#if HY_HAVE_GL
#include "hy_anim.h"
/* hy_anim_draw_fn: computes (or waits for, or reuses) the run of frame f's
 * overrides and draws its figure on f->data and f->overlay.  With
 * a->single set (one drawing thread, frames in any order) only the last
 * frame's run is kept. */
int scene_anim_draw(void *state, const hy_anim_frame *f, hy_error *err);
#endif

#endif
