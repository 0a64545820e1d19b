/* SPDX-License-Identifier: MIT */
/* test_markup.c: markup parser token sequences for the paper's labels, errors, and script layout. */
#include <stdio.h>
#include <string.h>

#include "hy_markup.h"

#include "../hy_test.h"

/* Renders runs as "text/script/italic/group" joined by spaces. */
static void describe(const hy_mrun *r, size_t n, char *out, size_t cap)
{
    static const char sc[] = "BPB";
    out[0] = '\0';
    for (size_t i = 0; i < n; i++) {
        char one[4096];
        snprintf(one, sizeof one, "%s[%s|%c%s|%d]", i ? " " : "", r[i].text,
                 r[i].script == HY_SCRIPT_SUB ? 'b' : sc[r[i].script], r[i].italic ? "i" : "",
                 r[i].group);
        strncat(out, one, cap - strlen(out) - 1);
    }
}

static void expect(const char *src, const char *want)
{
    hy_mrun r[HY_MARKUP_MAX];
    size_t n;
    hy_error err;
    char got[2048];
    int rc = hy_markup_parse(src, r, HY_MARKUP_MAX, &n, &err);
    HY_CHECK(!rc, "\"%s\": %s", src, err.msg);
    if (rc)
        return;
    describe(r, n, got, sizeof got);
    HY_CHECK(!strcmp(got, want), "\"%s\"\n  got  %s\n  want %s", src, got, want);
}

static void expect_error(const char *src, const char *needle)
{
    hy_mrun r[HY_MARKUP_MAX];
    size_t n;
    hy_error err = {0, ""};
    HY_CHECK(hy_markup_parse(src, r, HY_MARKUP_MAX, &n, &err) && strstr(err.msg, needle),
             "\"%s\" should fail mentioning \"%s\" (got \"%s\")", src, needle, err.msg);
}

/* A fake backend: every byte advances 0.5 em; text calls are counted. */
static int ntext;
static void f_measure(void *ctx, const char *s, double size, int italic, hy_text_extents *e)
{
    (void)ctx, (void)italic;
    memset(e, 0, sizeof *e);
    e->advance = 0.5 * size * (double)strlen(s);
}
static void f_text(void *ctx, double x, double y, const char *s, double size, int it, int v, hy_rgb c)
{
    (void)ctx, (void)x, (void)y, (void)s, (void)size, (void)it, (void)v, (void)c;
    ntext++;
}
static const hy_canvas_ops fake_ops = {.name = "fake", .measure = f_measure, .text = f_text};

int main(void)
{
    /* U+00B0 degree, U+03B3 gamma, U+03C3 sigma, U+03C8 psi, U+03F1 varrho, U+2016, U+2212, U+221E */
    expect("y^\\circ_u", "[y|Bi|0] [\xC2\xB0|P|1] [u|bi|1]");
    expect("y^*_{u,k}(t)", "[y|Bi|0] [*|P|1] [u|bi|1] [,|b|1] [k|bi|1] [(|B|0] [t|Bi|0] [)|B|0]");
    expect("\\sigma_0 = 6", "[\xCF\x83|Bi|0] [0|b|1] [ = 6|B|0]");
    expect("\\psi_u(\\varrho)", "[\xCF\x88|Bi|0] [u|bi|1] [(|B|0] [\xCF\xB1|Bi|0] [)|B|0]");
    /* lowercase Greek is a variable (italic), uppercase and \\mathrm Greek upright; UTF-8 Greek too */
    expect("\\Gamma \\mathrm{\\gamma} \xCE\xBD", "[\xCE\x93 \xCE\xB3 |B|0] [\xCE\xBD|Bi|0]");
    expect("\\|y_\\gamma - y^*_u\\|_\\infty",
           "[\xE2\x80\x96|B|0] [y|Bi|0] [\xCE\xB3|bi|1] [ \xE2\x88\x92 |B|0] [y|Bi|0] [*|P|2] [u|bi|2] "
           "[\xE2\x80\x96|B|0] [\xE2\x88\x9E|b|3]");
    expect("g(v)", "[g|Bi|0] [(|B|0] [v|Bi|0] [)|B|0]");
    expect("$\\sigma_0$", "[\xCF\x83|Bi|0] [0|b|1]");
    expect("area = 0.123", "[area = 0.123|B|0]");
    expect("Bouc-Wen", "[Bouc-Wen|B|0]");
    expect("10^{-3}\\times F_s", "[10|B|0] [\xE2\x88\x92" "3|P|1] [\xC3\x97 |B|0] [F|Bi|0] [s|bi|2]");
    expect("u_{\\min,2}", "[u|Bi|0] [min,2|b|1]");
    expect("x_a^b_c", "[x|Bi|0] [a|bi|1] [b|Pi|1] [c|bi|2]");
    expect("\\mathrm{d}t", "[d|B|0] [t|Bi|0]");
    expect_error("y_{u", "missing '}'");
    expect_error("a}", "unbalanced");
    expect_error("\\foo", "\\foo");
    expect_error("x^", "no argument");

    /* Layout: a stacked sup/sub takes the wider of the two, scripts at 70 %. */
    hy_canvas cv = {&fake_ops, NULL};
    hy_markup_box b;
    hy_mrun r[HY_MARKUP_MAX];
    size_t n;
    hy_markup_parse("y^*_u", r, HY_MARKUP_MAX, &n, NULL);
    hy_markup_layout(&cv, r, n, 10.0, 1, 0, 0, 0, (hy_rgb){0, 0, 0}, &b);
    double want = 5.0 + 0.8 + 3.5; /* y, italic correction of the superscript, * at 7 pt */
    HY_CHECK(!(b.width < want - 1e-9 || b.width > want + 1e-9 || ntext != 3),
             "layout y^*_u: width %g (want %g), %d text calls (want 3)", b.width, want, ntext);
    /* a subscript alone tucks under its italic base: no gap before it (u_{min,2}) */
    hy_markup_parse("u_2", r, HY_MARKUP_MAX, &n, NULL);
    hy_markup_layout(&cv, r, n, 10.0, 0, 0, 0, 0, (hy_rgb){0, 0, 0}, &b);
    want = 5.0 - 0.3 + 3.5;
    HY_CHECK(!(b.width < want - 1e-9 || b.width > want + 1e-9),
             "layout u_2: width %g (want %g: the subscript starts 0.03 em left of the base's advance)", b.width, want);
    HY_CHECK(b.ascent > 7.8 && b.descent > 2.4, "layout y^*_u: ascent %g descent %g do not include the scripts",
             b.ascent, b.descent);
    /* numbers in labels: as a reader writes them */
    const struct { double v; const char *want; } nums[] = {
        {1000, "1000"}, {1e3 + 0.5, "1000"}, {0.25, "0.25"}, {-0.043, "-0.043"}, {6.3341, "6.334"},
        {1e-4, "10^{-4}"}, {1.424e-4, "1.424\\times10^{-4}"}, {9.99996e-5, "10^{-4}"}, {2.5e7, "2.5\\times10^{7}"},
        {-3e-6, "-3\\times10^{-6}"}, {0, "0"}, {12345.6, "1.235\\times10^{4}"},
    };
    for (size_t i = 0; i < sizeof nums / sizeof nums[0]; i++) {
        char buf[64];
        hy_markup_number(buf, sizeof buf, nums[i].v, 4);
        HY_CHECK(!strcmp(buf, nums[i].want), "number %g: \"%s\", want \"%s\"", nums[i].v, buf, nums[i].want);
    }
    return hy_test_finish("markup");
}
