/* SPDX-License-Identifier: MIT */
/* test_scene_param.c: named parameters ([param NAME], key = $NAME): values, overrides, mark/restore, writing,
 * and every error at its file:line:col. */
#include "scene_test.h"

static const char *text =
    "[series t20]\n"
    "data = transient\n"
    "gamma = $g20   # the transient's\n"
    "[series g20]\n"
    "data = ygamma\n"
    "gamma = $g20\n"
    "[series g200]\n"
    "data = ygamma\n"
    "gamma = 200\n"
    "[compute]\n"
    "points = $n\n"
    "[param g20]\n"
    "value = 20\n"
    "[param n]\n"
    "value = 300\n";

static double num(const hy_scene *s, const char *sec, const char *name, const char *key)
{
    double v = -999;
    CHECK(hy_scene_get_num(s, sec, name, key, &v) == HY_SCENE_SET);
    return v;
}

static void values(void)
{
    hy_scene *s = PARSE_OK("p.scene", text);
    hy_error err = {0, ""};
    long n = 0;
    if (!s)
        return;
    CHECK(num(s, "series", "t20", "gamma") == 20 && num(s, "series", "g20", "gamma") == 20);
    CHECK(hy_scene_get_int(s, "compute", NULL, "points", &n) == HY_SCENE_SET && n == 300);
    CHECK_STR(hy_scene_get_ref(s, "series", "t20", "gamma"), "g20");
    CHECK(hy_scene_get_ref(s, "series", "g200", "gamma") == NULL);
    CHECK(hy_scene_get_ref(s, "series", "nope", "gamma") == NULL);
    /* the parameter moves both readers; the scene after restore is as parsed */
    uint64_t h0 = hy_scene_hash(s);
    hy_scene_mark(s);
    CHECK(hy_scene_set(s, "param.g20.value=35.5", &err) == 0);
    CHECK(num(s, "series", "t20", "gamma") == 35.5 && num(s, "series", "g20", "gamma") == 35.5);
    CHECK(num(s, "series", "g200", "gamma") == 200);
    /* one reader gets its own value, or reads another parameter */
    CHECK(hy_scene_set(s, "series.g20.gamma=7", &err) == 0);
    CHECK(hy_scene_get_ref(s, "series", "g20", "gamma") == NULL);
    CHECK(hy_scene_set(s, "param.g20.value=8", &err) == 0);
    CHECK(num(s, "series", "t20", "gamma") == 8 && num(s, "series", "g20", "gamma") == 7);
    CHECK(hy_scene_set(s, "series.g200.gamma=$n", &err) == 0);
    CHECK(num(s, "series", "g200", "gamma") == 300);
    CHECK_STR(hy_scene_get_ref(s, "series", "g200", "gamma"), "n");
    hy_scene_restore(s);
    CHECK(hy_scene_hash(s) == h0);
    CHECK(num(s, "series", "t20", "gamma") == 20 && num(s, "series", "g20", "gamma") == 20);
    CHECK(num(s, "series", "g200", "gamma") == 200);
    CHECK_STR(hy_scene_get_ref(s, "series", "g20", "gamma"), "g20");
    CHECK(hy_scene_get_ref(s, "series", "g200", "gamma") == NULL);
    /* refused: the scene stays as it was */
    SET_FAILS(s, "param.g20.value=-1",
              "--set param.g20.value=-1: 'gamma' in [series t20] must be > 0, got -1 (it reads $g20 at p.scene:3)");
    SET_FAILS(s, "param.n.value=2.5",
              "--set param.n.value=2.5: 'points' in [compute] expects an integer, got '2.5' (it reads $n at p.scene:11)");
    SET_FAILS(s, "series.g200.gamma=$g2", "--set series.g200.gamma=$g2: unknown parameter $g2: the scene has no "
              "[param g2] with a value");
    SET_FAILS(s, "series.g200.style=$g20", "--set series.g200.style=$g20: 'style' in [series g200] cannot read a "
              "parameter ($NAME): only number and integer keys can");
    CHECK(num(s, "series", "t20", "gamma") == 20 && num(s, "series", "g200", "gamma") == 200);
    CHECK(hy_scene_hash(s) == h0);
    hy_scene_free(s);
}

/* Written back, the scene keeps its references and parses to the same values. */
static void write_back(void)
{
    hy_scene *s = PARSE_OK("p.scene", text), *t = NULL;
    hy_error err = {0, ""};
    char *buf = NULL;
    size_t len = 0;
    FILE *f = open_memstream(&buf, &len);
    if (!s || !f)
        return;
    CHECK(hy_scene_set(s, "param.g20.value=40", &err) == 0);
    CHECK(hy_scene_write(s, f, 0) == HY_OK);
    fclose(f);
    CHECK(strstr(buf, "gamma = $g20") != NULL);
    CHECK(hy_scene_parse_buffer("w.scene", buf, len, &t, &err) == 0);
    if (t) {
        CHECK(num(t, "series", "t20", "gamma") == 40 && num(t, "series", "g20", "gamma") == 40);
        CHECK_STR(hy_scene_get_ref(t, "series", "g20", "gamma"), "g20");
    }
    hy_scene_free(t);
    hy_scene_free(s);
    free(buf);
}

