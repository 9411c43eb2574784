// The painted sky's strokes (issue 13), laid once per shot over the sky's directions; the frame
// turns them into sprites by the camera's rotation alone (frame/sky_sprites.h).
#pragma once

#include <cstdint>
#include <glm/vec3.hpp>
#include <vector>

#include "pipeline/input/scene.h"

namespace pleinair {

// The sky's strokes as directions (world, unit) from the eye: rows of equal angular height
// from just under the horizon to the zenith, each row's strokes spaced by equal angles, a
// jittered place in each cell. Two layers: base strokes of /sky/stroke_size, and half-size
// strokes that only cloud edges keep.
struct SkyStrokes {
    std::vector<glm::vec3> direction;
    std::vector<float> label;    // 0..1: noise offsets, size and angle jitter, order
    std::vector<uint8_t> small;  // 1: an edge stroke
    size_t size() const { return direction.size(); }
};

// Deterministic in /sky/seed; empty when the scene has no sky (or paints a canvas).
SkyStrokes build_sky_strokes(const SceneDesc& scene);

}  // namespace pleinair
