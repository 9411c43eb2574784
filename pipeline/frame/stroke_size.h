// A brush stroke's size on screen: its world size at a view depth, under the stroke
// perspective (thesis ch. I: brush strokes do not shrink like geometry).
#pragma once

#include "pipeline/input/camera.h"
#include "pipeline/input/settings.h"

namespace pleinair {

// Screen size in pixels of a world length at view depth z: true perspective at
// stroke_perspective 1, the size it has at the camera's focus distance whatever the depth at 0,
// in between otherwise. The painter then enlarges anything under min_stroke_px.
float stroke_screen_px(const Camera& cam, const RenderSettings& r, double world, double depth);

}  // namespace pleinair
