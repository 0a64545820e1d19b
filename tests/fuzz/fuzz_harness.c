/* SPDX-License-Identifier: MIT */
/* fuzz_harness.c: one fuzz input through the parser and the `data` path, in a file sandbox
 * (see fuzz_harness.h). */
#include "fuzz_harness.h"

#include "hy_config.h"

#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <gsl/gsl_errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "scene_model.h"
#include "scene_run.h"

/* ---- the sandbox --------------------------------------------------------- */

static char sb_dir[512];        /* the temporary directory, canonical          */
static size_t sb_len;
static int sb_on;               /* inside hy_fuzz_one: file operations checked  */
static unsigned long sb_refused;
static int last_stage;
static char last_msg[sizeof ((hy_error *)0)->msg];

/* Names libFuzzer gives the files it writes when an input fails (it writes
 * them from its crash, timeout and out-of-memory handlers, while the
 * sandbox is still on). */
static const char *const fuzzer_artifacts[] = {"crash-", "timeout-", "oom-", "leak-", "slow-unit-",
                                               "mismatch-", NULL};

/* A path the code under test may read: inside the directory once "." and ".."
 * parts are resolved (the directory holds no symbolic link, so resolving them
 * by the text is what the kernel would do). */
static int sb_readable(const char *path)
{
    if (!sb_on)
        return 1;
    if (!path || path[0] != '/')
        return 0;
    /* the build tree's marker (hy_file.c: a program in its build tree never
       looks in an install): read-only, written by meson, no scene names it */
    const char *base = strrchr(path, '/') + 1;
    if (!strcmp(base, HY_SOURCE_ROOT_FILE))
        return 1;
    char norm[4096];
    size_t n = 0;
    for (const char *p = path; *p;) {
        while (*p == '/')
            p++;
        const char *e = strchr(p, '/');
        if (!e)
            e = p + strlen(p);
        size_t len = (size_t)(e - p);
        if (len == 2 && p[0] == '.' && p[1] == '.') {
            while (n > 0 && norm[--n] != '/')
                ;
        } else if (len && !(len == 1 && p[0] == '.')) {
            if (n + 1 + len >= sizeof norm)
                return 0;
            norm[n++] = '/';
            memcpy(norm + n, p, len);
            n += len;
        }
        p = e;
    }
    norm[n] = '\0';
    /* the directory itself too: the scene policy resolves the scene's directory */
    return n >= sb_len && !strncmp(norm, sb_dir, sb_len) && (norm[sb_len] == '/' || norm[sb_len] == '\0');
}

static int sb_writable(const char *path)
{
    if (!sb_on)
        return 1;
    const char *base = path ? strrchr(path, '/') : NULL;
    base = base ? base + 1 : path;
    for (size_t i = 0; base && fuzzer_artifacts[i]; i++)
        if (!strncmp(base, fuzzer_artifacts[i], strlen(fuzzer_artifacts[i])))
            return 1;
    return 0;
}

static int sb_refuse(void)
{
    sb_refused++;
    errno = EACCES;
    return -1;
}

#ifdef O_TMPFILE
#define HY_O_TMPFILE O_TMPFILE
#else
#define HY_O_TMPFILE 0
#endif

static int open_writes(int flags)
{
    return (flags & O_ACCMODE) != O_RDONLY || (flags & (O_CREAT | O_TRUNC | O_APPEND)) != 0;
}

static int mode_writes(const char *mode)
{
    return mode && strpbrk(mode, "wa+") != NULL;
}

/* The link option -Wl,--wrap=NAME sends every call of NAME in the program to
 * __wrap_NAME; __real_NAME is the C library's. */
#define REAL(ret, name, ...)                                                                      \
    ret __real_##name(__VA_ARGS__);                                                               \
    ret __wrap_##name(__VA_ARGS__)

