// Bark strokes sampled on the render mesh, face by face, with the count set by coverage.
#include "generators/bark.h"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <stdexcept>

#include "generators/rng.h"

namespace pleinair {

namespace {

float quad_area(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c, const glm::vec3& d) {
    return 0.5f * (glm::length(glm::cross(b - a, c - a)) + glm::length(glm::cross(c - a, d - a)));
}

glm::vec3 bilinear(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c, const glm::vec3& d,
                   float u, float v) {
    // Corners counter-clockwise: a (0, 0), b (1, 0), c (1, 1), d (0, 1).
    return (1 - v) * ((1 - u) * a + u * b) + v * ((1 - u) * d + u * c);
}

// A unit vector perpendicular to n (n unit).
glm::vec3 any_perpendicular(const glm::vec3& n) {
    const glm::vec3 helper = std::abs(n.y) < 0.9f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
    return glm::normalize(glm::cross(n, helper));
}

}  // namespace

BarkParticles emit_bark(const Tree& tree, const BarkOptions& o, uint64_t seed) {
    BarkParticles out;
    const QuadMesh& m = tree.render;
    const size_t per_face = size_t{1} << (2 * std::max(tree.render_levels, 0));
    if (m.quads.size() != tree.control.quads.size() * per_face)
        throw std::invalid_argument("emit_bark: the render mesh is not the control mesh after " +
                                    std::to_string(tree.render_levels) +
                                    " rounds of Catmull-Clark");
    if (!(o.coverage > 0)) return out;
    const float stroke_area = std::max(o.stroke_length * o.stroke_width, 1e-12f);
    const std::vector<glm::vec3> vn = vertex_normals(m);
    // Where the planting depth is measured from: the trunk's base ring, along its first segment.
    struct {
        glm::vec3 origin{0.0f}, axis{0, 1, 0};
    } ground;
    if (!tree.branches.empty() && tree.branches[0].ring_centers.size() >= 2) {
        const auto& c = tree.branches[0].ring_centers;
        const float len = glm::length(c[1] - c[0]);
        ground.origin = c[0];
        if (len > 0) ground.axis = (c[1] - c[0]) / len;
    }
    for (const BranchInfo& b : tree.branches) {
        if (b.level > o.max_level) continue;
        const size_t rings = std::min(b.ring_centers.size(), b.ring_radii.size());
        for (size_t k = 0; k < b.faces.size() && k < b.face_segments.size(); ++k) {
            // The limb's segment under this face: its axis orients the strokes.
            const size_t s = std::min<size_t>(b.face_segments[k], rings >= 2 ? rings - 2 : 0);
            const glm::vec3 c0 = rings ? b.ring_centers[s] : b.start;
            const glm::vec3 c1 = rings >= 2 ? b.ring_centers[s + 1] : b.end;
            const float r0 = rings ? b.ring_radii[s] : 0.0f;
            const float r1 = rings >= 2 ? b.ring_radii[s + 1] : r0;
            if (std::max(r0, r1) < o.min_radius) continue;
            glm::vec3 axis = c1 - c0;
            const float len = glm::length(axis);
            axis = len > 1e-12f && std::isfinite(len) ? axis / len : glm::vec3(0, 1, 0);
            const uint32_t slot = k < b.face_slots.size() ? b.face_slots[k] : k;
            Rng rng = make_rng(seed, Purpose::kBark, b.key, slot);
            const size_t first = static_cast<size_t>(b.faces[k]) * per_face;
            for (size_t f = first; f < first + per_face; ++f) {
                const glm::uvec4& q = m.quads[f];
                const glm::vec3 &pa = m.positions[q[0]], &pb = m.positions[q[1]],
                                &pc = m.positions[q[2]], &pd = m.positions[q[3]];
                const float area = quad_area(pa, pb, pc, pd);
                if (!std::isfinite(area)) continue;
                const auto n = static_cast<size_t>(o.coverage * area / stroke_area + rand1(rng));
                for (size_t i = 0; i < n; ++i) {
                    const float u = static_cast<float>(rand1(rng)),
                                v = static_cast<float>(rand1(rng));
                    const float label = static_cast<float>(rand_range(rng, 1e-6, 1.0 - 1e-6));
                    const glm::vec3 p = bilinear(pa, pb, pc, pd, u, v);
                    // The trunk's domed base is below ground: no strokes there.
                    if (b.id == 0 && glm::dot(p - ground.origin, ground.axis) < tree.planting_depth)
                        continue;
                    glm::vec3 normal = bilinear(vn[q[0]], vn[q[1]], vn[q[2]], vn[q[3]], u, v);
                    const float nl = glm::length(normal);
                    if (!(nl > 1e-6f)) {
                        normal = glm::cross(pc - pa, pd - pb);  // the face's own
                        const float fl = glm::length(normal);
                        normal = fl > 0 ? normal / fl : axis;
                    } else {
                        normal /= nl;
                    }
                    // Along the limb, within the surface; on a cap, where the axis is the
                    // normal, any direction in the surface will do.
                    glm::vec3 tangent = axis - normal * glm::dot(normal, axis);
                    const float tl = glm::length(tangent);
                    tangent = tl > 1e-3f ? tangent / tl : any_perpendicular(normal);
                    const float along = len > 1e-12f ? glm::dot(p - c0, axis) / len : 0.0f;
                    out.position.push_back(p);
                    out.normal.push_back(normal);
                    out.tangent.push_back(tangent);
                    out.radius.push_back(r0 + (r1 - r0) * std::clamp(along, 0.0f, 1.0f));
                    out.label.push_back(label);
                    out.limb.push_back(b.id);
                    out.tree_id.push_back(tree.id);
                }
            }
        }
    }
    return out;
}

}  // namespace pleinair
