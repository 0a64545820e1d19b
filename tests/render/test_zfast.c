/* SPDX-License-Identifier: MIT */
/* test_zfast.c: hy_zfast_png's zlib streams, inflated by zlib (an independent
 * decoder, which also checks the Adler-32), equal the PNG image data they
 * stand for, byte for byte: filter byte 0, then R, G, B of every pixel.
 * Frames: flat white, noise (all literals), a plot-like frame (lines, text
 * blocks, long runs, repeated rows), colours whose unused byte varies (only
 * R, G, B may count), widths 1 to 10,922 (runs longer than one 258-byte
 * match, rows at deflate's largest distance), and a skewed palette whose
 * pixels drawn from a skewed palette; and the Huffman code lengths against
 * package-merge's optimal length-limited codes: the same cost where 15 bits
 * hold the Huffman code, within 0.1 % (random weights) and 2 % (Fibonacci
 * weights, 29 levels unlimited) at 15 bits where the limit binds, 12 % for
 * the Fibonacci weights at 7 bits (the header's code), complete always.
 * Every stream also goes through the strict inflater zstrict.c (every
 * Huffman code complete: issue 38) with no empty block, among them streams
 * whose tokens end exactly at a block's end; and the strict inflater is
 * held to hand-made blocks it must refuse (the empty block with end-of-block
 * its only code, which zlib takes; no distance code; over-subscribed,
 * incomplete, no end-of-block code) or take (one distance code of length
 * 1; zlib's stored, fixed and dynamic blocks). */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <math.h>
#include <zlib.h>

#include "hy_frame.h"
#include "hy_zfast.h"
#include "rcheck.h"
#include "zstrict.h"

static uint32_t rnd_state = 2024u;
static uint32_t rnd(void)
{
    rnd_state = rnd_state * 1664525u + 1013904223u;
    return rnd_state >> 8;
}

/* The rows a PNG decoder expects from the pixels. */
static unsigned char *expected(const uint32_t *px, int w, int h, size_t *n)
{
    *n = (size_t)h * (1 + 3 * (size_t)w);
    unsigned char *e = malloc(*n), *d = e;
    for (int y = 0; y < h; y++) {
        *d++ = 0;
        for (int x = 0; x < w; x++, d += 3) {
            uint32_t p = px[(size_t)y * w + x];
            d[0] = (unsigned char)(p >> 16), d[1] = (unsigned char)(p >> 8), d[2] = (unsigned char)p;
        }
    }
    return e;
}

static int nstreams;

static void check(hy_zfast *z, const char *what, const uint32_t *px, int w, int h)
{
    nstreams++;
    size_t n, zn = hy_zfast_png(z, (const unsigned char *)px, w, h, 4 * w);
    unsigned char *want = expected(px, w, h, &n);
    CHECK(zn > 6, "%s %dx%d: no stream", what, w, h);
    if (zn > 6) {
        const unsigned char *s = hy_zfast_data(z);
        CHECK(s[0] == 0x78 && (s[0] * 256 + s[1]) % 31 == 0, "%s: zlib header %02x %02x", what, s[0], s[1]);
        uLongf got_n = (uLongf)n + 16;
        unsigned char *got = malloc(got_n);
        int rc = uncompress(got, &got_n, s, (uLong)zn);
        CHECK(rc == Z_OK, "%s %dx%d: inflate says %d", what, w, h, rc);
        CHECK(rc != Z_OK || (got_n == n && !memcmp(got, want, n)), "%s %dx%d: inflated %lu bytes, %s", what, w, h,
              (unsigned long)got_n, got_n == n ? "different" : "not the image's size");
        free(got);
        /* the strict decoder: every code complete (a strict inflater, as
         * chromium's createImageBitmap, refuses an incomplete one that zlib
         * takes), and no empty block */
        unsigned char *strict = malloc(n);
        zstrict_info info;
        char why[200];
        rc = zstrict_inflate(s, zn, strict, n, &info, why, sizeof why);
        CHECK(!rc, "%s %dx%d: the strict decoder refuses the stream: %s", what, w, h, why);
        CHECK(rc || (info.out == n && !memcmp(strict, want, n)), "%s %dx%d: strictly inflated %zu bytes, %s", what, w,
              h, info.out, info.out == n ? "different" : "not the image's size");
        CHECK(!info.empty && !info.one_dist && !info.stored && !info.fixed,
              "%s %dx%d: %d empty blocks, %d one-code distance codes, %d stored, %d fixed (%d blocks)", what, w, h,
              info.empty, info.one_dist, info.stored, info.fixed, info.blocks);
        free(strict);
    }
    free(want);
}

