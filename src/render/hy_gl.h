/* SPDX-License-Identifier: MIT */
/* hy_gl.h: the OpenGL backend (core profile 3.3+) of hy_canvas, off-screen
 * through OSMesa or EGL (hy_gl_select; llvmpipe or a GPU).
 *
 * A hy_gl owns one off-screen context and its RGBA framebuffer; it is used
 * on the thread that created it (one per thread: contexts are never
 * shared).  Its canvas draws the DATA layer of a figure (polylines, markers,
 * filled rectangles, clipping) with GLSL shaders from shaders/NAME.glsl embedded
 * at build time: thick polylines as instanced segments with coverage AA
 * (miter joins, or round joins and caps for round pens, as cairo draws them;
 * dense polylines are first simplified to 0.1 px), dash patterns, per-vertex colour
 * from a colour map with alpha fading by age ("effects", keyed by the pen
 * colour).  A separate 3-D pass draws a lit ribbon with depth; a frame
 * with 3-D is drawn into a 4x multisampled framebuffer, resolved at hy_gl_read.  Drawing is recorded and sent
 * to GL in one batch at hy_gl_read or before the 3-D pass.  Text is not
 * drawn here: use hy_figure_draw_layers with a cairo overlay, then
 * hy_gl_read (bottom-up rows) and hy_frame_composite (hy_frame.h).
 *
 *     hy_gl *g;
 *     if (hy_gl_create(&g, 1280, 720, &err)) ...;       // err names the cause
 *     hy_canvas data = hy_gl_canvas(g, 1.0);             // 1 point = 1 pixel
 *     hy_figure_draw_layers(&fig, &data, &overlay, &err);
 *     hy_gl_read(g, rgba, &err);                         // width*height*4 bytes
 *     hy_gl_free(g);
 *
 * Only built with a GL backend (HY_HAVE_GL: OSMesa and/or EGL).
 */
#ifndef HY_GL_H
#define HY_GL_H

#include <stdio.h>

#include "hy_canvas.h"
#include "hy_gl_pick.h"
#include "hy_status.h"

typedef struct hy_gl hy_gl;

enum { HY_CMAP_NONE = 0, HY_CMAP_VIRIDIS, HY_CMAP_OKABE_ITO };

/* A stroke effect: strokes whose pen colour equals key exactly take their
 * colour per vertex from cmap at t0 + (t1 - t0) s (s = arc-length fraction
 * along the path, 0 at its start) and their alpha multiplied by
 * fade + (1 - fade) s: fade < 1 makes a trail whose old end fades out. */
typedef struct hy_gl_effect {
    hy_rgb key;
    int cmap;                 /* HY_CMAP_*; NONE keeps the pen colour */
    double t0, t1;            /* colour-map range along the path */
    double fade;              /* alpha at the oldest end, in [0, 1]; 1: no fade */
} hy_gl_effect;

/* hy_gl_backends, hy_gl_select, hy_gl_backend_name, hy_gl_check: the
 * backend's choice (hy_gl_pick.h, included above). */
/* Writes the backends built, the one in use and why, its devices (EGL:
 * HYSTVIZ_EGL_DEVICE) and the renderer of a test context to f; HY_OK, or
 * the error of making that context. */
int hy_gl_info(FILE *f, hy_error *err);

/* Creates a width x height context (core profile, version >= 3.3) on the
 * selected backend with its shaders compiled and makes it current.
 * HY_EUNSUP when the backend cannot create one (or is not built), HY_EINVAL
 * for a bad size or backend choice, HY_ENUM for a shader error (file, stage, log). */
int hy_gl_create(hy_gl **out, int width, int height, hy_error *err);
/* Releases the context and its buffers (NULL is ignored). */
void hy_gl_free(hy_gl *g);
/* "GL_VERSION / GL_RENDERER (backend)" of the context, for reports. */
const char *hy_gl_describe(const hy_gl *g);

/* A canvas drawing on g; coordinates in points times scale = pixels.
 * text and measure do nothing (the overlay's job). */
