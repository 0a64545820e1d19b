/* SPDX-License-Identifier: MIT */
/* hy_forc.c: FORC data, readers (MicroMag 2900/3900, CSV), drift correction,
 * the FORC protocol, and ρ = −½ ∂²M/∂H_a∂H_b by local quadratic least squares
 * (Pike, Roberts & Verosub 1999; docs/FORC.md).  Each fit is a Householder QR
 * of the n × 6 design matrix in a reused workspace; only the last coefficient
 * (of x·y) is needed, so no back substitution. */
#include "hy_forc.h"

#include <ctype.h>
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "hy_os.h"

/* ---- data set -------------------------------------------------------------- */

void hy_forc_data_free(hy_forc_data *d)
{
    if (!d)
        return;
    free(d->curve);
    free(d->hb);
    free(d->m);
    memset(d, 0, sizeof *d);
}

/* The refusal of a NULL where the header says it must not be (HY_EINVAL). */
static int null_arg(hy_error *err, const char *fn, const char *what)
{
    return hy_error_set(err, HY_EINVAL, "%s: %s must not be NULL", fn, what);
}

static void data_init(hy_forc_data *d)
{
    memset(d, 0, sizeof *d);
    d->field_unit = "";
    d->moment_unit = "";
    d->field_to_tesla = NAN;
    d->hsat = d->hcal = d->hncr = NAN;
}

/* Room for one more point / curve; 0 or HY_ENOMEM. */
typedef struct builder {
    hy_forc_data *d;
    size_t pcap, ccap;
} builder;

static int push_point(builder *b, double hb, double m)
{
    hy_forc_data *d = b->d;
    if (d->npoints == b->pcap) {
        size_t cap = b->pcap ? 2 * b->pcap : 1024;
        double *h = realloc(d->hb, cap * sizeof *h);
        if (!h)
            return HY_ENOMEM;
        d->hb = h;
        double *mm = realloc(d->m, cap * sizeof *mm);
        if (!mm)
            return HY_ENOMEM;
        d->m = mm;
        b->pcap = cap;
    }
    d->hb[d->npoints] = hb;
    d->m[d->npoints] = m;
    d->npoints++;
    return HY_OK;
}

static int push_curve(builder *b, double ha, size_t first, size_t line)
{
    hy_forc_data *d = b->d;
    hy_forc_curve *c = hy_grow(d->curve, d->ncurves, &b->ccap, sizeof *c, 64);
    if (!c)
        return HY_ENOMEM;
    d->curve = c;
    d->curve[d->ncurves++] = (hy_forc_curve){ha, first, d->npoints - first, NAN, NAN, line};
    return HY_OK;
}

int hy_forc_data_set(hy_forc_data *d, size_t ncurves, const double *ha, const size_t *n, const double *hb,
                     const double *m, hy_error *err)
{
    if (!d)
        return null_arg(err, "hy_forc_data_set", "d");
    data_init(d);
    if (!ha || !n || !hb || !m)
        return null_arg(err, "hy_forc_data_set", !ha ? "ha" : !n ? "n" : !hb ? "hb" : "m");
    if (ncurves < 1 || ncurves > HY_FORC_MAX_CURVES)
        return hy_error_set(err, HY_EINVAL, "FORC data: %zu curves (1 to %u)", ncurves, HY_FORC_MAX_CURVES);
    size_t total = 0;
    for (size_t i = 0; i < ncurves; i++) {
        if (n[i] < 1 || n[i] > HY_FORC_MAX_POINTS - total)
            return hy_error_set(err, HY_EINVAL, "FORC data: curve %zu has %zu points (1 or more, %u in all)", i,
                                n[i], HY_FORC_MAX_POINTS);
        total += n[i];
    }
    builder b = {d, 0, 0};
    size_t k = 0;
    for (size_t i = 0; i < ncurves; i++) {
        if (!isfinite(ha[i]))
            return hy_error_set(err, HY_EINVAL, "FORC data: curve %zu: H_a is not finite", i);
        size_t first = d->npoints;
        for (size_t j = 0; j < n[i]; j++, k++) {
            if (!isfinite(hb[k]) || !isfinite(m[k]))
                return hy_error_set(err, HY_EINVAL, "FORC data: curve %zu point %zu is not finite", i, j);
            if (j && !(hb[k] > hb[k - 1]))
                return hy_error_set(err, HY_EINVAL, "FORC data: curve %zu: H_b does not ascend at point %zu", i, j);
            if (push_point(&b, hb[k], m[k]))
                return hy_error_set(err, HY_ENOMEM, "FORC data: out of memory");
        }
        if (push_curve(&b, ha[i], first, 0))
            return hy_error_set(err, HY_ENOMEM, "FORC data: out of memory");
    }
    return HY_OK;
}

/* ---- text scanning ---------------------------------------------------------- */

typedef struct scan {
    const char *p, *end, *name;
    size_t line;              /* number of the line last returned           */
    const char *ls, *le;      /* that line, without its line end            */
} scan;

/* Next line; 0 at the end of the text, -1 when a line passes the cap. */
static int next_line(scan *s)
{
    if (s->p >= s->end)
        return 0;
    const char *nl = memchr(s->p, '\n', (size_t)(s->end - s->p));
    const char *le = nl ? nl : s->end;
    s->ls = s->p;
    s->le = le;
    s->p = nl ? nl + 1 : s->end;
    s->line++;
    if (s->le > s->ls && s->le[-1] == '\r')
        s->le--;
    return (size_t)(s->le - s->ls) > HY_FORC_MAX_LINE ? -1 : 1;
}

static int at_err(hy_error *err, const scan *s, const char *at, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 4, 5)))
#endif
    ;
/* "name:line:col: message" (col 1-based from at; at NULL: the line's end). */
static int at_err(hy_error *err, const scan *s, const char *at, const char *fmt, ...)
{
    char msg[400];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    size_t col = (size_t)((at ? at : s->le) - s->ls) + 1;
    return hy_error_set(err, HY_EINVAL, "%s:%zu:%zu: %s", s->name, s->line, col, msg);
}

static const char *skip_sp(const char *p, const char *e)
{
    while (p < e && (*p == ' ' || *p == '\t'))
        p++;
    return p;
}

