// Heightfield terrain: cosine hills plus fractal noise offset by the seed.
#include "generators/terrain.h"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>

#include "generators/rng.h"
#include "shading/noise.h"
#include "shading/portable_math.h"

namespace pleinair {

void eval_grid(const GridSurface& g, double u, double v, glm::vec3& position, glm::vec3& normal) {
    const double cu = std::clamp(u, 0.0, 1.0) * (g.nu - 1),
                 cv = std::clamp(v, 0.0, 1.0) * (g.nv - 1);
    const int i = std::min(static_cast<int>(cu), g.nu - 2),
              j = std::min(static_cast<int>(cv), g.nv - 2);
    const float fu = static_cast<float>(cu - i), fv = static_cast<float>(cv - j);
    const glm::vec3 &p00 = g.at(i, j), &p10 = g.at(i + 1, j), &p01 = g.at(i, j + 1),
                    &p11 = g.at(i + 1, j + 1);
    position = (1 - fv) * ((1 - fu) * p00 + fu * p10) + fv * ((1 - fu) * p01 + fu * p11);
    glm::vec3 du = (1 - fv) * (p10 - p00) + fv * (p11 - p01);
    glm::vec3 dv = (1 - fu) * (p01 - p00) + fu * (p11 - p10);
    glm::vec3 n = glm::cross(dv, du);
    float len = glm::length(n);
    normal = len > 1e-20f && std::isfinite(len) ? n / len : glm::vec3(0, 1, 0);
}

QuadMesh grid_mesh(const GridSurface& g) {
    QuadMesh m;
    m.positions = g.positions;
    for (int j = 0; j + 1 < g.nv; ++j)
        for (int i = 0; i + 1 < g.nu; ++i) {
            auto id = [&](int a, int b) { return static_cast<unsigned>(b * g.nu + a); };
            m.quads.push_back({id(i, j), id(i, j + 1), id(i + 1, j + 1), id(i + 1, j)});
        }
    return m;
}

namespace {
struct NoiseOffset {
    float x, z;
};
NoiseOffset noise_offset(uint64_t seed) {
    Rng rng = make_rng(seed, Purpose::kTerrain);
    return {static_cast<float>(rand_range(rng, 0, 256)),
            static_cast<float>(rand_range(rng, 0, 256))};
}

double height_at(const TerrainParams& p, NoiseOffset o, double x, double z) {
    double h = p.base_height;
    if (p.height_map) {
        const double w = p.max.x - p.min.x, d = p.max.y - p.min.y;
        h += p.height_map->at(w > 0 ? (x - p.min.x) / w : 0.0, d > 0 ? (z - p.min.y) / d : 0.0);
    }
    for (const Hill& hill : p.hills) {
        if (!(hill.radius > 0)) continue;
        double d = pmath::hypot(x - hill.center.x, z - hill.center.y) / hill.radius;
        if (d < 1) h += hill.height * 0.5 * (1 + pmath::cos(M_PI * d));
    }
    if (p.noise_amplitude != 0) {
        // Noise coordinates relative to the terrain's corner, so a terrain far from the origin
        // keeps float precision.
        double nx = (x - p.min.x) * p.noise_frequency, nz = (z - p.min.y) * p.noise_frequency;
        float n = fractal_noise(static_cast<float>(std::fmod(nx, 256.0)) + o.x,
                                static_cast<float>(std::fmod(nz, 256.0)) + o.z, p.noise_octaves);
        h += p.noise_amplitude * (n - 0.5);
    }
    return std::isfinite(h) ? h : p.base_height;
}
}  // namespace

double terrain_height(const TerrainParams& p, uint64_t seed, double x, double z) {
    return height_at(p, noise_offset(seed), x, z);
}

GridSurface generate_terrain(const TerrainParams& p, uint64_t seed) {
    GridSurface g;
    g.nu = g.nv = std::clamp(p.resolution, 2, 8193);  // 67 M points at most
    g.positions.resize(static_cast<size_t>(g.nu) * g.nv);
    const NoiseOffset o = noise_offset(seed);
    for (int j = 0; j < g.nv; ++j)
        for (int i = 0; i < g.nu; ++i) {
            double x = p.min.x + (p.max.x - p.min.x) * i / (g.nu - 1);
            double z = p.min.y + (p.max.y - p.min.y) * j / (g.nv - 1);
            g.positions[static_cast<size_t>(j) * g.nu + i] =
                glm::vec3(static_cast<float>(x), static_cast<float>(height_at(p, o, x, z)),
                          static_cast<float>(z));
        }
    return g;
}

}  // namespace pleinair
