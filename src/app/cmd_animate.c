/* SPDX-License-Identifier: MIT */
/* cmd_animate.c: `hystviz animate NAME`: option parsing and the run of one
 * built-in animation (anim_scenes.c) through the engine (hy_anim.c). */
#include "cmd_animate.h"

#include "hy_config.h"

#include <gsl/gsl_errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "anim_worker.h"
#include "cli_util.h"
#include "hy_frame.h"
#include "hy_jobs.h"

#if HY_HAVE_GL
#include <errno.h>
#include <unistd.h>

#include "anim_assemble.h"
#include "anim_scenes.h"
#include "hy_gl.h"
#include "hy_grid.h"
#include "scene_anim.h"

#endif

static const char animate_help[] =
    "usage: hystviz animate NAME|SCENE.scene [-o DIR] [--quality Q] [--size WxH] [--fps F] [--duration S]\n"
    "                            [--frames A:B | --shard K/N] [-j N] [--quiet] [--video mp4|webm|gif [--no-frames]]\n"
    "                            [--gl osmesa|egl] [--include-dir DIR]... [--max-work N] [--set KEY=VALUE]...\n"
    "       hystviz animate NAME|SCENE.scene --assemble mp4|webm|gif [-o DIR] [timing options]\n"
    "       hystviz animate --list | --gl-info [--gl osmesa|egl]\n"
    "\n"
    "Renders animation NAME as PNG frames DIR/NAME/frame_00000.png ... (off-screen OpenGL,\n"
    "OSMesa or EGL, for the data, cairo for text and axes) and a poster DIR/NAME.png (the last frame).\n"
    "A path ending in .scene animates that scene: its [keyframe NAME] sections set numeric\n"
    "keys per frame, its [animation] section gives duration, fps, easing and quality (the\n"
    "options below beat it); NAME is then the scene's output name (docs/SCENES.md).\n"
    "\n"
    "With a scene, --include-dir, --max-work (the budget of all frames together) and\n"
    "--set (in every frame; the keyframes' values beat it) work as for render.\n"
    "-j is at most 64: each thread has its own GL context; the frames are identical\n"
    "for any N.\n"
    "\n";

static const char animate_tail[] =
    "environment:\n"
    "  HYSTVIZ_GL=osmesa|egl    the backend when --gl is not given\n"
    "  HYSTVIZ_EGL_DEVICE=N     EGL device N (--gl-info lists them; default: the first GPU,\n"
    "                           else the software rasteriser)\n"
    "\n"
    "example:\n"
    "  hystviz animate gamma-sweep-ex2 -o frames --quality 480p15 -j 2\n";

/* --png: the modes from their table (hy_frame.h HY_PNG_MODES) */
static const char *png_more(char *buf, size_t size, int doc)
{
    (void)doc;
#define MODE_LINE(n, level, engine, d) "\n" n ": " d
    snprintf(buf, size, "%s", HY_PNG_MODES(MODE_LINE));
#undef MODE_LINE
    return buf;
}

enum { OPT_OUT = CLI_FIRST, OPT_QUALITY, OPT_SIZE, OPT_FPS, OPT_DURATION, OPT_FRAMES, OPT_SHARD, OPT_ASSEMBLE,
       OPT_QUIET, OPT_VIDEO, OPT_NO_FRAMES, OPT_GL, OPT_LIST, OPT_GL_INFO, OPT_INFO, OPT_SET, OPT_WORKER, OPT_PNG };
