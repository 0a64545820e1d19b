/* SPDX-License-Identifier: MIT */
/* hy_sweep.c: the engine of `hystviz sweep` (hy_sweep.h): a parameter grid's
 * points computed by a pool of threads, each point exactly as `hystviz render
 * SCENE --set KEY=VALUE ...` computes it, its row (CSV) or record (.npy,
 * docs/STUDIES.md) written in point order, a table-only point of a Dahl/LuGre
 * scene with a bimodal input by the closed-form kernel (Theorem 2's steady
 * state and Theorem A(b)'s loops without the scene pipeline, the same
 * bytes); and hy_sweep_npy (hystviz.h), the same study's .npy in memory. */
#include "hy_sweep.h"

#include <errno.h>
#include <inttypes.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "hy_config.h"
#include "hy_cost.h"
#include "hy_dtoa.h"
#include "hystviz.h"
#include "scene_model.h"
#include "scene_run.h"


/* ---- names and rows --------------------------------------------------- */

/* The point's file base name: pINDEX then _KEY-VALUE per axis (the
 * study's name_parts), at most 200 bytes and size - 1 (the index alone
 * keeps names unique). */
static void point_name(const hy_sweep_study *s, size_t i, char *buf, size_t size)
{
    const hy_grid *g = &s->o->grid;
    size_t max = size - 1 < 200 ? size - 1 : 200, n = 0;
    char digits[24];
    size_t nd = 0;
    for (size_t v = i; nd < (size_t)s->index_width || v; v /= 10)
        digits[nd++] = (char)('0' + v % 10);
    if (n < max)
        buf[n++] = 'p';
    while (nd && n < max)
        buf[n++] = digits[--nd];
    for (size_t a = 0; a < g->naxes && n < max; a++) {
        const char *t = s->name_parts[a][hy_grid_coord(g, i, a)];
        size_t len = strlen(t);
        len = len < max - n ? len : max - n;
        memcpy(buf + n, t, len);
        n += len;
    }
    buf[n] = '\0';
}

/* "_KEY-VALUE" of each axis and value, as point names spell them: the short
 * key, then the value with characters other than [A-Za-z0-9.-] as '_'
 * (made once: a point's name is its coordinates' parts); -1 out of memory. */
static int make_name_parts(hy_sweep_study *s)
{
    const hy_grid *g = &s->o->grid;
    s->name_parts = calloc(g->naxes ? g->naxes : 1, sizeof *s->name_parts);
    for (size_t a = 0; s->name_parts && a < g->naxes; a++) {
        if (!(s->name_parts[a] = calloc(g->axes[a].nvalues, sizeof **s->name_parts)))
            return -1;
        for (size_t v = 0; v < g->axes[a].nvalues; v++) {
            const char *val = g->axes[a].values[v];
            size_t nk = strlen(s->short_keys[a]), nv = strlen(val);
            char *t = malloc(nk + nv + 3);
            if (!(s->name_parts[a][v] = t))
                return -1;
            snprintf(t, nk + nv + 3, "_%s-%s", s->short_keys[a], val);
            for (char *c = t + 1; *c; c++)
                if (!((*c >= 'a' && *c <= 'z') || (*c >= 'A' && *c <= 'Z') || (*c >= '0' && *c <= '9') || *c == '.' ||
                      *c == '-'))
                    *c = '_';
        }
    }
    return s->name_parts ? 0 : -1;
}

/* The short key of each axis: the part after the last '.', or the whole key
 * ('.' as '-') when two axes share it. */
static int make_short_keys(hy_sweep_study *s)
{
    const hy_grid *g = &s->o->grid;
    s->short_keys = calloc(g->naxes ? g->naxes : 1, sizeof *s->short_keys);
    if (!s->short_keys)
        return -1;
    for (size_t a = 0; a < g->naxes; a++) {
        const char *last = strrchr(g->axes[a].key, '.') + 1;
        int shared = 0;
        for (size_t b = 0; b < g->naxes; b++)
            shared |= b != a && !strcmp(strrchr(g->axes[b].key, '.') + 1, last);
        const char *src = shared ? g->axes[a].key : last;
        size_t n = strlen(src);
        if (!(s->short_keys[a] = malloc(n + 1)))
            return -1;
        for (size_t c = 0; c <= n; c++)
            s->short_keys[a][c] = src[c] == '.' ? '-' : src[c];
    }
    return 0;
}

/* A row being formatted: bytes, grown as needed (kept between points, so a
 * point allocates nothing once the buffer has grown); err once out of memory. */
typedef struct rowbuf {
    char *b;
    size_t len, cap;
    int err;
} rowbuf;

/* Room for n more bytes at b + len; NULL (err set) when out of memory. */
static char *rb_room(rowbuf *r, size_t n)
{
    if (r->len + n > r->cap && !r->err) {
        size_t cap = 2 * (r->len + n) + 256;
        char *b = realloc(r->b, cap);
        if (b) {
            r->b = b;
            r->cap = cap;
        } else
            r->err = 1;
    }
    return r->err ? NULL : r->b + r->len;
}

static void rb_add(rowbuf *r, const char *t, size_t n)
{
    char *p = rb_room(r, n);
    if (p) {
        memcpy(p, t, n);
        r->len += n;
    }
}

/* Appends bytes from .. to - 1 of the row again. */
static void rb_again(rowbuf *r, size_t from, size_t to)
{
    char *p = rb_room(r, to - from);
    if (p) {
        memcpy(p, r->b + from, to - from);
        r->len += to - from;
    }
}

static void rb_chr(rowbuf *r, char c)
{
    rb_add(r, &c, 1);
}

static void rb_str(rowbuf *r, const char *t)
{
    rb_add(r, t, strlen(t));
}

static void rb_size(rowbuf *r, size_t v)
{
    char d[24], *w = d + sizeof d;
    do
        *--w = (char)('0' + v % 10);
    while (v /= 10);
    rb_add(r, w, (size_t)(d + sizeof d - w));
}

/* v as the shortest decimal that reads back to it (hy_dtoa: %.17g's layout) */
static void rb_double(rowbuf *r, double v)
{
    char *p = rb_room(r, HY_DTOA_MAX);
    if (p)
        r->len += hy_dtoa(v, p);
}

/* A CSV field: as is, or in double quotes (quotes doubled) if it holds a
 * comma, quote or line break. */
static void csv_field(rowbuf *f, const char *t)
{
    if (!strpbrk(t, ",\"\n\r")) {
        rb_str(f, t);
        return;
    }
    rb_chr(f, '"');
    for (; *t; t++) {
        if (*t == '"')
            rb_chr(f, '"');
        rb_chr(f, *t);
    }
    rb_chr(f, '"');
}

/* ",v", or "," for NaN (not computed) */
static void csv_num(rowbuf *f, double v)
{
    rb_chr(f, ',');
    if (!isnan(v))
        rb_double(f, v);
}

/* The result columns after the grid's (and compute_s): their names. */
#define RESULT_COLUMNS "ysteady_min,ysteady_max,nminor,major_area,minor1_area,minor_areas,energy"

