/* SPDX-License-Identifier: MIT */
/* zfast_harness.h: one fuzz input -> one image -> hy_zfast_png, held to zlib
 * and to the strict inflater (tests/render/zstrict.c).  Shared by the
 * libFuzzer target fuzz_zfast.c and the replay test zfast_replay.c.
 *
 * The input's first 8 bytes choose the image (the rest feeds it):
 *   byte 0      kind: 0 random pixels from the bytes, 1 a palette of
 *               1 + byte 5 % 16 colours indexed by the bytes (runs, repeats),
 *               2 plot-like (white, then 8-byte drawing steps: lines, boxes,
 *               curves, a block copied elsewhere as text repeats), 3 a
 *               gradient a x + b y + c (bytes 5..7: b; 1-pixel-wide columns
 *               reach block boundaries exactly, issue 38)
 *   bytes 1, 2  width 1 + (b1 | b2 << 8) % 2048
 *   bytes 3, 4  height 1 + (b3 | b4 << 8) % 4096, both cut so that
 *               width x height <= 2^16 pixels (a few milliseconds an input;
 *               tens under the fuzzer's sanitizers)
 * The unused byte of each pixel varies (only R, G, B may count).
 */
#ifndef ZFAST_HARNESS_H
#define ZFAST_HARNESS_H

#include <stddef.h>
#include <stdint.h>

/* 0 when the stream hy_zfast made of the input's image inflates with zlib
 * and with the strict inflater to exactly the image's PNG rows and no block
 * is empty; -1 with the reason in why otherwise. */
int zfast_fuzz_one(const uint8_t *data, size_t n, char *why, size_t whylen);

#endif
