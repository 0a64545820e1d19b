/* SPDX-License-Identifier: MIT */
/* hy_zfast.h: a fast zlib stream of a PNG frame's image data, made for plot
 * frames (flat backgrounds, thin lines, text).  Every row is filtered with
 * "none"; the deflate matches are runs of the previous pixel (distance 3
 * bytes), the pixels of the row above (distance one row) and earlier
 * occurrences of a pixel pair found through a small hash table (glyphs,
 * lines shifted by a pixel), all in whole pixels; blocks use dynamic Huffman
 * codes (RFC 1951) limited to 15 bits, every code complete (two codes at
 * least in each alphabet, as zlib's deflate makes them) and no block empty.
 * Any inflater decodes the stream to exactly the rows a PNG decoder
 * expects, strict ones too (chromium's createImageBitmap refuses an
 * incomplete code that zlib takes); tests/render/test_zfast.c checks it
 * against zlib's inflate and the strict inflater tests/render/zstrict.c.
 *
 *     hy_zfast *z = hy_zfast_new();
 *     size_t n = hy_zfast_png(z, xrgb, w, h, stride);   // 0: out of memory
 *     fwrite(hy_zfast_data(z), 1, n, fp);               // the IDAT payload
 *     hy_zfast_free(z);
 *
 * A hy_zfast keeps its buffers between frames (one per thread).
 */
#ifndef HY_ZFAST_H
#define HY_ZFAST_H

#include <stddef.h>
#include <stdint.h>

typedef struct hy_zfast hy_zfast;

hy_zfast *hy_zfast_new(void);
void hy_zfast_free(hy_zfast *z);

/* The zlib stream (header, deflate blocks, Adler-32) of the PNG image data of
 * w x h cairo RGB24 pixels (native 0x00RRGGBB words, rows stride bytes apart,
 * top row first) as 8-bit RGB rows with filter byte 0; its length, or 0 when
 * memory ran out.  w must be at most 10,922 (a row's distance fits deflate's
 * 32 kB window). */
size_t hy_zfast_png(hy_zfast *z, const unsigned char *xrgb, int w, int h, int stride);

/* The bytes of the last stream made by z. */
const unsigned char *hy_zfast_data(const hy_zfast *z);

/* The Huffman code lengths of n <= HY_ZFAST_MAX_SYMBOLS symbols of these
 * frequencies (0: unused, length 0), at most maxlen bits, the code complete
 * (sum of 2^-len = 1) when two symbols or more are used; optimal when the
 * unlimited code fits.  (Exposed for tests/render/test_zfast.c.) */
#define HY_ZFAST_MAX_SYMBOLS 286
void hy_zfast_code_lengths(const uint32_t *freq, int n, int maxlen, uint8_t *len);

#endif
