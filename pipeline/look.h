// Measures of a painted frame's look (issue 13 §6), computed from its pixels and AOVs: how much
// brush texture a region carries, whether a smooth region bands in 8-bit output, and how well
// water mirrors the bank above it.
#pragma once

#include <cstdint>
#include <vector>

#include "pipeline/frame.h"

namespace pleinair {

struct Shot;
struct FrameView;

// Per pixel, CIE L* (0..100) of a frame's linear colour.
std::vector<float> frame_lightness(const Frame& frame);

// Brush texture at a scale: the RMS over the pixels of `mask` of L*'s standard deviation in
// the (2 radius + 1)^2 window around each, counting only windows wholly inside the mask (a
// region's edges would count as texture); 0 when none is. Radius 2 sees the edges of small
// dabs, 8 those of broad strokes. `count`, when given, receives the pixels measured.
double brush_texture(const std::vector<float>& lightness, int width, int height,
                     const std::vector<uint8_t>& mask, int radius, uint64_t* count = nullptr);

// Banding: along rows of `mask`, the mean length of runs of pixels whose 8-bit sRGB colour is
// the same; a smooth gradient quantised to 8 bits makes long runs (bands), brush strokes short.
double mean_flat_run(const Frame& frame, const std::vector<uint8_t>& mask);

// The regions of a painted frame (AOVs required): sky (no surface or stroke with an id, the
// ray above the horizon), trees (leaf and bark strokes), and water (camera rays that meet the
// water's mesh first; empty when the shot has no camera scene or no water).
struct LookRegions {
    std::vector<uint8_t> sky, trees, water;
};
LookRegions look_regions(const Shot& shot, const FrameView& view, const Frame& frame);

// The Pearson correlation of L* between each water pixel and the pixel mirrored about its
// column's shore (the topmost water pixel): (x, y) against (x, 2 shore - 1 - y), over the pairs
// whose mirrored pixel is inside the frame and not water. 0 when fewer than 16 pairs.
double mirror_correlation(const std::vector<float>& lightness, int width, int height,
                          const std::vector<uint8_t>& water, uint64_t* pairs = nullptr);

}  // namespace pleinair
