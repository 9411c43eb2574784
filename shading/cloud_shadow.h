// The shadows of clouds on the land (issue 52 section 3): large patches of light and shade over
// the ground, the trees and the water, as a pure function of where a point stands.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "shading/curves.h"
#include "shading/noise.h"

namespace pleinair {

// Scene key /sun/clouds; documented where parsed (pipeline/input/scene.cpp). They stand still
// over a shot, as a painter fixes the light on a meadow: a frame's light stays a function of
// the shot and its camera, whatever the caches (sun light, mirrors) keep from frame to frame.
struct CloudShadowParams {
    float cover = 0.0f;     // share of the land in a cloud's shadow; 0: none
    float size = 80.0f;     // world units: a patch of light or shade's typical width
    float softness = 0.1f;  // share of the land in a shadow's fading edge
    float light = 0.35f;    // the sun's light left in a cloud's shadow (0 as a cast shadow)
    uint64_t seed = 1;
    bool operator==(const CloudShadowParams&) const = default;
};

namespace cloud_detail {
// Quantiles of the three-octave fractal noise at 0, 5%, ..., 100% (measured over a million
// points, two samplings agreeing to 3e-4; the ends opened to 0 and 1): the field crowds about
// 0.5, so a threshold read from this table puts the share `cover` of the land in shade.
inline constexpr float kQuantile[21] = {0.0f,    0.3569f, 0.3875f, 0.4088f, 0.4260f, 0.4406f,
                                        0.4537f, 0.4660f, 0.4776f, 0.4889f, 0.5000f, 0.5112f,
                                        0.5225f, 0.5341f, 0.5463f, 0.5595f, 0.5741f, 0.5911f,
                                        0.6125f, 0.6430f, 1.0f};
inline float quantile(float q) {
    const float x = clamp01(q) * 20.0f;
    const int i = x >= 20.0f ? 19 : static_cast<int>(x);
    return kQuantile[i] + (kQuantile[i + 1] - kQuantile[i]) * (x - static_cast<float>(i));
}
}  // namespace cloud_detail

// The sun's light left at ground position (x, z) by the clouds' shadows: 1 in the open,
// `light` deep in a shadow. A point is in shade where the field rises over its (1 - cover)
// quantile, its edge fading over the quantiles `softness` wide about it.
inline float cloud_light(const CloudShadowParams& p, double x, double z) {
    if (!(p.cover > 0.0f)) return 1.0f;
    const float light = clamp01(p.light);
    if (p.cover >= 1.0f) return light;
    const double inv = 1.0 / (p.size > 1e-3f ? p.size : 1e-3f);
    // The seed shifts the field; positions wrap at the noise's 256-unit lattice in double, so a
    // far point keeps the float precision of a near one.
    const double ox = static_cast<double>((p.seed * 0x9E3779B97F4A7C15ull) >> 40) / 65536.0;
    const double oz = static_cast<double>((p.seed * 0xC2B2AE3D27D4EB4Full) >> 40) / 65536.0;
    auto wrap = [](double u) { return static_cast<float>(u - 256.0 * std::floor(u / 256.0)); };
    const float n = fractal_noise(wrap(x * inv + ox), wrap(z * inv + oz), 3);
    const float c = 1.0f - p.cover, half = 0.5f * std::max(p.softness, 1e-3f);
    const float shade =
        smoothstep(cloud_detail::quantile(c - half), cloud_detail::quantile(c + half), n);
    return 1.0f - (1.0f - light) * shade;
}

}  // namespace pleinair
