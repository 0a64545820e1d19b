/* SPDX-License-Identifier: MIT */
/* test_layout.c: layout properties through a recording canvas: text inside the figure, series
 * clipped to the frame, "best" legend corner avoids the data, non-finite points break lines. */
#include <cairo.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "figures.h"
#include "hy_cairo.h"

#include "rcheck.h"

/* Forwards to cairo (for real text metrics) and records geometry. */
typedef struct rec {
    hy_canvas inner;
    double W, H;
    int text_outside;            /* text runs whose box leaves the figure */
    double minx, maxx, miny, maxy; /* extent of path points drawn while clipped */
    int clipped;
    double clip[4];
    int white_rects;
    double legend[4];            /* the last white rectangle after the background */
    int moves, lines, texts, clips;
} rec;

static void note_point(rec *r, double x, double y)
{
    if (!r->clipped)
        return;
    r->minx = fmin(r->minx, x), r->maxx = fmax(r->maxx, x);
    r->miny = fmin(r->miny, y), r->maxy = fmax(r->maxy, y);
}
static void r_begin(void *c) { ((rec *)c)->inner.ops->begin_path(((rec *)c)->inner.ctx); }
static void r_move(void *c, double x, double y)
{
    rec *r = c;
    note_point(r, x, y);
    r->moves += r->clipped;
    r->inner.ops->move_to(r->inner.ctx, x, y);
}
static void r_line(void *c, double x, double y)
{
    rec *r = c;
    note_point(r, x, y);
    r->lines += r->clipped;
    r->inner.ops->line_to(r->inner.ctx, x, y);
}
static void r_stroke(void *c, const hy_pen *p) { ((rec *)c)->inner.ops->stroke(((rec *)c)->inner.ctx, p); }
static void r_rect(void *c, double x, double y, double w, double h, hy_rgb col, double a)
{
    rec *r = c;
    if (col.r == 1 && col.g == 1 && col.b == 1 && r->white_rects++ > 0)
        r->legend[0] = x, r->legend[1] = y, r->legend[2] = w, r->legend[3] = h;
    r->inner.ops->fill_rect(r->inner.ctx, x, y, w, h, col, a);
}
static void r_marker(void *c, int s, double x, double y, double sz, const hy_pen *p, const hy_rgb *f)
{
    ((rec *)c)->inner.ops->marker(((rec *)c)->inner.ctx, s, x, y, sz, p, f);
}
static void r_text(void *c, double x, double y, const char *s, double sz, int it, int v, hy_rgb col)
{
    rec *r = c;
    hy_text_extents e;
    r->texts++;
    r->inner.ops->measure(r->inner.ctx, s, sz, it, &e);
    double x0, x1, y0, y1;   /* box of the run: advance x (0.78 / 0.24 em) */
    if (v)
        x0 = x - 0.78 * sz, x1 = x + 0.24 * sz, y0 = y - e.advance, y1 = y;
    else
        x0 = x, x1 = x + e.advance, y0 = y - 0.78 * sz, y1 = y + 0.24 * sz;
    if (x0 < -0.01 || y0 < -0.01 || x1 > r->W + 0.01 || y1 > r->H + 0.01) {
        r->text_outside++;
        printf("  text \"%s\" box [%.1f, %.1f] x [%.1f, %.1f] leaves %.0f x %.0f\n", s, x0, x1, y0, y1,
               r->W, r->H);
    }
    r->inner.ops->text(r->inner.ctx, x, y, s, sz, it, v, col);
}
static void r_measure(void *c, const char *s, double sz, int it, hy_text_extents *e)
{
    ((rec *)c)->inner.ops->measure(((rec *)c)->inner.ctx, s, sz, it, e);
}
static void r_clip(void *c, double x, double y, double w, double h)
{
    rec *r = c;
    r->clipped = 1;
    r->clips++;
    r->clip[0] = x, r->clip[1] = y, r->clip[2] = w, r->clip[3] = h;
    r->inner.ops->clip(r->inner.ctx, x, y, w, h);
}
static void r_unclip(void *c)
{
    ((rec *)c)->clipped = 0;
    ((rec *)c)->inner.ops->unclip(((rec *)c)->inner.ctx);
}
static const hy_canvas_ops rec_ops = {"recorder", r_begin, r_move, r_line, r_stroke, r_rect,
                                      r_marker, r_text, r_measure, r_clip, r_unclip};

