// One frame's context as its stages run (as Mitsuba's ScopedPhase keeps accounting beside the
// code): what every stage reads (the shot, the view, the settings, the plan) and where it
// reports. A stage opens a StagePhase with its name, does its work, and says what it did; the
// phase adds its time. paint_frame then reads as the list of stages.
#pragma once

#include <string>
#include <utility>

#include "pipeline/frame/frame_plan.h"
#include "pipeline/frame/frame_report.h"
#include "pipeline/frame/frame_view.h"

namespace pleinair {

struct Shot;

struct FrameContext {
    const Shot& shot;
    const FrameView& view;
    const FrameSettings& settings;
    const FramePlan& plan;
    FrameReport& report;
    const RenderSettings& render() const { return settings.render; }
};

// A stage's pass as --explain prints it: its name, why it ran, its time and its counts.
class StagePhase {
  public:
    // `announce`: the stage is long enough to tell the progress callback it starts.
    StagePhase(const FrameContext& ctx, const char* name, bool announce = false)
        : ctx_(ctx), name_(name) {
        if (ctx.settings.abandon && ctx.settings.abandon()) throw FrameAbandoned();
        if (announce && ctx.settings.progress) ctx.settings.progress(name, 0.0);
    }
    void done(std::string why, std::string counts = "") {
        ctx_.report.passes.push_back({name_, true, std::move(why), timer_.ms(), std::move(counts)});
    }

  private:
    const FrameContext& ctx_;
    const char* name_;
    PassTimer timer_;
};

}  // namespace pleinair
