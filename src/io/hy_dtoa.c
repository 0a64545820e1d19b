/* SPDX-License-Identifier: MIT */
/* hy_dtoa.c: shortest round-trip decimal of a double, Schubfach (R. Giulietti,
 * "The Schubfach way to render doubles", 2020, sections 8-10: the rounding
 * interval scaled by 10^-k with one 128-bit multiply per end, round to odd;
 * the closest of the at most two candidates of the shortest length), laid out
 * as printf's %.17g (hy_dtoa.h). */
#include "hy_dtoa.h"

#include <stdint.h>
#include <string.h>

#include "hy_dtoa_table.h"

__extension__ typedef unsigned __int128 u128; /* GCC and clang */

/* floor(x * g / 2^128) with a sticky low bit: odd when the 192-bit product
 * has a fraction above 1 unit of 2^-64 (g is 10^b rounded up by at most 1). */
static uint64_t round_to_odd(const uint64_t g[2], uint64_t x)
{
    u128 lo = (u128)g[1] * x, hi = (u128)g[0] * x;
    u128 mid = (hi & UINT64_MAX) + (uint64_t)(lo >> 64);
    uint64_t y1 = (uint64_t)(hi >> 64) + (uint64_t)(mid >> 64), y0 = (uint64_t)mid;
    return y1 | (y0 > 1);
}

/* floor(q log10 2), floor(q log10 2 - log10(4/3)), floor(b log2 10): exact
 * over the exponents used (checked by tools/gen_dtoa_table.py). */
static int flog10_pow2(int q)
{
    return (int)(((int64_t)q * 661971961083LL) >> 41);
}

static int flog10_3q_pow2(int q)
{
    return (int)(((int64_t)q * 661971961083LL - 274743187321LL) >> 41);
}

static int flog2_pow10(int b)
{
    return (int)(((int64_t)b * 913124641741LL) >> 38);
}

void hy_dtoa_digits(double v, unsigned long long *digits, int *exp10)
{
    uint64_t bits;
    memcpy(&bits, &v, sizeof bits);
    uint64_t t = bits & ((UINT64_C(1) << 52) - 1);
    int e = (int)(bits >> 52 & 0x7ff);
    uint64_t c = e ? t | UINT64_C(1) << 52 : t;
    int q = e ? e - 1075 : -1074;
    /* v = c 2^q; its rounding interval is (cbl, cbr) 2^(q-2), ends included
     * when c is even (strtod rounds ties to even) */
    uint64_t out = c & 1, cb = c << 2, cbr = cb + 2, cbl;
    int k;
    if (t || e <= 1) { /* symmetric */
        cbl = cb - 2;
        k = flog10_pow2(q);
    } else { /* c = 2^52: the lower neighbour is half as far */
        cbl = cb - 1;
        k = flog10_3q_pow2(q);
    }
    int h = q + flog2_pow10(-k) + 1; /* 1..4 */
    const uint64_t *g = hy_dtoa_g[-k - HY_DTOA_BMIN];
    uint64_t vbl = round_to_odd(g, cbl << h), vb = round_to_odd(g, cb << h), vbr = round_to_odd(g, cbr << h);
    uint64_t lower = vbl + out, upper = vbr - out; /* the interval times 4 10^-k */
    uint64_t s = vb >> 2, d;
    if (s >= 10) { /* one digit fewer: a multiple of 10^(k+1) in the interval */
        uint64_t sp = s / 10;
        int up_in = lower <= 40 * sp, wp_in = 40 * sp + 40 <= upper;
        if (up_in != wp_in) {
            d = sp + (uint64_t)wp_in;
            k++;
            goto strip;
        }
    }
    {
        int u_in = lower <= 4 * s, w_in = 4 * s + 4 <= upper;
        if (u_in != w_in)
            d = s + (uint64_t)w_in;
        else { /* both or neither: the closer, ties to even */
            uint64_t mid = 4 * s + 2;
            d = s + (uint64_t)(vb > mid || (vb == mid && (s & 1)));
        }
    }
strip:
    while (d % 10 == 0) {
        d /= 10;
        k++;
    }
    *digits = d;
    *exp10 = k;
}

size_t hy_dtoa(double v, char *buf)
{
    uint64_t bits;
    memcpy(&bits, &v, sizeof bits);
    char *p = buf;
    if (bits >> 63)
        *p++ = '-';
    uint64_t mag = bits & (UINT64_MAX >> 1);
    if (mag >= UINT64_C(0x7ff) << 52) {
        memcpy(p, mag == UINT64_C(0x7ff) << 52 ? "inf" : "nan", 4);
        return (size_t)(p - buf) + 3;
    }
    if (!mag) {
        memcpy(p, "0", 2);
        return (size_t)(p - buf) + 1;
    }
    unsigned long long d;
    int k;
    hy_dtoa_digits(v < 0 ? -v : v, &d, &k);
    char dig[20];
    int n = 0;
    for (char *w = dig + sizeof dig; d; d /= 10, n++)
        *--w = (char)('0' + d % 10);
    const char *ds = dig + sizeof dig - n;
    int x = k + n - 1; /* the exponent of the first digit */
    if (x < -4 || x >= 17) {
        *p++ = ds[0];
        if (n > 1) {
            *p++ = '.';
            memcpy(p, ds + 1, (size_t)n - 1);
            p += n - 1;
        }
        *p++ = 'e';
        *p++ = x < 0 ? '-' : '+';
        int ax = x < 0 ? -x : x;
        if (ax >= 100)
            *p++ = (char)('0' + ax / 100);
        *p++ = (char)('0' + ax / 10 % 10);
        *p++ = (char)('0' + ax % 10);
    } else if (x < 0) { /* 0.000ddd */
        *p++ = '0';
        *p++ = '.';
        for (int z = -1; z > x; z--)
            *p++ = '0';
        memcpy(p, ds, (size_t)n);
        p += n;
    } else if (n <= x + 1) { /* an integer: ddd000 */
        memcpy(p, ds, (size_t)n);
        p += n;
        for (int z = n; z <= x; z++)
            *p++ = '0';
    } else { /* ddd.ddd */
        memcpy(p, ds, (size_t)x + 1);
        p += x + 1;
        *p++ = '.';
        memcpy(p, ds + x + 1, (size_t)(n - x - 1));
        p += n - x - 1;
    }
    *p = '\0';
    return (size_t)(p - buf);
}
