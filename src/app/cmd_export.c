/* SPDX-License-Identifier: MIT */
/* cmd_export.c: `hystviz export SCENE --grid KEY=SPEC ... -o FILE.html`
 * (issue 21 item 6): the scene's SVG at every point of a sweep grid
 * (hy_grid.h: the same specs, values and row-major numbering as `hystviz
 * sweep`), each byte for byte what `hystviz render SCENE --set ... --format
 * svg` writes, in one offline HTML page with a slider per grid key
 * (export_page.h).  With --shard K/N it renders the points i mod N = K into
 * FILE.shard-K-of-N (the shard partition of sweep); `export --merge FILE`
 * joins the N shards into the page the unsharded run writes, byte for byte.
 *
 * A shard file is gzip (concatenated members) of the text
 *     # hystviz export shard K/N points P scene HASH meta LEN\n  META\n
 * then per point i of the shard, in order: "I ok|invalid LEN\n" + LEN bytes
 * (the SVG or the scene's message) + "\n".  META is the page's description
 * (JSON), the same for every shard of one study. */
#include "cmd_export.h"

#include <errno.h>
#include <inttypes.h>
#include <math.h>
#include <pthread.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include <zlib.h>

#include "cli_util.h"
#include "export_anim.h"
#include "export_page.h"
#include "hy_grid.h"
#include "hy_jobs.h"
#include "hy_out.h"
#include "hy_plot.h"
#include "hy_scene_schema.h"
#include "scene_run.h"

/* The most points one page holds (a slider per key, every figure inside). */
#define EXPORT_MAX_POINTS 20000UL

static const char export_help[] =
    "usage: hystviz export SCENE --grid SECTION.KEY=SPEC... [-o FILE.html] [--set SECTION.KEY=VALUE]...\n"
    "                      [-j N] [--shard K/N] [--include-dir DIR]... [--max-work N] [-q]\n"
    "       hystviz export ANIMATION [-o FILE.html] [--set SECTION.KEY=VALUE]... [--size WxH] [-j N]\n"
    "                      [--include-dir DIR]... [--max-work N] [-q]\n"
    "       hystviz export --merge FILE.html\n"
    "\n"
    "An interactive figure as one offline file: the scene is rendered at every point\n"
    "of the grid (--grid as for hystviz sweep: a list 1,2,5, a range FROM:TO:COUNT\n"
    "or FROM:TO:logCOUNT; the first --grid is the outermost axis) and FILE.html\n"
    "gets every figure, with a slider per grid key that snaps to its values.  Each\n"
    "position shows byte for byte the SVG that `hystviz render SCENE --set ...\n"
    "--set KEY=VALUE ... --format svg` writes, and that command line.  The page\n"
    "needs no server and no network: open it from disk, a course page or an LMS\n"
    "(a browser with DecompressionStream: Chromium 80, Firefox 113, Safari 16.4).\n"
    "Parts the figures share (fonts, axes, legend) are stored once and the rest is\n"
    "compressed.  A point the scene refuses (e.g. u_min,2 > u_max,1) is shown as\n"
    "refused, with the scene's message.\n"
    "\n"
    "An animation (a built-in NAME of `hystviz animate --list`, or a scene with\n"
    "[keyframe] sections), given without --grid, exports as a player: every frame\n"
    "rendered as `hystviz animate` renders it (frame i byte for byte the PNG of\n"
    "`hystviz animate ANIMATION --frames i:i+1` with the same --set and --size),\n"
    "played at the animation's frame rate (its easing is in the frames), with\n"
    "play/pause (space), a scrub slider (left/right step) and a frame counter.\n"
    "Frames equal to an earlier one are stored once.\n"
    "\n"
    "\n";

static const char export_tail[] =
    "exit status: 0 the page is written (refused points shown as such); 2 usage\n"
    "error, an unreadable scene or bad grid, every point refused, or shards missing\n"
    "or of another study (nothing written); 1 a point failed to compute or a file\n"
    "could not be written (nothing written); 3 an animation, but hystviz was built\n"
    "without OpenGL (nothing written).\n";

