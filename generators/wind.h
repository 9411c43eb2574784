// The wind's pose of a tree: each limb of the skeleton bent by a pure function of (time, seed,
// limb, wind), the bends composed from the trunk out, and its leaves' flutter; no state is kept
// and nothing is drawn per frame, so frame N alone is frame N in a sequence.
#pragma once

#include <cstdint>
#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>
#include <vector>

#include "generators/tree.h"

namespace pleinair {

struct BarkParticles;

// A rigid motion of tree-local points: p -> m p + t.
struct LimbMotion {
    glm::mat3 m{1.0f};
    glm::vec3 t{0.0f};
    glm::vec3 apply(const glm::vec3& p) const { return m * p + t; }
};

// Where a tree's particles hang on its skeleton, built once per grown tree. Every ring of
// every limb is a joint: the bend at joint k turns what lies beyond ring k on its limb (and the
// limbs growing there), so the trunk's ring 0 is the root, which bends with the whole wind, and
// a limb's ring 0 is where it leaves its parent. A particle moves with the joint of the ring
// segment it lies along (its twig's, for a leaf).
struct WindRig {
    static constexpr uint32_t kNone = ~0u;
    std::vector<uint32_t> first_joint;   // per limb its ring 0's joint, then the joint count
    std::vector<uint32_t> parent_joint;  // per limb the joint of its parent it hangs from
    std::vector<glm::vec3> center;       // per joint, its ring's centre at rest (tree-local)
    std::vector<uint32_t> leaf_joint;    // per leaf particle
    std::vector<uint32_t> bark_joint;    // per bark stroke (when built with them)
    // The farthest any particle lies from its joint's centre (tree units): with the joints'
    // own moves it bounds every particle's move (TreePose::reach).
    float reach = 0;
};
WindRig build_wind_rig(const Tree& tree, const BarkParticles* bark);

// The wind where a tree stands at one time, in the tree's own frame.
struct WindAtTree {
    glm::vec3 direction{1.0f, 0.0f, 0.0f};  // unit and level: where the wind blows to
    double speed = 0;                       // m/s, its gusts included
    double time = 0;                        // s, the shot's clock
    uint64_t seed = 0;                      // the tree's own phases (its id and the wind's seed)
};

// How far the wind's levels reach into a tree (1 all, 0 none), from its distance (as
// SpeedTree's wind LOD): far trees sway as a whole, the middle distance adds the limbs, the near
// field the leaves' flutter. Weights, not switches, so a tree crossing a circle blends.
struct WindTiers {
    float trunk = 1, limbs = 1, leaves = 1;
};

// A tree bent by the wind at one time: one motion per joint of its rig.
struct TreePose {
    std::vector<LimbMotion> joints;  // empty: the tree at rest, every particle where it was
    double time = 0;
    uint64_t seed = 0;
    float flutter = 0;  // the leaves' flutter amplitude, radians about their own normal
    float reach = 0;    // no particle moves farther than this from rest (tree units)
    bool at_rest() const { return joints.empty(); }
};

// Pure: the pose at wind.time; the same whatever was posed before, in any order or process.
// Zero speed or zero tiers give a pose at rest.
TreePose pose_tree(const Tree& tree, const WindRig& rig, const WindStiffness& stiffness,
                   const WindAtTree& wind, const WindTiers& tiers);

// The angle a leaf's stroke turns about its normal at the pose's time (radians): its own
// phase and frequency, drawn from its label.
float leaf_flutter(const TreePose& pose, float label);

// Waves and gusts: pure functions of time, no trigonometry (the same bits everywhere).
// Smoothed triangle wave (GPU Gems 3, ch. 16): period 1, in [-1, 1], C1.
double smooth_triangle_wave(double x);
// A limb's sway: two smoothed triangle waves of incommensurate periods, in [-1, 1].
double sway_wave(double t, double frequency, double phase);
// Gusts: value noise over (tau, cross) lattice cells with quintic interpolation, in [0, 1]
// and C2 in tau: tau in gust periods along the wind's clock, cross in turbulence widths across
// the wind.
double gust_envelope(double tau, double cross, uint64_t seed);

}  // namespace pleinair
