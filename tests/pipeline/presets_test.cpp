// Preset files: every shipped preset loads; bad ones give one line per problem naming the file
// and the key; saved presets load back to the same tree.
#include "pipeline/input/presets.h"

#include <gtest/gtest.h>

#include "generators/tree.h"
#include "pipeline/input/draft.h"
#include "pipeline/input/error.h"
#include "pipeline/input/graftal_io.h"
#include "pipeline/input/imposter_io.h"
#include "pipeline/input/json_params.h"
#include "pipeline/input/scene.h"
#include "pipeline/input/shader_io.h"
#include "test_util.h"

namespace pleinair {
namespace {

std::vector<std::string> problems_of(const std::string& text, std::vector<std::string> set = {}) {
    try {
        parse_tree_params(text, "presets/trees/oak.json", set);
    } catch (const InputError& e) {
        std::vector<std::string> lines;
        std::string all = e.what();
        size_t start = 0;
        while (start <= all.size()) {
            size_t end = all.find('\n', start);
            if (end == std::string::npos) end = all.size();
            lines.push_back(all.substr(start, end - start));
            start = end + 1;
        }
        return lines;
    }
    return {};
}

// The problems of a scene as one string ("" when it parses), its source "s.json".
std::string scene_problem(const std::string& text) {
    try {
        parse_scene(text, "s.json");
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

TEST(Presets, AtLeastSixShipWithDescriptions) {
    auto presets = list_tree_presets();
    ASSERT_GE(presets.size(), 6u);
    for (const auto& p : presets) {
        EXPECT_FALSE(p.description.empty()) << p.name;
        EXPECT_EQ(load_tree_preset(p.file).name, p.name) << "name key matches the file name";
    }
}

TEST(Presets, OutOfRangeNamesFileKeyRangeAndValue) {
    EXPECT_EQ(problems_of(R"({"trunk": {"taper": {"base": 1.7, "var": 0.02}}})"),
              std::vector<std::string>{
                  "presets/trees/oak.json: /trunk/taper/base: must be in [0, 1], got 1.7"});
    // A plain number is named as written.
    EXPECT_EQ(problems_of(R"({"trunk": {"taper": 1.7}})"),
              std::vector<std::string>{
                  "presets/trees/oak.json: /trunk/taper: must be in [0, 1], got 1.7"});
    EXPECT_EQ(problems_of(R"({"trunk": {"taper": {"base": 0.9, "var": -1}}})"),
              std::vector<std::string>{
                  "presets/trees/oak.json: /trunk/taper/var: must be in [0, 1], got -1"});
}

TEST(Presets, UnknownKeysAreErrorsWithASuggestion) {
    EXPECT_EQ(problems_of(R"({"trunk": {"tapr": 0.9}})"),
              std::vector<std::string>{
                  "presets/trees/oak.json: /trunk/tapr: unknown key (did you mean \"taper\"?)"});
    EXPECT_EQ(problems_of(R"({"colour": 1})"),
              std::vector<std::string>{"presets/trees/oak.json: /colour: unknown key"});
    EXPECT_EQ(problems_of(R"({"trunk": {"taper": {"base": 0.9, "varr": 0.1}}})").size(), 1u);
}

// A key given twice is a problem, not "the last one wins": in objects nested in objects and
// in lists alike, each pointer to the duplicate.
TEST(Presets, DuplicateKeysAreErrors) {
    EXPECT_EQ(
        problems_of(R"({"trunk": {"taper": 0.9, "twist": 3, "taper": 0.5}})"),
        std::vector<std::string>{
            "presets/trees/oak.json: /trunk/taper: duplicate key: given twice in one object"});
    EXPECT_EQ(problems_of(R"({"unit": 1, "unit": 1})"),
              std::vector<std::string>{
                  "presets/trees/oak.json: /unit: duplicate key: given twice in one object"});
    try {
        parse_scene(R"({"families": {"a": {"preset": "oak"}},
                        "trees": [{"family": "a"}, {"family": "a", "seed": 1, "seed": 2}]})",
                    "s.json");
        ADD_FAILURE() << "a duplicate seed went through";
    } catch (const InputError& e) {
        EXPECT_EQ(std::string(e.what()),
                  "s.json: /trees/1/seed: duplicate key: given twice in one object");
    }
}

// Hostile JSON: each class is one line naming the file and, where the parser knows it, the
// key. Nesting 100,000 deep used to overflow the stack while the message was built; a number
// past a double's range gave the JSON library's raw message and exit 1; a key holding "/" was
// reported as two keys and one holding a newline printed over two lines.
TEST(Presets, HostileJsonIsOneLineNamingWhere) {
    const std::string deep = std::string(100000, '[') + std::string(100000, ']');
    EXPECT_EQ(problems_of("{\"trunk\":\n" + deep + "}"),
              std::vector<std::string>{"presets/trees/oak.json: line 2: nested more than 64 "
                                       "levels deep (the limit for every input)"});
    // Brackets in strings and comments do not count; 64 levels pass the depth check.
    const std::string ok = std::string(63, '[') + std::string(63, ']');
    const auto shallow = problems_of("{\"x\": \"" + std::string(200, '[') + "\", // [[[[\n" +
                                     "\"trunk\": " + ok + "}");
    ASSERT_EQ(shallow.size(), 2u);
    EXPECT_EQ(shallow[0],
              "presets/trees/oak.json: /trunk: expected an object, got [[[[[[[[[[["
              "[[[[[[[[[[[[[[[[[[[[[[[[[[...");
    EXPECT_EQ(problems_of(R"({"trunk": {"taper": [1, 2, 1e400]}})"),
              std::vector<std::string>{"presets/trees/oak.json: /trunk/taper/2: number out of "
                                       "range: 1e400 (a double holds magnitudes up to about "
                                       "1.8e308)"});
    EXPECT_EQ(problems_of(R"({"trunk": {"a/b~c": 1}})"),
              std::vector<std::string>{"presets/trees/oak.json: /trunk/a~1b~0c: unknown key"});
    EXPECT_EQ(problems_of("{\"trunk\": {\"new\\nline\": 1}}"),
              std::vector<std::string>{"presets/trees/oak.json: /trunk/new\\nline: unknown key"});
    // --set: a value nested too deep, and an index that would allocate without bound.
    EXPECT_EQ(problems_of("{}", {"/trunk=" + deep}),
              std::vector<std::string>{"presets/trees/oak.json: /trunk: --set value line 1: "
                                       "nested more than 64 levels deep (the limit for every "
                                       "input)"});
    try {
        parse_scene(R"({"families": {"a": {"preset": "oak"}}, "trees": [{"family": "a"}]})",
                    "s.json", {"/trees/99999999999/seed=3", "/trees/1/seed=3", "/new/7=1"});
        ADD_FAILURE() << "an index past the end went through";
    } catch (const InputError& e) {
        EXPECT_EQ(std::string(e.what()),
                  "s.json: /trees/99999999999/seed: --set cannot place a value here: index "
                  "99999999999 is past the end of /trees, which has 1 element\n"
                  "s.json: /new/7: --set cannot place a value here: /new does not exist, so "
                  "only index 0 can start it\n"
                  // Just past the end appends: a tree with a seed and no family.
                  "s.json: /trees/1/family: no family \"\" in /families (have: a)");
    }
}

// Values that were accepted and then quietly ignored, or quietly did nothing, are refused with
// the key and what was expected.
TEST(Presets, ValuesThatWouldBeIgnoredAreRefused) {
    try {
        parse_shader_preset(
            R"({"palette": "corot-foliage", "distance": {"dist_value_min": 0.8, "dist_value_max": 0.2}})",
            "leaves.json");
        ADD_FAILURE() << "dist_value_min above dist_value_max went through";
    } catch (const InputError& e) {
        EXPECT_EQ(
            std::string(e.what()),
            "leaves.json: /distance/dist_value_max: must be >= dist_value_min (0.8), got 0.2");
    }
    EXPECT_EQ(
        problems_of(R"({"branches": {"tropism": {"direction": [0, 0, 0], "strength": 0.4}}})"),
        std::vector<std::string>{"presets/trees/oak.json: /branches/tropism/direction: must "
                                 "not be [0, 0, 0] while the strength is not 0"});
    EXPECT_TRUE(problems_of(R"({"branches": {"tropism": {"direction": [0, 0, 0], "strength": 0}}})")
                    .empty());
    const std::string land = R"("camera": {"position": [0, 3, 40], "look_at": [0, 2, 0]},
        "materials": {"grass": {"shader": "grass"}, "rock": {"shader": "rock"}},
        "terrain": {"seed": 1, "min": [-50, -50], "max": [50, 50], "material": "grass"},)";
    EXPECT_EQ(scene_problem("{" + land + R"("rocks": [{"position": [0, 0, 0], "scale": [1, 0, -1],
                                          "radius": 0, "material": "rock"}]})"),
              "s.json: /rocks/0/scale: expected three finite numbers > 0, got [1, 0, -1]\n"
              "s.json: /rocks/0/radius: must be > 0, got 0");
    EXPECT_EQ(scene_problem("{" + land + R"("families": {"oak": {"preset": "oak"}},
        "groups": [{"center": [0, 0], "radius": 10000, "min_distance": 1, "families": {"oak": 1}}]})"),
              "s.json: /groups/0/min_distance: too small for the radius: the Poisson-disk grid "
              "would have 800041225 cells (the limit is 4000000); raise min_distance or split "
              "the group");
    EXPECT_EQ(scene_problem("{" + land +
                            R"("families": {"oak": {"preset": "oak", "leaf_shader": "grass"}}})"),
              "s.json: /families/oak/leaf_shader: shader \"grass\" has a \"surface\" section, "
              "which only a material's strokes read; leaves and bark would ignore it");
}