enum { OPT_GRID = CLI_FIRST, OPT_SET, OPT_SIZE, OPT_OUT, OPT_SHARD, OPT_MERGE, OPT_QUIET };
static const cli_opt export_opts_table[] = {
    {"grid", 0, "K=SPEC", "a grid axis (repeatable; at most 20000 points in all)", OPT_GRID, CLI_SCENE_KEY, NULL,
     NULL, NULL},
    {"set", 0, "S.K=V", "a fixed override applied to every point before the grid\n"
     "(an animation scene: in every frame; its keyframes beat it)", OPT_SET, CLI_SCENE_KEY, NULL, NULL, NULL},
    {"size", 0, "WxH", "(animations) the frame size in pixels (default: the animation's)", OPT_SIZE, 0, NULL, NULL,
     NULL},
    {"output", 'o', "FILE", "the page (default: the scene's name with .html, here)", OPT_OUT, 0, NULL, NULL, NULL},
    {.group = cli_jobs_opts},
    {"shard", 0, "K/N", "only points with index mod N = K (0 <= K < N), into\n"
     "FILE.shard-K-of-N for --merge", OPT_SHARD, 0, NULL, NULL, NULL},
    {"merge", 0, "FILE", "join FILE's N shards (FILE.shard-K-of-N) into FILE, the\n"
     "page the unsharded run writes (refused unless all N are there)", OPT_MERGE, 0, NULL, NULL, NULL},
    {.group = cli_policy_opts},
    {"quiet", 'q', NULL, "print only errors", OPT_QUIET, 0, NULL, NULL, NULL},
    {0},
};
static const cli_cmd export_cli = {"export", export_help, export_tail, "SCENE", export_opts_table};

typedef struct export_opts {
    const char *scene, *out, *merge, *size;
    char **sets;
    size_t nsets;
    hy_grid grid;
    hy_scene_policy pol;
    const char **dirs;
    long jobs, shard_k, shard_n;
    int sharded, quiet, anim; /* anim: no --grid, an animation */
    char out_buf[4096];
} export_opts;

/* One rendered point: its SVG, or the scene's message. */
typedef struct point_res {
    unsigned char *svg;
    size_t len;
    int kind;           /* 0 ok, 1 refused (HY_EINVAL), 2 failed */
    char msg[512];
} point_res;

/* ---- options ------------------------------------------------------------ */

/* Whether o->scene, given without --grid, is an animation: 1 a built-in
 * name (hystviz-animate checks it) or a scene with [keyframe] sections, 0 a
 * scene without, -1 an unreadable or invalid scene (message printed). */
static int is_animation(const export_opts *o)
{
    size_t n = strlen(o->scene);
    if (!strchr(o->scene, '/') && !(n > 6 && !strcmp(o->scene + n - 6, ".scene")))
        return 1;
    hy_scene *sc = NULL;
    hy_error err = {0};
    if (hy_scene_parse_file_policy(o->scene, &o->pol, &sc, &err)) {
        fprintf(stderr, "hystviz export: %s\n", err.msg);
        return -1;
    }
    hy_scene_doc d;
    int anim = hy_scene_decode_fill(sc, &d, &err) ? -1 : d.nkeyframe > 0;
    if (anim < 0)
        fprintf(stderr, "hystviz export: %s\n", err.msg);
    hy_scene_doc_free(&d);
    hy_scene_free(sc);
    return anim;
}

/* Checks how the options read into o combine and names the page when -o did
 * not: 0 ok, 2 usage error (message printed). */
static int finish_opts(export_opts *o)
{
    if (o->merge && (o->scene || o->grid.naxes || o->sharded || o->out)) {
        fprintf(stderr, "hystviz export: --merge FILE takes no scene, --grid, --shard or -o\n");
        return 2;
    }
    if (o->merge)
        return 0;
    if (!o->scene) {
        fprintf(stderr, "hystviz export: give a scene file (see hystviz export --help)\n");
        return 2;
    }
    if (!o->grid.naxes && (o->anim = is_animation(o)) != 1)
        return o->anim ? 2 : (fprintf(stderr, "hystviz export: give at least one --grid KEY=SPEC (a slider each); "
                                      "'%s' has no [keyframe] sections, so it is no animation\n", o->scene), 2);
    if (o->anim && o->sharded) {
        fprintf(stderr, "hystviz export: an animation is exported whole (-j N renders its frames in parallel); "
                "--shard is for --grid\n");
        return 2;
    }
    if (o->size && !o->anim) {
        fprintf(stderr, "hystviz export: --size is for animations (a figure's size is its scene's)\n");
        return 2;
    }
    if (hy_grid_points(&o->grid) > EXPORT_MAX_POINTS) {
        fprintf(stderr, "hystviz export: the grid has %zu points; a page holds at most %lu\n",
                hy_grid_points(&o->grid), EXPORT_MAX_POINTS);
        return 2;
    }
    if (!o->out) { /* NAME.html from the scene file's name, in the current directory */
        const char *base = strrchr(o->scene, '/') ? strrchr(o->scene, '/') + 1 : o->scene;
        size_t n = strlen(base);
        if (n > 6 && !strcmp(base + n - 6, ".scene"))
            n -= 6;
        snprintf(o->out_buf, sizeof o->out_buf, "%.*s.html", (int)n, base);
        o->out = o->out_buf;
    }
    return 0;
}

