/* SPDX-License-Identifier: MIT */
/* hy_scene_decode.c: one generic decoder from a parsed scene to typed structs, driven by the
 * schema's field table (offset and C type per key), and the checks that span keys and sections. */
#include "hy_scene_decl.h"
#include "hy_scene_internal.h"
#include "hy_scene.h"

#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

int hy_scene_kind_ctype(hy_scene_kind kind)
{
    switch (kind) {
    case HY_KIND_NUMBER:
    case HY_KIND_LENGTH: return HY_CTYPE_DOUBLE;
    case HY_KIND_INTEGER: return HY_CTYPE_LONG;
    case HY_KIND_BOOL:
    case HY_KIND_ENUM: return HY_CTYPE_INT;
    case HY_KIND_STRING:
    case HY_KIND_NAME:
    case HY_KIND_PATH: return HY_CTYPE_STR;
    case HY_KIND_NUMBER_LIST:
    case HY_KIND_INTEGER_LIST:
    case HY_KIND_ENUM_LIST: return HY_CTYPE_LIST;
    case HY_KIND_LENGTH_PAIR: return HY_CTYPE_DOUBLE2;
    case HY_KIND_COLOR: return HY_CTYPE_COLOR;
    case HY_KIND_PAIR:
    case HY_KIND_LIMITS: return HY_CTYPE_PAIR;
    }
    return HY_CTYPE_NONE;
}

/* Reads key k of [sec name] into the field at p through the getter of its
 * kind; returns what the getter found. */
static int read_key(const hy_scene *s, const char *sec, const char *name, const hy_scene_key_spec *k, char *p)
{
    switch (k->kind) {
    case HY_KIND_NUMBER: return hy_scene_get_num(s, sec, name, k->name, (double *)(void *)p);
    case HY_KIND_LENGTH: return hy_scene_get_length_pt(s, sec, name, k->name, (double *)(void *)p);
    case HY_KIND_INTEGER: return hy_scene_get_int(s, sec, name, k->name, (long *)(void *)p);
    case HY_KIND_BOOL: return hy_scene_get_bool(s, sec, name, k->name, (int *)(void *)p);
    case HY_KIND_ENUM: return hy_scene_get_enum(s, sec, name, k->name, (int *)(void *)p, NULL);
    case HY_KIND_STRING:
    case HY_KIND_NAME:
    case HY_KIND_PATH: return hy_scene_get_str(s, sec, name, k->name, (const char **)(void *)p);
    case HY_KIND_NUMBER_LIST:
    case HY_KIND_INTEGER_LIST:
    case HY_KIND_ENUM_LIST: {
        hy_scene_list *l = (hy_scene_list *)(void *)p;
        return hy_scene_get_list(s, sec, name, k->name, &l->v, &l->n);
    }
    case HY_KIND_LENGTH_PAIR: return hy_scene_get_length_pair_pt(s, sec, name, k->name, (double *)(void *)p);
    case HY_KIND_COLOR: return hy_scene_get_color(s, sec, name, k->name, (hy_scene_color *)(void *)p);
    case HY_KIND_PAIR:
    case HY_KIND_LIMITS: {
        hy_scene_pair *q = (hy_scene_pair *)(void *)p;
        return hy_scene_get_pair(s, sec, name, k->name, q->v, &q->is_auto);
    }
    }
    return HY_SCENE_BADKEY;
}

int hy_scene_decode_section(const hy_scene *s, const char *section, const char *name, hy_decl_head *h)
{
    int si = hy_scene_schema_section(section);
    if (si < 0)
        return HY_EINVAL;
    const hy_scene_section_spec *spec = hy_scene_schema(NULL) + si;
    h->spec = spec;
    h->name = name;
    h->source = hy_scene_source(s);
    h->loc = (hy_scene_loc){h->source, 0, 0};
    hy_scene_get_loc(s, section, name, NULL, &h->loc);
    const char *kind = NULL; /* the section's kind, for a model's own rows */
    for (size_t j = 0; j < spec->nkeys && j < HY_SCENE_KEYS_MAX; j++) {
        const hy_scene_key_spec *k = &spec->keys[j];
        hy_decl_field *f = &h->at[j];
        f->loc = (hy_scene_loc){h->source, 0, 0};
        if (k->model && !kind && hy_scene_get_enum(s, section, name, "kind", NULL, &kind) < 0)
            kind = "";
        if (!k->ctype || (k->model && strcmp(k->model, kind))) { /* another model's row fills nothing */
            f->got = HY_SCENE_BADKEY;
            f->set = hy_scene_get_loc(s, section, name, k->name, &f->loc);
            continue;
        }
        f->got = read_key(s, section, name, k, (char *)h + k->field);
        f->set = f->got == HY_SCENE_SET;
        if (f->set) {
            hy_scene_get_loc(s, section, name, k->name, &f->loc);
            f->ref = hy_scene_get_ref(s, section, name, k->name);
        }
    }
    return HY_OK;
}

