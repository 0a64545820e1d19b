/* SPDX-License-Identifier: MIT */
/* fuzz_harness.h: one fuzz input through the scene parser and the whole `data` path.
 *
 * The input is the text of one scene.  hy_fuzz_one parses it from memory
 * (and checks that the written effective scene parses back to the same
 * values), then, if it is valid, saves it as the only scene of a private
 * temporary directory and runs what `hystviz data SCENE` runs: load
 * (validate, build model and input), plan, compute, and the CSV into memory.
 *
 *     hy_fuzz_one((const uint8_t *)text, strlen(text));
 *
 * Both the libFuzzer target (fuzz_scene.c) and the replay test of the normal
 * suite (replay.c) call it, so a reproducer runs the same code in both.
 *
 * While a scene is parsed or computed a sandbox is on: every open, fopen,
 * realpath, stat, mkdir, ... of the hystviz code is refused (EACCES) unless
 * the path lies in the temporary directory, and any write or create is
 * refused everywhere.  The directory holds a few fixed files for includes
 * and `[input] file` to find (hy_fuzz_dir lists them), so the fuzzer reaches
 * that code without reading the real file system.  The sandbox needs the
 * link options of HY_FUZZ_WRAP (meson: fuzz_wrap_args).
 *
 * Work is capped before computing (HY_FUZZ_MAX_POINTS, HY_FUZZ_MAX_BW): a
 * scene above the cap is parsed and loaded but not computed, so one input
 * runs in milliseconds and the fuzzer does not spend its time on big, valid
 * scenes.  Invariants whose violation aborts (a fuzzer finding): a failed
 * call leaves a message with text after its location; the effective scene written by
 * hy_scene_write parses back and writes the same text again. */
#ifndef HY_FUZZ_HARNESS_H
#define HY_FUZZ_HARNESS_H

#include <stddef.h>
#include <stdint.h>

/* Inputs longer than this are ignored (the parser's caps are tested elsewhere). */
#define HY_FUZZ_MAX_BYTES 65536
/* Grid points x (solves + series + 1) allowed in a seed-000 scene. */
#define HY_FUZZ_MAX_POINTS 200000.0
/* Newmark integration samples allowed in a Bouc-Wen scene. */
#define HY_FUZZ_MAX_BW 200000.0

/* Creates the temporary directory and its files (once; removed at exit).
 * Returns 0, or -1 with a message on stderr. */
int hy_fuzz_init(void);

/* Runs one input (see above).  Returns 0; aborts on a broken invariant. */
int hy_fuzz_one(const uint8_t *data, size_t size);

/* The temporary directory (after hy_fuzz_init). */
const char *hy_fuzz_dir(void);

/* How many file operations the sandbox has refused so far. */
unsigned long hy_fuzz_refused(void);

/* What the last hy_fuzz_one reached: 0 parse failed, 1 parsed, 2 loaded,
 * 3 computed and written as CSV, -1 skipped (too long or over the cap). */
int hy_fuzz_stage(void);

/* The error message of the last hy_fuzz_one that failed somewhere, or "". */
const char *hy_fuzz_message(void);

#endif
