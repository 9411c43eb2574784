// A painted frame's palette in CIELAB (issue 27 §2): how saturated it is, how much of it is a
// warm accent, and how its values spread, the figures a restricted palette like Corot's keeps.
#pragma once

#include <array>
#include <cstddef>

#include "pipeline/frame/frame_image.h"

namespace pleinair {

// CIELAB (D65 white) of a linear sRGB colour: L* 0..100, a*, b*. Written out here because
// OpenImageIO's colour configurations have no CIELAB; the sRGB primaries' matrix and the
// CIE 1976 formulas.
std::array<float, 3> linear_srgb_to_lab(float r, float g, float b);

// CIELAB of a frame's pixel i (its premultiplied colour over its alpha), and its chroma.
std::array<float, 3> pixel_lab(const Frame& frame, size_t i);
float pixel_chroma(const Frame& frame, size_t i);

// A warm accent: chroma at least kWarmChroma, hue angle (atan2(b*, a*)) within kWarmHue degrees
// of kWarmHueCentre: saturated reds, oranges and ochres; Corot's browns are duller than this.
inline constexpr float kWarmChroma = 30.0f;
inline constexpr float kWarmHueCentre = 40.0f, kWarmHue = 45.0f;

struct PaletteLook {
    double chroma_mean = 0;  // CIELAB chroma sqrt(a*^2 + b*^2), over every pixel
    double chroma_p95 = 0;   // its 95th percentile
    double warm = 0;         // share of the pixels that are warm accents
    double lightness_median = 0;
    std::array<double, 5> lightness{};  // shares of L* in [0, 20), [20, 40), ... [80, 100]
};

PaletteLook palette_look(const Frame& frame);

}  // namespace pleinair
