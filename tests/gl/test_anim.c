/* SPDX-License-Identifier: MIT */
/* test_anim.c: the animation engine and `hystviz animate` in-process: timeline
 * and presets, frame count and size, --frames ranges, byte-identical frames
 * across runs and across -j 1 / -j 2, the γ cache (one solve per distinct γ),
 * reference frames (tests/reference/gl_*.png, max channel difference 8), the
 * ffmpeg message and ordered piping (to a stand-in ffmpeg), errors from a
 * scene and bad parameters. */
#include "hy_config.h"

#include <cairo.h>
#include <dirent.h>
#include <fcntl.h>
#include <math.h>
#include <stdarg.h>
#include <string.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include "anim_scenes.h"
#include "animtest.h"
#include "gltest.h"

#define TOL 8                 /* largest channel difference allowed against a reference */

static void test_timeline(void)
{
    CHECK(hy_ease(HY_EASE_LINEAR, 0.25) == 0.25 && hy_ease(HY_EASE_SMOOTH, 0.5) == 0.5, "ease midpoints");
    CHECK(fabs(hy_ease(HY_EASE_SMOOTH, 0.25) - 0.15625) < 1e-15 && hy_ease(HY_EASE_SMOOTH, 2) == 1, "smoothstep");
    hy_key k[3] = {{1, 1, 0}, {2, 100, HY_EASE_LINEAR}, {3, 50, HY_EASE_SMOOTH}};
    hy_track lin = {k, 3, 0}, lg = {k, 2, 1};
    CHECK(hy_track_eval(&lin, 0) == 1 && hy_track_eval(&lin, 9) == 50, "hold outside the keys");
    CHECK(fabs(hy_track_eval(&lin, 1.5) - 50.5) < 1e-12, "linear key segment");
    CHECK(fabs(hy_track_eval(&lg, 1.5) - 10) < 1e-12, "log track: geometric midpoint, got %g", hy_track_eval(&lg, 1.5));
    CHECK(fabs(hy_track_eval(&lin, 2.5) - 75) < 1e-12, "smooth segment midpoint");
    int w, h;
    double fps;
    hy_error err;
    CHECK(!hy_anim_quality("480p15", &w, &h, &fps, &err) && w == 854 && h == 480 && fps == 15, "480p15");
    CHECK(!hy_anim_quality("2160p60", &w, &h, &fps, &err) && w == 3840 && h == 2160 && fps == 60, "2160p60");
    CHECK(hy_anim_quality("999p1", &w, &h, &fps, &err) == HY_EINVAL && strstr(err.msg, "720p30"), "bad preset");
}

