/* SPDX-License-Identifier: MIT */
/* zstrict.h: a strict zlib/deflate decoder for the tests (RFC 1950, RFC 1951),
 * written apart from hy_zfast and zlib so that it shares neither's mistakes.
 * It inflates the whole stream and refuses, with a reason, anything a strict
 * inflater may refuse although zlib takes it:
 *
 *   - a Huffman code that is not complete (Kraft sum of 2^-len not exactly 1)
 *     or over-subscribed: the code-length code, every literal/length code and
 *     every distance code.  The one exception is the case RFC 1951 3.2.7
 *     describes and zlib's inflate accepts: a distance code of exactly one
 *     code of length 1.  (An all-zero distance code, "no distances", is
 *     allowed by the RFC but refused here: no encoder of ours needs it.)
 *   - HLIT > 286 or HDIST > 30, a length repeat (16) with nothing before it,
 *     repeats past HLIT + HDIST, end-of-block without a code, symbols 286,
 *     287, 30, 31, a distance before the start, BTYPE 3, LEN != ~NLEN;
 *   - a zlib header that is not deflate with a window <= 32 kB, a preset
 *     dictionary, a wrong FCHECK, a wrong Adler-32, bytes after it, output
 *     past outcap.
 *
 *     zstrict_info info;
 *     char why[160];
 *     if (zstrict_inflate(s, n, out, outcap, &info, why, sizeof why))
 *         printf("refused: %s\n", why);
 *
 * It also counts what it saw (blocks of each type, empty blocks, codes with
 * one distance code) so a test can hold an encoder to more than validity.
 */
#ifndef ZSTRICT_H
#define ZSTRICT_H

#include <stddef.h>

typedef struct zstrict_info {
    size_t out;                        /* bytes inflated */
    int blocks, stored, fixed, dynamic;
    int empty;                         /* blocks with no symbol but end-of-block */
    int one_dist;                      /* dynamic blocks whose distance code is the one-code exception */
    int last_empty;                    /* the final block is empty */
} zstrict_info;

/* Inflates the zlib stream in[0..n) into out (at most outcap bytes).
 * Returns 0 when it is valid under the rules above, -1 with the reason and
 * the byte offset in why otherwise; info (may be NULL) is filled either way
 * with what was seen up to there. */
int zstrict_inflate(const unsigned char *in, size_t n, unsigned char *out, size_t outcap, zstrict_info *info,
                    char *why, size_t whylen);

#endif