static void errors(void)
{
    PARSE_FAILS("[series a]\ngamma = $gama\n[param gamma]\nvalue = 1\n",
                "t.scene:2:9: unknown parameter $gama; did you mean $gamma?");
    PARSE_FAILS("[series a]\ngamma =  $zz\n", "t.scene:2:10: unknown parameter $zz: the scene has no [param zz]");
    PARSE_FAILS("[series a]\ngamma = $p\n[param p]\n", "t.scene:2:9: parameter $p: [param p] sets no value");
    PARSE_FAILS("[series a]\ngamma = $p\n[param p]\nvalue = -2\n",
                "t.scene:2:9: $p = -2: 'gamma' in [series a] must be > 0, got -2");
    PARSE_FAILS("[compute]\npoints = $p\n[param p]\nvalue = 1.5\n",
                "t.scene:2:10: $p = 1.5: 'points' in [compute] expects an integer, got '1.5'");
    PARSE_FAILS("[series a]\ngamma = $\n", "t.scene:2:9: expected a parameter name after '$' (a [param NAME] of the scene)");
    PARSE_FAILS("[series a]\ngamma = $p q\n", "t.scene:2:12: unexpected 'q' after the parameter $p");
    PARSE_FAILS("[series a]\nstyle = $p\n",
                "t.scene:2:9: 'style' in [series a] cannot read a parameter ($NAME): only number and integer keys can");
    /* a parameter's value is a number: a reference there cannot make a cycle */
    PARSE_FAILS("[param a]\nvalue = $b\n[param b]\nvalue = $a\n",
                "t.scene:2:9: 'value' in [param a] is a number: a parameter cannot read another ($NAME)");
    PARSE_FAILS("[param]\nvalue = 1\n", "t.scene:1:2: section [param] needs a name, as in [param NAME]");
}

/* Caption placeholders: replaced by the values the scene has now; other braces stay. */
static void captions(void)
{
    static const char cap[] = "[model]\nsigma0 = 6\n[input]\nkind = bimodal\n[figure]\n"
                              "caption = \"σ0 = {model.sigma0}, u_min,2 = {input.umin2}, {model.kind}; y*_{u,k} {x} {g.y}\"\n";
    hy_scene *s = PARSE_OK("c.scene", cap);
    hy_error err = {0, ""};
    char *out = NULL;
    const char *c = NULL;
    if (!s)
        return;
    CHECK(hy_scene_get_str(s, "figure", NULL, "caption", &c) == HY_SCENE_SET);
    CHECK(hy_scene_expand(s, c, &out, &err) == HY_OK);
    CHECK_STR(out, "σ0 = 6, u_min,2 = 0.2, lugre; y*_{u,k} {x} {g.y}");
    free(out);
    CHECK(hy_scene_set(s, "model.sigma0=60", &err) == 0 && hy_scene_set(s, "input.umin2=0.25", &err) == 0);
    CHECK(hy_scene_expand(s, c, &out, &err) == HY_OK);
    CHECK_STR(out, "σ0 = 60, u_min,2 = 0.25, lugre; y*_{u,k} {x} {g.y}");
    free(out);
    out = NULL;
    CHECK(hy_scene_expand(s, "{series.none.gamma}", &out, &err) == HY_EINVAL && out == NULL);
    CHECK_STR(err.msg, "'{series.none.gamma}' has no value in this scene (is the section's name right?)");
    hy_scene_free(s);
    PARSE_FAILS("[figure]\ncaption = \"σ0 = {model.sigma}\"\n",
                "t.scene:2:1: caption: '{model.sigma}' names no key of the scene format (write {section.key} or "
                "{section.NAME.key})");
    PARSE_FAILS("[series a]\ndata = ygamma\nlabel = \"\\\\gamma = {param.g.value}\"\n",
                "t.scene:3:1: label: '{param.g.value}' has no value in this scene (is the section's name right?)");
    PARSE_FAILS("[figure]\ncaption = \"{figure.xlim}\"\n",
                "t.scene:2:1: caption: '{figure.xlim}' (limits) cannot be shown: a placeholder shows a number, an identifier or a name");
}

int main(void)
{
    captions();
    values();
    write_back();
    errors();
    return st_done("test_scene_param");
}
