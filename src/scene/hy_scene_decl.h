/* SPDX-License-Identifier: MIT */
/* hy_scene_decl.h: a scene decoded once into typed structs through the schema's field table.
 *
 * Each key row of the schema (hy_scene_schema.c) names the struct field it
 * fills (offsetof) and that field's C type; hy_scene_decode walks the table
 * once, fills every section's struct with its value (set or default) and
 * notes where each value was written, then checks what spans several keys
 * or sections (an annotation needs x and y, an inset both zoom_x and
 * zoom_y, ...).  A scene that decodes computes: the pipeline reads these
 * structs, never the scene, and names a value's place through the head:
 *
 *     hy_scene_doc d;
 *     if (hy_scene_decode(scene, &d, &err)) { puts(err.msg); return 2; }
 *     printf("%g\n", d.figure.size[0]);
 *     if (d.figure.dpi > 600)
 *         hy_decl_error(&d.figure.h, offsetof(hy_decl_figure, dpi), &err, HY_EINVAL, "too fine");
 *     hy_scene_doc_free(&d);
 *
 * Strings and lists point into the scene, which must outlive the doc and
 * stay unchanged while it is read (decode again after hy_scene_set).
 */
#ifndef HY_SCENE_DECL_H
#define HY_SCENE_DECL_H

#include <stddef.h>

#include "hy_scene_types.h"
#include "hy_status.h"

/* The largest parameter struct a model's own rows may fill (hy_decl_model.par). */
#define HY_MODEL_PAR_MAX 256

/* The most keys a section may have (a schema test checks every section). */
#define HY_SCENE_KEYS_MAX 40

/* A list value: n numbers (an ENUM_LIST: indices in the key's enum list). */
typedef struct hy_scene_list {
    const double *v;
    size_t n;
} hy_scene_list;

/* A PAIR or LIMITS value: v[0] < v[1], or is_auto (LIMITS only) with v unset. */
typedef struct hy_scene_pair {
    double v[2];
    int is_auto;
} hy_scene_pair;

/* What decode found for one key: HY_SCENE_SET, _DEFAULT or _ABSENT (the
 * field then holds zero; _BADKEY: the key fills no field, e.g. a row of
 * another model than [model] kind), whether the scene or an override wrote
 * it, where (line 0: not written, or an override) and, for a value written
 * `key = $NAME`, the NAME of the [param NAME] it reads (else NULL). */
typedef struct hy_decl_field {
    int got;
    int set;
    hy_scene_loc loc;
    const char *ref;
} hy_decl_field;

/* The first member of every decoded section: which section, its label, where
 * its header was first written (line 0: absent), and one field per key of
 * the section in table order. */
typedef struct hy_decl_head {
    const hy_scene_section_spec *spec;
    const char *name;
    const char *source; /* the scene file, for messages when nothing was written */
    hy_scene_loc loc;
    hy_decl_field at[HY_SCENE_KEYS_MAX];
} hy_decl_head;

/* The sections.  A field's C type follows its key's kind: NUMBER and LENGTH
 * (in pt) double, INTEGER long, BOOL and ENUM (the index) int, STRING, NAME
 * and PATH const char *, lists hy_scene_list, PAIR and LIMITS hy_scene_pair,
 * LENGTH_PAIR double[2] (pt), COLOR hy_scene_color.  The field's name is the
 * key's name.  A model that declares its own [model] rows (hy_scene_model_rows.h)
 * has its parameter struct at par, filled for a scene of its kind. */
typedef struct hy_decl_model {
    hy_decl_head h;
    int kind;
    double sigma0, sigma1, sigma2, fc, fs, vs, beta, rho, x0, tau;
    double m, c, k, alpha, bw_beta, bw_gamma, delta, nu;
    _Alignas(max_align_t) unsigned char par[HY_MODEL_PAR_MAX];
} hy_decl_model;

typedef struct hy_decl_input {
    hy_decl_head h;
    int kind;
    double umin1, umin2, umax1, umax2;
    hy_scene_list t;
    int shape;
    hy_scene_list extrema, times;
    double amp, offset, period, min, max;
    hy_scene_list points;
    const char *file;
    double fs;
    long samples;
    hy_scene_pair band;
    double rms;
    long seed;
    double rate;
    const char *data;
    int start;
} hy_decl_input;

typedef struct hy_decl_compute {
    hy_decl_head h;
    hy_scene_list gamma, k;
    long cycles;
    int solver;
    double rtol, atol;
    hy_scene_pair tspan;
    long points, settle, upsample;
    int decimate;
    double noise;
} hy_decl_compute;

