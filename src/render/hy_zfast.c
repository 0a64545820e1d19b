/* SPDX-License-Identifier: MIT */
/* hy_zfast.c: see hy_zfast.h.  Deflate format: RFC 1951; zlib wrapper: RFC 1950. */
#include "hy_zfast.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "hy_config.h"
#include "hy_pixels.h"
#if HY_HAVE_LIBDEFLATE
#include <libdeflate.h>
#else
#include <zlib.h>
#endif

#define NLIT HY_ZFAST_MAX_SYMBOLS                      /* literal/length symbols 0..285 */
#define NDIST 30
#define NCL 19                         /* code-length symbols */
#define BLOCK_TOKENS 16384             /* tokens per deflate block (32768: 0.5 % larger, 6 % faster) */
#define HASH_BITS 14
#define MATCH_FLAG 0x80000000u         /* token: literal byte, or flag | (len - 3) << 16 | (dist - 1) */

struct hy_zfast {
    uint32_t *tok;                     /* the block's tokens */
    size_t ntok, tokcap;
    unsigned char *row;                /* the current row as PNG bytes: filter 0, R, G, B, ... */
    size_t rowcap;
    unsigned char *out;
    size_t outcap, outlen;
    uint64_t acc;                      /* bit writer: bits not yet stored, LSB first */
    int nacc;
    int failed;
    uint32_t lfreq[NLIT], dfreq[NDIST];
    uint32_t hash[1u << HASH_BITS];   /* pixel pair -> 1 + its pixel index (0: none) */
};

/* ---- symbols ---- */

static const uint16_t len_base[29] = {3,  4,  5,  6,  7,  8,  9,  10, 11,  13,  15,  17,  19,  23, 27,
                                      31, 35, 43, 51, 59, 67, 83, 99, 115, 131, 163, 195, 227, 258};
static const uint8_t len_extra[29] = {0, 0, 0, 0, 0, 0, 0, 0, 1, 1, 1, 1, 2, 2, 2,
                                      2, 3, 3, 3, 3, 4, 4, 4, 4, 5, 5, 5, 5, 0};
static const uint16_t dist_base[30] = {1,   2,   3,   4,   5,   7,    9,    13,   17,   25,   33,   49,   65,    97,    129,
                                       193, 257, 385, 513, 769, 1025, 1537, 2049, 3073, 4097, 6145, 8193, 12289, 16385, 24577};
static const uint8_t dist_extra[30] = {0, 0, 0, 0, 1, 1, 2, 2, 3, 3, 4, 4, 5, 5, 6,
                                       6, 7, 7, 8, 8, 9, 9, 10, 10, 11, 11, 12, 12, 13, 13};
static const uint8_t cl_order[NCL] = {16, 17, 18, 0, 8, 7, 9, 6, 10, 5, 11, 4, 12, 3, 13, 2, 14, 1, 15};

static uint8_t len_codes[259];         /* length 3..258 -> its code 0..28 (symbol 257 + code) */

static void init_len_codes(void)
{
    for (int c = 0; c < 29; c++)
        for (unsigned l = len_base[c]; l <= 258 && (c == 28 || l < len_base[c + 1]); l++)
            len_codes[l] = (uint8_t)c;
}

static inline int len_code(unsigned len) { return len_codes[len]; }

static int dist_code(unsigned d)      /* 1..32768 -> 0..29 */
{
    if (d <= 4)
        return (int)d - 1;
    unsigned v = d - 1;
    int n = 31 - __builtin_clz(v);    /* v >= 4: n >= 2 */
    return 2 * n + (int)((v >> (n - 1)) & 1);
}

/* ---- Huffman code lengths, at most maxlen bits, complete ---- */

typedef struct hnode {
    uint32_t freq;
    int16_t left, right;               /* children: < n leaf symbols, else internal n + k; -1 leaf */
    int16_t sym;
} hnode;

static int cmp_leaf(const void *a, const void *b)
{
    const hnode *x = a, *y = b;
    return x->freq != y->freq ? (x->freq < y->freq ? -1 : 1) : x->sym - y->sym;
}

