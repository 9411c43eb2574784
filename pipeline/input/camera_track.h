// A camera track: keys in time (position, look-at, up, field of view, distance circles), and the
// sun's direction and the wind in time, interpolated into any frame as a pure function of time.
#pragma once

#include <glm/vec3.hpp>
#include <string>
#include <vector>

#include "pipeline/input/camera.h"
#include "pipeline/input/distance_circles.h"
#include "pipeline/input/error.h"

namespace pleinair {

// One key of a camera track, at `time` seconds.
struct CameraKey {
    double time = 0;
    glm::dvec3 position{0, 1.6, 12};
    glm::dvec3 look_at{0, 2.5, 0};
    glm::dvec3 up{0, 1, 0};  // a direction; need not be unit
    double fov = 40;         // vertical, degrees, in (0, 180)
    // Slows the approach to this key (ease_in) and the departure from it (ease_out): 0 is the
    // plain spline, 1 brings the camera to rest at the key, values between blend.
    double ease_in = 0, ease_out = 0;
    // The level-of-detail distance circles (world units, DistanceCircles); 0 = not set. A
    // circle is set on every key of a track or on none; one the track does not set comes from
    // the camera's.
    double leaf_near = 0, leaf_far = 0, trunk_near = 0, trunk_far = 0, near_field = 0;
};

enum class TrackInterpolation {
    // Centripetal Catmull-Rom (alpha = 1/2) through the points of each vector channel: no loops,
    // cusps or overshoot at uneven spacing; C1 in time at interior keys.
    kCatmullRom,
    kLinear,  // straight between keys; the velocity jumps at keys unless eased
};

// "catmull-rom" or "linear".
const char* interpolation_name(TrackInterpolation interpolation);
// False (and `out` untouched) for any other name.
bool parse_interpolation(const std::string& name, TrackInterpolation& out);

struct CameraTrack {
    std::vector<CameraKey> keys;  // by increasing time; empty: a still
    TrackInterpolation interpolation = TrackInterpolation::kCatmullRom;
    // The position moves at one speed along the whole path between the first and the last
    // key's times (arc length); the other channels follow the same path parameter. Interior
    // keys are passed through but not at their own times, and only the first key's ease_out
    // and the last key's ease_in apply (to the progress along the whole path). A camera that
    // does not move falls back to the keys' own times.
    bool constant_speed = false;
};

// The track's channels at time t (clamped to the first and last keys' times). At a key's time
// (and at the ends with constant_speed) the key itself comes back, bit for bit; elsewhere `up`
// is unit length and `time` is t. Interpolation, per channel:
// - position, look_at, up: the track's interpolation of the points, each channel with its own
//   centripetal knots; the knots are timed by a monotone cubic (Fritsch-Butland) through the
//   keys' times, so the keys are hit at their times and the velocity is continuous there.
// - fov and the circles: the same monotone cubic in time (Catmull-Rom) or linear: never outside
//   the range of the segment's two keys.
// - ease: a cubic remap of the segment's time whose slope at a key is 1 - ease.
// Requires a track that validate_track accepts.
CameraKey track_at(const CameraTrack& track, double t);

// The key's circles; `fallback`'s where the key leaves a circle unset (a pair is taken whole).
DistanceCircles circles_of(const CameraKey& key, const DistanceCircles& fallback);

// `base` (its width and height) with the track's position, look-at, up and fov at time t.
CameraParams camera_at(const CameraTrack& track, const CameraParams& base, double t);
// `base` with the key's position, look-at, up and fov.
CameraParams camera_of(const CameraKey& key, const CameraParams& base);

// Path length of the position between the first and the last key (Gauss-Legendre).
double track_length(const CameraTrack& track);

// One problem per line: fewer than two keys, times not increasing, non-finite values, a key
// whose position equals its look-at, a zero up, fov outside (0, 180), ease outside [0, 1], a
// negative circle, near beyond far, a circle set on some keys only. Pointers start with
// `pointer` ("/camera/track" gives "/camera/track/3/time").
std::vector<Problem> validate_track(const CameraTrack& track, const std::string& pointer);

// The direction towards the sun at a time.
struct SunKey {
    double time = 0;
    glm::dvec3 direction{-0.5, 0.8, 0.4};
};

// Spherical linear interpolation of the keys' normalised directions; clamped at the ends; the
// key's direction itself, bit for bit, at its time.
glm::dvec3 sun_at(const std::vector<SunKey>& keys, double t);

// Fewer than two keys, times not increasing, a zero or non-finite direction, consecutive keys
// pointing opposite ways (no single arc between them).
std::vector<Problem> validate_sun_track(const std::vector<SunKey>& keys,
                                        const std::string& pointer);

// The wind's mean speed and direction at a time (the scene's /wind, its gusts aside).
struct WindKey {
    double time = 0;
    double strength = 0;                  // m/s
    glm::dvec3 direction{1.0, 0.0, 0.0};  // where it blows to, level (y is dropped)
    bool own_direction = false;  // the key names one (else /wind/direction's, checked there)
};

// The wind of a scene (/wind): a mean that a track may key, gusts that pass over the land with
// the wind (gust_envelope, in generators/wind.h), and the seed of both.
struct WindDesc {
    bool present = false;
    double strength = 0;  // m/s, the mean when no track keys it
    glm::dvec3 direction{1.0, 0.0, 0.0};
    double gustiness = 0.4;  // 0: steady; 1: gusts from half the mean to twice it
    double gust_period = 6;  // s between one gust's value and the next
    double turbulence = 40;  // world units across the wind over which gusts are one
    uint64_t seed = 1;
    std::vector<WindKey> track;  // empty: the mean stays
};

// The wind's mean at t: linear in time between keys (speed) and along the level arc between
// their directions; clamped at the ends; the key's own values at its time. The direction is
// unit and level.
WindKey wind_at(const WindDesc& wind, double t);

// The wind's speed at a place and time, its gusts included: the gust field moves downwind at
// the wind's mean (/wind/strength, at least 1 m/s), so a gust reaches the trees in its path one
// after another; across the wind it changes every `turbulence` units.
double gust_speed(const WindDesc& wind, const WindKey& at, const glm::dvec3& world);

// Fewer than two keys, times not increasing, a non-finite or negative strength, a direction
// with no level part, consecutive keys pointing opposite ways.
std::vector<Problem> validate_wind_track(const std::vector<WindKey>& keys,
                                         const std::string& pointer);

// Frames are numbered from 1, as in Blender: frame N is at (N - 1) / fps seconds.
double frame_time(int frame, double fps);
// The frames whose times lie within [first key, last key]: first_frame..last_frame (an empty
// range, last < first, when no frame time falls inside). Frame times are compared exactly as
// frame_time computes them. A still (no keys) has the one frame 1.
int track_first_frame(const CameraTrack& track, double fps);
int track_last_frame(const CameraTrack& track, double fps);
bool frame_in_track(const CameraTrack& track, int frame, double fps);
// Frames 1..N whose times lie within [0, last key's time]: N, the length of the shot in frames
// (those before the first key's time, if it is after 0, are outside the track).
int track_frame_count(const CameraTrack& track, double fps);

}  // namespace pleinair
