// The wind in a frame (wind_stage.h): calm air on the track paints the bytes still air paints,
// the wind moves strokes by no more than the poses' reach, the plan says what it does and
// that shadows are frozen, and a scene's bad /wind is one line a key.
#include <gtest/gtest.h>

#include <glm/geometric.hpp>
#include <map>

#include "pipeline/frame/paint_frame.h"
#include "pipeline/frame/sprites.h"
#include "pipeline/frame/wind_stage.h"
#include "pipeline/input/error.h"
#include "pipeline/input/scene.h"
#include "pipeline/output/image_io.h"
#include "pipeline/shot/shot.h"
#include "tests/test_util.h"

namespace pleinair {
namespace {

SceneDesc willow_gust(const std::vector<std::string>& sets = {}) {
    std::vector<std::string> all = {"/camera/width=192", "/camera/height=108"};
    all.insert(all.end(), sets.begin(), sets.end());
    return load_scene(test::source_dir() / "presets" / "scenes" / "willow-gust.json", all);
}

std::vector<uint8_t> paint_at(const Shot& shot, double t, FrameReport* report = nullptr) {
    const Frame f =
        paint_frame(shot, view_at(shot.scene, t), scene_frame_settings(shot.scene), report);
    return frame_srgb8(f);
}

TEST(WindFrame, CalmAirOnTheTrackPaintsWhatStillAirPaints) {
    // Calm for the first two seconds, then a wind: the calm frames are still air's, bit for
    // bit, though the shot poses its trees every frame.
    const std::string calm = R"(/wind/track=[{"time": 0, "strength": 0}, {"time": 2, "strength": 0},
                                            {"time": 8, "strength": 9}])";
    const Shot windy = build_shot(willow_gust({calm}));
    SceneDesc no_wind = willow_gust();
    no_wind.wind = WindDesc{};
    const Shot still = build_shot(no_wind);
    ASSERT_TRUE(windy.plan.wind);
    ASSERT_FALSE(still.plan.wind);
    ASSERT_FALSE(windy.wind_rigs.empty());
    FrameReport report;
    EXPECT_EQ(paint_at(windy, 1.0, &report), paint_at(still, 1.0));
    bool posed = false;
    for (const PassReport& p : report.passes) posed |= p.name == std::string("wind");
    EXPECT_TRUE(posed);
    // Later the wind blows, and the willow moves.
    const std::vector<uint8_t> a = paint_at(windy, 6.0), b = paint_at(still, 6.0);
    EXPECT_GT(test::byte_diff(a, b).differ, a.size() / 100);
}

TEST(WindFrame, AStillCameraInAWindTrackHasFramesThatMove) {
    // The willow seen from a camera that does not move: the wind's track alone makes the shot.
    SceneDesc s = willow_gust();
    s.camera_track.keys.clear();
    ASSERT_TRUE(s.animated());
    const FrameRange r = animation_frames(s);
    EXPECT_EQ(r.first, 1);
    EXPECT_EQ(r.last, 193);  // 8 s at 24 fps
    const FrameView v = view_at(s, 2.0);
    EXPECT_EQ(v.time, 2.0);
    EXPECT_FALSE(v.on_track);
    EXPECT_EQ(v.camera.eye, still_view(s).camera.eye);
    const Shot shot = build_shot(s);
    const std::vector<uint8_t> a = paint_at(shot, 1.0), b = paint_at(shot, 2.0);
    EXPECT_GT(test::byte_diff(a, b).differ, a.size() / 200);
    EXPECT_EQ(paint_at(shot, 2.0), b);
}

TEST(WindFrame, StrokesMoveNoFartherThanTheReachAndKeepTheirNoise) {
    const Shot shot = build_shot(willow_gust());
    const FrameSettings fs = scene_frame_settings(shot.scene);
    const FrameView view = view_at(shot.scene, 2.5);
    const FramePlan plan = plan_frame(shot, fs);
    ASSERT_TRUE(plan.wind);
    const FrameLod lod = level_of_detail(shot, view, fs.render);
    const FrameWind wind = frame_wind(shot, view.time, lod);
    ASSERT_TRUE(wind.on);
    ASSERT_GT(wind.reach[0], 0.0f);
    const SeenWindow seen = seen_window(shot.scene, view, fs.render);
    SpriteStageInput in{shot, view, plan, fs.render, lod, shot.sun_rays.get(), &seen};
    const SpriteSet rest = make_sprites(in);
    in.wind = &wind;
    const SpriteSet blown = make_sprites(in);
    std::map<uint64_t, const Sprite*> at_rest;
    for (const Sprite& s : rest.sprites) at_rest[sprite_key(s)] = &s;
    const double px_per_world = view.camera.focal_px / 10.0;  // the willow stands >= 10 m away
    size_t matched = 0, moved = 0;
    for (const Sprite& s : blown.sprites) {
        auto it = at_rest.find(sprite_key(s));
        if (it == at_rest.end()) continue;
        ++matched;
        const Sprite& r = *it->second;
        const double d = std::hypot(s.x - r.x, s.y - r.y);
        ASSERT_TRUE(std::isfinite(d));
        ASSERT_LE(d, wind.reach[0] * px_per_world + 1.0);
        moved += d > 0.25;
        // The stroke keeps its noise and its paint; only its place, turn and order move.
        ASSERT_EQ(s.k.offset_s, r.k.offset_s);
        ASSERT_EQ(s.k.offset_t, r.k.offset_t);
        ASSERT_GE(s.swap_speed, r.swap_speed);
    }
    EXPECT_GT(matched, rest.sprites.size() * 9 / 10);
    EXPECT_GT(moved, matched / 4);
}