void hy_zfast_code_lengths(const uint32_t *freq, int n, int maxlen, uint8_t *len)
{
    hnode leaf[NLIT], inner[NLIT];
    int nl = 0;
    memset(len, 0, (size_t)n);
    for (int s = 0; s < n; s++)
        if (freq[s])
            leaf[nl++] = (hnode){freq[s], -1, -1, (int16_t)s};
    if (nl == 0)
        return;
    if (nl == 1) {
        len[leaf[0].sym] = 1;
        return;
    }
    qsort(leaf, (size_t)nl, sizeof *leaf, cmp_leaf);
    /* two queues: leaves ascending, inner nodes made in ascending order */
    int li = 0, ii = 0, ni = 0;
    while (nl - li + ni - ii > 1) {
        int16_t pick[2];
        uint32_t f = 0;
        for (int k = 0; k < 2; k++) {
            if (li < nl && (ii >= ni || leaf[li].freq <= inner[ii].freq))
                pick[k] = (int16_t)li, f += leaf[li++].freq;
            else
                pick[k] = (int16_t)(NLIT + ii), f += inner[ii++].freq;
        }
        inner[ni++] = (hnode){f, pick[0], pick[1], -1};
    }
    /* depths from the root (the last inner node) down */
    uint8_t depth[NLIT];
    depth[ni - 1] = 0;
    int maxd = 0;
    for (int k = ni - 1; k >= 0; k--)
        for (int c = 0; c < 2; c++) {
            int16_t ch = c ? inner[k].right : inner[k].left;
            if (ch >= NLIT)
                depth[ch - NLIT] = (uint8_t)(depth[k] + 1);
            else {
                int d = depth[k] + 1;
                len[leaf[ch].sym] = (uint8_t)d;
                maxd = d > maxd ? d : maxd;
            }
        }
    if (maxd <= maxlen)
        return;
    /* too deep: count the lengths with the deep ones clamped, move leaves
     * down until Kraft's sum 2^-len is 1 again (each step: a leaf at the
     * deepest level below the limit goes one down, with one clamped leaf as
     * its sibling), then give the shortest lengths to the most frequent */
    uint32_t count[16] = {0}, k = 0, full = 1u << maxlen;
    for (int s = 0; s < n; s++)
        if (len[s]) {
            int l = len[s] > maxlen ? maxlen : len[s];
            count[l]++;
            k += 1u << (maxlen - l);
        }
    for (; k > full; k--) {
        int b = maxlen - 1;
        while (!count[b])
            b--;
        count[b]--, count[b + 1] += 2, count[maxlen]--;
    }
    for (int i = 0; i < nl; i++)      /* leaf[] is ascending: the most frequent last */
        for (int l = 1; l <= maxlen; l++)
            if (count[l]) {
                count[l]--;
                len[leaf[nl - 1 - i].sym] = (uint8_t)l;
                break;
            }
}

/* Canonical codes (RFC 1951 3.2.2), bit-reversed for the LSB-first stream. */
static void huff_codes(const uint8_t *len, int n, uint16_t *code)
{
    uint16_t count[16] = {0}, next[16];
    for (int s = 0; s < n; s++)
        count[len[s]]++;
    count[0] = 0;
    unsigned c = 0;
    for (int b = 1; b < 16; b++) {
        c = (c + count[b - 1]) << 1;
        next[b] = (uint16_t)c;
    }
    for (int s = 0; s < n; s++) {
        if (!len[s]) {
            code[s] = 0;
            continue;
        }
        unsigned v = next[len[s]]++, r = 0;
        for (int b = 0; b < len[s]; b++)
            r |= ((v >> b) & 1u) << (len[s] - 1 - b);
        code[s] = (uint16_t)r;
    }
}

/* ---- bit writer ---- */

static void put(hy_zfast *z, uint32_t v, int n)
{
    z->acc |= (uint64_t)v << z->nacc;
    z->nacc += n;
    if (z->nacc >= 32) {
        unsigned char *o = z->out + z->outlen;
        o[0] = (unsigned char)z->acc, o[1] = (unsigned char)(z->acc >> 8);
        o[2] = (unsigned char)(z->acc >> 16), o[3] = (unsigned char)(z->acc >> 24);
        z->outlen += 4;
        z->acc >>= 32;
        z->nacc -= 32;
    }
}

