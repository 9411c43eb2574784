// The graftals stage of a frame (file 000): each tuft's level chosen from its λ, filtered and
// switched with hysteresis along the camera track replayed from its first frame (and, placed by
// the difference image, whether and how strongly it is placed), its graftals posed (σ, ρ, τ, λ)
// and drawn into patches, each patch a sprite that composites with the strokes in depth order.
#pragma once

#include <cstdint>
#include <vector>

#include "pipeline/frame/frame_context.h"
#include "pipeline/frame/sprites.h"
#include "pipeline/shot/graftal_instances.h"

namespace pleinair {

struct Shot;
struct FrameView;

struct GraftalStageReport {
    uint64_t tufts = 0;              // in the shot
    uint64_t drawn = 0;              // graftals drawn this frame
    uint64_t growing = 0;            // of those, growing in or fading out (0 < τ < 1)
    uint64_t culled = 0;             // off screen, through the near plane or not at their level
    uint64_t pixels = 0;             // patch pixels rasterised
    uint64_t replayed = 0;           // frames of the track replayed for the tufts' filters
    double draw_ms = 0;              // of the stage's time, drawing the patches (Cairo)
    std::vector<uint64_t> at_level;  // tufts at each level after filtering, over every group
};

// The sprite of each graftal drawn in the frame (kind kGraftal, its patch in sprites.patches,
// its τ times its placement's weight as its fade), appended in a fixed order: group, tuft, graftal.
// Tufts and patches are worked out in parallel; the bytes do not depend on the number of threads.
// The tufts' levels are chosen as seen from `lod_view` when given (the coherence bench freezes them
// at its first frame), from `view` otherwise.
GraftalStageReport add_graftal_sprites(const Shot& shot, const FrameView& view,
                                       const RenderSettings& settings, SpriteSet& sprites,
                                       const FrameView* lod_view = nullptr);

// A graftal's or imposter's patch as a sprite (kind kGraftal) of the frame seen from `view`,
// standing at `at` in the world: its box, depth, range and swap speed (as for strokes,
// sprites.cpp: how fast its distance can cross an overlapping sprite's while the eye moves, so
// patches too change order softly); the caller sets its item, particle, object, fade and patch.
Sprite patch_sprite(const GraftalPatch& patch, const FrameView& view, const glm::dvec3& at);
// Appends the sprite with its patch (sprites.patches) and counts it; returns the patch's pixels.
uint64_t add_patch_sprite(SpriteSet& sprites, Sprite sp, GraftalPatch patch);

// The tufts the difference image places in a frame seen by `cam` (file 004): per group, one
// weight per site for the groups placed that way (0: not placed; below 1: fading, within `band`
// of the threshold), empty for the others. The candidates are the groups' sites in the frame or
// a margin around it; each wants its own ρ (file 004's N.V), less where another object's
// candidate lies nearer in its cell (occlusion), less the dots of those placed before it, laid
// between the cells of an image at the first such description's cell_px. They are tried in the
// order of a hash of their keys, the same in every frame, so the same ones win while the view
// changes a little, with no history (graftal_placement.h).
std::vector<std::vector<float>> difference_placement(const Shot& shot, const Camera& cam);

// For the coherence bench: each graftal's presence at `view` (its τ times its placement's
// weight: 0 not drawn, 1 fully in),
// -1 where its base is off screen, and the sprite keys they go by, in the same order (group,
// graftal).
std::vector<float> graftal_presences(const Shot& shot, const FrameView& view);
std::vector<uint64_t> graftal_keys(const Shot& shot);

// The graftals stage: add_graftal_sprites after the strokes' sprites (so their indices and the
// shadow grids' stay as they are), its pass line.
void graftals_stage(const FrameContext& ctx, SpriteSet& sprites);

}  // namespace pleinair
