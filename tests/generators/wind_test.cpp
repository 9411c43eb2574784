// The wind's pose of a tree (generators/wind.h): a pure function of time in any order, gusts
// without a jump, still air leaving every particle where it was, stiffness that holds, bends
// that keep every limb's length, and the reach that bounds every particle's move.
#include "generators/wind.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <glm/geometric.hpp>
#include <thread>

#include "tests/test_util.h"

namespace pleinair {
namespace {

struct Posed {
    Tree tree;
    WindRig rig;
};

const Posed& willow() {
    static const Posed p = [] {
        Posed out;
        out.tree = generate_tree(test::preset("willow"), 4);
        out.rig = build_wind_rig(out.tree, nullptr);
        return out;
    }();
    return p;
}

WindAtTree wind(double speed, double t) {
    WindAtTree w;
    w.direction = glm::normalize(glm::vec3(1.0f, 0.0f, -0.3f));
    w.speed = speed;
    w.time = t;
    w.seed = 11;
    return w;
}

bool same_bits(const TreePose& a, const TreePose& b) {
    return a.joints.size() == b.joints.size() && a.reach == b.reach && a.flutter == b.flutter &&
           std::memcmp(a.joints.data(), b.joints.data(), a.joints.size() * sizeof(LimbMotion)) == 0;
}

TEST(Wind, ThePoseAtATimeIsTheSameInAnyOrder) {
    const Posed& w = willow();
    const WindStiffness st;
    const double times[] = {0.0, 0.37, 5.0, 123.456, 2.0, 0.37};
    std::vector<TreePose> forward, backward;
    for (double t : times) forward.push_back(pose_tree(w.tree, w.rig, st, wind(6, t), {}));
    for (int i = 5; i >= 0; --i)
        backward.insert(backward.begin(), pose_tree(w.tree, w.rig, st, wind(6, times[i]), {}));
    for (size_t i = 0; i < forward.size(); ++i) EXPECT_TRUE(same_bits(forward[i], backward[i]));
    EXPECT_TRUE(same_bits(forward[1], forward[5]));
    EXPECT_FALSE(same_bits(forward[0], forward[1]));  // it moves
    // The flutter of a leaf is its own and moves with time.
    EXPECT_NE(leaf_flutter(forward[1], 0.25f), leaf_flutter(forward[1], 0.75f));
    EXPECT_NE(leaf_flutter(forward[1], 0.25f), leaf_flutter(forward[2], 0.25f));
}

// Each tree's phases are its own, from its seed alone: a pose is the same whether its thread
// posed other trees before it or none (a memo kept per thread would hand the second tree the
// first one's phase), and two trees in the same wind do not sway in step.
TEST(Wind, EachTreesPhaseIsItsOwnWhateverItsThreadPosedBefore) {
    const Posed& w = willow();
    const WindStiffness st;
    auto at = [](uint64_t seed) {
        WindAtTree a = wind(6, 1.3);
        a.seed = seed;
        return a;
    };
    TreePose alone, after_other, other;
    std::thread([&] { alone = pose_tree(w.tree, w.rig, st, at(202), {}); }).join();
    std::thread([&] {
        other = pose_tree(w.tree, w.rig, st, at(101), {});
        after_other = pose_tree(w.tree, w.rig, st, at(202), {});
    }).join();
    ASSERT_FALSE(alone.at_rest());
    EXPECT_TRUE(same_bits(alone, after_other)) << "a pose depends on what its thread posed before";
    EXPECT_FALSE(same_bits(alone, other)) << "two trees' seeds, one sway";
    // And in the same thread, the first seed's pose again after the second's.
    TreePose again;
    std::thread([&] {
        pose_tree(w.tree, w.rig, st, at(202), {});
        again = pose_tree(w.tree, w.rig, st, at(101), {});
    }).join();
    EXPECT_TRUE(same_bits(other, again));
}

TEST(Wind, GustsAndWavesHaveNoJump) {
    // Across many cell boundaries in time and across the wind, the envelope moves by no more
    // than its slope allows: quintic interpolation has slope at most 15/8 per cell.
    for (int k = -50; k < 50; ++k)
        for (double cross : {-3.7, 0.0, 0.5, 12.25}) {
            const double eps = 1e-6;
            const double a = gust_envelope(k - eps, cross, 9), b = gust_envelope(k + eps, cross, 9);
            ASSERT_NEAR(a, b, 4 * eps) << k;
            ASSERT_GE(a, 0.0);
            ASSERT_LE(a, 1.0);
            const double c = gust_envelope(k + 0.3, std::floor(cross) - eps, 9),
                         d = gust_envelope(k + 0.3, std::floor(cross) + eps, 9);
            ASSERT_NEAR(c, d, 4 * eps);
        }
    // It does vary: gusts come and go.
    double lo = 1, hi = 0;
    for (int k = 0; k < 200; ++k) {
        const double g = gust_envelope(0.1 * k, 0.0, 9);
        lo = std::min(lo, g), hi = std::max(hi, g);
    }
    EXPECT_GT(hi - lo, 0.5);
    // The waves: continuous at their corners, within [-1, 1].
    for (double x : {0.0, 0.5, 1.0, 7.5, -2.0}) {
        EXPECT_NEAR(smooth_triangle_wave(x - 1e-7), smooth_triangle_wave(x + 1e-7), 1e-6);
        for (double f : {0.3, 1.7})
            for (double t : {x, x + 0.01}) EXPECT_LE(std::abs(sway_wave(t, f, 0.4)), 1.0);
    }
    // A pose over time: no joint moves by more than its speed allows between close times.
    const Posed& w = willow();
    for (double t : {0.0, 2.99, 3.0, 9.5}) {
        const TreePose a = pose_tree(w.tree, w.rig, {}, wind(8, t), {});
        const TreePose b = pose_tree(w.tree, w.rig, {}, wind(8, t + 1e-4), {});
        for (size_t k = 0; k < a.joints.size(); ++k)
            ASSERT_LT(glm::length(a.joints[k].apply(w.rig.center[k]) -
                                  b.joints[k].apply(w.rig.center[k])),
                      1e-2f);
    }
    // Not finite: still air.
    EXPECT_EQ(gust_envelope(NAN, 0.0, 1), 0.0);
    EXPECT_EQ(smooth_triangle_wave(INFINITY), 0.0);
}

TEST(Wind, StillAirLeavesEveryParticleWhereItWas) {
    const Posed& w = willow();
    for (double speed : {0.0, -3.0, double(NAN)}) {
        const TreePose p = pose_tree(w.tree, w.rig, {}, wind(speed, 4.0), {});
        EXPECT_TRUE(p.at_rest());
        EXPECT_EQ(p.flutter, 0.0f);
        EXPECT_EQ(p.reach, 0.0f);
        EXPECT_EQ(leaf_flutter(p, 0.3f), 0.0f);
    }
    WindTiers none;
    none.trunk = none.limbs = none.leaves = 0;
    const TreePose p = pose_tree(w.tree, w.rig, {}, wind(8, 4.0), none);
    EXPECT_TRUE(p.at_rest());
    EXPECT_EQ(p.flutter, 0.0f);
}

// The mean move of the tree's leaves at a pose.
double mean_leaf_move(const Posed& w, const TreePose& p) {
    double sum = 0;
    const LeafParticles& L = w.tree.leaves;
    for (size_t j = 0; j < L.size(); ++j) {
        const glm::vec3 q = p.joints[w.rig.leaf_joint[j]].apply(L.position[j]);
        sum += glm::length(q - L.position[j]);
    }
    return sum / std::max<size_t>(1, L.size());
}

TEST(Wind, AStifferTreeBendsLess) {
    const Posed& w = willow();
    WindStiffness soft, stiff_limbs, stiff_trunk, stiff_leaves;
    stiff_limbs.limbs = 2;
    stiff_trunk.trunk = 2;
    stiff_leaves.leaves = 2;
    for (double t : {0.5, 3.0, 7.25}) {
        const TreePose a = pose_tree(w.tree, w.rig, soft, wind(6, t), {});
        const TreePose b = pose_tree(w.tree, w.rig, stiff_limbs, wind(6, t), {});
        const TreePose c = pose_tree(w.tree, w.rig, stiff_trunk, wind(6, t), {});
        const TreePose d = pose_tree(w.tree, w.rig, stiff_leaves, wind(6, t), {});
        EXPECT_LT(mean_leaf_move(w, b), mean_leaf_move(w, a));
        EXPECT_LT(mean_leaf_move(w, c), mean_leaf_move(w, a));
        EXPECT_LT(d.flutter, a.flutter);
        // The trunk's top moves less with a stiffer trunk (limbs as they were).
        const uint32_t top = w.rig.first_joint[1] - 1;
        const glm::vec3 ct = w.rig.center[top];
        EXPECT_LT(glm::length(c.joints[top].apply(ct) - ct),
                  glm::length(a.joints[top].apply(ct) - ct));
    }
    // And a stronger wind bends more; a gale stays bounded.
    const double breeze = mean_leaf_move(w, pose_tree(w.tree, w.rig, soft, wind(3, 1), {}));
    const double strong = mean_leaf_move(w, pose_tree(w.tree, w.rig, soft, wind(10, 1), {}));
    const TreePose gale = pose_tree(w.tree, w.rig, soft, wind(1e6, 1), {});
    EXPECT_LT(breeze, strong);
    EXPECT_TRUE(std::isfinite(mean_leaf_move(w, gale)));
    EXPECT_LT(gale.flutter, 0.5f);
}

TEST(Wind, BendsKeepEveryLimbsLengthAndItsPlaceOnItsParent) {
    const Posed& w = willow();
    for (double speed : {4.0, 12.0, 40.0}) {
        const TreePose p = pose_tree(w.tree, w.rig, {}, wind(speed, 2.5), {});
        ASSERT_FALSE(p.at_rest());
        for (size_t i = 0; i < w.tree.branches.size(); ++i) {
            const uint32_t first = w.rig.first_joint[i], last = w.rig.first_joint[i + 1];
            for (uint32_t k = first; k + 1 < last; ++k) {
                const glm::vec3 a = w.rig.center[k], b = w.rig.center[k + 1];
                // Ring k + 1 lies beyond joint k; it moves with joint k + 1, which leaves it
                // where joint k takes it.
                const glm::vec3 pa = p.joints[k].apply(a), pb = p.joints[k + 1].apply(b);
                ASSERT_NEAR(glm::length(pb - pa), glm::length(b - a),
                            1e-4f * (1 + glm::length(b - a)));
                ASSERT_LT(glm::length(p.joints[k].apply(b) - pb), 1e-4f);
            }
            // Its base stays where its parent's joint takes that point.
            if (w.rig.parent_joint[i] != WindRig::kNone) {
                const glm::vec3 c = w.rig.center[first];
                ASSERT_LT(glm::length(p.joints[first].apply(c) -
                                      p.joints[w.rig.parent_joint[i]].apply(c)),
                          1e-4f);
            }
        }
        // The reach bounds every leaf's move.
        const LeafParticles& L = w.tree.leaves;
        float most = 0;
        for (size_t j = 0; j < L.size(); ++j)
            most = std::max(most, glm::length(p.joints[w.rig.leaf_joint[j]].apply(L.position[j]) -
                                              L.position[j]));
        EXPECT_LE(most, p.reach * (1 + 1e-5f));
        EXPECT_GT(most, 0.1f * p.reach);  // and is not far above it
    }
}

TEST(Wind, TheRigHangsEveryParticleOnItsOwnLimb) {
    const Posed& w = willow();
    const LeafParticles& L = w.tree.leaves;
    ASSERT_EQ(w.rig.leaf_joint.size(), L.size());
    for (size_t j = 0; j < L.size(); ++j) {
        const uint32_t k = w.rig.leaf_joint[j];
        ASSERT_GE(k, w.rig.first_joint[L.limb[j]]);
        ASSERT_LT(k, w.rig.first_joint[L.limb[j] + 1]);
    }
    // Parents come before... any order: every limb but the trunk hangs from a joint of its parent.
    for (size_t i = 1; i < w.tree.branches.size(); ++i) {
        const int parent = w.tree.branches[i].parent;
        ASSERT_GE(parent, 0);
        const uint32_t k = w.rig.parent_joint[i];
        ASSERT_GE(k, w.rig.first_joint[static_cast<size_t>(parent)]);
        ASSERT_LT(k, w.rig.first_joint[static_cast<size_t>(parent) + 1]);
    }
    EXPECT_EQ(w.rig.parent_joint[0], WindRig::kNone);
    // A tree with no limbs: a rig with nothing to move, posed at rest.
    const Tree empty;
    const WindRig none = build_wind_rig(empty, nullptr);
    EXPECT_TRUE(pose_tree(empty, none, {}, wind(8, 1), {}).at_rest());
}

}  // namespace
}  // namespace pleinair