static int reserve(hy_zfast *z, size_t more)
{
    if (z->outcap - z->outlen >= more)
        return 0;
    size_t cap = z->outcap ? 2 * z->outcap : 1u << 18;
    while (cap - z->outlen < more)
        cap *= 2;
    unsigned char *o = realloc(z->out, cap);
    if (!o)
        return -1;
    z->out = o, z->outcap = cap;
    return 0;
}

/* ---- blocks ---- */

/* When fewer than two of the n symbols are used, symbols a and b get a
 * frequency of 1 if they have none: every code then has two codes or more
 * and hy_zfast_code_lengths makes it complete.  A code of one symbol would
 * be one code of length 1, half of the code space unused: zlib's inflate
 * takes that, strict inflaters (chromium's createImageBitmap among them)
 * refuse it.  zlib's deflate likewise forces two codes in every tree
 * (trees.c, build_tree; it adds symbol 0, or the one after the used one). */
static void two_codes(uint32_t *freq, int n, int a, int b)
{
    int used = 0;
    for (int s = 0; s < n && used < 2; s++)
        used += freq[s] > 0;
    if (used < 2)
        freq[a] += !freq[a], freq[b] += !freq[b];
}

/* The first hlit literal/length code lengths and the first hdist distance
 * code lengths, run-length coded (RFC 1951 3.2.7): their code-length symbols
 * (0..18) in sym and each one's extra bits in extra (both at least
 * NLIT + NDIST long); returns how many symbols. */
static int rle_code_lengths(const uint8_t *llen, int hlit, const uint8_t *dlen, int hdist,
                            uint8_t *sym, uint8_t *extra)
{
    uint8_t all[NLIT + NDIST];
    int n = 0, ns = 0;
    for (int s = 0; s < hlit; s++)
        all[n++] = llen[s];
    for (int s = 0; s < hdist; s++)
        all[n++] = dlen[s];
    for (int i = 0; i < n;) {
        int v = all[i], run = 1;
        while (i + run < n && all[i + run] == v)
            run++;
        i += run;
        if (!v) {
            while (run >= 11) {
                int r = run > 138 ? 138 : run;
                sym[ns] = 18, extra[ns++] = (uint8_t)(r - 11), run -= r;
            }
            if (run >= 3)
                sym[ns] = 17, extra[ns++] = (uint8_t)(run - 3), run = 0;
        } else {
            sym[ns] = (uint8_t)v, extra[ns++] = 0, run--;
            while (run >= 3) {
                int r = run > 6 ? 6 : run;
                sym[ns] = 16, extra[ns++] = (uint8_t)(r - 3), run -= r;
            }
        }
        while (run-- > 0)
            sym[ns] = (uint8_t)v, extra[ns++] = 0;
    }
    return ns;
}

/* Writes the block of z's tokens with its own dynamic codes; final: BFINAL.
 * Every code is complete: the literal/length code always (a block has a
 * token besides end-of-block, and two_codes guards it anyway), the distance
 * code with symbols 0 and 1 added when a block has no distance or one, the
 * code-length code with 0 and 8 added when one symbol would do. */
