// The draft: a lighter way to paint frames for a quick look, as Blender's Simplify is for its
// viewport: a few frame settings eased, the shot untouched, the user's own --set kept.
#pragma once

#include <string>
#include <vector>

#include "pipeline/input/settings.h"

namespace pleinair {

// One setting the draft eases: its scene key, its draft value as --set would write it (and
// setting it, beside it), and what the picture gives for the time saved.
struct DraftSetting {
    const char* pointer;
    const char* value;
    void (*set)(RenderSettings&);
    const char* why;
};

// Every setting the draft eases, in the order they are applied.
const std::vector<DraftSetting>& draft_settings();

// The draft's values set in r, except a key the user set themselves: one of `sets`
// ("POINTER=VALUE", as --set takes them) names it or a key that holds it. The frame is then a
// pure function of (shot, time, settings) as any other: render --draft --frame N paints frame N
// of animate --draft.
void apply_draft(RenderSettings& r, const std::vector<std::string>& sets);

// The README's table of the draft's settings.
std::string draft_reference();

}  // namespace pleinair
