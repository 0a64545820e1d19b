/* SPDX-License-Identifier: MIT */
/* scene_forc.c: [figure] kind = forc: the FORC protocol (docs/FORC.md, "The
 * protocol on a model") on any rate-independent model of the model table (its
 * hy_rateind_type) or on the γ → ∞ limit y*_u of Dahl/LuGre/the filter system
 * (seed 000, Theorem 2: y*_u depends only on the input's values, one
 * hy_limit_step per monotone move), or a measured FORC file ([forc] file);
 * then ρ by hy_forc_rho and the heat map by hy_forc_plot.  Generic through
 * the table: no model is named here. */
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "hy_cost.h"
#include "hy_forc.h"
#include "hy_forc_plot.h"
#include "hy_limit.h"
#include "hy_os.h"
#include "hy_out.h"
#include "hy_preisach_table.h"
#include "hy_scene_policy.h"
#include "scene_forc.h"
#include "scene_model.h"

#define FORC_FILE_MAX ((size_t)64 << 20) /* bytes of a FORC file read (as hystviz forc) */

struct hy_scene_forc {
    hy_forc_data d;
    hy_forc_grid g;
    hy_forc_opts o;
    int have_d, have_g;
    double seconds_data, seconds_rho;
    size_t nfit;
    double *m_model;          /* reproduce: the tabulated Preisach model's M at the data's points;
                               * protocol = file (without reproduce): the measured M */
    double rms_meas;          /* protocol = file: RMS of the model's M against the measured (NaN: none) */
    double rms, offset;       /* reproduce: the fitted density's RMS and saturation output */
    double rms_clip;          /* reproduce: the clipped distribution's RMS (the baseline)   */
    size_t ntable, nclipped;
    hy_preisach_table_fitres fit; /* reproduce: the least-squares density                  */
    int have_fit;
    double seconds_fit;
    char legend[2][160];      /* draw = curves: the two labels */
};

/* The y*_u limit as a rate-independent model: y after each monotone move. */
typedef struct ystar_ctx {
    double a, g0, u, y;
} ystar_ctx;

static int ystar_fn(void *ctx, double u, double *y, hy_error *err)
{
    (void)err;
    ystar_ctx *c = ctx;
    if (u != c->u)
        c->y = hy_limit_step(c->a, c->g0, c->y, u > c->u ? 1 : -1, fabs(u - c->u));
    c->u = u;
    *y = c->y;
    return HY_OK;
}

static int ri_fn(void *ctx, double u, double *y, hy_error *err)
{
    hy_rateind *m = ctx;
    int rc = hy_rateind_apply(m, u, err);
    *y = m->out[0];
    return rc;
}

static const hy_decl_forc *decl(const hy_scene_run *r) { return &r->doc.forc; }

#define AT(field) offsetof(hy_decl_forc, field)

static int has_file(const hy_scene_run *r) { return hy_decl_got(&decl(r)->h, AT(file)) >= 0; }

/* The protocol of [forc] (defaults filled in), checked at its keys. */
static int protocol(const hy_scene_run *r, hy_forc_protocol *pr, hy_error *err)
{
    const hy_decl_forc *f = decl(r);
    double lo = f->range.v[0], hi = f->range.v[1];
    pr->ha_lo = lo;
    pr->ha_hi = hi;
    pr->hb_max = hy_decl_got(&f->h, AT(hb_max)) >= 0 ? f->hb_max : hi;
    pr->hsat = hy_decl_got(&f->h, AT(hsat)) >= 0 ? f->hsat : hi + (hi - lo);
    pr->ncurves = (size_t)f->curves;
    if (!(pr->hb_max >= hi))
        return hy_decl_error(&f->h, AT(hb_max), err, HY_EINVAL, "hb_max = %g is below the range's upper end %g",
                             pr->hb_max, hi);
    if (!(pr->hsat >= pr->hb_max))
        return hy_decl_error(&f->h, AT(hsat), err, HY_EINVAL, "hsat = %g is below hb_max = %g: no saturation",
                             pr->hsat, pr->hb_max);
    return HY_OK;
}

