/* SPDX-License-Identifier: MIT */
/* anim_scenes.h: the built-in animations of seed 000, Section 4 (Examples 1-4),
 * each a prepare/draw/release triple driven by hy_anim_run.
 *
 *     const anim_scene *sc = anim_scene_find("gamma-sweep-ex2");
 *     void *st;
 *     if (sc->prepare(&st, &p, &err)) ...;
 *     hy_anim_run(&p, sc->draw, st, &stats, &err);
 *     fprintf(stderr, "%s\n", sc->describe(st));   // solves, cache hits
 *     sc->release(st);
 *
 * The draw functions run on several threads; their caches are locked.
 * gamma-sweep-ex1 integrates with GSL (hy_ode.h): callers turn GSL's
 * aborting error handler off first (gsl_set_error_handler_off).
 */
#ifndef HY_ANIM_SCENES_H
#define HY_ANIM_SCENES_H

#include "hy_anim.h"

typedef struct anim_scene {
    const char *name;
    const char *summary;
    double duration;           /* default seconds */
    /* Computes what every frame shares; HY_EINVAL/HY_ENOMEM/HY_ENUM with a message. */
    int (*prepare)(void **state, const hy_anim_params *p, hy_error *err);
    hy_anim_draw_fn draw;
    /* Work counters after a run, e.g. "42 solves for 42 distinct gamma, 18 reused". */
    const char *(*describe)(void *state);
    void (*release)(void *state);
} anim_scene;

/* The scenes, NULL-terminated. */
const anim_scene *const *anim_scene_list(void);
/* The scene called name, or NULL. */
const anim_scene *anim_scene_find(const char *name);

/* Solves counted by the γ caches of the last run of state (tests). */
long anim_scene_solves(void *state);

#endif
