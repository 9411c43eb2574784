// libFuzzer entry for the shader_preset target (targets.h).
#include "targets.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    return pleinair::fuzz::shader_preset(data, size);
}
