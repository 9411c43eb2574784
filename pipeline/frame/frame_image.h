// A painted frame: linear, premultiplied RGBA, with the AOV channels when asked for.
#pragma once

#include <vector>

namespace pleinair {

// Opaque where the background shows. AOVs are filled only when asked for: view depth and
// object id (tree id + 1, 0x10000 + material for surfaces, 0 for background) of the frontmost
// stroke more than half opaque, accumulated stroke alpha, and that stroke's lightness. A pixel
// covered only by strokes each at most half opaque has object id 0 and the underpainting's
// depth (or the largest float): no single stroke is its front.
struct Frame {
    int width = 0, height = 0;
    std::vector<float> rgba;
    bool has_aovs = false;
    std::vector<float> depth, object_id, alpha, lightness;
};

}  // namespace pleinair
