/* SPDX-License-Identifier: MIT */
/* test_validation.c: the official validation multisine (data/boucwen):
 * upsample uval x20 by DFT zero-padding, integrate 3 + 1 periods, decimate
 * 2-2-5 as MATLAB decimate 'fir', and compare the last kept period with the
 * authors' yval (e_RMS of Eq. (6), absolute, metres). */
#include "bw_test.h"
#include "hy_boucwen.h"
#include "hy_signal.h"

#include <math.h>

/* Reached: 2.2e-16 m (yval's RMS is 6.7e-4 m, so 3e-13 relative).  The bound
 * leaves a factor ~20 for other compilers/libm (the FIR sums and the Newton
 * iterations round differently).  Near misses are far above it: one-stage
 * decimation gives 2.9e-6 m, Eq. (3) without its parentheses 7.6e-4 m. */
#define ERMS_BOUND 5e-15

int main(void)
{
    const char *dir = bw_data_dir();
    char pu[4096], py[4096];
    snprintf(pu, sizeof pu, "%s/uval_multisine.txt", dir);
    snprintf(py, sizeof py, "%s/yval_multisine.txt", dir);
    hy_error err;
    double *u = NULL, *yref = NULL, fs;
    size_t n, ny;
    if (hy_signal_read(pu, &u, &n, &fs, &err) || hy_signal_read(py, &yref, &ny, &fs, &err)) {
        fprintf(stderr, "%s\n", err.msg);
        return 1;
    }
    CHECK(n == 8192 && ny == 8192, "n = %zu, ny = %zu", n, ny);
    const size_t r = 20, periods = 3;
    double *u15 = malloc(n * r * sizeof *u15);
    double *y = malloc(periods * n * sizeof *y);
    CHECK(hy_signal_upsample_fft(u, n, r, u15, &err) == HY_OK, "%s", err.msg);
    /* the DFT interpolation keeps the 750 Hz samples (rounding only) */
    double dmax = 0;
    for (size_t i = 0; i < n; i++)
        dmax = fmax(dmax, fabs(u15[i * r] - u[i]));
    CHECK(dmax < 1e-12, "upsampled input moved a sample by %g N", dmax);

    hy_boucwen_params p;
    hy_newmark_opts o;
    hy_boucwen_params_default(&p);
    hy_newmark_opts_default(&o);
    int rc = hy_boucwen_synth_periodic(&p, &o, 750.0, r, 1, u15, n * r, periods, y, &err);
    CHECK(rc == HY_OK, "%s", rc ? err.msg : "");
    if (rc == HY_OK) {
        double e = hy_signal_erms(y + (periods - 1) * n, yref, n);
        double e2 = hy_signal_erms(y + (periods - 2) * n, yref, n);
        printf("validation multisine: e_RMS = %.3e m (previous period %.3e m), "
               "RMS(yval) = %.3e m\n", e, e2, hy_signal_rms(yref, n));
        CHECK(e < ERMS_BOUND, "e_RMS = %g m >= %g m", e, ERMS_BOUND);
    }
    free(u);
    free(yref);
    free(u15);
    free(y);
    return hy_test_finish("test_validation");
}
