/* SPDX-License-Identifier: MIT */
/* hy_markup.c: TeX-subset label markup (Greek, scripts, symbols) parsed into runs and set on a hy_canvas. */
#include "hy_markup.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct sym {
    const char *name, *utf8;
} sym;

static const sym syms[] = {
    {"alpha", "\xCE\xB1"}, {"beta", "\xCE\xB2"}, {"gamma", "\xCE\xB3"}, {"delta", "\xCE\xB4"},
    {"epsilon", "\xCF\xB5"}, {"varepsilon", "\xCE\xB5"}, {"zeta", "\xCE\xB6"}, {"eta", "\xCE\xB7"},
    {"theta", "\xCE\xB8"}, {"vartheta", "\xCF\x91"}, {"iota", "\xCE\xB9"}, {"kappa", "\xCE\xBA"},
    {"lambda", "\xCE\xBB"}, {"mu", "\xCE\xBC"}, {"nu", "\xCE\xBD"}, {"xi", "\xCE\xBE"},
    {"pi", "\xCF\x80"}, {"rho", "\xCF\x81"}, {"varrho", "\xCF\xB1"}, {"sigma", "\xCF\x83"},
    {"tau", "\xCF\x84"}, {"upsilon", "\xCF\x85"}, {"phi", "\xCF\x95"}, {"varphi", "\xCF\x86"},
    {"chi", "\xCF\x87"}, {"psi", "\xCF\x88"}, {"omega", "\xCF\x89"},
    {"Gamma", "\xCE\x93"}, {"Delta", "\xCE\x94"}, {"Theta", "\xCE\x98"}, {"Lambda", "\xCE\x9B"},
    {"Xi", "\xCE\x9E"}, {"Pi", "\xCE\xA0"}, {"Sigma", "\xCE\xA3"}, {"Phi", "\xCE\xA6"},
    {"Psi", "\xCE\xA8"}, {"Omega", "\xCE\xA9"},
    {"infty", "\xE2\x88\x9E"}, {"circ", "\xC2\xB0"}, {"cdot", "\xC2\xB7"}, {"times", "\xC3\x97"},
    {"pm", "\xC2\xB1"}, {"le", "\xE2\x89\xA4"}, {"leq", "\xE2\x89\xA4"}, {"ge", "\xE2\x89\xA5"},
    {"geq", "\xE2\x89\xA5"}, {"approx", "\xE2\x89\x88"}, {"to", "\xE2\x86\x92"},
    {"rightarrow", "\xE2\x86\x92"}, {"partial", "\xE2\x88\x82"}, {"dots", "\xE2\x80\xA6"},
    {"ldots", "\xE2\x80\xA6"}, {"in", "\xE2\x88\x88"}, {"quad", "\xE2\x80\x83"},
    {"prime", "\xE2\x80\xB2"}, {"sim", "\xE2\x88\xBC"}, {"neq", "\xE2\x89\xA0"},
    {"int", "\xE2\x88\xAB"}, {"oint", "\xE2\x88\xAE"},
};

typedef struct parser {
    const char *src, *p;
    hy_mrun *runs;
    size_t cap, n;
    int upright;          /* inside \mathrm{...} */
    int integral;         /* an integral sign was set: a "dx" after it is a differential */
    int ngroups;
    int last_group, last_script;  /* the script group just closed, for stacking */
    hy_error *err;
} parser;

static int is_alpha(char c)
{
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z');
}

/* Whether a UTF-8 sequence starts with a lowercase Greek letter (U+03B1 to
 * U+03C9, and the variants U+03D1, U+03D5, U+03F1, U+03F5): a variable, set in
 * italic as TeX and mathtext do (uppercase Greek stays upright). */
static int is_lower_greek(const char *s)
{
    unsigned char a = (unsigned char)s[0], b = (unsigned char)s[1];
    unsigned cp = (a & 0xE0) == 0xC0 && (b & 0xC0) == 0x80 ? ((a & 0x1Fu) << 6) | (b & 0x3Fu) : 0;
    return (cp >= 0x3B1 && cp <= 0x3C9) || cp == 0x3D1 || cp == 0x3D5 || cp == 0x3F1 || cp == 0x3F5;
}

