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

// The weave's height, 0 (between threads) .. 1 (a thread's crown), tabulated over a square
// tile that holds a whole number of the weave's periods (two threads), so it repeats without a
// seam; its side is near 256 pixels and the threads are widened or narrowed by under 2% to fit.
struct CanvasWeave {
    int side = 1;
    float thread = 1;  // the threads' width as fitted to the tile, pixels
    std::vector<float> height;
    float at(int x, int y) const {
        const int u = ((x % side) + side) % side, v = ((y % side) + side) % side;
        return height[static_cast<size_t>(v) * side + u];
    }
};

// Threads thread_px wide: in each cell of the weave one thread lies on top (the warp and the
// weft alternate), rounded across its width; each thread's thickness varies a little by a
// hash of its index, as linen's does.
inline CanvasWeave make_canvas_weave(float thread_px) {
    CanvasWeave w;
    const float want = std::max(thread_px, 3.0f);
    const int periods = std::max(1, static_cast<int>(256.0f / (2.0f * want) + 0.5f));
    w.side = std::max(6, static_cast<int>(2.0f * want * static_cast<float>(periods) + 0.5f));
    const float t = static_cast<float>(w.side) / (2.0f * static_cast<float>(periods));
    w.thread = t;
    w.height.resize(static_cast<size_t>(w.side) * w.side);
    constexpr float kPi = 3.14159265358979f;
    for (int y = 0; y < w.side; ++y)
        for (int x = 0; x < w.side; ++x) {
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
            w.height[static_cast<size_t>(y) * w.side + x] =
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