/* 0 ok, 1 help printed, 2 usage error (message printed). */
static int parse_opts(int argc, char **argv, export_opts *o)
{
    memset(o, 0, sizeof *o);
    hy_grid_init(&o->grid);
    o->jobs = hy_jobs_default();
    o->pol = hy_scene_policy_default();
    o->sets = calloc((size_t)argc, sizeof *o->sets);
    o->dirs = calloc((size_t)argc, sizeof *o->dirs);
    if (!o->sets || !o->dirs) {
        fprintf(stderr, "hystviz export: out of memory\n");
        return 2;
    }
    hy_error err = {0};
    cli_parser p;
    cli_parser_init(&p, &export_cli, argc, argv, 1);
    for (int id; (id = cli_next(&p)) != CLI_END;) {
        const char *v = p.val;
        if (id == CLI_STOP || id == CLI_ERROR)
            return id == CLI_STOP ? 1 : 2;
        if (id == OPT_GRID) {
            if (hy_grid_add(&o->grid, v, &err)) {
                fprintf(stderr, "hystviz export: %s\n", err.msg);
                return 2;
            }
        } else if (id == OPT_SET)
            o->sets[o->nsets++] = (char *)v;
        else if (id == OPT_SIZE)
            o->size = v;
        else if (id == OPT_OUT)
            o->out = v;
        else if (id == CLI_JOBS) {
            if (cli_long(p.optname, v, 1, 1024, &o->jobs))
                return 2;
        } else if (id == OPT_SHARD) {
            if (hy_shard_parse(v, &o->shard_k, &o->shard_n, &err)) {
                fprintf(stderr, "hystviz export: %s\n", err.msg);
                return 2;
            }
            o->sharded = 1;
        } else if (id == OPT_MERGE)
            o->merge = v;
        else if (id == OPT_QUIET)
            o->quiet = 1;
        else if (id == CLI_ARG && o->scene)
            return cli_unexpected(&p), 2;
        else if (id == CLI_ARG)
            o->scene = v;
        else if (cli_policy_take(&o->pol, o->dirs, "export", id, v) < 0)
            return 2;
    }
    return finish_opts(o);
}

/* ---- the study ---------------------------------------------------------- */

/* The schema's entry of a --grid key (SECTION.KEY or SECTION.NAME.KEY), or
 * NULL: its symbol and unit label the page's slider as serve's are. */
static const hy_scene_key_spec *grid_key_spec(const char *full)
{
    char sec[64];
    size_t n = strcspn(full, ".");
    if (n >= sizeof sec || !full[n])
        return NULL;
    memcpy(sec, full, n);
    sec[n] = 0;
    int si = hy_scene_schema_section(sec), ki = si < 0 ? -1 : hy_scene_schema_key(si, strrchr(full, '.') + 1);
    if (ki < 0)
        return NULL;
    size_t ns;
    return &hy_scene_schema(&ns)[si].keys[ki];
}

/* The number the scene (with --set) holds for a --grid key, as "%.17g" into
 * buf, or "null": the page finds a preset's figure among the grid's with it. */
static void grid_file_value(const hy_scene_doc *d, const char *full, char *buf, size_t n)
{
    char sec[64], name[128] = "";
    const char *dot = strchr(full, '.'), *last = strrchr(full, '.');
    snprintf(buf, n, "null");
    if (!dot || (size_t)(dot - full) >= sizeof sec || (size_t)(last - dot) > sizeof name)
        return;
    snprintf(sec, sizeof sec, "%.*s", (int)(dot - full), full);
    if (last > dot)
        snprintf(name, sizeof name, "%.*s", (int)(last - dot - 1), dot + 1);
    double v;
    const hy_decl_head *h = hy_scene_doc_find(d, sec, last > dot ? name : NULL);
    int st = h ? hy_decl_num(h, last + 1, &v) : -1;
    if ((st == HY_SCENE_SET || st == HY_SCENE_DEFAULT) && isfinite(v))
        snprintf(buf, n, "%.17g", v);
}

