// The plan's measures (pipeline/bench/mass_look.h) on images whose answer is known: a tiled
// motif repeats and a 1/f texture does not; three flat masses are three values, a gradient one;
// crisp touches have crisp edges and blurred ones blurred edges (pipeline/bench/edge_look.h); a
// field of horizontal touches runs horizontal, round spots no way (pipeline/bench/grain_look.h);
// a trunk in a pool of shade stands, one on bare ground floats (pipeline/bench/contact_look.h).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "pipeline/bench/contact_look.h"
#include "pipeline/bench/edge_look.h"
#include "pipeline/bench/grain_look.h"
#include "pipeline/bench/mass_look.h"

namespace pleinair {
namespace {

constexpr int kW = 960, kH = 540;

// Bilinear value noise with cells of `cell` px: smooth, its energy at one scale.
std::vector<float> value_noise(int cell, uint32_t seed) {
    const int gw = kW / cell + 2, gh = kH / cell + 2;
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    std::vector<float> g(static_cast<size_t>(gw) * gh);
    for (float& v : g) v = u(rng);
    std::vector<float> out(static_cast<size_t>(kW) * kH);
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
            const float fx = float(x) / cell, fy = float(y) / cell;
            const int ix = int(fx), iy = int(fy);
            const float tx = fx - ix, ty = fy - iy;
            auto at = [&](int a, int b) { return g[static_cast<size_t>(b) * gw + a]; };
            const float top = at(ix, iy) * (1 - tx) + at(ix + 1, iy) * tx;
            const float bot = at(ix, iy + 1) * (1 - tx) + at(ix + 1, iy + 1) * tx;
            out[static_cast<size_t>(y) * kW + x] = top * (1 - ty) + bot * ty;
        }
    return out;
}

// 1/f texture (an amplitude spectrum falling as 1/f, as natural images' does): in two
// dimensions that is the same energy in every octave, here octaves from 2 to 256 px.
std::vector<float> pink_texture(uint32_t seed) {
    std::vector<float> l(static_cast<size_t>(kW) * kH, 60.0f);
    for (int cell = 2; cell <= 256; cell *= 2) {
        const std::vector<float> n = value_noise(cell, seed + cell);
        for (size_t i = 0; i < l.size(); ++i) l[i] += 6.0f * n[i];
    }
    return l;
}

// A 48 x 36 px motif of random greys, tiled over the frame.
std::vector<float> tiled(uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(40.0f, 90.0f);
    std::vector<float> tile(48 * 36);
    for (float& v : tile) v = u(rng);
    const std::vector<float> soft = value_noise(12, seed);
    std::vector<float> l(static_cast<size_t>(kW) * kH);
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x)
            l[static_cast<size_t>(y) * kW + x] =
                tile[(y % 36) * 48 + x % 48] * 0.3f + 40.0f * (1.0f + soft[(y % 36) * kW + x % 48]);
    return l;
}

const std::vector<uint8_t> kAll(static_cast<size_t>(kW) * kH, 1);

TEST(MassLook, ATiledMotifRepeats) {
    for (uint32_t seed : {1u, 2u}) {
        const RepeatLook r = texture_repeat(tiled(seed), kW, kH, kAll);
        EXPECT_GT(r.score, 0.9) << seed;
        // One tile away (the frame is reduced by 4, so within a reduced pixel of it).
        EXPECT_TRUE(std::abs(std::abs(r.dx) % 48) <= 4 || std::abs(std::abs(r.dx) % 48) >= 44)
            << r.dx;
        EXPECT_TRUE(std::abs(r.dy) % 36 <= 4 || std::abs(r.dy) % 36 >= 32) << r.dy;
    }
}

TEST(MassLook, APinkTextureDoesNotRepeat) {
    for (uint32_t seed : {1u, 2u, 3u}) {
        const RepeatLook r = texture_repeat(pink_texture(seed), kW, kH, kAll);
        EXPECT_LT(r.score, 0.15) << seed;
        EXPECT_GT(r.pixels, 30000u);
    }
}

TEST(MassLook, OnlyTheMaskIsMeasured) {
    // The top half tiled, the bottom half 1/f: the mask picks which one is measured.
    const std::vector<float> t = tiled(5), p = pink_texture(5);
    std::vector<float> l(t.size());
    std::vector<uint8_t> top(t.size(), 0), bottom(t.size(), 0);
    for (size_t i = 0; i < l.size(); ++i) {
        const bool upper = i < l.size() / 2;
        l[i] = upper ? t[i] : p[i];
        (upper ? top : bottom)[i] = 1;
    }
    EXPECT_GT(texture_repeat(l, kW, kH, top).score, 0.9);
    EXPECT_LT(texture_repeat(l, kW, kH, bottom).score, 0.2);
    // Too little of a region to say anything: no score.
    std::vector<uint8_t> speck(t.size(), 0);
    for (int y = 0; y < 20; ++y)
        for (int x = 0; x < 20; ++x) speck[static_cast<size_t>(y) * kW + x] = 1;
    EXPECT_EQ(texture_repeat(l, kW, kH, speck).score, 0.0);
}

