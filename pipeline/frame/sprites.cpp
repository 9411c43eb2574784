// make_sprites: per tree and per surface chunk in parallel, concatenated in item order so the
// sprite list (and every byte painted from it) does not depend on threads.
#include "pipeline/frame/sprites.h"

#include <tbb/combinable.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>

#include "pipeline/frame/buffer_pool.h"
#include "pipeline/frame/distance_mass.h"
#include "pipeline/frame/group_cull.h"
#include "pipeline/frame/seen_memo.h"
#include "pipeline/shot/particle_input.h"
#include "pipeline/shot/shot.h"
#include "shading/portable_math.h"

namespace pleinair {

namespace {

// One particle as the sprite maker reads it (particle_input.h), with what the level of detail
// does to it.
struct SpriteInput : ParticleInput {
    ParticleLod lod;
    float spin = 0;        // the wind's turn of a leaf's stroke about its normal (radians)
    float wind_speed = 0;  // the farther the wind moves it into or out of this frame (world)
};

// What every sprite of a frame shares.
struct SpriteContext {
    const Shot& shot;
    const Camera& cam;
    const RenderSettings& rs;
    const FramePlan& plan;
    const FrameLod& lod;
    glm::vec3 sun;
    double eye_speed;       // world units per frame
    const FrameWind* wind;  // null or off: the trees at rest
};

// A particle's stroke on screen at view depth z before the level of detail, in pixels: its
// width and length (the length times `crest`, Fig. 25), the thinnest enlarged to
// min_stroke_px with the length in proportion. The one rule for a sprite's size and the
// heights its occlusion rays start from.
void stroke_px(const Camera& cam, const RenderSettings& rs, const StrokeShaderParams& p,
               const SpriteInput& in, double z, float crest, float& w, float& l) {
    const float jitter = stroke_size_jitter(p, in.label);
    const double px_per_world = stroke_screen_px(cam, rs, 1.0, z);
    w = static_cast<float>(px_per_world * in.width * jitter);
    l = static_cast<float>(px_per_world * in.length * jitter) * crest;
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
    // The wind moves the particle itself by up to wind_speed a frame.
    out.swap_speed =
        static_cast<float>(c.eye_speed * pmath::hypot(out.half_w, out.half_l) / c.cam.focal_px) +
        in.wind_speed;
    // Stroke direction on screen: along the projected tangent (a normal-free frame, so a limb
    // seen end-on still gets one), else the shader's stroke_angle; jittered by the label.
    double angle = 0;
    if (glm::dot(in.tangent, in.tangent) > 0) {
        glm::dvec3 t(in.tangent);
        double tx = glm::dot(t, c.cam.right), ty = -glm::dot(t, c.cam.up);
        if (tx * tx + ty * ty > 1e-8) angle = pmath::atan2(ty, tx) - 0.5 * M_PI;
    } else {
        // The sprite's axis (-sin a, cos a) runs down the screen at a = 0; a turn by -a is
        // counter-clockwise as the viewer sees it (rows run down).
        angle = -static_cast<double>(p.stroke_angle) * M_PI / 180.0;
    }
    angle += stroke_angle_jitter(p, in.label) + in.spin;
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
    if (c.plan.atmosphere) lay_in_distance_value(a, out.depth, out.k);
    if (surface) {
        const SurfaceParticles& S = *in.surface;
        const float h = S.height(in.index);
        float l = surface_lightness(*m.surface, n_dot_l, h);
        if (in.shadow < 1.0f) l *= shadow_remap(in.shadow, p.shadow_bias);
        // The tree's shade at its foot: a dark accent there, the palette's darks (never black),
        // as the sun's shadow remapped could not make it against a lit ground.
        l *= in.contact;
        out.k.lightness = l;
        surface_frequencies(*m.surface, h, out.k.frequ_s, out.k.frequ_t);
        out.object_id = surface_object_id(S.material[in.index]);
        if (in.own_color) {
            out.k.own = *in.own_color / m.mid_luminance;
            out.k.own_amount = in.own_amount;
        }
    } else {
        out.object_id = in.tree_id + 1;
        if (in.kind == SpriteKind::kLeaf && p.sun_side > 0.0f) {
            const float side = 0.5f + 0.5f * glm::dot(in.from_center, c.sun);
            out.k.lightness = crown_side_lightness(p, out.k.lightness, side);
            const StrokeNoise n =
                stroke_noise_for(p, out.k.lightness, in.center_distance, in.label);
            out.k.frequ_s = n.frequ_s, out.k.frequ_t = n.frequ_t;
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
    SpriteInput in;
    static_cast<ParticleInput&>(in) = particle_input(shot, item, kind, j, o, mat);
    return in;
}

// The thinning of small strokes (lod.h's thin_presence): a stroke drawn narrower than
// render/thin_below_px (stroke_px's width, enlarged to min_stroke_px, times its level of
// detail's scale) is kept by its draw, and a survivor grows to keep the area they all covered,
// at most render/thin_max_growth. False when it is thinned out.
bool thin(const SpriteContext& c, const SpriteMaterial& m, size_t item, size_t j, SpriteInput& in) {
    const double z = view_depth(c.cam, in.world);
    if (!(z > c.cam.near_depth)) return true;
    const float jitter = stroke_size_jitter(*m.shader, in.label);
    const float w = stroke_screen_px(c.cam, c.rs, in.width * jitter, z);
    const float drawn = std::max(w, c.rs.min_stroke_px) * in.lod.scale;
    const float r = drawn / c.rs.thin_below_px;
    if (!(r < 1.0f)) return true;
    const float kept = thin_presence(r, thin_draw(item, in.kind, j));
    if (!(kept > 0.0f)) return false;
    in.lod.fade *= kept;
    const float grow = std::min(1.0f / std::sqrt(thin_kept(r * r)), c.rs.thin_max_growth);
    in.lod.scale *= grow;
    in.lod.growth *= grow;
    return true;
}

// Where the wind takes a tree's particle this frame (wind_stage.h): moved with its joint, its
// directions turned, its stroke spun about its normal, and how fast it moves for the depth
// order. Its ray origin moves along for the rays that follow it (shadows per fragment).
void blow(const SpriteContext& c, size_t item, SpriteKind kind, size_t j, SpriteInput& in,
          RayOrigin& o) {
    const BuiltTree& b = (*c.shot.trees)[item];
    const bool leaf = kind == SpriteKind::kLeaf;
    const glm::vec3& local = leaf ? b.tree().leaves.position[j] : b.bark().position[j];
    const WindMove m = wind_move(c.shot, *c.wind, item, leaf, j, local, in.label);
    in.spin = m.spin;
    if (!m.moved) return;
    in.world += m.delta;
    o.world += m.delta;
    in.wind_speed = m.speed;
    in.normal = glm::normalize(m.turn * in.normal);
    if (glm::dot(in.tangent, in.tangent) > 0) in.tangent = glm::normalize(m.turn * in.tangent);
    if (glm::dot(in.from_center, in.from_center) > 0)
        in.from_center = glm::normalize(m.turn * in.from_center);
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
    tbb::combinable<uint64_t> occlusion_rays{[] { return uint64_t{0}; }};
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
// sprites in front paint over the silhouette), from the occlusion maps (occlusion_map.h) of
// the seen window's cameras. The heights are points above the particle on the sprite,
// back-projected to its depth; only upwards, since below a ground stroke's centre lies the
// ground. `o` is where the sprite is painted; a moving camera's window tests the particle's
// own place (`at`) and size, which no frame changes, so a lattice time's answer is the same
// whichever frame asks (the level of detail moves and grows survivors a little every frame).
float visibility(const SpriteContext& c, const SeenWindow* window,
                 const std::vector<OcclusionMap>& maps, const SpriteMaterial& m,
                 const SpriteInput& in, const RayOrigin& at, const RayOrigin& o, const Sprite& sp,
                 uint8_t* const* memo, size_t slot, Counters& n) {
    if (!c.shot.view_rays) return 1.0f;
    static constexpr double kHeight[3] = {0.0, 0.5, 1.0};
    // From camera `cam`, whose map (the frame plan's occlusion_maps) is `map` or null.
    // `answer`: where the ray's answer is kept from frame to frame (SeenMemo), or null.
    auto seen_from = [&](const Camera& cam, const OcclusionMap* map, const RayOrigin& o, int height,
                         double radius, uint8_t* answer) {
        const glm::dvec3 from = o.lifted() + cam.up * (kHeight[height] * radius);
        const glm::dvec3 d = from - cam.eye;
        const double z = glm::dot(d, cam.forward);
        if (map && z > cam.near_depth) {
            const double f = cam.focal_px / z;
            const MapAnswer a = occluded_at(*map, 0.5 * cam.width + f * glm::dot(d, cam.right),
                                            0.5 * cam.height - f * glm::dot(d, cam.up), z);
            if (a != MapAnswer::kUnsure) return a == MapAnswer::kSeen;
        }
        // No map, or on a surface, at a silhouette or off the map: its own ray towards the
        // eye, where any hit short of the eye hides it (an occlusion query, cheaper than the
        // nearest hit).
        const glm::dvec3 to_eye = cam.eye - from;
        const double dist = glm::length(to_eye);
        ++n.occlusion_rays.local();
        const bool s = !(dist > 0) || !c.shot.view_rays->occluded(from, glm::vec3(to_eye / dist),
                                                                  static_cast<float>(dist) * 0.999f,
                                                                  o.surface_normal());
        if (answer) *answer = s ? SeenMemo::kSeen : SeenMemo::kHidden;
        return s;
    };
    int seen = 0, tests = 0;
    if (!window || window->cameras.empty()) {
        const double radius = std::max(sp.half_w, sp.half_l) * sp.depth / c.cam.focal_px;
        const OcclusionMap* map = maps.empty() ? nullptr : &maps[0];
        for (int h = 0; h < 3; ++h) seen += seen_from(c.cam, map, o, h, radius, nullptr);
        tests = 3;
    } else {
        for (size_t i = 0; i < window->cameras.size(); ++i) {
            // An answer kept is a ray's, cast where this camera's map (the same every frame) was
            // unsure or absent: taken first, before the stroke's size is worked out.
            uint8_t* answer = memo ? &memo[i][slot] : nullptr;
            if (answer && *answer != SeenMemo::kUnknown) {
                seen += *answer == SeenMemo::kSeen;
                continue;
            }
            const Camera& cam = window->cameras[i];
            seen += seen_from(cam, maps.empty() ? nullptr : &maps[i], at, window->heights[i],
                              drawn_radius(cam, c.rs, m, in, at.world), answer);
        }
        tests = static_cast<int>(window->cameras.size());
    }
    if (seen == 0) ++n.hidden.local();
    return static_cast<float>(seen) / static_cast<float>(tests);
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

namespace {

// Makes the sprites of one item into `out`, particle by particle.
struct ItemSprites {
    const SpriteContext& c;
    const SpriteStageInput& input;
    size_t item;
    SpriteSet& out;
    Counters& counters;
    const std::vector<OcclusionMap>& maps;  // the seen window's (seen_memo.h)
    std::vector<uint8_t*> memo;  // per window camera, this item's rays' answers kept from before

    void remember() {
        if (!input.seen_memo || !input.seen || input.seen->cameras.empty()) return;
        const size_t n = item_particles(c.shot, item);
        for (size_t k = 0; k < input.seen->cameras.size(); ++k)
            memo.push_back(input.seen_memo->answers(k, item, n));
    }

    void particle(SpriteKind kind, size_t j, const RayOrigin& origin, size_t slot) {
        const Shot& shot = c.shot;
        const FramePlan& plan = c.plan;
        if (drawn_as_graftals(shot, item, kind, j)) return;
        // Cheapest test first: faded out, on screen, thinned, then seen past the surfaces, then
        // lit.
        MaterialId mat;
        // Where it is painted, which the level of detail may move; its light stays the
        // particle's own (as the shot's light cache has it).
        RayOrigin o = origin;
        SpriteInput in = sprite_input(shot, item, kind, j, o, mat);
        if (in.hole) return void(++out.culled);
        if (!apply_lod(c, item, j, in, o)) return void((++out.culled, ++out.faded));
        Sprite sp;
        sp.item = static_cast<uint32_t>(item), sp.particle = static_cast<uint32_t>(j);
        if (c.lod.thin_small && !thin(c, shot.materials[mat], item, j, in))
            return void((++out.culled, ++out.thinned));
        // Seen past the surfaces from where it stands at rest: the wind's sway never hides a
        // stroke behind a trunk or a crest in one frame.
        const RayOrigin at_rest = o;
        if (c.wind && c.wind->on && kind != SpriteKind::kSurface) blow(c, item, kind, j, in, o);
        if (!place_sprite(c, mat, in, sp)) return void(++out.culled);
        const float seen = visibility(c, input.seen, maps, shot.materials[mat], in, origin, at_rest,
                                      sp, memo.empty() ? nullptr : memo.data(), slot, counters);
        if (!(seen > 0.0f)) return void(++out.culled);
        sp.fade *= seen;
        const bool traced = plan.sun_light == SunLightSource::kShotScene ||
                            plan.sun_light == SunLightSource::kFrameScene;
        if (plan.sun_light == SunLightSource::kShot) {
            bool cast = false;
            in.shadow = shot.sun_light->light(*shot.sun_rays, item, slot, origin, cast);
            if (cast) ++counters.shadow_rays.local();
        } else if (traced && !plan.fragment_shadows)
            ++counters.shadow_rays.local(),
                in.shadow = sun_light_at(*input.sun_rays, origin, c.sun, c.rs.shadows);
        in.shadow += (1.0f - in.shadow) * in.lod.shadow_lift;
        // The clouds' shadows after the level of detail's lift: they are the land's large
        // patches of light and shade, which stay however far off, not a detail that fades.
        in.shadow *= cloud_light(shot.scene.clouds, origin.world.x, origin.world.z);
        shade_sprite(c, mat, in, sp);
        if (plan.fragment_shadows) {
            sp.grid = static_cast<int32_t>(out.grids.size());
            out.grids.push_back(shadow_grid(c, *input.sun_rays, o, sp, counters));
        }
        out.sprites.push_back(sp);
    }

    // Every particle, in for_each_particle's order.
    void each() {
        size_t k = 0;  // the particle's index in the shot's light cache
        for_each_particle(c.shot, item, [&](SpriteKind kind, size_t j, const RayOrigin& origin) {
            particle(kind, j, origin, k++);
        });
    }

    // Cluster by cluster: those that cannot show are counted as culled without a look at their
    // particles; the others' particles are visited in for_each_particle's order, so the sprites
    // are the same as each()'s.
    void by_cluster() {
        const Shot& shot = c.shot;
        const ItemClusters& ic = shot.clusters[item];
        const bool tree = item < shot.trees->size();
        std::vector<uint32_t> shown[2];  // bark or surface, then leaves
        for (const ParticleCluster& cl : ic.clusters) {
            // A tree's clusters widened by as far as the wind moves any of its particles.
            const double pad = tree && c.wind && c.wind->on ? c.wind->reach[item] : 0.0;
            ClusterFate fate = cluster_fate(shot, c.lod, c.cam, c.rs, item, cl, pad);
            // Behind the surfaces from every camera of the seen window: a few lookups.
            const bool hidden = fate == ClusterFate::kShown &&
                                cluster_hidden(shot, c.lod, c.rs, item, cl, pad, maps);
            if (fate == ClusterFate::kShown && !hidden) {
                std::vector<uint32_t>& to = shown[cl.kind == SpriteKind::kLeaf];
                to.insert(to.end(), ic.order.begin() + cl.first,
                          ic.order.begin() + cl.first + cl.count);
                continue;
            }
            // Counted as each() counts them: graftal-styled particles are no strokes.
            uint64_t n = cl.count;
            if (!shot.graftals.empty())
                n = std::count_if(
                    ic.order.begin() + cl.first, ic.order.begin() + cl.first + cl.count,
                    [&](uint32_t j) { return !drawn_as_graftals(shot, item, cl.kind, j); });
            out.culled += n, out.grouped += n;
            if (fate == ClusterFate::kFaded) out.faded += n;
            if (hidden) out.hidden += n;
        }
        const SpriteKind first = tree ? SpriteKind::kBark : SpriteKind::kSurface;
        // At most one sprite a particle looked at: one allocation, not a doubling series.
        out.sprites.reserve(shown[0].size() + shown[1].size());
        for (int k = 0; k < 2; ++k) {
            std::sort(shown[k].begin(), shown[k].end());
            const SpriteKind kind = k == 0 ? first : SpriteKind::kLeaf;
            for (const uint32_t j : shown[k])
                particle(kind, j, particle_origin(shot, item, kind, j),
                         particle_slot(shot, item, kind, j));
        }
    }
};

}  // namespace

SpriteSet make_sprites(const SpriteStageInput& input) {
    const Shot& shot = input.shot;
    const SpriteContext c{shot,
                          input.view.camera,
                          input.settings,
                          input.plan,
                          input.lod,
                          glm::vec3(input.view.sun_direction),
                          input.view.eye_speed,
                          input.wind};
    const size_t items = shot.item_count();
    std::vector<SpriteSet> per_item(items);
    // Each item's part in the memory it had the frame before (buffer_pool.h): the parts and
    // the list they are joined into are tens of megabytes, and fresh pages cost more to touch
    // than the whole join.
    std::vector<std::vector<Sprite>> parts;
    if (input.buffers) parts = input.buffers->take_sprite_parts();
    parts.resize(items);
    for (size_t i = 0; i < items; ++i) per_item[i].sprites = std::move(parts[i]);
    Counters counters;
    const bool by_cluster = input.group_culling && shot.clusters.size() == items;
    // The seen window's occlusion maps, kept from the frames before when the memo has them.
    uint64_t map_rays = 0;
    std::vector<OcclusionMap> own;
    const std::vector<OcclusionMap>& maps =
        !input.plan.occlusion_maps ? own
        : input.seen_memo          ? input.seen_memo->maps(shot, input.seen, c.cam, map_rays)
                                   : (own = occlusion_maps(shot, input.seen, c.cam, map_rays));
    if (input.seen_memo && input.seen) input.seen_memo->begin_frame(shot, *input.seen, c.rs);
    tbb::parallel_for(size_t{0}, items, [&](size_t i) {
        FlushDenormals ftz;  // Embree's modes, while this task traces
        ItemSprites make{c, input, i, per_item[i], counters, maps, {}};
        make.remember();
        by_cluster ? make.by_cluster() : make.each();
    });
    SpriteSet all;
    if (input.buffers) all.sprites = input.buffers->take_sprites();
    // One allocation of the frame's size (a doubling series would touch fresh pages), kept an
    // eighth over so that the next frames' few more sprites fit it.
    size_t total = 0;
    for (const SpriteSet& s : per_item) total += s.sprites.size();
    if (all.sprites.capacity() < total)
        all.sprites.reserve(input.buffers ? total + total / 8 : total);
    for (size_t i = 0; i < items; ++i) {
        SpriteSet& s = per_item[i];
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
        all.thinned += s.thinned;
        all.grouped += s.grouped;
        all.hidden += s.hidden;
        parts[i] = std::move(s.sprites);
        s = SpriteSet{};
    }
    if (input.buffers) input.buffers->give_sprite_parts(std::move(parts));
    all.shadow_rays = counters.shadow_rays.combine(std::plus<uint64_t>());
    all.hidden += counters.hidden.combine(std::plus<uint64_t>());
    all.occlusion_rays = counters.occlusion_rays.combine(std::plus<uint64_t>());
    all.map_rays = map_rays;
    return all;
}

SpriteSet sprites_stage(const FrameContext& ctx, const FrameLod& lod, const FrameWind& wind,
                        const RayScene* sun_rays, const SeenWindow& seen) {
    StagePhase phase(ctx, "sprites", true);
    const FramePlan& plan = ctx.plan;
    SpriteStageInput input{ctx.shot, ctx.view, plan, ctx.render(), lod, sun_rays, &seen};
    input.seen_memo = ctx.settings.seen_memo;
    input.buffers = ctx.settings.buffers;
    input.wind = &wind;
    SpriteSet sprites = make_sprites(input);
    FrameReport& rep = ctx.report;
    rep.leaf_sprites = sprites.leaf, rep.bark_sprites = sprites.bark;
    rep.surface_sprites = sprites.surface, rep.culled = sprites.culled;
    rep.shadow_rays = sprites.shadow_rays;
    phase.done(
        std::string("every particle faces the camera") +
            (plan.fragment_shadows ? "; 4 x 4 shadow rays per sprite"
             : plan.sun_light == SunLightSource::kShot
                 ? "; light kept in the shot, traced when first shown"
             : plan.shadows ? "; a shadow ray per particle"
                            : "") +
            (!plan.underpaint       ? ""
             : seen.cameras.empty() ? "; hidden ones culled"
                                    : "; hidden ones culled, seen from where the eye is over " +
                                          std::to_string(seen.cameras.size()) + " frames") +
            (plan.underpaint && plan.occlusion_maps
                 ? " (each camera's occlusion map first, a cluster at a time where all of it is "
                   "behind)"
                 : ""),
        std::to_string(sprites.sprites.size()) + " sprites, " + std::to_string(sprites.culled) +
            " culled (" + std::to_string(sprites.hidden) + " hidden, " +
            std::to_string(sprites.faded) + " faded out" +
            (sprites.thinned ? ", " + std::to_string(sprites.thinned) + " thinned" : "") +
            (sprites.grouped ? "; " + std::to_string(sprites.grouped) + " of them by group" : "") +
            ")" +
            (sprites.shadow_rays ? ", " + std::to_string(sprites.shadow_rays) + " shadow rays"
                                 : "") +
            (sprites.map_rays
                 ? ", " + std::to_string(sprites.map_rays) + " occlusion map rays" +
                       (ctx.settings.seen_memo ? " (the other maps kept from frames before)" : "")
                 : "") +
            (sprites.occlusion_rays
                 ? ", " + std::to_string(sprites.occlusion_rays) + " occlusion rays" +
                       (plan.occlusion_maps ? " where a map was unsure" : "") +
                       (ctx.settings.seen_memo ? " (the others' answers kept from frames before)"
                                               : "")
                 : ""));
    return sprites;
}

}  // namespace pleinair
