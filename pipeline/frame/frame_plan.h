// The first stage of a frame: what it needs, decided from the shot and the frame settings
// alone (DESIGN.md: "the plan"), each decision with the reason --explain prints.
#pragma once

#include <exception>
#include <functional>
#include <vector>

#include "pipeline/frame/frame_view.h"
#include "pipeline/input/camera.h"
#include "pipeline/input/distance_circles.h"
#include "pipeline/input/settings.h"
#include "pipeline/shot/pass_report.h"

namespace pleinair {

class BufferPool;
class MirrorMemo;
class SeenMemo;

struct Shot;

// How a frame is painted from a shot: nothing in here rebuilds anything.
struct FrameSettings {
    RenderSettings render;
    bool aovs = false;  // depth, object id, alpha and lightness channels
    // Benchmarks only: each sprite's footprint blended with a constant colour at opacity 0.5
    // instead of shaded, to measure what the shader costs over the bare blend.
    bool bare_blend = false;
    // The coherence bench only (coherence_measures.h): keep the sprites and each pixel's two
    // nearest strokes (FrameReport::trace); see the level of detail from `lod_view` instead of the
    // frame's (frozen at another frame); shift every stroke's noise by `noise_reseed` (boiling).
    bool trace = false;
    const FrameView* lod_view = nullptr;
    uint32_t noise_reseed = 0;
    // The coherence bench only: false paints still water without its mirror (the baseline of
    // the water's flicker).
    bool reflections = true;
    // The coherence bench only: false paints the trees at rest in a windy shot (the baseline
    // of the wind's flicker).
    bool wind = true;
    // Told when each stage starts (done 0) and how far the paint stage has come, for frames
    // long enough to report on; called from worker threads (the callee serializes).
    std::function<void(const char* stage, double done)> progress;
    // Asked as each stage starts: true abandons the frame, and paint_frame throws
    // FrameAbandoned. An interactive client (the studio) sets it so that the latest request
    // wins; the frame path knows nothing of who asks.
    std::function<bool()> abandon;
    // Frames of one shot painted in order (animate, the coherence bench): the seen window's
    // occlusion maps kept from one frame to the next (seen_memo.h). Null builds every map.
    SeenMemo* seen_memo = nullptr;
    // The same for water strokes' mirrors at their lattice times (mirror_memo.h). Null traces
    // the lattice times a frame reads.
    MirrorMemo* mirror_memo = nullptr;
    // Frames painted in a row: the image and stroke layers' memory kept from the frame before
    // (buffer_pool.h). Null allocates them anew.
    BufferPool* buffers = nullptr;
};

// What paint_frame throws when FrameSettings::abandon says so between stages.
struct FrameAbandoned : std::exception {
    const char* what() const noexcept override { return "frame abandoned for a newer one"; }
};

// How a frame learns each particle's light.
enum class SunLightSource {
    kNone,       // no shadows: every particle is lit
    kShot,       // traced once by the shot (a still sun, per-particle shadows)
    kShotScene,  // traced per frame through the shot's sun scene, for the particles it shows
    kFrameScene  // the sun moves: its scene is built for this frame, then traced
};

struct FramePlan {
    bool bark = false;        // bark strokes (grown by the shot)
    bool tint = false;        // some shader has unique_tint_amt > 0
    bool atmosphere = false;  // an atmosphere and some shader with a non-zero distance effect
    bool sub_stroke = false;  // some shader varies colour inside strokes
    bool aovs = false;
    bool shadows = false;
    SunLightSource sun_light = SunLightSource::kNone;
    bool fragment_shadows = false;  // a 4 x 4 grid of shadow rays per sprite
    bool underpaint = false;        // a visible mesh: flat colour under the strokes
    // Occlusion maps (occlusion_map.h) answer first where a frame tests many more strokes
    // than its maps have texels (a dense wood); elsewhere each stroke casts its rays.
    bool occlusion_maps = false;
    bool bare_blend = false;
    bool lod = false;          // the camera carries distance circles and level_of_detail is on
    bool graftals = false;     // some family or material is drawn in a graftal style
    bool imposters = false;    // some family or material carries graftal imposters
    bool sky = false;          // a painted sky (sky_sprites.h): its strokes under every other
    bool reflections = false;  // still water mirrors what its reflected rays find
    bool pigment = false;      // strokes mix as pigments (shading/pigment.h)
    bool canvas = false;       // a canvas weave under thin paint and at stroke edges
    bool wind = false;         // the scene's wind poses the trees (wind_stage.h)
    bool trace = false;
    uint32_t noise_reseed = 0;
    std::vector<PassReport> decisions;
};

FramePlan plan_frame(const Shot& shot, const FrameSettings& settings);

// Whether a shader shows distance (hue, saturation or value ranges move with it).
struct StrokeShaderParams;
bool has_atmosphere_effect(const StrokeShaderParams& p);

}  // namespace pleinair
