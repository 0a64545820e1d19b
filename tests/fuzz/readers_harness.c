/* SPDX-License-Identifier: MIT */
/* readers_harness.c: one fuzz input through a data file reader (see
 * readers_harness.h): [data]'s table, a FORC file, a Preisach density file. */
#include "readers_harness.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hy_forc.h"
#include "hy_preisach.h"
#include "hy_preisach_table.h"
#include "hy_status.h"
#include "hy_table.h"

#define NAME "fuzz.dat"

static int fail(char *why, size_t whylen, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(why, whylen, fmt, ap);
    va_end(ap);
    return -1;
}

/* A refusal's message: terminated, text (hy_text_check), and for a refused
 * file (HY_EINVAL) "NAME:" followed by more than a location. */
static int check_message(int rc, const hy_error *err, const char *reader, char *why, size_t whylen)
{
    if (!memchr(err->msg, '\0', sizeof err->msg))
        return fail(why, whylen, "%s: unterminated error message", reader);
    if (hy_text_check(err->msg) >= 0)
        return fail(why, whylen, "%s: the error message is not text", reader);
    size_t n = strlen(err->msg);
    while (n && (err->msg[n - 1] == ' ' || err->msg[n - 1] == '\n'))
        n--;
    if (!n || err->msg[n - 1] == ':')
        return fail(why, whylen, "%s: empty error message '%s'", reader, err->msg);
    if (rc == HY_EINVAL && strncmp(err->msg, NAME ":", strlen(NAME ":")) != 0)
        return fail(why, whylen, "%s: the message does not name the file: '%s'", reader, err->msg);
    return 0;
}

/* The column specs of [data] the mode byte chooses among. */
static const hy_table_spec table_specs[4] = {
    {{"1", "2", NULL, NULL}, {1, 1, 1}},
    {{"H", "B", "t", NULL}, {1e-3, 1, 1}},
    {{"2", "1", "3", "4"}, {1, 1, 1}},
    {{"u", "y", NULL, "3"}, {1, 1e300, 1}},
};

static int table_one(const char *text, size_t len, unsigned mode, char *why, size_t whylen)
{
    hy_table tb;
    hy_error err = {0, ""};
    int rc = hy_table_parse(text, len, NAME, &table_specs[(mode / 3) % 4], (mode >> 6) & 1, &tb, &err);
    if (rc)
        return check_message(rc, &err, "hy_table_parse", why, whylen);
    int bad = 0;
    if (!tb.nrec || tb.rec[0] != 0 || tb.rec[tb.nrec] != tb.n)
        bad = fail(why, whylen, "hy_table_parse: %zu records do not cover the %zu rows", tb.nrec, tb.n);
    for (size_t j = 0; !bad && j < tb.nrec; j++) {
        if (tb.rec[j + 1] <= tb.rec[j])
            bad = fail(why, whylen, "hy_table_parse: record %zu is empty or out of order", j);
        else
            (void)hy_table_area(tb.u + tb.rec[j], tb.y + tb.rec[j], tb.rec[j + 1] - tb.rec[j]);
    }
    for (size_t i = 0; !bad && i < tb.n; i++)
        if (isnan(tb.u[i]) || isnan(tb.y[i]) || (tb.t && isnan(tb.t[i])))
            bad = fail(why, whylen, "hy_table_parse: row %zu holds NaN", i);
    hy_table_free(&tb);
    return bad;
}

static int forc_checks(const hy_forc_data *d, char *why, size_t whylen)
{
    size_t sum = 0;
    for (size_t i = 0; i < d->ncurves; i++) {
        const hy_forc_curve *c = &d->curve[i];
        if (c->first != sum || c->n == 0 || c->first + c->n > d->npoints || !isfinite(c->ha))
            return fail(why, whylen, "hy_forc_read: curve %zu (first %zu, %zu points) of %zu points", i, c->first,
                        c->n, d->npoints);
        for (size_t k = c->first; k < c->first + c->n; k++)
            if (!isfinite(d->hb[k]) || !isfinite(d->m[k]) || (k > c->first && !(d->hb[k] > d->hb[k - 1])))
                return fail(why, whylen, "hy_forc_read: curve %zu, point %zu: not finite or not ascending", i,
                            k - c->first);
        sum += c->n;
    }
    if (sum != d->npoints)
        return fail(why, whylen, "hy_forc_read: the curves hold %zu of %zu points", sum, d->npoints);
    return 0;
}