/* The measured file of [forc] file, read under the scene's file policy. */
static int read_file(hy_scene_run *r, hy_scene_forc *F, hy_error *err)
{
    const hy_decl_forc *f = decl(r);
    char *text;
    size_t len;
    double t0 = hy_now();
    int user, rc = hy_scene_read_path_max(r->scene, "forc", NULL, "file", FORC_FILE_MAX, &text, &len, &user, err);
    if (rc)
        return rc;
    rc = hy_forc_read(&F->d, text, len, f->file, err); /* file:line:col of the FORC file */
    free(text);
    F->seconds_data = hy_now() - t0;
    if (rc)
        return rc;
    F->have_d = 1;
    if (f->drift && (rc = hy_forc_drift(&F->d, err)))
        return hy_decl_error(&f->h, AT(drift), err, rc, "%s: %s", f->file, err->msg);
    return HY_OK;
}

int hy_scene_forc_load(hy_scene_run *r, hy_error *err)
{
    const hy_decl_forc *f = decl(r);
    if (r->doc.nseries)
        return hy_decl_error(&r->doc.series[0].h, HY_DECL_HEAD, err, HY_EINVAL,
                             "a [figure] kind = forc draws the FORC diagram of [forc], not [series]");
    if (r->doc.nannotation || r->doc.npanel)
        return hy_decl_error(r->doc.nannotation ? &r->doc.annotation[0].h : &r->doc.panel[0].h, HY_DECL_HEAD, err,
                             HY_EINVAL, "a [figure] kind = forc draws its FORC diagram alone: no [%s] (not drawn)",
                             r->doc.nannotation ? "annotation" : "panel");
    if (!(r->forc = calloc(1, sizeof *r->forc)))
        return hy_error_set(err, HY_ENOMEM, "out of memory");
    hy_scene_forc *F = r->forc;
    F->o = hy_forc_defaults();
    F->o.sf = f->sf;
    F->o.extend = f->extend;
    if (f->sc1 > 0) {
        if (!(f->sc1 >= 1))
            return hy_decl_error(&f->h, AT(sc1), err, HY_EINVAL, "sc1 = %g: 0 (off) or at least 1", f->sc1);
        F->o.sc0 = f->sc0;
        F->o.sc1 = f->sc1;
    }
    F->rms_meas = NAN;
    int rc;
    if (f->protocol == 1 && !has_file(r))
        return hy_decl_error(&f->h, AT(protocol), err, HY_EINVAL, "protocol = file needs [forc] file");
    if (has_file(r) && ((rc = read_file(r, F, err)) || f->protocol == 0))
        return rc;
    hy_forc_protocol pr;
    if (!has_file(r) && (rc = protocol(r, &pr, err)))
        return rc;
    const hy_scene_model *mt = r->mtype;
    if (mt->ri) {
        if (!(r->ri_par = calloc(1, mt->ri_par_size)))
            return hy_error_set(err, HY_ENOMEM, "out of memory");
        return hy_scene_model_read(mt, r->scene, &r->doc.model, r->ri_par, err);
    }
    if (mt->caps & HY_CAP_YSTAR) /* Dahl, LuGre, the filter system: their limit y*_u */
        return hy_scene_run_build_model(r, err);
    return hy_decl_error(&r->doc.model.h, offsetof(hy_decl_model, kind), err, HY_EINVAL,
                         "a FORC diagram needs a rate-independent model or one with the limit y*_u; %s has neither",
                         mt->name);
}

int hy_scene_forc_estimate(const hy_scene_run *r, double *work, char *what, size_t size, hy_error *err)
{
    (void)err;
    const hy_decl_forc *f = decl(r);
    double n = has_file(r) ? (double)r->forc->d.npoints : 0.5 * (double)f->curves * (double)f->curves;
    double sf = f->sc1 > 0 ? fmax(f->sc0, f->sc1) : f->sf;
    /* the moves, and the regression's dot products */
    *work = hy_cost(r->cost_counts, HY_COST_FORC, n * (1 + 0.01 * (2 * sf + 1) * (2 * sf + 1)));
    if (what && size)
        snprintf(what, size, "%.0f FORC points, SF %g", n, sf);
    return HY_OK;
}


