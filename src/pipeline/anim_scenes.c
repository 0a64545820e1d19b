/* SPDX-License-Identifier: MIT */
/* anim_scenes.c: the animations of seed 000, Section 4: γ sweeps onto y*_u
 * (Examples 1-3, Figs. 4, 7, 11), the k-cycle approach to y°_u (Figs. 8-9,
 * 12-13) and Example 4's minor loop under σ0 and u_min,2 (Figs. 15-17).
 * Each distinct γ is solved once (locked cache).  (The 3-D ribbon of γ-loops
 * was removed: it had no axes or scale; hy_gl's ribbon pass stays.) */
#include "anim_scenes.h"

#include "anim_names.h"
#include "anim_preisach.h"

#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hy_gamma.h"
#include "hy_limit.h"
#include "hy_loops.h"
#include "hy_markup.h"
#include "hy_ode.h"
#include "hy_plot.h"

#define NPTS 720              /* points per plotted time span */
#define TRAIL 4               /* earlier γ loops shown fading behind the current one */

/* The colour that marks y_γ / the trail for the GL colour-map effect (viridis
 * at 0.5, so the cairo legend sample looks right). */
static const hy_rgb key_rgb = {0.163625, 0.471133, 0.558148};

/* ---- shared: the example's model and input ---- */

typedef struct example {
    hy_model m;
    hy_input in;
    hy_steady st;
    int have_in, have_st;
} example;

static int example_init(example *ex, int which, hy_error *err)
{
    memset(ex, 0, sizeof *ex);
    int s;
    if (which == 1) {             /* system (16): Dahl then filter, u = sin(2π t) */
        hy_model_dahl_filter_init(&ex->m, 1.0, 1.0, 1.0);
        s = hy_input_sine(&ex->in, 1.0, 1.0, 0.0, err);
    } else if (which == 2) {      /* LuGre of Sec. 4.2, triangle input of Fig. 6 */
        hy_model_lugre_init(&ex->m, 1, 1, 1, 2, 1, 1);
        s = hy_input_pwl(&ex->in, (const double[]){0, 1, 2}, (const double[]){0, 1, 0}, 3, err);
    } else {                      /* Example 3: bimodal input of Fig. 10 */
        hy_model_lugre_init(&ex->m, 1, 1, 1, 2, 1, 1);
        s = hy_input_bimodal(&ex->in, 0, 0.2, 1, 1.5, NULL, HY_SHAPE_LINEAR, err);
    }
    if (s)
        return s;
    ex->have_in = 1;
    if ((s = hy_steady_init(&ex->st, &ex->m, &ex->in, err)))
        return s;
    ex->have_st = 1;
    return HY_OK;
}

static void example_free(example *ex)
{
    if (ex->have_st)
        hy_steady_free(&ex->st);
    if (ex->have_in)
        hy_input_free(&ex->in);
}

static double fig_font(void) { return 10.0; }

static hy_figure one_panel(const hy_anim_frame *f, const hy_axes *ax)
{
    return (hy_figure){.width = f->width / f->scale, .height = f->height / f->scale, .dpi = 72 * f->scale,
                       .font_size = fig_font(), .axes = ax, .nrows = 1, .ncols = 1};
}

/* A viridis colour bar for t0..t1 of the map, with a caption above and end
 * labels below it, so a frame says what its colours mean; placed as the
 * legend is ("best"): where it covers the least of the frame's data, and
 * never the legend. */
