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

/* Runs the subcommand; returns the process exit status: 0 success, 1 a
 * computation or file error, 2 a usage error (message on stderr). */
int hy_cmd_boucwen(int argc, char **argv);

#endif
