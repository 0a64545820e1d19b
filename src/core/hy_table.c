/* SPDX-License-Identifier: MIT */
/* hy_table.c: measured samples from CSV or whitespace-separated text (untrusted:
 * caps, file:line:col on every refusal, nothing of the file quoted unless asked),
 * and the shoelace area of a closed measured loop. */
#include "hy_table.h"

#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "hy_file.h"

/* One line split into fields: start offsets (from the line's start) and lengths. */
typedef struct fields {
    size_t n;
    size_t at[HY_TABLE_MAX_COLS + 1], len[HY_TABLE_MAX_COLS + 1];
} fields;

typedef struct reader {
    const char *name;
    int quote;
    hy_error *err;
    size_t lineno;
} reader;

static int fail(const reader *rd, size_t col, const char *what)
{
    return hy_error_set(rd->err, HY_EINVAL, "%s:%zu:%zu: %s", rd->name, rd->lineno, col, what);
}

/* Splits s[0..n) at commas when it holds one, else at blanks; fields trimmed.
 * -1 when it has more than HY_TABLE_MAX_COLS. */
static int split(const char *s, size_t n, fields *f)
{
    int comma = memchr(s, ',', n) != NULL;
    size_t i = 0;
    f->n = 0;
    while (i <= n) {
        while (i < n && (s[i] == ' ' || s[i] == '\t'))
            i++;
        if (!comma && i == n)
            break;
        size_t a = i;
        while (i < n && (comma ? s[i] != ',' : s[i] != ' ' && s[i] != '\t'))
            i++;
        size_t b = i;
        while (b > a && (s[b - 1] == ' ' || s[b - 1] == '\t'))
            b--;
        if (f->n == HY_TABLE_MAX_COLS)
            return -1;
        f->at[f->n] = a;
        f->len[f->n++] = b - a;
        if (comma && i == n)
            break;
        if (comma)
            i++; /* past the comma */
    }
    return 0;
}

/* Whether s[0..n) is a decimal number: [+-] digits [. digits] [(e|E) [+-] digits]. */
static int decimal(const char *s, size_t n)
{
    size_t i = 0, d = 0;
    if (i < n && (s[i] == '+' || s[i] == '-'))
        i++;
    while (i < n && isdigit((unsigned char)s[i]))
        i++, d++;
    if (i < n && s[i] == '.')
        for (i++; i < n && isdigit((unsigned char)s[i]); i++)
            d++;
    if (!d)
        return 0;
    if (i < n && (s[i] == 'e' || s[i] == 'E')) {
        size_t e = 0;
        if (++i < n && (s[i] == '+' || s[i] == '-'))
            i++;
        while (i < n && isdigit((unsigned char)s[i]))
            i++, e++;
        if (!e)
            return 0;
    }
    return i == n;
}

/* The field's value into *v: 0; 1 not a number; 2 nan, inf or out of range. */
static int number(const char *s, size_t n, double *v)
{
    char buf[128];
    if (!decimal(s, n)) {
        const char *p = s + (n && (s[0] == '+' || s[0] == '-'));
        size_t m = n - (size_t)(p - s);
        if ((m == 3 && !strncasecmp(p, "nan", 3)) || (m == 3 && !strncasecmp(p, "inf", 3)) ||
            (m == 8 && !strncasecmp(p, "infinity", 8)))
            return 2;
        return 1;
    }
    if (n >= sizeof buf)
        return 1;
    memcpy(buf, s, n);
    buf[n] = '\0';
    *v = strtod(buf, NULL);
    return isfinite(*v) ? 0 : 2;
}

/* Whether every field of the line is a number (of any kind: a header has a word). */
static int all_numbers(const char *s, const fields *f)
{
    for (size_t i = 0; i < f->n; i++) {
        double v;
        if (number(s + f->at[i], f->len[i], &v) == 1)
            return 0;
    }
    return 1;
}

/* The header's fields, kept for naming columns. */
typedef struct header {
    const char *s;  /* the header's text (a comment: after '#') */
    fields f;
    size_t line, col0; /* its line and the column of s[0] */
    int have;
} header;

/* Column index (0-based) of spec text c, or an error at the first row (line
 * row_line). */
