// water_reflectance, mirror, mirror_lattice and add_reflections.
#include "pipeline/frame/reflection.h"

#include <tbb/combinable.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>

#include "pipeline/frame/background.h"
#include "pipeline/frame/distance_mass.h"
#include "pipeline/frame/mirror_memo.h"
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
    MirrorContext c{shot, view, plan, settings, nullptr, {}, FramePlan{}};
    if (sun_rays && sun_rays->caster_count() > 0) c.sun_rays = sun_rays;
    // Built once: copying the plan's notes for every ray cost an allocation per ray.
    c.flat = plan;
    c.flat.decisions.clear();
    c.flat.reflections = false;
    // What the water mirrors keeps the haze it has where it stands (the far bank mirrored as
    // pale and blue as it is seen); the water's own atmosphere comes after, on the mirror.
    const SceneDesc& scene = shot.scene;
    const bool haze = plan.atmosphere && scene.has_atmosphere;
    const int steps = haze ? MirrorContext::kFoliageDepths : 1;
    c.foliage.assign(static_cast<size_t>(steps), Color(0.0f));
    if (scene.families.empty()) return c;
    for (int i = 0; i < steps; ++i) {
        const float depth =
            static_cast<float>(scene.atmosphere.near_distance +
                               (scene.atmosphere.far_distance - scene.atmosphere.near_distance) *
                                   i / std::max(steps - 1, 1));
        for (const Family& f : scene.families) {
            const StrokeShaderParams& p = f.leaf_shader;
            const bool on = haze && has_atmosphere_effect(p);
            const float d = on ? distance_value(depth, scene.atmosphere.near_distance,
                                                scene.atmosphere.far_distance, p.dist_curve_bias)
                               : 0.0f;
            StrokeConstants k =
                stroke_constants(p, 0.5f, 0.5f, 0.5f, 0.5f, 0, 1.0f, d, 0.0f, false, on);
            if (haze) lay_in_distance_value(scene.atmosphere, depth, k);
            c.foliage[static_cast<size_t>(i)] +=
                finish_color(k, palette_lookup(f.leaf_palette, 0.3f));
        }
        c.foliage[static_cast<size_t>(i)] /= static_cast<float>(scene.families.size());
    }
    return c;
}

Color mirrored_foliage(const MirrorContext& c, float distance) {
    if (c.foliage.size() < 2) return c.foliage.empty() ? Color(0.0f) : c.foliage[0];
    const auto& a = c.shot.scene.atmosphere;
    const float span = static_cast<float>(a.far_distance - a.near_distance);
    const float u = span > 0.0f ? clamp01((distance - static_cast<float>(a.near_distance)) / span)
                                : (distance >= static_cast<float>(a.far_distance) ? 1.0f : 0.0f);
    const float x = u * static_cast<float>(c.foliage.size() - 1);
    const size_t i = std::min(static_cast<size_t>(x), c.foliage.size() - 2);
    return mix(c.foliage[i], c.foliage[i + 1], x - static_cast<float>(i));
}

namespace {
// What one reflected ray sees from `at`: the view `dir` reflected about `n`, hazed for the
// light's path, `eye_distance` to the water and on from there. Adds its rays.
Color mirrored(const MirrorContext& c, const RayOrigin& at, const glm::vec3& n,
               const glm::dvec3& dir, double eye_distance, int& rays) {
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
        // The hit's own flat colour, as the underpainting paints it (it casts its shadow ray),
        // in the haze of the light's path; the water's atmosphere comes after, on the mirror.
        seen = surface_hit_color(c.shot, c.view, c.flat, c.settings, c.sun_rays, h,
                                 from + r * static_cast<double>(h.t), h.normal, r,
                                 static_cast<float>(eye_distance + h.t));
        rays += c.flat.shadows && c.sun_rays;
    } else {
        seen = c.plan.sky ? sky_color(scene, rf, glm::vec3(c.view.sun_direction))
                          : background_at(scene.background, r);
    }
    if (c.sun_rays) {
        // Leaf strokes between the water and what it mirrors, as the sun's casters, hazed for
        // the path to where the ray meets them. The eye's place enters only by its distance, so
        // a mirror traced from a lattice frame's eye is the same whichever frame asks.
        float t = 0.0f;
        const float through = c.sun_rays->transmittance_depth(
            from, rf, h.hit ? h.t * 0.999f : std::numeric_limits<float>::infinity(),
            at.surface_normal(), t);
        seen = mix(mirrored_foliage(c, static_cast<float>(eye_distance + t)), seen, through);
        ++rays;
    }
    return seen;
}
}  // namespace

