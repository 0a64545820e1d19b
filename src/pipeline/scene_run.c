/* SPDX-License-Identifier: MIT */
/* scene_run.c: scene → plan → computed series → hy_figure → files (DESIGN.md
 * data flow); the series are those of seed 000's figures: u, ψ_u, g, y*_u,
 * y°_u, y_γ, y*_{u,k}, transients, major and minor loops. */
#include "scene_run.h"

#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>

#include "hy_cost.h"
#include "hy_gamma.h"
#include "hy_ode.h"
#include "hy_plot.h"
#include "scene_boucwen.h"
#include "scene_forc.h"
#include "scene_model.h"
#include "scene_verify.h"

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

#define DATA_NAME(id, name) name,
static const char *const data_names[] = {HY_SERIES_DATA(DATA_NAME)};

/* Re-raises a core message at the scene location of the key it names. */
static int located(const hy_decl_head *h, const char *const *keys, hy_error *err)
{
    char msg[sizeof err->msg];
    memcpy(msg, err->msg, sizeof msg);
    for (size_t i = 0; keys[i]; i++) {
        size_t n = strlen(keys[i]);
        if (!strncmp(msg, keys[i], n) && (msg[n] == ' ' || msg[n] == '[' || msg[n] == '/'))
            return hy_decl_error(h, hy_decl_offset(h, keys[i]), err, err->code, "%s", msg);
    }
    /* Definition 1 messages name u_min,1 ... u_max,2: point at the first one named */
    static const char *const paper[] = {"u_min,1", "u_min,2", "u_max,1", "u_max,2"};
    static const char *const key_of[] = {"umin1", "umin2", "umax1", "umax2"};
    const char *first = NULL;
    int which = -1;
    for (int i = 0; i < 4; i++) {
        const char *at = strstr(msg, paper[i]);
        if (at && (!first || at < first)) {
            first = at;
            which = i;
        }
    }
    if (which >= 0 && hy_decl_got(h, hy_decl_offset(h, key_of[which])) == HY_SCENE_SET)
        return hy_decl_error(h, hy_decl_offset(h, key_of[which]), err, err->code, "%s", msg);
    return hy_decl_error(h, HY_DECL_HEAD, err, err->code, "%s", msg);
}

const char *hy_scene_data_name(int data)
{
    return data >= 0 && data < (int)(sizeof data_names / sizeof *data_names) ? data_names[data] : "?";
}

int hy_scene_run_build_model(hy_scene_run *r, hy_error *err)
{
    static const char *const keys[] = {"sigma0", "sigma1", "sigma2", "fc", "fs", "vs", "beta", "rho", "tau", "x0", NULL};
    const hy_decl_model *d = &r->doc.model;
    const char *kind = hy_decl_enum_text(&d->h, offsetof(hy_decl_model, kind), d->kind);
    hy_model *m = &r->model;
    if (!strcmp(kind, "dahl"))
        hy_model_dahl_init(m, d->rho, d->fc);
    else if (!strcmp(kind, "dahl-filter"))
        hy_model_dahl_filter_init(m, d->rho, d->fc, d->tau);
    else {
        hy_model_lugre_init(m, d->sigma0, d->sigma1, d->fc, d->fs, d->vs, d->beta);
        m->sigma2 = d->sigma2;
    }
    m->x0 = d->x0;
    if (hy_model_validate(m, err))
        return located(&d->h, keys, err);
    return HY_OK;
}

/* A pwl input from its points t0, u0, t1, u1, ... */
static int pwl_input(hy_input *in, const hy_scene_list *pts, hy_error *err)
{
    size_t n = pts->n;
    double *t = malloc(n * sizeof *t);
    if (!t)
        return hy_error_set(err, HY_ENOMEM, "out of memory");
    for (size_t i = 0; i < n / 2; i++) {
        t[i] = pts->v[2 * i];
        t[n / 2 + i] = pts->v[2 * i + 1];
    }
    int rc = hy_input_pwl(in, t, t + n / 2, n / 2, err);
    free(t);
    return rc;
}

/* A file input: the samples of [input] file, read through the scene's path
 * policy (the one read of the scene after decode: the policy's roots). */
static int file_input(hy_scene_run *r, hy_error *err)
{
    const hy_decl_input *d = &r->doc.input;
    char *text;
    size_t len;
    int user, rc = hy_scene_read_path(r->scene, "input", NULL, "file", &text, &len, &user, err);
    if (rc)
        return rc; /* located at the key by the policy */
    rc = hy_input_text(&r->input, text, len, d->file, user, err);
    free(text);
    if (rc)
        return hy_decl_error(&d->h, offsetof(hy_decl_input, file), err, rc, "%s", err->msg);
    return HY_OK;
}

const double *hy_scene_bimodal_t(const hy_decl_input *d)
{
    return hy_decl_got(&d->h, offsetof(hy_decl_input, t)) >= 0 && d->t.n == 4 ? d->t.v : NULL;
}

int hy_scene_input_shape(const hy_decl_input *d)
{
    return strcmp(hy_decl_enum_text(&d->h, offsetof(hy_decl_input, shape), d->shape), "cosine") ? HY_SHAPE_LINEAR
                                                                                                 : HY_SHAPE_COSINE;
}

int hy_scene_run_build_input(hy_scene_run *r, hy_error *err)
{
    static const char *const keys[] = {"umin1", "umin2", "umax1", "umax2", "extrema", "times", "amp", "period",
                                       "offset", "points", "file", NULL};
    const hy_decl_input *d = &r->doc.input;
    const hy_decl_head *h = &d->h;
    int shape = hy_scene_input_shape(d), rc;
    if (d->kind == HY_INPUT_BIMODAL) {
        rc = hy_input_bimodal(&r->input, d->umin1, d->umin2, d->umax1, d->umax2, hy_scene_bimodal_t(d), shape, err);
        if (rc && strstr(err->msg, "t1 < t2"))
            return hy_decl_error(h, offsetof(hy_decl_input, t), err, rc, "%s", err->msg);
    } else if (d->kind == HY_INPUT_MULTIMODAL) {
        if (hy_decl_got(h, offsetof(hy_decl_input, extrema)) < 0)
            return hy_decl_error(h, offsetof(hy_decl_input, kind), err, HY_EINVAL, "a multimodal input needs 'extrema'");
        int have_tm = hy_decl_got(h, offsetof(hy_decl_input, times)) >= 0;
        if (have_tm && d->times.n != d->extrema.n + 1)
            return hy_decl_error(h, offsetof(hy_decl_input, times), err, HY_EINVAL,
                                 "'times' needs %zu values (0, then the time of each extremum after the first, then the period), got %zu",
                                 d->extrema.n + 1, d->times.n);
        rc = hy_input_multimodal(&r->input, d->extrema.v, d->extrema.n, have_tm ? d->times.v : NULL, shape, err);
    } else if (d->kind == HY_INPUT_TRIANGLE) {
        double lo = hy_decl_got(h, offsetof(hy_decl_input, min)) >= 0 ? d->min : d->offset - d->amp;
        double hi = hy_decl_got(h, offsetof(hy_decl_input, max)) >= 0 ? d->max : d->offset + d->amp;
        rc = hy_input_triangle(&r->input, lo, hi, d->period, err);
    } else if (d->kind == HY_INPUT_SINE)
        rc = hy_input_sine(&r->input, d->amp, d->period, d->offset, err);
    else if (d->kind == HY_INPUT_PWL) {
        if (hy_decl_got(h, offsetof(hy_decl_input, points)) < 0)
            return hy_decl_error(h, offsetof(hy_decl_input, kind), err, HY_EINVAL, "a pwl input needs 'points = t0, u0, t1, u1, ...'");
        rc = pwl_input(&r->input, &d->points, err);
    } else if (d->kind == HY_INPUT_DATA) /* measured u: read at load (scene_data.c) */
        return hy_scene_run_data_input(r, err);
    else { /* file */
        if (hy_decl_got(h, offsetof(hy_decl_input, file)) < 0)
            return hy_decl_error(h, offsetof(hy_decl_input, kind), err, HY_EINVAL, "a file input needs 'file = \"PATH\"'");
        if ((rc = file_input(r, err)))
            return rc;
    }
    if (rc)
        return located(h, keys, err);
    r->have_input = 1;
    return HY_OK;
}

