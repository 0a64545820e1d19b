/* cmd_animate.c: `hystviz animate NAME`: option parsing and the run of one
 * built-in animation (anim_scenes.c) through the engine (hy_anim.c). */
#include "cmd_animate.h"

#include "hy_config.h"

#include <gsl/gsl_errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli_util.h"
#include "hy_jobs.h"

#if HY_HAVE_GL
#include "anim_assemble.h"
#include "anim_scenes.h"
#include "hy_gl.h"
#include "hy_grid.h"
#include "scene_anim.h"

#endif

static const char animate_help[] =
    "usage: hystviz animate NAME|SCENE.scene [-o DIR] [--quality Q] [--size WxH] [--fps F] [--duration S]\n"
    "                            [--frames A:B | --shard K/N] [-j N] [--quiet] [--video mp4|webm|gif [--no-frames]]\n"
    "                            [--gl osmesa|egl] [--include-dir DIR]... [--max-work N]\n"
    "       hystviz animate NAME|SCENE.scene --assemble mp4|webm|gif [-o DIR] [timing options]\n"
    "       hystviz animate --list | --gl-info [--gl osmesa|egl]\n"
    "\n"
    "Renders animation NAME as PNG frames DIR/NAME/frame_00000.png ... (off-screen OpenGL,\n"
    "OSMesa or EGL, for the data, cairo for text and axes) and a poster DIR/NAME.png (the last frame).\n"
    "A path ending in .scene animates that scene: its [keyframe NAME] sections set numeric\n"
    "keys per frame, its [animation] section gives duration, fps, easing and quality (the\n"
    "options below beat it); NAME is then the scene's output name (docs/SCENES.md).\n"
    "\n"
    "  -o, --output DIR   output directory (default: frames)\n"
    "  --quality Q        480p15 (854x480@15), 480p30, 720p30 (default), 720p60, 1080p30,\n"
    "                     1080p60, 1440p60, 2160p60\n"
    "  --size WxH         frame size in pixels (overrides the preset's)\n"
    "  --fps F            frames per second (overrides the preset's)\n"
    "  --duration S       seconds (default: the animation's, 6, or the scene's)\n"
    "  --frames A:B       render only frames A .. B-1 (B may be empty: to the end)\n"
    "  --shard K/N        render only piece K of N (0 <= K < N): frames\n"
    "                     floor(F*K/N) .. floor(F*(K+1)/N)-1 of the F frames\n"
    "  --assemble FMT     render nothing: encode the frames DIR/NAME/frame_*.png, rendered\n"
    "                     in pieces (--frames, --shard; same size, fps, duration), into\n"
    "                     DIR/NAME.FMT with ffmpeg; refused, listing them, if frames are missing\n"
    "  -j, --jobs N\n" /* hy_jobs_help: the one description of -j */
    "                     (at most 64): each thread has its own GL context; the\n"
    "                     frames are identical for any N\n"
    "  --quiet            no progress bar (it is shown only when stderr is a terminal)\n"
    "  --video FMT        also encode DIR/NAME.FMT by piping frames to ffmpeg (must be on PATH);\n"
    "                     the file appears only when the whole clip is encoded\n"
    "  --no-frames        with --video: write the video (and poster) but no PNG frames\n"
    "  --gl B             GL backend: osmesa or egl (default: $HYSTVIZ_GL, else osmesa where\n"
    "                     built, else egl); frames are the same on either with the software rasteriser\n"
    "  --list             the animations and what they show, then the GL backend and renderer\n"
    "  --gl-info          the GL backends built, the one used, its EGL devices and renderer\n"
    "  --info             print 'frames N fps F size WxH duration S' for these options and stop\n"
    "\n"
    "environment:\n"
    "  HYSTVIZ_GL=osmesa|egl    the backend when --gl is not given\n"
    "  HYSTVIZ_EGL_DEVICE=N     EGL device N (--gl-info lists them; default: the first GPU,\n"
    "                           else the software rasteriser)\n"
    "  --include-dir DIR  (SCENE.scene) a directory the scene may include from; repeatable\n"
    "  --max-work N       (SCENE.scene) work budget of all frames together (default 1e8)\n"
    "\n"
    "example:\n"
    "  hystviz animate gamma-sweep-ex2 -o frames --quality 480p15 -j 2\n";

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

