/* SPDX-License-Identifier: MIT */
/* hy_forc.h: first-order reversal curves (FORC): a data set of curves, the
 * readers of measured files (MicroMag 2900/3900 text, plain CSV), drift
 * correction, the FORC protocol on a rate-independent model, and the FORC
 * distribution
 *     ρ(H_a, H_b) = −½ ∂²M/∂H_a∂H_b
 * by local second-order polynomial regression (Pike, Roberts & Verosub 1999)
 * on a grid of H_c = (H_b − H_a)/2, H_u = (H_a + H_b)/2.  docs/FORC.md says
 * exactly what is computed.  Numbers only: text in, structs out, no files.
 *
 *     hy_forc_data d;  hy_forc_grid g;  hy_error err;
 *     if (hy_forc_read(&d, text, len, "sample.forc", &err)) ...   // file:line:col: ...
 *     hy_forc_opts o = hy_forc_defaults();                        // SF = 3, extension on
 *     hy_forc_grid_auto(&d, &o, &g);                              // the data's (H_c, H_u) box
 *     if (hy_forc_rho(&d, &o, &g, &err)) ...                      // g.rho[iu * g.nc + ic]
 *     hy_forc_grid_free(&g); hy_forc_data_free(&d);
 *
 * A curve i holds its reversal field H_a and points (H_b, M) with H_b
 * strictly ascending; curves are kept in the order read (a MicroMag file's
 * H_a decreases).  Every point of a measured file counts: fields need not lie
 * on a regular grid.  Errors: HY_EINVAL with "name:line:col: what" for
 * a refused file, HY_ENOMEM, HY_ENUM.  hy_forc_data and hy_forc_grid own
 * their arrays (free them with their _free, also after a failed call).
 *
 * Pointers: err may always be NULL (no message).  A pointer each function
 * below says must not be NULL gives HY_EINVAL and the message "FUNCTION: X
 * must not be NULL" (a void function: nothing done), never a crash.
 */
#ifndef HY_FORC_H
#define HY_FORC_H

#include <stddef.h>
#include "hy_preisach.h"
#include "hy_rateind.h"
#include "hy_status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Caps on a file (untrusted input): more is refused naming the cap. */
#define HY_FORC_MAX_CURVES 100000u   /* curves in one file                 */
#define HY_FORC_MAX_POINTS 4000000u  /* points (H_b, M) in all curves      */
#define HY_FORC_MAX_LINE 4096u       /* bytes in one line                  */

/* Units of a file: MicroMag's "Units of measure". */
enum { HY_FORC_UNITS_NONE = 0, HY_FORC_UNITS_HYBRID_SI, HY_FORC_UNITS_SI, HY_FORC_UNITS_CGS };

typedef struct hy_forc_curve {
    double ha;          /* reversal field H_a                                   */
    size_t first, n;    /* its points are hb[first .. first+n), m[...] of the set */
    double cal_h, cal_m;/* calibration point measured before it (NaN: none)     */
    size_t line;        /* line of its first point in the file (0: not read)    */
} hy_forc_curve;

typedef struct hy_forc_data {
    hy_forc_curve *curve;
    size_t ncurves;
    double *hb, *m;           /* every curve's points, curve after curve        */
    size_t npoints;
    int units;                /* HY_FORC_UNITS_*                                */
    const char *field_unit;   /* "T" (μ0H), "A/m", "Oe", "" (static strings)    */
    const char *moment_unit;  /* "A m2", "emu", ""                              */
    double field_to_tesla;    /* μ0H in T per field unit (NaN when unknown)     */
    /* header fields of a MicroMag file (NaN / 0 when absent or N/A) */
    double hsat, hcal, hncr;
    long ncrv, ndata;
    size_t ncal;              /* curves with a calibration point               */
} hy_forc_data;

/* Reads a MicroMag 2900/3900 FORC text file (name is for messages only):
 * line 1 "MicroMag 2900/3900 Data File ...", header lines (`Key = value`,
 * `Key : value` or `Key  value`), then groups of "field,moment" lines
 * separated by blank lines; a one-point group at the calibration field
 * (header HCal) is the calibration point of the next curve; each curve's
 * first point is its reversal field.  LF or CRLF.  A column header
 * ("Field ... Moment") and a units line in parentheses before the data are
 * skipped.  Refused (HY_EINVAL, "name:line:col: ..."): a first line
 * that is not MicroMag's, a header value of NCrv/NData/HCal/HNcr/HSat that
 * is not a number or N/A, unknown units, a data line that is not two finite
 * numbers, a curve whose fields do not ascend, fewer (or more) curves than
 * NCrv or data lines than NData, a missing end line when neither count is
 * given, and anything past the caps above.
 * Pointers (the three readers): d must not be NULL; text may be NULL only
 * when len is 0; name may be NULL ("FORC file"). */
int hy_forc_read_micromag(hy_forc_data *d, const char *text, size_t len, const char *name, hy_error *err);

/* Reads CSV rows "H_a,H_b,M" (comma, semicolon, tab or spaces between; a
 * first line of column names and lines starting with '#' skipped).  Rows
 * with the same H_a in a row form one curve, H_b ascending.  Units none. */
int hy_forc_read_csv(hy_forc_data *d, const char *text, size_t len, const char *name, hy_error *err);

