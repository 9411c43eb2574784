// Branches: eligibility and probability, the square first step, radii, tropism, ground, keys.
#include "generators/branches.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <glm/geometric.hpp>
#include <map>

#include "generators/tree.h"
#include "generators/trunk.h"
#include "test_util.h"

namespace pleinair {
namespace {

TreeMesh grow(const TreeParams& p, uint64_t seed) {
    TreeMesh tm;
    grow_skeleton(tm, p, seed);
    return tm;
}

TEST(Branches, ProbabilityZeroGrowsNone) {
    TreeParams p = test::preset("oak");
    p.branches.probability.base = 0;
    TreeMesh tm = grow(p, 3);
    EXPECT_EQ(tm.limbs.size(), 1u);
}

TEST(Branches, ProbabilityOneUsesEveryEligibleFace) {
    TreeParams p = test::preset("oak");
    p.branches.probability.base = 1;
    p.twigs.enabled = false;
    TreeMesh tm = grow(p, 3);
    const Limb& trunk = tm.limbs[0];
    const double top = trunk.centers.back().y;
    int eligible = 0, used = 0;
    for (size_t s = 0; s + 1 < trunk.rings.size(); ++s) {
        double at = 0.5 * (trunk.centers[s].y + trunk.centers[s + 1].y) / top;
        if (at < p.branches.min_height.base || at > p.branches.max_height.base) {
            for (int j = 0; j < 4; ++j) EXPECT_TRUE(trunk.sides[4 * s + j].is_valid());
            continue;
        }
        for (int j = 0; j < 4; ++j) {
            ++eligible;
            used += !trunk.sides[4 * s + j].is_valid();
        }
    }
    EXPECT_GT(eligible, 8);
    EXPECT_EQ(used, eligible);
    EXPECT_EQ(static_cast<int>(tm.limbs.size()) - 1, eligible);
    MeshCheck c = check_mesh(to_quad_mesh(tm));
    EXPECT_TRUE(c.ok());
    EXPECT_EQ(c.euler, 2);
}

TEST(Branches, FirstStepIsSquareAndPlanar) {
    TreeMesh tm = grow(test::preset("oak"), 4);
    ASSERT_GT(tm.limbs.size(), 3u);
    for (size_t i = 1; i < tm.limbs.size(); ++i) {
        const Ring& ring = tm.limbs[i].rings[1];
        glm::dvec3 p[4];
        for (int j = 0; j < 4; ++j) p[j] = tm.point(ring[j]);
        double side = glm::length(p[1] - p[0]);
        for (int j = 0; j < 4; ++j)
            EXPECT_NEAR(glm::length(p[(j + 1) & 3] - p[j]), side, 1e-9 * side);
        EXPECT_NEAR(glm::length(p[2] - p[0]), glm::length(p[3] - p[1]), 1e-9 * side);
        glm::dvec3 n = glm::normalize(glm::cross(p[1] - p[0], p[3] - p[0]));
        EXPECT_NEAR(glm::dot(p[2] - p[0], n), 0.0, 1e-9 * side);
        // Short: the first extrusion is a small fraction of the branch's width.
        EXPECT_LT(glm::length(tm.limbs[i].centers[1] - tm.limbs[i].centers[0]), side);
    }
}

TEST(Branches, ChildrenAreNeverThickerThanTheirParent) {
    for (const auto& name : test::shipped_tree_presets()) {
        Tree t = generate_tree(test::preset(name), 11);
        for (const auto& b : t.branches) {
            if (b.parent < 0) continue;
            const auto& parent = t.branches[b.parent];
            float thickest = *std::max_element(parent.ring_radii.begin(), parent.ring_radii.end());
            EXPECT_LE(b.ring_radii[1], thickest) << name;
            EXPECT_LE(b.ring_radii[1], b.ring_radii[0]) << name;  // ring 0: parent's girth there
        }
    }
}

TEST(Branches, GravityBendsBranchesDown) {
    TreeParams p = test::preset("oak");
    p.twigs.enabled = false;
    p.branches.wobble = {0, 0, 0, 90};
    auto mean_rise = [&](double strength) {
        p.branches.tropism = {{0, -1, 0}, {strength, 0, 0, 10}};
        Tree t = generate_tree(p, 8);
        double rise = 0;
        for (size_t i = 1; i < t.branches.size(); ++i)
            rise += t.branches[i].end.y - t.branches[i].start.y;
        return rise / double(t.branches.size() - 1);
    };
    EXPECT_GT(mean_rise(0.0), 0.5);
    EXPECT_LT(mean_rise(1.0), mean_rise(0.0) - 1.0);
}

// A pull that grows along the branch leaves its start as it was and bends its end further:
// the willow's branch rises, then arches over.
TEST(Branches, ATropismThatIncreasesBendsTheEndMoreThanTheStart) {
    TreeParams p = test::preset("oak");
    p.twigs.enabled = false;
    p.branches.wobble = {0, 0, 0, 90};
    p.branches.max_length = {8, 0, 1e-3, 1e5};
    p.branches.max_steps = {12, 0, 1, 256, true};
    p.branches.tropism = {{0, -1, 0}, {0, 0, 0, 10}};
    const TreeMesh still = grow(p, 8);
    p.branches.tropism.increase = 0.3;
    const TreeMesh arched = grow(p, 8);
    ASSERT_EQ(still.limbs.size(), arched.limbs.size());  // the pull changes no decision
    int bent = 0;
    for (size_t i = 1; i < still.limbs.size(); ++i) {
        const Limb &a = still.limbs[i], &b = arched.limbs[i];
        // The first extrusion is the same, the face being forced square along the normal.
        EXPECT_EQ(a.centers[1], b.centers[1]);
        if (a.centers.size() < 5 || b.centers.size() < 5) continue;
        const glm::dvec3 da = glm::normalize(a.centers.back() - a.centers[a.centers.size() - 2]);
        const glm::dvec3 db = glm::normalize(b.centers.back() - b.centers[b.centers.size() - 2]);
        EXPECT_LT(db.y, da.y - 0.2) << "branch " << i;
        EXPECT_LT(db.y, 0.0) << "branch " << i;  // past its arch, it falls
        ++bent;
    }
    EXPECT_GT(bent, 4);
    // A negative increase that would take the pull below zero stops at none.
    p.branches.tropism.increase = -5;
    const TreeMesh eased = grow(p, 8);
    for (size_t i = 0; i < still.limbs.size(); ++i)
        EXPECT_EQ(still.limbs[i].centers, eased.limbs[i].centers);
}

// Apical dominance: branches scale their length by where they start, from length_at_base at
// min_height to length_at_top at max_height.
TEST(Branches, LengthFollowsTheApicalProfile) {
    TreeParams p = test::preset("poplar");
    p.twigs.enabled = false;
    p.branches.probability.base = 1;
    p.branches.max_length = {3, 0, 1e-3, 1e5};
    p.branches.max_steps = {64, 0, 1, 256, true};
    p.branches.length_at_base = 1.5;
    p.branches.length_at_top = 0.2;
    const TreeMesh tm = grow(p, 5);
    const Limb& trunk = tm.limbs[0];
    const double top = trunk.centers.back().y;
    const double lo = p.branches.min_height.base, hi = p.branches.max_height.base;
    ASSERT_GT(tm.limbs.size(), 10u);
    for (size_t i = 1; i < tm.limbs.size(); ++i) {
        const Limb& L = tm.limbs[i];
        const int s = L.parent_segment;
        const double at = 0.5 * (trunk.centers[s].y + trunk.centers[s + 1].y) / top;
        const double scale = 1.5 + (0.2 - 1.5) * std::clamp((at - lo) / (hi - lo), 0.0, 1.0);
        // It stops at the first step that reaches its length, or on the ground.
        const double want = 3 * scale, step = 1.01 * p.branches.extrude_length.base +
                                              4 * p.branches.extrude_length.var;
        EXPECT_LE(L.length, want + step) << "branch " << i << " at " << at;
        if (L.centers.back().y > 0.5) {
            EXPECT_GE(L.length, want - 1e-9) << "branch " << i;
        }
    }
}

TEST(Branches, NothingGrowsIntoTheGround) {
    TreeParams p = test::preset("shrub");
    p.branches.angle = {175, 5, 0, 180};  // pointing down
    p.branches.tropism = {{0, -1, 0}, {3.0, 0, 0, 10}};
    p.branches.probability.base = 1;
    p.branches.min_height.base = 0;
    p.leaves.tropism = {{0, -1, 0}, {3.0, 0, 0, 10}};
    for (uint64_t seed : {1, 2, 3}) {
        Tree t = generate_tree(p, seed);
        for (const auto& v : t.control.positions) ASSERT_GE(v.y, 0.0f);
        for (const auto& v : t.leaves.position) ASSERT_GE(v.y, 0.0f);
        MeshCheck c = check_mesh(t.render);
        EXPECT_TRUE(c.ok());
        EXPECT_EQ(c.euler, 2);
    }
}

// Keyed streams: a branch is decided and grown from its own (parent, segment, side) key.
std::map<uint64_t, std::vector<glm::dvec3>> limbs_by_key(const TreeMesh& tm, int level) {
    std::map<uint64_t, std::vector<glm::dvec3>> out;
    for (const auto& L : tm.limbs)
        if (L.level == level) out[L.key] = L.centers;
    return out;
}

TEST(Branches, AddingBranchesLeavesTheOthersUnchanged) {
    TreeParams p = test::preset("oak");
    auto before = limbs_by_key(grow(p, 21), 1);
    p.branches.probability.base = 0.6;
    auto after = limbs_by_key(grow(p, 21), 1);
    EXPECT_GT(after.size(), before.size());
    for (const auto& [key, centers] : before) {
        ASSERT_TRUE(after.count(key)) << "branch disappeared";
        EXPECT_EQ(after[key], centers);
    }
}

// The second level grows where the preset asks for it: twigs on the oak's and the willow's
// branches, none when turned off.
TEST(Branches, SecondLevelGrowsTwigs) {
    for (const char* name : {"oak", "willow"}) {
        TreeParams p = test::preset(name);
        ASSERT_TRUE(p.twigs.enabled) << name;
        auto count = [](const Tree& t) {
            return std::count_if(t.branches.begin(), t.branches.end(),
                                 [](const BranchInfo& b) { return b.level == 2; });
        };
        EXPECT_GT(count(generate_tree(p, 4)), 5) << name;
        p.twigs.enabled = false;
        EXPECT_EQ(count(generate_tree(p, 4)), 0) << name;
    }
}

TEST(Branches, TwigsDoNotChangeBranches) {
    TreeParams p = test::preset("oak");
    auto with = limbs_by_key(grow(p, 5), 1);
    p.twigs.enabled = false;
    EXPECT_EQ(limbs_by_key(grow(p, 5), 1), with);
}

}  // namespace
}  // namespace pleinair
