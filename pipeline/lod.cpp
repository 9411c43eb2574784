// level_of_detail: per tree, the distance values at its centre and the survivors' growth.
#include "pipeline/lod.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#define GLM_ENABLE_EXPERIMENTAL
#include <glm/gtx/norm.hpp>

#include "pipeline/frame_plan.h"
#include "pipeline/shot.h"
#include "shading/curves.h"
#include "shading/stroke_shader.h"

namespace pleinair {

double view_depth(const Camera& cam, const glm::dvec3& world) {
    return glm::dot(world - cam.eye, cam.forward);
}

float leaf_fade(float value, float fade_begin, float fade_end, float g) {
    if (!(fade_end > fade_begin)) return value >= fade_begin ? 0.0f : 1.0f;
    return 1.0f - gain((value - fade_begin) / (fade_end - fade_begin), g);
}

float bark_fade(float trunk_value, int limb_level, float label, float g) {
    if (limb_level < 2) return 1.0f;
    const float begin = 0.6f * label_hash(label, 3);
    return leaf_fade(trunk_value, begin, begin + 0.4f, g);
}

float near_field_fade(float near_value, float center_distance, float label, float g) {
    if (!(near_value > 0)) return 1.0f;
    const float begin = 0.15f + 0.55f * clamp01(center_distance) + 0.3f * label_hash(label, 4);
    return leaf_fade(near_value, begin, begin + 0.3f, g);
}

namespace {

// A direction's continuous bin coordinates: elevation and azimuth, each in bin units.
void direction_bins(const glm::vec3& v, float r, float& e, float& a) {
    constexpr float kPi = 3.14159265358979f;
    const float el = std::asin(std::clamp(v.y / r, -1.0f, 1.0f));  // -pi/2 .. pi/2
    const float az = std::atan2(v.z, v.x);                         // -pi .. pi
    e = (el / kPi + 0.5f) * kElevationBins - 0.5f;
    a = (az / (2 * kPi) + 0.5f) * kAzimuthBins - 0.5f;
}

// The survivors' move, bin by bin: sums in double and in index order, so no thread count or
// order can change a bit of it.
void radial_spread(const LeafParticles& L, const glm::vec3& center, float gain, float max_growth,
                   TreeLod& t) {
    constexpr int kBins = kElevationBins * kAzimuthBins;
    std::vector<double> all_w(kBins, 0.0), all_r2(kBins, 0.0), kept_w(kBins, 0.0),
        kept_r2(kBins, 0.0);
    for (size_t j = 0; j < L.size(); ++j) {
        const glm::vec3 v = L.position[j] - center;
        const float r = glm::length(v);
        if (!(r > 0)) continue;
        float e, a;
        direction_bins(v, r, e, a);
        const int be = std::clamp(static_cast<int>(std::lround(e)), 0, kElevationBins - 1);
        const int ba = (static_cast<int>(std::lround(a)) + kAzimuthBins) % kAzimuthBins;
        const int bin = be * kAzimuthBins + ba;
        const double alpha = leaf_fade(t.leaf, L.fade_begin[j], L.fade_end[j], gain);
        all_w[bin] += 1, all_r2[bin] += double(r) * r;
        kept_w[bin] += alpha, kept_r2[bin] += alpha * r * r;
    }
    // Bins too faint to measure take the whole tree's ratio.
    double aw = 0, ar = 0, kw = 0, kr = 0;
    for (int i = 0; i < kBins; ++i)
        aw += all_w[i], ar += all_r2[i], kw += kept_w[i], kr += kept_r2[i];
    if (!(kw > 1e-6) || !(kr > 0)) return;
    const double whole = std::sqrt((ar / aw) / (kr / kw));
    t.center = center;
    t.radial.assign(kBins, 1.0f);
    for (int i = 0; i < kBins; ++i) {
        const double ratio = kept_w[i] > 0.5 && kept_r2[i] > 0
                                 ? std::sqrt((all_r2[i] / all_w[i]) / (kept_r2[i] / kept_w[i]))
                             : all_w[i] > 0 ? whole
                                            : 1.0;
        t.radial[i] = static_cast<float>(ratio);
    }
    // Interpolating between bins blurs their ratios; one more pass scales them so the
    // survivors' RMS distance comes back to the whole crown's.
    double moved = 0;
    for (size_t j = 0; j < L.size(); ++j) {
        const double alpha = leaf_fade(t.leaf, L.fade_begin[j], L.fade_end[j], gain);
        if (alpha > 0)
            moved += alpha * glm::length2(glm::dvec3(spread_leaf(t, L.position[j]) - center));
    }
    const double fix = moved > 0 ? std::sqrt((ar / aw) / (moved / kw)) : 1.0;
    for (float& r : t.radial) r = static_cast<float>(std::clamp(r * fix, 1.0, double(max_growth)));
}

}  // namespace

glm::vec3 spread_leaf(const TreeLod& t, const glm::vec3& p) {
    if (t.radial.empty()) return p;
    const glm::vec3 v = p - t.center;
    const float r = glm::length(v);
    if (!(r > 0)) return p;
    float e, a;
    direction_bins(v, r, e, a);
    e = std::clamp(e, 0.0f, kElevationBins - 1.0f);
    const int e0 = std::min(static_cast<int>(e), kElevationBins - 2);
    const float fe = e - e0;
    const float af = std::floor(a);
    const float fa = a - af;
    const int a0 = (static_cast<int>(af) + kAzimuthBins) % kAzimuthBins;
    const int a1 = (a0 + 1) % kAzimuthBins;
    auto at = [&](int ei, int ai) { return t.radial[static_cast<size_t>(ei * kAzimuthBins + ai)]; };
    const float s = (at(e0, a0) * (1 - fa) + at(e0, a1) * fa) * (1 - fe) +
                    (at(e0 + 1, a0) * (1 - fa) + at(e0 + 1, a1) * fa) * fe;
    return t.center + v * s;
}

bool scene_has_circles(const Shot& shot) {
    const SceneDesc& s = shot.scene;
    if (s.circles.any()) return true;
    return !s.camera_track.keys.empty() && circles_of(s.camera_track.keys.front(), {}).any();
}

FrameLod level_of_detail(const Shot& shot, const FrameView& view, const RenderSettings& rs) {
    FrameLod lod;
    if (!rs.level_of_detail) return lod;
    const DistanceCircles& c = view.circles;
    lod.circles = c;
    lod.fade_gain = rs.fade_gain;
    lod.leaves = c.leaves();
    lod.trunks = c.trunks() && shot.plan.bark;
    lod.surfaces = c.leaves();
    lod.near_field = c.near_field > 0;
    if (!lod.leaves && !lod.trunks) return lod;
    const std::vector<BuiltTree>& trees = *shot.trees;
    lod.trees.resize(trees.size());
    const float max_growth = std::max(1.0f, rs.max_leaf_growth);
    tbb::parallel_for(size_t{0}, trees.size(), [&](size_t i) {
        const BuiltTree& b = trees[i];
        TreeLod& t = lod.trees[i];
        const double depth = view_depth(view.camera, shot.placements[i].place(b.tree.center));
        if (lod.trunks) t.trunk = circle_value(depth, c.trunk_near, c.trunk_far);
        if (!lod.leaves) return;
        t.leaf = circle_value(depth, c.leaf_near, c.leaf_far);
        const LeafParticles& L = b.tree.leaves;
        if (L.size() == 0 || t.leaf <= 0) return;
        double sum = 0;
        for (size_t j = 0; j < L.size(); ++j)
            sum += leaf_fade(t.leaf, L.fade_begin[j], L.fade_end[j], rs.fade_gain);
        // Cook et al. 2007: the survivors' area grows by 1 / u, so the crown's coverage stays
        // (for leaves overlapping at random).
        t.kept = static_cast<float>(sum / static_cast<double>(L.size()));
        const float floor = 1.0f / (max_growth * max_growth);
        t.growth = std::min(max_growth, 1.0f / std::sqrt(std::max(t.kept, floor)));
        radial_spread(L, b.tree.center, rs.fade_gain, max_growth, t);
    });
    return lod;
}

}  // namespace pleinair