static void colour_bar(const hy_anim_frame *f, const hy_figure *fig, double t0, double t1, const char *caption,
                       const char *left, const char *right)
{
    const hy_canvas *o = &f->overlay;
    double fs = fig->font_size;
    hy_markup_box cb, lb, rb;
    hy_rgb ink = {0, 0, 0};
    hy_markup_text(o, caption, 0.85 * fs, 0, 0, 0, 0, ink, &cb);
    hy_markup_text(o, left, 0.8 * fs, 0, 0, 0, 0, ink, &lb);
    hy_markup_text(o, right, 0.8 * fs, 0, 0, 0, 0, ink, &rb);
    double w = 7.0 * fs, h = 0.55 * fs;
    w = cb.width > w ? cb.width : w;
    w = lb.width + rb.width + fs > w ? lb.width + rb.width + fs : w;
    double box[4] = {0, 0, w + 0.8 * fs, 2.9 * fs};
    if (hy_figure_free_box(fig, o, 0, box, NULL))
        return;
    double x = box[0] + 0.4 * fs, y = box[1] + 1.6 * fs;
    o->ops->fill_rect(o->ctx, box[0], box[1], box[2], box[3], (hy_rgb){1, 1, 1}, 0.85);
    for (int i = 0; i < 48; i++)
        o->ops->fill_rect(o->ctx, x + w * i / 48.0, y, w / 48.0 + 0.05, h,
                          hy_cmap(HY_CMAP_VIRIDIS, t0 + (t1 - t0) * (i + 0.5) / 48.0), 1.0);
    hy_markup_text(o, caption, 0.85 * fs, 1, 0, x, y - 0.4 * fs, ink, NULL);
    hy_markup_text(o, left, 0.8 * fs, 1, 0, x, y + h + 0.95 * fs, ink, NULL);
    hy_markup_text(o, right, 0.8 * fs, 1, 0, x + w - rb.width, y + h + 0.95 * fs, ink, NULL);
}

static void extent(const double *v, size_t n, double *lo, double *hi)
{
    for (size_t i = 0; i < n; i++)
        if (isfinite(v[i])) {
            *lo = v[i] < *lo ? v[i] : *lo;
            *hi = v[i] > *hi ? v[i] : *hi;
        }
}

/* ---- γ sweeps (a): y_γ with a γ cache ---- */

typedef struct gentry {
    double gamma;
    double *y;
    int state;                /* 0 computing, 1 ready, 2 failed */
} gentry;

typedef struct sweep {
    example ex;
    int which;
    double cycles;            /* periods plotted */
    double t[NPTS], u[NPTS], ystar[NPTS];
    double uss[NPTS], yss[NPTS];
    hy_key keys[3];
    hy_track track;
    double ylo, yhi;
    gentry *cache;
    size_t ncache, capcache;
    long solves, hits;
    pthread_mutex_t mu;
    pthread_cond_t cv;
    char desc[200];
} sweep;

static int solve(const sweep *s, double gamma, double *y, hy_error *err)
{
    if (hy_gamma_exact_applies(&s->ex.m, &s->ex.in))
        return hy_gamma_exact(&s->ex.m, &s->ex.in, gamma, s->t, NPTS, y, NULL, err);
    hy_ode_opts o = hy_ode_defaults();
    o.stepper = "rk4imp";
    o.rtol = 1e-7, o.atol = 1e-9;
    return hy_ode_solve(&s->ex.m, &s->ex.in, gamma, &o, s->t, NPTS, y, NULL, err);
}

/* y_γ on s->t, solved once per distinct γ; concurrent callers of one γ wait. */
static const double *cache_get(sweep *s, double gamma, hy_error *err)
{
    pthread_mutex_lock(&s->mu);
    size_t i = 0;
    while (i < s->ncache && s->cache[i].gamma != gamma)
        i++;
    if (i < s->ncache) {
        while (s->cache[i].state == 0)
            pthread_cond_wait(&s->cv, &s->mu);
        int ok = s->cache[i].state == 1;
        s->hits += ok;
        pthread_mutex_unlock(&s->mu);
        if (!ok)
            hy_error_set(err, HY_ENUM, "solving for gamma = %g failed on another thread", gamma);
        return ok ? s->cache[i].y : NULL;
    }
    if (s->ncache == s->capcache) {
        pthread_mutex_unlock(&s->mu);
        hy_error_set(err, HY_ENOMEM, "gamma cache full (%zu values)", s->capcache);
        return NULL;
    }
    s->cache[s->ncache++] = (gentry){gamma, NULL, 0};
    pthread_mutex_unlock(&s->mu);
    double *y = malloc(NPTS * sizeof *y);
    int st = y ? solve(s, gamma, y, err) : hy_error_set(err, HY_ENOMEM, "out of memory");
    pthread_mutex_lock(&s->mu);
    s->cache[i].y = st ? NULL : y;
    s->cache[i].state = st ? 2 : 1;
    s->solves++;
    pthread_cond_broadcast(&s->cv);
    pthread_mutex_unlock(&s->mu);
    if (st)
        free(y);
    return st ? NULL : y;
}

static void sweep_release(void *state)
{
    sweep *s = state;
    if (!s)
        return;
    for (size_t i = 0; i < s->ncache; i++)
        free(s->cache[i].y);
    free(s->cache);
    pthread_mutex_destroy(&s->mu);
    pthread_cond_destroy(&s->cv);
    example_free(&s->ex);
    free(s);
}

