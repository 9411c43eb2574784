// A shot: everything that does not depend on the frame time, built once per process (trees
// grown and placed, surface strokes, the material table, Embree scenes and the sun's stroke
// casters, and the light each particle gets from a still sun); frames are painted from it.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "generators/wind.h"
#include "pipeline/input/scene.h"
#include "pipeline/shot/built_trees.h"
#include "pipeline/shot/graftal_instances.h"
#include "pipeline/shot/imposter_objects.h"
#include "pipeline/shot/landscape.h"
#include "pipeline/shot/leaf_basis.h"
#include "pipeline/shot/materials.h"
#include "pipeline/shot/particle_clusters.h"
#include "pipeline/shot/particle_input.h"
#include "pipeline/shot/pass_report.h"
#include "pipeline/shot/rays.h"
#include "pipeline/shot/sky_strokes.h"
#include "pipeline/shot/sun_light_cache.h"

namespace pleinair {

// The tree's leaf strokes as shadow casters: cards facing the sun, sized and turned like the
// strokes, with the same noise (IV.4.2), placed in the world. The shot's sun scenes place its
// member's cards by instances instead (member_casters); these are what those are tested against.
std::vector<StrokeCaster> leaf_casters(const SceneDesc& scene, const BuiltTree& tree,
                                       const glm::vec3& sun);
// The same, written to out[0 .. tree.tree().leaves.size() - 1].
void leaf_casters(const SceneDesc& scene, const BuiltTree& tree, const glm::vec3& sun,
                  StrokeCaster* out);

struct Shot;

// A tree's member's leaf strokes as casters in its own space (rays.h), for the sun's scenes to
// place by instances: built once per grown tree, whatever the sun.
MemberCasters member_casters(const Shot& shot, const BuiltTree& tree);

// The particle files' strokes that cast shadows (ParticleFileDesc::casts_shadows), as cards
// facing the sun like leaf strokes', per scene material.
std::vector<std::vector<StrokeCaster>> imported_casters(const Shot& shot, const glm::vec3& sun);

struct ShotOptions {
    // Each particle's light from a still sun, kept in the shot for every frame once a frame
    // has traced it (animations); off, each frame traces it for the particles it shows. The
    // light is the same either way.
    bool cache_sun_light = false;
    // An earlier shot of the same trees and landscape (the same objects) whose families name
    // the same styles and imposters: its graftal tufts and imposter meshes, which read nothing
    // else of the scene, are taken instead of placed again (the studio after a shader, sun or
    // camera change). Null, or another shot's trees or landscape: built.
    const Shot* carry_from = nullptr;
};

// What the shot holds, decided from the scene alone.
struct ShotPlan {
    bool bark = false;        // bark strokes grown and painted (render/bark_coverage > 0)
    bool shadows = false;     // the sun casts shadows and something is there to cast them
    bool sun_moves = false;   // a keyed sun: its scene and the light are traced per frame
    bool underpaint = false;  // a visible mesh (terrain, water, rocks): the camera's ray scene
    bool sun_light = false;   // each particle's light kept in the shot once traced
    bool wind = false;        // a /wind that ever blows: the trees' rigs are built
};

// What a camera-scene geometry is painted with underneath: a material, or the terrain's (which
// varies over it).
struct ViewSurface {
    bool terrain = false;
    MaterialId material;
};

// Immutable once built; nothing in it points into itself, so it may be moved (animate holds it
// on the heap). Not copied: its Embree scenes are owned once.
struct Shot {
    SceneDesc scene;
    ShotPlan plan;
    std::shared_ptr<const std::vector<BuiltTree>> trees;
    std::shared_ptr<const BuiltLandscape> land;
    std::vector<TreePlacement> placements;  // one per tree
    MaterialTable materials;
    float surface_lift = 0;  // surface strokes' rays start above the deepest strokes

    // Embree: each tree's limbs built once, placed by instances in the camera's scene and the
    // sun's; the anchor (the still camera's eye) keeps far landscapes precise in float.
    glm::dvec3 anchor{0.0};
    std::unique_ptr<RayMeshes> limbs;
    std::vector<uint32_t> limb_mesh;      // per tree, its grown tree's mesh in `limbs`
    std::unique_ptr<RayScene> view_rays;  // plan.underpaint
    std::vector<ViewSurface> view_surfaces;
    std::unique_ptr<RayScene> sun_rays;  // plan.shadows and a still sun
    // plan.sun_light: per item (trees, then surface chunks), per particle in the order
    // for_each_particle visits them, the light reaching it, traced when a frame first shows
    // the particle (the one part of a shot that frames fill in, sun_light_cache.h).
    std::unique_ptr<SunLightCache> sun_light;
    // Per item, its particles grouped by place with the bounds a frame culls them by, a group
    // at a time (particle_clusters.h).
    std::vector<ItemClusters> clusters;
    // Per tree, its member's leaves as the level of detail reads them (leaf_basis.h), shared by
    // the trees of one member; empty when the scene turns the level of detail off.
    std::vector<std::shared_ptr<const LeafBasis>> leaf_basis;
    // Per tree, its member's wind rig (generators/wind.h), shared by the trees of one member;
    // empty in still air (plan.wind false).
    std::vector<std::shared_ptr<const WindRig>> wind_rigs;

