// Still water as a broken mirror (issue 13 §2): a water stroke takes the colour its reflected
// ray finds (terrain, rocks and trunks through the camera's scene, leaf strokes through the
// sun's stroke casters, the painted sky or the background where it meets nothing), in the
// share water's Fresnel reflectance gives, so the far bank hangs upside down in the pond in
// broken horizontal strokes and the water darkens to its own colour towards the viewer.
#pragma once

#include <cstdint>
#include <glm/vec3.hpp>
#include <vector>

#include "pipeline/frame/frame_context.h"
#include "pipeline/frame/frame_plan.h"
#include "pipeline/frame/sprites.h"

namespace pleinair {

struct Shot;
struct RayOrigin;
class RayScene;
class MirrorMemo;

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
    // A reflected leaf stroke: the families' leaf palettes in shade, each pushed into the
    // distance by its leaf shader's atmosphere at kFoliageDepths distances from the
    // atmosphere's near to its far (one colour when the frame has no atmosphere).
    static constexpr int kFoliageDepths = 33;
    std::vector<Color> foliage;
    FramePlan flat;  // the plan hits are coloured by: the frame's atmosphere, no mirror, no notes
};
// The reflected leaves' colour at the end of a light path this long (MirrorContext::foliage,
// interpolated).
Color mirrored_foliage(const MirrorContext& c, float distance);
MirrorContext mirror_context(const Shot& shot, const FrameView& view, const FramePlan& plan,
                             const RenderSettings& settings, const RayScene* sun_rays);

// The mean of what the view `dir` (unit, from the eye, `eye_distance` away) reflected about each
// of `count` normals (unit; ripples lean them off the water's normal) finds from water at `at`,
// in the haze of the light's whole path (eye to water to what it meets). Adds its rays.
inline constexpr int kMaxMirrorRays = 16;
Color mirror_seen(const MirrorContext& c, const RayOrigin& at, const glm::vec3* normals, int count,
                  const glm::dvec3& dir, double eye_distance, int& rays);
// k.mirror and k.mirror_keep from what the mirror saw (greyed by /water/mirror_saturation), in
// the share water's Fresnel reflectance gives the view `dir` against the water's normal `up`;
// k.lightness falls by that share (the water's dark body shows where it does not mirror).
void set_mirror(const MirrorContext& c, const Color& seen, const glm::vec3& up,
                const glm::dvec3& dir, StrokeConstants& k);
// Both for one view: set_mirror from mirror_seen. Returns the rays cast.
int mirror(const MirrorContext& c, const RayOrigin& at, const glm::vec3* normals, int count,
           const glm::vec3& up, const glm::dvec3& dir, double eye_distance, StrokeConstants& k);

// Where a moving camera's mirrors are traced from (render/reflection_frames K > 1; a still
// sun): a water stroke traces its mirror from the eye at lattice times m (frame m + 1 of the
// track's clock) congruent to its own phase modulo K, so a K-th of the strokes trace in any
// one frame, and takes the colour between two of them linearly; the Fresnel share stays the
// frame's own. A mirror read through ripples changes colour wherever its rays cross an edge,
// and linear in time it cannot jump from one frame to the next. frames 1: the frame's eye.
struct MirrorLattice {
    int frames = 1;
    double u = 0;                  // the frame's time in frames of the track's clock
    int64_t base = 0;              // floor(u)
    int64_t first = 0;             // the lattice time of eyes[0]
    std::vector<glm::dvec3> eyes;  // base - K + 1 .. base + K
};
MirrorLattice mirror_lattice(const SceneDesc& scene, const FrameView& view, int frames);
// A water particle's phase on a lattice of `frames`, drawn from its label: its lattice times
// are those congruent to it.
int64_t mirror_phase(float label, int frames);

struct ReflectionReport {
    uint64_t strokes = 0, rays = 0;
};

// Every water stroke's mirror for the frame, in parallel (the plan's reflections): from the
// frame's eye, or on `lattice` when it has frames > 1, the lattice times' mirrors read from
// and kept in `memo` when there is one.
ReflectionReport add_reflections(const MirrorContext& c, SpriteSet& sprites,
                                 const MirrorLattice* lattice = nullptr,
                                 MirrorMemo* memo = nullptr);

// The reflections stage: add_reflections for the frame, its rays in the report.
void reflections_stage(const FrameContext& ctx, const RayScene* sun_rays, SpriteSet& sprites);

}  // namespace pleinair
