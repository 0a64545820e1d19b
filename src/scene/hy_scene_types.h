/* SPDX-License-Identifier: MIT */
/* hy_scene_types.h: the scene's small types, at the bottom of src/scene:
 * hy_scene.h (the parser and getters), hy_scene_schema.h (the table) and
 * hy_scene_decl.h (the decoded structs) include it, and it includes nothing of the scene,
 * so the decoded structs and the schema's rows do not depend on the parser's
 * header (tools/include_graph.py: no circle between files).
 */
#ifndef HY_SCENE_TYPES_H
#define HY_SCENE_TYPES_H

#include <stddef.h>

typedef struct hy_scene hy_scene;

/* Where a value was written: file (as opened, or "--set ..."), 1-based line
 * and column (line 0 for an override).  file lives as long as the scene. */
typedef struct hy_scene_loc {
    const char *file;
    int line;
    int col;
} hy_scene_loc;

/* A colour: components in [0, 1]; index is the Okabe-Ito index 1-8, or 0
 * for a #rrggbb colour. */
typedef struct hy_scene_color {
    double r, g, b;
    int index;
} hy_scene_color;

/* What a getter found. */
enum {
    HY_SCENE_SET = 1,      /* the scene (or an override) set the key        */
    HY_SCENE_DEFAULT = 0,  /* not set: *out holds the schema default        */
    HY_SCENE_ABSENT = -1,  /* not set and no default: *out untouched        */
    HY_SCENE_BADKEY = -2   /* no such section/key, or a getter of another kind */
};

/* The user's command-line choices a scene is loaded with (hy_scene_policy.h). */
typedef struct hy_scene_policy hy_scene_policy;

/* ---- the schema's row types (the table itself: hy_scene_schema.h) ---- */

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
    HY_SPEC_EVEN = 1u << 4,     /* a list must hold an even count (pairs)  */
    HY_SPEC_G = 1u << 5         /* a [model] key of the friction function
                                   g(v), read for data = g (HY_READS_G)    */
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
/* A number key's domain given the other keys, for serve's sliders (all zero:
 * none): where the scene's model takes inputs whose takers meet takers (the
 * model table's inputs column; 0: every model), the slider keeps strictly
 * above the value of key above and below that of below ("section.key") and,
 * with per (the other factor), on whole multiples of 1 / its value, these
 * three where [input] kind is kind (NULL: any); within [lo, hi] where lo < hi
 * (where the computation is known to work); work: the work estimate grows at
 * most in proportion to the key (the page keeps it below value x budget /
 * work). */
typedef struct hy_scene_domain {
    const char *kind;
    unsigned takers;
    const char *above, *below, *per;
    double lo, hi;
    int work;
} hy_scene_domain;
#define HY_SCENE_NO_DOMAIN {NULL, 0u, NULL, NULL, NULL, 0.0, 0.0, 0}

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
    hy_scene_domain dom;
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

#endif
