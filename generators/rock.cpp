// Rocks through OpenMesh: its Catmull-Clark refines the cube (meshes here are small, so its
// speed does not matter), then every vertex is moved along its direction from the centre.
#include "generators/rock.h"

// OpenMesh's subdivider needs a mesh kernel included before it.
#include <OpenMesh/Core/Mesh/PolyMesh_ArrayKernelT.hh>
#include <OpenMesh/Tools/Subdivider/Uniform/CatmullClarkT.hh>
#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>

#include "generators/rng.h"
#include "shading/curves.h"
#include "shading/noise.h"

namespace pleinair {

namespace {
using RockMesh = OpenMesh::PolyMesh_ArrayKernelT<>;
}

QuadMesh generate_rock(const RockParams& p, uint64_t seed, const glm::dvec3& position) {
    RockMesh mesh;
    RockMesh::VertexHandle v[8];
    for (int i = 0; i < 8; ++i)
        v[i] =
            mesh.add_vertex(RockMesh::Point((i & 1) ? 1 : -1, (i & 2) ? 1 : -1, (i & 4) ? 1 : -1));
    // Counter-clockwise seen from outside.
    const int faces[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                             {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
    for (const auto& f : faces) mesh.add_face(v[f[0]], v[f[1]], v[f[2]], v[f[3]]);
    OpenMesh::Subdivider::Uniform::CatmullClarkT<RockMesh> cc;
    cc.attach(mesh);
    cc(static_cast<size_t>(std::clamp(p.subdivision_levels, 0, 6)));
    cc.detach();

    Rng rng = make_rng(seed, Purpose::kTerrain, uint64_t{0x70c6});
    const float ox = static_cast<float>(rand_range(rng, 0, 200));
    const float oy = static_cast<float>(rand_range(rng, 0, 200));
    const float oz = static_cast<float>(rand_range(rng, 0, 200));
    const double radius = std::max(std::abs(p.radius), 1e-6);
    const double rough = std::clamp(p.roughness, 0.0, 0.9);
    const glm::dvec3 scale = glm::max(glm::abs(p.scale), glm::dvec3(1e-3));
    const double f = p.noise_frequency;

    QuadMesh out;
    out.positions.reserve(mesh.n_vertices());
    for (auto vh : mesh.vertices()) {
        const auto& q = mesh.point(vh);
        glm::dvec3 dir = glm::normalize(glm::dvec3(q[0], q[1], q[2]));
        // Noise in 0..1 around the unit sphere: radius shrinks by up to `rough`, never through
        // the centre, so the surface cannot fold over itself.
        float n = 0.5f;
        if (rough > 0) {
            float sum = 0, amp = 1, norm = 0, k = 1;
            for (int o = 0; o < std::max(p.noise_octaves, 1); ++o) {
                sum += amp * signed_noise(static_cast<float>(dir.x * f * k) + ox,
                                          static_cast<float>(dir.y * f * k) + oy,
                                          static_cast<float>(dir.z * f * k) + oz);
                norm += amp, amp *= 0.5f, k *= 2;
            }
            n = clamp01(0.5f + 0.5f * sum / norm);
        }
        double r = radius * (1.0 - rough * n);
        out.positions.push_back(glm::vec3(position + dir * r * scale));
    }
    for (auto fh : mesh.faces()) {
        glm::uvec4 quad;
        int k = 0;
        for (auto fv : mesh.fv_range(fh)) quad[k++] = static_cast<unsigned>(fv.idx());
        if (k == 4) out.quads.push_back(quad);
    }
    return out;
}

}  // namespace pleinair
