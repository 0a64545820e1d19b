/* SPDX-License-Identifier: MIT */
/* model_friction.c: Dahl, LuGre (seed 000, Eqs. 1-3) and the Example-1
 * system (16) in the model table; their numerics are src/core (hy_model,
 * hy_gamma, hy_ode, hy_limit, hy_loops) and their stages scene_run.c. */
#include "scene_model.h"

#define FRICTION_CAPS (HY_CAP_STEADY | HY_CAP_YSTAR | HY_CAP_ENERGY | HY_CAP_EXACT_STEP | HY_CAP_GSL)

static const char *const output_only[] = {"output", NULL};
static const char *const dahl_keys[] = {"rho", "fc", "x0", NULL};
static const char *const lugre_keys[] = {"sigma0", "sigma1", "sigma2", "fc", "fs", "vs", "beta", "x0", NULL};
static const char *const filter_keys[] = {"rho", "fc", "tau", "x0", NULL};

const hy_scene_model hy_scene_model_dahl = {
    "dahl", dahl_keys, output_only, NULL, NULL, FRICTION_CAPS | HY_CAP_CLOSED_MINOR | HY_CAP_RATE_INDEPENDENT,
    "the bristle state z (y = Fc w)", hy_scene_friction_load, hy_scene_friction_estimate, hy_scene_friction_compute,
    NULL, 0, NULL, NULL, NULL};

const hy_scene_model hy_scene_model_lugre = {
    "lugre", lugre_keys, output_only, NULL, NULL, FRICTION_CAPS | HY_CAP_CLOSED_MINOR,
    "the bristle deflection z", hy_scene_friction_load, hy_scene_friction_estimate, hy_scene_friction_compute,
    NULL, 0, NULL, NULL, NULL};

const hy_scene_model hy_scene_model_dahl_filter = {
    "dahl-filter", filter_keys, output_only, NULL, NULL, FRICTION_CAPS,
    "the Dahl state and the filter output", hy_scene_friction_load, hy_scene_friction_estimate,
    hy_scene_friction_compute, NULL, 0, NULL, NULL, NULL};
