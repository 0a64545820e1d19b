/* SPDX-License-Identifier: MIT */
/* hy_resample.c: band-limited upsampling (DFT zero-padding, windowed sinc)
 * and MATLAB decimate(x, r, 'fir') (fir1 order 30, Hamming) for the
 * benchmark's 20x integration rate (seeds/001, Section 4). */
#include "hy_signal.h"

#include "hy_args.h"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_fft_halfcomplex.h>
#include <gsl/gsl_fft_real.h>
#include <gsl/gsl_sf_bessel.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

/* In-place real forward DFT (GSL halfcomplex layout) of n values. */
static int fft_real(double *x, size_t n, hy_error *err)
{
    gsl_fft_real_wavetable *wt = gsl_fft_real_wavetable_alloc(n);
    gsl_fft_real_workspace *ws = gsl_fft_real_workspace_alloc(n);
    int rc = HY_OK;
    if (!wt || !ws)
        rc = hy_error_set(err, HY_ENOMEM, "out of memory for a DFT of %zu points", n);
    else if (gsl_fft_real_transform(x, 1, n, wt, ws) != GSL_SUCCESS)
        rc = hy_error_set(err, HY_ENUM, "GSL real DFT of %zu points failed", n);
    gsl_fft_real_wavetable_free(wt);
    gsl_fft_real_workspace_free(ws);
    return rc;
}

/* In-place inverse of fft_real (divides by n). */
static int ifft_halfcomplex(double *x, size_t n, hy_error *err)
{
    gsl_fft_halfcomplex_wavetable *wt = gsl_fft_halfcomplex_wavetable_alloc(n);
    gsl_fft_real_workspace *ws = gsl_fft_real_workspace_alloc(n);
    int rc = HY_OK;
    if (!wt || !ws)
        rc = hy_error_set(err, HY_ENOMEM, "out of memory for a DFT of %zu points", n);
    else if (gsl_fft_halfcomplex_inverse(x, 1, n, wt, ws) != GSL_SUCCESS)
        rc = hy_error_set(err, HY_ENUM, "GSL inverse DFT of %zu points failed", n);
    gsl_fft_halfcomplex_wavetable_free(wt);
    gsl_fft_real_workspace_free(ws);
    return rc;
}

int hy_signal_fft_forward(double *x, size_t n, hy_error *err)
{
    HY_NONNULL(err, x);
    if (n < 1)
        return hy_error_set(err, HY_EINVAL, "a DFT needs n >= 1 values");
    return fft_real(x, n, err);
}

int hy_signal_fft_inverse(double *x, size_t n, hy_error *err)
{
    HY_NONNULL(err, x);
    if (n < 1)
        return hy_error_set(err, HY_EINVAL, "a DFT needs n >= 1 values");
    return ifft_halfcomplex(x, n, err);
}

int hy_signal_upsample_fft(const double *x, size_t n, size_t r, double *y,
                           hy_error *err)
{
    HY_NONNULL(err, x);
    HY_NONNULL(err, y);
    if (n == 0 || r == 0)
        return hy_error_set(err, HY_EINVAL, "upsampling needs n >= 1 samples and r >= 1");
    if (n > SIZE_MAX / sizeof *y / r)
        return hy_error_set(err, HY_EINVAL, "upsampling: %zu x %zu samples do not fit in memory", n, r);
    size_t L = n * r;
    double *X = malloc(n * sizeof *X);
    if (!X)
        return hy_error_set(err, HY_ENOMEM, "out of memory for %zu samples", n);
    memcpy(X, x, n * sizeof *X);
    int rc = fft_real(X, n, err);
    if (rc) {
        free(X);
        return rc;
    }
    memset(y, 0, L * sizeof *y);
    double g = (double)r; /* the inverse divides by L = n r */
    y[0] = g * X[0];
    size_t half = (n - 1) / 2; /* complex lines 1 .. half */
    for (size_t k = 1; k <= half; k++) {
        y[2 * k - 1] = g * X[2 * k - 1];
        y[2 * k] = g * X[2 * k];
    }
    if (n % 2 == 0 && n >= 2) {
        if (r == 1)
            y[n - 1] = g * X[n - 1];
        else /* Nyquist line n/2 split: half at +n/2, half at -n/2 */
            y[n - 1] = 0.5 * g * X[n - 1];
    }
    free(X);
    return ifft_halfcomplex(y, L, err);
}

