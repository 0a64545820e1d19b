/* SPDX-License-Identifier: MIT */
/* hy_grid.c: grid specs (list, linear and log ranges), the row-major point
 * numbering of their Cartesian product, the i mod N shard partition and the
 * shard files of a split (sweep, export). */
#include "hy_grid.h"

#include <dirent.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

void hy_grid_init(hy_grid *g)
{
    memset(g, 0, sizeof *g);
    g->npoints = 1;
}

void hy_grid_format(double v, char *buf, size_t size)
{
    for (int prec = 15; prec <= 17; prec++) {
        snprintf(buf, size, "%.*g", prec, v);
        if (strtod(buf, NULL) == v)
            return;
    }
}

static void free_values(char **v, size_t n)
{
    for (size_t i = 0; v && i < n; i++)
        free(v[i]);
    free(v);
}

/* A finite number filling the whole of [s, s + n). */
static int range_num(const char *s, size_t n, double *out)
{
    char buf[64];
    if (n == 0 || n >= sizeof buf)
        return -1;
    memcpy(buf, s, n);
    buf[n] = '\0';
    char *end;
    errno = 0;
    *out = strtod(buf, &end);
    return *end || end == buf || !isfinite(*out) ? -1 : 0;
}

/* The values of "A:B:N" or "A:B:logN" into *out. */
static int parse_range(const char *arg, const char *spec, char ***out, size_t *nout, hy_error *err)
{
    const char *c1 = strchr(spec, ':'), *c2 = c1 ? strchr(c1 + 1, ':') : NULL;
    double a, b;
    if (!c2 || strchr(c2 + 1, ':') || range_num(spec, (size_t)(c1 - spec), &a) ||
        range_num(c1 + 1, (size_t)(c2 - c1 - 1), &b))
        return hy_error_set(err, HY_EINVAL, "--grid %s: a range is FROM:TO:COUNT or FROM:TO:logCOUNT with finite bounds", arg);
    const char *cnt = c2 + 1;
    int is_log = !strncmp(cnt, "log", 3);
    if (is_log)
        cnt += 3;
    char *end;
    errno = 0;
    unsigned long n = strtoul(cnt, &end, 10);
    if (end == cnt || *end || errno || cnt[0] == '-' || cnt[0] == '+' || n < 1 || n > HY_GRID_MAX_VALUES)
        return hy_error_set(err, HY_EINVAL, "--grid %s: the count '%s' is not an integer in [1, %lu]", arg, cnt,
                            HY_GRID_MAX_VALUES);
    if (n == 1 && a != b)
        return hy_error_set(err, HY_EINVAL, "--grid %s: a range of one value needs FROM = TO", arg);
    if (is_log && (a <= 0 || b <= 0))
        return hy_error_set(err, HY_EINVAL, "--grid %s: a log range needs bounds > 0", arg);
    char **v = calloc(n, sizeof *v);
    if (!v)
        return hy_error_set(err, HY_ENOMEM, "out of memory");
    double la = is_log ? log10(a) : a, lb = is_log ? log10(b) : b;
    for (unsigned long i = 0; i < n; i++) {
        double x;
        if (i == 0)
            x = a;
        else if (i == n - 1)
            x = b;
        else {
            double t = (double)i / (double)(n - 1), m = la * (1 - t) + lb * t;
            x = is_log ? pow(10.0, m) : m;
        }
        char buf[40];
        hy_grid_format(x, buf, sizeof buf);
        if (!(v[i] = strdup(buf))) {
            free_values(v, i);
            return hy_error_set(err, HY_ENOMEM, "out of memory");
        }
    }
    *out = v;
    *nout = n;
    return HY_OK;
}

/* The items of "V1,V2,..." (spaces around each trimmed, none empty) into *out. */
static int parse_list(const char *arg, const char *spec, char ***out, size_t *nout, hy_error *err)
{
    size_t n = 1;
    for (const char *c = spec; *c; c++)
        n += *c == ',';
    if (n > HY_GRID_MAX_VALUES)
        return hy_error_set(err, HY_EINVAL, "--grid %s: more than %lu values", arg, HY_GRID_MAX_VALUES);
    char **v = calloc(n, sizeof *v);
    if (!v)
        return hy_error_set(err, HY_ENOMEM, "out of memory");
    const char *s = spec;
    for (size_t i = 0; i < n; i++) {
        const char *e = strchr(s, ',');
        if (!e)
            e = s + strlen(s);
        const char *b = s, *t = e;
        while (b < t && (*b == ' ' || *b == '\t'))
            b++;
        while (t > b && (t[-1] == ' ' || t[-1] == '\t'))
            t--;
        if (b == t) {
            free_values(v, i);
            return hy_error_set(err, HY_EINVAL, "--grid %s: value %zu of the list is empty", arg, i + 1);
        }
        if (!(v[i] = strndup(b, (size_t)(t - b)))) {
            free_values(v, i);
            return hy_error_set(err, HY_ENOMEM, "out of memory");
        }
        s = e + 1;
    }
    *out = v;
    *nout = n;
    return HY_OK;
}

