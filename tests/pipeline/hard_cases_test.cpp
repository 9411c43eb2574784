// The hard-case suite: every case named in kCases (the README's "Hard cases" table lists them
// with what each covers) is a small scene painted in full, with AOVs, or an input refused.
// Painted, every buffer must be finite and sane (colours and coverage in [0, 1], depths
// positive, object ids whole), and the case's own expectation must hold: strokes painted, or
// none. Refused, the one line must name what is wrong.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <string>
#include <vector>

#include "pipeline/input/error.h"
#include "pipeline/frame/paint_frame.h"
#include "pipeline/input/scene.h"
#include "ply_writer.h"
#include "test_util.h"

namespace pleinair {
namespace {

namespace fs = std::filesystem;

enum class Expect { kStrokes, kNoStrokes, kFinite, kRefused };

struct HardCase {
    const char* name;
    const char* covers;            // what it tries, for the table
    std::vector<std::string> set;  // --set overrides of the base scene
    Expect expect = Expect::kStrokes;
    const char* refusal = "";      // kRefused: in the message
    const char* scene = nullptr;   // another scene than the base
    int cloud = 5;                 // particles in cloud.ply (at the origin's neighbourhood)
    const char* cloud_where = "";  // "eye": at the camera; "behind": behind it; "one": one point
};

// A small landscape with every kind of particle: terrain with a hill and water, a rock, a
// shrub, and a particle file; shadows and atmosphere on; 64 x 48.
constexpr const char* kBase = R"({
  "camera": {"position": [0, 2, 14], "look_at": [0, 1.5, 0], "fov": 50, "width": 64, "height": 48},
  "sun": {"direction": [-0.5, 0.7, 0.5], "casts_shadows": true},
  "atmosphere": {"near": 10, "far": 100},
  "materials": {"grass": {"shader": "grass.json"}, "water": {"shader": "water"},
                "rock": {"shader": "rock"}},
  "terrain": {"seed": 2, "min": [-30, -30], "max": [30, 30], "resolution": 17,
              "material": "grass", "hills": [{"center": [-8, -10], "radius": 8, "height": 3}],
              "strokes": {"particle_spans_u": 24, "particle_spans_v": 24,
                          "particles_per_cluster": 2}},
  "water": {"level": -0.2, "material": "water",
            "strokes": {"particle_spans_u": 4, "particle_spans_v": 4}},
  "rocks": [{"seed": 1, "position": [3, 0, 4], "radius": 0.6, "material": "rock"}],
  "families": {"shrub": {"preset": "shrub.json"}},
  "trees": [{"family": "shrub", "seed": 1, "position": [-2, 0, 2]}],
  "particles": [{"file": "cloud.ply", "material": "grass"}]
})";

// The same scene 99,900 units out, at the edge of the world (every coordinate within 1e5).
constexpr const char* kEdge = R"({
  "camera": {"position": [99900, 2, 99914], "look_at": [99900, 1.5, 99900], "fov": 50,
             "width": 64, "height": 48},
  "sun": {"direction": [-0.5, 0.7, 0.5], "casts_shadows": true},
  "materials": {"grass": {"shader": "grass.json"}, "rock": {"shader": "rock"}},
  "terrain": {"seed": 2, "min": [99870, 99870], "max": [99930, 99930], "resolution": 17,
              "material": "grass",
              "strokes": {"particle_spans_u": 24, "particle_spans_v": 24,
                          "particles_per_cluster": 2}},
  "rocks": [{"seed": 1, "position": [99903, 0, 99904], "radius": 0.6, "material": "rock"}],
  "families": {"shrub": {"preset": "shrub.json"}},
  "trees": [{"family": "shrub", "seed": 1, "position": [99898, 0, 99902]}],
  "particles": [{"file": "cloud.ply", "material": "grass", "position": [99900, 0, 99900]}]
})";

// Particles alone: the base scene's camera, sun and particle file.
constexpr const char* kParticlesOnly = R"({
  "camera": {"position": [0, 2, 14], "look_at": [0, 1.5, 0], "fov": 50, "width": 64, "height": 48},
  "sun": {"direction": [-0.5, 0.7, 0.5], "casts_shadows": true},
  "materials": {"grass": {"shader": "grass.json"}},
  "particles": [{"file": "cloud.ply", "material": "grass"}]
})";

constexpr const char* kEmptyWithShadows = R"({"sun": {"casts_shadows": true},
  "camera": {"width": 64, "height": 48}})";

