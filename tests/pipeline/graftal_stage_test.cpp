// The graftals stage in frames of the shipped truffula scenes: graftal-styled crowns and
// surfaces paint no strokes, tufts gain levels as the camera nears them and grow in over time,
// and the frame's bytes depend on neither the thread count nor the frames painted before.
#include "pipeline/graftal_stage.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cmath>

#include "pipeline/error.h"
#include "pipeline/paint.h"
#include "pipeline/presets.h"
#include "pipeline/shot.h"

namespace pleinair {
namespace {

// σ is a size on screen: the walk's tufts reach their higher levels at a frame this wide.
SceneDesc truffula(const char* name, std::vector<std::string> more = {}, int width = 192) {
    std::vector<std::string> sets = {"/camera/width=" + std::to_string(width),
                                     "/camera/height=" + std::to_string(width * 9 / 16)};
    sets.insert(sets.end(), more.begin(), more.end());
    return load_scene(resolve_preset("scenes", name, "SCENE"), sets);
}

TEST(GraftalStage, GraftalStyledCrownsAndSurfacesPaintNoStrokes) {
    const Shot shot = build_shot(truffula("truffula"));
    ASSERT_FALSE(shot.graftals.empty());
    FrameReport rep;
    const Frame f =
        paint_frame(shot, still_view(shot.scene), scene_frame_settings(shot.scene), &rep);
    EXPECT_EQ(rep.leaf_sprites, 0u);
    EXPECT_EQ(rep.surface_sprites, 0u);
    EXPECT_GT(rep.bark_sprites, 0u);  // trunks stay strokes
    EXPECT_GT(rep.graftal_sprites, 100u);
    for (float v : f.rgba) ASSERT_TRUE(std::isfinite(v) && v >= 0.0f && v <= 1.0001f);

    // The same scene in strokes: no graftals, and the leaves and turf are strokes again.
    const Shot strokes = build_shot(truffula(
        "truffula", {"/families/truffula/style=\"strokes\"", "/materials/turf/style=\"strokes\""}));
    EXPECT_TRUE(strokes.graftals.empty());
    FrameReport srep;
    paint_frame(strokes, still_view(strokes.scene), scene_frame_settings(strokes.scene), &srep);
    EXPECT_EQ(srep.graftal_sprites, 0u);
    EXPECT_GT(srep.leaf_sprites, 0u);
    EXPECT_GT(srep.surface_sprites, 0u);
}

TEST(GraftalStage, TuftsGainLevelsAsTheCameraNearsAndGrowInOverTime) {
    const Shot shot = build_shot(truffula("truffula-walk", {}, 640));
    const FrameRange frames = animation_frames(shot.scene);
    uint64_t first_high = 0, most_high = 0, growing_frames = 0;
    for (int f = frames.first; f <= frames.last; f += 8) {
        SpriteSet sprites;
        const GraftalStageReport r =
            add_graftal_sprites(shot, view_at(shot.scene, frame_time(f, shot.scene.fps)), sprites);
        ASSERT_EQ(r.drawn, sprites.sprites.size());
        ASSERT_EQ(sprites.patches.size(), sprites.sprites.size());
        uint64_t high = 0;
        for (size_t l = 1; l < r.at_level.size(); ++l) high += r.at_level[l];
        if (f == frames.first) first_high = high;
        most_high = std::max(most_high, high);
        growing_frames += r.growing > 0;
    }
    // Walking into the grove, more tufts stand at their higher levels than at the start...
    EXPECT_GT(most_high, first_high + 5);
    // ...and the changes are spread over time, not switched in a frame.
    EXPECT_GE(growing_frames, 3u);
}

TEST(GraftalStage, AFrameIsTheSameOnOneThreadOrManyAndAloneOrInSequence) {
    const Shot shot = build_shot(truffula("truffula-walk"));
    const FrameSettings settings = scene_frame_settings(shot.scene);
    const FrameView view = view_at(shot.scene, frame_time(97, shot.scene.fps));
    const Frame many = paint_frame(shot, view, settings);
    Frame one;
    {
        tbb::global_control single(tbb::global_control::max_allowed_parallelism, 1);
        // Frames before it painted first change nothing: its history is replayed, not carried.
        paint_frame(shot, view_at(shot.scene, frame_time(96, shot.scene.fps)), settings);
        one = paint_frame(shot, view, settings);
    }
    EXPECT_EQ(many.rgba, one.rgba);
}

TEST(GraftalStage, AStyleThatIsNoGraftalIsRefusedWithItsKey) {
    try {
        truffula("truffula", {"/families/truffula/style=\"no-such-tuft\""});
        FAIL() << "accepted";
    } catch (const InputError& e) {
        ASSERT_FALSE(e.problems().empty());
        EXPECT_EQ(e.problems()[0].pointer, "/families/truffula/style");
    }
    try {
        truffula("truffula", {"/materials/turf/style=7"});
        FAIL() << "accepted";
    } catch (const InputError& e) {
        ASSERT_FALSE(e.problems().empty());
        EXPECT_EQ(e.problems()[0].pointer, "/materials/turf/style");
    }
}

}  // namespace
}  // namespace pleinair
