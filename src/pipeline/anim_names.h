/* SPDX-License-Identifier: MIT */
/* anim_names.h: the names of the built-in animations (anim_scenes.c's table
 * spells each with these macros), without GL: hystviz, which links no
 * OpenGL, checks a name against them before it passes one to
 * hystviz-animate (the gallery's gallery-builtins file).
 *
 *     if (!anim_name_known(name)) ...;   // not a built-in animation
 */
#ifndef HY_ANIM_NAMES_H
#define HY_ANIM_NAMES_H

#include <string.h>

#define HY_ANIM_GAMMA_SWEEP_EX1 "gamma-sweep-ex1"
#define HY_ANIM_GAMMA_SWEEP_EX2 "gamma-sweep-ex2"
#define HY_ANIM_GAMMA_SWEEP_EX3 "gamma-sweep-ex3"
#define HY_ANIM_K_CYCLE_EX2 "k-cycle-ex2"
#define HY_ANIM_K_CYCLE_EX3 "k-cycle-ex3"
#define HY_ANIM_MINOR_LOOP_EX4 "minor-loop-ex4"
#define HY_ANIM_PREISACH_PLANE "preisach-plane"
#define HY_ANIM_NBUILTIN 7 /* anim_scenes.c asserts its table has as many */

/* Whether name is one of the built-in animations (`hystviz animate --list`). */
static inline int anim_name_known(const char *name)
{
    static const char *const names[HY_ANIM_NBUILTIN] = {
        HY_ANIM_GAMMA_SWEEP_EX1, HY_ANIM_GAMMA_SWEEP_EX2, HY_ANIM_GAMMA_SWEEP_EX3, HY_ANIM_K_CYCLE_EX2,
        HY_ANIM_K_CYCLE_EX3,     HY_ANIM_MINOR_LOOP_EX4,  HY_ANIM_PREISACH_PLANE};
    for (size_t i = 0; name && i < HY_ANIM_NBUILTIN; i++)
        if (!strcmp(names[i], name))
            return 1;
    return 0;
}

#endif
