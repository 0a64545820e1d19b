/* SPDX-License-Identifier: MIT */
/* hystviz.c: libhystviz's pipeline entry points (hystviz.h): a scene's
 * series, loops and figure in memory through the pipeline `hystviz render`
 * and `hystviz data` use (src/pipeline), so the numbers and bytes are theirs. */
#include "hystviz.h"

#include <errno.h>
#include <gsl/gsl_errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hy_config.h"
#include "hy_out.h"
#include "hy_plot.h"
#include "hy_scene.h"
#include "hy_scene_schema.h"
#include "scene_fit.h"
#include "scene_model.h"
#include "scene_run.h"

/* err may always be NULL (hystviz.h, "Pointers"), but the pipeline reads
 * back the messages it writes (to prefix file:line:col): an entry point that
 * runs it gives it one on its own frame when the caller gave none. */
#define ERR_OWN(err)                                                                                                   \
    hy_error err##_own;                                                                                                \
    if (!(err))                                                                                                        \
    (err) = &err##_own

struct hy_result {
    hy_scene_run run;
    char *name; /* run.path points here */
};

const char *hy_version(void)
{
    return HY_VERSION;
}

void hy_gsl_quiet(void)
{
    gsl_set_error_handler_off();
}

static int finish(hy_result *r, int rc, hy_result **out)
{
    if (!rc) {
        *out = r;
        return HY_OK;
    }
    free(r->name);
    free(r);
    return rc;
}

/* Loads (through load, on r->run) and computes. */
static int compute(hy_result *r, hy_result **out, hy_error *err)
{
    int rc = hy_scene_run_compute(&r->run, NULL, err);
    if (rc)
        hy_scene_run_free(&r->run);
    return finish(r, rc, out);
}

/* The overrides of an entry point fn: sets may be NULL only when nsets is 0,
 * no sets[i] is NULL; 0, or HY_EINVAL with the message. */
static int sets_check(const char *fn, const char *const *sets, size_t nsets, hy_error *err)
{
    if (!sets && nsets)
        return hy_error_set(err, HY_EINVAL, "%s: sets is NULL but nsets is %zu", fn, nsets);
    for (size_t i = 0; i < nsets; i++)
        if (!sets[i])
            return hy_error_set(err, HY_EINVAL, "%s: override sets[%zu] is NULL", fn, i);
    return HY_OK;
}

/* The arguments every entry point that makes a result checks (hystviz.h,
 * "Pointers"): 0, or HY_EINVAL with the message. */
static int args_check(const char *what, const void *src, const char *const *sets, size_t nsets, double max_work,
                      hy_result **out, hy_error *err)
{
    if (out)
        *out = NULL;
    else
        return hy_error_set(err, HY_EINVAL, "hy_result_from_%s: out must not be NULL (nothing computed)", what);
    if (!src)
        return hy_error_set(err, HY_EINVAL, "hy_result_from_%s: no scene %s (NULL)", what,
                            strcmp(what, "file") ? "text" : "path");
    int rc = sets_check(strcmp(what, "file") ? "hy_result_from_text" : "hy_result_from_file", sets, nsets, err);
    if (rc)
        return rc;
    if (!isfinite(max_work))
        return hy_error_set(err, HY_EINVAL, "hy_result_from_%s: the work budget max_work must be a finite number "
                            "(<= 0: the default), got %g", what, max_work);
    return HY_OK;
}

static hy_result *result_new(const char *name, hy_result **out, hy_error *err)
{
    *out = NULL;
    hy_result *r = calloc(1, sizeof *r);
    if (r && !(r->name = strdup(name ? name : "<scene>"))) {
        free(r);
        r = NULL;
    }
    if (!r)
        hy_error_set(err, HY_ENOMEM, "out of memory");
    return r;
}

static hy_scene_policy policy(double max_work)
{
    hy_scene_policy pol = hy_scene_policy_default();
    pol.max_work = max_work;
    return pol;
}

