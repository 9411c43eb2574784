// Gradient noise in 2D and 3D with RenderMan's range (0..1, 0.5 on average), deterministic on
// every platform: Perlin's improved noise (3D on his permutation, 2D on an integer hash of the
// lattice), in float, no library calls beyond floor.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>

namespace pleinair {

namespace noise_detail {

// Perlin's reference permutation (2002).
inline constexpr uint8_t kPerm256[256] = {
    151, 160, 137, 91,  90,  15,  131, 13,  201, 95,  96,  53,  194, 233, 7,   225, 140, 36,  103,
    30,  69,  142, 8,   99,  37,  240, 21,  10,  23,  190, 6,   148, 247, 120, 234, 75,  0,   26,
    197, 62,  94,  252, 219, 203, 117, 35,  11,  32,  57,  177, 33,  88,  237, 149, 56,  87,  174,
    20,  125, 136, 171, 168, 68,  175, 74,  165, 71,  134, 139, 48,  27,  166, 77,  146, 158, 231,
    83,  111, 229, 122, 60,  211, 133, 230, 220, 105, 92,  41,  55,  46,  245, 40,  244, 102, 143,
    54,  65,  25,  63,  161, 1,   216, 80,  73,  209, 76,  132, 187, 208, 89,  18,  169, 200, 196,
    135, 130, 116, 188, 159, 86,  164, 100, 109, 198, 173, 186, 3,   64,  52,  217, 226, 250, 124,
    123, 5,   202, 38,  147, 118, 126, 255, 82,  85,  212, 207, 206, 59,  227, 47,  16,  58,  17,
    182, 189, 28,  42,  223, 183, 170, 213, 119, 248, 152, 2,   44,  154, 163, 70,  221, 153, 101,
    155, 167, 43,  172, 9,   129, 22,  39,  253, 19,  98,  108, 110, 79,  113, 224, 232, 178, 185,
    112, 104, 218, 246, 97,  228, 251, 34,  242, 193, 238, 210, 144, 12,  191, 179, 162, 241, 81,
    51,  145, 235, 249, 14,  239, 107, 49,  192, 214, 31,  181, 199, 106, 157, 184, 84,  204, 176,
    115, 121, 50,  45,  127, 4,   150, 254, 138, 236, 205, 93,  222, 114, 67,  29,  24,  72,  243,
    141, 128, 195, 78,  66,  215, 61,  156, 180};

// Repeated once, so index arithmetic (i + 1, perm[i] + j) never wraps.
inline constexpr std::array<uint8_t, 512> kPerm = [] {
    std::array<uint8_t, 512> p{};
    for (int i = 0; i < 512; ++i) p[i] = kPerm256[i & 255];
    return p;
}();

inline float fade(float t) { return t * t * t * (t * (t * 6.0f - 15.0f) + 10.0f); }
inline float lerp(float a, float b, float t) { return a + t * (b - a); }

// Eight gradients of the square's edges and diagonals; the diagonals' length (sqrt 2) keeps the
// signed range at about [-1, 1]. As tables, so the vector kernel (stroke_kernel.cpp) gathers
// the same numbers and computes the same bits.
inline constexpr float kGrad2X[8] = {1, -1, 1, -1, 1, -1, 0, 0};
inline constexpr float kGrad2Y[8] = {1, 1, -1, -1, 0, 0, 1, -1};
inline float grad2(int h, float x, float y) { return kGrad2X[h & 7] * x + kGrad2Y[h & 7] * y; }

// Perlin's twelve cube-edge gradients (four repeated to make sixteen).
inline float grad3(int h, float x, float y, float z) {
    h &= 15;
    float u = h < 8 ? x : y;
    float v = h < 4 ? y : (h == 12 || h == 14 ? x : z);
    return ((h & 1) ? -u : u) + ((h & 2) ? -v : v);
}

// Lattice cell and fraction; the lattice repeats every 256 units.
inline int cell(float x, float& frac) {
    float f = std::floor(x);
    frac = x - f;
    // Wrapping through int64 keeps coordinates far from 0 (and NaN) well-defined.
    if (!(f > -1e9f && f < 1e9f)) {
        frac = 0.0f;
        return 0;
    }
    return static_cast<int>(static_cast<int64_t>(f) & 255);
}

}  // namespace noise_detail

namespace noise_detail {
// The 2D lattice's gradient choice: an integer hash of the corner instead of Perlin's
// permutation, because the vector kernel computes it in registers where the permutation
// would need six gathers per evaluation. Corners wrap at 256 like the permutation's lattice.
inline uint32_t lattice_hash(uint32_t x, uint32_t y) {
    uint32_t h = (x * 0x8DA6B343u) ^ (y * 0xD8163841u);
    h ^= h >> 15;
    h *= 0x2C1B3C6Du;
    h ^= h >> 12;
    return h;
}
}  // namespace noise_detail

// Signed 2D gradient noise, about [-1, 1], 0 at every lattice point.
inline float signed_noise(float x, float y) {
    using namespace noise_detail;
    float fx, fy;
    int X = cell(x, fx), Y = cell(y, fy);
    float u = fade(fx), v = fade(fy);
    uint32_t x0 = static_cast<uint32_t>(X), x1 = (x0 + 1) & 255u;
    uint32_t y0 = static_cast<uint32_t>(Y), y1 = (y0 + 1) & 255u;
    float n00 = grad2(static_cast<int>(lattice_hash(x0, y0) & 7u), fx, fy);
    float n10 = grad2(static_cast<int>(lattice_hash(x1, y0) & 7u), fx - 1.0f, fy);
    float n01 = grad2(static_cast<int>(lattice_hash(x0, y1) & 7u), fx, fy - 1.0f);
    float n11 = grad2(static_cast<int>(lattice_hash(x1, y1) & 7u), fx - 1.0f, fy - 1.0f);
    return lerp(lerp(n00, n10, u), lerp(n01, n11, u), v);
}

// Signed 3D gradient noise, about [-1, 1].
inline float signed_noise(float x, float y, float z) {
    using namespace noise_detail;
    float fx, fy, fz;
    int X = cell(x, fx), Y = cell(y, fy), Z = cell(z, fz);
    float u = fade(fx), v = fade(fy), w = fade(fz);
    int A = kPerm[X] + Y, AA = kPerm[A] + Z, AB = kPerm[A + 1] + Z;
    int B = kPerm[X + 1] + Y, BA = kPerm[B] + Z, BB = kPerm[B + 1] + Z;
    float x1 = fx - 1.0f, y1 = fy - 1.0f, z1 = fz - 1.0f;
    return lerp(
        lerp(lerp(grad3(kPerm[AA], fx, fy, fz), grad3(kPerm[BA], x1, fy, fz), u),
             lerp(grad3(kPerm[AB], fx, y1, fz), grad3(kPerm[BB], x1, y1, fz), u), v),
        lerp(lerp(grad3(kPerm[AA + 1], fx, fy, z1), grad3(kPerm[BA + 1], x1, fy, z1), u),
             lerp(grad3(kPerm[AB + 1], fx, y1, z1), grad3(kPerm[BB + 1], x1, y1, z1), u), v),
        w);
}

// RenderMan's noise(): 0..1, 0.5 at lattice points.
inline float noise(float x, float y) {
    float n = 0.5f + 0.5f * signed_noise(x, y);
    return n > 0.0f ? (n < 1.0f ? n : 1.0f) : 0.0f;
}
inline float noise(float x, float y, float z) {
    float n = 0.5f + 0.5f * signed_noise(x, y, z);
    return n > 0.0f ? (n < 1.0f ? n : 1.0f) : 0.0f;
}

// Octaves at doubling frequency and halving amplitude, normalised back to 0..1. Each octave is
// shifted so lattice points of different octaves do not line up. `octave(f, i)` is the signed
// noise of octave i at frequency f.
template <class Octave>
inline float fractal_sum(int octaves, Octave&& octave) {
    float sum = 0.0f, amp = 1.0f, norm = 0.0f, f = 1.0f;
    for (int i = 0; i < octaves; ++i) {
        sum += amp * octave(f, static_cast<float>(i));
        norm += amp;
        amp *= 0.5f;
        f *= 2.0f;
    }
    float n = 0.5f + 0.5f * sum / norm;
    return n > 0.0f ? (n < 1.0f ? n : 1.0f) : 0.0f;
}

// octaves <= 1 is plain noise.
inline float fractal_noise(float x, float y, int octaves) {
    if (octaves <= 1) return noise(x, y);
    return fractal_sum(octaves, [&](float f, float i) {
        return signed_noise(x * f + 17.17f * i, y * f + 31.31f * i);
    });
}

// The same over 3D noise (solid textures, displacement).
inline float fractal_noise(float x, float y, float z, int octaves) {
    if (octaves <= 1) return noise(x, y, z);
    return fractal_sum(octaves, [&](float f, float i) {
        return signed_noise(x * f + 17.17f * i, y * f + 31.31f * i, z * f + 43.43f * i);
    });
}

}  // namespace pleinair