/* The model behind fn at the measured file's fields (protocol = file): each
 * curve from hsat to its H_a, then through its H_b; F->d becomes the model's
 * data, the measured M kept in F->m_model (for the curves figure) and the
 * RMS of the difference in F->rms_meas. */
static int on_fields(hy_scene_run *r, hy_scene_forc *F, hy_rateind_fn fn, void *ctx, hy_error *err)
{
    hy_forc_data *d = &F->d, md;
    const hy_decl_forc *f = decl(r);
    double hsat = hy_decl_got(&f->h, AT(hsat)) >= 0 ? f->hsat : d->hsat, ss = 0;
    for (size_t k = 0; !isfinite(hsat) && k < d->npoints; k++)
        hsat = fabs(d->hb[k]); /* no HSat in the file: the largest field measured */
    for (size_t k = 0; k < d->npoints; k++)
        hsat = fmax(hsat, fabs(d->hb[k]));
    double *ha = malloc(d->ncurves * sizeof *ha), *m = malloc(d->npoints * sizeof *m);
    size_t *n = malloc(d->ncurves * sizeof *n);
    int rc = ha && m && n ? HY_OK : hy_error_set(err, HY_ENOMEM, "out of memory");
    for (size_t i = 0; i < d->ncurves && !rc; i++) {
        const hy_forc_curve *c = &d->curve[i];
        double y;
        ha[i] = c->ha;
        n[i] = c->n;
        rc = fn(ctx, hsat, &y, err);
        if (!rc)
            rc = fn(ctx, c->ha, &y, err);
        for (size_t j = c->first; j < c->first + c->n && !rc; j++)
            if (!(rc = fn(ctx, d->hb[j], &m[j], err)))
                ss += (m[j] - d->m[j]) * (m[j] - d->m[j]);
    }
    if (!rc && !(rc = hy_forc_data_set(&md, d->ncurves, ha, n, d->hb, m, err))) {
        md.units = d->units, md.field_unit = d->field_unit, md.moment_unit = d->moment_unit;
        md.field_to_tesla = d->field_to_tesla;
        F->rms_meas = sqrt(ss / (double)d->npoints);
        memcpy(m, d->m, d->npoints * sizeof *m); /* the measured M, for the figure */
        F->m_model = m;
        m = NULL;
        hy_forc_data_free(d);
        *d = md;
    }
    free(ha);
    free(m);
    free(n);
    return rc;
}

/* The protocol on the model into F->d. */
static int run_protocol(hy_scene_run *r, hy_scene_forc *F, hy_error *err)
{
    hy_forc_protocol pr = {isfinite(F->d.hsat) ? F->d.hsat : 0, 0, 0, 0, 0}; /* protocol = file: a start only */
    int rc = F->have_d ? HY_OK : protocol(r, &pr, err);
    if (rc)
        return rc;
    if (r->mtype->ri) {
        hy_rateind m;
        if ((rc = hy_rateind_alloc(&m, r->mtype->ri, r->ri_par, pr.hsat, err)))
            return hy_scene_model_relocate(&r->doc.model, r->mtype, rc, err);
        rc = F->have_d ? on_fields(r, F, ri_fn, &m, err) : hy_forc_protocol_run(&F->d, &pr, ri_fn, &m, err);
        hy_rateind_free(&m);
    } else {
        double g0 = hy_model_g0(&r->model), a = hy_model_a(&r->model);
        if ((rc = hy_model_validate(&r->model, err)))
            return hy_decl_error(&r->doc.model.h, HY_DECL_HEAD, err, rc, "%s", err->msg);
        if (!(isfinite(a) && a > 0 && isfinite(g0) && g0 > 0))
            return hy_decl_error(&r->doc.model.h, HY_DECL_HEAD, err, HY_EINVAL,
                                 "sigma0/g(0) = %g/%g is not a finite positive number", r->model.sigma0, g0);
        ystar_ctx c = {a, g0, pr.hsat, g0}; /* positive saturation at hsat */
        rc = F->have_d ? on_fields(r, F, ystar_fn, &c, err) : hy_forc_protocol_run(&F->d, &pr, ystar_fn, &c, err);
    }
    if (rc && !strncmp(err->msg, "FORC protocol", 13)) /* the protocol's own refusal: at [forc] */
        return hy_decl_error(&decl(r)->h, HY_DECL_HEAD, err, rc, "%s", err->msg);
    if (rc) /* the model refused a move: at the [model] key its message names */
        return hy_scene_model_relocate(&r->doc.model, r->mtype, rc, err);
    F->have_d = 1;
    return HY_OK;
}

