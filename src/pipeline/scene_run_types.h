/* SPDX-License-Identifier: MIT */
/* scene_run_types.h: the types of a scene's run (hy_scene_run, its series and
 * measured data), at the bottom of src/pipeline: scene_run.h and the stages'
 * headers (scene_verify.h, ...) include it, and it includes no pipeline
 * header, so a stage's header does not depend on the driver's
 * (tools/include_graph.py: no circle between files).  scene_run.h is the
 * manual of the run (load, compute, draw, write).
 */
#ifndef HY_SCENE_RUN_TYPES_H
#define HY_SCENE_RUN_TYPES_H

#include <stdio.h>

#include "hy_input.h"
#include "hy_limit.h"
#include "hy_loops.h"
#include "hy_model.h"
#include "hy_plot.h"
#include "hy_scene.h"
#include "hy_scene_decl.h"
#include "hy_table.h"

#define HY_DATA_ENUM(id, name) HY_DATA_##id,
enum { HY_SERIES_DATA(HY_DATA_ENUM) HY_DATA_COUNT };

typedef struct hy_run_series {
    const char *name;         /* the [series NAME]                                */
    const hy_decl_series *decl; /* its decoded section (in r->doc)              */
    int data;                 /* HY_DATA_*                                         */
    double gamma;             /* for ygamma/transient                              */
    long k;                   /* for yk                                            */
    double *x, *y;            /* n points (NaN separates pieces)                  */
    size_t n;
    double err;               /* max error against the exact answer, or NaN       */
    double dist;              /* ygamma/transient: max |y_γ - y*_u| over the series'
                               * points when the limit is computed, else NaN       */
    const char *err_ref;      /* what err was measured against, or "not measured:
                               * WHY" with err NaN; NULL: nothing to measure      */
    char err_note[224];       /* storage for err_ref                              */
    double seconds;           /* compute time                                     */
    int has_mark;             /* a marker at 'at'                                 */
    double mark_x, mark_y;
    size_t grid_n;            /* figure_only: the points of the grid it would have
                               * sampled when it holds fewer (thinned, or drawn
                               * as its mark only), else 0                       */
    double *ymeas;            /* data = modelled: the measured y at each point
                               * (NaN in the gaps), else NULL; hystviz data
                               * writes it and the residual beside the model's  */
} hy_run_series;

/* A [data NAME] section, read once at load (scene_data.c): the whole file's
 * table and the records chosen ([data] record), rows i0 .. i1-1. */
typedef struct hy_run_data {
    const hy_decl_data *decl; /* its decoded section (in r->doc)                 */
    const char *name;
    hy_table tb;              /* every row and record of the file, scaled       */
    size_t r0, r1;            /* the records chosen: r0 .. r1-1                 */
    size_t i0, i1;            /* their rows                                      */
    double *area;             /* per chosen record: its closed polygon's signed
                               * area, hy_table_area (∮ u dy, counter-clockwise
                               * positive)                                       */
} hy_run_data;

/* figure_only: a series with more points than this on its grid is drawn from
 * fewer (scene_run.c, "Drawn-only series"); none of the gallery's has as many. */
enum { HY_THIN_MIN = 131072 };
/* ... and its drawn polyline stays within this fraction of the narrowest y
 * window the scene can show of the exact closed form's polyline. */
#define HY_THIN_TOL 1e-6
/* ... through at least this many points of each loop interval, evenly in ϱ,
 * so that the output's own simplification (hy_simplify.h) finds vertices as
 * far apart as it would on a grid of that size */
#define HY_THIN_SPAN 32768.0

/* err_ref of a series whose error was not measured because of no_verify. */
#define HY_NOT_SAMPLED "not measured: the run was asked for no error measurement (outside hystviz sweep's sample)"

