/* SPDX-License-Identifier: MIT */
/* hy_preisach_table.c: the classical Preisach model with a tabulated density
 * (weighted relays on an (H_c, H_u) grid): Everett function by cell
 * quadrature and the FORCs M(H_a, H_b) = y_s − 2E(+∞, H_a) + 2E(H_b, H_a);
 * the density file (text rows hc,hu,mu); the least-squares density, μ >= 0,
 * of FORC data (normal equations, projected coordinate descent)
 * (docs/FORC.md, "A Preisach density from FORCs" and "The density file"). */
#include "hy_preisach_table.h"

#include <gsl/gsl_matrix.h>
#include <gsl/gsl_vector.h>

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

int hy_preisach_table_from_grid(hy_preisach_table *t, const hy_forc_grid *g, hy_error *err)
{
    t->n = t->nclipped = 0;
    t->alpha = t->beta = t->w = NULL;
    if (!g->rho || g->nc < 2 || g->nu < 2)
        return hy_error_set(err, HY_EINVAL, "Preisach table: a grid of at least 2 x 2 nodes with values is needed");
    double dc = (g->hc1 - g->hc0) / (double)(g->nc - 1), du = (g->hu1 - g->hu0) / (double)(g->nu - 1);
    size_t cap = g->nc * g->nu;
    t->alpha = malloc(cap * sizeof *t->alpha);
    t->beta = malloc(cap * sizeof *t->beta);
    t->w = malloc(cap * sizeof *t->w);
    if (!t->alpha || !t->beta || !t->w) {
        hy_preisach_table_free(t);
        return hy_error_set(err, HY_ENOMEM, "Preisach table: out of memory");
    }
    for (size_t iu = 0; iu < g->nu; iu++)
        for (size_t ic = 0; ic < g->nc; ic++) {
            double rho = g->rho[iu * g->nc + ic], hc = g->hc0 + (double)ic * dc, hu = g->hu0 + (double)iu * du;
            if (isfinite(rho) && rho < 0)
                t->nclipped++;
            if (!(rho > 0))
                continue;
            double area = 2 * dc * du * (ic == 0 && g->hc0 == 0 ? 0.5 : 1.0); /* the H_c = 0 row: half a cell */
            t->alpha[t->n] = hu + hc;
            t->beta[t->n] = hu - hc;
            t->w[t->n++] = rho * area;
        }
    return HY_OK;
}

int hy_preisach_table_forc(const hy_preisach_table *t, const hy_forc_data *d, double *m_model, double *rms,
                           double *offset, hy_error *err)
{
    if (!d->npoints)
        return hy_error_set(err, HY_EINVAL, "Preisach table: FORC data without points");
    double sum = 0;
    for (size_t i = 0; i < d->ncurves; i++) {
        const hy_forc_curve *c = &d->curve[i];
        double e_inf = hy_preisach_table_everett(t, INFINITY, c->ha);
        for (size_t j = c->first; j < c->first + c->n; j++) {
            m_model[j] = 2 * hy_preisach_table_everett(t, d->hb[j], c->ha) - 2 * e_inf;
            sum += d->m[j] - m_model[j];
        }
    }
    double c0 = sum / (double)d->npoints, ss = 0; /* least squares for the constant */
    for (size_t k = 0; k < d->npoints; k++) {
        m_model[k] += c0;
        ss += (m_model[k] - d->m[k]) * (m_model[k] - d->m[k]);
    }
    *offset = c0;
    *rms = sqrt(ss / (double)d->npoints);
    return HY_OK;
}

void hy_preisach_table_free(hy_preisach_table *t)
{
    free(t->alpha);
    free(t->beta);
    free(t->w);
    t->alpha = t->beta = t->w = NULL;
    t->n = 0;
}

/* ---- the density file ------------------------------------------------------ */

/* Node i of n from lo to hi, the last exactly hi (so the reader's first and
 * last nodes are the grid's ends, bit for bit). */
static double node_at(double lo, double hi, size_t i, size_t n)
{
    return i + 1 == n ? hi : lo + (double)i * ((hi - lo) / (double)(n - 1));
}

