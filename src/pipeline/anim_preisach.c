/* SPDX-License-Identifier: MIT */
/* anim_preisach.c: the animation preisach-plane (anim_preisach.h).  Left, the
 * relay plane α >= β drawn by the GL pass hy_gl_draw_plane (one fragment per
 * relay: its state from the memory, its shade from the density); over it the
 * staircase of the memory, stroked from the memory's extrema exactly, and the
 * present input on the diagonal.  Right, the loop u -> y traced so far.
 * Every frame is computed from the model alone (no state between frames):
 * frames are the same for any -j. */
#include "anim_preisach.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hy_cairo.h"
#include "hy_markup.h"
#include "hy_plot.h"

#define NTRACE 1601           /* samples of the loop over the two periods */
#define PERIODS 2.0
#define MAXSTAIR (HY_GL_PLANE_MAX + 3)

/* The panel's ranges (both axes): the input's range [0, 1.5] with a margin,
 * where the density below leaves ~2e-4 of its mass outside (3.5 widths). */
static const double LO = -0.1, HI = 1.6;
#define POSTER_FONT "STIXGeneral"
static const hy_rgb UP = {0.835, 0.369, 0.0}, DOWN = {0.0, 0.447, 0.698}; /* vermillion, blue (Okabe-Ito) */

typedef struct pplane {
    hy_preisach p;
    hy_input in;
    double t[NTRACE], u[NTRACE], y[NTRACE];
    double duration;
    char desc[160];
} pplane;

int pplane_prepare(void **state, const hy_anim_params *prm, hy_error *err)
{
    pplane *s = calloc(1, sizeof *s);
    if (!s)
        return hy_error_set(err, HY_ENOMEM, "out of memory preparing the animation");
    /* Fig. 2: u_min,1 = 0, u_min,2 = 0.2, u_max,1 = 1, u_max,2 = 1.5, half-cosine pieces;
     * relays switching up around 0.9 and down around 0.6 (width 0.2): the input
     * saturates the model at both ends and its minor loop is inside */
    static const double tb[4] = {1, 2.2, 3.2, 5};
    int rc = hy_input_bimodal(&s->in, 0, 0.2, 1, 1.5, tb, HY_SHAPE_COSINE, err);
    if (rc) {
        free(s);
        return rc;
    }
    rc = hy_preisach_init(&s->p, HY_PREISACH_GAUSSIAN, 0.9, 0.2, 0.6, 0.2, 1.0, err);
    for (int i = 0; i < NTRACE; i++) {
        s->t[i] = PERIODS * s->in.period * i / (NTRACE - 1);
        s->u[i] = hy_input_u(&s->in, s->t[i]);
    }
    if (!rc)
        rc = hy_preisach_drive(&s->p, &s->in, s->t, NTRACE, s->y, err);
    if (rc) {
        pplane_release(s);
        return rc;
    }
    s->duration = prm->duration;
    *state = s;
    return HY_OK;
}

void pplane_release(void *state)
{
    pplane *s = state;
    if (!s)
        return;
    hy_input_free(&s->in);
    free(s);
}

const char *pplane_describe(void *state)
{
    pplane *s = state;
    snprintf(s->desc, sizeof s->desc, "exact staircase output per frame (Everett function), 0 ODE solves");
    return s->desc;
}

const hy_preisach *pplane_model(const void *state) { return &((const pplane *)state)->p; }

double pplane_input_time(const void *state, double time)
{
    const pplane *s = state;
    double x = s->duration > 0 ? time / s->duration : 0;
    return PERIODS * s->in.period * (x < 0 ? 0 : x > 1 ? 1 : x);
}

