/* SPDX-License-Identifier: MIT */
/* test_cancel.c: the cancellation hook (hy_cancel.h, issue 36 item 2): a
 * hook that says stop ends a GSL solve, a Newmark run and a rate-independent
 * model's moves with HY_ECANCEL after a bounded amount of work; a hook that
 * never says stop leaves every number as without one, bit for bit. */
#include <stdlib.h>

#include "hy_boucwen.h"
#include "hy_cancel.h"
#include "hy_jiles.h"
#include "hy_ode.h"
#include "hy_rateind.h"
#include "tutil.h"

typedef struct {
    int asked;      /* how often the hook was asked */
    int stop_after; /* says stop from this question on (0: never) */
} counter;

static int hook(void *ctx)
{
    counter *c = ctx;
    c->asked++;
    return c->stop_after && c->asked >= c->stop_after;
}

static void poll_counts(void)
{
    counter k = {0, 0};
    hy_cancel c = {hook, &k};
    unsigned tick = 0;
    int stop = 0;
    for (int i = 0; i < 1000; i++)
        stop |= hy_cancel_poll(&c, &tick, 100);
    CHECK(k.asked == 10 && !stop, "asked %d times in 1000 units of 100 (want 10)", k.asked);
    CHECK(!hy_cancel_poll(NULL, &tick, 1), "a NULL hook never stops");
}

static void ode(void)
{
    hy_model m;
    hy_input in;
    hy_error err;
    hy_model_lugre_init(&m, 1, 1, 1, 2, 1, 1);
    CHECK(!hy_input_parse(&in, "sine:1,1", &err), "input: %s", err.msg);
    enum { N = 2000 };
    double *t = malloc(N * sizeof *t), *y0 = malloc(N * sizeof *y0), *y1 = malloc(N * sizeof *y1);
    for (int i = 0; i < N; i++)
        t[i] = 40.0 * i / (N - 1);
    hy_ode_opts o = hy_ode_defaults();
    CHECK(!hy_ode_solve(&m, &in, 1, &o, t, N, y0, NULL, &err), "no hook: %s", err.msg);
    counter never = {0, 0};
    hy_cancel c = {hook, &never};
    o.cancel = &c;
    CHECK(!hy_ode_solve(&m, &in, 1, &o, t, N, y1, NULL, &err), "a hook that never stops: %s", err.msg);
    CHECK(!memcmp(y0, y1, N * sizeof *y0), "a hook that never stops changed the solution");
    CHECK(never.asked > 0, "the hook was never asked in 40 periods");
    counter first = {0, 1};
    c.ctx = &first;
    CHECK_MSG(hy_ode_solve(&m, &in, 1, &o, t, N, y1, NULL, &err), err, HY_ECANCEL, "no longer wanted");
    CHECK(first.asked == 1, "asked %d times after saying stop", first.asked);
    free(t), free(y0), free(y1);
    hy_input_free(&in);
}

static void newmark(void)
{
    hy_boucwen_params p;
    hy_newmark_opts o;
    hy_error err;
    hy_boucwen_params_default(&p);
    hy_newmark_opts_default(&o);
    enum { N = 5 * HY_NEWMARK_CANCEL_STEPS + 7 };
    double *u = malloc(N * sizeof *u), *y0 = malloc(N * sizeof *y0), *y1 = malloc(N * sizeof *y1);
    for (int i = 0; i < N; i++)
        u[i] = 50.0 * sin(2 * M_PI * 5.0 * i / 750.0);
    CHECK(!hy_boucwen_simulate(&p, &o, 1.0 / 750.0, u, N, NULL, y0, NULL, &err), "no hook: %s", err.msg);
    counter never = {0, 0};
    hy_cancel c = {hook, &never};
    o.cancel = &c;
    CHECK(!hy_boucwen_simulate(&p, &o, 1.0 / 750.0, u, N, NULL, y1, NULL, &err), "never: %s", err.msg);
    CHECK(!memcmp(y0, y1, N * sizeof *y0), "a hook that never stops changed the Newmark run");
    CHECK(never.asked == 5, "asked %d times in %d steps (want 5, one a block)", never.asked, N);
    counter second = {0, 2};
    c.ctx = &second;
    CHECK_MSG(hy_boucwen_simulate(&p, &o, 1.0 / 750.0, u, N, NULL, y1, NULL, &err), err, HY_ECANCEL, "no longer wanted");
    CHECK(!memcmp(y0, y1, (2 * HY_NEWMARK_CANCEL_STEPS + 1) * sizeof *y0), "the samples before the stop differ");
    free(u), free(y0), free(y1);
}