static int build_run(hy_scene_run *r, const hy_scene_doc *base, hy_error *err);
static int build_decoded(hy_scene_run *r, int validated, hy_error *err);

int hy_scene_run_load(hy_scene_run *r, const char *path, char *const *sets, size_t nsets, hy_error *err)
{
    return hy_scene_run_load_policy(r, path, sets, nsets, NULL, err);
}

/* The steps after parsing (rc: the parse's status): overrides, model, input. */
static int load_parsed(hy_scene_run *r, int rc, char *const *sets, size_t nsets, hy_error *err)
{
    for (size_t i = 0; !rc && i < nsets; i++)
        rc = hy_scene_set(r->scene, sets[i], err);
    if (!rc)
        rc = build_run(r, NULL, err);
    else
        hy_scene_run_free(r);
    return rc;
}

int hy_scene_run_load_scene(hy_scene_run *r, hy_scene *scene, const char *path, double budget, hy_error *err)
{
    return hy_scene_run_load_marked(r, scene, NULL, path, budget, err);
}

int hy_scene_run_load_marked(hy_scene_run *r, hy_scene *scene, const hy_scene_doc *base, const char *path,
                             double budget, hy_error *err)
{
    memset(r, 0, sizeof *r);
    r->path = path;
    r->budget = budget;
    r->scene = scene;
    r->scene_borrowed = 1;
    return build_run(r, base, err);
}

int hy_scene_run_load_doc(hy_scene_run *r, hy_scene *scene, const hy_scene_doc *doc, int validated, const char *path,
                          double budget, hy_error *err)
{
    /* zeroed around doc, which is copied (a sweep's every point: the doc is most of the run's bytes) */
    size_t at = offsetof(hy_scene_run, doc), after = at + sizeof r->doc;
    memset(r, 0, at);
    memset((char *)r + after, 0, sizeof *r - after);
    r->doc = *doc;
    r->path = path;
    r->budget = budget;
    r->scene = scene;
    r->scene_borrowed = 1;
    r->doc_borrowed = 1;
    return build_decoded(r, validated, err);
}

/* A series' quantity, where written, is one the model draws. */
static int check_quantities(const hy_scene_run *r, hy_error *err)
{
    for (size_t i = 0; i < r->doc.nseries; i++) {
        const hy_decl_series *ds = &r->doc.series[i];
        if (hy_decl_got(&ds->h, offsetof(hy_decl_series, quantity)) != HY_SCENE_SET)
            continue;
        const char *q = hy_decl_enum_text(&ds->h, offsetof(hy_decl_series, quantity), ds->quantity);
        size_t j = 0;
        while (r->mtype->quantities[j] && strcmp(r->mtype->quantities[j], q))
            j++;
        if (!r->mtype->quantities[j]) {
            char list[160] = "";
            for (j = 0; r->mtype->quantities[j]; j++)
                snprintf(list + strlen(list), sizeof list - strlen(list), "%s%s", j ? ", " : "",
                         r->mtype->quantities[j]);
            return hy_decl_error(&ds->h, offsetof(hy_decl_series, quantity), err, HY_EINVAL,
                                 "a %s model draws quantity %s, not %s", r->mtype->name, list, q);
        }
    }
    return HY_OK;
}

/* The [panel NAME] scenes, each loaded as its own run (one level: a panel
 * scene has no panels), read through the scene's path policy; a panel file
 * the scene names (not --set) reads, besides what lies below its own
 * directory, what lies below the scene's (its include dir): a panel in
 * scenes/ferrite/ includes "../style.scene" and reads "../data/...". */
static int load_panels(hy_scene_run *r, hy_error *err)
{
    size_t n = r->doc.npanel;
    if (!n)
        return HY_OK;
    if (!(r->panels = calloc(n, sizeof *r->panels)))
        return hy_error_set(err, HY_ENOMEM, "out of memory");
    for (size_t i = 0; i < n; i++) {
        const hy_decl_panel *dp = &r->doc.panel[i];
        const char *name = dp->h.name, *path = dp->scene; /* decode refused a panel without one */
        char *text;
        size_t len;
        int user, rc = hy_scene_read_path(r->scene, "panel", name, "scene", &text, &len, &user, err);
        if (rc)
            return rc;
        char dir[4200];
        const char *slash = r->path ? strrchr(r->path, '/') : NULL, *dirs[1] = {dir};
        if (slash == r->path) /* "/x.scene": the root */
            snprintf(dir, sizeof dir, "/");
        else
            snprintf(dir, sizeof dir, "%.*s", slash ? (int)(slash - r->path) : 1, slash ? r->path : ".");
        hy_scene_policy pol = hy_scene_policy_default();
        if (!user)
            pol.include_dirs = dirs, pol.ninclude_dirs = 1;
        rc = hy_scene_run_load_text(&r->panels[i], path, text, len, NULL, 0, &pol, err);
        free(text);
        if (rc)
            return rc;
        r->npanels = i + 1;
        r->panels[i].budget = r->budget;
        if (r->panels[i].npanels)
            return hy_decl_error(&dp->h, offsetof(hy_decl_panel, scene), err, HY_EINVAL,
                                 "%s has panels of its own: a panel is one figure", path);
    }
    return HY_OK;
}

/* The model and input of the parsed scene r->scene (decoded from base, the
 * doc at its mark, where given); r freed on error. */
static int build_run(hy_scene_run *r, const hy_scene_doc *base, hy_error *err)
{
    int rc = base ? hy_scene_decode_marked(r->scene, base, &r->doc, err) : hy_scene_decode(r->scene, &r->doc, err);
    if (rc) {
        hy_scene_run_free(r);
        return rc;
    }
    return build_decoded(r, 0, err);
}

/* build_run's steps after decoding: model, input, panels, checks (the
 * placeholders' unless validated: hy_scene_run_load_doc). */
static int build_decoded(hy_scene_run *r, int validated, hy_error *err)
{
    int rc;
    r->figure_kind = r->doc.figure.kind;
    r->mtype = hy_scene_model_of(&r->doc.model);
    rc = check_quantities(r, err);
    if (!rc)
        rc = hy_scene_run_read_data(r, err); /* every [data] file, once */
    if (!rc)
        rc = r->figure_kind == FIG_FORC ? hy_scene_forc_load(r, err) : r->mtype->load(r, err);
    if (!rc)
        rc = hy_scene_run_data_check(r, err); /* data = measured, modelled: their [data] */
    if (!rc)
        rc = load_panels(r, err);
    if (!rc && !validated)
        rc = hy_scene_run_validate(r, err);
    if (rc)
        hy_scene_run_free(r);
    return rc;
}

int hy_scene_run_load_policy(hy_scene_run *r, const char *path, char *const *sets, size_t nsets,
                             const hy_scene_policy *pol, hy_error *err)
{
    memset(r, 0, sizeof *r);
    r->path = path;
    r->budget = hy_scene_policy_budget(pol);
    return load_parsed(r, hy_scene_parse_file_policy(path, pol, &r->scene, err), sets, nsets, err);
}

int hy_scene_run_load_text(hy_scene_run *r, const char *path, const char *text, size_t len, char *const *sets,
                           size_t nsets, const hy_scene_policy *pol, hy_error *err)
{
    memset(r, 0, sizeof *r);
    r->path = path;
    r->budget = hy_scene_policy_budget(pol);
    return load_parsed(r, hy_scene_parse_buffer_policy(path, text, len, pol, &r->scene, err), sets, nsets, err);
}

