/* SPDX-License-Identifier: MIT */
/* hy_cairo.c: cairo implementation of the hy_canvas operations. */
#include "hy_cairo.h"

#include <math.h>

static cairo_t *cr_of(void *ctx) { return ((hy_cairo_canvas *)ctx)->cr; }

static void c_begin_path(void *ctx) { cairo_new_path(cr_of(ctx)); }
static void c_move_to(void *ctx, double x, double y) { cairo_move_to(cr_of(ctx), x, y); }
static void c_line_to(void *ctx, double x, double y) { cairo_line_to(cr_of(ctx), x, y); }

#define MAX_DASH 16

/* cairo_set_dash (1.16) folds a zero-length "on" entry that is not the first
 * into its neighbouring gaps ({5, 2.4, 0, 2.4} becomes {5, 4.8}: dash-dot
 * draws as plain dashes in every backend), but keeps one in first place.  So
 * the pattern is rotated to start at its first inner zero "on" entry, with the
 * offset that keeps the phase; any further inner zero becomes 1e-6 pt (a dot
 * all the same, drawn by its round caps). */
static void set_dash(cairo_t *cr, const double *dash, int n)
{
    double d[MAX_DASH], total = 0.0, prefix = 0.0;
    int start = 0;
    if (!dash || n <= 0 || n > MAX_DASH || n % 2) {
        cairo_set_dash(cr, dash, dash ? n : 0, 0.0);
        return;
    }
    for (int i = 0; i < n; i++)
        total += dash[i];
    for (int i = 2; i < n && !start; i += 2)
        if (dash[i] == 0.0)
            start = i;
    for (int i = 0; i < start; i++)
        prefix += dash[i];
    for (int i = 0; i < n; i++) {
        d[i] = dash[(start + i) % n];
        if (i > 0 && i % 2 == 0 && d[i] == 0.0)
            d[i] = 1e-6;
    }
    cairo_set_dash(cr, d, n, start ? total - prefix : 0.0);
}

static void set_pen(cairo_t *cr, const hy_pen *pen)
{
    double a = pen->alpha > 0 ? pen->alpha : 1.0;
    cairo_set_source_rgba(cr, pen->colour.r, pen->colour.g, pen->colour.b, a);
    cairo_set_line_width(cr, pen->width);
    set_dash(cr, pen->dash, pen->dash ? pen->ndash : 0);
    cairo_set_line_cap(cr, pen->round_caps ? CAIRO_LINE_CAP_ROUND : CAIRO_LINE_CAP_BUTT);
    cairo_set_line_join(cr, pen->miter_joins ? CAIRO_LINE_JOIN_MITER : CAIRO_LINE_JOIN_ROUND);
}

static void c_stroke(void *ctx, const hy_pen *pen)
{
    cairo_t *cr = cr_of(ctx);
    set_pen(cr, pen);
    cairo_stroke(cr);
}

static void c_fill_rect(void *ctx, double x, double y, double w, double h, hy_rgb c, double alpha)
{
    cairo_t *cr = cr_of(ctx);
    cairo_new_path(cr);
    cairo_rectangle(cr, x, y, w, h);
    cairo_set_source_rgba(cr, c.r, c.g, c.b, alpha > 0 ? alpha : 1.0);
    cairo_fill(cr);
}

static void c_marker(void *ctx, int shape, double x, double y, double size, const hy_pen *pen,
                     const hy_rgb *fill)
{
    cairo_t *cr = cr_of(ctx);
    cairo_new_path(cr);
    if (shape == HY_SHAPE_SQUARE)
        cairo_rectangle(cr, x - 0.5 * size, y - 0.5 * size, size, size);
    else
        cairo_arc(cr, x, y, 0.5 * size, 0.0, 2.0 * M_PI);
    cairo_close_path(cr);
    if (fill) {
        cairo_set_source_rgb(cr, fill->r, fill->g, fill->b);
        cairo_fill_preserve(cr);
    }
    hy_pen solid = *pen;
    solid.dash = NULL;
    solid.ndash = 0;
    solid.miter_joins = shape == HY_SHAPE_SQUARE;
    set_pen(cr, &solid);
    cairo_stroke(cr);
}

static void select_font(hy_cairo_canvas *cc, double size, int italic)
{
    cairo_select_font_face(cc->cr, cc->font, italic ? CAIRO_FONT_SLANT_ITALIC : CAIRO_FONT_SLANT_NORMAL,
                           CAIRO_FONT_WEIGHT_NORMAL);
    cairo_set_font_size(cc->cr, size);
}

static void c_text(void *ctx, double x, double y, const char *utf8, double size, int italic,
                   int vertical, hy_rgb c)
{
    hy_cairo_canvas *cc = ctx;
    cairo_t *cr = cc->cr;
    cairo_save(cr);
    cairo_new_path(cr);
    select_font(cc, size, italic);
    cairo_translate(cr, x, y);
    if (vertical)
        cairo_rotate(cr, -0.5 * M_PI);
    cairo_move_to(cr, 0.0, 0.0);
    cairo_set_source_rgb(cr, c.r, c.g, c.b);
    cairo_show_text(cr, utf8);
    cairo_new_path(cr);
    cairo_restore(cr);
}

static void c_measure(void *ctx, const char *utf8, double size, int italic, hy_text_extents *ext)
{
    hy_cairo_canvas *cc = ctx;
    cairo_text_extents_t te;
    cairo_font_extents_t fe;
    cairo_save(cc->cr);
    select_font(cc, size, italic);
    cairo_text_extents(cc->cr, utf8, &te);
    cairo_font_extents(cc->cr, &fe);
    cairo_restore(cc->cr);
    ext->advance = te.x_advance;
    ext->ascent = fe.ascent;
    ext->descent = fe.descent;
    ext->ink_top = te.y_bearing;
    ext->ink_bottom = te.y_bearing + te.height;
}

static void c_clip(void *ctx, double x, double y, double w, double h)
{
    cairo_t *cr = cr_of(ctx);
    cairo_save(cr);
    cairo_new_path(cr);
    cairo_rectangle(cr, x, y, w, h);
    cairo_clip(cr);
}

static void c_unclip(void *ctx) { cairo_restore(cr_of(ctx)); }

static const hy_canvas_ops cairo_ops = {
    "cairo", c_begin_path, c_move_to, c_line_to, c_stroke, c_fill_rect,
    c_marker, c_text, c_measure, c_clip, c_unclip,
};

hy_canvas hy_canvas_cairo(hy_cairo_canvas *state, cairo_t *cr, const char *font)
{
    state->cr = cr;
    state->font = font ? font : "DejaVu Sans";
    cairo_font_options_t *fo = cairo_font_options_create();
    cairo_font_options_set_hint_metrics(fo, CAIRO_HINT_METRICS_OFF);
    cairo_font_options_set_hint_style(fo, CAIRO_HINT_STYLE_NONE);
    cairo_font_options_set_antialias(fo, CAIRO_ANTIALIAS_GRAY);
    cairo_set_font_options(cr, fo);
    cairo_font_options_destroy(fo);
    return (hy_canvas){&cairo_ops, state};
}
