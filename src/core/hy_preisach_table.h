/* SPDX-License-Identifier: MIT */
/* hy_preisach_table.h: a classical Preisach model whose density is tabulated
 * on an (H_c, H_u) grid, e.g. a FORC distribution (hy_forc.h): for the
 * Preisach model ρ(H_a, H_b) = μ(α = H_b, β = H_a), so a measured ρ, clipped
 * to ρ >= 0 (a Preisach density is not negative) with NaN nodes as 0, is a
 * density, and the model it defines predicts the FORCs it came from
 * (docs/FORC.md, "A Preisach density from FORCs").
 *
 *     hy_preisach_table t;
 *     hy_preisach_table_from_grid(&t, &grid, &err);     // μ = max(ρ, 0)
 *     hy_preisach_table_forc(&t, &data, m_model, &rms, &offset, &err);
 *     hy_preisach_table_free(&t);
 *
 * Quadrature: node (i_c, i_u) stands for its cell, of area 2 ΔH_c ΔH_u in
 * (α, β) (α = H_u + H_c, β = H_u − H_c), half that on the H_c = 0 row; the
 * Everett function E(a, b) = ∫∫_{b <= β <= α <= a} μ is the sum over the
 * nodes inside.  The existing analytic densities (hy_preisach.h) are not
 * touched.
 */
#ifndef HY_PREISACH_TABLE_H
#define HY_PREISACH_TABLE_H

#include <stddef.h>

#include "hy_forc.h"
#include "hy_status.h"

typedef struct hy_preisach_table {
    size_t n;              /* nodes with μ > 0                          */
    double *alpha, *beta;  /* their switching fields α = H_b, β = H_a   */
    double *w;             /* μ times the cell's area in (α, β)          */
    size_t nclipped;       /* finite nodes with ρ < 0 set to 0           */
} hy_preisach_table;

/* μ = max(ρ, 0) on the grid's nodes (NaN: 0).  HY_EINVAL for a grid without
 * values or with fewer than 2 nodes a side, HY_ENOMEM. */
int hy_preisach_table_from_grid(hy_preisach_table *t, const hy_forc_grid *g, hy_error *err);

/* E(a, b): the weight of the nodes with b <= β and α <= a (0 when a <= b). */
double hy_preisach_table_everett(const hy_preisach_table *t, double a, double b);

/* The model's FORCs at the data's points: M(H_a, H_b) = c + 2 E(H_b, H_a) −
 * 2 E(+∞, H_a) (from positive saturation, docs/FORC.md), the constant c
 * (the output at positive saturation) by least squares over all points;
 * m_model[k] for the data's point k (the caller's array of d->npoints),
 * *rms = sqrt(mean (M_model − M)²) over all points, *offset = c.
 * HY_EINVAL for data without points. */
int hy_preisach_table_forc(const hy_preisach_table *t, const hy_forc_data *d, double *m_model, double *rms,
                           double *offset, hy_error *err);

void hy_preisach_table_free(hy_preisach_table *t);

#endif
