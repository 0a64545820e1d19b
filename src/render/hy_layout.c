/* SPDX-License-Identifier: MIT */
/* hy_layout.c: plot layout (ranges, ticks, margins, legend placement, clipping) drawn through a hy_canvas. */
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "hy_markup.h"
#include "hy_plot.h"
#include "hy_plot_private.h"
#include "hy_simplify.h"
#include "hy_ticks.h"

const hy_rgb hy_palette[HY_PALETTE_SIZE] = {
    {0.000, 0.000, 0.000}, {0.902, 0.624, 0.000}, {0.337, 0.706, 0.914},
    {0.000, 0.620, 0.451}, {0.941, 0.894, 0.259}, {0.000, 0.447, 0.698},
    {0.835, 0.369, 0.000}, {0.800, 0.475, 0.655},
};

#define TICK_LEN 3.5   /* major tick length, points, drawn inward */
#define PAD 3.0        /* tick label to frame */
#define GAP 4.0        /* tick labels to axis label */
#define OUTER 3.0      /* figure edge */
#define FRAME_W 0.6
#define LEGEND_PAD 4.0    /* legend box padding */
#define LEGEND_SAMPLE 22.0 /* length of a legend's line sample */
#define LEGEND_GAP 6.0    /* frame to a legend placed outside it */

double hy_cm(double cm) { return cm * 72.0 / 2.54; }
double hy_in(double in) { return in * 72.0; }
double hy_px(double px, double dpi) { return px * 72.0 / dpi; }

int hy_pt_to_px(double pt, double dpi)
{
    long v = lround(pt * dpi / 72.0);
    return v < 1 ? 1 : v > 100000 ? 100000 : (int)v;
}

void hy__figure_size(const hy_figure *f, double *width, double *height, double *dpi)
{
    *width = f->width > 0 ? f->width : hy_cm(8.0);
    *height = f->height > 0 ? f->height : hy_cm(6.0);
    *dpi = f->dpi > 0 ? f->dpi : 150.0;
}

const char *hy__figure_font(const hy_figure *f)
{
    return f->font && f->font[0] ? f->font : HY__DEFAULT_FONT;
}

/* A theme (hy_figure.theme): background, text and frame, the shaded band,
 * grid lines, legend frame, inset outline and annotation leaders; line widths
 * and text sizes as multiples of the figure's.  On a dark background a dark
 * curve colour (black, the palette's first) is drawn in the text colour. */
typedef struct theme {
    hy_rgb bg, fg, band, grid, legend, inset, leader;
    double line, text;
    int dark;
} theme;

static const theme themes[] = {
    [HY_THEME_PAPER] = {{1, 1, 1}, {0, 0, 0}, {0.88, 0.88, 0.88}, {0.82, 0.82, 0.82}, {0.55, 0.55, 0.55},
                        {0.45, 0.45, 0.45}, {0.35, 0.35, 0.35}, 1.0, 1.0, 0},
    [HY_THEME_SLIDES] = {{0.11, 0.12, 0.14}, {0.93, 0.93, 0.91}, {0.24, 0.26, 0.30}, {0.30, 0.32, 0.36},
                         {0.60, 0.60, 0.60}, {0.70, 0.70, 0.70}, {0.75, 0.75, 0.75}, 2.0, 1.4, 1},
};

static const theme *theme_of(const hy_figure *f)
{
    return f->theme > 0 && (size_t)f->theme < sizeof themes / sizeof themes[0] ? &themes[f->theme]
                                                                                : &themes[HY_THEME_PAPER];
}

static hy_rgb colour_of(const theme *th, hy_colour c)
{
    hy_rgb v = c.palette == HY_RGB_EXPLICIT ? c.rgb
                                            : hy_palette[(c.palette < 0 ? -c.palette : c.palette) % HY_PALETTE_SIZE];
    if (th->dark && 0.2126 * v.r + 0.7152 * v.g + 0.0722 * v.b < 0.25)
        return th->fg;
    return v;
}

/* Where an annotation went: its baseline start, box and the point it labels. */
typedef struct text_place {
    int ok, leader;
    double x, y, box[4], ax, ay;
} text_place;

/* A series as drawn: device points (NaN breaks the line), simplified. */
typedef struct curve {
    double *x, *y;
    size_t n, cap;
    int built, oom;
} curve;

/* The drawn curves of a panel's series for the frame and limits in key. */
typedef struct curves {
    double key[8];
    int valid;
    curve *c;                            /* per series; x NULL: drawn from the data */
} curves;

/* One panel being laid out: its frame in points and its axis mappings. */
typedef struct panel {
    const hy_axes *ax;
    const hy_canvas *cv;                 /* axes, text, legend; also measures */
    const hy_canvas *dv;                 /* data: band, grid, series, marks */
    const theme *th;
    double fs;
    double x0, y0, w, h;
    double xlo, xhi, ylo, yhi;
    int xlog, ylog;
    hy_ticks xt, yt;
    double ytick_w, xtick_h;
    double cx, cy, cw, ch;               /* the grid cell */
    double ml, mr, mt, mb;               /* margins: frame to cell edges */
    int legend_outside;                  /* "best" found no free spot inside: right of the frame */
    text_place *tplace;                  /* ax->ntexts placed annotations */
    int has_inset;                       /* a zoomed inset: its axes, cell and own panel */
    hy_axes inset_ax;
    double inset[4];                     /* the inset's cell (frame and tick labels), x y w h */
    struct panel *inset_panel;
    struct place_grid *grid;             /* while annotations are placed, else NULL */
    double tol;                          /* curve tolerance in points; 0: every point drawn */
    double dense;                        /* lines with more points per point of length are simplified */
    double vtol;                         /* vector output: strokes simplified to this (points), else 0 */
    curves *cache;                       /* the drawn curves (for the current frame) */
    const hy_cancel *cancel;             /* the figure's: asked between annotations */
} panel;

static double tr(double v, int log_scale) { return log_scale ? log10(v) : v; }

static double map_x(const panel *p, double v)
{
    return p->x0 + (tr(v, p->xlog) - tr(p->xlo, p->xlog)) /
                       (tr(p->xhi, p->xlog) - tr(p->xlo, p->xlog)) * p->w;
}

static double map_y(const panel *p, double v)
{
    return p->y0 + p->h - (tr(v, p->ylog) - tr(p->ylo, p->ylog)) /
                              (tr(p->yhi, p->ylog) - tr(p->ylo, p->ylog)) * p->h;
}

static int usable(double v, int log_scale) { return isfinite(v) && (!log_scale || v > 0.0); }

static void grow(double v, int log_scale, double *lo, double *hi)
{
    if (!usable(v, log_scale))
        return;
    if (v < *lo)
        *lo = v;
    if (v > *hi)
        *hi = v;
}

/* Data range of one axis (0 = x, 1 = y) with 4 % padding, or the explicit limits. */
static int axis_range(const hy_axes *ax, int axis, double *lo, double *hi, hy_error *err)
{
    const hy_range *r = axis ? &ax->y : &ax->x;
    int lg = r->log;
    if (r->lo < r->hi) {
        if (!isfinite(r->lo) || !isfinite(r->hi) || (lg && r->lo <= 0.0))
            return hy_error_set(err, HY_EINVAL, "%s-axis limits [%g, %g] are not usable%s",
                                axis ? "y" : "x", r->lo, r->hi, lg ? " on a log scale" : "");
        *lo = r->lo;
        *hi = r->hi;
        return HY_OK;
    }
    *lo = INFINITY;
    *hi = -INFINITY;
    for (size_t s = 0; s < ax->nseries; s++) {
        const hy_series *se = &ax->series[s];
        const double *v = axis ? se->y : se->x;
        for (size_t i = 0; v && i < se->n; i++)
            if (usable(se->x ? se->x[i] : 0, ax->x.log) && usable(se->y ? se->y[i] : 0, ax->y.log))
                grow(v[i], lg, lo, hi);
    }
    for (size_t m = 0; m < ax->nmarks; m++)
        grow(axis ? ax->marks[m].y : ax->marks[m].x, lg, lo, hi);
    if (!(*lo <= *hi)) {
        *lo = lg ? 1.0 : 0.0;
        *hi = lg ? 10.0 : 1.0;
        return HY_OK;
    }
    double a = tr(*lo, lg), b = tr(*hi, lg);
    if (!isfinite(b - a) || !isfinite(1.1 * (b - a)))
        return hy_error_set(err, HY_EINVAL, "%s-axis data range [%g, %g] is too wide to plot; "
                            "set explicit limits", axis ? "y" : "x", *lo, *hi);
    if (b - a < 1e-12 * (fabs(a) + fabs(b)) || b == a) {
        double d = lg ? 0.5 : (a != 0.0 ? 0.1 * fabs(a) : 1.0);
        a -= d;
        b += d;
    } else {
        double pad = r->tight ? 0.0 : 0.04 * (b - a);
        a -= pad;
        b += pad;
    }
    *lo = lg ? pow(10.0, a) : a;
    *hi = lg ? pow(10.0, b) : b;
    return HY_OK;
}

typedef struct measure_ctx {
    const hy_canvas *cv;
    double fs;
    int horizontal;
} measure_ctx;

static double measure_label(void *ctx, const char *label)
{
    const measure_ctx *m = ctx;
    hy_markup_box b;
    hy_markup_text(m->cv, label, m->fs, 0, 0, 0, 0, hy_palette[0], &b);
    return m->horizontal ? b.width : b.ascent + b.descent;
}

static double label_height(const hy_canvas *cv, const char *s, double fs, double *desc)
{
    hy_markup_box b = {0, 0, 0};
    if (s && *s)
        hy_markup_text(cv, s, fs, 0, 0, 0, 0, hy_palette[0], &b);
    if (desc)
        *desc = b.descent;
    return s && *s ? b.ascent + b.descent : 0.0;
}

/* Ticks for both axes at the current frame size, and the extents of their labels. */
static int panel_ticks(panel *p)
{
    measure_ctx mx = {p->cv, p->fs, 1}, my = {p->cv, p->fs, 0};
    int st = hy_ticks_fit(p->xlo, p->xhi, p->xlog, p->w, 0.8 * p->fs, 10, measure_label, &mx, &p->xt);
    if (!st)
        st = hy_ticks_fit(p->ylo, p->yhi, p->ylog, p->h, 0.5 * p->fs, 10, measure_label, &my, &p->yt);
    p->ytick_w = 0.0;
    p->xtick_h = p->fs;
    for (int i = 0; i < p->yt.n; i++) {
        double w = measure_label(&mx, p->yt.label[i]);
        if (w > p->ytick_w)
            p->ytick_w = w;
    }
    for (int i = 0; i < p->xt.n; i++) {
        double hgt = measure_label(&my, p->xt.label[i]);
        if (hgt > p->xtick_h)
            p->xtick_h = hgt;
    }
    return st;
}

/* Places the frame in the cell with the given margins and picks ticks for it. */
static int panel_frame(panel *p, hy_error *err)
{
    p->x0 = p->cx + p->ml;
    p->y0 = p->cy + p->mt;
    p->w = p->cw - p->ml - p->mr;
    p->h = p->ch - p->mt - p->mb;
    if (p->w < 2.0 * p->fs || p->h < 2.0 * p->fs)
        return hy_error_set(err, HY_EINVAL, "figure too small: a panel's plot area would be "
                            "%.0f x %.0f pt", p->w, p->h);
    if (panel_ticks(p))
        return hy_error_set(err, HY_EINVAL, "cannot place ticks on the axis range");
    return HY_OK;
}

