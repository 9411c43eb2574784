// The wind stage of a frame: each tree posed by the scene's wind at the frame's time and one
// frame later (generators/wind.h), how far the wind reaches into it by its distance, and the
// move of one particle that the sprites stage applies.
#pragma once

#include <cstddef>
#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>
#include <vector>

#include "generators/wind.h"
#include "pipeline/frame/frame_context.h"
#include "pipeline/frame/lod.h"

namespace pleinair {

struct Shot;

struct FrameWind {
    bool on = false;
    // Per tree: its pose now, one frame before and one frame later (they tell how fast each
    // stroke moves into and out of this frame, for the soft depth order), at rest where the
    // wind does not reach.
    std::vector<TreePose> now, before, next;
    std::vector<float> reach;  // per tree: no particle moves farther from rest (world units)
};

// How far the wind reaches into tree i (WindTiers) from its leaves' distance value (lod.h):
// the whole tree sways at any distance; its limbs up to the value 0.55, fading out by 1 (the
// far circle); its leaves' flutter up to 0, fading out by 0.3. The values are replayed along
// the track and change by at most a fade's worth a frame, so a tree crossing a circle blends.
// Every level where the frame has no level of detail.
WindTiers wind_tiers(const FrameLod& lod, size_t tree);

// The poses of every tree at `time` (seconds on the shot's clock), one frame before and one
// frame later. Pure.
FrameWind frame_wind(const Shot& shot, double time, const FrameLod& lod);

// The stage: frame_wind at the view's time, timed and described for --explain; off (no pose)
// when the shot has no wind or the settings turn it off.
FrameWind wind_stage(const FrameContext& ctx, const FrameLod& lod);

// What the wind does to one particle of a tree: its move (world), the turn of its directions
// (world), the farther it moves into or out of this frame (world units) and, for a leaf, the
// turn of its stroke about its normal (radians).
struct WindMove {
    glm::dvec3 delta{0.0};
    glm::mat3 turn{1.0f};
    float speed = 0;
    float spin = 0;
    bool moved = false;
};
// Particle j of kind `kind` (bark or leaf) of tree `item`, at rest at tree-local `local`.
WindMove wind_move(const Shot& shot, const FrameWind& wind, size_t item, bool leaf, size_t j,
                   const glm::vec3& local, float label);

}  // namespace pleinair
