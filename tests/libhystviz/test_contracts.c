/* SPDX-License-Identifier: MIT */
/* test_contracts.c: every function of hystviz.h called with NULL for each
 * pointer argument and with edge values (issue 36 item 4): a pointer the
 * header says must not be NULL gives HY_EINVAL and a message, never a crash;
 * one it says may be NULL gives what it says; a non-finite work budget is
 * refused (INFINITY silently disabled the budget); hy_write_file writes
 * through the output writer (whole file, a link out refused).  Run in the
 * sanitizer build too (suite lib): an out-of-bounds or NULL access fails.
 * Of the installed core headers, the readers' (hy_table.h, hy_forc.h) are
 * held to the same: each pointer argument NULL in turn; the others in
 * test_core_contracts.c.  Every function of the committed ABI list
 * (argument 1) must be reached by such a call (contracts.h). */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "hystviz.h"
#include "hy_forc.h"
#include "hy_table.h"
#include "../core/tutil.h"
#include "../tmpdir.h"
#include "contracts.h"

static const char scene[] = "[model]\nkind = lugre\nsigma0 = 6\n[input]\nkind = bimodal\n[compute]\npoints = 50\n"
                            "[figure]\nkind = loop\n[series minor]\ndata = minor\n";


static hy_result *good(void)
{
    hy_result *r = NULL;
    hy_error err;
    int rc = hy_result_from_text("t.scene", scene, sizeof scene - 1, NULL, 0, 0, &r, &err);
    CHECK(!rc && r, "the good scene: %s", err.msg);
    return r;
}

static void makers(void)
{
    hy_result *r = (hy_result *)&r; /* not NULL: must be set to NULL on error */
    hy_error err;
    const char *sets[] = {"model.sigma0=2", NULL};
    REFUSED(hy_result_from_text("t", scene, sizeof scene - 1, NULL, 0, 0, NULL, &err), err, "out must not be NULL");
    REFUSED(hy_result_from_file("x.scene", NULL, 0, 0, NULL, &err), err, "out must not be NULL");
    CHECK(hy_result_from_text("t", scene, sizeof scene - 1, NULL, 0, 0, NULL, NULL) == HY_EINVAL, "out NULL, err NULL");
    REFUSED(hy_result_from_text("t", NULL, 0, NULL, 0, 0, &r, &err), err, "no scene text");
    CHECK(r == NULL, "*out NULL after an error");
    REFUSED(hy_result_from_file(NULL, NULL, 0, 0, &r, &err), err, "no scene path");
    REFUSED(hy_result_from_text("t", scene, sizeof scene - 1, NULL, 1, 0, &r, &err), err, "sets is NULL but nsets is 1");
    REFUSED(hy_result_from_text("t", scene, sizeof scene - 1, sets, 2, 0, &r, &err), err, "sets[1] is NULL");
    REFUSED(hy_result_from_file("x.scene", sets, 2, 0, &r, &err), err, "sets[1] is NULL");
    double budgets[] = {INFINITY, -INFINITY, NAN};
    for (int i = 0; i < 3; i++) {
        REFUSED(hy_result_from_text("t", scene, sizeof scene - 1, NULL, 0, budgets[i], &r, &err), err,
                "max_work must be a finite number");
        REFUSED(hy_result_from_file("x.scene", NULL, 0, budgets[i], &r, &err), err, "max_work must be a finite number");
    }
    /* a budget of 1 unit is a budget: refused for its cost, not ignored */
    int rc = hy_result_from_text("t", scene, sizeof scene - 1, NULL, 0, 1, &r, &err);
    CHECK(rc && r == NULL && strstr(err.msg, "work"), "max_work = 1 refuses the scene: %d %s", rc, err.msg);
    /* name NULL: "<scene>"; len 0: an empty scene (refused or computed, never read past) */
    rc = hy_result_from_text(NULL, "[model]\nkind = dahl\nsigma0 = -1\n", 30, NULL, 0, 0, &r, &err);
    CHECK(rc == HY_EINVAL && strstr(err.msg, "<scene>:3:"), "name NULL is <scene>: %s", err.msg);
    rc = hy_result_from_text("t", "", 0, NULL, 0, 0, &r, &err);
    hy_result_free(rc ? NULL : r);
    rc = hy_result_from_text("t", scene, sizeof scene - 1, sets, 1, -5, &r, NULL); /* err NULL, <= 0: default budget */
    CHECK(!rc && r, "err NULL with a good scene: %d", rc);
    hy_result_free(r);
}

