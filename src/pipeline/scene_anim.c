/* SPDX-License-Identifier: MIT */
/* scene_anim.c: scene-file animations: [keyframe NAME] tracks (linear or
 * smoothstep easing, optionally in log(value)) applied as overrides per frame,
 * the scene pipeline once per distinct set of values (shared cache), GL drawing. */
#include "scene_anim.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "scene_run.h"


/* ---- keyframes ---- */

#define KF_AT(f) offsetof(hy_decl_keyframe, f)

/* Splits "section.key" / "section.NAME.key" and checks it against the schema
 * and the decoded scene d; fills k->target and k->integer. */
static int resolve_key(const hy_scene_doc *d, scene_kf *k, const char *text, hy_error *err)
{
    const hy_decl_head *h = &k->decl->h;
    size_t at = KF_AT(key);
    const char *d1 = strchr(text, '.'), *d2 = strrchr(text, '.');
    char sec[64] = "", name[96] = "", key[64] = "";
    if (!d1 || d1 == text || !d2[1] || (size_t)(d1 - text) >= sizeof sec || strlen(d2 + 1) >= sizeof key)
        return hy_decl_error(h, at, err, HY_EINVAL, "keyframe '%s': key \"%s\" is not section.key or section.NAME.key",
                             k->label, text);
    memcpy(sec, text, (size_t)(d1 - text));
    strcpy(key, d2 + 1);
    if (d2 > d1) {
        if ((size_t)(d2 - d1 - 1) >= sizeof name)
            return hy_decl_error(h, at, err, HY_EINVAL, "keyframe '%s': name too long", k->label);
        memcpy(name, d1 + 1, (size_t)(d2 - d1 - 1));
    }
    int si = hy_scene_schema_section(sec), ki = hy_scene_schema_key(si, key);
    size_t nsec;
    const hy_scene_section_spec *spec = hy_scene_schema(&nsec);
    if (si < 0 || ki < 0 || !strcmp(sec, "keyframe") || !strcmp(sec, "animation"))
        return hy_decl_error(h, at, err, HY_EINVAL,
                             "keyframe '%s': unknown key \"%s\" (write it as for --set: model.sigma0, series.NAME.gamma)",
                             k->label, text);
    if (spec[si].takes_name != (name[0] != '\0'))
        return hy_decl_error(h, at, err, HY_EINVAL, "keyframe '%s': [%s] sections %s a name (\"%s\")", k->label, sec,
                             spec[si].takes_name ? "need" : "take no", text);
    if (name[0] && !hy_scene_doc_find(d, sec, name))
        return hy_decl_error(h, at, err, HY_EINVAL, "keyframe '%s': the scene has no [%s %s]", k->label, sec, name);
    hy_scene_kind kind = spec[si].keys[ki].kind;
    if (kind != HY_KIND_NUMBER && kind != HY_KIND_INTEGER)
        return hy_decl_error(h, at, err, HY_EINVAL,
                             "keyframe '%s': \"%s\" is not numeric (its kind: %s); only numbers and integers can be animated",
                             k->label, text, hy_scene_kind_name(kind));
    k->integer = kind == HY_KIND_INTEGER;
    snprintf(k->target, sizeof k->target, "%s", text);
    return HY_OK;
}