/* hy_result_from_text's work (err not NULL).  verify 0: the closed-form
 * series are not measured against the long-double references (no_verify,
 * scene_run_types.h: the same numbers, no error), for a caller that returns
 * the numbers alone (hy_steady_loop). */
static int result_text(const char *name, const char *text, size_t len, const char *const *sets, size_t nsets,
                       double max_work, int verify, hy_result **out, hy_error *err)
{
    int bad = args_check("text", text, sets, nsets, max_work, out, err);
    if (bad)
        return bad;
    hy_result *r = result_new(name, out, err);
    if (!r)
        return HY_ENOMEM;
    hy_scene_policy pol = policy(max_work);
    int rc = hy_scene_run_load_text(&r->run, r->name, text, len, (char *const *)sets, nsets, &pol, err);
    if (rc)
        return finish(r, rc, out);
    r->run.no_verify = !verify;
    return compute(r, out, err);
}

int hy_result_from_text(const char *name, const char *text, size_t len, const char *const *sets, size_t nsets,
                        double max_work, hy_result **out, hy_error *err)
{
    ERR_OWN(err);
    return result_text(name, text, len, sets, nsets, max_work, 1, out, err);
}

int hy_result_from_file(const char *path, const char *const *sets, size_t nsets, double max_work, hy_result **out,
                        hy_error *err)
{
    ERR_OWN(err);
    int bad = args_check("file", path, sets, nsets, max_work, out, err);
    if (bad)
        return bad;
    hy_result *r = result_new(path, out, err);
    if (!r)
        return HY_ENOMEM;
    hy_scene_policy pol = policy(max_work);
    int rc = hy_scene_run_load_policy(&r->run, r->name, (char *const *)sets, nsets, &pol, err);
    return rc ? finish(r, rc, out) : compute(r, out, err);
}

void hy_result_free(hy_result *r)
{
    if (!r)
        return;
    hy_scene_run_free(&r->run);
    free(r->name);
    free(r);
}

size_t hy_result_nseries(const hy_result *r)
{
    return r ? r->run.nseries : 0;
}

static const hy_run_series *series_at(const hy_result *r, size_t i)
{
    return r && i < r->run.nseries ? &r->run.series[i] : NULL;
}

size_t hy_result_series(const hy_result *r, size_t i, const double **x, const double **y)
{
    const hy_run_series *se = series_at(r, i);
    if (x)
        *x = se ? se->x : NULL;
    if (y)
        *y = se ? se->y : NULL;
    return se ? se->n : 0;
}

size_t hy_result_series_copy(const hy_result *r, size_t i, double *x, double *y, size_t cap)
{
    const hy_run_series *se = series_at(r, i);
    if (!se)
        return 0;
    size_t m = se->n < cap ? se->n : cap;
    if (x && m)
        memcpy(x, se->x, m * sizeof *x);
    if (y && m)
        memcpy(y, se->y, m * sizeof *y);
    return se->n;
}

const char *hy_result_series_name(const hy_result *r, size_t i)
{
    const hy_run_series *se = series_at(r, i);
    return se ? se->name : NULL;
}

const char *hy_result_series_data(const hy_result *r, size_t i)
{
    const hy_run_series *se = series_at(r, i);
    if (!se)
        return NULL;
    int sec = hy_scene_schema_section("series");
    const hy_scene_section_spec *spec = hy_scene_schema(NULL) + sec;
    int k = hy_scene_schema_key(sec, "data");
    return spec->keys[k].enums[se->data];
}

double hy_result_series_error(const hy_result *r, size_t i, const char **ref)
{
    const hy_run_series *se = series_at(r, i);
    if (ref)
        *ref = se ? se->err_ref : NULL;
    return se ? se->err : NAN;
}

const hy_loops *hy_result_loops(const hy_result *r)
{
    return r && r->run.have_loops ? &r->run.loops : NULL;
}