/* Appends UTF-8 bytes with a style, merging with the previous run when possible. */
static int emit(parser *ps, const char *s, size_t len, int script, int italic, int group)
{
    hy_mrun *r = ps->n ? &ps->runs[ps->n - 1] : NULL;
    if (!r || r->script != script || r->italic != italic || r->group != group ||
        strlen(r->text) + len >= HY_MRUN_BYTES) {
        if (ps->n >= ps->cap)
            return hy_error_set(ps->err, HY_EINVAL, "label \"%s\" has too many parts", ps->src);
        r = &ps->runs[ps->n++];
        r->text[0] = '\0';
        r->script = script;
        r->italic = italic;
        r->group = group;
    }
    size_t m = strlen(r->text);
    memcpy(r->text + m, s, len);
    r->text[m + len] = '\0';
    if (script == HY_SCRIPT_BASE)
        ps->last_group = 0;
    return HY_OK;
}

static int parse_seq(parser *ps, int script, int group, int in_brace);
static int parse_char(parser *ps, int script, int group);
static int is_integral(const char *s);
static int integral_space(parser *ps, int script, int group);

/* A backslash command at ps->p (pointing after the backslash). */
static int parse_command(parser *ps, int script, int group)
{
    const char *p = ps->p;
    if (!is_alpha(*p)) {
        static const char esc[] = "_^{}\\$%&#";
        ps->p = p + (*p ? 1 : 0);
        if (*p == '|')
            return emit(ps, "\xE2\x80\x96", 3, script, 0, group);
        if (*p == ',')
            return emit(ps, "\xE2\x80\x89", 3, script, 0, group);
        if (*p == ';' || *p == ':' || *p == ' ')
            return emit(ps, " ", 1, script, 0, group);
        if (*p && strchr(esc, *p))
            return emit(ps, p, 1, script, 0, group);
        return hy_error_set(ps->err, HY_EINVAL, "label \"%s\": unknown command '\\%c'", ps->src,
                            *p ? *p : ' ');
    }
    size_t len = 0;
    while (is_alpha(p[len]))
        len++;
    ps->p = p + len;
    if ((len == 6 && !strncmp(p, "mathrm", 6)) || (len == 4 && !strncmp(p, "text", 4)) ||
        (len == 2 && !strncmp(p, "rm", 2))) {
        int saved = ps->upright;
        ps->upright = 1;
        int st = HY_OK;
        if (*ps->p == '{') {
            ps->p++;
            st = parse_seq(ps, script, group, 1);
            ps->upright = saved;
        }
        return st;
    }
    static const char *const ops[] = {"min", "max", "sin", "cos", "tan", "exp", "log", "ln",
                                      "sup", "inf", "lim", "arg", "det", "sgn", "sign"};
    for (size_t i = 0; i < sizeof ops / sizeof ops[0]; i++)
        if (strlen(ops[i]) == len && !strncmp(ops[i], p, len))
            return emit(ps, p, len, script, 0, group);   /* operator names: upright */
    for (size_t i = 0; i < sizeof syms / sizeof syms[0]; i++)
        if (strlen(syms[i].name) == len && !strncmp(syms[i].name, p, len) && is_integral(syms[i].utf8)) {
            ps->p = syms[i].utf8;   /* \oint, \int: as the sign itself */
            const char *rest = p + len;
            int st = parse_char(ps, script, group);
            ps->p = rest;
            return st ? st : integral_space(ps, script, group);
        } else if (strlen(syms[i].name) == len && !strncmp(syms[i].name, p, len))
            return emit(ps, syms[i].utf8, strlen(syms[i].utf8), script,
                        !ps->upright && is_lower_greek(syms[i].utf8), group);
    return hy_error_set(ps->err, HY_EINVAL, "label \"%s\": unknown command '\\%.*s'", ps->src,
                        (int)len, p);
}

