/* SPDX-License-Identifier: MIT */
/* test_ticks.c: tick selection: round steps, counts, compact labels, log decades, no label overlap. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "hy_ticks.h"

#include "rcheck.h"

static int is_round_step(double s)
{
    double m = s / pow(10.0, floor(log10(s) + 1e-12));
    return fabs(m - 1) < 1e-9 || fabs(m - 2) < 1e-9 || fabs(m - 2.5) < 1e-9 || fabs(m - 5) < 1e-9;
}

/* Digits after the decimal point of a label's leading number ("0.25" 2, "3" 0,
 * "2.5\\times10^{5}" 1). */
static int decimals(const char *label)
{
    const char *p = label;
    while (*p && *p != '.' && *p != '\\')
        p++;
    int n = 0;
    if (*p == '.')
        for (p++; *p >= '0' && *p <= '9'; p++)
            n++;
    return n;
}

/* Every label of an axis (but a bare "0" among m x 10^k labels) has one decimal count. */
static void check_decimals(const hy_ticks *t, const char *what)
{
    int sci = 0, ref = -1;
    for (int i = 0; i < t->n; i++)
        sci |= strstr(t->label[i], "times") != NULL;
    for (int i = 0; i < t->n; i++) {
        if (sci && !strcmp(t->label[i], "0"))
            continue;
        if (ref < 0)
            ref = i;
        CHECK(decimals(t->label[i]) == decimals(t->label[ref]), "%s: \"%s\" and \"%s\" differ in decimals",
              what, t->label[ref], t->label[i]);
    }
}

static void check_linear(double lo, double hi, int target)
{
    hy_ticks t;
    CHECK(hy_ticks_linear(lo, hi, target, &t) == 0, "linear(%g, %g) failed", lo, hi);
    CHECK(is_round_step(t.step), "step %g for [%g, %g] is not 1, 2, 2.5 or 5 x 10^k", t.step, lo, hi);
    CHECK(t.n >= 2 && t.n <= 2 * target + 2, "[%g, %g] target %d gave %d ticks", lo, hi, target, t.n);
    for (int i = 0; i < t.n; i++) {
        double k = t.v[i] / t.step;
        CHECK(fabs(k - round(k)) < 1e-6, "tick %g not a multiple of %g", t.v[i], t.step);
        CHECK(t.v[i] >= lo - 1e-9 * t.step && t.v[i] <= hi + 1e-9 * t.step, "tick %g outside", t.v[i]);
        for (int j = 0; j < i; j++)
            CHECK(strcmp(t.label[i], t.label[j]), "labels %d and %d both \"%s\"", i, j, t.label[i]);
    }
    check_decimals(&t, "linear");
}

static void expect_labels(const hy_ticks *t, const char *const *want, int n, const char *what)
{
    CHECK(t->n == n, "%s: %d ticks, want %d", what, t->n, n);
    for (int i = 0; i < n && i < t->n; i++)
        CHECK(!strcmp(t->label[i], want[i]), "%s: label %d is \"%s\", want \"%s\"", what, i,
              t->label[i], want[i]);
}

static double fake_width(void *ctx, const char *label)
{
    return *(const double *)ctx * (double)strlen(label);
}

/* The chosen labels must not overlap: centre distance >= half widths + gap. */
static void check_fit(double lo, double hi, int lg, double len, double per_char)
{
    hy_ticks t;
    double gap = 4.0;
    hy_ticks_fit(lo, hi, lg, len, gap, 10, fake_width, &per_char, &t);
    CHECK(t.n >= 1, "fit gave no ticks");
    for (int i = 1; i < t.n; i++) {
        double a = lg ? log10(t.v[i - 1]) : t.v[i - 1], b = lg ? log10(t.v[i]) : t.v[i];
        double L = lg ? log10(hi) - log10(lo) : hi - lo;
        double dist = (b - a) / L * len;
        double need = 0.5 * (fake_width(&per_char, t.label[i - 1]) + fake_width(&per_char, t.label[i])) + gap;
        CHECK(dist >= need - 1e-9, "[%g, %g] len %g: labels \"%s\" \"%s\" overlap (%g < %g)", lo, hi,
              len, t.label[i - 1], t.label[i], dist, need);
    }
}

