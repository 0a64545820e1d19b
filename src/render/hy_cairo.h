/* SPDX-License-Identifier: MIT */
/* hy_cairo.h: the cairo backend of hy_canvas (vector and raster figures).
 *
 * Wraps an existing cairo context whose user space is in points.  The font
 * is selected through cairo's toy API (fontconfig), hinting off so that text
 * metrics are the same in SVG, PDF and PNG.  hy_figure_write (hy_plot.h)
 * uses it; call it directly to overlay axes on another drawing.
 *
 *     hy_cairo_canvas cc;
 *     hy_canvas cv = hy_canvas_cairo(&cc, cr, "DejaVu Sans");
 *     hy_figure_draw(&fig, &cv, &err);
 */
#ifndef HY_CAIRO_H
#define HY_CAIRO_H

#include <cairo.h>

#include "hy_canvas.h"

/* Backend state; lives as long as the canvas made from it. */
typedef struct hy_cairo_canvas {
    cairo_t *cr;              /* borrowed */
    const char *font;         /* borrowed family name */
} hy_cairo_canvas;

/* Returns a canvas drawing on cr through state (which it initialises). */
hy_canvas hy_canvas_cairo(hy_cairo_canvas *state, cairo_t *cr, const char *font);

#endif
