/* SPDX-License-Identifier: MIT */
/* cmd_serve.h: `hystviz serve` (live preview in the browser) and `hystviz watch`. */
#ifndef HY_CMD_SERVE_H
#define HY_CMD_SERVE_H

int hy_cmd_serve(int argc, char **argv);
int hy_cmd_watch(int argc, char **argv);

#endif
