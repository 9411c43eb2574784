// Sprites from particles, depth sort, tile binning and per-tile back-to-front compositing with
// the stroke shader; the background is painted per tile first.
#include "pipeline/paint.h"

#include <tbb/combinable.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>
#include <tbb/parallel_sort.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstring>
#include <glm/geometric.hpp>
#include <limits>
#include <memory>
#include <optional>

#include "generators/rng.h"
#include "pipeline/rays.h"
#include "shading/stroke_kernel.h"

namespace pleinair {

namespace {

using Clock = std::chrono::steady_clock;
double ms_since(Clock::time_point t0) {
    return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

constexpr int kTile = 64;

struct SpriteMaterial {
    const StrokeShaderParams* shader = nullptr;
    const Palette* palette = nullptr;
    const SurfaceShaderParams* surface = nullptr;  // surface materials only
    EdgeTable edge;
};

enum SpriteKind : uint8_t { kLeaf, kBark, kSurface };

// Shadows per fragment: the light at a 4 x 4 grid of points over the sprite, interpolated.
constexpr int kGrid = 4;
using ShadowGrid = std::array<float, kGrid * kGrid>;

float grid_at(const ShadowGrid& g, float s, float t) {
    const float x = std::clamp(s * kGrid - 0.5f, 0.0f, kGrid - 1.0f);
    const float y = std::clamp(t * kGrid - 0.5f, 0.0f, kGrid - 1.0f);
    const int i = std::min(static_cast<int>(x), kGrid - 2),
              j = std::min(static_cast<int>(y), kGrid - 2);
    const float fx = x - i, fy = y - j;
    const float* r0 = &g[static_cast<size_t>(j) * kGrid + i];
    const float* r1 = r0 + kGrid;
    return (r0[0] * (1 - fx) + r0[1] * fx) * (1 - fy) + (r1[0] * (1 - fx) + r1[1] * fx) * fy;
}

struct Sprite {
    float x = 0, y = 0, depth = 0;
    float half_w = 0, half_l = 0;  // across and along the stroke, pixels
    float ax = 0, ay = 1;          // unit screen direction of the stroke's length
    float opacity = 1;             // detail strokes fading with distance (IV.7)
    int32_t grid = -1;             // its shadow grid, with shadows per fragment
    uint32_t material = 0;
    uint32_t object_id = 0;
    uint8_t kind = kLeaf;
    StrokeConstants k;
};

// A 0..1 value from a label, for size and angle jitter that differ from the noise offsets.
float label_hash(float label, uint32_t salt) {
    uint32_t bits;
    static_assert(sizeof bits == sizeof label);
    std::memcpy(&bits, &label, sizeof bits);
    return tree_hash01(bits ^ (salt * 0x27d4eb2fu));
}

// Half extents of a sprite's screen-aligned bounding box (the rotated rectangle's).
void extent(const Sprite& sp, float& ex, float& ey) {
    ex = std::abs(sp.ax) * sp.half_l + std::abs(sp.ay) * sp.half_w;
    ey = std::abs(sp.ay) * sp.half_l + std::abs(sp.ax) * sp.half_w;
}

// The pixels of row y that may hold a sample inside the sprite, given s and t's screen
// gradients: each of 0 < s < 1 and 0 < t < 1 is a slab in x, widened by half a pixel in x and
// y for the sub-pixel samples. Narrows [xa, xb]; false when the row misses the sprite.
bool row_span(const Sprite& sp, float sx, float sy, float txx, float tyy, int y, int& xa, int& xb) {
    const float dy = static_cast<float>(y) + 0.5f - sp.y;
    float lo = -std::numeric_limits<float>::infinity(), hi = -lo;
    auto slab = [&](float gx, float gy) {
        const float c0 = 0.5f + dy * gy, slack = 0.5f * (std::abs(gx) + std::abs(gy));
        const float a = -slack - c0, b = 1.0f + slack - c0;  // gx * dx must lie in (a, b)
        if (gx > 0) {
            lo = std::max(lo, a / gx), hi = std::min(hi, b / gx);
        } else if (gx < 0) {
            lo = std::max(lo, b / gx), hi = std::min(hi, a / gx);
        } else if (!(a < 0 && b > 0)) {
            hi = lo = 0, lo = 1;  // empty
        }
    };
    slab(sx, sy);
    slab(txx, tyy);
    if (!(hi >= lo)) return false;
    // dx = x + 0.5 - sp.x, so x lies in (lo + sp.x - 0.5, hi + sp.x - 0.5).
    float fa = std::floor(lo + sp.x - 0.5f), fb = std::ceil(hi + sp.x - 0.5f);
    if (fa > static_cast<float>(xa)) xa = static_cast<int>(fa);
    if (fb < static_cast<float>(xb)) xb = static_cast<int>(fb);
    return xa <= xb;
}

glm::dvec3 rotate_y(const glm::dvec3& v, double c, double s) {
    return {c * v.x + s * v.z, v.y, -s * v.x + c * v.z};
}

bool has_atmosphere_effect(const StrokeShaderParams& p) {
    return p.dist_hue_strength > 0 || p.dist_sat_limiter > 0 || p.dist_value_min > 0 ||
           p.dist_value_max < 1;
}

struct SpriteInput {
    glm::dvec3 world;
    glm::vec3 normal;   // world, unit
    glm::vec3 tangent;  // world, unit (bark), or zero (leaves)
    double width;       // world units
    double length;
    float center_distance, branch_distance, label;
    uint32_t tree_id;
    float shadow = 1;  // light reaching the particle, 0..1 (IV.4.2)
    // Surface strokes (IV.7): their own lightness and frequencies, the crest shrink and the
    // distance fade. Null for leaves and bark.
    const SurfaceParticles* surface = nullptr;
    size_t index = 0;
};

// Projects one particle; returns false if it is culled (behind the camera, not finite, too
// small, or off screen).
bool make_sprite(const SceneDesc& scene, const FramePlan& plan, const SpriteMaterial& m,
                 uint32_t mat, const SpriteInput& in, Sprite& out) {
    const Camera& cam = scene.camera;
    const StrokeShaderParams& p = *m.shader;
    Projection c = project(cam, in.world);
    if (!c.in_front) return false;
    double z = c.depth;
    float jitter = 1.0f + p.size_jitter * (2.0f * label_hash(in.label, 1) - 1.0f);
    float w = stroke_screen_px(cam, scene.render, in.width * jitter, z);
    float l = stroke_screen_px(cam, scene.render, in.length * jitter, z);
    float opacity = 1;
    if (in.surface) {
        const SurfaceParticles& S = *in.surface;
        // Fig. 25: a surface seen edge-on keeps only the middle of its sprites' height.
        glm::vec3 to_eye(glm::normalize(cam.eye - in.world));
        l *= crest_factor(glm::dot(S.normal(in.index), to_eye), m.surface->crest_shrink);
        // Detail strokes fade over their own span of the distance value (IV.7).
        const float fb = S.fade_begin(in.index);
        if (fb <= 1.0f) {
            float dv = color_detail::unit_in(static_cast<float>(z), scene.atmosphere.near_distance,
                                             scene.atmosphere.far_distance);
            opacity = 1.0f - smoothstep(fb, S.fade_end(in.index), dv);
            if (!(opacity > 0.0f)) return false;
        }
    }
    float min_px = scene.render.min_stroke_px;
    if (w < min_px) l *= min_px / std::max(w, 1e-12f), w = min_px;
    if (!(w > 0.0f) || !(l > 0.0f) || !std::isfinite(w) || !std::isfinite(l)) return false;
    out.x = c.x;
    out.y = c.y;
    out.depth = c.depth;
    out.half_w = 0.5f * w;
    out.half_l = 0.5f * l;

    // Stroke direction on screen: along the projected tangent (a normal-free frame, so a limb
    // seen end-on still gets one), jittered by the label.
    double angle = 0;
    if (glm::dot(in.tangent, in.tangent) > 0) {
        glm::dvec3 t(in.tangent);
        double tx = glm::dot(t, cam.right), ty = -glm::dot(t, cam.up);
        if (tx * tx + ty * ty > 1e-8) angle = std::atan2(ty, tx) - 0.5 * M_PI;
    }
    angle += (label_hash(in.label, 2) - 0.5) * p.angle_jitter * M_PI / 180.0;
    out.ax = static_cast<float>(-std::sin(angle));
    out.ay = static_cast<float>(std::cos(angle));
    float ex, ey;
    extent(out, ex, ey);
    if (c.x + ex < 0 || c.y + ey < 0 || c.x - ex > cam.width || c.y - ey > cam.height) return false;

    float n_dot_l = glm::dot(in.normal, glm::vec3(scene.sun_direction));
    float d = 0;
    if (plan.atmosphere)
        d = distance_value(c.depth, scene.atmosphere.near_distance, scene.atmosphere.far_distance,
                           p.dist_curve_bias);
    out.k =
        stroke_constants(p, n_dot_l, in.center_distance, in.branch_distance, in.label, in.tree_id,
                         in.shadow, d, 0.0f, !in.surface && plan.tint && p.unique_tint_amt > 0,
                         plan.atmosphere && has_atmosphere_effect(p));
    if (in.surface) {
        const SurfaceParticles& S = *in.surface;
        const float h = S.height(in.index);
        float l = surface_lightness(*m.surface, n_dot_l, h);
        if (in.shadow < 1.0f) l *= shadow_remap(in.shadow, p.shadow_bias);
        out.k.lightness = l;
        surface_frequencies(*m.surface, h, out.k.frequ_s, out.k.frequ_t);
        out.kind = kSurface;
        out.object_id = 0x10000u + S.material[in.index];
    } else {
        out.kind = glm::dot(in.tangent, in.tangent) > 0 ? kBark : kLeaf;
        out.object_id = in.tree_id + 1;
    }
    if (!plan.sub_stroke) out.k.sub_amt = 0;
    out.opacity = opacity;
    out.material = mat;
    return true;
}

Color background_color(const SceneDesc& s, const Color lin[4], double x, double y) {
    const Background& b = s.background;
    glm::dvec3 dir = ray_direction(s.camera, x, y);
    float e = static_cast<float>(dir.y);
    Color c;
    if (b.canvas) {
        c = lin[0];
    } else {
        Color sky = mix(lin[1], lin[0], smoothstep(0.0f, 0.6f, e));
        Color ground = mix(lin[2], lin[3], smoothstep(0.0f, 0.5f, -e));
        c = mix(ground, sky, smoothstep(-b.horizon_softness, b.horizon_softness, e));
    }
    if (b.texture > 0) {
        // Attached to the view direction, so it does not swim when the camera moves.
        float az = static_cast<float>(std::atan2(dir.x, -dir.z));
        float n = fractal_noise(az * 9.0f + 50.0f, e * 9.0f + 50.0f, 3);
        c *= 1.0f + 2.0f * b.texture * (n - 0.5f);
    }
    return c;
}

}  // namespace

// True perspective scaled by (focus / z)^(1 - stroke_perspective), so strokes shrink less than
// geometry.
float stroke_screen_px(const Camera& cam, const RenderSettings& r, double world, double z) {
    double p = std::clamp<double>(r.stroke_perspective, 0.0, 1.0);
    double px = cam.focal_px * world / (std::pow(cam.focus_distance, 1.0 - p) * std::pow(z, p));
    return static_cast<float>(px);
}

TreePlacement placement(const BuiltTree& b) {
    return {std::cos(b.rotation * M_PI / 180.0), std::sin(b.rotation * M_PI / 180.0), b.scale,
            b.position};
}

glm::dvec3 TreePlacement::place(const glm::vec3& p) const {
    return position + rotate_y(glm::dvec3(p) * scale, c, s);
}

glm::vec3 TreePlacement::turn(const glm::vec3& v) const {
    return glm::vec3(rotate_y(glm::dvec3(v), c, s));
}

glm::dmat3 TreePlacement::linear() const {
    return glm::dmat3(glm::dvec3(c, 0, -s) * scale, glm::dvec3(0, scale, 0),
                      glm::dvec3(s, 0, c) * scale);
}

std::vector<StrokeCaster> leaf_casters(const SceneDesc& scene, const BuiltTree& b,
                                       const glm::vec3& sun) {
    std::vector<StrokeCaster> out(b.tree.leaves.size());
    leaf_casters(scene, b, sun, out.data());
    return out;
}

void leaf_casters(const SceneDesc& scene, const BuiltTree& b, const glm::vec3& sun,
                  StrokeCaster* out) {
    const TreePlacement pl = placement(b);
    const StrokeShaderParams& p = scene.families[b.family].leaf_shader;
    const LeafParticles& L = b.tree.leaves;
    const double w = p.sprite_size * scene.families[b.family].params.unit * b.scale;
    // A frame perpendicular to the sun; each card turned by its stroke's angle jitter.
    const glm::vec3 ref = std::abs(sun.y) < 0.9f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
    const glm::vec3 a0 = glm::normalize(glm::cross(ref, sun)), b0 = glm::cross(sun, a0);
    for (size_t j = 0; j < L.size(); ++j) {
        StrokeCaster& c = out[j];
        c.center = pl.place(L.position[j]);
        const float jitter = 1.0f + p.size_jitter * (2.0f * label_hash(L.label[j], 1) - 1.0f);
        const double ang = (label_hash(L.label[j], 2) - 0.5) * p.angle_jitter * M_PI / 180;
        const float ca = static_cast<float>(std::cos(ang)), sa = static_cast<float>(std::sin(ang));
        c.axis_s = ca * a0 + sa * b0;
        c.axis_t = -sa * a0 + ca * b0;
        c.half_w = static_cast<float>(0.5 * w * jitter);
        c.half_l = c.half_w * p.stroke_aspect;
        c.noise = noise_of(stroke_constants(p, glm::dot(pl.turn(L.normal[j]), sun),
                                            L.center_distance[j], L.branch_distance[j], L.label[j],
                                            L.tree_id[j], 1.0f, 0.0f, 0.0f, false, false));
    }
}

std::vector<BuiltTree> build_trees(const SceneDesc& scene, bool bark) {
    std::vector<BuiltTree> out(scene.trees.size());
    tbb::parallel_for(size_t{0}, scene.trees.size(), [&](size_t i) {
        const PlacedTree& t = scene.trees[i];
        const Family& f = scene.families[t.family];
        TreeOptions o;
        o.tree_id = static_cast<uint32_t>(i);
        o.lod = false;
        BuiltTree& b = out[i];
        b.tree = generate_tree(f.params, t.seed, o);
        b.family = t.family;
        b.position = t.position;
        // Catmull-Clark rounds the trunk's base into a dome: plant the tree deep enough that
        // the ground meets the trunk at its full width.
        b.position.y -= b.tree.planting_depth * t.scale;
        b.rotation = t.rotation;
        b.scale = t.scale;
        if (bark) {
            BarkOptions bo;
            const StrokeShaderParams& p = f.bark_shader;
            bo.stroke_width = static_cast<float>(p.sprite_size * f.params.unit);
            bo.stroke_length = bo.stroke_width * p.stroke_aspect;
            bo.coverage = scene.render.bark_coverage;
            b.bark = emit_bark(b.tree, bo, t.seed);
        }
    });
    return out;
}

FramePlan plan_frame(const SceneDesc& scene, const PaintOptions& options) {
    FramePlan plan;
    auto add = [&](const char* name, bool ran, std::string why) {
        plan.decisions.push_back({name, ran, std::move(why), 0, ""});
    };
    bool tint = false, atmos = false, sub = false;
    for (const auto& f : scene.families)
        for (const auto* p : {&f.leaf_shader, &f.bark_shader}) {
            tint |= p->unique_tint_amt > 0;
            atmos |= has_atmosphere_effect(*p);
            sub |= p->sub_stroke_amt > 0 && p->sub_stroke_frequ >= 0;
        }
    plan.bark = options.bark && scene.render.bark_coverage > 0;
    add("bark", plan.bark,
        plan.bark ? "trunks and branches are painted as strokes"
                  : (options.bark ? "render/bark_coverage is 0" : "bark strokes turned off"));
    plan.tint = tint;
    add("tint", tint,
        tint ? "a shader has unique_tint_amt > 0" : "unique_tint_amt is 0 in every shader");
    plan.atmosphere = scene.has_atmosphere && atmos;
    add("atmosphere", plan.atmosphere,
        !scene.has_atmosphere ? "the scene has no atmosphere"
        : atmos               ? "atmosphere near/far set and a shader has distance effects"
                              : "every shader's distance effects are zero");
    plan.sub_stroke = sub;
    add("sub-stroke colour", sub,
        sub ? "a shader has sub_stroke_amt > 0" : "sub_stroke_amt is 0 in every shader");
    plan.aovs = options.aovs;
    add("aovs", options.aovs, options.aovs ? "asked for (--aovs)" : "not asked for");
    const bool meshes = scene.terrain.present || !scene.rocks.empty();
    const bool casters = meshes || !scene.trees.empty();
    plan.shadows = scene.sun_casts_shadows && casters;
    add("shadows", plan.shadows,
        !scene.sun_casts_shadows ? "the sun casts no shadows: no shadow scene, no shadow ray"
        : casters ? "the sun casts shadows: one ray per particle through the stroke casters"
                  : "nothing in the scene to cast a shadow");
    plan.underpaint = meshes;
    add("underpaint", meshes,
        meshes ? "terrain or rocks are visible: flat colour and depth under the strokes"
               : "no visible mesh (no terrain, no rocks)");
    return plan;
}

Frame paint_frame(const SceneDesc& scene, const std::vector<BuiltTree>& trees,
                  const FramePlan& plan, FrameReport* report) {
    static const BuiltLandscape kNone;
    return paint_frame(scene, trees, kNone, plan, report);
}

Frame paint_frame(const SceneDesc& scene, const std::vector<BuiltTree>& trees,
                  const BuiltLandscape& land, const FramePlan& plan, FrameReport* report) {
    const Camera& cam = scene.camera;
    const RenderSettings& rs = scene.render;
    FrameReport local;
    FrameReport& rep = report ? *report : local;

    // Materials: per family, leaves then bark; then the scene's surface materials.
    const size_t nf = scene.families.size();
    std::vector<SpriteMaterial> materials(2 * nf + scene.materials.size());
    for (size_t f = 0; f < nf; ++f) {
        const Family& fam = scene.families[f];
        for (int kind = 0; kind < 2; ++kind) {
            SpriteMaterial& m = materials[2 * f + kind];
            m.shader = kind == 0 ? &fam.leaf_shader : &fam.bark_shader;
            m.palette = kind == 0 ? &fam.leaf_palette : &fam.bark_palette;
            m.edge = make_edge_table(m.shader->stroke_fullness);
        }
    }
    for (size_t i = 0; i < scene.materials.size(); ++i) {
        SpriteMaterial& m = materials[2 * nf + i];
        m.shader = &scene.materials[i].shader;
        m.palette = &scene.materials[i].palette;
        m.surface = &scene.materials[i].surface;
        m.edge = make_edge_table(m.shader->stroke_fullness);
    }

    std::vector<TreePlacement> placements;
    placements.reserve(trees.size());
    for (const BuiltTree& b : trees) placements.push_back(placement(b));

    // Ray scenes, only as the plan asks: the camera's (underpainting and culling of sprites
    // behind the ground) and the sun's (shadows cast as brush strokes).
    auto t0 = Clock::now();
    std::unique_ptr<RayScene> view_rays, sun_rays;
    const glm::dvec3 anchor = cam.eye;
    const glm::vec3 sun(scene.sun_direction);
    // What each camera-scene geometry is painted with underneath: a material index, or -1 for
    // the terrain (its material varies over it).
    std::vector<int64_t> view_material;
    // Each tree's limbs are built once, in its own space, and placed in both scenes.
    std::optional<RayMeshes> limbs;  // only when a ray scene is built: no Embree device else
    if (plan.underpaint || plan.shadows) {
        limbs.emplace();
        for (const BuiltTree& b : trees) limbs->add(b.tree.render);
        limbs->commit();
    }
    auto build_view = [&] {
        view_rays = std::make_unique<RayScene>(anchor, &*limbs);
        if (land.has_terrain) view_rays->add_mesh(land.terrain_mesh), view_material.push_back(-1);
        if (land.has_water)
            view_rays->add_mesh(land.water_mesh),
                view_material.push_back(static_cast<int64_t>(2 * nf + scene.water.material));
        for (size_t i = 0; i < land.rocks.size(); ++i)
            view_rays->add_mesh(land.rocks[i]),
                view_material.push_back(static_cast<int64_t>(2 * nf + scene.rocks[i].material));
        for (size_t i = 0; i < trees.size(); ++i)
            view_rays->add_instance(static_cast<uint32_t>(i), placements[i].linear(),
                                    placements[i].position),
                view_material.push_back(static_cast<int64_t>(2 * trees[i].family + 1));
        view_rays->commit();
    };
    auto build_sun = [&] {
        sun_rays = std::make_unique<RayScene>(anchor, &*limbs);
        // Surfaces that grow grass and rock strokes cast shadows though the camera never sees
        // them (IV.7); water casts none.
        if (land.has_terrain) sun_rays->add_mesh(land.terrain_mesh);
        for (const auto& r : land.rocks) sun_rays->add_mesh(r);
        for (size_t i = 0; i < trees.size(); ++i)
            sun_rays->add_instance(static_cast<uint32_t>(i), placements[i].linear(),
                                   placements[i].position);
        // Leaf strokes as cards facing the sun, one caster set per family's leaf shader, each
        // in tree order whatever the threads did.
        std::vector<std::vector<StrokeCaster>> casters(nf);
        std::vector<size_t> offset(trees.size());
        for (size_t i = 0; i < trees.size(); ++i) {
            offset[i] = casters[trees[i].family].size();
            casters[trees[i].family].resize(offset[i] + trees[i].tree.leaves.size());
        }
        tbb::parallel_for(size_t{0}, trees.size(), [&](size_t i) {
            leaf_casters(scene, trees[i], sun, casters[trees[i].family].data() + offset[i]);
        });
        for (size_t f = 0; f < nf; ++f)
            if (!casters[f].empty())
                sun_rays->add_casters(casters[f], scene.families[f].leaf_shader,
                                      materials[2 * f].edge);
        sun_rays->commit();
    };
    // The two scenes only read what they share (the device, the committed limbs): built side
    // by side (Embree's builds are partly serial).
    if (plan.underpaint && plan.shadows)
        tbb::parallel_invoke(build_view, build_sun);
    else if (plan.underpaint)
        build_view();
    else if (plan.shadows)
        build_sun();
    rep.view_scene = plan.underpaint;
    rep.sun_scene = plan.shadows;
    if (plan.underpaint || plan.shadows)
        rep.passes.push_back(
            {"ray scenes", true, "Embree scenes the plan asks for", ms_since(t0),
             std::to_string(limbs->size()) + " trees' limbs built once and placed in each; " +
                 (view_rays ? std::to_string(view_rays->mesh_count()) + " meshes for the camera"
                            : std::string("no camera scene")) +
                 (sun_rays
                      ? ", " + std::to_string(sun_rays->mesh_count()) + " meshes + " +
                            std::to_string(sun_rays->caster_count()) + " stroke casters for the sun"
                      : std::string(", no shadow scene"))});
    const ShadowMode shadow_mode =
        rs.shadows == "threshold" ? ShadowMode::kThreshold : ShadowMode::kTransmissive;
    // Counted per thread: one shared atomic, bumped for every ray, bounces between the cores.
    tbb::combinable<uint64_t> shadow_rays([] { return uint64_t{0}; }),
        view_culled([] { return uint64_t{0}; });

    // Light reaching a particle from the sun, lifted off its surface by `lift` along `n`.
    auto light_at = [&](const glm::dvec3& world, const glm::vec3* n, float lift) -> float {
        if (!sun_rays) return 1.0f;
        ++shadow_rays.local();
        glm::dvec3 o = n ? world + glm::dvec3(*n) * static_cast<double>(lift) : world;
        return sun_rays->transmittance(o, sun, shadow_mode, std::numeric_limits<float>::infinity(),
                                       n);
    };
    // Whether the camera sees the particle past the opaque surfaces (a sprite whose centre lies
    // behind a hill or a trunk is culled; the sprites in front paint over the silhouette).
    auto visible = [&](const glm::dvec3& world, const glm::vec3* n, float lift) {
        if (!view_rays) return true;
        glm::dvec3 o = n ? world + glm::dvec3(*n) * static_cast<double>(lift) : world;
        glm::dvec3 to_eye = cam.eye - o;
        double dist = glm::length(to_eye);
        if (!(dist > 0)) return true;
        // Any hit short of the eye hides it: an occlusion query, cheaper than the nearest hit.
        bool seen =
            !view_rays->occluded(o, glm::vec3(to_eye / dist), static_cast<float>(dist) * 0.999f, n);
        if (!seen) ++view_culled.local();
        return seen;
    };

    // Sprites, per tree in parallel, concatenated in tree order, then the surface strokes in
    // chunks.
    double max_displacement = scene.terrain.strokes.displacement_height;
    max_displacement = std::max(max_displacement, scene.water.strokes.displacement_height);
    for (const auto& r : scene.rocks)
        max_displacement = std::max(max_displacement, r.strokes.displacement_height);
    // Surface strokes are lifted above the deepest strokes, so none is hidden or shadowed by
    // the very ground it was emitted from.
    const float surface_lift = 2.0f * static_cast<float>(max_displacement) + 0.01f;

    t0 = Clock::now();
    std::vector<std::vector<Sprite>> per_item(trees.size() + land.chunks.size());
    std::vector<std::vector<ShadowGrid>> per_item_grids(per_item.size());
    const bool fragment_shadows = sun_rays && rs.shadow_samples == "fragment";
    // The sprite of one particle with its light: one shadow ray at the particle, or a grid of
    // them over the sprite's footprint (back-projected at the particle's depth).
    auto add_sprite = [&](SpriteInput& in, const SpriteMaterial& m, uint32_t mat,
                          const glm::vec3* n, float lift, std::vector<Sprite>& out,
                          std::vector<ShadowGrid>& grids) {
        in.shadow = fragment_shadows ? 1.0f : light_at(in.world, n, lift);
        Sprite sp;
        if (!make_sprite(scene, plan, m, mat, in, sp)) return false;
        if (fragment_shadows) {
            ShadowGrid g;
            const double world_per_px = sp.depth / cam.focal_px;
            for (int j = 0; j < kGrid; ++j)
                for (int i = 0; i < kGrid; ++i) {
                    const double s = (i + 0.5) / kGrid - 0.5, t = (j + 0.5) / kGrid - 0.5;
                    const double dx = 2 * s * sp.half_w * sp.ay + 2 * t * sp.half_l * sp.ax;
                    const double dy = -2 * s * sp.half_w * sp.ax + 2 * t * sp.half_l * sp.ay;
                    const glm::dvec3 p = in.world + (cam.right * dx - cam.up * dy) * world_per_px;
                    g[static_cast<size_t>(j) * kGrid + i] = light_at(p, n, lift);
                }
            sp.grid = static_cast<int32_t>(grids.size());
            grids.push_back(g);
        }
        out.push_back(sp);
        return true;
    };
    std::vector<uint64_t> culled(per_item.size(), 0);
    tbb::parallel_for(size_t{0}, per_item.size(), [&](size_t i) {
        FlushDenormals ftz;  // Embree's modes, while this task traces
        std::vector<Sprite>& out = per_item[i];
        std::vector<ShadowGrid>& grids = per_item_grids[i];
        if (i >= trees.size()) {
            const size_t chunk = i - trees.size();
            const SurfaceParticles& S = land.chunks[chunk];
            out.reserve(S.size());
            for (size_t j = 0; j < S.size(); ++j) {
                const uint32_t mat = static_cast<uint32_t>(2 * nf + S.material[j]);
                const SpriteMaterial& m = materials[mat];
                const StrokeShaderParams& p = *m.shader;
                const glm::dvec3 world(S.position[j]);
                const float lift = surface_lift;
                const glm::vec3 n = S.normal(j);
                if (!visible(world, &n, lift)) {
                    ++culled[i];
                    continue;
                }
                const double w = p.sprite_size * land.chunk_size[chunk] *
                                 inside_size(S.height(j), m.surface->inside_growth);
                SpriteInput in{
                    world,
                    lighting_normal(n, S.random_normal(j), m.surface->random_normal_weight),
                    glm::vec3(0, 1, 0),
                    w,
                    w * p.stroke_aspect,
                    0.5f,
                    0.5f,
                    S.label[j],
                    0};
                in.surface = &S;
                in.index = j;
                if (!add_sprite(in, m, mat, &n, lift, out, grids)) ++culled[i];
            }
            return;
        }
        const BuiltTree& b = trees[i];
        const Family& fam = scene.families[b.family];
        const TreePlacement& pl = placements[i];
        const LeafParticles& L = b.tree.leaves;
        out.reserve(L.size() + (plan.bark ? b.bark.size() : 0));
        const uint32_t leaf_mat = static_cast<uint32_t>(2 * b.family), bark_mat = leaf_mat + 1;
        if (plan.bark) {
            const BarkParticles& B = b.bark;
            const StrokeShaderParams& p = fam.bark_shader;
            double w = p.sprite_size * fam.params.unit * b.scale;
            const float lift = static_cast<float>(0.02 * fam.params.unit * b.scale);
            for (size_t j = 0; j < B.size(); ++j) {
                const glm::dvec3 world = pl.place(B.position[j]);
                const glm::vec3 n = pl.turn(B.normal[j]);
                if (!visible(world, &n, lift)) {
                    ++culled[i];
                    continue;
                }
                SpriteInput in{
                    world,      n,        pl.turn(B.tangent[j]), w, w * p.stroke_aspect, 0.5f, 0.5f,
                    B.label[j], b.tree.id};
                if (!add_sprite(in, materials[bark_mat], bark_mat, &n, lift, out, grids))
                    ++culled[i];
            }
        }
        const StrokeShaderParams& p = fam.leaf_shader;
        double w = p.sprite_size * fam.params.unit * b.scale;
        for (size_t j = 0; j < L.size(); ++j) {
            const glm::dvec3 world = pl.place(L.position[j]);
            if (!visible(world, nullptr, 0.0f)) {
                ++culled[i];
                continue;
            }
            SpriteInput in{world,
                           pl.turn(L.normal[j]),
                           glm::vec3(0.0f),
                           w,
                           w * p.stroke_aspect,
                           L.center_distance[j],
                           L.branch_distance[j],
                           L.label[j],
                           L.tree_id[j]};
            if (!add_sprite(in, materials[leaf_mat], leaf_mat, nullptr, 0.0f, out, grids))
                ++culled[i];
        }
    });
    std::vector<Sprite> sprites;
    std::vector<ShadowGrid> grids;
    for (size_t i = 0; i < per_item.size(); ++i) {
        for (Sprite& sp : per_item[i])
            if (sp.grid >= 0) sp.grid += static_cast<int32_t>(grids.size());
        grids.insert(grids.end(), per_item_grids[i].begin(), per_item_grids[i].end());
        for (const Sprite& sp : per_item[i])
            (sp.kind == kLeaf   ? rep.leaf_sprites
             : sp.kind == kBark ? rep.bark_sprites
                                : rep.surface_sprites)++;
        sprites.insert(sprites.end(), per_item[i].begin(), per_item[i].end());
        rep.culled += culled[i];
    }
    per_item.clear();
    per_item_grids.clear();
    rep.shadow_rays = shadow_rays.combine(std::plus<uint64_t>());
    rep.passes.push_back(
        {"sprites", true,
         std::string("every particle faces the camera") +
             (plan.shadows ? (fragment_shadows ? "; 4 x 4 shadow rays per sprite"
                                               : "; a shadow ray per particle")
                           : "") +
             (plan.underpaint ? "; hidden ones culled" : ""),
         ms_since(t0),
         std::to_string(sprites.size()) + " sprites, " + std::to_string(rep.culled) + " culled (" +
             std::to_string(view_culled.combine(std::plus<uint64_t>())) + " hidden)" +
             (plan.shadows ? ", " + std::to_string(rep.shadow_rays) + " shadow rays" : "")});

    // Back to front; the index breaks ties so the order is total and thread-independent.
    t0 = Clock::now();
    std::vector<uint32_t> order(sprites.size());
    for (size_t i = 0; i < order.size(); ++i) order[i] = static_cast<uint32_t>(i);
    tbb::parallel_sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) {
        if (sprites[a].depth != sprites[b].depth) return sprites[a].depth > sprites[b].depth;
        return a < b;
    });
    rep.passes.push_back({"sort", true, "back-to-front compositing", ms_since(t0), ""});