/* hy_table.h and hy_forc.h: each pointer the header says must not be NULL
 * refused with HY_EINVAL naming it; each it says may be NULL does what it says. */
static void core_readers(void)
{
    hy_error err;
    const char csv[] = "u,y\n0,0\n1,1\n0,1\n";
    hy_table_spec sp = {{"u", "y", NULL, NULL}, {1, 1, 1}}, half = {{"u", NULL, NULL, NULL}, {1, 1, 1}};
    hy_table tb;
    REFUSED(hy_table_parse(csv, sizeof csv - 1, "d.csv", &sp, 1, NULL, &err), err, "out must not be NULL");
    REFUSED(hy_table_parse(csv, sizeof csv - 1, "d.csv", NULL, 1, &tb, &err), err, "spec must not be NULL");
    CHECK(tb.n == 0 && tb.u == NULL, "hy_table_parse: out zeroed on a refusal");
    REFUSED(hy_table_parse(csv, sizeof csv - 1, "d.csv", &half, 1, &tb, &err), err, "u and y columns");
    REFUSED(hy_table_parse(NULL, 5, "d.csv", &sp, 1, &tb, &err), err, "text (len is not 0) must not be NULL");
    CHECK(hy_table_parse(NULL, 0, "d.csv", &sp, 1, &tb, &err) == HY_EINVAL && strstr(err.msg, "d.csv:"),
          "hy_table_parse: NULL text of length 0 is an empty file: %s", err.msg);
    CHECK(hy_table_parse(csv, sizeof csv - 1, NULL, &sp, 1, &tb, NULL) == 0 && tb.n == 3, "hy_table_parse: name NULL");
    /* the triangle (0,0) (1,1) (0,1): counter-clockwise, area 1/2 exactly */
    CHECK(hy_table_area(tb.u, tb.y, tb.n) == 0.5, "hy_table_area of the table");
    hy_table_free(&tb);
    hy_table_free(&tb);
    NC(hy_table_free(NULL));
    CHECK(isnan(NC(hy_table_area(NULL, tb.y, 3))) && isnan(hy_table_area(tb.u, NULL, 3)) &&
              hy_table_area(NULL, NULL, 2) == 0, "hy_table_area with NULL columns");

    hy_forc_data d;
    const char forc[] = "Ha,Hb,M\n-1,-1,-1\n-1,0,0\n-1,1,1\n0,0,0.5\n0,1,1\n";
    REFUSED(hy_forc_read(NULL, forc, sizeof forc - 1, "f.csv", &err), err, "d must not be NULL");
    REFUSED(hy_forc_read_csv(NULL, forc, sizeof forc - 1, "f.csv", &err), err, "d must not be NULL");
    REFUSED(hy_forc_read_micromag(NULL, forc, sizeof forc - 1, "f.csv", &err), err, "d must not be NULL");
    REFUSED(hy_forc_read(&d, NULL, 9, "f.csv", &err), err, "text (len is not 0) must not be NULL");
    REFUSED(hy_forc_read_micromag(&d, NULL, 9, "f.csv", &err), err, "text (len is not 0) must not be NULL");
    CHECK(hy_forc_read(&d, NULL, 0, "f.csv", &err) != 0 && d.ncurves == 0, "hy_forc_read: NULL text of length 0");
    hy_forc_data_free(&d);
    CHECK(hy_forc_read(&d, forc, sizeof forc - 1, NULL, NULL) == 0 && d.ncurves == 2 && d.npoints == 5,
          "hy_forc_read: name NULL, err NULL");
    double da = -1, db = -1;
    hy_forc_steps(&d, &da, NULL);
    hy_forc_steps(&d, NULL, &db);
    CHECK(da == 1 && db == 1, "hy_forc_steps with one of da, db NULL: %g %g", da, db);
    NC(hy_forc_steps(NULL, &da, &db));
    CHECK(da == 0 && db == 0, "hy_forc_steps(NULL)");
    hy_forc_opts o = NC(hy_forc_defaults());
    hy_forc_grid g;
    NC(hy_forc_grid_auto(NULL, NULL, &g));
    CHECK(g.nc == 2 && g.nu == 2 && g.hc0 == 0 && g.hc1 == 1 && g.hu0 == 0 && g.hu1 == 1 && !g.rho,
          "hy_forc_grid_auto(NULL, NULL, g): the 2 x 2 grid at 0, step 1");
    hy_forc_grid_auto(&d, &o, NULL);
    hy_forc_grid_auto(&d, &o, &g);
    REFUSED(hy_forc_rho(NULL, &o, &g, NULL, &err), err, "hy_forc_rho: d must not be NULL");
    REFUSED(hy_forc_rho(&d, NULL, &g, NULL, &err), err, "hy_forc_rho: o must not be NULL");
    REFUSED(hy_forc_rho(&d, &o, NULL, NULL, &err), err, "hy_forc_rho: g must not be NULL");
    hy_forc_grid_free(&g);
    NC(hy_forc_grid_free(NULL));
    REFUSED(hy_forc_drift(NULL, &err), err, "hy_forc_drift: d must not be NULL");
    hy_forc_data_free(&d);
    NC(hy_forc_data_free(NULL));
    double ha[] = {0}, hb[] = {0, 1}, m[] = {0, 1};
    size_t n[] = {2};
    REFUSED(hy_forc_data_set(NULL, 1, ha, n, hb, m, &err), err, "hy_forc_data_set: d must not be NULL");
    REFUSED(hy_forc_data_set(&d, 1, NULL, n, hb, m, &err), err, "ha must not be NULL");
    REFUSED(hy_forc_data_set(&d, 1, ha, NULL, hb, m, &err), err, "n must not be NULL");
    REFUSED(hy_forc_data_set(&d, 1, ha, n, NULL, m, &err), err, "hb must not be NULL");
    REFUSED(hy_forc_data_set(&d, 1, ha, n, hb, NULL, &err), err, "m must not be NULL");
    hy_forc_data_free(&d);
    hy_forc_protocol pr = {2, -1, 1, 1, 3};
    REFUSED(hy_forc_protocol_run(NULL, &pr, NULL, NULL, &err), err, "hy_forc_protocol_run: d must not be NULL");
    REFUSED(hy_forc_protocol_run(&d, NULL, NULL, NULL, &err), err, "pr must not be NULL");
    REFUSED(hy_forc_protocol_run(&d, &pr, NULL, NULL, &err), err, "fn must not be NULL");
    hy_forc_data_free(&d);
    REFUSED(hy_forc_preisach(NULL, &pr, NULL, &err), err, "hy_forc_preisach: d must not be NULL");
    REFUSED(hy_forc_preisach(&d, NULL, NULL, &err), err, "pr must not be NULL");
    REFUSED(hy_forc_preisach(&d, &pr, NULL, &err), err, "p must not be NULL");
    hy_forc_data_free(&d);
}