int hy_result_render(const hy_result *r, const char *format, unsigned char **bytes, size_t *len, hy_error *err)
{
    ERR_OWN(err);
    if (bytes)
        *bytes = NULL;
    if (len)
        *len = 0;
    if (!bytes || !len)
        return hy_error_set(err, HY_EINVAL, "hy_result_render: %s must not be NULL", bytes ? "len" : "bytes");
    if (!r)
        return hy_error_set(err, HY_EINVAL, "no result to draw");
    if (!format)
        return hy_error_set(err, HY_EINVAL, "give one format (svg, pdf or png), not NULL");
    int fmt[3];
    size_t n = 0;
    int rc = hy_scene_formats_parse(format, fmt, &n, err);
    if (!rc && n != 1)
        rc = hy_error_set(err, HY_EINVAL, "give one format (svg, pdf or png), not '%s'", format);
    return rc ? rc : hy_scene_run_render(&r->run, fmt[0], bytes, len, NULL, err);
}

int hy_result_csv(const hy_result *r, char **text, size_t *len, hy_error *err)
{
    ERR_OWN(err);
    if (text)
        *text = NULL;
    if (len)
        *len = 0;
    if (!text || !len)
        return hy_error_set(err, HY_EINVAL, "hy_result_csv: %s must not be NULL", text ? "len" : "text");
    if (!r)
        return hy_error_set(err, HY_EINVAL, "no result to print");
    return hy_scene_run_csv(&r->run, text, len, err);
}

int hy_boucwen_run(const double *u, size_t n, double fs, double *y, hy_error *err)
{
    hy_boucwen_params p;
    hy_newmark_opts o;
    hy_boucwen_params_default(&p);
    hy_newmark_opts_default(&o);
    if (!u || !y || n < 1)
        return hy_error_set(err, HY_EINVAL, "the force needs at least one sample");
    if (!(fs > 0) || !isfinite(fs))
        return hy_error_set(err, HY_EINVAL, "fs must be a positive number of Hz, got %g", fs);
    return hy_boucwen_synth(&p, &o, fs, 1, 1, u, n, y, err);
}

/* The scene of hy_steady_loop after its two sections: one period at points
 * samples, the input and y° as the series 0 and 1 of a time series. */
#define STEADY_TAIL                                                                                                    \
    "[compute]\npoints = %zu\ncycles = 1\n[figure]\nkind = timeseries\n[series u]\ndata = input\n"                     \
    "[series y]\ndata = ysteady\n"

int hy_steady_loop(const char *name, const char *model, const char *input, const char *const *sets, size_t nsets,
                   size_t points, double *t, double *u, double *y, hy_error *err)
{
    if (!model || !input)
        return hy_error_set(err, HY_EINVAL, "hy_steady_loop: no [%s] text (NULL)", model ? "input" : "model");
    int bad = sets_check("hy_steady_loop", sets, nsets, err);
    if (bad)
        return bad;
    /* model, a line break if it has none at its end, input, one, the tail */
    size_t lm = strlen(model), li = strlen(input);
    size_t cap = lm + li + 2 + sizeof STEADY_TAIL + 20; /* %zu: at most 20 digits */
    char *text = malloc(cap), *p = text;
    if (!text)
        return hy_error_set(err, HY_ENOMEM, "out of memory");
    memcpy(p, model, lm);
    p += lm;
    if (lm && model[lm - 1] != '\n')
        *p++ = '\n';
    memcpy(p, input, li);
    p += li;
    if (li && input[li - 1] != '\n')
        *p++ = '\n';
    size_t head = (size_t)(p - text);
    int tail = snprintf(p, cap - head, STEADY_TAIL, points);
    /* the numbers alone: y° is not measured against its long-double reference
     * (a sixth of a 200-point call; the same y bit for bit, every model kind:
     * tests/python/test_python.py against hy_result_from_text's) */
    hy_result *r = NULL;
    ERR_OWN(err);
    int rc = tail < 0 ? hy_error_set(err, HY_EINVAL, "hy_steady_loop: cannot write the scene")
                      : result_text(name, text, head + (size_t)tail, sets, nsets, 0, 0, &r, err);
    free(text);
    if (rc)
        return rc;
    /* the input's and y°'s series are sampled on the one grid of points + 1 (src/pipeline/scene_run.c) */
    size_t n = points + 1;
    if (hy_result_nseries(r) != 2 || hy_result_series_copy(r, 0, NULL, NULL, 0) != n ||
        hy_result_series_copy(r, 1, NULL, NULL, 0) != n)
        rc = hy_error_set(err, HY_ENUM, "hy_steady_loop: the input and y° are not sampled on %zu points", n);
    else {
        hy_result_series_copy(r, 0, t, u, n);
        hy_result_series_copy(r, 1, NULL, y, n);
    }
    hy_result_free(r);
    return rc;
}

