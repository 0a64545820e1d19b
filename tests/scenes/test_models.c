/* SPDX-License-Identifier: MIT */
/* test_models.c: the model table and the rate-independent models in scenes.
 *  - the table and the schema agree: every [model] kind has one entry, every
 *    key an entry reads is a schema row of [model], every quantity it draws a
 *    value of series.quantity;
 *  - Fig. 1 (Jiles-Atherton): the minor loop the scene finds equals the one
 *    hy_jiles_minor_loop computes by its own route (driving the bimodal input
 *    period after period, hy_jiles.c), and the major loop's coercive field and
 *    remanence equal hy_jiles_major_loop's for a symmetric drive;
 *  - Preisach: the loops close bit for bit (return-point memory), their areas
 *    are the closed-form loop areas, and the transient equals hy_preisach_drive;
 *  - every input kind drives both models; refusals name the key (file:line:col);
 *  - the Bouc-Wen operator against RK4 in long double; the five-model panel
 *    figure (only Preisach closes its minor loop). */
#include <gsl/gsl_errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "../core/tutil.h"
#include "../tmpdir.h"
#include "hy_jiles.h"
#include "hy_preisach.h"
#include "scene_model.h"
#include "scene_run.h"

static const char *SRC;

static const char *JA = "[model]\nkind = jiles-atherton\n"
                        "[input]\nkind = bimodal\numin1 = -1500\numin2 = -1100\numax1 = 500\numax2 = 1500\n"
                        "[figure]\nkind = loop\n"
                        "[series major]\ndata = major\n[series minor]\ndata = minor\n";
static const char *PR = "[model]\nkind = preisach\npr_hc = 0.3\npr_width = 0.25\n"
                        "[input]\nkind = bimodal\numin1 = -1\numin2 = -0.4\numax1 = 0.5\numax2 = 1\n"
                        "[figure]\nkind = loop\n"
                        "[series major]\ndata = major\n[series minor]\ndata = minor\n";

/* Loads and computes text (+ overrides); 0 on success, else the status. */
static int run_text(const char *name, const char *text, char **sets, size_t nsets, hy_scene_run *r, hy_error *err)
{
    int rc = hy_scene_run_load_text(r, name, text, strlen(text), sets, nsets, NULL, err);
    if (rc)
        return rc;
    rc = hy_scene_run_compute(r, NULL, err);
    if (rc)
        hy_scene_run_free(r);
    return rc;
}

static const hy_run_series *find(const hy_scene_run *r, const char *name)
{
    for (size_t i = 0; i < r->nseries; i++)
        if (!strcmp(r->series[i].name, name))
            return &r->series[i];
    return NULL;
}

static void table_matches_schema(void)
{
    size_t nsec;
    const hy_scene_section_spec *spec = hy_scene_schema(&nsec);
    const hy_scene_section_spec *model = &spec[hy_scene_schema_section("model")];
    const hy_scene_section_spec *series = &spec[hy_scene_schema_section("series")];
    int kind = hy_scene_schema_key(hy_scene_schema_section("model"), "kind");
    int quantity = hy_scene_schema_key(hy_scene_schema_section("series"), "quantity");
    const char *const *kinds = model->keys[kind].enums;
    size_t nk = 0, nt = 0;
    for (; kinds[nk]; nk++)
        CHECK(hy_scene_model_find(kinds[nk]) != NULL, "model kind %s has no table entry", kinds[nk]);
    for (; hy_scene_models[nt]; nt++) {
        const hy_scene_model *mt = hy_scene_models[nt];
        CHECK(mt->load && mt->estimate && mt->compute, "%s: a stage is missing", mt->name);
        /* read NULL: its own rows' struct is its parameters (hy_scene_model_read); shared keys need read */
        CHECK(!mt->ri || (mt->ri_par_size && (mt->read || !mt->params)),
              "%s: a rate-independent entry needs its parameters' size, and read unless its own rows are them", mt->name);
        const char *p;
        size_t np = 0;
        for (; (p = hy_scene_model_param(mt, np)); np++)
            CHECK(hy_scene_schema_key(hy_scene_schema_section("model"), p) >= 0,
                  "%s reads '%s', which is no [model] key of the schema", mt->name, p);
        CHECK(np > 0, "%s reads no [model] key", mt->name);
        for (size_t i = 0; mt->quantities[i]; i++) {
            int found = 0;
            for (size_t j = 0; series->keys[quantity].enums[j]; j++)
                found |= !strcmp(series->keys[quantity].enums[j], mt->quantities[i]);
            CHECK(found, "%s draws quantity '%s', which series.quantity does not list", mt->name, mt->quantities[i]);
        }
    }
    CHECK(nk == nt, "%zu schema kinds, %zu table entries", nk, nt);
}

/* The scene's loops against hy_jiles_minor_loop (periods driven by its own
 * loop in hy_jiles.c, areas from its own path integral): both settle to
 * 1e-11..1e-12 of the range, so they agree to about 1e-10 relative. */
