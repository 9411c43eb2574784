// Small meshes for mesh tests.
#pragma once

#include "generators/quad_mesh.h"

namespace pleinair::test {

// The cube [-h, h]^3, faces counter-clockwise from outside. Corner i has x = bit 0, y = bit 1,
// z = bit 2 (0 -> -h, 1 -> +h).
inline QuadMesh cube(float h) {
    QuadMesh m;
    for (int i = 0; i < 8; ++i)
        m.positions.emplace_back(i & 1 ? h : -h, i & 2 ? h : -h, i & 4 ? h : -h);
    m.quads = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
    return m;
}

}  // namespace pleinair::test
