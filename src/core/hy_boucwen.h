/* SPDX-License-Identifier: MIT */
/* hy_boucwen.h: the Bouc-Wen oscillator of the nonlinear benchmark and its
 * Newmark integrator (seeds/001, Eqs. (1)-(5), Tables 1-2).
 *
 *     m ÿ + c ẏ + k y + z = u,
 *     ż = α ẏ − β (γ |ẏ| |z|^(ν−1) z + δ ẏ |z|^ν).
 *
 * Fill a hy_boucwen_params with hy_boucwen_params_default() (Table 1), change
 * what you need (by field or by name with hy_boucwen_params_set()), then
 * integrate a force sampled every h seconds:
 *
 *     hy_boucwen_params p;  hy_newmark_opts o;  hy_error err;
 *     hy_boucwen_params_default(&p);
 *     hy_newmark_opts_default(&o);
 *     if (hy_boucwen_simulate(&p, &o, 1.0 / 15000, u, n, NULL, y, NULL, &err))
 *         fprintf(stderr, "%s\n", err.msg);
 *
 * hy_boucwen_synth() adds the benchmark's pipeline around it: integrate at the
 * upsampled rate, then decimate back with MATLAB decimate(y, r, 'fir').
 * Nothing here allocates global state; every call is reentrant.
 */
#ifndef HY_BOUCWEN_H
#define HY_BOUCWEN_H

#include "hy_cancel.h"
#include "hy_status.h"

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Physical parameters, SI units (Table 1 of the benchmark by default). */
typedef struct hy_boucwen_params {
    double m;     /* mass m_L, kg                 (> 0)   */
    double c;     /* viscous damping c_L, N s/m   (>= 0)  */
    double k;     /* linear stiffness k_L, N/m    (>= 0)  */
    double alpha; /* α, N/m                       (>= 0)  */
    double beta;  /* β, 1/m^ν (0: linear system)  (>= 0)  */
    double gamma; /* γ                            (finite) */
    double delta; /* δ                            (finite) */
    double nu;    /* ν, may be non-integer        (> 0)   */
} hy_boucwen_params;

/* Linear modal parameters of Table 2 (linearised stiffness k + α). */
typedef struct hy_boucwen_modal {
    double f0_hz; /* natural frequency sqrt((k+α)/m) / 2π, Hz */
    double zeta;  /* damping ratio c / (2 sqrt((k+α) m)), a fraction (0.0112) */
} hy_boucwen_modal;

/* Newmark constants of Eqs. (4)-(5) and the Newton-Raphson stopping rule. */
typedef struct hy_newmark_opts {
    double a, b, c; /* 0.5, 0.25, 0.5 in the benchmark                     */
    double tol;     /* relative size of the last Newton update to stop at
                       (plus a floor of 4 ulps of each equation's terms)   */
    int max_iter;   /* Newton iterations allowed per step                  */
    const hy_cancel *cancel; /* asked every HY_NEWMARK_CANCEL_STEPS steps;
                                stop: HY_ECANCEL, the samples so far written
                                (NULL: never; hy_cancel.h)                 */
} hy_newmark_opts;

/* Newmark steps between two questions to hy_newmark_opts.cancel. */
#define HY_NEWMARK_CANCEL_STEPS 8192

/* State at one time instant: displacement, velocity, acceleration, z, ż. */
typedef struct hy_boucwen_state {
    double t, y, v, a, z, zd;
} hy_boucwen_state;

/* Sets p to Table 1: m 2, c 10, k 5e4, α 5e4, β 1e3, γ 0.8, δ -1.1, ν 1
 * (p NULL: nothing done). */
void hy_boucwen_params_default(hy_boucwen_params *p);

/* Checks every parameter is finite and in its domain (m > 0; c, k, α, β >= 0;
 * ν > 0; k + α > 0).  Returns HY_EINVAL with a message naming the parameter
 * (p must not be NULL: HY_EINVAL). */
int hy_boucwen_params_validate(const hy_boucwen_params *p, hy_error *err);

/* Sets the parameter called name ("m", "c", "k", "alpha", "beta", "gamma",
 * "delta", "nu") to value.  Unknown name: HY_EINVAL, p untouched.  The value
 * is not range-checked here (call hy_boucwen_params_validate).  p and name
 * must not be NULL (HY_EINVAL). */
int hy_boucwen_params_set(hy_boucwen_params *p, const char *name, double value,
                          hy_error *err);

