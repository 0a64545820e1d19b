/* SPDX-License-Identifier: MIT */
/* test_core_contracts.c: the installed core headers other than the readers'
 * (issue 36 item 4): each function called with each pointer argument NULL in
 * turn and with edge numbers (NaN, infinities, sizes whose byte count
 * overflows).  A pointer the header says must not be NULL gives its
 * documented refusal (HY_EINVAL "FUNCTION: X must not be NULL", NaN, 0, or
 * nothing done), never a crash; one it says may be NULL does what it says.
 * Linked into lib-contracts, which runs under ASan and UBSan in build-san. */
#include <errno.h>
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hy_boucwen.h"
#include "hy_cancel.h"
#include "hy_file.h"
#include "hy_fit.h"
#include "hy_gamma.h"
#include "hy_jiles.h"
#include "hy_limit.h"
#include "hy_loops.h"
#include "hy_model.h"
#include "hy_ode.h"
#include "hy_preisach.h"
#include "hy_rateind.h"
#include "hy_ref.h"
#include "hy_signal.h"
#include "hy_status.h"
#include "../core/tutil.h"
#include "contracts.h"

/* ---- what NC() and REFUSED() reached ------------------------------------- */

static char reached[512][64];
static size_t nreached;

void tc_mark(const char *call)
{
    char name[64];
    size_t n = 0;
    while (*call == ' ' || *call == '(')
        call++;
    while (n + 1 < sizeof name && (call[n] == '_' || (call[n] >= 'a' && call[n] <= 'z') ||
                                   (call[n] >= 'A' && call[n] <= 'Z') || (call[n] >= '0' && call[n] <= '9')))
        name[n] = call[n], n++;
    name[n] = '\0';
    for (size_t i = 0; i < nreached; i++)
        if (!strcmp(reached[i], name))
            return;
    if (nreached < sizeof reached / sizeof reached[0])
        memcpy(reached[nreached++], name, n + 1);
}

int tc_coverage(const char *path)
{
    FILE *f = fopen(path, "r");
    if (!f) {
        fprintf(stderr, "FAIL cannot read the ABI list %s\n", path);
        return 1;
    }
    char line[256];
    int missed = 0, listed = 0;
    while (fgets(line, sizeof line, f)) {
        if (strncmp(line, "symbol ", 7))
            continue;
        char *name = line + 7;
        name[strcspn(name, "@\n")] = '\0';
        int found = 0;
        for (size_t i = 0; i < nreached && !found; i++)
            found = !strcmp(reached[i], name);
        listed++;
        if (!found) {
            fprintf(stderr, "FAIL %s is exported (%s) but lib-contracts has no NULL or edge case for it\n", name,
                    path);
            missed++;
        }
    }
    fclose(f);
    printf("coverage: %d exported functions, %d without a NULL or edge case\n", listed, missed);
    return missed + (listed == 0);
}

/* ---- objects the cases need ---------------------------------------------- */

static hy_input bimodal(void)
{
    hy_input in;
    hy_error err;
    CHECK(hy_input_bimodal(&in, 0, 0.5, 1, 1.5, NULL, HY_SHAPE_LINEAR, &err) == HY_OK, "bimodal input: %s", err.msg);
    return in;
}

static hy_model lugre(void)
{
    hy_model m;
    hy_model_lugre_init(&m, 6, 1, 1, 2, 1, 1);
    return m;
}

/* ---- hy_status.h, hy_cancel.h, hy_file.h --------------------------------- */

static int stop(void *ctx)
{
    (void)ctx;
    return 1;
}

static void status_file(void)
{
    hy_error err;
    char buf[32];
    /* through pointers: a literal NULL format would be a compile-time warning */
    int (*set)(hy_error *, int, const char *, ...) = hy_error_set;
    void (*prefix)(hy_error *, const char *, ...) = hy_error_prefix;
    tc_mark("hy_error_set");
    CHECK(set(&err, HY_ENUM, NULL) == HY_ENUM && err.code == HY_ENUM && !strcmp(err.msg, "(no message)"),
          "hy_error_set fmt NULL: %s", err.msg);
    CHECK(set(NULL, HY_EIO, NULL) == HY_EIO, "hy_error_set e NULL, fmt NULL");
    tc_mark("hy_error_prefix");
    prefix(&err, NULL);
    prefix(NULL, "x");
    CHECK(!strcmp(err.msg, "(no message)"), "hy_error_prefix fmt NULL leaves the message");
    memset(buf, 'z', sizeof buf);
    NC(hy_text_shown(NULL, buf, sizeof buf));
    CHECK(buf[0] == '\0', "hy_text_shown src NULL: the empty text");
    NC(hy_text_shown("ab", NULL, 8));
    buf[0] = 'z';
    NC(hy_text_shown("ab", buf, 0));
    CHECK(buf[0] == 'z', "hy_text_shown size 0 writes nothing");
    CHECK(NC(hy_text_check(NULL)) == -1, "hy_text_check(NULL)");

    hy_cancel c = {stop, NULL}, none = {NULL, NULL};
    unsigned tick = 0;
    CHECK(NC(hy_cancel_poll(NULL, &tick, 1)) == 0 && hy_cancel_poll(&c, NULL, 1) == 0 &&
              hy_cancel_poll(&none, &tick, 1) == 0,
          "hy_cancel_poll with c, tick or c->fn NULL: never stops");
    CHECK(hy_cancel_poll(&c, &tick, 0) == 1, "hy_cancel_poll every 0 asks");

    char *b = (char *)buf, why[80] = "";
    size_t len = 9;
    CHECK(NC(hy_file_read(NULL, 10, &b, &len, NULL, why, sizeof why)) == EINVAL && !b && len == 0 &&
              strstr(why, "path must not be NULL"),
          "hy_file_read path NULL: %s", why);
    CHECK(hy_file_read("/dev/null", 10, NULL, &len, NULL, why, sizeof why) == EINVAL && strstr(why, "buf must"),
          "hy_file_read buf NULL: %s", why);
    CHECK(hy_file_read("/dev/null", 10, &b, NULL, NULL, NULL, 0) == EINVAL && !b, "hy_file_read len NULL, why NULL");
    CHECK(NC(hy_file_excerpt(NULL, 5, buf, sizeof buf)) == buf && buf[0] == '\0', "hy_file_excerpt p NULL");
    CHECK(hy_file_excerpt("abc", 3, NULL, 8) == NULL, "hy_file_excerpt buf NULL");
    CHECK(NC(hy_file_shown(NULL, 5, 20, buf, sizeof buf)) == buf && buf[0] == '\0', "hy_file_shown p NULL");
    CHECK(hy_file_shown("abc", 3, 20, NULL, 0) == NULL, "hy_file_shown buf NULL");
    buf[0] = 'z';
    CHECK(NC(hy_file_installed(HY_INSTALLED_DATA, NULL, buf, sizeof buf)) == -1 && buf[0] == '\0',
          "hy_file_installed sub NULL");
    CHECK(hy_file_installed(HY_INSTALLED_DATA, "scenes", NULL, 16) == -1 &&
              hy_file_installed(HY_INSTALLED_DATA, "scenes", NULL, 0) == -1,
          "hy_file_installed buf NULL");
}