// Coordinates beyond the supported world (scene.h) are refused with their key; they passed
// validation and then aborted inside Embree.
TEST(Presets, CoordinatesBeyondTheWorldAreRefused) {
    const std::string head = R"({"camera": {"position": [0, 3, 40], "look_at": [0, 2, 0]},
        "materials": {"grass": {"shader": "grass"}, "rock": {"shader": "rock"}},
        "families": {"oak": {"preset": "oak"}},)";
    EXPECT_EQ(scene_problem(head + R"("trees": [{"family": "oak", "position": [1e19, 0, 0]}]})"),
              "s.json: /trees/0/position: beyond the world pleinair supports: every coordinate "
              "within +-100000, got 1e+19");
    EXPECT_EQ(scene_problem(head + R"("rocks": [{"position": [99999, 0, 0], "radius": 2}]})"),
              "s.json: /rocks/0/position: beyond the world pleinair supports: every coordinate "
              "within +-100000, got 100001");
    EXPECT_EQ(scene_problem(head + R"("terrain": {"min": [-1e20, -50], "max": [50, 50]}})"),
              "s.json: /terrain/min: beyond the world pleinair supports: every coordinate "
              "within +-100000, got -1e+20");
    EXPECT_EQ(scene_problem(R"({"camera": {"position": [0, 3, 4e5], "look_at": [0, 2, 0]}})"),
              "s.json: /camera/position: beyond the world pleinair supports: every coordinate "
              "within +-100000, got 400000");
    // At the edge, a tree 1e5 away is a tree.
    EXPECT_EQ(scene_problem(head + R"("trees": [{"family": "oak", "position": [1e5, 0, -1e5]}]})"),
              "");
}

