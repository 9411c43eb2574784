// Silhouette edges of known meshes: a cube from a corner and face on, an open box's rim, and a
// generated rock whose silhouette closes into loops from any eye.
#include "pipeline/shot/silhouette.h"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>
#include <map>

#include "generators/rng.h"
#include "generators/rock.h"
#include "test_util.h"

namespace pleinair {
namespace {

// Silhouette degree of each vertex.
std::map<uint32_t, int> degrees(const std::vector<SilhouetteEdge>& edges) {
    std::map<uint32_t, int> d;
    for (const SilhouetteEdge& e : edges) ++d[e.a], ++d[e.b];
    return d;
}

TEST(Silhouette, ACubeSeenFromACornerIsAHexagon) {
    ASSERT_TRUE(check_mesh(test::unit_cube()).ok());
    const auto edges = silhouette_edges(test::unit_cube(), {3, 2.5, 4});
    ASSERT_EQ(edges.size(), 6u);
    const auto d = degrees(edges);
    EXPECT_EQ(d.size(), 6u);  // every corner but the nearest and the farthest
    for (const auto& [v, n] : d) EXPECT_EQ(n, 2) << v;
    EXPECT_EQ(d.count(7), 0u);  // (+,+,+), nearest the eye: inside the outline
    EXPECT_EQ(d.count(0), 0u);  // (-,-,-), hidden behind
    for (const SilhouetteEdge& e : edges) {
        // The face that owns the edge faces the eye.
        const glm::uvec4 q = test::unit_cube().quads[e.front_face];
        const glm::vec3 n =
            glm::cross(test::unit_cube().positions[q.z] - test::unit_cube().positions[q.x],
                       test::unit_cube().positions[q.w] - test::unit_cube().positions[q.y]);
        EXPECT_GT(glm::dot(glm::dvec3(n), glm::dvec3(3, 2.5, 4)), 0.0);
    }
}

TEST(Silhouette, ACubeSeenFaceOnInPerspectiveIsItsFrontSquare) {
    // From straight in front the side faces turn away (perspective), so the outline is the
    // front face's four edges.
    const auto edges = silhouette_edges(test::unit_cube(), {0, 0, 10});
    ASSERT_EQ(edges.size(), 4u);
    for (const SilhouetteEdge& e : edges) EXPECT_EQ(e.front_face, 1u);  // the +z face
    // From infinitely far (orthographic in the limit) nothing changes but the distance.
    EXPECT_EQ(silhouette_edges(test::unit_cube(), {0, 0, 1e6}).size(), 4u);
}

TEST(Silhouette, AnOpenBoxShowsTheRimOfTheWallThatFacesTheEye) {
    QuadMesh box = test::unit_cube();
    box.quads.erase(box.quads.begin() + 3);  // no top (+y): four borders at y = 0.5
    // From beside, the +z wall faces the eye and its top border has no face beyond it.
    int rim = 0;
    for (const SilhouetteEdge& e : silhouette_edges(box, {0.2, 0.3, 10}))
        rim += box.positions[e.a].y > 0 && box.positions[e.b].y > 0;
    EXPECT_EQ(rim, 1);
    // From straight above the opening every outside face turns away: nothing is outlined (the
    // inside has no faces of its own in a one-sided mesh).
    EXPECT_TRUE(silhouette_edges(box, {0.1, 10, 0.2}).empty());
}

TEST(Silhouette, ARocksSilhouetteClosesIntoLoopsFromEveryEye) {
    const QuadMesh rock = generate_rock(RockParams{}, 11, {0, 0, 0});
    ASSERT_TRUE(check_mesh(rock).ok());
    Rng rng = make_rng(3, Purpose::kSurface);
    for (int i = 0; i < 20; ++i) {
        const glm::dvec3 eye(rand_range(rng, -6, 6), rand_range(rng, -3, 6),
                             rand_range(rng, -6, 6));
        if (glm::length(eye) < 2) continue;  // inside the rock: no outline to speak of
        const auto edges = silhouette_edges(rock, eye);
        EXPECT_GT(edges.size(), 8u);
        EXPECT_LT(edges.size(), rock.quads.size() * 2);
        for (const auto& [v, n] : degrees(edges)) EXPECT_EQ(n % 2, 0) << "vertex " << v;
        // Same eye, same edges: a function of (mesh, eye).
        EXPECT_EQ(silhouette_edges(rock, eye).size(), edges.size());
    }
}

TEST(Silhouette, BrokenIndicesAndDegenerateFacesDoNotCrash) {
    QuadMesh m = test::unit_cube();
    m.quads.push_back({0, 1, 99, 2});  // an index past the end: skipped
    m.positions[3] = m.positions[1] = glm::vec3(0.5f, -0.5f, -0.5f);  // a collapsed face
    const auto edges = silhouette_edges(m, {3, 2.5, 4});
    for (const SilhouetteEdge& e : edges) {
        EXPECT_LT(e.a, m.positions.size());
        EXPECT_LT(e.b, m.positions.size());
    }
    EXPECT_TRUE(silhouette_edges(QuadMesh{}, {0, 0, 1}).empty());
}

}  // namespace
}  // namespace pleinair
