// plan_frame: every decision of a frame, from the shot's plan and the frame settings.
#include "pipeline/frame/frame_plan.h"

#include <cstdio>

#include "pipeline/frame/frame_view.h"
#include "pipeline/frame/occlusion_map.h"
#include "pipeline/shot/shot.h"

namespace pleinair {

bool has_atmosphere_effect(const StrokeShaderParams& p) {
    return p.dist_hue_strength > 0 || p.dist_sat_limiter > 0 || p.dist_value_min > 0 ||
           p.dist_value_max < 1;
}

FramePlan plan_frame(const Shot& shot, const FrameSettings& settings) {
    const SceneDesc& scene = shot.scene;
    FramePlan plan;
    auto add = [&](const char* name, bool ran, std::string why) {
        plan.decisions.push_back({name, ran, std::move(why), 0, ""});
    };
    bool tint = false, atmos = false, sub = false;
    auto read = [&](const StrokeShaderParams& p) {
        tint |= p.unique_tint_amt > 0;
        atmos |= has_atmosphere_effect(p);
        sub |= p.sub_stroke_amt > 0 && p.sub_stroke_frequ >= 0;
    };
    for (const auto& f : scene.families) read(f.leaf_shader), read(f.bark_shader);
    // The materials' shaders too (ground, water, rocks, particle files, figures): a scene of
    // land and figures without a tree still takes their sub-strokes, tint and haze.
    for (const Material& m : scene.materials) read(m.shader);
    if (!shot.sky.direction.empty()) sub |= scene.sky.shader.sub_stroke_amt > 0;
    plan.bark = shot.plan.bark;
    add("bark", plan.bark,
        plan.bark ? "trunks and branches are painted as strokes" : "render/bark_coverage is 0");
    plan.tint = tint;
    add("tint", tint,
        tint ? "a shader has unique_tint_amt > 0" : "unique_tint_amt is 0 in every shader");
    // The distance's one value (/atmosphere/value_pull) is the haze too, whatever the shaders.
    atmos |= scene.atmosphere.value_pull > 0;
    plan.atmosphere = scene.has_atmosphere && atmos;
    add("atmosphere", plan.atmosphere,
        !scene.has_atmosphere ? "the scene has no atmosphere"
        : atmos               ? "atmosphere near/far set and a shader has distance effects"
                              : "every shader's distance effects are zero");
    add("cloud shadows", scene.clouds.cover > 0,
        scene.clouds.cover > 0 ? "sun/clouds/cover > 0: patches of light and shade on the land"
                               : "the scene's sun has no clouds");
    plan.sub_stroke = sub;
    add("sub-stroke colour", sub,
        sub ? "a shader has sub_stroke_amt > 0" : "sub_stroke_amt is 0 in every shader");
    plan.aovs = settings.aovs;
    add("aovs", settings.aovs, settings.aovs ? "asked for (--aovs)" : "not asked for");

    plan.shadows = shot.plan.shadows;
    plan.fragment_shadows =
        plan.shadows && settings.render.shadow_samples == ShadowSamples::kFragment;
    if (!plan.shadows)
        plan.sun_light = SunLightSource::kNone;
    else if (shot.plan.sun_moves)
        plan.sun_light = SunLightSource::kFrameScene;
    else if (shot.plan.sun_light && !plan.fragment_shadows &&
             settings.render.shadows == scene.render.shadows)
        plan.sun_light = SunLightSource::kShot;
    else
        plan.sun_light = SunLightSource::kShotScene;
    const char* where =
        plan.fragment_shadows ? "a 4 x 4 grid of rays per sprite" : "one ray per particle";
    add("shadows", plan.shadows,
        !scene.sun_casts_shadows ? "the sun casts no shadows: no shadow scene, no shadow ray"
        : !plan.shadows          ? "nothing in the scene to cast a shadow"
        : plan.sun_light == SunLightSource::kShot
            ? "the still sun's light at each particle, kept in the shot once a frame has traced "
              "it"
        : plan.sun_light == SunLightSource::kFrameScene
            ? std::string("the sun moves: its scene is built for this frame; ") + where
            : std::string("the sun casts shadows through the stroke casters: ") + where);
    plan.underpaint = shot.plan.underpaint;
    std::string under = "terrain or rocks are visible: flat colour and depth under the strokes";
    if (const float tone = settings.render.underpaint_tone_amount; tone > 0) {
        char buf[64];
        std::snprintf(buf, sizeof buf, ", taken %.2g of the way to the lay-in's tone", tone);
        under += buf;
    }
    add("underpaint", plan.underpaint,
        plan.underpaint ? under : "no visible mesh (no terrain, no rocks)");
    // A map costs a ray a texel per camera of the seen window; it saves at most a ray a stroke
    // it answers, and on open ground it is unsure of most (BENCHMARKS.md, "Occlusion maps"):
    // drawn where the shot holds at least kMapsPay strokes a texel ray.
    constexpr double kMapsPay = 8;
    const double texel_rays = static_cast<double>(occlusion_map_rays(shot.scene.camera)) *
                              std::max(1, settings.render.occlusion_frames);
    double strokes = 0;
    for (size_t i = 0; i < shot.item_count(); ++i) strokes += double(item_particles(shot, i));
    plan.occlusion_maps = plan.underpaint && strokes >= kMapsPay * texel_rays;
    add("occlusion maps", plan.occlusion_maps,
        !plan.underpaint ? "nothing opaque to hide behind"
        : plan.occlusion_maps
            ? "the shot's strokes outnumber the seen window's map texels " +
                  std::to_string(static_cast<int>(strokes / texel_rays)) +
                  " to 1: each camera draws the surfaces' depth, hidden clusters are culled "
                  "unread and a stroke casts its ray only where its map is unsure"
            : "fewer than " + std::to_string(static_cast<int>(kMapsPay)) +
                  " strokes a map texel: each stroke casts its rays");
    const bool circles = scene_has_circles(shot.scene);
    plan.lod = circles && settings.render.level_of_detail;
    add("level of detail", plan.lod,
        !circles ? "the camera carries no distance circles"
        : plan.lod
            ? "the camera's distance circles: leaves fade outside in, survivors grow, twigs' "
              "bark cross-fades to the low-detail model"
            : "render/level_of_detail is false: every tree at full detail");
    plan.graftals = !shot.graftals.empty();
    add("graftals", plan.graftals,
        plan.graftals ? "some family or material is drawn in a graftal style: tufts' levels "
                        "from λ, graftals drawn into patches and composited with the strokes"
                      : "every family and material is painted with strokes");
    plan.imposters = !shot.imposters.empty();
    add("imposters", plan.imposters,
        plan.imposters ? "some family or material carries graftal imposters: silhouette edges "
                         "found, extruded and drawn from the atlas"
                       : "no family or material names imposters");
    plan.sky = !shot.sky.direction.empty();
    add("sky", plan.sky,
        plan.sky             ? "a painted sky: strokes at infinity, turned with the camera, "
                               "painted where no surface hides the sky"
        : !scene.sky.present ? "the scene has no /sky: the background's gradient"
                             : "the background is a canvas");
    plan.reflections =
        scene.water.present && scene.water.reflection > 0 && shot.view_rays && settings.reflections;
    add("reflections", plan.reflections,
        plan.reflections ? "still water: each water stroke in view averages /water/mirror_rays rays"
        : !scene.water.present          ? "the scene has no water"
        : !(scene.water.reflection > 0) ? "/water/reflection is 0"
        : !settings.reflections         ? "turned off for a baseline (coherence bench)"
                                        : "no camera scene to reflect");
    plan.pigment = settings.render.pigment_mixing;
    add("pigment mixing", plan.pigment,
        plan.pigment ? "strokes mix as Kubelka-Munk pigments in a latent space"
                     : "render/pigment_mixing is off: alpha blending in linear RGB");
    plan.canvas = settings.render.canvas_weave > 0;
    add("canvas", plan.canvas,
        plan.canvas ? "a canvas weave under thin paint and at the strokes' edges"
                    : "render/canvas_weave is 0");
    plan.wind = shot.plan.wind && settings.wind;
    add("wind", plan.wind,
        plan.wind ? "the /wind bends the trees at the frame's time; shadows are frozen: each "
                    "stroke keeps the light it has at rest, and the shadows trees cast, the "
                    "water's mirror of them and graftal crowns stay as they stand at rest"
        : !shot.plan.wind ? "still air: no /wind, or one that never blows, or no trees"
                          : "turned off for a baseline (coherence bench)");
    plan.bare_blend = settings.bare_blend;
    plan.trace = settings.trace;
    plan.noise_reseed = settings.noise_reseed;
    return plan;
}

}  // namespace pleinair
