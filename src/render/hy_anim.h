/* SPDX-License-Identifier: MIT */
/* hy_anim.h: the animation engine: timeline (duration, fps, easing,
 * keyframe tracks), quality presets, parallel frame rendering (one GL
 * context per thread, frames byte-identical for any number of threads),
 * PNG frames DIR/NAME/frame_00000.png plus a poster DIR/NAME.png, a progress
 * bar on a terminal, and optional video through ffmpeg.
 *
 * A scene is a draw callback and a state pointer; the callback draws frame f
 * on f->data (GL) and f->overlay (cairo, text and axes), usually through
 * hy_figure_draw_layers, and may call hy_gl_draw_ribbon on f->gl.  It is
 * called from several threads at once: the state must be read-only or
 * guard its caches.
 *
 *     hy_anim_params p = hy_anim_defaults();
 *     p.outdir = "frames"; p.name = "gamma-sweep-ex2"; p.jobs = 2;
 *     hy_anim_stats s;
 *     if (hy_anim_run(&p, draw, state, &s, &err)) fprintf(stderr, "%s\n", err.msg);
 *
 * Only built with a GL backend (HY_HAVE_GL: OSMesa and/or EGL).
 */
#ifndef HY_ANIM_H
#define HY_ANIM_H

#include <stddef.h>
#include <stdio.h>

#include "hy_canvas.h"
#include "hy_figure_names.h"
#include "hy_frame.h"
#include "hy_gl.h"
#include "hy_status.h"

/* ---- timeline ---- */

/* HY_EASE_LINEAR = 0, HY_EASE_SMOOTH: HY_EASINGS (hy_figure_names.h). */
#define HY__EASE_ID(id, name) HY_EASE_##id,
enum { HY_EASINGS(HY__EASE_ID) HY_EASE_COUNT };
#undef HY__EASE_ID

/* Eased progress for x in [0, 1] (clamped): linear, or smoothstep 3x² - 2x³. */
double hy_ease(int ease, double x);

/* A keyframe: at time t (seconds) the track has value v; ease shapes the
 * segment that ends at this key. */
typedef struct hy_key {
    double t, v;
    int ease;
} hy_key;

/* keys sorted by t; log != 0 interpolates log(v) (v > 0), e.g. for γ. */
typedef struct hy_track {
    const hy_key *keys;
    size_t n;
    int log;
} hy_track;

/* The track's value at time t; held constant before the first and after the last key. */
double hy_track_eval(const hy_track *tr, double t);

/* ---- quality presets (as manim's) ---- */

/* Fills width, height and fps for "480p15" (854x480@15), "720p30", "1080p60",
 * "2160p60" and the like; HY_EINVAL listing the presets for an unknown name. */
int hy_anim_quality(const char *name, int *width, int *height, double *fps, hy_error *err);
/* The preset names, NULL-terminated. */
const char *const *hy_anim_quality_names(void);

/* Frames are figures HY_ANIM_POINTS_HIGH points high (480 x 270 pt at
 * 16:9), scaled to the frame: text and line widths grow with the frame
 * height, and 9 pt text is 1/30 of it (24 px at 720p, readable projected). */
#define HY_ANIM_POINTS_HIGH 270.0

/* ---- running ---- */

typedef struct hy_anim_frame {
    long index, nframes;      /* this frame and the animation's total */
    double time, duration;    /* seconds */
    double progress;          /* index / (nframes - 1), 0 for a single frame */
    int width, height;        /* pixels; 1 point = scale pixels */
    double scale;
    hy_gl *gl;
    hy_canvas data;           /* GL canvas */
    hy_canvas overlay;        /* cairo canvas on a transparent ARGB32 surface */
} hy_anim_frame;

typedef int (*hy_anim_draw_fn)(void *state, const hy_anim_frame *f, hy_error *err);

typedef struct hy_anim_params {
    const char *outdir;       /* frames go to outdir/name/ (created) */
    const char *name;
    int width, height;
    double scale;             /* pixels per point; 0 -> height / HY_ANIM_POINTS_HIGH */
    double fps, duration;     /* frames = round(duration * fps), at least 1 */
    long first, last;         /* frames [first, last); last < 0: to the end */
    int jobs;                 /* threads, each with its own GL context; 0 -> 1 */
    int quiet;                /* no progress bar even on a terminal */
    int poster;               /* also write outdir/name.png (the last frame) */
    const char *video;        /* NULL, "mp4", "webm" or "gif": pipe frames to ffmpeg, which
                               * writes a temporary of the output writer (hy_out.h), renamed
                               * to outdir/name.FMT only when every frame went and ffmpeg
                               * succeeded */
    int no_frames;            /* with video: no PNG frames, only the video (and poster) */
    hy_png_opts png;
} hy_anim_params;

typedef struct hy_anim_stats {
    long frames;              /* frames written */
    double seconds;           /* wall time */
    double draw_s, read_s, png_s; /* summed over threads */
} hy_anim_stats;

/* 1280x720 at 30 fps for 4 s, all frames, 1 job, poster on, PNG frame defaults. */
hy_anim_params hy_anim_defaults(void);

/* Number of frames the parameters describe. */
long hy_anim_nframes(const hy_anim_params *p);

/* Renders frames [first, last) through draw.  Returns HY_OK; HY_EINVAL for bad
 * parameters; HY_EUNSUP when GL (or ffmpeg for video) is unavailable, before
 * anything is written; HY_EIO naming the file; the first error of draw.
 * Frames written before a failure stay (each is complete). Before rendering,
 * frames numbered nframes and above (left by a longer earlier run) and the
 * temporaries of killed runs (hy_out_sweep) are removed from outdir/name/ and
 * outdir, so the frame directory holds this animation's frames only.
 * stats may be NULL.
 * With video, SIGPIPE is ignored during the run (an ffmpeg that dies gives
 * HY_EIO, not a killed process) and restored afterwards. */
int hy_anim_run(const hy_anim_params *p, hy_anim_draw_fn draw, void *state, hy_anim_stats *stats,
                hy_error *err);

/* ---- a warm renderer: one GL context kept from frame to frame ---- */

/* hystviz-animate --worker renders frames on request with one context
 * instead of one process per frame.  A frame's PNG is byte for byte the
 * file hy_anim_run writes for it (the same drawing and encoder).
 *
 *     hy_anim_renderer *r;
 *     if (hy_anim_renderer_new(&r, 1280, 720, &err)) ...
 *     hy_anim_renderer_png(r, &p, draw, state, 10, memstream, &err);
 *     hy_anim_renderer_free(r);
 */
typedef struct hy_anim_renderer hy_anim_renderer;

/* A GL context of width x height pixels; HY_EUNSUP without GL. */
int hy_anim_renderer_new(hy_anim_renderer **out, int width, int height, hy_error *err);

/* The renderer's frame size. */
int hy_anim_renderer_size(const hy_anim_renderer *r, int *width, int *height);

/* Draws frame index of p's animation (p's size must be the renderer's) and
 * writes its PNG (p->png's settings) on png.  Returns HY_OK, HY_EINVAL for a
 * frame outside the animation or another size, draw's error, HY_EIO. */
int hy_anim_renderer_png(hy_anim_renderer *r, const hy_anim_params *p, hy_anim_draw_fn draw, void *state, long index,
                         FILE *png, hy_error *err);

/* Frees the context; NULL is allowed. */
void hy_anim_renderer_free(hy_anim_renderer *r);

/* Whether a program is on PATH (used for ffmpeg). */
int hy_anim_on_path(const char *prog);

#endif
