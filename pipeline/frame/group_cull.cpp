// cluster_fate: the level of detail's fades at the cluster's nearest depth, then its corners
// projected and widened by the largest sprite it can hold.
#include "pipeline/frame/group_cull.h"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <limits>

#include "pipeline/frame/stroke_size.h"
#include "pipeline/shot/shot.h"

namespace pleinair {

namespace {

glm::dvec3 corner(const glm::dvec3& lo, const glm::dvec3& hi, int c) {
    return {(c & 1) ? hi.x : lo.x, (c & 2) ? hi.y : lo.y, (c & 4) ? hi.z : lo.z};
}

double nearest_depth(const Camera& cam, const glm::dvec3& lo, const glm::dvec3& hi) {
    double z = std::numeric_limits<double>::infinity();
    for (int c = 0; c < 8; ++c) z = std::min(z, view_depth(cam, corner(lo, hi, c)));
    return z;
}

// Every particle faded out: a tree's distance value (the same for all its particles) or a
// surface stroke's own, which only grows with depth, at or past the cluster's gone_at.
bool faded(const Shot& shot, const FrameLod& lod, size_t item, const ParticleCluster& c) {
    const std::vector<BuiltTree>& trees = *shot.trees;
    if (c.kind == SpriteKind::kSurface) {
        if (shot.land->is_near(item - trees.size())) return !lod.near_field;
        if (!std::isfinite(c.gone_at)) return false;
        const double z = nearest_depth(lod.camera, c.lo, c.hi);
        const DistanceCircles& circles = lod.circles;
        const Atmosphere& a = shot.scene.atmosphere;
        const float dv = lod.surfaces ? circle_value(z, circles.leaf_near, circles.leaf_far)
                                      : circle_value(z, a.near_distance, a.far_distance);
        return dv >= c.gone_at;
    }
    if (lod.trees.empty()) return false;
    const TreeLod& t = lod.trees[item];
    if (c.kind == SpriteKind::kLeaf) return lod.leaves && t.leaf >= c.gone_at;
    return lod.trunks && t.trunk >= c.gone_at;
}

}  // namespace

ClusterFate cluster_fate(const Shot& shot, const FrameLod& lod, const Camera& cam,
                         const RenderSettings& rs, size_t item, const ParticleCluster& c,
                         double pad) {
    if (faded(shot, lod, item, c)) return ClusterFate::kFaded;
    // Survivors of a thinned crown are spread out and grown (lod.h).
    const bool spread =
        c.kind == SpriteKind::kLeaf && lod.leaves && !lod.trees.empty() && lod.trees[item].leaf > 0;
    const glm::dvec3 lo = (spread ? c.spread_lo : c.lo) - glm::dvec3(pad);
    const glm::dvec3 hi = (spread ? c.spread_hi : c.hi) + glm::dvec3(pad);
    const float scale = spread ? std::max(1.0f, lod.trees[item].growth) : 1.0f;
    double zmin = std::numeric_limits<double>::infinity();
    double x0 = zmin, y0 = zmin, x1 = -zmin, y1 = -zmin;
    int in_front = 0;
    for (int k = 0; k < 8; ++k) {
        const glm::dvec3 d = corner(lo, hi, k) - cam.eye;
        const double z = glm::dot(d, cam.forward);
        if (!(z > cam.near_depth)) continue;
        ++in_front;
        zmin = std::min(zmin, z);
        const double f = cam.focal_px / z;
        const double x = 0.5 * cam.width + f * glm::dot(d, cam.right);
        const double y = 0.5 * cam.height - f * glm::dot(d, cam.up);
        x0 = std::min(x0, x), x1 = std::max(x1, x), y0 = std::min(y0, y), y1 = std::max(y1, y);
    }
    // Depth is linear over the box: no corner in front, no particle is.
    if (in_front == 0) return ClusterFate::kOffScreen;
    // A box across the near plane projects without bounds.
    if (in_front < 8) return ClusterFate::kShown;
    // The largest sprite any of its particles makes at the nearest depth (sprites.cpp's
    // stroke_px: a stroke under min_stroke_px is enlarged with its length in proportion; the
    // crest shrink and the near field only make it smaller; a thinned stroke's survivor is
    // drawn at most thin_below_px wide), and a pixel for rounding.
    const double thinned = lod.thin_small ? c.min_px_factor * rs.thin_below_px : 0.0;
    const double reach =
        scale * (stroke_screen_px(cam, rs, c.stroke, zmin) + c.min_px_factor * rs.min_stroke_px) +
        thinned + 1.0;
    if (!std::isfinite(reach) || !std::isfinite(x0 + x1 + y0 + y1)) return ClusterFate::kShown;
    if (x1 + reach < 0 || y1 + reach < 0 || x0 - reach > cam.width || y0 - reach > cam.height)
        return ClusterFate::kOffScreen;
    return ClusterFate::kShown;
}

}  // namespace pleinair
