/* SPDX-License-Identifier: MIT */
/* hy_model.h: the Dahl and LuGre friction models (seed 000, Eqs. (1)-(3)) and
 * the system (16) of Example 1 (Dahl followed by the filter ẏ = -y + x).
 *
 * Every model is held as time-scaled LuGre parameters:
 *     ż = -σ0 |u̇| / g(u̇/γ) · z + u̇,
 *     y_γ = σ0 z + (σ1/γ) ż + f(u̇/γ),   g(v) = Fc + (Fs - Fc) e^{-|v/vs|^β},
 *     f(v) = σ2 v.
 * Dahl (ρ, Fc) is LuGre with σ0 = ρ Fc, g ≡ Fc, σ1 = σ2 = 0.  The model type
 * (a static const struct, exported by pointer) names the model and validates it.
 *
 *     hy_model m;
 *     hy_model_lugre_init(&m, 6, 1, 1, 2, 1, 1);      // σ0 σ1 Fc Fs vs β
 *     if (hy_model_validate(&m, &err)) ...
 *     double g0 = hy_model_g(&m, 0.0);
 */
#ifndef HY_MODEL_H
#define HY_MODEL_H

#include "hy_status.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct hy_model hy_model;

typedef struct hy_model_type {
    const char *name;                  /* "dahl", "lugre", "dahl-filter" */
    int has_filter;                    /* output passes ẏ = (γ/τ)(x - y) */
    int (*validate)(const hy_model *m, hy_error *err);
} hy_model_type;

extern const hy_model_type *const hy_model_dahl;
extern const hy_model_type *const hy_model_lugre;
extern const hy_model_type *const hy_model_dahl_filter;

struct hy_model {
    const hy_model_type *type;
    double sigma0, sigma1, sigma2;     /* stiffness, micro-damping, viscous  */
    double fc, fs, vs, beta;           /* g(v) = fc + (fs-fc) e^{-|v/vs|^β}  */
    double rho;                        /* Dahl's ρ (informative; σ0 = ρ Fc)  */
    double tau;                        /* filter time constant (dahl-filter) */
    double x0;                         /* initial state z(0)                 */
    double yf0;                        /* initial filter output (dahl-filter)*/
};

/* Fill m with a LuGre model; f is zero (set m->sigma2 for f(v) = σ2 v).
 * The three _init functions: m NULL, nothing done; the numbers are checked
 * by hy_model_validate, not here. */
void hy_model_lugre_init(hy_model *m, double sigma0, double sigma1, double fc,
                    double fs, double vs, double beta);
/* Fill m with a Dahl model y = Fc w, ẇ = ρ(u̇ - |u̇| w) (m NULL: nothing done). */
void hy_model_dahl_init(hy_model *m, double rho, double fc);
/* Fill m with system (16): Dahl(ρ, Fc) then ẏ = (x - y)/τ in unscaled time
 * (m NULL: nothing done). */
void hy_model_dahl_filter_init(hy_model *m, double rho, double fc, double tau);

/* Returns HY_OK, or HY_EINVAL with a message naming the bad parameter (m
 * NULL or without a type: HY_EINVAL). */
int hy_model_validate(const hy_model *m, hy_error *err);
/* Finds a model type by name; NULL when unknown or name is NULL. */
const hy_model_type *hy_model_type_find(const char *name);

/* g(v) for the model (constant for Dahl); m NULL: NaN. */
double hy_model_g(const hy_model *m, double v);
/* g(0), the only value of g the γ → ∞ limit depends on; m NULL: NaN. */
double hy_model_g0(const hy_model *m);
/* a = σ0 / g(0), the decay rate of y* per unit of input variation; m NULL:
 * NaN. */
double hy_model_a(const hy_model *m);
/* Nonzero when y_γ does not depend on γ (g constant, σ1 = σ2 = 0, no filter);
 * 0 for m NULL or without a type. */
int hy_model_rate_independent(const hy_model *m);

#ifdef __cplusplus
}
#endif

#endif