static int sweep_new(sweep **out, int which, double cycles, size_t cap, hy_error *err)
{
    sweep *s = calloc(1, sizeof *s);
    if (!s || !(s->cache = calloc(cap, sizeof *s->cache))) {
        free(s);
        return hy_error_set(err, HY_ENOMEM, "out of memory preparing the animation");
    }
    s->capcache = cap;
    pthread_mutex_init(&s->mu, NULL);
    pthread_cond_init(&s->cv, NULL);
    s->which = which, s->cycles = cycles;
    int st = example_init(&s->ex, which, err);
    if (st) {
        sweep_release(s);
        return st;
    }
    double T = s->ex.in.period;
    for (size_t i = 0; i < NPTS; i++) {
        s->t[i] = cycles * T * (double)i / (NPTS - 1);
        s->u[i] = hy_input_u(&s->ex.in, s->t[i]);
        s->ystar[i] = hy_ystar_at(&s->ex.st, s->ex.m.x0, s->t[i]);
    }
    hy_steady_sample(&s->ex.st, NPTS, s->uss, s->yss);
    *out = s;
    return HY_OK;
}

static int sweep_prepare(void **state, const hy_anim_params *p, int which, hy_error *err)
{
    sweep *s = NULL;
    /* one solve per frame, plus the trail's γ that fall between frames */
    int st = sweep_new(&s, which, which == 3 ? 3.0 : 4.0, (size_t)(TRAIL + 1) * ((size_t)hy_anim_nframes(p) + 2), err);
    if (st)
        return st;
    double D = p->duration;
    s->keys[0] = (hy_key){0.08 * D, 1.0, HY_EASE_LINEAR};
    s->keys[1] = (hy_key){0.88 * D, 1000.0, HY_EASE_SMOOTH};
    s->track = (hy_track){s->keys, 2, 1};
    s->ylo = INFINITY, s->yhi = -INFINITY;
    extent(s->ystar, NPTS, &s->ylo, &s->yhi);
    extent(s->yss, NPTS, &s->ylo, &s->yhi);
    const double *y1 = cache_get(s, 1.0, err);      /* frame 0's γ: reused there */
    if (!y1) {
        sweep_release(s);
        return err ? err->code : HY_ENUM;
    }
    extent(y1, NPTS, &s->ylo, &s->yhi);
    double pad = 0.05 * (s->yhi - s->ylo);
    s->ylo -= pad, s->yhi += pad;
    *state = s;
    return HY_OK;
}

/* Examples 2 and 3: the current γ's loop (the last period), a fading trail of
 * the loops of the γ of 0.25, 0.5, ... s earlier, y*_u on that period (what
 * the distance is measured against) and the limit loop y°_u.  Example 1:
 * every period of y_γ coloured by time, with a colour bar saying so. */
