/* SPDX-License-Identifier: MIT */
/* hy_signal.h: the Bouc-Wen benchmark's signals (seeds/001, Sections 4-5):
 * input design, resampling, noise and the figure of merit of Eq. (6).
 *
 * A periodic multisine is designed at the integration rate (fs * r) and read
 * back at the working rate fs by taking every r-th sample; a 750 Hz period
 * from elsewhere is brought to the integration rate exactly with
 * hy_signal_upsample_fft().  Non-periodic inputs use hy_signal_upsample_sinc().
 * The output is brought back with hy_signal_decimate() (MATLAB decimate 'fir').
 *
 *     hy_multisine ms;  hy_multisine_default(&ms);
 *     double *u15k = malloc(ms.n * 20 * sizeof *u15k);
 *     hy_multisine_design(&ms, 20, u15k, &err);     // one period, 163840 samples
 *
 * Buffers are owned by the caller unless a function says it allocates; such
 * functions return memory to be released with free().
 */
#ifndef HY_SIGNAL_H
#define HY_SIGNAL_H

#include "hy_status.h"

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Random-phase multisine: lines of equal magnitude, phases uniform in [0, 2π). */
typedef struct hy_multisine {
    double fs;    /* working sampling rate, Hz (750)     */
    size_t n;     /* samples per period at fs (8192)     */
    double fmin;  /* lowest excited frequency, Hz (5)    */
    double fmax;  /* highest excited frequency, Hz (150) */
    double rms;   /* standard deviation, N (50)          */
    uint64_t seed;
} hy_multisine;

/* Linear sine sweep u = A sin(2π (f0 t + rate t²/2)), sampled at t = i / fs
 * for t in [0, T), T = (f1 - f0) / rate: the instantaneous frequency f0 +
 * rate t reaches f1 one sample after the last (as the published sweep). */
typedef struct hy_sweep {
    double amp;  /* N (40)             */
    double f0;   /* Hz (20)            */
    double f1;   /* Hz (50)            */
    double rate; /* Hz/s (10/60)       */
} hy_sweep;

/* xoshiro256** generator seeded through splitmix64 (reproducible everywhere). */
typedef struct hy_rng {
    uint64_t s[4];
} hy_rng;

/* Seeds r from one 64-bit seed (r NULL: nothing done). */
void hy_rng_seed(hy_rng *r, uint64_t seed);
/* Next uniform double in [0, 1) with 53 random bits (r NULL: NaN). */
double hy_rng_uniform(hy_rng *r);
/* Next standard normal deviate (Box-Muller; one deviate per two uniforms; r
 * NULL: NaN). */
double hy_rng_normal(hy_rng *r);

/* Sets ms to the benchmark's 750 Hz, 8192 samples, 5-150 Hz, 50 N, seed 1
 * (ms NULL: nothing done; so for hy_sweep_default and hy_sweep_validation's
 * sw). */
void hy_multisine_default(hy_multisine *ms);

/* First and last excited DFT line of a period: ceil(fmin/f0) .. ceil(fmax/f0),
 * f0 = fs/n (the official signal holds lines 55..1639); the first is at least
 * line 1 (DC is never excited).  HY_EINVAL if the band holds no line or
 * reaches fs/2, for any finite fs, fmin, fmax.  ms must not be NULL
 * (HY_EINVAL); kmin and kmax may be NULL (not written). */
int hy_multisine_lines(const hy_multisine *ms, size_t *kmin, size_t *kmax,
                       hy_error *err);

/* One period designed at the integration rate fs * r: n * r samples into u,
 * scaled so that sqrt(sum u² / (n r - 1)) = rms (MATLAB's std, as the
 * benchmark's example does).  u[r i] is the period at the working rate fs.
 * ms and u must not be NULL (HY_EINVAL). */
int hy_multisine_design(const hy_multisine *ms, size_t r, double *u,
                        hy_error *err);

/* Sets sw to the paper's sweep (seeds/001, Section 5): 40 N, 20 -> 50 Hz at
 * 10 Hz/min (180 s).  The defaults of both `hystviz boucwen data --signal
 * sweep` and the scene's [input] kind = sweep: the one table of them. */
void hy_sweep_default(hy_sweep *sw);

/* Most samples a sweep may have (2^40: 8 TiB of doubles, beyond any machine;
 * the bound keeps the count representable before the memory caps apply). */
#define HY_SWEEP_MAX_SAMPLES 1099511627776.0

/* Sets sw to the benchmark's published validation sweep: 40 N, 18 -> 52 Hz at
 * 10 Hz/min (204 s, the paper's 20-50 Hz with 2 Hz either side), that is
 * u = 40 sin(2π (18 t + t²/12)); at 750 Hz, 153000 samples.  The data set
 * was decimated in one stage (MATLAB decimate(y, 20, 'fir')). */
void hy_sweep_validation(hy_sweep *sw);

/* Number of samples of the sweep at rate fs: ceil(T fs), the samples with
 * t = i / fs < T (135000 for the paper's at 750 Hz); 0 if the parameters are
 * invalid or sw is NULL (then hy_sweep_fill refuses them with a message). */
size_t hy_sweep_length(const hy_sweep *sw, double fs);

/* Writes n samples of the sweep at rate fs (sample i at t = i / fs).  sw
 * must not be NULL, nor u when n > 0 (HY_EINVAL). */
int hy_sweep_fill(const hy_sweep *sw, double fs, double *u, size_t n,
                  hy_error *err);

/* Writes n samples of amp sin(2π f t) at rate fs (u must not be NULL when n
 * > 0: HY_EINVAL). */
