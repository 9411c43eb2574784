// The compositing stage of a frame: the background, the underpainting under the strokes, then
// the sprites composited front to back under one another, tile by tile in parallel, each tile
// until the strokes already painted cover it.
#pragma once

#include <cstdint>

#include "pipeline/bin.h"
#include "pipeline/frame.h"
#include "pipeline/frame_plan.h"
#include "pipeline/sprites.h"

namespace pleinair {

struct Shot;
struct SceneDesc;
class RayScene;

// A frame of the camera's size: background everywhere, AOV buffers allocated when planned.
Frame make_frame(const Camera& cam, bool aovs);

// Sky and ground seen from the camera (or the canvas colour), with slow noise.
void paint_background(const SceneDesc& scene, const Camera& cam, Frame& frame);

// A flat palette colour and a depth where the camera sees terrain, water, rocks or trunks, at
// underpaint_scale of the resolution, so no sky shows between strokes. Coverage is
// interpolated, so silhouettes stay soft. Returns the camera rays traced.
uint64_t paint_underpainting(const Shot& shot, const FrameView& view, const FramePlan& plan,
                             const RenderSettings& settings, const RayScene* sun_rays,
                             Frame& frame);

// Composites the binned sprites over what the frame holds, nearest first, skipping pixels the
// nearer strokes already cover (less than 1/2048 of their light left); the result is the
// back-to-front "over" of every sprite to within that. Returns the fragments (pixel samples)
// shaded.
uint64_t paint_strokes(const Shot& shot, const SpriteSet& sprites, const TileBins& bins,
                       const FramePlan& plan, const RenderSettings& settings, Frame& frame);

}  // namespace pleinair