static const cli_opt animate_opts[] = {
    {"output", 'o', "DIR", "output directory (default: frames)", OPT_OUT, 0, NULL, NULL, NULL},
    {"quality", 0, "Q", "480p15 (854x480@15), 480p30, 720p30 (default), 720p60, 1080p30,\n"
     "1080p60, 1440p60, 2160p60", OPT_QUALITY, 0, NULL, NULL, NULL},
    {"size", 0, "WxH", "frame size in pixels (overrides the preset's)", OPT_SIZE, 0, NULL, NULL, NULL},
    {"fps", 0, "F", "frames per second (overrides the preset's)", OPT_FPS, 0, NULL, NULL, NULL},
    {"duration", 0, "S", "seconds (default: the animation's, 6, or the scene's)", OPT_DURATION, 0, NULL, NULL, NULL},
    {"frames", 0, "A:B", "render only frames A .. B-1 (B may be empty: to the end)", OPT_FRAMES, 0, NULL, NULL,
     NULL},
    {"shard", 0, "K/N", "render only piece K of N (0 <= K < N): frames\n"
     "floor(F*K/N) .. floor(F*(K+1)/N)-1 of the F frames", OPT_SHARD, 0, NULL, NULL, NULL},
    {"assemble", 0, "FMT", "render nothing: encode the frames DIR/NAME/frame_*.png, rendered\n"
     "in pieces (--frames, --shard; same size, fps, duration), into\n"
     "DIR/NAME.FMT with ffmpeg; refused, listing them, if frames are missing", OPT_ASSEMBLE, 0, NULL, NULL, NULL},
    {.group = cli_jobs_opts},
    {"quiet", 'q', NULL, "no progress bar (it is shown only when stderr is a terminal)", OPT_QUIET, 0, NULL, NULL,
     NULL},
    {"video", 0, "FMT", "also encode DIR/NAME.FMT by piping frames to ffmpeg (must be on PATH);\n"
     "the file appears only when the whole clip is encoded", OPT_VIDEO, 0, NULL, NULL, NULL},
    {"no-frames", 0, NULL, "with --video: write the video (and poster) but no PNG frames", OPT_NO_FRAMES, 0, NULL,
     NULL, NULL},
    {"png", 0, "MODE", "how PNG frames are compressed (default: fast):", OPT_PNG, 0, png_more, NULL, NULL},
    {"gl", 0, "B", "GL backend: osmesa or egl (default: $HYSTVIZ_GL, else osmesa where\n"
     "built, else egl); frames are the same on either with the software rasteriser", OPT_GL, 0, NULL, NULL, NULL},
    {"list", 0, NULL, "the animations and what they show, then the GL backend and renderer", OPT_LIST, 0, NULL, NULL,
     NULL},
    {"gl-info", 0, NULL, "the GL backends built, the one used, its EGL devices and renderer", OPT_GL_INFO, 0, NULL,
     NULL, NULL},
    {"info", 0, NULL, "print 'frames N fps F size WxH duration S' for these options and stop", OPT_INFO, 0, NULL, NULL,
     NULL},
    {"set", 0, "KEY=VALUE", "(SCENE.scene) override a key in every frame; repeatable", OPT_SET, CLI_SCENE_KEY, NULL,
     NULL, NULL},
    {.group = cli_policy_opts},
    {"worker", 0, NULL, "answer frame requests on standard input with PNG frames on standard\n"
     "output, one GL context kept (the protocol of hystviz serve: src/io/anim_worker.h)", OPT_WORKER, 0, NULL, NULL,
     NULL},
    {0},
};
static const cli_cmd animate_cli = {"animate", animate_help, animate_tail, "NAME|SCENE.scene", animate_opts};

#if HY_HAVE_GL

typedef struct anim_args {
    hy_anim_params p;
    hy_scene_policy pol;      /* --include-dir, --max-work (scene animations) */
    const char *dirs[64];
    const char *name, *quality, *gl;
    int w, h, have_size, have_fps, have_duration, have_quality, list, gl_info, have_frames, info;
    double fps, duration;
    const char *assemble;     /* --assemble FMT */
    long shard_k, shard_n;    /* --shard K/N (shard_n 0: none) */
    char *sets[SCENE_ANIM_MAX_SETS]; /* --set (scene animations) */
    size_t nsets;
    int worker;               /* --worker */
} anim_args;

static int parse_range(const char *v, long *a, long *b)
{
    char *end;
    if (!v)
        return -1;
    *a = strtol(v, &end, 10);
    if (end == v || *end != ':' || *a < 0)
        return -1;
    const char *s = end + 1;
    if (!*s) {
        *b = -1;
        return 0;
    }
    *b = strtol(s, &end, 10);
    return (*end || *b <= *a) ? -1 : 0;
}

static int parse_size(const char *v, int *w, int *h)
{
    char *end;
    long a = v ? strtol(v, &end, 10) : 0;
    if (!v || end == v || (*end != 'x' && *end != 'X'))
        return -1;
    const char *s = end + 1;
    long b = strtol(s, &end, 10);
    if (end == s || *end || a < 16 || b < 16 || a > 8192 || b > 8192)
        return -1;
    *w = (int)a, *h = (int)b;
    return 0;
}

