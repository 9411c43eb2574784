// paint_frame: the frame's stages in order; each times and describes itself (frame_context.h).
#include "pipeline/frame/paint_frame.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <glm/geometric.hpp>
#include <optional>
#include <stdexcept>

#include "pipeline/frame/background.h"
#include "pipeline/frame/composite.h"
#include "pipeline/frame/graftal_stage.h"
#include "pipeline/frame/imposter_stage.h"
#include "pipeline/frame/reflection.h"
#include "pipeline/frame/sky_sprites.h"
#include "pipeline/frame/sprites.h"
#include "pipeline/frame/tile_bins.h"
#include "pipeline/frame/underpaint.h"
#include "pipeline/frame/wind_stage.h"

namespace pleinair {

FrameSettings scene_frame_settings(const SceneDesc& scene, bool aovs) {
    FrameSettings s;
    s.render = scene.render;
    s.aovs = aovs;
    return s;
}

namespace {

// A moving sun's scene (its casters face it) is built for this frame; a still one is the
// shot's (null here).
std::unique_ptr<RayScene> sun_scene_stage(const FrameContext& ctx) {
    if (ctx.plan.sun_light != SunLightSource::kFrameScene) return nullptr;
    StagePhase phase(ctx, "sun scene");
    auto sun = build_sun_scene(ctx.shot, glm::vec3(ctx.view.sun_direction));
    phase.done("the sun moves: its casters face it this frame",
               std::to_string(sun->caster_count()) + " casters");
    return sun;
}

// A traced frame keeps its sprites and each pixel's two nearest strokes; the sky's strokes are
// traced where no nearer stroke is, after the others' indices.
std::shared_ptr<FrameTrace> trace_of(SpriteSet& sprites, StrokeLayer& strokes,
                                     const SkyLayer* sky) {
    if (sky) {
        const uint32_t offset = static_cast<uint32_t>(sprites.sprites.size());
        sprites.sprites.insert(sprites.sprites.end(), sky->sprites.sprites.begin(),
                               sky->sprites.sprites.end());
        const StrokeLayer& k = sky->layer;
        StrokeLayer& s = strokes;
        for (size_t p = 0; p < s.first.size(); ++p) {
            const auto lift = [&](uint32_t i) { return i == ~0u ? i : i + offset; };
            if (s.first[p] == ~0u)
                s.first[p] = lift(k.first[p]), s.second[p] = lift(k.second[p]),
                s.first_weight[p] = k.first_weight[p];
            else if (s.second[p] == ~0u)
                s.second[p] = lift(k.first[p]);
        }
    }
    return std::make_shared<FrameTrace>(FrameTrace{std::move(sprites.sprites), strokes.first,
                                                   strokes.second, strokes.first_weight,
                                                   strokes.through});
}

}  // namespace

Frame paint_frame(const Shot& shot, const FrameView& view_in, const FrameSettings& settings,
                  FrameReport* report) {
    FrameReport local;
    FrameReport& rep = report ? *report : local;
    FrameView view = view_in;
    if (shot.scene.sun_track.empty()) view.sun_direction = shot.scene.sun_direction;
    const FramePlan plan = plan_frame(shot, settings);
    rep.decisions = plan.decisions;
    const FrameContext ctx{shot, view, settings, plan, rep};

    const std::unique_ptr<RayScene> frame_sun = sun_scene_stage(ctx);
    const RayScene* sun_rays = frame_sun ? frame_sun.get() : shot.sun_rays.get();
    const FrameLod lod = lod_stage(ctx);
    const FrameWind wind = wind_stage(ctx, lod);
    const SeenWindow seen = seen_window(shot.scene, view, settings.render);
    SpriteSet sprites = sprites_stage(ctx, lod, wind, sun_rays, seen);
    if (plan.reflections) reflections_stage(ctx, sun_rays, sprites);
    if (plan.graftals) graftals_stage(ctx, sprites);
    if (plan.imposters) imposters_stage(ctx, sprites, seen);
    const TileBins bins = order_stage(ctx, sprites.sprites);

    Frame frame = make_frame(view.camera, plan.aovs, settings.buffers);
    StrokeLayer strokes = paint_stage(ctx, sprites, bins, frame);
    std::optional<SkyLayer> sky =
        plan.sky ? std::optional<SkyLayer>(sky_stage(ctx, strokes, frame)) : std::nullopt;
    background_stage(ctx, strokes, sky ? &sky->layer : nullptr, frame);
    if (plan.underpaint) underpaint_stage(ctx, sun_rays, strokes, frame);
    composite_stage(ctx, strokes, frame);
    if (plan.trace) rep.trace = trace_of(sprites, strokes, sky ? &*sky : nullptr);
    give_back(strokes, settings.buffers);
    if (sky) give_back(sky->layer, settings.buffers);
    if (settings.buffers) settings.buffers->give_sprites(std::move(sprites.sprites));
    return frame;
}

uint64_t frame_buffer_bytes(int width, int height, bool aovs, float underpaint_scale,
                            double output_bytes) {
    const double px = static_cast<double>(width) * static_cast<double>(height);
    const double per = (aovs ? 32.0 : 16.0) + 16.0 +
                       20.0 * double(underpaint_scale) * double(underpaint_scale) + output_bytes;
    return static_cast<uint64_t>(px * per);
}

Frame paint_still(const SceneDesc& scene, bool aovs, FrameReport* report) {
    const Shot shot = build_shot(scene);
    return paint_frame(shot, still_view(shot.scene), scene_frame_settings(shot.scene, aovs),
                       report);
}

Frame paint_still(const SceneDesc& scene, std::vector<BuiltTree> trees, bool aovs,
                  FrameReport* report) {
    const Shot shot =
        build_shot(scene, std::make_shared<const std::vector<BuiltTree>>(std::move(trees)),
                   std::make_shared<const BuiltLandscape>());
    return paint_frame(shot, still_view(shot.scene), scene_frame_settings(shot.scene, aovs),
                       report);
}

}  // namespace pleinair
