// SeenMemo: one array of answers per lattice time and item, grown on first use.
#include "pipeline/frame/seen_memo.h"

#include <algorithm>

#include "pipeline/frame/frame_view.h"
#include "pipeline/shot/shot.h"

namespace pleinair {

void SeenMemo::begin_frame(const Shot& shot, const SeenWindow& window, const RenderSettings& rs) {
    const int w = window.cameras.empty() ? 0 : window.cameras.front().width;
    const int h = window.cameras.empty() ? 0 : window.cameras.front().height;
    if (shot_ != &shot || stroke_perspective_ != rs.stroke_perspective ||
        min_stroke_px_ != rs.min_stroke_px || width_ != w || height_ != h)
        times_.clear();
    shot_ = &shot, stroke_perspective_ = rs.stroke_perspective;
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
