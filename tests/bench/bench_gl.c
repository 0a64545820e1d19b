/* SPDX-License-Identifier: MIT */
/* bench_gl.c: GL frame timings per backend built (OSMesa, EGL): context
 * creation; 1920x1080 and 3840x2160 γ-sweep frames (GL data layer, cairo
 * overlay, finish), the readback alone and libpng writing the frame; the
 * 120-frame 1280x720 γ sweep at -j 1, 2, 4, 8, 16; and, once, libpng at other
 * settings.  Everything is written under a fresh temporary directory
 * ($TMPDIR or /tmp), removed at the end: nothing in the working directory.
 * Prints figures; asserts nothing (exits 77 without a GL context).
 * bench_gl --smoke: the same steps at tiny sizes (a test runs it). */
#define _XOPEN_SOURCE 700
#include <cairo.h>
#include <ftw.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "anim_scenes.h"
#include "hy_cairo.h"
#include "hy_anim.h"
#include "hy_gl.h"

static char tmpdir[4096];             /* every file written goes under it */
static char png_path[4200];           /* tmpdir/bench_frame.png */
static int smoke;                     /* --smoke: tiny sizes, few frames */

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

typedef struct one {
    hy_gl *gl;
    cairo_surface_t *frame;   /* the context's buffer as a cairo RGB24 image */
    const unsigned char *fb;
    unsigned char *rgb;       /* the same frame packed as RGB, for the RGB encode figures */
    int w, h;
} one;

static double t_gl_read, t_composite; /* the two parts of *t_read */
static double frame_log[64];           /* whole render times of the timed frames */
static int n_frame_log;

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* Draws frame index of scene sc into o exactly as hy_anim.c's render_one does
 * (overlay recorded, GL finished into its own buffer, overlay painted onto
 * it); adds the seconds of drawing and of finishing + overlay. */
static int frame(one *o, const anim_scene *sc, void *st, long index, long nframes, double fps, double *t_draw,
                 double *t_read)
{
    hy_error err;
    double t0 = now(), k = o->h / HY_ANIM_POINTS_HIGH;
    cairo_rectangle_t ext = {0, 0, o->w, o->h};
    cairo_surface_t *rec = cairo_recording_surface_create(CAIRO_CONTENT_COLOR_ALPHA, &ext);
    cairo_t *cr = cairo_create(rec);
    cairo_scale(cr, k, k);
    hy_cairo_canvas cc;
    hy_anim_frame f = {index, nframes, index / fps, nframes / fps, (double)index / (nframes - 1), o->w, o->h, k,
                       o->gl, hy_gl_canvas(o->gl, k), hy_canvas_cairo(&cc, cr, NULL)};
    hy_gl_begin(o->gl, (hy_rgb){1, 1, 1});
    int rc = sc->draw(st, &f, &err);
    cairo_destroy(cr);
    double t1 = now();
    const unsigned char *fb = rc ? NULL : hy_gl_finish(o->gl, &err);
    double t1b = now();
    if (fb) {
        if (!o->frame)
            o->frame = cairo_image_surface_create_for_data((unsigned char *)fb, CAIRO_FORMAT_RGB24, o->w, o->h, 4 * o->w);
        cairo_surface_mark_dirty(o->frame);
        cairo_t *c2 = cairo_create(o->frame);
        cairo_set_source_surface(c2, rec, 0, 0);
        cairo_paint(c2);
        cairo_destroy(c2);
        cairo_surface_flush(o->frame);
        o->fb = fb;
    } else
        rc = rc ? rc : HY_ENUM;
    cairo_surface_destroy(rec);
    double t2 = now();
    t_gl_read += t1b - t1, t_composite += t2 - t1b;
    if (n_frame_log < 64)
        frame_log[n_frame_log++] = t2 - t0;
    *t_draw += t1 - t0, *t_read += t2 - t1;
    if (rc)
        fprintf(stderr, "bench_gl: %s\n", err.msg);
    return rc;
}

static void bench_png(const one *o)
{
    static const char *fname[] = {"none", "sub", "up", "paeth", "all"};
    const int levels[] = {1, 2, 3, 6}, strategies[] = {0, 3};
    printf("libpng writing that frame from packed RGB at other settings (mean of 5):\n");
    for (size_t l = 0; l < sizeof levels / sizeof levels[0]; l++)
        for (int sg = 0; sg < 2; sg++)
            for (int fl = 0; fl < 5; fl++) {
                hy_png_opts po = {levels[l], fl, strategies[sg], HY_PNG_ZLIB};
                hy_error err;
                double t0 = now();
                for (int r = 0; r < 5; r++)
                    hy_png_write_rgb(png_path, o->w, o->h, o->rgb, &po, &err);
                double t = (now() - t0) / 5;
                struct stat sb;
                stat(png_path, &sb);
                printf("  level %d %-7s filter %-5s %7.2f ms  %8ld bytes\n", levels[l], sg ? "RLE" : "default",
                       fname[fl], 1e3 * t, (long)sb.st_size);
            }
    hy_png_opts d = hy_png_frame_defaults();
    printf("  (frame default: level %d, strategy %s, filter %s)\n", d.level, d.strategy == 3 ? "RLE" : "default",
           fname[d.filter]);
}

