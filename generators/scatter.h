// Scattering tree groups over a terrain: seeded Poisson-disk placement inside a region, a
// weighted mix of families, and no tree on steep slopes or under water.
#pragma once

#include <cstdint>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <vector>

#include "generators/terrain.h"

namespace pleinair {

// A stretch kept free of trunks: every point within `radius` of the segment from `from` to
// `to` (a disc when they are equal), e.g. a path through a wood or a glade.
struct Clearing {
    glm::dvec2 from{0.0}, to{0.0};  // (x, z)
    double radius = 3;
};

struct ScatterParams {
    glm::dvec2 center{0.0};          // (x, z) of the region
    double radius = 30;              // the region is a disc
    double min_distance = 6;         // between trunks (Poisson-disk radius)
    std::vector<double> weights{1};  // relative frequency of each family in the group
    double max_slope = 25;           // degrees from horizontal; steeper ground gets no tree
    double water_level = -1e30;      // no tree where the ground is below this
    double scale_var = 0.1;          // relative size variation (gaussian sd)
    int max_trees = 10000;
    std::vector<Clearing> clearings;  // no trunk stands in these
};

// The distance from (x, z) to a clearing's segment.
double clearing_distance(const Clearing& c, const glm::dvec2& p);

struct ScatteredTree {
    glm::dvec3 position{0.0};  // on the terrain
    uint32_t family = 0;       // index into the weights
    uint64_t seed = 0;         // the tree's own seed
    double rotation = 0;       // degrees about +y
    double scale = 1;
};

// Bridson's background grid holds cells of min_distance / sqrt(2) over the region's square;
// past kMaxScatterCells of them (16 MB of grid) scatter_trees refuses, and a scene refuses the
// group up front (pipeline/input/scene.cpp), naming both numbers.
inline constexpr double kMaxScatterCells = 4e6;
double scatter_grid_cells(const ScatterParams& params);

// Pure in (terrain, params, seed, group key). Bridson's algorithm with 30 candidates per
// active point; points that fail the slope, water or clearing test are kept as blockers but not
// planted, so the spacing holds everywhere. A region with no room gives an empty list.
std::vector<ScatteredTree> scatter_trees(const TerrainParams& terrain, uint64_t terrain_seed,
                                         const ScatterParams& params, uint64_t seed,
                                         uint64_t group_key);

}  // namespace pleinair
