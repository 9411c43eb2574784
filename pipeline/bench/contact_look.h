// Whether the trees stand in the ground (issue 52 sections 3 and 7): at each tree's foot on
// screen, the ground beside the trunk against the same rows of ground further out.
#pragma once

#include <cstdint>
#include <vector>

namespace pleinair {

struct Shot;
struct FrameView;
struct Frame;

// A tree's foot on screen: where its base projects, the screen's pixels per metre there, and
// the object id its own strokes carry in the frame's AOV (their pixels are not ground).
struct TreeBase {
    float x = 0, y = 0;
    float px_per_m = 0;
    float object_id = 0;
};

// The ground's L* in two bands of the rows within kContactRows metres of the foot: beside the
// trunk (kContactNear metres to either side) and further out (kContactFar), counting only
// pixels of neither the tree nor the sky. A foot whose trunk stands in its shade and its ground
// touches is darker beside it (`drop`, far less near, in L*, > 0); a trunk standing on nothing
// shows the same ground on both sides (0), a light seam a negative drop. A foot counts when
// both bands hold at least kContactMinPixels pixels.
struct ContactLook {
    int bases = 0;              // feet measured
    double median_drop = 0;     // L*
    double standing_share = 0;  // share of feet with a drop of at least kContactStanding
};
// The feet of a frame's trees, from the shot's placements: those in front of the camera, inside
// the frame, at least kContactMinScale pixels a metre, and not hidden behind something nearer
// (the frame's depth AOV at the foot within 10% of the foot's depth, or the tree's own paint).
inline constexpr double kContactMinScale = 2.0;
std::vector<TreeBase> tree_bases(const Shot& shot, const FrameView& view, const Frame& frame);

inline constexpr double kContactRows = 0.3, kContactNear[2] = {0.6, 1.8},
                        kContactFar[2] = {4.0, 6.0};
inline constexpr double kContactStanding = 3.0;
inline constexpr int kContactMinPixels = 8;
ContactLook contact_look(const std::vector<float>& lightness, int width, int height,
                         const std::vector<float>& object_id, const std::vector<uint8_t>& sky,
                         const std::vector<TreeBase>& bases);

}  // namespace pleinair