static void readers(hy_result *r)
{
    const double *x = (const double *)1, *y = (const double *)1;
    const char *ref = "x";
    double buf[4];
    CHECK(NC(hy_version()) && *hy_version(), "hy_version");
    /* no arguments: reached (after tc_core, whose refusals must not depend on
       GSL's handler being off), twice in a row harmless */
    NC(hy_gsl_quiet());
    hy_gsl_quiet();
    NC(hy_result_free(NULL));
    CHECK(NC(hy_result_nseries(NULL)) == 0, "nseries(NULL)");
    CHECK(NC(hy_result_series(NULL, 0, &x, &y)) == 0 && !x && !y, "series(NULL)");
    CHECK(hy_result_series(r, 0, NULL, NULL) > 0, "series with x, y NULL");
    CHECK(hy_result_series(r, (size_t)-1, &x, &y) == 0 && !x && !y, "series out of range");
    CHECK(NC(hy_result_series_copy(NULL, 0, buf, buf, 4)) == 0, "series_copy(NULL)");
    CHECK(hy_result_series_copy(r, 0, NULL, NULL, 4) > 0, "series_copy with x, y NULL");
    CHECK(hy_result_series_copy(r, 0, buf, buf, 0) > 0, "series_copy cap 0");
    CHECK(hy_result_series_copy(r, 99, buf, buf, 4) == 0, "series_copy out of range");
    CHECK(!NC(hy_result_series_name(NULL, 0)) && !hy_result_series_name(r, 99), "series_name NULL / out of range");
    CHECK(!NC(hy_result_series_data(NULL, 0)) && !hy_result_series_data(r, 99), "series_data NULL / out of range");
    CHECK(hy_result_series_name(r, 0) && hy_result_series_data(r, 0), "series_name, series_data");
    CHECK(isnan(NC(hy_result_series_error(NULL, 0, &ref))) && ref == NULL, "series_error(NULL)");
    CHECK(isnan(hy_result_series_error(r, 99, NULL)), "series_error out of range, ref NULL");
    CHECK(NC(hy_result_loops(NULL)) == NULL && hy_result_loops(r) != NULL, "loops");
}

