// The painted sky's field (shading/sky.h): cover, lit sides, the glow and finite values at the
// zenith, the horizon and under it.
#include "shading/sky.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace pleinair {
namespace {

glm::vec3 dir(float azimuth_deg, float elevation_deg) {
    const float a = azimuth_deg * 3.14159265f / 180.0f, e = elevation_deg * 3.14159265f / 180.0f;
    return {std::cos(e) * std::sin(a), std::sin(e), -std::cos(e) * std::cos(a)};
}

// Mean cloud over a grid of directions between 10 and 80 degrees up.
float mean_cloud(const SkyParams& p) {
    const glm::vec3 sun = glm::normalize(glm::vec3(-0.5f, 0.6f, 0.4f));
    double sum = 0;
    int n = 0;
    for (int a = 0; a < 360; a += 3)
        for (int e = 10; e <= 80; e += 2, ++n) sum += sky_sample(p, dir(a, e), sun).cloud;
    return static_cast<float>(sum / n);
}

TEST(Sky, CoverGovernsTheShareOfCloud) {
    SkyParams p;
    p.cloud_cover = 0;
    EXPECT_LT(mean_cloud(p), 0.02f);
    p.cloud_cover = 1;
    EXPECT_GT(mean_cloud(p), 0.95f);
    float last = -1;
    for (float c : {0.2f, 0.4f, 0.6f, 0.8f}) {
        p.cloud_cover = c;
        const float m = mean_cloud(p);
        EXPECT_GT(m, last) << c;
        last = m;
    }
}

TEST(Sky, ClearSkyDarkensTowardsTheZenithAndGlowsAroundTheSun) {
    SkyParams p;
    p.cloud_cover = 0;
    p.sun_glow = 0;
    const glm::vec3 sun = glm::normalize(glm::vec3(0.0f, 0.3f, 1.0f));  // behind the view
    EXPECT_NEAR(sky_sample(p, dir(0, 0.5f), sun).lightness, p.horizon_lightness, 0.01f);
    EXPECT_NEAR(sky_sample(p, dir(0, 89), sun).lightness, p.zenith_lightness, 0.01f);
    const float plain = sky_sample(p, sun, sun).lightness;
    const glm::vec3 away = glm::normalize(glm::vec3(0.0f, 0.3f, -1.0f));
    const float plain_away = sky_sample(p, away, sun).lightness;
    p.sun_glow = 0.2f;
    EXPECT_NEAR(sky_sample(p, sun, sun).lightness - plain, 0.2f, 1e-4f);  // the glow at the sun
    EXPECT_EQ(sky_sample(p, away, sun).lightness, plain_away);            // none opposite it
}

TEST(Sky, CloudsAreLighterOnTheSunsSide) {
    // A rim whose cloud thins towards the sun (the density a tenth of a cloud towards it is
    // lower) faces the sun and is lit: lighter with the sun on that side than with the sun
    // opposite. Signed, so a sky lit from the side away from the sun fails (an absolute
    // difference could not tell the two apart).
    SkyParams p;
    p.cloud_cover = 0.5f;
    p.sun_glow = 0;
    const glm::vec3 east = glm::normalize(glm::vec3(1, 0.5f, 0)),
                    west = glm::normalize(glm::vec3(-1, 0.5f, 0));
    double facing = 0, away = 0;
    int n_facing = 0, n_away = 0;
    for (int a = 0; a < 360; a += 2)
        for (int e = 20; e <= 70; e += 1) {
            const glm::vec3 d = dir(a, e);
            const SkySample s = sky_sample(p, d, east), w = sky_sample(p, d, west);
            EXPECT_EQ(s.cloud, w.cloud);  // the sun lights clouds; it does not move them
            if (!(s.cloud > 0.3f && s.cloud < 0.95f)) continue;
            const glm::vec2 q = sky_detail::plane(p, d);
            const float thinning =
                sky_detail::density(q) - sky_detail::density(q + glm::vec2(0.25f, 0));
            if (thinning > 0.06f) facing += s.lightness - w.lightness, ++n_facing;  // faces east
            if (thinning < -0.06f) away += s.lightness - w.lightness, ++n_away;     // faces west
        }
    ASSERT_GT(n_facing, 50);
    ASSERT_GT(n_away, 50);
    EXPECT_GT(facing / n_facing, 0.05) << "rims facing the sun must be the lighter";
    EXPECT_LT(away / n_away, -0.05) << "rims facing away must be the darker";
}

TEST(Sky, FiniteEverywhereEvenAtTheZenithAndUnderTheHorizon) {
    SkyParams p;
    p.cloud_scale = 0.05f;
    p.haze = 0.001f;
    p.cloud_softness = 0.001f;
    for (const glm::vec3& d : {glm::vec3(0, 1, 0), glm::vec3(0, -1, 0), glm::vec3(1, 0, 0),
                               glm::vec3(0, 1e-30f, -1), glm::vec3(1e5f, 0, 0)})
        for (const glm::vec3& sun : {glm::vec3(0, 1, 0), glm::vec3(0, -1, 0), glm::vec3(0)}) {
            const SkySample s = sky_sample(p, d, sun);
            EXPECT_TRUE(std::isfinite(s.lightness) && s.lightness >= 0 && s.lightness <= 1);
            EXPECT_TRUE(std::isfinite(s.cloud) && s.cloud >= 0 && s.cloud <= 1);
            EXPECT_TRUE(std::isfinite(s.edge));
        }
    // No cloud at or under the horizon: the haze thins them to nothing.
    p.cloud_cover = 1;
    EXPECT_EQ(sky_sample(p, dir(30, -5), glm::vec3(0, 1, 0)).cloud, 0.0f);
}

// The share of the cells of 10 degrees of azimuth by 10 of elevation between 15 and 45 degrees
// up (the masses are about 20 degrees across) that are nearly clear or nearly all cloud: a bank
// or a clear reach, not the even mix of a sky with clouds spread evenly over it.
float decided_share(const SkyParams& p) {
    const glm::vec3 sun = glm::normalize(glm::vec3(-0.5f, 0.6f, 0.4f));
    std::vector<double> mean;
    for (int a0 = 0; a0 < 360; a0 += 10)
        for (int e0 = 15; e0 < 45; e0 += 10) {
            double sum = 0;
            int n = 0;
            for (int a = a0; a < a0 + 10; ++a)
                for (int e = e0; e < e0 + 10; ++e, ++n) sum += sky_sample(p, dir(a, e), sun).cloud;
            mean.push_back(sum / n);
        }
    double decided = 0;
    for (double x : mean) decided += (x < 0.1 || x > 0.9) ? 1.0 / mean.size() : 0.0;
    return static_cast<float>(decided);
}

TEST(Sky, CloudsGatherIntoMassesWithClearReachesBetween) {
    // Corot's few large masses: with cloud_masses the cover swells and opens from one part of
    // the sky to another; without, the clouds spread evenly (every sector much the same).
    SkyParams p;
    p.cloud_cover = 0.5f;
    p.cloud_masses = 0;
    const float even = decided_share(p);
    p.cloud_masses = 0.8f;
    const float massed = decided_share(p);
    EXPECT_GT(massed, 2.0f * even) << even << " " << massed;
    // The cover still governs the share of cloud on average.
    EXPECT_NEAR(mean_cloud(p), 0.5f, 0.12f);
}

// Pearson correlation of the strokes' tone between directions 1.5 degrees apart (a fifth of an
// 8-degree stroke: neighbours on the canvas) over a band of sky, each stroke's label drawn apart.
double neighbour_tone_correlation(const SkyParams& p) {
    const float rad = 8.0f * 3.14159265f / 180.0f;
    double sa = 0, sb = 0, saa = 0, sbb = 0, sab = 0;
    int n = 0;
    uint32_t h = 12345;
    auto draw = [&] { return ((h = h * 1664525u + 1013904223u) >> 8) / float(1 << 24); };
    for (int a = 0; a < 360; a += 3)
        for (int e = 10; e <= 60; e += 3, ++n) {
            const float x = p.stroke_jitter > 0 ? 1.0f : 0.0f;
            const double ta = sky_stroke_tone(p, dir(a, e), rad, draw()) * x;
            const double tb = sky_stroke_tone(p, dir(a + 1.5f, e), rad, draw()) * x;
            sa += ta, sb += tb, saa += ta * ta, sbb += tb * tb, sab += ta * tb;
        }
    const double cov = sab / n - sa / n * sb / n;
    return cov / std::sqrt((saa / n - sa / n * sa / n) * (sbb / n - sb / n * sb / n));
}

TEST(Sky, NeighbouringTouchesAgreeInPatchesAndKeepTheirRange) {
    SkyParams p;
    p.jitter_coherence = 0;  // each touch on its own: a tiled field of same-size dabs
    EXPECT_LT(std::abs(neighbour_tone_correlation(p)), 0.15);
    p.jitter_coherence = 0.7f;
    EXPECT_GT(neighbour_tone_correlation(p), 0.5);
    // Within stroke_jitter peak to peak, whatever the draw.
    for (float c : {0.0f, 0.7f, 1.0f}) {
        p.jitter_coherence = c;
        for (int a = 0; a < 360; a += 7)
            for (float r : {0.0f, 0.5f, 0.999f}) {
                const float t = sky_stroke_tone(p, dir(a, 30), 0.14f, r);
                EXPECT_LE(std::abs(t), 0.5f * p.stroke_jitter + 1e-5f);
            }
    }
}

TEST(Sky, StrokeSizesVaryOverTheSkyWithinTheirRange) {
    SkyParams p;
    float lo = 10, hi = 0;
    for (int a = 0; a < 360; a += 2)
        for (int e = 5; e <= 85; e += 5) {
            const float s = sky_stroke_scale(p, dir(a, e), 0.14f);
            lo = std::min(lo, s), hi = std::max(hi, s);
        }
    EXPECT_GE(lo, 1.0f - 0.5f * p.stroke_variety - 1e-5f);
    EXPECT_LE(hi, 1.0f + 0.5f * p.stroke_variety + 1e-5f);
    EXPECT_GT(hi - lo, 0.5f * p.stroke_variety);  // broad and fine reaches both present
    p.stroke_variety = 0;
    EXPECT_EQ(sky_stroke_scale(p, dir(40, 30), 0.14f), 1.0f);
}

}  // namespace
}  // namespace pleinair