/* One option; 0 handled or 2 usage error (message printed). */
static int take(anim_args *a, cli_parser *p, int id)
{
    const char *v = p->val;
    long n;
    hy_error err = {0};
    switch (id) {
    case OPT_INFO: return a->info = 1, 0;
    case OPT_LIST: return a->list = 1, 0;
    case OPT_GL_INFO: return a->gl_info = 1, 0;
    case OPT_QUIET: return a->p.quiet = 1, 0;
    case OPT_NO_FRAMES: return a->p.no_frames = 1, 0;
    case OPT_WORKER: return a->worker = 1, 0;
    case OPT_OUT: return a->p.outdir = v, 0;
    case OPT_QUALITY: return a->quality = v, a->have_quality = 1, 0;
    case OPT_VIDEO: return a->p.video = v, 0;
    case OPT_GL: return a->gl = v, 0;
    case OPT_PNG:
        if (hy_png_mode(v, &a->p.png, &err))
            return fprintf(stderr, "hystviz animate: --png: %s\n", err.msg), 2;
        return 0;
    case OPT_ASSEMBLE: return a->assemble = v, 0;
    case OPT_SIZE:
        if (parse_size(v, &a->w, &a->h))
            return fprintf(stderr, "hystviz animate: --size '%s' is not WxH with 16 <= W, H <= 8192\n", v), 2;
        return a->have_size = 1, 0;
    case OPT_FPS:
        if (cli_num(p->optname, v, &a->fps) || !(a->fps > 0 && a->fps <= 240))
            return fprintf(stderr, "hystviz animate: --fps must be in (0, 240]\n"), 2;
        return a->have_fps = 1, 0;
    case OPT_DURATION:
        if (cli_num(p->optname, v, &a->duration) || !(a->duration > 0 && a->duration <= 3600))
            return fprintf(stderr, "hystviz animate: --duration must be in (0, 3600] seconds\n"), 2;
        return a->have_duration = 1, 0;
    case OPT_FRAMES:
        if (parse_range(v, &a->p.first, &a->p.last))
            return fprintf(stderr, "hystviz animate: --frames '%s' is not A:B with 0 <= A < B (or A:)\n", v), 2;
        return a->have_frames = 1, 0;
    case OPT_SHARD:
        if (hy_shard_parse(v, &a->shard_k, &a->shard_n, &err))
            return fprintf(stderr, "hystviz animate: %s\n", err.msg), 2;
        return 0;
    case OPT_SET:
        if (a->nsets == SCENE_ANIM_MAX_SETS)
            return fprintf(stderr, "hystviz animate: at most %d --set\n", SCENE_ANIM_MAX_SETS), 2;
        return a->sets[a->nsets++] = (char *)v, 0;
    case CLI_JOBS:
        if (cli_long(p->optname, v, 1, 64, &n))
            return 2;
        return a->p.jobs = (int)n, 0;
    case CLI_ARG:
        if (a->name)
            return fprintf(stderr, "hystviz animate: one animation at a time ('%s' and '%s')\n", a->name, v), 2;
        return a->name = v, 0;
    default:
        if (a->pol.ninclude_dirs >= sizeof a->dirs / sizeof a->dirs[0])
            return fprintf(stderr, "hystviz animate: at most %zu --include-dir\n", sizeof a->dirs / sizeof a->dirs[0]),
                   2;
        return cli_policy_take(&a->pol, a->dirs, "animate", id, v) < 0 ? 2 : 0;
    }
}

/* 0, 1 help printed, 2 usage error (message printed). */
static int parse_args(int argc, char **argv, anim_args *a)
{
    memset(a, 0, sizeof *a);
    a->p = hy_anim_defaults();
    a->p.outdir = "frames";
    long jobs = hy_jobs_default();
    a->p.jobs = jobs < 64 ? (int)jobs : 64;
    a->quality = "720p30";
    cli_parser p;
    cli_parser_init(&p, &animate_cli, argc, argv, 1);
    for (int id; (id = cli_next(&p)) != CLI_END;) {
        if (id == CLI_STOP || id == CLI_ERROR)
            return id == CLI_STOP ? 1 : 2;
        if (take(a, &p, id))
            return 2;
    }
    if ((a->have_frames && a->shard_n) || (a->assemble && (a->have_frames || a->shard_n || a->p.video))) {
        fprintf(stderr, "hystviz animate: %s\n", a->assemble ? "--assemble renders nothing: it takes no --frames, "
                "--shard or --video" : "--frames and --shard both choose the frames: give one");
        return 2;
    }
    return 0;
}

