/* SPDX-License-Identifier: MIT */
/* scene_fit.c: a scene's [model] fitted to its measured data (scene_fit.h;
 * issue 32 item 2, docs/FIT.md "Fitting a scene"): residual = model at the
 * measured inputs - measured output, over every [data] set chosen, by the
 * least-squares engine hy_fit.c.  The model is evaluated only through
 * hy_scene_run_set_model / hy_scene_run_model_at_data (scene_data.c), so a
 * model of the table is fitted without code of its own. */
#include "scene_fit.h"

#include <math.h>
#include <pthread.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hy_file.h"
#include "hy_scene_policy.h"
#include "scene_model.h"
#include "scene_run.h"

#define TEXT_MAX (1u << 20) /* a scene file read for its fitted copy (the parser's own limit) */

/* One thread's runs: one per data set, each set to the parameters it is asked for. */
typedef struct fit_slot {
    pthread_mutex_t mu;
    hy_scene_run *run; /* ndata */
} fit_slot;

typedef struct fit_ctx {
    const hy_scene_fit *f;
    fit_slot *slot;
    size_t nslot;
    const hy_cancel *user;  /* the caller's hook (o->fit.cancel), or NULL */
    size_t max_evals;       /* 0, or evaluations o->max_work allows */
    atomic_size_t evals;    /* evaluations begun */
    atomic_int over;        /* max_evals reached */
    atomic_int stopped;     /* user said stop once (a hook may say it only once: serve's looks
                               at most once a millisecond and says 0 between) */
    hy_cancel hook;         /* {fit_stop, this}: what hy_fit polls */
} fit_ctx;

/* Whether the fit is to stop: the caller said so, or the budget is spent. */
static int fit_stop(void *vctx)
{
    fit_ctx *c = vctx;
    if (!atomic_load(&c->stopped) && c->user && c->user->fn && c->user->fn(c->user->ctx))
        atomic_store(&c->stopped, 1);
    return atomic_load(&c->over) || atomic_load(&c->stopped);
}

void hy_scene_fit_opts_default(hy_scene_fit_opts *o)
{
    memset(o, 0, sizeof *o);
    hy_fit_opts_default(&o->fit);
}

void hy_scene_key_range(const hy_scene_key_spec *k, double v, double *lo, double *hi, int *log)
{
    int has_min = (k->flags & HY_SPEC_MIN) != 0, has_max = (k->flags & HY_SPEC_MAX) != 0;
    int integer = k->kind == HY_KIND_INTEGER;
    *log = 0;
    if (has_min && k->min >= 0 && v > 0) {
        *lo = v / 100, *hi = v * 100;
        if (integer)
            *lo = ceil(*lo), *hi = floor(*hi);
        if (*lo < k->min || (*lo == k->min && (k->flags & HY_SPEC_MIN_EXCL)))
            *lo = (k->flags & HY_SPEC_MIN_EXCL) ? (k->min > 0 ? k->min * 1.000001 : v / 100) : k->min;
        if (has_max && *hi > k->max)
            *hi = k->max;
        if (integer && *lo < 1)
            *lo = 1;
        *log = *lo > 0 && *hi / *lo >= 50;
        if (!*log && integer && !has_max)
            *hi = *lo + 100;
    } else if (has_min && k->min >= 0) { /* v = 0 */
        *lo = k->min;
        *hi = has_max ? k->max : k->min + (integer ? 100 : 1);
    } else {
        double w = fabs(v) > 0 ? fabs(v) : 1;
        *lo = v - w, *hi = v + w;
        if (has_min && *lo < k->min)
            *lo = k->min;
        if (has_max && *hi > k->max)
            *hi = k->max;
    }
    if (!(*hi > *lo))
        *hi = *lo + 1;
}

/* The residual: every data set's model output at theta minus its measured y.
 * Reentrant: each caller takes a slot (its own runs) under the slot's lock. */