typedef struct hy_decl_figure {
    hy_decl_head h;
    int kind;
    const char *title, *caption, *xlabel, *ylabel;
    hy_scene_pair xlim, ylim;
    int xlog, ylog;
    double size[2];
    long dpi;
    int full_resolution, legend;
    const char *font;
    double fontsize;
    int grid;
    hy_scene_pair shade, zoom_x, zoom_y;
    int zoom_follow, theme;
    long columns;
} hy_decl_figure;

/* [forc]: the FORC protocol and distribution of a [figure] kind = forc
 * (docs/FORC.md, "In a scene"). */
typedef struct hy_decl_forc {
    hy_decl_head h;
    const char *file;
    int drift;
    double hsat;
    hy_scene_pair range;
    double hb_max;
    long curves;
    double sf, sc0, sc1;
    int extend;
    double vmax, field_to_tesla;
    const char *rho_unit;
    int reproduce, draw, protocol;
} hy_decl_forc;

typedef struct hy_decl_series {
    hy_decl_head h;
    int data;
    double gamma;
    long k;
    int style;
    hy_scene_color color;
    double width;
    int marker;
    const char *label;
    double at;
    int quantity;
    double yscale, floor;
    const char *of;
} hy_decl_series;

typedef struct hy_decl_data {
    hy_decl_head h;
    const char *file, *u, *y, *t;
    double u_scale, y_scale, t_scale;
    const char *split;
    long record;
} hy_decl_data;

typedef struct hy_decl_annotation {
    hy_decl_head h;
    const char *text;
    double x, y, point_x, point_y;
} hy_decl_annotation;

typedef struct hy_decl_panel {
    hy_decl_head h;
    const char *scene;
} hy_decl_panel;

typedef struct hy_decl_output {
    hy_decl_head h;
    const char *name;
    hy_scene_list formats;
    const char *dir;
} hy_decl_output;

typedef struct hy_decl_controls {
    hy_decl_head h;
    const char *main;
} hy_decl_controls;

typedef struct hy_decl_param {
    hy_decl_head h;
    double value;
} hy_decl_param;

typedef struct hy_decl_preset {
    hy_decl_head h;
    const char *label, *set;
} hy_decl_preset;

typedef struct hy_decl_animation {
    hy_decl_head h;
    double duration;
    long fps;
    int easing, quality;
} hy_decl_animation;

typedef struct hy_decl_keyframe {
    hy_decl_head h;
    const char *key;
    hy_scene_list times, values;
    int easing, log;
} hy_decl_keyframe;

/* The sections a doc holds, X(name): each fills the member `name` of type
 * hy_decl_<name>, the named ones as an array `name` of `nname` structs.
 * Decode, free and hy_scene_doc_find are generated from these lists. */
#define HY_DOC_UNNAMED(X) X(model) X(input) X(compute) X(figure) X(forc) X(output) X(controls) X(animation)
#define HY_DOC_NAMED(X) X(series) X(data) X(annotation) X(panel) X(param) X(preset) X(keyframe)

/* A whole scene: its unnamed sections and, in file order, its named ones. */
#define HY_DOC_ONE(sec) hy_decl_##sec sec;
#define HY_DOC_ARRAY(sec) hy_decl_##sec *sec; size_t n##sec;
typedef struct hy_scene_doc {
    const char *source;
    HY_DOC_UNNAMED(HY_DOC_ONE)
    HY_DOC_NAMED(HY_DOC_ARRAY)
} hy_scene_doc;
#undef HY_DOC_ONE
#undef HY_DOC_ARRAY

/* The C type of a decoded field (hy_scene_key_spec.ctype; 0: not decoded). */
enum {
    HY_CTYPE_NONE,
    HY_CTYPE_DOUBLE,
    HY_CTYPE_LONG,
    HY_CTYPE_INT,
    HY_CTYPE_STR,
    HY_CTYPE_LIST,
    HY_CTYPE_PAIR,
    HY_CTYPE_DOUBLE2,
    HY_CTYPE_COLOR
};

/* The ctype code of an lvalue's type (the schema's rows use it on their field). */
#define HY_CTYPE_OF(lv)                                                                        \
    _Generic((lv), double: HY_CTYPE_DOUBLE, long: HY_CTYPE_LONG, int: HY_CTYPE_INT,            \
             const char *: HY_CTYPE_STR, hy_scene_list: HY_CTYPE_LIST, hy_scene_pair: HY_CTYPE_PAIR, \
             double *: HY_CTYPE_DOUBLE2, hy_scene_color: HY_CTYPE_COLOR)

/* The ctype a key of this kind decodes into. */
int hy_scene_kind_ctype(hy_scene_kind kind);

