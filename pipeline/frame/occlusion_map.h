// Occlusion maps: what one camera sees of the opaque surfaces (terrain, rocks, water, trunks
// and limbs) at a few pixels a texel, as the view depth of the first surface each texel's ray
// meets, with a pyramid of maxima, so that a stroke, a cluster of strokes or a whole tree is
// found hidden by a lookup instead of a ray a stroke (issue 53: hidden clusters and trees cost
// close to nothing).
#pragma once

#include <cstdint>
#include <vector>

#include "pipeline/input/camera.h"

namespace pleinair {

class RayScene;

struct OcclusionMap {
    Camera camera;
    int texel_px = 2;           // pixels a texel spans, each way
    int width = 0, height = 0;  // texels at level 0
    // Level 0: per texel, the farthest of the surfaces' depths met by its own ray and its eight
    // neighbours' (infinity where a ray meets none, and beside the map's edge), so a point is
    // hidden only where the surface in front of it is met all around it: a stroke within a
    // texel of a silhouette, or on the ground it stands on, is not hidden by sampling. Level k:
    // the maximum over 2^k x 2^k texels of level 0.
    std::vector<std::vector<float>> levels;
    std::vector<int> level_width, level_height;
    // Per texel the nearest of those nine depths: a point nearer than it is in front of every
    // surface around it.
    std::vector<float> nearest;
    uint64_t rays = 0;  // cast to build it
};

// The texel's size for an image `image_width` wide: 2 pixels, more above 960 so a map has at
// most about 480 texels across (130,000 rays a map at 1920x1080).
int occlusion_texel_px(int image_width);
// The rays (texels) of the camera's map: what drawing it costs, for the frame plan to weigh.
uint64_t occlusion_map_rays(const Camera& camera);

// One nearest-hit ray through the centre of each texel of the camera's image, rows in
// parallel (each texel's answer its own, so the map is the same at any thread count).
OcclusionMap build_occlusion_map(const RayScene& rays, const Camera& camera);

// What a map says of a point the camera projects to (x, y) px at view depth z: hidden when it
// lies deeper than the farthest surface met within a texel of it, seen when nearer than the
// nearest, and unsure otherwise (on a surface, at a silhouette, off the image): there the
// point's own ray decides.
enum class MapAnswer : uint8_t { kSeen, kHidden, kUnsure };
MapAnswer occluded_at(const OcclusionMap& map, double x, double y, double z);

// Whether every point that projects into the pixel rectangle [x0, x1] x [y0, y1] at view depth
// z or more is occluded_at's kHidden: so a cluster whose every stroke lies there can be culled
// unread. Conservative: false when the rectangle leaves the image.
bool occluded_box(const OcclusionMap& map, double x0, double y0, double x1, double y1, double z);

}  // namespace pleinair
