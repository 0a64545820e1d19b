/* SPDX-License-Identifier: MIT */
/* scene_rateind.c: the scene stages of every rate-independent model in the
 * table (Jiles-Atherton, Preisach): load, work estimate, compute.
 *
 * Such a model's output depends on the input's path only, so y_γ = y* for
 * every γ (seed 000, Theorem 2 holds trivially) and each series is the model
 * driven through the input's extrema (hy_rateind_sample, exact for every
 * hy_input): ystar, ygamma and transient from the initial state over the
 * time span, yk over period k, ysteady over one period of the periodic state
 * (periods driven until the output repeats, hy_rateind_settle), and the major
 * and minor loops of the rainflow pairing (hy_loops_pair, the finder of the
 * friction models) along ϱ from that state.  Loop areas are ∮ u dy (or ∮ y du
 * for HY_RI_AREA_YDU models, so that dissipation is > 0): from the path
 * integral ∫ y du the model tracks (HY_RI_PATH_AREA), else from its
 * closed-form loop area where minor loops close (HY_RI_RETURN_POINT). */
#include "hy_cost.h"
#include "hy_os.h"
#include "scene_model.h"
#include "scene_run.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>


#define SETTLE_TOL 1e-12    /* relative change of y per period counted as periodic */
#define SETTLE_MAX 5000     /* periods driven at most before refusing              */

/* Series a rate-independent model draws; gamma is not needed (y_γ = y*). */
static int check_series(const hy_scene_run *r, hy_error *err)
{
    for (size_t i = 0; i < r->doc.nseries; i++) { /* yk's k: checked by decode */
        const hy_decl_series *ds = &r->doc.series[i];
        int d = -1;
        if (hy_scene_series_data(ds, &d))
            return hy_decl_error(&ds->h, HY_DECL_HEAD, err, HY_EINVAL,
                                 "series '%s' needs 'data = ...' (input, psi, ystar, ysteady, ygamma, yk, "
                                 "transient, minor, major)", ds->h.name);
    }
    return HY_OK;
}

int hy_scene_rateind_load(hy_scene_run *r, hy_error *err)
{
    int rc = HY_OK; /* what the model does not accept: refused before (hy_scene_model_accepts) */
    if (!(r->ri_par = calloc(1, r->mtype->ri_par_size)))
        rc = hy_error_set(err, HY_ENOMEM, "out of memory");
    if (!rc)
        rc = hy_scene_model_read(r->mtype, r->scene, &r->doc.model, r->ri_par, err);
    if (!rc)
        rc = hy_scene_run_build_input(r, err);
    if (!rc)
        rc = check_series(r, err);
    return rc;
}

/* The cost kind of a rate-independent model's moves (hy_cost.h): its table
 * entry's column. */
static int move_kind(const hy_scene_model *mt)
{
    return mt->cost_move;
}

/* The turning points find_loops feeds the model to measure every loop,
 * from the input's extrema alone (no model evaluated, O(nruns)): the
 * memory stack of the extrema over two periods, where an extremum wipes
 * out each pair of earlier ones whose range it covers (a loop closes);
 * measure_loop feeds the runs from the period's start to a loop's close,
 * so a loop costs its close's index.  1,200 nested extrema close all their
 * 600 loops at the period's end: 600 x 1,200 moves (issue 36 item 1). */
static double loop_feeds(const hy_input *in)
{
    size_t n = in->nruns, top = 0;
    double *s = malloc((2 * n + 2) * sizeof *s), feeds = (double)n; /* the major loop: one period */
    size_t *at = malloc((2 * n + 2) * sizeof *at);
    if (!s || !at) { /* no memory for the profile: the worst case, every loop at the period's end */
        free(s);
        free(at);
        return (double)n * (double)n;
    }
    s[top] = n ? in->runs[0].u0 : 0, at[top++] = 0;
    for (size_t j = 0; j < 2 * n; j++) {
        double v = in->runs[j % n].u1;
        while (top >= 2 && fabs(v - s[top - 1]) >= fabs(s[top - 1] - s[top - 2])) {
            if (top == 2) { /* the start is not a loop's: the first reversal takes its place */
                s[0] = s[1], at[0] = at[1], top = 1;
                break;
            }
            if (at[top - 2] < n) /* a loop opened in the first period closes at j */
                feeds += (double)(j + 1);
            top -= 2;
        }
        s[top] = v, at[top++] = j + 1;
    }
    free(s);
    free(at);
    return feeds;
}

