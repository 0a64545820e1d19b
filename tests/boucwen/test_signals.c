/* SPDX-License-Identifier: MIT */
/* test_signals.c: the benchmark's signal tools: multisine design, DFT and
 * sinc upsampling, MATLAB fir1/decimate semantics, noise, sweep, e_RMS. */
#include "bw_test.h"
#include "hy_signal.h"

#include <math.h>

static void test_multisine(void)
{
    hy_multisine ms;
    hy_error e;
    size_t kmin, kmax, r = 20;
    hy_multisine_default(&ms);
    CHECK(hy_multisine_lines(&ms, &kmin, &kmax, &e) == HY_OK, "%s", e.msg);
    /* the official validation signal holds lines 55 .. 1639 */
    CHECK(kmin == 55 && kmax == 1639, "lines %zu..%zu", kmin, kmax);
    size_t L = ms.n * r;
    double *u = malloc(L * sizeof *u), *d = malloc(ms.n * sizeof *d);
    CHECK(hy_multisine_design(&ms, r, u, &e) == HY_OK, "%s", e.msg);
    /* MATLAB std(u) = 50 at 15 kHz, hence RMS 50 sqrt((L-1)/L) at 750 Hz too */
    double s = hy_signal_rms(u, L) * sqrt((double)L / (double)(L - 1));
    CHECK(fabs(s - 50) < 1e-12, "std %.17g", s);
    for (size_t i = 0; i < ms.n; i++)
        d[i] = u[i * r];
    double want = 50 * sqrt((double)(L - 1) / (double)L);
    CHECK(fabs(hy_signal_rms(d, ms.n) - want) < 1e-12, "rms at 750 Hz %.17g", hy_signal_rms(d, ms.n));
    /* spectrum: equal magnitudes on the lines, nothing elsewhere */
    CHECK(hy_signal_fft_forward(d, ms.n, &e) == HY_OK, "%s", e.msg);
    double mag0 = hypot(d[2 * kmin - 1], d[2 * kmin]), off = 0, spread = 0;
    for (size_t k = 1; k < ms.n / 2; k++) {
        double mg = hypot(d[2 * k - 1], d[2 * k]);
        if (k >= kmin && k <= kmax)
            spread = fmax(spread, fabs(mg - mag0) / mag0);
        else
            off = fmax(off, mg / mag0);
    }
    CHECK(spread < 1e-9 && off < 1e-12, "line spread %g, off-band %g", spread, off);
    /* the same seed gives the same signal; another seed another one */
    double *u2 = malloc(L * sizeof *u2);
    hy_multisine_design(&ms, r, u2, &e);
    CHECK(memcmp(u, u2, L * sizeof *u) == 0, "not reproducible");
    ms.seed = 2;
    hy_multisine_design(&ms, r, u2, &e);
    CHECK(hy_signal_erms(u, u2, L) > 10, "seed ignored");
    ms.fmax = 400;
    CHECK(hy_multisine_design(&ms, r, u2, &e) == HY_EINVAL && strstr(e.msg, "fmax"), "%s", e.msg);
    free(u);
    free(u2);
    free(d);
}

static void test_upsample(void)
{
    enum { N = 64, R = 5 };
    double x[N], y[N * R], ys[N * R];
    hy_error e;
    /* DFT zero-padding is exact for a band-limited periodic signal, including
     * an even-n Nyquist line (split evenly: cos(π i) -> cos(π j / R)) */
    for (int i = 0; i < N; i++)
        x[i] = sin(2 * M_PI * 3 * i / N + 0.3) + 0.5 * cos(2 * M_PI * 17 * i / N) + 0.25 * cos(M_PI * i);
    CHECK(hy_signal_upsample_fft(x, N, R, y, &e) == HY_OK, "%s", e.msg);
    double err = 0;
    for (int j = 0; j < N * R; j++) {
        double t = (double)j / R;
        double ex = sin(2 * M_PI * 3 * t / N + 0.3) + 0.5 * cos(2 * M_PI * 17 * t / N) + 0.25 * cos(M_PI * t);
        err = fmax(err, fabs(y[j] - ex));
    }
    CHECK(err < 1e-13, "fft upsampling error %g", err);
    /* windowed sinc: the samples are kept exactly; a slow sine is
     * interpolated to the window's accuracy away from the ends */
    for (int i = 0; i < N; i++)
        x[i] = sin(2 * M_PI * 0.02 * i);
    CHECK(hy_signal_upsample_sinc(x, N, R, ys, &e) == HY_OK, "%s", e.msg);
    err = 0;
    for (int j = 0; j < N * R; j++) {
        if (j % R == 0)
            CHECK(ys[j] == x[j / R], "sample %d moved", j / R);
        if (j < 16 * R || j > (N - 17) * R)
            continue;
        err = fmax(err, fabs(ys[j] - sin(2 * M_PI * 0.02 * j / R)));
    }
    printf("sinc upsampling: max interior error %.3e\n", err);
    /* Kaiser β = 8, 32 taps: ripple ~1e-5 in the pass band at 0.04 of fs */
    CHECK(err < 1e-4, "sinc upsampling error %g", err);
}

