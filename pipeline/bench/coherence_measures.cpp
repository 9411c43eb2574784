// measure_coherence: four runs of the same frames, compared frame to frame.
#include "pipeline/bench/coherence_measures.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <unordered_map>

#include "pipeline/frame/graftal_stage.h"
#include "pipeline/frame/imposter_stage.h"
#include "pipeline/frame/lod.h"
#include "pipeline/frame/paint_frame.h"
#include "pipeline/input/camera_track.h"
#include "shading/color.h"
#include "shading/portable_math.h"

namespace pleinair {

double CoherenceReport::flicker_score() const {
    const double span = flicker_boiling - flicker_floor;
    return span > 0 ? (flicker - flicker_floor) / span : 0.0;
}

namespace {

constexpr uint32_t kNone = ~0u;

// One traced frame, kept until the next is compared with it.
struct Traced {
    Frame frame;
    FrameReport report;
    std::unordered_map<uint64_t, uint32_t> index;  // sprite key -> its index in the trace
};

Traced paint_traced(const Shot& shot, const FrameView& view, const FrameSettings& settings) {
    Traced t;
    t.frame = paint_frame(shot, view, settings, &t.report);
    const auto& sprites = t.report.trace->sprites;
    t.index.reserve(sprites.size());
    for (uint32_t i = 0; i < sprites.size(); ++i) t.index.emplace(sprite_key(sprites[i]), i);
    return t;
}

// How much of a particle's stroke a traced frame drew: its fade there, 0 if culled.
float drawn(const Traced& t, uint64_t key) {
    const auto found = t.index.find(key);
    return found == t.index.end() ? 0.0f : t.report.trace->sprites[found->second].fade;
}

// The summed colour change along the strokes' motion from `prev` to `cur`, and the pixels it
// was measured at.
struct Sum {
    double total = 0;
    uint64_t count = 0;
};

// `only`, when given, picks the strokes measured (the water's).
Sum flicker_between(const Traced& prev, const Traced& cur,
                    const std::function<bool(const Sprite&)>& only = {}) {
    const auto& ct = *cur.report.trace;
    const auto& pt = *prev.report.trace;
    const int w = cur.frame.width, h = cur.frame.height;
    std::vector<Sum> rows(static_cast<size_t>(h));
    tbb::parallel_for(0, h, [&](int y) {
        Sum& s = rows[static_cast<size_t>(y)];
        for (int x = 0; x < w; ++x) {
            const size_t p = static_cast<size_t>(y) * w + x;
            const uint32_t i = ct.first[p];
            if (i == kNone) continue;
            const Sprite& a = ct.sprites[i];
            if (only && !only(a)) continue;
            const auto found = prev.index.find(sprite_key(a));
            if (found == prev.index.end()) continue;
            const Sprite& b = pt.sprites[found->second];
            // The pixel's place on the stroke, in units of its half length and half width,
            // then the same place on the stroke as the previous frame drew it.
            const float dx = x + 0.5f - a.x, dy = y + 0.5f - a.y;
            const float l = (dx * a.ax + dy * a.ay) / a.half_l;
            const float u = (dx * a.ay - dy * a.ax) / a.half_w;
            const float px = b.x + l * b.half_l * b.ax + u * b.half_w * b.ay;
            const float py = b.y + l * b.half_l * b.ay - u * b.half_w * b.ax;
            if (!(px >= 0 && py >= 0 && px < w && py < h)) continue;
            const size_t q = static_cast<size_t>(py) * w + static_cast<size_t>(px);
            if (pt.first[q] != found->second) continue;  // another stroke is nearest there now
            double d = 0;
            for (int c = 0; c < 3; ++c)
                d += std::abs(linear_to_srgb(cur.frame.rgba[4 * p + c]) -
                              linear_to_srgb(prev.frame.rgba[4 * q + c]));
            s.total += d / 3;
            ++s.count;
        }
    });
    Sum all;
    for (const Sum& s : rows) all.total += s.total, all.count += s.count;
    return all;
}

// The pairs of visibly different strokes nearest and next nearest somewhere in the frame, each
// keyed (lower key, higher key) with the weight of the lower key's stroke being in front: 1 or
// 0 in a plain order, between while the two blend as their distances cross (composite.h).
struct PairHash {
    size_t operator()(const std::pair<uint64_t, uint64_t>& p) const {
        return std::hash<uint64_t>()(p.first * 0x9E3779B97F4A7C15ull ^ p.second);
    }
};
using PairOrders = std::unordered_map<std::pair<uint64_t, uint64_t>, float, PairHash>;

PairOrders order_pairs(const Traced& t) {
    const auto& tr = *t.report.trace;
    PairOrders pairs;
    for (size_t p = 0; p < tr.first.size(); ++p) {
        const uint32_t a = tr.first[p], b = tr.second[p];
        if (a == kNone || b == kNone) continue;
        const Sprite &sa = tr.sprites[a], &sb = tr.sprites[b];
        if (std::abs(sa.k.lightness - sb.k.lightness) <= 0.05f) continue;
        const uint64_t ka = sprite_key(sa), kb = sprite_key(sb);
        const float w = tr.first_weight[p];
        pairs.emplace(ka < kb ? std::pair(ka, kb) : std::pair(kb, ka), ka < kb ? w : 1.0f - w);
    }
    return pairs;
}

// Pairs in both frames whose order crossed from one side of 1/2 to the other, and of those the
// ones whose order weight moved by more than a third in the one frame: swaps made at once.
void swaps_between(const PairOrders& prev, const PairOrders& cur, uint64_t& swaps,
                   uint64_t& abrupt) {
    for (const auto& [pair, w] : cur) {
        const auto found = prev.find(pair);
        if (found == prev.end()) continue;
        const float v = found->second;
        if ((v < 0.5f) == (w < 0.5f)) continue;
        ++swaps;
        abrupt += std::abs(w - v) > 1.0f / 3.0f;
    }
}

// Each particle's presence in a frame, -1 where it is off screen (or behind the camera).
std::vector<float> presences(const Shot& shot, const FrameView& view, const RenderSettings& rs) {
    const FrameLod lod = level_of_detail(shot, view, rs);
    const Camera& cam = view.camera;
    std::vector<std::vector<float>> per_item(shot.item_count());
    tbb::parallel_for(size_t{0}, per_item.size(), [&](size_t i) {
        for_each_particle(shot, i, [&](SpriteKind kind, size_t j, const RayOrigin& o) {
            // Never drawn as a stroke: a graftal's crown or surface is measured by its graftals.
            if (drawn_as_graftals(shot, i, kind, j)) return per_item[i].push_back(-1.0f);
            const ParticleLod l = particle_lod(shot, lod, i, kind, j, o.world);
            const Projection pr = project(cam, l.world);
            const bool on =
                pr.in_front && pr.x >= 0 && pr.y >= 0 && pr.x < cam.width && pr.y < cam.height;
            per_item[i].push_back(on ? (l.gone() ? 0.0f : l.presence()) : -1.0f);
        });
    });
    std::vector<float> all;
    for (auto& v : per_item) all.insert(all.end(), v.begin(), v.end());
    // Graftals: their τ, a level growing in or fading out (graftal_stage.h).
    const std::vector<float> g = graftal_presences(shot, view);
    all.insert(all.end(), g.begin(), g.end());
    // Imposters: each edge's weight at or near the silhouette (imposter_stage.h).
    const std::vector<float> im = imposter_presences(shot, view);
    all.insert(all.end(), im.begin(), im.end());
    return all;
}

// Particle keys in the order `presences` lists them.
std::vector<uint64_t> particle_keys(const Shot& shot) {
    std::vector<uint64_t> keys;
    for (size_t i = 0; i < shot.item_count(); ++i)
        for_each_particle(shot, i, [&](SpriteKind kind, size_t j, const RayOrigin&) {
            keys.push_back(particle_key(static_cast<uint32_t>(i), kind, static_cast<uint32_t>(j)));
        });
    const std::vector<uint64_t> g = graftal_keys(shot);
    keys.insert(keys.end(), g.begin(), g.end());
    const std::vector<uint64_t> im = imposter_keys(shot);
    keys.insert(keys.end(), im.begin(), im.end());
    return keys;
}

// Covered area (share of the frame) and mean L* over it, weighted by coverage.
void area_and_lightness(const Traced& t, double& area, double& lightness) {
    const auto& through = t.report.trace->through;
    double a = 0, l = 0;
    for (size_t p = 0; p < through.size(); ++p) {
        const double cover = 1.0 - through[p];
        if (!(cover > 0)) continue;
        const float* c = &t.frame.rgba[4 * p];
        const double y = 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2];
        const double f = y > 216.0 / 24389.0 ? pmath::cbrt(y) : (24389.0 / 27.0 * y + 16) / 116;
        a += cover;
        l += cover * (116 * f - 16);
    }
    area = a / static_cast<double>(std::max<size_t>(through.size(), 1));
    lightness = a > 0 ? l / a : 0;
}

// How much the two frames' covered shapes agree: their coverage averaged over blocks of
// kBlock x kBlock pixels (a stroke's own place does not count, the crown's outline does),
// then the sum of the smaller over the sum of the larger, 1 for the same shape.
double shape_overlap(const Traced& a, const Traced& b, int width, int height) {
    constexpr int kBlock = 4;
    const auto& ta = a.report.trace->through;
    const auto& tb = b.report.trace->through;
    double common = 0, either = 0;
    for (int by = 0; by < height; by += kBlock)
        for (int bx = 0; bx < width; bx += kBlock) {
            double ca = 0, cb = 0;
            for (int y = by; y < std::min(by + kBlock, height); ++y)
                for (int x = bx; x < std::min(bx + kBlock, width); ++x) {
                    const size_t p = static_cast<size_t>(y) * width + x;
                    ca += 1.0 - ta[p], cb += 1.0 - tb[p];
                }
            common += std::min(ca, cb), either += std::max(ca, cb);
        }
    return either > 0 ? common / either : 1.0;
}

}  // namespace

