/* SPDX-License-Identifier: MIT */
/* hy_plot.h: figure description (pure data) and figure output.
 *
 * A figure is a grid of panels (hy_axes); each panel holds series (lines
 * and/or markers), point marks, text labels and an optional shaded x-band.
 * Everything is plain data borrowed by pointer: the caller owns the arrays
 * and strings, which must outlive the call that draws them.  Sizes are in
 * points (1/72 in); zero fields take sensible defaults, so a zero-initialised
 * struct plus data is a valid figure.  Labels are markup (hy_markup.h).
 *
 *     hy_series s = { .x = t, .y = y, .n = n, .style = HY_LINE_DASHED,
 *                     .colour = { .palette = 1 }, .label = "\\gamma = 10" };
 *     hy_axes ax = { .series = &s, .nseries = 1, .xlabel = "t",
 *                    .ylabel = "y_\\gamma(t)", .legend = HY_LEGEND_BEST };
 *     hy_figure fig = { .width = hy_cm(8), .height = hy_cm(6), .dpi = 300,
 *                       .axes = &ax, .nrows = 1, .ncols = 1 };
 *     hy_error err;
 *     if (hy_figure_write(&fig, "fig7.pdf", HY_FORMAT_PDF, &err)) puts(err.msg);
 *
 * Output needs the "DejaVu Sans" font (Debian/Ubuntu: fonts-dejavu-core).
 */
#ifndef HY_PLOT_H
#define HY_PLOT_H

#include <stddef.h>

#include "hy_cancel.h"
#include "hy_canvas.h"
#include "hy_figure_names.h"
#include "hy_formats.h"
#include "hy_status.h"

/* HY_LINE_SOLID = 0, ..., HY_MARKER_*, HY_LEGEND_* and HY_THEME_* in the
 * order of their tables in hy_figure_names.h (the scene's names); *_COUNT of
 * each. */
#define HY__LINE_ID(id, name) HY_LINE_##id,
#define HY__MARKER_ID(id, name) HY_MARKER_##id,
#define HY__LEGEND_ID(id, name) HY_LEGEND_##id,
#define HY__THEME_ID(id, name) HY_THEME_##id,
enum { HY_LINE_STYLES(HY__LINE_ID) HY_LINE_COUNT };
enum { HY_MARKERS(HY__MARKER_ID) HY_MARKER_COUNT };
enum { HY_LEGEND_PLACES(HY__LEGEND_ID) HY_LEGEND_COUNT };
enum { HY_THEMES(HY__THEME_ID) HY_THEME_COUNT };
#undef HY__LINE_ID
#undef HY__MARKER_ID
#undef HY__LEGEND_ID
#undef HY__THEME_ID
/* HY_FORMAT_SVG = 0, _PDF, _PNG, ... in the order of HY_FIGURE_FORMATS
 * (hy_formats.h); HY_FORMAT_COUNT of them. */
#define HY__FORMAT_ID(id, ext, mime) HY_FORMAT_##id,
enum { HY_FIGURE_FORMATS(HY__FORMAT_ID) HY_FORMAT_COUNT };
#undef HY__FORMAT_ID
/* Text anchor for hy_text: which point of the label sits at (x, y). */
enum { HY_ANCHOR_LEFT = 0, HY_ANCHOR_CENTER, HY_ANCHOR_RIGHT };

#define HY_PALETTE_SIZE 8
#define HY_RGB_EXPLICIT (-1)

/* Okabe-Ito palette: 0 black, 1 orange, 2 sky blue, 3 bluish green,
 * 4 yellow, 5 blue, 6 vermillion, 7 reddish purple. */
extern const hy_rgb hy_palette[HY_PALETTE_SIZE];

/* palette >= 0 selects hy_palette[palette % 8]; HY_RGB_EXPLICIT uses rgb. */
typedef struct hy_colour {
    int palette;
    hy_rgb rgb;
} hy_colour;

typedef struct hy_series {
    const double *x, *y;      /* n points; non-finite points break the line */
    size_t n;
    int style;                /* HY_LINE_* */
    hy_colour colour;
    double width;             /* line width in points; 0 -> 1.0 */
    int marker;               /* HY_MARKER_* drawn at every point */
    double marker_size;       /* points; 0 -> 4 */
    int marker_filled;
    const char *label;        /* legend entry (markup) or NULL */
} hy_series;

/* A single marker at a data point. */
typedef struct hy_mark {
    double x, y;
    int marker;               /* HY_MARKER_CIRCLE or HY_MARKER_SQUARE */
    double size;              /* points; 0 -> 5 */
    int filled;
    hy_colour colour;
} hy_mark;