static int column(const reader *rd, const header *h, size_t ncols, const char *c, const char *key, size_t *idx)
{
    char what[300];
    size_t n = strlen(c), k = 0;
    int digits = n > 0 && n < 10;
    for (size_t i = 0; i < n; i++)
        digits &= isdigit((unsigned char)c[i]) != 0;
    if (digits) {
        k = (size_t)strtoul(c, NULL, 10);
        if (k < 1 || k > ncols) {
            snprintf(what, sizeof what, "column %s (%s) does not exist: the rows have %zu columns", c, key, ncols);
            return fail(rd, 1, what);
        }
        *idx = k - 1;
        return HY_OK;
    }
    char shown[100];
    hy_file_shown(c, n, 40, shown, sizeof shown);
    if (!h->have) {
        snprintf(what, sizeof what, "no header line names the columns: choose %s = '%s' by its 1-based index (1 to %zu)",
                 key, shown, ncols);
        return fail(rd, 1, what);
    }
    size_t found = (size_t)-1;
    for (size_t i = 0; i < h->f.n; i++)
        if (h->f.len[i] == n && !memcmp(h->s + h->f.at[i], c, n)) {
            if (found != (size_t)-1) {
                reader at = *rd;
                at.lineno = h->line;
                snprintf(what, sizeof what, "the header names column '%s' twice (columns %zu and %zu)", shown,
                         found + 1, i + 1);
                return fail(&at, h->col0 + h->f.at[i], what);
            }
            found = i;
        }
    if (found == (size_t)-1) {
        reader at = *rd;
        at.lineno = h->line;
        size_t o = (size_t)snprintf(what, sizeof what, "no column named '%s' (%s) in the header", shown, key);
        for (size_t i = 0; rd->quote && i < h->f.n && o < sizeof what; i++) {
            char nm[100];
            hy_file_shown(h->s + h->f.at[i], h->f.len[i], 40, nm, sizeof nm);
            /* quoted: a name may hold ", " or end in ':' (the list would be ambiguous);
               a name that does not fit whole is left out, said by "..." */
            const char *sep = i ? ", " : "; it names ";
            if (o + strlen(sep) + strlen(nm) + 2 + sizeof ", ..." > sizeof what) {
                snprintf(what + o, sizeof what - o, ", ...");
                break;
            }
            o += (size_t)snprintf(what + o, sizeof what - o, "%s'%s'", sep, nm);
        }
        if (!rd->quote && o < sizeof what)
            snprintf(what + o, sizeof what - o, " of %zu columns", h->f.n);
        return fail(&at, h->col0, what);
    }
    if (found >= ncols) {
        reader at = *rd;
        at.lineno = h->line;
        snprintf(what, sizeof what, "column '%s' (%s) is column %zu of the header, but the rows have %zu columns",
                 shown, key, found + 1, ncols);
        return fail(&at, h->col0 + h->f.at[found], what);
    }
    *idx = found;
    return HY_OK;
}

typedef struct grow {
    double *v[3];
    size_t cap;
    size_t *rec, *line;
    size_t rcap;
} grow;

/* Room for need rows of u, y (and t when with_t). */
static int grow_rows(grow *g, size_t need, int with_t)
{
    if (need <= g->cap)
        return 0;
    size_t c = g->cap ? 2 * g->cap : 1024;
    for (int i = 0; i < 2 + with_t; i++) {
        double *p = realloc(g->v[i], c * sizeof *p);
        if (!p)
            return -1;
        g->v[i] = p;
    }
    g->cap = c;
    return 0;
}

static int grow_recs(grow *g, size_t need)
{
    if (need <= g->rcap)
        return 0;
    size_t c = g->rcap ? 2 * g->rcap : 16;
    size_t *a = realloc(g->rec, (c + 1) * sizeof *a);
    if (a)
        g->rec = a;
    size_t *b = a ? realloc(g->line, (c + 1) * sizeof *b) : NULL;
    if (b)
        g->line = b;
    if (!a || !b)
        return -1;
    g->rcap = c;
    return 0;
}

/* The parser's state across lines. */
typedef struct state {
    reader rd;
    const hy_table_spec *spec;
    header h, comment; /* the header; the last comment line seen before the first row */
    size_t ncols;      /* fields of every row (0: no row yet) */
    size_t idx[HY_TABLE_NCOL];
    int want[HY_TABLE_NCOL];
    double last_split;
    hy_table *t;
    grow g;
} state;