/* ---- hy_model.h, hy_input.h ---------------------------------------------- */

static void model_input(void)
{
    hy_error err;
    hy_model m, z;
    memset(&z, 0, sizeof z);
    NC(hy_model_lugre_init(NULL, 6, 1, 1, 2, 1, 1));
    NC(hy_model_dahl_init(NULL, 1, 1));
    NC(hy_model_dahl_filter_init(NULL, 1, 1, 1));
    REFUSED(hy_model_validate(NULL, &err), err, "model has no type");
    hy_model_lugre_init(&m, NAN, 1, 1, 2, 1, 1);
    REFUSED(hy_model_validate(&m, &err), err, "sigma0");
    hy_model_dahl_init(&m, INFINITY, 1);
    CHECK(hy_model_validate(&m, &err) == HY_EINVAL, "Dahl with rho = INFINITY refused");
    CHECK(NC(hy_model_type_find(NULL)) == NULL, "hy_model_type_find(NULL)");
    CHECK(isnan(NC(hy_model_g(NULL, 0))) && isnan(NC(hy_model_g0(NULL))) && isnan(NC(hy_model_a(NULL))),
          "hy_model_g, _g0, _a of NULL: NaN");
    CHECK(NC(hy_model_rate_independent(NULL)) == 0 && hy_model_rate_independent(&z) == 0,
          "hy_model_rate_independent of NULL or a model without type: 0");

    hy_input in = bimodal(), x, freed = bimodal();
    hy_input_free(&freed);
    double t[3] = {0, 1, 2}, u[3] = {0, 1, 0}, e[2] = {0, 1};
    hy_piece pcs[4];
    hy_run runs[4];
    REFUSED(hy_input_pwl(NULL, t, u, 3, &err), err, "hy_input_pwl: in must not be NULL");
    REFUSED(hy_input_pwl(&x, NULL, u, 3, &err), err, "t must not be NULL");
    REFUSED(hy_input_pwl(&x, t, NULL, 3, &err), err, "u must not be NULL");
    REFUSED(hy_input_bimodal(NULL, 0, 0.5, 1, 1.5, NULL, 0, &err), err, "in must not be NULL");
    REFUSED(hy_input_bimodal_buf(NULL, pcs, runs, 0, 0.5, 1, 1.5, NULL, 0, &err), err, "in must not be NULL");
    REFUSED(hy_input_bimodal_buf(&x, NULL, runs, 0, 0.5, 1, 1.5, NULL, 0, &err), err, "pieces must not be NULL");
    REFUSED(hy_input_bimodal_buf(&x, pcs, NULL, 0, 0.5, 1, 1.5, NULL, 0, &err), err, "runs must not be NULL");
    REFUSED(hy_input_multimodal(NULL, e, 2, NULL, 0, &err), err, "in must not be NULL");
    REFUSED(hy_input_multimodal(&x, NULL, 2, NULL, 0, &err), err, "e must not be NULL");
    REFUSED(hy_input_triangle(NULL, 0, 1, 1, &err), err, "in must not be NULL");
    REFUSED(hy_input_triangle(&x, 0, 1, INFINITY, &err), err, "period");
    REFUSED(hy_input_sine(NULL, 1, 1, 0, &err), err, "in must not be NULL");
    REFUSED(hy_input_sine(&x, NAN, 1, 0, &err), err, "amplitude");
    REFUSED(hy_input_file(NULL, "x", &err), err, "in must not be NULL");
    REFUSED(hy_input_file(&x, NULL, &err), err, "path must not be NULL");
    REFUSED(hy_input_text(NULL, "0 0\n", 4, "t", 1, &err), err, "in must not be NULL");
    REFUSED(hy_input_text(&x, NULL, 4, "t", 1, &err), err, "text must not be NULL");
    CHECK(hy_input_text(&x, NULL, 0, NULL, 1, &err) == HY_EINVAL && strstr(err.msg, "input"),
          "hy_input_text: NULL text of length 0, name NULL: an empty 'input': %s", err.msg);
    CHECK(hy_input_text(&x, "0 0\n1 1\n", 8, NULL, 1, &err) == HY_OK, "hy_input_text name NULL: %s", err.msg);
    hy_input_free(&x);
    REFUSED(hy_input_parse(NULL, "triangle:0,1,1", &err), err, "in must not be NULL");
    REFUSED(hy_input_parse(&x, NULL, &err), err, "spec must not be NULL");
    NC(hy_input_free(NULL));
    double tm = 0, k = 0, r = 0;
    CHECK(isnan(NC(hy_input_reduce(NULL, 1, 1))), "hy_input_reduce(NULL)");
    CHECK(NC(hy_input_snap(0)) > 0 && hy_input_snap(NAN) > 0, "hy_input_snap of 0 and NaN: a positive width");
    CHECK(NC(hy_input_piece_at(NULL, 1, &tm, &k)) == 0 && isnan(tm) && isnan(k), "hy_input_piece_at(NULL)");
    CHECK(hy_input_piece_at(&freed, 1, NULL, NULL) == 0, "hy_input_piece_at of a freed input, tmod NULL");
    CHECK(hy_input_piece_at(&in, NAN, NULL, NULL) < in.npieces, "hy_input_piece_at(NaN) inside the pieces");
    CHECK(isnan(NC(hy_input_u(NULL, 1))) && isnan(NC(hy_input_du(&freed, 1))) && isnan(NC(hy_input_ddu(NULL, 1))) &&
              isnan(NC(hy_input_rho(&freed, 1))) && isnan(NC(hy_input_psi(NULL, 1))),
          "u, du, ddu, rho, psi of NULL or a freed input: NaN");
    CHECK(isnan(hy_input_u(&in, NAN)), "hy_input_u(NaN) is NaN");
    CHECK(isnan(NC(hy_piece_u(NULL, 0))) && isnan(NC(hy_piece_du(NULL, 0))), "hy_piece_u, _du of NULL");
    CHECK(NC(hy_input_run_at(NULL, 1, &r)) == 0 && isnan(r), "hy_input_run_at(NULL)");
    CHECK(hy_input_run_at(&in, INFINITY, NULL) < in.nruns, "hy_input_run_at(INFINITY) inside the runs");
    hy_input_free(&in);
}

/* ---- hy_limit.h, hy_loops.h, hy_gamma.h, hy_ref.h ------------------------ */

