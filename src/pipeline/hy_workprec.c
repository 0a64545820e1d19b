/* SPDX-License-Identifier: MIT */
/* hy_workprec.c: work-precision runs (DiffEqDevTools conventions: L∞ and RMS
 * error on a fixed grid, median wall time) for Examples 1-3 of seed 000, the
 * stiff LuGre of Åström & Canudas de Wit (2008), the Bouc-Wen benchmark of
 * seed 001 (Newmark at several h against a fine-h reference) and the
 * Jiles-Atherton system of Fig. 1 (each GSL stepper in H against rk8pd at
 * rtol 1e-13). */
#include "hy_workprec.h"

#include "hy_gamma.h"
#include "hy_ode.h"
#include "hy_ref.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

/* Step ends kept for err_steps (16 MiB); past it, the first TRACE_CAP. */
#define TRACE_CAP ((size_t)1 << 20)

/* The named problems, one line each: X(name, init, exact), init filling the
 * problem (quick: a cheaper reference), exact 1 where the reference is then
 * the exact exponential formula (hy_wp_exact_ld). */
#define WP_NAMED(X)                  \
    X("ex1", init_ex1, 0)            \
    X("lugre-stiff", init_stiff, 1)  \
    X("boucwen", init_boucwen, 0)    \
    X("jiles", init_jiles, 0)

#define WP_NAME(name, init, exact) name,
static const char *const problem_names[] = {
    "ex2-g1", "ex2-g10", "ex2-g100", "ex2-g1e4",
    "ex3-g1", "ex3-g10", "ex3-g100", "ex3-g1e4",
    WP_NAMED(WP_NAME) NULL,
};
#undef WP_NAME

hy_wp_cfg hy_wp_cfg_defaults(void)
{
    hy_wp_cfg c = {.repeats = 5, .max_steps = 200000, .time_cap = 2.0};
    return c;
}

double hy_wp_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

void hy_wp_error(const double *y, const double *yref, size_t n, double *emax, double *el2)
{
    double mx = 0, s2 = 0;
    for (size_t i = 0; i < n; i++) {
        double e = fabs(y[i] - yref[i]);
        if (!isfinite(e)) {
            mx = s2 = INFINITY;
            break;
        }
        mx = fmax(mx, e);
        s2 += e * e;
    }
    if (emax)
        *emax = mx;
    if (el2)
        *el2 = n ? sqrt(s2 / (double)n) : 0;
}

const char *hy_wp_status_name(int status)
{
    static const char *const names[] = {"ok", "fail", "stepcap", "timecap", "skipped"};
    return status >= 0 && status <= HY_WP_SKIPPED ? names[status] : "?";
}

const char *const *hy_wp_problem_names(void)
{
    return problem_names;
}

int hy_wp_exact_ld(const hy_model *m, const hy_input *in, double gamma, const double *t, size_t n,
                   double *y, hy_error *err)
{
    return hy_ref_gamma(m, in, gamma, t, n, y, err);
}

/* Output grid of n points over [0, span], offset so no point sits on a breakpoint. */
static int grid_alloc(hy_wp_problem *p, size_t n, double span)
{
    p->n = n;
    p->t = malloc(n * sizeof *p->t);
    p->yref = malloc(n * sizeof *p->yref);
    if (!p->t || !p->yref)
        return HY_ENOMEM;
    for (size_t i = 0; i < n; i++)
        p->t[i] = span * ((double)i + 0.3711) / (double)n;
    return HY_OK;
}

/* Examples 2 and 3: LuGre σ0 = σ1 = Fc = vs = β = 1, Fs = 2; 3 periods. */
static int init_example(hy_wp_problem *p, int ex, double gamma, hy_error *err)
{
    hy_model_lugre_init(&p->model, 1, 1, 1, 2, 1, 1);
    int rc = ex == 2 ? hy_input_triangle(&p->input, 0, 1, 2, err)
                     : hy_input_bimodal(&p->input, 0, 0.2, 1, 1.5, NULL, HY_SHAPE_LINEAR, err);
    if (rc)
        return rc;
    p->gamma = gamma;
    snprintf(p->title, sizeof p->title, "Example %d, \\gamma = %g", ex, gamma);
    return grid_alloc(p, 300, 3 * p->input.period);
}

