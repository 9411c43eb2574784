// The trunk: cube, extrusion until height or steps, taper and twist edge cases.
#include "generators/trunk.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <glm/geometric.hpp>
#include <limits>

#include "generators/tree.h"
#include "generators/tree_mesh.h"
#include "test_util.h"

namespace pleinair {
namespace {

// A trunk with no randomness at all: every draw's variance is 0.
TreeParams plain_trunk() {
    TreeParams p;
    p.branches.enabled = false;
    p.twigs.enabled = false;
    p.leaves.probability.base = 0;
    p.trunk.initial_size = {1.0, 0, 1e-3, 1e3};
    p.trunk.max_height = {5.5, 0, 1e-3, 1e5};
    p.trunk.max_steps.base = 20;
    p.trunk.extrude_length = {1.0, 0, 1e-3, 1e3};
    p.trunk.twist = {0, 0, -360, 360};
    p.trunk.taper = {0.9, 0, 0, 1};
    p.trunk.wobble = {0, 0, 0, 90};
    return p;
}

std::vector<glm::vec3> sorted(std::vector<glm::vec3> v) {
    std::sort(v.begin(), v.end(), [](const glm::vec3& a, const glm::vec3& b) {
        return a.x != b.x ? a.x < b.x : (a.y != b.y ? a.y < b.y : a.z < b.z);
    });
    return v;
}

TEST(Trunk, StartsFromACubeOfTheInitialSize) {
    TreeParams p = plain_trunk();
    p.trunk.max_steps.base = 0;
    Tree t = generate_tree(p, 1);
    EXPECT_EQ(t.control.positions.size(), 8u);
    EXPECT_EQ(t.control.quads.size(), 6u);
    Bounds b = bounds_of(t.control.positions);
    EXPECT_NEAR(b.max.x - b.min.x, 1.0f, 1e-6f);
    EXPECT_NEAR(b.max.y - b.min.y, 1.0f, 1e-6f);
    EXPECT_NEAR(b.max.z - b.min.z, 1.0f, 1e-6f);
    EXPECT_EQ(b.min.y, 0.0f);
    MeshCheck c = check_mesh(t.control);
    EXPECT_TRUE(c.ok());
    EXPECT_EQ(c.euler, 2);
}

TEST(Trunk, StopsAtMaxHeightOrMaxSteps) {
    TreeParams p = plain_trunk();
    Tree t = generate_tree(p, 1);
    const auto& rings = t.branches[0].ring_centers;
    // Centres at y = 0, 1, 2, ...: growth stops at the first ring at or above 5.5.
    ASSERT_EQ(rings.size(), 7u);
    EXPECT_NEAR(rings.back().y, 6.0f, 1e-5f);
    p.trunk.max_steps.base = 3;
    EXPECT_EQ(generate_tree(p, 1).branches[0].ring_centers.size(), 5u);  // cube's two + 3
}

TEST(Trunk, TaperScalesEachRingAndRadiiNeverGrow) {
    Tree t = generate_tree(plain_trunk(), 1);
    const auto& r = t.branches[0].ring_radii;
    for (size_t i = 2; i < r.size(); ++i) EXPECT_NEAR(r[i] / r[i - 1], 0.9f, 1e-5f);
    for (const auto& name : test::shipped_tree_presets())
        for (uint64_t seed : {1, 2, 3}) {
            Tree tree = generate_tree(test::preset(name), seed);
            for (const auto& b : tree.branches)
                for (size_t i = 1; i < b.ring_radii.size(); ++i)
                    ASSERT_LE(b.ring_radii[i], b.ring_radii[i - 1]) << name << " seed " << seed;
        }
}

// The same, measured on the control mesh itself rather than on the recorded radii: each ring's
// mean vertex distance from its centroid, along every limb of every shipped family, and a
// branch's first ring against the parent face it grew from.
TEST(Trunk, MeasuredRingRadiiNeverGrowAlongALimb) {
    for (const auto& name : test::shipped_tree_presets())
        for (uint64_t seed : {1, 2, 3}) {
            TreeMesh tm;
            grow_skeleton(tm, test::preset(name), seed);
            for (const Limb& L : tm.limbs) {
                double previous = std::numeric_limits<double>::infinity();
                for (const Ring& ring : L.rings) {
                    glm::dvec3 c(0);
                    for (auto v : ring) c += tm.point(v) * 0.25;
                    double r = 0;
                    for (auto v : ring) r += 0.25 * glm::length(tm.point(v) - c);
                    ASSERT_LE(r, previous * (1 + 1e-9)) << name << " seed " << seed;
                    previous = r;
                }
            }
        }
}

TEST(Trunk, WithoutVarianceTheSeedChangesNothing) {
    TreeParams p = plain_trunk();
    EXPECT_EQ(generate_tree(p, 1).control.positions, generate_tree(p, 99).control.positions);
}

TEST(Trunk, TaperZeroEndsInASmallButValidTip) {
    TreeParams p = plain_trunk();
    p.trunk.taper = {0, 0, 0, 1};
    Tree t = generate_tree(p, 1);
    const auto& r = t.branches[0].ring_radii;
    ASSERT_EQ(r.size(), 3u);  // the cube's rings, then one collapsed ring, then it stops
    EXPECT_NEAR(r.back(), 0.02f * r.front(), 1e-6f);
    MeshCheck c = check_mesh(t.render);
    EXPECT_TRUE(c.ok());
    EXPECT_GT(c.min_face_area, 0.0);
    EXPECT_GT(check_mesh(t.control).min_face_area, 0.0);
}

TEST(Trunk, HalfTurnTwistEqualsNoTwistUpToVertexPairing) {
    TreeParams p = plain_trunk();
    p.trunk.taper = {1, 0, 0, 1};
    Tree straight = generate_tree(p, 1);
    p.trunk.twist = {180, 0, -360, 360};
    Tree twisted = generate_tree(p, 1);
    auto a = sorted(straight.control.positions), b = sorted(twisted.control.positions);
    ASSERT_EQ(a.size(), b.size());
    for (size_t i = 0; i < a.size(); ++i) EXPECT_LT(glm::length(a[i] - b[i]), 1e-5f);
    MeshCheck c = check_mesh(twisted.render);
    EXPECT_TRUE(c.ok());
    EXPECT_EQ(c.euler, 2);
    // Side faces keep their full area: no quad folds across the axis.
    EXPECT_NEAR(check_mesh(twisted.control).min_face_area, 1.0, 1e-4);
}

TEST(Trunk, LargeTwistsAndWobbleKeepTheMeshValid) {
    TreeParams p = plain_trunk();
    for (double twist : {45.0, 89.0, 135.0, -170.0, 360.0}) {
        p.trunk.twist = {twist, 30, -360, 360};
        p.trunk.wobble = {40, 20, 0, 90};
        Tree t = generate_tree(p, 5);
        MeshCheck c = check_mesh(t.render);
        EXPECT_TRUE(c.ok()) << twist;
        EXPECT_EQ(c.euler, 2) << twist;
        EXPECT_GT(check_mesh(t.control).min_face_area, 0.0) << twist;
    }
}

}  // namespace
}  // namespace pleinair
