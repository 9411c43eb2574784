// Paint that mixes like paint (shading/pigment.h): yellow over blue is green, a colour over
// itself stays itself, mixtures stay in the gamut and finite; and the canvas weave's bounds.
#include "shading/pigment.h"

#include <gtest/gtest.h>

#include <cmath>

#include "shading/canvas.h"

namespace pleinair {
namespace {

// Hue in degrees (0 red, 120 green, 240 blue) and saturation (max - min) of an sRGB colour.
void hue_sat(Color c, float& hue, float& sat) {
    const float mx = std::max({c.x, c.y, c.z}), mn = std::min({c.x, c.y, c.z});
    sat = mx - mn;
    float h = 0;
    if (sat > 0) {
        if (mx == c.x)
            h = 60.0f * std::fmod((c.y - c.z) / sat, 6.0f);
        else if (mx == c.y)
            h = 60.0f * ((c.z - c.x) / sat + 2.0f);
        else
            h = 60.0f * ((c.x - c.y) / sat + 4.0f);
    }
    hue = h < 0 ? h + 360.0f : h;
}

TEST(PigmentMixing, YellowOverBlueIsGreenNotGrey) {
    const PigmentTable& t = PigmentTable::shared();
    const Color yellow = srgb_to_linear(Color(0.95f, 0.85f, 0.1f));
    for (const Color blue_srgb :
         {Color(0.1f, 0.2f, 0.7f), Color(0.05f, 0.35f, 0.75f), Color(0.2f, 0.3f, 0.6f)}) {
        const Color blue = srgb_to_linear(blue_srgb);
        for (float a : {0.4f, 0.5f, 0.6f}) {
            float hp, sp, hl, sl;
            hue_sat(linear_to_srgb(pigment_over(t, yellow, blue, a)), hp, sp);
            hue_sat(linear_to_srgb(mix(blue, yellow, a)), hl, sl);
            EXPECT_GT(hp, 80.0f) << a;  // green: from yellow-green to blue-green
            EXPECT_LT(hp, 195.0f) << a;
            EXPECT_GT(sp, 0.1f) << a;  // a colour, not a grey
            // Alpha blending in linear RGB is a warm grey there, far from green.
            EXPECT_TRUE(hl < 60.0f || hl > 200.0f || sl < 0.1f) << hl << " " << sl;
        }
    }
}

TEST(PigmentMixing, TheFourPigmentsAreWhiteYellowBlueMagenta) {
    auto masstone = [](int p) {
        std::array<float, 4> c{};
        c[p] = 1;
        return linear_to_srgb(pigment_mix_rgb(c));
    };
    EXPECT_GT(std::min({masstone(0).x, masstone(0).y, masstone(0).z}), 0.9f);
    float h, s;
    hue_sat(masstone(1), h, s);
    EXPECT_NEAR(h, 55.0f, 15.0f);
    hue_sat(masstone(2), h, s);
    EXPECT_NEAR(h, 195.0f, 20.0f);
    hue_sat(masstone(3), h, s);
    EXPECT_GT(h, 300.0f);
    // Equal parts of yellow and blue pigment: green, darker than either's lightest channel.
    hue_sat(linear_to_srgb(pigment_mix_rgb({0, 0.5f, 0.5f, 0})), h, s);
    EXPECT_GT(h, 90.0f);
    EXPECT_LT(h, 170.0f);
}

TEST(PigmentMixing, AColourOverItselfStaysItself) {
    const PigmentTable& t = PigmentTable::shared();
    uint32_t s = 7;
    auto rnd = [&] { return (s = s * 1664525u + 1013904223u) >> 8 & 0xffffff; };
    float worst = 0;
    for (int i = 0; i < 5000; ++i) {
        const Color c(rnd() / 16777216.0f, rnd() / 16777216.0f, rnd() / 16777216.0f);
        const float a = rnd() / 16777216.0f;
        const Color m = pigment_over(t, c, c, a);
        for (int k = 0; k < 3; ++k) worst = std::max(worst, std::abs(m[k] - c[k]));
    }
    EXPECT_LT(worst, 2e-6f);  // float rounding only
    // Opaque paint covers: a over b at 1 is a.
    const Color a = srgb_to_linear(Color(0.8f, 0.3f, 0.2f)),
                b = srgb_to_linear(Color(0.1f, 0.5f, 0.9f));
    const Color m = pigment_over(t, a, b, 1.0f);
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(m[k], a[k], 2e-6f);
}

TEST(PigmentMixing, MixturesStayInTheGamutAndFinite) {
    const PigmentTable& t = PigmentTable::shared();
    uint32_t s = 11;
    auto rnd = [&] { return ((s = s * 1664525u + 1013904223u) >> 8 & 0xffffff) / 16777216.0f; };
    for (int i = 0; i < 5000; ++i) {
        const Color a(rnd(), rnd(), rnd()), b(rnd(), rnd(), rnd());
        const Color m = pigment_over(t, a, b, rnd());
        for (int k = 0; k < 3; ++k) {
            ASSERT_TRUE(std::isfinite(m[k]));
            ASSERT_GE(m[k], 0.0f);
            ASSERT_LE(m[k], 1.0f);
        }
    }
    // What no stroke should carry, but a bad input could: still finite, still in the gamut.
    const float inf = std::numeric_limits<float>::infinity(), nan = std::nanf("");
    for (const Color c :
         {Color(nan, 0.5f, 0.5f), Color(inf, -inf, 2.0f), Color(-1.0f), Color(1e30f, 0.0f, 0.0f)}) {
        const PigmentLatent z = t.encode(c);
        const Color d = t.decode(z);
        for (int k = 0; k < 3; ++k) {
            EXPECT_TRUE(std::isfinite(d[k]));
            EXPECT_GE(d[k], 0.0f);
            EXPECT_LE(d[k], 1.0f);
        }
        for (float v : z.c) EXPECT_TRUE(std::isfinite(v) && v >= 0.0f && v <= 1.0001f);
    }
}

// The tile repeats without a seam only if it holds whole periods of the weave (two threads):
// a tile of 256 pixels with threads of exactly the width asked for cuts a thread at every
// 256th column of a frame wider than that (5ff87d5's review fixed it; this holds the fix).
TEST(Canvas, TheTileHoldsWholePeriodsOfTheWeave) {
    for (float px : {3.0f, 4.7f, 6.0f, 7.5f, 11.3f, 19.0f, 64.0f}) {
        SCOPED_TRACE(px);
        const CanvasWeave w = make_canvas_weave(px);
        const double periods = w.side / (2.0 * w.thread);
        EXPECT_NEAR(periods, std::round(periods), 1e-4) << "a thread cut at the tile's edge";
        EXPECT_GE(periods, 1.0);
        EXPECT_NEAR(w.thread, px, 0.02 * px + 0.5 / periods) << "the threads keep their width";
    }
}

TEST(Canvas, WeaveAndEdgesStayInRange) {
    for (float px : {1.0f, 3.0f, 7.5f, 64.0f}) {  // 1: held to 3
        const CanvasWeave w = make_canvas_weave(px);
        float lo = 1, hi = 0;
        for (float h : w.height) {
            ASSERT_TRUE(std::isfinite(h));
            lo = std::min(lo, h), hi = std::max(hi, h);
        }
        EXPECT_GE(lo, 0.0f);
        EXPECT_LE(hi, 1.0f);
        EXPECT_GT(hi - lo, 0.5f) << px;  // threads and the gaps between them
    }
    for (float h : {0.0f, 0.5f, 1.0f})
        for (float s : {0.0f, 0.5f, 1.0f}) {
            EXPECT_EQ(canvas_edge(0.0f, h, s), 0.0f);  // nothing painted stays unpainted
            EXPECT_EQ(canvas_edge(1.0f, h, s), 1.0f);  // full paint stays full
            const float e = canvas_edge(0.5f, h, s);
            EXPECT_GE(e, 0.0f);
            EXPECT_LE(e, 1.0f);
        }
    EXPECT_GT(canvas_edge(0.5f, 1.0f, 0.5f), 0.5f);  // a crown catches paint
    EXPECT_LT(canvas_edge(0.5f, 0.0f, 0.5f), 0.5f);  // a gap misses it
}

}  // namespace
}  // namespace pleinair
