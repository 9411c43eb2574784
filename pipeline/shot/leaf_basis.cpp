// leaf_basis: one pass over a member's leaves, in index order.
#include "pipeline/shot/leaf_basis.h"

#include <algorithm>
#include <glm/geometric.hpp>

#include "shading/portable_math.h"

namespace pleinair {

void direction_bins(const glm::vec3& v, float r, float& e, float& a) {
    constexpr float kPi = 3.14159265358979f;
    const float el = pmath::asin(std::clamp(v.y / r, -1.0f, 1.0f));  // -pi/2 .. pi/2
    const float az = pmath::atan2(v.z, v.x);                         // -pi .. pi
    e = (el / kPi + 0.5f) * kElevationBins - 0.5f;
    a = (az / (2 * kPi) + 0.5f) * kAzimuthBins - 0.5f;
}

LeafBasis leaf_basis(const Tree& tree, const StrokeShaderParams& leaf_shader) {
    const LeafParticles& L = tree.leaves;
    LeafBasis b;
    b.light0.resize(L.size()), b.light1.resize(L.size());
    b.r.assign(L.size(), 0.0f), b.e.assign(L.size(), 0.0f), b.a.assign(L.size(), 0.0f);
    for (size_t j = 0; j < L.size(); ++j) {
        b.light0[j] =
            stroke_lightness(leaf_shader, 0.5f, L.center_distance[j], L.branch_distance[j], 0.0f);
        b.light1[j] =
            stroke_lightness(leaf_shader, 0.5f, L.center_distance[j], L.branch_distance[j], 1.0f);
        const glm::vec3 v = L.position[j] - tree.center;
        const float r = glm::length(v);
        if (!(r > 0)) continue;
        b.r[j] = r;
        direction_bins(v, r, b.e[j], b.a[j]);
    }
    return b;
}

}  // namespace pleinair
