/* SPDX-License-Identifier: MIT */
/* cmd_loop.c: `hystviz loop` (steady loop, y*_{u,k} or y_γ as CSV) and
 * `hystviz loops` (major and minor loops with their areas). */
#include "cmd_loop.h"

#include <gsl/gsl_errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cli_util.h"
#include "hy_gamma.h"
#include "hy_limit.h"
#include "hy_loops.h"
#include "hy_ode.h"
#include "hy_out.h"

static const char loop_usage[] =
    "usage: hystviz loop [MODEL OPTIONS] --input SPEC [--points N] [--k K]\n"
    "                    [--gamma G [--solver NAME] [--cycles C] [--rtol R] [--atol A]] [-o FILE]\n"
    "       hystviz loops [MODEL OPTIONS] --input SPEC [-o FILE]\n"
    "\n"
    "loop prints CSV 't,u,y' (%.17g) over one period of the input:\n"
    "  default        the steady hysteresis loop y°_u (Theorem 2(b), exact)\n"
    "  --k K          the k-cycle function y*_{u,K}(t) = y*_u(t + K T) (exact)\n"
    "  --gamma G      y_γ at finite γ over C periods from z(0) = x0 (--cycles, default 1),\n"
    "                 exact for piecewise-linear inputs, else --solver (default rkf45)\n"
    "loops prints one CSV row per loop (the major loop first): its ϱ interval,\n"
    "the input and output where it starts and closes, and ∮ y du (energy per cycle).\n"
    "The model options' defaults are the LuGre of Example 2:\n"
    "sigma0 = sigma1 = FC = VS = BETA = 1, FS = 2, sigma2 = 0, x0 = 0.\n"
    "\n";

static const char loop_tail[] =
    "input SPEC:\n"
    "  bimodal:umin1,umin2,umax1,umax2[,t1,t2,t3,t4][:cosine]   multimodal:e0,e1,...[:cosine]\n"
    "  triangle:min,max,T   sine:amp,T[,offset]   pwl:t0,u0,t1,u1,...   file:PATH\n"
    "example:\n"
    "  hystviz loop --model lugre --sigma0 6 --fc 1 --fs 2 --vs 1 --beta 1 \\\n"
    "               --input bimodal:0,0.5,1,1.5 --points 200\n";

enum { OPT_INPUT = CLI_FIRST, OPT_OUT, OPT_SOLVER, OPT_POINTS, OPT_CYCLES, OPT_K, OPT_GAMMA, OPT_RTOL, OPT_ATOL };
static const cli_opt loop_opts[] = {
    {.group = cli_model_opts},
    {"input", 0, "SPEC", "the input u (below); required", OPT_INPUT, 0, NULL, NULL, NULL},
    {"points", 0, "N", "points over the period (default 200)", OPT_POINTS, 0, NULL, NULL, NULL},
    {"k", 0, "K", "the k-cycle function y*_{u,K} instead of y°_u", OPT_K, 0, NULL, NULL, NULL},
    {"gamma", 0, "G", "y_γ at finite γ = G instead of y°_u", OPT_GAMMA, 0, NULL, NULL, NULL},
    {"solver", 0, "NAME", "the solver of --gamma: exact or a GSL stepper (rkf45, ...)", OPT_SOLVER, 0, NULL, NULL,
     NULL},
    {"cycles", 0, "C", "periods of --gamma (default 1)", OPT_CYCLES, 0, NULL, NULL, NULL},
    {"rtol", 0, "R", "the GSL steppers' local error control, atol + rtol |z| on\n"
     "the state z (|z| <= g(0)/sigma0): default rtol 1e-10 and\n"
     "atol = 1e-2 rtol g(0)/sigma0, i.e. 1e-2 rtol g(0) in y = sigma0 z\n"
     "(g(0) = FS for LuGre, FC for Dahl).  A stepper that is too\n"
     "stiff for the input (its work estimate from the stiffness ratio\n"
     "sigma0*du/g of each piece passes 1e7 evaluations) is refused at\n"
     "once (exit status 2) with the advice to use exact, bsimp or msbdf", OPT_RTOL, 0, NULL, NULL, NULL},
    {"atol", 0, "A", "see --rtol", OPT_ATOL, 0, NULL, NULL, NULL},
    {"output", 'o', "FILE", "the CSV file (default: standard output)", OPT_OUT, 0, NULL, NULL, NULL},
    {0},
};
static const cli_cmd loop_cli = {NULL, loop_usage, loop_tail, NULL, loop_opts};

