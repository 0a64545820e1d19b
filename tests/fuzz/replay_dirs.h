/* SPDX-License-Identifier: MIT */
/* replay_dirs.h: what the byte-input fuzz targets (fuzz_zfast, fuzz_readers)
 * and their regression tests (zfast_replay, readers_replay) share: one input
 * through a harness under libFuzzer, and every file of the directories named
 * on the command line, in name order, through it. */
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

/* libFuzzer's LLVMFuzzerTestOneInput for harness one: a failure prints
 * "PROG: reason" and aborts (a finding).  Returns 0. */
int fuzz_bytes_one(const char *prog, replay_one_fn one, const uint8_t *data, size_t size);

#endif
