// The crowns' and the palette's measures of a painted frame (pipeline/bench/crown_look.h,
// palette_look.h) and the masks they share (masks.h): on shapes and colours made to have a known
// answer, and a painted scene's bark found only where its trees are.
#include <gtest/gtest.h>

#include <cmath>

#include "pipeline/bench/crown_look.h"
#include "pipeline/bench/look_measures.h"
#include "pipeline/bench/palette_look.h"
#include "pipeline/frame/paint_frame.h"
#include "pipeline/shot/shot.h"
#include "test_util.h"

namespace pleinair {
namespace {

Mask disc(int w, int h, double cx, double cy, double r) {
    Mask m(static_cast<size_t>(w) * h, 0);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            m[static_cast<size_t>(y) * w + x] = std::hypot(x + 0.5 - cx, y + 0.5 - cy) <= r ? 1 : 0;
    return m;
}

size_t count(const Mask& m) {
    size_t n = 0;
    for (uint8_t v : m) n += v != 0;
    return n;
}

TEST(Masks, ADiscsEdgeIsFourAndAHalfRootsOfItsArea) {
    const int w = 200, h = 200;
    const Mask d = disc(w, h, 100, 100, 60);
    const double ratio = double(boundary_length(d, w, h)) / std::sqrt(double(count(d)));
    EXPECT_NEAR(ratio, 8.0 / std::sqrt(M_PI), 0.05);
    // The frame's edge is not an edge: the whole frame has none, a half disc cut by it less.
    EXPECT_EQ(boundary_length(Mask(size_t(w) * h, 1), w, h), 0u);
    const Mask half = disc(w, h, 100, 0, 60);
    EXPECT_NEAR(double(boundary_length(half, w, h)), 0.5 * boundary_length(d, w, h), 4.0);
}

TEST(Masks, AnOutlineFillsWhatItEnclosesAndClosesNarrowGaps) {
    const int w = 64, h = 64;
    Mask ring = disc(w, h, 32, 32, 20);
    const Mask hole = disc(w, h, 32, 32, 8);
    for (size_t i = 0; i < ring.size(); ++i) ring[i] &= !hole[i];
    EXPECT_EQ(outline(ring, w, h, 0), disc(w, h, 32, 32, 20));
    // A slit two pixels wide from the hole to the outside: open at r 0, closed at r 2.
    Mask slit = ring;
    for (int y = 0; y < 32; ++y) slit[size_t(y) * w + 32] = slit[size_t(y) * w + 33] = 0;
    EXPECT_LT(count(outline(slit, w, h, 0)), count(ring));
    EXPECT_EQ(count(outline(slit, w, h, 2)), count(disc(w, h, 32, 32, 20)));
}

TEST(Crowns, SkyBarkAndEdgeInsideEachTreesOutline) {
    const int w = 240, h = 120;
    TreePixels t{std::vector<uint32_t>(size_t(w) * h, 0), Mask(size_t(w) * h, 0)};
    Mask sky(size_t(w) * h, 0);
    // Tree 3: a disc with a regular lattice of one-pixel holes that show the sky, and a trunk
    // of bark up its middle. Tree 5: a smooth disc. Tree 7: too small to measure.
    const Mask a = disc(w, h, 60, 60, 40), b = disc(w, h, 170, 60, 40), c = disc(w, h, 230, 10, 3);
    size_t holes = 0, bark = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const size_t i = size_t(y) * w + x;
            sky[i] = !a[i] && !b[i] && !c[i];
            if (a[i]) {
                const bool open = x % 4 == 0 && y % 4 == 0 && std::hypot(x - 60, y - 60) < 35;
                t.tree[i] = open ? 0 : 3, sky[i] = open, holes += open;
                const bool trunk = !open && x >= 58 && x < 62;
                t.bark[i] = trunk, bark += trunk;
            }
            if (b[i]) t.tree[i] = 5;
            if (c[i]) t.tree[i] = 7;
        }
    const std::vector<CrownLook> crowns = measure_crowns(t, sky, w, h, 200);
    ASSERT_EQ(crowns.size(), 2u);
    const double area = double(count(a));
    EXPECT_NEAR(crowns[0].sky, holes / area, 0.02 * holes / area);
    EXPECT_NEAR(crowns[0].bark, bark / area, 0.02 * bark / area);
    EXPECT_EQ(crowns[0].pixels, count(a) - holes);
    EXPECT_EQ(crowns[1].sky, 0.0);
    EXPECT_EQ(crowns[1].bark, 0.0);
    EXPECT_NEAR(crowns[1].edge, 8.0 / std::sqrt(M_PI), 0.1);
    // A crown whose rim breaks into touches: the edge grows, its outline's area barely.
    TreePixels broken = t;
    for (int y = 0; y < h; ++y)
        for (int x = 110; x < w; ++x) {
            const size_t i = size_t(y) * w + x;
            if (b[i] && std::hypot(x - 170, y - 60) > 32 && (x / 3 + y / 3) % 2) broken.tree[i] = 0;
        }
    const std::vector<CrownLook> after = measure_crowns(broken, sky, w, h, 200);
    EXPECT_GT(after[1].edge, 2.0 * crowns[1].edge);
    const CrownLook m = median_crown(crowns);
    EXPECT_EQ(m.pixels, 2u);
    EXPECT_NEAR(m.sky, 0.5 * crowns[0].sky, 1e-9);
}

TEST(Crowns, BarkShowsOnlyWhereTheScenesTreesArePainted) {
    const auto file =
        test::source_dir() / "tests" / "golden" / "mortefontaine-small" / "scene.json";
    auto paint = [&](const std::vector<std::string>& set) {
        const Shot shot = build_shot(load_scene(file, set));
        const FrameView view = still_view(shot.scene);
        const Frame f = paint_frame(shot, view, scene_frame_settings(shot.scene, true));
        return tree_pixels(shot, view, f);
    };
    const TreePixels with = paint({});
    size_t trees = 0, bark = 0;
    for (size_t i = 0; i < with.tree.size(); ++i) {
        trees += with.tree[i] != 0, bark += with.bark[i] != 0;
        if (with.bark[i]) {
            EXPECT_NE(with.tree[i], 0u) << i;
        }
    }
    EXPECT_GT(bark, 20u);
    EXPECT_LT(bark, trees / 2);
    const TreePixels without = paint({"/families={}", "/trees=[]", "/groups=[]"});
    for (size_t i = 0; i < without.tree.size(); ++i)
        ASSERT_TRUE(without.tree[i] == 0 && !without.bark[i]) << i;
}

TEST(PaletteLook, CielabOfKnownColours) {
    const auto white = linear_srgb_to_lab(1, 1, 1);
    EXPECT_NEAR(white[0], 100.0f, 0.01f);
    EXPECT_NEAR(white[1], 0.0f, 0.01f);
    EXPECT_NEAR(white[2], 0.0f, 0.01f);
    // sRGB red: L* 53.24, a* 80.09, b* 67.20 (the standard's published figures).
    const auto red = linear_srgb_to_lab(1, 0, 0);
    EXPECT_NEAR(red[0], 53.24f, 0.05f);
    EXPECT_NEAR(red[1], 80.09f, 0.1f);
    EXPECT_NEAR(red[2], 67.20f, 0.1f);
    const auto grey = linear_srgb_to_lab(0.18f, 0.18f, 0.18f);
    EXPECT_NEAR(std::hypot(grey[1], grey[2]), 0.0f, 0.01f);
    EXPECT_NEAR(grey[0], 49.5f, 0.1f);
    EXPECT_EQ(linear_srgb_to_lab(0, 0, 0)[0], 0.0f);
}

TEST(PaletteLook, ChromaWarmAccentsAndValuesOfAFrame) {
    Frame f;
    f.width = 100, f.height = 10;
    f.rgba.assign(4 * 1000, 0.0f);
    for (int i = 0; i < 1000; ++i) {
        // Grey at L* 49.5, ten pixels of orange, and a tenth of the frame near black (L* < 20).
        const float v = i < 100 ? 0.01f : 0.18f;
        float* p = &f.rgba[4 * i];
        p[0] = p[1] = p[2] = v, p[3] = 1;
        if (i >= 500 && i < 510) p[0] = 0.9f, p[1] = 0.3f, p[2] = 0.02f;
        if (i >= 600 && i < 700) p[0] = 0.05f, p[1] = 0.1f, p[2] = 0.6f;  // blue: not warm
    }
    const PaletteLook p = palette_look(f);
    EXPECT_NEAR(p.warm, 0.01, 1e-12);
    EXPECT_NEAR(p.lightness[0], 0.1, 1e-12);
    double sum = 0;
    for (double s : p.lightness) sum += s;
    EXPECT_NEAR(sum, 1.0, 1e-12);
    EXPECT_NEAR(p.lightness_median, 49.5, 0.1);
    EXPECT_GT(p.chroma_mean, 5.0);  // a tenth of the frame saturated blue
    EXPECT_GT(p.chroma_p95, 50.0);
    for (float& v : f.rgba) v = 0.5f;
    const PaletteLook grey = palette_look(f);
    EXPECT_LT(grey.chroma_p95, 0.01);
    EXPECT_EQ(grey.warm, 0.0);
}

}  // namespace
}  // namespace pleinair