/* The scene's presets as JSON ([{"name","label","sets":[...]}], serve's
 * form): the page offers those whose values all lie on the grid. */
static void presets_json(FILE *f, const hy_scene *s, const hy_scene_doc *d)
{
    char (*sets)[HY_SCENE_SET_MAX] = malloc(HY_SCENE_PRESET_MAX * sizeof *sets);
    fputs(",\"presets\":[", f);
    for (size_t i = 0, first = 1; sets && i < d->npreset; i++) {
        const hy_decl_preset *p = &d->preset[i];
        size_t n;
        hy_error err = {0};
        if (hy_scene_preset_sets(s, p->h.name, sets, HY_SCENE_PRESET_MAX, &n, &err))
            continue;
        const char *label = hy_decl_got(&p->h, offsetof(hy_decl_preset, label)) == HY_SCENE_SET ? p->label : p->h.name;
        fputs(first ? "{\"name\":" : ",{\"name\":", f);
        first = 0;
        exp_json_str(f, p->h.name, strlen(p->h.name));
        fputs(",\"label\":", f);
        exp_json_str(f, label, strlen(label));
        fputs(",\"sets\":[", f);
        for (size_t j = 0; j < n; j++) {
            fputs(j ? "," : "", f);
            exp_json_str(f, sets[j], strlen(sets[j]));
        }
        fputs("]}", f);
    }
    fputs("]", f);
    free(sets);
}

/* Checks the scene loads with the user's --set and writes the page's
 * description (JSON) into *meta and the scene's content hash; 2 on bad
 * input (message printed). */
static int describe(const export_opts *o, char **meta, uint64_t *hash)
{
    hy_scene *base = NULL;
    hy_error err = {0};
    if (hy_scene_parse_file_policy(o->scene, &o->pol, &base, &err)) {
        fprintf(stderr, "hystviz export: %s\n", err.msg);
        return err.code == HY_ENOMEM ? 1 : 2;
    }
    for (size_t k = 0; k < o->nsets; k++)
        if (hy_scene_set(base, o->sets[k], &err)) {
            fprintf(stderr, "hystviz export: --set %s: %s\n", o->sets[k], err.msg);
            hy_scene_free(base);
            return 2;
        }
    hy_scene_doc d;
    if (hy_scene_decode_fill(base, &d, &err)) {
        fprintf(stderr, "hystviz export: %s\n", err.msg);
        hy_scene_doc_free(&d);
        hy_scene_free(base);
        return 1;
    }
    const char *name = d.output.name;
    char fallback[256];
    if (hy_decl_got(&d.output.h, offsetof(hy_decl_output, name)) < 0 || !name || !*name) {
        const char *b = strrchr(o->scene, '/') ? strrchr(o->scene, '/') + 1 : o->scene;
        snprintf(fallback, sizeof fallback, "%.*s", (int)strcspn(b, "."), b);
        name = fallback;
    }
    *hash = hy_scene_hash(base);
    size_t len = 0;
    FILE *f = open_memstream(meta, &len);
    if (!f) {
        hy_scene_doc_free(&d);
        hy_scene_free(base);
        return 1;
    }
    fputs("{\"title\":", f);
    exp_json_str(f, name, strlen(name));
    fputs(",\"name\":", f);
    exp_json_str(f, name, strlen(name));
    fputs(",\"scene\":", f);
    exp_json_str(f, o->scene, strlen(o->scene));
    fputs(",\"sets\":[", f);
    for (size_t k = 0; k < o->nsets; k++) {
        fputs(k ? "," : "", f);
        exp_json_str(f, o->sets[k], strlen(o->sets[k]));
    }
    fputs("],\"axes\":[", f);
    for (size_t a = 0; a < o->grid.naxes; a++) {
        const hy_grid_axis *ax = &o->grid.axes[a];
        fputs(a ? ",{\"key\":" : "{\"key\":", f);
        exp_json_str(f, ax->key, strlen(ax->key));
        const hy_scene_key_spec *k = grid_key_spec(ax->key);
        const char *sym = k && k->symbol ? k->symbol : "", *unit = k && k->unit ? k->unit : "";
        fputs(",\"sym\":", f);
        exp_json_str(f, sym, strlen(sym));
        fputs(",\"unit\":", f);
        exp_json_str(f, unit, strlen(unit));
        char file[40];
        grid_file_value(&d, ax->key, file, sizeof file);
        fprintf(f, ",\"file\":%s", file);
        fputs(",\"values\":[", f);
        for (size_t v = 0; v < ax->nvalues; v++) {
            fputs(v ? "," : "", f);
            exp_json_str(f, ax->values[v], strlen(ax->values[v]));
        }
        fputs("]}", f);
    }
    fputs("]", f);
    presets_json(f, base, &d);
    fputs("}", f);
    hy_scene_doc_free(&d);
    hy_scene_free(base);
    return fclose(f) ? 1 : 0;
}