/* Margins from measured labels, iterated to a fixed point (ticks depend on the frame size). */
static int panel_layout(panel *p, hy_error *err)
{
    const hy_axes *ax = p->ax;
    double ylab = label_height(p->cv, ax->ylabel, p->fs, NULL);
    double xlab = label_height(p->cv, ax->xlabel, p->fs, NULL);
    double ttl = label_height(p->cv, ax->title, p->fs, NULL);
    p->ytick_w = 2.5 * p->fs;
    p->xtick_h = p->fs;
    p->mr = OUTER + 0.5 * p->fs;
    for (int iter = 0; iter < 3; iter++) {
        p->ml = OUTER + (ylab > 0 ? ylab + GAP : 0.0) + p->ytick_w + PAD;
        p->mb = OUTER + (xlab > 0 ? xlab + GAP : 0.0) + p->xtick_h + PAD;
        p->mt = OUTER + (ttl > 0 ? ttl + GAP : 0.5 * p->fs);
        int st = panel_frame(p, err);
        if (st)
            return st;
        /* The last x tick label may stick out on the right. */
        p->mr = OUTER + 0.5 * p->fs;
        if (p->xt.n > 0) {
            measure_ctx mx = {p->cv, p->fs, 1};
            double half = 0.5 * measure_label(&mx, p->xt.label[p->xt.n - 1]);
            double room = p->x0 + p->w - map_x(p, p->xt.v[p->xt.n - 1]);
            if (OUTER + half - room > p->mr)
                p->mr = OUTER + half - room;
        }
    }
    return HY_OK;
}

static void line(const hy_canvas *cv, double x1, double y1, double x2, double y2, const hy_pen *pen)
{
    cv->ops->begin_path(cv->ctx);
    cv->ops->move_to(cv->ctx, x1, y1);
    cv->ops->line_to(cv->ctx, x2, y2);
    cv->ops->stroke(cv->ctx, pen);
}

/* Liang-Barsky: clips the segment to [xa,xb]x[ya,yb]; 0 if nothing is left. */
static int clip_segment(double *x1, double *y1, double *x2, double *y2,
                        double xa, double ya, double xb, double yb)
{
    double t0 = 0.0, t1 = 1.0, dx = *x2 - *x1, dy = *y2 - *y1;
    double pq[4][2] = {{-dx, *x1 - xa}, {dx, xb - *x1}, {-dy, *y1 - ya}, {dy, yb - *y1}};
    for (int i = 0; i < 4; i++) {
        double pp = pq[i][0], q = pq[i][1];
        if (pp == 0.0) {
            if (q < 0.0)
                return 0;
            continue;
        }
        double r = q / pp;
        if (pp < 0.0) {
            if (r > t1)
                return 0;
            if (r > t0)
                t0 = r;
        } else {
            if (r < t0)
                return 0;
            if (r < t1)
                t1 = r;
        }
    }
    double ox = *x1, oy = *y1;
    *x1 = ox + t0 * dx;
    *y1 = oy + t0 * dy;
    *x2 = ox + t1 * dx;
    *y2 = oy + t1 * dy;
    return 1;
}

/* The pen of a series: width, colour and a dash pattern that survives greyscale. */
static hy_pen series_pen(const theme *th, const hy_series *s, double dash[4])
{
    double w = (s->width > 0 ? s->width : 1.0) * th->line, k = w > 0.8 ? w : 0.8;
    hy_pen pen = {colour_of(th, s->colour), 1.0, w, dash, 0, 0, 0};
    switch (s->style) {
    case HY_LINE_DASHED:
        dash[0] = 5.0 * k, dash[1] = 2.5 * k, pen.ndash = 2;
        break;
    case HY_LINE_DOTTED:
        dash[0] = 0.0, dash[1] = 2.2 * k, pen.ndash = 2, pen.round_caps = 1;
        break;
    case HY_LINE_DASHDOT:
        dash[0] = 5.0 * k, dash[1] = 2.4 * k, dash[2] = 0.0, dash[3] = 2.4 * k;
        pen.ndash = 4, pen.round_caps = 1;
        break;
    default:
        pen.dash = NULL;
        break;
    }
    return pen;
}

static void draw_marker(const hy_canvas *cv, const theme *th, int marker, double x, double y, double size,
                        hy_rgb c, int filled)
{
    hy_pen pen = {c, 1.0, 0.7 * th->line, NULL, 0, 0, 0};
    size *= th->text;
    int shape = marker == HY_MARKER_SQUARE ? HY_SHAPE_SQUARE : HY_SHAPE_CIRCLE;
    cv->ops->marker(cv->ctx, shape, x, y, size, &pen, filled ? &c : NULL);
}

/* ---- curves at the output's resolution (issue 23 item 2) -------------------
 * What a series' line draws is computed once per frame and limits: its
 * points mapped to the device; a dense solid line (more than 20 points per
 * point of width) first thinned per 0.25 pt column (M4 aggregation: the
 * first, lowest, highest and last point of each column in their order);
 * then simplified to p->tol (hy_simplify.h: every point within tol of the
 * polyline drawn, turning points and extremes kept exactly).  Drawing, label
 * placement and the legend's free spot all look at these points.  With
 * p->tol 0 (the figure's full_resolution) every point is drawn as given. */

typedef struct feed {
    hy_simplify simp;
    int simplify;            /* 0: every point fed is emitted */
    size_t *keep, nkeep, k;
} feed;

static void curve_emit(void *ctx, double x, double y)
{
    curve *c = ctx;
    if (c->oom)
        return;
    if (c->n == c->cap) {
        size_t cap = c->cap ? 2 * c->cap : 256;
        double *nx = realloc(c->x, cap * sizeof *nx);
        if (nx)
            c->x = nx;
        double *ny = nx ? realloc(c->y, cap * sizeof *ny) : NULL;
        if (!ny) {
            c->oom = 1;
            return;
        }
        c->y = ny, c->cap = cap;
    }
    c->x[c->n] = x, c->y[c->n] = y, c->n++;
}

static void feed_point(feed *f, double x, double y, size_t i)
{
    if (!f->simplify) {
        f->simp.emit(f->simp.ctx, x, y);
        return;
    }
    while (f->k < f->nkeep && f->keep[f->k] < i)
        f->k++;
    hy_simplify_point(&f->simp, x, y, f->k < f->nkeep && f->keep[f->k] == i);
}

/* Feeds a dense solid series thinned: consecutive points falling in one
 * 0.25 pt column are replaced by the first, lowest, highest and last of them
 * in their original order (M4 aggregation).  NaN breaks survive. */
static void thin_series(const panel *p, const hy_series *s, feed *f)
{
    size_t i = 0;
    while (i < s->n) {
        if (!usable(s->x[i], p->xlog) || !usable(s->y[i], p->ylog)) {
            feed_point(f, NAN, NAN, i++);
            continue;
        }
        double x0 = map_x(p, s->x[i]);
        double col = floor(x0 * 4.0);
        size_t first = i, lo = i, hi = i, last = i;
        double ylo = map_y(p, s->y[i]), yhi = ylo;
        for (i++; i < s->n && usable(s->x[i], p->xlog) && usable(s->y[i], p->ylog); i++) {
            double x = map_x(p, s->x[i]);
            if (floor(x * 4.0) != col)
                break;
            double y = map_y(p, s->y[i]);
            if (y < ylo)
                ylo = y, lo = i;
            if (y > yhi)
                yhi = y, hi = i;
            last = i;
        }
        size_t keep[4] = {first, lo < hi ? lo : hi, lo < hi ? hi : lo, last};
        for (int k = 0; k < 4; k++)
            if (!k || keep[k] != keep[k - 1])
                feed_point(f, map_x(p, s->x[keep[k]]), map_y(p, s->y[keep[k]]), keep[k]);
    }
}

static void curve_build(const panel *p, const hy_series *s, curve *c)
{
    hy_turns t;
    hy_turns_begin(&t, p->tol);
    double len = 0.0, px = NAN, py = NAN;
    size_t used = 0;
    for (size_t i = 0; i < s->n; i++) {
        int ok = usable(s->x[i], p->xlog) && usable(s->y[i], p->ylog);
        double x = ok ? map_x(p, s->x[i]) : NAN, y = ok ? map_y(p, s->y[i]) : NAN;
        hy_turns_point(&t, x, y, i);
        if (ok && !isnan(px))
            len += sqrt((x - px) * (x - px) + (y - py) * (y - py));
        px = x, py = y, used += ok;
    }
    feed f = {.simplify = (double)used > p->dense * len};
    if (hy_turns_end(&t, &f.keep, &f.nkeep)) {
        c->oom = 1;
        return;
    }
    hy_simplify_begin(&f.simp, p->tol, curve_emit, c);
    if (s->style == HY_LINE_SOLID && (double)s->n > 20.0 * p->w)
        thin_series(p, s, &f);
    else
        for (size_t i = 0; i < s->n; i++) {
            int ok = usable(s->x[i], p->xlog) && usable(s->y[i], p->ylog);
            feed_point(&f, ok ? map_x(p, s->x[i]) : NAN, ok ? map_y(p, s->y[i]) : NAN, i);
        }
    if (f.simplify)
        hy_simplify_end(&f.simp);
    free(f.keep);
}

static void curves_free(curves *cc, size_t n)
{
    for (size_t i = 0; cc->c && i < n; i++)
        free(cc->c[i].x), free(cc->c[i].y);
    free(cc->c);
    cc->c = NULL;
    cc->valid = 0;
}

/* The drawn curve of series s, or NULL where its line is drawn from the data
 * (no line, markers at every point, every point asked for, out of memory). */
static const curve *panel_curve(const panel *p, size_t s)
{
    curves *cc = p->cache;
    const hy_series *se = &p->ax->series[s];
    if (!cc || !(p->tol > 0.0) || se->style == HY_LINE_NONE || !se->x || !se->y || se->marker != HY_MARKER_NONE)
        return NULL;
    double key[8] = {p->x0, p->y0, p->w, p->h, p->xlo, p->xhi, p->ylo, p->yhi};
    if (!cc->valid || memcmp(key, cc->key, sizeof key)) {
        curves_free(cc, p->ax->nseries);
        cc->c = calloc(p->ax->nseries, sizeof *cc->c);
        if (!cc->c)
            return NULL;
        memcpy(cc->key, key, sizeof key);
        cc->valid = 1;
    }
    curve *c = &cc->c[s];
    if (!c->built)
        curve_build(p, se, c);
    c->built = 1;
    return c->oom ? NULL : c;
}

/* How many points series s has as drawn (device points, see series_pt). */
static size_t series_npts(const panel *p, size_t s, const curve *c)
{
    const hy_series *se = &p->ax->series[s];
    if (se->style == HY_LINE_NONE && se->marker == HY_MARKER_NONE)
        return 0; /* draws nothing (a series drawn as one mark) */
    return c ? c->n : se->x && se->y ? se->n : 0;
}

/* Point i of series s as drawn, in device points; 0 where the line breaks. */
static int series_pt(const panel *p, const hy_series *se, const curve *c, size_t i, double *x, double *y)
{
    if (c) {
        *x = c->x[i], *y = c->y[i];
        return !isnan(*x);
    }
    if (!usable(se->x[i], p->xlog) || !usable(se->y[i], p->ylog))
        return 0;
    *x = map_x(p, se->x[i]), *y = map_y(p, se->y[i]);
    return 1;
}

/* The stroke of one series being built: clipped segments to the canvas. */
typedef struct stroke {
    const hy_canvas *cv;
    double xa, ya, xb, yb;
    int have_prev, open;
    double px, py, ex, ey;
} stroke;

