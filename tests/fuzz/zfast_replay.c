/* SPDX-License-Identifier: MIT */
/* zfast_replay.c: zfast_replay DIR...: every file of the directories through
 * zfast_fuzz_one (hy_zfast's stream against zlib and the strict inflater),
 * the seed corpus of fuzz_zfast and its reproducers; exit 0 only when all
 * pass and there was at least one. */
#include "replay_dirs.h"
#include "zfast_harness.h"

int main(int argc, char **argv)
{
    return replay_dirs(argc, argv, "zfast_replay", zfast_fuzz_one);
}
