/* SPDX-License-Identifier: MIT */
/* hy_canvas.h: the drawing backend interface the plot layout draws through.
 *
 * The layout code (hy_layout.c) never calls cairo or GL directly: it draws on
 * a hy_canvas, a context pointer plus a static const table of operations that
 * a backend fills in (NanoVG style).  hy_cairo.c provides the cairo backend;
 * an OpenGL backend can implement the same table and draw the data while
 * cairo draws the axes and text.  Coordinates are in points, y pointing down.
 *
 *     hy_canvas cv;
 *     hy_canvas_cairo_init(&cv, cr);            // see hy_plot.h
 *     hy_figure_draw(&fig, &cv, &err);
 */
#ifndef HY_CANVAS_H
#define HY_CANVAS_H

#include <stddef.h>

typedef struct hy_rgb {
    double r, g, b;           /* each in [0, 1] */
} hy_rgb;

/* How a path or marker outline is stroked. dash == NULL or ndash == 0: solid.
 * A zero-length "on" entry of dash is a dot (round_caps draws it round).
 * Joins are round unless miter_joins (frames and boxes, whose corners are
 * right angles): a mitred spike would pass a curve's sharp turning point. */
typedef struct hy_pen {
    hy_rgb colour;
    double alpha;             /* 0 means opaque (1) */
    double width;             /* points */
    const double *dash;       /* on/off lengths in points */
    int ndash;
    int round_caps;           /* round caps (dotted and dash-dotted lines) */
    int miter_joins;          /* sharp corners (rectangles) instead of round joins */
} hy_pen;

/* Text metrics in points for one run at one size. */
typedef struct hy_text_extents {
    double advance;           /* horizontal advance */
    double ascent, descent;   /* of the font at this size, both >= 0 */
    double ink_top, ink_bottom; /* of the run's ink, relative to the baseline, y down */
} hy_text_extents;

enum { HY_SHAPE_CIRCLE = 1, HY_SHAPE_SQUARE = 2 };

typedef struct hy_canvas_ops {
    const char *name;
    void (*begin_path)(void *ctx);
    void (*move_to)(void *ctx, double x, double y);
    void (*line_to)(void *ctx, double x, double y);
    /* Strokes and clears the current path. */
    void (*stroke)(void *ctx, const hy_pen *pen);
    void (*fill_rect)(void *ctx, double x, double y, double w, double h, hy_rgb c, double alpha);
    /* A marker of the given size (diameter / side, points) centred at (x, y);
     * filled with fill unless fill == NULL, then outlined with pen. */
    void (*marker)(void *ctx, int shape, double x, double y, double size,
                   const hy_pen *pen, const hy_rgb *fill);
    /* UTF-8 text with its baseline starting at (x, y); vertical: rotated a
     * quarter turn counter-clockwise (reads bottom to top). */
    void (*text)(void *ctx, double x, double y, const char *utf8, double size,
                 int italic, int vertical, hy_rgb c);
    void (*measure)(void *ctx, const char *utf8, double size, int italic,
                    hy_text_extents *ext);
    /* Restricts drawing to a rectangle until unclip. */
    void (*clip)(void *ctx, double x, double y, double w, double h);
    void (*unclip)(void *ctx);
} hy_canvas_ops;

typedef struct hy_canvas {
    const hy_canvas_ops *ops;
    void *ctx;
} hy_canvas;

#endif
