// Height maps: 16-bit and float files read back as the heights written, a terrain built on one
// stands on those heights, and bad files are refused with their file and key.
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "pipeline/input/error.h"
#include "pipeline/input/height_map_io.h"
#include "pipeline/input/scene.h"
#include "pipeline/output/height_map_writer.h"
#include "pipeline/output/image_io.h"
#include "test_util.h"

namespace pleinair {
namespace {

namespace fs = std::filesystem;

// A 5 x 3 grid whose heights are 10 i + j, over x in [0, 40] and z in [0, 20].
GridSurface ramp() {
    GridSurface g;
    g.nu = 5, g.nv = 3;
    for (int j = 0; j < g.nv; ++j)
        for (int i = 0; i < g.nu; ++i)
            g.positions.emplace_back(10.0f * i, 10.0f * i + j, 10.0f * j);
    return g;
}

// An image of `channels` channels of `T` samples, all `value` but sample `odd` (if any), which
// is `odd_value`: the files a height map must not be.
template <class T>
void write_image(const fs::path& path, int w, int h, int channels, OIIO::TypeDesc type, T value,
                 int odd = -1, T odd_value = T()) {
    std::vector<T> px(size_t(w) * h * channels, value);
    if (odd >= 0) px[odd] = odd_value;
    auto out = OIIO::ImageOutput::create(path.string());
    ASSERT_TRUE(out && out->open(path.string(), OIIO::ImageSpec(w, h, channels, type)));
    ASSERT_TRUE(out->write_image(type, px.data()));
    out->close();
}

std::string error_of(const fs::path& file, double low = 0, double high = 1) {
    try {
        read_height_map(file, low, high, "scene.json", "/terrain/height_map/file");
    } catch (const InputError& e) {
        EXPECT_EQ(e.source(), "scene.json");
        EXPECT_EQ(e.problems().at(0).pointer, "/terrain/height_map/file");
        return e.problems().at(0).message;
    }
    return "";
}

TEST(HeightMap, SixteenBitFilesReadBackWithinOneStep) {
    const fs::path dir = test::temp_dir("height-map-16");
    const GridSurface g = ramp();
    for (const char* name : {"h.png", "h.tif"}) {
        SCOPED_TRACE(name);
        write_height_map(dir / name, g, -2.0, 50.0);
        const HeightMap m = read_height_map(dir / name, -2.0, 50.0, "s", "/p");
        ASSERT_EQ(m.width, 5);
        ASSERT_EQ(m.height, 3);
        for (size_t k = 0; k < g.positions.size(); ++k)
            EXPECT_NEAR(m.heights[k], g.positions[k].y, 52.0 / 65535 / 2 + 1e-5);
        // Column 0 at u 0 (min x), row 0 at v 0 (min z); bilinear between them.
        EXPECT_NEAR(m.at(0.0, 0.0), 0.0, 1e-3);
        EXPECT_NEAR(m.at(1.0, 0.0), 40.0, 1e-3);
        EXPECT_NEAR(m.at(0.0, 1.0), 2.0, 1e-3);
        EXPECT_NEAR(m.at(0.125, 0.25), 5.5, 1e-3);
    }
    fs::remove_all(dir);
}

TEST(HeightMap, FloatExrKeepsItsHeightsAsTheyStand) {
    const fs::path dir = test::temp_dir("height-map-exr");
    const GridSurface g = ramp();
    write_height_map(dir / "h.exr", g, 0, 0);
    const HeightMap m = read_height_map(dir / "h.exr", 0.0, 1.0, "s", "/p");
    for (size_t k = 0; k < g.positions.size(); ++k) EXPECT_EQ(m.heights[k], g.positions[k].y);
    // low and high scale a float map too.
    const HeightMap scaled = read_height_map(dir / "h.exr", 100.0, 102.0, "s", "/p");
    EXPECT_EQ(scaled.heights[6], 100.0f + 2.0f * g.positions[6].y);
    fs::remove_all(dir);
}

TEST(HeightMap, ATerrainOnAMapStandsOnItsHeights) {
    TerrainParams p;
    p.min = {0, 0}, p.max = {40, 20};
    p.resolution = 9;
    p.noise_amplitude = 0;
    p.base_height = 1;
    auto map = std::make_shared<HeightMap>();
    map->width = 5, map->height = 3;
    for (const glm::vec3& q : ramp().positions) map->heights.push_back(q.y);
    p.height_map = map;
    EXPECT_NEAR(terrain_height(p, 1, 20.0, 10.0), 1.0 + 21.0, 1e-9);  // sample (2, 1)
    EXPECT_NEAR(terrain_height(p, 1, 25.0, 10.0), 1.0 + 26.0, 1e-9);  // halfway to (3, 1)
    const GridSurface g = generate_terrain(p, 1);
    EXPECT_FLOAT_EQ(g.at(8, 8).y, 1.0f + 42.0f);
}

TEST(HeightMap, BadFilesAreNamedWithWhatWasExpected) {
    const fs::path dir = test::temp_dir("height-map-bad");
    EXPECT_NE(error_of(dir / "none.png").find("no height map file"), std::string::npos);

    // An 8-bit greyscale PNG: 256 heights terrace the ground.
    write_image<uint8_t>(dir / "eight.png", 4, 4, 1, OIIO::TypeDesc::UINT8, 7);
    EXPECT_NE(error_of(dir / "eight.png").find("expected 16-bit (PNG, TIFF) or float"),
              std::string::npos)
        << error_of(dir / "eight.png");

    // Three channels.
    write_image<uint16_t>(dir / "rgb.png", 4, 4, 3, OIIO::TypeDesc::UINT16, 7);
    EXPECT_NE(error_of(dir / "rgb.png").find("3 channels; expected one"), std::string::npos);

    // A truncated PNG.
    write_height_map(dir / "whole.png", ramp(), 0, 50);
    const std::string bytes = test::read_file(dir / "whole.png");
    std::ofstream(dir / "cut.png", std::ios::binary) << bytes.substr(0, bytes.size() / 2);
    EXPECT_NE(error_of(dir / "cut.png").find("chunk (truncated)"), std::string::npos)
        << error_of(dir / "cut.png");

    // A NaN in an EXR, with its place.
    write_image<float>(dir / "nan.exr", 3, 2, 1, OIIO::TypeDesc::FLOAT, 1.0f, 4, std::nanf(""));
    EXPECT_NE(error_of(dir / "nan.exr").find("column 1, row 1 is not a finite height"),
              std::string::npos)
        << error_of(dir / "nan.exr");

    // One sample a side is no grid.
    write_image<uint16_t>(dir / "thin.png", 1, 5, 1, OIIO::TypeDesc::UINT16, 7);
    EXPECT_NE(error_of(dir / "thin.png").find("is 1 x 5; expected 2 to 8193"), std::string::npos);
    fs::remove_all(dir);
}

// Through the command: one line naming the scene, the key and the problem; exit 2; no image.
TEST(HeightMap, ABadMapInASceneIsOneLineExitTwo) {
    const fs::path dir = test::temp_dir("height-map-cli");
    write_image<uint8_t>(dir / "eight.png", 4, 4, 1, OIIO::TypeDesc::UINT8, 7);
    std::ofstream(dir / "scene.json") << R"({"materials": {"grass": {"shader": "grass"}},
               "terrain": {"height_map": {"file": "eight.png", "high": 30}}})";
    const auto r = test::run_pleinair("render " + (dir / "scene.json").string() + " -o " +
                                      (dir / "out.png").string());
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_NE(r.err.find("scene.json: /terrain/height_map/file: height map"), std::string::npos)
        << r.err;
    EXPECT_FALSE(fs::exists(dir / "out.png"));
    fs::remove_all(dir);
}

