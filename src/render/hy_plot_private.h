/* SPDX-License-Identifier: MIT */
/* hy_plot_private.h: helpers shared by the layout and the output code (not public). */
#ifndef HY_PLOT_PRIVATE_H
#define HY_PLOT_PRIVATE_H

#include <stdio.h>

#include "hy_plot.h"

#define HY__DEFAULT_FONT "DejaVu Sans"

/* The figure's size in points and PNG resolution, defaults applied. */
void hy__figure_size(const hy_figure *f, double *width, double *height, double *dpi);

/* The font family, default applied. */
const char *hy__figure_font(const hy_figure *f);

/* hy_figure_draw_mapped for an output: vector (SVG, PDF) simplifies every
 * stroke to HY_CURVE_TOL_PX (hy_plot.h); the layout is the raster one. */
/* Writes text with XML's five special characters escaped (0 or an errno):
 * the <title> and <desc> of an SVG (hy_output.c, hy_forc_plot.c). */
int hy__svg_escaped(FILE *fp, const char *text);

int hy__figure_draw_out(const hy_figure *f, const hy_canvas *cv, int vector, hy_panel_map *maps, size_t nmaps,
                        hy_error *err);

#endif