static void stroke_point(void *ctx, double x, double y)
{
    stroke *k = ctx;
    if (isnan(x)) {
        k->have_prev = 0;
        return;
    }
    if (k->have_prev) {
        double x1 = k->px, y1 = k->py, x2 = x, y2 = y;
        if (clip_segment(&x1, &y1, &x2, &y2, k->xa, k->ya, k->xb, k->yb)) {
            if (!k->open || x1 != k->ex || y1 != k->ey)
                k->cv->ops->move_to(k->cv->ctx, x1, y1);
            k->cv->ops->line_to(k->cv->ctx, x2, y2);
            k->open = 1;
            k->ex = x2, k->ey = y2;
        }
    }
    k->px = x, k->py = y, k->have_prev = 1;
}

/* A drawn curve simplified once more to p->vtol for a vector output: its
 * turning points and extremes found first, then the stream to the stroke.
 * 0, or -1 out of memory (nothing drawn yet). */
static int stroke_vector(const panel *p, const curve *c, stroke *k)
{
    hy_turns t;
    hy_turns_begin(&t, p->vtol);
    for (size_t i = 0; i < c->n; i++)
        hy_turns_point(&t, c->x[i], c->y[i], i);
    feed f = {.simplify = 1};
    if (hy_turns_end(&t, &f.keep, &f.nkeep))
        return -1;
    hy_simplify_begin(&f.simp, p->vtol, stroke_point, k);
    for (size_t i = 0; i < c->n; i++)
        feed_point(&f, c->x[i], c->y[i], i);
    hy_simplify_end(&f.simp);
    free(f.keep);
    return 0;
}

static void draw_series(const panel *p, size_t si)
{
    const hy_canvas *cv = p->dv;
    const hy_series *s = &p->ax->series[si];
    double dash[4], lw = s->width > 0 ? s->width : 1.0;
    hy_pen pen = series_pen(p->th, s, dash);
    if (s->style == HY_LINE_NONE || !s->x || !s->y)
        return;
    stroke k = {cv, p->x0 - 2 * lw, p->y0 - 2 * lw, p->x0 + p->w + 2 * lw, p->y0 + p->h + 2 * lw, 0, 0, 0, 0, NAN, NAN};
    const curve *c = panel_curve(p, si);
    cv->ops->begin_path(cv->ctx);
    if (!c || !(p->vtol > 0.0) || stroke_vector(p, c, &k))
        for (size_t i = 0, n = series_npts(p, si, c); i < n; i++) {
            double x, y;
            int ok = series_pt(p, s, c, i, &x, &y);
            stroke_point(&k, ok ? x : NAN, ok ? y : NAN);
        }
    cv->ops->stroke(cv->ctx, &pen);
}

/* The markers of a series (drawn after every line, so no line covers them). */
static void draw_series_markers(const panel *p, const hy_series *s)
{
    const hy_canvas *cv = p->dv;
    double lw = s->width > 0 ? s->width : 1.0;
    double xa = p->x0 - 2 * lw, xb = p->x0 + p->w + 2 * lw;
    double ya = p->y0 - 2 * lw, yb = p->y0 + p->h + 2 * lw;
    if (s->marker != HY_MARKER_NONE && s->x && s->y) {
        double ms = s->marker_size > 0 ? s->marker_size : 4.0;
        for (size_t i = 0; i < s->n; i++) {
            if (!usable(s->x[i], p->xlog) || !usable(s->y[i], p->ylog))
                continue;
            double x = map_x(p, s->x[i]), y = map_y(p, s->y[i]);
            if (x >= xa && x <= xb && y >= ya && y <= yb)
                draw_marker(cv, p->th, s->marker, x, y, ms, colour_of(p->th, s->colour), s->marker_filled);
        }
    }
}

static void draw_band_grid(const panel *p)
{
    const hy_axes *ax = p->ax;
    const hy_canvas *cv = p->dv;
    if (ax->band && usable(ax->band_lo, p->xlog) && usable(ax->band_hi, p->xlog)) {
        double a = map_x(p, ax->band_lo), b = map_x(p, ax->band_hi);
        if (a > b) {
            double t = a;
            a = b;
            b = t;
        }
        a = a < p->x0 ? p->x0 : a;
        b = b > p->x0 + p->w ? p->x0 + p->w : b;
        if (b > a)
            cv->ops->fill_rect(cv->ctx, a, p->y0, b - a, p->h, p->th->band, 1.0);
    }
    if (!ax->grid)
        return;
    hy_pen pen = {p->th->grid, 1.0, 0.4 * p->th->line, NULL, 0, 0, 0};
    for (int i = 0; i < p->xt.n; i++) {
        double x = map_x(p, p->xt.v[i]);
        line(cv, x, p->y0, x, p->y0 + p->h, &pen);
    }
    for (int i = 0; i < p->yt.n; i++) {
        double y = map_y(p, p->yt.v[i]);
        line(cv, p->x0, y, p->x0 + p->w, y, &pen);
    }
}

/* Minor log ticks at 2..9 x 10^k between lo and hi, on one axis. */
static void draw_minor_log(const panel *p, int axis, const hy_pen *pen)
{
    double lo = axis ? p->ylo : p->xlo, hi = axis ? p->yhi : p->xhi;
    hy_ticks *t = axis ? (hy_ticks *)&p->yt : (hy_ticks *)&p->xt;
    if (t->step != 1.0)
        return;   /* only when every decade is labelled */
    for (int d = (int)floor(log10(lo)); d <= (int)ceil(log10(hi)); d++)
        for (int m = 2; m <= 9; m++) {
            double v = m * pow(10.0, d);
            if (v < lo || v > hi)
                continue;
            if (axis) {
                double y = map_y(p, v);
                line(p->cv, p->x0, y, p->x0 + 0.55 * TICK_LEN, y, pen);
                line(p->cv, p->x0 + p->w, y, p->x0 + p->w - 0.55 * TICK_LEN, y, pen);
            } else {
                double x = map_x(p, v);
                line(p->cv, x, p->y0 + p->h, x, p->y0 + p->h - 0.55 * TICK_LEN, pen);
                line(p->cv, x, p->y0, x, p->y0 + 0.55 * TICK_LEN, pen);
            }
        }
}

static void draw_frame_ticks(const panel *p)
{
    const hy_canvas *cv = p->cv;
    hy_rgb black = p->th->fg;
    hy_pen pen = {black, 1.0, FRAME_W * p->th->line, NULL, 0, 0, 1};
    double x1 = p->x0 + p->w, y1 = p->y0 + p->h;
    cv->ops->begin_path(cv->ctx);
    cv->ops->move_to(cv->ctx, p->x0, p->y0);
    cv->ops->line_to(cv->ctx, x1, p->y0);
    cv->ops->line_to(cv->ctx, x1, y1);
    cv->ops->line_to(cv->ctx, p->x0, y1);
    cv->ops->line_to(cv->ctx, p->x0, p->y0);
    cv->ops->stroke(cv->ctx, &pen);
    for (int i = 0; i < p->xt.n; i++) {
        double x = map_x(p, p->xt.v[i]);
        hy_markup_box b;
        line(cv, x, y1, x, y1 - TICK_LEN, &pen);
        line(cv, x, p->y0, x, p->y0 + TICK_LEN, &pen);
        hy_markup_text(cv, p->xt.label[i], p->fs, 0, 0, 0, 0, black, &b);
        hy_markup_text(cv, p->xt.label[i], p->fs, 1, 0, x - 0.5 * b.width, y1 + PAD + b.ascent,
                       black, NULL);
    }
    for (int i = 0; i < p->yt.n; i++) {
        double y = map_y(p, p->yt.v[i]);
        hy_markup_box b;
        line(cv, p->x0, y, p->x0 + TICK_LEN, y, &pen);
        line(cv, x1, y, x1 - TICK_LEN, y, &pen);
        hy_markup_text(cv, p->yt.label[i], p->fs, 0, 0, 0, 0, black, &b);
        hy_markup_text(cv, p->yt.label[i], p->fs, 1, 0, p->x0 - PAD - b.width, y + 0.36 * p->fs,
                       black, NULL);
    }
    hy_pen minor = pen;
    minor.width = 0.5;
    if (p->xlog)
        draw_minor_log(p, 0, &minor);
    if (p->ylog)
        draw_minor_log(p, 1, &minor);
}

static void draw_labels(const panel *p)
{
    const hy_axes *ax = p->ax;
    const hy_canvas *cv = p->cv;
    hy_rgb black = p->th->fg;
    hy_markup_box b;
    if (ax->xlabel && *ax->xlabel) {
        hy_markup_text(cv, ax->xlabel, p->fs, 0, 0, 0, 0, black, &b);
        /* At the bottom of the (row-aligned) margin, so labels of a row line up. */
        double base = p->y0 + p->h + p->mb - OUTER - b.descent;
        hy_markup_text(cv, ax->xlabel, p->fs, 1, 0, p->x0 + 0.5 * (p->w - b.width), base, black, NULL);
    }
    if (ax->ylabel && *ax->ylabel) {
        hy_markup_text(cv, ax->ylabel, p->fs, 0, 1, 0, 0, black, &b);
        double base = p->x0 - p->ml + OUTER + b.ascent;   /* column-aligned */
        hy_markup_text(cv, ax->ylabel, p->fs, 1, 1, base, p->y0 + 0.5 * (p->h + b.width), black, NULL);
    }
    if (ax->title && *ax->title) {
        hy_markup_text(cv, ax->title, p->fs, 0, 0, 0, 0, black, &b);
        hy_markup_text(cv, ax->title, p->fs, 1, 0, p->x0 + 0.5 * (p->w - b.width),
                       p->y0 - GAP - b.descent, black, NULL);
    }
}

static void draw_marks(const panel *p)
{
    const hy_axes *ax = p->ax;
    for (size_t i = 0; i < ax->nmarks; i++) {
        const hy_mark *m = &ax->marks[i];
        if (!usable(m->x, p->xlog) || !usable(m->y, p->ylog))
            continue;
        double x = map_x(p, m->x), y = map_y(p, m->y);
        if (x >= p->x0 - 1 && x <= p->x0 + p->w + 1 && y >= p->y0 - 1 && y <= p->y0 + p->h + 1)
            draw_marker(p->dv, p->th, m->marker ? m->marker : HY_MARKER_CIRCLE, x, y,
                        m->size > 0 ? m->size : 5.0, colour_of(p->th, m->colour), m->filled);
    }
}

/* Box (x, y, w, h; y down) of annotation i where it was placed. */
static int text_box(const panel *p, size_t i, double b[4])
{
    if (!p->tplace || !p->tplace[i].ok)
        return 0;
    memcpy(b, p->tplace[i].box, sizeof p->tplace[i].box);
    return 1;
}

static double overlap(const panel *p, double rx, double ry, double rw, double rh);
static double overlap_bounded(const panel *p, double rx, double ry, double rw, double rh, double bound);

/* The point of a box's edge nearest to (x, y). */
static void nearest_on_box(const double b[4], double x, double y, double *nx, double *ny)
{
    *nx = x < b[0] ? b[0] : x > b[0] + b[2] ? b[0] + b[2] : x;
    *ny = y < b[1] ? b[1] : y > b[1] + b[3] ? b[1] + b[3] : y;
}

static int segs_cross(double ax, double ay, double bx, double by, double cx, double cy, double dx, double dy)
{
    double d1 = (bx - ax) * (cy - ay) - (by - ay) * (cx - ax), d2 = (bx - ax) * (dy - ay) - (by - ay) * (dx - ax);
    double d3 = (dx - cx) * (ay - cy) - (dy - cy) * (ax - cx), d4 = (dx - cx) * (by - cy) - (dy - cy) * (bx - cx);
    return ((d1 > 0) != (d2 > 0)) && ((d3 > 0) != (d4 > 0));
}

static int pg_leader_crosses(const panel *p, double x1, double y1, double x2, double y2);
static double seg_in_rect(double x1, double y1, double x2, double y2, double rx, double ry, double rw, double rh);
static double pg_overlap(const panel *p, double rx, double ry, double rw, double rh, double bound);