int hy_preisach_table_write(FILE *f, const hy_forc_grid *g, hy_error *err)
{
    fprintf(f, "# hystviz Preisach density: mu on a regular (H_c, H_u) grid, alpha = H_u + H_c, beta = H_u - H_c "
               "(docs/FORC.md)\nhc,hu,mu\n");
    for (size_t iu = 0; iu < g->nu; iu++)
        for (size_t ic = 0; ic < g->nc; ic++) {
            double mu = g->rho[iu * g->nc + ic];
            fprintf(f, "%.17g,%.17g,%.17g\n", node_at(g->hc0, g->hc1, ic, g->nc),
                    node_at(g->hu0, g->hu1, iu, g->nu), mu > 0 ? mu : 0.0);
        }
    if (fflush(f) || ferror(f))
        return hy_error_set(err, HY_EIO, "Preisach density: writing failed");
    return HY_OK;
}

typedef struct rd {
    const char *name;
    size_t line;
    hy_error *err;
} rd;

/* One field of a row: a finite decimal number at *p (at most 63 bytes; a
 * subnormal is taken as strtod rounds it, so a written value reads back),
 * then blanks, then ',' or the line's end; *p moves past it.  line: the
 * line's start, for the column in messages. */
static int field(rd *r, const char *line, const char **p, const char *end, double *v)
{
    while (*p < end && (**p == ' ' || **p == '\t'))
        ++*p;
    char buf[64];
    size_t n = 0;
    const char *s = *p;
    while (*p < end && **p != ',' && **p != ' ' && **p != '\t' && n < sizeof buf - 1)
        buf[n++] = *(*p)++;
    buf[n] = 0;
    int longer = *p < end && **p != ',' && **p != ' ' && **p != '\t';
    char *e;
    errno = 0;
    *v = n ? strtod(buf, &e) : 0;
    if (!n || longer || *e || !isfinite(*v) || (errno == ERANGE && fabs(*v) > 1) || strpbrk(buf, "xXnNiI"))
        return hy_error_set(r->err, HY_EINVAL, "%s:%zu:%zu: not a finite decimal number", r->name, r->line,
                            (size_t)(s - line) + 1);
    while (*p < end && (**p == ' ' || **p == '\t'))
        ++*p;
    if (*p < end && **p == ',')
        ++*p;
    return HY_OK;
}

/* The header line: the names hc, hu, mu separated by ',' or blanks. */
static int is_header(const char *p, const char *end)
{
    static const char *const want[] = {"hc", "hu", "mu"};
    for (size_t i = 0; i < 3; i++) {
        while (p < end && (*p == ' ' || *p == '\t' || (i && *p == ',')))
            p++;
        size_t n = strlen(want[i]);
        if ((size_t)(end - p) < n || strncmp(p, want[i], n))
            return 0;
        p += n;
        if (p < end && *p != ' ' && *p != '\t' && *p != ',')
            return 0;
    }
    while (p < end && (*p == ' ' || *p == '\t'))
        p++;
    return p == end;
}

typedef struct rows {
    double *v;    /* hc, hu, mu of each row */
    size_t *line; /* its line               */
    size_t n, cap;
} rows;

static int rows_add(rows *t, const double v[3], size_t line)
{
    if (t->n == t->cap) {
        size_t cap = t->cap ? 2 * t->cap : 256;
        double *nv = realloc(t->v, 3 * cap * sizeof *nv);
        if (nv)
            t->v = nv;
        size_t *nl = nv ? realloc(t->line, cap * sizeof *nl) : NULL;
        if (!nl)
            return HY_ENOMEM;
        t->line = nl;
        t->cap = cap;
    }
    memcpy(t->v + 3 * t->n, v, 3 * sizeof *v);
    t->line[t->n++] = line;
    return HY_OK;
}