void hy_sweep_write_header(const hy_sweep_study *s, FILE *f)
{
    const hy_grid *g = &s->o->grid;
    fputs("index,status,name", f);
    for (size_t a = 0; a < g->naxes; a++) {
        rowbuf k = {0};
        csv_field(&k, g->axes[a].key);
        fprintf(f, ",%.*s", k.err ? 0 : (int)k.len, k.b ? k.b : "");
        free(k.b);
    }
    if (s->o->times)
        fputs(",compute_s", f);
    fputs("," RESULT_COLUMNS, f);
    fprintf(f, ",err_measured_1_in_%ld", s->o->verify_every);
    for (int dist = 0; dist < 2; dist++)
        for (size_t k = 0; k < s->nseries; k++)
            if (!dist || s->series_dist[k]) {
                rowbuf col = {0};
                char name[300];
                snprintf(name, sizeof name, "%s.%s", s->series[k], dist ? "dist" : "err");
                csv_field(&col, name);
                fprintf(f, ",%.*s", col.err ? 0 : (int)col.len, col.b ? col.b : "");
                free(col.b);
            }
    fputs(",message\n", f);
}

/* Series k of the study in run r (NULL if r has none of that name): r's
 * series are the scene's, in the same order, so index k is tried first. */
static const hy_run_series *find_series(const hy_scene_run *r, const hy_sweep_study *s, size_t k)
{
    const char *name = s->series[k];
    if (r && k < r->nseries && !strcmp(r->series[k].name, name))
        return &r->series[k];
    for (size_t j = 0; r && j < r->nseries; j++)
        if (!strcmp(r->series[j].name, name))
            return &r->series[j];
    return NULL;
}

/* The scalars of a row: NaN where not computed. */
typedef struct row_vals {
    double ymin, ymax, nminor, major, minor1, energy, measured;
    const hy_loops *L;
} row_vals;

static void row_values(const hy_sweep_study *s, size_t i, const hy_scene_run *r, int ok, row_vals *v)
{
    v->ymin = v->ymax = NAN;
    if (ok && r->have_steady)
        for (size_t k = 0; k <= r->input.nruns; k++) {
            double y = r->steady.y_run[k];
            v->ymin = k && v->ymin <= y ? v->ymin : y;
            v->ymax = k && v->ymax >= y ? v->ymax : y;
        }
    const hy_loops *L = ok && r->have_loops ? &r->loops : NULL;
    v->L = L;
    v->nminor = L ? (double)L->nminor : NAN;
    v->major = L ? L->major.area : NAN;
    v->minor1 = L && L->nminor ? L->minor[0].area : NAN;
    v->energy = L ? L->area_period : NAN;
    v->measured = ok ? (i % (size_t)s->o->verify_every ? 0 : 1) : NAN;
}

/* The row of point i: r is the computed run (NULL if loading failed),
 * status "ok", "invalid" or "failed", msg the reason or "". */
static void write_row(const hy_sweep_study *s, rowbuf *f, size_t i, const char *name, const hy_scene_run *r, const char *status,
                      const char *msg)
{
    const hy_grid *g = &s->o->grid;
    rb_size(f, i);
    rb_chr(f, ',');
    rb_str(f, status);
    rb_chr(f, ',');
    rb_str(f, name);
    for (size_t a = 0; a < g->naxes; a++) {
        rb_chr(f, ',');
        csv_field(f, hy_grid_value(g, i, a));
    }
    int ok = status[0] == 'o';
    if (s->o->times)
        csv_num(f, ok ? r->seconds_compute : NAN);
    row_vals v;
    row_values(s, i, r, ok, &v);
    csv_num(f, v.ymin);
    csv_num(f, v.ymax);
    rb_chr(f, ',');
    if (v.L)
        rb_size(f, v.L->nminor);
    csv_num(f, v.major);
    size_t m0 = f->len + 1; /* minor1_area's digits: minor_areas starts with them */
    csv_num(f, v.minor1);
    size_t m1 = f->len;
    rb_chr(f, ',');
    for (size_t k = 0; v.L && k < v.L->nminor; k++) {
        if (k)
            rb_chr(f, ';');
        if (k == 0 && !isnan(v.minor1)) /* the same double, L->minor[0].area: its digits again */
            rb_again(f, m0, m1);
        else
            rb_double(f, v.L->minor[k].area);
    }
    csv_num(f, v.energy);
    rb_chr(f, ',');
    if (ok)
        rb_chr(f, v.measured ? '1' : '0');
    for (size_t k = 0; k < s->nseries; k++) {
        const hy_run_series *se = ok ? find_series(r, s, k) : NULL;
        csv_num(f, se && se->err_ref ? se->err : NAN);
    }
    for (size_t k = 0; k < s->nseries; k++)
        if (s->series_dist[k]) {
            const hy_run_series *se = ok ? find_series(r, s, k) : NULL;
            csv_num(f, se ? se->dist : NAN);
        }
    rb_chr(f, ',');
    csv_field(f, msg);
    rb_chr(f, '\n');
}

/* ---- the .npy table ------------------------------------------------- */

/* A structured array, one field per column (docs/STUDIES.md): index <i8,
 * status |i1 (0 ok, 1 invalid, 2 failed), name |S<longest name>, each grid
 * axis <f8 when all its values are numbers, else |S<longest value>; every
 * number <f8 (NaN where the CSV is empty; nminor and err_measured too);
 * minor_areas <f8 (NPY_MINOR,): the first NPY_MINOR minor loops' areas,
 * NaN after the last; message |S<NPY_MESSAGE> (cut at a UTF-8 character). */
#define NPY_MINOR 8
#define NPY_MESSAGE 256

static void put_u64(rowbuf *r, uint64_t v)
{
    char *p = rb_room(r, 8);
    for (int k = 0; p && k < 8; k++)
        p[k] = (char)(v >> (8 * k) & 0xff);
    if (p)
        r->len += 8;
}

static void put_f8(rowbuf *r, double v)
{
    uint64_t b;
    memcpy(&b, &v, sizeof b);
    put_u64(r, b);
}

/* t in a field of w bytes, NUL-padded; cut at a UTF-8 character boundary. */
static void put_text(rowbuf *r, const char *t, size_t w)
{
    size_t n = strlen(t);
    if (n > w) {
        n = w;
        while (n > 0 && ((unsigned char)t[n] & 0xc0) == 0x80)
            n--;
    }
    char *p = rb_room(r, w);
    if (p) {
        memcpy(p, t, n);
        memset(p + n, 0, w - n);
        r->len += w;
    }
}

/* A field name as a Python string literal. */
static void descr_field(rowbuf *d, const char *name, const char *type)
{
    rb_str(d, d->len > 1 ? ", ('" : "('");
    for (const char *c = name; *c; c++) {
        if (*c == '\'' || *c == '\\')
            rb_chr(d, '\\');
        rb_chr(d, *c);
    }
    rb_str(d, "', ");
    rb_str(d, type);
    rb_chr(d, ')');
}

/* The record layout of the study: fills descr, name_w, axis_w, axis_num;
 * -1 when out of memory. */
