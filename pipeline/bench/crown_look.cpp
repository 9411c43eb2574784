// tree_pixels, measure_crowns and median_crown.
#include "pipeline/bench/crown_look.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <map>

#include "pipeline/bench/tree_form.h"
#include "pipeline/frame/frame_view.h"
#include "pipeline/input/camera.h"
#include "pipeline/shot/shot.h"

namespace pleinair {

TreePixels tree_pixels(const Shot& shot, const FrameView& view, const Frame& f) {
    const size_t n = static_cast<size_t>(f.width) * f.height;
    TreePixels t{std::vector<uint32_t>(n, 0), Mask(n, 0)};
    if (!f.has_aovs) return t;
    const Camera& cam = view.camera;
    const uint32_t bark_end = 2 * static_cast<uint32_t>(shot.scene.families.size());
    tbb::parallel_for(0, f.height, [&](int y) {
        FlushDenormals ftz;
        for (int x = 0; x < f.width; ++x) {
            const size_t i = static_cast<size_t>(y) * f.width + x;
            const float id = f.object_id[i];
            if (!(id >= 1.0f && id < 65536.0f)) continue;
            t.tree[i] = static_cast<uint32_t>(id);
            if (!shot.view_rays) continue;
            const glm::dvec3 d = ray_direction(cam, x + 0.5, y + 0.5);
            const RayHit h = shot.view_rays->intersect(cam.eye, glm::vec3(d));
            if (!h.hit) continue;
            const ViewSurface& vs = shot.view_surfaces[h.geometry];
            const uint32_t m = vs.material.index;
            if (vs.terrain || m >= bark_end || m % 2 == 0) continue;
            // The trunk's depth along the view against the nearest stroke's: a leaf in front
            // hides it. 2% for the strokes lifted off their surface.
            const double depth = static_cast<double>(h.t) * glm::dot(d, cam.forward);
            t.bark[i] = depth <= 1.02 * static_cast<double>(f.depth[i]) + 0.05;
        }
    });
    return t;
}

namespace {

struct Box {
    int x0 = 1 << 30, y0 = 1 << 30, x1 = -1, y1 = -1;
    size_t pixels = 0;
};

CrownLook measure_crown(const TreePixels& t, uint32_t id, const Box& b, const Mask& sky, int w) {
    const int extent = std::max(b.x1 - b.x0 + 1, b.y1 - b.y0 + 1);
    const int r = static_cast<int>(std::lround(kOutlineRadius * extent));
    // The tree's box, padded so the closing and the outside's flood have room.
    const int pad = r + 1, cx = b.x0 - pad, cy = b.y0 - pad;
    const int cw = b.x1 - b.x0 + 1 + 2 * pad, ch = b.y1 - b.y0 + 1 + 2 * pad;
    Mask own(static_cast<size_t>(cw) * ch, 0);
    for (int y = b.y0; y <= b.y1; ++y)
        for (int x = b.x0; x <= b.x1; ++x)
            own[static_cast<size_t>(y - cy) * cw + (x - cx)] =
                t.tree[static_cast<size_t>(y) * w + x] == id;
    const Mask shut = outline(own, cw, ch, r);
    size_t area = 0, open = 0, bark = 0;
    for (int y = 0; y < ch; ++y)
        for (int x = 0; x < cw; ++x) {
            const size_t c = static_cast<size_t>(y) * cw + x;
            if (!shut[c]) continue;
            ++area;
            // Inside the outline lies inside the tree's box, so inside the frame.
            const size_t i = static_cast<size_t>(y + cy) * w + (x + cx);
            open += sky[i] != 0;
            bark += own[c] && t.bark[i];
        }
    CrownLook c;
    c.pixels = b.pixels;
    c.area = area;
    if (area == 0) return c;
    const double a = static_cast<double>(area);
    c.sky = static_cast<double>(open) / a;
    c.bark = static_cast<double>(bark) / a;
    c.edge = static_cast<double>(boundary_length(outline(own, cw, ch, 0), cw, ch)) / std::sqrt(a);
    return c;
}

}  // namespace

std::vector<CrownLook> measure_crowns(const TreePixels& t, const Mask& sky, int w, int h,
                                      size_t min_pixels) {
    std::map<uint32_t, Box> boxes;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const uint32_t id = t.tree[static_cast<size_t>(y) * w + x];
            if (id == 0) continue;
            Box& b = boxes[id];
            b.x0 = std::min(b.x0, x), b.y0 = std::min(b.y0, y);
            b.x1 = std::max(b.x1, x), b.y1 = std::max(b.y1, y);
            ++b.pixels;
        }
    std::vector<CrownLook> out;
    for (const auto& [id, b] : boxes)
        if (b.pixels >= min_pixels) out.push_back(measure_crown(t, id, b, sky, w));
    return out;
}

CrownLook median_crown(std::vector<CrownLook> crowns) {
    CrownLook m;
    m.pixels = crowns.size();
    if (crowns.empty()) return m;
    auto median = [&](double CrownLook::*field) {
        std::vector<double> v;
        for (const CrownLook& c : crowns) v.push_back(c.*field);
        std::sort(v.begin(), v.end());
        const size_t k = v.size() / 2;
        return v.size() % 2 ? v[k] : 0.5 * (v[k - 1] + v[k]);
    };
    m.sky = median(&CrownLook::sky), m.edge = median(&CrownLook::edge);
    m.bark = median(&CrownLook::bark);
    return m;
}

CrownLook pooled_crown(const std::vector<CrownLook>& crowns) {
    CrownLook m;
    m.pixels = crowns.size();
    double area = 0, sky = 0, bark = 0, edge = 0;
    for (const CrownLook& c : crowns) {
        const double a = static_cast<double>(c.area);
        area += a, sky += c.sky * a, bark += c.bark * a, edge += c.edge * a;
    }
    if (area == 0) return m;
    m.area = static_cast<size_t>(area);
    m.sky = sky / area, m.bark = bark / area, m.edge = edge / area;
    return m;
}

}  // namespace pleinair
