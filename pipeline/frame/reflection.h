// Still water as a broken mirror (issue 13 §2): a water stroke takes the colour its reflected
// ray finds (terrain, rocks and trunks through the camera's scene, leaf strokes through the
// sun's stroke casters, the painted sky or the background where it meets nothing), in the
// share water's Fresnel reflectance gives, so the far bank hangs upside down in the pond in
// broken horizontal strokes and the water darkens to its own colour towards the viewer.
#pragma once

#include <cstdint>
#include <glm/vec3.hpp>

#include "pipeline/frame/frame_context.h"
#include "pipeline/frame/frame_plan.h"
#include "pipeline/frame/sprites.h"

namespace pleinair {

struct Shot;
struct RayOrigin;
class RayScene;

// Schlick's approximation of water's reflectance (F0 = 0.02) at the cosine of the angle
// between the view and the normal; 1 at grazing angles.
float water_reflectance(float cos_view);

// What a frame's mirrors read, gathered once per frame.
struct MirrorContext {
    const Shot& shot;
    const FrameView& view;
    const FramePlan& plan;  // the frame's; hits are coloured without atmosphere or mirrors
    const RenderSettings& settings;
    const RayScene* sun_rays = nullptr;  // the leaf strokes' casters, when the frame has them
    Color foliage{0.0f};  // a reflected leaf stroke: the families' leaf palettes in shade
    FramePlan flat;       // the plan hits are coloured by: no atmosphere, no mirror, no notes
};
MirrorContext mirror_context(const Shot& shot, const FrameView& view, const FramePlan& plan,
                             const RenderSettings& settings, const RayScene* sun_rays);

// Sets k.mirror and k.mirror_keep for water at `at`: the mean of what the view `dir` (unit,
// from the eye) reflected about each of `count` normals (unit; ripples lean them off the
// water's normal `up`) finds. Returns the rays cast.
inline constexpr int kMaxMirrorRays = 16;
int mirror(const MirrorContext& c, const RayOrigin& at, const glm::vec3* normals, int count,
           const glm::vec3& up, const glm::dvec3& dir, StrokeConstants& k);

struct ReflectionReport {
    uint64_t strokes = 0, rays = 0;
};

// Every water stroke's mirror for the frame, in parallel (the plan's reflections).
ReflectionReport add_reflections(const MirrorContext& c, SpriteSet& sprites);

// The reflections stage: add_reflections for the frame, its rays in the report.
void reflections_stage(const FrameContext& ctx, const RayScene* sun_rays, SpriteSet& sprites);

}  // namespace pleinair
