// `pleinair render` as a user runs it: images in every format, the plan, and bad scenes.
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <thread>
#include <vector>

#include "test_util.h"

namespace pleinair {
namespace {

namespace fs = std::filesystem;
using test::run_pleinair;

// Appends rather than "a" + b: GCC 12 warns falsely (-Wrestrict) on the latter at -O3.
std::string render_small(const std::string& rest) {
    std::string s = "render tests/golden/oak-study/scene.json ";
    s.append(rest);
    return s;
}

TEST(RenderCli, WritesPngTiffAndExrWithAovs) {
    auto dir = test::temp_dir("render-formats");
    auto png = run_pleinair(render_small("-o " + (dir / "a.png").string()));
    ASSERT_EQ(png.exit_code, 0) << png.err;
    auto tif = run_pleinair(render_small("-o " + (dir / "a.tif").string()));
    ASSERT_EQ(tif.exit_code, 0) << tif.err;
    auto exr = run_pleinair(render_small("--aovs -o " + (dir / "a.exr").string()));
    ASSERT_EQ(exr.exit_code, 0) << exr.err;
    auto in = OIIO::ImageInput::open((dir / "a.exr").string());
    ASSERT_TRUE(in);
    const auto& spec = in->spec();
    EXPECT_EQ(spec.channelformat(0), OIIO::TypeDesc::HALF);  // colour in half float
    EXPECT_EQ(spec.nchannels, 8);
    for (const char* c : {"R", "G", "B", "A", "Z", "object_id", "stroke_alpha", "lightness"})
        EXPECT_GE(spec.channelindex(c), 0) << c;
    const int id = spec.channelindex("object_id");
    std::vector<float> px(size_t(spec.width) * spec.height * spec.nchannels);
    ASSERT_TRUE(in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, px.data()));
    size_t tree = 0;
    for (size_t i = 0; i < px.size(); i += spec.nchannels) {
        for (int c = 0; c < spec.nchannels; ++c) ASSERT_TRUE(std::isfinite(px[i + c]));
        tree += px[i + id] == 1.0f;
    }
    EXPECT_GT(tree, 1000u);
    ASSERT_EQ(spec.channelformats.size(), 8u);
    EXPECT_EQ(spec.channelformat(id), OIIO::TypeDesc::FLOAT);
    EXPECT_EQ(spec.channelformat(spec.channelindex("Z")), OIIO::TypeDesc::FLOAT);
    // A landscape: surface strokes' ids (65536 + material) survive exactly, no Inf.
    auto land = run_pleinair(
        "render windmill-hills --set /camera/width=64 --set /camera/height=36 "
        "--aovs -o " +
        (dir / "l.exr").string());
    ASSERT_EQ(land.exit_code, 0) << land.err;
    auto lin = OIIO::ImageInput::open((dir / "l.exr").string());
    ASSERT_TRUE(lin);
    const auto& ls = lin->spec();
    std::vector<float> lp(size_t(ls.width) * ls.height * ls.nchannels);
    ASSERT_TRUE(lin->read_image(0, 0, 0, ls.nchannels, OIIO::TypeDesc::FLOAT, lp.data()));
    size_t ground = 0;
    for (size_t i = 0; i < lp.size(); i += ls.nchannels) {
        for (int c = 0; c < ls.nchannels; ++c) ASSERT_TRUE(std::isfinite(lp[i + c]));
        const float oid = lp[i + ls.channelindex("object_id")];
        ground += oid == 65536.0f || oid == 65537.0f;  // grass or earth
    }
    EXPECT_GT(ground, 100u);
    auto png_in = OIIO::ImageInput::open((dir / "a.png").string());
    ASSERT_TRUE(png_in);
    EXPECT_EQ(png_in->spec().format, OIIO::TypeDesc::UINT8);
    for (const auto& e : fs::directory_iterator(dir))
        EXPECT_EQ(e.path().string().find(".partial"), std::string::npos) << e.path();
    fs::remove_all(dir);
}

TEST(RenderCli, TheTiffIs16BitAndMatchesThePng) {
    auto dir = test::temp_dir("render-tiff");
    ASSERT_EQ(run_pleinair(render_small("-o " + (dir / "a.png").string())).exit_code, 0);
    ASSERT_EQ(run_pleinair(render_small("-o " + (dir / "a.tif").string())).exit_code, 0);
    auto tif = OIIO::ImageInput::open((dir / "a.tif").string());
    auto png = OIIO::ImageInput::open((dir / "a.png").string());
    ASSERT_TRUE(tif && png);
    EXPECT_EQ(tif->spec().format, OIIO::TypeDesc::UINT16);
    EXPECT_EQ(tif->spec().nchannels, 3);
    const size_t n = size_t(tif->spec().width) * tif->spec().height * 3;
    ASSERT_EQ(n, size_t(png->spec().width) * png->spec().height * 3);
    std::vector<uint16_t> t(n);
    std::vector<uint8_t> p(n);
    ASSERT_TRUE(tif->read_image(0, 0, 0, 3, OIIO::TypeDesc::UINT16, t.data()));
    ASSERT_TRUE(png->read_image(0, 0, 0, 3, OIIO::TypeDesc::UINT8, p.data()));
    // The same sRGB values, rounded to 16 bits and to 8: within half an 8-bit level, and the
    // 16-bit file holds levels the 8-bit one cannot (it is not the PNG widened).
    size_t finer = 0;
    for (size_t i = 0; i < n; ++i) {
        ASSERT_LE(std::abs(t[i] / 257.0 - p[i]), 0.5 + 1e-9) << i;
        finer += t[i] % 257 != 0;
    }
    EXPECT_GT(finer, n / 2);
}

// `bench accuracy` on a small frame: every row measured, the rows equal to the reference
// identical to it, and the error falling as each accuracy setting rises.
TEST(RenderCli, BenchAccuracyMeasuresEveryRowHonestly) {
    const auto r = run_pleinair(
        "bench accuracy tests/golden/oak-study/scene.json --repeat 1 --set /camera/width=48 "
        "--set /camera/height=48");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    std::map<std::string, double> rmse;
    std::istringstream lines(r.out);
    std::string line;
    while (std::getline(lines, line)) {
        if (line.rfind("| ", 0) != 0 || line.find("---") != std::string::npos ||
            line.find("| setting") == 0)
            continue;
        std::vector<std::string> cells;
        std::istringstream row(line.substr(2));
        for (std::string c; std::getline(row, c, '|');) {
            while (!c.empty() && c.front() == ' ') c.erase(c.begin());
            while (!c.empty() && c.back() == ' ') c.pop_back();
            cells.push_back(c);
        }
        ASSERT_GE(cells.size(), 5u) << line;
        const double ms = std::stod(cells[2]), err = std::stod(cells[3]);
        EXPECT_TRUE(std::isfinite(ms) && ms >= 0 && std::isfinite(err) && err >= 0) << line;
        rmse[cells[1]] = err;
    }
    ASSERT_GE(rmse.size(), 14u) << r.out;
    for (const char* same : {"16 samples per pixel", "exact per fragment", "exact (sin, pow)",
                             "0 (every stroke)", "every one at the samples above"})
        EXPECT_EQ(rmse.at(same), 0.0) << same;
    EXPECT_GT(rmse.at("1 sample per pixel"), rmse.at("4 samples per pixel"));
    EXPECT_GT(rmse.at("4 samples per pixel"), 0.0);
    EXPECT_GT(rmse.at("1 octave"), rmse.at("2 octaves"));
    EXPECT_GT(rmse.at("2 octaves"), rmse.at("4 octaves"));
    EXPECT_GT(rmse.at("1/256"), 0.0);
}

// `bench trees`: a row a family with its members' median and range; a bad preset or an option
// another kind reads is one line on stderr, exit 2, and nothing on stdout.
TEST(RenderCli, BenchTreesMeasuresEachFamilyOrRefusesInOneLine) {
    const auto r = run_pleinair("bench trees shrub --members 2 --width 120 --height 135");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const size_t row = r.out.find("| shrub | ");
    ASSERT_NE(row, std::string::npos) << r.out;
    EXPECT_NE(r.out.find(" (", row), std::string::npos) << r.out;  // median (least-most)
    for (const char* bad : {"bench trees nosuch", "bench trees shrub --frames 1-2",
                            "bench trees shrub --set /nokey=1", "bench look grove --members 2"}) {
        const auto b = run_pleinair(bad);
        EXPECT_EQ(b.exit_code, 2) << bad;
        EXPECT_EQ(b.out, "") << bad;
        EXPECT_EQ(std::count(b.err.begin(), b.err.end(), '\n'), 1) << bad << ": " << b.err;
    }
    // The unknown family is named as bench trees' argument, not as an option it has not.
    const auto nosuch = run_pleinair("bench trees nosuch");
    EXPECT_EQ(nosuch.err.rfind("bench trees: no tree preset \"nosuch\"", 0), 0u) << nosuch.err;
}

// Same bytes through the command line on a frame of many tiles (192 of 64 px), on one thread
// and on four times more threads than this machine has cores.
TEST(RenderCli, ManyTilesSameBytesOnOneThreadAndOnMoreThreadsThanCores) {
    const auto dir = test::temp_dir("render-threads");
    const std::string size = " --set /camera/width=1024 --set /camera/height=768";
    const unsigned many = 4 * std::max(1u, std::thread::hardware_concurrency());
    ASSERT_EQ(run_pleinair(render_small("-o " + (dir / "one.png").string() + size + " --threads 1"))
                  .exit_code,
              0);
    ASSERT_EQ(run_pleinair(render_small("-o " + (dir / "many.png").string() + size + " --threads " +
                                        std::to_string(many)))
                  .exit_code,
              0);
    const std::string one = test::read_file(dir / "one.png");
    EXPECT_GT(one.size(), 10000u);
    EXPECT_EQ(one, test::read_file(dir / "many.png"));
}

// --fast-rays lets Embree pick its widest instruction set: a few values may move on a CPU with
// AVX2 or AVX-512 (their BVH and hit tests round differently from SSE2's), no more.
TEST(RenderCli, FastRaysPaintsWhatThePortableDefaultDoesWithinALevel) {
    const auto dir = test::temp_dir("render-fast-rays");
    const std::string scene = "render tests/golden/shadows-per-fragment/scene.json -o ";
    ASSERT_EQ(run_pleinair(scene + (dir / "portable.png").string()).exit_code, 0);
    ASSERT_EQ(run_pleinair(scene + (dir / "fast.png").string() + " --fast-rays").exit_code, 0);
    auto a = OIIO::ImageInput::open((dir / "portable.png").string());
    auto b = OIIO::ImageInput::open((dir / "fast.png").string());
    ASSERT_TRUE(a && b);
    const size_t n = size_t(a->spec().width) * a->spec().height * 3;
    std::vector<uint8_t> pa(n), pb(n);
    ASSERT_TRUE(a->read_image(0, 0, 0, 3, OIIO::TypeDesc::UINT8, pa.data()));
    ASSERT_TRUE(b->read_image(0, 0, 0, 3, OIIO::TypeDesc::UINT8, pb.data()));
    size_t moved = 0;
    for (size_t i = 0; i < n; ++i) moved += pa[i] != pb[i];
    EXPECT_LE(moved, n / 1000);  // at most 0.1% of the values
    RecordProperty("values_moved", static_cast<int>(moved));
}

TEST(RenderCli, ExplainPrintsThePlanWithSkippedPasses) {
    auto dir = test::temp_dir("render-explain");
    auto r = run_pleinair(render_small("--explain -o " + (dir / "a.png").string()));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find("atmosphere"), std::string::npos);
    EXPECT_NE(r.out.find("skipped     the scene has no atmosphere"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("skipped     not asked for"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("fragments"), std::string::npos);
    fs::remove_all(dir);
}

TEST(RenderCli, BadScenesAreOneLineExitTwoAndNoImage) {
    auto dir = test::temp_dir("render-bad");
    struct Case {
        std::string json, expected;
    } cases[] = {
        {R"({"camera": {"fov": 0}})", ": /camera/fov: must be in [0.001, 179], got 0\n"},
        {R"({"materials": {"grass": {"shader": "grass"}}, "terrain": {"max": [-200, 5]}})",
         ": /terrain/max: must be greater than /terrain/min in x and z; in x -200 is not > -100\n"},
        {R"({"terrain": {"material": "grss"}})",
         ": /terrain/material: no material \"grss\" in /materials (have: none)\n"},
        {R"({"materials": {"g": {"shader": "corot-leaves"}}})",
         ": /materials/g/shader: shader \"corot-leaves\" has no \"surface\" section"},
        {R"({"render": {"shadows": "soft"}})",
         ": /render/shadows: expected \"transmissive\" or \"threshold\", got \"soft\"\n"},
        {R"({"materials": {"grass": {"shader": "grass"}}, "terrain": {},
             "rocks": [{"radius": -1, "material": "grass"}]})",
         ": /rocks/0/radius: must be in [0, 1e+06], got -1\n"},
        {R"({"materials": {"grass": {"shader": "grass"}}, "terrain": {},
             "groups": [{"families": {"elm": 1}}]})",
         ": /groups/0/families/elm: no family \"elm\" in /families\n"},
        {R"({"camra": {}})", ": /camra: unknown key (did you mean \"camera\"?)\n"},
        {R"({"families": {"a": {"preset": "oka"}}})",
         ": /families/a/preset: no tree preset \"oka\""},
        {R"({"families": {"a": {"preset": "oak"}}, "trees": [{"family": "b"}]})",
         ": /trees/0/family: no family \"b\" in /families (have: a)\n"},
        {R"({"render": {"samples": 3}})", ": /render/samples: must be 1, 4 or 16, got 3\n"},
        {R"({"families": {"a": {"preset": "oak"}}, "trees": [{"family": "a", "scale": 0}]})",
         ": /trees/0/scale: must be in [0.0001, 10000], got 0\n"},
        {R"({"families": {"a": {"preset": "oak", "leaf_palette": "missing.json"}}})",
         ": /families/a/leaf_palette: "},
        {R"({"background": {"sky_zenith": [2, 0, 0]}})",
         ": /background/sky_zenith: expected a colour"},
        {"{ \"camera\": ", ": "},
    };
    int i = 0;
    for (const auto& c : cases) {
        fs::path scene = dir / std::to_string(i++);
        scene += ".json";
        { std::ofstream(scene) << c.json; }
        fs::path out = dir / "never.png";
        auto r = run_pleinair("render " + scene.string() + " -o " + out.string());
        EXPECT_EQ(r.exit_code, 2) << c.json;
        EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
        EXPECT_EQ(r.err.rfind(scene.string() + c.expected, 0), 0u) << r.err;
        EXPECT_FALSE(fs::exists(out));
    }
    auto r = run_pleinair("render /nonexistent/scene.json -o " + (dir / "x.png").string());
    EXPECT_EQ(r.exit_code, 2);
    r = run_pleinair(render_small("-o " + (dir / "x.jpg").string()));
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find(".png, .tif, .tiff or .exr"), std::string::npos) << r.err;
    fs::remove_all(dir);
}

TEST(RenderCli, BadShaderPresetNamesItsFileAndKey) {
    auto dir = test::temp_dir("render-bad-shader");
    { std::ofstream(dir / "leaves.json") << R"({"stroke": {"stroke_fullness": 1.5}})"; }
    {
        std::ofstream(dir / "scene.json")
            << R"({"families": {"a": {"preset": "oak", "leaf_shader": "leaves.json"}}})";
    }
    auto r =
        run_pleinair("render " + (dir / "scene.json").string() + " -o " + (dir / "x.png").string());
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_EQ(r.err, (dir / "scene.json").string() +
                         ": /families/a/leaf_shader: " + (dir / "leaves.json").string() +
                         ": /stroke/stroke_fullness: must be in [0, 1], got 1.5\n");
    fs::remove_all(dir);
}

}  // namespace
}  // namespace pleinair