static void test_counts(void)
{
    CHECK(run_cmd("animate", "--list", NULL) == 0, "--list");
    CHECK(run_cmd("animate", "no-such-animation", NULL) == 2, "unknown animation");
    CHECK(run_cmd("animate", "k-cycle-ex3", "--frames", "9:3", NULL) == 2, "bad range");
    CHECK(run_cmd("animate", "k-cycle-ex3", "--size", "12x9000", NULL) == 2, "bad size");
    CHECK(run_cmd("animate", "gamma-sweep-ex2", "-o", "out_count", "--size", "320x180", "--fps", "10", "--duration",
                  "1.5", "--quiet", "-j", "2", NULL) == 0, "count run");
    CHECK(count_frames("out_count/gamma-sweep-ex2") == 15, "15 frames expected, got %ld",
          count_frames("out_count/gamma-sweep-ex2"));
    cairo_surface_t *s = cairo_image_surface_create_from_png("out_count/gamma-sweep-ex2/frame_00014.png");
    CHECK(cairo_surface_status(s) == CAIRO_STATUS_SUCCESS && cairo_image_surface_get_width(s) == 320 &&
          cairo_image_surface_get_height(s) == 180, "frame size");
    cairo_surface_destroy(s);
    CHECK(same_file("out_count/gamma-sweep-ex2/frame_00014.png", "out_count/gamma-sweep-ex2.png"),
          "the poster is the last frame");
    CHECK(run_cmd("animate", "k-cycle-ex3", "-o", "out_range", "--quality", "480p15", "--size", "320x180",
                  "--frames", "5:8", "--quiet", NULL) == 0, "range run");
    CHECK(count_frames("out_range/k-cycle-ex3") == 3 && access("out_range/k-cycle-ex3/frame_00005.png", F_OK) == 0 &&
          access("out_range/k-cycle-ex3/frame_00007.png", F_OK) == 0, "--frames 5:8 renders frames 5, 6, 7");
    CHECK(access("out_range/k-cycle-ex3.png", F_OK) != 0, "no poster without the last frame");
    /* --png: both modes decode to the same pixels, in different bytes; an
     * unknown mode is refused */
    CHECK(run_cmd("animate", "k-cycle-ex3", "-o", "out_png_small", "--size", "320x180", "--frames", "5:6", "--png",
                  "small", "--quiet", NULL) == 0, "--png small");
    CHECK(run_cmd("animate", "k-cycle-ex3", "-o", "out_png_fast", "--size", "320x180", "--frames", "5:6", "--png",
                  "fast", "--quiet", NULL) == 0, "--png fast");
    CHECK(run_cmd("animate", "k-cycle-ex3", "--png", "tiny", NULL) == 2, "--png tiny is refused");
    cairo_surface_t *pa = cairo_image_surface_create_from_png("out_png_small/k-cycle-ex3/frame_00005.png");
    cairo_surface_t *pb = cairo_image_surface_create_from_png("out_png_fast/k-cycle-ex3/frame_00005.png");
    int pw = cairo_image_surface_get_width(pa), ph = cairo_image_surface_get_height(pa), same_px = pw == 320;
    cairo_surface_flush(pa), cairo_surface_flush(pb);
    for (int y = 0; same_px && y < ph; y++)   /* RGB24 words, the unused byte aside */
        for (int x = 0; x < pw; x++) {
            uint32_t u, v;
            memcpy(&u, cairo_image_surface_get_data(pa) + (size_t)y * cairo_image_surface_get_stride(pa) + 4 * x, 4);
            memcpy(&v, cairo_image_surface_get_data(pb) + (size_t)y * cairo_image_surface_get_stride(pb) + 4 * x, 4);
            same_px &= ((u ^ v) & 0xffffffu) == 0;
        }
    CHECK(same_px, "--png small and --png fast decode to different pixels");
    CHECK(!same_file("out_png_small/k-cycle-ex3/frame_00005.png", "out_png_fast/k-cycle-ex3/frame_00005.png"),
          "--png small wrote the same bytes as --png fast");
    cairo_surface_destroy(pa);
    cairo_surface_destroy(pb);
}

/* Runs scene name at 320x180, 8 fps for 3 s into dir with jobs threads; returns solves. */
static long run_scene(const char *name, const char *dir, int jobs)
{
    const anim_scene *sc = anim_scene_find(name);
    hy_anim_params p = hy_anim_defaults();
    p.outdir = dir, p.name = name, p.width = 320, p.height = 180, p.fps = 8, p.duration = 3;
    p.jobs = jobs, p.quiet = 1;
    void *st = NULL;
    hy_error err;
    long solves = -1;
    int rc = sc->prepare(&st, &p, &err);
    if (!rc)
        rc = hy_anim_run(&p, sc->draw, st, NULL, &err);
    CHECK(rc == 0, "%s: %s", name, err.msg);
    if (!rc && strstr(name, "sweep"))
        solves = anim_scene_solves(st);
    if (st)
        sc->release(st);
    return solves;
}

/* Distinct γ of the sweeps' schedule (anim_scenes.c: log-interpolated from
 * 1 at 8 % to 1000 at 88 % of the duration, smooth) over 24 frames at 8 fps,
 * plus the γ = 1 that prepare solves; with trail, also the γ of 0.25, 0.5,
 * 0.75 and 1 s before each frame (Examples 2 and 3 draw those loops fading). */
static long distinct_gammas(int trail)
{
    hy_key k[2] = {{0.08 * 3, 1.0, HY_EASE_LINEAR}, {0.88 * 3, 1000.0, HY_EASE_SMOOTH}};
    hy_track tr = {k, 2, 1};
    double g[24 * 5 + 1];
    long n = 0;
    g[n++] = 1.0;
    for (int i = 0; i < 24; i++)
        for (int j = 0; j <= (trail ? 4 : 0); j++) {
            double t = i / 8.0 - 0.25 * j;
            if (t < 0)
                continue;
            double v = hy_track_eval(&tr, t);
            int seen = 0;
            for (long m = 0; m < n; m++)
                seen |= g[m] == v;
            if (!seen)
                g[n++] = v;
        }
    return n;
}

