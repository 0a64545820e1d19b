/* SPDX-License-Identifier: MIT */
/* hy_scene_schema.h: the table of scene sections and keys (kinds, ranges, defaults, docs).
 *
 * The whole scene vocabulary lives in one static table (hy_scene_schema.c).
 * The parser validates against it, the getters fall back to its defaults, and
 * the reference in docs/SCENES.md is generated from it.  Read it like this:
 *
 *     size_t n;
 *     const hy_scene_section_spec *sec = hy_scene_schema(&n);
 *     for (size_t i = 0; i < n; i++)
 *         for (size_t j = 0; j < sec[i].nkeys; j++)
 *             printf("%s.%s\n", sec[i].name, sec[i].keys[j].name);
 */
#ifndef HY_SCENE_SCHEMA_H
#define HY_SCENE_SCHEMA_H

#include <stddef.h>

/* The model kinds: HY_MODEL_KINDS(X), X(id, "kind") per model, generated
 * from the model table (src/pipeline/meson.build).  The schema's [model]
 * kind list and the pipeline's model table (src/pipeline/scene_model.c,
 * which expects a `hy_scene_model_<id>` from each model's own file) are both
 * generated from it, so a model is added there, once. */
#include "hy_models.h"

/* What a [series] draws, one line per kind: X(ID, "name").  The schema's
 * data list and the pipeline's HY_DATA_ID values (scene_run.h) are both
 * generated from it, so the index decode gives is the HY_DATA_ value. */
#define HY_SERIES_DATA(X)                   \
    X(INPUT, "input")                       \
    X(PSI, "psi")                           \
    X(G, "g")                               \
    X(YSTAR, "ystar")                       \
    X(YSTEADY, "ysteady")                   \
    X(YGAMMA, "ygamma")                     \
    X(YK, "yk")                             \
    X(TRANSIENT, "transient")               \
    X(MINOR, "minor")                       \
    X(MAJOR, "major")                       \
    X(BOUCWEN, "boucwen")                   \
    X(MEASURED, "measured")                 \
    X(MODELLED, "modelled")

/* The figure kinds, one line per kind: X(ID, "name").  The schema's
 * [figure] kind list and the pipeline's FIG_ID values (scene_model.h) are
 * both generated from it. */
#define HY_FIGURE_KINDS(X)                  \
    X(TIMESERIES, "timeseries")             \
    X(LOOP, "loop")                         \
    X(INPUT, "input")                       \
    X(G, "g")                               \
    X(PSI, "psi")                           \
    X(FORC, "forc")

/* What a [series] quantity draws, one line per quantity: X(ID, "name", bw),
 * bw 1 where the Bouc-Wen benchmark draws it.  The schema's quantity list,
 * scene_boucwen.c's Q_ID values and its model's list of quantities are
 * generated from it. */
#define HY_SERIES_QUANTITIES(X)                  \
    X(OUTPUT, "output", 1)                       \
    X(INPUT, "input", 1)                         \
    X(OUTPUT_DB, "output-db", 1)                 \
    X(TRANSIENT_DB, "transient-db", 1)           \
    X(SPECTRUM, "spectrum", 1)                   \
    X(ENVELOPE, "envelope", 1)                   \
    X(SINC_INPUT, "sinc-input-error", 1)         \
    X(SINC_OUTPUT, "sinc-output-error", 1)       \
    X(MAGNETISATION, "magnetisation", 0)

