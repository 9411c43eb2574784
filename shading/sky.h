// The painted sky's field: cloud density over a cloud plane, the clouds lit from the sun's side,
// and the lightness a sky stroke takes in a direction, as pure functions of that direction.
#pragma once

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "shading/curves.h"
#include "shading/noise.h"
#include "shading/portable_math.h"

namespace pleinair {

// The weather of a painted sky (scene key /sky; documented where parsed, pipeline/input/scene.cpp).
struct SkyParams {
    float cloud_cover = 0.45f;     // share of the sky in cloud, 0..1
    float cloud_scale = 1.0f;      // size of the clouds (1: a few across the view)
    float cloud_softness = 0.10f;  // noise band over which a cloud's edge fades
    float stroke_size = 8.0f;      // degrees of sky a base stroke spans along its length
    float detail = 1.0f;           // share of the small strokes kept along cloud edges
    float haze = 0.12f;            // sine of elevation over which clouds fade into the horizon
    float sun_glow = 0.25f;        // lightness added around the sun
    float stroke_jitter = 0.16f;   // lightness a stroke may differ from its neighbours (label)
    float zenith_lightness = 0.46f, horizon_lightness = 0.74f;  // clear sky
    float cloud_light = 0.90f, cloud_shade = 0.30f;             // a cloud's lit and shaded sides
};

namespace sky_detail {
// The cloud plane: directions to (x, z) over elevation, so clouds flatten and crowd towards
// the horizon as a ceiling of cloud does; 0.15 keeps the horizon's values finite.
inline glm::vec2 plane(const SkyParams& p, const glm::vec3& d) {
    const float k = 1.6f / std::max(p.cloud_scale, 1e-3f) / (std::max(d.y, 0.0f) + 0.15f);
    return {d.x * k, d.z * k};
}
inline float field(const glm::vec2& q) { return fractal_noise(q.x + 37.0f, q.y + 11.0f, 4); }
// The noise level above which there is cloud, from the cover: the fractal noise stays within
// about 0.2..0.8, so cover 0 puts the whole soft band above it and cover 1 below it.
inline float threshold(const SkyParams& p) {
    const float soft = std::max(p.cloud_softness, 1e-3f);
    return 0.8f + soft - (0.6f + 2.0f * soft) * clamp01(p.cloud_cover);
}
}  // namespace sky_detail

// What a sky stroke in direction d (unit) shows: its lightness (palette lookup) and the cloud
// there. Clear sky darkens from the horizon to the zenith; a cloud is light where its density
// falls towards the sun (light reaches it through little cloud) and shaded where it rises; a
// glow surrounds the sun.
struct SkySample {
    float lightness = 0;
    float cloud = 0;  // how much cloud: 0 clear, 1 full
    float edge = 0;   // 1 on a cloud's rim, 0 in clear sky and deep inside
};

inline SkySample sky_sample(const SkyParams& p, const glm::vec3& d, const glm::vec3& sun) {
    using namespace sky_detail;
    SkySample s;
    const glm::vec2 q = plane(p, d);
    const float n = field(q);
    // Cloud where the noise is over the cover's threshold, thinned to nothing in the haze.
    const float thr = threshold(p), soft = std::max(p.cloud_softness, 1e-3f);
    s.cloud =
        smoothstep(thr - soft, thr + soft, n) * smoothstep(0.0f, std::max(p.haze, 1e-3f), d.y);
    s.edge = clamp01(4.0f * s.cloud * (1.0f - s.cloud));
    // Towards the sun across the cloud plane: its azimuth, a step of a tenth of a cloud.
    glm::vec2 to_sun(sun.x, sun.z);
    const float len = glm::length(to_sun);
    to_sun = len > 1e-6f ? to_sun / len : glm::vec2(1.0f, 0.0f);
    const float lit = smoothstep(-0.06f, 0.06f, n - field(q + 0.25f * to_sun));
    const float clear = p.horizon_lightness +
                        (p.zenith_lightness - p.horizon_lightness) * smoothstep(0.0f, 0.7f, d.y);
    const float thick = smoothstep(thr, thr + 0.2f, n);
    float cloud = p.cloud_shade + (p.cloud_light - p.cloud_shade) * (0.3f + 0.7f * lit);
    cloud -= 0.1f * thick * (1.0f - lit);
    const float toward = std::max(glm::dot(d, sun), 0.0f);
    const float t2 = toward * toward, t4 = t2 * t2;
    s.lightness = clamp01(clear + (cloud - clear) * s.cloud + p.sun_glow * t4 * t4);
    return s;
}

}  // namespace pleinair