/* ---- units and differentials: one rule for every label ----------------
 * SI (and CGS) units are set upright, as ISO 80000-1 and the journals ask,
 * whatever way a scene writes them: a compound unit (letters joined by '/'
 * or '·', powers '²' '³') every part of which is a unit below is upright
 * anywhere ("A/m", "J/m³", "kA/m"); a lone unit ("T", "N", "s") is upright
 * in a unit's place only, after a number ("1.5 T", "10^{-4} T") or alone
 * in parentheses ("B (T)"), so a variable T or s elsewhere stays italic.
 * Multi-letter words ("mm", "Hz") are upright by the word rule anyway. */
static const char *const units[] = {"A", "T", "N", "J", "W", "V", "C", "Pa", "Hz", "s", "m", "g",
                                    "K", "Wb", "Oe", "G", "rad", "dB", "h", "min"};

/* Whether the len bytes at s spell a unit of the list, with an SI prefix
 * and a trailing power '²' or '³' allowed. */
static int is_unit(const char *s, size_t len)
{
    if (len >= 2 && (unsigned char)s[len - 2] == 0xC2 &&
        ((unsigned char)s[len - 1] == 0xB2 || (unsigned char)s[len - 1] == 0xB3))
        len -= 2;
    for (int pre = 0; pre < 2; pre++) {
        const char *u = s;
        size_t n = len;
        if (pre) {   /* k, M, m, c, n, G prefixes, and μ (U+03BC) */
            if (n > 2 && (unsigned char)s[0] == 0xCE && (unsigned char)s[1] == 0xBC)
                u += 2, n -= 2;
            else if (n > 1 && strchr("kMmcnG", s[0]))
                u++, n--;
            else
                continue;
        }
        for (size_t i = 0; i < sizeof units / sizeof units[0]; i++)
            if (strlen(units[i]) == n && !strncmp(units[i], u, n))
                return 1;
    }
    return 0;
}

/* Length of the unit-like word at p: letters (μ included), '/', '·', '²', '³'. */
static size_t unit_word(const char *p, int *compound)
{
    size_t k = 0;
    *compound = 0;
    for (;;) {
        unsigned char a = (unsigned char)p[k], b = a ? (unsigned char)p[k + 1] : 0;
        if (is_alpha((char)a))
            k++;
        else if (a == '/')
            k++, *compound = 1;
        else if (a == 0xC2 && b == 0xB7)
            k += 2, *compound = 1;
        else if (a == 0xC2 && (b == 0xB2 || b == 0xB3))
            k += 2;
        else if (a == 0xCE && b == 0xBC)
            k += 2;
        else
            break;
    }
    return k;
}

/* Whether the k bytes at p are a compound unit: every part between '/' and
 * '·' a unit, none empty. */
static int compound_unit(const char *p, size_t k)
{
    size_t i = 0;
    while (i < k) {
        size_t j = i;
        while (j < k && p[j] != '/' && !((unsigned char)p[j] == 0xC2 && (unsigned char)p[j + 1] == 0xB7))
            j++;
        if (j == i || !is_unit(p + i, j - i))
            return 0;
        i = j + (j < k ? (p[j] == '/' ? 1 : 2) : 0);
        if (j < k && i >= k)
            return 0;   /* a trailing '/' */
    }
    return 1;
}

/* Whether the word of k bytes at p stands where a unit stands: after a
 * number and a space, or alone in parentheses. */
static int unit_place(const parser *ps, const char *p, size_t k)
{
    if (p > ps->src && p[-1] == '(' && p[k] == ')')
        return 1;
    const char *q = p;
    while (q > ps->src && q[-1] == ' ')
        q--;
    return q < p && q > ps->src && ((q[-1] >= '0' && q[-1] <= '9') || q[-1] == '}');
}

/* Emits the unit word of k bytes at ps->p upright when it is a unit in a
 * unit's place (*done = 1), else leaves it to the character rules. */
