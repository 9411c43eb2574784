// Forests by instancing (issue 26 §2): a family's trees drawn from a few grown members share
// their geometry and particles, and paint as the same trees grown one by one would; storage
// grows with the members, not the trees.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <set>
#include <string>

#include "pipeline/frame/paint_frame.h"
#include "pipeline/input/scene.h"
#include "pipeline/output/image_io.h"
#include "pipeline/shot/shot.h"

namespace pleinair {
namespace {

// A row of `n` oaks, seeds 1..n, each turned and scaled its own way, seen from the side; the
// family grows `members` (0: each tree its own).
std::string row_scene(int n, int members, const std::vector<uint64_t>& seeds = {},
                      glm::dvec3 offset = glm::dvec3(0.0)) {
    auto num = [](double v) {
        char b[64];
        std::snprintf(b, sizeof b, "%.17g", v);
        return std::string(b);
    };
    auto vec = [&](glm::dvec3 v) {
        v += offset;
        std::string out = "[";
        out += num(v.x);
        out += ", ";
        out += num(v.y);
        out += ", ";
        out += num(v.z);
        out += "]";
        return out;
    };
    std::string trees;
    for (int i = 0; i < n; ++i) {
        const uint64_t seed = seeds.empty() ? uint64_t(i + 1) : seeds[size_t(i)];
        trees += std::string(i ? ", " : "") + R"({"family": "oak", "seed": )" +
                 std::to_string(seed) + R"(, "position": )" +
                 vec({-12.0 + 24.0 * i / std::max(1, n - 1), 0, -6.0 * (i % 3)}) +
                 R"(, "rotation": )" + std::to_string(37 * i) + R"(, "scale": )" +
                 num(0.8 + 0.05 * (i % 5)) + "}";
    }
    return R"({"camera": {"position": )" + vec({0, 4, 28}) + R"(, "look_at": )" + vec({0, 4, 0}) +
           R"(, "fov": 50, "width": 160, "height": 90},
        "sun": {"direction": [-0.5, 0.7, 0.5], "casts_shadows": true},
        "families": {"oak": {"preset": "oak", "members": )" +
           std::to_string(members) + R"(}},
        "trees": [)" +
           trees + "]}";
}

TEST(Members, StorageGrowsWithMembersNotTrees) {
    for (const int members : {1, 3}) {
        const std::vector<BuiltTree> trees =
            build_trees(parse_scene(row_scene(24, members), "row.json"));
        std::set<const Tree*> grown;
        std::set<const BarkParticles*> bark;
        size_t leaves = 0;
        for (const BuiltTree& b : trees) {
            if (grown.insert(&b.tree()).second) leaves += b.tree().leaves.size();
            bark.insert(&b.bark());
        }
        EXPECT_LE(grown.size(), size_t(members));
        EXPECT_GE(grown.size(), 1u);
        EXPECT_EQ(bark.size(), grown.size());
        // The leaves held are the members', however many trees draw from them.
        EXPECT_LE(leaves, grown.size() * trees.front().tree().leaves.size() * 2);
        std::set<uint32_t> ids;
        for (const BuiltTree& b : trees) ids.insert(b.id);
        EXPECT_EQ(ids.size(), trees.size());  // each tree its own noise and tint
    }
    // Without members, every tree is grown: as many as trees.
    const std::vector<BuiltTree> each = build_trees(parse_scene(row_scene(24, 0), "row.json"));
    std::set<const Tree*> grown;
    for (const BuiltTree& b : each) grown.insert(&b.tree());
    EXPECT_EQ(grown.size(), each.size());
    // The shot's ray meshes too: one per member.
    const Shot shot = build_shot(parse_scene(row_scene(24, 3), "row.json"));
    ASSERT_TRUE(shot.limbs);
    EXPECT_LE(shot.limbs->size(), 3u);
    EXPECT_EQ(shot.limb_mesh.size(), 24u);
}

TEST(Members, InstancedTreesPaintAsTheSameTreesGrownOneByOne) {
    // The forest drawn from 2 members, and the same forest with each tree grown from the seed
    // of the tree that grew its member: the same picture, byte for byte.
    const SceneDesc instanced = parse_scene(row_scene(7, 2), "row.json");
    std::vector<uint64_t> seeds(7);
    std::map<uint32_t, uint64_t> member_seed;
    for (size_t i = 0; i < 7; ++i) {
        const uint32_t m = tree_member(instanced, i);
        member_seed.emplace(m, instanced.trees[i].seed);
        seeds[i] = member_seed[m];
    }
    ASSERT_EQ(member_seed.size(), 2u);  // both members drawn
    const SceneDesc grown = parse_scene(row_scene(7, 0, seeds), "row.json");
    const std::vector<uint8_t> a = frame_srgb8(paint_still(instanced));
    const std::vector<uint8_t> b = frame_srgb8(paint_still(grown));
    ASSERT_EQ(a.size(), b.size());
    EXPECT_TRUE(a == b);
    // And they are trees, not an empty picture: much of it differs from the bare sky.
    size_t dark = 0;
    for (size_t k = 0; k < a.size(); k += 3) dark += a[k + 1] < 120;
    EXPECT_GT(dark, a.size() / 3 / 20);
}

TEST(Members, AnInstanceFarFromTheOriginPaintsAsOneAtTheOriginMoved) {
    const std::vector<uint8_t> here = frame_srgb8(paint_still(parse_scene(row_scene(3, 1), "r")));
    const glm::dvec3 far(4.0e4, 0, -3.0e4);
    const std::vector<uint8_t> there =
        frame_srgb8(paint_still(parse_scene(row_scene(3, 1, {}, far), "r")));
    ASSERT_EQ(here.size(), there.size());
    // Within the golden gate: RMSE under 1 level of 8-bit sRGB.
    double sq = 0;
    for (size_t k = 0; k < here.size(); ++k) sq += std::pow(int(here[k]) - int(there[k]), 2);
    EXPECT_LT(std::sqrt(sq / double(here.size())), 1.0);
}

}  // namespace
}  // namespace pleinair
