/* SPDX-License-Identifier: MIT */
/* scene_data.c: measured data in a scene (issue 32 item 1): [data NAME] read once
 * at load through the file policy (hy_table.c, untrusted text), drawn as a series
 * (data = measured), driving a rate-independent model ([input] kind = data) whose
 * output at the measured inputs is a series too (data = modelled), and the
 * fitter's evaluation (hy_scene_run_model_at_data). */
#include "scene_model.h"
#include "scene_run.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "hy_gamma.h"
#include "hy_scene_policy.h"

#define SETTLE_TOL 1e-12 /* start = periodic: relative change of y at a record's end counted as periodic */
#define SETTLE_MAX 5000  /* ... and the passes driven at most                                             */

enum { START_ZERO, START_FIRST, START_PERIODIC }; /* [input] start, the schema's order */

/* The [data NAME] of r, or NULL. */
static const hy_run_data *find_data(const hy_scene_run *r, const char *name)
{
    for (size_t i = 0; name && i < r->ndata; i++)
        if (!strcmp(r->data[i].name, name))
            return &r->data[i];
    return NULL;
}

/* Reads and parses one [data] section's file; chooses its records. */
static int read_one(hy_scene_run *r, const hy_decl_data *d, hy_run_data *rd, hy_error *err)
{
    static const char *const scales[] = {"u_scale", "y_scale", "t_scale"};
    const double sc[3] = {d->u_scale, d->y_scale, d->t_scale};
    rd->decl = d;
    rd->name = d->h.name;
    if (hy_decl_got(&d->h, offsetof(hy_decl_data, file)) < 0)
        return hy_decl_error(&d->h, HY_DECL_HEAD, err, HY_EINVAL, "[data %s] needs 'file = \"PATH\"'", d->h.name);
    for (int i = 0; i < 3; i++)
        if (!(sc[i] != 0))
            return hy_decl_error(&d->h, hy_decl_offset(&d->h, scales[i]), err, HY_EINVAL,
                                 "'%s' must not be 0 (it multiplies the column as read)", scales[i]);
    char *text;
    size_t len;
    int user, rc = hy_scene_read_path_max(r->scene, "data", d->h.name, "file", HY_TABLE_MAX_BYTES, &text, &len, &user, err);
    if (rc)
        return rc; /* at the key, by the policy: outside the scene's directory, too large, missing */
    int have_t = hy_decl_got(&d->h, offsetof(hy_decl_data, t)) >= 0;
    int have_split = hy_decl_got(&d->h, offsetof(hy_decl_data, split)) >= 0;
    hy_table_spec sp = {{d->u, d->y, have_t ? d->t : NULL, have_split ? d->split : NULL}, {sc[0], sc[1], sc[2]}};
    rc = hy_table_parse(text, len, d->file, &sp, user, &rd->tb, err); /* file:line:col of the data file */
    free(text);
    if (rc)
        return rc;
    size_t nrec = rd->tb.nrec;
    if (d->record > 0 && (size_t)d->record > nrec)
        return hy_decl_error(&d->h, offsetof(hy_decl_data, record), err, HY_EINVAL,
                             "record %ld does not exist: %s has %zu record%s%s", d->record, d->file, nrec,
                             nrec == 1 ? "" : "s", have_split ? "" : " (no 'split' column: the whole file is one)");
    rd->r0 = d->record > 0 ? (size_t)d->record - 1 : 0;
    rd->r1 = d->record > 0 ? (size_t)d->record : nrec;
    rd->i0 = rd->tb.rec[rd->r0];
    rd->i1 = rd->tb.rec[rd->r1];
    if (!(rd->area = malloc((rd->r1 - rd->r0) * sizeof *rd->area)))
        return hy_error_set(err, HY_ENOMEM, "out of memory");
    for (size_t j = rd->r0; j < rd->r1; j++) {
        size_t a = rd->tb.rec[j], n = rd->tb.rec[j + 1] - a;
        rd->area[j - rd->r0] = hy_table_area(rd->tb.u + a, rd->tb.y + a, n);
    }
    return HY_OK;
}

int hy_scene_run_read_data(hy_scene_run *r, hy_error *err)
{
    size_t n = r->doc.ndata;
    if (!n)
        return HY_OK;
    if (!(r->data = calloc(n, sizeof *r->data)))
        return hy_error_set(err, HY_ENOMEM, "out of memory");
    for (size_t i = 0; i < n; i++) {
        r->ndata = i + 1;
        int rc = read_one(r, &r->doc.data[i], &r->data[i], err);
        if (rc)
            return rc;
    }
    return HY_OK;
}