int hy_sine_fill(double amp, double f, double fs, double *u, size_t n,
                 hy_error *err);

/* Reads an input file: one value a line, or "t,u" a line (uniform t).  Blank
 * lines and lines starting with '#' are skipped.  On success *u (allocated,
 * free() it) holds *n >= 1 values and *fs is 1/Δt, or 0 for one-column files.
 * A missing, empty or malformed file is HY_EIO / HY_EINVAL with "file:line".
 * Times are uniform to the precision they are printed with: a time printed
 * to d significant digits or D decimals (the most any time of the file has)
 * has resolution q = max(10^(floor(log10|t|) - d + 1), 10^-D) and is within
 * q/2 of the true time; each step must match the first within those halves,
 * each time the grid through the first and last times (Δt = (t[n-1] - t[0])
 * / (n - 1)) within (q + the coarser end's q) / 2, and q <= Δt/2 so that a
 * missing sample is always seen.  Lines are at most 4095 bytes; a NUL byte
 * is refused with file:line:col.  path, u and n must not be NULL (HY_EINVAL,
 * *u NULL and *n 0 when given); fs may be NULL (not written). */
int hy_signal_read(const char *path, double **u, size_t *n, double *fs,
                   hy_error *err);

/* Exact band-limited interpolation of one period of a periodic signal by
 * zero-padding its DFT: x (n samples) -> y (n r samples), y[r i] = x[i] up to
 * rounding.  A Nyquist line (even n) is split evenly between ±n/2.  Here and
 * in hy_signal_upsample_sinc: x and y must not be NULL and n r must fit in
 * memory (HY_EINVAL). */
int hy_signal_upsample_fft(const double *x, size_t n, size_t r, double *y,
                           hy_error *err);

/* Band-limited interpolation of a non-periodic signal: Kaiser-windowed sinc
 * (β 8, 16 input samples each side, cutoff at the input Nyquist), with the
 * signal continued past its ends by point reflection (2 x[0] - x[i]).
 * x (n >= 2 samples) -> y (n r samples: every input sample's interval, the
 * last one extrapolated from the reflection), y[r i] = x[i] exactly.  Its
 * accuracy limit (the window's, worst near fs/2 and at the ends) is drawn by
 * scenes/bw_sinc_upsampling_error.scene. */
int hy_signal_upsample_sinc(const double *x, size_t n, size_t r, double *y,
                            hy_error *err);

/* In-place real DFT of n values into GSL's halfcomplex layout
 * (hy_signal_fft_forward), and its inverse (hy_signal_fft_inverse, which
 * divides by n).  Mixed radix: any n >= 1 (n 0 or x NULL: HY_EINVAL). */
int hy_signal_fft_forward(double *x, size_t n, hy_error *err);
int hy_signal_fft_inverse(double *x, size_t n, hy_error *err);

/* Number of taps of the decimation filter: 31 (MATLAB fir1 order 30). */
#define HY_DECIMATE_TAPS 31

/* MATLAB fir1(30, 1/r): ideal low-pass of cutoff 1/r (of Nyquist) truncated
 * to 31 taps, Hamming window, scaled to unit DC gain.  r >= 2 (r < 2 or b
 * NULL: nothing done). */
void hy_fir1_lowpass(size_t r, double b[HY_DECIMATE_TAPS]);

/* MATLAB decimate(x, r, 'fir'): filters with hy_fir1_lowpass(r), zero phase
 * (the 15-sample delay compensated), the ends continued by point reflection,
 * and keeps samples 0, r, 2r, ...: writes ceil(n / r) values to y.  n >= 16.
 * x and y must not be NULL (HY_EINVAL). */
int hy_signal_decimate(const double *x, size_t n, size_t r, double *y,
                       hy_error *err);

/* Decimation by r in one stage (staged == 0) or in its prime factors in
 * increasing order (20 -> 2, 2, 5; what is left above 65536 once the factors
 * up to it are divided out is one stage: a prime for r < 2^32).  Writes
 * ceil(n / r) samples to y either way, and that count to *ny.  Allocates
 * scratch internally.  x and y must not be NULL (HY_EINVAL); ny may be NULL
 * (not written). */
int hy_signal_decimate_stages(const double *x, size_t n, size_t r, int staged,
                              double *y, size_t *ny, hy_error *err);

/* How far hy_signal_decimate_stages(·, r, staged) reaches: output k is a
 * function of the input samples k r - reach .. k r + reach alone (and of
 * reflections of the record only where that window leaves it).  So a record
 * cut anywhere outside those windows, at a multiple of r at its start, gives
 * the same bits for the outputs whose windows it holds.  r >= 1. */
size_t hy_signal_decimate_reach(size_t r, int staged);

/* Gaussian noise band-limited to [0, band_hz] at rate fs, scaled so that its
 * sample RMS is exactly rms (rms = 0 writes zeros).  band_hz >= fs/2 gives
 * white noise; otherwise the DFT lines above band_hz are removed.  Seeded and
 * reproducible.  Adds to out (out[i] += noise[i]); out must not be NULL when
 * n > 0 (HY_EINVAL). */
int hy_signal_add_noise(double *out, size_t n, double rms, double band_hz,
                        double fs, uint64_t seed, hy_error *err);

/* e_RMS of Eq. (6): sqrt(mean((a - b)²)) over n >= 1 samples (0 for n = 0;
 * a or b NULL with n > 0: NaN). */
double hy_signal_erms(const double *a, const double *b, size_t n);

/* Plain RMS sqrt(mean(x²)) (0 for n = 0; x NULL with n > 0: NaN). */
double hy_signal_rms(const double *x, size_t n);

#ifdef __cplusplus
}
#endif

#endif