/* Validates one decoded [keyframe NAME] into k; ease0 is the [animation] easing. */
static int load_kf(const hy_scene_doc *d, scene_kf *k, int ease0, hy_error *err)
{
    const hy_decl_keyframe *kd = k->decl;
    const hy_decl_head *h = &kd->h;
    const char *lb = k->label;
    if (hy_decl_got(h, KF_AT(key)) < 0)
        return hy_decl_error(h, HY_DECL_HEAD, err, HY_EINVAL, "keyframe '%s' needs a key", lb);
    int rc = resolve_key(d, k, kd->key, err);
    if (rc)
        return rc;
    if (hy_decl_got(h, KF_AT(times)) < 0 || hy_decl_got(h, KF_AT(values)) < 0)
        return hy_decl_error(h, HY_DECL_HEAD, err, HY_EINVAL, "keyframe '%s' needs times and values", lb);
    k->t = kd->times.v;
    k->n = kd->times.n;
    k->v = kd->values.v;
    if (kd->values.n != k->n)
        return hy_decl_error(h, KF_AT(values), err, HY_EINVAL, "keyframe '%s': %zu values for %zu times (they must be as many)",
                             lb, kd->values.n, k->n);
    for (size_t i = 1; i < k->n; i++)
        if (!(k->t[i] > k->t[i - 1]))
            return hy_decl_error(h, KF_AT(times), err, HY_EINVAL,
                                 "keyframe '%s': times must be strictly ascending (%g after %g)", lb, k->t[i], k->t[i - 1]);
    k->ease = hy_decl_got(h, KF_AT(easing)) >= 0 ? kd->easing : ease0;
    k->log = kd->log;
    for (size_t i = 0; k->log && i < k->n; i++)
        if (!(k->v[i] > 0))
            return hy_decl_error(h, KF_AT(values), err, HY_EINVAL,
                                 "keyframe '%s': log = true needs values > 0 (value %zu is %g)", lb, i + 1, k->v[i]);
    return HY_OK;
}

/* The [animation] timing (set or default) from the decoded scene. */
static void read_timing(scene_anim *a)
{
    const hy_decl_animation *an = &a->doc.animation;
    a->duration = an->duration;
    a->fps = (double)an->fps;
    a->fps_set = hy_decl_got(&an->h, offsetof(hy_decl_animation, fps)) == HY_SCENE_SET;
    a->quality = hy_decl_enum_text(&an->h, offsetof(hy_decl_animation, quality), an->quality);
    a->quality_set = hy_decl_got(&an->h, offsetof(hy_decl_animation, quality)) == HY_SCENE_SET;
}

int scene_anim_load(scene_anim *a, const char *path, hy_error *err)
{
    return scene_anim_load_policy(a, path, NULL, err);
}

int scene_anim_load_policy(scene_anim *a, const char *path, const hy_scene_policy *pol, hy_error *err)
{
    return scene_anim_load_src(a, path, NULL, 0, NULL, 0, pol, err);
}

/* The scene parsed from a's text (or its file) with the user's overrides. */
static int parse_scene(const scene_anim *a, hy_scene **s, hy_error *err)
{
    int rc = a->text ? hy_scene_parse_buffer_policy(a->path, a->text, a->len, &a->pol, s, err)
                     : hy_scene_parse_file_policy(a->path, &a->pol, s, err);
    for (size_t i = 0; !rc && i < a->nuser; i++)
        if ((rc = hy_scene_set(*s, a->user[i], err))) {
            hy_scene_free(*s);
            *s = NULL;
        }
    return rc;
}

/* The user's overrides, then the keyframes' (which beat them), into all. */
static size_t all_sets(const scene_anim *a, char *const *kf, char **all)
{
    size_t n = 0;
    for (size_t i = 0; i < a->nuser; i++)
        all[n++] = a->user[i];
    for (size_t i = 0; i < a->nkf; i++)
        all[n++] = kf[i];
    return n;
}

/* A run of the scene with the frame's keyframe overrides kf. */
static int load_run(const scene_anim *a, hy_scene_run *r, char *const *kf, hy_error *err)
{
    char *sets[SCENE_ANIM_MAX_SETS + 64];
    size_t n = all_sets(a, kf, sets);
    return a->text ? hy_scene_run_load_text(r, a->path, a->text, a->len, sets, n, &a->pol, err)
                   : hy_scene_run_load_policy(r, a->path, sets, n, &a->pol, err);
}

/* Frees what scene_anim_load_src copied (text, overrides). */
static void free_src(scene_anim *a)
{
    for (size_t i = 0; i < a->nuser; i++)
        free(a->user[i]);
    free(a->user);
    free(a->text);
}