static void jiles_fig1(void)
{
    hy_scene_run r;
    hy_error err;
    if (run_text("ja.scene", JA, NULL, 0, &r, &err)) {
        CHECK(0, "ja scene: %s", err.msg);
        return;
    }
    CHECK(r.have_loops && r.loops.nminor == 1, "one minor loop (got %zu)", r.loops.nminor);
    hy_jiles j;
    hy_jiles_init(&j, 1.6e6, 1100, 400, 0.2, 1.6e-3, &err);
    hy_minor_loop ref;
    int rc = hy_jiles_minor_loop(&j, &r.input, &ref, &err);
    CHECK(rc == 0, "hy_jiles_minor_loop: %s", err.msg);
    if (!rc && r.loops.nminor == 1) {
        const hy_loop *m = &r.loops.minor[0];
        CHECK(m->u_start == 500 && m->u_turn == -1100, "minor loop from 500 to -1100 A/m (%g, %g)", m->u_start,
              m->u_turn);
        CHECK_CLOSE(m->y_start, ref.y_start, 1e-9, "minor loop B at its start (T)");
        CHECK_CLOSE(m->y_close, ref.y_close, 1e-9, "minor loop B at its close (T)");
        CHECK_CLOSE(m->area, ref.area, 1e-8 * ref.area, "minor loop area (J/m^3)");
        CHECK_CLOSE(r.loops.area_period, ref.area_period, 1e-8 * ref.area_period, "energy per cycle (J/m^3)");
        CHECK(m->y_close != m->y_start, "Jiles-Atherton has no exact return-point memory");
        printf("jiles fig1: minor area %.10g J/m^3 (ref %.10g), per cycle %.10g\n", m->area, ref.area,
               r.loops.area_period);
    }
    const hy_run_series *mi = find(&r, "minor");
    CHECK(mi && mi->n == 2001 && isnan(mi->x[2000]), "minor series: one loop of 2000 points and a gap");
    if (mi) /* first point: the loop's start (H, B) */
        CHECK(mi->x[0] == 500 && fabs(mi->y[0] - r.loops.minor[0].y_start) < 1e-15, "minor series starts at the loop's start");
    hy_scene_run_free(&r);

    /* a symmetric sine drive of +-10 kA/m: coercive field and remanence of the
       drawn major loop (linear interpolation between samples 5 A/m apart)
       against hy_jiles_major_loop's root finding (Hc = 314.03 A/m, Br = 0.62388 T) */
    char *sets[] = {"input.kind=sine", "input.amp=10000", "compute.points=8000"};
    if (run_text("ja_sine.scene", JA, sets, 3, &r, &err)) {
        CHECK(0, "ja sine: %s", err.msg);
        return;
    }
    hy_jiles_loop L;
    CHECK(hy_jiles_major_loop(&j, 1e4, &L, &err) == 0, "major loop: %s", err.msg);
    const hy_run_series *ma = find(&r, "major");
    double hc = NAN, br = NAN;
    for (size_t i = 0; ma && i + 1 < ma->n; i++) {
        double x0 = ma->x[i], x1 = ma->x[i + 1], y0 = ma->y[i], y1 = ma->y[i + 1];
        if (!(x1 < x0)) /* the descending branch only */
            continue;
        if (y0 > 0 && y1 <= 0)
            hc = x0 + (x1 - x0) * y0 / (y0 - y1);
        if (x0 > 0 && x1 <= 0)
            br = y0 + (y1 - y0) * x0 / (x0 - x1);
    }
    CHECK_CLOSE(-hc, L.hc, 0.05, "coercive field (A/m) of the drawn loop");
    CHECK_CLOSE(br, L.br, 1e-4, "remanence (T) of the drawn loop");
    printf("jiles major loop: Hc %.4f A/m (core %.4f), Br %.6f T (core %.6f)\n", -hc, L.hc, br, L.br);
    hy_scene_run_free(&r);
}

static void preisach_loops(void)
{
    hy_scene_run r;
    hy_error err;
    if (run_text("pr.scene", PR, NULL, 0, &r, &err)) {
        CHECK(0, "preisach scene: %s", err.msg);
        return;
    }
    hy_preisach p;
    hy_preisach_symmetric(&p, HY_PREISACH_GAUSSIAN, 0.3, 0.25, 1, &err);
    double amin, amaj;
    hy_preisach_loop_area(&p, -0.4, 0.5, &amin, &err);
    hy_preisach_loop_area(&p, -1, 1, &amaj, &err);
    CHECK(r.loops.nminor == 1, "one minor loop");
    if (r.loops.nminor == 1) {
        const hy_loop *m = &r.loops.minor[0];
        CHECK(m->y_close == m->y_start, "return-point memory: %.17g vs %.17g", m->y_close, m->y_start);
        CHECK(m->area == amin, "minor area is the closed form: %.17g vs %.17g", m->area, amin);
        CHECK(m->own_area == amin, "nothing nested in the minor loop");
        CHECK(r.loops.major.own_area == amaj, "major loop's own area: %.17g vs %.17g", r.loops.major.own_area, amaj);
        CHECK(r.loops.area_period == amaj + amin, "energy per cycle = both areas");
    }
    hy_scene_run_free(&r);

    /* the transient over two periods: bit for bit hy_preisach_drive at the same times */
    const char *tr = "[model]\nkind = preisach\n[input]\nkind = bimodal\numin1 = -1\numin2 = -0.4\numax1 = 0.5\n"
                     "umax2 = 1\n[compute]\ncycles = 2\npoints = 50\n[series y]\ndata = transient\n";
    if (run_text("pr2.scene", tr, NULL, 0, &r, &err)) {
        CHECK(0, "preisach transient: %s", err.msg);
        return;
    }
    hy_preisach_symmetric(&p, HY_PREISACH_GAUSSIAN, 0.5, 0.2, 1, &err);
    const hy_run_series *y = find(&r, "y");
    double *ref = y ? malloc(y->n * sizeof *ref) : NULL;
    if (y && ref && !hy_preisach_drive(&p, &r.input, y->x, y->n, ref, &err)) {
        size_t bad = 0;
        for (size_t i = 0; i < y->n; i++)
            bad += y->y[i] != ref[i];
        CHECK(bad == 0, "preisach transient: %zu of %zu samples differ from hy_preisach_drive", bad, y->n);
    } else
        CHECK(0, "preisach transient reference");
    free(ref);
    hy_scene_run_free(&r);
}