/* The rows of the text after its header line; HY_EINVAL/HY_ENOMEM set err. */
static int read_rows(rd *r, const char *text, size_t len, rows *t)
{
    int header = 0;
    const char *p = text, *stop = text + len;
    for (r->line = 1; p < stop; r->line++) {
        const char *nl = memchr(p, '\n', (size_t)(stop - p)), *end = nl ? nl : stop, *line = p;
        if (end > p && end[-1] == '\r')
            end--;
        if (end - p > 4095)
            return hy_error_set(r->err, HY_EINVAL, "%s:%zu:4096: a line longer than 4095 bytes", r->name, r->line);
        const char *q = p;
        p = nl ? nl + 1 : stop;
        while (q < end && (*q == ' ' || *q == '\t'))
            q++;
        if (q == end || *q == '#')
            continue;
        if (!header) {
            if (!is_header(q, end))
                return hy_error_set(r->err, HY_EINVAL, "%s:%zu:1: expected the column line 'hc,hu,mu' first",
                                    r->name, r->line);
            header = 1;
            continue;
        }
        double v[3];
        for (int k = 0; k < 3; k++) {
            if (q == end)
                return hy_error_set(r->err, HY_EINVAL, "%s:%zu:%zu: a row needs 3 fields (hc, hu, mu), got %d",
                                    r->name, r->line, (size_t)(q - line) + 1, k);
            const char *at = q;
            int rc = field(r, line, &q, end, &v[k]);
            if (rc)
                return rc;
            if (k == 2 && v[2] < 0)
                return hy_error_set(r->err, HY_EINVAL, "%s:%zu:%zu: mu = %g < 0: a Preisach density is not negative",
                                    r->name, r->line, (size_t)(at - line) + 1, v[2]);
        }
        if (q != end)
            return hy_error_set(r->err, HY_EINVAL, "%s:%zu:%zu: text after the 3 fields hc, hu, mu", r->name,
                                r->line, (size_t)(q - line) + 1);
        if (t->n == HY_PREISACH_TABLE_MAX_NODES)
            return hy_error_set(r->err, HY_EINVAL, "%s:%zu:1: more than %zu nodes", r->name, r->line,
                                HY_PREISACH_TABLE_MAX_NODES);
        if (rows_add(t, v, r->line))
            return hy_error_set(r->err, HY_ENOMEM, "out of memory");
    }
    if (!header)
        return hy_error_set(r->err, HY_EINVAL, "%s:%zu:1: no column line 'hc,hu,mu' (empty file?)", r->name,
                            r->line > 1 ? r->line - 1 : 1);
    return HY_OK;
}

/* Whether x is value within tol. */
static int near(double x, double value, double tol) { return fabs(x - value) <= tol; }

/* The rows as a regular grid: nc from the first run of equal H_u, each row
 * checked in order (H_c ascending from >= 0, the same H_c in every run, one
 * H_u per run, runs equally spaced). */
static int to_grid(rd *r, const rows *t, hy_forc_grid *g)
{
    const double *v = t->v;
    size_t nc = 1, last = t->n ? t->line[t->n - 1] : r->line;
    while (nc < t->n && v[3 * nc + 1] == v[1])
        nc++;
    if (t->n < 4 || nc < 2 || t->n / nc < 2)
        return hy_error_set(r->err, HY_EINVAL, "%s:%zu:1: a density grid needs at least 2 nodes along H_c and 2 "
                            "along H_u (got %zu rows, %zu per H_u)", r->name, last, t->n, nc);
    if (t->n % nc)
        return hy_error_set(r->err, HY_EINVAL, "%s:%zu:1: %zu rows are not whole runs of %zu nodes along H_c "
                            "(truncated?)", r->name, last, t->n, nc);
    size_t nu = t->n / nc;
    double hc0 = v[0], hc1 = v[3 * (nc - 1)], hu0 = v[1], hu1 = v[3 * (t->n - 1) + 1];
    double dc = (hc1 - hc0) / (double)(nc - 1), du = (hu1 - hu0) / (double)(nu - 1);
    if (hc0 < 0)
        return hy_error_set(r->err, HY_EINVAL, "%s:%zu:1: H_c = %g < 0 (alpha below beta is no relay)", r->name,
                            t->line[0], hc0);
    for (size_t k = 1; k < t->n; k++) {
        size_t ic = k % nc, iu = k / nc;
        double hc = v[3 * k], hu = v[3 * k + 1];
        if (!(dc > 0) || !near(hc, node_at(hc0, hc1, ic, nc), 1e-6 * dc))
            return hy_error_set(r->err, HY_EINVAL, "%s:%zu:1: H_c = %.10g is not node %zu of the first run's regular "
                                "H_c grid (%g to %g, %zu nodes)", r->name, t->line[k], hc, ic, hc0, hc1, nc);
        if (!(du > 0) || !near(hu, node_at(hu0, hu1, iu, nu), 1e-6 * du) || (ic && hu != v[3 * k - 2]))
            return hy_error_set(r->err, HY_EINVAL, "%s:%zu:1: H_u = %.10g is not node %zu of a regular ascending H_u "
                                "grid (%g to %g, %zu nodes; one H_u per run of %zu rows)", r->name, t->line[k], hu,
                                iu, hu0, hu1, nu, nc);
    }
    if (!(g->rho = malloc(t->n * sizeof *g->rho)))
        return hy_error_set(r->err, HY_ENOMEM, "out of memory");
    for (size_t k = 0; k < t->n; k++)
        g->rho[k] = v[3 * k + 2];
    g->hc0 = hc0, g->hc1 = hc1, g->hu0 = hu0, g->hu1 = hu1, g->nc = nc, g->nu = nu;
    return HY_OK;
}