/* Decodes every [section NAME] of a kind into a calloc'd array of n structs
 * of size each; *out NULL when there is none. */
static int decode_named(const hy_scene *s, const char *section, size_t size, void **out, size_t *n, hy_error *err)
{
    *n = hy_scene_count(s, section);
    *out = NULL;
    if (!*n)
        return HY_OK;
    char *a = calloc(*n, size);
    if (!a)
        return hy_error_set(err, HY_ENOMEM, "out of memory");
    *out = a;
    for (size_t i = 0; i < *n; i++)
        hy_scene_decode_section(s, section, hy_scene_name_at(s, section, i), (hy_decl_head *)(void *)(a + i * size));
    return HY_OK;
}

#define OFF(T, f) offsetof(T, f)
#define GOT(p, T, f) hy_decl_got(&(p)->h, OFF(T, f))

/* The index of text in the enum list of key of section (both known). */
static int enum_index(const char *section, const char *key, const char *text)
{
    int si = hy_scene_schema_section(section), ki = hy_scene_schema_key(si, key);
    const char *const *e = hy_scene_schema(NULL)[si].keys[ki].enums;
    for (int i = 0; e[i]; i++)
        if (!strcmp(e[i], text))
            return i;
    return -1;
}

/* An annotation is placed at x, y; a leader line needs both point_x and point_y. */
static int check_annotations(const hy_scene_doc *d, hy_error *err)
{
    for (size_t i = 0; i < d->nannotation; i++) {
        const hy_decl_annotation *a = &d->annotation[i];
        if (GOT(a, hy_decl_annotation, x) < 0 || GOT(a, hy_decl_annotation, y) < 0)
            return hy_decl_error(&a->h, HY_DECL_HEAD, err, HY_EINVAL, "annotation '%s' needs x and y", a->h.name);
        if ((GOT(a, hy_decl_annotation, point_x) < 0) != (GOT(a, hy_decl_annotation, point_y) < 0))
            return hy_decl_error(&a->h, HY_DECL_HEAD, err, HY_EINVAL,
                                 "annotation '%s' needs both point_x and point_y, or neither", a->h.name);
    }
    return HY_OK;
}

/* The inset: zoom_follow = minor follows a minor-loop series; else zoom_x
 * and zoom_y come together. */
static int check_zoom(const hy_scene_doc *d, hy_error *err)
{
    const hy_decl_figure *f = &d->figure;
    if (f->zoom_follow == enum_index("figure", "zoom_follow", "minor")) {
        int minor = enum_index("series", "data", "minor");
        for (size_t i = 0; i < d->nseries; i++)
            if (GOT(&d->series[i], hy_decl_series, data) >= 0 && d->series[i].data == minor)
                return HY_OK;
        return hy_decl_error(&f->h, OFF(hy_decl_figure, zoom_follow), err, HY_EINVAL,
                             "zoom_follow = minor needs a [series] with data = minor to follow");
    }
    int hzx = GOT(f, hy_decl_figure, zoom_x) == HY_SCENE_SET, hzy = GOT(f, hy_decl_figure, zoom_y) == HY_SCENE_SET;
    if (hzx != hzy)
        return hy_decl_error(&f->h, hzx ? OFF(hy_decl_figure, zoom_x) : OFF(hy_decl_figure, zoom_y), err, HY_EINVAL,
                             "a zoomed inset needs both zoom_x and zoom_y");
    return HY_OK;
}

/* A yk series names its k (whether ygamma needs a gamma is the model's: a
 * rate-independent one has y_gamma = y*). */