static uint32_t *frame(int w, int h) { return calloc((size_t)w * h, 4); }

static int cmp_u64(const void *a, const void *b)
{
    uint64_t x = *(const uint64_t *)a, y = *(const uint64_t *)b;
    return x < y ? -1 : x > y;
}

/* The cost sum freq x length of an optimal code of at most maxlen bits, by
 * package-merge (Larmore and Hirschberg): merge the sorted weights with the
 * pairs of the previous list maxlen - 1 times; the cost is the sum of the
 * 2m - 2 lightest items of the last list (m symbols used). */
static uint64_t optimal_cost(const uint32_t *freq, int n, int maxlen)
{
    uint64_t leaves[HY_ZFAST_MAX_SYMBOLS], list[2 * HY_ZFAST_MAX_SYMBOLS], next[2 * HY_ZFAST_MAX_SYMBOLS];
    int m = 0;
    for (int i = 0; i < n; i++)
        if (freq[i])
            leaves[m++] = freq[i];
    if (m < 2)
        return m ? leaves[0] : 0;
    qsort(leaves, (size_t)m, sizeof *leaves, cmp_u64);
    memcpy(list, leaves, (size_t)m * sizeof *list);
    int nl = m;
    for (int level = 1; level < maxlen; level++) {
        int np = nl / 2, a = 0, b = 0, k = 0;
        while (a < m || b < np) {              /* merge leaves with the packages list[2b] + list[2b + 1] */
            uint64_t pk = b < np ? list[2 * b] + list[2 * b + 1] : UINT64_MAX;
            if (a < m && leaves[a] <= pk)
                next[k++] = leaves[a++];
            else
                next[k++] = pk, b++;
        }
        memcpy(list, next, (size_t)k * sizeof *list);
        nl = k;
    }
    uint64_t cost = 0;
    for (int i = 0; i < 2 * m - 2; i++)
        cost += list[i];
    return cost;
}

/* hy_zfast_code_lengths: within the limit, complete, and its cost within
 * slack of the optimal limited code's. */
static void code_lengths(const char *what, const uint32_t *freq, int n, int maxlen, double slack)
{
    uint8_t len[HY_ZFAST_MAX_SYMBOLS];
    hy_zfast_code_lengths(freq, n, maxlen, len);
    uint64_t kraft = 0, cost = 0, opt = optimal_cost(freq, n, maxlen);
    int deepest = 0, bad = 0;
    for (int i = 0; i < n; i++) {
        bad += (freq[i] != 0) != (len[i] != 0);
        deepest = len[i] > deepest ? len[i] : deepest;
        kraft += len[i] ? (uint64_t)1 << (32 - len[i]) : 0;
        cost += (uint64_t)freq[i] * len[i];
    }
    CHECK(!bad, "%s: %d symbols with a code iff used violated", what, bad);
    CHECK(deepest <= maxlen, "%s: a code of %d bits, limit %d", what, deepest, maxlen);
    CHECK(kraft == (uint64_t)1 << 32, "%s: Kraft sum %.9f, not 1 (incomplete or over-full)", what, kraft / 4294967296.0);
    CHECK(cost >= opt && cost <= opt * slack, "%s: cost %llu against the optimum %llu (allowed x%.3f)", what,
          (unsigned long long)cost, (unsigned long long)opt, slack);
}

