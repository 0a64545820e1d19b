/* SPDX-License-Identifier: MIT */
/* hy_scene_value.c: scene value lexing and typed conversion (numbers, lists, lengths, colours), and typo suggestions. */
#include "hy_scene_internal.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hy_os.h"

/* One comma-separated element of a value as written. */
typedef struct item {
    char *text; /* unescaped, owned */
    int quoted;
    int col;
} item;

typedef struct lexed {
    item *it;
    size_t n, cap;
} lexed;

typedef struct vctx {
    const hy_scene_key_spec *spec;
    const char *where;
    int *errcol;
    char *msg;
    size_t msgsz;
    char shown[2][HY_SCENE_SHOWN_MAX * 4 + 4]; /* quoted values, for messages */
} vctx;

/* A scene's text as a message quotes it: at most HY_SCENE_SHOWN_MAX bytes
 * ("..." after), non-printable bytes as \xNN (issue 20 item 10); slot 0 or 1. */
static const char *shown(vctx *c, int slot, const char *text)
{
    return hy_file_shown(text, strlen(text), HY_SCENE_SHOWN_MAX, c->shown[slot], sizeof c->shown[slot]);
}

static int fail(vctx *c, int col, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

static int fail(vctx *c, int col, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(c->msg, c->msgsz, fmt, ap);
    va_end(ap);
    *c->errcol = col;
    return HY_EINVAL;
}

static int is_hex_color(const char *p, const char *end)
{
    if (end - p < 7 || p[0] != '#')
        return 0;
    for (int i = 1; i <= 6; i++)
        if (!isxdigit((unsigned char)p[i]))
            return 0;
    return p + 7 == end || p[7] == ',' || isspace((unsigned char)p[7]);
}

const char *hy__char_text(int ch, char buf[8])
{
    unsigned char u = (unsigned char)ch;
    if (isprint(u))
        snprintf(buf, 8, "%c", u);
    else
        snprintf(buf, 8, "\\x%02x", u);
    return buf;
}

int hy__is_comment(const char *p, const char *end)
{
    return p < end && *p == '#' && !is_hex_color(p, end);
}

static void lexed_free(lexed *l)
{
    for (size_t i = 0; i < l->n; i++)
        free(l->it[i].text);
    free(l->it);
    l->it = NULL;
    l->n = l->cap = 0;
}

static int lexed_push(lexed *l, char *text, int quoted, int col)
{
    if (!text)
        return HY_ENOMEM;
    item *it = hy_grow(l->it, l->n, &l->cap, sizeof *it, 8);
    if (!it) {
        free(text);
        return HY_ENOMEM;
    }
    l->it = it;
    l->it[l->n++] = (item){text, quoted, col};
    return HY_OK;
}

/* Reads a "..." string starting at *pp (on the quote); \" and \\ are escapes,
 * any other backslash is kept as written (TeX-like markup passes through). */
static int lex_string(vctx *c, const char **pp, const char *end, int col0, const char *base,
                      lexed *l)
{
    const char *p = *pp + 1;
    char *buf = malloc((size_t)(end - p) + 1);
    size_t n = 0;
    if (!buf)
        return HY_ENOMEM;
    while (p < end && *p != '"') {
        if (*p == '\\' && p + 1 < end && (p[1] == '"' || p[1] == '\\'))
            p++;
        buf[n++] = *p++;
    }
    if (p == end) {
        free(buf);
        return fail(c, col0 + (int)(*pp - base), "unterminated string (missing closing '\"')");
    }
    buf[n] = '\0';
    int rc = lexed_push(l, buf, 1, col0 + (int)(*pp - base));
    *pp = p + 1;
    return rc;
}

static int word_end_char(const char *p, const char *start)
{
    return *p == ',' || *p == '"' || isspace((unsigned char)*p) || (*p == '#' && p != start);
}

/* Splits a value into items: quoted strings or bare words, separated by commas. */
static int lex_value(vctx *c, const char *text, size_t len, int col0, lexed *l)
{
    const char *p = text, *end = text + len;
    for (;;) {
        while (p < end && isspace((unsigned char)*p))
            p++;
        int col = col0 + (int)(p - text);
        if (p == end || hy__is_comment(p, end)) {
            if (!l->n && p + 1 < end && isalnum((unsigned char)p[1]))
                return fail(c, col, "missing value after '=' ('#' starts a comment unless "
                                    "it opens a #rrggbb colour)");
            return fail(c, col, l->n ? "empty list element after ','"
                                     : "missing value after '='");
        }
        if (*p == ',')
            return fail(c, col, "empty list element before ','");
        if (*p == '"') {
            int rc = lex_string(c, &p, end, col0, text, l);
            if (rc)
                return rc;
        } else {
            const char *s = p;
            while (p < end && !word_end_char(p, s))
                p++;
            char *w = malloc((size_t)(p - s) + 1);
            if (w) {
                memcpy(w, s, (size_t)(p - s));
                w[p - s] = '\0';
            }
            if (lexed_push(l, w, 0, col))
                return HY_ENOMEM;
        }
        while (p < end && isspace((unsigned char)*p))
            p++;
        if (p == end || hy__is_comment(p, end))
            return HY_OK;
        if (*p != ',') {
            int kind = c->spec->kind;
            const char *hint = (kind == HY_KIND_STRING || kind == HY_KIND_PATH)
                                   ? " (quote text that contains spaces)"
                                   : " (separate list elements with ',')";
            char ch[8];
            return fail(c, col0 + (int)(p - text), "unexpected '%s' after the value of '%s'%s",
                        hy__char_text(*p, ch), c->spec->name, hint);
        }
        p++;
    }
}

/* p past an optional sign and one or more digits; NULL when no digit follows. */
static const char *signed_digits(const char *p)
{
    if (*p == '+' || *p == '-')
        p++;
    if (!isdigit((unsigned char)*p))
        return NULL;
    while (isdigit((unsigned char)*p))
        p++;
    return p;
}

/* Strict decimal number: [+-]digits[.digits][e[+-]digits]; no nan, inf or hex.
 * Returns 0 on success, 1 on bad syntax, 2 if it does not fit a double. */
static int strict_number(const char *s, double *out)
{
    const char *p = s;
    int digits = 0;
    if (*p == '+' || *p == '-')
        p++;
    while (isdigit((unsigned char)*p))
        p++, digits++;
    if (*p == '.') {
        p++;
        while (isdigit((unsigned char)*p))
            p++, digits++;
    }
    if (!digits)
        return 1;
    if ((*p == 'e' || *p == 'E') && !(p = signed_digits(p + 1)))
        return 1;
    if (*p)
        return 1;
    errno = 0;
    double v = strtod(s, NULL);
    if (!isfinite(v))
        return 2;
    *out = v;
    if (v != 0 && !(fabs(v) >= HY_SCENE_NUM_MIN))
        return 3; /* subnormal: no model or axis means it, and 1/x overflows */
    return 0;
}

/* The message of a subnormal number. */
static int magnitude_fail(vctx *c, const item *it)
{
    char r[96];
    hy_scene_range_text(c->spec, r, sizeof r);
    if (r[0])
        return fail(c, it->col, "'%s' in %s must be %s and at least %.17g in magnitude (subnormal numbers are "
                    "refused), got %s", c->spec->name, c->where, r, HY_SCENE_NUM_MIN, shown(c, 0, it->text));
    return fail(c, it->col, "'%s' in %s must be 0 or at least %.17g in magnitude (subnormal numbers are refused), "
                "got %s", c->spec->name, c->where, HY_SCENE_NUM_MIN, shown(c, 0, it->text));
}

static int strict_integer(const char *s, long *out)
{
    const char *p = signed_digits(s);
    if (!p || *p)
        return 1;
    errno = 0;
    long v = strtol(s, NULL, 10);
    if (errno == ERANGE)
        return 2;
    *out = v;
    return 0;
}

static int in_range(const hy_scene_key_spec *k, double v)
{
    if (k->flags & HY_SPEC_MIN) {
        if ((k->flags & HY_SPEC_MIN_EXCL) ? !(v > k->min) : !(v >= k->min))
            return 0;
    }
    if (k->flags & HY_SPEC_MAX) {
        if ((k->flags & HY_SPEC_MAX_EXCL) ? !(v < k->max) : !(v <= k->max))
            return 0;
    }
    return 1;
}

static int check_range(vctx *c, const item *it, double v)
{
    if (in_range(c->spec, v))
        return HY_OK;
    char r[96];
    hy_scene_range_text(c->spec, r, sizeof r);
    return fail(c, it->col, "'%s' in %s must be %s, got %s", c->spec->name, c->where, r,
                shown(c, 0, it->text));
}

static int num_item(vctx *c, const item *it, double *out)
{
    if (it->quoted)
        return fail(c, it->col, "'%s' in %s expects a number, got a quoted string",
                    c->spec->name, c->where);
    int rc = strict_number(it->text, out);
    if (rc == 3)
        return magnitude_fail(c, it);
    if (rc == 2)
        return fail(c, it->col, "'%s' in %s: %s does not fit a double", c->spec->name,
                    c->where, shown(c, 0, it->text));
    if (rc)
        return fail(c, it->col, "'%s' in %s expects a finite decimal number, got '%s'",
                    c->spec->name, c->where, shown(c, 0, it->text));
    return check_range(c, it, *out);
}

static int int_item(vctx *c, const item *it, long *out)
{
    int rc = it->quoted ? 1 : strict_integer(it->text, out);
    if (rc == 2)
        return fail(c, it->col, "'%s' in %s: %s does not fit an integer", c->spec->name,
                    c->where, shown(c, 0, it->text));
    if (rc)
        return fail(c, it->col, "'%s' in %s expects an integer, got '%s'", c->spec->name,
                    c->where, shown(c, 0, it->text));
    return check_range(c, it, (double)*out);
}

static int enum_item(vctx *c, const item *it, long *out)
{
    const char *const *e = c->spec->enums;
    size_t n = 0;
    for (; e[n]; n++)
        if (!it->quoted && strcmp(e[n], it->text) == 0) {
            *out = (long)n;
            return HY_OK;
        }
    char list[256];
    size_t used = 0;
    list[0] = '\0';
    for (size_t i = 0; i < n && used + 1 < sizeof list; i++)
        used += (size_t)snprintf(list + used, sizeof list - used, "%s%s", i ? ", " : "", e[i]);
    const char *sug = hy__suggest(it->text, e, n);
    if (sug)
        return fail(c, it->col, "'%s' in %s must be one of %s, got '%s'; did you mean '%s'?",
                    c->spec->name, c->where, list, shown(c, 0, it->text), sug);
    return fail(c, it->col, "'%s' in %s must be one of %s, got '%s'", c->spec->name, c->where,
                list, shown(c, 0, it->text));
}

static int length_item(vctx *c, const item *it, double *val, int *unit)
{
    static const struct { const char *s; int u; } units[] = {
        {"pt", HY__UNIT_PT}, {"cm", HY__UNIT_CM}, {"mm", HY__UNIT_MM},
        {"in", HY__UNIT_IN}, {"px", HY__UNIT_PX}};
    size_t n = strlen(it->text);
    *unit = HY__UNIT_PT;
    char num[64];
    if (it->quoted || n == 0 || n >= sizeof num)
        return fail(c, it->col, "'%s' in %s expects a length such as 9pt, 1.2cm, 3mm, 1in or 12px",
                    c->spec->name, c->where);
    memcpy(num, it->text, n + 1);
    if (n > 2 && isalpha((unsigned char)num[n - 1])) {
        size_t u = 0;
        while (u < sizeof units / sizeof units[0] && strcmp(num + n - 2, units[u].s) != 0)
            u++;
        if (u == sizeof units / sizeof units[0])
            return fail(c, it->col, "'%s' in %s: unknown unit in '%s' (use pt, cm, mm, in or px)",
                        c->spec->name, c->where, shown(c, 0, it->text));
        *unit = units[u].u;
        num[n - 2] = '\0';
    }
    int rc = strict_number(num, val);
    if (rc == 3)
        return magnitude_fail(c, it);
    if (rc)
        return fail(c, it->col, "'%s' in %s expects a length such as 9pt, 1.2cm, 3mm, 1in or 12px, got '%s'",
                    c->spec->name, c->where, shown(c, 0, it->text));
    return check_range(c, it, *val);
}

static const struct { const char *name; unsigned rgb; } okabe_ito[] = {
    {"orange", 0xE69F00}, {"skyblue", 0x56B4E9}, {"bluishgreen", 0x009E73},
    {"yellow", 0xF0E442}, {"blue", 0x0072B2}, {"vermillion", 0xD55E00},
    {"reddishpurple", 0xCC79A7}, {"black", 0x000000}};

static void set_rgb(hy_scene_color *col, unsigned rgb, int index)
{
    col->r = ((rgb >> 16) & 0xff) / 255.0;
    col->g = ((rgb >> 8) & 0xff) / 255.0;
    col->b = (rgb & 0xff) / 255.0;
    col->index = index;
}

static int color_item(vctx *c, const item *it, hy_scene_color *out)
{
    const char *t = it->text;
    size_t n = strlen(t);
    long idx;
    if (!it->quoted && strict_integer(t, &idx) == 0) {
        if (idx < 1 || idx > 8)
            return fail(c, it->col, "'%s' in %s: Okabe-Ito colour index must be in [1, 8], got %s",
                        c->spec->name, c->where, shown(c, 0, t));
        set_rgb(out, okabe_ito[idx - 1].rgb, (int)idx);
        return HY_OK;
    }
    if (!it->quoted && n == 7 && is_hex_color(t, t + n)) {
        set_rgb(out, (unsigned)strtoul(t + 1, NULL, 16), 0);
        return HY_OK;
    }
    const char *names[8];
    for (int i = 0; i < 8; i++) {
        names[i] = okabe_ito[i].name;
        if (!it->quoted && strcmp(t, names[i]) == 0) {
            set_rgb(out, okabe_ito[i].rgb, i + 1);
            return HY_OK;
        }
    }
    if (!it->quoted && strcmp(t, "vermilion") == 0) {
        set_rgb(out, okabe_ito[5].rgb, 6);
        return HY_OK;
    }
    const char *sug = hy__suggest(t, names, 8);
    return fail(c, it->col,
                "'%s' in %s expects a colour (1-8, an Okabe-Ito name or #rrggbb), got '%s'%s%s%s",
                c->spec->name, c->where, shown(c, 0, t), sug ? "; did you mean '" : "", sug ? sug : "",
                sug ? "'?" : "");
}

static int valid_name(const char *s)
{
    if (!*s)
        return 0;
    for (; *s; s++)
        if (!isalnum((unsigned char)*s) && *s != '_' && *s != '-' && *s != '.')
            return 0;
    return 1;
}

static int text_value(vctx *c, const item *it, const char *dir, hy__value *out)
{
    hy_scene_kind k = c->spec->kind;
    if (k == HY_KIND_NAME && !valid_name(it->text))
        return fail(c, it->col, "'%s' in %s must be a name of letters, digits, '_', '-' and '.', got '%s'",
                    c->spec->name, c->where, shown(c, 0, it->text));
    if (k == HY_KIND_PATH && !it->text[0])
        return fail(c, it->col, "'%s' in %s: empty path", c->spec->name, c->where);
    /* text is drawn (titles, labels) or names a file: UTF-8 without control
     * characters, refused here rather than when the figure is drawn (an
     * include's name is the policy's to judge: it quotes it escaped) */
    long bad = strcmp(c->spec->name, "include") ? hy_text_check(it->text) : -1;
    if (bad >= 0) {
        unsigned char b = (unsigned char)it->text[bad];
        return fail(c, it->col + it->quoted + (int)bad, "'%s' in %s %s (byte \\x%02x)", c->spec->name, c->where,
                    b < 0x20 || b == 0x7f ? "holds a control character" : "is not valid UTF-8 text", b);
    }
    if (k == HY_KIND_PATH && it->text[0] != '/' && dir && strcmp(dir, ".") != 0)
        out->str = hy_path_join(dir, it->text);
    else
        out->str = strdup(it->text);
    return out->str ? HY_OK : HY_ENOMEM;
}

static int count_ok(vctx *c, const lexed *l)
{
    const hy_scene_key_spec *k = c->spec;
    int col = l->it[l->n - 1].col;
    if (k->min_len && l->n < k->min_len)
        return fail(c, l->it[0].col, "'%s' in %s needs at least %u elements, got %zu", k->name,
                    c->where, k->min_len, l->n);
    if (k->max_len && l->n > k->max_len)
        return fail(c, col, "'%s' in %s takes at most %u elements, got %zu", k->name, c->where,
                    k->max_len, l->n);
    if ((k->flags & HY_SPEC_EVEN) && l->n % 2)
        return fail(c, col, "'%s' in %s needs an even number of elements (pairs), got %zu",
                    k->name, c->where, l->n);
    return HY_OK;
}

static int list_value(vctx *c, const lexed *l, hy__value *out)
{
    int rc = count_ok(c, l);
    if (rc)
        return rc;
    out->list = malloc(l->n * sizeof *out->list);
    if (!out->list)
        return HY_ENOMEM;
    out->n = l->n;
    for (size_t i = 0; i < l->n && !rc; i++) {
        long iv = 0;
        switch (c->spec->kind) {
        case HY_KIND_NUMBER_LIST: rc = num_item(c, &l->it[i], &out->list[i]); break;
        case HY_KIND_INTEGER_LIST: rc = int_item(c, &l->it[i], &iv); out->list[i] = (double)iv; break;
        default: rc = enum_item(c, &l->it[i], &iv); out->list[i] = (double)iv; break;
        }
    }
    return rc;
}

/* An axis range the plot can draw: a finite width, and at least
 * HY_LIMITS_MIN_REL of its magnitude (about 4500 ulps), so that the axis map
 * (v - lo) / (hi - lo) and the tick labels (at most 13 significant digits
 * apart) can tell its points apart. */
#define HY_LIMITS_MIN_REL 1e-12
static int limits_drawable(vctx *c, const lexed *l, double lo, double hi)
{
    double mag = fmax(fabs(lo), fabs(hi));
    if (!isfinite(hi - lo))
        return fail(c, l->it[1].col, "'%s' in %s spans %s to %s, a width beyond the largest double: "
                    "the axis cannot be drawn", c->spec->name, c->where, shown(c, 0, l->it[0].text), shown(c, 1, l->it[1].text));
    if (hi - lo < HY_LIMITS_MIN_REL * mag)
        return fail(c, l->it[1].col, "'%s' in %s spans %s to %s, a width of %.3g, below %g of its magnitude "
                    "%.3g: the axis cannot be drawn (widen the range)", c->spec->name, c->where,
                    l->it[0].text, l->it[1].text, hi - lo, HY_LIMITS_MIN_REL, mag);
    return HY_OK;
}

static int pair_value(vctx *c, const lexed *l, hy__value *out)
{
    hy_scene_kind k = c->spec->kind;
    if (k == HY_KIND_LIMITS && l->n == 1 && !l->it[0].quoted && strcmp(l->it[0].text, "auto") == 0) {
        out->is_auto = 1;
        return HY_OK;
    }
    if (l->n != 2)
        return fail(c, l->it[l->n > 2 ? 2 : 0].col, "'%s' in %s expects two %s%s, got %zu element%s",
                    c->spec->name, c->where, k == HY_KIND_LENGTH_PAIR ? "lengths" : "numbers",
                    k == HY_KIND_LIMITS ? " or auto" : "", l->n, l->n == 1 ? "" : "s");
    int rc = HY_OK;
    for (int i = 0; i < 2 && !rc; i++)
        rc = k == HY_KIND_LENGTH_PAIR ? length_item(c, &l->it[i], &out->a[i], &out->unit[i])
                                      : num_item(c, &l->it[i], &out->a[i]);
    if (!rc && k != HY_KIND_LENGTH_PAIR && !(out->a[0] < out->a[1]))
        return fail(c, l->it[1].col, "'%s' in %s needs first < second, got %s, %s",
                    c->spec->name, c->where, shown(c, 0, l->it[0].text), shown(c, 1, l->it[1].text));
    if (!rc && k == HY_KIND_LIMITS)
        return limits_drawable(c, l, out->a[0], out->a[1]);
    return rc;
}

static int one_value(vctx *c, const lexed *l, const char *dir, hy__value *out)
{
    hy_scene_kind k = c->spec->kind;
    const item *it = &l->it[0];
    if (l->n != 1)
        return fail(c, l->it[1].col, "'%s' in %s takes one %s, not a list", c->spec->name,
                    c->where, hy_scene_kind_name(k));
    switch (k) {
    case HY_KIND_NUMBER: return num_item(c, it, &out->num);
    case HY_KIND_INTEGER: {
        int rc = int_item(c, it, &out->ival);
        out->num = (double)out->ival;
        return rc;
    }
    case HY_KIND_BOOL:
        if (!it->quoted && (strcmp(it->text, "true") == 0 || strcmp(it->text, "false") == 0)) {
            out->ival = it->text[0] == 't';
            return HY_OK;
        }
        return fail(c, it->col, "'%s' in %s expects true or false, got '%s'", c->spec->name,
                    c->where, shown(c, 0, it->text));
    case HY_KIND_ENUM: return enum_item(c, it, &out->ival);
    case HY_KIND_LENGTH: return length_item(c, it, &out->a[0], &out->unit[0]);
    case HY_KIND_COLOR: return color_item(c, it, &out->color);
    default: return text_value(c, it, dir, out);
    }
}

int hy__value_parse(const hy_scene_key_spec *spec, const char *where, const char *dir,
                    const char *text, size_t len, int col0, hy__value *out, int *errcol,
                    char *msg, size_t msgsz)
{
    vctx c = {.spec = spec, .where = where, .errcol = errcol, .msg = msg, .msgsz = msgsz};
    lexed l = {0};
    memset(out, 0, sizeof *out);
    out->kind = spec->kind;
    int rc = lex_value(&c, text, len, col0, &l);
    if (rc == HY_OK) {
        switch (spec->kind) {
        case HY_KIND_NUMBER_LIST:
        case HY_KIND_INTEGER_LIST:
        case HY_KIND_ENUM_LIST: rc = list_value(&c, &l, out); break;
        case HY_KIND_PAIR:
        case HY_KIND_LIMITS:
        case HY_KIND_LENGTH_PAIR: rc = pair_value(&c, &l, out); break;
        default: rc = one_value(&c, &l, dir, out); break;
        }
    }
    if (rc == HY_ENOMEM)
        fail(&c, col0, "out of memory");
    lexed_free(&l);
    if (rc)
        hy__value_clear(out);
    return rc;
}

void hy__value_clear(hy__value *v)
{
    free(v->str);
    free(v->list);
    memset(v, 0, sizeof *v);
}

size_t hy__edit_distance(const char *a, const char *b)
{
    enum { MAXL = 64 };
    size_t n = strlen(a), m = strlen(b);
    if (n >= MAXL || m >= MAXL)
        return (size_t)-1;
    size_t d[MAXL][MAXL];
    for (size_t i = 0; i <= n; i++)
        d[i][0] = i;
    for (size_t j = 0; j <= m; j++)
        d[0][j] = j;
    for (size_t i = 1; i <= n; i++)
        for (size_t j = 1; j <= m; j++) {
            size_t cost = a[i - 1] != b[j - 1];
            size_t best = d[i - 1][j] + 1;
            if (d[i][j - 1] + 1 < best)
                best = d[i][j - 1] + 1;
            if (d[i - 1][j - 1] + cost < best)
                best = d[i - 1][j - 1] + cost;
            if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1] &&
                d[i - 2][j - 2] + 1 < best)
                best = d[i - 2][j - 2] + 1;
            d[i][j] = best;
        }
    return d[n][m];
}