int hy_write_file(const char *path, const void *data, size_t len, hy_error *err)
{
    if (!path)
        return hy_error_set(err, HY_EINVAL, "hy_write_file: no path (NULL)");
    if (!data && len)
        return hy_error_set(err, HY_EINVAL, "cannot write '%s': no data (NULL) for %zu bytes", path, len);
    hy_out o;
    int rc = hy_out_open(&o, path, 0, err);
    if (rc)
        return rc;
    if (len && fwrite(data, 1, len, hy_out_file(&o)) != len) {
        int e = errno;
        hy_out_abort(&o);
        return hy_error_set(err, HY_EIO, "cannot write '%s': %s", path, strerror(e));
    }
    return hy_out_commit(&o, err);
}

/* ---- the schema as JSON --------------------------------------------------- */

static void json_str(FILE *f, const char *s)
{
    fputc('"', f);
    for (const unsigned char *p = (const unsigned char *)(s ? s : ""); *p; p++) {
        if (*p == '"' || *p == '\\')
            fprintf(f, "\\%c", *p);
        else if (*p < 0x20)
            fprintf(f, "\\u%04x", *p);
        else
            fputc(*p, f);
    }
    fputc('"', f);
}

static void json_list(FILE *f, const char *const *v)
{
    fputc('[', f);
    for (size_t i = 0; v && v[i]; i++) {
        if (i)
            fputc(',', f);
        json_str(f, v[i]);
    }
    fputc(']', f);
}

static void json_bound(FILE *f, const char *name, int has, double v, int excl)
{
    fprintf(f, ",\"%s\":", name);
    if (has)
        fprintf(f, "%.17g,\"%s_exclusive\":%s", v, name, excl ? "true" : "false");
    else
        fputs("null", f);
}

/* s as a JSON string, or null when s is NULL */
static void json_str_or_null(FILE *f, const char *s)
{
    if (s)
        json_str(f, s);
    else
        fputs("null", f);
}

/* One key of the schema as a JSON object: name, kind, bounds, default, enums,
 * doc, unit ("N s/m"; null: none or dimensionless) and the symbol as the
 * papers print it (markup; null: none). */
static void json_key(FILE *f, const hy_scene_key_spec *k)
{
    fputs("{\"name\":", f);
    json_str(f, k->name);
    fputs(",\"kind\":", f);
    json_str(f, hy_scene_kind_name(k->kind));
    json_bound(f, "min", k->flags & HY_SPEC_MIN, k->min, k->flags & HY_SPEC_MIN_EXCL);
    json_bound(f, "max", k->flags & HY_SPEC_MAX, k->max, k->flags & HY_SPEC_MAX_EXCL);
    fputs(",\"default\":", f);
    json_str_or_null(f, k->def);
    fputs(",\"enums\":", f);
    json_list(f, k->enums);
    fputs(",\"doc\":", f);
    json_str(f, k->doc);
    fputs(",\"unit\":", f);
    json_str_or_null(f, k->unit);
    fputs(",\"symbol\":", f);
    json_str_or_null(f, k->symbol);
    fputc('}', f);
}

