// build_occlusion_map: a ray a texel, the 3 x 3 maximum, then the pyramid; and the two lookups.
#include "pipeline/frame/occlusion_map.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <limits>

#include "pipeline/shot/rays.h"

namespace pleinair {

namespace {

constexpr float kNone = std::numeric_limits<float>::infinity();

// A point at depth z is behind a surface at depth d by more than a thousandth of d: the
// surfaces' own strokes, lifted off them, stay in front of the depth their texel's ray met.
bool behind(double z, float d) { return z > static_cast<double>(d) * (1.0 + 1e-3); }

// The ray through each texel's centre: the view depth of its nearest hit, or kNone.
std::vector<float> cast_texels(const RayScene& rays, const Camera& cam, int w, int h, int k) {
    std::vector<float> depth(static_cast<size_t>(w) * h, kNone);
    tbb::parallel_for(0, h, [&](int ty) {
        FlushDenormals ftz;  // Embree's modes, while this task traces
        for (int tx = 0; tx < w; ++tx) {
            const double x = std::min((tx + 0.5) * k, cam.width - 0.5);
            const double y = std::min((ty + 0.5) * k, cam.height - 0.5);
            const glm::dvec3 dir = ray_direction(cam, x, y);
            const RayHit hit = rays.intersect(cam.eye, glm::vec3(dir));
            if (hit.hit && std::isfinite(hit.t))
                depth[static_cast<size_t>(ty) * w + tx] =
                    static_cast<float>(hit.t * glm::dot(dir, cam.forward));
        }
    });
    return depth;
}

// Each texel's maximum and minimum over itself and its eight neighbours, those beyond the edge
// counting as no surface (the maximum) or left out (the minimum).
void dilate(const std::vector<float>& d, int w, int h, std::vector<float>& far,
            std::vector<float>& near) {
    far.assign(d.size(), kNone);
    near.assign(d.size(), kNone);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            float lo = kNone;
            for (int j = std::max(0, y - 1); j <= std::min(h - 1, y + 1); ++j)
                for (int i = std::max(0, x - 1); i <= std::min(w - 1, x + 1); ++i)
                    lo = std::min(lo, d[static_cast<size_t>(j) * w + i]);
            near[static_cast<size_t>(y) * w + x] = lo;
            if (x == 0 || y == 0 || x == w - 1 || y == h - 1) continue;
            float hi = 0;
            for (int j = -1; j <= 1; ++j)
                for (int i = -1; i <= 1; ++i)
                    hi = std::max(hi, d[static_cast<size_t>(y + j) * w + (x + i)]);
            far[static_cast<size_t>(y) * w + x] = hi;
        }
}

}  // namespace

int occlusion_texel_px(int image_width) { return std::max(2, (image_width + 959) / 480); }

uint64_t occlusion_map_rays(const Camera& c) {
    const int k = occlusion_texel_px(c.width);
    return static_cast<uint64_t>((c.width + k - 1) / k) *
           static_cast<uint64_t>((c.height + k - 1) / k);
}

OcclusionMap build_occlusion_map(const RayScene& rays, const Camera& camera) {
    OcclusionMap m;
    m.camera = camera;
    m.texel_px = occlusion_texel_px(camera.width);
    m.width = (camera.width + m.texel_px - 1) / m.texel_px;
    m.height = (camera.height + m.texel_px - 1) / m.texel_px;
    m.rays = static_cast<uint64_t>(m.width) * m.height;
    m.levels.emplace_back();
    dilate(cast_texels(rays, camera, m.width, m.height, m.texel_px), m.width, m.height,
           m.levels.back(), m.nearest);
    m.level_width.push_back(m.width);
    m.level_height.push_back(m.height);
    while (m.level_width.back() > 1 || m.level_height.back() > 1) {
        const int pw = m.level_width.back(), ph = m.level_height.back();
        const int w = (pw + 1) / 2, h = (ph + 1) / 2;
        const std::vector<float>& p = m.levels.back();
        std::vector<float> l(static_cast<size_t>(w) * h, 0.0f);
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                float v = 0;
                for (int j = 0; j < 2; ++j)
                    for (int i = 0; i < 2; ++i) {
                        const int px = std::min(2 * x + i, pw - 1),
                                  py = std::min(2 * y + j, ph - 1);
                        v = std::max(v, p[static_cast<size_t>(py) * pw + px]);
                    }
                l[static_cast<size_t>(y) * w + x] = v;
            }
        m.levels.push_back(std::move(l));
        m.level_width.push_back(w);
        m.level_height.push_back(h);
    }
    return m;
}

MapAnswer occluded_at(const OcclusionMap& m, double x, double y, double z) {
    if (!(x >= 0 && y >= 0 && x < m.camera.width && y < m.camera.height)) return MapAnswer::kUnsure;
    const int tx = std::min(static_cast<int>(x) / m.texel_px, m.width - 1);
    const int ty = std::min(static_cast<int>(y) / m.texel_px, m.height - 1);
    const size_t t = static_cast<size_t>(ty) * m.width + tx;
    if (behind(z, m.levels[0][t])) return MapAnswer::kHidden;
    // In front of every surface around it by as much: no surface between it and the eye, but
    // one thinner than a texel that every ray missed.
    if (z * (1.0 + 1e-3) < static_cast<double>(m.nearest[t])) return MapAnswer::kSeen;
    return MapAnswer::kUnsure;
}

bool occluded_box(const OcclusionMap& m, double x0, double y0, double x1, double y1, double z) {
    if (!(x0 >= 0 && y0 >= 0 && x1 < m.camera.width && y1 < m.camera.height && x0 <= x1 &&
          y0 <= y1))
        return false;
    int tx0 = std::min(static_cast<int>(x0) / m.texel_px, m.width - 1);
    int ty0 = std::min(static_cast<int>(y0) / m.texel_px, m.height - 1);
    int tx1 = std::min(static_cast<int>(x1) / m.texel_px, m.width - 1);
    int ty1 = std::min(static_cast<int>(y1) / m.texel_px, m.height - 1);
    // The finest level at which the rectangle spans at most eight texels each way: at most 64
    // reads, of blocks that reach past it by less than one block (at two texels a rectangle
    // could read four times its size where the grid's steps fall badly, and miss a wall it
    // lies within).
    size_t level = 0;
    while (level + 1 < m.levels.size() && (tx1 - tx0 > 7 || ty1 - ty0 > 7))
        tx0 >>= 1, ty0 >>= 1, tx1 >>= 1, ty1 >>= 1, ++level;
    const std::vector<float>& l = m.levels[level];
    const int w = m.level_width[level];
    float d = 0;
    for (int y = ty0; y <= ty1; ++y)
        for (int x = tx0; x <= tx1; ++x) d = std::max(d, l[static_cast<size_t>(y) * w + x]);
    return behind(z, d);
}

}  // namespace pleinair