static int resid(const double *theta, double *r, void *vctx)
{
    fit_ctx *c = vctx;
    const hy_scene_fit *f = c->f;
    if (c->max_evals && atomic_fetch_add(&c->evals, 1) >= c->max_evals)
        atomic_store(&c->over, 1);
    if (fit_stop(c)) /* fails at once: hy_fit stops at its next poll */
        return HY_ECANCEL;
    fit_slot *s = NULL;
    for (size_t i = 0; !s && i < c->nslot; i++)
        if (!pthread_mutex_trylock(&c->slot[i].mu))
            s = &c->slot[i];
    if (!s) { /* more callers than slots: wait for the first */
        s = &c->slot[0];
        pthread_mutex_lock(&s->mu);
    }
    size_t p = f->pb.p;
    char buf[16][96], *sets[16];
    for (size_t j = 0; j < p; j++) {
        snprintf(buf[j], sizeof buf[j], "model.%s=%.17g", f->prm[j].name, theta[j]);
        sets[j] = buf[j];
    }
    int rc = HY_OK;
    hy_error err = {0};
    for (size_t d = 0; !rc && d < f->ndata; d++) {
        rc = hy_scene_run_set_model(&s->run[d], sets, p, &err);
        if (!rc)
            rc = hy_scene_run_model_at_data(&s->run[d], r + f->off[d], &err);
    }
    pthread_mutex_unlock(&s->mu);
    if (rc)
        return rc;
    for (size_t i = 0; i < f->pb.n; i++)
        r[i] -= f->y[i];
    return HY_OK;
}

/* One free key: known, a number key of the scene's model, with a range of
 * more than one value; its bounds and the scene's value. */
static int free_key(const hy_scene_run *r, const char *key, hy_fit_param *q, double *x0, hy_error *err)
{
    if (!strncmp(key, "model.", 6))
        key += 6;
    int si = hy_scene_schema_section("model"), ki = hy_scene_schema_key(si, key);
    size_t n;
    const hy_scene_section_spec *sec = hy_scene_schema(&n);
    if (ki < 0)
        return hy_error_set(err, HY_EINVAL, "--free %s: [model] has no key '%s'", key, key);
    const hy_scene_key_spec *k = &sec[si].keys[ki];
    if (k->kind != HY_KIND_NUMBER)
        return hy_error_set(err, HY_EINVAL, "--free %s: a %s, not a number: only [model] number keys are fitted", key,
                            hy_scene_kind_name(k->kind));
    if (!strcmp(key, "kind") || !hy_scene_model_has_key(r->mtype, key))
        return hy_error_set(err, HY_EINVAL, "--free %s: the %s model does not read it", key, r->mtype->name);
    if ((k->flags & HY_SPEC_MIN) && (k->flags & HY_SPEC_MAX) && !(k->max > k->min))
        return hy_error_set(err, HY_EINVAL, "--free %s: the schema fixes it at %g", key, k->min);
    double v;
    if (hy_scene_doc_num(&r->doc, "model", key, &v))
        return hy_error_set(err, HY_EINVAL, "--free %s: it has no value to start from (set it in [model])", key);
    int lg;
    hy_scene_key_range(k, v, &q->lo, &q->hi, &lg);
    q->name = k->name;
    q->scale = lg ? HY_FIT_LOG : HY_FIT_LINEAR;
    *x0 = fmin(fmax(v, q->lo), q->hi);
    return HY_OK;
}

/* Loads one run per data set (the scene's own [input] data when none are
 * named): with --data NAME the model is driven by NAME (input.data=NAME) and
 * every modelled series follows it (series.S.of=NAME), so that the scene
 * loads whatever data its figure draws. */
