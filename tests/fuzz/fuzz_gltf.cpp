// libFuzzer entry for the gltf target (targets.h).
#include "targets.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    return pleinair::fuzz::gltf(data, size);
}