static void test_identical(void)
{
    const char *names[] = {"gamma-sweep-ex3", "minor-loop-ex4", "gamma-sweep-ex2", "k-cycle-ex2"};
    for (int i = 0; i < 4; i++) {
        long s1 = run_scene(names[i], "out_j1", 1), s2 = run_scene(names[i], "out_j2", 2);
        long s3 = run_scene(names[i], "out_j2b", 2);
        CHECK(s1 == s2 && s2 == s3, "%s: solves differ between runs (%ld, %ld, %ld)", names[i], s1, s2, s3);
        if (s1 >= 0)
            CHECK(s1 == distinct_gammas(1), "%s: %ld solves for %ld distinct gamma", names[i], s1, distinct_gammas(1));
        for (int f = 0; f < 24; f++) {
            char a[256], b[256], c[256];
            snprintf(a, sizeof a, "out_j1/%s/frame_%05d.png", names[i], f);
            snprintf(b, sizeof b, "out_j2/%s/frame_%05d.png", names[i], f);
            snprintf(c, sizeof c, "out_j2b/%s/frame_%05d.png", names[i], f);
            CHECK(same_file(a, b), "%s differs between -j 1 and -j 2", a);
            CHECK(same_file(b, c), "%s differs between two -j 2 runs", b);
        }
    }
}

/* Compares frame path with tests/reference/ref (or writes it with HY_UPDATE_REFERENCE=1). */
static void compare_reference(const char *path, const char *ref)
{
    char refpath[1024];
    snprintf(refpath, sizeof refpath, "%s/tests/reference/%s", HY_SOURCE_DIR, ref);
    cairo_surface_t *a = cairo_image_surface_create_from_png(path);
    if (getenv("HY_UPDATE_REFERENCE")) {
        CHECK(cairo_surface_write_to_png(a, refpath) == CAIRO_STATUS_SUCCESS, "writing %s", refpath);
        cairo_surface_destroy(a);
        return;
    }
    cairo_surface_t *b = cairo_image_surface_create_from_png(refpath);
    int w = cairo_image_surface_get_width(a), h = cairo_image_surface_get_height(a);
    int ok = cairo_surface_status(a) == 0 && cairo_surface_status(b) == 0 && w == cairo_image_surface_get_width(b) &&
             h == cairo_image_surface_get_height(b);
    CHECK(ok, "%s or %s unreadable or of another size", path, refpath);
    int maxd = 0;
    long ndiff = 0;
    for (int y = 0; ok && y < h; y++) {
        const unsigned *ra = (const void *)(cairo_image_surface_get_data(a) + y * cairo_image_surface_get_stride(a));
        const unsigned *rb = (const void *)(cairo_image_surface_get_data(b) + y * cairo_image_surface_get_stride(b));
        for (int x = 0; x < w; x++)
            for (int sh = 0; sh < 24; sh += 8) {
                int d = abs((int)((ra[x] >> sh) & 255) - (int)((rb[x] >> sh) & 255));
                maxd = d > maxd ? d : maxd;
                ndiff += d > 0;
            }
    }
    printf("%-22s vs reference: %ld channels differ, largest difference %d (tolerance %d)\n", ref, ndiff, maxd, TOL);
    CHECK(maxd <= TOL, "%s differs from %s by %d > %d", path, refpath, maxd, TOL);
    cairo_surface_destroy(a);
    cairo_surface_destroy(b);
}

static void test_references(void)
{
    compare_reference("out_j1/gamma-sweep-ex3/frame_00012.png", "gl_gamma_sweep_ex3.png");
    compare_reference("out_j1/minor-loop-ex4.png", "gl_minor_loop_ex4.png");
    compare_reference("out_j1/gamma-sweep-ex2/frame_00010.png", "gl_gamma_sweep_ex2.png");
    compare_reference("out_j1/k-cycle-ex2/frame_00015.png", "gl_k_cycle_ex2.png");
}

static int failing_draw(void *state, const hy_anim_frame *f, hy_error *err)
{
    (void)state;
    return f->index == 3 ? hy_error_set(err, HY_ENUM, "scene failed at frame %ld", f->index) : HY_OK;
}

