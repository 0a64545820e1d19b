/* SPDX-License-Identifier: MIT */
/* serve_util.h: pieces of `hystviz serve` that need no HTTP library (and are
 * tested alone): a growable text buffer with JSON escaping, scene names,
 * the controls of a scene, override checks, shell quoting and "save as new
 * scene". */
#ifndef HY_SERVE_UTIL_H
#define HY_SERVE_UTIL_H

#include <stddef.h>

#include "hy_scene.h"
#include "hy_scene_decl.h"
#include "hy_status.h"

/* A growable NUL-terminated buffer; oom is set once an append failed. */
typedef struct sv_buf {
    char *s;
    size_t len, cap;
    int oom;
} sv_buf;

void sv_add(sv_buf *b, const char *s, size_t n);
void sv_puts(sv_buf *b, const char *s);
void sv_printf(sv_buf *b, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
/* s as a JSON string with its quotes. */
void sv_json(sv_buf *b, const char *s);
/* s quoted for a POSIX shell when it needs it (single quotes). */
void sv_shell(sv_buf *b, const char *s);
/* The shortest %.Ng (N = 1..17) that reads back as v. */
void sv_num(sv_buf *b, double v);

/* Whether name is a scene file name that may be served: letters, digits,
 * '_', '-', '.', not starting with '.', ending in ".scene", at most 200
 * bytes (so no '/', no "..", no NUL). */
int sv_scene_name_ok(const char *name);

/* Checks an override "section.key=value" or "section.NAME.key=value" that a
 * page may send: at most 300 bytes, split by hy_scene_set_split (the parser
 * the override itself goes through), and its section and key kind on the
 * allow-list (numbers, switches, choices, lengths, colours of [model],
 * [input], [compute], [series], [figure], [annotation]; never a PATH or text).
 * Returns HY_OK or HY_EINVAL with a message. */
int sv_set_ok(const char *set, hy_error *err);

/* The sections a page may set keys of, as text for messages and --help. */
const char *sv_settable_sections(void);

/* Appends the JSON array of the scene's numeric controls: for every NUMBER
 * or INTEGER key the scene sets in [model], [input], [compute] and its
 * [series NAME] sections, and the model kind's parameters and a bimodal
 * input's extrema (with their defaults), leaving out the [model] and
 * [input] keys the computation does not read (reads: the HY_READS_* bits of hy_scene_reads, which the caller passes):
 *   {"key":"input.umin2","value":"0.5","set":true,"int":false,
 *    "lo":0,"hi":1,"log":false,"range":"","doc":"...","sym":"u_{min,2}",
 *    "unit":"","main":2,"above":"input.umin1","below":"input.umax1"}
 * sym and unit come from the schema; main is the key's place (1-9) in the
 * scene's [controls] main, 0 if not listed; above/below name the keys whose
 * current values bound this one strictly, per the key whose inverse is the
 * step (period x fs whole).  The values come from d, s decoded
 * (hy_scene_decode_fill); s gives only the [controls] main keys. */
void sv_controls_json(sv_buf *b, const hy_scene *s, const hy_scene_doc *d, unsigned reads);

/* Appends the JSON array of the scene's [preset NAME] sections, in file
 * order: {"name":"fig16","label":"Fig. 16: sigma0 = 1","sets":["model.sigma0=1",...]};
 * a preset whose set is malformed is left out (the render refuses the scene).
 * d is s decoded; s splits each preset's set text. */
void sv_presets_json(sv_buf *b, const hy_scene *s, const hy_scene_doc *d);

/* The text of a new scene: the original text with every override written in
 * (a key the file sets is replaced on its line, a key it does not set goes
 * under its section's header, or into a new section at the end) and
 * [output] name = out_name.  s is the original scene parsed from path (not
 * overridden).  Returns malloc'd text or NULL with err set. */
char *sv_scene_with_sets(const hy_scene *s, const char *path, const char *text, char *const *sets, size_t nsets,
                         const char *out_name, hy_error *err);

/* Writes text to path atomically (a temporary name in the same directory,
 * then link(2)), never replacing an existing file: HY_EINVAL if path exists,
 * HY_EIO on failure; no partial file either way. */
int sv_write_new(const char *path, const char *text, size_t len, hy_error *err);

/* Reads the scene file name (sv_scene_name_ok, one component) of the
 * directory dirfd through one descriptor: opened beneath dirfd (openat2
 * RESOLVE_BENEATH, else O_NOFOLLOW), checked with fstat to be a regular file
 * of at most max bytes, and read through it, so no link swapped in between a
 * check and the read can redirect it.  Returns malloc'd NUL-terminated text
 * or NULL with errno set (ENOENT, ELOOP, EXDEV, EINVAL not regular, EFBIG). */
char *sv_read_beneath(int dirfd, const char *name, size_t max, size_t *len);

/* Reads a whole (small) file; NULL on error (errno set). */
char *sv_read_file(const char *path, size_t max, size_t *len);

#endif
