/* SPDX-License-Identifier: MIT */
/* hy_scene_policy.h: what a scene may read and write, and how much it may ask for
 * (docs/SCENES.md, "Files a scene may read and write").
 *
 * A scene file is untrusted text.  Everything it names goes through this one
 * place: includes and `[input] file` are read by hy_scene_read_path and the
 * parser's include step (regular files only, below the scene's directory or an
 * --include-dir, with size caps), and `[output] dir` is resolved by
 * hy_scene_output_dir (relative, below the scene's directory).  What the user
 * names on the command line (-o, --set, --input) is the user's choice.
 *
 *     hy_scene_policy pol = hy_scene_policy_default();
 *     pol.include_dirs = dirs; pol.ninclude_dirs = n;      (--include-dir)
 *     pol.max_work = 1e10;                                 (--max-work)
 *     hy_scene_parse_file_policy(path, &pol, &s, &err);
 */
#ifndef HY_SCENE_POLICY_H
#define HY_SCENE_POLICY_H

#include <stddef.h>

#include "hy_input.h"
#include "hy_status.h"

typedef struct hy_scene hy_scene;

/* Caps (docs/SCENES.md states them). */
#define HY_SCENE_MAX_FILE_BYTES (4u << 20)       /* one scene or included file: 4 MiB        */
#define HY_SCENE_MAX_TOTAL_BYTES (16u << 20)     /* all files of one scene, repeats counted  */
#define HY_SCENE_MAX_INCLUDES 256                /* included files per scene, repeats counted */
#define HY_INPUT_MAX_FILE_BYTES HY_INPUT_FILE_MAX  /* an input (samples) file: 128 MiB (hy_input.h) */
#define HY_SCENE_WORK_DEFAULT 1e8                /* work budget of one scene (--max-work)    */

/* The user's command-line choices a scene is loaded with. */
typedef struct hy_scene_policy {
    const char *const *include_dirs; /* --include-dir roots, in search order (may be NULL) */
    size_t ninclude_dirs;
    double max_work;                 /* work budget; <= 0 means HY_SCENE_WORK_DEFAULT      */
} hy_scene_policy;

/* No include dirs, the default budget. */
hy_scene_policy hy_scene_policy_default(void);

/* The budget pol asks for (the default for NULL or max_work <= 0). */
double hy_scene_policy_budget(const hy_scene_policy *pol);

/* As hy_scene_parse_file, under pol (NULL: the default policy). */
int hy_scene_parse_file_policy(const char *path, const hy_scene_policy *pol, hy_scene **out,
                               hy_error *err);

/* As hy_scene_parse_buffer, under pol: text already read (by a caller that
 * opened the file once, e.g. hystviz serve) named name for messages, includes
 * and relative paths. */
int hy_scene_parse_buffer_policy(const char *name, const char *text, size_t len,
                                 const hy_scene_policy *pol, hy_scene **out, hy_error *err);

/* Reads the file named by the PATH key section[.name].key into *buf (NUL
 * terminated, caller frees) and *len.  A path written in a scene file must
 * lie below the scene's directory or an include dir; one set by --set is the
 * user's.  Regular files of at most HY_INPUT_MAX_FILE_BYTES only.  *user is
 * set to 1 for a --set path (messages may quote a short excerpt of it), 0 for
 * a scene's (nothing of its content may be quoted).  Errors name the key's
 * file:line:col. */
int hy_scene_read_path(const hy_scene *s, const char *section, const char *name, const char *key,
                       char **buf, size_t *len, int *user, hy_error *err);

/* As hy_scene_read_path with a cap of max bytes (a measured data file:
 * HY_TABLE_MAX_BYTES) instead of HY_INPUT_MAX_FILE_BYTES. */
int hy_scene_read_path_max(const hy_scene *s, const char *section, const char *name, const char *key, size_t max,
                           char **buf, size_t *len, int *user, hy_error *err);

/* The directory a scene's figures go to: cli_dir if not NULL (the user's
 * -o, unrestricted), else `[output] dir` resolved against the scene's
 * directory; a dir written in a scene must be relative and stay below that
 * directory (no '..' above it, no symlink out of it: checked on the
 * directories that exist).  *out is malloc'ed. */
int hy_scene_output_dir(const hy_scene *s, const char *cli_dir, char **out, hy_error *err);

/* After the directory exists: fails if its real path left the scene's
 * directory (a symlink planted on the way).  For cli_dir != NULL always OK. */
int hy_scene_output_dir_check(const hy_scene *s, const char *cli_dir, const char *dir,
                              hy_error *err);

#endif