hy_canvas hy_gl_canvas(hy_gl *g, double scale);
/* Starts a frame: clears colour (to c, opaque), depth, effects and clipping. */
void hy_gl_begin(hy_gl *g, hy_rgb c);
/* Registers an effect for this frame (at most 8); HY_EINVAL beyond that. */
int hy_gl_set_effect(hy_gl *g, const hy_gl_effect *e, hy_error *err);

/* A ribbon: nloops polylines of npts points (x, y, z in [-1, 1]), loop i
 * at row i of pts (3 * npts doubles each), joined into a lit surface; colour
 * per loop from cmap at i/(nloops-1).  Camera: orbit angles in radians. */
typedef struct hy_gl_ribbon {
    const double *pts;
    int nloops, npts;
    int cmap;
    double azimuth, elevation, distance;   /* distance 0 -> 3.2 */
    double vx, vy, vw, vh;                 /* viewport in pixels, y down; vw == 0: all */
} hy_gl_ribbon;
/* Draws r with depth test and lighting; HY_EINVAL for a bad ribbon, HY_ENOMEM. */
int hy_gl_draw_ribbon(hy_gl *g, const hy_gl_ribbon *r, hy_error *err);
/* Where the point xyz of r's space lands in the frame (pixels, y down), for
 * labels drawn by the overlay.  Returns 0 when it is behind the camera. */
int hy_gl_ribbon_project(const hy_gl *g, const hy_gl_ribbon *r, const double xyz[3], double *px, double *py);

/* The relay plane of a Preisach model (shaders/plane.frag.glsl): in the
 * pixel rectangle vx, vy, vw, vh (y down) showing beta from xlo to xhi across
 * and alpha from ylo to yhi up, every pixel with alpha >= beta at its centre
 * is the relay (alpha, beta), coloured up or down as the staircase memory
 * s[0..n] (alternating extrema, s[0] = -inf or +inf as kind0 = -1 or +1: the
 * initial saturation) leaves it, shaded by the density shape dist (0
 * Gaussian, 1 Lorentzian) of centres ma, mb and widths sa, sb; pixels with
 * alpha < beta are left as they are.  Drawn now, over the 2-D data so far. */
#define HY_GL_PLANE_MAX 63
typedef struct hy_gl_plane {
    double vx, vy, vw, vh;
    double xlo, xhi, ylo, yhi;
    const double *s;
    int n, kind0;
    int dist;
    double ma, sa, mb, sb;
    hy_rgb up, down;
} hy_gl_plane;
/* HY_EINVAL for a bad rectangle or range, or n > HY_GL_PLANE_MAX. */
int hy_gl_draw_plane(hy_gl *g, const hy_gl_plane *pl, hy_error *err);

/* Finishes drawing and returns the frame in the context's own buffer, laid
 * out as a cairo RGB24 image (a native-endian 0x??RRGGBB word per pixel,
 * stride 4 * width, top row first), valid until the next drawing on this
 * context.  NULL (and err) on a GL error. */
const unsigned char *hy_gl_finish(hy_gl *g, hy_error *err);

/* Finishes drawing and reads the frame (glReadPixels) as RGBA8, rows
 * bottom-up as GL stores them; rgba holds width * height * 4 bytes. */
int hy_gl_read(hy_gl *g, unsigned char *rgba, hy_error *err);

/* One stage of a program: its file name (for messages), GL stage enum
 * (GL_VERTEX_SHADER = 0x8B31, GL_FRAGMENT_SHADER = 0x8B30), source, and
 * optional preprocessor lines inserted after its #version line (NULL: none). */
typedef struct hy_gl_stage {
    const char *file;
    unsigned stage;
    const char *src;
    const char *defines;
} hy_gl_stage;
/* Compiles and links a program in the current context; on failure HY_ENUM
 * with "FILE (STAGE shader): LOG" or "program FILES: link: LOG". */
int hy_gl_program(const hy_gl_stage *stages, int n, unsigned *program, hy_error *err);

/* Colour map value at t in [0, 1] (clamped). */
hy_rgb hy_cmap(int cmap, double t);

#endif
