/* SPDX-License-Identifier: MIT */
/* test_scene_anim.c: `hystviz animate SCENE.scene` ([keyframe NAME] sections):
 * frame count and size, byte-identical frames for -j 1 and -j 2, first and
 * last frames equal to the still rendered through the same GL path with the
 * start and end values given as --set overrides, one run per distinct set of
 * values, keyframe errors with file:line:col (and no frames written; also a
 * combination of values the model refuses at some frame), and
 * interpolation that hits the key values exactly at the key times. */
#include "hy_config.h"

#include <cairo.h>
#include <gsl/gsl_errno.h>
#include <dirent.h>
#include <math.h>
#include <stdarg.h>
#include <string.h>
#include <unistd.h>

#include "animtest.h"
#include "gltest.h"
#include "scene_anim.h"
#include "scene_run.h"

/* y_γ of a LuGre model under the bimodal input with γ swept 1 -> 1000 (log)
 * and σ0 moved 1 -> 3 and held; line numbers matter to the error tests. */
static const char good_scene[] =
    "[model]\n"
    "kind = lugre\n"
    "[input]\n"
    "kind = bimodal\n"
    "[compute]\n"
    "cycles = 2\n"
    "points = 400\n"
    "[figure]\n"
    "kind = loop\n"
    "ylim = -1.5, 1.5\n"
    "[series ystar]\n"
    "data = ystar\n"
    "[series g]\n"
    "data = ygamma\n"
    "gamma = 5\n"
    "label = \"y_\\gamma\"\n"
    "[animation]\n"
    "duration = 1\n"
    "fps = 10\n"
    "easing = linear\n"
    "[keyframe gamma]\n"
    "key = \"series.g.gamma\"\n"
    "times = 0, 0.5, 1\n"
    "values = 1, 1, 1000\n"
    "log = true\n"
    "[keyframe sigma]\n"
    "key = \"model.sigma0\"\n"
    "times = 0, 1\n"
    "values = 1, 3\n"
    "easing = smooth\n";

static void write_file(const char *path, const char *text)
{
    FILE *f = fopen(path, "w");
    if (!f || fputs(text, f) < 0 || fclose(f)) {
        printf("cannot write %s\n", path);
        exit(1);
    }
}

static void test_frames(void)
{
    CHECK(run_cmd("animate", "kf.scene", "-o", "out_kf1", "--size", "320x180", "--quiet", "-j", "1", NULL) == 0,
          "keyframed scene, -j 1");
    CHECK(run_cmd("animate", "kf.scene", "-o", "out_kf2", "--size", "320x180", "--quiet", "-j", "2", NULL) == 0,
          "keyframed scene, -j 2");
    CHECK(count_frames("out_kf1/kf") == 10, "10 frames (1 s at the scene's 10 fps), got %ld", count_frames("out_kf1/kf"));
    cairo_surface_t *s = cairo_image_surface_create_from_png("out_kf1/kf/frame_00009.png");
    CHECK(cairo_surface_status(s) == CAIRO_STATUS_SUCCESS && cairo_image_surface_get_width(s) == 320 &&
          cairo_image_surface_get_height(s) == 180, "frame size 320x180");
    cairo_surface_destroy(s);
    for (int i = 0; i < 10; i++) {
        char a[64], b[64];
        snprintf(a, sizeof a, "out_kf1/kf/frame_%05d.png", i);
        snprintf(b, sizeof b, "out_kf2/kf/frame_%05d.png", i);
        CHECK(same_file(a, b), "frame %d differs between -j 1 and -j 2", i);
    }
    CHECK(run_cmd("animate", "kf.scene", "-o", "out_kf3", "--size", "320x180", "--fps", "4", "--duration", "2",
                  "--quiet", NULL) == 0, "options beat [animation]");
    CHECK(count_frames("out_kf3/kf") == 8, "--fps 4 --duration 2: 8 frames, got %ld", count_frames("out_kf3/kf"));
}

/* The still: the scene with fixed overrides, drawn like a frame. */
typedef struct still {
    char *sets[2];
} still;

static int still_draw(void *state, const hy_anim_frame *f, hy_error *err)
{
    still *st = state;
    hy_scene_run r;
    int rc = hy_scene_run_load(&r, "kf.scene", st->sets, 2, err);
    if (rc)
        return rc;
    hy_scene_fig fig;
    memset(&fig, 0, sizeof fig);
    if (!(rc = hy_scene_run_compute(&r, NULL, err)) && !(rc = hy_scene_run_figure(&r, &fig, err))) {
        fig.fig.width = f->width / f->scale;
        fig.fig.height = f->height / f->scale;
        fig.fig.dpi = 72.0 * f->scale;
        rc = hy_figure_draw_layers(&fig.fig, &f->data, &f->overlay, err);
    }
    hy_scene_fig_free(&fig);
    hy_scene_run_free(&r);
    return rc;
}

