/* SPDX-License-Identifier: MIT */
/* replay_dirs.h: the regression tests of the byte-input fuzz targets
 * (zfast_replay, readers_replay): every file of the directories named on the
 * command line, in name order, through the target's harness. */
#ifndef REPLAY_DIRS_H
#define REPLAY_DIRS_H

#include <stddef.h>
#include <stdint.h>

/* A harness: 0 when the input passes, -1 with the reason in why. */
typedef int (*replay_one_fn)(const uint8_t *data, size_t n, char *why, size_t whylen);

/* Runs one over every file (at most 1 MiB read) of argv[1..argc), printing
 * "FAIL PATH: reason" for each failure and "PROG: N inputs, ..." at the end.
 * Returns the exit status: 0 only when all passed and there was at least one. */
int replay_dirs(int argc, char **argv, const char *prog, replay_one_fn one);

#endif
