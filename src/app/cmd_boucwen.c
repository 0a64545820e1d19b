/* SPDX-License-Identifier: MIT */
/* cmd_boucwen.c: `hystviz boucwen`: Table 2 and synthesised benchmark data
 * (seeds/001, Sections 2-5: signal, 20x upsampling, Newmark, decimation,
 * output noise), written as CSV t,u,y through the output writer (hy_out). */
#include "cmd_boucwen.h"

#include "cli_opt.h"
#include "hy_boucwen.h"
#include "hy_config.h"
#include "hy_file.h"
#include "hy_out.h"
#include "hy_signal.h"

#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

static const char usage[] =
    "usage: hystviz boucwen table2 [--set-param NAME=VALUE]...\n"
    "       hystviz boucwen data --signal KIND [options] [-o FILE]\n"
    "       hystviz boucwen --help\n"
    "\n"
    "The Bouc-Wen hysteretic benchmark (Noel & Schoukens):\n"
    "  m y'' + c y' + k y + z = u,\n"
    "  z' = alpha y' - beta (gamma |y'| |z|^(nu-1) z + delta y' |z|^nu),\n"
    "integrated by Newmark (a 0.5, b 0.25, c 0.5) with Newton-Raphson at\n"
    "fs x UPSAMPLE Hz, then decimated like MATLAB decimate(y, r, 'fir') in the\n"
    "prime factors of r (20: 2, 2, 5).\n"
    "\n"
    "table2      print Table 2 (natural frequency and damping ratio from the\n"
    "            linearised stiffness k + alpha)\n"
    "data        write CSV 't,u,y' (s, N, m) at the working rate, %.17g\n"
    "\n";

/* After the options (C99's 4095-character limit keeps it apart from usage). */
static const char signals[] =
    "signals (--signal KIND):\n"
    "  multisine         random-phase multisine 5-150 Hz, 8192 samples a\n"
    "                    period at 750 Hz, std 50 N (set at the integration\n"
    "                    rate); P periods from rest (default 5), the first\n"
    "                    holds the transient; decimated in stages 2, 2, 5\n"
    "  validation        the official validation input uval_multisine.txt,\n"
    "                    P steady-state periods (default 1; comparable with\n"
    "                    yval_multisine.txt); noiseless unless --noise;\n"
    "                    decimated in stages 2, 2, 5 (as the data set)\n"
    "  validation-sweep  the benchmark's validation sine sweep, the data\n"
    "                    set yval_sinesweep (BoucWenFiles.zip, folder Test\n"
    "                    signals/Validation signals/, nonlinearbenchmark.org):\n"
    "                    u = 40 sin(2 pi (18 t + t^2/12)), t = n/750,\n"
    "                    n = 0..152999: 18 -> 52 Hz at 10 Hz/min over 204 s;\n"
    "                    made at 15000 Hz, decimated in ONE stage as the\n"
    "                    data set was (MATLAB decimate(y, 20, 'fir'));\n"
    "                    noiseless unless --noise; 153000 rows\n"
    "  sweep             linear sine sweep from rest, t in [0, T): defaults\n"
    "                    the paper's 40 N, 20 -> 50 Hz at 10 Hz/min (180 s,\n"
    "                    135000 rows; the scene's [input] kind = sweep has\n"
    "                    the same); made at the integration rate; decimated\n"
    "                    in stages 2, 2, 5 unless --single-stage\n"
    "  sine              120 N at 1 Hz, P periods from rest (default 10);\n"
    "                    decimated in stages 2, 2, 5\n"
    "  file              the force in --input FILE: one value a line or\n"
    "                    't,u' lines (uniform t gives fs); n samples are\n"
    "                    upsampled by a Kaiser-windowed sinc to n x UPSAMPLE\n"
    "                    and decimated back to one row per input sample\n"
    "                    (its limit on the validation sweep: y within 5e-8 m,\n"
    "                    1.3e-8 m RMS; scenes/bw_sinc_upsampling_error.scene);\n"
    "                    with --upsample 1 the 't,u' file is at the\n"
    "                    integration rate and is decimated to --fs (its rate\n"
    "                    / fs a whole number); decimated in stages unless\n"
    "                    --single-stage; t is written from 0\n"
    "\n"
    "Exit status: 0 done, 1 computation or output failed, 2 usage error or a\n"
    "refused parameter (nothing written).  Scenes draw the same system: [model] kind = boucwen (docs/SCENES.md).\n";