static const char *const keys[HY_TABLE_NCOL] = {"u", "y", "t", "split"};

/* The first row fixes the columns: its count, the header, each column's index. */
static int first_row(state *st, const fields *f)
{
    st->ncols = f->n;
    if (!st->h.have && st->comment.have && st->comment.f.n == f->n)
        st->h = st->comment;
    for (int i = 0; i < HY_TABLE_NCOL; i++)
        if (st->want[i]) {
            int rc = column(&st->rd, &st->h, f->n, st->spec->col[i], keys[i], &st->idx[i]);
            if (rc)
                return rc;
        }
    return HY_OK;
}

/* One data row s (fields f) into the table. */
static int data_row(state *st, const char *s, size_t len, const fields *f)
{
    reader *rd = &st->rd;
    hy_table *t = st->t;
    if (!st->ncols) {
        int rc = first_row(st, f);
        if (rc)
            return rc;
    }
    if (f->n != st->ncols) {
        char what[160];
        snprintf(what, sizeof what, "the row has %zu column%s, the rows before it %zu", f->n, f->n == 1 ? "" : "s",
                 st->ncols);
        return fail(rd, f->n < st->ncols ? len + 1 : f->at[st->ncols] + 1, what);
    }
    double v[HY_TABLE_NCOL] = {0, 0, 0, 0};
    for (size_t i = 0; i < f->n; i++) { /* every field: a measured file holds numbers only */
        double x;
        int k = number(s + f->at[i], f->len[i], &x);
        if (k) {
            char what[160];
            snprintf(what, sizeof what, k == 2 ? "column %zu is not a finite number (nan, inf and overflow are refused)"
                                               : "column %zu is not a number", i + 1);
            return fail(rd, f->at[i] + 1, what);
        }
        for (int c = 0; c < HY_TABLE_NCOL; c++)
            if (st->want[c] && st->idx[c] == i)
                v[c] = x;
    }
    if (t->n == HY_TABLE_MAX_ROWS) {
        char what[120];
        snprintf(what, sizeof what, "more than %zu data rows (the cap on a measured data file)", (size_t)HY_TABLE_MAX_ROWS);
        return fail(rd, 1, what);
    }
    if (grow_rows(&st->g, t->n + 1, st->want[HY_TABLE_T]))
        return hy_error_set(rd->err, HY_ENOMEM, "%s:%zu:1: out of memory", rd->name, rd->lineno);
    int fresh = t->n == 0 || (st->want[HY_TABLE_SPLIT] && v[HY_TABLE_SPLIT] != st->last_split);
    if (fresh) {
        if (grow_recs(&st->g, t->nrec + 1))
            return hy_error_set(rd->err, HY_ENOMEM, "%s:%zu:1: out of memory", rd->name, rd->lineno);
        st->g.rec[t->nrec] = t->n;
        st->g.line[t->nrec++] = rd->lineno;
    }
    st->last_split = v[HY_TABLE_SPLIT];
    for (int c = 0; c < 2 + st->want[HY_TABLE_T]; c++)
        st->g.v[c][t->n] = v[c] * st->spec->scale[c];
    for (int c = 0; c < 2 + st->want[HY_TABLE_T]; c++)
        if (!isfinite(st->g.v[c][t->n])) {
            char what[160];
            snprintf(what, sizeof what, "column %zu times its scale is not a finite number", st->idx[c] + 1);
            return fail(rd, f->at[st->idx[c]] + 1, what);
        }
    t->n++;
    return HY_OK;
}

/* One line s[0..len) (its end removed). */
static int one_line(state *st, const char *s, size_t len)
{
    size_t i = 0;
    while (i < len && (s[i] == ' ' || s[i] == '\t'))
        i++;
    if (i == len)
        return HY_OK;
    fields f;
    if (s[i] == '#') { /* a comment; the last one before the first row may name the columns */
        if (st->ncols || st->h.have)
            return HY_OK;
        const char *c = s + i + 1;
        size_t n = len - i - 1;
        if (split(c, n, &f) || f.n < 2)
            return HY_OK;
        st->comment = (header){c, f, st->rd.lineno, i + 2, 1};
        return HY_OK;
    }
    if (split(s, len, &f)) {
        char what[80];
        snprintf(what, sizeof what, "more than %d columns", HY_TABLE_MAX_COLS);
        return fail(&st->rd, 1, what);
    }
    if (!st->ncols && !st->h.have && !all_numbers(s, &f)) {
        st->h = (header){s, f, st->rd.lineno, 1, 1};
        return HY_OK;
    }
    return data_row(st, s, len, &f);
}

