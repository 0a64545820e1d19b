/* SPDX-License-Identifier: MIT */
/* test_grid.c: hy_grid (sweep grid specs, point numbering) and the shard
 * partition, against values computed here independently. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "hy_grid.h"

#include "../render/rcheck.h"

/* Every value text of a range reads back within 4 ulp-ish of the formula
 * (1e-15 relative: pow/log10 rounding), endpoints exactly. */
static void ranges(void)
{
    hy_grid g;
    hy_error err;
    hy_grid_init(&g);
    CHECK(!hy_grid_add(&g, "model.sigma0=1:1e3:log7", &err), "log range: %s", err.msg);
    CHECK(!hy_grid_add(&g, "input.umin2=0.1:0.5:5", &err), "linear range: %s", err.msg);
    CHECK(hy_grid_points(&g) == 35, "35 points, got %zu", hy_grid_points(&g));
    for (size_t i = 0; i < 7; i++) {
        double want = pow(10.0, 0.5 * (double)i), got = strtod(g.axes[0].values[i], NULL);
        CHECK(fabs(got - want) <= 1e-15 * want, "log value %zu: %s vs %.17g", i, g.axes[0].values[i], want);
    }
    CHECK(!strcmp(g.axes[0].values[0], "1") && !strcmp(g.axes[0].values[6], "1000"), "log endpoints exact");
    const char *lin[] = {"0.1", "0.2", "0.3", "0.4", "0.5"};
    for (size_t i = 0; i < 5; i++)
        CHECK(!strcmp(g.axes[1].values[i], lin[i]), "linear value %zu: %s", i, g.axes[1].values[i]);
    /* row-major: the last axis fastest */
    for (size_t i = 0; i < 35; i++) {
        CHECK(hy_grid_coord(&g, i, 0) == i / 5 && hy_grid_coord(&g, i, 1) == i % 5, "coords of point %zu", i);
    }
    CHECK(!strcmp(hy_grid_value(&g, 17, 0), g.axes[0].values[3]) && !strcmp(hy_grid_value(&g, 17, 1), "0.3"),
          "point 17 is (3, 2)");
    hy_grid_free(&g);
}

static void formats(void)
{
    /* the shortest text that reads back: 0.1 stays 0.1, 0.1 + 0.2 needs 17 digits */
    double v[] = {0.1, 0.1 + 0.2, 1.0 / 3.0, 1e-300, 6.02214076e23, -2.5};
    const char *want[] = {"0.1", "0.30000000000000004", "0.3333333333333333", "1e-300",
                          "6.02214076e+23", "-2.5"};
    for (size_t i = 0; i < sizeof v / sizeof v[0]; i++) {
        char buf[40];
        hy_grid_format(v[i], buf, sizeof buf);
        CHECK(strtod(buf, NULL) == v[i], "%s does not read back", buf);
        CHECK(!strcmp(buf, want[i]), "format %.17g: %s, want %s", v[i], buf, want[i]);
    }
}

static void refusals(void)
{
    const char *bad[] = {"model.sigma0", "sigma0=1", "=1", "model.sigma0=", "model.sigma0=1:2", "model.sigma0=1:2:3:4",
                         "model.sigma0=1:2:0", "model.sigma0=1:2:-3", "model.sigma0=1:2:+3", "model.sigma0=1:2:1",
                         "model.sigma0=0:1:log3", "model.sigma0=-1:1:log3", "model.sigma0=a:1:3", "model.sigma0=1:inf:3",
                         "model.sigma0=1,,2", "model.sigma0=1, ,2", "model.sigma0=1:2:2000000"};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        hy_grid g;
        hy_error err = {0, ""};
        hy_grid_init(&g);
        CHECK(hy_grid_add(&g, bad[i], &err) == HY_EINVAL && strstr(err.msg, "--grid"), "'%s' accepted (%s)", bad[i],
              err.msg);
        CHECK(g.naxes == 0 && hy_grid_points(&g) == 1, "'%s' changed the grid", bad[i]);
        hy_grid_free(&g);
    }
    hy_grid g;
    hy_error err;
    hy_grid_init(&g);
    CHECK(!hy_grid_add(&g, "model.sigma0=1:2:10000", &err), "10^4 values");
    CHECK(!hy_grid_add(&g, "model.fc=1:2:10000", &err), "10^8 points");
    CHECK(hy_grid_add(&g, "model.fs=1,2", &err) == HY_EINVAL && hy_grid_points(&g) == 100000000UL, "2 x 10^8 accepted");
    CHECK(hy_grid_add(&g, "model.fc=3", &err) == HY_EINVAL, "a key twice accepted");
    CHECK(!hy_grid_add(&g, "model.fs=7", &err) && hy_grid_points(&g) == 100000000UL, "one more value-1 axis");
    hy_grid_free(&g);
}

