// Occlusion answers kept from frame to frame: a moving camera's rays towards the eye (the seen
// window, frame_view.h) depend only on their lattice time and the particle, so frames of one
// shot painted in order, which share n - 1 of their lattice times, need cast each ray once.
// The answers are the rays' own: a frame painted with the memo is the one painted without it.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "pipeline/input/settings.h"

namespace pleinair {

struct Shot;
struct SeenWindow;

class SeenMemo {
  public:
    enum : uint8_t { kUnknown = 0, kSeen = 1, kHidden = 2 };

    // Before a frame's sprites, on one thread: keeps the answers of the window's lattice times
    // (from the frames before) and drops the others; all of them when the shot or what the
    // rays read of the settings (sizes, stroke perspective, the image's size) changed.
    void begin_frame(const Shot& shot, const SeenWindow& window, const RenderSettings& rs);
    // The answers of window camera k for the particles of item `item` (particles: its count),
    // indexed as for_each_particle visits them. Each item's are touched by one task at a time.
    uint8_t* answers(size_t k, size_t item, size_t particles);

  private:
    struct Time {
        int64_t lattice = 0;
        std::vector<std::vector<uint8_t>> items;
    };
    const Shot* shot_ = nullptr;
    float stroke_perspective_ = 0, min_stroke_px_ = 0;
    int width_ = 0, height_ = 0;
    std::vector<Time> times_;  // the current window's, in its order
};

}  // namespace pleinair
