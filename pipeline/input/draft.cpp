// The draft's settings, and their application under the user's own.
#include "pipeline/input/draft.h"

namespace pleinair {

namespace {

// Whether "POINTER=VALUE" sets `pointer` or an object holding it ("/render" does).
bool names(const std::string& set, const std::string& pointer) {
    const std::string p = set.substr(0, set.find('='));
    if (p.empty()) return false;
    return pointer == p || (pointer.size() > p.size() && pointer.compare(0, p.size(), p) == 0 &&
                            (p.back() == '/' || pointer[p.size()] == '/'));
}

}  // namespace

const std::vector<DraftSetting>& draft_settings() {
    static const std::vector<DraftSetting> all = {
        {"/render/samples", "1", [](RenderSettings& r) { r.samples = 1; },
         "one stroke-mask sample a pixel, the feather widened by the pixel's footprint instead "
         "of supersampled: the strokes' edges a little harder"},
        {"/render/thin_below_px", "6", [](RenderSettings& r) { r.thin_below_px = 6.0f; },
         "strokes drawn narrower than 6 px thinned at random, the survivors grown to keep their "
         "area: far crowns in fewer, larger strokes"},
        {"/render/thin_max_growth", "4", [](RenderSettings& r) { r.thin_max_growth = 4.0f; },
         "those survivors grown up to 4x (linear) so the draft's far crowns keep their area"},
        {"/render/coverage_cutoff", "0.01", [](RenderSettings& r) { r.coverage_cutoff = 0.01f; },
         "a pixel stops taking strokes once 1% of the light gets through: the sky's stroke field "
         "a shade bluer where it shows through crowns"},
        {"/render/reflection_frames", "8", [](RenderSettings& r) { r.reflection_frames = 8; },
         "a moving camera's water mirrors traced every 8th frame, interpolated between"},
    };
    return all;
}

void apply_draft(RenderSettings& r, const std::vector<std::string>& sets) {
    for (const DraftSetting& d : draft_settings()) {
        bool user = false;
        for (const std::string& s : sets) user |= names(s, d.pointer);
        if (!user) d.set(r);
    }
}

std::string draft_reference() {
    std::string out = "| key | draft value | what the picture gives |\n|---|---|---|\n";
    for (const DraftSetting& d : draft_settings())
        out += std::string("| `") + d.pointer + "` | `" + d.value + "` | " + d.why + " |\n";
    return out;
}

}  // namespace pleinair