/* Model moves before computing (as the friction models count points): each
 * series' samples (the grid, one period, or one period per loop drawn, each
 * from the periodic state through the input's runs); the settling periods
 * and the loops' turning points (loop_feeds) where loops are measured. */
int hy_scene_rateind_estimate(const hy_scene_run *r, double *work, char *what, size_t size, hy_error *err)
{
    double t0, t1;
    size_t npts, per, ns = r->doc.nseries, na = r->doc.nannotation;
    long cycles;
    int rc = hy_scene_run_grid(r, &t0, &t1, &npts, &per, &cycles, err);
    if (rc)
        return rc;
    double nruns = (double)r->input.nruns, loops = fmin(64.0, fmax(1.0, nruns)), sum = 0, history = 0;
    int need_loops = 0;
    for (size_t i = 0; i < ns; i++) {
        int d = HY_DATA_INPUT;
        hy_scene_series_data(&r->doc.series[i], &d);
        need_loops |= d == HY_DATA_MINOR || d == HY_DATA_MAJOR;
        sum += d == HY_DATA_MINOR || d == HY_DATA_MAJOR ? ((double)per + 1 + nruns) * loops
               : d == HY_DATA_YSTEADY || d == HY_DATA_YK || d == HY_DATA_PSI ? (double)per + 1
                                                                               : (double)npts;
    }
    for (size_t i = 0; i < na; i++)
        need_loops |= r->doc.annotation[i].text && hy_scene_text_has_placeholder(r->doc.annotation[i].text);
    if (need_loops)
        history = 2 * nruns + loop_feeds(&r->input); /* settling (return-point memory: a period or two) */
    *work = hy_cost(r->cost_counts, move_kind(r->mtype), sum + history) +
            hy_cost(r->cost_counts, HY_COST_ANNOTATION, (double)na);
    if (what && size)
        snprintf(what, size, "%zu series of a %s model over %zu points (%zu per period), %.0f moves measuring loops "
                 "of %zu extrema, %zu annotations", ns, r->mtype->name, npts, per, history, r->input.nruns, na);
    return HY_OK;
}

/* ---- compute ------------------------------------------------------------ */

typedef struct ri_plan {
    hy_rateind init;     /* the model at u(0), t = 0                 */
    hy_rateind steady;   /* the periodic state at a period's start    */
    int have_init, have_steady;
    double t0, t1;
    size_t npts, per;
    long cycles;
} ri_plan;

static int quantity_of(const hy_scene_run *r, const hy_decl_series *ds)
{
    const char *q = hy_decl_enum_text(&ds->h, offsetof(hy_decl_series, quantity), ds->quantity);
    for (int i = 0; r->mtype->quantities[i]; i++)
        if (!strcmp(r->mtype->quantities[i], q))
            return i;
    return 0;
}

/* Samples model m (cloned, m unchanged) at x[0..n-1]: rows[q] only. */
static int sample_from(const hy_rateind *m, const hy_input *in, int by_rho, const double *x, size_t n, int q,
                       double *y, double *iy, hy_error *err)
{
    hy_rateind c;
    int rc = hy_rateind_clone(&c, m, err);
    if (rc)
        return rc;
    double *rows[HY_RI_NOUT] = {NULL, NULL, NULL};
    rows[q] = y;
    if (iy)
        rows[2] = iy;
    rc = hy_rateind_sample(&c, in, by_rho, x, n, rows, err);
    hy_rateind_free(&c);
    return rc;
}

/* Re-raises a model error in compute at the [model] key it names. */
static int at_model(const hy_scene_run *r, int rc, hy_error *err)
{
    return hy_scene_model_relocate(&r->doc.model, r->mtype, rc, err);
}

static int need_steady_state(hy_scene_run *r, ri_plan *p, hy_error *err)
{
    if (p->have_steady)
        return HY_OK;
    int rc = hy_rateind_clone(&p->steady, &p->init, err);
    if (rc)
        return rc;
    p->have_steady = 1;
    return at_model(r, hy_rateind_settle(&p->steady, &r->input, SETTLE_TOL, SETTLE_MAX, &r->ri_periods, err), err);
}

