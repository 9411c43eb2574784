// libFuzzer entry for the studio_request target (targets.h).
#include "targets.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    return pleinair::fuzz::studio_request(data, size);
}