/* One option at argv[*i]; 0 handled, 1 help printed, 2 usage error. */
static int parse_one(anim_args *a, int argc, char **argv, int *i)
{
    const char *s = argv[*i], *v = *i + 1 < argc ? argv[*i + 1] : NULL;
    long n;
    if (!strcmp(s, "-h") || !strcmp(s, "--help"))
        return hy_jobs_help(stdout, animate_help), 1;
    if (!strcmp(s, "--info"))
        return a->info = 1, 0;
    if (!strcmp(s, "--list"))
        return a->list = 1, 0;
    if (!strcmp(s, "--gl-info"))
        return a->gl_info = 1, 0;
    if (!strcmp(s, "--quiet") || !strcmp(s, "-q"))
        return a->p.quiet = 1, 0;
    if (!strcmp(s, "--no-frames"))
        return a->p.no_frames = 1, 0;
    if (s[0] != '-')
        return fprintf(stderr, "hystviz animate: one animation at a time ('%s' and '%s')\n", a->name, s), 2;
    if ((!strncmp(s, "--include-dir", 13) || !strncmp(s, "--max-work", 10)) && a->pol.ninclude_dirs < 64)
        switch (cli_policy_option(&a->pol, a->dirs, "animate", argc, argv, i)) {
        case 1: return 0;
        case 0: return fprintf(stderr, "hystviz animate: unknown option '%s' (see hystviz animate --help)\n", s), 2;
        default: return 2;
        }
    if (!v)
        return fprintf(stderr, "hystviz animate: unknown option '%s' or it needs a value (see --help)\n", s), 2;
    (*i)++;
    if (!strcmp(s, "-o") || !strcmp(s, "--output"))
        a->p.outdir = v;
    else if (!strcmp(s, "--quality"))
        a->quality = v, a->have_quality = 1;
    else if (!strcmp(s, "--video"))
        a->p.video = v;
    else if (!strcmp(s, "--gl"))
        a->gl = v;
    else if (!strcmp(s, "--size")) {
        if (parse_size(v, &a->w, &a->h))
            return fprintf(stderr, "hystviz animate: --size '%s' is not WxH with 16 <= W, H <= 8192\n", v), 2;
        a->have_size = 1;
    } else if (!strcmp(s, "--fps")) {
        if (cli_num(s, v, &a->fps) || !(a->fps > 0 && a->fps <= 240))
            return fprintf(stderr, "hystviz animate: --fps must be in (0, 240]\n"), 2;
        a->have_fps = 1;
    } else if (!strcmp(s, "--duration")) {
        if (cli_num(s, v, &a->duration) || !(a->duration > 0 && a->duration <= 3600))
            return fprintf(stderr, "hystviz animate: --duration must be in (0, 3600] seconds\n"), 2;
        a->have_duration = 1;
    } else if (!strcmp(s, "--frames")) {
        if (parse_range(v, &a->p.first, &a->p.last))
            return fprintf(stderr, "hystviz animate: --frames '%s' is not A:B with 0 <= A < B (or A:)\n", v), 2;
        a->have_frames = 1;
    } else if (!strcmp(s, "--shard")) {
        hy_error err = {0};
        if (hy_shard_parse(v, &a->shard_k, &a->shard_n, &err))
            return fprintf(stderr, "hystviz animate: %s\n", err.msg), 2;
    } else if (!strcmp(s, "--assemble")) {
        a->assemble = v;
    } else if (!strcmp(s, "-j") || !strcmp(s, "--jobs")) {
        if (cli_long(s, v, 1, 64, &n))
            return 2;
        a->p.jobs = (int)n;
    } else
        return fprintf(stderr, "hystviz animate: unknown option '%s' (see hystviz animate --help)\n", s), 2;
    return 0;
}

static int parse_args(int argc, char **argv, anim_args *a)
{
    memset(a, 0, sizeof *a);
    a->p = hy_anim_defaults();
    a->p.outdir = "frames";
    long jobs = hy_jobs_default();
    a->p.jobs = jobs < 64 ? (int)jobs : 64;
    a->quality = "720p30";
    for (int i = 1; i < argc; i++) {
        if (argv[i][0] != '-' && !a->name) {
            a->name = argv[i];
            continue;
        }
        int r = parse_one(a, argc, argv, &i);
        if (r)
            return r;
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
static void print_info(const anim_args *a)
{
    printf("frames %ld fps %.17g size %dx%d duration %.17g\n", hy_anim_nframes(&a->p), a->p.fps, a->p.width, a->p.height,
           a->p.duration);
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
    if (scene_anim_load_policy(&sa, a->name, &a->pol, &err)) {
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

static int animate(int argc, char **argv)
{
    anim_args a;
    int r = parse_args(argc, argv, &a);
    if (r)
        return r == 1 ? 0 : 2;
    if ((r = pick_backend(a.gl, a.gl_info || a.list)))
        return r;
    if (a.gl_info)
        return gl_info();
    if (a.list)
        return list_scenes();
    if (a.name && ends_with(a.name, ".scene"))
        return animate_scene(&a);
    const anim_scene *sc = anim_scene_find(a.name);
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
    if (argc > 1 && (!strcmp(argv[1], "--help") || !strcmp(argv[1], "-h"))) {
        hy_jobs_help(stdout, animate_help);
        return 0;
    }
    fprintf(stderr, "hystviz animate: this hystviz was built without OSMesa and EGL, so it cannot render "
            "animations (install libosmesa6-dev or libegl-dev and reconfigure with -Dgl=auto)\n");
    return 3;
}
#endif