// Three horizontal bands of flat L* plus a little brush noise (the strokes inside a mass).
std::vector<float> bands(const std::vector<float>& values, float noise) {
    std::vector<float> l(static_cast<size_t>(kW) * kH);
    const std::vector<float> n = value_noise(4, 9);
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
            const size_t i = static_cast<size_t>(y) * kW + x;
            l[i] = values[static_cast<size_t>(y) * values.size() / kH] + noise * n[i];
        }
    return l;
}

TEST(MassLook, FlatMassesAreTheirValues) {
    const ValueMasses three = value_masses(bands({30, 55, 80}, 4), kW, kH);
    ASSERT_EQ(three.values, 3);
    EXPECT_NEAR(three.modes[0], 30, 2);
    EXPECT_NEAR(three.modes[1], 55, 2);
    EXPECT_NEAR(three.modes[2], 80, 2);
    for (double s : three.shares) EXPECT_NEAR(s, 1.0 / 3, 0.05);
    EXPECT_EQ(value_masses(bands({40, 75}, 4), kW, kH).values, 2);
    EXPECT_EQ(value_masses(bands({20, 40, 60, 80, 95}, 3), kW, kH).values, 5);
}

TEST(MassLook, AGradientOrMushIsOneValue) {
    std::vector<float> ramp(static_cast<size_t>(kW) * kH);
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) ramp[static_cast<size_t>(y) * kW + x] = 20.0f + 70.0f * x / kW;
    EXPECT_EQ(value_masses(ramp, kW, kH).values, 1);
    // 1/f paint, its values running into one another: no decided value.
    EXPECT_LE(value_masses(pink_texture(4), kW, kH).values, 1);
}

TEST(MassLook, BlurKeepsTheMeanAndFlattensDetail) {
    // Detail 4 px across blurred by a box of 33 px: little is left of it.
    std::vector<float> p = value_noise(4, 7);
    for (float& v : p) v = 50.0f + 20.0f * v;
    const std::vector<float> b = blur_box3(p, kW, kH, 16);
    double mp = 0, mb = 0, vp = 0, vb = 0;
    for (size_t i = 0; i < p.size(); ++i) mp += p[i], mb += b[i];
    mp /= p.size(), mb /= b.size();
    for (size_t i = 0; i < p.size(); ++i)
        vp += (p[i] - mp) * (p[i] - mp), vb += (b[i] - mb) * (b[i] - mb);
    EXPECT_NEAR(mb, mp, 1.0);
    EXPECT_LT(vb, 0.05 * vp);
}

// Touches: 300 ellipses of random size, angle and L* over a mid ground, each pixel the mean of
// a 4 x 4 grid of samples (the painter's anti-aliasing), so a crisp edge is a pixel or two wide.
// `angle` (degrees, counter-clockwise from horizontal), when given, turns them all one way, and
// `aspect`, when over 0, sets their length over width (1: round spots).
std::vector<float> touches(uint32_t seed, float angle = NAN, float aspect = 0) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    struct Touch {
        float x, y, a, b, c, s, l;
    };
    std::vector<Touch> t(300);
    for (Touch& k : t) {
        float ang = 6.2831853f * u(rng);
        // Image rows run down: a turn counter-clockwise on screen is a negative one in rows.
        if (!std::isnan(angle)) ang = -angle * 0.017453292f;
        k = {kW * u(rng),   kH * u(rng),   8 + 30 * u(rng), 5 + 12 * u(rng),
             std::cos(ang), std::sin(ang), 25 + 60 * u(rng)};
        if (aspect > 0) k.b = k.a / aspect;
    }
    // Painted in order into 4 x 4 samples a pixel over each touch's box, then averaged.
    constexpr int kS = 4;
    std::vector<float> fine(static_cast<size_t>(kW) * kH * kS * kS, 50.0f);
    for (const Touch& k : t) {
        const int x0 = std::max(0, static_cast<int>((k.x - k.a) * kS));
        const int x1 = std::min(kW * kS, static_cast<int>((k.x + k.a) * kS) + 1);
        const int y0 = std::max(0, static_cast<int>((k.y - k.a) * kS));
        const int y1 = std::min(kH * kS, static_cast<int>((k.y + k.a) * kS) + 1);
        for (int y = y0; y < y1; ++y)
            for (int x = x0; x < x1; ++x) {
                const float dx = (x + 0.5f) / kS - k.x, dy = (y + 0.5f) / kS - k.y;
                const float along = dx * k.c + dy * k.s, across = -dx * k.s + dy * k.c;
                if (along * along / (k.a * k.a) + across * across / (k.b * k.b) < 1)
                    fine[static_cast<size_t>(y) * kW * kS + x] = k.l;
            }
    }
    std::vector<float> l(static_cast<size_t>(kW) * kH);
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
            float sum = 0;
            for (int j = 0; j < kS; ++j)
                for (int i = 0; i < kS; ++i)
                    sum += fine[static_cast<size_t>(y * kS + j) * kW * kS + x * kS + i];
            l[static_cast<size_t>(y) * kW + x] = sum / (kS * kS);
        }
    return l;
}

