// The stroke shader's functions value by value: lighting modifiers, shadow remap, frequency,
// edge mask, opacity, distance and the per-fragment colour.
#include "shading/stroke_shader.h"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

namespace pleinair {
namespace {

TEST(StrokeShader, ShadowRemapNeverGoesBelowTheBiasedHalf) {
    EXPECT_FLOAT_EQ(shadow_remap(1.0f, 0.4f), 1.0f);
    EXPECT_NEAR(shadow_remap(0.0f, 0.5f), 0.5f, 1e-6f);  // bias 0.5: plain remap
    EXPECT_NEAR(shadow_remap(0.5f, 0.5f), 0.75f, 1e-6f);
    EXPECT_NEAR(shadow_remap(0.0f, 0.4f), 0.4f, 1e-6f);  // bias(0.5, b) = b: darker shadows
    EXPECT_NEAR(shadow_remap(0.0f, 0.7f), 0.7f, 1e-6f);
    float prev = 0;
    for (int i = 0; i <= 100; ++i) {
        float v = shadow_remap(i / 100.0f, 0.4f);
        EXPECT_GE(v, prev);
        prev = v;
    }
    EXPECT_TRUE(std::isfinite(shadow_remap(std::nanf(""), 0.0f)));
}

TEST(StrokeShader, OuterLeavesAreLighterAndDistanceRemovesInnerDarkening) {
    StrokeShaderParams p;
    float inner = stroke_lightness(p, 0.5f, 0.0f, 0.0f, 0.0f);
    float outer = stroke_lightness(p, 0.5f, 1.0f, 1.0f, 0.0f);
    EXPECT_LT(inner, 0.5f);
    EXPECT_GT(outer, 0.5f);
    // The darkening is 0.45 * 1 * 1 at the very centre.
    EXPECT_NEAR(inner, 0.5f * (1.0f - 0.45f), 1e-6f);
    EXPECT_NEAR(stroke_lightness(p, 0.5f, 0.0f, 0.0f, 1.0f), 0.5f, 1e-6f);
    p.outer_brighten = p.inner_darken = 0;
    EXPECT_NEAR(stroke_lightness(p, 0.3f, 0.8f, 0.1f, 0.0f), 0.3f, 1e-6f);
    EXPECT_EQ(stroke_lightness(p, -0.7f, 0.5f, 0.5f, 0.0f), 0.0f);  // N.L clamped
}

TEST(StrokeShader, FrequencyRisesAwayFromTheCentreAndInTheLight) {
    StrokeShaderParams p;
    EXPECT_FLOAT_EQ(stroke_frequency(p, 0, 0), p.stroke_frequ);
    EXPECT_FLOAT_EQ(stroke_frequency(p, 1, 0), p.stroke_frequ + p.center_frequ_factor);
    EXPECT_FLOAT_EQ(stroke_frequency(p, 0, 1), p.stroke_frequ + p.lightness_frequ_factor);
    EXPECT_GT(stroke_frequency(p, 0.8f, 0.8f), stroke_frequency(p, 0.2f, 0.2f));
}

TEST(StrokeShader, EdgeMaskIsOneInTheMiddleZeroOnTheBorderAndGrowsWithFullness) {
    for (float b : {0.2f, 0.5f, 0.8f}) {
        EXPECT_NEAR(edge_mask(0.5f, 0.5f, b), 1.0f, 1e-6f);
        EXPECT_NEAR(edge_mask(0.0f, 0.5f, b), 0.0f, 1e-6f);
        EXPECT_EQ(edge_mask(0.5f, 1.0f, b), 0.0f);
        EXPECT_EQ(edge_mask(1.0f, 1.0f, b), 0.0f);  // two tiny negative sines must not multiply
    }
    // Fig. 20: higher fullness pushes the mask to the border.
    EXPECT_GT(edge_mask(0.1f, 0.5f, 0.8f), edge_mask(0.1f, 0.5f, 0.5f));
    EXPECT_GT(edge_mask(0.1f, 0.5f, 0.5f), edge_mask(0.1f, 0.5f, 0.2f));
    EXPECT_NEAR(edge_mask(0.25f, 0.5f, 0.5f), std::sin(3.14159265f * 0.25f), 1e-6f);
}

TEST(StrokeShader, OpacityIsThresholdedAndClamped) {
    StrokeShaderParams p;  // feather 0.4..0.6, max 0.9
    EXPECT_EQ(stroke_opacity(p, 0.3f, 1.0f), 0.0f);
    EXPECT_NEAR(stroke_opacity(p, 0.5f, 1.0f), 0.5f, 1e-6f);
    EXPECT_NEAR(stroke_opacity(p, 0.9f, 1.0f), 0.9f, 1e-6f);
    EXPECT_EQ(stroke_opacity(p, 0.9f, 0.0f), 0.0f);
    p.stroke_feather_min = p.stroke_feather_max = 0.5f;  // equal thresholds: a clean step
    EXPECT_EQ(stroke_opacity(p, 0.49f, 1.0f), 0.0f);
    EXPECT_NEAR(stroke_opacity(p, 0.5f, 1.0f), 0.9f, 1e-6f);
}

TEST(StrokeShader, DistanceValueIsCurvedAndSafeWithEqualDistances) {
    EXPECT_EQ(distance_value(5, 10, 100, 0.1f), 0.0f);
    EXPECT_EQ(distance_value(200, 10, 100, 0.1f), 1.0f);
    EXPECT_NEAR(distance_value(55, 10, 100, 0.5f), 0.5f, 1e-6f);
    EXPECT_NEAR(distance_value(55, 10, 100, 0.1f), 0.1f, 1e-6f);  // bias(0.5, b) = b
    EXPECT_EQ(distance_value(49, 50, 50, 0.1f), 0.0f);
    EXPECT_EQ(distance_value(50, 50, 50, 0.1f), 1.0f);
}

Palette one_colour(Color c) {
    Palette p;
    p.dark = p.mid = p.light = {{c}};
    return p;
}

TEST(StrokeShader, ColourIsThePaletteWithoutTintOrAtmosphere) {
    StrokeShaderParams p;
    Palette pal = one_colour(Color(0.2f, 0.3f, 0.1f));
    StrokeConstants k =
        stroke_constants(p, 0.7f, 0.5f, 0.5f, 0.3f, 4, 1.0f, 0.0f, 0.0f, false, false);
    for (float s : {0.1f, 0.5f, 0.9f}) {
        Color c = stroke_color(k, pal, s, 0.4f);
        EXPECT_NEAR(c.x, 0.2f, 1e-6f);
        EXPECT_NEAR(c.y, 0.3f, 1e-6f);
    }
}

TEST(StrokeShader, FullAtmosphereGreysAndClampsValue) {
    StrokeShaderParams p;
    p.dist_sat_limiter = 1.0f;
    p.dist_hue_strength = 0.0f;
    p.dist_value_min = 0.5f;
    p.dist_value_max = 0.6f;
    Palette pal = one_colour(srgb_to_linear(Color(0.9f, 0.2f, 0.1f)));
    StrokeConstants k =
        stroke_constants(p, 0.7f, 0.5f, 0.5f, 0.3f, 4, 1.0f, 1.0f, 0.0f, false, true);
    Color c = stroke_color(k, pal, 0.5f, 0.5f);
    EXPECT_NEAR(c.x, c.y, 1e-6f);  // no saturation left
    EXPECT_NEAR(c.y, c.z, 1e-6f);
    EXPECT_NEAR(linear_to_srgb(c.x), 0.6f, 1e-4f);  // value lowered to dist_value_max
    // Half way, half the effect: saturation limit 0.5.
    k = stroke_constants(p, 0.7f, 0.5f, 0.5f, 0.3f, 4, 1.0f, 0.5f, 0.0f, false, true);
    c = stroke_color(k, pal, 0.5f, 0.5f);
    EXPECT_NEAR((c.x - c.z) / c.x, 0.5f, 1e-4f);
}

TEST(StrokeShader, TintMixesTheTreesColourByAmount) {
    StrokeShaderParams p;
    p.unique_tint_amt = 0.5f;
    p.tint_color1 = p.tint_color2 = Color(1.0f, 0.0f, 0.0f);
    p.sub_stroke_amt = 0;
    Palette pal = one_colour(Color(0.0f, 0.0f, 1.0f));
    StrokeConstants k =
        stroke_constants(p, 0.7f, 0.5f, 0.5f, 0.3f, 9, 1.0f, 0.0f, 0.0f, true, false);
    Color c = stroke_color(k, pal, 0.5f, 0.5f);
    EXPECT_NEAR(c.x, 0.5f, 1e-6f);
    EXPECT_NEAR(c.z, 0.5f, 1e-6f);
    EXPECT_NE(tree_hash01(1), tree_hash01(2));
}

TEST(StrokeShader, EdgeTableMatchesTheExactMask) {
    for (float b : {0.2f, 0.5f, 0.8f, 0.95f}) {
        EdgeTable t = make_edge_table(b);
        float worst = 0;
        for (int i = 0; i <= 200; ++i)
            for (int j = 0; j <= 200; ++j) {
                float s = i / 200.0f, u = j / 200.0f;
                worst = std::max(worst, std::abs(edge_mask(t, s, u, b) - edge_mask(s, u, b)));
            }
        EXPECT_LT(worst, 5e-3f) << b;  // under one 8-bit level of opacity
        EXPECT_EQ(edge_mask(t, 0.0f, 0.5f, b), 0.0f);
        EXPECT_NEAR(edge_mask(t, 0.5f, 0.5f, b), 1.0f, 1e-6f);
    }
}

TEST(StrokeShader, ColourRampMatchesTheExactColour) {
    StrokeShaderParams p;
    p.unique_tint_amt = 0.3f;
    p.dist_sat_limiter = 0.5f;
    Palette pal;
    pal.dark = {{Color(0.02f, 0.03f, 0.01f), Color(0.05f, 0.06f, 0.02f)}};
    pal.mid = {{Color(0.1f, 0.12f, 0.05f), Color(0.2f, 0.22f, 0.1f)}};
    pal.light = {{Color(0.4f, 0.42f, 0.2f), Color(0.7f, 0.68f, 0.45f)}};
    for (float ndl : {0.1f, 0.35f, 0.62f, 0.9f}) {
        StrokeConstants k = stroke_constants(p, ndl, 0.6f, 0.4f, 0.37f, 3, 1, 0.7f, 0, true, true);
        StrokeRamp r = make_ramp(k, pal);
        float worst = 0;
        for (int i = 0; i < 400; ++i) {
            float s = (i % 20 + 0.5f) / 20, t = (i / 20 + 0.5f) / 20;
            worst =
                std::max(worst, glm::length(stroke_color(k, r, s, t) - stroke_color(k, pal, s, t)));
        }
        // 16 intervals over the noise's swing: the error is largest inside a cut-off band,
        // where two splines mix, and stays under 1e-2 in linear RGB (about two 8-bit sRGB
        // levels at mid-tones; the image-level cost is in BENCHMARKS.md's accuracy table).
        EXPECT_LT(worst, 1e-2f) << ndl;
    }
    // No sub-stroke variation: the ramp's middle colour is the exact one everywhere.
    p.sub_stroke_amt = 0;
    StrokeConstants k = stroke_constants(p, 0.5f, 0.6f, 0.4f, 0.37f, 3, 1, 0.7f, 0, true, true);
    Color exact = stroke_color(k, pal, 0.3f, 0.3f);
    Color fast = stroke_color(k, make_ramp(k, pal), 0.3f, 0.3f);
    EXPECT_NEAR(glm::length(exact - fast), 0.0f, 1e-6f);
}

TEST(StrokeShader, LabelsGiveEverySpriteItsOwnNoise) {
    StrokeShaderParams p;
    StrokeConstants a = stroke_constants(p, 0.5f, 0.5f, 0.5f, 0.25f, 0, 1, 0, 0, false, false);
    StrokeConstants b = stroke_constants(p, 0.5f, 0.5f, 0.5f, 0.26f, 0, 1, 0, 0, false, false);
    int differ = 0;
    for (int i = 0; i < 64; ++i) {
        float s = (i % 8 + 0.5f) / 8, t = (i / 8 + 0.5f) / 8;
        differ += std::abs(stroke_noise(a, s, t, 1) - stroke_noise(b, s, t, 1)) > 0.02f;
    }
    EXPECT_GT(differ, 32);
}

}  // namespace
}  // namespace pleinair
