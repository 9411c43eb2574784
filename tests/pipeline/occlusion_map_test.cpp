// Occlusion maps (issue 53): a wall hides what stands behind it, not what stands in front or
// beside it; near its edge the map is unsure; and a box it calls hidden holds no point it would
// call anything else.
#include "pipeline/frame/occlusion_map.h"

#include <gtest/gtest.h>

#include <random>

#include "pipeline/shot/rays.h"

namespace pleinair {
namespace {

// A wall across x in [-2, 2], y in [0, 3], at z = 0; the camera at z = 10 looking down -z.
struct Wall {
    RayScene rays;
    Camera cam;
    Wall() {
        QuadMesh m;
        m.positions = {{-2, 0, 0}, {2, 0, 0}, {2, 3, 0}, {-2, 3, 0}};
        m.quads = {{0, 1, 2, 3}};
        rays.add_mesh(m);
        rays.commit();
        CameraParams p;
        p.position = {0, 1.5, 10};
        p.look_at = {0, 1.5, 0};
        p.width = 200, p.height = 120;
        EXPECT_EQ(make_camera(p, cam), "");
    }
    MapAnswer at(const OcclusionMap& m, const glm::dvec3& w) const {
        const Projection pr = project(cam, w);
        return occluded_at(m, pr.x, pr.y, pr.depth);
    }
};

TEST(OcclusionMap, AWallHidesWhatIsBehindItOnly) {
    Wall w;
    const OcclusionMap m = build_occlusion_map(w.rays, w.cam);
    EXPECT_EQ(m.texel_px, 2);
    EXPECT_EQ(m.width, 100);
    EXPECT_EQ(m.rays, 100u * 60u);
    EXPECT_EQ(w.at(m, {0, 1.5, -1}), MapAnswer::kHidden);  // behind its middle
    EXPECT_EQ(w.at(m, {0.5, 1, -5}), MapAnswer::kHidden);
    EXPECT_EQ(w.at(m, {0, 1.5, 1}), MapAnswer::kSeen);          // in front of it
    EXPECT_EQ(w.at(m, {0, 1.5, 0}), MapAnswer::kUnsure);        // on it
    EXPECT_EQ(w.at(m, {4, 1.5, -1}), MapAnswer::kSeen);         // beside it: open sky
    EXPECT_EQ(occluded_at(m, -1, 60, 20), MapAnswer::kUnsure);  // off the image: not mapped
    EXPECT_EQ(occluded_at(m, 100, 120, 20), MapAnswer::kUnsure);
    // At its edge, within a texel: unsure, whatever the depth.
    const Projection edge = project(w.cam, {2, 1.5, 0});
    EXPECT_EQ(occluded_at(m, edge.x - 1, edge.y, 20), MapAnswer::kUnsure);
    EXPECT_EQ(occluded_at(m, edge.x - 5, edge.y, 20), MapAnswer::kHidden);
}

TEST(OcclusionMap, ABoxCalledHiddenHoldsOnlyHiddenPoints) {
    Wall w;
    const OcclusionMap m = build_occlusion_map(w.rays, w.cam);
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> px(-10, 210), size(0, 30), depth(5, 30);
    int hidden_boxes = 0;
    for (int k = 0; k < 3000; ++k) {
        const double x0 = px(rng), y0 = px(rng) * 0.6, x1 = x0 + size(rng), y1 = y0 + size(rng);
        const double z = depth(rng);
        if (!occluded_box(m, x0, y0, x1, y1, z)) continue;
        ++hidden_boxes;
        for (int s = 0; s < 20; ++s) {
            const double x = x0 + (x1 - x0) * (s % 5) / 4.0, y = y0 + (y1 - y0) * (s / 5) / 3.0;
            ASSERT_EQ(occluded_at(m, x, y, z + s), MapAnswer::kHidden) << x << " " << y;
        }
    }
    EXPECT_GT(hidden_boxes, 50);
    // The wall's whole face at a depth behind it; not when the box reaches past its edge.
    const Projection a = project(w.cam, {-1.5, 2.5, 0}), b = project(w.cam, {1.5, 0.5, 0});
    EXPECT_TRUE(occluded_box(m, a.x, a.y, b.x, b.y, 12));
    EXPECT_FALSE(occluded_box(m, a.x, a.y, b.x + 40, b.y, 12));
    EXPECT_FALSE(occluded_box(m, a.x, a.y, b.x, b.y, 9.9));  // in front of the wall
}

}  // namespace
}  // namespace pleinair
