// underpaint_color and paint_underpainting: camera rays at a fraction of the resolution, one
// flat palette colour per hit (water mirroring), interpolated up and composited over the
// background.
#include "pipeline/frame/underpaint.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <utility>

#include "pipeline/frame/composite.h"
#include "pipeline/frame/reflection.h"
#include "pipeline/frame/surface_hit.h"
#include "pipeline/shot/shot.h"

namespace pleinair {

namespace {

// The low-resolution underpainting: premultiplied colour, coverage and depth per cell.
struct Underpainting {
    int w = 0, h = 0;
    double fx = 1, fy = 1;  // image pixels per cell
    std::vector<Color> color;
    std::vector<float> cover, depth;

    // The cells a pixel interpolates from, and its weights: one rule for what is traced and
    // what is read back.
    struct Lerp {
        int i0, i1, j0, j1;
        float wx, wy;
    };
    float cell_y(int y) const {
        return std::clamp(static_cast<float>((y + 0.5) / fy - 0.5), 0.0f, h - 1.0f);
    }
    Lerp at(int x, float sy) const {
        const float sx = std::clamp(static_cast<float>((x + 0.5) / fx - 0.5), 0.0f, w - 1.0f);
        Lerp l;
        l.j0 = static_cast<int>(sy), l.j1 = std::min(l.j0 + 1, h - 1), l.wy = sy - l.j0;
        l.i0 = static_cast<int>(sx), l.i1 = std::min(l.i0 + 1, w - 1), l.wx = sx - l.i0;
        return l;
    }
    size_t cell(int i, int j) const { return static_cast<size_t>(j) * w + i; }
};

}  // namespace

Color underpaint_color(const Shot& shot, const FrameView& view, const FramePlan& plan,
                       const RenderSettings& rs, const RayScene* sun_rays, const RayHit& h,
                       const glm::dvec3& world, glm::vec3 n, const glm::dvec3& dir,
                       const MirrorContext& mirrors, SurfaceHit* seen) {
    SurfaceHit s = surface_hit(shot, view, plan, rs, sun_rays, h, world, n, dir);
    if (plan.reflections && s.water)
        mirror(mirrors, RayOrigin{world, s.n, true, shot.surface_lift}, &s.n, 1, s.n, dir,
               glm::length(world - view.camera.eye), s.k);
    if (seen) *seen = s;
    // The lay-in's own tone under a dry surface's colour, before finish_color's atmosphere, so a
    // far surface's underpaint still goes into the haze; water keeps its mirror.
    Color base = s.base;
    if (rs.underpaint_tone_amount > 0.0f && !s.water)
        base = mix(base, srgb_to_linear(Color(rs.underpaint_tone)),
                   std::clamp(rs.underpaint_tone_amount, 0.0f, 1.0f));
    return finish_color(s.k, base);
}

namespace {

// Which cells some open pixel interpolates from (every cell when `all`). Rows in parallel:
// neighbouring rows mark the same cells, with the same value, through atomic stores.
std::vector<uint8_t> needed_cells(const Underpainting& u, const StrokeLayer& strokes, bool all) {
    std::vector<uint8_t> need(static_cast<size_t>(u.w) * u.h, all ? 1 : 0);
    if (all) return need;
    tbb::parallel_for(0, strokes.height, [&](int y) {
        const float sy = u.cell_y(y);
        for (int x = 0; x < strokes.width; ++x) {
            if (strokes.covered(static_cast<size_t>(y) * strokes.width + x)) continue;
            const Underpainting::Lerp l = u.at(x, sy);
            for (int j : {l.j0, l.j1})
                for (int i : {l.i0, l.i1}) {
                    std::atomic_ref<uint8_t> cell(need[u.cell(i, j)]);
                    if (!cell.load(std::memory_order_relaxed))
                        cell.store(1, std::memory_order_relaxed);
                }
        }
    });
    return need;
}

// The two rounds of shading. Every cell under an open pixel casts its camera ray, so every
// surface, however thin, is found; but a cell's shading (its sun's shadow ray, water's mirror)
// is not always traced. A cell is "coarse" along an axis at an even index or the last: the
// cells coarse both ways are shaded first, and each other cell lies between two or four of them
// (its bracket). It takes their mean colour when they and it see the same surface of the same
// material, all dry or all water, at nearly one depth (within kDepthRatio of its own: no
// silhouette between), and the bracket is in nearly one sun (within kSunStep: no shadow's edge)
// and of nearly one colour (within kColorStep a channel: no mirrored edge); elsewhere it is
// shaded. A shading is most of a cell's cost: a water cell's mirror takes about 10 us of a core
// (its ray crosses the far bank's leaf casters).
struct UnderpaintCells {
    static constexpr float kSunStep = 0.02f;
    static constexpr float kDepthRatio = 1.05f;
    static constexpr float kColorStep = 0.01f;
    struct Seen {
        bool hit = false, water = false;
        uint32_t geometry = 0;
        MaterialId material;
        float sun = 1.0f;
    };
    static bool coarse(int i, int n) { return i % 2 == 0 || i == n - 1; }
    // The shaded cells a cell along one axis lies between (itself when coarse).
    static std::pair<int, int> bracket(int i, int n) {
        return coarse(i, n) ? std::pair{i, i} : std::pair{i - 1, i + 1};
    }
    // Whether the corners' mean may stand for a cell that sees `own` at depth `at`.
    static bool alike(const Seen& own, float at, const Seen* const s[4], const float depth[4],
                      const Color color[4]) {
        float sun_lo = s[0]->sun, sun_hi = sun_lo;
        Color c_lo = color[0], c_hi = c_lo;
        for (int k = 0; k < 4; ++k) {
            if (!s[k]->hit || s[k]->water != own.water || s[k]->geometry != own.geometry ||
                !(s[k]->material == own.material) || !(depth[k] <= at * kDepthRatio) ||
                !(at <= depth[k] * kDepthRatio))
                return false;
            sun_lo = std::min(sun_lo, s[k]->sun), sun_hi = std::max(sun_hi, s[k]->sun);
            c_lo = glm::min(c_lo, color[k]), c_hi = glm::max(c_hi, color[k]);
        }
        const Color spread = c_hi - c_lo;
        return sun_hi - sun_lo <= kSunStep &&
               std::max({spread.x, spread.y, spread.z}) <= kColorStep;
    }
};

// Which cells the first round traces: the corners of every needed cell's bracket.
std::vector<uint8_t> first_round(const Underpainting& u, const std::vector<uint8_t>& need) {
    std::vector<uint8_t> first(need.size(), 0);
    tbb::parallel_for(0, u.h, [&](int j) {
        const auto [j0, j1] = UnderpaintCells::bracket(j, u.h);
        for (int i = 0; i < u.w; ++i) {
            if (!need[u.cell(i, j)]) continue;
            const auto [i0, i1] = UnderpaintCells::bracket(i, u.w);
            for (int jj : {j0, j1})
                for (int ii : {i0, i1}) {
                    std::atomic_ref<uint8_t> cell(first[u.cell(ii, jj)]);
                    if (!cell.load(std::memory_order_relaxed))
                        cell.store(1, std::memory_order_relaxed);
                }
        }
    });
    return first;
}

Underpainting trace_underpainting(const Shot& shot, const FrameView& view, const FramePlan& plan,
                                  const RenderSettings& rs, const RayScene* sun_rays,
                                  const StrokeLayer& strokes, bool shade_every_cell,
                                  UnderpaintRays& rays) {
    const Camera& cam = view.camera;
    Underpainting u;
    u.w = std::max(1, static_cast<int>(std::ceil(cam.width * rs.underpaint_scale)));
    u.h = std::max(1, static_cast<int>(std::ceil(cam.height * rs.underpaint_scale)));
    u.fx = static_cast<double>(cam.width) / u.w;
    u.fy = static_cast<double>(cam.height) / u.h;
    u.color.assign(static_cast<size_t>(u.w) * u.h, Color(0.0f));
    u.cover.assign(u.color.size(), 0.0f);
    u.depth.assign(u.color.size(), 0.0f);
    const std::vector<uint8_t> need = needed_cells(u, strokes, plan.aovs);
    const std::vector<uint8_t> first = first_round(u, need);
    std::vector<UnderpaintCells::Seen> seen(u.color.size());
    // Once for the frame, not per water cell.
    const MirrorContext mirrors = mirror_context(shot, view, plan, rs, sun_rays);
    std::atomic<uint64_t> cast{0}, shaded{0};
    // The camera ray of cell c, its depth and what it sees (shaded or not).
    auto look = [&](int i, int j, glm::dvec3& dir, glm::dvec3& world) {
        dir = ray_direction(cam, (i + 0.5) * u.fx, (j + 0.5) * u.fy);
        const RayHit h = shot.view_rays->intersect(cam.eye, glm::vec3(dir));
        if (!h.hit) return h;
        world = cam.eye + dir * static_cast<double>(h.t);
        const size_t c = u.cell(i, j);
        u.cover[c] = 1.0f;
        u.depth[c] = static_cast<float>(glm::dot(world - cam.eye, cam.forward));
        return h;
    };
    auto shade = [&](size_t c, const RayHit& h, const glm::dvec3& world, const glm::dvec3& dir) {
        SurfaceHit s;
        u.color[c] =
            underpaint_color(shot, view, plan, rs, sun_rays, h, world, h.normal, dir, mirrors, &s);
        seen[c] = {true, s.water, h.geometry, s.material, s.sun};
    };
    tbb::parallel_for(0, u.h, [&](int j) {
        FlushDenormals ftz;
        uint64_t n = 0, m = 0;
        for (int i = 0; i < u.w; ++i) {
            if (!first[u.cell(i, j)]) continue;
            glm::dvec3 dir, world;
            const RayHit h = look(i, j, dir, world);
            ++n;
            if (h.hit) shade(u.cell(i, j), h, world, dir), ++m;
        }
        cast += n, shaded += m;
    });
    // The second round reads only first-round cells and writes only the others.
    tbb::parallel_for(0, u.h, [&](int j) {
        FlushDenormals ftz;
        uint64_t n = 0, m = 0;
        const auto [j0, j1] = UnderpaintCells::bracket(j, u.h);
        for (int i = 0; i < u.w; ++i) {
            const size_t c = u.cell(i, j);
            if (!need[c] || first[c]) continue;
            glm::dvec3 dir, world;
            const RayHit h = look(i, j, dir, world);
            ++n;
            if (!h.hit) continue;
            const auto [i0, i1] = UnderpaintCells::bracket(i, u.w);
            const size_t k[4] = {u.cell(i0, j0), u.cell(i1, j0), u.cell(i0, j1), u.cell(i1, j1)};
            const UnderpaintCells::Seen* const s[4] = {&seen[k[0]], &seen[k[1]], &seen[k[2]],
                                                       &seen[k[3]]};
            const float d[4] = {u.depth[k[0]], u.depth[k[1]], u.depth[k[2]], u.depth[k[3]]};
            const Color col[4] = {u.color[k[0]], u.color[k[1]], u.color[k[2]], u.color[k[3]]};
            UnderpaintCells::Seen own{true, false, h.geometry, {}, 1.0f};
            own.material = surface_material(shot, h, world, own.water);
            if (!shade_every_cell && UnderpaintCells::alike(own, u.depth[c], s, d, col))
                // The mean of the four (two when the cell is coarse along one axis: each twice).
                u.color[c] = 0.25f * (col[0] + col[1] + col[2] + col[3]);
            else
                shade(c, h, world, dir), ++m;
        }
        cast += n, shaded += m;
    });
    rays.camera += cast.load();
    rays.shaded += shaded.load();
    return u;
}

}  // namespace

UnderpaintRays paint_underpainting(const Shot& shot, const FrameView& view, const FramePlan& plan,
                                   const RenderSettings& rs, const RayScene* sun_rays,
                                   const StrokeLayer& strokes, Frame& frame,
                                   bool shade_every_cell) {
    UnderpaintRays rays;
    const Underpainting u =
        trace_underpainting(shot, view, plan, rs, sun_rays, strokes, shade_every_cell, rays);
    const int width = frame.width;
    tbb::parallel_for(0, frame.height, [&](int y) {
        const float sy = u.cell_y(y);
        for (int x = 0; x < width; ++x) {
            const size_t pi = static_cast<size_t>(y) * width + x;
            const bool covered = strokes.covered(pi);
            if (covered && !plan.aovs) continue;
            const Underpainting::Lerp l = u.at(x, sy);
            const float wx = l.wx, wy = l.wy;
            const size_t a = u.cell(l.i0, l.j0), b = u.cell(l.i1, l.j0), c = u.cell(l.i0, l.j1),
                         d = u.cell(l.i1, l.j1);
            auto lerp = [](float p, float q, float t) { return p + (q - p) * t; };
            const float cov =
                lerp(lerp(u.cover[a], u.cover[b], wx), lerp(u.cover[c], u.cover[d], wx), wy);
            if (!(cov > 0.0f)) continue;
            if (!covered) {
                const Color col =
                    mix(mix(u.color[a], u.color[b], wx), mix(u.color[c], u.color[d], wx), wy);
                float* px = &frame.rgba[4 * pi];
                // Both premultiplied: the underpainting over the background.
                px[0] = col.x + px[0] * (1.0f - cov);
                px[1] = col.y + px[1] * (1.0f - cov);
                px[2] = col.z + px[2] * (1.0f - cov);
            }
            // Its depth where no stroke over half opaque gave one.
            if (plan.aovs && cov >= 0.5f && frame.object_id[pi] == 0.0f) {
                const size_t nearest = u.cell(wx < 0.5f ? l.i0 : l.i1, wy < 0.5f ? l.j0 : l.j1);
                frame.depth[pi] = u.cover[nearest] > 0 ? u.depth[nearest] : u.depth[a];
            }
        }
    });
    return rays;
}

void underpaint_stage(const FrameContext& ctx, const RayScene* sun_rays, const StrokeLayer& strokes,
                      Frame& frame) {
    StagePhase phase(ctx, "underpaint", true);
    const UnderpaintRays rays =
        paint_underpainting(ctx.shot, ctx.view, ctx.plan, ctx.render(), sun_rays, strokes, frame);
    ctx.report.underpaint_rays = rays.camera;
    phase.done("flat palette colour where the camera sees a surface and the strokes leave gaps",
               std::to_string(rays.camera) + " camera rays; " + std::to_string(rays.shaded) +
                   " cells shaded, the others their neighbours' mean");
}

}  // namespace pleinair
