// track_camera, the views of stills and of a shot's frames, replay_path and seen_window.
#include "pipeline/frame/frame_view.h"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <stdexcept>

#include "pipeline/input/camera_track.h"

namespace pleinair {

std::string track_camera(const SceneDesc& scene, const CameraKey& key, Camera& out) {
    return make_camera(camera_of(key, scene.camera_params), out);
}

std::string track_camera(const SceneDesc& scene, double t, Camera& out) {
    return track_camera(scene, track_at(scene.camera_track, t), out);
}

FrameView still_view(const SceneDesc& scene) {
    return {scene.camera, scene.sun_direction, scene.circles};
}

FrameView view_at(const SceneDesc& scene, double t) {
    FrameView v = still_view(scene);
    v.time = t;  // the sun's and the wind's clock, with or without a camera track
    if (!scene.camera_track.keys.empty()) {
        const CameraKey key = track_at(scene.camera_track, t);
        if (std::string why = track_camera(scene, key, v.camera); !why.empty())
            throw std::runtime_error("the camera track at " + std::to_string(t) + " s: " + why);
        v.circles = circles_of(key, scene.circles);
        v.on_track = true;
        // Central difference over a frame either side (one side at the track's ends).
        const double dt = 1.0 / scene.fps;
        const double ta = std::max(t - dt, scene.camera_track.keys.front().time);
        const double tb = std::min(t + dt, scene.camera_track.keys.back().time);
        if (tb > ta)
            v.eye_speed = glm::length(track_at(scene.camera_track, tb).position -
                                      track_at(scene.camera_track, ta).position) *
                          (dt / (tb - ta));
    }
    if (!scene.sun_track.empty()) v.sun_direction = sun_at(scene.sun_track, t);
    return v;
}

TimeSpan animation_span(const SceneDesc& scene) {
    const auto& cam = scene.camera_track.keys;
    if (!cam.empty()) return {cam.front().time, cam.back().time};
    if (!scene.sun_track.empty())
        return {scene.sun_track.front().time, scene.sun_track.back().time};
    if (!scene.wind.track.empty())
        return {scene.wind.track.front().time, scene.wind.track.back().time};
    return {};
}

FrameRange animation_frames(const SceneDesc& scene) {
    if (!scene.animated()) return {1, 1, 1};
    const TimeSpan span = animation_span(scene);
    CameraTrack times;  // the frame counting only reads the keys' times
    times.keys = {CameraKey{span.first}, CameraKey{span.last}};
    return {track_first_frame(times, scene.fps), track_last_frame(times, scene.fps), 1};
}

std::vector<FrameView> replay_path(const SceneDesc& scene, const FrameView& view) {
    if (!view.on_track) return {view};
    std::vector<FrameView> path;
    const int first = track_first_frame(scene.camera_track, scene.fps);
    for (int f = first; frame_time(f, scene.fps) < view.time; ++f)
        path.push_back(view_at(scene, frame_time(f, scene.fps)));
    path.push_back(view);
    return path;
}

bool scene_has_circles(const SceneDesc& s) {
    if (s.circles.any()) return true;
    return !s.camera_track.keys.empty() && circles_of(s.camera_track.keys.front(), {}).any();
}

SeenWindow seen_window(const SceneDesc& scene, const FrameView& view, const RenderSettings& rs) {
    SeenWindow w;
    const int n = rs.occlusion_frames;
    const auto& keys = scene.camera_track.keys;
    if (n <= 1 || !view.on_track || !(view.eye_speed > 0) || keys.empty()) return w;
    // Lattice times (m + c) / fps, c = 1/2 for an even n so the window centres on the frame;
    // the n nearest the frame's time. The epsilon keeps a frame's own time, (N - 1) / fps times
    // fps, from rounding to the frame before.
    const double u = view.time * scene.fps + 1e-6;
    const double c = n % 2 == 0 ? 0.5 : 0.0;
    const int64_t first = static_cast<int64_t>(std::floor(u - c)) - (n - 1) / 2;
    for (int i = 0; i < n; ++i) {
        const int64_t m = first + i;
        const double t = std::clamp((static_cast<double>(m) + c) / scene.fps, keys.front().time,
                                    keys.back().time);
        Camera cam;
        if (!track_camera(scene, t, cam).empty())
            cam = view.camera;  // a key the track's checks let through cannot fail here
        w.cameras.push_back(cam);
        w.heights.push_back(static_cast<uint8_t>(((m % 3) + 3) % 3));
        w.lattice.push_back(m);
    }
    return w;
}

}  // namespace pleinair
