/* SPDX-License-Identifier: MIT */
/* model_boucwen.c: Bouc-Wen scenes (seeds/001, Figs. 1-2): Table 1 from [model], a
 * sine, multisine or sweep force, Newmark at fs x upsample (Eqs. 1-5), MATLAB-style
 * decimation back to fs (Section 4), then the series y, u, |y| dB, transient dB, spectrum.
 *
 * The boucwen model's stages and table entry (its line in the model table of
 * src/pipeline/meson.build): its [model] holds Table 1 (m, c, k, alpha,
 * bw_beta, bw_gamma, delta, nu), its [input] is a force (sine, multisine or
 * sweep at a working rate fs: the entry's inputs), and its series are
 * `data = boucwen` with a `quantity` (output y in mm, input u in N, output and
 * transient in dB, spectrum).  The output is integrated by Newmark at fs x
 * upsample and decimated back to fs like the benchmark, then stored as
 * hy_run_series that scene_draw.c draws unchanged.  Every error names
 * file:line:col of the key at fault (docs/SCENES.md). */
#include "scene_model.h"
#include "scene_run.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "hy_boucwen.h"
#include "hy_cost.h"
#include "hy_os.h"
#include "hy_signal.h"

enum { IN_SINE, IN_MULTISINE, IN_SWEEP };
/* Q_ID: the index of the schema's quantity list (HY_SERIES_QUANTITIES). */
#define Q_ID(id, name, bw) Q_##id,
enum { HY_SERIES_QUANTITIES(Q_ID) };
#undef Q_ID
enum { DEC_STAGED, DEC_SINGLE, DEC_NONE };

/* Integration samples allowed in one scene (u, y and decimation scratch: ~32 B each). */
#define BW_MAX_SAMPLES 40000000.0

/* The quantities the benchmark draws (bw = 1 in HY_SERIES_QUANTITIES). */
#define BW_NAME(id, name, bw) BW_NAME_##bw(name)
#define BW_NAME_1(name) name,
#define BW_NAME_0(name)
static const char *const quantity_names[] = {HY_SERIES_QUANTITIES(BW_NAME) NULL};
#undef BW_NAME
#undef BW_NAME_1
#undef BW_NAME_0

/* Everything a boucwen scene asks for, read and checked once. */
typedef struct bw_setup {
    hy_boucwen_params p;
    int input;            /* IN_*                                            */
    double fs;            /* working rate, Hz                                */
    size_t r;             /* integration rate = fs * r                       */
    int dec;              /* DEC_*                                           */
    long cycles, settle;  /* periods kept, periods discarded before them     */
    double noise;         /* output noise RMS, m                             */
    uint64_t seed;        /* [input] seed: multisine phases, and the noise   */
    double amp, period, offset;
    hy_multisine ms;
    hy_sweep sw;
    size_t nd;            /* samples at fs: one period, or the whole sweep   */
    int need_output;      /* some series needs the simulated y               */
    int need_sinc;        /* bits: 1 the sinc-upsampled force, 2 its output  */
    double work;          /* Newmark steps + series samples (the work budget) */
    const hy_cancel *cancel; /* asked between blocks of Newmark steps (NULL: never) */
} bw_setup;

#define IN(f) offsetof(hy_decl_input, f)
#define CO(f) offsetof(hy_decl_compute, f)
#define SE(f) offsetof(hy_decl_series, f)

/* The identifier of an ENUM field of a decoded section. */
#define ENUM_TEXT(sec, T, f) hy_decl_enum_text(&(sec)->h, offsetof(T, f), (sec)->f)

/* The first of keys (NULL-terminated) written in h's section, or HY_DECL_HEAD
 * (the section): where a message about several keys points. */
static size_t first_set(const hy_decl_head *h, const char *const *keys)
{
    for (size_t i = 0; keys[i]; i++)
        if (hy_decl_got(h, hy_decl_offset(h, keys[i])) == HY_SCENE_SET)
            return hy_decl_offset(h, keys[i]);
    return HY_DECL_HEAD;
}

/* Re-raises the core message in err at the scene location of the field at
 * off (HY_DECL_HEAD: the section), prefixed with what. */
static int relocate(const hy_decl_head *h, size_t off, hy_error *err, int code, const char *what)
{
    return hy_decl_error(h, off, err, code, "%s%s", what, err->msg);
}