typedef struct loop_args {
    cli_model cm;
    const char *input, *out, *solver;
    long points, cycles;
    double k, gamma, rtol, atol;
    int have_k, have_gamma, have_atol;
} loop_args;

/* One option; 0 or 2 (message printed). */
static int take(loop_args *a, int id, const char *s, const char *v)
{
    switch (id) {
    case OPT_INPUT: a->input = v; return 0;
    case OPT_OUT: a->out = v; return 0;
    case OPT_SOLVER: a->solver = v; return 0;
    case OPT_POINTS: return cli_long(s, v, 2, 100000000L, &a->points) ? 2 : 0;
    case OPT_CYCLES: return cli_long(s, v, 1, 1000000L, &a->cycles) ? 2 : 0;
    case OPT_K:
        if (cli_num(s, v, &a->k))
            return 2;
        if (a->k < 0 || a->k != floor(a->k)) {
            fprintf(stderr, "hystviz: --k must be a whole number >= 0 (got %s)\n", v);
            return 2;
        }
        a->have_k = 1;
        return 0;
    case OPT_GAMMA: a->have_gamma = 1; return cli_num(s, v, &a->gamma) ? 2 : 0;
    case OPT_RTOL: return cli_num(s, v, &a->rtol) ? 2 : 0;
    case OPT_ATOL: a->have_atol = 1; return cli_num(s, v, &a->atol) ? 2 : 0;
    default: return cli_model_take(&a->cm, id, v) < 0 ? 2 : 0;
    }
}

/* 0, 1 help printed, or 2 (message printed). */
static int parse_args(int argc, char **argv, loop_args *a)
{
    memset(a, 0, sizeof *a);
    cli_model_defaults(&a->cm);
    a->points = 200;
    a->cycles = 1;
    a->rtol = 1e-10;
    cli_parser p;
    cli_parser_init(&p, &loop_cli, argc, argv, 1);
    for (int id; (id = cli_next(&p)) != CLI_END;) {
        if (id == CLI_STOP || id == CLI_ERROR)
            return id == CLI_STOP ? 1 : 2;
        if (take(a, id, p.optname, p.val))
            return 2;
    }
    if (!a->input) {
        fprintf(stderr, "hystviz loop: --input SPEC is required (see hystviz loop --help)\n");
        return 2;
    }
    return 0;
}

static int compute(const loop_args *a, const hy_model *m, const hy_input *in, double *t, double *u,
                   double *y, size_t n)
{
    hy_error err = {0};
    double span = in->period * (a->have_gamma ? (double)a->cycles : 1.0);
    for (size_t i = 0; i < n; i++) {
        t[i] = span * (double)i / (double)(n - 1);
        u[i] = hy_input_u(in, t[i]);
    }
    if (a->have_gamma) {
        int rc;
        if (!a->solver && hy_gamma_exact_applies(m, in))
            rc = hy_gamma_exact(m, in, a->gamma, t, n, y, NULL, &err);
        else {
            hy_ode_opts o = hy_ode_defaults();
            o.stepper = a->solver ? a->solver : "rkf45";
            o.rtol = a->rtol;
            o.atol = a->have_atol ? a->atol : 1e-2 * a->rtol * hy_model_g0(m) / m->sigma0; /* |z| <= g(0)/σ0 */
            rc = (a->solver && !strcmp(a->solver, "exact")) ? hy_gamma_exact(m, in, a->gamma, t, n, y, NULL, &err)
                                                            : hy_ode_solve(m, in, a->gamma, &o, t, n, y, NULL, &err);
        }
        if (rc) {
            fprintf(stderr, "hystviz loop: %s\n", err.msg);
            return cli_exit_status(rc);
        }
        return 0;
    }
    hy_steady st;
    if (hy_steady_init(&st, m, in, &err)) {
        fprintf(stderr, "hystviz loop: %s\n", err.msg);
        return cli_exit_status(err.code);
    }
    for (size_t i = 0; i < n; i++)
        y[i] = a->have_k ? hy_ystar_k(&st, m->x0, a->k, t[i]) : hy_steady_at(&st, t[i]);
    y[n - 1] = a->have_k ? hy_ystar_k(&st, m->x0, a->k, in->period) : st.y_run[in->nruns];
    hy_steady_free(&st);
    return 0;
}

