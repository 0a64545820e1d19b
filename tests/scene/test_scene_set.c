/* SPDX-License-Identifier: MIT */
/* test_scene_set.c: --set overrides: valid assignments, precedence, and every error (scene left unchanged). */
#include "scene_test.h"

static const char *scene_text =
    "[model]\nsigma0 = 6\n[series ystar]\ndata = ystar\nstyle = solid\n[series y.1]\ndata = ygamma\n";


static void valid(void)
{
    hy_scene *s = PARSE_OK("s.scene", scene_text);
    hy_error err;
    double v;
    const char *t;
    hy_scene_loc loc;
    uint64_t h0 = hy_scene_hash(s);
    CHECK(hy_scene_set(s, "model.sigma0=2.5", &err) == 0);
    CHECK(hy_scene_get_num(s, "model", NULL, "sigma0", &v) == HY_SCENE_SET);
    CHECK_NEAR(v, 2.5, 0);
    CHECK(hy_scene_get_loc(s, "model", NULL, "sigma0", &loc) == 1);
    CHECK_STR(loc.file, "--set model.sigma0=2.5");
    CHECK(loc.line == 0 && loc.col == 0);
    CHECK(hy_scene_error_at(s, "model", NULL, "sigma0", &err, HY_EINVAL, "too stiff") == HY_EINVAL);
    CHECK_STR(err.msg, "--set model.sigma0=2.5: too stiff");
    /* later overrides win */
    CHECK(hy_scene_set(s, "model.sigma0 = 3", &err) == 0);
    CHECK(hy_scene_get_num(s, "model", NULL, "sigma0", &v) == HY_SCENE_SET);
    CHECK_NEAR(v, 3, 0);
    /* named sections, including names with dots */
    CHECK(hy_scene_set(s, "series.ystar.style=dashed", &err) == 0);
    CHECK(hy_scene_get_enum(s, "series", "ystar", "style", NULL, &t) == HY_SCENE_SET);
    CHECK_STR(t, "dashed");
    CHECK(hy_scene_set(s, "series.y.1.gamma=10", &err) == 0);
    CHECK(hy_scene_get_num(s, "series", "y.1", "gamma", &v) == HY_SCENE_SET);
    CHECK_NEAR(v, 10, 0);
    /* strings, lists, colours: same syntax as in files */
    CHECK(hy_scene_set(s, "figure.title=\"Fig. 15 # not a comment\"", &err) == 0);
    CHECK(hy_scene_get_str(s, "figure", NULL, "title", &t) == HY_SCENE_SET);
    CHECK_STR(t, "Fig. 15 # not a comment");
    CHECK(hy_scene_set(s, "compute.gamma=1,2", &err) == 0);
    const double *l;
    size_t n;
    CHECK(hy_scene_get_list(s, "compute", NULL, "gamma", &l, &n) == HY_SCENE_SET && n == 2 && l[1] == 2);
    hy_scene_color c;
    CHECK(hy_scene_set(s, "series.ystar.color=#0072b2", &err) == 0);
    CHECK(hy_scene_get_color(s, "series", "ystar", "color", &c) == HY_SCENE_SET && c.index == 0);
    CHECK_NEAR(c.b, 0xb2 / 255.0, 1e-15);
    /* an absent unnamed section is created */
    CHECK(hy_scene_count(s, "animation") == 0);
    CHECK(hy_scene_set(s, "animation.quality=1080p60", &err) == 0);
    CHECK(hy_scene_count(s, "animation") == 1);
    CHECK(hy_scene_get_enum(s, "animation", NULL, "quality", NULL, &t) == HY_SCENE_SET);
    CHECK_STR(t, "1080p60");
    CHECK(hy_scene_hash(s) != h0);
    hy_scene_free(s);
}

static void invalid(void)
{
    hy_scene *s = PARSE_OK("s.scene", scene_text);
    uint64_t h0 = hy_scene_hash(s);
    SET_FAILS(s, "model.sigma0", "--set model.sigma0: expected section.key=value");
    SET_FAILS(s, "sigma0=1", "--set sigma0=1: expected section.key=value or section.NAME.key=value");
    SET_FAILS(s, "model.=1", "--set model.=1: expected section.key=value or section.NAME.key=value");
    SET_FAILS(s, ".sigma0=1", "--set .sigma0=1: expected section.key=value or section.NAME.key=value");
    SET_FAILS(s, "modle.sigma0=1", "--set modle.sigma0=1: unknown section [modle]; did you mean 'model'?");
    SET_FAILS(s, "model.sigam0=1", "--set model.sigam0=1: unknown key 'sigam0' in [model]; did you mean 'sigma0'?");
    SET_FAILS(s, "output.where=x", "--set output.where=x: unknown key 'where' in [output]; valid keys are name, formats, dir");
    SET_FAILS(s, "model.sigma0=-1", "--set model.sigma0=-1: 'sigma0' in [model] must be > 0, got -1");
    SET_FAILS(s, "model.sigma0=", "--set model.sigma0=: missing value after '='");
    SET_FAILS(s, "model.sigma0=1 2",
              "--set model.sigma0=1 2: unexpected '2' after the value of 'sigma0' (separate list elements with ',')");
    SET_FAILS(s, "model.sigma0=nan", "--set model.sigma0=nan: 'sigma0' in [model] expects a finite decimal number, got 'nan'");
    SET_FAILS(s, "series.style=dashed", "--set series.style=dashed: [series] sections are named: write series.NAME.style=...");
    SET_FAILS(s, "model.a.sigma0=1", "--set model.a.sigma0=1: [model] takes no name: write model.sigma0=...");
    SET_FAILS(s, "series.ystr.style=dashed", "--set series.ystr.style=dashed: the scene has no section [series ystr]");
    SET_FAILS(s, "series.ystar.style=dahsed",
              "--set series.ystar.style=dahsed: 'style' in [series ystar] must be one of solid, dashed, dotted, dashdot, none, got 'dahsed'; did you mean 'dashed'?");
    SET_FAILS(s, "figure.title=\"open", "--set figure.title=\"open: unterminated string (missing closing '\"')");
    /* nothing changed */
    double v;
    const char *t;
    CHECK(hy_scene_get_num(s, "model", NULL, "sigma0", &v) == HY_SCENE_SET);
    CHECK_NEAR(v, 6, 0);
    CHECK(hy_scene_get_enum(s, "series", "ystar", "style", NULL, &t) == HY_SCENE_SET);
    CHECK_STR(t, "solid");
    CHECK(hy_scene_count(s, "series") == 2 && hy_scene_count(s, "figure") == 0);
    CHECK(hy_scene_hash(s) == h0);
    CHECK(hy_scene_set(s, "model.sigma0=x", NULL) == HY_EINVAL); /* NULL err is allowed */
    hy_scene_free(s);
}

