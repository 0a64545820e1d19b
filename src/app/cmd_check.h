/* SPDX-License-Identifier: MIT */
/* cmd_check.h: the `hystviz check` subcommand: stiff and extreme cases of the
 * core (σ0, g(0), γ, k cycles, degenerate minor loops, 1e6 extrema,
 * amplitudes, Bouc-Wen ν/β/δ), each against an exact or independent value.
 *
 *     hystviz check [--quick] [--verbose]
 *
 * main() calls hy_cmd_check(argc - 1, argv + 1) so that argv[0] is "check".
 */
#ifndef CMD_CHECK_H
#define CMD_CHECK_H

/* Prints one row per case on stdout; returns 0 when every case passes, 1 when
 * any fails, 2 on a usage error. */
int hy_cmd_check(int argc, char **argv);

#endif
