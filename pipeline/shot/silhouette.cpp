// Silhouette edges by the sign of N·V on either side of each edge, from an edge list built once.
#include "pipeline/shot/silhouette.h"

#include <algorithm>
#include <glm/geometric.hpp>

namespace pleinair {

std::vector<glm::dvec3> face_normals(const QuadMesh& mesh) {
    const size_t nv = mesh.positions.size();
    std::vector<glm::dvec3> normal(mesh.quads.size(), glm::dvec3(0.0));
    for (size_t f = 0; f < mesh.quads.size(); ++f) {
        const glm::uvec4& q = mesh.quads[f];
        if (q.x >= nv || q.y >= nv || q.z >= nv || q.w >= nv) continue;  // left at 0: edge-on
        const glm::dvec3 d1 = glm::dvec3(mesh.positions[q.z]) - glm::dvec3(mesh.positions[q.x]);
        const glm::dvec3 d2 = glm::dvec3(mesh.positions[q.w]) - glm::dvec3(mesh.positions[q.y]);
        normal[f] = glm::cross(d1, d2);
    }
    return normal;
}

std::vector<MeshEdge> mesh_edges(const QuadMesh& mesh) {
    const size_t nv = mesh.positions.size();
    // Directed edges (from, to, face), sorted so an edge's reverse is found by search.
    struct Half {
        uint32_t from, to, face;
    };
    std::vector<Half> half;
    half.reserve(mesh.quads.size() * 4);
    for (uint32_t f = 0; f < mesh.quads.size(); ++f)
        for (int c = 0; c < 4; ++c) {
            const uint32_t a = mesh.quads[f][c], b = mesh.quads[f][(c + 1) % 4];
            if (a < nv && b < nv && a != b) half.push_back({a, b, f});
        }
    auto less = [](const Half& x, const Half& y) {
        return x.from != y.from ? x.from < y.from : x.to != y.to ? x.to < y.to : x.face < y.face;
    };
    std::sort(half.begin(), half.end(), less);
    std::vector<MeshEdge> out;
    out.reserve(half.size() / 2 + 1);
    for (size_t k = 0; k < half.size(); ++k) {
        const Half& h = half[k];
        // A directed edge two faces run (a mesh not consistently oriented): one edge.
        if (k > 0 && half[k - 1].from == h.from && half[k - 1].to == h.to) continue;
        auto it = std::lower_bound(half.begin(), half.end(), Half{h.to, h.from, 0}, less);
        const bool has_twin = it != half.end() && it->from == h.to && it->to == h.from;
        // Once per edge: a border from its one face; a shared edge from the smaller-numbered
        // vertex's side, with the first face found on each side.
        if (!has_twin) {
            out.push_back({h.from, h.to, h.face, MeshEdge::kBorder});
        } else if (h.from < h.to) {
            out.push_back({h.from, h.to, h.face, it->face});
        }
    }
    return out;
}

std::vector<SilhouetteEdge> silhouette_edges(const QuadMesh& mesh,
                                             const std::vector<MeshEdge>& edges,
                                             const std::vector<glm::dvec3>& normal,
                                             const glm::dvec3& eye) {
    std::vector<SilhouetteEdge> out;
    for (const MeshEdge& e : edges) {
        const glm::dvec3 mid =
            0.5 * (glm::dvec3(mesh.positions[e.a]) + glm::dvec3(mesh.positions[e.b]));
        const double here = glm::dot(normal[e.face0], eye - mid);
        if (e.face1 == MeshEdge::kBorder) {
            if (here > 0) out.push_back({e.a, e.b, e.face0});  // a border of a front face
            continue;
        }
        const double there = glm::dot(normal[e.face1], eye - mid);
        if (here * there > 0) continue;
        // From the side that faces the eye (the first of the two by face index when both are
        // edge-on), in the order that face runs it.
        const bool first = here > there || (here == there && e.face0 < e.face1);
        if (first)
            out.push_back({e.a, e.b, e.face0});
        else
            out.push_back({e.b, e.a, e.face1});
    }
    std::sort(out.begin(), out.end(), [](const SilhouetteEdge& x, const SilhouetteEdge& y) {
        return x.a != y.a ? x.a < y.a : x.b < y.b;
    });
    return out;
}

std::vector<SilhouetteEdge> silhouette_edges(const QuadMesh& mesh, const glm::dvec3& eye) {
    return silhouette_edges(mesh, mesh_edges(mesh), face_normals(mesh), eye);
}

}  // namespace pleinair