int main(void)
{
    hy_ticks t;
    CHECK(fabs(hy_ticks_nice_step(0, 1, 5) - 0.2) < 1e-12, "step 0..1/5");
    CHECK(fabs(hy_ticks_nice_step(0, 4.6, 6) - 1.0) < 1e-12, "step 0..4.6/6");
    CHECK(fabs(hy_ticks_nice_step(0, 10, 4) - 2.5) < 1e-12, "step 0..10/4");
    CHECK(fabs(hy_ticks_nice_step(0, 1e-3, 5) - 2e-4) < 1e-15, "step 0..1e-3/5");
    CHECK(hy_ticks_nice_step(1, 1, 5) == 0.0, "empty range step");
    CHECK(hy_ticks_linear(1, 1, 5, &t) != 0, "empty range accepted");

    hy_ticks_linear(0, 4.6, 6, &t);
    expect_labels(&t, (const char *const[]){"0", "1", "2", "3", "4"}, 5, "0..4.6");
    hy_ticks_linear(-0.8, 1.0, 8, &t);
    expect_labels(&t, (const char *const[]){"-0.75", "-0.50", "-0.25", "0.00", "0.25", "0.50", "0.75", "1.00"},
                  8, "-0.8..1 step 0.25");
    hy_ticks_linear(-0.83, 1.04, 10, &t);
    expect_labels(&t, (const char *const[]){"-0.8", "-0.6", "-0.4", "-0.2", "0.0", "0.2", "0.4", "0.6",
                                            "0.8", "1.0"}, 10, "-0.83..1.04");
    hy_ticks_linear(0, 3e5, 3, &t);
    expect_labels(&t, (const char *const[]){"0", "1\\times10^{5}", "2\\times10^{5}", "3\\times10^{5}"}, 4, "sci");
    hy_ticks_linear(0, 25, 2, &t);
    expect_labels(&t, (const char *const[]){"0", "20"}, 2, "0..25/2");
    double ranges[][2] = {{0, 1}, {-5.3, 17.2}, {1e-6, 3e-6}, {1234, 1267}, {-1e7, 1e7}, {0.001, 0.0013}};
    for (size_t i = 0; i < sizeof ranges / sizeof ranges[0]; i++)
        for (int target = 2; target <= 10; target++)
            check_linear(ranges[i][0], ranges[i][1], target);

    /* issue 10 item 4: near DBL_MAX the last multiple overflowed to inf (and
       its decade, converted to int, to INT_MIN before a negation) */
    CHECK(hy_ticks_linear(-0.1, 1.7976931348623157e308, 5, &t) == 0 && t.n >= 2, "ticks up to DBL_MAX: %d", t.n);
    for (int i = 0; i < t.n; i++)
        CHECK(isfinite(t.v[i]) && t.v[i] <= 1.7976931348623157e308 && t.label[i][0] && !strstr(t.label[i], "inf"),
              "tick %d = %g '%s'", i, t.v[i], t.label[i]);

    hy_ticks_log(1e-4, 0.2, 10, &t);
    expect_labels(&t, (const char *const[]){"10^{-4}", "10^{-3}", "10^{-2}", "10^{-1}"}, 4, "log decades");
    hy_ticks_log(1e-19, 1e-2, 6, &t);
    CHECK(t.n >= 2 && t.n <= 6, "log 17 decades target 6 gave %d ticks", t.n);
    CHECK(t.step == 3.0, "log stride %g, want 3", t.step);
    hy_ticks_log(2, 9, 5, &t);
    expect_labels(&t, (const char *const[]){"2", "5"}, 2, "log within a decade");
    CHECK(hy_ticks_log(-1, 10, 5, &t) != 0, "log of a negative range accepted");
    hy_ticks_log(0.04, 0.6, 10, &t);
    expect_labels(&t, (const char *const[]){"0.05", "0.10", "0.20", "0.50"}, 4, "log 1-2-5 decimals");
    hy_ticks_linear(0, 1, 4, &t);
    expect_labels(&t, (const char *const[]){"0.00", "0.25", "0.50", "0.75", "1.00"}, 5, "0..1 by 0.25");
    /* a sweep of ranges, as the layout picks them: one decimal count per axis */
    for (int k = 0; k < 400; k++) {
        double lo = -3.0 + 0.0137 * k * k / 40.0, hi = lo + 0.01 + 0.37 * (k % 23);
        for (int target = 2; target <= 10; target += 4) {
            hy_ticks_linear(lo, hi, target, &t);
            check_decimals(&t, "sweep");
        }
    }

    check_fit(0, 1, 0, 200, 5.0);
    check_fit(1000.5, 1001.5, 0, 120, 6.0);       /* long labels on a short axis */
    check_fit(-1e-7, 1e-7, 0, 100, 6.0);
    check_fit(1e-18, 1e-2, 1, 150, 6.0);
    hy_ticks_fit(0, 1, 0, 200, 4.0, 10, fake_width, &(double){5.0}, &t);
    CHECK(t.n >= 5, "0..1 on 200 pt got only %d ticks", t.n);
    hy_ticks_fit(0, 1, 0, 60, 4.0, 10, fake_width, &(double){30.0}, &t);
    CHECK(t.n <= 2, "labels 90 pt wide on a 60 pt axis: %d ticks", t.n);
    hy_ticks_fit(0, 1, 0, 30, 4.0, 10, fake_width, &(double){30.0}, &t);
    CHECK(t.n == 1, "labels 90 pt wide on a 30 pt axis: %d ticks, want 1", t.n);

    return hy_test_finish("ticks");
}
