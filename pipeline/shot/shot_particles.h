// for_each_particle: the one walk over a shot's particles that the sprites stage and the sun
// light cache share, so a particle's ray origin and its index in the cache always agree.
#pragma once

#include "pipeline/shot/shot.h"

namespace pleinair {

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
        const BarkParticles& B = b.bark;
        const float lift =
            static_cast<float>(0.02 * shot.scene.families[b.family].params.unit * b.scale);
        for (size_t j = 0; j < B.size(); ++j)
            fn(SpriteKind::kBark, j,
               RayOrigin{pl.place(B.position[j]), pl.turn(B.normal[j]), true, lift});
    }
    const LeafParticles& L = b.tree.leaves;
    for (size_t j = 0; j < L.size(); ++j)
        fn(SpriteKind::kLeaf, j, RayOrigin{pl.place(L.position[j]), glm::vec3(0.0f), false, 0.0f});
}

}  // namespace pleinair
