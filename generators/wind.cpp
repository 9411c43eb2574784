// build_wind_rig, pose_tree and the waves: a tree's skeleton bent by the wind at a time.
#include "generators/wind.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <glm/geometric.hpp>

#include "generators/bark.h"
#include "generators/rng.h"
#include "shading/portable_math.h"

namespace pleinair {

namespace {

// How far a part bends at a wind speed v (m/s): k v^2 / stiffness (drag grows with the square
// of the speed), saturated towards the most a part of that level may bend. Chosen so a light
// breeze (4 m/s) leans a trunk by a third of a degree and tosses a limb by two, and a strong
// gust (12 m/s) bends the trunk by three and the limbs by about eighteen; no gale folds a tree.
constexpr double kBend[3] = {3.3e-4, 2.2e-3, 3.3e-3};  // trunk, branches, twigs (rad s^2/m^2)
constexpr double kMaxBend[3] = {0.12, 0.6, 0.8};       // radians
constexpr double kFrequency[3] = {0.32, 0.85, 1.5};    // Hz, about which each limb's is drawn
constexpr double kSway = 0.5;      // the sway's share of the mean bend, downwind
constexpr double kLateral = 0.35;  // the sway across the wind, as a share of the mean bend
// A leaf's flutter: kFlutter v / stiffness radians about its normal, saturated at kMaxFlutter;
// about 3 degrees in a light breeze, at 2-3 Hz: a stroke stands for a clump of leaves, and a
// faster or wider turn reads as jitter at 24 frames a second.
constexpr double kFlutter = 0.012, kMaxFlutter = 0.3, kLeafFrequency = 2.5;
// Limbs of one tree sway nearly together (the gust drives them all): each one's phase lies
// within kPhaseSpread of a cycle of its tree's, its frequency within 10% of its level's, so
// neighbouring twigs drift apart slowly instead of crossing each other every frame.
constexpr double kPhaseSpread = 0.25;

// x / (1 + x / most): x for small x, `most` for large; no transcendental.
double saturate(double x, double most) { return x / (1.0 + x / most); }

double unit(uint64_t h) { return static_cast<double>(h >> 11) * 0x1.0p-53; }

// The nearest segment of a ring polyline to p: the joint (ring index) it moves with. Past the
// last ring a point moves with the last joint, before the first with the first.
uint32_t nearest_joint(const std::vector<glm::vec3>& rings, const glm::vec3& p) {
    if (rings.size() < 2) return 0;
    float best = INFINITY;
    uint32_t joint = 0;
    for (size_t s = 0; s + 1 < rings.size(); ++s) {
        const glm::vec3 a = rings[s], ab = rings[s + 1] - a;
        const float len2 = glm::dot(ab, ab);
        const float u = len2 > 0 ? glm::dot(p - a, ab) / len2 : 0.0f;
        const glm::vec3 q = a + ab * std::clamp(u, 0.0f, 1.0f);
        const float d2 = glm::dot(p - q, p - q);
        if (d2 < best)
            best = d2, joint = static_cast<uint32_t>(u > 1.0f && s + 2 == rings.size() ? s + 1 : s);
    }
    return joint;
}

std::vector<glm::vec3> rings_of(const BranchInfo& b) {
    if (b.ring_centers.size() >= 2) return b.ring_centers;
    return {b.start, b.end};
}

// The rotation by the angle |w| about w's direction (Rodrigues), in double then rounded.
glm::mat3 rotation(const glm::dvec3& w) {
    const double angle = glm::length(w);
    if (!(angle > 1e-12)) return glm::mat3(1.0f);
    const glm::dvec3 k = w / angle;
    double s, c;
    pmath::sincos(angle, s, c);
    const double v = 1.0 - c;
    glm::dmat3 r;  // column-major: r[col][row]
    r[0] = {c + k.x * k.x * v, k.y * k.x * v + k.z * s, k.z * k.x * v - k.y * s};
    r[1] = {k.x * k.y * v - k.z * s, c + k.y * k.y * v, k.z * k.y * v + k.x * s};
    r[2] = {k.x * k.z * v + k.y * s, k.y * k.z * v - k.x * s, c + k.z * k.z * v};
    return glm::mat3(r);
}

// The limbs in an order with every parent before its children.
std::vector<uint32_t> parents_first(const std::vector<BranchInfo>& limbs) {
    std::vector<uint32_t> order, depth(limbs.size(), 0);
    for (size_t i = 0; i < limbs.size(); ++i) {
        int p = limbs[i].parent;
        uint32_t d = 0;
        while (p >= 0 && static_cast<size_t>(p) < limbs.size() && d <= limbs.size())
            p = limbs[static_cast<size_t>(p)].parent, ++d;
        depth[i] = d;
        order.push_back(static_cast<uint32_t>(i));
    }
    std::stable_sort(order.begin(), order.end(),
                     [&](uint32_t a, uint32_t b) { return depth[a] < depth[b]; });
    return order;
}

}  // namespace

WindRig build_wind_rig(const Tree& tree, const BarkParticles* bark) {
    WindRig rig;
    const std::vector<BranchInfo>& limbs = tree.branches;
    std::vector<std::vector<glm::vec3>> rings(limbs.size());
    for (size_t i = 0; i < limbs.size(); ++i) {
        rings[i] = rings_of(limbs[i]);
        rig.first_joint.push_back(static_cast<uint32_t>(rig.center.size()));
        rig.center.insert(rig.center.end(), rings[i].begin(), rings[i].end());
    }
    rig.first_joint.push_back(static_cast<uint32_t>(rig.center.size()));
    rig.parent_joint.assign(limbs.size(), WindRig::kNone);
    for (size_t i = 0; i < limbs.size(); ++i) {
        const int p = limbs[i].parent;
        if (p < 0 || static_cast<size_t>(p) >= limbs.size()) continue;
        rig.parent_joint[i] = rig.first_joint[static_cast<size_t>(p)] +
                              nearest_joint(rings[static_cast<size_t>(p)], limbs[i].start);
    }
    auto joint_of = [&](uint32_t limb, const glm::vec3& p) -> uint32_t {
        if (limbs.empty()) return WindRig::kNone;
        if (limb >= limbs.size()) limb = 0;
        const uint32_t j = rig.first_joint[limb] + nearest_joint(rings[limb], p);
        rig.reach = std::max(rig.reach, glm::length(p - rig.center[j]));
        return j;
    };
    const LeafParticles& L = tree.leaves;
    rig.leaf_joint.resize(L.size());
    for (size_t j = 0; j < L.size(); ++j)
        rig.leaf_joint[j] = joint_of(j < L.limb.size() ? L.limb[j] : 0, L.position[j]);
    if (bark) {
        rig.bark_joint.resize(bark->size());
        for (size_t j = 0; j < bark->size(); ++j)
            rig.bark_joint[j] =
                joint_of(j < bark->limb.size() ? bark->limb[j] : 0, bark->position[j]);
    }
    if (!std::isfinite(rig.reach)) rig.reach = 0;
    return rig;
}

TreePose pose_tree(const Tree& tree, const WindRig& rig, const WindStiffness& stiffness,
                   const WindAtTree& wind, const WindTiers& tiers) {
    TreePose pose;
    pose.time = wind.time, pose.seed = wind.seed;
    const double v = std::isfinite(wind.speed) ? std::max(0.0, wind.speed) : 0.0;
    const glm::dvec3 w = glm::dvec3(wind.direction);
    const bool moves = v > 0 && (tiers.trunk > 0 || tiers.limbs > 0) && glm::dot(w, w) > 0.5;
    pose.flutter = v > 0
                       ? static_cast<float>(std::clamp(tiers.leaves, 0.0f, 1.0f) *
                                            saturate(kFlutter * v / stiffness.leaves, kMaxFlutter))
                       : 0.0f;
    const std::vector<BranchInfo>& limbs = tree.branches;
    if (!moves || rig.first_joint.size() != limbs.size() + 1) return pose;
    pose.joints.resize(rig.center.size());
    std::vector<double> turned(rig.center.size(), 0.0);  // the most angle a joint has turned
    const double tree_phase = unit(hash_keys(wind.seed, 0x54524545u));
    double moved = 0, angle = 0;
    for (const uint32_t i : parents_first(limbs)) {
        const BranchInfo& b = limbs[i];
        const int level = std::clamp(b.level, 0, 2);
        const double tier = std::clamp(level == 0 ? tiers.trunk : tiers.limbs, 0.0f, 1.0f);
        const double stiff = level == 0 ? stiffness.trunk : stiffness.limbs;
        const double mean = tier * saturate(kBend[level] * v * v / stiff, kMaxBend[level]);
        glm::dvec3 d = glm::dvec3(b.end - b.start);
        const double dl = glm::length(d);
        d = dl > 1e-9 ? d / dl : glm::dvec3(0, 1, 0);
        const glm::dvec3 across = glm::cross(d, w);
        const double s = glm::length(across);
        const uint64_t h = hash_keys(wind.seed, b.key, 0x57494e44u);
        const double f = kFrequency[level] * (0.9 + 0.2 * unit(h));
        const double phase = tree_phase + kPhaseSpread * unit(mix64(h));
        const double push = mean * s * (1.0 + kSway * sway_wave(wind.time, f, phase));
        const double lateral =
            mean * kLateral *
            sway_wave(wind.time, 1.17 * f, phase + 0.5 * unit(mix64(h ^ 0x5bd1e995u)));
        glm::dvec3 omega = w * lateral;
        if (s > 1e-6) omega += across / s * push;
        const uint32_t first = rig.first_joint[i], n = rig.first_joint[i + 1] - first;
        const glm::dvec3 step = omega / static_cast<double>(std::max(n, 1u));
        const glm::mat3 r = rotation(step);
        const double step_angle = glm::length(step);
        LimbMotion a;
        double total = 0;
        if (rig.parent_joint[i] != WindRig::kNone)
            a = pose.joints[rig.parent_joint[i]], total = turned[rig.parent_joint[i]];
        for (uint32_t k = 0; k < n; ++k) {
            const glm::vec3 c = rig.center[first + k];
            a = {a.m * r, a.t + a.m * (c - r * c)};
            total += step_angle;
            pose.joints[first + k] = a;
            turned[first + k] = total;
            moved = std::max(moved, static_cast<double>(glm::length(a.apply(c) - c)));
            angle = std::max(angle, total);
        }
    }
    pose.reach = static_cast<float>(moved + angle * rig.reach);
    if (!std::isfinite(pose.reach)) pose.joints.clear(), pose.reach = 0;
    return pose;
}

float leaf_flutter(const TreePose& pose, float label) {
    if (!(pose.flutter > 0)) return 0.0f;
    uint32_t bits;
    std::memcpy(&bits, &label, sizeof bits);
    const uint64_t h = hash_keys(pose.seed, bits, 0x464c5554u);
    const double f = kLeafFrequency * (0.7 + 0.6 * unit(h));
    return static_cast<float>(pose.flutter * sway_wave(pose.time, f, unit(mix64(h))));
}

double smooth_triangle_wave(double x) {
    if (!std::isfinite(x)) return 0.0;
    const double y = x + 0.5;
    const double tri = std::abs(2.0 * (y - std::floor(y)) - 1.0);
    return 2.0 * tri * tri * (3.0 - 2.0 * tri) - 1.0;
}

double sway_wave(double t, double frequency, double phase) {
    // Periods 1 and 1 / 2.37 of the limb's: the sum never repeats within a shot.
    return 0.65 * smooth_triangle_wave(t * frequency + phase) +
           0.35 * smooth_triangle_wave(2.37 * t * frequency + 1.7 * phase);
}

double gust_envelope(double tau, double cross, uint64_t seed) {
    if (!std::isfinite(tau) || !std::isfinite(cross)) return 0.0;
    tau = std::clamp(tau, -1e15, 1e15), cross = std::clamp(cross, -1e15, 1e15);
    const double fi = std::floor(tau), fj = std::floor(cross);
    const double u = tau - fi, w = cross - fj;
    const int64_t i = static_cast<int64_t>(fi), j = static_cast<int64_t>(fj);
    auto value = [&](int64_t a, int64_t b) {
        return unit(hash_keys(seed, static_cast<uint64_t>(a), static_cast<uint64_t>(b)));
    };
    auto quintic = [](double x) { return x * x * x * (x * (6.0 * x - 15.0) + 10.0); };
    const double su = quintic(u), sw = quintic(w);
    const double lo = value(i, j) + (value(i + 1, j) - value(i, j)) * su;
    const double hi = value(i, j + 1) + (value(i + 1, j + 1) - value(i, j + 1)) * su;
    return lo + (hi - lo) * sw;
}

}  // namespace pleinair
