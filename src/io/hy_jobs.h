/* SPDX-License-Identifier: MIT */
/* hy_jobs.h: the default number of worker threads of every command with -j
 * (sweep, gallery, animate) and of serve's concurrent renders: the CPUs this
 * process may run on (sched_getaffinity: taskset, a Slurm task's cpuset),
 * capped by its cgroup's CPU quota (cgroup v2 cpu.max, v1
 * cpu.cfs_quota_us / cpu.cfs_period_us, of the process's own cgroup and its
 * parents), rounded up, at least 1.
 *
 *     long jobs = hy_jobs_default();
 *
 * -j's one description, with this default, is cli_jobs_opts (cli_util.h).
 */
#ifndef HY_JOBS_H
#define HY_JOBS_H

#include <stdio.h>

/* The default -j (>= 1).  Never fails: what cannot be read does not cap. */
long hy_jobs_default(void);

/* CPUs (rounded up, >= 1) of a cgroup v2 cpu.max text "QUOTA PERIOD"
 * ("max PERIOD": no limit); 0 for no limit, -1 for a text that is not one. */
long hy_jobs_parse_cpu_max(const char *text);

/* The same from cgroup v1's cpu.cfs_quota_us and cpu.cfs_period_us texts
 * ("-1": no limit). */
long hy_jobs_parse_cfs(const char *quota, const char *period);

/* The quota (CPUs, 0 none) of the cgroup that proc_cgroup (the text of
 * /proc/self/cgroup) names, read under sysfs (normally "/sys/fs/cgroup"):
 * the smallest of its own and its parents' limits. */
long hy_jobs_cgroup_quota(const char *proc_cgroup, const char *sysfs);

#endif
