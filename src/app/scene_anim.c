/* scene_anim.c: scene-file animations: [keyframe NAME] tracks (linear or
 * smoothstep easing, optionally in log(value)) applied as overrides per frame,
 * the scene pipeline per frame with a per-thread run cache, GL drawing. */
#include "scene_anim.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "scene_run.h"

#define CACHE_RUNS 4          /* runs kept per thread (least recently used goes) */

/* ---- keyframes ---- */

/* Splits "section.key" / "section.NAME.key" and checks it against the schema
 * and the scene; fills k->target and k->integer. */
static int resolve_key(const hy_scene *s, scene_kf *k, const char *text, hy_error *err)
{
    const char *d1 = strchr(text, '.'), *d2 = strrchr(text, '.');
    char sec[64] = "", name[96] = "", key[64] = "";
    if (!d1 || d1 == text || !d2[1] || (size_t)(d1 - text) >= sizeof sec || strlen(d2 + 1) >= sizeof key)
        return hy_scene_error_at(s, "keyframe", k->label, "key", err, HY_EINVAL,
                                 "keyframe '%s': key \"%s\" is not section.key or section.NAME.key", k->label, text);
    memcpy(sec, text, (size_t)(d1 - text));
    strcpy(key, d2 + 1);
    if (d2 > d1) {
        if ((size_t)(d2 - d1 - 1) >= sizeof name)
            return hy_scene_error_at(s, "keyframe", k->label, "key", err, HY_EINVAL, "keyframe '%s': name too long", k->label);
        memcpy(name, d1 + 1, (size_t)(d2 - d1 - 1));
    }
    int si = hy_scene_schema_section(sec), ki = hy_scene_schema_key(si, key);
    size_t nsec;
    const hy_scene_section_spec *spec = hy_scene_schema(&nsec);
    if (si < 0 || ki < 0 || !strcmp(sec, "keyframe") || !strcmp(sec, "animation"))
        return hy_scene_error_at(s, "keyframe", k->label, "key", err, HY_EINVAL,
                                 "keyframe '%s': unknown key \"%s\" (write it as for --set: model.sigma0, series.NAME.gamma)",
                                 k->label, text);
    if (spec[si].takes_name != (name[0] != '\0'))
        return hy_scene_error_at(s, "keyframe", k->label, "key", err, HY_EINVAL, "keyframe '%s': [%s] sections %s a name (\"%s\")",
                                 k->label, sec, spec[si].takes_name ? "need" : "take no", text);
    hy_scene_loc loc;
    if (name[0] && !hy_scene_get_loc(s, sec, name, NULL, &loc))
        return hy_scene_error_at(s, "keyframe", k->label, "key", err, HY_EINVAL,
                                 "keyframe '%s': the scene has no [%s %s]", k->label, sec, name);
    hy_scene_kind kind = spec[si].keys[ki].kind;
    if (kind != HY_KIND_NUMBER && kind != HY_KIND_INTEGER)
        return hy_scene_error_at(s, "keyframe", k->label, "key", err, HY_EINVAL,
                                 "keyframe '%s': \"%s\" is not numeric (its kind: %s); only numbers and integers can be animated", k->label,
                                 text, hy_scene_kind_name(kind));
    k->integer = kind == HY_KIND_INTEGER;
    snprintf(k->target, sizeof k->target, "%s", text);
    return HY_OK;
}

