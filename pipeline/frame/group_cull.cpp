// cluster_fate: the level of detail's fades at the cluster's nearest depth, then its corners
// projected and widened by the largest sprite it can hold.
#include "pipeline/frame/group_cull.h"

#include <algorithm>
#include <cmath>
#include <glm/common.hpp>
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

namespace {

// The cluster's box on one camera's screen: its corners projected, widened by the largest
// sprite any of its particles makes at the nearest depth, and that depth. False when the box
// reaches the near plane (it projects without bounds) or is not finite.
struct ScreenBox {
    double x0, y0, x1, y1, zmin;
    int in_front;
};
ScreenBox screen_box(const Camera& cam, const glm::dvec3& lo, const glm::dvec3& hi) {
    ScreenBox b;
    b.zmin = std::numeric_limits<double>::infinity();
    b.x0 = b.y0 = b.zmin, b.x1 = b.y1 = -b.zmin;
    b.in_front = 0;
    for (int k = 0; k < 8; ++k) {
        const glm::dvec3 d = corner(lo, hi, k) - cam.eye;
        const double z = glm::dot(d, cam.forward);
        if (!(z > cam.near_depth)) continue;
        ++b.in_front;
        b.zmin = std::min(b.zmin, z);
        const double f = cam.focal_px / z;
        const double x = 0.5 * cam.width + f * glm::dot(d, cam.right);
        const double y = 0.5 * cam.height - f * glm::dot(d, cam.up);
        b.x0 = std::min(b.x0, x), b.x1 = std::max(b.x1, x);
        b.y0 = std::min(b.y0, y), b.y1 = std::max(b.y1, y);
    }
    return b;
}

// The largest sprite any of its particles makes at depth z (sprites.cpp's stroke_px: a stroke
// under min_stroke_px is enlarged with its length in proportion; the crest shrink and the near
// field only make it smaller; a thinned stroke's survivor is drawn at most thin_below_px wide),
// and a pixel for rounding.
double sprite_reach(const Camera& cam, const RenderSettings& rs, const FrameLod& lod,
                    const ParticleCluster& c, float scale, double z) {
    const double thinned = lod.thin_small ? c.min_px_factor * rs.thin_below_px : 0.0;
    return scale * (stroke_screen_px(cam, rs, c.stroke, z) + c.min_px_factor * rs.min_stroke_px) +
           thinned + 1.0;
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
    const ScreenBox b = screen_box(cam, lo, hi);
    // Depth is linear over the box: no corner in front, no particle is.
    if (b.in_front == 0) return ClusterFate::kOffScreen;
    // A box across the near plane projects without bounds.
    if (b.in_front < 8) return ClusterFate::kShown;
    const double reach = sprite_reach(cam, rs, lod, c, scale, b.zmin);
    if (!std::isfinite(reach) || !std::isfinite(b.x0 + b.x1 + b.y0 + b.y1))
        return ClusterFate::kShown;
    if (b.x1 + reach < 0 || b.y1 + reach < 0 || b.x0 - reach > cam.width ||
        b.y0 - reach > cam.height)
        return ClusterFate::kOffScreen;
    return ClusterFate::kShown;
}

bool cluster_hidden(const Shot& shot, const FrameLod& lod, const RenderSettings& rs, size_t item,
                    const ParticleCluster& c, double pad, const std::vector<OcclusionMap>& maps) {
    if (maps.empty()) return false;
    const std::vector<BuiltTree>& trees = *shot.trees;
    // The rays' lift off the surface a particle stands on (particle_input.h's RayOrigin).
    const double lift = c.kind == SpriteKind::kSurface ? shot.surface_lift
                        : c.kind == SpriteKind::kBark  ? bark_ray_lift(shot, trees[item])
                                                       : 0.0;
    // Visibility reads a particle where it stands (a moving camera's window) or where the
    // level of detail moved it (a still one): both boxes.
    const bool spread = c.kind == SpriteKind::kLeaf;
    const glm::dvec3 lo = (spread ? glm::min(c.lo, c.spread_lo) : c.lo) - glm::dvec3(pad + lift);
    const glm::dvec3 hi = (spread ? glm::max(c.hi, c.spread_hi) : c.hi) + glm::dvec3(pad + lift);
    const float scale =
        spread && !lod.trees.empty() ? std::max(1.0f, lod.trees[item].growth) : 1.0f;
    for (const OcclusionMap& m : maps) {
        const ScreenBox b = screen_box(m.camera, lo, hi);
        if (b.in_front < 8) return false;
        const double reach = sprite_reach(m.camera, rs, lod, c, scale, b.zmin);
        if (!std::isfinite(reach)) return false;
        // A hair nearer than the nearest corner: a particle's own depth is worked out from its
        // lifted place, not the box's corners, and rounds differently.
        if (!occluded_box(m, b.x0 - reach, b.y0 - reach, b.x1 + reach, b.y1 + reach,
                          b.zmin * (1.0 - 1e-5)))
            return false;
    }
    return true;
}

}  // namespace pleinair