Color mirror_seen(const MirrorContext& c, const RayOrigin& at, const glm::vec3* normals, int count,
                  const glm::dvec3& dir, double eye_distance, int& rays) {
    Color seen(0.0f);
    for (int i = 0; i < count; ++i) seen += mirrored(c, at, normals[i], dir, eye_distance, rays);
    return seen / static_cast<float>(count);
}

void set_mirror(const MirrorContext& c, const Color& seen, const glm::vec3& up,
                const glm::dvec3& dir, StrokeConstants& k) {
    const float amount_max = clamp01(c.shot.scene.water.reflection);
    // Silvered: the reflectance taken part of the way to 1, the painter's light pond over the
    // physicist's dark one.
    const float silver = clamp01(c.shot.scene.water.silver);
    const float physical = water_reflectance(static_cast<float>(glm::dot(dir, glm::dvec3(up))));
    const float fresnel = physical + (1.0f - physical) * silver;
    const float amount = amount_max * fresnel;
    const float dim = 1.0f - kNearDarken * amount_max * (1.0f - fresnel);
    const Color grey(luminance(seen));
    k.mirror = mix(grey, seen, clamp01(c.shot.scene.water.mirror_saturation)) * (amount * dim);
    k.mirror_keep = (1.0f - amount) * dim;
    // Where it mirrors, the water's own colour is its body's, dark (its surface scatters little
    // light): the stroke's lightness falls with the share the mirror takes, so the reflection
    // stays darker than what it mirrors.
    k.lightness *= 1.0f - amount;
}

int mirror(const MirrorContext& c, const RayOrigin& at, const glm::vec3* normals, int count,
           const glm::vec3& up, const glm::dvec3& dir, double eye_distance, StrokeConstants& k) {
    if (!(clamp01(c.shot.scene.water.reflection) > 0.0f) || !c.shot.view_rays || count < 1)
        return 0;
    int rays = 0;
    set_mirror(c, mirror_seen(c, at, normals, count, dir, eye_distance, rays), up, dir, k);
    return rays;
}

MirrorLattice mirror_lattice(const SceneDesc& scene, const FrameView& view, int frames) {
    MirrorLattice l;
    if (frames <= 1 || !view.on_track || !(view.eye_speed > 0) || !scene.sun_track.empty() ||
        scene.camera_track.keys.empty())
        return l;
    l.frames = frames;
    l.u = view.time * scene.fps;
    // A frame's own time, (N - 1) / fps times fps, may fall a last bit short of N - 1.
    l.base = static_cast<int64_t>(std::floor(l.u + 1e-6));
    if (std::abs(l.u - static_cast<double>(l.base)) < 1e-6) l.u = static_cast<double>(l.base);
    l.first = l.base - frames + 1;
    for (int64_t m = l.first; m <= l.base + frames; ++m) {
        Camera cam = view.camera;
        // The frame's own rule for its camera (view_at), so lattice time N - 1 is frame N's eye;
        // a key the track's checks let through cannot fail here.
        if (!track_camera(scene, static_cast<double>(m) / scene.fps, cam).empty())
            cam = view.camera;
        l.eyes.push_back(cam.eye);
    }
    return l;
}

int64_t mirror_phase(float label, int frames) {
    return std::min<int64_t>(frames - 1, static_cast<int64_t>(label_hash(label, 61u) * frames));
}

namespace {

// The mirror a particle finds from the eye at lattice time m: the memo's, or traced (and kept).
struct LatticeMirror {
    const MirrorContext& c;
    const MirrorLattice& l;
    MirrorMemo::Entry* entry;  // null: no memo
    const RayOrigin& at;
    const glm::dvec3& world;
    const glm::vec3* normals;
    int count;
    int rays = 0;

    Color at_time(int64_t m, int64_t keep) {
        if (entry)
            for (int s = 0; s < 2; ++s)
                if (entry->time[s] == m) return entry->seen[s];
        const glm::dvec3 to = world - l.eyes[static_cast<size_t>(m - l.first)];
        const Color seen =
            mirror_seen(c, at, normals, count, glm::normalize(to), glm::length(to), rays);
        if (entry) {
            // Over the slot this frame does not read, else the older (kNone is the oldest).
            const int s = entry->time[0] == keep   ? 1
                          : entry->time[1] == keep ? 0
                                                   : (entry->time[0] < entry->time[1] ? 0 : 1);
            entry->time[s] = m, entry->seen[s] = seen;
        }
        return seen;
    }