/* Kaiser window of shape beta at x in [-1, 1]. */
static double kaiser(double x, double beta)
{
    double a = 1.0 - x * x;
    if (a <= 0)
        return 0.0;
    return gsl_sf_bessel_I0(beta * sqrt(a)) / gsl_sf_bessel_I0(beta);
}

/* x continued by point reflection past both ends. */
static double reflect(const double *x, size_t n, long i)
{
    long last = (long)n - 1;
    /* n >= 2: each reflection brings i closer to [0, last], so this ends. */
    if (i < 0)
        return 2.0 * x[0] - reflect(x, n, -i);
    if (i > last)
        return 2.0 * x[last] - reflect(x, n, 2 * last - i);
    return x[i];
}

int hy_signal_upsample_sinc(const double *x, size_t n, size_t r, double *y,
                            hy_error *err)
{
    enum { K = 16 };
    const double beta = 8.0;
    HY_NONNULL(err, x);
    HY_NONNULL(err, y);
    if (n < 2 || r == 0)
        return hy_error_set(err, HY_EINVAL, "sinc upsampling needs n >= 2 samples and r >= 1");
    if (n > SIZE_MAX / sizeof *y / r || r > SIZE_MAX / sizeof *y / (2 * K))
        return hy_error_set(err, HY_EINVAL, "sinc upsampling: %zu x %zu samples do not fit in memory", n, r);
    /* Polyphase kernel: w[j][m] for fraction j/r and input offset m - K + 1. */
    double *w = malloc(r * 2 * K * sizeof *w);
    if (!w)
        return hy_error_set(err, HY_ENOMEM, "out of memory for the sinc kernel");
    for (size_t j = 0; j < r; j++) {
        double frac = (double)j / (double)r;
        for (int m = 0; m < 2 * K; m++) {
            double d = frac - (double)(m - K + 1); /* distance to sample */
            double s = d == 0 ? 1.0 : sin(M_PI * d) / (M_PI * d);
            w[j * 2 * K + m] = s * kaiser(d / K, beta);
        }
    }
    for (size_t i = 0; i < n; i++) {
        for (size_t j = 0; j < r; j++) {
            if (j == 0) { /* sinc zeros: exact samples */
                y[i * r] = x[i];
                continue;
            }
            const double *wj = w + j * 2 * K;
            double acc = 0.0;
            for (int m = 0; m < 2 * K; m++)
                acc += wj[m] * reflect(x, n, (long)i + m - K + 1);
            y[i * r + j] = acc;
        }
    }
    free(w);
    return HY_OK;
}

void hy_fir1_lowpass(size_t r, double b[HY_DECIMATE_TAPS])
{
    const int M = (HY_DECIMATE_TAPS - 1) / 2; /* 15: the group delay */
    if (r < 2 || !b)
        return;
    double wn = 1.0 / (double)r, sum = 0.0;
    /* half and mirror, as MATLAB's hamming does: exactly symmetric taps */
    for (int i = 0; i <= M; i++) {
        int d = M - i;
        double ideal = d == 0 ? wn : sin(M_PI * wn * d) / (M_PI * d);
        double ham = 0.54 - 0.46 * cos(2.0 * M_PI * i / (HY_DECIMATE_TAPS - 1));
        b[i] = b[HY_DECIMATE_TAPS - 1 - i] = ideal * ham;
    }
    for (int i = 0; i < HY_DECIMATE_TAPS; i++)
        sum += b[i];
    for (int i = 0; i < HY_DECIMATE_TAPS; i++)
        b[i] /= sum;
}

/* Output k of the decimation by r: the taps b over x around k r, the
 * record reflected past its ends. */
static double decimate_one(const double *x, size_t n, size_t r, const double *b, size_t k)
{
    const long M = (HY_DECIMATE_TAPS - 1) / 2;
    long c = (long)(k * r);
    double acc = 0.0;
    if (c >= M && c + M < (long)n) {
        const double *xc = x + c - M;
        for (long j = 0; j < HY_DECIMATE_TAPS; j++)
            acc += b[j] * xc[j];
    } else {
        for (long j = 0; j < HY_DECIMATE_TAPS; j++)
            acc += b[j] * reflect(x, n, c - M + j);
    }
    return acc;
}

