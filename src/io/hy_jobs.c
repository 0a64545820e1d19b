/* SPDX-License-Identifier: MIT */
/* hy_jobs.c: the default -j: CPUs of the affinity mask (sched_getaffinity)
 * capped by the cgroup CPU quota (cgroup v2 cpu.max, v1 cfs quota/period),
 * ceil(quota / period), at least 1.  See hy_jobs.h. */
#define _GNU_SOURCE
#include "hy_jobs.h"

#include <errno.h>
#include <sched.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

/* Reads up to size-1 bytes of path into buf; 0 ok, -1 unreadable. */
static int read_text(const char *path, char *buf, size_t size)
{
    FILE *f = fopen(path, "r");
    if (!f)
        return -1;
    size_t n = fread(buf, 1, size - 1, f);
    int bad = ferror(f);
    fclose(f);
    buf[n] = 0;
    return bad ? -1 : 0;
}

/* A whole number >= 1 at *s (then *s moves past it); -1 if none. */
static long long parse_count(const char **s)
{
    char *end;
    if (**s < '0' || **s > '9') /* strtoll would take spaces and signs */
        return -1;
    errno = 0;
    long long v = strtoll(*s, &end, 10);
    if (end == *s || errno || v < 1)
        return -1;
    *s = end;
    return v;
}

static long ceil_div(long long q, long long p)
{
    long long c = (q + p - 1) / p;
    return c < 1 ? 1 : c > 1L << 20 ? 1L << 20 : (long)c;
}

long hy_jobs_parse_cpu_max(const char *text)
{
    const char *s = text;
    long long q = -2;
    if (!strncmp(s, "max", 3))
        s += 3;
    else if ((q = parse_count(&s)) < 0)
        return -1;
    if (*s != ' ')
        return -1;
    s++;
    long long p = parse_count(&s);
    if (p < 0 || (*s && strcmp(s, "\n")))
        return -1;
    return q == -2 ? 0 : ceil_div(q, p);
}

long hy_jobs_parse_cfs(const char *quota, const char *period)
{
    const char *s = period;
    long long p = parse_count(&s);
    if (p < 0 || (*s && strcmp(s, "\n")))
        return -1;
    if (!strcmp(quota, "-1") || !strcmp(quota, "-1\n"))
        return 0;
    s = quota;
    long long q = parse_count(&s);
    if (q < 0 || (*s && strcmp(s, "\n")))
        return -1;
    return ceil_div(q, p);
}

/* dir/name into path (a truncated path is not read: 0, no quota). */
static int file_in(char *path, size_t size, const char *dir, const char *name)
{
    int n = snprintf(path, size, "%s/%s", dir, name);
    return n > 0 && (size_t)n < size;
}

/* The quota (0: none) in directory dir: v2 cpu.max, else v1 cfs files. */
static long dir_quota(const char *dir, int v2)
{
    char path[4400], a[128], b[128];
    if (v2) {
        long c = !file_in(path, sizeof path, dir, "cpu.max") || read_text(path, a, sizeof a) ? 0
                                                                                              : hy_jobs_parse_cpu_max(a);
        return c > 0 ? c : 0;
    }
    if (!file_in(path, sizeof path, dir, "cpu.cfs_quota_us") || read_text(path, a, sizeof a))
        return 0;
    if (!file_in(path, sizeof path, dir, "cpu.cfs_period_us") || read_text(path, b, sizeof b))
        return 0;
    long c = hy_jobs_parse_cfs(a, b);
    return c > 0 ? c : 0;
}

/* The smallest quota of mount/cg and each of its parents up to mount. */
static long walk_quota(const char *mount, const char *cg, int v2)
{
    char dir[4400];
    if (snprintf(dir, sizeof dir, "%s%s", mount, cg) >= (int)sizeof dir)
        return 0;
    size_t root = strlen(mount);
    long best = 0;
    for (;;) {
        size_t n = strlen(dir);
        while (n > root && dir[n - 1] == '/')
            dir[--n] = 0;
        long c = dir_quota(dir, v2);
        if (c > 0 && (!best || c < best))
            best = c;
        char *slash = strrchr(dir, '/');
        if (n <= root || !slash || (size_t)(slash - dir) < root)
            break;
        *slash = 0;
    }
    return best;
}

/* Whether the comma list ctl names the controller "cpu". */
static int has_cpu(const char *ctl, size_t len)
{
    for (size_t i = 0; i < len;) {
        size_t j = i;
        while (j < len && ctl[j] != ',')
            j++;
        if (j - i == 3 && !strncmp(ctl + i, "cpu", 3))
            return 1;
        i = j + 1;
    }
    return 0;
}

long hy_jobs_cgroup_quota(const char *proc_cgroup, const char *sysfs)
{
    static const char *const v1_mounts[] = {"cpu", "cpu,cpuacct", "cpuacct,cpu"};
    long best = 0;
    for (const char *line = proc_cgroup; *line;) {
        const char *eol = strchr(line, '\n');
        size_t len = eol ? (size_t)(eol - line) : strlen(line);
        const char *c1 = memchr(line, ':', len);
        const char *c2 = c1 ? memchr(c1 + 1, ':', len - (size_t)(c1 + 1 - line)) : NULL;
        char cg[4096];
        size_t cglen = c2 ? len - (size_t)(c2 + 1 - line) : 0;
        if (c2 && cglen < sizeof cg && c2[1] == '/') {
            memcpy(cg, c2 + 1, cglen);
            cg[cglen] = 0;
            long c = 0;
            char mount[4400];
            if (c2 == c1 + 1 && !strncmp(line, "0:", 2)) /* v2: "0::/path" */
                c = walk_quota(sysfs, cg, 1);
            else if (has_cpu(c1 + 1, (size_t)(c2 - c1 - 1)))
                for (size_t m = 0; m < sizeof v1_mounts / sizeof *v1_mounts && !c; m++) {
                    snprintf(mount, sizeof mount, "%s/%s", sysfs, v1_mounts[m]);
                    if (access(mount, F_OK) == 0)
                        c = walk_quota(mount, cg, 0);
                }
            if (c > 0 && (!best || c < best))
                best = c;
        }
        line += len + (eol != NULL);
    }
    return best;
}

/* CPUs in this process's affinity mask; 0 if unknown. */
static long affinity_cpus(void)
{
    for (int ncpu = 1024; ncpu <= 1 << 20; ncpu *= 4) {
        cpu_set_t *set = CPU_ALLOC((size_t)ncpu);
        if (!set)
            return 0;
        size_t size = CPU_ALLOC_SIZE((size_t)ncpu);
        CPU_ZERO_S(size, set);
        if (sched_getaffinity(0, size, set) == 0) {
            long n = CPU_COUNT_S(size, set);
            CPU_FREE(set);
            return n;
        }
        int e = errno;
        CPU_FREE(set);
        if (e != EINVAL)
            return 0;
    }
    return 0;
}

long hy_jobs_default(void)
{
    long n = affinity_cpus();
    if (n < 1) {
        n = sysconf(_SC_NPROCESSORS_ONLN);
        n = n > 0 ? n : 1;
    }
    char text[16384];
    if (read_text("/proc/self/cgroup", text, sizeof text) == 0) {
        long q = hy_jobs_cgroup_quota(text, "/sys/fs/cgroup");
        if (q > 0 && q < n)
            n = q;
    }
    return n;
}
