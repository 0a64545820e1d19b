/* SPDX-License-Identifier: MIT */
/* test_jobs.c: the default -j (hy_jobs.h): the cgroup v2 cpu.max and v1 cfs
 * parsers on sample texts, the cgroup walk on a fake /sys/fs/cgroup tree (v2,
 * v1, a parent's smaller quota), and the affinity cap: pinned to one CPU the
 * default is 1. */
#define _GNU_SOURCE
#include <sched.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "hy_jobs.h"

#include "../render/rcheck.h"

static void parsers(void)
{
    CHECK(hy_jobs_parse_cpu_max("max 100000\n") == 0, "max: no limit");
    CHECK(hy_jobs_parse_cpu_max("max 100000") == 0, "max without newline");
    CHECK(hy_jobs_parse_cpu_max("150000 100000\n") == 2, "1.5 CPUs round up to 2: %ld",
          hy_jobs_parse_cpu_max("150000 100000\n"));
    CHECK(hy_jobs_parse_cpu_max("50000 100000\n") == 1, "half a CPU is 1: %ld", hy_jobs_parse_cpu_max("50000 100000\n"));
    CHECK(hy_jobs_parse_cpu_max("1000 100000\n") == 1, "a hundredth is 1");
    CHECK(hy_jobs_parse_cpu_max("400000 100000\n") == 4, "4 CPUs");
    CHECK(hy_jobs_parse_cpu_max("400001 100000\n") == 5, "a little over 4 is 5");
    const char *bad[] = {"", "\n", "max", "150000", "x 100000", "150000 0", "-5 100000", "150000 100000 7",
                         "150000  100000", "max x"};
    for (size_t i = 0; i < sizeof bad / sizeof *bad; i++)
        CHECK(hy_jobs_parse_cpu_max(bad[i]) == -1, "'%s' accepted as cpu.max: %ld", bad[i],
              hy_jobs_parse_cpu_max(bad[i]));
    CHECK(hy_jobs_parse_cfs("-1\n", "100000\n") == 0, "v1 -1: no limit");
    CHECK(hy_jobs_parse_cfs("250000\n", "100000\n") == 3, "v1 2.5 CPUs: 3");
    CHECK(hy_jobs_parse_cfs("50000\n", "100000\n") == 1, "v1 half a CPU: 1");
    CHECK(hy_jobs_parse_cfs("x\n", "100000\n") == -1, "v1 garbage quota");
    CHECK(hy_jobs_parse_cfs("50000\n", "0\n") == -1, "v1 zero period");
}

static void put(const char *root, const char *rel, const char *text)
{
    char path[4200], dir[4300];
    snprintf(path, sizeof path, "%s/%s", root, rel);
    snprintf(dir, sizeof dir, "mkdir -p '%s'", path);
    *strrchr(dir, '/') = 0;
    strcat(dir, "'");
    CHECK(system(dir) == 0, "%s", dir);
    FILE *f = fopen(path, "w");
    CHECK(f != NULL, "cannot write %s", path);
    if (f) {
        fputs(text, f);
        fclose(f);
    }
}

static void walk(void)
{
    char root[4096];
    const char *tmp = getenv("TMPDIR");
    snprintf(root, sizeof root, "%s/hy_test_jobs_XXXXXX", tmp && *tmp ? tmp : "/tmp");
    if (!mkdtemp(root)) {
        CHECK(0, "mkdtemp failed");
        return;
    }
    /* v2: the process's cgroup has no limit, its parent 1.5 CPUs, the root 3 */
    put(root, "v2/cpu.max", "300000 100000\n");
    put(root, "v2/user.slice/cpu.max", "150000 100000\n");
    put(root, "v2/user.slice/job_7/cpu.max", "max 100000\n");
    char sys[4200];
    snprintf(sys, sizeof sys, "%s/v2", root);
    long q = hy_jobs_cgroup_quota("0::/user.slice/job_7\n", sys);
    CHECK(q == 2, "v2: the parent's 1.5 CPUs cap: %ld", q);
    q = hy_jobs_cgroup_quota("0::/\n", sys);
    CHECK(q == 3, "v2 root cgroup: %ld", q);
    q = hy_jobs_cgroup_quota("0::/other\n", sys);
    CHECK(q == 3, "v2 cgroup directory missing: the root's: %ld", q);
    /* v1: cpu,cpuacct mounted together; the quota on the job's own cgroup */
    put(root, "v1/cpu,cpuacct/cpu.cfs_quota_us", "-1\n");
    put(root, "v1/cpu,cpuacct/cpu.cfs_period_us", "100000\n");
    put(root, "v1/cpu,cpuacct/slurm/job_3/cpu.cfs_quota_us", "50000\n");
    put(root, "v1/cpu,cpuacct/slurm/job_3/cpu.cfs_period_us", "100000\n");
    snprintf(sys, sizeof sys, "%s/v1", root);
    q = hy_jobs_cgroup_quota("12:memory:/slurm/job_3\n4:cpu,cpuacct:/slurm/job_3\n1:name=systemd:/\n0::/\n", sys);
    CHECK(q == 1, "v1 half a CPU: %ld", q);
    q = hy_jobs_cgroup_quota("4:cpuacct,cpu:/\n", sys);
    CHECK(q == 0, "v1 no limit: %ld", q);
    q = hy_jobs_cgroup_quota("4:cpuset:/slurm/job_3\n", sys);
    CHECK(q == 0, "v1 without the cpu controller: %ld", q);
    q = hy_jobs_cgroup_quota("garbage\n\n:::\n", sys);
    CHECK(q == 0, "garbage /proc/self/cgroup: %ld", q);
    char cmd[4300];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", root);
    CHECK(system(cmd) == 0, "%s", cmd);
}

/* Pinned to one CPU (as `taskset -c 0`), the default is 1. */
static void affinity(void)
{
    long before = hy_jobs_default();
    CHECK(before >= 1, "default %ld", before);
    cpu_set_t set;
    CPU_ZERO(&set);
    CHECK(sched_getaffinity(0, sizeof set, &set) == 0, "sched_getaffinity");
    int first = 0;
    while (first < CPU_SETSIZE && !CPU_ISSET(first, &set))
        first++;
    cpu_set_t one;
    CPU_ZERO(&one);
    CPU_SET(first, &one);
    CHECK(sched_setaffinity(0, sizeof one, &one) == 0, "sched_setaffinity");
    CHECK(hy_jobs_default() == 1, "pinned to CPU %d: default %ld", first, hy_jobs_default());
    sched_setaffinity(0, sizeof set, &set);
    CHECK(hy_jobs_default() == before, "affinity restored: %ld, was %ld", hy_jobs_default(), before);
}

int main(void)
{
    parsers();
    walk();
    affinity();
    return hy_test_finish("test_jobs");
}
