// One frame whichever command paints it (issue 24): every shipped shot's first, middle and last
// frames through `render --frame` and through `animate` (alone, a range with a step, resumed)
// give the same pixels; the open sky of every shipped scene and shot frame keeps to the colours
// its palette and gradient can give, read from the AOVs of what the commands wrote.
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>

#include "pipeline/bench/look_measures.h"
#include "pipeline/frame/paint_frame.h"
#include "pipeline/input/scene.h"
#include "pipeline/shot/shot.h"
#include "test_util.h"

namespace pleinair {
namespace {

namespace fs = std::filesystem;
using test::run_pleinair;

// Small, so every shipped shot runs under the sanitizers too.
constexpr int kWidth = 112, kHeight = 64;
const std::string kSize = " --set /camera/width=" + std::to_string(kWidth) +
                          " --set /camera/height=" + std::to_string(kHeight);

struct ShippedScene {
    std::string name;
    fs::path file;
    bool animated = false;
    FrameRange frames;  // its track's (frame 1 alone for a still)
};

// Every scene in presets/scenes: a new one joins these tests by being shipped.
std::vector<ShippedScene> shipped_scenes() {
    std::vector<ShippedScene> out;
    for (const auto& e : fs::directory_iterator(test::source_dir() / "presets" / "scenes")) {
        if (e.path().extension() != ".json") continue;
        const SceneDesc scene = load_scene(e.path());
        out.push_back(
            {e.path().stem().string(), e.path(), scene.animated(), animation_frames(scene)});
    }
    std::sort(out.begin(), out.end(),
              [](const ShippedScene& a, const ShippedScene& b) { return a.name < b.name; });
    return out;
}

// The shipped scenes with a track.
std::vector<ShippedScene> shipped_shots() {
    std::vector<ShippedScene> out = shipped_scenes();
    out.erase(std::remove_if(out.begin(), out.end(), [](const auto& s) { return !s.animated; }),
              out.end());
    return out;
}

std::vector<uint8_t> read_rgb8(const fs::path& path) {
    auto in = OIIO::ImageInput::open(path.string());
    if (!in) return {};
    const OIIO::ImageSpec& spec = in->spec();
    std::vector<uint8_t> px(static_cast<size_t>(spec.width) * spec.height * 3);
    if (!in->read_image(0, 0, 0, 3, OIIO::TypeDesc::UINT8, px.data())) return {};
    return px;
}

// An EXR with AOVs, as pleinair writes it, back into a Frame.
Frame read_exr(const fs::path& path) {
    Frame f;
    auto in = OIIO::ImageInput::open(path.string());
    if (!in) return f;
    const OIIO::ImageSpec& spec = in->spec();
    if (spec.nchannels != 8) return f;
    f.width = spec.width, f.height = spec.height, f.has_aovs = true;
    const size_t n = static_cast<size_t>(f.width) * f.height;
    std::vector<float> all(n * 8);
    if (!in->read_image(0, 0, 0, 8, OIIO::TypeDesc::FLOAT, all.data())) return Frame{};
    // By name: the EXR reader orders channels other than RGBA as the file does.
    int at[8];
    const char* names[8] = {"R", "G", "B", "A", "Z", "object_id", "stroke_alpha", "lightness"};
    for (int k = 0; k < 8; ++k) {
        at[k] = spec.channelindex(names[k]);
        if (at[k] < 0) return Frame{};
    }
    f.rgba.resize(4 * n), f.depth.resize(n), f.object_id.resize(n);
    f.alpha.resize(n), f.lightness.resize(n);
    for (size_t i = 0; i < n; ++i) {
        const float* p = &all[8 * i];
        for (int c = 0; c < 4; ++c) f.rgba[4 * i + c] = p[at[c]];
        f.depth[i] = p[at[4]], f.object_id[i] = p[at[5]];
        f.alpha[i] = p[at[6]], f.lightness[i] = p[at[7]];
    }
    return f;
}

size_t differing_pixels(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b) {
    if (a.size() != b.size()) return std::max(a.size(), b.size()) / 3;
    size_t n = 0;
    for (size_t i = 0; i < a.size(); i += 3)
        n += a[i] != b[i] || a[i + 1] != b[i + 1] || a[i + 2] != b[i + 2];
    return n;
}

std::string frame_name(const fs::path& dir, const char* prefix, int f, const char* ext) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%s%04d.%s", prefix, f, ext);
    return (dir / buf).string();
}

class OneFrame : public ::testing::Test {
  protected:
    void SetUp() override { dir_ = test::temp_dir("one-frame"); }
    void TearDown() override { fs::remove_all(dir_); }
    fs::path dir_;
};

// Under AddressSanitizer each command runs about four times slower, and what it checks there is
// memory, which one shot built per command shows as well as three: the sanitized build renders
// only the middle frame alone (CI's time, Makefile's test-sanitize).
#if defined(__SANITIZE_ADDRESS__)
constexpr bool kSanitized = true;
#else
constexpr bool kSanitized = false;
#endif

// The bug of issue 24 lived here: animate held its shot on the heap and the moved shot's
// materials still pointed into the one it was moved from, so its sky was painted from freed
// memory; render, whose shot never moved, painted it right. Nothing compared the two.
TEST_F(OneFrame, RenderAndAnimatePaintTheSamePixelsForEveryShippedShot) {
    const std::vector<ShippedScene> shots = shipped_shots();
    for (const ShippedScene& s : shots) {
        SCOPED_TRACE(s.name);
        const FrameRange& all = s.frames;
        const int first = all.first, last = all.last, step = std::max(1, (last - first) / 2);
        const int middle = std::min(last, first + step);
        const fs::path dir = dir_ / s.name;
        const std::string out = " -o " + (dir / "a_####.png").string() + " --progress log" + kSize;
        // The middle frame alone; then the range with a step, resumed (the middle kept); then
        // the last frame alone if the step missed it.
        auto r = run_pleinair("animate " + s.name + " --frames " + std::to_string(middle) + out);
        ASSERT_EQ(r.exit_code, 0) << r.err;
        r = run_pleinair("animate " + s.name + " --resume --frames " + std::to_string(first) + "-" +
                         std::to_string(last) + "x" + std::to_string(step) + out);
        ASSERT_EQ(r.exit_code, 0) << r.err;
        if (!fs::exists(frame_name(dir, "a_", last, "png"))) {
            r = run_pleinair("animate " + s.name + " --frames " + std::to_string(last) + out);
            ASSERT_EQ(r.exit_code, 0) << r.err;
        }
        for (int f : {first, middle, last}) {
            if (kSanitized && f != middle) continue;
            SCOPED_TRACE("frame " + std::to_string(f));
            const std::string rendered = frame_name(dir, "r_", f, "png");
            r = run_pleinair("render " + s.name + " --frame " + std::to_string(f) + " -o " +
                             rendered + kSize);
            ASSERT_EQ(r.exit_code, 0) << r.err;
            const std::vector<uint8_t> a = read_rgb8(frame_name(dir, "a_", f, "png"));
            const std::vector<uint8_t> b = read_rgb8(rendered);
            ASSERT_EQ(a.size(), size_t{kWidth} * kHeight * 3);
            EXPECT_EQ(differing_pixels(a, b), 0u) << "render --frame and animate differ";
        }
        // --preview halves the size alike in both commands (a size rule: the sanitized build
        // leaves it to the plain one, as it leaves the first and last frames).
        if (kSanitized) continue;
        const std::string preview = frame_name(dir, "p_", middle, "png");
        r = run_pleinair("render " + s.name + " --preview --frame " + std::to_string(middle) +
                         " -o " + preview + " --set /camera/width=" + std::to_string(2 * kWidth) +
                         " --set /camera/height=" + std::to_string(2 * kHeight));
        ASSERT_EQ(r.exit_code, 0) << r.err;
        EXPECT_EQ(
            differing_pixels(read_rgb8(preview), read_rgb8(frame_name(dir, "a_", middle, "png"))),
            0u)
            << "render --preview";
    }
    EXPECT_GE(shots.size(), 5u);
}

// The benches measure the frames the user's commands paint: `bench look --frame N --save` and
// `bench coherence --frames N --save` write the frame they measured, and it is render's and
// animate's, pixel for pixel, for the middle frame of every shipped shot.
TEST_F(OneFrame, BenchesMeasureTheFramesRenderAndAnimatePaint) {
    const std::vector<ShippedScene> shots = shipped_shots();
    for (const ShippedScene& s : shots) {
        SCOPED_TRACE(s.name);
        const FrameRange& all = s.frames;
        const int f = all.first + (all.last - all.first) / 2;
        const fs::path dir = dir_ / s.name;
        const std::string frame = " --frame " + std::to_string(f);
        auto r =
            run_pleinair("render " + s.name + frame + " -o " + (dir / "r.png").string() + kSize);
        ASSERT_EQ(r.exit_code, 0) << r.err;
        r = run_pleinair("bench look " + s.name + frame + " --save " + (dir / "l.png").string() +
                         kSize);
        ASSERT_EQ(r.exit_code, 0) << r.err;
        r = run_pleinair("bench coherence " + s.name + " --frames " + std::to_string(f) +
                         " --save " + (dir / "c_####.png").string() + kSize);
        ASSERT_EQ(r.exit_code, 0) << r.err;
        const std::vector<uint8_t> rendered = read_rgb8(dir / "r.png");
        ASSERT_EQ(rendered.size(), size_t{kWidth} * kHeight * 3);
        EXPECT_EQ(differing_pixels(read_rgb8(dir / "l.png"), rendered), 0u) << "bench look";
        EXPECT_EQ(differing_pixels(read_rgb8(frame_name(dir, "c_", f, "png")), rendered), 0u)
            << "bench coherence";
    }
    EXPECT_GE(shots.size(), 5u);
}

// The shortcuts one path takes give what another computes: a shot moved to the heap (animate),
// the sun's light cached in the shot (animate, bench coherence) or traced per frame (render),
// AOVs (bench look) and traces (bench coherence) on or off: the same colour, bit for bit. The
// walk's frame has a painted sky, still water's mirror, shadows and distance circles.
TEST(OneFrameShortcuts, EveryShortcutPaintsTheSameColours) {
    std::vector<std::string> sets = {"/camera/width=96", "/camera/height=54"};
    const SceneDesc scene =
        load_scene(test::source_dir() / "presets" / "scenes" / "mortefontaine-walk.json", sets);
    const FrameView view = view_at(scene, frame_time(150, scene.fps));
    const Shot traced = build_shot(scene);
    const Frame reference = paint_frame(traced, view, scene_frame_settings(traced.scene));
    ASSERT_GT(traced.sky.size(), 0u);

    ShotOptions cached;
    cached.cache_sun_light = true;
    Shot shot = build_shot(scene, cached);
    ASSERT_TRUE(shot.plan.sun_light);
    EXPECT_EQ(paint_frame(shot, view, scene_frame_settings(shot.scene)).rgba, reference.rgba)
        << "the shot's cached light";
    // Moved twice (construction, then assignment), the first shot destroyed: nothing may point
    // into it.
    auto moved = std::make_unique<Shot>(std::move(shot));
    Shot again;
    again = std::move(*moved);
    moved.reset();
    EXPECT_EQ(paint_frame(again, view, scene_frame_settings(again.scene)).rgba, reference.rgba)
        << "a moved shot";
    FrameSettings with = scene_frame_settings(again.scene, true);
    with.trace = true;
    FrameReport report;
    const Frame traced_frame = paint_frame(again, view, with, &report);
    EXPECT_EQ(traced_frame.rgba, reference.rgba) << "AOVs and a trace";
    ASSERT_TRUE(report.trace);
}

// The open sky (no stroke or surface in front, above the horizon) of every shipped scene and of
// the middle frame of every shipped shot, as `render` and `animate` write it with AOVs, stays
// within what its palette and gradient can give: the black blotches of issue 24 lie 0.5 to 0.8
// below it. The margin (measured: 0.17 at most on the shipped scenes) covers what the paint
// adds legitimately: strokes lighter or darker than their palette entry (stroke_jitter), the
// background's texture, and graftal tufts on a hill's crest, which write no AOV of their own.
TEST_F(OneFrame, TheOpenSkyKeepsToItsPaletteInEveryShippedScene) {
    constexpr float kMargin = 0.2f;
    int skies = 0;
    for (const ShippedScene& s : shipped_scenes()) {
        SCOPED_TRACE(s.name);
        std::vector<std::string> sets = {"/camera/width=" + std::to_string(kWidth),
                                         "/camera/height=" + std::to_string(kHeight)};
        const SceneDesc scene = load_scene(s.file, sets);
        if (scene.background.canvas) continue;  // a canvas has no sky
        const FrameRange all = animation_frames(scene);
        const int frame = all.first + (all.last - all.first) / 2;
        const double t = scene.animated() ? frame_time(frame, scene.fps) : 0.0;
        const Camera camera = (scene.animated() ? view_at(scene, t) : still_view(scene)).camera;
        std::vector<fs::path> painted;
        const std::string exr = (dir_ / (s.name + ".exr")).string();
        auto r = run_pleinair("render " + s.name + " --aovs -o " + exr + kSize +
                              (scene.animated() ? " --frame " + std::to_string(frame) : ""));
        ASSERT_EQ(r.exit_code, 0) << r.err;
        painted.push_back(exr);
        if (scene.animated()) {
            r = run_pleinair("animate " + s.name + " --aovs --progress log --frames " +
                             std::to_string(frame) + " -o " +
                             (dir_ / (s.name + "_####.exr")).string() + kSize);
            ASSERT_EQ(r.exit_code, 0) << r.err;
            painted.push_back(frame_name(dir_, (s.name + "_").c_str(), frame, "exr"));
        }
        const SkyGamut gamut = sky_gamut(scene);
        for (const fs::path& p : painted) {
            SCOPED_TRACE(p.filename().string());
            const Frame f = read_exr(p);
            ASSERT_EQ(f.width, kWidth);
            const std::vector<uint8_t> sky = sky_region(camera, f);
            const size_t seen = std::count(sky.begin(), sky.end(), uint8_t{1});
            if (seen == 0) continue;
            ++skies;
            EXPECT_EQ(pixels_outside(f, sky, gamut, kMargin), 0u)
                << "of " << seen << " open-sky pixels lie outside the palette's colours";
        }
    }
    EXPECT_GE(skies, 8);
}

}  // namespace
}  // namespace pleinair
