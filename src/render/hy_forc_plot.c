/* SPDX-License-Identifier: MIT */
/* hy_forc_plot.c: the FORC diagram (hy_forc_plot.h): heat map as one image,
 * contours by marching squares on the grid (segments, saddles resolved by
 * the cell's mean), a colour bar and axes, through cairo. */
#include "hy_forc_plot.h"

#include <cairo-pdf.h>
#include <cairo-svg.h>
#include <cairo.h>
#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "hy_plot.h"
#include "hy_plot_private.h"
#include "hy_ticks.h"

hy_forc_plot_opts hy_forc_plot_defaults(void)
{
    hy_forc_plot_opts o = {.vmax = 0, .nlevels = 11, .field_to_mt = 0, .rho_unit = "", .width = 400,
                           .height = 320, .dpi = 150};
    static const double lv[] = {0, 0.1, -0.1, 0.3, -0.3, 0.5, -0.5, 0.7, -0.7, 0.9, -0.9};
    memcpy(o.levels, lv, sizeof lv);
    return o;
}

double hy_forc_plot_max(const hy_forc_grid *g, double hc_min)
{
    double m = 0, dc = g->nc > 1 ? (g->hc1 - g->hc0) / (double)(g->nc - 1) : 0;
    for (size_t iu = 0; iu < g->nu; iu++)
        for (size_t ic = 0; ic < g->nc; ic++) {
            double r = g->rho[iu * g->nc + ic];
            if (isfinite(r) && g->hc0 + (double)ic * dc >= hc_min)
                m = fmax(m, fabs(r));
        }
    return m;
}

/* Diverging map: t in [-1, 1] -> blue (-1), white (0), red (+1), through
 * lighter tones (the "RdBu" idea, linear in each half). */
static void cmap(double t, double rgb[3])
{
    static const double neg[3] = {0.13, 0.40, 0.67}, pos[3] = {0.70, 0.09, 0.17};
    t = fmax(-1, fmin(1, t));
    const double *c = t < 0 ? neg : pos;
    double a = sqrt(fabs(t)); /* small values still tinted */
    for (int k = 0; k < 3; k++)
        rgb[k] = 1 + a * (c[k] - 1);
}

typedef struct frame {
    double x0, y0, w, h;         /* plot rectangle, points */
    double cx0, cx1, uy0, uy1;   /* data ranges in axis units */
} frame;

static double fx(const frame *f, double v) { return f->x0 + (v - f->cx0) / (f->cx1 - f->cx0) * f->w; }
static double fy(const frame *f, double v) { return f->y0 + f->h - (v - f->uy0) / (f->uy1 - f->uy0) * f->h; }

/* The heat map: one pixel per node (NaN transparent), pixel (ic, row) over
 * the node's cell [h − Δ/2, h + Δ/2], clipped to the frame. */
static int draw_map(cairo_t *cr, const hy_forc_grid *g, const frame *f, double k, double vmax, int smooth)
{
    int w = (int)g->nc, h = (int)g->nu;
    cairo_surface_t *img = cairo_image_surface_create(CAIRO_FORMAT_ARGB32, w, h);
    if (cairo_surface_status(img)) {
        cairo_surface_destroy(img);
        return HY_ENOMEM;
    }
    cairo_surface_flush(img);
    unsigned char *px = cairo_image_surface_get_data(img);
    int stride = cairo_image_surface_get_stride(img);
    for (int iu = 0; iu < h; iu++) {
        uint32_t *row = (uint32_t *)(void *)(px + (size_t)(h - 1 - iu) * (size_t)stride);
        for (int ic = 0; ic < w; ic++) {
            double r = g->rho[(size_t)iu * g->nc + (size_t)ic], c[3];
            if (!isfinite(r)) {
                row[ic] = 0;
                continue;
            }
            cmap(r / vmax, c);
            row[ic] = 0xff000000u | (uint32_t)lround(255 * c[0]) << 16 | (uint32_t)lround(255 * c[1]) << 8 |
                      (uint32_t)lround(255 * c[2]);
        }
    }
    cairo_surface_mark_dirty(img);
    double dc = (g->hc1 - g->hc0) / (double)(g->nc - 1), du = (g->hu1 - g->hu0) / (double)(g->nu - 1);
    double sx = k * dc * f->w / (f->cx1 - f->cx0), sy = k * du * f->h / (f->uy1 - f->uy0);
    cairo_save(cr);
    cairo_rectangle(cr, f->x0, f->y0, f->w, f->h);
    cairo_clip(cr);
    cairo_translate(cr, fx(f, k * (g->hc0 - 0.5 * dc)), fy(f, k * (g->hu0 + ((double)h - 0.5) * du)));
    cairo_scale(cr, sx, sy);
    cairo_set_source_surface(cr, img, 0, 0);
    cairo_pattern_set_filter(cairo_get_source(cr), smooth ? CAIRO_FILTER_BILINEAR : CAIRO_FILTER_NEAREST);
    cairo_paint(cr);
    cairo_restore(cr);
    cairo_surface_destroy(img);
    return HY_OK;
}

