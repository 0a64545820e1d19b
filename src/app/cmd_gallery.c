/* SPDX-License-Identifier: MIT */
/* cmd_gallery.c: `hystviz gallery`: renders every figure scene of a directory
 * with a pool of POSIX threads, skips scenes whose content hash (hy_scene_hash,
 * includes and program version folded in) matches the manifest, and writes a
 * static index.html (DESIGN.md: "gallery index"). */
#include "cmd_gallery.h"

#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <gsl/gsl_errno.h>
#include <inttypes.h>
#include <math.h>
#include <pthread.h>
#include <signal.h>
#include <spawn.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "hy_config.h"
#include "anim_names.h"
#include "cli_util.h"
#include "export_anim.h"
#include "hy_child.h"
#include "hy_file.h"
#include "hy_grid.h"
#include "hy_jobs.h"
#include "hy_os.h"
#include "hy_out.h"
#include "scene_run.h"

static const char gallery_help[] =
    "usage: hystviz gallery [-j N] [--scenes DIR] [-o DIR] [--force] [--data] [--times] [--quiet]\n"
    "                       [--include-dir DIR]... [--max-work N]\n"
    "                       [--shard K/N | --merge]\n"
    "\n"
    "Renders every figure scene DIR/*.scene (files without a [series] or [panel] section,\n"
    "such as style.scene, are includes, not figures) into the gallery directory,\n"
    "in the formats each scene asks for (its [output] dir is ignored), and writes\n"
    "an index.html there.  A scene whose text, included files and hystviz version\n"
    "are unchanged since the last run (gallery/.manifest) and whose outputs exist\n"
    "is not rendered again.  A failing scene is reported as file:line:col, keeps\n"
    "its previous outputs, is retried next time and makes the exit status 1.\n"
    "A scene file name with a control character is refused before anything is\n"
    "rendered or written (exit 2).\n"
    "\n"
    "\n";

enum { OPT_SCENES = CLI_FIRST, OPT_OUT, OPT_FORCE, OPT_DATA, OPT_TIMES, OPT_NO_TIMES, OPT_QUIET, OPT_SHARD, OPT_MERGE };
static const cli_opt gallery_opts[] = {
    {.group = cli_jobs_opts},
    {"scenes", 0, "DIR", "where the scenes are (default: scenes, or the papers' scenes\n"
     "an install ships, PREFIX/share/hystviz/scenes, when there is\n"
     "no scenes directory here)", OPT_SCENES, 0, NULL, NULL, NULL},
    {"output", 'o', "DIR", "the gallery directory (default: gallery)", OPT_OUT, 0, NULL, NULL, NULL},
    {"force", 0, NULL, "render every scene, changed or not", OPT_FORCE, 0, NULL, NULL, NULL},
    {"data", 0, NULL, "also write NAME.csv (hystviz data) per figure", OPT_DATA, 0, NULL, NULL, NULL},
    {"times", 0, NULL, "add render times to index.html (off by default: the\n"
     "committed page stays byte-stable)", OPT_TIMES, 0, NULL, NULL, NULL},
    {"no-times", 0, NULL, "no render times (the default)", OPT_NO_TIMES, 0, NULL, NULL, NULL},
    {"quiet", 'q', NULL, "print only errors (no progress, no summary)", OPT_QUIET, 0, NULL, NULL, NULL},
    {.group = cli_policy_opts},
    {"shard", 0, "K/N", "render only figure scenes number K, K+N, K+2N, ... (in file\n"
     "name order) and write their records to DIR/.manifest.shard-K-of-N\n"
     "instead of the manifest and index.html (0 <= K < N)", OPT_SHARD, 0, NULL, NULL, NULL},
    {"merge", 0, NULL, "join the N shard records into DIR/.manifest and index.html, as\n"
     "the unsharded run writes them; refused, with the missing\n"
     "shards listed, unless all N are there for the same scenes", OPT_MERGE, 0, NULL, NULL, NULL},
    {0},
};
static const cli_cmd gallery_cli = {"gallery", gallery_help, NULL, NULL, gallery_opts};

enum { J_SKIP, J_UNCHANGED, J_PENDING, J_RENDERED, J_FAILED };

typedef struct opts {
    const char *scenes, *out;
    long jobs;
    int force, data, times, quiet, progress;
    hy_scene_policy pol;      /* --include-dir, --max-work */
    const char *dirs[64];
    long shard_k, shard_n; /* --shard K/N (shard_n 0: unsharded) */
    int merge;             /* --merge                            */
    char installed[4200];  /* PREFIX/share/hystviz/scenes          */
} opts;

/* One manifest line: what the last good render of a scene produced. */
typedef struct entry {
    char *scene;    /* scene file name                               */
    char key[17];   /* hex hash of scene text, includes, version     */
    int failed;     /* the last attempt failed: render again         */
    double seconds; /* render time of the last good render           */
    double err;     /* max error against the exact answer, or NaN    */
    char *ref;      /* what err was measured against, or NULL        */
    char **outputs; /* the file names it wrote (in the gallery dir)  */
    size_t nout;
} entry;

typedef struct job {
    char *file;     /* scene file name                               */
    char *path;     /* DIR/file                                      */
    char name[256]; /* output base name                              */
    int state;      /* J_*                                           */
    entry *old;     /* manifest entry, or NULL                       */
    entry now;      /* what the new manifest says (if have_now)      */
    int have_now;
    int other_shard;  /* a figure of another shard (--shard): not rendered here */
    char msg[sizeof ((hy_error *)0)->msg + 64];
} job;

typedef struct pool {
    const opts *o;
    job *jobs;
    size_t *queue, nqueue, next, done;
    pthread_mutex_t mu;
} pool;

static char *dupstr(const char *s)
{
    size_t n = strlen(s) + 1;
    char *d = malloc(n);
    return d ? memcpy(d, s, n) : NULL;
}

static void entry_free(entry *e)
{
    free(e->scene);
    free(e->ref);
    for (size_t i = 0; i < e->nout; i++)
        free(e->outputs[i]);
    free(e->outputs);
    memset(e, 0, sizeof *e);
}

/* Appends a copy of the n bytes at name to e's outputs; -1 out of memory. */
static int entry_add(entry *e, const char *name, size_t n)
{
    char **v = realloc(e->outputs, (e->nout + 1) * sizeof *v);
    if (!v)
        return -1;
    e->outputs = v;
    if (!(v[e->nout] = malloc(n + 1)))
        return -1;
    memcpy(v[e->nout], name, n);
    v[e->nout++][n] = '\0';
    return 0;
}

static int entry_has(const entry *e, const char *name)
{
    for (size_t i = 0; i < e->nout; i++)
        if (!strcmp(e->outputs[i], name))
            return 1;
    return 0;
}

static int entry_copy(entry *d, const entry *s)
{
    *d = *s;
    d->scene = dupstr(s->scene);
    d->ref = s->ref ? dupstr(s->ref) : NULL;
    d->outputs = NULL;
    d->nout = 0;
    int bad = !d->scene || (s->ref && !d->ref);
    for (size_t i = 0; i < s->nout && !bad; i++)
        bad = entry_add(d, s->outputs[i], strlen(s->outputs[i]));
    if (bad) {
        entry_free(d);
        return -1;
    }
    return 0;
}

/* ---- manifest -------------------------------------------------------- */

static const char manifest_head[] = "# hystviz gallery manifest 1: scene, key, status, seconds, error, reference, outputs\n";

/* Manifest fields are tab-separated and the outputs space-separated; in
 * names, '%', space and control bytes are written %XX (names hystviz writes
 * today have none of them, so older manifests read the same). */
static void put_name(FILE *f, const char *s)
{
    for (; *s; s++) {
        unsigned char c = (unsigned char)*s;
        if (c <= ' ' || c == '%' || c == 0x7f)
            fprintf(f, "%%%02X", c);
        else
            fputc(c, f);
    }
}

static int hexval(int c)
{
    return c >= '0' && c <= '9' ? c - '0' : c >= 'A' && c <= 'F' ? c - 'A' + 10 : c >= 'a' && c <= 'f' ? c - 'a' + 10 : -1;
}

/* Decodes %XX in place; the length of the result. */
static size_t get_name(char *s, size_t n)
{
    size_t o = 0;
    for (size_t i = 0; i < n; i++) {
        int hi, lo;
        if (s[i] == '%' && i + 2 < n && (hi = hexval(s[i + 1])) >= 0 && (lo = hexval(s[i + 2])) >= 0 && (hi || lo)) {
            s[o++] = (char)(hi * 16 + lo);
            i += 2;
        } else
            s[o++] = s[i];
    }
    s[o] = '\0';
    return o;
}

static char *field(char **s)
{
    char *f = *s, *t = f ? strchr(f, '\t') : NULL;
    if (t)
        *t = '\0';
    *s = t ? t + 1 : NULL;
    return f;
}