REAL(FILE *, fopen, const char *path, const char *mode);
FILE *__wrap_fopen(const char *path, const char *mode)
{
    if (mode_writes(mode) ? !sb_writable(path) : !sb_readable(path))
        return sb_refuse(), NULL;
    return __real_fopen(path, mode);
}

REAL(FILE *, fopen64, const char *path, const char *mode);
FILE *__wrap_fopen64(const char *path, const char *mode)
{
    if (mode_writes(mode) ? !sb_writable(path) : !sb_readable(path))
        return sb_refuse(), NULL;
    return __real_fopen64(path, mode);
}

REAL(FILE *, freopen, const char *path, const char *mode, FILE *f);
FILE *__wrap_freopen(const char *path, const char *mode, FILE *f)
{
    if (sb_on)
        return sb_refuse(), NULL;
    return __real_freopen(path, mode, f);
}

#define WRAP_OPEN(name)                                                                           \
    int __real_##name(const char *path, int flags, ...);                                          \
    int __wrap_##name(const char *path, int flags, ...)                                           \
    {                                                                                             \
        mode_t mode = 0;                                                                          \
        if (flags & (O_CREAT | HY_O_TMPFILE)) {                                                      \
            va_list ap;                                                                           \
            va_start(ap, flags);                                                                  \
            mode = (mode_t)va_arg(ap, unsigned);                                                  \
            va_end(ap);                                                                           \
        }                                                                                         \
        if (open_writes(flags) ? !sb_writable(path) : !sb_readable(path))                         \
            return sb_refuse();                                                                   \
        return __real_##name(path, flags, mode);                                                  \
    }
WRAP_OPEN(open)
WRAP_OPEN(open64)

#define WRAP_OPENAT(name)                                                                         \
    int __real_##name(int dirfd, const char *path, int flags, ...);                               \
    int __wrap_##name(int dirfd, const char *path, int flags, ...)                                \
    {                                                                                             \
        mode_t mode = 0;                                                                          \
        if (flags & (O_CREAT | HY_O_TMPFILE)) {                                                      \
            va_list ap;                                                                           \
            va_start(ap, flags);                                                                  \
            mode = (mode_t)va_arg(ap, unsigned);                                                  \
            va_end(ap);                                                                           \
        }                                                                                         \
        /* relative to a directory descriptor: the sandbox cannot tell where */                   \
        if ((path && path[0] != '/' && dirfd != AT_FDCWD && sb_on) ||                             \
            (open_writes(flags) ? !sb_writable(path) : !sb_readable(path)))                       \
            return sb_refuse();                                                                   \
        return __real_##name(dirfd, path, flags, mode);                                           \
    }
WRAP_OPENAT(openat)
WRAP_OPENAT(openat64)

REAL(char *, realpath, const char *path, char *resolved);
char *__wrap_realpath(const char *path, char *resolved)
{
    if (!sb_readable(path))
        return sb_refuse(), NULL;
    return __real_realpath(path, resolved);
}

REAL(DIR *, opendir, const char *path);
DIR *__wrap_opendir(const char *path)
{
    if (!sb_readable(path))
        return sb_refuse(), NULL;
    return __real_opendir(path);
}

#define WRAP_READ(ret, name, T2)                                                                  \
    ret __real_##name(const char *path, T2 a);                                                    \
    ret __wrap_##name(const char *path, T2 a)                                                     \
    {                                                                                             \
        if (!sb_readable(path))                                                                   \
            return sb_refuse();                                                                   \
        return __real_##name(path, a);                                                            \
    }
WRAP_READ(int, stat, struct stat *)
WRAP_READ(int, lstat, struct stat *)
WRAP_READ(int, access, int)

int __real_fstatat(int dirfd, const char *path, struct stat *st, int flags);
int __wrap_fstatat(int dirfd, const char *path, struct stat *st, int flags)
{
    if (sb_on && path && path[0] && (path[0] != '/' || !sb_readable(path)))
        return sb_refuse();
    return __real_fstatat(dirfd, path, st, flags);
}

