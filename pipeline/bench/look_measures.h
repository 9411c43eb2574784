// Measures of a painted frame's look (issue 13 §6), computed from its pixels and AOVs: how much
// brush texture a region carries, whether a smooth region bands in 8-bit output, and how well
// water mirrors the bank above it (about its shore's row, and as a flat mirror does), and
// whether the open sky keeps to its palette.
#pragma once

#include <cstdint>
#include <vector>

#include "pipeline/frame/frame_image.h"
#include "pipeline/input/camera.h"
#include "pipeline/input/scene.h"

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

// The share of the windows brush_texture measures whose L* spreads (standard deviation) less
// than `max_spread`: paint left smooth at that scale, a soft blob's inside rather than a brush's
// marks.
double smooth_share(const std::vector<float>& lightness, int width, int height,
                    const std::vector<uint8_t>& mask, int radius, double max_spread);

// Banding: along rows of `mask`, the mean length of runs of pixels whose 8-bit sRGB colour is
// the same; a smooth gradient quantised to 8 bits makes long runs (bands), brush strokes short.
double mean_flat_run(const Frame& frame, const std::vector<uint8_t>& mask);

// The regions of a painted frame (AOVs required): sky (no surface or stroke with an id, the
// ray above the horizon), trees (leaf and bark strokes), and water (camera rays that meet the
// water's mesh first; empty when the shot has no camera scene or no water).
struct LookRegions {
    std::vector<uint8_t> sky, trees, water;
    // The near ground: camera rays that meet the terrain within kNearGround and whose pixel a
    // ground stroke paints (a meadow's foreground, issue 27 §4).
    std::vector<uint8_t> near_ground;
};
// Metres from the eye: the ground a walker sees at their feet and a few steps on, where Corot's
// strokes are broadest.
inline constexpr double kNearGround = 15.0;

// The object id a scene's water strokes carry in the frame's AOV.
float water_stroke_id(const SceneDesc& scene);
LookRegions look_regions(const Shot& shot, const FrameView& view, const Frame& frame);

// The Pearson correlation of L* between each water pixel and the pixel mirrored about its
// column's shore (the topmost water pixel): (x, y) against (x, 2 shore - 1 - y), over the pairs
// whose mirrored pixel is inside the frame and not water. 0 when fewer than 16 pairs.
double mirror_correlation(const std::vector<float>& lightness, int width, int height,
                          const std::vector<uint8_t>& water, uint64_t* pairs = nullptr);

// What a flat mirror shows at each water pixel: the frame's own pixels above the water, each at
// its depth mirrored about the water's plane (height `level`) and projected back into the frame;
// the nearest wins where several land on one pixel, and each also fills the pixel below it (a
// mirrored row may stretch by one). The sources are the pixels off `water`; the targets those on
// it whose nearest stroke has `water_id` (not the bank's grass painted over its edge). Per pixel
// the source's index + 1, 0 where none lands or off the targets. Unlike the mirror about the
// shore's row, this is where a glass mirror puts the bank whatever stands behind the shore: a
// perfect mirror scores 1 against it (issue 27 §3).
std::vector<uint32_t> mirror_sources(const Frame& frame, const Camera& camera, double level,
                                     const std::vector<uint8_t>& water, float water_id);

// The side of the square blocks over which mirror_match compares forms: at 1920x1080 about a
// trunk's width across the pond, finer than a far crown, coarser than a water stroke's height.
inline constexpr int kMirrorBlock = 8;

// How the water's paint matches what it mirrors (mirror_sources), over the water pixels that
// have a source.
struct MirrorMatch {
    double pixels = 0;     // Pearson correlation of L*, each water pixel against its source
    double forms = 0;      // the same between kMirrorBlock blocks' means (blocks half matched)
    double lightness = 0;  // mean L* of the water pixels over their sources'
    double chroma = 0;     // mean CIELAB chroma of the water pixels over their sources'
    uint64_t pairs = 0;
};
MirrorMatch mirror_match(const Frame& frame, const std::vector<float>& lightness,
                         const std::vector<uint32_t>& sources);

// What colour a day sky may take (sRGB, per channel): the least and the most over the sky
// palette's colours, the background's sky gradient and, under a painted sky, the shader's
// distance hue (its strokes lie at infinity). A sky painted black and white where its palette
// is pale blue lies far outside it (issue 24).
struct SkyGamut {
    float lo[3] = {1, 1, 1}, hi[3] = {0, 0, 0};
};
SkyGamut sky_gamut(const SceneDesc& scene);

// The pixels of `mask` whose sRGB colour lies outside `gamut` widened by `margin` in any
// channel.
uint64_t pixels_outside(const Frame& frame, const std::vector<uint8_t>& mask, const SkyGamut& gamut,
                        float margin);

// The open sky of a frame, from its AOVs and the camera alone: look_regions' sky (no stroke or
// surface with an id in front, the underpainting's far depth, the ray above the horizon) with
// no more than 2% of other strokes' paint over it (a crown's thin edges have no id).
std::vector<uint8_t> sky_region(const Camera& camera, const Frame& frame);

}  // namespace pleinair