static int parse_unit(parser *ps, int script, int group, int *done)
{
    const char *p = ps->p;
    int compound;
    size_t k = unit_word(p, &compound);
    *done = 0;
    if (!k || (p > ps->src && is_alpha(p[-1])) || ps->upright)
        return HY_OK;
    if (compound ? !compound_unit(p, k) : !(is_unit(p, k) && unit_place(ps, p, k)))
        return HY_OK;
    *done = 1;
    ps->p = p + k;
    return emit(ps, p, k, script, 0, group);
}

/* Replaces a space just emitted by a thin space (U+2009), or adds one. */
static int thin_space(parser *ps, int script, int group)
{
    hy_mrun *r = ps->n ? &ps->runs[ps->n - 1] : NULL;
    size_t m = r ? strlen(r->text) : 0;
    if (r && m && r->text[m - 1] == ' ')
        r->text[m - 1] = '\0';
    else if (r && m >= 3 && !strcmp(r->text + m - 3, "\xE2\x80\x89"))
        return HY_OK;   /* a "\," already written */
    return emit(ps, "\xE2\x80\x89", 3, script, 0, group);
}

/* Whether s starts with an integral sign: ∫ (U+222B), ∬, ∭ or ∮ (U+222E). */
static int is_integral(const char *s)
{
    return (unsigned char)s[0] == 0xE2 && (unsigned char)s[1] == 0x88 &&
           ((unsigned char)s[2] >= 0xAB && (unsigned char)s[2] <= 0xAE);
}

/* After an integral sign: the spaces (and a "\,") written after it become
 * one thin space, so the sign never touches the integrand nor floats off. */
static int integral_space(parser *ps, int script, int group)
{
    for (;;) {
        if (*ps->p == ' ')
            ps->p++;
        else if (ps->p[0] == '\\' && ps->p[1] == ',')
            ps->p += 2;
        else
            break;
    }
    if (!*ps->p || *ps->p == '}' || *ps->p == '_' || *ps->p == '^')
        return HY_OK;   /* limits go on the sign itself */
    return emit(ps, "\xE2\x80\x89", 3, script, 0, group);
}

/* After an integral sign: the differential d of "dB", "du", "dH" (a word
 * of 'd' and one letter) is set upright with a thin space before it, the
 * variable italic, so "∮ H dB" reads ∮ H d B and not decibels. */
static int parse_differential(parser *ps, int script, int group, int *done)
{
    const char *p = ps->p;
    *done = 0;
    if (!ps->integral || p[0] != 'd' || (p > ps->src && is_alpha(p[-1])) || !is_alpha(p[1]) || is_alpha(p[2]))
        return HY_OK;
    *done = 1;
    ps->p = p + 2;
    int st = thin_space(ps, script, group);
    if (!st)
        st = emit(ps, "d", 1, script, 0, group);
    return st ? st : emit(ps, p + 1, 1, script, !ps->upright, group);
}

/* One ordinary character (UTF-8 sequence) at ps->p. */
static int parse_char(parser *ps, int script, int group)
{
    const char *p = ps->p;
    unsigned char c = (unsigned char)*p;
    int done = 0, st = parse_unit(ps, script, group, &done);
    if (!done && !st)
        st = parse_differential(ps, script, group, &done);
    if (done || st)
        return st;
    if (is_integral(p)) {   /* the sign, then a thin space in place of any spaces */
        ps->p = p + 3;
        ps->integral = 1;
        st = emit(ps, p, 3, script, 0, group);
        return st ? st : integral_space(ps, script, group);
    }
    size_t len = c < 0x80 ? 1 : c >= 0xF0 ? 4 : c >= 0xE0 ? 3 : c >= 0xC0 ? 2 : 1;
    for (size_t i = 1; i < len; i++)
        if (!p[i]) {
            len = i;
            break;
        }
    ps->p = p + len;
    int prev_alpha = p > ps->src && is_alpha(p[-1]);
    int next_alpha = is_alpha(p[1]);
    if (len == 1 && is_alpha(*p))
        return emit(ps, p, 1, script, !ps->upright && !prev_alpha && !next_alpha, group);
    if (len == 2 && is_lower_greek(p))
        return emit(ps, p, 2, script, !ps->upright, group);
    if (*p == '-' && !(prev_alpha && next_alpha))
        return emit(ps, "\xE2\x88\x92", 3, script, 0, group);
    return emit(ps, p, len, script, 0, group);
}

