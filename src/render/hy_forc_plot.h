/* SPDX-License-Identifier: MIT */
/* hy_forc_plot.h: a FORC diagram (hy_forc_grid) drawn with cairo: the
 * distribution as a heat map in a diverging colour map centred at 0 (blue
 * negative, white 0, red positive), contour lines at chosen fractions of the
 * colour scale (0 in grey; none in cells below 1e-3 of the scale, where it
 * would trace rounding noise), a colour bar with the unit, axes μ0H_c and μ0H_u.
 * SVG and PDF hold the map as one embedded image and everything else as
 * vectors; PNG is the same drawing rasterised.
 *
 *     hy_forc_plot_opts po = hy_forc_plot_defaults();
 *     po.field_to_mt = 1e3;                          // fields in T -> axes in mT
 *     po.rho_unit = "A m²/T²";
 *     hy_forc_plot_write(&g, &po, fp, HY_FORMAT_SVG, &err);
 */
#ifndef HY_FORC_PLOT_H
#define HY_FORC_PLOT_H

#include <stdio.h>

#include "hy_forc.h"

#define HY_FORC_PLOT_LEVELS 32

typedef struct hy_forc_plot_opts {
    double vmax;          /* colour scale ±vmax (<= 0: the largest |ρ| of the grid) */
    double levels[HY_FORC_PLOT_LEVELS]; /* contour levels as fractions of vmax */
    int nlevels;
    double field_to_mt;   /* axis value in mT per field unit (<= 0: raw fields, no unit) */
    const char *rho_unit; /* unit of ρ for the colour bar ("" or NULL: none)        */
    double width, height; /* points (default 400 x 320)                            */
    double dpi;           /* PNG resolution (default 150)                           */
    const char *title, *desc; /* an SVG's <title> and <desc> (NULL: none)            */
} hy_forc_plot_opts;

/* vmax from the grid, levels 0, ±0.1, ±0.3, ±0.5, ±0.7, ±0.9, raw fields, 400 x 320 pt, 150 dpi. */
hy_forc_plot_opts hy_forc_plot_defaults(void);

/* The largest |ρ| of the grid over nodes with H_c >= hc_min (NaN skipped); 0 when none. */
double hy_forc_plot_max(const hy_forc_grid *g, double hc_min);

/* Draws the diagram into fp as format (HY_FORMAT_SVG, _PDF, _PNG of hy_plot.h).
 * HY_EINVAL for a grid without finite values or bad options, HY_EIO when
 * writing fails, HY_ENOMEM. */
int hy_forc_plot_write(const hy_forc_grid *g, const hy_forc_plot_opts *o, FILE *fp, int format, hy_error *err);

/* The grid as CSV "hc,hu,rho" (H_u slowest; %.10g fields, %.17g rho, "nan"
 * outside the data): what `hystviz forc -o` and `hystviz data` of a forc
 * scene write. */
void hy_forc_write_csv(const hy_forc_grid *g, FILE *f);

#endif