/* After the timing is settled: --shard's frame range, or --assemble's video.
 * Returns -1 to go on rendering, else the exit status. */
static int split_or_assemble(anim_args *a)
{
    if (a->assemble) {
        hy_error err = {0};
        int st = hy_anim_assemble(&a->p, a->assemble, &err);
        if (st)
            fprintf(stderr, "hystviz animate: %s\n", err.msg);
        else if (!a->p.quiet)
            fprintf(stderr, "%s: %ld frames -> %s/%s.%s\n", a->p.name, hy_anim_nframes(&a->p), a->p.outdir, a->p.name,
                    a->assemble);
        return st == HY_EUNSUP ? 3 : cli_exit_status(st);
    }
    if (a->shard_n) {
        hy_anim_shard_range(hy_anim_nframes(&a->p), a->shard_k, a->shard_n, &a->p.first, &a->p.last);
        if (a->p.first == a->p.last) {
            if (!a->p.quiet)
                fprintf(stderr, "%s: shard %ld/%ld has no frames (%ld in all)\n", a->p.name, a->shard_k, a->shard_n,
                        hy_anim_nframes(&a->p));
            return 0;
        }
    }
    return -1;
}

/* --gl, else $HYSTVIZ_GL, checked before any work or output: 2 for an
 * unknown name or a bad HYSTVIZ_EGL_DEVICE (unless only_name), 3 for a
 * backend not built or without a device. */
static int pick_backend(const char *name, int only_name)
{
    hy_error err = {0};
    int st = name ? hy_gl_select(name, &err) : HY_OK;
    if (!st)
        st = only_name ? (hy_gl_backend_name(&err) ? HY_OK : err.code) : hy_gl_check(&err);
    if (!st)
        return 0;
    fprintf(stderr, "hystviz animate: %s\n", err.msg);
    return st == HY_EUNSUP ? 3 : 2;
}

/* --gl-info on stdout; 3 when no context can be made, 2 for a bad
 * HYSTVIZ_EGL_DEVICE (the reason on stderr too). */
static int gl_info(void)
{
    hy_error err = {0};
    fflush(stdout);
    int st = hy_gl_info(stdout, &err);
    if (st)
        fprintf(stderr, "hystviz animate: no GL context: %s\n", err.msg);
    return st == HY_EINVAL ? 2 : st ? 3 : 0;
}

/* The animations, then the GL backend and renderer they would use (a test
 * context); 3 if none can be made. */
static int list_scenes(void)
{
    for (const anim_scene *const *s = anim_scene_list(); *s; s++)
        printf("%-16s %s\n", (*s)->name, (*s)->summary);
    printf("\n");
    return gl_info();
}

/* --frames A:B must lie within the animation's frames; 2 (usage) if not. */
static int check_range(const anim_args *a)
{
    long nf = hy_anim_nframes(&a->p);
    if (a->p.first >= nf || a->p.last > nf) {
        fprintf(stderr, "hystviz animate: --frames %ld:%ld is outside the %ld frames of %s (0:%ld)\n",
                a->p.first, a->p.last, nf, a->p.name, nf);
        return 2;
    }
    return 0;
}

static int settle(anim_args *a, const anim_scene *sc)
{
    hy_error err = {0};
    double fps;
    if (hy_anim_quality(a->quality, &a->p.width, &a->p.height, &fps, &err)) {
        fprintf(stderr, "hystviz animate: %s\n", err.msg);
        return 2;
    }
    a->p.fps = a->have_fps ? a->fps : fps;
    if (a->have_size)
        a->p.width = a->w, a->p.height = a->h;
    a->p.duration = a->have_duration ? a->duration : sc->duration;
    a->p.name = sc->name;
    return check_range(a);
}

/* Options beat the scene's [animation] values; the frame range must fit. */
static int settle_scene(anim_args *a, const scene_anim *sa)
{
    hy_error err = {0};
    double fps;
    const char *q = a->have_quality ? a->quality : sa->quality;
    if (hy_anim_quality(q, &a->p.width, &a->p.height, &fps, &err)) {
        fprintf(stderr, "hystviz animate: %s\n", err.msg);
        return 2;
    }
    /* --fps, else --quality's rate, else [animation] fps, else its quality's rate */
    a->p.fps = a->have_fps ? a->fps : a->have_quality ? fps : sa->fps_set || !sa->quality_set ? sa->fps : fps;
    if (a->have_size)
        a->p.width = a->w, a->p.height = a->h;
    a->p.duration = a->have_duration ? a->duration : sa->duration;
    a->p.name = sa->name;
    return check_range(a);
}