static void test_errors(void)
{
    hy_anim_params p = hy_anim_defaults();
    p.outdir = "out_err", p.name = "fails", p.width = 64, p.height = 64, p.fps = 10, p.duration = 1, p.quiet = 1;
    hy_error err;
    CHECK(hy_anim_run(&p, failing_draw, NULL, NULL, &err) == HY_ENUM && strstr(err.msg, "frame 3"),
          "scene error not passed on: %s", err.msg);
    p.first = 20;
    CHECK(hy_anim_run(&p, failing_draw, NULL, NULL, &err) == HY_EINVAL && strstr(err.msg, "0:10"),
          "range outside the animation: %s", err.msg);
    p.first = 0, p.video = "mp4";
    char *old = getenv("PATH") ? strdup(getenv("PATH")) : NULL;
    setenv("PATH", "/nonexistent-hystviz-test", 1);
    int rc = hy_anim_run(&p, failing_draw, NULL, NULL, &err);
    printf("video without ffmpeg: %s\n", err.msg);
    CHECK(rc == HY_EUNSUP && strstr(err.msg, "ffmpeg") && strstr(err.msg, "not on PATH") &&
          strstr(err.msg, "frame_%05d.png"), "ffmpeg message: %s", err.msg);
    CHECK(run_cmd("animate", "k-cycle-ex3", "-o", "out_err", "--video", "webm", "--quiet", NULL) == 3,
          "animate --video without ffmpeg exits 3");
    p.video = "avi";
    CHECK(hy_anim_run(&p, failing_draw, NULL, NULL, &err) == HY_EINVAL && strstr(err.msg, "avi"), "bad format");
    if (old)
        setenv("PATH", old, 1);
    free(old);
}

/* A stand-in ffmpeg on PATH that stores its stdin in its last argument:
 * the raw frames must arrive complete and in order for any -j. */
static void test_video_pipe(void)
{
    mkdir("fakebin", 0755);
    FILE *f = fopen("fakebin/ffmpeg", "w");
    fputs("#!/bin/sh\nfor a; do last=$a; done\ncat > \"$last\"\n", f);
    fclose(f);
    chmod("fakebin/ffmpeg", 0755);
    char cwd[900], path[2000];
    CHECK(getcwd(cwd, sizeof cwd) != NULL, "getcwd");
    char *old = getenv("PATH") ? strdup(getenv("PATH")) : NULL;
    snprintf(path, sizeof path, "%s/fakebin:%s", cwd, old ? old : "/usr/bin:/bin");
    setenv("PATH", path, 1);
    CHECK(run_cmd("animate", "k-cycle-ex2", "-o", "out_vid1", "--size", "64x48", "--fps", "10", "--duration", "2",
                  "--video", "mp4", "--quiet", "-j", "1", NULL) == 0, "video run -j 1");
    CHECK(run_cmd("animate", "k-cycle-ex2", "-o", "out_vid2", "--size", "64x48", "--fps", "10", "--duration", "2",
                  "--video", "mp4", "--quiet", "-j", "2", NULL) == 0, "video run -j 2");
    size_t n1 = 0, n2 = 0;
    char *a = hy_test_slurp("out_vid1/k-cycle-ex2.mp4", &n1), *b = hy_test_slurp("out_vid2/k-cycle-ex2.mp4", &n2);
    CHECK(a && n1 == 20 * 64 * 48 * 4, "ffmpeg got %zu bytes, expected %d (20 frames of 64 x 48, 4 bytes a pixel)", n1, 20 * 64 * 48 * 4);
    CHECK(a && b && n1 == n2 && !memcmp(a, b, n1), "piped frames differ between -j 1 and -j 2 (order)");
    free(a);
    free(b);
    struct stat sb;
    CHECK(count_tmps("out_vid1") == 0, "the temporary video was renamed");
    /* --no-frames: the video and the poster, no frame directory */
    CHECK(run_cmd("animate", "k-cycle-ex2", "-o", "out_vid3", "--size", "64x48", "--fps", "10", "--duration", "2",
                  "--video", "mp4", "--no-frames", "--quiet", NULL) == 0, "video run --no-frames");
    size_t n3 = 0;
    char *c = hy_test_slurp("out_vid3/k-cycle-ex2.mp4", &n3);
    CHECK(c && n3 == n1, "--no-frames: ffmpeg got %zu bytes, expected %zu", n3, n1);
    free(c);
    CHECK(stat("out_vid3/k-cycle-ex2", &sb) != 0, "--no-frames wrote a frame directory");
    CHECK(stat("out_vid3/k-cycle-ex2.png", &sb) == 0, "--no-frames still writes the poster");
    CHECK(run_cmd("animate", "k-cycle-ex2", "-o", "out_vid4", "--no-frames", "--quiet", NULL) != 0 &&
              stat("out_vid4", &sb) != 0,
          "--no-frames without --video is refused before anything is written");
    /* an ffmpeg that fails: no video file and no temporary left, status non-zero */
    f = fopen("fakebin/ffmpeg", "w");
    fputs("#!/bin/sh\nfor a; do last=$a; done\nhead -c 100 > \"$last\"\ncat > /dev/null\nexit 1\n", f);
    fclose(f);
    CHECK(run_cmd("animate", "k-cycle-ex2", "-o", "out_vid5", "--size", "64x48", "--fps", "10", "--duration", "2",
                  "--video", "mp4", "--quiet", NULL) != 0, "a failing ffmpeg fails the run");
    CHECK(stat("out_vid5/k-cycle-ex2.mp4", &sb) != 0 && count_tmps("out_vid5") == 0,
          "a failing ffmpeg leaves no video and no temporary");
    if (old)
        setenv("PATH", old, 1);
    free(old);
}