static int blank(const char *p, const char *e)
{
    return skip_sp(p, e) == e;
}

/* A decimal number at p ([+-] digits [. digits] [e [+-] digits]); *v finite.
 * Returns the end of the token, or NULL (not a number or out of range). */
static const char *num_tok(const char *p, const char *e, double *v)
{
    const char *q = p;
    if (q < e && (*q == '+' || *q == '-'))
        q++;
    size_t digits = 0;
    while (q < e && isdigit((unsigned char)*q))
        q++, digits++;
    if (q < e && *q == '.') {
        q++;
        while (q < e && isdigit((unsigned char)*q))
            q++, digits++;
    }
    if (!digits)
        return NULL;
    if (q < e && (*q == 'e' || *q == 'E')) {
        const char *r = q + 1;
        if (r < e && (*r == '+' || *r == '-'))
            r++;
        if (r < e && isdigit((unsigned char)*r)) {
            while (r < e && isdigit((unsigned char)*r))
                r++;
            q = r;
        } else
            return NULL; /* "1.5E" or "1.5E-": cut short */
    }
    char buf[80];
    if ((size_t)(q - p) >= sizeof buf)
        return NULL;
    memcpy(buf, p, (size_t)(q - p));
    buf[q - p] = 0;
    *v = strtod(buf, NULL);
    return isfinite(*v) ? q : NULL;
}

/* Why the token at p is not a number, for messages. */
static const char *why_not_num(const char *p, const char *e)
{
    if (p >= e)
        return "a number is missing";
    /* past a sign; strncasecmp may read all 3 bytes, so 3 must lie before e
       (a token "+na" at the end of the text was read one byte past it) */
    const char *q = e - p >= 4 && (*p == '+' || *p == '-') ? p + 1 : p;
    if (e - q >= 3 && (!strncasecmp(q, "nan", 3) || !strncasecmp(q, "inf", 3)))
        return "NaN or infinity is not a measurement";
    return "expected a number";
}

/* n numbers separated by ',', ';', tab or spaces, nothing else on the line.
 * Returns NULL when they parse, else where it went wrong (*why set). */
static const char *parse_row(const char *p, const char *e, double *v, int n, const char **why)
{
    p = skip_sp(p, e);
    for (int i = 0; i < n; i++) {
        if (i) {
            const char *q = skip_sp(p, e);
            if (q < e && (*q == ',' || *q == ';'))
                q = skip_sp(q + 1, e);
            else if (q == p && q < e) {
                *why = "expected a separator (',', ';' or blanks)";
                return p;
            }
            p = q;
        }
        const char *q = num_tok(p, e, &v[i]);
        if (!q) {
            double dummy;
            const char *r = p;
            if (r < e && (*r == '+' || *r == '-'))
                r++;
            int digits = r < e && (isdigit((unsigned char)*r) || *r == '.');
            *why = (digits && !num_tok(p, e, &dummy)) ? "a number that is cut short or out of range"
                                                      : why_not_num(p, e);
            return p;
        }
        p = q;
    }
    p = skip_sp(p, e);
    if (p < e) {
        *why = "unexpected text after the numbers";
        return p;
    }
    return NULL;
}

/* ---- MicroMag ---------------------------------------------------------------- */

static const char mm_magic[] = "MicroMag 2900/3900 Data File";
static const char mm_end[] = "MicroMag 2900/3900 Data File ends";

static int key_is(const char *k, size_t kn, const char *want)
{
    return strlen(want) == kn && !strncasecmp(k, want, kn);
}

/* A header value: a number or N/A (*v NaN).  Returns NULL or the error place. */
static const char *head_num(const char *v, const char *ve, double *out, int integer)
{
    if (ve - v == 3 && !strncasecmp(v, "N/A", 3)) {
        *out = NAN;
        return NULL;
    }
    const char *q = num_tok(v, ve, out);
    if (!q || skip_sp(q, ve) != ve)
        return v;
    if (integer && (*out != floor(*out) || *out < 1 || *out > 1e9))
        return v;
    return NULL;
}

/* One header line: Key = value, Key : value or Key<2+ spaces>value; known
 * keys checked.  0 or HY_EINVAL. */
static int mm_header(hy_forc_data *d, const scan *s, hy_error *err)
{
    const char *l = skip_sp(s->ls, s->le), *e = s->le;
    const char *sep = memchr(l, '=', (size_t)(e - l)), *v;
    if (!sep)
        sep = memchr(l, ':', (size_t)(e - l));
    if (sep)
        v = sep + 1;
    else { /* two or more blanks between key and value */
        const char *q = l;
        while (q + 1 < e && !((q[0] == ' ' || q[0] == '\t') && (q[1] == ' ' || q[1] == '\t')))
            q++;
        if (q + 1 >= e)
            return HY_OK; /* free text: a title, a date, a section name */
        sep = q;
        v = q;
    }
    const char *ke = sep;
    while (ke > l && (ke[-1] == ' ' || ke[-1] == '\t'))
        ke--;
    v = skip_sp(v, e);
    const char *ve = e;
    while (ve > v && (ve[-1] == ' ' || ve[-1] == '\t'))
        ve--;
    if (ke == l)
        return at_err(err, s, l, "broken header line: no key before '%c'", *sep);
    size_t kn = (size_t)(ke - l);
    if (ve == v && *sep == '=')
        return at_err(err, s, NULL, "broken header line: '%.*s' has no value", (int)(kn > 40 ? 40 : kn), l);
    if (key_is(l, kn, "Units of measure")) {
        size_t vn = (size_t)(ve - v);
        if (key_is(v, vn, "Hybrid SI"))
            d->units = HY_FORC_UNITS_HYBRID_SI, d->field_unit = "T", d->moment_unit = "A m2", d->field_to_tesla = 1;
        else if (key_is(v, vn, "SI"))
            d->units = HY_FORC_UNITS_SI, d->field_unit = "A/m", d->moment_unit = "A m2",
            d->field_to_tesla = 4e-7 * M_PI;
        else if (key_is(v, vn, "cgs"))
            d->units = HY_FORC_UNITS_CGS, d->field_unit = "Oe", d->moment_unit = "emu", d->field_to_tesla = 1e-4;
        else
            return at_err(err, s, v, "unknown units of measure (Hybrid SI, SI or cgs)");
        return HY_OK;
    }
    static const char *const nums[] = {"NCrv", "NData", "HCal", "HNcr", "HSat"};
    for (int i = 0; i < 5; i++)
        if (key_is(l, kn, nums[i])) {
            double x;
            const char *bad = head_num(v, ve, &x, i < 2);
            if (bad)
                return at_err(err, s, bad, "broken header: %s must be %s or N/A", nums[i],
                              i < 2 ? "a whole number >= 1" : "a finite number");
            if (i == 0)
                d->ncrv = isnan(x) ? 0 : (long)x;
            else if (i == 1)
                d->ndata = isnan(x) ? 0 : (long)x;
            else
                *(i == 2 ? &d->hcal : i == 3 ? &d->hncr : &d->hsat) = x;
        }
    return HY_OK;
}