/* The installed data directory (not compiled into a string literal: a long
 * install prefix would pass C's 4095-character limit). */
static const char *data_dir_more(char *buf, size_t size, int doc)
{
    (void)doc;
    snprintf(buf, size, "%s/boucwen,\nthen tests/data/boucwen of the source tree)", HY_DATA_DIR);
    return buf;
}

enum { OPT_SIGNAL = CLI_FIRST, OPT_INPUT, OPT_DATA_DIR, OPT_OUT, OPT_PERIODS, OPT_NOISE, OPT_SEED, OPT_FS,
       OPT_UPSAMPLE, OPT_PARAM, OPT_BAND, OPT_RATE, OPT_AMP, OPT_SINGLE };
static const cli_opt bw_opts[] = {
    {"signal", 0, "KIND", "data: the force, multisine, validation, validation-sweep,\n"
     "sweep, sine or file (below)", OPT_SIGNAL, 0, NULL, NULL, NULL},
    {"band", 0, "F1,F2", "sweep: start and end frequency in Hz (20,50)", OPT_BAND, 0, NULL, NULL, NULL},
    {"rate", 0, "HZ_PER_MIN", "sweep: frequency rate in Hz per minute (10)", OPT_RATE, 0, NULL, NULL, NULL},
    {"amp", 0, "N", "sweep: force amplitude in N (40)", OPT_AMP, 0, NULL, NULL, NULL},
    {"input", 0, "FILE", "input force file (implies --signal file)", OPT_INPUT, 0, NULL, NULL, NULL},
    {"data-dir", 0, "DIR", "folder of uval_multisine.txt (validation; default\n"
     "$HY_BOUCWEN_DATA, then the installed copy in\n", OPT_DATA_DIR, 0, data_dir_more, NULL, NULL},
    {"periods", 0, "P", "number of periods written (periodic signals)", OPT_PERIODS, 0, NULL, NULL, NULL},
    {"noise", 0, "RMS", "output noise RMS in metres, Gaussian band-limited\n"
     "to 0-fs/2 (default 8e-6 = 8e-3 mm; 0 = none;\n"
     "validation and validation-sweep: 0)", OPT_NOISE, 0, NULL, NULL, NULL},
    {"seed", 0, "S", "seed of the multisine phases and the noise (1)", OPT_SEED, 0, NULL, NULL, NULL},
    {"fs", 0, "HZ", "working sampling rate (750; file: from t if given,\n"
     "with --upsample 1 the output rate)", OPT_FS, 0, NULL, NULL, NULL},
    {"upsample", 0, "R", "integration rate factor (20)", OPT_UPSAMPLE, 0, NULL, NULL, NULL},
    {"single-stage", 0, NULL, "decimate in one stage instead of prime factors\n"
     "(validation-sweep: always)", OPT_SINGLE, 0, NULL, NULL, NULL},
    {"set-param", 0, "N=V", "change a parameter: m c k alpha beta gamma delta nu\n"
     "(Table 1: 2 10 5e4 5e4 1e3 0.8 -1.1 1); repeatable", OPT_PARAM, 0, NULL, NULL, NULL},
    {NULL, 'o', "FILE", "output file (written to a temporary name, then\n"
     "renamed; '-' or none: standard output)", OPT_OUT, 0, NULL, NULL, NULL},
    {0},
};
static const cli_cmd bw_cli = {"boucwen", usage, signals, NULL, bw_opts};

typedef struct opts {
    const char *signal, *input, *data_dir, *out;
    size_t periods; /* 0: the signal's default */
    double noise;   /* NAN: the signal's default */
    uint64_t seed;
    double fs;
    size_t upsample;
    int staged;
    double band[2], rate, amp; /* sweep; NAN: not given (hy_sweep_default) */
    hy_boucwen_params p;
} opts;

typedef struct series {
    double *t, *u, *y;
    size_t n;
} series;

static void series_free(series *s)
{
    free(s->t);
    free(s->u);
    free(s->y);
}