typedef struct hy_scene_run {
    hy_scene *scene;          /* the parsed scene: read by load's decode only    */
    hy_scene_doc doc;         /* the scene decoded (hy_scene_decl.h): what the
                               * pipeline reads, with where each value was written */
    const char *path;
    const struct hy_scene_model *mtype; /* the [model] kind's type (scene_model.h)  */
    struct hy_scene_run *panels; /* the [panel] scenes' runs, drawn side by side  */
    size_t npanels;
    void *ri_par;             /* a rate-independent model's parameters (malloc'd) */
    int ri_periods;           /* its periods driven until the output was periodic */
    hy_model model;
    hy_input input;
    int have_input;
    int figure_kind;          /* index in the schema's figure kinds               */
    hy_steady steady;
    int have_steady;
    hy_loops loops;
    int have_loops;
    hy_run_series *series;
    size_t nseries;
    hy_run_data *data;        /* the [data] sections, in file order, read at load */
    size_t ndata;
    const hy_run_data *drive; /* the one that drives the model ([input] kind = data), or NULL */
    int model_marked;         /* hy_scene_run_set_model marked the scene        */
    char plan[2048];          /* the plan, one step a line (render -v)            */
    double budget;            /* work budget (hy_scene_policy, --max-work)        */
    double work;              /* the estimate of the last compute                 */
    double *cost_counts;      /* NULL, or HY_COST_COUNT counts the estimate adds
                               * each kind of work to (hy_cost.h; --print-work)  */
    const char *formats;      /* set before compute: the formats the figure will
                               * be written in ("svg,png"; NULL: the scene's
                               * [output] formats): a PNG's pixels count as work */
    int numbers_only;         /* set before compute: u, ψ and g are not sampled
                               * (n = 0; the table-only path of hystviz sweep);
                               * the closed forms are, so their measured error
                               * is the same as with figures (issue 11)          */
    int no_verify;            /* set before compute: closed-form series and exact
                               * y_γ solves are not measured against the
                               * long-double references (err NaN, err_ref "not
                               * measured: ..."); with numbers_only the
                               * closed-form series are then not sampled at all
                               * (hystviz sweep's points outside the sample)    */
    int figure_only;          /* set before compute: the series are drawn, never
                               * written as data (render, serve's figures, the
                               * gallery without --data).  Series of more than
                               * HY_THIN_MIN grid points are then drawn from
                               * fewer: one drawn only as its mark (style none,
                               * marker, at) is evaluated at that point; a
                               * Dahl/LuGre loop is kept at the grid points its
                               * curvature bound needs (HY_THIN_TOL), unless
                               * [figure] full_resolution                       */
    int scene_borrowed;       /* scene belongs to the caller (not freed)          */
    int doc_borrowed;         /* doc's section arrays belong to the caller        */
    int (*cancelled)(void *); /* set before compute (may be NULL): polled between
                               * the steps of compute and render (each gamma
                               * solve, each series, the Newmark run, before
                               * drawing); nonzero stops the work with
                               * HY_ECANCEL (serve: the client has gone)          */
    void *cancel_ctx;         /* the argument cancelled is called with            */
    hy_cancel cancel_hook;    /* {cancelled, cancel_ctx} for the core's loops
                               * (hy_scene_run_cancel_hook)                      */
    double seconds_compute;
    struct hy_scene_forc *forc; /* [figure] kind = forc: its data and grid (scene_forc.h) */
} hy_scene_run;

/* HY_ECANCEL (with a message) if r->cancelled says the work is no longer
 * wanted, else HY_OK.  Here, with the run's type, so that every stage polls
 * it without calling into the driver. */
static inline int hy_scene_run_check_cancel(const hy_scene_run *r, hy_error *err)
{
    if (r->cancelled && r->cancelled(r->cancel_ctx))
        return hy_error_set(err, HY_ECANCEL, "%s: stopped: the work is no longer wanted", r->path);
    return HY_OK;
}

/* r->cancelled as the hook the core's long loops poll inside a series
 * (hy_cancel.h: hy_rateind, hy_ode_opts, hy_newmark_opts, hy_figure), or
 * NULL when r has none. */
static inline const hy_cancel *hy_scene_run_cancel_hook(hy_scene_run *r)
{
    r->cancel_hook.fn = r->cancelled;
    r->cancel_hook.ctx = r->cancel_ctx;
    return r->cancelled ? &r->cancel_hook : NULL;
}

/* An axis range from [figure] xlim or ylim and xlog or ylog (lo = hi = 0:
 * automatic); every figure kind's axes take theirs through this. */
static inline hy_range hy_scene_axis_range(const hy_scene_pair *lim, int log)
{
    hy_range rg = {0, 0, 0, 0};
    if (!lim->is_auto) {
        rg.lo = lim->v[0];
        rg.hi = lim->v[1];
    }
    rg.log = log;
    return rg;
}

#endif
