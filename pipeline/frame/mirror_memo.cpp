// MirrorMemo: two lattice times' mirrors per particle of the land chunks that hold water.
#include "pipeline/frame/mirror_memo.h"

namespace pleinair {

void MirrorMemo::begin_frame(const Shot& shot, const RayScene* sun_rays, int frames,
                             int shadow_mode, bool sky, bool shadows) {
    if (shot_ != &shot || sun_rays_ != sun_rays || frames_ != frames ||
        shadow_mode_ != shadow_mode || sky_ != sky || shadows_ != shadows)
        chunks_.clear();
    shot_ = &shot, sun_rays_ = sun_rays, frames_ = frames;
    shadow_mode_ = shadow_mode, sky_ = sky, shadows_ = shadows;
}

MirrorMemo::Entry* MirrorMemo::entries(size_t chunk, size_t particles) {
    if (chunks_.size() <= chunk) chunks_.resize(chunk + 1);
    std::vector<Entry>& e = chunks_[chunk];
    if (e.size() != particles) e.assign(particles, Entry{});
    return e.data();
}

}  // namespace pleinair