static int sweep_draw(void *state, const hy_anim_frame *f, hy_error *err)
{
    sweep *s = state;
    double gamma = hy_track_eval(&s->track, f->time);
    const double *y = cache_get(s, gamma, err);
    if (!y)
        return err ? err->code : HY_ENUM;
    size_t i0 = s->which == 1 ? 0 : (size_t)((s->cycles - 1.0) / s->cycles * (NPTS - 1));
    size_t n = NPTS - i0;
    double dist = 0;
    for (size_t i = i0; i < NPTS; i++)
        dist = fmax(dist, fabs(y[i] - s->ystar[i]));
    char title[200], gtxt[64], dtxt[64];
    hy_markup_number(gtxt, sizeof gtxt, gamma, 3);
    hy_markup_number(dtxt, sizeof dtxt, dist, 3);
    hy_series sr[3 + TRAIL];
    size_t ns = 0;
    sr[ns++] = (hy_series){.x = s->uss, .y = s->yss, .n = NPTS,
                           .colour = {.palette = HY_RGB_EXPLICIT, .rgb = {0.8, 0.8, 0.8}}, .width = 5.0,
                           .label = "y^\\circ_u (limit loop)"};
    if (s->which == 1) {
        hy_gl_effect e = {key_rgb, HY_CMAP_VIRIDIS, 0.05, 0.95, 1.0};
        if (hy_gl_set_effect(f->gl, &e, err))
            return HY_EINVAL;
        sr[ns++] = (hy_series){.x = s->u, .y = s->ystar, .n = NPTS, .style = HY_LINE_DASHED,
                               .colour = {.palette = 0}, .width = 1.0, .label = "y^*_u"};
        sr[ns++] = (hy_series){.x = s->u, .y = y, .n = NPTS, .colour = {.palette = HY_RGB_EXPLICIT, .rgb = key_rgb},
                               .width = 1.8, .label = "y_\\gamma (colour: time)"};
        snprintf(title, sizeof title, "Example 1:  \\gamma = %s   \\|y_\\gamma - y^*_u\\|_\\infty = %s", gtxt, dtxt);
    } else {
        /* the trail first (oldest, palest, at the bottom), the current loop on top */
        static const hy_rgb verm = {0.835, 0.369, 0.0};
        for (int k = TRAIL; k >= 1; k--) {
            double tk = f->time - 0.25 * k;
            if (tk < 0)
                continue;
            const double *yk = cache_get(s, hy_track_eval(&s->track, tk), err);
            if (!yk)
                return err ? err->code : HY_ENUM;
            double fade = 0.35 + 0.13 * k;
            hy_rgb c = {verm.r + fade * (1 - verm.r), verm.g + fade * (1 - verm.g), verm.b + fade * (1 - verm.b)};
            sr[ns++] = (hy_series){.x = s->u + i0, .y = yk + i0, .n = n, .colour = {.palette = HY_RGB_EXPLICIT, .rgb = c},
                                   .width = 1.2, .label = k == 2 ? "y_\\gamma of earlier \\gamma (paler: older)" : NULL};
        }
        sr[ns++] = (hy_series){.x = s->u + i0, .y = s->ystar + i0, .n = n, .style = HY_LINE_DASHED,
                               .colour = {.palette = 0}, .width = 1.0, .label = "y^*_u"};
        sr[ns++] = (hy_series){.x = s->u + i0, .y = y + i0, .n = n, .colour = {.palette = HY_RGB_EXPLICIT, .rgb = verm},
                               .width = 2.2, .label = "y_\\gamma, current \\gamma"};
        snprintf(title, sizeof title, "Example %d, last period:  \\gamma = %s   \\|y_\\gamma - y^*_u\\|_\\infty = %s",
                 s->which, gtxt, dtxt);
    }
    hy_axes ax = {.series = sr, .nseries = ns, .xlabel = s->which == 1 ? "u_\\gamma" : "u",
                  .ylabel = "y", .title = title, .y = {s->ylo, s->yhi, 0, 0}, .legend = HY_LEGEND_BEST};
    hy_figure fig = one_panel(f, &ax);
    int st = hy_figure_draw_layers(&fig, &f->data, &f->overlay, err);
    if (!st && s->which == 1)
        colour_bar(f, &fig, 0.05, 0.95, "colour of y_\\gamma: time", "t = 0", "t = 4T");
    return st;
}

static int sweep1_prepare(void **st, const hy_anim_params *p, hy_error *e) { return sweep_prepare(st, p, 1, e); }
static int sweep2_prepare(void **st, const hy_anim_params *p, hy_error *e) { return sweep_prepare(st, p, 2, e); }
static int sweep3_prepare(void **st, const hy_anim_params *p, hy_error *e) { return sweep_prepare(st, p, 3, e); }

static const char *sweep_describe(void *state)
{
    sweep *s = state;
    snprintf(s->desc, sizeof s->desc, "%ld solves (one per distinct gamma), %ld frames reused a cached solve",
             s->solves, s->hits);
    return s->desc;
}

long anim_scene_solves(void *state) { return ((sweep *)state)->solves; }

/* ---- k-cycle (b): y*_u drawing itself, approaching y°_u ---- */

#define KMAX_PTS (NPTS * 8)

typedef struct kcycle {
    sweep base;               /* first member: anim_scene_solves and describe work on it */
    int which, kmax;
    double ylo, yhi;
    double u[KMAX_PTS], y[KMAX_PTS], dist[8];
} kcycle;

