// bench trees' measures: on masks whose form is known by construction, on hand-made leaves and
// limbs, and on a shipped family painted from the side.
#include "pipeline/bench/tree_form.h"

#include <gtest/gtest.h>

#include <cmath>

#include "pipeline/input/presets.h"
#include "pipeline/output/contact_sheet.h"
#include "pipeline/shot/family.h"
#include "test_util.h"

namespace pleinair {
namespace {

// A 400x400 side view: a trunk 8 px wide from row `trunk_top` to the bottom row, and leaves
// where `leaf(x, y)` holds.
template <class F>
SideMasks masks(int trunk_top, F leaf) {
    SideMasks m;
    m.width = m.height = 400;
    m.leaf.assign(400 * 400, 0);
    m.bark.assign(400 * 400, 0);
    for (int y = 0; y < 400; ++y)
        for (int x = 0; x < 400; ++x) {
            const size_t i = static_cast<size_t>(y) * 400 + x;
            m.leaf[i] = leaf(x, y);
            m.bark[i] = y >= trunk_top && std::abs(x - 200) < 4;
        }
    return m;
}

bool in_disc(int x, int y, double cx, double cy, double r) {
    return std::hypot(x - cx, y - cy) <= r;
}

TEST(TreeForm, OneDiscOnATrunk) {
    // A disc of radius 100 centred at row 150 on a trunk from row 150 to 399: a crown 200 px
    // wide, its lowest leaves at row 250 of a tree 350 rows tall (rows 50-399).
    const SideMasks m = masks(150, [](int x, int y) { return in_disc(x, y, 200, 150, 100); });
    const TreeForm f = measure_form(m, Tree{});
    EXPECT_NEAR(f.crown_ratio, 200.0 / 350.0, 0.02);
    EXPECT_NEAR(f.clear_trunk, 150.0 / 350.0, 0.02);
    EXPECT_EQ(f.clumps, 1);
    EXPECT_NEAR(f.holes, 0.0, 0.01);  // the trunk inside the crown is no sky
    EXPECT_EQ(f.droop, 0.0);          // a tree with no leaves' limbs droops nowhere
}

// The hem is where the crown's sides end: a round crown's sides end high on its trunk, a
// curtain hanging from them ends near the ground.
TEST(TreeForm, TheHemIsWhereTheSidesEnd) {
    // The disc of OneDiscOnATrunk: its sides are its outer 40 columns each way, whose lowest
    // leaves are at row 230 (where x = 140 meets the circle), 169 rows above the trunk's foot
    // in a tree 350 rows tall (0.48); cutting the sides' lowest 2% of pixels (some 90, where
    // the circle's arc is thin) raises that by about ten rows.
    const SideMasks disc = masks(150, [](int x, int y) { return in_disc(x, y, 200, 150, 100); });
    const double round = measure_form(disc, Tree{}).hem;
    EXPECT_GT(round, 169.0 / 350.0);
    EXPECT_LT(round, 184.0 / 350.0);
    // Strips 10 px wide hang from its sides to row 380: the hem falls to about 19 rows above
    // the foot, raised by the cut (2% of the sides' 5,700 pixels: 11 rows of the strips).
    const SideMasks curtain = masks(150, [](int x, int y) {
        return in_disc(x, y, 200, 150, 100) ||
               (y <= 380 && y >= 150 && ((x >= 100 && x < 110) || (x > 290 && x <= 300)));
    });
    EXPECT_NEAR(measure_form(curtain, Tree{}).hem, 30.0 / 350.0, 0.02);
}

TEST(TreeForm, SeparateMassesAreClumpsAndEnclosedSkyIsHoles) {
    // Two discs of radius 60, 40 px apart, on one trunk: two clumps, no enclosed sky.
    const SideMasks two = masks(150, [](int x, int y) {
        return in_disc(x, y, 120, 150, 60) || in_disc(x, y, 280, 150, 60);
    });
    const TreeForm t = measure_form(two, Tree{});
    EXPECT_EQ(t.clumps, 2);
    EXPECT_NEAR(t.crown_ratio, 280.0 / 310.0, 0.02);  // rows 90-399
    EXPECT_NEAR(t.holes, 0.0, 0.01);
    // A ring from radius 50 to 120 around the trunk's top: one clump, and the inner disc (less
    // the trunk in it) is sky inside the outline, the outline the ring's outer disc.
    const SideMasks ring = masks(200, [](int x, int y) {
        const double r = std::hypot(x - 200.0, y - 180.0);
        return r >= 50 && r <= 120;
    });
    const TreeForm r = measure_form(ring, Tree{});
    EXPECT_EQ(r.clumps, 1);
    const double sky = M_PI * 50 * 50 - 8 * 30;  // the trunk rises 30 rows into the hole
    EXPECT_NEAR(r.holes, sky / (M_PI * 120 * 120), 0.01);
    // Two discs of radius 70, 6 px apart: the closing (kClumpRadius) bridges them with a
    // waist some 29 px tall, narrower than the 47 px square that wears kNeckRadius off a crown
    // 287 px wide, so two masses. Drawn 60 px apart they share a waist 126 px tall: one mass.
    const SideMasks lobes = masks(150, [](int x, int y) {
        return in_disc(x, y, 127, 150, 70) || in_disc(x, y, 273, 150, 70);
    });
    EXPECT_EQ(measure_form(lobes, Tree{}).clumps, 2);
    const SideMasks fused = masks(150, [](int x, int y) {
        return in_disc(x, y, 170, 150, 70) || in_disc(x, y, 230, 150, 70);
    });
    EXPECT_EQ(measure_form(fused, Tree{}).clumps, 1);
    // A bud of radius 45, 6 px off a crown's side: a core of its own, but of a couple of
    // hundred pixels against the crown's some 13,000, under kMassShare, so not a mass.
    const SideMasks bud = masks(150, [](int x, int y) {
        return in_disc(x, y, 200, 150, 100) || in_disc(x, y, 351, 150, 45);
    });
    EXPECT_EQ(measure_form(bud, Tree{}).clumps, 1);
    // A strand 12 px wide, thinner everywhere than the waist: worn away whole, still one mass.
    const SideMasks strand =
        masks(150, [](int x, int y) { return y >= 40 && y < 300 && std::abs(x - 230) < 6; });
    EXPECT_EQ(measure_form(strand, Tree{}).clumps, 1);
    // Many 6 px specks a few pixels apart are one mass, not hundreds.
    const SideMasks specks = masks(
        150, [](int x, int y) { return in_disc(x, y, 200, 150, 100) && x % 9 < 6 && y % 9 < 6; });
    EXPECT_EQ(measure_form(specks, Tree{}).clumps, 1);
}

TEST(TreeForm, DroopCountsLeavesBelowTheirLimbsBase) {
    Tree t;
    t.branches.resize(2);
    t.branches[0].start = glm::vec3(0, 0, 0);
    t.branches[1].start = glm::vec3(0, 5, 0);
    t.leaves.position = {{0, 6, 0}, {1, 4, 0}, {2, 3, 0}, {0, 1, 0}};
    t.leaves.limb = {1, 1, 1, 0};  // two of the first limb's three hang below its base at 5
    const SideMasks m = masks(150, [](int x, int y) { return in_disc(x, y, 200, 150, 100); });
    EXPECT_DOUBLE_EQ(measure_form(m, t).droop, 0.5);
    // No leaf or no trunk in view: nothing to measure.
    const SideMasks bare = masks(150, [](int, int) { return false; });
    EXPECT_EQ(measure_form(bare, t).crown_ratio, 0.0);
}

// A shipped family from the side: a poplar three times taller than its crown is wide, a stone
// pine's crown nearly as wide as the tree is tall on a trunk clear for much of its height; the
// masks are the same bytes painted twice.
TEST(TreeForm, ShippedFamiliesFromTheSide) {
    auto form = [](const std::string& preset, SideMasks* keep = nullptr) {
        const auto file = resolve_tree_preset(preset);
        const TreeParams params = load_tree_preset(file, {});
        SceneDesc scene;
        scene.families = {sheet_family(preset, preset, params)};
        scene.has_atmosphere = false;
        const Tree t = generate_family(params, 1, 1).front();
        BuiltTree b;
        b.tree() = t;
        b.position = t.origin;
        b.bark() = family_bark(scene.families[0], t, scene.build.bark_coverage, t.seed);
        const SideMasks m = side_masks(scene, b, 240, 270);
        if (keep) {
            const SideMasks again = side_masks(scene, b, 240, 270);
            EXPECT_EQ(m.leaf, again.leaf);
            EXPECT_EQ(m.bark, again.bark);
            *keep = m;
        }
        return measure_form(m, t);
    };
    SideMasks m;
    const TreeForm poplar = form("poplar", &m);
    size_t leaf = 0, bark = 0;
    for (size_t i = 0; i < m.leaf.size(); ++i) leaf += m.leaf[i], bark += m.bark[i];
    EXPECT_GT(leaf, 2000u);
    EXPECT_GT(bark, 100u);
    EXPECT_LT(poplar.crown_ratio, 1.0 / 3.0);  // three times as tall as wide
    const TreeForm pine = form("pine");
    EXPECT_GT(pine.crown_ratio, 0.6);
    EXPECT_GT(pine.clear_trunk, 0.35);
    EXPECT_GT(pine.clear_trunk, 2 * poplar.clear_trunk);
}

}  // namespace
}  // namespace pleinair