const char *hy__suggest(const char *word, const char *const *cands, size_t n)
{
    const char *best = NULL;
    size_t bd = (size_t)-1;
    for (size_t i = 0; i < n; i++) {
        size_t d = hy__edit_distance(word, cands[i]);
        if (d < bd) {
            bd = d;
            best = cands[i];
        }
    }
    if (!best)
        return NULL;
    size_t len = strlen(best);
    return (bd <= 1 + len / 4 && bd < len) ? best : NULL;
}

static const char *const unit_names[] = {"pt", "cm", "mm", "in", "px"};

static void put_string(FILE *f, const char *s)
{
    fputc('"', f);
    for (; *s; s++) {
        if (*s == '"' || (*s == '\\' && (s[1] == '"' || s[1] == '\\' || s[1] == '\0')))
            fputc('\\', f);
        fputc(*s, f);
    }
    fputc('"', f);
}

void hy__value_write(const hy_scene_key_spec *k, const hy__value *v, FILE *f)
{
    switch (k->kind) {
    case HY_KIND_NUMBER: fprintf(f, "%.17g", v->num); break;
    case HY_KIND_INTEGER: fprintf(f, "%ld", v->ival); break;
    case HY_KIND_BOOL: fputs(v->ival ? "true" : "false", f); break;
    case HY_KIND_ENUM: fputs(k->enums[v->ival], f); break;
    case HY_KIND_STRING:
    case HY_KIND_NAME:
    case HY_KIND_PATH: put_string(f, v->str); break;
    case HY_KIND_NUMBER_LIST:
    case HY_KIND_INTEGER_LIST:
    case HY_KIND_ENUM_LIST:
        for (size_t i = 0; i < v->n; i++) {
            if (i)
                fputs(", ", f);
            if (k->kind == HY_KIND_ENUM_LIST)
                fputs(k->enums[(size_t)v->list[i]], f);
            else
                fprintf(f, "%.17g", v->list[i]);
        }
        break;
    case HY_KIND_LENGTH: fprintf(f, "%.17g%s", v->a[0], unit_names[v->unit[0]]); break;
    case HY_KIND_LENGTH_PAIR:
        fprintf(f, "%.17g%s, %.17g%s", v->a[0], unit_names[v->unit[0]], v->a[1],
                unit_names[v->unit[1]]);
        break;
    case HY_KIND_COLOR:
        if (v->color.index)
            fputs(okabe_ito[v->color.index - 1].name, f);
        else
            fprintf(f, "#%02x%02x%02x", (unsigned)lround(v->color.r * 255),
                    (unsigned)lround(v->color.g * 255), (unsigned)lround(v->color.b * 255));
        break;
    case HY_KIND_PAIR:
    case HY_KIND_LIMITS:
        if (v->is_auto)
            fputs("auto", f);
        else
            fprintf(f, "%.17g, %.17g", v->a[0], v->a[1]);
        break;
    }
}
