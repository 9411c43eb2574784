// A camera track: keys in time interpolated by centripetal Catmull-Rom timed by a monotone cubic,
// eased per key, optionally at constant speed along the path; the sun's direction by slerp, the
// wind's mean linearly and along the level arc.
#include "pipeline/input/camera_track.h"

#include <algorithm>
#include <climits>
#include <cmath>
#include <glm/geometric.hpp>

#include "generators/tree_params.h"
#include "generators/wind.h"
#include "shading/portable_math.h"

namespace pleinair {

namespace {

using VectorField = glm::dvec3 CameraKey::*;
using ScalarField = double CameraKey::*;

constexpr ScalarField kCircles[] = {&CameraKey::leaf_near, &CameraKey::leaf_far,
                                    &CameraKey::trunk_near, &CameraKey::trunk_far,
                                    &CameraKey::near_field};
constexpr const char* kCircleNames[] = {"leaf_near", "leaf_far", "trunk_near", "trunk_far",
                                        "near_field"};

// The cubic on [0, 1] with values p0, p1 and derivatives m0, m1 at its ends.
template <class T>
T hermite(const T& p0, const T& m0, const T& p1, const T& m1, double u) {
    const double u2 = u * u, u3 = u2 * u;
    return (2 * u3 - 3 * u2 + 1) * p0 + (u3 - 2 * u2 + u) * m0 + (-2 * u3 + 3 * u2) * p1 +
           (u3 - u2) * m1;
}

template <class T>
T hermite_derivative(const T& p0, const T& m0, const T& p1, const T& m1, double u) {
    const double u2 = u * u;
    return (6 * u2 - 6 * u) * p0 + (3 * u2 - 4 * u + 1) * m0 + (-6 * u2 + 6 * u) * p1 +
           (3 * u2 - 2 * u) * m1;
}

// A segment's eased time: slope 1 - ease_out at its start and 1 - ease_in at its end; with no
// ease, u itself. Slopes in [0, 1] keep it monotone.
double ease(double u, double ease_out, double ease_in) {
    if (ease_out == 0 && ease_in == 0) return u;
    return hermite(0.0, 1 - ease_out, 1.0, 1 - ease_in, u);
}

// Fritsch-Butland slope at a key between secants s0 (interval h0 before) and s1 (h1 after): a
// weighted harmonic mean, 0 at an extremum, never over 3 times either secant, so the cubic
// through the keys is monotone wherever the keys are.
double monotone_slope(double s0, double s1, double h0, double h1) {
    if (!(s0 * s1 > 0)) return 0;
    const double w1 = 2 * h1 + h0, w2 = h1 + 2 * h0;
    return (w1 + w2) / (w1 / s0 + w2 / s1);
}

// One segment of a vector channel as a function of the segment's (eased) time u: the
// centripetal Catmull-Rom piece p(v) = hermite(p0, m0, p1, m1, v) in its knot parameter v, and
// v(u) = hermite(0, v0, 1, v1, u), the monotone cubic that times the knots.
struct VectorSegment {
    glm::dvec3 p0{0.0}, m0{0.0}, p1{0.0}, m1{0.0};
    double v0 = 1, v1 = 1;
    bool linear = false;