/* Whether a leader line from (x1, y1) to within 2 pt of (x2, y2) crosses a drawn curve. */
static int leader_crosses(const panel *p, double x1, double y1, double x2, double y2)
{
    double len = hypot(x2 - x1, y2 - y1);
    if (len > 2.0)
        x2 -= 2.0 * (x2 - x1) / len, y2 -= 2.0 * (y2 - y1) / len;
    int hit = p->grid ? pg_leader_crosses(p, x1, y1, x2, y2) : -1;
    if (hit >= 0)
        return hit;
    for (size_t s = 0; s < p->ax->nseries; s++) {
        const hy_series *se = &p->ax->series[s];
        const curve *c = panel_curve(p, s);
        double px = NAN, py = NAN, x, y;
        for (size_t i = 0, n = series_npts(p, s, c); se->style != HY_LINE_NONE && i < n; i++) {
            if (!series_pt(p, se, c, i, &x, &y)) {
                px = NAN;
                continue;
            }
            if (isfinite(px) && segs_cross(x1, y1, x2, y2, px, py, x, y))
                return 1;
            px = x, py = y;
        }
    }
    return 0;
}

/* ---- the placement grid (issue 20 item 8) ----------------------------------
 * Placing an annotation tries up to 2 x 31 rings x 24 spots, and each spot
 * asked overlap() about every point of every series and every placed box:
 * 400 annotations took 6 s, 3000 over a minute.  While annotations are
 * placed, a uniform grid over the frame (and a margin) lists, per cell, the
 * points whose segment or marker reaches into it, and the boxes placed so
 * far; a spot looks only at the cells it covers, and stops once what it
 * covers passes the least covering spot found.  The sum it returns is the
 * scan's, term for term in the scan's order, so placement is unchanged. */
typedef struct text_entry {
    int text, next;
} text_entry;

typedef struct place_grid {
    double gx0, gy0, gx1, gy1, cs;       /* the grid's area and cell size (points) */
    int nx, ny;
    double reach;                        /* what a rectangle is grown by to find them */
    size_t npts;                         /* points of every series, in scan order */
    double *px, *py;                     /* mapped (NaN where not usable) */
    int *ser;
    size_t *start;                       /* cell c's points: item[start[c] .. start[c + 1]) */
    uint32_t *item;
    int *head;                           /* cell c's boxes: tent[head[c]], linked by next */
    text_entry *tent;
    size_t ntent, captent;
    unsigned *mark, stamp;               /* visited in this query (points, then texts) */
    size_t nitem;                        /* points + annotations */
    size_t *found;
    size_t visits;                       /* items looked at by every query so far */
} place_grid;

static void pg_cells(const place_grid *g, double x, double y, int *cx, int *cy)
{
    double fx = floor((x - g->gx0) / g->cs), fy = floor((y - g->gy0) / g->cs);
    *cx = fx < 0 ? 0 : fx >= g->nx ? g->nx - 1 : (int)fx;
    *cy = fy < 0 ? 0 : fy >= g->ny ? g->ny - 1 : (int)fy;
}

/* The columns [*a, *b] of row r that the segment (x1, y1)-(x2, y2) reaches, one more
 * each side, within its bounding cells c0..c1 (rows r0..r1). */
static void pg_row_span(const place_grid *g, double x1, double y1, double x2, double y2, int r, int r0, int r1,
                        int c0, int c1, int *a, int *b)
{
    *a = c0, *b = c1;
    if (y1 != y2 && r1 > r0) {
        double ya = fmax(fmin(y1, y2), g->gy0 + r * g->cs), yb = fmin(fmax(y1, y2), g->gy0 + (r + 1) * g->cs);
        double xa = x1 + (ya - y1) * (x2 - x1) / (y2 - y1), xb = x1 + (yb - y1) * (x2 - x1) / (y2 - y1);
        int dummy;
        pg_cells(g, fmin(xa, xb), ya, a, &dummy);
        pg_cells(g, fmax(xa, xb), ya, b, &dummy);
        *a = *a > c0 ? *a - 1 : c0;
        *b = *b < c1 ? *b + 1 : c1;
    }
}

/* Calls out for every cell the segment (clipped to the grid) may touch:
 * per row, the columns between its x at the row's edges, one more each side.
 * fill 0 counts into start[c + 1], 1 writes id at pos[c]++. */
static void pg_segment(place_grid *g, double x1, double y1, double x2, double y2, uint32_t id, int fill,
                       size_t *pos, int *last)
{
    if (!clip_segment(&x1, &y1, &x2, &y2, g->gx0, g->gy0, g->gx1, g->gy1))
        return;
    int r0, r1, c0, c1;
    pg_cells(g, fmin(x1, x2), fmin(y1, y2), &c0, &r0);
    pg_cells(g, fmax(x1, x2), fmax(y1, y2), &c1, &r1);
    for (int r = r0; r <= r1; r++) {
        int a, b;
        pg_row_span(g, x1, y1, x2, y2, r, r0, r1, c0, c1, &a, &b);
        for (int c = a; c <= b; c++) {
            int cell = r * g->nx + c;
            if (*last == cell)
                continue;
            if (fill)
                g->item[pos[cell]++] = id;
            else
                g->start[cell + 1]++;
        }
        *last = -1;
    }
}

/* Registers point i of the scan (its segment from the point before and its marker). */
static void pg_point(const panel *p, place_grid *g, size_t i, int fill, size_t *pos)
{
    const hy_series *se = &p->ax->series[g->ser[i]];
    double ms = se->marker != HY_MARKER_NONE ? 0.5 * (se->marker_size > 0 ? se->marker_size : 4.0) : 0;
    int last = -1;
    if (!isfinite(g->px[i]))
        return;
    if (se->style != HY_LINE_NONE && i > 0 && g->ser[i - 1] == g->ser[i] && isfinite(g->px[i - 1]))
        pg_segment(g, g->px[i - 1], g->py[i - 1], g->px[i], g->py[i], (uint32_t)i, fill, pos, &last);
    if (ms > 0)
        pg_segment(g, g->px[i], g->py[i], g->px[i], g->py[i], (uint32_t)i, fill, pos, &last);
}

static void pg_free(place_grid *g)
{
    if (!g)
        return;
    free(g->px), free(g->py), free(g->ser), free(g->start), free(g->item), free(g->head), free(g->tent);
    free(g->mark), free(g->found), free(g);
}

/* The grid of p's series, or NULL (out of memory, or nothing to place:
 * overlap() then scans as before). */
static place_grid *pg_build(const panel *p)
{
    const hy_axes *ax = p->ax;
    place_grid *g = calloc(1, sizeof *g);
    if (!g)
        return NULL;
    double hw = 0, ms = 0;
    for (size_t s = 0; s < ax->nseries; s++) {
        const hy_series *se = &ax->series[s];
        g->npts += series_npts(p, s, panel_curve(p, s));
        hw = fmax(hw, 0.5 * (se->width > 0 ? se->width : 1.0) + 1.0);
        if (se->marker != HY_MARKER_NONE)
            ms = fmax(ms, 0.5 * (se->marker_size > 0 ? se->marker_size : 4.0));
    }
    g->reach = fmax(hw, ms) + 1.0;
    double margin = 24.0 + g->reach;
    g->gx0 = p->x0 - margin, g->gy0 = p->y0 - margin, g->gx1 = p->x0 + p->w + margin, g->gy1 = p->y0 + p->h + margin;
    double area = (g->gx1 - g->gx0) * (g->gy1 - g->gy0), target = fmin(65536.0, fmax(64.0, (double)g->npts + 4.0 * (double)ax->ntexts));
    g->cs = fmax(2.0, sqrt(area / target));
    g->nx = (int)ceil((g->gx1 - g->gx0) / g->cs), g->ny = (int)ceil((g->gy1 - g->gy0) / g->cs);
    size_t ncell = (size_t)g->nx * (size_t)g->ny, nitem = g->npts + ax->ntexts;
    g->nitem = nitem;
    g->px = malloc((g->npts + 1) * sizeof *g->px), g->py = malloc((g->npts + 1) * sizeof *g->py);
    g->ser = malloc((g->npts + 1) * sizeof *g->ser), g->start = calloc(ncell + 1, sizeof *g->start);
    g->head = malloc(ncell * sizeof *g->head), g->mark = calloc(nitem + 1, sizeof *g->mark);
    g->found = malloc((nitem + 1) * sizeof *g->found);
    if (!g->px || !g->py || !g->ser || !g->start || !g->head || !g->mark || !g->found || nitem >= UINT32_MAX) {
        pg_free(g);
        return NULL;
    }
    for (size_t c = 0; c < ncell; c++)
        g->head[c] = -1;
    size_t k = 0;
    for (size_t s = 0; s < ax->nseries; s++) {
        const hy_series *se = &ax->series[s];
        const curve *c = panel_curve(p, s);
        for (size_t i = 0, n = series_npts(p, s, c); i < n; i++, k++) {
            double x, y;
            int ok = series_pt(p, se, c, i, &x, &y);
            g->px[k] = ok ? x : NAN;
            g->py[k] = ok ? y : NAN;
            g->ser[k] = (int)s;
        }
    }
    for (size_t i = 0; i < g->npts; i++)
        pg_point(p, g, i, 0, NULL);
    for (size_t c = 0; c < ncell; c++)
        g->start[c + 1] += g->start[c];
    size_t *pos = malloc((ncell + 1) * sizeof *pos);
    g->item = malloc((g->start[ncell] + 1) * sizeof *g->item);
    if (!pos || !g->item) {
        free(pos);
        pg_free(g);
        return NULL;
    }
    memcpy(pos, g->start, ncell * sizeof *pos);
    for (size_t i = 0; i < g->npts; i++)
        pg_point(p, g, i, 1, pos);
    free(pos);
    return g;
}

/* Adds annotation t's box to the cells it covers (0, or -1 out of memory). */
static int pg_add_text(place_grid *g, int t, const double b[4])
{
    int c0, r0, c1, r1;
    pg_cells(g, b[0], b[1], &c0, &r0);
    pg_cells(g, b[0] + b[2], b[1] + b[3], &c1, &r1);
    for (int r = r0; r <= r1; r++)
        for (int c = c0; c <= c1; c++) {
            if (g->ntent == g->captent) {
                size_t cap = g->captent ? 2 * g->captent : 256;
                text_entry *e = realloc(g->tent, cap * sizeof *e);
                if (!e)
                    return -1;
                g->tent = e, g->captent = cap;
            }
            int cell = r * g->nx + c;
            g->tent[g->ntent] = (text_entry){t, g->head[cell]};
            g->head[cell] = (int)g->ntent++;
        }
    return 0;
}

/* A fresh query stamp. */
static unsigned pg_stamp(place_grid *g)
{
    if (++g->stamp == 0) {
        memset(g->mark, 0, (g->nitem + 1) * sizeof *g->mark);
        g->stamp = 1;
    }
    return g->stamp;
}

/* What point i of the scan adds to overlap(): its segment's length inside
 * the rectangle (grown by the pen) and its marker. */
static double pg_point_overlap(const panel *p, const place_grid *g, size_t i, double rx, double ry, double rw,
                               double rh)
{
    const hy_series *se = &p->ax->series[g->ser[i]];
    double hw = 0.5 * (se->width > 0 ? se->width : 1.0) + 1.0;
    double ms = se->marker != HY_MARKER_NONE ? 0.5 * (se->marker_size > 0 ? se->marker_size : 4.0) : 0;
    double x = g->px[i], y = g->py[i], sum = 0.0;
    if (!isfinite(x))
        return 0.0;
    if (se->style != HY_LINE_NONE && i > 0 && g->ser[i - 1] == g->ser[i] && isfinite(g->px[i - 1]))
        sum += seg_in_rect(g->px[i - 1], g->py[i - 1], x, y, rx - hw, ry - hw, rw + 2 * hw, rh + 2 * hw);
    if (ms > 0 && x >= rx - ms && x <= rx + rw + ms && y >= ry - ms && y <= ry + rh + ms)
        sum += 2 * ms;
    return sum;
}

