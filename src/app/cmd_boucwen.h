/* SPDX-License-Identifier: MIT */
/* cmd_boucwen.h: the `hystviz boucwen` subcommand (the Bouc-Wen benchmark).
 *
 *     hystviz boucwen table2 [--set-param name=value]...
 *     hystviz boucwen data --signal multisine|validation|validation-sweep|sweep|sine|file ... [-o FILE]
 *     hystviz boucwen --help
 *
 * main() calls hy_cmd_boucwen(argc - 1, argv + 1) so that argv[0] is
 * "boucwen".  Messages go to stderr, results to stdout or the -o file.
 */
#ifndef CMD_BOUCWEN_H
#define CMD_BOUCWEN_H

#include <stddef.h>

/* Runs the subcommand; returns the process exit status: 0 success, 1 a
 * computation or file error, 2 a usage error (message on stderr). */
int hy_cmd_boucwen(int argc, char **argv);

/* The path of the benchmark's data file `file` (uval_multisine.txt, ...) in
 * data_dir when given (not checked), else the first folder holding it of
 * $HY_BOUCWEN_DATA, the installed copy and the source tree's
 * tests/data/boucwen (a build run before `meson install`).  0, or -1 when
 * none holds it. */
int hy_cmd_boucwen_data_file(const char *data_dir, const char *file, char *path, size_t size);

#endif