/* A shorter re-run leaves exactly its own frames (ffmpeg -i frame_%05d.png
 * would encode a longer run's tail after them), and the temporaries of a
 * killed run go; a locked one (a live writer's) and other files stay. */
static void test_rerun(void)
{
    const char *d = "out_rerun/k-cycle-ex2";
    CHECK(run_cmd("animate", "k-cycle-ex2", "-o", "out_rerun", "--size", "64x48", "--fps", "10", "--duration", "1",
                  "--quiet", NULL) == 0, "first run");
    CHECK(count_frames(d) == 10, "10 frames expected, got %ld", count_frames(d));
    static const char *const planted[] = {"out_rerun/k-cycle-ex2/.frame_00004.png.hystviz-tmp.AbC123",
                                          "out_rerun/.k-cycle-ex2.png.hystviz-tmp.dEf456",
                                          "out_rerun/k-cycle-ex2/frame_00002.png.tmp.Xy9Zq1",
                                          "out_rerun/k-cycle-ex2/.live.png.hystviz-tmp.LiVe01",
                                          "out_rerun/k-cycle-ex2/notes.txt"};
    for (size_t i = 0; i < sizeof planted / sizeof *planted; i++)
        fclose(fopen(planted[i], "w"));
    int live = open(planted[3], O_RDONLY);
    CHECK(live >= 0 && flock(live, LOCK_EX) == 0, "lock the live temporary");
    CHECK(run_cmd("animate", "k-cycle-ex2", "-o", "out_rerun", "--size", "64x48", "--fps", "10", "--duration", "0.5",
                  "--quiet", NULL) == 0, "shorter run");
    CHECK(count_frames(d) == 5, "the shorter run left %ld frames, expected its 5", count_frames(d));
    CHECK(access("out_rerun/k-cycle-ex2/frame_00004.png", F_OK) == 0 &&
          access("out_rerun/k-cycle-ex2/frame_00005.png", F_OK) != 0 &&
          access("out_rerun/k-cycle-ex2/frame_00009.png", F_OK) != 0, "frames 5..9 of the longer run remain");
    for (size_t i = 0; i < 3; i++)
        CHECK(access(planted[i], F_OK) != 0, "stale temporary %s kept", planted[i]);
    CHECK(access(planted[3], F_OK) == 0 && access(planted[4], F_OK) == 0, "a locked temporary or a user file removed");
    close(live);
    /* a range run keeps the other frames of the same animation */
    CHECK(run_cmd("animate", "k-cycle-ex2", "-o", "out_rerun", "--size", "64x48", "--fps", "10", "--duration", "0.5",
                  "--frames", "2:3", "--quiet", NULL) == 0, "range run");
    CHECK(count_frames(d) == 5, "a --frames run removed frames: %ld left", count_frames(d));
}

static int ok_draw(void *state, const hy_anim_frame *f, hy_error *err)
{
    (void)state, (void)f, (void)err;
    return HY_OK;
}

/* Without --quiet the engine still prints nothing when stderr is not a terminal. */
static void test_silent(void)
{
    hy_anim_params p = hy_anim_defaults();
    p.outdir = "out_silent", p.name = "quiet", p.width = 32, p.height = 32, p.fps = 10, p.duration = 0.5;
    fflush(stderr);
    int saved = dup(2);
    FILE *f = fopen("out_silent_stderr.txt", "w");
    dup2(fileno(f), 2);
    hy_error err;
    int rc = hy_anim_run(&p, ok_draw, NULL, NULL, &err);
    fflush(stderr);
    dup2(saved, 2);
    close(saved);
    fclose(f);
    size_t n = 0;
    free(hy_test_slurp("out_silent_stderr.txt", &n));
    CHECK(rc == 0 && n == 0, "progress output on a non-terminal stderr (%zu bytes)", n);
}

int main(void)
{
    hy_gl_free(gl_or_skip(64, 64));
    test_timeline();
    test_counts();
    test_identical();
    test_references();
    test_errors();
    test_video_pipe();
    test_rerun();
    test_silent();
    return hy_test_finish("anim");
}