/* The names of the table's rate-independent models, for a refusal. */
static void ri_names(char *buf, size_t size)
{
    buf[0] = '\0';
    for (size_t i = 0; hy_scene_models[i]; i++)
        if (hy_scene_models[i]->ri)
            snprintf(buf + strlen(buf), size - strlen(buf), "%s%s", buf[0] ? ", " : "", hy_scene_models[i]->name);
}

/* Whether the model is one of the time-stepped friction models, driven by
 * the exact piecewise-exponential solution at the measured times (r->model). */
static int stepped(const hy_scene_run *r)
{
    return !r->mtype->ri && (r->mtype->caps & HY_CAP_EXACT_STEP);
}

/* Refuses a model that cannot be driven by measured data, at the key off of h. */
static int need_drivable(const hy_scene_run *r, const hy_decl_head *h, size_t off, const char *what, hy_error *err)
{
    if (r->mtype->ri || stepped(r))
        return HY_OK;
    char names[200];
    ri_names(names, sizeof names);
    return hy_decl_error(h, off, err, HY_EUNSUP,
                         "%s drives a rate-independent model (%s: the measured u in order) or a Dahl/LuGre model "
                         "(the measured t and u); a %s model is not driven by measured data", what, names,
                         r->mtype->name);
}

/* The times of the driving record for a time-stepped model: t - t[0] (the
 * sample index without a t column, for a rate-independent one), malloc'd. */
static double *record_times(const hy_run_data *rd)
{
    size_t n = rd->i1 - rd->i0;
    double *t = malloc((n + 1) * sizeof *t);
    for (size_t i = 0; t && i < n; i++)
        t[i] = rd->tb.t ? rd->tb.t[rd->i0 + i] - rd->tb.t[rd->i0] : (double)i;
    return t;
}

/* What a time-stepped model needs of the data that drive it: a t column
 * (unless the model is rate-independent: Dahl), one record, no periodic start. */
static int stepped_ok(const hy_scene_run *r, const hy_run_data *rd, hy_error *err)
{
    const hy_decl_input *d = &r->doc.input;
    if (!rd->tb.t && !(r->mtype->caps & HY_CAP_RATE_INDEPENDENT))
        return hy_decl_error(&d->h, offsetof(hy_decl_input, data), err, HY_EINVAL,
                             "a %s model is time-stepped: it is driven by the measured t and u, and [data %s] has no "
                             "t column (t = NAME or index)", r->mtype->name, rd->name);
    if (rd->r1 - rd->r0 != 1)
        return hy_decl_error(&d->h, offsetof(hy_decl_input, data), err, HY_EINVAL,
                             "a %s model is driven by one record of measured t and u: choose it with record = K in "
                             "[data %s] (%zu records)", r->mtype->name, rd->name, rd->r1 - rd->r0);
    if (d->start == START_PERIODIC)
        return hy_decl_error(&d->h, offsetof(hy_decl_input, start), err, HY_EINVAL,
                             "start = periodic drives rate-independent models; a %s model starts from x0", r->mtype->name);
    return HY_OK;
}

int hy_scene_run_data_input(hy_scene_run *r, hy_error *err)
{
    const hy_decl_input *d = &r->doc.input;
    const hy_decl_head *h = &d->h;
    if (hy_decl_got(h, offsetof(hy_decl_input, data)) < 0)
        return hy_decl_error(h, offsetof(hy_decl_input, kind), err, HY_EINVAL, "a data input needs 'data = NAME' (a [data NAME])");
    const hy_run_data *rd = find_data(r, d->data);
    if (!rd)
        return hy_decl_error(h, offsetof(hy_decl_input, data), err, HY_EINVAL, "no [data %s] in the scene", d->data);
    int rc = need_drivable(r, h, offsetof(hy_decl_input, kind), "[input] kind = data", err);
    if (!rc && stepped(r))
        rc = stepped_ok(r, rd, err);
    if (rc)
        return rc;
    size_t n = rd->i1 - rd->i0, m = n + 1;
    double *t = stepped(r) ? record_times(rd) : malloc(m * sizeof *t), *u = malloc(m * sizeof *u);
    if (!t || !u) {
        free(t);
        free(u);
        return hy_error_set(err, HY_ENOMEM, "out of memory");
    }
    for (size_t i = 0; i < n; i++) {
        t[i] = stepped(r) ? t[i] : (double)i;
        u[i] = rd->tb.u[rd->i0 + i];
    }
    if (u[n - 1] != u[0]) { /* closed back to the first u, one mean step on */
        t[n] = n > 1 ? t[n - 1] + t[n - 1] / (double)(n - 1) : 1.0;
        u[n] = u[0];
    } else
        m = n;
    rc = hy_input_pwl(&r->input, t, u, m, err);
    free(t);
    free(u);
    if (rc)
        return hy_decl_error(h, offsetof(hy_decl_input, data), err, rc, "[data %s]: %s", rd->name, err->msg);
    snprintf(r->input.desc, sizeof r->input.desc, "measured u of [data %s], %zu samples", rd->name, n);
    r->have_input = 1;
    r->drive = rd;
    return HY_OK;
}