/* --info: what the options resolve to (hystviz serve reads the frame count). */
static void format_info(const anim_args *a, char *buf, size_t size)
{
    snprintf(buf, size, "frames %ld fps %.17g size %dx%d duration %.17g\n", hy_anim_nframes(&a->p), a->p.fps,
             a->p.width, a->p.height, a->p.duration);
}

static void print_info(const anim_args *a)
{
    char line[200];
    format_info(a, line, sizeof line);
    fputs(line, stdout);
}

static int ends_with(const char *s, const char *tail)
{
    size_t n = strlen(s), m = strlen(tail);
    return n > m && !strcmp(s + n - m, tail);
}

/* `hystviz animate SCENE.scene ...`: validate every frame, then render. */
static int animate_scene(anim_args *a)
{
    hy_error err = {0};
    scene_anim sa;
    gsl_set_error_handler_off();
    if (scene_anim_load_src(&sa, a->name, NULL, 0, a->sets, a->nsets, &a->pol, &err)) {
        fprintf(stderr, "hystviz animate: %s\n", err.msg);
        return err.code == HY_ENOMEM ? 1 : 2; /* an unreadable or invalid scene */
    }
    int r = settle_scene(a, &sa);
    if (!r && a->info) {
        print_info(a);
        return scene_anim_free(&sa), 0;
    }
    if (!r)
        r = split_or_assemble(a); /* -1: render */
    if (r >= 0)
        return scene_anim_free(&sa), r;
    int st = scene_anim_check(&sa, hy_anim_nframes(&a->p), a->p.duration, &err);
    hy_anim_stats stats;
    if (!st)
        st = hy_anim_run(&a->p, scene_anim_draw, &sa, &stats, &err);
    if (st)
        fprintf(stderr, "hystviz animate: %s\n", err.msg);
    else if (!a->p.quiet)
        fprintf(stderr, "%s: %ld frames %dx%d in %.2f s (%.1f frames/s, %d jobs) -> %s/%s/; %zu keyframes, "
                "%ld runs computed, %ld frames reused one\n", sa.name, stats.frames, a->p.width, a->p.height,
                stats.seconds, stats.frames / (stats.seconds + 1e-9), a->p.jobs > 0 ? a->p.jobs : 1, a->p.outdir, sa.name, sa.nkf,
                sa.computes, sa.hits);
    scene_anim_free(&sa);
    return st == HY_EUNSUP ? 3 : cli_exit_status(st);
}

/* ---- --worker: frames on request, one GL context (anim_worker.h) ---- */

typedef struct worker_state {
    const anim_args *opts;    /* the worker's own options: --include-dir, --max-work */
    FILE *out;                /* the records: the standard output the worker was given */
    int out_failed;
    hy_anim_renderer *r;      /* kept while the frame size stays */
    const anim_scene *sc;     /* the built-in prepared last, its state and timing */
    void *state;
    double sc_duration, sc_fps;
    scene_anim *sa;           /* the scene animation loaded and checked last ... */
    char *sa_path;            /* ... its (virtual) path, */
    uint64_t sa_hash;         /* ... its scene's hash (its files, includes, overrides) */
    long sa_frames;
    double sa_duration;
} worker_state;

static void worker_drop_scene(worker_state *ws)
{
    if (ws->sa) {
        scene_anim_free(ws->sa);
        free(ws->sa);
    }
    free(ws->sa_path);
    ws->sa = NULL, ws->sa_path = NULL;
}

/* Frames [p->first, p->last) as "frame I" records; 0 or the exit status the
 * command line would give (the message on stderr). */
