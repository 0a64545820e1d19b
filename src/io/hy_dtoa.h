/* SPDX-License-Identifier: MIT */
/* hy_dtoa.h: a double as the shortest decimal that reads back to it (strtod
 * round to nearest), laid out as printf's "%.17g" lays out its digits.
 *
 *     char buf[HY_DTOA_MAX];
 *     size_t n = hy_dtoa(0.1, buf);     // "0.1", n = 3 (printf "%.17g": 0.10000000000000001)
 *
 * The digits are Schubfach's (R. Giulietti, "The Schubfach way to render
 * doubles", 2020): the shortest decimal in the double's rounding interval,
 * the closest to it when there are two.  The layout is %.17g's with X the
 * decimal exponent of the first digit: d.ddde-XX when X < -4 or X >= 17
 * (at least two exponent digits), else fixed notation; no trailing zeros
 * after a point, no point after the last digit; "-0", "inf", "-inf", "nan",
 * "-nan" as glibc prints them.  So where %.17g's digits are already the
 * shortest that read back (e.g. 0.5, 1e+100, 6, 0.25), the text is %.17g's
 * byte for byte; elsewhere it is shorter and reads back to the same double.
 */
#ifndef HY_DTOA_H
#define HY_DTOA_H

#include <stddef.h>

/* The most bytes hy_dtoa writes, with the terminating NUL
 * ("-2.2250738585072014e-308", "-0.00012345678901234567"). */
#define HY_DTOA_MAX 32

/* Writes v into buf (HY_DTOA_MAX bytes), NUL-terminated; returns its length. */
size_t hy_dtoa(double v, char *buf);

/* The shortest decimal of a finite v > 0 as digits * 10^exp10: *digits has no
 * trailing zeros and at most 17 digits. */
void hy_dtoa_digits(double v, unsigned long long *digits, int *exp10);

#endif
