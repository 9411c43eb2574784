// Terrain: a seeded heightfield of named hills plus fractal noise, as a grid surface that the
// surface-stroke builder and (later) the ray queries read.
#pragma once

#include <cstdint>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <memory>
#include <string>
#include <vector>

#include "generators/height_map.h"
#include "generators/quad_mesh.h"

namespace pleinair {

// A rectangular grid of points, row-major: point (i, j) is positions[j * nu + i], u along i.
// Its quads face +normal where (u, v) turn counter-clockwise.
struct GridSurface {
    int nu = 0, nv = 0;
    std::vector<glm::vec3> positions;
    const glm::vec3& at(int i, int j) const { return positions[static_cast<size_t>(j) * nu + i]; }
};

// The grid's position and unit normal at (u, v) in [0, 1]^2, bilinear over its cells; the
// normal is the cross product of the bilinear patch's tangents (falls back to +y where they
// degenerate).
void eval_grid(const GridSurface& g, double u, double v, glm::vec3& position, glm::vec3& normal);

// The grid as quads (for meshes, checks and rays).
QuadMesh grid_mesh(const GridSurface& g);

struct Hill {
    std::string name;
    glm::dvec2 center{0.0};  // (x, z)
    double radius = 20;      // where the hill meets the plain
    double height = 5;
};

struct TerrainParams {
    glm::dvec2 min{-100, -100};  // (x, z) corner
    glm::dvec2 max{100, 100};
    int resolution = 129;  // grid points along each side
    double base_height = 0;
    std::vector<Hill> hills;
    double noise_amplitude = 0.4;   // peak-to-peak, world units
    double noise_frequency = 0.04;  // per world unit
    int noise_octaves = 3;
    // Heights from a map over [min, max] (a survey, a sculpted ground), under the hills and
    // noise; null: none. Shared: scenes are copied, the map is not.
    std::shared_ptr<const HeightMap> height_map;
};

// Height at (x, z): base + the height map + each hill's cosine bump + noise. Pure in (params,
// seed).
double terrain_height(const TerrainParams& p, uint64_t seed, double x, double z);

// The terrain as a grid surface facing +y. Rejects nothing: a degenerate extent or resolution
// below 2 gives a 2 x 2 grid; non-finite heights become base_height.
GridSurface generate_terrain(const TerrainParams& p, uint64_t seed);

}  // namespace pleinair