static int worker_frames(worker_state *ws, const hy_anim_params *p, hy_anim_draw_fn draw, void *state, long *count)
{
    hy_error err = {0};
    int w = 0, h = 0, st = HY_OK;
    if (ws->r)
        hy_anim_renderer_size(ws->r, &w, &h);
    if (ws->r && (w != p->width || h != p->height)) {
        hy_anim_renderer_free(ws->r);
        ws->r = NULL;
    }
    if (!ws->r)
        st = hy_anim_renderer_new(&ws->r, p->width, p->height, &err);
    for (long i = p->first; !st && i < p->last; i++) {
        char *png = NULL;
        size_t len = 0;
        FILE *m = open_memstream(&png, &len);
        st = m ? hy_anim_renderer_png(ws->r, p, draw, state, i, m, &err) : hy_error_set(&err, HY_ENOMEM, "out of memory");
        if (m)
            fclose(m);
        if (!st && aw_record_write(ws->out, "frame", i, png, len))
            ws->out_failed = 1;
        free(png);
        if (ws->out_failed)
            return 1;
        *count += !st;
    }
    if (!st)
        return 0;
    fprintf(stderr, "hystviz animate: %s\n", err.msg);
    return st == HY_EUNSUP ? 3 : cli_exit_status(st);
}

static int worker_info(worker_state *ws, const anim_args *a)
{
    char line[200];
    format_info(a, line, sizeof line);
    if (aw_record_write(ws->out, "info", 0, line, strlen(line)))
        ws->out_failed = 1;
    return ws->out_failed;
}

/* A built-in animation: prepared once for its timing, kept for the next request. */
static int worker_builtin(worker_state *ws, anim_args *a, const anim_scene *sc, long *count)
{
    int r = settle(a, sc);
    if (r || a->info)
        return r ? r : worker_info(ws, a);
    if (ws->sc != sc || ws->sc_duration != a->p.duration || ws->sc_fps != a->p.fps) {
        if (ws->state)
            ws->sc->release(ws->state);
        ws->sc = NULL, ws->state = NULL;
        hy_error err = {0};
        int st = sc->prepare(&ws->state, &a->p, &err);
        if (st) {
            fprintf(stderr, "hystviz animate: %s\n", err.msg);
            return st == HY_EUNSUP ? 3 : cli_exit_status(st);
        }
        ws->sc = sc, ws->sc_duration = a->p.duration, ws->sc_fps = a->p.fps;
    }
    return worker_frames(ws, &a->p, sc->draw, ws->state, count);
}

/* A scene animation from the request's text: loaded (a parse: includes and
 * overrides go into its hash), checked for every frame only when it is not
 * the one of the last request, then drawn keeping one run (single). */
static int worker_scene(worker_state *ws, anim_args *a, const aw_request *rq, long *count)
{
    hy_error err = {0};
    char *path = strdup(rq->name);
    scene_anim *sa = malloc(sizeof *sa);
    if (!path || !sa || scene_anim_load_src(sa, path, rq->text, rq->len, a->sets, a->nsets, &a->pol, &err)) {
        if (!path || !sa)
            hy_error_set(&err, HY_ENOMEM, "out of memory");
        fprintf(stderr, "hystviz animate: %s\n", err.msg);
        free(path);
        free(sa);
        return err.code == HY_ENOMEM ? 1 : 2;
    }
    int r = settle_scene(a, sa);
    if (!r && a->info)
        r = worker_info(ws, a);
    uint64_t h = hy_scene_hash(sa->scene);
    long nf = hy_anim_nframes(&a->p);
    if (r || a->info || (ws->sa && ws->sa_hash == h && !strcmp(ws->sa_path, path) && ws->sa_frames == nf &&
                         ws->sa_duration == a->p.duration)) {
        scene_anim_free(sa);
        free(sa);
        free(path);
        if (r || a->info)
            return r;
    } else {
        int st = scene_anim_check(sa, nf, a->p.duration, &err);
        if (st) {
            fprintf(stderr, "hystviz animate: %s\n", err.msg);
            scene_anim_free(sa);
            free(sa);
            free(path);
            return st == HY_EUNSUP ? 3 : cli_exit_status(st);
        }
        worker_drop_scene(ws);
        sa->single = 1;
        ws->sa = sa, ws->sa_path = path, ws->sa_hash = h, ws->sa_frames = nf, ws->sa_duration = a->p.duration;
    }
    return worker_frames(ws, &a->p, scene_anim_draw, ws->sa, count);
}

/* One request as the command line `hystviz animate NAME --frames A:B
 * [--size WxH] [--set S]...` (or --info) would run it; 0 or its exit status. */
