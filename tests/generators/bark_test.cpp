// Bark strokes: on the render mesh's surface, oriented along their limb, as many as the
// coverage asks, keyed so a seed repeats them exactly and one limb's strokes never move
// another's.
#include "generators/bark.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <tuple>

#include "generators/tree.h"
#include "test_util.h"

namespace pleinair {
namespace {

// Distance from p to triangle abc (Ericson, Real-Time Collision Detection, 5.1.5).
float point_triangle(const glm::vec3& p, const glm::vec3& a, const glm::vec3& b,
                     const glm::vec3& c) {
    const glm::vec3 ab = b - a, ac = c - a, ap = p - a;
    const float d1 = glm::dot(ab, ap), d2 = glm::dot(ac, ap);
    if (d1 <= 0 && d2 <= 0) return glm::length(p - a);
    const glm::vec3 bp = p - b;
    const float d3 = glm::dot(ab, bp), d4 = glm::dot(ac, bp);
    if (d3 >= 0 && d4 <= d3) return glm::length(p - b);
    const float vc = d1 * d4 - d3 * d2;
    if (vc <= 0 && d1 >= 0 && d3 <= 0) return glm::length(p - (a + ab * (d1 / (d1 - d3))));
    const glm::vec3 cp = p - c;
    const float d5 = glm::dot(ab, cp), d6 = glm::dot(ac, cp);
    if (d6 >= 0 && d5 <= d6) return glm::length(p - c);
    const float vb = d5 * d2 - d1 * d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0) return glm::length(p - (a + ac * (d2 / (d2 - d6))));
    const float va = d3 * d6 - d5 * d4;
    if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
        return glm::length(p - (b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)))));
    const float denom = 1.0f / (va + vb + vc);
    return glm::length(p - (a + ab * (vb * denom) + ac * (vc * denom)));
}

float mesh_area(const QuadMesh& m) {
    double a = 0;
    for (const auto& q : m.quads) {
        const glm::vec3 p0 = m.positions[q[0]], p1 = m.positions[q[1]], p2 = m.positions[q[2]],
                        p3 = m.positions[q[3]];
        a += 0.5 * (glm::length(glm::cross(p1 - p0, p2 - p0)) +
                    glm::length(glm::cross(p2 - p0, p3 - p0)));
    }
    return static_cast<float>(a);
}

TEST(Bark, StrokesLieOnTheRenderMeshAlongTheirLimb) {
    Tree t = generate_tree(test::preset("oak"), 2);
    t.planting_depth = 0;  // nothing below ground, and
    BarkOptions o;
    o.max_level = 99;  // every limb: the strokes cover the whole render mesh
    BarkParticles b = emit_bark(t, o, 2);
    ASSERT_GT(b.size(), 500u);
    const double expected = o.coverage * mesh_area(t.render) / (o.stroke_length * o.stroke_width);
    EXPECT_NEAR(double(b.size()), expected, 0.03 * expected + 20);

    // A typical render face's size: the scale of "on the surface".
    const float edge = std::sqrt(mesh_area(t.render) / static_cast<float>(t.render.quads.size()));
    // Along the limb, away from forks and tips (where the surface turns across the axis), the
    // tangent is the nearest segment's axis; everywhere the normal points away from it.
    size_t shaft = 0, along_axis = 0, outward = 0;
    for (size_t i = 0; i < b.size(); ++i) {
        ASSERT_NEAR(glm::length(b.normal[i]), 1.0f, 1e-4f);
        ASSERT_NEAR(glm::length(b.tangent[i]), 1.0f, 1e-4f);
        ASSERT_NEAR(glm::dot(b.normal[i], b.tangent[i]), 0.0f, 1e-4f);
        ASSERT_GT(b.label[i], 0.0f);
        ASSERT_LT(b.label[i], 1.0f);
        ASSERT_EQ(b.tree_id[i], t.id);
        ASSERT_LT(b.limb[i], t.branches.size());
        ASSERT_GT(b.radius[i], 0.0f);
        const BranchInfo& br = t.branches[b.limb[i]];
        float best = 1e30f;
        size_t nearest = 0;
        glm::vec3 from_axis(0.0f), axis(0.0f);
        for (size_t s = 0; s + 1 < br.ring_centers.size(); ++s) {
            const glm::vec3 c0 = br.ring_centers[s], a = br.ring_centers[s + 1] - c0;
            const float len = glm::length(a);
            const float u = std::clamp(glm::dot(b.position[i] - c0, a) / (len * len), 0.f, 1.f);
            const glm::vec3 off = b.position[i] - (c0 + a * u);
            if (glm::length(off) < best)
                best = glm::length(off), nearest = s, from_axis = off, axis = a / len;
        }
        if (glm::dot(from_axis, b.normal[i]) > 0) ++outward;
        if (br.level <= 1 && nearest > 0 && nearest + 2 < br.ring_centers.size()) {
            ++shaft;
            if (std::abs(glm::dot(axis, b.tangent[i])) > 0.9f) ++along_axis;
        }
    }
    EXPECT_GT(shaft, b.size() / 3);
    EXPECT_GT(along_axis, shaft * 9 / 10);
    EXPECT_GT(outward, b.size() * 9 / 10);

    // On the surface: a sample of strokes, each against every render face (two triangles).
    for (size_t i = 0; i < b.size(); i += b.size() / 150) {
        float d = 1e30f;
        for (const auto& q : t.render.quads) {
            const auto& P = t.render.positions;
            d = std::min(d, point_triangle(b.position[i], P[q[0]], P[q[1]], P[q[2]]));
            d = std::min(d, point_triangle(b.position[i], P[q[0]], P[q[2]], P[q[3]]));
        }
        // A bilinear patch bulges off its two triangles by a small part of its size.
        ASSERT_LT(d, 0.05f * edge) << "stroke " << i;
    }
}