int hy_preisach_table_read(const char *text, size_t len, const char *name, hy_forc_grid *g, hy_error *err)
{
    rd r = {name, 1, err};
    rows t = {NULL, NULL, 0, 0};
    g->rho = NULL;
    int rc = read_rows(&r, text, len, &t);
    if (!rc)
        rc = to_grid(&r, &t, g);
    free(t.v);
    free(t.line);
    return rc;
}

/* ---- least squares of the density to FORC data ------------------------------- */

#define FIT_TOL 1e-9      /* coordinate descent stops when no x moves more (relative) */
#define FIT_SWEEPS 20000  /* or after this many sweeps                                */
#define FIT_RIDGE 1e-9    /* added to the normal equations' diagonal, relative         */

/* G = AᵀA and Aᵀy of the scaled problem: row k of A has −2 at the relays
 * with β_j >= H_a and α_j > H_b (switched down at H_a, not yet back up at
 * H_b) and 1 at the offset. */
static void normal_eqs(const hy_forc_data *d, const double *alpha, const double *beta, size_t m, double R,
                       gsl_matrix *G, gsl_vector *b, size_t *idx)
{
    size_t n = m + 1;
    for (size_t i = 0; i < d->ncurves; i++) {
        const hy_forc_curve *cv = &d->curve[i];
        for (size_t k = cv->first; k < cv->first + cv->n; k++) {
            size_t nz = 0;
            for (size_t j = 0; j < m; j++)
                if (beta[j] >= cv->ha && alpha[j] > d->hb[k])
                    idx[nz++] = j;
            double y = d->m[k] / R;
            for (size_t a = 0; a < nz; a++) {
                double *row = gsl_matrix_ptr(G, idx[a], 0);
                for (size_t e = 0; e <= a; e++)
                    row[idx[e]] += 4;
                row[m] -= 2;
                *gsl_vector_ptr(b, idx[a]) -= 2 * y;
            }
            *gsl_matrix_ptr(G, m, m) += 1;
            *gsl_vector_ptr(b, m) += y;
        }
    }
    for (size_t a = 0; a < n; a++) /* the lower triangle was summed: mirror it */
        for (size_t e = 0; e < a; e++) {
            double v = gsl_matrix_get(G, a, e) + gsl_matrix_get(G, e, a); /* one of the two is 0 */
            gsl_matrix_set(G, a, e, v);
            gsl_matrix_set(G, e, a, v);
        }
}

/* min ½ xᵀGx − bᵀx over x_j >= 0 (j < n − 1; the last, the offset, free) by
 * cyclic coordinate descent, keeping the gradient g = Gx − b: each step
 * minimises exactly along one coordinate and projects.  Stops when no
 * coordinate moves by more than tol (relative to the largest x) in a sweep,
 * or after max sweeps; *sweeps gets their number. */
static int nnls_cd(const gsl_matrix *G, const gsl_vector *b, double *x, size_t n, double tol, size_t max,
                   size_t *sweeps)
{
    double *g = malloc(n * sizeof *g);
    if (!g)
        return HY_ENOMEM;
    for (size_t i = 0; i < n; i++) {
        double s = -gsl_vector_get(b, i);
        for (size_t k = 0; k < n; k++)
            s += gsl_matrix_get(G, i, k) * x[k];
        g[i] = s;
    }
    size_t it = 0;
    for (; it < max; it++) {
        double moved = 0, big = 0;
        for (size_t j = 0; j < n; j++) {
            double xj = x[j] - g[j] / gsl_matrix_get(G, j, j);
            if (j + 1 < n && xj < 0)
                xj = 0;
            double dx = xj - x[j];
            if (dx != 0) {
                const double *col = gsl_matrix_const_ptr(G, j, 0); /* G is symmetric: row j is column j */
                for (size_t k = 0; k < n; k++)
                    g[k] += col[k] * dx;
                x[j] = xj;
            }
            moved = fmax(moved, fabs(dx));
            big = fmax(big, fabs(x[j]));
        }
        if (moved <= tol * big)
            break;
    }
    *sweeps = it + 1 < max ? it + 1 : max;
    free(g);
    return HY_OK;
}

