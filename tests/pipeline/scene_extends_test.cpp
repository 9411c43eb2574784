// Scenes that extend others: the shipped shots are their stills plus a track, keys merge as a
// JSON merge patch, and a missing base, a cycle or a bad value is one clear error.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "pipeline/input/error.h"
#include "pipeline/frame/paint_frame.h"
#include "pipeline/input/presets.h"
#include "pipeline/input/scene.h"
#include "test_util.h"

namespace pleinair {
namespace {

namespace fs = std::filesystem;

SceneDesc shipped(const std::string& name) {
    return load_scene(resolve_preset("scenes", name, "SCENE"));
}

TEST(SceneExtends, ShippedShotsAreTheirStillsWithATrack) {
    const SceneDesc still = shipped("mortefontaine"), walk = shipped("mortefontaine-walk");
    EXPECT_TRUE(walk.animated());
    EXPECT_FALSE(still.animated());
    EXPECT_EQ(walk.camera_track.keys.size(), 4u);
    EXPECT_TRUE(walk.camera_track.constant_speed);
    EXPECT_EQ(walk.camera_params.width, still.camera_params.width);  // merged, not replaced
    EXPECT_EQ(walk.camera_params.fov, still.camera_params.fov);
    EXPECT_EQ(walk.trees.size(), still.trees.size());
    EXPECT_EQ(walk.terrain.params.resolution, still.terrain.params.resolution);
    EXPECT_EQ(walk.render.samples, still.render.samples);
    EXPECT_NE(walk.description, still.description);
    for (const char* shot : {"grove-orbit", "forest-edge-walk", "tree-dolly"})
        EXPECT_TRUE(shipped(shot).animated()) << shot;
}

// Every scene that ships loads (its presets, shaders and palettes with it), as a user's first
// `render NAME` does, and holds what a scene needs: something to paint, a camera, and for a
// shot more than one frame.
TEST(SceneExtends, EveryShippedSceneLoads) {
    int scenes = 0;
    for (const auto& entry : fs::directory_iterator(test::source_dir() / "presets" / "scenes")) {
        if (entry.path().extension() != ".json") continue;
        const std::string name = entry.path().stem().string();
        SCOPED_TRACE(name);
        SceneDesc s;
        ASSERT_NO_THROW(s = load_scene(entry.path()));
        EXPECT_FALSE(s.description.empty());
        EXPECT_TRUE(!s.trees.empty() || s.terrain.present);
        EXPECT_GT(s.camera.width, 0);
        if (s.animated()) {
            const FrameRange frames = animation_frames(s);
            EXPECT_GT(frames.last, frames.first);
        }
        ++scenes;
    }
    EXPECT_GE(scenes, 8);
}

class Extends : public ::testing::Test {
  protected:
    void SetUp() override { dir_ = test::temp_dir("extends"); }
    void TearDown() override { fs::remove_all(dir_); }
    fs::path write(const std::string& name, const std::string& text) {
        std::ofstream(dir_ / name) << text;
        return dir_ / name;
    }
    std::string error_of(const fs::path& file) {
        try {
            load_scene(file);
        } catch (const InputError& e) {
            return e.what();
        }
        return "";
    }
    fs::path dir_;
};

TEST_F(Extends, ObjectsMergeListsReplaceNullRemoves) {
    write("base.json", R"({"camera": {"position": [0, 2, 30], "fov": 30, "width": 64},
        "atmosphere": {"near": 5, "far": 50},
        "families": {"oak": {"preset": "oak"}, "birch": {"preset": "birch"}},
        "trees": [{"family": "oak", "seed": 1}, {"family": "birch", "seed": 2}]})");
    const fs::path child = write("child.json", R"({"extends": "base",
        "camera": {"fov": 50}, "atmosphere": null,
        "trees": [{"family": "birch", "seed": 9}]})");
    const SceneDesc s = load_scene(child);
    EXPECT_EQ(s.camera_params.fov, 50);
    EXPECT_EQ(s.camera_params.width, 64);
    EXPECT_EQ(s.camera_params.position, glm::dvec3(0, 2, 30));
    EXPECT_FALSE(s.has_atmosphere);
    ASSERT_EQ(s.trees.size(), 1u);
    EXPECT_EQ(s.trees[0].seed, 9u);
    EXPECT_EQ(s.families.size(), 2u);
    // --set applies to the merged scene.
    const SceneDesc set = load_scene(child, {"/camera/width=32"});
    EXPECT_EQ(set.camera_params.width, 32);
    EXPECT_EQ(set.camera_params.fov, 50);
    // A chain: grandchild -> child -> base.
    const SceneDesc g = load_scene(write("grand.json", R"({"extends": "child.json",
        "camera": {"height": 40}})"));
    EXPECT_EQ(g.camera_params.height, 40);
    EXPECT_EQ(g.camera_params.fov, 50);
}

TEST_F(Extends, BadBasesAreOneClearError) {
    EXPECT_NE(
        error_of(write("a.json", R"({"extends": "nowhere"})")).find("/extends: no scene file"),
        std::string::npos);
    EXPECT_NE(error_of(write("b.json", R"({"extends": 3})")).find("/extends: expected a scene"),
              std::string::npos);
    fs::create_directories(dir_ / "other");
    write("other/base.json", R"({"families": {}})");
    EXPECT_NE(error_of(write("s.json", R"({"extends": "other/base.json"})"))
                  .find("/extends: expected the name of a scene file in the same folder"),
              std::string::npos);
    write("c1.json", R"({"extends": "c2"})");
    EXPECT_NE(error_of(write("c2.json", R"({"extends": "c1"})")).find("a cycle"),
              std::string::npos);
    // A problem inside the base names the base file.
    write("broken.json", R"({"camera": {"fov": 10, "fov": 20}})");
    const std::string e = error_of(write("d.json", R"({"extends": "broken"})"));
    EXPECT_NE(e.find("broken.json"), std::string::npos) << e;
    EXPECT_NE(e.find("duplicate key"), std::string::npos) << e;
    // A bad value merged in is reported at its pointer.
    write("good.json", R"({"families": {"oak": {"preset": "oak"}}, "trees": []})");
    const std::string f = error_of(write("e.json", R"({"extends": "good", "fps": -1})"));
    EXPECT_NE(f.find("/fps"), std::string::npos) << f;
}

}  // namespace
}  // namespace pleinair