/* Whatever creates, removes or changes a file: refused while the sandbox is on. */
#define WRAP_WRITE(name, params, args)                                                            \
    int __real_##name params;                                                                     \
    int __wrap_##name params                                                                      \
    {                                                                                             \
        if (sb_on)                                                                                \
            return sb_refuse();                                                                   \
        return __real_##name args;                                                                \
    }
WRAP_WRITE(mkdir, (const char *p, mode_t m), (p, m))
WRAP_WRITE(mkdirat, (int d, const char *p, mode_t m), (d, p, m))
WRAP_WRITE(unlink, (const char *p), (p))
WRAP_WRITE(unlinkat, (int d, const char *p, int f), (d, p, f))
WRAP_WRITE(rmdir, (const char *p), (p))
WRAP_WRITE(remove, (const char *p), (p))
WRAP_WRITE(rename, (const char *a, const char *b), (a, b))
WRAP_WRITE(renameat, (int d, const char *a, int e, const char *b), (d, a, e, b))
WRAP_WRITE(mkstemp, (char *t), (t))
WRAP_WRITE(mkostemp, (char *t, int f), (t, f))
WRAP_WRITE(mkstemps, (char *t, int n), (t, n))
WRAP_WRITE(creat, (const char *p, mode_t m), (p, m))
WRAP_WRITE(symlink, (const char *a, const char *b), (a, b))
WRAP_WRITE(link, (const char *a, const char *b), (a, b))
WRAP_WRITE(truncate, (const char *p, off_t n), (p, n))
WRAP_WRITE(chmod, (const char *p, mode_t m), (p, m))
WRAP_WRITE(mkfifo, (const char *p, mode_t m), (p, m))

/* ---- the temporary directory -------------------------------------------- */

/* The files includes and [input] file may find (names also in scene.dict). */
static const struct {
    const char *name, *text;
} fixed_files[] = {
    {"style.scene", "# a shared look, as scenes/style.scene\n[figure]\nsize = 12cm, 9cm\ndpi = 200\n"
                    "font = \"DejaVu Sans\"\nfontsize = 9pt\nlegend = best\n\n[output]\n"
                    "formats = svg, pdf, png\ndir = \"gallery\"\n"},
    {"part.scene", "include \"style.scene\"\n[compute]\npoints = 50\ncycles = 2\n"},
    {"self.scene", "[model]\nkind = dahl\ninclude \"self.scene\"\n"},
    {"sub/inner.scene", "[input]\nkind = file\nfile = \"v.txt\"\n"},
    {"sub/v.txt", "0 1\n0.5 -1\n1 1\n"},
    {"u.txt", "0 0\n0.25 0.5\n0.5 1\n0.75 0.5\n1 0\n1.25 -0.5\n1.5 -1\n1.75 -0.5\n2 0\n"},
    {"u1.txt", "0\n1\n0.5\n-1\n0.25\n0\n"},
    {"bad.txt", "0 0\n0.5 1\nx y\n"},
    {"empty.txt", ""},
};

static void remove_dir(void)
{
    if (!sb_len)
        return;
    int was = sb_on;
    sb_on = 0;
    char path[600];
    for (size_t i = sizeof fixed_files / sizeof *fixed_files; i-- > 0;) {
        snprintf(path, sizeof path, "%s/%s", sb_dir, fixed_files[i].name);
        unlink(path);
    }
    snprintf(path, sizeof path, "%s/fuzz.scene", sb_dir);
    unlink(path);
    snprintf(path, sizeof path, "%s/sub", sb_dir);
    rmdir(path);
    rmdir(sb_dir);
    sb_on = was;
}

