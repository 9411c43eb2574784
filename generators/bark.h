// Bark stroke particles: the trunk and branches painted as strokes laid on the render mesh's
// surface, each oriented along its limb, instead of a flat-shaded mesh.
#pragma once

#include <cstdint>
#include <glm/vec3.hpp>
#include <vector>

#include "generators/tree.h"

namespace pleinair {

struct BarkParticles {
    std::vector<glm::vec3> position;  // tree-local, on the render mesh's surface
    std::vector<glm::vec3> normal;    // unit, the surface's (smooth) normal there
    std::vector<glm::vec3> tangent;   // unit, in the surface: the limb's axis projected into it
    std::vector<float> radius;        // of the limb where the stroke sits (tree units)
    std::vector<float> label;         // in (0, 1): seeds the stroke noise
    std::vector<uint32_t> limb;       // BranchInfo::id of the limb under the stroke
    std::vector<uint32_t> tree_id;
    size_t size() const { return position.size(); }
};

struct BarkOptions {
    float stroke_length = 0.6f;  // tree units
    float stroke_width = 0.25f;  // tree units
    float coverage = 2.5f;       // strokes' total area over the surface's area
    int max_level = 2;           // limbs deeper than this get no strokes
    float min_radius = 0.0f;     // thinner limb segments get no strokes (tree units)
};

// Pure: strokes are scattered uniformly over each render face of the limbs that qualify, as
// many as coverage asks (a fractional count is rounded by a draw), except on the trunk below
// its planting depth. Each control face draws from its own stream keyed by (seed, limb key,
// the face's slot on the limb), so a face's strokes depend on no other face: not on other
// limbs, nor on which of its own limb's sides branches took over.
BarkParticles emit_bark(const Tree& tree, const BarkOptions& options, uint64_t seed);

}  // namespace pleinair