/* Marching squares for level L of v = ρ/vmax: segments added to the path. */
static void contour(cairo_t *cr, const hy_forc_grid *g, const frame *f, double k, double vmax, double L)
{
    static const signed char seg[16][4] = {
        {-1, -1, -1, -1}, {3, 0, -1, -1}, {0, 1, -1, -1}, {3, 1, -1, -1}, {1, 2, -1, -1}, {-2, -1, -1, -1},
        {0, 2, -1, -1},   {3, 2, -1, -1}, {2, 3, -1, -1}, {0, 2, -1, -1}, {-3, -1, -1, -1}, {1, 2, -1, -1},
        {1, 3, -1, -1},   {0, 1, -1, -1}, {3, 0, -1, -1}, {-1, -1, -1, -1}};
    double dc = (g->hc1 - g->hc0) / (double)(g->nc - 1), du = (g->hu1 - g->hu0) / (double)(g->nu - 1);
    for (size_t iu = 0; iu + 1 < g->nu; iu++)
        for (size_t ic = 0; ic + 1 < g->nc; ic++) {
            const double *r0 = g->rho + iu * g->nc + ic, *r1 = r0 + g->nc;
            double v[4] = {r0[0] / vmax, r0[1] / vmax, r1[1] / vmax, r1[0] / vmax};
            if (!(isfinite(v[0]) && isfinite(v[1]) && isfinite(v[2]) && isfinite(v[3])))
                continue;
            /* a cell below 1e-3 of the colour scale everywhere is white: a
             * zero contour there would trace rounding noise */
            if (fmax(fmax(fabs(v[0]), fabs(v[1])), fmax(fabs(v[2]), fabs(v[3]))) < 1e-3)
                continue;
            int c = (v[0] > L) | (v[1] > L) << 1 | (v[2] > L) << 2 | (v[3] > L) << 3;
            /* corners (x, y) in cell units: 0 (0,0) 1 (1,0) 2 (1,1) 3 (0,1); edge e from corner e to e+1 */
            static const double cx[4] = {0, 1, 1, 0}, cy[4] = {0, 0, 1, 1};
            double ex[4], ey[4];
            for (int e = 0; e < 4; e++) {
                int a = e, b = (e + 1) & 3;
                double t = (v[b] != v[a]) ? (L - v[a]) / (v[b] - v[a]) : 0.5;
                ex[e] = cx[a] + t * (cx[b] - cx[a]);
                ey[e] = cy[a] + t * (cy[b] - cy[a]);
            }
            signed char s[4];
            memcpy(s, seg[c], 4);
            if (s[0] < -1) { /* saddle: the mean decides which corners connect */
                int above = 0.25 * (v[0] + v[1] + v[2] + v[3]) > L;
                int cut_even = (s[0] == -2) != above; /* case 5 above: cut corners 1, 3 */
                static const signed char odd[4] = {0, 1, 2, 3}, even[4] = {3, 0, 1, 2};
                memcpy(s, cut_even ? even : odd, 4);
            }
            for (int q = 0; q < 4 && s[q] >= 0; q += 2) {
                double x0 = g->hc0 + ((double)ic + ex[s[q]]) * dc, y0 = g->hu0 + ((double)iu + ey[s[q]]) * du;
                double x1 = g->hc0 + ((double)ic + ex[s[q + 1]]) * dc, y1 = g->hu0 + ((double)iu + ey[s[q + 1]]) * du;
                cairo_move_to(cr, fx(f, k * x0), fy(f, k * y0));
                cairo_line_to(cr, fx(f, k * x1), fy(f, k * y1));
            }
        }
}