int pplane_memory(const void *state, double time, hy_preisach_mem *m, hy_error *err)
{
    const pplane *s = state;
    double tin = pplane_input_time(state, time);
    int rc = hy_preisach_mem_init(m, &s->p, hy_input_u(&s->in, 0), err);
    if (rc)
        return rc;
    /* every piece's end before tin (the extrema among them), then u(tin) */
    for (int k = 0; !rc && k < (int)PERIODS; k++)
        for (size_t i = 0; !rc && i < s->in.npieces; i++) {
            double tb = k * s->in.period + s->in.pieces[i].t1;
            if (tb >= tin)
                break;
            rc = hy_preisach_mem_apply(m, s->in.pieces[i].u1, NULL, err);
        }
    if (!rc)
        rc = hy_preisach_mem_apply(m, hy_input_u(&s->in, tin), NULL, err);
    if (rc)
        hy_preisach_mem_free(m);
    return rc;
}

size_t pplane_staircase(const hy_preisach_mem *m, double lo, double hi, double *beta, double *alpha, size_t cap)
{
    size_t k = 0;
    if (m->n < 1 || cap < m->n + 1)
        return 0;
    /* s[j] is a maximum when it is above s[j-1]: a horizontal step at α = s[j]
     * from the last minimum's β; a minimum: a vertical step at β = s[j] */
    int max1 = m->s[1] > m->s[0];
    beta[k] = max1 ? lo : m->s[1], alpha[k] = max1 ? m->s[1] : hi, k++;
    for (size_t j = 2; j <= m->n; j++) {
        int is_max = m->s[j] > m->s[j - 1];
        beta[k] = is_max ? m->s[j - 1] : m->s[j];
        alpha[k] = is_max ? m->s[j] : m->s[j - 1];
        k++;
    }
    beta[k] = m->s[m->n], alpha[k] = m->s[m->n], k++;
    return k;
}

/* The figure of a frame: the plane (no series: drawn by GL) and the loop. */
typedef struct frame_fig {
    hy_series sr[1];
    hy_mark mk[1];
    hy_axes ax[2];
    hy_figure fig;
    char title[200];
} frame_fig;

static void build(frame_fig *ff, const hy_anim_frame *f, const double *u, const double *y, size_t n, double un,
                  double yn, double periods)
{
    memset(ff, 0, sizeof *ff);
    ff->sr[0] = (hy_series){.x = u, .y = y, .n = n, .colour = {.palette = 0}, .width = 1.6, .label = NULL};
    ff->mk[0] = (hy_mark){un, yn, HY_MARKER_CIRCLE, 7, 1, {.palette = 6}};
    snprintf(ff->title, sizeof ff->title, "t / T = %.2f   u = %.3f   y = %+.3f", periods, un, yn);
    ff->ax[0] = (hy_axes){.xlabel = "\\beta", .ylabel = "\\alpha",
                          .title = "Preisach plane: relays up, down",
                          .x = {LO, HI, 0, 0}, .y = {LO, HI, 0, 0}, .legend = HY_LEGEND_NONE};
    ff->ax[1] = (hy_axes){.series = ff->sr, .nseries = 1, .marks = ff->mk, .nmarks = 1, .xlabel = "u",
                          .ylabel = "y", .title = ff->title, .x = {LO, HI, 0, 0}, .y = {-1.15, 1.15, 0, 0},
                          .legend = HY_LEGEND_NONE, .grid = 1};
    /* the gallery's look (scenes/style.scene): STIX at 9 pt on a 12 cm
     * figure, so the text takes the same share of the width on the index page */
    double W = f->width / f->scale;
    ff->fig = (hy_figure){.width = W, .height = f->height / f->scale, .dpi = 72 * f->scale,
                          .font = POSTER_FONT, .font_size = fmax(9.0, 9.0 * W / hy_cm(12.0)), .axes = ff->ax,
                          .nrows = 1, .ncols = 2};
}

/* The frame's overlay canvas set in the gallery's font: the overlay is cairo
 * (hy_anim.h), made with the default font; a copy of its state names STIX. */
static hy_canvas stix_overlay(const hy_anim_frame *f, hy_cairo_canvas *keep)
{
    if (!f->overlay.ops || strcmp(f->overlay.ops->name, "cairo"))
        return f->overlay;
    *keep = *(const hy_cairo_canvas *)f->overlay.ctx;
    keep->font = POSTER_FONT;
    return (hy_canvas){f->overlay.ops, keep};
}