    // Bins: each tile lists the sprites touching it, in depth order.
    t0 = Clock::now();
    const int tiles_x = (cam.width + kTile - 1) / kTile, tiles_y = (cam.height + kTile - 1) / kTile;
    std::vector<std::vector<uint32_t>> bins(static_cast<size_t>(tiles_x) * tiles_y);
    for (uint32_t idx : order) {
        const Sprite& sp = sprites[idx];
        float ex, ey;
        extent(sp, ex, ey);
        int x0 =
            static_cast<int>(std::clamp(std::floor((sp.x - ex) / kTile), 0.0f, tiles_x - 1.0f));
        int x1 =
            static_cast<int>(std::clamp(std::floor((sp.x + ex) / kTile), 0.0f, tiles_x - 1.0f));
        int y0 =
            static_cast<int>(std::clamp(std::floor((sp.y - ey) / kTile), 0.0f, tiles_y - 1.0f));
        int y1 =
            static_cast<int>(std::clamp(std::floor((sp.y + ey) / kTile), 0.0f, tiles_y - 1.0f));
        for (int ty = y0; ty <= y1; ++ty)
            for (int tx = x0; tx <= x1; ++tx)
                bins[static_cast<size_t>(ty) * tiles_x + tx].push_back(idx);
    }
    rep.passes.push_back(
        {"bin", true, "tiles paint in parallel", ms_since(t0),
         std::to_string(bins.size()) + " tiles of " + std::to_string(kTile) + " px"});

