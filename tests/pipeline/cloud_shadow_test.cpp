// The clouds' shadows on the land (shading/cloud_shadow.h): none without cover, a share of the
// land in shade that follows the cover, in patches of about the size asked, finite however far;
// and a frame painted with them darker in patches, its sky untouched.
#include "shading/cloud_shadow.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "pipeline/bench/look_measures.h"
#include "pipeline/frame/paint_frame.h"
#include "pipeline/shot/shot.h"
#include "test_util.h"

namespace pleinair {
namespace {

TEST(CloudShadows, TheShareInShadeFollowsTheCoverInPatchesOfTheirSize) {
    CloudShadowParams p;
    p.size = 50.0f, p.light = 0.2f;
    EXPECT_EQ(cloud_light(p, 12.0, -40.0), 1.0f);  // cover 0: none
    double last_share = 0.0;
    for (float cover : {0.2f, 0.5f, 0.8f}) {
        p.cover = cover;
        int shade = 0, n = 0, changes = 0;
        bool was = false;
        // Along rows 37 m apart over 4 km: the share in shade, and how often a row crosses a
        // shadow's edge.
        for (int row = 0; row < 100; ++row)
            for (int i = 0; i < 1000; ++i) {
                const double x = -2000.0 + 4.0 * i, z = -1850.0 + 37.0 * row;
                const float l = cloud_light(p, x, z);
                ASSERT_GE(l, p.light - 1e-6f);
                ASSERT_LE(l, 1.0f);
                const bool in = l < 0.5f * (1.0f + p.light);
                shade += in, ++n;
                if (i > 0 && in != was) ++changes;
                was = in;
            }
        const double share = double(shade) / n;
        EXPECT_NEAR(share, cover, 0.15) << cover;
        EXPECT_GT(share, last_share);
        last_share = share;
        // Patches of about the size: a row of 4 km crosses an edge every 0.5 to 4 sizes.
        const double per_row = changes / 100.0, sizes = 4000.0 / p.size;
        EXPECT_GT(per_row, sizes / 4.0) << cover;
        EXPECT_LT(per_row, sizes * 2.0) << cover;
    }
    // Another seed, other patches; a far point as finite as a near one.
    CloudShadowParams q = p;
    q.seed = 2;
    int differ = 0;
    for (int i = 0; i < 400; ++i)
        differ += cloud_light(p, 7.0 * i, 3.0) != cloud_light(q, 7.0 * i, 3.0);
    EXPECT_GT(differ, 100);
    for (double far : {1e6, -1e7, 3e8}) {
        const float l = cloud_light(p, far, -far);
        EXPECT_TRUE(std::isfinite(l));
        EXPECT_GE(l, p.light - 1e-6f);
    }
}

// The small forest edge under half-covered clouds: its ground and trees darker in patches (some
// of the frame darker, some as before), its sky as before; and deep shadow everywhere under full
// cover.
TEST(CloudShadows, AFrameTakesTheirPatchesOfShade) {
    const auto file = test::source_dir() / "tests" / "golden" / "forest-edge-small" / "scene.json";
    // The strokes' own lightness (the AOV) over the pixels a stroke fronts, summed; and L*.
    double stroke_l[3] = {0, 0, 0};
    int strokes = 0;
    auto paint = [&](const std::vector<std::string>& set, std::vector<uint8_t>* sky, int k) {
        const Shot shot = build_shot(load_scene(file, set));
        const FrameView view = still_view(shot.scene);
        const Frame f = paint_frame(shot, view, scene_frame_settings(shot.scene, true));
        if (sky) *sky = look_regions(shot, view, f).sky;
        if (k == 0) strokes = 0;
        for (size_t i = 0; i < f.lightness.size(); ++i)
            if (f.object_id[i] != 0) stroke_l[k] += f.lightness[i], strokes += k == 0;
        return frame_lightness(f);
    };
    std::vector<uint8_t> sky;
    const std::vector<float> open = paint({}, &sky, 0);
    const std::vector<float> half = paint(
        {"/sun/clouds/cover=0.5", "/sun/clouds/size=20", "/sun/clouds/light=0.1"}, nullptr, 1);
    const std::vector<float> full =
        paint({"/sun/clouds/cover=1", "/sun/clouds/light=0"}, nullptr, 2);
    // The strokes darken (a stroke in full shade keeps at least half its light: the shadow
    // remap's floor), not only the lay-in between them.
    ASSERT_GT(strokes, 3000);
    EXPECT_LT(stroke_l[2], 0.8 * stroke_l[0]) << stroke_l[2] << " vs " << stroke_l[0];
    EXPECT_LT(stroke_l[1], stroke_l[0] - 0.05 * (stroke_l[0] - stroke_l[2]));
    int land = 0, darker = 0, same = 0, full_darker = 0;
    double sky_moved = 0;
    int sky_n = 0;
    for (size_t i = 0; i < open.size(); ++i) {
        if (sky[i]) {
            sky_moved += std::abs(half[i] - open[i]), ++sky_n;
            continue;
        }
        ++land;
        darker += half[i] < open[i] - 3.0f;
        same += std::abs(half[i] - open[i]) < 1.0f;
        full_darker += full[i] < open[i] - 3.0f;
    }
    ASSERT_GT(land, 5000);
    ASSERT_GT(sky_n, 5000);
    EXPECT_GT(darker, land / 10) << darker << " of " << land;
    EXPECT_GT(same, land / 10) << same << " of " << land;
    EXPECT_GT(full_darker, land * 6 / 10) << full_darker << " of " << land;
    EXPECT_LT(sky_moved / sky_n, 0.5);
}

}  // namespace
}  // namespace pleinair
