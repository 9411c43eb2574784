// Forests by instancing (issue 26 §2): a family's trees drawn from a few grown members share
// their geometry and particles, and paint as the same trees grown one by one would; storage
// grows with the members, not the trees.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
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

// Every tree's leaf cards turned to the sun `dir` and placed in the world (leaf_casters), one
// caster set a family: what the shot's instanced casters are held to.
void add_world_cards(const Shot& shot, const glm::vec3& dir, RayScene& world) {
    std::vector<std::vector<StrokeCaster>> cards(shot.scene.families.size());
    for (const BuiltTree& tree : *shot.trees)
        for (const StrokeCaster& c : leaf_casters(shot.scene, tree, dir))
            cards[tree.family].push_back(c);
    for (size_t f = 0; f < cards.size(); ++f)
        world.add_casters(cards[f], shot.scene.families[f].leaf_shader,
                          shot.materials[shot.materials.leaf(uint32_t(f))].edge);
}

// The sun's leaf casters are each member's cards, placed by an instance per tree and turned to
// the sun as the ray sees them: they shade as the same cards built in the world, tree by tree.
TEST(Members, InstancedCastersShadeAsCardsPlacedInTheWorld) {
    for (const glm::vec3 sun : {glm::vec3(-0.5f, 0.7f, 0.5f), glm::vec3(0.1f, 0.95f, -0.3f)}) {
        const Shot shot = build_shot(parse_scene(row_scene(5, 2), "row.json"));
        ASSERT_TRUE(shot.limbs);
        ASSERT_GE(shot.limbs->caster_sets(), 1u);
        const glm::vec3 dir = glm::normalize(sun);
        const std::vector<BuiltTree>& trees = *shot.trees;
        RayScene instanced(shot.anchor, shot.limbs.get()), world(shot.anchor);
        for (size_t i = 0; i < trees.size(); ++i)
            instanced.add_caster_instance(shot.limb_mesh[i], shot.placements[i].linear(),
                                          shot.placements[i].position);
        add_world_cards(shot, dir, world);
        instanced.commit();
        world.commit();
        EXPECT_EQ(instanced.caster_count(), world.caster_count());
        EXPECT_EQ(instanced.caster_cards_stored(), 0u);
        // From every third leaf, and from the ground under it, towards the sun.
        double sum = 0, worst = 0, shade = 0, far_diff = 0, far_sum = 0;
        size_t n = 0;
        for (size_t i = 0; i < trees.size(); ++i) {
            const LeafParticles& L = trees[i].tree().leaves;
            for (size_t j = 0; j < L.size(); j += 3) {
                for (const bool ground : {false, true}) {
                    glm::dvec3 o = shot.placements[i].place(L.position[j]);
                    if (ground) o.y = 0.0;
                    const float a = instanced.transmittance(o, dir, ShadowMode::kTransmissive);
                    const float b = world.transmittance(o, dir, ShadowMode::kTransmissive);
                    sum += std::abs(a - b), worst = std::max(worst, double(std::abs(a - b)));
                    shade += 1.0 - b, ++n;
                    // A mirror's ray finds the leaves at the same distance either way.
                    float da = 0, db = 0;
                    const float inf = std::numeric_limits<float>::infinity();
                    const float ta = instanced.transmittance_depth(o, dir, inf, nullptr, da);
                    const float tb = world.transmittance_depth(o, dir, inf, nullptr, db);
                    far_diff += std::abs(ta - tb) + std::abs(da - db), far_sum += db;
                }
            }
        }
        EXPECT_GT(shade / double(n), 0.5);  // the crowns do shade (0.86 and 0.93)
        // The same light but for float rounding (measured: mean 7e-7, worst 1e-4).
        EXPECT_LT(sum / double(n), 1e-5);
        EXPECT_LT(worst, 2e-3);
        EXPECT_GT(far_sum / double(n), 0.3) << "the rays meet leaves some way off";
        EXPECT_LT(far_diff / double(n), 1e-3) << far_sum / double(n);
    }
}

// The shot's own sun scene (build_sun_scene, as render and animate build it) shades like the
// same cards and limbs built in the world, tree by tree: every tree of the row is turned its
// own way, so a caster instance placed without its tree's turn leaves the shade elsewhere.
TEST(Members, TheShotsSunSceneTurnsEachTreesCardsWithIt) {
    const Shot shot = build_shot(parse_scene(row_scene(5, 2), "row.json"));
    ASSERT_TRUE(shot.sun_rays) << "a still sun: the shot builds its sun scene once";
    const glm::vec3 dir = glm::normalize(glm::vec3(shot.scene.sun_direction));
    const std::vector<BuiltTree>& trees = *shot.trees;
    RayScene world(shot.anchor, shot.limbs.get());
    if (shot.land->has_terrain) world.add_mesh(shot.land->terrain_mesh);
    for (const auto& r : shot.land->rocks) world.add_mesh(r);
    for (size_t i = 0; i < trees.size(); ++i)
        world.add_instance(shot.limb_mesh[i], shot.placements[i].linear(),
                           shot.placements[i].position);
    add_world_cards(shot, dir, world);
    world.commit();
    EXPECT_EQ(shot.sun_rays->caster_count(), world.caster_count());
    double sum = 0, shade = 0;
    size_t n = 0;
    for (size_t i = 0; i < trees.size(); ++i) {
        const LeafParticles& L = trees[i].tree().leaves;
        for (size_t j = 0; j < L.size(); j += 7)
            for (const bool ground : {false, true}) {
                glm::dvec3 o = shot.placements[i].place(L.position[j]);
                if (ground) o.y = 0.0;
                const float a = shot.sun_rays->transmittance(o, dir, ShadowMode::kTransmissive);
                const float b = world.transmittance(o, dir, ShadowMode::kTransmissive);
                sum += std::abs(a - b), shade += 1.0 - b, ++n;
            }
    }
    ASSERT_GT(n, 100u);
    EXPECT_GT(shade / double(n), 0.5);  // the crowns do shade
    // The same light but for float rounding (as the instancing test above: mean 7e-7).
    EXPECT_LT(sum / double(n), 1e-5);
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
