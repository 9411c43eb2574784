// The painted sky (issue 13): strokes laid over the sky's directions once per shot, turned into
// sprites each frame by the camera's rotation alone, and painted under every other stroke,
// over the background's gradient, where the surfaces leave the sky in view.
#pragma once

#include <cstdint>
#include <glm/vec3.hpp>
#include <vector>

#include "pipeline/frame/frame_plan.h"
#include "pipeline/frame/sprites.h"

namespace pleinair {

struct SkyDesc;

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

// The sky's sprites seen by the view's camera with its eye at the origin: where a stroke lies
// on screen depends on the camera's rotation and field of view only. Sprites are SpriteKind::
// kSky with the shot's sky material, behind every other sprite (their ranges are beyond any
// world distance), the small strokes in front of the large.
SpriteSet sky_sprites(const Shot& shot, const FrameView& view, const FramePlan& plan,
                      const RenderSettings& rs);

// The colour of the painted sky in a direction, as its strokes paint it before their noise:
// the palette at sky_sample's lightness, linear. Reflections read it (water).
Color sky_color(const SceneDesc& scene, const glm::vec3& direction, const glm::vec3& sun);

}  // namespace pleinair
