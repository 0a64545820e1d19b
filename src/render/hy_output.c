/* SPDX-License-Identifier: MIT */
/* hy_output.c: figure output to SVG, PDF (cairo) and PNG (libpng), written
 * through the one output writer (hy_out: temporary + rename). */
#include <cairo-pdf.h>
#include <cairo-svg.h>
#include <cairo.h>
#include <errno.h>
#include <png.h>
#include <setjmp.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "hy_cairo.h"
#include "hy_out.h"
#include "hy_plot.h"
#include "hy_plot_private.h"

/* Sink for cairo's stream surfaces; remembers the first write error.  With
 * buf set it collects the bytes in memory instead (SVG, renumbered later). */
typedef struct sink {
    FILE *fp;
    int err;   /* errno of the first failure, 0 if none */
    unsigned char *buf;
    size_t len, cap;
    int buffered;
} sink;

static cairo_status_t sink_write(void *closure, const unsigned char *data, unsigned int len)
{
    sink *s = closure;
    if (s->err)
        return CAIRO_STATUS_WRITE_ERROR;
    if (s->buffered) {
        if (s->len + len > s->cap) {
            size_t cap = s->cap ? 2 * s->cap : 65536;
            while (cap < s->len + len)
                cap *= 2;
            unsigned char *nb = realloc(s->buf, cap);
            if (!nb) {
                s->err = ENOMEM;
                return CAIRO_STATUS_NO_MEMORY;
            }
            s->buf = nb;
            s->cap = cap;
        }
        memcpy(s->buf + s->len, data, len);
        s->len += len;
        return CAIRO_STATUS_SUCCESS;
    }
    if (fwrite(data, 1, len, s->fp) != len) {
        s->err = errno ? errno : EIO;
        return CAIRO_STATUS_WRITE_ERROR;
    }
    return CAIRO_STATUS_SUCCESS;
}

/* cairo numbers SVG surfaces ("surface123") with a process-wide counter;
 * renumber them by first appearance so the bytes depend only on the figure. */
int hy__svg_escaped(FILE *fp, const char *text)
{
    for (const char *c = text; *c; c++) {
        const char *e = *c == '<' ? "&lt;" : *c == '>' ? "&gt;" : *c == '&' ? "&amp;" : *c == '"' ? "&quot;"
                      : *c == '\'' ? "&apos;" : NULL;
        if (e ? fputs(e, fp) < 0 : fputc(*c, fp) == EOF)
            return errno ? errno : EIO;
    }
    return 0;
}

/* The root element's start tag as cairo wrote it, then the figure's <title>
 * and <desc> (its first children, where SVG 1.1 section 5.4 and screen
 * readers look); returns the offset after the tag, 0 when there is none. */
static size_t svg_head(sink *s, const hy_figure *f, int *rc)
{
    const unsigned char *root = NULL;
    for (size_t i = 0; !root && i + 4 <= s->len; i++)
        if (!memcmp(s->buf + i, "<svg", 4))
            root = s->buf + i;
    const unsigned char *gt = root ? memchr(root, '>', s->len - (size_t)(root - s->buf)) : NULL;
    *rc = 0;
    if (!gt || (!f->svg_title && !f->svg_desc))
        return 0;
    size_t n = (size_t)(gt + 1 - s->buf);
    if (fwrite(s->buf, 1, n, s->fp) != n)
        return *rc = errno ? errno : EIO, n;
    const char *tag[2] = {"title", "desc"}, *text[2] = {f->svg_title, f->svg_desc};
    for (int i = 0; i < 2 && !*rc; i++)
        if (text[i]) {
            if (fprintf(s->fp, "\n<%s>", tag[i]) < 0 || (*rc = hy__svg_escaped(s->fp, text[i])) ||
                fprintf(s->fp, "</%s>", tag[i]) < 0)
                *rc = *rc ? *rc : errno ? errno : EIO;
        }
    return n;
}