/* One pass of the model m through u[0..n), outputs into y (may be NULL). */
static int pass(hy_rateind *m, const double *u, size_t n, double *y, double *lo, double *hi, hy_error *err)
{
    for (size_t i = 0; i < n; i++) {
        int rc = hy_rateind_apply(m, u[i], err);
        if (rc)
            return rc;
        if (y)
            y[i] = m->out[0];
        *lo = fmin(*lo, m->out[0]), *hi = fmax(*hi, m->out[0]);
    }
    return HY_OK;
}

/* The model's output along one record u[0..n) from the start state into y. */
static int drive_record(const hy_scene_run *r, int start, const double *u, size_t n, double *y, hy_error *err)
{
    hy_rateind m;
    int rc = hy_rateind_alloc(&m, r->mtype->ri, r->ri_par, start == START_ZERO ? 0.0 : u[0], err);
    if (rc)
        return rc;
    double lo = INFINITY, hi = -INFINITY;
    if (start == START_PERIODIC) { /* passes until y at the record's end repeats, twice in a row */
        double prev = NAN;
        int same = 0, k = 0;
        for (; !rc && same < 2 && k < SETTLE_MAX; k++) {
            lo = INFINITY, hi = -INFINITY;
            rc = pass(&m, u, n, NULL, &lo, &hi, err);
            double tol = SETTLE_TOL * fmax(fabs(lo), fabs(hi));
            same = fabs(m.out[0] - prev) <= tol ? same + 1 : 0;
            prev = m.out[0];
        }
        if (!rc && same < 2)
            rc = hy_error_set(err, HY_ENUM, "start = periodic: the output did not repeat within %d passes of the record",
                              SETTLE_MAX);
    }
    if (!rc && start == START_FIRST) { /* at u[0] already: its output, then on */
        y[0] = m.out[0];
        rc = pass(&m, u + 1, n - 1, y + 1, &lo, &hi, err);
    } else if (!rc)
        rc = pass(&m, u, n, y, &lo, &hi, err);
    hy_rateind_free(&m);
    return rc;
}

int hy_scene_run_driving(const hy_scene_run *r, hy_data_view *v, hy_error *err)
{
    memset(v, 0, sizeof *v);
    const hy_run_data *rd = r->drive;
    if (!rd)
        return hy_error_set(err, HY_EINVAL, "%s: no measured data drive the model ([input] kind = data, data = NAME)",
                            r->path ? r->path : "scene");
    v->name = rd->name;
    v->n = rd->i1 - rd->i0;
    v->u = rd->tb.u + rd->i0;
    v->y = rd->tb.y + rd->i0;
    v->nrec = rd->r1 - rd->r0;
    v->rec = rd->tb.rec + rd->r0;
    return HY_OK;
}

int hy_scene_run_model_at_data(const hy_scene_run *r, double *y_model, hy_error *err)
{
    hy_data_view v;
    int rc = hy_scene_run_driving(r, &v, err), start = r->doc.input.start;
    if (rc)
        return rc;
    if (stepped(r)) { /* one record (load checked it): y_1 at its times, from x0 (Eq. 3, gamma = 1) */
        double *t = record_times(r->drive);
        rc = t ? hy_gamma_exact(&r->model, &r->input, 1.0, t, v.n, y_model, NULL, err)
               : hy_error_set(err, HY_ENOMEM, "out of memory");
        free(t);
        return rc ? hy_decl_error(&r->doc.model.h, HY_DECL_HEAD, err, rc, "%s", err->msg) : HY_OK;
    }
    for (size_t j = 0; !rc && j < v.nrec; j++) {
        size_t a = v.rec[j] - v.rec[0], n = v.rec[j + 1] - v.rec[j];
        rc = drive_record(r, start, v.u + a, n, y_model + a, err);
    }
    return rc ? hy_scene_model_relocate(&r->doc.model, r->mtype, rc, err) : HY_OK;
}

