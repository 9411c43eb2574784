// The pleinair binary as a user runs it: outputs, exit codes and one-line errors.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "test_util.h"

namespace pleinair {
namespace {

namespace fs = std::filesystem;
using test::run_pleinair;

size_t line_count(const std::string& s) { return std::count(s.begin(), s.end(), '\n'); }

TEST(Cli, TreeWritesMeshesAndParticlesDeterministically) {
    auto dir = test::temp_dir("cli-tree");
    auto a = run_pleinair("tree --preset oak --seed 3 -o " + (dir / "a").string());
    ASSERT_EQ(a.exit_code, 0) << a.err;
    EXPECT_EQ(a.err, "");
    auto b = run_pleinair("tree --preset oak --seed 3 --threads 1 --out " + (dir / "b").string());
    ASSERT_EQ(b.exit_code, 0) << b.err;
    for (const char* f : {"control.obj", "control.ply", "render.obj", "render.ply", "lod.obj",
                          "lod.ply", "leaves.ply", "tree.json"}) {
        std::string bytes = test::read_file(dir / "a" / f);
        EXPECT_GT(bytes.size(), 100u) << f;
        EXPECT_EQ(bytes, test::read_file(dir / "b" / f)) << f;
    }
    auto meta = nlohmann::json::parse(test::read_file(dir / "a" / "tree.json"));
    EXPECT_EQ(meta["seed"], 3);
    EXPECT_EQ(meta["branches"][0]["id"], 0);
    EXPECT_EQ(meta["branches"][0]["parent"], -1);
    fs::remove_all(dir);
}

TEST(Cli, StatsIsOneJsonLine) {
    auto r = run_pleinair("tree --preset poplar --seed 2 --stats --repeat 3");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(line_count(r.out), 1u);
    auto j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j["preset"], "poplar");
    EXPECT_GT(j["render"]["vertices"].get<int>(), j["control"]["vertices"].get<int>());
    EXPECT_GT(j["leaves"].get<int>(), 0);
    EXPECT_EQ(j["time_ms"]["repeat"], 3);
    EXPECT_TRUE(j["time_ms"]["median"].is_number());  // a time: its value is not asserted
    EXPECT_LT(j["bbox"]["min"][1].get<double>(), j["bbox"]["max"][1].get<double>());
    // The counts are the tree's own: those of the files the same preset and seed write.
    auto dir = test::temp_dir("cli-stats");
    ASSERT_EQ(run_pleinair("tree --preset poplar --seed 2 -o " + (dir / "t").string()).exit_code,
              0);
    const std::string ply = test::read_file(dir / "t" / "leaves.ply");
    const std::string count = "element vertex " + std::to_string(j["leaves"].get<int>()) + "\n";
    EXPECT_NE(ply.find(count), std::string::npos) << count;
    fs::remove_all(dir);
}

TEST(Cli, BadPresetIsOneLineExitTwoAndNothingWritten) {
    auto dir = test::temp_dir("cli-bad");
    fs::path bad = dir / "bad.json";
    { std::ofstream(bad) << "{ \"trunk\": { \"taper\": { \"base\": 1.7, \"var\": 0.02 } } }"; }
    auto r = run_pleinair("tree --preset " + bad.string() + " -o " + (dir / "out").string());
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_EQ(r.err, bad.string() + ": /trunk/taper/base: must be in [0, 1], got 1.7\n");
    EXPECT_FALSE(fs::exists(dir / "out"));
    fs::remove_all(dir);
}

TEST(Cli, MissingAndUnknownPresetsExitTwo) {
    auto r = run_pleinair("tree --preset /nonexistent/x.json -o /tmp/never");
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_EQ(line_count(r.err), 1u);
    EXPECT_NE(r.err.find("/nonexistent/x.json"), std::string::npos) << r.err;
    r = run_pleinair("tree --preset oka --stats");
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find("available: birch"), std::string::npos) << r.err;
}

TEST(Cli, UsageErrorsExitTwo) {
    EXPECT_EQ(run_pleinair("family --preset oak --count 0 -o /tmp/never").exit_code, 2);
    EXPECT_EQ(run_pleinair("tree --seed 3").exit_code, 2);
    EXPECT_EQ(run_pleinair("tree --preset oak --set /trunk/taper=x").exit_code, 2);
    EXPECT_EQ(run_pleinair("frobnicate").exit_code, 2);
    auto help = run_pleinair("tree --help");
    EXPECT_EQ(help.exit_code, 0);
    EXPECT_NE(help.out.find("--preset"), std::string::npos);
}

