// The draft: its values are what the scene parser reads for its keys, and a user's own --set
// of a key (or of an object holding it) keeps that key out of the draft.
#include "pipeline/input/draft.h"

#include <gtest/gtest.h>

#include "pipeline/input/scene.h"

namespace pleinair {
namespace {

const char* kScene = R"({"camera": {"width": 64, "height": 36}})";

// The fields the draft may touch, for comparison.
struct Eased {
    int samples, reflection_frames;
    float thin_below_px, thin_max_growth, coverage_cutoff;
    bool operator==(const Eased&) const = default;
};
Eased eased(const RenderSettings& r) {
    return {r.samples, r.reflection_frames, r.thin_below_px, r.thin_max_growth, r.coverage_cutoff};
}

TEST(Draft, ItsValuesAreWhatTheSceneParserReadsForItsKeys) {
    std::vector<std::string> sets;
    for (const DraftSetting& d : draft_settings())
        sets.push_back(std::string(d.pointer) + "=" + d.value);
    ASSERT_EQ(sets.size(), 5u);
    const SceneDesc parsed = parse_scene(kScene, "draft.json", sets);
    SceneDesc drafted = parse_scene(kScene, "draft.json");
    const Eased before = eased(drafted.render);
    apply_draft(drafted.render, {});
    EXPECT_EQ(eased(drafted.render), eased(parsed.render));
    // Every key it names changes something: none is already the default.
    for (const DraftSetting& d : draft_settings()) {
        const SceneDesc one =
            parse_scene(kScene, "draft.json", {std::string(d.pointer) + "=" + d.value});
        EXPECT_FALSE(eased(one.render) == before) << d.pointer;
    }
}

TEST(Draft, TheUsersOwnKeysStayTheirs) {
    const RenderSettings defaults;
    RenderSettings r;
    r.samples = 16;
    apply_draft(r, {"/render/samples=16"});
    EXPECT_EQ(r.samples, 16);
    EXPECT_EQ(r.thin_below_px, 6.0f);
    EXPECT_EQ(r.reflection_frames, 8);
    // An object holding the key keeps all of it.
    RenderSettings whole;
    apply_draft(whole, {R"(/render={"samples": 4})"});
    EXPECT_EQ(eased(whole), eased(defaults));
    // A key that only starts like one of the draft's is another key.
    RenderSettings other;
    apply_draft(other, {"/render/samples_extra=2", "/rend=1", "=3"});
    EXPECT_EQ(other.samples, 1);
    EXPECT_EQ(other.coverage_cutoff, 0.01f);
}

}  // namespace
}  // namespace pleinair