static void outputs(hy_result *r)
{
    hy_error err;
    unsigned char *bytes = (unsigned char *)"x";
    char *text = "x";
    size_t len = 7;
    REFUSED(hy_result_render(r, "svg", NULL, &len, &err), err, "bytes must not be NULL");
    CHECK(len == 0, "render: *len 0 after an error");
    REFUSED(hy_result_render(r, "svg", &bytes, NULL, &err), err, "len must not be NULL");
    CHECK(bytes == NULL, "render: *bytes NULL after an error");
    REFUSED(hy_result_render(r, "svg", NULL, NULL, &err), err, "must not be NULL");
    REFUSED(hy_result_render(NULL, "svg", &bytes, &len, &err), err, "no result");
    REFUSED(hy_result_render(r, NULL, &bytes, &len, &err), err, "not NULL");
    REFUSED(hy_result_render(r, "svg,png", &bytes, &len, &err), err, "give one format");
    CHECK(hy_result_render(r, "", &bytes, &len, &err) != 0 && !bytes, "render format \"\"");
    CHECK(hy_result_render(r, "svg", &bytes, &len, NULL) == 0 && bytes && len > 100, "render svg, err NULL");
    free(bytes);
    REFUSED(hy_result_csv(r, NULL, &len, &err), err, "text must not be NULL");
    REFUSED(hy_result_csv(r, &text, NULL, &err), err, "len must not be NULL");
    CHECK(text == NULL, "csv: *text NULL after an error");
    REFUSED(hy_result_csv(NULL, &text, &len, &err), err, "no result");
    CHECK(hy_result_csv(r, &text, &len, NULL) == 0 && text && len == strlen(text), "csv, err NULL");
    free(text);
    char *json = NC(hy_schema_json());
    CHECK(json && json[0] == '{', "schema_json");
    free(json);
    double u[3] = {0, 1, 0}, y[3];
    REFUSED(hy_boucwen_run(NULL, 3, 750, y, &err), err, "at least one sample");
    REFUSED(hy_boucwen_run(u, 3, 750, NULL, &err), err, "at least one sample");
    REFUSED(hy_boucwen_run(u, 0, 750, y, &err), err, "at least one sample");
    REFUSED(hy_boucwen_run(u, 3, INFINITY, y, &err), err, "fs must be");
    REFUSED(hy_boucwen_run(u, 3, NAN, y, &err), err, "fs must be");
    CHECK(hy_boucwen_run(u, 3, 750, y, NULL) == 0 && isfinite(y[2]), "boucwen_run, err NULL");
}

