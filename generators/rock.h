// Procedural rocks: a cube refined by OpenMesh's Catmull-Clark, pushed onto a sphere, displaced
// by seeded 3D noise and flattened, giving a closed quad mesh for stroke emission and rays.
#pragma once

#include <cstdint>
#include <glm/vec3.hpp>

#include "generators/quad_mesh.h"

namespace pleinair {

struct RockParams {
    double radius = 1.0;               // world units
    glm::dvec3 scale{1.0, 0.6, 0.85};  // squash: rocks sit low
    double roughness = 0.35;           // radial displacement, as a fraction of the radius
    double noise_frequency = 1.2;      // per radius
    int noise_octaves = 3;
    int subdivision_levels = 3;  // 6 * 4^levels quads
};

// Pure in (params, seed). Degenerate parameters (radius 0, roughness that would turn the
// surface inside out) are clamped so the mesh stays closed, oriented and finite: displacement
// never exceeds 90% of the radius.
QuadMesh generate_rock(const RockParams& params, uint64_t seed, const glm::dvec3& position);

}  // namespace pleinair
