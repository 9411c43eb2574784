// Sites on meshes and the tufts grown at them, all randomness keyed by the site.
#include "pipeline/shot/graftal_instances.h"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>

#include "generators/rng.h"
#include "generators/tree_mesh.h"
#include "shading/portable_math.h"

namespace pleinair {

namespace {

glm::dvec3 corner(const QuadMesh& m, const glm::uvec4& q, int c) {
    return glm::dvec3(m.positions[q[c]]);
}

// A quad's (unnormalised) normal and area, from its diagonals.
glm::dvec3 diagonal_cross(const QuadMesh& m, const glm::uvec4& q) {
    return glm::cross(corner(m, q, 2) - corner(m, q, 0), corner(m, q, 3) - corner(m, q, 1));
}

bool indices_ok(const QuadMesh& m, const glm::uvec4& q) {
    const size_t n = m.positions.size();
    return q.x < n && q.y < n && q.z < n && q.w < n;
}

glm::vec3 unit_or_up(const glm::dvec3& v) {
    return glm::vec3(safe_normalize(v, glm::dvec3(0, 1, 0)));
}

}  // namespace

std::vector<GraftalSite> leaf_sites(const GraftalDesc& desc, const std::vector<glm::dvec3>& world,
                                    const std::vector<glm::vec3>& normals, uint64_t seed,
                                    uint32_t object) {
    std::vector<GraftalSite> out;
    // By the difference image, every leaf is a candidate; the frame chooses among them.
    const uint32_t k = desc.placement == GraftalPlacement::kDifference
                           ? 1u
                           : static_cast<uint32_t>(std::max(desc.every_k, 1));
    for (size_t j = 0; j < world.size() && j < normals.size(); ++j) {
        if (k > 1) {
            Rng rng = make_rng(seed, Purpose::kGraftal, object, j, 3);
            if (next_u32(rng) % k != 0) continue;
        }
        out.push_back({world[j], unit_or_up(glm::dvec3(normals[j])), object, j});
    }
    return out;
}

std::vector<GraftalSite> mesh_sites(const GraftalDesc& desc, const QuadMesh& mesh, uint64_t seed,
                                    uint32_t object) {
    std::vector<GraftalSite> out;
    switch (desc.placement) {
        case GraftalPlacement::kVertices: {
            const std::vector<glm::vec3> normals = vertex_normals(mesh);
            for (size_t v = 0; v < mesh.positions.size(); ++v)
                out.push_back(
                    {glm::dvec3(mesh.positions[v]), unit_or_up(glm::dvec3(normals[v])), object, v});
            break;
        }
        case GraftalPlacement::kFaces:
        case GraftalPlacement::kEveryKthFace:
            for (size_t f = 0; f < mesh.quads.size(); ++f) {
                const glm::uvec4& q = mesh.quads[f];
                if (!indices_ok(mesh, q)) continue;
                if (desc.placement == GraftalPlacement::kEveryKthFace) {
                    Rng rng = make_rng(seed, Purpose::kGraftal, object, f, 0);
                    if (next_u32(rng) % static_cast<uint32_t>(std::max(desc.every_k, 1)) != 0)
                        continue;
                }
                const glm::dvec3 c = 0.25 * (corner(mesh, q, 0) + corner(mesh, q, 1) +
                                             corner(mesh, q, 2) + corner(mesh, q, 3));
                out.push_back({c, unit_or_up(diagonal_cross(mesh, q)), object, f});
            }
            break;
        case GraftalPlacement::kDensity:
            for (size_t f = 0; f < mesh.quads.size(); ++f) {
                const glm::uvec4& q = mesh.quads[f];
                if (!indices_ok(mesh, q)) continue;
                const glm::dvec3 n = diagonal_cross(mesh, q);
                const double area = 0.5 * glm::length(n);
                if (!(area > 0) || !std::isfinite(area)) continue;
                Rng rng = make_rng(seed, Purpose::kGraftal, object, f, 1);
                // The expected count, its fraction decided by one draw: an unbiased total.
                const double expected = area * desc.per_area;
                const int count = static_cast<int>(std::min(expected + rand1(rng), 1e6));
                for (int i = 0; i < count; ++i) {
                    const double u = rand1(rng), v = rand1(rng);  // bilinear over the quad
                    const glm::dvec3 p =
                        (1 - u) * (1 - v) * corner(mesh, q, 0) + u * (1 - v) * corner(mesh, q, 1) +
                        u * v * corner(mesh, q, 2) + (1 - u) * v * corner(mesh, q, 3);
                    out.push_back({p, unit_or_up(n), object, (static_cast<uint64_t>(f) << 20) | i});
                }
            }
            break;
        case GraftalPlacement::kLeafParticles:
        case GraftalPlacement::kDifference:
            break;
    }
    return out;
}

std::vector<GraftalInstance> grow_tufts(const GraftalDesc& desc,
                                        const std::vector<GraftalSite>& sites, uint64_t seed) {
    std::vector<GraftalInstance> out;
    if (desc.examples.empty()) return out;
    // Examples by name, once.
    std::vector<std::vector<uint16_t>> level_examples(desc.tuft.levels.size());
    for (size_t l = 0; l < desc.tuft.levels.size(); ++l) {
        for (const std::string& name : desc.tuft.levels[l].examples)
            for (size_t e = 0; e < desc.examples.size(); ++e)
                if (desc.examples[e].name == name)
                    level_examples[l].push_back(static_cast<uint16_t>(e));
        if (level_examples[l].empty())
            for (size_t e = 0; e < desc.examples.size(); ++e)
                level_examples[l].push_back(static_cast<uint16_t>(e));
    }
    const GraftalVariation& var = desc.variation;
    for (size_t s = 0; s < sites.size(); ++s) {
        const GraftalSite& site = sites[s];
        const glm::dvec3 n(site.normal);
        const auto [t1, t2] = orthonormal_basis(safe_normalize(n, glm::dvec3(0, 1, 0)));
        Rng rng = make_rng(seed, Purpose::kGraftal, site.object, site.key, 2);
        uint32_t child = 0;
        for (size_t l = 0; l < desc.tuft.levels.size(); ++l) {
            const TuftLevel& level = desc.tuft.levels[l];
            for (int i = 0; i < level.count; ++i, ++child) {
                // Every draw is made whatever is used, so later ones never shift.
                const double r = std::sqrt(rand1(rng)), a = 2 * pmath::kPi * rand1(rng);
                const double dl = rand_range(rng, -1, 1), dw = rand_range(rng, -1, 1);
                const double da = rand_range(rng, -1, 1), dc = rand_range(rng, -1, 1);
                const double delay = rand1(rng);
                GraftalInstance g;
                const bool base = l == 0 && i == 0;
                double sa, ca;
                pmath::sincos(a, sa, ca);
                const double reach = base ? 0.0 : desc.tuft.spread * desc.length * r;
                g.position = site.position + reach * (ca * t1 + sa * t2);
                g.normal = site.normal;
                g.object = site.object;
                g.tuft = static_cast<uint32_t>(s);
                g.example = level_examples[l][static_cast<size_t>(i) % level_examples[l].size()];
                g.level = static_cast<uint8_t>(l);
                // Added graftals are a little smaller than their tuft's first (file 000 §3).
                const double shrink = l > 0 ? 0.85 : 1.0;
                g.length = static_cast<float>(desc.length * shrink * (1 + var.length * dl));
                g.width = static_cast<float>(1 + var.width * dw);
                g.angle = static_cast<float>(var.angle * da);
                g.lightness = static_cast<float>(1 + var.color * dc);
                g.delay = base ? 0.0f : static_cast<float>(0.5 * delay);
                g.key = hash_keys(site.object, site.key, child);
                out.push_back(g);
            }
        }
    }
    return out;
}

namespace {

// Fixed: a site's key and its object already tell every tuft apart.
constexpr uint64_t kGraftalSeed = 0x6772616674616cull;  // "graftal"

ShotGraftals group_of(std::shared_ptr<const GraftalDesc> desc, std::vector<GraftalSite> sites) {
    ShotGraftals g;
    g.desc = std::move(desc);
    g.sites = std::move(sites);
    g.instances = grow_tufts(*g.desc, g.sites, kGraftalSeed);
    g.first.assign(g.sites.size() + 1, 0);
    // grow_tufts lists each site's graftals together, in site order.
    for (const GraftalInstance& i : g.instances) ++g.first[i.tuft + 1];
    for (size_t s = 0; s < g.sites.size(); ++s) g.first[s + 1] += g.first[s];
    return g;
}

}  // namespace

std::vector<ShotGraftals> build_graftals(const SceneDesc& scene,
                                         const std::vector<BuiltTree>& trees,
                                         const std::vector<TreePlacement>& placements,
                                         const BuiltLandscape& land) {
    std::vector<ShotGraftals> out;
    for (size_t i = 0; i < trees.size(); ++i) {
        const BuiltTree& b = trees[i];
        const Family& fam = scene.families[b.family];
        if (!fam.graftal) continue;
        const LeafParticles& L = b.tree().leaves;
        const TreePlacement& pl = placements[i];
        std::vector<glm::dvec3> world(L.size());
        std::vector<glm::vec3> normals(L.size());
        for (size_t j = 0; j < L.size(); ++j)
            world[j] = pl.place(L.position[j]), normals[j] = pl.turn(L.normal[j]);
        GraftalDesc scaled = *fam.graftal;
        scaled.length *= static_cast<float>(b.scale);  // a tree's graftals grow with it
        out.push_back(group_of(std::make_shared<const GraftalDesc>(std::move(scaled)),
                               leaf_sites(*fam.graftal, world, normals, kGraftalSeed, b.id + 1)));
    }
    for (size_t m = 0; m < scene.materials.size(); ++m) {
        const auto& desc = scene.materials[m].graftal;
        if (!desc) continue;
        const uint32_t object = 0x10000u + static_cast<uint32_t>(m);
        std::vector<GraftalSite> sites;
        // The difference image chooses among candidates at the description's density.
        GraftalDesc candidates = *desc;
        if (candidates.placement == GraftalPlacement::kDifference)
            candidates.placement = GraftalPlacement::kDensity;
        if (land.has_terrain) {
            for (const GraftalSite& s :
                 mesh_sites(candidates, land.terrain_mesh, kGraftalSeed, object)) {
                if (terrain_material_at(scene, s.position) != m) continue;
                if (land.has_water && s.position.y <= scene.water.level) continue;
                sites.push_back(s);
            }
        }
        for (size_t r = 0; r < scene.rocks.size() && r < land.rocks.size(); ++r) {
            if (scene.rocks[r].material != m) continue;
            // Keys apart from the terrain's: a rock's sites are numbered from 2^40 x (r + 1).
            for (GraftalSite s :
                 mesh_sites(candidates, land.rocks[r], kGraftalSeed + r + 1, object)) {
                s.key += (uint64_t(r) + 1) << 40;
                sites.push_back(s);
            }
        }
        if (!sites.empty()) out.push_back(group_of(desc, std::move(sites)));
    }
    return out;
}

}  // namespace pleinair