static void test_decimate(void)
{
    double b[HY_DECIMATE_TAPS];
    hy_error e;
    for (size_t r = 2; r <= 5; r++) {
        hy_fir1_lowpass(r, b);
        double s = 0, asym = 0;
        for (int i = 0; i < HY_DECIMATE_TAPS; i++) {
            s += b[i];
            asym = fmax(asym, fabs(b[i] - b[HY_DECIMATE_TAPS - 1 - i]));
        }
        CHECK(fabs(s - 1) < 1e-15 && asym == 0, "r %zu: sum %.17g asym %g", r, s, asym);
    }
    hy_fir1_lowpass(2, b); /* half band: every other tap is zero */
    for (int i = 2; i < 15; i += 2) /* sin(π i / 2) rounds to ~1e-16 */
        CHECK(fabs(b[15 - i]) < 1e-16, "tap %d = %g", 15 - i, b[15 - i]);
    /* a straight line passes unchanged, ends included (point reflection) */
    enum { N = 203 };
    double x[N], y[N], y1[N];
    size_t ny;
    for (int i = 0; i < N; i++)
        x[i] = 3.0 - 0.25 * i;
    CHECK(hy_signal_decimate(x, N, 5, y, &e) == HY_OK, "%s", e.msg);
    for (int k = 0; k < (N + 4) / 5; k++)
        CHECK(fabs(y[k] - x[5 * k]) < 1e-12, "ramp k %d: %g vs %g", k, y[k], x[5 * k]);
    /* stages: 20 = 2 2 5, ceil lengths */
    CHECK(hy_signal_decimate_stages(x, N, 20, 1, y, &ny, &e) == HY_OK && ny == 11, "ny %zu", ny);
    CHECK(hy_signal_decimate_stages(x, N, 20, 0, y1, &ny, &e) == HY_OK && ny == 11, "ny %zu", ny);
    for (int k = 0; k < 11; k++)
        CHECK(fabs(y[k] - x[20 * k]) < 1e-12 && fabs(y1[k] - x[20 * k]) < 1e-12, "k %d", k);
    /* a line in the pass band keeps its value at the kept samples to the
     * filter's pass-band accuracy; one above the cutoff is removed */
    for (int i = 0; i < N; i++)
        x[i] = cos(2 * M_PI * 0.01 * i) + cos(2 * M_PI * 0.45 * i);
    hy_signal_decimate(x, N, 2, y, &e);
    for (int k = 10; k < N / 2 - 10; k++)
        CHECK(fabs(y[k] - cos(2 * M_PI * 0.01 * 2 * k)) < 2e-3, "k %d: %g", k, y[k]);
    CHECK(hy_signal_decimate(x, 10, 2, y, &e) == HY_EINVAL, "short input accepted");
}

static void test_noise(void)
{
    enum { N = 8192 };
    double *a = calloc(N, sizeof *a), *b = calloc(N, sizeof *b);
    hy_error e;
    CHECK(hy_signal_add_noise(a, N, 8e-6, 375, 750, 7, &e) == HY_OK, "%s", e.msg);
    CHECK(fabs(hy_signal_rms(a, N) - 8e-6) < 1e-18, "rms %g", hy_signal_rms(a, N));
    hy_signal_add_noise(b, N, 8e-6, 375, 750, 7, &e);
    CHECK(memcmp(a, b, N * sizeof *a) == 0, "noise not reproducible");
    memset(b, 0, N * sizeof *b);
    hy_signal_add_noise(b, N, 8e-6, 375, 750, 8, &e);
    CHECK(hy_signal_erms(a, b, N) > 8e-6, "seed ignored");
    /* mean ~0 and Gaussian kurtosis ~3 (N = 8192: standard errors 0.011, 0.054) */
    double m = 0, m4 = 0;
    for (int i = 0; i < N; i++) {
        m += a[i] / 8e-6;
        m4 += pow(a[i] / 8e-6, 4);
    }
    CHECK(fabs(m / N) < 0.05 && fabs(m4 / N - 3) < 0.3, "mean %g kurtosis %g", m / N, m4 / N);
    /* band-limited to 100 Hz at 750 Hz: no DFT line above */
    memset(b, 0, N * sizeof *b);
    CHECK(hy_signal_add_noise(b, N, 1.0, 100, 750, 1, &e) == HY_OK, "%s", e.msg);
    hy_signal_fft_forward(b, N, &e);
    double hi = 0;
    for (int k = (int)(100.0 * N / 750) + 1; k < N / 2; k++)
        hi = fmax(hi, hypot(b[2 * k - 1], b[2 * k]));
    CHECK(hi < 1e-10, "energy above the band: %g", hi);
    CHECK(hy_signal_add_noise(a, N, -1, 375, 750, 1, &e) == HY_EINVAL && strstr(e.msg, "rms"), "%s", e.msg);
    free(a);
    free(b);
}

