/* SPDX-License-Identifier: MIT */
/* scene_run.c: scene → plan → computed series → hy_figure → files (DESIGN.md
 * data flow); the series are those of seed 000's figures: u, ψ_u, g, y*_u,
 * y°_u, y_γ, y*_{u,k}, transients, major and minor loops. */
#include "scene_run.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "hy_cost.h"
#include "hy_plot.h"
#include "scene_forc.h"
#include "scene_model.h"

#define DATA_NAME(id, name) name,
static const char *const data_names[] = {HY_SERIES_DATA(DATA_NAME)};

int hy_scene_located(const hy_decl_head *h, const char *const *keys, hy_error *err)
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

int hy_scene_series_log(const hy_run_series *se, FILE *log)
{
    if (se->data == HY_DATA_MEASURED || se->data == HY_DATA_MODELLED)
        return 0;
    fprintf(log, "  series %-12s data=%-9s %7zu points %8.3f ms", se->name, hy_scene_data_name(se->data), se->n,
            1e3 * se->seconds);
    return 1;
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
        return hy_scene_located(h, keys, err);
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
        rc = r->figure_kind == FIG_FORC ? hy_scene_forc_load(r, err) : hy_scene_model_accepts(r, err);
    if (!rc && r->figure_kind != FIG_FORC)
        rc = r->mtype->load(r, err);
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

int hy_scene_run_estimate_px(const hy_scene_run *r, double pixel_work, double *work, char *what, size_t size,
                             hy_error *err)
{
    int rc = estimate_models(r, work, what, size, err);
    if (!rc)
        *work += pixel_work;
    return rc;
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
