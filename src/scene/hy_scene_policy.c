/* SPDX-License-Identifier: MIT */
/* hy_scene_policy.c: the one place where a scene's files are checked: includes and
 * input files below the scene's directory (or an --include-dir), regular files
 * with size caps, include counts, and the scene's output directory. */
#include "hy_scene_policy.h"

#include <errno.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "hy_file.h"
#include "hy_os.h"
#include "hy_scene_internal.h"
#include "hy_scene.h"

hy_scene_policy hy_scene_policy_default(void)
{
    hy_scene_policy p = {NULL, 0, HY_SCENE_WORK_DEFAULT};
    return p;
}

double hy_scene_policy_budget(const hy_scene_policy *pol)
{
    return pol && pol->max_work > 0 ? pol->max_work : HY_SCENE_WORK_DEFAULT;
}

/* Whether the real path real lies at or below the real directory root. */
static int below(const char *real, const char *root)
{
    size_t n = strlen(root);
    if (n == 1 && root[0] == '/')
        return real[0] == '/';
    return strncmp(real, root, n) == 0 && (real[n] == '/' || real[n] == '\0');
}

/* Whether real lies below the scene's directory or one of its include dirs. */
static int allowed(const hy_scene *s, const char *real)
{
    if (s->root && below(real, s->root))
        return 1;
    for (size_t i = 0; i < s->nincdirs; i++)
        if (below(real, s->incdirs[i]))
            return 1;
    return 0;
}

int hy__policy_roots(hy_scene *s, const char *top_dir, const hy_scene_policy *pol, size_t len,
                     hy_error *err)
{
    /* the real directory of the top file (of the directory if the name is no file);
     * NULL: nothing can be read */
    char *real = realpath(hy_scene_source(s), NULL), *slash = real ? strrchr(real, '/') : NULL;
    if (slash) {
        if (slash == real)
            slash[1] = '\0';
        else
            *slash = '\0';
        s->root = real;
    } else {
        free(real);
        s->root = realpath(top_dir, NULL);
    }
    s->inc_bytes = len;
    if (len > HY_SCENE_MAX_FILE_BYTES)
        return hy_error_set(err, HY_EINVAL, "%s: the scene is %zu bytes, more than the %u allowed",
                            hy_scene_source(s), len, HY_SCENE_MAX_FILE_BYTES);
    size_t n = pol ? pol->ninclude_dirs : 0;
    /* last of all: the scenes an install ships (an include such as
       "style.scene" of a copied paper scene is found there) */
    char inst[4200];
    int have_inst = !hy_file_installed(HY_INSTALLED_DATA, "scenes", inst, sizeof inst);
    if (!n && !have_inst)
        return HY_OK;
    s->incdirs = calloc(n + 1, sizeof *s->incdirs);
    if (!s->incdirs)
        return hy_error_set(err, HY_ENOMEM, "out of memory");
    for (size_t i = 0; i < n; i++) {
        struct stat st;
        const char *d = pol->include_dirs[i];
        if (stat(d, &st) || !S_ISDIR(st.st_mode))
            return hy_error_set(err, HY_EINVAL, "--include-dir %s: %s", d,
                                errno == ENOENT ? "no such directory" : "not a directory");
        if (!(s->incdirs[i] = realpath(d, NULL)))
            return hy_error_set(err, HY_EINVAL, "--include-dir %s: %s", d, strerror(errno));
        s->nincdirs = i + 1;
    }
    if (have_inst && (s->incdirs[n] = realpath(inst, NULL)))
        s->nincdirs = n + 1;
    return HY_OK;
}

static char *join(const char *dir, const char *rel)
{
    size_t a = strlen(dir), b = strlen(rel);
    char *p = malloc(a + b + 2);
    if (!p)
        return NULL;
    if (!strcmp(dir, "."))
        memcpy(p, rel, b + 1);
    else {
        memcpy(p, dir, a);
        p[a] = '/';
        memcpy(p + a + 1, rel, b + 1);
    }
    return p;
}

static int ends_with(const char *s, const char *tail)
{
    size_t n = strlen(s), m = strlen(tail);
    return n >= m && !strcmp(s + n - m, tail);
}

/* The first of dir/rel, incdir/rel... that exists (lstat), else dir/rel. */
static char *locate(const hy_scene *s, const char *dir, const char *rel)
{
    struct stat st;
    char *p = join(dir, rel);
    for (size_t i = 0; p && lstat(p, &st) && i < s->nincdirs; i++) {
        char *q = join(s->incdirs[i], rel);
        if (q && !lstat(q, &st)) {
            free(p);
            return q;
        }
        free(q);
    }
    return p;
}

