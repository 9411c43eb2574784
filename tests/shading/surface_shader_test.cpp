// The generalized surface-stroke shader's functions, value by value and at their edges.
#include "shading/surface_shader.h"

#include <gtest/gtest.h>

namespace pleinair {
namespace {

TEST(SurfaceShader, LightingNormalBlendsAndSurvivesOppositeNormals) {
    glm::vec3 up(0, 1, 0), side(1, 0, 0);
    EXPECT_EQ(lighting_normal(up, side, 0.0f), up);
    EXPECT_EQ(lighting_normal(up, side, 1.0f), side);
    glm::vec3 half = lighting_normal(up, side, 0.5f);
    EXPECT_NEAR(half.x, std::sqrt(0.5f), 1e-6f);
    EXPECT_NEAR(half.y, std::sqrt(0.5f), 1e-6f);
    EXPECT_EQ(lighting_normal(up, -up, 0.5f), up);    // cancels: the surface's normal
    EXPECT_EQ(lighting_normal(up, side, -3.0f), up);  // weight clamped
}

TEST(SurfaceShader, DeeperStrokesAreDarker) {
    SurfaceShaderParams p;
    EXPECT_FLOAT_EQ(surface_lightness(p, 0.8f, 1.0f), 0.8f);
    EXPECT_FLOAT_EQ(surface_lightness(p, 0.8f, 0.0f), 0.8f * (1 - 0.35f));
    EXPECT_FLOAT_EQ(surface_lightness(p, -0.5f, 1.0f), 0.0f);
    EXPECT_LT(surface_lightness(p, 0.6f, 0.2f), surface_lightness(p, 0.6f, 0.7f));
}

TEST(SurfaceShader, DetailStrokesGetTheirOwnFrequencies) {
    SurfaceShaderParams p;
    float s, t;
    surface_frequencies(p, 0.3f, s, t);  // base
    EXPECT_FLOAT_EQ(s, 1.5f);
    EXPECT_FLOAT_EQ(t, 1.5f);
    surface_frequencies(p, 0.9f, s, t);  // detail: thin vertical tufts
    EXPECT_FLOAT_EQ(s, 4.0f * 4.0f);
    EXPECT_FLOAT_EQ(t, 4.0f * 0.6f);
    EXPECT_FALSE(is_detail(p, 0.6f));  // the threshold itself is base
    EXPECT_TRUE(is_detail(p, 0.61f));
}

TEST(SurfaceShader, CrestShrinksTheVerticalMask) {
    EXPECT_FLOAT_EQ(crest_factor(1.0f, 0.8f), 1.0f);
    EXPECT_FLOAT_EQ(crest_factor(-1.0f, 0.8f), 1.0f);
    EXPECT_NEAR(crest_factor(0.0f, 0.8f), 0.2f, 1e-6f);
    EXPECT_GT(crest_factor(0.0f, 1.0f), 0.0f);  // never zero: no division by it
    EXPECT_FLOAT_EQ(crest_t(0.5f, 0.2f), 0.5f);
    EXPECT_FLOAT_EQ(crest_t(0.6f, 0.2f), 1.0f);  // the band's edge
    EXPECT_GT(crest_t(0.9f, 0.2f), 1.0f);        // outside: masked
    EXPECT_FLOAT_EQ(crest_t(0.9f, 1.0f), 0.9f);
}

TEST(SurfaceShader, InsideGrowthAndMaterials) {
    EXPECT_FLOAT_EQ(inside_size(1.0f, 2.0f), 1.0f);
    EXPECT_FLOAT_EQ(inside_size(0.0f, 2.0f), 3.0f);
    EXPECT_FLOAT_EQ(inside_size(0.0f, -1.0f), 1.0f);
    int ones = 0;
    for (int i = 0; i < 400; ++i)
        ones += noise_material((i % 20) / 20.0f, (i / 20) / 20.0f, 6.0f, 0.5f, 3.7f);
    EXPECT_GT(ones, 100);  // a hillside mixes both materials
    EXPECT_LT(ones, 300);
    EXPECT_EQ(noise_material(0.3f, 0.3f, 6.0f, 1.0f, 0.0f), 0);  // threshold 1: never
}

}  // namespace
}  // namespace pleinair