void hy_scene_run_free(hy_scene_run *r)
{
    if (!r->doc_borrowed)
        hy_scene_doc_free(&r->doc);
    for (size_t i = 0; i < r->npanels; i++)
        hy_scene_run_free(&r->panels[i]);
    free(r->panels);
    for (size_t i = 0; i < r->nseries; i++) {
        free(r->series[i].x);
        free(r->series[i].y);
        free(r->series[i].ymeas);
    }
    free(r->series);
    for (size_t i = 0; i < r->ndata; i++) {
        hy_table_free(&r->data[i].tb);
        free(r->data[i].area);
    }
    free(r->data);
    if (r->have_loops)
        hy_loops_free(&r->loops);
    if (r->have_steady)
        hy_steady_free(&r->steady);
    if (r->have_input)
        hy_input_free(&r->input);
    if (r->ri_par)
        hy_scene_model_par_free(r->mtype, r->ri_par);
    free(r->ri_par);
    hy_scene_forc_free(r);
    if (!r->scene_borrowed)
        hy_scene_free(r->scene);
    memset(r, 0, sizeof *r);
}

/* ---- planning -------------------------------------------------------- */

typedef struct gamma_solve {
    double gamma;
    double *y;         /* on the shared grid */
    double err;        /* against the exact solution, or NaN */
    const char *ref;
    char refbuf[224];
    int exact;         /* solved by the exact solver */
    double seconds;
} gamma_solve;

typedef struct plan {
    double t0, t1;     /* the time span of every t-grid */
    size_t npts;       /* grid points over [t0, t1] */
    double *t;         /* the grid */
    long cycles;
    size_t per_period; /* points per period */
    gamma_solve *solves;
    size_t nsolves;
    int verbose;
} plan;

/* Appends a line to r->plan when the plan is logged (p->verbose): the
 * formatting is a good part of a table-only sweep point's time. */
static void plan_line(const plan *p, hy_scene_run *r, const char *fmt, ...) __attribute__((format(printf, 3, 4)));
static void plan_line(const plan *p, hy_scene_run *r, const char *fmt, ...)
{
    if (!p->verbose)
        return;
    size_t len = strlen(r->plan);
    va_list ap;
    va_start(ap, fmt);
    if (len + 1 < sizeof r->plan)
        vsnprintf(r->plan + len, sizeof r->plan - len, fmt, ap);
    va_end(ap);
}

int hy_scene_series_data(const hy_decl_series *ds, int *data)
{
    if (hy_decl_got(&ds->h, offsetof(hy_decl_series, data)) < 0)
        return -1;
    *data = ds->data; /* the schema's list is HY_SERIES_DATA's order */
    return 0;
}

unsigned hy_scene_doc_reads(const hy_scene_doc *doc)
{
    unsigned reads = 0;
    for (size_t i = 0; i < doc->nseries; i++) {
        const hy_decl_series *ds = &doc->series[i];
        int d = ds->data;
        if (hy_decl_got(&ds->h, offsetof(hy_decl_series, data)) < 0)
            return HY_READS_MODEL | HY_READS_G | HY_READS_INPUT; /* refused later: nothing to hide */
        if (d == HY_DATA_MEASURED)
            continue; /* the data alone: no model, no input */
        if (d == HY_DATA_G)
            reads |= HY_READS_G;
        else
            reads |= HY_READS_INPUT | (d == HY_DATA_INPUT || d == HY_DATA_PSI ? 0u : HY_READS_MODEL | HY_READS_G);
    }
    for (size_t i = 0; i < doc->nannotation; i++) {
        const char *text = doc->annotation[i].text ? doc->annotation[i].text : "";
        if (strstr(text, "{model."))
            reads |= HY_READS_MODEL | HY_READS_G;
        if (strstr(text, "{input."))
            reads |= HY_READS_INPUT;
    }
    return reads;
}

unsigned hy_scene_reads(const hy_scene *s)
{
    hy_scene_doc d;
    hy_error err;
    unsigned reads = hy_scene_decode_fill(s, &d, &err) ? HY_READS_MODEL | HY_READS_G | HY_READS_INPUT
                                                        : hy_scene_doc_reads(&d);
    hy_scene_doc_free(&d);
    return reads;
}

/* The GSL options of a solve at the scene's solver (rk8pd where it asks for
 * exact and exact does not apply); NULL when the exact solution serves. */
static const hy_ode_opts *solve_opts(const hy_scene_run *r, hy_ode_opts *o)
{
    const hy_decl_compute *dc = &r->doc.compute;
    const char *solver = hy_decl_enum_text(&dc->h, offsetof(hy_decl_compute, solver), dc->solver);
    if (!strcmp(solver, "exact") && hy_gamma_exact_applies(&r->model, &r->input))
        return NULL;
    *o = hy_ode_defaults();
    o->stepper = strcmp(solver, "exact") ? solver : "rk8pd";
    o->rtol = dc->rtol;
    o->atol = dc->atol;
    return o;
}

/* Refuses, at the solver's line, a scene whose GSL solves would pass their
 * work limit: every solve is checked before the first starts (issue 36
 * item 1: Fig. 4 at 7000 cycles computed for 15 s before its third γ was
 * refused). */
static int check_solves(const hy_scene_run *r, const plan *p, hy_error *err)
{
    const hy_decl_compute *dc = &r->doc.compute;
    for (size_t i = 0; i < p->nsolves; i++) {
        hy_ode_opts o;
        if (solve_opts(r, &o) && hy_ode_check_work(&r->model, &r->input, p->solves[i].gamma, &o, p->t1, err))
            return hy_decl_error(&dc->h, offsetof(hy_decl_compute, solver), err, HY_EINVAL, "gamma = %g: %s",
                                 p->solves[i].gamma, err->msg);
    }
    return HY_OK;
}

static int solve_gamma(hy_scene_run *r, plan *p, gamma_solve *g, hy_error *err)
{
    const hy_decl_compute *dc = &r->doc.compute;
    const char *solver = hy_decl_enum_text(&dc->h, offsetof(hy_decl_compute, solver), dc->solver);
    g->y = malloc(p->npts * sizeof *g->y);
    if (!g->y)
        return hy_error_set(err, HY_ENOMEM, "out of memory for %zu points", p->npts);
    g->err = NAN;
    double t0 = now();
    int rc;
    int exact_ok = hy_gamma_exact_applies(&r->model, &r->input);
    if (!strcmp(solver, "exact") && exact_ok) {
        rc = hy_gamma_exact(&r->model, &r->input, g->gamma, p->t, p->npts, g->y, NULL, err);
        g->seconds = now() - t0;
        g->exact = 1;
        if (!rc && !r->no_verify) /* measured against a long-double evaluation coded apart */
            hy_verify_gamma(r, g->gamma, p->t, g->y, p->npts, &g->err, g->refbuf, sizeof g->refbuf);
        else if (!rc)
            snprintf(g->refbuf, sizeof g->refbuf, "%s", HY_NOT_SAMPLED);
        g->ref = g->refbuf;
        return rc;
    } else {
        hy_ode_opts o;
        solve_opts(r, &o);
        o.cancel = hy_scene_run_cancel_hook(r);
        rc = hy_ode_solve(&r->model, &r->input, g->gamma, &o, p->t, p->npts, g->y, NULL, err);
        if (!rc && exact_ok && p->verbose && !r->no_verify) { /* the error, measured only when asked */
            double *ye = malloc(p->npts * sizeof *ye);
            if (ye && !hy_gamma_exact(&r->model, &r->input, g->gamma, p->t, p->npts, ye, NULL, err)) {
                g->err = 0;
                for (size_t i = 0; i < p->npts; i++)
                    g->err = fmax(g->err, fabs(ye[i] - g->y[i]));
                g->ref = "exact piecewise-exponential solution";
            }
            free(ye);
        } else if (!rc && exact_ok && p->verbose)
            g->ref = HY_NOT_SAMPLED;
        if (rc)
            return hy_decl_error(&dc->h, offsetof(hy_decl_compute, solver), err, rc, "gamma = %g: %s", g->gamma, err->msg);
    }
    g->seconds = now() - t0;
    return rc;
}

