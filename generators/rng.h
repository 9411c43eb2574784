// Keyed random streams: every random choice in pleinair comes from an Rng built from a seed and
// stable keys, so adding a tree or a branch never changes the numbers another one draws.
#pragma once

#include <cmath>
#include <cstdint>

#include "shading/portable_math.h"

namespace pleinair {

// SplitMix64's finaliser: a bijective 64-bit mix with full avalanche.
constexpr uint64_t mix64(uint64_t x) {
    x += 0x9e3779b97f4a7c15ull;
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
    return x ^ (x >> 31);
}

// Hash of a seed and an ordered list of keys; order matters, (a, b) != (b, a).
constexpr uint64_t hash_keys(uint64_t seed) { return mix64(seed); }
template <class... Keys>
constexpr uint64_t hash_keys(uint64_t seed, uint64_t key, Keys... rest) {
    return hash_keys(mix64(seed) ^ (key * 0xd1b54a32d192ed03ull + 0x8cb92ba72f3d8dd7ull),
                     static_cast<uint64_t>(rest)...);
}

// What a stream is for; part of every key so two purposes never share numbers.
enum class Purpose : uint64_t {
    kTree = 1,   // per-tree samples (initial size, maximum height, ...)
    kTrunk = 2,  // per-step trunk samples
    kBranchDecide = 3,
    kBranchGrow = 4,
    kLeafDecide = 5,
    kLeafGrow = 6,
    kFamily = 7,      // member seeds of a family
    kLeafLimb = 8,    // per-limb leaf eligibility
    kBark = 9,        // bark stroke particles, per limb segment
    kTerrain = 10,    // terrain noise offsets
    kSurface = 11,    // surface stroke particles, per (surface, span u, span v)
    kScatter = 12,    // tree placement, per group
    kLeafLabel = 13,  // a leaf's label, per (emitter, step)
    kImported = 14,   // an imported particle's label and random normal, per (file, id)
    kGraftal = 15,    // graftal sites and tufts, per (object, site, use)
    kImposter = 16,   // graftal imposters: atlas variations, per (row, column)
    kSky = 17,        // the painted sky's strokes, per (layer, row, column)
    kFigure = 18,     // a figure's touches, per (figure seed, part)
};

// PCG32 (O'Neill 2014): small state, good statistics, and fully specified, so every platform
// draws the same numbers (the standard library's engines are, its distributions are not).
struct Rng {
    uint64_t state = 0;
    uint64_t inc = 1;
    double spare = 0;  // Box-Muller makes normals in pairs; the second waits here
    bool has_spare = false;
};

inline uint32_t next_u32(Rng& rng) {
    uint64_t old = rng.state;
    rng.state = old * 6364136223846793005ull + rng.inc;
    auto xorshifted = static_cast<uint32_t>(((old >> 18u) ^ old) >> 27u);
    auto rot = static_cast<uint32_t>(old >> 59u);
    return (xorshifted >> rot) | (xorshifted << ((32u - rot) & 31u));
}

template <class... Keys>
inline Rng make_rng(uint64_t seed, Purpose purpose, Keys... keys) {
    uint64_t h = hash_keys(seed, static_cast<uint64_t>(purpose), static_cast<uint64_t>(keys)...);
    Rng rng;
    rng.inc = (mix64(h ^ 0x5851f42d4c957f2dull) << 1u) | 1u;
    rng.state = h + rng.inc;
    next_u32(rng);
    return rng;
}

// Uniform double in [0, 1) with 53 random bits.
inline double rand1(Rng& rng) {
    uint64_t hi = next_u32(rng) >> 5;  // 27 bits
    uint64_t lo = next_u32(rng) >> 6;  // 26 bits
    return static_cast<double>((hi << 26) | lo) * 0x1.0p-53;
}

inline double rand_range(Rng& rng, double lo, double hi) { return lo + (hi - lo) * rand1(rng); }

// Standard normal by Box-Muller, one pair per four 32-bit draws: how far a stream has gone
// depends only on how many numbers were asked of it, never on their values.
inline double rand_gaussian(Rng& rng) {
    if (rng.has_spare) {
        rng.has_spare = false;
        return rng.spare;
    }
    double u1 = 1.0 - rand1(rng);  // (0, 1]: log is finite
    double u2 = rand1(rng);
    // pleinair's own log and sincos: libm's differ in the last bit between C libraries, and a
    // draw decides a branch.
    double radius = std::sqrt(-2.0 * pmath::log(u1));
    double s, c;
    pmath::sincos(2.0 * pmath::kPi * u2, s, c);
    rng.spare = radius * s;
    rng.has_spare = true;
    return radius * c;
}

}  // namespace pleinair