/* sum plus what the panel's marks (their sizes) and its inset (width plus
 * height) put inside the rectangle, added in that order. */
static double marks_overlap(const panel *p, double sum, double rx, double ry, double rw, double rh)
{
    const hy_axes *ax = p->ax;
    for (size_t m = 0; m < ax->nmarks; m++) {
        const hy_mark *mk = &ax->marks[m];
        if (!usable(mk->x, p->xlog) || !usable(mk->y, p->ylog))
            continue;
        double x = map_x(p, mk->x), y = map_y(p, mk->y), r = 0.5 * (mk->size > 0 ? mk->size : 5.0);
        if (x >= rx - r && x <= rx + rw + r && y >= ry - r && y <= ry + rh + r)
            sum += 2 * r;
    }
    if (p->has_inset && p->inset[0] < rx + rw && p->inset[0] + p->inset[2] > rx && p->inset[1] < ry + rh &&
        p->inset[1] + p->inset[3] > ry)
        sum += p->inset[2] + p->inset[3];
    return sum;
}

static int cmp_size(const void *a, const void *b)
{
    size_t x = *(const size_t *)a, y = *(const size_t *)b;
    return x < y ? -1 : x > y;
}

/* overlap() through the grid: the same sum, or a value >= bound as soon as
 * the rectangle is known to cover that much; -1 when the rectangle reaches
 * past the grid (the caller scans). */
static double pg_overlap(const panel *p, double rx, double ry, double rw, double rh, double bound)
{
    place_grid *g = p->grid;
    double m = g->reach;
    if (rx - m < g->gx0 || ry - m < g->gy0 || rx + rw + m > g->gx1 || ry + rh + m > g->gy1)
        return -1.0;
    unsigned st = pg_stamp(g);
    size_t nf = 0;
    double fixed = marks_overlap(p, 0.0, rx, ry, rw, rh), partial = fixed;
    if (partial >= bound && partial > 0)
        return partial;
    int c0, r0, c1, r1;
    pg_cells(g, rx - m, ry - m, &c0, &r0);
    pg_cells(g, rx + rw + m, ry + rh + m, &c1, &r1);
    for (int r = r0; r <= r1; r++)
        for (int c = c0; c <= c1; c++) {
            int cell = r * g->nx + c;
            for (size_t k = g->start[cell]; k < g->start[cell + 1]; k++) {
                uint32_t i = g->item[k];
                g->visits++;
                if (g->mark[i] == st)
                    continue;
                g->mark[i] = st;
                double v = pg_point_overlap(p, g, i, rx, ry, rw, rh);
                if (v > 0) {
                    g->found[nf++] = i;
                    if ((partial += v) >= bound)
                        return partial; /* covers at least the least found: its exact sum is not needed */
                }
            }
            for (int e = g->head[cell]; e >= 0; e = g->tent[e].next) {
                size_t id = g->npts + (size_t)g->tent[e].text;
                double b[4];
                g->visits++;
                if (g->mark[id] == st)
                    continue;
                g->mark[id] = st;
                if (text_box(p, (size_t)g->tent[e].text, b) && b[0] < rx + rw && b[0] + b[2] > rx && b[1] < ry + rh &&
                    b[1] + b[3] > ry) {
                    g->found[nf++] = id;
                    if ((partial += b[2]) >= bound)
                        return partial;
                }
            }
        }
    /* the exact sum, in the scan's order: points, marks and inset, boxes */
    qsort(g->found, nf, sizeof *g->found, cmp_size);
    double sum = 0.0;
    size_t f = 0;
    for (; f < nf && g->found[f] < g->npts; f++)
        sum += pg_point_overlap(p, g, g->found[f], rx, ry, rw, rh);
    sum += fixed;
    for (; f < nf; f++) {
        double b[4];
        text_box(p, g->found[f] - g->npts, b);
        sum += b[2];
    }
    return sum;
}

/* leader_crosses() through the grid: 1, 0, or -1 when the line reaches past it. */
static int pg_leader_crosses(const panel *p, double x1, double y1, double x2, double y2)
{
    place_grid *g = p->grid;
    if (fmin(x1, x2) < g->gx0 || fmin(y1, y2) < g->gy0 || fmax(x1, x2) > g->gx1 || fmax(y1, y2) > g->gy1)
        return -1;
    unsigned st = pg_stamp(g);
    int r0, r1, c0, c1;
    pg_cells(g, fmin(x1, x2), fmin(y1, y2), &c0, &r0);
    pg_cells(g, fmax(x1, x2), fmax(y1, y2), &c1, &r1);
    for (int r = r0; r <= r1; r++) {
        int a, b;
        pg_row_span(g, x1, y1, x2, y2, r, r0, r1, c0, c1, &a, &b);
        for (int c = a; c <= b; c++) {
            int cell = r * g->nx + c;
            for (size_t k = g->start[cell]; k < g->start[cell + 1]; k++) {
                uint32_t i = g->item[k];
                if (g->mark[i] == st)
                    continue;
                g->mark[i] = st;
                const hy_series *se = &p->ax->series[g->ser[i]];
                if (se->style != HY_LINE_NONE && i > 0 && g->ser[i - 1] == g->ser[i] && isfinite(g->px[i]) &&
                    isfinite(g->px[i - 1]) &&
                    segs_cross(x1, y1, x2, y2, g->px[i - 1], g->py[i - 1], g->px[i], g->py[i]))
                    return 1;
            }
        }
    }
    return 0;
}

/* Box (x, y, w, h) of a legend at a fixed place (a corner, or outside), or 0. */
static int fixed_legend_box(const panel *p, double b[4]);

/* Items the placement grid may look at in a panel while it still ranks the
 * spots of a label that finds no free one (issue 36 item 1).  Ranking needs
 * each spot's overlap summed until it passes the least so far; where labels
 * pile up (hundreds asking for one place), that least grows with the pile
 * and every spot of every later label walks it: quadratic.  Past this many
 * visits a spot is only asked whether it covers anything (the walk stops at
 * the first item), and a label with no free spot stays at its own place and
 * is not avoided by later labels (they would walk the pile it makes).
 * The gallery's figures look at fewer than 1e5 items. */
#define PLACE_RANK_VISITS 4000000u

/* One label's search for a spot (place_texts): the box b, from (bx, by) on
 * rings outwards, inside the frame and off the fixed legend; the first spot
 * that covers nothing (in pass 0 also with a leader to (lx, ly) that crosses
 * no curve) goes to *x, *y and 1 is returned; else 0, with the least
 * covering spot inside the frame in *lx_, *ly_ and its overlap in *least
 * (INFINITY when no spot of the rings lies inside the frame). */
typedef struct spot_search {
    const hy_markup_box *b;
    double lx, ly;            /* where a leader line would go */
    int has_point, rank, has_lg;
    double lg[4];
    double least, least_x, least_y;
} spot_search;

static int search_spot(const panel *p, spot_search *s, double bx, double by, double *x, double *y)
{
    const hy_markup_box *b = s->b;
    for (int pass = 0; pass < 2; pass++)
        for (int ring = 0; ring <= 30; ring++) {
            double r = ring * 0.5 * p->fs;
            int dirs = ring ? 24 : 1;
            for (int k = 0; k < dirs; k++) {
                double a = 2.0 * M_PI * k / dirs;
                double cx = bx + r * cos(a), cy = by - r * sin(a);
                double box[4] = {cx - 1.0, cy - b->ascent - 1.0, b->width + 2.0, b->ascent + b->descent + 2.0};
                if (box[0] < p->x0 + 2 || box[1] < p->y0 + 2 || box[0] + box[2] > p->x0 + p->w - 2 ||
                    box[1] + box[3] > p->y0 + p->h - 2)
                    continue;
                if (s->has_lg && s->lg[0] < box[0] + box[2] && s->lg[0] + s->lg[2] > box[0] &&
                    s->lg[1] < box[1] + box[3] && s->lg[1] + s->lg[3] > box[1])
                    continue;
                /* avoids the curves and the annotations placed before it */
                double o = overlap_bounded(p, box[0], box[1], box[2], box[3], s->rank ? s->least : DBL_MIN);
                if (o < s->least)
                    s->least = o, s->least_x = cx, s->least_y = cy;
                if (o != 0.0)
                    continue;
                if (pass == 0 && s->has_point) {
                    double nx, ny;
                    nearest_on_box(box, s->lx, s->ly, &nx, &ny);
                    if (leader_crosses(p, nx, ny, s->lx, s->ly))
                        continue;
                }
                *x = cx, *y = cy;
                return 1;
            }
        }
    return 0;
}

static double clampd(double v, double lo, double hi) { return v < lo ? lo : v > hi ? hi : v; }

/* Places every annotation: at (x, y) shifted by (dx, dy) when its box covers
 * no curve, marker, inset, fixed legend or earlier annotation; else at the
 * nearest free spot inside the frame on rings around it (with none free, the
 * least covering one, or its own place once PLACE_RANK_VISITS are spent).
 * A label whose rings reach no spot inside the frame (placed in data units
 * far off the axes' range, as a slider can make it) is searched for again
 * from the nearest place inside the frame (issue 38 item 3).  A label with a
 * point gets a leader line to it, and prefers spots whose leader crosses no
 * curve.  The run's cancel hook is asked before each label. */
static int place_texts(panel *p, hy_error *err)
{
    const hy_axes *ax = p->ax;
    spot_search s;
    s.has_lg = fixed_legend_box(p, s.lg);
    int rc = HY_OK;
    unsigned tick = 0;
    for (size_t i = 0; i < ax->ntexts; i++)
        p->tplace[i].ok = 0;
    p->grid = ax->ntexts ? pg_build(p) : NULL;
    for (size_t i = 0; i < ax->ntexts; i++) {
        const hy_text *t = &ax->texts[i];
        if (hy_cancel_poll(p->cancel, &tick, 1)) { /* a label: up to HY_PLACE_SPOTS spots */
            rc = hy_cancel_error(err);
            break;
        }
        text_place *tp = &p->tplace[i];
        hy_markup_box b;
        if (!t->text || !usable(t->x, p->xlog) || !usable(t->y, p->ylog))
            continue;
        hy_markup_text(p->cv, t->text, p->fs, 0, 0, 0, 0, hy_palette[0], &b);
        double ax0 = map_x(p, t->x), ay0 = map_y(p, t->y);
        double bx = ax0 + t->dx - 0.5 * t->anchor * b.width, by = ay0 - t->dy, best_x = bx, best_y = by;
        s.b = &b;
        s.lx = ax0, s.ly = ay0;
        s.has_point = t->has_point;
        if (t->has_point && usable(t->px, p->xlog) && usable(t->py, p->ylog))
            s.lx = map_x(p, t->px), s.ly = map_y(p, t->py);
        s.rank = !p->grid || p->grid->visits < PLACE_RANK_VISITS;
        s.least = INFINITY, s.least_x = bx, s.least_y = by;
        int found = search_spot(p, &s, bx, by, &best_x, &best_y);
        if (!found && s.least == INFINITY) /* no ring reached the frame: from the nearest place inside */
            found = search_spot(p, &s, clampd(bx, p->x0 + 3.0, p->x0 + p->w - 3.0 - b.width),
                                clampd(by, p->y0 + 3.0 + b.ascent, p->y0 + p->h - 3.0 - b.descent), &best_x, &best_y);
        if (!found && s.rank)   /* nowhere free: the least covering spot inside the frame */
            best_x = s.least_x, best_y = s.least_y;
        tp->ax = ax0, tp->ay = ay0;
        tp->ok = 1;
        tp->x = best_x, tp->y = best_y;
        tp->box[0] = best_x - 1.0, tp->box[1] = best_y - b.ascent - 1.0;
        tp->box[2] = b.width + 2.0, tp->box[3] = b.ascent + b.descent + 2.0;
        /* a leader only to a point the label is about, never for a nudge */
        tp->leader = 0;
        if (t->has_point && usable(t->px, p->xlog) && usable(t->py, p->ylog))
            tp->ax = map_x(p, t->px), tp->ay = map_y(p, t->py), tp->leader = 1;
        /* a label past the ranking budget with no free spot is not avoided by
         * later ones: a pile at one place would make every later query walk it */
        if (p->grid && (found || s.rank) && pg_add_text(p->grid, (int)i, tp->box)) {
            pg_free(p->grid); /* out of memory: the scan from here on */
            p->grid = NULL;
        }
    }
    pg_free(p->grid);
    p->grid = NULL;
    return rc;
}

