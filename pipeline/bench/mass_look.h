// A painted frame's plan as a painter judges it from across the room (issue 52 §7): whether a
// region's texture repeats as a tiled motif does, and how many distinct values the frame holds
// once blurred down to its masses.
#pragma once

#include <cstdint>
#include <vector>

namespace pleinair {

// How a region's texture repeats: the masked autocorrelation of its L*, local mean removed, at
// offsets beyond the central lobe (the offsets joined to zero through positive correlation).
// A tiled motif correlates fully with itself one tile away (score 1); a varied texture such as
// 1/f noise keeps nothing beyond its own lobe (score near 0.05). The frame is first reduced so
// its width is about kRepeatWidth (the pattern a viewer sees across the picture, not a stroke's
// bristles), and offsets reach a quarter of the reduced frame each way while the overlap keeps
// at least half the region (a motif must recur across half of it to be wallpaper).
struct RepeatLook {
    double score = 0;     // the highest correlation outside the central lobe; 0 when none
    int dx = 0, dy = 0;   // where it lies, in full-size pixels
    uint64_t pixels = 0;  // reduced pixels of the region measured
};
inline constexpr int kRepeatWidth = 240;
RepeatLook texture_repeat(const std::vector<float>& lightness, int width, int height,
                          const std::vector<uint8_t>& mask);

// The frame's values at the scale of its masses: L* blurred by three box passes of 1/30 of the
// width (about what a painter sees squinting at the picture), its histogram, and the modes that
// stand apart: a valley between two modes must fall under half the lower one, else they are one
// value spread out. A mode counts when it holds at least kValueMinShare of the frame. Three
// flat masses are three values; a smooth gradient, or masses mushed into one another, is one.
struct ValueMasses {
    int values = 0;              // the distinct values
    std::vector<double> modes;   // their L*, darkest first
    std::vector<double> shares;  // the frame's share in each one's basin
};
inline constexpr double kValueMinShare = 0.03;
ValueMasses value_masses(const std::vector<float>& lightness, int width, int height);

// L* blurred by three box passes of radius r (each a (2 r + 1) wide box, clamped at the
// frame's edges): close to a Gaussian of sigma r.
std::vector<float> blur_box3(const std::vector<float>& lightness, int width, int height, int r);

}  // namespace pleinair
