// The trunk generator: a cube of the preset's initial size, extruded upward from its top face
// until a maximum height or number of steps (thesis IV.3, Fig. 11).
#pragma once

#include "generators/tree_mesh.h"

namespace pleinair {

// Builds the cube as limb 0 of an empty TreeMesh and grows it. Draws from the streams
// (seed, kTree) and (seed, kTrunk) only.
void grow_trunk(TreeMesh& tm, const TreeParams& params, uint64_t seed);

}  // namespace pleinair