/* A text label anchored at a data point, shifted by (dx, dy) points (dy up).
 * If its box would cover a curve, a marker, an inset, the legend or an
 * earlier label, it moves to the nearest free spot in the frame.  With
 * has_point a leader line joins it to (px, py), the point it is about. */
typedef struct hy_text {
    double x, y;
    const char *text;         /* markup */
    int anchor;               /* HY_ANCHOR_* (vertical: baseline) */
    double dx, dy;
    hy_colour colour;
    int has_point;
    double px, py;
} hy_text;

/* Axis range: explicit when lo < hi, else automatic from the data, padded by
 * 4 % of the span on each side unless tight (e.g. time axes). */
typedef struct hy_range {
    double lo, hi;
    int log;                  /* logarithmic scale (data <= 0 is skipped) */
    int tight;                /* automatic limits exactly at the data's extremes */
} hy_range;

#define HY_INSET_MIN_ZOOM 1.5

typedef struct hy_axes {
    const hy_series *series;
    size_t nseries;
    const hy_mark *marks;
    size_t nmarks;
    const hy_text *texts;
    size_t ntexts;
    const char *xlabel, *ylabel, *title;  /* markup or NULL */
    hy_range x, y;
    int legend;               /* HY_LEGEND_* */
    int grid;                 /* light grid lines at the ticks */
    int band;                 /* shade band_lo <= x <= band_hi in light grey */
    double band_lo, band_hi;
    /* A zoomed inset (when zoom_x.lo < zoom_x.hi and zoom_y.lo < zoom_y.hi):
     * the same series and marks over these ranges, in a box about 40 % of the
     * frame placed where it covers the least data, the zoomed region outlined
     * on the main axes; for a feature too small to see, e.g. a sliver loop.
     * Left out when the window holds nothing drawn (hy_axes_zoom_shows_data)
     * or the inset would enlarge it less than HY_INSET_MIN_ZOOM times in
     * both directions (it would only cover the data it repeats). */
    hy_range zoom_x, zoom_y;
} hy_axes;

typedef struct hy_figure {
    double width, height;     /* points; 0 -> 8 cm x 6 cm */
    double dpi;               /* PNG resolution; 0 -> 150 */
    const char *font;         /* NULL -> "DejaVu Sans" */
    double font_size;         /* points; 0 -> 9 */
    const hy_axes *axes;      /* nrows * ncols panels, row-major */
    int nrows, ncols;         /* 0 -> 1 */
    int full_resolution;      /* draw every point of every line (see HY_CURVE_TOL_PX) */
    int theme;                /* HY_THEME_*; 0 -> paper */
    const hy_cancel *cancel;  /* asked between annotations while they are
                               * placed; stop: HY_ECANCEL (NULL: never) */
    /* Plain text an SVG carries as its <title> and <desc> (NULL: none), for
     * screen readers and search: cairo draws the glyphs as paths. */
    const char *svg_title, *svg_desc;
} hy_figure;

/* Lines at the output's resolution (issue 23 item 2).  A line with more
 * than HY_CURVE_DENSE_PX points per pixel of its length (pixels at the
 * figure's dpi) is simplified so that every point stays within
 * HY_CURVE_TOL_PX pixels of the polyline drawn; turning points, extremes and
 * markers are kept exactly.  Layout and PNG use these lines (a line no denser
 * than that is drawn point for point, so PNGs of such figures are unchanged);
 * SVG and PDF strokes are simplified to HY_CURVE_TOL_PX whatever their
 * density.  full_resolution keeps every point (an SVG meant to be zoomed or
 * reused). */
#define HY_CURVE_DENSE_PX 8.0
#define HY_CURVE_TOL_PX 0.1

/* Unit helpers: lengths to points, and points to pixels at a resolution. */
double hy_cm(double cm);
double hy_in(double in);
double hy_px(double px, double dpi);   /* px at dpi -> points */
int hy_pt_to_px(double pt, double dpi); /* rounded, at least 1 */

/* Draws the whole figure on cv (white background included).  Returns
 * HY_EINVAL with a message for an invalid figure (no panels, bad range). */
int hy_figure_draw(const hy_figure *f, const hy_canvas *cv, hy_error *err);

/* As hy_figure_draw, but the white background, shaded bands, grid, series and
 * marks go to data (e.g. an OpenGL canvas) and text, frame, ticks, labels and
 * legend to overlay (e.g. cairo), which also measures text.  data may be NULL. */
int hy_figure_draw_layers(const hy_figure *f, const hy_canvas *data, const hy_canvas *overlay,
                          hy_error *err);

