// Bark stroke particles: the trunk and branches painted as strokes laid over the limbs' surface,
// each oriented along its limb, instead of a flat-shaded mesh.
#pragma once

#include <cstdint>
#include <glm/vec3.hpp>
#include <vector>

#include "generators/tree.h"

namespace pleinair {

struct BarkParticles {
    std::vector<glm::vec3> position;  // tree-local, on the limb's surface
    std::vector<glm::vec3> normal;    // unit, outward from the limb's axis
    std::vector<glm::vec3> tangent;   // unit, along the limb towards its tip
    std::vector<float> radius;        // of the limb where the stroke sits (tree units)
    std::vector<float> label;         // in (0, 1): seeds the stroke noise
    std::vector<uint32_t> tree_id;
    size_t size() const { return position.size(); }
};

struct BarkOptions {
    float stroke_length = 0.6f;  // tree units
    float stroke_width = 0.25f;  // tree units
    float coverage = 2.5f;       // strokes' total area over the limb's lateral area
    float surface_scale = 0.9f;  // Catmull-Clark pulls the surface inside the control rings
    int max_level = 2;           // limbs deeper than this get no strokes
    float min_radius = 0.0f;     // thinner limb segments get no strokes (tree units)
};

// Pure: strokes per limb segment drawn from streams keyed by (seed, limb key, segment), so a
// limb's strokes never depend on other limbs.
BarkParticles emit_bark(const Tree& tree, const BarkOptions& options, uint64_t seed);

}  // namespace pleinair