/* max M − min M of the data (1 when flat). */
static double m_range(const hy_forc_data *d)
{
    double lo = INFINITY, hi = -INFINITY;
    for (size_t k = 0; k < d->npoints; k++)
        lo = fmin(lo, d->m[k]), hi = fmax(hi, d->m[k]);
    return hi > lo ? hi - lo : 1;
}

/* [forc] reproduce: the baseline (ρ clipped as a tabulated Preisach density)
 * and the least-squares density (hy_preisach_table_fit), its FORCs. */
static int reproduce(hy_scene_run *r, hy_scene_forc *F, hy_error *err)
{
    hy_preisach_table t;
    double clip_offset;
    free(F->m_model); /* protocol = file's measured M: the table's replaces it in the figure */
    F->m_model = malloc(F->d.npoints * sizeof *F->m_model);
    int rc = F->m_model ? hy_preisach_table_from_grid(&t, &F->g, err) : hy_error_set(err, HY_ENOMEM, "out of memory");
    if (!rc) {
        rc = hy_preisach_table_forc(&t, &F->d, F->m_model, &F->rms_clip, &clip_offset, err);
        F->ntable = t.n;
        F->nclipped = t.nclipped;
        hy_preisach_table_free(&t);
    }
    size_t nc, nu;
    hy_preisach_table_fit_shape(&F->g, &nc, &nu);
    double t0 = hy_now();
    if (!rc && !(rc = hy_preisach_table_fit(&F->d, &F->g, nc, nu, &F->fit, err))) {
        F->have_fit = 1;
        if (!(rc = hy_preisach_table_from_grid(&t, &F->fit.g, err))) {
            rc = hy_preisach_table_forc(&t, &F->d, F->m_model, &F->rms, &F->offset, err);
            hy_preisach_table_free(&t);
        }
    }
    F->seconds_fit = hy_now() - t0;
    if (rc)
        return hy_decl_error(&decl(r)->h, AT(reproduce), err, rc, "%s", err->msg);
    return HY_OK;
}