static void limit_loops(void)
{
    hy_error err;
    hy_input in = bimodal(), freed = bimodal();
    hy_input_free(&freed);
    hy_model m = lugre();
    hy_steady st, zero;
    memset(&zero, 0, sizeof zero);
    double yr[8];
    /* phi1(0) = 1 and phi2(0) = 1/2 exactly (their limits); a step of 0 moves nothing */
    CHECK(NC(hy_phi1(0)) == 1 && NC(hy_phi2(0)) == 0.5 && isnan(hy_phi1(NAN)), "phi1, phi2 at 0 and NaN");
    CHECK(NC(hy_limit_step(2, 1, 0.25, 1, 0)) == 0.25 && NC(hy_limit_step_area(2, 1, 0.25, 1, 0)) == 0,
          "a monotone run of variation 0");
    /* the _em form is hy_limit_step_area given expm1(-ad): the same bits, at 0 and past it */
    CHECK(NC(hy_limit_step_area_em(2, 1, 0.25, 1, 0, 0)) == 0 &&
              hy_limit_step_area_em(2, 1, 0.25, -1, 0.5, expm1(-1.0)) == hy_limit_step_area(2, 1, 0.25, -1, 0.5) &&
              isnan(hy_limit_step_area_em(2, 1, 0.25, 1, NAN, NAN)),
          "hy_limit_step_area_em at variation 0, 0.5 and NaN");
    REFUSED(hy_steady_init(NULL, &m, &in, &err), err, "hy_steady_init: st must not be NULL");
    REFUSED(hy_steady_init(&st, NULL, &in, &err), err, "m must not be NULL");
    CHECK(st.y_run == NULL, "hy_steady_init: st->y_run NULL after a refusal");
    REFUSED(hy_steady_init(&st, &m, NULL, &err), err, "in must not be NULL");
    REFUSED(hy_steady_init(&st, &m, &freed, &err), err, "in has no pieces");
    REFUSED(hy_steady_init_buf(NULL, &m, &in, yr, &err), err, "st must not be NULL");
    REFUSED(hy_steady_init_buf(&st, &m, &in, NULL, &err), err, "y_run must not be NULL");
    NC(hy_steady_free(NULL));
    CHECK(hy_steady_init(&st, &m, &in, &err) == HY_OK, "hy_steady_init: %s", err.msg);
    CHECK(isnan(NC(hy_steady_at_rho(NULL, 0))) && isnan(NC(hy_steady_at(&zero, 0))) &&
              isnan(NC(hy_ystar_at(NULL, 0, 0))) && isnan(NC(hy_ystar_k(&zero, 0, 0, 0))),
          "the steady state's values of NULL or an uninitialised one: NaN");
    yr[0] = -7;
    NC(hy_steady_sample(NULL, 4, NULL, yr));
    hy_steady_sample(&st, 1, NULL, yr);
    hy_steady_sample(&st, 4, NULL, NULL);
    CHECK(yr[0] == -7, "hy_steady_sample: st NULL or n < 2 writes nothing");
    hy_steady_sample(&st, 4, NULL, yr);
    /* the steady state is periodic: y(0) = y(T); y[0] is formed as g0 s + (y - g0 s), within ulps of g0 */
    CHECK(fabs(yr[0] - yr[3]) <= 8 * DBL_EPSILON * 2 && yr[0] != -7, "hy_steady_sample u_out NULL: y over one period");

    hy_theorem_a th;
    REFUSED(hy_theorem_a_init(NULL, 6, 2, 0, 0.5, 1, 1.5, &err), err, "th must not be NULL");
    REFUSED(hy_theorem_a_init(&th, NAN, 2, 0, 0.5, 1, 1.5, &err), err, "sigma0");
    CHECK(isnan(NC(hy_theorem_a_eval(NULL, 0))) && isnan(NC(hy_theorem_a_psi(NULL, 0))) &&
              isnan(NC(hy_theorem_a_printed(NULL, 0, 0))),
          "Theorem A of NULL: NaN");
    CHECK(hy_theorem_a_init(&th, 6, 2, 0, 0.5, 1, 1.5, &err) == HY_OK && isnan(hy_theorem_a_eval(&th, INFINITY)),
          "Theorem A at rho = INFINITY: NaN");

    hy_loops L;
    hy_loops nest = {.nminor = 2};
    char work[1];
    REFUSED(hy_loops_find(NULL, &L, &err), err, "hy_loops_find: st must not be NULL");
    REFUSED(hy_loops_find(&st, NULL, &err), err, "out must not be NULL");
    REFUSED(hy_loops_find(&zero, &L, &err), err, "not an initialised steady state");
    REFUSED(hy_loops_find_buf(NULL, &L, work, &err), err, "st must not be NULL");
    REFUSED(hy_loops_find_buf(&st, NULL, work, &err), err, "out must not be NULL");
    CHECK(hy_loops_find_buf(&st, &L, NULL, &err) == HY_OK && L.nminor == 1, "hy_loops_find_buf work NULL: %s",
          err.msg);
    hy_loops_free(&L);
    NC(hy_loops_free(NULL));
    CHECK(NC(hy_loops_work_size(SIZE_MAX)) == 0 && hy_loops_work_size(4) > 0, "hy_loops_work_size overflow: 0");
    REFUSED(hy_loops_pair(NULL, &L, &err), err, "in must not be NULL");
    REFUSED(hy_loops_pair(&in, NULL, &err), err, "out must not be NULL");
    REFUSED(hy_loops_nest(NULL, &err), err, "out must not be NULL");
    REFUSED(hy_loops_nest(&nest, &err), err, "out->minor must not be NULL");
    hy_arc arcs[4];
    CHECK(isnan(NC(hy_steady_area(NULL, 0, 1))) && isnan(hy_steady_area(&st, 0, INFINITY)) &&
              isnan(hy_steady_area(&st, NAN, 1)),
          "hy_steady_area of NULL or to INFINITY: NaN (no endless loop)");
    CHECK(NC(hy_steady_arcs(NULL, 0, 1, arcs, 4)) == 0 && hy_steady_arcs(&st, 0, 1, NULL, 4) == 0 &&
              hy_steady_arcs(&st, 0, INFINITY, arcs, 4) == 0 && hy_steady_arcs(&st, 0, 1, NULL, 0) >= 1,
          "hy_steady_arcs: NULL, arcs NULL, to INFINITY");

    double t[2] = {0, 0.5}, y[2];
    CHECK(NC(hy_gamma_exact_applies(NULL, &in)) == 0 && hy_gamma_exact_applies(&m, NULL) == 0,
          "hy_gamma_exact_applies with NULL: 0");
    REFUSED(hy_gamma_exact(NULL, &in, 1, t, 2, y, NULL, &err), err, "hy_gamma_exact: m must not be NULL");
    REFUSED(hy_gamma_exact(&m, NULL, 1, t, 2, y, NULL, &err), err, "in must not be NULL");
    REFUSED(hy_gamma_exact(&m, &in, 1, NULL, 2, y, NULL, &err), err, "t must not be NULL");
    REFUSED(hy_gamma_exact(&m, &in, 1, t, 2, NULL, NULL, &err), err, "y_out must not be NULL");
    REFUSED(hy_gamma_exact(&m, &in, INFINITY, t, 2, y, NULL, &err), err, "gamma");
    REFUSED(hy_gamma_check(NAN, &err), err, "gamma");

    hy_ref_limit R;
    long double lr[8] = {-7};
    REFUSED(hy_ref_limit_init(NULL, 6, 2, &in, &err), err, "R must not be NULL");
    REFUSED(hy_ref_limit_init(&R, 6, 2, NULL, &err), err, "in must not be NULL");
    REFUSED(hy_ref_limit_init(&R, NAN, 2, &in, &err), err, "sigma0");
    NC(hy_ref_limit_free(NULL));
    CHECK(isnan(NC(hy_ref_steady_rho(NULL, 0))) && isnan(NC(hy_ref_in_period(NULL, lr, 0))) &&
              isnan((double)NC(hy_ref_period(NULL, 0))),
          "the reference of NULL: NaN");
    NC(hy_ref_runs(NULL, 0, lr));
    CHECK(lr[0] == -7, "hy_ref_runs(NULL) writes nothing");
    CHECK(hy_ref_limit_init(&R, 6, 2, &in, &err) == HY_OK, "hy_ref_limit_init: %s", err.msg);
    hy_ref_runs(&R, 0, NULL);
    CHECK(hy_ref_in_period(&R, NULL, 0.3) == hy_ref_in_period(&R, R.y_run, 0.3), "hy_ref_in_period yrun NULL: R's");
    hy_ref_limit_free(&R);
    REFUSED(hy_ref_gamma(NULL, &in, 1, t, 2, y, &err), err, "hy_ref_gamma: m must not be NULL");
    REFUSED(hy_ref_gamma(&m, NULL, 1, t, 2, y, &err), err, "in must not be NULL");
    REFUSED(hy_ref_gamma(&m, &in, 1, NULL, 2, y, &err), err, "t must not be NULL");
    REFUSED(hy_ref_gamma(&m, &in, 1, t, 2, NULL, &err), err, "y must not be NULL");
    REFUSED(hy_ref_gamma(&m, &in, NAN, t, 2, y, &err), err, "gamma");
    hy_steady_free(&st);
    hy_input_free(&in);
}