static void write_block(hy_zfast *z, int final)
{
    /* at most 15 + 5 + 15 + 13 bits a token, plus the header */
    if (z->failed || reserve(z, z->ntok * 6 + 1024)) {
        z->failed = 1;
        return;
    }
    z->lfreq[256]++;                   /* end of block */
    two_codes(z->lfreq, NLIT, 0, 1);
    two_codes(z->dfreq, NDIST, 0, 1);
    uint8_t llen[NLIT], dlen[NDIST];
    uint16_t lcode[NLIT], dcode[NDIST];
    hy_zfast_code_lengths(z->lfreq, NLIT, 15, llen);
    hy_zfast_code_lengths(z->dfreq, NDIST, 15, dlen);
    huff_codes(llen, NLIT, lcode);
    huff_codes(dlen, NDIST, dcode);
    int hlit = NLIT, hdist = NDIST;
    while (hlit > 257 && !llen[hlit - 1])
        hlit--;
    while (hdist > 1 && !dlen[hdist - 1])
        hdist--;
    /* the code lengths, run-length coded with symbols 16, 17, 18 */
    uint8_t sym[NLIT + NDIST], extra[NLIT + NDIST];
    int ns = rle_code_lengths(llen, hlit, dlen, hdist, sym, extra);
    uint32_t cfreq[NCL] = {0};
    for (int i = 0; i < ns; i++)
        cfreq[sym[i]]++;
    two_codes(cfreq, NCL, 0, 8);
    uint8_t clen[NCL];
    uint16_t ccode[NCL];
    hy_zfast_code_lengths(cfreq, NCL, 7, clen);
    huff_codes(clen, NCL, ccode);
    int hclen = NCL;
    while (hclen > 4 && !clen[cl_order[hclen - 1]])
        hclen--;
    put(z, (uint32_t)final | 2u << 1, 3);   /* BFINAL, BTYPE 10: dynamic codes */
    put(z, (uint32_t)(hlit - 257), 5);
    put(z, (uint32_t)(hdist - 1), 5);
    put(z, (uint32_t)(hclen - 4), 4);
    for (int i = 0; i < hclen; i++)
        put(z, clen[cl_order[i]], 3);
    for (int i = 0; i < ns; i++) {
        put(z, ccode[sym[i]], clen[sym[i]]);
        if (sym[i] >= 16)
            put(z, extra[i], sym[i] == 16 ? 2 : sym[i] == 17 ? 3 : 7);
    }
    for (size_t i = 0; i < z->ntok; i++) {
        uint32_t t = z->tok[i];
        if (!(t & MATCH_FLAG)) {
            put(z, lcode[t], llen[t]);
            continue;
        }
        unsigned len = ((t >> 16) & 0xff) + 3, dist = (t & 0x7fff) + 1;
        int lc = len_code(len), dc = dist_code(dist);
        put(z, lcode[257 + lc], llen[257 + lc]);
        if (len_extra[lc])
            put(z, len - len_base[lc], len_extra[lc]);
        put(z, dcode[dc], dlen[dc]);
        if (dist_extra[dc])
            put(z, dist - dist_base[dc], dist_extra[dc]);
    }
    put(z, lcode[256], llen[256]);
    z->ntok = 0;
    memset(z->lfreq, 0, sizeof z->lfreq);
    memset(z->dfreq, 0, sizeof z->dfreq);
}

/* Writes the block once it holds BLOCK_TOKENS tokens.  Called before a step
 * adds its tokens, never after the last: the final block holds the frame's
 * last tokens, so no block is empty (an empty final block, written when the
 * tokens ended exactly at a block's end, had end-of-block as its only
 * literal/length code: issue 38).  Nonzero when memory ran out. */
static inline int block_full(hy_zfast *z)
{
    if (z->ntok < BLOCK_TOKENS)
        return 0;
    write_block(z, 0);
    return z->failed;                  /* out of memory: the tokens are not stored on */
}

static inline void literal(hy_zfast *z, unsigned b)
{
    z->tok[z->ntok++] = b;
    z->lfreq[b]++;
}

/* A match of npx whole pixels (3 npx bytes) at byte distance dist, as
 * tokens of at most 258 bytes (86 pixels; every piece a multiple of 3). */
static void match(hy_zfast *z, unsigned npx, unsigned dist)
{
    int dc = dist_code(dist);
    for (unsigned left = 3 * npx; left;) {
        unsigned len = left > 258 ? 258 : left;
        left -= len;
        z->tok[z->ntok++] = MATCH_FLAG | (len - 3) << 16 | (dist - 1);
        z->lfreq[257 + len_code(len)]++;
        z->dfreq[dc]++;
    }
}

static inline int same(uint32_t a, uint32_t b) { return !((a ^ b) & 0xffffffu); }

/* How many of the first n pixels of a and b are the same colour: two pixels
 * a step while their words are equal, then pixel by pixel on the colour. */