int hy_scene_forc_compute(hy_scene_run *r, FILE *log, hy_error *err)
{
    hy_scene_forc *F = r->forc;
    double t0 = hy_now();
    int rc = HY_OK, read = F->have_d && decl(r)->protocol == 0;
    if (!read)
        rc = run_protocol(r, F, err);
    double t1 = hy_now();
    if (!rc) {
        hy_forc_grid_auto(&F->d, &F->o, &F->g);
        F->have_g = 1;
        if ((rc = hy_forc_rho(&F->d, &F->o, &F->g, &F->nfit, err)))
            rc = hy_decl_error(&decl(r)->h, HY_DECL_HEAD, err, rc, "%s", err->msg);
    }
    if (!rc && decl(r)->reproduce)
        rc = reproduce(r, F, err);
    int model_on_file = decl(r)->protocol == 1;
    snprintf(F->legend[0], sizeof F->legend[0], "%s", has_file(r) && !model_on_file ? "measured" : r->mtype->name);
    if (!rc && model_on_file && !decl(r)->reproduce)
        snprintf(F->legend[1], sizeof F->legend[1], "measured (RMS of the model: %.2g %% of the range of M)",
                 100 * F->rms_meas / m_range(&F->d));
    else if (!rc && F->m_model)
        snprintf(F->legend[1], sizeof F->legend[1], "Preisach, least-squares density ρ ≥ 0 (RMS %.2g %%)", 100 * F->rms / m_range(&F->d));
    if (!read)
        F->seconds_data = t1 - t0;
    F->seconds_rho = hy_now() - t1;
    r->seconds_compute = F->seconds_data + F->seconds_rho;
    if (!rc && log) {
        double da, db;
        hy_forc_steps(&F->d, &da, &db);
        fprintf(log, "%s: FORC %s: %zu curves, %zu points, steps %.6g / %.6g, %s %.3f ms; rho on %zu x %zu nodes "
                "(%zu fitted) %.3f ms\n", r->path, read ? decl(r)->file : r->mtype->name, F->d.ncurves,
                F->d.npoints, da, db, read ? "read" : "protocol", 1e3 * F->seconds_data, F->g.nc, F->g.nu,
                F->nfit, 1e3 * F->seconds_rho);
        if (isfinite(F->rms_meas))
            fprintf(log, "%s: FORC %s at the fields of %s: RMS of M against the measured over all %zu points %.6g\n",
                    r->path, r->mtype->name, decl(r)->file, F->d.npoints, F->rms_meas);
        if (F->have_fit) {
            fprintf(log, "%s: FORC Preisach density from rho clipped (%zu nodes > 0, %zu negative clipped to 0): RMS "
                    "of M over all %zu points %.6g (%.3g %% of the range of M)\n", r->path, F->ntable, F->nclipped,
                    F->d.npoints, F->rms_clip, 100 * F->rms_clip / m_range(&F->d));
            fprintf(log, "%s: FORC Preisach density by least squares on %zu x %zu nodes (%zu free parameters, %zu "
                    "sweeps, %.3f ms): RMS of M over all %zu points %.6g (%.3g %% of the range of M), saturation "
                    "output %.6g\n", r->path, F->fit.g.nc, F->fit.g.nu, F->fit.nfree, F->fit.iters,
                    1e3 * F->seconds_fit, F->d.npoints, F->rms, 100 * F->rms / m_range(&F->d), F->offset);
        }
    }
    return rc;
}

/* The plot's options: [forc] scale and units, [figure] size and dpi. */
static hy_forc_plot_opts plot_opts(const hy_scene_run *r)
{
    const hy_decl_forc *f = decl(r);
    const hy_scene_forc *F = r->forc;
    hy_forc_plot_opts po = hy_forc_plot_defaults();
    po.width = r->doc.figure.size[0];
    po.height = r->doc.figure.size[1];
    po.dpi = (double)r->doc.figure.dpi;
    po.vmax = f->vmax;
    if (!(po.vmax > 0)) {
        double da, db, sf = F->o.sc1 > 0 ? F->o.sc0 : F->o.sf;
        hy_forc_steps(&F->d, &da, &db);
        po.vmax = hy_forc_plot_max(&F->g, F->o.extend ? (sf + 0.5) * db : -INFINITY);
        if (!(po.vmax > 0))
            po.vmax = hy_forc_plot_max(&F->g, -INFINITY);
    }
    if (has_file(r)) {
        po.field_to_mt = isfinite(F->d.field_to_tesla) ? 1e3 * F->d.field_to_tesla : 0;
        po.rho_unit = F->d.units == HY_FORC_UNITS_HYBRID_SI ? "A m²/T²"
                      : F->d.units == HY_FORC_UNITS_CGS     ? "emu/Oe²"
                      : F->d.units == HY_FORC_UNITS_SI      ? "A m²/(A/m)²"
                                                            : "";
    } else {
        po.field_to_mt = 1e3 * f->field_to_tesla;
        po.rho_unit = f->rho_unit;
    }
    return po;
}

/* draw = curves: M(H_b) of every curve (NaN between curves), measured and,
 * with reproduce, the tabulated Preisach model's; *fig points into st. */
typedef struct curves_fig {
    double *x, *y, *ym;
    hy_series s[2];
    hy_axes ax;
    hy_figure fig;
    char xlabel[64], ylabel[64];
} curves_fig;

