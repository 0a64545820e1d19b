/* SPDX-License-Identifier: MIT */
/* cmd_fit.h: the `fit` subcommand (today: --benchmark boucwen). */
#ifndef HY_CMD_FIT_H
#define HY_CMD_FIT_H
/* Runs `hystviz fit` (argv[0] "fit"); returns the exit status. */
int hy_cmd_fit(int argc, char **argv);
#endif
