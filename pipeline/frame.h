// A painted frame: linear, premultiplied RGBA, with the AOV channels when asked for.
#pragma once

#include <vector>

namespace pleinair {

// Opaque where the background shows. AOVs are filled only when asked for: view depth and
// object id (tree id + 1, 0x10000 + material for surfaces, 0 for background) of the frontmost
// stroke more than half opaque, accumulated stroke alpha, and that stroke's lightness.
struct Frame {
    int width = 0, height = 0;
    std::vector<float> rgba;
    bool has_aovs = false;
    std::vector<float> depth, object_id, alpha, lightness;
};

}  // namespace pleinair