/* Text pieces: s, then sub-scripted when sub (smaller, lowered). */
typedef struct piece {
    const char *s;
    int sub;
} piece;

static double pieces_width(cairo_t *cr, const piece *p, int n, double size)
{
    double w = 0;
    for (int i = 0; i < n; i++) {
        cairo_text_extents_t te;
        cairo_set_font_size(cr, p[i].sub ? 0.7 * size : size);
        cairo_text_extents(cr, p[i].s, &te);
        w += te.x_advance;
    }
    return w;
}

/* Draws the pieces with the baseline at (x, y) centred on x (rotated a
 * quarter turn counter-clockwise when vertical: centred on y). */
static void draw_pieces(cairo_t *cr, const piece *p, int n, double size, double x, double y, int vertical)
{
    double w = pieces_width(cr, p, n, size);
    cairo_save(cr);
    cairo_translate(cr, x, y);
    if (vertical)
        cairo_rotate(cr, -M_PI / 2);
    double at = -0.5 * w;
    for (int i = 0; i < n; i++) {
        cairo_text_extents_t te;
        cairo_set_font_size(cr, p[i].sub ? 0.7 * size : size);
        cairo_move_to(cr, at, p[i].sub ? 0.25 * size : 0);
        cairo_show_text(cr, p[i].s);
        cairo_text_extents(cr, p[i].s, &te);
        at += te.x_advance;
    }
    cairo_restore(cr);
}

/* A tick label with the decimals the step needs (0.25: two), a true minus. */
static void label(char *buf, size_t n, double v, double step)
{
    if (fabs(v) < 1e-9 * step)
        v = 0;
    int d = 0;
    while (d < 12 && fabs(step * pow(10, d) - round(step * pow(10, d))) > 1e-6 * step * pow(10, d))
        d++;
    char tmp[24];
    snprintf(tmp, sizeof tmp, "%.*f", d, fmin(fabs(v), 1e15));
    snprintf(buf, n, "%s%s", v < 0 ? "−" : "", tmp);
}

/* Ticks and labels of one axis (x: bottom, else left) and its title. */
static void axis(cairo_t *cr, const frame *f, int x_axis, const piece *title, int nt, double size)
{
    double lo = x_axis ? f->cx0 : f->uy0, hi = x_axis ? f->cx1 : f->uy1;
    double step = hy_ticks_nice_step(lo, hi, x_axis ? 5 : 6);
    if (!(step > 0))
        return;
    cairo_set_font_size(cr, size);
    for (double v = ceil(lo / step - 1e-9) * step; v <= hi + 1e-9 * step; v += step) {
        char buf[40];
        label(buf, sizeof buf, v, step);
        cairo_text_extents_t te;
        cairo_text_extents(cr, buf, &te);
        if (x_axis) {
            double X = fx(f, v);
            cairo_move_to(cr, X, f->y0 + f->h);
            cairo_line_to(cr, X, f->y0 + f->h + 4);
            cairo_move_to(cr, X - 0.5 * te.x_advance, f->y0 + f->h + 6 + size);
        } else {
            double Y = fy(f, v);
            cairo_move_to(cr, f->x0, Y);
            cairo_line_to(cr, f->x0 - 4, Y);
            cairo_move_to(cr, f->x0 - 6 - te.x_advance, Y + 0.35 * size);
        }
        cairo_show_text(cr, buf);
        cairo_new_sub_path(cr);
    }
    cairo_set_line_width(cr, 0.6);
    cairo_stroke(cr);
    if (x_axis)
        draw_pieces(cr, title, nt, size * 1.1, f->x0 + 0.5 * f->w, f->y0 + f->h + 2.4 * size + 8, 0);
    else
        draw_pieces(cr, title, nt, size * 1.1, f->x0 - 3.3 * size - 4, f->y0 + 0.5 * f->h, 1);
}