int hy_sweep_npy_layout(hy_sweep_study *s)
{
    const hy_grid *g = &s->o->grid;
    rowbuf d = {0};
    char ty[64];
    rb_chr(&d, '[');
    descr_field(&d, "index", "'<i8'");
    descr_field(&d, "status", "'|i1'");
    s->name_w = 1 + (size_t)s->index_width;
    s->axis_w = calloc(g->naxes + 1, sizeof *s->axis_w);
    s->axis_num = calloc(g->naxes + 1, sizeof *s->axis_num);
    if (!s->axis_w || !s->axis_num)
        return -1;
    for (size_t a = 0; a < g->naxes; a++) {
        size_t longest = 1;
        int numeric = 1;
        for (size_t v = 0; v < g->axes[a].nvalues; v++) {
            const char *t = g->axes[a].values[v];
            char *end;
            size_t n = strlen(t);
            longest = n > longest ? n : longest;
            strtod(t, &end);
            numeric &= end != t && !*end;
        }
        s->name_w += 2 + strlen(s->short_keys[a]) + longest;
        if (numeric) {
            if (!(s->axis_num[a] = malloc(g->axes[a].nvalues * sizeof **s->axis_num)))
                return -1;
            for (size_t v = 0; v < g->axes[a].nvalues; v++)
                s->axis_num[a][v] = strtod(g->axes[a].values[v], NULL);
        } else
            s->axis_w[a] = longest;
    }
    if (s->name_w > 200)
        s->name_w = 200;
    snprintf(ty, sizeof ty, "'|S%zu'", s->name_w);
    descr_field(&d, "name", ty);
    for (size_t a = 0; a < g->naxes; a++) {
        snprintf(ty, sizeof ty, "'|S%zu'", s->axis_w[a]);
        descr_field(&d, g->axes[a].key, s->axis_w[a] ? ty : "'<f8'");
    }
    if (s->o->times)
        descr_field(&d, "compute_s", "'<f8'");
    static const char *const res[] = {"ysteady_min", "ysteady_max", "nminor", "major_area", "minor1_area"};
    for (size_t k = 0; k < sizeof res / sizeof *res; k++)
        descr_field(&d, res[k], "'<f8'");
    snprintf(ty, sizeof ty, "'<f8', (%d,)", NPY_MINOR);
    descr_field(&d, "minor_areas", ty);
    descr_field(&d, "energy", "'<f8'");
    snprintf(ty, sizeof ty, "err_measured_1_in_%ld", s->o->verify_every);
    descr_field(&d, ty, "'<f8'");
    for (int dist = 0; dist < 2; dist++)
        for (size_t k = 0; k < s->nseries; k++)
            if (!dist || s->series_dist[k]) {
                char col[300];
                snprintf(col, sizeof col, "%s.%s", s->series[k], dist ? "dist" : "err");
                descr_field(&d, col, "'<f8'");
            }
    snprintf(ty, sizeof ty, "'|S%d'", NPY_MESSAGE);
    descr_field(&d, "message", ty);
    rb_str(&d, "]");
    rb_chr(&d, '\0');
    s->descr = d.b;
    return d.err ? -1 : 0;
}

int hy_sweep_prepare(hy_sweep_study *s, hy_error *err)
{
    const hy_sweep_opts *o = s->o;
    size_t npoints = hy_grid_points(&o->grid);
    if (make_short_keys(s) || make_name_parts(s))
        return hy_error_set(err, HY_ENOMEM, "out of memory"), -1;
    char digits[32];
    s->index_width = snprintf(digits, sizeof digits, "%zu", npoints > 1 ? npoints - 1 : 0);
    s->nmine = o->sharded ? hy_shard_count(npoints, o->shard_k, o->shard_n) : npoints;
    if (o->npy && hy_sweep_npy_layout(s))
        return hy_error_set(err, HY_ENOMEM, "out of memory"), -1;
    return 0;
}


/* The record of point i (as write_row's row). */
static void write_record(const hy_sweep_study *s, rowbuf *f, size_t i, const char *name, const hy_scene_run *r, int kind,
                         const char *msg)
{
    const hy_grid *g = &s->o->grid;
    put_u64(f, (uint64_t)i);
    char st = (char)kind;
    rb_add(f, &st, 1);
    put_text(f, name, s->name_w);
    for (size_t a = 0; a < g->naxes; a++) {
        size_t c = hy_grid_coord(g, i, a);
        if (s->axis_w[a])
            put_text(f, g->axes[a].values[c], s->axis_w[a]);
        else
            put_f8(f, s->axis_num[a][c]);
    }
    int ok = kind == 0;
    if (s->o->times)
        put_f8(f, ok ? r->seconds_compute : NAN);
    row_vals v;
    row_values(s, i, r, ok, &v);
    put_f8(f, v.ymin);
    put_f8(f, v.ymax);
    put_f8(f, v.nminor);
    put_f8(f, v.major);
    put_f8(f, v.minor1);
    for (size_t k = 0; k < NPY_MINOR; k++)
        put_f8(f, v.L && k < v.L->nminor ? v.L->minor[k].area : NAN);
    put_f8(f, v.energy);
    put_f8(f, v.measured);
    for (size_t k = 0; k < s->nseries; k++) {
        const hy_run_series *se = ok ? find_series(r, s, k) : NULL;
        put_f8(f, se && se->err_ref ? se->err : NAN);
    }
    for (size_t k = 0; k < s->nseries; k++)
        if (s->series_dist[k]) {
            const hy_run_series *se = ok ? find_series(r, s, k) : NULL;
            put_f8(f, se ? se->dist : NAN);
        }
    put_text(f, msg, NPY_MESSAGE);
}

/* ---- one point -------------------------------------------------------- */

typedef struct point_buf {
    char **sets;      /* KEY=VALUE per axis, then output.name */
    char *text;       /* the KEY=VALUE texts */
    size_t text_size;
    FILE *log;        /* /dev/null: given to compute at the points whose errors
                       * are measured, so that it measures every error it can
                       * (a GSL solve against the exact solution) */
    hy_scene *scene;  /* the worker's scene, parsed once with the user's --set
                       * applied and marked: each point restores it to that
                       * and applies its own overrides (hy_scene_mark) */
    int scene_rc;     /* parsing it failed: every point reports scene_err */
    hy_scene_doc base; /* the scene decoded once, at its mark: a point decodes
                        * again only the sections its overrides change */
    int have_base;
    hy_error scene_err;
    int typed;         /* every axis is a typed write into work (typed_axes) */
    struct typed_axis *ta;
    hy_scene_doc work; /* base with the typed axes' fields of the last point */
    int validated;     /* a point loaded from work: its placeholders were checked */
    struct closed_kernel *ck; /* the closed-form kernel, where it applies (closed_setup) */
} point_buf;

/* The worker's scene: parsed under the policy, the user's --set applied,
 * marked.  On failure pb->scene_rc and scene_err say why. */