/* Parses one manifest line into e; 0 on success, -1 if malformed. */
static int entry_parse(char *line, entry *e)
{
    memset(e, 0, sizeof *e);
    line[strcspn(line, "\n")] = '\0';
    char *s = line;
    char *f[7];
    for (int i = 0; i < 7; i++)
        if (!(f[i] = field(&s)))
            return -1;
    if (s || strlen(f[1]) != 16 || (strcmp(f[2], "ok") && strcmp(f[2], "failed")))
        return -1;
    memcpy(e->key, f[1], 17);
    e->failed = !strcmp(f[2], "failed");
    e->seconds = strtod(f[3], NULL);
    e->err = strcmp(f[4], "-") ? strtod(f[4], NULL) : NAN;
    get_name(f[0], strlen(f[0]));
    e->scene = dupstr(f[0]);
    e->ref = strcmp(f[5], "-") ? dupstr(f[5]) : NULL;
    int bad = !e->scene || (strcmp(f[5], "-") && !e->ref);
    for (char *t = f[6]; *t && !bad;) {
        size_t n = strcspn(t, " ");
        char end = t[n];
        bad = n && entry_add(e, t, get_name(t, n));
        t += n + (end == ' ');
    }
    if (bad) {
        entry_free(e);
        return -1;
    }
    return 0;
}

/* Reads DIR/.manifest (missing: no entries; malformed lines are dropped, so
 * their scenes are rendered again). */
static entry *manifest_read(const char *path, size_t *n)
{
    *n = 0;
    FILE *f = fopen(path, "r");
    if (!f)
        return NULL;
    entry *v = NULL;
    size_t cap = 0;
    char *line = NULL;
    size_t lsz = 0;
    while (getline(&line, &lsz, f) > 0) {
        entry e;
        if (line[0] == '#' || entry_parse(line, &e))
            continue;
        if (*n == cap) {
            entry *nv = realloc(v, (cap = cap ? 2 * cap : 32) * sizeof *v);
            if (!nv) {
                entry_free(&e);
                break;
            }
            v = nv;
        }
        v[(*n)++] = e;
    }
    free(line);
    fclose(f);
    return v;
}

/* One manifest line. */
static void entry_write(FILE *f, const entry *e)
{
    put_name(f, e->scene);
    fprintf(f, "	%s	%s	%.6f	", e->key, e->failed ? "failed" : "ok", e->seconds);
    if (isnan(e->err))
        fputs("-", f);
    else
        fprintf(f, "%.17g", e->err);
    fprintf(f, "	%s	", e->ref ? e->ref : "-");
    for (size_t k = 0; k < e->nout; k++) {
        if (k)
            fputc(' ', f);
        put_name(f, e->outputs[k]);
    }
    fputc('\n', f);
}

static int manifest_write(const char *path, const job *jobs, size_t n, hy_error *err)
{
    hy_out o;
    if (hy_out_open(&o, path, 0, err))
        return -1;
    FILE *f = hy_out_file(&o);
    fputs(manifest_head, f);
    for (size_t i = 0; i < n; i++)
        if (jobs[i].have_now)
            entry_write(f, &jobs[i].now);
    return hy_out_commit(&o, err) ? -1 : 0;
}

/* ---- planning: which scenes, which of them changed -------------------- */

static int by_name(const void *a, const void *b)
{
    return strcmp(*(char *const *)a, *(char *const *)b);
}

/* The sorted names of DIR's *.scene files; NULL (message printed) on error. */
static char **list_scenes(const char *dir, size_t *n)
{
    DIR *d = opendir(dir);
    if (!d) {
        fprintf(stderr, "hystviz gallery: %s: cannot open the scenes directory: %s\n", dir, strerror(errno));
        return NULL;
    }
    char **v = NULL;
    size_t cap = 0;
    *n = 0;
    for (struct dirent *de; (de = readdir(d));) {
        size_t len = strlen(de->d_name);
        if (len <= 6 || strcmp(de->d_name + len - 6, ".scene") || de->d_name[0] == '.')
            continue;
        if (*n == cap) {
            char **nv = realloc(v, (cap = cap ? 2 * cap : 64) * sizeof *v);
            if (!nv)
                break;
            v = nv;
        }
        if (!(v[*n] = dupstr(de->d_name)))
            break;
        (*n)++;
    }
    closedir(d);
    if (*n)
        qsort(v, *n, sizeof *v, by_name);
    if (!v)
        v = calloc(1, sizeof *v);
    return v;
}

/* The manifest key: the scene hash, then the program version and the gallery
 * options that change the outputs, folded in with the same FNV-1a. */
static void scene_key(const hy_scene *s, int data, char key[17])
{
    uint64_t h = hy_scene_hash(s);
    hy_scene_doc d;
    hy_error e;
    if (hy_scene_decode_fill(s, &d, &e))
        hy_scene_doc_free(&d); /* out of memory: the key without the panels (the render reports it) */
    size_t nforc = d.forc.file ? 1 : 0; /* [forc] file: a measured FORC file */
    for (size_t i = 0; i < d.npanel + d.ndata + nforc; i++) { /* its panel files' and measured data's text too */
        char *t;
        size_t n;
        int user;
        /* the file's bytes, read as the scene resolves the path (a file, not a value) */
        if (i < d.npanel ? hy_scene_read_path(s, "panel", d.panel[i].h.name, "scene", &t, &n, &user, &e)
            : i < d.npanel + d.ndata
                ? hy_scene_read_path_max(s, "data", d.data[i - d.npanel].h.name, "file", HY_TABLE_MAX_BYTES, &t, &n,
                                         &user, &e)
                : hy_scene_read_path_max(s, "forc", NULL, "file", HY_TABLE_MAX_BYTES, &t, &n, &user, &e))
            continue; /* the render reports it */
        for (size_t k = 0; k < n; k++) {
            h ^= (unsigned char)t[k];
            h *= UINT64_C(0x100000001b3);
        }
        free(t);
    }
    hy_scene_doc_free(&d);
    char extra[64];
    snprintf(extra, sizeof extra, "\nhystviz %s%s", HY_VERSION, data ? " data" : "");
    for (const char *c = extra; *c; c++) {
        h ^= (unsigned char)*c;
        h *= UINT64_C(0x100000001b3);
    }
    snprintf(key, 17, "%016" PRIx64, h);
}

/* Every output of e exists in dir. */
static int outputs_exist(const char *dir, const entry *e)
{
    int ok = e->nout > 0;
    for (size_t i = 0; i < e->nout && ok; i++) {
        char *p = hy_path_join(dir, e->outputs[i]);
        struct stat st;
        ok = p && stat(p, &st) == 0 && S_ISREG(st.st_mode);
        free(p);
    }
    return ok;
}

/* A name the page and the manifest can carry: no control bytes (a form feed,
 * a line break), which no browser shows and which hide markup in a name. */
static int printable_name(const char *s)
{
    for (; *s; s++)
        if ((unsigned char)*s < 0x20 || *s == 0x7f)
            return 0;
    return 1;
}

static void job_fail(job *j, const char *msg)
{
    j->state = J_FAILED;
    size_t n = strlen(j->path);
    if (strncmp(msg, j->path, n) || msg[n] != ':')
        snprintf(j->msg, sizeof j->msg, "%s: %s", j->path, msg);
    else
        snprintf(j->msg, sizeof j->msg, "%s", msg);
}

/* Parses j's scene (cheap: no computing) to learn whether it is a figure,
 * its output name and key, and whether the manifest says it is up to date. */
static void job_plan(const opts *o, job *jobs, size_t i, entry *man, size_t nman)
{
    job *j = &jobs[i];
    for (size_t k = 0; k < nman; k++)
        if (!strcmp(man[k].scene, j->file))
            j->old = &man[k];
    snprintf(j->name, sizeof j->name, "%.*s", (int)(strlen(j->file) - 6), j->file);
    j->state = J_PENDING;
    hy_scene_run probe;
    hy_error err = {0};
    memset(&probe, 0, sizeof probe);
    probe.path = j->path;
    if (hy_scene_parse_file_policy(j->path, &o->pol, &probe.scene, &err)) {
        job_fail(j, err.msg);
        return;
    }
    if (!hy_scene_is_figure(probe.scene))
        j->state = J_SKIP;
    hy_scene_probe_name(probe.scene, probe.path, j->name, sizeof j->name);
    char key[17];
    scene_key(probe.scene, o->data, key);
    hy_scene_free(probe.scene);
    for (size_t k = 0; k < i && j->state != J_SKIP; k++)
        if (jobs[k].state != J_SKIP && !strcmp(jobs[k].name, j->name)) {
            snprintf(err.msg, sizeof err.msg, "its output name '%s' is also the output name of %s", j->name, jobs[k].file);
            job_fail(j, err.msg);
            return;
        }
    if (j->state == J_PENDING && !o->force && j->old && !j->old->failed && !strcmp(j->old->key, key) &&
        outputs_exist(o->out, j->old))
        j->state = J_UNCHANGED;
}

