/* SPDX-License-Identifier: MIT */
/* hy_scene.h: scene files: parse, validate, override, query (format in docs/SCENES.md).
 *
 * A scene is an INI-like text file of [section] or [section NAME] headers and
 * `key = value` lines, validated against the table in hy_scene_schema.c.
 * Parse once, apply command-line overrides, then read typed values; a getter
 * falls back to the schema default and says whether the scene set the key:
 *
 *     hy_scene *s; hy_error err;
 *     if (hy_scene_parse_file("scenes/fig15.scene", &s, &err)) { puts(err.msg); return 1; }
 *     if (hy_scene_set(s, "series.ystar.style=dashed", &err)) { ... }
 *     double s0;
 *     if (hy_scene_get_num(s, "model", NULL, "sigma0", &s0) < 0) { ... no value ... }
 *     for (size_t i = 0; i < hy_scene_count(s, "series"); i++)
 *         draw(hy_scene_name_at(s, "series", i));
 *     hy_scene_free(s);
 *
 * Every error message is one sentence prefixed with `file:line:col:` (or
 * `--set section.key=value:` for an override).  No global state: scenes are
 * independent and may be parsed and freed repeatedly, from several threads
 * if each scene stays in one.  Numbers are read with strtod after a strict
 * syntax check, so LC_NUMERIC must stay "C" (the default).
 */
#ifndef HY_SCENE_H
#define HY_SCENE_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "hy_scene_schema.h"
#include "hy_status.h"

#include "hy_scene_types.h" /* hy_scene, hy_scene_loc, hy_scene_color, HY_SCENE_SET ... */

/* Parses the scene file at path and the files it includes into *out.
 * On error returns a status, leaves *out NULL and writes err. Caller frees. */
int hy_scene_parse_file(const char *path, hy_scene **out, hy_error *err);

/* As hy_scene_parse_file, from len bytes of text; name is shown in messages
 * and its directory is where relative includes and paths are looked up. */
int hy_scene_parse_buffer(const char *name, const char *text, size_t len, hy_scene **out,
                          hy_error *err);

/* Frees the scene and everything it owns; NULL is allowed. */
void hy_scene_free(hy_scene *s);

/* Applies one override "section.key=value" or "section.NAME.key=value",
 * parsed and validated like a scene line; it beats every value in the files.
 * On error the scene is unchanged. */
int hy_scene_set(hy_scene *s, const char *assignment, hy_error *err);

/* Notes the scene as it is now, so that hy_scene_restore can undo the
 * overrides applied after it (hystviz sweep parses a scene once and applies
 * each point's overrides to it).  A new mark replaces the old one.  Returns
 * HY_OK. */
int hy_scene_mark(hy_scene *s);

/* Undoes every hy_scene_set since hy_scene_mark: values, their locations,
 * sections the overrides created, the override names and the hash are as at
 * the mark, so the scene equals a fresh parse plus the overrides made before
 * the mark.  The mark stays.  Nothing happens without a mark. */
void hy_scene_restore(hy_scene *s);

/* The one parser of an override: splits "section[.NAME].key=value" (blanks
 * around the section, name and key trimmed) into malloc'd *sec, *name (NULL
 * without one) and *key, and *value pointing into a.  hy_scene_set applies
 * what it returns; whoever checks an override first (hystviz serve) checks
 * these parts, never the raw text.  On error all three are NULL or to be
 * freed (free(NULL) is fine either way). */
int hy_scene_set_split(const char *a, char **sec, char **name, char **key, const char **value,
                       hy_error *err);

/* 64-bit FNV-1a over the bytes of every file read (in reading order) and of
 * every override applied: equal hashes mean the same scene text. */
uint64_t hy_scene_hash(const hy_scene *s);

/* Typed getters.  name is the section's label for [series NAME]-like
 * sections and NULL otherwise.  Each returns HY_SCENE_SET, HY_SCENE_DEFAULT,
 * HY_SCENE_ABSENT or HY_SCENE_BADKEY (see above). */

/* A number (NUMBER kind), or an INTEGER converted. */
int hy_scene_get_num(const hy_scene *s, const char *section, const char *name,
                     const char *key, double *out);

/* An INTEGER. */
int hy_scene_get_int(const hy_scene *s, const char *section, const char *name,
                     const char *key, long *out);

/* A BOOL as 0 or 1. */
int hy_scene_get_bool(const hy_scene *s, const char *section, const char *name,
                      const char *key, int *out);

/* An ENUM: its index in the key's enum list and/or its text (either may be
 * NULL; the text is static). */
int hy_scene_get_enum(const hy_scene *s, const char *section, const char *name,
                      const char *key, int *index, const char **text);

/* A STRING, NAME or PATH (a PATH already resolved against the directory of
 * the file that set it); the text is owned by the scene. */
int hy_scene_get_str(const hy_scene *s, const char *section, const char *name,
                     const char *key, const char **out);

/* A NUMBER_LIST or INTEGER_LIST: *vals (owned by the scene) and *n; an
 * ENUM_LIST gives the indices of its identifiers in the key's enum list. */
