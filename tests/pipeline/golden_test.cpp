// Golden images: every tests/golden/<case>/scene.json painted and compared with the
// reference.png beside it, within the tolerance stated in tests/golden/README.md.
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "pipeline/frame/paint_frame.h"
#include "pipeline/output/height_map_writer.h"
#include "pipeline/output/image_io.h"
#include "test_util.h"

namespace pleinair {
namespace {

namespace fs = std::filesystem;

// The largest mean absolute difference, in 8-bit levels over the three channels, of any 8 x 8
// block (at every offset) between two images: the RMSE over the whole frame cannot see a few
// missing or recoloured strokes, this can.
double worst_block(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b, int w, int h) {
    constexpr int kBlock = 8;
    // Summed-area table of the per-pixel difference.
    std::vector<double> sat(static_cast<size_t>(w + 1) * (h + 1), 0.0);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            double d = 0;
            for (int c = 0; c < 3; ++c) {
                const size_t i = 3 * (static_cast<size_t>(y) * w + x) + c;
                d += std::abs(int(a[i]) - int(b[i]));
            }
            sat[(y + 1) * (w + 1) + x + 1] = d / 3 + sat[y * (w + 1) + x + 1] +
                                             sat[(y + 1) * (w + 1) + x] - sat[y * (w + 1) + x];
        }
    double worst = 0;
    for (int y = 0; y + kBlock <= h; ++y)
        for (int x = 0; x + kBlock <= w; ++x) {
            const double sum = sat[(y + kBlock) * (w + 1) + x + kBlock] -
                               sat[y * (w + 1) + x + kBlock] - sat[(y + kBlock) * (w + 1) + x] +
                               sat[y * (w + 1) + x];
            worst = std::max(worst, sum / (kBlock * kBlock));
        }
    return worst;
}

// The gate sees what it must: a 6 x 6 patch of a crown recoloured by 40 levels (a stroke
// painted from the wrong part of its palette), which keeps the RMSE under a level.
TEST(GoldenImages, TheGateSeesARecolouredStroke) {
    const fs::path dir = test::source_dir() / "tests" / "golden" / "oak-study";
    Frame frame = paint_still(load_scene(dir / "scene.json"));
    const std::vector<uint8_t> good = frame_srgb8(frame);
    std::vector<uint8_t> recoloured = good;
    const int w = frame.width;
    const int cx = w / 2 + 10, cy = frame.height / 2 - 20;  // inside the crown
    for (int y = cy; y < cy + 6; ++y)
        for (int x = cx; x < cx + 6; ++x)
            for (int c = 0; c < 3; ++c) {
                uint8_t& v = recoloured[3 * (static_cast<size_t>(y) * w + x) + c];
                v = static_cast<uint8_t>(v < 128 ? v + 40 : v - 40);
            }
    double sq = 0;
    for (size_t i = 0; i < good.size(); ++i) sq += std::pow(int(good[i]) - int(recoloured[i]), 2);
    EXPECT_LT(std::sqrt(sq / good.size()), 1.0) << "the RMSE alone would pass it";
    EXPECT_GT(worst_block(good, recoloured, w, frame.height), 16.0);
    EXPECT_EQ(worst_block(good, good, w, frame.height), 0.0);
}

// The height map round trip (issue 29): the small Mortefontaine's noise terrain written as a
// 16-bit height map at its grid's resolution, then read back in place of the noise (hills and
// noise off), paints the same picture within the gate: water, strokes, trees and all stand on
// the same ground, to the map's 1/65535 of the height range between grid points.
TEST(GoldenImages, AHeightMapWrittenFromANoiseTerrainPaintsThatTerrain) {
    const fs::path scene =
        test::source_dir() / "tests" / "golden" / "mortefontaine-small" / "scene.json";
    const SceneDesc noise = load_scene(scene);
    ASSERT_TRUE(noise.terrain.present);
    const GridSurface grid = generate_terrain(noise.terrain.params, noise.terrain.seed);
    double lo = 1e300, hi = -1e300;
    for (const glm::vec3& p : grid.positions)
        lo = std::min<double>(lo, p.y), hi = std::max<double>(hi, p.y);
    const fs::path dir = test::temp_dir("height-map-round-trip");
    write_height_map(dir / "heights.png", grid, lo, hi);
    char map[512];
    std::snprintf(map, sizeof map,
                  "/terrain/height_map={\"file\": \"%s\", \"low\": %.17g, \"high\": %.17g}",
                  (dir / "heights.png").string().c_str(), lo, hi);
    const SceneDesc mapped = load_scene(
        scene, {map, "/terrain/noise_amplitude=0", "/terrain/hills=[]", "/terrain/base_height=0"});
    ASSERT_TRUE(mapped.terrain.params.height_map);
    EXPECT_EQ(mapped.terrain.params.height_map->width, grid.nu);
    const Frame a = paint_still(noise), b = paint_still(mapped);
    const std::vector<uint8_t> pa = frame_srgb8(a), pb = frame_srgb8(b);
    ASSERT_EQ(pa.size(), pb.size());
    double sq = 0;
    for (size_t i = 0; i < pa.size(); ++i) sq += std::pow(int(pa[i]) - int(pb[i]), 2);
    const double rmse = std::sqrt(sq / pa.size());
    const double block = worst_block(pa, pb, a.width, a.height);
    EXPECT_LE(rmse, 1.0);
    EXPECT_LE(block, 16.0);
    RecordProperty("rmse", std::to_string(rmse));
    RecordProperty("worst_block", std::to_string(block));
    std::printf("height map round trip: RMSE %.3f, worst 8x8 block %.2f levels\n", rmse, block);
    fs::remove_all(dir);
}

// A case's painted image in 8-bit sRGB: a scene painted as a still, or a frame of a shipped shot
// painted by `pleinair animate` with the arguments its `animate` file holds (the path a user's
// fly-through takes; issue 24's sky broke there alone).
std::vector<uint8_t> paint_case(const fs::path& dir, int& width, int& height) {
    if (!fs::exists(dir / "animate")) {
        Frame frame = paint_still(load_scene(dir / "scene.json"));
        width = frame.width, height = frame.height;
        return frame_srgb8(frame);
    }
    std::string args = test::read_file(dir / "animate");
    while (!args.empty() && (args.back() == '\n' || args.back() == ' ')) args.pop_back();
    const fs::path out = test::temp_dir("golden-" + dir.filename().string());
    // shot-NAME, or shot-NAME@WHEN for another frame of the same shot.
    const std::string name = dir.filename().string().substr(5);
    const std::string shot = name.substr(0, name.find('@'));
    const auto r = test::run_pleinair("animate " + shot + " " + args + " -o " +
                                      (out / "f_####.png").string() + " --progress log");
    EXPECT_EQ(r.exit_code, 0) << r.err;
    std::vector<uint8_t> px;
    for (const auto& e : fs::directory_iterator(out)) {
        auto in = OIIO::ImageInput::open(e.path().string());
        if (!in) continue;
        width = in->spec().width, height = in->spec().height;
        px.resize(static_cast<size_t>(width) * height * 3);
        if (!in->read_image(0, 0, 0, 3, OIIO::TypeDesc::UINT8, px.data())) px.clear();
    }
    fs::remove_all(out);
    return px;
}

TEST(GoldenImages, MatchTheirReferences) {
    // Two minutes of test time under the sanitizers, for painters the every-shipped-scene test
    // runs there already (CI's time, issue 51): the plain build compares the references.
    if (test::kAddressSanitizer) GTEST_SKIP() << "the golden images are compared in the plain build";
    fs::path root = test::source_dir() / "tests" / "golden";
    int cases = 0;
    for (const auto& entry : fs::directory_iterator(root)) {
        if (!entry.is_directory()) continue;
        const std::string name = entry.path().filename().string();
        SCOPED_TRACE(name);
        int width = 0, height = 0;
        const std::vector<uint8_t> got = paint_case(entry.path(), width, height);
        ASSERT_EQ(got.size(), static_cast<size_t>(width) * height * 3);

        auto in = OIIO::ImageInput::open((entry.path() / "reference.png").string());
        ASSERT_TRUE(in) << "missing reference; see tests/golden/README.md";
        const OIIO::ImageSpec& spec = in->spec();
        ASSERT_EQ(spec.width, width);
        ASSERT_EQ(spec.height, height);
        ASSERT_EQ(spec.nchannels, 3);
        std::vector<uint8_t> want(got.size());
        ASSERT_TRUE(in->read_image(0, 0, 0, 3, OIIO::TypeDesc::UINT8, want.data()));
        in->close();

        double sq = 0;
        for (size_t i = 0; i < got.size(); ++i) sq += std::pow(int(got[i]) - int(want[i]), 2);
        double rmse = std::sqrt(sq / got.size());
        EXPECT_LE(rmse, 1.0) << "RMSE in 8-bit levels";
        EXPECT_LE(worst_block(got, want, width, height), 16.0)
            << "mean difference over the worst 8 x 8 block, in 8-bit levels";
        ++cases;
    }
    EXPECT_GE(cases, 18);
}

// Every shipped shot has a golden frame (tests/golden/shot-NAME): a new shot joins the gate by
// being shipped, or this fails until its case is added (make golden paints it).
TEST(GoldenImages, EveryShippedShotHasAGoldenFrame) {
    const fs::path root = test::source_dir();
    int shots = 0;
    for (const auto& e : fs::directory_iterator(root / "presets" / "scenes")) {
        if (e.path().extension() != ".json" || !load_scene(e.path()).animated()) continue;
        ++shots;
        const fs::path dir = root / "tests" / "golden" / ("shot-" + e.path().stem().string());
        EXPECT_TRUE(fs::exists(dir / "animate") && fs::exists(dir / "reference.png"))
            << e.path().stem() << " has no golden frame in " << dir;
    }
    EXPECT_GE(shots, 5);
}

}  // namespace
}  // namespace pleinair
