// A compact all-quad polygon mesh (positions and corner indices) and the checks that say whether
// it is a closed, consistently oriented 2-manifold.
#pragma once

#include <cstdint>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>
#include <vector>

namespace pleinair {

struct QuadMesh {
    std::vector<glm::vec3> positions;
    std::vector<glm::uvec4> quads;  // corners counter-clockwise seen from outside
};

struct Bounds {
    glm::vec3 min{0.0f};
    glm::vec3 max{0.0f};
};

Bounds bounds_of(const std::vector<glm::vec3>& points);

// What check_mesh found; `ok()` is the invariant every generated mesh must satisfy.
struct MeshCheck {
    bool finite = true;             // no NaN or Inf coordinate
    bool indices_valid = true;      // every corner names an existing vertex, no repeated corner
    bool oriented = true;           // no directed edge used twice (consistent orientation)
    bool closed = true;             // every directed edge has its reverse
    bool manifold_vertices = true;  // each vertex's faces form a single fan
    bool no_isolated = true;        // every vertex is used by a face
    int folded_faces = 0;           // bow-tie quads: two corners turning against the face
    int euler = 0;                  // V - E + F; 2 for a closed genus-0 surface
    double min_face_area = 0;       // smallest face area (degenerate faces are ~0)

    bool ok() const {
        return finite && indices_valid && oriented && closed && manifold_vertices && no_isolated &&
               folded_faces == 0;
    }
};

MeshCheck check_mesh(const QuadMesh& mesh);

// Area-weighted vertex normals (for writers; the generators do not need them).
std::vector<glm::vec3> vertex_normals(const QuadMesh& mesh);

}  // namespace pleinair
