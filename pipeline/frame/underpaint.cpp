// underpaint_color and paint_underpainting: camera rays at a fraction of the resolution, one
// flat palette colour per hit (water mirroring), interpolated up and composited over the
// background.
#include "pipeline/frame/underpaint.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <glm/geometric.hpp>

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
                       const MirrorContext& mirrors) {
    SurfaceHit s = surface_hit(shot, view, plan, rs, sun_rays, h, world, n, dir);
    if (plan.reflections && s.water)
        mirror(mirrors, RayOrigin{world, s.n, true, shot.surface_lift}, &s.n, 1, s.n, dir, s.k);
    return finish_color(s.k, s.base);
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

Underpainting trace_underpainting(const Shot& shot, const FrameView& view, const FramePlan& plan,
                                  const RenderSettings& rs, const RayScene* sun_rays,
                                  const StrokeLayer& strokes, uint64_t& rays) {
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
    for (uint8_t n : need) rays += n;
    // Once for the frame, not per water cell.
    const MirrorContext mirrors = mirror_context(shot, view, plan, rs, sun_rays);
    tbb::parallel_for(0, u.h, [&](int j) {
        FlushDenormals ftz;
        for (int i = 0; i < u.w; ++i) {
            if (!need[static_cast<size_t>(j) * u.w + i]) continue;
            const glm::dvec3 dir = ray_direction(cam, (i + 0.5) * u.fx, (j + 0.5) * u.fy);
            const RayHit h = shot.view_rays->intersect(cam.eye, glm::vec3(dir));
            if (!h.hit) continue;
            const glm::dvec3 world = cam.eye + dir * static_cast<double>(h.t);
            const size_t c = static_cast<size_t>(j) * u.w + i;
            u.color[c] =
                underpaint_color(shot, view, plan, rs, sun_rays, h, world, h.normal, dir, mirrors);
            u.cover[c] = 1.0f;
            u.depth[c] = static_cast<float>(glm::dot(world - cam.eye, cam.forward));
        }
    });
    return u;
}

}  // namespace

uint64_t paint_underpainting(const Shot& shot, const FrameView& view, const FramePlan& plan,
                             const RenderSettings& rs, const RayScene* sun_rays,
                             const StrokeLayer& strokes, Frame& frame) {
    uint64_t rays = 0;
    const Underpainting u = trace_underpainting(shot, view, plan, rs, sun_rays, strokes, rays);
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
    ctx.report.underpaint_rays =
        paint_underpainting(ctx.shot, ctx.view, ctx.plan, ctx.render(), sun_rays, strokes, frame);
    phase.done("flat palette colour where the camera sees a surface and the strokes leave gaps",
               std::to_string(ctx.report.underpaint_rays) + " camera rays");
}

}  // namespace pleinair
