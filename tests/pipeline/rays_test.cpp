// Embree ray queries: hits, shadow rays, and no acne on ground far from the origin.
#include "pipeline/rays.h"

#include <gtest/gtest.h>

#include <cmath>

#include "generators/rng.h"
#include "generators/rock.h"
#include "generators/terrain.h"

namespace pleinair {
namespace {

QuadMesh floor_quad(float half) {
    QuadMesh m;
    m.positions = {{-half, 0, -half}, {-half, 0, half}, {half, 0, half}, {half, 0, -half}};
    m.quads = {{0, 1, 2, 3}};
    return m;
}

TEST(Rays, NearestHitAndShadowRays) {
    RayScene rays;
    rays.add_mesh(floor_quad(10));
    RockParams rp;
    rp.roughness = 0;
    rays.add_mesh(generate_rock(rp, 1, {0, 3, 0}));  // a squashed ball above the floor
    rays.commit();
    EXPECT_EQ(rays.mesh_count(), 2u);
    RayHit h = rays.intersect({5, 5, 5}, {0, -1, 0});
    ASSERT_TRUE(h.hit);
    EXPECT_NEAR(h.t, 5.0f, 1e-4f);
    EXPECT_EQ(h.geometry, 0u);
    EXPECT_NEAR(std::abs(h.normal.y), 1.0f, 1e-5f);
    EXPECT_FALSE(rays.intersect({5, 5, 5}, {0, 1, 0}).hit);
    EXPECT_FALSE(rays.intersect({5, 5, 5}, {0, -1, 0}, 4.0f).hit);  // beyond tmax
    // The ball shadows the floor under it and not beside it.
    EXPECT_TRUE(rays.occluded({0, 0, 0}, {0, 1, 0}));
    EXPECT_FALSE(rays.occluded({6, 0, 6}, {0, 1, 0}));
    EXPECT_FALSE(rays.occluded({0, 0, 0}, {0, 1, 0}, 1.0f));  // the ball is 2.4 above
}

// A lit flat ground with no casters has no shadowed point, near the origin and 1e5 away, with
// the sun overhead or grazing at 2 degrees.
TEST(Rays, FlatGroundHasNoAcneAnywhere) {
    for (double far : {0.0, 1e5}) {
        TerrainParams tp;
        tp.noise_amplitude = 0;
        tp.min = {far - 100, far - 100};
        tp.max = {far + 100, far + 100};
        tp.base_height = far > 0 ? 250.0 : 0.0;
        tp.resolution = 33;
        GridSurface g = generate_terrain(tp, 1);
        glm::dvec3 anchor(far, tp.base_height, far);
        RayScene rays(anchor);
        // The mesh is placed relative to the anchor in double, as a scene would do.
        QuadMesh m = grid_mesh(g);
        for (auto& p : m.positions) p = glm::vec3(glm::dvec3(p) - anchor);
        rays.add_mesh(m, anchor);
        rays.commit();
        Rng rng = make_rng(3, Purpose::kTree, 1);
        int shadowed = 0;
        for (double elevation : {90.0, 20.0, 2.0}) {
            double e = elevation * M_PI / 180;
            glm::vec3 sun(static_cast<float>(std::cos(e) * 0.6), static_cast<float>(std::sin(e)),
                          static_cast<float>(std::cos(e) * 0.8));
            for (int i = 0; i < 3000; ++i) {
                glm::vec3 pos, n;
                eval_grid(g, rand1(rng), rand1(rng), pos, n);
                glm::dvec3 world = glm::dvec3(pos);  // eval_grid is in world units already
                shadowed += rays.occluded(world, sun, std::numeric_limits<float>::infinity(), &n);
            }
        }
        EXPECT_EQ(shadowed, 0) << "far = " << far;
    }
}

TEST(Rays, EpsilonScalesWithMagnitude) {
    EXPECT_FLOAT_EQ(ray_epsilon({0, 0, 0}), ray_epsilon({1, -1, 0.5}));
    EXPECT_NEAR(ray_epsilon({1e5, 0, 0}) / ray_epsilon({1, 0, 0}), 1e5f, 1.0f);
    EXPECT_GT(ray_epsilon({0, -2e4, 0}), ray_epsilon({0, 1e4, 0}));
    // Larger than the float spacing of the coordinate itself, so an origin computed in float
    // world space cannot sit on the wrong side of its surface.
    EXPECT_GT(ray_epsilon({1e5, 0, 0}), 1e5f * std::numeric_limits<float>::epsilon());
}

}  // namespace
}  // namespace pleinair