static int load_runs(const char *path, const hy_scene_fit_opts *o, size_t ndata, hy_scene_run *run, hy_error *err)
{
    hy_scene *sc = NULL;
    hy_scene_doc d;
    memset(&d, 0, sizeof d);
    int rc = !o->ndata ? HY_OK
             : o->text ? hy_scene_parse_buffer_policy(path, o->text, o->text_len, o->pol, &sc, err)
                       : hy_scene_parse_file_policy(path, o->pol, &sc, err);
    if (!rc && sc && (rc = hy_scene_decode(sc, &d, err)))
        memset(&d, 0, sizeof d);
    size_t ns = 0, nm = 0;
    for (size_t i = 0; i < d.nseries; i++)
        nm += d.series[i].data == HY_DATA_MODELLED;
    char (*set)[200] = calloc(nm + 1, sizeof *set), **sets = calloc(o->nsets + nm + 1, sizeof *sets);
    if (!rc && (!set || !sets))
        rc = hy_error_set(err, HY_ENOMEM, "out of memory");
    size_t d_ok = 0;
    for (; !rc && d_ok < ndata; d_ok++) {
        ns = 0; /* the caller's overrides, then the data set's */
        for (size_t i = 0; i < o->nsets; i++)
            sets[ns++] = o->sets[i];
        size_t k = 0;
        if (o->ndata) {
            snprintf(set[k], sizeof set[k], "input.data=%s", o->data[d_ok]);
            sets[ns++] = set[k++];
            for (size_t i = 0; i < d.nseries; i++)
                if (d.series[i].data == HY_DATA_MODELLED) {
                    snprintf(set[k], sizeof set[k], "series.%s.of=%s", d.series[i].h.name, o->data[d_ok]);
                    sets[ns++] = set[k++];
                }
        }
        rc = o->text ? hy_scene_run_load_text(&run[d_ok], path, o->text, o->text_len, sets, ns, o->pol, err)
                     : hy_scene_run_load_policy(&run[d_ok], path, sets, ns, o->pol, err);
    }
    if (rc)
        for (size_t e = 0; e + 1 < d_ok; e++)
            hy_scene_run_free(&run[e]);
    free(set);
    free(sets);
    if (sc) {
        hy_scene_doc_free(&d);
        hy_scene_free(sc);
    }
    return rc;
}

static void free_slots(fit_slot *s, size_t nslot, size_t ndata)
{
    for (size_t i = 0; s && i < nslot; i++) {
        for (size_t d = 0; s[i].run && d < ndata; d++)
            hy_scene_run_free(&s[i].run[d]);
        free(s[i].run);
        pthread_mutex_destroy(&s[i].mu);
    }
    free(s);
}

/* The measured data of slot 0's runs into f (u, y, offsets, names). */
static int take_data(hy_scene_fit *f, const hy_scene_run *run, hy_error *err)
{
    hy_data_view v;
    f->off = calloc(f->ndata + 1, sizeof *f->off);
    f->nrec = calloc(f->ndata, sizeof *f->nrec);
    f->dname = calloc(f->ndata, sizeof *f->dname);
    if (!f->off || !f->nrec || !f->dname)
        return hy_error_set(err, HY_ENOMEM, "out of memory");
    for (size_t d = 0; d < f->ndata; d++) {
        int rc = hy_scene_run_driving(&run[d], &v, err);
        if (rc)
            return rc;
        f->off[d + 1] = f->off[d] + v.n;
        f->nrec[d] = v.nrec;
        if (!(f->dname[d] = strdup(v.name)))
            return hy_error_set(err, HY_ENOMEM, "out of memory");
    }
    size_t n = f->off[f->ndata];
    f->u = malloc(n * sizeof *f->u);
    f->y = malloc(n * sizeof *f->y);
    f->ymodel = malloc(n * sizeof *f->ymodel);
    if (!f->u || !f->y || !f->ymodel)
        return hy_error_set(err, HY_ENOMEM, "out of memory");
    for (size_t d = 0; d < f->ndata; d++) {
        hy_scene_run_driving(&run[d], &v, err);
        memcpy(f->u + f->off[d], v.u, v.n * sizeof *f->u);
        memcpy(f->y + f->off[d], v.y, v.n * sizeof *f->y);
    }
    return HY_OK;
}

/* Appends len bytes to the growing text *t (*n used, *cap allocated). */
static int put(char **t, size_t *n, size_t *cap, const char *s, size_t len)
{
    if (*n + len + 1 > *cap) {
        size_t c = 2 * (*n + len + 1);
        char *g = realloc(*t, c);
        if (!g)
            return HY_ENOMEM;
        *t = g, *cap = c;
    }
    memcpy(*t + *n, s, len);
    (*t)[*n += len] = '\0';
    return HY_OK;
}

/* The scene's text with each free key's estimate written in: on the key's
 * own line when the file writes it there, else after the [model] header,
 * else in a [model] section added at the end; a header comment says so. */