static int series_alloc(series *s, size_t n)
{
    s->n = n;
    s->t = malloc(n * sizeof *s->t);
    s->u = malloc(n * sizeof *s->u);
    s->y = malloc(n * sizeof *s->y);
    return s->t && s->u && s->y ? 0 : -1;
}

static int bad_usage(const char *fmt, const char *arg)
{
    fprintf(stderr, "hystviz boucwen: ");
    fprintf(stderr, fmt, arg);
    fprintf(stderr, " (try 'hystviz boucwen --help')\n");
    return 2;
}

static int parse_size(const char *s, size_t *out)
{
    char *end;
    errno = 0;
    unsigned long long v = strtoull(s, &end, 10);
    if (end == s || *end || errno || s[0] == '-')
        return -1;
    *out = (size_t)v;
    return 0;
}

static int parse_double(const char *s, double *out)
{
    char *end;
    *out = strtod(s, &end);
    return end == s || *end ? -1 : 0;
}

/* "F1,F2" with 0 <= F1 < F2, both finite. */
static int parse_band(const char *s, double band[2])
{
    char *end;
    band[0] = strtod(s, &end);
    if (end == s || *end != ',')
        return -1;
    const char *b = end + 1;
    band[1] = strtod(b, &end);
    if (end == b || *end || !isfinite(band[0]) || !isfinite(band[1]))
        return -1;
    return band[0] >= 0 && band[1] > band[0] ? 0 : -1;
}

/* One option; 0 or 2 (message printed). */
static int take(opts *o, int id, const char *v)
{
    hy_error err = {0};
    size_t sz;
    switch (id) {
    case OPT_SIGNAL: o->signal = v; return 0;
    case OPT_INPUT: o->input = v; return 0;
    case OPT_DATA_DIR: o->data_dir = v; return 0;
    case OPT_OUT: o->out = v; return 0;
    case OPT_SINGLE: o->staged = 0; return 0;
    case OPT_PERIODS:
        if (parse_size(v, &o->periods) || o->periods < 1 || o->periods > 1000)
            return bad_usage("--periods '%s' must be an integer in 1..1000", v);
        return 0;
    case OPT_NOISE:
        if (parse_double(v, &o->noise) || !isfinite(o->noise) || o->noise < 0)
            return bad_usage("--noise '%s' must be a finite RMS >= 0 in metres", v);
        return 0;
    case OPT_SEED:
        if (parse_size(v, &sz))
            return bad_usage("--seed '%s' must be a non-negative integer", v);
        o->seed = (uint64_t)sz;
        return 0;
    case OPT_FS:
        if (parse_double(v, &o->fs) || !isfinite(o->fs) || o->fs <= 0)
            return bad_usage("--fs '%s' must be a positive number of Hz", v);
        return 0;
    case OPT_UPSAMPLE:
        if (parse_size(v, &o->upsample) || o->upsample < 1 || o->upsample > 1000)
            return bad_usage("--upsample '%s' must be an integer in 1..1000", v);
        return 0;
    case OPT_BAND:
        if (parse_band(v, o->band))
            return bad_usage("--band '%s' must be F1,F2 in Hz with 0 <= F1 < F2", v);
        return 0;
    case OPT_RATE:
        if (parse_double(v, &o->rate) || !isfinite(o->rate) || o->rate <= 0)
            return bad_usage("--rate '%s' must be a positive number of Hz per minute", v);
        return 0;
    case OPT_AMP:
        if (parse_double(v, &o->amp) || !isfinite(o->amp) || o->amp < 0)
            return bad_usage("--amp '%s' must be a finite force >= 0 in N", v);
        return 0;
    default: /* OPT_PARAM */
        return hy_boucwen_params_parse(&o->p, v, &err) ? bad_usage("%s", err.msg) : 0;
    }
}

/* Parses argv[first..]; returns 0, 1 (help printed) or an exit status. */
static int parse_opts(int argc, char **argv, int first, opts *o)
{
    cli_parser p;
    cli_parser_init(&p, &bw_cli, argc, argv, first);
    for (int id; (id = cli_next(&p)) != CLI_END;) {
        if (id == CLI_STOP || id == CLI_ERROR)
            return id == CLI_STOP ? 1 : 2;
        int rc = take(o, id, p.val);
        if (rc)
            return rc;
    }
    return 0;
}

