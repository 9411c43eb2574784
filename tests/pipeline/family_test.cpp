// Families: keyed member seeds, identical bytes on any number of threads, and the species' bark.
#include "pipeline/shot/family.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <filesystem>
#include <fstream>
#include <set>

#include "pipeline/input/error.h"
#include "pipeline/input/presets.h"
#include "pipeline/input/scene.h"
#include "pipeline/input/shader_io.h"
#include "pipeline/output/contact_sheet.h"
#include "test_util.h"

namespace pleinair {
namespace {

TEST(Family, MemberSeedsAreDistinctAndIndependentOfFamilySize) {
    std::set<uint64_t> seeds;
    for (uint32_t i = 0; i < 1000; ++i) seeds.insert(member_seed(5, i));
    EXPECT_EQ(seeds.size(), 1000u);
    EXPECT_NE(member_seed(5, 0), member_seed(6, 0));
    TreeParams p = test::preset("shrub");
    auto three = generate_family(p, 5, 3), five = generate_family(p, 5, 5);
    for (size_t i = 0; i < 3; ++i) EXPECT_EQ(test::hash_tree(three[i]), test::hash_tree(five[i]));
    EXPECT_EQ(five[4].id, 4u);
    EXPECT_EQ(five[4].leaves.tree_id.front(), 4u);
}

TEST(Family, OneAndTwoThreadsGiveTheSameBytes) {
    TreeParams p = test::preset("oak");
    std::vector<uint64_t> hashes[2];
    for (int threads : {1, 2}) {
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
        for (const Tree& t : generate_family(p, 9, 6))
            hashes[threads - 1].push_back(test::hash_tree(t));
    }
    EXPECT_EQ(hashes[0], hashes[1]);
}

// A tree preset's bark_palette paints the species' bark where a scene names no palette (the
// birch's white bark), in a scene and on `family`'s contact sheet alike; a scene's own
// bark_palette wins; a preset without one keeps the shader's; a palette that names nothing is
// told as the preset file's key, in a scene under the family's preset key.
TEST(Family, TheSpeciesBarkIsTheDefaultAndASceneMayPaintItOtherwise) {
    const SceneDesc s = parse_scene(R"({"families": {
        "birch": {"preset": "birch"},
        "dark-birch": {"preset": "birch", "bark_palette": "corot-bark"},
        "oak": {"preset": "oak"}}})",
                                    "bark.json");
    ASSERT_EQ(s.families.size(), 3u);
    const Family &birch = s.families[0], &dark_birch = s.families[1], &oak = s.families[2];
    EXPECT_EQ(birch.params.bark_palette, "birch-bark");
    EXPECT_EQ(birch.bark_palette, shader_palette(load_palette("birch-bark"), birch.bark_shader));
    EXPECT_EQ(dark_birch.bark_palette,
              shader_palette(load_palette("corot-bark"), dark_birch.bark_shader));
    EXPECT_FALSE(birch.bark_palette == dark_birch.bark_palette);
    EXPECT_EQ(oak.params.bark_palette, "");
    EXPECT_EQ(oak.bark_palette, dark_birch.bark_palette);  // corot-bark: the shader's
    EXPECT_EQ(sheet_family("birch", "birch", birch.params).bark_palette, birch.bark_palette);
    EXPECT_EQ(sheet_family("oak", "oak", oak.params).bark_palette, oak.bark_palette);

    const std::filesystem::path file = test::temp_dir("bark-palette") / "pale.json";
    std::ofstream(file) << R"({"name": "pale", "bark_palette": "no-such-palette"})";
    auto problem = [&](auto&& fn) {
        try {
            fn();
        } catch (const InputError& e) {
            return std::string(e.what());
        }
        return std::string();
    };
    const std::string in_scene = problem([&] {
        parse_scene(R"({"families": {"pale": {"preset": ")" + file.string() + R"("}}})",
                    "pale-scene.json");
    });
    const std::string on_sheet =
        problem([&] { sheet_family("pale", file.string(), load_tree_preset(file)); });
    for (const std::string& what : {in_scene, on_sheet}) {
        EXPECT_NE(what.find(file.string() + ": /bark_palette"), std::string::npos) << what;
        EXPECT_NE(what.find("no-such-palette"), std::string::npos) << what;
    }
    EXPECT_NE(in_scene.find("pale-scene.json: /families/pale/preset"), std::string::npos)
        << in_scene;
    std::filesystem::remove_all(file.parent_path());
}

}  // namespace
}  // namespace pleinair