/* A MicroMag file when the text starts with "MicroMag", else CSV. */
int hy_forc_read(hy_forc_data *d, const char *text, size_t len, const char *name, hy_error *err);

/* A data set from arrays: curve i has reversal field ha[i] and n[i] points
 * hb[..], m[..] (all curves' points one after the other), no calibration.
 * d, ha, n, hb and m must not be NULL. */
int hy_forc_data_set(hy_forc_data *d, size_t ncurves, const double *ha, const size_t *n, const double *hb,
                     const double *m, hy_error *err);

/* Frees d's curves and points and zeroes it (d may be NULL; a second call is
 * harmless). */
void hy_forc_data_free(hy_forc_data *d);

/* Drift correction: multiplies every curve's M by cal_m(first curve) /
 * cal_m(curve).  HY_EINVAL when a curve has no calibration point or one is
 * not positive in magnitude (the ratio would be meaningless).  d must not be
 * NULL. */
int hy_forc_drift(hy_forc_data *d, hy_error *err);

/* The typical field steps of the data: median spacing of H_b within curves
 * (*db) and of the sorted distinct H_a (*da); 0 when there are none.  d may
 * be NULL (no data: both 0); da and db may be NULL (not written). */
void hy_forc_steps(const hy_forc_data *d, double *da, double *db);

/* ---- the distribution ---------------------------------------------------- */

typedef struct hy_forc_opts {
    double sf;     /* smoothing factor SF >= 1: the neighbourhood of a node is the
                    * points with |H_a − H_a0| <= (SF + ½) Δ_a and |H_b − H_b0| <=
                    * (SF + ½) Δ_b, i.e. (2 SF + 1)² points on a regular grid   */
    double sc0, sc1, ramp; /* variable smoothing when sc1 > 0: SF(H_c) = sc0 +
                    * (sc1 − sc0) min(1, H_c / ramp) (ramp <= 0: the grid's
                    * largest H_c); sf is then unused                           */
    int extend;    /* 1: M(H_a, H_b) = M(H_a, H_a) for H_b < H_a (constant
                    * extension, Pike 2003), so H_c = 0 has a neighbourhood     */
    double da, db; /* field steps Δ_a, Δ_b (<= 0: hy_forc_steps)               */
} hy_forc_opts;

/* SF = 3, no variable smoothing, extension on, steps from the data. */
hy_forc_opts hy_forc_defaults(void);

/* ρ on nc × nu nodes: H_c = hc0 + i (hc1 − hc0)/(nc − 1), H_u likewise;
 * rho[iu * nc + ic], NaN where the node lies outside the data or its
 * neighbourhood cannot fit the six coefficients. */
typedef struct hy_forc_grid {
    double hc0, hc1, hu0, hu1;
    size_t nc, nu;
    double *rho;        /* owned; filled by hy_forc_rho */
} hy_forc_grid;

/* The grid over the data's H_c >= 0 and H_u ranges, one node per field step
 * (at most 1000 a side); rho NULL.  d may be NULL (no data: a 2 x 2 grid at
 * 0 with step 1), o may be NULL (hy_forc_defaults); g NULL: nothing done. */
void hy_forc_grid_auto(const hy_forc_data *d, const hy_forc_opts *o, hy_forc_grid *g);

/* Fills g->rho (allocated here).  HY_EINVAL for bad options or a grid with
 * fewer than 1 or more than 4e6 nodes, data with fewer than 2 curves;
 * HY_ENOMEM.  Also reports the fitted nodes in *nfit (may be NULL).  d, o
 * and g must not be NULL. */
int hy_forc_rho(const hy_forc_data *d, const hy_forc_opts *o, hy_forc_grid *g, size_t *nfit, hy_error *err);

/* Frees g->rho (g may be NULL; a second call is harmless). */
void hy_forc_grid_free(hy_forc_grid *g);

/* ---- the protocol on a model ---------------------------------------------- */

/* Curves at H_a = ha_hi − i Δ (i = 0 .. ncurves−1, Δ = (ha_hi − ha_lo)/(ncurves − 1)),
 * each from H_b = H_a up to hb_max in steps of Δ (the last point at hb_max or
 * below), each after saturation at hsat: the model is moved to hsat, down to
 * H_a, then up through the H_b. */
typedef struct hy_forc_protocol {
    double hsat, ha_lo, ha_hi, hb_max;
    size_t ncurves;
} hy_forc_protocol;

/* Runs the protocol on any rate-independent model through fn (hy_rateind.h:
 * moves the model in ctx monotonically to u and gives its output) into d.
 * d, pr and fn must not be NULL; ctx may be NULL (handed to fn as it is). */
int hy_forc_protocol_run(hy_forc_data *d, const hy_forc_protocol *pr, hy_rateind_fn fn, void *ctx,
                         hy_error *err);

/* The protocol on the classical Preisach model p (hy_preisach_mem from
 * saturation at hsat): M(H_a, H_b) = y_s − 2E(+∞, H_a) + 2E(H_b, H_a), whose
 * FORC distribution is the density μ(α = H_b, β = H_a).  d, pr and p must
 * not be NULL. */
int hy_forc_preisach(hy_forc_data *d, const hy_forc_protocol *pr, const hy_preisach *p, hy_error *err);

#ifdef __cplusplus
}
#endif

#endif
