// The frame's strokes: each tile composites its sprites front to back with
// the stroke kernel (vector rows when the sprite's colours come from its ramp, scalar samples
// when they vary per fragment), tiles in parallel, and stops where nothing behind would show.
#include "pipeline/frame/composite.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <limits>
#include <memory>
#include <string>

#include "pipeline/shot/shot.h"
#include "shading/canvas.h"
#include "shading/curves.h"
#include "shading/pigment.h"
#include "shading/portable_math.h"
#include "shading/stroke_kernel.h"

namespace pleinair {

namespace {

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

// One sprite's footprint inside one tile, and the screen gradients of its (s, t): across and
// along the stroke, 0..1 over the sprite.
struct SpriteSpan {
    int x0, x1, y0, y1;
    float sx, sy, txx, tyy;
};

SpriteSpan sprite_span(const Sprite& sp, int px0, int py0, int px1, int py1) {
    float ex, ey;
    sprite_extent(sp, ex, ey);
    SpriteSpan s;
    s.x0 = std::max(px0, static_cast<int>(std::floor(sp.x - ex)));
    s.x1 = std::min(px1 - 1, static_cast<int>(std::floor(sp.x + ex)));
    s.y0 = std::max(py0, static_cast<int>(std::floor(sp.y - ey)));
    s.y1 = std::min(py1 - 1, static_cast<int>(std::floor(sp.y + ey)));
    s.sx = sp.ay / (2.0f * sp.half_w), s.sy = -sp.ax / (2.0f * sp.half_w);
    s.txx = sp.ax / (2.0f * sp.half_l), s.tyy = sp.ay / (2.0f * sp.half_l);
    return s;
}

// One tile's strokes composited front to back: the premultiplied colour gathered so far, the
// light still let through (transmittance), and the AOVs of the nearest stroke more than half
// opaque. The background and underpainting go under it when the tile is done.
//
// Soft depth order (thesis V.3, Fig. 31): while the camera moves, two strokes whose eye
// distances are within `window` frames' worth of their swap speeds (Sprite::swap_speed: the
// most the eye's travel changes their difference in a frame) of each other are not put in one
// order: each is seen through the other in proportion to how likely it is to be behind,
//     C = sum_i c_i a_i prod_{j != i} (1 - a_j s_ji),
// with s_ji easing from 1/2 at equal distances to 1 (j in front of i) and 0 at the window's
// edges. Hard orders make it plain "over"; for two strokes it is exactly the mix of both orders
// "over" gives, so a swap takes at least 2 x window frames; more strokes at once are scaled to
// the coverage all of them give in any order. To evaluate it front to back, each pixel holds up
// to kHeld strokes that a later one could still blend with, and settles each once no later
// stroke can (the strokes come nearest first). A still camera holds none: plain "over".
struct TileLayer {
    int x0 = 0, y0 = 0, w = 0, h = 0;
    // Light that still reaches a pixel through the strokes painted in front of it, at or below
    // which nothing behind can change the pixel by more than that: the default 1/2048 of a
    // linear unit is under a third of an 8-bit sRGB level even in the darkest paint.
    float cutoff = 0;
    int saturated = 0;  // pixels whose transmittance fell to the cutoff
    std::array<float, 3 * kTile * kTile> color;
    std::array<float, kTile * kTile> through;      // through every stroke taken, held or not
    std::array<float, 4 * kTile * kTile> pigment;  // pigment mixing: concentrations gathered
    std::array<uint32_t, kTile * kTile> front;     // sprite index of the AOVs, or kNone
    // The coherence bench's trace: the two nearest strokes over 5% opaque (filled when traced),
    // and the weight of the first's being in front of the second (1 in plain order).
    std::array<uint32_t, kTile * kTile> first, second;
    std::array<float, kTile * kTile> first_weight;
    static constexpr uint32_t kNone = ~0u;
    static constexpr float kInf = std::numeric_limits<float>::infinity();