/* The colour bar right of the frame, with ticks in units of 10^p. */
static void colour_bar(cairo_t *cr, const frame *f, double vmax, const char *unit, double size)
{
    double bx = f->x0 + f->w + 14, bw = 10, by = f->y0, bh = f->h;
    enum { N = 128 };
    for (int i = 0; i < N; i++) {
        double c[3], t = -1 + 2 * ((double)i + 0.5) / N;
        cmap(t, c);
        cairo_set_source_rgb(cr, c[0], c[1], c[2]);
        cairo_rectangle(cr, bx, by + bh * (1 - (double)(i + 1) / N), bw, bh / N + 0.02 * bh / N);
        cairo_fill(cr);
    }
    cairo_set_source_rgb(cr, 0, 0, 0);
    cairo_set_line_width(cr, 0.6);
    cairo_rectangle(cr, bx, by, bw, bh);
    cairo_stroke(cr);
    int p = vmax >= 1e-2 && vmax < 1e3 ? 0 : (int)floor(log10(vmax));
    double sc = pow(10, p), step = hy_ticks_nice_step(-vmax / sc, vmax / sc, 6);
    cairo_set_font_size(cr, size);
    for (double v = ceil(-vmax / sc / step - 1e-9) * step; step > 0 && v <= vmax / sc + 1e-9 * step; v += step) {
        char buf[40];
        label(buf, sizeof buf, v, step);
        double Y = by + bh * (1 - (v * sc / vmax + 1) / 2);
        cairo_move_to(cr, bx + bw, Y);
        cairo_line_to(cr, bx + bw + 3, Y);
        cairo_move_to(cr, bx + bw + 5, Y + 0.35 * size);
        cairo_show_text(cr, buf);
        cairo_new_sub_path(cr);
    }
    cairo_stroke(cr);
    /* title: ρ (10^p unit), vertical, right of the labels */
    char pw[64] = "", title[160];
    if (p) {
        static const char *const sup[] = {"⁰", "¹", "²", "³", "⁴", "⁵", "⁶", "⁷", "⁸", "⁹"};
        char digits[16];
        snprintf(digits, sizeof digits, "%d", abs(p));
        strcpy(pw, "10");
        if (p < 0)
            strcat(pw, "⁻");
        for (char *d = digits; *d; d++)
            strcat(pw, sup[*d - '0']);
        strcat(pw, " ");
    }
    if (unit && *unit)
        snprintf(title, sizeof title, "ρ (%s%s)", pw, unit);
    else if (p)
        snprintf(title, sizeof title, "ρ (×%.*s)", (int)strlen(pw) - 1, pw);
    else
        snprintf(title, sizeof title, "ρ");
    piece t[1] = {{title, 0}};
    draw_pieces(cr, t, 1, size * 1.1, bx + bw + 5 + 3.2 * size + 6, by + 0.5 * bh, 1);
}