/* Reads and validates one [keyframe NAME]; ease0 is the [animation] easing. */
static int load_kf(const hy_scene *s, scene_kf *k, int ease0, hy_error *err)
{
    const char *text, *lb = k->label;
    size_t nv;
    if (hy_scene_get_str(s, "keyframe", lb, "key", &text) < 0)
        return hy_scene_error_at(s, "keyframe", lb, NULL, err, HY_EINVAL, "keyframe '%s' needs a key", lb);
    int rc = resolve_key(s, k, text, err);
    if (rc)
        return rc;
    if (hy_scene_get_list(s, "keyframe", lb, "times", &k->t, &k->n) < 0 ||
        hy_scene_get_list(s, "keyframe", lb, "values", &k->v, &nv) < 0)
        return hy_scene_error_at(s, "keyframe", lb, NULL, err, HY_EINVAL, "keyframe '%s' needs times and values", lb);
    if (nv != k->n)
        return hy_scene_error_at(s, "keyframe", lb, "values", err, HY_EINVAL,
                                 "keyframe '%s': %zu values for %zu times (they must be as many)", lb, nv, k->n);
    for (size_t i = 1; i < k->n; i++)
        if (!(k->t[i] > k->t[i - 1]))
            return hy_scene_error_at(s, "keyframe", lb, "times", err, HY_EINVAL,
                                     "keyframe '%s': times must be strictly ascending (%g after %g)", lb, k->t[i], k->t[i - 1]);
    k->ease = ease0;
    const char *et;
    hy_scene_get_enum(s, "keyframe", lb, "easing", &k->ease, &et);
    hy_scene_get_bool(s, "keyframe", lb, "log", &k->log);
    for (size_t i = 0; k->log && i < k->n; i++)
        if (!(k->v[i] > 0))
            return hy_scene_error_at(s, "keyframe", lb, "values", err, HY_EINVAL,
                                     "keyframe '%s': log = true needs values > 0 (value %zu is %g)", lb, i + 1, k->v[i]);
    return HY_OK;
}

static void read_timing(scene_anim *a)
{
    const hy_scene *s = a->scene;
    long fps = 30;
    a->duration = 5;
    hy_scene_get_num(s, "animation", NULL, "duration", &a->duration);
    a->fps_set = hy_scene_get_int(s, "animation", NULL, "fps", &fps) == HY_SCENE_SET;
    a->fps = (double)fps;
    a->quality = "720p30";
    a->quality_set = hy_scene_get_enum(s, "animation", NULL, "quality", NULL, &a->quality) == HY_SCENE_SET;
}

int scene_anim_load(scene_anim *a, const char *path, hy_error *err)
{
    memset(a, 0, sizeof *a);
    a->path = path;
    int rc = hy_scene_parse_file(path, &a->scene, err);
    if (rc)
        return rc;
    read_timing(a);
    int ease0 = 1;
    const char *et;
    hy_scene_get_enum(a->scene, "animation", NULL, "easing", &ease0, &et);
    a->nkf = hy_scene_count(a->scene, "keyframe");
    a->kf = calloc(a->nkf + 1, sizeof *a->kf);
    if (!a->kf)
        rc = hy_error_set(err, HY_ENOMEM, "out of memory");
    for (size_t i = 0; !rc && i < a->nkf; i++) {
        a->kf[i].label = hy_scene_name_at(a->scene, "keyframe", i);
        rc = load_kf(a->scene, &a->kf[i], ease0, err);
    }
    for (size_t i = 0; !rc && i < a->nkf; i++)
        for (size_t j = 0; j < i; j++)
            if (!strcmp(a->kf[i].target, a->kf[j].target)) {
                rc = hy_scene_error_at(a->scene, "keyframe", a->kf[i].label, "key", err, HY_EINVAL,
                                       "keyframe '%s' animates %s, as keyframe '%s' does", a->kf[i].label, a->kf[i].target,
                                       a->kf[j].label);
                break;
            }
    if (!rc) {
        hy_scene_run tmp = {0};
        tmp.path = path;
        tmp.scene = a->scene;
        hy_scene_run_name(&tmp, a->name, sizeof a->name);
        pthread_mutex_init(&a->mu, NULL);
        return HY_OK;
    }
    hy_scene_free(a->scene);
    free(a->kf);
    memset(a, 0, sizeof *a);
    return rc;
}

