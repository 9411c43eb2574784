// Still water's mirror (pipeline/reflection.h) and the look's measures (pipeline/look.h): the
// Fresnel curve, the measures on images made to have a known answer, and the small
// Mortefontaine's pond mirroring its far bank only with reflections on.
#include "pipeline/reflection.h"

#include <gtest/gtest.h>

#include <cmath>

#include "pipeline/look.h"
#include "pipeline/paint.h"
#include "pipeline/shot.h"
#include "test_util.h"

namespace pleinair {
namespace {

TEST(Reflection, WaterReflectsLittleLookingDownAndAllAtGrazing) {
    EXPECT_NEAR(water_reflectance(1.0f), 0.02f, 1e-6f);
    EXPECT_NEAR(water_reflectance(0.0f), 1.0f, 1e-6f);
    EXPECT_EQ(water_reflectance(-0.3f), water_reflectance(0.3f));  // either side of the plane
    float last = 2;
    for (float c = 0; c <= 1.0001f; c += 0.05f) {
        const float r = water_reflectance(c);
        EXPECT_LT(r, last);
        last = r;
    }
    EXPECT_TRUE(std::isfinite(water_reflectance(std::nanf(""))));
}

TEST(Look, TextureSeesEdgesInsideTheRegionOnly) {
    const int w = 40, h = 30;
    std::vector<float> flat(w * h, 50.0f), checker(w * h);
    std::vector<uint8_t> all(w * h, 1), left(w * h, 0);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            checker[y * w + x] = ((x / 4 + y / 4) % 2) ? 60.0f : 40.0f;
            left[y * w + x] = x < w / 2;
        }
    EXPECT_EQ(brush_texture(flat, w, h, all, 2), 0.0);
    EXPECT_GT(brush_texture(checker, w, h, all, 2), 5.0);
    // A step at the region's edge is not texture: only whole windows inside count.
    std::vector<float> step(w * h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) step[y * w + x] = x < w / 2 ? 30.0f : 80.0f;
    uint64_t n = 0;
    EXPECT_EQ(brush_texture(step, w, h, left, 2, &n), 0.0);
    EXPECT_EQ(n, uint64_t((w / 2 - 4) * (h - 4)));
    EXPECT_EQ(brush_texture(step, w, h, std::vector<uint8_t>(w * h, 0), 8), 0.0);
}

TEST(Look, MirrorCorrelationOfAMirroredImageIsOne) {
    const int w = 32, h = 40, shore = 20;
    std::vector<float> l(w * h);
    std::vector<uint8_t> water(w * h, 0);
    for (int y = 0; y < shore; ++y)
        for (int x = 0; x < w; ++x) l[y * w + x] = 40.0f + 20.0f * std::sin(0.7f * x + 0.3f * y);
    for (int y = shore; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            l[y * w + x] = 0.5f * l[(2 * shore - 1 - y) * w + x] + 10.0f;  // dimmer, mirrored
            water[y * w + x] = 1;
        }
    uint64_t pairs = 0;
    EXPECT_NEAR(mirror_correlation(l, w, h, water, &pairs), 1.0, 1e-9);
    EXPECT_EQ(pairs, uint64_t(w * (h - shore)));
    for (int y = shore; y < h; ++y)
        for (int x = 0; x < w; ++x) l[y * w + x] = 30.0f + 5.0f * ((x * 7 + y * 13) % 5);
    EXPECT_LT(std::abs(mirror_correlation(l, w, h, water)), 0.2);
}

TEST(Look, FlatRunsAreLongOnAGradientAndShortOnNoise) {
    Frame f;
    f.width = 64, f.height = 4;
    f.rgba.assign(4 * 64 * 4, 1.0f);
    for (int x = 0; x < 64; ++x)
        for (int y = 0; y < 4; ++y)
            for (int c = 0; c < 3; ++c) f.rgba[4 * (y * 64 + x) + c] = 0.5f + 0.001f * x;
    const std::vector<uint8_t> all(64 * 4, 1);
    EXPECT_GT(mean_flat_run(f, all), 4.0);
    for (int i = 0; i < 64 * 4; ++i) f.rgba[4 * i] = (i % 2) ? 0.2f : 0.6f;
    EXPECT_EQ(mean_flat_run(f, all), 1.0);
}

TEST(Reflection, ThePondMirrorsItsFarBankOnlyWithReflections) {
    const auto file =
        test::source_dir() / "tests" / "golden" / "mortefontaine-small" / "scene.json";
    auto measure = [&](const std::vector<std::string>& set, FrameReport* rep) {
        const Shot shot = build_shot(load_scene(file, set));
        const FrameView view = still_view(shot.scene);
        const Frame f = paint_frame(shot, view, scene_frame_settings(shot.scene, true), rep);
        for (float v : f.rgba) EXPECT_TRUE(std::isfinite(v));
        const LookRegions r = look_regions(shot, view, f);
        uint64_t pairs = 0;
        const double c = mirror_correlation(frame_lightness(f), f.width, f.height, r.water, &pairs);
        EXPECT_GT(pairs, 300u);
        return c;
    };
    FrameReport on, off;
    const double with = measure({}, &on), without = measure({"/water/reflection=0"}, &off);
    EXPECT_GT(on.reflection_rays, 0u);
    EXPECT_EQ(off.reflection_rays, 0u);
    EXPECT_GT(with, without + 0.1) << with << " vs " << without;
}

}  // namespace
}  // namespace pleinair