static int draw(cairo_t *cr, const hy_forc_grid *g, const hy_forc_plot_opts *o, double vmax, int raster)
{
    double k = o->field_to_mt > 0 ? o->field_to_mt : 1, size = 9;
    cairo_set_source_rgb(cr, 1, 1, 1);
    cairo_paint(cr);
    cairo_select_font_face(cr, "DejaVu Sans", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
    cairo_font_options_t *fo = cairo_font_options_create();
    cairo_font_options_set_hint_metrics(fo, CAIRO_HINT_METRICS_OFF);
    cairo_font_options_set_hint_style(fo, CAIRO_HINT_STYLE_NONE);
    cairo_set_font_options(cr, fo);
    cairo_font_options_destroy(fo);
    frame f = {.x0 = 58, .y0 = 12, .cx0 = k * g->hc0, .cx1 = k * g->hc1, .uy0 = k * g->hu0, .uy1 = k * g->hu1};
    f.w = o->width - f.x0 - 78;
    f.h = o->height - f.y0 - 42;
    if (!(f.w > 20 && f.h > 20))
        return HY_EINVAL;
    int rc = draw_map(cr, g, &f, k, vmax, raster);
    if (rc)
        return rc;
    /* contours, clipped to the frame: 0 grey and wider, the others thin
     * black (segments per cell: a dash pattern would restart in each) */
    cairo_save(cr);
    cairo_rectangle(cr, f.x0, f.y0, f.w, f.h);
    cairo_clip(cr);
    cairo_set_line_cap(cr, CAIRO_LINE_CAP_ROUND);
    for (int i = 0; i < o->nlevels; i++) {
        contour(cr, g, &f, k, vmax, o->levels[i]);
        if (o->levels[i] == 0)
            cairo_set_source_rgba(cr, 0.35, 0.35, 0.35, 0.9);
        else
            cairo_set_source_rgba(cr, 0, 0, 0, 0.6);
        cairo_set_line_width(cr, o->levels[i] == 0 ? 0.6 : 0.4);
        cairo_stroke(cr);
    }
    cairo_restore(cr);
    cairo_set_source_rgb(cr, 0, 0, 0);
    cairo_set_line_width(cr, 0.8);
    cairo_rectangle(cr, f.x0, f.y0, f.w, f.h);
    cairo_stroke(cr);
    const char *u = o->field_to_mt > 0 ? " (mT)" : "";
    piece xt[5] = {{"μ", 0}, {"0", 1}, {"H", 0}, {"c", 1}, {u, 0}}, yt[5] = {{"μ", 0}, {"0", 1}, {"H", 0}, {"u", 1}, {u, 0}};
    axis(cr, &f, 1, o->field_to_mt > 0 ? xt : xt + 2, o->field_to_mt > 0 ? 5 : 2, size);
    axis(cr, &f, 0, o->field_to_mt > 0 ? yt : yt + 2, o->field_to_mt > 0 ? 5 : 2, size);
    colour_bar(cr, &f, vmax, o->rho_unit, size);
    return cairo_status(cr) ? HY_ENOMEM : HY_OK;
}

static cairo_status_t to_file(void *closure, const unsigned char *data, unsigned int len)
{
    return fwrite(data, 1, len, closure) == len ? CAIRO_STATUS_SUCCESS : CAIRO_STATUS_WRITE_ERROR;
}

/* cairo numbers SVG surfaces and images ("surface123", "image456") with
 * process-wide counters: renumber each kind by first appearance (after '"'
 * or '#': ids and references, never base64 text) so that the bytes depend
 * only on the figure, not on what the process drew before (the gallery). */
static int svg_renumbered(const char *b, size_t len, const hy_forc_plot_opts *o, FILE *fp)
{
    static const char *const keys[] = {"surface", "image"};
    long seen[2][64];
    int nseen[2] = {0, 0};
    size_t i = 0;
    const char *root = NULL;
    for (size_t k = 0; !root && k + 4 <= len; k++)
        if (!memcmp(b + k, "<svg", 4))
            root = b + k;
    const char *gt = root ? memchr(root, '>', len - (size_t)(root - b)) : NULL;
    if (gt && (o->title || o->desc)) { /* the root's start tag, then <title> and <desc> (hy_output.c's rule) */
        i = (size_t)(gt + 1 - b);
        if (fwrite(b, 1, i, fp) != i)
            return HY_EIO;
        const char *tag[2] = {"title", "desc"}, *text[2] = {o->title, o->desc};
        for (int q = 0; q < 2; q++)
            if (text[q] && (fprintf(fp, "\n<%s>", tag[q]) < 0 || hy__svg_escaped(fp, text[q]) ||
                            fprintf(fp, "</%s>", tag[q]) < 0))
                return HY_EIO;
    }
    while (i < len) {
        int k = -1;
        for (int q = 0; q < 2 && i > 0 && (b[i - 1] == '"' || b[i - 1] == '#'); q++) {
            size_t n = strlen(keys[q]);
            if (i + n < len && !memcmp(b + i, keys[q], n) && b[i + n] >= '0' && b[i + n] <= '9')
                k = q;
        }
        if (k < 0) {
            if (fputc(b[i++], fp) == EOF)
                return HY_EIO;
            continue;
        }
        size_t j = i + strlen(keys[k]);
        long v = 0;
        while (j < len && b[j] >= '0' && b[j] <= '9' && v < 100000000L)
            v = v * 10 + (b[j++] - '0');
        int id = 0;
        while (id < nseen[k] && seen[k][id] != v)
            id++;
        if (id == nseen[k] && nseen[k] < 64)
            seen[k][nseen[k]++] = v;
        if (fprintf(fp, "%s%d", keys[k], id + 1) < 0)
            return HY_EIO;
        i = j;
    }
    return HY_OK;
}

static int plot_write(const hy_forc_grid *g, const hy_forc_plot_opts *o, FILE *fp, int format, hy_error *err);

int hy_forc_plot_write(const hy_forc_grid *g, const hy_forc_plot_opts *o, FILE *fp, int format, hy_error *err)
{
    if (format != HY_FORMAT_SVG)
        return plot_write(g, o, fp, format, err);
    char *b = NULL;
    size_t len = 0;
    FILE *mem = open_memstream(&b, &len);
    if (!mem)
        return hy_error_set(err, HY_ENOMEM, "FORC figure: out of memory");
    int rc = plot_write(g, o, mem, format, err);
    if (fclose(mem) && !rc)
        rc = hy_error_set(err, HY_ENOMEM, "FORC figure: out of memory");
    if (!rc && svg_renumbered(b, len, o, fp))
        rc = hy_error_set(err, HY_EIO, "FORC figure: cannot write: %s", strerror(errno ? errno : EIO));
    free(b);
    return rc;
}

static int plot_write(const hy_forc_grid *g, const hy_forc_plot_opts *o, FILE *fp, int format, hy_error *err)
{
    if (!g->rho || g->nc < 2 || g->nu < 2 || g->nc > 100000 || g->nu > 100000 || !(g->hc1 > g->hc0) ||
        !(g->hu1 > g->hu0))
        return hy_error_set(err, HY_EINVAL, "FORC figure: the grid needs at least 2 x 2 nodes over ascending ranges");
    double vmax = o->vmax > 0 ? o->vmax : hy_forc_plot_max(g, -INFINITY);
    if (!(vmax > 0) || !isfinite(vmax))
        return hy_error_set(err, HY_EINVAL, "FORC figure: the distribution has no finite nonzero value");
    if (o->nlevels < 0 || o->nlevels > HY_FORC_PLOT_LEVELS || !(o->width >= 100 && o->width <= 5000) ||
        !(o->height >= 100 && o->height <= 5000) || !(o->dpi >= 10 && o->dpi <= 1200))
        return hy_error_set(err, HY_EINVAL, "FORC figure: bad size, resolution or contour levels");
    cairo_surface_t *s;
    if (format == HY_FORMAT_SVG)
        s = cairo_svg_surface_create_for_stream(to_file, fp, o->width, o->height);
    else if (format == HY_FORMAT_PDF)
        s = cairo_pdf_surface_create_for_stream(to_file, fp, o->width, o->height);
    else if (format == HY_FORMAT_PNG)
        s = cairo_image_surface_create(CAIRO_FORMAT_RGB24, (int)lround(o->width * o->dpi / 72),
                                       (int)lround(o->height * o->dpi / 72));
    else
        return hy_error_set(err, HY_EINVAL, "FORC figure: unknown format %d (svg, pdf or png)", format);
    if (format == HY_FORMAT_PDF)
        cairo_pdf_surface_set_metadata(s, CAIRO_PDF_METADATA_CREATE_DATE, "2000-01-01T00:00:00Z");
    cairo_t *cr = cairo_create(s);
    if (format == HY_FORMAT_PNG)
        cairo_scale(cr, o->dpi / 72, o->dpi / 72);
    int rc = draw(cr, g, o, vmax, format == HY_FORMAT_PNG);
    cairo_destroy(cr);
    if (!rc && format == HY_FORMAT_PNG)
        rc = cairo_surface_write_to_png_stream(s, to_file, fp) ? HY_EIO : HY_OK;
    cairo_surface_finish(s);
    if (!rc && cairo_surface_status(s))
        rc = HY_EIO;
    cairo_surface_destroy(s);
    if (rc == HY_EIO)
        return hy_error_set(err, rc, "FORC figure: cannot write: %s", strerror(errno ? errno : EIO));
    if (rc)
        return hy_error_set(err, rc, "FORC figure: cannot draw (size or memory)");
    return HY_OK;
}

void hy_forc_write_csv(const hy_forc_grid *g, FILE *f)
{
    fprintf(f, "hc,hu,rho\n");
    double dc = g->nc > 1 ? (g->hc1 - g->hc0) / (double)(g->nc - 1) : 0;
    double du = g->nu > 1 ? (g->hu1 - g->hu0) / (double)(g->nu - 1) : 0;
    for (size_t iu = 0; g->rho && iu < g->nu; iu++)
        for (size_t ic = 0; ic < g->nc; ic++) {
            double r = g->rho[iu * g->nc + ic];
            fprintf(f, "%.10g,%.10g,", g->hc0 + (double)ic * dc, g->hu0 + (double)iu * du);
            if (isfinite(r))
                fprintf(f, "%.17g\n", r);
            else
                fputs("nan\n", f);
        }
}
