// water_reflectance, mirror and add_reflections.
#include "pipeline/frame/reflection.h"

#include <tbb/combinable.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>

#include "pipeline/frame/background.h"
#include "pipeline/frame/sky_sprites.h"
#include "pipeline/frame/surface_hit.h"
#include "pipeline/shot/shot.h"
#include "shading/portable_math.h"

namespace pleinair {

namespace {
// Water darkens towards the viewer to this share of its colour, where it mirrors least: its
// depth shows instead of the sky.
constexpr float kNearDarken = 0.35f;
}  // namespace

float water_reflectance(float cos_view) {
    const float m = 1.0f - clamp01(std::abs(cos_view));
    const float m2 = m * m;
    return 0.02f + 0.98f * m2 * m2 * m;
}

MirrorContext mirror_context(const Shot& shot, const FrameView& view, const FramePlan& plan,
                             const RenderSettings& settings, const RayScene* sun_rays) {
    MirrorContext c{shot, view, plan, settings, nullptr, Color(0.0f), FramePlan{}};
    if (sun_rays && sun_rays->caster_count() > 0) c.sun_rays = sun_rays;
    // Built once: copying the plan's notes for every ray cost an allocation per ray.
    c.flat = plan;
    c.flat.decisions.clear();
    c.flat.atmosphere = false;
    c.flat.reflections = false;
    const auto& fams = shot.scene.families;
    for (const Family& f : fams) c.foliage += palette_lookup(f.leaf_palette, 0.3f);
    if (!fams.empty()) c.foliage /= static_cast<float>(fams.size());
    return c;
}

namespace {
// What one reflected ray sees from `at`: the view `dir` reflected about `n`. Adds its rays.
Color mirrored(const MirrorContext& c, const RayOrigin& at, const glm::vec3& n,
               const glm::dvec3& dir, int& rays) {
    const SceneDesc& scene = c.shot.scene;
    // The reflected ray, kept above the water where a ripple would turn it under.
    glm::dvec3 r = dir - 2.0 * glm::dot(dir, glm::dvec3(n)) * glm::dvec3(n);
    if (!(r.y >= 0.01)) r.y = 0.01;
    r = glm::normalize(r);
    const glm::vec3 rf(r);
    const glm::dvec3 from = at.lifted();
    const RayHit h = c.shot.view_rays->intersect(from, rf, std::numeric_limits<float>::infinity(),
                                                 at.surface_normal());
    ++rays;
    Color seen;
    if (h.hit) {
        // The hit's own flat colour, as the underpainting paints it (it casts its shadow ray);
        // the water's atmosphere comes after, on the mirrored colour.
        seen = surface_hit_color(c.shot, c.view, c.flat, c.settings, c.sun_rays, h,
                                 from + r * static_cast<double>(h.t), h.normal, r);
        rays += c.flat.shadows && c.sun_rays;
    } else {
        seen = c.plan.sky ? sky_color(scene, rf, glm::vec3(c.view.sun_direction))
                          : background_at(scene.background, r);
    }
    if (c.sun_rays) {
        // Leaf strokes between the water and what it mirrors, as the sun's casters.
        const float through = c.sun_rays->transmittance(
            from, rf, c.settings.shadows,
            h.hit ? h.t * 0.999f : std::numeric_limits<float>::infinity(), at.surface_normal());
        seen = mix(c.foliage, seen, through);
        ++rays;
    }
    return seen;
}
}  // namespace

int mirror(const MirrorContext& c, const RayOrigin& at, const glm::vec3* normals, int count,
           const glm::vec3& up, const glm::dvec3& dir, StrokeConstants& k) {
    const float amount_max = clamp01(c.shot.scene.water.reflection);
    if (!(amount_max > 0.0f) || !c.shot.view_rays || count < 1) return 0;
    int rays = 0;
    Color seen(0.0f);
    for (int i = 0; i < count; ++i) seen += mirrored(c, at, normals[i], dir, rays);
    seen /= static_cast<float>(count);
    const float fresnel = water_reflectance(static_cast<float>(glm::dot(dir, glm::dvec3(up))));
    const float amount = amount_max * fresnel;
    const float dim = 1.0f - kNearDarken * amount_max * (1.0f - fresnel);
    k.mirror = seen * (amount * dim);
    k.mirror_keep = (1.0f - amount) * dim;
    return rays;
}

ReflectionReport add_reflections(const MirrorContext& c, SpriteSet& set) {
    ReflectionReport rep;
    const Shot& shot = c.shot;
    const MaterialId water = shot.materials.surface(shot.scene.water.material);
    const float ripple = shot.scene.water.ripple;
    const int count = std::clamp(shot.scene.water.mirror_rays, 1, kMaxMirrorRays);
    const size_t trees = shot.trees->size();
    tbb::combinable<uint64_t> strokes{[] { return uint64_t{0}; }}, rays{[] { return uint64_t{0}; }};
    tbb::parallel_for(
        tbb::blocked_range<size_t>(0, set.sprites.size(), 512),
        [&](const tbb::blocked_range<size_t>& range) {
            FlushDenormals ftz;  // Embree's modes, while this task traces
            for (size_t i = range.begin(); i < range.end(); ++i) {
                Sprite& sp = set.sprites[i];
                if (sp.kind != SpriteKind::kSurface || !(sp.material == water)) continue;
                const SurfaceParticles& S = shot.land->chunks[sp.item - trees];
                const size_t j = sp.particle;
                const glm::dvec3 world(S.position[j]);
                const glm::vec3 up = S.normal(j);
                // Its ripples: the stroke's random normal, then more drawn from its label, each
                // leaning the water's normal a little.
                glm::vec3 n[kMaxMirrorRays];
                n[0] = lighting_normal(up, S.random_normal(j), ripple);
                for (int k = 1; k < count; ++k) {
                    const float z = 2.0f * label_hash(S.label[j], 20u + k) - 1.0f;
                    const float a = 6.2831853f * label_hash(S.label[j], 40u + k);
                    const float rho = std::sqrt(std::max(0.0f, 1.0f - z * z));
                    n[k] = lighting_normal(up,
                                           glm::vec3(rho * static_cast<float>(pmath::cos(a)), z,
                                                     rho * static_cast<float>(pmath::sin(a))),
                                           ripple);
                }
                const glm::dvec3 dir = glm::normalize(world - c.view.camera.eye);
                rays.local() += static_cast<uint64_t>(mirror(
                    c, RayOrigin{world, up, true, shot.surface_lift}, n, count, up, dir, sp.k));
                ++strokes.local();
            }
        });
    rep.strokes = strokes.combine(std::plus<uint64_t>());
    rep.rays = rays.combine(std::plus<uint64_t>());
    return rep;
}

void reflections_stage(const FrameContext& ctx, const RayScene* sun_rays, SpriteSet& sprites) {
    StagePhase phase(ctx, "reflections");
    const ReflectionReport r = add_reflections(
        mirror_context(ctx.shot, ctx.view, ctx.plan, ctx.render(), sun_rays), sprites);
    ctx.report.reflection_rays = r.rays;
    phase.done(
        "each water stroke in view takes the colour its reflected ray finds (surfaces, "
        "trunks, leaf strokes, the sky), by water's Fresnel reflectance",
        std::to_string(r.strokes) + " water strokes, " + std::to_string(r.rays) + " rays");
}

}  // namespace pleinair
