/* SPDX-License-Identifier: MIT */
/* cmd_report.h: the `hystviz report` subcommand (work-precision benchmark).
 *
 *     hystviz report [-o DIR] [--quick] [--problems LIST] [--solvers LIST]
 *                    [--repeats N] [--max-steps N] [--time-cap S]
 *
 * main() calls hy_cmd_report(argc - 1, argv + 1) so that argv[0] is "report".
 * Writes DIR/report.csv, DIR/report.md and DIR/wp-PROBLEM.{svg,png}.
 */
#ifndef CMD_REPORT_H
#define CMD_REPORT_H

/* Runs the subcommand; returns 0 when the report was written (failed runs are
 * rows, not errors), 1 on a file or setup error, 2 on a usage error. */
int hy_cmd_report(int argc, char **argv);

#endif
