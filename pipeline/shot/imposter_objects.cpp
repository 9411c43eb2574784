// make_imposter_object and build_imposters: each imposter-bearing mesh's edges, faces, rows,
// colours and directions, once per shot.
#include "pipeline/shot/imposter_objects.h"

#include <cmath>
#include <glm/geometric.hpp>
#include <glm/matrix.hpp>
#include <map>

#include "generators/rng.h"

namespace pleinair {

namespace {

glm::vec3 unit_or(const glm::dvec3& v, const glm::vec3& fallback) {
    const double l = glm::length(v);
    return l > 1e-12 && std::isfinite(l) ? glm::vec3(v / l) : fallback;
}

}  // namespace

ImposterObject make_imposter_object(std::shared_ptr<const ImposterDesc> desc, const QuadMesh& mesh,
                                    const glm::dvec3& position, const glm::dmat3& linear,
                                    double scale, uint32_t object_id, uint64_t key,
                                    const std::vector<bool>& excluded,
                                    std::shared_ptr<const ImposterAtlas> atlas) {
    ImposterObject o;
    const ImposterDesc& d = *desc;
    o.atlas = atlas ? std::move(atlas) : std::make_shared<const ImposterAtlas>(imposter_atlas(d));
    o.desc = std::move(desc);
    o.mesh = &mesh;
    o.position = position, o.linear = linear;
    o.scale = scale;
    o.height = double(d.height) * scale;
    o.object_id = object_id, o.key = key;
    o.edges = mesh_edges(mesh);
    const std::vector<glm::dvec3> n = face_normals(mesh);
    o.normals.resize(n.size());
    for (size_t f = 0; f < n.size(); ++f) o.normals[f] = unit_or(n[f], glm::vec3(0.0f));
    const Bounds box = bounds_of(mesh.positions);
    auto uv_of = [&](const glm::vec3& p) { return imposter_uv(d.uv, p, box.min, box.max); };
    // The control texture at each edge's middle, thinned to `coverage` by a hash of the edge.
    const size_t nv = mesh.positions.size();
    o.rows.assign(o.edges.size(), int8_t{-1});
    auto out = [&](uint32_t f) { return !excluded.empty() && excluded[f]; };
    for (size_t i = 0; i < o.edges.size(); ++i) {
        const MeshEdge& e = o.edges[i];
        if (out(e.face0) || (e.face1 != MeshEdge::kBorder && out(e.face1))) continue;
        if (d.coverage < 1.0f) {
            const double u = double(hash_keys(key, 0x636f766572ull /* "cover" */,
                                              std::min(e.a, e.b), std::max(e.a, e.b)) >>
                                    11) *
                             (1.0 / 9007199254740992.0);
            if (!(u < d.coverage)) continue;
        }
        const int row = control_row(d, uv_of(0.5f * (mesh.positions[e.a] + mesh.positions[e.b])));
        // A control image's green or blue over an atlas of fewer rows: nothing there.
        o.rows[i] = static_cast<int8_t>(row < d.atlas_rows ? row : -1);
    }
    const bool wrap = d.uv == ImposterUv::kCylinder;  // round the object; a plan's sides clamp
    // The colour texture at each vertex.
    o.colors.resize(nv);
    for (size_t v = 0; v < nv; ++v) {
        const glm::vec2 uv = uv_of(mesh.positions[v]);
        o.colors[v] = !d.color.empty() ? glm::vec3(d.color.sample(uv.x, 1.0f - uv.y, wrap))
                                       : d.bottom + (d.top - d.bottom) * uv.y;
    }
    // The vector field at each edge's middle, in the mesh's frame.
    const glm::dmat3 inv = glm::inverse(linear);
    const glm::vec3 up_local = unit_or(inv * glm::dvec3(0, 1, 0), glm::vec3(0, 1, 0));
    o.directions.resize(o.edges.size());
    for (size_t i = 0; i < o.edges.size(); ++i) {
        const MeshEdge& e = o.edges[i];
        const glm::vec3 n_edge = unit_or(
            glm::dvec3(o.normals[e.face0]) +
                (e.face1 == MeshEdge::kBorder ? glm::dvec3(0.0) : glm::dvec3(o.normals[e.face1])),
            o.normals[e.face0]);
        glm::vec3 dir = d.normal * n_edge + d.up * up_local;
        if (!d.field.empty()) {
            const glm::vec2 uv = uv_of(0.5f * (mesh.positions[e.a] + mesh.positions[e.b]));
            dir += glm::vec3(d.field.sample(uv.x, 1.0f - uv.y, wrap)) * 2.0f - 1.0f;
        }
        o.directions[i] = unit_or(glm::dvec3(dir), n_edge);
    }
    return o;
}

std::vector<ImposterObject> build_imposters(const SceneDesc& scene,
                                            const std::vector<BuiltTree>& trees,
                                            const std::vector<TreePlacement>& placements,
                                            const BuiltLandscape& land) {
    std::vector<ImposterObject> out;
    // One atlas per description, drawn once and shared by every object that names it.
    std::map<const ImposterDesc*, std::shared_ptr<const ImposterAtlas>> atlases;
    auto atlas_of = [&](const std::shared_ptr<const ImposterDesc>& d) {
        auto& a = atlases[d.get()];
        if (!a) a = std::make_shared<const ImposterAtlas>(imposter_atlas(*d));
        return a;
    };
    for (size_t i = 0; i < trees.size(); ++i) {
        const BuiltTree& b = trees[i];
        const auto& desc = scene.families[b.family].imposters;
        if (!desc) continue;
        const QuadMesh& mesh =
            desc->mesh == ImposterMesh::kControl ? b.tree().control : b.tree().render;
        const TreePlacement& pl = placements[i];
        out.push_back(make_imposter_object(desc, mesh, pl.position, pl.linear(), pl.scale, b.id + 1,
                                           hash_keys(0x74726565ull, b.id), {}, atlas_of(desc)));
    }
    for (size_t m = 0; m < scene.materials.size(); ++m) {
        const auto& desc = scene.materials[m].imposters;
        if (!desc) continue;
        const uint32_t object = 0x10000u + static_cast<uint32_t>(m);
        if (land.has_terrain) {
            const QuadMesh& t = land.terrain_mesh;
            std::vector<bool> excluded(t.quads.size(), true);
            bool any = false;
            for (size_t f = 0; f < t.quads.size(); ++f) {
                glm::dvec3 c(0.0);
                for (int k = 0; k < 4; ++k) c += glm::dvec3(t.positions[t.quads[f][k]]);
                c *= 0.25;
                const bool mine = terrain_material_at(scene, c) == m &&
                                  !(land.has_water && c.y <= scene.water.level);
                excluded[f] = !mine, any |= mine;
            }
            if (any)
                out.push_back(make_imposter_object(desc, t, glm::dvec3(0.0), glm::dmat3(1.0), 1.0,
                                                   object, hash_keys(0x7465727261ull, m), excluded,
                                                   atlas_of(desc)));
        }
        for (size_t r = 0; r < scene.rocks.size() && r < land.rocks.size(); ++r)
            if (scene.rocks[r].material == m)
                out.push_back(
                    make_imposter_object(desc, land.rocks[r], glm::dvec3(0.0), glm::dmat3(1.0), 1.0,
                                         object, hash_keys(0x726f636bull, r), {}, atlas_of(desc)));
    }
    return out;
}

}  // namespace pleinair