static void test_sweep(void)
{
    hy_sweep sw;
    hy_error e;
    hy_sweep_default(&sw);
    /* 20 -> 50 Hz at 10 Hz/min: 180 s, t in [0, 180): 135000 samples at 750 Hz */
    CHECK(hy_sweep_length(&sw, 750) == 135000, "length %zu", hy_sweep_length(&sw, 750));
    CHECK(hy_sweep_length(&sw, 15000) == 2700000, "length %zu", hy_sweep_length(&sw, 15000));
    /* the published validation sweep: n = 0 .. 152999 at 750 Hz */
    hy_sweep_validation(&sw);
    CHECK(hy_sweep_length(&sw, 750) == 153000, "validation length %zu", hy_sweep_length(&sw, 750));
    CHECK(sw.amp == 40 && sw.f0 == 18 && sw.f1 == 52 && fabs(sw.rate * 12 - 2) < 1e-15, "validation sweep");
    sw.rate = 1e-300; /* refused, not an overflowing length */
    CHECK(hy_sweep_length(&sw, 750) == 0, "length of a 1e302 s sweep");
    hy_sweep_default(&sw);
    double u[4];
    CHECK(hy_sweep_fill(&sw, 750, u, 4, &e) == HY_OK, "%s", e.msg);
    CHECK(u[0] == 0 && fabs(u[1] - 40 * sin(2 * M_PI * (20.0 / 750 + 0.5 / 6 / 750 / 750))) < 1e-12, "u1 %g", u[1]);
    sw.f1 = 10;
    CHECK(hy_sweep_fill(&sw, 750, u, 4, &e) == HY_EINVAL && strstr(e.msg, "f1"), "%s", e.msg);
    double a[3] = {1, 2, 3}, b[3] = {1, 2, 5};
    CHECK(fabs(hy_signal_erms(a, b, 3) - 2 / sqrt(3.0)) < 1e-15, "erms");
}

/* issue 10 items 1 and 4: rates and bands at the ends of the doubles are
 * refused before any float -> size_t conversion or any write; a band reaching
 * below the first line starts at line 1 (kmin = 0 wrote u[-1]). */
static void test_extreme_signals(void)
{
    hy_multisine ms;
    hy_error e;
    size_t kmin = 99, kmax = 99, r = 2;
    hy_multisine_default(&ms);
    ms.n = 64;
    ms.fs = 64; /* lines 1 Hz apart */
    ms.fmin = 1e-12;
    ms.fmax = 3;
    CHECK(hy_multisine_lines(&ms, &kmin, &kmax, &e) == HY_OK && kmin == 1 && kmax == 3, "lines %zu..%zu", kmin,
          kmax);
    /* exactly n r samples: ASan reports a write outside them */
    double *u = malloc(ms.n * r * sizeof *u);
    CHECK(hy_multisine_design(&ms, r, u, &e) == HY_OK, "%s", e.msg);
    /* lines 1..3 hold the power, DC none: the mean is 0 to rounding (std 50) */
    double mean = 0;
    for (size_t i = 0; i < ms.n * r; i++)
        mean += u[i] / (double)(ms.n * r);
    CHECK(fabs(mean) < 1e-12, "mean %g: DC excited", mean);
    free(u);
    hy_multisine_default(&ms);
    ms.fs = 1e-20;
    CHECK(hy_multisine_lines(&ms, &kmin, &kmax, &e) == HY_EINVAL && strstr(e.msg, "below fs/2"), "%s", e.msg);
    ms.fs = 1e-15;
    CHECK(hy_multisine_lines(&ms, &kmin, &kmax, &e) == HY_EINVAL && strstr(e.msg, "below fs/2"), "%s", e.msg);
    ms.fs = 1e308;
    CHECK(hy_multisine_lines(&ms, &kmin, &kmax, &e) == HY_EINVAL && strstr(e.msg, "holds no DFT line"), "%s",
          e.msg);
    ms.fs = 750;
    ms.fmin = 1e300;
    ms.fmax = 1e300;
    CHECK(hy_multisine_lines(&ms, &kmin, &kmax, &e) == HY_EINVAL && strstr(e.msg, "below fs/2"), "%s", e.msg);
    /* a sweep of 1e-300 Hz/s would last ~1e302 s: refused, length 0 */
    hy_sweep sw;
    hy_sweep_default(&sw);
    sw.rate = 1e-300;
    CHECK(hy_sweep_length(&sw, 750) == 0, "length %zu", hy_sweep_length(&sw, 750));
    CHECK(hy_sweep_fill(&sw, 750, NULL, 0, &e) == HY_EINVAL && strstr(e.msg, "more than the 1099511627776"), "%s",
          e.msg);
    hy_sweep_default(&sw);
    CHECK(hy_sweep_length(&sw, 1e300) == 0, "length at fs = 1e300");
}

int main(void)
{
    test_extreme_signals();
    test_multisine();
    test_upsample();
    test_decimate();
    test_noise();
    test_sweep();
    return hy_test_finish("test_signals");
}
