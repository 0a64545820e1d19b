/* SPDX-License-Identifier: MIT */
/* hy_preisach_table.c: the classical Preisach model with a tabulated density
 * (a clipped FORC distribution): Everett function by cell quadrature and the
 * FORCs M(H_a, H_b) = y_s − 2E(+∞, H_a) + 2E(H_b, H_a) (docs/FORC.md, "The
 * protocol on a model" and "A Preisach density from FORCs"). */
#include "hy_preisach_table.h"

#include <math.h>
#include <stdlib.h>

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

double hy_preisach_table_everett(const hy_preisach_table *t, double a, double b)
{
    double e = 0;
    for (size_t k = 0; k < t->n; k++)
        if (t->beta[k] >= b && t->alpha[k] <= a)
            e += t->w[k];
    return e;
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