typedef struct mm_state {
    builder b;
    size_t gfirst, gline;  /* the open group's first point and line          */
    int open;              /* a group is open                                 */
    double cal_h, cal_m;   /* pending calibration point                       */
    size_t cal_line;
    long lines;            /* data lines read                                 */
} mm_state;

/* Closes the open group: a calibration point or a curve. */
static int mm_group(hy_forc_data *d, mm_state *st, scan *s, hy_error *err)
{
    if (!st->open)
        return HY_OK;
    st->open = 0;
    size_t n = d->npoints - st->gfirst;
    double h0 = d->hb[st->gfirst];
    double tol = 0.05 * fabs(d->hcal) + (isfinite(d->hncr) ? fabs(d->hncr) : 0);
    if (n == 1 && isfinite(d->hcal) && fabs(h0 - d->hcal) <= tol) {
        if (!isnan(st->cal_h)) {
            s->line = st->gline;
            s->le = s->ls;
            return at_err(err, s, s->ls, "two calibration points in a row (line %zu and this one)", st->cal_line);
        }
        st->cal_h = h0;
        st->cal_m = d->m[st->gfirst];
        st->cal_line = st->gline;
        d->npoints--; /* not a curve point */
        return HY_OK;
    }
    if (d->ncurves >= HY_FORC_MAX_CURVES) {
        s->line = st->gline;
        return at_err(err, s, s->ls, "more than %u curves", HY_FORC_MAX_CURVES);
    }
    if (d->ncrv && d->ncurves >= (size_t)d->ncrv) {
        size_t line = s->line;
        s->line = st->gline;
        int rc = at_err(err, s, s->ls, "curve %zu, but the header says NCrv = %ld", d->ncurves + 1, d->ncrv);
        s->line = line;
        return rc;
    }
    if (push_curve(&st->b, h0, st->gfirst, st->gline))
        return hy_error_set(err, HY_ENOMEM, "%s: out of memory", s->name);
    hy_forc_curve *c = &d->curve[d->ncurves - 1];
    c->cal_h = st->cal_h;
    c->cal_m = st->cal_m;
    if (!isnan(st->cal_h))
        d->ncal++;
    st->cal_h = st->cal_m = NAN;
    return HY_OK;
}

/* One data line of a group (text at s->ls..s->le). */
static int mm_point(hy_forc_data *d, mm_state *st, scan *s, hy_error *err)
{
    double v[2];
    const char *why = NULL, *bad = parse_row(s->ls, s->le, v, 2, &why);
    if (bad)
        return at_err(err, s, bad, "%s (data lines are 'field,moment')", why);
    if (!st->open) {
        st->open = 1;
        st->gfirst = d->npoints;
        st->gline = s->line;
    } else if (!(v[0] > d->hb[d->npoints - 1]))
        return at_err(err, s, skip_sp(s->ls, s->le), "the field does not ascend along the curve (%.7g after %.7g)",
                      v[0], d->hb[d->npoints - 1]);
    if (d->npoints >= HY_FORC_MAX_POINTS)
        return at_err(err, s, s->ls, "more than %u points", HY_FORC_MAX_POINTS);
    if (push_point(&st->b, v[0], v[1]))
        return hy_error_set(err, HY_ENOMEM, "%s: out of memory", s->name);
    st->lines++;
    return HY_OK;
}

/* Whether the word w occurs in [p, e). */
static int has_word(const char *p, const char *e, const char *w)
{
    size_t n = strlen(w);
    for (; (size_t)(e - p) >= n; p++)
        if (!memcmp(p, w, n))
            return 1;
    return 0;
}

static int is_data_line(const scan *s)
{
    double v[2];
    const char *why;
    return !parse_row(s->ls, s->le, v, 2, &why);
}