// render --export-height-map writes the terrain's grid and says how to read it back; a scene
// without a terrain has none to write (exit 2, one line, nothing written).
TEST(HeightMap, RenderExportsTheTerrainItWouldPaint) {
    const fs::path dir = test::temp_dir("height-map-export");
    auto r =
        test::run_pleinair("render mortefontaine --export-height-map " + (dir / "h.tif").string());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find("/terrain/height_map {\"file\": \"h.tif\", \"low\": "), std::string::npos)
        << r.out;
    const SceneDesc scene =
        load_scene(test::source_dir() / "presets" / "scenes" / "mortefontaine.json");
    const GridSurface grid = generate_terrain(scene.terrain.params, scene.terrain.seed);
    auto in = OIIO::ImageInput::open((dir / "h.tif").string());
    ASSERT_TRUE(in);
    EXPECT_EQ(in->spec().width, grid.nu);
    EXPECT_EQ(in->spec().format, OIIO::TypeDesc::UINT16);
    in->close();
    std::ofstream(dir / "bare.json") << R"({"camera": {"width": 64, "height": 36}})";
    r = test::run_pleinair("render " + (dir / "bare.json").string() + " --export-height-map " +
                           (dir / "bare.png").string());
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_NE(r.err.find("/terrain: --export-height-map needs a terrain"), std::string::npos)
        << r.err;
    EXPECT_FALSE(fs::exists(dir / "bare.png"));
    fs::remove_all(dir);
}

}  // namespace
}  // namespace pleinair
