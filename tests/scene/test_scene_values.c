/* SPDX-License-Identifier: MIT */
/* test_scene_values.c: value kinds: numbers, integers, bools, enums, strings, lists, lengths, colours, pairs. */
#include "scene_test.h"

static void numbers(void)
{
    hy_scene *s = PARSE_OK("n.scene", "[model]\nsigma0 = 6\nsigma1=0\nfc = 1.5e-3 # comment\n"
                                      "x0 = -.5\n[compute]\ncycles = 3\n");
    double v = 0;
    long i = 0;
    CHECK(hy_scene_get_num(s, "model", NULL, "sigma0", &v) == HY_SCENE_SET);
    CHECK_NEAR(v, 6, 0);
    CHECK(hy_scene_get_num(s, "model", NULL, "sigma1", &v) == HY_SCENE_SET);
    CHECK_NEAR(v, 0, 0);
    CHECK(hy_scene_get_num(s, "model", NULL, "fc", &v) == HY_SCENE_SET);
    CHECK_NEAR(v, 1.5e-3, 0);
    CHECK(hy_scene_get_num(s, "model", NULL, "x0", &v) == HY_SCENE_SET);
    CHECK_NEAR(v, -0.5, 0);
    CHECK(hy_scene_get_num(s, "model", NULL, "fs", &v) == HY_SCENE_DEFAULT);
    CHECK_NEAR(v, 2, 0);
    CHECK(hy_scene_get_int(s, "compute", NULL, "cycles", &i) == HY_SCENE_SET && i == 3);
    CHECK(hy_scene_get_num(s, "compute", NULL, "cycles", &v) == HY_SCENE_SET && v == 3);
    CHECK(hy_scene_get_int(s, "compute", NULL, "points", &i) == HY_SCENE_DEFAULT && i == 2000);
    /* wrong getter kind, unknown key, name on an unnamed section */
    CHECK(hy_scene_get_int(s, "model", NULL, "sigma0", &i) == HY_SCENE_BADKEY);
    CHECK(hy_scene_get_num(s, "model", NULL, "nokey", &v) == HY_SCENE_BADKEY);
    CHECK(hy_scene_get_num(s, "nosection", NULL, "x", &v) == HY_SCENE_BADKEY);
    CHECK(hy_scene_get_num(s, "model", "a", "sigma0", &v) == HY_SCENE_BADKEY);
    /* no default */
    v = 42;
    CHECK(hy_scene_get_num(s, "series", "x", "gamma", &v) == HY_SCENE_ABSENT && v == 42);
    hy_scene_free(s);

    PARSE_FAILS("[model]\nsigma0 = nan\n",
                "t.scene:2:10: 'sigma0' in [model] expects a finite decimal number, got 'nan'");
    PARSE_FAILS("[model]\nsigma0 = inf\n",
                "t.scene:2:10: 'sigma0' in [model] expects a finite decimal number, got 'inf'");
    PARSE_FAILS("[model]\nsigma0 = -Infinity\n",
                "t.scene:2:10: 'sigma0' in [model] expects a finite decimal number, got '-Infinity'");
    PARSE_FAILS("[model]\nsigma0 = 0x10\n",
                "t.scene:2:10: 'sigma0' in [model] expects a finite decimal number, got '0x10'");
    PARSE_FAILS("[model]\nsigma0 = 6abc\n",
                "t.scene:2:10: 'sigma0' in [model] expects a finite decimal number, got '6abc'");
    PARSE_FAILS("[model]\nsigma0 = 1e999\n", "t.scene:2:10: 'sigma0' in [model]: 1e999 does not fit a double");
    PARSE_FAILS("[model]\nsigma0 = 1e\n",
                "t.scene:2:10: 'sigma0' in [model] expects a finite decimal number, got '1e'");
    PARSE_FAILS("[model]\nsigma0 = \"6\"\n",
                "t.scene:2:10: 'sigma0' in [model] expects a number, got a quoted string");
    PARSE_FAILS("[model]\nsigma0 = 0\n", "t.scene:2:10: 'sigma0' in [model] must be > 0, got 0");
    PARSE_FAILS("[model]\nsigma1 = -1\n", "t.scene:2:10: 'sigma1' in [model] must be >= 0, got -1");
    PARSE_FAILS("[figure]\ndpi = 20\n", "t.scene:2:7: 'dpi' in [figure] must be in [36, 2400], got 20");
    PARSE_FAILS("[figure]\ndpi = 72.5\n", "t.scene:2:7: 'dpi' in [figure] expects an integer, got '72.5'");
    PARSE_FAILS("[compute]\nrtol = 1.5\n", "t.scene:2:8: 'rtol' in [compute] must be in (0, 1], got 1.5");
    PARSE_FAILS("[compute]\npoints = 99999999999999999999999\n",
                "t.scene:2:10: 'points' in [compute]: 99999999999999999999999 does not fit an integer");
    PARSE_FAILS("[model]\nsigma0 = 6, 7\n", "t.scene:2:13: 'sigma0' in [model] takes one number, not a list");
}