/* Table 1 from [model]; the schema has checked each value's own range. */
static int read_params(const hy_decl_model *m, hy_boucwen_params *p, hy_error *err)
{
    hy_boucwen_params_default(p);
    p->m = m->m;
    p->c = m->c;
    p->k = m->k;
    p->alpha = m->alpha;
    p->beta = m->bw_beta;
    p->gamma = m->bw_gamma;
    p->delta = m->delta;
    p->nu = m->nu;
    if (!(p->k + p->alpha > 0))
        return hy_decl_error(&m->h,
                             hy_decl_got(&m->h, offsetof(hy_decl_model, k)) == HY_SCENE_SET ? offsetof(hy_decl_model, k)
                                                                                            : offsetof(hy_decl_model, alpha),
                             err, HY_EINVAL,
                             "k + alpha (the linearised stiffness of Table 2) must be > 0, got k = %g, alpha = %g",
                             p->k, p->alpha);
    if (hy_boucwen_params_validate(p, err))
        return relocate(&m->h, HY_DECL_HEAD, err, HY_EINVAL, "");
    return HY_OK;
}

static int read_sine(const hy_decl_input *in, bw_setup *b, hy_error *err)
{
    b->amp = in->amp;
    b->period = in->period;
    b->offset = in->offset;
    double nd = b->period * b->fs;
    if (!(nd <= BW_MAX_SAMPLES)) /* before the conversion below: fs may be 1e300 */
        return hy_decl_error(&in->h, hy_decl_got(&in->h, IN(fs)) == HY_SCENE_SET ? IN(fs) : IN(period), err, HY_EINVAL,
                             "a Bouc-Wen sine of period x fs = %g x %g = %.3g samples is more than the %.0f "
                             "integration samples a scene may use", b->period, b->fs, nd, BW_MAX_SAMPLES);
    if (fabs(nd - nearbyint(nd)) > 1e-9 * nd || nearbyint(nd) < 4)
        return hy_decl_error(&in->h, IN(period), err, HY_EINVAL,
                             "a Bouc-Wen sine needs a whole number (>= 4) of samples per period: "
                             "period x fs = %g x %g = %.10g",
                             b->period, b->fs, nd);
    b->nd = (size_t)nearbyint(nd);
    return HY_OK;
}

static int read_multisine(const hy_decl_input *in, bw_setup *b, hy_error *err)
{
    size_t kmin, kmax;
    hy_multisine_default(&b->ms);
    b->ms.fs = b->fs;
    b->ms.n = (size_t)in->samples;
    b->ms.fmin = in->band.v[0];
    b->ms.fmax = in->band.v[1];
    b->ms.rms = in->rms;
    b->ms.seed = b->seed;
    static const char *const culprits[] = {"band", "fs", "samples", NULL};
    if (hy_multisine_lines(&b->ms, &kmin, &kmax, err))
        return relocate(&in->h, first_set(&in->h, culprits), err, HY_EINVAL, "");
    b->nd = b->ms.n;
    return HY_OK;
}

static int read_sweep(const hy_decl_input *in, const hy_decl_compute *co, bw_setup *b, hy_error *err)
{
    static const char *const periodic[] = {"cycles", "settle"};
    hy_sweep_default(&b->sw); /* the defaults of `hystviz boucwen data --signal sweep` too */
    for (size_t i = 0; i < 2; i++)
        if (hy_decl_got(&co->h, hy_decl_offset(&co->h, periodic[i])) == HY_SCENE_SET)
            return hy_decl_error(&co->h, hy_decl_offset(&co->h, periodic[i]), err, HY_EINVAL,
                                 "'%s' counts input periods, and a sweep is not periodic", periodic[i]);
    b->cycles = 1;
    /* keys the scene leaves unset keep hy_sweep_default (the schema's defaults
     * of amp and band are the triangle's and the multisine's) */
    double band[2] = {b->sw.f0, b->sw.f1};
    if (hy_decl_got(&in->h, IN(band)) == HY_SCENE_SET)
        band[0] = in->band.v[0], band[1] = in->band.v[1];
    if (hy_decl_got(&in->h, IN(amp)) == HY_SCENE_SET)
        b->sw.amp = in->amp;
    if (hy_decl_got(&in->h, IN(rate)) == HY_SCENE_SET)
        b->sw.rate = in->rate / 60.0;
    b->sw.f0 = band[0];
    b->sw.f1 = band[1];
    b->nd = hy_sweep_length(&b->sw, b->fs);
    if (b->nd == 0) {
        static const char *const culprits[] = {"rate", "band", "fs", "amp", NULL};
        hy_sweep_fill(&b->sw, b->fs, NULL, 0, err);
        return relocate(&in->h, first_set(&in->h, culprits), err, HY_EINVAL, "");
    }
    if (b->nd < 16)
        return hy_decl_error(&in->h, IN(band), err, HY_EINVAL,
                             "the sweep lasts %zu samples at fs = %g Hz; at least 16 are needed", b->nd, b->fs);
    return HY_OK;
}

