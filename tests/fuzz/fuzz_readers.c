/* SPDX-License-Identifier: MIT */
/* fuzz_readers.c: the libFuzzer target (clang -fsanitize=fuzzer) of the data
 * file readers: byte 0 chooses [data]'s table, a FORC file or a Preisach
 * density file, the rest is the file's text (readers_harness.h); a broken
 * invariant aborts with its reason.  Built only with -Dfuzz=true;
 * `sh tools/setup.sh fuzz MINUTES readers` builds and runs it. */
#include <stdint.h>

#include "readers_harness.h"
#include "replay_dirs.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    return fuzz_bytes_one("fuzz_readers", readers_fuzz_one, data, size);
}