static void worker_scene(const hy_sweep_opts *o, point_buf *pb)
{
    pb->scene = NULL;
    pb->scene_err = (hy_error){0};
    pb->scene_rc = hy_scene_parse_file_policy(o->scene, &o->pol, &pb->scene, &pb->scene_err);
    for (size_t k = 0; !pb->scene_rc && k < o->nsets; k++)
        pb->scene_rc = hy_scene_set(pb->scene, o->sets[k], &pb->scene_err);
    if (!pb->scene_rc)
        pb->scene_rc = hy_scene_mark(pb->scene);
    pb->have_base = 0;
    if (!pb->scene_rc) { /* where it does not decode, each point decodes (and reports) on its own */
        hy_error e = {0};
        pb->have_base = !hy_scene_decode(pb->scene, &pb->base, &e);
        if (!pb->have_base)
            hy_scene_doc_free(&pb->base);
    }
}

/* ---- grid values as typed writes (issue 37) ------------------------- */

/* An axis whose key is a NUMBER or INTEGER of [model], [input] or [compute]:
 * a point writes its value into the field the decoder fills, and the
 * override's note (where written), into a copy of the decoded scene, instead
 * of setting the text and decoding the section again. */
typedef struct typed_axis {
    int sec;              /* 0 model, 1 input, 2 compute */
    size_t field, key;    /* the field's offset in its section, the key's index */
    int is_long;          /* INTEGER: long, else double */
    hy_decl_field meta;   /* what decode notes for an override of the key */
    double *num;          /* the axis' values */
    char **label;         /* ... and each one's "--set KEY=VALUE", where the
                           * decoder's note of an override points (messages) */
} typed_axis;

static char *sec_of(hy_scene_doc *d, int sec, size_t *size)
{
    *size = sec == 0 ? sizeof d->model : sec == 1 ? sizeof d->input : sizeof d->compute;
    return sec == 0 ? (char *)&d->model : sec == 1 ? (char *)&d->input : (char *)&d->compute;
}

static void typed_write(hy_scene_doc *d, const typed_axis *t, size_t v)
{
    size_t size;
    char *b = sec_of(d, t->sec, &size);
    if (t->is_long) {
        long l = (long)t->num[v];
        memcpy(b + t->field, &l, sizeof l);
    } else
        memcpy(b + t->field, &t->num[v], sizeof(double));
    hy_decl_field *f = &((hy_decl_head *)(void *)b)->at[t->key];
    *f = t->meta;
    f->loc.file = t->label[v];
}

/* Axis a as a typed write, checked: its values are plain numbers, and at
 * its first, middle and last value the write gives the section the generic
 * override (hy_scene_set, decode) gives, byte for byte.  0 if it is not one. */
static int typed_axis_make(const hy_sweep_opts *o, point_buf *pb, size_t a, typed_axis *t)
{
    const hy_grid_axis *ax = &o->grid.axes[a];
    char *sec = NULL, *name = NULL, *key = NULL, buf[4400];
    const char *val;
    snprintf(buf, sizeof buf, "%s=0", ax->key);
    int ok = !hy_scene_set_split(buf, &sec, &name, &key, &val, NULL) && !name && sec && key;
    t->sec = !ok ? -1 : !strcmp(sec, "model") ? 0 : !strcmp(sec, "input") ? 1 : !strcmp(sec, "compute") ? 2 : -1;
    ok = ok && t->sec >= 0;
    const hy_scene_section_spec *spec = ok ? &hy_scene_schema(NULL)[hy_scene_schema_section(sec)] : NULL;
    size_t k = 0;
    while (spec && k < spec->nkeys && strcmp(spec->keys[k].name, key))
        k++;
    ok = ok && k < spec->nkeys && k < HY_SCENE_KEYS_MAX && spec->keys[k].ctype &&
         (spec->keys[k].kind == HY_KIND_NUMBER || spec->keys[k].kind == HY_KIND_INTEGER) && strcmp(key, "kind");
    free(sec);
    free(name);
    free(key);
    if (!ok || !(t->num = malloc(ax->nvalues * sizeof *t->num)) || !(t->label = calloc(ax->nvalues, sizeof *t->label)))
        return 0;
    t->key = k;
    t->field = spec->keys[k].field;
    t->is_long = spec->keys[k].kind == HY_KIND_INTEGER;
    for (size_t v = 0; v < ax->nvalues && ok; v++) {
        const char *x = ax->values[v];
        char *end;
        ok = strspn(x, "0123456789.eE+-") == strlen(x);
        t->num[v] = t->is_long ? (double)strtol(x, &end, 10) : strtod(x, &end);
        ok = ok && end != x && !*end && (!t->is_long || fabs(t->num[v]) < 0x1p53);
        size_t n = strlen(ax->key) + strlen(x) + 8;
        if (ok && (t->label[v] = malloc(n)))
            snprintf(t->label[v], n, "--set %s=%s", ax->key, x);
        ok = ok && t->label[v];
    }
    size_t checks[3] = {0, ax->nvalues / 2, ax->nvalues - 1};
    for (int c = 0; c < 3 && ok; c++) {
        hy_error e = {0};
        hy_scene_doc d;
        hy_scene_restore(pb->scene);
        snprintf(buf, sizeof buf, "%s=%s", ax->key, ax->values[checks[c]]);
        if (hy_scene_set(pb->scene, buf, &e) || hy_scene_decode_marked(pb->scene, &pb->base, &d, &e)) {
            ok = 0;
            break;
        }
        size_t size;
        char *want = sec_of(&d, t->sec, &size);
        hy_decl_field *wf = &((hy_decl_head *)(void *)want)->at[k];
        if (c == 0)
            t->meta = *wf;
        if (wf->loc.file && !strcmp(wf->loc.file, t->label[checks[c]]))
            wf->loc.file = t->label[checks[c]]; /* the same text: compared as such */
        hy_scene_doc mine = pb->base;
        typed_write(&mine, t, checks[c]);
        ok = !memcmp(sec_of(&mine, t->sec, &size), want, size);
        hy_scene_doc_free(&d);
    }
    hy_scene_restore(pb->scene);
    return ok;
}

/* Whether every axis of the grid can be a typed write (table-only sweeps). */
static void typed_setup(const hy_sweep_opts *o, point_buf *pb)
{
    pb->typed = 0;
    pb->validated = 0;
    pb->ta = NULL;
    if (o->figures || !pb->have_base || !o->grid.naxes || !(pb->ta = calloc(o->grid.naxes, sizeof *pb->ta)))
        return;
    int all = 1;
    for (size_t a = 0; a < o->grid.naxes && all; a++)
        all = typed_axis_make(o, pb, a, &pb->ta[a]);
    pb->typed = all;
    pb->work = pb->base;
    for (size_t a = 0; a < o->grid.naxes && all; a++)
        typed_write(&pb->work, &pb->ta[a], 0);
}

static void typed_free(const hy_sweep_opts *o, point_buf *pb)
{
    for (size_t a = 0; pb->ta && a < o->grid.naxes; a++) {
        for (size_t v = 0; pb->ta[a].label && v < o->grid.axes[a].nvalues; v++)
            free(pb->ta[a].label[v]);
        free(pb->ta[a].label);
        free(pb->ta[a].num);
    }
    free(pb->ta);
}

