// A tree's form seen from the side, in the figures a botanist's description gives (issue 27's
// `bench trees`): how wide its crown is for its height, how much bare trunk stands under it,
// how much of its foliage hangs, in how many masses, and how much sky shows through the crown.
#pragma once

#include <cstdint>
#include <vector>

#include "pipeline/shot/built_trees.h"

namespace pleinair {

struct TreeForm {
    double crown_ratio = 0;  // the crown's width (spread) over the tree's height, from the side
    double clear_trunk = 0;  // trunk clear of leaves, over the tree's height
    double droop = 0;        // share of the leaves below the base of the limb they grow from
    double hem = 0;          // how high the crown's sides end, over the tree's height (kHemSide)
    int clumps = 0;          // separate masses of leaves (kClumpRadius, kNeckRadius, kMassShare)
    double holes = 0;        // share of the crown's outline (kOutlineRadius) where sky shows
};

// What a stroke is as a mass and as an outline, in fractions of the crown's larger extent:
// leaf pixels closer than 2 x kClumpRadius belong to one mass; masses joined only by a waist
// narrower than 2 x kNeckRadius are separate (a painter reads two lobes on a thin waist as two
// masses, as Corot's oaks are read), and one counts when its core, what is left after wearing
// kNeckRadius off the crown, holds at least kMassShare of all the cores. The outline closes
// gaps narrower than 2 x kOutlineRadius and fills what it then encloses.
inline constexpr double kClumpRadius = 0.015;
inline constexpr double kNeckRadius = 0.08;
inline constexpr double kMassShare = 0.05;
inline constexpr double kOutlineRadius = 0.04;
// The crown's sides are the outer kHemSide of its width each way; their hem is where their
// lowest leaves end, less the lowest kHemStray of those leaves (a stray stroke does not lower
// it). A weeping willow's curtain ends near the ground, a stone pine's parasol high.
inline constexpr double kHemSide = 0.2;
inline constexpr double kHemStray = 0.02;

// Coverage seen from the side, row 0 at the top, 1 where a stroke more than half opaque lies.
struct SideMasks {
    int width = 0, height = 0;
    std::vector<uint8_t> leaf, bark;
};

// The form from the masks, and the droop from the tree's leaves and limbs. A mask with no leaf
// or no bark gives a form of zeros.
TreeForm measure_form(const SideMasks& masks, const Tree& tree);

// `tree` painted from the side (the contact sheet's camera) twice, its leaves alone, then its bark
// alone, with the family's shaders in `scene`.
SideMasks side_masks(const SceneDesc& scene, const BuiltTree& tree, int width, int height);

}  // namespace pleinair