static int mm_read(hy_forc_data *d, scan *s, hy_error *err)
{
    int r = next_line(s);
    if (r <= 0 || (size_t)(s->le - s->ls) < sizeof mm_magic - 1 || memcmp(s->ls, mm_magic, sizeof mm_magic - 1))
        return at_err(err, s, s->ls, "not a MicroMag 2900/3900 data file (its first line starts '%s')", mm_magic);
    /* header: up to the first data line (or a "Field ... Moment" column header) */
    int data = 0;
    while (!data && (r = next_line(s)) > 0) {
        if (blank(s->ls, s->le))
            continue;
        if (is_data_line(s)) {
            data = 1;
            break;
        }
        const char *l = skip_sp(s->ls, s->le);
        if ((size_t)(s->le - l) >= 5 && !strncasecmp(l, "Field", 5) && has_word(l, s->le, "oment")) {
            /* column names; a units line "(T) (Am2)" may follow */
            const char *save = s->p;
            size_t sline = s->line;
            if ((r = next_line(s)) > 0 && *skip_sp(s->ls, s->le) != '(')
                s->p = save, s->line = sline;
            data = 2;
            break;
        }
        if (mm_header(d, s, err))
            return err ? err->code : HY_EINVAL;
    }
    if (r < 0)
        return at_err(err, s, s->ls, "line longer than %u bytes", HY_FORC_MAX_LINE);
    if (!data)
        return at_err(err, s, NULL, "the file ends in its header: no data (truncated?)");
    mm_state st = {{d, 0, 0}, 0, 0, 0, NAN, NAN, 0, 0};
    int ended = 0;
    if (data == 1 && mm_point(d, &st, s, err))
        return err ? err->code : HY_EINVAL;
    while ((r = next_line(s)) > 0) {
        if (ended) {
            if (!blank(s->ls, s->le))
                return at_err(err, s, s->ls, "text after the line '%s'", mm_end);
            continue;
        }
        int rc = HY_OK;
        if (blank(s->ls, s->le))
            rc = mm_group(d, &st, s, err);
        else if ((size_t)(s->le - s->ls) >= sizeof mm_end - 1 && !memcmp(s->ls, mm_end, sizeof mm_end - 1))
            rc = mm_group(d, &st, s, err), ended = 1;
        else
            rc = mm_point(d, &st, s, err);
        if (rc)
            return rc;
    }
    if (r < 0)
        return at_err(err, s, s->ls, "line longer than %u bytes", HY_FORC_MAX_LINE);
    if (!ended && mm_group(d, &st, s, err))
        return err ? err->code : HY_EINVAL;
    if (!isnan(st.cal_h))
        return at_err(err, s, NULL, "the file ends after the calibration point of line %zu: no curve follows "
                      "(truncated?)", st.cal_line);
    if (d->ncrv && d->ncurves < (size_t)d->ncrv)
        return at_err(err, s, NULL, "the file ends after %zu curves; the header says NCrv = %ld (truncated?)",
                      d->ncurves, d->ncrv);
    if (d->ndata && st.lines != d->ndata)
        return at_err(err, s, NULL, "%ld data lines; the header says NData = %ld%s", st.lines, d->ndata,
                      st.lines < d->ndata ? " (truncated?)" : "");
    if (!ended && !d->ncrv && !d->ndata)
        return at_err(err, s, NULL, "no line '%s' and no NCrv or NData to check against (truncated?)", mm_end);
    if (!d->ncurves)
        return at_err(err, s, NULL, "no curves");
    return HY_OK;
}

/* Runs reader over the text; on failure d owns nothing. */
static int read_with(int (*reader)(hy_forc_data *, scan *, hy_error *), hy_forc_data *d, const char *text,
                     size_t len, const char *name, hy_error *err)
{
    if (!d)
        return null_arg(err, "hy_forc_read", "d");
    data_init(d);
    if (!text && len)
        return null_arg(err, "hy_forc_read", "text (len is not 0)");
    if (!text)
        text = ""; /* len 0 */
    scan s = {text, text + len, name ? name : "FORC file", 0, text, text};
    int rc = reader(d, &s, err);
    if (rc)
        hy_forc_data_free(d);
    return rc;
}

int hy_forc_read_micromag(hy_forc_data *d, const char *text, size_t len, const char *name, hy_error *err)
{
    return read_with(mm_read, d, text, len, name, err);
}

/* ---- CSV ------------------------------------------------------------------- */

static int csv_read(hy_forc_data *d, scan *s, hy_error *err)
{
    builder b = {d, 0, 0};
    int r, first = 1;
    size_t cfirst = 0, cline = 0;
    double ha = NAN;
    while ((r = next_line(s)) > 0) {
        const char *l = skip_sp(s->ls, s->le);
        if (l == s->le || *l == '#')
            continue;
        double v[3];
        const char *why = NULL, *bad = parse_row(s->ls, s->le, v, 3, &why);
        if (bad && first && !isdigit((unsigned char)*l) && *l != '+' && *l != '-' && *l != '.') {
            first = 0; /* column names */
            continue;
        }
        first = 0;
        if (bad)
            return at_err(err, s, bad, "%s (rows are 'H_a,H_b,M')", why);
        if (d->npoints && v[0] == ha) {
            if (!(v[1] > d->hb[d->npoints - 1]))
                return at_err(err, s, l, "H_b does not ascend along the curve of H_a = %.7g", ha);
        } else {
            if (d->npoints && push_curve(&b, ha, cfirst, cline))
                return hy_error_set(err, HY_ENOMEM, "%s: out of memory", s->name);
            if (d->ncurves >= HY_FORC_MAX_CURVES)
                return at_err(err, s, l, "more than %u curves", HY_FORC_MAX_CURVES);
            ha = v[0], cfirst = d->npoints, cline = s->line;
        }
        if (d->npoints >= HY_FORC_MAX_POINTS)
            return at_err(err, s, l, "more than %u points", HY_FORC_MAX_POINTS);
        if (push_point(&b, v[1], v[2]))
            return hy_error_set(err, HY_ENOMEM, "%s: out of memory", s->name);
    }
    if (r < 0)
        return at_err(err, s, s->ls, "line longer than %u bytes", HY_FORC_MAX_LINE);
    if (!d->npoints)
        return at_err(err, s, NULL, "no data rows");
    if (push_curve(&b, ha, cfirst, cline))
        return hy_error_set(err, HY_ENOMEM, "%s: out of memory", s->name);
    return HY_OK;
}

int hy_forc_read_csv(hy_forc_data *d, const char *text, size_t len, const char *name, hy_error *err)
{
    return read_with(csv_read, d, text, len, name, err);
}

int hy_forc_read(hy_forc_data *d, const char *text, size_t len, const char *name, hy_error *err)
{
    if (text && len >= 8 && !memcmp(text, "MicroMag", 8))
        return hy_forc_read_micromag(d, text, len, name, err);
    return hy_forc_read_csv(d, text, len, name, err);
}

/* ---- drift, steps -------------------------------------------------------------- */

int hy_forc_drift(hy_forc_data *d, hy_error *err)
{
    if (!d)
        return null_arg(err, "hy_forc_drift", "d");
    if (!d->ncurves)
        return hy_error_set(err, HY_EINVAL, "drift correction: no curves");
    double ref = d->curve[0].cal_m;
    for (size_t i = 0; i < d->ncurves; i++) {
        double c = d->curve[i].cal_m;
        if (!isfinite(c) || !(fabs(c) > 0) || !(c * ref > 0))
            return hy_error_set(err, HY_EINVAL,
                                "drift correction: curve %zu (H_a = %.7g) has %s calibration point", i + 1,
                                d->curve[i].ha, isfinite(c) ? "a zero or sign-changed" : "no");
    }
    for (size_t i = 0; i < d->ncurves; i++) {
        const hy_forc_curve *c = &d->curve[i];
        double f = ref / c->cal_m;
        for (size_t j = 0; j < c->n; j++)
            d->m[c->first + j] *= f;
    }
    return HY_OK;
}

