// Leaf particles: counts, normalised attributes, unique labels, centre locator and fades.
#include "generators/leaves.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <map>
#include <set>
#include <tuple>

#include "generators/tree.h"
#include "generators/tree_mesh.h"
#include "test_util.h"

namespace pleinair {
namespace {

TEST(Leaves, AttributesAreNormalisedUniqueAndFinite) {
    for (const auto& name : test::shipped_tree_presets()) {
        TreeOptions o;
        o.tree_id = 17;
        Tree t = generate_tree(test::preset(name), 2, o);
        const LeafParticles& l = t.leaves;
        ASSERT_GT(l.size(), 100u) << name;
        EXPECT_EQ(l.normal.size(), l.size());
        float max_along = 0, max_center = 0;
        std::set<float> labels;
        for (size_t i = 0; i < l.size(); ++i) {
            ASSERT_TRUE(std::isfinite(l.position[i].x + l.position[i].y + l.position[i].z));
            ASSERT_NEAR(glm::length(l.normal[i]), 1.0f, 1e-5f);
            ASSERT_GE(l.branch_distance[i], 0.0f);
            ASSERT_LE(l.branch_distance[i], 1.0f);
            ASSERT_GE(l.center_distance[i], 0.0f);
            ASSERT_LE(l.center_distance[i], 1.0f);
            ASSERT_GT(l.label[i], 0.0f);
            ASSERT_LT(l.label[i], 1.0f);
            ASSERT_EQ(l.tree_id[i], 17u);
            ASSERT_GE(l.position[i].y, 0.0f);
            max_along = std::max(max_along, l.branch_distance[i]);
            max_center = std::max(max_center, l.center_distance[i]);
            labels.insert(l.label[i]);
        }
        EXPECT_EQ(max_along, 1.0f) << name;
        EXPECT_EQ(max_center, 1.0f) << name;
        EXPECT_EQ(labels.size(), l.size()) << name << ": labels must be unique";
    }
}

TEST(Leaves, NeighbouringParticlesGetDistantLabels) {
    Tree t = generate_tree(test::preset("oak"), 2);
    double mean_gap = 0;
    for (size_t i = 1; i < t.leaves.size(); ++i)
        mean_gap += std::abs(t.leaves.label[i] - t.leaves.label[i - 1]);
    mean_gap /= double(t.leaves.size() - 1);
    EXPECT_GT(mean_gap, 0.2);  // consecutive indices would give 1/N
}

// A leaf's label is its own (DESIGN.md: adding a branch never changes the others): the leaves
// both trees share keep their labels when more branches grow.
TEST(Leaves, AddingBranchesKeepsTheOtherLeavesLabels) {
    TreeParams p = test::preset("oak");
    Tree before = generate_tree(p, 21);
    p.branches.probability.base = 0.6;
    Tree after = generate_tree(p, 21);
    ASSERT_GT(after.leaves.size(), before.leaves.size());
    std::map<std::tuple<float, float, float>, float> label_at;
    for (size_t i = 0; i < after.leaves.size(); ++i) {
        const glm::vec3& q = after.leaves.position[i];
        label_at[{q.x, q.y, q.z}] = after.leaves.label[i];
    }
    size_t shared = 0;
    for (size_t i = 0; i < before.leaves.size(); ++i) {
        const glm::vec3& q = before.leaves.position[i];
        auto it = label_at.find({q.x, q.y, q.z});
        if (it == label_at.end()) continue;
        ++shared;
        EXPECT_EQ(it->second, before.leaves.label[i]);
    }
    EXPECT_GT(shared, before.leaves.size() / 2);
}

TEST(Leaves, EveryEligibleVertexEmitsAFullImpliedBranchAtProbabilityOne) {
    TreeParams p = test::preset("poplar");
    p.leaves.probability.base = 1;
    p.leaves.tropism = {{0, 1, 0},
                        {0.5, 0, 0, 10}};  // upward: no strand is cut short by the ground
    TreeMesh tm;
    grow_skeleton(tm, p, 6);
    size_t eligible = 0;
    for (const Limb& L : tm.limbs) {
        int last = int(L.rings.size()) - 1;
        for (int r = 0; r <= last; ++r) {
            const auto& l = p.leaves;  // the preset's values have no variance
            bool ok = L.level == 0 ? (r >= l.lowest_step_trunk.base &&
                                      r <= last - l.trim_top_steps_trunk.base)
                                   : (r >= std::max(1.0, l.steps_from_center.base) &&
                                      r <= last - l.steps_from_tip.base);
            eligible += ok ? 4 : 0;
        }
    }
    glm::dvec3 center;
    LeafParticles l = emit_leaves(tm, p, 6, 0, center);
    EXPECT_EQ(l.size(), eligible * size_t(p.leaves.branching_steps.base));
    p.leaves.probability.base = 0;
    EXPECT_EQ(emit_leaves(tm, p, 6, 0, center).size(), 0u);
    EXPECT_EQ(center, tm.limbs[0].centers.back());  // no canopy: the top of the trunk
}

// /leaves/lowest_level keeps leaves off the lower levels, and the others' leaves stay as
// they were (each emitter draws from its own stream).
TEST(Leaves, LowestLevelKeepsLeavesOffTheLowerLimbs) {
    TreeParams p = test::preset("oak");
    p.leaves.lowest_level = 0;
    TreeMesh tm;
    grow_skeleton(tm, p, 6);
    glm::dvec3 center;
    const LeafParticles all = emit_leaves(tm, p, 6, 0, center);
    for (int level : {1, 2}) {
        p.leaves.lowest_level = level;
        const LeafParticles some = emit_leaves(tm, p, 6, 0, center);
        std::vector<glm::vec3> kept;
        for (size_t i = 0; i < all.size(); ++i)
            if (tm.limbs[all.limb[i]].level >= level) kept.push_back(all.position[i]);
        ASSERT_GT(kept.size(), 100u);
        ASSERT_LT(kept.size(), all.size());
        EXPECT_EQ(some.position, kept) << "lowest level " << level;
        for (uint32_t limb : some.limb) EXPECT_GE(tm.limbs[limb].level, level);
    }
}

// A strand's pull that grows with its length hangs its last leaves lower than a constant one.
TEST(Leaves, ATropismThatIncreasesHangsTheStrandsEnds) {
    TreeParams p = test::preset("birch");
    p.leaves.branching_steps = {8, 0, 1, 64, true};
    p.leaves.tropism = {{0, -1, 0}, {0.1, 0, 0, 10}};
    TreeMesh tm;
    grow_skeleton(tm, p, 2);
    glm::dvec3 center;
    const LeafParticles flat = emit_leaves(tm, p, 2, 0, center);
    p.leaves.tropism.increase = 2;
    const LeafParticles hung = emit_leaves(tm, p, 2, 0, center);
    double mean_flat = 0, mean_hung = 0;
    for (const auto& q : flat.position) mean_flat += q.y / flat.size();
    for (const auto& q : hung.position) mean_hung += q.y / hung.size();
    EXPECT_LT(mean_hung, mean_flat - 0.3);
}

TEST(Leaves, ParticlesFollowTheirImpliedBranch) {
    TreeParams p = test::preset("birch");
    p.leaves.probability.base = 1;
    p.leaves.branch_dir_wobble = {0, 0, 0, 180};
    p.leaves.branching_distance = {0.3, 0, 1e-4, 1e3};
    p.leaves.tropism.strength.base = 0;
    Tree t = generate_tree(p, 3);
    const auto& l = t.leaves;
    const size_t k = size_t(p.leaves.branching_steps.base);
    ASSERT_EQ(l.size() % k, 0u);
    for (size_t i = 0; i < l.size(); ++i) {
        if (i % k == 0) continue;
        // Each particle sits one branching distance from the previous, along its own normal.
        glm::vec3 step = l.position[i] - l.position[i - 1];
        EXPECT_NEAR(glm::length(step), 0.3f, 1e-4f);
        EXPECT_GT(glm::dot(glm::normalize(step), l.normal[i]), 0.9999f);
        EXPECT_GT(l.branch_distance[i], l.branch_distance[i - 1]);
    }
}

TEST(Leaves, CentreIsTheCanopyCentroidPlusTheOffset) {
    TreeParams p = test::preset("oak");
    Tree t = generate_tree(p, 2);
    glm::dvec3 sum(0);
    for (const auto& q : t.leaves.position) sum += glm::dvec3(q);
    glm::vec3 centroid(sum / double(t.leaves.size()));
    EXPECT_LT(glm::length(t.center - centroid), 1e-3f);
    p.center_offset = {0, 2, 0};
    Tree moved = generate_tree(p, 2);
    EXPECT_LT(glm::length(moved.center - (centroid + glm::vec3(0, 2, 0))), 1e-3f);
    EXPECT_EQ(moved.leaves.position, t.leaves.position);  // the offset moves only the locator
}

TEST(Leaves, OuterLeavesFadeFirst) {
    TreeParams p = test::preset("oak");
    p.leaves.fade.threshold_var = 0;
    p.leaves.fade.length = {0.3, 0, 0, 10};
    p.leaves.fade.length_min = 0.2;
    Tree t = generate_tree(p, 2);
    const auto& l = t.leaves;
    std::vector<size_t> order(l.size());
    for (size_t i = 0; i < order.size(); ++i) order[i] = i;
    // Distance from the centre in units of the crown's spread along each axis.
    glm::dvec3 spread(0.0), c(t.center);
    for (const glm::vec3& q : l.position) spread += (glm::dvec3(q) - c) * (glm::dvec3(q) - c);
    spread = glm::sqrt(spread / static_cast<double>(l.size()));
    std::vector<double> d(l.size());
    for (size_t i = 0; i < l.size(); ++i)
        d[i] = glm::length((glm::dvec3(l.position[i]) - c) / spread);
    std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return d[a] < d[b]; });
    // Without variance: ordered by that distance, save where two leaves' distances are the
    // same to the float precision this test measures them in (the generator's are doubles).
    for (size_t i = 1; i < order.size(); ++i) {
        if (d[order[i]] - d[order[i - 1]] <= 1e-6 * d[order[i]]) continue;
        ASSERT_LE(l.fade_begin[order[i]], l.fade_begin[order[i - 1]])
            << d[order[i]] << " against " << d[order[i - 1]];
    }
    size_t kept = 0;
    for (size_t i = 0; i < l.size(); ++i) {
        if (l.fade_begin[i] > 1.0f) {  // never fades
            ++kept;
            continue;
        }
        ASSERT_GE(l.fade_begin[i], 0.0f);
        ASSERT_LE(l.fade_end[i], 1.0f + 1e-6f);  // gone by the far circle: none half there
        ASSERT_GE(l.fade_end[i] - l.fade_begin[i], 0.2f - 1e-6f);
    }
    // The innermost fifth (p.leaves.fade.keep) never fades.
    EXPECT_NEAR(static_cast<double>(kept) / l.size(), p.leaves.fade.keep, 1.5 / l.size());
    EXPECT_LT(l.fade_begin[order.back()], 0.01f);  // the outermost starts at the near circle
    EXPECT_GT(l.fade_end[order.front()], 1.0f);    // the innermost survives the far circle
}