static gamma_solve *find_solve(plan *p, double gamma)
{
    for (size_t i = 0; i < p->nsolves; i++)
        if (p->solves[i].gamma == gamma)
            return &p->solves[i];
    return NULL;
}

int hy_scene_run_grid(const hy_scene_run *r, double *t0, double *t1, size_t *npts, size_t *per, long *cycles,
                      hy_error *err)
{
    const hy_decl_compute *dc = &r->doc.compute;
    long pts = dc->points;
    *cycles = dc->cycles;
    double T = r->input.period;
    if (hy_decl_got(&dc->h, offsetof(hy_decl_compute, tspan)) == HY_SCENE_SET) {
        *t0 = dc->tspan.v[0];
        *t1 = dc->tspan.v[1];
        if (*t0 < 0)
            return hy_decl_error(&dc->h, offsetof(hy_decl_compute, tspan), err, HY_EINVAL, "tspan must start at t >= 0 (got %g)", *t0);
    } else {
        *t0 = 0;
        *t1 = (double)*cycles * T;
    }
    double periods = (*t1 - *t0) / T;
    double np = (double)pts * fmax(1.0, periods);
    if (!(np <= 2e7)) /* NaN too: np is converted below */
        return hy_decl_error(&dc->h, offsetof(hy_decl_compute, points), err, HY_EINVAL,
                             "%g points per period over %g periods is more than 2e7 points", (double)pts, periods);
    *npts = (size_t)np + 1;
    *per = (size_t)pts;
    return HY_OK;
}

/* Decides the grid and the shared computations; solves each distinct γ once. */
void hy_scene_friction_needs(const hy_scene_doc *doc, int *need_steady, int *need_loops)
{
    *need_steady = *need_loops = 0;
    for (size_t i = 0; i < doc->nseries; i++) {
        int d = doc->series[i].data;
        if (d == HY_DATA_YSTAR || d == HY_DATA_YSTEADY || d == HY_DATA_YK)
            *need_steady = 1;
        if (d == HY_DATA_MINOR || d == HY_DATA_MAJOR)
            *need_steady = *need_loops = 1;
    }
    for (size_t i = 0; i < doc->nannotation; i++)
        if (doc->annotation[i].text && hy_scene_text_has_placeholder(doc->annotation[i].text))
            *need_steady = *need_loops = 1;
}

static int make_plan(hy_scene_run *r, plan *p, hy_error *err)
{
    int grc = hy_scene_run_grid(r, &p->t0, &p->t1, &p->npts, &p->per_period, &p->cycles, err);
    if (grc)
        return grc;
    size_t ns = r->doc.nseries;
    p->solves = calloc(ns ? ns : 1, sizeof *p->solves);
    if (!p->solves)
        return hy_error_set(err, HY_ENOMEM, "out of memory");
    /* the time grid: for y_γ solves and for u and y* over the time span (the
       table-only path outside the error sample samples no curve) */
    int need_steady, need_loops, need_grid = 0;
    hy_scene_friction_needs(&r->doc, &need_steady, &need_loops);
    for (size_t i = 0; i < ns; i++) { /* data, gamma and k checked by load (check_friction_series) */
        const hy_decl_series *ds = &r->doc.series[i];
        int d = ds->data;
        if ((d == HY_DATA_INPUT || d == HY_DATA_YSTAR) && !(r->numbers_only && r->no_verify))
            need_grid = 1;
        if (d == HY_DATA_YGAMMA || d == HY_DATA_TRANSIENT) {
            if (!find_solve(p, ds->gamma))
                p->solves[p->nsolves++].gamma = ds->gamma;
            need_grid = 1;
        }
    }
    int crc = check_solves(r, p, err);
    if (crc)
        return crc;
    if (need_grid) {
        if (!(p->t = malloc(p->npts * sizeof *p->t)))
            return hy_error_set(err, HY_ENOMEM, "out of memory for %zu points", p->npts);
        for (size_t i = 0; i < p->npts; i++)
            p->t[i] = p->t0 + (p->t1 - p->t0) * (double)i / (double)(p->npts - 1);
    }
    if (need_steady) {
        double t0 = p->verbose ? now() : 0; /* timed for the plan only (the sweep's every point: no clock) */
        static const char *const mkeys[] = {"sigma0", "sigma1", "sigma2", "fc", "fs", "vs", "beta", "rho", "tau", "x0", NULL};
        int rc = hy_steady_init(&r->steady, &r->model, &r->input, err);
        if (rc)
            return located(&r->doc.model.h, mkeys, err); /* at the key the message names, else at [model] */
        r->have_steady = 1;
        if (p->verbose)
            plan_line(p, r, "steady state y° (Theorem 2, fixed point of the period map): %.3f ms\n", 1e3 * (now() - t0));
    }
    if (need_loops) {
        double t0 = p->verbose ? now() : 0;
        int rc = hy_loops_find(&r->steady, &r->loops, err);
        if (rc)
            return rc;
        r->have_loops = 1;
        if (p->verbose)
            plan_line(p, r, "major and minor loops (rainflow pairing of ψ_u's extrema): %.3f ms\n", 1e3 * (now() - t0));
    }
    for (size_t i = 0; i < p->nsolves; i++) {
        int rc = hy_scene_run_check_cancel(r, err);
        if (!rc)
            rc = solve_gamma(r, p, &p->solves[i], err);
        if (rc)
            return rc;
        char what[160];
        snprintf(what, sizeof what, " for gamma = %g over %zu points%s", p->solves[i].gamma, p->npts,
                 p->solves[i].exact ? " (exact)" : "");
        plan_line(p, r, "y_gamma solve: %.3f ms%s\n", 1e3 * p->solves[i].seconds, what);
    }
    if (!need_steady && !p->nsolves)
        plan_line(p, r, "analytic only: no steady state, no ODE solve\n");
    return HY_OK;
}

/* ---- series ---------------------------------------------------------- */

static double interp(const plan *p, const double *y, double t)
{
    double f = (t - p->t0) / (p->t1 - p->t0) * (double)(p->npts - 1);
    if (!(f > 0))
        return y[0];
    if (!(f < (double)(p->npts - 1))) /* before the cast: f may be any size */
        return y[p->npts - 1];
    size_t i = (size_t)f;
    double w = f - (double)i;
    return y[i] * (1 - w) + y[i + 1] * w;
}

/* y of the series at time t (ϱ for psi, minor, major; v for g) */
static double series_y(const hy_scene_run *r, const plan *p, const hy_run_series *se, double t)
{
    switch (se->data) {
    case HY_DATA_INPUT: return hy_input_u(&r->input, t);
    case HY_DATA_PSI: return hy_input_psi(&r->input, t);
    case HY_DATA_G: return hy_model_g(&r->model, t);
    case HY_DATA_YSTAR: return hy_ystar_at(&r->steady, r->model.x0, t);
    case HY_DATA_YSTEADY: return hy_steady_at(&r->steady, t);
    case HY_DATA_YK: return hy_ystar_k(&r->steady, r->model.x0, (double)se->k, fmod(t, r->input.period));
    case HY_DATA_MINOR:
    case HY_DATA_MAJOR: return hy_steady_at_rho(&r->steady, t);
    default: {
        gamma_solve *g = find_solve((plan *)p, se->gamma);
        return g ? interp(p, g->y, t) : NAN;
    }
    }
}

/* x of the series at parameter t: u in loop figures, else t itself */
static double series_x(const hy_scene_run *r, const hy_run_series *se, double t)
{
    if (r->figure_kind != FIG_LOOP)
        return t;
    if (se->data == HY_DATA_MINOR || se->data == HY_DATA_MAJOR || se->data == HY_DATA_PSI)
        return hy_input_psi(&r->input, t);
    return hy_input_u(&r->input, t);
}