/* One sub/superscript argument: a braced group, a command or a character. */
static int parse_script(parser *ps, int base_script, char kind)
{
    int s = kind == '^' ? HY_SCRIPT_SUP : HY_SCRIPT_SUB;
    int group;
    if (base_script != HY_SCRIPT_BASE) {
        s = base_script;          /* nested script: kept at the script level */
        group = ps->n ? ps->runs[ps->n - 1].group : 0;
    } else if (ps->last_group && ps->last_script != s) {
        group = ps->last_group;   /* y^a_b: stack on the same base */
    } else {
        group = ++ps->ngroups;
    }
    ps->p++;
    while (*ps->p == ' ')
        ps->p++;
    int st;
    if (*ps->p == '{') {
        ps->p++;
        st = parse_seq(ps, s, group, 1);
    } else if (*ps->p == '\\') {
        ps->p++;
        st = parse_command(ps, s, group);
    } else if (*ps->p) {
        st = parse_char(ps, s, group);
    } else {
        return hy_error_set(ps->err, HY_EINVAL, "label \"%s\": '%c' at the end has no argument",
                            ps->src, kind);
    }
    if (base_script == HY_SCRIPT_BASE && st == HY_OK) {
        /* A second script stacks only on a group holding one kind so far. */
        ps->last_group = ps->last_group == group ? 0 : group;
        ps->last_script = s;
    }
    return st;
}

static int parse_seq(parser *ps, int script, int group, int in_brace)
{
    while (*ps->p) {
        char c = *ps->p;
        int st = HY_OK;
        if (c == '}') {
            if (!in_brace)
                return hy_error_set(ps->err, HY_EINVAL, "label \"%s\": unbalanced '}'", ps->src);
            ps->p++;
            return HY_OK;
        } else if (c == '{') {
            ps->p++;
            st = parse_seq(ps, script, group, 1);
        } else if (c == '^' || c == '_') {
            st = parse_script(ps, script, c);
        } else if (c == '\\') {
            ps->p++;
            st = parse_command(ps, script, group);
        } else if (c == '$') {
            ps->p++;
        } else {
            st = parse_char(ps, script, group);
        }
        if (st)
            return st;
    }
    if (in_brace)
        return hy_error_set(ps->err, HY_EINVAL, "label \"%s\": missing '}'", ps->src);
    return HY_OK;
}

int hy_markup_parse(const char *src, hy_mrun *runs, size_t cap, size_t *n, hy_error *err)
{
    parser ps = {.src = src ? src : "", .p = src ? src : "", .runs = runs, .cap = cap, .err = err};
    int st = parse_seq(&ps, HY_SCRIPT_BASE, 0, 0);
    *n = ps.n;
    return st;
}

typedef struct group_state {
    int id, sup_used, sub_used;
    double x0, sup_w, sub_w;
} group_state;

/* Width of a closed script group: the wider of the scripts it holds. */
static double group_width(const group_state *g)
{
    double sup = g->sup_used ? g->sup_w : 0.0, sub = g->sub_used ? g->sub_w : 0.0;
    return sup > sub ? sup : sub;
}

static double run_shift(int script, double size)
{
    return script == HY_SCRIPT_SUP ? -0.38 * size : script == HY_SCRIPT_SUB ? 0.22 * size : 0.0;
}