/* Stiff LuGre (Åström & Canudas de Wit 2008), 0.1 mm bimodal input at 1 mm/s. */
static int init_stiff(hy_wp_problem *p, int quick, hy_error *err)
{
    (void)quick;
    hy_model_lugre_init(&p->model, 1e5, sqrt(1e5), 1, 1.5, 1e-3, 2);
    const double tm[4] = {0.1, 0.18, 0.31, 0.46};
    int rc = hy_input_bimodal(&p->input, 0, 0.2e-4, 1e-4, 1.5e-4, tm, HY_SHAPE_LINEAR, err);
    if (rc)
        return rc;
    p->gamma = 1;
    snprintf(p->title, sizeof p->title, "stiff LuGre, \\sigma_0 = 10^5, 0.1 mm at 1 mm/s");
    return grid_alloc(p, 300, 3 * p->input.period);
}

/* Example 1: system (16), Dahl ρ = Fc = 1, τ = 1, sine input, γ = 20, 3 periods;
 * reference rk8pd at rtol 1e-14 (quick: 1e-12), checked against bsimp. */
static int init_ex1(hy_wp_problem *p, int quick, hy_error *err)
{
    hy_model_dahl_filter_init(&p->model, 1, 1, 1);
    int rc = hy_input_sine(&p->input, 1, 1, 0, err);
    if (rc)
        return rc;
    p->gamma = 20;
    snprintf(p->title, sizeof p->title, "Example 1 (Dahl + filter), \\gamma = 20");
    if ((rc = grid_alloc(p, 300, 3 * p->input.period)))
        return rc;
    hy_ode_opts o = hy_ode_defaults();
    o.stepper = "rk8pd";
    o.rtol = quick ? 1e-12 : 1e-14;
    o.atol = o.rtol * 1e-2;
    o.max_steps = 10000000;
    if ((rc = hy_ode_solve(&p->model, &p->input, p->gamma, &o, p->t, p->n, p->yref, NULL, err)))
        return rc;
    double *y2 = malloc(p->n * sizeof *y2), d = NAN;
    o.stepper = "bsimp";
    o.rtol = quick ? 1e-11 : 1e-13;
    o.atol = o.rtol * 1e-2;
    if (y2 && !hy_ode_solve(&p->model, &p->input, p->gamma, &o, p->t, p->n, y2, NULL, err))
        hy_wp_error(y2, p->yref, p->n, &d, NULL);
    free(y2);
    snprintf(p->ref_method, sizeof p->ref_method,
             "rk8pd rtol %.0e atol %.0e with restarts (bsimp rtol %.0e differs by %.1e)",
             quick ? 1e-12 : 1e-14, quick ? 1e-14 : 1e-16, quick ? 1e-11 : 1e-13, d);
    return HY_OK;
}

/* Bouc-Wen force: 100 sin(2π 5 t) + 50 sin(2π 23 t) N. */
static double bw_force(double t)
{
    return 100 * sin(2 * M_PI * 5 * t) + 50 * sin(2 * M_PI * 23 * t);
}

/* Newmark at h = span/(n-1)/2^k, sampled on the n-point grid t_j = j span/(n-1). */
static int bw_solve(const hy_wp_problem *p, double h, double *y_out, hy_error *err)
{
    double dt = p->t[1] - p->t[0];
    size_t r = (size_t)llround(dt / h), nn = (p->n - 1) * r + 1;
    double *u = malloc(nn * sizeof *u), *y = malloc(nn * sizeof *y);
    int rc = HY_ENOMEM;
    if (u && y) {
        for (size_t i = 0; i < nn; i++)
            u[i] = bw_force((double)i * h);
        hy_newmark_opts o;
        hy_newmark_opts_default(&o);
        rc = hy_boucwen_simulate(&p->bw, &o, h, u, nn, NULL, y, NULL, err);
        for (size_t j = 0; rc == HY_OK && j < p->n; j++)
            y_out[j] = y[j * r];
    } else {
        hy_error_set(err, HY_ENOMEM, "out of memory for %zu Newmark samples", nn);
    }
    free(u);
    free(y);
    return rc;
}