/* Copies the text and the overrides into a. */
static int copy_src(scene_anim *a, const char *text, size_t len, char *const *sets, size_t nsets, hy_error *err)
{
    if (nsets > SCENE_ANIM_MAX_SETS)
        return hy_error_set(err, HY_EINVAL, "at most %d overrides of an animation", SCENE_ANIM_MAX_SETS);
    if (text && (a->text = malloc(len + 1))) {
        memcpy(a->text, text, len);
        a->text[len] = '\0';
        a->len = len;
    }
    if (nsets && (a->user = calloc(nsets, sizeof *a->user)))
        for (; a->nuser < nsets && (a->user[a->nuser] = strdup(sets[a->nuser])); a->nuser++)
            ;
    if ((text && !a->text) || a->nuser < nsets)
        return hy_error_set(err, HY_ENOMEM, "out of memory");
    return HY_OK;
}

int scene_anim_load_src(scene_anim *a, const char *path, const char *text, size_t len, char *const *sets,
                        size_t nsets, const hy_scene_policy *pol, hy_error *err)
{
    memset(a, 0, sizeof *a);
    a->path = path;
    a->pol = pol ? *pol : hy_scene_policy_default();
    int rc = copy_src(a, text, len, sets, nsets, err);
    if (!rc)
        rc = parse_scene(a, &a->scene, err);
    if (rc) {
        free_src(a);
        memset(a, 0, sizeof *a);
        return rc;
    }
    rc = hy_scene_decode_fill(a->scene, &a->doc, err);
    if (!rc)
        read_timing(a);
    a->nkf = a->doc.nkeyframe;
    a->kf = rc ? NULL : calloc(a->nkf + 1, sizeof *a->kf);
    if (!rc && !a->kf)
        rc = hy_error_set(err, HY_ENOMEM, "out of memory");
    for (size_t i = 0; !rc && i < a->nkf; i++) {
        a->kf[i].decl = &a->doc.keyframe[i];
        a->kf[i].label = a->doc.keyframe[i].h.name;
        rc = load_kf(&a->doc, &a->kf[i], a->doc.animation.easing, err);
    }
    for (size_t i = 0; !rc && i < a->nkf; i++)
        for (size_t j = 0; j < i; j++)
            if (!strcmp(a->kf[i].target, a->kf[j].target)) {
                rc = hy_decl_error(&a->kf[i].decl->h, KF_AT(key), err, HY_EINVAL,
                                   "keyframe '%s' animates %s, as keyframe '%s' does", a->kf[i].label, a->kf[i].target,
                                   a->kf[j].label);
                break;
            }
    if (!rc) {
        hy_scene_probe_name(a->scene, path, a->name, sizeof a->name);
        pthread_mutex_init(&a->mu, NULL);
        pthread_cond_init(&a->cv, NULL);
        return HY_OK;
    }
    hy_scene_doc_free(&a->doc);
    hy_scene_free(a->scene);
    free(a->kf);
    free_src(a);
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
    double work = 0, budget = hy_scene_policy_budget(&a->pol);
    int rc = parse_scene(a, &s, err);
    if (rc)
        return rc;
    char buf[4096], *sets[64];
    if (a->nkf > 64)
        rc = hy_decl_error(&a->kf[64].decl->h, HY_DECL_HEAD, err, HY_EINVAL, "at most 64 keyframe sections");
    for (long f = 0; !rc && f < nframes; f++) {
        double t = scene_anim_time(f, nframes, duration);
        if (scene_anim_sets(a, t, buf, sizeof buf, sets)) {
            rc = hy_error_set(err, HY_EINVAL, "%s: keyframe overrides too long", a->path);
            break;
        }
        for (size_t i = 0; i < a->nkf && !rc; i++) {
            hy_error e2 = {0};
            if (hy_scene_set(s, sets[i], &e2)) {
                const char *why = strstr(e2.msg, ": ");
                rc = hy_decl_error(&a->kf[i].decl->h, KF_AT(values), err, HY_EINVAL,
                                   "keyframe '%s': at frame %ld (t = %g s) %s is refused%s", a->kf[i].label, f, t, sets[i],
                                   why ? why : "");
            }
        }
        hy_scene_run r;
        hy_error e3 = {0};
        double w = 0;
        if (!rc && (a->nkf || f == 0) && load_run(a, &r, sets, &e3))
            rc = a->nkf ? hy_decl_error(&a->kf[0].decl->h, HY_DECL_HEAD, err, e3.code,
                                        "at frame %ld (t = %g s) the keyframe values give an invalid scene: %s", f, t, e3.msg)
                        : (*err = e3, e3.code);
        else if (!rc && (a->nkf || f == 0)) {
            rc = hy_scene_run_estimate(&r, &w, NULL, 0, err);
            hy_scene_run_free(&r);
            work += a->nkf ? w : w * (double)nframes; /* no keyframes: every frame is frame 0 */
        }
        if (!rc && work > budget) {
            char what[96];
            snprintf(what, sizeof what, "%ld frames%s", nframes, f + 1 < nframes && a->nkf ? ", counted so far" : "");
            rc = hy_scene_run_over_budget(&a->doc, work, budget, what, err); /* at the scene as written */
        }
    }
    hy_scene_free(s);
    return rc;
}