const std::vector<HardCase>& cases() {
    static const std::vector<HardCase> c = {
        {"Baseline", "every kind of particle, shadows and atmosphere on", {}},
        {"ImpostersOnEveryMesh",
         "graftal imposters on the shrub's limbs, the terrain and the rock",
         {"/families/shrub/imposters=\"seuss-fringe\"",
          "/materials/grass/imposters=\"grass-fringe\"",
          "/materials/rock/imposters=\"grass-fringe\""}},
        {"ImpostersWithTheEyeInsideTheRock",
         "imposters on the rock, the eye inside it: its quads through the near plane",
         {"/materials/rock/imposters=\"grass-fringe\"", "/camera/position=[3, 0.1, 4]",
          "/camera/look_at=[3, 0.1, 0]"},
         Expect::kFinite},
        {"ImpostersOnATerrainAMillimetreWide",
         "imposters on a terrain of 1 mm, its edges far under a pixel",
         {"/materials/grass/imposters=\"grass-fringe\"", "/terrain/min=[0, 0]",
          "/terrain/max=[0.001, 0.001]", "/terrain/hills=[]", "/rocks=[]"},
         Expect::kFinite},
        {"CameraAtATreesCentre",
         "the eye inside the shrub's crown, at its centre",
         {"/camera/position=[-2, 1, 2]", "/camera/look_at=[-2, 1, 0]"},
         Expect::kFinite},
        {"CameraUnderTheTerrain",
         "the eye below the ground, looking along it",
         {"/camera/position=[0, -5, 10]", "/camera/look_at=[0, -5, 0]"},
         Expect::kFinite},
        {"CameraLookingStraightDown",
         "the view parallel to the up vector (another stands in)",
         {"/camera/position=[0, 20, 0]", "/camera/look_at=[0, 0, 0]"}},
        {"CameraLookingStraightUp",
         "the view parallel to up, looking at the sky",
         {"/camera/position=[0, 1, 0]", "/camera/look_at=[0, 30, 0]"},
         Expect::kFinite},
        {"SkyAtTheZenith",
         "a painted sky seen straight up: strokes of every azimuth meet",
         {"/sky={\"stroke_size\": 1}", "/camera/position=[0, 1, 0]", "/camera/look_at=[0, 30, 0]"},
         Expect::kFinite},
        {"SkyWideAndOvercast",
         "full cloud cover, the hardest cloud edge, seen through a 179-degree lens",
         {"/sky={\"cloud_cover\": 1, \"cloud_softness\": 0.001, \"haze\": 0.001}",
          "/camera/fov=179"}},
        {"WaterMirrorAllRipples",
         "water mirroring fully with ripples turning its rays under it",
         {"/water/reflection=1", "/water/ripple=1"}},
        {"WaterMirrorsTheSky",
         "reflected rays meeting nothing but a painted sky, shadows on",
         {"/water/reflection=1", "/sky={}", "/sun/casts_shadows=true"}},
        {"SkyOnACanvas",
         "a sky asked for over a canvas background: none painted",
         {"/sky={}", "/background/canvas=true"}},
        {"FieldOfViewTiny",
         "fov 0.001 degrees: a telescope onto a few strokes",
         {"/camera/fov=0.001"},
         Expect::kFinite},
        {"FieldOfViewWidest",
         "fov 179 degrees: strokes at the edges stretched",
         {"/camera/fov=179"}},
        {"OnePixelImage",
         "a 1 x 1 image",
         {"/camera/width=1", "/camera/height=1"},
         Expect::kFinite},
        {"OnePixelColumn",
         "a 1 x 256 image: tiles one pixel wide",
         {"/camera/width=1", "/camera/height=256"},
         Expect::kFinite},
        {"SunAtTheHorizon",
         "light along the ground: N.L zero for flat ground, long shadows",
         {"/sun/direction=[1, 0, 0]"}},
        {"SunAtTheZenith",
         "light straight down: no shadow leaves its caster",
         {"/sun/direction=[0, 1, 0]"}},
        {"SunBelowTheHorizon",
         "every surface facing away from the light",
         {"/sun/direction=[0, -1, 0.2]"}},
        {"SunGrazingWithShadowsPerFragment",
         "a 4 x 4 shadow grid per sprite under a grazing sun",
         {"/sun/direction=[1, 0.001, 0]", "/render/shadow_samples=\"fragment\""}},
        {"TerrainAMillimetreWide",
         "a terrain 1 mm across: sections far smaller than a stroke",
         {"/terrain/min=[0, 0]", "/terrain/max=[0.001, 0.001]", "/terrain/hills=[]", "/rocks=[]",
          "/trees=[]"}},
        {"TerrainOfZeroArea",
         "min equal to max: refused",
         {"/terrain/max=[-30, -30]"},
         Expect::kRefused,
         "/terrain/max: must be greater than /terrain/min"},
        {"TerrainSteep",
         "hills 500 units of noise over 60: normals near horizontal",
         {"/terrain/noise_amplitude=500", "/terrain/noise_frequency=0.2"},
         Expect::kFinite},
        {"EverythingUnderWater",
         "the water above every point of the ground",
         {"/water/level=50"},
         Expect::kFinite},
        {"EmptySceneWithShadows",
         "nothing to paint or to cast, shadows asked",
         {},
         Expect::kNoStrokes,
         "",
         kEmptyWithShadows},
        {"CoordinatesAtTheEdgeOfTheWorld",
         "a landscape, a tree, a rock and particles 99,900 out",
         {},
         Expect::kStrokes,
         "",
         kEdge},
        {"CoordinatesBeyondTheWorld",
         "a tree a million units out: refused",
         {"/trees/0/position=[1000000, 0, 0]"},
         Expect::kRefused,
         "/trees/0/position: beyond the world pleinair supports"},
        {"OneColourPalette",
         "every spline of the palette one colour",
         {"/materials/grass/palette=\"one-colour.json\""}},
        {"EqualCutOffs",
         "dark and mid cut-offs all at one lightness",
         {"/materials/grass/shader=\"equal-cutoffs.json\""}},
        {"EqualFeatherThresholds",
         "smoothstep's two edges equal: a hard threshold",
         {"/materials/grass/shader=\"equal-feather.json\""}},
        {"StrokeFullnessZero",
         "the rounded edge mask at its narrowest",
         {"/materials/grass/shader=\"fullness-zero.json\""},
         Expect::kFinite},
        {"TreeOfOneStep",
         "a trunk of one extrusion and no branches",
         {"/families/shrub/preset=\"one-step.json\""}},
        {"ParticleFileOfOneParticle",
         "a PLY file holding one vertex",
         {},
         Expect::kStrokes,
         "",
         nullptr,
         1},
        {"ParticlesAllAtOnePoint",
         "1,000 particles at one position, one depth",
         {},
         Expect::kStrokes,
         "",
         kParticlesOnly,
         1000,
         "one"},
        {"ParticleAtTheEye",
         "a particle exactly at the camera",
         {},
         Expect::kFinite,
         "",
         nullptr,
         1,
         "eye"},
        {"ParticlesBehindTheCamera",
         "every imported particle behind the eye",
         {},
         Expect::kNoStrokes,
         "",
         kParticlesOnly,
         200,
         "behind"},
        {"StrokesLargerThanTheScreen",
         "particles 200 units wide at 14 units",
         {"/particles/0/size_to_width=1000"},
         Expect::kStrokes,
         "",
         nullptr,
         50},
        {"StrokePerspectiveZero",
         "strokes keep their screen size at every depth",
         {"/render/stroke_perspective=0"}},
        {"StrokePerspectiveOne",
         "true perspective: near strokes huge",
         {"/render/stroke_perspective=1"}},
        {"SixteenSamplesEightOctaves",
         "the most accurate settings",
         {"/render/samples=16", "/render/octaves=8"}},
        {"AtmosphereNearEqualsFar", "the distance ramp of zero width", {"/atmosphere/far=10"}},
        {"RockTiny", "a rock 0.1 mm across", {"/rocks/0/radius=0.0001"}},
        {"DistanceCirclesOfZeroWidth",
         "leaf_near equal to leaf_far, near field on",
         {"/camera/leaf_near=5", "/camera/leaf_far=5", "/camera/near_field=3"}},
        {"GroupWithNoRoom",
         "a group whose disc holds no tree",
         {"/groups=[{\"seed\": 1, \"center\": [0, 0], \"radius\": 0.001, \"min_distance\": 5, "
          "\"families\": {\"shrub\": 1}}]"}},
        {"SetValueNotUtf8",
         "fuzzing found it: a --set value of invalid UTF-8 (exit 1 before)",
         {"/description=\xd1seed"},
         Expect::kRefused,
         "--set: not valid UTF-8"},
    };
    return c;
}