/* Bouc-Wen benchmark (Table 1), 0.4 s at 750 Hz; reference h = 1/(750·2^12). */
static int init_boucwen(hy_wp_problem *p, int quick, hy_error *err)
{
    p->kind = HY_WP_BOUCWEN;
    hy_boucwen_params_default(&p->bw);
    snprintf(p->title, sizeof p->title, "Bouc-Wen benchmark (Newmark), 5 + 23 Hz force");
    p->n = 301;
    p->t = malloc(p->n * sizeof *p->t);
    p->yref = malloc(p->n * sizeof *p->yref);
    if (!p->t || !p->yref)
        return hy_error_set(err, HY_ENOMEM, "out of memory");
    for (size_t j = 0; j < p->n; j++)
        p->t[j] = (double)j / 750.0;
    int k = quick ? 9 : 12;
    p->bw_h_ref = 1.0 / (750.0 * (double)(1 << k));
    snprintf(p->ref_method, sizeof p->ref_method, "Newmark at h = 1/(750*2^%d) s", k);
    return bw_solve(p, p->bw_h_ref, p->yref, err);
}

/* B of the Jiles-Atherton problem at p's grid with stepper at rtol, within
 * max_steps steps (0: the model's default budget, HY_JILES_MAX_STEPS). */
static int ja_solve(const hy_wp_problem *p, const char *stepper, double rtol, unsigned long max_steps, double *y,
                    hy_jiles_stats *st, hy_error *err)
{
    hy_jiles j = p->ja;
    j.stepper = stepper;
    j.rtol = rtol;
    j.max_steps = max_steps;
    return hy_jiles_drive(&j, &p->input, p->t, p->n, NULL, y, st, err);
}

/* Fig. 1's magnetic system (scenes/fig01_magnetic_minor_loop.scene): the
 * Jiles-Atherton parameters of 1986 driven by Fig. 2's bimodal input scaled
 * to H = 2000 u - 1500 A/m, two periods from the demagnetised state, B in
 * tesla; reference rk8pd at rtol 1e-13 (quick: 1e-11), checked against rkck. */
static int init_jiles(hy_wp_problem *p, int quick, hy_error *err)
{
    p->kind = HY_WP_JILES;
    int rc = hy_jiles_init(&p->ja, 1.6e6, 1100, 400, 0.2, 1.6e-3, err);
    const double tm[4] = {1, 2.2, 3.2, 5};
    if (rc || (rc = hy_input_bimodal(&p->input, -1500, -1100, 500, 1500, tm, HY_SHAPE_COSINE, err)))
        return rc;
    snprintf(p->title, sizeof p->title, "Jiles-Atherton (Fig. 1), B over two periods");
    if ((rc = grid_alloc(p, 300, 2 * p->input.period)))
        return hy_error_set(err, rc, "out of memory");
    double rtol = quick ? 1e-11 : 1e-13, d = NAN;
    if ((rc = ja_solve(p, "rk8pd", rtol, 0, p->yref, NULL, err)))
        return rc;
    double *y2 = malloc(p->n * sizeof *y2);
    if (y2 && !ja_solve(p, "rkck", rtol, 0, y2, NULL, err))
        hy_wp_error(y2, p->yref, p->n, &d, NULL);
    free(y2);
    snprintf(p->ref_method, sizeof p->ref_method, "rk8pd rtol %.0e, restarts at reversals and guard switches "
             "(rkck at the same rtol differs by %.1e T)", rtol, d);
    return HY_OK;
}

int hy_wp_problem_init(hy_wp_problem *p, const char *name, int quick, hy_error *err)
{
    memset(p, 0, sizeof *p);
    snprintf(p->name, sizeof p->name, "%s", name);
#define WP_ROW(name, init, exact) {name, init, exact},
    static const struct {
        const char *name;
        int (*init)(hy_wp_problem *p, int quick, hy_error *err);
        int exact;
    } named[] = {WP_NAMED(WP_ROW)};
#undef WP_ROW
    int rc;
    size_t i = 0, n = sizeof named / sizeof *named;
    while (i < n && strcmp(named[i].name, name))
        i++;
    if (!strncmp(name, "ex2-g", 5) || !strncmp(name, "ex3-g", 5)) {
        char *end;
        double g = strtod(name + 5, &end);
        if (*end || !(g > 0))
            return hy_error_set(err, HY_EINVAL, "problem '%s': bad gamma", name);
        rc = init_example(p, name[2] - '0', g, err);
    } else if (i < n) {
        rc = named[i].init(p, quick, err);
        if (!named[i].exact)
            return rc;
    } else {
        char list[128] = "ex2-gG, ex3-gG";
        for (i = 0; i < n; i++)
            snprintf(list + strlen(list), sizeof list - strlen(list), ", %s", named[i].name);
        return hy_error_set(err, HY_EINVAL, "unknown problem '%s' (%s)", name, list);
    }
    if (rc)
        return rc == HY_ENOMEM ? hy_error_set(err, rc, "out of memory") : rc;
    snprintf(p->ref_method, sizeof p->ref_method, "exact exponential formula in long double");
    return hy_wp_exact_ld(&p->model, &p->input, p->gamma, p->t, p->n, p->yref, err);
}