static void writer(void)
{
    hy_error err;
    char dir[4096], path[4200], link[4200];
    if (!test_tmppath(dir, sizeof dir, "contracts") || mkdir(dir, 0700)) {
        CHECK(0, "a temporary directory");
        return;
    }
    snprintf(path, sizeof path, "%s/out.txt", dir);
    REFUSED(hy_write_file(NULL, "x", 1, &err), err, "no path");
    REFUSED(hy_write_file(path, NULL, 3, &err), err, "no data");
    CHECK(access(path, F_OK) != 0, "nothing written for NULL data");
    CHECK(hy_write_file(path, NULL, 0, &err) == 0, "an empty file (data NULL, len 0): %s", err.msg);
    CHECK(hy_write_file(path, "abc", 3, NULL) == 0, "write, err NULL");
    struct stat st;
    CHECK(!stat(path, &st) && st.st_size == 3, "3 bytes written");
    snprintf(link, sizeof link, "%s/link.txt", dir);
    CHECK(!symlink("/etc/passwd", link), "a link out: %s", strerror(errno));
    CHECK(hy_write_file(link, "x", 1, &err) == HY_EINVAL, "a link out of the directory is refused: %s", err.msg);
    CHECK(!lstat(link, &st) && S_ISLNK(st.st_mode), "the link is left as it was");
    unlink(link);
    unlink(path);
    CHECK(rmdir(dir) == 0, "nothing else left in %s (no temporary): %s", dir, strerror(errno));
}

/* hy_fit_scene and its readers: NULLs refused or answered as the header says;
 * one real fit (a play operator, 3 points of known r) read through them. */