/* Decodes scene s into *d (every section through the field table) and checks
 * what spans keys and sections.  On error returns HY_EINVAL (or HY_ENOMEM)
 * with "file:line:col: what" in err; call hy_scene_doc_free either way. */
int hy_scene_decode(const hy_scene *s, hy_scene_doc *d, hy_error *err);

/* As hy_scene_decode, for a scene marked (hy_scene_mark) when base was
 * decoded from it, and changed since only by overrides: d is a copy of base
 * with the sections those overrides changed decoded again (the undo log
 * says which), and the checks run on it; where an override made a section,
 * the whole scene is decoded.  A sweep's point costs one section, not the
 * scene.  base must outlive d's use; call hy_scene_doc_free on d. */
int hy_scene_decode_marked(const hy_scene *s, const hy_scene_doc *base, hy_scene_doc *d, hy_error *err);

/* As hy_scene_decode without the checks: the structs only (hystviz serve
 * reads a scene's series to choose its controls).  HY_ENOMEM or HY_OK. */
int hy_scene_decode_fill(const hy_scene *s, hy_scene_doc *d, hy_error *err);

/* Whether a parsed scene is a figure: it has a [series] or a [panel]
 * section (else it is a file of shared settings that scenes include). */
int hy_scene_is_figure(const hy_scene *s);

/* Fills the section struct whose head is h from [section name] of s (name
 * NULL for an unnamed section).  Returns HY_OK, or HY_EINVAL for an unknown
 * section. */
int hy_scene_decode_section(const hy_scene *s, const char *section, const char *name, hy_decl_head *h);

/* Frees what hy_scene_decode allocated (the named sections' arrays). */
void hy_scene_doc_free(hy_scene_doc *d);

/* The offset of the field that key fills in h's struct, or HY_DECL_HEAD. */
size_t hy_decl_offset(const hy_decl_head *h, const char *key);

/* Where the field at offset off was written ({file, 0, 0}: not written). */
hy_scene_loc hy_decl_loc(const hy_decl_head *h, size_t off);

/* What decode found for the field at byte offset off of h's struct:
 * HY_SCENE_SET, _DEFAULT, _ABSENT, or _BADKEY if no key fills it. */
int hy_decl_got(const hy_decl_head *h, size_t off);

/* Writes "file:line:col: <message>" at where the field at offset off was
 * written (else at the section header, else the scene file) into err and
 * returns code; off HY_DECL_HEAD names the section itself.  The arguments
 * may include err->msg. */
#define HY_DECL_HEAD ((size_t)-1)
int hy_decl_error(const hy_decl_head *h, size_t off, hy_error *err, int code, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 5, 6)))
#endif
    ;

/* As hy_decl_error at the j-th key of h's section: where it was written
 * (also a row of another model, which fills nothing), else the header. */
int hy_decl_error_row(const hy_decl_head *h, size_t j, hy_error *err, int code, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 5, 6)))
#endif
    ;

/* The identifier of value idx of the ENUM or ENUM_LIST field at offset off
 * of h's struct ("minor" for figure.zoom_follow 1), or "" if none. */
const char *hy_decl_enum_text(const hy_decl_head *h, size_t off, int idx);

/* The value of the numeric (NUMBER or INTEGER) key section.key of an
 * unnamed section of d, set or default, into *out: 0, or -1 if there is no
 * such key or no value ({model.sigma0} placeholders). */
int hy_scene_doc_num(const hy_scene_doc *d, const char *section, const char *key, double *out);

/* The value of the numeric (NUMBER or INTEGER) key of h's section, set or
 * default, into *out: returns HY_SCENE_SET or HY_SCENE_DEFAULT, or a
 * negative HY_SCENE_ status (no such key, no value: *out unchanged). */
int hy_decl_num(const hy_decl_head *h, const char *key, double *out);

/* The head of the decoded [section name] of d (name NULL for an unnamed
 * section, whose head is there even when the scene lacks the section), or
 * NULL if d has no such section. */
const hy_decl_head *hy_scene_doc_find(const hy_scene_doc *d, const char *section, const char *name);

/* How many [section NAME] d holds (1 for an unnamed section, 0 for an
 * unknown one), and the head of the i-th in file order (NULL past the end). */
size_t hy_scene_doc_count(const hy_scene_doc *d, const char *section);
const hy_decl_head *hy_scene_doc_at(const hy_scene_doc *d, const char *section, size_t i);

/* The decoded [series NAME] of d, or NULL. */
const hy_decl_series *hy_scene_doc_series(const hy_scene_doc *d, const char *name);

#endif
