// One graftal imposter drawn in a frame (file 002's equations 5.9.2-5.9.5): its quad inverted
// pixel by pixel into its atlas cell, sampled trilinearly and keyed with the surface's colour.
#pragma once

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "pipeline/input/camera.h"
#include "pipeline/shot/graftal_draw.h"
#include "pipeline/shot/imposter_atlas.h"

namespace pleinair {

// The paper's keyed blend for one atlas sample (premultiplied): the outline's (0, g, b) where
// the key red is 0, the surface's colour where it is 1, between them in proportion; alpha kept.
// Premultiplied linear RGB and alpha out.
glm::vec4 keyed_blend(const glm::vec4& atlas_premultiplied, const glm::vec3& surface_linear);

// One imposter as the frame draws it: the quad (base v0, v1 on the silhouette edge; tips
// extruded from them) in the world, its atlas cell and the surface's colour at each end.
struct ImposterQuad {
    glm::dvec3 v0{0.0}, v1{0.0}, t0{0.0}, t1{0.0};
    int row = 0, column = 0;
    glm::vec3 color0{1.0f}, color1{1.0f};  // linear, shaded
    float opacity = 1;
};

// The quad as `cam` sees it, textured from its atlas cell (trilinear between the two levels that
// bracket its size on screen) and keyed, into an 8-bit premultiplied sRGB patch like a graftal's.
// Empty when a corner lies behind the near plane or it misses the frame; `max_px` bounds the
// patch's side. Pure: the same arguments give the same bytes on any thread.
GraftalPatch draw_imposter(const ImposterAtlas& atlas, const ImposterQuad& q, const Camera& cam,
                           int max_px = 2048);

}  // namespace pleinair