/* ∮ u dy = -∮ y du (magnetic), or ∮ y du (HY_RI_AREA_YDU): dissipation > 0. */
static double area_sign(const hy_scene_run *r)
{
    return hy_scene_model_area_sign(r->mtype);
}

/* Feeds m the turning points of the input (run ends, exact values) from run
 * *r of period *k on, while their ϱ is below limit by more than 1e-9 ρ_T. */
static int feed_ends(hy_rateind *m, const hy_input *in, size_t *r, double *k, double limit, hy_error *err)
{
    for (;;) {
        double end = *k * in->rho_T + in->runs[*r].rho1;
        if (!(end < limit - 1e-9 * in->rho_T))
            return HY_OK;
        int rc = hy_rateind_apply(m, in->runs[*r].u1, err);
        if (rc)
            return rc;
        if (++*r == in->nruns) {
            *r = 0;
            *k += 1;
        }
    }
}

/* A loop's y at its ends and its area ∮ u dy, from the periodic state: the
 * path through the turning points to u_start, then on to where it returns
 * to u_start, fed as the exact value u_start (not ψ at a computed ϱ, which
 * may miss it by an ulp), so a model with return-point memory closes bit
 * for bit. */
static int measure_loop(hy_scene_run *r, ri_plan *p, hy_loop *L, hy_error *err)
{
    hy_rateind c;
    int rc = hy_rateind_clone(&c, &p->steady, err);
    if (rc)
        return rc;
    size_t run = 0;
    double k = 0, iy0 = 0;
    if (!(rc = feed_ends(&c, &r->input, &run, &k, L->rho_start, err)) &&
        !(rc = hy_rateind_apply(&c, L->u_start, err))) {
        L->y_start = c.out[0];
        iy0 = c.out[2];
    }
    if (!rc && !(rc = feed_ends(&c, &r->input, &run, &k, L->rho_close, err)) &&
        !(rc = hy_rateind_apply(&c, L->u_start, err)))
        L->y_close = c.out[0];
    if (!rc && (r->mtype->ri->caps & HY_RI_PATH_AREA)) /* the chord u = u_start closes a loop that does not */
        L->area = area_sign(r) * (c.out[2] - iy0);
    else if (!rc)
        rc = r->mtype->ri->loop_area(r->ri_par, fmin(L->u_start, L->u_turn), fmax(L->u_start, L->u_turn), &L->area,
                                     err); /* own area, nested loops added by add_nested */
    hy_rateind_free(&c);
    return at_model(r, rc, err);
}

static int inside(const hy_loop *M, const hy_loop *L, double rT)
{
    return (M->rho_start >= L->rho_start && M->rho_close <= L->rho_close) ||
           (M->rho_start + rT >= L->rho_start && M->rho_close + rT <= L->rho_close);
}

/* Closed-form areas are each loop's own: a loop's path also goes round every
 * loop nested in it (which all close: return-point memory). */
static void add_nested(hy_loops *L, double rT)
{
    double *own = malloc((L->nminor ? L->nminor : 1) * sizeof *own);
    if (!own)
        return;
    for (size_t i = 0; i < L->nminor; i++)
        own[i] = L->minor[i].area;
    for (size_t i = 0; i < L->nminor; i++) {
        L->major.area += own[i];
        for (size_t j = 0; j < L->nminor; j++)
            if (j != i && L->minor[j].depth > L->minor[i].depth && inside(&L->minor[j], &L->minor[i], rT))
                L->minor[i].area += own[j];
    }
    free(own);
}

static int find_loops(hy_scene_run *r, ri_plan *p, hy_error *err)
{
    int rc = hy_loops_pair(&r->input, &r->loops, err);
    if (rc)
        return rc;
    r->have_loops = 1;
    if ((rc = hy_loops_nest(&r->loops, err))) /* depths, for add_nested */
        return rc;
    rc = measure_loop(r, p, &r->loops.major, err);
    for (size_t i = 0; !rc && i < r->loops.nminor; i++)
        rc = measure_loop(r, p, &r->loops.minor[i], err);
    if (rc)
        return rc;
    if (r->mtype->ri->caps & HY_RI_PATH_AREA) { /* one period through its turning points */
        hy_rateind c;
        if ((rc = hy_rateind_clone(&c, &p->steady, err)))
            return rc;
        for (size_t i = 0; !rc && i < r->input.nruns; i++)
            rc = hy_rateind_apply(&c, r->input.runs[i].u1, err);
        double iy1 = c.out[2];
        hy_rateind_free(&c);
        if (rc)
            return at_model(r, rc, err);
        r->loops.area_period = area_sign(r) * (iy1 - p->steady.out[2]);
    } else {
        add_nested(&r->loops, r->input.rho_T);
        r->loops.area_period = r->loops.major.area;
    }
    return hy_loops_nest(&r->loops, err);
}