/* [input] and [compute]; the memory bound is checked here, before any allocation. */
static int read_signal(const hy_scene_doc *d, bw_setup *b, hy_error *err)
{
    const hy_decl_input *in = &d->input;
    const hy_decl_compute *co = &d->compute;
    const char *kind = ENUM_TEXT(in, hy_decl_input, kind);
    b->fs = in->fs;
    b->r = (size_t)co->upsample;
    b->dec = co->decimate;
    b->cycles = co->cycles;
    b->settle = co->settle;
    b->noise = 1e-3 * co->noise;
    b->seed = (uint64_t)in->seed;
    int rc;
    if (in->kind == HY_INPUT_SINE) {
        b->input = IN_SINE;
        rc = read_sine(in, b, err);
    } else if (in->kind == HY_INPUT_MULTISINE) {
        b->input = IN_MULTISINE;
        rc = read_multisine(in, b, err);
    } else if (in->kind == HY_INPUT_SWEEP) {
        b->input = IN_SWEEP;
        rc = read_sweep(in, co, b, err);
    } else
        return hy_decl_error(&in->h, IN(kind), err, HY_EINVAL,
                             "a boucwen model takes [input] kind = sine, multisine or sweep, not %s", kind);
    if (rc)
        return rc;
    /* the periodic synthesis integrates one extra period for the filter's edge */
    double periods = b->input == IN_SWEEP ? 1.0 : (double)(b->cycles + b->settle + (b->dec != DEC_NONE));
    double total = periods * (double)b->nd * (double)b->r;
    b->work = total;
    if (total > BW_MAX_SAMPLES)
        return hy_decl_error(&co->h, b->input == IN_SWEEP ? CO(upsample) : CO(cycles), err, HY_EINVAL,
                             "%.0f integration samples (%g periods of %zu samples at %g Hz x %zu) "
                             "is more than %.0f",
                             total, periods, b->nd, b->fs, b->r, BW_MAX_SAMPLES);
    return HY_OK;
}

/* What one series of a boucwen scene may draw: its quantity against the
 * figure's kind and the input's. */
static int check_quantity(const hy_scene_run *r, const bw_setup *b, const hy_decl_series *ds, hy_error *err)
{
    int q = ds->quantity;
    const char *why = NULL;
    if ((q == Q_SINC_INPUT || q == Q_SINC_OUTPUT) && b->input != IN_SWEEP)
        why = "compares the sinc-upsampled sweep with the exact one: it needs [input] kind = sweep";
    else if (q >= Q_ENVELOPE && r->figure_kind == FIG_LOOP)
        why = "is a value a second, drawn against t, not in a loop figure";
    else if ((q == Q_TRANSIENT_DB || q == Q_SPECTRUM) && b->input == IN_SWEEP)
        why = "needs a periodic input (sine or multisine), not a sweep";
    else if (q == Q_SPECTRUM && r->figure_kind == FIG_LOOP)
        why = "is drawn against frequency, not in a loop figure";
    if (why)
        return hy_decl_error(&ds->h, SE(quantity), err, HY_EINVAL, "quantity = %s %s",
                             hy_decl_enum_text(&ds->h, SE(quantity), q), why);
    if (q == Q_TRANSIENT_DB && b->cycles < 2)
        return hy_decl_error(&ds->h, SE(quantity), err, HY_EINVAL,
                             "quantity = transient-db subtracts the last period: it needs [compute] cycles >= 2, got %ld",
                             b->cycles);
    return HY_OK;
}