/* ---- rendering ------------------------------------------------------- */

static int write_csv(const hy_scene_run *r, const char *dir, const char *name, hy_error *err)
{
    char file[300];
    snprintf(file, sizeof file, "%s.csv", name);
    char *path = hy_path_join(dir, file);
    hy_out o;
    int rc = path ? hy_out_open(&o, path, 0, err) : hy_error_set(err, HY_ENOMEM, "out of memory");
    if (!rc) {
        hy_scene_run_data(r, hy_out_file(&o), NULL); /* a write error shows at commit */
        rc = hy_out_commit(&o, err);
    }
    free(path);
    return rc;
}

/* The manifest entry of a good render: outputs from the written paths. */
static int entry_of_run(entry *e, const job *j, const hy_scene_run *r, const char *written, int data, double seconds)
{
    memset(e, 0, sizeof *e);
    scene_key(r->scene, data, e->key);
    e->seconds = seconds;
    e->err = NAN;
    const char *ref = NULL;
    for (size_t i = 0; i < r->nseries; i++)
        if (r->series[i].err_ref && !isnan(r->series[i].err) && !(r->series[i].err <= e->err)) {
            e->err = r->series[i].err;
            ref = r->series[i].err_ref;
        }
    e->ref = ref ? dupstr(ref) : NULL;
    e->scene = dupstr(j->file);
    int bad = !e->scene || (!isnan(e->err) && !e->ref);
    for (const char *l = written; *l && !bad;) { /* one path a line: keep the file names */
        const char *nl = strchr(l, '\n'), *end = nl ? nl : l + strlen(l), *b = end;
        while (b > l && b[-1] != '/')
            b--;
        bad = end > b && entry_add(e, b, (size_t)(end - b));
        l = nl ? nl + 1 : end;
    }
    char csv[300];
    snprintf(csv, sizeof csv, "%s.csv", j->name);
    if (!bad && data)
        bad = entry_add(e, csv, strlen(csv));
    if (bad) {
        entry_free(e);
        return -1;
    }
    return 0;
}

/* Loads, computes and writes one scene into the gallery dir; fills j. */
static void render_one(const opts *o, job *j)
{
    double t0 = hy_now();
    char *logbuf = NULL;
    size_t loglen = 0;
    FILE *log = open_memstream(&logbuf, &loglen); /* asks compute to measure every error it can */
    hy_scene_run run;
    hy_error err = {0};
    int rc = hy_scene_run_load_policy(&run, j->path, NULL, 0, &o->pol, &err);
    if (!rc) {
        char written[4096] = "";
        hy_scene_run_name(&run, j->name, sizeof j->name);
        run.figure_only = !o->data; /* with --data every point is written */
        rc = hy_scene_run_compute(&run, log, &err);
        if (!rc)
            rc = hy_scene_run_write(&run, o->out, NULL, written, sizeof written, &err);
        if (!rc && o->data)
            rc = write_csv(&run, o->out, j->name, &err);
        if (!rc && entry_of_run(&j->now, j, &run, written, o->data, hy_now() - t0))
            rc = hy_error_set(&err, HY_ENOMEM, "out of memory");
        hy_scene_run_free(&run);
    }
    if (log)
        fclose(log);
    free(logbuf);
    if (rc)
        job_fail(j, err.msg);
    else {
        j->state = J_RENDERED;
        j->have_now = 1;
    }
}

static void *worker(void *arg)
{
    pool *p = arg;
    for (;;) {
        pthread_mutex_lock(&p->mu);
        size_t k = p->next < p->nqueue ? p->queue[p->next++] : SIZE_MAX;
        pthread_mutex_unlock(&p->mu);
        if (k == SIZE_MAX)
            return NULL;
        job *j = &p->jobs[k];
        double t0 = hy_now();
        render_one(p->o, j);
        double dt = hy_now() - t0;
        char what[32] = "failed";
        if (j->state != J_FAILED)
            snprintf(what, sizeof what, "%.3f s", dt);
        pthread_mutex_lock(&p->mu);
        p->done++;
        if (p->o->progress)
            fprintf(stderr, "[%zu/%zu] %s (%s)\n", p->done, p->nqueue, j->name, what);
        pthread_mutex_unlock(&p->mu);
    }
}

/* Renders the J_PENDING jobs (queue: their indices) with o->jobs threads (fewer if fewer jobs). */
static int run_pool(const opts *o, job *jobs, size_t n)
{
    pool p;
    memset(&p, 0, sizeof p);
    p.o = o;
    p.jobs = jobs;
    p.queue = malloc((n ? n : 1) * sizeof *p.queue);
    if (!p.queue)
        return -1;
    for (size_t i = 0; i < n; i++)
        if (jobs[i].state == J_PENDING)
            p.queue[p.nqueue++] = i;
    size_t nt = (size_t)o->jobs < p.nqueue ? (size_t)o->jobs : p.nqueue;
    pthread_t *th = calloc(nt ? nt : 1, sizeof *th);
    pthread_mutex_init(&p.mu, NULL);
    size_t started = 0;
    while (th && started < nt && pthread_create(&th[started], NULL, worker, &p) == 0)
        started++;
    if (started == 0)
        worker(&p); /* no thread could be started: render here */
    for (size_t i = 0; i < started; i++)
        pthread_join(th[i], NULL);
    pthread_mutex_destroy(&p.mu);
    free(th);
    free(p.queue);
    return 0;
}

/* ---- index.html ------------------------------------------------------ */

/* Every string the page interpolates goes through html() (text and
 * attribute values: the five markup characters as entities, control bytes
 * other than tab and line breaks as U+FFFD, which HTML and XML forbid) or
 * url() (href and src: percent-encoded bytes, then safe in an attribute). */
/* ---- built-in animations' posters (DIR/gallery-builtins) --------------- */

/* The built-in GL animations (hystviz animate --list) are not scenes: the
 * scene directory names the ones the gallery shows in DIR/gallery-builtins,
 * one "NAME FRAME" a line (# comments), and each is shown by that frame,
 * rendered by hystviz-animate into builtin_NAME.png.  The frame is rendered
 * when the file is missing or with --force; where hystviz-animate cannot
 * render (built without GL) the gallery says so in one line and goes on. */
#define BUILTINS_FILE "gallery-builtins"
#define BUILTINS_MAX 16
#define BUILTINS_BYTES 16384 /* 16 lines of at most 254 characters, comments besides */
#define POSTER_SIZE "640x360"
#define POSTER_TIMEOUT_S 120

typedef struct builtin {
    char name[64];
    long frame;
    int have; /* builtin_NAME.png is there */
} builtin;

/* DIR/gallery-builtins under the scene file policy: a regular file (never
 * a FIFO, device or directory: hy_file_read opens without blocking), at
 * most BUILTINS_BYTES, whose real path lies below DIR's (a link out is
 * refused, not read).  0 with *buf (NUL-terminated; NULL: no file), or 2
 * with a message naming the file. */
static int builtins_load(const char *dir, const char *path, char **buf, size_t *len)
{
    char why[200], *real = NULL, *root = NULL;
    struct stat st;
    *buf = NULL;
    if (lstat(path, &st) && errno == ENOENT)
        return 0;
    int e = hy_file_read(path, BUILTINS_BYTES, buf, len, &real, why, sizeof why);
    if (e == EFBIG)
        snprintf(why, sizeof why, "larger than the %d bytes allowed", BUILTINS_BYTES);
    else if (!e && (!(root = realpath(dir, NULL)) ||
                    (strcmp(root, "/") && (strncmp(real, root, strlen(root)) || real[strlen(root)] != '/')))) {
        snprintf(why, sizeof why, "it lies outside the scene directory (a link out of it is not followed)");
        e = EINVAL;
    }
    free(real);
    free(root);
    if (!e)
        return 0;
    fprintf(stderr, "hystviz gallery: %s: cannot read: %s\n", path, why);
    free(*buf);
    *buf = NULL;
    return 2;
}

/* Reads DIR/gallery-builtins into b (at most BUILTINS_MAX); none is no file.
 * Each name must be one of the built-in animations (anim_names.h): a line
 * such as "--worker 1" is refused, never passed on.  0, or 2 with one
 * message naming the file and line. */
