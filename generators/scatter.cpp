// Poisson-disk scattering (Bridson 2007) on a background grid, drawing from one keyed stream.
#include "generators/scatter.h"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <numeric>

#include "generators/rng.h"
#include "shading/portable_math.h"

namespace pleinair {

double scatter_grid_cells(const ScatterParams& p) {
    const double cells = std::max(1.0, std::ceil(2 * p.radius / (p.min_distance / std::sqrt(2.0))));
    return cells * cells;
}

double clearing_distance(const Clearing& c, const glm::dvec2& p) {
    const glm::dvec2 d = c.to - c.from;
    const double len2 = glm::dot(d, d);
    const double u = len2 > 0 ? std::clamp(glm::dot(p - c.from, d) / len2, 0.0, 1.0) : 0.0;
    return glm::length(p - (c.from + u * d));
}

std::vector<ScatteredTree> scatter_trees(const TerrainParams& terrain, uint64_t terrain_seed,
                                         const ScatterParams& p, uint64_t seed,
                                         uint64_t group_key) {
    std::vector<ScatteredTree> out;
    const double r = p.min_distance, R = p.radius;
    if (!(r > 0) || !(R >= 0) || !std::isfinite(r) || !std::isfinite(R) || p.weights.empty())
        return out;
    const double total_weight = std::accumulate(p.weights.begin(), p.weights.end(), 0.0);
    if (!(total_weight > 0)) return out;
    // Grid cells of r / sqrt(2) hold at most one point.
    const double cell = r / std::sqrt(2.0);
    const double cells = std::max(1.0, std::ceil(2 * R / cell));
    if (!(scatter_grid_cells(p) <= kMaxScatterCells)) return out;  // the scene refuses these
    const int n = static_cast<int>(cells);
    std::vector<int> grid(static_cast<size_t>(n) * n, -1);
    std::vector<glm::dvec2> points;  // relative to the region's corner
    auto cell_of = [&](const glm::dvec2& q) {
        return glm::ivec2(std::clamp(static_cast<int>(q.x / cell), 0, n - 1),
                          std::clamp(static_cast<int>(q.y / cell), 0, n - 1));
    };
    auto inside = [&](const glm::dvec2& q) { return glm::length(q - glm::dvec2(R)) <= R; };
    auto far_enough = [&](const glm::dvec2& q) {
        glm::ivec2 c = cell_of(q);
        for (int j = std::max(c.y - 2, 0); j <= std::min(c.y + 2, n - 1); ++j)
            for (int i = std::max(c.x - 2, 0); i <= std::min(c.x + 2, n - 1); ++i) {
                int k = grid[static_cast<size_t>(j) * n + i];
                if (k >= 0 && glm::length(points[k] - q) < r) return false;
            }
        return true;
    };
    Rng rng = make_rng(seed, Purpose::kScatter, group_key);
    auto add = [&](const glm::dvec2& q) {
        glm::ivec2 c = cell_of(q);
        grid[static_cast<size_t>(c.y) * n + c.x] = static_cast<int>(points.size());
        points.push_back(q);
    };
    add(glm::dvec2(R));  // the centre
    std::vector<int> active{0};
    const double cos_max = pmath::cos(std::clamp(p.max_slope, 0.0, 90.0) * M_PI / 180.0);
    auto plant = [&](const glm::dvec2& q) {
        double x = p.center.x - R + q.x, z = p.center.y - R + q.y;
        double y = terrain_height(terrain, terrain_seed, x, z);
        // Slope from central differences over a tenth of the spacing.
        double h = 0.1 * r;
        double dx = (terrain_height(terrain, terrain_seed, x + h, z) -
                     terrain_height(terrain, terrain_seed, x - h, z)) /
                    (2 * h);
        double dz = (terrain_height(terrain, terrain_seed, x, z + h) -
                     terrain_height(terrain, terrain_seed, x, z - h)) /
                    (2 * h);
        double up = 1.0 / std::sqrt(1.0 + dx * dx + dz * dz);  // normal's y
        // Draws happen for every point, planted or not, so the stream stays aligned.
        double pick = rand1(rng) * total_weight, rot = rand_range(rng, 0.0, 360.0);
        double size = 1.0 + p.scale_var * rand_gaussian(rng);
        uint64_t tree_seed = next_u32(rng) | (uint64_t{next_u32(rng)} << 32);
        if (up < cos_max || y < p.water_level || static_cast<int>(out.size()) >= p.max_trees)
            return;
        for (const Clearing& c : p.clearings)
            if (clearing_distance(c, glm::dvec2(x, z)) < c.radius) return;
        uint32_t family = 0;
        for (double acc = p.weights[0]; pick >= acc && family + 1 < p.weights.size();)
            acc += p.weights[++family];
        out.push_back({glm::dvec3(x, y, z), family, tree_seed, rot, std::clamp(size, 0.5, 1.5)});
    };
    plant(points[0]);
    while (!active.empty()) {
        // The oldest active point: a deterministic order independent of container tricks.
        int a = active.front();
        bool found = false;
        for (int k = 0; k < 30; ++k) {
            double ang = rand_range(rng, 0.0, 2 * M_PI), dist = r * (1 + rand1(rng));
            glm::dvec2 q = points[a] + dist * glm::dvec2(pmath::cos(ang), pmath::sin(ang));
            if (!inside(q) || !far_enough(q)) continue;
            add(q);
            active.push_back(static_cast<int>(points.size()) - 1);
            plant(q);
            found = true;
            break;
        }
        if (!found) active.erase(active.begin());
    }
    return out;
}

}  // namespace pleinair