/* ---- hy_ode.h ------------------------------------------------------------- */

static void ode(void)
{
    hy_error err;
    hy_input in = bimodal();
    hy_model m = lugre();
    hy_ode_opts o = NC(hy_ode_defaults()), bad = o;
    double t[2] = {0, 0.5}, y[2], tr[2];
    CHECK(o.work_limit == 1e7, "hy_ode_defaults: a finite work limit");
    CHECK(NC(hy_ode_stepper_names()) && hy_ode_stepper_names()[0], "hy_ode_stepper_names");
    CHECK(NC(hy_ode_stepper_known(NULL)) == 0, "hy_ode_stepper_known(NULL)");
    CHECK(isnan(NC(hy_ode_work_estimate(NULL, &in, 1, &o, 1, NULL))) &&
              isnan(hy_ode_work_estimate(&m, NULL, 1, &o, 1, NULL)) &&
              isnan(hy_ode_work_estimate(&m, &in, 1, NULL, 1, NULL)) &&
              isnan(hy_ode_work_estimate(&m, &in, 1, &o, INFINITY, NULL)),
          "hy_ode_work_estimate with NULL or t_end INFINITY: NaN");
    REFUSED(hy_ode_check_work(NULL, &in, 1, &o, 1, &err), err, "hy_ode_check_work: m must not be NULL");
    REFUSED(hy_ode_check_work(&m, NULL, 1, &o, 1, &err), err, "in must not be NULL");
    REFUSED(hy_ode_check_work(&m, &in, 1, NULL, 1, &err), err, "o must not be NULL");
    REFUSED(hy_ode_check_work(&m, &in, 1, &o, NAN, &err), err, "t_end must be finite");
    const double budgets[] = {INFINITY, NAN, -1};
    for (int i = 0; i < 3; i++) {
        bad.work_limit = budgets[i];
        REFUSED(hy_ode_check_work(&m, &in, 1, &bad, 1, &err), err, "work_limit must be a finite number >= 0");
        REFUSED(hy_ode_solve(&m, &in, 1, &bad, t, 2, y, NULL, &err), err, "work_limit must be a finite number");
    }
    REFUSED(hy_ode_solve(NULL, &in, 1, &o, t, 2, y, NULL, &err), err, "hy_ode_solve: m must not be NULL");
    REFUSED(hy_ode_solve(&m, NULL, 1, &o, t, 2, y, NULL, &err), err, "in must not be NULL");
    REFUSED(hy_ode_solve(&m, &in, 1, NULL, t, 2, y, NULL, &err), err, "o must not be NULL");
    REFUSED(hy_ode_solve(&m, &in, 1, &o, NULL, 2, y, NULL, &err), err, "t must not be NULL");
    REFUSED(hy_ode_solve(&m, &in, 1, &o, t, 2, NULL, NULL, &err), err, "y_out must not be NULL");
    bad = o;
    bad.dense = 1;
    bad.trace_t = tr;
    bad.trace_cap = 2;
    REFUSED(hy_ode_solve(&m, &in, 1, &bad, t, 2, y, NULL, &err), err, "trace_t and trace_y");
    CHECK(hy_ode_solve(&m, &in, 1, &o, t, 2, y, NULL, NULL) == HY_OK, "hy_ode_solve stats NULL, err NULL");
    hy_input_free(&in);
}

/* ---- hy_boucwen.h --------------------------------------------------------- */

