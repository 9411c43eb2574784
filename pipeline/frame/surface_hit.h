// What a ray that meets a surface of the camera's scene sees there, as the underpainting paints
// it: its material's palette at a middle-depth stroke's lightness, in the sun's light and
// shadow, pushed into the distance when the plan has atmosphere. Water's mirror is added by its
// callers (the underpainting); a mirror's own hits stop here, so mirrors do not recurse.
#pragma once

#include <glm/vec3.hpp>

#include "pipeline/frame/frame_plan.h"
#include "pipeline/frame/frame_view.h"
#include "pipeline/shot/materials.h"
#include "pipeline/shot/rays.h"
#include "shading/stroke_shader.h"

namespace pleinair {

struct Shot;

struct SurfaceHit {
    StrokeConstants k;   // the stroke constants a middle-depth stroke there has
    Color base;          // its palette colour, before finish_color
    bool water = false;  // the hit is still water (the underpainting mirrors it)
    glm::vec3 n{0.0f};   // the normal, facing the ray
    MaterialId material;
    float sun = 1.0f;  // the sun's light reaching it past its casters (1 without shadows)
};

// The material a hit `h` of the camera's scene shows at `world`, and whether it is still water:
// surface_hit's own rule, without the shading.
MaterialId surface_material(const Shot& shot, const RayHit& h, const glm::dvec3& world,
                            bool& water);

// The hit `h` at `world` (normal n, seen along dir), in the plan's atmosphere at `depth` (< 0:
// its depth from the view's camera; a mirror gives the length of the light's path).
SurfaceHit surface_hit(const Shot& shot, const FrameView& view, const FramePlan& plan,
                       const RenderSettings& settings, const RayScene* sun_rays, const RayHit& h,
                       const glm::dvec3& world, glm::vec3 n, const glm::dvec3& dir,
                       float depth = -1.0f);
// Its flat colour, linear: finish_color of the two.
Color surface_hit_color(const Shot& shot, const FrameView& view, const FramePlan& plan,
                        const RenderSettings& settings, const RayScene* sun_rays, const RayHit& h,
                        const glm::dvec3& world, const glm::vec3& n, const glm::dvec3& dir,
                        float depth = -1.0f);

}  // namespace pleinair
