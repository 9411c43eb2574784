// Catmull-Clark subdivision of closed quad meshes on flat arrays.
//
// OpenMesh's CatmullClarkT gives the same surface but works through its general half-edge
// kernel and per-element properties; on a tree's control mesh it is several times slower than
// this flat version (tests/bench, BM_Subdivide*), which generation uses. Tests check that both
// give the same vertices.
#pragma once

#include "generators/quad_mesh.h"

namespace pleinair {

// `levels` rounds of Catmull-Clark. The input must be closed (check_mesh().closed); throws
// std::invalid_argument otherwise. Vertex order: old vertices, then edge points, then face
// points, so level-0 vertices keep their indices. Face order: face f's children are faces
// 4f .. 4f + 3, child c starting at f's corner c; after `levels` rounds, f's pieces are faces
// f * 4^levels .. (f + 1) * 4^levels - 1 (bark strokes find a limb's render faces this way).
QuadMesh catmull_clark(const QuadMesh& mesh, int levels);

}  // namespace pleinair