TEST(Presets, WrongTypesSayWhatWasExpected) {
    EXPECT_EQ(problems_of(R"({"trunk": {"max_steps": "ten"}})"),
              std::vector<std::string>{"presets/trees/oak.json: /trunk/max_steps: expected a "
                                       "number or {\"base\": b, \"var\": v}, got \"ten\""});
    EXPECT_EQ(problems_of(R"({"trunk": {"max_steps": 2.5}})"),
              std::vector<std::string>{
                  "presets/trees/oak.json: /trunk/max_steps: must be a whole number, got 2.5"});
    EXPECT_EQ(problems_of(R"({"subdivision_levels": 1.5})"),
              std::vector<std::string>{
                  "presets/trees/oak.json: /subdivision_levels: expected an integer, got 1.5"});
    EXPECT_EQ(
        problems_of(R"({"trunk": 3})"),
        std::vector<std::string>{"presets/trees/oak.json: /trunk: expected an object, got 3"});
    EXPECT_EQ(problems_of(R"({"center_offset": [1, 2]})"),
              std::vector<std::string>{"presets/trees/oak.json: /center_offset: expected three "
                                       "numbers [x, y, z], got [1,2]"});
    EXPECT_EQ(problems_of(R"({"trunk": {"max_steps": 100000}})"),
              std::vector<std::string>{
                  "presets/trees/oak.json: /trunk/max_steps: must be in [0, 256], got 100000"});
}