static int worker_answer(worker_state *ws, const aw_request *rq, long *count)
{
    if (!rq->name[0] || rq->name[0] == '-') {
        fprintf(stderr, "hystviz animate: worker: the name '%.40s' is not an animation\n", rq->name);
        return 2;
    }
    char *argv[9 + 2 * AW_MAX_SETS], size[40], range[64];
    int n = 0;
    argv[n++] = "animate";
    if (rq->width || rq->height) {
        snprintf(size, sizeof size, "%dx%d", rq->width, rq->height);
        argv[n++] = "--size", argv[n++] = size;
    }
    if (!strcmp(rq->op, "info"))
        argv[n++] = "--info";
    else {
        snprintf(range, sizeof range, "%ld:%ld", rq->first, rq->last);
        argv[n++] = "--frames", argv[n++] = range;
    }
    for (size_t i = 0; i < rq->nsets; i++)
        argv[n++] = "--set", argv[n++] = rq->sets[i];
    argv[n++] = "--", argv[n++] = rq->name; /* a name, whatever it starts with */
    anim_args a;
    if (parse_args(n, argv, &a))
        return 2;
    a.pol = ws->opts->pol;
    a.p.quiet = 1, a.p.jobs = 1;
    int scene = ends_with(rq->name, ".scene");
    if (scene != (rq->text != NULL)) {
        fprintf(stderr, "hystviz animate: worker: %s\n", scene ? "a scene animation needs its text" : "a built-in animation takes no text");
        return 2;
    }
    if (scene)
        return worker_scene(ws, &a, rq, count);
    const anim_scene *sc = anim_scene_find(rq->name);
    if (!sc || a.nsets) {
        fprintf(stderr, "hystviz animate: %s '%s'\n", sc ? "--set changes a scene animation; built in:" : "unknown animation",
                rq->name);
        return 2;
    }
    return worker_builtin(ws, &a, sc, count);
}

/* Answers one request: its records, then "end" or "error" with what the
 * command line would have printed on stderr (captured meanwhile).  -1 when
 * the records cannot be written (serve has gone). */
static int worker_request(worker_state *ws, const aw_request *rq)
{
    char *msg = NULL;
    size_t mlen = 0;
    FILE *mem = open_memstream(&msg, &mlen), *saved = stderr;
    if (mem)
        stderr = mem;
    long count = 0;
    int status = worker_answer(ws, rq, &count);
    if (mem) {
        stderr = saved;
        fclose(mem);
    }
    if (!ws->out_failed && status)
        ws->out_failed = aw_record_write(ws->out, "error", status, msg ? msg : "", msg ? mlen : 0) != 0;
    else if (!ws->out_failed)
        ws->out_failed = aw_record_write(ws->out, "end", count, NULL, 0) != 0;
    free(msg);
    return ws->out_failed ? -1 : 0;
}

/* --worker: requests on stdin until its end (anim_worker.h); the records go
 * to the standard output it was given, and anything else printed there to
 * stderr, so nothing can fall between two records. */
static int run_worker(const anim_args *opts)
{
    worker_state ws;
    memset(&ws, 0, sizeof ws);
    ws.opts = opts;
    int fd = dup(1);
    if (fd < 0 || !(ws.out = fdopen(fd, "w")) || dup2(2, 1) < 0) {
        fprintf(stderr, "hystviz animate: --worker: cannot keep standard output: %s\n", strerror(errno));
        if (fd >= 0 && !ws.out)
            close(fd);
        return 1;
    }
    gsl_set_error_handler_off();
    int status = 0;
    for (;;) {
        aw_request rq;
        hy_error err = {0};
        int r = aw_request_read(stdin, &rq, &err);
        if (r == AW_END)
            break;
        if (r) {
            fprintf(stderr, "hystviz animate: %s\n", err.msg);
            aw_record_write(ws.out, "error", 2, err.msg, strlen(err.msg));
            status = 2;
            break;
        }
        r = worker_request(&ws, &rq);
        aw_request_free(&rq);
        if (r) {
            status = 1;
            break;
        }
    }
    worker_drop_scene(&ws);
    if (ws.state)
        ws.sc->release(ws.state);
    hy_anim_renderer_free(ws.r);
    if (fclose(ws.out) && !status)
        status = 1;
    /* the end of a worker: _exit, not exit.  Under EGL, Mesa loads its C++
       runtime (swrast, LLVM) late, and at exit libstdc++'s stream teardown
       flushed a FILE already freed: glibc aborted ("invalid stdio handle",
       worker_egl in a fresh-clone CI; core: ios_base::Init::~Init ->
       fflush of freed memory).  Everything of ours is flushed and freed here. */
    if ((fflush(stdout) || fflush(stderr)) && !status)
        status = 1;
    _exit(status);
}

