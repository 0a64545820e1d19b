/* SPDX-License-Identifier: MIT */
/* test_dtoa.c: hy_dtoa (src/io/hy_dtoa.h) against the C library, on edge cases
 * and N random doubles (HY_DTOA_N, default 1e6; the benchmark-size run is
 * HY_DTOA_N=10000000): every text reads back (strtod) to the same bits; it is
 * printf's %.17g byte for byte or has fewer digits; no decimal with one digit
 * fewer reads back (the three (n-1)-digit neighbours of v are tried); and on 1
 * in 16 values the shortest %.{p}g, p = 1..17, that reads back has no fewer
 * digits, and the same digits when as many. */
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hy_dtoa.h"

static unsigned long nchecked, nsame, nshorter, nsearched, fails;

static uint64_t rng = 0x9e3779b97f4a7c15u;
static uint64_t next(void) /* splitmix64 */
{
    uint64_t z = (rng += 0x9e3779b97f4a7c15u);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9u;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebu;
    return z ^ (z >> 31);
}

static int fail(double v, const char *what, const char *got, const char *want)
{
    if (fails++ < 20)
        fprintf(stderr, "FAIL %a: %s: got '%s', %s\n", v, what, got, want);
    return 0;
}

/* The significant digits of a printf text (no sign, point, exponent or
 * leading zeros; trailing zeros kept). */
static int sig_digits(const char *s, char *d)
{
    int n = 0, lead = 1;
    for (; *s && *s != 'e'; s++)
        if (*s >= '0' && *s <= '9' && !(lead && *s == '0')) {
            d[n++] = *s;
            lead = 0;
        }
    d[n] = 0;
    while (n > 0 && d[n - 1] == '0')
        d[--n] = 0;
    return n;
}

/* Whether the decimal DIGITS (a string of n digits) * 10^e reads back to v. */
static int reads_back(unsigned long long digits, int e, double v)
{
    char t[64];
    snprintf(t, sizeof t, "%s%llue%d", signbit(v) ? "-" : "", digits, e);
    return strtod(t, NULL) == v;
}

static int check(double v, int search)
{
    char got[HY_DTOA_MAX + 8], ref[64];
    memset(got, 'x', sizeof got);
    size_t n = hy_dtoa(v, got);
    nchecked++;
    if (n != strlen(got) || n >= HY_DTOA_MAX)
        return fail(v, "length", got, "length wrong or too long");
    snprintf(ref, sizeof ref, "%.17g", v);
    if (isnan(v)) {
        if (strcmp(got, signbit(v) ? "-nan" : "nan"))
            fail(v, "nan", got, ref);
        return 0;
    }
    double back = strtod(got, NULL);
    if (memcmp(&back, &v, sizeof v))
        return fail(v, "round trip", got, ref);
    char dg[40], dr[40];
    int ng = sig_digits(got, dg), nr = sig_digits(ref, dr);
    if (!strcmp(got, ref))
        nsame++;
    else if (ng < nr)
        nshorter++;
    else
        return fail(v, "not %.17g though as long", got, ref);
    if (!isfinite(v) || v == 0)
        return 0;
    /* shortest: no decimal of ng - 1 digits near v reads back */
    unsigned long long d;
    int e;
    hy_dtoa_digits(fabs(v), &d, &e);
    if (ng > 1) {
        char t[64];
        snprintf(t, sizeof t, "%.*e", ng - 2, fabs(v)); /* the nearest of ng - 1 digits */
        unsigned long long m = 0;
        for (const char *c = t; *c && *c != 'e'; c++)
            if (*c >= '0' && *c <= '9')
                m = m * 10 + (unsigned long long)(*c - '0');
        int ex = atoi(strchr(t, 'e') + 1) - (ng - 2);
        for (int off = -1; off <= 1; off++)
            if (m + (unsigned long long)off > 0 && reads_back(m + (unsigned long long)off, ex, v))
                fail(v, "a decimal one digit shorter reads back", got, t);
    }
    if (!search)
        return 0;
    nsearched++;
    for (int p = 1; p <= 17; p++) {
        char t[64];
        snprintf(t, sizeof t, "%.*g", p, v);
        if (strtod(t, NULL) != v)
            continue;
        char dt[40];
        int nt = sig_digits(t, dt);
        if (nt < ng || (nt == ng && strcmp(dt, dg)))
            fail(v, "%.{p}g reads back with fewer or other digits", got, t);
        break;
    }
    return 0;
}