/* Figure kind, series and annotations of a boucwen scene. */
static int check_series(const hy_scene_run *r, bw_setup *b, hy_error *err)
{
    static const char *const kinds[] = {"timeseries", "loop", "input", "g", "psi"};
    const hy_scene_doc *d = &r->doc;
    if (r->figure_kind != FIG_TIMESERIES && r->figure_kind != FIG_LOOP)
        return hy_decl_error(&d->figure.h, offsetof(hy_decl_figure, kind), err, HY_EINVAL,
                             "a boucwen scene draws a figure of kind timeseries or loop, not %s",
                             r->figure_kind >= 0 && r->figure_kind < 5 ? kinds[r->figure_kind] : "this");
    b->need_output = 0;
    for (size_t i = 0; i < d->nseries; i++) {
        const hy_decl_series *ds = &d->series[i];
        int q = ds->quantity, rc;
        if (hy_decl_got(&ds->h, SE(data)) < 0)
            return hy_decl_error(&ds->h, HY_DECL_HEAD, err, HY_EINVAL,
                                 "series '%s' needs 'data = boucwen' (and a 'quantity')", ds->h.name);
        if (ds->data != HY_DATA_BOUCWEN)
            return hy_decl_error(&ds->h, SE(data), err, HY_EINVAL,
                                 "a boucwen model draws 'data = boucwen' series (with a 'quantity'), not %s",
                                 ENUM_TEXT(ds, hy_decl_series, data));
        if ((rc = check_quantity(r, b, ds, err)))
            return rc;
        b->need_output |= q != Q_INPUT && q != Q_SINC_INPUT;
        b->need_sinc |= q == Q_SINC_OUTPUT ? 2 : q == Q_SINC_INPUT;
        b->work += (double)b->nd * (double)(b->input == IN_SWEEP ? 1 : b->cycles) *
                   (b->dec == DEC_NONE ? (double)b->r : 1.0);
        if (q == Q_SINC_INPUT || q == Q_SINC_OUTPUT) /* the sinc-upsampled force, and its own Newmark run */
            b->work += (double)b->nd * (double)b->r * (q == Q_SINC_OUTPUT ? 2.0 : 1.0);
    }
    for (size_t i = 0; i < d->nannotation; i++) {
        const hy_decl_annotation *a = &d->annotation[i];
        if (a->text && strchr(a->text, '{'))
            return hy_decl_error(&a->h, offsetof(hy_decl_annotation, text), err, HY_EINVAL,
                                 "{...} placeholders measure Dahl/LuGre loops; a boucwen scene has none");
    }
    return HY_OK;
}

static int read_setup(const hy_scene_run *r, bw_setup *b, hy_error *err)
{
    memset(b, 0, sizeof *b);
    int rc = read_params(&r->doc.model, &b->p, err);
    if (!rc)
        rc = read_signal(&r->doc, b, err);
    if (!rc)
        rc = check_series(r, b, err);
    return rc;
}

/* The work estimate (Newmark steps plus series samples), from the setup alone. */
static int boucwen_work(const hy_scene_run *r, double *work, hy_error *err)
{
    bw_setup b;
    int rc = read_setup(r, &b, err);
    *work = rc ? 0.0 : b.work;
    return rc;
}

/* Checks the scene before anything is computed: parameters, input, compute
 * keys, figure kind and every series (errors at the key's location). */
static int boucwen_load(hy_scene_run *r, hy_error *err)
{
    bw_setup b;
    return read_setup(r, &b, err);
}

/* ---- compute ------------------------------------------------------------ */

/* The simulated record at the output rate: the kept samples only. */
typedef struct bw_record {
    double *t, *u, *y;   /* n samples (y NULL if no series needs it)            */
    size_t n;
    double *du;          /* sinc: |u_sinc - u| at the integration rate (ndu)    */
    size_t ndu;
    double *ysinc;       /* sinc: y of the sinc-upsampled force (n samples)     */
    size_t nper;         /* samples per period at the output rate (periodic)    */
    double fs_out;
    double sim_seconds;
} bw_record;

static void record_free(bw_record *rec)
{
    free(rec->t);
    free(rec->u);
    free(rec->y);
    free(rec->du);
    free(rec->ysinc);
}

/* One period (or the whole sweep) of the force at the integration rate fs * r. */
static int make_force(const bw_setup *b, double **u, size_t *n, hy_error *err)
{
    double fint = b->fs * (double)b->r;
    *n = b->nd * b->r; /* a sweep: every one of its nd intervals at fs */
    *u = malloc(*n * sizeof **u);
    if (!*u)
        return hy_error_set(err, HY_ENOMEM, "out of memory for %zu input samples", *n);
    int rc;
    if (b->input == IN_SINE) {
        rc = hy_sine_fill(b->amp, 1.0 / b->period, fint, *u, *n, err);
        for (size_t i = 0; !rc && i < *n; i++)
            (*u)[i] += b->offset;
    } else if (b->input == IN_MULTISINE)
        rc = hy_multisine_design(&b->ms, b->r, *u, err);
    else
        rc = hy_sweep_fill(&b->sw, fint, *u, *n, err);
    return rc;
}

/* Integrates the whole record (settle + cycles periods, or the sweep) into y;
 * decimated periodic records hold only the kept periods (y's settling
 * samples are left unwritten: make_record reads from skip on). */