/* One section of the schema as a JSON object, its keys included. */
static void json_section(FILE *f, const hy_scene_section_spec *sec)
{
    fputs("{\"name\":", f);
    json_str(f, sec->name);
    fprintf(f, ",\"takes_name\":%s,\"repeatable\":%s,\"doc\":", sec->takes_name ? "true" : "false",
            sec->repeatable ? "true" : "false");
    json_str(f, sec->doc);
    fputs(",\"keys\":[", f);
    for (size_t j = 0; j < sec->nkeys; j++) {
        fputs(j ? "," : "", f);
        json_key(f, &sec->keys[j]);
    }
    fputs("]}", f);
}

/* One entry of the model table as a JSON object: its keys, quantities, state
 * and capabilities. */
static void json_model(FILE *f, const hy_scene_model *mt)
{
    fputs("{\"name\":", f);
    json_str(f, mt->name);
    fputs(",\"params\":[", f);
    const char *p;
    for (size_t k = 0; (p = hy_scene_model_param(mt, k)); k++) {
        fputs(k ? "," : "", f);
        json_str(f, p);
    }
    fputc(']', f);
    fputs(",\"quantities\":", f);
    json_list(f, mt->quantities);
    fputs(",\"state\":", f);
    json_str(f, mt->state);
    fputs(",\"caps\":[", f);
    int first = 1;
    for (unsigned b = 1; b; b <<= 1)
        if ((mt->caps & b) && hy_scene_cap_name(b)) {
            fputs(first ? "" : ",", f);
            first = 0;
            json_str(f, hy_scene_cap_name(b));
        }
    fputs("]}", f);
}

char *hy_schema_json(void)
{
    char *buf = NULL;
    size_t len = 0, nsec;
    FILE *f = open_memstream(&buf, &len);
    if (!f)
        return NULL;
    const hy_scene_section_spec *sec = hy_scene_schema(&nsec);
    fputs("{\"version\":", f);
    json_str(f, HY_VERSION);
    fputs(",\"sections\":[", f);
    for (size_t i = 0; i < nsec; i++) {
        fputs(i ? "," : "", f);
        json_section(f, &sec[i]);
    }
    /* the model table: each kind's keys, quantities and capabilities */
    fputs("],\"models\":[", f);
    for (size_t i = 0; hy_scene_models[i]; i++) {
        fputs(i ? "," : "", f);
        json_model(f, hy_scene_models[i]);
    }
    fputs("]}", f);
    if (fclose(f)) {
        free(buf);
        return NULL;
    }
    return buf;
}

/* ---- hy_fit_scene (scene_fit.c) ---- */

struct hy_scene_fitted {
    hy_scene_fit f;
    double *unident, *offsets, *lo, *hi; /* the int and size_t arrays as doubles */
};

int hy_fit_scene(const char *path, const char *const *free_keys, size_t nfree, const char *const *data, size_t ndata,
                 size_t starts, unsigned long long seed, int jobs, hy_scene_fitted **out, hy_error *err)
{
    ERR_OWN(err);
    if (out)
        *out = NULL;
    if (!out)
        return hy_error_set(err, HY_EINVAL, "hy_fit_scene: out must not be NULL");
    if (!path || !free_keys || nfree < 1 || nfree > 16)
        return hy_error_set(err, HY_EINVAL, "hy_fit_scene: a scene path and 1 to 16 free keys");
    for (size_t j = 0; j < nfree; j++)
        if (!free_keys[j])
            return hy_error_set(err, HY_EINVAL, "hy_fit_scene: free_keys[%zu] is NULL", j);
    for (size_t d = 0; data && d < ndata; d++)
        if (!data[d])
            return hy_error_set(err, HY_EINVAL, "hy_fit_scene: data[%zu] is NULL", d);
    if (jobs < 1 || jobs > 64)
        return hy_error_set(err, HY_EINVAL, "hy_fit_scene: jobs must be 1 to 64 (got %d)", jobs);
    hy_scene_fit_opts o;
    hy_scene_fit_opts_default(&o);
    o.free_keys = free_keys, o.nfree = nfree;
    o.data = data, o.ndata = data ? ndata : 0;
    o.fit.starts = starts, o.fit.seed = seed, o.fit.jobs = jobs;
    hy_scene_fitted *r = calloc(1, sizeof *r);
    if (!r)
        return hy_error_set(err, HY_ENOMEM, "out of memory");
    hy_error e = {0};
    int rc = hy_scene_fit_run(path, &o, &r->f, err ? err : &e);
    size_t p = rc ? 0 : r->f.pb.p, nd = rc ? 0 : r->f.ndata;
    if (!rc && (!(r->unident = malloc(p * sizeof *r->unident)) || !(r->lo = malloc(p * sizeof *r->lo)) ||
                !(r->hi = malloc(p * sizeof *r->hi)) || !(r->offsets = malloc((nd + 1) * sizeof *r->offsets))))
        rc = hy_error_set(err, HY_ENOMEM, "out of memory");
    for (size_t j = 0; !rc && j < p; j++)
        r->unident[j] = r->f.res.unident[j], r->lo[j] = r->f.prm[j].lo, r->hi[j] = r->f.prm[j].hi;
    for (size_t d = 0; !rc && d <= nd; d++)
        r->offsets[d] = (double)r->f.off[d];
    if (rc) {
        hy_scene_fitted_free(r);
        return rc;
    }
    *out = r;
    return HY_OK;
}

