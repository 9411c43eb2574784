// The depth-order stage of a frame: sprites sorted back to front and binned into screen tiles,
// each tile listing the sprites that touch it back to front (the compositor walks it nearest
// first).
#pragma once

#include <cstdint>
#include <vector>

#include "pipeline/frame/frame_context.h"
#include "pipeline/frame/sprites.h"

namespace pleinair {

constexpr int kTile = 64;  // pixels

struct TileBins {
    int tiles_x = 0, tiles_y = 0;
    std::vector<std::vector<uint32_t>> bins;  // per tile, row-major: sprite indices back to front
};

// Back to front by distance from the eye, which turning the camera does not change: two
// camera-facing sprites ordered by view depth swap as the view turns (thesis V.3, Fig. 31).
// The sprite's index breaks ties, so the order is total and the same on any number of threads.
std::vector<uint32_t> depth_order(const std::vector<Sprite>& sprites);

TileBins bin_sprites(const std::vector<Sprite>& sprites, const std::vector<uint32_t>& order,
                     int width, int height);

// The sort and bin stages: depth order, then the sprites binned into the frame's tiles.
TileBins order_stage(const FrameContext& ctx, const std::vector<Sprite>& sprites);

}  // namespace pleinair
