// Gradient noise against an independent double-precision reference, its range and its edges.
#include "shading/noise.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace pleinair {
namespace {

// Textbook improved Perlin noise in double, written separately from shading/noise.h.
double ref_fade(double t) { return t * t * t * (t * (t * 6 - 15) + 10); }
double ref_grad2(int h, double x, double y) {
    static const double g[8][2] = {{1, 1}, {-1, 1}, {1, -1}, {-1, -1},
                                   {1, 0}, {-1, 0}, {0, 1},  {0, -1}};
    return g[h & 7][0] * x + g[h & 7][1] * y;
}
// The lattice hash, spelled out with 64-bit arithmetic reduced mod 2^32.
int H(int64_t x, int64_t y) {
    uint64_t h =
        ((uint64_t(x & 255) * 0x8DA6B343ull) ^ (uint64_t(y & 255) * 0xD8163841ull)) & 0xFFFFFFFFull;
    h ^= h >> 15;
    h = (h * 0x2C1B3C6Dull) & 0xFFFFFFFFull;
    h ^= h >> 12;
    return static_cast<int>(h & 7);
}
double ref_noise2(double x, double y) {
    int64_t X = static_cast<int64_t>(std::floor(x)), Y = static_cast<int64_t>(std::floor(y));
    double fx = x - std::floor(x), fy = y - std::floor(y);
    double u = ref_fade(fx), v = ref_fade(fy);
    double n00 = ref_grad2(H(X, Y), fx, fy), n10 = ref_grad2(H(X + 1, Y), fx - 1, fy);
    double n01 = ref_grad2(H(X, Y + 1), fx, fy - 1);
    double n11 = ref_grad2(H(X + 1, Y + 1), fx - 1, fy - 1);
    double a = n00 + u * (n10 - n00), b = n01 + u * (n11 - n01);
    return a + v * (b - a);
}

// Perlin's reference ImprovedNoise (2002) in double.
double ref_grad3(int h, double x, double y, double z) {
    h &= 15;
    double u = h < 8 ? x : y, v = h < 4 ? y : (h == 12 || h == 14 ? x : z);
    return ((h & 1) ? -u : u) + ((h & 2) ? -v : v);
}
int P(int i) { return noise_detail::kPerm256[i & 255]; }
double ref_noise3(double x, double y, double z) {
    int X = static_cast<int>(std::floor(x)) & 255, Y = static_cast<int>(std::floor(y)) & 255,
        Z = static_cast<int>(std::floor(z)) & 255;
    x -= std::floor(x), y -= std::floor(y), z -= std::floor(z);
    double u = ref_fade(x), v = ref_fade(y), w = ref_fade(z);
    int A = P(X) + Y, AA = P(A) + Z, AB = P(A + 1) + Z, B = P(X + 1) + Y, BA = P(B) + Z,
        BB = P(B + 1) + Z;
    auto L = [](double t, double a, double b) { return a + t * (b - a); };
    return L(
        w,
        L(v, L(u, ref_grad3(P(AA), x, y, z), ref_grad3(P(BA), x - 1, y, z)),
          L(u, ref_grad3(P(AB), x, y - 1, z), ref_grad3(P(BB), x - 1, y - 1, z))),
        L(v, L(u, ref_grad3(P(AA + 1), x, y, z - 1), ref_grad3(P(BA + 1), x - 1, y, z - 1)),
          L(u, ref_grad3(P(AB + 1), x, y - 1, z - 1), ref_grad3(P(BB + 1), x - 1, y - 1, z - 1))));
}

TEST(Noise, ThreeDMatchesPerlinsReference) {
    for (int i = 0; i < 2000; ++i) {
        float x = -20.0f + 0.0371f * i * 1.7f, y = 9.3f - 0.0219f * i, z = 0.013f * i * i * 0.01f;
        ASSERT_NEAR(signed_noise(x, y, z), ref_noise3(x, y, z), 2e-6) << x << ", " << y;
    }
}

TEST(Noise, MatchesAnIndependentReference) {
    for (int i = 0; i < 2000; ++i) {
        float x = -40.0f + 0.0371f * i * 3.1f, y = 17.3f - 0.0219f * i * 2.3f;
        ASSERT_NEAR(signed_noise(x, y), ref_noise2(x, y), 2e-6) << x << ", " << y;
    }
}

TEST(Noise, IsHalfAtLatticePointsAndStaysInZeroOne) {
    for (int i = -5; i < 5; ++i)
        for (int j = -5; j < 5; ++j) {
            EXPECT_EQ(noise(float(i), float(j)), 0.5f);
            EXPECT_EQ(noise(float(i), float(j), float(i + j)), 0.5f);
        }
    double sum = 0, lo = 1, hi = 0;
    const int n = 200000;
    for (int i = 0; i < n; ++i) {
        float x = 0.61803f * i, y = 0.41421f * i * 0.7f;
        float v2 = noise(x, y), v3 = noise(x, y, 0.3f * x);
        ASSERT_GE(v2, 0.0f);
        ASSERT_LE(v2, 1.0f);
        ASSERT_GE(v3, 0.0f);
        ASSERT_LE(v3, 1.0f);
        sum += v2, lo = std::min<double>(lo, v2), hi = std::max<double>(hi, v2);
    }
    EXPECT_NEAR(sum / n, 0.5, 0.01);
    EXPECT_LT(lo, 0.15);  // it uses its range, like RenderMan's noise
    EXPECT_GT(hi, 0.85);
}

TEST(Noise, IsContinuous) {
    for (int i = 0; i < 5000; ++i) {
        float x = 0.0137f * i, y = 3.0f + 0.0093f * i;
        EXPECT_LT(std::abs(noise(x + 1e-3f, y) - noise(x, y)), 5e-3f);
        EXPECT_LT(std::abs(noise(x, y, 1.5f + 1e-3f) - noise(x, y, 1.5f)), 5e-3f);
    }
}

TEST(Noise, FarAndNonFiniteInputsGiveFiniteValues) {
    const float inf = std::numeric_limits<float>::infinity();
    const float nan = std::numeric_limits<float>::quiet_NaN();
    for (float x : {1e9f, -1e9f, 3e38f, inf, -inf, nan}) {
        EXPECT_TRUE(std::isfinite(noise(x, 0.5f))) << x;
        EXPECT_TRUE(std::isfinite(noise(0.5f, x, x))) << x;
        EXPECT_TRUE(std::isfinite(fractal_noise(x, x, 4))) << x;
    }
    // Lattice periodicity: 256 apart is the same value.
    EXPECT_EQ(noise(3.25f, 7.75f), noise(3.25f + 256.0f, 7.75f));
}

TEST(Noise, OctavesAddDetailAndOneOctaveIsPlainNoise) {
    EXPECT_EQ(fractal_noise(1.3f, 2.7f, 1), noise(1.3f, 2.7f));
    EXPECT_EQ(fractal_noise(1.3f, 2.7f, 0), noise(1.3f, 2.7f));
    // More octaves: a larger share of the variation happens over short steps.
    auto roughness = [](int octaves) {
        double small = 0, large = 0;
        for (int i = 0; i < 4000; ++i) {
            float x = 0.05f * i;
            float n = fractal_noise(x, 0.3f, octaves);
            small += std::abs(fractal_noise(x + 0.05f, 0.3f, octaves) - n);
            large += std::abs(fractal_noise(x + 1.5f, 0.3f, octaves) - n);
        }
        return small / large;
    };
    EXPECT_GT(roughness(4), 1.3 * roughness(1));
    // The 3D form: plain noise at one octave, in 0..1, rougher with more.
    EXPECT_EQ(fractal_noise(1.3f, 2.7f, 0.4f, 1), noise(1.3f, 2.7f, 0.4f));
    auto roughness3 = [](int octaves) {
        double small = 0, large = 0;
        for (int i = 0; i < 4000; ++i) {
            float x = 0.05f * i;
            float n = fractal_noise(x, 0.3f, 0.7f, octaves);
            EXPECT_GE(n, 0.0f);
            EXPECT_LE(n, 1.0f);
            small += std::abs(fractal_noise(x + 0.05f, 0.3f, 0.7f, octaves) - n);
            large += std::abs(fractal_noise(x + 1.5f, 0.3f, 0.7f, octaves) - n);
        }
        return small / large;
    };
    EXPECT_GT(roughness3(4), 1.3 * roughness3(1));
}

}  // namespace
}  // namespace pleinair