static void fitter(void)
{
    hy_error err;
    hy_scene_fitted *f = (hy_scene_fitted *)&f; /* not NULL: must be set to NULL on error */
    const char *keys[] = {"play_r"}, *nulls[] = {NULL};
    REFUSED(hy_fit_scene("x.scene", keys, 1, NULL, 0, 0, 1, 1, NULL, &err), err, "out must not be NULL");
    CHECK(hy_fit_scene("x.scene", keys, 1, NULL, 0, 0, 1, 1, NULL, NULL) == HY_EINVAL, "fit: out NULL, err NULL");
    REFUSED(hy_fit_scene(NULL, keys, 1, NULL, 0, 0, 1, 1, &f, &err), err, "a scene path and 1 to 16 free keys");
    CHECK(f == NULL, "fit: *out NULL after an error");
    REFUSED(hy_fit_scene("x.scene", NULL, 1, NULL, 0, 0, 1, 1, &f, &err), err, "1 to 16 free keys");
    REFUSED(hy_fit_scene("x.scene", keys, 0, NULL, 0, 0, 1, 1, &f, &err), err, "1 to 16 free keys");
    REFUSED(hy_fit_scene("x.scene", keys, 17, NULL, 0, 0, 1, 1, &f, &err), err, "1 to 16 free keys");
    REFUSED(hy_fit_scene("x.scene", nulls, 1, NULL, 0, 0, 1, 1, &f, &err), err, "free_keys[0] is NULL");
    REFUSED(hy_fit_scene("x.scene", keys, 1, nulls, 1, 0, 1, 1, &f, &err), err, "data[0] is NULL");
    REFUSED(hy_fit_scene("x.scene", keys, 1, NULL, 0, 0, 1, 0, &f, &err), err, "jobs must be 1 to 64");
    REFUSED(hy_fit_scene("x.scene", keys, 1, NULL, 0, 0, 1, 65, &f, &err), err, "jobs must be 1 to 64");
    size_t len = 7;
    CHECK(NC(hy_scene_fitted_array(NULL, "theta", &len)) == NULL && len == 0, "fitted_array(NULL)");
    CHECK(isnan(NC(hy_scene_fitted_stat(NULL, "rms"))) && !NC(hy_scene_fitted_key(NULL, 0)) &&
              !NC(hy_scene_fitted_data(NULL, 0)) && !NC(hy_scene_fitted_text(NULL)), "fitted readers of NULL");
    NC(hy_scene_fitted_free(NULL));
    char dir[4200], csv[4300], sc[4300];
    test_tmppath(dir, sizeof dir, "");
    snprintf(csv, sizeof csv, "%s/p.csv", dir);
    snprintf(sc, sizeof sc, "%s/p.scene", dir);
    FILE *fp = fopen(csv, "w");
    fputs("u,y\n0,0\n1,0.7\n-1,-0.7\n0.5,0.2\n", fp); /* play r = 0.3 from y0 = 0 */
    fclose(fp);
    fp = fopen(sc, "w");
    fputs("[model]\nkind = play\nplay_r = 0.25\n[data d]\nfile = \"p.csv\"\nu = u\ny = y\n[input]\nkind = data\n"
          "data = d\n[figure]\nkind = loop\n[series m]\ndata = modelled\nof = d\n", fp);
    fclose(fp);
    int rc = hy_fit_scene(sc, keys, 1, NULL, 0, 0, 1, 1, &f, &err);
    CHECK(rc == 0 && f, "fit of play: %s", rc ? err.msg : "");
    if (!rc) {
        const double *th = hy_scene_fitted_array(f, "theta", &len);
        CHECK(th && len == 1 && fabs(th[0] - 0.3) < 1e-9, "play_r %g", th ? th[0] : NAN);
        CHECK(hy_scene_fitted_array(f, "resid", &len) && len == 4, "resid: %zu", len);
        CHECK(hy_scene_fitted_array(f, "corr", &len) && len == 1, "corr: %zu", len);
        CHECK(hy_scene_fitted_array(f, "nosuch", &len) == NULL && len == 0, "unknown array");
        CHECK(hy_scene_fitted_array(f, NULL, NULL) == NULL && hy_scene_fitted_array(f, "u", NULL) != NULL, "len NULL");
        CHECK(isnan(hy_scene_fitted_stat(f, "nosuch")) && isnan(hy_scene_fitted_stat(f, NULL)) &&
                  hy_scene_fitted_stat(f, "rms") < 1e-9, "stats");
        CHECK(!strcmp(hy_scene_fitted_key(f, 0), "play_r") && !hy_scene_fitted_key(f, 1) &&
                  !strcmp(hy_scene_fitted_data(f, 0), "d") && !hy_scene_fitted_data(f, 1), "key and data names");
        CHECK(strstr(hy_scene_fitted_text(f), "play_r = 0.3") != NULL, "fitted text: %s", hy_scene_fitted_text(f));
    }
    hy_scene_fitted_free(f);
    unlink(csv);
    unlink(sc);
}

/* Whether the n bytes at b hold the text t. */
static int has(const unsigned char *b, size_t n, const char *t)
{
    size_t m = strlen(t);
    for (size_t i = 0; i + m <= n; i++)
        if (!memcmp(b + i, t, m))
            return 1;
    return 0;
}

/* hy_sweep_npy: NULLs and empty axes refused with *npy NULL, *len 0; a
 * two-point study gives an .npy with two records. */
