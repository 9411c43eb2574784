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
#include "pipeline/input/frame_range.h"
#include "pipeline/shot/pass_report.h"
#include "pipeline/shot/shot.h"
#include "pipeline/frame/sprites.h"

namespace pleinair {

struct FrameReport {
    std::vector<PassReport> decisions;  // the plan's, with no time of their own
    std::vector<PassReport> passes;
    uint64_t leaf_sprites = 0, bark_sprites = 0, surface_sprites = 0, culled = 0;
    uint64_t graftal_sprites = 0;   // graftals drawn (graftal_stage.h)
    uint64_t imposter_sprites = 0;  // imposters drawn (imposter_stage.h)
    uint64_t sky_sprites = 0;       // strokes of the painted sky in view (sky_sprites.h)
    uint64_t reflection_rays = 0;   // cast for still water's mirror (reflection.h)
    uint64_t shadow_rays = 0, underpaint_rays = 0;
    uint64_t fragments = 0;  // pixel samples evaluated by the stroke shader
    // Traced frames only (FrameSettings::trace): the frame's sprites, each pixel's two nearest
    // strokes (indices into them, ~0u for none), the weight of the first's order (StrokeLayer)
    // and the light the strokes leave through.
    struct Trace {
        std::vector<Sprite> sprites;
        std::vector<uint32_t> first, second;
        std::vector<float> first_weight;
        std::vector<float> through;
    };
    std::shared_ptr<Trace> trace;
};

// The frame settings a scene file asks for.
FrameSettings scene_frame_settings(const SceneDesc& scene, bool aovs = false);

// The view of a still: the scene's camera and sun.
FrameView still_view(const SceneDesc& scene);

// The view at t seconds: the camera track's camera and the sun's keyed direction, where the
// scene has them (a still's otherwise). Throws std::runtime_error if the track's camera is
// degenerate there (its look-at passing through its position).
FrameView view_at(const SceneDesc& scene, double t);

// The seconds an animated scene's tracks cover: its camera track's first and last keys', or its
// sun track's when it has no camera track; {0, 0} for a still.
struct TimeSpan {
    double first = 0, last = 0;
};
TimeSpan animation_span(const SceneDesc& scene);

// The frames of an animated scene: those whose times lie within animation_span; frame 1 alone
// for a still.
FrameRange animation_frames(const SceneDesc& scene);

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
