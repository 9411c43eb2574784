// The stroke kernel alone (shading/stroke_kernel.h): every row of a few hundred random sprites,
// small (1.5 to 6 px wide, a preview's or a far tree's strokes) or large (10 to 40 px, a near
// stroke at 1920x1080), at 1, 4 and 16 samples a pixel, on one core; in ns per pixel shaded,
// each row clipped to the sprite as the painter clips it.
// Only the public entry point is called, so the file builds against any version of the kernel
// (BENCHMARKS.md compares them in one run).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "generators/rng.h"
#include "shading/stroke_kernel.h"

using namespace pleinair;

namespace {

struct Sprite {
    StrokeConstants k;
    EdgeTable edge;
    StrokeRamp ramp;
    StrokeRow row;
};

// The sprites of a size class, as stroke_kernel_test draws them, with the shipped presets'
// feathers (0.34 to 0.40 under 0.48 to 0.60) and fullness (0.75 to 0.85).
std::vector<Sprite> sprites(bool large) {
    Palette pal;
    pal.dark = {{Color(0.02f, 0.03f, 0.01f), Color(0.05f, 0.06f, 0.02f)}};
    pal.mid = {{Color(0.1f, 0.12f, 0.05f), Color(0.2f, 0.22f, 0.1f)}};
    pal.light = {{Color(0.4f, 0.42f, 0.2f), Color(0.7f, 0.68f, 0.45f)}};
    Rng rng = make_rng(11, Purpose::kTree, large ? 2 : 1);
    std::vector<Sprite> out(large ? 60 : 600);
    for (size_t i = 0; i < out.size(); ++i) {
        Sprite& sp = out[i];
        StrokeShaderParams p;
        p.stroke_fullness = static_cast<float>(rand_range(rng, 0.75, 0.85));
        p.stroke_feather_min = static_cast<float>(rand_range(rng, 0.34, 0.40));
        p.stroke_feather_max =
            p.stroke_feather_min + static_cast<float>(rand_range(rng, 0.14, 0.2));
        p.max_stroke_opacity = 0.9f;
        p.sub_stroke_amt = 0.2f;
        sp.k = stroke_constants(p, static_cast<float>(rand1(rng)), static_cast<float>(rand1(rng)),
                                static_cast<float>(rand1(rng)), static_cast<float>(rand1(rng)),
                                static_cast<uint32_t>(i), 1.0f, 0.3f, 0.0f, false, false);
        sp.edge = make_edge_table(p.stroke_fullness);
        sp.ramp = make_ramp(sp.k, pal);
        StrokeRow& row = sp.row;
        row.cx = static_cast<float>(rand_range(rng, 0, 64));
        row.cy = static_cast<float>(rand_range(rng, 0, 64));
        const float half_w =
            0.5f * static_cast<float>(large ? rand_range(rng, 10, 40) : rand_range(rng, 1.5, 6));
        const float half_l = half_w * 1.4f;
        const float angle = static_cast<float>(rand_range(rng, 0, 6.28));
        const float ax = -std::sin(angle), ay = std::cos(angle);
        row.sx = ay / (2 * half_w), row.sy = -ax / (2 * half_w);
        row.txx = ax / (2 * half_l), row.tyy = ay / (2 * half_l);
        row.feather_min = p.stroke_feather_min, row.feather_max = p.stroke_feather_max;
        row.max_opacity = p.max_stroke_opacity, row.stroke_fullness = p.stroke_fullness;
        row.octaves = 1;
    }
    for (Sprite& sp : out) sp.row.k = &sp.k, sp.row.edge = &sp.edge, sp.row.ramp = &sp.ramp;
    return out;
}

// The pixels of row y that a sample of the sprite may reach, as the painter clips its rows
// (composite.cpp's row_span): where (s, t) at the pixel centre lies within half a pixel's
// change of the unit square.
bool row_span(const StrokeRow& row, int y, int& xa, int& xb) {
    const float dy = static_cast<float>(y) + 0.5f - row.cy;
    float lo = -1e30f, hi = 1e30f;
    for (const auto& [gx, gy] : {std::pair{row.sx, row.sy}, std::pair{row.txx, row.tyy}}) {
        const float c0 = 0.5f + dy * gy, slack = 0.5f * (std::abs(gx) + std::abs(gy));
        const float a = -slack - c0, b = 1.0f + slack - c0;
        if (gx > 0) {
            lo = std::max(lo, a / gx), hi = std::min(hi, b / gx);
        } else if (gx < 0) {
            lo = std::max(lo, b / gx), hi = std::min(hi, a / gx);
        } else if (!(a < 0 && b > 0)) {
            return false;
        }
    }
    if (!(hi >= lo)) return false;
    xa = std::max(xa, static_cast<int>(std::floor(lo + row.cx - 0.5f)));
    xb = std::min(xb, static_cast<int>(std::ceil(hi + row.cx - 0.5f)));
    return xa <= xb;
}

// range(0): samples per axis; range(1): 1 for large sprites.
void BM_StrokeKernel(benchmark::State& state) {
    std::vector<Sprite> all = sprites(state.range(1) != 0);
    for (Sprite& sp : all) sp.row.samples_per_axis = static_cast<int>(state.range(0));
    std::vector<float> a(kStrokeRowMax), r(kStrokeRowMax), g(kStrokeRowMax), b(kStrokeRowMax);
    std::vector<int> in(kStrokeRowMax);
    uint64_t pixels = 0;
    double shown = 0;
    for (auto _ : state) {
        for (const Sprite& sp : all) {
            const float half = 0.5f / std::min(std::hypot(sp.row.sx, sp.row.sy),
                                               std::hypot(sp.row.txx, sp.row.tyy));
            const int rad = static_cast<int>(std::ceil(half));
            const int x0 = static_cast<int>(sp.row.cx) - rad, count = 2 * rad + 1;
            for (int y = static_cast<int>(sp.row.cy) - rad; y <= static_cast<int>(sp.row.cy) + rad;
                 ++y) {
                int xa = x0, xb = x0 + count - 1;
                if (!row_span(sp.row, y, xa, xb)) continue;
                const int n = xb - xa + 1;
                shade_stroke_row(sp.row, y, xa, n, a.data(), r.data(), g.data(), b.data(),
                                 in.data());
                for (int c = 0; c < n; ++c) shown += a[c];
                pixels += static_cast<uint64_t>(n);
            }
        }
    }
    benchmark::DoNotOptimize(shown);
    state.counters["ns_per_pixel"] =
        benchmark::Counter(static_cast<double>(pixels) * 1e-9,
                           benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

}  // namespace

BENCHMARK(BM_StrokeKernel)
    ->ArgNames({"samples_per_axis", "large"})
    ->ArgsProduct({{1, 2, 4}, {0, 1}})
    ->Unit(benchmark::kMillisecond);
BENCHMARK_MAIN();
