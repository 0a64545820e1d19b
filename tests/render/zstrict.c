/* SPDX-License-Identifier: MIT */
/* zstrict.c: see zstrict.h.  A canonical-code decoder that reads one bit at
 * a time (RFC 1951 3.2.2: codes of one length are consecutive integers), so
 * every check is a few lines next to the rule it enforces. */
#include "zstrict.h"

#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

typedef struct zs {
    const unsigned char *in;
    size_t n, pos;                     /* next byte */
    uint32_t bits;                     /* bits not yet used, LSB first */
    int nbits;
    unsigned char *out;
    size_t outcap, outlen;
    char *why;
    size_t whylen;
    int bad;
} zs;

typedef struct code {
    uint16_t count[16];                /* codes of each length; count[0] unused */
    uint16_t sym[320];                 /* symbols in canonical order */
} code;

static int fail(zs *s, const char *fmt, ...)
{
    if (!s->bad && s->why && s->whylen) {
        va_list ap;
        va_start(ap, fmt);
        int k = vsnprintf(s->why, s->whylen, fmt, ap);
        va_end(ap);
        if (k >= 0 && (size_t)k < s->whylen)
            snprintf(s->why + k, s->whylen - (size_t)k, " (at byte %zu)", s->pos);
    }
    s->bad = 1;
    return -1;
}

static int bits(zs *s, int need, unsigned *v)
{
    while (s->nbits < need) {
        if (s->pos >= s->n)
            return fail(s, "the stream ends inside a block");
        s->bits |= (uint32_t)s->in[s->pos++] << s->nbits;
        s->nbits += 8;
    }
    *v = s->bits & ((1u << need) - 1);
    s->bits >>= need;
    s->nbits -= need;
    return 0;
}

/* The canonical code of these lengths.  Returns 0 when it is complete; 1 when
 * it is the one code of length 1 (the caller decides whether that may be);
 * -1 (with the reason) when over-subscribed, incomplete otherwise, or empty. */
static int build(zs *s, code *c, const uint8_t *len, int n, const char *what)
{
    uint16_t offs[16];
    memset(c->count, 0, sizeof c->count);
    for (int i = 0; i < n; i++)
        c->count[len[i]]++;
    c->count[0] = 0;
    int32_t left = 1, used = 0;        /* codes of the current length not yet given */
    for (int l = 1; l < 16; l++) {
        left = 2 * left - c->count[l];
        used += c->count[l];
        if (left < 0)
            return fail(s, "%s code over-subscribed (%d codes, %d too many at length %d)", what, used, -left, l);
    }
    offs[1] = 0;
    for (int l = 1; l < 15; l++)
        offs[l + 1] = (uint16_t)(offs[l] + c->count[l]);
    for (int i = 0; i < n; i++)
        if (len[i])
            c->sym[offs[len[i]]++] = (uint16_t)i;
    if (!left)
        return 0;
    if (used == 1 && c->count[1] == 1)
        return 1;
    return fail(s, "%s code incomplete: %d codes, Kraft sum %.6f", what, used, 1.0 - left / 32768.0);
}

static int decode(zs *s, const code *c, int *sym)
{
    int cd = 0, first = 0, index = 0;
    for (int l = 1; l < 16; l++) {
        unsigned b;
        if (bits(s, 1, &b))
            return -1;
        cd |= (int)b;
        int count = c->count[l];
        if (cd - count < first) {
            *sym = c->sym[index + (cd - first)];
            return 0;
        }
        index += count, first += count;
        first <<= 1, cd <<= 1;
    }
    return fail(s, "a code word that is not in the code");   /* only the one-code case can get here */
}

static const uint16_t lbase[29] = {3,  4,  5,  6,  7,  8,  9,  10, 11,  13,  15,  17,  19,  23, 27,
                                   31, 35, 43, 51, 59, 67, 83, 99, 115, 131, 163, 195, 227, 258};
static const uint8_t lextra[29] = {0, 0, 0, 0, 0, 0, 0, 0, 1, 1, 1, 1, 2, 2, 2, 2, 3, 3, 3, 3, 4, 4, 4, 4, 5, 5, 5, 5, 0};
static const uint16_t dbase[30] = {1,   2,   3,   4,   5,   7,    9,    13,   17,   25,   33,   49,   65,    97,    129,
                                   193, 257, 385, 513, 769, 1025, 1537, 2049, 3073, 4097, 6145, 8193, 12289, 16385, 24577};