static inline unsigned same_run(const uint32_t *a, const uint32_t *b, unsigned n)
{
    unsigned i = 0;
    for (uint64_t u, v; i + 2 <= n; i += 2) {
        memcpy(&u, a + i, 8), memcpy(&v, b + i, 8);
        if (u != v)
            break;
    }
    while (i < n && same(a[i], b[i]))
        i++;
    return i;
}

/* How many of the first n pixels of a are p's colour. */
static inline unsigned same_as(const uint32_t *a, uint32_t p, unsigned n)
{
    uint64_t pp = (uint64_t)p << 32 | p;
    unsigned i = 0;
    for (uint64_t u; i + 2 <= n; i += 2) {
        memcpy(&u, a + i, 8);
        if (u != pp)
            break;
    }
    while (i < n && same(a[i], p))
        i++;
    return i;
}

/* One row of pixels as PNG bytes R, G, B. */
static void to_rgb(const uint32_t *px, int w, unsigned char *d, int le)
{
    int x = 0;
    if (le)                            /* four pixels as three little-endian words */
        for (; x + 4 <= w; x += 4, d += 12) {
            uint32_t t0 = __builtin_bswap32(px[x]) >> 8, t1 = __builtin_bswap32(px[x + 1]) >> 8;
            uint32_t t2 = __builtin_bswap32(px[x + 2]) >> 8, t3 = __builtin_bswap32(px[x + 3]) >> 8;
            uint32_t o0 = t0 | t1 << 24, o1 = t1 >> 8 | t2 << 16, o2 = t2 >> 16 | t3 << 8;
            memcpy(d, &o0, 4), memcpy(d + 4, &o1, 4), memcpy(d + 8, &o2, 4);   /* three stores, no stack copy */
        }
    for (; x < w; x++, d += 3) {       /* the word 0x00RRGGBB, either byte order */
        uint32_t p = px[x];
        d[0] = (unsigned char)(p >> 16), d[1] = (unsigned char)(p >> 8), d[2] = (unsigned char)p;
    }
}

static inline uint32_t pair_hash(uint32_t a, uint32_t b)
{
    return (((a & 0xffffffu) * 2654435761u) ^ ((b & 0xffffffu) * 2246822519u)) >> (32 - HASH_BITS);
}

hy_zfast *hy_zfast_new(void) { return calloc(1, sizeof(hy_zfast)); }

void hy_zfast_free(hy_zfast *z)
{
    if (!z)
        return;
    free(z->tok);
    free(z->row);
    free(z->out);
    free(z);
}

const unsigned char *hy_zfast_data(const hy_zfast *z) { return z->out; }

/* Grows z's token buffer (a block's tokens plus a row's) and its row buffer
 * to rows of rowb bytes; nonzero, with the short buffer's capacity 0, when
 * memory ran out. */
static int grow_buffers(hy_zfast *z, size_t rowb)
{
    if (z->tokcap < BLOCK_TOKENS + rowb) {   /* a step adds at most 3 literals or rowb / 86 + 1 matches */
        free(z->tok);
        if (!(z->tok = malloc((BLOCK_TOKENS + rowb) * sizeof *z->tok)))
            return z->tokcap = 0, 1;
        z->tokcap = BLOCK_TOKENS + rowb;
    }
    if (z->rowcap < rowb) {
        free(z->row);
        if (!(z->row = malloc(rowb)))
            return z->rowcap = 0, 1;
        z->rowcap = rowb;
    }
    return 0;
}

/* Ends the stream after its final block: the last bits to a byte boundary and
 * the Adler-32 of the data (RFC 1950).  The stream's length, or 0 when writing
 * failed or memory ran out. */
static size_t finish_stream(hy_zfast *z, uint32_t adler)
{
    if (z->failed || reserve(z, 16))
        return 0;
    while (z->nacc > 0) {             /* the last bits, to a byte boundary */
        z->out[z->outlen++] = (unsigned char)z->acc;
        z->acc >>= 8;
        z->nacc -= 8;
    }
    z->nacc = 0, z->acc = 0;
    unsigned char *o = z->out + z->outlen;
    o[0] = (unsigned char)(adler >> 24), o[1] = (unsigned char)(adler >> 16);
    o[2] = (unsigned char)(adler >> 8), o[3] = (unsigned char)adler;
    z->outlen += 4;
    return z->outlen;
}

