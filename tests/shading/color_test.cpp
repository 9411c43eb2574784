// sRGB transfer, colour splines, the three-spline palette and the atmosphere's colour edits.
#include "shading/color.h"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

namespace pleinair {
namespace {

void expect_color(Color a, Color b, float tol = 1e-5f) {
    EXPECT_NEAR(a.x, b.x, tol);
    EXPECT_NEAR(a.y, b.y, tol);
    EXPECT_NEAR(a.z, b.z, tol);
}

TEST(Color, SrgbTransferValuesAndRoundTrip) {
    EXPECT_NEAR(srgb_to_linear(0.5f), 0.214041f, 1e-5f);
    EXPECT_NEAR(linear_to_srgb(0.214041f), 0.5f, 1e-5f);
    EXPECT_NEAR(srgb_to_linear(0.04f), 0.04f / 12.92f, 1e-7f);
    for (int i = 0; i <= 255; ++i) {
        float c = i / 255.0f;
        EXPECT_NEAR(linear_to_srgb(srgb_to_linear(c)), c, 2e-6f);
    }
    EXPECT_EQ(srgb_to_linear(-1.0f), 0.0f);
    EXPECT_EQ(linear_to_srgb(std::numeric_limits<float>::quiet_NaN()), 0.0f);
}

TEST(Color, LinearSplineInterpolatesEvenlySpacedColours) {
    ColorSpline s{{Color(0, 0, 0), Color(1, 0, 0), Color(1, 1, 0)}, SplineBasis::kLinear};
    expect_color(eval(s, 0.0f), Color(0, 0, 0));
    expect_color(eval(s, 0.25f), Color(0.5f, 0, 0));
    expect_color(eval(s, 0.5f), Color(1, 0, 0));
    expect_color(eval(s, 0.75f), Color(1, 0.5f, 0));
    expect_color(eval(s, 1.0f), Color(1, 1, 0));
    expect_color(eval(s, 7.0f), Color(1, 1, 0));  // clamped
    ColorSpline one{{Color(0.2f, 0.3f, 0.4f)}};
    for (float x : {0.0f, 0.5f, 1.0f}) expect_color(eval(one, x), Color(0.2f, 0.3f, 0.4f));
}

TEST(Color, CatmullRomPassesThroughItsColoursAndStaysInRange) {
    ColorSpline s{{Color(0.1f), Color(0.9f), Color(0.0f), Color(1.0f)}, SplineBasis::kCatmullRom};
    for (int i = 0; i < 4; ++i) expect_color(eval(s, i / 3.0f), s.colors[i], 1e-5f);
    for (int i = 0; i <= 300; ++i) {
        Color c = eval(s, i / 300.0f);
        EXPECT_GE(c.x, 0.0f);
        EXPECT_LE(c.x, 1.0f);
    }
    // Differs from linear between the points.
    ColorSpline lin = s;
    lin.basis = SplineBasis::kLinear;
    EXPECT_GT(std::abs(eval(s, 0.15f).x - eval(lin, 0.15f).x), 0.01f);
}

Palette test_palette() {
    Palette p;
    p.dark = {{Color(0.0f, 0.0f, 0.1f), Color(0.1f, 0.0f, 0.1f)}};
    p.mid = {{Color(0.2f, 0.3f, 0.2f), Color(0.4f, 0.5f, 0.4f)}};
    p.light = {{Color(0.6f, 0.6f, 0.5f), Color(0.9f, 0.9f, 0.8f)}};
    return p;
}

TEST(Palette, EachRangeUsesItsSplineAndBandsMix) {
    Palette p = test_palette();
    // Below dark_cutoff_start (0.3): dark spline over 0..dark_cutoff_end (0.4).
    expect_color(palette_lookup(p, 0.2f), eval(p.dark, 0.2f / 0.4f));
    // Between dark_cutoff_end and mid_cutoff_start: mid spline over 0.3..0.68.
    expect_color(palette_lookup(p, 0.5f), eval(p.mid, (0.5f - 0.3f) / 0.38f));
    // Above mid_cutoff_end: light spline over 0.6..1.
    expect_color(palette_lookup(p, 0.9f), eval(p.light, (0.9f - 0.6f) / 0.4f));
    // Inside the dark band, halfway: the average of both splines.
    Color both = 0.5f * (eval(p.dark, 0.35f / 0.4f) + eval(p.mid, 0.05f / 0.38f));
    expect_color(palette_lookup(p, 0.35f), both);
}

TEST(Palette, IsContinuousInLightness) {
    Palette p = test_palette();
    Color prev = palette_lookup(p, 0.0f);
    for (int i = 1; i <= 10000; ++i) {
        Color c = palette_lookup(p, i / 10000.0f);
        ASSERT_LT(glm::length(c - prev), 0.01f) << i;
        prev = c;
    }
}

TEST(Palette, EqualCutoffsAndOneColourAreSafe) {
    Palette p = test_palette();
    p.dark_cutoff_start = p.dark_cutoff_end = p.mid_cutoff_start = p.mid_cutoff_end = 0.5f;
    for (int i = 0; i <= 100; ++i) {
        Color c = palette_lookup(p, i / 100.0f);
        ASSERT_TRUE(std::isfinite(c.x) && std::isfinite(c.y) && std::isfinite(c.z));
    }
    expect_color(palette_lookup(p, 0.49f), eval(p.dark, 0.49f / 0.5f));
    expect_color(palette_lookup(p, 0.51f), eval(p.light, 0.01f / 0.5f));
    Palette one;
    one.dark = one.mid = one.light = {{Color(0.3f, 0.4f, 0.2f)}};
    for (float l : {0.0f, 0.35f, 0.64f, 1.0f})
        expect_color(palette_lookup(one, l), Color(0.3f, 0.4f, 0.2f));
}

TEST(Color, SaturationLimitKeepsHueOrderAndValue) {
    Color c(0.8f, 0.4f, 0.2f);  // saturation 0.75
    Color d = limit_saturation(c, 0.25f);
    float hi = std::max({d.x, d.y, d.z}), lo = std::min({d.x, d.y, d.z});
    EXPECT_NEAR((hi - lo) / hi, 0.25f, 1e-5f);
    EXPECT_NEAR(hi, 0.8f, 1e-6f);
    EXPECT_GT(d.x, d.y);
    EXPECT_GT(d.y, d.z);
    expect_color(limit_saturation(c, 0.9f), c);
    expect_color(limit_saturation(c, 0.0f), Color(0.8f));
    expect_color(limit_saturation(Color(0.0f), 0.0f), Color(0.0f));
}

TEST(Color, ValueClampScalesIntoRange) {
    Color c(0.1f, 0.05f, 0.02f);
    Color up = clamp_value(c, 0.3f, 0.9f);
    EXPECT_NEAR(std::max({up.x, up.y, up.z}), 0.3f, 1e-6f);
    EXPECT_NEAR(up.y / up.x, 0.5f, 1e-5f);
    Color down = clamp_value(Color(1.0f, 0.5f, 0.5f), 0.0f, 0.6f);
    EXPECT_NEAR(down.x, 0.6f, 1e-6f);
    expect_color(clamp_value(Color(0.0f), 0.2f, 0.8f), Color(0.2f));
    expect_color(clamp_value(Color(0.5f, 0.4f, 0.3f), 0.0f, 1.0f), Color(0.5f, 0.4f, 0.3f));
}

}  // namespace
}  // namespace pleinair
