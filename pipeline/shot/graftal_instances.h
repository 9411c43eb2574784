// Graftals placed on surfaces, once per shot (file 000 §2.2.2: "graftals remain in fixed
// positions on the model surface"): sites from a mesh by the description's rule, and at each
// site a tuft, its level-0 graftal and the graftals of its higher levels around it, every
// variation drawn from a stream keyed by the site, so a site's graftals do not change when other
// sites come or go.
#pragma once

#include <cstdint>
#include <glm/vec3.hpp>
#include <memory>
#include <vector>

#include "generators/quad_mesh.h"
#include "pipeline/input/graftal_desc.h"
#include "pipeline/input/scene.h"
#include "pipeline/shot/built_trees.h"
#include "pipeline/shot/landscape.h"

namespace pleinair {

// Where a tuft stands: a point of a surface, its unit normal, the object it belongs to and a
// key that names it in every frame (a leaf's label, a vertex or face index).
struct GraftalSite {
    glm::dvec3 position{0.0};
    glm::vec3 normal{0, 1, 0};
    uint32_t object = 0;
    uint64_t key = 0;
};

// Sites on `mesh` by the description's placement: a vertex (with its area-weighted normal), a
// face centre, one face in every k (chosen per face by the seed, so the same faces in every
// run), or points at a density per unit area (each face's count and points by the seed).
// kLeafParticles and kDifference take their sites elsewhere: an empty list here.
std::vector<GraftalSite> mesh_sites(const GraftalDesc& desc, const QuadMesh& mesh, uint64_t seed,
                                    uint32_t object);

// Sites at leaf particles (world positions and unit normals, keyed by particle index): every
// one, or with every_k > 1 one in k chosen per particle by the seed, so crowns of thousands of
// leaves carry a few hundred tufts. By the difference image every leaf is a candidate site.
std::vector<GraftalSite> leaf_sites(const GraftalDesc& desc, const std::vector<glm::dvec3>& world,
                                    const std::vector<glm::vec3>& normals, uint64_t seed,
                                    uint32_t object);

struct GraftalInstance {
    glm::dvec3 position{0.0};
    glm::vec3 normal{0, 1, 0};
    uint32_t object = 0;
    uint32_t tuft = 0;     // index of its site
    uint16_t example = 0;  // index into desc.examples
    uint8_t level = 0;     // the tuft level that draws it
    float length = 1;      // world length (desc.length x its variation)
    float width = 1;       // width scale
    float angle = 0;       // degrees about the normal
    float lightness = 1;   // colour scale
    float delay = 0;       // [0, 1): the share of its level's transition it waits before growing
    uint64_t key = 0;      // names it from frame to frame
};

// Every tuft's graftals, site by site and level by level. Level i adds levels[i].count graftals
// (level 0's first stands at the site itself; the others within tuft.spread graftal lengths of
// it, in the surface's tangent plane), from the level's examples in turn (all, if it names
// none). Higher levels' graftals are a little smaller and start their growth a little later, so
// a level comes in as a ripple, not all at once (file 000 §3, the truffula tops).
std::vector<GraftalInstance> grow_tufts(const GraftalDesc& desc,
                                        const std::vector<GraftalSite>& sites, uint64_t seed);

}  // namespace pleinair

namespace pleinair {

// One surface's graftals in a shot (a tree's crown, a material's part of the terrain or a
// rock): its description, tufts and their graftals, grouped by tuft.
struct ShotGraftals {
    std::shared_ptr<const GraftalDesc> desc;
    std::vector<GraftalSite> sites;
    std::vector<GraftalInstance> instances;  // by tuft, in site order
    std::vector<uint32_t> first;             // per site, its first instance; sites + 1 entries
};

// Once per shot: the graftals of every family whose style is a graftal description (at its
// trees' leaf particles) and of every such material (on the terrain where the terrain has that
// material, above any water, and on the rocks made of it), sites and tufts keyed so that a
// tree or a face keeps its graftals whatever else the scene holds.
std::vector<ShotGraftals> build_graftals(const SceneDesc& scene,
                                         const std::vector<BuiltTree>& trees,
                                         const std::vector<TreePlacement>& placements,
                                         const BuiltLandscape& land);

}  // namespace pleinair