    // The colour at the frame's time: linear between the lattice times either side.
    Color seen(float label) {
        const int64_t k = l.frames, phase = mirror_phase(label, l.frames);
        const int64_t m0 = l.base - (((l.base - phase) % k) + k) % k;
        const float w =
            static_cast<float>((l.u - static_cast<double>(m0)) / static_cast<double>(k));
        const Color s0 = at_time(m0, m0 + k);
        if (!(w > 0.0f)) return s0;
        const Color s1 = at_time(m0 + k, m0);
        return s0 + w * (s1 - s0);
    }
};

}  // namespace

ReflectionReport add_reflections(const MirrorContext& c, SpriteSet& set,
                                 const MirrorLattice* lattice, MirrorMemo* memo) {
    ReflectionReport rep;
    const Shot& shot = c.shot;
    if (!(clamp01(shot.scene.water.reflection) > 0.0f) || !shot.view_rays) return rep;
    const MaterialId water = shot.materials.surface(shot.scene.water.material);
    const float ripple = shot.scene.water.ripple;
    const int count = std::clamp(shot.scene.water.mirror_rays, 1, kMaxMirrorRays);
    const size_t trees = shot.trees->size();
    const bool on_lattice = lattice && lattice->frames > 1;
    auto is_water = [&](const Sprite& sp) {
        return sp.kind == SpriteKind::kSurface && sp.material == water;
    };
    // The memo's arrays made here, on one thread, for the chunks with water in view.
    std::vector<MirrorMemo::Entry*> entries;
    if (on_lattice && memo) {
        entries.assign(shot.land->chunks.size(), nullptr);
        for (const Sprite& sp : set.sprites) {
            if (!is_water(sp)) continue;
            const size_t ch = sp.item - trees;
            if (!entries[ch])
                entries[ch] = memo->entries(ch, shot.land->chunks[ch].position.size());
        }
    }
    tbb::combinable<uint64_t> strokes{[] { return uint64_t{0}; }}, rays{[] { return uint64_t{0}; }};
    tbb::parallel_for(
        tbb::blocked_range<size_t>(0, set.sprites.size(), 512),
        [&](const tbb::blocked_range<size_t>& range) {
            FlushDenormals ftz;  // Embree's modes, while this task traces
            for (size_t i = range.begin(); i < range.end(); ++i) {
                Sprite& sp = set.sprites[i];
                if (!is_water(sp)) continue;
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
                const glm::dvec3 to = world - c.view.camera.eye;
                const glm::dvec3 dir = glm::normalize(to);
                const RayOrigin at{world, up, true, shot.surface_lift};
                if (on_lattice) {
                    MirrorMemo::Entry* e = entries.empty() ? nullptr : entries[sp.item - trees] + j;
                    LatticeMirror lm{c, *lattice, e, at, world, n, count};
                    set_mirror(c, lm.seen(S.label[j]), up, dir, sp.k);
                    rays.local() += static_cast<uint64_t>(lm.rays);
                } else {
                    rays.local() += static_cast<uint64_t>(
                        mirror(c, at, n, count, up, dir, glm::length(to), sp.k));
                }
                ++strokes.local();
            }
        });
    rep.strokes = strokes.combine(std::plus<uint64_t>());
    rep.rays = rays.combine(std::plus<uint64_t>());
    return rep;
}

void reflections_stage(const FrameContext& ctx, const RayScene* sun_rays, SpriteSet& sprites) {
    StagePhase phase(ctx, "reflections");
    const RenderSettings& rs = ctx.render();
    const MirrorLattice lattice = mirror_lattice(ctx.shot.scene, ctx.view, rs.reflection_frames);
    MirrorMemo* memo = lattice.frames > 1 ? ctx.settings.mirror_memo : nullptr;
    const MirrorContext c = mirror_context(ctx.shot, ctx.view, ctx.plan, rs, sun_rays);
    if (memo)
        memo->begin_frame(ctx.shot, c.sun_rays, lattice.frames, static_cast<int>(rs.shadows),
                          c.flat.sky, c.flat.shadows);
    const ReflectionReport r = add_reflections(c, sprites, &lattice, memo);
    ctx.report.reflection_rays = r.rays;
    std::string how =
        std::to_string(r.strokes) + " water strokes, " + std::to_string(r.rays) + " rays";
    if (lattice.frames > 1)
        how += " (traced from the eye every " + std::to_string(lattice.frames) + " frames" +
               (memo ? ", the others kept from frames before)" : " either side of this one)");
    phase.done(
        "each water stroke in view takes the colour its reflected ray finds (surfaces, "
        "trunks, leaf strokes, the sky), by water's Fresnel reflectance; while the camera "
        "moves, from its eye at every /render/reflection_frames-th frame, interpolated between",
        how);
}

}  // namespace pleinair
