/* SPDX-License-Identifier: MIT */
/* fuzz_zfast.c: the libFuzzer target (clang -fsanitize=fuzzer) of hy_zfast: each
 * input is an image (zfast_harness.h), encoded and held to zlib and the strict
 * inflater; a failure aborts with its reason.  Built only with -Dfuzz=true;
 * `sh tools/setup.sh fuzz MINUTES zfast` builds and runs it. */
#include <stdint.h>

#include "zfast_harness.h"
#include "replay_dirs.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    return fuzz_bytes_one("fuzz_zfast", zfast_fuzz_one, data, size);
}