    // Soft order, in a tile where some sprite moves against another (speed_max > 0).
    // Six: a willow's strands in a gust layer five or more swaying strokes within one another's
    // window at a pixel, and with four the nearest was settled early, so its swap was made in
    // one frame (BENCHMARKS.md, "Wind").
    static constexpr int kHeld = 6;
    struct Held {
        float r, g, b, a, range, speed;
        float light;  // reaching it through the settled strokes and those held settled before it
        uint32_t idx;
    };
    bool soft = false;
    bool solo = false;    // the stroke being painted can blend with no later one
    float window = 0;     // render/order_blend_frames / 2
    float speed_max = 0;  // the tile's largest swap speed
    // A pixel takes strokes nearer than this: all while light gets through, and once covered,
    // those that might still blend in front of a held stroke. Saturated pixels' largest.
    std::array<float, kTile * kTile> open_until;
    float open_until_all = -kInf;
    // Per pixel: light through the settled strokes, alpha gathered (a_i times its weight), the
    // held strokes, and whether any two blended.
    std::array<float, kTile * kTile> settled, gathered;
    std::array<uint8_t, kTile * kTile> held_count, blended;
    Held* held = nullptr;  // kHeld per pixel, the thread's (soft tiles only)

    // Ready for the tile [px0, px1) x [py0, py1): the arrays a frame reads set, those it does
    // not (pigments, AOVs, the trace; the soft order's, set by make_soft) left as they were. A
    // layer is a quarter megabyte, reused tile after tile by its thread.
    void reset(int px0, int py0, int px1, int py1, float cut, const FramePlan& plan,
               bool pigments) {
        x0 = px0, y0 = py0, w = px1 - px0, h = py1 - py0, cutoff = cut;
        saturated = 0, range = 0;
        soft = solo = false, window = speed_max = 0, held = nullptr;
        open_until_all = -kInf;
        color.fill(0.0f);
        through.fill(1.0f);
        open_until.fill(kInf);
        if (pigments) pigment.fill(0.0f);
        if (plan.aovs) front.fill(kNone);
        if (plan.trace) {
            first.fill(kNone);
            second.fill(kNone);
            first_weight.fill(1.0f);
        }
    }
    // Pixels a layer in front already covers: closed before the first stroke.
    void close_covered(const StrokeLayer& front_layer) {
        for (int y = y0; y < y0 + h; ++y)
            for (int x = x0; x < x0 + w; ++x)
                if (front_layer.covered(static_cast<size_t>(y) * front_layer.width + x)) {
                    open_until[at(x, y)] = -kInf;
                    ++saturated;
                }
    }
    void make_soft(float win, float speed, Held* pool) {
        soft = true, window = win, speed_max = speed, held = pool;
        settled.fill(1.0f);
        gathered.fill(0.0f);
        held_count.fill(0);
        blended.fill(0);
    }
    size_t at(int x, int y) const { return static_cast<size_t>(y - y0) * kTile + (x - x0); }
    // The eye distance of the stroke being painted: whether it can change a pixel.
    float range = 0;
    bool open(int x, int y) const { return range < open_until[at(x, y)]; }
    bool full(float next_range) const {
        return saturated == w * h && !(next_range < open_until_all);
    }
    // Whether any pixel of the box [x0, x1] x [y0, y1] (inside the tile) can still change.
    bool any_open(int bx0, int by0, int bx1, int by1) const {
        for (int y = by0; y <= by1; ++y)
            for (int x = bx0; x <= bx1; ++x)
                if (open(x, y)) return true;
        return false;
    }
    // How far beyond a held stroke a later one may lie and still blend with it.
    float reach(const Held& e) const { return window * (e.speed + speed_max); }
    // After a stroke at pixel li: counts it saturated, and how long it stays open.
    void settle(size_t li, bool was_open) {
        const bool now_open = through[li] > cutoff;
        if (was_open && !now_open) ++saturated;
        if (now_open) return;
        float until = -kInf;
        if (soft)
            for (int k = 0; k < held_count[li]; ++k) {
                const Held& e = held[li * kHeld + k];
                until = std::max(until, e.range + reach(e));
            }
        open_until[li] = until;
        open_until_all = std::max(open_until_all, until);
    }
};

// The weight of a stroke at distance ra being in front of one at rb, for the pair's window
// `reach` (TileLayer): 1 beyond it, 1/2 at equal distances.
float in_front(float ra, float rb, float reach) {
    return rb - ra >= reach ? 1.0f : smoothstep(-reach, reach, rb - ra);
}

// What the tile painter shares across its sprites.
struct TilePainter {
    const Shot& shot;
    const SpriteSet& set;
    const FramePlan& plan;
    const RenderSettings& rs;
    Frame& frame;
    int n;  // samples per pixel axis: the sprite's (paint), from the frame's
    TileLayer& layer;
    StrokeLayer& out;
    const PigmentTable* pigments = nullptr;  // pigment mixing
    const CanvasWeave* canvas = nullptr;     // a canvas weave catching the strokes' edges
    int frame_n = 1;                         // the settings' samples per pixel axis
    float one_sample_px = 0;                 // paint_strokes' rule for large strokes
    uint64_t fragments = 0;