/* A cancel hook (hy_cancel.h) that says stop from its stop_at-th question on
 * (0: never), counting them. */
typedef struct {
    int asked, stop_at;
} asker;

static int ask(void *ctx)
{
    asker *a = ctx;
    return ++a->asked >= a->stop_at && a->stop_at;
}

static int draw(const hy_figure *fig, rec *r)
{
    cairo_surface_t *img = cairo_image_surface_create(CAIRO_FORMAT_ARGB32, 10, 10);
    cairo_t *cr = cairo_create(img);
    hy_cairo_canvas cc;
    hy_error err;
    memset(r, 0, sizeof *r);
    r->inner = hy_canvas_cairo(&cc, cr, "DejaVu Sans");
    r->W = fig->width, r->H = fig->height;
    r->minx = r->miny = INFINITY;
    r->maxx = r->maxy = -INFINITY;
    hy_canvas cv = {&rec_ops, r};
    int st = hy_figure_draw(fig, &cv, &err);
    if (st)
        printf("  %s\n", err.msg);
    cairo_destroy(cr);
    cairo_surface_destroy(img);
    return st;
}

int main(void)
{
    rec r;
    /* Margins: no text of the test figures leaves the page, in several sizes. */
    for (int i = 0; i < FIG_COUNT; i++) {
        static const double scale[3] = {0.7, 1.0, 1.6};
        for (int k = 0; k < 3; k++) {
            hy_figure fig;
            const char *name = fig_build(i, &fig);
            fig.width *= scale[k], fig.height *= scale[k];
            CHECK(draw(&fig, &r) == 0, "%s x%.1f failed", name, scale[k]);
            CHECK(r.text_outside == 0, "%s x%.1f: %d text runs outside the figure", name, scale[k],
                  r.text_outside);
        }
    }

    /* Clipping: a series far outside explicit limits is cut at the frame (+2 line widths). */
    static double x[5] = {-1e9, 0.5, 1e12, 0.7, NAN}, y[5] = {0.5, 0.5, 1e12, 0.2, 0.3};
    hy_series s = {.x = x, .y = y, .n = 5};
    hy_axes ax = {.series = &s, .nseries = 1, .x = {.lo = 0, .hi = 1}, .y = {.lo = 0, .hi = 1}};
    hy_figure fig = {.width = 200, .height = 150, .axes = &ax, .nrows = 1, .ncols = 1};
    CHECK(draw(&fig, &r) == 0, "clip figure failed");
    CHECK(r.minx >= r.clip[0] - 2.01 && r.maxx <= r.clip[0] + r.clip[2] + 2.01 &&
          r.miny >= r.clip[1] - 2.01 && r.maxy <= r.clip[1] + r.clip[3] + 2.01,
          "path points [%g, %g] x [%g, %g] outside the frame %g %g %g %g", r.minx, r.maxx, r.miny,
          r.maxy, r.clip[0], r.clip[1], r.clip[2], r.clip[3]);
    CHECK(r.lines == 3 && r.moves == 2, "clipped polyline: %d lines %d moves (want 3 and 2)", r.lines, r.moves);

    /* Legend "best": data on the rising diagonal leaves the top-left corner free. */
    static double d[50];
    for (int i = 0; i < 50; i++)
        d[i] = i / 49.0;
    hy_series diag = {.x = d, .y = d, .n = 50, .label = "y = u"};
    hy_axes la = {.series = &diag, .nseries = 1, .legend = HY_LEGEND_BEST};
    fig.axes = &la;
    CHECK(draw(&fig, &r) == 0, "legend figure failed");
    CHECK(r.white_rects == 2, "no legend box drawn");
    CHECK(r.legend[0] < r.clip[0] + 0.5 * r.clip[2] && r.legend[1] < r.clip[1] + 0.5 * r.clip[3],
          "best legend at (%g, %g), want the top-left quarter", r.legend[0], r.legend[1]);
    static double fall[50];
    for (int i = 0; i < 50; i++)
        fall[i] = 1.0 - d[i];
    diag.y = fall;   /* falling diagonal: top-right is free */
    CHECK(draw(&fig, &r) == 0, "legend figure failed");
    CHECK(r.legend[0] > r.clip[0] + 0.5 * r.clip[2] && r.legend[1] < r.clip[1] + 0.5 * r.clip[3],
          "best legend at (%g, %g), want the top-right quarter", r.legend[0], r.legend[1]);

    /* Insets (issue 21 item 7): a window the line crosses between two points
       keeps its inset (a second white cell and two more clips: its cover and its curves); a window off
       the line, with nothing drawn in it, is left out, and so is one that
       would enlarge its window less than HY_INSET_MIN_ZOOM times. */
    {
        static double sx[2] = {0, 1};
        hy_series seg = {.x = sx, .y = sx, .n = 2};
        hy_axes za = {.series = &seg, .nseries = 1, .zoom_x = {.lo = 0.4, .hi = 0.6}, .zoom_y = {.lo = 0.4, .hi = 0.6}};
        fig.axes = &za;
        CHECK(hy_axes_zoom_shows_data(&za), "a window the line crosses counted empty");
        CHECK(draw(&fig, &r) == 0 && r.white_rects == 2 && r.clips == 3,
              "inset over the line: %d white cells, %d clips (want 2 and 3)", r.white_rects, r.clips);
        za.zoom_x = (hy_range){.lo = 0.1, .hi = 0.2}, za.zoom_y = (hy_range){.lo = 0.8, .hi = 0.9};
        CHECK(!hy_axes_zoom_shows_data(&za), "a window off the line counted as showing data");
        CHECK(draw(&fig, &r) == 0 && r.white_rects == 1 && r.clips == 1,
              "inset over an empty window: %d white cells, %d clips (want 1 and 1: left out)", r.white_rects,
              r.clips);
        za.zoom_x = (hy_range){.lo = 0.1, .hi = 0.9}, za.zoom_y = (hy_range){.lo = 0.1, .hi = 0.9};
        CHECK(hy_axes_zoom_shows_data(&za) && draw(&fig, &r) == 0 && r.white_rects == 1 && r.clips == 1,
              "an inset of 80 %% of the axes (enlarging less than %g times) was drawn: %d white cells",
              HY_INSET_MIN_ZOOM, r.white_rects);
        za.zoom_x = (hy_range){.lo = 0.1, .hi = 0.2}, za.zoom_y = (hy_range){.lo = 0.8, .hi = 0.9};
        static double mx[1] = {0.15}, my[1] = {0.85};
        hy_series dots = {.x = mx, .y = my, .n = 1, .style = HY_LINE_NONE, .marker = HY_MARKER_CIRCLE};
        hy_series both[2] = {seg, dots};
        za.series = both, za.nseries = 2;
        CHECK(hy_axes_zoom_shows_data(&za) && draw(&fig, &r) == 0 && r.white_rects == 2,
              "a marker in the window did not keep the inset");
        dots.marker = HY_MARKER_NONE;
        both[1] = dots;
        CHECK(!hy_axes_zoom_shows_data(&za), "a series drawn with neither line nor marker counted as data");
    }

    /* issue 10 item 4: on a y range of one ulp a segment is ~1e15 pt long, and
       legend placement converted len / 3 to int (undefined; a hang at -O3) */
    static double ux[2] = {0, 1}, uy[2] = {1, 1.0000000000000002};
    hy_series us = {.x = ux, .y = uy, .n = 2, .label = "one ulp"};
    hy_axes ua = {.series = &us, .nseries = 1, .legend = HY_LEGEND_BEST, .x = {.lo = 0, .hi = 1},
                  .y = {.lo = 1, .hi = 1.0000000000000002}};
    fig.axes = &ua;
    CHECK(draw(&fig, &r) == 0 && r.white_rects == 2, "a one-ulp y range with a legend failed");

    /* Invalid input is refused with a message, not drawn. */
    hy_axes bad = {.series = &diag, .nseries = 1, .x = {.lo = -1, .hi = 1, .log = 1}};
    fig.axes = &bad;
    CHECK(draw(&fig, &r) == HY_EINVAL, "log axis with a negative limit accepted");
    static double huge[2] = {-1.7e308, 1.7e308}, tiny[2] = {1e-300, 3e-300};
    hy_series hs = {.x = tiny, .y = huge, .n = 2};
    hy_axes ha = {.series = &hs, .nseries = 1};
    fig.axes = &ha;
    CHECK(draw(&fig, &r) == HY_EINVAL, "a y range of 3.4e308 accepted");
    hs.y = tiny;
    CHECK(draw(&fig, &r) == 0 && r.text_outside == 0, "a range of 2e-300 failed");
    fig.axes = &la;
    fig.width = 20;
    CHECK(draw(&fig, &r) == HY_EINVAL, "a 20 pt wide figure accepted");

    /* Layers: data (series, marks) and overlay (text, axes) go to separate canvases. */
    {
        hy_figure lf;
        fig_build(1, &lf);
        rec a, b;
        cairo_surface_t *img = cairo_image_surface_create(CAIRO_FORMAT_ARGB32, 10, 10);
        cairo_t *cra = cairo_create(img), *crb = cairo_create(img);
        hy_cairo_canvas ca, cb;
        memset(&a, 0, sizeof a);
        memset(&b, 0, sizeof b);
        a.inner = hy_canvas_cairo(&ca, cra, "DejaVu Sans");
        b.inner = hy_canvas_cairo(&cb, crb, "DejaVu Sans");
        a.W = b.W = lf.width, a.H = b.H = lf.height;
        hy_canvas ov = {&rec_ops, &a}, dv = {&rec_ops, &b};
        hy_error err;
        CHECK(hy_figure_draw_layers(&lf, &dv, &ov, &err) == 0, "layers failed");
        CHECK(b.texts == 0 && a.texts > 0, "text on the data layer (%d) or none on the overlay (%d)",
              b.texts, a.texts);
        CHECK(b.clips == 1 && a.clips == 0, "series clip on the wrong layer (data %d, overlay %d)",
              b.clips, a.clips);
        cairo_destroy(cra);
        cairo_destroy(crb);
        cairo_surface_destroy(img);
    }

    /* Cancellation (issue 36 item 2): the layout asks the figure's hook
       before each annotation it places; a hook that never stops changes
       nothing drawn, one that stops ends the drawing with HY_ECANCEL. */
    {
        enum { NT = 300 };
        static hy_text t[NT];
        static double sx[2] = {0, 1};
        for (int i = 0; i < NT; i++)
            t[i] = (hy_text){.x = 0.5, .y = 0.5, .text = "a label asking for one place"};
        hy_series seg = {.x = sx, .y = sx, .n = 2};
        hy_axes ta = {.series = &seg, .nseries = 1, .texts = t, .ntexts = NT};
        hy_figure tf = {.width = 300, .height = 200, .axes = &ta, .nrows = 1, .ncols = 1};
        rec a, b;
        CHECK(draw(&tf, &a) == 0, "300 labels failed");
        asker never = {0, 0};
        hy_cancel c = {ask, &never};
        tf.cancel = &c;
        CHECK(draw(&tf, &b) == 0, "300 labels with a hook that never stops failed");
        CHECK(never.asked == NT, "the hook was asked %d times for %d labels", never.asked, NT);
        CHECK(a.texts == b.texts && a.lines == b.lines && a.minx == b.minx && a.maxy == b.maxy,
              "a hook that never stops changed the drawing");
        asker third = {0, 3};
        c.ctx = &third;
        CHECK(draw(&tf, &b) == HY_ECANCEL && third.asked == 3, "stopped with asked %d (want HY_ECANCEL at 3)",
              third.asked);
    }

    cairo_debug_reset_static_data();
    return hy_test_finish("layout");
}