/* Opens the CSV output before computing: a directory or a missing folder
 * fails at once, and a failed computation leaves nothing. */
static int open_out(const char *cmd, const char *path, hy_out *o)
{
    hy_error err = {0};
    if (hy_out_open(o, path ? path : "-", HY_OUT_FOLLOW, &err)) {
        fprintf(stderr, "hystviz %s: %s\n", cmd, err.msg);
        return 1;
    }
    return 0;
}

static int close_out(const char *cmd, hy_out *o)
{
    hy_error err = {0};
    if (hy_out_commit(o, &err)) {
        fprintf(stderr, "hystviz %s: %s\n", cmd, err.msg);
        return 1;
    }
    return 0;
}

static void write_loop(FILE *f, const double *t, const double *u, const double *y, size_t n)
{
    fprintf(f, "t,u,y\n");
    for (size_t i = 0; i < n; i++)
        fprintf(f, "%.17g,%.17g,%.17g\n", t[i], u[i], y[i]);
}

static void write_loops(FILE *f, const hy_loops *L)
{
    fprintf(f, "loop,depth,rho_start,rho_turn,rho_close,u_start,u_turn,y_start,y_close,area,own_area\n");
    for (size_t i = 0; i <= L->nminor; i++) {
        const hy_loop *p = i ? &L->minor[i - 1] : &L->major;
        fprintf(f, "%s,%d,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g\n", i ? "minor" : "major",
                p->depth, p->rho_start, p->rho_turn, p->rho_close, p->u_start, p->u_turn, p->y_start,
                p->y_close, p->area, p->own_area);
    }
    fprintf(f, "# energy per cycle (closed integral of y du over one period): %.17g\n", L->area_period);
}

int hy_cmd_loop(int argc, char **argv)
{
    loop_args a;
    int rc = parse_args(argc, argv, &a);
    if (rc)
        return rc == 1 ? 0 : 2;
    gsl_set_error_handler_off();
    hy_model m;
    if (cli_model_build(&a.cm, &m))
        return 2;
    hy_input in;
    hy_error err = {0};
    if (hy_input_parse(&in, a.input, &err)) {
        fprintf(stderr, "hystviz loop: --input: %s\n", err.msg);
        return 2;
    }
    hy_out o;
    if (open_out(argv[0], a.out, &o)) {
        hy_input_free(&in);
        return 1;
    }
    if (!strcmp(argv[0], "loops")) {
        hy_steady st;
        hy_loops L;
        rc = hy_steady_init(&st, &m, &in, &err) || hy_loops_find(&st, &L, &err);
        if (rc) {
            fprintf(stderr, "hystviz loops: %s\n", err.msg);
            rc = cli_exit_status(err.code);
        }
        else {
            write_loops(hy_out_file(&o), &L);
            rc = close_out(argv[0], &o);
            hy_loops_free(&L);
        }
        hy_steady_free(&st);
        hy_input_free(&in);
        hy_out_abort(&o);
        return rc;
    }
    size_t n = (size_t)a.points;
    double *buf = malloc(3 * n * sizeof *buf);
    if (!buf) {
        fprintf(stderr, "hystviz loop: out of memory for %zu points\n", n);
        hy_input_free(&in);
        hy_out_abort(&o);
        return 1;
    }
    rc = compute(&a, &m, &in, buf, buf + n, buf + 2 * n, n);
    if (!rc) {
        write_loop(hy_out_file(&o), buf, buf + n, buf + 2 * n, n);
        rc = close_out(argv[0], &o);
    }
    hy_out_abort(&o);
    free(buf);
    hy_input_free(&in);
    return rc;
}