#define NTIMED 20

/* Context creation: the first (library and driver start included) and the
 * median of 5 more, w x h. */
static int bench_create(int w, int h)
{
    hy_gl *g;
    hy_error err;
    double t[6];
    for (int i = 0; i < 6; i++) {
        double t0 = now();
        if (hy_gl_create(&g, w, h, &err)) {
            printf("SKIP: %s\n", err.msg);
            return 77;
        }
        t[i] = now() - t0;
        if (i == 0)
            printf("context: %s\n", hy_gl_describe(g));
        hy_gl_free(g);
    }
    qsort(t + 1, 5, sizeof *t, cmp_double);
    printf("context creation %dx%d (shaders compiled): first %.1f ms, then median %.1f ms\n", w, h, 1e3 * t[0],
           1e3 * t[3]);
    return 0;
}

/* One w x h frame: render (draw + finish + overlay), the readback alone
 * (hy_gl_read of the finished frame, RGBA bottom-up) and the PNG encode. */
static int bench_frame(int w, int h, int png_table)
{
    one o = {.w = w, .h = h};
    hy_error err;
    int ntimed = smoke ? 2 : NTIMED;
    if (hy_gl_create(&o.gl, o.w, o.h, &err)) {
        printf("SKIP: %s\n", err.msg);
        return 77;
    }
    o.rgb = malloc((size_t)o.w * o.h * 3);
    unsigned char *rgba = malloc((size_t)o.w * o.h * 4);
    const anim_scene *sc = anim_scene_find("gamma-sweep-ex3");
    hy_anim_params p = hy_anim_defaults();
    p.width = o.w, p.height = o.h, p.fps = 30, p.duration = 4;
    void *st;
    if (!o.rgb || !rgba || sc->prepare(&st, &p, &err))
        return fprintf(stderr, "bench_gl: %s\n", o.rgb && rgba ? err.msg : "out of memory"), 1;
    double td = 0, tr = 0;
    for (int i = 0; i < 3; i++) /* warm-up: solves this gamma; llvmpipe compiles its shaders on first use */
        frame(&o, sc, st, 60, 120, 30, &td, &tr);
    td = tr = t_gl_read = t_composite = 0;
    n_frame_log = 0;
    for (int i = 0; i < ntimed; i++)
        frame(&o, sc, st, 60, 120, 30, &td, &tr);
    qsort(frame_log, (size_t)n_frame_log, sizeof *frame_log, cmp_double);
    double r_min = frame_log[0], r_med = frame_log[n_frame_log / 2];
    printf("%dx%d gamma-sweep-ex3 frame, %d frames (solve cached): render min %.2f ms, median %.2f ms; "
           "mean parts: draw (GL commands + recorded overlay) %.2f, GL finish %.2f, overlay painted on the frame %.2f\n",
           w, h, ntimed, 1e3 * r_min, 1e3 * r_med, 1e3 * td / ntimed, 1e3 * t_gl_read / ntimed,
           1e3 * t_composite / ntimed);
    double rb[NTIMED];
    for (int i = 0; i < ntimed; i++) {
        double t0 = now();
        hy_gl_read(o.gl, rgba, &err);
        rb[i] = now() - t0;
    }
    qsort(rb, (size_t)ntimed, sizeof *rb, cmp_double);
    printf("  readback alone (glReadPixels RGBA of the finished %dx%d frame): min %.2f ms, median %.2f ms\n", w, h,
           1e3 * rb[0], 1e3 * rb[ntimed / 2]);
    /* the encoder, as the engine calls it on that frame, in each PNG mode (the first: the default) */
#define MODE_NAME(n, level, engine, desc) n,
    static const char *const modes[] = {HY_PNG_MODES(MODE_NAME) NULL};
#undef MODE_NAME
    for (int m = 0; modes[m]; m++) {
        hy_png_opts d;
        hy_png_mode(modes[m], &d, &err);
        double enc[NTIMED];
        for (int i = 0; i < ntimed; i++) {
            double t0 = now();
            hy_png_write_xrgb(png_path, o.w, o.h, o.fb, 4 * o.w, &d, &err);
            enc[i] = now() - t0;
        }
        qsort(enc, (size_t)ntimed, sizeof *enc, cmp_double);
        struct stat sb;
        long bytes = stat(png_path, &sb) ? -1 : (long)sb.st_size;
        printf("  PNG encode of that frame (hy_png_write_xrgb, --png %s): min %.2f ms, median %.2f ms, %ld bytes; "
               "render / encode %.2f (medians)\n", modes[m], 1e3 * enc[0], 1e3 * enc[ntimed / 2], bytes,
               r_med / enc[ntimed / 2]);
    }
    double te = now();              /* the floor: clear and finish an empty frame */
    for (int i = 0; i < 10; i++) {
        hy_gl_begin(o.gl, (hy_rgb){1, 1, 1});
        hy_gl_finish(o.gl, &err);
    }
    printf("  empty %dx%d GL frame (clear + finish, nothing drawn): %.2f ms\n", w, h, 1e2 * (now() - te));
    if (png_table) {
        for (size_t i = 0; i < (size_t)o.w * o.h; i++) { /* packed RGB for the settings table */
            uint32_t px;
            memcpy(&px, o.fb + 4 * i, 4);
            o.rgb[3 * i] = (unsigned char)(px >> 16), o.rgb[3 * i + 1] = (unsigned char)(px >> 8),
                      o.rgb[3 * i + 2] = (unsigned char)px;
        }
        bench_png(&o);
    }
    sc->release(st);
    if (o.frame)
        cairo_surface_destroy(o.frame);
    free(o.rgb);
    free(rgba);
    hy_gl_free(o.gl);
    return 0;
}

