// Embree ray queries: hits, shadow rays, and no acne on ground far from the origin.
#include "pipeline/shot/rays.h"

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

// A shared mesh placed by an instance answers like the same mesh copied into place: the same
// hits, the hit named by the instance's id, the normal turned into the world.
TEST(Rays, InstancesAnswerLikeTheMeshCopiedIntoPlace) {
    RockParams rp;
    rp.roughness = 0.3;
    const QuadMesh rock = generate_rock(rp, 3, {0, 0, 0});
    const double angle = 0.7, scale = 1.8;
    const double c = std::cos(angle), s = std::sin(angle);
    const glm::dmat3 linear(glm::dvec3(c, 0, -s) * scale, glm::dvec3(0, 1, 0) * scale,
                            glm::dvec3(s, 0, c) * scale);
    const glm::dvec3 where(1e4, 3, -2e4), anchor(1e4 + 7, 0, -2e4 + 5);
    QuadMesh placed = rock;
    for (auto& p : placed.positions) p = glm::vec3(linear * glm::dvec3(p));
    RayScene copied(anchor);
    copied.add_mesh(floor_quad(50), where);
    copied.add_mesh(placed, where);
    copied.commit();
    RayMeshes shared;
    const uint32_t m = shared.add(rock);
    shared.commit();
    RayScene instanced(anchor, &shared);
    instanced.add_mesh(floor_quad(50), where);
    EXPECT_EQ(instanced.add_instance(m, linear, where), 1u);
    instanced.commit();
    EXPECT_EQ(instanced.mesh_count(), 2u);
    Rng rng = make_rng(11, Purpose::kTree, 0);
    int rock_hits = 0;
    for (int i = 0; i < 400; ++i) {
        const glm::dvec3 o = where + glm::dvec3(rand_range(rng, -2, 2), 6, rand_range(rng, -2, 2));
        const glm::vec3 d =
            glm::normalize(glm::vec3(rand_range(rng, -0.3, 0.3), -1, rand_range(rng, -0.3, 0.3)));
        const RayHit a = copied.intersect(o, d), b = instanced.intersect(o, d);
        ASSERT_EQ(a.hit, b.hit) << i;
        if (!a.hit) continue;
        ASSERT_EQ(a.geometry, b.geometry) << i;
        EXPECT_NEAR(a.t, b.t, 1e-3f) << i;
        if (a.geometry != 1 || a.primitive != b.primitive) continue;
        EXPECT_GT(glm::dot(a.normal, b.normal), 0.999f) << i;  // the instance's, in the world
        ++rock_hits;
        EXPECT_TRUE(instanced.occluded(o, d, a.t + 0.05f)) << i;
        EXPECT_FALSE(instanced.occluded(o, d, a.t - 0.05f)) << i;
    }
    EXPECT_GT(rock_hits, 100);
    // The smallest and largest placements a scene allows keep finite, unit normals.
    for (double k : {1e-4, 1e4}) {
        RayScene r(glm::dvec3(0.0), &shared);  // at the origin: ray offsets stay below 1e-4
        r.add_instance(m, linear * k, glm::dvec3(0.0));
        r.commit();
        const RayHit h = r.intersect(glm::dvec3(0, 40.0 * k, 0), {0, -1, 0});
        ASSERT_TRUE(h.hit) << k;
        EXPECT_NEAR(glm::length(h.normal), 1.0f, 1e-4f) << k;
        EXPECT_GT(h.normal.y, 0.5f) << k;  // the rock's top faces up
    }
    // A squashed, turned placement: normals go through the inverse transpose, not the matrix.
    const glm::dmat3 squash =
        linear * glm::dmat3(glm::dvec3(1, 0, 0), glm::dvec3(0, 0.3, 0), glm::dvec3(0, 0, 2.5));
    QuadMesh flat = rock;
    for (auto& p : flat.positions) p = glm::vec3(squash * glm::dvec3(p));
    RayScene copied2(anchor), instanced2(anchor, &shared);
    copied2.add_mesh(flat, where);
    instanced2.add_instance(m, squash, where);
    copied2.commit();
    instanced2.commit();
    int squashed_hits = 0;
    for (int i = 0; i < 200; ++i) {
        // From all round, slanting: the sides, where squashing turns the normals most.
        const double az = rand_range(rng, 0, 2 * M_PI);
        const glm::dvec3 o =
            where + glm::dvec3(8 * std::cos(az), rand_range(rng, -2, 2), 8 * std::sin(az));
        const glm::vec3 d = glm::normalize(
            glm::vec3(where - o) +
            glm::vec3(rand_range(rng, -1, 1), rand_range(rng, -1, 1), rand_range(rng, -1, 1)));
        const RayHit a = copied2.intersect(o, d), b = instanced2.intersect(o, d);
        ASSERT_EQ(a.hit, b.hit) << i;
        if (!a.hit || a.primitive != b.primitive) continue;
        EXPECT_GT(glm::dot(a.normal, b.normal), 0.999f) << i;
        ++squashed_hits;
    }
    EXPECT_GT(squashed_hits, 50);
    EXPECT_THROW(instanced.add_instance(5, linear, where), std::invalid_argument);
    RayScene alone;
    EXPECT_THROW(alone.add_instance(0, linear, where), std::invalid_argument);
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

// One leaf card 5 above the floor, facing a sun straight up. Its shadow is its stroke mask:
// the light getting through at each point below is 1 - the mask's opacity there, so the
// corners of the card's square and the gaps between noise blobs cast no shadow.
StrokeCaster card(glm::dvec3 center, float label, const StrokeShaderParams& p) {
    StrokeCaster c;
    c.center = center;
    c.axis_s = {1, 0, 0};
    c.axis_t = {0, 0, 1};
    c.half_w = c.half_l = 1.0f;
    c.noise =
        noise_of(stroke_constants(p, 1.0f, 0.5f, 0.5f, label, 0, 1.0f, 0.0f, 0.0f, false, false));
    return c;
}

TEST(Rays, StrokeCastersShadowAsTheirMaskNotAsSquares) {
    StrokeShaderParams p;
    EdgeTable edge = make_edge_table(p.stroke_fullness);
    StrokeCaster c = card({0, 5, 0}, 0.37f, p);
    RayScene rays;
    rays.add_mesh(floor_quad(10));
    rays.add_casters({c}, p, edge);
    rays.commit();
    EXPECT_EQ(rays.caster_count(), 1u);
    const glm::vec3 up(0, 1, 0);
    int lit_inside = 0, dark = 0, n = 0;
    for (int j = 0; j < 40; ++j)
        for (int i = 0; i < 40; ++i) {
            const float s = (i + 0.5f) / 40, t = (j + 0.5f) / 40;
            const glm::dvec3 p0(2.0 * s - 1.0, 0.0, 2.0 * t - 1.0);
            const float want = 1.0f - stroke_opacity(p, stroke_noise(c.noise, s, t, 1),
                                                     edge_mask(edge, s, t, p.stroke_fullness));
            const float got = rays.transmittance(p0, up, ShadowMode::kTransmissive,
                                                 std::numeric_limits<float>::infinity(), &up);
            EXPECT_NEAR(got, want, 2e-3f) << s << ", " << t;
            const float thr = rays.transmittance(p0, up, ShadowMode::kThreshold,
                                                 std::numeric_limits<float>::infinity(), &up);
            EXPECT_EQ(thr, want < 0.5f ? 0.0f : 1.0f) << s << ", " << t;
            lit_inside += got == 1.0f;
            dark += got < 0.5f;
            ++n;
        }
    EXPECT_GT(lit_inside, n / 10) << "a square would shade every point under it";
    EXPECT_GT(dark, n / 10);
    // Beside the card, full light; the floor itself is not a caster of the points on it.
    EXPECT_EQ(rays.transmittance({3, 0, 3}, up, ShadowMode::kTransmissive), 1.0f);
}

TEST(Rays, LightThroughStackedCardsIsTheProductAndOpaqueSurfacesBlock) {
    StrokeShaderParams p;
    p.max_stroke_opacity = 0.6f;  // every card lets some light through
    EdgeTable edge = make_edge_table(p.stroke_fullness);
    StrokeCaster a = card({0, 5, 0}, 0.2f, p), b = card({0, 7, 0}, 0.8f, p);
    RayScene rays;
    rays.add_casters({a, b}, p, edge);
    QuadMesh roof = floor_quad(1);
    rays.add_mesh(roof, {5, 9, 0});  // an opaque roof over x in [4, 6]
    rays.commit();
    const glm::vec3 up(0, 1, 0);
    for (float s : {0.3f, 0.5f, 0.62f}) {
        const float t = 0.45f;
        auto op = [&](const StrokeCaster& c) {
            return stroke_opacity(p, stroke_noise(c.noise, s, t, 1),
                                  edge_mask(edge, s, t, p.stroke_fullness));
        };
        const float want = (1 - op(a)) * (1 - op(b));
        EXPECT_NEAR(
            rays.transmittance({2.0 * s - 1.0, 0, 2.0 * t - 1.0}, up, ShadowMode::kTransmissive),
            want, 2e-3f);
    }
    EXPECT_EQ(rays.transmittance({5, 0, 0}, up, ShadowMode::kTransmissive), 0.0f);
    EXPECT_TRUE(rays.occluded({5, 0, 0}, up));
    EXPECT_FALSE(rays.intersect({0, 0, 0}, up).hit) << "cards are invisible to camera rays";
}

}  // namespace
}  // namespace pleinair