static void sweeper(void)
{
    hy_error err;
    unsigned char *npy = (unsigned char *)&err; /* not NULL: must be set to NULL on error */
    size_t len = 7, one = 1, two = 2, zero = 0;
    const char *keys[] = {"model.sigma0"}, *nokey[] = {NULL};
    double v[2] = {1, 2}, inf = INFINITY;
    const double *vals[] = {v}, *infs[] = {&inf};
    char sc[4300];
    test_tmppath(sc, sizeof sc, "sweep.scene");
    FILE *fp = fopen(sc, "w");
    if (fp) {
        fputs(scene, fp);
        fclose(fp);
    }
    REFUSED(hy_sweep_npy(NULL, NULL, 0, keys, vals, &two, 1, 0, 1, 1, 0, &npy, &len, &err), err, "must not be NULL");
    CHECK(npy == NULL && len == 0, "sweep_npy: *npy NULL, *len 0 after an error");
    REFUSED(hy_sweep_npy(sc, NULL, 0, keys, vals, &two, 1, 0, 1, 1, 0, NULL, &len, &err), err, "must not be NULL");
    REFUSED(hy_sweep_npy(sc, NULL, 0, keys, vals, &two, 1, 0, 1, 1, 0, &npy, NULL, &err), err, "must not be NULL");
    REFUSED(hy_sweep_npy(sc, NULL, 1, keys, vals, &two, 1, 0, 1, 1, 0, &npy, &len, &err), err, "must not be NULL");
    REFUSED(hy_sweep_npy(sc, NULL, 0, NULL, vals, &two, 1, 0, 1, 1, 0, &npy, &len, &err), err, "must not be NULL");
    REFUSED(hy_sweep_npy(sc, NULL, 0, keys, NULL, &two, 1, 0, 1, 1, 0, &npy, &len, &err), err, "must not be NULL");
    REFUSED(hy_sweep_npy(sc, NULL, 0, keys, vals, NULL, 1, 0, 1, 1, 0, &npy, &len, &err), err, "must not be NULL");
    REFUSED(hy_sweep_npy(sc, NULL, 0, nokey, vals, &two, 1, 0, 1, 1, 0, &npy, &len, &err), err, "key is NULL");
    REFUSED(hy_sweep_npy(sc, NULL, 0, keys, vals, &zero, 1, 0, 1, 1, 0, &npy, &len, &err), err, "no values");
    REFUSED(hy_sweep_npy(sc, NULL, 0, keys, infs, &one, 1, 0, 1, 1, 0, &npy, &len, &err), err, "finite");
    REFUSED(hy_sweep_npy(sc, NULL, 0, keys, vals, &two, 1, 0, 1, 1, NAN, &npy, &len, &err), err, "max_work");
    REFUSED(hy_sweep_npy(sc, NULL, 0, keys, vals, &two, 1, 2, 2, 1, 0, &npy, &len, &err), err, "shard 2 of 2");
    REFUSED(hy_sweep_npy(sc, NULL, 0, keys, vals, &two, 1, 0, 0, 1, 0, &npy, &len, &err), err, "shard 0 of 0");
    CHECK(hy_sweep_npy(sc, NULL, 0, keys, vals, &two, 1, 1, 2, 1, 0, &npy, &len, NULL) == 0 && npy &&
              has(npy, len, "'shape': (1,)"), "sweep_npy shard 1 of 2: one record");
    free(npy);
    CHECK(hy_sweep_npy(sc, NULL, 0, keys, vals, &two, 1, 0, 1, 2, 0, &npy, &len, NULL) == 0 && npy && len > 128 &&
              !memcmp(npy, "\x93NUMPY", 6) && has(npy, len, "'shape': (2,)"),
          "sweep_npy of two points, err NULL");
    free(npy);
    unlink(sc);
}

/* hy_steady_loop: NULLs refused with the arrays untouched; t, u, y NULL
 * allowed; its arrays equal the series of the scene it stands for (the two
 * sections, points, the input and ysteady as hy_steady_loop's header says),
 * computed through hy_result_from_text, bit for bit; a section without its
 * last line break reads the same. */