static int forc_one(const char *text, size_t len, char *why, size_t whylen)
{
    hy_forc_data d;
    memset(&d, 0, sizeof d);
    hy_error err = {0, ""};
    int rc = hy_forc_read(&d, text, len, NAME, &err);
    if (rc) {
        hy_forc_data_free(&d);
        return check_message(rc, &err, "hy_forc_read", why, whylen);
    }
    int bad = forc_checks(&d, why, whylen);
    if (!bad) {
        double da, db;
        hy_forc_steps(&d, &da, &db);
        if (hy_forc_drift(&d, &err))
            bad = check_message(HY_ENUM, &err, "hy_forc_drift", why, whylen);
    }
    if (!bad && d.npoints <= 64) { /* the distribution, on a small grid (milliseconds) */
        hy_forc_opts o = hy_forc_defaults();
        hy_forc_grid g;
        hy_forc_grid_auto(&d, &o, &g);
        if (g.nc >= 1 && g.nu >= 1 && g.nc <= 20 && g.nu <= 20) {
            size_t nfit = 0;
            rc = hy_forc_rho(&d, &o, &g, &nfit, &err);
            if (rc)
                bad = check_message(HY_ENUM, &err, "hy_forc_rho", why, whylen);
            else if (nfit > g.nc * g.nu)
                bad = fail(why, whylen, "hy_forc_rho: %zu nodes fitted of %zu", nfit, g.nc * g.nu);
        }
        hy_forc_grid_free(&g);
    }
    hy_forc_data_free(&d);
    return bad;
}

static int density_one(const char *text, size_t len, char *why, size_t whylen)
{
    hy_forc_grid g;
    memset(&g, 0, sizeof g);
    hy_error err = {0, ""};
    int rc = hy_preisach_table_read(text, len, NAME, &g, &err);
    if (rc)
        return check_message(rc, &err, "hy_preisach_table_read", why, whylen);
    int bad = 0;
    if (g.nc < 2 || g.nu < 2 || !(g.hc1 > g.hc0) || !(g.hu1 > g.hu0))
        bad = fail(why, whylen, "hy_preisach_table_read: a grid of %zu x %zu nodes over [%g, %g] x [%g, %g]", g.nc,
                   g.nu, g.hc0, g.hc1, g.hu0, g.hu1);
    for (size_t i = 0; !bad && i < g.nc * g.nu; i++)
        if (!(g.rho[i] >= 0) || !isfinite(g.rho[i]))
            bad = fail(why, whylen, "hy_preisach_table_read: node %zu holds %g", i, g.rho[i]);
    if (!bad) {
        hy_preisach_table t;
        rc = hy_preisach_table_from_grid(&t, &g, &err);
        if (rc)
            bad = check_message(HY_ENUM, &err, "hy_preisach_table_from_grid", why, whylen);
        else {
            if (t.n > g.nc * g.nu)
                bad = fail(why, whylen, "hy_preisach_table_from_grid: %zu relays from %zu nodes", t.n, g.nc * g.nu);
            hy_preisach_table_free(&t);
        }
    }
    free(g.rho);
    return bad;
}

int readers_fuzz_one(const uint8_t *data, size_t n, char *why, size_t whylen)
{
    if (n < 1 || n - 1 > READERS_FUZZ_MAX_BYTES)
        return 0;
    /* the text in its own allocation, exactly its length (ASan sees a read past it) */
    size_t len = n - 1;
    char *text = malloc(len ? len : 1);
    if (!text)
        return 0;
    if (len)
        memcpy(text, data + 1, len);
    unsigned mode = data[0];
    int rc = mode % 3 == 0 ? table_one(text, len, mode, why, whylen)
             : mode % 3 == 1 ? forc_one(text, len, why, whylen)
                             : density_one(text, len, why, whylen);
    free(text);
    return rc;
}