int hy__policy_include(hy_scene *s, const char *dir, const char *rel, char **path, char **buf,
                       size_t *len, char **canon, char *why, size_t whysz)
{
    *path = *buf = *canon = NULL;
    *len = 0;
    char shown[32 * 4 + 4]; /* the name as written, at most 32 bytes, non-printables as \xNN */
    hy_file_shown(rel, strlen(rel), 32, shown, sizeof shown);
    if (rel[0] == '/') {
        snprintf(why, whysz, "include paths must be relative (to the including file's directory "
                             "or an --include-dir), got an absolute path");
        return HY_EINVAL;
    }
    if (!ends_with(rel, ".scene")) {
        snprintf(why, whysz, "an included file must be a scene file named *.scene, got '%s'", shown);
        return HY_EINVAL;
    }
    if (s->inc_files >= HY_SCENE_MAX_INCLUDES) {
        snprintf(why, whysz, "more than %d included files in one scene (repeats counted) at '%s'",
                 HY_SCENE_MAX_INCLUDES, shown);
        return HY_EINVAL;
    }
    if (!(*path = locate(s, dir, rel))) {
        snprintf(why, whysz, "out of memory");
        return HY_ENOMEM;
    }
    size_t left = HY_SCENE_MAX_TOTAL_BYTES - (s->inc_bytes < HY_SCENE_MAX_TOTAL_BYTES ? s->inc_bytes : HY_SCENE_MAX_TOTAL_BYTES);
    size_t cap = left < HY_SCENE_MAX_FILE_BYTES ? left : HY_SCENE_MAX_FILE_BYTES;
    char r[200];
    int e = hy_file_read(*path, HY_SCENE_MAX_FILE_BYTES, buf, len, canon, r, sizeof r);
    int rc = HY_OK;
    if (e == EISDIR)
        rc = HY_EINVAL, snprintf(why, whysz, "cannot include '%s': it is a directory, not a scene file", shown);
    else if (e == EFBIG)
        rc = HY_EINVAL, snprintf(why, whysz, "cannot include '%s': it is larger than the %u bytes allowed for one scene file", shown,
                                 HY_SCENE_MAX_FILE_BYTES);
    else if (e)
        rc = (e == EINVAL ? HY_EINVAL : HY_EIO),
        snprintf(why, whysz, "cannot read included file '%s': %s", shown, r);
    else if (!allowed(s, *canon))
        rc = HY_EINVAL, snprintf(why, whysz, "cannot include '%s': it lies outside the scene's directory%s "
                                 "(a scene reads only files below it)", shown, s->nincdirs ? " and every --include-dir" : "");
    else if (*len > cap)
        rc = HY_EINVAL, snprintf(why, whysz, "cannot include '%s': the scene and its includes pass %u bytes in all "
                                 "(repeats counted)", shown, HY_SCENE_MAX_TOTAL_BYTES);
    if (rc) {
        free(*buf);
        free(*canon);
        free(*path);
        *buf = *canon = *path = NULL;
        return rc;
    }
    s->inc_files++;
    s->inc_bytes += *len;
    return HY_OK;
}

int hy_scene_read_path(const hy_scene *s, const char *section, const char *name, const char *key,
                       char **buf, size_t *len, int *user, hy_error *err)
{
    return hy_scene_read_path_max(s, section, name, key, HY_INPUT_MAX_FILE_BYTES, buf, len, user, err);
}

int hy_scene_read_path_max(const hy_scene *s, const char *section, const char *name, const char *key, size_t max,
                           char **buf, size_t *len, int *user, hy_error *err)
{
    const char *path;
    hy_scene_loc loc = {NULL, 0, 0};
    *buf = NULL;
    *len = 0;
    if (hy_scene_get_str(s, section, name, key, &path) < 0)
        return hy_scene_error_at(s, section, name, key, err, HY_EINVAL, "'%s' needs a file name", key);
    hy_scene_get_loc(s, section, name, key, &loc);
    *user = loc.line == 0; /* --set: the user's own choice */
    char r[200], *real = NULL;
    int e = hy_file_read(path, max, buf, len, *user ? NULL : &real, r, sizeof r);
    if (e)
        return hy_scene_error_at(s, section, name, key, err, hy_file_status(e),
                                 "%s: cannot open input file: %s", path, r);
    if (!*user && !allowed(s, real)) {
        free(*buf);
        free(real);
        *buf = NULL;
        *len = 0;
        return hy_scene_error_at(s, section, name, key, err, HY_EINVAL,
                                 "'%s' lies outside the scene's directory%s; a scene reads only files below it",
                                 path, s->nincdirs ? " and every --include-dir" : "");
    }
    free(real);
    return HY_OK;
}