/* What a value must look like. */
typedef enum hy_scene_kind {
    HY_KIND_NUMBER,       /* finite decimal number: 1, -2.5, 3e-4               */
    HY_KIND_INTEGER,      /* decimal integer: 12, -3                            */
    HY_KIND_BOOL,         /* true | false                                       */
    HY_KIND_ENUM,         /* one identifier from the key's list                 */
    HY_KIND_STRING,       /* "quoted text" (or one bare word)                   */
    HY_KIND_NAME,         /* identifier-like text: letters, digits, _ - .      */
    HY_KIND_PATH,         /* file path, resolved relative to the defining file  */
    HY_KIND_NUMBER_LIST,  /* 1, 10, 100                                         */
    HY_KIND_INTEGER_LIST, /* 0, 1, 2                                            */
    HY_KIND_ENUM_LIST,    /* svg, pdf                                           */
    HY_KIND_LENGTH,       /* 9pt, 0.4cm, 1in, 12px (bare number = pt)           */
    HY_KIND_LENGTH_PAIR,  /* 12cm, 9cm                                          */
    HY_KIND_COLOR,        /* Okabe-Ito index 1-8, its name, or #rrggbb          */
    HY_KIND_PAIR,         /* two numbers, first < second: 0, 4.6                */
    HY_KIND_LIMITS        /* a pair as above, or auto                           */
} hy_scene_kind;

/* Every number in a scene is 0 or at least this in magnitude (DBL_MIN, the
 * smallest normal double): subnormal numbers such as 4.9e-324 are refused. */
#define HY_SCENE_NUM_MIN 2.2250738585072014e-308

/* Flags of a key spec: which bounds apply and whether they are strict. */
enum {
    HY_SPEC_MIN = 1u << 0,      /* value >= min (or > min with MIN_EXCL)   */
    HY_SPEC_MAX = 1u << 1,      /* value <= max (or < max with MAX_EXCL)   */
    HY_SPEC_MIN_EXCL = 1u << 2,
    HY_SPEC_MAX_EXCL = 1u << 3,
    HY_SPEC_EVEN = 1u << 4      /* a list must hold an even count (pairs)  */
};

/* One key: its name, kind, allowed identifiers (NULL-terminated, for ENUM and
 * ENUM_LIST), bounds (for numbers, integers, list elements and lengths, whose
 * bound applies to the number before the unit), list length limits (0 = no
 * limit), default written as scene text (NULL = none), a one-line doc, and
 * for a quantity its symbol as the papers print it (markup: "u_{min,2}",
 * "σ_0"; NULL = none) and its unit ("Hz", "N s/m"; NULL = none or
 * dimensionless), which serve's controls show; for a key that hy_scene_decode
 * reads (hy_scene_decl.h), the offset of the field it fills in its section's
 * struct and that field's C type (HY_CTYPE_*; 0: the key is not decoded);
 * for a [model] key that one model declares in its own file
 * (hy_scene_model_rows.h), that model's kind (NULL: any kind's key). */
typedef struct hy_scene_key_spec {
    const char *name;
    hy_scene_kind kind;
    const char *const *enums;
    unsigned flags;
    double min, max;
    unsigned min_len, max_len;
    const char *def;
    const char *doc;
    const char *symbol;
    const char *unit;
    size_t field;
    int ctype;
    const char *model;
} hy_scene_key_spec;

/* One section: [name] or, when takes_name, [name LABEL]; repeatable sections
 * may occur once per distinct label. */
typedef struct hy_scene_section_spec {
    const char *name;
    int takes_name;
    int repeatable;
    const hy_scene_key_spec *keys;
    size_t nkeys;
    const char *doc;
} hy_scene_section_spec;

/* Returns the static table of sections and stores its length in *n. */
const hy_scene_section_spec *hy_scene_schema(size_t *n);

/* Returns the index of the section called name, or -1. */
int hy_scene_schema_section(const char *name);

/* Returns the index of key in section sec, or -1. */
int hy_scene_schema_key(int sec, const char *key);

/* Returns the human name of a kind ("number", "list of integers", ...). */
const char *hy_scene_kind_name(hy_scene_kind kind);

/* Writes the numeric range of k as text ("> 0", "in [36, 2400]", "in (0, 1]");
 * an empty string if unbounded. */
void hy_scene_range_text(const hy_scene_key_spec *k, char *buf, size_t n);

#endif
