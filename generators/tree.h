// A whole generated tree: control, render and low-detail meshes, leaf particles, skeleton and
// centre locator, built from a preset and a seed by one pure function.
#pragma once

#include <cstdint>
#include <glm/vec3.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "generators/leaves.h"
#include "generators/quad_mesh.h"
#include "generators/tree_params.h"

namespace pleinair {

// One limb of the skeleton, for the stages after generation (leaf LOD, bark strokes).
struct BranchInfo {
    uint32_t id = 0;        // index in Tree::branches; 0 is the trunk
    uint64_t key = 0;       // structural key (parent, segment, side): keys later random streams
    int level = 0;          // 0 trunk, 1 branch, 2 twig
    int parent = -1;        // id of the parent, -1 for the trunk
    glm::vec3 start{0.0f};  // centre of the base ring (tree-local)
    glm::vec3 end{0.0f};    // centre of the tip ring
    float length = 0;       // along the skeleton
    // It bears a leaf that never fades (fade_begin > 1): a twig's bark stays with such leaves
    // at every level of detail, or they would hang in the air when the tree recedes.
    bool keeps_leaves = false;
    std::vector<glm::vec3> ring_centers;
    std::vector<float> ring_radii;  // non-increasing from base to tip
    // The control-mesh faces this limb owns, in a stable order (its side faces segment by
    // segment, then its cap; the trunk also owns its base), and the segment each belongs to
    // (rings s and s + 1). Every control face is owned by exactly one limb. Render face
    // f * 4^render_levels + k, for k < 4^render_levels, is a piece of control face f.
    std::vector<uint32_t> faces;
    std::vector<uint32_t> face_segments;
    // Each face's place on the limb, stable whatever other limbs do: 4 * segment + side for a
    // side face, then the cap, then (trunk) the base. A side a branch grew from is the
    // branch's, and its slot is simply missing here; later stages key random streams by slot.
    std::vector<uint32_t> face_slots;
};

struct TreeOptions {
    uint32_t tree_id = 0;        // stored in every particle; seeds the painter's tint
    glm::dvec3 origin{0, 0, 0};  // where the tree stands; geometry itself is tree-local
    bool lod = true;             // build the low-detail mesh
};

struct Tree {
    uint64_t seed = 0;
    uint32_t id = 0;
    glm::dvec3 origin{0, 0, 0};  // add to tree-local positions for world space (in double)
    QuadMesh control;            // trunk and branches as grown by extrusion
    QuadMesh render;             // control after Catmull-Clark
    int render_levels = 0;       // rounds of Catmull-Clark from control to render
    QuadMesh lod;                // trunk and first-level branches, fewer subdivision levels
    LeafParticles leaves;
    std::vector<BranchInfo> branches;
    glm::vec3 center{0.0f};  // centre locator, tree-local
    // Height above the trunk's base ring at which the render mesh reaches nine tenths of the
    // trunk's width: below it is the cap Catmull-Clark rounds into a dome. Scenes plant the
    // tree this deep, and no bark stroke is painted below it.
    float planting_depth = 0;
};

class InvalidParams : public std::invalid_argument {
  public:
    explicit InvalidParams(std::vector<std::string> problems);
    std::vector<std::string> problems;
};

// Pure: the same params, seed and options give the same Tree, bit for bit. Throws
// InvalidParams if validate(params) finds a problem.
Tree generate_tree(const TreeParams& params, uint64_t seed, const TreeOptions& options = {});

// The stages, for benchmarks and tests; generate_tree runs them in this order.
struct TreeMesh;
void grow_skeleton(TreeMesh& tm, const TreeParams& params, uint64_t seed,
                   QuadMesh* lod_control = nullptr);

}  // namespace pleinair
