// The distance laid in as one value (pipeline/frame/distance_mass.h): a touch's colour goes to
// the distance's luminance keeping its hue, the pull grows smoothly with depth, and a frame's
// far bank, painted with it, reads as one value while its near ground keeps its own.
#include "pipeline/frame/distance_mass.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "pipeline/bench/look_measures.h"
#include "pipeline/frame/paint_frame.h"
#include "pipeline/frame/reflection.h"
#include "pipeline/frame/surface_hit.h"
#include "pipeline/shot/shot.h"
#include "shading/stroke_shader.h"
#include "test_util.h"

namespace pleinair {
namespace {

TEST(DistanceMass, AFarTouchTakesTheDistancesValueKeepingItsHue) {
    EXPECT_NEAR(luminance_of_lstar(100.0f), 1.0f, 1e-6f);
    EXPECT_NEAR(luminance_of_lstar(50.0f), 0.18419f, 1e-4f);
    EXPECT_NEAR(luminance_of_lstar(5.0f), 5.0f / 903.3f, 1e-7f);
    const float key = luminance_of_lstar(58.0f);
    for (const Color c : {Color(0.02f, 0.05f, 0.01f), Color(0.6f, 0.5f, 0.3f),
                          Color(0.2f, 0.25f, 0.4f), Color(0.0f)}) {
        for (float amount : {0.0f, 0.5f, 1.0f}) {
            StrokeConstants k;
            k.key_luminance = key;
            k.key_amount = amount;
            const Color out = finish_color(k, c);
            const float y = luminance(c);
            EXPECT_NEAR(luminance(out), y + (key - y) * amount, 1e-5f) << amount;
            // Its hue kept: the channels keep their ratios (a black becomes a grey).
            if (y > 0.0f) {
                EXPECT_NEAR(out.x * c.y, out.y * c.x, 1e-5f);
                EXPECT_NEAR(out.z * c.y, out.y * c.z, 1e-5f);
            } else if (amount > 0.0f) {
                EXPECT_FLOAT_EQ(out.x, out.y);
            }
            EXPECT_TRUE(std::isfinite(out.x) && std::isfinite(out.y) && std::isfinite(out.z));
        }
    }
}

TEST(DistanceMass, ThePullGrowsSmoothlyFromNearToFar) {
    Atmosphere a;
    a.value_near = 80, a.value_far = 160, a.value_pull = 0.7f;
    EXPECT_EQ(distance_mass_amount(a, 0.0f), 0.0f);
    EXPECT_EQ(distance_mass_amount(a, 80.0f), 0.0f);
    EXPECT_NEAR(distance_mass_amount(a, 120.0f), 0.35f, 1e-6f);
    EXPECT_NEAR(distance_mass_amount(a, 160.0f), 0.7f, 1e-6f);
    EXPECT_NEAR(distance_mass_amount(a, 1e6f), 0.7f, 1e-6f);
    // Continuous: a touch 0.1 m further moves by well under 1% of the pull (no pop as the eye
    // walks), and never back.
    float last = 0.0f;
    for (float d = 0.0f; d < 300.0f; d += 0.1f) {
        const float now = distance_mass_amount(a, d);
        EXPECT_GE(now, last);
        EXPECT_LT(now - last, 0.003f) << d;
        last = now;
    }
    a.value_pull = 0.0f;
    EXPECT_EQ(distance_mass_amount(a, 1e6f), 0.0f);
    StrokeConstants k;
    lay_in_distance_value(a, 1e6f, k);
    EXPECT_EQ(k.key_amount, 0.0f);
}

// The small Mortefontaine painted with its distance laid in (fully, past 60 m): the pixels whose
// front stroke or underpainting lies past 60 m all take L* 58, the sky keeps its own, and the
// near ground (within 40 m) is painted as without it. The mirrored far leaves take it too.
TEST(DistanceMass, TheFarBankSquintedAtIsOneValue) {
    const auto file =
        test::source_dir() / "tests" / "golden" / "mortefontaine-small" / "scene.json";
    struct Painted {
        std::vector<float> l, depth;
        std::vector<uint8_t> sky;
    };
    auto paint = [&](float pull) {
        const Shot shot = build_shot(load_scene(
            file, {"/atmosphere/value=58", "/atmosphere/value_near=40", "/atmosphere/value_far=60",
                   "/atmosphere/value_pull=" + std::to_string(pull)}));
        const FrameView view = still_view(shot.scene);
        const FrameSettings fs = scene_frame_settings(shot.scene, true);
        const Frame f = paint_frame(shot, view, fs);
        const MirrorContext c =
            mirror_context(shot, view, plan_frame(shot, fs), fs.render, shot.sun_rays.get());
        if (pull == 1.0f) {
            EXPECT_NEAR(luminance(mirrored_foliage(c, 1e4f)), luminance_of_lstar(58.0f), 1e-5f);
            // The underpainting's flat colour of a far hit, as it shows between touches.
            const Camera& cam = view.camera;
            int far_hits = 0;
            for (int y = 0; y < cam.height; y += 4) {
                const glm::dvec3 dir = ray_direction(cam, cam.width * 0.5, y + 0.5);
                const RayHit h = shot.view_rays->intersect(cam.eye, glm::vec3(dir));
                if (!h.hit || !(h.t > 100.0f)) continue;
                const glm::dvec3 at = cam.eye + dir * static_cast<double>(h.t);
                EXPECT_NEAR(luminance(surface_hit_color(shot, view, plan_frame(shot, fs), fs.render,
                                                        shot.sun_rays.get(), h, at, h.normal, dir)),
                            luminance_of_lstar(58.0f), 1e-4f);
                ++far_hits;
            }
            EXPECT_GT(far_hits, 0);
        }
        return Painted{frame_lightness(f), f.depth, look_regions(shot, view, f).sky};
    };
    const Painted off = paint(0.0f), on = paint(1.0f);
    auto spread = [](const Painted& p, auto&& keep) {
        std::vector<float> dev;
        for (size_t i = 0; i < p.l.size(); ++i)
            if (!p.sky[i] && keep(p.depth[i])) dev.push_back(std::abs(p.l[i] - 58.0f));
        std::sort(dev.begin(), dev.end());
        return dev;
    };
    auto far = [](float d) { return d > 80.0f && d < 1e6f; };
    const std::vector<float> far_on = spread(on, far), far_off = spread(off, far);
    ASSERT_GT(far_on.size(), 500u);
    // Laid in: the far pixels within a few L* of the value (edges blend with the sky's strokes).
    EXPECT_LT(far_on[far_on.size() / 2], 1.0f);
    EXPECT_LT(far_on[far_on.size() * 9 / 10], 4.0f);
    // Without it, the same far bank spreads over many values.
    EXPECT_GT(far_off[far_off.size() * 9 / 10], 8.0f);
    // The near ground is left as it is.
    double near_moved = 0;
    int near = 0;
    for (size_t i = 0; i < on.l.size(); ++i)
        if (!on.sky[i] && on.depth[i] < 30.0f && off.depth[i] < 30.0f)
            near_moved += std::abs(on.l[i] - off.l[i]), ++near;
    ASSERT_GT(near, 1000);
    EXPECT_LT(near_moved / near, 0.5);
}

}  // namespace
}  // namespace pleinair