static int curves_figure(const hy_scene_run *r, curves_fig *c, hy_error *err)
{
    const hy_scene_forc *F = r->forc;
    const hy_forc_data *d = &F->d;
    const hy_decl_figure *df = &r->doc.figure;
    memset(c, 0, sizeof *c);
    size_t n = d->npoints + d->ncurves;
    c->x = malloc(n * sizeof *c->x);
    c->y = malloc(n * sizeof *c->y);
    c->ym = malloc(n * sizeof *c->ym);
    if (!c->x || !c->y || !c->ym)
        return hy_error_set(err, HY_ENOMEM, "out of memory");
    hy_forc_plot_opts po = plot_opts(r);
    double f = po.field_to_mt > 0 ? po.field_to_mt : 1;
    size_t k = 0;
    for (size_t i = 0; i < d->ncurves; i++) {
        const hy_forc_curve *cv = &d->curve[i];
        for (size_t j = cv->first; j < cv->first + cv->n; j++, k++) {
            c->x[k] = f * d->hb[j];
            c->y[k] = d->m[j];
            c->ym[k] = F->m_model ? F->m_model[j] : NAN;
        }
        c->x[k] = c->y[k] = c->ym[k] = NAN;
        k++;
    }
    snprintf(c->xlabel, sizeof c->xlabel, "%s", po.field_to_mt > 0 ? "μ_0H_b (mT)" : "H_b");
    c->s[0] = (hy_series){c->x, c->y, n, HY_LINE_SOLID, {0, {0, 0, 0}}, 0.5, 0, 0, 0, F->legend[0]};
    c->s[1] = (hy_series){c->x, c->ym, n, HY_LINE_DASHED, {6, {0, 0, 0}}, 0.7, 0, 0, 0, F->legend[1]};
    c->ax.series = c->s;
    c->ax.nseries = F->m_model ? 2 : 1;
    c->ax.xlabel = df->xlabel ? df->xlabel : c->xlabel;
    const char *mu = !strcmp(d->moment_unit, "A m2") ? "A m^2" : d->moment_unit; /* the file's */
    snprintf(c->ylabel, sizeof c->ylabel, *mu ? "M (\\mathrm{%s})" : "M", mu); /* units upright */
    c->ax.ylabel = df->ylabel ? df->ylabel : c->ylabel;
    c->ax.title = df->title && df->title[0] ? df->title : NULL;
    c->ax.x = hy_scene_axis_range(&df->xlim, df->xlog); /* in the drawn units (mT where converted) */
    c->ax.y = hy_scene_axis_range(&df->ylim, df->ylog);
    c->ax.legend = df->legend;
    c->ax.grid = df->grid;
    c->fig = (hy_figure){.width = df->size[0], .height = df->size[1], .dpi = (double)df->dpi, .font = df->font,
                         .font_size = df->fontsize, .axes = &c->ax, .nrows = 1, .ncols = 1,
                         .full_resolution = df->full_resolution, .theme = df->theme};
    return HY_OK;
}

static void curves_free(curves_fig *c)
{
    free(c->x);
    free(c->y);
    free(c->ym);
}

/* The figure's <title> (the caption's first clause, else "FORC diagram") and
 * <desc> (the caption with its {section.key} filled in, then what is drawn)
 * for an SVG, as scene_draw.c writes them for the other figures. */
static void forc_text(const hy_scene_run *r, const hy_forc_plot_opts *po, int curves, char *title, size_t tn,
                      char *desc, size_t dn)
{
    const char *cap = r->doc.figure.caption && r->doc.figure.caption[0] ? r->doc.figure.caption : NULL;
    char *capx = NULL;
    hy_error e = {0};
    if (cap && strchr(cap, '{') && !hy_scene_expand(r->scene, cap, &capx, &e))
        cap = capx;
    size_t n = cap ? strcspn(cap, ";(") : 0;
    while (n > 0 && (cap[n - 1] == ' ' || cap[n - 1] == ',' || cap[n - 1] == ':'))
        n--;
    snprintf(title, tn, "%.*s", (int)(n ? n : 12), n ? cap : "FORC diagram");
    const char *unit = po->field_to_mt > 0 ? " (mT)" : "";
    if (curves)
        snprintf(desc, dn, "%s%sFirst-order reversal curves: x axis the field H_b, y axis the moment M, one curve "
                 "per reversal field H_a%s.", cap ? cap : "", cap ? " " : "",
                 has_file(r) && decl(r)->reproduce ? ", measured and reproduced" : "");
    else
        snprintf(desc, dn, "%s%sFORC diagram: x axis μ0H_c%s, y axis μ0H_u%s; colour the FORC distribution ρ%s%s%s "
                 "on a diverging scale of ±%.3g centred at 0, with contour lines.", cap ? cap : "", cap ? " " : "",
                 unit, unit, po->rho_unit && po->rho_unit[0] ? " (" : "", po->rho_unit ? po->rho_unit : "",
                 po->rho_unit && po->rho_unit[0] ? ")" : "", po->vmax);
    free(capx);
}