int hy_signal_decimate(const double *x, size_t n, size_t r, double *y,
                       hy_error *err)
{
    const long M = (HY_DECIMATE_TAPS - 1) / 2;
    HY_NONNULL(err, x);
    HY_NONNULL(err, y);
    if (r < 1)
        return hy_error_set(err, HY_EINVAL, "decimation factor r must be >= 1");
    if (r == 1) {
        memmove(y, x, n * sizeof *y);
        return HY_OK;
    }
    if (n < (size_t)M + 1)
        return hy_error_set(err, HY_EINVAL,
                            "decimation needs at least %ld samples (got %zu)",
                            M + 1, n);
    double b[HY_DECIMATE_TAPS];
    hy_fir1_lowpass(r, b);
    size_t nout = (n + r - 1) / r, k = 0;
    while (k < nout && (long)(k * r) < M) /* the reflected head */
        y[k] = decimate_one(x, n, r, b, k), k++;
    /* four outputs at a time inside the record: each sum in the order
       decimate_one adds (the same roundings), but four chains of additions
       in flight instead of one (the FIR was 13 % of a bw_fig1a render in
       serve) */
    for (; k + 4 <= nout && (long)((k + 3) * r) + M < (long)n; k += 4) {
        const double *x0 = x + k * r - M, *x1 = x0 + r, *x2 = x1 + r, *x3 = x2 + r;
        double a0 = 0.0, a1 = 0.0, a2 = 0.0, a3 = 0.0;
        for (long j = 0; j < HY_DECIMATE_TAPS; j++) {
            a0 += b[j] * x0[j];
            a1 += b[j] * x1[j];
            a2 += b[j] * x2[j];
            a3 += b[j] * x3[j];
        }
        y[k] = a0, y[k + 1] = a1, y[k + 2] = a2, y[k + 3] = a3;
    }
    for (; k < nout; k++)
        y[k] = decimate_one(x, n, r, b, k);
    return HY_OK;
}

/* The factors of a staged (prime factors, increasing) or single-stage
 * decimation by r into f; returns their count (0 for r = 1). */
static size_t decimate_factors(size_t r, int staged, size_t f[64])
{
    size_t nf = 0;
    if (staged) {
        size_t q = r;
        /* trial division by p <= 65536 and p <= sqrt(q): what is left
           above 1 is one stage, the largest prime factor when r < 2^32 (a
           large prime r took r divisions, 2^61 - 1 a hang) */
        for (size_t p = 2; p <= 65536 && p <= q / p && nf < 64; p++)
            while (q % p == 0) {
                f[nf++] = p;
                q /= p;
            }
        if (q > 1 && nf < 64)
            f[nf++] = q;
    } else if (r > 1) {
        f[nf++] = r;
    }
    return nf;
}

size_t hy_signal_decimate_reach(size_t r, int staged)
{
    /* stage s reads M of its inputs either side, each F_s = f_1 .. f_(s-1)
       samples of the record apart: M (1 + f_1 + f_1 f_2 + ...) */
    size_t f[64], nf = decimate_factors(r, staged, f), reach = 0, span = 1;
    for (size_t s = 0; s < nf; s++) {
        reach += (size_t)(HY_DECIMATE_TAPS - 1) / 2 * span;
        span *= f[s];
    }
    return reach;
}

int hy_signal_decimate_stages(const double *x, size_t n, size_t r, int staged,
                              double *y, size_t *ny, hy_error *err)
{
    size_t ny_local;
    HY_NONNULL(err, x);
    HY_NONNULL(err, y);
    if (!ny)
        ny = &ny_local;
    if (r < 1)
        return hy_error_set(err, HY_EINVAL, "decimation factor r must be >= 1");
    size_t f[64], nf = decimate_factors(r, staged, f);
    if (nf == 0) {
        memmove(y, x, n * sizeof *y);
        *ny = n;
        return HY_OK;
    }
    double *a = malloc(n * sizeof *a), *bb = malloc(n * sizeof *bb);
    int rc = HY_OK;
    if (!a || !bb) {
        rc = hy_error_set(err, HY_ENOMEM, "out of memory for %zu samples", n);
    } else {
        memcpy(a, x, n * sizeof *a);
        size_t m = n;
        for (size_t s = 0; s < nf && !rc; s++) {
            rc = hy_signal_decimate(a, m, f[s], bb, err);
            m = (m + f[s] - 1) / f[s];
            double *t = a;
            a = bb;
            bb = t;
        }
        if (!rc) {
            memcpy(y, a, m * sizeof *y);
            *ny = m;
        }
    }
    free(a);
    free(bb);
    return rc;
}
