/* SPDX-License-Identifier: MIT */
/* hy_frame.c: overlay compositing (premultiplied "over", vertical flip of the
 * GL layer) and libpng frame output through the output writer (hy_out). */
#include "hy_frame.h"

#include <errno.h>
#include <png.h>
#include <pthread.h>
#include <setjmp.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <zlib.h>

#include "hy_config.h"
#include "hy_out.h"
#include "hy_zfast.h"
#if HY_HAVE_LIBDEFLATE
#include <libdeflate.h>
#endif

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

/* hy_zfast (fast) on the 720p gamma-sweep clip's frames: 1.6 ms and 75 kB a
 * frame against libdeflate level 2's 4.2-4.6 ms and 65 kB (the engine
 * before) and zlib level 1's 9-12 ms and 78 kB (the frames before issue
 * 23); on 1920x1080 frames adaptive filtering cost 45-60 ms for nothing. */
static const struct png_mode {
    const char *name;
    hy_png_opts o;
} png_modes[] = {
#define MODE_ROW(n, level, engine, d) {n, {level, HY_PNG_FILTER_NONE, 0, engine}},
    HY_PNG_MODES(MODE_ROW)
#undef MODE_ROW
};

hy_png_opts hy_png_frame_defaults(void) { return png_modes[0].o; }

