/* SPDX-License-Identifier: MIT */
/* hy_bwfit.c: the Bouc-Wen benchmark as an identification task: training data
 * as Section 4 prescribes, a grey-box fit of Table 1's parameters with hy_fit,
 * e_RMS (Eq. 6) on the two test sets (seeds/001, Sections 4-5). */
#include "hy_bwfit.h"

#include "hy_signal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define FS 750.0
#define UP 20 /* integration at 15 kHz */
#define NOISE_SALT 0x6e6f697365ULL /* as `hystviz boucwen data` seeds its noise */

void hy_bwfit_opts_default(hy_bwfit_opts *o)
{
    memset(o, 0, sizeof *o);
    o->seed = 1;
    o->realisations = 1;
    o->periods = 1;
    o->n = 8192;
    o->noise = 8e-6;
    o->set = HY_BWFIT_IDENT;
    o->fit_nu = 1;
    hy_fit_opts_default(&o->fit);
    /* stop when a step gains less than 1e-10 of the RSS: at n = 8192 samples
       that is within 1e-3 standard errors of the minimum (RSS - RSS_min =
       s^2 (distance in SE)^2), where the last iterations of xtol 1e-12
       spent 5-10 more steps without changing a printed digit */
    o->fit.ftol = 1e-10;
}

void hy_bwfit_train_free(hy_bwfit_train *tr)
{
    free(tr->u);
    free(tr->y);
    memset(tr, 0, sizeof *tr);
}

int hy_bwfit_make_train(const hy_bwfit_opts *o, const hy_boucwen_params *truth, hy_bwfit_train *tr, hy_error *err)
{
    memset(tr, 0, sizeof *tr);
    if (o->realisations < 1 || o->periods < 1 || o->n < 64 || o->realisations * o->periods > 1000 ||
        !(o->noise >= 0 && isfinite(o->noise)))
        return hy_error_set(err, HY_EINVAL, "training data: need 1 or more realisations and periods (at most 1000 "
                            "in all), 64 or more samples a period and a noise RMS >= 0");
    size_t R = o->realisations, P = o->periods, n = o->n;
    *tr = (hy_bwfit_train){R, P, n, UP, FS, malloc(R * n * UP * sizeof(double)), malloc(R * P * n * sizeof(double))};
    double *y = malloc((P + 1) * n * sizeof *y);
    int rc = tr->u && tr->y && y ? HY_OK : hy_error_set(err, HY_ENOMEM, "out of memory for the training data");
    hy_newmark_opts no;
    hy_newmark_opts_default(&no);
    for (size_t q = 0; !rc && q < R; q++) {
        hy_multisine ms;
        hy_multisine_default(&ms);
        ms.n = n;
        ms.seed = o->seed + q;
        double *u = tr->u + q * n * UP;
        rc = hy_multisine_design(&ms, UP, u, err);
        if (!rc)
            rc = hy_boucwen_synth_periodic(truth, &no, FS, UP, 1, u, n * UP, P + 1, y, err);
        if (!rc)
            rc = hy_signal_add_noise(y, (P + 1) * n, o->noise, FS / 2, FS,
                                     o->noise_seed ? o->noise_seed + q : (o->seed + q) ^ NOISE_SALT, err);
        if (!rc)
            memcpy(tr->y + q * P * n, y + n, P * n * sizeof *y);
    }
    free(y);
    if (rc)
        hy_bwfit_train_free(tr);
    return rc;
}

/* Bounds and scales (docs/FIT.md): wide enough for a start +-50 % off and
 * far beyond, inside the model's domain (m > 0, beta > 0, nu > 0). */
static const hy_fit_param all8[8] = {
    {"m", 0.5, 8, HY_FIT_LOG},        {"c", 1, 100, HY_FIT_LOG},         {"k", 5e3, 5e5, HY_FIT_LOG},
    {"alpha", 5e3, 5e5, HY_FIT_LOG},  {"beta", 10, 1e5, HY_FIT_LOG},     {"gamma", -10, 10, HY_FIT_LINEAR},
    {"delta", -10, 10, HY_FIT_LINEAR}, {"nu", 0.5, 3, HY_FIT_LINEAR},
};
static const hy_fit_param ident7[7] = {
    {"m", 0.5, 8, HY_FIT_LOG},       {"c", 1, 100, HY_FIT_LOG},   {"k", 5e3, 5e5, HY_FIT_LOG},
    {"alpha", 5e3, 5e5, HY_FIT_LOG}, {"beta*gamma", -1e4, 1e4, HY_FIT_LINEAR},
    {"beta*delta", -1e4, 1e4, HY_FIT_LINEAR}, {"nu", 0.5, 3, HY_FIT_LINEAR},
};
static const double start_factor[8] = {1.5, 0.5, 1.5, 0.5, 1.5, 1.5, 0.5, 1.5};
static const double start_factor7[7] = {1.5, 0.5, 1.5, 0.5, 1.5, 0.5, 1.5};