static int fitted_text(hy_scene_fit *f, const char *path, const hy_scene_fit_opts *o, hy_error *err)
{
    const hy_scene_policy *pol = o->pol;
    char *src = NULL, why[200];
    size_t len = o->text_len;
    if (o->text && (src = malloc(len + 1))) { /* the caller's text: the file as read once */
        memcpy(src, o->text, len);
        src[len] = '\0';
    } else if (o->text)
        return hy_error_set(err, HY_ENOMEM, "out of memory");
    else if (hy_file_read(path, TEXT_MAX, &src, &len, NULL, why, sizeof why))
        return hy_error_set(err, HY_EIO, "cannot read %s: %s", path, why);
    hy_scene *sc = NULL; /* the file as written (the runs' scenes carry the last evaluation's overrides) */
    if (pol ? hy_scene_parse_buffer_policy(path, src, len, pol, &sc, err) : hy_scene_parse_buffer(path, src, len, &sc, err)) {
        free(src);
        return err->code;
    }
    hy_scene_doc d;
    if (hy_scene_decode(sc, &d, err)) {
        hy_scene_free(sc);
        free(src);
        return err->code;
    }
    const hy_decl_head *h = &d.model.h;
    int hline = h->loc.line > 0 && h->loc.file && !strcmp(h->loc.file, path) ? h->loc.line : 0;
    size_t p = f->pb.p, n = 0, cap = 0;
    int *kline = calloc(p, sizeof *kline);
    char (*kv)[120] = calloc(p, sizeof *kv), line[200];
    int rc = kline && kv ? HY_OK : HY_ENOMEM;
    for (size_t j = 0; !rc && j < p; j++) {
        hy_scene_loc kl = hy_decl_loc(h, hy_decl_offset(h, f->prm[j].name));
        kline[j] = hline && kl.line > 0 && kl.file && !strcmp(kl.file, path) ? kl.line : 0;
        snprintf(kv[j], sizeof kv[j], "%s = %.17g", f->prm[j].name, f->res.theta[j]); /* round-trips */
    }
    /* hline 0: [model] in an include (or nowhere): a new [model] section at the end */
    snprintf(line, sizeof line, "# fitted by hystviz fit (docs/FIT.md): RMS %.17g over %zu points; standard errors:\n",
             f->res.rms, f->pb.n);
    if (!rc)
        rc = put(&f->text, &n, &cap, line, strlen(line));
    for (size_t j = 0; !rc && j < p; j++) {
        snprintf(line, sizeof line, "#   %s %.17g\n", f->prm[j].name, f->res.se[j]);
        rc = put(&f->text, &n, &cap, line, strlen(line));
    }
    for (size_t i = 0; !rc && i < o->nsets; i++) /* not written in: render needs them too */
        rc = put(&f->text, &n, &cap, i ? " --set " : "# fitted with --set ", i ? 7 : 20) ||
             put(&f->text, &n, &cap, o->sets[i], strlen(o->sets[i])) ||
             (i + 1 == o->nsets && put(&f->text, &n, &cap, "\n", 1));
    int ln = 1;
    for (const char *s = src; !rc && *s; ln++) {
        const char *nl = strchr(s, '\n');
        size_t l = nl ? (size_t)(nl - s) + 1 : strlen(s);
        int done = 0;
        for (size_t j = 0; !rc && j < p; j++)
            if (kline[j] == ln && !done) {
                rc = put(&f->text, &n, &cap, kv[j], strlen(kv[j])) || put(&f->text, &n, &cap, "\n", 1);
                done = 1;
            }
        if (!rc && !done)
            rc = put(&f->text, &n, &cap, s, l) || (!nl && put(&f->text, &n, &cap, "\n", 1));
        for (size_t j = 0; !rc && hline == ln && j < p; j++)
            if (!kline[j])
                rc = put(&f->text, &n, &cap, kv[j], strlen(kv[j])) || put(&f->text, &n, &cap, "\n", 1);
        s += l;
    }
    if (!rc && !hline) {
        rc = put(&f->text, &n, &cap, "\n[model]\n", 9);
        for (size_t j = 0; !rc && j < p; j++)
            if (!kline[j])
                rc = put(&f->text, &n, &cap, kv[j], strlen(kv[j])) || put(&f->text, &n, &cap, "\n", 1);
    }
    free(src);
    hy_scene_doc_free(&d);
    hy_scene_free(sc);
    free(kline);
    free(kv);
    return rc ? hy_error_set(err, HY_ENOMEM, "out of memory") : HY_OK;
}