/* The shards of n items: counts sum to n, differ by at most one, and item i
 * is in shard i mod N only. */
static void shards(void)
{
    for (long nsh = 1; nsh <= 12; nsh++)
        for (size_t n = 0; n <= 40; n++) {
            size_t sum = 0, lo = (size_t)-1, hi = 0;
            for (long k = 0; k < nsh; k++) {
                size_t c = hy_shard_count(n, k, nsh), brute = 0;
                for (size_t i = 0; i < n; i++)
                    brute += i % (size_t)nsh == (size_t)k;
                CHECK(c == brute, "count of shard %ld/%ld of %zu: %zu vs %zu", k, nsh, n, c, brute);
                sum += c;
                lo = c < lo ? c : lo;
                hi = c > hi ? c : hi;
            }
            CHECK(sum == n && hi - lo <= 1, "shards of %zu in %ld: sum %zu, sizes %zu..%zu", n, nsh, sum, lo, hi);
        }
    long k, n;
    hy_error err;
    CHECK(!hy_shard_parse("3/8", &k, &n, &err) && k == 3 && n == 8, "3/8");
    const char *bad[] = {"8/8", "-1/8", "1/0", "1", "1/", "/2", "a/2", "1/2x", "+1/2", "1/+2", "1/100001", ""};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++)
        CHECK(hy_shard_parse(bad[i], &k, &n, &err) == HY_EINVAL, "--shard '%s' accepted", bad[i]);
}

/* hy_shard_find / hy_shard_missing: the shard files of one split in a
 * directory (sweep --merge, export --merge), no aliases, two splits refused. */
static void shard_files(void)
{
    char dir[] = "/tmp/test_grid.XXXXXX", path[256], list[256];
    CHECK(mkdtemp(dir) != NULL, "mkdtemp");
    const char *names[] = {"p.html.shard-0-of-3", "p.html.shard-2-of-3", "p.html.shard-01-of-3",
                           "p.html.shard-+1-of-3", "q.html.shard-1-of-3", "p.html.shard-1-of-3.x"};
    for (size_t i = 0; i < sizeof names / sizeof names[0]; i++) {
        snprintf(path, sizeof path, "%s/%s", dir, names[i]);
        FILE *f = fopen(path, "w");
        CHECK(f && !fclose(f), "cannot create %s", path);
    }
    long n = 0;
    unsigned char *present = NULL;
    hy_error err = {0};
    CHECK(!hy_shard_find(dir, "p.html.shard-", "", &n, &present, &err) && n == 3, "find: %s", err.msg);
    CHECK(present && present[0] && !present[1] && present[2], "shard 1/3 (only as aliases) counted present");
    CHECK(present && hy_shard_missing(n, present, list, sizeof list) == 1 && !strcmp(list, " 1/3"), "missing: '%s'", list);
    free(present);
    CHECK(hy_shard_find(dir, "r.html.shard-", "", &n, &present, &err) == HY_EINVAL && strstr(err.msg, "no shard"),
          "no shards: %s", err.msg);
    snprintf(path, sizeof path, "%s/p.html.shard-0-of-4", dir);
    FILE *f = fopen(path, "w");
    CHECK(f && !fclose(f), "cannot create %s", path);
    CHECK(hy_shard_find(dir, "p.html.shard-", "", &n, &present, &err) == HY_EINVAL && strstr(err.msg, "two splits") &&
              !present, "two splits: %s", err.msg);
    for (size_t i = 0; i < sizeof names / sizeof names[0]; i++) {
        snprintf(path, sizeof path, "%s/%s", dir, names[i]);
        remove(path);
    }
    snprintf(path, sizeof path, "%s/p.html.shard-0-of-4", dir);
    remove(path);
    CHECK(!rmdir(dir), "test directory left non-empty");
}

int main(void)
{
    shard_files();
    ranges();
    formats();
    refusals();
    shards();
    return hy_test_finish("test_grid");
}
