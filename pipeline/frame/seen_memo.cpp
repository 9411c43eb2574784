// occlusion_maps and SeenMemo: a map per camera, kept while a later frame's window holds the
// same camera.
#include "pipeline/frame/seen_memo.h"

#include <algorithm>

#include "pipeline/frame/frame_view.h"
#include "pipeline/shot/shot.h"

namespace pleinair {

namespace {

// The cameras whose maps a frame reads.
std::vector<Camera> map_cameras(const SeenWindow* window, const Camera& frame_camera) {
    if (window && !window->cameras.empty()) return window->cameras;
    return {frame_camera};
}

// A map serves another frame whose camera is the same in every bit a ray reads.
bool same_camera(const Camera& a, const Camera& b) {
    return a.eye == b.eye && a.forward == b.forward && a.right == b.right && a.up == b.up &&
           a.focal_px == b.focal_px && a.width == b.width && a.height == b.height;
}

}  // namespace

std::vector<OcclusionMap> occlusion_maps(const Shot& shot, const SeenWindow* window,
                                         const Camera& frame_camera, uint64_t& rays) {
    std::vector<OcclusionMap> out;
    if (!shot.view_rays) return out;
    for (const Camera& cam : map_cameras(window, frame_camera)) {
        out.push_back(build_occlusion_map(*shot.view_rays, cam));
        rays += out.back().rays;
    }
    return out;
}

const std::vector<OcclusionMap>& SeenMemo::maps(const Shot& shot, const SeenWindow* window,
                                                const Camera& frame_camera, uint64_t& rays) {
    if (shot_ != &shot) maps_.clear();
    shot_ = &shot;
    std::vector<OcclusionMap> next;
    if (shot.view_rays)
        for (const Camera& cam : map_cameras(window, frame_camera)) {
            auto it = std::find_if(maps_.begin(), maps_.end(), [&](const OcclusionMap& m) {
                return same_camera(m.camera, cam);
            });
            if (it != maps_.end()) {
                next.push_back(std::move(*it));
                maps_.erase(it);
                continue;
            }
            next.push_back(build_occlusion_map(*shot.view_rays, cam));
            rays += next.back().rays;
        }
    maps_ = std::move(next);
    return maps_;
}

void SeenMemo::begin_frame(const Shot& shot, const SeenWindow& window, const RenderSettings& rs) {
    const int w = window.cameras.empty() ? 0 : window.cameras.front().width;
    const int h = window.cameras.empty() ? 0 : window.cameras.front().height;
    if (answers_shot_ != &shot || stroke_perspective_ != rs.stroke_perspective ||
        min_stroke_px_ != rs.min_stroke_px || width_ != w || height_ != h)
        times_.clear();
    answers_shot_ = &shot, stroke_perspective_ = rs.stroke_perspective;
    min_stroke_px_ = rs.min_stroke_px, width_ = w, height_ = h;
    std::vector<Time> kept;
    for (const int64_t m : window.lattice) {
        auto it = std::find_if(times_.begin(), times_.end(),
                               [&](const Time& t) { return t.lattice == m; });
        Time t;
        if (it != times_.end()) t = std::move(*it);
        t.lattice = m;
        t.items.resize(shot.item_count());
        kept.push_back(std::move(t));
    }
    times_ = std::move(kept);
}

uint8_t* SeenMemo::answers(size_t k, size_t item, size_t particles) {
    std::vector<uint8_t>& a = times_[k].items[item];
    if (a.size() != particles) a.assign(particles, kUnknown);
    return a.data();
}

}  // namespace pleinair
