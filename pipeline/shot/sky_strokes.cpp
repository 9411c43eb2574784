// build_sky_strokes: the sky's directions, rows of equal angular height, a jittered place a cell.
#include "pipeline/shot/sky_strokes.h"

#include <algorithm>
#include <cmath>

#include "generators/rng.h"
#include "shading/portable_math.h"

namespace pleinair {

namespace {

constexpr double kPi = 3.14159265358979323846;
// The lowest row: a little under the horizon, so strokes reach the horizon's haze (the
// background keeps them off the ground, frame/composite.cpp).
constexpr double kLowest = -0.03;
// Cells are 0.55 of a stroke in each direction: every point of the sky under about three.
constexpr double kSpacing = 0.55;

}  // namespace

SkyStrokes build_sky_strokes(const SceneDesc& scene) {
    SkyStrokes out;
    const SkyDesc& sky = scene.sky;
    if (!sky.present || scene.background.canvas) return out;
    const SkyParams& p = sky.params;
    const double aspect = std::max<double>(sky.shader.stroke_aspect, 0.1);
    for (int layer = 0; layer < (p.detail > 0 ? 2 : 1); ++layer) {
        const double length = p.stroke_size * kPi / 180.0 * (layer ? 0.5 : 1.0);
        const double row = kSpacing * length / aspect, col = kSpacing * length;
        const int rows = static_cast<int>(std::ceil((0.5 * kPi - kLowest) / row));
        for (int r = 0; r < rows; ++r) {
            const double e0 = kLowest + r * row;
            const double mid = std::min(e0 + 0.5 * row, 0.5 * kPi);
            const int cols =
                std::max(1, static_cast<int>(std::lround(2 * kPi * pmath::cos(mid) / col)));
            for (int c = 0; c < cols; ++c) {
                Rng rng = make_rng(sky.seed, Purpose::kSky, layer, r, c);
                const double e = std::min(e0 + rand1(rng) * row, 0.5 * kPi);
                const double az = (c + rand1(rng)) * 2 * kPi / cols;
                const double ce = pmath::cos(e);
                out.direction.emplace_back(ce * pmath::sin(az), pmath::sin(e),
                                           -ce * pmath::cos(az));
                out.label.push_back(static_cast<float>(rand1(rng)));
                out.small.push_back(static_cast<uint8_t>(layer));
            }
        }
    }
    return out;
}

}  // namespace pleinair
