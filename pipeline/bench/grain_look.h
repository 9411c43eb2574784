// Which way a region's touches run (issue 52 §3 and §7): the ground laid in horizontal touches
// that follow the land, or dotted with round spots that run no way at all.
#pragma once

#include <cstdint>
#include <vector>

namespace pleinair {

// The grain of a region's paint from the direction of its edges. At each pixel of the mask
// whose 3 x 3 neighbourhood lies in it, L*'s Sobel gradient gives an edge running across the
// gradient; each edge weighs by the gradient's length, so a touch's edge counts and the noise
// of a flat patch barely does.
// - horizontal: the weight of edges within kGrainTolerance degrees of horizontal over all; a
//   field of touches laid flat scores near 1, round spots (edges every way) 1/3, upright
//   strokes (grass blades, or leaves that read as rain) near 0.
// - coherence: how much the edges agree on one direction, |sum w e^{2 i phi}| / sum w over the
//   edges' angles phi (doubled: an edge has no sense), 1 when they all run one way, 0 for
//   round spots; `angle` is that direction in degrees from horizontal, counter-clockwise.
struct GrainLook {
    double horizontal = 0;
    double coherence = 0;
    double angle = 0;
    uint64_t pixels = 0;  // pixels measured
};
inline constexpr double kGrainTolerance = 30.0;
GrainLook grain_look(const std::vector<float>& lightness, int width, int height,
                     const std::vector<uint8_t>& mask);

}  // namespace pleinair