/* n points evenly over [a, b] into x. */
static void spread(double *x, size_t n, double a, double b)
{
    for (size_t i = 0; i < n; i++)
        x[i] = n > 1 ? a + (b - a) * (double)i / (double)(n - 1) : a;
}

/* The loop series: each interval from the periodic state, sampled along ϱ,
 * drawn against ψ_u (NaN between intervals). */
static int loop_series(hy_scene_run *r, ri_plan *p, hy_run_series *se, int q, hy_error *err)
{
    double a[64], b[64];
    int k = hy_scene_loop_intervals(r, se->data == HY_DATA_MAJOR, a, b, 64);
    if (k < 0)
        return hy_scene_too_narrow(r, err);
    size_t per = p->per, total = (size_t)k * (per + 1);
    int rc = hy_run_series_alloc(se, total ? total : 1, err);
    se->n = total;
    for (int i = 0; !rc && i < k; i++) {
        double *x = se->x + (size_t)i * (per + 1), *y = se->y + (size_t)i * (per + 1);
        spread(x, per, a[i], b[i]);
        rc = at_model(r, sample_from(&p->steady, &r->input, 1, x, per, q, y, NULL, err), err);
        for (size_t j = 0; j < per; j++)
            x[j] = hy_input_psi(&r->input, x[j]);
        x[per] = y[per] = NAN; /* gap */
    }
    return rc;
}

static int compute_series(hy_scene_run *r, ri_plan *p, hy_run_series *se, hy_error *err)
{
    const hy_input *in = &r->input;
    int q = quantity_of(r, se->decl), loopfig = r->figure_kind == FIG_LOOP, rc = HY_OK;
    double T = in->period, t0 = hy_now();
    se->err = se->dist = NAN;
    if (r->numbers_only || se->data == HY_DATA_MEASURED || se->data == HY_DATA_MODELLED)
        return HY_OK; /* the sweep's table: loops only (computed in the plan); data series: scene_data.c */
    if (se->data == HY_DATA_MINOR || se->data == HY_DATA_MAJOR)
        rc = loop_series(r, p, se, q, err);
    else if (se->data == HY_DATA_PSI) {
        if (!(rc = hy_run_series_alloc(se, p->per + 1, err)))
            for (size_t i = 0; i <= p->per; i++) {
                se->x[i] = in->rho_T * (double)i / (double)p->per;
                se->y[i] = hy_input_psi(in, se->x[i]);
            }
    } else if (se->data == HY_DATA_INPUT) {
        if (!(rc = hy_run_series_alloc(se, p->npts, err)))
            for (size_t i = 0; i < p->npts; i++) {
                se->x[i] = p->t0 + (p->t1 - p->t0) * (double)i / (double)(p->npts - 1);
                se->y[i] = hy_input_u(in, se->x[i]);
            }
    } else {
        /* ysteady: one period of the periodic state; yk: period k from the
           initial state; ystar, ygamma, transient: the time span from it */
        int steady = se->data == HY_DATA_YSTEADY, yk = se->data == HY_DATA_YK;
        size_t n = steady || yk ? p->per + 1 : p->npts;
        double a = steady || yk ? 0 : p->t0, b = steady || yk ? T : p->t1, shift = yk ? (double)se->k * T : 0;
        if ((rc = hy_run_series_alloc(se, n, err)))
            return rc;
        spread(se->x, n, a + shift, b + shift);
        rc = at_model(r, sample_from(steady ? &p->steady : &p->init, in, 0, se->x, n, q, se->y, NULL, err), err);
        for (size_t i = 0; i < n; i++)
            se->x[i] = loopfig ? hy_input_u(in, se->x[i]) : se->x[i] - shift;
    }
    double at = se->decl->at;
    if (!rc && hy_decl_got(&se->decl->h, offsetof(hy_decl_series, at)) == HY_SCENE_SET) {
        int by_rho = se->data == HY_DATA_MINOR || se->data == HY_DATA_MAJOR || se->data == HY_DATA_PSI;
        int from_steady = by_rho || se->data == HY_DATA_YSTEADY;
        double x = at + (se->data == HY_DATA_YK ? (double)se->k * T : 0);
        se->has_mark = 1;
        se->mark_x = !loopfig ? at : by_rho ? hy_input_psi(in, at) : hy_input_u(in, at);
        if (se->data == HY_DATA_INPUT)
            se->mark_y = hy_input_u(in, at);
        else if (se->data == HY_DATA_PSI)
            se->mark_y = hy_input_psi(in, at);
        else if (!(at >= 0))
            rc = hy_decl_error(&se->decl->h, offsetof(hy_decl_series, at), err, HY_EINVAL,
                               "'at' is a time or variation >= 0 for a %s model, got %g", r->mtype->name, at);
        else
            rc = at_model(r, sample_from(from_steady ? &p->steady : &p->init, in, by_rho, &x, 1, q, &se->mark_y,
                                         NULL, err), err);
    }
    se->seconds = hy_now() - t0;
    return rc;
}

