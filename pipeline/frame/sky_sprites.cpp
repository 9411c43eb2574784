// sky_sprites and sky_color.
#include "pipeline/frame/sky_sprites.h"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <limits>
#include <string>

#include "pipeline/shot/shot.h"
#include "shading/portable_math.h"
#include "shading/sky.h"

namespace pleinair {

namespace {

constexpr double kPi = 3.14159265358979323846;
// Ranges of sky sprites, beyond any world distance (kMaxWorldCoordinate), small before large.
constexpr float kSmallRange = 1e30f, kBaseRange = 4e30f;

}  // namespace

SpriteSet sky_sprites(const Shot& shot, const FrameView& view, const FramePlan& plan,
                      const RenderSettings& rs) {
    SpriteSet out;
    const SkyStrokes& sky = shot.sky;
    if (sky.size() == 0) return out;
    const SkyParams& p = shot.scene.sky.params;
    const MaterialId mat = shot.materials.sky();
    const StrokeShaderParams& shader = *shot.materials[mat].shader;
    const float aspect = std::max(shader.stroke_aspect, 0.1f);
    // The camera turned, never moved: the sky lies at infinity.
    Camera rot = view.camera;
    rot.eye = glm::dvec3(0.0);
    rot.near_depth = 1e-6;  // directions lie at distance 1, whatever the focus distance
    const glm::vec3 sun(view.sun_direction);
    const float min_px = std::max(rs.min_stroke_px, 0.5f);
    for (size_t i = 0; i < sky.size(); ++i) {
        const glm::vec3 d = sky.direction[i];
        const float label = sky.label[i];
        const bool small = sky.small[i] != 0;
        if (small && label_hash(label, 5) >= p.detail) continue;
        const Projection pr = project(rot, glm::dvec3(d));
        if (!pr.in_front) continue;
        const SkySample s = sky_sample(p, d, sun);
        // Strokes thin into the horizon's haze; edge strokes only where a cloud's rim is.
        float fade = 0.35f + 0.65f * smoothstep(-0.03f, p.haze, d.y);
        if (small) fade *= smoothstep(0.1f, 0.6f, s.edge);
        if (!(fade > 0.02f)) continue;
        // Along the horizontal through d (any azimuth at the zenith), half the stroke's angle.
        glm::vec3 t(-d.z, 0.0f, d.x);
        const float tl = glm::length(t);
        if (tl > 1e-4f) {
            t /= tl;
        } else {
            const float a = 2.0f * static_cast<float>(kPi) * label;
            t = glm::vec3(pmath::cos(a), 0.0f, pmath::sin(a));
        }
        const float stroke_rad = p.stroke_size * static_cast<float>(kPi / 180.0);
        const float half = 0.5f * stroke_rad * (small ? 0.5f : 1.0f) *
                           stroke_size_jitter(shader, label) * sky_stroke_scale(p, d, stroke_rad);
        const Projection pe = project(rot, glm::dvec3(glm::normalize(d + t * pmath::tan(half))));
        if (!pe.in_front) continue;
        const float dx = pe.x - pr.x, dy = pe.y - pr.y;
        const float half_l = pmath::hypot(dx, dy);
        if (!(half_l * 2.0f / aspect >= min_px) || !std::isfinite(half_l)) continue;
        Sprite sp;
        sp.x = pr.x, sp.y = pr.y;
        sp.depth = std::numeric_limits<float>::max();
        sp.range = (small ? kSmallRange : kBaseRange) * (1.0f + 0.5f * label);
        sp.half_l = half_l, sp.half_w = half_l / aspect;
        // The stroke's length along the horizon's direction on screen, jittered by the label.
        const double base = pmath::atan2(static_cast<double>(dy), static_cast<double>(dx));
        const double angle = base - 0.5 * kPi + stroke_angle_jitter(shader, label);
        sp.ax = static_cast<float>(-pmath::sin(angle));
        sp.ay = static_cast<float>(pmath::cos(angle));
        // Off screen, or so far off the axis that projection stretches it across the frame: a
        // wide lens' corners stretch by 1 / cos^2 of their angle, 4 at 60 degrees; beyond 8x
        // its size on the axis the stroke's centre lies far outside any frame.
        if (!(half_l < 8.0f * static_cast<float>(rot.focal_px) * half)) continue;
        float ex, ey;
        sprite_extent(sp, ex, ey);
        if (sp.x + ex < 0 || sp.y + ey < 0 || sp.x - ex > rot.width || sp.y - ey > rot.height)
            continue;
        sp.fade = fade;
        sp.material = mat;
        sp.kind = SpriteKind::kSky;
        sp.particle = static_cast<uint32_t>(i);
        sp.k = stroke_constants(shader, 1.0f, 0.0f, 0.5f, label, 0, 1.0f, 0.0f, 0.0f, false, false);
        // Each stroke a little lighter or darker than the field: the brush's own load of paint.
        const float l =
            clamp01(s.lightness + sky_stroke_tone(p, d, stroke_rad, label_hash(label, 6)));
        sp.k.lightness = l;
        const StrokeNoise n = stroke_noise_for(shader, l, 0.0f, label);
        sp.k.frequ_s = n.frequ_s, sp.k.frequ_t = n.frequ_t;
        if (!plan.sub_stroke) sp.k.sub_amt = 0;
        reseed_noise(sp.k, plan.noise_reseed);
        out.sprites.push_back(sp);
    }
    return out;
}

Color sky_color(const SceneDesc& scene, const glm::vec3& direction, const glm::vec3& sun) {
    return palette_lookup(scene.sky.palette,
                          sky_sample(scene.sky.params, direction, sun).lightness);
}

SkyLayer sky_stage(const FrameContext& ctx, const StrokeLayer& strokes, Frame& frame) {
    StagePhase phase(ctx, "sky", true);
    FramePlan sky_plan = ctx.plan;
    sky_plan.aovs = false;
    sky_plan.pigment = false;
    sky_plan.canvas = false;
    const Camera& cam = ctx.view.camera;
    SkyLayer sky;
    sky.sprites = sky_sprites(ctx.shot, ctx.view, ctx.plan, ctx.render());
    const TileBins bins =
        bin_sprites(sky.sprites.sprites, depth_order(sky.sprites.sprites), cam.width, cam.height);
    sky.layer = paint_strokes(ctx.shot, sky.sprites, bins, sky_plan, ctx.render(), frame, nullptr,
                              &strokes, ctx.settings.buffers, ctx.render().sky_one_sample_px);
    ctx.report.sky_sprites = sky.sprites.sprites.size();
    ctx.report.fragments += sky.layer.fragments;
    phase.done(
        "the sky's strokes turned with the camera, painted where the strokes in front leave "
        "light through",
        std::to_string(sky.sprites.sprites.size()) + " of " + std::to_string(ctx.shot.sky.size()) +
            " sky strokes in view, " + std::to_string(sky.layer.fragments) + " fragments");
    return sky;
}

}  // namespace pleinair
