/* SPDX-License-Identifier: MIT */
/* scene_fit.h: a scene's [model] fitted to its measured data (issue 32 item
 * 2; docs/FIT.md "Fitting a scene"): least squares (hy_fit.h) of the model's
 * output at the measured inputs against the measured outputs, over one or
 * several [data] sections at once, through the pipeline's fitter calls
 * (hy_scene_run_set_model, hy_scene_run_model_at_data): every model of the
 * table is fitted the same way, with nothing fit-specific in its file.
 *
 *     const char *freek[] = {"sigma0", "fc"};
 *     hy_scene_fit_opts o;
 *     hy_scene_fit_opts_default(&o);
 *     o.free_keys = freek; o.nfree = 2;
 *     hy_scene_fit f;
 *     if (hy_scene_fit_run("friction.scene", &o, &f, &err)) ... err.msg ...
 *     hy_fit_report(stdout, &f.pb, &f.res);  puts(f.text);
 *     hy_scene_fit_free(&f);
 */
#ifndef HY_SCENE_FIT_H
#define HY_SCENE_FIT_H

#include <stddef.h>

#include "hy_fit.h"
#include "hy_scene_schema.h"
#include "hy_status.h"

typedef struct hy_scene_fit_opts {
    const char *const *free_keys; /* nfree [model] keys, "sigma0" or "model.sigma0" */
    size_t nfree;
    const char *const *data;      /* ndata [data] names to fit at once, each driving
                                     the model in turn ([input] data = NAME); 0: the
                                     scene's own [input] data */
    size_t ndata;
    hy_fit_opts fit;              /* starts, seed, jobs, progress (hy_fit_opts_default);
                                     fit.cancel also stops the model evaluations */
    const struct hy_scene_policy *pol; /* include dirs, work budget (NULL: defaults) */
    char *const *sets;            /* nsets overrides "SECTION.KEY=VALUE" (render's
                                     --set) applied before fitting: the start
                                     values and the fixed ones */
    size_t nsets;
    const char *text;             /* the scene's text (text_len bytes; path names
                                     it), or NULL: read from path */
    size_t text_len;
    double max_work;              /* 0, or the most measured points over all
                                     evaluations (serve's budget of one fit):
                                     past it the fit stops with HY_EINVAL */
} hy_scene_fit_opts;

/* A fit: the problem as hy_fit saw it, its result, and what it was fitted to. */
typedef struct hy_scene_fit {
    hy_fit_problem pb;     /* n residuals, p parameters, param = prm */
    hy_fit_param *prm;     /* p: name (the [model] key), bounds, scale */
    double *x0;            /* p: the scene's values (start 0) */
    double *u, *y;         /* n: measured inputs and outputs, the data sets one after another */
    double *ymodel;        /* n: the model at the estimate */
    size_t ndata;
    char **dname;          /* ndata [data] names */
    size_t *off;           /* ndata + 1 offsets into u, y, ymodel, res.resid */
    size_t *nrec;          /* ndata: records of each (each from [input] start) */
    hy_fit_result res;     /* hy_fit_run's */
    char *text;            /* the scene's text with the estimates written in */
} hy_scene_fit;

/* o with no keys, no data names and hy_fit_opts_default's options. */
void hy_scene_fit_opts_default(hy_scene_fit_opts *o);

/* The range of a number or integer key at the scene's value v: the range
 * serve's slider gives it and the bounds hystviz fit keeps it in (one rule
 * for both): the schema's bounds; where one is open, v/100 .. 100 v for a
 * key >= 0 (an integer: whole, at least 1, lo + 100 when linear and open
 * above), v -+ |v| otherwise; logarithmic when it is positive and spans at
 * least a factor 50.  Always lo < hi. */
void hy_scene_key_range(const hy_scene_key_spec *k, double v, double *lo, double *hi, int *log);

/* Loads the scene at path, checks the free keys and the data, fits.  HY_OK:
 * f holds the result (release with hy_scene_fit_free).  HY_EINVAL with one
 * line: an unknown key, not a [model] number key of the scene's model, a
 * range of one value, no data, a bad data file (file:line:col), a bad
 * override, o->max_work spent; HY_ENUM: every start failed; HY_ECANCEL:
 * o->fit.cancel said stop.  On error f needs no free. */
int hy_scene_fit_run(const char *path, const hy_scene_fit_opts *o, hy_scene_fit *f, hy_error *err);

/* Releases f; f is zeroed. */
void hy_scene_fit_free(hy_scene_fit *f);

#endif