static int simulate(const bw_setup *b, const double *u, size_t nu, double *y, hy_error *err)
{
    hy_newmark_opts o;
    hy_newmark_opts_default(&o);
    o.cancel = b->cancel;
    size_t P = (size_t)(b->cycles + b->settle);
    int staged = b->dec == DEC_STAGED;
    if (b->input == IN_SWEEP && b->dec != DEC_NONE)
        return hy_boucwen_synth(&b->p, &o, b->fs, b->r, staged, u, nu, y, err);
    if (b->input == IN_SWEEP)
        return hy_boucwen_simulate(&b->p, &o, 1.0 / (b->fs * (double)b->r), u, nu, NULL, y, NULL, err);
    if (b->dec != DEC_NONE) /* the kept periods alone (the settling ones are not read) */
        return hy_boucwen_synth_periodic_kept(&b->p, &o, b->fs, b->r, staged, u, nu, (size_t)b->settle, P,
                                              y + (size_t)b->settle * (nu / b->r), err);
    double *ua = malloc(P * nu * sizeof *ua);
    if (!ua)
        return hy_error_set(err, HY_ENOMEM, "out of memory for %zu input samples", P * nu);
    for (size_t q = 0; q < P; q++)
        memcpy(ua + q * nu, u, nu * sizeof *ua);
    int rc = hy_boucwen_simulate(&b->p, &o, 1.0 / (b->fs * (double)b->r), ua, P * nu, NULL, y, NULL, err);
    free(ua);
    return rc;
}

/* The route of `hystviz boucwen data --signal file`: the sweep sampled at fs
 * and brought to fs x r by the Kaiser-windowed sinc; rec->du its distance to
 * the exact force u, and with need_sinc & 2 rec->ysinc its decimated output. */
static int sinc_route(const bw_setup *b, const double *u, size_t nu, bw_record *rec, size_t skip, hy_error *err)
{
    double *lo = malloc(b->nd * sizeof *lo), *us = malloc(nu * sizeof *us), *ys = NULL;
    rec->du = malloc(nu * sizeof *rec->du);
    rec->ndu = nu;
    int rc = lo && us && rec->du ? HY_OK : hy_error_set(err, HY_ENOMEM, "out of memory for the sinc route");
    if (!rc)
        rc = hy_sweep_fill(&b->sw, b->fs, lo, b->nd, err);
    if (!rc)
        rc = hy_signal_upsample_sinc(lo, b->nd, b->r, us, err);
    for (size_t i = 0; !rc && i < nu; i++)
        rec->du[i] = fabs(us[i] - u[i]);
    if (!rc && (b->need_sinc & 2)) {
        rec->ysinc = malloc(rec->n * sizeof *rec->ysinc);
        ys = malloc((skip + rec->n) * sizeof *ys);
        rc = rec->ysinc && ys ? simulate(b, us, nu, ys, err)
                              : hy_error_set(err, HY_ENOMEM, "out of memory for the sinc route");
        if (!rc)
            memcpy(rec->ysinc, ys + skip, rec->n * sizeof *ys);
    }
    free(lo);
    free(us);
    free(ys);
    return rc;
}

