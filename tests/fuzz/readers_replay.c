/* SPDX-License-Identifier: MIT */
/* readers_replay.c: readers_replay DIR...: every file of the directories
 * through readers_fuzz_one (a data file's text through [data]'s, the FORC
 * and the Preisach density readers: readers_harness.h), the seed corpus of
 * fuzz_readers and its reproducers; exit 0 only when all pass and there was
 * at least one. */
#include "readers_harness.h"
#include "replay_dirs.h"

int main(int argc, char **argv)
{
    return replay_dirs(argc, argv, "readers_replay", readers_fuzz_one);
}
