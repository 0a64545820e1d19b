/* SPDX-License-Identifier: MIT */
/* test_composite.c: hy_frame_composite against the definition, pixel by
 * pixel: out = overlay + gl * (1 - alpha), premultiplied "over" rounded to
 * nearest, GL rows flipped (exact: both are integer); and hy_png_write_xrgb
 * (the animation frames' writer, cairo RGB24 words in) read back by cairo's
 * own PNG reader equal to its input in every pixel. */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <cairo.h>

#include "hy_frame.h"
#include "rcheck.h"

static uint32_t rnd_state = 12345u;
static uint32_t rnd(void)
{
    rnd_state = rnd_state * 1664525u + 1013904223u;
    return rnd_state >> 8;
}

static unsigned char ref_channel(unsigned ov, unsigned g, unsigned a)
{
    /* ov + round(g * (255 - a) / 255): computed in double, independent of div255 */
    double v = (double)g * (double)(255 - a) / 255.0;
    return (unsigned char)(ov + (unsigned)(v + 0.5));
}

static void one(int w, int h, int density)
{
    int stride = 4 * w + 4 * (int)(rnd() % 3); /* cairo strides may be wider than the row */
    unsigned char *gl = malloc((size_t)w * h * 4), *ov = calloc((size_t)stride * h, 1), *out = malloc((size_t)w * h * 3);
    for (size_t i = 0; i < (size_t)w * h * 4; i++)
        gl[i] = (unsigned char)rnd();
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            if ((int)(rnd() % 100) >= density)
                continue;                 /* transparent: all four bytes zero */
            unsigned a = rnd() % 256, r = a ? rnd() % (a + 1) : 0, g = a ? rnd() % (a + 1) : 0,
                     b = a ? rnd() % (a + 1) : 0;
            uint32_t p = (a << 24) | (r << 16) | (g << 8) | b;
            memcpy(ov + (size_t)y * stride + 4 * (size_t)x, &p, 4);
        }
    hy_frame_composite(w, h, gl, ov, stride, out);
    int bad = 0;
    for (int y = 0; y < h && bad < 3; y++)
        for (int x = 0; x < w && bad < 3; x++) {
            const unsigned char *s = gl + ((size_t)(h - 1 - y) * w + x) * 4;
            uint32_t p;
            memcpy(&p, ov + (size_t)y * stride + 4 * (size_t)x, 4);
            unsigned a = p >> 24;
            unsigned char want[3] = {ref_channel((p >> 16) & 255, s[0], a), ref_channel((p >> 8) & 255, s[1], a),
                                     ref_channel(p & 255, s[2], a)};
            const unsigned char *o = out + ((size_t)y * w + x) * 3;
            if (memcmp(o, want, 3)) {
                bad++;
                CHECK(0, "%dx%d density %d: pixel (%d,%d) = %u,%u,%u, want %u,%u,%u", w, h, density, x, y, o[0], o[1],
                      o[2], want[0], want[1], want[2]);
            }
        }
    /* without an overlay: the GL layer, flipped */
    hy_frame_composite(w, h, gl, NULL, 0, out);
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++)
            if (memcmp(out + ((size_t)y * w + x) * 3, gl + ((size_t)(h - 1 - y) * w + x) * 4, 3)) {
                CHECK(0, "%dx%d no overlay: pixel (%d,%d) differs", w, h, x, y);
                y = h;
                break;
            }
    free(gl), free(ov), free(out);
}

/* The frame encoders: libpng + zlib, and libdeflate at its levels (zlib
 * where not built with it); each must decode to the pixels written. */
static const hy_png_opts encoders[] = {
    {1, HY_PNG_FILTER_NONE, 0, HY_PNG_ZLIB},      {0, HY_PNG_FILTER_NONE, 0, HY_PNG_LIBDEFLATE},
    {2, HY_PNG_FILTER_NONE, 0, HY_PNG_LIBDEFLATE}, {6, HY_PNG_FILTER_NONE, 0, HY_PNG_LIBDEFLATE},
    {12, HY_PNG_FILTER_NONE, 0, HY_PNG_LIBDEFLATE},
};

/* pngcheck (Debian pngcheck), where installed, finds the file a valid PNG
 * (chunk CRCs, IHDR, the zlib stream). */
static void png_valid(const char *path)
{
    if (system("command -v pngcheck > /dev/null 2>&1"))
        return;
    char cmd[256];
    snprintf(cmd, sizeof cmd, "pngcheck -q %s > /dev/null 2>&1", path);
    CHECK(system(cmd) == 0, "pngcheck finds %s invalid", path);
}

static void xrgb_png(int w, int h, const hy_png_opts *enc)
{
    int stride = 4 * w + 8;           /* wider than the row, as cairo may make it */
    unsigned char *px = malloc((size_t)stride * h);
    for (size_t i = 0; i < (size_t)stride * h; i++)
        px[i] = (unsigned char)rnd();
    hy_error err;
    hy_png_opts o = enc ? *enc : hy_png_frame_defaults();
    int rc = hy_png_write_xrgb("composite_xrgb.png", w, h, px, stride, &o, &err);
    CHECK(rc == 0, "write: %s", rc ? err.msg : "");
    png_valid("composite_xrgb.png");
    cairo_surface_t *s = cairo_image_surface_create_from_png("composite_xrgb.png");
    CHECK(cairo_surface_status(s) == CAIRO_STATUS_SUCCESS && cairo_image_surface_get_width(s) == w &&
              cairo_image_surface_get_height(s) == h, "read back %dx%d", w, h);
    if (cairo_surface_status(s) == CAIRO_STATUS_SUCCESS) {
        const unsigned char *d = cairo_image_surface_get_data(s);
        int ds = cairo_image_surface_get_stride(s), bad = 0;
        for (int y = 0; y < h && !bad; y++)
            for (int x = 0; x < w && !bad; x++) {
                uint32_t a, b;
                memcpy(&a, px + (size_t)y * stride + 4 * (size_t)x, 4);
                memcpy(&b, d + (size_t)y * ds + 4 * (size_t)x, 4);
                if ((a & 0xFFFFFFu) != (b & 0xFFFFFFu)) {
                    bad = 1;
                    CHECK(0, "xrgb %dx%d: pixel (%d,%d) %06x read back as %06x", w, h, x, y, a & 0xFFFFFFu,
                          b & 0xFFFFFFu);
                }
            }
    }
    cairo_surface_destroy(s);
    CHECK(hy_png_write_xrgb("composite_bad.png", w, h, px, 4 * w - 1, &o, &err) != 0 && strstr(err.msg, "stride"),
          "a stride below 4 w is refused");
    free(px);
}

int main(void)
{
    for (size_t e = 0; e <= sizeof encoders / sizeof *encoders; e++) { /* the last: the frames' default */
        const hy_png_opts *enc = e < sizeof encoders / sizeof *encoders ? &encoders[e] : NULL;
        xrgb_png(1, 1, enc);
        xrgb_png(7, 5, enc);
        xrgb_png(333, 17, enc);
    }
    const int widths[] = {1, 2, 3, 4, 5, 7, 8, 9, 17, 64, 333};
    const int dens[] = {0, 3, 50, 100};
    for (size_t i = 0; i < sizeof widths / sizeof *widths; i++)
        for (size_t d = 0; d < 4; d++)
            one(widths[i], 1 + (int)(rnd() % 7), dens[d]);
    printf("composite: %zu sizes x 4 overlay densities\n", sizeof widths / sizeof *widths);
    return hy_test_finish("composite");
}