/* Every input hystviz has drives both models; outputs finite, loops found. */
static void every_input(void)
{
    char path[4200];
    FILE *f = fopen(test_tmppath(path, sizeof path, "u.txt"), "w");
    CHECK(f != NULL, "cannot write %s", path);
    if (!f)
        return;
    fputs("0 0\n1 1\n2 -0.3\n3 0.4\n4 -1\n5 0\n", f);
    fclose(f);
    char scene[4200];
    test_tmppath(scene, sizeof scene, "m.scene");
    const char *inputs[] = {"kind = bimodal\numin1 = -1\numin2 = -0.2\numax1 = 0.4\numax2 = 1\n",
                            "kind = multimodal\nextrema = -1, 0.6, -0.3, 1, -0.5, 0.2\n",
                            "kind = sine\namp = 1.2\nperiod = 2\n", "kind = triangle\nmin = -1\nmax = 1\n",
                            "kind = pwl\npoints = 0, 0, 1, 1, 2, -1, 2.5, 0.3, 3, -0.2, 4, 0\n",
                            "kind = file\nfile = \"u.txt\"\n"};
    const char *models[] = {"kind = jiles-atherton\nja_k = 0.4\nja_a = 1.1\nja_ms = 1.6e3\n",
                            "kind = preisach\n",
                            "kind = jiles-atherton\nja_k = 0.4\nja_a = 1.1\nja_ms = 1.6e3\nja_variant = jtd1992\n",
                            "kind = preisach\npr_start = demagnetised\npr_support = triangle\npr_hs = 0.9\n"};
    for (size_t m = 0; m < sizeof models / sizeof *models; m++)
        for (size_t i = 0; i < sizeof inputs / sizeof *inputs; i++) {
            char text[1024];
            snprintf(text, sizeof text,
                     "[model]\n%s[input]\n%s[compute]\npoints = 200\ncycles = 2\n[figure]\nkind = loop\n"
                     "[series a]\ndata = major\n[series b]\ndata = ysteady\n[series c]\ndata = transient\n"
                     "[series d]\ndata = yk\nk = 1\n[series e]\ndata = ystar\n",
                     models[m], inputs[i]);
            hy_scene_run r;
            hy_error err;
            if (run_text(scene, text, NULL, 0, &r, &err)) {
                CHECK(0, "model %zu input %zu: %s", m, i, err.msg);
                continue;
            }
            size_t nonfinite = 0, total = 0;
            for (size_t s = 0; s < r.nseries; s++)
                for (size_t k = 0; k < r.series[s].n; k++, total++)
                    nonfinite += !isnan(r.series[s].x[k]) && (!isfinite(r.series[s].y[k]) || !isfinite(r.series[s].x[k]));
            CHECK(nonfinite == 0 && total > 800, "model %zu input %zu: %zu of %zu points not finite", m, i, nonfinite,
                  total);
            CHECK(r.have_loops && isfinite(r.loops.area_period) && r.loops.area_period > 0,
                  "model %zu input %zu: energy per cycle %g", m, i, r.loops.area_period);
            hy_scene_run_free(&r);
        }
}

static void refused(const char *text, int at_load, const char *want)
{
    hy_scene_run r;
    hy_error err = {0};
    int rc = hy_scene_run_load_text(&r, "bad.scene", text, strlen(text), NULL, 0, NULL, &err);
    int loaded = rc == 0;
    if (!rc) {
        rc = hy_scene_run_compute(&r, NULL, &err);
        hy_scene_run_free(&r);
    }
    CHECK(rc != 0 && (!at_load || !loaded) && strstr(err.msg, want), "expected%s '%s', got %d: %s",
          at_load ? " at load" : "", want, rc, rc ? err.msg : "");
}

/* Loop areas follow one convention (docs/SCENES.md, "Loop areas"): the
 * printed area is the energy a loop dissipates, ∮ y du for the models whose
 * output is a force against the input (Dahl, LuGre, the Bouc-Wen operator:
 * clockwise loops) and ∮ u dy = -∮ y du for those whose output answers an
 * input field (Jiles-Atherton, Preisach, play: counter-clockwise).  Each
 * model's printed energy per cycle against ∮ y du measured here on its drawn
 * periodic state (ysteady against u, the trapezoid rule on 4000 points, a
 * closed path), its minor loop's area against the drawn minor loop (closed by
 * the chord, the loops' own rule), and {minor1.turn} against that loop's
 * measured orientation. */
static double trapezoid_ydu(const hy_run_series *se)
{
    double a = 0;
    size_t n = se->n;
    while (n > 0 && isnan(se->x[n - 1])) /* the loop series' trailing gap */
        n--;
    for (size_t k = 0; k + 1 < n; k++)
        a += 0.5 * (se->y[k] + se->y[k + 1]) * (se->x[k + 1] - se->x[k]);
    if (n > 1) /* the chord back to the start */
        a += 0.5 * (se->y[n - 1] + se->y[0]) * (se->x[0] - se->x[n - 1]);
    return a;
}

