// The leaf generator: eligible vertices of the control mesh emit implied branches of particles
// (thesis IV.3, Fig. 13 and 14), each carrying what the painter and the level of detail need.
#pragma once

#include <cstdint>
#include <glm/vec3.hpp>
#include <vector>

#include "generators/tree_params.h"

namespace pleinair {

struct TreeMesh;

// Struct of arrays: the raster loop touches a few attributes of many particles.
struct LeafParticles {
    std::vector<glm::vec3> position;     // tree-local
    std::vector<glm::vec3> normal;       // unit: the implied branch's direction at the particle
    std::vector<float> branch_distance;  // along its implied branch, 0..1 over the tree
    std::vector<float> center_distance;  // from the centre locator, 0..1 over the tree
    std::vector<float> label;            // unique in (0, 1): seeds the stroke noise
    std::vector<uint32_t> tree_id;       // seeds the per-tree tint
    std::vector<float> fade_begin;       // distance value where the particle starts to fade
    std::vector<float> fade_end;         // ... and where it is gone (> 1: it never is)
    std::vector<uint32_t> limb;          // the limb its twig grows from (Tree::branches index)

    size_t size() const { return position.size(); }
};

// Emits the particles and the centre locator. All randomness is drawn here, from streams keyed
// by (limb key, ring, corner), so a vertex's implied branch is the same whatever else changes.
// `center` receives the locator: the particles' centroid plus center_offset (or, with no
// particles, the top of the trunk).
LeafParticles emit_leaves(const TreeMesh& tm, const TreeParams& params, uint64_t seed,
                          uint32_t tree_id, glm::dvec3& center);

}  // namespace pleinair