/* The key to the plane's shading, in its empty lower-right triangle (alpha <
 * beta holds no relay): for relays up and down, a bar of the 33 shades
 * plane.frag draws (white mixed with the colour by 0.12 + 0.88 w, w the
 * density mu(alpha, beta) over its peak, in steps of 1/32), 0 to 1. */
static void draw_key(const hy_canvas *cv, const double rect[4], double fs)
{
    double kw = 0.4 * rect[2], bh = 0.75 * fs, gap = 0.5 * fs;
    double x0 = rect[0] + rect[2] - kw - 0.03 * rect[2], y1 = rect[1] + rect[3] - 0.03 * rect[3];
    double lw = 0.0;
    hy_markup_box b;
    const char *name[2] = {"up", "down"};
    for (int i = 0; i < 2; i++) {
        hy_markup_text(cv, name[i], fs, 0, 0, 0, 0, hy_palette[0], &b);
        lw = fmax(lw, b.width);
    }
    double bx = x0 + lw + gap, bw = kw - lw - gap;
    /* from the bottom: the tick labels, two bars, the heading */
    double yt = y1, yb = yt - 1.1 * fs - bh, ya = yb - gap - bh, yh = ya - 0.45 * fs;
    hy_rgb c[2] = {UP, DOWN};
    for (int i = 0; i < 2; i++) {
        double y = i ? yb : ya;
        for (int k = 0; k <= 32; k++) {
            double w = k / 32.0, m = 0.12 + 0.88 * w;
            hy_rgb s = {1 + (c[i].r - 1) * m, 1 + (c[i].g - 1) * m, 1 + (c[i].b - 1) * m};
            cv->ops->fill_rect(cv->ctx, bx + bw * k / 33.0, y, bw / 33.0 + 0.3, bh, s, 1.0);
        }
        hy_markup_text(cv, name[i], fs, 1, 0, x0, y + 0.8 * bh, hy_palette[0], NULL);
    }
    hy_pen frame = {{0.3, 0.3, 0.3}, 1, 0.5, NULL, 0, 0, 0};
    for (int i = 0; i < 2; i++) {
        double y = i ? yb : ya;
        cv->ops->begin_path(cv->ctx);
        cv->ops->move_to(cv->ctx, bx, y);
        cv->ops->line_to(cv->ctx, bx + bw, y);
        cv->ops->line_to(cv->ctx, bx + bw, y + bh);
        cv->ops->line_to(cv->ctx, bx, y + bh);
        cv->ops->line_to(cv->ctx, bx, y);
        cv->ops->stroke(cv->ctx, &frame);
    }
    hy_markup_text(cv, "0", fs, 1, 0, bx, yt, hy_palette[0], NULL);
    hy_markup_text(cv, "1", fs, 0, 0, 0, 0, hy_palette[0], &b);
    hy_markup_text(cv, "1", fs, 1, 0, bx + bw - b.width, yt, hy_palette[0], NULL);
    const char *head = "density \\mu / \\mu_{max}";
    hy_markup_text(cv, head, fs, 0, 0, 0, 0, hy_palette[0], &b);
    hy_markup_text(cv, head, fs, 1, 0, x0 + kw - b.width, yh, hy_palette[0], NULL);
}

int pplane_panel(const void *state, const hy_anim_frame *f, double rect[4], double lim[4], hy_error *err)
{
    (void)state;
    frame_fig ff;
    hy_cairo_canvas keep;
    hy_canvas ov = stix_overlay(f, &keep);
    build(&ff, f, NULL, NULL, 0, 0, 0, 0);
    int rc = hy_figure_frame(&ff.fig, &ov, 0, rect, err);
    for (int i = 0; i < 4; i++)
        rect[i] *= f->scale;
    lim[0] = LO, lim[1] = HI, lim[2] = LO, lim[3] = HI;
    return rc;
}

