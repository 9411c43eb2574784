// contact_look.
#include "pipeline/bench/contact_look.h"

#include <algorithm>
#include <cmath>

#include "pipeline/frame/frame_image.h"
#include "pipeline/frame/frame_view.h"
#include "pipeline/input/camera.h"
#include "pipeline/shot/shot.h"

namespace pleinair {

namespace {

// Mean L* of the ground pixels in rows [y0, y1] whose distance from column x lies in [a, b].
bool band_mean(const std::vector<float>& l, int w, int h, const std::vector<float>& id,
               const std::vector<uint8_t>& sky, const TreeBase& t, int y0, int y1, double a,
               double b, double& mean) {
    double sum = 0;
    int n = 0;
    for (int y = std::max(0, y0); y <= std::min(h - 1, y1); ++y)
        for (int side : {-1, 1})
            for (int x = static_cast<int>(std::lround(t.x + side * a));
                 side > 0 ? x <= std::lround(t.x + b) : x >= std::lround(t.x - b); x += side) {
                if (x < 0 || x >= w) continue;
                const size_t i = static_cast<size_t>(y) * w + x;
                if (sky[i] || (!id.empty() && id[i] == t.object_id)) continue;
                sum += l[i], ++n;
            }
    if (n < kContactMinPixels) return false;
    mean = sum / n;
    return true;
}

}  // namespace

std::vector<TreeBase> tree_bases(const Shot& shot, const FrameView& view, const Frame& f) {
    std::vector<TreeBase> out;
    const Camera& cam = view.camera;
    for (size_t i = 0; i < shot.placements.size(); ++i) {
        const Projection p = project(cam, shot.placements[i].position);
        if (!p.in_front || !(p.depth > 0.0f)) continue;
        const int x = static_cast<int>(p.x), y = static_cast<int>(p.y);
        if (p.x < 0 || p.y < 0 || x >= f.width || y >= f.height) continue;
        TreeBase t;
        t.x = p.x, t.y = p.y;
        t.px_per_m = static_cast<float>(cam.focal_px / p.depth);
        t.object_id = static_cast<float>((*shot.trees)[i].id + 1);  // as its strokes carry it
        if (t.px_per_m < kContactMinScale) continue;
        if (f.has_aovs) {
            const size_t k = static_cast<size_t>(y) * f.width + x;
            if (f.object_id[k] != t.object_id && f.depth[k] < 0.9f * p.depth) continue;
        }
        out.push_back(t);
    }
    return out;
}

ContactLook contact_look(const std::vector<float>& l, int w, int h,
                         const std::vector<float>& object_id, const std::vector<uint8_t>& sky,
                         const std::vector<TreeBase>& bases) {
    ContactLook out;
    std::vector<double> drops;
    for (const TreeBase& t : bases) {
        if (!(t.px_per_m > 0.0f) || !std::isfinite(t.x) || !std::isfinite(t.y)) continue;
        const double m = t.px_per_m;
        const int y0 = static_cast<int>(std::floor(t.y - kContactRows * m));
        const int y1 = static_cast<int>(std::ceil(t.y + kContactRows * m));
        if (y1 < 0 || y0 >= h) continue;
        double near = 0, far = 0;
        if (!band_mean(l, w, h, object_id, sky, t, y0, y1, kContactNear[0] * m, kContactNear[1] * m,
                       near) ||
            !band_mean(l, w, h, object_id, sky, t, y0, y1, kContactFar[0] * m, kContactFar[1] * m,
                       far))
            continue;
        drops.push_back(far - near);
    }
    out.bases = static_cast<int>(drops.size());
    if (drops.empty()) return out;
    std::sort(drops.begin(), drops.end());
    const size_t k = drops.size() / 2;
    out.median_drop = drops.size() % 2 ? drops[k] : 0.5 * (drops[k - 1] + drops[k]);
    out.standing_share =
        static_cast<double>(std::count_if(drops.begin(), drops.end(),
                                          [](double d) { return d >= kContactStanding; })) /
        static_cast<double>(drops.size());
    return out;
}

}  // namespace pleinair