CoherenceReport measure_coherence(const Shot& shot, const std::vector<int>& frames,
                                  const FrameSettings& base,
                                  const std::function<void(int)>& progress,
                                  const std::function<void(int, const Frame&)>& painted) {
    CoherenceReport rep;
    const SceneDesc& scene = shot.scene;
    if (frames.empty()) return rep;
    FrameSettings on = base;
    on.trace = true;
    const FrameView first_view = view_at(scene, frame_time(frames.front(), scene.fps));
    FrameSettings frozen = on, off = on, boiling = on;
    frozen.lod_view = &first_view;
    off.render.level_of_detail = false;
    rep.lod = plan_frame(shot, on).lod;

    const std::vector<uint64_t> keys = particle_keys(shot);
    Traced p_on, p_frozen, p_off, p_boil;
    PairOrders p_pairs;
    std::vector<float> p_presence;
    double p_area_on = 0, p_area_off = 0;
    Sum f_on, f_frozen, f_boil;
    // Still water's mirror: its strokes' flicker with it, without it, and boiling.
    rep.water = plan_frame(shot, on).reflections;
    FrameSettings dry = on;
    dry.reflections = false;
    const MaterialId water = shot.materials.surface(shot.scene.water.material);
    const std::function<bool(const Sprite&)> is_water = [&](const Sprite& sp) {
        return sp.kind == SpriteKind::kSurface && sp.material == water;
    };
    Traced p_dry;
    Sum w_on, w_dry, w_boil;
    // The wind: the trees' strokes' flicker in it, in still air, and boiling.
    rep.wind = plan_frame(shot, on).wind;
    FrameSettings calm = on;
    calm.wind = false;
    const std::function<bool(const Sprite&)> is_tree = [](const Sprite& sp) {
        return sp.kind == SpriteKind::kLeaf || sp.kind == SpriteKind::kBark;
    };
    Traced p_calm;
    Sum t_on, t_calm, t_boil;
    for (size_t n = 0; n < frames.size(); ++n) {
        const FrameView view = view_at(scene, frame_time(frames[n], scene.fps));
        boiling.noise_reseed = static_cast<uint32_t>(frames[n]) + 1;
        Traced c_on = paint_traced(shot, view, on), c_frozen = paint_traced(shot, view, frozen);
        if (painted) painted(frames[n], c_on.frame);
        Traced c_off = paint_traced(shot, view, off), c_boil = paint_traced(shot, view, boiling);
        Traced c_dry;
        if (rep.water) c_dry = paint_traced(shot, view, dry);
        Traced c_calm;
        if (rep.wind) c_calm = paint_traced(shot, view, calm);
        PairOrders c_pairs = order_pairs(c_on);
        std::vector<float> c_presence = presences(shot, view, on.render);
        double area_on, l_on, area_off, l_off;
        area_and_lightness(c_on, area_on, l_on);
        area_and_lightness(c_off, area_off, l_off);
        const double overlap = shape_overlap(c_on, c_off, view.camera.width, view.camera.height);
        rep.shape_overlap = std::min(rep.shape_overlap, overlap);
        rep.shape_floor = std::min(
            rep.shape_floor, shape_overlap(c_on, c_boil, view.camera.width, view.camera.height));
        CoherenceReport::Frame row{frames[n], area_on, area_off, l_on, l_off, overlap, 0, 0};
        const auto& sprites_on = c_on.report.trace->sprites;
        rep.sprites_on += sprites_on.size();
        rep.sprites_off += c_off.report.trace->sprites.size();
        rep.fragments_on += c_on.report.fragments;
        rep.fragments_off += c_off.report.fragments;
        if (area_off > 1e-6) {
            rep.area_difference = std::max(rep.area_difference, std::abs(area_on / area_off - 1));
            rep.lightness_difference = std::max(rep.lightness_difference, std::abs(l_on - l_off));
        }
        if (n > 0) {
            auto add = [](Sum& to, const Sum& s) { to.total += s.total, to.count += s.count; };
            add(f_on, flicker_between(p_on, c_on));
            add(f_frozen, flicker_between(p_frozen, c_frozen));
            add(f_boil, flicker_between(p_boil, c_boil));
            if (rep.water) {
                add(w_on, flicker_between(p_on, c_on, is_water));
                add(w_dry, flicker_between(p_dry, c_dry, is_water));
                add(w_boil, flicker_between(p_boil, c_boil, is_water));
            }
            if (rep.wind) {
                add(t_on, flicker_between(p_on, c_on, is_tree));
                add(t_calm, flicker_between(p_calm, c_calm, is_tree));
                add(t_boil, flicker_between(p_boil, c_boil, is_tree));
            }
            swaps_between(p_pairs, c_pairs, row.order_swaps, row.abrupt_swaps);
            rep.order_swaps += row.order_swaps, rep.abrupt_swaps += row.abrupt_swaps;
            for (size_t k = 0; k < c_presence.size(); ++k) {
                const float a = p_presence[k], b = c_presence[k];
                if (a < 0 || b < 0) continue;  // off screen in one of the two
                rep.steepest_fade = std::max(rep.steepest_fade, double(std::abs(a - b)));
                if (std::abs(a - b) > 1.0f / 3.0f) {
                    ++rep.pops;
                } else if (a > 1.0f / 3.0f && b > 1.0f / 3.0f) {
                    rep.cull_pops +=
                        std::abs(drawn(p_on, keys[k]) - drawn(c_on, keys[k])) > 1.0f / 3.0f;
                }
            }
            if (p_area_on > 1e-6 && p_area_off > 1e-6)
                rep.area_step =
                    std::max(rep.area_step, std::abs(area_on / p_area_on - area_off / p_area_off));
        }
        p_on = std::move(c_on), p_frozen = std::move(c_frozen);
        p_off = std::move(c_off), p_boil = std::move(c_boil), p_dry = std::move(c_dry);
        p_calm = std::move(c_calm);
        p_pairs = std::move(c_pairs);
        p_presence = std::move(c_presence);
        p_area_on = area_on, p_area_off = area_off;
        rep.per_frame.push_back(row);
        ++rep.frames;
        if (progress) progress(rep.frames);
    }
    auto mean = [](const Sum& s) { return s.count ? s.total / static_cast<double>(s.count) : 0.0; };
    rep.flicker = mean(f_on), rep.flicker_floor = mean(f_frozen);
    rep.flicker_boiling = mean(f_boil);
    rep.water_flicker = mean(w_on), rep.water_flicker_dry = mean(w_dry);
    rep.water_flicker_boiling = mean(w_boil);
    rep.tree_flicker = mean(t_on), rep.tree_flicker_calm = mean(t_calm);
    rep.tree_flicker_boiling = mean(t_boil);
    return rep;
}

}  // namespace pleinair
