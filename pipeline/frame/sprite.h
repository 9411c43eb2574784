// One brush stroke on screen: what the sprites stage makes of a particle, and what the depth
// order, the painter and the frames' kept memory (buffer_pool.h) read.
#pragma once

#include <cstdint>

#include "pipeline/shot/materials.h"
#include "shading/stroke_shader.h"

namespace pleinair {

// The object id a surface stroke of scene material `material` carries in the frame's AOV:
// after every tree's (tree id + 1 stays below it).
inline uint32_t surface_object_id(uint32_t material) { return 0x10000u + material; }

struct Sprite {
    float x = 0, y = 0, depth = 0;
    float range = 0;  // distance from the eye: what the depth order sorts by
    // The most its range can change in one frame against that of a sprite overlapping it on
    // screen: the eye's travel times the sprite's angular radius (0 for a still camera).
    float swap_speed = 0;
    float half_w = 0, half_l = 0;  // across and along the stroke, pixels
    float ax = 0, ay = 1;          // unit screen direction of the stroke's length
    // Fading with distance (IV.6, IV.7): 1 whole, 0 gone. A fade raises the stroke's noise
    // threshold (composite.cpp), so it breaks into dabs and vanishes with crisp edges.
    float fade = 1;
    int32_t grid = -1;   // its shadow grid, with shadows per fragment
    int32_t patch = -1;  // a graftal's patch in SpriteSet::patches
    MaterialId material;
    uint32_t object_id = 0;  // frame_image.h's AOV: see surface_object_id for surfaces
    SpriteKind kind = SpriteKind::kLeaf;
    // Which particle: stable from frame to frame (the coherence bench follows it).
    uint32_t item = 0, particle = 0;
    StrokeConstants k;
};

// A particle's key, unique in its shot: item, kind (3 bits) and index.
inline uint64_t particle_key(uint32_t item, SpriteKind kind, uint32_t particle) {
    return (uint64_t{item} << 35) | (uint64_t(kind) << 32) | particle;
}
inline uint64_t sprite_key(const Sprite& sp) { return particle_key(sp.item, sp.kind, sp.particle); }

}  // namespace pleinair
