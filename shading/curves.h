// Shaping curves of the painterly shader (Perlin's bias and gain, smoothstep), safe at every edge.
#pragma once

#include <algorithm>
#include <cmath>

#include "shading/portable_math.h"

namespace pleinair {

// NaN maps to 0, so nothing downstream ever sees it.
inline float clamp01(float x) { return x > 0.0f ? (x < 1.0f ? x : 1.0f) : 0.0f; }

// Perlin's bias: bias(0.5, b) = b, bias(0) = 0, bias(1) = 1; b = 0.5 is the identity. The
// exponent is finite because b is kept inside (0, 1).
inline float bias(float x, float b) {
    x = clamp01(x);
    b = std::clamp(b, 1e-6f, 1.0f - 1e-6f);
    if (x <= 0.0f) return 0.0f;
    return pmath::pow(x, pmath::log(b) / pmath::log(0.5f));
}

// Perlin's gain through (0.5, 0.5): an S-curve, flat at both ends and steep in the middle, for
// g > 0.5; its inverse, steep at the ends, for g < 0.5.
inline float gain(float x, float g) {
    x = clamp01(x);
    if (x < 0.5f) return 0.5f * bias(2.0f * x, 1.0f - g);
    return 1.0f - 0.5f * bias(2.0f - 2.0f * x, 1.0f - g);
}

// Hermite smoothstep; with equal (or crossed) edges it is a step at e0 instead of 0/0.
inline float smoothstep(float e0, float e1, float x) {
    if (!(e1 > e0)) return x >= e0 ? 1.0f : 0.0f;
    float t = clamp01((x - e0) / (e1 - e0));
    return t * t * (3.0f - 2.0f * t);
}

}  // namespace pleinair