static int make_record(const hy_scene_doc *d, const bw_setup *b, bw_record *rec, hy_error *err)
{
    double *u = NULL, *yall = NULL;
    size_t nu, step = b->dec == DEC_NONE ? 1 : b->r;
    memset(rec, 0, sizeof *rec);
    int rc = make_force(b, &u, &nu, err);
    if (rc) {
        free(u);
        return relocate(&d->input.h, IN(kind), err, rc, "");
    }
    int sweep = b->input == IN_SWEEP;
    size_t nout = sweep ? (nu + step - 1) / step : nu / step; /* per period, or all */
    size_t skip = sweep ? 0 : (size_t)b->settle * nout, nkeep = sweep ? nout : (size_t)b->cycles * nout;
    rec->fs_out = b->fs * (double)b->r / (double)step;
    rec->nper = sweep ? 0 : nout;
    rec->n = nkeep;
    rec->t = malloc(nkeep * sizeof *rec->t);
    rec->u = malloc(nkeep * sizeof *rec->u);
    if (b->need_output) {
        rec->y = malloc(nkeep * sizeof *rec->y);
        yall = malloc((skip + nkeep) * sizeof *yall);
    }
    if (!rec->t || !rec->u || (b->need_output && (!rec->y || !yall))) {
        free(u);
        free(yall);
        return hy_error_set(err, HY_ENOMEM, "out of memory for %zu samples", skip + nkeep);
    }
    for (size_t i = 0; i < nkeep; i++) {
        rec->t[i] = (double)(skip + i) / rec->fs_out;
        rec->u[i] = u[(sweep ? i : i % nout) * step];
    }
    if (b->need_output || b->need_sinc) {
        double t0 = hy_now();
        rc = b->need_output ? simulate(b, u, nu, yall, err) : HY_OK;
        if (rc)
            rc = relocate(&d->model.h, HY_DECL_HEAD, err, rc, "Bouc-Wen integration failed: ");
        else if (b->need_output)
            memcpy(rec->y, yall + skip, nkeep * sizeof *rec->y);
        if (!rc && b->need_sinc) {
            rc = sinc_route(b, u, nu, rec, skip, err);
            if (rc)
                rc = relocate(&d->model.h, HY_DECL_HEAD, err, rc, "the sinc route's integration failed: ");
        }
        /* as `hystviz boucwen data`: the noise stream is seeded apart from the phases */
        if (!rc && b->noise > 0 && b->need_output)
            rc = hy_signal_add_noise(rec->y, nkeep, b->noise, rec->fs_out / 2, rec->fs_out,
                                     b->seed ^ 0x6e6f697365ULL, err);
        if (!rc && b->noise > 0 && rec->ysinc) /* the same noise: the routes' difference stays noiseless */
            rc = hy_signal_add_noise(rec->ysinc, nkeep, b->noise, rec->fs_out / 2, rec->fs_out,
                                     b->seed ^ 0x6e6f697365ULL, err);
        rec->sim_seconds = hy_now() - t0;
    }
    free(u);
    free(yall);
    return rc;
}

/* 20 log10(|y| / 1 mm) for y in metres; NaN (a gap in the curve) for y = 0. */
static double db_mm(double y)
{
    double a = fabs(1e3 * y);
    return a > 0 ? 20.0 * log10(a) : NAN;
}

/* The last period's one-sided amplitude spectrum in dB re 1 mm, f in Hz. */
static int spectrum(const bw_record *rec, hy_run_series *se, hy_error *err)
{
    size_t N = rec->nper, nf = N / 2 + 1;
    double *X = malloc(N * sizeof *X);
    se->x = malloc(nf * sizeof *se->x);
    se->y = malloc(nf * sizeof *se->y);
    se->n = nf;
    if (!X || !se->x || !se->y) {
        free(X);
        return hy_error_set(err, HY_ENOMEM, "out of memory for series '%s'", se->name);
    }
    memcpy(X, rec->y + rec->n - N, N * sizeof *X);
    int rc = hy_signal_fft_forward(X, N, err);
    for (size_t k = 0; !rc && k < nf; k++) {
        double re = k == 0 ? X[0] : (2 * k == N ? X[N - 1] : X[2 * k - 1]);
        double im = k == 0 || 2 * k == N ? 0.0 : X[2 * k];
        double amp = (k == 0 || 2 * k == N ? 1.0 : 2.0) * hypot(re, im) / (double)N;
        se->x[k] = (double)k * rec->fs_out / (double)N;
        se->y[k] = db_mm(amp);
    }
    free(X);
    return rc;
}

/* Largest |y - y_exact| in mm against the linear oscillator's exact steady
 * state (bw_beta = 0 and a sine force); NaN otherwise. */
static double linear_error(const bw_setup *b, const bw_record *rec)
{
    if (b->p.beta != 0 || b->input != IN_SINE || !rec->y)
        return NAN;
    double w = 2 * M_PI / b->period, K = b->p.k + b->p.alpha;
    double re = K - b->p.m * w * w, im = b->p.c * w, d = re * re + im * im;
    double hr = re / d, hi = -im / d, e = 0;
    for (size_t i = 0; i < rec->n; i++) {
        double wt = w * rec->t[i];
        double ye = b->amp * (hr * sin(wt) + hi * cos(wt)) + b->offset / K;
        e = fmax(e, fabs(rec->y[i] - ye));
    }
    return 1e3 * e;
}

/* One point a second: the largest |a| (|a - b| if b) over each block of
 * round(rate) samples, times scale, at the block's middle (t0: time of a[0]). */
