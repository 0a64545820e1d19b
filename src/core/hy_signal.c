/* SPDX-License-Identifier: MIT */
/* hy_signal.c: the benchmark's test signals (random-phase multisine, sine
 * sweep, sine, input files), band-limited Gaussian output noise and the
 * e_RMS figure of merit of Eq. (6) (seeds/001, Sections 4-5). */
#include "hy_signal.h"

#include "hy_args.h"
#include "hy_file.h"
#include "hy_input.h"
#include "hy_os.h"

#include <errno.h>
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/types.h>

static uint64_t splitmix64(uint64_t *x)
{
    uint64_t z = (*x += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
}

void hy_rng_seed(hy_rng *r, uint64_t seed)
{
    if (!r)
        return;
    for (int i = 0; i < 4; i++)
        r->s[i] = splitmix64(&seed);
}

static uint64_t rotl(uint64_t x, int k)
{
    return (x << k) | (x >> (64 - k));
}

/* xoshiro256** (Blackman and Vigna). */
static uint64_t rng_next(hy_rng *r)
{
    uint64_t *s = r->s;
    uint64_t out = rotl(s[1] * 5, 7) * 9, t = s[1] << 17;
    s[2] ^= s[0];
    s[3] ^= s[1];
    s[1] ^= s[2];
    s[0] ^= s[3];
    s[2] ^= t;
    s[3] = rotl(s[3], 45);
    return out;
}

double hy_rng_uniform(hy_rng *r)
{
    if (!r)
        return NAN;
    return (double)(rng_next(r) >> 11) * 0x1.0p-53;
}

double hy_rng_normal(hy_rng *r)
{
    if (!r)
        return NAN;
    double u1 = 1.0 - hy_rng_uniform(r); /* (0, 1]: log is finite */
    double u2 = hy_rng_uniform(r);
    return sqrt(-2.0 * log(u1)) * cos(2.0 * M_PI * u2);
}

void hy_multisine_default(hy_multisine *ms)
{
    if (!ms)
        return;
    ms->fs = 750.0;
    ms->n = 8192;
    ms->fmin = 5.0;
    ms->fmax = 150.0;
    ms->rms = 50.0;
    ms->seed = 1;
}

int hy_multisine_lines(const hy_multisine *ms, size_t *kmin, size_t *kmax,
                       hy_error *err)
{
    size_t kmin_local, kmax_local;
    if (!kmin)
        kmin = &kmin_local;
    if (!kmax)
        kmax = &kmax_local;
    HY_NONNULL(err, ms);
    if (!(isfinite(ms->fs) && ms->fs > 0))
        return hy_error_set(err, HY_EINVAL, "multisine fs = %g must be finite and > 0", ms->fs);
    if (ms->n < 4)
        return hy_error_set(err, HY_EINVAL, "multisine period n = %zu must be >= 4", ms->n);
    if (!(isfinite(ms->fmin) && ms->fmin > 0))
        return hy_error_set(err, HY_EINVAL, "multisine fmin = %g must be finite and > 0", ms->fmin);
    if (!(isfinite(ms->fmax) && ms->fmax >= ms->fmin))
        return hy_error_set(err, HY_EINVAL, "multisine fmax = %g must be finite and >= fmin", ms->fmax);
    if (!(isfinite(ms->rms) && ms->rms >= 0))
        return hy_error_set(err, HY_EINVAL, "multisine rms = %g must be finite and >= 0", ms->rms);
    /* lines in units of f0 = fs/n; the tiny slack keeps exact integers.  The
       bounds are checked in double before any conversion (fs may be 1e-20 or
       1e308), and DC (line 0, which has no phase) is never excited. */
    double lo = ceil(ms->fmin * (double)ms->n / ms->fs - 1e-9);
    double hi = ceil(ms->fmax * (double)ms->n / ms->fs - 1e-9);
    if (!(2 * hi < (double)ms->n))
        return hy_error_set(err, HY_EINVAL,
                            "multisine fmax = %g Hz must stay below fs/2 = %g Hz",
                            ms->fmax, ms->fs / 2);
    if (lo < 1)
        lo = 1;
    if (!(hi >= lo))
        return hy_error_set(err, HY_EINVAL,
                            "multisine band %g .. %g Hz holds no DFT line: the lines of a period "
                            "of %zu samples at fs = %g Hz are %g Hz apart",
                            ms->fmin, ms->fmax, ms->n, ms->fs, ms->fs / (double)ms->n);
    *kmin = (size_t)lo;
    *kmax = (size_t)hi;
    return HY_OK;
}

int hy_multisine_design(const hy_multisine *ms, size_t r, double *u,
                        hy_error *err)
{
    size_t kmin, kmax;
    HY_NONNULL(err, ms);
    HY_NONNULL(err, u);
    int rc = hy_multisine_lines(ms, &kmin, &kmax, err);
    if (rc)
        return rc;
    if (r < 1 || ms->n > SIZE_MAX / sizeof *u / r)
        return hy_error_set(err, HY_EINVAL, "upsampling factor r = %zu must be >= 1 and n r samples "
                            "must fit in memory", r);
    size_t L = ms->n * r;
    memset(u, 0, L * sizeof *u);
    hy_rng g;
    hy_rng_seed(&g, ms->seed);
    for (size_t k = kmin; k <= kmax; k++) { /* unit lines, random phase */
        double ph = 2.0 * M_PI * hy_rng_uniform(&g);
        u[2 * k - 1] = cos(ph);
        u[2 * k] = sin(ph);
    }
    rc = hy_signal_fft_inverse(u, L, err);
    if (rc)
        return rc;
    double ss = 0.0;
    for (size_t i = 0; i < L; i++)
        ss += u[i] * u[i];
    double g_scale = ms->rms / sqrt(ss / (double)(L - 1)); /* MATLAB std */
    for (size_t i = 0; i < L; i++)
        u[i] *= g_scale;
    return HY_OK;
}

void hy_sweep_default(hy_sweep *sw)
{
    if (!sw)
        return;
    sw->amp = 40.0;
    sw->f0 = 20.0;
    sw->f1 = 50.0;
    sw->rate = 10.0 / 60.0;
}

void hy_sweep_validation(hy_sweep *sw)
{
    if (!sw)
        return;
    sw->amp = 40.0;
    sw->f0 = 18.0;
    sw->f1 = 52.0;
    sw->rate = 10.0 / 60.0;
}

/* The sweep's sample count as a double (finite once the duration is checked);
 * the slack keeps whole products whole: 204 s x 750 Hz is 153000. */
static double sweep_samples(const hy_sweep *sw, double fs)
{
    return ceil((sw->f1 - sw->f0) / sw->rate * fs - 1e-9);
}

static int sweep_check(const hy_sweep *sw, double fs, hy_error *err)
{
    if (!sw)
        return hy_error_set(err, HY_EINVAL, "the sweep sw must not be NULL");
    if (!(isfinite(sw->amp)))
        return hy_error_set(err, HY_EINVAL, "sweep amplitude %g must be finite", sw->amp);
    if (!(isfinite(sw->f0) && sw->f0 >= 0))
        return hy_error_set(err, HY_EINVAL, "sweep start frequency f0 = %g must be finite and >= 0", sw->f0);
    if (!(isfinite(sw->f1) && sw->f1 > sw->f0))
        return hy_error_set(err, HY_EINVAL, "sweep end frequency f1 = %g must be finite and > f0", sw->f1);
    if (!(isfinite(sw->rate) && sw->rate > 0))
        return hy_error_set(err, HY_EINVAL, "sweep rate %g Hz/s must be finite and > 0", sw->rate);
    if (!(isfinite(fs) && fs > 2 * sw->f1))
        return hy_error_set(err, HY_EINVAL, "sampling rate fs = %g must exceed twice the sweep's f1", fs);
    /* checked in double before hy_sweep_length converts it (rate may be 1e-300) */
    double dur = (sw->f1 - sw->f0) / sw->rate;
    if (!(dur * fs < HY_SWEEP_MAX_SAMPLES))
        return hy_error_set(err, HY_EINVAL,
                            "a sweep from %g to %g Hz at %g Hz/s lasts %g s: %.3g samples at fs = %g Hz, "
                            "more than the %.0f a sweep may hold", sw->f0, sw->f1, sw->rate, dur,
                            dur * fs, fs, HY_SWEEP_MAX_SAMPLES);
    /* the length hy_sweep_length gives, so a sweep that passes has a sample */
    if (!(sweep_samples(sw, fs) >= 1))
        return hy_error_set(err, HY_EINVAL,
                            "a sweep from %g to %g Hz at %g Hz/s lasts %g s: less than one sample at fs = %g Hz",
                            sw->f0, sw->f1, sw->rate, dur, fs);
    return HY_OK;
}

size_t hy_sweep_length(const hy_sweep *sw, double fs)
{
    if (sweep_check(sw, fs, NULL))
        return 0;
    return (size_t)sweep_samples(sw, fs);
}

int hy_sweep_fill(const hy_sweep *sw, double fs, double *u, size_t n,
                  hy_error *err)
{
    int rc = sweep_check(sw, fs, err);
    if (rc)
        return rc;
    HY_NONNULL_N(err, u, n);
    for (size_t i = 0; i < n; i++) {
        double t = (double)i / fs;
        u[i] = sw->amp * sin(2.0 * M_PI * (sw->f0 * t + 0.5 * sw->rate * t * t));
    }
    return HY_OK;
}

int hy_sine_fill(double amp, double f, double fs, double *u, size_t n,
                 hy_error *err)
{
    HY_NONNULL_N(err, u, n);
    if (!isfinite(amp))
        return hy_error_set(err, HY_EINVAL, "sine amplitude %g must be finite", amp);
    if (!(isfinite(f) && f > 0))
        return hy_error_set(err, HY_EINVAL, "sine frequency %g must be finite and > 0", f);
    if (!(isfinite(fs) && fs > 2 * f))
        return hy_error_set(err, HY_EINVAL, "sampling rate fs = %g must exceed twice the sine frequency", fs);
    for (size_t i = 0; i < n; i++)
        u[i] = amp * sin(2.0 * M_PI * f * (double)i / fs);
    return HY_OK;
}

/* The digits a number was printed with: *sig significant digits (from the
 * first nonzero one, trailing zeros included) and *dec the decimal place of
 * its last digit ("3720.00133" -> 9, 5; "1.23457e+01" -> 6, 4; "47" -> 2, 0).
 * Hexadecimal numbers are exact: 17 and 1074 (as fine as a double gets). */
static void printed_digits(const char *s, const char *end, double *sig, double *dec)
{
    const char *p = s + (*s == '+' || *s == '-');
    *sig = 17;
    *dec = 1074;
    if (p[0] == '0' && (p[1] == 'x' || p[1] == 'X'))
        return;
    double nsig = 0, frac = 0;
    int point = 0;
    for (; p < end && ((*p >= '0' && *p <= '9') || *p == '.'); p++) {
        if (*p == '.') {
            point = 1;
            continue;
        }
        nsig += nsig > 0 || *p != '0';
        frac += point;
    }
    double e = p < end && (*p == 'e' || *p == 'E') ? strtod(p + 1, NULL) : 0.0;
    *sig = nsig;
    *dec = fmax(-400.0, fmin(1074.0, frac - e));
}

/* Parses up to 2 numbers separated by ',' or blanks; returns the count or -1.
 * sig, dec: the digits the first was printed with (printed_digits). */
static int parse_line(char *s, double v[2], double *sig, double *dec, char **bad)
{
    int n = 0;
    for (;;) {
        while (*s == ' ' || *s == '\t' || *s == '\r' || *s == '\n')
            s++;
        if (*s == '\0')
            return n;
        if (n == 2) {
            *bad = s;
            return -1;
        }
        char *end;
        errno = 0;
        v[n] = strtod(s, &end);
        if (end == s || !isfinite(v[n])) {
            *bad = s;
            return -1;
        }
        if (n == 0)
            printed_digits(s, end, sig, dec);
        n++;
        s = end;
        while (*s == ' ' || *s == '\t')
            s++;
        if (*s == ',')
            s++;
    }
}

/* Appends v to the growing array *a of *n values (capacity *cap). */
static int push(double **a, size_t *n, size_t *cap, double v)
{
    if (*n == *cap) {
        size_t nc = *cap ? 2 * *cap : 1024;
        double *na = realloc(*a, nc * sizeof *na);
        if (!na)
            return -1;
        *a = na;
        *cap = nc;
    }
    (*a)[(*n)++] = v;
    return 0;
}

/* The time column of a "t,u" file as read: times, line numbers, and the most
 * significant digits and decimals any time was printed with. */
typedef struct time_col {
    double *t, *line;
    size_t n, nl, cap_t, cap_l;
    double sig, dec;
} time_col;

static void time_col_free(time_col *c)
{
    free(c->t);
    free(c->line);
}

/* Resolution of a time t of the file: the place value of the last digit it
 * was printed with, whether to d significant digits (%.6g, trailing zeros
 * dropped: "3720" may be 3720.00) or to D decimals (%.6f), d and D the most
 * seen in the file: max(10^(floor(log10|t|) - d + 1), 10^-D). */
static double time_resolution(const time_col *c, double t)
{
    double e = t != 0 ? floor(log10(fabs(t))) - c->sig + 1 : -1074.0;
    return pow(10.0, fmax(e, -c->dec));
}

/* Uniform times, to the precision they were printed with.  With q[i] the
 * resolution of t[i] (time_resolution: the printed time is within q[i]/2 of
 * the true one), each step t[i] - t[i-1] is within (q[i] + q[i-1] + q[0] +
 * q[1]) / 2 of the first one, and with dt = (t[n-1] - t[0]) / (n - 1), the
 * grid through the first and last times (which bounds a slow drift), the
 * true times being uniform means
 *     |t[i] - (t[0] + i dt)| <= (q[i] + max(q[0], q[n-1])) / 2,
 * to which 1e-6 dt and 8 ulps of t are added for the arithmetic.  Times must
 * increase, and every q[i] <= dt / 2, so that a missing or repeated sample
 * (off by dt) never passes.  Sets *dt. */
static int check_uniform(const time_col *c, const char *path, double *dt, hy_error *err)
{
    size_t n = c->n;
    for (size_t i = 1; i < n; i++)
        if (!(c->t[i] > c->t[i - 1]))
            return hy_error_set(err, HY_EINVAL, "%s:%zu: time %.17g is not after the previous time %.17g",
                                path, (size_t)c->line[i], c->t[i], c->t[i - 1]);
    /* first, each step against the first one (to name where the spacing
       changes): both are differences of printed times, each off by q/2 */
    double d01 = c->t[1] - c->t[0], q01 = time_resolution(c, c->t[0]) + time_resolution(c, c->t[1]);
    for (size_t i = 2; i < n; i++) {
        double di = c->t[i] - c->t[i - 1];
        double tol = 0.5 * (q01 + time_resolution(c, c->t[i]) + time_resolution(c, c->t[i - 1])) + 1e-6 * d01 +
                     8 * DBL_EPSILON * fabs(c->t[i]);
        if (!(fabs(di - d01) <= tol))
            return hy_error_set(err, HY_EINVAL,
                                "%s:%zu: time %.17g breaks the uniform spacing %.17g of the first two lines "
                                "(by %.3g, more than the %.3g their printed digits allow)",
                                path, (size_t)c->line[i], c->t[i], d01, di - d01, tol);
    }
    *dt = (c->t[n - 1] - c->t[0]) / (double)(n - 1);
    double qend = fmax(time_resolution(c, c->t[0]), time_resolution(c, c->t[n - 1]));
    for (size_t i = 0; i < n; i++) {
        size_t line = (size_t)c->line[i];
        double q = time_resolution(c, c->t[i]);
        if (!(q <= 0.5 * *dt))
            return hy_error_set(err, HY_EINVAL,
                                "%s:%zu: time %.17g is printed to a resolution of %g, too coarse for the "
                                "spacing %g of the samples (print more digits)", path, line, c->t[i], q,
                                *dt);
        double off = c->t[i] - (c->t[0] + (double)i * *dt);
        double tol = 0.5 * (q + qend) + 1e-6 * *dt +
                     8 * DBL_EPSILON * fmax(fabs(c->t[0]), fabs(c->t[i]));
        if (!(fabs(off) <= tol))
            return hy_error_set(err, HY_EINVAL,
                                "%s:%zu: time %.17g is %.3g off the uniform spacing %.17g of the file's "
                                "first and last times (more than the %.3g its printed digits allow)",
                                path, line, c->t[i], off, *dt, tol);
    }
    return HY_OK;
}

/* One line of at most 4095 bytes into *buf (getline): 1, or 0 at the end, or
 * minus a status with err set (an over-long line, a NUL byte, no memory). */
static int next_line(FILE *f, const char *path, size_t lineno, char **buf, size_t *cap, hy_error *err)
{
    errno = 0;
    ssize_t len = getline(buf, cap, f);
    if (len < 0)
        return errno == ENOMEM ? -hy_error_set(err, HY_ENOMEM, "%s:%zu: out of memory", path, lineno) : 0;
    if (len > 4095)
        return -hy_error_set(err, HY_EINVAL, "%s:%zu: line too long", path, lineno);
    const char *nul = memchr(*buf, '\0', (size_t)len);
    if (nul)
        return -hy_error_set(err, HY_EINVAL, "%s:%zu:%zu: NUL byte in the line (is this a text file?)", path,
                             lineno, (size_t)(nul - *buf) + 1);
    return 1;
}

static int read_lines(FILE *f, const char *path, time_col *tc, double **u,
                      size_t *n, int *ncol, hy_error *err)
{
    char *line = NULL;
    size_t cap_u = 0, lineno = 0, cap = 0;
    int got, rc = HY_OK;
    *ncol = 0;
    while (!rc && (got = next_line(f, path, lineno + 1, &line, &cap, err)) != 0) {
        lineno++;
        if (got < 0) {
            rc = -got;
            break;
        }
        char *s = line;
        while (*s == ' ' || *s == '\t')
            s++;
        if (*s == '#' || *s == '\n' || *s == '\r' || *s == '\0')
            continue;
        double v[2], sig = 0, dec = 0;
        char *bad = NULL;
        int c = parse_line(s, v, &sig, &dec, &bad);
        if (c < 0) {
            char ex[96]; /* a file the user named: at most 20 bytes of the line, escaped */
            rc = hy_error_set(err, HY_EINVAL, "%s:%zu: expected one value or 't,u', got '%s'", path, lineno,
                              hy_file_excerpt(bad, strlen(bad), ex, sizeof ex));
        } else if (*ncol && c != *ncol)
            rc = hy_error_set(err, HY_EINVAL, "%s:%zu: %d column(s) where earlier lines have %d", path,
                              lineno, c, *ncol);
        else {
            *ncol = c;
            tc->sig = fmax(tc->sig, sig);
            tc->dec = fmax(tc->dec, dec);
            if ((c == 2 && (push(&tc->t, &tc->n, &tc->cap_t, v[0]) ||
                            push(&tc->line, &tc->nl, &tc->cap_l, (double)lineno))) ||
                push(u, n, &cap_u, v[c - 1]))
                rc = hy_error_set(err, HY_ENOMEM, "%s:%zu: out of memory", path, lineno);
        }
    }
    free(line);
    if (!rc && ferror(f))
        rc = hy_error_set(err, HY_EIO, "%s: read error", path);
    if (!rc && *n == 0)
        rc = hy_error_set(err, HY_EINVAL, "%s:%zu: no samples (empty file)", path, lineno);
    return rc;
}

int hy_signal_read(const char *path, double **u, size_t *n, double *fs,
                   hy_error *err)
{
    char *text;
    size_t len;
    if (u)
        *u = NULL;
    if (n)
        *n = 0;
    HY_NONNULL(err, path);
    HY_NONNULL(err, u);
    HY_NONNULL(err, n);
    int rc = hy_file_load(path, HY_INPUT_FILE_MAX, &text, &len, "cannot open", err);
    if (rc)
        return rc;
    FILE *f = len ? fmemopen(text, len, "r") : NULL; /* the checked bytes, read as a stream */
    time_col tc = {0};
    double *v = NULL, dt = 0;
    size_t nv = 0;
    int ncol = 0;
    rc = f ? read_lines(f, path, &tc, &v, &nv, &ncol, err)
           : len ? hy_error_set(err, HY_ENOMEM, "%s: out of memory", path)
                 : hy_error_set(err, HY_EINVAL, "%s:0: no samples (empty file)", path);
    if (f)
        fclose(f);
    free(text);
    if (!rc && ncol == 2 && nv >= 2)
        rc = check_uniform(&tc, path, &dt, err);
    time_col_free(&tc);
    if (rc) {
        free(v);
        return rc;
    }
    if (fs)
        *fs = dt > 0 ? 1.0 / dt : 0.0;
    *u = v;
    *n = nv;
    return HY_OK;
}

int hy_signal_add_noise(double *out, size_t n, double rms, double band_hz,
                        double fs, uint64_t seed, hy_error *err)
{
    HY_NONNULL_N(err, out, n);
    if (!(isfinite(rms) && rms >= 0))
        return hy_error_set(err, HY_EINVAL, "noise rms = %g must be finite and >= 0", rms);
    if (!(isfinite(fs) && fs > 0))
        return hy_error_set(err, HY_EINVAL, "noise sampling rate fs = %g must be finite and > 0", fs);
    if (!(band_hz > 0)) /* NaN too */
        return hy_error_set(err, HY_EINVAL, "noise band %g Hz must be > 0", band_hz);
    if (rms == 0 || n == 0)
        return HY_OK;
    double *w = malloc(n * sizeof *w);
    if (!w)
        return hy_error_set(err, HY_ENOMEM, "out of memory for %zu noise samples", n);
    hy_rng g;
    hy_rng_seed(&g, seed);
    for (size_t i = 0; i < n; i++)
        w[i] = hy_rng_normal(&g);
    int rc = HY_OK;
    if (band_hz < fs / 2) { /* brick-wall low-pass on the DFT lines */
        rc = hy_signal_fft_forward(w, n, err);
        for (size_t k = 1; !rc && 2 * k <= n; k++) {
            if ((double)k * fs / (double)n > band_hz) {
                w[2 * k - 1] = 0;
                if (2 * k < n)
                    w[2 * k] = 0;
            }
        }
        if (!rc)
            rc = hy_signal_fft_inverse(w, n, err);
    }
    double s = rc ? 0.0 : hy_signal_rms(w, n);
    if (!rc && s > 0)
        for (size_t i = 0; i < n; i++)
            out[i] += w[i] * (rms / s);
    free(w);
    return rc;
}

double hy_signal_erms(const double *a, const double *b, size_t n)
{
    double s = 0.0;
    if (n && (!a || !b))
        return NAN;
    for (size_t i = 0; i < n; i++)
        s += (a[i] - b[i]) * (a[i] - b[i]);
    return n ? sqrt(s / (double)n) : 0.0;
}

double hy_signal_rms(const double *x, size_t n)
{
    double s = 0.0;
    if (n && !x)
        return NAN;
    for (size_t i = 0; i < n; i++)
        s += x[i] * x[i];
    return n ? sqrt(s / (double)n) : 0.0;
}
