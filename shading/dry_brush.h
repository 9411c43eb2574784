// The dry-brush fade: a stroke fading with distance keeps its crisp edges and breaks into dabs,
// because the threshold on its noise rises, instead of turning transparent (which reads as
// blur). A table per shader maps the fade, the share of the stroke's covered area it keeps, to
// the threshold's rise, so a stroke at fade 1/2 covers half what it did.
#pragma once

#include <algorithm>
#include <array>

#include "shading/stroke_shader.h"

namespace pleinair {

struct DryBrushTable {
    static constexpr int kSize = 32;
    // The stroke's mean coverage with its thresholds raised by i / kSize of the way from
    // stroke_feather_min to 1 (where nothing passes): non-increasing, 0 at the end.
    std::array<float, kSize + 1> cover{};
};

// Measured once per shader over a 16 x 16 grid of the sprite, for 8 labels, at the frequency of
// a stroke of middling centre distance and lightness, and one octave.
inline DryBrushTable make_dry_brush_table(const StrokeShaderParams& p) {
    DryBrushTable t;
    constexpr int kGrid = 16, kLabels = 8;
    // A stroke of middling centre distance and lightness (IV.4.4's frequencies).
    const float f = stroke_frequency(p, 0.5f, 0.5f);
    for (int i = 0; i <= DryBrushTable::kSize; ++i) {
        const float rise =
            static_cast<float>(i) / DryBrushTable::kSize * (1.0f - p.stroke_feather_min);
        StrokeShaderParams q = p;
        q.stroke_feather_min += rise;
        q.stroke_feather_max += rise;
        double sum = 0;
        for (int l = 0; l < kLabels; ++l) {
            const float label = (l + 0.5f) / kLabels;
            const StrokeNoise n{f * p.s_frequ_scale, f * p.t_frequ_scale, 211.37f * label,
                                97.91f * label + 13.0f};
            for (int y = 0; y < kGrid; ++y)
                for (int x = 0; x < kGrid; ++x) {
                    const float s = (x + 0.5f) / kGrid, tt = (y + 0.5f) / kGrid;
                    const float e = stroke_noise(n, s, tt, 1) * edge_mask(s, tt, p.stroke_fullness);
                    sum += stroke_opacity(q, 1.0f, e);
                }
        }
        t.cover[i] = static_cast<float>(sum / (kGrid * kGrid * kLabels));
        if (i > 0) t.cover[i] = std::min(t.cover[i], t.cover[i - 1]);
    }
    t.cover[DryBrushTable::kSize] = 0.0f;
    return t;
}

// How far to raise the stroke's thresholds so it keeps `fade` (0..1) of its coverage: 0 at 1,
// 1 - stroke_feather_min (nothing passes) at 0.
inline float dry_brush_rise(const DryBrushTable& t, const StrokeShaderParams& p, float fade) {
    const float span = 1.0f - p.stroke_feather_min;
    if (!(fade < 1.0f)) return 0.0f;
    if (!(fade > 0.0f) || !(t.cover[0] > 0.0f)) return span;
    const float target = fade * t.cover[0];
    int i = 0;
    while (i < DryBrushTable::kSize && t.cover[i + 1] >= target) ++i;
    if (i == DryBrushTable::kSize) return span;
    const float a = t.cover[i], b = t.cover[i + 1];
    const float u = a > b ? (a - target) / (a - b) : 0.0f;
    return (static_cast<float>(i) + std::clamp(u, 0.0f, 1.0f)) / DryBrushTable::kSize * span;
}

}  // namespace pleinair