int pplane_draw(void *state, const hy_anim_frame *f, hy_error *err)
{
    pplane *s = state;
    hy_preisach_mem m;
    int rc = pplane_memory(s, f->time, &m, err);
    if (rc)
        return rc;
    if (m.n > HY_GL_PLANE_MAX) {
        hy_preisach_mem_free(&m);
        return hy_error_set(err, HY_EINVAL, "the memory holds %zu extrema; the plane draws at most %d", m.n,
                            HY_GL_PLANE_MAX);
    }
    double tin = pplane_input_time(s, f->time), un = m.s[m.n], yn = m.y;
    size_t n = 0;
    while (n < NTRACE && s->t[n] < tin)
        n++;
    double *u = malloc((n + 1) * sizeof *u), *y = malloc((n + 1) * sizeof *y);
    if (!u || !y) {
        free(u), free(y), hy_preisach_mem_free(&m);
        return hy_error_set(err, HY_ENOMEM, "out of memory");
    }
    memcpy(u, s->u, n * sizeof *u), memcpy(y, s->y, n * sizeof *y);
    u[n] = un, y[n] = yn; /* the trace ends at the present point exactly */
    frame_fig ff;
    hy_cairo_canvas keep;
    hy_canvas ov = stix_overlay(f, &keep);
    build(&ff, f, u, y, n + 1, un, yn, tin / s->in.period);
    double rect[4];
    rc = hy_figure_draw_layers(&ff.fig, &f->data, &ov, err);
    if (!rc)
        rc = hy_figure_frame(&ff.fig, &ov, 0, rect, err);
    if (!rc)
        draw_key(&ov, rect, ff.fig.font_size);
    if (!rc) {
        double k = f->scale;
        hy_gl_plane pl = {rect[0] * k, rect[1] * k, rect[2] * k, rect[3] * k, LO, HI, LO, HI,
                          m.s, (int)m.n, m.s[0] > 0 ? 1 : -1, s->p.dist, s->p.ma, s->p.sa, s->p.mb, s->p.sb,
                          UP, DOWN};
        rc = hy_gl_draw_plane(f->gl, &pl, err);
    }
    if (!rc) { /* the diagonal α = β, the staircase, the present input on the diagonal */
        const hy_canvas *d = &f->data;
        double sx = rect[2] / (HI - LO), sy = rect[3] / (HI - LO);
#define PX(b) (rect[0] + ((b) - LO) * sx)
#define PY(a) (rect[1] + rect[3] - ((a) - LO) * sy)
        d->ops->clip(d->ctx, rect[0], rect[1], rect[2], rect[3]);
        hy_pen diag = {{0.45, 0.45, 0.45}, 1, 0.8, NULL, 0, 0, 0};
        d->ops->begin_path(d->ctx);
        d->ops->move_to(d->ctx, PX(LO), PY(LO));
        d->ops->line_to(d->ctx, PX(HI), PY(HI));
        d->ops->stroke(d->ctx, &diag);
        double sb[MAXSTAIR], sa[MAXSTAIR];
        size_t ns = pplane_staircase(&m, LO - 1, HI + 1, sb, sa, MAXSTAIR);
        hy_pen stair = {{0, 0, 0}, 1, 1.8, NULL, 0, 0, 1};
        d->ops->begin_path(d->ctx);
        for (size_t i = 0; i < ns; i++)
            (i ? d->ops->line_to : d->ops->move_to)(d->ctx, PX(sb[i]), PY(sa[i]));
        d->ops->stroke(d->ctx, &stair);
        hy_pen ring = {{0, 0, 0}, 1, 0.8, NULL, 0, 0, 0};
        hy_rgb dot = hy_palette[6];
        d->ops->marker(d->ctx, HY_SHAPE_CIRCLE, PX(un), PY(un), 7, &ring, &dot);
        d->ops->unclip(d->ctx);
#undef PX
#undef PY
    }
    free(u);
    free(y);
    hy_preisach_mem_free(&m);
    return rc;
}
