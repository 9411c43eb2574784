// A canvas under the paint (issue 13 §3): a plain weave of slightly irregular threads in the
// picture plane, showing through where the paint is thin and catching the strokes' soft edges
// on the threads' crowns.
#pragma once

#include <cmath>
#include <cstdint>
#include <vector>

#include "shading/curves.h"
#include "shading/stroke_shader.h"

namespace pleinair {

// The weave's height, 0 (between threads) .. 1 (a thread's crown), tabulated over a 256 x 256
// pixel tile that repeats (a canvas is regular; 256 pixels hide the repeat under the paint).
struct CanvasWeave {
    static constexpr int kSize = 256;
    std::vector<float> height;
    float at(int x, int y) const {
        return height[static_cast<size_t>(y & (kSize - 1)) * kSize + (x & (kSize - 1))];
    }
};

// Threads thread_px wide: in each cell of the weave one thread lies on top (the warp and the
// weft alternate), rounded across its width; each thread's thickness varies a little by a
// hash of its index, as linen's does.
inline CanvasWeave make_canvas_weave(float thread_px) {
    CanvasWeave w;
    w.height.resize(CanvasWeave::kSize * CanvasWeave::kSize);
    const float t = std::max(thread_px, 3.0f);
    constexpr float kPi = 3.14159265358979f;
    for (int y = 0; y < CanvasWeave::kSize; ++y)
        for (int x = 0; x < CanvasWeave::kSize; ++x) {
            const float fx = (static_cast<float>(x) + 0.5f) / t,
                        fy = (static_cast<float>(y) + 0.5f) / t;
            const int i = static_cast<int>(fx), j = static_cast<int>(fy);
            // Which thread is on top here: the weft (along x) where the cell's parity says.
            const bool weft = ((i + j) & 1) != 0;
            const float across = weft ? fy - static_cast<float>(j) : fx - static_cast<float>(i);
            const int index = weft ? j : i;
            const float thick =
                0.75f + 0.5f * tree_hash01(static_cast<uint32_t>(index) * 2u + (weft ? 1u : 0u));
            const float s = clamp01(static_cast<float>(pmath::sin(kPi * across)));
            w.height[static_cast<size_t>(y) * CanvasWeave::kSize + x] =
                clamp01(static_cast<float>(pmath::pow(s, 1.0f / thick)) * (0.85f + 0.15f * thick));
        }
    return w;
}

// A stroke's coverage a at a pixel whose weave height is h: the soft edge (a between 0 and 1)
// is taken a little further on a crown and held back between threads; 0 and 1 stay.
inline float canvas_edge(float a, float h, float strength) {
    return clamp01(a * (1.0f + strength * (h - 0.5f) * 4.0f * (1.0f - a)));
}

// A pixel's colour with the canvas showing where the paint over it is thin: the weave's
// shadow and light, in proportion to the light the strokes let through (`thin`, 0 under full
// paint), and a trace of it everywhere (paint follows the canvas it lies on).
inline Color canvas_show(Color c, float h, float thin, float strength) {
    const float k = strength * (0.25f + 0.75f * clamp01(thin));
    return c * (1.0f + 0.5f * k * (h - 0.5f));
}

}  // namespace pleinair