void PrintTo(const HardCase& c, std::ostream* os) { *os << c.name; }

class HardCases : public ::testing::TestWithParam<HardCase> {
  protected:
    fs::path dir = test::temp_dir("hard-cases");

    void write(const std::string& name, const std::string& text) {
        std::ofstream(dir / name, std::ios::binary) << text;
    }
    static std::string replaced(std::string text, const std::string& from, const std::string& to) {
        const size_t at = text.find(from);
        EXPECT_NE(at, std::string::npos) << from;
        return at == std::string::npos ? text : text.replace(at, from.size(), to);
    }

    // The files the cases name, beside the scene.
    void write_inputs(const HardCase& c) {
        const fs::path presets = test::source_dir() / "presets";
        const std::string grass = test::read_file(presets / "shaders" / "grass.json");
        write("grass.json", grass);
        write("equal-cutoffs.json",
              replaced(grass, R"("dark_cutoff_start": 0.28, "dark_cutoff_end": 0.38,
                      "mid_cutoff_start": 0.58, "mid_cutoff_end": 0.68)",
                       R"("dark_cutoff_start": 0.5, "dark_cutoff_end": 0.5,
                      "mid_cutoff_start": 0.5, "mid_cutoff_end": 0.5)"));
        write("equal-feather.json",
              replaced(grass, R"("stroke_feather_min": 0.38, "stroke_feather_max": 0.58)",
                       R"("stroke_feather_min": 0.5, "stroke_feather_max": 0.5)"));
        write("fullness-zero.json",
              replaced(grass, R"("stroke_fullness": 0.80)", R"("stroke_fullness": 0)"));
        write("one-colour.json", R"({"dark": ["#6a7a50"], "mid": ["#6a7a50"],
                                      "light": ["#6a7a50"]})");
        const std::string shrub = test::read_file(presets / "trees" / "shrub.json");
        write("shrub.json", shrub);
        write("one-step.json", replaced(replaced(shrub, R"("max_steps": 4)", R"("max_steps": 1)"),
                                        R"("probability": 0.6)", R"("probability": 0)"));
        std::vector<test::PlyColumn> cols = {
            {"float", "x", {}}, {"float", "y", {}}, {"float", "z", {}}};
        for (int i = 0; i < c.cloud; ++i) {
            double x = 1.5 + 0.3 * std::sin(i * 1.7), y = 0.6 + 0.3 * std::cos(i * 2.3),
                   z = 5 + 0.3 * std::sin(i * 0.9);
            const std::string where = c.cloud_where;
            if (where == "eye") x = 0, y = 2, z = 14;
            if (where == "one") x = 0, y = 1.5, z = 5;
            if (where == "behind") z = 20 + i * 0.1;
            cols[0].values.push_back(x), cols[1].values.push_back(y), cols[2].values.push_back(z);
        }
        write("cloud.ply", test::write_ply(cols, "binary_little_endian"));
    }
};