static void bools_enums_strings(void)
{
    hy_scene *s = PARSE_OK("b.scene",
                           "[figure]\nxlog = true\nylog=false\nkind = loop\n"
                           "xlabel = \"u\"\nylabel = \"y^\\circ_u \\\"q\\\" \\\\ end\"\n"
                           "title = Single\n[output]\nname = fig15_loop_ex4\n");
    int b = -1, idx = -1;
    const char *t = NULL;
    CHECK(hy_scene_get_bool(s, "figure", NULL, "xlog", &b) == HY_SCENE_SET && b == 1);
    CHECK(hy_scene_get_bool(s, "figure", NULL, "ylog", &b) == HY_SCENE_SET && b == 0);
    CHECK(hy_scene_get_bool(s, "figure", NULL, "grid", &b) == HY_SCENE_DEFAULT && b == 0);
    CHECK(hy_scene_get_enum(s, "figure", NULL, "kind", &idx, &t) == HY_SCENE_SET);
    CHECK(idx == 1);
    CHECK_STR(t, "loop");
    CHECK(hy_scene_get_enum(s, "figure", NULL, "legend", NULL, &t) == HY_SCENE_DEFAULT);
    CHECK_STR(t, "best");
    CHECK(hy_scene_get_str(s, "figure", NULL, "xlabel", &t) == HY_SCENE_SET);
    CHECK_STR(t, "u");
    CHECK(hy_scene_get_str(s, "figure", NULL, "ylabel", &t) == HY_SCENE_SET);
    CHECK_STR(t, "y^\\circ_u \"q\" \\ end");
    CHECK(hy_scene_get_str(s, "figure", NULL, "title", &t) == HY_SCENE_SET);
    CHECK_STR(t, "Single");
    CHECK(hy_scene_get_str(s, "figure", NULL, "font", &t) == HY_SCENE_DEFAULT);
    CHECK_STR(t, "serif");
    CHECK(hy_scene_get_str(s, "output", NULL, "name", &t) == HY_SCENE_SET);
    CHECK_STR(t, "fig15_loop_ex4");
    hy_scene_free(s);

    s = PARSE_OK("sub/dir/p.scene", "[input]\nkind = file\nfile = \"data/u.txt\"\n");
    CHECK(hy_scene_get_str(s, "input", NULL, "file", &t) == HY_SCENE_SET);
    CHECK_STR(t, "sub/dir/data/u.txt");
    hy_scene_free(s);
    s = PARSE_OK("p.scene", "[input]\nfile = \"/abs/u.txt\"\n");
    CHECK(hy_scene_get_str(s, "input", NULL, "file", &t) == HY_SCENE_SET);
    CHECK_STR(t, "/abs/u.txt");
    hy_scene_free(s);

    PARSE_FAILS("[figure]\nxlog = yes\n", "t.scene:2:8: 'xlog' in [figure] expects true or false, got 'yes'");
    /* the kinds are the model table's (src/pipeline/meson.build): a new model appends its own */
    char kinds[512] = "", want[700];
    int ms = hy_scene_schema_section("model");
    const char *const *e = hy_scene_schema(NULL)[ms].keys[hy_scene_schema_key(ms, "kind")].enums;
    for (size_t i = 0; e[i]; i++)
        snprintf(kinds + strlen(kinds), sizeof kinds - strlen(kinds), "%s%s", i ? ", " : "", e[i]);
    const char *known = "dahl, lugre, dahl-filter, boucwen, jiles-atherton, preisach, boucwen-operator";
    CHECK(!strncmp(kinds, known, strlen(known)));
    snprintf(want, sizeof want, "t.scene:2:8: 'kind' in [model] must be one of %s, got 'lugr'; did you mean 'lugre'?",
             kinds);
    PARSE_FAILS("[model]\nkind = lugr\n", want);
    snprintf(want, sizeof want, "t.scene:2:8: 'kind' in [model] must be one of %s, got 'coulomb'", kinds);
    PARSE_FAILS("[model]\nkind = coulomb\n", want);
    PARSE_FAILS("[figure]\ntitle = \"abc\n", "t.scene:2:9: unterminated string (missing closing '\"')");
    /* issue 20 item 11: text that is not UTF-8, or holds control characters, is
       refused where it is written (it failed when the figure was drawn) */
    PARSE_FAILS("[figure]\ntitle = \"ab\xff\"\n", "t.scene:2:12: 'title' in [figure] is not valid UTF-8 text (byte \\xff)");
    PARSE_FAILS("[figure]\nxlabel = \"u \xc3(\"\n", "t.scene:2:13: 'xlabel' in [figure] is not valid UTF-8 text (byte \\xc3)");
    PARSE_FAILS("[figure]\ntitle = \"a\x1b[31m\"\n", "t.scene:2:11: 'title' in [figure] holds a control character (byte \\x1b)");
    hy_scene_free(PARSE_OK("u.scene", "[figure]\ntitle = \"\xce\xb3 \xe2\x86\xbb\tloops\"\n"));
    PARSE_FAILS("[figure]\ntitle = Hello world\n",
                "t.scene:2:15: unexpected 'w' after the value of 'title' (quote text that contains spaces)");
    PARSE_FAILS("[figure]\ntitle = \"a\" \"b\"\n",
                "t.scene:2:13: unexpected '\"' after the value of 'title' (quote text that contains spaces)");
    PARSE_FAILS("[output]\nname = \"fig 15\"\n",
                "t.scene:2:8: 'name' in [output] must be a name of letters, digits, '_', '-' and '.', got 'fig 15'");
}