static double from_bits(uint64_t b)
{
    double v;
    memcpy(&v, &b, sizeof v);
    return v;
}

int main(void)
{
    const char *env = getenv("HY_DTOA_N");
    unsigned long n = env ? strtoul(env, NULL, 10) : 1000000ul;
    /* edge cases */
    static const double fixed[] = {0.0, -0.0, 1.0, -1.0, 0.1, 0.2, 0.3, 1.0 / 3, 2.0 / 3, 0.5, 0.25, 1e-5, 1e-4,
                                   1.5e-4, 9.5e-5, 1e15, 1e16, 1e17, 1e21, 1e22, 1e23, 123456789012345678.0,
                                   DBL_MIN, DBL_MAX, DBL_TRUE_MIN, DBL_EPSILON, 9007199254740992.0,
                                   9007199254740994.0, 5e-324, 2.2250738585072009e-308, 1.7976931348623157e308,
                                   4.9406564584124654e-324, 2.2250738585072014e-308, 0.1 + 0.2, 100, 6, 1e100,
                                   1e-100, 123.456, INFINITY, -INFINITY, NAN, -NAN};
    for (size_t k = 0; k < sizeof fixed / sizeof *fixed; k++)
        check(fixed[k], 1);
    for (int e = -1074; e <= 1023; e++) { /* powers of two and their neighbours */
        double p = ldexp(1.0, e);
        check(p, 1), check(nextafter(p, 0), 1), check(nextafter(p, INFINITY), 1), check(-p, 0);
    }
    for (int e = -323; e <= 308; e++) { /* powers of ten and their neighbours */
        char t[16];
        snprintf(t, sizeof t, "1e%d", e);
        double p = strtod(t, NULL);
        check(p, 1), check(nextafter(p, 0), 1), check(nextafter(p, INFINITY), 1);
    }
    for (long i = 0; i <= 20000; i++) /* integers, and k/10, k/100, k/1000: 0.1-like */
        check((double)i, 0), check(i / 10.0, 0), check(i / 100.0, 0), check(i / 1000.0, i % 16 == 0);
    for (long i = 0; i < 20000; i++) { /* halfway neighbours: 2^53..2^55 integers, both ends' subnormals */
        check(9007199254740992.0 + 2.0 * (double)i, 0);
        check(18014398509481984.0 + 4.0 * (double)i, 0);
        check(from_bits((uint64_t)i), i % 16 == 0);
        check(from_bits(0x7fefffffffffffffu - (uint64_t)i), i % 16 == 0);
        check(from_bits(0x0010000000000000u + (uint64_t)i - 10000), i % 16 == 0);
    }
    unsigned long edge = nchecked;
    for (unsigned long i = 0; i < n; i++) {
        uint64_t r = next();
        double v;
        switch (i % 4) {
        case 0: /* bit patterns uniform (NaN and infinities included) */
            v = from_bits(r);
            break;
        case 1: /* uniform in [0, 1) */
            v = (double)(r >> 11) * 0x1p-53;
            break;
        case 2: /* uniform in [0, 10^j), j = 0..20 */
            v = (double)(r >> 11) * 0x1p-53 * pow(10, (double)(r % 21));
            break;
        default: /* subnormal bit patterns */
            v = from_bits(r & 0x800fffffffffffffu);
            break;
        }
        check(v, i % 16 == 0);
    }
    printf("test_dtoa: %lu doubles (%lu edge cases, %lu random), %lu as %%.17g, %lu shorter than %%.17g, %lu "
           "searched over %%.{p}g; %lu failures\n",
           nchecked, edge, nchecked - edge, nsame, nshorter, nsearched, fails);
    return fails ? 1 : 0;
}