int hy_table_parse(const char *text, size_t len, const char *name, const hy_table_spec *spec, int quote,
                   hy_table *out, hy_error *err)
{
    if (out)
        memset(out, 0, sizeof *out);
    const char *null = !out                                                  ? "out"
                       : !spec                                               ? "spec"
                       : !spec->col[HY_TABLE_U] || !spec->col[HY_TABLE_Y]    ? "spec's u and y columns"
                       : !text && len                                        ? "text (len is not 0)"
                                                                             : NULL;
    if (null)
        return hy_error_set(err, HY_EINVAL, "hy_table_parse: %s must not be NULL", null);
    if (!text)
        text = ""; /* len 0 */
    if (!name)
        name = "data file";
    state st;
    memset(&st, 0, sizeof st);
    st.rd = (reader){name, quote, err, 1};
    st.spec = spec;
    st.t = out;
    for (int i = 0; i < HY_TABLE_NCOL; i++)
        st.want[i] = spec->col[i] != NULL;
    int rc = HY_OK;
    if (len > HY_TABLE_MAX_BYTES)
        rc = hy_error_set(err, HY_EINVAL, "%s:1:1: the file is %zu bytes, more than the %zu allowed for measured data",
                          name, len, (size_t)HY_TABLE_MAX_BYTES);
    /* header lines are kept as pointers into text: a comment's or a row's */
    for (const char *p = text, *end = text + len; !rc && p < end; st.rd.lineno++) {
        const char *nl = memchr(p, '\n', (size_t)(end - p));
        size_t ll = (size_t)((nl ? nl : end) - p);
        const char *nul = memchr(p, '\0', ll);
        if (ll && p[ll - 1] == '\r')
            ll--;
        if (nul)
            rc = fail(&st.rd, (size_t)(nul - p) + 1, "NUL byte in the line (is this a text file?)");
        else if (ll > HY_TABLE_MAX_LINE) {
            char what[80];
            snprintf(what, sizeof what, "the line is longer than %d bytes", HY_TABLE_MAX_LINE);
            rc = fail(&st.rd, HY_TABLE_MAX_LINE + 1, what);
        } else
            rc = one_line(&st, p, ll);
        p = nl ? nl + 1 : end;
    }
    if (!rc && !out->n) {
        st.rd.lineno = st.rd.lineno > 1 ? st.rd.lineno - 1 : 1;
        rc = fail(&st.rd, 1, "no data rows (the file is empty or holds only comments and a header)");
    }
    if (!rc && grow_recs(&st.g, out->nrec + 1))
        rc = hy_error_set(err, HY_ENOMEM, "%s: out of memory", name);
    out->u = st.g.v[0];
    out->y = st.g.v[1];
    out->rec = st.g.rec;
    out->line = st.g.line;
    if (st.want[HY_TABLE_T])
        out->t = st.g.v[2];
    else
        free(st.g.v[2]);
    if (rc) {
        hy_table_free(out);
        return rc;
    }
    out->rec[out->nrec] = out->n;
    return HY_OK;
}

void hy_table_free(hy_table *t)
{
    if (!t)
        return;
    free(t->u);
    free(t->y);
    free(t->t);
    free(t->rec);
    free(t->line);
    memset(t, 0, sizeof *t);
}

double hy_table_area(const double *u, const double *y, size_t n)
{
    if (n < 3)
        return 0;
    if (!u || !y)
        return NAN;
    double s = 0;
    for (size_t i = 1; i + 1 < n; i++) /* the edges from and to point 0 vanish relative to it */
        s += (u[i] - u[0]) * (y[i + 1] - y[0]) - (u[i + 1] - u[0]) * (y[i] - y[0]);
    return 0.5 * s;
}