/* ---- the closed-form kernel (issue 37) ------------------------------- */

/* A table-only point of a Dahl/LuGre scene with a bimodal input whose series
 * need only the steady state and its loops (Theorem 2, Theorem A(b); no γ
 * solve, no measured data) is computed without the scene pipeline: the
 * grid's values are written into one decoded scene (typed_write), and the
 * very functions the pipeline calls (hy_scene_run_build_model,
 * hy_input_bimodal_buf, hy_steady_init_buf, hy_loops_find_buf, the plan's
 * checks) run on storage kept between points: no allocation, no scene copy,
 * no text per point, the same doubles.  Points in the error sample, and any
 * point one of those functions refuses, go the generic way (which measures,
 * or words the refusal).  HYSTVIZ_SWEEP_GENERIC=1 turns the kernel off
 * (tests/cli/test_sweep_kernel.sh compares the two byte for byte). */
typedef struct closed_kernel {
    hy_scene_run r;        /* doc: the decoded scene with the point's values; model,
                            * input, steady, loops: the point's; nothing else set */
    hy_piece pieces[4];
    hy_run runs[4];
    double y_run[5];
    void *work;            /* hy_loops_work_size(4) bytes */
    int shape;             /* [input] shape, HY_SHAPE_* */
    double pixel_work;     /* the PNG raster's work: [figure] and the formats
                            * only, which no typed axis writes */
    int need_steady, need_loops, want_minor, want_major;
} closed_kernel;

/* Whether series data d is one the kernel computes nothing for (its table
 * columns come from the steady state and loops alone). */
static int closed_data(int d)
{
    return d == HY_DATA_INPUT || d == HY_DATA_PSI || d == HY_DATA_G || d == HY_DATA_YSTAR || d == HY_DATA_YSTEADY ||
           d == HY_DATA_YK || d == HY_DATA_MINOR || d == HY_DATA_MAJOR;
}

/* The kernel for this worker, or NULL where the scene is not one it computes
 * (decided once, on the scene's point-0 run loaded the generic way). */
static closed_kernel *closed_setup(const hy_sweep_opts *o, point_buf *pb)
{
    const char *off = getenv("HYSTVIZ_SWEEP_GENERIC");
    if (!pb->typed || o->times || (off && *off && strcmp(off, "0")))
        return NULL;
    hy_scene_run r0;
    hy_error e = {0};
    if (hy_scene_run_load_doc(&r0, pb->scene, &pb->work, 0, o->scene, hy_scene_policy_budget(&o->pol), &e))
        return NULL;
    int ok = r0.mtype->compute == hy_scene_friction_compute && r0.figure_kind != FIG_FORC && !r0.npanels &&
             !r0.ndata && !r0.drive && r0.doc.input.kind == HY_INPUT_BIMODAL;
    for (size_t k = 0; ok && k < r0.doc.nseries; k++)
        ok = closed_data(r0.doc.series[k].data);
    closed_kernel *ck = ok ? calloc(1, sizeof *ck) : NULL;
    if (ck && !(ck->work = malloc(hy_loops_work_size(4)))) {
        free(ck);
        ck = NULL;
    }
    if (ck) {
        ck->r.doc = pb->work; /* its arrays are the worker's base doc's: never freed through r */
        ck->r.path = o->scene;
        ck->r.scene = pb->scene;
        ck->r.budget = hy_scene_policy_budget(&o->pol);
        ck->r.mtype = r0.mtype;
        ck->r.figure_kind = r0.figure_kind;
        ck->r.numbers_only = ck->r.no_verify = 1;
        ck->shape = hy_scene_input_shape(&r0.doc.input);
        ck->pixel_work = hy_cost(NULL, HY_COST_PIXEL, hy_scene_run_png_pixels(&ck->r));
        hy_scene_friction_needs(&r0.doc, &ck->need_steady, &ck->need_loops);
        for (size_t k = 0; k < r0.doc.nseries; k++) {
            ck->want_minor |= r0.doc.series[k].data == HY_DATA_MINOR;
            ck->want_major |= r0.doc.series[k].data == HY_DATA_MAJOR;
        }
    }
    hy_scene_run_free(&r0);
    return ck;
}

static void closed_free(closed_kernel *ck)
{
    if (ck)
        free(ck->work);
    free(ck);
}

/* Point i by the kernel into ck->r: 0, or -1 where the generic way must
 * compute it (the error sample, a value some step refuses). */
static int closed_point(const hy_sweep_study *s, point_buf *pb, size_t i)
{
    const hy_sweep_opts *o = s->o;
    closed_kernel *ck = pb->ck;
    hy_scene_run *r = &ck->r;
    hy_error e;
    if (i % (size_t)o->verify_every == 0)
        return -1;
    for (size_t a = 0; a < o->grid.naxes; a++)
        typed_write(&r->doc, &pb->ta[a], hy_grid_coord(&o->grid, i, a));
    const hy_decl_input *d = &r->doc.input;
    r->have_steady = r->have_loops = 0;
    if (hy_scene_run_build_model(r, &e) ||
        hy_input_bimodal_buf(&r->input, ck->pieces, ck->runs, d->umin1, d->umin2, d->umax1, d->umax2,
                             hy_scene_bimodal_t(d), ck->shape, &e))
        return -1;
    double work, t0, t1, a[64], b[64];
    size_t npts, per;
    long cycles;
    if (hy_scene_run_estimate_px(r, ck->pixel_work, &work, NULL, 0, &e) || work > (r->budget > 0 ? r->budget : HY_SCENE_WORK_DEFAULT) ||
        hy_scene_run_grid(r, &t0, &t1, &npts, &per, &cycles, &e))
        return -1;
    if (ck->need_steady && hy_steady_init_buf(&r->steady, &r->model, &r->input, ck->y_run, &e))
        return -1;
    r->have_steady = ck->need_steady;
    if (ck->need_loops && hy_loops_find_buf(&r->steady, &r->loops, ck->work, &e))
        return -1;
    r->have_loops = ck->need_loops;
    if ((ck->want_minor && hy_scene_loop_intervals(r, 0, a, b, 64) < 0) ||
        (ck->want_major && hy_scene_loop_intervals(r, 1, a, b, 64) < 0))
        return -1;
    return 0;
}

/* Loads, computes and writes point i; appends its row to out and counts
 * its status into *kind (0 ok, 1 invalid, 2 failed). */