int hy_scene_run_series_new(hy_scene_run *r, hy_error *err)
{
    size_t ns = r->doc.nseries;
    r->series = calloc(ns ? ns : 1, sizeof *r->series);
    if (!r->series)
        return hy_error_set(err, HY_ENOMEM, "out of memory");
    for (size_t i = 0; i < ns; i++) {
        hy_run_series *se = &r->series[i];
        const hy_decl_series *ds = &r->doc.series[i];
        se->decl = ds;
        se->name = ds->h.name;
        if (hy_scene_series_data(ds, &se->data))
            se->data = HY_DATA_INPUT;
        se->gamma = ds->gamma;
        se->k = ds->k;
    }
    r->nseries = ns;
    return HY_OK;
}

int hy_run_series_alloc(hy_run_series *se, size_t n, hy_error *err)
{
    se->x = malloc(n * sizeof *se->x);
    se->y = malloc(n * sizeof *se->y);
    se->n = n;
    if (!se->x || !se->y)
        return hy_error_set(err, HY_ENOMEM, "out of memory for series '%s'", se->name);
    return HY_OK;
}

/* Samples the series over [a, b] of its parameter with n points. */
static void sample(const hy_scene_run *r, const plan *p, hy_run_series *se, size_t off, size_t n, double a, double b)
{
    for (size_t i = 0; i < n; i++) {
        double t = n > 1 ? a + (b - a) * (double)i / (double)(n - 1) : a;
        se->x[off + i] = series_x(r, se, t);
        se->y[off + i] = series_y(r, p, se, t);
    }
}

/* ---- drawn-only series (figure_only) -----------------------------------
 * A series that is drawn and never written as data need not hold every point
 * of its grid when that has more than HY_THIN_MIN: one drawn only as its
 * mark is evaluated at the mark; a loop (y° against ψ_u, data = minor or
 * major) is kept at the grid points that a polyline through them needs to
 * stay within tol of the full grid's.  Within a run of ψ_u, ψ is linear in ϱ
 * and y° = s g0 + (y_i - s g0) e^{-a (ϱ - ϱ_i)} is monotone and convex or
 * concave, so the chord over [ϱ, ϱ + Δ] is within
 * Δ² a² |y_i - s g0| e^{-a (ϱ - ϱ_i)} / 8 of the curve vertically (so also
 * perpendicularly, in any scaling of the axes).  The grid points on both
 * sides of every run's end are kept: the extremes of x and y are the full
 * grid's and no turn is cut.  Values are computed as sample() computes them
 * (same ϱ, same functions), so every point drawn is one the full grid has. */

static int thin_wanted(const hy_scene_run *r, double points)
{
    return r->figure_only && points > HY_THIN_MIN && !r->doc.figure.full_resolution;
}

/* Whether series se draws only its mark (style none, a marker, at). */
static int mark_only(const hy_run_series *se, double *at)
{
    const hy_decl_series *d = se->decl;
    *at = d->at;
    return d->style == HY_LINE_NONE && d->marker && hy_decl_got(&d->h, offsetof(hy_decl_series, at)) == HY_SCENE_SET;
}

/* The end of the run of ψ_u that ϱ = rho lies in, in rho's own units (past
 * rho: an end closer than rho's resolution counts as the next double). */
static double run_end(const hy_input *in, double rho, size_t *run, double *rmod)
{
    *run = hy_input_run_at(in, rho, rmod);
    double end = rho + (in->runs[*run].rho1 - *rmod);
    return end > rho ? end : nextafter(rho, INFINITY);
}

/* The extent of y° over [a, b] of ϱ: its extremes lie at the ends and at the
 * ends of runs (monotone within each). */
static double loop_y_extent(const hy_scene_run *r, double a, double b)
{
    double lo = hy_steady_at_rho(&r->steady, a), hi = lo, x = a, rm;
    size_t run;
    for (size_t n = 0; x < b && n < 4 * r->input.nruns + 4; n++) {
        double e = run_end(&r->input, x, &run, &rm);
        x = e < b ? e : b;
        double y = hy_steady_at_rho(&r->steady, x);
        lo = fmin(lo, y), hi = fmax(hi, y);
    }
    return hi - lo;
}

/* The chord tolerance of series se's thinned loop: HY_THIN_TOL of the
 * narrowest y window the scene can show (y°'s range over the period, ylim,
 * zoom_y, each minor loop's range when the inset follows it), in the units
 * of y° before series.yscale.  0: not thinned. */
static double thin_tol(const hy_scene_run *r, const hy_run_series *se)
{
    const hy_decl_figure *df = &r->doc.figure;
    double lo = r->steady.y_run[0], hi = lo, f = se->decl->yscale;
    for (size_t i = 1; i <= r->input.nruns; i++)
        lo = fmin(lo, r->steady.y_run[i]), hi = fmax(hi, r->steady.y_run[i]);
    double w = hi - lo;
    if (df->ylog) /* the bound is for a linear y axis */
        return 0;
    if (hy_decl_got(&df->h, offsetof(hy_decl_figure, ylim)) == HY_SCENE_SET && !df->ylim.is_auto)
        w = fmin(w, fabs(df->ylim.v[1] - df->ylim.v[0]) / fabs(f));
    if (hy_decl_got(&df->h, offsetof(hy_decl_figure, zoom_y)) == HY_SCENE_SET)
        w = fmin(w, fabs(df->zoom_y.v[1] - df->zoom_y.v[0]) / fabs(f));
    int follow = df->zoom_follow; /* nonzero: minor (the schema's none, minor) */
    for (size_t i = 0; follow && i < r->loops.nminor; i++)
        w = fmin(w, loop_y_extent(r, r->loops.minor[i].rho_start, r->loops.minor[i].rho_close));
    return w > 0 && isfinite(w) ? HY_THIN_TOL * w : 0;
}

/* The grid index after j (of per on [a, b]) that a chord from j reaches
 * within tol: at most the last grid point of j's run, one step past it. */
static size_t thin_next(const hy_scene_run *r, double a, double b, size_t per, size_t j, double tol)
{
    double h = (b - a) / (double)(per - 1), rho = a + (b - a) * (double)j / (double)(per - 1), rm;
    size_t i;
    double f = floor((run_end(&r->input, rho, &i, &rm) - a) / h);
    size_t jb = f < (double)(per - 1) ? (size_t)f : per - 1;
    if (jb <= j)
        return j + 1;
    const hy_run *run = &r->input.runs[i];
    double as = r->steady.a, D = fabs(r->steady.y_run[i] - run->sign * r->steady.g0);
    double c = as * as * D * exp(-as * (rm - run->rho0)); /* |y''| at ϱ, its largest ahead in the run */
    double k = c > 0 ? floor(sqrt(8 * tol / c) / h) : INFINITY;
    k = fmin(k, floor((double)(per - 1) / HY_THIN_SPAN)); /* candidates as dense as HY_THIN_SPAN's grid */
    if (!(k >= 1))
        return j + 1;
    return k >= (double)(jb - j) ? jb : j + (size_t)k;
}

/* The points thin_sample keeps on [a, b]. */
static size_t thin_count(const hy_scene_run *r, double a, double b, size_t per, double tol)
{
    size_t m = 1;
    for (size_t j = 0; j < per - 1; j = thin_next(r, a, b, per, j, tol))
        m++;
    return m;
}

/* Samples the loop series over [a, b] at the grid points (of per) that
 * thin_next keeps; their number. */
static size_t thin_sample(const hy_scene_run *r, const plan *p, hy_run_series *se, size_t off, size_t per, double a,
                          double b, double tol)
{
    size_t m = 0;
    for (size_t j = 0;; j = thin_next(r, a, b, per, j, tol)) {
        double t = a + (b - a) * (double)j / (double)(per - 1); /* as sample() */
        se->x[off + m] = series_x(r, se, t);
        se->y[off + m] = series_y(r, p, se, t);
        m++;
        if (j >= per - 1)
            return m;
    }
}

