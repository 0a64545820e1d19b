/* SPDX-License-Identifier: MIT */
/* test_lib.c SCENE HYSTVIZ: libhystviz's pipeline API (hystviz.h), linked
 * against the shared library (only what it exports):
 *  - a scene's CSV equals what `hystviz data` prints for it, byte for byte;
 *  - results computed on four threads at once equal those computed one after
 *    another (no global state);
 *  - a refused scene gives HY_EINVAL and a message starting NAME:LINE:COL;
 *  - the loops of Fig. 15 are there, with one minor loop of positive area. */
#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hystviz.h"

#include "../hy_test.h"

static const char *scene;
#define CHECK HY_CHECK /* tests/hy_test.h */

static char *csv_of(double sigma0)
{
    char set[64];
    snprintf(set, sizeof set, "model.sigma0=%.17g", sigma0);
    const char *sets[] = {set};
    hy_result *r;
    hy_error err;
    if (hy_result_from_file(scene, sets, 1, 0, &r, &err)) {
        printf("FAIL: %s\n", err.msg);
        return NULL;
    }
    char *text;
    size_t len;
    int rc = hy_result_csv(r, &text, &len, &err);
    hy_result_free(r);
    return rc ? NULL : text;
}

static void *worker(void *arg)
{
    return csv_of(*(const double *)arg);
}

static char *run_cli(const char *hv)
{
    char cmd[8192];
    snprintf(cmd, sizeof cmd, "'%s' data '%s'", hv, scene);
    FILE *p = popen(cmd, "r");
    if (!p)
        return NULL;
    size_t cap = 1 << 16, n = 0;
    char *buf = malloc(cap);
    size_t got;
    while (buf && (got = fread(buf + n, 1, cap - n - 1, p)) > 0)
        if ((n += got) + 1 == cap) {
            char *b = realloc(buf, cap *= 2);
            if (!b)
                free(buf);
            buf = b;
        }
    if (pclose(p) != 0 || !buf) {
        free(buf);
        return NULL;
    }
    buf[n] = '\0';
    return buf;
}

int main(int argc, char **argv)
{
    if (argc != 3) {
        fprintf(stderr, "usage: test_lib SCENE HYSTVIZ\n");
        return 2;
    }
    scene = argv[1];
    CHECK(strcmp(hy_version(), "") != 0, "no version");
    /* the headers' version macros and the library's version come from meson's one project version */
    CHECK(strcmp(hy_version(), HYSTVIZ_VERSION_STRING) == 0, "hy_version() %s, the headers %s", hy_version(),
          HYSTVIZ_VERSION_STRING);
    char made[64];
    snprintf(made, sizeof made, "%d.%d.%d", HYSTVIZ_VERSION_MAJOR, HYSTVIZ_VERSION_MINOR, HYSTVIZ_VERSION_PATCH);
    CHECK(strcmp(made, HYSTVIZ_VERSION_STRING) == 0, "MAJOR.MINOR.PATCH %s, HYSTVIZ_VERSION_STRING %s", made,
          HYSTVIZ_VERSION_STRING);
    CHECK(HYSTVIZ_VERSION_CHECK(HYSTVIZ_VERSION_MAJOR, HYSTVIZ_VERSION_MINOR, HYSTVIZ_VERSION_PATCH) &&
              HYSTVIZ_VERSION_CHECK(0, 0, 0) &&
              !HYSTVIZ_VERSION_CHECK(HYSTVIZ_VERSION_MAJOR, HYSTVIZ_VERSION_MINOR, HYSTVIZ_VERSION_PATCH + 1) &&
              !HYSTVIZ_VERSION_CHECK(HYSTVIZ_VERSION_MAJOR + 1, 0, 0),
          "HYSTVIZ_VERSION_CHECK: true for this version and older, false for newer");

    /* the CLI's numbers */
    hy_result *r;
    hy_error err;
    CHECK(hy_result_from_file(scene, NULL, 0, 0, &r, &err) == HY_OK, "load: %s", err.msg);
    char *mine = NULL, *cli = run_cli(argv[2]);
    size_t len;
    if (r && !hy_result_csv(r, &mine, &len, &err))
        CHECK(cli && strcmp(mine, cli) == 0, "hy_result_csv differs from hystviz data");
    const hy_loops *L = r ? hy_result_loops(r) : NULL;
    CHECK(L && L->nminor == 1 && L->minor[0].area > 0, "Fig. 15: one minor loop of positive area");
    CHECK(r && hy_result_nseries(r) == 4 && strcmp(hy_result_series_data(r, 1), "minor") == 0,
          "series 1 of Fig. 15 draws the minor loop");
    const double *x, *y;
    CHECK(r && hy_result_series(r, 99, &x, &y) == 0 && !x && !y, "series out of range: 0 points, NULL");
    unsigned char *svg;
    size_t nsvg;
    CHECK(r && hy_result_render(r, "svg", &svg, &nsvg, &err) == HY_OK && nsvg > 1000 && !memcmp(svg, "<?xml", 5),
          "render svg");
    if (r && nsvg)
        free(svg);
    CHECK(r && hy_result_render(r, "svg,pdf", &svg, &nsvg, &err) == HY_EINVAL, "two formats refused");
    free(mine);
    free(cli);
    hy_result_free(r);

    /* four threads at once == one after another */
    double sig[4] = {1, 3, 6, 20};
    char *seq[4];
    for (int i = 0; i < 4; i++)
        seq[i] = csv_of(sig[i]);
    pthread_t th[4];
    for (int i = 0; i < 4; i++)
        pthread_create(&th[i], NULL, worker, &sig[i]);
    for (int i = 0; i < 4; i++) {
        void *par;
        pthread_join(th[i], &par);
        CHECK(seq[i] && par && strcmp(seq[i], par) == 0, "thread %d differs from the sequential result", i);
        free(par);
        free(seq[i]);
    }

    /* a refused scene names file:line:col */
    const char *bad = "[model]\nkind = lugre\nsigma0 = -1\n";
    r = (hy_result *)&err; /* must become NULL */
    int rc = hy_result_from_text("bad.scene", bad, strlen(bad), NULL, 0, 0, &r, &err);
    CHECK(rc == HY_EINVAL && r == NULL, "bad scene: rc %d", rc);
    CHECK(strncmp(err.msg, "bad.scene:3:", 12) == 0, "bad scene's message: '%s'", err.msg);

    /* Bouc-Wen: a force of zero leaves the oscillator at rest */
    double u[64] = {0}, yb[64];
    CHECK(hy_boucwen_run(u, 64, 750, yb, &err) == HY_OK, "boucwen: %s", err.msg);
    int rest = 1;
    for (int i = 0; i < 64; i++)
        rest &= yb[i] == 0;
    CHECK(rest, "boucwen: zero force, non-zero output");
    CHECK(hy_boucwen_run(u, 64, -1, yb, &err) == HY_EINVAL, "boucwen: fs -1 accepted");

    char *js = hy_schema_json();
    CHECK(js && strstr(js, "\"name\":\"sigma0\"") && strstr(js, "\"sections\""), "schema JSON");
    free(js);
    return hy_test_finish("lib-api");
}