namespace pleinair {
namespace {

// A mirror's ray (transmittance_depth) lets the same light through as a shadow ray, and finds
// the leaves where the light is taken: the cards' distances weighed by the depth each adds,
// over every card on the ray, even past where a shadow ray would stop as blocked.
TEST(Rays, AMirrorRayFindsWhereTheLeavesTakeItsLight) {
    StrokeShaderParams p;
    p.max_stroke_opacity = 0.9f;
    EdgeTable edge = make_edge_table(p.stroke_fullness);
    std::vector<StrokeCaster> stack;
    for (int k = 0; k < 14; ++k) stack.push_back(card({0, 2.0 + k, 0}, 0.05f + 0.06f * k, p));
    const glm::vec3 up(0, 1, 0);
    auto depth_of = [&](const StrokeCaster& c, float s, float t) {
        const float a = stroke_opacity(p, stroke_noise(c.noise, s, t, 1),
                                       edge_mask(edge, s, t, p.stroke_fullness));
        return -std::log2(std::max(1.0f - a, 1e-6f));
    };
    for (const size_t n : {size_t(2), stack.size()}) {
        RayScene rays;
        rays.add_casters(std::vector<StrokeCaster>(stack.begin(), stack.begin() + long(n)), p,
                         edge);
        rays.commit();
        int blocked = 0;
        for (float s : {0.3f, 0.5f, 0.62f}) {
            const float t = 0.45f;
            const glm::dvec3 o(2.0 * s - 1.0, 0, 2.0 * t - 1.0);
            double sum = 0, weighed = 0;
            for (size_t k = 0; k < n; ++k) {
                const double d = depth_of(stack[k], s, t);
                sum += d, weighed += d * stack[k].center.y;
            }
            ASSERT_GT(sum, 0.0);
            float distance = -1;
            const float got = rays.transmittance_depth(
                o, up, std::numeric_limits<float>::infinity(), nullptr, distance);
            EXPECT_EQ(got, rays.transmittance(o, up, ShadowMode::kTransmissive));
            EXPECT_NEAR(distance, weighed / sum, 0.02) << n << " cards, s " << s;
            if (sum >= 10.0) {  // a shadow ray stops as blocked part of the way up the stack
                EXPECT_EQ(got, 0.0f);
                ++blocked;
            }
        }
        if (n == stack.size()) {
            EXPECT_GT(blocked, 0) << "fourteen cards take all the light somewhere";
        }
    }
    // Nothing on the ray: all the light and no distance; an opaque surface: none.
    RayScene rays;
    rays.add_casters(stack, p, edge);
    rays.add_mesh(floor_quad(1), {5, 9, 0});
    rays.commit();
    float distance = -1;
    EXPECT_EQ(rays.transmittance_depth({3, 0, 3}, up, std::numeric_limits<float>::infinity(),
                                       nullptr, distance),
              1.0f);
    EXPECT_EQ(distance, 0.0f);
    EXPECT_EQ(rays.transmittance_depth({5, 0, 0}, up, std::numeric_limits<float>::infinity(),
                                       nullptr, distance),
              0.0f);
}

}  // namespace
}  // namespace pleinair