static int animate(int argc, char **argv)
{
    anim_args a;
    int r = parse_args(argc, argv, &a);
    if (r)
        return r == 1 ? 0 : 2;
    /* Mesa's shader disk cache stays as Mesa sets it (on, under
       ~/.cache/mesa_shader_cache; MESA_SHADER_CACHE_DISABLE=true turns it
       off): without it llvmpipe compiles every shader variant at each run's
       first frames, 0.08-0.1 s of a 120-frame 720p clip's 0.7-0.8 s.  It had
       been turned off for a worker's abort at exit that was libstdc++'s
       stream teardown (run_worker ends with _exit).  The test command points
       it at a directory of its own (tools/setup.sh run_tests). */
    /* With two frame threads or more, llvmpipe rasterises in the thread that
       draws (LP_NUM_THREADS=0) unless the user set it: the frame threads
       already fill the cores, and handing each frame to llvmpipe's own
       threads cost time (the 720p clip at -j 2: 0.69-0.79 s against
       0.77-0.97 s, alternating runs); at -j 1 its threads are kept, and in
       serve's frame workers (--worker: one frame at a time, as soon as it
       can be shown). */
    if (a.p.jobs >= 2 && !a.worker)
        setenv("LP_NUM_THREADS", "0", 0);
    if ((r = pick_backend(a.gl, a.gl_info || a.list)))
        return r;
    if (a.worker)
        return run_worker(&a);
    if (a.gl_info)
        return gl_info();
    if (a.list)
        return list_scenes();
    if (a.name && ends_with(a.name, ".scene"))
        return animate_scene(&a);
    const anim_scene *sc = anim_scene_find(a.name);
    if (sc && a.nsets) {
        fprintf(stderr, "hystviz animate: --set changes a scene animation (SCENE.scene); %s is built in\n", a.name);
        return 2;
    }
    if (!sc) {
        fprintf(stderr, "hystviz animate: %s%s%s (hystviz animate --list shows them)\n",
                a.name ? "unknown animation '" : "which animation?", a.name ? a.name : "", a.name ? "'" : "");
        return 2;
    }
    if ((r = settle(&a, sc)))
        return r;
    if (a.info)
        return print_info(&a), 0;
    if ((r = split_or_assemble(&a)) >= 0)
        return r;
    gsl_set_error_handler_off();
    hy_error err = {0};
    void *state = NULL;
    hy_anim_stats stats;
    int st = sc->prepare(&state, &a.p, &err);
    if (!st)
        st = hy_anim_run(&a.p, sc->draw, state, &stats, &err);
    if (st)
        fprintf(stderr, "hystviz animate: %s\n", err.msg);
    else if (!a.p.quiet)
        fprintf(stderr, "%s: %ld frames %dx%d in %.2f s (%.1f frames/s, %d jobs) -> %s/%s/; %s\n", sc->name,
                stats.frames, a.p.width, a.p.height, stats.seconds, stats.frames / (stats.seconds + 1e-9),
                a.p.jobs, a.p.outdir, sc->name, sc->describe(state));
    if (state)
        sc->release(state);
    return st == HY_EUNSUP ? 3 : cli_exit_status(st);
}

int hy_cmd_animate(int argc, char **argv) { return animate(argc, argv); }

#else /* built without OSMesa */

int hy_cmd_animate(int argc, char **argv)
{
    cli_parser p;
    cli_parser_init(&p, &animate_cli, argc, argv, 1);
    for (int id; (id = cli_next(&p)) != CLI_END;)
        if (id == CLI_STOP || id == CLI_ERROR)
            return id == CLI_STOP ? 0 : 2;
    static const char why[] = "hystviz animate: this hystviz was built without OSMesa and EGL, so it cannot render "
                              "animations (install libosmesa6-dev or libegl-dev and reconfigure with -Dgl=auto)\n";
    for (int i = 1; i < argc; i++)
        if (!strcmp(argv[i], "--worker")) { /* every request answered with the reason (anim_worker.h) */
            aw_request rq;
            hy_error err = {0};
            while (aw_request_read(stdin, &rq, &err) == 0) {
                aw_request_free(&rq);
                if (aw_record_write(stdout, "error", 3, why, strlen(why)))
                    break;
            }
            return 3;
        }
    fputs(why, stderr);
    return 3;
}
#endif