static int kcycle_prepare(void **state, const hy_anim_params *p, int which, hy_error *err)
{
    (void)p;
    kcycle *k = calloc(1, sizeof *k);
    if (!k)
        return hy_error_set(err, HY_ENOMEM, "out of memory preparing the animation");
    pthread_mutex_init(&k->base.mu, NULL);
    pthread_cond_init(&k->base.cv, NULL);
    int st = example_init(&k->base.ex, which, err);
    if (st) {
        sweep_release(k);
        return st;
    }
    k->which = which, k->kmax = which == 2 ? 8 : 4;
    const hy_input *in = &k->base.ex.in;
    size_t per = KMAX_PTS / (size_t)k->kmax;
    for (int c = 0; c < k->kmax; c++) {
        k->dist[c] = 0;
        for (size_t j = 0; j < per; j++) {
            double t = in->period * (double)j / (double)(per - 1);
            size_t i = (size_t)c * per + j;
            k->u[i] = hy_input_u(in, t);
            k->y[i] = hy_ystar_k(&k->base.ex.st, k->base.ex.m.x0, c, t);
            k->dist[c] = fmax(k->dist[c], fabs(k->y[i] - hy_steady_at(&k->base.ex.st, t)));
        }
    }
    hy_steady_sample(&k->base.ex.st, NPTS, k->base.uss, k->base.yss);
    k->ylo = INFINITY, k->yhi = -INFINITY;
    extent(k->y, KMAX_PTS, &k->ylo, &k->yhi);
    extent(k->base.yss, NPTS, &k->ylo, &k->yhi);
    double pad = 0.06 * (k->yhi - k->ylo);
    k->ylo -= pad, k->yhi += pad;
    *state = k;
    return HY_OK;
}

static int kcycle_draw(void *state, const hy_anim_frame *f, hy_error *err)
{
    kcycle *k = state;
    size_t per = KMAX_PTS / (size_t)k->kmax;
    double pos = hy_ease(HY_EASE_LINEAR, f->progress) * (double)(KMAX_PTS - 1);
    size_t n = (size_t)pos + 1, head = n - 1;
    int c = (int)(head / per);
    /* the trail: the last 1.5 cycles, fading with age */
    size_t tail = (size_t)(1.5 * (double)per), start = n > tail ? n - tail : 0;
    hy_gl_effect e = {key_rgb, HY_CMAP_VIRIDIS, 0.15 + 0.8 * (double)start / KMAX_PTS,
                      0.15 + 0.8 * (double)head / KMAX_PTS, 0.0};
    if (hy_gl_set_effect(f->gl, &e, err))
        return HY_EINVAL;
    /* the legend's swatch: the trail's colour at its head, from the map the
       trail and the colour bar use (a sample of no points: legend only) */
    hy_series sr[3] = {
        {.x = k->base.uss, .y = k->base.yss, .n = NPTS, .colour = {.palette = 0}, .width = 1.2,
         .label = "y^\\circ_u"},
        {.x = k->u + start, .y = k->y + start, .n = n - start, .colour = {.palette = HY_RGB_EXPLICIT, .rgb = key_rgb},
         .width = 2.6},
        {.x = k->u, .y = k->y, .n = 0, .colour = {.palette = HY_RGB_EXPLICIT, .rgb = hy_cmap(HY_CMAP_VIRIDIS, e.t1)},
         .width = 2.6, .label = "y^*_{u,k} (trail, colour: k)"},
    };
    hy_mark mk = {k->u[head], k->y[head], HY_MARKER_CIRCLE, 7, 1, {.palette = 6}};
    char title[160];
    snprintf(title, sizeof title, "Example %d:  k = %d   \\|y^*_{u,k} - y^\\circ_u\\|_\\infty = %.3g",
             k->which, c, k->dist[c]);
    hy_axes ax = {.series = sr, .nseries = 3, .marks = &mk, .nmarks = 1, .xlabel = "u", .ylabel = "y",
                  .title = title, .y = {k->ylo, k->yhi, 0, 0}, .legend = HY_LEGEND_BEST};
    hy_figure fig = one_panel(f, &ax);
    int st = hy_figure_draw_layers(&fig, &f->data, &f->overlay, err);
    if (!st) {   /* the trail's colour is the cycle index: 0.15 + 0.8 k / kmax of viridis */
        char right[32];
        snprintf(right, sizeof right, "k = %d", k->kmax);
        colour_bar(f, &fig, 0.15, 0.95, "colour of the trail: cycle k", "k = 0", right);
    }
    return st;
}

static int kcycle2_prepare(void **st, const hy_anim_params *p, hy_error *e) { return kcycle_prepare(st, p, 2, e); }
static int kcycle3_prepare(void **st, const hy_anim_params *p, hy_error *e) { return kcycle_prepare(st, p, 3, e); }