/* The directory part of the top scene's path as written ("." if none). */
static char *scene_dir(const hy_scene *s)
{
    return hy_path_dir(hy_scene_source(s));
}

/* dir normalised lexically ("a/./b/../c" -> "a/c"); -1 if '..' climbs above it. */
static int normalise(const char *dir, char *out, size_t size)
{
    size_t o = 0;
    out[0] = '\0';
    for (const char *p = dir; *p;) {
        const char *e = strchr(p, '/');
        size_t n = e ? (size_t)(e - p) : strlen(p);
        if (n == 2 && p[0] == '.' && p[1] == '.') {
            if (!o)
                return -1;
            while (o && out[o - 1] != '/')
                o--;
            if (o)
                o--;
            out[o] = '\0';
        } else if (n && !(n == 1 && p[0] == '.')) {
            if (o + n + 2 > size)
                return -2;
            if (o)
                out[o++] = '/';
            memcpy(out + o, p, n);
            o += n;
            out[o] = '\0';
        }
        p += n + (e != NULL);
    }
    return 0;
}

int hy_scene_output_dir_check(const hy_scene *s, const char *cli_dir, const char *dir, hy_error *err)
{
    hy_scene_loc loc;
    if (cli_dir || (hy_scene_get_loc(s, "output", NULL, "dir", &loc) && loc.line == 0))
        return HY_OK;
    /* every existing prefix of dir must stay below the scene's directory */
    char buf[PATH_MAX];
    snprintf(buf, sizeof buf, "%s", dir);
    for (char *p = buf + strlen(buf);; ) {
        char *real = realpath(buf, NULL);
        if (real) {
            int ok = s->root && below(real, s->root);
            free(real);
            if (!ok)
                return hy_scene_error_at(s, "output", NULL, "dir", err, HY_EINVAL,
                                         "the output directory %s leaves the scene's directory through a "
                                         "symbolic link; a scene writes only below its own directory", buf);
            return HY_OK;
        }
        p = strrchr(buf, '/');
        if (!p || p == buf)
            return HY_OK;
        *p = '\0';
    }
}

int hy_scene_output_dir(const hy_scene *s, const char *cli_dir, char **out, hy_error *err)
{
    const char *d = ".";
    hy_scene_loc loc = {NULL, 0, 0};
    *out = NULL;
    if (cli_dir) {
        *out = strdup(cli_dir);
        return *out ? HY_OK : hy_error_set(err, HY_ENOMEM, "out of memory");
    }
    hy_scene_get_str(s, "output", NULL, "dir", &d);
    int set = hy_scene_get_loc(s, "output", NULL, "dir", &loc);
    if (set && loc.line == 0) { /* --set output.dir=...: the user's choice, from the working directory */
        *out = strdup(d);
        return *out ? HY_OK : hy_error_set(err, HY_ENOMEM, "out of memory");
    }
    if (!d[0] || d[0] == '/')
        return hy_scene_error_at(s, "output", NULL, "dir", err, HY_EINVAL,
                                 "'dir' in [output] must be a relative directory below the scene's directory, got '%s'"
                                 " (an absolute path: write it with -o on the command line instead)", d);
    char norm[PATH_MAX];
    int n = normalise(d, norm, sizeof norm);
    if (n)
        return hy_scene_error_at(s, "output", NULL, "dir", err, HY_EINVAL,
                                 n == -1 ? "'dir' in [output] must stay below the scene's directory, got '%s' "
                                           "('..' climbs above it; use -o on the command line)"
                                         : "'dir' in [output] is too long: '%s'", d);
    char *base = scene_dir(s);
    if (!base)
        return hy_error_set(err, HY_ENOMEM, "out of memory");
    *out = norm[0] ? join(base, norm) : strdup(base);
    free(base);
    if (!*out)
        return hy_error_set(err, HY_ENOMEM, "out of memory");
    int rc = hy_scene_output_dir_check(s, NULL, *out, err);
    if (rc) {
        free(*out);
        *out = NULL;
    }
    return rc;
}
