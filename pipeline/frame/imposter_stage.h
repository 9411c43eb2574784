// The imposters stage of a frame (file 002): each imposter-bearing mesh's silhouette edges found
// from an adjacency built once, extruded along the vector field into quads, the control texture
// choosing where and which atlas row, each drawn into a patch that composites with the strokes in
// depth order. Nothing carries from frame to frame: an edge fades in as it nears the silhouette,
// so frame N alone is frame N in a sequence.
#pragma once

#include <cstdint>
#include <glm/mat3x3.hpp>
#include <memory>
#include <vector>

#include "pipeline/frame/frame_context.h"
#include "pipeline/frame/imposter_draw.h"
#include "pipeline/input/imposter_desc.h"
#include "pipeline/shot/imposter_objects.h"
#include "pipeline/shot/silhouette.h"

namespace pleinair {

struct Shot;
struct FrameView;
struct SpriteSet;
struct SeenWindow;

// What an object shows at a view: one quad per edge at or near its silhouette that the control
// allows, in edge order, with the weight that fades it (1 on the silhouette, less as the edge
// turns away from it or shrinks on screen); occlusion is the stage's. `eye_speed` (world units
// a frame, FrameView::eye_speed) widens the fade band near a moving eye: an edge d away turns
// by up to eye_speed / d radians a frame, and a band of 1.5 x fade_frames times that (the
// smoothstep's steepest slope is 1.5) keeps every edge fading over fade_frames frames at least,
// however near the eye passes.
struct ImposterCandidate {
    uint32_t edge = 0;
    ImposterQuad quad;
    float weight = 1;
};
std::vector<ImposterCandidate> imposter_candidates(const ImposterObject& o, const Camera& cam,
                                                   const glm::vec3& sun, double eye_speed = 0);

struct ImposterStageReport {
    uint64_t objects = 0;
    uint64_t candidates = 0;  // edges at or near a silhouette the control allows
    uint64_t hidden = 0;      // of those, behind an opaque surface
    uint64_t drawn = 0;
    uint64_t pixels = 0;
};

// The sprite of each imposter drawn in the frame (kind kGraftal, its patch in sprites.patches,
// its weight times the share of it seen as its fade), appended in object and edge order. The
// share seen is that of rays from points up its middle past the opaque surfaces: to the frame's
// eye from a third, two thirds and all of its height; or, with a moving camera's `seen` window
// (sprites.h), one ray to each of the window's cameras from its lattice time's height, so the
// share changes by at most 1/n a frame. Worked out in parallel; the bytes do not depend on the
// number of threads.
ImposterStageReport add_imposter_sprites(const Shot& shot, const FrameView& view,
                                         SpriteSet& sprites, const SeenWindow* seen = nullptr);

// For the coherence bench: each edge's presence at `view` (its candidate weight: 0 where it is
// not drawn, 1 on the silhouette), -1 where its middle is off screen, object by object, edge by
// edge; and the sprite keys they go by, in the same order.
std::vector<float> imposter_presences(const Shot& shot, const FrameView& view);
std::vector<uint64_t> imposter_keys(const Shot& shot);

// The imposters stage: add_imposter_sprites with the frame's seen window, its pass line.
void imposters_stage(const FrameContext& ctx, SpriteSet& sprites, const SeenWindow& seen);

}  // namespace pleinair