    // Adds a stroke's colour at pixel li with weight w: in linear RGB, or as paint (its
    // pigment concentrations apart, the residual where the colour goes).
    void add(size_t li, Color col, float w) {
        if (pigments) {
            const PigmentLatent z = pigments->encode(col);
            float* p = &layer.pigment[4 * li];
            for (int k = 0; k < 4; ++k) p[k] += z.c[k] * w;
            col = z.residual;
        }
        float* c = &layer.color[3 * li];
        c[0] += col.x * w;
        c[1] += col.y * w;
        c[2] += col.z * w;
    }

    // Premultiplied "under" of one stroke fragment: it shows through what lies in front (or,
    // while the camera moves, is held to blend with its neighbours in distance: TileLayer).
    void composite(int x, int y, Color col, float a, uint32_t idx) {
        if (canvas) a = canvas_edge(a, canvas->at(x, y), rs.canvas_weave);
        const size_t li = layer.at(x, y);
        if (layer.soft) return hold(li, col, a, idx);
        float& through = layer.through[li];
        const bool was_open = through > layer.cutoff;
        trace(li, a, idx);
        add(li, col, through * a);
        if (plan.aovs && a > 0.5f && layer.front[li] == TileLayer::kNone) layer.front[li] = idx;
        through *= 1.0f - a;
        layer.settle(li, was_open);
    }

    // Soft order: settles the held strokes no later one can blend with, then holds this one
    // (dropped if the pixel is covered and it can blend with none of them).
    void hold(size_t li, Color col, float a, uint32_t idx) {
        const Sprite& sp = set.sprites[idx];
        TileLayer::Held* h = &layer.held[li * TileLayer::kHeld];
        uint8_t& count = layer.held_count[li];
        while (count > 0 && !(sp.range < h[0].range + layer.reach(h[0]))) settle_front(li);
        float& through = layer.through[li];
        const bool was_open = through > layer.cutoff;
        if (!was_open) {
            bool blends = false;
            for (int k = 0; k < count; ++k)
                blends |= sp.range - h[k].range < layer.window * (h[k].speed + sp.swap_speed);
            if (!blends) return;
        }
        if (count == TileLayer::kHeld) settle_front(li);
        trace(li, a, idx);
        if (plan.aovs && a > 0.5f && layer.front[li] == TileLayer::kNone) layer.front[li] = idx;
        if (count == 0 && layer.solo) {
            // Nothing held here and no later stroke of the tile can blend with it: settled at
            // once, as plain "over" would.
            const float w = layer.settled[li] * a;
            add(li, col, w);
            layer.gathered[li] += w;
            layer.settled[li] *= 1.0f - a;
        } else {
            h[count++] = {col.x, col.y, col.z, a, sp.range, sp.swap_speed, layer.settled[li], idx};
        }
        through *= 1.0f - a;
        layer.settle(li, was_open);
    }

    // The nearest held stroke at pixel li settled: its colour added, seen through the strokes
    // held with it by how likely each is in front, and its light taken from theirs.
    void settle_front(size_t li) {
        TileLayer::Held* h = &layer.held[li * TileLayer::kHeld];
        uint8_t& count = layer.held_count[li];
        const TileLayer::Held& f = h[0];
        float light = f.light;
        for (int k = 1; k < count; ++k) {
            const float reach = layer.window * (f.speed + h[k].speed);
            const float front = in_front(f.range, h[k].range, reach);
            if (front < 1.0f) {
                light *= 1.0f - h[k].a * (1.0f - front);  // k in front of f
                h[k].light *= 1.0f - f.a * front;
                layer.blended[li] = 1;
                if (plan.trace && layer.first[li] == f.idx && layer.second[li] == h[k].idx)
                    layer.first_weight[li] = front;
            } else {
                h[k].light *= 1.0f - f.a;
            }
        }
        const float w = light * f.a;
        add(li, Color(f.r, f.g, f.b), w);
        layer.gathered[li] += w;
        layer.settled[li] *= 1.0f - f.a;
        std::copy(h + 1, h + count, h);
        --count;
    }