void hy_preisach_table_fit_shape(const hy_forc_grid *g, size_t *nc, size_t *nu)
{
    double s = sqrt((double)HY_PREISACH_TABLE_FIT_NODES / (double)(g->nc * g->nu));
    *nc = s < 1 ? (size_t)fmax(2, floor(s * (double)g->nc)) : g->nc;
    *nu = s < 1 ? (size_t)fmax(2, floor(s * (double)g->nu)) : g->nu;
}

int hy_preisach_table_fit(const hy_forc_data *d, const hy_forc_grid *shape, size_t nc, size_t nu,
                          hy_preisach_table_fitres *res, hy_error *err)
{
    memset(res, 0, sizeof *res);
    if (!d->npoints || nc < 2 || nu < 2 || nc * nu > 4000 || !(shape->hc1 > shape->hc0) || !(shape->hu1 > shape->hu0))
        return hy_error_set(err, HY_EINVAL, "Preisach density fit: data without points or a bad grid (%zu x %zu)",
                            nc, nu);
    size_t m = nc * nu, n = m + 1;
    double lo = INFINITY, hi = -INFINITY, mean = 0;
    for (size_t k = 0; k < d->npoints; k++)
        lo = fmin(lo, d->m[k]), hi = fmax(hi, d->m[k]), mean += d->m[k] / (double)d->npoints;
    double R = hi > lo ? hi - lo : 1;
    hy_forc_grid g = {shape->hc0, shape->hc1, shape->hu0, shape->hu1, nc, nu, NULL};
    double *alpha = malloc(m * sizeof *alpha), *beta = malloc(m * sizeof *beta), *area = malloc(m * sizeof *area);
    size_t *idx = malloc(m * sizeof *idx);
    gsl_matrix *G = gsl_matrix_calloc(n, n);
    gsl_vector *b = gsl_vector_calloc(n);
    double *x = malloc(n * sizeof *x);
    g.rho = malloc(m * sizeof *g.rho);
    int rc = alpha && beta && area && idx && G && b && x && g.rho ? HY_OK
                                                                   : hy_error_set(err, HY_ENOMEM, "out of memory");
    double dc = (g.hc1 - g.hc0) / (double)(nc - 1), du = (g.hu1 - g.hu0) / (double)(nu - 1);
    for (size_t j = 0; !rc && j < m; j++) { /* the nodes as hy_preisach_table_from_grid places them */
        size_t ic = j % nc, iu = j / nc;
        double hc = g.hc0 + (double)ic * dc, hu = g.hu0 + (double)iu * du;
        alpha[j] = hu + hc;
        beta[j] = hu - hc;
        area[j] = 2 * dc * du * (ic == 0 && g.hc0 == 0 ? 0.5 : 1.0);
    }
    if (!rc) {
        normal_eqs(d, alpha, beta, m, R, G, b, idx);
        size_t seen = 0;
        for (size_t j = 0; j < m; j++)
            seen += gsl_matrix_get(G, j, j) > 0;
        for (size_t j = 0; j < n; j++) {
            double *gjj = gsl_matrix_ptr(G, j, j);
            /* start: the range of M spread over the relays the data see; a relay no point
               switches has a zero column: a unit diagonal keeps it at 0 */
            x[j] = j == m ? mean / R + 0.5 : *gjj > 0 ? 0.5 / (double)seen : 0;
            *gjj = *gjj > 0 ? *gjj * (1 + FIT_RIDGE) : 1;
        }
        res->nfree = seen + 1;
        if (nnls_cd(G, b, x, n, FIT_TOL, FIT_SWEEPS, &res->iters))
            rc = hy_error_set(err, HY_ENOMEM, "out of memory");
    }
    for (size_t j = 0; !rc && j < m; j++)
        g.rho[j] = x[j] * R / area[j];
    if (!rc) {
        hy_preisach_table t;
        double *mm = malloc(d->npoints * sizeof *mm);
        rc = mm ? hy_preisach_table_from_grid(&t, &g, err) : hy_error_set(err, HY_ENOMEM, "out of memory");
        if (!rc) {
            rc = hy_preisach_table_forc(&t, d, mm, &res->rms, &res->offset, err);
            hy_preisach_table_free(&t);
        }
        free(mm);
    }
    if (!rc) {
        res->g = g;
        g.rho = NULL;
    }
    free(g.rho);
    free(alpha);
    free(beta);
    free(area);
    free(idx);
    gsl_matrix_free(G);
    gsl_vector_free(b);
    free(x);
    return rc;
}
