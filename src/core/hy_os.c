/* SPDX-License-Identifier: MIT */
/* hy_os.c: the monotonic clock and path joining every floor shares (hy_os.h). */
#include "hy_os.h"

#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "hy_file.h"

double hy_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

char *hy_path_join(const char *dir, const char *file)
{
    size_t a = strlen(dir), b = strlen(file);
    char *p = malloc(a + b + 2);
    if (p) {
        memcpy(p, dir, a);
        p[a] = '/';
        memcpy(p + a + 1, file, b + 1);
    }
    return p;
}

char *hy_path_dir(const char *path)
{
    const char *slash = strrchr(path, '/');
    if (!slash)
        return strdup(".");
    return strndup(path, slash == path ? 1 : (size_t)(slash - path));
}

void *hy_grow(void *p, size_t n, size_t *cap, size_t size, size_t first)
{
    if (n < *cap)
        return p;
    size_t c = *cap ? 2 * *cap : first;
    void *q = realloc(p, c * size);
    if (q)
        *cap = c;
    return q;
}

int hy_file_status(int e)
{
    return e == ENOENT || e == EACCES || e == EIO ? HY_EIO : HY_EINVAL;
}

int hy_file_load(const char *path, size_t max, char **buf, size_t *len, const char *what, hy_error *err)
{
    char why[200];
    int e = hy_file_read(path, max, buf, len, NULL, why, sizeof why);
    return e ? hy_error_set(err, hy_file_status(e), "%s: %s: %s", path, what, why) : HY_OK;
}