static int cmd_table2(const opts *o)
{
    hy_boucwen_modal md;
    hy_error err = {0};
    if (hy_boucwen_table2(&o->p, &md, &err)) {
        fprintf(stderr, "hystviz boucwen: %s\n", err.msg);
        return err.code == HY_EINVAL ? 2 : 1;
    }
    printf("Table 2: linear modal parameters (linearised stiffness k + alpha)\n");
    printf("%-28s %8s  %s\n", "parameter", "value", "full precision");
    printf("%-28s %8.2f  %.17g\n", "natural frequency f0 (Hz)", md.f0_hz, md.f0_hz);
    printf("%-28s %8.2f  %.17g\n", "damping ratio zeta (%)", 100 * md.zeta, 100 * md.zeta);
    return 0;
}

/* The source tree's tests/data/boucwen for a program run from its build
 * directory, into buf: the build writes its source root into the file
 * HY_SOURCE_ROOT_FILE at the top of the build directory, found from the
 * program's own location upwards (so that no build path is compiled into the
 * program); NULL if there is none. */
static const char *source_data_dir(char *buf, size_t size)
{
    char dir[4096], root[4096];
    ssize_t n = readlink("/proc/self/exe", dir, sizeof dir - 1);
    if (n <= 0)
        return NULL;
    dir[n] = 0;
    for (char *slash; (slash = strrchr(dir, '/')) && slash > dir;) {
        *slash = 0;
        char path[4200];
        snprintf(path, sizeof path, "%s/" HY_SOURCE_ROOT_FILE, dir);
        FILE *f = fopen(path, "r");
        if (!f)
            continue;
        int ok = fgets(root, sizeof root, f) != NULL;
        fclose(f);
        root[strcspn(root, "\n")] = 0;
        if (!ok || !root[0] || snprintf(buf, size, "%s/tests/data/boucwen", root) >= (int)size)
            return NULL;
        return buf;
    }
    return NULL;
}

int hy_cmd_boucwen_data_file(const char *data_dir, const char *file, char *path, size_t size)
{
    char src[4200], inst[4200];
    const char *cand[] = {data_dir, getenv("HY_BOUCWEN_DATA"),
                          hy_file_installed(HY_INSTALLED_DATA, "boucwen", inst, sizeof inst) ? NULL : inst,
                          source_data_dir(src, sizeof src)};
    for (size_t i = 0; i < sizeof cand / sizeof *cand; i++) {
        struct stat st;
        if (!cand[i])
            continue;
        snprintf(path, size, "%s/%s", cand[i], file);
        if (stat(path, &st) == 0 || data_dir)
            return 0;
    }
    return -1;
}

/* Finds uval_multisine.txt (hy_cmd_boucwen_data_file). */
static int validation_path(const opts *o, char *path, size_t size)
{
    if (hy_cmd_boucwen_data_file(o->data_dir, "uval_multisine.txt", path, size) == 0)
        return 0;
    fprintf(stderr, "hystviz boucwen: uval_multisine.txt not found; give --data-dir DIR\n");
    return -1;
}

/* Periodic signals: one period u_per at the integration rate, P periods out;
 * skip leading periods are integrated but not written (steady state). */
static int synth_periodic(const opts *o, const double *u_per, size_t n_per,
                          size_t P, size_t skip, series *s, hy_error *err)
{
    hy_newmark_opts no;
    hy_newmark_opts_default(&no);
    size_t r = o->upsample, nd = n_per / r, total = P + skip;
    double *y = malloc(total * nd * sizeof *y);
    if (!y || series_alloc(s, P * nd)) {
        free(y);
        return hy_error_set(err, HY_ENOMEM, "out of memory for %zu periods", total);
    }
    int rc = hy_boucwen_synth_periodic(&o->p, &no, o->fs, r, o->staged, u_per,
                                       n_per, total, y, err);
    for (size_t i = 0; !rc && i < s->n; i++) {
        s->t[i] = (double)i / o->fs;
        s->u[i] = u_per[(i % nd) * r];
        s->y[i] = y[skip * nd + i];
    }
    free(y);
    return rc;
}

/* Non-periodic signals: n_int samples at the integration rate fs_out * d,
 * decimated by d to fs_out (the u column: every d-th integration sample). */
