// Whole trees: valid meshes for every preset, determinism, family resemblance, species shapes
// and the hard cases (variance 0, probabilities 0 and 1, extreme units, far from the origin).
#include "generators/tree.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <glm/geometric.hpp>

#include "test_util.h"

namespace pleinair {
namespace {

void expect_valid(const Tree& t, const std::string& what) {
    for (const QuadMesh* m : {&t.control, &t.render}) {
        MeshCheck c = check_mesh(*m);
        EXPECT_TRUE(c.ok()) << what;
        EXPECT_EQ(c.euler, 2) << what;
        EXPECT_GT(c.min_face_area, 0.0) << what;
    }
    if (!t.lod.quads.empty()) {
        MeshCheck c = check_mesh(t.lod);
        EXPECT_TRUE(c.ok()) << what;
        EXPECT_EQ(c.euler, 2) << what;
    }
    for (size_t i = 0; i < t.leaves.size(); ++i) {
        const auto& p = t.leaves.position[i];
        ASSERT_TRUE(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z)) << what;
        ASSERT_TRUE(std::isfinite(t.leaves.fade_begin[i]) && std::isfinite(t.leaves.fade_end[i]));
        ASSERT_TRUE(std::isfinite(t.leaves.normal[i].x)) << what;
    }
    EXPECT_TRUE(std::isfinite(t.center.x + t.center.y + t.center.z)) << what;
    // Every control face is owned by exactly one limb, and the render mesh is the control
    // mesh's faces each cut into 4^render_levels pieces.
    std::vector<int> owners(t.control.quads.size(), 0);
    for (const BranchInfo& b : t.branches) {
        ASSERT_EQ(b.faces.size(), b.face_segments.size()) << what;
        ASSERT_EQ(b.faces.size(), b.face_slots.size()) << what;
        // Slots name a face's place on its limb: distinct, in order.
        EXPECT_TRUE(std::adjacent_find(b.face_slots.begin(), b.face_slots.end(),
                                       [](uint32_t x, uint32_t y) { return x >= y; }) ==
                    b.face_slots.end())
            << what;
        for (size_t k = 0; k < b.faces.size(); ++k) {
            ASSERT_LT(b.faces[k], owners.size()) << what;
            ++owners[b.faces[k]];
            ASSERT_LT(b.face_segments[k] + 1, b.ring_centers.size()) << what;
        }
    }
    EXPECT_EQ(std::count(owners.begin(), owners.end(), 1), static_cast<long>(owners.size()))
        << what;
    // The only face no limb records itself is the trunk's base, its first face.
    const BranchInfo& trunk = t.branches[0];
    ASSERT_GE(trunk.faces.size(), 2u) << what;
    EXPECT_EQ(trunk.faces.back(), 0u) << what;
    EXPECT_EQ(trunk.face_slots.back(), trunk.face_slots[trunk.faces.size() - 2] + 1) << what;
    EXPECT_EQ(t.render.quads.size(), t.control.quads.size() << (2 * t.render_levels)) << what;
}

// A limb's side face lies between the two rings of its segment: the centroid projects onto
// the segment's axis near its middle, at about the ring radius from it (a face given to the
// wrong segment or limb would project outside it).
TEST(Tree, LimbsOwnTheirSideFacesSegmentBySegment) {
    Tree t = generate_tree(test::preset("oak"), 7);
    size_t checked = 0;
    for (const BranchInfo& b : t.branches) {
        // Sides first, then the cap (and, for the trunk, its base).
        const size_t sides = b.faces.size() - (b.id == 0 ? 2 : 1);
        for (size_t k = 0; k < sides; ++k) {
            const glm::uvec4 q = t.control.quads[b.faces[k]];
            glm::vec3 c(0.0f);
            for (int j = 0; j < 4; ++j) c += 0.25f * t.control.positions[q[j]];
            const uint32_t s = b.face_segments[k];
            const glm::vec3 c0 = b.ring_centers[s], axis = b.ring_centers[s + 1] - c0;
            const float len = glm::length(axis);
            const float along = glm::dot(c - c0, axis / len) / len;
            const float dist = glm::length(c - c0 - axis * along);
            EXPECT_GT(along, 0.2f) << b.id << " " << k;
            EXPECT_LT(along, 0.8f) << b.id << " " << k;
            // Ring 0 of a branch is the parent's face, a rectangle as long as the parent's
            // segment: up to a few radii across (3.1 for the oak's limbs, which keep 0.92 of
            // their parent face's width, first_taper).
            EXPECT_LT(dist, 4.0f * std::max(b.ring_radii[s], b.ring_radii[s + 1])) << b.id;
            EXPECT_GT(dist, 0.3f * b.ring_radii[s + 1]) << b.id << " " << k;
            ++checked;
        }
    }
    EXPECT_GT(checked, 200u);
}

TEST(Tree, EveryPresetGivesClosedManifoldMeshes) {
    for (const auto& name : test::shipped_tree_presets())
        for (uint64_t seed : {1, 2, 3, 4}) {
            Tree t = generate_tree(test::preset(name), seed);
            expect_valid(t, name + " seed " + std::to_string(seed));
            EXPECT_GT(t.render.positions.size(), t.control.positions.size() * 10);
            EXPECT_LT(t.lod.quads.size(), t.render.quads.size());
        }
}

// A limb keeps its leaves exactly when one of the leaves it bears never fades, and some oak
// twigs do while others do not (the level of detail keeps the first ones' bark).
TEST(Tree, ALimbKeepsLeavesWhenOneOfItsLeavesNeverFades) {
    for (const auto& name : test::shipped_tree_presets()) {
        const Tree t = generate_tree(test::preset(name), 3);
        std::vector<int> kept(t.branches.size(), 0);
        for (size_t i = 0; i < t.leaves.size(); ++i) {
            ASSERT_LT(t.leaves.limb[i], t.branches.size()) << name;
            kept[t.leaves.limb[i]] += t.leaves.fade_begin[i] > 1.0f;
        }
        for (const BranchInfo& b : t.branches)
            EXPECT_EQ(b.keeps_leaves, kept[b.id] > 0) << name << " limb " << b.id;
    }
    const Tree oak = generate_tree(test::preset("oak"), 1);
    int keeping = 0, twigs = 0;
    for (const BranchInfo& b : oak.branches)
        if (b.level == 2) ++twigs, keeping += b.keeps_leaves;
    EXPECT_GT(keeping, 0);
    EXPECT_LT(keeping, twigs);
}

TEST(Tree, SamePresetAndSeedGiveTheSameBytes) {
    for (const auto& name : test::shipped_tree_presets()) {
        TreeParams p = test::preset(name);
        EXPECT_EQ(test::hash_tree(generate_tree(p, 42)), test::hash_tree(generate_tree(p, 42)));
        EXPECT_NE(test::hash_tree(generate_tree(p, 42)), test::hash_tree(generate_tree(p, 43)));
    }
}

struct Shape {
    float height, width, crown_base, low_leaf_fraction;
    size_t leaves;
};

// A few numbers that tell species apart at a glance: height, spread, where the crown starts,
// how much foliage hangs low.
Shape shape_of(const Tree& t) {
    Bounds b = bounds_of(t.leaves.position);
    Bounds m = bounds_of(t.render.positions);
    float top = std::max(b.max.y, m.max.y);
    Shape s;
    s.height = top;
    s.width = std::max(b.max.x - b.min.x, b.max.z - b.min.z);
    std::vector<float> ys;
    for (const auto& p : t.leaves.position) ys.push_back(p.y);
    std::sort(ys.begin(), ys.end());
    s.crown_base = ys[ys.size() / 20] / top;  // 5th percentile of leaf height
    s.low_leaf_fraction =
        float(std::lower_bound(ys.begin(), ys.end(), 0.35f * top) - ys.begin()) / ys.size();
    s.leaves = ys.size();
    return s;
}

// What makes each shipped family recognisable, checked on every member (the family means are
// checked with tighter margins below).
bool recognisable(const std::string& name, const Shape& s) {
    if (name == "oak") return s.height / s.width < 1.3f && s.height > 9;
    if (name == "poplar") return s.height / s.width > 2.4f;
    // The willow's leaves hang along branchlets from its arches towards the ground: its
    // lowest leaves are low, and a good share of them hang in the lowest third.
    if (name == "willow")
        return s.crown_base < 0.25f && s.low_leaf_fraction > 0.15f && s.height < 12;
    if (name == "birch") return s.crown_base > 0.3f && s.height / s.width > 1.2f && s.leaves < 1800;
    if (name == "pine") return s.crown_base > 0.48f;
    if (name == "shrub") return s.height < 5.5f;
    return true;
}

TEST(Tree, ChangingOnlyTheSeedGivesARecognisablySimilarTree) {
    for (const auto& name : test::shipped_tree_presets()) {
        TreeParams p = test::preset(name);
        std::vector<Shape> family;
        for (uint64_t seed = 1; seed <= 9; ++seed)
            family.push_back(shape_of(generate_tree(p, seed)));
        std::vector<float> heights;
        for (const Shape& s : family) heights.push_back(s.height);
        std::nth_element(heights.begin(), heights.begin() + 4, heights.end());
        for (size_t i = 0; i < family.size(); ++i) {
            EXPECT_TRUE(recognisable(name, family[i]))
                << name << " member " << i << ": height " << family[i].height << ", width "
                << family[i].width << ", crown base " << family[i].crown_base << ", low leaves "
                << family[i].low_leaf_fraction;
            EXPECT_NEAR(family[i].height / heights[4], 1.0, 0.45) << name << " member " << i;
        }
    }
}

TEST(Tree, PresetsReadAsDifferentSpecies) {
    auto mean = [](const std::string& name) {
        Shape m{0, 0, 0, 0, 0};
        for (uint64_t seed = 1; seed <= 6; ++seed) {
            Shape s = shape_of(generate_tree(test::preset(name), seed));
            m.height += s.height / 6, m.width += s.width / 6, m.crown_base += s.crown_base / 6;
            m.low_leaf_fraction += s.low_leaf_fraction / 6, m.leaves += s.leaves / 6;
        }
        return m;
    };
    auto print = [](const char* n, const Shape& s) {
        std::printf("%-7s height %5.2f width %5.2f crown base %4.2f low leaves %4.2f leaves %zu\n",
                    n, s.height, s.width, s.crown_base, s.low_leaf_fraction, s.leaves);
    };
    Shape oak = mean("oak"), poplar = mean("poplar"), willow = mean("willow"),
          birch = mean("birch"), pine = mean("pine"), shrub = mean("shrub");
    for (auto [n, s] : {std::pair{"oak", oak},
                        {"poplar", poplar},
                        {"willow", willow},
                        {"birch", birch},
                        {"pine", pine},
                        {"shrub", shrub}})
        print(n, s);
    EXPECT_GT(poplar.height / poplar.width, 2.5f);  // a column
    EXPECT_LT(oak.height / oak.width, 1.2f);        // broader than tall
    EXPECT_GT(willow.low_leaf_fraction, 0.3f);      // foliage hangs low
    EXPECT_GT(pine.crown_base, 0.5f);               // bare trunk, crown on top
    EXPECT_GT(pine.width / (pine.height * (1 - pine.crown_base)), 1.8f);  // flat parasol
    EXPECT_LT(shrub.height, 5.0f);                                        // low
    EXPECT_GT(birch.crown_base, 0.3f);
    // Fewer leaves than the oak's (how airy each crown is, bench trees measures: the sky in it).
    EXPECT_LT(birch.leaves, oak.leaves * 3 / 4);
    EXPECT_GT(oak.height, shrub.height * 2);
}

TEST(Tree, ZeroVarianceAndExtremeProbabilitiesStayValid) {
    TreeParams p = test::preset("oak");
    for (Param* q :
         {&p.trunk.initial_size, &p.trunk.max_height, &p.trunk.extrude_length, &p.trunk.twist,
          &p.trunk.taper, &p.trunk.wobble, &p.branches.angle, &p.branches.max_length,
          &p.branches.extrude_length, &p.branches.taper, &p.branches.wobble, &p.leaves.branch_angle,
          &p.leaves.branching_distance, &p.leaves.branch_dir_wobble})
        q->var = 0;
    expect_valid(generate_tree(p, 1), "variance 0");
    for (double prob : {0.0, 1.0}) {
        p.branches.probability.base = p.twigs.probability.base = p.leaves.probability.base = prob;
        Tree t = generate_tree(p, 1);
        expect_valid(t, "probability " + std::to_string(prob));
        EXPECT_EQ(t.branches.size() == 1, prob == 0.0);
        EXPECT_EQ(t.leaves.size() == 0, prob == 0.0);
    }
}

TEST(Tree, TaperZeroEverywhereStaysValid) {
    TreeParams p = test::preset("oak");
    p.trunk.taper = {0, 0, 0, 1};
    p.branches.taper = {0, 0, 0, 1};
    p.twigs.taper = {0, 0, 0, 1};
    expect_valid(generate_tree(p, 1), "taper 0");
    p.trunk.taper = {0.6, 0, 0, 1};
    expect_valid(generate_tree(p, 1), "branch taper 0");
}

TEST(Tree, HalfTurnTwistPerStepStaysValid) {
    TreeParams p = test::preset("willow");
    p.trunk.twist = p.branches.twist = p.twigs.twist = {180, 0, -360, 360};
    expect_valid(generate_tree(p, 3), "twist 180");
}

// The unit scales every length: a tree at unit u is the unit-1 tree scaled by u.
TEST(Tree, ExtremeUnitsScaleTheSameTree) {
    TreeParams p = test::preset("oak");
    Tree ref = generate_tree(p, 9);
    for (double unit : {1e-4, 1e4}) {
        p.unit = unit;
        Tree t = generate_tree(p, 9);
        expect_valid(t, "unit " + std::to_string(unit));
        ASSERT_EQ(t.render.positions.size(), ref.render.positions.size());
        ASSERT_EQ(t.leaves.size(), ref.leaves.size());
        float scale = glm::length(bounds_of(ref.render.positions).max);
        for (size_t i = 0; i < ref.render.positions.size(); ++i)
            ASSERT_LT(glm::length(t.render.positions[i] / float(unit) - ref.render.positions[i]),
                      1e-4f * scale);
        EXPECT_EQ(t.leaves.label, ref.leaves.label);
        for (size_t i = 0; i < ref.leaves.size(); ++i)
            ASSERT_NEAR(t.leaves.center_distance[i], ref.leaves.center_distance[i], 1e-5f);
    }
}

// Growth never reads the origin: a tree is grown in its own frame and only placed, so one
// grown 141 km out is the same tree bit for bit (this fails if any draw, noise or threshold
// took the world position). Where it lands is tested on the files written
// (TreeIo.FarFromOriginWritesFiniteWorldPositions) and on the painted landscape
// (Landscape.FarFromTheOriginPaintsTheSamePicture).
TEST(Tree, GrowthNeverReadsTheOrigin) {
    TreeParams p = test::preset("pine");
    Tree ref = generate_tree(p, 4);
    TreeOptions o;
    o.origin = {1e5, 0, -1e5};
    Tree far = generate_tree(p, 4, o);
    EXPECT_EQ(far.origin, o.origin);
    EXPECT_EQ(test::hash_tree(far), test::hash_tree(ref));
}

TEST(Tree, InvalidParametersAreRejectedWithEveryProblem) {
    TreeParams p;
    p.trunk.taper.base = 1.7;
    p.leaves.probability.base = -0.1;
    try {
        generate_tree(p, 1);
        FAIL() << "expected InvalidParams";
    } catch (const InvalidParams& e) {
        ASSERT_EQ(e.problems.size(), 2u);
        EXPECT_EQ(e.problems[0], "/trunk/taper/base: must be in [0, 1], got 1.7");
        EXPECT_EQ(e.problems[1], "/leaves/probability/base: must be in [0, 1], got -0.1");
    }
}

}  // namespace
}  // namespace pleinair
