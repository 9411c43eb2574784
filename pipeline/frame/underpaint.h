// The underpainting stage of a frame: a flat palette colour where the camera sees a surface and
// the strokes leave gaps, at a fraction of the resolution.
#pragma once

#include <cstdint>

#include "pipeline/frame/composite.h"
#include "pipeline/frame/frame_context.h"
#include "pipeline/frame/frame_view.h"
#include "pipeline/frame/surface_hit.h"
#include "pipeline/shot/rays.h"

namespace pleinair {

struct Shot;
struct MirrorContext;

// The flat palette colour the underpainting gives a camera-scene hit `h` at `world` (normal n,
// seen along dir): its material's palette at a middle-depth stroke's lightness, in the sun's
// light and shadow, pushed into the distance when the plan has atmosphere; water mirrors what
// it reflects when the plan has reflections, through `mirrors` (the frame's mirror_context,
// built once). `seen`, when given, receives the surface as surface_hit saw it.
Color underpaint_color(const Shot& shot, const FrameView& view, const FramePlan& plan,
                       const RenderSettings& settings, const RayScene* sun_rays, const RayHit& h,
                       const glm::dvec3& world, glm::vec3 n, const glm::dvec3& dir,
                       const MirrorContext& mirrors, SurfaceHit* seen = nullptr);

// A flat palette colour and a depth where the camera sees terrain, water, rocks or trunks, at
// underpaint_scale of the resolution, so no sky shows between strokes, over the background.
// Coverage is interpolated, so silhouettes stay soft. Only cells under pixels the strokes leave
// open are painted (all of them when the AOVs ask for depth), each casting its camera ray; every
// other cell each way is shaded (its shadow ray, water's mirror), and a cell between traced ones
// takes their mean where they see one surface in one light and colour (underpaint.cpp's
// UnderpaintCells), else is shaded too; `shade_every_cell` (tests, benchmarks) shades them all.
// Returns the camera rays cast and the cells shaded.
struct UnderpaintRays {
    uint64_t camera = 0, shaded = 0;
};
UnderpaintRays paint_underpainting(const Shot& shot, const FrameView& view, const FramePlan& plan,
                                   const RenderSettings& settings, const RayScene* sun_rays,
                                   const StrokeLayer& strokes, Frame& frame,
                                   bool shade_every_cell = false);

// The underpainting stage: paint_underpainting, its camera rays in the report.
void underpaint_stage(const FrameContext& ctx, const RayScene* sun_rays, const StrokeLayer& strokes,
                      Frame& frame);

}  // namespace pleinair