static int builtins_read(const char *dir, builtin *b, size_t *n)
{
    *n = 0;
    char *path = hy_path_join(dir, BUILTINS_FILE), *text = NULL;
    size_t size = 0;
    if (!path)
        return 2;
    int rc = builtins_load(dir, path, &text, &size);
    if (rc || !text) { /* refused (said), or no file */
        free(path);
        return rc;
    }
    char line[256];
    const char *why = NULL, *at = text, *stop = text + size;
    long ln = 0;
    while (!why && at < stop) {
        ln++;
        const char *nl = memchr(at, '\n', (size_t)(stop - at));
        size_t len = nl ? (size_t)(nl - at) : (size_t)(stop - at);
        if (len > sizeof line - 2) {
            why = "a line longer than 254 characters";
            break;
        }
        if (memchr(at, '\0', len)) {
            why = "a NUL byte (not a text file)";
            break;
        }
        memcpy(line, at, len);
        line[len] = '\0';
        at += len + (nl != NULL);
        char *t = line + strspn(line, " \t");
        if (*t == '#' || *t == '\n' || *t == '\r' || *t == '\0')
            continue;
        size_t m = strspn(t, "abcdefghijklmnopqrstuvwxyz0123456789-");
        char *end = NULL;
        long frame = -1;
        if (m > 0 && m < sizeof b->name && (t[m] == ' ' || t[m] == '\t')) {
            errno = 0;
            frame = strtol(t + m, &end, 10);
            if (end == t + m || errno || frame < 0 || frame > 1000000)
                frame = -1;
            else
                end += strspn(end, " \t\r\n");
        }
        if (m == 0 || m >= sizeof b->name || (t[m] != ' ' && t[m] != '\t'))
            why = "expected NAME FRAME: a built-in animation's name as `hystviz animate --list` prints it "
                  "(a-z, 0-9, -; at most 63 characters) and a frame number";
        else if (frame < 0)
            why = "the frame is a whole number from 0 to 1000000";
        else if (*end)
            why = "one NAME and one FRAME a line";
        else if ((t[m] = '\0', !anim_name_known(t)))
            why = "not a built-in animation's name (hystviz animate --list names them)";
        else if (*n == BUILTINS_MAX)
            why = "at most 16 built-in animations";
        else {
            memcpy(b[*n].name, t, m);
            b[*n].name[m] = '\0';
            for (size_t k = 0; k < *n && !why; k++)
                if (!strcmp(b[k].name, b[*n].name))
                    why = "this animation is named twice";
            b[*n].frame = frame;
            b[*n].have = 0;
            if (!why)
                (*n)++;
        }
    }
    free(text);
    if (why)
        fprintf(stderr, "hystviz gallery: %s:%ld: %s\n", path, ln, why);
    free(path);
    return why ? 2 : 0;
}

/* Runs argv with its standard output to /dev/null and its standard error
 * into the file err, for POSTER_TIMEOUT_S at most (then killed).  Its exit
 * status, or -1 (could not run, killed: said in why). */
static int poster_run(char *const *argv, const char *err, char *why, size_t size)
{
    posix_spawn_file_actions_t fa;
    posix_spawn_file_actions_init(&fa);
    posix_spawn_file_actions_addopen(&fa, 1, "/dev/null", O_WRONLY, 0);
    posix_spawn_file_actions_addopen(&fa, 2, err, O_WRONLY | O_CREAT | O_TRUNC, 0600);
    pid_t pid;
    int sp = hy_child_spawn(&pid, argv, &fa);
    posix_spawn_file_actions_destroy(&fa);
    if (sp) {
        snprintf(why, size, "cannot run %s: %s", argv[0], strerror(sp));
        return -1;
    }
    int status = 0;
    double t0 = hy_now();
    for (;;) {
        pid_t w = waitpid(pid, &status, WNOHANG);
        if (w == pid)
            break;
        if (w < 0 && errno != EINTR) {
            snprintf(why, size, "lost %s: %s", argv[0], strerror(errno));
            return -1;
        }
        if (hy_now() - t0 > POSTER_TIMEOUT_S) {
            kill(pid, SIGKILL);
            while (waitpid(pid, &status, 0) < 0 && errno == EINTR)
                ;
            snprintf(why, size, "hystviz-animate took over %d s: stopped", POSTER_TIMEOUT_S);
            return -1;
        }
        struct timespec ts = {0, 20000000};
        nanosleep(&ts, NULL);
    }
    if (!WIFEXITED(status)) {
        snprintf(why, size, "hystviz-animate was killed (signal %d)", WTERMSIG(status));
        return -1;
    }
    return WEXITSTATUS(status);
}

/* The first line that is not blank of file path into why (what
 * hystviz-animate said). */
static void first_line(const char *path, char *why, size_t size)
{
    FILE *f = fopen(path, "r");
    why[0] = '\0';
    while (f && !why[0] && fgets(why, (int)size, f))
        why[strcspn(why, "\r\n")] = '\0';
    if (f)
        fclose(f);
    if (!why[0])
        snprintf(why, size, "hystviz-animate failed without a message");
}

/* Renders b's poster into DIR/builtin_NAME.png (atomically: rendered in a
 * temporary directory beside it, then renamed).  0; 1 when it cannot be
 * made here (no GL: said, not an error); -1 when it failed (said). */
static int poster_render(const opts *o, builtin *b)
{
    char prog[4200], tmp[4400], err[4500], frame[4600], dst[4400], range[48], why[320];
    if (hy_file_installed(HY_INSTALLED_LIBEXEC, "hystviz-animate", prog, sizeof prog)) {
        fprintf(stderr, "hystviz gallery: built-in animation %s: no poster (hystviz-animate is not installed "
                        "beside hystviz)\n", b->name);
        return 1;
    }
    if (snprintf(tmp, sizeof tmp, "%s/.builtin.XXXXXX", o->out) >= (int)sizeof tmp || !mkdtemp(tmp)) {
        fprintf(stderr, "hystviz gallery: %s: cannot make a temporary directory: %s\n", o->out, strerror(errno));
        return -1;
    }
    snprintf(range, sizeof range, "%ld:%ld", b->frame, b->frame + 1);
    snprintf(err, sizeof err, "%s/stderr", tmp);
    char *argv[] = {prog, "animate", "--size", POSTER_SIZE, "--frames", range, "-o", tmp, "--quiet", "--", b->name,
                    NULL}; /* "--": a name is never an option */
    int st = poster_run(argv, err, why, sizeof why);
    int rc = 0;
    if (st > 0)
        first_line(err, why, sizeof why);
    if (st == 3) { /* built without GL: the gallery goes on without it */
        fprintf(stderr, "hystviz gallery: built-in animation %s: no poster (%s)\n", b->name, why);
        rc = 1;
    } else if (st != 0) {
        fprintf(stderr, "hystviz gallery: built-in animation %s, frame %ld: %s\n", b->name, b->frame, why);
        rc = -1;
    } else if (snprintf(frame, sizeof frame, "%s/%s/frame_%05ld.png", tmp, b->name, b->frame) >= (int)sizeof frame ||
               snprintf(dst, sizeof dst, "%s/builtin_%s.png", o->out, b->name) >= (int)sizeof dst ||
               rename(frame, dst)) {
        fprintf(stderr, "hystviz gallery: built-in animation %s: frame %ld was not written (%s)\n", b->name,
                b->frame, strerror(errno));
        rc = -1;
    } else
        b->have = 1;
    exp_remove_tree(tmp, 1);
    return rc;
}

/* Every poster there (or rendered: missing, --force); -1 if one failed. */
static int posters(const opts *o, builtin *b, size_t n)
{
    int rc = 0;
    for (size_t i = 0; i < n; i++) {
        char dst[4400];
        struct stat st;
        snprintf(dst, sizeof dst, "%s/builtin_%s.png", o->out, b[i].name);
        b[i].have = !o->force && !stat(dst, &st) && S_ISREG(st.st_mode);
        if (!b[i].have && poster_render(o, &b[i]) < 0)
            rc = -1;
    }
    return rc;
}

static void html(FILE *f, const char *s, size_t n)
{
    for (size_t i = 0; i < n; i++) {
        unsigned char c = (unsigned char)s[i];
        switch (c) {
        case '&': fputs("&amp;", f); break;
        case '<': fputs("&lt;", f); break;
        case '>': fputs("&gt;", f); break;
        case '"': fputs("&quot;", f); break;
        case '\'': fputs("&#39;", f); break;
        default:
            if ((c < 0x20 && c != '\t' && c != '\n' && c != '\r') || c == 0x7f)
                fputs("\xef\xbf\xbd", f);
            else
                fputc(c, f);
        }
    }
}

static void htmls(FILE *f, const char *s)
{
    html(f, s, strlen(s));
}

