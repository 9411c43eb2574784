// The painted sky's stage (pipeline/frame/sky_sprites.h): its strokes follow the camera's rotation
// and never its translation, stay on the sky side of the horizon, and are planned only when asked
// for.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <glm/geometric.hpp>

#include "pipeline/bench/look_measures.h"
#include "pipeline/frame/paint_frame.h"
#include "pipeline/frame/sky_sprites.h"
#include "pipeline/input/error.h"
#include "pipeline/output/image_io.h"
#include "pipeline/shot/shot.h"
#include "test_util.h"

namespace pleinair {
namespace {

std::string sky_scene(const std::string& camera, const std::string& sky = R"({"seed": 3})",
                      const std::string& extra = "") {
    return R"({"camera": )" + camera + R"(,
        "sun": {"direction": [-0.5, 0.6, 0.4]},
        "background": {"horizon_softness": 0.01},
        "sky": )" +
           sky + extra + "}";
}

const char* kLevel =
    R"({"position": [0, 2, 0], "look_at": [0, 5, -20], "fov": 50, "width": 160, "height": 90})";

SpriteSet sprites_of(const Shot& shot, const FrameView& view) {
    const FrameSettings fs = scene_frame_settings(shot.scene);
    return sky_sprites(shot, view, plan_frame(shot, fs), fs.render);
}

bool same(const Sprite& a, const Sprite& b) {
    return a.x == b.x && a.y == b.y && a.half_w == b.half_w && a.half_l == b.half_l &&
           a.ax == b.ax && a.ay == b.ay && a.fade == b.fade && a.range == b.range &&
           a.particle == b.particle && a.k.lightness == b.k.lightness &&
           a.k.frequ_s == b.k.frequ_s && a.k.frequ_t == b.k.frequ_t &&
           a.k.offset_s == b.k.offset_s && a.k.offset_t == b.k.offset_t;
}

TEST(SkyStage, StrokesAreUnitDirectionsFromTheHorizonUpAndDeterministic) {
    const Shot shot = build_shot(parse_scene(sky_scene(kLevel), "test"));
    const SkyStrokes& s = shot.sky;
    ASSERT_GT(s.size(), 1000u);
    size_t small = 0;
    for (size_t i = 0; i < s.size(); ++i) {
        EXPECT_NEAR(glm::length(s.direction[i]), 1.0f, 1e-5f);
        EXPECT_GE(s.direction[i].y, -0.031f);
        EXPECT_TRUE(s.label[i] >= 0 && s.label[i] < 1);
        small += s.small[i];
    }
    EXPECT_GT(small, s.size() / 2);  // half-size edge strokes: four to a base stroke's cell
    const SkyStrokes again = build_sky_strokes(shot.scene);
    ASSERT_EQ(again.size(), s.size());
    EXPECT_EQ(
        0, std::memcmp(again.direction.data(), s.direction.data(), s.size() * sizeof(glm::vec3)));
    // Half the stroke size: about four times the strokes.
    const SceneDesc finer = parse_scene(sky_scene(kLevel, R"({"seed": 3, "stroke_size": 4})"), "t");
    const double ratio = double(build_sky_strokes(finer).size()) / double(s.size());
    EXPECT_GT(ratio, 3.5);
    EXPECT_LT(ratio, 4.5);
}

TEST(SkyStage, FollowsTheCamerasRotationNotItsTranslation) {
    const Shot shot = build_shot(parse_scene(sky_scene(kLevel), "test"));
    FrameView here = still_view(shot.scene);
    const SpriteSet a = sprites_of(shot, here);
    ASSERT_GT(a.sprites.size(), 20u);
    // The eye walks 500 m (and 40 km) with the same gaze: the same sprites, bit for bit.
    for (const glm::dvec3 move : {glm::dvec3(120, 30, -480), glm::dvec3(4e4, 0, 0)}) {
        FrameView there = here;
        there.camera.eye += move;
        const SpriteSet b = sprites_of(shot, there);
        ASSERT_EQ(a.sprites.size(), b.sprites.size());
        for (size_t i = 0; i < a.sprites.size(); ++i) EXPECT_TRUE(same(a.sprites[i], b.sprites[i]));
    }
    // The gaze turns 2 degrees left: every stroke near the middle moves right by about the
    // focal length times tan(2 degrees), and none moves vertically by more than a pixel.
    CameraParams turned = shot.scene.camera_params;
    const double t = 2.0 * M_PI / 180.0;
    const glm::dvec3 d = turned.look_at - turned.position;
    turned.look_at = turned.position + glm::dvec3(d.x * std::cos(t) + d.z * std::sin(t), d.y,
                                                  -d.x * std::sin(t) + d.z * std::cos(t));
    FrameView view = here;
    ASSERT_TRUE(make_camera(turned, view.camera).empty());
    const SpriteSet b = sprites_of(shot, view);
    const double expect = here.camera.focal_px * std::tan(t) /
                          std::cos(std::atan2(-d.y, glm::length(glm::dvec2(d.x, d.z))));
    int checked = 0;
    for (const Sprite& sa : a.sprites)
        for (const Sprite& sb : b.sprites)
            if (sa.particle == sb.particle && std::abs(sa.x - 80) < 30 &&
                std::abs(sa.y - 45) < 20) {
                EXPECT_NEAR(sb.x - sa.x, expect, 0.15 * expect);
                EXPECT_NEAR(sb.y, sa.y, 1.0);
                ++checked;
            }
    EXPECT_GT(checked, 3);
}

TEST(SkyStage, NoSpritesWhereTheCameraSeesNoSky) {
    const char* down =
        R"({"position": [0, 50, 0], "look_at": [0, 0, -1], "fov": 30, "width": 64, "height": 64})";
    const Shot shot = build_shot(parse_scene(sky_scene(down), "test"));
    EXPECT_GT(shot.sky.size(), 0u);
    EXPECT_TRUE(sprites_of(shot, still_view(shot.scene)).sprites.empty());
}

TEST(SkyStage, StaysOnTheSkySideOfTheHorizon) {
    // A level camera: the lower half of the frame is the background's ground. The sky paints
    // above the horizon and leaves the ground's pixels exactly as they were.
    const char* cam =
        R"({"position": [0, 2, 0], "look_at": [0, 2, -20], "fov": 50, "width": 160, "height": 90})";
    SceneDesc with = parse_scene(sky_scene(cam), "test");
    SceneDesc without = with;
    without.sky.present = false;
    const Frame a = paint_still(with, false), b = paint_still(without, false);
    int differ_above = 0;
    for (int y = 0; y < 90; ++y)
        for (int x = 0; x < 160; ++x) {
            const size_t p = 4 * (static_cast<size_t>(y) * 160 + x);
            bool differ = false;
            for (int c = 0; c < 4; ++c) {
                ASSERT_TRUE(std::isfinite(a.rgba[p + c]));
                differ |= a.rgba[p + c] != b.rgba[p + c];
            }
            // The horizon is row 45; the background's 4-pixel lattice blends a row either side.
            if (y >= 50) {
                EXPECT_FALSE(differ) << x << ", " << y;
            }
            if (y < 40) differ_above += differ;
        }
    EXPECT_GT(differ_above, 40 * 160 * 9 / 10);
}

TEST(SkyStage, PlannedOnlyWithASkyAndNoCanvas) {
    auto planned = [](const std::string& text) {
        const Shot shot = build_shot(parse_scene(text, "test"));
        const FramePlan plan = plan_frame(shot, scene_frame_settings(shot.scene));
        return plan.sky;
    };
    EXPECT_TRUE(planned(sky_scene(kLevel)));
    EXPECT_FALSE(planned(R"({"camera": )" + std::string(kLevel) + "}"));
    EXPECT_FALSE(planned(R"({"camera": )" + std::string(kLevel) +
                         R"(, "background": {"canvas": true}, "sky": {}})"));
}

TEST(SkyStage, BadKeysNameTheKey) {
    auto error_of = [](const std::string& sky) {
        try {
            parse_scene(sky_scene(kLevel, sky), "scene.json");
        } catch (const InputError& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    EXPECT_NE(error_of(R"({"cloud_cover": 1.5})").find("/sky/cloud_cover"), std::string::npos);
    EXPECT_NE(error_of(R"({"stroke_size": 0})").find("/sky/stroke_size"), std::string::npos);
    EXPECT_NE(error_of(R"({"shader": "no-such-sky"})").find("/sky/shader"), std::string::npos);
    EXPECT_NE(error_of(R"({"palette": "no-such-palette"})").find("/sky/palette"),
              std::string::npos);
    EXPECT_NE(error_of(R"({"clouds": 1})").find("/sky/clouds"), std::string::npos);
}

}  // namespace
}  // namespace pleinair

namespace pleinair {
namespace {

// The look's measures (look_measures.h) on the small Mortefontaine with and without its painted
// sky: the sky carries brush texture at the scale of its strokes, and no bands in 8 bits.
TEST(SkyStage, BrushesTheSkyWithoutBanding) {
    const auto file = PLEINAIR_SOURCE_DIR "/tests/golden/mortefontaine-sky/scene.json";
    auto measure = [&](bool sky, double& run) {
        SceneDesc scene = load_scene(file);
        scene.sky.present = sky;
        const Shot shot = build_shot(scene);
        const FrameView view = still_view(shot.scene);
        const Frame f = paint_frame(shot, view, scene_frame_settings(shot.scene, true));
        const LookRegions r = look_regions(shot, view, f);
        uint64_t n = 0;
        const double t = brush_texture(frame_lightness(f), f.width, f.height, r.sky, 4, &n);
        EXPECT_GT(n, 2000u);
        run = mean_flat_run(f, r.sky);
        return t;
    };
    double run_with = 0, run_without = 0;
    const double with = measure(true, run_with), without = measure(false, run_without);
    EXPECT_GT(with, 3.0 * without) << with << " vs " << without;
    EXPECT_LT(run_with, 3.0);
    EXPECT_GT(run_without, 2.0 * run_with) << run_without << " vs " << run_with;
}

// Sky strokes at least sky_one_sample_px wide take one sample a pixel: none in a small frame
// (the same bytes), many when a narrow lens enlarges them, fewer samples then and a picture within
// half a level (RMS, 8-bit) of every stroke at 4 samples.
TEST(SkyStage, LargeSkyStrokesTakeOneSample) {
    const auto file = PLEINAIR_SOURCE_DIR "/tests/golden/mortefontaine-sky/scene.json";
    auto paint = [&](const std::vector<std::string>& sets, float px, FrameReport& report) {
        SceneDesc scene = load_scene(file, sets);
        scene.render.sky_one_sample_px = px;
        const Shot shot = build_shot(scene);
        return frame_srgb8(
            paint_frame(shot, still_view(shot.scene), scene_frame_settings(shot.scene), &report));
    };
    FrameReport a, b;
    EXPECT_EQ(paint({}, 24, a), paint({}, 0, b));
    EXPECT_EQ(a.fragments, b.fragments);
    const std::vector<std::string> zoom = {"/camera/fov=12", "/camera/width=320",
                                           "/camera/height=180"};
    const auto one = paint(zoom, 24, a), every = paint(zoom, 0, b);
    EXPECT_LT(a.fragments, b.fragments);
    ASSERT_EQ(one.size(), every.size());
    const test::ByteDiff d = test::byte_diff(one, every);
    EXPECT_GT(d.differ, 0u);
    EXPECT_LE(d.rms, 0.5);
}

}  // namespace
}  // namespace pleinair
