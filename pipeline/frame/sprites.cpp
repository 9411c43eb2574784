// make_sprites: per tree and per surface chunk in parallel, concatenated in item order so the
// sprite list (and every byte painted from it) does not depend on threads.
#include "pipeline/frame/sprites.h"

#include <tbb/combinable.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>

#include "pipeline/shot/shot.h"
#include "shading/portable_math.h"

namespace pleinair {

namespace {

// One particle as the sprite maker reads it, whatever its kind.
struct SpriteInput {
    SpriteKind kind = SpriteKind::kLeaf;
    glm::dvec3 world{0.0};
    glm::vec3 normal{0.0f};   // world, unit: the lighting normal
    glm::vec3 tangent{0.0f};  // world, unit (bark, surfaces), or zero (leaves)
    double width = 0;         // world units
    double length = 0;
    float center_distance = 0.5f, branch_distance = 0.5f, label = 0;
    uint32_t tree_id = 0;
    float shadow = 1;  // light reaching the particle, 0..1 (IV.4.2)
    // Surface strokes (IV.7): their own lightness and frequencies, the crest shrink and the
    // distance fade. Null for leaves and bark.
    const SurfaceParticles* surface = nullptr;
    size_t index = 0;
    const Color* own_color = nullptr;  // an imported particle's colour
    float own_amount = 0;
    glm::vec3 from_center{0.0f};  // leaves: unit direction from the crown's centre (world)
    bool hole = false;            // leaves: in a hole of the crown (not drawn)
    ParticleLod lod;              // what the level of detail does to it (IV.6, IV.7)
};

// What every sprite of a frame shares.
struct SpriteContext {
    const Shot& shot;
    const Camera& cam;
    const RenderSettings& rs;
    const FramePlan& plan;
    const FrameLod& lod;
    glm::vec3 sun;
    double eye_speed;  // world units per frame
};

// A particle's stroke on screen at view depth z before the level of detail, in pixels: its
// width and length (the length times `crest`, Fig. 25), the thinnest enlarged to
// min_stroke_px with the length in proportion. The one rule for a sprite's size and the
// heights its occlusion rays start from.
void stroke_px(const Camera& cam, const RenderSettings& rs, const StrokeShaderParams& p,
               const SpriteInput& in, double z, float crest, float& w, float& l) {
    const float jitter = stroke_size_jitter(p, in.label);
    w = stroke_screen_px(cam, rs, in.width * jitter, z);
    l = stroke_screen_px(cam, rs, in.length * jitter, z) * crest;
    const float min_px = rs.min_stroke_px;
    if (w < min_px) l *= min_px / std::max(w, 1e-12f), w = min_px;
}

// Size, fade and crest shrink of a sprite on screen; false when nothing of it would show.
bool sprite_size(const SpriteContext& c, const SpriteMaterial& m, const SpriteInput& in,
                 const Projection& pr, Sprite& out) {
    float crest = 1.0f;
    if (in.surface) {
        const SurfaceParticles& S = *in.surface;
        // Fig. 25: a surface seen edge-on keeps only the middle of its sprites' height.
        glm::vec3 to_eye(glm::normalize(c.cam.eye - in.world));
        crest = crest_factor(glm::dot(S.normal(in.index), to_eye), m.surface->crest_shrink);
    }
    float w, l;
    stroke_px(c.cam, c.rs, *m.shader, in, pr.depth, crest, w, l);
    w *= in.lod.scale, l *= in.lod.scale;
    float fade = in.lod.fade;
    if (in.kind == SpriteKind::kLeaf) {
        const float e = crown_edge_size(*m.shader, in.center_distance);
        w *= e, l *= e;
        fade *= crown_edge_fade(*m.shader, in.center_distance);
    }
    if (!(w > 0.0f) || !(l > 0.0f) || !std::isfinite(w) || !std::isfinite(l)) return false;
    out.half_w = 0.5f * w;
    out.half_l = 0.5f * l;
    out.fade = fade;
    return true;
}

// Projects one particle to its sprite's place, size and direction on screen; returns false if
// it is culled (behind the camera, not finite, too small, too faint or off screen).
bool place_sprite(const SpriteContext& c, MaterialId mat, const SpriteInput& in, Sprite& out) {
    const SpriteMaterial& m = c.shot.materials[mat];
    const StrokeShaderParams& p = *m.shader;
    const Projection pr = project(c.cam, in.world);
    if (!pr.in_front) return false;
    if (!sprite_size(c, m, in, pr, out)) return false;
    out.x = pr.x;
    out.y = pr.y;
    out.depth = pr.depth;
    out.range = static_cast<float>(glm::length(in.world - c.cam.eye));
    // Two sprites overlapping on screen lie within the sum of their angular radii of each other
    // as seen from the eye, so the eye's travel changes their ranges' difference by at most the
    // sum of their swap speeds.
    out.swap_speed =
        static_cast<float>(c.eye_speed * pmath::hypot(out.half_w, out.half_l) / c.cam.focal_px);
    // Stroke direction on screen: along the projected tangent (a normal-free frame, so a limb
    // seen end-on still gets one), jittered by the label.
    double angle = 0;
    if (glm::dot(in.tangent, in.tangent) > 0) {
        glm::dvec3 t(in.tangent);
        double tx = glm::dot(t, c.cam.right), ty = -glm::dot(t, c.cam.up);
        if (tx * tx + ty * ty > 1e-8) angle = pmath::atan2(ty, tx) - 0.5 * M_PI;
    }
    angle += stroke_angle_jitter(p, in.label);
    out.ax = static_cast<float>(-pmath::sin(angle));
    out.ay = static_cast<float>(pmath::cos(angle));
    float ex, ey;
    sprite_extent(out, ex, ey);
    return !(pr.x + ex < 0 || pr.y + ey < 0 || pr.x - ex > c.cam.width || pr.y - ey > c.cam.height);
}

// The placed sprite's paint: its stroke constants, lit by in.shadow.
void shade_sprite(const SpriteContext& c, MaterialId mat, const SpriteInput& in, Sprite& out) {
    const SpriteMaterial& m = c.shot.materials[mat];
    const StrokeShaderParams& p = *m.shader;
    const float n_dot_l = glm::dot(in.normal, c.sun);
    float d = 0;
    const Atmosphere& a = c.shot.scene.atmosphere;
    if (c.plan.atmosphere)
        d = distance_value(out.depth, a.near_distance, a.far_distance, p.dist_curve_bias);
    const bool surface = in.kind == SpriteKind::kSurface;
    out.k = stroke_constants(p, n_dot_l, in.center_distance, in.branch_distance, in.label,
                             in.tree_id, in.shadow, d, in.lod.lod_distance,
                             !surface && c.plan.tint && p.unique_tint_amt > 0,
                             c.plan.atmosphere && has_atmosphere_effect(p));
    if (surface) {
        const SurfaceParticles& S = *in.surface;
        const float h = S.height(in.index);
        float l = surface_lightness(*m.surface, n_dot_l, h);
        if (in.shadow < 1.0f) l *= shadow_remap(in.shadow, p.shadow_bias);
        out.k.lightness = l;
        surface_frequencies(*m.surface, h, out.k.frequ_s, out.k.frequ_t);
        out.object_id = 0x10000u + S.material[in.index];
        if (in.own_color) {
            out.k.own = *in.own_color / m.mid_luminance;
            out.k.own_amount = in.own_amount;
        }
    } else {
        out.object_id = in.tree_id + 1;
        if (in.kind == SpriteKind::kLeaf && p.sun_side > 0.0f) {
            const float side = 0.5f + 0.5f * glm::dot(in.from_center, c.sun);
            out.k.lightness = crown_side_lightness(p, out.k.lightness, side);
            const float f = stroke_frequency(p, in.center_distance, out.k.lightness);
            out.k.frequ_s = f * p.s_frequ_scale, out.k.frequ_t = f * p.t_frequ_scale;
        }
    }
    out.kind = in.kind;
    if (!c.plan.sub_stroke) out.k.sub_amt = 0;
    if (in.lod.growth > 1.0f) {
        // A grown survivor's noise grows with it by the square root only: larger dabs, fewer
        // of them (IV.6's lower frequencies), without the whole crown going soft.
        const float f = std::sqrt(in.lod.growth);
        out.k.frequ_s *= f, out.k.frequ_t *= f;
    }
    reseed_noise(out.k, c.plan.noise_reseed);
    out.material = mat;
}

// The particle's sprite input, by kind; `light` is filled in by the caller.
SpriteInput sprite_input(const Shot& shot, size_t item, SpriteKind kind, size_t j,
                         const RayOrigin& o, MaterialId& mat) {
    const std::vector<BuiltTree>& trees = *shot.trees;
    SpriteInput in;
    in.kind = kind;
    in.world = o.world;
    if (kind == SpriteKind::kSurface) {
        const size_t chunk = item - trees.size();
        const SurfaceParticles& S = shot.land->chunks[chunk];
        mat = shot.materials.surface(S.material[j]);
        const SpriteMaterial& m = shot.materials[mat];
        double w = m.shader->sprite_size * shot.land->chunk_size[chunk] *
                   inside_size(S.height(j), m.surface->inside_growth);
        // A particle file's own sizes and colours, where it has them.
        const BuiltLandscape::ChunkSource from = chunk < shot.land->chunk_source.size()
                                                     ? shot.land->chunk_source[chunk]
                                                     : BuiltLandscape::ChunkSource{};
        if (from.file) {
            if (!from.file->width.empty()) w = from.file->width[from.first + j];
            if (!from.file->color.empty() && from.color_amount > 0)
                in.own_color = &from.file->color[from.first + j], in.own_amount = from.color_amount;
        }
        in.normal = lighting_normal(o.normal, S.random_normal(j), m.surface->random_normal_weight);
        in.tangent = glm::vec3(0, 1, 0);
        in.width = w;
        in.length = w * m.shader->stroke_aspect;
        in.label = S.label[j];
        in.surface = &S;
        in.index = j;
        return in;
    }
    const BuiltTree& b = trees[item];
    const TreePlacement& pl = shot.placements[item];
    const Family& fam = shot.scene.families[b.family];
    const bool bark = kind == SpriteKind::kBark;
    mat = bark ? shot.materials.bark(b.family) : shot.materials.leaf(b.family);
    const StrokeShaderParams& p = bark ? fam.bark_shader : fam.leaf_shader;
    in.width = tree_stroke_width(fam, p, b.scale);
    in.length = in.width * p.stroke_aspect;
    if (bark) {
        in.normal = o.normal;
        in.tangent = pl.turn(b.bark.tangent[j]);
        in.label = b.bark.label[j];
        in.tree_id = b.tree.id;
    } else {
        const LeafParticles& L = b.tree.leaves;
        in.normal = pl.turn(L.normal[j]);
        in.center_distance = L.center_distance[j];
        in.branch_distance = L.branch_distance[j];
        in.label = L.label[j];
        in.tree_id = L.tree_id[j];
        const glm::vec3 out = L.position[j] - b.tree.center;
        const float len = glm::length(out);
        if (len > 1e-6f && std::isfinite(len)) in.from_center = pl.turn(out / len);
        in.hole =
            crown_hole(p, L.position[j].x, L.position[j].y, L.position[j].z, L.center_distance[j]);
    }
    return in;
}

// The level of detail's fade, place and growth of a particle (lod.h); false when it has faded
// out. A survivor that moves takes its ray origin along.
bool apply_lod(const SpriteContext& c, size_t item, size_t j, SpriteInput& in, RayOrigin& o) {
    in.lod = particle_lod(c.shot, c.lod, item, in.kind, j, in.world);
    if (in.lod.gone()) return false;
    if (in.lod.moved) o.world = in.world = in.lod.world;
    return true;
}

}  // namespace

bool drawn_as_graftals(const Shot& shot, size_t item, SpriteKind kind, size_t j) {
    const std::vector<BuiltTree>& trees = *shot.trees;
    if (kind == SpriteKind::kLeaf)
        return shot.scene.families[trees[item].family].graftal != nullptr;
    if (kind == SpriteKind::kSurface)
        return shot.scene.materials[shot.land->chunks[item - trees.size()].material[j]].graftal !=
               nullptr;
    return false;
}

namespace {

// Counters summed over threads: one shared atomic, bumped for every ray, bounces between cores.
struct Counters {
    tbb::combinable<uint64_t> shadow_rays{[] { return uint64_t{0}; }};
    tbb::combinable<uint64_t> hidden{[] { return uint64_t{0}; }};
};

// A particle's stroke's world radius as `cam` draws it before the level of detail (sprite_size's
// rule, without the crest shrink and the survivors' growth).
double drawn_radius(const Camera& cam, const RenderSettings& rs, const SpriteMaterial& m,
                    const SpriteInput& in, const glm::dvec3& world) {
    const double z = std::max<double>(project(cam, world).depth, cam.near_depth);
    float w, l;
    stroke_px(cam, rs, *m.shader, in, z, 1.0f, w, l);
    return 0.5 * std::max(w, l) * z / cam.focal_px;
}

// How much of the sprite the camera sees past the opaque surfaces (none: it is culled; the
// sprites in front paint over the silhouette), from the rays of SeenWindow. The heights are
// points above the particle on the sprite, back-projected to its depth; only upwards, since
// below a ground stroke's centre lies the ground. `o` is where the sprite is painted; a
// moving camera's rays start from the particle's own place (`at`) and size, which no frame
// changes, so a lattice time's rays are the same whichever frame casts them (the level of
// detail moves and grows survivors a little every frame).
float visibility(const SpriteContext& c, const SeenWindow* window, const SpriteMaterial& m,
                 const SpriteInput& in, const RayOrigin& at, const RayOrigin& o, const Sprite& sp,
                 Counters& n) {
    if (!c.shot.view_rays) return 1.0f;
    static constexpr double kHeight[3] = {0.0, 0.5, 1.0};
    auto seen_from = [&](const Camera& cam, const RayOrigin& o, int height, double radius) {
        const glm::dvec3 from = o.lifted() + cam.up * (kHeight[height] * radius);
        const glm::dvec3 to_eye = cam.eye - from;
        const double dist = glm::length(to_eye);
        // Any hit short of the eye hides it: an occlusion query, cheaper than the nearest hit.
        return !(dist > 0) ||
               !c.shot.view_rays->occluded(from, glm::vec3(to_eye / dist),
                                           static_cast<float>(dist) * 0.999f, o.surface_normal());
    };
    int seen = 0, rays = 0;
    if (!window || window->cameras.empty()) {
        const double radius = std::max(sp.half_w, sp.half_l) * sp.depth / c.cam.focal_px;
        for (int h = 0; h < 3; ++h) seen += seen_from(c.cam, o, h, radius);
        rays = 3;
    } else {
        for (size_t i = 0; i < window->cameras.size(); ++i) {
            const Camera& cam = window->cameras[i];
            seen +=
                seen_from(cam, at, window->heights[i], drawn_radius(cam, c.rs, m, in, at.world));
        }
        rays = static_cast<int>(window->cameras.size());
    }
    if (seen == 0) ++n.hidden.local();
    return static_cast<float>(seen) / static_cast<float>(rays);
}

// The 4 x 4 grid of light over a sprite's footprint, back-projected at the particle's depth.
ShadowGrid shadow_grid(const SpriteContext& c, const RayScene& sun_rays, const RayOrigin& o,
                       const Sprite& sp, Counters& n) {
    ShadowGrid g;
    const double world_per_px = sp.depth / c.cam.focal_px;
    for (int j = 0; j < kShadowGrid; ++j)
        for (int i = 0; i < kShadowGrid; ++i) {
            const double s = (i + 0.5) / kShadowGrid - 0.5, t = (j + 0.5) / kShadowGrid - 0.5;
            const double dx = 2 * s * sp.half_w * sp.ay + 2 * t * sp.half_l * sp.ax;
            const double dy = -2 * s * sp.half_w * sp.ax + 2 * t * sp.half_l * sp.ay;
            RayOrigin at = o;
            at.world = o.world + (c.cam.right * dx - c.cam.up * dy) * world_per_px;
            ++n.shadow_rays.local();
            g[static_cast<size_t>(j) * kShadowGrid + i] =
                sun_light_at(sun_rays, at, c.sun, c.rs.shadows);
        }
    return g;
}

}  // namespace

float grid_at(const ShadowGrid& g, float s, float t) {
    constexpr int kGrid = kShadowGrid;
    const float x = std::clamp(s * kGrid - 0.5f, 0.0f, kGrid - 1.0f);
    const float y = std::clamp(t * kGrid - 0.5f, 0.0f, kGrid - 1.0f);
    const int i = std::min(static_cast<int>(x), kGrid - 2),
              j = std::min(static_cast<int>(y), kGrid - 2);
    const float fx = x - i, fy = y - j;
    const float* r0 = &g[static_cast<size_t>(j) * kGrid + i];
    const float* r1 = r0 + kGrid;
    return (r0[0] * (1 - fx) + r0[1] * fx) * (1 - fy) + (r1[0] * (1 - fx) + r1[1] * fx) * fy;
}

void reseed_noise(StrokeConstants& k, uint32_t noise_reseed) {
    if (!noise_reseed) return;
    const float shift = 256.0f * tree_hash01(noise_reseed);
    k.offset_s = std::fmod(k.offset_s + shift, 256.0f);
    k.offset_t = std::fmod(k.offset_t + 0.618f * shift, 256.0f);
}

void sprite_extent(const Sprite& sp, float& ex, float& ey) {
    ex = std::abs(sp.ax) * sp.half_l + std::abs(sp.ay) * sp.half_w;
    ey = std::abs(sp.ay) * sp.half_l + std::abs(sp.ax) * sp.half_w;
}

// True perspective scaled by (focus / z)^(1 - stroke_perspective), so strokes shrink less than
// geometry.
float stroke_screen_px(const Camera& cam, const RenderSettings& r, double world, double z) {
    double p = std::clamp<double>(r.stroke_perspective, 0.0, 1.0);
    double px = cam.focal_px * world / (pmath::pow(cam.focus_distance, 1.0 - p) * pmath::pow(z, p));
    return static_cast<float>(px);
}

SpriteSet make_sprites(const SpriteStageInput& input) {
    const Shot& shot = input.shot;
    const FramePlan& plan = input.plan;
    const RenderSettings& rs = input.settings;
    const RayScene* sun_rays = input.sun_rays;
    const SpriteContext c{shot,
                          input.view.camera,
                          rs,
                          plan,
                          input.lod,
                          glm::vec3(input.view.sun_direction),
                          input.view.eye_speed};
    const size_t items = shot.item_count();
    std::vector<SpriteSet> per_item(items);
    Counters counters;
    const bool traced = plan.sun_light == SunLightSource::kShotScene ||
                        plan.sun_light == SunLightSource::kFrameScene;
    tbb::parallel_for(size_t{0}, items, [&](size_t i) {
        FlushDenormals ftz;  // Embree's modes, while this task traces
        SpriteSet& out = per_item[i];
        size_t k = 0;  // the particle's index in the shot's light cache
        for_each_particle(shot, i, [&](SpriteKind kind, size_t j, const RayOrigin& origin) {
            const size_t slot = k++;
            if (drawn_as_graftals(shot, i, kind, j)) return;
            // Cheapest test first: faded out, on screen, then seen past the surfaces, then lit.
            MaterialId mat;
            // Where it is painted, which the level of detail may move; its light stays the
            // particle's own (as the shot's light cache has it).
            RayOrigin o = origin;
            SpriteInput in = sprite_input(shot, i, kind, j, o, mat);
            if (in.hole) return void(++out.culled);
            if (!apply_lod(c, i, j, in, o)) return void((++out.culled, ++out.faded));
            Sprite sp;
            sp.item = static_cast<uint32_t>(i), sp.particle = static_cast<uint32_t>(j);
            if (!place_sprite(c, mat, in, sp)) return void(++out.culled);
            const float seen =
                visibility(c, input.seen, shot.materials[mat], in, origin, o, sp, counters);
            if (!(seen > 0.0f)) return void(++out.culled);
            sp.fade *= seen;
            if (plan.sun_light == SunLightSource::kShot)
                in.shadow = shot.sun_light[i][slot];
            else if (traced && !plan.fragment_shadows)
                ++counters.shadow_rays.local(),
                    in.shadow = sun_light_at(*sun_rays, origin, c.sun, rs.shadows);
            in.shadow += (1.0f - in.shadow) * in.lod.shadow_lift;
            shade_sprite(c, mat, in, sp);
            if (plan.fragment_shadows) {
                sp.grid = static_cast<int32_t>(out.grids.size());
                out.grids.push_back(shadow_grid(c, *sun_rays, o, sp, counters));
            }
            out.sprites.push_back(sp);
        });
    });
    SpriteSet all;
    for (SpriteSet& s : per_item) {
        for (Sprite& sp : s.sprites) {
            if (sp.grid >= 0) sp.grid += static_cast<int32_t>(all.grids.size());
            (sp.kind == SpriteKind::kLeaf   ? all.leaf
             : sp.kind == SpriteKind::kBark ? all.bark
                                            : all.surface)++;
        }
        all.grids.insert(all.grids.end(), s.grids.begin(), s.grids.end());
        all.sprites.insert(all.sprites.end(), s.sprites.begin(), s.sprites.end());
        all.culled += s.culled;
        all.faded += s.faded;
        s = SpriteSet{};
    }
    all.shadow_rays = counters.shadow_rays.combine(std::plus<uint64_t>());
    all.hidden = counters.hidden.combine(std::plus<uint64_t>());
    return all;
}

SpriteSet sprites_stage(const FrameContext& ctx, const FrameLod& lod, const RayScene* sun_rays,
                        const SeenWindow& seen) {
    StagePhase phase(ctx, "sprites", true);
    const FramePlan& plan = ctx.plan;
    SpriteSet sprites =
        make_sprites({ctx.shot, ctx.view, plan, ctx.render(), lod, sun_rays, &seen});
    FrameReport& rep = ctx.report;
    rep.leaf_sprites = sprites.leaf, rep.bark_sprites = sprites.bark;
    rep.surface_sprites = sprites.surface, rep.culled = sprites.culled;
    rep.shadow_rays = sprites.shadow_rays;
    phase.done(
        std::string("every particle faces the camera") +
            (plan.fragment_shadows                     ? "; 4 x 4 shadow rays per sprite"
             : plan.sun_light == SunLightSource::kShot ? "; light from the shot"
             : plan.shadows                            ? "; a shadow ray per particle"
                                                       : "") +
            (!plan.underpaint       ? ""
             : seen.cameras.empty() ? "; hidden ones culled"
                                    : "; hidden ones culled, seen from where the eye is over " +
                                          std::to_string(seen.cameras.size()) + " frames"),
        std::to_string(sprites.sprites.size()) + " sprites, " + std::to_string(sprites.culled) +
            " culled (" + std::to_string(sprites.hidden) + " hidden, " +
            std::to_string(sprites.faded) + " faded out)" +
            (sprites.shadow_rays ? ", " + std::to_string(sprites.shadow_rays) + " shadow rays"
                                 : ""));
    return sprites;
}

}  // namespace pleinair
