// Where a frame looks from: the one rule for the camera at a time (track_camera), the view of a
// still or of a frame of a shot, the views the level of detail replays and the cameras around
// a frame that decide what is seen. Every command, stage and bench takes its view from here.
#pragma once

#include <cstdint>
#include <glm/vec3.hpp>
#include <string>
#include <vector>

#include "pipeline/input/camera.h"
#include "pipeline/input/camera_track.h"
#include "pipeline/input/distance_circles.h"
#include "pipeline/input/frame_range.h"
#include "pipeline/input/scene.h"
#include "pipeline/input/settings.h"

namespace pleinair {

// What the camera track and the sun's keys give at the frame's time. The sun is the view's only
// when the scene keys it; a still sun is the shot's (its light and casters were built for it).
struct FrameView {
    Camera camera;
    glm::dvec3 sun_direction{0, 1, 0};  // towards the sun, unit
    DistanceCircles circles;            // carried by the camera (IV.6)
    // On a camera track: the level of detail replays the track up to `time`, the frame's
    // seconds (the sun's and the wind's clock in any animated scene; 0 for a still).
    bool on_track = false;
    double time = 0;
    // How far the eye moves in one frame there (zero for a still): strokes whose distances from
    // the eye are about to cross blend from one order to the other (composite.h).
    double eye_speed = 0;
};

// The camera of the scene's track at t seconds (the one rule every view uses): the track's
// key at t over the scene's camera parameters. Returns why it is degenerate there (its look-at
// passing through its position), or "".
std::string track_camera(const SceneDesc& scene, double t, Camera& out);
// The same from the track's key at that time, for a caller that reads the key's circles too.
std::string track_camera(const SceneDesc& scene, const CameraKey& key, Camera& out);

// The view of a still: the scene's camera and sun.
FrameView still_view(const SceneDesc& scene);

// The view at t seconds: the camera track's camera and the sun's keyed direction, where the
// scene has them (a still's otherwise). Throws std::runtime_error if the track's camera is
// degenerate there.
FrameView view_at(const SceneDesc& scene, double t);

// The seconds an animated scene's tracks cover: its camera track's first and last keys', or its
// sun track's when it has no camera track, or its wind track's when it has neither; {0, 0} for a
// still.
struct TimeSpan {
    double first = 0, last = 0;
};
TimeSpan animation_span(const SceneDesc& scene);

// The frames of an animated scene: those whose times lie within animation_span; frame 1 alone
// for a still.
FrameRange animation_frames(const SceneDesc& scene);

// The views whose history a frame's level of detail depends on (hysteresis and fades are
// replayed from the camera track, never carried from the frame painted before): the track's
// frames from its first up to the view's time, then the view itself; the view alone for a
// still.
std::vector<FrameView> replay_path(const SceneDesc& scene, const FrameView& view);

// Whether the scene carries circles anywhere (on the camera or on its track's keys).
bool scene_has_circles(const SceneDesc& scene);

// Where rays towards the eye go to decide how much of a stroke is seen past the opaque
// surfaces. A still camera: the frame's eye, from three heights on the sprite (its particle,
// half way up and its top), so a stroke rising from behind a crest shows a third at a time.
// A moving one (render/occlusion_frames n > 1): the camera at n times one frame apart around
// the frame's, each ray from one of the three heights of the sprite as that camera draws it.
// The times lie on a lattice fixed to the track's clock and each lattice time keeps its height,
// so frame N + 1 casts n - 1 of frame N's rays again: the share seen changes by at most 1/n a
// frame, whatever the silhouettes do.
struct SeenWindow {
    std::vector<Camera> cameras;   // empty: the frame's camera, at all three heights
    std::vector<uint8_t> heights;  // per camera: 0, 1 or 2 (particle, half way, top)
    std::vector<int64_t> lattice;  // per camera: its lattice time's index m
};
SeenWindow seen_window(const SceneDesc& scene, const FrameView& view, const RenderSettings& rs);

}  // namespace pleinair