static void area_convention(void)
{
    const struct {
        const char *model;
        int sign; /* the area printed: +1 ∮ y du, -1 ∮ u dy */
    } cases[] = {{"kind = dahl\n", 1},
                 {"kind = lugre\nsigma0 = 6\n", 1},
                 {"kind = boucwen-operator\nalpha = 3\nbw_beta = 3\nbw_gamma = 0.75\ndelta = 0.25\n", 1},
                 {"kind = jiles-atherton\nja_k = 0.4\nja_a = 1.1\nja_ms = 1.6e3\n", -1},
                 {"kind = jiles-atherton\nja_k = 0.4\nja_a = 1.1\nja_ms = 1.6e3\nja_variant = jtd1992\n", -1},
                 {"kind = preisach\n", -1},
                 {"kind = preisach\npr_start = demagnetised\npr_support = triangle\npr_hs = 0.9\n", -1},
                 {"kind = play\nplay_r = 0.1\n", -1}};
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
        char text[1024], name[64];
        snprintf(name, sizeof name, "%.*s", (int)strcspn(cases[c].model + 7, "\n"), cases[c].model + 7);
        snprintf(text, sizeof text,
                 "[model]\n%s[input]\nkind = bimodal\numin1 = -1\numin2 = -0.2\numax1 = 0.4\numax2 = 1\n"
                 "[compute]\npoints = 4000\n[figure]\nkind = loop\n[series s]\ndata = ysteady\n[series b]\n"
                 "data = minor\n[annotation t]\ntext = \"{minor1.turn}\"\nx = 0\ny = 0\n",
                 cases[c].model);
        hy_scene_run r;
        hy_error err;
        if (run_text("area.scene", text, NULL, 0, &r, &err)) {
            CHECK(0, "%s: %s", name, err.msg);
            continue;
        }
        double ydu = trapezoid_ydu(find(&r, "s")), mydu = trapezoid_ydu(find(&r, "b"));
        double energy = r.loops.area_period, minor = r.loops.nminor ? r.loops.minor[0].area : NAN;
        /* the trapezoid rule on 4000 points: O(h²) on the smooth pieces between reversals,
           h = 1/2000 of the range, about 1e-6 of the area (3e-6 measured); 2e-5 */
        CHECK(energy > 0 && fabs(energy - cases[c].sign * ydu) <= 2e-5 * fabs(energy),
              "%s: printed energy per cycle %.10g, measured integral of y du %.10g (sign %+d expected)", name, energy,
              ydu, cases[c].sign);
        CHECK(fabs(minor - cases[c].sign * mydu) <= 2e-5 * fabs(minor) + 1e-12,
              "%s: printed minor-loop area %.10g, measured integral of y du %.10g (sign %+d expected)", name, minor,
              mydu, cases[c].sign);
        hy_scene_fig st;
        memset(&st, 0, sizeof st);
        int rc = hy_scene_run_figure(&r, &st, &err);
        const char *turn = mydu > 0 ? "\xE2\x86\xBB" : "\xE2\x86\xBA"; /* ↻ clockwise, ↺ counter-clockwise */
        CHECK(!rc && strstr(st.textbuf[0], turn), "%s: {minor1.turn} gave '%s', the loop's integral of y du is %g (%s)",
              name, rc ? "" : st.textbuf[0], mydu, rc ? err.msg : "");
        hy_scene_fig_free(&st);
        printf("area convention: %-16s energy %.8g (integral of y du %.8g), minor %.8g (%.8g) %s\n", name, energy, ydu,
               minor, mydu, turn);
        hy_scene_run_free(&r);
    }
}

/* The conventions a fitter needs, through scenes: the Preisach triangle
 * from the demagnetised state against the closed form (f_alpha = f_beta,
 * hc = 0: y = 2K (F(u) - 1/2)² with K = 2/(2F(hs) - 1)², test_preisach.c),
 * and the two Jiles-Atherton variants drawing different loops. */
