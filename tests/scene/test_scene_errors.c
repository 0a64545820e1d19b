/* SPDX-License-Identifier: MIT */
/* test_scene_errors.c: every structural error class, its location and message text. */
#include "scene_test.h"

static void syntax(void)
{
    PARSE_FAILS("[model]\nsigma0 6\n", "t.scene:2:8: missing '=' after key 'sigma0'");
    PARSE_FAILS("[model]\nsigma0\n", "t.scene:2:7: missing '=' after key 'sigma0'");
    PARSE_FAILS("[model]\n= 6\n", "t.scene:2:1: expected 'key = value', '[section]' or 'include \"file\"', got '='");
    PARSE_FAILS("[model\n", "t.scene:1:7: bad section header: expected ']'");
    PARSE_FAILS("[]\n", "t.scene:1:2: bad section header: expected a section name after '['");
    PARSE_FAILS("[series a b]\n", "t.scene:1:11: bad section header: expected ']' after the section name");
    PARSE_FAILS("[model] x\n", "t.scene:1:9: unexpected 'x' after the section header");
    PARSE_FAILS("  [series a!]\n", "t.scene:1:12: bad section header: expected ']' after the section name");
    PARSE_FAILS("[model]\n\x01\n", "t.scene:2:1: expected 'key = value', '[section]' or 'include \"file\"', got '\\x01'");
    /* issue 20 item 10: a refused value is quoted cut to 40 bytes, controls as \xNN */
    PARSE_FAILS("[figure]\nkind = a\x1b]0;PWNED-TITLE\x07\x1b[31mRED\xffxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxx\n",
                "t.scene:2:8: 'kind' in [figure] must be one of timeseries, loop, input, g, psi, forc, got "
                "'a\\x1b]0;PWNED-TITLE\\x07\\x1b[31mRED\\xffxxxxxxxxxxxxxx...'");
    PARSE_FAILS("sigma0 = 1\n", "t.scene:1:1: key 'sigma0' outside any section (start one with a [section] header)");
    PARSE_FAILS("[figure]\ntitle = \"x\" junk\n",
                "t.scene:2:13: unexpected 'j' after the value of 'title' (quote text that contains spaces)");
    PARSE_FAILS("[model]\nsigma0 = 6 7\n",
                "t.scene:2:12: unexpected '7' after the value of 'sigma0' (separate list elements with ',')");
    PARSE_FAILS("# c\n\n[model]\r\nsigma0 = 1\r\nfc = \"1\r\n",
                "t.scene:5:6: unterminated string (missing closing '\"')");
    /* comments and blank lines and CRLF are fine; the header column is kept */
    hy_scene *s = PARSE_OK("ok.scene", "\xEF\xBB\xBF# a scene\r\n\r\n   [model]   # c\r\n\tsigma0\t=\t2\r\n");
    hy_scene_loc loc;
    CHECK(hy_scene_get_loc(s, "model", NULL, NULL, &loc) == 1);
    CHECK_STR(loc.file, "ok.scene");
    CHECK(loc.line == 3 && loc.col == 4);
    CHECK(hy_scene_get_loc(s, "model", NULL, "sigma0", &loc) == 1);
    CHECK(loc.line == 4 && loc.col == 2);
    CHECK(hy_scene_get_loc(s, "model", NULL, "fc", &loc) == 0);
    hy_scene_free(s);
}