    // Paint.
    t0 = Clock::now();
    Frame frame;
    frame.width = cam.width;
    frame.height = cam.height;
    const size_t npix = static_cast<size_t>(cam.width) * cam.height;
    frame.rgba.assign(4 * npix, 0.0f);
    frame.has_aovs = plan.aovs;
    if (plan.aovs) {
        frame.depth.assign(npix, std::numeric_limits<float>::infinity());
        frame.object_id.assign(npix, 0.0f);
        frame.alpha.assign(npix, 0.0f);
        frame.lightness.assign(npix, 0.0f);
    }
    const Background& bg = scene.background;
    const Color bg_lin[4] = {srgb_to_linear(bg.canvas ? bg.canvas_color : bg.sky_zenith),
                             srgb_to_linear(bg.sky_horizon), srgb_to_linear(bg.ground_horizon),
                             srgb_to_linear(bg.ground_near)};
    const int n = rs.samples >= 16 ? 4 : rs.samples >= 4 ? 2 : 1;
    const float inv_n = 1.0f / static_cast<float>(n);
    const int octaves = rs.octaves;
    std::vector<uint64_t> tile_fragments(bins.size(), 0);

    // The background is smooth (a gradient under slow noise): it is evaluated on a lattice of
    // every kBgStep-th pixel and interpolated bilinearly, 1/16 of the work.
    constexpr int kBgStep = 4;
    const int gw = (cam.width + kBgStep - 1) / kBgStep + 1;
    const int gh = (cam.height + kBgStep - 1) / kBgStep + 1;
    std::vector<Color> lattice(static_cast<size_t>(gw) * gh);
    tbb::parallel_for(0, gh, [&](int j) {
        for (int i = 0; i < gw; ++i)
            lattice[static_cast<size_t>(j) * gw + i] =
                background_color(scene, bg_lin, kBgStep * i + 0.5, kBgStep * j + 0.5);
    });
    tbb::parallel_for(0, cam.height, [&](int y) {
        const int j = y / kBgStep;
        const float fy = static_cast<float>(y % kBgStep) / kBgStep;
        const Color* r0 = &lattice[static_cast<size_t>(j) * gw];
        const Color* r1 = r0 + gw;
        for (int x = 0; x < cam.width; ++x) {
            const int i = x / kBgStep;
            const float fx = static_cast<float>(x % kBgStep) / kBgStep;
            Color c = mix(mix(r0[i], r0[i + 1], fx), mix(r1[i], r1[i + 1], fx), fy);
            float* px = &frame.rgba[4 * (static_cast<size_t>(y) * cam.width + x)];
            px[0] = c.x, px[1] = c.y, px[2] = c.z, px[3] = 1.0f;
        }
    });
    rep.passes.push_back({"background", true,
                          bg.canvas ? "canvas colour" : "sky and ground seen from the camera",
                          ms_since(t0), ""});