static void run_point(const hy_sweep_study *s, point_buf *pb, size_t i, int *kind, int *closed, rowbuf *out)
{
    const hy_sweep_opts *o = s->o;
    const hy_grid *g = &o->grid;
    char name[256];
    point_name(s, i, name, sizeof name);
    *closed = 0;
    if (pb->ck && !pb->scene_rc && !closed_point(s, pb, i)) {
        *kind = 0;
        *closed = 1;
        if (o->npy)
            write_record(s, out, i, name, &pb->ck->r, 0, "");
        else
            write_row(s, out, i, name, &pb->ck->r, "ok", "");
        return;
    }
    size_t used = 0, nsets = 0;
    for (size_t a = 0; a < g->naxes && !pb->typed; a++) {
        pb->sets[nsets++] = pb->text + used;
        used += (size_t)snprintf(pb->text + used, pb->text_size - used, "%s=%s", g->axes[a].key, hy_grid_value(g, i, a)) + 1;
    }
    if (o->figures) {
        pb->sets[nsets++] = pb->text + used;
        snprintf(pb->text + used, pb->text_size - used, "output.name=\"%s\"", name);
    }
    hy_scene_run r;
    hy_error err = pb->scene_err;
    int loaded = 0, rc = pb->scene_rc, measured = i % (size_t)o->verify_every == 0;
    if (!rc && pb->typed) { /* the decoded scene with this point's values written in */
        for (size_t a = 0; a < g->naxes; a++)
            typed_write(&pb->work, &pb->ta[a], hy_grid_coord(g, i, a));
        rc = hy_scene_run_load_doc(&r, pb->scene, &pb->work, pb->validated, o->scene, hy_scene_policy_budget(&o->pol),
                                   &err);
        pb->validated |= !rc; /* only grid values change from here on: placeholders stay valid */
    } else if (!rc) { /* the parsed scene as the file + the user's --set, then this point's overrides */
        hy_scene_restore(pb->scene);
        for (size_t k = 0; k < nsets && !rc; k++)
            rc = hy_scene_set(pb->scene, pb->sets[k], &err);
    }
    if (!rc && !pb->typed)
        rc = hy_scene_run_load_marked(&r, pb->scene, pb->have_base ? &pb->base : NULL, o->scene,
                                      hy_scene_policy_budget(&o->pol), &err);
    if (!rc) {
        loaded = 1;
        r.numbers_only = !o->figures;
        r.no_verify = !measured;
        if (o->figures) /* formats and raster limits, before computing */
            rc = hy_scene_run_check_output(&r, o->formats, &err);
        if (!rc)
            rc = hy_scene_run_compute(&r, measured ? pb->log : NULL, &err);
    }
    if (!rc && o->figures)
        rc = hy_scene_run_write(&r, o->out, o->formats, NULL, 0, &err);
    *kind = !rc ? 0 : err.code == HY_EINVAL ? 1 : 2;
    if (o->npy)
        write_record(s, out, i, name, loaded && !rc ? &r : NULL, *kind, rc ? err.msg : "");
    else
        write_row(s, out, i, name, loaded && !rc ? &r : NULL, *kind == 0 ? "ok" : *kind == 1 ? "invalid" : "failed",
                  rc ? err.msg : "");
    if (loaded)
        hy_scene_run_free(&r);
    if (rc && !o->quiet) {
        static pthread_mutex_t print_mu = PTHREAD_MUTEX_INITIALIZER;
        static size_t printed;
        pthread_mutex_lock(&print_mu);
        if (printed++ < 10)
            fprintf(stderr, "hystviz sweep: point %zu (%s): %s%s\n", i, name, err.msg,
                    printed == 10 ? " (further failures: see the table's message column)" : "");
        pthread_mutex_unlock(&print_mu);
    }
}

/* ---- the pool --------------------------------------------------------- */

static void *worker(void *arg)
{
    hy_sweep_study *s = arg;
    const hy_sweep_opts *o = s->o;
    point_buf pb;
    pb.sets = calloc(o->grid.naxes + 1, sizeof *pb.sets);
    pb.text_size = 512;
    for (size_t a = 0; a < o->grid.naxes; a++)
        pb.text_size += strlen(o->grid.axes[a].key) + 64;
    for (size_t a = 0; a < o->grid.naxes; a++) {
        size_t longest = 0;
        for (size_t v = 0; v < o->grid.axes[a].nvalues; v++) {
            size_t n = strlen(o->grid.axes[a].values[v]);
            longest = n > longest ? n : longest;
        }
        pb.text_size += longest;
    }
    pb.text = malloc(pb.text_size);
    pb.log = fopen("/dev/null", "w");
    worker_scene(o, &pb);
    typed_setup(o, &pb);
    pb.ck = closed_setup(o, &pb);
    pthread_mutex_lock(&s->mu);
    if (!pb.sets || !pb.text)
        s->io_error = 1;
    for (;;) {
        while (!s->io_error && s->next < s->nmine && s->next >= s->written + s->window)
            pthread_cond_wait(&s->cv, &s->mu);
        if (s->io_error || s->next >= s->nmine)
            break;
        size_t j = s->next++;
        pthread_mutex_unlock(&s->mu);
        size_t i = o->sharded ? (size_t)o->shard_k + j * (size_t)o->shard_n : j;
        int kind, closed;
        rowbuf *row = &s->slots[j % s->window]; /* row j - window is written: the slot is this worker's */
        row->len = 0;
        run_point(s, &pb, i, &kind, &closed, row);
        pthread_mutex_lock(&s->mu);
        s->nclosed += (size_t)closed;
        if (row->err)
            s->io_error = 1;
        *(kind == 0 ? &s->nok : kind == 1 ? &s->ninvalid : &s->nfailed) += 1;
        s->ready[j % s->window] = 1;
        while (!s->io_error && s->written < s->nmine && s->ready[s->written % s->window]) {
            size_t w = s->written % s->window;
            if (fwrite(s->slots[w].b, 1, s->slots[w].len, s->table) != s->slots[w].len)
                s->io_error = 1;
            s->ready[w] = 0;
            s->written++;
        }
        pthread_cond_broadcast(&s->cv);
    }
    pthread_cond_broadcast(&s->cv);
    pthread_mutex_unlock(&s->mu);
    free(pb.sets);
    free(pb.text);
    closed_free(pb.ck);
    typed_free(o, &pb);
    if (pb.have_base)
        hy_scene_doc_free(&pb.base);
    hy_scene_free(pb.scene);
    if (pb.log)
        fclose(pb.log);
    return NULL;
}

int hy_sweep_run_pool(hy_sweep_study *s)
{
    long nt = s->o->jobs < (long)s->nmine ? s->o->jobs : (long)s->nmine;
    if (nt < 1)
        nt = 1;
    s->window = 4 * (size_t)nt + 16;
    s->slots = calloc(s->window, sizeof *s->slots);
    s->ready = calloc(s->window, 1);
    pthread_t *th = calloc((size_t)nt, sizeof *th);
    if (!s->slots || !s->ready || !th) {
        free(th);
        free(s->slots);
        free(s->ready);
        return -1;
    }
    pthread_mutex_init(&s->mu, NULL);
    pthread_cond_init(&s->cv, NULL);
    long started = 0;
    for (; started < nt; started++)
        if (pthread_create(&th[started], NULL, worker, s))
            break;
    if (started == 0)
        worker(s);
    for (long t = 0; t < started; t++)
        pthread_join(th[t], NULL);
    pthread_mutex_destroy(&s->mu);
    pthread_cond_destroy(&s->cv);
    for (size_t k = 0; k < s->window; k++)
        free(s->slots[k].b);
    free(s->slots);
    free(s->ready);
    free(th);
    return 0;
}


