/* hy_frame.c: overlay compositing (premultiplied "over", vertical flip of the
 * GL layer) and libpng frame output through the output writer (hy_out). */
#include "hy_frame.h"

#include <errno.h>
#include <png.h>
#include <setjmp.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <zlib.h>

#include "hy_out.h"

/* x / 255 rounded to nearest for x in [0, 255 * 255] (exact, no division). */
static inline unsigned div255(unsigned x)
{
    x += 128;
    return (x + (x >> 8)) >> 8;
}

void hy_frame_composite(int w, int h, const unsigned char *gl, const unsigned char *argb, int stride,
                        unsigned char *rgb)
{
    for (int y = 0; y < h; y++) {
        const unsigned char *src = gl + (size_t)(h - 1 - y) * (size_t)w * 4;
        unsigned char *dst = rgb + (size_t)y * (size_t)w * 3;
        const uint32_t *ov = argb ? (const uint32_t *)(const void *)(argb + (size_t)y * (size_t)stride) : NULL;
        for (int x = 0; x < w; x++) {
            uint32_t p = ov ? ov[x] : 0;
            unsigned a = p >> 24, k = 255 - a;
            if (a == 0) {             /* most pixels: the GL layer shows through */
                dst[3 * x] = src[4 * x], dst[3 * x + 1] = src[4 * x + 1], dst[3 * x + 2] = src[4 * x + 2];
                continue;
            }
            dst[3 * x] = (unsigned char)(((p >> 16) & 255) + div255(src[4 * x] * k));
            dst[3 * x + 1] = (unsigned char)(((p >> 8) & 255) + div255(src[4 * x + 1] * k));
            dst[3 * x + 2] = (unsigned char)((p & 255) + div255(src[4 * x + 2] * k));
        }
    }
}

hy_png_opts hy_png_frame_defaults(void)
{
    /* Measured by bench_gl on a 1920x1080 plot frame (flat colours, thin
     * lines): level 1 without filtering wrote it in 16 ms / 251 KB, against
     * 20 ms / 258 KB (level 2, sub), 29 ms / 219 KB (level 6, none) and
     * 45-60 ms for adaptive filtering, which gains nothing on such frames. */
    return (hy_png_opts){1, HY_PNG_FILTER_NONE, 0};
}

static void png_fail(png_structp png, png_const_charp msg)
{
    (void)msg;
    png_longjmp(png, 1);
}

static int filter_flags(int f)
{
    switch (f) {
    case HY_PNG_FILTER_NONE: return PNG_FILTER_NONE;
    case HY_PNG_FILTER_SUB: return PNG_FILTER_SUB;
    case HY_PNG_FILTER_UP: return PNG_FILTER_UP;
    case HY_PNG_FILTER_PAETH: return PNG_FILTER_PAETH;
    default: return PNG_ALL_FILTERS;
    }
}

/* Pixels: packed RGB (stride 3w) when xrgb_stride is 0, else cairo RGB24
 * words (0x00RRGGBB in native byte order) with that stride, converted by
 * libpng row by row as it encodes. */
static int encode(FILE *fp, int w, int h, const unsigned char *rgb, int xrgb_stride, const hy_png_opts *o)
{
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, NULL, png_fail, NULL);
    png_infop info = png ? png_create_info_struct(png) : NULL;
    if (!info) {
        png_destroy_write_struct(&png, NULL);
        return -1;
    }
    if (setjmp(png_jmpbuf(png))) {
        png_destroy_write_struct(&png, &info);
        return -1;
    }
    png_init_io(png, fp);
    png_set_compression_level(png, o->level < 0 ? 0 : o->level > 9 ? 9 : o->level);
    png_set_compression_strategy(png, o->strategy == 1 ? Z_FILTERED : o->strategy == 3 ? Z_RLE
                                                                                       : Z_DEFAULT_STRATEGY);
    png_set_filter(png, PNG_FILTER_TYPE_BASE, filter_flags(o->filter));
    png_set_IHDR(png, info, (png_uint_32)w, (png_uint_32)h, 8, PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE,
                 PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    png_write_info(png, info);
    if (xrgb_stride) {
        if (hy_little_endian()) {                  /* little-endian: bytes B, G, R, x */
            png_set_bgr(png);
            png_set_filler(png, 0, PNG_FILLER_AFTER);
        } else                        /* big-endian: bytes x, R, G, B */
            png_set_filler(png, 0, PNG_FILLER_BEFORE);
    }
    size_t row = xrgb_stride ? (size_t)xrgb_stride : (size_t)w * 3;
    for (int y = 0; y < h; y++)
        png_write_row(png, rgb + (size_t)y * row);
    png_write_end(png, info);
    png_destroy_write_struct(&png, &info);
    return 0;
}

static int write_png(const char *path, int w, int h, const unsigned char *rgb, int xrgb_stride,
                     const hy_png_opts *o, hy_error *err)
{
    hy_png_opts def = hy_png_frame_defaults();
    hy_out out;
    int st = hy_out_open(&out, path, 0, err);
    if (st)
        return st;
    errno = 0;
    if (encode(hy_out_file(&out), w, h, rgb, xrgb_stride, o ? o : &def) != 0) {
        int e = errno;
        hy_out_abort(&out);
        return hy_error_set(err, HY_EIO, "cannot write '%s': %s", path, e ? strerror(e) : "PNG encoding failed");
    }
    return hy_out_commit(&out, err);
}

int hy_png_write_rgb(const char *path, int w, int h, const unsigned char *rgb, const hy_png_opts *o,
                     hy_error *err)
{
    return write_png(path, w, h, rgb, 0, o, err);
}

int hy_png_write_xrgb(const char *path, int w, int h, const unsigned char *xrgb, int stride, const hy_png_opts *o,
                      hy_error *err)
{
    if (stride < 4 * w)
        return hy_error_set(err, HY_EINVAL, "cannot write '%s': stride %d is less than 4 x %d", path, stride, w);
    return write_png(path, w, h, xrgb, stride, o, err);
}
