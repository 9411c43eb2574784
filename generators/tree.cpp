// generate_tree: trunk, branches, twigs, subdivision and leaves, in that order.
#include "generators/tree.h"

#include <algorithm>
#include <glm/geometric.hpp>

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

namespace {

float planting_depth(const Tree& tree) {
    if (tree.branches.empty() || tree.branches[0].ring_centers.size() < 2) return 0.0f;
    const BranchInfo& trunk = tree.branches[0];
    const glm::vec3 c0 = trunk.ring_centers[0], c1 = trunk.ring_centers[1];
    const float len = glm::length(c1 - c0);
    if (!(len > 0)) return 0.0f;
    const glm::vec3 axis = (c1 - c0) / len;
    // Heights along the first segment's axis and distances from it, of the render vertices
    // of the trunk's faces within that segment.
    const size_t per_face = size_t{1} << (2 * tree.render_levels);
    std::vector<std::pair<float, float>> points;
    for (uint32_t f : trunk.faces)
        for (size_t k = f * per_face; k < (f + 1) * per_face; ++k)
            for (int c = 0; c < 4; ++c) {
                const glm::vec3 rel = tree.render.positions[tree.render.quads[k][c]] - c0;
                const float h = glm::dot(rel, axis);
                if (h <= len) points.emplace_back(h, glm::length(rel - axis * h));
            }
    float full = 0;
    for (const auto& p : points) full = std::max(full, p.second);
    float depth = len;
    for (const auto& p : points)
        if (p.second >= 0.9f * full) depth = std::min(depth, p.first);
    return std::max(depth, 0.0f);
}

}  // namespace

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
    tree.render_levels = params.subdivision_levels;
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
        const uint32_t last_segment =
            L.centers.size() >= 2 ? static_cast<uint32_t>(L.centers.size() - 2) : 0;
        for (size_t k = 0; k < L.sides.size(); ++k)
            if (L.sides[k].is_valid()) {  // invalid: a branch grew from it and owns it
                b.faces.push_back(static_cast<uint32_t>(L.sides[k].idx()));
                b.face_segments.push_back(static_cast<uint32_t>(k / 4));
                b.face_slots.push_back(static_cast<uint32_t>(k));
            }
        b.faces.push_back(static_cast<uint32_t>(L.top.idx()));
        b.face_segments.push_back(last_segment);
        b.face_slots.push_back(static_cast<uint32_t>(L.sides.size()));
        tree.branches.push_back(std::move(b));
    }
    // The one face no limb lists: the trunk's base, the first face the trunk added.
    std::vector<bool> owned(tree.control.quads.size(), false);
    for (const BranchInfo& b : tree.branches)
        for (uint32_t f : b.faces) owned[f] = true;
    BranchInfo& trunk = tree.branches[0];
    const uint32_t base_slot = trunk.face_slots.back() + 1;
    for (uint32_t f = 0; f < owned.size(); ++f)
        if (!owned[f]) {
            trunk.faces.push_back(f);
            trunk.face_segments.push_back(0);
            trunk.face_slots.push_back(base_slot);
        }
    const LeafParticles& leaves = tree.leaves;
    for (size_t i = 0; i < leaves.size(); ++i)
        if (leaves.fade_begin[i] > 1.0f) tree.branches[leaves.limb[i]].keeps_leaves = true;
    tree.planting_depth = planting_depth(tree);
    return tree;
}

}  // namespace pleinair