double scene_kf_eval(const scene_kf *k, double t)
{
    if (t <= k->t[0])
        return k->v[0];
    size_t i = 1;
    while (i < k->n && k->t[i] < t)
        i++;
    if (i == k->n)
        return k->v[k->n - 1];
    if (t == k->t[i])
        return k->v[i];
    double a = k->v[i - 1], b = k->v[i], x = (t - k->t[i - 1]) / (k->t[i] - k->t[i - 1]);
    double f = k->ease ? x * x * (3.0 - 2.0 * x) : x;
    if (a == b)
        return a;
    if (k->log)
        return exp(log(a) + f * (log(b) - log(a)));
    return a + f * (b - a);
}

double scene_anim_time(long index, long nframes, double duration)
{
    if (nframes <= 1)
        return 0.0;
    if (index >= nframes - 1)
        return duration;
    return duration * (double)index / (double)(nframes - 1);
}

int scene_anim_sets(const scene_anim *a, double t, char *buf, size_t size, char **sets)
{
    size_t o = 0;
    for (size_t i = 0; i < a->nkf; i++) {
        const scene_kf *k = &a->kf[i];
        double v = scene_kf_eval(k, t);
        int w = k->integer ? snprintf(buf + o, size - o, "%s=%.0f", k->target, floor(v + 0.5))
                           : snprintf(buf + o, size - o, "%s=%.17g", k->target, v);
        if (w < 0 || (size_t)w + 1 >= size - o)
            return -1;
        sets[i] = buf + o;
        o += (size_t)w + 1;
    }
    return 0;
}

int scene_anim_check(const scene_anim *a, long nframes, double duration, hy_error *err)
{
    hy_scene *s;
    int rc = hy_scene_parse_file(a->path, &s, err);
    if (rc)
        return rc;
    char buf[4096], *sets[64];
    if (a->nkf > 64)
        rc = hy_scene_error_at(a->scene, "keyframe", a->kf[64].label, NULL, err, HY_EINVAL, "at most 64 keyframe sections");
    for (long f = 0; !rc && f < nframes; f++) {
        double t = scene_anim_time(f, nframes, duration);
        if (scene_anim_sets(a, t, buf, sizeof buf, sets)) {
            rc = hy_error_set(err, HY_EINVAL, "%s: keyframe overrides too long", a->path);
            break;
        }
        for (size_t i = 0; i < a->nkf && !rc; i++) {
            hy_error e2;
            if (hy_scene_set(s, sets[i], &e2)) {
                const char *why = strstr(e2.msg, ": ");
                rc = hy_scene_error_at(a->scene, "keyframe", a->kf[i].label, "values", err, HY_EINVAL,
                                       "keyframe '%s': at frame %ld (t = %g s) %s is refused%s", a->kf[i].label, f, t,
                                       sets[i], why ? why : "");
            }
        }
        hy_scene_run r;
        hy_error e3;
        if (!rc && a->nkf && hy_scene_run_load(&r, a->path, sets, a->nkf, &e3))
            rc = hy_scene_error_at(a->scene, "keyframe", a->kf[0].label, NULL, err, e3.code,
                                   "at frame %ld (t = %g s) the keyframe values give an invalid scene: %s", f, t,
                                   e3.msg);
        else if (!rc && a->nkf)
            hy_scene_run_free(&r);
    }
    hy_scene_free(s);
    return rc;
}

/* ---- per-thread run cache ---- */

typedef struct cache_run {
    char *key;                /* the joined overrides, NULL if unused */
    hy_scene_run run;
    unsigned long used;
} cache_run;

struct scene_cache {
    const void *owner;        /* the thread's GL context */
    cache_run runs[CACHE_RUNS];
    unsigned long clock;
};

static void cache_free(scene_cache *c)
{
    for (int i = 0; i < CACHE_RUNS; i++)
        if (c->runs[i].key) {
            hy_scene_run_free(&c->runs[i].run);
            free(c->runs[i].key);
        }
}

