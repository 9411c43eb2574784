// The scene's trees as grown, before the shot: each tree's geometry and bark strokes with where
// it stands (BuiltTree), and the placement that takes tree-local points into the world. The
// shot and its once-per-shot builders (graftals, imposters) read them.
#pragma once

#include <cstdint>
#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>
#include <memory>
#include <vector>

#include "generators/bark.h"
#include "generators/tree.h"
#include "pipeline/input/scene.h"

namespace pleinair {

struct BuiltTree {
    // Tree-local geometry and bark strokes, which the transform below places: shared by every
    // tree drawn from one member of its family (Family::members). Builders fill them in before
    // they are shared; nothing changes them after.
    std::shared_ptr<Tree> grown = std::make_shared<Tree>();
    std::shared_ptr<BarkParticles> bark_strokes = std::make_shared<BarkParticles>();
    Tree& tree() { return *grown; }
    const Tree& tree() const { return *grown; }
    BarkParticles& bark() { return *bark_strokes; }
    const BarkParticles& bark() const { return *bark_strokes; }
    // This tree's own number (its index in the scene): its strokes' noise and tint and its
    // object id, so no two trees drawn from one member look stamped.
    uint32_t id = 0;
    uint32_t member = 0;  // which of its family's grown trees (its index when not shared)
    uint32_t family = 0;
    glm::dvec3 position{0.0};
    double rotation = 0;  // about +y, degrees
    double scale = 1;
};

// A tree's placement in the world: rotation about +y and scale, then its position (in double).
struct TreePlacement {
    double c = 1, s = 0, scale = 1;
    glm::dvec3 position{0.0};
    glm::dvec3 place(const glm::vec3& tree_local) const;
    glm::vec3 turn(const glm::vec3& direction) const;
    glm::dmat3 linear() const;  // place(p) = position + linear() * p
};
TreePlacement placement(const BuiltTree& tree);

// A stroke's world width on a tree of `family`: the shader's sprite_size in the tree's units,
// times the tree's scale. Leaves, bark strokes and the leaves' shadow casters agree through it.
double tree_stroke_width(const Family& family, const StrokeShaderParams& shader, double scale);

// The bark strokes of a tree of `family` (its bark shader's size and aspect) at a coverage.
BarkParticles family_bark(const Family& family, const Tree& tree, float coverage, uint64_t seed);

// Generates every tree of the scene (in parallel; the result does not depend on threads), with
// bark strokes when `bark`. A family with members grows that many trees once, each from the
// seed of the first of its trees to draw it, and its trees share them (tree_member).
std::vector<BuiltTree> build_trees(const SceneDesc& scene, bool bark = true);

// Which member of its family scene tree i is drawn from: drawn from its seed among the
// family's members, or i itself when the family grows every tree (members 0).
uint32_t tree_member(const SceneDesc& scene, size_t i);
// The same where `regrow[i]`, the others copied from `before` (the trees the same scene grew
// before a change that reached only those): what build_trees would give, for less work.
std::vector<BuiltTree> regrow_trees(const SceneDesc& scene, bool bark,
                                    const std::vector<BuiltTree>& before,
                                    const std::vector<bool>& regrow);

}  // namespace pleinair