static void boucwen(void)
{
    hy_error err;
    hy_boucwen_params p;
    hy_newmark_opts o;
    hy_boucwen_modal md;
    hy_boucwen_state s = {.t = -7};
    double u[64] = {0}, y[64], ic[3] = {0, 0, 0};
    NC(hy_boucwen_params_default(NULL));
    NC(hy_newmark_opts_default(NULL));
    hy_boucwen_params_default(&p);
    hy_newmark_opts_default(&o);
    REFUSED(hy_boucwen_params_validate(NULL, &err), err, "p must not be NULL");
    REFUSED(hy_boucwen_params_set(NULL, "m", 1, &err), err, "p must not be NULL");
    REFUSED(hy_boucwen_params_set(&p, NULL, 1, &err), err, "name must not be NULL");
    REFUSED(hy_boucwen_params_parse(NULL, "m=1", &err), err, "p must not be NULL");
    REFUSED(hy_boucwen_params_parse(&p, NULL, &err), err, "assignment must not be NULL");
    REFUSED(hy_boucwen_table2(NULL, &md, &err), err, "p must not be NULL");
    REFUSED(hy_boucwen_table2(&p, NULL, &err), err, "out must not be NULL");
    REFUSED(hy_newmark_opts_validate(NULL, &err), err, "o must not be NULL");
    NC(hy_boucwen_state_init(NULL, 0, 0, 0, 0, &s));
    hy_boucwen_state_init(&p, 0, 0, 0, 0, NULL);
    CHECK(s.t == -7, "hy_boucwen_state_init p NULL: s untouched");
    hy_boucwen_state_init(&p, 0, 0, 0, 0, &s);
    REFUSED(hy_boucwen_step(NULL, &o, 1e-3, 0, &s, &err), err, "p must not be NULL");
    REFUSED(hy_boucwen_step(&p, NULL, 1e-3, 0, &s, &err), err, "o must not be NULL");
    REFUSED(hy_boucwen_step(&p, &o, 1e-3, 0, NULL, &err), err, "s must not be NULL");
    REFUSED(hy_boucwen_simulate(NULL, &o, 1e-3, u, 4, ic, y, NULL, &err), err, "p must not be NULL");
    REFUSED(hy_boucwen_simulate(&p, NULL, 1e-3, u, 4, ic, y, NULL, &err), err, "o must not be NULL");
    REFUSED(hy_boucwen_simulate(&p, &o, 1e-3, NULL, 4, ic, y, NULL, &err), err, "u must not be NULL");
    REFUSED(hy_boucwen_simulate(&p, &o, 1e-3, u, 4, ic, NULL, NULL, &err), err, "y must not be NULL");
    REFUSED(hy_boucwen_simulate(&p, &o, INFINITY, u, 4, ic, y, NULL, &err), err, "time step h");
    CHECK(hy_boucwen_simulate(&p, &o, 1e-3, u, 4, NULL, y, NULL, NULL) == HY_OK && y[3] == 0,
          "hy_boucwen_simulate ic, z NULL: at rest, stays at rest");
    REFUSED(hy_boucwen_synth(NULL, &o, 750, 2, 0, u, 32, y, &err), err, "p must not be NULL");
    REFUSED(hy_boucwen_synth(&p, NULL, 750, 2, 0, u, 32, y, &err), err, "o must not be NULL");
    REFUSED(hy_boucwen_synth(&p, &o, 750, 2, 0, NULL, 32, y, &err), err, "u_int must not be NULL");
    REFUSED(hy_boucwen_synth(&p, &o, 750, 2, 0, u, 32, NULL, &err), err, "y_out must not be NULL");
    REFUSED(hy_boucwen_synth(&p, &o, NAN, 2, 0, u, 32, y, &err), err, "sampling rate");
    REFUSED(hy_boucwen_synth(&p, &o, 750, 2, 0, u, SIZE_MAX, y, &err), err, "do not fit in memory");
    REFUSED(hy_boucwen_synth_periodic(NULL, &o, 750, 2, 0, u, 32, 1, y, &err), err, "p must not be NULL");
    REFUSED(hy_boucwen_synth_periodic(&p, &o, 750, 2, 0, NULL, 32, 1, y, &err), err, "u_period must not be NULL");
    REFUSED(hy_boucwen_synth_periodic(&p, &o, 750, 2, 0, u, 32, 1, NULL, &err), err, "y_out must not be NULL");
    REFUSED(hy_boucwen_synth_periodic_kept(&p, NULL, 750, 2, 0, u, 32, 0, 1, y, &err), err, "o must not be NULL");
    REFUSED(hy_boucwen_synth_periodic_kept(&p, &o, 750, 2, 0, u, 32, 0, SIZE_MAX / 8, y, &err), err,
            "do not fit in memory");
}

/* ---- hy_signal.h ---------------------------------------------------------- */