static const char *kcycle_describe(void *state)
{
    kcycle *k = state;
    snprintf(k->base.desc, sizeof k->base.desc, "%d cycles of y*_u computed once (exact), 0 ODE solves",
             k->kmax);
    return k->base.desc;
}

/* ---- Example 4 (c): the minor loop under σ0 and u_min,2 ---- */

typedef struct ex4 {
    sweep base;               /* only its counters and lock are used */
    hy_key ks[4], ku[4];
    hy_track sigma, umin2;
} ex4;

static int ex4_prepare(void **state, const hy_anim_params *p, hy_error *err)
{
    ex4 *x = calloc(1, sizeof *x);
    if (!x)
        return hy_error_set(err, HY_ENOMEM, "out of memory preparing the animation");
    pthread_mutex_init(&x->base.mu, NULL);
    pthread_cond_init(&x->base.cv, NULL);
    double D = p->duration;
    /* Fig. 17 (σ0 1, u_min,2 0.2) -> Fig. 16 (σ0 1, 0.5) -> Fig. 15 (σ0 6, 0.5) */
    x->ku[0] = (hy_key){0.10 * D, 0.2, 0}, x->ku[1] = (hy_key){0.40 * D, 0.5, HY_EASE_SMOOTH};
    x->ks[0] = (hy_key){0.55 * D, 1.0, 0}, x->ks[1] = (hy_key){0.90 * D, 6.0, HY_EASE_SMOOTH};
    x->umin2 = (hy_track){x->ku, 2, 0};
    x->sigma = (hy_track){x->ks, 2, 1};
    *state = x;
    return HY_OK;
}

typedef struct ex4_curves {
    double u[NPTS], y[NPTS], mu[NPTS], my[NPTS];
    hy_loops L;
    double sigma0, umin2;
} ex4_curves;

static int ex4_compute(ex4_curves *c, hy_error *err)
{
    hy_model m;
    hy_input in;
    hy_steady st;
    hy_model_lugre_init(&m, c->sigma0, 1, 1, 2, 1, 1);
    int s = hy_input_bimodal(&in, 0, c->umin2, 1, 1.5, NULL, HY_SHAPE_LINEAR, err);
    if (s)
        return s;
    if ((s = hy_steady_init(&st, &m, &in, err))) {
        hy_input_free(&in);
        return s;
    }
    hy_steady_sample(&st, NPTS, c->u, c->y);
    s = hy_loops_find(&st, &c->L, err);
    if (!s && c->L.nminor) {
        const hy_loop *lp = &c->L.minor[0];
        for (size_t i = 0; i < NPTS; i++) {
            double r = lp->rho_start + (lp->rho_close - lp->rho_start) * (double)i / (NPTS - 1);
            c->mu[i] = hy_input_psi(&in, r);
            c->my[i] = hy_steady_at_rho(&st, r);
        }
    }
    hy_steady_free(&st);
    hy_input_free(&in);
    return s;
}