int hy_scene_fit_run(const char *path, const hy_scene_fit_opts *o, hy_scene_fit *f, hy_error *err)
{
    memset(f, 0, sizeof *f);
    if (!path || !o || !o->nfree || o->nfree > 16)
        return hy_error_set(err, HY_EINVAL, "hy_scene_fit_run: a scene and 1 to 16 free keys");
    f->ndata = o->ndata ? o->ndata : 1;
    size_t nslot = o->fit.jobs > 1 ? (size_t)o->fit.jobs : 1;
    fit_slot *slot = calloc(nslot, sizeof *slot);
    int rc = slot ? HY_OK : hy_error_set(err, HY_ENOMEM, "out of memory");
    for (size_t i = 0; !rc && i < nslot; i++)
        pthread_mutex_init(&slot[i].mu, NULL); /* all of them: free_slots destroys each */
    for (size_t i = 0; !rc && i < nslot; i++) {
        slot[i].run = calloc(f->ndata, sizeof *slot[i].run);
        rc = slot[i].run ? load_runs(path, o, f->ndata, slot[i].run, err) : hy_error_set(err, HY_ENOMEM, "out of memory");
        if (rc) {
            free(slot[i].run);
            slot[i].run = NULL;
        }
    }
    size_t p = o->nfree;
    f->prm = rc ? NULL : calloc(p, sizeof *f->prm);
    f->x0 = rc ? NULL : calloc(p, sizeof *f->x0);
    if (!rc && (!f->prm || !f->x0))
        rc = hy_error_set(err, HY_ENOMEM, "out of memory");
    for (size_t j = 0; !rc && j < p; j++) {
        rc = free_key(&slot[0].run[0], o->free_keys[j], &f->prm[j], &f->x0[j], err);
        for (size_t i = 0; !rc && i < j; i++)
            if (!strcmp(f->prm[i].name, f->prm[j].name))
                rc = hy_error_set(err, HY_EINVAL, "--free %s: named twice", f->prm[j].name);
    }
    if (!rc)
        rc = take_data(f, slot[0].run, err);
    fit_ctx c = {.f = f, .slot = slot, .nslot = nslot, .user = o->fit.cancel};
    atomic_init(&c.evals, 0);
    atomic_init(&c.over, 0);
    atomic_init(&c.stopped, 0);
    c.hook = (hy_cancel){fit_stop, &c};
    hy_fit_opts fo = o->fit;
    fo.cancel = &c.hook;
    if (!rc) {
        f->pb = (hy_fit_problem){f->off[f->ndata], p, f->prm, resid, &c, f->x0, f->y};
        if (f->pb.n <= p)
            rc = hy_error_set(err, HY_EINVAL, "%zu measured points for %zu free parameters: too few", f->pb.n, p);
        if (o->max_work > 0) /* at least one evaluation: the budget refuses fits, not scenes */
            c.max_evals = (size_t)fmax(1, floor(o->max_work / (double)(f->pb.n ? f->pb.n : 1)));
    }
    if (!rc)
        rc = hy_fit_run(&f->pb, &fo, &f->res, err);
    if (rc && atomic_load(&c.over)) /* the budget, not the caller, stopped it */
        rc = hy_error_set(err, HY_EINVAL, "the fit stopped after %zu model evaluations of %zu points: over its work "
                          "budget of %.3g points (hystviz fit runs it)", c.max_evals, f->pb.n, o->max_work);
    else if (rc && atomic_load(&c.stopped))
        rc = hy_cancel_error(err);
    if (!rc) { /* the model at the estimate (the residual plus the data) */
        for (size_t i = 0; i < f->pb.n; i++)
            f->ymodel[i] = f->res.resid[i] + f->y[i];
        rc = fitted_text(f, path, o, err);
    }
    f->pb.ctx = NULL; /* c goes with this call */
    free_slots(slot, nslot, f->ndata);
    if (rc)
        hy_scene_fit_free(f);
    return rc;
}

void hy_scene_fit_free(hy_scene_fit *f)
{
    if (!f)
        return;
    if (f->res.theta)
        hy_fit_result_free(&f->res);
    for (size_t d = 0; f->dname && d < f->ndata; d++)
        free(f->dname[d]);
    free(f->dname);
    free(f->off);
    free(f->nrec);
    free(f->prm);
    free(f->x0);
    free(f->u);
    free(f->y);
    free(f->ymodel);
    free(f->text);
    memset(f, 0, sizeof *f);
}