size_t hy_bwfit_params(const hy_bwfit_opts *o, hy_fit_param *prm, double *x0, double *x_true)
{
    hy_boucwen_params t;
    hy_boucwen_params_default(&t);
    double all[8] = {t.m, t.c, t.k, t.alpha, t.beta, t.gamma, t.delta, t.nu};
    double id[7] = {t.m, t.c, t.k, t.alpha, t.beta * t.gamma, t.beta * t.delta, t.nu};
    size_t p = o->set == HY_BWFIT_ALL ? 8 : 7;
    for (size_t j = 0; j < p; j++) {
        double tv = p == 8 ? all[j] : id[j];
        if (prm)
            prm[j] = p == 8 ? all8[j] : ident7[j];
        if (x0)
            x0[j] = tv * (p == 8 ? start_factor[j] : start_factor7[j]);
        if (x_true)
            x_true[j] = tv;
    }
    return o->fit_nu ? p : p - 1; /* nu is last */
}

void hy_bwfit_to_params(const hy_bwfit_opts *o, const double *th, hy_boucwen_params *p)
{
    hy_boucwen_params_default(p);
    p->m = th[0];
    p->c = th[1];
    p->k = th[2];
    p->alpha = th[3];
    if (o->set == HY_BWFIT_ALL) {
        p->beta = th[4];
        p->gamma = th[5];
        p->delta = th[6];
        if (o->fit_nu)
            p->nu = th[7];
    } else {
        p->beta = 1;
        p->gamma = th[4];
        p->delta = th[5];
        if (o->fit_nu)
            p->nu = th[6];
    }
}

typedef struct ctx {
    const hy_bwfit_opts *o;
    const hy_bwfit_train *tr;
} ctx;

/* model - data over every kept sample; reentrant (called from the engine's
 * threads): the simulation's buffers are its own. */
static int resid(const double *th, double *r, void *vc)
{
    const ctx *c = vc;
    const hy_bwfit_train *tr = c->tr;
    hy_boucwen_params p;
    hy_newmark_opts no;
    hy_error err;
    hy_bwfit_to_params(c->o, th, &p);
    hy_newmark_opts_default(&no);
    if (c->o->newton_tol > 0)
        no.tol = c->o->newton_tol;
    if (hy_boucwen_params_validate(&p, &err))
        return 1;
    size_t kept = tr->P * tr->n;
    for (size_t q = 0; q < tr->R; q++) {
        double *rq = r + q * kept;
        if (hy_boucwen_synth_periodic_kept(&p, &no, tr->fs, tr->r, 1, tr->u + q * tr->n * tr->r, tr->n * tr->r, 1,
                                           tr->P + 1, rq, &err))
            return 1;
        for (size_t i = 0; i < kept; i++)
            rq[i] -= tr->y[q * kept + i];
    }
    return 0;
}

int hy_bwfit_run(const hy_bwfit_opts *o, const hy_bwfit_train *tr, const double *x0, hy_fit_result *res,
                 hy_error *err)
{
    hy_fit_param prm[8];
    double start[8];
    size_t p = hy_bwfit_params(o, prm, start, NULL);
    ctx c = {o, tr};
    hy_fit_problem pb = {tr->R * tr->P * tr->n, p, prm, resid, &c, x0 ? x0 : start, tr->y};
    return hy_fit_run(&pb, &o->fit, res, err);
}

int hy_bwfit_evaluate(const hy_bwfit_opts *o, const hy_bwfit_train *tr, const double *theta, hy_fit_result *res,
                      hy_error *err)
{
    hy_fit_param prm[8];
    size_t p = hy_bwfit_params(o, prm, NULL, NULL);
    ctx c = {o, tr};
    hy_fit_problem pb = {tr->R * tr->P * tr->n, p, prm, resid, &c, NULL, tr->y};
    return hy_fit_evaluate(&pb, theta, res, err);
}

int hy_bwfit_erms_multisine(const hy_boucwen_params *p, const double *uval, const double *yval, size_t n,
                            double *erms, hy_error *err)
{
    double *u = malloc(n * UP * sizeof *u), *y = malloc(n * sizeof *y);
    int rc = u && y ? HY_OK : hy_error_set(err, HY_ENOMEM, "out of memory for the validation multisine");
    hy_newmark_opts no;
    hy_newmark_opts_default(&no);
    if (!rc)
        rc = hy_signal_upsample_fft(uval, n, UP, u, err);
    if (!rc) /* two settling periods: the transient is ~1e-24 of y after them */
        rc = hy_boucwen_synth_periodic_kept(p, &no, FS, UP, 1, u, n * UP, 2, 3, y, err);
    if (!rc)
        *erms = hy_signal_erms(y, yval, n);
    free(u);
    free(y);
    return rc;
}

int hy_bwfit_erms_sweep(const hy_boucwen_params *p, const hy_boucwen_params *truth, double *erms, hy_error *err)
{
    hy_sweep sw;
    hy_sweep_validation(&sw);
    size_t nd = hy_sweep_length(&sw, FS), n = nd * UP;
    double *u = malloc(n * sizeof *u), *ya = malloc(nd * sizeof *ya), *yb = malloc(nd * sizeof *yb);
    int rc = u && ya && yb ? HY_OK : hy_error_set(err, HY_ENOMEM, "out of memory for the validation sweep");
    hy_newmark_opts no;
    hy_newmark_opts_default(&no);
    if (!rc)
        rc = hy_sweep_fill(&sw, FS * UP, u, n, err);
    if (!rc)
        rc = hy_boucwen_synth(p, &no, FS, UP, 0, u, n, ya, err);
    if (!rc)
        rc = hy_boucwen_synth(truth, &no, FS, UP, 0, u, n, yb, err);
    if (!rc)
        *erms = hy_signal_erms(ya, yb, nd);
    free(u);
    free(ya);
    free(yb);
    return rc;
}