static void signals(void)
{
    hy_error err;
    hy_multisine ms;
    hy_sweep sw;
    double x[32], y[64], b[HY_DECIMATE_TAPS];
    size_t kmin, kmax, ny = 0;
    for (int i = 0; i < 32; i++)
        x[i] = sin(0.3 * i);
    NC(hy_rng_seed(NULL, 1));
    CHECK(isnan(NC(hy_rng_uniform(NULL))) && isnan(NC(hy_rng_normal(NULL))), "hy_rng_uniform, _normal of NULL: NaN");
    NC(hy_multisine_default(NULL));
    NC(hy_sweep_default(NULL));
    NC(hy_sweep_validation(NULL));
    hy_multisine_default(&ms);
    hy_sweep_default(&sw);
    REFUSED(hy_multisine_lines(NULL, &kmin, &kmax, &err), err, "ms must not be NULL");
    CHECK(hy_multisine_lines(&ms, NULL, NULL, &err) == HY_OK, "hy_multisine_lines kmin, kmax NULL");
    REFUSED(hy_multisine_design(NULL, 1, y, &err), err, "ms must not be NULL");
    REFUSED(hy_multisine_design(&ms, 1, NULL, &err), err, "u must not be NULL");
    CHECK(NC(hy_sweep_length(NULL, 750)) == 0 && hy_sweep_length(&sw, INFINITY) == 0, "hy_sweep_length: NULL, fs inf");
    REFUSED(hy_sweep_fill(NULL, 750, y, 4, &err), err, "sw must not be NULL");
    REFUSED(hy_sweep_fill(&sw, 750, NULL, 4, &err), err, "u must not be NULL");
    REFUSED(hy_sweep_fill(&sw, NAN, y, 4, &err), err, "sampling rate");
    REFUSED(hy_sine_fill(1, 1, 10, NULL, 4, &err), err, "u must not be NULL");
    REFUSED(hy_sine_fill(NAN, 1, 10, y, 4, &err), err, "amplitude");
    double *su = (double *)x, fs;
    size_t sn = 5;
    REFUSED(hy_signal_read(NULL, &su, &sn, &fs, &err), err, "path must not be NULL");
    CHECK(su == NULL && sn == 0, "hy_signal_read: *u NULL, *n 0 after a refusal");
    REFUSED(hy_signal_read("x", NULL, &sn, &fs, &err), err, "u must not be NULL");
    REFUSED(hy_signal_read("x", &su, NULL, &fs, &err), err, "n must not be NULL");
    /* what may be NULL: hy_signal_read's fs, hy_file_read's real and why */
    char path[4200], *text = NULL;
    size_t tlen = 0;
    FILE *f = fopen(test_tmppath(path, sizeof path, "signal.txt"), "w");
    CHECK(f && fputs("1\n2\n3\n", f) >= 0 && fclose(f) == 0, "cannot write %s", path);
    CHECK(hy_signal_read(path, &su, &sn, NULL, &err) == HY_OK && sn == 3 && su[2] == 3, "hy_signal_read fs NULL: %s",
          err.msg);
    free(su);
    CHECK(hy_file_read(path, 100, &text, &tlen, NULL, NULL, 0) == 0 && tlen == 6 && !strcmp(text, "1\n2\n3\n"),
          "hy_file_read real NULL, why NULL");
    free(text);
    REFUSED(hy_signal_upsample_fft(NULL, 4, 2, y, &err), err, "x must not be NULL");
    REFUSED(hy_signal_upsample_fft(x, 4, 2, NULL, &err), err, "y must not be NULL");
    REFUSED(hy_signal_upsample_fft(x, 4, SIZE_MAX / 2, y, &err), err, "do not fit in memory");
    REFUSED(hy_signal_upsample_sinc(NULL, 4, 2, y, &err), err, "x must not be NULL");
    REFUSED(hy_signal_upsample_sinc(x, 4, 2, NULL, &err), err, "y must not be NULL");
    REFUSED(hy_signal_upsample_sinc(x, 4, SIZE_MAX / 2, y, &err), err, "do not fit in memory");
    REFUSED(hy_signal_fft_forward(NULL, 4, &err), err, "x must not be NULL");
    REFUSED(hy_signal_fft_forward(x, 0, &err), err, "n >= 1");
    REFUSED(hy_signal_fft_inverse(NULL, 4, &err), err, "x must not be NULL");
    REFUSED(hy_signal_fft_inverse(x, 0, &err), err, "n >= 1");
    b[0] = -7;
    NC(hy_fir1_lowpass(2, NULL));
    hy_fir1_lowpass(1, b);
    hy_fir1_lowpass(0, b);
    CHECK(b[0] == -7, "hy_fir1_lowpass r < 2: nothing written");
    REFUSED(hy_signal_decimate(NULL, 32, 2, y, &err), err, "x must not be NULL");
    REFUSED(hy_signal_decimate(x, 32, 2, NULL, &err), err, "y must not be NULL");
    REFUSED(hy_signal_decimate_stages(NULL, 32, 2, 1, y, &ny, &err), err, "x must not be NULL");
    REFUSED(hy_signal_decimate_stages(x, 32, 2, 1, NULL, &ny, &err), err, "y must not be NULL");
    CHECK(hy_signal_decimate_stages(x, 32, 4, 1, y, NULL, &err) == HY_OK, "decimate_stages ny NULL: %s", err.msg);
    /* 2^61 - 1 is prime: a staged factorisation by trial division to r took 2^61 steps */
    CHECK(NC(hy_signal_decimate_reach(((size_t)1 << 61) - 1, 1)) == 15 && hy_signal_decimate_reach(0, 1) == 0,
          "hy_signal_decimate_reach of a large prime (one stage, reach 15) and of 0");
    REFUSED(hy_signal_add_noise(NULL, 4, 1, 10, 100, 1, &err), err, "out must not be NULL");
    CHECK(hy_signal_add_noise(NULL, 0, 1, 10, 100, 1, &err) != HY_EINVAL || !strstr(err.msg, "NULL"),
          "hy_signal_add_noise out NULL with n 0 is not a NULL refusal");
    REFUSED(hy_signal_add_noise(y, 4, NAN, 10, 100, 1, &err), err, "rms");
    CHECK(isnan(NC(hy_signal_erms(NULL, x, 3))) && isnan(hy_signal_erms(x, NULL, 3)) &&
              hy_signal_erms(NULL, NULL, 0) == 0,
          "hy_signal_erms with NULL");
    CHECK(isnan(NC(hy_signal_rms(NULL, 3))) && hy_signal_rms(NULL, 0) == 0, "hy_signal_rms with NULL");
}

/* ---- hy_rateind.h: a model whose output is its input (y = u) -------------- */

static int id_init(const void *par, void *st, double u0, double out[HY_RI_NOUT], hy_error *err)
{
    (void)par, (void)err;
    *(double *)st = u0;
    out[0] = u0, out[1] = out[2] = NAN;
    return HY_OK;
}

static int id_apply(const void *par, void *st, double u, double out[HY_RI_NOUT], hy_error *err)
{
    return id_init(par, st, u, out, err);
}

static const hy_rateind_type id_type = {"identity", sizeof(double), 0, id_init, id_apply, NULL, NULL, NULL};

static int id_fn(void *ctx, double u, double *y, hy_error *err)
{
    (void)ctx, (void)err;
    *y = u;
    return HY_OK;
}

static void rateind(void)
{
    hy_error err;
    hy_input in = bimodal();
    hy_rateind m, c, freed;
    double t[2] = {0, 0.5}, y[2], e[4];
    int periods = -1;
    REFUSED(hy_rateind_drive(NULL, t, 2, id_fn, NULL, y, &err), err, "in must not be NULL");
    REFUSED(hy_rateind_drive(&in, t, 2, NULL, NULL, y, &err), err, "fn must not be NULL");
    REFUSED(hy_rateind_drive(&in, t, 2, id_fn, NULL, NULL, &err), err, "y must not be NULL");
    REFUSED(hy_rateind_drive(&in, NULL, 2, id_fn, NULL, y, &err), err, "t must not be NULL");
    CHECK(hy_rateind_drive(&in, t, 2, id_fn, NULL, y, &err) == HY_OK && y[1] == hy_input_u(&in, 0.5),
          "hy_rateind_drive ctx NULL: %s", err.msg);
    REFUSED(hy_rateind_bimodal(NULL, e, &err), err, "in must not be NULL");
    REFUSED(hy_rateind_bimodal(&in, NULL, &err), err, "e must not be NULL");
    REFUSED(hy_rateind_alloc(NULL, &id_type, NULL, 0, &err), err, "m must not be NULL");
    REFUSED(hy_rateind_alloc(&m, NULL, NULL, 0, &err), err, "type must not be NULL");
    CHECK(hy_rateind_alloc(&m, &id_type, NULL, 0, &err) == HY_OK && hy_rateind_alloc(&freed, &id_type, NULL, 0, &err) ==
              HY_OK, "hy_rateind_alloc par NULL: %s", err.msg);
    hy_rateind_free(&freed);
    REFUSED(hy_rateind_apply(NULL, 1, &err), err, "m must not be NULL");
    REFUSED(hy_rateind_apply(&freed, 1, &err), err, "m is not allocated");
    REFUSED(hy_rateind_clone(NULL, &m, &err), err, "dst must not be NULL");
    REFUSED(hy_rateind_clone(&c, NULL, &err), err, "src must not be NULL");
    CHECK(c.st == NULL, "hy_rateind_clone: dst->st NULL after a refusal");
    REFUSED(hy_rateind_clone(&c, &freed, &err), err, "src is not allocated");
    NC(hy_rateind_free(NULL));
    REFUSED(hy_rateind_settle(NULL, &in, 1e-9, 10, &periods, &err), err, "m must not be NULL");
    REFUSED(hy_rateind_settle(&m, NULL, 1e-9, 10, &periods, &err), err, "in must not be NULL");
    REFUSED(hy_rateind_settle(&m, &in, NAN, 10, &periods, &err), err, "tol");
    REFUSED(hy_rateind_settle(&m, &in, 1e-9, 0, &periods, &err), err, "max_periods");
    CHECK(hy_rateind_settle(&m, &in, 1e-9, 10, NULL, &err) == HY_OK, "hy_rateind_settle periods NULL: %s", err.msg);
    double *const rows[HY_RI_NOUT] = {y, NULL, NULL};
    REFUSED(hy_rateind_sample(NULL, &in, 0, t, 2, rows, &err), err, "m must not be NULL");
    REFUSED(hy_rateind_sample(&m, NULL, 0, t, 2, rows, &err), err, "in must not be NULL");
    REFUSED(hy_rateind_sample(&m, &in, 0, NULL, 2, rows, &err), err, "x must not be NULL");
    CHECK(hy_rateind_sample(&m, &in, 0, t, 2, NULL, &err) == HY_OK, "hy_rateind_sample rows NULL: %s", err.msg);
    hy_rateind_free(&m);
    hy_input_free(&in);
}