static void log_run(const hy_scene_run *r, const ri_plan *p, FILE *log)
{
    fprintf(log, "%s: plan\n  %s model driven through the input's extrema (rate-independent: y_gamma = y*)\n",
            r->path, r->mtype->name);
    if (p->have_steady)
        fprintf(log, "  periodic after %d periods (output change <= %g of its range)\n", r->ri_periods, SETTLE_TOL);
    for (size_t i = 0; i < r->nseries; i++)
        if (hy_scene_series_log(&r->series[i], log))
            fputc('\n', log);
    if (r->have_loops)
        fprintf(log, "  %zu minor loops; energy per cycle %.10g\n", r->loops.nminor, r->loops.area_period);
    fprintf(log, "  compute total %.3f ms (work estimate %.3g)\n", 1e3 * r->seconds_compute, r->work);
}

int hy_scene_rateind_compute(hy_scene_run *r, FILE *log, hy_error *err)
{
    double t_start = hy_now();
    ri_plan p;
    memset(&p, 0, sizeof p);
    int rc = hy_scene_run_series_new(r, err);
    if (rc)
        return rc;
    size_t ns = r->nseries;
    rc = hy_scene_run_grid(r, &p.t0, &p.t1, &p.npts, &p.per, &p.cycles, err);
    int need_steady = 0, need_loops = 0;
    for (size_t i = 0; i < ns && !rc; i++) {
        hy_run_series *se = &r->series[i];
        need_steady |= se->data == HY_DATA_YSTEADY || se->data == HY_DATA_MINOR || se->data == HY_DATA_MAJOR;
        need_loops |= se->data == HY_DATA_MINOR || se->data == HY_DATA_MAJOR;
        rc = hy_scene_check_series_kind(r, se, err);
    }
    for (size_t i = 0; i < r->doc.nannotation; i++)
        if (r->doc.annotation[i].text && hy_scene_text_has_placeholder(r->doc.annotation[i].text))
            need_steady = need_loops = 1;
    if (!rc) {
        rc = at_model(r, hy_rateind_alloc(&p.init, r->mtype->ri, r->ri_par, hy_input_u(&r->input, 0), err), err);
        p.have_init = !rc;
        p.init.cancel = hy_scene_run_cancel_hook(r); /* its clones too: every move inside a series (a model's
                                                         own steps: its compute stage, as model_jiles.c's) */
    }
    if (!rc && need_steady)
        rc = need_steady_state(r, &p, err);
    if (!rc && need_loops)
        rc = find_loops(r, &p, err);
    for (size_t i = 0; i < ns && !rc; i++)
        rc = compute_series(r, &p, &r->series[i], err);
    r->seconds_compute = hy_now() - t_start;
    if (!rc && log)
        log_run(r, &p, log);
    if (p.have_steady)
        hy_rateind_free(&p.steady);
    if (p.have_init)
        hy_rateind_free(&p.init);
    return rc;
}