static void steady(void)
{
    static const char model[] = "[model]\nkind = lugre\nsigma0 = 6\n", input[] = "[input]\nkind = bimodal\n";
    static const char whole[] = "[model]\nkind = lugre\nsigma0 = 6\n[input]\nkind = bimodal\n[compute]\npoints = 50\n"
                                "cycles = 1\n[figure]\nkind = timeseries\n[series u]\ndata = input\n"
                                "[series y]\ndata = ysteady\n";
    enum { P = 50, N = P + 1 };
    hy_error err;
    double t[N], u[N], y[N], t2[N], u2[N], y2[N];
    const char *sets[] = {"model.sigma0=2", NULL};
    for (int i = 0; i < N; i++)
        t[i] = u[i] = y[i] = -1;
    REFUSED(hy_steady_loop(NULL, NULL, input, NULL, 0, P, t, u, y, &err), err, "no [model] text");
    REFUSED(hy_steady_loop(NULL, model, NULL, NULL, 0, P, t, u, y, &err), err, "no [input] text");
    REFUSED(hy_steady_loop(NULL, model, input, NULL, 1, P, t, u, y, &err), err, "sets is NULL but nsets is 1");
    REFUSED(hy_steady_loop(NULL, model, input, sets, 2, P, t, u, y, &err), err, "sets[1] is NULL");
    REFUSED(hy_steady_loop(NULL, model, input, NULL, 0, 1, t, u, y, &err), err, "'points'");
    REFUSED(hy_steady_loop(NULL, model, input, NULL, 0, 0, t, u, y, &err), err, "'points'");
    REFUSED(hy_steady_loop(NULL, model, input, NULL, 0, (size_t)-1, t, u, y, &err), err, "'points'");
    REFUSED(hy_steady_loop(NULL, "[model]\nkind = lugre\nsigma0 = -1\n", input, NULL, 0, P, t, u, y, &err), err,
            "<scene>:3:");
    CHECK(hy_steady_loop(NULL, model, input, NULL, 0, P, NULL, NULL, NULL, NULL) == HY_OK, "t, u, y NULL, err NULL");
    /* a failure deep in the pipeline with err NULL (Jiles-Atherton does not
       settle on 2 points: the message is rewritten to name the model's key;
       that read err->msg, a crash with err NULL), and with err: its message */
    static const char ja[] = "[model]\nkind = jiles-atherton\n";
    int rc = hy_steady_loop(NULL, ja, input, NULL, 0, 2, t, u, y, NULL);
    CHECK(rc != HY_OK, "a model that does not settle, err NULL: refused (%d), no crash", rc);
    CHECK(hy_steady_loop(NULL, ja, input, NULL, 0, 2, t, u, y, &err) == rc && strstr(err.msg, "<scene>:1:1:"),
          "the same with err: %d %s", rc, err.msg);
    int untouched = 1;
    for (int i = 0; i < N; i++)
        untouched &= t[i] == -1 && u[i] == -1 && y[i] == -1;
    CHECK(untouched, "the arrays are not written by a refused call");
    CHECK(hy_steady_loop("s", model, input, sets, 1, P, t, u, y, &err) == HY_OK, "steady_loop: %s", err.msg);
    hy_result *r = NULL;
    CHECK(hy_result_from_text("s", whole, sizeof whole - 1, sets, 1, 0, &r, &err) == HY_OK && r, "the scene: %s",
          err.msg);
    CHECK(hy_result_series_copy(r, 0, t2, u2, N) == N && hy_result_series_copy(r, 1, NULL, y2, N) == N,
          "the scene's series have %d points", N);
    hy_result_free(r);
    CHECK(!memcmp(t, t2, sizeof t) && !memcmp(u, u2, sizeof u) && !memcmp(y, y2, sizeof y),
          "steady_loop's arrays are the scene's series bit for bit");
    CHECK(t[0] == 0 && u[0] == 0 && y[0] == y[P] && t[P] > 0, "one period: t from 0, y(0) = y(T)");
    CHECK(hy_steady_loop("s", "[model]\nkind = lugre\nsigma0 = 6", "[input]\nkind = bimodal", sets, 1, P, t2, u2, y2,
                         &err) == HY_OK, "sections without their last line break: %s", err.msg);
    CHECK(!memcmp(t, t2, sizeof t) && !memcmp(u, u2, sizeof u) && !memcmp(y, y2, sizeof y),
          "sections without their last line break read the same");
}

int main(int argc, char **argv)
{
    if (argc != 2) {
        fprintf(stderr, "usage: test_contracts ABI-LIST (tests/libhystviz/abi.txt)\n");
        return 2;
    }
    int core = tc_core();
    core_readers();
    makers();
    hy_result *r = good();
    if (r) {
        readers(r);
        outputs(r);
    }
    hy_result_free(r);
    writer();
    fitter();
    sweeper();
    steady();
    int missed = tc_coverage(argv[1]);
    return tu_finish("contracts") | core | (missed != 0);
}