void hy_wp_problem_free(hy_wp_problem *p)
{
    if (p->kind != HY_WP_BOUCWEN && p->input.pieces)
        hy_input_free(&p->input);
    free(p->t);
    free(p->yref);
    p->t = p->yref = NULL;
}

int hy_wp_solver_applies(const hy_wp_problem *p, const char *solver)
{
    if (p->kind == HY_WP_BOUCWEN)
        return !strcmp(solver, "newmark");
    if (p->kind == HY_WP_JILES)
        return hy_ode_stepper_known(solver);
    if (!strcmp(solver, "exact"))
        return hy_gamma_exact_applies(&p->model, &p->input);
    return hy_ode_stepper_known(solver);
}

/* The step ends of a GSL run (hy_ode's trace). */
typedef struct trace {
    double *t, *y;
    size_t cap, n;
} trace;

/* One call of the solver; fills y, the run's counters and tr (may be NULL). */
static int solve_once(const hy_wp_problem *p, hy_wp_run *r, const hy_wp_cfg *cfg, double *y, trace *tr,
                      hy_error *err)
{
    if (p->kind == HY_WP_BOUCWEN)
        return bw_solve(p, r->tol, y, err);
    if (p->kind == HY_WP_JILES) { /* always restarted at reversals: the model's own breakpoints */
        hy_jiles_stats st = {0};
        int rc = ja_solve(p, r->solver, r->tol, (unsigned long)cfg->max_steps, y, &st, err); /* the report's cap */
        r->nfev = st.nfev;
        r->steps = st.steps;
        r->fails = st.fails;
        return rc;
    }
    if (!strcmp(r->solver, "exact"))
        return hy_gamma_exact(&p->model, &p->input, p->gamma, p->t, p->n, y, NULL, err);
    hy_ode_opts o = hy_ode_defaults();
    o.stepper = r->solver;
    o.rtol = r->tol;
    o.atol = r->tol * 1e-2 * hy_model_g0(&p->model) / p->model.sigma0; /* |z| <= g/σ0 */
    o.restart = r->restart;
    o.max_steps = cfg->max_steps;
    o.work_limit = 0; /* the report measures what the caps stop */
    o.dense = 1;      /* free steps, Hermite outputs: the tolerance decides */
    o.trace_t = tr ? tr->t : NULL;
    o.trace_y = tr ? tr->y : NULL;
    o.trace_cap = tr ? tr->cap : 0;
    hy_ode_stats s = {0};
    int rc = hy_ode_solve(&p->model, &p->input, p->gamma, &o, p->t, p->n, y, &s, err);
    if (tr)
        tr->n = s.ntrace;
    r->nfev = s.nfev;
    r->njev = s.njev;
    r->steps = s.steps;
    r->fails = s.fails;
    return rc;
}

/* The reference at arbitrary ascending times: the long-double exponential,
 * or (Example 1) rk8pd at rtol 1e-13 ending a step at every time. */