namespace pleinair {
namespace {

// Base strokes laid along the ground (lay): standing by default, along the azimuth on level
// ground, across the fall line on a slope, always in the ground's plane when lying; detail
// strokes stand.
TEST(SurfaceShader, LaidStrokesFollowTheContourOrTheBrushAzimuth) {
    SurfaceShaderParams p;
    const glm::vec3 up(0, 1, 0);
    EXPECT_EQ(surface_stroke_direction(p, up, 0.2f), up);  // lay 0: as before
    p.lay = 1.0f;
    p.lay_azimuth = 90.0f;
    const glm::vec3 level = surface_stroke_direction(p, up, 0.2f);
    EXPECT_NEAR(level.x, 0.0f, 1e-6f);
    EXPECT_NEAR(level.y, 0.0f, 1e-6f);
    EXPECT_NEAR(level.z, -1.0f, 1e-6f);  // +x turned 90 degrees about +y
    EXPECT_EQ(surface_stroke_direction(p, up, 0.9f), up) << "detail strokes stand";
    // A slope of 30 degrees falling towards +x: the stroke runs along z, level, in its plane.
    const float s = 0.5f, c = 0.8660254f;
    const glm::vec3 n(s, c, 0.0f);
    for (float az : {0.0f, 45.0f, 90.0f, -120.0f}) {
        p.lay_azimuth = az;
        const glm::vec3 d = surface_stroke_direction(p, n, 0.2f);
        EXPECT_NEAR(glm::length(d), 1.0f, 1e-5f);
        EXPECT_NEAR(d.y, 0.0f, 1e-5f) << az;
        EXPECT_NEAR(std::abs(d.z), 1.0f, 1e-5f) << az;
        EXPECT_NEAR(glm::dot(d, n), 0.0f, 1e-5f);
    }
    // Gentle slopes blend towards the azimuth; every direction lies in the ground's plane.
    p.lay_azimuth = 0.0f;
    for (float tilt : {0.0f, 0.05f, 0.1f, 0.2f}) {
        const glm::vec3 m = glm::normalize(glm::vec3(0.0f, 1.0f, tilt));
        const glm::vec3 d = surface_stroke_direction(p, m, 0.2f);
        EXPECT_NEAR(glm::length(d), 1.0f, 1e-5f);
        EXPECT_NEAR(glm::dot(d, m), 0.0f, 1e-5f) << tilt;
        EXPECT_GT(d.x, 0.99f) << "the fall line is along z, so contour and azimuth agree";
    }
    // Half laid: between standing and lying.
    p.lay = 0.5f;
    const glm::vec3 half = surface_stroke_direction(p, up, 0.2f);
    EXPECT_NEAR(half.y, std::sqrt(0.5f), 1e-5f);
    EXPECT_NEAR(half.x, std::sqrt(0.5f), 1e-5f);
}

TEST(SurfaceShader, BaseAspectLengthensOnlyTheBaseStrokes) {
    SurfaceShaderParams p;
    EXPECT_EQ(surface_aspect(p, 0.2f), 1.0f);  // the default: every stroke as the tufts
    p.base_aspect = 1.5f;
    EXPECT_EQ(surface_aspect(p, 0.2f), 1.5f);                        // a base stroke
    EXPECT_EQ(surface_aspect(p, p.detail_threshold + 0.01f), 1.0f);  // a tuft keeps its shape
    EXPECT_EQ(surface_aspect(p, p.detail_threshold), 1.5f);          // at the threshold, still base
}

}  // namespace
}  // namespace pleinair