/* Renders point i into res as `render --set ... --format svg` would. */
static void render_point(const export_opts *o, size_t i, point_res *res)
{
    const hy_grid *g = &o->grid;
    char **sets = calloc(o->nsets + g->naxes + 1, sizeof *sets);
    char *text = NULL;
    size_t tlen = 0;
    FILE *t = open_memstream(&text, &tlen);
    memset(res, 0, sizeof *res);
    if (!sets || !t) {
        if (t)
            fclose(t);
        free(sets);
        res->kind = 2;
        snprintf(res->msg, sizeof res->msg, "out of memory");
        return;
    }
    size_t offs[64], nax = g->naxes < 64 ? g->naxes : 64;
    for (size_t a = 0; a < nax; a++) {
        offs[a] = (size_t)ftell(t);
        fprintf(t, "%s=%s", g->axes[a].key, hy_grid_value(g, i, a));
        fputc('\0', t);
    }
    int bad = fclose(t) != 0;
    memcpy(sets, o->sets, o->nsets * sizeof *sets);
    for (size_t a = 0; a < nax && !bad; a++)
        sets[o->nsets + a] = text + offs[a];
    hy_scene_run r;
    hy_error err = {0};
    err.msg[0] = '\0';
    int rc = bad ? hy_error_set(&err, HY_ENOMEM, "out of memory")
                 : hy_scene_run_load_policy(&r, o->scene, sets, o->nsets + nax, &o->pol, &err);
    if (!rc) {
        if (!(rc = hy_scene_run_compute(&r, NULL, &err)))
            rc = hy_scene_run_render(&r, HY_FORMAT_SVG, &res->svg, &res->len, NULL, &err);
        hy_scene_run_free(&r);
    }
    res->kind = !rc ? 0 : err.code == HY_EINVAL ? 1 : 2;
    if (rc)
        snprintf(res->msg, sizeof res->msg, "%s", err.msg);
    free(sets);
    free(text);
}

/* ---- parallel rendering, in batches, consumed in point order ------------ */

typedef struct batch {
    const export_opts *o;
    size_t first, count;   /* shard-local indices of this batch */
    size_t next;
    point_res *res;
    pthread_mutex_t mu;
} batch;

static size_t point_of(const export_opts *o, size_t j)
{
    return o->sharded ? (size_t)o->shard_k + j * (size_t)o->shard_n : j;
}

static void *batch_worker(void *arg)
{
    batch *b = arg;
    for (;;) {
        pthread_mutex_lock(&b->mu);
        size_t j = b->next++;
        pthread_mutex_unlock(&b->mu);
        if (j >= b->count)
            return NULL;
        render_point(b->o, point_of(b->o, b->first + j), &b->res[j]);
    }
}

/* Renders the shard's points (all without --shard) on o->jobs threads and
 * hands each to take() in point order; stops at take's first nonzero status. */
static int render_all(const export_opts *o, size_t nmine, int (*take)(void *ctx, size_t i, point_res *r), void *ctx)
{
    size_t width = 4 * (size_t)o->jobs;
    batch b;
    memset(&b, 0, sizeof b);
    b.o = o;
    b.res = calloc(width, sizeof *b.res);
    pthread_t *th = calloc((size_t)o->jobs, sizeof *th);
    if (!b.res || !th) {
        free(b.res);
        free(th);
        fprintf(stderr, "hystviz export: out of memory\n");
        return 1;
    }
    pthread_mutex_init(&b.mu, NULL);
    int rc = 0;
    for (size_t first = 0; first < nmine && !rc; first += width) {
        b.first = first;
        b.count = nmine - first < width ? nmine - first : width;
        b.next = 0;
        long started = 0;
        for (; started < o->jobs && (size_t)started < b.count; started++)
            if (pthread_create(&th[started], NULL, batch_worker, &b))
                break;
        if (!started)
            batch_worker(&b);
        for (long k = 0; k < started; k++)
            pthread_join(th[k], NULL);
        for (size_t j = 0; j < b.count; j++) {
            if (!rc)
                rc = take(ctx, point_of(o, first + j), &b.res[j]);
            free(b.res[j].svg);
        }
    }
    pthread_mutex_destroy(&b.mu);
    free(b.res);
    free(th);
    return rc;
}