// The wind's direction is the world's: a tree turned by its placement is posed in its own
// frame by the inverse of that turn, so its leaves move downwind on screen whichever way it
// was planted (turned by the placement's own rotation, a tree turned a quarter would lean
// across the wind, and one turned a half into it).
TEST(WindFrame, ATurnedTreeBendsDownwindInTheWorld) {
    for (const char* rotation : {"0", "90", "200", "-65"}) {
        SCOPED_TRACE(std::string("rotation ") + rotation);
        const Shot shot = build_shot(willow_gust({std::string("/trees/0/rotation=") + rotation}));
        const double t = 2.5;
        const FrameWind fw = frame_wind(shot, t, FrameLod{});
        ASSERT_TRUE(fw.on);
        const glm::dvec3 downwind = wind_at(shot.scene.wind, t).direction;
        ASSERT_NEAR(glm::length(downwind), 1.0, 1e-9);
        const LeafParticles& L = (*shot.trees)[0].tree().leaves;
        glm::dvec3 sum(0.0);
        size_t moved = 0;
        for (size_t j = 0; j < L.size(); ++j) {
            const WindMove m = wind_move(shot, fw, 0, true, j, L.position[j], L.label[j]);
            sum += m.delta, moved += m.moved;
        }
        ASSERT_GT(moved, L.size() / 2);
        const glm::dvec3 mean = sum / double(L.size());
        ASSERT_GT(glm::length(mean), 0.01);  // metres: the gust does move the crown
        // Downwind within about 45 degrees (the limbs' sway across the wind is a third of it).
        EXPECT_GT(glm::dot(mean, downwind), 0.7 * glm::length(mean))
            << "mean move " << mean.x << ", " << mean.y << ", " << mean.z;
    }
}

std::vector<std::string> scene_problems(const std::vector<std::string>& sets) {
    try {
        willow_gust(sets);
    } catch (const InputError& e) {
        std::vector<std::string> lines;
        std::string all = e.what();
        for (size_t start = 0; start <= all.size();) {
            size_t end = all.find('\n', start);
            if (end == std::string::npos) end = all.size();
            const size_t from = all.find(": ", start) + 2;
            std::string line = all.substr(from, end - from);
            const std::string by = " (set by --set)";
            if (line.size() > by.size() && line.substr(line.size() - by.size()) == by)
                line.resize(line.size() - by.size());
            lines.push_back(line);
            start = end + 1;
        }
        return lines;
    }
    return {};
}

TEST(WindFrame, ABadWindIsOneLineAKey) {
    EXPECT_EQ(scene_problems({"/wind/gustiness=2"}),
              std::vector<std::string>{"/wind/gustiness: must be in [0, 1], got 2"});
    EXPECT_EQ(scene_problems({"/wind/direction=[0, 1, 0]"}),
              std::vector<std::string>{
                  "/wind/direction: must be a finite direction with a level part (x or z)"});
    EXPECT_EQ(scene_problems({R"(/wind/track=[{"time": 1, "strength": 2}])"}),
              std::vector<std::string>{"/wind/track: a track needs at least two keys, got 1"});
    EXPECT_EQ(scene_problems(
                  {R"(/wind/track=[{"time": 1, "strength": 2}, {"time": 0.5, "strength": -1}])"}),
              (std::vector<std::string>{
                  "/wind/track/1/strength: must be in [0, 60], got -1",
                  "/wind/track/1/time: keys must be in time order: 0.5 comes before key 0's 1"}));
    EXPECT_EQ(scene_problems(
                  {R"(/wind/track=[{"time": 1, "strength": 2}, {"time": 0.5, "strength": 1}])"}),
              std::vector<std::string>{
                  "/wind/track/1/time: keys must be in time order: 0.5 comes before key 0's 1"});
    EXPECT_TRUE(scene_problems({"/wind/strength=30"}).empty());
}

TEST(WindFrame, TheTracksMeanIsContinuousAndHitsItsKeys) {
    WindDesc w;
    w.present = true;
    w.track = {{0, 2, {1, 0, 0}}, {2, 8, {0, 0.3, 1}}, {4, 4, {-1, 0, 0.2}}};
    EXPECT_EQ(wind_at(w, 2).strength, 8);
    EXPECT_NEAR(wind_at(w, 2).direction.z, 1, 1e-12);
    EXPECT_EQ(wind_at(w, -1).strength, 2);
    EXPECT_EQ(wind_at(w, 9).strength, 4);
    for (double t = 0.01; t < 4; t += 0.25) {
        const WindKey a = wind_at(w, t), b = wind_at(w, t + 1e-6);
        EXPECT_NEAR(a.strength, b.strength, 1e-4);
        EXPECT_NEAR(glm::length(a.direction - b.direction), 0, 1e-5);
        EXPECT_NEAR(glm::length(a.direction), 1, 1e-12);
        EXPECT_EQ(a.direction.y, 0);
    }
    // Gusts over a place: continuous in time, within the promised band.
    w.gustiness = 1;
    for (double t = 0; t < 30; t += 0.37) {
        const double s = gust_speed(w, wind_at(w, t), {3, 0, 7});
        const double m = wind_at(w, t).strength;
        EXPECT_GE(s, 0.5 * m - 1e-9);
        EXPECT_LE(s, 2.0 * m + 1e-9);
    }
}

}  // namespace
}  // namespace pleinair
