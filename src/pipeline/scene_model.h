/* SPDX-License-Identifier: MIT */
/* scene_model.h: the model table of the scene pipeline, one static const
 * type per [model] kind, in the form of GSL's gsl_odeiv2_step_type.
 *
 * Each model kind (one line of the model table, src/pipeline/meson.build,
 * which generates HY_MODEL_KINDS) has one file that exports
 * `const hy_scene_model hy_scene_model_<id>`: its name, the [model] keys it
 * reads (its own rows, HY_MODEL_ROWS of hy_scene_model_rows.h, or the
 * schema's shared rows it names; each row holds its kind, range, default,
 * unit and doc), what it can compute (caps), the quantities a series can
 * draw from it, and the three stages the pipeline dispatches through it:
 *
 *     const hy_scene_model *mt = hy_scene_model_of(scene);
 *     rc = mt->load(r, err);                 // scene -> model + input, checked
 *     rc = mt->estimate(r, &work, what, n, err);
 *     rc = mt->compute(r, log, err);         // series, loops
 *
 * A rate-independent model (Jiles-Atherton, Preisach) fills `ri` (its core
 * type, hy_rateind.h) and `read` (its core parameters, a struct of
 * ri_par_size bytes, from the decoded [model]: its rows' struct at m->par)
 * and takes load/estimate/compute from scene_rateind.c; nothing else in the
 * pipeline knows it.
 */
#ifndef HY_SCENE_MODEL_H
#define HY_SCENE_MODEL_H

#include <stdio.h>

#include "hy_rateind.h"
#include "hy_scene_schema.h"
#include "scene_run_types.h"

enum {
    HY_CAP_STEADY = 1u << 0,          /* steady periodic state y° and its loops            */
    HY_CAP_YSTAR = 1u << 1,           /* the limit y* as gamma -> infinity (Theorem 2)     */
    HY_CAP_CLOSED_MINOR = 1u << 2,    /* minor loops in closed form (Theorem A; Everett)  */
    HY_CAP_ENERGY = 1u << 3,          /* loop areas: energy per cycle                      */
    HY_CAP_RETURN_POINT = 1u << 4,    /* minor loops close at their reversal point         */
    HY_CAP_RATE_INDEPENDENT = 1u << 5,/* y_gamma = y* for every gamma                      */
    HY_CAP_EXACT_STEP = 1u << 6,      /* an exact solver (no time-stepping error)          */
    HY_CAP_GSL = 1u << 7              /* a right-hand side for GSL odeiv2 steppers          */
};

typedef struct hy_scene_model {
    const char *name;                 /* the [model] kind                                      */
    const char *const *params;        /* the shared [model] keys it reads, NULL-ended; NULL for
                                       * a model with its own rows (hy_scene_model_param)     */
    const char *const *quantities;    /* values of a series' quantity it draws, NULL-ended;
                                       * the first is the default (rate-independent models:
                                       * index q is out[q] of hy_rateind.h)                    */
    const char *u_label, *y_label;    /* loop axes' default labels (NULL: the figure's)        */
    unsigned caps;                    /* HY_CAP_*                                               */
    const char *state;                /* the state in words (docs, hystviz check)              */
    int (*load)(hy_scene_run *r, hy_error *err);
    int (*estimate)(const hy_scene_run *r, double *work, char *what, size_t size, hy_error *err);
    int (*compute)(hy_scene_run *r, FILE *log, hy_error *err);
    /* rate-independent models only (else NULL / 0) */
    const hy_rateind_type *ri;
    size_t ri_par_size;
    /* from the decoded [model] of scene s (files its keys name are read
       through s's file policy); on error par owns nothing.  NULL: par is its
       rows' struct at m->par, copied whole (the rows' ranges check it):
       hy_scene_model_read */
    int (*read)(const hy_scene *s, const hy_decl_model *m, void *par, hy_error *err);
    /* how the core's messages name key i (hy_scene_model_param; NULL: no relocation) */
    const char *const *core_names;
    /* frees what read allocated in par (not par itself); NULL: nothing */
    void (*par_free)(void *par);
    /* what it accepts, beyond its [model] keys (hy_scene_model_accepts
     * refuses the rest): the [input] kinds whose takers (HY_INPUT_KINDS'
     * column) meet this mask, and the series data of bits 1u << HY_DATA_* */
    unsigned inputs;
    unsigned data;
    /* the cost kind of one of its steps (HY_COST_*, hy_cost.h): a
     * rate-independent model's estimate counts its moves at that weight */
    int cost_move;
} hy_scene_model;

