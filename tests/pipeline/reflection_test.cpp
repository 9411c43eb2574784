// Still water's mirror (pipeline/frame/reflection.h) and the look's measures (pipeline/bench/look_measures.h): the
// Fresnel curve, the measures on images made to have a known answer, and the small
// Mortefontaine's pond mirroring its far bank only with reflections on.
#include "pipeline/frame/reflection.h"

#include <gtest/gtest.h>

#include <cmath>

#include "pipeline/bench/look_measures.h"
#include "pipeline/frame/paint_frame.h"
#include "pipeline/shot/shot.h"
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

// A known object: a dark post standing on the far bank of the small Mortefontaine's pond, seen
// low across the water. With reflections on, the water right under the post darkens over about
// the post's height, upside down (from the shore downwards); water beside it does not, and
// without reflections nothing does. A mirror showing only the sky passes the correlation test
// above; it fails this.
TEST(Reflection, APostOnTheFarBankStandsUpsideDownInThePond) {
    const auto file =
        test::source_dir() / "tests" / "golden" / "mortefontaine-small" / "scene.json";
    struct Painted {
        Frame f;
        std::vector<float> l;
        std::vector<uint8_t> water;
        float post_id = 0;
    };
    auto paint = [&](int reflection) {
        const Shot shot = build_shot(load_scene(
            file, {"/rocks/0/position=[-6,0,-45]", "/rocks/0/radius=5",
                   "/rocks/0/scale=[0.1,1.2,0.1]", "/families={}", "/trees=[]", "/groups=[]",
                   "/camera/position=[-4,2.5,10]", "/camera/look_at=[-6,0,-60]", "/camera/fov=30",
                   "/water/reflection=" + std::to_string(reflection)}));
        const FrameView view = still_view(shot.scene);
        Painted p;
        p.f = paint_frame(shot, view, scene_frame_settings(shot.scene, true));
        p.l = frame_lightness(p.f);
        p.water = look_regions(shot, view, p.f).water;
        p.post_id = float(0x10000u + shot.scene.rocks[0].material);
        return p;
    };
    const Painted on = paint(1), off = paint(0);
    const int w = on.f.width, h = on.f.height;
    // The post's columns and its top and bottom rows, from its strokes' ids.
    int x0 = w, x1 = -1, top = h, bottom = -1;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            if (on.f.object_id[size_t(y) * w + x] == on.post_id)
                x0 = std::min(x0, x), x1 = std::max(x1, x), top = std::min(top, y),
                bottom = std::max(bottom, y);
    ASSERT_GE(x1, x0) << "the post is in view";
    const int height = bottom - top + 1;
    ASSERT_GE(height, 10);
    ASSERT_LE(x1 - x0, 12) << "a post, not a wall";
    // Mean L* of the water in columns [a, b] over rows [r0, r1].
    auto mean = [&](const Painted& p, int a, int b, int r0, int r1) {
        double sum = 0;
        int n = 0;
        for (int y = std::max(r0, 0); y <= std::min(r1, h - 1); ++y)
            for (int x = std::max(a, 0); x <= std::min(b, w - 1); ++x)
                if (p.water[size_t(y) * w + x]) sum += p.l[size_t(y) * w + x], ++n;
        return n ? sum / n : -1.0;
    };
    // The first half of the mirrored post below the shore, and the same rows beside it.
    const int r0 = bottom + 1, r1 = bottom + height / 2;
    const int beside = x1 + 3 * (x1 - x0 + 1) + 6;
    const double under_on = mean(on, x0, x1, r0, r1), under_off = mean(off, x0, x1, r0, r1);
    const double beside_on = mean(on, beside, beside + (x1 - x0), r0, r1);
    const double beside_off = mean(off, beside, beside + (x1 - x0), r0, r1);
    ASSERT_GT(under_on, 0);
    ASSERT_GT(under_off, 0);
    ASSERT_GT(beside_on, 0);
    ASSERT_GT(beside_off, 0);
    // The mirror lightens the whole pond (it shows the sky); under the post it shows the post.
    const double dark_on = beside_on - under_on, dark_off = beside_off - under_off;
    EXPECT_GT(dark_on, dark_off + 6)
        << "the water under the post, against the water beside it: " << dark_on
        << " L* darker with reflections, " << dark_off << " without";
    // Upside down: the dark reaches down about the post's height, not far past it.
    const double far_on = mean(on, x0, x1, bottom + 2 * height, bottom + 3 * height);
    const double far_beside =
        mean(on, beside, beside + (x1 - x0), bottom + 2 * height, bottom + 3 * height);
    if (far_on > 0 && far_beside > 0) {
        EXPECT_LT(far_beside - far_on, 0.5 * dark_on) << "dark far below the post's reflection";
    }
}

}  // namespace
}  // namespace pleinair