TEST(EdgeLook, CrispTouchesHaveCrispEdgesAndBlurredOnesBlurredEdges) {
    const std::vector<float> crisp = touches(5);
    const EdgeLook c = edge_look(crisp, kW, kH, kAll);
    EXPECT_GT(c.edges, 5000u);
    EXPECT_LT(c.blurred_share, 0.1) << c.median_width;
    EXPECT_LT(c.median_width, 2.0);
    // Blurred by three box passes of radius 3 (near a Gaussian of sigma 3.5 px): the edges about
    // 9 px wide (2.56 sigma).
    const EdgeLook b = edge_look(blur_box3(crisp, kW, kH, 3), kW, kH, kAll);
    EXPECT_GT(b.edges, 1000u);
    EXPECT_GT(b.blurred_share, 0.8) << b.median_width;
    EXPECT_GT(b.median_width, 5.0);
    EXPECT_LT(b.median_width, 10.0);
    // A blur of sigma 1 px sits between: wider edges, most still crisp by the gate.
    const EdgeLook m = edge_look(blur_box3(crisp, kW, kH, 1), kW, kH, kAll);
    EXPECT_GT(m.median_width, c.median_width);
    EXPECT_LT(m.median_width, b.median_width);
}

TEST(EdgeLook, SoftVariationIsNoEdgeAndOnlyTheMaskCounts) {
    // A gradient and a 1/f texture of small steps: nothing spans the contrast an edge needs.
    std::vector<float> g(static_cast<size_t>(kW) * kH);
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) g[static_cast<size_t>(y) * kW + x] = 20 + 60.0f * x / kW;
    EXPECT_EQ(edge_look(g, kW, kH, kAll).edges, 0u);
    // The left half crisp, the right blurred: each half measured alone.
    std::vector<float> half = touches(6);
    const std::vector<float> soft = blur_box3(half, kW, kH, 3);
    for (int y = 0; y < kH; ++y)
        for (int x = kW / 2; x < kW; ++x)
            half[static_cast<size_t>(y) * kW + x] = soft[static_cast<size_t>(y) * kW + x];
    std::vector<uint8_t> left(kAll.size(), 0), right(kAll.size(), 0);
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
            const size_t i = static_cast<size_t>(y) * kW + x;
            left[i] = x<kW / 2 - 20, right[i] = x> kW / 2 + 20;
        }
    EXPECT_LT(edge_look(half, kW, kH, left).blurred_share, 0.1);
    EXPECT_GT(edge_look(half, kW, kH, right).blurred_share, 0.8);
}

// Touches laid flat (4:1, horizontal) run horizontal: most of their edges' weight within 30
// degrees of it (measured 0.86) and agreeing (coherence 0.77); round spots' edges run every way,
// a third within 30 degrees (0.33) and no agreement (0.01); upright strokes, as blades of grass
// or leaves that read as rain, almost none (0.04), agreeing on the vertical.
TEST(GrainLook, FlatTouchesRunHorizontalRoundSpotsNoWayUprightOnesVertical) {
    const GrainLook flat = grain_look(touches(7, 0.0f, 4.0f), kW, kH, kAll);
    EXPECT_GT(flat.pixels, 500000u);
    EXPECT_GT(flat.horizontal, 0.75);
    EXPECT_GT(flat.coherence, 0.5);
    EXPECT_NEAR(flat.angle, 0.0, 5.0);
    const GrainLook round = grain_look(touches(7, NAN, 1.0f), kW, kH, kAll);
    EXPECT_NEAR(round.horizontal, 1.0 / 3.0, 0.05);
    EXPECT_LT(round.coherence, 0.1);
    const GrainLook upright = grain_look(touches(7, 90.0f, 4.0f), kW, kH, kAll);
    EXPECT_LT(upright.horizontal, 0.1);
    EXPECT_GT(upright.coherence, 0.5);
    EXPECT_NEAR(std::abs(upright.angle), 90.0, 5.0);
    // Tilted 30 degrees up to the right, it reads as that angle (the sense of the turn).
    const GrainLook tilted = grain_look(touches(7, 30.0f, 4.0f), kW, kH, kAll);
    EXPECT_NEAR(tilted.angle, 30.0, 5.0);
    // A smooth gradient has edges of one way but no touch: all weight on its one direction.
    std::vector<float> g(static_cast<size_t>(kW) * kH);
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) g[static_cast<size_t>(y) * kW + x] = 20 + 60.0f * y / kH;
    EXPECT_GT(grain_look(g, kW, kH, kAll).horizontal, 0.99);
}