/* ---- the page ----------------------------------------------------------- */

typedef struct page_ctx {
    exp_page *pg;
    size_t nfailed;
    int quiet;
    char first_msg[600];
} page_ctx;

/* Adds one point to the page: its SVG or its refusal; a failed point stops
 * the export (status 1). */
static int add_point(page_ctx *c, size_t i, int kind, const char *svg, size_t len, const char *msg)
{
    hy_error err = {0};
    int rc;
    if (kind == 2) {
        fprintf(stderr, "hystviz export: point %zu: %s\n", i, msg);
        return 1;
    }
    if (kind == 1 && !c->first_msg[0])
        snprintf(c->first_msg, sizeof c->first_msg, "point %zu: %s", i, msg);
    rc = kind == 0 ? exp_page_add(c->pg, svg, len, &err) : exp_page_refused(c->pg, msg, &err);
    if (rc) {
        fprintf(stderr, "hystviz export: %s\n", err.msg);
        return cli_exit_status(rc);
    }
    return 0;
}

static int take_page(void *ctx, size_t i, point_res *r)
{
    return add_point(ctx, i, r->kind, (const char *)r->svg, r->len, r->msg);
}

/* Writes the page into out (opened before computing, so that a bad target
 * fails first) and commits it; refused (2) when every point was refused.  out
 * is done afterwards, written or dropped. */
static int write_page(page_ctx *c, const char *meta, hy_out *out, int quiet)
{
    size_t nref, n = exp_page_points(c->pg, &nref);
    hy_error err = {0};
    if (nref == n) {
        hy_out_abort(out);
        fprintf(stderr, "hystviz export: the scene refuses every point of the grid (%s); nothing written\n",
                c->first_msg);
        return 2;
    }
    if (exp_page_write(c->pg, meta, hy_out_file(out), &err)) {
        hy_out_abort(out);
        fprintf(stderr, "hystviz export: %s\n", err.msg);
        return 1;
    }
    char path[4200];
    snprintf(path, sizeof path, "%s", out->path);
    if (exp_out_finish(out, 0))
        return 1;
    if (!quiet)
        fprintf(stderr, "export: %zu points, %zu refused by the scene (shown as such); %s\n", n, nref, path);
    return 0;
}

/* Opens the page's output; 1 with a message on failure. */
static int open_out(hy_out *out, const char *path)
{
    hy_error err = {0};
    if (hy_out_open(out, path, HY_OUT_FOLLOW, &err)) { /* the user's own file: as the shell's > */
        fprintf(stderr, "hystviz export: %s\n", err.msg);
        return 1;
    }
    return 0;
}

/* ---- shards ------------------------------------------------------------- */

static void shard_path(const char *out, long k, long n, char *buf, size_t size)
{
    snprintf(buf, size, "%s.shard-%ld-of-%ld", out, k, n);
}

/* Appends text (len bytes) to f as one gzip member. */
static int put_gz(FILE *f, const void *text, size_t len)
{
    unsigned char *gz;
    size_t gzlen;
    hy_error err = {0};
    if (exp_gzip(text, len, &gz, &gzlen, &err))
        return -1;
    size_t w = fwrite(gz, 1, gzlen, f);
    free(gz);
    return w == gzlen ? 0 : -1;
}

static int take_shard(void *ctx, size_t i, point_res *r)
{
    FILE *f = ctx;
    if (r->kind == 2) {
        fprintf(stderr, "hystviz export: point %zu: %s\n", i, r->msg);
        return 1;
    }
    char head[96];
    const char *body = r->kind ? r->msg : (const char *)r->svg;
    size_t blen = r->kind ? strlen(r->msg) : r->len;
    int n = snprintf(head, sizeof head, "%zu %s %zu\n", i, r->kind ? "invalid" : "ok", blen);
    char *rec = malloc((size_t)n + blen + 1);
    if (!rec)
        return 1;
    memcpy(rec, head, (size_t)n);
    memcpy(rec + n, body, blen);
    rec[(size_t)n + blen] = '\n';
    int rc = put_gz(f, rec, (size_t)n + blen + 1) ? 1 : 0;
    free(rec);
    return rc;
}

