// Terrain heightfields and the surface-stroke builder: shapes, ranges, determinism, hard cases.
#include "generators/terrain.h"

#include <gtest/gtest.h>

#include <cmath>
#include <glm/geometric.hpp>
#include <set>

#include "generators/rock.h"
#include "generators/scatter.h"
#include "generators/surface_strokes.h"
#include "test_util.h"

namespace pleinair {
namespace {

TerrainParams two_hills() {
    TerrainParams p;
    p.hills = {{"near", {-30, 10}, 25, 8}, {"far", {40, -50}, 40, 15}};
    p.resolution = 65;
    return p;
}

TEST(Terrain, HillsRiseToTheirHeightAndThePlainStaysFlat) {
    TerrainParams p = two_hills();
    p.noise_amplitude = 0;
    EXPECT_NEAR(terrain_height(p, 1, -30, 10), 8.0, 1e-9);
    EXPECT_NEAR(terrain_height(p, 1, 40, -50), 15.0, 1e-9);
    EXPECT_NEAR(terrain_height(p, 1, -30 + 12.5, 10), 4.0, 1e-9);  // half way: half height
    EXPECT_EQ(terrain_height(p, 1, 90, 90), 0.0);
    // Noise stays within its amplitude.
    p.noise_amplitude = 0.4;
    for (int i = 0; i < 200; ++i) {
        double h = terrain_height(p, 3, 90 - 0.37 * i, 90);
        EXPECT_LE(std::abs(h), 0.2 + 1e-9);
    }
}

TEST(Terrain, GridIsDeterministicFacesUpAndSeedsDiffer) {
    TerrainParams p = two_hills();
    GridSurface a = generate_terrain(p, 7), b = generate_terrain(p, 7), c = generate_terrain(p, 8);
    ASSERT_EQ(a.positions.size(), 65u * 65u);
    EXPECT_EQ(a.positions, b.positions);
    EXPECT_NE(a.positions, c.positions);
    QuadMesh m = grid_mesh(a);
    EXPECT_EQ(m.quads.size(), 64u * 64u);
    for (int k = 0; k < 100; ++k) {
        glm::vec3 pos, n;
        eval_grid(a, k / 99.0, (k * 37 % 100) / 99.0, pos, n);
        EXPECT_NEAR(glm::length(n), 1.0f, 1e-5f);
        EXPECT_GT(n.y, 0.3f);  // gentle hills face up
    }
}

TEST(Terrain, FarFromTheOriginAndDegenerateInputsStayFinite) {
    TerrainParams p = two_hills();
    p.min = {1e5, 1e5};
    p.max = {1e5 + 200, 1e5 + 200};
    p.hills = {{"h", {1e5 + 100, 1e5 + 100}, 30, 10}, {"zero", {1e5, 1e5}, 0, 5}};
    p.resolution = 1;  // becomes 2 x 2
    GridSurface g = generate_terrain(p, 1);
    EXPECT_EQ(g.nu, 2);
    for (const auto& q : g.positions) EXPECT_TRUE(std::isfinite(q.y));
    p.resolution = 33;
    g = generate_terrain(p, 1);
    float top = -1e9f;
    for (const auto& q : g.positions) top = std::max(top, q.y);
    EXPECT_NEAR(top, 10.0f, 0.5f);
    // A vertical cliff: degenerate cells give +y, not NaN.
    GridSurface flat{2, 2, {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}, {0, 0, 0}}};
    glm::vec3 pos, n;
    eval_grid(flat, 0.5, 0.5, pos, n);
    EXPECT_EQ(n, glm::vec3(0, 1, 0));
}

TEST(SurfaceStrokes, CountsRangesAndTheDetailSplit) {
    TerrainParams tp = two_hills();
    GridSurface g = generate_terrain(tp, 2);
    SurfaceStrokeParams p;
    p.particle_spans_u = 12, p.particle_spans_v = 9, p.particles_per_cluster = 7;
    p.displacement_height = 0.3;
    p.material = 3;
    SurfaceParticles s;
    emit_surface_strokes(g, p, 5, 1, s);
    ASSERT_EQ(s.size(), 12u * 9u * 7u);
    std::set<float> labels;
    size_t detail = 0;
    for (size_t i = 0; i < s.size(); ++i) {
        EXPECT_GE(s.height(i), 0.0f);
        EXPECT_LE(s.height(i), 1.0f);
        EXPECT_NEAR(glm::length(s.normal(i)), 1.0f, 1e-5f);
        EXPECT_NEAR(glm::length(s.random_normal(i)), 1.0f, 1e-5f);
        EXPECT_GE(s.uv(i).x, 0.0f);
        EXPECT_LE(s.uv(i).y, 1.0f);
        EXPECT_EQ(s.material[i], 3u);
        labels.insert(s.label[i]);
        // The particle sits displacement * normal off the surface point at its uv.
        glm::vec3 on, n;
        eval_grid(g, s.uv(i).x, s.uv(i).y, on, n);
        float d = glm::dot(s.position[i] - on, n);
        EXPECT_NEAR(d, (s.height(i) * 2 - 1) * 0.3f, 1e-3f);
        if (s.height(i) > p.detail_threshold) {
            ++detail;
            EXPECT_GE(s.fade_begin(i), 0.0f);
            EXPECT_LE(s.fade_end(i), 1.0f + 1e-6f);
            EXPECT_GE(s.fade_end(i) - s.fade_begin(i), p.min_fade_length - 1e-6);
        } else {
            EXPECT_GT(s.fade_begin(i), 1.0f);  // base strokes never fade
        }
    }
    EXPECT_EQ(labels.size(), s.size());
    // Heights are uniform: about 40% above 0.6.
    EXPECT_NEAR(double(detail) / s.size(), 0.4, 0.06);
}

// Particles are packed (36 bytes): unit vectors to within 1e-4 rad, 0..1 values to within
// half a step of 1/65534 with 0, 0.5 and 1 exact.
TEST(SurfaceStrokes, PackedValuesRoundTrip) {
    Rng rng = make_rng(9, Purpose::kSurface, 77);
    for (int i = 0; i < 20000; ++i) {
        double z = rand_range(rng, -1.0, 1.0), a = rand_range(rng, 0.0, 2 * M_PI);
        double r = std::sqrt(1 - z * z);
        glm::vec3 n(float(r * std::cos(a)), float(r * std::sin(a)), float(z));
        if (i < 6) n = glm::vec3(0.0f), n[i % 3] = i < 3 ? 1.0f : -1.0f;  // the axes
        glm::vec3 back = decode_unit(encode_unit(n));
        ASSERT_NEAR(glm::length(back), 1.0f, 1e-6f);
        ASSERT_LT(glm::length(back - n), 1e-4f)
            << n.x << " " << n.y << " " << n.z;  // chord ~ angle
        float x = float(rand1(rng));
        ASSERT_NEAR(decode_unorm(encode_unorm(x)), x, 0.5f / 65534.0f + 1e-7f);
    }
    for (float x : {0.0f, 0.5f, 1.0f}) EXPECT_EQ(decode_unorm(encode_unorm(x)), x);
    EXPECT_EQ(decode_unorm(encode_unorm(-3.0f)), 0.0f);
    EXPECT_EQ(decode_unorm(encode_unorm(7.0f)), 1.0f);
    EXPECT_LT(glm::length(decode_unit(encode_unit(glm::vec3(0.0f))) - glm::vec3(0, 1, 0)), 1e-4f);
    // A particle's real footprint, read from SurfaceParticles itself: one element of each of its
    // arrays, every array as long as the particle count. Packing is what keeps it at 36 bytes.
    SurfaceParticles emitted;
    emit_surface_strokes(generate_terrain(two_hills(), 2), SurfaceStrokeParams{}, 5, 1, emitted);
    ASSERT_GT(emitted.size(), 0u);
    size_t bytes = 0, arrays = 0;
    emitted.each_array([&](auto& a) {
        bytes += sizeof(a[0]);
        ++arrays;
        EXPECT_EQ(a.size(), emitted.size());
    });
    EXPECT_EQ(arrays, 8u);
    EXPECT_EQ(bytes, 36u);
}

TEST(SurfaceStrokes, SectionsAreKeyedAndHardCasesEmitSafely) {
    GridSurface g = generate_terrain(two_hills(), 2);
    SurfaceStrokeParams p;
    SurfaceParticles a, b;
    emit_surface_strokes(g, p, 5, 1, a);
    emit_surface_strokes(g, p, 5, 1, b);
    EXPECT_EQ(a.position, b.position);
    SurfaceParticles other;
    emit_surface_strokes(g, p, 5, 2, other);  // another surface key: other strokes
    EXPECT_NE(a.position, other.position);
    p.particles_per_cluster = 0;
    SurfaceParticles none;
    emit_surface_strokes(g, p, 5, 1, none);
    EXPECT_EQ(none.size(), 0u);
    p.particles_per_cluster = 3;
    p.displacement_height = 0;
    SurfaceParticles flat;
    emit_surface_strokes(g, p, 5, 1, flat);
    for (size_t i = 0; i < flat.size(); ++i) EXPECT_EQ(flat.height(i), 0.5f);
    GridSurface empty;
    emit_surface_strokes(empty, p, 5, 1, none);
    EXPECT_EQ(none.size(), 0u);
}

TEST(Rock, ClosedOrientedDeterministicAndVaried) {
    RockParams p;
    QuadMesh a = generate_rock(p, 3, {5, 0, -2}), b = generate_rock(p, 3, {5, 0, -2});
    QuadMesh c = generate_rock(p, 4, {5, 0, -2});
    EXPECT_EQ(a.positions, b.positions);
    EXPECT_NE(a.positions, c.positions);
    EXPECT_EQ(a.quads.size(), 6u * 64u);
    MeshCheck check = check_mesh(a);
    EXPECT_TRUE(check.ok());
    EXPECT_EQ(check.euler, 2);
    EXPECT_GT(check.min_face_area, 0.0);
    // Inside its scaled radius, squashed vertically, centred where asked.
    Bounds bb = bounds_of(a.positions);
    EXPECT_LE(bb.max.y, 0.6f + 1e-4f);
    EXPECT_GE(bb.min.x, 5.0f - 1.0f - 1e-4f);
    EXPECT_GT(bb.max.x - bb.min.x, 2 * 0.6f);  // roughness removes at most 35%
    // Outward orientation: the face normals point away from the centre.
    for (const auto& q : a.quads) {
        glm::vec3 n = glm::cross(a.positions[q[2]] - a.positions[q[0]],
                                 a.positions[q[3]] - a.positions[q[1]]);
        glm::vec3 mid =
            0.25f * (a.positions[q[0]] + a.positions[q[1]] + a.positions[q[2]] + a.positions[q[3]]);
        EXPECT_GT(glm::dot(n, mid - glm::vec3(5, 0, -2)), 0.0f);
    }
}

TEST(Rock, DegenerateParametersStillGiveAClosedFiniteMesh) {
    RockParams p;
    p.radius = 0;
    p.roughness = 5;            // clamped to 0.9
    p.scale = {0, -1, 1};       // clamped to a sliver, mirrored scale taken as positive
    p.subdivision_levels = 99;  // clamped
    QuadMesh m = generate_rock(p, 1, {1e5, 0, 1e5});
    MeshCheck check = check_mesh(m);
    EXPECT_TRUE(check.finite);
    EXPECT_TRUE(check.closed);
    EXPECT_TRUE(check.oriented);
    p = RockParams{};
    p.roughness = 0;
    p.subdivision_levels = 0;
    m = generate_rock(p, 1, {0, 0, 0});
    EXPECT_EQ(m.quads.size(), 6u);
    EXPECT_TRUE(check_mesh(m).ok());
}

TEST(Scatter, PoissonSpacingInsideTheRegionWithTheFamilyMix) {
    TerrainParams t;  // flat with gentle noise
    ScatterParams p;
    p.center = {10, -20};
    p.radius = 40;
    p.min_distance = 5;
    p.weights = {3, 1};
    auto trees = scatter_trees(t, 1, p, 9, 0);
    ASSERT_GT(trees.size(), 100u);
    size_t first = 0;
    for (size_t i = 0; i < trees.size(); ++i) {
        const auto& a = trees[i];
        EXPECT_LE(std::hypot(a.position.x - 10, a.position.z + 20), 40 + 1e-9);
        EXPECT_NEAR(a.position.y, terrain_height(t, 1, a.position.x, a.position.z), 1e-12);
        first += a.family == 0;
        EXPECT_LT(a.family, 2u);
        for (size_t j = 0; j < i; ++j)
            EXPECT_GE(
                std::hypot(a.position.x - trees[j].position.x, a.position.z - trees[j].position.z),
                5.0 - 1e-9);
    }
    EXPECT_NEAR(double(first) / trees.size(), 0.75, 0.1);
    auto again = scatter_trees(t, 1, p, 9, 0);
    ASSERT_EQ(again.size(), trees.size());
    for (size_t i = 0; i < trees.size(); ++i) {
        EXPECT_EQ(again[i].position, trees[i].position);
        EXPECT_EQ(again[i].seed, trees[i].seed);
    }
    auto other = scatter_trees(t, 1, p, 9, 1);  // another group: another placement
    EXPECT_NE(other.front().seed, trees.front().seed);
}

// A path and a glade stay free of trunks; the trees elsewhere are the ones planted without them
// (a clearing only withholds, the draws stay aligned).
TEST(Scatter, ClearingsHoldNoTrunkAndMoveNoOtherTree) {
    TerrainParams t;
    ScatterParams p;
    p.radius = 60;
    p.min_distance = 4;
    const std::vector<ScatteredTree> open = scatter_trees(t, 1, p, 5, 0);
    p.clearings = {{{-50, 5}, {40, -5}, 3.5}, {{20, 30}, {20, 30}, 8}};
    const std::vector<ScatteredTree> cleared = scatter_trees(t, 1, p, 5, 0);
    ASSERT_GT(open.size(), 300u);
    size_t inside = 0;
    for (const ScatteredTree& a : open) {
        const glm::dvec2 q(a.position.x, a.position.z);
        inside +=
            clearing_distance(p.clearings[0], q) < 3.5 || clearing_distance(p.clearings[1], q) < 8;
    }
    EXPECT_GT(inside, 20u);
    EXPECT_EQ(cleared.size(), open.size() - inside);
    size_t k = 0;
    for (const ScatteredTree& a : cleared) {
        const glm::dvec2 q(a.position.x, a.position.z);
        EXPECT_GE(clearing_distance(p.clearings[0], q), 3.5);
        EXPECT_GE(clearing_distance(p.clearings[1], q), 8.0);
        while (k < open.size() && open[k].seed != a.seed) ++k;
        ASSERT_LT(k, open.size()) << "a tree planted only with the clearings";
        EXPECT_EQ(open[k].position, a.position);
    }
    // A point on the segment, at its end and past it.
    EXPECT_DOUBLE_EQ(clearing_distance({{0, 0}, {10, 0}, 1}, {5, 2}), 2.0);
    EXPECT_DOUBLE_EQ(clearing_distance({{0, 0}, {10, 0}, 1}, {13, 4}), 5.0);
    EXPECT_DOUBLE_EQ(clearing_distance({{3, 3}, {3, 3}, 1}, {6, 7}), 5.0);
}

TEST(Scatter, NoTreeOnSteepSlopesOrInWater) {
    TerrainParams t;
    t.noise_amplitude = 0;
    t.hills = {{"steep", {0, 0}, 20, 30}};  // slopes up to about 67 degrees
    ScatterParams p;
    p.radius = 35;
    p.min_distance = 3;
    p.max_slope = 30;
    auto trees = scatter_trees(t, 1, p, 4, 0);
    ASSERT_GT(trees.size(), 20u);  // the plain around the hill and its gentle top
    for (const auto& a : trees) {
        double h = 0.01;
        double dx = (terrain_height(t, 1, a.position.x + h, a.position.z) -
                     terrain_height(t, 1, a.position.x - h, a.position.z)) /
                    (2 * h);
        double dz = (terrain_height(t, 1, a.position.x, a.position.z + h) -
                     terrain_height(t, 1, a.position.x, a.position.z - h)) /
                    (2 * h);
        EXPECT_LE(std::atan(std::hypot(dx, dz)) * 180 / M_PI, 31.0);
    }
    // Water over everything, or no slope allowed on a hill: no room for trees.
    p.water_level = 100;
    EXPECT_TRUE(scatter_trees(t, 1, p, 4, 0).empty());
    p.water_level = -1e30;
    p.center = {10, 0};  // on the hill's flank
    p.radius = 3;
    p.max_slope = 0;
    EXPECT_TRUE(scatter_trees(t, 1, p, 4, 0).empty());
    // Degenerate inputs.
    p.min_distance = 0;
    EXPECT_TRUE(scatter_trees(t, 1, p, 4, 0).empty());
    p.min_distance = 1e-9;
    p.radius = 1e6;
    EXPECT_TRUE(scatter_trees(t, 1, p, 4, 0).empty());
    p = ScatterParams{};
    p.radius = 0;  // a single point
    EXPECT_EQ(scatter_trees(TerrainParams{}, 1, p, 4, 0).size(), 1u);
}

}  // namespace
}  // namespace pleinair
