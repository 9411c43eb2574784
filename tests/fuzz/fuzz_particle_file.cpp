// libFuzzer entry for the particle_file target (targets.h).
#include "targets.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    return pleinair::fuzz::particle_file(data, size);
}