static int svg_flush_renumbered(sink *s, const hy_figure *f)
{
    static const char key[] = "surface";
    long seen[64];
    int nseen = 0, rc;
    size_t i = svg_head(s, f, &rc), k = sizeof key - 1;
    if (rc)
        return rc;
    while (i < s->len) {
        if (i + k < s->len && !memcmp(s->buf + i, key, k) && s->buf[i + k] >= '0' && s->buf[i + k] <= '9') {
            size_t j = i + k;
            long v = 0;
            while (j < s->len && s->buf[j] >= '0' && s->buf[j] <= '9' && v < 100000000L)
                v = v * 10 + (s->buf[j++] - '0');
            int id = 0;
            while (id < nseen && seen[id] != v)
                id++;
            if (id == nseen && nseen < 64)
                seen[nseen++] = v;
            if (fprintf(s->fp, "%s%d", key, id + 1) < 0)
                return errno ? errno : EIO;
            i = j;
            continue;
        }
        size_t start = i++;
        while (i < s->len && s->buf[i] != 's')
            i++;
        if (fwrite(s->buf + start, 1, i - start, s->fp) != i - start)
            return errno ? errno : EIO;
    }
    return 0;
}

static int draw_on(cairo_surface_t *surf, const hy_figure *f, double scale, int vector, hy_panel_map *maps,
                   size_t nmaps, hy_error *err)
{
    cairo_t *cr = cairo_create(surf);
    hy_cairo_canvas cc;
    hy_canvas cv = hy_canvas_cairo(&cc, cr, hy__figure_font(f));
    if (scale != 1.0)
        cairo_scale(cr, scale, scale);
    int st = hy__figure_draw_out(f, &cv, vector, maps, nmaps, err);
    cairo_status_t cs = cairo_status(cr);
    cairo_destroy(cr);
    if (!st && cs != CAIRO_STATUS_SUCCESS)
        st = hy_error_set(err, cs == CAIRO_STATUS_NO_MEMORY ? HY_ENOMEM : HY_EIO,
                          "cairo failed while drawing: %s", cairo_status_to_string(cs));
    return st;
}

/* The PDF creation date into buf: $SOURCE_DATE_EPOCH (seconds since
 * 1970-01-01 UTC, reproducible-builds.org) when it is a whole number up to
 * year 9999, else a fixed 2000-01-01T00:00:00Z: identical runs give identical
 * files either way. */
static void pdf_date(char *buf, size_t size)
{
    const char *s = getenv("SOURCE_DATE_EPOCH");
    char *end = NULL;
    errno = 0;
    long long v = s && *s >= '0' && *s <= '9' ? strtoll(s, &end, 10) : -1;
    time_t t = (time_t)v;
    struct tm tm;
    if (v < 0 || *end || errno || v > 253402300799LL || !gmtime_r(&t, &tm) ||
        !strftime(buf, size, "%Y-%m-%dT%H:%M:%SZ", &tm))
        snprintf(buf, size, "2000-01-01T00:00:00Z");
}

static int write_vector(const hy_figure *f, int format, sink *sk, hy_panel_map *maps, size_t nmaps, hy_error *err)
{
    double W, H, dpi;
    hy__figure_size(f, &W, &H, &dpi);
    cairo_surface_t *surf;
    sk->buffered = format == HY_FORMAT_SVG;
    if (format == HY_FORMAT_SVG) {
        surf = cairo_svg_surface_create_for_stream(sink_write, sk, W, H);
        cairo_svg_surface_set_document_unit(surf, CAIRO_SVG_UNIT_PT);
    } else {
        surf = cairo_pdf_surface_create_for_stream(sink_write, sk, W, H);
        cairo_pdf_surface_set_metadata(surf, CAIRO_PDF_METADATA_CREATOR, "hystviz");
        char date[40];
        pdf_date(date, sizeof date);
        cairo_pdf_surface_set_metadata(surf, CAIRO_PDF_METADATA_CREATE_DATE, date);
    }
    int st = draw_on(surf, f, 1.0, 1, maps, nmaps, err);
    cairo_surface_finish(surf);
    cairo_status_t cs = cairo_surface_status(surf);
    cairo_surface_destroy(surf);
    if (!st && !sk->err && cs == CAIRO_STATUS_SUCCESS && sk->buffered)
        sk->err = svg_flush_renumbered(sk, f);
    free(sk->buf);
    sk->buf = NULL;
    if (!st && (cs != CAIRO_STATUS_SUCCESS || sk->err))
        st = hy_error_set(err, HY_EIO, "%s", sk->err ? strerror(sk->err) : cairo_status_to_string(cs));
    return st;
}