static void draw_texts(const panel *p)
{
    const hy_axes *ax = p->ax;
    for (size_t i = 0; i < ax->ntexts; i++) {
        const hy_text *t = &ax->texts[i];
        const text_place *tp = &p->tplace[i];
        if (!tp->ok)
            continue;
        if (tp->leader) {
            double nx, ny;
            hy_pen pen = {p->th->leader, 1.0, 0.5 * p->th->line, NULL, 0, 1, 0};
            nearest_on_box(tp->box, tp->ax, tp->ay, &nx, &ny);
            line(p->cv, nx, ny, tp->ax, tp->ay, &pen);
            p->cv->ops->marker(p->cv->ctx, HY_SHAPE_CIRCLE, tp->ax, tp->ay, 1.6, &pen, &pen.colour);
        }
        hy_markup_text(p->cv, t->text, p->fs, 1, 0, tp->x, tp->y, colour_of(p->th, t->colour), NULL);
    }
}

/* Length (points) of the part of segment (x1, y1)-(x2, y2) inside the
 * rectangle; a zero-length segment inside counts as 1. */
static double seg_in_rect(double x1, double y1, double x2, double y2, double rx, double ry, double rw,
                          double rh)
{
    if (!clip_segment(&x1, &y1, &x2, &y2, rx, ry, rx + rw, ry + rh))
        return 0.0;
    double len = hypot(x2 - x1, y2 - y1);
    return len > 0.0 ? len : 1.0;
}

/* How much of what the panel draws lies inside a rectangle: the length of
 * every series segment as stroked (vertical jumps included, the rectangle
 * grown by the pen's half width), markers and annotation boxes as their
 * sizes.  0 means the rectangle covers nothing. */
static double overlap_bounded(const panel *p, double rx, double ry, double rw, double rh, double bound)
{
    const hy_axes *ax = p->ax;
    double sum = p->grid ? pg_overlap(p, rx, ry, rw, rh, bound) : -1.0;
    if (sum >= 0.0)
        return sum;
    sum = 0.0;
    for (size_t s = 0; s < ax->nseries; s++) {
        const hy_series *se = &ax->series[s];
        double hw = 0.5 * (se->width > 0 ? se->width : 1.0) + 1.0;
        double ms = se->marker != HY_MARKER_NONE ? 0.5 * (se->marker_size > 0 ? se->marker_size : 4.0) : 0;
        const curve *c = panel_curve(p, s);
        double px = NAN, py = NAN, x, y;
        for (size_t i = 0, n = series_npts(p, s, c); i < n; i++) {
            if (!series_pt(p, se, c, i, &x, &y)) {
                px = NAN;
                continue;
            }
            if (se->style != HY_LINE_NONE && isfinite(px))
                sum += seg_in_rect(px, py, x, y, rx - hw, ry - hw, rw + 2 * hw, rh + 2 * hw);
            if (ms > 0 && x >= rx - ms && x <= rx + rw + ms && y >= ry - ms && y <= ry + rh + ms)
                sum += 2 * ms;
            px = x, py = y;
        }
    }
    sum = marks_overlap(p, sum, rx, ry, rw, rh);
    for (size_t t = 0; t < ax->ntexts; t++) {
        double b[4];
        if (text_box(p, t, b) && b[0] < rx + rw && b[0] + b[2] > rx && b[1] < ry + rh &&
            b[1] + b[3] > ry)
            sum += b[2];
    }
    return sum;
}

static double overlap(const panel *p, double rx, double ry, double rw, double rh)
{
    return overlap_bounded(p, rx, ry, rw, rh, INFINITY);
}

/* Size of the panel's legend box (0 x 0 when it has none) and its row height. */
static void legend_size(const panel *p, double *bw, double *bh, double *rowh)
{
    const hy_axes *ax = p->ax;
    double maxw = 0.0;
    size_t rows = 0;
    *rowh = 1.25 * p->fs;
    for (size_t s = 0; s < ax->nseries; s++) {
        hy_markup_box b;
        if (!ax->series[s].label)
            continue;
        hy_markup_text(p->cv, ax->series[s].label, p->fs, 0, 0, 0, 0, hy_palette[0], &b);
        maxw = b.width > maxw ? b.width : maxw;
        *rowh = b.ascent + b.descent + 1.0 > *rowh ? b.ascent + b.descent + 1.0 : *rowh;
        rows++;
    }
    if (!rows || ax->legend == HY_LEGEND_NONE) {
        *bw = *bh = 0.0;
        return;
    }
    *bw = 2 * LEGEND_PAD + LEGEND_SAMPLE + 5.0 + maxw;
    *bh = 2 * LEGEND_PAD + (double)rows * *rowh - 0.25 * p->fs;
}

/* The inside position for a "best" legend that covers nothing, trying the
 * corners first, then the middles of the sides, then a 5 x 5 grid; returns 0
 * (and the least covered candidate) when every one covers something. */
static int legend_free_spot(const panel *p, double bw, double bh, double *x, double *y)
{
    const double inset = 5.0;
    double left = p->x0 + inset, right = p->x0 + p->w - inset - bw;
    double top = p->y0 + inset, bottom = p->y0 + p->h - inset - bh;
    static const double order[][2] = {{1, 0}, {0, 0}, {1, 1}, {0, 1}, {0.5, 0}, {0.5, 1}, {1, 0.5}, {0, 0.5}};
    double cand[8 + 25][2], best = INFINITY;
    int nc = 0;
    if (right < left || bottom < top) {
        *x = left, *y = top;
        return 0;
    }
    for (int i = 0; i < 8; i++, nc++)
        cand[nc][0] = order[i][0], cand[nc][1] = order[i][1];
    for (int i = 0; i < 5; i++)
        for (int j = 0; j < 5; j++, nc++)
            cand[nc][0] = 0.125 + 0.1875 * j, cand[nc][1] = 0.125 + 0.1875 * i;
    for (int c = 0; c < nc; c++) {
        double cx = left + cand[c][0] * (right - left), cy = top + cand[c][1] * (bottom - top);
        double o = overlap(p, cx - 2, cy - 2, bw + 4, bh + 4);
        if (o < best)
            best = o, *x = cx, *y = cy;
        if (o == 0.0)
            return 1;
    }
    return 0;
}

/* Top-left corner of the panel's bw x bh legend box. */
static void legend_place(const panel *p, double bw, double bh, double *x, double *y)
{
    const double inset = 5.0;
    double left = p->x0 + inset, right = p->x0 + p->w - inset - bw;
    double top = p->y0 + inset, bottom = p->y0 + p->h - inset - bh;
    if (p->legend_outside) {
        *x = p->x0 + p->w + LEGEND_GAP;
        *y = p->y0;
        return;
    }
    switch (p->ax->legend) {
    case HY_LEGEND_TOP_LEFT: *x = left, *y = top; break;
    case HY_LEGEND_BOTTOM_RIGHT: *x = right, *y = bottom; break;
    case HY_LEGEND_BOTTOM_LEFT: *x = left, *y = bottom; break;
    case HY_LEGEND_BEST: legend_free_spot(p, bw, bh, x, y); break;
    default: *x = right, *y = top; break;
    }
}

static int fixed_legend_box(const panel *p, double b[4])
{
    double rowh;
    legend_size(p, &b[2], &b[3], &rowh);
    if (b[2] <= 0.0 || (p->ax->legend == HY_LEGEND_BEST && !p->legend_outside))
        return 0;
    legend_place(p, b[2], b[3], &b[0], &b[1]);
    return 1;
}

static void draw_legend(const panel *p)
{
    const hy_axes *ax = p->ax;
    const hy_canvas *cv = p->cv;
    double bw, bh, rowh, x, y;
    legend_size(p, &bw, &bh, &rowh);
    if (bw <= 0.0)
        return;
    legend_place(p, bw, bh, &x, &y);
    cv->ops->fill_rect(cv->ctx, x, y, bw, bh, p->th->bg, 1.0);
    hy_pen frame = {p->th->legend, 1.0, 0.5 * p->th->line, NULL, 0, 0, 1};
    cv->ops->begin_path(cv->ctx);
    cv->ops->move_to(cv->ctx, x, y);
    cv->ops->line_to(cv->ctx, x + bw, y);
    cv->ops->line_to(cv->ctx, x + bw, y + bh);
    cv->ops->line_to(cv->ctx, x, y + bh);
    cv->ops->line_to(cv->ctx, x, y);
    cv->ops->stroke(cv->ctx, &frame);
    double row_y = y + LEGEND_PAD + 0.5 * rowh - 0.125 * p->fs;
    for (size_t s = 0; s < ax->nseries; s++) {
        const hy_series *se = &ax->series[s];
        if (!se->label)
            continue;
        double dash[4];
        hy_pen pen = series_pen(p->th, se, dash);
        double x0 = x + LEGEND_PAD;
        if (se->style != HY_LINE_NONE)
            line(cv, x0, row_y, x0 + LEGEND_SAMPLE, row_y, &pen);
        if (se->marker != HY_MARKER_NONE)
            draw_marker(cv, p->th, se->marker, x0 + 0.5 * LEGEND_SAMPLE, row_y,
                        se->marker_size > 0 ? se->marker_size : 4.0, pen.colour, se->marker_filled);
        hy_markup_text(cv, se->label, p->fs, 1, 0, x0 + LEGEND_SAMPLE + 5.0, row_y + 0.36 * p->fs,
                       p->th->fg, NULL);
        row_y += rowh;
    }
}

/* ---- zoomed inset ---- */

static int rects_meet(const double *a, const double *b)
{
    return a[0] < b[0] + b[2] && a[0] + a[2] > b[0] && a[1] < b[1] + b[3] && a[1] + a[3] > b[1];
}

/* The zoomed region on the main axes, as a rectangle x y w h (points). */
static void zoom_rect(const panel *p, double r[4])
{
    double x0 = map_x(p, p->ax->zoom_x.lo), x1 = map_x(p, p->ax->zoom_x.hi);
    double y0 = map_y(p, p->ax->zoom_y.hi), y1 = map_y(p, p->ax->zoom_y.lo);
    r[0] = x0, r[1] = y0, r[2] = x1 - x0, r[3] = y1 - y0;
}

static int fixed_legend_box(const panel *p, double b[4]);

/* Whether the segment (x0, y0)-(x1, y1) meets the rectangle [lo, hi] (x and
 * y), clipped parametrically (Liang-Barsky). */