int hy_scene_run_set_model(hy_scene_run *r, char *const *sets, size_t nsets, hy_error *err)
{
    for (size_t i = 0; i < nsets; i++)
        if (strncmp(sets[i], "model.", 6) || !strncmp(sets[i], "model.kind", 10))
            return hy_error_set(err, HY_EINVAL, "'%s': a loaded run changes only its [model] parameters (model.KEY=VALUE, "
                                "not model.kind)", sets[i]);
    if (!r->mtype->ri && !stepped(r))
        return need_drivable(r, &r->doc.model.h, HY_DECL_HEAD, "hy_scene_run_set_model", err);
    int rc = HY_OK;
    if (!r->model_marked && !(rc = hy_scene_mark(r->scene))) /* the scene as loaded: each call starts there */
        r->model_marked = 1;
    else if (!rc)
        hy_scene_restore(r->scene);
    for (size_t i = 0; !rc && i < nsets; i++)
        rc = hy_scene_set(r->scene, sets[i], err);
    if (rc)
        return rc;
    hy_scene_doc d;
    void *par = malloc(r->mtype->ri ? r->mtype->ri_par_size : 1);
    rc = par ? hy_scene_decode(r->scene, &d, err) : hy_error_set(err, HY_ENOMEM, "out of memory");
    if (!rc && !r->mtype->ri) { /* Dahl, LuGre: r->model from the new [model], kept as it was if refused */
        hy_decl_model keep = r->doc.model;
        hy_model old = r->model;
        r->doc.model = d.model;
        if ((rc = hy_scene_run_build_model(r, err))) {
            r->doc.model = keep;
            r->model = old;
        }
    } else if (!rc && !(rc = hy_scene_model_read(r->mtype, r->scene, &d.model, par, err))) { /* checked: only then the run's */
        r->doc.model = d.model;
        hy_scene_model_par_free(r->mtype, r->ri_par); /* the new parameters own what read allocated */
        memcpy(r->ri_par, par, r->mtype->ri_par_size);
    }
    if (par)
        hy_scene_doc_free(&d);
    free(par);
    return rc;
}

/* x of point i of a data series: u in a loop figure, else t (the running
 * sample index without a t column). */
static double data_x(const hy_scene_run *r, const hy_run_data *rd, size_t i)
{
    if (r->figure_kind == FIG_LOOP)
        return rd->tb.u[i];
    return rd->tb.t ? rd->tb.t[i] : (double)(i - rd->i0);
}

/* The points of one data series: its records, a NaN between two. */
static int fill(hy_scene_run *r, hy_run_series *se, const hy_run_data *rd, const double *ymodel, hy_error *err)
{
    size_t nrec = rd->r1 - rd->r0, n = rd->i1 - rd->i0 + nrec - 1, o = 0;
    int rc = hy_run_series_alloc(se, n, err);
    if (!rc && ymodel && !(se->ymeas = malloc(n * sizeof *se->ymeas)))
        rc = hy_error_set(err, HY_ENOMEM, "out of memory");
    for (size_t j = rd->r0; !rc && j < rd->r1; j++) {
        if (j > rd->r0) {
            se->x[o] = se->y[o] = NAN;
            if (se->ymeas)
                se->ymeas[o] = NAN;
            o++;
        }
        for (size_t i = rd->tb.rec[j]; i < rd->tb.rec[j + 1]; i++, o++) {
            se->x[o] = data_x(r, rd, i);
            se->y[o] = ymodel ? ymodel[i - rd->i0] : rd->tb.y[i];
            if (se->ymeas)
                se->ymeas[o] = rd->tb.y[i];
        }
    }
    return rc;
}