    if (plan.underpaint) {
        // Underpainting: a flat palette colour and a depth where the camera sees terrain, water,
        // rocks or trunks, at underpaint_scale of the resolution, so no sky shows through the
        // gaps between strokes. Coverage is interpolated, so silhouettes stay soft.
        t0 = Clock::now();
        const int uw = std::max(1, static_cast<int>(std::ceil(cam.width * rs.underpaint_scale)));
        const int uh = std::max(1, static_cast<int>(std::ceil(cam.height * rs.underpaint_scale)));
        const double fx = static_cast<double>(cam.width) / uw,
                     fy = static_cast<double>(cam.height) / uh;
        std::vector<Color> ucol(static_cast<size_t>(uw) * uh, Color(0.0f));  // premultiplied
        std::vector<float> ucov(ucol.size(), 0.0f), udepth(ucol.size(), 0.0f);
        tbb::parallel_for(0, uh, [&](int j) {
            FlushDenormals ftz;
            for (int i = 0; i < uw; ++i) {
                const glm::dvec3 dir = ray_direction(cam, (i + 0.5) * fx, (j + 0.5) * fy);
                const RayHit h = view_rays->intersect(cam.eye, glm::vec3(dir));
                if (!h.hit) continue;
                const glm::dvec3 world = cam.eye + dir * static_cast<double>(h.t);
                glm::vec3 n = h.normal;
                if (glm::dot(glm::dvec3(n), dir) > 0) n = -n;
                const int64_t vm = view_material[h.geometry];
                const uint32_t mat =
                    vm >= 0 ? static_cast<uint32_t>(vm)
                            : static_cast<uint32_t>(2 * nf + terrain_material_at(scene, world));
                const SpriteMaterial& m = materials[mat];
                const float n_dot_l = glm::dot(n, sun);
                // A middle-depth stroke's lightness, a little darker: paint under paint.
                float l =
                    m.surface ? surface_lightness(*m.surface, n_dot_l, 0.5f) : clamp01(n_dot_l);
                l *= 0.9f;
                if (plan.shadows) {
                    float sh = light_at(world, &n, 0.01f);
                    if (sh < 1.0f) l *= shadow_remap(sh, m.shader->shadow_bias);
                }
                const float depth = static_cast<float>(glm::dot(world - cam.eye, cam.forward));
                float d = 0;
                if (plan.atmosphere)
                    d = distance_value(depth, scene.atmosphere.near_distance,
                                       scene.atmosphere.far_distance, m.shader->dist_curve_bias);
                StrokeConstants k =
                    stroke_constants(*m.shader, n_dot_l, 0.5f, 0.5f, 0.5f, 0, 1.0f, d, 0.0f, false,
                                     plan.atmosphere && has_atmosphere_effect(*m.shader));
                const size_t u = static_cast<size_t>(j) * uw + i;
                ucol[u] = finish_color(k, palette_lookup(*m.palette, l));
                ucov[u] = 1.0f;
                udepth[u] = depth;
            }
        });
        rep.underpaint_rays = static_cast<uint64_t>(uw) * uh;
        tbb::parallel_for(0, cam.height, [&](int y) {
            const float sy = std::clamp(static_cast<float>((y + 0.5) / fy - 0.5), 0.0f, uh - 1.0f);
            const int j0 = static_cast<int>(sy), j1 = std::min(j0 + 1, uh - 1);
            const float wy = sy - j0;
            for (int x = 0; x < cam.width; ++x) {
                const float sx =
                    std::clamp(static_cast<float>((x + 0.5) / fx - 0.5), 0.0f, uw - 1.0f);
                const int i0 = static_cast<int>(sx), i1 = std::min(i0 + 1, uw - 1);
                const float wx = sx - i0;
                const size_t a = static_cast<size_t>(j0) * uw + i0,
                             b = static_cast<size_t>(j0) * uw + i1,
                             c = static_cast<size_t>(j1) * uw + i0,
                             d = static_cast<size_t>(j1) * uw + i1;
                auto lerp = [](float p, float q, float t) { return p + (q - p) * t; };
                const float cov = lerp(lerp(ucov[a], ucov[b], wx), lerp(ucov[c], ucov[d], wx), wy);
                if (!(cov > 0.0f)) continue;
                const Color col = mix(mix(ucol[a], ucol[b], wx), mix(ucol[c], ucol[d], wx), wy);
                float* px = &frame.rgba[4 * (static_cast<size_t>(y) * cam.width + x)];
                // Both premultiplied: the underpainting over the background.
                px[0] = col.x + px[0] * (1.0f - cov);
                px[1] = col.y + px[1] * (1.0f - cov);
                px[2] = col.z + px[2] * (1.0f - cov);
                if (plan.aovs && cov >= 0.5f) {
                    const size_t pi = static_cast<size_t>(y) * cam.width + x;
                    const size_t nearest = static_cast<size_t>(wy < 0.5f ? j0 : j1) * uw +
                                           static_cast<size_t>(wx < 0.5f ? i0 : i1);
                    frame.depth[pi] = ucov[nearest] > 0 ? udepth[nearest] : udepth[a];
                }
            }
        });
        rep.passes.push_back({"underpaint", true,
                              "flat palette colour where the camera sees a surface", ms_since(t0),
                              std::to_string(uw) + "x" + std::to_string(uh) + " camera rays"});
    }

