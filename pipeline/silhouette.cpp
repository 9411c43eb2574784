// Silhouette edges by the sign of N·V on either side of each edge.
#include "pipeline/silhouette.h"

#include <algorithm>
#include <glm/geometric.hpp>

namespace pleinair {

std::vector<SilhouetteEdge> silhouette_edges(const QuadMesh& mesh, const glm::dvec3& eye) {
    const size_t nv = mesh.positions.size();
    std::vector<glm::dvec3> normal(mesh.quads.size());
    for (size_t f = 0; f < mesh.quads.size(); ++f) {
        const glm::uvec4& q = mesh.quads[f];
        if (q.x >= nv || q.y >= nv || q.z >= nv || q.w >= nv) continue;  // left at 0: edge-on
        const glm::dvec3 d1 = glm::dvec3(mesh.positions[q.z]) - glm::dvec3(mesh.positions[q.x]);
        const glm::dvec3 d2 = glm::dvec3(mesh.positions[q.w]) - glm::dvec3(mesh.positions[q.y]);
        normal[f] = glm::cross(d1, d2);
    }
    // Directed edges (from, to, face), sorted so an edge's reverse is found by search.
    struct Half {
        uint32_t from, to, face;
    };
    std::vector<Half> half;
    half.reserve(mesh.quads.size() * 4);
    for (uint32_t f = 0; f < mesh.quads.size(); ++f)
        for (int c = 0; c < 4; ++c) {
            const uint32_t a = mesh.quads[f][c], b = mesh.quads[f][(c + 1) % 4];
            if (a < nv && b < nv) half.push_back({a, b, f});
        }
    auto less = [](const Half& x, const Half& y) {
        return x.from != y.from ? x.from < y.from : x.to != y.to ? x.to < y.to : x.face < y.face;
    };
    std::sort(half.begin(), half.end(), less);
    auto facing = [&](uint32_t face, uint32_t a, uint32_t b) {
        const glm::dvec3 mid =
            0.5 * (glm::dvec3(mesh.positions[a]) + glm::dvec3(mesh.positions[b]));
        return glm::dot(normal[face], eye - mid);
    };
    std::vector<SilhouetteEdge> out;
    for (const Half& h : half) {
        const double here = facing(h.face, h.from, h.to);
        auto it = std::lower_bound(half.begin(), half.end(), Half{h.to, h.from, 0}, less);
        const bool has_twin = it != half.end() && it->from == h.to && it->to == h.from;
        if (!has_twin) {
            if (here > 0) out.push_back({h.from, h.to, h.face});  // a border of a front face
            continue;
        }
        const double there = facing(it->face, h.from, h.to);
        if (here * there > 0) continue;
        // Once per edge: from the side that faces the eye (the first of the two when both are
        // edge-on or both face it, by face index).
        const bool mine = here > there || (here == there && h.face < it->face);
        if (mine) out.push_back({h.from, h.to, h.face});
    }
    std::sort(out.begin(), out.end(), [](const SilhouetteEdge& x, const SilhouetteEdge& y) {
        return x.a != y.a ? x.a < y.a : x.b < y.b;
    });
    return out;
}

}  // namespace pleinair