static int cmp_dbl(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* (value, index) pairs by value, then index */
static int cmp_pair(const void *a, const void *b)
{
    const double *x = a, *y = b;
    int c = cmp_dbl(x, y);
    return c ? c : cmp_dbl(x + 1, y + 1);
}

/* Median of the positive values v[0..n) (sorted in place); 0 when none. */
static double median_pos(double *v, size_t n)
{
    size_t k = 0;
    for (size_t i = 0; i < n; i++)
        if (v[i] > 0)
            v[k++] = v[i];
    if (!k)
        return 0;
    qsort(v, k, sizeof *v, cmp_dbl);
    return k % 2 ? v[k / 2] : 0.5 * (v[k / 2 - 1] + v[k / 2]);
}

void hy_forc_steps(const hy_forc_data *d, double *da, double *db)
{
    double sa, sb;
    if (!da)
        da = &sa;
    if (!db)
        db = &sb;
    *da = *db = 0;
    if (!d)
        return;
    size_t n = d->npoints > d->ncurves ? d->npoints : d->ncurves;
    double *v = malloc((n + 1) * sizeof *v);
    *da = *db = 0;
    if (!v)
        return;
    size_t k = 0;
    for (size_t i = 0; i < d->ncurves; i++)
        for (size_t j = 1; j < d->curve[i].n; j++)
            v[k++] = d->hb[d->curve[i].first + j] - d->hb[d->curve[i].first + j - 1];
    *db = median_pos(v, k);
    for (size_t i = 0; i < d->ncurves; i++)
        v[i] = d->curve[i].ha;
    qsort(v, d->ncurves, sizeof *v, cmp_dbl);
    for (size_t i = 1; i < d->ncurves; i++)
        v[i - 1] = v[i] - v[i - 1];
    *da = d->ncurves > 1 ? median_pos(v, d->ncurves - 1) : 0;
    free(v);
}

/* ---- the distribution --------------------------------------------------------- */

hy_forc_opts hy_forc_defaults(void)
{
    return (hy_forc_opts){.sf = 3, .sc0 = 0, .sc1 = 0, .ramp = 0, .extend = 1, .da = 0, .db = 0};
}

void hy_forc_grid_free(hy_forc_grid *g)
{
    if (g) {
        free(g->rho);
        g->rho = NULL;
    }
}

void hy_forc_grid_auto(const hy_forc_data *d, const hy_forc_opts *o, hy_forc_grid *g)
{
    if (!g)
        return;
    hy_forc_data none = {0};
    hy_forc_opts dflt = hy_forc_defaults();
    if (!d)
        d = &none;
    if (!o)
        o = &dflt;
    double da = o->da, db = o->db, sa, sb;
    hy_forc_steps(d, &sa, &sb);
    if (!(da > 0))
        da = sa;
    if (!(db > 0))
        db = sb;
    double hcmax = 0, humin = INFINITY, humax = -INFINITY;
    for (size_t i = 0; i < d->ncurves; i++) {
        const hy_forc_curve *c = &d->curve[i];
        for (size_t j = 0; j < c->n; j++) {
            double hb = d->hb[c->first + j];
            if (hb < c->ha)
                continue;
            double hc = 0.5 * (hb - c->ha), hu = 0.5 * (hb + c->ha);
            hcmax = fmax(hcmax, hc);
            humin = fmin(humin, hu);
            humax = fmax(humax, hu);
        }
    }
    double step = db > 0 ? db : 1;
    if (!(humin <= humax))
        humin = humax = 0;
    /* spacing exactly one step (on a regular grid every node then sees a
     * neighbourhood of the same shape), coarser when a side would pass 1000 */
    double nc = floor(hcmax / step + 0.5) + 1, nu = floor((humax - humin) / step + 0.5) + 1;
    double sc = nc > 1000 || nu > 1000 ? ceil(fmax(nc, nu) / 1000) : 1;
    g->nc = (size_t)fmax(2, floor((nc - 1) / sc) + 1);
    g->nu = (size_t)fmax(2, floor((nu - 1) / sc) + 1);
    g->hc0 = 0;
    g->hc1 = (double)(g->nc - 1) * sc * step;
    g->hu0 = humin;
    g->hu1 = humin + (double)(g->nu - 1) * sc * step;
    g->rho = NULL;
}

/* The curves sorted by H_a, and the workspace of one fit. */
/* The weights of earlier neighbourhoods by their shape: on a regular grid
 * the nodes' neighbourhoods repeat a few shapes, and ρ at a node is then one
 * dot product.  Direct-mapped; a slot keeps the points' offsets quantised
 * to 2^-30 step (key) and the weights computed from the first node of that
 * shape, so nodes whose offsets differ by rounding share them. */
enum { WC_SLOTS = 64 };
typedef struct wc_slot {
    size_t n, cap;
    uint64_t hash;
    int64_t *key;     /* 2n quantised offsets */
    double *w;        /* n weights            */
} wc_slot;

typedef struct fit_ws {
    const hy_forc_data *d;
    size_t *ord;      /* curve indices by ascending H_a */
    double *ha;       /* H_a in that order              */
    double *a, *b;    /* design matrix (column-major, cap rows) and right-hand side */
    double *w;        /* weights of the present fit     */
    int64_t *key;     /* its shape                      */
    size_t cap;
    wc_slot slot[WC_SLOTS];
    size_t hits, misses;  /* past 256 misses with fewer than 1 hit in 16 the cache is bypassed (irregular data) */
} fit_ws;

static int ws_grow(fit_ws *w, size_t n)
{
    if (n <= w->cap)
        return HY_OK;
    size_t cap = w->cap ? w->cap : 64;
    while (cap < n)
        cap *= 2;
    double *a = realloc(w->a, 6 * cap * sizeof *a);
    if (!a)
        return HY_ENOMEM;
    /* the columns move to their new offsets k·cap (last first: they only
     * move up), so rows gathered before the growth stay where they belong */
    for (int k = 5; k > 0 && w->cap; k--)
        memmove(a + (size_t)k * cap, a + (size_t)k * w->cap, w->cap * sizeof *a);
    w->a = a;
    double *b = realloc(w->b, cap * sizeof *b);
    if (!b)
        return HY_ENOMEM;
    w->b = b;
    double *wt = realloc(w->w, cap * sizeof *wt);
    if (!wt)
        return HY_ENOMEM;
    w->w = wt;
    int64_t *key = realloc(w->key, 2 * cap * sizeof *key);
    if (!key)
        return HY_ENOMEM;
    w->key = key;
    w->cap = cap;
    return HY_OK;
}

/* First index i in the ascending v[0..n) with v[i] >= x. */
static size_t lower(const double *v, size_t n, double x)
{
    size_t lo = 0, hi = n;
    while (lo < hi) {
        size_t mid = lo + (hi - lo) / 2;
        if (v[mid] < x)
            lo = mid + 1;
        else
            hi = mid;
    }
    return lo;
}

/* Adds the row (x, y, M) to the fit: columns 1, x, y, x², y², x·y (x·y last:
 * its coefficient is the one wanted).  Rows are written transposed into a
 * temporary order and moved into columns after counting (see gather). */
static void row_put(double *a, size_t cap, size_t i, double x, double y, double m, double *b)
{
    a[0 * cap + i] = 1;
    a[1 * cap + i] = x;
    a[2 * cap + i] = y;
    a[3 * cap + i] = x * x;
    a[4 * cap + i] = y * y;
    a[5 * cap + i] = x * y;
    b[i] = m;
}

/* The points of the box |H_a − ha0| <= wa, |H_b − hb0| <= wb (with the
 * constant extension below each curve's first point) into the workspace, in
 * units of the steps; returns their count, or (size_t)-1 out of memory. */
static size_t gather(fit_ws *w, double ha0, double hb0, double wa, double wb, double da, double db, int extend)
{
    const hy_forc_data *d = w->d;
    size_t k0 = lower(w->ha, d->ncurves, ha0 - wa), n = 0;
    for (size_t k = k0; k < d->ncurves && w->ha[k] <= ha0 + wa; k++) {
        const hy_forc_curve *c = &d->curve[w->ord[k]];
        const double *hb = d->hb + c->first, *m = d->m + c->first;
        double x = (c->ha - ha0) / da;
        size_t j = lower(hb, c->n, hb0 - wb);
        size_t need = n + (c->n - j) + (extend ? (size_t)(2 * wb / db) + 2 : 0);
        if (ws_grow(w, need))
            return (size_t)-1;
        if (extend && hb0 - wb < hb[0]) { /* M(H_a, H_b) = M(H_a, first point) below the first point */
            for (size_t e = 1;; e++) {
                double h = hb[0] - (double)e * db;
                if (h < hb0 - wb)
                    break;
                if (h <= hb0 + wb)
                    row_put(w->a, w->cap, n++, x, (h - hb0) / db, m[0], w->b);
            }
        }
        for (; j < c->n && hb[j] <= hb0 + wb; j++)
            row_put(w->a, w->cap, n++, x, (hb[j] - hb0) / db, m[j], w->b);
    }
    return n;
}

/* Householder QR of the n × 6 design matrix (columns at a + k·cap, x·y
 * last), then the weights w of the least-squares x·y coefficient,
 * c5 = Σ w_i M_i: w = Q e_5 / R_55 (the reflectors applied to e_5 in
 * reverse order).  Returns -1 when the matrix is rank-deficient. */
static int qr_weights(double *a, size_t cap, size_t n, double *w)
{
    double v0[6], vtv[6];
    for (int k = 0; k < 6; k++) {
        double *ak = a + (size_t)k * cap, scale = 0, full = 0, nrm = 0;
        for (size_t i = (size_t)k; i < n; i++)
            scale = fmax(scale, fabs(ak[i]));
        for (size_t i = 0; i < n; i++)
            full = fmax(full, fabs(ak[i]));
        if (!(scale > 0))
            return -1;
        for (size_t i = (size_t)k; i < n; i++)
            nrm += (ak[i] / scale) * (ak[i] / scale);
        nrm = scale * sqrt(nrm);
        if (nrm <= 1e-9 * full) /* this column is (nearly) a combination of the previous ones */
            return -1;
        double alpha = ak[k] > 0 ? -nrm : nrm;
        vtv[k] = 2 * nrm * (nrm + fabs(ak[k])); /* v = column − alpha e_k */
        ak[k] -= alpha;
        v0[k] = ak[k];
        for (int j = k + 1; j < 6; j++) {
            double *aj = a + (size_t)j * cap, t = 0;
            for (size_t i = (size_t)k; i < n; i++)
                t += ak[i] * aj[i];
            t = 2 * t / vtv[k];
            for (size_t i = (size_t)k; i < n; i++)
                aj[i] -= t * ak[i];
        }
        ak[k] = alpha; /* R_kk */
    }
    for (size_t i = 0; i < n; i++)
        w[i] = i == 5;
    for (int k = 5; k >= 0; k--) {
        const double *ak = a + (size_t)k * cap;
        double t = v0[k] * w[k];
        for (size_t i = (size_t)k + 1; i < n; i++)
            t += ak[i] * w[i];
        t = 2 * t / vtv[k];
        w[k] -= t * v0[k];
        for (size_t i = (size_t)k + 1; i < n; i++)
            w[i] -= t * ak[i];
    }
    double r55 = a[5 * cap + 5];
    for (size_t i = 0; i < n; i++)
        w[i] /= r55;
    return 0;
}

/* The weights for the n gathered points: from the cache when a node of the
 * same shape came before, else by QR (and kept).  NULL when rank-deficient,
 * or out of memory (*oom set). */
static const double *weights(fit_ws *w, size_t n, int *oom)
{
    if (w->misses >= 256 && w->hits < w->misses / 16)
        return qr_weights(w->a, w->cap, n, w->w) ? NULL : w->w;
    uint64_t h = 1469598103934665603ull ^ n;
    for (size_t i = 0; i < n; i++) {
        w->key[2 * i] = llround(w->a[w->cap + i] * 0x1p30);
        w->key[2 * i + 1] = llround(w->a[2 * w->cap + i] * 0x1p30);
        h = (h ^ (uint64_t)w->key[2 * i]) * 1099511628211ull;
        h = (h ^ (uint64_t)w->key[2 * i + 1]) * 1099511628211ull;
    }
    wc_slot *sl = &w->slot[(h ^ (h >> 32)) % WC_SLOTS];
    if (sl->n == n && sl->hash == h && !memcmp(sl->key, w->key, 2 * n * sizeof *w->key)) {
        w->hits++;
        return sl->w;
    }
    w->misses++;
    if (qr_weights(w->a, w->cap, n, w->w))
        return NULL;
    if (n > sl->cap) {
        int64_t *k = realloc(sl->key, 2 * n * sizeof *k);
        if (k)
            sl->key = k;
        double *ww = k ? realloc(sl->w, n * sizeof *ww) : NULL;
        if (!ww) {
            *oom = 1;
            return NULL;
        }
        sl->w = ww;
        sl->cap = n;
    }
    sl->n = n;
    sl->hash = h;
    memcpy(sl->key, w->key, 2 * n * sizeof *w->key);
    memcpy(sl->w, w->w, n * sizeof *w->w);
    return w->w;
}

/* Whether the node lies inside the data: a curve within 0.75 Δ_a of its H_a
 * whose points reach H_b (the extension covers H_b below them). */
static int inside(const fit_ws *w, double ha0, double hb0, double da, double db, int extend)
{
    const hy_forc_data *d = w->d;
    size_t k = lower(w->ha, d->ncurves, ha0);
    size_t best = k < d->ncurves ? k : d->ncurves - 1;
    if (k > 0 && (k == d->ncurves || ha0 - w->ha[k - 1] < w->ha[k] - ha0))
        best = k - 1;
    if (fabs(w->ha[best] - ha0) > 0.75 * da)
        return 0;
    const hy_forc_curve *c = &d->curve[w->ord[best]];
    const double *hb = d->hb + c->first;
    if (hb0 > hb[c->n - 1] + 0.5 * db)
        return 0;
    return extend || hb0 >= hb[0] - 0.5 * db;
}

static int ws_init(fit_ws *w, const hy_forc_data *d)
{
    memset(w, 0, sizeof *w);
    w->d = d;
    w->ord = malloc(d->ncurves * sizeof *w->ord);
    w->ha = malloc(d->ncurves * sizeof *w->ha);
    double *key = malloc(2 * d->ncurves * sizeof *key);
    if (!w->ord || !w->ha || !key || ws_grow(w, 256)) {
        free(key);
        return HY_ENOMEM;
    }
    /* sort (H_a, index) pairs: stable order for equal H_a */
    for (size_t i = 0; i < d->ncurves; i++)
        key[2 * i] = d->curve[i].ha, key[2 * i + 1] = (double)i;
    qsort(key, d->ncurves, 2 * sizeof *key, cmp_pair);
    for (size_t i = 0; i < d->ncurves; i++)
        w->ha[i] = key[2 * i], w->ord[i] = (size_t)key[2 * i + 1];
    free(key);
    return HY_OK;
}

static void ws_free(fit_ws *w)
{
    free(w->ord);
    free(w->ha);
    free(w->a);
    free(w->b);
    free(w->w);
    free(w->key);
    for (int i = 0; i < WC_SLOTS; i++) {
        free(w->slot[i].key);
        free(w->slot[i].w);
    }
}

static int check_opts(const hy_forc_data *d, const hy_forc_opts *o, const hy_forc_grid *g, double da, double db,
                      hy_error *err)
{
    if (!d || d->ncurves < 2)
        return hy_error_set(err, HY_EINVAL, "FORC distribution: at least 2 curves are needed");
    int vari = o->sc1 > 0;
    if (!vari && !(o->sf >= 1 && o->sf <= 50))
        return hy_error_set(err, HY_EINVAL, "FORC distribution: SF must be in [1, 50] (got %g)", o->sf);
    if (vari && !(o->sc0 >= 1 && o->sc0 <= 50 && o->sc1 >= 1 && o->sc1 <= 50 && isfinite(o->ramp)))
        return hy_error_set(err, HY_EINVAL, "FORC distribution: sc0 and sc1 must be in [1, 50] (got %g, %g)",
                            o->sc0, o->sc1);
    if (!(da > 0 && db > 0 && isfinite(da) && isfinite(db)))
        return hy_error_set(err, HY_EINVAL, "FORC distribution: no positive field step (Δ_a = %g, Δ_b = %g)", da,
                            db);
    if (g->nc < 1 || g->nu < 1 || g->nc > 4000000 / g->nu)
        return hy_error_set(err, HY_EINVAL, "FORC distribution: a grid of %zu x %zu nodes (1 to 4e6)", g->nc,
                            g->nu);
    if (!(isfinite(g->hc0) && isfinite(g->hc1) && isfinite(g->hu0) && isfinite(g->hu1)) ||
        (g->nc > 1 && !(g->hc1 > g->hc0)) || (g->nu > 1 && !(g->hu1 > g->hu0)))
        return hy_error_set(err, HY_EINVAL, "FORC distribution: the grid's ranges must be finite and ascending");
    return HY_OK;
}

int hy_forc_rho(const hy_forc_data *d, const hy_forc_opts *o, hy_forc_grid *g, size_t *nfit, hy_error *err)
{
    if (!d || !o || !g)
        return null_arg(err, "hy_forc_rho", !d ? "d" : !o ? "o" : "g");
    double da = o->da, db = o->db, sa = 0, sb = 0;
    if (!(da > 0) || !(db > 0))
        hy_forc_steps(d, &sa, &sb);
    if (!(da > 0))
        da = sa;
    if (!(db > 0))
        db = sb;
    int rc = check_opts(d, o, g, da, db, err);
    if (rc)
        return rc;
    free(g->rho);
    g->rho = malloc(g->nc * g->nu * sizeof *g->rho);
    fit_ws w;
    memset(&w, 0, sizeof w);
    if (!g->rho || ws_init(&w, d)) {
        ws_free(&w);
        return hy_error_set(err, HY_ENOMEM, "FORC distribution: out of memory");
    }
    double ramp = o->ramp > 0 ? o->ramp : fmax(fabs(g->hc1), fabs(g->hc0));
    double dc = g->nc > 1 ? (g->hc1 - g->hc0) / (double)(g->nc - 1) : 0;
    double du = g->nu > 1 ? (g->hu1 - g->hu0) / (double)(g->nu - 1) : 0;
    size_t fitted = 0;
    for (size_t iu = 0; iu < g->nu; iu++)
        for (size_t ic = 0; ic < g->nc; ic++) {
            double hc = g->hc0 + (double)ic * dc, hu = g->hu0 + (double)iu * du;
            double ha0 = hu - hc, hb0 = hu + hc, *out = &g->rho[iu * g->nc + ic];
            *out = NAN;
            if (!inside(&w, ha0, hb0, da, db, o->extend))
                continue;
            double s = o->sf;
            if (o->sc1 > 0)
                s = o->sc0 + (o->sc1 - o->sc0) * fmin(1, fabs(hc) / (ramp > 0 ? ramp : 1));
            size_t n = gather(&w, ha0, hb0, (s + 0.5) * da, (s + 0.5) * db, da, db, o->extend);
            if (n == (size_t)-1) {
                ws_free(&w);
                return hy_error_set(err, HY_ENOMEM, "FORC distribution: out of memory");
            }
            if (n < 9)
                continue;
            int oom = 0;
            const double *wt = weights(&w, n, &oom);
            if (oom) {
                ws_free(&w);
                return hy_error_set(err, HY_ENOMEM, "FORC distribution: out of memory");
            }
            if (!wt)
                continue;
            double c = 0;
            for (size_t i = 0; i < n; i++)
                c += wt[i] * w.b[i];
            *out = -0.5 * c / (da * db);
            fitted++;
        }
    ws_free(&w);
    if (nfit)
        *nfit = fitted;
    return HY_OK;
}

/* ---- the protocol ------------------------------------------------------------- */

int hy_forc_protocol_run(hy_forc_data *d, const hy_forc_protocol *pr, hy_rateind_fn fn, void *ctx,
                         hy_error *err)
{
    if (!d)
        return null_arg(err, "hy_forc_protocol_run", "d");
    data_init(d);
    if (!pr || !fn)
        return null_arg(err, "hy_forc_protocol_run", !pr ? "pr" : "fn");
    size_t nc = pr->ncurves;
    if (nc < 2 || nc > HY_FORC_MAX_CURVES)
        return hy_error_set(err, HY_EINVAL, "FORC protocol: %zu curves (2 to %u)", nc, HY_FORC_MAX_CURVES);
    if (!(isfinite(pr->ha_lo) && isfinite(pr->ha_hi) && isfinite(pr->hb_max) && isfinite(pr->hsat)) ||
        !(pr->ha_lo < pr->ha_hi) || !(pr->hb_max >= pr->ha_hi) || !(pr->hsat >= pr->hb_max))
        return hy_error_set(err, HY_EINVAL,
                            "FORC protocol: needs finite ha_lo < ha_hi <= hb_max <= hsat (got %g, %g, %g, %g)",
                            pr->ha_lo, pr->ha_hi, pr->hb_max, pr->hsat);
    double step = (pr->ha_hi - pr->ha_lo) / (double)(nc - 1);
    size_t total = 0;
    for (size_t i = 0; i < nc; i++) {
        double ha = pr->ha_hi - (double)i * step;
        total += (size_t)floor((pr->hb_max - ha) / step + 1e-9) + 1;
        if (total > HY_FORC_MAX_POINTS)
            return hy_error_set(err, HY_EINVAL, "FORC protocol: more than %u points", HY_FORC_MAX_POINTS);
    }
    builder b = {d, 0, 0};
    int rc = HY_OK;
    for (size_t i = 0; i < nc && !rc; i++) {
        double ha = i + 1 == nc ? pr->ha_lo : pr->ha_hi - (double)i * step, y;
        size_t np = (size_t)floor((pr->hb_max - ha) / step + 1e-9) + 1, first = d->npoints;
        if ((rc = fn(ctx, pr->hsat, &y, err)) || (rc = fn(ctx, ha, &y, err)))
            break;
        if (push_point(&b, ha, y))
            rc = HY_ENOMEM;
        for (size_t j = 1; j < np && !rc; j++) {
            double hb = ha + (double)j * step;
            if (!(rc = fn(ctx, hb, &y, err)) && push_point(&b, hb, y))
                rc = HY_ENOMEM;
        }
        if (!rc && push_curve(&b, ha, first, 0))
            rc = HY_ENOMEM;
    }
    if (rc == HY_ENOMEM)
        hy_error_set(err, rc, "FORC protocol: out of memory");
    if (rc)
        hy_forc_data_free(d);
    return rc;
}

static int preisach_fn(void *ctx, double u, double *y, hy_error *err)
{
    return hy_preisach_mem_apply(ctx, u, y, err);
}

int hy_forc_preisach(hy_forc_data *d, const hy_forc_protocol *pr, const hy_preisach *p, hy_error *err)
{
    if (!d)
        return null_arg(err, "hy_forc_preisach", "d");
    data_init(d);
    if (!pr || !p)
        return null_arg(err, "hy_forc_preisach", !pr ? "pr" : "p");
    if (!isfinite(pr->hsat))
        return hy_error_set(err, HY_EINVAL, "FORC protocol: hsat is not finite");
    hy_preisach_mem mem;
    int rc = hy_preisach_mem_init(&mem, p, pr->hsat, err);
    if (rc)
        return rc;
    rc = hy_forc_protocol_run(d, pr, preisach_fn, &mem, err);
    hy_preisach_mem_free(&mem);
    return rc;
}