int hy_fuzz_init(void)
{
    if (sb_len)
        return 0;
    const char *tmp = getenv("TMPDIR");
    char templ[480];
    snprintf(templ, sizeof templ, "%s/hyfuzz.XXXXXX", tmp && tmp[0] == '/' ? tmp : "/tmp");
    char canon[4096];
    if (!mkdtemp(templ) || !realpath(templ, canon) || strlen(canon) >= sizeof sb_dir) {
        fprintf(stderr, "hy_fuzz: cannot create a temporary directory from %s: %s\n", templ, strerror(errno));
        return -1;
    }
    sb_len = strlen(canon);
    memcpy(sb_dir, canon, sb_len + 1);
    atexit(remove_dir);
    char path[600];
    snprintf(path, sizeof path, "%s/sub", sb_dir);
    int rc = mkdir(path, 0700);
    for (size_t i = 0; !rc && i < sizeof fixed_files / sizeof *fixed_files; i++) {
        snprintf(path, sizeof path, "%s/%s", sb_dir, fixed_files[i].name);
        FILE *f = fopen(path, "w");
        rc = !f || fputs(fixed_files[i].text, f) == EOF;
        if (f)
            rc |= fclose(f) != 0;
    }
    if (rc) {
        fprintf(stderr, "hy_fuzz: cannot write %s: %s\n", path, strerror(errno));
        return -1;
    }
    return 0;
}

const char *hy_fuzz_dir(void)
{
    return sb_dir;
}

unsigned long hy_fuzz_refused(void)
{
    return sb_refused;
}

int hy_fuzz_stage(void)
{
    return last_stage;
}

const char *hy_fuzz_message(void)
{
    return last_msg;
}

/* ---- invariants ---------------------------------------------------------- */

static void broken(const char *what, const char *detail)
{
    sb_on = 0;
    fprintf(stderr, "hy_fuzz: invariant broken: %s%s%s\n", what, detail ? ": " : "", detail ? detail : "");
    abort();
}

/* What err holds before each call: a message that still contains it was
 * never written by the call (issue 20 item 4: an unset message printed).
 * It starts with bytes no message can hold (a quoted scene string shows
 * them as \x01\xff), so a scene that contains the words, as the fuzzer
 * learns them from this comparison, is not taken for the mark. */
#define UNSET_MARK "\x01\xff[hy_fuzz: message not set]"

static void poison(hy_error *err)
{
    snprintf(err->msg, sizeof err->msg, "%s", UNSET_MARK);
}

/* Whether s is text a terminal shows as it is: UTF-8 without control
 * characters (C0, DEL, C1). */
static int is_text(const char *s)
{
    const unsigned char *p = (const unsigned char *)s;
    while (*p) {
        if (*p < 0x20 || *p == 0x7f)
            return 0;
        if (*p < 0x80) {
            p++;
            continue;
        }
        int n = (*p & 0xe0) == 0xc0 ? 1 : (*p & 0xf0) == 0xe0 ? 2 : (*p & 0xf8) == 0xf0 ? 3 : -1;
        if (n < 0 || *p < 0xc2 || *p > 0xf4 || (*p == 0xc2 && p[1] < 0xa0))
            return 0; /* a bad lead byte or overlong form, or a C1 control */
        for (int k = 1; k <= n; k++)
            if ((p[k] & 0xc0) != 0x80)
                return 0;
        p += n + 1;
    }
    return 1;
}

/* A failed call must say why: a message that does not end at a colon,
 * written by the call, and text (no control characters, valid UTF-8). */