static const uint8_t dextra[30] = {0, 0, 0, 0, 1, 1, 2, 2, 3, 3, 4, 4, 5, 5, 6, 6, 7, 7, 8, 8, 9, 9, 10, 10, 11, 11, 12, 12, 13, 13};

/* The symbols of one block up to end-of-block; *nsym counts them. */
static int codes(zs *s, const code *lit, const code *dist, int *nsym)
{
    for (*nsym = 0;; ++*nsym) {
        int sym;
        if (decode(s, lit, &sym))
            return -1;
        if (sym < 256) {
            if (s->outlen >= s->outcap)
                return fail(s, "more output than the %zu bytes expected", s->outcap);
            s->out[s->outlen++] = (unsigned char)sym;
            continue;
        }
        if (sym == 256)
            return 0;
        sym -= 257;
        if (sym >= 29)
            return fail(s, "length symbol %d (286 and 287 are invalid)", sym + 257);
        unsigned e = 0, d = 0;
        if (bits(s, lextra[sym], &e))
            return -1;
        size_t len = lbase[sym] + e;
        int ds;
        if (decode(s, dist, &ds))
            return -1;
        if (ds >= 30)
            return fail(s, "distance symbol %d (30 and 31 are invalid)", ds);
        if (bits(s, dextra[ds], &d))
            return -1;
        size_t dd = dbase[ds] + d;
        if (dd > s->outlen)
            return fail(s, "distance %zu before the start (%zu bytes out)", dd, s->outlen);
        if (len > s->outcap - s->outlen)
            return fail(s, "more output than the %zu bytes expected", s->outcap);
        for (size_t i = 0; i < len; i++, s->outlen++)
            s->out[s->outlen] = s->out[s->outlen - dd];
    }
}

static int fixed_block(zs *s, int *nsym)
{
    static code lit, dist;
    static int done;
    if (!done) {
        uint8_t l[288];
        memset(l, 8, 144), memset(l + 144, 9, 112), memset(l + 256, 7, 24), memset(l + 280, 8, 8);
        zs t = {0};
        build(&t, &lit, l, 288, "fixed");
        memset(l, 5, 30);
        build(&t, &dist, l, 30, "fixed");   /* 30 of 32 five-bit codes: incomplete by design (RFC 1951 3.2.6) */
        done = 1;
    }
    return codes(s, &lit, &dist, nsym);
}

static const uint8_t cl_order[19] = {16, 17, 18, 0, 8, 7, 9, 6, 10, 5, 11, 4, 12, 3, 13, 2, 14, 1, 15};

static int dynamic_block(zs *s, int *nsym, int *one_dist)
{
    unsigned hlit, hdist, hclen, v;
    if (bits(s, 5, &hlit) || bits(s, 5, &hdist) || bits(s, 4, &hclen))
        return -1;
    hlit += 257, hdist += 1, hclen += 4;
    if (hlit > 286 || hdist > 30)
        return fail(s, "HLIT %u or HDIST %u too large (286, 30 at most)", hlit, hdist);
    uint8_t len[320] = {0};
    for (unsigned i = 0; i < hclen; i++) {
        if (bits(s, 3, &v))
            return -1;
        len[cl_order[i]] = (uint8_t)v;
    }
    code cl, lit, dist;
    int r = build(s, &cl, len, 19, "code-length");
    if (r < 0)
        return -1;
    if (r == 1)
        return fail(s, "code-length code of one code (incomplete)");
    memset(len, 0, sizeof len);
    for (unsigned i = 0; i < hlit + hdist;) {
        int sym;
        if (decode(s, &cl, &sym))
            return -1;
        if (sym < 16) {
            len[i++] = (uint8_t)sym;
            continue;
        }
        unsigned rep, val = 0;
        if (sym == 16) {
            if (!i)
                return fail(s, "a length repeat (16) with no length before it");
            val = len[i - 1];
            if (bits(s, 2, &rep))
                return -1;
            rep += 3;
        } else if (sym == 17) {
            if (bits(s, 3, &rep))
                return -1;
            rep += 3;
        } else {
            if (bits(s, 7, &rep))
                return -1;
            rep += 11;
        }
        if (i + rep > hlit + hdist)
            return fail(s, "code lengths repeated past HLIT + HDIST (%u + %u > %u)", i, rep, hlit + hdist);
        while (rep--)
            len[i++] = (uint8_t)val;
    }
    if (!len[256])
        return fail(s, "end-of-block has no code");
    if (build(s, &lit, len, (int)hlit, "literal/length"))   /* 1: one literal/length code, refused */
        return s->bad ? -1 : fail(s, "literal/length code of one code (incomplete: Kraft sum 0.5)");
    r = build(s, &dist, len + hlit, (int)hdist, "distance");
    if (r < 0)
        return -1;
    *one_dist = r == 1;
    return codes(s, &lit, &dist, nsym);
}