static void structure(void)
{
    PARSE_FAILS("[modle]\n", "t.scene:1:2: unknown section [modle]; did you mean 'model'?");
    PARSE_FAILS("[camera]\n", "t.scene:1:2: unknown section [camera]");
    PARSE_FAILS("[model]\nsigam0 = 6\n", "t.scene:2:1: unknown key 'sigam0' in [model]; did you mean 'sigma0'?");
    PARSE_FAILS("[figure]\n  xlable = \"u\"\n", "t.scene:2:3: unknown key 'xlable' in [figure]; did you mean 'xlabel'?");
    PARSE_FAILS("[series a]\ncolour = 2\n", "t.scene:2:1: unknown key 'colour' in [series a]; did you mean 'color'?");
    /* [model]'s keys: the shared rows, then each model's own in table order (a new model appends its own) */
    char keys[1024] = "", want[1200];
    const hy_scene_section_spec *ms = hy_scene_schema(NULL) + hy_scene_schema_section("model");
    for (size_t i = 0; i < ms->nkeys; i++)
        snprintf(keys + strlen(keys), sizeof keys - strlen(keys), "%s%s", i ? ", " : "", ms->keys[i].name);
    const char *known = "kind, sigma0, sigma1, sigma2, fc, fs, vs, beta, rho, x0, tau, m, c, k, alpha, bw_beta, "
                        "bw_gamma, delta, nu, ja_ms, ja_a, ja_k, ja_c, ja_alpha, ja_m0, ja_variant, pr_density, pr_hc, "
                        "pr_width, pr_ys, pr_start, pr_support, pr_hs";
    CHECK(!strncmp(keys, known, strlen(known)));
    snprintf(want, sizeof want, "t.scene:2:1: unknown key 'zzzzzz' in [model]; valid keys are %s", keys);
    PARSE_FAILS("[model]\nzzzzzz = 6\n", want);
    PARSE_FAILS("[model]\nsigma0 = 1\nfc = 2\nsigma0 = 3\n",
                "t.scene:4:1: duplicate key 'sigma0' in [model] (first set at line 2)");
    PARSE_FAILS("[model]\nsigma0 = 1\n[input]\n[model]\n", "t.scene:4:1: duplicate section [model] (first at line 1)");
    PARSE_FAILS("[series a]\n[series b]\n[series a]\n", "t.scene:3:1: duplicate section [series a] (first at line 1)");
    PARSE_FAILS("[series]\n", "t.scene:1:2: section [series] needs a name, as in [series NAME]");
    PARSE_FAILS("[model lugre]\n", "t.scene:1:8: section [model] takes no name, got 'lugre'");
}

static void named_sections(void)
{
    hy_scene *s = PARSE_OK("n.scene", "[series ystar]\ndata = ystar\n[model]\n[series y1]\ndata = ygamma\ngamma = 1\n"
                                      "[annotation t1]\ntext = \"t_1\"\nx = 1\ny = 0.5\n[series y.10]\ndata = ygamma\n");
    CHECK(hy_scene_count(s, "series") == 3);
    CHECK(hy_scene_count(s, "model") == 1);
    CHECK(hy_scene_count(s, "input") == 0);
    CHECK(hy_scene_count(s, "annotation") == 1);
    CHECK_STR(hy_scene_name_at(s, "series", 0), "ystar");
    CHECK_STR(hy_scene_name_at(s, "series", 1), "y1");
    CHECK_STR(hy_scene_name_at(s, "series", 2), "y.10");
    CHECK(hy_scene_name_at(s, "series", 3) == NULL);
    CHECK(hy_scene_name_at(s, "model", 0) == NULL);
    const char *t;
    CHECK(hy_scene_get_enum(s, "series", "y1", "data", NULL, &t) == HY_SCENE_SET);
    CHECK_STR(t, "ygamma");
    CHECK(hy_scene_get_str(s, "annotation", "t1", "text", &t) == HY_SCENE_SET);
    CHECK_STR(t, "t_1");
    hy_error err;
    CHECK(hy_scene_error_at(s, "series", "y1", "gamma", &err, HY_EINVAL,
                            "gamma %d is too small for the solver", 1) == HY_EINVAL);
    CHECK_STR(err.msg, "n.scene:6:1: gamma 1 is too small for the solver");
    CHECK(hy_scene_error_at(s, "series", "y1", "k", &err, HY_EINVAL, "a ygamma curve needs k") == HY_EINVAL);
    CHECK_STR(err.msg, "n.scene:4:1: a ygamma curve needs k");
    hy_scene_error_at(s, "input", NULL, "kind", &err, HY_EINVAL, "no input");
    CHECK_STR(err.msg, "n.scene: no input");
    CHECK_STR(hy_scene_source(s), "n.scene");
    hy_scene_free(s);
}

static void missing_file(void)
{
    hy_scene *s = (hy_scene *)1;
    hy_error err;
    CHECK(hy_scene_parse_file("/nonexistent/dir/x.scene", &s, &err) == HY_EIO);
    CHECK(s == NULL);
    CHECK_STR(err.msg, "/nonexistent/dir/x.scene: cannot read scene file: No such file or directory");
    CHECK(hy_scene_parse_buffer("x", "[x]", 3, &s, NULL) == HY_EINVAL); /* NULL err is allowed */
    CHECK(s == NULL);
    static const char nul[] = "[model]\nsigma0 = 1\0\n";
    CHECK(hy_scene_parse_buffer("t.scene", nul, sizeof nul - 1, &s, &err) == HY_EINVAL);
    CHECK_STR(err.msg, "t.scene:2:1: NUL byte in scene text");
}

int main(void)
{
    syntax();
    structure();
    named_sections();
    missing_file();
    return st_result("test_scene_errors");
}