static int synth_once(const opts *o, double fs_out, size_t d, const double *u_int,
                      size_t n_int, series *s, hy_error *err)
{
    hy_newmark_opts no;
    hy_newmark_opts_default(&no);
    size_t nd = (n_int + d - 1) / d;
    if (series_alloc(s, nd))
        return hy_error_set(err, HY_ENOMEM, "out of memory for %zu samples", nd);
    int rc = hy_boucwen_synth(&o->p, &no, fs_out, d, o->staged, u_int, n_int, s->y, err);
    for (size_t i = 0; !rc && i < nd; i++) {
        s->t[i] = (double)i / fs_out;
        s->u[i] = u_int[i * d];
    }
    return rc;
}

static int signal_multisine(const opts *o, series *s, hy_error *err)
{
    size_t r = o->upsample;
    hy_multisine ms;
    hy_multisine_default(&ms);
    ms.fs = o->fs;
    ms.seed = o->seed;
    size_t kmin, kmax; /* the band against --fs, before any allocation */
    int rc = hy_multisine_lines(&ms, &kmin, &kmax, err);
    if (rc) {
        hy_error_prefix(err, "--fs %g", o->fs);
        return rc;
    }
    double *u = malloc(ms.n * r * sizeof *u);
    if (!u)
        return hy_error_set(err, HY_ENOMEM, "out of memory for the multisine");
    rc = hy_multisine_design(&ms, r, u, err);
    if (!rc)
        rc = synth_periodic(o, u, ms.n * r, o->periods ? o->periods : 5, 0, s, err);
    free(u);
    return rc;
}

static int signal_validation(const opts *o, series *s, hy_error *err)
{
    size_t r = o->upsample, n;
    char path[4096];
    double *uv = NULL, *u = NULL, fsf;
    if (validation_path(o, path, sizeof path))
        return hy_error_set(err, HY_EIO, "validation data not found");
    int rc = hy_signal_read(path, &uv, &n, &fsf, err);
    if (!rc && !(u = malloc(n * r * sizeof *u)))
        rc = hy_error_set(err, HY_ENOMEM, "out of memory for the validation input");
    if (!rc)
        rc = hy_signal_upsample_fft(uv, n, r, u, err);
    /* two settling periods: the transient is ~1e-24 of y after them */
    if (!rc)
        rc = synth_periodic(o, u, n * r, o->periods ? o->periods : 1, 2, s, err);
    for (size_t i = 0; !rc && i < s->n; i++) /* the file's values, bit-exact */
        s->u[i] = uv[i % n];
    free(uv);
    free(u);
    return rc;
}

static int signal_sine(const opts *o, series *s, hy_error *err)
{
    size_t r = o->upsample;
    double fint = o->fs * (double)r;
    size_t n = (size_t)llround(fint); /* one 1 Hz period */
    if (fabs((double)n - fint) > 1e-9 * fint || n % r)
        return hy_error_set(err, HY_EINVAL, "sine: fs x upsample = %g Hz must be an integer", fint);
    double *u = malloc(n * sizeof *u);
    if (!u)
        return hy_error_set(err, HY_ENOMEM, "out of memory for the sine");
    int rc = hy_sine_fill(120.0, 1.0, fint, u, n, err);
    if (!rc)
        rc = synth_periodic(o, u, n, o->periods ? o->periods : 10, 0, s, err);
    free(u);
    return rc;
}

/* Integration samples a non-periodic run may take (u, y and the decimation
 * scratch: 32 bytes each), as the scenes allow. */
#define MAX_INT_SAMPLES 40000000.0

/* The sweep: --band/--rate/--amp over hy_sweep_default (validation-sweep:
 * hy_sweep_validation, one-stage decimation), made at the integration rate,
 * nd x r samples for the nd rows at fs. */