/* A series of measured or modelled data (decoded d): its [data] and what it may draw. */
static int series_data(const hy_scene_run *r, const hy_decl_series *d, const hy_run_data **rd, hy_error *err)
{
    if (hy_decl_got(&d->h, offsetof(hy_decl_series, of)) < 0)
        return hy_decl_error(&d->h, offsetof(hy_decl_series, data), err, HY_EINVAL,
                             "series '%s' (data = %s) needs 'of = NAME', a [data NAME] of the scene", d->h.name,
                             hy_scene_data_name(d->data));
    if (!(*rd = find_data(r, d->of)))
        return hy_decl_error(&d->h, offsetof(hy_decl_series, of), err, HY_EINVAL, "no [data %s] in the scene", d->of);
    if (d->data == HY_DATA_MODELLED && *rd != r->drive)
        return hy_decl_error(&d->h, offsetof(hy_decl_series, of), err, HY_EINVAL,
                             "data = modelled draws the model at the inputs of the data that drive it: [input] kind = data "
                             "and data = %s", d->of);
    return HY_OK;
}

int hy_scene_run_data_check(const hy_scene_run *r, hy_error *err)
{
    for (size_t i = 0; i < r->doc.nseries; i++) {
        const hy_decl_series *d = &r->doc.series[i];
        const hy_run_data *rd;
        int rc = HY_OK;
        if (hy_decl_got(&d->h, offsetof(hy_decl_series, data)) >= 0 &&
            (d->data == HY_DATA_MEASURED || d->data == HY_DATA_MODELLED))
            rc = series_data(r, d, &rd, err);
        if (rc)
            return rc;
    }
    return HY_OK;
}

int hy_scene_run_data_series(hy_scene_run *r, hy_error *err)
{
    for (size_t i = 0; i < r->nseries; i++) {
        hy_run_series *se = &r->series[i];
        if (se->data != HY_DATA_MEASURED && se->data != HY_DATA_MODELLED)
            continue;
        const hy_run_data *rd = NULL;
        int rc = series_data(r, se->decl, &rd, err);
        if (rc)
            return rc;
        se->err = se->dist = NAN;
        se->err_ref = NULL;
        double *ym = NULL;
        if (se->data == HY_DATA_MODELLED) {
            if (!(ym = malloc((rd->i1 - rd->i0) * sizeof *ym)))
                return hy_error_set(err, HY_ENOMEM, "out of memory");
            rc = hy_scene_run_model_at_data(r, ym, err);
        }
        if (!rc)
            rc = fill(r, se, rd, ym, err);
        free(ym);
        if (rc)
            return rc;
    }
    return HY_OK;
}

double hy_scene_data_value(const hy_scene_run *r, const hy_run_series *se, const char *field)
{
    const hy_run_data *rd = find_data(r, se->decl ? se->decl->of : NULL);
    if (!rd || (se->data != HY_DATA_MEASURED && se->data != HY_DATA_MODELLED) || !se->y)
        return NAN;
    if (!strcmp(field, "area") && rd->r1 - rd->r0 == 1 && se->n == rd->i1 - rd->i0)
        return hy_table_area(rd->tb.u + rd->i0, se->y, se->n);
    if (!strcmp(field, "rms") && se->ymeas) {
        double s = 0;
        size_t m = 0;
        for (size_t i = 0; i < se->n; i++)
            if (!isnan(se->ymeas[i])) {
                double d = se->y[i] - se->ymeas[i];
                s += d * d;
                m++;
            }
        return m ? sqrt(s / (double)m) : NAN;
    }
    return NAN;
}

void hy_scene_data_log(const hy_scene_run *r, FILE *log)
{
    for (size_t i = 0; i < r->nseries; i++) {
        const hy_run_series *se = &r->series[i];
        const hy_run_data *rd = find_data(r, se->decl ? se->decl->of : NULL);
        if (!rd || (se->data != HY_DATA_MEASURED && se->data != HY_DATA_MODELLED))
            continue;
        fprintf(log, "  series %-12s data=%-9s %7zu points of [data %s], %zu record%s", se->name,
                hy_scene_data_name(se->data), rd->i1 - rd->i0, rd->name, rd->r1 - rd->r0, rd->r1 - rd->r0 == 1 ? "" : "s");
        if (se->data == HY_DATA_MEASURED) {
            fprintf(log, "; loop areas (shoelace, counter-clockwise > 0):");
            for (size_t j = 0; j < rd->r1 - rd->r0; j++)
                fprintf(log, " %.6g", rd->area[j]);
        } else
            fprintf(log, "; RMS of model - measured %.6g", hy_scene_data_value(r, se, "rms"));
        fputc('\n', log);
    }
}
