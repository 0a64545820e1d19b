/* SPDX-License-Identifier: MIT */
/* hy_scene_model_rows.h: a model's own [model] keys, declared in the model's file.
 *
 * A model file (src/pipeline/model_NAME.c, one line in the model table of
 * src/pipeline/meson.build) names its parameter struct and writes one row
 * per [model] key: symbol, unit, key, the struct field it fills, then kind,
 * enums, range, list lengths, default and doc as the schema's rows do
 * (each model_*.c with a three-column table line is a whole example):
 *
 *     typedef struct xx_par { double r, y0; } xx_par;
 *     #define PAR xx_par
 *     HY_MODEL_ROWS(xx, xx_par,
 *         HY_ROW("r", NULL, xx_r, r, HY_KIND_NUMBER, NULL, HY_POS, 0, 0, "1", "xx: half-width r"),
 *         HY_ROW("y_0", NULL, xx_y0, y0, HY_KIND_NUMBER, NULL, HY_NOLIM, 0, 0, "0", "xx: y at t = 0"));
 *     #ifndef HY_MODEL_ROWS_ONLY
 *     ... the stages: const xx_par *p = (const void *)m->par (hy_decl_model) ...
 *     #endif
 *
 * The build compiles the file twice: into the scene library with
 * HY_MODEL_ROWS_ONLY, where HY_MODEL_ROWS defines `hy_model_rows_<id>` and
 * the schema appends its rows to [model] (after the shared rows, in table
 * order, each marked with its kind); and into the pipeline, where
 * HY_MODEL_ROWS only declares it and the stages follow.  Decoding a scene of
 * that kind fills the struct (set or default) at hy_decl_model.par; a key of
 * another kind fills nothing (hy_decl_got: HY_SCENE_BADKEY) and keeps where
 * it was written (hy_decl_field.loc), for the model's refusal.
 */
#ifndef HY_SCENE_MODEL_ROWS_H
#define HY_SCENE_MODEL_ROWS_H

#include <stddef.h>

#include "hy_scene_decl.h"

/* A model's rows: n keys filling a struct of par_size bytes. */
typedef struct hy_model_rows {
    const hy_scene_key_spec *rows;
    size_t n;
    size_t par_size;
} hy_model_rows;

/* The flags, min, max of a row without bounds, > 0, >= 0. */
#define HY_NOLIM 0u, 0.0, 0.0
#define HY_POS (HY_SPEC_MIN | HY_SPEC_MIN_EXCL), 0.0, 0.0
#define HY_NONNEG HY_SPEC_MIN, 0.0, 0.0

/* One row: key `key` fills field `field` of the struct PAR (define PAR first). */
#define HY_ROW(...) HY_ROW_(__VA_ARGS__)
#define HY_ROW_(sym, unit, key, field, kind, enums, flags, lo, hi, nmin, nmax, def, doc)                       \
    {                                                                                                         \
        #key, kind, enums, flags, lo, hi, nmin, nmax, def, doc, sym, unit,                                    \
            offsetof(hy_decl_model, par) + offsetof(PAR, field), HY_CTYPE_OF(((PAR *)0)->field), NULL,        \
            HY_SCENE_NO_DOMAIN                                                                                \
    }

#ifdef HY_MODEL_ROWS_ONLY
#define HY_MODEL_ROWS(id, par, ...)                                                                           \
    extern const hy_model_rows hy_model_rows_##id;                                                            \
    static const hy_scene_key_spec id##_rows_[] = {__VA_ARGS__};                                             \
    _Static_assert(sizeof(par) <= HY_MODEL_PAR_MAX, #par " exceeds HY_MODEL_PAR_MAX (hy_scene_decl.h)");     \
    const hy_model_rows hy_model_rows_##id = {id##_rows_, sizeof id##_rows_ / sizeof id##_rows_[0], sizeof(par)}
#else
#define HY_MODEL_ROWS(id, par, ...) extern const hy_model_rows hy_model_rows_##id
#endif

#endif
