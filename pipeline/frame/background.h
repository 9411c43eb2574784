// The background stage of a frame: sky and ground seen from the camera (or a canvas), with slow
// noise, where the strokes leave it in view, the painted sky's strokes over its sky share.
#pragma once

#include <glm/vec3.hpp>

#include "pipeline/frame/composite.h"
#include "pipeline/frame/frame_context.h"
#include "pipeline/frame/frame_image.h"
#include "pipeline/input/camera.h"
#include "pipeline/input/scene.h"

namespace pleinair {

// Sky and ground seen from the camera (or the canvas colour), with slow noise, where the
// strokes let it show; under the painted sky's strokes (`sky`, painted behind `strokes`) when
// the scene has them.
void paint_background(const SceneDesc& scene, const Camera& cam, const StrokeLayer& strokes,
                      Frame& frame, const StrokeLayer* sky = nullptr);

// The background's colour (linear, before its lattice and the painted sky) in a unit
// direction: what a reflected ray that meets nothing sees when the scene has no painted sky.
Color background_at(const Background& background, const glm::dvec3& direction);

// The background stage: paint_background under the strokes and the painted sky's layer.
void background_stage(const FrameContext& ctx, const StrokeLayer& strokes, const StrokeLayer* sky,
                      Frame& frame);

}  // namespace pleinair
