// The branch generator: side faces of a parent limb sprout branches, each a short first
// extrusion forced square and planar, then per-step extrusions (thesis IV.3, Fig. 12), with an
// optional tropism and a second level the thesis lacks.
#pragma once

#include "generators/tree_mesh.h"

namespace pleinair {

// Grows one level of branches (level 1 from the trunk, level 2 from level-1 branches). Each
// side face draws from its own streams keyed by (parent key, segment, side), so changing one
// branch never changes another.
void grow_branches(TreeMesh& tm, const BranchParams& params, int level, uint64_t seed);

}  // namespace pleinair
