// Water strokes' mirrors kept from frame to frame: while the camera moves, a stroke traces its
// mirror only from the eye at lattice times (reflection.h's MirrorLattice), which no frame
// changes, so frames of one shot painted in order trace each lattice time's mirror once.
// The colours are the rays' own: a frame painted with the memo is the one painted without it.
#pragma once

#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#include "shading/color.h"

namespace pleinair {

struct Shot;
class RayScene;

class MirrorMemo {
  public:
    static constexpr int64_t kNone = std::numeric_limits<int64_t>::min();
    // What a particle's last two lattice times' mirrors found (kNone: not traced).
    struct Entry {
        int64_t time[2] = {kNone, kNone};
        Color seen[2]{Color(0.0f), Color(0.0f)};
    };

    // Before a frame's reflections, on one thread: drops everything when the shot, the sun's
    // casters, the lattice's spacing or what the mirrors read of the settings changed.
    void begin_frame(const Shot& shot, const RayScene* sun_rays, int frames, int shadow_mode,
                     bool sky, bool shadows);
    // The entries of land chunk `chunk` (particles: its count), grown on first use; call on
    // one thread (reflection.cpp makes them before its parallel loop).
    Entry* entries(size_t chunk, size_t particles);

  private:
    const Shot* shot_ = nullptr;
    const RayScene* sun_rays_ = nullptr;
    int frames_ = 0, shadow_mode_ = -1;
    bool sky_ = false, shadows_ = false;
    std::vector<std::vector<Entry>> chunks_;
};

}  // namespace pleinair
