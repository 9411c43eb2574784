// Closed-manifold checks and normals for QuadMesh.
#include "generators/quad_mesh.h"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <limits>

namespace pleinair {

Bounds bounds_of(const std::vector<glm::vec3>& points) {
    Bounds b;
    if (points.empty()) return b;
    b.min = b.max = points[0];
    for (const auto& p : points) {
        b.min = glm::min(b.min, p);
        b.max = glm::max(b.max, p);
    }
    return b;
}

namespace {

double quad_area(const QuadMesh& m, const glm::uvec4& q) {
    glm::dvec3 p[4];
    for (int c = 0; c < 4; ++c) p[c] = glm::dvec3(m.positions[q[c]]);
    // Half the norm of the sum of cross products (Newell); exact for planar quads.
    glm::dvec3 n = glm::cross(p[2] - p[0], p[3] - p[1]);
    return 0.5 * glm::length(n);
}

}  // namespace

MeshCheck check_mesh(const QuadMesh& m) {
    MeshCheck r;
    const auto nv = static_cast<uint32_t>(m.positions.size());
    for (const auto& p : m.positions)
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) r.finite = false;
    for (const auto& q : m.quads)
        for (int c = 0; c < 4; ++c)
            if (q[c] >= nv || q[c] == q[(c + 1) % 4] || q[c] == q[(c + 2) % 4]) {
                r.indices_valid = false;
                return r;
            }

    // Directed half-edges sorted by (from, to); each is (from, to, face*4 + corner).
    struct He {
        uint32_t a, b, fc;
    };
    std::vector<He> hes;
    hes.reserve(m.quads.size() * 4);
    for (uint32_t f = 0; f < m.quads.size(); ++f)
        for (uint32_t c = 0; c < 4; ++c)
            hes.push_back({m.quads[f][c], m.quads[f][(c + 1) % 4], f * 4 + c});
    std::sort(hes.begin(), hes.end(),
              [](const He& x, const He& y) { return x.a != y.a ? x.a < y.a : x.b < y.b; });
    auto find = [&](uint32_t a, uint32_t b) -> const He* {
        auto it = std::lower_bound(
            hes.begin(), hes.end(), He{a, b, 0},
            [](const He& x, const He& y) { return x.a != y.a ? x.a < y.a : x.b < y.b; });
        return (it != hes.end() && it->a == a && it->b == b) ? &*it : nullptr;
    };
    size_t undirected = 0;
    for (size_t i = 0; i < hes.size(); ++i) {
        if (i > 0 && hes[i].a == hes[i - 1].a && hes[i].b == hes[i - 1].b) r.oriented = false;
        if (!find(hes[i].b, hes[i].a)) {
            r.closed = false;
            ++undirected;  // a boundary edge counts once
        } else if (hes[i].a < hes[i].b) {
            ++undirected;
        }
    }

    // Vertex fans: from one outgoing half-edge, step to twin(prev(h)) until back at the start.
    std::vector<uint32_t> first(nv + 1, 0);
    for (const auto& h : hes) ++first[h.a + 1];
    for (uint32_t v = 0; v < nv; ++v) first[v + 1] += first[v];
    for (uint32_t v = 0; v < nv; ++v) {
        uint32_t valence = first[v + 1] - first[v];
        if (valence == 0) {
            r.no_isolated = false;
            continue;
        }
        if (!r.closed || !r.oriented) continue;
        const He* h = &hes[first[v]];
        uint32_t steps = 0;
        do {
            uint32_t f = h->fc / 4, c = h->fc % 4;
            uint32_t prev_from = m.quads[f][(c + 3) % 4];
            h = find(v, prev_from);  // twin of prev(h) = (v -> prev_from)
            ++steps;
        } while (h && h != &hes[first[v]] && steps <= valence);
        if (!h || steps != valence) r.manifold_vertices = false;
    }

    r.euler =
        static_cast<int>(nv) - static_cast<int>(undirected) + static_cast<int>(m.quads.size());
    r.min_face_area = m.quads.empty() ? 0 : std::numeric_limits<double>::max();
    for (const auto& q : m.quads) {
        r.min_face_area = std::min(r.min_face_area, quad_area(m, q));
        // A bow-tie (a quad folded across itself) has corners turning two one way and two the
        // other; a merely concave quad has one odd corner.
        glm::dvec3 p[4], k[4];
        for (int c = 0; c < 4; ++c) p[c] = glm::dvec3(m.positions[q[c]]);
        int ref = 0;
        for (int c = 0; c < 4; ++c) {
            k[c] = glm::cross(p[c] - p[(c + 3) % 4], p[(c + 1) % 4] - p[c]);
            if (glm::dot(k[c], k[c]) > glm::dot(k[ref], k[ref])) ref = c;
        }
        int against = 0;
        for (int c = 0; c < 4; ++c) against += glm::dot(k[c], k[ref]) < 0;
        r.folded_faces += against >= 2;
    }
    return r;
}

std::vector<glm::vec3> vertex_normals(const QuadMesh& m) {
    std::vector<glm::dvec3> acc(m.positions.size(), glm::dvec3(0));
    for (const auto& q : m.quads) {
        glm::dvec3 p[4];
        for (int c = 0; c < 4; ++c) p[c] = glm::dvec3(m.positions[q[c]]);
        glm::dvec3 n = glm::cross(p[2] - p[0], p[3] - p[1]);  // twice the area, outward
        for (int c = 0; c < 4; ++c) acc[q[c]] += n;
    }
    std::vector<glm::vec3> out(acc.size());
    for (size_t i = 0; i < acc.size(); ++i) {
        double len = glm::length(acc[i]);
        out[i] = len > 0 ? glm::vec3(acc[i] / len) : glm::vec3(0, 1, 0);
    }
    return out;
}

}  // namespace pleinair