/* A file name as a relative URL: unreserved bytes kept, the rest %XX. */
static void url(FILE *f, const char *s)
{
    for (; *s; s++) {
        unsigned char c = (unsigned char)*s;
        if ((c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || strchr("-._~", c))
            fputc(c, f);
        else
            fprintf(f, "%%%02X", c);
    }
}

/* The pixel size of a PNG (IHDR) or the viewBox of an SVG; 0 if unknown. */
static int image_size(const char *path, int svg, unsigned *w, unsigned *h)
{
    unsigned char b[2048];
    FILE *f = fopen(path, "rb");
    size_t n = f ? fread(b, 1, sizeof b - 1, f) : 0;
    if (f)
        fclose(f);
    b[n] = '\0';
    if (!svg) {
        if (n < 24 || memcmp(b, "\x89PNG\r\n\x1a\n", 8) || memcmp(b + 12, "IHDR", 4))
            return 0;
        *w = (unsigned)b[16] << 24 | (unsigned)b[17] << 16 | (unsigned)b[18] << 8 | b[19];
        *h = (unsigned)b[20] << 24 | (unsigned)b[21] << 16 | (unsigned)b[22] << 8 | b[23];
        return *w > 0 && *h > 0;
    }
    const char *vb = strstr((const char *)b, "viewBox=\"");
    double x, y, vw, vh;
    if (!vb || sscanf(vb + 9, "%lf %lf %lf %lf", &x, &y, &vw, &vh) != 4 || !(vw > 0 && vh > 0 && vw < 1e6 && vh < 1e6))
        return 0;
    *w = (unsigned)lround(vw);
    *h = (unsigned)lround(vh);
    return *w > 0 && *h > 0;
}

/* The scene's text for the page (a regular file under the scene cap, hy_file.h;
 * at most 256 KiB of it shown), or NULL. */
static char *read_text(const char *path, size_t *n)
{
    char *b, why[160];
    if (hy_file_read(path, HY_SCENE_MAX_FILE_BYTES, &b, n, NULL, why, sizeof why))
        return NULL;
    if (*n > (size_t)1 << 18)
        *n = (size_t)1 << 18;
    return b;
}

static const char index_css[] =
    "body{font-family:'DejaVu Sans',Helvetica,Arial,sans-serif;margin:1.5em auto;max-width:90em;padding:0 1em;color:#222}\n"
    "nav{margin:0 0 1.2em;line-height:1.7}nav a{margin-right:1em;white-space:nowrap}\n"
    "main{display:grid;grid-template-columns:repeat(auto-fill,minmax(26em,1fr));gap:1.2em}\n"
    ".fig{border:1px solid #ccc;border-radius:4px;padding:.8em;background:#fff}\n"
    ".fig h2{font-size:1.05em;margin:0 0 .5em}.fig h2 small{font-weight:normal;color:#666}\n"
    "h2.part{margin:1.4em 0 .6em}.cap{margin:.2em 0 .6em}\n"
    ".fig img{max-width:100%;height:auto;border:1px solid #eee}\n"
    ".links a{margin-right:.6em}\n"
    ".err{font-size:.9em;color:#444}\n"
    ".failed{color:#a00;font-size:.9em}\n"
    "pre{font-size:.8em;background:#f6f6f6;padding:.5em;overflow-x:auto}\n"
    "table{border-collapse:collapse}td,th{padding:.15em .8em;text-align:left}td.t{text-align:right}\n";

/* The <desc> of the entry's SVG (as written: XML-escaped), or NULL: the
 * thumbnail's alt text is the figure's description, not its file name. */
static char *svg_desc(const char *dir, const entry *e)
{
    char *desc = NULL;
    for (size_t i = 0; i < e->nout && !desc; i++) {
        const char *t = e->outputs[i];
        size_t n = strlen(t), len = 0;
        if (n < 5 || strcmp(t + n - 4, ".svg"))
            continue;
        char *p = hy_path_join(dir, t), *text = p ? read_text(p, &len) : NULL;
        const char *a = text ? strstr(text, "<desc>") : NULL, *b = a ? strstr(a, "</desc>") : NULL;
        if (b && (desc = malloc((size_t)(b - a))))
            snprintf(desc, (size_t)(b - a), "%.*s", (int)(b - a - 6), a + 6);
        free(text);
        free(p);
    }
    return desc;
}

/* The thumbnail: the PNG if there is one, else the SVG, with its size scaled to 400 px wide. */
static void index_thumb(FILE *f, const char *dir, const entry *e)
{
    const char *img = NULL;
    for (size_t i = 0; i < e->nout; i++) {
        const char *t = e->outputs[i];
        size_t n = strlen(t);
        if (n > 4 && !strcmp(t + n - 4, ".png"))
            img = t;
        else if (n > 4 && !strcmp(t + n - 4, ".svg") && !img)
            img = t;
    }
    unsigned w = 0, h = 0;
    char *p = img ? hy_path_join(dir, img) : NULL;
    if (p && image_size(p, !strcmp(img + strlen(img) - 4, ".svg"), &w, &h)) {
        unsigned tw = 400, th = (unsigned)lround(400.0 * h / w);
        fputs("<a href=\"", f);
        url(f, img);
        fputs("\"><img src=\"", f);
        url(f, img);
        fprintf(f, "\" width=\"%u\" height=\"%u\" alt=\"", tw, th ? th : 1);
        char *desc = svg_desc(dir, e);
        if (desc)
            fputs(desc, f);   /* XML-escaped already: &lt; &gt; &amp; &quot; &apos; are HTML too */
        else
            htmls(f, img);
        free(desc);
        fputs("\" /></a>\n", f);
    }
    free(p);
}

/* A link per output, labelled by its extension in capitals (SVG, PNG). */
static void index_links(FILE *f, const entry *e)
{
    fputs("<p class=\"links\">", f);
    for (size_t i = 0; i < e->nout; i++) {
        const char *t = e->outputs[i], *dot = strrchr(t, '.');
        char label[16];
        size_t n = 0;
        for (const char *c = dot ? dot + 1 : t; *c && n + 1 < sizeof label; c++)
            label[n++] = *c >= 'a' && *c <= 'z' ? (char)(*c - 'a' + 'A') : *c;
        label[n] = '\0';
        fputs(i ? " <a href=\"" : "<a href=\"", f);
        url(f, t);
        fputs("\">", f);
        htmls(f, label);
        fputs("</a>", f);
    }
    fputs("</p>\n", f);
}

/* Where a scene goes in the catalogue: hy_scene_catalogue_part (scene_run.h). */
#define catalogue_part hy_scene_catalogue_part

static const char *const part_title[4] = {
    "Minor loops of the Dahl and LuGre models (Ikhouane, Ma\xc3\xb1osa, Pujol)",
    "The Bouc-Wen benchmark (No\xc3\xabl, Schoukens)", "Beyond the papers' figures", "Animations"};

/* The heading of a figure: "Fig. 4", "Fig. 1a", or the output name. */
static void figure_heading(FILE *f, const job *j)
{
    char label[32];
    hy_scene_figure_label(j->file, label, sizeof label);
    if (label[0]) {
        fprintf(f, "%s <small>", label);
        htmls(f, j->name);
        fputs("</small>", f);
    } else
        htmls(f, j->name);
}

/* The scene's [figure] caption (its one-line description), or NULL: read from
 * the scene text itself (a caption is not inherited from an include). */
static char *scene_caption(const job *j)
{
    size_t n = 0;
    char *text = read_text(j->path, &n), *cap = NULL;
    int in_figure = 0;
    for (char *line = text, *next; line && *line; line = next) {
        next = strchr(line, '\n');
        if (next)
            *next++ = '\0';
        while (*line == ' ' || *line == '\t')
            line++;
        if (*line == '[')
            in_figure = !strncmp(line, "[figure]", 8);
        else if (in_figure && !strncmp(line, "caption", 7)) {
            char *q = strchr(line, '"'), *e = q ? strrchr(q + 1, '"') : NULL;
            if (q && e && e > q) {
                *e = '\0';
                cap = dupstr(q + 1);
                break;
            }
        }
    }
    free(text);
    hy_scene *sc = NULL;
    char *out = NULL;
    hy_error err = {0};
    if (cap && strchr(cap, '{') && !hy_scene_parse_file(j->path, &sc, &err) && !hy_scene_expand(sc, cap, &out, &err)) {
        free(cap); /* its placeholders ({model.sigma0}) replaced by the scene's values */
        cap = out;
    }
    hy_scene_free(sc);
    return cap;
}

static void index_figure(FILE *f, const opts *o, const job *j)
{
    fputs("<section class=\"fig\" id=\"", f);
    url(f, j->file);
    fputs("\">\n<h2>", f);
    figure_heading(f, j);
    fputs("</h2>\n", f);
    char *cap = scene_caption(j);
    if (cap) {
        fputs("<p class=\"cap\">", f);
        htmls(f, cap);
        fputs("</p>\n", f);
        free(cap);
    }
    if (catalogue_part(j->file) == 3) {
        fputs("<p class=\"err\">Animation: the image is its last frame (the poster). Render the frames or a video "
              "with <code>hystviz animate scenes/", f);
        htmls(f, j->file);
        fputs(" --video mp4</code>; the built-in animations are listed by <code>hystviz animate --list</code>.</p>\n",
              f);
    }
    if (j->state == J_FAILED) {
        fputs("<p class=\"failed\">render failed: ", f);
        htmls(f, j->msg);
        fputs(j->have_now ? " (the files below are from the last good render)</p>\n" : "</p>\n", f);
    }
    if (j->have_now) {
        index_thumb(f, o->out, &j->now);
        index_links(f, &j->now);
        if (!isnan(j->now.err)) {
            fprintf(f, "<p class=\"err\">max error %.3g against the ", j->now.err);
            htmls(f, j->now.ref ? j->now.ref : "exact answer");
            fputs("</p>\n", f);
        } else
            fputs("<p class=\"err\">no exact answer to compare with</p>\n", f);
    }
    size_t n = 0;
    char *text = read_text(j->path, &n);
    fputs("<details><summary>scene ", f);
    htmls(f, j->file);
    fputs("</summary>\n<pre>", f);
    if (text)
        html(f, text, n);
    fputs("</pre></details>\n</section>\n", f);
    free(text);
}

static void index_times(FILE *f, const job *jobs, size_t n, const size_t count[5], double total)
{
    fprintf(f, "<section id=\"times\">\n<h2>Render times</h2>\n<p>Last run: %zu rendered, %zu unchanged, %zu failed in %.2f s.</p>\n",
            count[J_RENDERED], count[J_UNCHANGED], count[J_FAILED], total);
    fputs("<table>\n<tr><th>figure</th><th>last render</th><th>this run</th></tr>\n", f);
    for (size_t i = 0; i < n; i++) {
        const job *j = &jobs[i];
        if (j->state == J_SKIP)
            continue;
        fputs("<tr><td><a href=\"#", f);
        url(f, j->file);
        fputs("\">", f);
        htmls(f, j->name);
        if (j->have_now)
            fprintf(f, "</a></td><td class=\"t\">%.3f s</td>", j->now.seconds);
        else
            fputs("</a></td><td class=\"t\">-</td>", f);
        fprintf(f, "<td>%s</td></tr>\n", j->state == J_RENDERED ? "rendered" : j->state == J_UNCHANGED ? "unchanged" : "failed");
    }
    fputs("</table>\n</section>\n", f);
}

/* A built-in animation's entry: its poster (frame F of it) and how to play it. */
static void index_builtin(FILE *f, const opts *o, const builtin *b)
{
    fprintf(f, "<section class=\"fig\" id=\"builtin-%s\">\n<h2>%s <small>built-in animation</small></h2>\n", b->name,
            b->name);
    fprintf(f, "<p class=\"err\">Frame %ld of the built-in animation %s (OpenGL, GLSL shaders): render its frames "
               "or a video with <code>hystviz animate %s --video mp4</code>; <code>hystviz animate --list</code> "
               "says what it shows.</p>\n",
            b->frame, b->name, b->name);
    char img[128], *p = NULL;
    unsigned w = 0, h = 0;
    snprintf(img, sizeof img, "builtin_%.63s.png", b->name);
    if (b->have && (p = hy_path_join(o->out, img)) && image_size(p, 0, &w, &h) && w) {
        unsigned th = (unsigned)lround(400.0 * h / w);
        fprintf(f, "<a href=\"%s\"><img src=\"%s\" width=\"400\" height=\"%u\" alt=\"Frame %ld of the built-in "
                   "animation %s\" /></a>\n", img, img, th ? th : 1, b->frame, b->name);
    } else
        fputs("<p class=\"failed\">no poster: this hystviz cannot render OpenGL frames</p>\n", f);
    free(p);
    fputs("</section>\n", f);
}

static int index_write(const opts *o, const job *jobs, size_t n, const builtin *b, size_t nb, const size_t count[5],
                       double total, hy_error *err)
{
    char *path = hy_path_join(o->out, "index.html");
    hy_out out;
    if (!path || hy_out_open(&out, path, 0, err)) {
        if (!path)
            hy_error_set(err, HY_ENOMEM, "out of memory");
        free(path);
        return -1;
    }
    FILE *f = hy_out_file(&out);
    size_t nfig = count[J_RENDERED] + count[J_UNCHANGED] + count[J_FAILED];
    fprintf(f, "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\" />\n"
               "<meta name=\"generator\" content=\"hystviz %s\" />\n<title>hystviz gallery</title>\n<style>\n%s</style>\n"
               "</head>\n<body>\n<h1>hystviz gallery</h1>\n<p>%zu figures "
               "rendered by hystviz %s from scene files.",
            HY_VERSION, index_css, nfig, HY_VERSION);
    if (o->times)
        fputs(" Render times are <a href=\"#times\">at the end</a>.", f);
    fputs("</p>\n<nav>\n", f);
    for (int part = 0; part < 4; part++)
        for (size_t i = 0; i < n; i++)
            if (jobs[i].state != J_SKIP && catalogue_part(jobs[i].file) == part) {
                fputs("<a href=\"#", f);
                url(f, jobs[i].file);
                fputs("\">", f);
                htmls(f, jobs[i].name);
                fputs("</a>\n", f);
            }
    for (size_t i = 0; i < nb; i++)
        fprintf(f, "<a href=\"#builtin-%s\">%s</a>\n", b[i].name, b[i].name);
    fputs("</nav>\n", f);
    for (int part = 0; part < 4; part++) {
        int any = 0;
        for (size_t i = 0; i < n; i++)
            any |= jobs[i].state != J_SKIP && catalogue_part(jobs[i].file) == part;
        if (!any)
            continue;
        fputs("<h2 class=\"part\">", f);
        htmls(f, part_title[part]);
        fputs("</h2>\n", f);
        fputs("<main>\n", f);
        for (size_t i = 0; i < n; i++)
            if (jobs[i].state != J_SKIP && catalogue_part(jobs[i].file) == part)
                index_figure(f, o, &jobs[i]);
        fputs("</main>\n", f);
    }
    if (nb) {
        fputs("<h2 class=\"part\">Built-in animations</h2>\n<main>\n", f);
        for (size_t i = 0; i < nb; i++)
            index_builtin(f, o, &b[i]);
        fputs("</main>\n", f);
    }
    if (o->times)
        index_times(f, jobs, n, count, total);
    fputs("</body>\n</html>\n", f);
    free(path);
    return hy_out_commit(&out, err) ? -1 : 0;
}

/* ---- the command ----------------------------------------------------- */

static const char default_scenes[] = "scenes";

static int parse_opts(int argc, char **argv, opts *o)
{
    *o = (opts){.scenes = default_scenes, .out = "gallery", .jobs = hy_jobs_default()};
    cli_parser p;
    cli_parser_init(&p, &gallery_cli, argc, argv, 1);
    for (int id; (id = cli_next(&p)) != CLI_END;) {
        const char *v = p.val;
        hy_error err = {0};
        switch (id) {
        case CLI_STOP: return 1;
        case CLI_ERROR: return 2;
        case CLI_JOBS: {
            char *end;
            errno = 0;
            o->jobs = strtol(v, &end, 10);
            if (errno || *end || end == v || o->jobs < 1 || o->jobs > 1024) {
                fprintf(stderr, "hystviz gallery: -j '%s': give a number of threads from 1 to 1024\n", v);
                return 2;
            }
            break;
        }
        case OPT_SCENES: o->scenes = v; break;
        case OPT_OUT: o->out = v; break;
        case OPT_FORCE: o->force = 1; break;
        case OPT_DATA: o->data = 1; break;
        case OPT_TIMES: o->times = 1; break;
        case OPT_NO_TIMES: o->times = 0; break;
        case OPT_QUIET: o->quiet = 1; break;
        case OPT_MERGE: o->merge = 1; break;
        case OPT_SHARD:
            if (hy_shard_parse(v, &o->shard_k, &o->shard_n, &err)) {
                fprintf(stderr, "hystviz gallery: %s\n", err.msg);
                return 2;
            }
            break;
        default:
            if (o->pol.ninclude_dirs >= sizeof o->dirs / sizeof o->dirs[0]) {
                fprintf(stderr, "hystviz gallery: at most %zu --include-dir\n", sizeof o->dirs / sizeof o->dirs[0]);
                return 2;
            }
            if (cli_policy_take(&o->pol, o->dirs, "gallery", id, v) < 0)
                return 2;
        }
    }
    o->progress = !o->quiet && isatty(STDERR_FILENO);
    struct stat st;
    if (o->scenes == default_scenes && stat(o->scenes, &st) &&
        !hy_file_installed(HY_INSTALLED_DATA, "scenes", o->installed, sizeof o->installed))
        o->scenes = o->installed; /* no ./scenes: the installed ones */
    if (o->merge && o->shard_n) {
        fprintf(stderr, "hystviz gallery: --merge joins the shards; it takes no --shard\n");
        return 2;
    }
    return 0;
}

static int make_dir(const char *dir)
{
    char buf[4096];
    snprintf(buf, sizeof buf, "%s", dir);
    for (char *p = buf + 1; *p; p++)
        if (*p == '/') {
            *p = '\0';
            if (mkdir(buf, 0755) && errno != EEXIST)
                return -1;
            *p = '/';
        }
    return mkdir(buf, 0755) && errno != EEXIST ? -1 : 0;
}

/* Removes the files of an old manifest entry that no current figure writes
 * (never a name with a '/': nothing outside the gallery). */
static void remove_unclaimed(const opts *o, const job *jobs, size_t n, const entry *old)
{
    for (size_t i = 0; i < old->nout; i++) {
        const char *t = old->outputs[i];
        int claimed = strchr(t, '/') != NULL;
        for (size_t k = 0; k < n && !claimed; k++)
            claimed = jobs[k].have_now && entry_has(&jobs[k].now, t);
        char *p = claimed ? NULL : hy_path_join(o->out, t);
        if (p)
            unlink(p);
        free(p);
    }
}

/* Removes what a re-rendered scene wrote last time and no longer writes (a
 * format dropped, a new output name), unless another figure writes it now. */
static void remove_stale(const opts *o, const job *jobs, size_t n)
{
    for (size_t i = 0; i < n; i++)
        if (jobs[i].state == J_RENDERED && jobs[i].old)
            remove_unclaimed(o, jobs, n, jobs[i].old);
}

/* Removes the outputs the manifest lists for scenes no longer in the scene
 * directory (a deleted or renamed scene), unless a current figure writes them. */
static void remove_deleted(const opts *o, const job *jobs, size_t n, const entry *man, size_t nman)
{
    for (size_t m = 0; m < nman; m++) {
        int present = 0;
        for (size_t i = 0; i < n && !present; i++)
            present = !strcmp(jobs[i].file, man[m].scene);
        if (!present)
            remove_unclaimed(o, jobs, n, &man[m]);
    }
}

/* ---- shards (--shard K/N, --merge) ------------------------------------ */

/* The figure scenes (not includes) in file-name order are numbered 0..F-1;
 * figure m belongs to shard m mod N.  Their names, folded with FNV-1a, key
 * the split: a merge refuses records made for another set of scenes. */
static uint64_t figures_key(const job *jobs, size_t n, size_t *nfig)
{
    uint64_t h = UINT64_C(14695981039346656037);
    *nfig = 0;
    for (size_t i = 0; i < n; i++)
        if (jobs[i].state != J_SKIP || jobs[i].other_shard) {
            for (const char *c = jobs[i].file; *c; c++)
                h = (h ^ (unsigned char)*c) * UINT64_C(0x100000001b3);
            h = (h ^ '\n') * UINT64_C(0x100000001b3);
            (*nfig)++;
        }
    return h;
}

/* Leaves J_PENDING/J_UNCHANGED/J_FAILED only on this shard's figures. */
static void shard_select(const opts *o, job *jobs, size_t n)
{
    size_t m = 0;
    for (size_t i = 0; i < n; i++)
        if (jobs[i].state != J_SKIP) {
            if (m % (size_t)o->shard_n != (size_t)o->shard_k) {
                jobs[i].other_shard = 1;
                jobs[i].state = J_SKIP;
            }
            m++;
        }
}

static const char *const state_word[] = {"skip", "unchanged", "pending", "rendered", "failed"};

/* DIR/.manifest.shard-K-of-N: a header, then per figure of this shard a line
 * "@ STATE FILE MESSAGE" (tab-separated) and its manifest line if it has one. */
static int shard_write(const opts *o, const job *jobs, size_t n, hy_error *err)
{
    char name[96];
    snprintf(name, sizeof name, ".manifest.shard-%ld-of-%ld", o->shard_k, o->shard_n);
    char *path = hy_path_join(o->out, name);
    hy_out out;
    if (!path) {
        hy_error_set(err, HY_ENOMEM, "out of memory");
        return -1;
    }
    if (hy_out_open(&out, path, 0, err)) {
        free(path);
        return -1;
    }
    FILE *f = hy_out_file(&out);
    size_t nfig;
    uint64_t key = figures_key(jobs, n, &nfig);
    fprintf(f, "# hystviz gallery shard %ld/%ld figures %zu key %016" PRIx64 "\n", o->shard_k, o->shard_n, nfig, key);
    for (size_t i = 0; i < n; i++) {
        const job *j = &jobs[i];
        if (j->state == J_SKIP)
            continue;
        fprintf(f, "@\t%s\t%s\t", state_word[j->state], j->file);
        for (const char *c = j->msg; j->state == J_FAILED && *c; c++)
            fputc(*c == '\t' || *c == '\n' || *c == '\r' ? ' ' : *c, f);
        fputc('\n', f);
        if (j->have_now)
            entry_write(f, &j->now);
    }
    free(path);
    return hy_out_commit(&out, err) ? -1 : 0;
}

/* K and N of a shard record's file name (canonical spelling only); 0 if not one. */
static int shard_file(const char *name, long *k, long *n)
{
    int end = 0;
    char canon[96];
    if (sscanf(name, ".manifest.shard-%ld-of-%ld%n", k, n, &end) != 2 || name[end] || *n < 1 ||
        *n > HY_SHARD_MAX || *k < 0 || *k >= *n)
        return 0;
    snprintf(canon, sizeof canon, ".manifest.shard-%ld-of-%ld", *k, *n);
    return !strcmp(canon, name);
}

/* The N of DIR's shard records; 2 (message printed) if none, several
 * splits, or shards missing (listed). */
static int shard_find(const char *dir, long *nshards)
{
    DIR *d = opendir(dir);
    long n = 0, other = 0, k, nn;
    unsigned char *present = NULL;
    for (struct dirent *de; d && (de = readdir(d));) {
        if (!shard_file(de->d_name, &k, &nn))
            continue;
        if (n && nn != n)
            other = nn;
        else {
            if (!n && !(present = calloc((size_t)(n = nn), 1)))
                break;
            present[k] = 1;
        }
    }
    if (d)
        closedir(d);
    if (!n || !present || other) {
        if (!n)
            fprintf(stderr, "hystviz gallery --merge: %s holds no shard records (.manifest.shard-K-of-N)\n", dir);
        else if (other)
            fprintf(stderr, "hystviz gallery --merge: %s holds shards of two splits (of %ld and of %ld): remove the "
                    "stale ones and merge again\n", dir, n, other);
        free(present);
        return 2;
    }
    long missing = 0;
    for (k = 0; k < n; k++)
        missing += !present[k];
    if (missing) {
        fprintf(stderr, "hystviz gallery --merge: %s: %ld of %ld shards missing:", dir, missing, n);
        for (k = 0, nn = 0; k < n && nn < 20; k++)
            if (!present[k])
                fprintf(stderr, "%s %ld/%ld", nn++ ? "," : "", k, n);
        fprintf(stderr, "%s\n  (run `hystviz gallery ... --shard K/%ld` for each, then merge again)\n",
                missing > nn ? ", ..." : "", n);
    }
    free(present);
    *nshards = n;
    return missing ? 2 : 0;
}

/* Reads shard k's records into the jobs it covers (covered[i] set); 2 with a
 * message if the record is not of this split, scene set or shard. */
static int shard_read(const opts *o, job *jobs, size_t n, long k, long nsh, unsigned char *covered)
{
    char name[96];
    snprintf(name, sizeof name, ".manifest.shard-%ld-of-%ld", k, nsh);
    char *path = hy_path_join(o->out, name), *line = NULL;
    FILE *f = path ? fopen(path, "r") : NULL;
    size_t lsz = 0, nfig, fig;
    uint64_t key = figures_key(jobs, n, &nfig), h;
    long kk, nn;
    job *cur = NULL;
    int rc = 0;
    if (!f || getline(&line, &lsz, f) < 0 ||
        sscanf(line, "# hystviz gallery shard %ld/%ld figures %zu key %" SCNx64, &kk, &nn, &fig, &h) != 4 || kk != k ||
        nn != nsh) {
        fprintf(stderr, "hystviz gallery --merge: '%s' is not a shard record of hystviz gallery\n", path ? path : name);
        rc = 2;
    } else if (fig != nfig || h != key) {
        fprintf(stderr, "hystviz gallery --merge: '%s' was made for another set of scenes than %s holds now: re-run "
                "shard %ld/%ld\n", path, o->scenes, k, nsh);
        rc = 2;
    }
    while (!rc && getline(&line, &lsz, f) > 0) {
        line[strcspn(line, "\n")] = '\0';
        if (line[0] == '@') {
            char *s = line + 2, *word = field(&s), *file = field(&s), *msg = s;
            int st = -1;
            for (int w = 0; word && w < 5; w++)
                if (!strcmp(word, state_word[w]))
                    st = w;
            cur = NULL;
            for (size_t i = 0, m = 0; file && i < n && !cur; i++)
                if (jobs[i].state != J_SKIP) {
                    if (!strcmp(jobs[i].file, file) && m % (size_t)nsh == (size_t)k && !covered[i])
                        cur = &jobs[i];
                    m++;
                }
            if (!cur || (st != J_RENDERED && st != J_UNCHANGED && st != J_FAILED)) {
                fprintf(stderr, "hystviz gallery --merge: '%s': a record of '%s' that is not this shard's\n", path,
                        file ? file : "?");
                rc = 2;
                break;
            }
            covered[cur - jobs] = 1;
            cur->state = st;
            snprintf(cur->msg, sizeof cur->msg, "%s", st == J_FAILED && msg ? msg : "");
        } else if (cur && !cur->have_now && !entry_parse(line, &cur->now))
            cur->have_now = 1;
        else {
            fprintf(stderr, "hystviz gallery --merge: '%s' is damaged: re-run shard %ld/%ld\n", path, k, nsh);
            rc = 2;
        }
    }
    free(line);
    if (f)
        fclose(f);
    free(path);
    return rc;
}

/* Fills every figure job from the shard records (2, message printed, and
 * nothing changed on disk if they are incomplete or not of these scenes). */
static int shard_merge(const opts *o, job *jobs, size_t n)
{
    long nsh = 0;
    int rc = shard_find(o->out, &nsh);
    unsigned char *covered = rc ? NULL : calloc(n ? n : 1, 1);
    if (!rc && !covered)
        rc = 2;
    for (long k = 0; k < nsh && !rc; k++)
        rc = shard_read(o, jobs, n, k, nsh, covered);
    for (size_t i = 0; i < n && !rc; i++)
        if (jobs[i].state != J_SKIP && !covered[i]) {
            fprintf(stderr, "hystviz gallery --merge: no shard has a record of %s: re-run its shard\n", jobs[i].file);
            rc = 2;
        }
    free(covered);
    return rc;
}

/* Removes the joined shard records. */
static void shard_remove(const opts *o)
{
    DIR *d = opendir(o->out);
    long k, n;
    for (struct dirent *de; d && (de = readdir(d));)
        if (shard_file(de->d_name, &k, &n)) {
            char *p = hy_path_join(o->out, de->d_name);
            if (p)
                unlink(p);
            free(p);
        }
    if (d)
        closedir(d);
}

/* Whether a scene's file name is one the page cannot carry (each one
 * printed): invalid input, refused before anything is rendered or written
 * (no index.html listing the others). */
static int bad_names(const opts *o, const job *jobs, size_t n)
{
    int bad_name = 0;
    for (size_t i = 0; i < n; i++)
        if (!printable_name(jobs[i].file)) {
            char shown[256];
            fprintf(stderr, "hystviz gallery: %s/%s: a scene file name with a control character (tab, line break, "
                            "form feed, ...) is not supported: rename the file\n",
                    o->scenes, hy_file_shown(jobs[i].file, strlen(jobs[i].file), 60, shown, sizeof shown));
            bad_name = 1;
        }
    return bad_name;
}

/* Plans, renders, writes the manifest and the index; returns the exit status. */
static int gallery(const opts *o, job *jobs, size_t n, entry *man, size_t nman, builtin *b, size_t nb)
{
    double t0 = hy_now();
    if (bad_names(o, jobs, n))
        return 2;
    for (size_t i = 0; i < n; i++)
        job_plan(o, jobs, i, man, nman);
    if (o->merge) {
        int mrc = shard_merge(o, jobs, n);
        if (mrc)
            return mrc;
    } else if (o->shard_n)
        shard_select(o, jobs, n);
    if (!o->merge && run_pool(o, jobs, n)) {
        fprintf(stderr, "hystviz gallery: out of memory\n");
        return 1;
    }
    size_t count[5] = {0};
    int rc = 0;
    for (size_t i = 0; i < n; i++) {
        job *j = &jobs[i];
        count[j->state]++;
        if (j->state == J_UNCHANGED && !o->merge)
            j->have_now = !entry_copy(&j->now, j->old);
        if (j->state == J_FAILED) {
            fprintf(stderr, "hystviz gallery: %s\n", j->msg);
            if (!o->merge) {
                j->have_now = j->old && !entry_copy(&j->now, j->old);
                j->now.failed = 1;
            }
            rc = 1;
        }
    }
    if (o->shard_n) {
        hy_error werr = {0};
        if (shard_write(o, jobs, n, &werr)) {
            fprintf(stderr, "hystviz gallery: %s\n", werr.msg);
            rc = 1;
        }
        if (!o->quiet)
            fprintf(stderr, "gallery shard %ld/%ld: %zu rendered, %zu unchanged, %zu failed in %.2f s\n", o->shard_k,
                    o->shard_n, count[J_RENDERED], count[J_UNCHANGED], count[J_FAILED], hy_now() - t0);
        return rc;
    }
    remove_stale(o, jobs, n);
    remove_deleted(o, jobs, n, man, nman);
    char *mpath = hy_path_join(o->out, ".manifest");
    hy_error err = {0};
    int written = 1;
    if (!mpath || manifest_write(mpath, jobs, n, &err)) {
        fprintf(stderr, "hystviz gallery: %s\n", mpath ? err.msg : "out of memory");
        rc = 1;
        written = 0;
    }
    free(mpath);
    if (posters(o, b, nb))
        rc = 1;
    double total = hy_now() - t0;
    if (index_write(o, jobs, n, b, nb, count, total, &err)) {
        fprintf(stderr, "hystviz gallery: %s\n", err.msg);
        rc = 1;
        written = 0;
    }
    if (o->merge && written)
        shard_remove(o); /* joined: the records are now .manifest and index.html */
    if (!o->quiet)
        fprintf(stderr, "gallery: %zu rendered, %zu unchanged, %zu failed in %.2f s\n", count[J_RENDERED],
                count[J_UNCHANGED], count[J_FAILED], hy_now() - t0);
    return rc;
}

/* Takes DIR/.lock (flock, waiting for a run that holds it): one gallery run
 * at a time per directory, so the manifest, the index and the files agree;
 * shards (--shard) hold it shared, so they run together but not beside an
 * unsharded run or a merge.
 * The lock goes with the process, also when it is killed.  -1: printed. */
static int lock_gallery(const opts *o)
{
    char *path = hy_path_join(o->out, ".lock");
    int fd = path ? open(path, O_RDWR | O_CREAT | O_NOFOLLOW | O_CLOEXEC, 0666) : -1;
    int op = o->shard_n ? LOCK_SH : LOCK_EX; /* shards write disjoint files: they share the directory */
    if (fd >= 0 && flock(fd, op | LOCK_NB) && errno == EWOULDBLOCK) {
        if (!o->quiet)
            fprintf(stderr, "gallery: waiting for another gallery run on %s to finish\n", o->out);
        while (flock(fd, op) && errno == EINTR)
            ;
    }
    struct stat st;
    if (fd < 0 || fstat(fd, &st) || !S_ISREG(st.st_mode)) {
        fprintf(stderr, "hystviz gallery: cannot lock '%s': %s\n", path ? path : o->out,
                fd < 0 ? strerror(errno) : "not a regular file");
        if (fd >= 0)
            close(fd);
        fd = -1;
    }
    free(path);
    return fd;
}

int hy_cmd_gallery(int argc, char **argv)
{
    opts o;
    int rc = parse_opts(argc, argv, &o);
    if (rc)
        return rc == 1 ? 0 : rc;
    size_t n = 0, nman = 0, nb = 0;
    builtin b[BUILTINS_MAX];
    if (builtins_read(o.scenes, b, &nb))
        return 2; /* before anything is rendered or written */
    char **names = list_scenes(o.scenes, &n);
    if (!names)
        return 2;
    int lock = -1;
    if (make_dir(o.out)) {
        fprintf(stderr, "hystviz gallery: %s: cannot create the gallery directory: %s\n", o.out, strerror(errno));
        rc = 1;
    } else if ((lock = lock_gallery(&o)) < 0)
        rc = 1;
    else
        hy_out_sweep(o.out); /* temporaries of killed runs (their locks are free) */
    char *mpath = hy_path_join(o.out, ".manifest");
    entry *man = mpath && !rc ? manifest_read(mpath, &nman) : NULL;
    free(mpath);
    job *jobs = calloc(n ? n : 1, sizeof *jobs);
    for (size_t i = 0; jobs && i < n; i++) {
        jobs[i].file = names[i];
        if (!(jobs[i].path = hy_path_join(o.scenes, names[i])))
            rc = 2;
    }
    if (!jobs)
        rc = 2;
    gsl_set_error_handler_off();
    tzset(); /* cairo's PDF writer reads the time zone: set it up before the threads */
    if (!rc)
        rc = gallery(&o, jobs, n, man, nman, b, nb);
    for (size_t i = 0; jobs && i < n; i++) {
        free(jobs[i].path);
        entry_free(&jobs[i].now);
    }
    for (size_t i = 0; i < n; i++)
        free(names[i]);
    for (size_t i = 0; i < nman; i++)
        entry_free(&man[i]);
    free(man);
    free(jobs);
    free(names);
    if (lock >= 0)
        close(lock); /* releases the gallery to the next run */
    return rc;
}