    glm::dvec3 at(double u) const {
        if (linear) return p0 + (p1 - p0) * u;
        return hermite(p0, m0, p1, m1, hermite(0.0, v0, 1.0, v1, u));
    }
    glm::dvec3 derivative(double u) const {
        if (linear) return p1 - p0;
        const double v = hermite(0.0, v0, 1.0, v1, u);
        return hermite_derivative(p0, m0, p1, m1, v) * hermite_derivative(0.0, v0, 1.0, v1, u);
    }
};

VectorSegment vector_segment(const CameraTrack& track, size_t i, VectorField field) {
    const auto& keys = track.keys;
    const auto n = static_cast<ptrdiff_t>(keys.size());
    VectorSegment s;
    s.p0 = keys[i].*field;
    s.p1 = keys[i + 1].*field;
    if (track.interpolation == TrackInterpolation::kLinear) {
        s.linear = true;
        return s;
    }
    // Points -1 and n are reflections of the second and the last but one through the ends.
    auto point = [&](ptrdiff_t k) {
        if (k < 0) return 2.0 * keys[0].*field - keys[1].*field;
        if (k >= n) return 2.0 * keys[n - 1].*field - keys[n - 2].*field;
        return keys[k].*field;
    };
    auto time = [&](ptrdiff_t k) { return keys[k].time; };
    // Centripetal knot spacing: the square root of the chord.
    auto knot = [&](ptrdiff_t k) { return std::sqrt(glm::length(point(k + 1) - point(k))); };
    auto quotient = [](const glm::dvec3& d, double h) { return h > 0 ? d / h : glm::dvec3(0.0); };
    // Derivative of the Catmull-Rom curve in its knot parameter at point k (Barry-Goldman);
    // at the ends, with the reflected points, the chord's direction.
    auto tangent = [&](ptrdiff_t k) {
        const double a = knot(k - 1), b = knot(k);
        return quotient(point(k) - point(k - 1), a) - quotient(point(k + 1) - point(k - 1), a + b) +
               quotient(point(k + 1) - point(k), b);
    };
    // Knots per second over segment k, and the monotone slope of knots over time at key k.
    auto secant = [&](ptrdiff_t k) { return knot(k) / (time(k + 1) - time(k)); };
    auto slope = [&](ptrdiff_t k) {
        if (k == 0) return secant(0);
        if (k == n - 1) return secant(n - 2);
        return monotone_slope(secant(k - 1), secant(k), time(k) - time(k - 1),
                              time(k + 1) - time(k));
    };
    const auto k = static_cast<ptrdiff_t>(i);
    const double h = knot(k);
    if (!(h > 0)) {  // the channel stands still over this segment
        s.linear = true;
        return s;
    }
    s.m0 = tangent(k) * h;
    s.m1 = tangent(k + 1) * h;
    const double sec = secant(k);
    s.v0 = slope(k) / sec;
    s.v1 = slope(k + 1) / sec;
    return s;
}

// A scalar channel over segment i at its eased time u: the monotone cubic through the keys in
// time (clamped to the segment's two values against rounding), or linear.
double scalar_at(const CameraTrack& track, size_t i, double u, ScalarField field) {
    const auto& keys = track.keys;
    const size_t n = keys.size();
    const double y0 = keys[i].*field, y1 = keys[i + 1].*field;
    if (track.interpolation == TrackInterpolation::kLinear || y0 == y1) return y0 + (y1 - y0) * u;
    auto h = [&](size_t k) { return keys[k + 1].time - keys[k].time; };
    auto secant = [&](size_t k) { return (keys[k + 1].*field - keys[k].*field) / h(k); };
    auto slope = [&](size_t k) {
        if (k == 0) return secant(0);
        if (k == n - 1) return secant(n - 2);
        return monotone_slope(secant(k - 1), secant(k), h(k - 1), h(k));
    };
    const double y = hermite(y0, slope(i) * h(i), y1, slope(i + 1) * h(i), u);
    return std::clamp(y, std::min(y0, y1), std::max(y0, y1));
}

// Every channel of segment i at its eased time u.
CameraKey segment_at(const CameraTrack& track, size_t i, double u, double t) {
    CameraKey key;
    key.time = t;
    key.position = vector_segment(track, i, &CameraKey::position).at(u);
    key.look_at = vector_segment(track, i, &CameraKey::look_at).at(u);
    const glm::dvec3 up = vector_segment(track, i, &CameraKey::up).at(u);
    const double l = glm::length(up);
    if (l > 1e-12 && std::isfinite(l))
        key.up = up / l;
    else  // keys' ups that cancel out: the nearer key's
        key.up = glm::normalize(u < 0.5 ? track.keys[i].up : track.keys[i + 1].up);
    key.fov = scalar_at(track, i, u, &CameraKey::fov);
    for (ScalarField f : kCircles) key.*f = scalar_at(track, i, u, f);
    return key;
}

// 5-point Gauss-Legendre nodes and weights on [-1, 1].
constexpr double kGaussNodes[5] = {-0.9061798459386640, -0.5384693101056831, 0.0,
                                   0.5384693101056831, 0.9061798459386640};
constexpr double kGaussWeights[5] = {0.2369268850561891, 0.4786286704993665, 0.5688888888888889,
                                     0.4786286704993665, 0.2369268850561891};
constexpr int kArcSteps = 32;  // Gauss-Legendre panels per segment

double arc(const VectorSegment& s, double a, double b) {
    double sum = 0;
    const double mid = (a + b) / 2, half = (b - a) / 2;
    for (int k = 0; k < 5; ++k)
        sum += kGaussWeights[k] * glm::length(s.derivative(mid + half * kGaussNodes[k]));
    return sum * half;
}

// Cumulative arc length at the panels' ends, kArcSteps + 1 values from 0.
std::vector<double> arc_table(const VectorSegment& s) {
    std::vector<double> table(kArcSteps + 1, 0.0);
    for (int k = 0; k < kArcSteps; ++k)
        table[k + 1] = table[k] + arc(s, double(k) / kArcSteps, double(k + 1) / kArcSteps);
    return table;
}

// The u at which the arc length from 0 reaches `target`: the panel by the table, then Newton
// kept inside its bracket (bisection when a step leaves it); a fixed iteration cap keeps it
// deterministic.
double invert_arc(const VectorSegment& s, const std::vector<double>& table, double target) {
    int k = 0;
    while (k + 1 < kArcSteps && table[k + 1] < target) ++k;
    double lo = double(k) / kArcSteps, hi = double(k + 1) / kArcSteps;
    const double a = lo, base = table[k], span = table[k + 1] - table[k];
    if (!(span > 0)) return lo;
    double u = lo + (hi - lo) * std::clamp((target - base) / span, 0.0, 1.0);
    for (int it = 0; it < 60; ++it) {
        const double f = base + arc(s, a, u) - target;
        if (std::abs(f) <= 1e-13 * table.back()) break;
        (f > 0 ? hi : lo) = u;
        const double speed = glm::length(s.derivative(u));
        double next = speed > 0 ? u - f / speed : lo;
        if (!(next > lo && next < hi)) next = (lo + hi) / 2;
        if (next == u) break;
        u = next;
    }
    return u;
}

CameraKey constant_speed_at(const CameraTrack& track, double t, double length) {
    const auto& keys = track.keys;
    const double t0 = keys.front().time, t1 = keys.back().time;
    const double progress = ease((t - t0) / (t1 - t0), keys.front().ease_out, keys.back().ease_in);
    double target = progress * length;
    for (size_t i = 0; i + 1 < keys.size(); ++i) {
        const VectorSegment s = vector_segment(track, i, &CameraKey::position);
        const std::vector<double> table = arc_table(s);
        if (target <= table.back() || i + 2 == keys.size())
            return segment_at(track, i, invert_arc(s, table, std::min(target, table.back())), t);
        target -= table.back();
    }
    return keys.back();
}

std::string key_pointer(const std::string& pointer, size_t i, const char* field) {
    return pointer + "/" + std::to_string(i) + "/" + field;
}

bool finite(const glm::dvec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

// Times present, finite and increasing: one problem per bad key.
template <class Key>
void check_times(const std::vector<Key>& keys, const std::string& pointer,
                 std::vector<Problem>& problems) {
    if (keys.size() < 2)
        problems.push_back(
            {pointer, "a track needs at least two keys, got " + std::to_string(keys.size())});
    for (size_t i = 0; i < keys.size(); ++i) {
        const double t = keys[i].time;
        if (!std::isfinite(t)) {
            problems.push_back({key_pointer(pointer, i, "time"), "must be a finite number"});
            continue;
        }
        if (i == 0 || !std::isfinite(keys[i - 1].time)) continue;
        const double prev = keys[i - 1].time;
        if (t == prev)
            problems.push_back({key_pointer(pointer, i, "time"),
                                "same time as key " + std::to_string(i - 1) + " (" +
                                    format_number(t) + "): keys need distinct times"});
        else if (t < prev)
            problems.push_back({key_pointer(pointer, i, "time"),
                                "keys must be in time order: " + format_number(t) +
                                    " comes before key " + std::to_string(i - 1) + "'s " +
                                    format_number(prev)});
    }
}

// The first frame at or after time t (>= 1) and the last at or before it (0 when none):
// started from the product and corrected against frame_time itself.
int first_frame_from(double t, double fps) {
    double guess = std::clamp(std::ceil(t * fps) + 1, 1.0, double(INT_MAX - 2));
    int f = static_cast<int>(guess);
    while (f > 1 && frame_time(f - 1, fps) >= t) --f;
    while (f < INT_MAX - 1 && frame_time(f, fps) < t) ++f;
    return f;
}

int last_frame_to(double t, double fps) {
    double guess = std::clamp(std::floor(t * fps) + 1, 0.0, double(INT_MAX - 2));
    int f = static_cast<int>(guess);
    while (f < INT_MAX - 1 && frame_time(f + 1, fps) <= t) ++f;
    while (f >= 1 && frame_time(f, fps) > t) --f;
    return f;
}

}  // namespace

const char* interpolation_name(TrackInterpolation interpolation) {
    return interpolation == TrackInterpolation::kLinear ? "linear" : "catmull-rom";
}

bool parse_interpolation(const std::string& name, TrackInterpolation& out) {
    for (auto i : {TrackInterpolation::kCatmullRom, TrackInterpolation::kLinear})
        if (name == interpolation_name(i)) {
            out = i;
            return true;
        }
    return false;
}

CameraKey track_at(const CameraTrack& track, double t) {
    const auto& keys = track.keys;
    if (keys.empty()) return CameraKey{};
    if (!(t > keys.front().time)) return keys.front();
    if (t >= keys.back().time) return keys.back();
    if (track.constant_speed) {
        const double length = track_length(track);
        if (length > 0 && std::isfinite(length)) return constant_speed_at(track, t, length);
    }
    // The segment [keys[i].time, keys[i + 1].time) holding t.
    const auto it = std::upper_bound(keys.begin(), keys.end(), t,
                                     [](double x, const CameraKey& k) { return x < k.time; });
    const size_t i = static_cast<size_t>(it - keys.begin()) - 1;
    if (keys[i].time == t) return keys[i];
    const double u = (t - keys[i].time) / (keys[i + 1].time - keys[i].time);
    return segment_at(track, i, ease(u, keys[i].ease_out, keys[i + 1].ease_in), t);
}

CameraParams camera_at(const CameraTrack& track, const CameraParams& base, double t) {
    return camera_of(track_at(track, t), base);
}

CameraParams camera_of(const CameraKey& key, const CameraParams& base) {
    CameraParams params = base;
    params.position = key.position;
    params.look_at = key.look_at;
    params.up = key.up;
    params.fov = key.fov;
    return params;
}

double track_length(const CameraTrack& track) {
    double length = 0;
    for (size_t i = 0; i + 1 < track.keys.size(); ++i)
        length += arc_table(vector_segment(track, i, &CameraKey::position)).back();
    return length;
}

std::vector<Problem> validate_track(const CameraTrack& track, const std::string& pointer) {
    std::vector<Problem> problems;
    const auto& keys = track.keys;
    check_times(keys, pointer, problems);
    for (size_t i = 0; i < keys.size(); ++i) {
        const CameraKey& k = keys[i];
        auto at = [&](const char* field) { return key_pointer(pointer, i, field); };
        bool vectors_finite = true;
        for (auto [field, name] :
             {std::pair{&CameraKey::position, "position"},
              std::pair{&CameraKey::look_at, "look_at"}, std::pair{&CameraKey::up, "up"}})
            if (!finite(k.*field)) {
                problems.push_back({at(name), "must be finite"});
                vectors_finite = false;
            }
        if (vectors_finite && k.position == k.look_at)
            problems.push_back(
                {at("look_at"), "must differ from the key's position " +
                                    format_vector(k.position.x, k.position.y, k.position.z)});
        if (vectors_finite && k.up == glm::dvec3(0.0))
            problems.push_back({at("up"), "must be a non-zero direction"});
        if (!(k.fov > 0 && k.fov < 180))
            problems.push_back({at("fov"), "must be in (0, 180), got " + format_number(k.fov)});
        if (!(k.ease_in >= 0 && k.ease_in <= 1))
            problems.push_back(
                {at("ease_in"), "must be in [0, 1], got " + format_number(k.ease_in)});
        if (!(k.ease_out >= 0 && k.ease_out <= 1))
            problems.push_back(
                {at("ease_out"), "must be in [0, 1], got " + format_number(k.ease_out)});
        for (Problem& p :
             validate_circles({k.leaf_near, k.leaf_far, k.trunk_near, k.trunk_far, k.near_field},
                              pointer + "/" + std::to_string(i)))
            problems.push_back(std::move(p));
    }
    // A circle set (non-zero) on some keys only has nothing to interpolate from elsewhere.
    for (int c = 0; c < 5; ++c) {
        size_t set = 0, first_set = 0;
        for (size_t i = 0; i < keys.size(); ++i)
            if (keys[i].*kCircles[c] != 0 && set++ == 0) first_set = i;
        if (set == 0 || set == keys.size()) continue;
        for (size_t i = 0; i < keys.size(); ++i)
            if (keys[i].*kCircles[c] == 0)
                problems.push_back({key_pointer(pointer, i, kCircleNames[c]),
                                    "missing: key " + std::to_string(first_set) +
                                        " sets it, and a circle is set on every key or none"});
    }
    return problems;
}

DistanceCircles circles_of(const CameraKey& k, const DistanceCircles& fallback) {
    DistanceCircles c = fallback;
    if (k.leaf_far > 0) c.leaf_near = k.leaf_near, c.leaf_far = k.leaf_far;
    if (k.trunk_far > 0) c.trunk_near = k.trunk_near, c.trunk_far = k.trunk_far;
    if (k.near_field > 0) c.near_field = k.near_field;
    return c;
}

glm::dvec3 sun_at(const std::vector<SunKey>& keys, double t) {
    if (keys.empty()) return SunKey{}.direction;
    if (!(t > keys.front().time)) return keys.front().direction;
    if (t >= keys.back().time) return keys.back().direction;
    const auto it = std::upper_bound(keys.begin(), keys.end(), t,
                                     [](double x, const SunKey& k) { return x < k.time; });
    const size_t i = static_cast<size_t>(it - keys.begin()) - 1;
    if (keys[i].time == t) return keys[i].direction;
    const double u = (t - keys[i].time) / (keys[i + 1].time - keys[i].time);
    const glm::dvec3 a = glm::normalize(keys[i].direction);
    const glm::dvec3 b = glm::normalize(keys[i + 1].direction);
    const double angle = pmath::acos(std::clamp(glm::dot(a, b), -1.0, 1.0));
    glm::dvec3 d =
        pmath::sin(angle) > 1e-9
            ? (pmath::sin((1 - u) * angle) * a + pmath::sin(u * angle) * b) / pmath::sin(angle)
            : a + (b - a) * u;  // nearly the same direction
    return glm::normalize(d);
}

std::vector<Problem> validate_sun_track(const std::vector<SunKey>& keys,
                                        const std::string& pointer) {
    std::vector<Problem> problems;
    check_times(keys, pointer, problems);
    for (size_t i = 0; i < keys.size(); ++i) {
        const glm::dvec3 d = keys[i].direction;
        const std::string at = key_pointer(pointer, i, "direction");
        if (!finite(d) || d == glm::dvec3(0.0)) {
            problems.push_back({at, "must be a finite, non-zero direction"});
            continue;
        }
        if (i > 0 && finite(keys[i - 1].direction) && keys[i - 1].direction != glm::dvec3(0.0) &&
            glm::dot(glm::normalize(d), glm::normalize(keys[i - 1].direction)) < -1 + 1e-9)
            problems.push_back({at, "points opposite to key " + std::to_string(i - 1) +
                                        "'s: no single arc joins them; add a key between"});
    }
    return problems;
}

namespace {

glm::dvec3 level(const glm::dvec3& d) {
    const glm::dvec3 l(d.x, 0.0, d.z);
    const double n = glm::length(l);
    return n > 1e-12 && std::isfinite(n) ? l / n : glm::dvec3(1.0, 0.0, 0.0);
}

}  // namespace

WindKey wind_at(const WindDesc& wind, double t) {
    const std::vector<WindKey>& keys = wind.track;
    WindKey out{t, wind.strength, level(wind.direction)};
    if (keys.empty()) return out;
    if (!(t > keys.front().time)) return {t, keys.front().strength, level(keys.front().direction)};
    if (t >= keys.back().time) return {t, keys.back().strength, level(keys.back().direction)};
    const auto it = std::upper_bound(keys.begin(), keys.end(), t,
                                     [](double x, const WindKey& k) { return x < k.time; });
    const size_t i = static_cast<size_t>(it - keys.begin()) - 1;
    const WindKey& a = keys[i];
    const WindKey& b = keys[i + 1];
    if (a.time == t) return {t, a.strength, level(a.direction)};
    const double u = (t - a.time) / (b.time - a.time);
    out.strength = a.strength + (b.strength - a.strength) * u;
    // Along the level arc: the angle between the two directions, turned by u of it.
    const glm::dvec3 da = level(a.direction), db = level(b.direction);
    const double angle = pmath::atan2(da.x * db.z - da.z * db.x, glm::dot(da, db));
    double s, c;
    pmath::sincos(-u * angle, s, c);
    out.direction = level({da.x * c - da.z * s, 0.0, da.x * s + da.z * c});
    return out;
}

double gust_speed(const WindDesc& wind, const WindKey& at, const glm::dvec3& world) {
    const double mean = std::max(0.0, at.strength);
    if (!(mean > 0) || !(wind.gustiness > 0)) return mean;
    const glm::dvec3 d = at.direction;
    const double along = world.x * d.x + world.z * d.z, across = world.z * d.x - world.x * d.z;
    const double front = std::max(1.0, wind.strength);
    const double g = gust_envelope((at.time - along / front) / wind.gust_period,
                                   across / wind.turbulence, wind.seed);
    // Peaks, not waves: the cube keeps most of the time near the calmer mean and brings a gust
    // up to (1 + gustiness) of it now and then; its mean over time is about the mean's.
    return mean * (1.0 - 0.5 * wind.gustiness + 1.5 * wind.gustiness * g * g * g);
}

std::vector<Problem> validate_wind_track(const std::vector<WindKey>& keys,
                                         const std::string& pointer) {
    std::vector<Problem> problems;
    check_times(keys, pointer, problems);
    for (size_t i = 0; i < keys.size(); ++i) {
        const glm::dvec3 d = keys[i].direction;
        const std::string at = key_pointer(pointer, i, "direction");
        if (!keys[i].own_direction) continue;
        if (!finite(d) || !(d.x * d.x + d.z * d.z > 1e-12)) {
            problems.push_back({at, "must be a finite direction with a level part (x or z)"});
            continue;
        }
        if (i > 0 && glm::dot(level(d), level(keys[i - 1].direction)) < -1 + 1e-9)
            problems.push_back({at, "points opposite to key " + std::to_string(i - 1) +
                                        "'s: no single arc joins them; add a key between"});
    }
    return problems;
}

double frame_time(int frame, double fps) { return (frame - 1) / fps; }

int track_first_frame(const CameraTrack& track, double fps) {
    return track.keys.empty() ? 1 : first_frame_from(track.keys.front().time, fps);
}

int track_last_frame(const CameraTrack& track, double fps) {
    return track.keys.empty() ? 1 : last_frame_to(track.keys.back().time, fps);
}

bool frame_in_track(const CameraTrack& track, int frame, double fps) {
    return frame >= track_first_frame(track, fps) && frame <= track_last_frame(track, fps);
}

int track_frame_count(const CameraTrack& track, double fps) { return track_last_frame(track, fps); }

}  // namespace pleinair