static int step_reference(const hy_wp_problem *p, const double *t, size_t n, double *y, hy_error *err)
{
    if (!p->model.type->has_filter && p->input.all_linear)
        return hy_ref_gamma(&p->model, &p->input, p->gamma, t, n, y, err);
    hy_ode_opts o = hy_ode_defaults();
    o.stepper = "rk8pd";
    o.rtol = 1e-13;
    o.atol = 1e-15;
    o.work_limit = 0;
    return hy_ode_solve(&p->model, &p->input, p->gamma, &o, t, n, y, NULL, err);
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* Records a failed call in r (status from the message: step cap or failure). */
static void run_failed(hy_wp_run *r, const hy_error *err)
{
    r->status = strstr(err->msg, "step cap") || strstr(err->msg, "step budget") ? HY_WP_STEPCAP : HY_WP_FAIL;
    snprintf(r->msg, sizeof r->msg, "%.150s", err->msg);
}

int hy_wp_run_solver(const hy_wp_problem *p, const char *solver, int restart, double tol,
                     const hy_wp_cfg *cfg, hy_wp_run *r)
{
    memset(r, 0, sizeof *r);
    snprintf(r->problem, sizeof r->problem, "%s", p->name);
    snprintf(r->solver, sizeof r->solver, "%s", solver);
    r->restart = hy_ode_stepper_known(solver) ? restart : -1;
    r->tol = tol;
    r->err_max = r->err_l2 = r->err_steps = r->t_med = r->t_min = r->t_max = NAN;
    double *y = malloc(p->n * sizeof *y), times[64];
    trace tr = {NULL, NULL, TRACE_CAP, 0};
    if (hy_ode_stepper_known(solver) && p->kind == HY_WP_LUGRE) {
        tr.t = malloc(2 * TRACE_CAP * sizeof *tr.t);
        tr.y = tr.t ? tr.t + TRACE_CAP : NULL;
    }
    int nrep = cfg->repeats < 1 ? 1 : cfg->repeats > 64 ? 64 : cfg->repeats;
    hy_error err = {0};
    if (!y) {
        r->status = HY_WP_FAIL;
        snprintf(r->msg, sizeof r->msg, "out of memory");
        return r->status;
    }
    for (int k = 0; k < nrep; k++) {
        double t0 = hy_wp_now();
        int rc = solve_once(p, r, cfg, y, tr.t ? &tr : NULL, &err);
        times[k] = hy_wp_now() - t0;
        r->repeats = k + 1;
        if (rc) {
            run_failed(r, &err);
            break;
        }
        if (times[k] > cfg->time_cap) {
            r->status = HY_WP_TIMECAP;
            snprintf(r->msg, sizeof r->msg, "run took %.3g s > time cap %.3g s: not repeated", times[k],
                     cfg->time_cap);
            break;
        }
    }
    if (r->status != HY_WP_FAIL && r->status != HY_WP_STEPCAP) {
        hy_wp_error(y, p->yref, p->n, &r->err_max, &r->err_l2);
        if (!isfinite(r->err_max)) {
            r->status = HY_WP_FAIL;
            snprintf(r->msg, sizeof r->msg, "non-finite output");
        } else if (tr.t && tr.n) { /* the integrator alone, at its own step ends */
            double *yr = malloc(tr.n * sizeof *yr);
            if (yr && !step_reference(p, tr.t, tr.n, yr, &err))
                hy_wp_error(tr.y, yr, tr.n, &r->err_steps, NULL);
            free(yr);
            size_t len = strlen(r->msg);
            if (tr.n == tr.cap && r->steps > tr.cap)
                snprintf(r->msg + len, sizeof r->msg - len, "%serr_steps over the first %zu of %lu step ends",
                         len ? "; " : "", tr.cap, r->steps);
        }
    }
    free(tr.t);
    qsort(times, (size_t)r->repeats, sizeof *times, cmp_double);
    r->t_min = times[0];
    r->t_max = times[r->repeats - 1];
    r->t_med = times[r->repeats / 2];
    free(y);
    return r->status;
}

void hy_wp_csv_header(FILE *f)
{
    fputs("problem,solver,restart,tol,status,err_max,err_l2,err_steps,time_med_s,time_min_s,time_max_s,"
          "repeats,nfev,njev,steps,fails,message\n", f);
}

void hy_wp_csv_row(FILE *f, const hy_wp_run *r)
{
    char msg[sizeof r->msg];
    size_t j = 0;
    for (const char *s = r->msg; *s && j + 1 < sizeof msg; s++)
        msg[j++] = (*s == ',' || *s == '"' || *s == '\n') ? ';' : *s;
    msg[j] = 0;
    fprintf(f, "%s,%s,%s,%.6g,%s,%.6e,%.6e,%.6e,%.6e,%.6e,%.6e,%d,%lu,%lu,%lu,%lu,%s\n", r->problem, r->solver,
            r->restart < 0 ? "" : r->restart ? "on" : "off", r->tol, hy_wp_status_name(r->status), r->err_max,
            r->err_l2, r->err_steps, r->t_med, r->t_min, r->t_max, r->repeats, r->nfev, r->njev, r->steps, r->fails, msg);
}
