/* SPDX-License-Identifier: MIT */
/* hy_bwfit.h: the Bouc-Wen benchmark as an identification task (seeds/001,
 * Sections 4-5; issue 32 item 4; docs/FIT.md).  Internal to hystviz (not an
 * installed header): `hystviz fit --benchmark boucwen`, its test and its
 * benchmark share it.
 *
 * Training data (hy_bwfit_train): R realisations of the benchmark's random-
 * phase multisine (5-150 Hz, std 50 N, n samples a period at 750 Hz, phases
 * seeded seed + q for realisation q), each simulated by the project's Newmark
 * pipeline at 15 kHz for 1 + P periods from rest (decimated in stages 2, 2,
 * 5) with the output corrupted by Gaussian noise of exactly `noise` m RMS
 * over the record, white up to 375 Hz = fs/2 (the benchmark's 0-375 Hz band),
 * seeded (seed + q) ^ 0x6e6f697365; the first (transient) period is dropped.
 * With n = 8192 realisation q is, bit for bit, rows n .. (P+1) n - 1 of
 * `hystviz boucwen data --signal multisine --seed S+q --periods P+1`.
 *
 * The fit (hy_bwfit_run) simulates the same pipeline (hy_boucwen_synth_
 * periodic_kept) at every evaluation: residual = model - data over the R P n
 * kept samples.  The test sets are read only by hy_bwfit_erms_*, after. */
#ifndef HY_BWFIT_H
#define HY_BWFIT_H

#include "hy_boucwen.h"
#include "hy_fit.h"

/* Which parameters are free. */
enum {
    HY_BWFIT_ALL = 0,  /* all eight of Table 1: m c k alpha beta gamma delta nu
                          (beta, gamma, delta enter only as beta gamma and beta
                          delta: the engine flags them) */
    HY_BWFIT_IDENT = 1 /* the identifiable seven: m c k alpha, beta gamma,
                          beta delta, nu (beta := 1, gamma := beta gamma,
                          delta := beta delta: the same model) */
};

typedef struct hy_bwfit_opts {
    uint64_t seed;        /* 1 */
    size_t realisations;  /* R (1) */
    size_t periods;       /* P kept periods per realisation (1) */
    size_t n;             /* samples a period at 750 Hz (8192) */
    double noise;         /* output noise RMS, m (8e-6 = 8e-3 mm) */
    uint64_t noise_seed;  /* 0: realisation q's noise is seeded (seed + q) ^
                             0x6e6f697365 as above; else noise_seed + q (the
                             same inputs under other noise) */
    int set;              /* HY_BWFIT_ALL or HY_BWFIT_IDENT */
    int fit_nu;           /* 1: nu free; 0: fixed at Table 1's 1 */
    double newton_tol;    /* the model's Newton stop in the fit (0: the
                             data's, hy_newmark_opts_default's 1e-12) */
    hy_fit_opts fit;      /* the engine's options (starts, jobs, progress ...;
                             ftol 1e-10 here) */
} hy_bwfit_opts;

typedef struct hy_bwfit_train {
    size_t R, P, n, r;   /* r: upsampling (20) */
    double fs;           /* 750 */
    double *u;           /* R x (n r): one period of each multisine at 15 kHz */
    double *y;           /* R x (P n): the noisy kept output */
} hy_bwfit_train;

/* Sets o to the defaults above (set HY_BWFIT_IDENT, fit_nu 1). */
void hy_bwfit_opts_default(hy_bwfit_opts *o);

/* Makes the training data of o with Table 1's parameters (truth).
 * Release with hy_bwfit_train_free. */
int hy_bwfit_make_train(const hy_bwfit_opts *o, const hy_boucwen_params *truth, hy_bwfit_train *tr, hy_error *err);
void hy_bwfit_train_free(hy_bwfit_train *tr);

/* The free parameters of o (names, bounds, scales: docs/FIT.md) into prm
 * (room for 8), the documented start (each +-50 % off Table 1: m x1.5,
 * c x0.5, k x1.5, alpha x0.5, beta x1.5, gamma x1.5, delta x0.5, nu x1.5;
 * IDENT: beta gamma x1.5, beta delta x0.5; the other way round, gamma
 * x0.5 and delta x1.5, beta (gamma + delta) = -1875 instead of Table 1's
 * -300 at nu 1.5, and the Newmark run fails at the start) into x0, the
 * truth into x_true; returns p (nu last, left out when fixed). */
size_t hy_bwfit_params(const hy_bwfit_opts *o, hy_fit_param *prm, double *x0, double *x_true);

/* theta (of o's set) -> Bouc-Wen parameters. */
void hy_bwfit_to_params(const hy_bwfit_opts *o, const double *theta, hy_boucwen_params *p);

/* Fits tr from x0 (NULL: the documented start).  res as hy_fit_run. */
int hy_bwfit_run(const hy_bwfit_opts *o, const hy_bwfit_train *tr, const double *x0, hy_fit_result *res,
                 hy_error *err);

/* The engine's statistics (hy_fit_evaluate) of o's set at theta, no fit. */
int hy_bwfit_evaluate(const hy_bwfit_opts *o, const hy_bwfit_train *tr, const double *theta, hy_fit_result *res,
                      hy_error *err);

/* e_RMS (Eq. 6) of p on the official validation multisine: uval (n samples,
 * one period at 750 Hz) upsampled x20 by DFT, simulated for 3 periods from
 * rest, the third decimated (stages 2, 2, 5), against yval. */
int hy_bwfit_erms_multisine(const hy_boucwen_params *p, const double *uval, const double *yval, size_t n,
                            double *erms, hy_error *err);

/* e_RMS of p against truth on the validation sine sweep (hy_sweep_validation:
 * 153000 samples at 750 Hz, made at 15 kHz, decimated in one stage), both
 * simulated here from rest. */
int hy_bwfit_erms_sweep(const hy_boucwen_params *p, const hy_boucwen_params *truth, double *erms, hy_error *err);

#endif