/* a rate-independent "model" that only counts its moves */
static int cnt_init(const void *par, void *st, double u0, double out[HY_RI_NOUT], hy_error *err)
{
    (void)par, (void)err;
    *(long *)st = 0;
    out[0] = u0, out[1] = out[2] = 0;
    return HY_OK;
}
static int cnt_apply(const void *par, void *st, double u, double out[HY_RI_NOUT], hy_error *err)
{
    (void)par, (void)err;
    ++*(long *)st;
    out[0] = u;
    return HY_OK;
}
static int cnt_copy(const void *par, void *dst, const void *src, hy_error *err)
{
    (void)par, (void)err;
    *(long *)dst = *(const long *)src;
    return HY_OK;
}

static void rateind(void)
{
    static const hy_rateind_type type = {"counter", sizeof(long), 0, cnt_init, cnt_apply, cnt_copy, NULL, NULL};
    hy_rateind m;
    hy_error err;
    CHECK(!hy_rateind_alloc(&m, &type, NULL, 0, &err) && m.cancel == NULL, "alloc: %s", err.msg);
    counter stop = {0, 1};
    hy_cancel c = {hook, &stop};
    m.cancel = &c;
    int rc = HY_OK, i;
    for (i = 0; i < 1000 && !rc; i++)
        rc = hy_rateind_apply(&m, i, &err);
    CHECK(rc == HY_ECANCEL && *(long *)m.st == HY_RI_CANCEL_MOVES - 1,
          "stopped with %d after %ld moves (want HY_ECANCEL after %d)", rc, *(long *)m.st, HY_RI_CANCEL_MOVES - 1);
    hy_rateind_free(&m);
}

/* one Jiles-Atherton stretch: thousands of GSL steps between two moves */
static void jiles(void)
{
    hy_jiles j;
    hy_jiles_state s0, s1;
    hy_error err;
    CHECK(!hy_jiles_init(&j, 1.6e6, 1100, 400, 0.2, 1.6e-3, &err) && j.cancel == NULL, "init: %s", err.msg);
    hy_jiles_state_init(&j, &s0, 0);
    CHECK(!hy_jiles_apply(&j, &s0, 2e4, NULL, &err), "no hook: %s", err.msg);
    counter never = {0, 0};
    hy_cancel c = {hook, &never};
    j.cancel = &c;
    hy_jiles_state_init(&j, &s1, 0);
    CHECK(!hy_jiles_apply(&j, &s1, 2e4, NULL, &err), "never: %s", err.msg);
    CHECK(s0.H == s1.H && s0.M == s1.M && s0.hb == s1.hb, "a hook that never stops changed M: %.17g vs %.17g", s0.M,
          s1.M);
    counter first = {0, 1};
    c.ctx = &first;
    hy_jiles_state_init(&j, &s1, 0);
    if (never.asked > 0) {
        CHECK_MSG(hy_jiles_apply(&j, &s1, 2e4, NULL, &err), err, HY_ECANCEL, "no longer wanted");
        CHECK(s1.H > 0 && s1.H < 2e4, "stopped at H = %g (want the last good step, inside the stretch)", s1.H);
    } else
        printf("jiles: the stretch took fewer than 64 steps: nothing to stop\n");
}

int main(void)
{
    poll_counts();
    ode();
    newmark();
    rateind();
    jiles();
    return tu_finish("cancel");
}