static int signal_sweep(opts *o, series *s, hy_error *err)
{
    size_t r = o->upsample;
    hy_sweep sw;
    if (strcmp(o->signal, "validation-sweep") == 0) {
        hy_sweep_validation(&sw);
        o->staged = 0;
    } else {
        hy_sweep_default(&sw);
        if (!isnan(o->band[0])) {
            sw.f0 = o->band[0];
            sw.f1 = o->band[1];
        }
        if (!isnan(o->rate))
            sw.rate = o->rate / 60.0;
        if (!isnan(o->amp))
            sw.amp = o->amp;
    }
    size_t nd = hy_sweep_length(&sw, o->fs);
    if (nd == 0)
        return hy_sweep_fill(&sw, o->fs, NULL, 0, err);
    if ((double)nd * (double)r > MAX_INT_SAMPLES || nd < 16)
        return hy_error_set(err, HY_EINVAL,
                            "sweep: %zu rows at %g Hz x %zu is %.0f integration samples; "
                            "16 rows to %.0f samples are allowed (see --band, --rate, --upsample)",
                            nd, o->fs, r, (double)nd * (double)r, MAX_INT_SAMPLES);
    size_t n = nd * r; /* generated at the integration rate */
    double *u = malloc(n * sizeof *u);
    if (!u)
        return hy_error_set(err, HY_ENOMEM, "out of memory for the sweep");
    int rc = hy_sweep_fill(&sw, o->fs * (double)r, u, n, err);
    if (!rc)
        rc = synth_once(o, o->fs, r, u, n, s, err);
    free(u);
    return rc;
}

/* --upsample 1: the file's rate (from t) is the integration rate, decimated
 * by the whole number d = rate / --fs. */
static int file_at_integration_rate(opts *o, const double *uf, size_t n, double fsf,
                                    series *s, hy_error *err)
{
    if (!(fsf > 0))
        return hy_error_set(err, HY_EINVAL,
                            "%s: with --upsample 1 the file is at the integration rate: give 't,u' lines",
                            o->input);
    double q = fsf / o->fs;
    size_t d = (size_t)llround(q);
    if (!(q >= 0.5 && q < 1e9) || d < 1 || fabs((double)d - q) > 1e-9 * q)
        return hy_error_set(err, HY_EINVAL,
                            "%s: its rate %.17g Hz / --fs %g Hz = %.10g must be a whole number >= 1",
                            o->input, fsf, o->fs, q);
    if (d > 1 && n < 16)
        return hy_error_set(err, HY_EINVAL, "%s: decimation needs at least 16 samples, got %zu",
                            o->input, n);
    return synth_once(o, o->fs, d, uf, n, s, err);
}

/* The force in --input: n samples upsampled by the windowed sinc to n x r
 * (every input sample's interval, so the last row is not a filter edge), or
 * at the integration rate already (--upsample 1). */
static int signal_file(opts *o, series *s, hy_error *err)
{
    size_t r = o->upsample, n;
    double *uf = NULL, *u = NULL, fsf;
    if (!o->input)
        return hy_error_set(err, HY_EINVAL, "--signal file needs --input FILE");
    int rc = hy_signal_read(o->input, &uf, &n, &fsf, err);
    if (!rc && r == 1) {
        rc = file_at_integration_rate(o, uf, n, fsf, s, err);
        free(uf);
        return rc;
    }
    if (!rc && fsf > 0)
        o->fs = fsf;
    if (!rc && n < 2)
        rc = hy_error_set(err, HY_EINVAL, "%s: needs at least 2 samples", o->input);
    if (!rc && (double)n * (double)r > MAX_INT_SAMPLES)
        rc = hy_error_set(err, HY_EINVAL, "%s: %zu samples x %zu is more than %.0f integration samples",
                          o->input, n, r, MAX_INT_SAMPLES);
    if (!rc && !(u = malloc(n * r * sizeof *u)))
        rc = hy_error_set(err, HY_ENOMEM, "out of memory for %s", o->input);
    if (!rc)
        rc = hy_signal_upsample_sinc(uf, n, r, u, err);
    if (!rc)
        rc = synth_once(o, o->fs, r, u, n * r, s, err);
    free(uf);
    free(u);
    return rc;
}

static int make_signal(opts *o, series *s, hy_error *err)
{
    if (strcmp(o->signal, "multisine") == 0)
        return signal_multisine(o, s, err);
    if (strcmp(o->signal, "validation") == 0)
        return signal_validation(o, s, err);
    if (strcmp(o->signal, "sine") == 0)
        return signal_sine(o, s, err);
    if (strcmp(o->signal, "sweep") == 0 || strcmp(o->signal, "validation-sweep") == 0)
        return signal_sweep(o, s, err);
    if (strcmp(o->signal, "file") == 0)
        return signal_file(o, s, err);
    return hy_error_set(err, HY_EINVAL,
                        "unknown signal '%s' (multisine, validation, validation-sweep, sweep, sine, file)",
                        o->signal);
}

