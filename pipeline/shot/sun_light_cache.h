// The still sun's light at each particle, traced the first time a frame asks for it and kept
// for the frames after (animations under a still sun): a frame that shows a tenth of a forest
// traces a tenth of its particles' light, and the frames after it little more.
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "pipeline/input/settings.h"
#include "pipeline/shot/particle_input.h"
#include "pipeline/shot/rays.h"

namespace pleinair {

// Part of a shot that frames fill in: each slot goes once from unknown to its ray's answer,
// which does not depend on the frame that traced it, so the pixels are those of tracing every
// frame anew. Safe to fill from many threads (two that race store the same bits).
class SunLightCache {
  public:
    // `particles[i]`: item i's particle count (slots as for_each_particle visits them).
    SunLightCache(const std::vector<size_t>& particles, const glm::vec3& sun, ShadowMode mode);

    // The light reaching item's particle `slot` at `o` through `sun_rays` (the shot's);
    // `traced` is set when this call cast the ray.
    float light(const RayScene& sun_rays, size_t item, size_t slot, const RayOrigin& o,
                bool& traced) const;
    // The light if a frame traced it already; negative if not.
    float known(size_t item, size_t slot) const;
    size_t items() const { return items_.size(); }
    size_t size(size_t item) const { return sizes_[item]; }

  private:
    static constexpr uint32_t kUnknown = 0xFFFFFFFFu;  // a NaN: no light is one
    glm::vec3 sun_;
    ShadowMode mode_;
    std::vector<size_t> sizes_;
    std::vector<std::unique_ptr<std::atomic<uint32_t>[]>> items_;
};

}  // namespace pleinair
