// The compositing stage of a frame: the sprites composited nearest first, tile by tile in
// parallel, each pixel until the strokes already painted cover it; then the background and the
// underpainting where light still gets through; then the strokes over them.
#pragma once

#include <cstdint>

#include "pipeline/frame/buffer_pool.h"
#include "pipeline/frame/frame_context.h"
#include "pipeline/frame/frame_image.h"
#include "pipeline/frame/frame_plan.h"
#include "pipeline/frame/sprites.h"
#include "pipeline/frame/tile_bins.h"

namespace pleinair {

struct Shot;
struct SceneDesc;
class RayScene;

// A frame of the camera's size, all zero, AOV buffers allocated when planned; its image from
// `pool` when given.
Frame make_frame(const Camera& cam, bool aovs, BufferPool* pool = nullptr);

// The strokes of a frame composited front to back, before what lies under them: per pixel the
// premultiplied colour gathered and the light still let through (1 where no stroke is).
struct StrokeLayer {
    int width = 0, height = 0;
    float cutoff = 0;            // render/coverage_cutoff
    std::vector<float> color;    // 3 per pixel
    std::vector<float> through;  // 1 per pixel
    // Pigment mixing (FramePlan::pigment): 4 pigment concentrations gathered per pixel, their
    // residual colour gathered in `color` (shading/pigment.h); empty otherwise.
    std::vector<float> pigment;
    uint64_t fragments = 0;  // pixel samples shaded
    // Traced frames only (FramePlan::trace): per pixel the sprite indices of the two nearest
    // strokes more than 5% opaque there, ~0u for none, and the weight of the first's order
    // when the two were blended as their eye distances crossed (1 when not).
    std::vector<uint32_t> first, second;
    std::vector<float> first_weight;
    // Nothing under the strokes can change the pixel by more than the cutoff.
    bool covered(size_t pixel) const { return !(through[pixel] > cutoff); }
};

// Composites the binned sprites nearest first, skipping pixels the nearer strokes already
// cover (at most coverage_cutoff of their light left); while the camera moves, strokes whose
// eye distances cross blend from one order to the other over render/order_blend_frames
// (composite.cpp: TileLayer). Fills the AOVs of the nearest stroke more than half opaque when
// the plan asks.
// `progress`, when set, hears ("paint", done) at each whole percent of the tiles.
// `behind`, when set, is a layer these strokes lie behind: they are painted only where it
// leaves light through (the painted sky behind every other stroke). The layer's colour and light
// come from `pool` when given (give_back returns them). A stroke whose narrower half-width on
// screen is at least `one_sample_px` (0: none) is painted at one sample a pixel, its feather
// filtered, whatever settings.samples says: a large stroke's noise spans pixels, and the filter
// stands in for the samples.
StrokeLayer paint_strokes(const Shot& shot, const SpriteSet& sprites, const TileBins& bins,
                          const FramePlan& plan, const RenderSettings& settings, Frame& frame,
                          const std::function<void(const char*, double)>* progress = nullptr,
                          const StrokeLayer* behind = nullptr, BufferPool* pool = nullptr,
                          float one_sample_px = 0.0f);
// The layer's colour and light handed to `pool` (none: nothing happens).
void give_back(StrokeLayer& layer, BufferPool* pool);

// The strokes over what the frame holds beneath them: equal to compositing every stroke, the
// underpainting and the background back to front with "over", to within the cutoff.
// With pigment mixing (plan.pigment) the strokes' paint and what lies under it mix as
// pigments; with a canvas (plan.canvas) its weave shows where the paint is thin.
void composite_strokes(const StrokeLayer& strokes, const FramePlan& plan,
                       const RenderSettings& settings, Frame& frame);

// The paint stage: the strokes front to back into their layer, the fragments in the report.
// Strokes first, nearest first: the background and underpainting are then needed only where
// the strokes leave some light through.
StrokeLayer paint_stage(const FrameContext& ctx, const SpriteSet& sprites, const TileBins& bins,
                        Frame& frame);

// The composite stage: composite_strokes over what the frame holds.
void composite_stage(const FrameContext& ctx, const StrokeLayer& strokes, Frame& frame);

}  // namespace pleinair
