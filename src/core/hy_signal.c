/* hy_signal.c: the benchmark's test signals (random-phase multisine, sine
 * sweep, sine, input files), band-limited Gaussian output noise and the
 * e_RMS figure of merit of Eq. (6) (seeds/001, Sections 4-5). */
#include "hy_signal.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static uint64_t splitmix64(uint64_t *x)
{
    uint64_t z = (*x += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
}

void hy_rng_seed(hy_rng *r, uint64_t seed)
{
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
    return (double)(rng_next(r) >> 11) * 0x1.0p-53;
}

double hy_rng_normal(hy_rng *r)
{
    double u1 = 1.0 - hy_rng_uniform(r); /* (0, 1]: log is finite */
    double u2 = hy_rng_uniform(r);
    return sqrt(-2.0 * log(u1)) * cos(2.0 * M_PI * u2);
}

void hy_multisine_default(hy_multisine *ms)
{
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
    /* lines in units of f0 = fs/n; the tiny slack keeps exact integers */
    double lo = ms->fmin * (double)ms->n / ms->fs;
    double hi = ms->fmax * (double)ms->n / ms->fs;
    *kmin = (size_t)ceil(lo - 1e-9);
    *kmax = (size_t)ceil(hi - 1e-9);
    if (2 * *kmax >= ms->n)
        return hy_error_set(err, HY_EINVAL,
                            "multisine fmax = %g Hz must stay below fs/2 = %g Hz",
                            ms->fmax, ms->fs / 2);
    return HY_OK;
}

int hy_multisine_design(const hy_multisine *ms, size_t r, double *u,
                        hy_error *err)
{
    size_t kmin, kmax;
    int rc = hy_multisine_lines(ms, &kmin, &kmax, err);
    if (rc)
        return rc;
    if (r < 1)
        return hy_error_set(err, HY_EINVAL, "upsampling factor r must be >= 1");
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
    sw->amp = 40.0;
    sw->f0 = 20.0;
    sw->f1 = 50.0;
    sw->rate = 10.0 / 60.0;
}

void hy_sweep_validation(hy_sweep *sw)
{
    sw->amp = 40.0;
    sw->f0 = 18.0;
    sw->f1 = 52.0;
    sw->rate = 10.0 / 60.0;
}

static int sweep_check(const hy_sweep *sw, double fs, hy_error *err)
{
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
    if ((sw->f1 - sw->f0) / sw->rate * fs > 1e12)
        return hy_error_set(err, HY_EINVAL, "a sweep of %g s at %g Hz is more than 1e12 samples",
                            (sw->f1 - sw->f0) / sw->rate, fs);
    return HY_OK;
}

size_t hy_sweep_length(const hy_sweep *sw, double fs)
{
    if (sweep_check(sw, fs, NULL))
        return 0;
    /* the slack keeps whole products whole: 204 s x 750 Hz is 153000 */
    return (size_t)ceil((sw->f1 - sw->f0) / sw->rate * fs - 1e-9);
}

int hy_sweep_fill(const hy_sweep *sw, double fs, double *u, size_t n,
                  hy_error *err)
{
    int rc = sweep_check(sw, fs, err);
    if (rc)
        return rc;
    for (size_t i = 0; i < n; i++) {
        double t = (double)i / fs;
        u[i] = sw->amp * sin(2.0 * M_PI * (sw->f0 * t + 0.5 * sw->rate * t * t));
    }
    return HY_OK;
}

int hy_sine_fill(double amp, double f, double fs, double *u, size_t n,
                 hy_error *err)
{
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

/* Parses up to 2 numbers separated by ',' or blanks; returns the count or -1. */
static int parse_line(char *s, double v[2], char **bad)
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

static int read_lines(FILE *f, const char *path, double **t, double **u,
                      size_t *n, int *ncol, hy_error *err)
{
    char line[4096];
    size_t cap_t = 0, cap_u = 0, nt = 0, lineno = 0;
    *ncol = 0;
    while (fgets(line, sizeof line, f)) {
        lineno++;
        size_t len = strlen(line);
        if (len == sizeof line - 1 && line[len - 1] != '\n' && !feof(f))
            return hy_error_set(err, HY_EINVAL, "%s:%zu: line too long", path, lineno);
        char *s = line;
        while (*s == ' ' || *s == '\t')
            s++;
        if (*s == '#' || *s == '\n' || *s == '\r' || *s == '\0')
            continue;
        double v[2];
        char *bad = NULL;
        int c = parse_line(s, v, &bad);
        if (c < 0) {
            bad[strcspn(bad, "\r\n")] = '\0';
            return hy_error_set(err, HY_EINVAL,
                                "%s:%zu: expected one value or 't,u', got '%.40s'",
                                path, lineno, bad);
        }
        if (*ncol && c != *ncol)
            return hy_error_set(err, HY_EINVAL,
                                "%s:%zu: %d column(s) where earlier lines have %d",
                                path, lineno, c, *ncol);
        *ncol = c;
        if ((c == 2 && push(t, &nt, &cap_t, v[0])) || push(u, n, &cap_u, v[c - 1]))
            return hy_error_set(err, HY_ENOMEM, "%s:%zu: out of memory", path, lineno);
        if (c == 2 && nt >= 2) { /* uniform, increasing time */
            double dt = (*t)[1] - (*t)[0];
            double expect = (*t)[0] + (double)(nt - 1) * dt;
            if (!(dt > 0) || fabs(v[0] - expect) > 1e-6 * dt)
                return hy_error_set(err, HY_EINVAL,
                                    "%s:%zu: time %g breaks the uniform spacing "
                                    "%g of the first two lines", path, lineno,
                                    v[0], dt);
        }
    }
    if (ferror(f))
        return hy_error_set(err, HY_EIO, "%s: read error", path);
    if (*n == 0)
        return hy_error_set(err, HY_EINVAL, "%s:%zu: no samples (empty file)", path, lineno);
    return HY_OK;
}

int hy_signal_read(const char *path, double **u, size_t *n, double *fs,
                   hy_error *err)
{
    FILE *f = fopen(path, "r");
    if (!f)
        return hy_error_set(err, HY_EIO, "%s: cannot open: %s", path, strerror(errno));
    double *t = NULL, *v = NULL;
    size_t nv = 0;
    int ncol;
    int rc = read_lines(f, path, &t, &v, &nv, &ncol, err);
    fclose(f);
    if (rc) {
        free(t);
        free(v);
        return rc;
    }
    *fs = (ncol == 2 && nv >= 2) ? 1.0 / (t[1] - t[0]) : 0.0;
    free(t);
    *u = v;
    *n = nv;
    return HY_OK;
}

int hy_signal_add_noise(double *out, size_t n, double rms, double band_hz,
                        double fs, uint64_t seed, hy_error *err)
{
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
    for (size_t i = 0; i < n; i++)
        s += (a[i] - b[i]) * (a[i] - b[i]);
    return n ? sqrt(s / (double)n) : 0.0;
}

double hy_signal_rms(const double *x, size_t n)
{
    double s = 0.0;
    for (size_t i = 0; i < n; i++)
        s += x[i] * x[i];
    return n ? sqrt(s / (double)n) : 0.0;
}
