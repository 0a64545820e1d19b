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
 * A density file (hy_preisach_table_write / _read; docs/FORC.md, "The
 * density file") holds μ on the grid as text: '#' comment lines, the line
 * `hc,hu,mu`, then one row `H_c,H_u,μ` per node, H_u outer and ascending,
 * H_c inner and ascending, on a regular grid; every μ finite and >= 0.
 * [model] kind = preisach with pr_file = "FILE" runs the model it defines
 * in any scene (src/pipeline/model_preisach.c).
 *
 * hy_preisach_table_fit finds μ >= 0 on a coarser grid by least squares of
 * the model's FORCs to the data: the model is linear in the relays'
 * weights, so the normal equations (GSL matrices) are formed once and
 * minimised over μ >= 0 by cyclic coordinate descent (exact along each
 * coordinate, projected).  GSL multifit_nlinear over μ = θ² reached the
 * same minimum on the measured file but in 500 trust-region iterations
 * (39 s of CPU for 296 parameters); the descent takes about 0.5 s.
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
#include <stdio.h>

#include "hy_forc.h"
#include "hy_preisach.h"
#include "hy_status.h"


/* μ = max(ρ, 0) on the grid's nodes (NaN: 0).  HY_EINVAL for a grid without
 * values or with fewer than 2 nodes a side, HY_ENOMEM. */
int hy_preisach_table_from_grid(hy_preisach_table *t, const hy_forc_grid *g, hy_error *err);


/* The model's FORCs at the data's points: M(H_a, H_b) = c + 2 E(H_b, H_a) −
 * 2 E(+∞, H_a) (from positive saturation, docs/FORC.md), the constant c
 * (the output at positive saturation) by least squares over all points;
 * m_model[k] for the data's point k (the caller's array of d->npoints),
 * *rms = sqrt(mean (M_model − M)²) over all points, *offset = c.
 * HY_EINVAL for data without points. */
int hy_preisach_table_forc(const hy_preisach_table *t, const hy_forc_data *d, double *m_model, double *rms,
                           double *offset, hy_error *err);



void hy_preisach_table_free(hy_preisach_table *t);

/* Caps of a density file: bytes, and nodes (as a FORC grid, hy_forc.h). */
#define HY_PREISACH_TABLE_MAX_BYTES ((size_t)64 << 20)
#define HY_PREISACH_TABLE_MAX_NODES ((size_t)4000000)

/* Writes g (rho: μ >= 0 or NaN, written as 0) to f in the density file's
 * format, %.17g (read back bit for bit).  HY_EIO when writing fails. */
int hy_preisach_table_write(FILE *f, const hy_forc_grid *g, hy_error *err);

/* Reads a density file's text[0..len) (name for messages) into g (rho
 * allocated here; caller frees with free(g->rho)).  Refused (HY_EINVAL,
 * "name:line:col: what"): no `hc,hu,mu` line, a field that is not a finite
 * decimal number, a row without 3 fields or with text after them, μ < 0,
 * nodes not on a regular grid in the order above, fewer than 2 nodes a
 * side, more than HY_PREISACH_TABLE_MAX_NODES, a line over 4095 bytes.  On
 * error g owns nothing. */
int hy_preisach_table_read(const char *text, size_t len, const char *name, hy_forc_grid *g, hy_error *err);

/* The fit's result: the density on the fit grid, how it was reached. */
typedef struct hy_preisach_table_fitres {
    hy_forc_grid g;      /* μ >= 0 on the fit grid (g.rho owned)              */
    double offset;       /* the output at positive saturation (fitted)        */
    double rms;          /* RMS of M_model − M over all points                */
    size_t nfree;        /* free parameters: the nodes the data see, + offset  */
    size_t iters;        /* coordinate-descent sweeps                          */
} hy_preisach_table_fitres;

/* The fit grid for a distribution's grid g: g's ranges with at most
 * HY_PREISACH_TABLE_FIT_NODES nodes, g's node counts scaled by one factor
 * (at least 2 a side). */
#define HY_PREISACH_TABLE_FIT_NODES 400
void hy_preisach_table_fit_shape(const hy_forc_grid *g, size_t *nc, size_t *nu);

/* Least squares of a tabulated density to FORC data d: μ >= 0 (μ = θ²) on
 * the grid over shape's ranges with nc x nu nodes (each >= 2), and the
 * offset, minimising Σ (M_model − M)² over all points (M_model as
 * hy_preisach_table_forc).  A node whose relay no point switches is 0.
 * The normal equations carry a ridge of 1e-9 of their diagonal.
 * HY_EINVAL for data without points or a bad grid, HY_ENUM when GSL
 * fails, HY_ENOMEM.  Free the result with free(res->g.rho). */
int hy_preisach_table_fit(const hy_forc_data *d, const hy_forc_grid *shape, size_t nc, size_t nu,
                          hy_preisach_table_fitres *res, hy_error *err);

#endif
