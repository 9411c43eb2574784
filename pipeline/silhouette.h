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

// Every silhouette edge once, sorted by (a, b). V is taken from the edge's midpoint to the eye,
// so the test holds under perspective; face normals are the cross product of the diagonals (a
// quad need not be planar). On a closed mesh the edges form closed loops: every vertex has an
// even number of them.
std::vector<SilhouetteEdge> silhouette_edges(const QuadMesh& mesh, const glm::dvec3& eye);

}  // namespace pleinair
