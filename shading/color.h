// Colour: sRGB transfer functions, colour splines and the three-spline palettes of thesis IV.4.3
// and IV.5, where lightness picks the colour instead of scaling it.
#pragma once

#include <algorithm>
#include <cmath>
#include <glm/vec3.hpp>
#include <vector>

#include "shading/curves.h"
#include "shading/portable_math.h"

namespace pleinair {

using Color = glm::vec3;  // linear RGB

inline float srgb_to_linear(float c) {
    c = clamp01(c);
    return c <= 0.04045f ? c / 12.92f : pmath::pow((c + 0.055f) / 1.055f, 2.4f);
}
inline float linear_to_srgb(float c) {
    c = clamp01(c);
    return c <= 0.0031308f ? 12.92f * c : 1.055f * pmath::pow(c, 1.0f / 2.4f) - 0.055f;
}
inline Color srgb_to_linear(Color c) {
    return {srgb_to_linear(c.x), srgb_to_linear(c.y), srgb_to_linear(c.z)};
}
inline Color linear_to_srgb(Color c) {
    return {linear_to_srgb(c.x), linear_to_srgb(c.y), linear_to_srgb(c.z)};
}

inline Color mix(Color a, Color b, float t) { return a + (b - a) * t; }

enum class SplineBasis { kLinear, kCatmullRom };

// Evenly spaced colours over 0..1 (thesis IV.4.3). Linear interpolates between neighbours;
// Catmull-Rom passes through every colour like RenderMan's spline(), with the end colours
// repeated as phantom points. Catmull-Rom can overshoot; the result is clamped to [0, 1].
struct ColorSpline {
    std::vector<Color> colors;  // linear RGB, at least one
    SplineBasis basis = SplineBasis::kLinear;
    bool operator==(const ColorSpline&) const = default;
};

inline Color eval(const ColorSpline& s, float x) {
    const size_t n = s.colors.size();
    if (n == 0) return Color(0.0f);
    if (n == 1) return s.colors[0];
    float u = clamp01(x) * static_cast<float>(n - 1);
    size_t i = static_cast<size_t>(u);
    if (i >= n - 1) i = n - 2;
    float t = u - static_cast<float>(i);
    if (s.basis == SplineBasis::kLinear) return mix(s.colors[i], s.colors[i + 1], t);
    const Color& p0 = s.colors[i == 0 ? 0 : i - 1];
    const Color& p1 = s.colors[i];
    const Color& p2 = s.colors[i + 1];
    const Color& p3 = s.colors[i + 2 < n ? i + 2 : n - 1];
    float t2 = t * t, t3 = t2 * t;
    Color c = 0.5f * ((2.0f * p1) + (-p0 + p2) * t + (2.0f * p0 - 5.0f * p1 + 4.0f * p2 - p3) * t2 +
                      (-p0 + 3.0f * p1 - 3.0f * p2 + p3) * t3);
    return {clamp01(c.x), clamp01(c.y), clamp01(c.z)};
}

// Dark, mid and light splines with their lightness cut-offs (thesis IV.5). Below
// dark_cutoff_start only the dark spline is used, between dark_cutoff_end and mid_cutoff_start
// only the mid one, above mid_cutoff_end only the light one; inside a cut-off band both
// neighbours are evaluated and mixed linearly. Each spline spans the lightness range where it is
// used (dark: 0..dark_cutoff_end, mid: dark_cutoff_start..mid_cutoff_end, light:
// mid_cutoff_start..1), so all of its colours are reachable.
struct Palette {
    ColorSpline dark, mid, light;
    float dark_cutoff_start = 0.30f;
    float dark_cutoff_end = 0.40f;
    float mid_cutoff_start = 0.60f;
    float mid_cutoff_end = 0.68f;
    bool operator==(const Palette&) const = default;
};

namespace color_detail {
// x mapped from [a, b] to [0, 1]; an empty range maps to a step.
inline float unit_in(float x, float a, float b) {
    if (!(b > a)) return x >= a ? 1.0f : 0.0f;
    return clamp01((x - a) / (b - a));
}
}  // namespace color_detail

inline Color palette_lookup(const Palette& p, float lightness) {
    using color_detail::unit_in;
    const float l = clamp01(lightness);
    auto dark = [&] { return eval(p.dark, unit_in(l, 0.0f, p.dark_cutoff_end)); };
    auto mid = [&] { return eval(p.mid, unit_in(l, p.dark_cutoff_start, p.mid_cutoff_end)); };
    auto light = [&] { return eval(p.light, unit_in(l, p.mid_cutoff_start, 1.0f)); };
    if (l < p.dark_cutoff_start) return dark();
    if (l < p.dark_cutoff_end)
        return mix(dark(), mid(), unit_in(l, p.dark_cutoff_start, p.dark_cutoff_end));
    if (l < p.mid_cutoff_start) return mid();
    if (l < p.mid_cutoff_end)
        return mix(mid(), light(), unit_in(l, p.mid_cutoff_start, p.mid_cutoff_end));
    return light();
}

// Hue-preserving saturation and value edits for atmospheric perspective, on linear RGB.
// Saturation is HSV's (max - min) / max and value its max; both are the same in sRGB and linear
// for the questions asked here (ordering of channels, zero saturation), and working in linear
// keeps the transfer function out of the per-fragment loop.
inline Color limit_saturation(Color c, float max_saturation) {
    float hi = std::max(c.x, std::max(c.y, c.z));
    float lo = std::min(c.x, std::min(c.y, c.z));
    if (!(hi > 0.0f)) return c;
    float s = (hi - lo) / hi;
    if (s <= max_saturation) return c;
    float k = std::max(max_saturation, 0.0f) / s;  // channels keep their order and hue
    return Color(hi) - (Color(hi) - c) * k;
}

// Linear luminance (Rec. 709 weights).
inline float luminance(Color c) { return 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z; }

// A colour scaled by k, then down again if a channel passes 1, so its hue never shifts.
inline Color scale_keeping_hue(Color c, float k) {
    c = c * k;
    const float hi = std::max(c.x, std::max(c.y, c.z));
    return hi > 1.0f ? c / hi : c;
}

// A colour taken the share `amount` of the way to luminance `target`, keeping its hue (a black
// becomes the grey of the luminance reached).
inline Color toward_luminance(Color c, float target, float amount) {
    const float y = luminance(c);
    const float to = y + (target - y) * std::clamp(amount, 0.0f, 1.0f);
    if (!(y > 1e-6f)) return Color(to);
    return scale_keeping_hue(c, to / y);
}

inline Color clamp_value(Color c, float lo, float hi) {
    float v = std::max(c.x, std::max(c.y, c.z));
    if (!(v > 0.0f)) return Color(lo);  // black has no hue: it becomes the darkest grey allowed
    float target = std::clamp(v, lo, std::max(lo, hi));
    return c * (target / v);
}

}  // namespace pleinair