int hy_png_mode(const char *name, hy_png_opts *o, hy_error *err)
{
    for (size_t i = 0; name && i < sizeof png_modes / sizeof png_modes[0]; i++)
        if (!strcmp(name, png_modes[i].name)) {
            *o = png_modes[i].o;
            return HY_OK;
        }
#define MODE_NAME(n, level, engine, d) " " n
    return hy_error_set(err, HY_EINVAL, "unknown PNG mode '%s' (known:" HY_PNG_MODES(MODE_NAME) ")",
                        name ? name : "");
#undef MODE_NAME
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

static void put32(unsigned char *p, uint32_t v)
{
    p[0] = (unsigned char)(v >> 24), p[1] = (unsigned char)(v >> 16), p[2] = (unsigned char)(v >> 8);
    p[3] = (unsigned char)v;
}

static uint32_t crc32_of(uint32_t crc, const unsigned char *p, size_t n)
{
#if HY_HAVE_LIBDEFLATE
    return n ? libdeflate_crc32(crc, p, n) : crc; /* with no data it returns the initial value, not crc */
#else
    return (uint32_t)crc32(crc, p, (uInt)n);
#endif
}

/* One PNG chunk: length, type, data, CRC-32 of type and data. */
static int put_chunk(FILE *fp, const char *type, const unsigned char *data, size_t n)
{
    unsigned char head[8], tail[4];
    put32(head, (uint32_t)n);
    memcpy(head + 4, type, 4);
    put32(tail, crc32_of(crc32_of(0, head + 4, 4), data, n));
    return fwrite(head, 1, 8, fp) == 8 && (!n || fwrite(data, 1, n, fp) == n) && fwrite(tail, 1, 4, fp) == 4 ? 0 : -1;
}

/* A PNG of its zlib stream z (n bytes): signature, IHDR (8-bit RGB, no
 * interlace), IDAT chunks below 2^31 bytes, IEND. */
static int put_png(FILE *fp, int w, int h, const unsigned char *z, size_t n)
{
    unsigned char ihdr[13];
    put32(ihdr, (uint32_t)w);
    put32(ihdr + 4, (uint32_t)h);
    ihdr[8] = 8, ihdr[9] = 2, ihdr[10] = ihdr[11] = ihdr[12] = 0; /* 8-bit RGB, deflate, no interlace */
    static const unsigned char sig[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    if (!n || fwrite(sig, 1, 8, fp) != 8 || put_chunk(fp, "IHDR", ihdr, 13))
        return -1;
    for (size_t off = 0; off < n; off += 1u << 30)
        if (put_chunk(fp, "IDAT", z + off, n - off < (1u << 30) ? n - off : 1u << 30))
            return -1;
    return put_chunk(fp, "IEND", NULL, 0);
}

/* hy_zfast's encoder, one per thread, kept from frame to frame. */
static pthread_key_t zfast_key;
static pthread_once_t zfast_once = PTHREAD_ONCE_INIT;
static int zfast_ok;

static void zfast_free(void *p) { hy_zfast_free(p); }
static void zfast_init(void) { zfast_ok = !pthread_key_create(&zfast_key, zfast_free); }

static int encode_fast(FILE *fp, int w, int h, const unsigned char *xrgb, int stride)
{
    pthread_once(&zfast_once, zfast_init);
    hy_zfast *z = zfast_ok ? pthread_getspecific(zfast_key) : NULL;
    if (zfast_ok && !z && (z = hy_zfast_new()) && pthread_setspecific(zfast_key, z)) {
        hy_zfast_free(z);
        z = NULL;
    }
    size_t n = z ? hy_zfast_png(z, xrgb, w, h, stride) : 0;
    return n ? put_png(fp, w, h, hy_zfast_data(z), n) : -1;
}

#if HY_HAVE_LIBDEFLATE
/* Each thread keeps its compressor and buffers from frame to frame: fresh
 * pages cost about 20 us each on the machines measured (issue 23), which for
 * a 720p frame's 5.5 MB would take longer than compressing it. */
typedef struct deflate_cache {
    struct libdeflate_compressor *c;
    int level;
    unsigned char *raw, *z;
    size_t rawcap, zcap;
} deflate_cache;
static pthread_key_t cache_key;
static pthread_once_t cache_once = PTHREAD_ONCE_INIT;
static int cache_ok;

static void cache_free(void *p)
{
    deflate_cache *k = p;
    if (k->c)
        libdeflate_free_compressor(k->c);
    free(k->raw);
    free(k->z);
    free(k);
}

static void cache_init(void)
{
    cache_ok = !pthread_key_create(&cache_key, cache_free);
}

/* The calling thread's cache with a compressor at level and buffers of at
 * least n and the bound of n bytes; NULL when out of memory. */
static deflate_cache *cache_get(int level, size_t n)
{
    pthread_once(&cache_once, cache_init);
    deflate_cache *k = cache_ok ? pthread_getspecific(cache_key) : NULL;
    if (cache_ok && !k && (k = calloc(1, sizeof *k)) && pthread_setspecific(cache_key, k)) {
        free(k);
        k = NULL;
    }
    if (!k)
        return NULL;
    if (!k->c || k->level != level) {
        if (k->c)
            libdeflate_free_compressor(k->c);
        k->level = level;
        if (!(k->c = libdeflate_alloc_compressor(level)))
            return NULL;
    }
    size_t bound = libdeflate_zlib_compress_bound(k->c, n);
    if (k->rawcap < n) {
        free(k->raw);
        k->rawcap = (k->raw = malloc(n)) ? n : 0;
    }
    if (k->zcap < bound) {
        free(k->z);
        k->zcap = (k->z = malloc(bound)) ? bound : 0;
    }
    return k->raw && k->z ? k : NULL;
}

/* The PNG as encode() writes it (8-bit RGB, no interlace), its image data
 * filtered with "none" and compressed by libdeflate at level in one call. */
static int encode_deflate(FILE *fp, int w, int h, const unsigned char *px, int xrgb_stride, int level)
{
    size_t rowb = 1 + 3 * (size_t)w, n = rowb * (size_t)h;
    deflate_cache *k = cache_get(level < 0 ? 0 : level > 12 ? 12 : level, n);
    unsigned char *raw = k ? k->raw : NULL, *z = k ? k->z : NULL;
    struct libdeflate_compressor *c = k ? k->c : NULL;
    size_t bound = k ? k->zcap : 0;
    int rc = -1;
    if (k) {
        int le = hy_little_endian();
        for (int y = 0; y < h; y++) {
            unsigned char *d = raw + (size_t)y * rowb;
            *d++ = 0; /* filter type none */
            if (!xrgb_stride) {
                memcpy(d, px + (size_t)y * 3 * (size_t)w, 3 * (size_t)w);
                continue;
            }
            const unsigned char *s = px + (size_t)y * (size_t)xrgb_stride;
            for (int x = 0; x < w; x++, s += 4, d += 3) { /* B G R x, or x R G B */
                d[0] = le ? s[2] : s[1];
                d[1] = le ? s[1] : s[2];
                d[2] = le ? s[0] : s[3];
            }
        }
        size_t zn = libdeflate_zlib_compress(c, raw, n, z, bound);
        rc = zn ? put_png(fp, w, h, z, zn) : -1;
    }
    return rc;
}
#endif

/* The PNG of the pixels on fp with o's engine (NULL: the frame defaults); -1 on failure. */
static int encode_any(FILE *fp, int w, int h, const unsigned char *rgb, int xrgb_stride, const hy_png_opts *o)
{
    hy_png_opts def = hy_png_frame_defaults();
    if (!o)
        o = &def;
    if (o->engine == HY_PNG_FAST && xrgb_stride && w <= 10922)
        return encode_fast(fp, w, h, rgb, xrgb_stride);
#if HY_HAVE_LIBDEFLATE
    if (o->engine == HY_PNG_LIBDEFLATE || o->engine == HY_PNG_FAST)   /* FAST: packed RGB or too wide */
        return encode_deflate(fp, w, h, rgb, xrgb_stride, o->level);
#endif
    return encode(fp, w, h, rgb, xrgb_stride, o);
}

static int write_png(const char *path, int w, int h, const unsigned char *rgb, int xrgb_stride,
                     const hy_png_opts *o, hy_error *err)
{
    hy_out out;
    int st = hy_out_open(&out, path, 0, err);
    if (st)
        return st;
    errno = 0;
    int bad = encode_any(hy_out_file(&out), w, h, rgb, xrgb_stride, o);
    if (bad) {
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

int hy_png_encode_xrgb(FILE *fp, int w, int h, const unsigned char *xrgb, int stride, const hy_png_opts *o,
                       hy_error *err)
{
    if (stride < 4 * w)
        return hy_error_set(err, HY_EINVAL, "cannot encode a PNG: stride %d is less than 4 x %d", stride, w);
    errno = 0;
    if (encode_any(fp, w, h, xrgb, stride, o) || fflush(fp))
        return hy_error_set(err, HY_EIO, "cannot encode a PNG: %s", errno ? strerror(errno) : "encoding failed");
    return HY_OK;
}