static uint32_t adler32_of(const unsigned char *p, size_t n)
{
    uint32_t a = 1, b = 0;
    for (size_t i = 0; i < n; i++) {
        a = (a + p[i]) % 65521u;
        b = (b + a) % 65521u;
    }
    return b << 16 | a;
}

int zstrict_inflate(const unsigned char *in, size_t n, unsigned char *out, size_t outcap, zstrict_info *info,
                    char *why, size_t whylen)
{
    zs s = {.in = in, .n = n, .out = out, .outcap = outcap, .why = why, .whylen = whylen};
    zstrict_info k = {0};
    if (why && whylen)
        why[0] = 0;
    if (n < 2 || (in[0] & 15) != 8 || (in[0] >> 4) > 7 || (in[0] * 256u + in[1]) % 31 || (in[1] & 0x20)) {
        fail(&s, "not a zlib header for deflate without a dictionary");
        goto done;
    }
    s.pos = 2;
    for (unsigned final = 0; !final;) {
        unsigned type;
        int nsym = 0, one = 0, r;
        if (bits(&s, 1, &final) || bits(&s, 2, &type))
            goto done;
        k.blocks++;
        if (type == 0) {
            s.bits = 0, s.nbits = 0;   /* to a byte boundary */
            if (s.pos + 4 > n) {
                fail(&s, "the stream ends inside a stored block's header");
                goto done;
            }
            unsigned len = in[s.pos] | in[s.pos + 1] << 8, nlen = in[s.pos + 2] | in[s.pos + 3] << 8;
            s.pos += 4;
            if (len != (~nlen & 0xffffu) || len > n - s.pos || len > outcap - s.outlen) {
                fail(&s, "stored block: LEN %u, NLEN %u, or past the end", len, nlen);
                goto done;
            }
            memcpy(out + s.outlen, in + s.pos, len);
            s.pos += len, s.outlen += len, nsym = (int)len;
            k.stored++;
            r = 0;
        } else if (type == 1) {
            k.fixed++;
            r = fixed_block(&s, &nsym);
        } else if (type == 2) {
            k.dynamic++;
            r = dynamic_block(&s, &nsym, &one);
            k.one_dist += one;
        } else {
            fail(&s, "block type 3 (reserved)");
            goto done;
        }
        if (r)
            goto done;
        k.empty += !nsym;
        k.last_empty = final && !nsym;
    }
    s.bits = 0, s.nbits = 0;
    if (s.pos + 4 != n) {
        if (s.pos + 4 > n)
            fail(&s, "the Adler-32 is cut short");
        else
            fail(&s, "%zu bytes after the Adler-32", n - s.pos - 4);
        goto done;
    }
    uint32_t want = (uint32_t)in[s.pos] << 24 | (uint32_t)in[s.pos + 1] << 16 | (uint32_t)in[s.pos + 2] << 8 | in[s.pos + 3];
    if (want != adler32_of(out, s.outlen))
        fail(&s, "Adler-32 %08x, the data's %08x", (unsigned)want, (unsigned)adler32_of(out, s.outlen));
done:
    k.out = s.outlen;
    if (info)
        *info = k;
    return s.bad ? -1 : 0;
}