static void render_still(const char *name, const char *gamma, const char *sigma)
{
    char g[64], s[64];
    snprintf(g, sizeof g, "series.g.gamma=%s", gamma);
    snprintf(s, sizeof s, "model.sigma0=%s", sigma);
    still st = {{g, s}};
    hy_anim_params p = hy_anim_defaults();
    p.outdir = "out_still", p.name = name, p.width = 320, p.height = 180, p.fps = 10, p.duration = 0.1;
    p.quiet = 1, p.poster = 0;
    hy_error err;
    int rc = hy_anim_run(&p, still_draw, &st, NULL, &err);
    CHECK(rc == 0, "still %s: %s", name, err.msg);
}

static void test_ends(void)
{
    render_still("start", "1", "1");
    render_still("end", "1000", "3");
    CHECK(same_file("out_kf1/kf/frame_00000.png", "out_still/start/frame_00000.png"),
          "frame 0 equals the still with --set series.g.gamma=1 --set model.sigma0=1");
    CHECK(same_file("out_kf1/kf/frame_00009.png", "out_still/end/frame_00000.png"),
          "the last frame equals the still with --set series.g.gamma=1000 --set model.sigma0=3");
    CHECK(!same_file("out_kf1/kf/frame_00000.png", "out_kf1/kf/frame_00009.png"), "the animation moves");
}

static void test_cache(void)
{
    scene_anim a;
    hy_error err;
    CHECK(scene_anim_load(&a, "kf.scene", &err) == 0, "load: %s", err.msg);
    hy_anim_params p = hy_anim_defaults();
    p.outdir = "out_cache", p.name = "kf", p.width = 160, p.height = 90, p.fps = 10, p.duration = 1;
    p.quiet = 1, p.jobs = 1;
    /* distinct override sets over the 10 frames */
    char seen[10][512], buf[512], *sets[2];
    long distinct = 0;
    for (long i = 0; i < 10; i++) {
        scene_anim_sets(&a, scene_anim_time(i, 10, 1.0), buf, sizeof buf, sets);
        snprintf(seen[distinct], sizeof seen[distinct], "%s;%s", sets[0], sets[1]);
        int dup = 0;
        for (long j = 0; j < distinct; j++)
            dup |= !strcmp(seen[j], seen[distinct]);
        distinct += !dup;
    }
    CHECK(scene_anim_check(&a, 10, 1.0, &err) == 0 && hy_anim_run(&p, scene_anim_draw, &a, NULL, &err) == 0, "run: %s",
          err.msg);
    CHECK(a.computes == distinct && a.hits == 10 - distinct, "%ld runs computed for %ld distinct frames (%ld hits)",
          a.computes, distinct, a.hits);
    scene_anim_free(&a);

    /* a γ sweep that holds γ: each distinct γ solved once with -j 1 */
    write_file("kf_hold.scene", "[model]\nkind = lugre\n[input]\nkind = bimodal\n[figure]\nkind = loop\n"
                                "[series g]\ndata = ygamma\ngamma = 1\n[animation]\nduration = 1\nfps = 10\n"
                                "[keyframe g]\nkey = \"series.g.gamma\"\ntimes = 0, 0.3, 0.7, 1\n"
                                "values = 1, 1, 100, 100\nlog = true\n");
    CHECK(scene_anim_load(&a, "kf_hold.scene", &err) == 0, "load: %s", err.msg);
    p.name = "kf_hold";
    CHECK(hy_anim_run(&p, scene_anim_draw, &a, NULL, &err) == 0, "run: %s", err.msg);
    /* frames at t = 0, 1/9, 2/9 hold γ = 1, 7/9, 8/9, 1 hold γ = 100: 10 - 2 - 2 distinct */
    CHECK(a.computes == 6 && a.hits == 4, "held γ: %ld solves, %ld hits (want 6, 4)", a.computes, a.hits);
    CHECK(a.nentries == 0, "every run freed after its last frame (%zu left)", a.nentries);
    scene_anim_free(&a);
    /* the same with 2 threads: still one solve per distinct γ */
    CHECK(scene_anim_load(&a, "kf_hold.scene", &err) == 0, "load: %s", err.msg);
    p.name = "kf_hold2", p.jobs = 2;
    CHECK(hy_anim_run(&p, scene_anim_draw, &a, NULL, &err) == 0, "run: %s", err.msg);
    CHECK(a.computes == 6 && a.hits == 4, "held γ, -j 2: %ld solves, %ld hits (want 6, 4)", a.computes, a.hits);
    scene_anim_free(&a);
}