TEST(Leaves, FadesProgressAtOnePaceWhateverTheCrown) {
    // By rank, not by raw distance: the share of leaves gone grows evenly across the circles.
    TreeParams p = test::preset("oak");
    p.leaves.fade.threshold_var = 0;
    const Tree t = generate_tree(p, 3);
    const auto& l = t.leaves;
    ASSERT_GT(l.size(), 500u);
    for (double v : {0.25, 0.5, 0.75, 1.0}) {
        size_t gone = 0;
        for (size_t i = 0; i < l.size(); ++i) gone += l.fade_end[i] <= v;
        // Fading leaves (four fifths) end evenly over [length, 1] of the distance value.
        const double len = p.leaves.fade.length.base;
        const double expect =
            (1 - p.leaves.fade.keep) * std::clamp((v - len) / (1 - len), 0.0, 1.0);
        EXPECT_NEAR(static_cast<double>(gone) / l.size(), expect, 0.08) << v;
    }
}

TEST(Leaves, FadeVarianceStillFadesOuterLeavesFirstOnAverage) {
    Tree t = generate_tree(test::preset("oak"), 2);
    double outer = 0, inner = 0;
    int n_outer = 0, n_inner = 0;
    for (size_t i = 0; i < t.leaves.size(); ++i) {
        if (t.leaves.center_distance[i] > 0.6f) outer += t.leaves.fade_begin[i], ++n_outer;
        if (t.leaves.center_distance[i] < 0.4f) inner += t.leaves.fade_begin[i], ++n_inner;
    }
    ASSERT_GT(n_outer, 0);
    ASSERT_GT(n_inner, 0);
    EXPECT_LT(outer / n_outer + 0.2, inner / n_inner);
}

}  // namespace
}  // namespace pleinair