size_t hy_zfast_png(hy_zfast *z, const unsigned char *xrgb, int w, int h, int stride)
{
    size_t rowb = 1 + 3 * (size_t)w;
    if (w < 1 || h < 1 || rowb > 32768)
        return 0;
    if (grow_buffers(z, rowb))
        return 0;
    z->outlen = 0, z->acc = 0, z->nacc = 0, z->failed = 0, z->ntok = 0;
    memset(z->hash, 0, sizeof z->hash);   /* the same bytes for the same frame, whatever came before */
    memset(z->lfreq, 0, sizeof z->lfreq);
    memset(z->dfreq, 0, sizeof z->dfreq);
    if (reserve(z, 2))
        return 0;
    z->out[z->outlen++] = 0x78, z->out[z->outlen++] = 0x01;  /* deflate, 32 kB window, fastest */
#if HY_HAVE_LIBDEFLATE
    uint32_t adler = 1;
#else
    uLong adler = adler32(0, NULL, 0);
#endif
    unsigned char *row = z->row;
    int le = hy_little_endian();
    if (!len_codes[258])
        init_len_codes();
    for (int y = 0; y < h; y++) {
        const uint32_t *px = (const uint32_t *)(const void *)(xrgb + (size_t)y * (size_t)stride);
        const uint32_t *up = y ? (const uint32_t *)(const void *)(xrgb + (size_t)(y - 1) * (size_t)stride) : NULL;
        row[0] = 0;
        to_rgb(px, w, row + 1, le);
#if HY_HAVE_LIBDEFLATE
        adler = libdeflate_adler32(adler, row, rowb);
#else
        adler = adler32(adler, row, (uInt)rowb);
#endif
        if (block_full(z))
            return 0;
        literal(z, 0);                 /* filter type: none */
        size_t base = (size_t)y * rowb + 1;   /* stream offset of the row's first pixel */
        for (int x = 0; x < w;) {
            if (x && block_full(z))    /* (at x = 0: checked before the filter byte) */
                return 0;
            uint32_t p = px[x];
            unsigned run = 0, above = 0;
            if (up && same(up[x], p))
                above = same_run(px + x, up + x, (unsigned)(w - x));
            if (x && same(px[x - 1], p))
                run = same_as(px + x, p, (unsigned)(w - x));
            /* a tie goes to the run: distance 3 has no extra bits, a row's 9 to 13 */
            unsigned best = run >= above ? run : above, dist = run >= above ? 3u : (unsigned)rowb;
            if (best < 2 && x + 1 < w) {   /* an earlier pixel pair */
                uint32_t hsh = pair_hash(p, px[x + 1]), q = z->hash[hsh];
                z->hash[hsh] = (uint32_t)((size_t)y * (size_t)w + (size_t)x + 1);
                if (q--) {
                    size_t qy = q / (size_t)w, qx = q % (size_t)w, qoff = qy * rowb + 1 + 3 * qx;
                    size_t off = base + 3 * (size_t)x;
                    if (qoff < off && off - qoff <= 32768 && qy <= (size_t)y) {
                        const uint32_t *qp = (const uint32_t *)(const void *)(xrgb + qy * (size_t)stride) + qx;
                        size_t lim = (size_t)w - qx < (size_t)(w - x) ? (size_t)w - qx : (size_t)(w - x);
                        unsigned n = same_run(px + x, qp, (unsigned)lim);
                        if (n >= 2 && n > best)
                            best = n, dist = (unsigned)(off - qoff);
                    }
                }
            }
            if (best >= 2 || run == 1) {  /* one repeated pixel: shorter as a match at distance 3 */
                if (best < 2)
                    best = 1, dist = 3;
                match(z, best, dist);
                x += (int)best;
            } else {
                const unsigned char *d = row + 1 + 3 * (size_t)x;
                literal(z, d[0]), literal(z, d[1]), literal(z, d[2]);
                x++;
            }
        }
    }
    write_block(z, 1);
    return finish_stream(z, (uint32_t)adler);
}
