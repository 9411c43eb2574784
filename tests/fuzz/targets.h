// The fuzz targets: each runs one parser of hostile bytes through its whole validation and
// checks what must hold either way (an accepted input is usable, a refused one is one line).
// Built into libFuzzer programs (tests/fuzz, `make fuzz`) and into the test suite, which
// replays the committed corpus and regression inputs.
#pragma once

#include <cstddef>
#include <cstdint>

namespace pleinair::fuzz {

// Each returns 0, and aborts (a finding) when an invariant fails or anything but InputError
// is thrown.
int tree_preset(const uint8_t* data, size_t size);
int shader_preset(const uint8_t* data, size_t size);
int palette(const uint8_t* data, size_t size);
int scene(const uint8_t* data, size_t size);           // camera and sun tracks included
int set_value(const uint8_t* data, size_t size);       // --set POINTER=VALUE lines on a scene
int studio_request(const uint8_t* data, size_t size);  // a studio change request, then applied
int particle_file(const uint8_t* data, size_t size);
int graftal(const uint8_t* data, size_t size);   // a graftal description, then its tuft replayed
int imposter(const uint8_t* data, size_t size);  // an imposter description, then one drawn
int gltf(const uint8_t* data, size_t size);  // a glTF file's triangles and camera track

struct Target {
    const char* name;
    int (*run)(const uint8_t*, size_t);
};
inline constexpr Target kTargets[] = {
    {"tree_preset", tree_preset},
    {"shader_preset", shader_preset},
    {"palette", palette},
    {"scene", scene},
    {"set_value", set_value},
    {"studio_request", studio_request},
    {"particle_file", particle_file},
    {"graftal", graftal},
    {"imposter", imposter},
    {"gltf", gltf},
};

}  // namespace pleinair::fuzz
