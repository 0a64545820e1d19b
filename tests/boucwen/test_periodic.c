/* SPDX-License-Identifier: MIT */
/* test_periodic.c: hy_boucwen_synth_periodic_kept (and synth_periodic, which
 * is it with first = 0) integrates only as far as the decimation filter reads
 * and decimates only around the kept periods (issue 23).  The reference is
 * the record written out in full: periods + 1 copies of the period,
 * hy_boucwen_simulate over all of it, hy_signal_decimate_stages over all of
 * it, then the kept periods sliced out.  Equality is exact (memcmp): the
 * shortcut is only right if every kept output is the same sum of the same
 * samples, and an off-by-one in the reach or the alignment changes bits. */
#include "bw_test.h"
#include "hy_boucwen.h"
#include "hy_signal.h"

#include <math.h>

/* The whole record's periods first .. periods - 1 into want; 0 or an error. */
static int reference(const hy_boucwen_params *p, double fs, size_t r, int staged, const double *up, size_t n,
                     size_t first, size_t periods, double *want)
{
    hy_newmark_opts o;
    hy_newmark_opts_default(&o);
    hy_error err;
    size_t total = (periods + 1) * n, ny;
    double *u = malloc(total * sizeof *u), *y = malloc(total * sizeof *y), *yd = malloc(total * sizeof *yd);
    for (size_t i = 0; i < total; i++)
        u[i] = up[i % n];
    int rc = hy_boucwen_simulate(p, &o, 1.0 / (fs * (double)r), u, total, NULL, y, NULL, &err);
    if (!rc)
        rc = hy_signal_decimate_stages(y, total, r, staged, yd, &ny, &err);
    if (!rc)
        memcpy(want, yd + first * (n / r), (periods - first) * (n / r) * sizeof *want);
    else
        fprintf(stderr, "reference: %s\n", err.msg);
    free(u);
    free(y);
    free(yd);
    return rc;
}

int main(void)
{
    hy_boucwen_params p;
    hy_boucwen_params_default(&p);
    hy_newmark_opts o;
    hy_newmark_opts_default(&o);
    /* r: staged 2-2-5 (bw_fig1a's reach of 105 samples), one stage, a prime,
       none; n: periods shorter and longer than the reach */
    static const size_t rs[] = {20, 20, 7, 1}, ns[] = {15000 / 20, 40, 9, 300};
    static const int staged[] = {1, 0, 1, 1};
    int cases = 0;
    for (size_t c = 0; c < sizeof rs / sizeof rs[0]; c++)
        for (size_t k = 0; k < sizeof ns / sizeof ns[0]; k++)
            for (size_t periods = 1; periods <= 4; periods += 3)
                for (size_t first = 0; first < periods; first += 2) {
                    size_t r = rs[c], n = ns[k] * r, m = (periods - first) * (n / r);
                    double fs = 750.0, *u = malloc(n * sizeof *u);
                    double *got = malloc(m * sizeof *got), *want = malloc(m * sizeof *want);
                    hy_error err;
                    for (size_t i = 0; i < n; i++) /* a sine plus a ramp: no symmetry to hide an offset */
                        u[i] = 120 * sin(2 * M_PI * (double)i / (double)n) + 30.0 * (double)i / (double)n;
                    int rc = hy_boucwen_synth_periodic_kept(&p, &o, fs, r, staged[c], u, n, first, periods, got, &err);
                    CHECK(!rc, "r %zu n %zu: %s", r, n, err.msg);
                    if (!rc && !reference(&p, fs, r, staged[c], u, n, first, periods, want)) {
                        CHECK(!memcmp(got, want, m * sizeof *got),
                              "r %zu%s, %zu samples a period, periods %zu .. %zu: not the whole record's bits", r,
                              staged[c] ? " staged" : "", n, first, periods - 1);
                        cases++;
                    }
                    if (!first && !rc) { /* synth_periodic is the same with nothing dropped */
                        double *all = malloc(m * sizeof *all);
                        CHECK(!hy_boucwen_synth_periodic(&p, &o, fs, r, staged[c], u, n, periods, all, &err) &&
                                  !memcmp(all, got, m * sizeof *all),
                              "synth_periodic differs from synth_periodic_kept from period 0");
                        free(all);
                    }
                    free(u);
                    free(got);
                    free(want);
                }
    hy_error err;
    double u4[4] = {1, 2, 3, 4}, y4[4];
    CHECK(hy_boucwen_synth_periodic_kept(&p, &o, 750, 1, 1, u4, 4, 2, 2, y4, &err) == HY_EINVAL,
          "first = periods accepted");
    printf("test_periodic: %d cases equal to the whole record\n", cases);
    return hy_test_finish("test_periodic");
}