    // The graftal-styled families' crowns and materials' surfaces (graftal_stage.h); their
    // leaf and surface strokes are not painted. Graftal sprites' items count on from
    // item_count().
    std::vector<ShotGraftals> graftals;
    // The meshes that carry graftal imposters on their silhouettes (imposter_stage.h); their
    // sprites' items count on after the graftals'.
    std::vector<ImposterObject> imposters;

    // The painted sky's strokes (sky_strokes.h); empty without a /sky.
    SkyStrokes sky;

    std::vector<PassReport> passes;  // what the build did, for --explain

    Shot() = default;
    Shot(Shot&&) = default;
    Shot& operator=(Shot&&) = default;
    Shot(const Shot&) = delete;

    size_t item_count() const { return trees->size() + land->chunks.size(); }
    ParticleSource particles() const {
        return {scene, *trees, *land, placements, materials, plan.bark, surface_lift};
    }
};

// particle_input.h's readers, of a shot.
inline ParticleInput particle_input(const Shot& shot, size_t item, SpriteKind kind, size_t j,
                                    const RayOrigin& o, MaterialId& mat) {
    return particle_input(shot.particles(), item, kind, j, o, mat);
}
inline RayOrigin particle_origin(const Shot& shot, size_t item, SpriteKind kind, size_t j) {
    return particle_origin(shot.particles(), item, kind, j);
}
inline size_t item_particles(const Shot& shot, size_t item) {
    return item_particles(shot.particles(), item);
}
inline size_t particle_slot(const Shot& shot, size_t item, SpriteKind kind, size_t j) {
    return particle_slot(shot.particles(), item, kind, j);
}

// Builds the shot of a scene: grows the trees and the landscape, then everything else.
Shot build_shot(SceneDesc scene, const ShotOptions& options = {});
// The same from trees and a landscape already built from this scene (shared, not copied).
Shot build_shot(SceneDesc scene, std::shared_ptr<const std::vector<BuiltTree>> trees,
                std::shared_ptr<const BuiltLandscape> land, const ShotOptions& options = {});

// The sun's scene for a sun direction (unit, towards the sun): surfaces, limbs and leaf strokes
// as cards facing it. Built by the shot for a still sun, per frame for a keyed one.
std::unique_ptr<RayScene> build_sun_scene(const Shot& shot, const glm::vec3& sun);

// The light reaching a particle from the sun through the sun's scene.
float sun_light_at(const RayScene& sun_rays, const RayOrigin& origin, const glm::vec3& sun,
                   ShadowMode mode);

// How far a bark stroke's rays start off its limb: 2% of the tree's unit.
inline float bark_ray_lift(const Shot& shot, const BuiltTree& b) {
    return static_cast<float>(0.02 * shot.scene.families[b.family].params.unit * b.scale);
}

// Visits every particle of item i (tree i, then surface chunk i - trees): for a tree its bark
// strokes (when the plan paints bark) then its leaves; fn(kind, index, origin).
template <class Fn>
void for_each_particle(const Shot& shot, size_t item, Fn&& fn);

template <class Fn>
void for_each_particle(const Shot& shot, size_t item, Fn&& fn) {
    const std::vector<BuiltTree>& trees = *shot.trees;
    if (item >= trees.size()) {
        const SurfaceParticles& S = shot.land->chunks[item - trees.size()];
        for (size_t j = 0; j < S.size(); ++j)
            fn(SpriteKind::kSurface, j,
               RayOrigin{glm::dvec3(S.position[j]), S.normal(j), true, shot.surface_lift});
        return;
    }
    const BuiltTree& b = trees[item];
    const TreePlacement& pl = shot.placements[item];
    if (shot.plan.bark) {
        const BarkParticles& B = b.bark();
        const float lift = bark_ray_lift(shot, b);
        for (size_t j = 0; j < B.size(); ++j)
            fn(SpriteKind::kBark, j,
               RayOrigin{pl.place(B.position[j]), pl.turn(B.normal[j]), true, lift});
    }
    const LeafParticles& L = b.tree().leaves;
    for (size_t j = 0; j < L.size(); ++j)
        fn(SpriteKind::kLeaf, j, RayOrigin{pl.place(L.position[j]), glm::vec3(0.0f), false, 0.0f});
}

}  // namespace pleinair