static void check_message(int rc, const hy_error *err, const char *stage)
{
    if (rc)
        snprintf(last_msg, sizeof last_msg, "%.*s", (int)sizeof err->msg - 1, err->msg);
    if (!rc)
        return;
    if (!memchr(err->msg, '\0', sizeof err->msg))
        broken("unterminated error message", stage);
    if (strstr(err->msg, UNSET_MARK)) {
        fprintf(stderr, "hy_fuzz: %s: message '%s'\n", stage, err->msg);
        broken("an error message holds text the failing call never wrote", stage);
    }
    if (!is_text(err->msg)) {
        fprintf(stderr, "hy_fuzz: %s: message of %zu bytes with control characters or invalid UTF-8\n", stage,
                strlen(err->msg));
        broken("an error message is not text", stage);
    }
    /* "file:3:1: " with nothing after it is as empty as "" (a message that
     * fills the buffer was cut, perhaps after a colon: not judged) */
    size_t n = strlen(err->msg);
    if (n == sizeof err->msg - 1)
        return;
    while (n && (err->msg[n - 1] == ' ' || err->msg[n - 1] == '\n'))
        n--;
    if (!n || err->msg[n - 1] == ':') {
        fprintf(stderr, "hy_fuzz: %s: message '%s'\n", stage, err->msg);
        broken("empty error message (nothing after the location)", stage);
    }
}

/* The effective scene as text, without the origin comments (which name
 * where each value came from and so differ between the two parses). */
static char *written(const hy_scene *s, size_t *len)
{
    char *buf = NULL;
    FILE *f = open_memstream(&buf, len);
    if (!f)
        return NULL;
    int rc = hy_scene_write(s, f, 0);
    if (fclose(f) || rc) {
        free(buf);
        return NULL;
    }
    size_t o = 0;
    for (char *line = buf; *line;) {
        char *nl = strchr(line, '\n'), *next = nl ? nl + 1 : line + strlen(line);
        char *eol = nl ? nl : next, *end = eol;
        for (char *c = line; c + 6 <= eol; c++) /* the last "    # " starts the comment */
            if (!memcmp(c, "    # ", 6))
                end = c;
        if (line[0] == '#') /* "# effective scene of NAME" */
            end = line;
        memmove(buf + o, line, (size_t)(end - line));
        o += (size_t)(end - line);
        buf[o++] = '\n';
        line = next;
    }
    buf[o] = '\0';
    *len = o;
    return buf;
}

/* hy_scene_write's promise: the text parses back to the same values. */
static void check_round_trip(const hy_scene *s, const char *name)
{
    size_t n1 = 0, n2 = 0;
    char *t1 = written(s, &n1);
    if (!t1)
        return; /* out of memory */
    hy_scene *s2;
    hy_error err;
    if (hy_scene_parse_buffer(name, t1, n1, &s2, &err)) {
        fprintf(stderr, "%s", t1);
        free(t1);
        broken("the written effective scene does not parse", err.msg);
    }
    char *t2 = written(s2, &n2);
    hy_scene_free(s2);
    if (t2 && (n1 != n2 || memcmp(t1, t2, n1))) {
        fprintf(stderr, "first:\n%s\nsecond:\n%s", t1, t2);
        free(t1);
        free(t2);
        broken("the written effective scene changes when parsed and written again", NULL);
    }
    free(t1);
    free(t2);
}

/* ---- the work cap -------------------------------------------------------- */

static double num(const hy_scene *s, const char *sec, const char *key, double dflt)
{
    double v;
    return hy_scene_get_num(s, sec, NULL, key, &v) >= 0 ? v : dflt;
}

static double integer(const hy_scene *s, const char *sec, const char *key, long dflt)
{
    long v;
    return (double)(hy_scene_get_int(s, sec, NULL, key, &v) >= 0 ? v : dflt);
}

/* Whether the loaded scene's computation is small enough (an estimate of the
 * samples computed, from the keys that scale it). */