int hy_scene_get_list(const hy_scene *s, const char *section, const char *name,
                      const char *key, const double **vals, size_t *n);

/* An ENUM_LIST: the i-th identifier (static text) of the list, for i < *n;
 * call with i = 0 to learn *n.  Returns as above, or HY_SCENE_BADKEY if i is
 * past the end of a non-empty list. */
int hy_scene_get_enum_at(const hy_scene *s, const char *section, const char *name,
                         const char *key, size_t i, const char **text, size_t *n);

/* A LENGTH in points (1in = 72pt = 2.54cm; px uses [figure] dpi). */
int hy_scene_get_length_pt(const hy_scene *s, const char *section, const char *name,
                           const char *key, double *out);

/* A LENGTH_PAIR in points. */
int hy_scene_get_length_pair_pt(const hy_scene *s, const char *section, const char *name,
                                const char *key, double out[2]);

/* A PAIR or LIMITS; *is_auto (may be NULL for PAIR) is 1 for `auto`, when
 * out[] is left untouched. */
int hy_scene_get_pair(const hy_scene *s, const char *section, const char *name,
                      const char *key, double out[2], int *is_auto);

/* A COLOR. */
int hy_scene_get_color(const hy_scene *s, const char *section, const char *name,
                       const char *key, hy_scene_color *out);

/* Number of sections of a kind present (0 or 1 for unnamed kinds). */
size_t hy_scene_count(const hy_scene *s, const char *section);

/* Label of the i-th named section of a kind in order of first appearance,
 * or NULL past the end (or for unnamed kinds). */
const char *hy_scene_name_at(const hy_scene *s, const char *section, size_t i);

/* Where a key was set (key NULL: where the section header first appeared).
 * Returns 1 and fills *loc, or 0 if not written in the scene. */
int hy_scene_get_loc(const hy_scene *s, const char *section, const char *name,
                     const char *key, hy_scene_loc *loc);

/* For semantic checks after parsing: writes "file:line:col: <message>" at the
 * location of the key (or section, or the scene file if neither was written)
 * into err and returns code.  The arguments may include err->msg (a core
 * error re-raised at its scene location). */
int hy_scene_error_at(const hy_scene *s, const char *section, const char *name,
                      const char *key, hy_error *err, int code, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 7, 8)))
#endif
    ;

/* Writes the effective scene (every value after includes and overrides, with
 * its origin as a comment; with defaults != 0 also every schema default) as
 * scene text that parses back to the same values (PATH values are written
 * resolved).  Returns HY_OK or HY_EIO if writing failed. */
int hy_scene_write(const hy_scene *s, FILE *f, int defaults);

/* What a scene's computation reads of [model] and [input] (the pipeline's
 * hy_scene_reads, scene_run.h, decides from the series). */
enum { HY_READS_MODEL = 1u << 0, HY_READS_G = 1u << 1, HY_READS_INPUT = 1u << 2 };

/* The longest key of [controls] main ("series.NAME.gamma"), with its NUL. */
#define HY_SCENE_KEY_MAX 96

/* The scene's main parameters: the keys [controls] main lists, as written
 * for --set without a value ("model.sigma0"), at most max of them, into
 * keys[0 .. *n-1]; *n = 0 when the scene lists none.  Each must name a
 * number or integer key of a section the scene has that has a value (set or
 * default); else HY_EINVAL with the message at the main line. */
int hy_scene_main_keys(const hy_scene *s, char (*keys)[HY_SCENE_KEY_MAX], size_t max, size_t *n, hy_error *err);

/* The longest override of a [preset NAME] set (as hystviz serve allows one). */
#define HY_SCENE_SET_MAX 300
#define HY_SCENE_PRESET_MAX 32   /* values of one preset, at most */

/* The overrides of the scene's [preset name]: its set split at ';' and
 * trimmed ("model.sigma0=1"), at most max, into sets[0 .. *n-1].  Each must
 * be written SECTION.key=VALUE or SECTION.NAME.key=VALUE with a section and
 * key of the schema; else HY_EINVAL with the message at the set line. */
int hy_scene_preset_sets(const hy_scene *s, const char *name, char (*sets)[HY_SCENE_SET_MAX], size_t max, size_t *n,
                         hy_error *err);

/* The name of the [param NAME] whose value the key reads (written `key =
 * $NAME`, docs/SCENES.md), owned by the scene, or NULL when the key holds its
 * own value (or is not set). */
const char *hy_scene_get_ref(const hy_scene *s, const char *section, const char *name, const char *key);

/* Writes text with each placeholder {section.key} or {section.NAME.key}
 * (a number, integer, identifier or name key of the scene) replaced by the
 * key's value as the scene has it now, overrides included, into *out
 * (malloc'ed; the caller frees).  Other braces stay as written ("y*_{u,k}").
 * A [figure] caption is checked at parse time (file:line:col); for other
 * text an unknown key or one without a value gives HY_EINVAL and err. */
int hy_scene_expand(const hy_scene *s, const char *text, char **out, hy_error *err);

/* The path or display name the scene was parsed from (owned by the scene). */
const char *hy_scene_source(const hy_scene *s);

#endif