static void png_fail(png_structp png, png_const_charp msg)
{
    (void)msg;
    png_longjmp(png, 1);
}

static void png_sink(png_structp png, png_bytep data, size_t len)
{
    sink *s = png_get_io_ptr(png);
    if (!s->err && fwrite(data, 1, len, s->fp) != len)
        s->err = errno ? errno : EIO;
    if (s->err)
        png_error(png, "write failed");
}

static void png_flush_fn(png_structp png) { (void)png; }

/* Writes an opaque ARGB32 image as 8-bit RGB with its resolution (pHYs). */
static int png_encode(cairo_surface_t *img, double dpi, sink *sk, hy_error *err)
{
    int w = cairo_image_surface_get_width(img), h = cairo_image_surface_get_height(img);
    int stride = cairo_image_surface_get_stride(img);
    unsigned char *data = cairo_image_surface_get_data(img);
    unsigned char *row = malloc((size_t)w * 3);
    if (!row)
        return hy_error_set(err, HY_ENOMEM, "out of memory for a %d-pixel PNG row", w);
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, NULL, png_fail, NULL);
    png_infop info = png ? png_create_info_struct(png) : NULL;
    if (!info) {
        png_destroy_write_struct(&png, NULL);
        free(row);
        return hy_error_set(err, HY_ENOMEM, "out of memory for the PNG encoder");
    }
    if (setjmp(png_jmpbuf(png))) {
        png_destroy_write_struct(&png, &info);
        free(row);
        return hy_error_set(err, HY_EIO, "%s", sk->err ? strerror(sk->err) : "PNG encoding failed");
    }
    png_set_write_fn(png, sk, png_sink, png_flush_fn);
    /* figures are flat colour: no filter + zlib level 1 is ~6x faster than the
       defaults (adaptive filters, level 6) and gives smaller files here */
    png_set_compression_level(png, 1);
    png_set_filter(png, 0, PNG_FILTER_NONE);
    png_set_IHDR(png, info, (png_uint_32)w, (png_uint_32)h, 8, PNG_COLOR_TYPE_RGB,
                 PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    png_uint_32 ppm = (png_uint_32)(dpi / 0.0254 + 0.5);
    png_set_pHYs(png, info, ppm, ppm, PNG_RESOLUTION_METER);
    png_write_info(png, info);
    for (int y = 0; y < h; y++) {
        const uint32_t *src = (const uint32_t *)(const void *)(data + (size_t)y * stride);
        for (int x = 0; x < w; x++) {
            row[3 * x] = (unsigned char)(src[x] >> 16);
            row[3 * x + 1] = (unsigned char)(src[x] >> 8);
            row[3 * x + 2] = (unsigned char)src[x];
        }
        png_write_row(png, row);
    }
    png_write_end(png, info);
    png_destroy_write_struct(&png, &info);
    free(row);
    return HY_OK;
}

static int write_png(const hy_figure *f, sink *sk, hy_panel_map *maps, size_t nmaps, hy_error *err)
{
    double W, H, dpi;
    hy__figure_size(f, &W, &H, &dpi);
    int pw = hy_pt_to_px(W, dpi), ph = hy_pt_to_px(H, dpi);
    cairo_surface_t *img = cairo_image_surface_create(CAIRO_FORMAT_ARGB32, pw, ph);
    if (cairo_surface_status(img) != CAIRO_STATUS_SUCCESS) {
        cairo_surface_destroy(img);
        return hy_error_set(err, HY_ENOMEM, "cannot allocate a %d x %d image", pw, ph);
    }
    /* The figure is W x H points, rarely a whole number of pixels (12 cm at
     * 200 dpi is 944.9 px): the image is rounded to whole pixels and painted
     * white first, so its last column and row are background, not a grey
     * blend of the figure's edge with transparent black. */
    cairo_t *bg = cairo_create(img);
    cairo_set_source_rgb(bg, 1.0, 1.0, 1.0);
    cairo_paint(bg);
    cairo_destroy(bg);
    int st = draw_on(img, f, dpi / 72.0, 0, maps, nmaps, err);
    cairo_surface_flush(img);
    if (!st)
        st = png_encode(img, dpi, sk, err);
    cairo_surface_destroy(img);
    return st;
}