void hy_markup_layout(const hy_canvas *cv, const hy_mrun *runs, size_t n, double size,
                      int draw, int vertical, double x, double y, hy_rgb colour,
                      hy_markup_box *box)
{
    double pen = 0.0, asc = 0.78 * size, desc = 0.24 * size;
    group_state g = {0, 0, 0, 0, 0, 0};
    int prev_italic = 0;
    for (size_t i = 0; i < n; i++) {
        const hy_mrun *r = &runs[i];
        double rs = r->script == HY_SCRIPT_BASE ? size : 0.7 * size;
        double off = run_shift(r->script, size), at;
        hy_text_extents ext;
        cv->ops->measure(cv->ctx, r->text, rs, r->italic, &ext);
        if (r->group != g.id) {          /* close the previous group, open a new one */
            if (g.id)
                pen = g.x0 + group_width(&g);
            g.id = r->group;
            g.x0 = pen;
            /* an italic base leans right: its superscript starts a little
             * later (italic correction), its subscript tucks under it */
            g.sup_w = r->group && prev_italic ? 0.08 * size : 0.0;
            g.sub_w = r->group && prev_italic ? -0.03 * size : 0.0;
            g.sup_used = g.sub_used = 0;
        }
        if (r->group) {
            double *w = r->script == HY_SCRIPT_SUP ? &g.sup_w : &g.sub_w;
            *(r->script == HY_SCRIPT_SUP ? &g.sup_used : &g.sub_used) = 1;
            at = g.x0 + *w;
            *w += ext.advance;
        } else {
            at = pen;
            pen += ext.advance;
            prev_italic = r->italic;
        }
        if (draw) {
            double px = vertical ? x + off : x + at, py = vertical ? y - at : y + off;
            cv->ops->text(cv->ctx, px, py, r->text, rs, r->italic, vertical, colour);
        }
        if (0.78 * rs - off > asc)
            asc = 0.78 * rs - off;
        if (0.24 * rs + off > desc)
            desc = 0.24 * rs + off;
    }
    if (g.id)
        pen = g.x0 + group_width(&g);
    if (box) {
        box->width = pen;
        box->ascent = asc;
        box->descent = desc;
    }
}

void hy_markup_text(const hy_canvas *cv, const char *src, double size, int draw,
                    int vertical, double x, double y, hy_rgb colour, hy_markup_box *box)
{
    hy_mrun runs[HY_MARKUP_MAX];
    size_t n = 0;
    if (hy_markup_parse(src, runs, HY_MARKUP_MAX, &n, NULL)) {
        n = 0;   /* draw the label verbatim, in as many plain runs as it needs */
        for (const char *p = src ? src : ""; *p && n < HY_MARKUP_MAX; n++) {
            size_t k = strlen(p) < HY_MRUN_BYTES - 1 ? strlen(p) : HY_MRUN_BYTES - 1;
            while (k > 0 && ((unsigned char)p[k] & 0xC0) == 0x80)
                k--;   /* do not split a UTF-8 sequence */
            memcpy(runs[n].text, p, k);
            runs[n].text[k] = '\0';
            runs[n].script = HY_SCRIPT_BASE;
            runs[n].italic = runs[n].group = 0;
            p += k;
        }
    }
    hy_markup_layout(cv, runs, n, size, draw, vertical, x, y, colour, box);
}

char *hy_markup_number(char *buf, size_t size, double v, int sig)
{
    double a = fabs(v);
    sig = sig < 1 ? 1 : sig > 17 ? 17 : sig;
    if (!size)
        return buf;
    if (!isfinite(v)) {
        snprintf(buf, size, "%s", isnan(v) ? "NaN" : v > 0 ? "\\infty" : "-\\infty");
    } else if (v == floor(v) && a < 1e6) {
        snprintf(buf, size, "%.0f", v);
    } else if (a >= 1e-3 && a < pow(10.0, sig)) {   /* %g stays decimal there */
        snprintf(buf, size, "%.*g", sig, v);
    } else {
        int e = (int)floor(log10(a));
        double m = v / pow(10.0, e);
        char mant[40];
        snprintf(mant, sizeof mant, "%.*g", sig, m);
        if (fabs(strtod(mant, NULL)) >= 10.0) {   /* rounding carried into the next decade */
            m /= 10.0, e++;
            snprintf(mant, sizeof mant, "%.*g", sig, m);
        }
        double back = strtod(mant, NULL);
        if (back == 1.0)
            snprintf(buf, size, "10^{%d}", e);
        else if (back == -1.0)
            snprintf(buf, size, "-10^{%d}", e);
        else
            snprintf(buf, size, "%s\\times10^{%d}", mant, e);
    }
    return buf;
}
