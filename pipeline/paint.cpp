// Sprites from particles, depth sort, tile binning and per-tile back-to-front compositing with
// the stroke shader; the background is painted per tile first.
#include "pipeline/paint.h"

#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <glm/geometric.hpp>
#include <limits>

#include "generators/rng.h"
#include "shading/stroke_kernel.h"

namespace pleinair {

namespace {

using Clock = std::chrono::steady_clock;
double ms_since(Clock::time_point t0) {
    return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

constexpr int kTile = 64;

struct Material {
    const StrokeShaderParams* shader = nullptr;
    const Palette* palette = nullptr;
    EdgeTable edge;
};

struct Sprite {
    float x = 0, y = 0, depth = 0;
    float half_w = 0, half_l = 0;  // across and along the stroke, pixels
    float ax = 0, ay = 1;          // unit screen direction of the stroke's length
    uint32_t material = 0;
    uint32_t object_id = 0;
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

// Screen size of a world length at view depth z: true perspective scaled by
// (focus / z)^(1 - stroke_perspective), so strokes shrink less than geometry.
float stroke_px(const Camera& cam, const RenderSettings& r, double world, double z) {
    double p = std::clamp<double>(r.stroke_perspective, 0.0, 1.0);
    double px = cam.focal_px * world / (std::pow(cam.focus_distance, 1.0 - p) * std::pow(z, p));
    return static_cast<float>(px);
}

struct SpriteInput {
    glm::dvec3 world;
    glm::vec3 normal;   // world, unit
    glm::vec3 tangent;  // world, unit (bark), or zero (leaves)
    double width;       // world units
    double length;
    float center_distance, branch_distance, label;
    uint32_t tree_id;
};

// Projects one particle; returns false if it is culled (behind the camera, not finite, too
// small, or off screen).
bool make_sprite(const SceneDesc& scene, const FramePlan& plan, const Material& m, uint32_t mat,
                 const SpriteInput& in, Sprite& out) {
    const Camera& cam = scene.camera;
    const StrokeShaderParams& p = *m.shader;
    Projection c = project(cam, in.world);
    if (!c.in_front) return false;
    double z = c.depth;
    float jitter = 1.0f + p.size_jitter * (2.0f * label_hash(in.label, 1) - 1.0f);
    float w = stroke_px(cam, scene.render, in.width * jitter, z);
    float l = stroke_px(cam, scene.render, in.length * jitter, z);
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
    out.k = stroke_constants(p, n_dot_l, in.center_distance, in.branch_distance, in.label,
                             in.tree_id, 1.0f, d, 0.0f, plan.tint && p.unique_tint_amt > 0,
                             plan.atmosphere && has_atmosphere_effect(p));
    if (!plan.sub_stroke) out.k.sub_amt = 0;
    out.material = mat;
    out.object_id = in.tree_id + 1;
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
    return plan;
}

Frame paint_frame(const SceneDesc& scene, const std::vector<BuiltTree>& trees,
                  const FramePlan& plan, FrameReport* report) {
    const Camera& cam = scene.camera;
    const RenderSettings& rs = scene.render;
    FrameReport local;
    FrameReport& rep = report ? *report : local;

    // Materials: per family, leaves then bark.
    std::vector<Material> materials(2 * scene.families.size());
    for (size_t f = 0; f < scene.families.size(); ++f) {
        const Family& fam = scene.families[f];
        for (int kind = 0; kind < 2; ++kind) {
            Material& m = materials[2 * f + kind];
            m.shader = kind == 0 ? &fam.leaf_shader : &fam.bark_shader;
            m.palette = kind == 0 ? &fam.leaf_palette : &fam.bark_palette;
            m.edge = make_edge_table(m.shader->stroke_fullness);
        }
    }

    // Sprites, per tree in parallel, concatenated in tree order.
    auto t0 = Clock::now();
    std::vector<std::vector<Sprite>> per_tree(trees.size());
    std::vector<uint64_t> culled(trees.size(), 0);
    tbb::parallel_for(size_t{0}, trees.size(), [&](size_t i) {
        const BuiltTree& b = trees[i];
        const Family& fam = scene.families[b.family];
        double c = std::cos(b.rotation * M_PI / 180.0), s = std::sin(b.rotation * M_PI / 180.0);
        auto place = [&](const glm::vec3& p) {
            return b.position + rotate_y(glm::dvec3(p) * b.scale, c, s);
        };
        auto turn = [&](const glm::vec3& v) { return glm::vec3(rotate_y(glm::dvec3(v), c, s)); };
        std::vector<Sprite>& out = per_tree[i];
        const LeafParticles& L = b.tree.leaves;
        out.reserve(L.size() + (plan.bark ? b.bark.size() : 0));
        const uint32_t leaf_mat = 2 * b.family, bark_mat = 2 * b.family + 1;
        if (plan.bark) {
            const BarkParticles& B = b.bark;
            const StrokeShaderParams& p = fam.bark_shader;
            double w = p.sprite_size * fam.params.unit * b.scale;
            for (size_t j = 0; j < B.size(); ++j) {
                SpriteInput in{place(B.position[j]),
                               turn(B.normal[j]),
                               turn(B.tangent[j]),
                               w,
                               w * p.stroke_aspect,
                               0.5f,
                               0.5f,
                               B.label[j],
                               b.tree.id};
                Sprite sp;
                if (make_sprite(scene, plan, materials[bark_mat], bark_mat, in, sp))
                    out.push_back(sp);
                else
                    ++culled[i];
            }
        }
        const StrokeShaderParams& p = fam.leaf_shader;
        double w = p.sprite_size * fam.params.unit * b.scale;
        for (size_t j = 0; j < L.size(); ++j) {
            SpriteInput in{
                place(L.position[j]), turn(L.normal[j]),    glm::vec3(0.0f),      w,
                w * p.stroke_aspect,  L.center_distance[j], L.branch_distance[j], L.label[j],
                L.tree_id[j]};
            Sprite sp;
            if (make_sprite(scene, plan, materials[leaf_mat], leaf_mat, in, sp))
                out.push_back(sp);
            else
                ++culled[i];
        }
    });
    std::vector<Sprite> sprites;
    for (size_t i = 0; i < trees.size(); ++i) {
        for (const Sprite& sp : per_tree[i])
            (sp.material & 1 ? rep.bark_sprites : rep.leaf_sprites)++;
        sprites.insert(sprites.end(), per_tree[i].begin(), per_tree[i].end());
        rep.culled += culled[i];
    }
    per_tree.clear();
    rep.passes.push_back(
        {"sprites", true, "every particle faces the camera", ms_since(t0),
         std::to_string(sprites.size()) + " sprites, " + std::to_string(rep.culled) + " culled"});

    // Back to front; the index breaks ties so the order is total and thread-independent.
    t0 = Clock::now();
    std::vector<uint32_t> order(sprites.size());
    for (size_t i = 0; i < order.size(); ++i) order[i] = static_cast<uint32_t>(i);
    tbb::parallel_sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) {
        if (sprites[a].depth != sprites[b].depth) return sprites[a].depth > sprites[b].depth;
        return a < b;
    });
    rep.passes.push_back({"sort", true, "back-to-front compositing", ms_since(t0), ""});

    // Per-sprite colour ramps (palette, tint and atmosphere folded in), when the settings
    // allow the table instead of the exact lookup per fragment.
    std::vector<StrokeRamp> ramps;
    if (rs.palette_lut) {
        t0 = Clock::now();
        ramps.resize(sprites.size());
        tbb::parallel_for(size_t{0}, sprites.size(), [&](size_t i) {
            ramps[i] = make_ramp(sprites[i].k, *materials[sprites[i].material].palette);
        });
        rep.passes.push_back({"colour ramps", true,
                              "render/palette_lut: colours tabulated per sprite", ms_since(t0),
                              ""});
    }

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

    t0 = Clock::now();
    tbb::parallel_for(size_t{0}, bins.size(), [&](size_t tile) {
        const int tx = static_cast<int>(tile % tiles_x), ty = static_cast<int>(tile / tiles_x);
        const int px0 = tx * kTile, py0 = ty * kTile;
        const int px1 = std::min(px0 + kTile, cam.width), py1 = std::min(py0 + kTile, cam.height);
        uint64_t fragments = 0;
        // Premultiplied "over" of one stroke fragment, and the AOVs of the frontmost stroke.
        auto composite = [&](size_t pi, Color col, float a, const Sprite& sp) {
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
            const Material& m = materials[sp.material];
            const StrokeShaderParams& p = *m.shader;
            const StrokeRamp* ramp = ramps.empty() ? nullptr : &ramps[idx];
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
                    for (int c = 0; c <= xb - xa; ++c) {
                        fragments += static_cast<uint64_t>(ins[c]);
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
                    Color col = ramp ? stroke_color(sp.k, *ramp, s, t)
                                     : stroke_color(sp.k, *m.palette, s, t);
                    composite(static_cast<size_t>(y) * cam.width + x, col, a, sp);
                }
            }
        }
        tile_fragments[tile] = fragments;
    });
    for (uint64_t f : tile_fragments) rep.fragments += f;
    if (plan.aovs)
        for (float& d : frame.depth)
            if (!std::isfinite(d)) d = 0.0f;  // background: no depth (EXR readers expect finite)
    rep.passes.push_back({"paint", true, "strokes back to front, tiles in parallel", ms_since(t0),
                          std::to_string(rep.fragments) + " fragments"});
    return frame;
}

}  // namespace pleinair
