// The SIMD row kernel gives the scalar reference's bits, over many sprites and settings.
#include "shading/stroke_kernel.h"

#include <gtest/gtest.h>
#include <hwy/targets.h>

#include <cmath>
#include <cstring>

#include "generators/rng.h"

namespace pleinair {
namespace {

void expect_vector_matches_scalar();

// Every SIMD target compiled in and supported by this CPU (on x86-64 with Highway 1.0.3: EMU128,
// SSSE3, SSE4, AVX2 and AVX-512).
TEST(StrokeKernel, VectorMatchesScalarBitForBitOnEveryTarget) {
    int targets = 0;
    for (int64_t target : hwy::SupportedAndGeneratedTargets()) {
        SCOPED_TRACE(hwy::TargetName(target));
        hwy::SetSupportedTargetsForTest(target);
        expect_vector_matches_scalar();
        ++targets;
    }
    hwy::SetSupportedTargetsForTest(0);
    EXPECT_GE(targets, 1);
}

void expect_vector_matches_scalar() {
    Palette pal;
    pal.dark = {{Color(0.02f, 0.03f, 0.01f), Color(0.05f, 0.06f, 0.02f)}};
    pal.mid = {{Color(0.1f, 0.12f, 0.05f), Color(0.2f, 0.22f, 0.1f)}};
    pal.light = {{Color(0.4f, 0.42f, 0.2f), Color(0.7f, 0.68f, 0.45f)}};
    Rng rng = make_rng(7, Purpose::kTree, 99);
    int rows = 0, lit = 0;
    for (int sprite = 0; sprite < 300; ++sprite) {
        StrokeShaderParams p;
        p.stroke_fullness = static_cast<float>(rand_range(rng, 0.05, 0.97));
        p.stroke_feather_min = static_cast<float>(rand_range(rng, 0.1, 0.6));
        p.stroke_feather_max =
            sprite % 7 == 0 ? p.stroke_feather_min
                            : p.stroke_feather_min + static_cast<float>(rand_range(rng, 0.0, 0.4));
        p.max_stroke_opacity = static_cast<float>(rand_range(rng, 0.5, 1.0));
        p.sub_stroke_amt = sprite % 5 == 0 ? 0.0f : static_cast<float>(rand_range(rng, 0.0, 0.3));
        p.unique_tint_amt = 0.1f;
        StrokeConstants k =
            stroke_constants(p, static_cast<float>(rand1(rng)), static_cast<float>(rand1(rng)),
                             static_cast<float>(rand1(rng)), static_cast<float>(rand1(rng)), sprite,
                             1.0f, 0.3f, 0.0f, true, true);
        EdgeTable edge = make_edge_table(p.stroke_fullness);
        StrokeRamp ramp = make_ramp(k, pal);
        StrokeRow row;
        row.cx = static_cast<float>(rand_range(rng, 0, 64));
        row.cy = static_cast<float>(rand_range(rng, 0, 64));
        float half_w = static_cast<float>(rand_range(rng, 0.3, 20)), half_l = half_w * 1.7f;
        float angle = static_cast<float>(rand_range(rng, 0, 6.28));
        float ax = -std::sin(angle), ay = std::cos(angle);
        row.sx = ay / (2 * half_w), row.sy = -ax / (2 * half_w);
        row.txx = ax / (2 * half_l), row.tyy = ay / (2 * half_l);
        row.feather_min = p.stroke_feather_min, row.feather_max = p.stroke_feather_max;
        row.max_opacity = p.max_stroke_opacity, row.stroke_fullness = p.stroke_fullness;
        row.samples_per_axis = 1 << (sprite % 3);
        row.octaves = sprite % 4 == 3 ? 3 : 1;
        row.k = &k, row.edge = &edge, row.ramp = &ramp;
        const int r = static_cast<int>(std::ceil(std::hypot(half_w, half_l)));
        const int x0 = static_cast<int>(row.cx) - r, count = 2 * r + 1;
        std::vector<float> a1(count), r1(count), g1(count), b1(count);
        std::vector<float> a2(count), r2(count), g2(count), b2(count);
        std::vector<int> i1(count), i2(count);
        for (int y = static_cast<int>(row.cy) - r; y <= static_cast<int>(row.cy) + r; ++y) {
            shade_stroke_row(row, y, x0, count, a1.data(), r1.data(), g1.data(), b1.data(),
                             i1.data());
            shade_stroke_row_scalar(row, y, x0, count, a2.data(), r2.data(), g2.data(), b2.data(),
                                    i2.data());
            ASSERT_EQ(i1, i2) << sprite << " " << y;
            // A run starting anywhere in the row, of any length (the painter shades the runs of
            // pixels still open): the vector kernel's lanes fall differently, the bits do not.
            const int a = static_cast<int>(rand_range(rng, 0, count - 1));
            const int len = 1 + static_cast<int>(rand_range(rng, 0, count - a - 1));
            std::vector<float> a3(len), r3(len), g3(len), b3(len);
            std::vector<int> i3(len);
            shade_stroke_row(row, y, x0 + a, len, a3.data(), r3.data(), g3.data(), b3.data(),
                             i3.data());
            for (int c = 0; c < len; ++c) {
                ASSERT_EQ(i3[c], i2[a + c]) << sprite << " " << y << " " << a + c;
                ASSERT_EQ(0, std::memcmp(&a3[c], &a2[a + c], sizeof(float))) << sprite << " " << y;
                if (a3[c] > 0) {
                    ASSERT_EQ(r3[c], r2[a + c]) << sprite;
                }
            }
            ASSERT_EQ(0, std::memcmp(a1.data(), a2.data(), count * sizeof(float)))
                << sprite << " " << y;
            for (int c = 0; c < count; ++c) {
                if (!(a1[c] > 0)) continue;
                ++lit;
                ASSERT_EQ(r1[c], r2[c]) << sprite;
                ASSERT_EQ(g1[c], g2[c]) << sprite;
                ASSERT_EQ(b1[c], b2[c]) << sprite;
            }
            ++rows;
        }
    }
    EXPECT_GT(rows, 1000);
    EXPECT_GT(lit, 10000);  // the comparison saw painted fragments, not only empty ones
}

}  // namespace
}  // namespace pleinair