/* ---- hy_preisach.h -------------------------------------------------------- */

static void preisach(void)
{
    hy_error err;
    hy_input in = bimodal();
    hy_preisach p, q;
    hy_preisach_mem mem, empty;
    hy_minor_loop L;
    memset(&empty, 0, sizeof empty);
    hy_preisach_table none = {.n = 2}, zero = {0};
    double t[2] = {0, 0.5}, u[2] = {0, 1}, y[2], v;
    CHECK(isnan(NC(hy_preisach_table_everett(NULL, 1, 0))) && isnan(hy_preisach_table_everett(&none, 1, 0)) &&
              isnan(NC(hy_preisach_table_demag(&none, 1))) && isnan(NC(hy_preisach_table_area(NULL, 0, 1))),
          "the table sums of NULL or a table without arrays: NaN");
    CHECK(hy_preisach_table_area(&zero, 0, 1) == 0, "the table sums of an empty table: 0");
    CHECK(NC(hy_preisach_dist_name(-1)) == NULL && hy_preisach_dist_name(99) == NULL, "dist_name out of range");
    CHECK(NC(hy_preisach_dist_find(NULL)) == -1, "dist_find(NULL)");
    REFUSED(hy_preisach_init(NULL, 0, 1, 0.2, -1, 0.2, 1, &err), err, "p must not be NULL");
    REFUSED(hy_preisach_init(&q, 0, NAN, 0.2, -1, 0.2, 1, &err), err, "alpha");
    REFUSED(hy_preisach_symmetric(NULL, 0, 0.5, 0.2, 1, &err), err, "p must not be NULL");
    CHECK(hy_preisach_symmetric(&p, HY_PREISACH_GAUSSIAN, 0.5, 0.2, 1, &err) == HY_OK, "symmetric: %s", err.msg);
    REFUSED(hy_preisach_tabulated(NULL, &zero, &err), err, "p must not be NULL");
    REFUSED(hy_preisach_tabulated(&q, NULL, &err), err, "t must not be NULL");
    REFUSED(hy_preisach_tabulated(&q, &none, &err), err, "arrays must not be NULL");
    REFUSED(hy_preisach_support(NULL, 1, &err), err, "p must not be NULL");
    q = p;
    REFUSED(hy_preisach_support(&q, NAN, &err), err, "hs");
    REFUSED(hy_preisach_everett(NULL, 1, 0, &v, &err), err, "p must not be NULL");
    REFUSED(hy_preisach_everett(&p, 1, 0, NULL, &err), err, "E must not be NULL");
    REFUSED(hy_preisach_demag_output(NULL, &v, &err), err, "p must not be NULL");
    REFUSED(hy_preisach_demag_output(&p, NULL, &err), err, "y must not be NULL");
    REFUSED(hy_preisach_mem_init(NULL, &p, 0, &err), err, "m must not be NULL");
    REFUSED(hy_preisach_mem_init(&mem, NULL, 0, &err), err, "p must not be NULL");
    REFUSED(hy_preisach_mem_init(&mem, &p, INFINITY, &err), err, "finite");
    REFUSED(hy_preisach_mem_apply(NULL, 0, &v, &err), err, "m must not be NULL");
    REFUSED(hy_preisach_mem_apply(&empty, 0, &v, &err), err, "m is empty");
    CHECK(hy_preisach_mem_init(&mem, &p, 0, &err) == HY_OK && hy_preisach_mem_apply(&mem, 1, NULL, &err) == HY_OK,
          "hy_preisach_mem_apply y NULL: %s", err.msg);
    hy_preisach_mem_free(&mem);
    NC(hy_preisach_mem_free(NULL));
    REFUSED(hy_preisach_apply(NULL, u, 2, y, &err), err, "p must not be NULL");
    REFUSED(hy_preisach_apply(&p, NULL, 2, y, &err), err, "u must not be NULL");
    REFUSED(hy_preisach_apply(&p, u, 2, NULL, &err), err, "y must not be NULL");
    CHECK(hy_preisach_apply(&p, NULL, 0, NULL, &err) == HY_OK, "hy_preisach_apply of no samples, u and y NULL");
    REFUSED(hy_preisach_drive(NULL, &in, t, 2, y, &err), err, "p must not be NULL");
    REFUSED(hy_preisach_drive(&p, NULL, t, 2, y, &err), err, "in must not be NULL");
    REFUSED(hy_preisach_drive(&p, &in, NULL, 2, y, &err), err, "t must not be NULL");
    REFUSED(hy_preisach_drive(&p, &in, t, 2, NULL, &err), err, "y must not be NULL");
    REFUSED(hy_preisach_loop_area(NULL, -1, 1, &v, &err), err, "p must not be NULL");
    REFUSED(hy_preisach_loop_area(&p, -1, 1, NULL, &err), err, "area must not be NULL");
    REFUSED(hy_preisach_loop_area(&p, NAN, 1, &v, &err), err, "finite lo < hi");
    REFUSED(hy_preisach_minor_loop(NULL, &in, &L, &err), err, "p must not be NULL");
    REFUSED(hy_preisach_minor_loop(&p, NULL, &L, &err), err, "in must not be NULL");
    REFUSED(hy_preisach_minor_loop(&p, &in, NULL, &err), err, "out must not be NULL");
    hy_input_free(&in);
}

