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
#include "hy_scene_types.h"

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
 * model_boucwen.c's Q_ID values and its model's list of quantities are
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

/* The [input] kinds, one line per kind: X(ID, "name", takers), takers the
 * models that take it: HY_INPUT_OTHERS every model but the Bouc-Wen
 * oscillator, HY_INPUT_ALL every model, HY_INPUT_BOUCWEN the Bouc-Wen
 * oscillator alone (a force).  The schema's [input] kind list, the
 * HY_INPUT_<ID> values (the index decode gives) and the pipeline's dispatch
 * on them (scene_run.c, model_boucwen.c) and each model table
 * entry's inputs column (scene_model.h) are generated from it. */
#define HY_INPUT_OTHERS 1
#define HY_INPUT_ALL 3
#define HY_INPUT_BOUCWEN 2
#define HY_INPUT_KINDS(X)                         \
    X(BIMODAL, "bimodal", HY_INPUT_OTHERS)        \
    X(MULTIMODAL, "multimodal", HY_INPUT_OTHERS)  \
    X(TRIANGLE, "triangle", HY_INPUT_OTHERS)      \
    X(SINE, "sine", HY_INPUT_ALL)                 \
    X(PWL, "pwl", HY_INPUT_OTHERS)                \
    X(FILE, "file", HY_INPUT_OTHERS)              \
    X(MULTISINE, "multisine", HY_INPUT_BOUCWEN)   \
    X(SWEEP, "sweep", HY_INPUT_BOUCWEN)           \
    X(DATA, "data", HY_INPUT_OTHERS)
#define HY__INPUT_ID(id, name, takers) HY_INPUT_##id,
enum { HY_INPUT_KINDS(HY__INPUT_ID) HY_INPUT_KIND_COUNT };
#undef HY__INPUT_ID

/* Which models take input kind (an HY_INPUT_* value): HY_INPUT_OTHERS, _ALL
 * or _BOUCWEN; 0 for a value that is no kind. */
static inline int hy_input_kind_takers(int kind)
{
#define HY__INPUT_TAKERS(id, name, takers) takers,
    static const int takers[] = {HY_INPUT_KINDS(HY__INPUT_TAKERS)};
#undef HY__INPUT_TAKERS
    return kind >= 0 && kind < HY_INPUT_KIND_COUNT ? takers[kind] : 0;
}

/* hy_scene_kind, the key flags, hy_scene_key_spec and hy_scene_section_spec:
 * hy_scene_types.h (the bottom of src/scene: the decoded structs use them). */

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
