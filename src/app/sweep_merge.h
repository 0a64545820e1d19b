/* SPDX-License-Identifier: MIT */
/* sweep_merge.h: the shard manifests of `hystviz sweep --shard K/N` and
 * `hystviz sweep --merge DIR`, which joins them into DIR/sweep.csv.
 *
 * A shard manifest DIR/sweep.shard-K-of-N.csv is the first line
 *     # hystviz sweep shard K/N points P study HASH
 * then the table header and the rows of points K, K + N, K + 2N, ... in that
 * order, exactly as sweep.csv holds them.  With --table npy it is
 * DIR/sweep.shard-K-of-N.npy: the same first line, then an .npy file of
 * those rows (its shape the shard's row count); the merge writes sweep.npy
 * with shape (P,) and the records in point order.  It is written whole (temporary
 * name, renamed when the shard is done), so a killed shard leaves none.
 * The first line may go on with "\tCWD\tsweep ARGS": the shard's working
 * directory and arguments (without -j and --shard), quoted for sh, from
 * which the merge prints the command that re-runs a missing shard.
 */
#ifndef HY_SWEEP_MERGE_H
#define HY_SWEEP_MERGE_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "hy_sweep.h" /* hy_npy_header */

/* DIR/sweep.shard-K-of-N.EXT into buf (EXT: csv, npy). */
void hy_sweep_shard_path(const char *dir, long k, long n, const char *ext, char *buf, size_t size);

/* The re-run text of a shard run with argv ("sweep" ARGS...): "\tCWD\tsweep
 * ARGS" quoted for sh, without -j/--jobs N and --shard K/N; NULL when the
 * directory or an argument holds a tab or newline, or out of memory.  The
 * caller frees it. */
char *hy_sweep_shard_rerun(int argc, char **argv);

/* Writes the manifest's first line; rerun (or NULL) from hy_sweep_shard_rerun. */
void hy_sweep_shard_head(FILE *f, long k, long n, size_t npoints, uint64_t hash, const char *rerun);

/* Joins DIR's shard manifests into DIR/sweep.csv and removes them.  Refuses
 * (2, message listing them, with the commands that re-run them: by hand or
 * GNU parallel, and as Slurm tasks of tools/cluster/shard.sbatch, found in
 * $HYSTVIZ_CLUSTER, else tools/cluster; program $HYSTVIZ, else hystviz)
 * when shards are missing, come from another study
 * or split, or are damaged; 1 on an I/O error; else the status the unsharded
 * run would have had (0 all ok, 2 a point invalid, 1 a point failed).  plot
 * (or NULL): then draws the summary figure of that column (sweep_plot.h). */
int hy_sweep_merge(const char *dir, const char *plot, int quiet);

#endif
