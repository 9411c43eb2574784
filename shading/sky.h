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
    float cloud_cover = 0.45f;      // share of the sky in cloud, 0..1
    float cloud_scale = 1.0f;       // size of the clouds (1: a few across the view)
    float cloud_softness = 0.18f;   // noise band over which a cloud's edge fades
    float stroke_size = 8.0f;       // degrees of sky a base stroke spans along its length
    float detail = 1.0f;            // share of the small strokes kept along cloud edges
    float haze = 0.18f;             // sine of elevation over which clouds fade into the horizon
    float sun_glow = 0.25f;         // lightness added around the sun
    float stroke_jitter = 0.10f;    // lightness a stroke may differ from the field (peak to peak)
    float jitter_coherence = 0.7f;  // share of that drawn from a field a few strokes across
    float cloud_masses = 0.8f;      // how far the cover rises and falls over the sky's masses
    float stroke_variety = 0.5f;    // strokes' size, 1 -/+ half this, over the masses
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
// The cloud plane torn by a slower noise: outlines drawn out and ragged rather than the noise's
// own round blobs, which read as one motif tiled over the sky.
inline glm::vec2 warp(const glm::vec2& q) {
    const float u = fractal_noise(0.45f * q.x + 5.1f, 0.45f * q.y + 1.7f, 2);
    const float v = fractal_noise(0.45f * q.x + 9.3f, 0.45f * q.y + 4.2f, 2);
    return q + 1.1f * glm::vec2(u - 0.5f, v - 0.5f);
}
inline float density(const glm::vec2& q) { return field(warp(q)); }
// The sky's masses, about two across a 45-degree view whatever the clouds' size (a sky of small
// clouds gathers them into banks too), over a flatter plane than the clouds'
// (they do not crowd so towards the horizon): where they rise the clouds gather into a bank, where
// they fall the sky opens into a clear reach, as Corot's skies do, instead of spreading evenly.
// About 0.2..0.8, 0.5 on average.
inline float masses(const glm::vec3& d) {
    const float k = 2.4f / (std::max(d.y, 0.0f) + 0.5f);
    return fractal_noise(d.x * k + 3.1f, d.z * k + 7.7f, 2);
}
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
    const float n = density(q);
    // The masses fade at no cover and full cover, where there is nothing for them to gather.
    const float cover = clamp01(p.cloud_cover);
    const float mass = (masses(d) - 0.5f) * 4.0f * cover * (1.0f - cover);
    // Cloud where the noise is over the cover's threshold, lowered where the masses gather and
    // raised where they open, thinned to nothing in the haze.
    const float thr = threshold(p) - p.cloud_masses * mass,
                soft = std::max(p.cloud_softness, 1e-3f);
    s.cloud =
        smoothstep(thr - soft, thr + soft, n) * smoothstep(0.0f, std::max(p.haze, 1e-3f), d.y);
    s.edge = clamp01(4.0f * s.cloud * (1.0f - s.cloud));
    // Towards the sun across the cloud plane: its azimuth, a step of a tenth of a cloud.
    glm::vec2 to_sun(sun.x, sun.z);
    const float len = glm::length(to_sun);
    to_sun = len > 1e-6f ? to_sun / len : glm::vec2(1.0f, 0.0f);
    const float lit = smoothstep(-0.06f, 0.06f, n - density(q + 0.25f * to_sun));
    // Clear sky: light at the horizon, deeper to the zenith; a shade deeper in the gaps of a
    // bank of cloud, more luminous over an open reach.
    const float clear = p.horizon_lightness +
                        (p.zenith_lightness - p.horizon_lightness) * smoothstep(0.0f, 0.7f, d.y) -
                        0.15f * p.cloud_masses * mass;
    const float thick = smoothstep(thr, thr + 0.2f, n);
    float cloud = p.cloud_shade + (p.cloud_light - p.cloud_shade) * (0.3f + 0.7f * lit);
    cloud -= 0.1f * thick * (1.0f - lit);
    const float toward = std::max(glm::dot(d, sun), 0.0f);
    const float t2 = toward * toward, t4 = t2 * t2;
    s.lightness = clamp01(clear + (cloud - clear) * s.cloud + p.sun_glow * t4 * t4);
    return s;
}

// A sky stroke's own touch, as pure functions of its direction d (unit), its angle
// `stroke_rad` along its length and its label's draw `r` (0..1): how far its lightness departs
// from the field (mostly a field a few strokes across, so neighbouring touches agree and the sky
// shimmers in patches, not stroke by stroke) and its size, 1 -/+ stroke_variety / 2 over a
// slower field: broad touches in some reaches, finer ones in others.
inline float sky_stroke_tone(const SkyParams& p, const glm::vec3& d, float stroke_rad, float r) {
    const float k = 1.0f / (4.0f * std::max(stroke_rad, 1e-3f));
    const float field = fractal_noise(d.x * k + 1.3f, d.y * k + 2.9f, d.z * k + 5.3f, 2);
    const float c = clamp01(p.jitter_coherence);
    const float patch = std::clamp(1.6f * (field - 0.5f), -0.5f, 0.5f);
    return p.stroke_jitter * ((1.0f - c) * (r - 0.5f) + c * patch);
}
inline float sky_stroke_scale(const SkyParams& p, const glm::vec3& d, float stroke_rad) {
    const float k = 1.0f / (10.0f * std::max(stroke_rad, 1e-3f));
    const float field = fractal_noise(d.x * k + 8.1f, d.y * k + 0.7f, d.z * k + 3.9f, 2);
    return 1.0f + p.stroke_variety * std::clamp(1.6f * (field - 0.5f), -0.5f, 0.5f);
}

}  // namespace pleinair