int hy_grid_add(hy_grid *g, const char *arg, hy_error *err)
{
    const char *eq = strchr(arg, '=');
    if (!eq || eq == arg || !memchr(arg, '.', (size_t)(eq - arg)) || !eq[1])
        return hy_error_set(err, HY_EINVAL, "--grid '%s': expected SECTION.KEY=SPEC (e.g. model.sigma0=1:10:log10)", arg);
    size_t klen = (size_t)(eq - arg);
    for (size_t a = 0; a < g->naxes; a++)
        if (strlen(g->axes[a].key) == klen && !strncmp(g->axes[a].key, arg, klen))
            return hy_error_set(err, HY_EINVAL, "--grid %s: the key %.*s is already a grid axis", arg, (int)klen, arg);
    const char *spec = eq + 1;
    char **v = NULL;
    size_t n = 0;
    int rc = strchr(spec, ':') ? parse_range(arg, spec, &v, &n, err) : parse_list(arg, spec, &v, &n, err);
    if (rc)
        return rc;
    if (g->npoints > HY_GRID_MAX_POINTS / n) {
        free_values(v, n);
        return hy_error_set(err, HY_EINVAL, "--grid %s: the grid would have more than %lu points", arg, HY_GRID_MAX_POINTS);
    }
    hy_grid_axis *axes = realloc(g->axes, (g->naxes + 1) * sizeof *axes);
    char *key = strndup(arg, klen), *sp = strdup(spec);
    if (!axes || !key || !sp) {
        if (axes)
            g->axes = axes;
        free(key);
        free(sp);
        free_values(v, n);
        return hy_error_set(err, HY_ENOMEM, "out of memory");
    }
    g->axes = axes;
    g->axes[g->naxes++] = (hy_grid_axis){key, sp, v, n};
    g->npoints *= n;
    return HY_OK;
}

size_t hy_grid_points(const hy_grid *g)
{
    return g->npoints;
}

size_t hy_grid_coord(const hy_grid *g, size_t i, size_t a)
{
    size_t stride = 1;
    for (size_t b = g->naxes; b-- > a + 1;)
        stride *= g->axes[b].nvalues;
    return i / stride % g->axes[a].nvalues;
}

const char *hy_grid_value(const hy_grid *g, size_t i, size_t a)
{
    return g->axes[a].values[hy_grid_coord(g, i, a)];
}

void hy_grid_free(hy_grid *g)
{
    for (size_t a = 0; a < g->naxes; a++) {
        free(g->axes[a].key);
        free(g->axes[a].spec);
        free_values(g->axes[a].values, g->axes[a].nvalues);
    }
    free(g->axes);
    hy_grid_init(g);
}

int hy_shard_parse(const char *s, long *k, long *n, hy_error *err)
{
    char *end1, *end2 = NULL;
    errno = 0;
    long kk = strtol(s, &end1, 10);
    long nn = end1 != s && *end1 == '/' ? strtol(end1 + 1, &end2, 10) : 0;
    if (end1 == s || *end1 != '/' || end2 == end1 + 1 || *end2 || errno || s[0] == '+' || end1[1] == '+' ||
        nn < 1 || nn > HY_SHARD_MAX || kk < 0 || kk >= nn)
        return hy_error_set(err, HY_EINVAL, "--shard '%s': expected K/N with 0 <= K < N <= %ld (e.g. --shard 0/8)", s,
                            HY_SHARD_MAX);
    *k = kk;
    *n = nn;
    return HY_OK;
}

size_t hy_shard_count(size_t n, long k, long nshards)
{
    return (size_t)k < n ? (n - (size_t)k + (size_t)nshards - 1) / (size_t)nshards : 0;
}

/* K and N of a shard file's name PREFIX K-of-N SUFFIX; 0 if name is not one
 * (no "+1" or "01" aliases). */
static int shard_name(const char *name, const char *prefix, const char *suffix, long *k, long *n)
{
    size_t lp = strlen(prefix), ls = strlen(suffix), ln = strlen(name);
    int end = 0;
    if (ln <= lp + ls || strncmp(name, prefix, lp) || strcmp(name + ln - ls, suffix) ||
        sscanf(name + lp, "%ld-of-%ld%n", k, n, &end) != 2 || (size_t)end != ln - lp - ls || *n < 1 ||
        *n > HY_SHARD_MAX || *k < 0 || *k >= *n)
        return 0;
    char canon[64];
    snprintf(canon, sizeof canon, "%ld-of-%ld", *k, *n);
    return strlen(canon) == (size_t)end && !strncmp(canon, name + lp, (size_t)end);
}

int hy_shard_find(const char *dir, const char *prefix, const char *suffix, long *nshards, unsigned char **present,
                  hy_error *err)
{
    DIR *d = opendir(dir);
    *present = NULL;
    if (!d)
        return hy_error_set(err, HY_EINVAL, "%s: cannot open the directory: %s", dir, strerror(errno));
    long n = 0, other = 0;
    for (struct dirent *de; (de = readdir(d));) {
        long k, nn;
        if (!shard_name(de->d_name, prefix, suffix, &k, &nn))
            continue;
        if (n && nn != n) {
            other = nn;
            continue;
        }
        if (!n) {
            n = nn;
            if (!(*present = calloc((size_t)n, 1))) {
                closedir(d);
                return hy_error_set(err, HY_ENOMEM, "out of memory");
            }
        }
        (*present)[k] = 1;
    }
    closedir(d);
    if (!n)
        return hy_error_set(err, HY_EINVAL, "%s holds no shard manifests (%sK-of-N%s)", dir, prefix, suffix);
    if (other) {
        free(*present);
        *present = NULL;
        return hy_error_set(err, HY_EINVAL,
                            "%s holds shards of two splits (of %ld and of %ld): remove the stale ones (%s*-of-N%s) "
                            "and merge again",
                            dir, n, other, prefix, suffix);
    }
    *nshards = n;
    return HY_OK;
}

long hy_shard_missing(long n, const unsigned char *present, char *buf, size_t size)
{
    long missing = 0, shown = 0;
    size_t len = 0;
    buf[0] = '\0';
    for (long k = 0; k < n; k++)
        if (!present[k] && ++missing && shown < 20 && len < size) {
            len += (size_t)snprintf(buf + len, size - len, "%s %ld/%ld", shown ? "," : "", k, n);
            shown++;
        }
    if (missing > shown && len < size)
        snprintf(buf + len, size - len, ", ...");
    return missing;
}