/* Series data masks for the table's data column: every data kind, and the
 * series of a model driven along the input's path (seed 000's figures, the
 * data's own; not g, the friction function, nor a data kind of a model's
 * own, HY_DATA_BOUCWEN). */
#define HY__DATA_BIT(id, name) | 1u << HY_DATA_##id
#define HY_DATA_ALL (0u HY_SERIES_DATA(HY__DATA_BIT))
#define HY_DATA_PATH (HY_DATA_ALL & ~(1u << HY_DATA_G | 1u << HY_DATA_BOUCWEN))

/* Each model file's entry: hy_scene_model_dahl, ..._jiles, ..._preisach. */
#define HY_SCENE_MODEL_DECL(id, name) extern const hy_scene_model hy_scene_model_##id;
HY_MODEL_KINDS(HY_SCENE_MODEL_DECL)

/* The table: every model kind in HY_MODEL_KINDS order, NULL-terminated. */
extern const hy_scene_model *const hy_scene_models[];

/* The name of capability bit cap (one HY_CAP_*: "steady", "ystar", ...), or
 * NULL for a bit that is none (docs, bindings: hy_schema_json). */
const char *hy_scene_cap_name(unsigned cap);

/* The model named kind, or NULL. */
const hy_scene_model *hy_scene_model_find(const char *kind);
/* The model of the scene's [model] kind (its default when unset); never NULL
 * for a parsed scene (the schema admits only the table's kinds). */
const hy_scene_model *hy_scene_model_of(const hy_decl_model *m);
/* The i-th [model] key the model reads (its params, else its own rows in
 * the schema's order), or NULL past the last. */
const char *hy_scene_model_param(const hy_scene_model *mt, size_t i);
/* mt->read, or its rows' struct copied whole where mt has no read. */
int hy_scene_model_read(const hy_scene_model *mt, const hy_scene *s, const hy_decl_model *m, void *par,
                        hy_error *err);
/* Whether key is one of the model's [model] keys (kind included). */
int hy_scene_model_has_key(const hy_scene_model *mt, const char *key);
/* Refuses (HY_EINVAL at the line) what r's model r->mtype does not accept,
 * from its table entry: an [input] kind it does not take, a series data it
 * does not draw (naming the models that do, or what it accepts where that is
 * the shorter list), a [model] key it does not read. */
int hy_scene_model_accepts(const hy_scene_run *r, hy_error *err);

/* ---- shared by the model files (the generic driver scene_run.c, scene_rateind.c, model_friction.c) ---- */

/* The figure kinds FIG_ID, the index of the schema's figure kind list
 * (both from HY_FIGURE_KINDS). */
#define HY__FIG_ID(id, name) FIG_##id,
enum { HY_FIGURE_KINDS(HY__FIG_ID) };
#undef HY__FIG_ID

/* The Dahl/LuGre/filter model of the decoded [model] as r->model, checked
 * (HY_EINVAL at the key a message names). */
int hy_scene_run_build_model(hy_scene_run *r, hy_error *err);
/* Re-raises a core message (err->msg, err->code) at the scene location of
 * the key of keys (NULL-ended) it starts with, else at [section]. */
int hy_scene_located(const hy_decl_head *h, const char *const *keys, hy_error *err);
/* The scene's [input] as r->input (every input hystviz has). */
int hy_scene_run_build_input(hy_scene_run *r, hy_error *err);
/* The bimodal input's t1..t4 where [input] t gives them, else NULL (slopes
 * ±1), and the shape ([input] shape: HY_SHAPE_*), as build_input reads them. */
const double *hy_scene_bimodal_t(const hy_decl_input *d);
int hy_scene_input_shape(const hy_decl_input *d);
/* What a Dahl/LuGre run computes besides its series' own curves: the steady
 * state (ystar, ysteady, yk, loops, placeholders) and the loops (minor,
 * major, placeholders); the plan's rule, shared with hystviz sweep's
 * closed-form kernel. */
void hy_scene_friction_needs(const hy_scene_doc *doc, int *need_steady, int *need_loops);
/* HY_DATA_* of a decoded series' data into *data; -1 when it has none. */
int hy_scene_series_data(const hy_decl_series *ds, int *data);
/* The series data names, indexed by HY_DATA_*. */
const char *hy_scene_data_name(int data);
/* The start of a series' line of render -v (name, data, points, time; no
 * line end): 1, or 0 and nothing written for a measured or modelled series
 * (their own lines: hy_scene_data_log). */