/* ϱ intervals of the minor loops (minor) or of the rest of the period (major);
 * -1 if a minor loop is too narrow for ϱ at the input's scale to step past it */
int hy_scene_loop_intervals(const hy_scene_run *r, int major, double *a, double *b, size_t max)
{
    const hy_loops *L = &r->loops;
    size_t n = 0;
    if (!major) {
        for (size_t i = 0; i < L->nminor && n < max; i++, n++) {
            a[n] = L->minor[i].rho_start;
            b[n] = L->minor[i].rho_close;
        }
        return (int)n;
    }
    /* the period from the major loop's start, minus the top-level minor loops */
    double rT = r->input.rho_T, cur = L->major.rho_start, end = cur + rT;
    while (cur < end && n < max) {
        double next = end, skip_to = end;
        for (size_t i = 0; i < L->nminor; i++) {
            const hy_loop *m = &L->minor[i];
            if (m->depth != 1)
                continue;
            for (int w = -1; w <= 1; w++) {
                double s0 = m->rho_start + w * rT, s1 = m->rho_close + w * rT;
                if (s0 >= cur - 1e-12 * rT && s0 < next) {
                    next = s0;
                    skip_to = s1;
                }
            }
        }
        if (next > cur) {
            a[n] = cur;
            b[n] = next;
            n++;
        }
        if (!(skip_to > cur)) /* a loop narrower than an ulp of ϱ: no progress possible */
            return -1;
        cur = skip_to;
    }
    return (int)n;
}

int hy_scene_is_placeholder(const char *inner)
{
    return strchr(inner, '.') || !strcmp(inner, "energy") || !strcmp(inner, "nminor");
}

int hy_scene_text_has_placeholder(const char *text)
{
    for (const char *c = strchr(text, '{'); c; c = strchr(c + 1, '{')) {
        const char *e = strchr(c, '}');
        char inner[48];
        size_t n = e ? (size_t)(e - c - 1) : 0;
        if (!e || (n >= sizeof inner && memchr(c + 1, '.', n)))
            return 1;                 /* malformed: let the expansion report it */
        if (n >= sizeof inner)
            continue;                 /* a long markup group */
        snprintf(inner, sizeof inner, "%.*s", (int)n, c + 1);
        if (hy_scene_is_placeholder(inner))
            return 1;
    }
    return 0;
}

/* max |y_γ(t) - y*_u(t)| over the plan's points i0 .. i1-1 (the {NAME.dist}
 * placeholder), or NaN when the limit was not computed */
static double distance_to_limit(const hy_scene_run *r, const plan *p, const gamma_solve *g, size_t i0, size_t i1)
{
    if (!r->have_steady)
        return NAN;
    double d = 0;
    for (size_t i = i0; i < i1; i++)
        d = fmax(d, fabs(g->y[i] - hy_ystar_at(&r->steady, r->model.x0, p->t[i])));
    return d;
}

/* The refusal of an input whose minor loop is too narrow to sample. */
int hy_scene_too_narrow(const hy_scene_run *r, hy_error *err)
{
    static const char *const inkeys[] = {"points", "file", "extrema", NULL};
    const hy_decl_head *h = &r->doc.input.h;
    size_t off = HY_DECL_HEAD;
    for (size_t i = 0; inkeys[i] && off == HY_DECL_HEAD; i++)
        if (hy_decl_got(h, hy_decl_offset(h, inkeys[i])) == HY_SCENE_SET)
            off = hy_decl_offset(h, inkeys[i]);
    return hy_decl_error(h, off, err, HY_EINVAL,
                             "a minor loop of this input is narrower than the resolution of ϱ at its "
                             "scale (ρ_T = %g): the major loop cannot be computed", r->input.rho_T);
}

/* The solve's error and what it was measured against (copied: the solve's
 * buffer goes with the plan). */
static void copy_err(hy_run_series *se, const gamma_solve *g)
{
    se->err = g->err;
    se->err_ref = NULL;
    if (g->ref) {
        snprintf(se->err_note, sizeof se->err_note, "%s", g->ref);
        se->err_ref = se->err_note;
    }
}

/* The error of a series computed with no_verify: not measured, and said so. */
static void not_sampled(hy_run_series *se)
{
    se->err = NAN;
    se->err_ref = HY_NOT_SAMPLED; /* a literal: no formatting at the sweep's every point */
}

