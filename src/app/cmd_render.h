/* SPDX-License-Identifier: MIT */
/* cmd_render.h: `hystviz render` and `hystviz data` (argv[0] names which). */
#ifndef HY_CMD_RENDER_H
#define HY_CMD_RENDER_H
int hy_cmd_render(int argc, char **argv);
#endif
