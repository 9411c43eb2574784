// The per-fragment stroke kernel over one row of a sprite: stroke-mask coverage with n x n
// samples per pixel and the colour from the sprite's ramp. A scalar reference and a SIMD
// version (Google Highway, dispatched at run time to the best the CPU has) that computes the
// same bits.
#pragma once

#include <cstdint>

#include "shading/stroke_shader.h"

namespace pleinair {

// Everything the row kernel reads of one sprite.
struct StrokeRow {
    float cx = 0, cy = 0;                    // sprite centre, pixels
    float sx = 0, sy = 0, txx = 0, tyy = 0;  // d(s)/dx, d(s)/dy, d(t)/dx, d(t)/dy
    float feather_min = 0, feather_max = 1, max_opacity = 1;
    float stroke_fullness = 0.8f;
    int samples_per_axis = 1;  // 1, 2 or 4
    int octaves = 1;
    const StrokeConstants* k = nullptr;
    const EdgeTable* edge = nullptr;  // null: the exact edge mask (sin, pow); scalar only
    const StrokeRamp* ramp = nullptr;
};

// Shades pixels x0 .. x0 + count - 1 of row y. Per pixel: alpha (0 where no sample is inside
// or nothing shows), its colour (valid where alpha > 0, finite everywhere) and the number of
// samples inside the sprite (the fragments counted by the benchmarks). count <= kStrokeRowMax.
inline constexpr int kStrokeRowMax = 4096;
void shade_stroke_row(const StrokeRow& row, int y, int x0, int count, float* alpha, float* r,
                      float* g, float* b, int* inside);
// The scalar reference, pixel by pixel: the mean stroke opacity of pixel (x, y)'s n x n
// samples (0 when none lies inside the sprite), with the samples inside counted; and the
// pixel centre's (s, t), clamped to the sprite, where its colour is taken.
float stroke_coverage(const StrokeRow& row, int x, int y, int& inside);
void stroke_pixel_st(const StrokeRow& row, int x, int y, float& s, float& t);
void shade_stroke_row_scalar(const StrokeRow& row, int y, int x0, int count, float* alpha, float* r,
                             float* g, float* b, int* inside);

}  // namespace pleinair
