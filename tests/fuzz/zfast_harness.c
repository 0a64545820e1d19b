/* SPDX-License-Identifier: MIT */
/* zfast_harness.c: see zfast_harness.h. */
#include "zfast_harness.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <zlib.h>

#include "hy_zfast.h"
#include "zstrict.h"

static const uint32_t palette[16] = {0xffffff, 0x000000, 0x202020, 0xd55e00, 0x0072b2, 0x009e73, 0xe69f00, 0xcc79a7,
                                     0x56b4e9, 0xf0e442, 0x808080, 0xc0c0c0, 0xf0b090, 0x123456, 0xfefefe, 0x010101};

/* The byte stream after the header, read cyclically (0s when empty). */
typedef struct feed {
    const uint8_t *p;
    size_t n, i;
} feed;

static unsigned next(feed *f) { return f->n ? f->p[f->i++ % f->n] : 0; }

static void draw_plot(uint32_t *px, int w, int h, feed *f)
{
    for (size_t i = 0; i < (size_t)w * h; i++)
        px[i] = 0xffffff;
    size_t steps = f->n / 8 < 64 ? f->n / 8 : 64;
    for (size_t s = 0; s < steps; s++) {
        unsigned op = next(f) % 5, c = palette[next(f) % 16];
        int x0 = (int)((next(f) | next(f) << 8) % (unsigned)w), y0 = (int)((next(f) | next(f) << 8) % (unsigned)h);
        int a = (int)next(f), b = (int)next(f);
        if (op == 0)                   /* a horizontal line a + 1 long */
            for (int x = x0; x < w && x <= x0 + a; x++)
                px[(size_t)y0 * w + x] = c;
        else if (op == 1)              /* a vertical line */
            for (int y = y0; y < h && y <= y0 + a; y++)
                px[(size_t)y * w + x0] = c;
        else if (op == 2)              /* a box */
            for (int y = y0; y < h && y <= y0 + b % 32; y++)
                for (int x = x0; x < w && x <= x0 + a % 64; x++)
                    px[(size_t)y * w + x] = c;
        else if (op == 3)              /* a curve with grey edges across the frame */
            for (int x = 0; x < w; x++) {
                int y = y0 + (int)((a % 40) * sin(x / (4.0 + b)));
                for (int d = -1; d <= 1; d++)
                    if (y + d >= 0 && y + d < h)
                        px[(size_t)(y + d) * w + x] = d ? (c | 0x808080) : c;
            }
        else {                         /* a block copied to (a, b) * scale: repeated text */
            int bw = 1 + a % 40, bh = 1 + b % 16, tx = (int)(next(f) * (unsigned)w / 256), ty = (int)(next(f) * (unsigned)h / 256);
            for (int y = 0; y < bh && y0 + y < h && ty + y < h; y++)
                for (int x = 0; x < bw && x0 + x < w && tx + x < w; x++)
                    px[(size_t)(ty + y) * w + tx + x] = px[(size_t)(y0 + y) * w + x0 + x] ^ (uint32_t)(x * y % 3);
        }
    }
}

int zfast_fuzz_one(const uint8_t *data, size_t n, char *why, size_t whylen)
{
    uint8_t hd[8] = {0};
    memcpy(hd, data, n < 8 ? n : 8);
    feed f = {data + (n < 8 ? n : 8), n < 8 ? 0 : n - 8, 0};
    int w = 1 + (int)((hd[1] | hd[2] << 8) % 2048), h = 1 + (int)((hd[3] | hd[4] << 8) % 4096);
    while ((size_t)w * (size_t)h > (1u << 16))
        w > h ? (w = (w + 1) / 2) : (h = (h + 1) / 2);
    size_t np = (size_t)w * h, rawn = (size_t)h * (1 + 3 * (size_t)w);
    uint32_t *px = malloc(np * 4);
    unsigned char *want = malloc(rawn), *got = malloc(rawn + 1), *strict = malloc(rawn);
    hy_zfast *z = hy_zfast_new();
    int rc = -1;
    if (!px || !want || !got || !strict || !z) {
        snprintf(why, whylen, "out of memory");
        goto out;
    }
    int kind = hd[0] % 4, ncol = 1 + hd[5] % 16;
    uint32_t b = (uint32_t)(hd[5] | hd[6] << 8 | hd[7] << 16) | 1, a = b * 2654435761u;
    if (kind == 2)
        draw_plot(px, w, h, &f);
    for (size_t i = 0; i < np; i++) {
        uint32_t p = px[i];
        if (kind == 0)
            p = next(&f) | next(&f) << 8 | next(&f) << 16;
        else if (kind == 1)
            p = palette[next(&f) % (unsigned)ncol];
        else if (kind == 3)
            p = (a * (uint32_t)(i % (size_t)w) + b * (uint32_t)(i / (size_t)w) + 0x102030u) & 0xffffff;
        px[i] = (p & 0xffffff) | (uint32_t)(i * 0x9e3779b9u) << 24;
    }
    unsigned char *d = want;
    for (size_t i = 0; i < np; i++) {
        if (i % (size_t)w == 0)
            *d++ = 0;
        *d++ = (unsigned char)(px[i] >> 16), *d++ = (unsigned char)(px[i] >> 8), *d++ = (unsigned char)px[i];
    }
    size_t zn = hy_zfast_png(z, (const unsigned char *)px, w, h, 4 * w);
    if (!zn) {
        snprintf(why, whylen, "%dx%d kind %d: hy_zfast_png made no stream", w, h, kind);
        goto out;
    }
    const unsigned char *s = hy_zfast_data(z);
    uLongf gn = (uLongf)rawn + 1;
    int zr = uncompress(got, &gn, s, (uLong)zn);
    if (zr != Z_OK || gn != rawn || memcmp(got, want, rawn)) {
        snprintf(why, whylen, "%dx%d kind %d: zlib: status %d, %lu bytes of %zu%s", w, h, kind, zr, (unsigned long)gn,
                 rawn, zr == Z_OK && gn == rawn ? ", different" : "");
        goto out;
    }
    zstrict_info info;
    char sw[160];
    if (zstrict_inflate(s, zn, strict, rawn, &info, sw, sizeof sw)) {
        snprintf(why, whylen, "%dx%d kind %d: the strict inflater: %s", w, h, kind, sw);
        goto out;
    }
    if (info.out != rawn || memcmp(strict, want, rawn) || info.empty) {
        snprintf(why, whylen, "%dx%d kind %d: strictly inflated %zu bytes of %zu, %d empty blocks", w, h, kind,
                 info.out, rawn, info.empty);
        goto out;
    }
    rc = 0;
out:
    hy_zfast_free(z);
    free(px), free(want), free(got), free(strict);
    return rc;
}
