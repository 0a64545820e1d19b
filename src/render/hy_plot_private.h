/* hy_plot_private.h: helpers shared by the layout and the output code (not public). */
#ifndef HY_PLOT_PRIVATE_H
#define HY_PLOT_PRIVATE_H

#include "hy_plot.h"

#define HY__DEFAULT_FONT "DejaVu Sans"

/* The figure's size in points and PNG resolution, defaults applied. */
void hy__figure_size(const hy_figure *f, double *width, double *height, double *dpi);

/* The font family, default applied. */
const char *hy__figure_font(const hy_figure *f);

#endif