/* ---- the shared run cache ---- */

/* One distinct set of overrides: its run, computed by the first thread that
 * needs it (others wait), then lent to one drawing thread at a time under
 * `use`, and freed after its last frame. */
struct scene_entry {
    char *key;                /* the joined overrides */
    uint64_t hash;
    hy_scene_run run;
    int state;                /* 0 computing, 1 ready, 2 failed */
    hy_error err;             /* why it failed */
    long uses_left;           /* frames still to draw with it */
    pthread_mutex_t use;
};

static void entry_free(scene_entry *e)
{
    if (e->state == 1)
        hy_scene_run_free(&e->run);
    pthread_mutex_destroy(&e->use);
    free(e->key);
    free(e);
}

void scene_anim_free(scene_anim *a)
{
    if (!a->scene)
        return;
    for (size_t i = 0; i < a->nentries; i++)
        entry_free(a->entries[i]);
    if (a->last)
        entry_free(a->last);
    free(a->entries);
    free(a->frame_hash);
    free(a->kf);
    hy_scene_doc_free(&a->doc);
    hy_scene_free(a->scene);
    free_src(a);
    pthread_mutex_destroy(&a->mu);
    pthread_cond_destroy(&a->cv);
    memset(a, 0, sizeof *a);
}

#if HY_HAVE_GL

/* 64-bit FNV-1a of a frame's override text. */
static uint64_t fnv1a(const char *s)
{
    uint64_t h = 1469598103934665603ull;
    for (; *s; s++)
        h = (h ^ (unsigned char)*s) * 1099511628211ull;
    return h;
}

/* The joined overrides of frame `index` of nframes into key (size bytes). */
static int frame_key(const scene_anim *a, long index, long nframes, double duration, char *key, size_t size,
                     char **sets, char *buf, size_t bufsize)
{
    if (a->nkf > 64 || scene_anim_sets(a, scene_anim_time(index, nframes, duration), buf, bufsize, sets))
        return -1;
    size_t o = 0;
    key[0] = '\0';
    for (size_t i = 0; i < a->nkf && o < size; i++)
        o += (size_t)snprintf(key + o, size - o, "%s;", sets[i]);
    return o < size ? 0 : -1;
}

/* With a->mu held: the hash of every frame's key, made once. */
static int frame_hashes(scene_anim *a, long nframes, double duration)
{
    if (a->frame_hash)
        return a->nhash == nframes ? 0 : -1;
    a->frame_hash = malloc((size_t)nframes * sizeof *a->frame_hash);
    if (!a->frame_hash)
        return -1;
    char buf[4096], key[4096], *sets[64];
    for (long i = 0; i < nframes; i++) {
        if (frame_key(a, i, nframes, duration, key, sizeof key, sets, buf, sizeof buf))
            return free(a->frame_hash), a->frame_hash = NULL, -1;
        a->frame_hash[i] = fnv1a(key);
    }
    a->nhash = nframes;
    return 0;
}

/* With a->mu held: the entry of key, a new one (*fresh = 1) or NULL. */
static scene_entry *entry_get(scene_anim *a, const char *key, uint64_t h, int *fresh)
{
    *fresh = 0;
    for (size_t i = 0; i < a->nentries; i++)
        if (a->entries[i]->hash == h && !strcmp(a->entries[i]->key, key))
            return a->entries[i];
    scene_entry **grown = realloc(a->entries, (a->nentries + 1) * sizeof *grown);
    scene_entry *e = calloc(1, sizeof *e);
    if (grown)
        a->entries = grown;
    if (!grown || !e || !(e->key = strdup(key)))
        return free(e), NULL;
    e->hash = h;
    for (long i = 0; i < a->nhash; i++)
        e->uses_left += a->frame_hash[i] == h;
    pthread_mutex_init(&e->use, NULL);
    a->entries[a->nentries++] = e;
    *fresh = 1;
    return e;
}

