// The plan's measures (pipeline/bench/mass_look.h) on images whose answer is known: a tiled
// motif repeats and a 1/f texture does not; three flat masses are three values, a gradient one.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

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

}  // namespace
}  // namespace pleinair