static int seg_meets(double x0, double y0, double x1, double y1, const double lo[2], const double hi[2])
{
    double t0 = 0.0, t1 = 1.0, d[2] = {x1 - x0, y1 - y0}, o[2] = {x0, y0};
    for (int k = 0; k < 2; k++) {
        double e[2] = {lo[k] - o[k], hi[k] - o[k]};   /* from the start to each side */
        if (d[k] == 0.0) {
            if (e[0] > 0.0 || e[1] < 0.0)
                return 0;
            continue;
        }
        double a = e[0] / d[k], b = e[1] / d[k];
        if (a > b) {
            double t = a;
            a = b, b = t;
        }
        t0 = fmax(t0, a), t1 = fmin(t1, b);
        if (t0 > t1)
            return 0;
    }
    return 1;
}

int hy_axes_zoom_shows_data(const hy_axes *ax)
{
    int xl = ax->x.log, yl = ax->y.log;
    if (!usable(ax->zoom_x.lo, xl) || !usable(ax->zoom_y.lo, yl))
        return 0;
    double lo[2] = {tr(ax->zoom_x.lo, xl), tr(ax->zoom_y.lo, yl)}, hi[2] = {tr(ax->zoom_x.hi, xl), tr(ax->zoom_y.hi, yl)};
    for (size_t m = 0; m < ax->nmarks; m++) {
        const hy_mark *k = &ax->marks[m];
        if (usable(k->x, xl) && usable(k->y, yl) && seg_meets(tr(k->x, xl), tr(k->y, yl), tr(k->x, xl), tr(k->y, yl), lo, hi))
            return 1;
    }
    for (size_t s = 0; s < ax->nseries; s++) {
        const hy_series *se = &ax->series[s];
        int line = se->style != HY_LINE_NONE;
        if (!line && se->marker == HY_MARKER_NONE)
            continue;
        int prev = 0;   /* the previous point is usable: a line joins it */
        double px = 0.0, py = 0.0;
        for (size_t i = 0; i < se->n; i++) {
            if (!usable(se->x[i], xl) || !usable(se->y[i], yl)) {
                prev = 0;
                continue;
            }
            double x = tr(se->x[i], xl), y = tr(se->y[i], yl);
            if (line && prev ? seg_meets(px, py, x, y, lo, hi) : seg_meets(x, y, x, y, lo, hi))
                return 1;
            px = x, py = y, prev = 1;
        }
    }
    return 0;
}

/* Lays out the panel's inset (if its axes ask for one): its own panel with
 * the zoom ranges and 80 % text, in a cell of 42 % x 45 % of the frame, at
 * the spot (corners first, then a grid) that covers the least data, text,
 * fixed legend and zoomed region.  Returns a layout error of the inset. */
static int place_inset(panel *p, hy_error *err)
{
    const hy_axes *ax = p->ax;
    p->has_inset = 0;
    if (!p->inset_panel || !(ax->zoom_x.lo < ax->zoom_x.hi) || !(ax->zoom_y.lo < ax->zoom_y.hi) ||
        !usable(ax->zoom_x.lo, p->xlog) || !usable(ax->zoom_y.lo, p->ylog) || !isfinite(ax->zoom_x.hi) ||
        !isfinite(ax->zoom_y.hi) || !hy_axes_zoom_shows_data(ax))
        return HY_OK;   /* an inset of an empty window would show nothing: left out */
    panel *q = p->inset_panel;
    curves *qc = q->cache;
    double qtol = q->tol, qdense = q->dense, qvtol = q->vtol;
    memset(q, 0, sizeof *q);
    q->cache = qc, q->tol = qtol, q->dense = qdense, q->vtol = qvtol;
    p->inset_ax = *ax;
    hy_axes *qa = &p->inset_ax;
    qa->xlabel = qa->ylabel = qa->title = NULL;
    qa->texts = NULL, qa->ntexts = 0;
    qa->legend = HY_LEGEND_NONE;
    qa->zoom_x.lo = qa->zoom_x.hi = 0;
    q->ax = qa, q->cv = q->dv = p->cv, q->th = p->th, q->fs = 0.8 * p->fs;
    q->xlog = p->xlog, q->ylog = p->ylog;
    q->xlo = ax->zoom_x.lo, q->xhi = ax->zoom_x.hi, q->ylo = ax->zoom_y.lo, q->yhi = ax->zoom_y.hi;
    q->cw = 0.42 * p->w, q->ch = 0.45 * p->h;
    int st = panel_layout(q, err);
    if (st) {
        hy_error_prefix(err, "zoomed inset");
        return st;
    }
    const double inset = 4.0;
    double zr[4], lg[4];
    zoom_rect(p, zr);
    /* an inset that enlarges its window less than HY_INSET_MIN_ZOOM times
       either way (a minor loop followed as it grows) only covers the data */
    double qw = q->cw - q->ml - q->mr, qh = q->ch - q->mt - q->mb;
    if (!(qw > HY_INSET_MIN_ZOOM * zr[2] || qh > HY_INSET_MIN_ZOOM * zr[3]))
        return HY_OK;
    int has_lg = fixed_legend_box(p, lg);
    double best = INFINITY, bx = p->x0 + inset, by = p->y0 + inset;
    double spanx = p->w - 2 * inset - q->cw, spany = p->h - 2 * inset - q->ch;
    static const double order[][2] = {{0, 0}, {1, 0}, {0, 1}, {1, 1}, {0.5, 0}, {0.5, 1}, {0, 0.5}, {1, 0.5}};
    for (int c = 0; c < 8 + 25 && best > 0.0; c++) {
        double fx = c < 8 ? order[c][0] : 0.125 + 0.1875 * ((c - 8) % 5);
        double fy = c < 8 ? order[c][1] : 0.125 + 0.1875 * ((c - 8) / 5);
        double cell[4] = {p->x0 + inset + fx * spanx, p->y0 + inset + fy * spany, q->cw, q->ch};
        double o = overlap(p, cell[0], cell[1], cell[2], cell[3]);
        if (rects_meet(cell, zr))
            o += 1e6;
        if (has_lg && rects_meet(cell, lg))
            o += 1e6;
        if (o < best)
            best = o, bx = cell[0], by = cell[1];
    }
    q->cx = bx, q->cy = by;
    if ((st = panel_frame(q, err))) {
        hy_error_prefix(err, "zoomed inset");
        return st;
    }
    p->has_inset = 1;
    p->inset[0] = bx, p->inset[1] = by, p->inset[2] = q->cw, p->inset[3] = q->ch;
    return HY_OK;
}

static void rect_path(const hy_canvas *cv, const double r[4], const hy_pen *pen)
{
    cv->ops->begin_path(cv->ctx);
    cv->ops->move_to(cv->ctx, r[0], r[1]);
    cv->ops->line_to(cv->ctx, r[0] + r[2], r[1]);
    cv->ops->line_to(cv->ctx, r[0] + r[2], r[1] + r[3]);
    cv->ops->line_to(cv->ctx, r[0], r[1] + r[3]);
    cv->ops->line_to(cv->ctx, r[0], r[1]);
    cv->ops->stroke(cv->ctx, pen);
}

/* The zoomed region outlined on the main axes, then the inset over a white cell. */
static void draw_inset(const panel *p)
{
    if (!p->has_inset)
        return;
    const panel *q = p->inset_panel;
    const hy_canvas *cv = p->cv;
    hy_pen grey = {p->th->inset, 1.0, 0.5 * p->th->line, NULL, 0, 0, 1};
    double zr[4];
    zoom_rect(p, zr);
    cv->ops->clip(cv->ctx, p->x0, p->y0, p->w, p->h);
    rect_path(cv, zr, &grey);
    cv->ops->fill_rect(cv->ctx, p->inset[0], p->inset[1], p->inset[2], p->inset[3], p->th->bg, 1.0);
    cv->ops->unclip(cv->ctx);
    cv->ops->clip(cv->ctx, q->x0, q->y0, q->w, q->h);
    for (size_t s = 0; s < q->ax->nseries; s++)
        draw_series(q, s);
    for (size_t s = 0; s < q->ax->nseries; s++)
        draw_series_markers(q, &q->ax->series[s]);
    cv->ops->unclip(cv->ctx);
    draw_marks(q);
    draw_frame_ticks(q);
}

static void draw_panel_data(const panel *p)
{
    const hy_canvas *dv = p->dv;
    draw_band_grid(p);
    dv->ops->clip(dv->ctx, p->x0, p->y0, p->w, p->h);
    for (size_t s = 0; s < p->ax->nseries; s++)
        draw_series(p, s);
    for (size_t s = 0; s < p->ax->nseries; s++)
        draw_series_markers(p, &p->ax->series[s]);
    dv->ops->unclip(dv->ctx);
    draw_marks(p);
}

static void draw_panel_overlay(const panel *p)
{
    draw_inset(p);
    draw_texts(p);
    draw_frame_ticks(p);
    draw_labels(p);
    draw_legend(p);
}

static double maxd(double a, double b) { return a > b ? a : b; }

/* Lays out every panel alone, then gives panels in a column the same left and
 * right margins and panels in a row the same top and bottom, so frames align. */
/* Gives panels in a column the same left and right margins and panels in a
 * row the same top and bottom, then places every frame. */
static int align_frames(panel *ps, int rows, int cols, hy_error *err)
{
    for (int i = 0; i < rows * cols; i++) {
        panel *p = &ps[i];
        int r = i / cols, c = i % cols;
        for (int k = 0; k < rows; k++)
            p->ml = maxd(p->ml, ps[k * cols + c].ml), p->mr = maxd(p->mr, ps[k * cols + c].mr);
        for (int k = 0; k < cols; k++)
            p->mt = maxd(p->mt, ps[r * cols + k].mt), p->mb = maxd(p->mb, ps[r * cols + k].mb);
    }
    for (int i = 0; i < rows * cols; i++) {
        int st = panel_frame(&ps[i], err);
        if (st) {
            if (rows * cols > 1)
                hy_error_prefix(err, "panel %d", i + 1);
            return st;
        }
    }
    return HY_OK;
}

/* Lays out every panel alone, aligns the frames, then moves each "best"
 * legend that finds no free spot inside its frame to the right of it (the
 * frame narrows to make room) and places the annotations. */
static int layout_grid(panel *ps, int rows, int cols, hy_error *err)
{
    for (int i = 0; i < rows * cols; i++) {
        int st = axis_range(ps[i].ax, 0, &ps[i].xlo, &ps[i].xhi, err);
        if (!st)
            st = axis_range(ps[i].ax, 1, &ps[i].ylo, &ps[i].yhi, err);
        if (!st)
            st = panel_layout(&ps[i], err);
        if (st) {
            if (rows * cols > 1)
                hy_error_prefix(err, "panel %d", i + 1);
            return st;
        }
    }
    int st = align_frames(ps, rows, cols, err), moved = 0;
    for (int i = 0; !st && i < rows * cols; i++) {
        panel *p = &ps[i];
        double bw, bh, rowh, x, y;
        legend_size(p, &bw, &bh, &rowh);
        if (bw <= 0.0 || p->ax->legend != HY_LEGEND_BEST)
            continue;
        if ((st = place_inset(p, err)))
            break;
        if ((st = place_texts(p, err)))
            break;
        if (legend_free_spot(p, bw, bh, &x, &y))
            continue;
        /* outside only if the frame keeps most of its width; else the least covering spot inside */
        double extra = LEGEND_GAP + bw + OUTER - p->mr;
        if (extra > 0.0 && p->w - extra < maxd(0.55 * p->w, 8.0 * p->fs))
            continue;
        p->legend_outside = 1;
        p->mr = maxd(p->mr, LEGEND_GAP + bw + OUTER);
        moved = 1;
    }
    if (!st && moved)
        st = align_frames(ps, rows, cols, err);
    for (int i = 0; !st && i < rows * cols; i++) {
        st = place_inset(&ps[i], err);
        if (!st)
            st = place_texts(&ps[i], err);
    }
    return st;
}