/* No global state: many scenes parsed, overridden and freed in any order. */
static void repeated(void)
{
    hy_scene *a[8];
    hy_error err;
    for (int round = 0; round < 50; round++) {
        for (int i = 0; i < 8; i++) {
            a[i] = PARSE_OK("r.scene", scene_text);
            char set[64];
            snprintf(set, sizeof set, "model.sigma0=%d", i + 1);
            CHECK(a[i] && hy_scene_set(a[i], set, &err) == 0);
        }
        for (int i = 7; i >= 0; i--) {
            double v = 0;
            CHECK(hy_scene_get_num(a[i], "model", NULL, "sigma0", &v) == HY_SCENE_SET && v == i + 1);
            hy_scene_free(a[i]);
        }
    }
    hy_scene_free(NULL);
}

/* The scene as scene text (hy_scene_write with defaults), malloc'ed. */
static char *text_of(const hy_scene *s)
{
    char *buf = NULL;
    size_t len = 0;
    FILE *f = open_memstream(&buf, &len);
    CHECK(f && hy_scene_write(s, f, 1) == HY_OK);
    if (f)
        fclose(f);
    return buf;
}

/* hy_scene_mark / hy_scene_restore (hystviz sweep): a point's overrides on the
 * marked scene give the scene a fresh parse and the same overrides give, and
 * restoring undoes them, sections they created included, over many points. */
static void mark_restore(void)
{
    hy_error err = {0};
    hy_scene *s = PARSE_OK("m.scene", scene_text);
    CHECK(s && hy_scene_set(s, "figure.dpi=100", &err) == 0);
    char *before = text_of(s);
    uint64_t h_mark = hy_scene_hash(s);
    CHECK(hy_scene_mark(s) == HY_OK);
    for (int i = 0; i < 300; i++) {
        char set1[64], set2[64];
        snprintf(set1, sizeof set1, "model.sigma0=%d", i + 1);
        snprintf(set2, sizeof set2, "compute.points=%d", 100 + i); /* [compute]: not in the file */
        hy_scene_restore(s);
        CHECK(hy_scene_set(s, set1, &err) == 0 && hy_scene_set(s, set2, &err) == 0);
        CHECK(hy_scene_set(s, set1, &err) == 0); /* a key set twice */
        hy_scene *fresh = PARSE_OK("m.scene", scene_text);
        CHECK(fresh && hy_scene_set(fresh, "figure.dpi=100", &err) == 0 && hy_scene_set(fresh, set1, &err) == 0 &&
              hy_scene_set(fresh, set2, &err) == 0 && hy_scene_set(fresh, set1, &err) == 0);
        CHECK(hy_scene_hash(s) == hy_scene_hash(fresh));
        char *a = text_of(s), *b = text_of(fresh);
        CHECK(a && b && !strcmp(a, b));
        hy_scene_loc loc;
        CHECK(hy_scene_get_loc(s, "model", NULL, "sigma0", &loc) == 1);
        char label[80];
        snprintf(label, sizeof label, "--set %s", set1);
        CHECK_STR(loc.file, label);
        free(a);
        free(b);
        hy_scene_free(fresh);
    }
    hy_scene_restore(s);
    char *after = text_of(s);
    CHECK(before && after && !strcmp(before, after));
    CHECK(hy_scene_hash(s) == h_mark);
    double v = 0;
    long pts = 0;
    CHECK(hy_scene_get_num(s, "model", NULL, "sigma0", &v) == HY_SCENE_SET && v == 6);
    CHECK(hy_scene_get_int(s, "compute", NULL, "points", &pts) == HY_SCENE_DEFAULT);
    CHECK(hy_scene_get_int(s, "figure", NULL, "dpi", &pts) == HY_SCENE_SET && pts == 100);
    hy_scene_loc loc;
    CHECK(hy_scene_get_loc(s, "model", NULL, "sigma0", &loc) == 1 && loc.line == 2);
    /* a failed override changes nothing; restore without a new mark keeps working */
    CHECK(hy_scene_set(s, "model.sigma0=-1", &err) != 0);
    hy_scene_restore(s);
    CHECK(hy_scene_hash(s) == h_mark);
    free(before);
    free(after);
    hy_scene_free(s);
    /* no mark: restore does nothing */
    s = PARSE_OK("m.scene", scene_text);
    CHECK(s && hy_scene_set(s, "model.sigma0=2", &err) == 0);
    hy_scene_restore(s);
    CHECK(hy_scene_get_num(s, "model", NULL, "sigma0", &v) == HY_SCENE_SET && v == 2);
    hy_scene_free(s);
}

int main(void)
{
    valid();
    invalid();
    repeated();
    mark_restore();
    return st_result("test_scene_set");
}