static int check_series(const hy_scene_doc *d, hy_error *err)
{
    int yk = enum_index("series", "data", "yk");
    for (size_t i = 0; i < d->nseries; i++) {
        const hy_decl_series *se = &d->series[i];
        if (GOT(se, hy_decl_series, data) < 0)
            continue; /* which data a model draws, and its message, is the model's (its load) */
        if (se->data == yk && GOT(se, hy_decl_series, k) < 0)
            return hy_decl_error(&se->h, OFF(hy_decl_series, data), err, HY_EINVAL, "series '%s' (data = yk) needs 'k'",
                                 se->h.name);
    }
    return HY_OK;
}

/* A [panel] names its scene; columns divides the panels into full rows. */
static int check_panels(const hy_scene_doc *d, hy_error *err)
{
    for (size_t i = 0; i < d->npanel; i++)
        if (GOT(&d->panel[i], hy_decl_panel, scene) < 0)
            return hy_decl_error(&d->panel[i].h, HY_DECL_HEAD, err, HY_EINVAL, "[panel %s] needs 'scene = \"FILE\"'",
                                 d->panel[i].h.name);
    long cols = d->figure.columns;
    if (d->npanel && GOT(&d->figure, hy_decl_figure, columns) >= 0 && (cols < 1 || d->npanel % (size_t)cols))
        return hy_decl_error(&d->figure.h, OFF(hy_decl_figure, columns), err, HY_EINVAL,
                             "columns = %ld does not divide the %zu panels into full rows", cols, d->npanel);
    return HY_OK;
}

/* [controls] main and every [preset NAME] set name keys of the schema. */
static int check_controls(const hy_scene *s, hy_error *err)
{
    char keys[9][HY_SCENE_KEY_MAX];
    size_t nkeys;
    int rc = hy_scene_main_keys(s, keys, 9, &nkeys, err);
    for (size_t i = 0; !rc && i < hy_scene_count(s, "preset"); i++) {
        char (*sets)[HY_SCENE_SET_MAX] = malloc(HY_SCENE_PRESET_MAX * sizeof *sets);
        rc = sets ? hy_scene_preset_sets(s, hy_scene_name_at(s, "preset", i), sets, HY_SCENE_PRESET_MAX, &nkeys, err)
                  : hy_error_set(err, HY_ENOMEM, "out of memory");
        free(sets);
    }
    return rc;
}

int hy_scene_is_figure(const hy_scene *s)
{
    return hy_scene_count(s, "series") > 0 || hy_scene_count(s, "panel") > 0 || hy_scene_count(s, "forc") > 0;
}

/* The checks that span keys and sections of a decoded doc; with controls,
 * also those of [controls] main and the [preset]s (read from the scene). */
static int check_doc(const hy_scene *s, const hy_scene_doc *d, int controls, hy_error *err)
{
    int rc = check_annotations(d, err);
    if (!rc)
        rc = check_zoom(d, err);
    if (!rc)
        rc = check_series(d, err);
    if (!rc)
        rc = check_panels(d, err);
    if (!rc && controls)
        rc = check_controls(s, err);
    return rc;
}

int hy_scene_decode(const hy_scene *s, hy_scene_doc *d, hy_error *err)
{
    int rc = hy_scene_decode_fill(s, d, err);
    return rc ? rc : check_doc(s, d, 1, err);
}

/* Decodes section x of s again into its place in d (found by kind and name):
 * 1, or 0 where d has no such section (the caller decodes the whole scene). */