/* 64-bit FNV-1a of a string into h. */
static uint64_t fnv(uint64_t h, const char *t)
{
    for (const unsigned char *c = (const unsigned char *)t; *c; c++)
        h = (h ^ *c) * 1099511628211ULL;
    return (h ^ 0xff) * 1099511628211ULL; /* a separator: "ab","c" != "a","bc" */
}

/* The study's scene with its --set overrides in *base (the caller frees it);
 * 2, with the reason in msg and *base NULL, when it does not load or an
 * override is refused. */
static int load_base(const hy_sweep_opts *o, hy_scene **base, hy_error *msg)
{
    hy_error err = {0};
    *base = NULL;
    if (hy_scene_parse_file_policy(o->scene, &o->pol, base, &err)) {
        *msg = err;
        return 2;
    }
    for (size_t k = 0; k < o->nsets; k++)
        if (hy_scene_set(*base, o->sets[k], &err)) {
            hy_error_set(msg, err.code, "--set %s: %s", o->sets[k], err.msg);
            hy_scene_free(*base);
            *base = NULL;
            return 2;
        }
    return 0;
}

/* Fills the study's series columns (names, and which ones hold distances)
 * from the first ns series of d; 2 when out of memory (the columns made so
 * far stay in s for hy_sweep_study_free). */
static int series_columns(hy_sweep_study *s, const hy_scene_doc *d, size_t ns)
{
    int rc = 0;
    s->series = calloc(ns ? ns : 1, sizeof *s->series);
    s->series_dist = calloc(ns ? ns : 1, sizeof *s->series_dist);
    if (!s->series || !s->series_dist)
        rc = 2;
    for (size_t k = 0; k < ns && !rc; k++) {
        const hy_decl_series *se = &d->series[k];
        size_t n = strlen(se->h.name) + 1;
        if (!(s->series[k] = malloc(n)))
            rc = 2;
        else
            memcpy(s->series[k], se->h.name, n);
        s->series_dist[k] = hy_decl_got(&se->h, offsetof(hy_decl_series, data)) >= 0 &&
                            (se->data == HY_DATA_YGAMMA || se->data == HY_DATA_TRANSIENT);
        s->nseries++;
    }
    return rc;
}

/* Loads the whole scene at the grid's point 0 and checks its output formats
 * and its work against the budget (keys that only the model/input check
 * refuses); 2, with the reason in msg, when any of that fails. */
static int check_point0(const hy_sweep_opts *o, hy_error *msg)
{
    const hy_grid *g = &o->grid;
    hy_error err = {0};
    point_buf pb;
    pb.sets = calloc(o->nsets + g->naxes + 1, sizeof *pb.sets);
    hy_scene_run r;
    size_t nsets = o->nsets;
    char text[8192];
    size_t used = 0;
    if (!pb.sets)
        return 2;
    if (o->nsets) /* no overrides: sets may be NULL (memcpy from NULL is undefined even for 0 bytes) */
        memcpy(pb.sets, o->sets, o->nsets * sizeof *pb.sets);
    for (size_t a = 0; a < g->naxes && used < sizeof text; a++) {
        pb.sets[nsets++] = text + used;
        used += (size_t)snprintf(text + used, sizeof text - used, "%s=%s", g->axes[a].key, g->axes[a].values[0]) + 1;
    }
    if (used >= sizeof text || hy_scene_run_load_policy(&r, o->scene, pb.sets, nsets, &o->pol, &err)) {
        if (used >= sizeof text)
            hy_error_set(msg, HY_EINVAL, "the grid keys are too long");
        else
            *msg = err;
        free(pb.sets);
        return 2;
    }
    double work = 0;
    char what[256];
    int bad_output = (o->figures && hy_scene_run_check_output(&r, o->formats, &err)) ||
                     hy_scene_run_estimate(&r, &work, what, sizeof what, &err) ||
                     (work > hy_scene_policy_budget(&o->pol) &&
                      hy_scene_run_over_budget(&r.doc, work, hy_scene_policy_budget(&o->pol), what, &err));
    hy_scene_run_free(&r);
    free(pb.sets);
    if (bad_output) {
        *msg = err;
        return 2;
    }
    return 0;
}

/* Checks the study before anything is written: the scene loads at point 0,
 * every grid value is accepted by the scene on its own; fills the series
 * columns and the study hash.  2 on bad input (message printed). */
int hy_sweep_check(hy_sweep_study *s, uint64_t *hash, hy_error *msg)
{
    const hy_sweep_opts *o = s->o;
    const hy_grid *g = &o->grid;
    hy_error err = {0};
    hy_scene *base = NULL;
    if (load_base(o, &base, msg))
        return 2;
    uint64_t h = 14695981039346656037ULL;
    char num[64];
    snprintf(num, sizeof num, "%016" PRIx64, hy_scene_hash(base));
    h = fnv(fnv(fnv(h, "hystviz sweep 1"), HY_VERSION), num);
    h = fnv(fnv(h, o->figures ? (o->formats ? o->formats : "scene formats") : "none"), o->times ? "times" : "");
    snprintf(num, sizeof num, "verify %ld", o->verify_every); /* which rows hold errors */
    h = fnv(h, num);
    snprintf(num, sizeof num, "%.17g", hy_scene_policy_budget(&o->pol)); /* it decides which points are refused */
    h = fnv(h, num);
    if (o->npy) /* (the CSV study's hash is as before --table) */
        h = fnv(h, "table npy");
    int rc = 0;
    for (size_t a = 0; a < g->naxes && !rc; a++) {
        h = fnv(fnv(h, g->axes[a].key), g->axes[a].spec);
        char buf[4200];
        for (size_t v = 0; v < g->axes[a].nvalues && !rc; v++) {
            snprintf(buf, sizeof buf, "%s=%s", g->axes[a].key, g->axes[a].values[v]);
            if (hy_scene_set(base, buf, &err)) {
                hy_error_set(msg, err.code, "--grid %s=%s: value '%s': %s", g->axes[a].key, g->axes[a].spec,
                        g->axes[a].values[v], err.msg);
                rc = 2;
            }
        }
    }
    hy_scene_doc d = {0};
    if (!rc && hy_scene_decode_fill(base, &d, &err))
        rc = 2;
    if (series_columns(s, &d, rc ? 0 : d.nseries))
        rc = 2;
    hy_scene_doc_free(&d);
    hy_scene_free(base);
    if (rc || (rc = check_point0(o, msg)))
        return rc;
    *hash = h;
    return 0;
}

void hy_sweep_study_free(hy_sweep_study *s)
{
    for (size_t k = 0; s->series && k < s->nseries; k++)
        free(s->series[k]);
    free(s->series);
    free(s->series_dist);
    for (size_t a = 0; s->short_keys && a < s->o->grid.naxes; a++)
        free(s->short_keys[a]);
    free(s->short_keys);
    for (size_t a = 0; s->name_parts && a < s->o->grid.naxes; a++) {
        for (size_t v = 0; s->name_parts[a] && v < s->o->grid.axes[a].nvalues; v++)
            free(s->name_parts[a][v]);
        free(s->name_parts[a]);
    }
    free(s->name_parts);
    for (size_t a = 0; s->axis_num && a < s->o->grid.naxes; a++)
        free(s->axis_num[a]);
    free(s->axis_num);
    free(s->axis_w);
    free(s->descr);
}