// Only the mask is measured: the flat field's left half and the upright field's right half,
// each read on its own.
TEST(GrainLook, OnlyTheMaskCounts) {
    std::vector<float> l = touches(8, 0.0f, 4.0f);
    const std::vector<float> up = touches(9, 90.0f, 4.0f);
    std::vector<uint8_t> left(kAll.size(), 0), right(kAll.size(), 0), none(kAll.size(), 0);
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
            const size_t i = static_cast<size_t>(y) * kW + x;
            if (x >= kW / 2) l[i] = up[i];
            left[i] = x < kW / 2 - 20;
            right[i] = x > kW / 2 + 20;
        }
    EXPECT_GT(grain_look(l, kW, kH, left).horizontal, 0.7);
    EXPECT_LT(grain_look(l, kW, kH, right).horizontal, 0.15);
    const GrainLook empty = grain_look(l, kW, kH, none);
    EXPECT_EQ(empty.pixels, 0u);
    EXPECT_EQ(empty.horizontal, 0.0);
}

// Three trunks on a textured meadow (L* 55 +- 4), 20 px a metre: one standing in a pool of
// shade 2 m to either side (L* 38), one on nothing, one on a light seam. The trunks' own pixels
// (dark, their object id) lie over the foot and do not count as ground; the sky above does not
// either.
TEST(ContactLook, ATrunkInItsShadeStandsOneOnNothingFloats) {
    std::vector<float> l = value_noise(6, 4), id(static_cast<size_t>(kW) * kH, 0.0f);
    std::vector<uint8_t> sky(l.size(), 0);
    for (float& v : l) v = 55.0f + 4.0f * v;
    const float m = 20.0f;
    const std::vector<TreeBase> feet = {{200, 400, m, 1}, {480, 400, m, 2}, {760, 400, m, 3}};
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
            const size_t i = static_cast<size_t>(y) * kW + x;
            sky[i] = y < 300;
            for (const TreeBase& t : feet) {
                const float dx = std::abs(x - t.x), dy = std::abs(y - t.y);
                if (t.object_id == 1 && dx < 2.0f * m && dy < 0.5f * m) l[i] = 38.0f;
                if (t.object_id == 3 && dx < 2.0f * m && dy < 0.5f * m) l[i] = 70.0f;
                if (dx < 0.8f * m && y < t.y + 2) l[i] = 15.0f, id[i] = t.object_id;  // the trunk
            }
        }
    auto one = [&](size_t k) { return contact_look(l, kW, kH, id, sky, {feet[k]}); };
    const ContactLook stands = one(0), floats = one(1), seam = one(2);
    EXPECT_EQ(stands.bases, 1);
    EXPECT_NEAR(stands.median_drop, 17.0, 2.0);
    EXPECT_EQ(stands.standing_share, 1.0);
    EXPECT_NEAR(floats.median_drop, 0.0, 1.5);
    EXPECT_EQ(floats.standing_share, 0.0);
    EXPECT_NEAR(seam.median_drop, -15.0, 2.0);
    const ContactLook all = contact_look(l, kW, kH, id, sky, feet);
    EXPECT_EQ(all.bases, 3);
    EXPECT_NEAR(all.median_drop, floats.median_drop, 1e-9);
    EXPECT_NEAR(all.standing_share, 1.0 / 3.0, 1e-9);
    // A foot off the frame, or with no ground about it (all sky), is not measured.
    std::vector<uint8_t> all_sky(l.size(), 1);
    EXPECT_EQ(contact_look(l, kW, kH, id, all_sky, feet).bases, 0);
    EXPECT_EQ(contact_look(l, kW, kH, id, sky, {{5000, 400, m, 9}}).bases, 0);
}

}  // namespace
}  // namespace pleinair
