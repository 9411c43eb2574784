// A frame as a pure function of (shot, view, settings): paint_frame calls the frame's stages in
// order (plan, sprites, depth order and tiles, strokes nearest first, then the background and
// underpainting where the strokes leave light through, composite); the same inputs give the
// same bytes on any number of threads, in any frame order.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "pipeline/frame/frame_image.h"
#include "pipeline/frame/frame_plan.h"
#include "pipeline/frame/frame_report.h"
#include "pipeline/frame/frame_view.h"
#include "pipeline/frame/sprites.h"
#include "pipeline/input/frame_range.h"
#include "pipeline/shot/pass_report.h"
#include "pipeline/shot/shot.h"

namespace pleinair {

// A traced frame (FrameSettings::trace): the frame's sprites, each pixel's two nearest strokes
// (indices into them, ~0u for none), the weight of the first's order (StrokeLayer) and the
// light the strokes leave through.
struct FrameTrace {
    std::vector<Sprite> sprites;
    std::vector<uint32_t> first, second;
    std::vector<float> first_weight;
    std::vector<float> through;
};

// The frame settings a scene file asks for.
FrameSettings scene_frame_settings(const SceneDesc& scene, bool aovs = false);

// The bytes a frame's image buffers hold at once: the frame (RGBA in float, 16 a pixel, 32 with
// AOVs), the strokes' colour and light left (16), the underpainting (20 at its scale, squared)
// and the output's converted copy (`output_bytes`); what a command checks against
// --limit memory_mb before any work. Sprites and the shot come on top, and grow with the scene,
// not the image.
uint64_t frame_buffer_bytes(int width, int height, bool aovs, float underpaint_scale,
                            double output_bytes);

Frame paint_frame(const Shot& shot, const FrameView& view, const FrameSettings& settings,
                  FrameReport* report = nullptr);

// A still: the scene's shot, one frame of it with the scene's camera and settings.
Frame paint_still(const SceneDesc& scene, bool aovs = false, FrameReport* report = nullptr);
// The same with trees built by the caller and no landscape.
Frame paint_still(const SceneDesc& scene, std::vector<BuiltTree> trees, bool aovs = false,
                  FrameReport* report = nullptr);

}  // namespace pleinair