TEST_P(HardCases, PaintsFiniteAndSaneOrIsRefusedInOneLine) {
    const HardCase& c = GetParam();
    write_inputs(c);
    SceneDesc scene;
    try {
        scene = parse_scene(c.scene ? c.scene : kBase, (dir / "scene.json").string(), c.set);
    } catch (const InputError& e) {
        const std::string msg = e.what();
        ASSERT_EQ(c.expect, Expect::kRefused) << msg;
        EXPECT_NE(msg.find(c.refusal), std::string::npos) << msg;
        size_t lines = 1;
        for (char ch : msg) lines += ch == '\n';
        EXPECT_EQ(lines, e.problems().size()) << msg;  // one line a problem
        return;
    }
    ASSERT_NE(c.expect, Expect::kRefused) << "accepted";
    FrameReport report;
    const Frame f = paint_still(scene, true, &report);
    const size_t n = static_cast<size_t>(f.width) * f.height;
    ASSERT_EQ(f.rgba.size(), 4 * n);
    ASSERT_TRUE(f.has_aovs);
    size_t covered = 0;
    for (size_t i = 0; i < n; ++i) {
        for (int k = 0; k < 4; ++k) {
            const float v = f.rgba[4 * i + k];
            ASSERT_TRUE(std::isfinite(v) && v >= 0.0f && v <= 1.0f + 1e-5f) << i << " " << v;
        }
        ASSERT_TRUE(std::isfinite(f.alpha[i]) && f.alpha[i] >= 0 && f.alpha[i] <= 1.0f + 1e-5f);
        ASSERT_TRUE(std::isfinite(f.lightness[i]));
        ASSERT_TRUE(std::isfinite(f.depth[i]) && f.depth[i] > 0) << f.depth[i];
        ASSERT_TRUE(std::isfinite(f.object_id[i]) && f.object_id[i] >= 0 &&
                    f.object_id[i] == std::floor(f.object_id[i]));
        covered += f.alpha[i] > 0.5f;
    }
    if (c.expect == Expect::kStrokes) {
        EXPECT_GT(covered, 0u) << "no stroke painted";
        EXPECT_GT(report.surface_sprites + report.leaf_sprites + report.bark_sprites, 0u);
    }
    if (c.expect == Expect::kNoStrokes) {
        EXPECT_EQ(covered, 0u);
        EXPECT_EQ(report.surface_sprites + report.leaf_sprites + report.bark_sprites, 0u);
    }
}

INSTANTIATE_TEST_SUITE_P(Suite, HardCases, ::testing::ValuesIn(cases()),
                         [](const auto& info) { return std::string(info.param.name); });

TEST(HardCaseTable, TheReadmeListsEveryCaseWithWhatItCovers) {
    const std::string readme = test::read_file(test::source_dir() / "README.md");
    EXPECT_GE(cases().size(), 30u);
    for (const HardCase& c : cases())
        EXPECT_NE(readme.find("| `" + std::string(c.name) + "` | " + c.covers + " |"),
                  std::string::npos)
            << c.name;
}

}  // namespace
}  // namespace pleinair