    // The coherence bench's two nearest strokes over 5% opaque.
    void trace(size_t li, float a, uint32_t idx) {
        if (!plan.trace || !(a > 0.05f)) return;
        if (layer.first[li] == TileLayer::kNone)
            layer.first[li] = idx;
        else if (layer.second[li] == TileLayer::kNone && layer.first[li] != idx)
            layer.second[li] = idx;
    }

    // The feather, widened by the pixel's footprint in noise space at one sample per pixel
    // (with more, the samples filter; widening too measures worse).
    StrokeShaderParams filtered(const Sprite& sp, const SpriteMaterial& m) const {
        const StrokeShaderParams& p = *m.shader;
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
        // A dry-brush fade (shading/dry_brush.h): the thresholds rise until the stroke keeps
        // `fade` of its coverage. Made transparent instead, fading strokes read as blur.
        if (sp.fade < 1.0f) {
            const float rise = dry_brush_rise(m.dry_brush, p, sp.fade);
            pf.stroke_feather_min += rise;
            pf.stroke_feather_max += rise;
        }
        return pf;
    }

    // What the stroke kernels read of one sprite (no ramp yet).
    StrokeRow stroke_row(const Sprite& sp, const SpriteSpan& r, const SpriteMaterial& m,
                         const StrokeShaderParams& pf) const {
        StrokeRow row;
        row.cx = sp.x, row.cy = sp.y;
        row.sx = r.sx, row.sy = r.sy, row.txx = r.txx, row.tyy = r.tyy;
        row.feather_min = pf.stroke_feather_min, row.feather_max = pf.stroke_feather_max;
        row.max_opacity = m.shader->max_stroke_opacity;
        row.stroke_fullness = m.shader->stroke_fullness;
        row.samples_per_axis = n, row.octaves = rs.octaves;
        row.k = &sp.k, row.edge = &m.edge;
        return row;
    }

    // The vector kernel, one row of the sprite at a time, colours from the sprite's ramp.
    void rows(uint32_t idx, const SpriteSpan& r, const SpriteMaterial& m,
              const StrokeShaderParams& pf, const StrokeRamp& ramp) {
        const Sprite& sp = set.sprites[idx];
        StrokeRow row = stroke_row(sp, r, m, pf);
        row.ramp = &ramp;
        float al[kTile], rr[kTile], gg[kTile], bb[kTile];
        int ins[kTile];
        for (int y = r.y0; y <= r.y1; ++y) {
            int xa = r.x0, xb = r.x1;
            if (!row_span(sp, r.sx, r.sy, r.txx, r.tyy, y, xa, xb)) continue;
            // Each run of pixels that can still change, shaded as one span.
            for (int a = xa; a <= xb;) {
                if (!layer.open(a, y)) {
                    ++a;
                    continue;
                }
                int b = a;
                while (b < xb && layer.open(b + 1, y)) ++b;
                const int len = b - a + 1;
                shade_stroke_row(row, y, a, len, al, rr, gg, bb, ins);
                for (int c = 0; c < len; ++c) fragments += static_cast<uint64_t>(ins[c]);
                for (int c = 0; c < len; ++c)
                    if (al[c] > 0.0f) composite(a + c, y, Color(rr[c], gg[c], bb[c]), al[c], idx);
                a = b + 1;
            }
        }
    }

    // Sample by sample: exact edge mask or palette, or light varying over the sprite.
    void samples(uint32_t idx, const SpriteSpan& r, const SpriteMaterial& m,
                 const StrokeShaderParams& pf, const StrokeRamp* ramp, const ShadowGrid* grid);