// Numbers on the command line are checked as the files' are: a seed or an id is a whole
// number in its type's range (CLI11 alone wrapped -1 and clamped 2^64 to the largest seed),
// a position or a time is finite (NaN went into every OBJ, PLY and tree.json).
TEST(Cli, CommandLineNumbersAreCheckedAndNothingIsWritten) {
    auto dir = test::temp_dir("cli-numbers");
    const std::string out = " -o " + (dir / "out").string();
    const std::pair<const char*, const char*> cases[] = {
        {"tree --preset oak --seed -1",
         "pleinair: --seed: expected a whole number from 0 to 18446744073709551615, got -1"},
        {"tree --preset oak --seed 18446744073709551616",
         "pleinair: --seed: expected a whole number from 0 to 18446744073709551615, got "
         "18446744073709551616"},
        {"family --preset oak --seed 1e3",
         "pleinair: --seed: expected a whole number from 0 to 18446744073709551615, got 1e3"},
        {"tree --preset oak --id 4294967296",
         "pleinair: --id: expected a whole number from 0 to 4294967295, got 4294967296"},
        {"tree --preset oak --position nan,0,0",
         "pleinair: --position: expected a finite number within +-100000 (the world pleinair "
         "supports), got nan"},
        {"tree --preset oak --position 0,0,-inf",
         "pleinair: --position: expected a finite number within +-100000 (the world pleinair "
         "supports), got -inf"},
        {"tree --preset oak --position 1e7,0,1e7",
         "pleinair: --position: expected a finite number within +-100000 (the world pleinair "
         "supports), got 1e7"},
        {"render grove --time inf", "pleinair: --time: expected a finite number, got inf"},
    };
    for (const auto& [args, message] : cases) {
        auto r = run_pleinair(std::string(args) + out);
        EXPECT_EQ(r.exit_code, 2) << args;
        EXPECT_EQ(r.err, std::string(message) + " (see --help)\n") << args;
        EXPECT_FALSE(fs::exists(dir / "out")) << args;
    }
    // The largest seed is a seed.
    auto r = run_pleinair("tree --preset shrub --seed 18446744073709551615" + out);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    fs::remove_all(dir);
}

// An output that names an image where a folder is written (or a format pleinair does not
// write) is refused before anything exists; --save-preset creates its folder as -o does.
TEST(Cli, OutputsAreWhatTheirNamesSay) {
    auto dir = test::temp_dir("cli-outputs");
    auto r = run_pleinair("family --preset oak --count 2 -o " + (dir / "s.jpg").string());
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_EQ(r.err, "-o: \"" + (dir / "s.jpg").string() +
                         "\": a contact sheet is written as .png, .tif, .tiff or .exr; a folder "
                         "of members needs a name without an image extension\n");
    EXPECT_FALSE(fs::exists(dir / "s.jpg"));
    r = run_pleinair("tree --preset oak -o " + (dir / "t.png").string());
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_FALSE(fs::exists(dir / "t.png"));
    const fs::path saved = dir / "new" / "folder" / "shrub.json";
    r = run_pleinair("tree --preset shrub --save-preset " + saved.string());
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_TRUE(fs::is_regular_file(saved));
    fs::remove_all(dir);
}

TEST(Cli, PresetsListsEveryShippedFamily) {
    auto r = run_pleinair("presets");
    ASSERT_EQ(r.exit_code, 0);
    size_t tree_lines = 0;
    for (size_t at = 0; (at = r.out.find("tree ", at)) != std::string::npos; ++at)
        tree_lines += at == 0 || r.out[at - 1] == '\n';
    EXPECT_EQ(tree_lines, test::shipped_tree_presets().size());
    for (const auto& name : test::shipped_tree_presets())
        EXPECT_NE(r.out.find(" " + name + " "), std::string::npos) << name;
    for (const char* shipped :
         {"shader   corot-leaves", "palette  corot-foliage", "scene    grove"})
        EXPECT_NE(r.out.find(shipped), std::string::npos) << shipped;
}

TEST(Cli, SavedPresetReproducesTheTweakedTree) {
    auto dir = test::temp_dir("cli-save");
    std::string saved = (dir / "tweaked.json").string();
    auto a = run_pleinair(
        "tree --preset willow --set /leaves/branching_steps=4 --seed 8 "
        "--save-preset " +
        saved + " -o " + (dir / "a").string());
    ASSERT_EQ(a.exit_code, 0) << a.err;
    auto b = run_pleinair("tree --preset " + saved + " --seed 8 -o " + (dir / "b").string());
    ASSERT_EQ(b.exit_code, 0) << b.err;
    EXPECT_EQ(test::read_file(dir / "a" / "leaves.ply"), test::read_file(dir / "b" / "leaves.ply"));
    EXPECT_EQ(test::read_file(dir / "a" / "render.ply"), test::read_file(dir / "b" / "render.ply"));
    fs::remove_all(dir);
}

TEST(Cli, FamilyWritesEveryMemberTheSameOnOneOrTwoThreads) {
    auto dir = test::temp_dir("cli-family");
    auto a = run_pleinair("family --preset shrub --count 3 --seed 4 --threads 1 -o " +
                          (dir / "a").string());
    ASSERT_EQ(a.exit_code, 0) << a.err;
    auto b = run_pleinair("family --preset shrub --count 3 --seed 4 --threads 2 -o " +
                          (dir / "b").string());
    ASSERT_EQ(b.exit_code, 0) << b.err;
    auto index = nlohmann::json::parse(test::read_file(dir / "a" / "family.json"));
    ASSERT_EQ(index["members"].size(), 3u);
    for (const auto& m : index["members"]) {
        std::string sub = m["dir"];
        EXPECT_EQ(test::read_file(dir / "a" / sub / "leaves.ply"),
                  test::read_file(dir / "b" / sub / "leaves.ply"));
        EXPECT_TRUE(fs::exists(dir / "a" / sub / "render.obj"));
    }
    fs::remove_all(dir);
}

}  // namespace
}  // namespace pleinair