static void conventions(void)
{
    hy_scene_run r;
    hy_error err;
    /* the input rises from 0 (the demagnetised state's field) to 2, past hs = 1.5 */
    const char *pr0 = "[model]\nkind = preisach\npr_hc = 0\npr_width = 0.7\npr_start = demagnetised\n"
                      "pr_support = triangle\npr_hs = 1.5\n[input]\nkind = pwl\npoints = 0, 0, 1, 2, 3, -2, 4, 0\n"
                      "[compute]\npoints = 41\ncycles = 1\n[series y]\ndata = ystar\n";
    if (run_text("pr.scene", pr0, NULL, 0, &r, &err)) {
        CHECK(0, "preisach demagnetised triangle: %s", err.msg);
    } else {
        const hy_run_series *y = find(&r, "y");
        double F15 = 0.5 * erfc(-1.5 / 0.7 / sqrt(2)), K = 2 / ((2 * F15 - 1) * (2 * F15 - 1)), worst = 0;
        for (size_t i = 0; y && i < y->n && y->x[i] <= 1.0; i++) { /* the initial curve, u = 2t up to 2 */
            double u = fmin(2 * y->x[i], 1.5), F = 0.5 * erfc(-u / 0.7 / sqrt(2));
            worst = fmax(worst, fabs(y->y[i] - 2 * K * (F - 0.5) * (F - 0.5)));
        }
        /* 1e-13: the Everett quadrature's relative target */
        CHECK(y && y->n >= 11 && worst <= 1e-13, "demagnetised initial curve off the closed form by %.3g (%zu points)", worst,
              y ? y->n : 0);
        CHECK(y && y->y[0] == 0 && fabs(y->y[10] - 1) <= 1e-13, "y(0) = %g, y at u = 2 = %.17g", y ? y->y[0] : NAN,
              y ? y->y[10] : NAN);
        hy_scene_run_free(&r);
    }
    double area[2];
    for (int v = 0; v < 2; v++) {
        char text[512];
        snprintf(text, sizeof text,
                 "[model]\nkind = jiles-atherton\nja_variant = %s\n[input]\nkind = triangle\nmin = -10000\n"
                 "max = 10000\n[figure]\nkind = loop\n[series m]\ndata = major\n",
                 v ? "jtd1992" : "jiles1986");
        area[v] = NAN;
        if (run_text("ja.scene", text, NULL, 0, &r, &err)) {
            CHECK(0, "jiles-atherton %d: %s", v, err.msg);
            continue;
        }
        area[v] = r.loops.major.area;
        hy_scene_run_free(&r);
    }
    printf("Jiles-Atherton major loop +-10 kA/m: energy %.6g J/m^3 (jiles1986), %.6g J/m^3 (jtd1992)\n", area[0],
           area[1]);
    CHECK(area[0] > 0 && area[1] > 1.1 * area[0], "the variants' loop energies %g, %g", area[0], area[1]);
}

static void refusals(void)
{
    /* another model's key from --set: refused too (it has no line: at [model]) */
    char pr_hc[] = "model.pr_hc=1", *set[] = {pr_hc};
    hy_scene_run r;
    hy_error err = {0};
    int rc = hy_scene_run_load_text(&r, "o.scene", JA, strlen(JA), set, 1, NULL, &err);
    CHECK(rc != 0 && strstr(err.msg, "o.scene:1:1: 'pr_hc' is not a parameter of a jiles-atherton model"),
          "--set model.pr_hc on a jiles-atherton scene: %d %s", rc, rc ? err.msg : "");
    if (!rc)
        hy_scene_run_free(&r);
    refused("[model]\nkind = jiles-atherton\nja_c = 1\n[series a]\ndata = input\n", 1,
            "bad.scene:3:1: ja_c: Jiles-Atherton c (reversibility) must be in [0, 1) for jiles1986");
    refused("[model]\nkind = jiles-atherton\nja_alpha = 0.01\n[series a]\ndata = input\n", 1,
            "bad.scene:3:1: ja_alpha: Jiles-Atherton alpha = 0.01 is too large");
    refused("[model]\nkind = jiles-atherton\nja_m0 = 2e6\n[series a]\ndata = input\n", 1,
            "bad.scene:3:1: ja_m0: Jiles-Atherton initial magnetisation m0");
    refused("[model]\nkind = jiles-atherton\nsigma0 = 6\n[series a]\ndata = input\n", 1,
            "bad.scene:3:1: 'sigma0' is not a parameter of a jiles-atherton model");
    refused("[model]\nkind = jiles-atherton\nja_k = 300\npr_hc = 0.3\n[series a]\ndata = input\n", 1,
            "bad.scene:4:1: 'pr_hc' is not a parameter of a jiles-atherton model (its keys: ja_ms, ja_a, ja_k, "
            "ja_c, ja_alpha, ja_m0, ja_variant)"); /* another model's own row: decoded into nothing, refused where written */
    refused("[model]\nkind = preisach\nja_ms = 1e6\n[series a]\ndata = input\n", 1,
            "bad.scene:3:1: 'ja_ms' is not a parameter of a preisach model (its keys: pr_density, pr_hc, pr_width, "
            "pr_ys, pr_start, pr_support, pr_hs, pr_file)");
    refused("[model]\nkind = preisach\n[figure]\nkind = g\n[series a]\ndata = g\n", 1,
            "bad.scene:6:1: data = g needs [model] kind = dahl, lugre or dahl-filter (this model is preisach)");
    refused("[model]\nkind = lugre\n[series a]\ndata = ysteady\nquantity = magnetisation\n", 1,
            "bad.scene:5:1: a lugre model draws quantity output, not magnetisation");
    refused("[model]\nkind = preisach\npr_hc = 1e6\npr_width = 1e-7\n[series a]\ndata = input\n", 1,
            "bad.scene:4:1: pr_width: Preisach alpha (up-switching field) width sigma = 1e-07 is below 1e-12");
    refused("[model]\nkind = preisach\n[input]\nkind = multisine\n[series a]\ndata = input\n", 1,
            "bad.scene:4:1: [input] kind = multisine needs [model] kind = boucwen (this model is preisach)");
    refused("[model]\nkind = jiles-atherton\nja_variant = jtd1986\n[series a]\ndata = input\n", 1,
            "bad.scene:3:14: 'ja_variant' in [model] must be one of jiles1986, jtd1992");
    refused("[model]\nkind = preisach\npr_support = triangle\npr_hs = 0\n[series a]\ndata = input\n", 1,
            "bad.scene:4:9: 'pr_hs' in [model] must be > 0");
    refused("[model]\nkind = preisach\npr_support = triangle\npr_hs = 1e-30\npr_width = 0.01\n[series a]\n"
            "data = input\n", 1, "bad.scene:3:1: pr_support: Preisach density has no mass on the triangle");
    /* issue 36: Jiles-Atherton inputs it cannot integrate, refused at [input] before computing, naming the
       input's scale (they ran past 120 s, or blamed alpha and k) */
    const char *ja_bad[][2] = {
        {"ja_k = 1e-6\nja_alpha = 2e-3\n[input]\nkind = sine\namp = 1500\n", "bad.scene:5:1: the input's scale "
         "is beyond what Jiles-Atherton integrates: the field travels 6000 A/m (|H| up to 1500 A/m), 6e+09 times k"},
        {"[input]\nkind = sine\namp = 1e12\n", "bad.scene:3:1: the input's scale is beyond what Jiles-Atherton "
         "integrates: |H| reaches 1e+12 A/m"},
        {"[input]\nkind = triangle\nmin = -1e300\nmax = 1e300\n", "bad.scene:3:1: the input's scale is beyond what "
         "Jiles-Atherton integrates: |H| reaches 1e+300 A/m"}};
    for (size_t i = 0; i < sizeof ja_bad / sizeof ja_bad[0]; i++) {
        char text[512];
        snprintf(text, sizeof text, "[model]\nkind = jiles-atherton\n%s[compute]\npoints = 400\n[series a]\ndata = ystar\n",
                 ja_bad[i][0]);
        refused(text, 1, ja_bad[i][1]);
    }
}