static int ex4_draw(void *state, const hy_anim_frame *f, hy_error *err)
{
    ex4 *x = state;
    ex4_curves *c = malloc(sizeof *c);
    if (!c)
        return hy_error_set(err, HY_ENOMEM, "out of memory");
    c->sigma0 = hy_track_eval(&x->sigma, f->time), c->umin2 = hy_track_eval(&x->umin2, f->time);
    int st = ex4_compute(c, err);
    if (st) {
        free(c);
        return st;
    }
    int has = c->L.nminor > 0;
    const hy_loop *lp = has ? &c->L.minor[0] : NULL;
    hy_series sr[2] = {
        {.x = c->u, .y = c->y, .n = NPTS, .style = HY_LINE_DASHED, .colour = {.palette = 0}, .width = 1.2,
         .label = "G^\\circ_u"},
        {.x = c->mu, .y = c->my, .n = has ? NPTS : 0, .colour = {.palette = 6}, .width = 2.6,
         .label = "minor loop"},
    };
    hy_mark mk[2] = {{has ? lp->u_start : 0, has ? lp->y_start : 0, HY_MARKER_CIRCLE, 8, 0, {.palette = 5}},
                     {has ? lp->u_start : 0, has ? lp->y_close : 0, HY_MARKER_SQUARE, 8, 0, {.palette = 5}}};
    char title[200];
    char area[48], major[48];
    hy_markup_number(area, sizeof area, has ? lp->area : 0.0, 3);
    hy_markup_number(major, sizeof major, c->L.major.area, 3);
    snprintf(title, sizeof title, "Example 4:  \\sigma_0 = %.2f   u_{min,2} = %.3f   minor-loop area %s"
             "   (major %s)", c->sigma0, c->umin2, area, major);
    hy_axes ax = {.series = sr, .nseries = 2, .marks = mk, .nmarks = has ? 2 : 0, .xlabel = "u",
                  .ylabel = "y^\\circ_u", .title = title, .x = {-0.05, 1.55, 0, 0}, .y = {-2.2, 2.2, 0, 0},
                  .legend = HY_LEGEND_BEST};
    if (has) {   /* an inset that follows the minor loop (a thick line at full scale when σ0 is small) */
        double xlo = INFINITY, xhi = -INFINITY, ylo = INFINITY, yhi = -INFINITY;
        extent(c->mu, NPTS, &xlo, &xhi);
        extent(c->my, NPTS, &ylo, &yhi);
        double px = 0.12 * (xhi - xlo) + 1e-3, py = 0.12 * (yhi - ylo) + 1e-3;
        ax.zoom_x = (hy_range){xlo - px, xhi + px, 0, 0};
        ax.zoom_y = (hy_range){ylo - py, yhi + py, 0, 0};
    }
    hy_figure fig = one_panel(f, &ax);
    st = hy_figure_draw_layers(&fig, &f->data, &f->overlay, err);
    hy_loops_free(&c->L);
    free(c);
    return st;
}

static const char *ex4_describe(void *state)
{
    ex4 *x = state;
    snprintf(x->base.desc, sizeof x->base.desc, "closed form (Theorem A) per frame, 0 ODE solves");
    return x->base.desc;
}

/* ---- the list ---- */

static const anim_scene scenes[] = {
    {HY_ANIM_GAMMA_SWEEP_EX1, "Example 1 (Fig. 4): Dahl + filter, sine input, y_gamma vs u as gamma goes 1 -> 1000 (GSL)",
     6.0, sweep1_prepare, sweep_draw, sweep_describe, sweep_release},
    {HY_ANIM_GAMMA_SWEEP_EX2, "Example 2 (Figs. 7, 9): LuGre, triangle input, y_gamma onto y*_u as gamma goes 1 -> 1000",
     6.0, sweep2_prepare, sweep_draw, sweep_describe, sweep_release},
    {HY_ANIM_GAMMA_SWEEP_EX3, "Example 3 (Fig. 11): LuGre, bimodal input, y_gamma onto y*_u as gamma goes 1 -> 1000",
     6.0, sweep3_prepare, sweep_draw, sweep_describe, sweep_release},
    {HY_ANIM_K_CYCLE_EX2, "Example 2 (Figs. 8, 9): y*_u cycle by cycle converging onto the loop y°_u",
     6.0, kcycle2_prepare, kcycle_draw, kcycle_describe, sweep_release},
    {HY_ANIM_K_CYCLE_EX3, "Example 3 (Figs. 12, 13): y*_u cycle by cycle converging onto the loop y°_u",
     6.0, kcycle3_prepare, kcycle_draw, kcycle_describe, sweep_release},
    {HY_ANIM_MINOR_LOOP_EX4, "Example 4 (Figs. 15-17): the minor loop as sigma0 goes 1 -> 6 and u_min,2 0.2 -> 0.5",
     6.0, ex4_prepare, ex4_draw, ex4_describe, sweep_release},
    {HY_ANIM_PREISACH_PLANE, "Preisach model, Fig. 2's input: the (alpha, beta) plane's staircase memory beside the loop",
     8.0, pplane_prepare, pplane_draw, pplane_describe, pplane_release},
};
_Static_assert(sizeof scenes / sizeof scenes[0] == HY_ANIM_NBUILTIN, "anim_names.h names every built-in animation");

const anim_scene *const *anim_scene_list(void)
{
    static const anim_scene *list[sizeof scenes / sizeof scenes[0] + 1];
    for (size_t i = 0; i < sizeof scenes / sizeof scenes[0]; i++)
        list[i] = &scenes[i];
    return list;
}

const anim_scene *anim_scene_find(const char *name)
{
    for (size_t i = 0; name && i < sizeof scenes / sizeof scenes[0]; i++)
        if (!strcmp(scenes[i].name, name))
            return &scenes[i];
    return NULL;
}
