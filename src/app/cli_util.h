/* cli_util.h: small helpers shared by the hystviz subcommands (strict number
 * parsing, model options, atomic output files). */
#ifndef HY_CLI_UTIL_H
#define HY_CLI_UTIL_H

#include <stdio.h>
#include "hy_model.h"

/* Parses a finite double; on failure prints "hystviz: OPTION: ..." and returns -1. */
int cli_num(const char *opt, const char *s, double *out);
/* Parses an integer in [lo, hi]; on failure prints a message and returns -1. */
int cli_long(const char *opt, const char *s, long lo, long hi, long *out);

/* Model options: --model --sigma0 --sigma1 --sigma2 --fc --fs --vs --beta --rho --tau --x0.
 * cli_model_option returns 1 if argv[*i] was a model option (consuming its value),
 * 0 if not, -1 on error (message printed). */
typedef struct cli_model {
    const char *kind;
    double sigma0, sigma1, sigma2, fc, fs, vs, beta, rho, tau, x0;
    int set_sigma0, set_fs;
} cli_model;
void cli_model_defaults(cli_model *cm);
int cli_model_option(cli_model *cm, int argc, char **argv, int *i);
/* Builds and validates the model; prints the message and returns nonzero on error. */
int cli_model_build(const cli_model *cm, hy_model *m);

/* Opens PATH.tmp.PID for writing ("-" or NULL: stdout). */
FILE *cli_out_open(const char *path, char *tmp, size_t tmpsz);
/* Closes and renames into place; on any error removes the temp file, prints, returns -1. */
int cli_out_close(FILE *f, const char *path, const char *tmp);

#endif
