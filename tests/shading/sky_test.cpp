// The painted sky's field (shading/sky.h): cover, lit sides, the glow and finite values at the
// zenith, the horizon and under it.
#include "shading/sky.h"

#include <gtest/gtest.h>

#include <cmath>

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
                sky_detail::field(q) - sky_detail::field(q + glm::vec2(0.25f, 0));
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

}  // namespace
}  // namespace pleinair
