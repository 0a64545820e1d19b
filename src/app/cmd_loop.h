/* SPDX-License-Identifier: MIT */
/* cmd_loop.h: the `loop` and `loops` subcommands (argv[0] names which). */
#ifndef HY_CMD_LOOP_H
#define HY_CMD_LOOP_H
int hy_cmd_loop(int argc, char **argv);
#endif
