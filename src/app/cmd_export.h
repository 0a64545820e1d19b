/* SPDX-License-Identifier: MIT */
/* cmd_export.h: `hystviz export`: an interactive figure as one offline HTML
 * file, the scene's SVG at every point of a sweep grid behind a slider per
 * grid key, in shards like sweep (issue 21 item 6). */
#ifndef HY_CMD_EXPORT_H
#define HY_CMD_EXPORT_H

/* argv[0] is "export".  Returns the exit status (0 the page is written, 1 a
 * point failed to compute or an I/O error, 2 usage error or invalid input). */
int hy_cmd_export(int argc, char **argv);

#endif
