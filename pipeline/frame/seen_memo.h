// Occlusion maps and answers kept from frame to frame: a moving camera's seen window
// (frame_view.h) looks from cameras at lattice times fixed to the track's clock, so frames of
// one shot painted in order, which share n - 1 of their lattice times, need build each
// camera's occlusion map (occlusion_map.h) once, and cast once each ray a stroke casts where
// its map is unsure. Maps and rays are their camera's alone: a frame painted with the memo is
// the one painted without it.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "pipeline/frame/occlusion_map.h"
#include "pipeline/input/settings.h"

namespace pleinair {

struct Shot;
struct SeenWindow;

// The maps a frame's strokes are tested against: one per camera of the seen window, or the
// frame's own camera's alone for a still one (window empty or null). Null when the shot has no
// opaque surfaces to hide behind (no view rays). `rays` counts those cast for maps built here.
std::vector<OcclusionMap> occlusion_maps(const Shot& shot, const SeenWindow* window,
                                         const Camera& frame_camera, uint64_t& rays);

class SeenMemo {
  public:
    enum : uint8_t { kUnknown = 0, kSeen = 1, kHidden = 2 };

    // The frame's maps (occlusion_maps), those of cameras the frames before used kept and the
    // others built; all built again when the shot changed. On one thread, before the sprites.
    const std::vector<OcclusionMap>& maps(const Shot& shot, const SeenWindow* window,
                                          const Camera& frame_camera, uint64_t& rays);
    // Before a frame's sprites, on one thread: keeps the rays' answers of the window's lattice
    // times (from the frames before) and drops the others; all of them when the shot or what
    // the rays read of the settings (sizes, stroke perspective, the image's size) changed.
    void begin_frame(const Shot& shot, const SeenWindow& window, const RenderSettings& rs);
    // The answers of window camera k for the particles of item `item` (particles: its count),
    // indexed as for_each_particle visits them. Each item's are touched by one task at a time.
    uint8_t* answers(size_t k, size_t item, size_t particles);

  private:
    const Shot* shot_ = nullptr;
    std::vector<OcclusionMap> maps_;  // the last frame's, in its window's order
    struct Time {
        int64_t lattice = 0;
        std::vector<std::vector<uint8_t>> items;
    };
    const Shot* answers_shot_ = nullptr;
    float stroke_perspective_ = 0, min_stroke_px_ = 0;
    int width_ = 0, height_ = 0;
    std::vector<Time> times_;  // the current window's, in its order
};

}  // namespace pleinair