static void lists(void)
{
    hy_scene *s = PARSE_OK("l.scene", "[compute]\ngamma = 1, 10,100\nk=0 , 3\n"
                                      "[input]\npoints = 0, 0, 1, 1, 2, 0\n[output]\nformats = svg, png\n");
    const double *v = NULL;
    size_t n = 0;
    const char *t = NULL;
    CHECK(hy_scene_get_list(s, "compute", NULL, "gamma", &v, &n) == HY_SCENE_SET && n == 3);
    CHECK(n == 3 && v[0] == 1 && v[1] == 10 && v[2] == 100);
    CHECK(hy_scene_get_list(s, "compute", NULL, "k", &v, &n) == HY_SCENE_SET && n == 2);
    CHECK(n == 2 && v[0] == 0 && v[1] == 3);
    CHECK(hy_scene_get_list(s, "input", NULL, "points", &v, &n) == HY_SCENE_SET && n == 6);
    CHECK(hy_scene_get_enum_at(s, "output", NULL, "formats", 0, &t, &n) == HY_SCENE_SET && n == 2);
    CHECK_STR(t, "svg");
    CHECK(hy_scene_get_enum_at(s, "output", NULL, "formats", 1, &t, &n) == HY_SCENE_SET);
    CHECK_STR(t, "png");
    CHECK(hy_scene_get_enum_at(s, "output", NULL, "formats", 2, &t, &n) == HY_SCENE_BADKEY);
    hy_scene_free(s);

    s = PARSE_OK("l.scene", "");
    CHECK(hy_scene_get_list(s, "compute", NULL, "k", &v, &n) == HY_SCENE_DEFAULT && n == 4);
    CHECK(hy_scene_get_list(s, "input", NULL, "t", &v, &n) == HY_SCENE_ABSENT);
    hy_scene_free(s);

    PARSE_FAILS("[compute]\ngamma = 1, 0, 3\n", "t.scene:2:12: 'gamma' in [compute] must be > 0, got 0");
    PARSE_FAILS("[compute]\ngamma = 1,, 3\n", "t.scene:2:11: empty list element before ','");
    PARSE_FAILS("[compute]\ngamma = 1, 2,\n", "t.scene:2:14: empty list element after ','");
    PARSE_FAILS("[compute]\ngamma = 1 2\n",
                "t.scene:2:11: unexpected '2' after the value of 'gamma' (separate list elements with ',')");
    PARSE_FAILS("[compute]\nk = 1, 2.5\n", "t.scene:2:8: 'k' in [compute] expects an integer, got '2.5'");
    PARSE_FAILS("[input]\nt = 1, 2, 3\n", "t.scene:2:5: 't' in [input] needs at least 4 elements, got 3");
    PARSE_FAILS("[input]\nt = 1, 2, 3, 4, 5\n", "t.scene:2:17: 't' in [input] takes at most 4 elements, got 5");
    PARSE_FAILS("[input]\npoints = 0, 0, 1, 1, 2\n",
                "t.scene:2:22: 'points' in [input] needs an even number of elements (pairs), got 5");
    PARSE_FAILS("[output]\nformats = svg, jpg\n",
                "t.scene:2:16: 'formats' in [output] must be one of svg, pdf, png, got 'jpg'");
    PARSE_FAILS("[compute]\ngamma =\n", "t.scene:2:8: missing value after '='");
    PARSE_FAILS("[compute]\ngamma = # nothing\n", "t.scene:2:9: missing value after '='");
}

