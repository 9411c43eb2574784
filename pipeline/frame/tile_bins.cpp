// depth_order and bin_sprites.
#include "pipeline/frame/tile_bins.h"

#include <tbb/parallel_sort.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace pleinair {

std::vector<uint32_t> depth_order(const std::vector<Sprite>& sprites) {
    std::vector<uint32_t> order(sprites.size());
    for (size_t i = 0; i < order.size(); ++i) order[i] = static_cast<uint32_t>(i);
    tbb::parallel_sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) {
        if (sprites[a].range != sprites[b].range) return sprites[a].range > sprites[b].range;
        return a < b;
    });
    return order;
}

TileBins bin_sprites(const std::vector<Sprite>& sprites, const std::vector<uint32_t>& order,
                     int width, int height) {
    TileBins t;
    t.tiles_x = (width + kTile - 1) / kTile;
    t.tiles_y = (height + kTile - 1) / kTile;
    t.bins.resize(static_cast<size_t>(t.tiles_x) * t.tiles_y);
    auto tile_of = [](float v, int tiles) {
        return static_cast<int>(std::clamp(std::floor(v / kTile), 0.0f, tiles - 1.0f));
    };
    for (uint32_t idx : order) {
        const Sprite& sp = sprites[idx];
        float ex, ey;
        sprite_extent(sp, ex, ey);
        const int x0 = tile_of(sp.x - ex, t.tiles_x), x1 = tile_of(sp.x + ex, t.tiles_x);
        const int y0 = tile_of(sp.y - ey, t.tiles_y), y1 = tile_of(sp.y + ey, t.tiles_y);
        for (int ty = y0; ty <= y1; ++ty)
            for (int tx = x0; tx <= x1; ++tx)
                t.bins[static_cast<size_t>(ty) * t.tiles_x + tx].push_back(idx);
    }
    return t;
}

TileBins order_stage(const FrameContext& ctx, const std::vector<Sprite>& sprites) {
    StagePhase sort(ctx, "sort");
    const std::vector<uint32_t> order = depth_order(sprites);
    sort.done("depth order, ties by sprite");
    StagePhase bin(ctx, "bin");
    const Camera& cam = ctx.view.camera;
    TileBins bins = bin_sprites(sprites, order, cam.width, cam.height);
    bin.done("tiles paint in parallel",
             std::to_string(bins.bins.size()) + " tiles of " + std::to_string(kTile) + " px");
    return bins;
}

}  // namespace pleinair