/* dz/du of the Bouc-Wen operator (nu = 1), written apart from model_bwop.c */
static long double bw_rhs(long double z, int s)
{
    const long double a = 3, b = 3, g = 0.75L, d = 0.25L;
    return a - b * (g * s * z + d * fabsl(z));
}

/* Moves z from u0 to u1 by RK4 in long double (h = 1e-5) and adds the
 * trapezoid ∫ z du to *iz. */
static long double bw_ref_move(long double z, long double u0, long double u1, long double *iz)
{
    int s = u1 > u0 ? 1 : -1;
    long n = (long)ceill(fabsl(u1 - u0) / 1e-5L);
    long double h = (u1 - u0) / n;
    for (long i = 0; i < n; i++) {
        long double k1 = bw_rhs(z, s), k2 = bw_rhs(z + h * k1 / 2, s), k3 = bw_rhs(z + h * k2 / 2, s),
                    k4 = bw_rhs(z + h * k3, s), zn = z + h * (k1 + 2 * k2 + 2 * k3 + k4) / 6;
        *iz += h * (z + zn) / 2;
        z = zn;
    }
    return z;
}

/* The Bouc-Wen operator panel: its minor loop against RK4 in long double
 * (h = 1e-5: RK4's error ~1e-20 per unit, the kink at z = 0 and the
 * trapezoid area ~1e-10): ends to 1e-9, area to 1e-8. */
static void bouc_wen_operator(void)
{
    char path[1200];
    snprintf(path, sizeof path, "%s/scenes/compare/boucwen_operator.scene", SRC);
    hy_scene_run r;
    hy_error err;
    int rc = hy_scene_run_load(&r, path, NULL, 0, &err);
    if (!rc)
        rc = hy_scene_run_compute(&r, NULL, &err);
    CHECK(rc == 0, "boucwen operator: %s", err.msg);
    if (rc)
        return;
    const long double e[5] = {-1, 0.3333333333333333L, -0.7333333333333333L, 1, -1};
    long double z = 0, iz = 0, ys = 0, yc = 0, i0 = 0, i1 = 0;
    for (int k = 0; k < 8; k++) /* 8 periods: settled far below 1e-12 */
        for (int j = 0; j < 4; j++) {
            z = bw_ref_move(z, e[j], e[j + 1], &iz);
            if (k == 7 && j == 0)
                ys = z, i0 = iz;
        }
    /* the last period again, stopping where the minor loop closes */
    z = bw_ref_move(z, e[0], e[1], &iz);
    i0 = iz, ys = z;
    z = bw_ref_move(z, e[1], e[2], &iz);
    yc = bw_ref_move(z, e[2], e[1], &iz);
    i1 = iz;
    const hy_loop *m = r.loops.nminor == 1 ? &r.loops.minor[0] : NULL;
    CHECK(m != NULL, "boucwen operator: one minor loop");
    if (m) {
        CHECK_CLOSE(m->y_start, (double)ys, 1e-9, "boucwen operator: z at the minor loop's start");
        CHECK_CLOSE(m->y_close, (double)yc, 1e-9, "boucwen operator: z where it returns");
        CHECK_CLOSE(m->area, (double)(i1 - i0), 1e-8, "boucwen operator: minor loop area (integral of z du)");
        printf("boucwen operator: minor loop area %.12g (RK4 %.12Lg), gap %.6g\n", m->area, i1 - i0,
               m->y_close - m->y_start);
    }
    hy_scene_run_free(&r);
}

/* The five-model figure: six panels, one run each; only Preisach's minor
 * loop closes; data rows are PANEL/SERIES; columns must divide the panels. */
