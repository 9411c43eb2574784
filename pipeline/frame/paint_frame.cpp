// paint_frame: the frame's stages in order, each timed for --explain.
#include "pipeline/frame/paint_frame.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <glm/geometric.hpp>
#include <stdexcept>

#include "pipeline/frame/tile_bins.h"
#include "pipeline/frame/composite.h"
#include "pipeline/frame/graftal_stage.h"
#include "pipeline/frame/imposter_stage.h"
#include "pipeline/frame/reflection.h"
#include "pipeline/frame/sky_sprites.h"
#include "pipeline/frame/sprites.h"

namespace pleinair {

FrameSettings scene_frame_settings(const SceneDesc& scene, bool aovs) {
    FrameSettings s;
    s.render = scene.render;
    s.aovs = aovs;
    return s;
}

FrameView still_view(const SceneDesc& scene) {
    return {scene.camera, scene.sun_direction, scene.circles};
}

FrameView view_at(const SceneDesc& scene, double t) {
    FrameView v = still_view(scene);
    if (!scene.camera_track.keys.empty()) {
        const CameraKey key = track_at(scene.camera_track, t);
        if (std::string why = make_camera(camera_of(key, scene.camera_params), v.camera);
            !why.empty())
            throw std::runtime_error("the camera track at " + std::to_string(t) + " s: " + why);
        v.circles = circles_of(key, scene.circles);
        v.on_track = true;
        v.time = t;
        // Central difference over a frame either side (one side at the track's ends).
        const double dt = 1.0 / scene.fps;
        const double ta = std::max(t - dt, scene.camera_track.keys.front().time);
        const double tb = std::min(t + dt, scene.camera_track.keys.back().time);
        if (tb > ta)
            v.eye_speed = glm::length(track_at(scene.camera_track, tb).position -
                                      track_at(scene.camera_track, ta).position) *
                          (dt / (tb - ta));
    }
    if (!scene.sun_track.empty()) v.sun_direction = sun_at(scene.sun_track, t);
    return v;
}

TimeSpan animation_span(const SceneDesc& scene) {
    const auto& cam = scene.camera_track.keys;
    if (!cam.empty()) return {cam.front().time, cam.back().time};
    if (!scene.sun_track.empty())
        return {scene.sun_track.front().time, scene.sun_track.back().time};
    return {};
}

FrameRange animation_frames(const SceneDesc& scene) {
    if (!scene.animated()) return {1, 1, 1};
    const TimeSpan span = animation_span(scene);
    CameraTrack times;  // the frame counting only reads the keys' times
    times.keys = {CameraKey{span.first}, CameraKey{span.last}};
    return {track_first_frame(times, scene.fps), track_last_frame(times, scene.fps), 1};
}

namespace {

// The level of detail's line for --explain: the circles, and how far the trees have faded.
PassReport lod_report(const FrameLod& lod, double ms) {
    auto num = [](double v) {
        char b[32];
        std::snprintf(b, sizeof b, "%g", v);
        return std::string(b);
    };
    const DistanceCircles& c = lod.circles;
    std::string what;
    if (lod.leaves) what += "leaves " + num(c.leaf_near) + "-" + num(c.leaf_far);
    if (lod.trunks)
        what += std::string(what.empty() ? "" : ", ") + "trunks " + num(c.trunk_near) + "-" +
                num(c.trunk_far);
    if (lod.near_field)
        what += std::string(what.empty() ? "" : ", ") + "near field " + num(c.near_field);
    std::string detail;
    if (lod.leaves && !lod.trees.empty()) {
        double kept = 0;
        float most = 1;
        for (const TreeLod& t : lod.trees) kept += t.kept, most = std::max(most, t.growth);
        detail = "leaves kept " + num(std::round(1000 * kept / lod.trees.size()) / 10) +
                 "% on average, survivors grown up to " + num(std::round(100 * most) / 100) + "x";
    }
    return {"level of detail", true, "distance circles: " + (what.empty() ? "none" : what), ms,
            detail};
}

}  // namespace

Frame paint_frame(const Shot& shot, const FrameView& view_in, const FrameSettings& settings,
                  FrameReport* report) {
    FrameReport local;
    FrameReport& rep = report ? *report : local;
    FrameView view = view_in;
    if (shot.scene.sun_track.empty()) view.sun_direction = shot.scene.sun_direction;
    const Camera& cam = view.camera;
    const RenderSettings& rs = settings.render;
    const FramePlan plan = plan_frame(shot, settings);
    rep.decisions = plan.decisions;

    // A moving sun's scene (its casters face it) is built for this frame; a still one is the
    // shot's.
    std::unique_ptr<RayScene> frame_sun;
    const RayScene* sun_rays = shot.sun_rays.get();
    if (plan.sun_light == SunLightSource::kFrameScene) {
        PassTimer t;
        frame_sun = build_sun_scene(shot, glm::vec3(view.sun_direction));
        sun_rays = frame_sun.get();
        rep.passes.push_back({"sun scene", true, "the sun moves: its casters face it this frame",
                              t.ms(), std::to_string(sun_rays->caster_count()) + " casters"});
    }

    auto stage = [&](const char* name) {
        if (settings.progress) settings.progress(name, 0.0);
    };
    stage("sprites");
    PassTimer t;
    const FrameLod lod = level_of_detail(shot, settings.lod_view ? *settings.lod_view : view, rs);
    if (plan.lod) rep.passes.push_back(lod_report(lod, t.ms()));
    t = PassTimer();
    const SeenWindow seen = seen_window(shot.scene, view, rs);
    SpriteSet sprites = make_sprites({shot, view, plan, rs, lod, sun_rays, &seen});
    rep.leaf_sprites = sprites.leaf, rep.bark_sprites = sprites.bark;
    rep.surface_sprites = sprites.surface, rep.culled = sprites.culled;
    rep.shadow_rays = sprites.shadow_rays;
    rep.passes.push_back(
        {"sprites", true,
         std::string("every particle faces the camera") +
             (plan.fragment_shadows                     ? "; 4 x 4 shadow rays per sprite"
              : plan.sun_light == SunLightSource::kShot ? "; light from the shot"
              : plan.shadows                            ? "; a shadow ray per particle"
                                                        : "") +
             (!plan.underpaint       ? ""
              : seen.cameras.empty() ? "; hidden ones culled"
                                     : "; hidden ones culled, seen from where the eye is over " +
                                           std::to_string(seen.cameras.size()) + " frames"),
         t.ms(),
         std::to_string(sprites.sprites.size()) + " sprites, " + std::to_string(sprites.culled) +
             " culled (" + std::to_string(sprites.hidden) + " hidden, " +
             std::to_string(sprites.faded) + " faded out)" +
             (sprites.shadow_rays ? ", " + std::to_string(sprites.shadow_rays) + " shadow rays"
                                  : "")});

    if (plan.reflections) {
        PassTimer tr;
        const ReflectionReport r =
            add_reflections(mirror_context(shot, view, plan, rs, sun_rays), sprites);
        rep.reflection_rays = r.rays;
        rep.passes.push_back(
            {"reflections", true,
             "each water stroke in view takes the colour its reflected ray finds (surfaces, "
             "trunks, leaf strokes, the sky), by water's Fresnel reflectance",
             tr.ms(),
             std::to_string(r.strokes) + " water strokes, " + std::to_string(r.rays) + " rays"});
    }
    if (plan.graftals) {
        // After the strokes' sprites, so their indices (and the shadow grids') stay as they are.
        PassTimer tg;
        const GraftalStageReport g =
            add_graftal_sprites(shot, view, rs, sprites, settings.lod_view);
        rep.graftal_sprites = sprites.graftal;
        std::string levels;
        for (size_t l = 0; l < g.at_level.size(); ++l)
            levels += (l ? ", " : "") + std::to_string(g.at_level[l]);
        rep.passes.push_back(
            {"graftals", true,
             "tufts' levels from λ" +
                 (view.on_track ? ", filtered over " + std::to_string(g.replayed) +
                                      " frames of the track replayed"
                                : std::string()) +
                 "; graftals drawn by " +
                 (rs.graftal_raster == GraftalRaster::kCairo ? "Cairo" : "scanline coverage") +
                 " into patches (" + std::to_string(int(g.draw_ms + 0.5)) + " ms of it)",
             tg.ms(),
             std::to_string(g.tufts) + " tufts (per level: " + levels + "), " +
                 std::to_string(g.drawn) + " graftals drawn (" + std::to_string(g.growing) +
                 " growing or fading), " + std::to_string(g.pixels) + " patch pixels"});
    }
    if (plan.imposters) {
        PassTimer ti;
        const ImposterStageReport im = add_imposter_sprites(shot, view, sprites, &seen);
        rep.imposter_sprites = im.drawn;
        rep.passes.push_back(
            {"imposters", true,
             "silhouette edges (and edges turning towards one) of " + std::to_string(im.objects) +
                 " meshes extruded along the vector field, drawn from the atlas and keyed",
             ti.ms(),
             std::to_string(im.candidates) + " edges the control allows, " +
                 std::to_string(im.hidden) + " hidden, " + std::to_string(im.drawn) +
                 " imposters drawn, " + std::to_string(im.pixels) + " patch pixels"});
    }
    t = PassTimer();
    const std::vector<uint32_t> order = depth_order(sprites.sprites);
    rep.passes.push_back({"sort", true, "depth order, ties by sprite", t.ms(), ""});
    t = PassTimer();
    const TileBins bins = bin_sprites(sprites.sprites, order, cam.width, cam.height);
    rep.passes.push_back(
        {"bin", true, "tiles paint in parallel", t.ms(),
         std::to_string(bins.bins.size()) + " tiles of " + std::to_string(kTile) + " px"});

    // Strokes first, nearest first: the background and underpainting are then needed only
    // where the strokes leave some light through.
    stage("paint");
    t = PassTimer();
    Frame frame = make_frame(cam, plan.aovs);
    StrokeLayer strokes = paint_strokes(shot, sprites, bins, plan, rs, frame, &settings.progress);
    rep.fragments = strokes.fragments;
    rep.passes.push_back({"paint", true,
                          "strokes front to back, tiles in parallel, each until it is covered",
                          t.ms(), std::to_string(rep.fragments) + " fragments"});
    // The painted sky behind every stroke, where they leave it in view.
    StrokeLayer sky;
    SpriteSet sky_set;
    if (plan.sky) {
        stage("sky");
        t = PassTimer();
        FramePlan sky_plan = plan;
        sky_plan.aovs = false;     // the sky is the background in the AOVs
        sky_plan.pigment = false;  // its strokes blend among themselves, then lie under paint
        sky_plan.canvas = false;
        sky_set = sky_sprites(shot, view, plan, rs);
        const TileBins sky_bins =
            bin_sprites(sky_set.sprites, depth_order(sky_set.sprites), cam.width, cam.height);
        sky = paint_strokes(shot, sky_set, sky_bins, sky_plan, rs, frame, nullptr, &strokes);
        rep.sky_sprites = sky_set.sprites.size();
        rep.fragments += sky.fragments;
        rep.passes.push_back({"sky", true,
                              "the sky's strokes turned with the camera, painted where the "
                              "strokes in front leave light through",
                              t.ms(),
                              std::to_string(sky_set.sprites.size()) + " of " +
                                  std::to_string(shot.sky.size()) + " sky strokes in view, " +
                                  std::to_string(sky.fragments) + " fragments"});
    }
    t = PassTimer();
    paint_background(shot.scene, cam, strokes, frame, plan.sky ? &sky : nullptr);
    rep.passes.push_back(
        {"background", true,
         shot.scene.background.canvas ? "canvas colour" : "sky and ground seen from the camera",
         t.ms(), ""});
    if (plan.underpaint) {
        stage("underpaint");
        t = PassTimer();
        rep.underpaint_rays = paint_underpainting(shot, view, plan, rs, sun_rays, strokes, frame);
        rep.passes.push_back(
            {"underpaint", true,
             "flat palette colour where the camera sees a surface and the strokes leave gaps",
             t.ms(), std::to_string(rep.underpaint_rays) + " camera rays"});
    }
    t = PassTimer();
    composite_strokes(strokes, plan, rs, frame);
    rep.passes.push_back({"composite", true, "the strokes over what lies under them", t.ms(), ""});
    if (plan.trace && plan.sky) {
        // The sky's strokes are traced where no nearer stroke is: after the others' indices.
        const uint32_t offset = static_cast<uint32_t>(sprites.sprites.size());
        sprites.sprites.insert(sprites.sprites.end(), sky_set.sprites.begin(),
                               sky_set.sprites.end());
        StrokeLayer& s = strokes;
        for (size_t p = 0; p < s.first.size(); ++p) {
            const auto lift = [&](uint32_t i) { return i == ~0u ? i : i + offset; };
            if (s.first[p] == ~0u)
                s.first[p] = lift(sky.first[p]), s.second[p] = lift(sky.second[p]),
                s.first_weight[p] = sky.first_weight[p];
            else if (s.second[p] == ~0u)
                s.second[p] = lift(sky.first[p]);
        }
    }
    if (plan.trace)
        rep.trace = std::make_shared<FrameReport::Trace>(
            FrameReport::Trace{std::move(sprites.sprites), strokes.first, strokes.second,
                               strokes.first_weight, strokes.through});
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
