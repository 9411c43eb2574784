// Temporal coherence measured on a shot (../shared/notes/coherence.md): flicker along the
// strokes' own motion against a frozen and a boiling baseline, pops, depth-order swaps, and the
// silhouette with the level of detail on against off.
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "pipeline/frame/frame_image.h"
#include "pipeline/frame/frame_plan.h"

namespace pleinair {

struct Shot;

struct CoherenceReport {
    int frames = 0;  // frames measured (pairs of consecutive frames: frames - 1)
    // Flicker: the mean change of a pixel's colour (sRGB, 0..1, mean over channels) from one
    // frame to the next at the same point of the stroke nearest there, where that stroke was
    // also nearest there in the previous frame. With the level of detail frozen at the first
    // frame (the floor: motion alone), as it is, and with every stroke's noise reseeded each
    // frame (boiling).
    double flicker_floor = 0, flicker = 0, flicker_boiling = 0;
    // The same over still water's strokes alone, when the shot's water mirrors (water): with
    // the mirror, without it (the water's own floor: its strokes' noise and light only), and
    // boiling.
    bool water = false;
    double water_flicker = 0, water_flicker_dry = 0, water_flicker_boiling = 0;
    // The same over the trees' strokes alone, when the shot's wind blows (wind): in the wind,
    // in still air (the trees at rest, its floor) and boiling.
    bool wind = false;
    double tree_flicker = 0, tree_flicker_calm = 0, tree_flicker_boiling = 0;
    // Where the shot lies between its floor (0) and boiling (1).
    double flicker_score() const;
    // Strokes on screen in two consecutive frames whose presence (their fade times their
    // near-field thinning) changed by more than a third.
    uint64_t pops = 0;
    // The steepest change of a stroke's presence in one frame: at most 1/4 means every fade
    // takes at least 4 frames.
    double steepest_fade = 0;
    // Strokes on screen and present in two consecutive frames whose drawn share changed by more
    // than a third: culled in one and drawn in the other, or seen through more or fewer of
    // their visibility rays (a silhouette crossed; sprites.h: SeenWindow): a pop the level of
    // detail does not cause.
    uint64_t cull_pops = 0;
    // Pairs of strokes over 5% opaque, nearest and next nearest at some pixel with lightness
    // differing by more than 0.05, whose order was the other way round in the previous frame
    // (for strokes blending between orders, whose weight crossed 1/2), and of those the swaps
    // completed in that one frame: the weight moved by more than a third.
    uint64_t order_swaps = 0, abrupt_swaps = 0;
    // The level of detail on against off, frame by frame: the largest relative difference of
    // the area the strokes cover, of the mean L* over it, and of the area's change from the
    // previous frame beyond what the camera's motion does to the full-detail picture.
    bool lod = false;
    double area_difference = 0, lightness_difference = 0, area_step = 0;
    // The least agreement of the covered shapes, on against off: coverage averaged over 4 x 4
    // pixel blocks, the sum of the smaller over the sum of the larger (1: the same outline).
    // Its floor: the same between the shot and its boiling baseline, where only the strokes'
    // noise differs.
    double shape_overlap = 1, shape_floor = 1;
    // The level of detail's effect on the work, summed over the frames: sprites and fragments
    // with it on and off.
    uint64_t sprites_on = 0, sprites_off = 0, fragments_on = 0, fragments_off = 0;
    // Frame by frame, to find where a figure above comes from: the covered area (share of the
    // frame) and mean L* with the level of detail on and off, and the order swaps made.
    struct Frame {
        int frame = 0;
        double area_on = 0, area_off = 0, lightness_on = 0, lightness_off = 0;
        // Its floor: the same between the shot and its boiling baseline, where only the strokes'
        // noise differs.
        double shape_overlap = 1, shape_floor = 1;
        uint64_t order_swaps = 0, abrupt_swaps = 0;
    };
    std::vector<Frame> per_frame;
};

// Paints `frames` of the shot four times (level of detail as planned, frozen at the first
// frame, off, and with boiling noise), once more when still water mirrors (without its mirror)
// and when the wind blows (in still air), and measures them. `progress` (optional) is called after
// each frame with the frames done; `painted` (optional) with each frame number and its frame as
// planned, the frame `render
// --frame` and `animate` paint (the trace it keeps changes no pixel).
CoherenceReport measure_coherence(const Shot& shot, const std::vector<int>& frames,
                                  const FrameSettings& settings,
                                  const std::function<void(int)>& progress = {},
                                  const std::function<void(int, const Frame&)>& painted = {});

}  // namespace pleinair
