/* SPDX-License-Identifier: MIT */
/* cmd_forc.h: the `forc` subcommand (FORC distribution of a file or a Preisach model). */
#ifndef HY_CMD_FORC_H
#define HY_CMD_FORC_H
int hy_cmd_forc(int argc, char **argv);
#endif