static void panels(void)
{
    char path[1200];
    snprintf(path, sizeof path, "%s/scenes/five_models_minor_loops.scene", SRC);
    hy_scene_run r;
    hy_error err;
    int rc = hy_scene_run_load(&r, path, NULL, 0, &err);
    if (!rc)
        rc = hy_scene_run_compute(&r, NULL, &err);
    CHECK(rc == 0, "five models: %s", err.msg);
    if (rc)
        return;
    CHECK(r.npanels == 6, "six panels (got %zu)", r.npanels);
    for (size_t i = 1; i < r.npanels; i++) {
        const hy_scene_run *p = &r.panels[i];
        int closes = p->have_loops && p->loops.nminor == 1 && p->loops.minor[0].y_close == p->loops.minor[0].y_start;
        int preisach = !strcmp(p->mtype->name, "preisach");
        CHECK(closes == preisach, "%s: minor loop %s at its reversal", p->mtype->name,
              closes ? "closes" : "does not close");
        CHECK(p->loops.nminor == 1 && p->loops.minor[0].area > 0, "%s: minor loop area > 0", p->mtype->name);
    }
    char *csv;
    size_t len;
    CHECK(hy_scene_run_csv(&r, &csv, &len, &err) == 0 && strstr(csv, "\npreisach/minor,") && strstr(csv, "\ndahl/major,"),
          "five models: CSV rows named PANEL/SERIES");
    free(csv);
    unsigned char *buf;
    CHECK(hy_scene_run_render(&r, HY_FORMAT_SVG, &buf, &len, NULL, &err) == 0 && len > 1000, "five models: SVG");
    free(buf);
    hy_scene_run_free(&r);
    char *sets[] = {"figure.columns=4"};
    if (!(rc = hy_scene_run_load(&r, path, sets, 1, &err))) /* on error load frees r */
        hy_scene_run_free(&r);
    /* issue 22: refused by load (decode), before computing; it was found when drawing */
    CHECK(rc == HY_EINVAL && strstr(err.msg, "columns = 4 does not divide the 6 panels"), "columns at load: %s", err.msg);
}

/* The play operator (model_play.c) under the default bimodal input (0 up to
 * 1, down to 0.2, up to 1.5): the minor loop from the dragged branch is the
 * parallelogram of area 2r (1 - 0.2 - 2r) = 0.12 at r = 0.1, closing where it
 * started, y = u_max,1 - r = 0.9 (exact pieces: a few ulps). */
static void play_loop(void)
{
    hy_scene_run r;
    hy_error err;
    if (run_text("play.scene", "[model]\nkind = play\nplay_r = 0.1\n[input]\nkind = bimodal\n[figure]\nkind = loop\n"
                 "[series minor]\ndata = minor\n", NULL, 0, &r, &err)) {
        CHECK(0, "play scene: %s", err.msg);
        return;
    }
    CHECK(r.have_loops && r.loops.nminor == 1, "one minor loop (got %zu)", r.loops.nminor);
    if (r.loops.nminor == 1) {
        const hy_loop *m = &r.loops.minor[0];
        CHECK_CLOSE(m->area, 2 * 0.1 * (1 - 0.2 - 2 * 0.1), 1e-15, "play minor loop area");
        CHECK_CLOSE(m->y_start, 0.9, 1e-15, "play minor loop y at its start");
        CHECK_CLOSE(m->y_close, 0.9, 1e-15, "play minor loop y at its close");
    }
    hy_scene_run_free(&r);
    refused("[model]\nkind = play\nplay_r = 0\n[series a]\ndata = input\n", 1,
            "bad.scene:3:10: 'play_r' in [model] must be > 0");
    refused("[model]\nkind = play\nja_k = 3\n[series a]\ndata = input\n", 1,
            "bad.scene:3:1: 'ja_k' is not a parameter of a play model (its keys: play_r, play_y0)");
}

/* The play operator's areas at both ends of the double range (issue 36 item
 * 6): the bimodal input scaled by 1e200 (umin1 .. umax2 = -1e200 .. 1e200,
 * r = 0.01) has a major loop of exact area 2r (2e200 - 2r) = 4e198 and a
 * minor one of 2r (1e200 - 2r), though y du is 1e400 (they were NaN; also
 * at 1e300 with r = 1); r =
 * 1e-300 on (0, 0.2, 1, 1.5) has a minor loop of 2r (0.8 - 2r) = 1.6e-300
 * (it was -0.0: the path integral's terms are O(1) and cancelled).  Each
 * within 1e-12 relative of the exact value, energy = major + minor. */
static void play_extreme_case(const char *input, double r, double lo, double mlo, double mhi, double hi)
{
    hy_scene_run run;
    hy_error err;
    char text[400];
    snprintf(text, sizeof text, "[model]\nkind = play\nplay_r = %.17g\n[input]\nkind = bimodal\n%s"
             "[figure]\nkind = loop\n[series minor]\ndata = minor\n", r, input);
    if (run_text("play.scene", text, NULL, 0, &run, &err)) {
        CHECK(0, "play scene r = %g: %s", r, err.msg);
        return;
    }
    double major = 2 * r * ((hi - lo) - 2 * r), minor = 2 * r * ((mhi - mlo) - 2 * r);
    CHECK(run.have_loops && run.loops.nminor == 1, "r = %g: one minor loop (got %zu)", r, run.loops.nminor);
    /* the major loop's path goes round the minor loop too: its area holds both, its own area is its own */
    CHECK_CLOSE(run.loops.major.area / (major + minor), 1, 1e-12, "play major loop area / (major + minor)");
    CHECK_CLOSE(run.loops.major.own_area / major, 1, 1e-12, "play major loop's own area / 2r (hi - lo - 2r)");
    if (run.loops.nminor == 1)
        CHECK_CLOSE(run.loops.minor[0].area / minor, 1, 1e-12, "play minor loop area / 2r (hi - lo - 2r)");
    CHECK_CLOSE(run.loops.area_period / (major + minor), 1, 1e-12, "play energy per cycle / (major + minor)");
    hy_scene_run_free(&run);
}

