// Particle clusters: each item's particles of one kind grouped into runs of up to
// kClusterSize, with the bounds a frame needs to cull a whole run (off screen, faded out)
// before it looks at any particle of it (built by cluster_build.h).
#pragma once

#include <cstdint>
#include <glm/vec3.hpp>
#include <limits>
#include <vector>

#include "generators/tree.h"
#include "pipeline/shot/materials.h"
#include "shading/stroke_shader.h"

namespace pleinair {

inline constexpr uint32_t kClusterSize = 64;

// The span of the trunk distance value over which one twig's bark stroke fades, and where its
// fade begins (between 0 and 0.6, drawn from its label): lod.h's bark_fade.
constexpr float kBarkFadeSpan = 0.4f;
inline float bark_fade_begin(float label) { return (1.0f - kBarkFadeSpan) * label_hash(label, 3); }
// Whether a limb's bark strokes fade with distance: a twig's do, unless it bears a leaf that
// never fades (the leaves the far circle keeps would otherwise hang in the air).
inline bool twig_bark_fades(const BranchInfo& limb) {
    return limb.level >= 2 && !limb.keeps_leaves;
}

struct ParticleCluster {
    SpriteKind kind = SpriteKind::kLeaf;
    uint32_t first = 0, count = 0;  // its particles: ItemClusters::order[first, first + count)
    // World bounds of the particles; for leaves also of every place the level of detail can
    // spread a survivor to (out along its direction from the crown's centre, never past the
    // crown's farthest leaf: lod.h's spread_leaf).
    glm::dvec3 lo{0.0}, hi{0.0};
    glm::dvec3 spread_lo{0.0}, spread_hi{0.0};
    // Bounds on a stroke's size on screen (sprites.cpp's stroke_px and sprite_size): the most
    // (width + length) x size jitter x crown edge size, world units, and the most
    // (1 + aspect) x crown edge size, which min_stroke_px enlarges a thin stroke to.
    float stroke = 0;
    float min_px_factor = 0;
    // The distance value at or above which every particle of it has faded out: its tree's
    // (leaves, bark) or its own (surface detail strokes); infinity if one never does.
    float gone_at = std::numeric_limits<float>::infinity();
};

struct ItemClusters {
    std::vector<uint32_t> order;  // particle indices, cluster by cluster, each kind by place
    std::vector<ParticleCluster> clusters;
};

}  // namespace pleinair
