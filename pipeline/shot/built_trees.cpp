// build_trees and the trees' placements: every tree of the scene grown (in parallel, the same
// whatever the threads), its bark strokes emitted, planted so the ground meets its full trunk.
#include "pipeline/shot/built_trees.h"

#include <tbb/parallel_for.h>

#include <cmath>
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

namespace {

BuiltTree build_tree(const SceneDesc& scene, size_t i, bool bark) {
    const PlacedTree& t = scene.trees[i];
    const Family& f = scene.families[t.family];
    TreeOptions o;
    o.tree_id = static_cast<uint32_t>(i);
    o.lod = false;
    BuiltTree b;
    b.tree = generate_tree(f.params, t.seed, o);
    b.family = t.family;
    b.position = t.position;
    // Catmull-Clark rounds the trunk's base into a dome: plant the tree deep enough that the
    // ground meets the trunk at its full width.
    b.position.y -= b.tree.planting_depth * t.scale;
    b.rotation = t.rotation;
    b.scale = t.scale;
    if (bark) b.bark = family_bark(f, b.tree, scene.build.bark_coverage, t.seed);
    return b;
}

}  // namespace

std::vector<BuiltTree> build_trees(const SceneDesc& scene, bool bark) {
    std::vector<BuiltTree> out(scene.trees.size());
    tbb::parallel_for(size_t{0}, scene.trees.size(),
                      [&](size_t i) { out[i] = build_tree(scene, i, bark); });
    return out;
}

std::vector<BuiltTree> regrow_trees(const SceneDesc& scene, bool bark,
                                    const std::vector<BuiltTree>& before,
                                    const std::vector<bool>& regrow) {
    if (before.size() != scene.trees.size() || regrow.size() != scene.trees.size())
        throw std::logic_error("regrow_trees: the scene's trees are not those grown before");
    std::vector<BuiltTree> out(scene.trees.size());
    tbb::parallel_for(size_t{0}, scene.trees.size(), [&](size_t i) {
        out[i] = regrow[i] ? build_tree(scene, i, bark) : before[i];
    });
    return out;
}

}  // namespace pleinair