    t0 = Clock::now();
    tbb::parallel_for(size_t{0}, bins.size(), [&](size_t tile) {
        const int tx = static_cast<int>(tile % tiles_x), ty = static_cast<int>(tile / tiles_x);
        const int px0 = tx * kTile, py0 = ty * kTile;
        const int px1 = std::min(px0 + kTile, cam.width), py1 = std::min(py0 + kTile, cam.height);
        uint64_t fragments = 0;
        // Premultiplied "over" of one stroke fragment, and the AOVs of the frontmost stroke.
        auto composite = [&](size_t pi, Color col, float a, const Sprite& sp) {
            a *= sp.opacity;
            float* px = &frame.rgba[4 * pi];
            float keep = 1.0f - a;
            px[0] = col.x * a + px[0] * keep;
            px[1] = col.y * a + px[1] * keep;
            px[2] = col.z * a + px[2] * keep;
            px[3] = a + px[3] * keep;
            if (plan.aovs) {
                frame.alpha[pi] = a + frame.alpha[pi] * keep;
                if (a > 0.5f) {
                    frame.depth[pi] = sp.depth;
                    frame.object_id[pi] = static_cast<float>(sp.object_id);
                    frame.lightness[pi] = sp.k.lightness;
                }
            }
        };
        for (uint32_t idx : bins[tile]) {
            const Sprite& sp = sprites[idx];
            const SpriteMaterial& m = materials[sp.material];
            const StrokeShaderParams& p = *m.shader;
            // The sprite's colour ramp (palette, tint and atmosphere folded in), when the
            // settings allow the table: built here, per tile the sprite touches, so no frame-
            // sized array of ramps is ever held (a ramp's 384 bytes would outweigh the sprite).
            StrokeRamp local_ramp;
            const StrokeRamp* ramp = nullptr;
            // Light varying over the sprite moves its lightness per fragment: no ramp then.
            const ShadowGrid* grid = sp.grid >= 0 ? &grids[static_cast<size_t>(sp.grid)] : nullptr;
            if (rs.palette_lut && !plan.bare_blend && !grid) {
                local_ramp = make_ramp(sp.k, *m.palette);
                ramp = &local_ramp;
            }
            const bool edge_lut = rs.edge_lut;
            float ex, ey;
            extent(sp, ex, ey);
            int x0 = std::max(px0, static_cast<int>(std::floor(sp.x - ex)));
            int x1 = std::min(px1 - 1, static_cast<int>(std::floor(sp.x + ex)));
            int y0 = std::max(py0, static_cast<int>(std::floor(sp.y - ey)));
            int y1 = std::min(py1 - 1, static_cast<int>(std::floor(sp.y + ey)));
            // (s, t) = across and along the stroke, 0..1 over the sprite.
            const float sx = sp.ay / (2.0f * sp.half_w), sy = -sp.ax / (2.0f * sp.half_w);
            const float txx = sp.ax / (2.0f * sp.half_l), tyy = sp.ay / (2.0f * sp.half_l);
            // The feather, widened by the pixel's footprint in noise space at one sample per
            // pixel (with more, the samples filter; widening too measures worse).
            StrokeShaderParams pf = p;
            if (rs.filter_strokes && n == 1) {
                // A smoothstep convolved with the footprint's box: widths add roughly in
                // quadrature around the same middle.
                const float w = stroke_filter_width(sp.k, sp.half_w, sp.half_l, n);
                const float mid = 0.5f * (p.stroke_feather_min + p.stroke_feather_max);
                const float width = p.stroke_feather_max - p.stroke_feather_min;
                const float half = 0.5f * std::sqrt(width * width + 4.0f * w * w);
                pf.stroke_feather_min = mid - half;
                pf.stroke_feather_max = mid + half;
            }
            if (plan.bare_blend) {
                for (int y = y0; y <= y1; ++y) {
                    int xa = x0, xb = x1;
                    if (!row_span(sp, sx, sy, txx, tyy, y, xa, xb)) continue;
                    for (int x = xa; x <= xb; ++x) {
                        float dx = x + 0.5f - sp.x, dy = y + 0.5f - sp.y;
                        float s = 0.5f + dx * sx + dy * sy, t = 0.5f + dx * txx + dy * tyy;
                        if (s <= 0.0f || s >= 1.0f || t <= 0.0f || t >= 1.0f) continue;
                        ++fragments;
                        float* px = &frame.rgba[4 * (static_cast<size_t>(y) * cam.width + x)];
                        px[0] = 0.1f + 0.5f * px[0];
                        px[1] = 0.2f + 0.5f * px[1];
                        px[2] = 0.05f + 0.5f * px[2];
                        px[3] = 0.5f + 0.5f * px[3];
                    }
                }
                continue;
            }
            if (ramp && edge_lut) {
                // The vector kernel: one row of the sprite at a time.
                StrokeRow row;
                row.cx = sp.x, row.cy = sp.y;
                row.sx = sx, row.sy = sy, row.txx = txx, row.tyy = tyy;
                row.feather_min = pf.stroke_feather_min, row.feather_max = pf.stroke_feather_max;
                row.max_opacity = p.max_stroke_opacity, row.stroke_fullness = p.stroke_fullness;
                row.samples_per_axis = n, row.octaves = octaves;
                row.k = &sp.k, row.edge = &m.edge, row.ramp = ramp;
                float al[kTile], rr[kTile], gg[kTile], bb[kTile];
                int ins[kTile];
                for (int y = y0; y <= y1; ++y) {
                    int xa = x0, xb = x1;
                    if (!row_span(sp, sx, sy, txx, tyy, y, xa, xb)) continue;
                    shade_stroke_row(row, y, xa, xb - xa + 1, al, rr, gg, bb, ins);
                    const int len = xb - xa + 1;
                    for (int c = 0; c < len; ++c) fragments += static_cast<uint64_t>(ins[c]);
                    for (int c = 0; c < len; ++c) {
                        const float a = al[c];
                        if (!(a > 0.0f)) continue;
                        const size_t pi = static_cast<size_t>(y) * cam.width + xa + c;
                        composite(pi, Color(rr[c], gg[c], bb[c]), a, sp);
                    }
                }
                continue;
            }
            for (int y = y0; y <= y1; ++y) {
                int xa = x0, xb = x1;
                if (!row_span(sp, sx, sy, txx, tyy, y, xa, xb)) continue;
                for (int x = xa; x <= xb; ++x) {
                    float cover = 0.0f;
                    int inside = 0;
                    for (int j = 0; j < n; ++j)
                        for (int i = 0; i < n; ++i) {
                            float dx = x + (i + 0.5f) * inv_n - sp.x;
                            float dy = y + (j + 0.5f) * inv_n - sp.y;
                            float s = 0.5f + dx * sx + dy * sy;
                            float t = 0.5f + dx * txx + dy * tyy;
                            if (s <= 0.0f || s >= 1.0f || t <= 0.0f || t >= 1.0f) continue;
                            ++inside;
                            float e = edge_lut ? edge_mask(m.edge, s, t, p.stroke_fullness)
                                               : edge_mask(s, t, p.stroke_fullness);
                            // noise <= 1: below the lower feather threshold nothing shows.
                            if (e < pf.stroke_feather_min || e <= 0.0f) continue;
                            cover += stroke_opacity(pf, stroke_noise(sp.k, s, t, octaves), e);
                        }
                    if (!inside) continue;
                    fragments += static_cast<uint64_t>(inside);
                    float a = cover * inv_n * inv_n;
                    if (!(a > 0.0f)) continue;
                    float dx = x + 0.5f - sp.x, dy = y + 0.5f - sp.y;
                    float s = clamp01(0.5f + dx * sx + dy * sy);
                    float t = clamp01(0.5f + dx * txx + dy * tyy);
                    Color col;
                    if (grid) {
                        StrokeConstants k = sp.k;
                        const float light = grid_at(*grid, s, t);
                        if (light < 1.0f) k.lightness *= shadow_remap(light, p.shadow_bias);
                        col = stroke_color(k, *m.palette, s, t);
                    } else {
                        col = ramp ? stroke_color(sp.k, *ramp, s, t)
                                   : stroke_color(sp.k, *m.palette, s, t);
                    }
                    composite(static_cast<size_t>(y) * cam.width + x, col, a, sp);
                }
            }
        }
        tile_fragments[tile] = fragments;
    });
    for (uint64_t f : tile_fragments) rep.fragments += f;
    if (plan.aovs)
        for (float& d : frame.depth)
            // Background: as far as a float goes (finite, as EXR readers expect, and sorting
            // behind everything, unlike 0, which reads as nearest).
            if (!std::isfinite(d)) d = std::numeric_limits<float>::max();
    rep.passes.push_back({"paint", true, "strokes back to front, tiles in parallel", ms_since(t0),
                          std::to_string(rep.fragments) + " fragments"});
    return frame;
}

}  // namespace pleinair
