// The level-of-detail stage of a frame (thesis IV.6): each tree's distance values from the
// camera's circles, how much of its foliage remains and how much the survivors grow, and the
// per-stroke fades the sprites stage applies.
#pragma once

#include <cstdint>
#include <glm/vec3.hpp>
#include <vector>

#include "pipeline/distance_circles.h"
#include "pipeline/settings.h"

namespace pleinair {

struct Shot;
struct FrameView;
struct Camera;

struct TreeLod {
    float leaf = 0;    // the leaves' distance value at the tree's centre: 0 full detail, 1 least
    float trunk = 0;   // the bark's: strokes on twigs fade towards 1
    float kept = 1;    // the mean opacity of its leaves at `leaf` (Cook et al.'s u)
    float growth = 1;  // each surviving leaf stroke's linear scale: 1 / sqrt(kept), bounded
    // Survivors move out from the centre locator to fill the crown's extent direction by
    // direction (the thesis's survivors only grew, so its far trees shrank to their core):
    // per bin of directions (kElevationBins x kAzimuthBins), the ratio of the RMS distance of
    // all the tree's leaves to that of its survivors, weighted by their opacity.
    glm::vec3 center{0.0f};
    std::vector<float> radial;  // empty: nothing moves
};

// What the sprites stage needs to know of the level of detail, for one frame.
struct FrameLod {
    bool leaves = false;      // leaves fade by their thresholds, survivors grow
    bool trunks = false;      // bark strokes on twigs cross-fade to the low-detail model
    bool surfaces = false;    // surface detail strokes fade with the leaf circles
    bool near_field = false;  // foliage opens up near the camera
    DistanceCircles circles;
    float fade_gain = 0.5f;
    std::vector<TreeLod> trees;  // one per tree, when leaves or trunks
};

// The frame's level of detail: off (every flag false) when the settings turn it off or the view
// carries no circles. Pure: a function of the shot, the view and the settings.
FrameLod level_of_detail(const Shot& shot, const FrameView& view, const RenderSettings& settings);

// Whether the scene carries circles anywhere (on the camera or on its track's keys).
bool scene_has_circles(const Shot& shot);

// Depth of a world point along the camera's view axis (the plane through the eye).
double view_depth(const Camera& cam, const glm::dvec3& world);

constexpr int kElevationBins = 6, kAzimuthBins = 12;

// Where a surviving leaf at p (tree-local) is painted: moved along its direction from the
// centre by the bins' ratios, interpolated bilinearly over directions so no leaf jumps.
glm::vec3 spread_leaf(const TreeLod& t, const glm::vec3& p);

// A leaf's opacity at its tree's distance value: 1 up to fade_begin, 0 from fade_end, eased
// between by Perlin's gain (IV.6); a step at fade_begin when the two are equal.
float leaf_fade(float value, float fade_begin, float fade_end, float gain);

// A bark stroke's opacity at its tree's trunk distance value: strokes on the trunk and first
// branches (the low-detail model) stay; deeper limbs' strokes fade, each over its own span of
// 0.4 starting between 0 and 0.6 (drawn from its label), so the model cross-fades.
float bark_fade(float trunk_value, int limb_level, float label, float gain);

// A leaf's size factor in the near field (value from near_field_value): interior leaves (small
// centre distance) shrink away first, each from its own threshold; outer ones stay, so the
// crown keeps its shape while the viewer sees into it. Below kThinnedOut the leaf is gone.
float near_field_fade(float near_value, float center_distance, float label, float gain);

// How much strokes shrink in the near field (1 at its circle, 0.6 at the camera), so they
// separate instead of blurring into large blobs (V.3).
constexpr float kThinnedOut = 0.05f;
inline float near_field_scale(float near_value) { return 1.0f - 0.4f * near_value; }

}  // namespace pleinair