/* ---- the strict inflater itself: hand-made blocks it must refuse or take ---- */

typedef struct bitw {
    unsigned char b[512];
    size_t n;
    unsigned acc, nacc;
} bitw;

static void bput(bitw *o, unsigned v, int n)   /* LSB first */
{
    for (int i = 0; i < n; i++, v >>= 1) {
        o->acc |= (v & 1u) << o->nacc;
        if (++o->nacc == 8)
            o->b[o->n++] = (unsigned char)o->acc, o->acc = 0, o->nacc = 0;
    }
}

static void bput_code(bitw *o, unsigned code, int len)   /* Huffman codes: MSB first */
{
    for (int i = len - 1; i >= 0; i--)
        bput(o, (code >> i) & 1u, 1);
}

/* Canonical codes of these lengths (RFC 1951 3.2.2), apart from hy_zfast's. */
static void canon(const uint8_t *len, int n, unsigned *code)
{
    unsigned count[16] = {0}, next[16] = {0}, c = 0;
    for (int i = 0; i < n; i++)
        count[len[i]]++;
    count[0] = 0;
    for (int l = 1; l < 16; l++)
        next[l] = c = (c + count[l - 1]) << 1;
    for (int i = 0; i < n; i++)
        code[i] = len[i] ? next[len[i]]++ : 0;
}

/* A zlib stream of one final dynamic block: literal/length lengths llen
 * (258 of them: literals, end-of-block, length 3), distance lengths dlen (ndist), the code-length code sixteen
 * 4-bit codes (complete), then syms (a match: 257 = length 3, its distance
 * symbol 0 = distance 1 next), then Adler-32 of `data`. */
static size_t craft(unsigned char *out, const uint8_t *llen, const uint8_t *dlen, int ndist, const int *syms,
                    int nsyms, const char *data)
{
    static const uint8_t order[19] = {16, 17, 18, 0, 8, 7, 9, 6, 10, 5, 11, 4, 12, 3, 13, 2, 14, 1, 15};
    bitw o = {.n = 2, .b = {0x78, 0x01}};
    unsigned lc[258], dc[30];
    canon(llen, 258, lc);
    canon(dlen, ndist, dc);
    bput(&o, 1, 1), bput(&o, 2, 2);                    /* BFINAL, dynamic */
    bput(&o, 1, 5), bput(&o, (unsigned)ndist - 1, 5), bput(&o, 15, 4);
    for (int i = 0; i < 19; i++)
        bput(&o, order[i] < 16 ? 4 : 0, 3);            /* code-length symbol s: the 4-bit code s */
    for (int i = 0; i < 258 + ndist; i++)
        bput_code(&o, i < 258 ? llen[i] : dlen[i - 258], 4);
    for (int i = 0; i < nsyms; i++) {
        bput_code(&o, lc[syms[i]], llen[syms[i]]);
        if (syms[i] == 257)
            i++, bput_code(&o, dc[syms[i]], dlen[syms[i]]);
    }
    bput(&o, 0, 7);                                    /* to a byte boundary */
    uint32_t a = (uint32_t)adler32(adler32(0, NULL, 0), (const unsigned char *)data, (uInt)strlen(data));
    memcpy(out, o.b, o.n);
    out[o.n] = (unsigned char)(a >> 24), out[o.n + 1] = (unsigned char)(a >> 16);
    out[o.n + 2] = (unsigned char)(a >> 8), out[o.n + 3] = (unsigned char)a;
    return o.n + 4;
}

/* Whether the strict inflater takes the stream (and inflates `data`);
 * why_has: a word its refusal must name. */
