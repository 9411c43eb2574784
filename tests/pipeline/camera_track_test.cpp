// Camera and sun tracks: keys hit bit for bit, a smooth path without loops, constant speed by arc
// length, frames counted from 1, and bad tracks in scene files reported one line per problem.
#include "pipeline/input/camera_track.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <glm/geometric.hpp>

#include "pipeline/input/error.h"
#include "pipeline/input/scene.h"
#include "test_util.h"

namespace pleinair {
namespace {

bool same_bits(double a, double b) {
    return std::bit_cast<uint64_t>(a) == std::bit_cast<uint64_t>(b);
}
bool same_bits(const glm::dvec3& a, const glm::dvec3& b) {
    return same_bits(a.x, b.x) && same_bits(a.y, b.y) && same_bits(a.z, b.z);
}

CameraKey key(double time, glm::dvec3 position, glm::dvec3 look_at, double fov = 40) {
    CameraKey k;
    k.time = time;
    k.position = position;
    k.look_at = look_at;
    k.fov = fov;
    return k;
}

// A walk with uneven key spacing in time and in space, turning, rising and zooming.
CameraTrack walk() {
    CameraTrack track;
    track.keys = {key(0.0, {0, 1.6, 12}, {0, 2, 0}, 40), key(1.5, {3, 1.7, 9}, {1, 2.2, 0}, 50),
                  key(2.25, {4.5, 2.5, 8.5}, {3, 2, -1}, 35),
                  key(5.0, {9, 2.0, 4}, {2, 1.5, -3}, 60), key(6.0, {10, 1.8, 1}, {0, 2, -5}, 45)};
    track.keys[1].up = {0.1, 1, 0};
    track.keys[2].up = {0, 2, 0.2};  // not unit: a direction
    return track;
}

glm::dvec3 position_at(const CameraTrack& track, double t) { return track_at(track, t).position; }

// Finite-difference velocity of the position just before and just after time t.
std::pair<glm::dvec3, glm::dvec3> velocities(const CameraTrack& track, double t, double h) {
    const glm::dvec3 p = position_at(track, t);
    return {(p - position_at(track, t - h)) / h, (position_at(track, t + h) - p) / h};
}

TEST(CameraTrack, KeysAreHitBitForBit) {
    for (auto interpolation : {TrackInterpolation::kCatmullRom, TrackInterpolation::kLinear}) {
        CameraTrack track = walk();
        track.interpolation = interpolation;
        track.keys[2].ease_in = 0.5;
        track.keys[3].ease_out = 1;
        for (auto& k : track.keys) k.leaf_near = 5 + k.time, k.leaf_far = 50 + k.time;
        for (const CameraKey& k : track.keys) {
            const CameraKey got = track_at(track, k.time);
            EXPECT_TRUE(same_bits(got.position, k.position)) << k.time;
            EXPECT_TRUE(same_bits(got.look_at, k.look_at)) << k.time;
            EXPECT_TRUE(same_bits(got.up, k.up)) << k.time;
            EXPECT_TRUE(same_bits(got.fov, k.fov)) << k.time;
            EXPECT_TRUE(same_bits(got.leaf_near, k.leaf_near)) << k.time;
            EXPECT_TRUE(same_bits(got.leaf_far, k.leaf_far)) << k.time;
            CameraParams base;
            base.width = 321;
            base.height = 123;
            const CameraParams cam = camera_at(track, base, k.time);
            EXPECT_TRUE(same_bits(cam.position, k.position));
            EXPECT_TRUE(same_bits(cam.look_at, k.look_at));
            EXPECT_TRUE(same_bits(cam.fov, k.fov));
            EXPECT_EQ(cam.width, 321);
            EXPECT_EQ(cam.height, 123);
        }
        // Between keys the track moves: the test above is not comparing a constant.
        EXPECT_GT(glm::length(position_at(track, 0.75) - track.keys[0].position), 0.1);
    }
    // With constant speed the ends still are the end keys.
    CameraTrack track = walk();
    track.constant_speed = true;
    EXPECT_TRUE(same_bits(position_at(track, 0.0), track.keys.front().position));
    EXPECT_TRUE(same_bits(position_at(track, 6.0), track.keys.back().position));
}

TEST(CameraTrack, TimesOutsideTheTrackClampToItsEnds) {
    const CameraTrack track = walk();
    EXPECT_TRUE(same_bits(position_at(track, -3), track.keys.front().position));
    EXPECT_TRUE(same_bits(position_at(track, 60), track.keys.back().position));
    EXPECT_TRUE(same_bits(track_at(track, 60).fov, track.keys.back().fov));
}

TEST(CameraTrack, CatmullRomHasNoVelocityJumpAtKeys) {
    const CameraTrack track = walk();
    const double h = 1e-6;
    for (size_t i = 1; i + 1 < track.keys.size(); ++i) {
        auto [before, after] = velocities(track, track.keys[i].time, h);
        ASSERT_GT(glm::length(before), 0.1) << "key " << i;
        EXPECT_LT(glm::length(after - before) / glm::length(before), 1e-3) << "key " << i;
        // The look-at point too.
        auto look = [&](double t) { return track_at(track, t).look_at; };
        const double t = track.keys[i].time;
        glm::dvec3 lb = (look(t) - look(t - h)) / h, la = (look(t + h) - look(t)) / h;
        EXPECT_LT(glm::length(la - lb) / glm::length(lb), 1e-3) << "key " << i;
    }
    // The same measure sees the corners of the linear track.
    CameraTrack linear = walk();
    linear.interpolation = TrackInterpolation::kLinear;
    auto [before, after] = velocities(linear, linear.keys[1].time, h);
    EXPECT_GT(glm::length(after - before) / glm::length(before), 0.1);
}

TEST(CameraTrack, EaseBringsTheCameraToRestAtItsKey) {
    const double h = 1e-6;
    const CameraTrack plain = walk();
    auto [plain_before, plain_after] = velocities(plain, 1.5, h);
    const double speed = glm::length(plain_before);
    ASSERT_GT(speed, 0.1);

    CameraTrack rest = walk();
    rest.keys[1].ease_in = rest.keys[1].ease_out = 1;
    auto [before, after] = velocities(rest, 1.5, h);
    EXPECT_LT(glm::length(before), 1e-3 * speed);
    EXPECT_LT(glm::length(after), 1e-3 * speed);
    // ...and still moves between keys.
    EXPECT_GT(glm::length(position_at(rest, 1.0) - position_at(rest, 1.5)), 0.1);

    // Half an ease in halves the speed of the approach and leaves the departure alone.
    CameraTrack half = walk();
    half.keys[1].ease_in = 0.5;
    auto [half_before, half_after] = velocities(half, 1.5, h);
    EXPECT_NEAR(glm::length(half_before) / speed, 0.5, 1e-3);
    EXPECT_NEAR(glm::length(half_after) / glm::length(plain_after), 1.0, 1e-3);

    // Easing the track's first key starts it from rest.
    CameraTrack start = walk();
    start.keys[0].ease_out = 1;
    EXPECT_LT(glm::length(position_at(start, h) - position_at(start, 0)) / h, 1e-3 * speed);
}

TEST(CameraTrack, CentripetalHasNoLoopOrOvershootAtUnevenSpacing) {
    // Keys 0.01 apart, then 100 apart at a right angle, then 0.01 apart again: uniform
    // Catmull-Rom would swing the short segments out by several units, outside the keys' box.
    CameraTrack track;
    track.keys = {key(0, {0, 0, 0}, {0, 0, -10}), key(1, {0.01, 0, 0}, {0, 0, -10}),
                  key(2, {0.01, 100, 0}, {0, 0, -10}), key(3, {0.02, 100, 0}, {0, 0, -10})};
    glm::dvec3 lo(1e300), hi(-1e300);
    for (const auto& k : track.keys) lo = glm::min(lo, k.position), hi = glm::max(hi, k.position);
    double outside = 0;
    for (int s = 0; s <= 3000; ++s) {
        const glm::dvec3 p = position_at(track, 3.0 * s / 3000);
        for (int c = 0; c < 3; ++c) outside = std::max({outside, lo[c] - p[c], p[c] - hi[c]});
    }
    EXPECT_LT(outside, 0.01 * glm::length(hi - lo));
    // The short segment stays short: within a few times its own length of its keys.
    for (int s = 0; s <= 100; ++s) {
        const glm::dvec3 p = position_at(track, s / 100.0);
        EXPECT_LT(glm::length(p), 0.05) << s;
    }
    // No loop: along each segment the path keeps moving towards the segment's end key.
    for (size_t i = 0; i + 1 < track.keys.size(); ++i) {
        const glm::dvec3 chord = track.keys[i + 1].position - track.keys[i].position;
        glm::dvec3 prev = track.keys[i].position;
        for (int s = 1; s <= 200; ++s) {
            const double t = track.keys[i].time + s / 200.0;
            const glm::dvec3 p = position_at(track, t);
            EXPECT_GE(glm::dot(p - prev, chord), 0) << "segment " << i << " sample " << s;
            prev = p;
        }
    }
}

// Speeds by finite differences over `n` equal steps of the whole track.
std::vector<double> speeds(const CameraTrack& track, int n) {
    const double t0 = track.keys.front().time, t1 = track.keys.back().time;
    const double dt = (t1 - t0) / n;
    std::vector<double> out;
    for (int s = 0; s < n; ++s)
        out.push_back(
            glm::length(position_at(track, t0 + (s + 1) * dt) - position_at(track, t0 + s * dt)) /
            dt);
    return out;
}

TEST(CameraTrack, ConstantSpeedIsConstantAlongThePath) {
    CameraTrack track = walk();
    track.keys[2].ease_in = 1;  // interior eases do not apply at constant speed
    track.constant_speed = true;
    const std::vector<double> v = speeds(track, 200);
    double mean = 0;
    for (double x : v) mean += x;
    mean /= double(v.size());
    for (size_t s = 0; s < v.size(); ++s) EXPECT_NEAR(v[s] / mean, 1.0, 0.01) << "step " << s;
    // The mean speed is the path's length over the track's duration.
    EXPECT_NEAR(mean * 6.0 / track_length(track), 1.0, 1e-3);
    // The path is the keyed one: it still passes through the interior keys.
    for (size_t i = 1; i + 1 < track.keys.size(); ++i) {
        double nearest = 1e300;
        for (int s = 0; s <= 6000; ++s)
            nearest = std::min(
                nearest, glm::length(position_at(track, s / 1000.0) - track.keys[i].position));
        EXPECT_LT(nearest, 5e-3) << "key " << i;
    }
    // Without it, the speed varies by far more than 1 %.
    track.constant_speed = false;
    const std::vector<double> w = speeds(track, 200);
    EXPECT_GT(*std::max_element(w.begin(), w.end()) / *std::min_element(w.begin(), w.end()), 2.0);
}

TEST(CameraTrack, ConstantSpeedEasesOnlyAtTheEnds) {
    CameraTrack track = walk();
    track.constant_speed = true;
    track.keys.front().ease_out = 1;
    track.keys.back().ease_in = 1;
    const std::vector<double> v = speeds(track, 400);
    EXPECT_LT(v.front(), 0.05 * v[200]);
    EXPECT_LT(v.back(), 0.05 * v[200]);
}

TEST(CameraTrack, LinearIsPiecewiseLinear) {
    CameraTrack track = walk();
    track.interpolation = TrackInterpolation::kLinear;
    for (size_t i = 0; i + 1 < track.keys.size(); ++i) {
        const CameraKey& a = track.keys[i];
        const CameraKey& b = track.keys[i + 1];
        for (double u : {0.1, 0.25, 0.5, 0.9}) {
            const CameraKey k = track_at(track, a.time + u * (b.time - a.time));
            EXPECT_LT(glm::length(k.position - (a.position + u * (b.position - a.position))), 1e-9);
            EXPECT_LT(glm::length(k.look_at - (a.look_at + u * (b.look_at - a.look_at))), 1e-9);
            EXPECT_NEAR(k.fov, a.fov + u * (b.fov - a.fov), 1e-9);
            EXPECT_NEAR(glm::length(k.up), 1.0, 1e-12);
        }
    }
    // Catmull-Rom is not: the same measure tells them apart.
    const CameraTrack curve = walk();
    const CameraKey& a = curve.keys[1];
    const CameraKey& b = curve.keys[2];
    EXPECT_GT(
        glm::length(position_at(curve, (a.time + b.time) / 2) - (a.position + b.position) / 2.0),
        1e-3);
}

TEST(CameraTrack, FovAndCirclesStayBetweenTheirKeys) {
    CameraTrack track = walk();
    const double fovs[] = {20, 80, 21, 79, 20};
    for (size_t i = 0; i < track.keys.size(); ++i) {
        track.keys[i].fov = fovs[i];
        track.keys[i].trunk_near = 10 * fovs[i];
        track.keys[i].trunk_far = 20 * fovs[i];
    }
    ASSERT_TRUE(validate_track(track, "/t").empty());
    bool moved = false;
    for (size_t i = 0; i + 1 < track.keys.size(); ++i) {
        const CameraKey& a = track.keys[i];
        const CameraKey& b = track.keys[i + 1];
        for (int s = 0; s <= 100; ++s) {
            const CameraKey k = track_at(track, a.time + (b.time - a.time) * s / 100);
            EXPECT_GE(k.fov, std::min(a.fov, b.fov));
            EXPECT_LE(k.fov, std::max(a.fov, b.fov));
            EXPECT_GE(k.trunk_far, std::min(a.trunk_far, b.trunk_far));
            EXPECT_LE(k.trunk_far, std::max(a.trunk_far, b.trunk_far));
            EXPECT_EQ(k.leaf_near, 0);  // not set anywhere: stays unset
            moved |= k.fov != a.fov && k.fov != b.fov;
        }
    }
    EXPECT_TRUE(moved);
}

TEST(CameraTrack, UpIsInterpolatedAndUnit) {
    const CameraTrack track = walk();
    for (int s = 1; s < 60; ++s) {
        const CameraKey k = track_at(track, s / 10.0);
        if (s == 15) continue;  // a key's up comes back as given
        EXPECT_NEAR(glm::length(k.up), 1.0, 1e-12) << s;
        EXPECT_GT(k.up.y, 0.9) << s;
    }
}

TEST(CameraTrack, SunKeysAreHitAndSlerped) {
    std::vector<SunKey> sun = {{0, glm::normalize(glm::dvec3(1, 0.2, 0))},
                               {4, glm::normalize(glm::dvec3(0, 1, 1))},
                               {10, glm::normalize(glm::dvec3(-1, 0.1, 0))}};
    ASSERT_TRUE(validate_sun_track(sun, "/sun/track").empty());
    for (const SunKey& k : sun) EXPECT_TRUE(same_bits(sun_at(sun, k.time), k.direction));
    EXPECT_TRUE(same_bits(sun_at(sun, -1), sun.front().direction));
    EXPECT_TRUE(same_bits(sun_at(sun, 11), sun.back().direction));
    // Halfway in time is halfway in angle, on the great circle, unit length.
    const glm::dvec3 mid = sun_at(sun, 2);
    EXPECT_NEAR(glm::length(mid), 1.0, 1e-12);
    const double to_a = std::acos(glm::dot(mid, sun[0].direction));
    const double to_b = std::acos(glm::dot(mid, sun[1].direction));
    EXPECT_NEAR(to_a, to_b, 1e-9);
    EXPECT_NEAR(glm::dot(mid, glm::cross(sun[0].direction, sun[1].direction)), 0, 1e-12);
    // A quarter of the way: a quarter of the angle.
    const double whole = std::acos(glm::dot(sun[0].direction, sun[1].direction));
    EXPECT_NEAR(std::acos(glm::dot(sun_at(sun, 1), sun[0].direction)), whole / 4, 1e-9);
}

TEST(CameraTrack, FramesCountFromOne) {
    EXPECT_EQ(frame_time(1, 24), 0.0);
    EXPECT_EQ(frame_time(25, 24), 1.0);
    CameraTrack track = walk();  // 0 to 6 s
    EXPECT_EQ(track_first_frame(track, 24), 1);
    EXPECT_EQ(track_last_frame(track, 24), 145);
    EXPECT_EQ(track_frame_count(track, 24), 145);
    // A track starting after 0: frames before it are outside.
    for (auto& k : track.keys) k.time += 0.5;  // 0.5 to 6.5 s
    EXPECT_EQ(track_first_frame(track, 24), 13);
    EXPECT_EQ(track_last_frame(track, 24), 157);
    EXPECT_EQ(track_frame_count(track, 24), 157);
    EXPECT_FALSE(frame_in_track(track, 12, 24));
    EXPECT_TRUE(frame_in_track(track, 13, 24));
    EXPECT_TRUE(frame_in_track(track, 157, 24));
    EXPECT_FALSE(frame_in_track(track, 158, 24));
    // At awkward rates the range agrees with frame_time itself, to the last bit.
    for (double fps : {23.976, 29.97, 30.0, 7.0, 1000.0}) {
        track.keys.front().time = 0.1;
        track.keys.back().time = 6.7;
        const int first = track_first_frame(track, fps), last = track_last_frame(track, fps);
        EXPECT_GE(frame_time(first, fps), 0.1) << fps;
        EXPECT_LT(frame_time(first - 1, fps), 0.1) << fps;
        EXPECT_LE(frame_time(last, fps), 6.7) << fps;
        EXPECT_GT(frame_time(last + 1, fps), 6.7) << fps;
    }
    EXPECT_EQ(track_frame_count(CameraTrack{}, 24), 1);  // a still: one frame
}

bool has_problem(const std::vector<Problem>& problems, const std::string& pointer,
                 const std::string& words = "") {
    for (const auto& p : problems)
        if (p.pointer == pointer && p.message.find(words) != std::string::npos) return true;
    return false;
}

TEST(CameraTrack, ValidationNamesEachBadKey) {
    const std::string at = "/camera/track";
    EXPECT_TRUE(validate_track(walk(), at).empty());
    CameraTrack t = walk();
    t.keys.resize(1);
    EXPECT_TRUE(has_problem(validate_track(t, at), at, "at least two keys"));
    t = walk();
    std::swap(t.keys[2].time, t.keys[3].time);
    auto p = validate_track(t, at);
    EXPECT_TRUE(has_problem(p, at + "/3/time", "time order")) << format_problems("", p);
    EXPECT_EQ(p.size(), 1u);
    t = walk();
    t.keys[2].time = t.keys[1].time;
    EXPECT_TRUE(has_problem(validate_track(t, at), at + "/2/time", "same time"));
    t = walk();
    t.keys[4].look_at = t.keys[4].position;
    EXPECT_TRUE(has_problem(validate_track(t, at), at + "/4/look_at", "differ"));
    for (double fov : {0.0, 180.0, -5.0, double(NAN)}) {
        t = walk();
        t.keys[0].fov = fov;
        EXPECT_TRUE(has_problem(validate_track(t, at), at + "/0/fov", "(0, 180)")) << fov;
    }
    t = walk();
    t.keys[1].ease_in = 1.5;
    t.keys[2].ease_out = -0.1;
    p = validate_track(t, at);
    EXPECT_TRUE(has_problem(p, at + "/1/ease_in"));
    EXPECT_TRUE(has_problem(p, at + "/2/ease_out"));
    t = walk();
    t.keys[3].position.x = INFINITY;
    t.keys[1].up = glm::dvec3(0.0);
    t.keys[2].time = NAN;
    p = validate_track(t, at);
    EXPECT_TRUE(has_problem(p, at + "/3/position", "finite"));
    EXPECT_TRUE(has_problem(p, at + "/1/up", "non-zero"));
    EXPECT_TRUE(has_problem(p, at + "/2/time", "finite"));
    t = walk();
    t.keys[1].leaf_near = 10;
    p = validate_track(t, at);
    EXPECT_TRUE(has_problem(p, at + "/0/leaf_near", "every key or none"));
    EXPECT_TRUE(has_problem(p, at + "/4/leaf_near", "every key or none"));
    for (auto& k : t.keys) k.leaf_near = 10, k.leaf_far = 5;
    EXPECT_TRUE(has_problem(validate_track(t, at), at + "/0/leaf_far", ">= leaf_near"));

    std::vector<SunKey> sun = {{0, {0, 1, 0}}, {1, {0, -1, 0}}, {1, {1, 0, 0}}, {2, {0, 0, 0}}};
    p = validate_sun_track(sun, "/sun/track");
    EXPECT_TRUE(has_problem(p, "/sun/track/1/direction", "opposite"));
    EXPECT_TRUE(has_problem(p, "/sun/track/2/time", "same time"));
    EXPECT_TRUE(has_problem(p, "/sun/track/3/direction", "non-zero"));
    EXPECT_TRUE(has_problem(validate_sun_track({{0, {0, 1, 0}}}, "/s"), "/s", "two keys"));
}

// Scene files.

const char* kTrack = R"([
    {"time": 0, "position": [0, 1.6, 12], "look_at": [0, 2, 0]},
    {"time": 2, "position": [4, 1.8, 8], "look_at": [1, 2, 0], "fov": 30, "up": [0, 3, 0],
     "ease_in": 0.5, "ease_out": 1, "leaf_near": 0, "trunk_near": 0},
    {"time": 5, "position": [8, 2, 2], "look_at": [0, 2, -4]}
])";

