// SunLightCache: one atomic word per particle, the light's float bits or kUnknown.
#include "pipeline/shot/sun_light_cache.h"

#include <cstring>
#include <limits>

namespace pleinair {

SunLightCache::SunLightCache(const std::vector<size_t>& particles, const glm::vec3& sun,
                             ShadowMode mode)
    : sun_(sun), mode_(mode), sizes_(particles) {
    items_.reserve(particles.size());
    for (size_t n : particles) {
        items_.push_back(std::make_unique<std::atomic<uint32_t>[]>(n));
        for (size_t j = 0; j < n; ++j) items_.back()[j].store(kUnknown, std::memory_order_relaxed);
    }
}

float SunLightCache::light(const RayScene& sun_rays, size_t item, size_t slot, const RayOrigin& o,
                           bool& traced) const {
    std::atomic<uint32_t>& word = items_[item][slot];
    uint32_t bits = word.load(std::memory_order_relaxed);
    traced = bits == kUnknown;
    if (!traced) {
        float l;
        std::memcpy(&l, &bits, sizeof l);
        return l;
    }
    // As shot.h's sun_light_at.
    const float l = sun_rays.transmittance(
        o.lifted(), sun_, mode_, std::numeric_limits<float>::infinity(), o.surface_normal());
    std::memcpy(&bits, &l, sizeof bits);
    word.store(bits, std::memory_order_relaxed);
    return l;
}

float SunLightCache::known(size_t item, size_t slot) const {
    const uint32_t bits = items_[item][slot].load(std::memory_order_relaxed);
    if (bits == kUnknown) return -1.0f;
    float l;
    std::memcpy(&l, &bits, sizeof l);
    return l;
}

}  // namespace pleinair