    // A graftal's patch (graftal_draw.h): each pixel's 8-bit premultiplied sRGB back to linear
    // light, composited like a stroke's fragment.
    void paint_patch(uint32_t idx) {
        const Sprite& sp = set.sprites[idx];
        const GraftalPatch& p = set.patches[static_cast<size_t>(sp.patch)];
        static const std::array<float, 256> lin = [] {
            std::array<float, 256> t{};
            for (int i = 0; i < 256; ++i) t[i] = srgb_to_linear(static_cast<float>(i) / 255.0f);
            return t;
        }();
        const int xa = std::max(layer.x0, p.x0), xb = std::min(layer.x0 + layer.w, p.x0 + p.width);
        const int ya = std::max(layer.y0, p.y0), yb = std::min(layer.y0 + layer.h, p.y0 + p.height);
        for (int y = ya; y < yb; ++y)
            for (int x = xa; x < xb; ++x) {
                if (!layer.open(x, y)) continue;
                const uint32_t px = p.pixels[static_cast<size_t>(y - p.y0) * p.width + (x - p.x0)];
                const uint32_t a8 = px >> 24;
                if (a8 == 0) continue;
                ++fragments;
                // Unpremultiplied to the nearest 8-bit level, as the drawing program meant it.
                auto channel = [&](int shift) {
                    const uint32_t c8 = (px >> shift) & 0xffu;
                    return lin[std::min<uint32_t>(255u, (c8 * 255u + a8 / 2) / a8)];
                };
                const float a = static_cast<float>(a8) * (1.0f / 255.0f) * sp.fade;
                composite(x, y, Color(channel(16), channel(8), channel(0)), a, idx);
            }
    }

    void paint(uint32_t idx) {
        const Sprite& sp = set.sprites[idx];
        if (sp.kind == SpriteKind::kGraftal) return paint_patch(idx);
        const SpriteMaterial& m = shot.materials[sp.material];
        n = one_sample_px > 0 && std::min(sp.half_w, sp.half_l) >= one_sample_px ? 1 : frame_n;
        const SpriteSpan r =
            sprite_span(sp, layer.x0, layer.y0, layer.x0 + layer.w, layer.y0 + layer.h);
        // Hidden here by nearer strokes: nothing to build or shade.
        if (!layer.any_open(r.x0, r.y0, r.x1, r.y1)) return;
        // Light varying over the sprite moves its lightness per fragment: no ramp then.
        const ShadowGrid* grid = sp.grid >= 0 ? &set.grids[static_cast<size_t>(sp.grid)] : nullptr;
        // The sprite's colour ramp (palette, tint and atmosphere folded in), when the settings
        // allow the table: built here, per tile the sprite touches, so no frame-sized array of
        // ramps is ever held (a ramp's 384 bytes would outweigh the sprite).
        StrokeRamp ramp;
        const bool use_ramp = rs.palette_lut && !grid;
        if (use_ramp) ramp = make_ramp(sp.k, *m.palette);
        const StrokeShaderParams pf = filtered(sp, m);
        if (use_ramp && rs.edge_lut) return rows(idx, r, m, pf, ramp);
        samples(idx, r, m, pf, use_ramp ? &ramp : nullptr, grid);
    }

    // Soft order: every held stroke settled; where three or more blended, the colour scaled to
    // the coverage they give in any order (two blended give it exactly).
    void settle_all() {
        for (int y = layer.y0; y < layer.y0 + layer.h; ++y)
            for (int x = layer.x0; x < layer.x0 + layer.w; ++x) {
                const size_t li = layer.at(x, y);
                while (layer.held_count[li] > 0) settle_front(li);
                const float cover = 1.0f - layer.through[li], gathered = layer.gathered[li];
                if (!layer.blended[li] || !(gathered > 0.0f)) continue;
                const float scale = cover / gathered;
                for (int k = 0; k < 3; ++k) layer.color[3 * li + k] *= scale;
                for (int k = 0; k < 4; ++k) layer.pigment[4 * li + k] *= scale;
            }
    }