/* With a->mu held: one frame of e drawn; frees e after its last frame. */
static void entry_done(scene_anim *a, scene_entry *e)
{
    if (--e->uses_left > 0)
        return;
    for (size_t i = 0; i < a->nentries; i++)
        if (a->entries[i] == e) {
            a->entries[i] = a->entries[--a->nentries];
            break;
        }
    entry_free(e);
}

static int draw_run(const hy_scene_run *r, const hy_anim_frame *f, hy_error *err)
{
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

/* One thread draws frames in any order (hystviz-animate --worker): the run
 * of the last frame is kept, reused by a frame of the same overrides and
 * replaced by the next one's, so memory holds one run whatever is asked. */
static int draw_single(scene_anim *a, const hy_anim_frame *f, const char *key, uint64_t h, char **sets,
                       hy_error *err)
{
    scene_entry *e = a->last;
    if (e && e->hash == h && !strcmp(e->key, key))
        a->hits++;
    else {
        if (e)
            entry_free(e);
        a->last = e = calloc(1, sizeof *e);
        if (!e || !(e->key = strdup(key))) {
            free(e);
            a->last = NULL;
            return hy_error_set(err, HY_ENOMEM, "out of memory");
        }
        e->hash = h;
        pthread_mutex_init(&e->use, NULL);
        int rc = load_run(a, &e->run, sets, &e->err);
        if (!rc && (rc = hy_scene_run_compute(&e->run, NULL, &e->err)))
            hy_scene_run_free(&e->run);
        e->state = rc ? 2 : 1;
        a->computes += !rc;
    }
    if (e->state == 2)
        return hy_error_set(err, e->err.code ? e->err.code : HY_EINVAL, "%s", e->err.msg);
    return draw_run(&e->run, f, err);
}

int scene_anim_draw(void *state, const hy_anim_frame *f, hy_error *err)
{
    scene_anim *a = state;
    char buf[4096], key[4096], *sets[64];
    if (frame_key(a, f->index, f->nframes, f->duration, key, sizeof key, sets, buf, sizeof buf))
        return hy_error_set(err, HY_EINVAL, "%s: too many keyframe overrides", a->path);
    uint64_t h = fnv1a(key);
    if (a->single)
        return draw_single(a, f, key, h, sets, err);
    int fresh = 0;
    pthread_mutex_lock(&a->mu);
    scene_entry *e = frame_hashes(a, f->nframes, f->duration) ? NULL : entry_get(a, key, h, &fresh);
    if (e && !fresh) {
        while (e->state == 0)
            pthread_cond_wait(&a->cv, &a->mu);
        a->hits++;
    }
    pthread_mutex_unlock(&a->mu);
    if (!e)
        return hy_error_set(err, HY_ENOMEM, "out of memory");
    if (fresh) {
        int rc = load_run(a, &e->run, sets, &e->err);
        if (!rc && (rc = hy_scene_run_compute(&e->run, NULL, &e->err)))
            hy_scene_run_free(&e->run);
        pthread_mutex_lock(&a->mu);
        e->state = rc ? 2 : 1;
        a->computes += !rc;
        pthread_cond_broadcast(&a->cv);
        pthread_mutex_unlock(&a->mu);
    }
    int rc;
    if (e->state == 2)
        rc = hy_error_set(err, e->err.code ? e->err.code : HY_EINVAL, "%s", e->err.msg);
    else {
        pthread_mutex_lock(&e->use);      /* one thread at a time draws from a run */
        rc = draw_run(&e->run, f, err);
        pthread_mutex_unlock(&e->use);
    }
    pthread_mutex_lock(&a->mu);
    entry_done(a, e);
    pthread_mutex_unlock(&a->mu);
    return rc;
}

#endif
