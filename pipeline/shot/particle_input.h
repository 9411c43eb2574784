// A particle of the shot as the painter reads it, whatever its kind: where its rays start,
// its material, world stroke size, normals and shading inputs, one rule for every reader.
#pragma once

#include <cstddef>
#include <glm/vec3.hpp>
#include <vector>

#include "pipeline/shot/built_trees.h"
#include "pipeline/shot/landscape.h"
#include "pipeline/shot/materials.h"
#include "shading/color.h"

namespace pleinair {

// Where a particle's rays start: its world position, lifted by `lift` along `normal` when it
// lies on a surface (bark, ground), so no ray hits the surface it was emitted from.
struct RayOrigin {
    glm::dvec3 world{0.0};
    glm::vec3 normal{0.0f};
    bool on_surface = false;
    float lift = 0;
    glm::dvec3 lifted() const {
        return on_surface ? world + glm::dvec3(normal) * double(lift) : world;
    }
    const glm::vec3* surface_normal() const { return on_surface ? &normal : nullptr; }
};

// What a shot's particles are read from (Shot::particles()).
struct ParticleSource {
    const SceneDesc& scene;
    const std::vector<BuiltTree>& trees;
    const BuiltLandscape& land;
    const std::vector<TreePlacement>& placements;
    const MaterialTable& materials;
    bool bark = false;       // the shot paints bark strokes (ShotPlan::bark)
    float surface_lift = 0;  // Shot::surface_lift
    size_t item_count() const { return trees.size() + land.chunks.size(); }
};

struct ParticleInput {
    SpriteKind kind = SpriteKind::kLeaf;
    glm::dvec3 world{0.0};
    glm::vec3 normal{0.0f};   // world, unit: the lighting normal
    glm::vec3 tangent{0.0f};  // world, unit (bark, surfaces), or zero (leaves)
    double width = 0;         // world units
    double length = 0;
    float center_distance = 0.5f, branch_distance = 0.5f, label = 0;
    uint32_t tree_id = 0;
    float shadow = 1;  // light reaching the particle, 0..1 (IV.4.2)
    // A ground touch at a tree's foot (ContactDesc): the light the tree leaves it, less towards
    // the trunk; 1 for every other particle.
    float contact = 1;
    // Surface strokes (IV.7): their own lightness and frequencies, the crest shrink and the
    // distance fade. Null for leaves and bark.
    const SurfaceParticles* surface = nullptr;
    size_t index = 0;
    const Color* own_color = nullptr;  // an imported particle's colour
    float own_amount = 0;
    glm::vec3 from_center{0.0f};  // leaves: unit direction from the crown's centre (world)
    bool hole = false;            // leaves: in a hole of the crown (not drawn)
};

// Particle j of kind `kind` of item `item` (tree, or surface chunk item - trees) at `o`; its
// material in `mat`.
ParticleInput particle_input(const ParticleSource& shot, size_t item, SpriteKind kind, size_t j,
                             const RayOrigin& o, MaterialId& mat);

// Where the particle's rays start (for_each_particle's origins, one at a time).
RayOrigin particle_origin(const ParticleSource& shot, size_t item, SpriteKind kind, size_t j);

// How many particles item `item` holds (what for_each_particle visits).
size_t item_particles(const ParticleSource& shot, size_t item);

// The particle's index in the order for_each_particle visits its item (the sun-light cache's).
size_t particle_slot(const ParticleSource& shot, size_t item, SpriteKind kind, size_t j);

}  // namespace pleinair