int hy_format_from_path(const char *path)
{
    const char *dot = path ? strrchr(path, '.') : NULL;
    if (!dot)
        return -1;
    static const char *const ext[] = {HY_FIGURE_FORMATS(HY_FORMAT_EXT) NULL};
    for (int k = 0; ext[k]; k++)
        if (!strcmp(dot + 1, ext[k]))
            return k;
    return -1;
}

double hy_figure_png_pixels(const hy_figure *f)
{
    double W, H, dpi;
    hy__figure_size(f, &W, &H, &dpi);
    return (double)hy_pt_to_px(W, dpi) * (double)hy_pt_to_px(H, dpi);
}

int hy_figure_check(const hy_figure *f, int format, hy_error *err)
{
    if (!f)
        return hy_error_set(err, HY_EINVAL, "no figure to write");
    if (format < 0 || format >= HY_FORMAT_COUNT)
        return hy_error_set(err, HY_EINVAL, "unknown figure format %d", format);
    if (format != HY_FORMAT_PNG)
        return HY_OK;
    double W, H, dpi;
    hy__figure_size(f, &W, &H, &dpi);
    double pw = W * dpi / 72.0, ph = H * dpi / 72.0;
    if (!(pw <= HY_PNG_MAX_SIDE && ph <= HY_PNG_MAX_SIDE && pw * ph <= HY_PNG_MAX_PIXELS))
        return hy_error_set(err, HY_EINVAL,
                            "a PNG of %.0f x %.0f pixels (%.4g x %.4g in at %.4g dpi) is too large: at most %d pixels "
                            "a side and %.0f million pixels; lower the dpi or the size",
                            pw, ph, W / 72.0, H / 72.0, dpi, HY_PNG_MAX_SIDE, HY_PNG_MAX_PIXELS / 1e6);
    return HY_OK;
}

int hy_figure_write_out(const hy_figure *f, hy_out *out, int format, hy_error *err)
{
    int st = hy_figure_check(f, format, err);
    if (st)
        return st;
    sink sk = {hy_out_file(out), 0, NULL, 0, 0, 0};
    st = format == HY_FORMAT_PNG ? write_png(f, &sk, NULL, 0, err) : write_vector(f, format, &sk, NULL, 0, err);
    if (!st)
        st = hy_out_finish(out, err);
    else {
        hy_error_prefix(err, "cannot write '%s'", out->path);
        hy_out_abort(out);
    }
    return st;
}

int hy_figure_write(const hy_figure *f, const char *path, int format, hy_error *err)
{
    if (!f || !path || !*path)
        return hy_error_set(err, HY_EINVAL, "hy_figure_write needs a figure and a path");
    hy_out out;
    int st = hy_figure_check(f, format, err);
    if (!st)
        st = hy_out_open(&out, path, 0, err);
    if (!st)
        st = hy_figure_write_out(f, &out, format, err);
    if (!st)
        st = hy_out_publish(&out, err);
    return st;
}

int hy_figure_render_mem(const hy_figure *f, int format, unsigned char **buf, size_t *len, hy_error *err)
{
    return hy_figure_render_mem_mapped(f, format, buf, len, NULL, 0, err);
}

int hy_figure_render_mem_mapped(const hy_figure *f, int format, unsigned char **buf, size_t *len, hy_panel_map *maps,
                                size_t nmaps, hy_error *err)
{
    *buf = NULL;
    *len = 0;
    if (!f)
        return hy_error_set(err, HY_EINVAL, "hy_figure_render_mem needs a figure");
    int st = hy_figure_check(f, format, err); /* format, PNG raster limits */
    if (st)
        return st;
    char *mem = NULL;
    size_t n = 0;
    sink sk = {open_memstream(&mem, &n), 0, NULL, 0, 0, 0};
    if (!sk.fp)
        return hy_error_set(err, HY_ENOMEM, "out of memory for the figure's bytes");
    /* the same encoders as hy_figure_write, into memory: identical bytes */
    st = format == HY_FORMAT_PNG ? write_png(f, &sk, maps, nmaps, err) : write_vector(f, format, &sk, maps, nmaps, err);
    if (fclose(sk.fp) != 0 && !st)
        st = hy_error_set(err, HY_ENOMEM, "out of memory for the figure's bytes");
    if (st) {
        free(mem);
        return st;
    }
    *buf = (unsigned char *)mem;
    *len = n;
    return HY_OK;
}