static int redecode(const hy_scene *s, const hy__section *x, hy_scene_doc *d)
{
    const char *kind = hy_scene_schema(NULL)[x->spec].name;
#define ONE(sec)                                                                    \
    if (!x->name && !strcmp(kind, #sec)) {                                          \
        memset(&d->sec, 0, sizeof d->sec);                                          \
        hy_scene_decode_section(s, #sec, NULL, &d->sec.h);                          \
        return 1;                                                                   \
    }
    HY_DOC_UNNAMED(ONE)
#undef ONE
#define NAMED(sec)                                                                  \
    if (x->name && !strcmp(kind, #sec)) {                                           \
        for (size_t i = 0; i < d->n##sec; i++)                                      \
            if (d->sec[i].h.name == x->name || !strcmp(d->sec[i].h.name, x->name)) { \
                memset(&d->sec[i], 0, sizeof d->sec[i]);                            \
                hy_scene_decode_section(s, #sec, x->name, &d->sec[i].h);            \
                return 1;                                                           \
            }                                                                       \
        return 0;                                                                   \
    }
    HY_DOC_NAMED(NAMED)
#undef NAMED
    return 0;
}

int hy_scene_decode_marked(const hy_scene *s, const hy_scene_doc *base, hy_scene_doc *d, hy_error *err)
{
    if (!s->marked || s->nsecs != s->mark_secs) /* sections the overrides made: decoded whole */
        return hy_scene_decode(s, d, err);
    *d = *base;
    int rc = HY_OK;
#define NAMED(sec)                                                     \
    d->sec = NULL;                                                     \
    if (!rc && base->n##sec) {                                         \
        if (!(d->sec = malloc(base->n##sec * sizeof *base->sec)))      \
            rc = hy_error_set(err, HY_ENOMEM, "out of memory");        \
        else                                                           \
            memcpy(d->sec, base->sec, base->n##sec * sizeof *base->sec); \
    }
    HY_DOC_NAMED(NAMED)
#undef NAMED
    if (rc)
        return rc;
    int controls = 0;
    for (size_t u = 0; u < s->nundo; u++) {
        const hy__section *x = &s->secs[s->undo[u].sec];
        const char *kind = hy_scene_schema(NULL)[x->spec].name;
        controls |= !strcmp(kind, "controls") || !strcmp(kind, "preset");
        if (!redecode(s, x, d)) {
            hy_scene_doc_free(d);
            return hy_scene_decode(s, d, err);
        }
    }
    return check_doc(s, d, controls, err);
}

int hy_scene_decode_fill(const hy_scene *s, hy_scene_doc *d, hy_error *err)
{
    memset(d, 0, sizeof *d);
    d->source = hy_scene_source(s);
#define ONE(sec) hy_scene_decode_section(s, #sec, NULL, &d->sec.h);
    HY_DOC_UNNAMED(ONE)
#undef ONE
    int rc = HY_OK;
    void *p;
#define NAMED(sec)                                                       \
    if (!rc) {                                                           \
        rc = decode_named(s, #sec, sizeof *d->sec, &p, &d->n##sec, err); \
        d->sec = p;                                                      \
    }
    HY_DOC_NAMED(NAMED)
#undef NAMED
    return rc;
}

void hy_scene_doc_free(hy_scene_doc *d)
{
#define NAMED(sec)   \
    free(d->sec);    \
    d->sec = NULL;   \
    d->n##sec = 0;
    HY_DOC_NAMED(NAMED)
#undef NAMED
}

/* The index of the key that fills offset off of h's struct, or -1 (the
 * rows of another model than the section's kind fill nothing: BADKEY). */
static int key_at(const hy_decl_head *h, size_t off)
{
    for (size_t j = 0; h->spec && j < h->spec->nkeys && j < HY_SCENE_KEYS_MAX; j++)
        if (h->at[j].got != HY_SCENE_BADKEY && h->spec->keys[j].field == off)
            return (int)j;
    return -1;
}

size_t hy_decl_offset(const hy_decl_head *h, const char *key)
{
    for (size_t j = 0; h->spec && j < h->spec->nkeys && j < HY_SCENE_KEYS_MAX; j++)
        if (h->at[j].got != HY_SCENE_BADKEY && !strcmp(h->spec->keys[j].name, key))
            return h->spec->keys[j].field;
    return HY_DECL_HEAD;
}

hy_scene_loc hy_decl_loc(const hy_decl_head *h, size_t off)
{
    int j = off == HY_DECL_HEAD ? -1 : key_at(h, off);
    return j < 0 ? (hy_scene_loc){h->source, 0, 0} : h->at[j].loc;
}

int hy_decl_got(const hy_decl_head *h, size_t off)
{
    int j = key_at(h, off);
    return j < 0 ? HY_SCENE_BADKEY : h->at[j].got;
}

const char *hy_decl_enum_text(const hy_decl_head *h, size_t off, int idx)
{
    int j = key_at(h, off);
    const char *const *e = j < 0 ? NULL : h->spec->keys[j].enums;
    for (int i = 0; e && e[i]; i++)
        if (i == idx)
            return e[i];
    return "";
}

static void error_vrow(const hy_decl_head *h, int j, hy_error *err, int code, const char *fmt, va_list ap)
{
    hy_scene_loc loc = j >= 0 && j < HY_SCENE_KEYS_MAX && h->at[j].loc.line > 0 ? h->at[j].loc : h->loc;
    if (!loc.file)
        loc.file = h->source;
    hy__error_vat(loc, err, code, fmt, ap);
}

int hy_decl_error(const hy_decl_head *h, size_t off, hy_error *err, int code, const char *fmt, ...)
{
    if (!err)
        return code;
    va_list ap;
    va_start(ap, fmt);
    error_vrow(h, off == HY_DECL_HEAD ? -1 : key_at(h, off), err, code, fmt, ap);
    va_end(ap);
    return code;
}

int hy_decl_error_row(const hy_decl_head *h, size_t j, hy_error *err, int code, const char *fmt, ...)
{
    if (!err)
        return code;
    va_list ap;
    va_start(ap, fmt);
    error_vrow(h, j < HY_SCENE_KEYS_MAX ? (int)j : -1, err, code, fmt, ap);
    va_end(ap);
    return code;
}

int hy_decl_num(const hy_decl_head *h, const char *key, double *out)
{
    int j = h->spec ? hy_scene_schema_key((int)(h->spec - hy_scene_schema(NULL)), key) : -1;
    if (j < 0 || j >= HY_SCENE_KEYS_MAX || !h->spec->keys[j].ctype)
        return HY_SCENE_BADKEY;
    if (h->at[j].got < 0)
        return h->at[j].got;
    const hy_scene_key_spec *k = &h->spec->keys[j];
    const char *p = (const char *)h + k->field;
    if (k->kind == HY_KIND_NUMBER)
        memcpy(out, p, sizeof *out);
    else if (k->kind == HY_KIND_INTEGER) {
        long v;
        memcpy(&v, p, sizeof v);
        *out = (double)v;
    } else
        return HY_SCENE_BADKEY;
    return h->at[j].got;
}

size_t hy_scene_doc_count(const hy_scene_doc *d, const char *section)
{
#define ONE(sec)               \
    if (!strcmp(section, #sec)) \
        return 1;
#define NAMED(sec)             \
    if (!strcmp(section, #sec)) \
        return d->n##sec;
    HY_DOC_UNNAMED(ONE)
    HY_DOC_NAMED(NAMED)
#undef ONE
#undef NAMED
    return 0;
}

const hy_decl_head *hy_scene_doc_at(const hy_scene_doc *d, const char *section, size_t i)
{
#define ONE(sec)                          \
    if (!strcmp(section, #sec))           \
        return i ? NULL : &d->sec.h;
#define NAMED(sec)                        \
    if (!strcmp(section, #sec))           \
        return i < d->n##sec ? &d->sec[i].h : NULL;
    HY_DOC_UNNAMED(ONE)
    HY_DOC_NAMED(NAMED)
#undef ONE
#undef NAMED
    return NULL;
}

const hy_decl_head *hy_scene_doc_find(const hy_scene_doc *d, const char *section, const char *name)
{
    size_t n = hy_scene_doc_count(d, section);
    int si = hy_scene_schema_section(section);
    if (si < 0 || !hy_scene_schema(NULL)[si].takes_name != !name)
        return NULL;
    for (size_t i = 0; i < n; i++) {
        const hy_decl_head *h = hy_scene_doc_at(d, section, i);
        if (!name || !strcmp(h->name, name))
            return h;
    }
    return NULL;
}

int hy_scene_doc_num(const hy_scene_doc *d, const char *section, const char *key, double *out)
{
    /* the sections a figure's {section.key} reads (not [animation]: a still has none) */
    const hy_decl_head *hs[] = {&d->model.h, &d->input.h, &d->compute.h, &d->figure.h, &d->output.h};
    for (size_t i = 0; i < sizeof hs / sizeof hs[0]; i++)
        if (hs[i]->spec && !strcmp(hs[i]->spec->name, section))
            return hy_decl_num(hs[i], key, out) >= 0 ? 0 : -1;
    return -1;
}

const hy_decl_series *hy_scene_doc_series(const hy_scene_doc *d, const char *name)
{
    for (size_t i = 0; i < d->nseries; i++)
        if (!strcmp(d->series[i].h.name, name))
            return &d->series[i];
    return NULL;
}