static void strict_case(const char *what, const unsigned char *s, size_t n, const char *data, int take,
                        const char *why_has, int zlib_takes)
{
    unsigned char out[64];
    char why[200];
    zstrict_info info;
    int rc = zstrict_inflate(s, n, out, sizeof out, &info, why, sizeof why);
    if (take)
        CHECK(!rc && info.out == strlen(data) && !memcmp(out, data, info.out), "strict, %s: refused (%s) or wrong bytes",
              what, why);
    else
        CHECK(rc && strstr(why, why_has), "strict, %s: %s, want a refusal naming \"%s\"", what, rc ? why : "taken",
              why_has);
    uLongf zn = sizeof out;
    int zr = uncompress(out, &zn, s, (uLong)n);
    CHECK((zr == Z_OK) == zlib_takes, "strict, %s: zlib %s it", what, zr == Z_OK ? "takes" : "refuses");
}

static void strict_cases(void)
{
    uint8_t ll[258] = {0}, dl[2] = {1, 1};
    unsigned char s[600];
    /* the stream hy_zfast closed frames with: end-of-block alone (Kraft 1/2) */
    ll[256] = 1;
    int eob[] = {256}, aaaa[] = {'a', 257, 0, 256}, ab[] = {'a', 'b', 256};
    size_t n = craft(s, ll, dl, 2, eob, 1, "");
    strict_case("an empty block, end-of-block the only code", s, n, "", 0, "literal/length code of one code", 1);
    /* one distance code of length 1: RFC 1951 3.2.7's case, taken */
    ll['a'] = 1, ll[256] = ll[257] = 2;
    uint8_t d1[1] = {1}, d0[1] = {0};
    n = craft(s, ll, d1, 1, aaaa, 4, "aaaa");
    strict_case("one distance code of length 1", s, n, "aaaa", 1, "", 1);
    zstrict_info info;
    unsigned char out[8];
    zstrict_inflate(s, n, out, sizeof out, &info, NULL, 0);
    CHECK(info.one_dist == 1 && info.dynamic == 1, "strict: one_dist %d, dynamic %d", info.one_dist, info.dynamic);
    /* no distance code at all (the RFC allows it; refused here) */
    ll[256] = 1, ll[257] = 0;
    n = craft(s, ll, d0, 1, eob, 1, "");
    strict_case("no distance code", s, n, "", 0, "distance code incomplete", 1);
    /* three codes of length 1: over-subscribed */
    ll['b'] = 1;
    n = craft(s, ll, dl, 2, ab, 3, "ab");
    strict_case("over-subscribed", s, n, "ab", 0, "over-subscribed", 0);
    /* end-of-block without a code */
    ll[256] = 0;
    n = craft(s, ll, dl, 2, ab, 2, "ab");
    strict_case("end-of-block without a code", s, n, "ab", 0, "end-of-block has no code", 0);
    /* three codes of length 2: incomplete (Kraft 3/4) */
    ll['a'] = ll['b'] = ll[256] = 2;
    n = craft(s, ll, dl, 2, ab, 3, "ab");
    strict_case("three codes of length 2", s, n, "ab", 0, "literal/length code incomplete", 0);
    /* zlib's own streams: stored (level 0), fixed (a short text), dynamic */
    static const char *texts[] = {"stored", "hysteresis", NULL};
    unsigned char big[4000], z[4200];
    for (int i = 0; i < 4000; i++)
        big[i] = (unsigned char)("hysteresis loops "[i % 17] + (i / 300));
    int kinds[3] = {0};
    for (int t = 0; t < 3; t++) {
        const unsigned char *src = texts[t] ? (const unsigned char *)texts[t] : big;
        uLong sn = texts[t] ? (uLong)strlen(texts[t]) : sizeof big;
        uLongf zl = sizeof z;
        compress2(z, &zl, src, sn, t == 0 ? 0 : 9);
        unsigned char *back = malloc(sn);
        char why[200];
        int rc = zstrict_inflate(z, zl, back, sn, &info, why, sizeof why);
        CHECK(!rc && info.out == sn && !memcmp(back, src, sn), "strict, zlib's stream %d refused: %s", t, why);
        kinds[0] += info.stored, kinds[1] += info.fixed, kinds[2] += info.dynamic;
        free(back);
    }
    CHECK(kinds[0] && kinds[1] && kinds[2], "strict: zlib's streams had %d stored, %d fixed, %d dynamic blocks",
          kinds[0], kinds[1], kinds[2]);
}

