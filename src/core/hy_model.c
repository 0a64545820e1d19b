/* SPDX-License-Identifier: MIT */
/* hy_model.c: Dahl, LuGre and Example-1 model types (seed 000, Eqs. (1), (3), (16)). */
#include "hy_model.h"

#include <math.h>
#include <string.h>

static int check_pos(const char *name, double v, hy_error *err)
{
    if (!isfinite(v))
        return hy_error_set(err, HY_EINVAL, "%s must be a finite number (got %g)", name, v);
    if (v <= 0)
        return hy_error_set(err, HY_EINVAL, "%s must be > 0 (got %g)", name, v);
    return HY_OK;
}

static int check_nonneg(const char *name, double v, hy_error *err)
{
    if (!isfinite(v))
        return hy_error_set(err, HY_EINVAL, "%s must be a finite number (got %g)", name, v);
    if (v < 0)
        return hy_error_set(err, HY_EINVAL, "%s must be >= 0 (got %g)", name, v);
    return HY_OK;
}

static int check_finite(const char *name, double v, hy_error *err)
{
    if (!isfinite(v))
        return hy_error_set(err, HY_EINVAL, "%s must be a finite number (got %g)", name, v);
    return HY_OK;
}

static int validate_common(const hy_model *m, hy_error *err)
{
    int rc;
    if ((rc = check_pos("sigma0", m->sigma0, err)) || (rc = check_pos("fc", m->fc, err)) ||
        (rc = check_finite("x0", m->x0, err)))
        return rc;
    return HY_OK;
}

static int validate_lugre(const hy_model *m, hy_error *err)
{
    int rc;
    if ((rc = validate_common(m, err)) || (rc = check_pos("fs", m->fs, err)) ||
        (rc = check_pos("vs", m->vs, err)) || (rc = check_pos("beta", m->beta, err)) ||
        (rc = check_nonneg("sigma1", m->sigma1, err)) ||
        (rc = check_nonneg("sigma2", m->sigma2, err)))
        return rc;
    return HY_OK;
}

static int validate_dahl(const hy_model *m, hy_error *err)
{
    int rc;
    if ((rc = check_pos("rho", m->rho, err)) || (rc = validate_common(m, err)))
        return rc;
    if (!isfinite(m->sigma0))
        return hy_error_set(err, HY_EINVAL, "rho * fc overflows (rho = %g, fc = %g)", m->rho, m->fc);
    return HY_OK;
}

static int validate_dahl_filter(const hy_model *m, hy_error *err)
{
    int rc;
    if ((rc = validate_dahl(m, err)) || (rc = check_pos("tau", m->tau, err)) ||
        (rc = check_finite("yf0", m->yf0, err)))
        return rc;
    return HY_OK;
}

static const hy_model_type dahl_type = {"dahl", 0, validate_dahl};
static const hy_model_type lugre_type = {"lugre", 0, validate_lugre};
static const hy_model_type dahl_filter_type = {"dahl-filter", 1, validate_dahl_filter};

const hy_model_type *const hy_model_dahl = &dahl_type;
const hy_model_type *const hy_model_lugre = &lugre_type;
const hy_model_type *const hy_model_dahl_filter = &dahl_filter_type;

void hy_model_lugre_init(hy_model *m, double sigma0, double sigma1, double fc, double fs,
                    double vs, double beta)
{
    if (!m)
        return;
    memset(m, 0, sizeof *m);
    m->type = hy_model_lugre;
    m->sigma0 = sigma0;
    m->sigma1 = sigma1;
    m->fc = fc;
    m->fs = fs;
    m->vs = vs;
    m->beta = beta;
    m->tau = 1;
}

void hy_model_dahl_init(hy_model *m, double rho, double fc)
{
    if (!m)
        return;
    memset(m, 0, sizeof *m);
    m->type = hy_model_dahl;
    m->rho = rho;
    m->fc = fc;
    m->fs = fc;
    m->vs = 1;
    m->beta = 1;
    m->sigma0 = rho * fc;
    m->tau = 1;
}

void hy_model_dahl_filter_init(hy_model *m, double rho, double fc, double tau)
{
    if (!m)
        return;
    hy_model_dahl_init(m, rho, fc);
    m->type = hy_model_dahl_filter;
    m->tau = tau;
}

int hy_model_validate(const hy_model *m, hy_error *err)
{
    if (!m || !m->type)
        return hy_error_set(err, HY_EINVAL, "model has no type (dahl, lugre or dahl-filter)");
    return m->type->validate(m, err);
}

const hy_model_type *hy_model_type_find(const char *name)
{
    const hy_model_type *all[] = {hy_model_dahl, hy_model_lugre, hy_model_dahl_filter};
    if (!name)
        return NULL;
    for (size_t i = 0; i < sizeof all / sizeof all[0]; i++)
        if (strcmp(all[i]->name, name) == 0)
            return all[i];
    return NULL;
}

double hy_model_g(const hy_model *m, double v)
{
    if (!m)
        return NAN;
    if (m->type != hy_model_lugre || m->fs == m->fc)
        return m->fc;
    double r = fabs(v / m->vs);
    if (r == 0)
        return m->fs;
    return m->fc + (m->fs - m->fc) * exp(-pow(r, m->beta));
}

double hy_model_g0(const hy_model *m)
{
    if (!m)
        return NAN;
    return m->type == hy_model_lugre ? m->fs : m->fc;
}

double hy_model_a(const hy_model *m)
{
    if (!m)
        return NAN;
    return m->sigma0 / hy_model_g0(m);
}

int hy_model_rate_independent(const hy_model *m)
{
    if (!m || !m->type)
        return 0;
    if (m->type->has_filter)
        return 0;
    if (m->type == hy_model_dahl)
        return 1;
    return m->fs == m->fc && m->sigma1 == 0 && m->sigma2 == 0;
}