int hy_scene_forc_draw(const hy_scene_run *r, FILE *fp, int format, hy_error *err)
{
    char title[256], desc[2048];
    if (!r->forc || !r->forc->have_g || !r->forc->g.rho)
        return hy_error_set(err, HY_EINVAL, "%s: the FORC diagram is not computed", r->path);
    if (decl(r)->draw == 1) {
        curves_fig c;
        unsigned char *buf = NULL;
        size_t len = 0;
        int rc = curves_figure(r, &c, err);
        hy_forc_plot_opts po = plot_opts(r);
        forc_text(r, &po, 1, title, sizeof title, desc, sizeof desc);
        c.fig.svg_title = title, c.fig.svg_desc = desc;
        if (!rc)
            rc = hy_figure_render_mem(&c.fig, format, &buf, &len, err);
        if (!rc && fwrite(buf, 1, len, fp) != len)
            rc = hy_error_set(err, HY_EIO, "%s: writing the figure: %s", r->path, strerror(errno));
        free(buf);
        curves_free(&c);
        return rc;
    }
    hy_forc_plot_opts po = plot_opts(r);
    forc_text(r, &po, 0, title, sizeof title, desc, sizeof desc);
    po.title = title, po.desc = desc;
    return hy_forc_plot_write(&r->forc->g, &po, fp, format, err);
}

int hy_scene_forc_render(const hy_scene_run *r, int format, unsigned char **buf, size_t *len, hy_error *err)
{
    char *b = NULL;
    size_t n = 0;
    FILE *fp = open_memstream(&b, &n);
    if (!fp)
        return hy_error_set(err, HY_ENOMEM, "out of memory for the figure");
    int rc = hy_scene_forc_draw(r, fp, format, err);
    if (fclose(fp) && !rc)
        rc = hy_error_set(err, HY_ENOMEM, "out of memory for the figure");
    if (rc) {
        free(b);
        return rc;
    }
    *buf = (unsigned char *)b;
    *len = n;
    return HY_OK;
}

int hy_scene_forc_write_all(const hy_scene_run *r, char (*paths)[4400], const int *fmt, size_t nf, hy_error *err)
{
    hy_out out[HY_FORMAT_COUNT];
    size_t opened = 0;
    int rc = HY_OK;
    for (size_t i = 0; i < nf && !rc; i++)
        if (!(rc = hy_out_open(&out[i], paths[i], HY_OUT_HOLD, err))) {
            opened++;
            if (!(rc = hy_scene_forc_draw(r, hy_out_file(&out[i]), fmt[i], err)))
                rc = hy_out_finish(&out[i], err);
        }
    for (size_t i = 0; i < opened && !rc; i++)
        if ((rc = hy_out_publish(&out[i], err)) && i)
            hy_error_prefix(err, "only %zu of the %zu files were replaced", i, nf);
    for (size_t i = 0; i < opened; i++)
        hy_out_abort(&out[i]); /* no-op once published */
    return rc;
}

void hy_scene_forc_data(const hy_scene_run *r, FILE *out)
{
    hy_forc_write_csv(&r->forc->g, out); /* as hystviz forc -o writes it */
}

void hy_scene_forc_free(hy_scene_run *r)
{
    hy_scene_forc *F = r->forc;
    if (!F)
        return;
    if (F->have_d)
        hy_forc_data_free(&F->d);
    if (F->have_g)
        hy_forc_grid_free(&F->g);
    free(F->m_model);
    free(F->fit.g.rho);
    free(F);
    r->forc = NULL;
}
