// depth_order and bin_sprites.
#include "pipeline/frame/tile_bins.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>

namespace pleinair {

namespace {

// A float's bits as an unsigned key in the float's order (-0 taken as +0, which it equals), so
// that sorting keys orders the floats.
uint32_t ordered_bits(float f) {
    if (f == 0.0f) f = 0.0f;
    uint32_t b;
    std::memcpy(&b, &f, sizeof b);
    return (b & 0x80000000u) ? ~b : b | 0x80000000u;
}

}  // namespace

std::vector<uint32_t> depth_order(const std::vector<Sprite>& sprites) {
    // One 64-bit key a sprite, farthest first and then by index (ranges are lengths, finite and
    // not negative): sorting the keys takes half the time of a comparator reading two sprites'
    // ranges at random places.
    const size_t n = sprites.size();
    std::vector<uint64_t> keys(n);
    tbb::parallel_for(tbb::blocked_range<size_t>(0, n, 4096), [&](const auto& r) {
        for (size_t i = r.begin(); i < r.end(); ++i)
            keys[i] = (static_cast<uint64_t>(~ordered_bits(sprites[i].range)) << 32) | i;
    });
    tbb::parallel_sort(keys.begin(), keys.end());
    std::vector<uint32_t> order(n);
    for (size_t i = 0; i < n; ++i) order[i] = static_cast<uint32_t>(keys[i]);
    return order;
}

TileBins bin_sprites(const std::vector<Sprite>& sprites, const std::vector<uint32_t>& order,
                     int width, int height) {
    TileBins t;
    t.tiles_x = (width + kTile - 1) / kTile;
    t.tiles_y = (height + kTile - 1) / kTile;
    t.bins.resize(static_cast<size_t>(t.tiles_x) * t.tiles_y);
    auto tile_of = [](float v, int tiles) {
        return static_cast<int16_t>(std::clamp(std::floor(v / kTile), 0.0f, tiles - 1.0f));
    };
    // Each sprite's tiles first, in sprite order and in parallel: the walk in depth order
    // below then reads 8 bytes a sprite instead of a whole sprite at a random place.
    struct Tiles {
        int16_t x0, x1, y0, y1;
    };
    std::vector<Tiles> tiles(sprites.size());
    tbb::parallel_for(tbb::blocked_range<size_t>(0, sprites.size(), 4096), [&](const auto& r) {
        for (size_t i = r.begin(); i < r.end(); ++i) {
            const Sprite& sp = sprites[i];
            float ex, ey;
            sprite_extent(sp, ex, ey);
            tiles[i] = {tile_of(sp.x - ex, t.tiles_x), tile_of(sp.x + ex, t.tiles_x),
                        tile_of(sp.y - ey, t.tiles_y), tile_of(sp.y + ey, t.tiles_y)};
        }
    });
    for (uint32_t idx : order) {
        const Tiles& k = tiles[idx];
        for (int ty = k.y0; ty <= k.y1; ++ty)
            for (int tx = k.x0; tx <= k.x1; ++tx)
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