/* Parses "name=value" and sets it; a malformed pair or value is HY_EINVAL, as
 * are p or assignment NULL. */
int hy_boucwen_params_parse(hy_boucwen_params *p, const char *assignment,
                            hy_error *err);

/* Table 2 from the parameters; validates them first.  p and out must not be
 * NULL (HY_EINVAL). */
int hy_boucwen_table2(const hy_boucwen_params *p, hy_boucwen_modal *out,
                      hy_error *err);

/* Sets o to the benchmark's a = 0.5, b = 0.25, c = 0.5, tol 1e-12, 50 its
 * (o NULL: nothing done). */
void hy_newmark_opts_default(hy_newmark_opts *o);

/* Checks the Newmark constants (finite, a, c in (0, 1], b in (0, 0.5],
 * tol in (0, 1e-3], max_iter >= 1).  HY_EINVAL names the bad field (o must
 * not be NULL: HY_EINVAL). */
int hy_newmark_opts_validate(const hy_newmark_opts *o, hy_error *err);

/* Initial state from y(0), ẏ(0), z(0) and the force u(0): ÿ(0) from Eq. (1),
 * ż(0) from Eq. (3).  Parameters are not validated here.  p or s NULL:
 * nothing done. */
void hy_boucwen_state_init(const hy_boucwen_params *p, double u0, double y0,
                           double v0, double z0, hy_boucwen_state *s);

/* One Newmark step of size h to force u1: predictor with ÿ = ż = 0 at t + h,
 * then Newton-Raphson on Eqs. (1) and (3).  On failure (no convergence,
 * non-finite value) returns HY_ENUM with the time and residual, and leaves s
 * at the last good step.  Parameters and opts are not validated here; p, o
 * and s must not be NULL (HY_EINVAL). */
int hy_boucwen_step(const hy_boucwen_params *p, const hy_newmark_opts *o,
                    double h, double u1, hy_boucwen_state *s, hy_error *err);

/* Integrates n samples of u (u[i] at t = i h) from ic = {y0, ẏ0, z0} (NULL:
 * zeros) and writes y[i] (and z[i] if z is not NULL), n >= 1.  Validates p, o
 * and h.  On error y and z hold the samples computed so far.  p, o, u and y
 * must not be NULL (HY_EINVAL); ic and z may be. */
int hy_boucwen_simulate(const hy_boucwen_params *p, const hy_newmark_opts *o,
                        double h, const double *u, size_t n, const double *ic,
                        double *y, double *z, hy_error *err);

/* The benchmark's synthesis: integrates u_int (n_int samples at fs * r Hz)
 * from zero initial conditions, then decimates by r with MATLAB
 * decimate(y, r, 'fir') semantics, in prime-factor stages if staged != 0.
 * Writes ceil(n_int / r) samples to y_out (sample k aligned with u_int[r k]).
 * p, o, u_int and y_out must not be NULL (HY_EINVAL). */
int hy_boucwen_synth(const hy_boucwen_params *p, const hy_newmark_opts *o,
                     double fs, size_t r, int staged, const double *u_int,
                     size_t n_int, double *y_out, hy_error *err);

/* Periodic synthesis with the benchmark's edge handling: integrates
 * periods + 1 periods of u_period (n_period samples at fs * r Hz, n_period a
 * multiple of r), decimates, drops the extra last period and writes
 * periods * n_period / r samples (the first period still holds the transient).
 * p, o, u_period and y_out must not be NULL, and a record too long for
 * memory (periods times n_period) is refused (HY_EINVAL). */
int hy_boucwen_synth_periodic(const hy_boucwen_params *p,
                              const hy_newmark_opts *o, double fs, size_t r,
                              int staged, const double *u_period,
                              size_t n_period, size_t periods, double *y_out,
                              hy_error *err);

/* hy_boucwen_synth_periodic's periods first .. periods - 1 alone, the same
 * bits: writes (periods - first) * n_period / r samples.  The settling
 * periods before first are integrated but not decimated, and the extra
 * period only as far as the filter reads it.  NULL pointers and a record too
 * long for memory are refused as by hy_boucwen_synth_periodic. */
int hy_boucwen_synth_periodic_kept(const hy_boucwen_params *p, const hy_newmark_opts *o, double fs, size_t r,
                                   int staged, const double *u_period, size_t n_period, size_t first,
                                   size_t periods, double *y_out, hy_error *err);

#ifdef __cplusplus
}
#endif

#endif
