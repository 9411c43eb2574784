// Corot's crowns measured in a painted scene (issue 27 §2): for each tree in view, how much sky
// shows through its outline, how broken that outline is, and how much of its limbs shows.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "pipeline/bench/masks.h"
#include "pipeline/frame/frame_image.h"

namespace pleinair {

struct Shot;
struct FrameView;

// Per pixel of a painted frame (AOVs required): the tree painted there (0 none, else its index
// + 1, the object id its strokes carry) and whether its bark shows (the camera ray's first hit is
// a trunk or limb of the scene, and no stroke lies in front of it).
struct TreePixels {
    std::vector<uint32_t> tree;
    Mask bark;
};
TreePixels tree_pixels(const Shot& shot, const FrameView& view, const Frame& frame);

// One tree's crown. Its outline is bench trees' (tree_form.h): its pixels closed by
// kOutlineRadius of their larger extent, with what that encloses.
struct CrownLook {
    size_t pixels = 0;  // the tree's own pixels
    size_t area = 0;    // the outline's pixels
    double sky = 0;     // open-sky pixels inside the outline, over the outline's area
    double edge = 0;    // the length of its pixels' edge (their holes filled) over the square
                        // root of the outline's area: 4.5 for a disc, more as touches break it
    double bark = 0;    // its bark pixels inside the outline, over the outline's area
};

// The crowns of every tree with at least `min_pixels` pixels, in the order of their ids. The
// edge counts where another tree or the ground hides this one as its edge too; the frame's edge
// does not count.
std::vector<CrownLook> measure_crowns(const TreePixels& trees, const Mask& sky, int width,
                                      int height, size_t min_pixels);

// The median of each measure over the crowns (zeros when there are none); `pixels` is the
// crowns' count.
CrownLook median_crown(std::vector<CrownLook> crowns);

// The crowns as the eye meets them, each weighed by its outline's area: the sky and bark inside
// all the outlines over their whole area, and the edge's mean weighed by area. A great tree
// near the camera counts for what it covers, not as one of forty distant masses (the far bank
// of a Corot is a soft mass with no holes; its near crowns are where the sky shows through).
// `pixels` is the crowns' count.
CrownLook pooled_crown(const std::vector<CrownLook>& crowns);

}  // namespace pleinair