/* A scene with one keyframe section whose body is kf; the error must name
 * kf_bad.scene:line:col and no frame directory may appear. */
static void bad(const char *kf, const char *where, const char *what)
{
    char text[2048];
    snprintf(text, sizeof text,
             "[model]\nkind = lugre\n[input]\nkind = bimodal\n[figure]\nkind = loop\n[series g]\n"
             "data = ygamma\ngamma = 1\n[animation]\nduration = 1\nfps = 5\n[keyframe k]\n%s", kf);
    write_file("kf_bad.scene", text);
    scene_anim a;
    hy_error err = {0, ""};
    int rc = scene_anim_load(&a, "kf_bad.scene", &err);
    if (!rc) {
        rc = scene_anim_check(&a, 5, 1.0, &err);
        scene_anim_free(&a);
    }
    CHECK(rc != 0 && !strncmp(err.msg, where, strlen(where)) && strstr(err.msg, what),
          "want '%s ... %s', got '%s'", where, what, err.msg);
    CHECK(run_cmd("animate", "kf_bad.scene", "-o", "out_bad", "--size", "160x90", "--quiet", NULL) == 2,
          "the command fails with status 2 (invalid input)");
    CHECK(access("out_bad/kf_bad", F_OK) != 0, "no frames written for a bad keyframe");
}

static void test_errors(void)
{
    bad("key = \"model.nosuch\"\ntimes = 0\nvalues = 1\n", "kf_bad.scene:14:1:", "unknown key");
    bad("key = \"model.kind\"\ntimes = 0\nvalues = 1\n", "kf_bad.scene:14:1:", "not numeric");
    bad("key = \"series.nosuch.gamma\"\ntimes = 0\nvalues = 1\n", "kf_bad.scene:14:1:", "no [series nosuch]");
    bad("key = \"model.sigma0\"\ntimes = 0, 1\nvalues = 1\n", "kf_bad.scene:16:1:", "1 values for 2 times");
    bad("key = \"model.sigma0\"\ntimes = 0, 1, 1\nvalues = 1, 2, 3\n", "kf_bad.scene:15:1:", "ascending");
    bad("key = \"model.sigma0\"\ntimes = 0, 1\nvalues = 1, -1\n", "kf_bad.scene:16:1:", "at frame 2");
    bad("key = \"series.g.gamma\"\ntimes = 0, 1\nvalues = 0, 10\nlog = true\n", "kf_bad.scene:16:1:", "values > 0");
    bad("key = \"input.umin2\"\ntimes = 0, 1\nvalues = 0.2, 1.2\n", "kf_bad.scene:13:1:", "u_min,2 < u_max,1");
    CHECK(run_cmd("animate", "no_such.scene", "--quiet", NULL) == 2, "a missing scene file: status 2");
}

static void test_interp(void)
{
    const double t[] = {0, 1.5, 4}, v[] = {1, 1000, 7};
    for (int ease = 0; ease < 2; ease++)
        for (int lg = 0; lg < 2; lg++) {
            scene_kf k = {.t = t, .v = v, .n = 3, .ease = ease, .log = lg};
            for (int i = 0; i < 3; i++)
                CHECK(scene_kf_eval(&k, t[i]) == v[i], "ease %d log %d: value at t = %g is %.17g, not %g", ease, lg,
                      t[i], scene_kf_eval(&k, t[i]), v[i]);
            CHECK(scene_kf_eval(&k, -1) == 1 && scene_kf_eval(&k, 9) == 7, "held outside the keys");
        }
    scene_kf lin = {.t = t, .v = v, .n = 3, .ease = 0, .log = 0}, lg = {.t = t, .v = v, .n = 3, .ease = 0, .log = 1};
    scene_kf sm = {.t = t, .v = v, .n = 3, .ease = 1, .log = 0};
    CHECK(fabs(scene_kf_eval(&lin, 0.75) - 500.5) < 1e-9, "linear midpoint");
    CHECK(fabs(scene_kf_eval(&lg, 0.75) - sqrt(1000.0)) < 1e-9, "log midpoint: geometric mean");
    CHECK(fabs(scene_kf_eval(&sm, 0.375) - (1 + 999 * 0.15625)) < 1e-9, "smoothstep at a quarter");
    CHECK(scene_anim_time(0, 10, 2) == 0 && scene_anim_time(9, 10, 2) == 2 && scene_anim_time(0, 1, 2) == 0,
          "first frame at 0, last at the duration");
}

int main(void)
{
    hy_gl_free(gl_or_skip(16, 16));
    gsl_set_error_handler_off();
    write_file("kf.scene", good_scene);
    test_interp();
    test_errors();
    test_frames();
    test_ends();
    test_cache();
    return hy_test_finish("scene_anim");
}