static void lengths(void)
{
    hy_scene *s = PARSE_OK("len.scene", "[figure]\nsize = 12cm, 3in\nfontsize = 10\ndpi = 144\n"
                                        "[series a]\nwidth = 288px\n[series b]\nwidth = 2.54mm\n");
    double p[2], v;
    CHECK(hy_scene_get_length_pair_pt(s, "figure", NULL, "size", p) == HY_SCENE_SET);
    CHECK_NEAR(p[0], 12 * 72 / 2.54, 1e-12);
    CHECK_NEAR(p[1], 216, 1e-12);
    CHECK(hy_scene_get_length_pt(s, "figure", NULL, "fontsize", &v) == HY_SCENE_SET);
    CHECK_NEAR(v, 10, 0);
    CHECK(hy_scene_get_length_pt(s, "series", "a", "width", &v) == HY_SCENE_SET);
    CHECK_NEAR(v, 144, 1e-12); /* 288 px at 144 dpi = 2 in */
    CHECK(hy_scene_get_length_pt(s, "series", "b", "width", &v) == HY_SCENE_SET);
    CHECK_NEAR(v, 7.2, 1e-12);
    hy_scene_free(s);

    s = PARSE_OK("len.scene", "[series a]\nwidth = 300px\n");
    CHECK(hy_scene_get_length_pt(s, "series", "a", "width", &v) == HY_SCENE_SET);
    CHECK_NEAR(v, 72, 1e-12); /* default dpi 300 */
    CHECK(hy_scene_get_length_pair_pt(s, "figure", NULL, "size", p) == HY_SCENE_DEFAULT);
    CHECK_NEAR(p[0], 12 * 72 / 2.54, 1e-12);
    CHECK(hy_scene_get_length_pt(s, "figure", NULL, "fontsize", &v) == HY_SCENE_DEFAULT);
    CHECK_NEAR(v, 9, 0);
    hy_scene_free(s);

    PARSE_FAILS("[figure]\nfontsize = 9em\n",
                "t.scene:2:12: 'fontsize' in [figure]: unknown unit in '9em' (use pt, cm, mm, in or px)");
    PARSE_FAILS("[figure]\nfontsize = 0pt\n", "t.scene:2:12: 'fontsize' in [figure] must be > 0, got 0pt");
    PARSE_FAILS("[figure]\nsize = 12cm\n",
                "t.scene:2:8: 'size' in [figure] expects two lengths, got 1 element");
    PARSE_FAILS("[figure]\nfontsize = cm\n",
                "t.scene:2:12: 'fontsize' in [figure] expects a length such as 9pt, 1.2cm, 3mm, 1in or 12px, got 'cm'");
}