static void write_rows(FILE *f, const series *s)
{
    fprintf(f, "t,u,y\n");
    for (size_t i = 0; i < s->n; i++)
        fprintf(f, "%.17g,%.17g,%.17g\n", s->t[i], s->u[i], s->y[i]);
}

static int cmd_data(opts *o)
{
    hy_error err = {0};
    series s = {0};
    if (!o->signal)
        o->signal = o->input ? "file" : NULL;
    if (!o->signal)
        return bad_usage("%s", "data needs --signal multisine|validation|validation-sweep|sweep|sine|file");
    int sweep = strcmp(o->signal, "sweep") == 0, vsweep = strcmp(o->signal, "validation-sweep") == 0;
    if ((sweep || vsweep) && o->periods)
        return bad_usage("--periods does not apply to the %s", o->signal);
    if (!sweep && !(isnan(o->band[0]) && isnan(o->rate) && isnan(o->amp)))
        return bad_usage("--band, --rate and --amp go with --signal sweep, not '%s'", o->signal);
    if (o->input && strcmp(o->signal, "file") != 0)
        return bad_usage("--input goes with --signal file, not '%s'", o->signal);
    int rc = hy_boucwen_params_validate(&o->p, &err);
    if (rc) {
        fprintf(stderr, "hystviz boucwen: %s\n", err.msg);
        return 2;
    }
    /* the output is opened first: a directory or a missing folder fails before
     * the synthesis, and a failed synthesis leaves nothing (hy_out.h) */
    hy_out out;
    if (hy_out_open(&out, o->out ? o->out : "-", HY_OUT_FOLLOW, &err)) {
        fprintf(stderr, "hystviz boucwen: %s\n", err.msg);
        return 1;
    }
    rc = make_signal(o, &s, &err);
    if (!rc) {
        int exact = strcmp(o->signal, "validation") == 0 || vsweep; /* the data sets: noiseless */
        double rms = isnan(o->noise) ? (exact ? 0.0 : 8e-6) : o->noise;
        /* the noise stream is seeded apart from the multisine phases */
        rc = hy_signal_add_noise(s.y, s.n, rms, o->fs / 2, o->fs,
                                 o->seed ^ 0x6e6f697365ULL, &err);
    }
    if (!rc) {
        write_rows(hy_out_file(&out), &s);
        rc = hy_out_commit(&out, &err);
    }
    hy_out_abort(&out);
    series_free(&s);
    if (rc) {
        fprintf(stderr, "hystviz boucwen: %s\n", err.msg);
        return rc == HY_EINVAL ? 2 : 1;
    }
    return 0;
}

int hy_cmd_boucwen(int argc, char **argv)
{
    opts o = {.signal = NULL, .input = NULL, .data_dir = NULL, .out = NULL,
              .periods = 0, .noise = NAN, .seed = 1, .fs = 750.0,
              .upsample = 20, .staged = 1, .band = {NAN, NAN}, .rate = NAN, .amp = NAN};
    hy_boucwen_params_default(&o.p);
    if (argc < 2)
        return bad_usage("%s", "needs 'table2', 'data' or '--help'");
    if (strcmp(argv[1], "help") == 0) {
        cli_help(stdout, &bw_cli, "boucwen");
        return 0;
    }
    if (argv[1][0] == '-') { /* --help, --version, or an option before the subcommand */
        int rc = parse_opts(argc, argv, 1, &o);
        return rc == 1 ? 0 : rc ? rc : bad_usage("%s", "needs 'table2' or 'data' before its options");
    }
    int is_table = strcmp(argv[1], "table2") == 0;
    if (!is_table && strcmp(argv[1], "data") != 0)
        return bad_usage("unknown subcommand '%s' (table2, data)", argv[1]);
    int rc = parse_opts(argc, argv, 2, &o);
    if (rc)
        return rc == 1 ? 0 : rc;
    return is_table ? cmd_table2(&o) : cmd_data(&o);
}