size_t hy_npy_header(const char *descr, size_t nrows, char *buf, size_t size)
{
    char dict[HY_NPY_HEAD_MAX];
    int n = snprintf(dict, sizeof dict, "{'descr': %s, 'fortran_order': False, 'shape': (%zu,), }", descr, nrows);
    if (n < 0 || (size_t)n + 1 >= sizeof dict)
        return 0;
    size_t total = (10 + (size_t)n + 1 + 63) / 64 * 64; /* magic, version, length, dict, '\n': 64-aligned */
    if (total > size || total - 10 > 65535)
        return 0;
    size_t hl = total - 10;
    memcpy(buf, "\x93NUMPY\x01\x00", 8);
    buf[8] = (char)(hl & 0xff);
    buf[9] = (char)(hl >> 8);
    memcpy(buf + 10, dict, (size_t)n);
    memset(buf + 10 + n, ' ', total - 11 - (size_t)n);
    buf[total - 1] = '\n';
    return total;
}

/* ---- the study in memory (hystviz.h) -------------------------------- */

/* "KEY=V1,V2,..." of axis a: each value as hy_grid writes a computed one;
 * NULL (err set) for a non-finite value or out of memory. */
static char *axis_arg(const char *key, const double *v, size_t n, hy_error *err)
{
    size_t cap = strlen(key) + 2 + 32 * n, len = 0;
    char *t = malloc(cap);
    if (!t)
        return hy_error_set(err, HY_ENOMEM, "out of memory"), NULL;
    len = (size_t)snprintf(t, cap, "%s=", key);
    for (size_t k = 0; k < n; k++) {
        if (!isfinite(v[k])) {
            free(t);
            hy_error_set(err, HY_EINVAL, "grid key '%s': value %zu is %g (a grid value must be a finite number)", key,
                         k, v[k]);
            return NULL;
        }
        char num[32];
        hy_grid_format(v[k], num, sizeof num);
        len += (size_t)snprintf(t + len, cap - len, "%s%s", k ? "," : "", num);
    }
    return t;
}

/* Adds the naxes axes (keys[a], counts[a] values at values[a]) to g, each
 * named in messages by its count of values; HY_OK, or the error (in err) of
 * the first axis that is missing, empty or refused. */
static int add_axes(hy_grid *g, const char *const *keys, const double *const *values, const size_t *counts,
                    size_t naxes, hy_error *err)
{
    int rc = 0;
    for (size_t a = 0; a < naxes && !rc; a++) {
        if (!keys[a] || (counts[a] && !values[a]) || !counts[a]) {
            rc = hy_error_set(err, HY_EINVAL, "grid axis %zu: %s", a,
                              !keys[a] ? "its key is NULL" : "it has no values (give at least one)");
            break;
        }
        char *arg = axis_arg(keys[a], values[a], counts[a], err);
        rc = !arg ? (err ? err->code : HY_EINVAL) : hy_grid_add(g, arg, err);
        free(arg);
        char *spec = rc ? NULL : malloc(48); /* messages name the axis by its count, not its list */
        if (spec) {
            snprintf(spec, 48, "<%zu values>", counts[a]);
            free(g->axes[a].spec);
            g->axes[a].spec = spec;
        }
    }
    return rc;
}

int hy_sweep_npy(const char *path, const char *const *sets, size_t nsets, const char *const *keys,
                 const double *const *values, const size_t *counts, size_t naxes, long shard_k, long shard_n,
                 long jobs, double max_work, unsigned char **npy, size_t *len, hy_error *err)
{
    hy_error own; /* err may be NULL; the scene's loading reads back its messages (as hystviz.c's ERR_OWN) */
    if (!err)
        err = &own;
    if (npy)
        *npy = NULL;
    if (len)
        *len = 0;
    if (!path || !npy || !len || (nsets && !sets) || (naxes && (!keys || !values || !counts)))
        return hy_error_set(err, HY_EINVAL, "hy_sweep_npy: path, npy and len must not be NULL, nor sets, keys, "
                                            "values or counts where there are any");
    if (!isfinite(max_work))
        return hy_error_set(err, HY_EINVAL, "hy_sweep_npy: the work budget max_work must be a finite number "
                                            "(<= 0: the default), got %g", max_work);
    if (shard_n < 1 || shard_n > HY_SHARD_MAX || shard_k < 0 || shard_k >= shard_n)
        return hy_error_set(err, HY_EINVAL, "hy_sweep_npy: shard %ld of %ld: want 0 <= shard_k < shard_n <= %ld",
                            shard_k, shard_n, HY_SHARD_MAX);
    hy_sweep_opts o;
    memset(&o, 0, sizeof o);
    o.sharded = shard_n > 1;
    o.shard_k = shard_k;
    o.shard_n = shard_n;
    o.scene = path;
    o.sets = (char **)(uintptr_t)sets;
    o.nsets = nsets;
    o.pol = hy_scene_policy_default();
    o.pol.max_work = max_work;
    o.jobs = jobs < 1 ? 1 : jobs > 1024 ? 1024 : jobs;
    o.verify_every = HY_SWEEP_VERIFY_EVERY;
    o.quiet = 1;
    o.npy = 1;
    hy_grid_init(&o.grid);
    int rc = add_axes(&o.grid, keys, values, counts, naxes, err);
    hy_sweep_study s;
    memset(&s, 0, sizeof s);
    s.o = &o;
    uint64_t hash;
    if (!rc)
        rc = hy_sweep_check(&s, &hash, err) ? HY_EINVAL : hy_sweep_prepare(&s, err) ? HY_ENOMEM : 0;
    char *buf = NULL;
    size_t n = 0;
    FILE *f = rc ? NULL : open_memstream(&buf, &n);
    if (!rc && !f)
        rc = hy_error_set(err, HY_ENOMEM, "out of memory");
    if (!rc) {
        size_t hsize = 65536 + 64, hl = 0;
        char *head = malloc(hsize);
        if (!head || !(hl = hy_npy_header(s.descr, s.nmine, head, hsize)) || fwrite(head, 1, hl, f) != hl)
            rc = hy_error_set(err, HY_ENOMEM, "the .npy header would pass 64 KiB (too many or too long columns), "
                                              "or out of memory");
        free(head);
        s.table = f;
    }
    if (!rc && (hy_sweep_run_pool(&s) || s.io_error || s.written != s.nmine))
        rc = hy_error_set(err, HY_ENOMEM, "out of memory");
    if (f && fclose(f) && !rc)
        rc = hy_error_set(err, HY_ENOMEM, "out of memory");
    if (rc)
        free(buf);
    else {
        *npy = (unsigned char *)buf;
        *len = n;
    }
    hy_sweep_study_free(&s);
    hy_grid_free(&o.grid);
    return rc;
}