void hy_scene_fitted_free(hy_scene_fitted *f)
{
    if (!f)
        return;
    hy_scene_fit_free(&f->f);
    free(f->unident);
    free(f->offsets);
    free(f->lo);
    free(f->hi);
    free(f);
}

const double *hy_scene_fitted_array(const hy_scene_fitted *f, const char *what, size_t *len)
{
    if (len)
        *len = 0;
    if (!f || !what)
        return NULL;
    const hy_fit_result *r = &f->f.res;
    size_t p = f->f.pb.p, n = f->f.pb.n;
    const struct { const char *name; const double *a; size_t n; } t[] = {
        {"theta", r->theta, p}, {"se", r->se, p}, {"ci_lo", r->ci_lo, p}, {"ci_hi", r->ci_hi, p},
        {"start", f->f.x0, p}, {"lo", f->lo, p}, {"hi", f->hi, p}, {"unident", f->unident, p},
        {"corr", r->corr, p * p}, {"u", f->f.u, n}, {"y", f->f.y, n}, {"model", f->f.ymodel, n},
        {"resid", r->resid, n}, {"offsets", f->offsets, f->f.ndata + 1}};
    for (size_t i = 0; i < sizeof t / sizeof t[0]; i++)
        if (!strcmp(what, t[i].name)) {
            if (len)
                *len = t[i].n;
            return t[i].a;
        }
    return NULL;
}

double hy_scene_fitted_stat(const hy_scene_fitted *f, const char *what)
{
    if (!f || !what)
        return NAN;
    const hy_fit_result *r = &f->f.res;
    const struct { const char *name; double v; } t[] = {
        {"rss", r->rss}, {"rms", r->rms}, {"nrms", r->nrms}, {"max_abs", r->max_abs}, {"fit_index", r->fit_index},
        {"cond", r->cond}, {"dof", (double)r->dof}, {"iterations", (double)r->iter},
        {"evaluations", (double)r->nevals}, {"seconds", r->seconds}, {"starts", (double)r->nstarts},
        {"failed", (double)r->nfailed}};
    for (size_t i = 0; i < sizeof t / sizeof t[0]; i++)
        if (!strcmp(what, t[i].name))
            return t[i].v;
    return NAN;
}

const char *hy_scene_fitted_key(const hy_scene_fitted *f, size_t j)
{
    return f && j < f->f.pb.p ? f->f.prm[j].name : NULL;
}

const char *hy_scene_fitted_data(const hy_scene_fitted *f, size_t j)
{
    return f && j < f->f.ndata ? f->f.dname[j] : NULL;
}

const char *hy_scene_fitted_text(const hy_scene_fitted *f)
{
    return f ? f->f.text : NULL;
}