std::string scene_with(const std::string& camera_extra, const std::string& top = "") {
    std::string s = R"({)" + top + R"("camera": {"fov": 35, "up": [0, 1, 0.5])";
    s.append(camera_extra).append("}}");
    return s;
}

// Every line of the InputError parse_scene throws, or {} if it does not throw.
std::vector<std::string> scene_problems(const std::string& text) {
    try {
        parse_scene(text, "walk.json");
    } catch (const InputError& e) {
        std::vector<std::string> lines;
        for (const auto& p : e.problems()) lines.push_back(format_problems(e.source(), {p}));
        return lines;
    }
    return {};
}

TEST(SceneTrack, ParsesKeysWithTheCamerasDefaults) {
    const SceneDesc s =
        parse_scene(scene_with(R"(, "track": )" + std::string(kTrack) +
                                   R"(, "interpolation": "linear", "constant_speed": true)",
                               R"("fps": 30, "sun": {"track": [{"time": 0, "direction": [0, 2, 0]},
                                                   {"time": 5, "direction": [1, 1, 0]}]}, )"),
                    "walk.json");
    EXPECT_TRUE(s.animated());
    EXPECT_EQ(s.fps, 30);
    ASSERT_EQ(s.camera_track.keys.size(), 3u);
    EXPECT_EQ(s.camera_track.interpolation, TrackInterpolation::kLinear);
    EXPECT_TRUE(s.camera_track.constant_speed);
    const CameraKey& k0 = s.camera_track.keys[0];
    EXPECT_EQ(k0.fov, 35);  // the camera's
    EXPECT_LT(glm::length(k0.up - glm::normalize(glm::dvec3(0, 1, 0.5))), 1e-15);
    const CameraKey& k1 = s.camera_track.keys[1];
    EXPECT_EQ(k1.time, 2);
    EXPECT_EQ(k1.fov, 30);
    EXPECT_EQ(k1.up, glm::dvec3(0, 1, 0));  // normalised
    EXPECT_EQ(k1.ease_in, 0.5);
    EXPECT_EQ(k1.ease_out, 1);
    EXPECT_EQ(k1.position, glm::dvec3(4, 1.8, 8));
    ASSERT_EQ(s.sun_track.size(), 2u);
    EXPECT_EQ(s.sun_track[0].direction, glm::dvec3(0, 1, 0));
    EXPECT_EQ(s.sun_track[1].time, 5);
    // Defaults: Catmull-Rom, 24 fps, not constant speed.
    const SceneDesc d = parse_scene(scene_with(R"(, "track": )" + std::string(kTrack)), "w.json");
    EXPECT_EQ(d.fps, 24);
    EXPECT_EQ(d.camera_track.interpolation, TrackInterpolation::kCatmullRom);
    EXPECT_FALSE(d.camera_track.constant_speed);
    EXPECT_TRUE(d.sun_track.empty());
}