// Catmull-Clark rounds the trunk's base into a dome; the tree is planted so the ground meets
// the trunk at nine tenths of its width, and nothing below that is painted.
TEST(Bark, NoStrokesBelowThePlantingDepth) {
    for (const auto& name : test::shipped_tree_presets()) {
        Tree t = generate_tree(test::preset(name), 4);
        const glm::vec3 c0 = t.branches[0].ring_centers[0];
        const glm::vec3 axis = glm::normalize(t.branches[0].ring_centers[1] - c0);
        // The dome is real: the render mesh reaches below the planting depth, but not far.
        float lowest = 1e30f;
        for (const auto& p : t.render.positions) lowest = std::min(lowest, glm::dot(p - c0, axis));
        EXPECT_GT(t.planting_depth, lowest) << name;
        EXPECT_LT(t.planting_depth, glm::length(t.branches[0].ring_centers[1] - c0)) << name;
        BarkParticles b = emit_bark(t, BarkOptions{}, 4);
        size_t near_ground = 0;
        for (size_t i = 0; i < b.size(); ++i) {
            if (b.limb[i] != 0) continue;
            const float h = glm::dot(b.position[i] - c0, axis);
            ASSERT_GE(h, t.planting_depth) << name;
            if (h < t.planting_depth + 0.5f * t.planting_depth) ++near_ground;
        }
        EXPECT_GT(near_ground, 0u) << name;  // the trunk is painted down to the ground
    }
}

TEST(Bark, SeedRepeatsLevelsAndThicknessLimitStrokes) {
    Tree t = generate_tree(test::preset("willow"), 5);
    BarkOptions o;
    BarkParticles a = emit_bark(t, o, 5), again = emit_bark(t, o, 5), other = emit_bark(t, o, 6);
    EXPECT_EQ(a.position, again.position);
    EXPECT_EQ(a.label, again.label);
    EXPECT_NE(a.position, other.position);
    o.max_level = 0;  // the trunk alone
    BarkParticles trunk = emit_bark(t, o, 5);
    EXPECT_LT(trunk.size(), a.size());
    EXPECT_GT(trunk.size(), 0u);
    for (uint32_t l : trunk.limb) ASSERT_EQ(l, 0u);
    o.max_level = -1;
    EXPECT_EQ(emit_bark(t, o, 5).size(), 0u);
    o.max_level = 2;
    o.min_radius = 1e9f;  // every limb thinner than this: none
    EXPECT_EQ(emit_bark(t, o, 5).size(), 0u);
    o.min_radius = 0;
    o.coverage = 0;
    EXPECT_EQ(emit_bark(t, o, 5).size(), 0u);
}

// Each limb draws from its own streams: the trunk's strokes are the same whether or not the
// branches get strokes too.
TEST(Bark, OneLimbsStrokesDoNotDependOnAnothers) {
    Tree t = generate_tree(test::preset("oak"), 3);
    BarkOptions o;
    o.max_level = 0;
    BarkParticles trunk = emit_bark(t, o, 9);
    o.max_level = 2;
    BarkParticles all = emit_bark(t, o, 9);
    std::vector<glm::vec3> trunk_in_all;
    for (size_t i = 0; i < all.size(); ++i)
        if (all.limb[i] == 0) trunk_in_all.push_back(all.position[i]);
    EXPECT_EQ(trunk.position, trunk_in_all);
}

// A branch growing from one of a limb's sides takes that face away; the strokes of the
// limb's other faces stay where they were.
TEST(Bark, StrokesOfAFaceDoNotDependOnTheLimbsOtherFaces) {
    Tree t = generate_tree(test::preset("oak"), 3);
    BarkOptions o;
    o.max_level = 0;
    const BarkParticles all = emit_bark(t, o, 9);
    Tree fewer = t;
    BranchInfo& trunk = fewer.branches[0];
    ASSERT_GT(trunk.faces.size(), 6u);
    trunk.faces.erase(trunk.faces.begin() + 2);  // a side of the first segment
    trunk.face_segments.erase(trunk.face_segments.begin() + 2);
    trunk.face_slots.erase(trunk.face_slots.begin() + 2);
    const BarkParticles some = emit_bark(fewer, o, 9);
    // Every stroke of `some` is one of `all`, and `all` has strokes only `some` lacks.
    std::vector<glm::vec3> a = all.position, b = some.position;
    auto less = [](const glm::vec3& p, const glm::vec3& q) {
        return std::tie(p.x, p.y, p.z) < std::tie(q.x, q.y, q.z);
    };
    std::sort(a.begin(), a.end(), less);
    std::sort(b.begin(), b.end(), less);
    EXPECT_TRUE(std::includes(a.begin(), a.end(), b.begin(), b.end(), less));
    EXPECT_LT(b.size(), a.size());
}

TEST(Bark, ARenderMeshThatIsNotTheControlSubdividedIsRejected) {
    Tree t = generate_tree(test::preset("oak"), 3);
    t.render.quads.pop_back();
    EXPECT_THROW(emit_bark(t, BarkOptions{}, 1), std::invalid_argument);
}

}  // namespace
}  // namespace pleinair