namespace pleinair {
namespace {

// smooth_share (bench look's foreground): the windows wholly inside the mask whose L* spreads
// less than the limit: the flat half of a made frame, none of its brushed half.
TEST(Look, SmoothShareCountsOnlyPaintWithoutMarks) {
    const int w = 40, h = 20;
    std::vector<float> l(size_t(w) * h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            l[size_t(y) * w + x] = x < 20 ? 50.0f : ((x + y) % 2 ? 40.0f : 60.0f);
    const std::vector<uint8_t> all(l.size(), 1);
    // Centres 2..37 across, 2..17 down; those with x <= 17 see only the flat half.
    EXPECT_NEAR(smooth_share(l, w, h, all, 2, 1.0), 16.0 * 16.0 / (36.0 * 16.0), 1e-12);
    EXPECT_EQ(smooth_share(l, w, h, all, 2, 100.0), 1.0);  // everything under a wide limit
    std::vector<uint8_t> brushed(l.size(), 0);
    for (int y = 0; y < h; ++y)
        for (int x = 20; x < w; ++x) brushed[size_t(y) * w + x] = 1;
    EXPECT_EQ(smooth_share(l, w, h, brushed, 2, 1.0), 0.0);
    EXPECT_EQ(smooth_share(l, w, h, std::vector<uint8_t>(l.size(), 0), 2, 1.0), 0.0);
}

}  // namespace
}  // namespace pleinair

namespace pleinair {
namespace {

// The open sky's palette check (OneFrame.TheOpenSkyKeepsToItsPaletteInEveryShippedScene) guards
// every shipped scene's sky; here it is held to colours with a known answer: a pixel is outside
// when any channel lies beyond the gamut widened by the margin, below or above, and only pixels
// of the mask count.
TEST(OpenSky, PixelsOutsideThePaletteAreCountedChannelByChannel) {
    SceneDesc scene;
    scene.background.sky_zenith = Color(0.40f, 0.50f, 0.60f);
    scene.background.sky_horizon = Color(0.70f, 0.80f, 0.90f);
    scene.sky.present = false;
    const SkyGamut g = sky_gamut(scene);
    for (int c = 0; c < 3; ++c) {
        EXPECT_FLOAT_EQ(g.lo[c], 0.40f + 0.1f * c);
        EXPECT_FLOAT_EQ(g.hi[c], 0.70f + 0.1f * c);
    }
    // sRGB colours, one a pixel, written as the painter does (linear, premultiplied, opaque).
    const std::vector<Color> srgb = {
        {0.55f, 0.65f, 0.75f},  // inside
        {0.00f, 0.00f, 0.00f},  // black: below in every channel
        {0.55f, 0.65f, 0.96f},  // above in blue alone, by 0.06
        {0.55f, 0.43f, 0.75f},  // below in green alone, by 0.07
        {0.39f, 0.81f, 0.91f},  // within a margin of 0.02 in every channel
        {0.00f, 0.00f, 0.00f},  // black, but not in the mask
    };
    Frame f;
    f.width = static_cast<int>(srgb.size()), f.height = 1;
    for (const Color& c : srgb) {
        const Color lin = srgb_to_linear(c);
        f.rgba.insert(f.rgba.end(), {lin.x, lin.y, lin.z, 1.0f});
    }
    const std::vector<uint8_t> mask = {1, 1, 1, 1, 1, 0};
    EXPECT_EQ(pixels_outside(f, mask, g, 0.02f), 3u);
    EXPECT_EQ(pixels_outside(f, mask, g, 0.065f), 2u);  // the blue one is inside now
    EXPECT_EQ(pixels_outside(f, mask, g, 0.5f), 1u);    // black lies 0.6 below the least blue
    EXPECT_EQ(pixels_outside(f, mask, g, 0.0f), 4u);
    EXPECT_EQ(pixels_outside(f, std::vector<uint8_t>(srgb.size(), 0), g, 0.0f), 0u);
}

}  // namespace
}  // namespace pleinair