static int compute_series(hy_scene_run *r, plan *p, hy_run_series *se, hy_error *err)
{
    size_t per = p->per_period;
    double T = r->input.period;
    double t0 = p->verbose ? now() : 0; /* se->seconds is for the plan's log only */
    int rc = HY_OK;
    double mark_at = 0;
    se->err = NAN;
    se->err_ref = NULL;
    se->dist = NAN;
    se->grid_n = 0;
    if (se->data == HY_DATA_MEASURED || se->data == HY_DATA_MODELLED)
        return HY_OK; /* from the data, after the model's compute (scene_data.c) */
    /* numbers only: u, ψ and g are not sampled; the closed forms are, so that
       their error is measured (issue 11) and the same as with figures */
    if (r->numbers_only && (se->data == HY_DATA_INPUT || se->data == HY_DATA_PSI || se->data == HY_DATA_G))
        return HY_OK;
    /* numbers only, errors not measured: the closed forms are not sampled
       either (the table holds none of their points), markers are evaluated at
       their point only */
    int closed = se->data == HY_DATA_MINOR || se->data == HY_DATA_MAJOR || se->data == HY_DATA_YSTEADY ||
                 se->data == HY_DATA_YK || se->data == HY_DATA_YSTAR;
    if (closed && r->numbers_only && r->no_verify) {
        double a[64], b[64];
        if ((se->data == HY_DATA_MINOR || se->data == HY_DATA_MAJOR) &&
            hy_scene_loop_intervals(r, se->data == HY_DATA_MAJOR, a, b, 64) < 0)
            return hy_scene_too_narrow(r, err); /* refused as when sampled */
        not_sampled(se);
    } else if (se->data == HY_DATA_MINOR || se->data == HY_DATA_MAJOR) {
        double a[64], b[64];
        int k = hy_scene_loop_intervals(r, se->data == HY_DATA_MAJOR, a, b, 64);
        if (k < 0)
            return hy_scene_too_narrow(r, err);
        size_t total = 0, full = (size_t)k * (per + 1);
        double tol = per > 1 && thin_wanted(r, (double)full) ? thin_tol(r, se) : 0;
        for (int i = 0; i < k; i++)
            total += tol > 0 ? thin_count(r, a[i], b[i], per, tol) + 1 : per + 1;
        if ((rc = hy_run_series_alloc(se, total ? total : 1, err)))
            return rc;
        size_t off = 0;
        for (int i = 0; i < k; i++) {
            size_t m = per;
            if (tol > 0)
                m = thin_sample(r, p, se, off, per, a[i], b[i], tol);
            else
                sample(r, p, se, off, per, a[i], b[i]);
            se->x[off + m] = se->y[off + m] = NAN; /* gap */
            off += m + 1;
        }
        se->n = total;
        se->grid_n = total < full ? full : 0;
        if (r->no_verify)
            not_sampled(se);
        else
            hy_verify_loops(r, se, a, b, k, per, total < full);
    } else if (se->data == HY_DATA_G) {
        double lim[2] = {r->doc.figure.xlim.v[0], r->doc.figure.xlim.v[1]};
        if (r->doc.figure.xlim.is_auto) {
            lim[0] = -4 * r->model.vs;
            lim[1] = 4 * r->model.vs;
        }
        if ((rc = hy_run_series_alloc(se, per + 1, err)))
            return rc;
        sample(r, p, se, 0, per + 1, lim[0], lim[1]);
    } else if (se->data == HY_DATA_PSI) {
        if ((rc = hy_run_series_alloc(se, per + 1, err)))
            return rc;
        sample(r, p, se, 0, per + 1, 0, r->input.rho_T);
    } else if ((se->data == HY_DATA_YSTEADY || se->data == HY_DATA_YK) && thin_wanted(r, (double)per + 1) &&
               mark_only(se, &mark_at) && mark_at >= 0 && mark_at < T) {
        se->grid_n = per + 1; /* drawn as its mark: evaluated there only (below) */
    } else if (se->data == HY_DATA_YSTEADY || se->data == HY_DATA_YK) {
        if ((rc = hy_run_series_alloc(se, per + 1, err)))
            return rc;
        sample(r, p, se, 0, per + 1, 0, T);
        se->y[per] = se->data == HY_DATA_YSTEADY ? r->steady.y_run[r->input.nruns]
                                                 : hy_ystar_k(&r->steady, r->model.x0, (double)se->k, T);
        if (r->no_verify)
            not_sampled(se);
        else
            hy_verify_time(r, se, NULL, se->y, per + 1);
    } else if ((se->data == HY_DATA_YGAMMA || se->data == HY_DATA_TRANSIENT) && r->figure_kind == FIG_LOOP) {
        /* loop figures: the last period is the steady state at this γ, the rest the transient */
        gamma_solve *g = find_solve(p, se->gamma);
        double split = p->t1 - T;
        size_t i0 = 0, i1 = p->npts;
        for (size_t i = 0; i < p->npts; i++)
            if (p->t[i] < split - 1e-12 * T)
                i0 = i + 1;
        if (p->cycles > 1) {
            if (se->data == HY_DATA_YGAMMA)
                i0 = i0 ? i0 - 1 : 0;
            else {
                i1 = i0;
                i0 = 0;
            }
        } else
            i0 = 0;
        if ((rc = hy_run_series_alloc(se, i1 - i0, err)))
            return rc;
        for (size_t i = i0; i < i1; i++) {
            se->x[i - i0] = hy_input_u(&r->input, p->t[i]);
            se->y[i - i0] = g->y[i];
        }
        copy_err(se, g);
        se->dist = distance_to_limit(r, p, g, i0, i1);
    } else if (se->data == HY_DATA_YGAMMA || se->data == HY_DATA_TRANSIENT) {
        gamma_solve *g = find_solve(p, se->gamma);
        if ((rc = hy_run_series_alloc(se, p->npts, err)))
            return rc;
        memcpy(se->x, p->t, p->npts * sizeof *se->x);
        memcpy(se->y, g->y, p->npts * sizeof *se->y);
        copy_err(se, g);
        se->dist = distance_to_limit(r, p, g, 0, p->npts);
    } else { /* input, ystar over the time span */
        if ((rc = hy_run_series_alloc(se, p->npts, err)))
            return rc;
        for (size_t i = 0; i < p->npts; i++) {
            se->x[i] = series_x(r, se, p->t[i]);
            se->y[i] = series_y(r, p, se, p->t[i]);
        }
        if (se->data == HY_DATA_YSTAR && r->no_verify)
            not_sampled(se);
        else if (se->data == HY_DATA_YSTAR)
            hy_verify_time(r, se, p->t, se->y, p->npts);
    }
    double at = se->decl->at;
    if (hy_decl_got(&se->decl->h, offsetof(hy_decl_series, at)) == HY_SCENE_SET) {
        se->has_mark = 1;
        se->mark_x = series_x(r, se, at);
        se->mark_y = series_y(r, p, se, at);
        if (se->grid_n && !se->n && r->no_verify)
            not_sampled(se);
        else if (se->grid_n && !se->n) /* its one point measured */
            hy_verify_time(r, se, &at, &se->mark_y, 1);
    }
    se->seconds = p->verbose ? now() - t0 : 0;
    return rc;
}

int hy_scene_check_series_kind(const hy_scene_run *r, const hy_run_series *se, hy_error *err)
{
    static const int ok_loop[] = {0, 1, 0, 1, 1, 1, 1, 1, 1, 1};
#define FIGURE_NAME(id, name) name,
    static const char *const kinds[] = {HY_FIGURE_KINDS(FIGURE_NAME)};
#undef FIGURE_NAME
    int bad = 0;
    if (se->data == HY_DATA_MEASURED || se->data == HY_DATA_MODELLED)
        bad = r->figure_kind != FIG_LOOP && r->figure_kind != FIG_TIMESERIES;
    else if (r->figure_kind == FIG_LOOP)
        bad = !ok_loop[se->data];
    else if (r->figure_kind == FIG_G)
        bad = se->data != HY_DATA_G;
    else if (r->figure_kind == FIG_PSI)
        bad = se->data != HY_DATA_PSI;
    else if (r->figure_kind == FIG_INPUT)
        bad = se->data != HY_DATA_INPUT;
    else
        bad = se->data == HY_DATA_G || se->data == HY_DATA_MINOR || se->data == HY_DATA_MAJOR;
    if (bad)
        return hy_decl_error(&se->decl->h, offsetof(hy_decl_series, data), err, HY_EINVAL,
                                 "data = %s cannot be drawn in a figure of kind %s", data_names[se->data],
                                 kinds[r->figure_kind]);
    return HY_OK;
}

/* Points of one series before computing: the grid, one period, or one period per loop. */
static double series_points(const hy_scene_run *r, int d, double npts, double per)
{
    switch (d) {
    case HY_DATA_MINOR:
    case HY_DATA_MAJOR: return (per + 1) * fmin(64.0, fmax(1.0, (double)r->input.nruns));
    case HY_DATA_G:
    case HY_DATA_PSI:
    case HY_DATA_YSTEADY:
    case HY_DATA_YK: return per + 1;
    default: return npts;
    }
}

/* The models' work of r and of its panels, in units (hy_cost.h). */
static int estimate_models(const hy_scene_run *r, double *work, char *what, size_t size, hy_error *err)
{
    *work = 0;
    int rc = r->figure_kind == FIG_FORC ? hy_scene_forc_estimate(r, work, what, size, err)
                                        : r->mtype->estimate(r, work, what, size, err);
    for (size_t i = 0; !rc && i < r->npanels; i++) { /* a [panel] figure: its panels' work too */
        double w;
        r->panels[i].cost_counts = r->cost_counts;
        rc = estimate_models(&r->panels[i], &w, NULL, 0, err);
        *work += w;
        if (what && size && i == 0)
            snprintf(what, size, "%zu panels", r->npanels);
    }
    return rc;
}

int hy_scene_run_estimate(const hy_scene_run *r, double *work, char *what, size_t size, hy_error *err)
{
    int rc = estimate_models(r, work, what, size, err);
    if (!rc) /* the PNG's raster, once for the figure */
        *work += hy_cost(r->cost_counts, HY_COST_PIXEL, hy_scene_run_png_pixels(r));
    return rc;
}

/* The friction models' estimate: the grid points of every distinct gamma
 * solve plus the points of every series (docs/SCENES.md, "Work budget"). */
int hy_scene_friction_estimate(const hy_scene_run *r, double *work, char *what, size_t size, hy_error *err)
{
    const hy_decl_compute *dc = &r->doc.compute;
    size_t na = r->doc.nannotation;
    long pts = dc->points, cycles = dc->cycles;
    double T = r->input.period, periods = (double)cycles;
    if (hy_decl_got(&dc->h, offsetof(hy_decl_compute, tspan)) == HY_SCENE_SET)
        periods = (dc->tspan.v[1] - dc->tspan.v[0]) / T;
    double npts = (double)pts * fmax(1.0, periods) + 1, pointsum = 0, *gam = NULL;
    size_t ns = r->doc.nseries, ng = 0;
    if (ns && !(gam = malloc(ns * sizeof *gam)))
        return hy_error_set(err, HY_ENOMEM, "out of memory");
    for (size_t i = 0; i < ns; i++) {
        const hy_decl_series *ds = &r->doc.series[i];
        int d = HY_DATA_INPUT;
        double g = ds->gamma;
        hy_scene_series_data(ds, &d);
        pointsum += series_points(r, d, npts, (double)pts);
        if ((d == HY_DATA_YGAMMA || d == HY_DATA_TRANSIENT) && hy_decl_got(&ds->h, offsetof(hy_decl_series, gamma)) >= 0) {
            size_t j = 0;
            while (j < ng && gam[j] != g)
                j++;
            if (j == ng)
                gam[ng++] = g;
        }
    }
    free(gam);
    *work = hy_cost(r->cost_counts, HY_COST_POINT, (double)ng * npts + pointsum) +
            hy_cost(r->cost_counts, HY_COST_ANNOTATION, (double)na);
    if (what && size)
        snprintf(what, size, "%zu series, %zu distinct gamma solves over %.0f points (%ld per period, %g periods), "
                 "%zu annotations", ns, ng, npts, pts, fmax(1.0, periods), na);
    return HY_OK;
}