static void play_extremes(void)
{
    play_extreme_case("umin1 = -1e200\numin2 = -0.5e200\numax1 = 0.5e200\numax2 = 1e200\n", 0.01, -1e200, -0.5e200,
                      0.5e200, 1e200);
    play_extreme_case("umin1 = -1e300\numin2 = -0.5e300\numax1 = 0.5e300\numax2 = 1e300\n", 1, -1e300, -0.5e300,
                      0.5e300, 1e300);
    play_extreme_case("", 1e-300, 0, 0.2, 1, 1.5);
    play_extreme_case("", 1e-200, 0, 0.2, 1, 1.5);
}

/* The Duhem model (model_duhem.c), dy/du = alpha s (a u - y) + b on a move
 * of sign s, with alpha = 5, a = 1, b = 0.5 (c = (a - b) / alpha = 0.1) and
 * the triangle 0 -> 1 -> 0 of period 2, against references written here:
 * (1) y* over one period from y(0) = 0, against the solution of that linear
 * equation on each ramp, rising y = u - c (1 - e^{-alpha u}) and falling
 * y = u + c + (y1 - 1 - c) e^{-alpha (1 - u)}: the model's pieces are exact,
 * so 1e-12 (a few hundred ulps of y ~ 1) bounds rounding alone; (2) the
 * periodic loop's area, integral over [0, 1] of y_fall - y_rise, from the
 * steady branches found by iterating the two ramps to a fixed point and
 * integrated by composite Simpson on 4000 intervals (error below
 * h^4 alpha^4 |y| / 180 ~ 2e-16: 1e-10 leaves room for rounding). */
static double duhem_rise(double c, double y0, double u)
{
    return u - c + (y0 + c) * exp(-5 * u);
}

static double duhem_fall(double c, double y1, double u)
{
    return u + c + (y1 - 1 - c) * exp(-5 * (1 - u));
}

static void duhem(void)
{
    const double c = 0.1;
    hy_scene_run r;
    hy_error err;
    if (run_text("duhem.scene", "[model]\nkind = duhem\nduhem_alpha = 5\nduhem_a = 1\nduhem_b = 0.5\n[input]\n"
                 "kind = triangle\nmin = 0\nmax = 1\nperiod = 2\n[compute]\npoints = 400\n[figure]\nkind = timeseries\n"
                 "[series ystar]\ndata = ystar\n[annotation e]\ntext = \"{energy}\"\nx = 0.1\ny = 0.1\n", NULL, 0, &r, &err)) {
        CHECK(0, "duhem scene: %s", err.msg);
        return;
    }
    const hy_run_series *se = &r.series[0];
    double y1 = duhem_rise(c, 0, 1), worst = 0;
    for (size_t i = 0; i < se->n; i++) {
        double t = se->x[i], u = hy_input_u(&r.input, t);
        double want = t <= 1 ? duhem_rise(c, 0, u) : duhem_fall(c, y1, u);
        worst = fmax(worst, fabs(se->y[i] - want));
    }
    CHECK(se->n == 401 && worst < 1e-12, "duhem y* on the two ramps: %zu points, max |y - exact| = %.3g", se->n,
          worst);
    double lo = 0, hi = 0; /* the steady branches' ends: y(0) and y(1) */
    for (int k = 0; k < 200; k++) {
        hi = duhem_rise(c, lo, 1);
        lo = duhem_fall(c, hi, 0);
    }
    const int n = 4000;
    double sum = 0;
    for (int j = 0; j <= n; j++) {
        double u = (double)j / n, w = j == 0 || j == n ? 1 : j % 2 ? 4 : 2;
        sum += w * (duhem_fall(c, hi, u) - duhem_rise(c, lo, u));
    }
    double area = sum / (3.0 * n);
    CHECK(r.have_loops, "duhem: loops found");
    if (r.have_loops) {
        CHECK_CLOSE(r.loops.major.area, area, 1e-10, "duhem: periodic loop area (Simpson on the exact branches)");
        printf("duhem: y* max error %.3g; loop area %.15g (reference %.15g)\n", worst, r.loops.major.area, area);
    }
    hy_scene_run_free(&r);
    refused("[model]\nkind = duhem\nduhem_alpha = 0\n[series a]\ndata = input\n", 1,
            "bad.scene:3:15: 'duhem_alpha' in [model] must be > 0");
    refused("[model]\nkind = duhem\nplay_r = 3\n[series a]\ndata = input\n", 1,
            "bad.scene:3:1: 'play_r' is not a parameter of a duhem model (its keys: duhem_alpha, duhem_a, duhem_b, "
            "duhem_y0)");
}

int main(int argc, char **argv)
{
    SRC = argc > 1 ? argv[1] : ".";
    gsl_set_error_handler_off();
    table_matches_schema();
    jiles_fig1();
    preisach_loops();
    every_input();
    area_convention();
    conventions();
    refusals();
    bouc_wen_operator();
    panels();
    play_loop();
    play_extremes();
    duhem();
    return tu_finish("models");
}
