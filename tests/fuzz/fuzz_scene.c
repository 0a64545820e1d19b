/* SPDX-License-Identifier: MIT */
/* fuzz_scene.c: the libFuzzer target (clang -fsanitize=fuzzer): each input is the text
 * of one scene, run through the parser and the `data` path by hy_fuzz_one.  Built
 * only with -Dfuzz=true; `sh tools/setup.sh fuzz MINUTES` builds and runs it. */
#include <stdint.h>
#include <stdlib.h>

#include "fuzz_harness.h"

int LLVMFuzzerInitialize(int *argc, char ***argv);
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerInitialize(int *argc, char ***argv)
{
    (void)argc;
    (void)argv;
    if (hy_fuzz_init())
        exit(1);
    return 0;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    return hy_fuzz_one(data, size);
}