TEST(Presets, EveryProblemGetsItsOwnLine) {
    auto lines = problems_of(R"({"unit": 0, "leaves": {"probability": 2}, "lod": {"x": 1}})");
    ASSERT_EQ(lines.size(), 3u);
    EXPECT_EQ(lines[0], "presets/trees/oak.json: /lod/x: unknown key");
    EXPECT_EQ(lines[1], "presets/trees/oak.json: /unit: must be in [1e-06, 1e+06], got 0");
    EXPECT_EQ(lines[2], "presets/trees/oak.json: /leaves/probability: must be in [0, 1], got 2");
    // A value breaking two rules of its key (out of range, not whole; above its partner) is one
    // line, the first rule's; two keys are two lines.
    EXPECT_EQ(problems_of(R"({"leaves": {"branching_steps": 0.5}})"),
              std::vector<std::string>{
                  "presets/trees/oak.json: /leaves/branching_steps: must be in [1, 64], got 0.5"});
    EXPECT_EQ(problems_of(R"({"branches": {"min_height": 2}, "trunk": {"taper": -1}})"),
              (std::vector<std::string>{
                  "presets/trees/oak.json: /trunk/taper: must be in [0, 1], got -1",
                  "presets/trees/oak.json: /branches/min_height: must be in [0, 1], got 2"}));
}

TEST(Presets, SyntaxErrorsGiveTheLine) {
    auto lines = problems_of("{\n  \"unit\": 1,\n  \"trunk\": {,}\n}");
    ASSERT_EQ(lines.size(), 1u);
    EXPECT_NE(lines[0].find("presets/trees/oak.json: "), std::string::npos);
    EXPECT_NE(lines[0].find("line 3"), std::string::npos) << lines[0];
}

TEST(Presets, CommentsAreAllowed) {
    TreeParams p = parse_tree_params("// a comment\n{ /* inline */ \"unit\": 2 }", "x.json");
    EXPECT_EQ(p.unit, 2);
}

TEST(Presets, MissingFileAndUnknownNameAreInputErrors) {
    EXPECT_THROW(load_tree_preset("/nonexistent/oak.json"), InputError);
    try {
        resolve_tree_preset("oka");
        FAIL();
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("available: birch"), std::string::npos) << e.what();
    }
}

TEST(Presets, OverridesAreAppliedAndValidated) {
    std::string text = test::read_file(test::source_dir() / "presets/trees/oak.json");
    TreeParams p =
        parse_tree_params(text, "oak.json", {"/trunk/taper/base=0.5", "/twigs/enabled=false"});
    EXPECT_EQ(p.trunk.taper.base, 0.5);
    EXPECT_FALSE(p.twigs.enabled);
    EXPECT_EQ(problems_of(text, {"/trunk/taper/base=1.7"}),
              std::vector<std::string>{"presets/trees/oak.json: /trunk/taper/base: must be in "
                                       "[0, 1], got 1.7 (set by --set)"});
    EXPECT_EQ(problems_of(text, {"trunk.taper=0.5"}).size(), 1u);
}

TEST(Presets, SavedPresetLoadsBackToTheSameTree) {
    for (const auto& name : test::shipped_tree_presets()) {
        TreeParams p = test::preset(name);
        p.trunk.taper.base = 0.91;  // a tweak
        std::string saved = save_tree_params(p);
        TreeParams back = parse_tree_params(saved, "saved.json");
        EXPECT_EQ(save_tree_params(back), saved) << name;
        EXPECT_EQ(test::hash_tree(generate_tree(back, 5)), test::hash_tree(generate_tree(p, 5)))
            << name;
    }
}

TEST(Presets, ReadmeReferenceMatchesTheKeyTable) {
    std::string readme = test::read_file(test::source_dir() / "README.md");
    for (const std::string& table :
         {tree_params_reference(), stroke_shader_reference(), scene_reference(),
          graftal_reference(), imposter_reference(), draft_reference()})
        EXPECT_NE(readme.find(table), std::string::npos)
            << "README.md's key reference is stale; regenerate it with `make reference`";
}

}  // namespace
}  // namespace pleinair