int main(void)
{
    strict_cases();
    hy_zfast *z = hy_zfast_new();
    CHECK(z != NULL, "hy_zfast_new");
    static const int ws[] = {1, 2, 3, 5, 86, 87, 173, 1280};
    for (size_t k = 0; k < sizeof ws / sizeof ws[0]; k++) {
        int w = ws[k], h = k % 2 ? 7 : 40;
        uint32_t *f = frame(w, h);
        for (size_t i = 0; i < (size_t)w * h; i++)
            f[i] = 0xffffffffu;
        check(z, "white", f, w, h);
        for (size_t i = 0; i < (size_t)w * h; i++)
            f[i] = rnd() ^ rnd() << 8;
        check(z, "noise", f, w, h);
        for (size_t i = 0; i < (size_t)w * h; i++)  /* the colour white, the unused byte anything */
            f[i] = (rnd() << 24) | 0xffffffu;
        check(z, "white, unused byte random", f, w, h);
        free(f);
    }
    /* plot-like: white, axes, a few anti-aliased curves, text-like blocks
     * repeated across the frame, rows equal to the row above */
    int w = 1280, h = 720;
    uint32_t *f = frame(w, h);
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            uint32_t p = 0xffffffu;
            if (x == 100 || y == 650 || (x > 100 && y > 600 && x % 80 == 0 && y < 610))
                p = 0x202020u;
            for (int c = 0; c < 3; c++) {      /* curves: y = a + b sin, 3 px wide with grey edges */
                double cy = 300 + 40 * c + 120.0 * sin(x / (60.0 + 20 * c));
                double d = y - cy;
                if (d > -2 && d < 2)
                    p = d > -1 && d < 1 ? 0xd55e00u - (uint32_t)c * 0x101010u : 0xf0b090u + (uint32_t)c;
            }
            if (y >= 20 && y < 34 && x >= 200 && x < 600 && ((x / 7 + y) % 5 == 0 || (x * 3 + y) % 11 == 0))
                p = 0x000000u + (uint32_t)(x % 7) * 0x111111u;
            f[(size_t)y * w + x] = p | 0xff000000u;
        }
    for (int y = 660; y < 680; y++)            /* the same "glyphs" again further down */
        memcpy(f + (size_t)y * w + 700, f + (size_t)(y - 640) * w + 200, 400 * 4);
    check(z, "plot", f, w, h);
    /* the same bytes for the same frame whatever the encoder made before:
     * tests/gl/test_assemble.sh's pieces and shards (it caught hash table
     * entries left from the last frame) */
    free(f);
    /* tokens ending exactly at a block boundary (16,384 tokens a block):
     * a 1-pixel-wide column of colours each unlike the one above is 4
     * literals a row (filter byte, R, G, B), so 4,096 rows end the first
     * block with the last pixel and 8,192 the second.  The encoder of
     * 2026-11 closed such a stream with an empty final block whose
     * literal/length code was end-of-block alone (length 1: Kraft sum 0.5):
     * zlib takes it, the strict decoder and chromium refuse it (issue 38).
     * The heights around the boundaries too. */
    static const int hs[] = {4095, 4096, 4097, 8191, 8192, 8193, 12288};
    for (size_t k = 0; k < sizeof hs / sizeof hs[0]; k++) {
        f = frame(1, hs[k]);
        for (int y = 0; y < hs[k]; y++)
            f[y] = (uint32_t)y * 0x010203u + 0x102030u;   /* each row unlike the row above */
        check(z, "a block boundary at the end", f, 1, hs[k]);
        free(f);
    }
    /* the degenerate alphabets: a block with no distance (one black pixel:
     * literals 0 and end-of-block only), one distance (a white row: a run at
     * distance 3), one literal value (a grey column, each row a copy of the
     * one above after the first) */
    uint32_t px1 = 0;
    check(z, "one black pixel (no distance)", &px1, 1, 1);
    f = frame(300, 1);
    for (int x = 0; x < 300; x++)
        f[x] = 0xffffffu;
    check(z, "a white row (one distance)", f, 300, 1);
    free(f);
    f = frame(1, 50);
    for (int y = 0; y < 50; y++)
        f[y] = 0x000000u;
    check(z, "a black column (one literal value, one distance)", f, 1, 50);
    free(f);
    /* the widest rows: one row apart is 32,767 bytes, deflate's window 32,768 */
    w = 10922, h = 4;
    f = frame(w, h);
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++)
            f[(size_t)y * w + x] = y == 0 || x % 97 ? (uint32_t)(x * 2654435761u) >> 8 : 0x123456u;
    check(z, "rows 32,767 bytes apart", f, w, h);
    free(f);
    CHECK(hy_zfast_png(z, (const unsigned char *)"", 10923, 1, 4 * 10923) == 0, "a row wider than the window is refused");
    /* a skewed palette: byte value k with weight Fibonacci(k) */
    w = 600, h = 60;
    f = frame(w, h);
    uint32_t fib[24] = {1, 1}, total = 2;
    for (int i = 2; i < 24; i++)
        total += fib[i] = fib[i - 1] + fib[i - 2];
    for (size_t i = 0; i < (size_t)w * h; i++) {
        uint32_t p = 0;
        for (int c = 0; c < 3; c++) {
            uint32_t r = rnd() % total, k = 0;
            while (r >= fib[k])
                r -= fib[k++];
            p = p << 8 | k;
        }
        f[i] = p;
    }
    check(z, "skewed palette", f, w, h);
    free(f);
    /* code lengths: weights 500..1000 (9 levels: the Huffman code itself,
     * optimal), weights 1..1000 (the limit binds a little), Fibonacci weights
     * (an unlimited code 29 levels deep) under 15 and 7 bits */
    uint32_t fq[HY_ZFAST_MAX_SYMBOLS] = {0};
    for (int i = 0; i < HY_ZFAST_MAX_SYMBOLS; i++)
        fq[i] = i % 7 == 3 ? 0 : 500 + rnd() % 501;
    code_lengths("weights 500..1000", fq, HY_ZFAST_MAX_SYMBOLS, 15, 1.0);
    for (int i = 0; i < HY_ZFAST_MAX_SYMBOLS; i++)
        fq[i] = i % 7 == 3 ? 0 : 1 + rnd() % 1000;
    code_lengths("weights 1..1000", fq, HY_ZFAST_MAX_SYMBOLS, 15, 1.001);
    uint32_t fb[30] = {1, 1};
    for (int i = 2; i < 30; i++)
        fb[i] = fb[i - 1] + fb[i - 2];
    code_lengths("Fibonacci weights, 15 bits", fb, 30, 15, 1.02);
    /* the clamp-and-move heuristic gives 1, 2, 3 and sixteen 7s here (11 %
     * over the optimum); the 7-bit code only codes a block's header of at
     * most 316 code lengths, so this costs a few bytes a block at worst */
    code_lengths("Fibonacci weights, 7 bits (19 symbols)", fb + 11, 19, 7, 1.12);
    uint32_t one[5] = {0, 0, 9, 0, 0}, two[3] = {5, 0, 1};
    uint8_t l1[5], l2[3];
    hy_zfast_code_lengths(one, 5, 15, l1);
    hy_zfast_code_lengths(two, 3, 15, l2);
    CHECK(l1[2] == 1 && !l1[0] && !l1[4], "one symbol: length %d", l1[2]);
    CHECK(l2[0] == 1 && l2[2] == 1 && !l2[1], "two symbols: lengths %d %d", l2[0], l2[2]);
    hy_zfast_free(z);
    printf("zfast: %d streams inflated and compared\n", nstreams);
    return hy_test_finish("zfast");
}
