// Catmull-Clark subdivision on flat arrays (see subdivide.h for why not OpenMesh's).
//
// Half-edge h = 4 * face + corner runs q[corner] -> q[corner + 1]. The first level finds twins
// by sorting; every later level derives its twins from the parent's in O(1) each, because
// Catmull-Clark's new connectivity is fixed by the old one.
#include "generators/subdivide.h"

#include <algorithm>
#include <glm/geometric.hpp>
#include <stdexcept>

namespace pleinair {

namespace {

// Twin of every half-edge of a closed quad mesh: half-edges bucketed by their smaller vertex
// (counting sort, linear time), then paired within each small bucket.
std::vector<uint32_t> find_twins(const QuadMesh& m) {
    const auto nv = static_cast<uint32_t>(m.positions.size());
    const auto nh = static_cast<uint32_t>(m.quads.size() * 4);
    auto ends = [&](uint32_t h, uint32_t& a, uint32_t& b) {
        a = m.quads[h / 4][h % 4];
        b = m.quads[h / 4][(h + 1) % 4];
    };
    std::vector<uint32_t> first(nv + 1, 0), bucket(nh);
    for (uint32_t h = 0; h < nh; ++h) {
        uint32_t a, b;
        ends(h, a, b);
        ++first[std::min(a, b) + 1];
    }
    for (uint32_t v = 0; v < nv; ++v) first[v + 1] += first[v];
    {
        std::vector<uint32_t> fill(first.begin(), first.end() - 1);
        for (uint32_t h = 0; h < nh; ++h) {
            uint32_t a, b;
            ends(h, a, b);
            bucket[fill[std::min(a, b)]++] = h;
        }
    }
    constexpr uint32_t kNone = ~0u;
    std::vector<uint32_t> twin(nh, kNone);
    for (uint32_t v = 0; v < nv; ++v)
        for (uint32_t i = first[v]; i < first[v + 1]; ++i) {
            uint32_t h = bucket[i], a, b;
            ends(h, a, b);
            for (uint32_t k = i + 1; k < first[v + 1]; ++k) {
                uint32_t g = bucket[k], c, d;
                ends(g, c, d);
                if (c == b && d == a) {
                    // A closed, oriented manifold has each edge once in each direction.
                    if (twin[h] != kNone || twin[g] != kNone)
                        throw std::invalid_argument("catmull_clark: mesh is not manifold");
                    twin[h] = g;
                    twin[g] = h;
                }
            }
        }
    for (uint32_t h = 0; h < nh; ++h)
        if (twin[h] == kNone) throw std::invalid_argument("catmull_clark: mesh is not closed");
    return twin;
}

// One level; `twin` is the input's and is replaced by the output's.
QuadMesh subdivide_once(const QuadMesh& in, std::vector<uint32_t>& twin) {
    const auto nv = static_cast<uint32_t>(in.positions.size());
    const auto nf = static_cast<uint32_t>(in.quads.size());
    const uint32_t nh = nf * 4;
    const glm::vec3* P = in.positions.data();

    // Edge ids: the half-edge with the smaller index owns the edge.
    std::vector<uint32_t> edge_of(nh);
    uint32_t ne = 0;
    for (uint32_t h = 0; h < nh; ++h)
        if (h < twin[h]) edge_of[h] = edge_of[twin[h]] = ne++;

    QuadMesh o;
    o.positions.resize(nv + ne + nf);
    glm::vec3* vp = o.positions.data();
    glm::vec3* ep = vp + nv;
    glm::vec3* fp = ep + ne;

    for (uint32_t f = 0; f < nf; ++f) {
        const auto& q = in.quads[f];
        fp[f] = 0.25f * (P[q[0]] + P[q[1]] + P[q[2]] + P[q[3]]);
    }
    // Edge point = mean of the two ends and the two adjacent face points: each half-edge adds
    // its tail and its face point. Vertex point = (Q + 2R + (n - 3) S) / n; in a closed mesh
    // each outgoing half-edge of v names one adjacent face (Q) and one incident edge (R).
    std::fill(ep, ep + ne, glm::vec3(0.0f));
    std::vector<glm::vec3> q_sum(nv, glm::vec3(0.0f)), r_sum(nv, glm::vec3(0.0f));
    std::vector<uint32_t> valence(nv, 0);
    for (uint32_t f = 0; f < nf; ++f) {
        const auto& q = in.quads[f];
        for (uint32_t c = 0; c < 4; ++c) {
            const uint32_t a = q[c], b = q[(c + 1) & 3];
            ep[edge_of[f * 4 + c]] += 0.25f * (P[a] + fp[f]);
            q_sum[a] += fp[f];
            r_sum[a] += P[b];  // midpoint sum = (n * S + sum of neighbours) / 2
            ++valence[a];
        }
    }
    for (uint32_t v = 0; v < nv; ++v) {
        const uint32_t n = valence[v];
        const glm::vec3 s = P[v];
        if (n == 0) {
            vp[v] = s;
            continue;
        }
        const float inv_n = 1.0f / static_cast<float>(n);
        const glm::vec3 q = q_sum[v] * inv_n;
        const glm::vec3 r = 0.5f * (s + r_sum[v] * inv_n);
        vp[v] = (q + 2.0f * r + static_cast<float>(static_cast<int>(n) - 3) * s) * inv_n;
    }

    // Child quad 4f + c = (v_c, E_c, F, E_{c-1}); its twins follow from the parent's.
    o.quads.resize(static_cast<size_t>(nf) * 4);
    std::vector<uint32_t> child_twin(static_cast<size_t>(nh) * 4);
    for (uint32_t f = 0; f < nf; ++f) {
        const auto& q = in.quads[f];
        const uint32_t face_point = nv + ne + f;
        for (uint32_t c = 0; c < 4; ++c) {
            const uint32_t h = f * 4 + c, h_prev = f * 4 + ((c + 3) & 3);
            o.quads[h] = glm::uvec4(q[c], nv + edge_of[h], face_point, nv + edge_of[h_prev]);
            const uint32_t t = twin[h], t_prev = twin[h_prev];
            const uint32_t child = h * 4;
            // v_c -> E_c pairs with the neighbour's child at the corner after the twin's.
            child_twin[child + 0] = ((t & ~3u) + ((t + 1) & 3)) * 4 + 3;
            child_twin[child + 1] = (f * 4 + ((c + 1) & 3)) * 4 + 2;
            child_twin[child + 2] = (f * 4 + ((c + 3) & 3)) * 4 + 1;
            child_twin[child + 3] = t_prev * 4 + 0;
        }
    }
    twin.swap(child_twin);
    return o;
}

}  // namespace

QuadMesh catmull_clark(const QuadMesh& mesh, int levels) {
    if (levels <= 0) return mesh;
    std::vector<uint32_t> twin = find_twins(mesh);
    QuadMesh m = subdivide_once(mesh, twin);
    for (int i = 1; i < levels; ++i) m = subdivide_once(m, twin);
    return m;
}

}  // namespace pleinair
