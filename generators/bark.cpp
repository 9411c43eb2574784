// Bark strokes scattered over each limb segment's frustum, with the count set by coverage.
#include "generators/bark.h"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>

#include "generators/rng.h"

namespace pleinair {

BarkParticles emit_bark(const Tree& tree, const BarkOptions& o, uint64_t seed) {
    BarkParticles out;
    const float stroke_area = std::max(o.stroke_length * o.stroke_width, 1e-12f);
    for (const BranchInfo& b : tree.branches) {
        if (b.level > o.max_level) continue;
        const size_t rings = std::min(b.ring_centers.size(), b.ring_radii.size());
        for (size_t s = 0; s + 1 < rings; ++s) {
            glm::vec3 c0 = b.ring_centers[s], c1 = b.ring_centers[s + 1];
            float r0 = b.ring_radii[s] * o.surface_scale,
                  r1 = b.ring_radii[s + 1] * o.surface_scale;
            if (std::max(r0, r1) < o.min_radius) continue;
            glm::vec3 axis = c1 - c0;
            float len = glm::length(axis);
            if (!(len > 1e-12f) || !std::isfinite(len)) continue;
            axis /= len;
            // Any frame around the axis; the angle is drawn uniformly, so which one is irrelevant.
            glm::vec3 helper = std::abs(axis.y) < 0.9f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
            glm::vec3 e1 = glm::normalize(glm::cross(axis, helper));
            glm::vec3 e2 = glm::cross(axis, e1);
            const float area = 3.14159265f * (r0 + r1) * len;
            Rng rng = make_rng(seed, Purpose::kBark, b.key, s);
            // Fractional counts are rounded by a draw, so thin twigs still get their share.
            double expected = o.coverage * area / stroke_area;
            auto n = static_cast<size_t>(expected + rand1(rng));
            for (size_t i = 0; i < n; ++i) {
                float u = static_cast<float>(rand1(rng));
                float theta = static_cast<float>(rand_range(rng, 0.0, 2.0 * M_PI));
                float label = static_cast<float>(rand_range(rng, 1e-6, 1.0 - 1e-6));
                glm::vec3 radial = std::cos(theta) * e1 + std::sin(theta) * e2;
                float r = r0 + (r1 - r0) * u;
                out.position.push_back(c0 + axis * (u * len) + radial * r);
                out.normal.push_back(radial);
                out.tangent.push_back(axis);
                out.radius.push_back(r);
                out.label.push_back(label);
                out.tree_id.push_back(tree.id);
            }
        }
    }
    return out;
}

}  // namespace pleinair
