// Catmull-Clark: exact values on a cube, topology, and agreement with OpenMesh's subdivider.
#include "generators/subdivide.h"

#include <gtest/gtest.h>

// OpenMesh's subdivider needs a mesh kernel included before it.
#include <OpenMesh/Core/Mesh/PolyMesh_ArrayKernelT.hh>
#include <OpenMesh/Tools/Subdivider/Uniform/CatmullClarkT.hh>
#include <algorithm>
#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/vec3.hpp>
#include <unordered_map>

#include "generators/tree_mesh.h"
#include "mesh_fixtures.h"
#include "test_util.h"

namespace pleinair {
namespace {

bool has_point(const QuadMesh& m, glm::vec3 p, float eps = 1e-6f) {
    return std::any_of(m.positions.begin(), m.positions.end(),
                       [&](const glm::vec3& q) { return glm::length(q - p) < eps; });
}

TEST(CatmullClark, CubeOneLevelHasTheKnownPoints) {
    QuadMesh r = catmull_clark(test::cube(1.0f), 1);
    EXPECT_EQ(r.positions.size(), 26u);  // 8 vertices + 12 edges + 6 faces
    EXPECT_EQ(r.quads.size(), 24u);
    // Corner: (Q + 2R + (n - 3) S) / n with n = 3: (1/3 + 4/3) / 3 = 5/9.
    EXPECT_TRUE(has_point(r, glm::vec3(5.0f / 9.0f)));
    EXPECT_TRUE(has_point(r, glm::vec3(-5.0f / 9.0f, 5.0f / 9.0f, -5.0f / 9.0f)));
    // Edge between (1,1,1) and (-1,1,1): (ends + face points (0,1,0), (0,0,1)) / 4.
    EXPECT_TRUE(has_point(r, glm::vec3(0.0f, 0.75f, 0.75f)));
    EXPECT_TRUE(has_point(r, glm::vec3(1.0f, 0.0f, 0.0f)));  // face point
    // Old vertices keep their indices.
    EXPECT_NEAR(r.positions[7].x, 5.0f / 9.0f, 1e-6f);
    MeshCheck c = check_mesh(r);
    EXPECT_TRUE(c.ok());
    EXPECT_EQ(c.euler, 2);
}

TEST(CatmullClark, ZeroLevelsIsTheIdentity) {
    QuadMesh m = test::cube(1.0f);
    QuadMesh r = catmull_clark(m, 0);
    EXPECT_EQ(r.positions, m.positions);
    EXPECT_EQ(r.quads, m.quads);
}

TEST(CatmullClark, RejectsAnOpenMesh) {
    QuadMesh m = test::cube(1.0f);
    m.quads.pop_back();
    EXPECT_THROW(catmull_clark(m, 1), std::invalid_argument);
}

// Later levels derive twins from the parent's; the result must equal subdividing one level at a
// time, where every level finds its twins from scratch.
TEST(CatmullClark, DerivedConnectivityEqualsLevelByLevel) {
    QuadMesh control = generate_tree(test::preset("oak"), 3).control;
    QuadMesh direct = catmull_clark(control, 3);
    QuadMesh stepwise = catmull_clark(catmull_clark(catmull_clark(control, 1), 1), 1);
    EXPECT_EQ(direct.quads, stepwise.quads);
    EXPECT_EQ(direct.positions, stepwise.positions);
    MeshCheck c = check_mesh(direct);
    EXPECT_TRUE(c.ok());
    EXPECT_EQ(c.euler, 2);
}

// Face f's pieces after L levels are faces f * 4^L .. (f + 1) * 4^L - 1: the first starts at
// f's first corner (old vertices keep their indices), and every piece's centroid lies nearer
// f's centroid than any other control face's does, on a tree's control mesh.
TEST(CatmullClark, FaceFsPiecesAreTheBlockAtFTimesFourToTheL) {
    const QuadMesh control = generate_tree(test::preset("oak"), 3).control;
    const int levels = 2;
    const QuadMesh render = catmull_clark(control, levels);
    const size_t per = size_t{1} << (2 * levels);
    ASSERT_EQ(render.quads.size(), control.quads.size() * per);
    auto centroid = [](const QuadMesh& m, size_t f) {
        glm::vec3 c(0.0f);
        for (int k = 0; k < 4; ++k) c += 0.25f * m.positions[m.quads[f][k]];
        return c;
    };
    std::vector<glm::vec3> centres(control.quads.size());
    for (size_t f = 0; f < control.quads.size(); ++f) centres[f] = centroid(control, f);
    size_t nearest_own = 0;
    for (size_t f = 0; f < control.quads.size(); ++f) {
        ASSERT_EQ(render.quads[f * per][0], control.quads[f][0]) << f;
        for (size_t k = 0; k < per; ++k) {
            const glm::vec3 c = centroid(render, f * per + k);
            size_t best = 0;
            for (size_t g = 1; g < centres.size(); ++g)
                if (glm::length(c - centres[g]) < glm::length(c - centres[best])) best = g;
            nearest_own += best == f;
        }
    }
    // Pieces at a face's corners can sit nearer a small neighbour (76% are nearest their own
    // here); a wrong block would leave almost none.
    EXPECT_GT(nearest_own, render.quads.size() * 2 / 3);
}

TEST(CatmullClark, AgreesWithOpenMeshCatmullClark) {
    using OmMesh = OpenMesh::PolyMesh_ArrayKernelT<>;
    QuadMesh control = generate_tree(test::preset("willow"), 5).control;
    OmMesh om;
    for (const auto& p : control.positions) om.add_vertex({p.x, p.y, p.z});
    for (const auto& q : control.quads)
        om.add_face(OmMesh::VertexHandle(int(q[0])), OmMesh::VertexHandle(int(q[1])),
                    OmMesh::VertexHandle(int(q[2])), OmMesh::VertexHandle(int(q[3])));
    OpenMesh::Subdivider::Uniform::CatmullClarkT<OmMesh> cc;
    cc.attach(om);
    cc(2);
    cc.detach();
    QuadMesh ours = catmull_clark(control, 2);
    ASSERT_EQ(om.n_vertices(), ours.positions.size());
    ASSERT_EQ(om.n_faces(), ours.quads.size());
    // Same points in another order: match each of ours to a point of theirs through a grid.
    const float cell = 1e-3f;
    auto cell_of = [&](const glm::vec3& p) { return glm::ivec3(glm::floor(p / cell)); };
    auto cell_key = [](glm::ivec3 c) {
        return (uint64_t(uint32_t(c.x)) * 73856093u) ^ (uint64_t(uint32_t(c.y)) * 19349663u) ^
               (uint64_t(uint32_t(c.z)) * 83492791u);
    };
    std::unordered_multimap<uint64_t, glm::vec3> grid;
    for (auto v : om.vertices()) {
        auto p = om.point(v);
        glm::vec3 q(p[0], p[1], p[2]);
        grid.emplace(cell_key(cell_of(q)), q);
    }
    size_t unmatched = 0;
    for (const auto& p : ours.positions) {
        bool found = false;
        glm::ivec3 c = cell_of(p);
        for (int dx = -1; dx <= 1 && !found; ++dx)
            for (int dy = -1; dy <= 1 && !found; ++dy)
                for (int dz = -1; dz <= 1 && !found; ++dz) {
                    auto range = grid.equal_range(cell_key(c + glm::ivec3(dx, dy, dz)));
                    for (auto it = range.first; it != range.second && !found; ++it)
                        found = glm::length(it->second - p) < 1e-4f;
                }
        unmatched += !found;
    }
    EXPECT_EQ(unmatched, 0u);
}

}  // namespace
}  // namespace pleinair