/* The frame (plot area) of panel index as hy_figure_draw would place it on
 * cv (which measures text): x, y, w, h in points, y down; for drawing beside
 * the data (a colour bar).  HY_EINVAL for a bad index or figure. */
int hy_figure_frame(const hy_figure *f, const hy_canvas *cv, int index, double rect[4], hy_error *err);

/* Whether the zoom window of ax (zoom_x x zoom_y) holds anything drawn: a
 * mark, a point of a series drawn with markers or a line through it.  An
 * inset over a window without (parameters moved the data away) is left out. */
int hy_axes_zoom_shows_data(const hy_axes *ax);

/* Where a box of box[2] x box[3] points (a colour bar and its labels) goes in
 * panel index's frame: the spot, among the legend's candidates, that covers
 * the least data and not the legend; its top-left corner into box[0], box[1]. */
int hy_figure_free_box(const hy_figure *f, const hy_canvas *cv, int index, double box[4], hy_error *err);

/* How much each annotation of panel index covers where hy_figure_draw
 * places it on cv (the test of "annotations off the curves"): into hits[i]
 * for the first n, the length in points of curve inside its box (grown by
 * the pen), plus marks, the inset, the legend and other annotations as
 * overlap() counts them; 0 when it covers nothing, +inf when the box leaves
 * the frame, NaN for an annotation not drawn.  HY_EINVAL for a bad index. */
int hy_figure_text_hits(const hy_figure *f, const hy_canvas *cv, int index, double *hits, size_t n, hy_error *err);

/* Largest PNG hystviz renders: cairo's image limit a side, and 2^28 pixels
 * (1 GiB of ARGB32) in all. */
#define HY_PNG_MAX_SIDE 32767
#define HY_PNG_MAX_PIXELS 268435456.0

/* HY_OK if f can be written as format (HY_FORMAT_*), else HY_EINVAL saying
 * why: an unknown format, or a PNG over the limits above (e.g. 40 x 40 in at
 * 2400 dpi).  Cheap: lets a caller refuse before computing anything. */
int hy_figure_check(const hy_figure *f, int format, hy_error *err);
/* The pixels of f's PNG raster (its size at its dpi, whole pixels). */
double hy_figure_png_pixels(const hy_figure *f);

/* Renders f as HY_FORMAT_SVG, _PDF or _PNG into path through the output
 * writer (hy_out.h): a temporary file in the same directory renamed on
 * success; on failure (HY_EIO with the path in the message, HY_EINVAL,
 * HY_ENOMEM) no file is left behind.  Output bytes depend only on f (fixed
 * PDF dates, no timestamps). */
int hy_figure_write(const hy_figure *f, const char *path, int format, hy_error *err);

/* Renders f into an output opened with hy_out_open and finishes it (the
 * caller publishes it, e.g. once every format of a figure is written); on
 * failure aborts it and names its path. */
struct hy_out;
int hy_figure_write_out(const hy_figure *f, struct hy_out *out, int format, hy_error *err);

/* Where a panel was drawn: its frame (x0, y0, w, h) in points from the
 * figure's top-left corner, and the axis limits mapped onto it (log10 scale
 * where xlog/ylog): data x maps to x0 + (x - xlo) / (xhi - xlo) * w, data y
 * to y0 + h - (y - ylo) / (yhi - ylo) * h. */
typedef struct hy_panel_map {
    double x0, y0, w, h;
    double xlo, xhi, ylo, yhi;
    int xlog, ylog;
} hy_panel_map;

/* As hy_figure_draw; also stores the first nmaps panels' maps (row-major). */
int hy_figure_draw_mapped(const hy_figure *f, const hy_canvas *cv, hy_panel_map *maps, size_t nmaps, hy_error *err);

/* Renders f as HY_FORMAT_SVG, _PDF or _PNG into memory: *buf (malloc'd, the
 * caller frees) holds *len bytes, the same bytes hy_figure_write writes.
 * Re-entrant: figures may be rendered from several threads at once. */
int hy_figure_render_mem(const hy_figure *f, int format, unsigned char **buf, size_t *len, hy_error *err);

/* As hy_figure_render_mem; also stores the first nmaps panels' maps (in
 * points, as the SVG's user units). */
int hy_figure_render_mem_mapped(const hy_figure *f, int format, unsigned char **buf, size_t *len, hy_panel_map *maps,
                                size_t nmaps, hy_error *err);

/* Format from a file name's extension (.svg .pdf .png), or -1. */
int hy_format_from_path(const char *path);

/* The most spots the layout tries for one annotation (2 passes of 30 rings
 * of 24 directions and the spot itself): the unit of placement work in the
 * work budget (docs/SCENES.md). */
#define HY_PLACE_SPOTS 1442

#endif
