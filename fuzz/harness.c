/* The libFuzzer entry point of one target of tests/support/fuzz_targets.h,
 * chosen when compiling (-DFUZZ_TARGET=fuzz_scene): `make fuzz` builds one
 * binary per target (docs/faults.md). */
#include "support/fuzz_targets.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    FUZZ_TARGET(data, size);
    return 0;
}
