/* SPDX-License-Identifier: MIT */
/* readers_harness.h: one fuzz input -> the text of one data file -> the reader
 * a scene hands it to: the measured samples of [data] (hy_table_parse,
 * src/core/hy_table.c), a FORC file (hy_forc_read, src/core/hy_forc.c) and a
 * Preisach density file (pr_file: hy_preisach_table_read,
 * src/core/hy_preisach_table.c).  Shared by the libFuzzer target
 * fuzz_readers.c and the replay test readers_replay.c.
 *
 * The scene target (fuzz_harness.h) reaches these readers only with the fixed
 * files of its directory; here the file's bytes are the fuzzer's.  The readers
 * take text from memory (scene_data.c, scene_forc.c and model_preisach.c read
 * the file under the scene's file policy first), so no file is written.
 *
 * Byte 0 chooses (the rest, at most 64 KiB, is the file's text):
 *   byte 0 % 3 == 0  [data]: hy_table_parse with column spec (byte 0 / 3) % 4
 *                    (indices, header names, four columns, a split column),
 *                    quote = bit 6; then every record's hy_table_area
 *   byte 0 % 3 == 1  FORC: hy_forc_read; then hy_forc_steps, hy_forc_drift
 *                    and, for at most 64 points, hy_forc_rho on a grid of at
 *                    most 400 nodes
 *   byte 0 % 3 == 2  pr_file: hy_preisach_table_read; then
 *                    hy_preisach_table_from_grid
 * Invariants (a violation is a finding): a refusal leaves a message that is
 * text, starts with the file's name and says something after its location;
 * what a reader accepts holds what its header promises (finite values,
 * records that partition the rows, curves whose H_b ascend, a regular grid of
 * at least 2 x 2 nodes with μ >= 0).
 */
#ifndef READERS_HARNESS_H
#define READERS_HARNESS_H

#include <stddef.h>
#include <stdint.h>

/* Inputs longer than this (the mode byte excluded) are ignored. */
#define READERS_FUZZ_MAX_BYTES 65536

/* 0 when the input keeps every invariant above; -1 with the reason in why. */
int readers_fuzz_one(const uint8_t *data, size_t n, char *why, size_t whylen);

#endif