int hy_scene_run_over_budget(const hy_scene_doc *d, double work, double budget, const char *what, hy_error *err)
{
    static const char *const keys[] = {"points", "cycles", "tspan", "gamma", "settle", "upsample", NULL};
    const char *fmt = "the scene asks for about %.3g units of work (%s), more than the budget of %.3g; "
                      "raise it with --max-work N if this is intended";
    const hy_decl_head *h = &d->compute.h;
    for (size_t i = 0; keys[i]; i++) {
        size_t off = hy_decl_offset(h, keys[i]);
        if (hy_decl_loc(h, off).line > 0)
            return hy_decl_error(h, off, err, HY_EINVAL, fmt, work, what, budget);
    }
    if (d->nseries && d->series[0].h.loc.line > 0)
        return hy_decl_error(&d->series[0].h, HY_DECL_HEAD, err, HY_EINVAL, fmt, work, what, budget);
    hy_error_set(err, HY_EINVAL, fmt, work, what, budget);
    hy_error_prefix(err, "%s:1:1", d->source);
    return HY_EINVAL;
}

int hy_scene_run_compute(hy_scene_run *r, FILE *log, hy_error *err)
{
    char what[200];
    int erc = hy_scene_run_estimate(r, &r->work, NULL, 0, err);
    if (erc)
        return erc;
    double budget = r->budget > 0 ? r->budget : HY_SCENE_WORK_DEFAULT;
    if (r->work > budget) { /* the breakdown only for the message */
        hy_scene_run_estimate(r, &r->work, what, sizeof what, err);
        return hy_scene_run_over_budget(&r->doc, r->work, budget, what, err);
    }
    int rc = HY_OK;
    for (size_t i = 0; !rc && i < r->npanels; i++) {
        if (!r->panels[i].cancelled) /* a [panel] stops with its figure */
            r->panels[i].cancelled = r->cancelled, r->panels[i].cancel_ctx = r->cancel_ctx;
        rc = hy_scene_run_compute(&r->panels[i], log, err);
    }
    if (!rc)
        rc = r->figure_kind == FIG_FORC ? hy_scene_forc_compute(r, log, err) : r->mtype->compute(r, log, err);
    if (!rc)
        rc = hy_scene_run_data_series(r, err); /* data = measured, modelled */
    if (!rc && log)
        hy_scene_data_log(r, log);
    for (size_t i = 0; !rc && i < r->nseries; i++) { /* series.yscale, where written */
        hy_run_series *se = &r->series[i];
        double f = se->decl->yscale;
        if (hy_decl_got(&se->decl->h, offsetof(hy_decl_series, yscale)) != HY_SCENE_SET)
            continue;
        for (size_t j = 0; j < se->n; j++)
            se->y[j] *= f;
        for (size_t j = 0; se->ymeas && j < se->n; j++)
            se->ymeas[j] *= f;
        se->mark_y *= f;
    }
    return rc;
}

int hy_scene_friction_compute(hy_scene_run *r, FILE *log, hy_error *err)
{
    double t_start = now();
    plan p;
    memset(&p, 0, sizeof p);
    p.verbose = log != NULL;
    int rc = hy_scene_run_series_new(r, err);
    size_t ns = r->nseries;
    for (size_t i = 0; i < ns && !rc; i++)
        rc = hy_scene_check_series_kind(r, &r->series[i], err);
    if (!rc)
        rc = make_plan(r, &p, err);
    for (size_t i = 0; i < ns && !rc; i++)
        if (!(rc = hy_scene_run_check_cancel(r, err)))
            rc = compute_series(r, &p, &r->series[i], err);
    r->seconds_compute = now() - t_start;
    if (!rc && log) {
        fprintf(log, "%s: plan\n%s", r->path, r->plan);
        for (size_t i = 0; i < ns; i++) {
            const hy_run_series *se = &r->series[i];
            if (se->data == HY_DATA_MEASURED || se->data == HY_DATA_MODELLED)
                continue; /* their own lines: hy_scene_data_log */
            fprintf(log, "  series %-12s data=%-9s %7zu points %8.3f ms", se->name, data_names[se->data], se->n,
                    1e3 * se->seconds);
            if (se->grid_n)
                fprintf(log, " (drawn: %s of the grid's %zu)", se->n ? "the points its curvature needs" : "its mark only",
                        se->grid_n);
            if (se->err_ref && isnan(se->err))
                fprintf(log, "  error %s", se->err_ref);
            else if (se->err_ref)
                fprintf(log, "  error %.3g vs %s", se->err, se->err_ref);
            else if (se->data == HY_DATA_YGAMMA || se->data == HY_DATA_TRANSIENT)
                fprintf(log, "  error not measured (no exact solution for this model and input)");
            fputc('\n', log);
        }
        fprintf(log, "  compute total %.3f ms (work estimate %.3g of the budget %.3g)\n", 1e3 * r->seconds_compute, r->work,
                r->budget > 0 ? r->budget : HY_SCENE_WORK_DEFAULT);
    }
    for (size_t i = 0; i < p.nsolves; i++)
        free(p.solves[i].y);
    free(p.solves);
    free(p.t);
    return rc;
}

/* What a Dahl or LuGre series draws: a data it has, and a y_gamma (ygamma,
 * transient) names its gamma (found by compute's plan before issue 22). */
static int check_friction_series(const hy_scene_run *r, hy_error *err)
{
    for (size_t i = 0; i < r->doc.nseries; i++) {
        const hy_decl_series *se = &r->doc.series[i];
        if (hy_decl_got(&se->h, offsetof(hy_decl_series, data)) < 0)
            return hy_decl_error(&se->h, HY_DECL_HEAD, err, HY_EINVAL, "series '%s' needs 'data = ...' (%s)", se->h.name,
                                 "input, psi, g, ystar, ysteady, ygamma, yk, transient, minor, major");
        if (se->data == HY_DATA_BOUCWEN)
            return hy_decl_error(&se->h, offsetof(hy_decl_series, data), err, HY_EUNSUP,
                                 "data = boucwen is drawn by the Bouc-Wen scenes' own kind, not in a %s figure",
                                 data_names[0]);
        if ((se->data == HY_DATA_YGAMMA || se->data == HY_DATA_TRANSIENT) &&
            hy_decl_got(&se->h, offsetof(hy_decl_series, gamma)) < 0)
            return hy_decl_error(&se->h, offsetof(hy_decl_series, data), err, HY_EINVAL,
                                 "series '%s' (data = %s) needs 'gamma'", se->h.name, data_names[se->data]);
    }
    return HY_OK;
}

int hy_scene_friction_load(hy_scene_run *r, hy_error *err)
{
    int rc = hy_scene_boucwen_load(r, err); /* refuses the Bouc-Wen-only parts */
    if (!rc)
        rc = check_friction_series(r, err);
    if (!rc)
        rc = hy_scene_run_build_model(r, err);
    if (!rc)
        rc = hy_scene_run_build_input(r, err);
    return rc;
}