static int per_second(const double *a, const double *b, size_t n, double rate, double t0, double scale,
                      hy_run_series *se, hy_error *err)
{
    size_t B = rate >= 1.5 ? (size_t)llround(rate) : 1, nb = (n + B - 1) / B;
    se->x = malloc((nb ? nb : 1) * sizeof *se->x);
    se->y = malloc((nb ? nb : 1) * sizeof *se->y);
    se->n = nb;
    if (!se->x || !se->y)
        return hy_error_set(err, HY_ENOMEM, "out of memory for series '%s'", se->name);
    for (size_t k = 0; k < nb; k++) {
        size_t i0 = k * B, len = n - i0 < B ? n - i0 : B;
        double m = 0;
        for (size_t i = i0; i < i0 + len; i++)
            m = fmax(m, fabs(b ? a[i] - b[i] : a[i]));
        se->x[k] = t0 + ((double)i0 + 0.5 * (double)(len - 1)) / rate;
        se->y[k] = scale * m;
    }
    return HY_OK;
}

/* dB series: values below [series] floor and the gaps of exact zeros drawn at it. */
static void apply_floor(hy_run_series *se)
{
    double floor_db = se->decl->floor;
    int q = se->decl->quantity;
    if (q == Q_OUTPUT || q == Q_INPUT || hy_decl_got(&se->decl->h, SE(floor)) != HY_SCENE_SET)
        return;
    for (size_t i = 0; i < se->n && se->y; i++)
        if (!(se->y[i] >= floor_db))
            se->y[i] = floor_db;
}

static int fill_series(const hy_scene_run *r, const bw_setup *b, const bw_record *rec, hy_run_series *se,
                       hy_error *err)
{
    int q = se->decl->quantity;
    se->err = NAN;
    se->err_ref = NULL;
    if (q == Q_SPECTRUM) {
        int rc = spectrum(rec, se, err);
        apply_floor(se);
        return rc;
    }
    if (q == Q_ENVELOPE)
        return per_second(rec->y, NULL, rec->n, rec->fs_out, rec->t[0], 1e3, se, err);
    if (q == Q_SINC_INPUT)
        return per_second(rec->du, NULL, rec->ndu, b->fs * (double)b->r, rec->t[0], 1.0, se, err);
    if (q == Q_SINC_OUTPUT)
        return per_second(rec->ysinc, rec->y, rec->n, rec->fs_out, rec->t[0], 1e3, se, err);
    size_t n = q == Q_TRANSIENT_DB ? rec->n - rec->nper : rec->n;
    se->x = malloc(n * sizeof *se->x);
    se->y = malloc(n * sizeof *se->y);
    se->n = n;
    if (!se->x || !se->y)
        return hy_error_set(err, HY_ENOMEM, "out of memory for series '%s'", se->name);
    const double *last = q == Q_TRANSIENT_DB ? rec->y + rec->n - rec->nper : NULL;
    for (size_t i = 0; i < n; i++) {
        se->x[i] = r->figure_kind == FIG_LOOP ? rec->u[i] : rec->t[i];
        switch (q) {
        case Q_INPUT: se->y[i] = rec->u[i]; break;
        case Q_OUTPUT_DB: se->y[i] = db_mm(rec->y[i]); break;
        case Q_TRANSIENT_DB: se->y[i] = db_mm(rec->y[i] - last[i % rec->nper]); break;
        default: se->y[i] = 1e3 * rec->y[i]; break;
        }
    }
    apply_floor(se);
    if (q == Q_OUTPUT) {
        se->err = linear_error(b, rec);
        if (!isnan(se->err))
            se->err_ref = "exact steady state of the linear oscillator (mm)";
    }
    return HY_OK;
}

/* A marker at the sample nearest to t = at (f = at for a spectrum). */
static void place_marker(const bw_record *rec, hy_run_series *se)
{
    double at = se->decl->at;
    if (se->n == 0 || hy_decl_got(&se->decl->h, SE(at)) != HY_SCENE_SET)
        return;
    int q = se->decl->quantity;
    double f = q == Q_SPECTRUM ? at * (double)rec->nper / rec->fs_out : (at - rec->t[0]) * rec->fs_out;
    size_t i = f > 0 ? (size_t)fmin(nearbyint(f), (double)(se->n - 1)) : 0;
    if (q >= Q_ENVELOPE) /* a point a second: the nearest */
        for (size_t k = i = 0; k < se->n; k++)
            if (fabs(se->x[k] - at) < fabs(se->x[i] - at))
                i = k;
    se->has_mark = 1;
    se->mark_x = se->x[i];
    se->mark_y = se->y[i];
}

