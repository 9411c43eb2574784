// generate_tree: trunk, branches, twigs, subdivision and leaves, in that order.
#include "generators/tree.h"

#include "generators/branches.h"
#include "generators/subdivide.h"
#include "generators/tree_mesh.h"
#include "generators/trunk.h"

namespace pleinair {

namespace {
std::string join_lines(const std::vector<std::string>& lines) {
    std::string s;
    for (const auto& l : lines) s += (s.empty() ? "" : "\n") + l;
    return s;
}
}  // namespace

InvalidParams::InvalidParams(std::vector<std::string> p)
    : std::invalid_argument(join_lines(p)), problems(std::move(p)) {}

void grow_skeleton(TreeMesh& tm, const TreeParams& params, uint64_t seed, QuadMesh* lod_control) {
    grow_trunk(tm, params, seed);
    grow_branches(tm, params.branches, 1, seed);
    if (lod_control) *lod_control = to_quad_mesh(tm);
    if (params.branches.enabled) grow_branches(tm, params.twigs, 2, seed);
}

Tree generate_tree(const TreeParams& params, uint64_t seed, const TreeOptions& options) {
    if (auto problems = validate(params); !problems.empty()) throw InvalidParams(problems);
    Tree tree;
    tree.seed = seed;
    tree.id = options.tree_id;
    tree.origin = options.origin;

    TreeMesh tm;
    QuadMesh lod_control;
    grow_skeleton(tm, params, seed, options.lod ? &lod_control : nullptr);
    tree.control = to_quad_mesh(tm);
    tree.render = catmull_clark(tree.control, params.subdivision_levels);
    if (options.lod) tree.lod = catmull_clark(lod_control, params.lod_subdivision_levels);

    glm::dvec3 center;
    tree.leaves = emit_leaves(tm, params, seed, options.tree_id, center);
    tree.center = glm::vec3(center);

    // Skeleton records, with ids in growth order; parents always precede children.
    tree.branches.reserve(tm.limbs.size());
    for (size_t i = 0; i < tm.limbs.size(); ++i) {
        const Limb& L = tm.limbs[i];
        BranchInfo b;
        b.id = static_cast<uint32_t>(i);
        b.key = L.key;
        b.level = L.level;
        b.parent = L.parent;
        b.start = glm::vec3(L.centers.front());
        b.end = glm::vec3(L.centers.back());
        b.length = static_cast<float>(L.length);
        for (const auto& c : L.centers) b.ring_centers.push_back(glm::vec3(c));
        for (double r : L.radii) b.ring_radii.push_back(static_cast<float>(r));
        tree.branches.push_back(std::move(b));
    }
    return tree;
}

}  // namespace pleinair