static void colors(void)
{
    hy_scene *s = PARSE_OK("c.scene", "[series a]\ncolor = 2\n[series b]\ncolor = vermillion\n"
                                      "[series c]\ncolor = #FF8000 # a comment\n[series d]\ncolor = black\n");
    hy_scene_color c;
    CHECK(hy_scene_get_color(s, "series", "a", "color", &c) == HY_SCENE_SET);
    CHECK(c.index == 2);
    CHECK_NEAR(c.r, 0x56 / 255.0, 1e-15);
    CHECK_NEAR(c.g, 0xB4 / 255.0, 1e-15);
    CHECK_NEAR(c.b, 0xE9 / 255.0, 1e-15);
    CHECK(hy_scene_get_color(s, "series", "b", "color", &c) == HY_SCENE_SET && c.index == 6);
    CHECK_NEAR(c.r, 0xD5 / 255.0, 1e-15);
    CHECK(hy_scene_get_color(s, "series", "c", "color", &c) == HY_SCENE_SET && c.index == 0);
    CHECK_NEAR(c.r, 1, 0);
    CHECK_NEAR(c.g, 128 / 255.0, 1e-15);
    CHECK_NEAR(c.b, 0, 0);
    CHECK(hy_scene_get_color(s, "series", "d", "color", &c) == HY_SCENE_SET && c.index == 8);
    CHECK(hy_scene_get_color(s, "series", "zz", "color", &c) == HY_SCENE_ABSENT);
    hy_scene_free(s);

    PARSE_FAILS("[series a]\ncolor = 9\n",
                "t.scene:2:9: 'color' in [series a]: Okabe-Ito colour index must be in [1, 8], got 9");
    PARSE_FAILS("[series a]\ncolor = skyblu\n",
                "t.scene:2:9: 'color' in [series a] expects a colour (1-8, an Okabe-Ito name or #rrggbb), got 'skyblu'; did you mean 'skyblue'?");
    PARSE_FAILS("[series a]\ncolor = #12345\n",
                "t.scene:2:9: missing value after '=' ('#' starts a comment unless it opens a #rrggbb colour)");
    PARSE_FAILS("[series a]\ncolor = #ff00ff0\n", "t.scene:2:9: missing value after '=' ('#' starts a comment unless it opens a #rrggbb colour)");
}

static void pairs(void)
{
    hy_scene *s = PARSE_OK("p.scene", "[figure]\nxlim = 0, 1.5\nylim = auto\nshade = 1, 1.8\n"
                                      "[compute]\ntspan = 0, 4.6\n");
    double p[2] = {-1, -1};
    int a = -1;
    CHECK(hy_scene_get_pair(s, "figure", NULL, "xlim", p, &a) == HY_SCENE_SET && a == 0);
    CHECK(p[0] == 0 && p[1] == 1.5);
    p[0] = p[1] = -7;
    CHECK(hy_scene_get_pair(s, "figure", NULL, "ylim", p, &a) == HY_SCENE_SET && a == 1);
    CHECK(p[0] == -7 && p[1] == -7);
    CHECK(hy_scene_get_pair(s, "figure", NULL, "shade", p, NULL) == HY_SCENE_SET);
    CHECK(p[0] == 1 && p[1] == 1.8);
    CHECK(hy_scene_get_pair(s, "compute", NULL, "tspan", p, NULL) == HY_SCENE_SET);
    CHECK(p[0] == 0 && p[1] == 4.6);
    hy_scene_free(s);

    s = PARSE_OK("p.scene", "");
    CHECK(hy_scene_get_pair(s, "figure", NULL, "xlim", p, &a) == HY_SCENE_DEFAULT && a == 1);
    CHECK(hy_scene_get_pair(s, "figure", NULL, "shade", p, &a) == HY_SCENE_ABSENT);
    hy_scene_free(s);

    PARSE_FAILS("[figure]\nxlim = 2, 1\n", "t.scene:2:11: 'xlim' in [figure] needs first < second, got 2, 1");
    PARSE_FAILS("[figure]\nxlim = 1\n",
                "t.scene:2:8: 'xlim' in [figure] expects two numbers or auto, got 1 element");
    PARSE_FAILS("[figure]\nxlim = 1, 2, 3\n",
                "t.scene:2:14: 'xlim' in [figure] expects two numbers or auto, got 3 elements");
    PARSE_FAILS("[compute]\ntspan = auto\n",
                "t.scene:2:9: 'tspan' in [compute] expects two numbers, got 1 element");
}

int main(void)
{
    numbers();
    bools_enums_strings();
    lists();
    lengths();
    colors();
    pairs();
    return st_result("test_scene_values");
}
