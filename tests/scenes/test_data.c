/* SPDX-License-Identifier: MIT */
/* test_data.c: measured data in scenes (issue 32 item 1, scene_data.c).
 *  - a model driven by [data] equals the model driven by the same u sequence
 *    given as an [input] kind = file, point for point (Jiles-Atherton, Preisach);
 *  - a measured loop's {NAME.area} against areas computed by hand;
 *  - the fitter's calls: hy_scene_run_model_at_data after hy_scene_run_set_model
 *    equals a fresh load with the same --set, and repeats give the same bits;
 *  - the start states: zero differs from first where a path leads to u[0];
 *    periodic is a fixed point of one more pass;
 *  - refusals name file:line:col (time-stepped models, modelled of data that
 *    does not drive the model, record past the last, a zero scale). */
#include <gsl/gsl_errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "../core/tutil.h"
#include "../tmpdir.h"
#include "scene_model.h"
#include "scene_run.h"

/* Writes text to the file name in the test's directory; its path into buf. */
static const char *put(const char *name, const char *text, char *buf, size_t size)
{
    test_tmppath(buf, size, name);
    FILE *f = fopen(buf, "w");
    if (f) {
        fputs(text, f);
        fclose(f);
    }
    return buf;
}

static int load(const char *name, const char *text, char **sets, size_t nsets, hy_scene_run *r, hy_error *err)
{
    char path[4200];
    put(name, text, path, sizeof path);
    int rc = hy_scene_run_load(r, path, sets, nsets, err);
    if (!rc && (rc = hy_scene_run_compute(r, NULL, err)))
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

/* A u sequence with a minor loop: up to 1, down to -1, up to 0.3, down to
 * -0.2, up to 1 again (the return-point of the minor loop), back to 0; N
 * samples, closed (u[N-1] = u[0] = 0). */
#define N 61
static double seq(size_t i)
{
    static const double ext[] = {0, 1, -1, 0.3, -0.2, 1, 0};
    double x = (double)i / (double)(N - 1) * 6.0;
    size_t k = (size_t)x < 6 ? (size_t)x : 5;
    double w = x - (double)k;
    return ext[k] + (ext[k + 1] - ext[k]) * w;
}

/* The model driven by data equals the model driven by the same u as a file
 * input, at every sample.  Both feed the model the same values in the same
 * order from the same state (the initial state at u[0]: start = first; the
 * file input's ystar starts there), so they are equal to the bit. */
static void data_equals_file(const char *model, double scale)
{
    char path[4200], csv[8192] = "u,y\n", txt[8192] = "";
    for (size_t i = 0; i < N; i++) {
        double u = scale * seq(i);
        snprintf(csv + strlen(csv), sizeof csv - strlen(csv), "%.17g,0\n", u);
        snprintf(txt + strlen(txt), sizeof txt - strlen(txt), "%zu %.17g\n", i, u);
    }
    put("seq.csv", csv, path, sizeof path);
    put("seq.txt", txt, path, sizeof path);
    char a[1024], b[1024];
    snprintf(a, sizeof a, "%s[data d]\nfile = \"seq.csv\"\nu = u\ny = y\n[input]\nkind = data\ndata = d\nstart = first\n"
             "[figure]\nkind = loop\n[series m]\ndata = modelled\nof = d\n", model);
    snprintf(b, sizeof b, "%s[input]\nkind = file\nfile = \"seq.txt\"\n[compute]\npoints = %d\n"
             "[figure]\nkind = loop\n[series s]\ndata = ystar\n", model, N - 1);
    hy_scene_run ra, rb;
    hy_error err;
    int rc = load("a.scene", a, NULL, 0, &ra, &err);
    CHECK(rc == 0, "%s driven by data: %s", model, err.msg);
    if (rc)
        return;
    rc = load("b.scene", b, NULL, 0, &rb, &err);
    CHECK(rc == 0, "%s driven by a file: %s", model, err.msg);
    if (!rc) {
        const hy_run_series *m = find(&ra, "m"), *s = find(&rb, "s");
        CHECK(m && s && m->n == N && s->n == N, "points: %zu %zu", m ? m->n : 0, s ? s->n : 0);
        size_t same = 0;
        for (size_t i = 0; m && s && i < N && i < s->n; i++)
            same += m->x[i] == s->x[i] && m->y[i] == s->y[i];
        CHECK(same == N, "%s: %zu of %d samples equal to the bit", model, same, N);
        /* hystviz data's rows: measured and residual beside the model's */
        CHECK(m && m->ymeas && m->ymeas[3] == 0 && isfinite(m->y[3]), "measured y kept beside the model's");
        hy_scene_run_free(&rb);
    }
    hy_scene_run_free(&ra);
}

/* {NAME.area} of measured loops: a triangle and a square, by hand. */
static void areas_by_hand(void)
{
    char path[4200];
    /* triangle (1,1) (4,1) (1,5): legs 3 and 4, area 6, counter-clockwise;
       then the unit square traversed clockwise: -1 */
    put("tri.csv", "# rec u y\n1 1 1\n1 4 1\n1 1 5\n2 0 0\n2 0 1\n2 1 1\n2 1 0\n", path, sizeof path);
    const char *sc = "[data t]\nfile = \"tri.csv\"\nu = u\ny = y\nsplit = rec\nrecord = 1\n"
                     "[data q]\nfile = \"tri.csv\"\nu = 2\ny = 3\nsplit = 1\nrecord = 2\n"
                     "[data all]\nfile = \"tri.csv\"\nu = u\ny = y\nsplit = rec\n"
                     "[figure]\nkind = loop\n[series t]\ndata = measured\nof = t\n[series q]\ndata = measured\nof = q\n"
                     "[series all]\ndata = measured\nof = all\n"
                     "[annotation a]\ntext = \"{t.area} {q.area}\"\nx = 0\ny = 0\n";
    hy_scene_run r;
    hy_error err;
    int rc = load("tri.scene", sc, NULL, 0, &r, &err);
    CHECK(rc == 0, "triangle scene: %s", err.msg);
    if (rc)
        return;
    const hy_run_series *t = find(&r, "t"), *q = find(&r, "q"), *all = find(&r, "all");
    CHECK(hy_scene_data_value(&r, t, "area") == 6.0, "triangle: %g", hy_scene_data_value(&r, t, "area"));
    CHECK(hy_scene_data_value(&r, q, "area") == -1.0, "clockwise square: %g", hy_scene_data_value(&r, q, "area"));
    CHECK(isnan(hy_scene_data_value(&r, all, "area")), "two records have no one area");
    /* two records: 3 + 4 points and a NaN between them */
    CHECK(all->n == 8 && isnan(all->x[3]) && all->x[4] == 0 && all->y[6] == 1, "pieces: n %zu", all->n);
    CHECK(r.data[2].area[0] == 6.0 && r.data[2].area[1] == -1.0, "per-record areas %g %g", r.data[2].area[0],
          r.data[2].area[1]);
    hy_scene_run_free(&r);
}

#define JA_HEAD                                                                                           \
    "[model]\nkind = jiles-atherton\nja_ms = 2.6e5\nja_a = 5.75\nja_k = 4.14\nja_c = 0.5\nja_alpha = 6.4e-8\n" \
    "[data f]\nfile = \"f.csv\"\nu = H\ny = B\nsplit = loop\n[input]\nkind = data\ndata = f\n"
#define JA_TAIL "[figure]\nkind = loop\n[series m]\ndata = modelled\nof = f\n"
static const char *JA_DATA = JA_HEAD JA_TAIL;

/* Two loops like the ferrite's: from the positive tip down and back up. */
static void ferrite_like(char *path, size_t size)
{
    char csv[16384] = "# loop,H,B\n";
    for (int loop = 1; loop <= 2; loop++)
        for (int i = 0; i <= 64; i++) {
            double h = 40.0 * loop * cos(2 * M_PI * i / 64.0);
            snprintf(csv + strlen(csv), sizeof csv - strlen(csv), "%d,%.17g,%.17g\n", loop, h, 0.3 * tanh(h / 20));
        }
    put("f.csv", csv, path, size);
}

/* The fitter's route: set_model + model_at_data against a fresh load with --set. */
static void fitter_calls(void)
{
    char path[4200];
    ferrite_like(path, sizeof path);
    hy_scene_run r, f;
    hy_error err;
    int rc = load("ja.scene", JA_DATA, NULL, 0, &r, &err);
    CHECK(rc == 0, "JA data scene: %s", err.msg);
    if (rc)
        return;
    hy_data_view v;
    CHECK(hy_scene_run_driving(&r, &v, &err) == 0 && v.n == 130 && v.nrec == 2 && v.rec[1] - v.rec[0] == 65,
          "driving: n %zu records %zu", v.n, v.nrec);
    double *y0 = malloc(v.n * sizeof *y0), *y1 = malloc(v.n * sizeof *y1), *y2 = malloc(v.n * sizeof *y2);
    char *sets[] = {"model.ja_k=6", "model.ja_a=7"};
    rc = hy_scene_run_model_at_data(&r, y0, &err);
    CHECK(rc == 0 && !memcmp(y0, find(&r, "m")->y, 65 * sizeof *y0), "model_at_data = the drawn series: %s", err.msg);
    for (int rep = 0; rep < 3; rep++) { /* each call from the scene as loaded: no drift */
        rc = hy_scene_run_set_model(&r, sets, 2, &err);
        rc = rc ? rc : hy_scene_run_model_at_data(&r, y1, &err);
        CHECK(rc == 0, "set_model + model_at_data: %s", err.msg);
    }
    rc = load("ja.scene", JA_DATA, sets, 2, &f, &err);
    CHECK(rc == 0, "fresh load with --set: %s", err.msg);
    if (!rc) {
        const hy_run_series *m = find(&f, "m");
        size_t same = 0;
        for (size_t i = 0, o = 0; i < v.n; i++, o++) {
            if (i == 65)
                o++; /* the series' NaN between the records */
            same += m->y[o] == y1[i];
        }
        CHECK(same == v.n, "set_model = fresh --set: %zu of %zu", same, v.n);
        CHECK(y1[10] != y0[10], "the parameters changed the output");
        hy_scene_run_free(&f);
    }
    /* a refused value leaves the run's model as it was */
    char *badk[] = {"model.ja_k=-1"};
    CHECK(hy_scene_run_set_model(&r, badk, 1, &err) == HY_EINVAL, "ja_k = -1 refused: %s", err.msg);
    char *other[] = {"figure.dpi=100"};
    CHECK(hy_scene_run_set_model(&r, other, 1, &err) == HY_EINVAL && strstr(err.msg, "only its [model]"),
          "another section refused: %s", err.msg);
    CHECK(hy_scene_run_model_at_data(&r, y2, &err) == 0 && !memcmp(y1, y2, v.n * sizeof *y1),
          "after the refusals the model is the last one set");
    free(y0);
    free(y1);
    free(y2);
    hy_scene_run_free(&r);
}

/* start = zero (from the demagnetised state at H = 0, up the initial curve to
 * the tip) differs from first (M = 0 put at the tip); periodic is periodic. */
static void starts(void)
{
    char path[4200], text[2048];
    ferrite_like(path, sizeof path);
    const char *st[] = {"zero", "first", "periodic"};
    double tip[3] = {0, 0, 0}, end[3] = {0, 0, 0};
    for (int k = 0; k < 3; k++) {
        snprintf(text, sizeof text, JA_HEAD "start = %s\n" JA_TAIL, st[k]);
        hy_scene_run r;
        hy_error err;
        int rc = load("st.scene", text, NULL, 0, &r, &err);
        CHECK(rc == 0, "start = %s: %s", st[k], err.msg);
        if (rc)
            continue;
        const hy_run_series *m = find(&r, "m");
        tip[k] = m->y[0];
        end[k] = m->y[64];
        if (k == 2) { /* one more pass from the periodic state's end gives the same loop */
            double *y = malloc(130 * sizeof *y);
            CHECK(hy_scene_run_model_at_data(&r, y, &err) == 0 && y[64] == end[2], "periodic repeats");
            free(y);
        }
        hy_scene_run_free(&r);
    }
    CHECK(tip[0] != tip[1] && tip[0] > 0.2, "zero (initial curve) vs first: B at the tip %g %g", tip[0], tip[1]);
    /* a closed loop in its periodic state ends where it started (tolerance: the
       settling criterion, 1e-12 of |B|, times a few passes) */
    CHECK(fabs(end[2] - tip[2]) <= 1e-9 * fabs(tip[2]), "periodic: start %.17g end %.17g", tip[2], end[2]);
}

static void refusals(void)
{
    char path[4200];
    ferrite_like(path, sizeof path);
    hy_scene_run r;
    hy_error err;
    int rc = load("lg.scene", "[model]\nkind = lugre\n[data f]\nfile = \"f.csv\"\nu = H\ny = B\nrecord = 1\n[input]\n"
                              "kind = data\ndata = f\n[figure]\nkind = loop\n[series m]\ndata = modelled\nof = f\n", NULL, 0, &r, &err);
    CHECK(rc == HY_EINVAL && strstr(err.msg, "lg.scene:10:1: a lugre model is time-stepped: it is driven by the measured t "
                                             "and u, and [data f] has no t column"), "lugre without t: %d %s", rc, err.msg);
    rc = load("bw.scene", "[model]\nkind = boucwen\n[data f]\nfile = \"f.csv\"\nu = H\ny = B\n[input]\nkind = data\n"
                          "data = f\n[figure]\nkind = timeseries\n[series m]\ndata = modelled\nof = f\n", NULL, 0, &r, &err);
    CHECK(rc != 0 && strstr(err.msg, "bw.scene:"), "boucwen refused with its place: %d %s", rc, err.msg);
    rc = load("nd.scene", "[model]\nkind = jiles-atherton\n[data f]\nfile = \"f.csv\"\nu = H\ny = B\n"
                          "[figure]\nkind = loop\n[series m]\ndata = modelled\nof = f\n", NULL, 0, &r, &err);
    CHECK(rc == HY_EINVAL && strstr(err.msg, "nd.scene:11:1: data = modelled draws the model at the inputs"),
          "modelled without driving: %s", err.msg);
    rc = load("rec.scene", "[data f]\nfile = \"f.csv\"\nu = H\ny = B\nsplit = loop\nrecord = 3\n"
                           "[figure]\nkind = loop\n[series m]\ndata = measured\nof = f\n", NULL, 0, &r, &err);
    CHECK(rc == HY_EINVAL && strstr(err.msg, "rec.scene:6:1: record 3 does not exist:") && strstr(err.msg, "has 2 records"),
          "record past the last: %s", err.msg);
    rc = load("sc.scene", "[data f]\nfile = \"f.csv\"\nu = H\ny = B\ny_scale = 0\n"
                          "[figure]\nkind = loop\n[series m]\ndata = measured\nof = f\n", NULL, 0, &r, &err);
    CHECK(rc == HY_EINVAL && strstr(err.msg, "sc.scene:5:1: 'y_scale' must not be 0"), "zero scale: %s", err.msg);
    rc = load("of.scene", "[figure]\nkind = loop\n[series m]\ndata = measured\nof = nope\n", NULL, 0, &r, &err);
    CHECK(rc == HY_EINVAL && strstr(err.msg, "of.scene:5:1: no [data nope] in the scene"), "unknown data: %s", err.msg);
}

/* LuGre driven by measured t and u equals LuGre driven by the same samples as
 * a file input, its y_gamma at gamma = 1 on a grid that is the sample times
 * (0.25 i: exact in binary, and the period 10 = 40 x 0.25), to the bit: both
 * are the exact solution at the same times.  Then the fitter's route for it. */
static void lugre_by_time(void)
{
    char path[4200], csv[8192] = "t,u,y\n", txt[8192] = "";
    for (int i = 0; i <= 40; i++) {
        double u = i < 40 ? 2 * sin(2 * M_PI * i / 40.0) : 0.0, t = 0.25 * i;
        snprintf(csv + strlen(csv), sizeof csv - strlen(csv), "%.17g,%.17g,%.17g\n", t, u, tanh(u));
        snprintf(txt + strlen(txt), sizeof txt - strlen(txt), "%.17g %.17g\n", t, u);
    }
    put("lg.csv", csv, path, sizeof path);
    put("lg.txt", txt, path, sizeof path);
    const char *a = "[model]\nkind = lugre\nsigma0 = 6\n[data d]\nfile = \"lg.csv\"\nu = u\ny = y\nt = t\n"
                    "[input]\nkind = data\ndata = d\n[figure]\nkind = timeseries\n[series m]\ndata = modelled\nof = d\n";
    const char *b = "[model]\nkind = lugre\nsigma0 = 6\n[input]\nkind = file\nfile = \"lg.txt\"\n[compute]\npoints = 40\n"
                    "[figure]\nkind = timeseries\n[series s]\ndata = ygamma\ngamma = 1\n";
    hy_scene_run ra, rb;
    hy_error err;
    int rc = load("lga.scene", a, NULL, 0, &ra, &err);
    CHECK(rc == 0, "lugre driven by t and u: %s", err.msg);
    if (rc)
        return;
    if (!(rc = load("lgb.scene", b, NULL, 0, &rb, &err))) {
        const hy_run_series *m = find(&ra, "m"), *s = find(&rb, "s");
        size_t same = 0;
        for (size_t i = 0; i < 41 && m->n == 41 && s->n == 41; i++)
            same += m->x[i] == s->x[i] && m->y[i] == s->y[i];
        CHECK(same == 41, "lugre: %zu of 41 samples equal to the bit", same);
        hy_scene_run_free(&rb);
    }
    CHECK(rc == 0, "lugre by file: %s", err.msg);
    double y1[41], y2[41];
    char *sets[] = {"model.sigma0=2"}, *bad[] = {"model.sigma0=-1"};
    rc = hy_scene_run_set_model(&ra, sets, 1, &err);
    rc = rc ? rc : hy_scene_run_model_at_data(&ra, y1, &err);
    CHECK(rc == 0 && y1[5] != find(&ra, "m")->y[5], "lugre set_model: %s", err.msg);
    CHECK(hy_scene_run_set_model(&ra, bad, 1, &err) != 0, "sigma0 = -1 refused");
    CHECK(hy_scene_run_model_at_data(&ra, y2, &err) == 0 && !memcmp(y1, y2, sizeof y1), "lugre kept its last model");
    hy_scene_run_free(&ra);
}

int main(void)
{
    gsl_set_error_handler_off();
    data_equals_file("[model]\nkind = jiles-atherton\n", 3000.0);
    data_equals_file("[model]\nkind = preisach\n", 1.0);
    areas_by_hand();
    fitter_calls();
    starts();
    refusals();
    lugre_by_time();
    return tu_finish("data");
}