    // The tile's part of the frame's stroke layer, and its AOVs.
    void finish() {
        if (layer.soft) settle_all();
        for (int y = layer.y0; y < layer.y0 + layer.h; ++y)
            for (int x = layer.x0; x < layer.x0 + layer.w; ++x) {
                const size_t li = layer.at(x, y), pi = static_cast<size_t>(y) * frame.width + x;
                std::copy_n(&layer.color[3 * li], 3, &out.color[3 * pi]);
                if (pigments) std::copy_n(&layer.pigment[4 * li], 4, &out.pigment[4 * pi]);
                out.through[pi] = layer.through[li];
                if (plan.trace) {
                    out.first[pi] = layer.first[li], out.second[pi] = layer.second[li];
                    out.first_weight[pi] = layer.first_weight[li];
                }
                if (!plan.aovs || layer.front[li] == TileLayer::kNone) continue;
                const Sprite& sp = set.sprites[layer.front[li]];
                frame.depth[pi] = sp.depth;
                frame.object_id[pi] = static_cast<float>(sp.object_id);
                frame.lightness[pi] = sp.k.lightness;
            }
    }
};

// Benchmarks: each sprite's footprint blended with a constant colour, back to front straight
// into the layer's colour: the cost floor of a fragment.
uint64_t paint_bare(const Sprite& sp, const SpriteSpan& r, StrokeLayer& out) {
    uint64_t fragments = 0;
    for (int y = r.y0; y <= r.y1; ++y) {
        int xa = r.x0, xb = r.x1;
        if (!row_span(sp, r.sx, r.sy, r.txx, r.tyy, y, xa, xb)) continue;
        for (int x = xa; x <= xb; ++x) {
            float dx = x + 0.5f - sp.x, dy = y + 0.5f - sp.y;
            float s = 0.5f + dx * r.sx + dy * r.sy, t = 0.5f + dx * r.txx + dy * r.tyy;
            if (s <= 0.0f || s >= 1.0f || t <= 0.0f || t >= 1.0f) continue;
            ++fragments;
            float* px = &out.color[3 * (static_cast<size_t>(y) * out.width + x)];
            px[0] = 0.1f + 0.5f * px[0];
            px[1] = 0.2f + 0.5f * px[1];
            px[2] = 0.05f + 0.5f * px[2];
        }
    }
    return fragments;
}

void TilePainter::samples(uint32_t idx, const SpriteSpan& r, const SpriteMaterial& m,
                          const StrokeShaderParams& pf, const StrokeRamp* ramp,
                          const ShadowGrid* grid) {
    const Sprite& sp = set.sprites[idx];
    const StrokeShaderParams& p = *m.shader;
    StrokeRow row = stroke_row(sp, r, m, pf);
    if (!rs.edge_lut) row.edge = nullptr;
    for (int y = r.y0; y <= r.y1; ++y) {
        int xa = r.x0, xb = r.x1;
        if (!row_span(sp, r.sx, r.sy, r.txx, r.tyy, y, xa, xb)) continue;
        for (int x = xa; x <= xb; ++x) {
            if (!layer.open(x, y)) continue;
            int inside = 0;
            const float a = stroke_coverage(row, x, y, inside);
            fragments += static_cast<uint64_t>(inside);
            if (!(a > 0.0f)) continue;
            float s, t;
            stroke_pixel_st(row, x, y, s, t);
            Color col;
            if (grid) {
                StrokeConstants k = sp.k;
                const float light = grid_at(*grid, s, t);
                if (light < 1.0f) k.lightness *= shadow_remap(light, p.shadow_bias);
                col = stroke_color(k, *m.palette, s, t);
            } else {
                col = ramp ? stroke_color(sp.k, *ramp, s, t) : stroke_color(sp.k, *m.palette, s, t);
            }
            composite(x, y, col, a, idx);
        }
    }
}

}  // namespace

Frame make_frame(const Camera& cam, bool aovs, BufferPool* pool) {
    Frame frame;
    frame.width = cam.width;
    frame.height = cam.height;
    const size_t npix = static_cast<size_t>(cam.width) * cam.height;
    frame.rgba = pooled(pool, 4 * npix, 0.0f);
    frame.has_aovs = aovs;
    if (aovs) {
        frame.depth.assign(npix, std::numeric_limits<float>::infinity());
        frame.object_id.assign(npix, 0.0f);
        frame.alpha.assign(npix, 0.0f);
        frame.lightness.assign(npix, 0.0f);
    }
    return frame;
}

StrokeLayer paint_strokes(const Shot& shot, const SpriteSet& set, const TileBins& bins,
                          const FramePlan& plan, const RenderSettings& rs, Frame& frame,
                          const std::function<void(const char*, double)>* progress,
                          const StrokeLayer* behind, BufferPool* pool, float one_sample_px) {
    StrokeLayer out;
    out.width = frame.width, out.height = frame.height;
    out.cutoff = rs.coverage_cutoff;
    const size_t npix = static_cast<size_t>(frame.width) * frame.height;
    out.color = pooled(pool, 3 * npix, 0.0f);
    out.through = pooled(pool, npix, 1.0f);
    if (plan.pigment) out.pigment.assign(4 * npix, 0.0f);
    const PigmentTable* pigments = plan.pigment ? &PigmentTable::shared() : nullptr;
    CanvasWeave weave;
    if (plan.canvas) weave = make_canvas_weave(rs.canvas_thread_px);
    if (plan.trace) {
        out.first.assign(npix, ~0u), out.second.assign(npix, ~0u);
        out.first_weight.assign(npix, 1.0f);
    }
    const int n = rs.samples >= 16 ? 4 : rs.samples >= 4 ? 2 : 1;
    std::vector<uint64_t> tile_fragments(bins.bins.size(), 0);
    std::atomic<size_t> tiles_done{0};
    const size_t tiles = bins.bins.size();
    // Each whole percent of the tiles, once.
    auto tile_done = [&] {
        if (!progress || !*progress) return;
        const size_t d = ++tiles_done;
        if (d * 100 / tiles != (d - 1) * 100 / tiles) (*progress)("paint", double(d) / tiles);
    };
    tbb::parallel_for(size_t{0}, bins.bins.size(), [&](size_t tile) {
        const int tx = static_cast<int>(tile % bins.tiles_x);
        const int ty = static_cast<int>(tile / bins.tiles_x);
        const int px0 = tx * kTile, py0 = ty * kTile;
        const int px1 = std::min(px0 + kTile, frame.width);
        const int py1 = std::min(py0 + kTile, frame.height);
        const std::vector<uint32_t>& bin = bins.bins[tile];
        if (plan.bare_blend) {
            for (uint32_t idx : bin)
                tile_fragments[tile] += paint_bare(
                    set.sprites[idx], sprite_span(set.sprites[idx], px0, py0, px1, py1), out);
            return tile_done();
        }
        // Front to back (the bin's order reversed), until every pixel of the tile is covered:
        // the strokes behind would not show.
        thread_local std::unique_ptr<TileLayer> kept;
        if (!kept) kept = std::make_unique<TileLayer>();
        TileLayer* layer = kept.get();
        layer->reset(px0, py0, px1, py1, rs.coverage_cutoff, plan, pigments != nullptr);
        if (behind) layer->close_covered(*behind);
        float speed_max = 0;
        for (uint32_t idx : bin) speed_max = std::max(speed_max, set.sprites[idx].swap_speed);
        if (rs.order_blend_frames > 0 && speed_max > 0) {
            // The held strokes, kept per thread: 6 x 32 bytes a pixel.
            thread_local std::vector<TileLayer::Held> pool;
            pool.resize(TileLayer::kHeld * kTile * kTile);
            layer->make_soft(0.5f * rs.order_blend_frames, speed_max, pool.data());
        }
        TilePainter painter{shot, set,          plan, rs,       frame,
                            n,    *layer,       out,  pigments, plan.canvas ? &weave : nullptr,
                            n,    one_sample_px};
        for (auto it = bin.rbegin(); it != bin.rend(); ++it) {
            const Sprite& sp = set.sprites[*it];
            layer->range = sp.range;
            if (layer->full(layer->range)) break;
            if (layer->soft) {
                // Whether the next stroke of the tile (and so every later one) lies beyond
                // this one's reach: then it blends with none of them.
                const auto next = std::next(it);
                layer->solo = next == bin.rend() ||
                              !(set.sprites[*next].range <
                                sp.range + layer->window * (sp.swap_speed + layer->speed_max));
            }
            painter.paint(*it);
        }
        painter.finish();
        tile_fragments[tile] = painter.fragments;
        tile_done();
    });
    for (uint64_t f : tile_fragments) out.fragments += f;
    return out;
}

void composite_strokes(const StrokeLayer& strokes, const FramePlan& plan, const RenderSettings& rs,
                       Frame& frame) {
    const bool paint = plan.pigment && !strokes.pigment.empty();
    const PigmentTable* pigments = paint ? &PigmentTable::shared() : nullptr;
    CanvasWeave weave;
    if (plan.canvas) weave = make_canvas_weave(rs.canvas_thread_px);
    tbb::parallel_for(0, frame.height, [&](int y) {
        for (int x = 0; x < frame.width; ++x) {
            const size_t pi = static_cast<size_t>(y) * frame.width + x;
            const float t = strokes.through[pi];
            const float* c = &strokes.color[3 * pi];
            float* px = &frame.rgba[4 * pi];
            // A covered pixel holds no background: what lies under adds at most the cutoff.
            const float under = strokes.covered(pi) ? 0.0f : t;
            Color out;
            if (pigments) {
                // The strokes' paint over what lies under them, mixed as paint: the latents'
                // weights sum to one (a covered pixel's strokes are scaled up to it).
                PigmentLatent z;
                const float* p = &strokes.pigment[4 * pi];
                for (int k = 0; k < 4; ++k) z.c[k] = p[k];
                z.residual = Color(c[0], c[1], c[2]);
                if (under > 0.0f) {
                    const PigmentLatent u = pigments->encode(Color(px[0], px[1], px[2]));
                    for (int k = 0; k < 4; ++k) z.c[k] += under * u.c[k];
                    z.residual += u.residual * under;
                } else if (t < 1.0f) {
                    const float s = 1.0f / (1.0f - t);
                    for (int k = 0; k < 4; ++k) z.c[k] *= s;
                    z.residual *= s;
                }
                out = t < 1.0f ? pigments->decode(z) : Color(px[0], px[1], px[2]);
            } else {
                out = Color(c[0] + under * px[0], c[1] + under * px[1], c[2] + under * px[2]);
            }
            if (plan.canvas) out = canvas_show(out, weave.at(x, y), t, rs.canvas_weave);
            px[0] = out.x, px[1] = out.y, px[2] = out.z;
            px[3] = (1.0f - t) + t * (strokes.covered(pi) ? 1.0f : px[3]);
            if (!plan.aovs) continue;
            frame.alpha[pi] = 1.0f - t;
            // Background: as far as a float goes (finite, as EXR readers expect, and sorting
            // behind everything, unlike 0, which reads as nearest).
            if (!std::isfinite(frame.depth[pi]))
                frame.depth[pi] = std::numeric_limits<float>::max();
        }
    });
}

StrokeLayer paint_stage(const FrameContext& ctx, const SpriteSet& sprites, const TileBins& bins,
                        Frame& frame) {
    StagePhase phase(ctx, "paint", true);
    StrokeLayer strokes = paint_strokes(ctx.shot, sprites, bins, ctx.plan, ctx.render(), frame,
                                        &ctx.settings.progress, nullptr, ctx.settings.buffers,
                                        ctx.render().one_sample_px);
    ctx.report.fragments = strokes.fragments;
    std::string what = std::to_string(strokes.fragments) + " fragments";
    if (const float px = ctx.render().one_sample_px; px > 0) {
        size_t large = 0;
        for (const Sprite& sp : sprites.sprites)
            large += sp.kind != SpriteKind::kGraftal && std::min(sp.half_w, sp.half_l) >= px;
        what += "; " + std::to_string(large) + " strokes at least " + std::to_string(int(2 * px)) +
                " px across at one sample, the feather filtered";
    }
    phase.done("strokes front to back, tiles in parallel, each until it is covered", what);
    return strokes;
}

void give_back(StrokeLayer& layer, BufferPool* pool) {
    if (!pool) return;
    pool->give(std::move(layer.color));
    pool->give(std::move(layer.through));
}

void composite_stage(const FrameContext& ctx, const StrokeLayer& strokes, Frame& frame) {
    StagePhase phase(ctx, "composite");
    composite_strokes(strokes, ctx.plan, ctx.render(), frame);
    phase.done("the strokes over what lies under them");
}

}  // namespace pleinair
