// Culling by group: whether a cluster of particles can show in a frame, decided from its bounds
// before any particle of it is read, so a tree wholly off screen or faded out costs a few
// projections instead of a look at each of its strokes.
#pragma once

#include <cstddef>
#include <cstdint>

#include "pipeline/frame/lod.h"
#include "pipeline/frame/occlusion_map.h"
#include "pipeline/shot/particle_clusters.h"

namespace pleinair {

struct Shot;
struct Camera;
struct RenderSettings;

enum class ClusterFate : uint8_t {
    kShown,      // some particle of it may show: each is looked at
    kFaded,      // every particle has faded out by the level of detail
    kOffScreen,  // every sprite lies behind the camera or wholly off screen
};

// Conservative: kFaded or kOffScreen only when the sprites stage, particle by particle, would
// cull each of the cluster's particles for that reason. `cam` is the frame's camera (the level
// of detail's may be another, lod.camera). `pad` widens the cluster's bounds by as far as its
// particles may have moved from them (the wind, world units).
ClusterFate cluster_fate(const Shot& shot, const FrameLod& lod, const Camera& cam,
                         const RenderSettings& rs, size_t item, const ParticleCluster& c,
                         double pad = 0);

// Whether every particle of a cluster cluster_fate shows is hidden from each of the maps at any
// height the sprites stage tests it from (sprites.cpp's visibility): its bounds (where the
// level of detail may move it, its rays' lift off its limb or ground, `pad`) projected by each
// map's camera and widened by the largest sprite it can hold, behind the farthest surface met
// over that rectangle. Conservative: true only when visibility() would find each particle
// hidden from every map, so culling it whole changes no sprite.
bool cluster_hidden(const Shot& shot, const FrameLod& lod, const RenderSettings& rs, size_t item,
                    const ParticleCluster& c, double pad, const std::vector<OcclusionMap>& maps);

}  // namespace pleinair
