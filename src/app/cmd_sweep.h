/* SPDX-License-Identifier: MIT */
/* cmd_sweep.h: `hystviz sweep`: a figure and a table row per point of a
 * parameter grid, split into shards for GNU parallel or Slurm (issue 13). */
#ifndef HY_CMD_SWEEP_H
#define HY_CMD_SWEEP_H

/* argv[0] is "sweep".  Returns the exit status (0 ok, 1 a point failed while
 * computing or an I/O error, 2 usage error or invalid input). */
int hy_cmd_sweep(int argc, char **argv);

#endif