static void log_run(const hy_scene_run *r, FILE *log)
{
    fprintf(log, "%s: plan\n%s", r->path, r->plan);
    for (size_t i = 0; i < r->nseries; i++) {
        const hy_run_series *se = &r->series[i];
        fprintf(log, "  series %-12s data=boucwen quantity=%-12s %7zu points %8.3f ms", se->name,
                ENUM_TEXT(se->decl, hy_decl_series, quantity), se->n, 1e3 * se->seconds);
        if (se->err_ref)
            fprintf(log, "  error %.3g vs %s", se->err, se->err_ref);
        fputc('\n', log);
    }
    fprintf(log, "  compute total %.3f ms\n", 1e3 * r->seconds_compute);
}

static void plan_text(hy_scene_run *r, const bw_setup *b, const bw_record *rec)
{
    static const char *const inputs[] = {"sine", "multisine", "sweep"};
    static const char *const decs[] = {"in prime-factor stages (decimate 'fir')", "in one stage (decimate 'fir')",
                                       "not decimated"};
    size_t len = strlen(r->plan);
    if (!b->need_output && !b->need_sinc) {
        snprintf(r->plan + len, sizeof r->plan - len, "Bouc-Wen: %s input only, no integration\n", inputs[b->input]);
        return;
    }
    char span[96];
    if (b->input == IN_SWEEP)
        snprintf(span, sizeof span, "the whole sweep (%zu samples at %g Hz)", b->nd, b->fs);
    else
        snprintf(span, sizeof span, "%ld period(s) kept after %ld settling", b->cycles, b->settle);
    snprintf(r->plan + len, sizeof r->plan - len,
             "Bouc-Wen: %s force, Newmark + Newton at %g Hz (%g Hz x %zu), %s, %s to %g Hz: %.3f ms\n",
             inputs[b->input], b->fs * (double)b->r, b->fs, b->r, span, decs[b->dec], rec->fs_out,
             1e3 * rec->sim_seconds);
}

/* Computes every series into r->series (x: t in s, or u in N in loop figures,
 * or f in Hz for spectra), logging the plan and timings to log (may be NULL);
 * on error the series computed so far stay in r for hy_scene_run_free. */
static int boucwen_compute(hy_scene_run *r, FILE *log, hy_error *err)
{
    double t_start = hy_now();
    bw_setup b;
    bw_record rec = {0};
    int rc = read_setup(r, &b, err);
    if (rc)
        return rc;
    b.cancel = hy_scene_run_cancel_hook(r);
    size_t ns = r->doc.nseries;
    r->series = calloc(ns ? ns : 1, sizeof *r->series);
    if (!r->series)
        return hy_error_set(err, HY_ENOMEM, "out of memory");
    r->nseries = ns;
    for (size_t i = 0; i < ns; i++) {
        r->series[i].decl = &r->doc.series[i];
        r->series[i].name = r->doc.series[i].h.name;
        r->series[i].data = HY_DATA_BOUCWEN;
    }
    rc = hy_scene_run_check_cancel(r, err);
    if (!rc)
        rc = make_record(&r->doc, &b, &rec, err);
    for (size_t i = 0; i < ns && !rc; i++) {
        double t0 = hy_now();
        if (!(rc = hy_scene_run_check_cancel(r, err)))
            rc = fill_series(r, &b, &rec, &r->series[i], err);
        if (!rc)
            place_marker(&rec, &r->series[i]);
        r->series[i].seconds = hy_now() - t0;
    }
    if (!rc)
        plan_text(r, &b, &rec);
    record_free(&rec);
    r->seconds_compute = hy_now() - t_start;
    if (!rc && log)
        log_run(r, log);
    return rc;
}

/* ---- the model table's entry ------------------------------------------- */

static const char *const bw_keys[] = {"m", "c", "k", "alpha", "bw_beta", "bw_gamma", "delta", "nu", NULL};

/* Newmark steps and series samples, plus the annotations' placement. */
static int bw_estimate(const hy_scene_run *r, double *work, char *what, size_t size, hy_error *err)
{
    size_t na = r->doc.nannotation;
    int rc = boucwen_work(r, work, err);
    *work = hy_cost(r->cost_counts, HY_COST_NEWMARK, *work) + hy_cost(r->cost_counts, HY_COST_ANNOTATION, (double)na);
    if (what && size)
        snprintf(what, size, "Newmark steps and series samples, %zu annotations", na);
    return rc;
}

const hy_scene_model hy_scene_model_boucwen = {
    "boucwen", bw_keys, quantity_names, NULL, NULL, 0,
    "displacement, velocity and the hysteretic z (Newmark)", boucwen_load, bw_estimate,
    boucwen_compute, NULL, 0, NULL, NULL, NULL, HY_INPUT_BOUCWEN, 1u << HY_DATA_BOUCWEN, HY_COST_NEWMARK};