static int within_cap(const hy_scene_run *r)
{
    const hy_scene *s = r->scene;
    if (r->mtype == &hy_scene_model_boucwen) {
        int idx = 0;
        const char *kind = "sine", *dec = "staged";
        hy_scene_get_enum(s, "input", NULL, "kind", &idx, &kind);
        hy_scene_get_enum(s, "compute", NULL, "decimate", &idx, &dec);
        double fs = num(s, "input", "fs", 750), band[2] = {5, 150}, nd, periods;
        hy_scene_get_pair(s, "input", NULL, "band", band, NULL);
        if (!strcmp(kind, "multisine"))
            nd = integer(s, "input", "samples", 8192);
        else if (!strcmp(kind, "sweep"))
            nd = fabs(band[1] - band[0]) / (num(s, "input", "rate", 10) / 60.0) * fs;
        else
            nd = num(s, "input", "period", 2) * fs;
        periods = strcmp(kind, "sweep") ? integer(s, "compute", "cycles", 1) + integer(s, "compute", "settle", 0) +
                                              (strcmp(dec, "none") != 0)
                                        : 1;
        double total = periods * nd * integer(s, "compute", "upsample", 20);
        return isfinite(total) && total <= HY_FUZZ_MAX_BW;
    }
    double T = r->input.period, span[2] = {0, 0};
    int is_auto = 1;
    double periods = integer(s, "compute", "cycles", 1);
    if (hy_scene_get_pair(s, "compute", NULL, "tspan", span, &is_auto) == HY_SCENE_SET && !is_auto)
        periods = (span[1] - span[0]) / T;
    double per = integer(s, "compute", "points", 2000);
    double ns = (double)hy_scene_count(s, "series");
    /* the grid for every solve and series, plus up to 64 loop pieces of a period each */
    double total = per * fmax(1.0, periods) * (ns + 1) + per * 64 * ns;
    return isfinite(total) && total <= HY_FUZZ_MAX_POINTS;
}

/* ---- one input ----------------------------------------------------------- */

static int write_scene(const char *path, const uint8_t *data, size_t size)
{
    FILE *f = fopen(path, "wb");
    if (!f)
        return -1;
    int bad = size && fwrite(data, 1, size, f) != size;
    return fclose(f) || bad ? -1 : 0;
}

int hy_fuzz_one(const uint8_t *data, size_t size)
{
    last_stage = -1;
    last_msg[0] = '\0';
    if (hy_fuzz_init())
        abort();
    if (size > HY_FUZZ_MAX_BYTES)
        return 0;
    gsl_set_error_handler_off();
    char path[600];
    snprintf(path, sizeof path, "%s/fuzz.scene", sb_dir);

    /* the parser alone, from memory */
    sb_on = 1;
    hy_scene *s = NULL;
    hy_error err;
    memset(&err, 0, sizeof err);
    poison(&err);
    int rc = hy_scene_parse_buffer(path, (const char *)data, size, &s, &err);
    check_message(rc, &err, "parse");
    last_stage = rc ? 0 : 1;
    if (!rc) {
        check_round_trip(s, path);
        hy_scene_free(s);
    }
    sb_on = 0;
    if (rc)
        return 0;

    /* the `data` path, from the scene saved as the directory's only scene */
    if (write_scene(path, data, size)) {
        fprintf(stderr, "hy_fuzz: cannot write %s: %s\n", path, strerror(errno));
        abort();
    }
    sb_on = 1;
    hy_scene_run run;
    poison(&err);
    rc = hy_scene_run_load(&run, path, NULL, 0, &err);
    check_message(rc, &err, "load");
    if (!rc) {
        last_stage = 2;
        if (!within_cap(&run)) {
            last_stage = -1;
            hy_scene_run_free(&run);
            sb_on = 0;
            return 0;
        }
        poison(&err);
        rc = hy_scene_run_compute(&run, NULL, &err);
        check_message(rc, &err, "compute");
        if (!rc) {
            char *csv = NULL;
            size_t len = 0;
            FILE *f = open_memstream(&csv, &len);
            if (f) {
                poison(&err);
                rc = hy_scene_run_data(&run, f, &err);
                check_message(rc, &err, "data");
                fclose(f);
                if (!rc)
                    last_stage = 3;
                if (!rc && (len < 11 || strncmp(csv, "series,x,y\n", 11)))
                    broken("the CSV does not start with its header", NULL);
            }
            free(csv);
        }
        hy_scene_run_free(&run);
    }
    sb_on = 0;
    return 0;
}