/* ---- hy_jiles.h ----------------------------------------------------------- */

static void jiles(void)
{
    hy_error err;
    hy_input in = bimodal();
    hy_jiles j;
    hy_jiles_state s = {.H = -7};
    hy_jiles_loop lp;
    hy_minor_loop L;
    double t[2] = {0, 0.5}, M[2];
    /* L(0) = 0 and L'(0) = 1/3: the limits the series gives exactly */
    CHECK(NC(hy_langevin(0)) == 0 && fabs(NC(hy_langevin_d(0)) - 1.0 / 3) <= DBL_EPSILON && isnan(hy_langevin(NAN)),
          "hy_langevin, _d at 0 and NaN");
    REFUSED(hy_jiles_init(NULL, 1.6e6, 1100, 400, 0.2, 1.6e-3, &err), err, "j must not be NULL");
    REFUSED(hy_jiles_init(&j, NAN, 1100, 400, 0.2, 1.6e-3, &err), err, "Ms");
    REFUSED(hy_jiles_validate(NULL, &err), err, "j must not be NULL");
    CHECK(hy_jiles_init(&j, 1.6e6, 1100, 400, 0.2, 1.6e-3, &err) == HY_OK, "hy_jiles_init: %s", err.msg);
    REFUSED(hy_jiles_input_check(NULL, 1, 0, &err), err, "j must not be NULL");
    REFUSED(hy_jiles_input_check(&j, INFINITY, 0, &err), err, "finite");
    NC(hy_jiles_state_init(NULL, &s, 0));
    hy_jiles_state_init(&j, NULL, 0);
    CHECK(s.H == -7, "hy_jiles_state_init j NULL: s untouched");
    CHECK(isnan(NC(hy_jiles_b(NULL))) && isnan(NC(hy_jiles_dmdh(NULL, 0, 0, 1))), "hy_jiles_b, _dmdh of NULL: NaN");
    hy_jiles_state_init(&j, &s, 0);
    REFUSED(hy_jiles_apply(NULL, &s, 1, NULL, &err), err, "j must not be NULL");
    REFUSED(hy_jiles_apply(&j, NULL, 1, NULL, &err), err, "s must not be NULL");
    REFUSED(hy_jiles_apply(&j, &s, NAN, NULL, &err), err, "finite");
    REFUSED(hy_jiles_drive(NULL, &in, t, 2, M, NULL, NULL, &err), err, "j must not be NULL");
    REFUSED(hy_jiles_drive(&j, NULL, t, 2, M, NULL, NULL, &err), err, "in must not be NULL");
    REFUSED(hy_jiles_drive(&j, &in, NULL, 2, M, NULL, NULL, &err), err, "t must not be NULL");
    CHECK(hy_jiles_drive(&j, &in, t, 2, NULL, NULL, NULL, &err) == HY_OK, "hy_jiles_drive M, B, stats NULL: %s",
          err.msg);
    REFUSED(hy_jiles_major_loop(NULL, 1e3, &lp, &err), err, "j must not be NULL");
    REFUSED(hy_jiles_major_loop(&j, 1e3, NULL, &err), err, "out must not be NULL");
    REFUSED(hy_jiles_major_loop(&j, INFINITY, &lp, &err), err, "hmax");
    REFUSED(hy_jiles_minor_loop(NULL, &in, &L, &err), err, "j must not be NULL");
    REFUSED(hy_jiles_minor_loop(&j, NULL, &L, &err), err, "in must not be NULL");
    REFUSED(hy_jiles_minor_loop(&j, &in, NULL, &err), err, "out must not be NULL");
    hy_input_free(&in);
}

/* ---- hy_fit.h ------------------------------------------------------------- */

static int line_resid(const double *th, double *r, void *ctx)
{
    (void)ctx;
    for (int i = 0; i < 3; i++)
        r[i] = th[0] * i - 2.0 * i;
    return 0;
}

static void fit(void)
{
    hy_error err;
    hy_fit_param prm[1] = {{"a", 0, 4, HY_FIT_LINEAR}};
    double x0[1] = {1}, th[1] = {2}, x[8];
    hy_fit_problem pb = {.n = 3, .p = 1, .param = prm, .f = line_resid, .start = x0};
    hy_fit_opts o;
    hy_fit_result res;
    NC(hy_fit_opts_default(NULL));
    hy_fit_opts_default(&o);
    REFUSED(hy_fit_run(NULL, &o, &res, &err), err, "pb must not be NULL");
    REFUSED(hy_fit_run(&pb, NULL, &res, &err), err, "o must not be NULL");
    REFUSED(hy_fit_run(&pb, &o, NULL, &err), err, "res must not be NULL");
    o.xtol = INFINITY;
    REFUSED(hy_fit_run(&pb, &o, &res, &err), err, "tolerances finite");
    REFUSED(hy_fit_evaluate(NULL, th, &res, &err), err, "pb must not be NULL");
    REFUSED(hy_fit_evaluate(&pb, NULL, &res, &err), err, "theta must not be NULL");
    REFUSED(hy_fit_evaluate(&pb, th, NULL, &err), err, "res must not be NULL");
    NC(hy_fit_result_free(NULL));
    REFUSED(hy_fit_design(1, NULL, 4, 1, x, &err), err, "param must not be NULL");
    REFUSED(hy_fit_design(1, prm, 4, 1, NULL, &err), err, "x must not be NULL");
    REFUSED(hy_fit_design(2, prm, SIZE_MAX / 2, 1, x, &err), err, "do not fit in memory");
    CHECK(isnan(NC(hy_fit_theta(NULL, 0))) && isnan(NC(hy_fit_u(NULL, 1))), "hy_fit_theta, _u of NULL: NaN");
    /* a report with a NULL argument prints nothing */
    char *text = NULL;
    size_t len = 0;
    FILE *f = open_memstream(&text, &len);
    CHECK(hy_fit_evaluate(&pb, th, &res, &err) == HY_OK, "hy_fit_evaluate: %s", err.msg);
    NC(hy_fit_report(NULL, &pb, &res));
    hy_fit_report(f, NULL, &res);
    hy_fit_report(f, &pb, NULL);
    fflush(f);
    CHECK(len == 0, "hy_fit_report with a NULL argument prints nothing (%zu bytes)", len);
    hy_fit_report(f, &pb, &res);
    fclose(f);
    CHECK(len > 0 && strstr(text, "a"), "hy_fit_report of a result prints it");
    free(text);
    hy_fit_result_free(&res);
}

int tc_core(void)
{
    status_file();
    model_input();
    limit_loops();
    ode();
    boucwen();
    signals();
    rateind();
    preisach();
    jiles();
    fit();
    return tu_finish("core contracts");
}