static int export_run(const export_opts *o)
{
    char *meta = NULL;
    uint64_t hash = 0;
    int rc = describe(o, &meta, &hash);
    if (rc) {
        free(meta);
        return rc;
    }
    size_t npoints = hy_grid_points(&o->grid);
    if (o->sharded) {
        char path[4200];
        shard_path(o->out, o->shard_k, o->shard_n, path, sizeof path);
        hy_out out;
        hy_error err = {0};
        if (hy_out_open(&out, path, 0, &err)) {
            fprintf(stderr, "hystviz export: %s\n", err.msg);
            free(meta);
            return 1;
        }
        FILE *f = hy_out_file(&out);
        char *head = NULL;
        size_t hlen = 0;
        FILE *h = open_memstream(&head, &hlen);
        if (h) {
            fprintf(h, "# hystviz export shard %ld/%ld points %zu scene %016" PRIx64 " meta %zu\n%s\n", o->shard_k,
                    o->shard_n, npoints, hash, strlen(meta), meta);
            fclose(h);
        }
        rc = !head || put_gz(f, head, hlen) ? 1 : 0;
        free(head);
        if (!rc)
            rc = render_all(o, hy_shard_count(npoints, o->shard_k, o->shard_n), take_shard, f);
        rc = exp_out_finish(&out, rc);
        if (!rc && !o->quiet)
            fprintf(stderr, "export: shard %ld/%ld, %zu of %zu points; %s\n", o->shard_k, o->shard_n,
                    hy_shard_count(npoints, o->shard_k, o->shard_n), npoints, path);
        free(meta);
        return rc;
    }
    page_ctx c;
    memset(&c, 0, sizeof c);
    hy_out out;
    if (open_out(&out, o->out)) {
        free(meta);
        return 1;
    }
    if (!(c.pg = exp_page_new())) {
        hy_out_abort(&out);
        free(meta);
        fprintf(stderr, "hystviz export: out of memory\n");
        return 1;
    }
    rc = render_all(o, npoints, take_page, &c);
    if (!rc)
        rc = write_page(&c, meta, &out, o->quiet);
    else
        hy_out_abort(&out);
    exp_page_free(c.pg);
    free(meta);
    return rc;
}

/* ---- --merge -------------------------------------------------------------- */

/* Reads one line (at most size - 1 bytes, '\n' dropped) from a shard. */
static int get_line(gzFile g, char *buf, int size)
{
    if (!gzgets(g, buf, size))
        return -1;
    size_t n = strlen(buf);
    if (!n || buf[n - 1] != '\n')
        return -1;
    buf[n - 1] = '\0';
    return 0;
}

/* Reads n bytes and the '\n' after them into a malloc'd buffer. */
static char *get_bytes(gzFile g, size_t n)
{
    char *b = malloc(n + 1);
    if (b && (gzread(g, b, (unsigned)n + 1) != (int)n + 1 || b[n] != '\n')) {
        free(b);
        return NULL;
    }
    if (b)
        b[n] = '\0';
    return b;
}

typedef struct shard_in {
    gzFile g;
    char path[4200];
} shard_in;

/* Opens the n shards and checks their heads against shard 0's; *meta and
 * *npoints from shard 0.  2 with a message on a mismatch. */
static int open_shards(const char *out, long n, shard_in *in, char **meta, size_t *npoints)
{
    uint64_t hash0 = 0;
    for (long k = 0; k < n; k++) {
        shard_path(out, k, n, in[k].path, sizeof in[k].path);
        if (!(in[k].g = gzopen(in[k].path, "rb"))) {
            fprintf(stderr, "hystviz export --merge: cannot open '%s': %s\n", in[k].path, strerror(errno));
            return 2;
        }
        char line[256];
        long kk, nn;
        size_t p, mlen;
        uint64_t h;
        char *m = NULL;
        if (get_line(in[k].g, line, sizeof line) ||
            sscanf(line, "# hystviz export shard %ld/%ld points %zu scene %" SCNx64 " meta %zu", &kk, &nn, &p, &h,
                   &mlen) != 5 ||
            kk != k || nn != n || mlen > (1u << 28) || !(m = get_bytes(in[k].g, mlen))) {
            fprintf(stderr, "hystviz export --merge: '%s' is not a shard of hystviz export\n", in[k].path);
            return 2;
        }
        if (k && (p != *npoints || h != hash0 || strcmp(m, *meta))) {
            fprintf(stderr,
                    "hystviz export --merge: '%s' belongs to another export than shard 0/%ld (other scene, grid or "
                    "options): re-run shard %ld/%ld with the same command\n",
                    in[k].path, n, k, n);
            free(m);
            return 2;
        }
        if (!k) {
            *meta = m;
            *npoints = p;
            hash0 = h;
        } else
            free(m);
    }
    return 0;
}