TEST(SceneTrack, WithoutATrackIsAStill) {
    const SceneDesc s = parse_scene(scene_with(""), "still.json");
    EXPECT_FALSE(s.animated());
    EXPECT_TRUE(s.camera_track.keys.empty());
    EXPECT_TRUE(s.sun_track.empty());
}

TEST(SceneTrack, EachBadTrackGivesOneLineNamingItsKey) {
    struct Case {
        std::string camera, top, line;
    };
    const std::string k0 = R"({"time": 0, "position": [0, 1, 5], "look_at": [0, 1, 0]})";
    const std::string k1 = R"({"time": 1, "position": [1, 1, 5], "look_at": [0, 1, 0]})";
    const Case cases[] = {
        {R"(, "track": [)" + k0 + "]", "", "walk.json: /camera/track: a track needs at least two"},
        {R"(, "track": [])", "",
         "walk.json: /camera/track: a track needs at least two keys, got 0"},
        {R"(, "track": [)" + k1 + ", " + k0 + "]", "", "walk.json: /camera/track/1/time: keys"},
        {R"(, "track": [)" + k0 + ", " + k0 + "]", "", "walk.json: /camera/track/1/time: same"},
        {R"(, "track": [)" + k0 + R"(, {"time": 1, "position": [0, 1, 0], "look_at": [0, 1, 0]}])",
         "", "walk.json: /camera/track/1/look_at: must differ from the key's position"},
        {R"(, "track": [)" + k0 +
             R"(, {"time": 1, "position": [1, 1, 5], "look_at": [0, 1, 0], "fov": 0}])",
         "", "walk.json: /camera/track/1/fov: must be in"},
        {R"(, "track": [)" + k0 +
             R"(, {"time": 1, "position": [1, 1, 5], "look_at": [0, 1, 0], "fov": 180}])",
         "", "walk.json: /camera/track/1/fov: must be in"},
        {R"(, "track": [)" + k0 +
             R"(, {"time": 1, "position": [1, 1, 5], "look_at": [0, 1, 0], "ease": 1}])",
         "", "walk.json: /camera/track/1/ease: unknown key"},
        {R"(, "track": [)" + k0 + R"(, {"time": 1, "position": [1, 1, 5], "look_at": [0, 1, 0],
              "fov": 30, "fov": 31}])",
         "", "walk.json: /camera/track/1/fov: duplicate key"},
        {R"(, "track": [)" + k0 + R"(, {"position": [1, 1, 5], "look_at": [0, 1, 0]}])", "",
         "walk.json: /camera/track/1/time: missing"},
        {R"(, "track": [)" + k0 + ", " + k1 + R"(], "interpolation": "spline")", "",
         "walk.json: /camera/interpolation: expected \"catmull-rom\" or \"linear\", got "
         "\"spline\""},
        {R"(, "track": {"time": 0})", "", "walk.json: /camera/track: expected a list"},
        {"", R"("fps": 0, )", "walk.json: /fps: must be in"},
        {"", R"("sun": {"track": [{"time": 0, "direction": [0, 1, 0]}]}, )",
         "walk.json: /sun/track: a track needs at least two keys"},
        {"", R"("sun": {"track": [{"time": 0, "direction": [0, 1, 0]}, {"time": 1}]}, )",
         "walk.json: /sun/track/1/direction: missing"},
    };
    for (const Case& c : cases) {
        const std::vector<std::string> lines = scene_problems(scene_with(c.camera, c.top));
        ASSERT_EQ(lines.size(), 1u) << c.line << "\n" << testing::PrintToString(lines);
        EXPECT_TRUE(lines[0].starts_with(c.line)) << lines[0] << "\nexpected: " << c.line;
    }
}

TEST(SceneTrack, RenderExitsTwoOnABadTrackAndWritesNothing) {
    const auto dir = test::temp_dir("bad-track");
    const auto scene = dir / "walk.json";
    std::ofstream(scene) << scene_with(
        R"(, "track": [{"time": 1, "position": [0, 1, 5], "look_at": [0, 1, 0]},
                       {"time": 0, "position": [0, 1, 0], "look_at": [0, 1, 0], "fov": 0}])");
    const auto out = dir / "still.png";
    const auto r = test::run_pleinair("render " + scene.string() + " -o " + out.string());
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_NE(r.err.find("/camera/track/1/time"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("/camera/track/1/fov"), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(out));
}

}  // namespace
}  // namespace pleinair