static void bench_run(const char *name, int w, int h, int jobs, long nframes)
{
    const anim_scene *sc = anim_scene_find(name);
    char out[4200];
    snprintf(out, sizeof out, "%s/frames", tmpdir);
    hy_anim_params p = hy_anim_defaults();
    p.outdir = out, p.name = name, p.width = w, p.height = h, p.fps = 30, p.duration = nframes / 30.0;
    p.jobs = jobs, p.quiet = 1;
    hy_anim_stats s;
    hy_error err;
    void *st;
    double t0 = now();
    if (sc->prepare(&st, &p, &err) || hy_anim_run(&p, sc->draw, st, &s, &err)) {
        fprintf(stderr, "bench_gl: %s\n", err.msg);
        return;
    }
    double total = now() - t0;
    printf("%s %ld frames %dx%d -j %d: %.2f s total (prepare included), %.1f frames/s; per frame summed over "
           "threads: draw %.1f ms, finish+overlay %.1f ms, png %.1f ms; %s\n", name, s.frames, w, h, jobs, total,
           s.frames / total, 1e3 * s.draw_s / s.frames, 1e3 * s.read_s / s.frames, 1e3 * s.png_s / s.frames,
           sc->describe(st));
    sc->release(st);
}

static int rm_one(const char *path, const struct stat *sb, int flag, struct FTW *ftw)
{
    (void)sb, (void)flag, (void)ftw;
    return remove(path);
}

static int bench_backend(const char *name, int first)
{
    hy_error err;
    if (hy_gl_select(name, &err))
        return fprintf(stderr, "bench_gl: %s\n", err.msg), 1;
    printf("\n== GL backend %s ==\n", name);
    int rc = bench_create(smoke ? 64 : 1280, smoke ? 64 : 720);
    if (!rc)
        rc = bench_frame(smoke ? 64 : 1920, smoke ? 36 : 1080, first && !smoke);
    if (!rc)
        rc = bench_frame(smoke ? 128 : 3840, smoke ? 72 : 2160, 0);
    if (rc)
        return rc;
    /* the clip at -j 1, 2, then past the two cores of the reference machine */
    const int jobs[] = {1, 2, 4, 8, 16};
    for (int i = 0; i < (smoke ? 2 : 5); i++)
        bench_run("gamma-sweep-ex3", smoke ? 64 : 1280, smoke ? 36 : 720, jobs[i], smoke ? 3 : 120);
    if (!smoke)
        bench_run("minor-loop-ex4", 1280, 720, 2, 120);
    return 0;
}

int main(int argc, char **argv)
{
    smoke = argc > 1 && !strcmp(argv[1], "--smoke");
    const char *base = getenv("TMPDIR");
    snprintf(tmpdir, sizeof tmpdir, "%s/hy_bench_gl.XXXXXX", base && *base ? base : "/tmp");
    if (!mkdtemp(tmpdir))
        return perror("bench_gl: mkdtemp"), 1;
    snprintf(png_path, sizeof png_path, "%s/bench_frame.png", tmpdir);
    printf("bench_gl: backends built: %s; writing under %s (removed at the end)\n", hy_gl_backends(), tmpdir);
    char list[64];
    snprintf(list, sizeof list, "%s", hy_gl_backends());
    int rc = 0, first = 1;
    for (char *save, *b = strtok_r(list, " ", &save); b && !rc; b = strtok_r(NULL, " ", &save), first = 0)
        rc = bench_backend(b, first);
    nftw(tmpdir, rm_one, 16, FTW_DEPTH | FTW_PHYS);
    return rc;
}
