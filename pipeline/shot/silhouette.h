// Silhouette edges of a quad mesh seen from an eye (Doss, graftal imposters; file 002 of the
// seeds): the edges between a face turned towards the eye and one turned away, where
// (N1·V)(N2·V) <= 0, plus the open borders of faces that face it. Graftal imposters are extruded
// along them.
#pragma once

#include <cstdint>
#include <glm/vec3.hpp>
#include <vector>

#include "generators/quad_mesh.h"

namespace pleinair {

struct SilhouetteEdge {
    uint32_t a = 0, b = 0;    // vertices, in the order the front-facing face runs (CCW outside)
    uint32_t front_face = 0;  // the face turned towards the eye
};

// An edge of a quad mesh with the faces on either side: `face0` runs a -> b, `face1` runs
// b -> a, or is kBorder on an open border.
struct MeshEdge {
    static constexpr uint32_t kBorder = ~0u;
    uint32_t a = 0, b = 0;
    uint32_t face0 = 0, face1 = kBorder;
};

// Every edge once, sorted by (a, b) as face0 runs it: the adjacency a frame's silhouette test
// reads, built once per mesh. A directed edge used by more than one face (a mesh that is not
// oriented) is one edge, with the first face that runs it and the first twin; corners naming no
// vertex are skipped.
std::vector<MeshEdge> mesh_edges(const QuadMesh& mesh);

// Face normals as the cross product of the diagonals (unnormalised; 0 for a face naming no
// vertex).
std::vector<glm::dvec3> face_normals(const QuadMesh& mesh);

// Every silhouette edge once, sorted by (a, b). V is taken from the edge's midpoint to the eye,
// so the test holds under perspective; face normals are the cross product of the diagonals (a
// quad need not be planar). On a closed mesh the edges form closed loops: every vertex has an
// even number of them.
std::vector<SilhouetteEdge> silhouette_edges(const QuadMesh& mesh, const glm::dvec3& eye);
// The same from the adjacency and normals built once (mesh_edges, face_normals): per frame only
// two dot products an edge.
std::vector<SilhouetteEdge> silhouette_edges(const QuadMesh& mesh,
                                             const std::vector<MeshEdge>& edges,
                                             const std::vector<glm::dvec3>& normals,
                                             const glm::dvec3& eye);

}  // namespace pleinair
