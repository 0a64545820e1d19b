/* SPDX-License-Identifier: MIT */
/* png_strict.c: png_strict FILE.png...: each PNG through three decoders that
 * must agree (issue 38: a frame zlib took that chromium refused).
 *   1. the chunks: signature, lengths, every CRC, IHDR 8-bit RGB or RGBA
 *      without interlace, IDAT, IEND last;
 *   2. the IDAT stream inflated by zlib and by zstrict.c (every Huffman code
 *      complete), to the same bytes, exactly h rows of 1 + w * channels;
 *   3. the rows unfiltered here (filters 0..4) equal to libpng's pixels
 *      (png_image API).
 * Prints one line per file that fails and a summary
 * "png_strict: N files, N ok, N failed"; exit 0 only when all are ok.
 * -v: a line per file (size, blocks). */
#include <png.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <zlib.h>

#include "zstrict.h"

#include "../hy_test.h"

static uint32_t be32(const unsigned char *p) { return (uint32_t)p[0] << 24 | (uint32_t)p[1] << 16 | (uint32_t)p[2] << 8 | p[3]; }

static int paeth(int a, int b, int c)
{
    int p = a + b - c, pa = abs(p - a), pb = abs(p - b), pc = abs(p - c);
    return pa <= pb && pa <= pc ? a : pb <= pc ? b : c;
}

/* The rows' filters undone in place into px (w * ch bytes a row); -1 on a bad filter. */
static int unfilter(const unsigned char *raw, unsigned char *px, size_t w, size_t h, int ch)
{
    size_t rb = w * (size_t)ch;
    for (size_t y = 0; y < h; y++) {
        const unsigned char *r = raw + y * (rb + 1) + 1;
        unsigned char *d = px + y * rb, *u = y ? d - rb : NULL;
        int ft = r[-1];
        for (size_t i = 0; i < rb; i++) {
            int a = i >= (size_t)ch ? d[i - ch] : 0, b = u ? u[i] : 0, c = u && i >= (size_t)ch ? u[i - ch] : 0;
            int p = ft == 0 ? 0 : ft == 1 ? a : ft == 2 ? b : ft == 3 ? (a + b) / 2 : ft == 4 ? paeth(a, b, c) : -1;
            if (p < 0)
                return -1;
            d[i] = (unsigned char)(r[i] + p);
        }
    }
    return 0;
}

static int verbose;

/* 0 when the file passes every check; prints why not. */
static int check_file(const char *path)
{
    static const unsigned char sig[8] = {137, 'P', 'N', 'G', 13, 10, 26, 10};
    size_t n = 0, zn = 0, rawn = 0;
    unsigned char *f = (unsigned char *)hy_test_slurp(path, &n), *z = NULL, *raw1 = NULL, *raw2 = NULL, *px = NULL, *lp = NULL;
    const char *bad = NULL;
    char why[200] = "";
    uint32_t w = 0, h = 0;
    int ch = 0, seen_end = 0;
    zstrict_info info = {0};
    if (!f || n < 8 || memcmp(f, sig, 8)) {
        bad = "not a PNG (or unreadable)";
        goto out;
    }
    z = malloc(n);
    for (size_t p = 8; !bad && p < n;) {
        if (seen_end) {
            bad = "bytes after IEND";
            break;
        }
        if (n - p < 12 || be32(f + p) > n - p - 12) {
            bad = "a chunk runs past the end";
            break;
        }
        uint32_t len = be32(f + p);
        const unsigned char *type = f + p + 4, *data = f + p + 8;
        if (be32(data + len) != (uint32_t)crc32(0, type, len + 4))
            bad = "a chunk's CRC is wrong";
        else if (!memcmp(type, "IHDR", 4)) {
            if (p != 8 || len != 13 || data[8] != 8 || (data[9] != 2 && data[9] != 6) || data[10] || data[11] || data[12])
                bad = "IHDR: not the first chunk, or not 8-bit RGB/RGBA without interlace";
            w = be32(data), h = be32(data + 4), ch = data[9] == 2 ? 3 : 4;
            if (!w || !h || w > 100000 || h > 100000)
                bad = "IHDR: size 0 or over 100,000";
        } else if (!memcmp(type, "IDAT", 4)) {
            memcpy(z + zn, data, len);
            zn += len;
        } else if (!memcmp(type, "IEND", 4))
            seen_end = 1;
        p += 12 + (size_t)len;
    }
    if (bad)
        goto out;
    if (!w || !seen_end || !zn) {
        bad = "no IHDR, IDAT or IEND";
        goto out;
    }
    rawn = (size_t)h * (1 + (size_t)w * (size_t)ch);
    raw1 = malloc(rawn + 1), raw2 = malloc(rawn);
    uLongf got = (uLongf)rawn + 1;
    int rc = uncompress(raw1, &got, z, (uLong)zn);
    if (rc != Z_OK || got != rawn) {
        snprintf(why, sizeof why, "zlib: status %d, %lu bytes of %zu", rc, (unsigned long)got, rawn);
        goto out;
    }
    if (zstrict_inflate(z, zn, raw2, rawn, &info, why + 8, sizeof why - 8)) {
        memcpy(why, "strict: ", 8);
        goto out;
    }
    if (info.out != rawn || memcmp(raw1, raw2, rawn)) {
        bad = "zlib and the strict decoder inflate different bytes";
        goto out;
    }
    px = malloc((size_t)w * h * (size_t)ch);
    if (unfilter(raw1, px, w, h, ch)) {
        bad = "a row's filter type is not 0..4";
        goto out;
    }
    png_image im;
    memset(&im, 0, sizeof im);
    im.version = PNG_IMAGE_VERSION;
    if (!png_image_begin_read_from_memory(&im, f, n)) {
        snprintf(why, sizeof why, "libpng: %s", im.message);
        goto out;
    }
    im.format = ch == 3 ? PNG_FORMAT_RGB : PNG_FORMAT_RGBA;
    lp = malloc(PNG_IMAGE_SIZE(im));
    if (!png_image_finish_read(&im, NULL, lp, 0, NULL)) {
        snprintf(why, sizeof why, "libpng: %s", im.message);
        png_image_free(&im);
        goto out;
    }
    if (im.width != w || im.height != h || memcmp(lp, px, (size_t)w * h * (size_t)ch))
        bad = "libpng's pixels differ from the rows inflated and unfiltered here";
out:
    if (bad)
        snprintf(why, sizeof why, "%s", bad);
    if (why[0])
        printf("FAIL %s: %s\n", path, why);
    else if (verbose)
        printf("ok %s: %ux%u, %zu bytes, %d blocks (%d dynamic, %d fixed, %d stored, %d empty)\n", path, w, h, n,
               info.blocks, info.dynamic, info.fixed, info.stored, info.empty);
    free(f), free(z), free(raw1), free(raw2), free(px), free(lp);
    return why[0] != 0;
}

int main(int argc, char **argv)
{
    int nf = 0, bad = 0;
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "-v")) {
            verbose = 1;
            continue;
        }
        nf++;
        bad += check_file(argv[i]);
    }
    printf("png_strict: %d files, %d ok, %d failed\n", nf, nf - bad, bad);
    return bad || !nf;
}