void scene_anim_free(scene_anim *a)
{
    if (!a->scene)
        return;
    for (size_t i = 0; i < a->ncache; i++)
        cache_free(&a->cache[i]);
    free(a->cache);
    free(a->kf);
    hy_scene_free(a->scene);
    pthread_mutex_destroy(&a->mu);
    memset(a, 0, sizeof *a);
}

#if HY_HAVE_OSMESA

/* The cache of the thread drawing on gl (one slot per thread, made once). */
static scene_cache *thread_cache(scene_anim *a, const void *gl, hy_error *err)
{
    scene_cache *c = NULL;
    pthread_mutex_lock(&a->mu);
    if (!a->cache) {
        size_t n = a->jobs > 0 ? (size_t)a->jobs : 1;
        a->cache = calloc(n, sizeof *a->cache);
        a->ncache = a->cache ? n : 0;
    }
    for (size_t i = 0; i < a->ncache && !c; i++)
        if (a->cache[i].owner == gl || !a->cache[i].owner) {
            a->cache[i].owner = gl;
            c = &a->cache[i];
        }
    pthread_mutex_unlock(&a->mu);
    if (!c)
        hy_error_set(err, HY_EINVAL, "more drawing threads than scene_anim.jobs");
    return c;
}

/* The computed run for the overrides sets (joined in key), from c or new. */
static const hy_scene_run *run_for(scene_anim *a, scene_cache *c, char **sets, const char *key, hy_error *err)
{
    cache_run *slot = &c->runs[0];
    for (int i = 0; i < CACHE_RUNS; i++) {
        cache_run *e = &c->runs[i];
        if (e->key && !strcmp(e->key, key)) {
            e->used = ++c->clock;
            pthread_mutex_lock(&a->mu);
            a->hits++;
            pthread_mutex_unlock(&a->mu);
            return &e->run;
        }
        if (!e->key || (slot->key && e->used < slot->used))
            slot = e;
    }
    if (slot->key) {
        hy_scene_run_free(&slot->run);
        free(slot->key);
        slot->key = NULL;
    }
    int rc = hy_scene_run_load(&slot->run, a->path, sets, a->nkf, err);
    if (rc)
        return NULL;
    if ((rc = hy_scene_run_compute(&slot->run, NULL, err)) || !(slot->key = strdup(key))) {
        if (!rc)
            hy_error_set(err, HY_ENOMEM, "out of memory");
        hy_scene_run_free(&slot->run);
        return NULL;
    }
    slot->used = ++c->clock;
    pthread_mutex_lock(&a->mu);
    a->computes++;
    pthread_mutex_unlock(&a->mu);
    return &slot->run;
}

int scene_anim_draw(void *state, const hy_anim_frame *f, hy_error *err)
{
    scene_anim *a = state;
    char buf[4096], key[4096], *sets[64];
    if (a->nkf > 64 || scene_anim_sets(a, scene_anim_time(f->index, f->nframes, f->duration), buf, sizeof buf, sets))
        return hy_error_set(err, HY_EINVAL, "%s: too many keyframe overrides", a->path);
    size_t o = 0;
    key[0] = '\0';
    for (size_t i = 0; i < a->nkf && o < sizeof key; i++)
        o += (size_t)snprintf(key + o, sizeof key - o, "%s;", sets[i]);
    scene_cache *c = thread_cache(a, f->gl, err);
    const hy_scene_run *r = c ? run_for(a, c, sets, key, err) : NULL;
    if (!r)
        return err->code ? err->code : HY_EINVAL;
    hy_scene_fig fig;
    int rc = hy_scene_run_figure(r, &fig, err);
    if (!rc) {
        fig.fig.width = f->width / f->scale;
        fig.fig.height = f->height / f->scale;
        fig.fig.dpi = 72.0 * f->scale;
        rc = hy_figure_draw_layers(&fig.fig, &f->data, &f->overlay, err);
    }
    hy_scene_fig_free(&fig);
    return rc;
}

#endif
