// What a painted frame reports: the plan's decisions, each stage's pass line with its time (what
// --explain prints) and the counts the benches read.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "pipeline/shot/pass_report.h"

namespace pleinair {

// Traced frames only (FrameSettings::trace), paint_frame.h.
struct FrameTrace;

struct FrameReport {
    std::vector<PassReport> decisions;  // the plan's, with no time of their own
    std::vector<PassReport> passes;
    uint64_t leaf_sprites = 0, bark_sprites = 0, surface_sprites = 0, culled = 0;
    uint64_t graftal_sprites = 0;   // graftals drawn (graftal_stage.h)
    uint64_t imposter_sprites = 0;  // imposters drawn (imposter_stage.h)
    uint64_t sky_sprites = 0;       // strokes of the painted sky in view (sky_sprites.h)
    uint64_t reflection_rays = 0;   // cast for still water's mirror (reflection.h)
    uint64_t shadow_rays = 0, underpaint_rays = 0;
    uint64_t fragments = 0;  // pixel samples evaluated by the stroke shader
    std::shared_ptr<FrameTrace> trace;
};

}  // namespace pleinair
