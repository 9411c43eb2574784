// The painted sky's frame side (issue 13): the shot's sky strokes (shot/sky_strokes.h) turned into
// sprites each frame by the camera's rotation alone, and painted under every other stroke,
// over the background's gradient, where the surfaces leave the sky in view.
#pragma once

#include <glm/vec3.hpp>

#include "pipeline/frame/composite.h"
#include "pipeline/frame/frame_context.h"
#include "pipeline/frame/frame_plan.h"
#include "pipeline/frame/sprites.h"

namespace pleinair {

// The sky's sprites seen by the view's camera with its eye at the origin: where a stroke lies
// on screen depends on the camera's rotation and field of view only. Sprites are SpriteKind::
// kSky with the shot's sky material, behind every other sprite (their ranges are beyond any
// world distance), the small strokes in front of the large.
SpriteSet sky_sprites(const Shot& shot, const FrameView& view, const FramePlan& plan,
                      const RenderSettings& rs);

// The colour of the painted sky in a direction, as its strokes paint it before their noise:
// the palette at sky_sample's lightness, linear. Reflections read it (water).
Color sky_color(const SceneDesc& scene, const glm::vec3& direction, const glm::vec3& sun);

// The painted sky behind every stroke, where they leave it in view: its sprites and its layer.
struct SkyLayer {
    SpriteSet sprites;
    StrokeLayer layer;
};

// The sky stage: the sky's sprites painted under `strokes` (its own plan: no AOVs, for the sky
// is the background in them; no pigments or canvas, for its strokes blend among themselves,
// then lie under paint).
SkyLayer sky_stage(const FrameContext& ctx, const StrokeLayer& strokes, Frame& frame);

}  // namespace pleinair
