// build_trees and the trees' placements: every tree of the scene grown (in parallel, the same
// whatever the threads), its bark strokes emitted, planted so the ground meets its full trunk.
#include "pipeline/shot/built_trees.h"

#include <tbb/parallel_for.h>

#include <cmath>
#include <map>
#include <stdexcept>

#include "shading/portable_math.h"

namespace pleinair {

namespace {

glm::dvec3 rotate_y(const glm::dvec3& v, double c, double s) {
    return {c * v.x + s * v.z, v.y, -s * v.x + c * v.z};
}

}  // namespace

TreePlacement placement(const BuiltTree& b) {
    return {pmath::cos(b.rotation * M_PI / 180.0), pmath::sin(b.rotation * M_PI / 180.0), b.scale,
            b.position};
}

glm::dvec3 TreePlacement::place(const glm::vec3& p) const {
    return position + rotate_y(glm::dvec3(p) * scale, c, s);
}

glm::vec3 TreePlacement::turn(const glm::vec3& v) const {
    return glm::vec3(rotate_y(glm::dvec3(v), c, s));
}

glm::dmat3 TreePlacement::linear() const {
    return glm::dmat3(glm::dvec3(c, 0, -s) * scale, glm::dvec3(0, scale, 0),
                      glm::dvec3(s, 0, c) * scale);
}

double tree_stroke_width(const Family& family, const StrokeShaderParams& shader, double scale) {
    return shader.sprite_size * family.params.unit * scale;
}

BarkParticles family_bark(const Family& family, const Tree& tree, float coverage, uint64_t seed) {
    BarkOptions bo;
    bo.stroke_width = static_cast<float>(tree_stroke_width(family, family.bark_shader, 1.0));
    bo.stroke_length = bo.stroke_width * family.bark_shader.stroke_aspect;
    bo.coverage = coverage;
    return emit_bark(tree, bo, seed);
}

uint32_t tree_member(const SceneDesc& scene, size_t i) {
    const PlacedTree& t = scene.trees[i];
    const int m = scene.families[t.family].members;
    if (m <= 0) return static_cast<uint32_t>(i);
    // SplitMix64's finaliser: the seed's low bits alone would give neighbours' members.
    uint64_t z = t.seed + 0x9e3779b97f4a7c15ull;
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    z ^= z >> 31;
    return static_cast<uint32_t>(z % static_cast<uint64_t>(m));
}

namespace {

// Tree i placed, its geometry grown (from tree `from`'s seed) unless `shared` holds it.
BuiltTree build_tree(const SceneDesc& scene, size_t i, size_t from, bool bark,
                     const BuiltTree* shared) {
    const PlacedTree& t = scene.trees[i];
    const Family& f = scene.families[t.family];
    BuiltTree b;
    if (shared) {
        b.grown = shared->grown, b.bark_strokes = shared->bark_strokes;
    } else {
        const PlacedTree& g = scene.trees[from];
        TreeOptions o;
        o.tree_id = static_cast<uint32_t>(from);
        o.lod = false;
        b.tree() = generate_tree(f.params, g.seed, o);
        if (bark) b.bark() = family_bark(f, b.tree(), scene.build.bark_coverage, g.seed);
    }
    b.id = static_cast<uint32_t>(i);
    b.member = tree_member(scene, i);
    b.family = t.family;
    b.position = t.position;
    // Catmull-Clark rounds the trunk's base into a dome: plant the tree deep enough that the
    // ground meets the trunk at its full width.
    b.position.y -= b.tree().planting_depth * t.scale;
    b.rotation = t.rotation;
    b.scale = t.scale;
    return b;
}

// The trees of `which` built: each member's first tree grown (in parallel), then the others
// sharing it. out[i] for i not in `which` is left as it is.
void grow(const SceneDesc& scene, bool bark, const std::vector<size_t>& which,
          std::vector<BuiltTree>& out) {
    // The first tree of each (family, member), in scene order: the one whose seed grows it.
    std::vector<size_t> first(scene.trees.size());
    std::vector<size_t> growers;
    {
        std::map<std::pair<uint32_t, uint32_t>, size_t> seen;
        for (size_t i : which) {
            const auto key = std::make_pair(scene.trees[i].family, tree_member(scene, i));
            auto [it, fresh] = seen.emplace(key, i);
            first[i] = it->second;
            if (fresh) growers.push_back(i);
        }
    }
    tbb::parallel_for(size_t{0}, growers.size(), [&](size_t k) {
        out[growers[k]] = build_tree(scene, growers[k], growers[k], bark, nullptr);
    });
    tbb::parallel_for(size_t{0}, which.size(), [&](size_t k) {
        const size_t i = which[k];
        if (first[i] != i) out[i] = build_tree(scene, i, first[i], bark, &out[first[i]]);
    });
}

}  // namespace

std::vector<BuiltTree> build_trees(const SceneDesc& scene, bool bark) {
    std::vector<BuiltTree> out(scene.trees.size());
    std::vector<size_t> all(scene.trees.size());
    for (size_t i = 0; i < all.size(); ++i) all[i] = i;
    grow(scene, bark, all, out);
    return out;
}

std::vector<BuiltTree> regrow_trees(const SceneDesc& scene, bool bark,
                                    const std::vector<BuiltTree>& before,
                                    const std::vector<bool>& regrow) {
    if (before.size() != scene.trees.size() || regrow.size() != scene.trees.size())
        throw std::logic_error("regrow_trees: the scene's trees are not those grown before");
    // A member is regrown with all its trees (a family's edit reaches every tree of it).
    std::vector<BuiltTree> out(scene.trees.size());
    std::vector<size_t> which;
    for (size_t i = 0; i < scene.trees.size(); ++i)
        regrow[i] ? which.push_back(i) : void(out[i] = before[i]);
    grow(scene, bark, which, out);
    return out;
}

}  // namespace pleinair
