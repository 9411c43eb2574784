// check_mesh must pass closed manifolds and catch each way a mesh can be broken.
#include "generators/quad_mesh.h"

#include <gtest/gtest.h>

#include <cmath>
#include <glm/geometric.hpp>

#include "mesh_fixtures.h"

namespace pleinair {
namespace {

TEST(QuadMesh, CubeIsAClosedGenusZeroManifold) {
    MeshCheck c = check_mesh(test::cube(1.0f));
    EXPECT_TRUE(c.ok());
    EXPECT_EQ(c.euler, 2);
    EXPECT_NEAR(c.min_face_area, 4.0, 1e-6);
}

TEST(QuadMesh, MissingFaceIsNotClosed) {
    QuadMesh m = test::cube(1.0f);
    m.quads.pop_back();
    MeshCheck c = check_mesh(m);
    EXPECT_FALSE(c.closed);
    EXPECT_FALSE(c.ok());
}

TEST(QuadMesh, FlippedFaceIsNotOriented) {
    QuadMesh m = test::cube(1.0f);
    std::swap(m.quads[2][1], m.quads[2][3]);
    EXPECT_FALSE(check_mesh(m).oriented);
}

TEST(QuadMesh, BowTieIsFoldedButConcaveIsNot) {
    QuadMesh m = test::cube(1.0f);
    std::swap(m.positions[2], m.positions[3]);  // face {0, 2, 3, 1} crosses itself
    EXPECT_GT(check_mesh(m).folded_faces, 0);
    EXPECT_FALSE(check_mesh(m).ok());
    QuadMesh dent;  // one quad, concave at its third corner
    dent.positions = {{-1, -1, 0}, {1, -1, 0}, {-0.3f, -0.3f, 0}, {-1, 1, 0}};
    dent.quads = {{0, 1, 2, 3}};
    EXPECT_EQ(check_mesh(dent).folded_faces, 0);
    QuadMesh bow = dent;  // edges 0-1 and 2-3 cross
    bow.positions = {{-1, -1, 0}, {1, 1, 0}, {1, -1, 0}, {-1, 1, 0}};
    EXPECT_EQ(check_mesh(bow).folded_faces, 1);
}

TEST(QuadMesh, IsolatedVertexAndNaNAreCaught) {
    QuadMesh m = test::cube(1.0f);
    m.positions.push_back(glm::vec3(5.0f));
    EXPECT_FALSE(check_mesh(m).no_isolated);
    m = test::cube(1.0f);
    m.positions[0].x = std::nanf("");
    EXPECT_FALSE(check_mesh(m).finite);
}

TEST(QuadMesh, TwoCubesSharingOneVertexArePinched) {
    QuadMesh a = test::cube(1.0f), b = test::cube(1.0f);
    // Move b so that its corner 0 lands on a's corner 6 (the opposite corner), then weld.
    glm::vec3 shift = a.positions[6] - b.positions[0];
    auto base = static_cast<uint32_t>(a.positions.size());
    for (auto& p : b.positions) a.positions.push_back(p + shift);
    for (auto q : b.quads) {
        for (int c = 0; c < 4; ++c) q[c] = q[c] == 0 ? 6 : q[c] + base;
        a.quads.push_back(q);
    }
    a.positions.erase(a.positions.begin() + base);  // b's corner 0 is now a's 6
    for (auto& q : a.quads)
        for (int c = 0; c < 4; ++c)
            if (q[c] > base) --q[c];
    MeshCheck c = check_mesh(a);
    EXPECT_TRUE(c.closed);
    EXPECT_FALSE(c.manifold_vertices);
}

TEST(QuadMesh, CubeNormalsPointOutward) {
    QuadMesh m = test::cube(2.0f);
    auto n = vertex_normals(m);
    for (size_t i = 0; i < n.size(); ++i) {
        EXPECT_NEAR(glm::length(n[i]), 1.0f, 1e-6f);
        EXPECT_GT(glm::dot(n[i], m.positions[i]), 0.0f);
    }
}

}  // namespace
}  // namespace pleinair
