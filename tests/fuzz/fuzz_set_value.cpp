// libFuzzer entry for the set_value target (targets.h).
#include "targets.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    return pleinair::fuzz::set_value(data, size);
}