static int draw_layers(const hy_figure *f, const hy_canvas *data, const hy_canvas *cv, hy_panel_map *maps,
                       size_t nmaps, int vector, hy_error *err);

/* Every panel and its inset panel get their curve cache and tolerances
 * (hy_plot.h): HY_CURVE_TOL_PX pixels at the figure's dpi, in points, for
 * lines denser than HY_CURVE_DENSE_PX points per pixel of their length, and
 * for every stroke of a vector output. */
static void panels_init(panel *ps, curves *cc, const hy_figure *f, int rows, int cols, int vector)
{
    double W, H, dpi;
    hy__figure_size(f, &W, &H, &dpi);
    for (int i = 0; i < 2 * rows * cols; i++) {
        ps[i].cache = &cc[i];
        ps[i].tol = f->full_resolution ? 0.0 : HY_CURVE_TOL_PX * 72.0 / dpi;
        ps[i].dense = HY_CURVE_DENSE_PX * dpi / 72.0;
        ps[i].vtol = vector ? ps[i].tol : 0.0;
        ps[i].cancel = f->cancel;
    }
}

/* Frees the panels and their curves (ps may be NULL). */
static void panels_free(panel *ps, curves *cc, int n)
{
    for (int i = 0; ps && cc && i < 2 * n; i++)
        curves_free(&cc[i], i < n ? ps[i].ax->nseries : ps[i - n].ax->nseries);
    free(cc);
    free(ps);
}

int hy_figure_draw_layers(const hy_figure *f, const hy_canvas *data, const hy_canvas *cv,
                          hy_error *err)
{
    return draw_layers(f, data, cv, NULL, 0, 0, err);
}

int hy_figure_draw_mapped(const hy_figure *f, const hy_canvas *cv, hy_panel_map *maps, size_t nmaps, hy_error *err)
{
    return draw_layers(f, cv, cv, maps, nmaps, 0, err);
}

int hy__figure_draw_out(const hy_figure *f, const hy_canvas *cv, int vector, hy_panel_map *maps, size_t nmaps,
                        hy_error *err)
{
    return draw_layers(f, cv, cv, maps, nmaps, vector, err);
}

static int draw_layers(const hy_figure *f, const hy_canvas *data, const hy_canvas *cv, hy_panel_map *maps,
                       size_t nmaps, int vector, hy_error *err)
{
    double W, H, dpi;
    hy__figure_size(f, &W, &H, &dpi);
    int rows = f->nrows > 0 ? f->nrows : 1, cols = f->ncols > 0 ? f->ncols : 1;
    double fs = f->font_size > 0 ? f->font_size : 9.0;
    if (!f->axes)
        return hy_error_set(err, HY_EINVAL, "figure has no panels (axes is NULL)");
    if (!isfinite(W) || !isfinite(H) || W > 1e5 || H > 1e5 || rows * cols > 64 || !(fs < 1000))
        return hy_error_set(err, HY_EINVAL, "figure size %g x %g pt, font %g pt or %d x %d panels "
                            "is not usable", W, H, fs, rows, cols);
    size_t ntexts = 0;
    for (int i = 0; i < rows * cols; i++)
        ntexts += f->axes[i].ntexts;
    panel *ps = calloc((size_t)(2 * rows * cols), sizeof *ps);   /* then one inset panel each */
    text_place *tp = calloc(ntexts + 1, sizeof *tp);
    curves *cc = calloc((size_t)(2 * rows * cols), sizeof *cc);
    if (!ps || !tp || !cc) {
        free(ps);
        free(tp);
        free(cc);
        return hy_error_set(err, HY_ENOMEM, "out of memory laying out %d panels", rows * cols);
    }
    panels_init(ps, cc, f, rows, cols, vector);
    for (size_t i = 0, k = 0; i < (size_t)(rows * cols); k += f->axes[i].ntexts, i++) {
        panel *p = &ps[i];
        p->tplace = tp + k;
        p->inset_panel = &ps[(size_t)(rows * cols) + i];
        p->ax = &f->axes[i], p->cv = cv, p->dv = data ? data : cv, p->th = theme_of(f), p->fs = fs * p->th->text;
        p->xlog = p->ax->x.log, p->ylog = p->ax->y.log;
        p->cx = (i % cols) * W / cols, p->cy = (i / cols) * H / rows;
        p->cw = W / cols, p->ch = H / rows;
    }
    int st = layout_grid(ps, rows, cols, err);
    if (!st) {
        const hy_canvas *dv = data ? data : cv;
        dv->ops->fill_rect(dv->ctx, 0, 0, W, H, theme_of(f)->bg, 1.0);
        for (int i = 0; i < rows * cols; i++) {
            draw_panel_data(&ps[i]);
            if (dv == cv)
                draw_panel_overlay(&ps[i]);
        }
        for (int i = 0; dv != cv && i < rows * cols; i++)
            draw_panel_overlay(&ps[i]);
        for (size_t i = 0; i < nmaps && i < (size_t)(rows * cols); i++) {
            const panel *p = &ps[i];
            maps[i] = (hy_panel_map){p->x0, p->y0, p->w, p->h, p->xlo, p->xhi, p->ylo, p->yhi, p->xlog, p->ylog};
        }
    }
    panels_free(ps, cc, rows * cols);
    free(tp);
    return st;
}

int hy_figure_draw(const hy_figure *f, const hy_canvas *cv, hy_error *err)
{
    return draw_layers(f, cv, cv, NULL, 0, 0, err);
}

/* The spot for a bw x bh box in p's frame (candidates as the legend's) that
 * covers the least data and never the legend box lg (w = 0: none). */
static void free_box(const panel *p, const double lg[4], double bw, double bh, double *x, double *y)
{
    const double inset = 5.0;
    double left = p->x0 + inset, right = p->x0 + p->w - inset - bw;
    double top = p->y0 + inset, bottom = p->y0 + p->h - inset - bh, best = INFINITY;
    static const double order[][2] = {{0, 0}, {1, 0}, {0, 1}, {1, 1}, {0.5, 0}, {0.5, 1}, {1, 0.5}, {0, 0.5}};
    *x = left, *y = top;
    for (int c = 0; c < 8 + 25 && right >= left && bottom >= top; c++) {
        double fx = c < 8 ? order[c][0] : 0.125 + 0.1875 * ((c - 8) % 5);
        double fy = c < 8 ? order[c][1] : 0.125 + 0.1875 * ((c - 8) / 5);
        double cx = left + fx * (right - left), cy = top + fy * (bottom - top);
        int hits_legend = lg[2] > 0 && cx < lg[0] + lg[2] && cx + bw > lg[0] && cy < lg[1] + lg[3] && cy + bh > lg[1];
        double o = overlap(p, cx - 2, cy - 2, bw + 4, bh + 4) + (hits_legend ? 1e9 : 0.0);
        if (o < best)
            best = o, *x = cx, *y = cy;
        if (o == 0.0)
            return;
    }
}

/* The layout of f on cv: panel index's frame into rect; with legend its
 * legend box (x, y, w, h; w = 0 without one) into legend; with box (w, h
 * given in box[2], box[3]) the free spot for such a box into box. */
static void text_hits(const panel *p, const double lg[4], double *hits, size_t n);

static int figure_layout(const hy_figure *f, const hy_canvas *cv, int index, double rect[4], double legend[4],
                         double box[4], double *hits, size_t nhits, hy_error *err)
{
    double W, H, dpi;
    hy__figure_size(f, &W, &H, &dpi);
    int rows = f->nrows > 0 ? f->nrows : 1, cols = f->ncols > 0 ? f->ncols : 1;
    double fs = f->font_size > 0 ? f->font_size : 9.0;
    if (!f->axes || index < 0 || index >= rows * cols || rows * cols > 64 || !(fs < 1000))
        return hy_error_set(err, HY_EINVAL, "no panel %d in a %d x %d figure", index, rows, cols);
    size_t ntexts = 0;
    for (int i = 0; i < rows * cols; i++)
        ntexts += f->axes[i].ntexts;
    panel *ps = calloc((size_t)(2 * rows * cols), sizeof *ps);
    text_place *tp = calloc(ntexts + 1, sizeof *tp);
    curves *cc = calloc((size_t)(2 * rows * cols), sizeof *cc);
    int st = HY_OK;
    if (!ps || !tp || !cc)
        st = hy_error_set(err, HY_ENOMEM, "out of memory laying out %d panels", rows * cols);
    else
        panels_init(ps, cc, f, rows, cols, 0);
    for (size_t i = 0, k = 0; !st && i < (size_t)(rows * cols); k += f->axes[i].ntexts, i++) {
        panel *p = &ps[i];
        p->tplace = tp + k;
        p->inset_panel = &ps[(size_t)(rows * cols) + i];
        p->ax = &f->axes[i], p->cv = p->dv = cv, p->th = theme_of(f), p->fs = fs * p->th->text;
        p->xlog = p->ax->x.log, p->ylog = p->ax->y.log;
        p->cx = (double)(i % (size_t)cols) * W / cols, p->cy = (double)(i / (size_t)cols) * H / rows;
        p->cw = W / cols, p->ch = H / rows;
    }
    if (!st)
        st = layout_grid(ps, rows, cols, err);
    if (!st)
        rect[0] = ps[index].x0, rect[1] = ps[index].y0, rect[2] = ps[index].w, rect[3] = ps[index].h;
    if (!st && legend) {
        double rowh;
        legend[0] = legend[1] = 0.0;
        legend_size(&ps[index], &legend[2], &legend[3], &rowh);
        if (legend[2] > 0.0)
            legend_place(&ps[index], legend[2], legend[3], &legend[0], &legend[1]);
        else
            legend[2] = legend[3] = 0.0;
    }
    if (!st && box)
        free_box(&ps[index], legend, box[2], box[3], &box[0], &box[1]);
    if (!st && hits)
        text_hits(&ps[index], legend, hits, nhits);
    panels_free(ps, cc, rows * cols);
    free(tp);
    return st;
}

int hy_figure_frame(const hy_figure *f, const hy_canvas *cv, int index, double rect[4], hy_error *err)
{
    return figure_layout(f, cv, index, rect, NULL, NULL, NULL, 0, err);
}

int hy_figure_free_box(const hy_figure *f, const hy_canvas *cv, int index, double box[4], hy_error *err)
{
    double rect[4], legend[4];
    return figure_layout(f, cv, index, rect, legend, box, NULL, 0, err);
}

/* What each placed annotation of p covers (see hy_figure_text_hits). */
static void text_hits(const panel *p, const double lg[4], double *hits, size_t n)
{
    for (size_t i = 0; i < n; i++) {
        const text_place *tp = &p->tplace[i];
        const double *b = tp->box;
        if (i >= p->ax->ntexts || !tp->ok) {
            hits[i] = NAN;
            continue;
        }
        /* overlap() counts the box itself among the annotations: take it off */
        hits[i] = overlap(p, b[0], b[1], b[2], b[3]) - b[2];
        if (lg[2] > 0 && lg[0] < b[0] + b[2] && lg[0] + lg[2] > b[0] && lg[1] < b[1] + b[3] && lg[1] + lg[3] > b[1])
            hits[i] += b[2];
        if (b[0] < p->x0 || b[1] < p->y0 || b[0] + b[2] > p->x0 + p->w || b[1] + b[3] > p->y0 + p->h)
            hits[i] = INFINITY;
    }
}

int hy_figure_text_hits(const hy_figure *f, const hy_canvas *cv, int index, double *hits, size_t n, hy_error *err)
{
    double rect[4], legend[4];
    return figure_layout(f, cv, index, rect, legend, NULL, hits, n, err);
}