int hy_scene_series_log(const hy_run_series *se, FILE *log);

/* Measured data (scene_data.c): every [data] read once, through the scene's
 * file policy (build_run, before the model's load); r->input for [input]
 * kind = data (the driving data's u over t = the sample index; refused for
 * a model that is not rate-independent); the points of the series data =
 * measured and modelled (hy_scene_run_compute, after the model's own). */
int hy_scene_run_read_data(hy_scene_run *r, hy_error *err);
int hy_scene_run_data_input(hy_scene_run *r, hy_error *err);
int hy_scene_run_data_series(hy_scene_run *r, hy_error *err);
/* Before computing: each data = measured or modelled series names a [data]
 * of the scene (modelled: the one that drives the model). */
int hy_scene_run_data_check(const hy_scene_run *r, hy_error *err);
/* A data series' {NAME.area} (the shoelace area of its points against the
 * measured u, one record only) and {NAME.rms} (modelled: RMS of model -
 * measured); NaN where it has none.  And its lines of render -v. */
double hy_scene_data_value(const hy_scene_run *r, const hy_run_series *se, const char *field);
void hy_scene_data_log(const hy_scene_run *r, FILE *log);

/* r->series from the scene's [series] sections (name, data, gamma, k). */
int hy_scene_run_series_new(hy_scene_run *r, hy_error *err);
/* se->x, se->y of n points (se->n = n); HY_ENOMEM naming the series. */
int hy_run_series_alloc(hy_run_series *se, size_t n, hy_error *err);
/* The time grid of [compute] points, cycles, tspan: [t0, t1] in *npts points,
 * *per a period; HY_EINVAL at the key (tspan before 0, over 2e7 points). */
int hy_scene_run_grid(const hy_scene_run *r, double *t0, double *t1, size_t *npts, size_t *per, long *cycles,
                      hy_error *err);
/* The ϱ intervals of r->loops' minor loops (major 0) or of the rest of the
 * period (major 1), at most max; -1 when a loop is narrower than ϱ resolves. */
int hy_scene_loop_intervals(const hy_scene_run *r, int major, double *a, double *b, size_t max);
/* The refusal of that -1, at the input's key. */
int hy_scene_too_narrow(const hy_scene_run *r, hy_error *err);
/* HY_EINVAL at the series' data when it cannot be drawn in the figure's kind. */
int hy_scene_check_series_kind(const hy_scene_run *r, const hy_run_series *se, hy_error *err);

/* The Dahl/LuGre stages (model_friction.c) and the rate-independent ones
 * (scene_rateind.c), for the model files' table entries. */
int hy_scene_friction_load(hy_scene_run *r, hy_error *err);
int hy_scene_friction_estimate(const hy_scene_run *r, double *work, char *what, size_t size, hy_error *err);
int hy_scene_friction_compute(hy_scene_run *r, FILE *log, hy_error *err);
int hy_scene_rateind_load(hy_scene_run *r, hy_error *err);
int hy_scene_rateind_estimate(const hy_scene_run *r, double *work, char *what, size_t size, hy_error *err);
int hy_scene_rateind_compute(hy_scene_run *r, FILE *log, hy_error *err);

/* Reads shared [model] keys (all numbers) into par at the given offsets, with
 * the schema's defaults: keys[i] fills the double at offsets[i]. */
void hy_scene_model_read_numbers(const hy_decl_model *m, const char *const *keys, const size_t *offsets, void *par);
/* The sign that turns ∮ y du into the loop area a scene prints (docs/SCENES.md,
 * "Loop areas"): +1 where the model's loops dissipate ∮ y du (a force against
 * a displacement: Dahl, LuGre, the Dahl filter, the Bouc-Wen operator:
 * clockwise loops), -1 where they dissipate ∮ u dy = -∮ y du (a response to
 * a field: Jiles-Atherton, Preisach, play: counter-clockwise loops). */
int hy_scene_model_area_sign(const hy_scene_model *mt);

/* Re-raises a core message (err->msg) with status rc at the [model] key it
 * names (the first mt->core_names[i] found in it is hy_scene_model_param(mt,
 * i)), else at [model]; rc 0 returns 0. */
/* Frees what mt's read allocated in par (a rate-independent model's). */
void hy_scene_model_par_free(const hy_scene_model *mt, void *par);

int hy_scene_model_relocate(const hy_decl_model *m, const hy_scene_model *mt, int rc, hy_error *err);

#endif
