// build_sky_strokes, sky_sprites and sky_color.
#include "pipeline/frame/sky_sprites.h"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <limits>

#include "generators/rng.h"
#include "pipeline/shot/shot.h"
#include "shading/portable_math.h"
#include "shading/sky.h"

namespace pleinair {

namespace {

constexpr double kPi = 3.14159265358979323846;
// The lowest row: a little under the horizon, so strokes reach the horizon's haze (the
// background keeps them off the ground, composite.cpp).
constexpr double kLowest = -0.03;
// Cells are 0.55 of a stroke in each direction: every point of the sky under about three.
constexpr double kSpacing = 0.55;
// Ranges of sky sprites, beyond any world distance (kMaxWorldCoordinate), small before large.
constexpr float kSmallRange = 1e30f, kBaseRange = 4e30f;

}  // namespace

SkyStrokes build_sky_strokes(const SceneDesc& scene) {
    SkyStrokes out;
    const SkyDesc& sky = scene.sky;
    if (!sky.present || scene.background.canvas) return out;
    const SkyParams& p = sky.params;
    const double aspect = std::max<double>(sky.shader.stroke_aspect, 0.1);
    for (int layer = 0; layer < (p.detail > 0 ? 2 : 1); ++layer) {
        const double length = p.stroke_size * kPi / 180.0 * (layer ? 0.5 : 1.0);
        const double row = kSpacing * length / aspect, col = kSpacing * length;
        const int rows = static_cast<int>(std::ceil((0.5 * kPi - kLowest) / row));
        for (int r = 0; r < rows; ++r) {
            const double e0 = kLowest + r * row;
            const double mid = std::min(e0 + 0.5 * row, 0.5 * kPi);
            const int cols =
                std::max(1, static_cast<int>(std::lround(2 * kPi * pmath::cos(mid) / col)));
            for (int c = 0; c < cols; ++c) {
                Rng rng = make_rng(sky.seed, Purpose::kSky, layer, r, c);
                const double e = std::min(e0 + rand1(rng) * row, 0.5 * kPi);
                const double az = (c + rand1(rng)) * 2 * kPi / cols;
                const double ce = pmath::cos(e);
                out.direction.emplace_back(ce * pmath::sin(az), pmath::sin(e),
                                           -ce * pmath::cos(az));
                out.label.push_back(static_cast<float>(rand1(rng)));
                out.small.push_back(static_cast<uint8_t>(layer));
            }
        }
    }
    return out;
}

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
        const float half = 0.5f * p.stroke_size * static_cast<float>(kPi / 180.0) *
                           (small ? 0.5f : 1.0f) * stroke_size_jitter(shader, label);
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
        const float l = clamp01(s.lightness + p.stroke_jitter * (label_hash(label, 6) - 0.5f));
        sp.k.lightness = l;
        const float f = stroke_frequency(shader, 0.0f, l);
        sp.k.frequ_s = f * shader.s_frequ_scale, sp.k.frequ_t = f * shader.t_frequ_scale;
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

}  // namespace pleinair