/* Point i from shard i mod n into the page. */
static int join_points(shard_in *in, long n, size_t npoints, page_ctx *c)
{
    for (size_t i = 0; i < npoints; i++) {
        shard_in *s = &in[i % (size_t)n];
        char line[128], kind[16];
        size_t idx, len;
        char *body = NULL;
        if (get_line(s->g, line, sizeof line) || sscanf(line, "%zu %15s %zu", &idx, kind, &len) != 3 || idx != i ||
            (strcmp(kind, "ok") && strcmp(kind, "invalid")) || len > ((size_t)1 << 31) ||
            !(body = get_bytes(s->g, len))) {
            fprintf(stderr, "hystviz export --merge: '%s' is incomplete or damaged at point %zu: re-run that shard\n",
                    s->path, i);
            return 2;
        }
        int rc = add_point(c, i, strcmp(kind, "ok") ? 1 : 0, body, len, body);
        free(body);
        if (rc)
            return rc;
    }
    for (long k = 0; k < n; k++) {
        char extra[8];
        if (gzread(in[k].g, extra, 1) > 0) {
            fprintf(stderr, "hystviz export --merge: '%s' has more points than its share of %zu\n", in[k].path,
                    npoints);
            return 2;
        }
    }
    return 0;
}

static int export_merge(const char *out, int quiet)
{
    char dir[4096], prefix[4200];
    const char *slash = strrchr(out, '/');
    snprintf(dir, sizeof dir, "%.*s", slash ? (int)(slash - out) + (slash == out) : 1, slash ? out : ".");
    snprintf(prefix, sizeof prefix, "%s.shard-", slash ? slash + 1 : out);
    long n = 0;
    unsigned char *present = NULL;
    hy_error err = {0};
    if (hy_shard_find(dir, prefix, "", &n, &present, &err)) {
        fprintf(stderr, "hystviz export --merge: %s\n", err.msg);
        return err.code == HY_ENOMEM ? 1 : 2;
    }
    char list[512];
    long missing = hy_shard_missing(n, present, list, sizeof list);
    free(present);
    if (missing) {
        fprintf(stderr,
                "hystviz export --merge: %s: %ld of %ld shards missing:%s\n"
                "  (run the same `hystviz export ... --shard K/%ld` for each, then merge again)\n",
                out, missing, n, list, n);
        return 2;
    }
    shard_in *in = calloc((size_t)n, sizeof *in);
    page_ctx c;
    memset(&c, 0, sizeof c);
    c.pg = exp_page_new();
    char *meta = NULL;
    size_t npoints = 0;
    int rc = !in || !c.pg ? 1 : open_shards(out, n, in, &meta, &npoints);
    hy_out o;
    if (!rc)
        rc = open_out(&o, out);
    if (!rc) {
        rc = join_points(in, n, npoints, &c);
        if (!rc)
            rc = write_page(&c, meta, &o, quiet);
        else
            hy_out_abort(&o);
    }
    for (long k = 0; in && k < n; k++)
        if (in[k].g)
            gzclose(in[k].g);
    if (!rc)
        for (long k = 0; k < n; k++)
            remove(in[k].path);
    free(in);
    free(meta);
    exp_page_free(c.pg);
    return rc;
}

int hy_cmd_export(int argc, char **argv)
{
    export_opts o;
    int rc = parse_opts(argc, argv, &o);
    if (!rc && o.anim) {
        exp_anim_opts ao = {o.scene, o.sets, o.nsets, &o.pol, o.size, o.jobs, o.out, o.quiet};
        rc = exp_anim_run(&ao);
    } else if (!rc)
        rc = o.merge ? export_merge(o.merge, o.quiet) : export_run(&o);
    else if (rc == 1)
        rc = 0;
    hy_grid_free(&o.grid);
    free(o.sets);
    free(o.dirs);
    return rc;
}
